//! Points of the surface named by parameters: a control triangle and
//! barycentric (v, w), the weights (1 − v − w, v, w) of its corners c0, c1,
//! c2 (DESIGN.md's parameterisation).
//!
//! What every layer above needs to know about these parameters, said once:
//! where a triangle's corners lie, which parameters name a control vertex,
//! and how a point moves into another triangle's parameters. Connectivity
//! only: nothing here evaluates the surface.

use crate::topology::{Topology, NONE};
use glam::DVec2;

/// A point of the surface named by its control triangle and barycentric
/// parameters (v, w): weights (1 − v − w, v, w) on the triangle's corners.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    pub tri: u32,
    pub v: f64,
    pub w: f64,
}

/// The parameters (v, w) of a triangle's corners c0, c1, c2: corner k is
/// where its own weight is 1 and the other two are 0. Local edge k runs
/// from corner k to corner k + 1 (mod 3), as in [`Topology`].
pub const CORNERS: [DVec2; 3] = [DVec2::ZERO, DVec2::X, DVec2::Y];

/// Interior sample parameters (v, w) of a control triangle for curvature
/// estimates: the centroid, points towards each corner and each side
/// (curvature peaks next to irregular vertices), none exactly on the
/// boundary (special corners report no derivatives). The chart mesher's
/// density and the remesher's sizes sample the same points.
pub const INTERIOR_SAMPLES: [(f64, f64); 10] = [
    (1.0 / 3.0, 1.0 / 3.0),
    (0.05, 0.05),
    (0.9, 0.05),
    (0.05, 0.9),
    (0.45, 0.05),
    (0.45, 0.5),
    (0.05, 0.45),
    (0.2, 0.2),
    (0.6, 0.2),
    (0.2, 0.6),
];

impl SurfacePoint {
    /// Corner `k` of triangle `tri`: exactly the limit position of the
    /// control vertex there.
    pub fn corner(tri: u32, k: usize) -> SurfacePoint {
        let (v, w) = CORNERS[k].into();
        SurfacePoint { tri, v, w }
    }

    /// The weights (1 − v − w, v, w) of the triangle's corners c0, c1, c2.
    pub fn weights(&self) -> [f64; 3] {
        [1.0 - self.v - self.w, self.v, self.w]
    }
}

/// Parameters a round-off excursion took outside the triangle (v ≥ 0,
/// w ≥ 0, v + w ≤ 1) put back in it: negative ones to 0, an excess of
/// v + w over 1 taken half from each. Cheap and exact inside the triangle;
/// for a point far outside it is no nearest point.
#[inline]
pub fn clamp_to_triangle(uv: DVec2) -> DVec2 {
    let (v, w) = (uv.x.max(0.0), uv.y.max(0.0));
    let excess = (v + w - 1.0).max(0.0);
    DVec2::new((v - excess / 2.0).max(0.0), (w - excess / 2.0).max(0.0))
}

/// Control vertex `vertex` as the corner it is of triangle `tri`; `None`
/// when it is not one of `tri`'s corners. The position there is the
/// vertex's limit whichever triangle names it, but at a crease or corner
/// the triangle picks the sector, whose one-sided derivatives and normal
/// are its own.
pub fn vertex_in(topo: &Topology, tri: u32, vertex: u32) -> Option<SurfacePoint> {
    let k = topo.triangles()[tri as usize]
        .iter()
        .position(|&c| c == vertex)?;
    Some(SurfacePoint::corner(tri, k))
}

/// Control vertex `vertex` as a point of the surface: the corner it is of
/// the first triangle of its fan ([`Topology::fan`]). `None` for a vertex
/// no triangle uses.
pub fn vertex_point(topo: &Topology, vertex: u32) -> Option<SurfacePoint> {
    let &tri = topo.fan(vertex as usize).first()?;
    vertex_in(topo, tri, vertex)
}

/// Point `p` in the parameters of control triangle `into`: possible when
/// `p` lies on a corner or side that `into` shares with `p.tri`, its
/// weights on the corners `into` lacks zero to round-off (1e-12; they are
/// dropped). `None` otherwise. Any triangle holding the corner or side
/// will do, not only an edge neighbour: around a vertex, every triangle
/// of its fan.
pub fn reparameterize(topo: &Topology, p: SurfacePoint, into: u32) -> Option<SurfacePoint> {
    if p.tri == into {
        return Some(p);
    }
    let from = topo.triangles().get(p.tri as usize)?;
    let to = topo.triangles().get(into as usize)?;
    let weights = p.weights();
    let mut out = [0.0; 3];
    for k in 0..3 {
        // Points on a side carry round-off in the third weight.
        if weights[k].abs() > 1e-12 {
            let j = to.iter().position(|&c| c == from[k])?;
            out[j] = weights[k];
        }
    }
    Some(SurfacePoint {
        tri: into,
        v: out[1],
        w: out[2],
    })
}

