//! Model labels of a mesh on the surface (docs/design.md, "The model"): the face
//! of every triangle, and the curve of every output edge that runs along a
//! hard control edge, with the curve parameters of its ends.
//!
//! Both need only each vertex's surface point (tri, v, w) and, for faces,
//! each triangle's chart, so they apply to any mesh that carries them (the
//! mesher's, the remesher's, or one a caller built from it). A vertex lies
//! on a curve when its point lies on one of the curve's control edges: at
//! one of its end vertices or on its side of the triangle holding the
//! point, within [`PARAMETER_TOLERANCE`] of the barycentric weights. On
//! that control edge, the k-th of its curve, a point at weight s of the
//! edge's second chain vertex has curve parameter t = k + s: the crease
//! rules are the cubic B-spline's on both, so the curve and the surface
//! share their parameterisation along the edge. An output edge lies on a
//! curve when its two ends are neighbours in t among the mesh's vertices on
//! that curve (so it may span several control edges, as the remesher's
//! do).

use crate::error::{Error, Result};
use crate::model::Model;
use crate::net::ControlNet;
use crate::parameters::SurfacePoint;
use crate::surface::{Surface, PARAMETER_TOLERANCE};
use crate::topology::NONE;

/// Output edges along the model's curves.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CurveEdges {
    /// Vertex pairs, each running the way its curve does (increasing t,
    /// but for a closed curve's edge across its start), ordered by curve
    /// and then by t, so that a curve's edges follow one another from its
    /// start to its end.
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
    let weights = p.weights();
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
    check_mesh(surface, params, triangles)?;
    let on_curve = vertices_on_curves(surface, params);
    // Only the edges between two vertices on curves: hashing every edge
    // took a third of a second on 250k triangles with no curve at all.
    let mut marked = vec![false; params.len()];
    for &(_, _, v) in &on_curve {
        marked[v as usize] = true;
    }
    let mut joined = std::collections::HashSet::new();
    for tri in triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if marked[a as usize] && marked[b as usize] {
                joined.insert((a.min(b), a.max(b)));
            }
        }
    }
    // Along each curve, neighbours in t joined by an output edge are its
    // edges (so an output edge may span several control edges); around a
    // closed curve, also its last and first vertex. Vertices at one t
    // (copies of one point, as where a mesh is cut open) are neighbours of
    // every vertex at the t before and after.
    let model = surface.model();
    let mut found: Vec<(u32, f64, [u32; 2], [f64; 2])> = Vec::new();
    for run in on_curve.chunk_by(|x, y| x.0 == y.0) {
        let c = run[0].0;
        let closed = model.curves()[c as usize].is_closed();
        let groups: Vec<&[(u32, f64, u32)]> = run.chunk_by(|x, y| x.1 == y.1).collect();
        let wrap = (closed && groups.len() > 1).then(|| (groups[groups.len() - 1], groups[0]));
        for (g, h) in groups.windows(2).map(|w| (w[0], w[1])).chain(wrap) {
            for (x, y) in g.iter().flat_map(|x| h.iter().map(move |y| (x, y))) {
                let (a, b) = (x.2, y.2);
                if a != b && joined.contains(&(a.min(b), a.max(b))) {
                    found.push((c, x.1, [a, b], [x.1, y.1]));
                }
            }
        }
    }
    found.sort_by(|x, y| {
        (x.0, x.1, x.2)
            .partial_cmp(&(y.0, y.1, y.2))
            .expect("finite")
    });
    found.dedup_by(|x, y| x.0 == y.0 && (x.2 == y.2 || x.2 == [y.2[1], y.2[0]]));
    Ok(CurveEdges {
        pairs: found.iter().map(|f| f.2).collect(),
        curves: found.iter().map(|f| f.0).collect(),
        params: found.iter().map(|f| f.3).collect(),
    })
}

/// Refuses a parameter off the surface and an index past the vertices,
/// naming the vertex or triangle.
fn check_mesh(surface: &Surface, params: &[SurfacePoint], triangles: &[[u32; 3]]) -> Result<()> {
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
    Ok(())
}

/// Every (curve, t, vertex) a vertex lies at, sorted and without repeats:
/// on a hard control edge, or at a chain vertex (a corner on several
/// curves; a closed curve's first vertex at both t = 0 and t = n).
fn vertices_on_curves(surface: &Surface, params: &[SurfacePoint]) -> Vec<(u32, f64, u32)> {
    let net = surface.net();
    let model = surface.model();
    let mut edge_pos = vec![NONE; net.topology().num_edges()];
    for curve in model.curves() {
        for (k, &e) in curve.edges.iter().enumerate() {
            edge_pos[e as usize] = k as u32;
        }
    }
    let mut on_curve: Vec<(u32, f64, u32)> = Vec::new();
    for (i, &p) in params.iter().enumerate() {
        match place_of(net, p) {
            place @ Place::Edge(e, _) => {
                if let Some(c) = model.curve_of_edge(e as usize) {
                    let pos = edge_pos[e as usize] as usize;
                    let from = model.curves()[c as usize].chain[pos];
                    on_curve.push((c, curve_param(net, place, e, pos, from), i as u32));
                }
            }
            Place::Vertex(x) => {
                for c in curves_at_vertex(surface, x) {
                    let chain = &model.curves()[c as usize].chain;
                    for (j, _) in chain.iter().enumerate().filter(|(_, &v)| v == x) {
                        on_curve.push((c, j as f64, i as u32));
                    }
                }
            }
            Place::Inside => {}
        }
    }
    on_curve.sort_by(|x, y| {
        (x.0, x.1, x.2)
            .partial_cmp(&(y.0, y.1, y.2))
            .expect("finite")
    });
    on_curve.dedup();
    on_curve
}

/// The curves of the hard edges at control vertex x, ascending, each once.
fn curves_at_vertex(surface: &Surface, x: u32) -> Vec<u32> {
    let topo = surface.net().topology();
    let model = surface.model();
    let mut curves: Vec<u32> = topo
        .ring(x as usize)
        .iter()
        .filter_map(|&y| topo.find_edge(x, y))
        .filter_map(|e| model.curve_of_edge(e))
        .collect();
    curves.sort_unstable();
    curves.dedup();
    curves
}
