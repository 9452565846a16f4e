//! One part of a partitioned net as a net of its own (`ls_part`): its
//! triangles and the halo their exact evaluation needs, the maps to the
//! whole net's ids, and its own stream, so that rank 0 can send each rank
//! only its part, or every rank can build only its own.

use crate::buffers::{malloc_copy, Blocks};
use crate::handles::ls_part;
use crate::net::ls_net;
use crate::status::LS_ERR_INVALID_ARGUMENT;
use crate::status::{input, output, read_options, run, run_void, write_defaults, Fail, Options};
use loopsurf::partition::{part, partition_with, PartitionOptions};
use std::ffi::c_int;

/// Options of `ls_net_part`: fill with `ls_part_options_default`, then
/// change what you need.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_part_options {
    /// `sizeof(ls_part_options)` as the caller was compiled with.
    pub struct_size: usize,
    /// The number of parts K, 1 to the number of triangles. Default 1.
    pub parts: c_int,
    /// Which part, 0 to K − 1. Default 0.
    pub part: c_int,
    /// METIS's random seed, as in `ls_partition_options`. Default 1.
    pub seed: c_int,
}

impl Options for ls_part_options {
    const FIRST_SIZE: usize = std::mem::size_of::<ls_part_options>();
    fn defaults() -> Self {
        ls_part_options {
            struct_size: std::mem::size_of::<ls_part_options>(),
            parts: 1,
            part: 0,
            seed: PartitionOptions::default().seed,
        }
    }
}

/// Writes the default options of `ls_net_part` into `options`.
#[no_mangle]
pub unsafe extern "C" fn ls_part_options_default(options: *mut ls_part_options) -> c_int {
    write_defaults("ls_part_options_default", options)
}

/// Partitions the net as `ls_net_partition` does (`options->parts`,
/// `options->seed`) and writes part `options->part` as a new `ls_part`,
/// to be released with `ls_part_free`. A surface built on its net
/// (`ls_part_net`, `ls_surface_build`) evaluates every owned triangle bit
/// for bit as the whole net's surface does. K or the part out of range is
/// `LS_ERR_INVALID_ARGUMENT`, and nothing is written.
#[no_mangle]
pub unsafe extern "C" fn ls_net_part(
    net: *const ls_net,
    options: *const ls_part_options,
    out: *mut *mut ls_part,
) -> c_int {
    run("ls_net_part", || {
        let net = &input(net, "net")?.0;
        let o = read_options(options, "options")?;
        let out = output(out, "out")?;
        let count = |x: c_int, what: &str| {
            usize::try_from(x).map_err(|_| {
                Fail::new(
                    LS_ERR_INVALID_ARGUMENT,
                    format!("{what} {x}: must not be negative"),
                )
            })
        };
        let (k, p) = (count(o.parts, "K =")?, count(o.part, "part")?);
        let partition = partition_with(net, k, &PartitionOptions { seed: o.seed })?;
        let made = part(net, &partition, p)?;
        *out = Box::into_raw(Box::new(ls_part(made)));
        Ok(())
    })
}

/// Frees a part (NULL is ignored).
#[no_mangle]
pub unsafe extern "C" fn ls_part_free(part: *mut ls_part) {
    if !part.is_null() {
        run_void("ls_part_free", || drop(Box::from_raw(part)));
    }
}

/// Writes the part's owned and halo triangle counts and its vertex count
/// (its net's; a rim vertex the halo touches from two sides counts once
/// per side).
#[no_mangle]
pub unsafe extern "C" fn ls_part_counts(
    part: *const ls_part,
    owned: *mut usize,
    halo: *mut usize,
    vertices: *mut usize,
) -> c_int {
    run("ls_part_counts", || {
        let part = &input(part, "part")?.0;
        let outs = (output(owned, "owned")?, output(halo, "halo")?);
        let vertices = output(vertices, "vertices")?;
        (*outs.0, *outs.1) = (part.num_owned(), part.num_halo());
        *vertices = part.net().points().len();
        Ok(())
    })
}

