//! The quality remesher: isotropic (or curvature-adaptive) triangles on the
//! exact limit surface, whatever the shapes of the control triangles.
//!
//! The chart mesher ([`crate::mesh`]) cuts each control triangle in its own
//! parameter domain, so its triangles copy the control net's shapes. Here
//! its output is only the start: a conforming mesh with the crease chains
//! as edge chains and every vertex a surface point. Then, for a few rounds,
//! the passes — [`split`] long edges, [`collapse`] short ones, [`flip`]
//! towards valence 6, [`relax`] tangentially — bring every edge within
//! [4/5, 4/3] of its target length with near-equilateral triangles, and a
//! last max–min angle flip and relaxation polish the angles, the last
//! relaxations keeping only the moves that close no vertex's smallest
//! angle. Twice early on the free vertices are shaken, deterministically: a
//! chart lattice of right triangles is otherwise a fixed point of all four
//! passes.
//!
//! After each round's collapses the mesh is [`renumber`]ed along a
//! Z-order curve through its vertices, so that the passes' walks stay in
//! cache. Caps facing a curve are removed in the polish ([`caps`]).
//!
//! Every vertex carries its parameters (tri, v, w) and is exactly the
//! surface there ([`vertices`]); corners never move, crease and boundary
//! vertices move along their exact curve, and the chains of output edges
//! along a curve are kept (split along the curve, collapsed only along it,
//! never flipped), so every triangle keeps its model face.
//!
//! In parts ([`Remesher::parts`], [`parts`]) each part of a METIS
//! partition of the control net is remeshed alone on its own sub-net's
//! surface, its interface vertices pinned, then the band around the
//! interfaces once more over a second partition that avoids them.
//!
//! The size is one length, or from the exact principal curvatures under a
//! chord tolerance, capped and graded ([`sizing`]). With a tolerance the
//! chord error is measured afterwards at every centroid and edge midpoint
//! (the distance to the surface by local projection, which is at least the
//! true distance, so a bound, confirmed by certified snap where it exceeds
//! the tolerance); where it is exceeded the sizes there shrink and the
//! rounds run again, up to [`TOLERANCE_ROUNDS`] times ([`tolerance`]).
//! The mesh then reports the largest chord error measured ([`SurfaceMesh::deviation`]),
//! which a caller compares with the tolerance: a few edges can be stuck
//! longer than their size (a split would fold a triangle where the
//! surface turns sharply within one edge, as at a cusp of a boundary
//! curve), and a mesh with the tolerance missed there is worth more than
//! none.

mod budget;
mod caps;
mod collapse;
mod connectivity;
mod finish;
mod flip;
mod parts;
pub use parts::{outcomes_from_bytes, outcomes_to_bytes, PartsJob, TaskOutcome};
mod relax;
mod remeshing;
mod renumber;
mod shake;
mod sizing;
mod split;
mod start;
mod tolerance;
mod untangle;
mod validity;
mod vertices;

use crate::error::{Error, Result};
use crate::mesh::{chord_tolerance, SurfaceMesh};
use crate::surface::Surface;
use budget::Budget;
use remeshing::Remeshing;
use sizing::Sizing;
use tolerance::{chord_errors, Shrinking};

/// The default size cap of curvature adaptation without `size`, as a
/// fraction of the bounding-box diagonal.
pub const DEFAULT_ADAPT_CAP: f64 = 0.05;

/// The default gradation: neighbouring sizes differ by at most this factor
/// per edge (MMG's default hgrad).
pub const DEFAULT_GRADATION: f64 = 1.3;

/// The default triangle budget ([`Remesher::max_triangles`]): about 8 GB
/// at the 0.4 KB per output triangle the remesher holds at its peak on a
/// small net, whole (pig at 0.2%: 883k triangles, 355 MB). In parts on a
/// large net it holds more (bunny00 refined twice in 8 parts: 1.2 KB per
/// triangle in one process), which the budget does not count. A tolerance on a surface
/// that folds (mpi.off: curvatures of 68 000 per unit) can ask for sizes
/// no memory holds, and the user should hear so, not meet the
/// out-of-memory killer.
pub const DEFAULT_MAX_TRIANGLES: usize = 20_000_000;

