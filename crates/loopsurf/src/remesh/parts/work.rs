//! One part's work: its sub-net, surface and sizes, its piece of a start
//! (its own chart mesh in the first pass, cut from the joined mesh in the
//! later ones) in local terms, remeshed with its pinned vertices, and the
//! workers that remesh the pieces side by side.

use super::super::budget::Budget;
use super::super::finish::{finish, without_curves};
use super::super::remeshing::Remeshing;
use super::super::sizing::Sizing;
use super::super::tolerance::chord_errors;
use super::super::vertices::Placer;
use super::super::{remesh, start, Remesher, Settled};
use super::cuts::{control_rings, fans};
use super::plan::{Pins, StartPlan};
use crate::error::{Error, Result};
use crate::mesh::{planned_chart, SurfaceMesh};
use crate::parameters::SurfacePoint;
use crate::partition::Part;
use crate::surface::Surface;
use crate::topology::NONE;
use crate::ControlNet;
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Rounds of max–min flips and guarded relaxation in a touch-up
/// ([`PartWork::touch_up`]).
const TOUCH_UP_ROUNDS: usize = 3;

/// One part being remeshed: its sub-net's surface and its sizes.
pub(super) struct PartWork {
    pub(super) part: Part,
    pub(super) surface: Surface,
    /// Per local triangle: whether the part owns it.
    pub(super) owned: Vec<bool>,
    /// Per local triangle: its face in the whole.
    pub(super) whole_face: Vec<u32>,
    pub(super) sizing: Sizing,
    pub(super) tolerance: Option<f64>,
    pub(super) budget: Budget,
    /// Per local triangle: the shrink factor its sizes start with.
    pub(super) shrunk: Vec<f64>,
}

/// One part's piece of the mesh, in the whole's triangle ids, and each
/// vertex's pinned id (its index in the start) or [`NONE`]; and the
/// shrink factors its tolerance rounds left on its own control triangles
/// (global id, factor; where below 1).
pub(super) struct Piece {
    pub(super) mesh: SurfaceMesh,
    pub(super) pinned: Vec<u32>,
    /// Each vertex's target size at the end.
    pub(super) sizes: Vec<f64>,
    pub(super) shrunk: Vec<(u32, f64)>,
}

impl PartWork {
    /// A part covering the control triangles `cover` and those within
    /// `rings` vertex rings of them as a sub-net (its vertices land only
    /// there), its surface and its sizes at `settled` settings, shrunk by
    /// `shrunk` per global triangle (if given); it owns the triangles t
    /// with `parts[t] == p`.
    pub(super) fn new(
        remesher: &Remesher,
        settled: &Settled,
        cover: &[u32],
        rings: usize,
        parts: &[u32],
        p: u32,
        shrunk: Option<&[f64]>,
    ) -> Result<PartWork> {
        let net = remesher.surface.net();
        let near = control_rings(net, cover.iter().copied(), rings);
        let near: Vec<u32> = (0..near.len() as u32)
            .filter(|&t| near[t as usize])
            .collect();
        let part = Part::new(net, &near)?;
        let owned = part
            .global_triangles()
            .iter()
            .map(|&g| parts[g as usize] == p)
            .collect();
        let faces = remesher.surface.model().face_of_triangle();
        let whole_face = part
            .global_triangles()
            .iter()
            .map(|&g| faces[g as usize])
            .collect();
        let surface = Surface::part_of(remesher.surface, &part)?;
        let sizing = remesher.sizing_with(&surface, settled);
        let (tolerance, budget) = (settled.tolerance, settled.budget);
        let shrunk = part
            .global_triangles()
            .iter()
            .map(|&g| shrunk.map_or(1.0, |s| s[g as usize]))
            .collect();
        Ok(PartWork {
            shrunk,
            part,
            surface,
            owned,
            whole_face,
            sizing,
            tolerance,
            budget,
        })
    }

    /// Remeshes part `p`'s piece of `start`, a remeshed mesh (whose
    /// triangle t part `owner[t]` owns), vertex v pinned where `pins.id[v]`
    /// is not [`NONE`], each pinned vertex's size bounded by `bounds` (each
    /// start vertex's size from the pass before). Vertices land only in
    /// the triangles that evaluate as in the whole (the part's [`Part`]
    /// owns them). Unlike the first pass, it is not shaken: bunny00 in 8
    /// parts at five sizes from 0.25% to 0.5% of the diagonal, shaken
    /// against not: 196 against 108 triangles below 35° (57 whole),
    /// mean-min 0.03–0.06° higher unshaken, the smallest angles no better
    /// either way (23.8–29.5° against 20.8–32.7°; whole 32.5–34.4°).
    pub(super) fn remesh(
        &self,
        start: &SurfaceMesh,
        owner: &[u32],
        pins: &Pins,
        bounds: &[f64],
        p: u32,
    ) -> Result<Piece> {
        let (mut work, ids) = self.start_work(start, owner, pins, p)?;
        for (i, &g) in ids.iter().enumerate() {
            if work.is_pinned(i as u32) {
                work.size_bound[i] = bounds[g as usize];
            }
        }
        self.finish_remesh(&mut work, false)
    }

