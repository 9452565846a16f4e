//! Cells: the pieces of a control triangle's patch after a few uniform
//! subdivision steps, each with a container that provably holds its piece
//! of the surface and is tight to second order.
//!
//! A cell's container is built around the flat triangle through the surface
//! points at its corners: every point of the piece lies within `lateral` of
//! that triangle when projected onto its plane, and between `below` and
//! `above` along its normal. Far from the cell this is as good as the box;
//! right above it the lower bound it gives is the height minus the piece's
//! bulge, which is of the order of curvature × size² — so only the cells
//! next to the nearest point survive the pruning.

use crate::geometry::area_normal;
use crate::parameters::CORNERS;
use glam::{DVec2, DVec3};
use std::ops::{Add, Mul, Sub};

/// A convex set holding one cell's piece of the surface, in the frame of
/// its flat triangle: origin at corner 0, axes e1, e2 in the plane and the
/// unit normal n (any orthonormal frame when the triangle is degenerate:
/// the container stays valid, only looser).
#[derive(Debug, Clone, Copy)]
pub(crate) struct CellBound {
    origin: DVec3,
    axes: [DVec3; 3],
    /// Corners 1 and 2 in the plane's coordinates (corner 0 is the origin).
    corners: [DVec2; 2],
    /// How far the piece reaches, in the plane, beyond the flat triangle.
    lateral: f64,
    /// The range of the height n · (x − origin) over the piece.
    below: f64,
    above: f64,
}

impl CellBound {
    /// The container of the convex hull of `points` (which must hold the
    /// piece), around the flat triangle `corners`, grown by `pad` for
    /// round-off.
    pub(crate) fn new(
        [a, b, c]: [DVec3; 3],
        points: impl IntoIterator<Item = DVec3>,
        pad: f64,
    ) -> Self {
        let n = flat_normal([a, b, c]);
        let e1 = (b - a)
            .reject_from_normalized(n)
            .try_normalize()
            .unwrap_or_else(|| n.any_orthonormal_vector());
        let axes = [e1, n.cross(e1), n];
        let mut bound = CellBound {
            origin: a,
            axes,
            corners: [DVec2::ZERO; 2],
            lateral: 0.0,
            below: 0.0,
            above: 0.0,
        };
        bound.corners = [b, c].map(|x| bound.local(x).truncate());
        for s in points {
            let q = bound.local(s);
            bound.lateral = bound.lateral.max(bound.outside(q.truncate()));
            bound.below = bound.below.min(q.z);
            bound.above = bound.above.max(q.z);
        }
        bound.lateral += pad;
        bound.below -= pad;
        bound.above += pad;
        bound
    }

    /// The container of the piece moved by any convex combination of
    /// `shifts` (the corner displacements of a displaced surface): the
    /// Minkowski sum with their hull.
    pub(crate) fn shifted(mut self, shifts: [DVec3; 3]) -> Self {
        let local = shifts.map(|d| {
            DVec3::new(
                d.dot(self.axes[0]),
                d.dot(self.axes[1]),
                d.dot(self.axes[2]),
            )
        });
        self.lateral += local
            .iter()
            .map(|d| d.truncate().length())
            .fold(0.0, f64::max);
        self.below += local.iter().map(|d| d.z).fold(f64::INFINITY, f64::min);
        self.above += local.iter().map(|d| d.z).fold(f64::NEG_INFINITY, f64::max);
        self
    }

    /// x in the frame: in-plane coordinates and height.
    fn local(&self, x: DVec3) -> DVec3 {
        let r = x - self.origin;
        DVec3::new(
            r.dot(self.axes[0]),
            r.dot(self.axes[1]),
            r.dot(self.axes[2]),
        )
    }

    /// Distance of an in-plane point from the flat triangle.
    fn outside(&self, q: DVec2) -> f64 {
        let [b, c] = self.corners;
        // Inside (the usual case for the points a container is made of):
        // on the inner side of all three sides, whatever the orientation.
        let (s0, s1, s2) = (b.perp_dot(q), (c - b).perp_dot(q - b), (-c).perp_dot(q - c));
        if (s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0) || (s0 <= 0.0 && s1 <= 0.0 && s2 <= 0.0) {
            return 0.0;
        }
        let t = closest_in_triangle(q, DVec2::ZERO, b, c);
        (q - (t.x * b + t.y * c)).length()
    }

