//! The quality remesher: isotropic (or curvature-adaptive) triangles on the
//! exact limit surface, whatever the shapes of the control triangles.
//!
//! The chart mesher ([`crate::mesh`]) cuts each control triangle in its own
//! parameter domain, so its triangles copy the control net's shapes. Here
//! its output is only the start: a conforming mesh with the crease chains
//! as edge chains and every vertex a surface point. Then, for a few rounds,
//! the passes of [`passes`] — split long edges, collapse short ones, flip
//! towards valence 6, relax tangentially — bring every edge within
//! [4/5, 4/3] of its target length with near-equilateral triangles, and a
//! last max–min angle flip and relaxation polish the angles, the last
//! relaxations keeping only the moves that close no vertex's smallest
//! angle. Twice early on the free vertices are shaken, deterministically: a
//! chart lattice of right triangles is otherwise a fixed point of all four
//! passes.
//!
//! After each round's collapses the mesh is renumbered along a Z-order
//! curve through its vertices, so that the passes' walks stay in cache.
//!
//! Every vertex carries its parameters (tri, v, w) and is exactly the
//! surface there ([`vertices`]); corners never move, crease and boundary
//! vertices move along their exact curve, and the chains of output edges
//! along a curve are kept (split along the curve, collapsed only along it,
//! never flipped), so every triangle keeps its model face.
//!
//! The size is one length, or from the exact principal curvatures under a
//! chord tolerance, capped and graded ([`sizing`]). With a tolerance the
//! chord error is measured afterwards at every centroid and edge midpoint
//! (the distance to the surface by local projection, which is at least the
//! true distance, so a bound, confirmed by certified snap where it exceeds
//! the tolerance); where it is exceeded the sizes there shrink and the
//! rounds run again, up to [`TOLERANCE_ROUNDS`] times. The mesh then
//! reports the largest chord error measured ([`SurfaceMesh::deviation`]),
//! which a caller compares with the tolerance: a few edges can be stuck
//! longer than their size (a split would fold a triangle where the
//! surface turns sharply within one edge, as at a cusp of a boundary
//! curve), and a mesh with the tolerance missed there is worth more than
//! none.

mod connectivity;
mod passes;
mod sizing;
mod vertices;

use crate::error::{Error, Result};
use crate::mesh::{Density, Mesher, SurfaceMesh};
use crate::refine::SurfacePoint;
use crate::surface::Surface;
use crate::topology::NONE;
use connectivity::Connectivity;
use glam::DVec3;
use passes::{Remeshing, EDGES_SHORT_BY};
use rayon::prelude::*;
use sizing::Sizing;
use std::collections::HashMap;
use vertices::{Kind, Placer, Vertex};

/// The default size cap of curvature adaptation without `size`, as a
/// fraction of the bounding-box diagonal.
pub const DEFAULT_ADAPT_CAP: f64 = 0.05;

/// The default gradation: neighbouring sizes differ by at most this factor
/// per edge (MMG's default hgrad).
pub const DEFAULT_GRADATION: f64 = 1.3;

/// The default triangle budget ([`Remesher::max_triangles`]): about 8 GB
/// at the 0.4 KB per output triangle the remesher holds at its peak (pig
/// at 0.2%: 883k triangles, 355 MB). A tolerance on a surface that folds
/// (mpi.off: curvatures of 68 000 per unit) can ask for sizes no memory
/// holds, and the user should hear so, not meet the out-of-memory killer.
pub const DEFAULT_MAX_TRIANGLES: usize = 20_000_000;

/// The chart mesher's start is denser than the remesher's output (about
/// 3× at the same size, the Viking at 1%: 75 840 against 24 752): its
/// budget is this many times the remesher's.
const START_BUDGET: usize = 4;

