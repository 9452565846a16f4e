//! Remeshing by parts as a job of stages, so that the same work runs on
//! threads or on the ranks of an MPI job.
//!
//! Each stage is a list of tasks that depend only on what every process
//! already holds: one part's sizes, one part's piece of the first pass, of
//! the band, or of a crossing blob. The tasks of a stage run anywhere, in
//! any order; their outcomes, all of them, then advance the job to its
//! next stage the same way on every process (a join, a partition, the
//! next stage's cuts). [`super::run`] runs every task on this process's
//! threads. An MPI program runs on each rank the tasks
//! [`PartsJob::assigned`] gives it, sends their outcomes as bytes
//! ([`super::outcome`]) to every rank, and advances with all of them: the
//! mesh is the threaded one, bit for bit, on any number of ranks.

use super::cuts::{blobs, control_rings, majority, mesh_rings, pieces_meeting};
use super::interior::{assemble, split, Interior, Numbering};
use super::join::{join, kept, Joined};
use super::outcome::{Outcome, TaskOutcome};
use super::plan::{Pins, StartPlan};
use super::work::{run_tasks, PartWork};
use super::{
    AVOID_RINGS, BAND_RINGS, CROSSING_RINGS, FIRST_RINGS, LATER_RINGS, SHARED_RINGS,
    TOUCH_UP_BELOW, TOUCH_UP_RINGS,
};
use crate::error::{Error, Result};
use crate::mesh::SurfaceMesh;
use crate::partition;
use crate::remesh::budget::expected_over;
use crate::remesh::{Remesher, Settled};
use crate::topology::NONE;
use rayon::prelude::*;
use std::sync::Mutex;

/// Remeshing in parts, stage by stage (see the module doc): make one with
/// [`Remesher::parts_job`], then until [`PartsJob::is_done`], run the
/// current stage's tasks ([`PartsJob::run_task`]) and hand every outcome,
/// in task order, to [`PartsJob::advance`].
pub struct PartsJob<'a> {
    remesher: Remesher<'a>,
    /// The remesher's settings, measured on the whole net once.
    settled: Settled,
    k: usize,
    /// Per control triangle: its part in the first partition, which also
    /// says which rank holds which triangle of the final mesh.
    first_parts: Vec<u32>,
    stage: Stage,
    /// The parts' works this process built in the sizes stage, kept for
    /// its first pass, each taken (and dropped) by its first-pass task:
    /// held until the first pass ended, they took one process remeshing
    /// bunny00 refined twice in 32 parts to 6.14 GB, against 4.28 GB.
    works: Vec<Mutex<Option<PartWork>>>,
    /// Per part: what its first-pass task weighed, which deals the parts'
    /// tasks, and so their interiors and their triangles of the finished
    /// mesh, to the ranks.
    first_weights: Vec<usize>,
    /// Per part: the interior of its first-pass piece, where this process
    /// made it.
    interiors: Vec<Option<Interior>>,
    /// Per part: how many vertices its interior holds off its rim, and
    /// on it (from the first pass on), which number the finished mesh.
    inner: Vec<usize>,
    rims: Vec<usize>,
}

enum Stage {
    /// Each part's sub-net, surface and sizes; the outcome is the largest
    /// size the part asks for.
    Sizes,
    /// Each part's chart mesh of its own control triangles at the levels
    /// planned from the sizes, remeshed with the points it shares pinned.
    First(Box<FirstPass>),
    /// The band around the first interfaces, cut by a second partition.
    Band(Box<BandPass>),
    /// The band around the places where the second cut crossed a first
    /// interface or three pieces met, each connected blob uncut.
    Crossings(Box<BandPass>),
    /// Around the triangles still below [`TOUCH_UP_BELOW`], each connected
    /// blob touched up uncut (flips and guarded relaxation only).
    TouchUp(Box<BandPass>),
    /// The band's mesh as the last pass left it; the finished mesh is it
    /// and the interiors.
    Done(Box<Joined>),
    /// A stage failed to advance: what went wrong.
    Failed(String),
}

