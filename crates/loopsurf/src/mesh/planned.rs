//! The chart mesh of some control triangles only, at levels planned
//! outside the mesher: each part of a remeshing by parts meshes its own
//! triangles on its own sub-net's surface, at levels planned over the
//! whole net, so two parts cut the edge they share into the same points.

use super::assemble::assemble;
use super::isotropic::Slivers;
use super::rounds::{segments, Cuts, Progress};
use super::{corner_points, Mesher, SurfaceMesh};
use crate::error::Result;
use crate::parameters::SurfacePoint;
use crate::surface::Surface;
use crate::topology::NONE;
use crate::ControlNet;

/// Where a point of a planned chart mesh comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ChartPoint {
    /// A control vertex's limit point.
    Vertex(u32),
    /// Inner point `index` of the `of` inner points of a control edge's
    /// cut, counted from the edge's first end vertex
    /// ([`crate::Topology::edges`]).
    Edge { edge: u32, index: u32, of: u32 },
    /// A point inside a control triangle.
    Inside,
}

/// The chart mesh of the control triangles t of `surface` with `keep[t]`,
/// each cut at `levels[t]` and each side into the more segments its two
/// triangles ask for; no swaps, no tolerance. Slivers (by their sides'
/// chord lengths) are cut into well-shaped triangles where
/// `isotropic_slivers`. Each point's source comes with it.
///
/// Whatever a triangle's cut depends on (its level, its neighbours'
/// levels, its own and its neighbours' sides) is read from the control
/// net and `levels` alone, so a caller that plans the levels over a whole
/// net gets, on any sub-net holding a triangle's neighbours, the points
/// the whole would have on the triangle's sides.
pub(crate) fn planned_chart(
    surface: &Surface,
    levels: &[u32],
    keep: &[bool],
    isotropic_slivers: bool,
) -> Result<(SurfaceMesh, Vec<ChartPoint>)> {
    let net = surface.net();
    let topo = net.topology();
    let mut corners = corner_points(surface)?;
    let mut used = vec![false; corners.len()];
    for (tri, _) in net.triangles().iter().zip(keep).filter(|x| *x.1) {
        for &v in tri {
            used[v as usize] = true;
        }
    }
    for (corner, _) in corners.iter_mut().zip(&used).filter(|x| !*x.1) {
        corner.0 = SurfacePoint {
            tri: NONE,
            v: 0.0,
            w: 0.0,
        };
    }
    let slivers = slivers(net, isotropic_slivers);
    let mesher = Mesher::new(surface).swaps(false);
    let mut cuts = Cuts::only(topo.edges().len(), keep.to_vec());
    let per_edge = cuts.edge_levels(topo, levels, &slivers);
    cuts.cut_edges(surface, &per_edge, &corners, None)?;
    let progress = Progress::new(&|_, _| {});
    cuts.cut_triangles(
        &mesher, levels, &per_edge, &slivers, &corners, None, &progress,
    )?;
    let (edge_cuts, tri_cuts) = cuts.into_cuts();
    let diagonal = net.bbox_diagonal();
    let (mesh, numbering) = assemble(surface, &corners, &edge_cuts, &tri_cuts, diagonal, false);
    let mut sources = vec![ChartPoint::Inside; mesh.points.len()];
    for (v, &i) in numbering.corner_index.iter().enumerate() {
        if i != NONE {
            sources[i as usize] = ChartPoint::Vertex(v as u32);
        }
    }
    for (e, cut) in edge_cuts.iter().enumerate() {
        let Some(cut) = cut else { continue };
        let start = numbering.edge_start[e] as usize;
        let of = cut.points.len() as u32;
        for index in 0..of {
            sources[start + index as usize] = ChartPoint::Edge {
                edge: e as u32,
                index,
                of,
            };
        }
    }
    Ok((mesh, sources))
}

/// Per control edge of `net`: the segments a planned chart mesh at
/// `levels` cuts it into ([`planned_chart`]).
pub(crate) fn planned_edge_cuts(
    net: &ControlNet,
    levels: &[u32],
    isotropic_slivers: bool,
) -> Vec<u32> {
    let topo = net.topology();
    let slivers = slivers(net, isotropic_slivers);
    (0..topo.edges().len())
        .map(|e| segments(topo, levels, &slivers, e))
        .collect()
}

/// The slivers of `net` by their chord lengths, or none.
fn slivers(net: &ControlNet, isotropic: bool) -> Slivers {
    match isotropic {
        true => Slivers::find(net.topology(), chord_lengths(net)),
        false => Slivers::none(net.triangles().len()),
    }
}

/// The straight length of each control edge, what planned levels are
/// read from: every process holding the net has it, surface or not.
pub(crate) fn chord_lengths(net: &ControlNet) -> Vec<f64> {
    let p = |v: u32| net.points()[v as usize];
    net.topology()
        .edges()
        .iter()
        .map(|&[a, b]| p(a).distance(p(b)))
        .collect()
}
