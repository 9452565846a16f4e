//! The remesher's output: the live mesh compacted into a [`SurfaceMesh`].

use super::remeshing::Remeshing;
use crate::mesh::SurfaceMesh;
use crate::parameters::SurfacePoint;
use crate::topology::NONE;
use glam::DVec3;

/// The output: live vertices and triangles compacted, feature edges
/// ordered by curve and parameter; and the id in `work` of each output
/// vertex.
pub(super) fn finish(work: &Remeshing, deviation: Option<f64>) -> (SurfaceMesh, Vec<u32>) {
    let (triangles, faces, index) = work.mesh.compact();
    let mut points = Vec::with_capacity(triangles.len() / 2 + 2);
    let mut params = Vec::with_capacity(triangles.len() / 2 + 2);
    let mut kept = Vec::with_capacity(triangles.len() / 2 + 2);
    for (v, &i) in index.iter().enumerate() {
        if i != NONE {
            points.push(work.vertices[v].x);
            params.push(work.vertices[v].at);
            kept.push(v as u32);
        }
    }
    let mut hard: Vec<(u32, f64, [u32; 2])> = Vec::new();
    let mesh = &work.mesh;
    for h in 0..mesh.num_half_edges() {
        if !mesh.is_alive(h) {
            continue;
        }
        let o = mesh.opposite(h);
        let label = mesh.edge_label[h as usize];
        if label == NONE || (o != NONE && o < h) {
            continue;
        }
        let (a, b) = (mesh.origin(h), mesh.dest(h));
        let ta = work.placer.t_on(&work.vertices[a as usize], label, None);
        let tb = work.placer.t_on(&work.vertices[b as usize], label, ta);
        let (ta, tb) = (ta.unwrap_or(0.0), tb.unwrap_or(0.0));
        let pair = [index[a as usize], index[b as usize]];
        if ta <= tb {
            hard.push((label, ta, pair));
        } else {
            hard.push((label, tb, [pair[1], pair[0]]));
        }
    }
    hard.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)));
    let diagonal = work.placer.surface.net().bbox_diagonal();
    let mut mesh = without_curves(points, triangles, params, faces, deviation, diagonal);
    mesh.hard_edges = hard.iter().map(|e| e.2).collect();
    mesh.hard_edge_curves = hard.iter().map(|e| e.0).collect();
    (mesh, kept)
}

/// A remesher's mesh from its arrays, its hard edges not yet listed, and
/// without charts: its triangles span control triangles.
pub(super) fn without_curves(
    points: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    params: Vec<SurfacePoint>,
    faces: Vec<u32>,
    deviation: Option<f64>,
    diagonal: f64,
) -> SurfaceMesh {
    SurfaceMesh {
        points,
        triangles,
        params,
        charts: Vec::new(),
        faces,
        hard_edges: Vec::new(),
        hard_edge_curves: Vec::new(),
        deviation,
        diagonal,
    }
}
