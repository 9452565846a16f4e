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
    let (tris, points) = (net.triangles(), net.points());
    let per_face: Vec<[f64; 3]> = tris
        .par_iter()
        .zip(charts)
        .map(|(tri, chart)| {
            let at = |q: glam::DVec2| surface.point(chart.tri as usize, q.x, q.y);
            let mut err = [0.0f64; 3];
            for k in 0..3 {
                let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
                let own = points[a].distance(at(chart.q[k])?);
                let mid = (0.5 * (points[a] + points[b]))
                    .distance(at(0.5 * (chart.q[k] + chart.q[(k + 1) % 3]))?);
                err[k] = err[k].max(own).max(mid);
                err[(k + 1) % 3] = err[(k + 1) % 3].max(mid);
            }
            Ok(err)
        })
        .collect::<Result<_>>()?;
    let mut out = vec![0.0f64; points.len()];
    for (tri, err) in tris.iter().zip(&per_face) {
        for k in 0..3 {
            let v = tri[k] as usize;
            out[v] = out[v].max(err[k]);
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