/// What the passes aim at for `--size H`, in units of H. Edges come out
/// shorter than their target (relaxation pulls each vertex to the centroid
/// of its triangles, and a collapse that would leave an edge too long is
/// refused): aimed at H, their median was 0.91–0.92 H and only 86–90% lay
/// within the target window [0.8 H, 4/3 H] (Viking 1%, fandisk and pig 0.5%).
/// Aimed at 1.07 H, the median is 0.98–0.99 H and 96–97% lie within it,
/// with the angles as good (mean-min 52.1°, 51.5°, 51.6°).
const UNIFORM_AIM: f64 = 1.07;

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

/// A control triangle that shrank is stuck when its worst chord error
/// after that is still above this share of the one before.
const STUCK: f64 = 0.8;

/// A quality remesher of `surface`; configure it, then [`Remesher::run`].
#[derive(Clone)]
pub struct Remesher<'a> {
    surface: &'a Surface,
    size: Option<f64>,
    tolerance: Option<f64>,
    adapt: bool,
    gradation: f64,
    max_triangles: usize,
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
        }
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

    /// The error of a density over the budget.
    fn over_budget(&self, expected: f64) -> Error {
        Error::OverBudget {
            needed: expected,
            limit: self.max_triangles,
            message: format!(
                "the requested density needs about {expected:.3e} triangles, over the budget of {}: loosen the tolerance, raise the size or raise the budget",
                self.max_triangles
            ),
        }
    }

    /// The size field and the tolerance in model units, checked.
    fn sizing(&self) -> Result<(Sizing, Option<f64>)> {
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
        let tolerance =
            crate::mesh::checked_tolerance(self.tolerance, self.adapt)?.map(|t| t * diagonal);
        let sizing = match (self.size, self.adapt, tolerance) {
            (Some(h), false, None) => Sizing::Uniform(h * UNIFORM_AIM),
            // A size with a tolerance sizes by curvature under the size.
            // Shrinking a uniform size only where probes missed did not
            // converge on featured models (fandisk, the Viking): its first
            // rounds at the full size left edges spanning features, whose
            // splits the alignment check refused.
            (size, _, Some(tol)) => {
                let cap = size.unwrap_or(DEFAULT_ADAPT_CAP * diagonal);
                Sizing::curvature(self.surface, tol, cap, cap * 1e-3, self.gradation)
            }
            (None, _, None) => {
                return bad(
                    "no density given: pass a size, a tolerance or curvature adaptation".into(),
                )
            }
            (Some(_), true, None) => unreachable!("adaptation has a tolerance"),
        };
        if self.max_triangles == 0 {
            return bad("max_triangles 0: must be at least 1".into());
        }
        if let Sizing::Uniform(h) = sizing {
            // From the control net's area (near the surface's), before
            // the start mesh is built.
            let expected =
                EDGES_SHORT_BY * self.surface.net().area() / (0.25 * 3f64.sqrt() * h * h);
            if expected > self.max_triangles as f64 {
                return Err(self.over_budget(expected));
            }
        }
        Ok((sizing, tolerance))
    }

    /// Remeshes the surface.
    pub fn run(&self) -> Result<SurfaceMesh> {
        let (sizing, tolerance) = self.sizing()?;
        // The chart mesher at the same density: conforming, with the crease
        // chains, and cheap. Under a tolerance it starts adapted, unless the
        // chart mesher cannot meet it (its own measure, in parameters, can
        // stall where the remesher's sizes do not): then from the largest
        // size alone.
        let plain = Mesher::new(self.surface)
            .density(Density::Size(sizing.largest()))
            .max_triangles(self.max_triangles.saturating_mul(START_BUDGET))
            .swaps(false);
        let start = match (&sizing, tolerance) {
            (Sizing::Curvature { .. }, Some(tol)) => {
                let diagonal = self.surface.net().bbox_diagonal();
                plain
                    .clone()
                    .adapt_curvature(true)
                    .tolerance((tol / diagonal).min(0.5))
                    .run()
                    .or_else(|_| plain.run())
            }
            _ => plain.run(),
        }
        .map_err(|e| {
            e.during(format!(
                "the chart mesh the remesher starts from (allowed {START_BUDGET} × the budget of {} triangles)",
                self.max_triangles
            ))
        })?;
        let mut work = start_from(self.surface, &start)?;
        let mut deviation = None;
        let mut shrink = vec![1.0; self.surface.net().triangles().len()];
        let mut last_missed = vec![f64::INFINITY; shrink.len()];
        for round in 0..=TOLERANCE_ROUNDS {
            for r in 0..ROUNDS {
                if round == 0 && SHAKE_ROUNDS.contains(&r) {
                    work.shake(SHAKE);
                }
                work.size = sizing.sizes(self.surface, &work.mesh, &work.vertices, &shrink);
                let expected = work.expected_triangles();
                if expected > self.max_triangles as f64 {
                    return Err(self.over_budget(expected));
                }
                // The estimate is from the mesh as it is; the splits are
                // bounded too, by triangle slots (dead ones too), which
                // bound the memory: splits adding more than the whole
                // budget run away. (Not the slots alone: the mesh they
                // start from may be denser than its sizes in places until
                // the collapses, and fandisk at 1e-4 with a budget of
                // 30 000 once held 60 000 after its first splits.)
                let limit =
                    (work.mesh.num_half_edges() as usize / 3).saturating_add(self.max_triangles);
                work.split_long(limit);
                if work.mesh.num_half_edges() as usize / 3 > limit {
                    return Err(Error::OverBudget {
                        needed: work.expected_triangles(),
                        limit: self.max_triangles,
                        message: format!(
                            "the splits ran past {limit} triangles where the sizes ask for about {:.3e} (the surface may fold over itself): loosen the tolerance, raise the size or raise the budget of {}",
                            work.expected_triangles(),
                            self.max_triangles
                        ),
                    });
                }
                work.collapse_short();
                work.renumber();
                work.equalize_valences();
                work.relax();
            }
            for _ in 0..POLISH {
                work.remove_caps();
                work.flip_for_angles();
                work.relax();
            }
            work.flip_for_angles();
            for _ in 0..GUARDED {
                work.relax_guarded();
            }
            let Some(tol) = tolerance else { break };
            let errors = chord_errors(&work, tol);
            let worst = errors.iter().map(|e| e.1).fold(0.0, f64::max);
            deviation = Some(worst);
            if worst <= tol || round == TOLERANCE_ROUNDS {
                break;
            }
            // Each control triangle shrinks once a round, by the factor its
            // worst miss asks for: chord error falls with the square of the
            // size. (Once per miss would compound over the many probes of
            // one triangle, down to the floor.)
            //
            // A control triangle whose worst miss did not fall after it
            // shrank is stuck, not too coarse (an edge that cannot be
            // split where the surface turns back within it, as at a cusp
            // of a crease or on a patch that folds): it shrinks no more.
            // Shrinking on, mpi.off at 40° missed by the same 0.2 in its
            // triangles 76, 82 and 84 each round while the sizes asked for
            // ever more, from 75 thousand triangles to 29 million.
            let mut missed = vec![0.0f64; shrink.len()];
            for (ids, e) in errors.iter().filter(|(_, e)| *e > tol) {
                for &v in ids {
                    let t = work.vertices[v as usize].at.tri as usize;
                    missed[t] = missed[t].max(*e);
                }
            }
            let stuck: Vec<bool> = (0..shrink.len())
                .map(|t| shrink[t] < 1.0 && missed[t] > STUCK * last_missed[t])
                .collect();
            // (A triangle that did not miss this round is judged afresh.)
            last_missed = missed
                .iter()
                .map(|&e| if e > 0.0 { e } else { f64::INFINITY })
                .collect();
            let mut factor = vec![1.0f64; shrink.len()];
            let topo = self.surface.net().topology();
            for (ids, e) in errors.iter().filter(|(_, e)| *e > tol) {
                let f = (0.8 * (tol / e).sqrt()).max(0.25);
                for &v in ids {
                    // Its control triangle and their neighbours: vertices
                    // relax across control edges, into sizes not shrunk.
                    let t = work.vertices[v as usize].at.tri as usize;
                    if stuck[t] {
                        continue;
                    }
                    factor[t] = factor[t].min(f);
                    for &e in &topo.triangle_edges()[t] {
                        for &n in &topo.edge_triangles()[e as usize] {
                            if n != NONE {
                                factor[n as usize] = factor[n as usize].min(f);
                            }
                        }
                    }
                }
            }
            for (s, f) in shrink.iter_mut().zip(factor) {
                *s *= f;
            }
        }
        Ok(finish(&work, deviation))
    }
}

