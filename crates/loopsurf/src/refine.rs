//! Uniform Loop refinement: every triangle split into four per level, with
//! the masks of [`crate::rules`], hard edges and corners carried along, and
//! for every refined vertex the control triangle and (v, w) it sits at.
//!
//! Together with the limit masks this is the exact dyadic
//! reference: the limit position of a vertex of level k *is* the surface at
//! its dyadic parameter (i/2ᵏ, j/2ᵏ).

use crate::error::{Error, Result};
use crate::features::Features;
use crate::features::VertexKind;
use crate::net::{ControlNet, NeighbourSums};
use crate::parameters::SurfacePoint;
use crate::parameters::{vertex_point, CORNERS};
use crate::rules;
use crate::topology::{corner_of, Topology, MIN_PER_TASK, NONE};
use glam::DVec3;
use rayon::prelude::*;

/// The result of [`refine_uniform`].
#[derive(Debug, Clone)]
pub struct Refinement {
    net: ControlNet,
    levels: u32,
    /// Where each vertex sits, as integer multiples of 2^-levels: 8 bytes a
    /// vertex instead of 24, which matters at millions of vertices.
    origins: Vec<Dyadic>,
}

/// A control triangle and (v, w) = (i, j) / 2^levels.
#[derive(Debug, Clone, Copy)]
struct Dyadic {
    tri: u32,
    i: u16,
    j: u16,
}

impl Refinement {
    /// The refined net: positions, triangles, hard edges and corners.
    /// Vertex i of the input keeps index i; triangle t of level l has the
    /// children 4t … 4t+3 on level l + 1.
    pub fn net(&self) -> &ControlNet {
        &self.net
    }

    /// The refined net, without the origins.
    pub fn into_net(self) -> ControlNet {
        self.net
    }

    /// Number of levels applied.
    pub fn levels(&self) -> u32 {
        self.levels
    }

    /// Every refined vertex pushed to the limit surface with its limit mask.
    pub fn limit_points(&self) -> Vec<DVec3> {
        self.net.limit_points()
    }

    /// Where refined vertex `vertex` sits on the control net: its control
    /// triangle and dyadic (v, w). `None` for vertices no triangle uses.
    /// Also `None` for an index past the last vertex.
    pub fn origin(&self, vertex: usize) -> Option<SurfacePoint> {
        let d = *self.origins.get(vertex)?;
        let scale = (1u32 << self.levels) as f64;
        (d.tri != NONE).then(|| SurfacePoint {
            tri: d.tri,
            v: d.i as f64 / scale,
            w: d.j as f64 / scale,
        })
    }

    /// [`Refinement::origin`] of every refined vertex, in vertex order.
    pub fn origins(&self) -> impl ExactSizeIterator<Item = Option<SurfacePoint>> + '_ {
        (0..self.origins.len()).map(|v| self.origin(v))
    }
}

/// The most levels [`refine_uniform`] accepts; each level multiplies the
/// triangle count by four, and 2^12 keeps dyadic parameters in 16 bits.
pub const MAX_LEVELS: u32 = 12;

/// The number of vertices after refining `net` `levels` times; fails when
/// `levels` exceeds [`MAX_LEVELS`] or the result would not fit 32-bit
/// indices.
fn refined_vertices(net: &ControlNet, levels: u32) -> Result<u128> {
    if levels > MAX_LEVELS {
        return Err(Error::InvalidArgument(format!(
            "refinement levels {levels}: at most {MAX_LEVELS} are supported"
        )));
    }
    // Edges outnumber triangles and vertices, so they set the limit.
    let (mut tris, mut edges) = (
        net.triangles().len() as u128,
        net.topology().num_edges() as u128,
    );
    // One new vertex per edge of every level but the last.
    let mut vertices = net.points().len() as u128;
    for _ in 0..levels {
        vertices += edges;
        (tris, edges) = (4 * tris, 2 * edges + 3 * tris);
    }
    if edges >= u32::MAX as u128 {
        return Err(Error::InvalidArgument(format!(
            "refining {} triangles {levels} times gives {edges} edges, more than 32-bit indices hold",
            net.triangles().len()
        )));
    }
    Ok(vertices)
}

/// The number of vertices of one refinement of the net (the evaluator's,
/// which refines the points with the connectivity, when it first makes a
/// patch); fails when they would not fit 32-bit indices.
pub(crate) fn once_refined_vertices(net: &ControlNet) -> Result<usize> {
    Ok(refined_vertices(net, 1)? as usize)
}

