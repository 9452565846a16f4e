//! Plain triangle geometry shared by the readers, validation, the mesher
//! and adaptive subdivision: measures of one triangle of points (normals,
//! area, angles), edge swapping in a parameter domain, points in
//! Z-order, and the crate's absent index. Nothing here knows about subdivision.

use glam::DVec3;
use rayon::prelude::*;

pub mod crossings;
pub(crate) mod swap;
mod z_order;

pub use z_order::z_order;

/// An absent index: the missing triangle beside a boundary edge, a
/// half-edge without a twin, a vertex no triangle uses. One value for the
/// whole crate, defined in its lowest layer so that every layer can name
/// it; no real index reaches it, since a net holds fewer than `u32::MAX`
/// vertices and refinement refuses to make that many edges.
pub const NONE: u32 = u32::MAX;

/// The area-weighted normal of triangle (a, b, c): (b − a) × (c − a),
/// whose length is twice the area. It points to the side from which the
/// corners run counter-clockwise (the right-hand rule), so on a
/// consistently oriented closed net it points outward. Left unnormalised
/// it serves sign tests and angles without a square root, and without
/// failing on a small triangle. A degenerate triangle gives a vector at
/// round-off level (zero when two corners coincide).
pub fn area_normal([a, b, c]: [DVec3; 3]) -> DVec3 {
    (b - a).cross(c - a)
}

/// The unit normal of triangle (a, b, c), oriented as [`area_normal`];
/// the zero vector where it has none (a triangle collapsed to a segment
/// or a point), so a caller may skip it without a branch on `Option`.
pub fn unit_normal(triangle: [DVec3; 3]) -> DVec3 {
    area_normal(triangle).normalize_or_zero()
}

/// The area of triangle (a, b, c): half the length of its
/// [`area_normal`]; never negative, round-off level when degenerate.
pub fn area(triangle: [DVec3; 3]) -> f64 {
    0.5 * area_normal(triangle).length()
}

/// The angle between two vectors, radians in [0, π], as atan2 of |a × b|
/// and a · b: accurate near 0 and π, where the arccosine of the cosine
/// loses half its digits (a nearly flat edge, a fold). 0 if either is zero.
pub fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The dihedral angle of two triangles, radians: the [`angle`] between
/// their normals, 0 where they are coplanar and equally oriented, π where
/// one folds back onto the other. `None` when either is degenerate
/// ([`is_degenerate`]): a triangle without a normal has no angle to its
/// neighbour.
pub fn dihedral_angle(t0: [DVec3; 3], t1: [DVec3; 3]) -> Option<f64> {
    if is_degenerate(t0) || is_degenerate(t1) {
        return None;
    }
    Some(angle(area_normal(t0), area_normal(t1)))
}

/// A triangle is degenerate when twice its area is at round-off level
/// relative to its longest edge squared: its normal is then undefined (so
/// are the dihedral angles of its edges), though Loop subdivision itself
/// only needs its corners.
pub fn is_degenerate(triangle: [DVec3; 3]) -> bool {
    let [a, b, c] = triangle;
    let longest = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    let twice_area = area_normal(triangle).length();
    twice_area <= 1e-14 * longest
}

/// The axis along which `d` is largest (the first of equals): the one a
/// median split of boxes cuts, the one a triangle's normal says to drop.
pub(crate) fn largest_axis(d: DVec3) -> usize {
    if d.x >= d.y && d.x >= d.z {
        0
    } else if d.y >= d.z {
        1
    } else {
        2
    }
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
