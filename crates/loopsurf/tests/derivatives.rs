//! First and second derivatives next to special vertices (valence 3, 4, 7
//! and 40, darts, corners, boundaries) against differences of exact dyadic
//! limit points: the net refined 7 times by the subdivision rules, every
//! vertex pushed to the limit with the limit masks, and remembered at its
//! control triangle's (v, w) — no evaluator code. Central differences with
//! steps 2⁻⁶ and 2⁻⁷ inside one polynomial piece, combined by Richardson
//! extrapolation (error O(h⁴)); a wrong factor, sign or ring would miss by
//! orders of magnitude more than the tolerance.

mod common;

use common::{bicone, example};
use loopsurf::refine::refine_uniform;
use loopsurf::{ControlNet, DVec3, Surface, VertexKind};
use std::collections::HashMap;

const LEVELS: u32 = 7;
const SCALE: f64 = (1u32 << LEVELS) as f64;

/// Exact limit points by control triangle and dyadic (i, j) = 2⁷ (v, w).
fn dyadic_limits(net: &ControlNet) -> HashMap<(u32, u32, u32), DVec3> {
    let refined = refine_uniform(net, LEVELS).unwrap();
    refined
        .limit_points()
        .into_iter()
        .zip(refined.origins())
        .filter_map(|(x, o)| {
            let o = o?;
            Some(((o.tri, (o.v * SCALE) as u32, (o.w * SCALE) as u32), x))
        })
        .collect()
}

/// Checks X's derivatives at points of the first ring around each special
/// corner.
fn check(name: &str, net: &ControlNet) {
    let surface = Surface::new(net).unwrap();
    let limits = dyadic_limits(net);
    let kinds = net.vertex_kinds();
    let topo = net.topology();
    let special = |v: usize| {
        kinds[v] != VertexKind::Smooth || topo.valence(v) != 6 || topo.is_boundary_vertex(v)
    };
    let mut checked = 0;
    let mut worst: f64 = 0.0;
    for (t, tri) in net.triangles().iter().enumerate() {
        for (k, &corner) in tri.iter().enumerate() {
            if !special(corner as usize) {
                continue;
            }
            // Offsets (a, b) from corner k along its two sides, in 1/32:
            // inside the three regular cells of the first ring around it
            // (the corner's level-1 child less its own corner child), each
            // one polynomial, with the whole stencil inside the cell so that
            // the differences see a smooth function.
            for (a, b) in [(10, 2), (2, 10), (6, 6)] {
                let (da, db) = (a as f64 / 32.0, b as f64 / 32.0);
                let (v, w) = match k {
                    0 => (da, db),
                    1 => (1.0 - da - db, da),
                    _ => (db, 1.0 - da - db),
                };
                // Every stencil point inside the triangle, off its sides.
                let h = 1.0 / 64.0;
                if v - h <= 0.0 || w - h <= 0.0 || v + w + 2.0 * h >= 1.0 {
                    continue;
                }
                let at = |dv: f64, dw: f64| {
                    let key = (
                        t as u32,
                        ((v + dv) * SCALE) as u32,
                        ((w + dw) * SCALE) as u32,
                    );
                    *limits
                        .get(&key)
                        .unwrap_or_else(|| panic!("{name}: no dyadic point {key:?}"))
                };
                // Central differences at step h, then Richardson on h, h/2.
                let differences = |h: f64| {
                    let x = at(0.0, 0.0);
                    [
                        (at(h, 0.0) - at(-h, 0.0)) / (2.0 * h),
                        (at(0.0, h) - at(0.0, -h)) / (2.0 * h),
                        (at(h, 0.0) - 2.0 * x + at(-h, 0.0)) / (h * h),
                        (at(h, h) - at(h, -h) - at(-h, h) + at(-h, -h)) / (4.0 * h * h),
                        (at(0.0, h) - 2.0 * x + at(0.0, -h)) / (h * h),
                    ]
                };
                let (coarse, fine) = (differences(h), differences(h / 2.0));
                let e = surface.eval(t, v, w).unwrap();
                let exact = [e.xv, e.xw, e.xvv, e.xvw, e.xww];
                let size = exact[..2].iter().map(|d| d.length()).fold(0.0, f64::max);
                for (i, d) in exact.iter().enumerate() {
                    let reference = (4.0 * fine[i] - coarse[i]) / 3.0;
                    // Second derivatives are compared at the scale of the
                    // first ones (per unit parameter), both to 1e-9.
                    let error = (reference - *d).length() / size.max(d.length());
                    worst = worst.max(error);
                    assert!(
                        error < 1e-9,
                        "{name}: triangle {t}, corner {k} ({:?}), (v, w) = ({v}, {w}), derivative {i}: \
                         evaluator {d} against differences {reference} ({error:e})",
                        kinds[corner as usize]
                    );
                }
                checked += 1;
            }
        }
    }
    eprintln!("{name}: {checked} points, worst relative difference {worst:e}");
    assert!(
        checked >= 4,
        "{name}: only {checked} points near special vertices"
    );
}

