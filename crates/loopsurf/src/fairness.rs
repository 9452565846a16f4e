//! How far the interpolating surface (Persson, Aftosmis & Haines §3.3, [`crate::interpolate`])
//! departs from the approximating one: the residual of the solve, how far
//! control points moved, and how much normals turned. It compares two
//! built surfaces, so it sits above [`crate::surface`].

use crate::error::{Error, Result};
use crate::geometry;
use crate::net::ControlNet;
use crate::parameters::vertex_in;
use crate::surface::{Surface, SurfaceMode};

/// The fairness report warns when a control point moves by more than this
/// fraction of the mean length of its edges.
pub const DISPLACEMENT_WARNING: f64 = 1.0;
/// The fairness report warns when the normal at an original point turns by
/// more than this many degrees between the two surfaces.
pub const NORMAL_WARNING_DEGREES: f64 = 15.0;

/// How far the interpolating surface departs from the approximating one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FairnessReport {
    /// max |S∞ x′ − x| over the vertices, relative to the bounding-box diagonal.
    pub residual: f64,
    /// max |x′ − x| / (mean length of the vertex's edges in the original net).
    pub max_displacement: f64,
    /// The vertex where it occurs.
    pub max_displacement_vertex: usize,
    /// Largest angle, in degrees, between the normals of the approximating
    /// surface (at the limit point of a vertex) and of the interpolating one
    /// (at the original point), over every vertex with a tangent plane, one
    /// sector per vertex at creases and corners.
    pub max_normal_change: f64,
    /// The vertex where it occurs.
    pub max_normal_change_vertex: usize,
}

impl FairnessReport {
    /// One line per threshold exceeded ([`DISPLACEMENT_WARNING`],
    /// [`NORMAL_WARNING_DEGREES`]); empty when the solved net looks fair.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.max_displacement > DISPLACEMENT_WARNING {
            out.push(format!(
                "vertex {} moves by {:.2} times its mean edge length (warning above {DISPLACEMENT_WARNING}): the interpolating surface may wiggle or cusp there",
                self.max_displacement_vertex, self.max_displacement
            ));
        }
        if self.max_normal_change > NORMAL_WARNING_DEGREES {
            out.push(format!(
                "the normal at vertex {} turns by {:.1}° (warning above {NORMAL_WARNING_DEGREES}°): the interpolating surface may fold there",
                self.max_normal_change_vertex, self.max_normal_change
            ));
        }
        out
    }
}

/// Compares the approximating surface of `original` with the interpolating
/// surface of `solved` (the output of [`crate::interpolate::solve`] for `original`).
pub fn fairness(original: &ControlNet, solved: &ControlNet) -> Result<FairnessReport> {
    if solved.triangles() != original.triangles() {
        return Err(Error::InvalidArgument(
            "fairness: the solved net must have the original's triangles".into(),
        ));
    }
    let topo = original.topology();
    let (x, x1) = (original.points(), solved.points());
    let limits = solved.limit_points();
    let diagonal = original.bbox_diagonal();
    let residual = x
        .iter()
        .zip(&limits)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0, f64::max);
    let mut report = FairnessReport {
        residual: residual / diagonal,
        max_displacement: 0.0,
        max_displacement_vertex: 0,
        max_normal_change: 0.0,
        max_normal_change_vertex: 0,
    };
    for v in 0..x.len() {
        let ring = topo.ring(v);
        if ring.is_empty() {
            continue; // an unreferenced vertex: fixed, and no edge to compare with
        }
        let mean_edge = ring
            .iter()
            .map(|&u| (x[u as usize] - x[v]).length())
            .sum::<f64>()
            / ring.len() as f64;
        let moved = (x1[v] - x[v]).length() / mean_edge;
        if moved > report.max_displacement {
            report.max_displacement = moved;
            report.max_displacement_vertex = v;
        }
    }
    let before = Surface::from_net(original.clone(), SurfaceMode::Approximating)?;
    let after = Surface::from_net(solved.clone(), SurfaceMode::Solve)?;
    for v in 0..x.len() {
        // At a crease or corner the normal is one sector's: the vertex's
        // lowest-numbered triangle picks it, the same in both surfaces.
        let at = topo.fan(v).iter().min();
        let Some(p) = at.and_then(|&tri| vertex_in(topo, tri, v as u32)) else {
            continue; // an unreferenced vertex
        };
        let (tri, cv, cw) = (p.tri as usize, p.v, p.w);
        let (Ok(a), Ok(b)) = (before.normal(tri, cv, cw), after.normal(tri, cv, cw)) else {
            continue; // no tangent plane (a corner vertex's sector may have none)
        };
        let angle = geometry::angle(a, b).to_degrees();
        if angle > report.max_normal_change {
            report.max_normal_change = angle;
            report.max_normal_change_vertex = v;
        }
    }
    Ok(report)
}
