//! The model's curves: exact evaluation against the surface on
//! both sides and against dyadic refinement (no shared code: refinement
//! applies the subdivision rules to the whole net), arc length, projection.

mod common;

use common::example;
use loopsurf::model::Curve;
use loopsurf::refine::refine_uniform;
use loopsurf::{ControlNet, DVec3, LimitCurve, Surface};

/// A dart crease: two hard edges (a, b), (b, c) inside the icosphere.
fn darts() -> ControlNet {
    let mut net = example("sphere", None);
    let [a, b, c] = net.triangles()[0];
    net.tag_edge(a, b).unwrap();
    net.tag_edge(b, c).unwrap();
    net
}

/// A longer dart crease (eight edges along a great circle of the sphere)
/// so that it has B-spline segments between the dart segments: segments
/// 2 to 5 have no dart tip in their support (with four edges, every
/// segment had one, and no dart curve was checked at the tight tolerance).
fn long_dart() -> ControlNet {
    let net = example("sphere", None);
    // Walk eight edges greedily from vertex 0 in a roughly straight line.
    let topo = net.topology();
    let mut chain = vec![0u32, topo.ring(0)[0]];
    while chain.len() < 9 {
        let (p, q) = (chain[chain.len() - 2], chain[chain.len() - 1]);
        let dir = net.points()[q as usize] - net.points()[p as usize];
        let next = *topo
            .ring(q as usize)
            .iter()
            .filter(|&&r| !chain.contains(&r))
            .max_by(|&&x, &&y| {
                let d = |r: u32| {
                    (net.points()[r as usize] - net.points()[q as usize])
                        .normalize()
                        .dot(dir)
                };
                d(x).total_cmp(&d(y))
            })
            .unwrap();
        chain.push(next);
    }
    let mut net = net.clone();
    for w in chain.windows(2) {
        net.tag_edge(w[0], w[1]).unwrap();
    }
    net
}

fn nets() -> Vec<(&'static str, ControlNet)> {
    let mut out = vec![
        ("cube", example("cube", Some(30.0))),
        ("viking", example("viking", Some(30.0))),
        ("open-disk", example("open-disk", None)),
        ("darts", darts()),
        ("long-dart", long_dart()),
    ];
    let mut tagged = example("viking", Some(30.0));
    tagged.tag_vertex(net_vertex_on_a_curve(&tagged)).unwrap();
    out.push(("viking-with-a-corner", tagged));
    out
}

/// A vertex on the Viking's first hard circle (tagging it turns that
/// closed loop into an open curve from the corner to itself).
fn net_vertex_on_a_curve(net: &ControlNet) -> u32 {
    net.hard_edges()[0][0]
}

/// The same point from the triangle on each side of the curve: the
/// surface at the point of control edge k at fraction s, and the first and
/// second derivatives along the edge.
fn surface_sides(surface: &Surface, c: &Curve, k: usize, s: f64) -> Vec<[DVec3; 3]> {
    let topo = surface.net().topology();
    let e = c.edges[k] as usize;
    topo.edge_triangles()[e]
        .into_iter()
        .filter(|&t| t != u32::MAX)
        .map(|t| {
            let corners = topo.triangles()[t as usize];
            let uv = |v: u32| {
                let i = corners.iter().position(|&x| x == v).unwrap();
                [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]][i]
            };
            let (a, b) = (uv(c.chain[k]), uv(c.chain[k + 1]));
            let d = [b[0] - a[0], b[1] - a[1]];
            let (v, w) = (a[0] + s * d[0], a[1] + s * d[1]);
            let ev = surface.eval(t as usize, v, w).unwrap();
            [
                ev.x,
                d[0] * ev.xv + d[1] * ev.xw,
                d[0] * d[0] * ev.xvv + 2.0 * d[0] * d[1] * ev.xvw + d[1] * d[1] * ev.xww,
            ]
        })
        .collect()
}

#[test]
fn curves_equal_the_surface_on_both_sides() {
    let mut all = nets();
    if let Some(path) = common::cgal_mesh("fandisk.off") {
        let mut fandisk = ControlNet::read(path).unwrap();
        fandisk.tag_by_angle(30.0).unwrap();
        all.push(("fandisk", fandisk));
    }
    for (name, net) in all {
        let surface = Surface::new(&net).unwrap();
        let diag = net.bbox_diagonal();
        let limits = net.limit_points();
        let model = surface.model();
        assert!(!model.curves().is_empty(), "{name}");
        for (id, c) in model.curves().iter().enumerate() {
            let curve = LimitCurve::new(&surface, id).unwrap();
            for k in 0..c.len() {
                // Integer t: the chain vertex's limit point.
                let at = curve.eval(k as f64).unwrap();
                assert!(
                    (at.x - limits[c.chain[k] as usize]).length() <= 1e-13 * diag,
                    "{name} curve {id} t={k}"
                );
                for s in [0.125, 0.37, 0.5, 0.91] {
                    let e = curve.eval(k as f64 + s).unwrap();
                    for [x, dx, ddx] in surface_sides(&surface, c, k, s) {
                        let scale = diag * c.len() as f64;
                        assert!(
                            (e.x - x).length() <= 1e-12 * diag,
                            "{name} curve {id} t={}: {} vs {x}",
                            k as f64 + s,
                            e.x
                        );
                        assert!(
                            (e.dx - dx).length() <= 1e-11 * scale,
                            "{name} curve {id} t={}: {} vs {dx}",
                            k as f64 + s,
                            e.dx
                        );
                        assert!(
                            (e.ddx - ddx).length() <= 1e-10 * scale,
                            "{name} curve {id} t={}: {} vs {ddx}",
                            k as f64 + s,
                            e.ddx
                        );
                    }
                }
            }
            let end = curve.eval(c.len() as f64).unwrap();
            assert!((end.x - limits[c.chain[c.len()] as usize]).length() <= 1e-13 * diag);
        }
    }
}