/// Point `p` in the parameters of the triangle across local edge `edge`
/// of `p.tri`; `None` on a boundary.
///
/// Laid out as a parallelogram, the two triangles share one affine
/// parametrisation: with a, b the shared corners and c, d the far ones,
/// d = a + b − c, so the point αa + βb + γc of `p.tri` is
/// (α + γ)a + (β + γ)b − γd of the neighbour. A point on the edge (γ = 0)
/// keeps its weights on a and b; one beyond it (γ < 0) lands in the
/// neighbour, or beyond that too where a weight comes out negative.
/// Whether the surface continues the same way there (across a smooth edge,
/// away from special vertices and without a displacement field) is for
/// the caller to judge.
pub fn across_edge(topo: &Topology, p: SurfacePoint, edge: usize) -> Option<SurfacePoint> {
    let e = topo.triangle_edges()[p.tri as usize][edge] as usize;
    let [t0, t1] = topo.edge_triangles()[e];
    let next = if t0 == p.tri { t1 } else { t0 };
    if next == NONE {
        return None;
    }
    let (here, there) = (
        topo.triangles()[p.tri as usize],
        topo.triangles()[next as usize],
    );
    let weights = p.weights();
    let far = weights[(edge + 2) % 3];
    let moved = there.map(|corner| match here.iter().position(|&c| c == corner) {
        Some(k) => weights[k] + far,
        None => -far,
    });
    Some(SurfacePoint {
        tri: next,
        v: moved[1],
        w: moved[2],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// The unit square cut along its diagonal 0–2: triangles (0, 1, 2)
    /// and (0, 2, 3), a parallelogram, so one affine map covers both.
    fn square() -> (Topology, [DVec3; 4]) {
        let topo = Topology::new(4, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        let points =
            [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]].map(|[x, y]| DVec3::new(x, y, 0.0));
        (topo, points)
    }

    /// Where a surface point sits on the flat square, from its own weights.
    fn flat(topo: &Topology, points: &[DVec3; 4], p: SurfacePoint) -> DVec3 {
        let c = topo.triangles()[p.tri as usize];
        let [a, b, d] = [1.0 - p.v - p.w, p.v, p.w];
        a * points[c[0] as usize] + b * points[c[1] as usize] + d * points[c[2] as usize]
    }

    #[test]
    fn corners_carry_all_the_weight_of_their_own_vertex() {
        for k in 0..3 {
            let mut expected = [0.0; 3];
            expected[k] = 1.0;
            assert_eq!(SurfacePoint::corner(7, k).weights(), expected);
        }
    }

    #[test]
    fn a_vertex_is_a_corner_of_a_triangle_holding_it() {
        let (topo, points) = square();
        for v in 0..4 {
            let p = vertex_point(&topo, v).unwrap();
            assert_eq!(flat(&topo, &points, p), points[v as usize]);
        }
        assert_eq!(vertex_in(&topo, 0, 3), None);
        let unused = Topology::new(5, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        assert_eq!(vertex_point(&unused, 4), None);
    }

    #[test]
    fn across_an_edge_the_point_stays_where_it_is() {
        let (topo, points) = square();
        // Edge 2 of triangle 0 runs from corner 2 to corner 0: the diagonal.
        // On it, inside the far triangle, and beyond the far triangle too.
        for (v, w) in [
            (0.0, 0.5),
            (0.0, 0.25),
            (-0.25, 0.5),
            (-0.5, 0.75),
            (-1.0, 1.5),
        ] {
            let p = SurfacePoint { tri: 0, v, w };
            let q = across_edge(&topo, p, 2).unwrap();
            assert_eq!(q.tri, 1);
            let gap = flat(&topo, &points, q) - flat(&topo, &points, p);
            assert!(gap.length() < 1e-15, "({v}, {w}): {gap}");
        }
        // Edge 0 of triangle 0 (corners 0 and 1) is on the boundary.
        let p = SurfacePoint {
            tri: 0,
            v: 0.5,
            w: 0.0,
        };
        assert_eq!(across_edge(&topo, p, 0), None);
    }

    #[test]
    fn reparameterizing_needs_a_shared_corner_or_side() {
        let (topo, points) = square();
        let on_diagonal = SurfacePoint {
            tri: 0,
            v: 0.0,
            w: 0.7,
        };
        let q = reparameterize(&topo, on_diagonal, 1).unwrap();
        assert_eq!(q.tri, 1);
        assert!((flat(&topo, &points, q) - flat(&topo, &points, on_diagonal)).length() < 1e-15);
        let corner = SurfacePoint::corner(0, 0);
        assert_eq!(
            reparameterize(&topo, corner, 1),
            Some(SurfacePoint::corner(1, 0))
        );
        let inside = SurfacePoint {
            tri: 0,
            v: 0.3,
            w: 0.3,
        };
        assert_eq!(reparameterize(&topo, inside, 1), None);
        assert_eq!(reparameterize(&topo, inside, 0), Some(inside));
    }

    #[test]
    fn clamping_repairs_round_off_and_keeps_inside_points() {
        let inside = DVec2::new(0.25, 0.5);
        assert_eq!(clamp_to_triangle(inside), inside);
        let q = clamp_to_triangle(DVec2::new(-1e-13, 0.5));
        assert_eq!(q, DVec2::new(0.0, 0.5));
        let q = clamp_to_triangle(DVec2::new(0.5 + 1e-13, 0.5 + 1e-13));
        assert!(q.x >= 0.0 && q.y >= 0.0 && q.x + q.y <= 1.0, "{q}");
    }
}
