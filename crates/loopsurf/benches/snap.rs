//! Snap throughput, single thread, on CGAL pig and bunny00:
//! (a) random points in the bounding box, (b) points within 1% of the
//! diagonal from the surface, (c) `snap_near` along a walk of nearby points,
//! each hinted with its predecessor's answer. Every answer is certified to
//! 1e-12 of the diagonal; (b) is also run at 1e-6, to show what the tight
//! certificate costs. Index build time is separate.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use loopsurf::snap;
use loopsurf::{ControlNet, DVec3, Surface};
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

const QUERIES: usize = 2000;

fn snap(c: &mut Criterion) {
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for name in ["pig", "bunny00"] {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join(format!("../../.cache/cgal/data/meshes/{name}.off"));
        let net = match ControlNet::read(&path) {
            Ok(net) => net,
            Err(err) => {
                eprintln!("snap bench skipped: {err} (scripts/test.sh extracts the CGAL meshes)");
                continue;
            }
        };
        let surface = Surface::new(&net).unwrap();
        let start = std::time::Instant::now();
        snap::closest_point(&surface, DVec3::ZERO).unwrap(); // builds the index
        eprintln!(
            "{name}: snap index built in {:.1} ms",
            start.elapsed().as_secs_f64() * 1e3
        );
        let queries = Queries::new(&net, &surface);
        bench_queries(c, name, &surface, &queries, &single);
    }
}

/// The query points: (a) in the bounding box, (b) near the surface, (c)
/// a walk of small steps.
struct Queries {
    in_box: Vec<DVec3>,
    near: Vec<DVec3>,
    walk: Vec<DVec3>,
}

impl Queries {
    fn new(net: &ControlNet, surface: &Surface) -> Queries {
        let lo = net.points().iter().fold(DVec3::INFINITY, |a, &b| a.min(b));
        let hi = net
            .points()
            .iter()
            .fold(DVec3::NEG_INFINITY, |a, &b| a.max(b));
        let diagonal = (hi - lo).length();
        let mut rng = Lcg(3);
        let in_box: Vec<DVec3> = (0..QUERIES)
            .map(|_| lo + (hi - lo) * DVec3::new(rng.next(), rng.next(), rng.next()))
            .collect();
        let near: Vec<DVec3> = (0..QUERIES)
            .map(|_| {
                let t = (rng.next() * net.triangles().len() as f64) as usize;
                let e = surface.eval(t, rng.next() * 0.5, rng.next() * 0.5).unwrap();
                let n = e.normal().unwrap_or_default();
                e.x + (rng.next() - 0.5) * 0.02 * diagonal * n
            })
            .collect();
        // A walk: each point a small step (0.1% of the diagonal) from the last.
        let mut walk = vec![near[0]];
        for _ in 1..QUERIES {
            let step = DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5);
            walk.push(*walk.last().unwrap() + 0.002 * diagonal * step);
        }
        Queries { in_box, near, walk }
    }
}

/// The four benchmarks of one mesh, on one thread.
fn bench_queries(
    c: &mut Criterion,
    name: &str,
    surface: &Surface,
    queries: &Queries,
    single: &rayon::ThreadPool,
) {
    let Queries { in_box, near, walk } = queries;
    let mut group = c.benchmark_group(format!("snap_{name}"));
    group.sample_size(10);
    group.throughput(Throughput::Elements(QUERIES as u64));
    group.bench_function("a_random_in_box", |b| {
        b.iter(|| {
            single.install(|| {
                in_box
                    .iter()
                    .map(|&p| snap::closest_point(surface, p).unwrap().distance)
                    .sum::<f64>()
            })
        })
    });
    group.bench_function("b_within_1pct", |b| {
        b.iter(|| {
            single.install(|| {
                near.iter()
                    .map(|&p| snap::closest_point(surface, p).unwrap().distance)
                    .sum::<f64>()
            })
        })
    });
    // What the tight certificate costs over a loose one.
    group.bench_function("b_within_1pct_tolerance_1e-6", |b| {
        b.iter(|| {
            single.install(|| {
                near.iter()
                    .map(|&p| {
                        snap::closest_point_within(surface, p, 1e-6)
                            .unwrap()
                            .distance
                    })
                    .sum::<f64>()
            })
        })
    });
    group.bench_function("c_snap_near_walk", |b| {
        b.iter(|| {
            single.install(|| {
                let mut hint = snap::closest_point(surface, walk[0]).unwrap();
                for &p in &walk[1..] {
                    hint = snap::snap_near(surface, p, hint.tri, hint.v, hint.w).unwrap();
                }
                hint.distance
            })
        })
    });
    group.finish();
}

criterion_group!(benches, snap);
criterion_main!(benches);
