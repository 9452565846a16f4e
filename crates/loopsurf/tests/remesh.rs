//! The quality remesher on its three benchmark cases (docs/remesher.md): the quality
//! goals measured against CGAL's figures, and the invariants checked with
//! references that share no code with it — the certified snap for the
//! surface and the faces, the certified curve projection for the creases.

mod common;
#[path = "support/sectors.rs"]
mod sectors;

use common::{cgal_mesh, chord_error_between_probes, example};
use loopsurf::snap;
use loopsurf::{ControlNet, DVec3, LimitCurve, Remesher, Surface, SurfaceMesh};
use std::collections::{HashMap, HashSet};

fn cgal(name: &str, angle: f64) -> Option<ControlNet> {
    let mut net = ControlNet::read(cgal_mesh(name)?).unwrap();
    net.tag_by_angle(angle).unwrap();
    Some(net)
}

/// The cases: net, relative size, and CGAL 5.5's isotropic remeshing at
/// that size (3 iterations, sharp edges constrained): triangles and
/// smallest angle, measured on 2026-11-28 (anchor on 2026-12-04, by
/// bench_peers). Anchor's concave corners whose surface folds are seamed
/// (`folds::seam_folded_concave_corners`); unseamed, its flaps cross the
/// mesh (3.3° and 30 crossing pairs at 1%). CGAL meshes the facets,
/// which have no flap.
fn cases() -> Vec<(&'static str, ControlNet, f64, usize, f64)> {
    let mut out = vec![("viking", example("viking", Some(30.0)), 0.01, 23_268, 26.1)];
    if let Some(net) = cgal("fandisk.off", 30.0) {
        out.push(("fandisk", net, 0.005, 110_548, 17.9));
    }
    if let Some(net) = cgal("pig.off", 40.0) {
        out.push(("pig", net, 0.005, 88_822, 4.3));
    }
    if let Some(mut net) = cgal("anchor.off", 30.0) {
        loopsurf::folds::seam_folded_concave_corners(&mut net).unwrap();
        out.push(("anchor, seamed", net, 0.01, 35_610, 10.6));
    }
    out
}

/// Undirected edge → its triangles' count, checking that no directed edge
/// repeats (a consistent orientation).
fn edge_use(mesh: &SurfaceMesh) -> HashMap<(u32, u32), u32> {
    let mut directed = HashMap::new();
    let mut undirected = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            assert_ne!(a, b, "triangle {t} repeats a vertex");
            assert!(
                directed.insert((a, b), t).is_none(),
                "directed edge {a}->{b} twice"
            );
            *undirected.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    undirected
}

/// The control triangles next to a fold of the net: an edge whose two
/// triangles' normals are opposed (turning by more than 150°), as at
/// pig's near-degenerate triangle 534, which folds back between its
/// neighbours (149° and 178.8°). Every triangle with a corner at a fold
/// edge's end is returned. Tagged hard, such edges make a crease that
/// ends inside a face with a fin of the surface along it, on which no
/// triangle has good angles.
fn next_to_folds(net: &ControlNet) -> HashSet<usize> {
    let (p, t) = (net.points(), net.triangles());
    let normal = |k: usize| {
        let [a, b, c] = t[k].map(|i| p[i as usize]);
        (b - a).cross(c - a).normalize()
    };
    let mut sides: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (k, tri) in t.iter().enumerate() {
        for j in 0..3 {
            let (a, b) = (tri[j], tri[(j + 1) % 3]);
            sides.entry((a.min(b), a.max(b))).or_default().push(k);
        }
    }
    let limit = -(30f64.to_radians().cos());
    let ends: HashSet<u32> = sides
        .iter()
        .filter(|(_, ts)| ts.len() == 2 && normal(ts[0]).dot(normal(ts[1])) < limit)
        .flat_map(|(&(a, b), _)| [a, b])
        .collect();
    (0..t.len())
        .filter(|&k| t[k].iter().any(|v| ends.contains(v)))
        .collect()
}

