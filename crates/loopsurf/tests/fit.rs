//! The fitted surrogate (`loopsurf::fit`) against the exact surfaces of
//! the CAD shapes (`loopsurf::cad`), never against the fit's own report.
//! Bounds are pinned as measured (docs/fitting.md; the default resolution
//! of 0.01 of the diagonal, remeshed at 0.02 and subdivided once, since
//! 2026-12-03): a change that makes the fit
//! worse fails here; one that makes it better tightens them.

mod common;

use loopsurf::cad::{self, Analytic};
use loopsurf::{folds, ControlNet, DVec3, Error, Fitter, Remesher, Surface};
use std::collections::HashMap;

const CHORD: f64 = 5e-4;
const ANGLE: f64 = 15.0;
const LATTICE: usize = 6;

fn fitted(shape: &dyn Analytic) -> Surface {
    let mut net = shape.net().unwrap();
    net.tag_by_angle(30.0).unwrap();
    let fit = Fitter::new(&net).tolerance(1.0).run().unwrap();
    Surface::new(&fit.net).unwrap()
}

/// On the sphere the fit meets the goals: 5× closer than the facets at
/// the worst, 10× on average, mean curvature within 5% on average at every
/// latitude (the valence-75 poles included), no fold, and its surface
/// remeshes at 1e-4.
#[test]
fn sphere_is_closer_than_its_facets() {
    let shape = cad::sphere(CHORD, ANGLE);
    let ex = shape.tessellation();
    let facets = cad::facet_distance(&shape, &ex.points, &ex.tris, LATTICE);
    let surface = fitted(&shape);
    let d = cad::surrogate_distance(&shape, &surface, LATTICE).unwrap();
    assert!(d.max <= facets.max / 5.0, "{d:?} against {facets:?}");
    assert!(d.mean <= facets.mean / 10.0, "{d:?} against {facets:?}");
    // Pinned as measured: 8.7e-6 / 1.73e-6 (3.5e-5 / 1.8e-6 on a net
    // remeshed at 0.015 of the diagonal with data predicted at its
    // spacing; 1.28e-5 / 1.62e-6 with data at half of it).
    assert!(d.max <= 9.2e-6 && d.mean <= 1.8e-6, "{d:?}");
    let k = cad::curvature_error(&shape, &surface, LATTICE, 0.1)
        .unwrap()
        .unwrap();
    assert!(k.mean <= 0.05, "{k:?}");
    // Pinned as measured: 32.2% / 2.44% (63.5% / 2.37% on a net remeshed
    // at 0.015 of the diagonal with data predicted at its spacing, 30.8% /
    // 2.29% with data at half of it; 20.5% / 1.70% on a net remeshed at
    // 0.03: a finer net fitted to the same data is less smooth in its
    // second derivatives).
    assert!(k.max <= 0.34 && k.mean <= 0.026, "{k:?}");
    assert!(folds::folded_patches(&surface).is_empty());
    let mesh = Remesher::new(&surface).tolerance(1e-4).run().unwrap();
    assert!(mesh.triangles.len() > 1000);
    let chord = mesh.deviation.unwrap() / mesh.diagonal;
    assert!(chord <= 1e-4, "remeshed chord error {chord:e}");
}

/// The cylinder's rims are fitted by the new net's crease curves: points
/// of the fitted surface on its hard edges are on the true rims to within
/// a fifth of the facets' rim polygon. The side, where the input has no
/// vertex between the rims, is fitted to the curves predicted along its
/// slivers: 5× closer than the facets at the worst and 10× on average.
#[test]
fn cylinder_rims_on_the_true_edges() {
    let shape = cad::cylinder(CHORD, ANGLE, cad::CapStyle::Fan);
    let surface = fitted(&shape);
    let net = surface.net();
    let features = shape.features();
    let near = |p| {
        features
            .iter()
            .map(|f| f.distance(p))
            .fold(f64::INFINITY, f64::min)
    };
    let topo = net.topology();
    let mut worst: f64 = 0.0;
    for e in 0..topo.num_edges() {
        if !net.features().is_hard_edge(e) {
            continue;
        }
        let t = topo.edge_triangles()[e][0] as usize;
        let [a, b] = topo.edges()[e];
        let c = topo.triangles()[t];
        let corner = |v| {
            let k = c.iter().position(|&x| x == v).unwrap();
            [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)][k]
        };
        let (pa, pb) = (corner(a), corner(b));
        for i in 0..=4 {
            let s = i as f64 / 4.0;
            let (v, w) = (pa.0 + s * (pb.0 - pa.0), pa.1 + s * (pb.1 - pa.1));
            worst = worst.max(near(surface.point(t, v, w).unwrap()));
        }
    }
    // The rim polygon's chord error: a cut of angle 2π/n of radius 0.5.
    let ex = shape.tessellation();
    let rim: Vec<_> = ex
        .points
        .iter()
        .filter(|p| p.z == 0.0 && p.length() > 0.0)
        .collect();
    let sagitta = cad::CYLINDER_RADIUS * (1.0 - (std::f64::consts::PI / rim.len() as f64).cos());
    assert!(
        worst <= sagitta / 5.0,
        "rims {worst:e} against the facets' {sagitta:e}"
    );
    let d = cad::surrogate_distance(&shape, &surface, LATTICE).unwrap();
    let facets = cad::facet_distance(&shape, &ex.points, &ex.tris, LATTICE);
    assert!(
        d.max <= facets.max / 5.0 && d.mean <= facets.mean / 10.0,
        "{d:?} against {facets:?}"
    );
    // Pinned as measured: 6.7e-5 / 2.0e-6 (6.3e-5 / 3.6e-6 on a net
    // remeshed at 0.015 of the diagonal with data predicted at its
    // spacing, 5.3e-5 / 3.0e-6 with data at half of it: the subdivided
    // net is 26% farther at the worst, beside the rim, and 34% closer on
    // average; fitted to the vertices alone it was 1.1e-3 / 4.3e-4).
    assert!(d.max <= 7.0e-5 && d.mean <= 2.1e-6, "{d:?}");
}

