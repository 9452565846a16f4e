//! The surface mesher (Persson, Aftosmis & Haines §4): a triangulation of the limit surface
//! whose every vertex lies exactly on it, uniform or curvature-adaptive,
//! within a chord tolerance, with the control net's hard edges and corners
//! kept as output edges and vertices.
//!
//! Each control triangle is cut in its own parameter domain (see
//! [`pattern`]): its sides into as many segments as the finer of the two
//! triangles sharing them, its interior into a lattice of its own level.
//! (For the remesher's start only, long slivers are cut by their edges'
//! lengths instead: see [`isotropic`].)
//! Points on a control edge are computed once and shared by both sides, so
//! the result is conforming and watertight wherever the net is. Every
//! output triangle lies inside one control triangle (its *chart*), which is
//! what a high-order FE code needs to curve it: its corners' (v, w) in that
//! chart are [`SurfaceMesh::triangle_params`]. Max–min angle swaps then
//! improve angles inside each chart ([`swap`]).
//!
//! Under a tolerance the chord error is measured, not estimated: at the
//! centroid of every output triangle and the midpoint of every output edge,
//! the distance from the flat triangle to the surface point at the same
//! parameters (an upper bound of the distance to the surface there, sharpened
//! by one projection step where it matters). Where it exceeds the
//! tolerance, the control triangle or edge is cut finer and rebuilt.
//!
//! The output carries the model's labels (docs/design.md, "The model"): the
//! face of every triangle and the curve of every hard output edge; see
//! [`labels`] for the same labels of any mesh whose vertices carry their
//! surface points.

mod assemble;
mod by_chunks;
pub(crate) mod density;
pub mod high_order;
mod isotropic;
pub mod labels;
mod pattern;
mod planned;
mod quality;
mod rounds;

pub use crate::geometry::min_angle;
pub use high_order::{onto_surface, CurvedMesh, OntoSurface};
pub use labels::{curve_edges, face_labels, CurveEdges};
pub(crate) use planned::{chord_lengths, planned_chart, planned_edge_cuts, ChartPoint};
pub use quality::{MeshQuality, ShortEdge, TriangleQuality};

use crate::error::{Error, Result};
use crate::parameters::{self, vertex_point, SurfacePoint};
use crate::surface::{Chart, Surface};
use crate::topology::NONE;
use assemble::assemble;
use density::{bend, edge_length, grade, level, level_for_tolerance};
use glam::{DVec2, DVec3};
use isotropic::Slivers;
use pattern::{side_param, Pattern};
use rayon::prelude::*;
use rounds::{Cuts, Progress};

/// The chord tolerance `--adapt curvature` uses when none is given, as a
/// fraction of the bounding-box diagonal.
pub const DEFAULT_ADAPT_TOLERANCE: f64 = 1e-3;

/// The relative chord tolerance a mesher works to: `tolerance` checked
/// (strictly between 0 and 1, a fraction of the bounding-box diagonal),
/// or with curvature adaptation and none given,
/// [`DEFAULT_ADAPT_TOLERANCE`]; `None` for neither. The chart mesher and
/// the remesher ([`crate::remesh`]) take their tolerance through it, so
/// both accept and refuse the same values with the same words.
pub fn chord_tolerance(tolerance: Option<f64>, adapt: bool) -> Result<Option<f64>> {
    match tolerance {
        Some(t) if !(t.is_finite() && t > 0.0 && t < 1.0) => Err(Error::InvalidArgument(format!(
            "tolerance {t}: must lie strictly between 0 and 1 (a fraction of the bounding-box diagonal)"
        ))),
        Some(t) => Ok(Some(t)),
        None if adapt => Ok(Some(DEFAULT_ADAPT_TOLERANCE)),
        None => Ok(None),
    }
}

/// Newton steps of the chord error's projection onto the surface, at most.
const PROJECTION_STEPS: usize = 4;

/// Rounds of measure-and-refine before the tolerance is declared unreachable.
const MAX_ROUNDS: usize = 16;

