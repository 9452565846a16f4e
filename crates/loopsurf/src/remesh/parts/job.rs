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
use super::join::{join, kept, sub_mesh, Joined};
use super::outcome::{Outcome, TaskOutcome};
use super::plan::{Pins, StartPlan};
use super::work::{run_tasks, PartWork};
use super::{
    AVOID_RINGS, BAND_RINGS, CROSSING_RINGS, FIRST_RINGS, LATER_RINGS, TOUCH_UP_BELOW,
    TOUCH_UP_RINGS,
};
use crate::error::{Error, Result};
use crate::mesh::SurfaceMesh;
use crate::partition;
use crate::remesh::budget::expected_over;
use crate::remesh::{Remesher, Settled};
use crate::topology::NONE;
use rayon::prelude::*;

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
    /// its first pass.
    works: Vec<Option<PartWork>>,
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
    Done(SurfaceMesh),
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
            works: (0..k).map(|_| None).collect(),
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
                let built;
                let work = match &self.works[i] {
                    Some(work) => work,
                    None => {
                        built = self.first_work(i)?;
                        &built
                    }
                };
                let net = remesher.surface.net();
                Outcome::Piece(Box::new(work.remesh_first(
                    net,
                    &f.plan,
                    &f.pins,
                    remesher.sliver_cuts,
                    i as u32,
                )?))
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
                // Dropped side by side: a part's surface is many small blocks.
                self.works.par_iter_mut().for_each(|w| *w = None);
                drop(f); // the plan and pins, before the join holds the mesh
                let joined = join_pieces(&self.remesher, Vec::new(), outcomes)?;
                Stage::Band(Box::new(self.band_pass(joined)?))
            }
            Stage::Band(b) => {
                let keep = kept(&b.pass, &b.owner);
                let moved = join_pieces(&self.remesher, vec![keep], outcomes)?;
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
            Stage::Crossings(b) => {
                let keep = kept(&b.pass, &b.owner);
                self.touch_up_or_done(join_pieces(&self.remesher, vec![keep], outcomes)?)
            }
            Stage::TouchUp(b) => {
                let keep = kept(&b.pass, &b.owner);
                Stage::Done(join_pieces(&self.remesher, vec![keep], outcomes)?.mesh)
            }
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
                    self.works[p] = work.map(|w| *w);
                }
                Outcome::Piece(_) => return Err(wrong_outcome("sizes")),
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
        let old: Vec<bool> = pass.from.iter().map(|&g| g != NONE).collect();
        let old_tris = mesh
            .params
            .iter()
            .zip(&old)
            .filter(|x| *x.1)
            .map(|x| x.0.tri);
        let avoid = control_rings(net, old_tris, AVOID_RINGS);
        let second = partition::partition_avoiding(net, self.k, &avoid)?;
        let band = mesh_rings(&mesh.triangles, &old, BAND_RINGS);
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
            Stage::Done(pass.mesh)
        }
    }

    /// A pass over `moved`: the band within `rings` edges of the vertices
    /// `seeds`, each connected blob of it one piece, uncut (for the
    /// crossings: first-interface vertices the second cut pinned again,
    /// and corners where three pieces met).
    fn blob_pass(&self, moved: Joined, seeds: &[bool], rings: usize) -> BandPass {
        let mesh = &moved.mesh;
        let band = mesh_rings(&mesh.triangles, seeds, rings);
        let (owner, count) = blobs(&mesh.triangles, &band);
        let nobody = vec![NONE; self.first_parts.len()];
        BandPass::new(moved, &band, owner, count, nobody, Vec::new())
    }

    /// The mesh, once the job is done.
    pub fn mesh(&self) -> Option<&SurfaceMesh> {
        match &self.stage {
            Stage::Done(mesh) => Some(mesh),
            _ => None,
        }
    }

    /// The mesh, once the job is done; an error before.
    pub fn into_mesh(self) -> Result<SurfaceMesh> {
        match self.stage {
            Stage::Done(mesh) => Ok(mesh),
            _ => Err(Error::InvalidArgument(format!(
                "the mesh is not made yet: the job is at its {} stage",
                self.stage_name()
            ))),
        }
    }

    /// Rank `rank`'s piece of the finished mesh ([`PartsJob::rank_triangles`])
    /// as a mesh of its own, and each of its vertices' index in the whole
    /// mesh: a vertex on the border between two pieces has one index.
    pub fn rank_piece(&self, rank: usize, ranks: usize) -> Result<(SurfaceMesh, Vec<u32>)> {
        let mine = self.rank_triangles(rank, ranks)?;
        let mesh = self
            .mesh()
            .expect("rank_triangles checked that the job is done");
        Ok(sub_mesh(mesh, mine.iter().map(|&t| t as usize)))
    }

    /// The triangles of the finished mesh that rank `rank` of `ranks`
    /// holds: those in the parts it meshed in the first pass (a triangle's
    /// part is the one most of its vertices' control triangles are in).
    pub fn rank_triangles(&self, rank: usize, ranks: usize) -> Result<Vec<u32>> {
        let Stage::Done(mesh) = &self.stage else {
            return Err(Error::InvalidArgument(format!(
                "no triangles to hand out yet: the job is at its {} stage",
                self.stage_name()
            )));
        };
        let per_part = {
            let mut count = vec![0usize; self.k];
            for &p in &self.first_parts {
                count[p as usize] += 1;
            }
            count
        };
        let rank_of = deal(&per_part, ranks);
        Ok((0..mesh.triangles.len() as u32)
            .filter(|&t| {
                let tri = mesh.triangles[t as usize];
                let part =
                    majority(tri.map(|v| self.first_parts[mesh.params[v as usize].tri as usize]));
                rank_of[part as usize] == rank
            })
            .collect())
    }
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
        let pins = Pins::new(&mesh.triangles, &owner, mesh.points.len(), |v| {
            meeting[v] >= 2 || !band[v]
        });
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

/// `first` and the pieces of `outcomes`, joined on their pinned vertices.
fn join_pieces(
    remesher: &Remesher,
    mut pieces: Vec<super::work::Piece>,
    outcomes: Vec<TaskOutcome>,
) -> Result<Joined> {
    for outcome in outcomes {
        match outcome.0 {
            Outcome::Piece(piece) => pieces.push(*piece),
            Outcome::Sizes { .. } => return Err(wrong_outcome("a remeshing")),
        }
    }
    join(remesher.surface, &pieces)
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