struct FirstPass {
    plan: StartPlan,
    /// The start's points two parts share, pinned.
    pins: Pins,
    /// Per part: the triangles its sizes ask for, what its task weighs.
    weights: Vec<usize>,
}

/// A pass over some triangles of a mesh: those `owner` gives a part are
/// remeshed, one task per part, the rest stays.
struct BandPass {
    pass: Joined,
    owner: Vec<u32>,
    /// The parts with triangles to remesh, in order: task i is part
    /// `parts[i]`.
    parts: Vec<u32>,
    /// Per part: the control triangles under its triangles.
    cover: Vec<Vec<u32>>,
    /// Per control triangle: the part whose sub-net owns it (for its
    /// shrink factors), or [`NONE`].
    control_owner: Vec<u32>,
    pins: Pins,
    /// Per vertex of the mesh: how many pieces meet there (up to 3), the
    /// triangles no part remeshes one piece.
    meeting: Vec<u8>,
    /// Per vertex of the mesh: whether it is a first-interface vertex
    /// (the band pass only, to find where the second cut crossed them).
    old: Vec<bool>,
}

impl<'a> PartsJob<'a> {
    /// The job of remeshing with `remesher` in `k` parts, at its first
    /// stage: the control net's first partition.
    pub(in crate::remesh) fn new(remesher: Remesher<'a>, k: usize) -> Result<PartsJob<'a>> {
        if k == 0 {
            return Err(Error::InvalidArgument(
                "0 parts: remesh in at least 1".into(),
            ));
        }
        let settled = remesher.settled()?;
        let first = partition::partition(remesher.surface.net(), k)?;
        Ok(PartsJob {
            remesher,
            settled,
            k,
            first_parts: first.parts().to_vec(),
            stage: Stage::Sizes,
            works: (0..k).map(|_| Mutex::new(None)).collect(),
            first_weights: Vec::new(),
            interiors: (0..k).map(|_| None).collect(),
            inner: Vec::new(),
            rims: Vec::new(),
        })
    }

    /// The number of parts.
    pub fn num_parts(&self) -> usize {
        self.k
    }

    /// Whether the mesh is made ([`PartsJob::mesh`]).
    pub fn is_done(&self) -> bool {
        matches!(self.stage, Stage::Done(_))
    }

    /// The number of tasks of the current stage (0 when done).
    pub fn tasks(&self) -> usize {
        self.weights().len()
    }

    /// The name of the current stage, for progress messages.
    pub fn stage_name(&self) -> &'static str {
        match self.stage {
            Stage::Sizes => "sizes",
            Stage::First(_) => "first pass",
            Stage::Band(_) => "interface band",
            Stage::Crossings(_) => "interface crossings",
            Stage::TouchUp(_) => "touch-up",
            Stage::Done(_) => "done",
            Stage::Failed(_) => "failed",
        }
    }

    /// Per task of the current stage: about how much work it is (control
    /// triangles of its part for the sizes; the triangles its sizes ask
    /// for in the first pass, where control triangles under-weighed the
    /// parts that mesh finely and left one thread working alone at the end
    /// on bunny00; mesh triangles to remesh after).
    pub fn weights(&self) -> Vec<usize> {
        let per_part = |owner: &[u32], n: usize| {
            let mut count = vec![0usize; n];
            for &p in owner.iter().filter(|&&p| p != NONE) {
                count[p as usize] += 1;
            }
            count
        };
        match &self.stage {
            Stage::Sizes => per_part(&self.first_parts, self.k),
            Stage::First(f) => f.weights.clone(),
            Stage::Band(b) | Stage::Crossings(b) | Stage::TouchUp(b) => {
                let count = per_part(&b.owner, b.cover.len());
                b.parts.iter().map(|&p| count[p as usize]).collect()
            }
            Stage::Done(_) | Stage::Failed(_) => Vec::new(),
        }
    }

