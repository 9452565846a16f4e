//! Plain triangle geometry shared by the readers, validation, the mesher
//! and adaptive subdivision: measures of one triangle of points, and edge
//! swapping in a parameter domain. Nothing here knows about subdivision.

use glam::DVec3;
use rayon::prelude::*;

pub(crate) mod swap;

/// A triangle is degenerate when twice its area is at round-off level
/// relative to its longest edge squared: its normal is then undefined (so
/// are the dihedral angles of its edges), though Loop subdivision itself
/// only needs its corners.
pub fn is_degenerate([a, b, c]: [DVec3; 3]) -> bool {
    let longest = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    let twice_area = (b - a).cross(c - a).length();
    twice_area <= 1e-14 * longest
}

/// The largest cosine of a triangle's angles (the cosine of its smallest
/// angle); degenerate triangles count as 1.
pub fn max_cosine(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let cos = |p: DVec3, q: DVec3, r: DVec3| {
        let (u, v) = (q - p, r - p);
        let d = (u.length_squared() * v.length_squared()).sqrt();
        if d > 0.0 {
            u.dot(v) / d
        } else {
            1.0
        }
    };
    cos(a, b, c).max(cos(b, c, a)).max(cos(c, a, b))
}

/// The smallest angle of any triangle of `tris` over `points`, degrees.
pub fn min_angle(points: &[DVec3], tris: &[[u32; 3]]) -> f64 {
    tris.par_iter()
        .map(|t| {
            max_cosine(
                points[t[0] as usize],
                points[t[1] as usize],
                points[t[2] as usize],
            )
        })
        .reduce(|| -1.0, f64::max)
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}