/// What the passes aim at for `--size H`, in units of H. Edges come out
/// shorter than their target (relaxation pulls each vertex to the centroid
/// of its triangles, and a collapse that would leave an edge too long is
/// refused): aimed at H, their median was 0.91–0.92 H and only 86–90% lay
/// within the target window [0.8 H, 4/3 H] (Viking 1%, fandisk and pig 0.5%).
/// Aimed at 1.07 H, the median is 0.98–0.99 H and 96–97% lie within it,
/// with the angles as good (mean-min 52.1°, 51.5°, 51.6°).
const UNIFORM_AIM: f64 = 1.07;

/// Sizes that follow curvature go no lower than this fraction of their
/// cap (the size, or the default cap).
const SMALLEST_ADAPTED: f64 = 1e-3;

/// Rounds of split, collapse, flip and relax.
const ROUNDS: usize = 5;

/// How far [`Remeshing::shake`] moves free vertices (a fraction of their
/// size), and in which rounds (after the first has brought the sizes
/// about right).
const SHAKE: f64 = 0.4;
const SHAKE_ROUNDS: [usize; 2] = [1, 2];

/// Rounds of max–min angle flips and relaxation after them.
const POLISH: usize = 2;

/// Last rounds of relaxation that keep only the moves leaving a vertex's
/// smallest angle no smaller. Plain relaxation moves a vertex to the
/// centroid of its triangles, which evens the sizes but need not open its
/// worst angle. Guarded, two rounds lift the mean smallest angle by 0.1°
/// and the smallest by up to 4° (fandisk adapted: 49.93° → 50.03°, the
/// 50° goal met; Viking adapted: min 23.8° → 27.9°); each further
/// round adds about 0.02°, and max–min flips after each 0.01° (they find
/// a handful of edges). Guarding the polish rounds instead gives 49.85°.
const GUARDED: usize = 2;

/// Rounds of re-sizing where the measured chord error exceeds the tolerance.
const TOLERANCE_ROUNDS: usize = 6;

/// [`Remesher::suggested_parts`] gives one part per this many triangles
/// the sizes ask for.
pub const TRIANGLES_PER_PART: f64 = 30_000.0;

/// The most parts [`Remesher::suggested_parts`] gives.
pub const MAX_SUGGESTED_PARTS: usize = 64;

/// [`Remesher::suggested_parts`] gives each part at least this many
/// control triangles: a part's sub-net holds its neighbours' triangles
/// too, which a smaller part would be mostly made of.
pub const MIN_PART_TRIANGLES: usize = 16;

/// A quality remesher of `surface`; configure it, then [`Remesher::run`].
#[derive(Clone)]
pub struct Remesher<'a> {
    surface: &'a Surface,
    size: Option<f64>,
    tolerance: Option<f64>,
    adapt: bool,
    gradation: f64,
    max_triangles: usize,
    parts: usize,
    /// Whether the start cuts slivers by their edges' lengths
    /// ([`start::chart_mesh`]).
    sliver_cuts: bool,
}

