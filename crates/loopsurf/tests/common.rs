//! Shared helpers for the integration tests: synthetic nets and the CGAL
//! meshes cached by the test script.
#![allow(dead_code)]

use loopsurf::ControlNet;
use std::path::PathBuf;

#[path = "support/cgal_data.rs"]
mod cgal_data;

/// A CGAL demo mesh (see [`cgal_data`]): `None` only when the data is
/// absent and `LOOPSURF_SKIP_DATA` asks to skip.
pub fn cgal_mesh(name: &str) -> Option<PathBuf> {
    cgal_data::cgal_file(name)
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
