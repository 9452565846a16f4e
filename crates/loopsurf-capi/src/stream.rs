//! The surface as bytes (e.g. for `MPI_Bcast` to every rank) and back.

use crate::buffers::malloc_copy;
use crate::status::{input, output, run};
use crate::surface::ls_surface;
use std::ffi::{c_int, c_void};

/// The surface as a versioned, checksummed byte stream, e.g. for
/// `MPI_Bcast` to every rank: writes a new buffer and its length, to be
/// released with `ls_free_bytes`. `ls_surface_load` turns it back into a
/// surface that evaluates bit-identically.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_save(
    surface: *const ls_surface,
    bytes: *mut *mut u8,
    n: *mut usize,
) -> c_int {
    run("ls_surface_save", || {
        let surface = &input(surface, "surface")?.0;
        let (bytes, n) = (output(bytes, "bytes")?, output(n, "n")?);
        let stream = loopsurf::stream::to_bytes(surface);
        *bytes = malloc_copy(&stream)?;
        *n = stream.len();
        Ok(())
    })
}

/// Frees a buffer returned by `ls_surface_save` (NULL is ignored); `n` is
/// its length, accepted for symmetry and not needed.
#[no_mangle]
pub unsafe extern "C" fn ls_free_bytes(bytes: *mut u8, n: usize) {
    let _ = n;
    libc::free(bytes as *mut c_void);
}

/// Rebuilds a surface from `n` bytes written by `ls_surface_save` (on any
/// rank or machine of the same byte order). Truncated, damaged or foreign
/// bytes give LS_ERR_BAD_STREAM.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_load(
    bytes: *const u8,
    n: usize,
    out: *mut *mut ls_surface,
) -> c_int {
    run("ls_surface_load", || {
        input(bytes, "bytes")?;
        let out = output(out, "out")?;
        let stream = std::slice::from_raw_parts(bytes, n);
        let surface = loopsurf::stream::from_bytes(stream)?;
        *out = Box::into_raw(Box::new(ls_surface(surface)));
        Ok(())
    })
}