impl<'a> Remesher<'a> {
    /// A remesher of `surface`; give it a size, or curvature adaptation.
    pub fn new(surface: &'a Surface) -> Remesher<'a> {
        Remesher {
            surface,
            size: None,
            tolerance: None,
            adapt: false,
            gradation: DEFAULT_GRADATION,
            max_triangles: DEFAULT_MAX_TRIANGLES,
            parts: 1,
            sliver_cuts: true,
        }
    }

    /// Starts from the chart mesh whose slivers are cut into copies of
    /// themselves, not by their edges' lengths: for the fit, whose worst
    /// distances hang on where the remeshed net's irregular vertices
    /// fall. From the sliver cuts, the fitted cone's
    /// worst distance to the true cone grew from 6.0e-4 to 1.1e-3 of the
    /// diagonal and the filleted box's from 1.5e-4 to 2.2e-4.
    pub(crate) fn lattice_start(mut self) -> Self {
        self.sliver_cuts = false;
        self
    }

    /// The target edge length in model units (the cap, when adapting).
    pub fn size(mut self, h: f64) -> Self {
        self.size = Some(h);
        self
    }

    /// The chord tolerance, relative to the bounding-box diagonal. Sizes
    /// then follow the exact curvature (as with
    /// [`Remesher::adapt_curvature`]), capped by the size if one is given.
    pub fn tolerance(mut self, relative: f64) -> Self {
        self.tolerance = Some(relative);
        self
    }

    /// Sizes from the exact principal curvatures under the tolerance
    /// ([`crate::mesh::DEFAULT_ADAPT_TOLERANCE`] if none).
    pub fn adapt_curvature(mut self, adapt: bool) -> Self {
        self.adapt = adapt;
        self
    }

    /// The largest ratio of neighbouring sizes per edge (> 1).
    pub fn gradation(mut self, g: f64) -> Self {
        self.gradation = g;
        self
    }

    /// The most triangles the mesh may have ([`DEFAULT_MAX_TRIANGLES`]
    /// unless set): a density asking for more fails with an error that
    /// says how many it asks for, before the memory is spent.
    pub fn max_triangles(mut self, max: usize) -> Self {
        self.max_triangles = max;
        self
    }

    /// Mesh the surface in `k` parts of its control net, each on its own
    /// ([`parts`]): the parts run in parallel, and the mesh is the same
    /// bits for any thread count. 1 (the default) meshes it whole.
    pub fn parts(mut self, k: usize) -> Self {
        self.parts = k;
        self
    }

    /// The number of parts worth remeshing in ([`Remesher::parts`]): one
    /// per [`TRIANGLES_PER_PART`] triangles the sizes ask for over the
    /// whole surface (before grading and tolerance rounds), at most
    /// [`MAX_SUGGESTED_PARTS`] and with at least [`MIN_PART_TRIANGLES`]
    /// control triangles each, rounded down to a power of two; 1, whole,
    /// below two parts' worth. It depends on the surface and the density
    /// alone, never on the threads, so the mesh it leads to is the same on
    /// any machine.
    ///
    /// Why a power of two: the parts of a stage run side by side, so K
    /// parts on T threads take as long as the most parts any thread runs.
    /// Most machines have a power of two of cores, or a multiple of one:
    /// fandisk's 3 parts ran only 1.46–1.48 times as fast on two threads
    /// as on one.
    ///
    /// Why so many triangles a part: each part costs a sub-net, its sizes
    /// and its share of the band remeshed twice, which small parts do
    /// not earn back. On one thread, bunny00 at 0.3% of its diagonal
    /// (249 000 triangles) took 1.07 to 1.13 times the whole run's time in
    /// 2 to 16 parts and 1.30 times in 32 (one run each; 1.2 times in 8,
    /// medians of 5, in another sitting); the Viking at 1% (21 000), 1.64
    /// times in 8.
    pub fn suggested_parts(&self) -> Result<usize> {
        let (sizing, _, _) = self.sizing_on(self.surface)?;
        let expected = budget::expected_over_net(self.surface.net(), &sizing);
        let most =
            MAX_SUGGESTED_PARTS.min(self.surface.net().triangles().len() / MIN_PART_TRIANGLES);
        let parts = (expected / TRIANGLES_PER_PART).floor();
        Ok(if parts < 2.0 {
            1
        } else {
            let k = (parts as usize).min(most).max(1);
            1 << k.ilog2()
        })
    }

    /// The size field over `surface` (the whole surface, or one part's),
    /// the tolerance in model units and the budget, checked (a uniform
    /// size against the budget too, before the start mesh is built). The
    /// tolerance and the default cap are relative to the whole surface's
    /// diagonal.
    fn sizing_on(&self, surface: &Surface) -> Result<(Sizing, Option<f64>, Budget)> {
        let settled = self.settled()?;
        Ok((
            self.sizing_with(surface, &settled),
            settled.tolerance,
            settled.budget,
        ))
    }

    /// The size field over `surface` at `settled` settings: for the many
    /// surfaces of a run in parts, which would otherwise measure the whole
    /// net (its diagonal and area) again for each part, band piece and
    /// blob (on bunny00 refined twice in 8 parts on 2 ranks, the touch-up's
    /// tasks took 8.9 s before, 1.0 s after).
    fn sizing_with(&self, surface: &Surface, settled: &Settled) -> Sizing {
        match (self.size, settled.tolerance) {
            (Some(h), None) => Sizing::Uniform(h * UNIFORM_AIM),
            // A size with a tolerance sizes by curvature under the size.
            // Shrinking a uniform size only where probes missed did not
            // converge on featured models (fandisk, the Viking): its first
            // rounds at the full size left edges spanning features, whose
            // splits the alignment check refused.
            (_, Some(tol)) => {
                let cap = settled.cap;
                Sizing::curvature(surface, tol, cap, cap * SMALLEST_ADAPTED, self.gradation)
            }
            (None, None) => unreachable!("settings asks for a density"),
        }
    }

    /// The smallest edge length these settings ask for anywhere: the
    /// size itself when it is uniform; where sizes follow curvature, the
    /// floor they never go below ([`SMALLEST_ADAPTED`] × the size, or ×
    /// the default cap). An output edge far below it is a degenerate one
    /// unless a feature forces it ([`crate::SurfaceMesh::short_edges`]).
    pub fn smallest_size(&self) -> Result<f64> {
        let (tolerance, _) = self.settings()?;
        Ok(match (self.size, tolerance) {
            (Some(h), None) => h,
            _ => self.adapt_cap() * SMALLEST_ADAPTED,
        })
    }

    /// The largest size where sizes follow curvature: the size, or
    /// [`DEFAULT_ADAPT_CAP`] of the diagonal.
    fn adapt_cap(&self) -> f64 {
        self.size
            .unwrap_or(DEFAULT_ADAPT_CAP * self.surface.net().bbox_diagonal())
    }

    /// [`Remesher::settings`], and the largest size where sizes follow
    /// curvature ([`Remesher::adapt_cap`]).
    fn settled(&self) -> Result<Settled> {
        let (tolerance, budget) = self.settings()?;
        Ok(Settled {
            tolerance,
            budget,
            cap: self.adapt_cap(),
        })
    }

    /// The settings checked: the chord tolerance in model units (relative
    /// to the whole surface's diagonal; none means a uniform size) and the
    /// budget, a uniform size checked against it.
    fn settings(&self) -> Result<(Option<f64>, Budget)> {
        let bad = |m: String| Err(Error::InvalidArgument(m));
        let diagonal = self.surface.net().bbox_diagonal();
        if let Some(h) = self.size {
            if !(h.is_finite() && h > 0.0) {
                return bad(format!("size {h}: must be a positive number"));
            }
        }
        if !(self.gradation.is_finite() && self.gradation > 1.0) {
            return bad(format!(
                "gradation {}: must be a number greater than 1",
                self.gradation
            ));
        }
        let tolerance = chord_tolerance(self.tolerance, self.adapt)?.map(|t| t * diagonal);
        if let (None, None) = (self.size, tolerance) {
            return bad(
                "no density given: pass a size, a tolerance or curvature adaptation".into(),
            );
        }
        let budget = Budget::new(self.max_triangles)?;
        if let (Some(h), None) = (self.size, tolerance) {
            budget.check_uniform(self.surface.net().area(), h * UNIFORM_AIM)?;
        }
        Ok((tolerance, budget))
    }

    /// Remeshes the surface: from the chart mesh ([`start`]), rounds of
    /// the passes and a polish; then, under a tolerance, the chord error
    /// measured, and where it is missed the sizes shrunk and the rounds
    /// and polish run again ([`tolerance`]).
    pub fn run(&self) -> Result<SurfaceMesh> {
        match self.parts {
            0 => Err(Error::InvalidArgument(
                "0 parts: remesh in at least 1".into(),
            )),
            1 => {
                let (sizing, tolerance, budget) = self.sizing_on(self.surface)?;
                let largest = sizing.largest(|_| true);
                let chart = start::chart_mesh(
                    self.surface,
                    largest,
                    sizing.adapts_to(),
                    &budget,
                    self.sliver_cuts,
                )?;
                let placer = vertices::Placer::new(self.surface);
                let mut work = start::start_from(placer, &chart)?;
                let (deviation, _) = remesh(&mut work, &sizing, tolerance, &budget, None, true)?;
                Ok(finish::finish(&work, deviation).0)
            }
            k => parts::run(self, k),
        }
    }

    /// Remeshing in [`Remesher::parts`] parts as a job of stages whose
    /// tasks may run anywhere, for an MPI program to share out among its
    /// ranks ([`PartsJob`]); [`Remesher::run`] runs them all on threads.
    /// In one part, the job remeshes the whole surface as one part: it
    /// need not give the mesh [`Remesher::run`] gives in one part, which
    /// remeshes the whole surface directly.
    pub fn parts_job(&self) -> Result<PartsJob<'a>> {
        PartsJob::new(self.clone(), self.parts)
    }
}