    /// The tasks of the current stage that rank `rank` of `ranks` runs,
    /// in order: the heaviest task first to the least loaded rank (the
    /// lowest on a tie), which every rank computes alike.
    pub fn assigned(&self, rank: usize, ranks: usize) -> Vec<usize> {
        let owners = deal(&self.weights(), ranks);
        (0..owners.len()).filter(|&i| owners[i] == rank).collect()
    }

    /// Runs task `i` of the current stage. It depends only on what every
    /// process holds, so any process may run it, with the same outcome.
    pub fn run_task(&self, i: usize) -> Result<TaskOutcome> {
        let tasks = self.tasks();
        if i >= tasks {
            return Err(Error::InvalidArgument(format!(
                "task {i} of the {} stage, which has {tasks}",
                self.stage_name()
            )));
        }
        let remesher = &self.remesher;
        Ok(TaskOutcome(match &self.stage {
            Stage::Sizes => {
                let work = self.first_work(i)?;
                let largest = work.sizing.largest(|t| work.owned[t]);
                let expected = expected_over(work.surface.net(), &work.sizing, |t| work.owned[t]);
                let globals = work.part.global_triangles();
                let sizes = match work.sizing.adapts_to() {
                    Some(_) => (0..globals.len())
                        .filter(|&t| work.owned[t])
                        .map(|t| (globals[t], work.sizing.of_triangle(t)))
                        .collect(),
                    None => Vec::new(),
                };
                Outcome::Sizes {
                    largest,
                    expected,
                    sizes,
                    work: Some(Box::new(work)),
                }
            }
            Stage::First(f) => {
                let kept = self.works[i]
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .take();
                let work = match kept {
                    Some(work) => work,
                    None => self.first_work(i)?,
                };
                let net = remesher.surface.net();
                let piece =
                    work.remesh_first(net, &f.plan, &f.pins, remesher.sliver_cuts, i as u32)?;
                drop(work);
                let (band, rim, interior) = split(piece, SHARED_RINGS);
                Outcome::Band {
                    band: Box::new(band),
                    rim,
                    inner: interior.inner(),
                    interior: Some(Box::new(interior)),
                }
            }
            Stage::Band(b) | Stage::Crossings(b) | Stage::TouchUp(b) => {
                let p = b.parts[i];
                let work = PartWork::new(
                    remesher,
                    &self.settled,
                    &b.cover[p as usize],
                    LATER_RINGS,
                    &b.control_owner,
                    p,
                    Some(&b.pass.shrunk),
                )?;
                let (start, owner, pins, sizes) = (&b.pass.mesh, &b.owner, &b.pins, &b.pass.sizes);
                let piece = match self.stage {
                    Stage::TouchUp(_) => work.touch_up(start, owner, pins, sizes, p)?,
                    _ => work.remesh(start, owner, pins, sizes, p)?,
                };
                Outcome::Piece(Box::new(piece))
            }
            Stage::Done(_) | Stage::Failed(_) => unreachable!("no task at the end"),
        }))
    }

    /// Runs the tasks `tasks` of the current stage on the current rayon
    /// pool's threads, the heaviest first; their outcomes in the order of
    /// `tasks`.
    pub fn run_tasks(&self, tasks: &[usize]) -> Result<Vec<TaskOutcome>> {
        let weights = self.weights();
        let of_tasks: Vec<usize> = tasks
            .iter()
            .map(|&i| weights.get(i).copied().unwrap_or(0))
            .collect();
        run_tasks(&of_tasks, |j| self.run_task(tasks[j]))
    }

    /// Part p's work in the first partition.
    fn first_work(&self, p: usize) -> Result<PartWork> {
        let cover: Vec<u32> = (0..self.first_parts.len() as u32)
            .filter(|&t| self.first_parts[t as usize] == p as u32)
            .collect();
        PartWork::new(
            &self.remesher,
            &self.settled,
            &cover,
            FIRST_RINGS,
            &self.first_parts,
            p as u32,
            None,
        )
    }

