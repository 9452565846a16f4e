//! The fuzzers' findings and minimised corpora, replayed on stable: every
//! file under `fuzz/corpus/<target>/` and `fuzz/regressions/<target>/` goes
//! through what its fuzz target does (fuzz/fuzz_targets/), and must end in
//! a result or a clear error — no panic, in bounded memory and time. The
//! targets outside this crate are replayed where they can be reached:
//! `queries` by crates/loopsurf-cli/tests/query_lines.rs, `arrays` by
//! crates/loopsurf-capi/tests/hostile_arrays.rs.

use loopsurf::io::{parse_mesh, ParseOptions};
use loopsurf::repair::Repairs;
use loopsurf::{ControlNet, Surface};
use std::path::{Path, PathBuf};

/// The inputs kept for one target.
fn inputs(target: &str) -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let mut files = Vec::new();
    for kind in ["corpus", "regressions"] {
        if let Ok(dir) = std::fs::read_dir(root.join(kind).join(target)) {
            files.extend(dir.map(|e| e.unwrap().path()));
        }
    }
    files.sort();
    files
}

/// What fuzz/fuzz_targets/<format>.rs does with one input.
fn mesh_pipeline(format: &str, data: &[u8]) {
    // Plain, split polygons, and every repair (which parse untrusted data too).
    for (triangulate, repairs) in [
        (false, Repairs::default()),
        (true, Repairs::default()),
        (true, Repairs::all()),
    ] {
        let opts = ParseOptions { triangulate };
        let name = format!("input.{format}");
        let Ok(mesh) = parse_mesh(data.to_vec(), Path::new(&name), &opts) else {
            continue;
        };
        if let Ok(net) = ControlNet::from_mesh_data_with(mesh, &repairs) {
            if net.triangles().len() <= 64 {
                let _ = Surface::new(&net);
            }
        }
    }
}

/// Runs `pipeline` on every kept input of fuzz target `target`, which
/// must have some: each ends in a result or an error, never a panic.
fn replay(target: &str, pipeline: impl Fn(&[u8]) + std::panic::RefUnwindSafe) {
    let files = inputs(target);
    assert!(
        !files.is_empty(),
        "{target}: no fuzz inputs kept (fuzz/corpus/{target})"
    );
    for file in files {
        let data = std::fs::read(&file).unwrap();
        let outcome = std::panic::catch_unwind(|| pipeline(&data));
        assert!(outcome.is_ok(), "{} panicked", file.display());
    }
}

#[test]
fn mesh_readers_replay_their_fuzz_inputs() {
    for format in ["off", "obj", "ply", "stl", "tri"] {
        replay(format, |data| mesh_pipeline(format, data));
    }
}

/// The high-order readers (fuzz/fuzz_targets/msh.rs and vtu.rs): parse,
/// then the Lagrange mesh the file holds.
#[test]
fn lagrange_readers_replay_their_fuzz_inputs() {
    replay("msh", |data| {
        let _ = loopsurf::io::parse_msh(data, Path::new("input.msh")).and_then(|m| m.to_lagrange());
    });
    replay("vtu", |data| {
        let _ = loopsurf::io::parse_vtu(data, Path::new("input.vtu")).and_then(|m| m.to_lagrange());
    });
}

#[test]
fn surface_streams_replay_their_fuzz_inputs() {
    replay("stream", |data| {
        let _ = loopsurf::stream::from_bytes(data);
    });
}

/// The outcomes of a job of remeshing by parts, as ranks send them
/// (fuzz/fuzz_targets/outcomes.rs).
#[test]
fn remesh_outcomes_replay_their_fuzz_inputs() {
    replay("outcomes", |data| {
        let _ = loopsurf::remesh::outcomes_from_bytes(data);
    });
}

/// A file of a hundred bytes claiming 2³¹ vertices is refused (or read for
/// what it holds) without reserving memory for the claim.
#[test]
fn huge_counts_in_tiny_files_are_refused_cheaply() {
    let cases: [(&str, Vec<u8>); 4] = [
        ("off", b"OFF\n2147483647 2147483647 0\n0 0 0\n".to_vec()),
        ("ply", b"ply\nformat ascii 1.0\nelement vertex 2147483647\nproperty float x\nproperty float y\nproperty float z\nelement face 2147483647\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n".to_vec()),
        ("tri", b"2147483647 2147483647\n0 0 0\n".to_vec()),
        ("stl", {
            let mut b = vec![0u8; 80];
            b.extend_from_slice(&u32::MAX.to_le_bytes());
            b.extend_from_slice(&[0u8; 50]);
            b
        }),
    ];
    for (format, data) in cases {
        let name = format!("input.{format}");
        let result = parse_mesh(data, Path::new(&name), &ParseOptions::default());
        assert!(
            result.is_err(),
            "{format}: a truncated file with huge counts read"
        );
    }
}
