//! Remesher throughput, reported as output triangles per second, on two of
//! the remesher's cases: CGAL pig at 0.5% of the control net's diagonal
//! (hard edges at 40°) and the built-in Viking at 1% (30°), single thread
//! and all threads. The surface is built once outside the loop (its cost is
//! the eval bench's). Also the check for crossing triangles, which the
//! remesher's last pass and `loopsurf mesh` each run once on a clean
//! mesh: on pig's output, on one thread.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use loopsurf::{examples, ControlNet, Remesher, Surface};
use std::path::PathBuf;

fn cgal(name: &str) -> Option<ControlNet> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../.cache/cgal/data/meshes")
        .join(name);
    match ControlNet::read(&path) {
        Ok(net) => Some(net),
        Err(err) => {
            eprintln!("remesh bench skipped: {err} (scripts/test.sh extracts the CGAL meshes)");
            None
        }
    }
}

fn viking() -> ControlNet {
    let ex = examples::by_name("viking").unwrap();
    ControlNet::from_arrays(ex.points, &ex.tris).unwrap()
}

fn remesh(c: &mut Criterion) {
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut group = c.benchmark_group("remesh");
    group.sample_size(10);
    // `relative` is the target edge length as a fraction of the control
    // net's bounding-box diagonal.
    let mut run = |name: &str, mut net: ControlNet, angle: f64, relative: f64| {
        net.tag_by_angle(angle).unwrap();
        let surface = Surface::new(&net).unwrap();
        let remesher = Remesher::new(&surface).size(relative * net.bbox_diagonal());
        let mesh = remesher.run().unwrap();
        let quality = mesh.quality();
        eprintln!(
            "{name}: {} triangles, min angle {:.1}°, mean-min {:.1}°",
            mesh.triangles.len(),
            quality.min_angle,
            quality.mean_min_angle
        );
        group.throughput(Throughput::Elements(mesh.triangles.len() as u64));
        group.bench_function(format!("{name}_1_thread"), |b| {
            b.iter(|| single.install(|| remesher.run().unwrap()))
        });
        group.bench_function(format!("{name}_all_threads"), |b| {
            b.iter(|| remesher.run().unwrap())
        });
        group.bench_function(format!("{name}_crossings_1_thread"), |b| {
            b.iter(|| single.install(|| mesh.crossings()))
        });
    };
    if let Some(pig) = cgal("pig.off") {
        run("pig_0.005", pig, 40.0, 0.005);
    }
    run("viking_0.01", viking(), 30.0, 0.01);
    group.finish();
}

criterion_group!(benches, remesh);
criterion_main!(benches);
