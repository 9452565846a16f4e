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

/// The chord error of a mesh between the probes the meshers bound
/// themselves (centroids and edge midpoints): the certified distance to
/// the limit surface (`snap::closest_point`, global, no hint) from
/// `per_triangle` interior points of every triangle. Their barycentric
/// coordinates come from the R2 sequence (irrational steps, an irrational
/// start, continued from triangle to triangle), folded into the triangle:
/// never a centroid, an edge midpoint or a corner. Returns the largest
/// distance (an upper bound of the true one) and its triangle.
pub fn chord_error_between_probes(
    surface: &loopsurf::Surface,
    points: &[DVec3],
    triangles: &[[u32; 3]],
    per_triangle: usize,
) -> (f64, usize) {
    use rayon::prelude::*;
    // The plastic number's powers: the R2 sequence's steps.
    const G: f64 = 1.324_717_957_244_746;
    let (a1, a2) = (1.0 / G, 1.0 / (G * G));
    triangles
        .par_iter()
        .enumerate()
        .map(|(t, tri)| {
            let [a, b, c] = tri.map(|i| points[i as usize]);
            let worst = (0..per_triangle)
                .map(|k| {
                    let i = (t * per_triangle + k) as f64;
                    let (mut s, mut r) =
                        ((0.271_828 + i * a1).fract(), (0.141_421 + i * a2).fract());
                    if s + r > 1.0 {
                        (s, r) = (1.0 - s, 1.0 - r);
                    }
                    let x = a + s * (b - a) + r * (c - a);
                    loopsurf::snap::closest_point(surface, x).unwrap().distance
                })
                .fold(0.0, f64::max);
            (worst, t)
        })
        .reduce(|| (0.0, 0), |x, y| if y.0 > x.0 { y } else { x })
}

/// The smallest distance between two vertices of `points` (a sweep along x).
pub fn closest_vertices(points: &[DVec3]) -> f64 {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x));
    let mut closest = f64::INFINITY;
    for i in 0..sorted.len() {
        for q in &sorted[i + 1..] {
            if q.x - sorted[i].x > closest {
                break;
            }
            closest = closest.min(sorted[i].distance(*q));
        }
    }
    closest
}