    /// `work` remeshed on the part's sizes (shaken if `shake`), as a piece.
    fn finish_remesh(&self, work: &mut Remeshing, shake: bool) -> Result<Piece> {
        let (deviation, factors) = remesh(
            work,
            &self.sizing,
            self.tolerance,
            &self.budget,
            Some(self.shrunk.clone()),
            shake,
        )?;
        Ok(self.piece(work, deviation, &factors))
    }

    /// Part `p`'s piece of the first pass: the chart mesh of its own
    /// control triangles at `plan`'s levels, on its own surface
    /// ([`planned_chart`]), its points that other parts share pinned
    /// (`pins`, by their ids in `plan`), remeshed. `net` is the whole
    /// control net.
    pub(super) fn remesh_first(
        &self,
        net: &ControlNet,
        plan: &StartPlan,
        pins: &Pins,
        sliver_cuts: bool,
        p: u32,
    ) -> Result<Piece> {
        let globals = self.part.global_triangles();
        let levels: Vec<u32> = globals.iter().map(|&g| plan.levels[g as usize]).collect();
        let (chart, sources) = planned_chart(&self.surface, &levels, &self.owned, sliver_cuts)?;
        let (triangles, from) = split_fans(&chart.triangles);
        let piece = without_curves(
            from.iter().map(|&v| chart.points[v as usize]).collect(),
            triangles,
            from.iter().map(|&v| chart.params[v as usize]).collect(),
            chart
                .charts
                .iter()
                .map(|&c| self.whole_face[c as usize])
                .collect(),
            None,
            chart.diagonal,
        );
        let ids: Vec<u32> = from
            .iter()
            .map(|&v| plan.pin(net, &self.part, sources[v as usize]))
            .collect();
        let mut work = self.begin(&piece, &ids, pins, p)?;
        self.finish_remesh(&mut work, true)
    }

    /// Touches up part `p`'s piece of `start` without remeshing it: max–min
    /// angle flips and relaxation that keeps only the moves leaving a
    /// vertex's smallest angle no smaller, at the sizes `sizes` the passes
    /// before left. So no triangle gets worse, and a triangle that sat at
    /// the pinned rim of an earlier piece, now inside this one, can open.
    /// Under a tolerance, the piece comes back untouched if touching it
    /// would take its chord error past both the tolerance and what it was.
    pub(super) fn touch_up(
        &self,
        start: &SurfaceMesh,
        owner: &[u32],
        pins: &Pins,
        sizes: &[f64],
        p: u32,
    ) -> Result<Piece> {
        let begin = || -> Result<Remeshing<'_>> {
            let (mut work, ids) = self.start_work(start, owner, pins, p)?;
            for (i, &g) in ids.iter().enumerate() {
                work.size[i] = sizes[g as usize];
            }
            Ok(work)
        };
        let worst = |work: &Remeshing, tol: f64| {
            chord_errors(work, tol)
                .iter()
                .map(|e| e.1)
                .fold(0.0, f64::max)
        };
        let mut work = begin()?;
        let before = self.tolerance.map(|tol| worst(&work, tol));
        for _ in 0..TOUCH_UP_ROUNDS {
            work.flip_for_angles();
            work.relax_guarded();
        }
        let (work, deviation) = match (self.tolerance, before) {
            (Some(tol), Some(before)) => match worst(&work, tol) {
                after if after <= tol.max(before) => (work, Some(after)),
                _ => (begin()?, Some(before)),
            },
            _ => (work, None),
        };
        let factors = vec![1.0; self.part.global_triangles().len()];
        Ok(self.piece(&work, deviation, &factors))
    }

    /// The remeshing of part `p`'s piece of `start` as it starts, its
    /// vertices pinned as `pins` says, and each vertex's id in `start`.
    fn start_work(
        &self,
        start: &SurfaceMesh,
        owner: &[u32],
        pins: &Pins,
        p: u32,
    ) -> Result<(Remeshing<'_>, Vec<u32>)> {
        let (piece, ids) = self.start_piece(start, owner, p)?;
        let work = self.begin(&piece, &ids, pins, p)?;
        Ok((work, ids))
    }

    /// The remeshing of `piece` as it starts, its vertex i pinned where
    /// `pins` pins `ids[i]` (no id: [`NONE`]).
    fn begin(
        &self,
        piece: &SurfaceMesh,
        ids: &[u32],
        pins: &Pins,
        p: u32,
    ) -> Result<Remeshing<'_>> {
        let placer = Placer::within(&self.surface, &self.whole_face, |t| self.part.is_owned(t));
        let mut work = start::start_from(placer, piece)?;
        for (i, &g) in ids.iter().enumerate().filter(|x| *x.1 != NONE) {
            work.pinned[i] = pins.id[g as usize];
            let g = g as usize;
            work.yields[i] = work.is_pinned(i as u32) && (pins.kept[g] || pins.lowest[g] < p);
        }
        Ok(work)
    }

    /// The piece `work` has made, in the whole's triangle ids, with the
    /// shrink factors `factors` (per local triangle) below 1 on the
    /// triangles the part owns.
    fn piece(&self, work: &Remeshing, deviation: Option<f64>, factors: &[f64]) -> Piece {
        let (mut mesh, kept) = finish(work, deviation);
        let pinned = kept.iter().map(|&v| work.pinned[v as usize]).collect();
        let sizes = kept.iter().map(|&v| work.size[v as usize]).collect();
        let globals = self.part.global_triangles();
        for at in &mut mesh.params {
            at.tri = globals[at.tri as usize];
        }
        let shrunk = (0..globals.len())
            .filter(|&t| self.owned[t] && factors[t] < 1.0)
            .map(|t| (globals[t], factors[t]))
            .collect();
        Piece {
            mesh,
            pinned,
            sizes,
            shrunk,
        }
    }

    /// Part `p`'s triangles of `start` in local terms (faces stay the
    /// whole's), and the start's id of each of its vertices. Where the
    /// piece's triangles at a vertex form several fans (the piece touches
    /// itself there), each fan has its own copy; such a vertex is on an
    /// interface, pinned, and the copies join again.
    fn start_piece(
        &self,
        start: &SurfaceMesh,
        owner: &[u32],
        p: u32,
    ) -> Result<(SurfaceMesh, Vec<u32>)> {
        let mine: Vec<usize> = (0..start.triangles.len())
            .filter(|&t| owner[t] == p)
            .collect();
        let (triangles, ids) =
            split_fans(&mine.iter().map(|&t| start.triangles[t]).collect::<Vec<_>>());
        let params = ids
            .iter()
            .map(|&v| {
                let at = start.params[v as usize];
                Ok(SurfacePoint {
                    tri: self.local(at.tri)?,
                    ..at
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let piece = without_curves(
            ids.iter().map(|&v| start.points[v as usize]).collect(),
            triangles,
            params,
            mine.iter().map(|&t| start.faces[t]).collect(),
            None,
            start.diagonal,
        );
        Ok((piece, ids))
    }

    /// The local id of global triangle `t`, which the part must hold.
    fn local(&self, t: u32) -> Result<u32> {
        self.part
            .local_triangle(t)
            .map(|l| l as u32)
            .ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "the start's triangle {t} lies outside the part that meshes next to it"
                ))
            })
    }
}

