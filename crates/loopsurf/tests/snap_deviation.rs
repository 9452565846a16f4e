//! `SurfaceMesh::snap_deviation` certifies only the probes whose local
//! bound could hold the maximum; here every probe is snapped (the global
//! closest point, no hint) and the largest distance must be the same.

mod common;

use loopsurf::{snap, DVec3, Remesher, Surface, SurfaceMesh};
use rayon::prelude::*;

/// The largest certified distance to the surface over every triangle's
/// centroid and every edge's midpoint, each snapped.
fn every_probe_snapped(surface: &Surface, mesh: &SurfaceMesh) -> f64 {
    let mut probes: Vec<DVec3> = Vec::new();
    let mut edges = std::collections::HashSet::new();
    for tri in &mesh.triangles {
        let [a, b, c] = tri.map(|i| mesh.points[i as usize]);
        probes.push((a + b + c) / 3.0);
        for k in 0..3 {
            let (i, j) = (tri[k], tri[(k + 1) % 3]);
            if edges.insert((i.min(j), i.max(j))) {
                probes.push(0.5 * (mesh.points[i as usize] + mesh.points[j as usize]));
            }
        }
    }
    probes
        .par_iter()
        .map(|&x| snap::closest_point(surface, x).unwrap().distance)
        .reduce(|| 0.0, f64::max)
}

#[test]
fn the_largest_bound_first_search_finds_the_certified_maximum() {
    for (name, angle, h) in [
        ("viking", 30.0, 0.04),
        ("torus", 30.0, 0.03),
        ("open-disk", 30.0, 0.05),
    ] {
        let net = common::example(name, Some(angle));
        let surface = Surface::new(&net).unwrap();
        let diagonal = net.bbox_diagonal();
        for mesh in [
            Remesher::new(&surface).size(h * diagonal).run().unwrap(),
            loopsurf::Mesher::new(&surface)
                .density(loopsurf::Density::Uniform(2))
                .run()
                .unwrap(),
        ] {
            let fast = mesh.snap_deviation(&surface).unwrap();
            let slow = every_probe_snapped(&surface, &mesh);
            println!(
                "{name}: {:e} against {:e} of the diagonal",
                fast / diagonal,
                slow / diagonal
            );
            assert!(slow > 0.0);
            assert!(
                (fast - slow).abs() <= 1e-9 * diagonal,
                "{name}: {fast:e} against every probe snapped {slow:e}"
            );
        }
    }
}
