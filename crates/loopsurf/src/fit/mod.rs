//! A fitted surrogate: a new control net whose Loop limit surface passes
//! within a tolerance of every input vertex, with creases on the input's
//! feature lines, for CAD tessellations whose own limit surface shrinks
//! the shape and whose interpolants wiggle (Persson, Aftosmis & Haines
//! §3.3).
//!
//! After Hoppe et al. (piecewise smooth surface reconstruction, 1994),
//! Litke, Levin & Schröder (fitting subdivision surfaces, 2001) and Marinov
//! & Kobbelt (optimization methods for scattered data approximation with
//! subdivision surfaces, 2005):
//!
//! 1. [`apex`]: cone apexes, which no dihedral angle marks, and [`kink`]:
//!    crease vertices where the crease turns sharply, are tagged as
//!    corners. [`start`]: the control net is the input's approximating
//!    surface remeshed by [`crate::Remesher`] at twice the chosen size,
//!    its crease chains and corners tagged, so the new creases lie on the
//!    input's feature lines, a polar grid around each apex ([`polar`]),
//!    and subdivided once.
//! 2. [`data`]: the data are the input's vertices and, where the input's
//!    edges and triangles are longer than half the net's spacing, points
//!    predicted between them from the tangent planes at the vertices
//!    ([`samples`]); those on hard edges and corners are fitted by the
//!    crease curves, the rest by the surface. Each round projects every
//!    datum onto the current surface (parameter correction) and gives it
//!    one equation.
//! 3. [`rows`]: the limit surface is linear in the control points; a
//!    datum's row is the exact limit position of the level-3 refined
//!    vertex nearest its footpoint (subdivision and limit masks composed
//!    as sparse maps), the offset to the footpoint carried on the
//!    right-hand side.
//! 4. [`fairness`]: the umbrella of the displacement from the start net,
//!    second differences along creases, weighted down round by round
//!    ([`LAMBDA`]).
//! 5. [`solve`]: the normal equations by faer's sparse Cholesky, three
//!    right-hand sides.
//! 6. [`report`]: the fitted surface measured by certified closest points.
//!
//! A fit that misses its tolerance at an input vertex is an error
//! ([`crate::Error::FitTolerance`], naming the vertex and the distance):
//! the caller never gets a worse surface without knowing it. The report
//! of a fit that met it is in [`Fit::report`].

mod apex;
mod data;
mod fairness;
mod kink;
mod polar;
mod report;
mod rows;
mod samples;
mod solve;
mod start;

pub use apex::{apexes, APEX_ANGLE_DEGREES};
pub use kink::{kinks, KINK_ANGLE_DEGREES};
pub use report::{Distances, FitReport};

use crate::error::{Error, Result};
use crate::net::ControlNet;
use crate::surface::Surface;
use glam::DVec3;
use std::time::Instant;

/// The default control-edge length, relative to the input's diagonal.
/// The net is remeshed at twice this length and subdivided once
/// ([`start`]). Measured on the CAD shapes of docs/fitting.md: at 0.03 (a
/// remeshed net, not subdivided) the fit of a filleted box and of a
/// cylinder blended into a plate overshoots the seams where fillets meet
/// flat faces (a surface as smooth as Loop's misses a jump in curvature by
/// about the jump times the spacing squared) and the torus misses its
/// data beside irregular control vertices; at 0.015 every shape was closer
/// at its worst but the sphere, for four times the control triangles. At
/// 0.01, remeshed at 0.02 and subdivided, the box and the cyl-plate come
/// within a fifth of the facets' distance at their worst (6.8e-5 and
/// 8.8e-5 of the diagonal, against 1.2e-4 and 1.7e-4 at 0.015 remeshed)
/// and the 110 000-triangle sphere fits in 8 s on one thread; at 0.0075,
/// remeshed at 0.015 and subdivided, the torus and the box are closer
/// still (1.8e-5 and 6.0e-5) but their fits take twice as long again.
pub const DEFAULT_RESOLUTION: f64 = 0.01;
/// The default tolerance on the distance to every input vertex, relative
/// to the diagonal: a fifth of a typical CAD chord tolerance (5e-4).
pub const DEFAULT_TOLERANCE: f64 = 1e-4;
/// The fairness weight of each round, per datum at a spacing of
/// [`LAMBDA_SPACING`] ([`fairness_weight`] scales it for others): strong
/// first, when the footpoints are poor, then weighted down as the fit
/// converges. The last rounds keep 4e-3, which is what keeps the net from
/// wiggling where the data are sparse; a quarter to four times the
/// weights fit the torus, box and cyl-plate within 20% of the same
/// distances.
pub const LAMBDA: [f64; 5] = [4e-1, 4e-2, 4e-3, 4e-3, 4e-3];
/// Data are predicted between the input's vertices at this fraction of
/// the net's spacing. At the spacing itself the surface was free to
/// stray between data, and did where it bends most or changes its
/// bending: beside the torus's irregular control vertices and along the
/// seams where fillets meet flat faces and cylinders. Measured on the CAD
/// shapes of docs/fitting.md, worst distance to the true surface at the
/// spacing → at half of it, on a net remeshed at 0.015 of the diagonal:
/// torus 1.1e-4 → 6.3e-5, filleted box 1.5e-4 → 1.2e-4, cyl-plate 2.0e-4
/// → 1.7e-4, sphere 3.5e-5 → 1.3e-5, cylinder 6.3e-5 → 5.3e-5 of the
/// diagonal; at a third, within 5% of half.
const DATA_SPACING: f64 = 0.5;
/// The spacing (relative to the diagonal) at which [`LAMBDA`] is the
/// weight per datum: the default resolution when the weights were chosen.
const LAMBDA_SPACING: f64 = 0.015;

