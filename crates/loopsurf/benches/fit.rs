//! Fitting time on one thread and on all: a CAD-like sphere of about
//! 110k triangles (chord 5e-4/16 of the diagonal, as in the fitting
//! tables of docs/fitting.md), fitted at the default resolution and
//! tolerance. The goal is 10 s on one thread.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use loopsurf::cad::{self, Analytic};
use loopsurf::Fitter;
use std::time::Duration;

fn fit(c: &mut Criterion) {
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let net = cad::sphere(5e-4 / 16.0, 15.0).net().unwrap();
    let mut group = c.benchmark_group("fit");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(60));
    group.throughput(Throughput::Elements(net.triangles().len() as u64));
    eprintln!("fine sphere: {} triangles", net.triangles().len());
    group.bench_function("sphere_110k_1_thread", |b| {
        b.iter(|| single.install(|| Fitter::new(&net).run().unwrap()))
    });
    group.bench_function("sphere_110k_all_threads", |b| {
        b.iter(|| Fitter::new(&net).run().unwrap())
    });
    group.finish();
}

criterion_group!(benches, fit);
criterion_main!(benches);