/// `mesh` without the triangles that have a vertex in one of the control
/// triangles `skip`.
fn without(mesh: &SurfaceMesh, skip: &HashSet<usize>) -> SurfaceMesh {
    let keep: Vec<usize> = (0..mesh.triangles.len())
        .filter(|&t| {
            mesh.triangles[t]
                .iter()
                .all(|&v| !skip.contains(&(mesh.params[v as usize].tri as usize)))
        })
        .collect();
    SurfaceMesh {
        triangles: keep.iter().map(|&t| mesh.triangles[t]).collect(),
        faces: keep.iter().map(|&t| mesh.faces[t]).collect(),
        ..mesh.clone()
    }
}

/// Every vertex is the surface at its parameters; closed where the net
/// is; every hard output edge on its curve (certified curve projection);
/// every corner an output vertex; the hard edges of a curve one chain.
fn check_invariants(name: &str, surface: &Surface, mesh: &SurfaceMesh) {
    let diagonal = surface.net().bbox_diagonal();
    for (i, (p, x)) in mesh.params.iter().zip(&mesh.points).enumerate() {
        let at = surface.point(p.tri as usize, p.v, p.w).unwrap();
        assert!(
            at.distance(*x) <= 1e-12 * diagonal,
            "{name}: vertex {i} off its parameters"
        );
    }
    let open = edge_use(mesh).values().filter(|&&n| n != 2).count();
    let net_open = surface.net().topology().edges().len()
        - (0..surface.net().topology().num_edges())
            .filter(|&e| !surface.net().topology().is_boundary_edge(e))
            .count();
    assert_eq!(
        open == 0,
        net_open == 0,
        "{name}: watertight exactly where the net is"
    );
    let model = surface.model();
    // The labels any mesh gets from its vertices' parameters alone (what
    // `ls_mesh_hard_edges` returns) are the remesher's own.
    let labels = loopsurf::mesh::curve_edges(surface, &mesh.params, &mesh.triangles).unwrap();
    let key = |p: [u32; 2]| (p[0].min(p[1]), p[0].max(p[1]));
    let mut ours: Vec<(u32, u32, u32)> = (mesh.hard_edges.iter().zip(&mesh.hard_edge_curves))
        .map(|(&p, &c)| (c, key(p).0, key(p).1))
        .collect();
    let mut theirs: Vec<(u32, u32, u32)> = (labels.pairs.iter().zip(&labels.curves))
        .map(|(&p, &c)| (c, key(p).0, key(p).1))
        .collect();
    ours.sort_unstable();
    theirs.sort_unstable();
    assert_eq!(ours, theirs, "{name}: hard edges from the parameters alone");
    let mut degree: HashMap<(u32, u32), u32> = HashMap::new();
    for (pair, &curve) in mesh.hard_edges.iter().zip(&mesh.hard_edge_curves) {
        for &v in pair {
            let x = mesh.points[v as usize];
            let d = LimitCurve::new(surface, curve as usize)
                .unwrap()
                .closest_point(x)
                .unwrap()
                .distance;
            assert!(
                d <= 1e-9 * diagonal,
                "{name}: vertex {v} is {d:e} off curve {curve}"
            );
            *degree.entry((curve, v)).or_insert(0) += 1;
        }
    }
    for (c, curve) in model.curves().iter().enumerate() {
        let ends = degree
            .iter()
            .filter(|(&(k, _), &n)| k == c as u32 && n == 1)
            .count();
        assert!(
            degree.iter().all(|(&(k, _), &n)| k != c as u32 || n <= 2),
            "{name}: curve {c} branches"
        );
        // A loop, or a curve from a corner back to itself, has no free end.
        let looped = curve.chain.first() == curve.chain.last();
        let expected = if looped { 0 } else { 2 };
        assert_eq!(ends, expected, "{name}: curve {c} is not one chain");
    }
    let net = surface.net();
    for &corner in model.corners() {
        let tri = net.topology().fan(corner as usize)[0] as usize;
        let k = net.triangles()[tri]
            .iter()
            .position(|&c| c == corner)
            .unwrap();
        let (v, w) = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)][k];
        let x = surface.point(tri, v, w).unwrap();
        assert!(
            mesh.points
                .iter()
                .any(|p| p.distance(x) <= 1e-12 * diagonal),
            "{name}: corner {corner} is not an output vertex"
        );
    }
}

