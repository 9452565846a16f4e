//! What a fit reports, measured on the fitted limit surface itself, not on
//! the rows the fit solved with: distances by certified closest points
//! ([`crate::snap::closest_point`]), normals and curvature by the exact
//! evaluator.

use crate::error::Result;
use crate::geometry::min_angle;
use crate::net::ControlNet;
use crate::snap;
use crate::surface::Surface;
use glam::DVec3;
use rayon::prelude::*;

/// Distances of the fitted surface to a set of points, relative to the
/// input's bounding-box diagonal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distances {
    pub max: f64,
    pub mean: f64,
    /// The index (an input vertex, or an input edge) where `max` is met.
    pub worst: usize,
}

/// The measures of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitReport {
    /// Limit surface to every input vertex.
    pub vertices: Distances,
    /// Limit surface to every input edge's midpoint (these are off the
    /// true surface by the input's chord error; for comparison).
    pub midpoints: Distances,
    /// The largest turn of the limit normal across a control edge between
    /// two smooth (or dart) vertices, degrees: between the normals at its
    /// two ends.
    pub max_normal_turn: f64,
    /// The smallest and largest mean curvature at the control triangles'
    /// centroids (where reliable), model units.
    pub mean_curvature: (f64, f64),
    /// The smallest angle of the control triangles, degrees.
    pub min_angle: f64,
    /// Input vertices found to be apexes ([`super::apexes`]) and kept as
    /// corners.
    pub apexes: usize,
    /// Crease vertices found to be kinks ([`super::kinks`]) and kept as
    /// corners.
    pub kinks: usize,
    /// Control vertices and triangles of the fitted net.
    pub control_vertices: usize,
    pub control_triangles: usize,
    /// Rounds of solve and parameter correction run.
    pub rounds: usize,
    /// Wall time, seconds.
    pub seconds: f64,
}

/// Certified distances from `surface` to `points`, relative to `diagonal`.
pub fn distances(surface: &Surface, points: &[DVec3], diagonal: f64) -> Result<Distances> {
    snap::build_index(surface);
    let d: Vec<f64> = points
        .par_iter()
        .map(|&p| snap::closest_point(surface, p).map(|s| s.distance / diagonal))
        .collect::<Result<_>>()?;
    let (worst, max) = d
        .iter()
        .copied()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, 0.0));
    Ok(Distances {
        max,
        mean: d.iter().sum::<f64>() / d.len().max(1) as f64,
        worst,
    })
}

/// The input edges' midpoints.
pub fn midpoints(input: &ControlNet) -> Vec<DVec3> {
    let p = input.points();
    input
        .topology()
        .edges()
        .iter()
        .map(|&[a, b]| 0.5 * (p[a as usize] + p[b as usize]))
        .collect()
}

/// The fairness and quality figures of the fitted surface.
pub fn shape(surface: &Surface) -> Result<(f64, (f64, f64), f64)> {
    let net = surface.net();
    let topo = net.topology();
    let normal_at = |v: u32| -> Option<DVec3> {
        let p = crate::parameters::vertex_point(topo, v)?;
        surface.normal(p.tri as usize, p.v, p.w).ok()
    };
    let normals: Vec<Option<DVec3>> = (0..net.points().len() as u32)
        .into_par_iter()
        .map(normal_at)
        .collect();
    // Crease and corner vertices have one normal per side: only edges
    // between smooth (or dart) vertices are measured.
    let kinds = net.vertex_kinds();
    let smooth = |v: u32| {
        matches!(
            kinds[v as usize],
            crate::features::VertexKind::Smooth | crate::features::VertexKind::Dart
        )
    };
    let turn = topo
        .edges()
        .iter()
        .enumerate()
        .filter(|&(e, &[a, b])| !net.features().is_hard_edge(e) && smooth(a) && smooth(b))
        .filter_map(|(_, &[a, b])| Some((normals[a as usize]?, normals[b as usize]?)))
        .map(|(a, b)| a.dot(b).clamp(-1.0, 1.0).acos().to_degrees())
        .fold(0.0, f64::max);
    let (lo, hi) = (0..net.triangles().len())
        .into_par_iter()
        .filter_map(|t| surface.curvature(t, 1.0 / 3.0, 1.0 / 3.0).ok())
        .filter(|k| k.reliable)
        .map(|k| (k.mean, k.mean))
        .reduce(
            || (f64::INFINITY, f64::NEG_INFINITY),
            |a, b| (a.0.min(b.0), a.1.max(b.1)),
        );
    Ok((turn, (lo, hi), min_angle(net.points(), net.triangles())))
}
