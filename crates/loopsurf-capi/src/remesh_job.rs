//! `ls_remesh_job`: remeshing in parts shared out among the ranks of a
//! program that runs its own transport (MPI or other). The library never
//! calls MPI: each stage, every rank runs its share of the tasks, hands
//! the bytes it gets to every other rank (`MPI_Allgatherv`), and advances
//! with everybody's bytes. The mesh is `ls_remesh`'s with the same number
//! of parts, bit for bit, on any number of ranks.

use crate::buffers::malloc_copy;
use crate::handles::ls_remesh_job;
use crate::remesh::{ls_remesh_options, pool, remesher, trimesh_of};
use crate::status::{input, input_mut, output, read_options, run, run_void, Fail};
use crate::status::{LS_ERR_BAD_STREAM, LS_ERR_INVALID_ARGUMENT};
use crate::surface::ls_surface;
use crate::trimesh::ls_trimesh;
use loopsurf::remesh::{outcomes_from_bytes, outcomes_to_bytes, TaskOutcome};
use loopsurf::Surface;
use std::ffi::{c_char, c_int};

/// Starts remeshing `surface` in `options->parts` parts as rank `rank` of
/// `ranks` (0 ≤ rank < ranks), and writes the job to `*job`, to be
/// released with `ls_remesh_job_free`. Every rank makes its job with the
/// same surface (loaded and tagged alike, e.g. each from the same file)
/// and the same options. `options` may be NULL for the defaults (which
/// remesh in 1 part: one piece remeshed as a part, not necessarily
/// `ls_remesh`'s whole run). `options->threads` threads run this rank's
/// tasks (0: the library's pool).
///
/// The job borrows `surface`: keep it until the job is freed.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh_job_new(
    surface: *const ls_surface,
    options: *const ls_remesh_options,
    rank: c_int,
    ranks: c_int,
    job: *mut *mut ls_remesh_job,
) -> c_int {
    run("ls_remesh_job_new", || {
        let surface: &'static Surface = &input(surface, "surface")?.0;
        let o = read_options(options, "options")?;
        let out = output(job, "job")?;
        if ranks < 1 || rank < 0 || rank >= ranks {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("rank {rank} of {ranks}: need 0 <= rank < ranks"),
            ));
        }
        let pool = pool(o.threads)?;
        let job = remesher(surface, &o)?.parts_job()?;
        *out = Box::into_raw(Box::new(ls_remesh_job {
            job,
            rank: rank as usize,
            ranks: ranks as usize,
            pool,
            own: None,
            sent: Vec::new(),
        }));
        Ok(())
    })
}

/// Writes 1 to `*done` when the mesh is made, else 0; and, if `stage` is
/// not NULL, the name of the current stage ("sizes", "first pass",
/// "interface band", "interface crossings", "touch-up", "done", or
/// "failed" once an advance has failed), a static string.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh_job_done(
    job: *const ls_remesh_job,
    done: *mut c_int,
    stage: *mut *const c_char,
) -> c_int {
    run("ls_remesh_job_done", || {
        let job = &input(job, "job")?.job;
        let done = output(done, "done")?;
        let name = match job.stage_name() {
            "sizes" => c"sizes",
            "first pass" => c"first pass",
            "interface band" => c"interface band",
            "interface crossings" => c"interface crossings",
            "touch-up" => c"touch-up",
            "failed" => c"failed",
            _ => c"done",
        };
        *done = job.is_done() as c_int;
        if !stage.is_null() {
            *stage = name.as_ptr();
        }
        Ok(())
    })
}

/// Runs this rank's tasks of the current stage and writes their outcomes
/// as bytes to `*bytes` and their number to `*n` (possibly 0 bytes' worth
/// of tasks, never 0 bytes). The bytes belong to the job and stay valid
/// until the next call on it; send them to every rank. Calling it again
/// in the same stage runs the tasks again.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh_job_run(
    job: *mut ls_remesh_job,
    bytes: *mut *const u8,
    n: *mut usize,
) -> c_int {
    run("ls_remesh_job_run", || {
        let job = input_mut(job, "job")?;
        let outs = (output(bytes, "bytes")?, output(n, "n")?);
        match job.job.stage_name() {
            "done" => {
                return Err(Fail::new(
                    LS_ERR_INVALID_ARGUMENT,
                    "the job is done: no tasks left to run",
                ))
            }
            "failed" => {
                return Err(Fail::new(
                    LS_ERR_INVALID_ARGUMENT,
                    "the job failed at an earlier advance: start a new one",
                ))
            }
            _ => {}
        }
        let tasks = job.job.assigned(job.rank, job.ranks);
        let outcomes = match &job.pool {
            None => job.job.run_tasks(&tasks)?,
            Some(pool) => pool.install(|| job.job.run_tasks(&tasks))?,
        };
        let own: Vec<(usize, TaskOutcome)> = tasks.into_iter().zip(outcomes).collect();
        job.sent = outcomes_to_bytes(&own.iter().map(|(i, o)| (*i, o)).collect::<Vec<_>>());
        job.own = Some(own);
        *outs.0 = job.sent.as_ptr();
        *outs.1 = job.sent.len();
        Ok(())
    })
}

