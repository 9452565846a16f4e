//! Local projection throughput, one thread, on CGAL pig and bunny00: what a
//! mesh generator's smoother does. Every query lies within 1e-3 of the
//! bounding-box diagonal of the surface (a surface point moved along its
//! normal by a uniform amount in ±1e-3 × diagonal), guessed from a
//! neighbouring point:
//!
//! - `along_walks`: the surface points follow walks of 1e-3 × diagonal
//!   steps (50 walks of 400 steps from random starts, each step the global
//!   closest point of a step along the surface's tangent), and each query's
//!   guess is the answer of the query before it — a smoother sweeping a
//!   mesh in order;
//! - `from_a_neighbour`: the surface points are random (triangle and
//!   parameters), each moved 5e-4 × diagonal along the surface, and the
//!   guess is the parameters of the unmoved point. Consecutive queries are
//!   far apart, so this also measures the memory traffic of random access.
//!
//! Throughput is in projections per second.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use loopsurf::snap;
use loopsurf::{ControlNet, DVec3, Snap, Surface};
use std::path::PathBuf;

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

const QUERIES: usize = 20_000;
const WALKS: usize = 50;

/// A random unit vector.
fn direction(rng: &mut Lcg) -> DVec3 {
    loop {
        let d = DVec3::new(rng.next(), rng.next(), rng.next()) * 2.0 - 1.0;
        if (0.01..=1.0).contains(&d.length_squared()) {
            return d.normalize();
        }
    }
}

/// The unit normal at a snap's point.
fn normal(surface: &Surface, s: &Snap) -> DVec3 {
    surface.normal(s.tri, s.v, s.w).unwrap_or(DVec3::Z)
}

/// Walks of `QUERIES / WALKS` points with steps of 1e-3 × diagonal, each
/// point moved off the surface along its normal: the query points, and for
/// each walk the parameters of its first surface point (the first guess).
fn walks(surface: &Surface, diagonal: f64, rng: &mut Lcg) -> Vec<(Snap, Vec<DVec3>)> {
    let triangles = surface.net().triangles().len();
    (0..WALKS)
        .map(|_| {
            let t = (rng.next() * triangles as f64) as usize;
            let (v, w) = (0.1 + 0.3 * rng.next(), 0.1 + 0.3 * rng.next());
            let start = snap::closest_point(surface, surface.point(t, v, w).unwrap()).unwrap();
            let mut here = start;
            let mut heading = direction(rng);
            let points = (0..QUERIES / WALKS)
                .map(|_| {
                    let n = normal(surface, &here);
                    let query = here.point + (rng.next() - 0.5) * 2e-3 * diagonal * n;
                    // On along the tangent, turning a little each step.
                    heading = (heading + 0.3 * direction(rng))
                        .reject_from(n)
                        .normalize_or(n.any_orthonormal_vector());
                    here = snap::closest_point(surface, here.point + 1e-3 * diagonal * heading)
                        .unwrap();
                    query
                })
                .collect();
            (start, points)
        })
        .collect()
}

fn project(c: &mut Criterion) {
    for name in ["pig", "bunny00"] {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join(format!("../../.cache/cgal/data/meshes/{name}.off"));
        let net = match ControlNet::read(&path) {
            Ok(net) => net,
            Err(err) => {
                eprintln!(
                    "project bench skipped: {err} (scripts/test.sh extracts the CGAL meshes)"
                );
                continue;
            }
        };
        let surface = Surface::new(&net).unwrap();
        let diagonal = net.bbox_diagonal();
        let mut rng = Lcg(3);
        let walks = walks(&surface, diagonal, &mut rng);
        let neighbours: Vec<(DVec3, usize, f64, f64)> = (0..QUERIES)
            .map(|_| {
                let t = (rng.next() * net.triangles().len() as f64) as usize;
                let (v, w) = (0.05 + 0.4 * rng.next(), 0.05 + 0.4 * rng.next());
                let e = surface.eval(t, v, w).unwrap();
                let n = e.normal().expect("a tangent plane inside the triangle");
                let along = e.xv * (rng.next() - 0.5) + e.xw * (rng.next() - 0.5);
                let p = e.x
                    + along * (5e-4 * diagonal / along.length())
                    + (rng.next() - 0.5) * 2e-3 * diagonal * n;
                (p, t, v, w)
            })
            .collect();
        let mut group = c.benchmark_group(format!("project_{name}"));
        group.sample_size(10);
        group.throughput(Throughput::Elements(QUERIES as u64));
        group.bench_function("along_walks", |b| {
            b.iter(|| {
                let mut sum = 0.0;
                for (start, points) in &walks {
                    let mut guess = *start;
                    for &p in points {
                        guess = snap::project(&surface, p, guess.tri, guess.v, guess.w).unwrap();
                        sum += guess.distance;
                    }
                }
                sum
            })
        });
        group.bench_function("from_a_neighbour", |b| {
            b.iter(|| {
                neighbours
                    .iter()
                    .map(|&(p, t, v, w)| snap::project(&surface, p, t, v, w).unwrap().distance)
                    .sum::<f64>()
            })
        });
        group.finish();
    }
}

criterion_group!(benches, project);
criterion_main!(benches);
