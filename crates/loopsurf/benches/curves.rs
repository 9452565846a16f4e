//! The model's curves on CGAL fandisk tagged at 30° (34 curves, 722 hard
//! edges), one thread: what a mesh generator does on a BRep's edges.
//!
//! - `eval`: X, X′, X″ at random (curve, t);
//! - `param_at_length`: the parameter at a random arc length (a mesher
//!   placing equally spaced points);
//! - `closest_point`: the certified closest point of one curve to a point
//!   within 1e-3 × diagonal of it; `project`: the local projection of the
//!   same points from a guess 0.05 away in t.
//!
//! Throughput is in queries per second.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use loopsurf::{ControlNet, DVec3, LimitCurve, Surface};
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

const QUERIES: usize = 2_000;

fn curves(c: &mut Criterion) {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../.cache/cgal/data/meshes/fandisk.off");
    let mut net = ControlNet::read(&path)
        .unwrap_or_else(|e| panic!("{e} (run scripts/test.sh once to fetch the CGAL meshes)"));
    net.tag_by_angle(30.0).unwrap();
    let surface = Surface::new(&net).unwrap();
    let queries = Queries::new(&surface);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    bench_queries(c, &surface, &queries, &one);
}

/// The queries: random (curve, t), points within 1e-3 × the diagonal of
/// them, and each curve's length.
struct Queries {
    params: Vec<(usize, f64)>,
    points: Vec<(usize, f64, DVec3)>,
    lengths: Vec<f64>,
}

impl Queries {
    fn new(surface: &Surface) -> Queries {
        let diagonal = surface.net().bbox_diagonal();
        let model = surface.model();
        let mut rng = Lcg(5);
        let queries: Vec<(usize, f64)> = (0..QUERIES)
            .map(|_| {
                let c = (rng.next() * model.curves().len() as f64) as usize;
                (c, rng.next() * model.curves()[c].len() as f64)
            })
            .collect();
        let points: Vec<(usize, f64, DVec3)> = queries
            .iter()
            .map(|&(c, t)| {
                let x = LimitCurve::new(surface, c).unwrap().eval(t).unwrap().x;
                let d = DVec3::new(rng.next(), rng.next(), rng.next()) * 2.0 - 1.0;
                (c, t, x + 1e-3 * diagonal * d)
            })
            .collect();
        let lengths: Vec<f64> = (0..model.curves().len())
            .map(|c| {
                LimitCurve::new(surface, c)
                    .unwrap()
                    .length(0.0, model.curves()[c].len() as f64)
                    .unwrap()
            })
            .collect();
        Queries {
            params: queries,
            points,
            lengths,
        }
    }
}

/// The four benchmarks, on one thread.
fn bench_queries(c: &mut Criterion, surface: &Surface, queries: &Queries, one: &rayon::ThreadPool) {
    let model = surface.model();
    let Queries {
        params: queries,
        points,
        lengths,
    } = queries;
    let mut group = c.benchmark_group("curves_fandisk");
    group.throughput(Throughput::Elements(QUERIES as u64));
    group.sample_size(10);
    group.bench_function("eval", |b| {
        b.iter(|| {
            one.install(|| {
                for &(c, t) in queries {
                    std::hint::black_box(LimitCurve::new(surface, c).unwrap().eval(t).unwrap());
                }
            })
        })
    });
    group.bench_function("param_at_length", |b| {
        b.iter(|| {
            one.install(|| {
                for &(c, t) in queries {
                    let s = lengths[c] * t / model.curves()[c].len() as f64;
                    std::hint::black_box(
                        LimitCurve::new(surface, c)
                            .unwrap()
                            .param_at_length(s)
                            .unwrap(),
                    );
                }
            })
        })
    });
    group.bench_function("closest_point", |b| {
        b.iter(|| {
            one.install(|| {
                for &(c, _, p) in points {
                    std::hint::black_box(
                        LimitCurve::new(surface, c)
                            .unwrap()
                            .closest_point(p)
                            .unwrap(),
                    );
                }
            })
        })
    });
    group.bench_function("project", |b| {
        b.iter(|| {
            one.install(|| {
                for &(c, t, p) in points {
                    let n = model.curves()[c].len() as f64;
                    std::hint::black_box(
                        LimitCurve::new(surface, c)
                            .unwrap()
                            .project(p, (t + 0.05).min(n))
                            .unwrap(),
                    );
                }
            })
        })
    });
    group.finish();
}

criterion_group!(benches, curves);
criterion_main!(benches);