/// Every `step`-th triangle faces the way the surface does at its
/// centroid's closest point, and carries the face of the control triangle
/// that point lies in (certified snap).
///
/// Where the control net folds back onto itself (pig's triangles 534 and
/// 535 meet at 178.8°), or the surface does (anchor's flat fans), two
/// sheets of the surface pass within 1e-6 of each other, and the closest
/// point may lie on the sheet the triangle does not approximate. There
/// the triangle must face as its own sheet does: at the local minimum of
/// the distance found from its vertices' parameters, nearer than 1% of
/// its longest side, with the two sheets' normals opposed. Such triangles
/// are counted, and at most `own_sheet` of them allowed (the count each
/// case had when measured: an excuse that cannot grow unnoticed).
fn check_orientation_and_faces(
    name: &str,
    surface: &Surface,
    mesh: &SurfaceMesh,
    step: usize,
    own_sheet: usize,
) {
    let (against, at_folds) = facing_against(name, surface, mesh, step);
    assert!(
        against.is_empty(),
        "{name}: triangles {against:?} face against the surface"
    );
    assert!(
        at_folds <= own_sheet,
        "{name}: {at_folds} triangles face their own sheet (at most {own_sheet})"
    );
}

/// The triangles of [`check_orientation_and_faces`] that face against the
/// surface (checking the faces as it does), and how many face their own
/// sheet where the surface folds back.
fn facing_against(
    name: &str,
    surface: &Surface,
    mesh: &SurfaceMesh,
    step: usize,
) -> (Vec<usize>, usize) {
    let faces = surface.model().face_of_triangle();
    let mut against = Vec::new();
    let mut wrong_face = 0;
    let mut at_folds = 0;
    for t in (0..mesh.triangles.len()).step_by(step) {
        let [a, b, c] = mesh.triangles[t].map(|i| mesh.points[i as usize]);
        let n = (b - a).cross(c - a).normalize();
        let centroid = (a + b + c) / 3.0;
        let snap = snap::closest_point(surface, centroid).unwrap();
        let normal = surface.normal(snap.tri, snap.v, snap.w).unwrap();
        if n.dot(normal) <= 0.0 {
            let longest = a.distance(b).max(b.distance(c)).max(c.distance(a));
            let own = mesh.triangles[t].iter().any(|&i| {
                let at = mesh.params[i as usize];
                snap::project(surface, centroid, at.tri as usize, at.v, at.w).is_ok_and(|p| {
                    let m = surface.normal(p.tri, p.v, p.w).unwrap();
                    p.distance <= 0.01 * longest && m.dot(n) > 0.0 && m.dot(normal) < -0.9
                })
            });
            if own {
                at_folds += 1;
            } else {
                against.push(t);
            }
        }
        if faces[snap.tri] != mesh.faces[t] {
            wrong_face += 1;
        }
    }
    println!("{name}: {at_folds} triangles face their own sheet where the surface folds back");
    // A centroid within round-off of a crease may snap onto its other side.
    assert!(
        wrong_face * 1000 <= mesh.triangles.len() / step,
        "{name}: {wrong_face} triangles carry the wrong face"
    );
    (against, at_folds)
}

