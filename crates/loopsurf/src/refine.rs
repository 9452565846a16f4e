//! Uniform Loop refinement: every triangle split into four per level, with
//! the masks of [`crate::rules`], hard edges and corners carried along, and
//! for every refined vertex the control triangle and (v, w) it sits at.
//!
//! Together with the limit masks this is DESIGN.md's exact dyadic
//! reference: the limit position of a vertex of level k *is* the surface at
//! its dyadic parameter (i/2ᵏ, j/2ᵏ).

use crate::error::{Error, Result};
use crate::features::VertexKind;
use crate::net::{ControlNet, NeighbourSums};
use crate::rules;
use crate::topology::NONE;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// A point of the surface named by its control triangle and barycentric
/// parameters (v, w): weights (1 − v − w, v, w) on the triangle's corners.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    pub tri: u32,
    pub v: f64,
    pub w: f64,
}

/// The result of [`refine_uniform`].
#[derive(Debug, Clone)]
pub struct Refinement {
    /// The refined net: positions, triangles, hard edges and corners.
    /// Vertex i of the input keeps index i; triangle t of level l has the
    /// children 4t … 4t+3 on level l + 1.
    pub net: ControlNet,
    /// For every refined vertex, where it sits on the control net; `None`
    /// for vertices no triangle uses.
    pub origins: Vec<Option<SurfacePoint>>,
    /// Number of levels applied.
    pub levels: u32,
}

impl Refinement {
    /// Every refined vertex pushed to the limit surface with its limit mask.
    pub fn limit_points(&self) -> Vec<DVec3> {
        self.net.limit_points()
    }
}

/// The most levels [`refine_uniform`] accepts; each level multiplies the
/// triangle count by four.
pub const MAX_LEVELS: u32 = 12;

/// Refines the net uniformly `levels` times.
///
/// Fails when `levels` exceeds [`MAX_LEVELS`] or the result would not fit
/// 32-bit indices.
pub fn refine_uniform(net: &ControlNet, levels: u32) -> Result<Refinement> {
    if levels > MAX_LEVELS {
        return Err(Error::InvalidArgument(format!(
            "refinement levels {levels}: at most {MAX_LEVELS} are supported"
        )));
    }
    let final_tris = (net.triangles().len() as u128) << (2 * levels);
    if final_tris >= u32::MAX as u128 {
        return Err(Error::InvalidArgument(format!(
            "refining {} triangles {levels} times gives {final_tris} triangles, more than 32-bit indices hold",
            net.triangles().len()
        )));
    }
    let topo = net.topology();
    let mut origins: Vec<Option<SurfacePoint>> = (0..topo.num_vertices())
        .map(|v| {
            let &t = topo.fan(v).first()?;
            let corner = topo.triangles()[t as usize]
                .iter()
                .position(|&c| c as usize == v)?;
            let p = CORNERS[corner];
            Some(SurfacePoint {
                tri: t,
                v: p.x,
                w: p.y,
            })
        })
        .collect();
    let mut params: Vec<[DVec2; 3]> = vec![CORNERS; topo.num_triangles()];
    let mut current = net.clone();
    for level in 0..levels {
        let topo = current.topology();
        // New vertices on edges: their parameter from the edge's first triangle.
        let shift = 2 * level;
        origins.extend(topo.edge_triangles().iter().enumerate().map(|(e, et)| {
            let t = et[0] as usize;
            let i = local_edge(topo.triangle_edges()[t], e);
            let p = 0.5 * (params[t][i] + params[t][(i + 1) % 3]);
            Some(SurfacePoint {
                tri: (t >> shift) as u32,
                v: p.x,
                w: p.y,
            })
        }));
        if level + 1 < levels {
            params = params.iter().flat_map(|p| split_params(*p)).collect();
        }
        current = subdivide(&current);
    }
    Ok(Refinement {
        net: current,
        origins,
        levels,
    })
}

/// (v, w) of a triangle's corners c0, c1, c2.
const CORNERS: [DVec2; 3] = [
    DVec2::new(0.0, 0.0),
    DVec2::new(1.0, 0.0),
    DVec2::new(0.0, 1.0),
];

/// Corner parameters of the four children, in [`crate::Topology::refined`]'s order.
fn split_params([p0, p1, p2]: [DVec2; 3]) -> [[DVec2; 3]; 4] {
    let (m0, m1, m2) = (0.5 * (p0 + p1), 0.5 * (p1 + p2), 0.5 * (p2 + p0));
    [[p0, m0, m2], [m0, p1, m1], [m2, m1, p2], [m1, m2, m0]]
}

fn local_edge(tri_edges: [u32; 3], e: usize) -> usize {
    tri_edges.iter().position(|&x| x as usize == e).unwrap_or(0)
}

/// One level of Loop subdivision.
fn subdivide(net: &ControlNet) -> ControlNet {
    let topo = net.topology();
    let features = net.features();
    let points = net.points();
    let kinds = features.vertex_kinds(topo);
    let sums = NeighbourSums::new(topo, features, points);
    let vertex_points = (0..points.len()).into_par_iter().map(|v| {
        let x = points[v];
        match kinds[v] {
            VertexKind::Smooth | VertexKind::Dart => {
                rules::smooth_vertex(x, sums.all[v], sums.valence[v] as usize)
            }
            VertexKind::Crease => rules::crease_vertex(x, sums.hard[v]),
            VertexKind::Corner => rules::corner_vertex(x),
        }
    });
    let tris = topo.triangles();
    let edge_points = topo.edges().par_iter().enumerate().map(|(e, &[a, b])| {
        let (pa, pb) = (points[a as usize], points[b as usize]);
        let [t0, t1] = topo.edge_triangles()[e];
        if features.is_hard_edge(e) || t1 == NONE {
            return rules::hard_edge(pa, pb);
        }
        let opposite = |t: u32| {
            let i = local_edge(topo.triangle_edges()[t as usize], e);
            points[tris[t as usize][(i + 2) % 3] as usize]
        };
        rules::smooth_edge(pa, pb, opposite(t0), opposite(t1))
    });
    let mut new_points = Vec::with_capacity(points.len() + topo.num_edges());
    new_points.par_extend(vertex_points);
    new_points.par_extend(edge_points);
    ControlNet::from_parts(new_points, topo.refined(), features.refined(topo))
}

impl ControlNet {
    /// Uniform refinement; see [`refine_uniform`].
    pub fn refine_uniform(&self, levels: u32) -> Result<Refinement> {
        refine_uniform(self, levels)
    }
}
