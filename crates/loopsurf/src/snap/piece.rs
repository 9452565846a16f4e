//! Pieces: dyadic sub-triangles of a control triangle's parameter domain
//! that the snap search refines below the index's finest cells, each with a
//! container of its piece of surface that tightens as it is split.
//!
//! A piece either lies in one polynomial of the surface (every dyadic
//! triangle that does not touch a special vertex does: regular level-1
//! children are one box spline, special ones a sequence of rings of them)
//! and is held in Bézier form, or it is the corner region of a special
//! vertex, held as the vertex's neighbourhood pushed down to its ring. The
//! first kind splits exactly by de Casteljau; the second into three
//! polynomial pieces of its ring and the corner region of the next ring.

use super::bezier::Quartic;
use super::cell::CellBound;
use crate::eval::affine::Affine;
use crate::parameters::CORNERS;
use crate::surface::{Surface, SurfaceMode};
use glam::{DVec2, DVec3};

/// How many levels a piece may lie below its polynomial region.
const MAX_DEPTH: usize = 64;

/// A piece of control triangle `tri`: the dyadic triangle `corners` (in
/// the triangle's (v, w)) of level `level`.
pub(crate) struct Piece {
    pub(crate) tri: usize,
    pub(crate) level: u32,
    pub(crate) corners: [DVec2; 3],
    pub(crate) shape: Shape,
}

// Pieces live a moment in one query's arena: boxing the polynomial would
// cost an allocation each.
#[allow(clippy::large_enum_variant)]
pub(crate) enum Shape {
    /// One quartic polynomial, in Bézier form on the piece.
    Poly(Quartic),
    /// The region at the special vertex at corner `at` of the piece: the
    /// neighbourhood of its ring as offsets from the vertex's limit point,
    /// and the surface (displaced, where it is) at the piece's corners: the
    /// frame of its container.
    Corner {
        at: usize,
        offsets: Vec<DVec3>,
        limit: DVec3,
        frame: [DVec3; 3],
    },
}

impl Piece {
    /// The piece for the dyadic triangle `corners` of level ≥ 1.
    pub(crate) fn new(surface: &Surface, tri: usize, level: u32, corners: [DVec2; 3]) -> Piece {
        debug_assert!(level >= 1, "a whole control triangle is not one piece");
        let evaluator = surface.evaluator();
        for (at, corner) in corners.iter().enumerate() {
            let Some(k) = CORNERS.iter().position(|c| c == corner) else {
                continue;
            };
            if let Some((patch, around)) = evaluator.special_corner(tri, k) {
                let (offsets, limit) =
                    patch.ring_offsets(evaluator.refined_points(), around, level as usize - 1);
                let frame = std::array::from_fn(|i| {
                    let uv = corners[i];
                    if i == at {
                        surface.displaced_point(tri, uv.x, uv.y, limit)
                    } else {
                        surface.displaced_point(tri, uv.x, uv.y, evaluator.point(tri, uv.x, uv.y))
                    }
                });
                return Piece {
                    tri,
                    level,
                    corners,
                    shape: Shape::Corner {
                        at,
                        offsets,
                        limit,
                        frame,
                    },
                };
            }
        }
        Piece::poly(surface, tri, level, corners)
    }

    /// A piece known to lie in one polynomial: that polynomial from the
    /// evaluator, cut down to the piece.
    fn poly(surface: &Surface, tri: usize, level: u32, corners: [DVec2; 3]) -> Piece {
        let centre = (corners[0] + corners[1] + corners[2]) / 3.0;
        let region = surface
            .evaluator()
            .bezier_at(tri, centre.x, centre.y)
            .expect("a piece off special vertices");
        Piece::within(surface, tri, level, corners, region)
    }

    /// The piece `corners` (of level `level`) of the polynomial region
    /// given in Bézier form on its own triangle with the map into that
    /// triangle's parameters: the region split down to the piece. The
    /// piece's corners come in the region's order.
    fn within(
        surface: &Surface,
        tri: usize,
        level: u32,
        corners: [DVec2; 3],
        (bezier, to_region): ([DVec3; 15], Affine),
    ) -> Piece {
        let from_region = inverse(&to_region);
        let mut at = CORNERS.map(|c| {
            let (v, w) = from_region.apply(c.x, c.y);
            DVec2::new(v, w)
        });
        let mut q = Quartic(bezier);
        let centre = (corners[0] + corners[1] + corners[2]) / 3.0;
        let same = |a: &[DVec2; 3]| a.iter().all(|x| corners.contains(x));
        // Dyadic corners are exact in binary: the walk meets the piece.
        for _ in 0..2 * MAX_DEPTH {
            if same(&at) {
                break;
            }
            let children = children(at);
            let c = (0..4)
                .find(|&c| contains(children[c], centre))
                .expect("the piece lies in its region");
            q = q.child(c);
            at = children[c];
        }
        debug_assert!(
            same(&at),
            "the piece {corners:?} is a dyadic part of its region"
        );
        if surface.mode() == SurfaceMode::Displacement {
            q = displaced(surface, tri, at, q);
        }
        Piece {
            tri,
            level,
            corners: at,
            shape: Shape::Poly(q),
        }
    }

