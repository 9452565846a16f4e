//! Remeshing by parts, checked against the whole surface and the whole
//! run: the same bits on one thread and on two, one closed mesh with every
//! interface vertex once, every vertex the whole surface's point at its
//! parameters (the parts evaluate on sub-nets of their own), the chord
//! tolerance met between the remesher's own probes, the curves kept, and
//! the count and angles of the whole run.

mod common;

use loopsurf::{ControlNet, Remesher, Surface, SurfaceMesh, SurfaceMode};
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

/// A CGAL demo mesh, hard edges tagged above `angle`, and its surface.
fn tagged(name: &str, angle: f64) -> Option<(ControlNet, Surface)> {
    let mut net = ControlNet::read(common::cgal_mesh(name)?).unwrap();
    net.tag_by_angle(angle).unwrap();
    let surface = Surface::new(&net).unwrap();
    Some((net, surface))
}

#[test]
fn fandisk_in_parts_is_one_mesh_on_the_whole_surface() {
    let Some((net, surface)) = tagged("fandisk.off", 30.0) else {
        return;
    };
    let diagonal = net.bbox_diagonal();
    let whole = remesh(&surface, 1, 2);
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

        assert_eq!(boundary_loops(&mesh, &what), 0, "{what}: open");
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

        println!(
            "{what}: chord {:.2e}, closest vertices {:.2e} of the diagonal",
            chord / diagonal,
            closest / diagonal
        );
        assert_as_good_as_whole(&mesh, &whole, &what);
    }
}

/// The goals of remeshing in parts against the whole run at the same
/// settings: triangle count within 2%, mean-min no more than 0.5° lower,
/// smallest angle no more than 2° lower, and no triangle below 20° where
/// the whole run has none.
fn assert_as_good_as_whole(mesh: &SurfaceMesh, whole: &SurfaceMesh, what: &str) {
    print_against_whole(mesh, whole, what);
    let (q, w) = (mesh.quality(), whole.quality());
    let count = mesh.triangles.len() as f64 / whole.triangles.len() as f64;
    assert!(
        (count - 1.0).abs() <= 0.02,
        "{what}: {count} times the whole's triangles"
    );
    assert!(
        q.mean_min_angle >= w.mean_min_angle - 0.5,
        "{what}: mean-min {} against the whole's {}",
        q.mean_min_angle,
        w.mean_min_angle
    );
    assert!(
        q.min_angle >= w.min_angle - 2.0,
        "{what}: smallest angle {} against the whole's {}",
        q.min_angle,
        w.min_angle
    );
    if w.below_20 == 0.0 {
        assert_eq!(q.below_20, 0.0, "{what}: triangles below 20°");
    }
}

/// Prints `mesh`'s triangle count and angles beside the whole run's.
fn print_against_whole(mesh: &SurfaceMesh, whole: &SurfaceMesh, what: &str) {
    let (q, w) = (mesh.quality(), whole.quality());
    println!(
        "{what}: {} triangles (whole {}), mean-min {:.2}° (whole {:.2}°), min {:.2}° (whole {:.2}°), below 20° {:.3}% (whole {:.3}%)",
        mesh.triangles.len(),
        whole.triangles.len(),
        q.mean_min_angle,
        w.mean_min_angle,
        q.min_angle,
        w.min_angle,
        100.0 * q.below_20,
        100.0 * w.below_20
    );
}

/// bunny00 (smooth, closed) at the bench's size, 0.3% of the diagonal, in
/// 8 parts against whole.
#[test]
fn bunny_in_8_parts_against_whole() {
    let Some(path) = common::cgal_mesh("bunny00.off") else {
        return;
    };
    let net = ControlNet::read(path).unwrap();
    let surface = Surface::new(&net).unwrap();
    let h = 0.003 * net.bbox_diagonal();
    let run = |k: usize| Remesher::new(&surface).size(h).parts(k).run().unwrap();
    let (whole, parts) = (run(1), run(8));
    assert_eq!(boundary_loops(&parts, "bunny00 in 8 parts"), 0);
    assert_as_good_as_whole(&parts, &whole, "bunny00 in 8 parts");
}

