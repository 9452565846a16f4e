//! Surfaces: build one from a net (approximating or interpolating), ask
//! its size and where it folds, free it.

pub use crate::handles::ls_surface;
use crate::net::ls_net;
use crate::status::{input, output, run, run_void, Fail, LS_ERR_INVALID_ARGUMENT};
use loopsurf::{Surface, SurfaceMode};
use std::ffi::c_int;

/// Freezes a net into an immutable surface. The net is copied: it may be
/// changed or freed after. The build refines nothing: the once-refined
/// net is made with the first query, and each triangle's evaluation data
/// the first time a query reaches it (any thread may query at any time,
/// and results do not depend on the order).
#[no_mangle]
pub unsafe extern "C" fn ls_surface_build(net: *const ls_net, out: *mut *mut ls_surface) -> c_int {
    run("ls_surface_build", || {
        let net = &input(net, "net")?.0;
        let out = output(out, "out")?;
        let surface = Surface::new(net)?;
        *out = Box::into_raw(Box::new(ls_surface(surface)));
        Ok(())
    })
}

/// `ls_surface_build_interpolating` mode: solve for new control points
/// whose smooth limit surface passes through the net's points.
pub const LS_INTERPOLATE_SOLVE: c_int = 1;

/// `ls_surface_build_interpolating` mode: the approximating surface plus a
/// linear correction per triangle, through the net's points exactly but
/// only C0 across edges.
pub const LS_INTERPOLATE_DISPLACEMENT: c_int = 2;

/// Like `ls_surface_build`, but the surface passes through the net's points
/// (Persson, Aftosmis & Haines, §3.3): `mode` is LS_INTERPOLATE_SOLVE or
/// LS_INTERPOLATE_DISPLACEMENT. Solving fails with LS_ERR_INVALID_ARGUMENT
/// if the net's limit operator is singular or too ill-conditioned.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_build_interpolating(
    net: *const ls_net,
    mode: c_int,
    out: *mut *mut ls_surface,
) -> c_int {
    run("ls_surface_build_interpolating", || {
        let net = &input(net, "net")?.0;
        let out = output(out, "out")?;
        let mode = match mode {
            LS_INTERPOLATE_SOLVE => SurfaceMode::Solve,
            LS_INTERPOLATE_DISPLACEMENT => SurfaceMode::Displacement,
            _ => {
                return Err(Fail::new(
                    LS_ERR_INVALID_ARGUMENT,
                    format!("mode {mode}: expected LS_INTERPOLATE_SOLVE (1) or LS_INTERPOLATE_DISPLACEMENT (2)"),
                ))
            }
        };
        let surface = Surface::with_mode(net, mode)?;
        *out = Box::into_raw(Box::new(ls_surface(surface)));
        Ok(())
    })
}

/// Writes the number of triangles of the surface's control net: valid
/// triangle indices are 0 to ntris − 1.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_num_triangles(
    surface: *const ls_surface,
    ntris: *mut usize,
) -> c_int {
    run("ls_surface_num_triangles", || {
        let surface = &input(surface, "surface")?.0;
        *output(ntris, "ntris")? = surface.net().triangles().len();
        Ok(())
    })
}

/// The control triangles whose patch of the limit surface folds over
/// itself (normals within it turning by more than 120°; coarse nets fold
/// next to corners, creases and irregular vertices of high valence, and no
/// mesh of a fold has good triangles that all face one way): `n` 0-based
/// indices, ascending, in a new array (allocated even when n = 0)
/// released with `ls_free_array`. Every patch is evaluated, about 150
/// times.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_folded_patches(
    surface: *const ls_surface,
    n: *mut usize,
    triangles: *mut *mut i32,
) -> c_int {
    run("ls_surface_folded_patches", || {
        let surface = &input(surface, "surface")?.0;
        let (n, triangles) = (output(n, "n")?, output(triangles, "triangles")?);
        let folded: Vec<i32> = loopsurf::folds::folded_patches(surface)
            .into_iter()
            .map(|t| t as i32)
            .collect();
        *triangles = crate::buffers::malloc_copy(&folded)?;
        *n = folded.len();
        Ok(())
    })
}

/// Frees a surface (NULL is ignored). No other thread may still use it.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_free(surface: *mut ls_surface) {
    if !surface.is_null() {
        run_void("ls_surface_free", || drop(Box::from_raw(surface)));
    }
}