    /// A lower bound on the distance from `p` to the cell's piece of
    /// surface: the distance to the container, a product of a thickened
    /// triangle and an interval. Once the height alone rules the cell out
    /// (reaches `cutoff`), that is returned without the in-plane part.
    pub(crate) fn lower_bound(&self, p: DVec3, cutoff: f64) -> f64 {
        let q = self.local(p);
        let along = (self.below - q.z).max(q.z - self.above).max(0.0);
        if along >= cutoff {
            return along;
        }
        let across = (self.outside(q.truncate()) - self.lateral).max(0.0);
        (across * across + along * along).sqrt()
    }

    /// Barycentric (v, w) of the point of the flat triangle nearest to `p`.
    pub(crate) fn nearest(&self, p: DVec3) -> DVec2 {
        let [b, c] = self.corners;
        closest_in_triangle(self.local(p).truncate(), DVec2::ZERO, b, c)
    }
}

/// The unit normal of a triangle, or a unit vector if it has none.
fn flat_normal(triangle: [DVec3; 3]) -> DVec3 {
    let [a, b, c] = triangle;
    let (e1, e2) = (b - a, c - a);
    area_normal(triangle)
        .try_normalize()
        .or_else(|| e1.any_orthonormal_vector().try_normalize())
        .or_else(|| e2.any_orthonormal_vector().try_normalize())
        .unwrap_or(DVec3::Z)
}

/// Points of the plane or of space.
pub(crate) trait Point:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self>
{
    fn dot(self, other: Self) -> f64;
}
impl Point for DVec2 {
    fn dot(self, other: Self) -> f64 {
        DVec2::dot(self, other)
    }
}
impl Point for DVec3 {
    fn dot(self, other: Self) -> f64 {
        DVec3::dot(self, other)
    }
}

