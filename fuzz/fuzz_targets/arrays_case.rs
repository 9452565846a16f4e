//! One call of `ls_net_from_arrays` decoded from arbitrary bytes, and what
//! must hold after it. Shared, as a module, by the fuzz target `arrays`
//! (fuzz/fuzz_targets/arrays.rs) and its stable replay
//! (crates/loopsurf-capi/tests/hostile_arrays.rs).
//!
//! Layout: a flags byte (low three bits 1, 2, 3: `xyz`, `tris` or `out` is
//! NULL; bit 3: raw numbers), a vertex count byte, then the coordinates and
//! the indices. Decoded, a coordinate byte is a point of a small grid or,
//! from 0xF8 up, NaN, ±inf, -0, the largest and the smallest doubles; an
//! index byte is itself (out of range when ≥ nverts) or, from 0xF8 up, -1,
//! `i32::MIN`, `i32::MAX`, nverts, nverts + 1, -nverts, 2³⁰ or
//! `i32::MIN + 1`. Raw, they are little-endian `f64`s and `i32`s. The
//! counts are always those of the buffers: a count larger than its buffer
//! is undefined behaviour in C too, and cannot be detected.

use loopsurf_capi::*;
use std::ffi::CStr;
use std::ptr::{null, null_mut};

/// The arguments of one call.
#[derive(Debug)]
pub struct Case {
    pub xyz: Vec<f64>,
    pub tris: Vec<i32>,
    pub null_xyz: bool,
    pub null_tris: bool,
    pub null_out: bool,
}

pub fn decode(data: &[u8]) -> Case {
    let (&flags, rest) = data.split_first().unwrap_or((&0, &[]));
    let (&nverts, rest) = rest.split_first().unwrap_or((&0, &[]));
    let raw = flags & 8 != 0;
    let size = if raw { 8 } else { 1 };
    let nverts = (nverts as usize).min(rest.len() / (3 * size));
    let (coords, indices) = rest.split_at(3 * nverts * size);
    let (xyz, tris) = if raw {
        let xyz = coords
            .chunks_exact(8)
            .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
            .collect();
        let n = indices.len() / 12 * 12;
        let tris = indices[..n]
            .chunks_exact(4)
            .map(|b| i32::from_le_bytes(b.try_into().unwrap()))
            .collect();
        (xyz, tris)
    } else {
        let n = indices.len() / 3 * 3;
        let tris = indices[..n].iter().map(|&b| index(b, nverts)).collect();
        (coords.iter().map(|&b| coordinate(b)).collect(), tris)
    };
    Case {
        xyz,
        tris,
        null_xyz: flags & 7 == 1,
        null_tris: flags & 7 == 2,
        null_out: flags & 7 == 3,
    }
}

fn coordinate(b: u8) -> f64 {
    match b {
        0xF8 => f64::NAN,
        0xF9 => f64::INFINITY,
        0xFA => f64::NEG_INFINITY,
        0xFB => -0.0,
        0xFC => f64::MAX,
        0xFD => f64::MIN_POSITIVE,
        0xFE => 5e-324,
        0xFF => -f64::NAN,
        _ => (b as f64 - 124.0) / 8.0,
    }
}

fn index(b: u8, nverts: usize) -> i32 {
    let n = nverts as i32;
    match b {
        0xF8 => -1,
        0xF9 => i32::MIN,
        0xFA => i32::MAX,
        0xFB => n,
        0xFC => n + 1,
        0xFD => -n,
        0xFE => 1 << 30,
        0xFF => i32::MIN + 1,
        _ => b as i32,
    }
}

/// Makes the call and checks it: a status, never a panic (a caught one is
/// `LS_ERR_INTERNAL`); on success a net of exactly the given counts, freed
/// again; on failure `out` untouched, a message, and the status code of a
/// problem the arguments do have.
///
/// # Safety
/// Calls the C ABI; the buffers of `case` are real, so it is sound.
pub unsafe fn check(case: &Case) {
    let (nverts, ntris) = (case.xyz.len() / 3, case.tris.len() / 3);
    // An empty buffer is still a real pointer, as `malloc(0)` may give.
    let (spare_xyz, spare_tris) = ([0.0f64; 3], [0i32; 3]);
    let xyz = match (case.null_xyz, case.xyz.is_empty()) {
        (true, _) => null(),
        (false, true) => spare_xyz.as_ptr(),
        (false, false) => case.xyz.as_ptr(),
    };
    let tris = match (case.null_tris, case.tris.is_empty()) {
        (true, _) => null(),
        (false, true) => spare_tris.as_ptr(),
        (false, false) => case.tris.as_ptr(),
    };
    let mut net: *mut ls_net = null_mut();
    let out: *mut *mut ls_net = if case.null_out { null_mut() } else { &mut net };
    let status = ls_net_from_arrays(nverts, xyz, ntris, tris, out);

    let out_of_range = |i: &i32| *i < 0 || *i as usize >= nverts;
    let any_out_of_range = case.tris.iter().any(out_of_range);
    let repeats = case
        .tris
        .chunks_exact(3)
        .any(|t| t[0] == t[1] || t[0] == t[2] || t[1] == t[2]);
    let non_finite = case.xyz.iter().any(|x| !x.is_finite());
    let null = case.null_xyz || case.null_tris || case.null_out;

    if status == LS_OK {
        assert!(!null && !any_out_of_range && !repeats && !non_finite);
        assert!(nverts > 0 && ntris > 0 && !net.is_null());
        let (mut v, mut t, mut h) = (0, 0, 0);
        assert_eq!(ls_net_counts(net, &mut v, &mut t, &mut h), LS_OK);
        assert_eq!((v, t), (nverts, ntris));
        let (mut n, mut pairs) = (0usize, null_mut::<i32>());
        assert_eq!(ls_net_hard_edges(net, &mut n, &mut pairs), LS_OK);
        assert_eq!(n, h);
        ls_free_array(pairs.cast());
        ls_net_free(net);
        return;
    }
    assert!(net.is_null(), "status {status}, yet the net was written");
    let message = CStr::from_ptr(ls_last_error()).to_str().unwrap();
    let prefix = "ls_net_from_arrays: ";
    assert!(
        message.starts_with(prefix) && message.len() > prefix.len(),
        "status {status}: {message:?}"
    );
    let expected = if null {
        Some(LS_ERR_NULL_POINTER)
    } else if nverts == 0 || ntris == 0 {
        Some(LS_ERR_DEGENERATE)
    } else if any_out_of_range && !repeats {
        Some(LS_ERR_INDEX_OUT_OF_RANGE)
    } else if !any_out_of_range && !repeats && non_finite {
        Some(LS_ERR_NOT_FINITE)
    } else {
        None
    };
    match expected {
        Some(code) => assert_eq!(status, code, "{message}"),
        None => assert!(
            [
                LS_ERR_INDEX_OUT_OF_RANGE,
                LS_ERR_DEGENERATE,
                LS_ERR_NOT_FINITE,
                LS_ERR_NON_MANIFOLD,
            ]
            .contains(&status),
            "status {status}: {message}"
        ),
    }
    let explained = match status {
        LS_ERR_INDEX_OUT_OF_RANGE => any_out_of_range,
        LS_ERR_NOT_FINITE => non_finite,
        LS_ERR_NON_MANIFOLD => !any_out_of_range && !repeats,
        _ => true,
    };
    assert!(explained, "status {status} without its cause: {message}");
}