    /// A convex container of the piece of surface, grown by `pad`.
    pub(crate) fn container(&self, surface: &Surface, pad: f64) -> CellBound {
        match &self.shape {
            Shape::Poly(q) => CellBound::new(q.corners(), q.0, pad),
            Shape::Corner {
                offsets,
                limit,
                frame,
                ..
            } => {
                let corners = *frame;
                // The displacement is linear over the piece: its values lie
                // in the hull of those at the piece's corners.
                let d = surface.displacements_of(self.tri);
                let shifts = self
                    .corners
                    .map(|uv| (1.0 - uv.x - uv.y) * d[0] + uv.x * d[1] + uv.y * d[2]);
                CellBound::new(corners, offsets.iter().map(|o| *o + *limit), pad).shifted(shifts)
            }
        }
    }

    /// The four children, numbered like the index's cells.
    pub(crate) fn split(self, surface: &Surface) -> Vec<Piece> {
        let children = children(self.corners);
        let level = self.level + 1;
        match self.shape {
            Shape::Poly(q) => q
                .split()
                .into_iter()
                .zip(children)
                .map(|(q, corners)| Piece {
                    tri: self.tri,
                    level,
                    corners,
                    shape: Shape::Poly(q),
                })
                .collect(),
            Shape::Corner {
                at, offsets, limit, ..
            } => {
                let child = CORNERS
                    .iter()
                    .position(|c| *c == self.corners[at])
                    .expect("a corner region sits at a corner");
                let evaluator = surface.evaluator();
                let (patch, _) = evaluator
                    .special_corner(self.tri, child)
                    .expect("a special corner");
                // The three regular cells of this ring, from the ring's points.
                let mut pieces: Vec<Piece> = (0..4)
                    .filter(|&c| c != at)
                    .map(|c| {
                        let corners = children[c];
                        let centre = (corners[0] + corners[1] + corners[2]) / 3.0;
                        let region = evaluator
                            .ring_bezier(self.tri, child, (&offsets, limit), (centre.x, centre.y))
                            .expect("a ring cell");
                        Piece::within(surface, self.tri, level, corners, region)
                    })
                    .collect();
                // The next corner region; its corners are the vertex and
                // corners of the ring's cells, whose surface points those
                // hold already.
                let corners = children[at];
                let frame = std::array::from_fn(|i| {
                    if i == at {
                        let uv = corners[at];
                        return surface.displaced_point(self.tri, uv.x, uv.y, limit);
                    }
                    pieces
                        .iter()
                        .find_map(|piece| {
                            let Shape::Poly(q) = &piece.shape else {
                                return None;
                            };
                            let k = piece.corners.iter().position(|c| *c == corners[i])?;
                            Some(q.corners()[k])
                        })
                        .expect("a ring cell shares each side's midpoint")
                });
                pieces.push(Piece {
                    tri: self.tri,
                    level,
                    corners,
                    shape: Shape::Corner {
                        at,
                        offsets: patch.next_ring(&offsets),
                        limit,
                        frame,
                    },
                });
                pieces
            }
        }
    }

    /// Local (s, t) of (v, w) of the control triangle.
    pub(crate) fn local(&self, uv: DVec2) -> DVec2 {
        let [a, b, c] = self.corners;
        let (e1, e2, r) = (b - a, c - a, uv - a);
        let det = e1.x * e2.y - e1.y * e2.x;
        DVec2::new(r.x * e2.y - r.y * e2.x, e1.x * r.y - e1.y * r.x) / det
    }

    /// (v, w) of the control triangle at local (s, t).
    pub(crate) fn global(&self, st: DVec2) -> DVec2 {
        let [a, b, c] = self.corners;
        a + st.x * (b - a) + st.y * (c - a)
    }
}

/// The four children of a triangle, numbered as uniform refinement numbers
/// triangles: child c < 3 at corner c, child 3 in the middle.
fn children([c0, c1, c2]: [DVec2; 3]) -> [[DVec2; 3]; 4] {
    let (m0, m1, m2) = ((c0 + c1) / 2.0, (c1 + c2) / 2.0, (c2 + c0) / 2.0);
    [[c0, m0, m2], [m0, c1, m1], [m2, m1, c2], [m1, m2, m0]]
}

/// Whether the triangle (counter-clockwise) holds `x` (inside, not on a side).
fn contains([a, b, c]: [DVec2; 3], x: DVec2) -> bool {
    let side = |p: DVec2, q: DVec2| (q - p).perp_dot(x - p) > 0.0;
    side(a, b) && side(b, c) && side(c, a)
}

/// The inverse of an invertible affine map.
fn inverse(f: &Affine) -> Affine {
    let [[a, b], [c, d]] = f.m;
    let det = a * d - b * c;
    let m = [[d / det, -b / det], [-c / det, a / det]];
    let b = [
        -(m[0][0] * f.b[0] + m[0][1] * f.b[1]),
        -(m[1][0] * f.b[0] + m[1][1] * f.b[1]),
    ];
    Affine { m, b }
}

/// The piece `corners` of `tri` moved by the displacement field, which is
/// linear there: its Bézier coefficients are its values at the domain
/// points.
fn displaced(surface: &Surface, tri: usize, [a, b, c]: [DVec2; 3], q: Quartic) -> Quartic {
    let d = surface.displacements_of(tri);
    let points = Quartic::domain_points();
    Quartic(std::array::from_fn(|i| {
        let (s, t) = points[i];
        let uv = a + s * (b - a) + t * (c - a);
        q.0[i] + (1.0 - uv.x - uv.y) * d[0] + uv.x * d[1] + uv.y * d[2]
    }))
}
