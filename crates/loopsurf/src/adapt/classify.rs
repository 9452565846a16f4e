//! The seed's NLFC step (next level flags calculation): which vertices are
//! *flat*, and which become *dead*.
//!
//! Seed 001 §4.2–4.4: the conical angle (CA) of a vertex is the largest
//! angle between the normals of the triangles meeting at it; the vertex is
//! flat when its CA is below the threshold, and dead when all its
//! neighbours are flat. Dead is final: a dead vertex is never classified
//! again, and the vertices later created next to it inherit its deadness
//! (see [`super::split`]).
//!
//! Hard features extend the seed, which has none: the normals are compared
//! only within one smooth sector (triangles joined around the vertex by
//! soft edges), since the angle across a hard edge is the feature itself,
//! not a lack of resolution; at a crease vertex the turning of the crease
//! curve counts as well, so curved creases keep refining and straight ones
//! stop.

use super::FaceChart;
use crate::error::Result;
use crate::features::VertexKind;
use crate::net::ControlNet;
use crate::surface::Surface;
use crate::topology::{Topology, NONE};
use glam::DVec3;
use rayon::prelude::*;

/// The angle between two vectors, radians, accurate at both ends.
fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The conical angle of every vertex but the `skip`ped ones (0 for
/// those), degrees.
pub(crate) fn conical_angles(net: &ControlNet, skip: &[bool]) -> Vec<f64> {
    let (topo, features, points) = (net.topology(), net.features(), net.points());
    let normals: Vec<DVec3> = topo
        .triangles()
        .par_iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| points[i as usize]);
            (b - a).cross(c - a).normalize_or_zero()
        })
        .collect();
    let kinds = features.vertex_kinds(topo);
    (0..topo.num_vertices())
        .into_par_iter()
        .map(|v| {
            if skip[v] {
                return 0.0;
            }
            let fan = topo.fan(v);
            // Sector of each fan triangle: union over soft edges at v.
            let mut sector: Vec<usize> = (0..fan.len()).collect();
            fn root(s: &mut [usize], i: usize) -> usize {
                let mut r = i;
                while s[r] != r {
                    r = s[r];
                }
                s[i] = r;
                r
            }
            for (i, &t) in fan.iter().enumerate() {
                for &e in &topo.triangle_edges()[t as usize] {
                    let [a, b] = topo.edges()[e as usize];
                    if (a as usize != v && b as usize != v) || features.is_hard_edge(e as usize) {
                        continue;
                    }
                    let [t0, t1] = topo.edge_triangles()[e as usize];
                    let other = if t0 == t { t1 } else { t0 };
                    if other == NONE {
                        continue;
                    }
                    if let Some(j) = fan.iter().position(|&f| f == other) {
                        let (ri, rj) = (root(&mut sector, i), root(&mut sector, j));
                        sector[ri] = rj;
                    }
                }
            }
            // The widest pair: the smallest cosine between unit normals.
            let mut cos: f64 = 1.0;
            for i in 0..fan.len() {
                for j in i + 1..fan.len() {
                    if root(&mut sector, i) == root(&mut sector, j) {
                        cos = cos.min(normals[fan[i] as usize].dot(normals[fan[j] as usize]));
                    }
                }
            }
            let mut ca = cos.clamp(-1.0, 1.0).acos();
            if kinds[v] == VertexKind::Crease {
                if let [a, b] = features.hard_neighbours(topo, v)[..] {
                    let p = points[v];
                    ca = ca.max(angle(p - points[a as usize], points[b as usize] - p));
                }
            }
            ca.to_degrees()
        })
        .collect()
}

/// How far every vertex's neighbourhood is from the limit surface, model
/// units: the larger of the vertex's distance to the surface at its own
/// parameters and, for each edge at it, the distance of the edge's
/// midpoint to the surface at the midpoint's parameters (issue 7's cheap
/// proxy for the distance of the refined mesh to the surface).
pub(crate) fn surface_errors(
    net: &ControlNet,
    charts: &[FaceChart],
    surface: &Surface,
) -> Result<Vec<f64>> {
    let (topo, tris, points) = (net.topology(), net.triangles(), net.points());
    // The surface at corner k of triangle t, or at the midpoint of its side k.
    let at = |t: usize, k: usize, mid: bool| {
        let (chart, q) = (charts[t], charts[t].q);
        let p = if mid {
            0.5 * (q[k] + q[(k + 1) % 3])
        } else {
            q[k]
        };
        surface.point(chart.tri as usize, p.x, p.y)
    };
    // Each vertex once, from the first triangle of its fan.
    let mut out: Vec<f64> = (0..points.len())
        .into_par_iter()
        .map(|v| match topo.fan(v).first() {
            None => Ok(0.0),
            Some(&t) => {
                let k = tris[t as usize]
                    .iter()
                    .position(|&c| c as usize == v)
                    .expect("in its fan");
                Ok(points[v].distance(at(t as usize, k, false)?))
            }
        })
        .collect::<Result<_>>()?;
    // Each edge once, from its first triangle.
    let edges: Vec<f64> = (0..topo.num_edges())
        .into_par_iter()
        .map(|e| {
            let t = topo.edge_triangles()[e][0] as usize;
            let k = topo.triangle_edges()[t]
                .iter()
                .position(|&x| x as usize == e)
                .expect("its edge");
            let [a, b] = topo.edges()[e].map(|v| points[v as usize]);
            Ok((0.5 * (a + b)).distance(at(t, k, true)?))
        })
        .collect::<Result<_>>()?;
    for (&[a, b], &err) in topo.edges().iter().zip(&edges) {
        for v in [a, b] {
            out[v as usize] = out[v as usize].max(err);
        }
    }
    Ok(out)
}

/// The dead flags after this level's NLFC: dead stays dead, and a vertex
/// dies when every neighbour is flat and it may (`allowed`).
pub(crate) fn next_dead(
    topo: &Topology,
    dead: &[bool],
    flat: &[bool],
    allowed: &[bool],
) -> Vec<bool> {
    (0..topo.num_vertices())
        .into_par_iter()
        .map(|v| dead[v] || (allowed[v] && topo.ring(v).iter().all(|&u| flat[u as usize])))
        .collect()
}
