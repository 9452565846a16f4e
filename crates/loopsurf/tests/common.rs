//! Shared helpers for the integration tests: synthetic nets and the CGAL
//! meshes cached by the test script.
#![allow(dead_code)]

use loopsurf::{ControlNet, DVec3};
use std::path::PathBuf;

#[path = "support/cgal_data.rs"]
pub mod cgal_data;

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

/// Deterministic pseudo-random numbers in [0, 1), for reproducible queries.
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A point of the box [lo, hi].
    pub fn point_in(&mut self, lo: DVec3, hi: DVec3) -> DVec3 {
        lo + (hi - lo) * DVec3::new(self.next(), self.next(), self.next())
    }

    /// A random unit vector.
    pub fn direction(&mut self) -> DVec3 {
        loop {
            let d = DVec3::new(self.next(), self.next(), self.next()) * 2.0 - 1.0;
            if (0.01..=1.0).contains(&d.length_squared()) {
                return d.normalize();
            }
        }
    }
}