/// How dense the mesh should be, before the tolerance refines it further.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Density {
    /// Every control edge cut into N segments: N² triangles per control
    /// triangle (Persson, Aftosmis & Haines's uniform mode).
    Uniform(u32),
    /// A target edge length, in model units.
    Size(f64),
    /// Only the tolerance decides (with [`Mesher::adapt_curvature`]) or,
    /// without it, the edge length that meets the tolerance everywhere.
    FromTolerance,
}

/// A surface mesher; configure it, then [`Mesher::run`].
#[derive(Clone)]
pub struct Mesher<'a> {
    surface: &'a Surface,
    density: Density,
    tolerance: Option<f64>,
    adapt: bool,
    swaps: bool,
    max_triangles: usize,
    isotropic_slivers: bool,
}

/// A triangulation of the limit surface.
#[derive(Debug, Clone)]
pub struct SurfaceMesh {
    /// Vertex positions, each exactly the surface at its parameters.
    pub points: Vec<DVec3>,
    /// Counter-clockwise like the control net (outward normals stay outward).
    pub triangles: Vec<[u32; 3]>,
    /// Per vertex: a control triangle and (v, w) where `eval` gives the vertex.
    pub params: Vec<SurfacePoint>,
    /// Per triangle: the control triangle whose parameter domain holds it.
    /// Empty for the remesher's output ([`crate::Remesher`]), whose
    /// triangles span several control triangles.
    pub charts: Vec<u32>,
    /// Per triangle: its model face, the face of its chart
    /// (`model().face_of_triangle()[charts[t]]`).
    pub faces: Vec<u32>,
    /// The output edges along the net's hard edges, as vertex pairs: each
    /// hard control edge's in turn (in edge order), from its first end
    /// vertex to its second.
    pub hard_edges: Vec<[u32; 2]>,
    /// Per hard output edge (parallel to `hard_edges`): its model curve,
    /// the curve of the control edge it lies on.
    pub hard_edge_curves: Vec<u32>,
    /// Largest measured chord error (model units): flat triangle to surface
    /// at the same parameters, over all centroids and edge midpoints. `None`
    /// when no tolerance was set: there is nothing to enforce then, and
    /// measuring costs about as much as meshing (snap the centroids and
    /// midpoints to measure afterwards).
    pub deviation: Option<f64>,
    /// The net's bounding-box diagonal, for relative figures.
    pub diagonal: f64,
}

/// One control edge, cut: its inner points from its first to its second
/// end vertex, and its chords' error.
struct EdgeCut {
    points: Vec<DVec3>,
    params: Vec<DVec2>,
    deviation: f64,
}

/// One control triangle, cut: local triangles over the pattern's points,
/// the interior points, and the chord error inside.
struct TriangleCut {
    pattern: Pattern,
    tris: Vec<[u32; 3]>,
    points: Vec<DVec3>,
    params: Vec<DVec2>,
    deviation: f64,
}