#[test]
fn quality_beats_cgal_at_the_same_size() {
    for (name, net, relative, cgal_count, cgal_min) in cases() {
        let surface = Surface::new(&net).unwrap();
        let h = relative * net.bbox_diagonal();
        let mesh = Remesher::new(&surface).size(h).run().unwrap();
        let q = mesh.quality();
        let count = mesh.triangles.len() as f64 / cgal_count as f64;
        println!(
            "{name}: {} triangles ({count:.3} of CGAL's), min {:.2}°, mean-min {:.2}°, below 20° {:.4}%, edges {:.3}–{:.3} h",
            mesh.triangles.len(),
            q.min_angle,
            q.mean_min_angle,
            100.0 * q.below_20,
            q.edge_lengths[1] / h,
            q.edge_lengths[3] / h
        );
        assert!(
            q.min_angle >= cgal_min,
            "{name}: min angle {} below CGAL's {cgal_min}",
            q.min_angle
        );
        // Below 20° only where the input forces it, decided here from the
        // control net's sectors: on pig 7 of its 23 lie in a sector
        // narrower than 20° at a corner; the other 16 (15 away from any
        // corner, one in a sector of 93°), all of which the remesher's own
        // `below_20_at_features` counts as forced, are pinned, so that
        // none is added.
        let small = sectors::small_angles(&surface, &mesh, 20.0);
        let below = (q.below_20 * mesh.triangles.len() as f64).round() as usize;
        assert_eq!(small.len(), below, "{name}: triangles below 20°");
        let unforced: Vec<_> = small.iter().filter(|s| !s.forced(20.0)).collect();
        println!(
            "{name}: {below} below 20°, {} not forced by the input's sectors",
            unforced.len()
        );
        let pinned = if name == "pig" { 16 } else { 0 };
        assert!(
            unforced.len() <= pinned,
            "{name}: {} triangles below 20° that the input does not force (at most {pinned}): {}",
            unforced.len(),
            sectors::list(&unforced)
        );
        // The goal.
        assert!(
            q.mean_min_angle >= 50.0,
            "{name}: mean-min {}",
            q.mean_min_angle
        );
        assert!(
            (0.85..=1.15).contains(&count),
            "{name}: {count} of CGAL's triangle count"
        );
        // The median within [0.8 h, 1.33 h], and 95% of the edges below
        // 1.33 h (shorter ones are forced where crease curves come close).
        let median = q.edge_lengths[2] / h;
        assert!(
            (0.8..=1.33).contains(&median),
            "{name}: median edge {median} h"
        );
        assert!(q.edge_lengths[3] <= 1.34 * h, "{name}: edge spread");
        check_invariants(name, &surface, &mesh);
        // Pig's 3 lie where its net folds back (triangles 534 and 535).
        let own_sheet = if name == "pig" { 3 } else { 0 };
        check_orientation_and_faces(name, &surface, &mesh, 1, own_sheet);
    }
}

/// Points of every output triangle at which the chord error is measured
/// between the remesher's own probes.
const PROBES_BETWEEN: usize = 4;

/// `net` adapted at the default tolerance 1e-3, with its surface: the
/// chord error within the tolerance, as bounded by the remesher and as
/// measured by certified snap (never above the bound) at its probes, and
/// between them (at points it never probes, [`chord_error_between_probes`]).
fn adapted(name: &str, net: &ControlNet) -> (Surface, SurfaceMesh) {
    let surface = Surface::new(net).unwrap();
    let tol = 1e-3;
    let mesh = Remesher::new(&surface)
        .adapt_curvature(true)
        .tolerance(tol)
        .run()
        .unwrap();
    let diagonal = net.bbox_diagonal();
    let bound = mesh.deviation.unwrap() / diagonal;
    let snapped = mesh.snap_deviation(&surface).unwrap() / diagonal;
    let (between, worst) =
        chord_error_between_probes(&surface, &mesh.points, &mesh.triangles, PROBES_BETWEEN);
    let between = between / diagonal;
    let q = mesh.quality();
    println!(
        "{name}: {} triangles, deviation {bound:.3e} (bound) {snapped:.3e} (snap) {between:.3e} (between probes, triangle {worst}), min {:.2}°, mean-min {:.2}°, below 20° {:.3}%",
        mesh.triangles.len(),
        q.min_angle,
        q.mean_min_angle,
        100.0 * q.below_20
    );
    assert!(
        bound <= tol && snapped <= tol,
        "{name}: {bound:e} / {snapped:e} over {tol}"
    );
    assert!(
        snapped <= bound * (1.0 + 1e-9),
        "{name}: the bound is below the snap"
    );
    assert!(
        between <= tol,
        "{name}: {between:e} over {tol} between the probes, at triangle {worst}"
    );
    (surface, mesh)
}

