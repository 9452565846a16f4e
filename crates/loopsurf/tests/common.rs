//! Shared helpers for the integration tests: synthetic nets and the CGAL
//! meshes cached by the test script.
#![allow(dead_code)]

use loopsurf::ControlNet;
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

/// [`loopsurf::examples::bicone`] as a control net.
pub fn bicone(n: usize, open: bool) -> ControlNet {
    let ex = loopsurf::examples::bicone(n, open);
    ControlNet::from_arrays(ex.points, &ex.tris).unwrap()
}

/// A built-in example as a control net, hard edges tagged above `angle`.
pub fn example(name: &str, angle: Option<f64>) -> ControlNet {
    let ex = loopsurf::examples::by_name(name).unwrap();
    let mut net = ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
    if let Some(a) = angle {
        net.tag_by_angle(a).unwrap();
    }
    net
}