/// The cone's apex, a fan of slivers that no dihedral angle marks, is
/// found and kept as a corner: the fitted surface reaches the true apex,
/// and strays from the true cone less than when the apex is rounded off
/// (5.5e-2 of the diagonal): 5× closer than the facets at the worst and
/// on average, though the facets' slivers lie on the cone's rulings (the
/// goal's 10× on average is missed: docs/fitting.md says why).
#[test]
fn cone_apex_is_kept() {
    let shape = cad::cone(CHORD, ANGLE);
    let mut net = shape.net().unwrap();
    net.tag_by_angle(30.0).unwrap();
    let fit = Fitter::new(&net).tolerance(1.0).run().unwrap();
    assert_eq!(fit.report.apexes, 1);
    let apex = loopsurf::DVec3::new(0.0, 0.0, cad::CONE_HEIGHT);
    let nearest = fit
        .net
        .limit_points()
        .iter()
        .map(|p| p.distance(apex))
        .fold(f64::INFINITY, f64::min);
    assert!(
        nearest <= 1e-4 * shape.diagonal(),
        "apex missed by {nearest:e}"
    );
    let surface = Surface::new(&fit.net).unwrap();
    let d = cad::surrogate_distance(&shape, &surface, LATTICE).unwrap();
    let ex = shape.tessellation();
    let facets = cad::facet_distance(&shape, &ex.points, &ex.tris, LATTICE);
    assert!(
        d.max <= facets.max / 5.0 && d.mean <= facets.mean / 5.0,
        "{d:?} against {facets:?}"
    );
    // Pinned as measured: 5.0e-5 / 7.0e-6 (3.8e-3 / 7.2e-5 while the
    // start net closed the apex with three triangles, 1.5e-3 / 6.6e-5
    // while the curves predicted along the rulings left the apex tilted,
    // 9.4e-4 / 7.3e-6 with six triangles around the apex, 6.0e-4 / 7.8e-6
    // with sixteen on a net remeshed at 0.015 of the diagonal, 1.9e-4 /
    // 7.2e-6 on the subdivided net with the fan opened by edge splits,
    // which left vertices of valence 4 and 13 beside the tip; the polar
    // grid around the apex took the worst away from the tip).
    assert!(d.max <= 5.2e-5 && d.mean <= 7.3e-6, "{d:?}");
}

/// On the torus the fit meets the goals: 5× closer than the facets at
/// the worst and 10× on average (3.0e-5 / 1.3e-6 against 4.0e-4 /
/// 1.4e-4; 1.1e-4 / 8.1e-6 on a net remeshed at 0.015 of the diagonal
/// with data predicted at its spacing, 6.2e-5 / 6.0e-6 with data at half
/// of it: beside the remeshed net's irregular vertices a Loop surface
/// cannot bend as a torus does, and a subdivided net has fewer of them).
/// Pinned as measured.
#[test]
fn torus_is_closer_than_its_facets() {
    let shape = cad::torus(CHORD, ANGLE);
    let ex = shape.tessellation();
    let facets = cad::facet_distance(&shape, &ex.points, &ex.tris, LATTICE);
    let d = cad::surrogate_distance(&shape, &fitted(&shape), LATTICE).unwrap();
    assert!(d.max <= facets.max / 5.0, "{d:?} against {facets:?}");
    assert!(d.mean <= facets.mean / 10.0, "{d:?} against {facets:?}");
    assert!(d.max <= 3.2e-5 && d.mean <= 1.4e-6, "{d:?}");
}