impl<'a> Mesher<'a> {
    /// A mesher of `surface`, with edge swaps. The density comes from the
    /// tolerance or curvature adaptation unless [`Mesher::density`] sets it;
    /// with none of the three, [`Mesher::run`] says so.
    pub fn new(surface: &'a Surface) -> Mesher<'a> {
        Mesher {
            surface,
            density: Density::FromTolerance,
            tolerance: None,
            adapt: false,
            swaps: true,
            max_triangles: 200_000_000,
            isotropic_slivers: false,
        }
    }

    pub fn density(mut self, density: Density) -> Self {
        self.density = density;
        self
    }

    /// The chord tolerance, relative to the bounding-box diagonal.
    pub fn tolerance(mut self, relative: f64) -> Self {
        self.tolerance = Some(relative);
        self
    }

    /// Let the density follow curvature (Persson, Aftosmis & Haines §4: curvature × area),
    /// bounded by the tolerance ([`DEFAULT_ADAPT_TOLERANCE`] if none).
    pub fn adapt_curvature(mut self, adapt: bool) -> Self {
        self.adapt = adapt;
        self
    }

    /// Whether to run the max–min angle swaps (on by default).
    pub fn swaps(mut self, swaps: bool) -> Self {
        self.swaps = swaps;
        self
    }

    /// Refuse to produce more triangles than this (default 200 million).
    pub fn max_triangles(mut self, max: usize) -> Self {
        self.max_triangles = max;
        self
    }

    /// Cut slivers by their edges' lengths into well-shaped triangles
    /// rather than into copies of themselves ([`isotropic`]): for the
    /// remesher's start, whose triangles need not keep their charts' shape.
    pub(crate) fn isotropic_slivers(mut self, on: bool) -> Self {
        self.isotropic_slivers = on;
        self
    }

    /// Checks the options; every error names the offending value.
    fn check(&self) -> Result<Option<f64>> {
        let bad = |m: String| Err(Error::InvalidArgument(m));
        match self.density {
            Density::Uniform(0) => return bad("uniform segment count 0: must be at least 1".into()),
            Density::Uniform(n) if n > 1 << 14 => {
                return bad(format!(
                    "uniform segment count {n}: at most {} is supported",
                    1 << 14
                ))
            }
            Density::Uniform(_) if self.adapt => {
                return bad("uniform meshing and curvature adaptation exclude each other".into())
            }
            Density::Size(h) if !(h.is_finite() && h > 0.0) => {
                return bad(format!("size {h}: must be a positive number"))
            }
            Density::FromTolerance if self.tolerance.is_none() && !self.adapt => {
                return bad("no density given: pass a uniform count, a size or a tolerance".into())
            }
            _ => {}
        }
        chord_tolerance(self.tolerance, self.adapt)
    }

    /// Meshes the surface.
    pub fn run(&self) -> Result<SurfaceMesh> {
        self.run_with_progress(&|_, _| {})
    }

    /// Meshes the surface, calling `progress(done, total)` as control
    /// triangles are cut (from several threads; `total` grows when a round
    /// of refinement is needed).
    ///
    /// Levels from the density (and the tolerance's curvature estimate),
    /// graded; then rounds of cutting what changed and, under a tolerance,
    /// measuring and refining where the chord error is missed, up to
    /// [`MAX_ROUNDS`]; then the cuts assembled into one mesh.
    pub fn run_with_progress(&self, progress: &(dyn Fn(u64, u64) + Sync)) -> Result<SurfaceMesh> {
        let relative = self.check()?;
        let surface = self.surface;
        let topo = surface.net().topology();
        let diagonal = surface.net().bbox_diagonal();
        let tolerance = relative.map(|r| r * diagonal);
        let corners = corner_points(surface)?;
        let lengths = edge_lengths(surface, &corners)?;
        let mut levels = self.start_levels(&lengths, tolerance)?;
        let slivers = if self.isotropic_slivers {
            Slivers::find(topo, lengths)
        } else {
            Slivers::none(levels.len())
        };
        grade(topo, &mut levels);
        let mut cuts = Cuts::new(topo.edges().len(), levels.len());
        let mut cuts_per_edge = cuts.edge_levels(topo, &levels, &slivers);
        let counter = Progress::new(progress);
        for round in 0.. {
            self.check_budget(&levels, &cuts_per_edge)?;
            cuts.cut_edges(surface, &cuts_per_edge, &corners, tolerance)?;
            cuts.cut_triangles(
                self,
                &levels,
                &cuts_per_edge,
                &slivers,
                &corners,
                tolerance,
                &counter,
            )?;
            let Some(tol) = tolerance else { break };
            if !cuts.refine_where_missed(topo, tol, &mut levels, &cuts_per_edge) {
                break;
            }
            if round + 1 == MAX_ROUNDS {
                return Err(Error::InvalidArgument(format!(
                    "tolerance {:e} not reached after {MAX_ROUNDS} rounds of refinement (chord error still {:e} of the diagonal)",
                    relative.unwrap_or(0.0),
                    cuts.worst() / diagonal
                )));
            }
            grade(topo, &mut levels);
            cuts_per_edge = cuts.edge_levels(topo, &levels, &slivers);
        }
        counter.finish();
        let (edge_cuts, tri_cuts) = cuts.into_cuts();
        Ok(assemble(
            surface,
            &corners,
            &edge_cuts,
            &tri_cuts,
            diagonal,
            tolerance.is_some(),
        )
        .0)
    }

    /// Each control triangle's first level: from the density and, under a
    /// tolerance, from its curvature estimate ([`bend`]) — with curvature
    /// adaptation its own, else one edge length for the whole surface.
    fn start_levels(&self, lengths: &[f64], tolerance: Option<f64>) -> Result<Vec<u32>> {
        let surface = self.surface;
        let topo = surface.net().topology();
        let longest = |t: usize| {
            topo.triangle_edges()[t]
                .iter()
                .map(|&e| lengths[e as usize])
                .fold(0.0, f64::max)
        };
        let triangles = surface.net().triangles().len();
        let bends: Vec<f64> = match tolerance {
            Some(_) => (0..triangles)
                .into_par_iter()
                .map(|t| bend(surface, t))
                .collect::<Result<_>>()?,
            None => Vec::new(),
        };
        let mut levels: Vec<u32> = (0..triangles)
            .map(|t| match self.density {
                Density::Uniform(n) => n,
                Density::Size(h) => level(longest(t) / h),
                Density::FromTolerance => 1,
            })
            .collect();
        if let Some(tol) = tolerance {
            if self.adapt {
                for (t, l) in levels.iter_mut().enumerate() {
                    *l = (*l).max(level_for_tolerance(bends[t], tol));
                }
            } else if self.density == Density::FromTolerance {
                // One edge length for the whole surface: the smallest any
                // triangle's curvature asks for.
                let h = (0..triangles)
                    .filter(|&t| bends[t] > 0.0)
                    .map(|t| longest(t) * (tol / bends[t]).sqrt())
                    .fold(f64::INFINITY, f64::min);
                if h.is_finite() {
                    for (t, l) in levels.iter_mut().enumerate() {
                        *l = level(longest(t) / h);
                    }
                }
            }
        }
        Ok(levels)
    }

    /// Refuses meshes over the triangle budget before building them.
    fn check_budget(&self, levels: &[u32], cuts: &[u32]) -> Result<()> {
        check_budget(levels, cuts, self.max_triangles)
    }

    /// Cuts control triangle `t`: evaluates its interior points, triangulates,
    /// swaps, and, given a tolerance, measures the chord error of every
    /// triangle and interior edge.
    fn cut_triangle(
        &self,
        t: usize,
        pattern: Pattern,
        mut points: Vec<DVec3>,
        tolerance: Option<f64>,
    ) -> Result<TriangleCut> {
        let surface = self.surface;
        let nb = pattern.boundary_len();
        let mut chart = surface.chart(t)?;
        let cut = match pattern.isotropic {
            true => isotropic::triangulate(&pattern, &points, |q| chart.point(q.x, q.y))?,
            false => None,
        };
        let (params, cut_tris) = match cut {
            Some(cut) => {
                points.extend(cut.points);
                (cut.params, Some(cut.tris))
            }
            None => {
                let params = pattern.params();
                for p in &params[nb..] {
                    points.push(chart.point(p.x, p.y)?);
                }
                (params, None)
            }
        };
        let mut chord = |ids: &[u32], points: &[DVec3], enough: f64| -> Result<f64> {
            let k = ids.len() as f64;
            let q = ids.iter().map(|&i| params[i as usize]).sum::<DVec2>() / k;
            let p = ids.iter().map(|&i| points[i as usize]).sum::<DVec3>() / k;
            chord_error(&mut chart, q, p, enough, tolerance.unwrap_or(0.0))
        };
        let isotropic = cut_tris.is_some();
        let mut tris = cut_tris.unwrap_or_else(|| pattern.triangles(&points));
        // The lattice repeats the chart's shape: its edges are already
        // max-min (Delaunay) unless the chart is obtuse, in which case the
        // whole chart is swapped; otherwise only the transition strips
        // (their diagonals, not the edges they share with the lattice),
        // which keeps swapping off the bulk of the work.
        let [a, b, c] = pattern.corners().map(|i| points[i as usize]);
        let obtuse =
            (b - a).dot(c - a) < 0.0 || (a - b).dot(c - b) < 0.0 || (a - c).dot(b - c) < 0.0;
        // A sliver's cut is Delaunay in its plane already.
        let swap_from = if isotropic {
            tris.len()
        } else if obtuse {
            0
        } else {
            pattern.strip_start()
        };
        if self.swaps && swap_from < tris.len() {
            let mut failure = None;
            let strips = &mut tris[swap_from..];
            crate::geometry::swap::swap_edges(strips, &params, &points, |a, b| match tolerance {
                None => true,
                Some(tol) => match (
                    chord(&a, &points, tol),
                    chord(&b, &points, tol),
                    chord(&[a[0], a[2]], &points, tol),
                ) {
                    (Ok(x), Ok(y), Ok(z)) => x.max(y).max(z) <= tol,
                    (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => {
                        failure = Some(e);
                        false
                    }
                },
            });
            if let Some(e) = failure {
                return Err(e);
            }
        }
        let is_side = |a: u32, b: u32| {
            (a as usize) < nb && (b as usize) < nb && b as usize == (a as usize + 1) % nb
        };
        let mut deviation: f64 = 0.0;
        for tri in tris.iter().filter(|_| tolerance.is_some()) {
            deviation = deviation.max(chord(tri, &points, deviation)?);
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if a < b && !is_side(a, b) && !is_side(b, a) {
                    deviation = deviation.max(chord(&[a, b], &points, deviation)?);
                }
            }
        }
        Ok(TriangleCut {
            pattern,
            tris,
            points: points.split_off(nb),
            params: params[nb..].to_vec(),
            deviation,
        })
    }
}

/// An upper bound of the distance from chord point `p` to the surface,
/// whose point at the same parameters `q` of triangle `t` is close. First
/// |p − S(q)|; when that exceeds `enough` (a bound already known to hold
/// elsewhere, so only larger values matter), the distance to the surface
/// point one Newton projection step from `q` (clamped into the triangle),
/// if nearer, and while that still exceeds the `tolerance` (so would cost
/// a refinement) up to [`PROJECTION_STEPS`] steps. The plain |p − S(q)|
/// counts the parametrisation's tangential drift, which is no error at all
/// and, next to crease and corner vertices, large: one step leaves part of
/// it, and the count grew twentyfold on CAD-like nets. The projected
/// distance is within round-off of what snap measures.
fn chord_error(chart: &mut Chart, q: DVec2, p: DVec3, enough: f64, tolerance: f64) -> Result<f64> {
    let mut best = chart.point(q.x, q.y)?.distance(p);
    let mut q = q;
    for step in 0..PROJECTION_STEPS {
        if best <= enough || (step > 0 && best <= tolerance) {
            break;
        }
        let e = chart.eval(q.x, q.y)?;
        let Some(step) = e.tangent_step(p - e.x) else {
            break;
        };
        let moved = nearest_in_triangle(q + step);
        let distance = chart.point(moved.x, moved.y)?.distance(p);
        if distance >= best {
            break;
        }
        (best, q) = (distance, moved);
    }
    Ok(best)
}

/// The nearest point of the parameter triangle (v, w ≥ 0, v + w ≤ 1) to `q`:
/// beyond the long side, its projection onto that side (clamped to its
/// ends); elsewhere, each coordinate clamped to [0, 1].
fn nearest_in_triangle(q: DVec2) -> DVec2 {
    if q.x + q.y > 1.0 {
        let t = ((q.x - q.y + 1.0) / 2.0).clamp(0.0, 1.0);
        DVec2::new(t, 1.0 - t)
    } else {
        q.clamp(DVec2::ZERO, DVec2::ONE)
    }
}

/// The level that should bring a measured chord error `error` down to
/// `tolerance`. Smooth patches converge with the square of the level; next
/// to irregular vertices (curvature unbounded above valence 6) and along
/// their edges more slowly, so the rate is taken from the previous
/// measurement of the same element when there is one (`last`: its level
/// and error), which saves rounds of rebuilding.
fn finer(level: u32, error: f64, tolerance: f64, last: &mut Option<(u32, f64)>) -> u32 {
    let rate = match *last {
        Some((n0, e0)) if n0 < level && e0 > error => {
            ((e0 / error).ln() / (level as f64 / n0 as f64).ln()).clamp(0.5, 2.0)
        }
        _ => 2.0,
    };
    *last = Some((level, error));
    // A rate measured between two levels can be pessimistic (the worst
    // point moves): at most four times the level per round, so one bad
    // estimate cannot blow up the count.
    let wanted = level as f64 * (error / tolerance).powf(1.0 / rate) * 1.05;
    (level + 1).max(density::level(wanted.min(4.0 * level as f64)))
}

/// Refuses a chart mesh at `levels` (per control triangle) with `cuts`
/// (segments per control edge) over `max_triangles` (or over what an
/// `i32` counts) before building it.
pub(crate) fn check_budget(levels: &[u32], cuts: &[u32], max_triangles: usize) -> Result<()> {
    let estimate: u128 = levels
        .iter()
        .map(|&n| (n as u128) * (n as u128))
        .sum::<u128>()
        + cuts.iter().map(|&n| n as u128).sum::<u128>();
    if estimate > max_triangles as u128 || estimate > i32::MAX as u128 {
        let limit = max_triangles.min(i32::MAX as usize);
        return Err(Error::OverBudget {
            needed: estimate as f64,
            limit,
            message: format!(
                "the requested density needs about {estimate} triangles, over the limit of {limit}"
            ),
        });
    }
    Ok(())
}

/// The first triangle of edge `e` and the side of it the edge is.
fn owner(topo: &crate::Topology, e: usize) -> (usize, usize) {
    let t = topo.edge_triangles()[e][0] as usize;
    let s = topo.triangle_edges()[t]
        .iter()
        .position(|&x| x as usize == e)
        .expect("edge of its triangle");
    (t, s)
}

/// The length of the limit curve over each control edge, from its ends
/// and its midpoint ([`edge_length`]).
fn edge_lengths(surface: &Surface, corners: &[(SurfacePoint, DVec3)]) -> Result<Vec<f64>> {
    let topo = surface.net().topology();
    let edges = topo.edges();
    let mids: Vec<DVec3> = (0..edges.len())
        .into_par_iter()
        .map(|e| {
            let (t, s) = owner(topo, e);
            let q = side_param(s, 0.5);
            surface.point(t, q.x, q.y)
        })
        .collect::<Result<_>>()?;
    Ok((0..edges.len())
        .map(|e| edge_length(edges[e].map(|v| corners[v as usize].1), mids[e]))
        .collect())
}

/// Per control vertex: its parameters in the first triangle of its fan and
/// its limit point (unused vertices get a placeholder and are never output).
fn corner_points(surface: &Surface) -> Result<Vec<(SurfacePoint, DVec3)>> {
    let net = surface.net();
    let topo = net.topology();
    (0..net.points().len())
        .into_par_iter()
        .map(|v| {
            let Some(p) = vertex_point(topo, v as u32) else {
                return Ok((
                    SurfacePoint {
                        tri: NONE,
                        v: 0.0,
                        w: 0.0,
                    },
                    DVec3::ZERO,
                ));
            };
            Ok((p, surface.point(p.tri as usize, p.v, p.w)?))
        })
        .collect()
}

/// Cuts control edge `e` into `n` segments of equal parameter length and,
/// given a tolerance, measures its chords at their midpoints.
fn cut_edge(
    surface: &Surface,
    e: usize,
    n: u32,
    corners: &[(SurfacePoint, DVec3)],
    tolerance: Option<f64>,
) -> Result<EdgeCut> {
    let topo = surface.net().topology();
    let (t, s) = owner(topo, e);
    let forward = surface.net().triangles()[t][s] == topo.edges()[e][0];
    let at = |k: f64| {
        side_param(
            s,
            if forward {
                k / n as f64
            } else {
                1.0 - k / n as f64
            },
        )
    };
    let params: Vec<DVec2> = (1..n).map(|k| at(k as f64)).collect();
    let mut chart = surface.chart(t)?;
    let points = params
        .iter()
        .map(|q| chart.point(q.x, q.y))
        .collect::<Result<Vec<_>>>()?;
    let ends = topo.edges()[e].map(|v| corners[v as usize].1);
    let node = |k: usize| {
        if k == 0 {
            ends[0]
        } else if k == n as usize {
            ends[1]
        } else {
            points[k - 1]
        }
    };
    let mut deviation: f64 = 0.0;
    let Some(tolerance) = tolerance else {
        return Ok(EdgeCut {
            points,
            params,
            deviation: 0.0,
        });
    };
    for k in 0..n as usize {
        let q = at(k as f64 + 0.5);
        let chord = 0.5 * (node(k) + node(k + 1));
        deviation = deviation.max(chord_error(&mut chart, q, chord, deviation, tolerance)?);
    }
    Ok(EdgeCut {
        points,
        params,
        deviation,
    })
}

/// Where boundary point `k` of triangle `t`'s pattern comes from: a control
/// vertex, or inner point i of a control edge's cut.
enum Source {
    Corner(u32),
    Edge(usize, usize),
}

fn boundary_source(surface: &Surface, t: usize, pattern: &Pattern, mut k: usize) -> Source {
    let net = surface.net();
    let topo = net.topology();
    let mut s = 0;
    while k >= pattern.sides[s] as usize {
        k -= pattern.sides[s] as usize;
        s += 1;
    }
    let corner = net.triangles()[t][s];
    if k == 0 {
        return Source::Corner(corner);
    }
    let e = topo.triangle_edges()[t][s] as usize;
    let n = pattern.sides[s] as usize;
    Source::Edge(
        e,
        if topo.edges()[e][0] == corner {
            k - 1
        } else {
            n - k - 1
        },
    )
}

/// Positions of a pattern's boundary points, shared with the neighbours.
fn boundary_points(
    surface: &Surface,
    t: usize,
    pattern: &Pattern,
    corners: &[(SurfacePoint, DVec3)],
    edge_cuts: &[Option<EdgeCut>],
) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(pattern.boundary_len() + pattern.interior_len());
    for k in 0..pattern.boundary_len() {
        out.push(match boundary_source(surface, t, pattern, k) {
            Source::Corner(v) => corners[v as usize].1,
            Source::Edge(e, i) => edge_cuts[e].as_ref().expect("edges are cut first").points[i],
        });
    }
    out
}

