//! Remeshing by parts, checked against the whole surface and the whole
//! run: the same bits on one thread and on two, one closed mesh with every
//! interface vertex once, every vertex the whole surface's point at its
//! parameters (the parts evaluate on sub-nets of their own), the chord
//! tolerance met between the remesher's own probes, the curves kept, and
//! the count and angles of the whole run.

mod common;

use loopsurf::{ControlNet, Remesher, Surface, SurfaceMesh};
use std::collections::{HashMap, HashSet};

/// The adapted remesh (default tolerance) of `surface` in `k` parts on a
/// pool of `threads` threads.
fn remesh(surface: &Surface, k: usize, threads: usize) -> SurfaceMesh {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| {
            Remesher::new(surface)
                .adapt_curvature(true)
                .parts(k)
                .run()
                .unwrap()
        })
}

/// Every directed edge once and its reverse once: closed, conforming and
/// consistently oriented.
fn assert_closed(mesh: &SurfaceMesh, what: &str) {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for tri in &mesh.triangles {
        for k in 0..3 {
            *directed.entry((tri[k], tri[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(n, 1, "{what}: edge {a}→{b} in {n} triangles");
        assert_eq!(directed.get(&(b, a)), Some(&1), "{what}: edge {a}–{b} open");
    }
}

#[test]
fn fandisk_in_parts_is_one_mesh_on_the_whole_surface() {
    let Some(path) = common::cgal_mesh("fandisk.off") else {
        return;
    };
    let mut net = ControlNet::read(&path).unwrap();
    net.tag_by_angle(30.0).unwrap();
    let surface = Surface::new(&net).unwrap();
    let diagonal = net.bbox_diagonal();
    let whole = remesh(&surface, 1, 2);
    let whole_quality = whole.quality();
    let whole_curves: HashSet<u32> = whole.hard_edge_curves.iter().copied().collect();
    for k in [3, 8] {
        let what = format!("fandisk in {k} parts");
        let mesh = remesh(&surface, k, 2);
        let serial = remesh(&surface, k, 1);
        assert_eq!(
            mesh.triangles, serial.triangles,
            "{what}: triangles differ on 1 thread"
        );
        assert_eq!(
            mesh.params, serial.params,
            "{what}: parameters differ on 1 thread"
        );
        let bits = |m: &SurfaceMesh| -> Vec<[u64; 3]> {
            m.points
                .iter()
                .map(|p| p.to_array().map(f64::to_bits))
                .collect()
        };
        assert_eq!(
            bits(&mesh),
            bits(&serial),
            "{what}: points differ on 1 thread"
        );

        assert_closed(&mesh, &what);
        let closest = common::closest_vertices(&mesh.points);
        assert!(
            closest > 1e-6 * diagonal,
            "{what}: two vertices {closest:e} apart"
        );
        for (i, (p, at)) in mesh.points.iter().zip(&mesh.params).enumerate() {
            let x = surface.point(at.tri as usize, at.v, at.w).unwrap();
            assert_eq!(
                x, *p,
                "{what}: vertex {i} is not the surface at its parameters"
            );
        }
        let (chord, t) =
            common::chord_error_between_probes(&surface, &mesh.points, &mesh.triangles, 6);
        assert!(
            chord <= 1e-3 * diagonal,
            "{what}: chord error {:e} of the diagonal at triangle {t}",
            chord / diagonal
        );
        let curves: HashSet<u32> = mesh.hard_edge_curves.iter().copied().collect();
        assert_eq!(curves, whole_curves, "{what}: curves with hard edges");

        let quality = mesh.quality();
        let count = mesh.triangles.len() as f64 / whole.triangles.len() as f64;
        println!(
            "{what}: {} triangles ({count:.4} of whole), mean-min {:.2}° (whole {:.2}°), min {:.2}° (whole {:.2}°), below 20° {:.3}%, chord {:.2e}, closest vertices {:.2e} of the diagonal",
            mesh.triangles.len(),
            quality.mean_min_angle,
            whole_quality.mean_min_angle,
            quality.min_angle,
            whole_quality.min_angle,
            100.0 * quality.below_20,
            chord / diagonal,
            closest / diagonal
        );
        assert!(
            (count - 1.0).abs() <= 0.02,
            "{what}: {count} times the whole's triangles"
        );
        assert!(
            quality.mean_min_angle >= whole_quality.mean_min_angle - 0.5,
            "{what}: mean-min {} against the whole's {}",
            quality.mean_min_angle,
            whole_quality.mean_min_angle
        );
    }
}

#[test]
fn zero_parts_are_refused() {
    let net = common::example("viking", Some(30.0));
    let surface = Surface::new(&net).unwrap();
    let err = Remesher::new(&surface)
        .size(0.05)
        .parts(0)
        .run()
        .unwrap_err();
    assert!(err.to_string().contains("0 parts"), "{err}");
    let n = net.triangles().len();
    let err = Remesher::new(&surface)
        .size(0.05)
        .parts(n + 1)
        .run()
        .unwrap_err();
    assert!(err.to_string().contains("parts"), "{err}");
}
