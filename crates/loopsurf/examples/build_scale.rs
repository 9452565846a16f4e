//! The build at scale (issue 20): reads a control net, builds its surface,
//! then answers a first snap (which builds the snap index), and prints the
//! times and the bytes held per control triangle. `scripts/scale.sh` runs
//! it on bunny00 refined three times (4.8M triangles), one thread.
//!
//!     cargo run --release -p loopsurf --example build_scale -- NET

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
    let t = Instant::now();
    let centre = net.points().iter().sum::<DVec3>() / net.points().len() as f64;
    surface.closest_point(centre).expect("a finite point snaps");
    let snap = t.elapsed().as_secs_f64();
    println!(
        "{path}: {n} triangles; read {read:.2} s, build {build:.2} s ({built} B per triangle), first snap {snap:.2} s ({} B per triangle with the snap index)",
        surface.memory_bytes() / n
    );
}