/// A remesher's settings in model units, measured on the whole net once.
#[derive(Debug, Clone, Copy)]
struct Settled {
    /// The chord tolerance; none for a uniform size.
    tolerance: Option<f64>,
    budget: Budget,
    /// The largest size where sizes follow curvature.
    cap: f64,
}

/// Remeshes `work`: rounds of the passes (the first shaken if `shake`)
/// and a polish; then, under a tolerance, the chord error measured, and
/// where it is missed the sizes shrunk and the rounds and polish run
/// again. The sizes start shrunk by `shrunk` per control triangle, if
/// given. Returns the largest chord error measured (under a tolerance)
/// and the shrink factors at the end.
fn remesh(
    work: &mut Remeshing,
    sizing: &Sizing,
    tolerance: Option<f64>,
    budget: &Budget,
    shrunk: Option<Vec<f64>>,
    shake: bool,
) -> Result<(Option<f64>, Vec<f64>)> {
    let mut shrinking = match shrunk {
        Some(factors) => Shrinking::from_factors(factors),
        None => Shrinking::new(work.placer.surface.net().triangles().len()),
    };
    let mut deviation = None;
    for round in 0..=TOLERANCE_ROUNDS {
        remesh_rounds(
            work,
            sizing,
            shrinking.factors(),
            budget,
            shake && round == 0,
        )?;
        polish(work);
        let Some(tol) = tolerance else { break };
        let errors = chord_errors(work, tol);
        let worst = errors.iter().map(|e| e.1).fold(0.0, f64::max);
        deviation = Some(worst);
        if worst <= tol || round == TOLERANCE_ROUNDS {
            break;
        }
        shrinking.shrink_where_missed(work, &errors, tol);
    }
    let untangled = work.untangle(tolerance);
    let untangled = untangled.max(work.clear_slivers(tolerance));
    let deviation = deviation.map(|d| d.max(untangled));
    Ok((deviation, shrinking.factors().to_vec()))
}

