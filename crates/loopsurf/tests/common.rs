//! Shared helpers for the integration tests: synthetic nets and the CGAL
//! meshes cached by the test script.
#![allow(dead_code)]

use loopsurf::{ControlNet, DVec3};
use std::f64::consts::TAU;
use std::path::PathBuf;

/// A CGAL demo mesh from the cache the test command extracts, or None (with a
/// note) when running outside it.
pub fn cgal_mesh(name: &str) -> Option<PathBuf> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../.cache/cgal/data/meshes")
        .join(name);
    if path.exists() {
        Some(path)
    } else {
        assert!(
            std::env::var_os("LOOPSURF_REQUIRE_DATA").is_none(),
            "{} missing: run scripts/test.sh",
            path.display()
        );
        eprintln!(
            "skipping: {} not extracted (scripts/test.sh does that)",
            path.display()
        );
        None
    }
}

/// A wavy bicone: two apexes of valence `n` joined by two rings of `n`
/// vertices; closed. With `open`, the bottom apex is left out, so the lower
/// ring is a boundary loop.
pub fn bicone(n: usize, open: bool) -> ControlNet {
    let mut points = vec![DVec3::new(0.1, -0.05, 1.3)];
    for ring in 0..2 {
        for i in 0..n {
            let a = TAU * (i as f64 + 0.5 * ring as f64) / n as f64;
            let r = 1.0 + 0.15 * (3.0 * a).sin() + 0.05 * ring as f64;
            let z = 0.4 - 0.8 * ring as f64 + 0.1 * (2.0 * a).cos();
            points.push(DVec3::new(r * a.cos(), r * a.sin(), z));
        }
    }
    let top_ring = |i: usize| 1 + (i % n) as u32;
    let low_ring = |i: usize| 1 + n as u32 + (i % n) as u32;
    let mut tris = Vec::new();
    for i in 0..n {
        tris.push([0, top_ring(i), top_ring(i + 1)]);
        tris.push([top_ring(i), low_ring(i), top_ring(i + 1)]);
        tris.push([top_ring(i + 1), low_ring(i), low_ring(i + 1)]);
    }
    if !open {
        let bottom = points.len() as u32;
        points.push(DVec3::new(-0.05, 0.1, -1.2));
        for i in 0..n {
            tris.push([bottom, low_ring(i + 1), low_ring(i)]);
        }
    }
    ControlNet::from_arrays(points, &tris).unwrap()
}