/// The chain of curve `c` after `levels` uniform refinements: each control
/// edge (a, b) becomes (a, m, b) with m = old vertex count + edge index.
fn refined_chain(net: &ControlNet, c: &Curve, levels: u32) -> (ControlNet, Vec<u32>) {
    let mut net = net.clone();
    let mut chain = c.chain.clone();
    for _ in 0..levels {
        let topo = net.topology();
        let nv = topo.num_vertices() as u32;
        let mut finer = vec![chain[0]];
        for w in chain.windows(2) {
            let e = topo.find_edge(w[0], w[1]).unwrap() as u32;
            finer.push(nv + e);
            finer.push(w[1]);
        }
        net = refine_uniform(&net, 1).unwrap().into_net();
        chain = finer;
    }
    (net, chain)
}

#[test]
fn curves_match_dyadic_refinement_with_derivatives() {
    const LEVELS: u32 = 4;
    // Segments of dart curves held to the tight tolerance.
    let mut tight_on_darts = 0;
    for (name, net) in nets() {
        let surface = Surface::new(&net).unwrap();
        let diag = net.bbox_diagonal();
        for (id, c) in surface.model().curves().iter().enumerate() {
            let curve = LimitCurve::new(&surface, id).unwrap();
            let (fine, chain) = refined_chain(&net, c, LEVELS);
            let limits = fine.limit_points();
            let step = 1.0 / (1 << LEVELS) as f64;
            // Positions at every dyadic t of level 4.
            let dyadic = |j: usize| limits[chain[j] as usize];
            for j in 0..chain.len() {
                let e = curve.eval(j as f64 * step).unwrap();
                assert!(
                    (e.x - dyadic(j)).length() <= 1e-13 * diag,
                    "{name} curve {id} t={}: {} vs {}",
                    j as f64 * step,
                    e.x,
                    dyadic(j)
                );
            }
            // Derivatives mid-segment by Richardson extrapolation of central
            // differences of those exact points (h = 1/8 and 1/16, inside
            // one segment: exact for a cubic, O(h⁴) next to a dart).
            for k in 0..c.len() {
                let mid = 16 * k + 8;
                let d1 = |h: usize| (dyadic(mid + h) - dyadic(mid - h)) / (2.0 * h as f64 * step);
                let d2 = |h: usize| {
                    (dyadic(mid + h) - 2.0 * dyadic(mid) + dyadic(mid - h))
                        / (h as f64 * step).powi(2)
                };
                let dx = (4.0 * d1(1) - d1(2)) / 3.0;
                let ddx = (4.0 * d2(1) - d2(2)) / 3.0;
                let e = curve.eval(k as f64 + 0.5).unwrap();
                let near_dart = is_near_dart(&surface, c, k);
                let on_dart_curve = (0..c.len()).any(|j| is_near_dart(&surface, c, j));
                tight_on_darts += usize::from(on_dart_curve && !near_dart);
                let tol = if near_dart { 1e-4 } else { 1e-11 };
                let scale = diag * c.len() as f64;
                assert!(
                    (e.dx - dx).length() <= tol * scale,
                    "{name} curve {id} k={k}: {} vs {dx}",
                    e.dx
                );
                assert!(
                    (e.ddx - ddx).length() <= 10.0 * tol * scale,
                    "{name} curve {id} k={k}: {} vs {ddx}",
                    e.ddx
                );
            }
        }
    }
    assert!(
        tight_on_darts >= 4,
        "only {tight_on_darts} segments of dart curves held to 1e-11"
    );
}

/// Whether segment k's B-spline support holds a dart tip (the curve there
/// is not a cubic).
fn is_near_dart(surface: &Surface, c: &Curve, k: usize) -> bool {
    let kinds = surface.net().vertex_kinds();
    let dart = |j: usize| kinds[c.chain[j] as usize] == loopsurf::VertexKind::Dart;
    !c.is_closed() && ((k <= 1 && dart(0)) || (k + 2 >= c.len() && dart(c.len())))
}