/// [`ROUNDS`] rounds of the passes at the sizes `sizing` gives, shrunk by
/// `shrink` per control triangle: split, collapse, renumber, valence
/// flips, relaxation; shaken first in [`SHAKE_ROUNDS`] when `shake`. Each
/// round's sizes are checked against the budget before its splits, and
/// the splits' count after them.
fn remesh_rounds(
    work: &mut Remeshing,
    sizing: &Sizing,
    shrink: &[f64],
    budget: &Budget,
    shake: bool,
) -> Result<()> {
    let surface = work.placer.surface;
    for r in 0..ROUNDS {
        if shake && SHAKE_ROUNDS.contains(&r) {
            work.shake(SHAKE);
        }
        work.size = sizing.sizes(
            surface,
            &work.mesh,
            &work.vertices,
            shrink,
            &work.size_bound,
        );
        budget.check(work.expected_triangles())?;
        let limit = budget.split_limit(work.triangle_slots());
        work.split_long(limit);
        budget.check_splits(work.triangle_slots(), limit, || work.expected_triangles())?;
        work.collapse_short();
        work.renumber();
        work.equalize_valences();
        work.relax();
    }
    Ok(())
}

/// The polish: [`POLISH`] rounds of cap removal, max–min angle flips and
/// relaxation, a last max–min flip, and [`GUARDED`] rounds of guarded
/// relaxation.
fn polish(work: &mut Remeshing) {
    for _ in 0..POLISH {
        work.remove_caps();
        work.flip_for_angles();
        work.relax();
    }
    work.flip_for_angles();
    for _ in 0..GUARDED {
        work.relax_guarded();
    }
}