#[test]
fn valence_3_and_boundaries() {
    check("tetrahedron (valence 3)", &example("tetra", None));
    check(
        "open disk (boundary, valence 3 and 4)",
        &example("open-disk", None),
    );
}

#[test]
fn corners_creases_and_high_valence() {
    check("cube 30° (corners, creases)", &example("cube", Some(30.0)));
    check("bicone of valence 7", &bicone(7, false));
    check("bicone of valence 40", &bicone(40, false));
    let mut dart = bicone(7, false);
    let [a, b] = dart.topology().edges()[0];
    dart.tag_edge(a, b).unwrap();
    assert!(dart.vertex_kinds().contains(&VertexKind::Dart));
    check("bicone with a dart", &dart);
}

/// The normal exactly at a special vertex is the normal its sector tends
/// to from inside the triangle: the normals inside approach it (at a crease
/// of fandisk only about 0.9 a level). CGAL's cross.off and joint.off at
/// 30° have corners where three creases meet next to reflex sectors: there
/// the tangent masks once gave normals 45° off (cross) or reversed (joint),
/// which the normals inside kept at that angle. (0.05° is the round-off
/// floor of normals 2^-60 from a corner.)
///
/// A sector whose two tangents inside are parallel to first order (the
/// sine of their angle below 1e-6 at 2^-30: fandisk has one, triangle
/// 186 at (1, 0)) has its normal from second order only, and the normals
/// computed inside it are round-off by 2^-50 (0.3° there, none at 2^-60):
/// those corners are counted, not compared, and at most one per mesh is
/// allowed.
#[test]
fn normals_at_special_vertices_are_the_sector_limits() {
    for name in ["cross.off", "joint.off", "fandisk.off"] {
        let Some(path) = common::cgal_mesh(name) else {
            return;
        };
        let mut net = ControlNet::read(path).unwrap();
        net.tag_by_angle(30.0).unwrap();
        let surface = Surface::new(&net).unwrap();
        let (mut checked, mut singular) = (0, 0);
        for t in 0..net.triangles().len() {
            for (v, w) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)] {
                let Ok(n) = surface.normal(t, v, w) else {
                    continue;
                };
                let at = |levels: i32| {
                    let h = 0.5f64.powi(levels);
                    (v + h * (1.0 / 3.0 - v), w + h * (1.0 / 3.0 - w))
                };
                let (a, b) = at(30);
                let e = surface.eval(t, a, b).unwrap();
                if e.xv.cross(e.xw).length() < 1e-6 * e.xv.length() * e.xw.length() {
                    singular += 1;
                    continue;
                }
                let angle = |levels: i32| {
                    let (a, b) = at(levels);
                    let inside = surface.normal(t, a, b).unwrap();
                    n.angle_between(inside).to_degrees()
                };
                let (far, near) = (angle(30), angle(60));
                assert!(
                    near <= 0.05 || near < 0.99 * far,
                    "{name}: triangle {t} at ({v}, {w}): {far}° at 2^-30, {near}° at 2^-60"
                );
                checked += 1;
            }
        }
        assert!(checked > net.triangles().len(), "{name}: {checked}");
        assert!(singular <= 1, "{name}: {singular} sectors without tangents");
    }
}