#[test]
fn adaptive_meshes_honour_the_tolerance_by_certified_snap() {
    let mut nets = vec![("viking", example("viking", Some(30.0)))];
    nets.extend(cgal("fandisk.off", 30.0).map(|n| ("fandisk", n)));
    if let Some(path) = cgal_mesh("pig.off") {
        nets.push(("pig (smooth)", ControlNet::read(path).unwrap()));
    }
    nets.extend(cgal("pig.off", 40.0).map(|n| ("pig (40°)", n)));
    for (name, net) in nets {
        let (surface, mesh) = adapted(name, &net);
        let q = mesh.quality();
        check_invariants(name, &surface, &mesh);
        assert!(
            q.mean_min_angle >= 50.0,
            "{name}: mean-min {}",
            q.mean_min_angle
        );
        if name != "pig (40°)" {
            check_orientation_and_faces(name, &surface, &mesh, 1, 0);
            // The goals: nothing below 20°.
            assert!(q.min_angle >= 20.0, "{name}: min angle {}", q.min_angle);
            continue;
        }
        // Not met on pig with its 40° creases (a known failure, docs/remesher.md). Its
        // net folds back at triangle 534 (see `next_to_folds`), and its
        // creases end inside its one face (the tail's, beside triangles
        // 548 and 565, bend by up to 90°): the caps and the triangles
        // facing against the surface lie there. Away from the fold, they
        // are counted and bounded, so that they cannot grow unnoticed:
        // any change to the sizes moves them (0–34 below 20° not forced by
        // a feature by the remesher's own count, 0–1 facing against, as
        // the sizes' bound varied). By the input's sectors (decided in the
        // test), 14 of the 21 below 20° there are not forced (2026-12-01):
        // the bound.
        let folds = next_to_folds(&net);
        assert!(!folds.is_empty(), "pig's fold is no longer found");
        let rest = without(&mesh, &folds);
        let (against, at_folds) = facing_against(name, &surface, &rest, 1);
        assert_eq!(at_folds, 0, "{name}: triangles face their own sheet");
        let q = rest.quality();
        let small = sectors::small_angles(&surface, &rest, 20.0);
        let unforced: Vec<_> = small.iter().filter(|s| !s.forced(20.0)).collect();
        println!(
            "{name}: {} triangles next to the fold left out; on the rest {} below 20°, {} not forced by the input's sectors (min {:.2}°), {} facing against the surface",
            mesh.triangles.len() - rest.triangles.len(),
            small.len(),
            unforced.len(),
            q.min_angle,
            against.len()
        );
        assert!(
            unforced.len() <= 14,
            "{name}: {} triangles below 20° that the input does not force: {}",
            unforced.len(),
            sectors::list(&unforced)
        );
        assert!(
            against.len() <= 3,
            "{name}: triangles {against:?} face against the surface"
        );
    }
}

#[test]
fn bad_options_are_refused_by_name() {
    let net = example("cube", None);
    let surface = Surface::new(&net).unwrap();
    let message = |r: loopsurf::Result<SurfaceMesh>| r.unwrap_err().to_string();
    assert!(message(Remesher::new(&surface).run()).contains("no density"));
    assert!(message(Remesher::new(&surface).size(-1.0).run()).contains("size -1"));
    assert!(message(Remesher::new(&surface).size(f64::NAN).run()).contains("size NaN"));
    assert!(message(Remesher::new(&surface).size(1.0).gradation(0.9).run()).contains("gradation"));
    assert!(message(Remesher::new(&surface).tolerance(2.0).run()).contains("tolerance 2"));
    assert!(message(Remesher::new(&surface).size(1e-9).run()).contains("over the budget"));
    assert!(
        message(Remesher::new(&surface).size(1.0).max_triangles(0).run())
            .contains("max_triangles 0")
    );
}

