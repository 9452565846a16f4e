//! Model labels of a mesh on the surface (DESIGN.md, "The model"): the face
//! of every triangle, and the curve of every output edge that runs along a
//! hard control edge, with the curve parameters of its ends.
//!
//! Both need only each vertex's surface point (tri, v, w) and, for faces,
//! each triangle's chart, so they apply to any mesh that carries them (the
//! mesher's, or one a caller built from it). An output edge lies on a curve
//! when both of its ends lie on the same hard control edge: at one of its
//! end vertices or on its side of the triangle holding the point, within
//! [`PARAMETER_TOLERANCE`] of the barycentric weights. On that control
//! edge, the k-th of its curve, a point at weight s of the edge's second
//! chain vertex has curve parameter t = k + s: the crease rules are the
//! cubic B-spline's on both, so the curve and the surface share their
//! parameterisation along the edge.

use crate::error::{Error, Result};
use crate::model::Model;
use crate::net::ControlNet;
use crate::refine::SurfacePoint;
use crate::surface::{Surface, PARAMETER_TOLERANCE};
use crate::topology::NONE;

/// Output edges along the model's curves.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CurveEdges {
    /// Vertex pairs, each running the way its curve does (increasing t),
    /// ordered by curve and then by t, so that a curve's edges follow one
    /// another from its start to its end.
    pub pairs: Vec<[u32; 2]>,
    /// The curve id of each pair.
    pub curves: Vec<u32>,
    /// The curve parameters t of each pair's two vertices.
    pub params: Vec<[f64; 2]>,
}

/// Where a surface point lies relative to the control net.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Place {
    /// At a control vertex.
    Vertex(u32),
    /// Inside control edge `e`, at weight `s` of its second end vertex
    /// (`topology().edges()[e][1]`).
    Edge(u32, f64),
    /// Inside a control triangle.
    Inside,
}

fn place_of(net: &ControlNet, p: SurfacePoint) -> Place {
    let topo = net.topology();
    let tri = net.triangles()[p.tri as usize];
    let weights = [1.0 - p.v - p.w, p.v, p.w];
    let zero = weights.map(|x| x.abs() <= PARAMETER_TOLERANCE);
    match zero.iter().filter(|&&z| z).count() {
        2 => {
            let k = (0..3).find(|&k| !zero[k]).expect("one weight left");
            Place::Vertex(tri[k])
        }
        1 => {
            // Side s joins corners s and s + 1: the one without corner z.
            let z = (0..3).find(|&k| zero[k]).expect("one zero weight");
            let e = topo.triangle_edges()[p.tri as usize][(z + 1) % 3];
            let second = topo.edges()[e as usize][1];
            let (a, b) = ((z + 1) % 3, (z + 2) % 3);
            let at_second = if tri[a] == second { a } else { b };
            Place::Edge(e, weights[at_second] / (weights[a] + weights[b]))
        }
        _ => Place::Inside,
    }
}

/// The control edge both places lie on, if any.
fn common_edge(net: &ControlNet, a: Place, b: Place) -> Option<u32> {
    let topo = net.topology();
    match (a, b) {
        (Place::Vertex(x), Place::Vertex(y)) => topo.find_edge(x, y).map(|e| e as u32),
        (Place::Vertex(x), Place::Edge(e, _)) | (Place::Edge(e, _), Place::Vertex(x)) => {
            topo.edges()[e as usize].contains(&x).then_some(e)
        }
        (Place::Edge(e, _), Place::Edge(f, _)) => (e == f).then_some(e),
        _ => None,
    }
}

/// The parameter, on curve edge k running from chain vertex `from`, of a
/// place on that control edge.
fn curve_param(net: &ControlNet, place: Place, e: u32, k: usize, from: u32) -> f64 {
    let s = match place {
        Place::Vertex(x) => (x != from) as u8 as f64,
        Place::Edge(_, s) if net.topology().edges()[e as usize][0] == from => s,
        Place::Edge(_, s) => 1.0 - s,
        Place::Inside => unreachable!("only places on the edge"),
    };
    k as f64 + s
}

/// The face of each triangle of a mesh whose triangle t lies in control
/// triangle `charts[t]`.
pub fn face_labels(model: &Model, charts: &[u32]) -> Result<Vec<u32>> {
    let faces = model.face_of_triangle();
    charts
        .iter()
        .enumerate()
        .map(|(t, &c)| {
            faces.get(c as usize).copied().ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "triangle {t}: chart {c} out of range (the net has {} triangles)",
                    faces.len()
                ))
            })
        })
        .collect()
}

/// The output edges of a mesh on `surface` (vertex `i` the surface at
/// `params[i]`) that lie on the model's curves: see [`CurveEdges`] and the
/// module doc. Every parameter and index is checked first; an error names
/// the vertex or triangle.
pub fn curve_edges(
    surface: &Surface,
    params: &[SurfacePoint],
    triangles: &[[u32; 3]],
) -> Result<CurveEdges> {
    let net = surface.net();
    for (i, p) in params.iter().enumerate() {
        surface
            .validate(p.tri as usize, p.v, p.w)
            .map_err(|e| match e {
                Error::InvalidArgument(m) => Error::InvalidArgument(format!("vertex {i}: {m}")),
                other => other,
            })?;
    }
    for (t, tri) in triangles.iter().enumerate() {
        if let Some(&i) = tri.iter().find(|&&i| i as usize >= params.len()) {
            return Err(Error::InvalidArgument(format!(
                "triangle {t} {tri:?} refers to vertex {i}, but there are {} vertices",
                params.len()
            )));
        }
    }
    let model = surface.model();
    let places: Vec<Place> = params.iter().map(|&p| place_of(net, p)).collect();
    let mut edge_pos = vec![NONE; net.topology().num_edges()];
    for curve in model.curves() {
        for (k, &e) in curve.edges.iter().enumerate() {
            edge_pos[e as usize] = k as u32;
        }
    }
    // (curve, t of the first end, pair, params), once per undirected edge.
    let mut found: Vec<(u32, f64, [u32; 2], [f64; 2])> = Vec::new();
    for tri in triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let (pa, pb) = (places[a as usize], places[b as usize]);
            let Some(e) = common_edge(net, pa, pb) else {
                continue;
            };
            let Some(c) = model.curve_of_edge(e as usize) else {
                continue;
            };
            let pos = edge_pos[e as usize] as usize;
            let from = model.curves()[c as usize].chain[pos];
            let (ta, tb) = (
                curve_param(net, pa, e, pos, from),
                curve_param(net, pb, e, pos, from),
            );
            found.push(if ta <= tb {
                (c, ta, [a, b], [ta, tb])
            } else {
                (c, tb, [b, a], [tb, ta])
            });
        }
    }
    found.sort_by(|x, y| {
        (x.0, x.1, x.2)
            .partial_cmp(&(y.0, y.1, y.2))
            .expect("finite")
    });
    found.dedup_by(|x, y| x.2 == y.2);
    Ok(CurveEdges {
        pairs: found.iter().map(|f| f.2).collect(),
        curves: found.iter().map(|f| f.0).collect(),
        params: found.iter().map(|f| f.3).collect(),
    })
}
