//! Exact evaluation throughput (all 18 numbers), single thread, on CGAL's
//! pig and bunny: (i) one point per triangle in random triangle order,
//! (ii) 16 points per triangle, triangle by triangle. Also the build time.
//! And the curvature at every vertex of a mesh, on the whole surface
//! against chunk by chunk ([`SurfaceMesh::vertex_curvature`]), each from a
//! surface with no patch made, with the bytes the surface keeps after.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use loopsurf::{ControlNet, Density, Mesher, Surface, SurfaceMesh};
use rayon::prelude::*;
use std::path::PathBuf;

fn mesh(name: &str) -> Option<ControlNet> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../.cache/cgal/data/meshes")
        .join(name);
    ControlNet::read(&path)
        .map_err(|e| {
            eprintln!("eval bench skipped: {e} (scripts/test.sh extracts the CGAL meshes)")
        })
        .ok()
}

/// A fixed pseudo-random sequence (no dependency, same points every run).
fn lcg(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}

fn point_in_triangle(state: &mut u64) -> (f64, f64) {
    let (a, b) = (lcg(state), lcg(state));
    if a + b > 1.0 {
        (1.0 - a, 1.0 - b)
    } else {
        (a, b)
    }
}

fn eval(c: &mut Criterion) {
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for name in ["pig.off", "bunny00.off"] {
        let Some(net) = mesh(name) else { return };
        let ntris = net.triangles().len();
        let mut group = c.benchmark_group(format!("eval_{name}"));
        group.sample_size(10);
        group.bench_function("build", |b| {
            b.iter(|| single.install(|| Surface::new(&net).unwrap()))
        });
        let surface = Surface::new(&net).unwrap();
        eprintln!(
            "{name}: built surface holds {:.0} bytes per control triangle ({} special-vertex configurations)",
            surface.memory_bytes() as f64 / ntris as f64,
            surface.configurations()
        );
        let mut state = 42u64;
        // (i) one point per triangle, triangles in random order.
        let mut order: Vec<u32> = (0..ntris as u32).collect();
        for i in (1..ntris).rev() {
            let j = (lcg(&mut state) * (i + 1) as f64) as usize;
            order.swap(i, j);
        }
        let one: Vec<(u32, f64, f64)> = order
            .iter()
            .map(|&t| {
                let (v, w) = point_in_triangle(&mut state);
                (t, v, w)
            })
            .collect();
        // (ii) 16 points per triangle.
        let sixteen: Vec<(u32, f64, f64)> = (0..ntris as u32)
            .flat_map(|t| (0..16).map(move |_| t))
            .map(|t| {
                let (v, w) = point_in_triangle(&mut state);
                (t, v, w)
            })
            .collect();
        for (label, queries) in [
            ("one_per_triangle_random", &one),
            ("sixteen_per_triangle", &sixteen),
        ] {
            group.throughput(Throughput::Elements(queries.len() as u64));
            group.bench_function(label, |b| {
                b.iter(|| {
                    let mut acc = 0.0;
                    for &(t, v, w) in queries.iter() {
                        acc += surface.eval(t as usize, v, w).unwrap().xvv.x;
                    }
                    acc
                })
            });
        }
        group.finish();
    }
}

/// The curvature at every vertex of the chart mesh (4 triangles per
/// control triangle) of bunny00 refined once, whose net is large enough to
/// be evaluated chunk by chunk, on the pool's threads: on the whole
/// surface, which makes every patch and keeps them, against chunk by
/// chunk.
fn vertex_curvature(c: &mut Criterion) {
    let Some(coarse) = mesh("bunny00.off") else {
        return;
    };
    let net = (loopsurf::refine::refine_uniform(&coarse, 1).unwrap()).into_net();
    let surface = Surface::new(&net).unwrap();
    let chart: SurfaceMesh = (Mesher::new(&surface).density(Density::Uniform(2)))
        .run()
        .unwrap();
    let whole = |s: &Surface| -> f64 {
        (chart.params.par_iter())
            .map(|p| s.curvature(p.tri as usize, p.v, p.w).unwrap().mean)
            .sum()
    };
    let chunks = |s: &Surface| -> f64 {
        chart
            .vertex_curvature(s)
            .unwrap()
            .iter()
            .map(|k| k.mean)
            .sum()
    };
    for (label, run) in [
        ("whole", &whole as &dyn Fn(&Surface) -> f64),
        ("chunks", &chunks),
    ] {
        let fresh = Surface::new(&net).unwrap();
        let before = fresh.memory_bytes();
        run(&fresh);
        eprintln!(
            "vertex curvature, {label}: the surface keeps {} MB after, {} MB before",
            fresh.memory_bytes() >> 20,
            before >> 20
        );
    }
    let mut group = c.benchmark_group("vertex_curvature_bunny00_refined");
    group.sample_size(10);
    group.throughput(Throughput::Elements(chart.params.len() as u64));
    group.bench_function("whole", |b| {
        b.iter_batched(
            || Surface::new(&net).unwrap(),
            |s| whole(&s),
            BatchSize::LargeInput,
        )
    });
    group.bench_function("chunks", |b| {
        b.iter_batched(
            || Surface::new(&net).unwrap(),
            |s| chunks(&s),
            BatchSize::LargeInput,
        )
    });
    group.finish();
}

criterion_group!(benches, eval, vertex_curvature);
criterion_main!(benches);
