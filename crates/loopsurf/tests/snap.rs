//! Snapping against a brute-force reference that shares no code with the
//! search: the exact dyadic limit points of a level-3 refinement as dense
//! samples, the best few polished by a derivative-free pattern search.

mod common;

use common::{cgal_mesh, example, Lcg};
use loopsurf::refine::refine_uniform;
use loopsurf::snap;
use loopsurf::{ControlNet, DVec3, Snap, Surface, SurfaceMode};

struct Reference {
    samples: Vec<(DVec3, usize, f64, f64)>,
}

impl Reference {
    fn new(net: &ControlNet) -> Reference {
        let refined = refine_uniform(net, 3).unwrap();
        let samples = refined
            .limit_points()
            .into_iter()
            .zip(refined.origins())
            .filter_map(|(x, o)| o.map(|o| (x, o.tri as usize, o.v, o.w)))
            .collect();
        Reference { samples }
    }

    /// The smallest distance from p to the surface, to ~1e-12 of the model.
    fn distance(&self, surface: &Surface, p: DVec3) -> f64 {
        let mut order: Vec<(f64, usize)> = self
            .samples
            .iter()
            .enumerate()
            .map(|(i, s)| ((s.0 - p).length_squared(), i))
            .collect();
        let k = 24.min(order.len());
        order.select_nth_unstable_by(k - 1, |a, b| a.0.total_cmp(&b.0));
        order[..k]
            .iter()
            .map(|&(_, i)| {
                let (_, tri, v, w) = self.samples[i];
                pattern_search(surface, p, tri, v, w)
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// Compass search over (v, w) inside one triangle: no derivatives. Each
/// round moves to the best of the six neighbours; the first step is an
/// eighth of the samples' spacing, so the search stays in the basin of its
/// sample instead of leaping into a neighbouring one.
fn pattern_search(surface: &Surface, p: DVec3, tri: usize, mut v: f64, mut w: f64) -> f64 {
    let dist = |v: f64, w: f64| (surface.eval(tri, v, w).unwrap().x - p).length();
    let mut best = dist(v, w);
    let mut h = 1.0 / 64.0;
    let dirs = [
        (1.0, 0.0),
        (-1.0, 0.0),
        (0.0, 1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (-1.0, 1.0),
    ];
    while h > 1e-11 {
        let (mut next, mut at) = (best, (v, w));
        for (dv, dw) in dirs {
            let (mut nv, mut nw) = ((v + h * dv).max(0.0), (w + h * dw).max(0.0));
            if nv + nw > 1.0 {
                let s = nv + nw;
                (nv, nw) = (nv / s, nw / s);
            }
            let d = dist(nv, nw);
            if d < next {
                (next, at) = (d, (nv, nw));
            }
        }
        if next < best {
            (best, (v, w)) = (next, at);
        } else {
            h *= 0.5;
        }
    }
    best
}

fn bbox(net: &ControlNet) -> (DVec3, DVec3) {
    let lo = net.points().iter().fold(DVec3::INFINITY, |a, &b| a.min(b));
    let hi = net
        .points()
        .iter()
        .fold(DVec3::NEG_INFINITY, |a, &b| a.max(b));
    (lo, hi)
}

/// The returned point is the surface at its parameters, and at an interior
/// minimiser the residual is normal to the surface.
fn check_consistent(surface: &Surface, p: DVec3, s: &Snap, diagonal: f64, what: &str) {
    let e = surface.eval(s.tri, s.v, s.w).unwrap();
    assert_eq!(e.x, s.point, "{what}");
    assert!(
        ((s.point - p).length() - s.distance).abs() <= 1e-15 * diagonal,
        "{what}"
    );
    let inside = s.v > 1e-6 && s.w > 1e-6 && s.v + s.w < 1.0 - 1e-6;
    let r = p - s.point;
    if inside && !e.at_special_vertex && r.length() > 1e-6 * diagonal {
        let cosines = [
            r.dot(e.xv) / (r.length() * e.xv.length()),
            r.dot(e.xw) / (r.length() * e.xw.length()),
        ];
        assert!(
            cosines.iter().all(|c| c.abs() < 1e-7),
            "{what}: residual not normal: {cosines:?}"
        );
    }
}

fn check_mesh(name: &str, net: &ControlNet, queries: usize) {
    let surface = Surface::new(net).unwrap();
    let reference = Reference::new(net);
    let diagonal = net.bbox_diagonal();
    let (lo, hi) = bbox(net);
    let margin = 0.2 * (hi - lo);
    let mut rng = Lcg(7);
    let mut points = Vec::new();
    for _ in 0..queries {
        // In and around the bounding box.
        points.push(("box", rng.point_in(lo - margin, hi + margin)));
        // Within 1% of the diagonal of a random surface point, either side.
        let t = (rng.next() * net.triangles().len() as f64) as usize;
        let (v, w) = (rng.next() * 0.5, rng.next() * 0.5);
        let e = surface.eval(t, v, w).unwrap();
        let n = e.normal().unwrap_or_default();
        points.push(("near", e.x + (rng.next() - 0.5) * 0.02 * diagonal * n));
        // A hundred times the model size away.
        let dir = (rng.point_in(DVec3::splat(-1.0), DVec3::ONE)).normalize();
        points.push(("far", 0.5 * (lo + hi) + 100.0 * diagonal * dir));
    }
    for (i, (kind, p)) in points.into_iter().enumerate() {
        let what = format!("{name}: {kind} point {i} {p:?}");
        let s = snap::closest_point(&surface, p).unwrap();
        check_consistent(&surface, p, &s, diagonal, &what);
        let r = reference.distance(&surface, p);
        assert!(
            (s.distance - r).abs() <= 1e-10 * diagonal,
            "{what}: snap {} vs reference {r} ({:e} of the diagonal)",
            s.distance,
            (s.distance - r) / diagonal
        );
        // From a hint elsewhere, the same global answer.
        let hint = snap::snap_near(&surface, p, i % net.triangles().len(), 0.2, 0.2).unwrap();
        assert!(
            (hint.distance - s.distance).abs() <= 1e-10 * diagonal,
            "{what}: snap_near"
        );
    }
}

#[test]
fn points_on_the_surface_snap_to_themselves() {
    let cases = [
        ("torus", example("torus", None), SurfaceMode::Approximating),
        (
            "cube",
            example("cube", Some(30.0)),
            SurfaceMode::Approximating,
        ),
        (
            "viking",
            example("viking", Some(30.0)),
            SurfaceMode::Approximating,
        ),
        (
            "viking, displacement",
            example("viking", Some(30.0)),
            SurfaceMode::Displacement,
        ),
        (
            "sphere, solved",
            example("sphere", None),
            SurfaceMode::Solve,
        ),
    ];
    for (name, net, mode) in cases {
        let surface = Surface::with_mode(&net, mode).unwrap();
        let diagonal = net.bbox_diagonal();
        let mut rng = Lcg(11);
        for _ in 0..200 {
            let t = (rng.next() * net.triangles().len() as f64) as usize;
            let (v, w) = (rng.next(), rng.next());
            let (v, w) = if v + w > 1.0 {
                (1.0 - v, 1.0 - w)
            } else {
                (v, w)
            };
            let x = surface.eval(t, v, w).unwrap().x;
            let s = snap::closest_point(&surface, x).unwrap();
            assert!(
                s.distance <= 1e-13 * diagonal,
                "{name}: triangle {t} ({v}, {w}): {:e}",
                s.distance / diagonal
            );
            let near = snap::snap_near(&surface, x, t, (v + 0.1).min(0.5), w * 0.5).unwrap();
            assert!(near.distance <= 1e-13 * diagonal, "{name}: snap_near");
        }
    }
}

#[test]
fn synthetic_shapes_match_the_reference() {
    check_mesh("torus", &example("torus", None), 15);
    check_mesh(
        "cube with hard edges and corners",
        &example("cube", Some(30.0)),
        15,
    );
    check_mesh("viking", &example("viking", Some(30.0)), 10);
    check_mesh("open disk (boundary)", &example("open-disk", None), 15);
}

#[test]
fn cgal_meshes_match_the_reference() {
    // bunny00: a 75k-triangle scan, bumpy at the scale of its triangles.
    for (name, angle, queries) in [
        ("fandisk.off", Some(30.0), 100),
        ("pig.off", None, 100),
        ("bunny00.off", None, 20),
    ] {
        let Some(path) = cgal_mesh(name) else {
            continue;
        };
        let mut net = ControlNet::read(path).unwrap();
        if let Some(a) = angle {
            net.tag_by_angle(a).unwrap();
        }
        check_mesh(name, &net, queries);
    }
}

/// Points within 1% of the pig's size where one control triangle's patch
/// holds two local minima of the distance (folds at the legs, ears and
/// snout): a search that trusts one solve per patch returns the wrong one
/// (each of these was off by 1e-5 to 3e-4 of the diagonal).
#[test]
fn several_minima_in_one_patch() {
    let Some(path) = cgal_mesh("pig.off") else {
        return;
    };
    let net = ControlNet::read(path).unwrap();
    let surface = Surface::new(&net).unwrap();
    let reference = Reference::new(&net);
    let diagonal = net.bbox_diagonal();
    for p in [
        [
            0.13483875804281278,
            0.05275120666237249,
            -0.13455074850284088,
        ],
        [
            -0.015490051197290399,
            -0.14106811158858276,
            0.4958140465150595,
        ],
        [
            -0.1371149704372163,
            -0.0010940697493740758,
            -0.40321934262256154,
        ],
        [0.09201969171846844, 0.1865430987939412, -0.1288125413519282],
        [
            0.23784010551881354,
            0.0030704021500688526,
            -0.32436790445848207,
        ],
        [
            0.25325693446467273,
            -0.01650534719514781,
            -0.39106313034988766,
        ],
        [
            -0.2633611181270685,
            -0.02065519866554638,
            -0.3572936545862878,
        ],
        [0.01398123222589549, -0.1495343058770601, 0.4932793918559052],
        [
            -0.10974316031500714,
            0.19408646117597922,
            -0.13340550549646454,
        ],
        [
            0.20727010573034998,
            -0.013412667387235181,
            -0.40121141227839685,
        ],
    ] {
        let p = DVec3::from_array(p);
        let s = snap::closest_point(&surface, p).unwrap();
        check_consistent(&surface, p, &s, diagonal, "pig fold");
        let r = reference.distance(&surface, p);
        assert!(
            (s.distance - r).abs() <= 1e-10 * diagonal,
            "{p:?}: snap {} vs reference {r}",
            s.distance
        );
    }
}

#[test]
fn concave_and_equidistant_points() {
    // The torus centre is equidistant from the whole inner equator; any
    // point of it is a correct answer, at the reference distance.
    let net = example("torus", None);
    let surface = Surface::new(&net).unwrap();
    let reference = Reference::new(&net);
    let (lo, hi) = bbox(&net);
    for p in [
        0.5 * (lo + hi),
        0.5 * (lo + hi) + DVec3::new(0.0, 0.0, 0.01),
    ] {
        let s = snap::closest_point(&surface, p).unwrap();
        let r = reference.distance(&surface, p);
        assert!(
            (s.distance - r).abs() <= 1e-10 * net.bbox_diagonal(),
            "{p:?}: {} vs {r}",
            s.distance
        );
    }
}

#[test]
fn thin_features_and_points_between_two_sheets() {
    // A sphere flattened to a 2%-thick disc: two sheets close together.
    let e = loopsurf::examples::by_name("sphere").unwrap();
    let points: Vec<DVec3> = e
        .points
        .iter()
        .map(|p| DVec3::new(p.x, p.y, 0.02 * p.z))
        .collect();
    let net = ControlNet::from_arrays(points, &e.tris).unwrap();
    let surface = Surface::new(&net).unwrap();
    let reference = Reference::new(&net);
    let diagonal = net.bbox_diagonal();
    let mut rng = Lcg(5);
    for _ in 0..20 {
        // In the mid-plane (equidistant from both sheets) and just off it.
        let (x, y) = (rng.next() - 0.5, rng.next() - 0.5);
        for z in [0.0, 0.001, -0.003] {
            let p = DVec3::new(x, y, z);
            let s = snap::closest_point(&surface, p).unwrap();
            let r = reference.distance(&surface, p);
            assert!(
                (s.distance - r).abs() <= 1e-10 * diagonal,
                "{p:?}: {} vs {r}",
                s.distance
            );
            check_consistent(&surface, p, &s, diagonal, "flat disc");
        }
    }
}

#[test]
fn non_finite_points_and_bad_hints_are_errors() {
    let net = example("sphere", None);
    let surface = Surface::new(&net).unwrap();
    assert!(snap::closest_point(&surface, DVec3::new(f64::NAN, 0.0, 0.0)).is_err());
    assert!(snap::snap_near(&surface, DVec3::ZERO, 99999, 0.1, 0.1).is_err());
    assert!(snap::snap_near(&surface, DVec3::ZERO, 0, 0.9, 0.9).is_err());
}

#[test]
fn the_index_is_counted_once_built() {
    let net = example("viking", Some(30.0));
    let surface = Surface::new(&net).unwrap();
    let before = surface.memory_bytes();
    snap::closest_point(&surface, DVec3::ZERO).unwrap();
    let after = surface.memory_bytes();
    // At least one container (~150 bytes) per control triangle.
    assert!(
        after >= before + 100 * net.triangles().len(),
        "{before} -> {after}"
    );
}