/// `triangles` renumbered so that where they form several fans at a
/// vertex (a piece that touches itself there), each fan has its own copy
/// of it; and per new vertex, its old one.
fn split_fans(triangles: &[[u32; 3]]) -> (Vec<[u32; 3]>, Vec<u32>) {
    let fans = fans(triangles);
    let mut local = HashMap::new();
    let mut from = Vec::new();
    let renumbered = triangles
        .iter()
        .enumerate()
        .map(|(i, tri)| {
            [0, 1, 2].map(|k| {
                *local.entry(fans[3 * i + k]).or_insert_with(|| {
                    from.push(tri[k]);
                    from.len() as u32 - 1
                })
            })
        })
        .collect();
    (renumbered, from)
}

/// Every task of a stage (`weights.len()` of them, task i about
/// `weights[i]` of work), run by `task`, the outcomes in task order.
///
/// The tasks are the unit of parallel work: as many workers as the
/// current rayon pool has threads each take the next task, the heaviest
/// first, and run it on a pool of their own (one thread each when there
/// are at least as many tasks as threads). Run as nested rayon jobs
/// instead, the pieces' serial passes held up each other's joins:
/// bunny00 in 8 parts ran 1.6 times faster on two threads than on one.
pub(super) fn run_tasks<T: Send>(
    weights: &[usize],
    task: impl Fn(usize) -> Result<T> + Sync,
) -> Result<Vec<T>> {
    let threads = rayon::current_num_threads();
    let workers = threads.min(weights.len()).max(1);
    let inner = (threads / workers).max(1);
    let mut order: Vec<usize> = (0..weights.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(weights[i]));
    let next = AtomicUsize::new(0);
    let done: Vec<Mutex<Option<Result<T>>>> = weights.iter().map(|_| Mutex::new(None)).collect();
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(inner).build();
                while let Some(&i) = order.get(next.fetch_add(1, Ordering::Relaxed)) {
                    let outcome = match &pool {
                        Ok(pool) => pool.install(|| task(i)),
                        Err(e) => Err(Error::InvalidArgument(format!("no thread pool: {e}"))),
                    };
                    *done[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(outcome);
                }
            });
        }
    });
    done.into_iter()
        .map(|m| {
            m.into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .unwrap_or_else(|| Err(Error::InvalidArgument("a task was not run".into())))
        })
        .collect()
}