    /// Advances to the next stage with the current stage's outcomes, one
    /// per task, in task order. A wrong number of outcomes leaves the job
    /// as it was; a stage that fails to advance leaves it failed.
    pub fn advance(&mut self, outcomes: Vec<TaskOutcome>) -> Result<()> {
        if let Stage::Failed(why) = &self.stage {
            return Err(Error::InvalidArgument(format!(
                "the job failed before: {why}"
            )));
        }
        if outcomes.len() != self.tasks() {
            return Err(Error::InvalidArgument(format!(
                "{} outcomes for the {} stage's {} tasks",
                outcomes.len(),
                self.stage_name(),
                self.tasks()
            )));
        }
        let stage = std::mem::replace(&mut self.stage, Stage::Failed(String::new()));
        match self.next_stage(stage, outcomes) {
            Ok(next) => {
                self.stage = next;
                Ok(())
            }
            Err(e) => {
                self.stage = Stage::Failed(e.to_string());
                Err(e)
            }
        }
    }

    /// The stage after `stage`, from its outcomes.
    fn next_stage(&mut self, stage: Stage, outcomes: Vec<TaskOutcome>) -> Result<Stage> {
        Ok(match stage {
            Stage::Sizes => Stage::First(Box::new(self.first_pass(outcomes)?)),
            Stage::First(f) => {
                // The works of parts another process ran, dropped side by
                // side: a part's surface is many small blocks.
                (self.works.par_iter_mut())
                    .for_each(|w| *w.get_mut().unwrap_or_else(|e| e.into_inner()) = None);
                let shared = f.pins.id.len();
                drop(f); // the plan and pins, before the join holds the band
                let joined = self.join_bands(shared, outcomes)?;
                Stage::Band(Box::new(self.band_pass(joined)?))
            }
            Stage::Band(b) => {
                let moved = self.rejoin(&b, outcomes)?;
                // The first interface's vertices the second cut pinned
                // again, and the corners where three pieces met (the second
                // cut at the band's rim, or three parts): their triangles
                // had every vertex pinned, so no pass could mend them.
                let again: Vec<bool> = moved
                    .from
                    .iter()
                    .map(|&g| {
                        g != NONE && {
                            let meeting = b.meeting[g as usize];
                            meeting >= 3 || (meeting == 2 && b.old[g as usize])
                        }
                    })
                    .collect();
                if again.contains(&true) {
                    Stage::Crossings(Box::new(self.blob_pass(moved, &again, CROSSING_RINGS)))
                } else {
                    self.touch_up_or_done(moved)
                }
            }
            Stage::Crossings(b) => self.touch_up_or_done(self.rejoin(&b, outcomes)?),
            Stage::TouchUp(b) => Stage::Done(Box::new(self.rejoin(&b, outcomes)?)),
            done @ (Stage::Done(_) | Stage::Failed(_)) => done,
        })
    }