/// The chord error of every triangle and edge as (its vertices, error):
/// the distance from its centroid or midpoint to the surface by local
/// projection (an upper bound of the true distance, and tight where the
/// guess is near) and, where that exceeds `tolerance`, by certified snap.
fn chord_errors(work: &Remeshing, tolerance: f64) -> Vec<(Vec<u32>, f64)> {
    let mesh = &work.mesh;
    let probes: Vec<(u32, Vec<u32>)> = (0..mesh.num_half_edges())
        .filter(|&h| mesh.is_alive(h))
        .flat_map(|h| {
            let o = mesh.opposite(h);
            let edge = (o == NONE || h < o).then(|| (h, vec![mesh.origin(h), mesh.dest(h)]));
            let tri = (h % 3 == 0).then(|| (h, mesh.corners(h).to_vec()));
            edge.into_iter().chain(tri)
        })
        .collect();
    probes
        .par_iter()
        .map(|(h, ids)| {
            let x = ids
                .iter()
                .map(|&i| work.vertices[i as usize].x)
                .sum::<DVec3>()
                / ids.len() as f64;
            let face = mesh.face[(h / 3) as usize];
            let guess = ids
                .iter()
                .map(|&i| &work.vertices[i as usize])
                .find(|v| v.is_free())
                .map(|v| v.at)
                .unwrap_or_else(|| work.placer.guess_in(&work.vertices[ids[0] as usize], face));
            let surface = work.placer.surface;
            let mut d = crate::snap::project(surface, x, guess.tri as usize, guess.v, guess.w)
                .map_or(f64::INFINITY, |s| s.distance);
            if d > tolerance {
                // A local minimum may be the wrong one (across a fold or a
                // crease): the certified snap decides.
                d = crate::snap::snap_near(surface, x, guess.tri as usize, guess.v, guess.w)
                    .map_or(f64::INFINITY, |s| s.distance);
            }
            (ids.clone(), d)
        })
        .collect()
}

