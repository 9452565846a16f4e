//! Mesher throughput, reported as output triangles per second: CGAL pig
//! curvature-adaptive at 5e-5 of the diagonal (about 245k triangles), CGAL bunny00 at a uniform
//! edge length to about 500k, single thread and all threads. The surface is
//! built once outside the loop (its cost is the eval bench's).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use loopsurf::{ControlNet, Density, Mesher, Surface};
use std::path::PathBuf;

fn cgal(name: &str) -> Option<Surface> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../.cache/cgal/data/meshes")
        .join(name);
    match ControlNet::read(&path) {
        Ok(net) => Some(Surface::new(&net).unwrap()),
        Err(err) => {
            eprintln!("mesh bench skipped: {err} (scripts/test.sh extracts the CGAL meshes)");
            None
        }
    }
}

fn mesh(c: &mut Criterion) {
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut group = c.benchmark_group("mesh");
    group.sample_size(10);
    let mut run = |name: &str, surface: &Surface, configure: &dyn Fn(Mesher) -> Mesher| {
        let mesher = configure(Mesher::new(surface));
        let triangles = mesher.run().unwrap().triangles.len() as u64;
        eprintln!("{name}: {triangles} triangles");
        group.throughput(Throughput::Elements(triangles));
        group.bench_function(format!("{name}_1_thread"), |b| {
            b.iter(|| single.install(|| mesher.run().unwrap()))
        });
        group.bench_function(format!("{name}_all_threads"), |b| {
            b.iter(|| mesher.run().unwrap())
        });
    };
    if let Some(pig) = cgal("pig.off") {
        run("pig_adaptive_5e-5", &pig, &|m| {
            m.density(Density::FromTolerance)
                .tolerance(5e-5)
                .adapt_curvature(true)
        });
    }
    if let Some(bunny) = cgal("bunny00.off") {
        run("bunny00_size_0.005", &bunny, &|m| {
            m.density(Density::Size(0.005))
        });
    }
    group.finish();
}

criterion_group!(benches, mesh);
criterion_main!(benches);