    /// The first pass from the sizes: its start planned over the whole
    /// net at the sizes the parts ask for ([`StartPlan`]). Where sizes
    /// follow curvature and that start would pass the budget, it is
    /// planned at the largest size alone, as the whole remesher's start
    /// falls back to.
    fn first_pass(&mut self, outcomes: Vec<TaskOutcome>) -> Result<FirstPass> {
        let mut largest: f64 = 0.0;
        let mut weights = Vec::with_capacity(outcomes.len());
        let mut per_triangle = Vec::new();
        for (p, outcome) in outcomes.into_iter().enumerate() {
            match outcome.0 {
                Outcome::Sizes {
                    largest: h,
                    expected,
                    sizes,
                    work,
                } => {
                    largest = largest.max(h);
                    weights.push(expected.round() as usize);
                    per_triangle.extend(sizes);
                    *self.works[p].get_mut().unwrap_or_else(|e| e.into_inner()) = work.map(|w| *w);
                }
                _ => return Err(wrong_outcome("sizes")),
            }
        }
        let net = self.remesher.surface.net();
        let budget = self.settled.budget;
        let uniform = vec![largest; net.triangles().len()];
        let mut sizes = uniform.clone();
        for &(t, h) in &per_triangle {
            let slot = sizes.get_mut(t as usize).ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "a part's sizes name control triangle {t}, but the net has {}",
                    net.triangles().len()
                ))
            })?;
            *slot = h.min(largest);
        }
        let plan = |sizes: &[f64]| {
            StartPlan::new(
                net,
                &self.first_parts,
                sizes,
                self.remesher.sliver_cuts,
                budget.start_allowance(),
            )
        };
        let (plan, pins) = match plan(&sizes) {
            Err(Error::OverBudget { .. }) if !per_triangle.is_empty() => plan(&uniform),
            planned => planned,
        }
        .map_err(|e| e.during(budget.start_context()))?;
        self.first_weights = weights.clone();
        Ok(FirstPass {
            plan,
            pins,
            weights,
        })
    }

    /// The band pass over the first pass's mesh `pass`, whose vertices
    /// pinned on an interface `pass.from` names: the band around the
    /// interfaces, cut along a second partition that keeps away from them.
    fn band_pass(&self, pass: Joined) -> Result<BandPass> {
        let net = self.remesher.surface.net();
        let mesh = &pass.mesh;
        let old: Vec<bool> = (pass.from.iter().zip(&pass.rim))
            .map(|(&g, &r)| g != NONE && r == NONE)
            .collect();
        let old_tris = mesh
            .params
            .iter()
            .zip(&old)
            .filter(|x| *x.1)
            .map(|x| x.0.tri);
        let avoid = control_rings(net, old_tris, AVOID_RINGS);
        let second = partition::partition_avoiding(net, self.k, &avoid)?;
        let band = within(&pass, &old, BAND_RINGS);
        let owner: Vec<u32> = mesh
            .triangles
            .iter()
            .map(|tri| {
                if tri.iter().any(|&v| band[v as usize]) {
                    majority(tri.map(|v| second.parts()[mesh.params[v as usize].tri as usize]))
                } else {
                    NONE
                }
            })
            .collect();
        Ok(BandPass::new(
            pass,
            &band,
            owner,
            self.k,
            second.parts().to_vec(),
            old,
        ))
    }

    /// The touch-up of `pass` where a triangle is below
    /// [`TOUCH_UP_BELOW`]; done if none is.
    fn touch_up_or_done(&self, pass: Joined) -> Stage {
        let quality = pass.mesh.triangle_quality();
        let mut seeds = vec![false; pass.mesh.points.len()];
        for (tri, q) in pass.mesh.triangles.iter().zip(&quality) {
            if q.min_angle < TOUCH_UP_BELOW {
                for &v in tri {
                    seeds[v as usize] = true;
                }
            }
        }
        if seeds.contains(&true) {
            Stage::TouchUp(Box::new(self.blob_pass(pass, &seeds, TOUCH_UP_RINGS)))
        } else {
            Stage::Done(Box::new(pass))
        }
    }

    /// A pass over `moved`: the band within `rings` edges of the vertices
    /// `seeds`, each connected blob of it one piece, uncut (for the
    /// crossings: first-interface vertices the second cut pinned again,
    /// and corners where three pieces met).
    fn blob_pass(&self, moved: Joined, seeds: &[bool], rings: usize) -> BandPass {
        let band = within(&moved, seeds, rings);
        let (owner, count) = blobs(&moved.mesh.triangles, &band);
        let nobody = vec![NONE; self.first_parts.len()];
        BandPass::new(moved, &band, owner, count, nobody, Vec::new())
    }

    /// The bands of the first pass's outcomes joined, each band's rim
    /// vertices pinned to ids past the plan's `shared` ones (so the join
    /// keeps them apart and the rim can be followed); the interiors this
    /// process made kept, and each part's counts that number the finished
    /// mesh.
    fn join_bands(&mut self, shared: usize, outcomes: Vec<TaskOutcome>) -> Result<Joined> {
        let mut bands = Vec::with_capacity(outcomes.len());
        let (mut inner, mut rims) = (Vec::new(), Vec::new());
        let mut next = shared as u32;
        for (p, outcome) in outcomes.into_iter().enumerate() {
            let Outcome::Band {
                mut band,
                rim,
                inner: n,
                interior,
            } = outcome.0
            else {
                return Err(wrong_outcome("the first pass's"));
            };
            for &v in &rim {
                band.pinned[v as usize] = next;
                next += 1;
            }
            inner.push(n);
            rims.push(rim.len());
            self.interiors[p] = interior.map(|i| *i);
            bands.push(*band);
        }
        let mut joined = join(self.remesher.surface, &bands)?;
        joined.rim = (joined.from.iter())
            .map(|&g| match g {
                NONE => NONE,
                g if g as usize >= shared => g - shared as u32,
                _ => NONE,
            })
            .collect();
        self.inner = inner;
        self.rims = rims;
        Ok(joined)
    }

    /// The mesh of the pass `b` with its parts' remeshed pieces
    /// `outcomes` in place, the rim carried over.
    fn rejoin(&self, b: &BandPass, outcomes: Vec<TaskOutcome>) -> Result<Joined> {
        let mut pieces = vec![kept(&b.pass, &b.owner)];
        for outcome in outcomes {
            match outcome.0 {
                Outcome::Piece(piece) => pieces.push(*piece),
                _ => return Err(wrong_outcome("a remeshing")),
            }
        }
        let mut joined = join(self.remesher.surface, &pieces)?;
        // Every rim vertex is pinned, so it comes from b's mesh.
        joined.rim = (joined.from.iter())
            .map(|&g| {
                if g == NONE {
                    NONE
                } else {
                    b.pass.rim[g as usize]
                }
            })
            .collect();
        Ok(joined)
    }

    /// The mesh, whole, once the job is done; an error before, or on a
    /// rank that did not make every part's interior (its piece is
    /// [`PartsJob::rank_piece`]).
    pub fn mesh(&self) -> Result<SurfaceMesh> {
        let band = self.band()?;
        let interiors = (self.interiors.iter().enumerate())
            .map(|(p, i)| {
                i.as_ref().map(|i| (p, i)).ok_or_else(|| {
                    Error::InvalidArgument(format!(
                        "the whole mesh is not on this process: part {p}'s interior \
                         was made on another rank (take this rank's piece)"
                    ))
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let all = 0..band.mesh.triangles.len();
        let (mut mesh, _) = assemble(&band.mesh, all, &interiors, &self.numbering(band))?;
        let curves =
            crate::mesh::curve_edges(self.remesher.surface, &mesh.params, &mesh.triangles)?;
        mesh.hard_edges = curves.pairs;
        mesh.hard_edge_curves = curves.curves;
        Ok(mesh)
    }

    /// The mesh, whole, once the job is done ([`PartsJob::mesh`]).
    pub fn into_mesh(self) -> Result<SurfaceMesh> {
        self.mesh()
    }

    /// Rank `rank`'s piece of the finished mesh as a mesh of its own (no
    /// curves), and each of its vertices' index in the whole mesh: a
    /// vertex on the border between two pieces has one index. The rank
    /// holds the parts whose first-pass tasks it ran (their interiors, and
    /// the band's triangles most of whose vertices lie on their control
    /// triangles); every triangle is in one rank's piece.
    pub fn rank_piece(&self, rank: usize, ranks: usize) -> Result<(SurfaceMesh, Vec<u32>)> {
        let band = self.band()?;
        let rank_of = deal(&self.first_weights, ranks);
        let mut interiors = Vec::new();
        for p in (0..self.k).filter(|&p| rank_of[p] == rank) {
            let interior = self.interiors[p].as_ref().ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "rank {rank} of {ranks} holds part {p}, but did not make its interior: \
                     the ranks' tasks were not dealt as this job deals them"
                ))
            })?;
            interiors.push((p, interior));
        }
        let mesh = &band.mesh;
        let mine = (0..mesh.triangles.len()).filter(|&t| {
            let tri = mesh.triangles[t];
            let part =
                majority(tri.map(|v| self.first_parts[mesh.params[v as usize].tri as usize]));
            rank_of[part as usize] == rank
        });
        assemble(mesh, mine, &interiors, &self.numbering(band))
    }

    /// Where the finished mesh's vertices go, `band` the last pass's.
    fn numbering(&self, band: &Joined) -> Numbering {
        Numbering::new(band.mesh.points.len(), &band.rim, &self.inner, &self.rims)
    }

    /// The band once the job is done; an error before.
    fn band(&self) -> Result<&Joined> {
        match &self.stage {
            Stage::Done(band) => Ok(band),
            _ => Err(Error::InvalidArgument(format!(
                "the mesh is not made yet: the job is at its {} stage",
                self.stage_name()
            ))),
        }
    }
}

