//! Remeshing by parts shared out among ranks, each rank a job of its own
//! that runs only its tasks and sees the others' outcomes as bytes, as
//! an MPI program does: the mesh is the threaded run's, bit for bit, for
//! any rank count, and the ranks' triangles cover it once.

mod common;

use loopsurf::remesh::{outcomes_from_bytes, outcomes_to_bytes, PartsJob, TaskOutcome};
use loopsurf::{Remesher, Surface, SurfaceMesh};

/// The jobs of `ranks` ranks run to the end, exchanging outcomes as bytes
/// stage by stage; the stages seen.
fn by_ranks<'a>(remesher: &Remesher<'a>, ranks: usize) -> (Vec<PartsJob<'a>>, Vec<&'static str>) {
    let mut jobs: Vec<PartsJob> = (0..ranks).map(|_| remesher.parts_job().unwrap()).collect();
    let mut stages = Vec::new();
    while !jobs[0].is_done() {
        stages.push(jobs[0].stage_name());
        // Each rank runs its tasks and sends their bytes to all.
        let own: Vec<Vec<(usize, TaskOutcome)>> = jobs
            .iter()
            .enumerate()
            .map(|(r, job)| {
                let mine = job.assigned(r, ranks);
                mine.iter()
                    .map(|&i| (i, job.run_task(i).unwrap()))
                    .collect()
            })
            .collect();
        let sent: Vec<Vec<u8>> = own
            .iter()
            .map(|o| outcomes_to_bytes(&o.iter().map(|(i, x)| (*i, x)).collect::<Vec<_>>()))
            .collect();
        for (r, (job, mine)) in jobs.iter_mut().zip(own).enumerate() {
            let mut all: Vec<Option<TaskOutcome>> = (0..job.tasks()).map(|_| None).collect();
            for (q, bytes) in sent.iter().enumerate().filter(|&(q, _)| q != r) {
                for (i, outcome) in outcomes_from_bytes(bytes).unwrap() {
                    assert!(all[i].is_none(), "task {i} run twice (rank {q})");
                    all[i] = Some(outcome);
                }
            }
            for (i, outcome) in mine {
                assert!(all[i].is_none(), "task {i} run twice (rank {r})");
                all[i] = Some(outcome);
            }
            let all: Vec<TaskOutcome> = all
                .into_iter()
                .map(|o| o.expect("every task run"))
                .collect();
            job.advance(all).unwrap();
        }
        assert!(jobs.iter().all(|j| j.is_done() == jobs[0].is_done()));
    }
    (jobs, stages)
}

fn bits(mesh: &SurfaceMesh) -> Vec<[u64; 3]> {
    mesh.points
        .iter()
        .map(|p| p.to_array().map(f64::to_bits))
        .collect()
}

#[test]
fn ranks_exchanging_bytes_make_the_threaded_mesh() {
    let Some(path) = common::cgal_mesh("fandisk.off") else {
        return;
    };
    let mut net = loopsurf::ControlNet::read(path).unwrap();
    net.tag_by_angle(30.0).unwrap();
    let surface = Surface::new(&net).unwrap();
    let remesher = Remesher::new(&surface).adapt_curvature(true).parts(8);
    let threaded = remesher.run().unwrap();
    for ranks in [1, 3, 8, 11] {
        let (jobs, stages) = by_ranks(&remesher, ranks);
        println!("{ranks} ranks: stages {stages:?}");
        assert!(stages.contains(&"interface crossings"), "{stages:?}");
        assert!(stages.contains(&"touch-up"), "{stages:?}");
        if ranks == 1 {
            let mesh = jobs[0].mesh().unwrap();
            assert_eq!(mesh.triangles, threaded.triangles);
            assert_eq!(mesh.params, threaded.params);
            assert_eq!(bits(&mesh), bits(&threaded));
            assert_eq!(mesh.hard_edges, threaded.hard_edges);
        } else {
            // No rank holds the whole mesh: each holds its own piece.
            let err = jobs[0].mesh().unwrap_err().to_string();
            assert!(err.contains("not on this process"), "{err}");
        }
        // The pieces, on their global ids, are the threaded mesh: each
        // vertex where its id says, each triangle in exactly one piece.
        let whole_bits = bits(&threaded);
        let mut held: Vec<[u32; 3]> = Vec::new();
        for (r, job) in jobs.iter().enumerate() {
            let (piece, ids) = job.rank_piece(r, ranks).unwrap();
            for (i, &g) in ids.iter().enumerate() {
                let g = g as usize;
                assert_eq!(piece.params[i], threaded.params[g], "rank {r} of {ranks}");
                assert_eq!(bits(&piece)[i], whole_bits[g], "rank {r} of {ranks}");
            }
            held.extend(piece.triangles.iter().map(|t| t.map(|v| ids[v as usize])));
        }
        let mut whole = threaded.triangles.clone();
        whole.sort_unstable();
        held.sort_unstable();
        assert_eq!(held, whole, "{ranks} ranks: the pieces are not the mesh");
    }
}

#[test]
fn a_damaged_outcome_and_a_wrong_count_are_refused() {
    let net = common::example("viking", Some(30.0));
    let surface = Surface::new(&net).unwrap();
    let remesher = Remesher::new(&surface).size(0.1).parts(3);
    let mut job = remesher.parts_job().unwrap();
    let outcome = job.run_task(0).unwrap();
    let mut bytes = outcomes_to_bytes(&[(0, &outcome)]);
    let n = bytes.len();
    bytes[n - 10] ^= 1;
    let err = outcomes_from_bytes(&bytes).err().unwrap().to_string();
    assert!(err.contains("checksum"), "{err}");
    let err = outcomes_from_bytes(&bytes[..n - 1])
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("runs past the end"), "{err}");
    let err = job.advance(vec![outcome]).unwrap_err().to_string();
    assert!(
        err.contains("1 outcomes for the sizes stage's 3 tasks"),
        "{err}"
    );
    let err = job.run_task(3).err().unwrap().to_string();
    assert!(
        err.contains("task 3 of the sizes stage, which has 3"),
        "{err}"
    );
    assert!(job.into_mesh().is_err());
}