/// The boundary loops of a mesh whose every edge is in one or two
/// triangles, consistently oriented (0: closed); panics otherwise.
fn boundary_loops(mesh: &SurfaceMesh, what: &str) -> usize {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for tri in &mesh.triangles {
        for k in 0..3 {
            *directed.entry((tri[k], tri[(k + 1) % 3])).or_default() += 1;
        }
    }
    let mut next: HashMap<u32, u32> = HashMap::new();
    for (&(a, b), &n) in &directed {
        assert_eq!(n, 1, "{what}: edge {a}→{b} in {n} triangles");
        if !directed.contains_key(&(b, a)) {
            assert!(
                next.insert(a, b).is_none(),
                "{what}: two boundary edges leave {a}"
            );
        }
    }
    let mut loops = 0;
    let mut seen = HashSet::new();
    for &start in next.keys() {
        if seen.insert(start) {
            loops += 1;
            let mut v = next[&start];
            while seen.insert(v) {
                v = next[&v];
            }
        }
    }
    loops
}

/// The pig (open, creased at 40°, folding in one place) in 5 parts: one
/// mesh with the whole run's boundary loops (an interface not joined would
/// open more), every vertex the surface at its parameters, and the same
/// bits on one thread and on two.
#[test]
fn an_open_creased_surface_in_parts_has_the_whole_runs_boundary() {
    let Some((_, surface)) = tagged("pig.off", 40.0) else {
        return;
    };
    let whole = remesh(&surface, 1, 2);
    let parts = remesh(&surface, 5, 2);
    let serial = remesh(&surface, 5, 1);
    assert_eq!(parts.triangles, serial.triangles);
    assert_eq!(parts.points, serial.points);
    let loops = boundary_loops(&whole, "the pig whole");
    assert!(loops > 0, "the pig is open");
    assert_eq!(boundary_loops(&parts, "the pig in 5 parts"), loops);
    for (p, at) in parts.points.iter().zip(&parts.params) {
        assert_eq!(surface.point(at.tri as usize, at.v, at.w).unwrap(), *p);
    }
    print_against_whole(&parts, &whole, "pig in 5 parts");
}

/// fandisk's displaced surface (the approximating surface plus a linear
/// correction through the net's points) in 4 parts: every vertex is that
/// surface's point at its parameters, bit for bit, as in the whole run
/// (the parts' sub-nets carry the whole's displacement; without it their
/// vertices lay on the approximating surface, 3.5e-3 of the diagonal
/// away), and the count is the whole run's within 2%.
#[test]
fn a_displaced_surface_in_parts_keeps_its_displacement() {
    let Some(path) = common::cgal_mesh("fandisk.off") else {
        return;
    };
    let mut net = ControlNet::read(path).unwrap();
    net.tag_by_angle(30.0).unwrap();
    let surface = Surface::with_mode(&net, SurfaceMode::Displacement).unwrap();
    let approximating = Surface::new(&net).unwrap();
    let diagonal = net.bbox_diagonal();
    let run = |k: usize| {
        (Remesher::new(&surface).size(0.01 * diagonal).parts(k))
            .run()
            .unwrap()
    };
    let (whole, parts) = (run(1), run(4));
    let mut apart: f64 = 0.0;
    for (i, (p, at)) in parts.points.iter().zip(&parts.params).enumerate() {
        let (tri, v, w) = (at.tri as usize, at.v, at.w);
        assert_eq!(
            surface.point(tri, v, w).unwrap(),
            *p,
            "vertex {i} is not the displaced surface at its parameters"
        );
        apart = apart.max((approximating.point(tri, v, w).unwrap() - *p).length());
    }
    assert!(
        apart > 1e-4 * diagonal,
        "the displaced and approximating surfaces are {apart:e} apart: nothing to tell"
    );
    assert_eq!(boundary_loops(&parts, "displaced fandisk in 4 parts"), 0);
    let count = parts.triangles.len() as f64 / whole.triangles.len() as f64;
    assert!(
        (count - 1.0).abs() <= 0.02,
        "{count} times the whole's triangles"
    );
}