/// The vertices of `pass` within `rings` edges of those `seeds` marks,
/// but its rim: the border the later passes keep.
fn within(pass: &Joined, seeds: &[bool], rings: usize) -> Vec<bool> {
    let mut near = mesh_rings(&pass.mesh.triangles, seeds, rings);
    for (n, &r) in near.iter_mut().zip(&pass.rim) {
        *n &= r == NONE;
    }
    near
}

impl BandPass {
    /// The pass over `pass.mesh`'s triangles that `owner` gives one of
    /// `k` parts, every vertex outside `band` and every vertex two parts
    /// share pinned; part p's sub-net owns the control triangles t with
    /// `control_owner[t] == p`.
    fn new(
        pass: Joined,
        band: &[bool],
        owner: Vec<u32>,
        k: usize,
        control_owner: Vec<u32>,
        old: Vec<bool>,
    ) -> BandPass {
        let mesh = &pass.mesh;
        let meeting = pieces_meeting(&mesh.triangles, &owner, mesh.points.len());
        let mut pins = Pins::new(&mesh.triangles, &owner, mesh.points.len(), |v| {
            meeting[v] >= 2 || !band[v]
        });
        // The rim is held by interiors no part sees, as by kept triangles.
        for (kept, &r) in pins.kept.iter_mut().zip(&pass.rim) {
            *kept |= r != NONE;
        }
        let mut cover: Vec<Vec<u32>> = vec![Vec::new(); k];
        for (tri, &p) in mesh.triangles.iter().zip(&owner) {
            if p != NONE {
                cover[p as usize].extend(tri.map(|v| mesh.params[v as usize].tri));
            }
        }
        let parts = (0..k as u32)
            .filter(|&p| !cover[p as usize].is_empty())
            .collect();
        BandPass {
            pass,
            owner,
            parts,
            cover,
            control_owner,
            pins,
            meeting,
            old,
        }
    }
}