/// Refines the net uniformly `levels` times.
///
/// Fails when `levels` exceeds [`MAX_LEVELS`] or the result would not fit
/// 32-bit indices.
pub fn refine_uniform(net: &ControlNet, levels: u32) -> Result<Refinement> {
    let vertices = refined_vertices(net, levels)?;
    let topo = net.topology();
    let full = 1u16 << levels;
    let mut origins: Vec<Dyadic> = Vec::with_capacity(vertices as usize);
    origins.extend(
        (0..topo.num_vertices() as u32).map(|v| match vertex_point(topo, v) {
            None => Dyadic {
                tri: NONE,
                i: 0,
                j: 0,
            },
            Some(p) => Dyadic {
                tri: p.tri,
                i: p.v as u16 * full,
                j: p.w as u16 * full,
            },
        }),
    );
    let mut current = net.clone();
    for level in 0..levels {
        let topo = current.topology();
        // New vertices on edges: the midpoint of the edge in its first triangle.
        origins.par_extend(
            (0..topo.num_edges())
                .into_par_iter()
                .with_min_len(MIN_PER_TASK)
                .map(|e| {
                    let t = topo.edge_triangles()[e][0] as usize;
                    let c = topo.triangles()[t];
                    let p = corner_params(t, level, full);
                    let [a, b] = topo.edges()[e].map(|v| p[corner_of(c, v) as usize]);
                    Dyadic {
                        tri: (t >> (2 * level)) as u32,
                        i: (a[0] + b[0]) / 2,
                        j: (a[1] + b[1]) / 2,
                    }
                }),
        );
        current = subdivide(&current);
    }
    Ok(Refinement {
        net: current,
        levels,
        origins,
    })
}

/// The [`CORNERS`] in units of 1/`full`.
fn corners(full: u16) -> [[u16; 2]; 3] {
    CORNERS.map(|c| [c.x as u16 * full, c.y as u16 * full])
}

/// Corner parameters of triangle t of the given level inside its control
/// triangle, read off the base-4 digits of t (child c of a triangle is 4t + c,
/// in [`crate::Topology::refined`]'s order). Exact: all are dyadic.
fn corner_params(t: usize, level: u32, full: u16) -> [[u16; 2]; 3] {
    let mid = |a: [u16; 2], b: [u16; 2]| [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    let mut p = corners(full);
    for l in (0..level).rev() {
        let [p0, p1, p2] = p;
        let (m0, m1, m2) = (mid(p0, p1), mid(p1, p2), mid(p2, p0));
        p = match (t >> (2 * l)) & 3 {
            0 => [p0, m0, m2],
            1 => [m0, p1, m1],
            2 => [m2, m1, p2],
            _ => [m1, m2, m0],
        };
    }
    p
}

/// One level of Loop subdivision.
fn subdivide(net: &ControlNet) -> ControlNet {
    let (topo, features) = (net.topology(), net.features());
    let new_points = subdivide_points(topo, features, net.points());
    ControlNet::from_parts(new_points, topo.refined(), features.refined(topo))
}

/// The positions of one subdivision step: old vertices first, then one new
/// vertex per edge, numbered as [`crate::Topology::refined`] numbers them.
/// Linear in `points`, so the evaluator also runs it on basis vectors to
/// read off local subdivision matrices: the masks live only in [`rules`].
pub(crate) fn subdivide_points(
    topo: &Topology,
    features: &Features,
    points: &[DVec3],
) -> Vec<DVec3> {
    subdivide_points_with(topo, features, points, MIN_PER_TASK)
}

/// [`subdivide_points`] on the calling thread alone (as
/// [`Topology::refined_here`]): for a caller holding a lock that other
/// threads wait on.
pub(crate) fn subdivide_points_here(
    topo: &Topology,
    features: &Features,
    points: &[DVec3],
) -> Vec<DVec3> {
    subdivide_points_with(topo, features, points, usize::MAX)
}

/// [`subdivide_points`], each loop split into tasks of at least `min_len`
/// items.
fn subdivide_points_with(
    topo: &Topology,
    features: &Features,
    points: &[DVec3],
    min_len: usize,
) -> Vec<DVec3> {
    let sums = NeighbourSums::new(topo, features, points);
    let mut new_points = vec![DVec3::ZERO; points.len() + topo.num_edges()];
    let (vertex_points, edge_points) = new_points.split_at_mut(points.len());
    vertex_points
        .par_iter_mut()
        .with_min_len(min_len)
        .enumerate()
        .for_each(|(v, out)| {
            let x = points[v];
            *out = match sums.kind(features, v) {
                VertexKind::Smooth | VertexKind::Dart => {
                    rules::smooth_vertex(x, sums.all[v], sums.valence[v] as usize)
                }
                VertexKind::Crease => rules::crease_vertex(x, sums.hard[v]),
                VertexKind::Corner => rules::corner_vertex(x),
            }
        });
    edge_points
        .par_iter_mut()
        .with_min_len(min_len)
        .enumerate()
        .for_each(|(e, out)| {
            let [a, b] = topo.edges()[e];
            let (pa, pb) = (points[a as usize], points[b as usize]);
            let [t0, t1] = topo.edge_triangles()[e];
            // Boundary edges are always hard, so both triangles exist below.
            *out = if features.is_hard_edge(e) {
                rules::hard_edge(pa, pb)
            } else {
                // The corner that is neither a nor b, without searching.
                let opposite = |t: u32| {
                    let [c0, c1, c2] = topo.triangles()[t as usize];
                    points[(c0 ^ c1 ^ c2 ^ a ^ b) as usize]
                };
                rules::smooth_edge(pa, pb, opposite(t0), opposite(t1))
            };
        });
    new_points
}
