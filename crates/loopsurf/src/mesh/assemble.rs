//! The chart mesher's output from its cuts: every point numbered once
//! (used control vertices, then edge points edge by edge, then interior
//! points triangle by triangle), the cuts' local triangles renumbered, and
//! the model's labels attached.

use super::pattern::Pattern;
use super::{boundary_source, EdgeCut, Source, SurfaceMesh, TriangleCut};
use crate::parameters::SurfacePoint;
use crate::surface::Surface;
use crate::topology::NONE;
use glam::DVec3;
use rayon::prelude::*;

/// Where each cut's points start in the output's numbering.
pub(super) struct Numbering {
    /// Per control vertex: its output vertex, `NONE` where unused.
    pub(super) corner_index: Vec<u32>,
    /// Per control edge: its first inner point.
    pub(super) edge_start: Vec<u32>,
    /// Per control triangle: its first interior point.
    interior_start: Vec<u32>,
}

/// Numbers the vertices and collects the output.
pub(super) fn assemble(
    surface: &Surface,
    corners: &[(SurfacePoint, DVec3)],
    edge_cuts: &[Option<EdgeCut>],
    tri_cuts: &[Option<TriangleCut>],
    diagonal: f64,
    measured: bool,
) -> (SurfaceMesh, Numbering) {
    let (numbering, points, params) = number_points(surface, corners, edge_cuts, tri_cuts);
    let (triangles, charts) = chart_triangles(surface, &numbering, tri_cuts);
    let model = surface.model();
    let faces = charts
        .iter()
        .map(|&c| model.face_of_triangle()[c as usize])
        .collect();
    let (hard_edges, hard_edge_curves) = hard_edge_chains(surface, &numbering, edge_cuts);
    let deviation = measured.then(|| {
        edge_cuts
            .iter()
            .flatten()
            .map(|c| c.deviation)
            .chain(tri_cuts.iter().flatten().map(|c| c.deviation))
            .fold(0.0, f64::max)
    });
    let mesh = SurfaceMesh {
        points,
        triangles,
        params,
        charts,
        faces,
        hard_edges,
        hard_edge_curves,
        deviation,
        diagonal,
    };
    (mesh, numbering)
}

/// Every point once, with its parameters, in the output's order.
fn number_points(
    surface: &Surface,
    corners: &[(SurfacePoint, DVec3)],
    edge_cuts: &[Option<EdgeCut>],
    tri_cuts: &[Option<TriangleCut>],
) -> (Numbering, Vec<DVec3>, Vec<SurfacePoint>) {
    let topo = surface.net().topology();
    let mut corner_index = vec![NONE; corners.len()];
    let mut points = Vec::new();
    let mut params = Vec::new();
    for (v, (p, x)) in corners.iter().enumerate() {
        if p.tri != NONE {
            corner_index[v] = points.len() as u32;
            points.push(*x);
            params.push(*p);
        }
    }
    let mut edge_start = Vec::with_capacity(edge_cuts.len());
    for (e, cut) in edge_cuts.iter().enumerate() {
        edge_start.push(points.len() as u32);
        let Some(cut) = cut else { continue };
        let t = topo.edge_triangles()[e][0];
        points.extend_from_slice(&cut.points);
        params.extend(cut.params.iter().map(|q| SurfacePoint {
            tri: t,
            v: q.x,
            w: q.y,
        }));
    }
    let mut interior_start = Vec::with_capacity(tri_cuts.len());
    for (t, cut) in tri_cuts.iter().enumerate() {
        interior_start.push(points.len() as u32);
        let Some(cut) = cut else { continue };
        points.extend_from_slice(&cut.points);
        params.extend(cut.params.iter().map(|q| SurfacePoint {
            tri: t as u32,
            v: q.x,
            w: q.y,
        }));
    }
    let numbering = Numbering {
        corner_index,
        edge_start,
        interior_start,
    };
    (numbering, points, params)
}

impl Numbering {
    /// The output vertex of point `local` of control triangle t's pattern.
    fn global(&self, surface: &Surface, t: usize, pattern: &Pattern, local: u32) -> u32 {
        let nb = pattern.boundary_len() as u32;
        if local >= nb {
            return self.interior_start[t] + (local - nb);
        }
        match boundary_source(surface, t, pattern, local as usize) {
            Source::Corner(v) => self.corner_index[v as usize],
            Source::Edge(e, i) => self.edge_start[e] + i as u32,
        }
    }
}

/// The cuts' triangles in output vertices, chart by chart, and the chart
/// of each.
fn chart_triangles(
    surface: &Surface,
    numbering: &Numbering,
    tri_cuts: &[Option<TriangleCut>],
) -> (Vec<[u32; 3]>, Vec<u32>) {
    let per_chart: Vec<Vec<[u32; 3]>> = tri_cuts
        .par_iter()
        .enumerate()
        .map(|(t, cut)| {
            let Some(cut) = cut else { return Vec::new() };
            cut.tris
                .iter()
                .map(|tri| tri.map(|l| numbering.global(surface, t, &cut.pattern, l)))
                .collect()
        })
        .collect();
    let charts: Vec<u32> = per_chart
        .iter()
        .enumerate()
        .flat_map(|(t, v)| std::iter::repeat(t as u32).take(v.len()))
        .collect();
    let triangles = per_chart.into_iter().flatten().collect();
    (triangles, charts)
}

/// The output edges along each hard control edge, from its first end to
/// its second, and the curve of each.
fn hard_edge_chains(
    surface: &Surface,
    numbering: &Numbering,
    edge_cuts: &[Option<EdgeCut>],
) -> (Vec<[u32; 2]>, Vec<u32>) {
    let net = surface.net();
    let model = surface.model();
    let (corner_index, edge_start) = (&numbering.corner_index, &numbering.edge_start);
    let mut hard_edges = Vec::new();
    let mut hard_edge_curves = Vec::new();
    for (e, &[a, b]) in net.topology().edges().iter().enumerate() {
        if let (true, Some(cut)) = (net.features().is_hard_edge(e), &edge_cuts[e]) {
            let n = cut.points.len() as u32;
            let chain: Vec<u32> = std::iter::once(corner_index[a as usize])
                .chain((0..n).map(|i| edge_start[e] + i))
                .chain(std::iter::once(corner_index[b as usize]))
                .collect();
            hard_edges.extend(chain.windows(2).map(|w| [w[0], w[1]]));
            let curve = model.curve_of_edge(e).expect("a hard edge is on a curve");
            hard_edge_curves.extend(std::iter::repeat(curve).take(n as usize + 1));
        }
    }
    (hard_edges, hard_edge_curves)
}