/// The triangle budget stops a density before its memory is spent, and
/// says how many triangles were asked for: for a uniform size from the
/// net's area before any meshing, for curvature sizes from the size
/// field on the mesh as it is, before each round's splits.
#[test]
fn densities_over_the_budget_fail_with_the_count() {
    let net = example("cube", None);
    let surface = Surface::new(&net).unwrap();
    let uniform = Remesher::new(&surface)
        .size(0.025)
        .max_triangles(1_000)
        .run();
    let err = uniform.unwrap_err();
    assert!(
        matches!(err, loopsurf::Error::OverBudget { limit: 1_000, needed, .. } if needed > 1_000.0),
        "{err:?}"
    );
    let message = err.to_string();
    assert!(message.contains("budget of 1000"), "{message}");
    // The unit cube's net has area 6 (its limit surface a bit less): at
    // h = 0.025 (aimed at 1.07 h, with 1.2 for edges coming out shorter
    // than aimed) it asks for about 1.2 · 6 / (√3/4 · 0.02675²) = 23 240.
    assert!(message.contains("2.324e4"), "{message}");
    let fits = Remesher::new(&surface).size(0.5).max_triangles(1_000).run();
    assert!(fits.unwrap().triangles.len() <= 1_000);
    // None only under LOOPSURF_SKIP_DATA.
    let Some(fandisk) = cgal("fandisk.off", 30.0) else {
        return;
    };
    let surface = Surface::new(&fandisk).unwrap();
    // At 1e-4 it makes about 42 000 triangles (the gradation test): its
    // start (the chart mesher's 32 365) fits in 4 × 10 000, its sizes do
    // not fit in 10 000.
    let adapted = |max| {
        Remesher::new(&surface)
            .tolerance(1e-4)
            .max_triangles(max)
            .run()
            .unwrap_err()
            .to_string()
    };
    let message = adapted(10_000);
    assert!(message.contains("over the budget of 10000"), "{message}");
    let asked: f64 = message
        .strip_prefix("the requested density needs about ")
        .and_then(|m| m.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no count in: {message}"));
    assert!((10_000.0..60_000.0).contains(&asked), "{message}");
    // Nor does the start fit in 4 × 5 000: that is said too.
    let message = adapted(5_000);
    assert!(
        message.contains("starts from (allowed 4 × the budget of 5000"),
        "{message}"
    );
    // Said where it happened, yet still a budget error: callers (and the C
    // ABI's LS_ERR_OVER_BUDGET) match on the kind.
    let err = Remesher::new(&surface)
        .tolerance(1e-4)
        .max_triangles(5_000)
        .run()
        .unwrap_err();
    assert!(
        matches!(
            err.root(),
            loopsurf::Error::OverBudget { limit: 20_000, .. }
        ),
        "{err:?}"
    );
}

/// mpi.off and its triangulation mpi_triang.off (tested here): at 40°
/// their crease chains turn back on themselves at chain vertices, where
/// the limit curve stops dead (a cusp: in mpi.off, triangulated by
/// `--repair`, curvature 1.4e6 per unit at vertex 39), and many patches
/// fold (41 of mpi.off's). The cusp's curvature once set the size of whole
/// flat control triangles to the floor (on mpi.off 8.6 million triangles
/// asked for, the splits past 40 million and 4 GB), and then the
/// tolerance rounds shrank the triangles whose chord error no size helps,
/// again and again (the sizes asking for 29 million). Now it meshes, and
/// says how far it missed.
#[test]
fn cusps_and_stuck_misses_do_not_run_away() {
    // None only under LOOPSURF_SKIP_DATA.
    let Some(net) = cgal("mpi_triang.off", 40.0) else {
        return;
    };
    let surface = Surface::new(&net).unwrap();
    let mesh = Remesher::new(&surface)
        .adapt_curvature(true)
        .tolerance(1e-3)
        .run()
        .unwrap();
    let deviation = mesh.deviation.unwrap() / net.bbox_diagonal();
    println!(
        "mpi_triang: {} triangles, deviation {deviation:.3e}",
        mesh.triangles.len()
    );
    assert!(
        mesh.triangles.len() <= 400_000,
        "mpi_triang: {} triangles",
        mesh.triangles.len()
    );
    assert!(deviation.is_finite() && deviation < 0.05, "{deviation}");
}

/// A size with a tolerance (no `adapt_curvature`): sizes follow curvature
/// under the size, and shrink only where the tolerance is still missed,
/// once per round per control triangle (it once compounded per probe, down
/// to the floor, and the octahedron ran out of memory). On fandisk at a
/// coarse size, shrinking a uniform size instead never converged: 428k
/// triangles, the error stuck at 3.5e-2.
#[test]
fn a_size_with_a_tolerance_refines_only_where_needed() {
    let octahedron = ControlNet::from_arrays(
        vec![
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, -1.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(0.0, 0.0, -1.0),
        ],
        &[
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    )
    .unwrap();
    let surface = Surface::new(&octahedron).unwrap();
    for tol in [1e-2, 1e-3] {
        let mesh = Remesher::new(&surface)
            .size(0.3)
            .tolerance(tol)
            .run()
            .unwrap();
        let snapped = mesh.snap_deviation(&surface).unwrap() / octahedron.bbox_diagonal();
        let q = mesh.quality();
        assert!(snapped <= tol, "{tol}: {snapped}");
        // Curvature sizing for the same tolerance needs about this many.
        assert!(
            mesh.triangles.len() < 4000,
            "{tol}: {} triangles",
            mesh.triangles.len()
        );
        assert!(q.min_angle > 30.0, "{tol}: min angle {}", q.min_angle);
        check_invariants("octahedron", &surface, &mesh);
    }
    let Some(fandisk) = cgal("fandisk.off", 30.0) else {
        return;
    };
    let surface = Surface::new(&fandisk).unwrap();
    let tol = 1e-3;
    let mesh = Remesher::new(&surface)
        .size(0.14 * fandisk.bbox_diagonal())
        .tolerance(tol)
        .run()
        .unwrap();
    let snapped = mesh.snap_deviation(&surface).unwrap() / fandisk.bbox_diagonal();
    let q = mesh.quality();
    println!(
        "fandisk, size and tolerance: {} triangles, deviation {snapped:.2e}, min {:.2}°, mean-min {:.2}°",
        mesh.triangles.len(),
        q.min_angle,
        q.mean_min_angle
    );
    assert!(snapped <= tol, "fandisk: {snapped}");
    assert!(
        q.min_angle >= 20.0 && q.mean_min_angle >= 49.0,
        "fandisk: {q:?}"
    );
    check_invariants("fandisk", &surface, &mesh);
}

/// The 99th percentile, over edges, of the ratio between the mean edge
/// lengths at its two ends: how fast the local size changes.
fn neighbour_size_ratio(mesh: &SurfaceMesh) -> f64 {
    let mut sum = vec![0.0; mesh.points.len()];
    let mut count = vec![0.0; mesh.points.len()];
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            let l = mesh.points[a].distance(mesh.points[b]);
            for v in [a, b] {
                sum[v] += l;
                count[v] += 1.0;
            }
        }
    }
    let mut ratios: Vec<f64> = mesh
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k] as usize, t[(k + 1) % 3] as usize)))
        .map(|(a, b)| {
            let (x, y) = (sum[a] / count[a], sum[b] / count[b]);
            x.max(y) / x.min(y)
        })
        .collect();
    ratios.sort_by(f64::total_cmp);
    ratios[(ratios.len() - 1) * 99 / 100]
}