/// Barycentric (v, w) of the point of triangle (a, b, c) nearest to p, the
/// point being a + v (b − a) + w (c − a). By Voronoi regions of the corners
/// and edges; a degenerate triangle gets the nearest point of its sides.
pub(crate) fn closest_in_triangle<P: Point>(p: P, a: P, b: P, c: P) -> DVec2 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return CORNERS[0];
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return CORNERS[1];
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return DVec2::new(d1 / (d1 - d3), 0.0);
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return CORNERS[2];
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return DVec2::new(0.0, d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 >= d3 && d5 >= d6 {
        let t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return DVec2::new(1.0 - t, t);
    }
    let sum = va + vb + vc;
    if sum > 0.0 && sum.is_finite() {
        return DVec2::new(vb, vc) / sum;
    }
    // Degenerate (collinear or non-finite): the nearest of the three sides.
    let side = |from: DVec2, to: DVec2| {
        let (x0, x1) = (a + ab * from.x + ac * from.y, a + ab * to.x + ac * to.y);
        let len2 = (x1 - x0).dot(x1 - x0);
        let s = if len2 > 0.0 {
            ((p - x0).dot(x1 - x0) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let gap = x0 + (x1 - x0) * s - p;
        (gap.dot(gap), from + s * (to - from))
    };
    (0..3)
        .map(|k| side(CORNERS[k], CORNERS[(k + 1) % 3]))
        .min_by(|s, t| s.0.total_cmp(&t.0))
        .map_or(DVec2::ZERO, |(_, q)| q)
}

/// The control triangle of cell `cell` of level `level` and the parameters
/// of its corners there. Cells are numbered as uniform refinement numbers
/// triangles: the children of t are 4t … 4t + 3, (c0 m0 m2), (m0 c1 m1),
/// (m2 m1 c2), (m1 m2 m0), mᵢ the midpoint of the side from cᵢ to cᵢ₊₁.
pub(crate) fn cell_corners(cell: usize, level: u32) -> (usize, [DVec2; 3]) {
    let mut c = CORNERS;
    for k in (0..level).rev() {
        let m = [
            (c[0] + c[1]) / 2.0,
            (c[1] + c[2]) / 2.0,
            (c[2] + c[0]) / 2.0,
        ];
        c = match (cell >> (2 * k)) & 3 {
            0 => [c[0], m[0], m[2]],
            1 => [m[0], c[1], m[1]],
            2 => [m[2], m[1], c[2]],
            _ => [m[1], m[2], m[0]],
        };
    }
    (cell >> (2 * level), c)
}

/// The cell of level `level` holding (v, w) of control triangle `tri` (on
/// a side shared by two cells, either).
#[cfg(test)]
fn cell_at(tri: usize, v: f64, w: f64, level: u32) -> usize {
    let (mut cell, mut s, mut t) = (tri, v, w);
    for _ in 0..level {
        let (child, s1, t1) = if s + t <= 0.5 {
            (0, 2.0 * s, 2.0 * t)
        } else if s >= 0.5 {
            (1, 2.0 * s - 1.0, 2.0 * t)
        } else if t >= 0.5 {
            (2, 2.0 * s, 2.0 * t - 1.0)
        } else {
            (3, 1.0 - 2.0 * s, 1.0 - 2.0 * t)
        };
        (cell, s, t) = (4 * cell + child, s1, t1);
    }
    cell
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Voronoi-region answer against a dense sampling of the triangle.
    #[test]
    fn closest_in_triangle_is_the_nearest_point() {
        let tris = [
            [DVec3::ZERO, DVec3::X, DVec3::Y],
            [
                DVec3::new(0.3, -0.2, 0.1),
                DVec3::new(2.0, 0.5, -0.4),
                DVec3::new(-0.5, 1.5, 0.8),
            ],
            // Degenerate: collinear corners.
            [DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)],
        ];
        let n = 60;
        for [a, b, c] in tris {
            for i in -4..=8 {
                for j in -4..=8 {
                    let p = DVec3::new(i as f64 / 4.0, j as f64 / 4.0, 0.3 - 0.07 * i as f64);
                    let q = closest_in_triangle(p, a, b, c);
                    assert!(q.x >= 0.0 && q.y >= 0.0 && q.x + q.y <= 1.0 + 1e-15);
                    let got = (a + q.x * (b - a) + q.y * (c - a) - p).length();
                    let sampled = (0..=n)
                        .flat_map(|k| (0..=n - k).map(move |l| (k, l)))
                        .map(|(k, l)| {
                            let (v, w) = (k as f64 / n as f64, l as f64 / n as f64);
                            (a + v * (b - a) + w * (c - a) - p).length()
                        })
                        .fold(f64::INFINITY, f64::min);
                    assert!(got <= sampled + 1e-12, "{p}: {got} > {sampled}");
                    assert!(got >= sampled - 0.05, "{p}: {got} far below the sampling");
                }
            }
        }
    }

    /// Every point of the hull is at least the bound away; a point above the
    /// flat triangle gets its height minus the bulge.
    #[test]
    fn lower_bound_holds_for_the_hull() {
        let corners = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let points = [
            DVec3::new(-0.1, -0.1, 0.02),
            DVec3::new(1.1, 0.0, -0.01),
            DVec3::new(0.0, 1.1, 0.03),
            DVec3::new(0.3, 0.3, 0.05),
        ];
        let bound = CellBound::new(corners, points, 0.0);
        let p = DVec3::new(0.25, 0.25, 1.0);
        assert!((bound.lower_bound(p, f64::INFINITY) - 0.95).abs() < 1e-15);
        for q in [DVec3::new(3.0, -2.0, 0.5), DVec3::new(-1.0, 0.4, -0.7), p] {
            for (i, s) in points.iter().enumerate() {
                for t in &points[i..] {
                    let x = 0.5 * (*s + *t);
                    assert!(bound.lower_bound(q, f64::INFINITY) <= (x - q).length() + 1e-15);
                    assert!(bound.lower_bound(q, 0.1) <= (x - q).length() + 1e-15);
                }
            }
        }
    }

    #[test]
    fn cells_tile_the_parameter_triangle() {
        for level in 0..4 {
            let area: f64 = (0..(1usize << (2 * level)) * 3)
                .map(|cell| {
                    let (tri, [a, b, c]) = cell_corners(cell, level);
                    assert_eq!(tri, cell >> (2 * level));
                    let (e1, e2) = (b - a, c - a);
                    (e1.x * e2.y - e1.y * e2.x).abs() / 2.0
                })
                .sum();
            assert!((area - 1.5).abs() < 1e-15, "level {level}: {area}");
            for cell in 0..(1usize << (2 * level)) * 3 {
                let (tri, [a, b, c]) = cell_corners(cell, level);
                let centre = (a + b + c) / 3.0;
                assert_eq!(cell_at(tri, centre.x, centre.y, level), cell);
            }
        }
    }
}