/// Writes the part's net's triangle count, a new array `global` (each
/// local triangle's id in the whole net, ascending) and a new array
/// `owned` (1 for an owned triangle, 0 for the halo), both to be released
/// with `ls_free_array`.
#[no_mangle]
pub unsafe extern "C" fn ls_part_triangles(
    part: *const ls_part,
    ntris: *mut usize,
    global: *mut *mut i32,
    owned: *mut *mut i32,
) -> c_int {
    run("ls_part_triangles", || {
        let part = &input(part, "part")?.0;
        let outs = (output(ntris, "ntris")?, output(global, "global")?);
        let owned = output(owned, "owned")?;
        let ids: Vec<i32> = part.global_triangles().iter().map(|&t| t as i32).collect();
        let flags: Vec<i32> = (0..ids.len()).map(|t| part.is_owned(t) as i32).collect();
        let mut blocks = Blocks::default();
        let (ids_out, flags_out) = (blocks.copy(&ids)?, blocks.copy(&flags)?);
        blocks.hand_over();
        (*outs.0, *outs.1, *owned) = (ids.len(), ids_out, flags_out);
        Ok(())
    })
}

/// Writes the part's net's vertex count and a new array `global`, each
/// local vertex's id in the whole net (non-decreasing: a rim vertex split
/// into two fans repeats its id), to be released with `ls_free_array`.
#[no_mangle]
pub unsafe extern "C" fn ls_part_vertices(
    part: *const ls_part,
    nverts: *mut usize,
    global: *mut *mut i32,
) -> c_int {
    run("ls_part_vertices", || {
        let part = &input(part, "part")?.0;
        let outs = (output(nverts, "nverts")?, output(global, "global")?);
        let ids: Vec<i32> = part.global_vertices().iter().map(|&v| v as i32).collect();
        *outs.1 = malloc_copy(&ids)?;
        *outs.0 = ids.len();
        Ok(())
    })
}

/// Writes a new net, a copy of the part's (owned and halo triangles in
/// the whole's order, local ids), to be released with `ls_net_free`;
/// freeze it with `ls_surface_build`.
#[no_mangle]
pub unsafe extern "C" fn ls_part_net(part: *const ls_part, out: *mut *mut ls_net) -> c_int {
    run("ls_part_net", || {
        let part = &input(part, "part")?.0;
        let out = output(out, "out")?;
        *out = Box::into_raw(Box::new(ls_net(part.net().clone())));
        Ok(())
    })
}

/// The part as a versioned, checksummed byte stream (64-bit counts):
/// writes a new buffer and its length, to be released with
/// `ls_free_bytes`. A stream over 2 GiB is sent in pieces of at most
/// `INT_MAX` bytes.
#[no_mangle]
pub unsafe extern "C" fn ls_part_save(
    part: *const ls_part,
    bytes: *mut *mut u8,
    n: *mut usize,
) -> c_int {
    run("ls_part_save", || {
        let part = &input(part, "part")?.0;
        let (bytes, n) = (output(bytes, "bytes")?, output(n, "n")?);
        let stream = loopsurf::stream::part_to_bytes(part);
        *bytes = malloc_copy(&stream)?;
        *n = stream.len();
        Ok(())
    })
}

/// Rebuilds a part from `n` bytes written by `ls_part_save`. Truncated,
/// damaged or foreign bytes give LS_ERR_BAD_STREAM, and nothing is
/// written.
#[no_mangle]
pub unsafe extern "C" fn ls_part_load(bytes: *const u8, n: usize, out: *mut *mut ls_part) -> c_int {
    run("ls_part_load", || {
        input(bytes, "bytes")?;
        let out = output(out, "out")?;
        let stream = std::slice::from_raw_parts(bytes, n);
        let part = loopsurf::stream::part_from_bytes(stream)?;
        *out = Box::into_raw(Box::new(ls_part(part)));
        Ok(())
    })
}
