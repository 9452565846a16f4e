//! The twelve control points of a regular patch, across creases and
//! boundaries too.
//!
//! A triangle is regular when each corner is a smooth vertex of valence 6, a
//! crease vertex of valence 6 whose two hard edges are opposite (three
//! triangles on each side), or a boundary vertex with three triangles. An
//! infinitely sharp crease decouples its two sides: every rule on the
//! triangle's side reads only that side and the crease. So the points across
//! a hard edge are replaced by phantoms, the reflections A + B − S of the
//! triangle-side apex S of a hard edge (A, B), which make Loop's smooth rules
//! reproduce the crease rules. The patch is then the box spline of
//! [`super::box_spline`].

use crate::features::{Features, VertexKind};
use crate::topology::Topology;
use glam::DVec3;

/// One control point of a patch: a net vertex, or a phantom a + b − minus.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    Vertex(u32),
    Phantom { a: u32, b: u32, minus: u32 },
}

impl Source {
    fn phantom(a: u32, b: u32, minus: u32) -> Source {
        let (a, b) = if a < b { (a, b) } else { (b, a) };
        Source::Phantom { a, b, minus }
    }

    /// The point's position.
    pub fn position(self, points: &[DVec3]) -> DVec3 {
        match self {
            Source::Vertex(i) => points[i as usize],
            Source::Phantom { a, b, minus } => {
                points[a as usize] + points[b as usize] - points[minus as usize]
            }
        }
    }
}

/// The control points of triangle t in Persson, Aftosmis & Haines's Fig. 6 order, or `None`
/// when t is not regular.
pub fn stencil(
    topo: &Topology,
    features: &Features,
    kinds: &[VertexKind],
    t: usize,
) -> Option<[Source; 12]> {
    let c = topo.triangles()[t];
    let ring = |i: usize| virtual_ring(topo, features, kinds, c[i], c[(i + 1) % 3]);
    let (r0, r1, r2) = (ring(0)?, ring(1)?, ring(2)?);
    // Each outer point is seen from two corners; both must agree.
    let agree = r0[0] == Source::Vertex(c[1])
        && r0[1] == Source::Vertex(c[2])
        && r1[2] == r0[5]
        && r2[2] == r1[5]
        && r2[5] == r0[2];
    agree.then(|| {
        let v = Source::Vertex;
        [
            v(c[0]),
            v(c[1]),
            v(c[2]),
            r1[5],
            r2[3],
            r2[4],
            r0[2],
            r0[3],
            r0[4],
            r0[5],
            r1[3],
            r1[4],
        ]
    })
}

/// The six neighbours of a regular corner `v` counter-clockwise from `from`,
/// with phantoms standing in across its hard edges; `None` if `v` is not a
/// regular corner.
fn virtual_ring(
    topo: &Topology,
    features: &Features,
    kinds: &[VertexKind],
    v: u32,
    from: u32,
) -> Option<[Source; 6]> {
    let ring = topo.ring(v as usize);
    let at = |k: usize| ring[k % ring.len()];
    let virtual_ring: [Source; 6] = match kinds[v as usize] {
        VertexKind::Smooth if ring.len() == 6 => std::array::from_fn(|k| Source::Vertex(ring[k])),
        VertexKind::Crease if !features.is_tagged_vertex(v as usize) => {
            // The side of the crease that holds the wedge (from, next) runs
            // from hard neighbour q to hard neighbour q + 3.
            let hard = features.hard_neighbours(topo, v as usize);
            let pos = |x: u32| ring.iter().position(|&r| r == x);
            let start = pos(from)?;
            let q = if topo.is_boundary_vertex(v as usize) {
                (ring.len() == 4).then_some(0)?
            } else {
                let (p0, p1) = (pos(hard[0])?, pos(hard[1])?);
                if ring.len() != 6 || (p0 + 6 - p1) % 6 != 3 {
                    return None;
                }
                [p0, p1].into_iter().find(|&p| (start + 6 - p) % 6 <= 2)?
            };
            let side: [u32; 4] = std::array::from_fn(|k| at(q + k));
            [
                Source::Vertex(side[0]),
                Source::Vertex(side[1]),
                Source::Vertex(side[2]),
                Source::Vertex(side[3]),
                Source::phantom(v, side[3], side[2]),
                Source::phantom(v, side[0], side[1]),
            ]
        }
        _ => return None,
    };
    let k = virtual_ring
        .iter()
        .position(|&s| s == Source::Vertex(from))?;
    Some(std::array::from_fn(|i| virtual_ring[(k + i) % 6]))
}
