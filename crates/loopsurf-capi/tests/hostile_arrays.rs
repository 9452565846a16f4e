//! `ls_net_from_arrays` with hostile arguments: counts whose 3 × n
//! overflows or exceeds `isize::MAX` (refused before any slice is made, with
//! NULL or a tiny real buffer), negative and out-of-range indices, NaN and
//! infinite coordinates, NULL pointers, zero counts. Each returns its status
//! code, leaves `out` alone and says what is wrong in `ls_last_error`. Also
//! replays the kept inputs of the fuzz target `arrays` (fuzz/corpus/arrays,
//! fuzz/regressions/arrays) through the target's own checks.

use loopsurf_capi::*;
use std::ffi::{c_int, CStr};
use std::path::Path;
use std::ptr::{null, null_mut};

#[path = "../../../fuzz/fuzz_targets/arrays_case.rs"]
mod arrays_case;

/// The unit tetrahedron, outward oriented.
const XYZ: [f64; 12] = [0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.];
const TRIS: [i32; 12] = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3];

/// Calls `ls_net_from_arrays`, frees a net it builds, and returns the
/// status with the last error message ("" on success).
fn call(nverts: usize, xyz: *const f64, ntris: usize, tris: *const i32) -> (c_int, String) {
    let mut net: *mut ls_net = null_mut();
    let status = unsafe { ls_net_from_arrays(nverts, xyz, ntris, tris, &mut net) };
    if status == LS_OK {
        assert!(!net.is_null());
        unsafe { ls_net_free(net) };
        return (status, String::new());
    }
    assert!(net.is_null(), "status {status}, yet the net was written");
    let message = unsafe { CStr::from_ptr(ls_last_error()) };
    (status, message.to_str().unwrap().to_owned())
}

/// The status must be `code` and the message must name the call and say `what`.
#[track_caller]
fn expect((status, message): (c_int, String), code: c_int, what: &str) {
    assert_eq!(status, code, "{message}");
    assert!(
        message.starts_with("ls_net_from_arrays: ") && message.contains(what),
        "{message:?} should say {what:?}"
    );
}

/// The tetrahedron with one index or one coordinate replaced.
fn with_index(at: usize, value: i32) -> (c_int, String) {
    let mut tris = TRIS;
    tris[at] = value;
    call(4, XYZ.as_ptr(), 4, tris.as_ptr())
}

fn with_coordinate(at: usize, value: f64) -> (c_int, String) {
    let mut xyz = XYZ;
    xyz[at] = value;
    call(4, xyz.as_ptr(), 4, TRIS.as_ptr())
}

#[test]
fn the_tetrahedron_is_accepted() {
    assert_eq!(call(4, XYZ.as_ptr(), 4, TRIS.as_ptr()).0, LS_OK);
}

/// 3 × n overflowing `usize`, or 3 × n elements beyond `isize::MAX` bytes:
/// refused from the count alone, before a slice of that length exists (the
/// buffers here hold one point and one triangle).
#[test]
fn counts_beyond_memory_are_refused_before_the_buffer_is_touched() {
    let huge_xyz = [
        usize::MAX,
        usize::MAX / 3 + 1,
        usize::MAX / 3,
        isize::MAX as usize / 3,
        isize::MAX as usize / 24 + 1,
    ];
    for n in huge_xyz {
        let (small_xyz, small_tris) = ([0.0f64; 3], [0i32, 1, 2]);
        expect(
            call(n, small_xyz.as_ptr(), 1, small_tris.as_ptr()),
            LS_ERR_INVALID_ARGUMENT,
            &format!("xyz: {n} × 3 is too large"),
        );
    }
    let huge_tris = [
        usize::MAX,
        usize::MAX / 3 + 1,
        isize::MAX as usize / 3,
        isize::MAX as usize / 12 + 1,
    ];
    for n in huge_tris {
        let small_tris = [0i32, 1, 2];
        expect(
            call(4, XYZ.as_ptr(), n, small_tris.as_ptr()),
            LS_ERR_INVALID_ARGUMENT,
            &format!("tris: {n} × 3 is too large"),
        );
    }
    // With NULL, NULL is what is wrong.
    expect(
        call(usize::MAX, null(), usize::MAX, null()),
        LS_ERR_NULL_POINTER,
        "xyz is NULL",
    );
    expect(
        call(4, XYZ.as_ptr(), usize::MAX, null()),
        LS_ERR_NULL_POINTER,
        "tris is NULL",
    );
}

