//! The remesher's start: the chart mesher's mesh at the same density
//! (conforming, with the crease chains as edge chains, and cheap), its
//! slivers cut into well-shaped triangles rather than copies of
//! themselves, its vertices given their kinds from its curve edges and
//! the model's corners.

use super::budget::Budget;
use super::connectivity::Connectivity;
use super::remeshing::Remeshing;
use super::vertices::{Kind, Placer, Vertex};
use crate::error::{Error, Result};
use crate::mesh::{Density, Mesher, SurfaceMesh};
use crate::parameters::SurfacePoint;
use crate::surface::Surface;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// The chart mesh at size `largest` (the largest the size field asks
/// for), its long slivers cut by their edges' lengths into well-shaped
/// triangles where `sliver_cuts`, not into copies of themselves. Under
/// curvature sizing (`adapt_to`, its chord tolerance in model
/// units) it starts adapted, unless the chart mesher cannot meet the
/// tolerance (its own measure, in parameters, can stall where the
/// remesher's sizes do not): then from the largest size alone.
pub(super) fn chart_mesh(
    surface: &Surface,
    largest: f64,
    adapt_to: Option<f64>,
    budget: &Budget,
    sliver_cuts: bool,
) -> Result<SurfaceMesh> {
    let plain = Mesher::new(surface)
        .density(Density::Size(largest))
        .max_triangles(budget.start_allowance())
        .swaps(false)
        .isotropic_slivers(sliver_cuts);
    match adapt_to {
        Some(tol) => {
            let diagonal = surface.net().bbox_diagonal();
            plain
                .clone()
                .adapt_curvature(true)
                .tolerance((tol / diagonal).min(0.5))
                .run()
                .or_else(|_| plain.run())
        }
        None => plain.run(),
    }
    .map_err(|e| e.during(budget.start_context()))
}

/// The remesher's start from a chart mesh: vertex kinds from the mesh's
/// curve edges and the model's corners. Its vertices move as `placer`
/// lets them.
pub(super) fn start_from<'a>(placer: Placer<'a>, start: &SurfaceMesh) -> Result<Remeshing<'a>> {
    let surface = placer.surface;
    let model = surface.model();
    let net = surface.net();
    let curve_edges = start.curve_edges(surface)?;
    let mut on_curve: Vec<Option<(u32, f64)>> = vec![None; start.points.len()];
    let mut labels = HashMap::with_capacity(curve_edges.pairs.len());
    for ((pair, &curve), ts) in curve_edges
        .pairs
        .iter()
        .zip(&curve_edges.curves)
        .zip(&curve_edges.params)
    {
        labels.insert((pair[0].min(pair[1]), pair[0].max(pair[1])), curve);
        for k in 0..2 {
            on_curve[pair[k] as usize] = Some((curve, ts[k]));
        }
    }
    let vertices: Vec<Vertex> = start
        .params
        .par_iter()
        .zip(&start.points)
        .zip(&on_curve)
        .map(|((&at, &x), &curve)| {
            if let Some(vertex) = control_vertex(net, at) {
                if model.corners().binary_search(&vertex).is_ok() {
                    return placer.corner(vertex, at);
                }
            }
            Ok(match curve {
                Some((curve, t)) => Vertex {
                    x,
                    at,
                    kind: Kind::Curve { curve, t },
                    normal: DVec3::ZERO,
                },
                None => Vertex {
                    x,
                    at,
                    kind: Kind::Free,
                    normal: surface
                        .normal(at.tri as usize, at.v, at.w)
                        .unwrap_or(DVec3::ZERO),
                },
            })
        })
        .collect::<Result<_>>()?;
    let mesh = Connectivity::new(
        start.points.len(),
        &start.triangles,
        &labels,
        start.faces.clone(),
    )
    .map_err(|e| Error::InvalidArgument(format!("the start mesh is not a manifold: {e:?}")))?;
    Ok(Remeshing::new(placer, mesh, vertices))
}

/// The control vertex a surface point sits at, if it sits at one.
fn control_vertex(net: &crate::ControlNet, at: SurfacePoint) -> Option<u32> {
    let k = at
        .weights()
        .iter()
        .position(|&x| (x - 1.0).abs() <= 1e-12)?;
    Some(net.triangles()[at.tri as usize][k])
}