#[test]
fn arc_length_matches_refined_polylines_and_inverts() {
    for (name, net) in nets() {
        let surface = Surface::new(&net).unwrap();
        for (id, c) in surface.model().curves().iter().enumerate() {
            let curve = LimitCurve::new(&surface, id).unwrap();
            let n = c.len() as f64;
            let total = curve.length(0.0, n).unwrap();
            // Additive over segments, antisymmetric.
            let sum: f64 = (0..c.len())
                .map(|k| curve.length(k as f64, k as f64 + 1.0).unwrap())
                .sum();
            assert!((sum - total).abs() <= 1e-13 * total, "{name} curve {id}");
            assert_eq!(curve.length(n, 0.0).unwrap(), -total);
            // Independent: polylines through the exact dyadic limit points
            // of levels 5 and 6, Richardson-extrapolated (error O(h⁴)).
            let poly = |levels: u32| {
                let (fine, chain) = refined_chain(&net, c, levels);
                let l = fine.limit_points();
                chain
                    .windows(2)
                    .map(|w| (l[w[1] as usize] - l[w[0] as usize]).length())
                    .sum::<f64>()
            };
            let reference = (4.0 * poly(6) - poly(5)) / 3.0;
            let dart = (0..c.len()).any(|k| is_near_dart(&surface, c, k));
            let tol = if dart { 1e-5 } else { 1e-8 };
            assert!(
                (total - reference).abs() <= tol * total,
                "{name} curve {id}: {total} vs {reference}"
            );
            // The inverse: equally spaced points come back to their lengths.
            for i in 0..=7 {
                let s = total * i as f64 / 7.0;
                let t = curve.param_at_length(s).unwrap();
                let back = curve.length(0.0, t).unwrap();
                assert!(
                    (back - s).abs() <= 1e-12 * total,
                    "{name} curve {id}: {s} → t {t} → {back}"
                );
            }
            assert!(curve.param_at_length(1.01 * total).is_err());
        }
    }
}

#[test]
fn points_of_a_curve_map_to_both_faces() {
    for (name, net) in nets() {
        let surface = Surface::new(&net).unwrap();
        let diag = net.bbox_diagonal();
        let model = surface.model();
        for (id, c) in model.curves().iter().enumerate() {
            let curve = LimitCurve::new(&surface, id).unwrap();
            for t in [0.0, 0.3, c.len() as f64 * 0.5 + 0.1, c.len() as f64] {
                let x = curve.eval(t).unwrap().x;
                let sides = curve.surface_points(t).unwrap();
                let faces: Vec<u32> = c.faces.iter().flatten().copied().collect();
                assert_eq!(
                    sides.iter().map(|s| s.0).collect::<Vec<_>>(),
                    faces,
                    "{name} curve {id}"
                );
                for (face, sp) in sides {
                    assert_eq!(model.face_of_triangle()[sp.tri as usize], face);
                    let y = surface.point(sp.tri as usize, sp.v, sp.w).unwrap();
                    assert!((x - y).length() <= 1e-12 * diag, "{name} curve {id} t={t}");
                }
            }
        }
    }
}

#[test]
fn projection_finds_the_nearest_curve_point_with_a_certificate() {
    for (name, net) in nets() {
        let surface = Surface::new(&net).unwrap();
        let diag = net.bbox_diagonal();
        let mut rng = common::Lcg(11);
        for (id, c) in surface.model().curves().iter().enumerate() {
            let curve = LimitCurve::new(&surface, id).unwrap();
            let n = c.len() as f64;
            for _ in 0..6 {
                let p = curve.eval(rng.next() * n).unwrap().x + 0.2 * diag * rng.direction();
                let snap = curve.closest_point(p).unwrap();
                // Brute force over a fine sampling: never nearer than the
                // answer, beyond the sampling's reach.
                let brute = (0..=400 * c.len())
                    .map(|i| (curve.eval(i as f64 / 400.0).unwrap().x - p).length())
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    snap.distance <= brute + 1e-12 * diag,
                    "{name} curve {id}: {snap:?} vs {brute}"
                );
                assert!(snap.lower_bound <= snap.distance);
                let dart = (0..c.len()).any(|k| is_near_dart(&surface, c, k));
                if !dart {
                    assert!(
                        snap.distance - snap.lower_bound <= 1e-12 * diag,
                        "{name} curve {id}: {snap:?}"
                    );
                }
                // Local projection from the answer's neighbourhood lands on it.
                let local = curve.project(p, (snap.t + 0.05).min(n)).unwrap();
                assert!(
                    (local.distance - snap.distance).abs() <= 1e-10 * diag,
                    "{name} {id}: {local:?} vs {snap:?}"
                );
                // A point on the curve projects to itself.
                let t = rng.next() * n;
                let on = curve.eval(t).unwrap().x;
                let back = curve.closest_point(on).unwrap();
                assert!(back.distance <= 1e-12 * diag, "{name} curve {id}: {back:?}");
            }
        }
    }
}
