//! The build at scale (docs/benchmarks.md): reads a control net, builds its surface,
//! evaluates once in every triangle (which makes every patch), then answers
//! a first snap (which builds the snap index), and prints the times and
//! the bytes held per control triangle. `scripts/scale.sh` runs
//! it on bunny00 refined three times (4.8M triangles), one thread.
//!
//!     cargo run --release -p loopsurf --example build_scale -- NET

use loopsurf::snap;
use loopsurf::{ControlNet, DVec3, Surface};
use std::time::Instant;

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: build_scale NET");
        std::process::exit(2);
    };
    let t = Instant::now();
    let net = match ControlNet::read(&path) {
        Ok(net) => net,
        Err(e) => {
            eprintln!("build_scale: {e}");
            std::process::exit(2);
        }
    };
    let read = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let surface = Surface::new(&net).expect("a valid net builds");
    let build = t.elapsed().as_secs_f64();
    let n = net.triangles().len();
    let built = surface.memory_bytes() / n;
    // Patches are made on first use: a first pass over every triangle
    // pays for them (what an eager build would have done).
    let t = Instant::now();
    let mut sum = DVec3::ZERO;
    for tri in 0..n {
        sum += surface.eval(tri, 0.25, 0.25).expect("inside").x;
    }
    let first_pass = t.elapsed().as_secs_f64();
    let made = surface.memory_bytes() / n;
    let t = Instant::now();
    let centre = net.points().iter().sum::<DVec3>() / net.points().len() as f64;
    snap::closest_point(&surface, centre).expect("a finite point snaps");
    let snap = t.elapsed().as_secs_f64();
    println!(
        "{path}: {n} triangles; read {read:.2} s, build {build:.2} s ({built} B per triangle), \
         first evaluation of every triangle {first_pass:.2} s ({made} B per triangle, checksum {:.3e}), \
         first snap {snap:.2} s ({} B per triangle with the snap index)",
        sum.length(),
        surface.memory_bytes() / n
    );
}