/// `gradation` bounds how fast sizes change from edge to edge: fandisk
/// at a tight tolerance (sizes from 1e-4 of the diagonal at its creases
/// to the cap) changes size by at most about the gradation per edge, and
/// a larger gradation lets sizes grow faster. (Not always with fewer
/// triangles: where more probes then miss the tolerance, their sizes
/// shrink; once, 3.0 gave 49 386 triangles against 41 958 at 1.3.)
#[test]
fn gradation_bounds_how_fast_sizes_change() {
    // None only under LOOPSURF_SKIP_DATA.
    let Some(net) = cgal("fandisk.off", 30.0) else {
        return;
    };
    let surface = Surface::new(&net).unwrap();
    let mesh = |g: f64| {
        Remesher::new(&surface)
            .adapt_curvature(true)
            .tolerance(1e-4)
            .gradation(g)
            .run()
            .unwrap()
    };
    let (gentle, steep) = (mesh(1.3), mesh(3.0));
    let (r_gentle, r_steep) = (neighbour_size_ratio(&gentle), neighbour_size_ratio(&steep));
    println!(
        "gradation 1.3: {} triangles, 99% of neighbouring sizes within {r_gentle:.3}; 3.0: {}, {r_steep:.3}",
        gentle.triangles.len(),
        steep.triangles.len()
    );
    assert!(r_gentle <= 1.3 + 0.25, "gradation 1.3: {r_gentle}");
    assert!(
        r_steep >= r_gentle + 0.2,
        "3.0: {r_steep} against {r_gentle}"
    );
}