fn wrong_outcome(stage: &str) -> Error {
    Error::InvalidArgument(format!(
        "an outcome of another stage handed to {stage} stage"
    ))
}

/// Per task: the rank of `ranks` that runs it, the heaviest first to the
/// least loaded (the lowest rank on a tie, the lower task on equal
/// weights).
fn deal(weights: &[usize], ranks: usize) -> Vec<usize> {
    let ranks = ranks.max(1);
    let mut order: Vec<usize> = (0..weights.len()).collect();
    order.sort_by_key(|&i| (std::cmp::Reverse(weights[i]), i));
    let mut load = vec![0usize; ranks];
    let mut owner = vec![0; weights.len()];
    for i in order {
        let r = (0..ranks).min_by_key(|&r| (load[r], r)).expect("a rank");
        owner[i] = r;
        load[r] += weights[i].max(1);
    }
    owner
}

#[cfg(test)]
mod tests {
    use super::deal;

    #[test]
    fn the_heaviest_task_goes_to_the_least_loaded_rank() {
        assert_eq!(deal(&[5, 9, 1, 4], 2), vec![1, 0, 0, 1]);
        assert_eq!(deal(&[3, 3, 3], 1), vec![0, 0, 0]);
        assert_eq!(deal(&[0, 0], 4), vec![0, 1]);
    }
}