#[test]
fn null_pointers_are_named() {
    expect(
        call(4, null(), 4, TRIS.as_ptr()),
        LS_ERR_NULL_POINTER,
        "xyz is NULL",
    );
    expect(
        call(4, XYZ.as_ptr(), 4, null()),
        LS_ERR_NULL_POINTER,
        "tris is NULL",
    );
    let status = unsafe { ls_net_from_arrays(4, XYZ.as_ptr(), 4, TRIS.as_ptr(), null_mut()) };
    assert_eq!(status, LS_ERR_NULL_POINTER);
    let message = unsafe { CStr::from_ptr(ls_last_error()) }.to_str().unwrap();
    assert_eq!(message, "ls_net_from_arrays: out is NULL");
    // Zero counts do not excuse a NULL pointer.
    expect(
        call(0, null(), 0, null()),
        LS_ERR_NULL_POINTER,
        "xyz is NULL",
    );
}

#[test]
fn zero_counts_are_an_empty_net() {
    expect(
        call(0, XYZ.as_ptr(), 4, TRIS.as_ptr()),
        LS_ERR_DEGENERATE,
        "empty mesh: 0 vertices, 4 triangles",
    );
    expect(
        call(4, XYZ.as_ptr(), 0, TRIS.as_ptr()),
        LS_ERR_DEGENERATE,
        "empty mesh: 4 vertices, 0 triangles",
    );
    expect(
        call(0, XYZ.as_ptr(), 0, TRIS.as_ptr()),
        LS_ERR_DEGENERATE,
        "empty mesh: 0 vertices, 0 triangles",
    );
}

#[test]
fn indices_outside_the_net_are_out_of_range() {
    for value in [-1, -4, i32::MIN, 4, 5, i32::MAX] {
        for at in [0, 5, 11] {
            let mut tris = TRIS;
            tris[at] = value;
            let t = at / 3;
            let tri = &tris[3 * t..3 * t + 3];
            expect(
                with_index(at, value),
                LS_ERR_INDEX_OUT_OF_RANGE,
                &format!(
                    "triangle {t} {tri:?} refers to vertex {value}, but there are only 4 vertices"
                ),
            );
        }
    }
    // A triangle that also repeats a vertex: the index outside is reported.
    let one = [0.0f64; 3];
    expect(
        call(1, one.as_ptr(), 1, [0i32, 0, 1].as_ptr()),
        LS_ERR_INDEX_OUT_OF_RANGE,
        "refers to vertex 1",
    );
}

#[test]
fn repeated_indices_are_degenerate() {
    expect(with_index(1, 0), LS_ERR_DEGENERATE, "repeats vertex 0");
    expect(
        call(4, XYZ.as_ptr(), 1, [3i32, 3, 3].as_ptr()),
        LS_ERR_DEGENERATE,
        "repeats vertex 3",
    );
}

#[test]
fn non_finite_coordinates_are_refused() {
    for value in [f64::NAN, -f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for at in [0, 4, 11] {
            expect(
                with_coordinate(at, value),
                LS_ERR_NOT_FINITE,
                &format!("vertex {} has a non-finite coordinate", at / 3),
            );
        }
    }
}

#[test]
fn arrays_replay_their_fuzz_inputs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let mut files = Vec::new();
    for kind in ["corpus", "regressions"] {
        if let Ok(dir) = std::fs::read_dir(root.join(kind).join("arrays")) {
            files.extend(dir.map(|e| e.unwrap().path()));
        }
    }
    files.sort();
    assert!(
        !files.is_empty(),
        "no fuzz inputs kept (fuzz/corpus/arrays)"
    );
    for file in files {
        let data = std::fs::read(&file).unwrap();
        let case = arrays_case::decode(&data);
        let outcome = std::panic::catch_unwind(|| unsafe { arrays_case::check(&case) });
        assert!(outcome.is_ok(), "{}: {case:?}", file.display());
    }
}