/// Where fillets meet flat faces and a cylinder, the fit meets the goal
/// at the worst: 5× closer than the facets (filleted box 6.8e-5 against
/// 4.3e-4, cyl-plate 8.8e-5 against 4.8e-4), and on average 9.5× and 16×
/// (the goal's 10× is missed on the box by a whisker). Pinned as
/// measured: 6.79e-5 / 1.87e-5 and 8.83e-5 / 8.31e-6 (1.5e-4 / 2.3e-5 and
/// 2.0e-4 / 1.3e-5 on a net remeshed at 0.015 of the diagonal with data
/// predicted at its spacing).
#[test]
fn blends_closer_than_facets() {
    for (shape, max, mean) in [
        (
            Box::new(cad::FilletedBox::new(CHORD, ANGLE)) as Box<dyn Analytic>,
            7.1e-5,
            1.95e-5,
        ),
        (Box::new(cad::cylinder_plate(CHORD, ANGLE)), 9.2e-5, 8.7e-6),
    ] {
        let ex = shape.tessellation();
        let facets = cad::facet_distance(shape.as_ref(), &ex.points, &ex.tris, LATTICE);
        let d = cad::surrogate_distance(shape.as_ref(), &fitted(shape.as_ref()), LATTICE).unwrap();
        let name = shape.name();
        assert!(
            d.max <= facets.max / 5.0 && d.mean <= facets.mean / 9.0,
            "{name}: {d:?} against {facets:?}"
        );
        assert!(d.max <= max && d.mean <= mean, "{name}: {d:?}");
    }
}

/// A tolerance that cannot be met is refused by name, with the input
/// vertex and the distance; a resolution that is no length is refused.
#[test]
fn refusals() {
    let shape = cad::sphere(CHORD, ANGLE);
    let net = shape.net().unwrap();
    match Fitter::new(&net).tolerance(1e-8).run() {
        Err(Error::FitTolerance {
            vertex,
            distance,
            tolerance,
        }) => {
            assert!(vertex < net.points().len());
            assert!(distance > tolerance && tolerance == 1e-8);
        }
        other => panic!("expected a refusal, got {other:?}"),
    }
    for h in [0.0, -1.0, f64::NAN] {
        let err = Fitter::new(&net).resolution(h).run().unwrap_err();
        assert!(matches!(err.root(), Error::InvalidArgument(_)), "{err}");
    }
}

/// The crease vertices of a triangulation where the crease turns by more
/// than `turn` degrees, a crease being the edges whose two triangles' normals
/// differ by more than `dihedral` degrees: found from the triangles alone.
fn sharp_crease_turns(points: &[DVec3], tris: &[[u32; 3]], dihedral: f64, turn: f64) -> Vec<u32> {
    let normal = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|i| points[i as usize]);
        (b - a).cross(c - a).normalize()
    };
    let mut sides: HashMap<(u32, u32), Vec<DVec3>> = HashMap::new();
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            sides
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push(normal(t));
        }
    }
    let mut hard: HashMap<u32, Vec<u32>> = HashMap::new();
    for (&(a, b), n) in &sides {
        if n.len() == 2 && n[0].angle_between(n[1]).to_degrees() > dihedral {
            hard.entry(a).or_default().push(b);
            hard.entry(b).or_default().push(a);
        }
    }
    let mut found: Vec<u32> = hard
        .iter()
        .filter(|(_, ends)| ends.len() == 2)
        .filter(|(&v, ends)| {
            let p = points[v as usize];
            let (into, out) = (p - points[ends[0] as usize], points[ends[1] as usize] - p);
            into.angle_between(out).to_degrees() > turn
        })
        .map(|(&v, _)| v)
        .collect();
    found.sort_unstable();
    found
}

/// CGAL's fandisk, creased at 30°: the one crease vertex where the crease
/// folds back (turning by 161°; every other turns by 23° at most) is kept
/// as a corner, and the fit passes within 1e-5 of the diagonal of it
/// (5.5e-6 measured; 1.3e-4 when Loop's crease rule rounded it off).
#[test]
fn fandisk_keeps_its_crease_fold() {
    let path = common::cgal_mesh("fandisk.off")
        .unwrap_or_else(|| panic!("fandisk.off not found: run scripts/test.sh"));
    let mut net = ControlNet::read(path).unwrap();
    let expected = sharp_crease_turns(net.points(), net.triangles(), 30.0, 45.0);
    assert_eq!(expected.len(), 1, "{expected:?}");
    net.tag_by_angle(30.0).unwrap();
    assert_eq!(loopsurf::fit::kinks(&net), expected);
    let fit = Fitter::new(&net).tolerance(1.0).run().unwrap();
    assert_eq!(fit.report.kinks, 1);
    let surface = Surface::new(&fit.net).unwrap();
    let fold = net.points()[expected[0] as usize];
    let d = loopsurf::snap::closest_point(&surface, fold)
        .unwrap()
        .distance
        / net.bbox_diagonal();
    assert!(d <= 1e-5, "{d:e}");
}
