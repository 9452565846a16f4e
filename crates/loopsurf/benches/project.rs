//! Local projection throughput, one thread, on CGAL pig and bunny00: what a
//! mesh generator's smoother does. Each query is a surface point moved 5e-4
//! of the diagonal along the surface and up to 1e-3 off it, projected from
//! the parameters of the point it was moved from (a neighbour's guess).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
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

const QUERIES: usize = 20_000;

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
        let queries: Vec<(DVec3, usize, f64, f64)> = (0..QUERIES)
            .map(|_| {
                let t = (rng.next() * net.triangles().len() as f64) as usize;
                let (v, w) = (0.05 + 0.4 * rng.next(), 0.05 + 0.4 * rng.next());
                let e = surface.eval(t, v, w).unwrap();
                let n = e.xv.cross(e.xw).normalize();
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
        group.bench_function("from_a_neighbour", |b| {
            b.iter(|| {
                queries
                    .iter()
                    .map(|&(p, t, v, w)| surface.project(p, t, v, w).unwrap().distance)
                    .sum::<f64>()
            })
        });
        group.finish();
    }
}

criterion_group!(benches, project);
criterion_main!(benches);