/// The remesher's start from a chart mesh: vertex kinds from the mesh's
/// curve edges and the model's corners.
fn start_from<'a>(surface: &'a Surface, start: &SurfaceMesh) -> Result<Remeshing<'a>> {
    let placer = Placer::new(surface);
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
    let weights = [1.0 - at.v - at.w, at.v, at.w];
    let k = weights.iter().position(|&x| (x - 1.0).abs() <= 1e-12)?;
    Some(net.triangles()[at.tri as usize][k])
}

/// The output: live vertices and triangles compacted, feature edges
/// ordered by curve and parameter.
fn finish(work: &Remeshing, deviation: Option<f64>) -> SurfaceMesh {
    let (triangles, faces, index) = work.mesh.compact();
    let mut points = Vec::with_capacity(triangles.len() / 2 + 2);
    let mut params = Vec::with_capacity(triangles.len() / 2 + 2);
    for (v, &i) in index.iter().enumerate() {
        if i != NONE {
            points.push(work.vertices[v].x);
            params.push(work.vertices[v].at);
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
    SurfaceMesh {
        points,
        triangles,
        params,
        charts: Vec::new(),
        faces,
        hard_edges: hard.iter().map(|e| e.2).collect(),
        hard_edge_curves: hard.iter().map(|e| e.0).collect(),
        deviation,
        diagonal: work.placer.surface.net().bbox_diagonal(),
    }
}