/// Advances the job to its next stage with every rank's bytes from
/// `ls_remesh_job_run`: `counts[q]` bytes from rank q, for q = 0 to ranks
/// − 1, one after another in `all` (what `MPI_Allgatherv` gathers). This
/// rank's own stretch is skipped: it keeps its outcomes. Damaged bytes
/// are `LS_ERR_BAD_STREAM`, a task missing or sent twice
/// `LS_ERR_INVALID_ARGUMENT`; the job then stays where it was. An error
/// of the stage's own work (a join, a partition) leaves the job failed.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh_job_advance(
    job: *mut ls_remesh_job,
    all: *const u8,
    counts: *const usize,
) -> c_int {
    run("ls_remesh_job_advance", || {
        let job = input_mut(job, "job")?;
        let counts = std::slice::from_raw_parts(input(counts, "counts")?, job.ranks);
        let total = counts
            .iter()
            .try_fold(0usize, |s, &c| s.checked_add(c))
            .ok_or_else(|| Fail::new(LS_ERR_INVALID_ARGUMENT, "counts overflow"))?;
        let all = match total {
            0 => &[][..],
            _ => std::slice::from_raw_parts(input(all, "all")?, total),
        };
        let Some(own_tasks) = job
            .own
            .as_ref()
            .map(|o| o.iter().map(|x| x.0).collect::<Vec<_>>())
        else {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                "this rank has not run its tasks of this stage (ls_remesh_job_run)",
            ));
        };
        let mut received = Vec::new();
        let mut at = 0;
        for (q, &c) in counts.iter().enumerate() {
            let stretch = &all[at..at + c];
            at += c;
            if q != job.rank {
                let theirs = outcomes_from_bytes(stretch).map_err(|e| {
                    Fail::new(LS_ERR_BAD_STREAM, format!("the bytes of rank {q}: {e}"))
                })?;
                received.push((q, theirs));
            }
        }
        // Every task from exactly one rank, checked before anything is
        // taken from the job, so that an error leaves it as it was.
        let tasks = job.job.tasks();
        let mut sender: Vec<Option<usize>> = vec![None; tasks];
        let mine = own_tasks.iter().map(|&i| (job.rank, i));
        let theirs = received
            .iter()
            .flat_map(|(q, o)| o.iter().map(move |(i, _)| (*q, *i)));
        for (q, i) in mine.chain(theirs) {
            match sender.get_mut(i) {
                Some(slot @ None) => *slot = Some(q),
                Some(Some(p)) => {
                    return Err(Fail::new(
                        LS_ERR_INVALID_ARGUMENT,
                        format!("task {i} sent twice, by ranks {p} and {q}"),
                    ))
                }
                None => {
                    return Err(Fail::new(
                        LS_ERR_INVALID_ARGUMENT,
                        format!("rank {q} sent task {i}; the stage has {tasks}"),
                    ))
                }
            }
        }
        if let Some(i) = sender.iter().position(Option::is_none) {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!(
                    "no rank sent task {i} of the {} stage",
                    job.job.stage_name()
                ),
            ));
        }
        let own = job.own.take().unwrap_or_default();
        let mut outcomes: Vec<Option<TaskOutcome>> = (0..tasks).map(|_| None).collect();
        for (i, o) in own
            .into_iter()
            .chain(received.into_iter().flat_map(|x| x.1))
        {
            outcomes[i] = Some(o);
        }
        job.job.advance(outcomes.into_iter().flatten().collect())?;
        job.sent = Vec::new();
        Ok(())
    })
}

/// The finished mesh, whole, as `ls_remesh` hands it over: a new
/// `ls_trimesh` in `*mesh`, released with `ls_trimesh_free`. Only a job
/// that ran every task holds it (one rank of one): on a rank of several,
/// which holds its own piece and the band along the interfaces,
/// `LS_ERR_INVALID_ARGUMENT` (take `ls_remesh_job_piece`); so too before
/// the job is done.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh_job_mesh(
    job: *const ls_remesh_job,
    mesh: *mut *mut ls_trimesh,
) -> c_int {
    run("ls_remesh_job_mesh", || {
        let job = &input(job, "job")?.job;
        let out = output(mesh, "mesh")?;
        let made = job.mesh()?;
        trimesh_of(&made)?.hand_over(out);
        Ok(())
    })
}

/// This rank's piece of the finished mesh: the triangles of the parts it
/// meshed in the first pass (every triangle of the whole is in exactly
/// one rank's piece), as a new `ls_trimesh` in `*piece` with its nodes
/// numbered 0 to n − 1, and in `*global_ids` a new array of n node ids
/// in the whole mesh (`ls_free_array`): a node on the border between two
/// pieces has the same id in both. Before the job is done:
/// `LS_ERR_INVALID_ARGUMENT`.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh_job_piece(
    job: *const ls_remesh_job,
    piece: *mut *mut ls_trimesh,
    global_ids: *mut *mut i64,
) -> c_int {
    run("ls_remesh_job_piece", || {
        let handle = input(job, "job")?;
        let job = &handle.job;
        let outs = (output(piece, "piece")?, output(global_ids, "global_ids")?);
        let (made, ids) = job.rank_piece(handle.rank, handle.ranks)?;
        let result = trimesh_of(&made)?;
        let ids: Vec<i64> = ids.into_iter().map(i64::from).collect();
        let ids = malloc_copy(&ids)?;
        *outs.1 = ids;
        result.hand_over(outs.0);
        Ok(())
    })
}

/// Releases a job; NULL is ignored.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh_job_free(job: *mut ls_remesh_job) {
    run_void("ls_remesh_job_free", || {
        if !job.is_null() {
            drop(Box::from_raw(job));
        }
    })
}