/// anchor.off (adapted, as `loopsurf mesh` does by default), whose
/// surface folds and crosses itself around its fans, in 3 and 4 parts: one closed manifold mesh, every directed edge once, every
/// vertex the surface at its parameters. Where the surface folds, both
/// sides of an interface see one corner as convex; each piece used to cut
/// it with the same new edge, and the band pass refused the joined mesh
/// ("not a manifold").
#[test]
fn a_folding_surface_in_parts_joins_into_one_manifold() {
    let Some((_, surface)) = tagged("anchor.off", 30.0) else {
        return;
    };
    for k in [3, 4] {
        let what = format!("anchor in {k} parts");
        let mesh = remesh(&surface, k, 2);
        assert_eq!(boundary_loops(&mesh, &what), 0, "{what}: open");
        for (p, at) in mesh.points.iter().zip(&mesh.params) {
            assert_eq!(surface.point(at.tri as usize, at.v, at.w).unwrap(), *p);
        }
    }
}

/// bull.off (read with every repair, 40°, its folded concave corners
/// seamed, adapted) in 4 parts: beside its folds a part cut a corner
/// between two pinned vertices that triangles no part remeshes already
/// joined, and the band pass refused the joined mesh ("not a manifold":
/// that edge four times). One closed manifold mesh now, every vertex the
/// surface at its parameters.
#[test]
fn kept_triangles_hold_their_edges_against_every_part() {
    let Some(path) = common::cgal_mesh("bull.off") else {
        return;
    };
    let mut net =
        ControlNet::read_with(path, &loopsurf::repair::ReadOptions::repair_all()).unwrap();
    net.tag_by_angle(40.0).unwrap();
    let folded = loopsurf::folds::seam_folded_concave_corners(&mut net).unwrap();
    assert!(folded.iter().any(|s| s.seam.is_some()), "{folded:?}");
    let surface = Surface::new(&net).unwrap();
    let what = "bull, seamed, in 4 parts";
    let mesh = remesh(&surface, 4, 2);
    assert_eq!(boundary_loops(&mesh, what), 0, "{what}: open");
    for (p, at) in mesh.points.iter().zip(&mesh.params) {
        assert_eq!(surface.point(at.tri as usize, at.v, at.w).unwrap(), *p);
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

/// The suggested number of parts is what the mesh it leads to holds: one
/// part per `TRIANGLES_PER_PART` triangles of the finished mesh, within
/// the estimate's slack (the sizes' areas before grading, on the control
/// net's area), rounded down to a power of two; whole below two parts'
/// worth; the cap past it.
#[test]
fn suggested_parts_follow_the_size_of_the_mesh() {
    use loopsurf::remesh::{MAX_SUGGESTED_PARTS, TRIANGLES_PER_PART};
    let e = loopsurf::examples::by_name("viking").unwrap();
    let net = ControlNet::from_arrays(e.points, &e.tris).unwrap();
    let surface = Surface::new(&net).unwrap();
    let diagonal = net.bbox_diagonal();
    for relative in [0.01, 0.005, 0.003] {
        let remesher = Remesher::new(&surface).size(relative * diagonal);
        let k = remesher.suggested_parts().unwrap();
        let made = remesher.parts(k).run().unwrap().triangles.len() as f64;
        let per_part = made / TRIANGLES_PER_PART;
        if per_part < 1.5 {
            assert_eq!(k, 1, "h = {relative}: {made} triangles, {k} parts");
        } else {
            // A power of two, the largest not past the count within the
            // slack: twice as many would be.
            assert!(
                k.is_power_of_two()
                    && k as f64 <= 1.25 * per_part + 1.0
                    && 2.0 * k as f64 > 0.75 * per_part - 1.0,
                "h = {relative}: {made} triangles, {k} parts"
            );
        }
    }
    let tiny = Remesher::new(&surface).size(1e-3 * diagonal);
    assert_eq!(tiny.suggested_parts().unwrap(), MAX_SUGGESTED_PARTS);
}
