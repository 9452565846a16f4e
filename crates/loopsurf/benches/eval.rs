//! Exact evaluation throughput (all 18 numbers), single thread, on CGAL's
//! pig and bunny: (i) one point per triangle in random triangle order,
//! (ii) 16 points per triangle, triangle by triangle. Also the build time.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use loopsurf::{ControlNet, Surface};
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

criterion_group!(benches, eval);
criterion_main!(benches);
