//! Adaptive subdivision throughput against uniform refinement of the same
//! input, as triangles produced per second: CGAL cow and elephant, four
//! levels, CA 11° (and 0°, the adaptive code doing uniform work), single
//! thread.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use loopsurf::refine::refine_uniform;
use loopsurf::Adapter;
use loopsurf::ControlNet;
use std::path::PathBuf;

fn cgal(name: &str) -> Option<ControlNet> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../.cache/cgal/data/meshes")
        .join(name);
    match ControlNet::read(&path) {
        Ok(net) => Some(net),
        Err(err) => {
            eprintln!("adapt bench skipped: {err} (scripts/test.sh extracts the CGAL meshes)");
            None
        }
    }
}

fn adapt(c: &mut Criterion) {
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut group = c.benchmark_group("adapt");
    group.sample_size(10);
    const LEVELS: u32 = 4;
    for name in ["cow.off", "elephant.off"] {
        let Some(net) = cgal(name) else { continue };
        let stem = name.trim_end_matches(".off");
        let uniform = net.triangles().len() as u64 * 4u64.pow(LEVELS);
        group.throughput(Throughput::Elements(uniform));
        group.bench_function(format!("{stem}_uniform_refine"), |b| {
            b.iter(|| single.install(|| refine_uniform(&net, LEVELS).unwrap()))
        });
        group.bench_function(format!("{stem}_adapt_ca0"), |b| {
            b.iter(|| {
                single.install(|| Adapter::new(&net).angle(0.0).levels(LEVELS).run().unwrap())
            })
        });
        let adapted = Adapter::new(&net).angle(11.0).levels(LEVELS).run().unwrap();
        let produced = adapted.net.triangles().len() as u64;
        eprintln!("{stem}: CA 11° gives {produced} triangles, uniform {uniform}");
        group.throughput(Throughput::Elements(produced));
        group.bench_function(format!("{stem}_adapt_ca11"), |b| {
            b.iter(|| {
                single.install(|| Adapter::new(&net).angle(11.0).levels(LEVELS).run().unwrap())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, adapt);
criterion_main!(benches);