/// The factor of [`LAMBDA`] on a net of `control` points and spacing
/// `relative` (to the diagonal) fitted to `data` points: per datum (the
/// data term grows with the data, the fairness term with the net), and
/// scaled by (LAMBDA_SPACING / relative)². The fairness sums squared
/// second differences of the displacement, which for one smooth
/// displacement shrink with the spacing h as h⁴ per control point, over a
/// number of points that grows as 1/h²: without the factor a finer net is
/// a less fair one, and wiggles between data it could fit (measured: from
/// a spacing of 0.03 to 0.01 of the diagonal, the sphere's worst distance
/// to the true surface grows from 4e-5 to 2.3e-4 of the diagonal with the
/// weight per datum alone, and to 9.4e-5 with the factor).
fn fairness_weight(data: usize, control: usize, relative: f64) -> f64 {
    data as f64 / control as f64 * (LAMBDA_SPACING / relative).powi(2)
}

/// A fit: configure it, then [`Fitter::run`].
#[derive(Debug, Clone)]
pub struct Fitter<'a> {
    input: &'a ControlNet,
    resolution: Option<f64>,
    tolerance: f64,
    hard_angle: Option<f64>,
}

/// A fitted control net and its report.
#[derive(Debug, Clone)]
pub struct Fit {
    /// The new control net, hard edges and corners tagged.
    pub net: ControlNet,
    pub report: FitReport,
}

impl<'a> Fitter<'a> {
    /// A fit of `input`, its hard edges and corners as tagged.
    pub fn new(input: &'a ControlNet) -> Fitter<'a> {
        Fitter {
            input,
            resolution: None,
            tolerance: DEFAULT_TOLERANCE,
            hard_angle: None,
        }
    }

    /// The control-edge length in model units ([`DEFAULT_RESOLUTION`] of
    /// the diagonal unless set).
    pub fn resolution(mut self, h: f64) -> Self {
        self.resolution = Some(h);
        self
    }

    /// The largest distance allowed from the limit surface to an input
    /// vertex, relative to the diagonal.
    pub fn tolerance(mut self, relative: f64) -> Self {
        self.tolerance = relative;
        self
    }

    /// Also tags the input's edges whose dihedral angle exceeds `degrees`.
    pub fn hard_angle(mut self, degrees: f64) -> Self {
        self.hard_angle = Some(degrees);
        self
    }

    /// Fits, or says where the tolerance is missed.
    pub fn run(&self) -> Result<Fit> {
        let clock = Instant::now();
        let mut input = self.input.clone();
        if let Some(a) = self.hard_angle {
            input.tag_by_angle(a)?;
        }
        let apexes = apex::apexes(&input);
        let kinks = kink::kinks(&input);
        for &v in apexes.iter().chain(&kinks) {
            input.tag_vertex(v)?;
        }
        let diagonal = input.bbox_diagonal();
        let size = self.resolution.unwrap_or(DEFAULT_RESOLUTION * diagonal);
        if !(size.is_finite() && size > 0.0) {
            return Err(Error::InvalidArgument(format!(
                "fit: resolution {size}: a positive length is needed"
            )));
        }
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(Error::InvalidArgument(format!(
                "fit: tolerance {}: a positive fraction of the diagonal is needed",
                self.tolerance
            )));
        }
        let net = start::control_net(&input, size)?;
        let rows = rows::Rows::new(&net)?;
        let fairness = fairness::normal_matrix(&net);
        let mut data = data::Data::new(&input, size * DATA_SPACING);
        let mut x: Vec<DVec3> = net.points().to_vec();
        let weight = fairness_weight(data.points.len(), x.len(), size / diagonal);
        let mut crease = data::Crease::new(&rows);
        for &lambda in &LAMBDA {
            let surface = Surface::new(&net.with_points(x.clone()))?;
            crease.at(&x);
            let equations = data.equations(&surface, &rows, &crease, &x)?;
            let refs: Vec<&rows::Row> = equations.vertices.iter().map(|&r| data.row(r)).collect();
            x = solve::solve(
                &refs,
                &equations.targets,
                &data.weights,
                &fairness,
                lambda * weight,
                net.points(),
                &x,
            )?;
        }
        let net = net.with_points(x);
        let surface = Surface::new(&net)?;
        let vertices = report::distances(&surface, &data.points[..data.vertices.len()], diagonal)?;
        if vertices.max > self.tolerance {
            return Err(Error::FitTolerance {
                vertex: data.vertices[vertices.worst],
                distance: vertices.max,
                tolerance: self.tolerance,
            });
        }
        let vertices = report::Distances {
            worst: data.vertices[vertices.worst],
            ..vertices
        };
        let midpoints = report::distances(&surface, &report::midpoints(&input), diagonal)?;
        let (max_normal_turn, mean_curvature, min_angle) = report::shape(&surface)?;
        let report = FitReport {
            vertices,
            midpoints,
            max_normal_turn,
            mean_curvature,
            min_angle,
            apexes: apexes.len(),
            kinks: kinks.len(),
            control_vertices: net.points().len(),
            control_triangles: net.triangles().len(),
            rounds: LAMBDA.len(),
            seconds: clock.elapsed().as_secs_f64(),
        };
        Ok(Fit { net, report })
    }
}