/// A CAD tessellation's fans: anchor.off has irregular vertices of valence
/// 34, 22 and 20 beside its 90° creases, at the inner corners of L-shaped
/// flat faces, where its surface (unseamed, as here) folds over itself
/// with huge curvature and a tiny chord error. Sized by
/// the curvature at each vertex alone, sizes ran away towards them
/// (42 434 triangles, 19% below 20°); the chord tolerance is met with far
/// fewer, and mostly good, triangles (0.23% below 20°, mean-min 49.9°,
/// since triangles with a corner on a crease are also checked at their
/// centroid; 1.4–2.1% and 48.7–49.1° before). On the folds every change
/// elsewhere moves those figures (variants of the split placement tried
/// on 2026-11-29 gave 1.5–2.8%, one 18%): the bounds catch a runaway.
/// They are those first set (at most 0.5% below 20°, mean-min at least
/// 49.5°, at most 5 triangles facing against the surface), met again on
/// 2026-12-01 (0.21%, 49.89°, 3).
#[test]
fn high_valence_fans_do_not_run_away() {
    // None only under LOOPSURF_SKIP_DATA.
    let Some(net) = cgal("anchor.off", 40.0) else {
        return;
    };
    let (surface, mesh) = adapted("anchor", &net);
    let q = mesh.quality();
    assert!(
        mesh.triangles.len() <= 25_000,
        "anchor: {} triangles",
        mesh.triangles.len()
    );
    assert!(q.below_20 <= 0.005, "anchor: {} below 20°", q.below_20);
    assert!(
        q.mean_min_angle >= 49.5,
        "anchor: mean-min {}",
        q.mean_min_angle
    );
    check_invariants("anchor", &surface, &mesh);
    // In those flat fans the surface itself folds: its normal flips
    // between +y and −y within one control triangle (500, beside the
    // valence-22 vertex, a concave corner) while it stays within 4e-7 of
    // the plane. A
    // triangle there faces one way or the other: every one that faces
    // against the nearest point's normal lies on a patch that folds
    // (`folds::folded_patches`, checked against the refined net in
    // tests/folds.rs) or on one sharing a control vertex with it.
    let folded = loopsurf::folds::folded_patches(&surface);
    assert!(!folded.is_empty(), "anchor: no folded patch found");
    let corners: HashSet<u32> = folded.iter().flat_map(|&t| net.triangles()[t]).collect();
    let (against, at_folds) = facing_against("anchor", &surface, &mesh, 1);
    println!(
        "anchor: {} triangles face against the surface, patches {folded:?} fold",
        against.len()
    );
    // 3 and 8 when measured (2026-12-01).
    assert!(
        against.len() <= 5,
        "anchor: triangles {against:?} face against the surface"
    );
    assert!(
        at_folds <= 8,
        "anchor: {at_folds} triangles face their own sheet"
    );
    for t in against {
        let beside = mesh.triangles[t].iter().any(|&v| {
            let tri = mesh.params[v as usize].tri as usize;
            net.triangles()[tri].iter().any(|c| corners.contains(c))
        });
        assert!(
            beside,
            "anchor: triangle {t} faces against the surface away from the folds"
        );
    }
}
