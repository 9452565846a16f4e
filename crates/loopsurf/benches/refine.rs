//! Uniform refinement throughput: CGAL bunny00 (75k triangles) to 3 levels
//! (4.8M triangles), single thread, reported as output triangles per second.
//! Peer figures (OpenSubdiv Far, OpenMesh LoopT) come from the C++ harness.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use loopsurf::refine::refine_uniform;
use loopsurf::ControlNet;
use std::path::PathBuf;

fn bunny() -> Option<ControlNet> {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../.cache/cgal/data/meshes/bunny00.off");
    match ControlNet::read(&path) {
        Ok(net) => Some(net),
        Err(err) => {
            eprintln!("refine bench skipped: {err} (scripts/test.sh extracts the CGAL meshes)");
            None
        }
    }
}

fn refine(c: &mut Criterion) {
    let Some(net) = bunny() else { return };
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let levels = 3;
    let out_tris = (net.triangles().len() as u64) << (2 * levels);
    let mut group = c.benchmark_group("refine_uniform");
    group.sample_size(10);
    group.throughput(Throughput::Elements(out_tris));
    group.bench_function("bunny00_3_levels_1_thread", |b| {
        b.iter(|| single.install(|| refine_uniform(&net, levels).unwrap()))
    });
    group.bench_function("bunny00_3_levels_all_threads", |b| {
        b.iter(|| refine_uniform(&net, levels).unwrap())
    });
    group.finish();
}

criterion_group!(benches, refine);
criterion_main!(benches);