impl SurfaceMesh {
    /// The parameters of triangle `t`'s corners in its chart (control
    /// triangle `charts[t]`): the map a high-order element is curved with.
    /// A vertex on a control edge or at a control vertex is stored in one
    /// neighbouring chart; here it is re-expressed in this one.
    pub fn triangle_params(&self, net: &crate::ControlNet, t: usize) -> [SurfacePoint; 3] {
        let chart = self.charts[t];
        self.triangles[t].map(|i| {
            let p = self.params[i as usize];
            parameters::reparameterize(net.topology(), p, chart)
                .unwrap_or(SurfacePoint { tri: chart, ..p })
        })
    }

    /// The hard output edges oriented and ordered along their curves, with
    /// the curve parameters of their ends ([`labels::curve_edges`]): the
    /// same edges as `hard_edges` with the same curves.
    pub fn curve_edges(&self, surface: &Surface) -> Result<CurveEdges> {
        labels::curve_edges(surface, &self.params, &self.triangles)
    }
}

#[cfg(test)]
mod tests {
    use super::nearest_in_triangle;
    use glam::DVec2;

    /// Every projection lands in the triangle and is no farther than any
    /// point of a fine grid over it; inside points stay put.
    #[test]
    fn nearest_in_triangle_is_the_projection() {
        let grid: Vec<DVec2> = (0..=40)
            .flat_map(|i| (0..=40 - i).map(move |j| DVec2::new(i as f64, j as f64) / 40.0))
            .collect();
        for i in -12..=24 {
            for j in -12..=24 {
                let q = DVec2::new(i as f64, j as f64) / 8.0 + DVec2::new(0.013, -0.007);
                let m = nearest_in_triangle(q);
                assert!(
                    m.x >= 0.0 && m.y >= 0.0 && m.x + m.y <= 1.0 + 1e-15,
                    "{q} -> {m}"
                );
                let best = grid
                    .iter()
                    .map(|g| g.distance(q))
                    .fold(f64::INFINITY, f64::min);
                assert!(m.distance(q) <= best + 1e-12, "{q} -> {m}");
            }
        }
        let inside = DVec2::new(0.25, 0.5);
        assert_eq!(nearest_in_triangle(inside), inside);
    }
}
