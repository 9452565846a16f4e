//! Interpolating control net solve (S∞ x′ = x, sparse LU) on CGAL bunny00
//! (37.7k vertices): single thread and all threads. Target: under 1 s
//! single thread.

use criterion::{criterion_group, criterion_main, Criterion};
use loopsurf::{interpolate, ControlNet};
use std::path::PathBuf;

fn interpolate(c: &mut Criterion) {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../.cache/cgal/data/meshes/bunny00.off");
    let net = match ControlNet::read(&path) {
        Ok(net) => net,
        Err(err) => {
            eprintln!(
                "interpolate bench skipped: {err} (scripts/test.sh extracts the CGAL meshes)"
            );
            return;
        }
    };
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut group = c.benchmark_group("interpolate_solve");
    group.sample_size(10);
    group.bench_function("bunny00_1_thread", |b| {
        b.iter(|| single.install(|| interpolate::solve(&net).unwrap()))
    });
    group.bench_function("bunny00_all_threads", |b| {
        b.iter(|| interpolate::solve(&net).unwrap())
    });
    group.finish();
}

criterion_group!(benches, interpolate);
criterion_main!(benches);
