//! Regular patches, crease and boundary phantoms included, against the
//! exact dyadic reference: limit positions of refined vertices.

use super::{box_spline, regular};
use crate::features::VertexKind;
use crate::refine::refine_uniform;
use crate::{examples, ControlNet, DVec3};

/// (patches with only real points, patches with phantoms) checked; panics
/// on any point off the reference by more than 1e-13 of the diagonal.
fn check_regular_patches(net: &ControlNet, levels: u32) -> (usize, usize) {
    let kinds = net.vertex_kinds();
    let stencils: Vec<Option<[regular::Source; 12]>> = (0..net.triangles().len())
        .map(|t| regular::stencil(net.topology(), net.features(), &kinds, t))
        .collect();
    let refined = refine_uniform(net, levels).unwrap();
    let limits = refined.limit_points();
    let diag = net.bbox_diagonal();
    let (mut plain, mut phantom) = (0, 0);
    for (origin, limit) in refined.origins().zip(&limits) {
        let Some(o) = origin else { continue };
        let Some(s) = &stencils[o.tri as usize] else {
            continue;
        };
        let wts = box_spline::weights(o.v, o.w)[0];
        let x: DVec3 = s
            .iter()
            .zip(wts)
            .map(|(p, w)| w * p.position(net.points()))
            .sum();
        let err = (x - *limit).length();
        assert!(
            err <= 1e-13 * diag,
            "patch {} at ({}, {}) off by {:e} of the diagonal: {s:?}",
            o.tri,
            o.v,
            o.w,
            err / diag
        );
        if s.iter()
            .any(|p| matches!(p, regular::Source::Phantom { .. }))
        {
            phantom += 1;
        } else {
            plain += 1;
        }
    }
    (plain, phantom)
}

#[path = "../../tests/support/cgal_data.rs"]
mod cgal_data;

/// A CGAL demo mesh with edges over `angle` degrees hard; `None` only when
/// the data is absent and `LOOPSURF_SKIP_DATA` asks to skip.
fn cgal(name: &str, angle: Option<f64>) -> Option<ControlNet> {
    let path = cgal_data::cgal_file(name)?;
    let mut net = ControlNet::read(&path).unwrap();
    if let Some(deg) = angle {
        net.tag_by_angle(deg).unwrap();
    }
    Some(net)
}

/// Nets with every kind of special vertex: a valence-9 dart and a crease
/// loop with irregular crease vertices, valence 3, cube corners, an
/// irregular boundary, valence 80.
fn every_kind_of_net() -> Vec<ControlNet> {
    let mut cone = bicone(9);
    cone.tag_edge(0, 1).unwrap();
    for i in 0..9u32 {
        cone.tag_edge(10 + i, 10 + (i + 1) % 9).unwrap();
    }
    vec![
        cone,
        example("tetra", None),
        example("cube", Some(30.0)),
        example("open-disk", None),
        bicone(80),
    ]
}

fn example(name: &str, hard_angle: Option<f64>) -> ControlNet {
    let ex = examples::by_name(name).unwrap();
    let mut net = ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
    if let Some(deg) = hard_angle {
        net.tag_by_angle(deg).unwrap();
    }
    net
}

#[test]
fn smooth_regular_patches_are_box_splines() {
    let torus = example("torus", None);
    let (plain, phantom) = check_regular_patches(&torus, 3);
    // Every triangle of the torus is regular: every refined vertex checked.
    assert_eq!(plain, refine_uniform(&torus, 3).unwrap().origins().len());
    assert_eq!(phantom, 0);
}

#[test]
fn crease_patches_use_reflected_phantoms() {
    let (plain, phantom) = check_regular_patches(&example("viking", Some(30.0)), 3);
    assert!(plain > 0 && phantom > 1000, "{plain} {phantom}");
}

#[test]
fn boundary_patches_use_reflected_phantoms() {
    let (plain, phantom) = check_regular_patches(&example("open-disk", None), 3);
    assert!(phantom > 0, "{plain} {phantom}");
}

#[test]
fn cgal_regular_patches() {
    for (name, angle) in [
        ("fandisk.off", Some(40.0)),
        ("pig.off", None),
        ("bunny00.off", None),
    ] {
        let Some(net) = cgal(name, angle) else { return };
        let (plain, phantom) = check_regular_patches(&net, 2);
        eprintln!("{name}: {plain} plain, {phantom} phantom");
        assert!(plain > 0);
    }
}

/// Every refined vertex of `levels` levels: the evaluator's position equals
/// its exact limit position. Returns how many points were checked.
fn check_evaluator(net: &ControlNet, levels: u32) -> usize {
    let eval = super::surface::Evaluator::new(net).unwrap();
    let refined = refine_uniform(net, levels).unwrap();
    let limits = refined.limit_points();
    let diag = net.bbox_diagonal();
    let mut checked = 0;
    for (origin, limit) in refined.origins().zip(&limits) {
        let Some(o) = origin else { continue };
        let Ok(d) = eval.eval(o.tri as usize, o.v, o.w) else {
            continue;
        };
        let err = (d[0] - *limit).length();
        assert!(
            err <= 1e-12 * diag,
            "triangle {} at ({}, {}) off by {:e} of the diagonal: {}",
            o.tri,
            o.v,
            o.w,
            err / diag,
            eval.describe(o.tri as usize, o.v, o.w)
        );
        assert!(d.iter().all(|x| x.is_finite()));
        checked += 1;
    }
    checked
}

#[test]
fn evaluator_matches_the_reference_on_every_vertex_kind() {
    let tetra = example("tetra", None);
    assert!(check_evaluator(&tetra, 4) > 0);
    let mut cone = bicone(9);
    cone.tag_edge(0, 1).unwrap(); // a dart at the apex
    cone.tag_vertex(12).unwrap(); // a corner on the upper ring
    for i in 0..9u32 {
        cone.tag_edge(10 + i, 10 + (i + 1) % 9).unwrap(); // a crease loop
    }
    cone.tag_edge(1, 10).unwrap(); // three hard edges at 10: a corner
    let kinds = cone.vertex_kinds();
    assert_eq!(
        (kinds[0], kinds[10], kinds[11]),
        (VertexKind::Dart, VertexKind::Corner, VertexKind::Crease)
    );
    assert!(check_evaluator(&cone, 4) > 0);
    assert!(check_evaluator(&example("cube", Some(30.0)), 3) > 0);
    assert!(check_evaluator(&example("open-disk", None), 4) > 0);
    assert!(check_evaluator(&example("viking", Some(30.0)), 2) > 0);
}

#[test]
fn evaluator_matches_the_reference_at_high_valence() {
    for n in [7, 8, 10, 11, 12] {
        assert!(check_evaluator(&bicone(n), 4) > 0);
    }
    assert!(check_evaluator(&bicone(80), 4) > 0);
}

#[test]
fn evaluator_matches_the_reference_on_cgal_meshes() {
    for (name, angle) in [
        ("fandisk.off", Some(40.0)),
        ("pig.off", None),
        ("cow.off", Some(60.0)),
    ] {
        let Some(net) = cgal(name, angle) else { return };
        assert!(check_evaluator(&net, 4) > 0);
    }
}

/// The closed wavy bicone of [`examples::bicone`] with apexes of valence n.
fn bicone(n: usize) -> ControlNet {
    let ex = examples::bicone(n, false);
    ControlNet::from_arrays(ex.points, &ex.tris).unwrap()
}

#[test]
fn special_matrices_reproduce_one_subdivision_step() {
    // Around a boundary vertex with two triangles, a dart, and valence 3.
    let mut cone = bicone(9);
    cone.tag_edge(0, 1).unwrap();
    let cases = [
        (example("open-disk", None), 33u32),
        (cone, 0),
        (example("tetra", None), 0),
    ];
    for (net, c) in cases {
        let l1 = refine_uniform(&net, 1).unwrap().into_net();
        let l2 = refine_uniform(&l1, 1).unwrap().into_net();
        let topo = l1.topology();
        let (p, q) = {
            let t = topo.fan(c as usize)[0] as usize;
            let tri = topo.triangles()[t];
            let k = tri.iter().position(|&x| x == c).unwrap();
            (tri[(k + 1) % 3], tri[(k + 2) % 3])
        };
        let (patch, k0) = super::special::patch_at(topo, l1.features(), [c, p, q]);
        let mid = |a: u32, b: u32| l1.points().len() as u32 + topo.find_edge(a, b).unwrap() as u32;
        let k1 = super::special::neighbourhood(l2.topology(), c, mid(c, p), mid(c, q));
        let x0: Vec<DVec3> = k0.iter().map(|&i| l1.points()[i as usize]).collect();
        let diag = net.bbox_diagonal();
        for (x, &g) in patch.step(&x0).iter().zip(&k1) {
            let err = (*x - l2.points()[g as usize]).length();
            assert!(err < 1e-13 * diag, "vertex {c}: {err:e}");
        }
    }
}

/// Keeps the triangles with a vertex within three edges of `c`, with their
/// tags; returns the smaller net and the new indices of `keep`.
fn crop(net: &ControlNet, c: u32, keep: &[u32]) -> (ControlNet, Vec<u32>) {
    let topo = net.topology();
    let mut dist = vec![u32::MAX; topo.num_vertices()];
    dist[c as usize] = 0;
    let mut queue = std::collections::VecDeque::from([c]);
    while let Some(v) = queue.pop_front() {
        for &n in topo.ring(v as usize) {
            if dist[n as usize] == u32::MAX {
                dist[n as usize] = dist[v as usize] + 1;
                queue.push_back(n);
            }
        }
    }
    let mut label = vec![u32::MAX; topo.num_vertices()];
    let mut points = Vec::new();
    let mut tris = Vec::new();
    for tri in topo.triangles() {
        if tri.iter().any(|&v| dist[v as usize] <= 3) {
            tris.push(tri.map(|v| {
                if label[v as usize] == u32::MAX {
                    label[v as usize] = points.len() as u32;
                    points.push(net.points()[v as usize]);
                }
                label[v as usize]
            }));
        }
    }
    // No geometric validation: deep down, round-off makes flat-looking triangles.
    let small_topo = crate::topology::Topology::new(points.len(), tris).unwrap();
    let mut features = crate::features::Features::new(&small_topo);
    for [a, b] in net.hard_edges() {
        if label[a as usize] != u32::MAX && label[b as usize] != u32::MAX {
            let _ = features.tag_edge(&small_topo, label[a as usize], label[b as usize]);
        }
    }
    for (v, &l) in label.iter().enumerate() {
        if net.features().is_tagged_vertex(v) && l != u32::MAX {
            features.tag_vertex(l).unwrap();
        }
    }
    let small = ControlNet::from_parts(points, small_topo, features);
    (small, keep.iter().map(|&v| label[v as usize]).collect())
}

/// Points 2^-1 … 2^-depth from special vertex `c` of control triangle `t`,
/// along the edge to the next corner and along the diagonal, against the
/// limit positions of vertices of a refinement cropped around `c`.
fn check_near_vertex(net: &ControlNet, (t, corner): (usize, usize), depth: u32) {
    let eval = super::surface::Evaluator::new(net).unwrap();
    let diag = net.bbox_diagonal();
    let tri = net.triangles()[t];
    let (c, p, q) = (tri[corner], tri[(corner + 1) % 3], tri[(corner + 2) % 3]);
    let params = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)];
    let (pc, pp, pq) = (
        params[corner],
        params[(corner + 1) % 3],
        params[(corner + 2) % 3],
    );
    let at = |a: f64, b: f64| {
        (
            pc.0 + a * (pp.0 - pc.0) + b * (pq.0 - pc.0),
            pc.1 + a * (pp.1 - pc.1) + b * (pq.1 - pc.1),
        )
    };
    let (mut fine, mut ids) = crop(net, c, &[c, p, q]);
    for k in 1..=depth {
        let step = refine_uniform(&fine, 1).unwrap().into_net();
        let topo = fine.topology();
        let n0 = fine.points().len() as u32;
        let mid = |a: u32, b: u32| n0 + topo.find_edge(a, b).unwrap() as u32;
        let (pk, qk) = (mid(ids[0], ids[1]), mid(ids[0], ids[2]));
        (fine, ids) = crop(&step, ids[0], &[ids[0], pk, qk]);
        let limits = fine.limit_points();
        // Along the edge: (2^-k, 0); across: the vertex opposite c beyond pk–qk.
        let h = (-(k as f64)).exp2();
        let (v, w) = at(h, 0.0);
        let along = eval.eval(t, v, w).unwrap()[0];
        let err = (along - limits[ids[1] as usize]).length();
        assert!(
            err <= 1e-12 * diag,
            "2^-{k} along an edge: off by {:e}",
            err / diag
        );
        let ftopo = fine.topology();
        let e = ftopo.find_edge(ids[1], ids[2]).unwrap();
        let far = ftopo.edge_triangles()[e]
            .iter()
            .map(|&t| ftopo.triangles()[t as usize])
            .flat_map(|t| t.into_iter())
            .find(|&v| v != ids[0] && v != ids[1] && v != ids[2])
            .unwrap();
        let (v, w) = at(h, h);
        let across = eval.eval(t, v, w).unwrap()[0];
        let err = (across - limits[far as usize]).length();
        assert!(
            err <= 1e-12 * diag,
            "2^-{k} inside: off by {:e}",
            err / diag
        );
    }
}

#[test]
fn exact_down_to_2_pow_minus_40_from_special_vertices() {
    // Past 2^-127 the largest cached power is applied more than once.
    check_near_vertex(&example("tetra", None), (0, 0), 200);
    let mut cone = bicone(9);
    cone.tag_edge(0, 1).unwrap();
    check_near_vertex(&cone, (0, 0), 200);
    check_near_vertex(&bicone(12), (0, 0), 40);
    check_near_vertex(&bicone(80), (0, 0), 40);
    // A corner, an irregular crease vertex and an irregular boundary vertex.
    let first_at = |net: &ControlNet, kind: VertexKind, valence: Option<usize>| {
        let kinds = net.vertex_kinds();
        (0..3 * net.triangles().len())
            .map(|i| (i / 3, i % 3))
            .find(|&(t, k)| {
                let v = net.triangles()[t][k] as usize;
                kinds[v] == kind && valence.is_none_or(|n| net.topology().valence(v) == n)
            })
            .expect("a triangle with that corner")
    };
    let cube = example("cube", Some(30.0));
    check_near_vertex(&cube, first_at(&cube, VertexKind::Corner, None), 40);
    let mut creased = bicone(9);
    for i in 0..9u32 {
        creased.tag_edge(10 + i, 10 + (i + 1) % 9).unwrap();
    }
    let valence = creased.topology().valence(10);
    assert_ne!(valence, 6);
    check_near_vertex(
        &creased,
        first_at(&creased, VertexKind::Crease, Some(valence)),
        40,
    );
    let disk = example("open-disk", None);
    check_near_vertex(&disk, first_at(&disk, VertexKind::Crease, Some(3)), 40);
}

/// First and second derivatives against central differences of the
/// evaluator's own positions (and first derivatives), inside regular and
/// special patches, with creases, corners, darts and boundaries.
#[test]
fn derivatives_match_central_differences() {
    for net in every_kind_of_net() {
        let eval = super::surface::Evaluator::new(&net).unwrap();
        let h: f64 = 1e-6;
        let scale = net.bbox_diagonal();
        for t in 0..net.triangles().len() {
            for &(v, w) in &[
                (0.2, 0.3),
                (0.01, 0.02),
                (0.6, 0.15),
                (0.3, 0.6),
                (0.26, 0.26),
                (0.0004, 0.0003),
            ] {
                let at = |v: f64, w: f64| eval.eval(t, v, w).unwrap();
                let d = at(v, w);
                let hv = h.min(v / 2.0);
                let hw = h.min(w / 2.0);
                let dv = (at(v + hv, w)[0] - at(v - hv, w)[0]) / (2.0 * hv);
                let dw = (at(v, w + hw)[0] - at(v, w - hw)[0]) / (2.0 * hw);
                let dvv = (at(v + hv, w)[1] - at(v - hv, w)[1]) / (2.0 * hv);
                let dvw = (at(v, w + hw)[1] - at(v, w - hw)[1]) / (2.0 * hw);
                let dww = (at(v, w + hw)[2] - at(v, w - hw)[2]) / (2.0 * hw);
                let first = d[1].length().max(d[2].length()).max(scale);
                let second = d[3]
                    .length()
                    .max(d[4].length())
                    .max(d[5].length())
                    .max(scale);
                for (name, got, want, size) in [
                    ("Xv", d[1], dv, first),
                    ("Xw", d[2], dw, first),
                    ("Xvv", d[3], dvv, second),
                    ("Xvw", d[4], dvw, second),
                    ("Xww", d[5], dww, second),
                ] {
                    let err = (got - want).length() / size;
                    // Central differences straddle patch seams and, next to a special
                    // vertex, fast-growing second derivatives: 1e-5 leaves room for
                    // that while any wrong chain rule is off by order one.
                    assert!(
                        err < 1e-5,
                        "{name} of triangle {t} at ({v}, {w}): {got} vs {want}"
                    );
                }
            }
        }
    }
}

/// The same point of a control edge evaluated from its two triangles: the
/// same position, and across smooth edges the same normal.
#[test]
fn neighbours_agree_along_shared_edges() {
    let params = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)];
    for net in every_kind_of_net() {
        let eval = super::surface::Evaluator::new(&net).unwrap();
        let topo = net.topology();
        let diag = net.bbox_diagonal();
        for (e, &[a, b]) in topo.edges().iter().enumerate() {
            let [t0, t1] = topo.edge_triangles()[e];
            if t1 == crate::topology::NONE {
                continue;
            }
            let at = |t: u32, x: f64| {
                let c = topo.triangles()[t as usize];
                let (pa, pb) = (
                    params[c.iter().position(|&v| v == a).unwrap()],
                    params[c.iter().position(|&v| v == b).unwrap()],
                );
                eval.eval(
                    t as usize,
                    pa.0 + x * (pb.0 - pa.0),
                    pa.1 + x * (pb.1 - pa.1),
                )
                .unwrap()
            };
            for x in [0.5f64.powi(30), 0.1, 0.25, 0.5, 0.7, 1.0 - 0.5f64.powi(20)] {
                let (d0, d1) = (at(t0, x), at(t1, x));
                assert!(
                    (d0[0] - d1[0]).length() <= 1e-13 * diag,
                    "edge ({a}, {b}) at {x}"
                );
                if !net.features().is_hard_edge(e) {
                    let (n0, n1) = (
                        d0[1].cross(d0[2]).normalize(),
                        d1[1].cross(d1[2]).normalize(),
                    );
                    assert!(
                        (n0 - n1).length() < 1e-9,
                        "normals across ({a}, {b}) at {x}: {n0} {n1}"
                    );
                }
            }
        }
    }
}

/// Every corner, edge midpoint and centre of every triangle of real meshes
/// (hard edges, darts, corners, boundaries): finite records, no NaN, and
/// normals wherever the surface has a tangent plane.
#[test]
fn no_nan_anywhere_on_cgal_meshes() {
    for (name, angle) in [("fandisk.off", Some(40.0)), ("pig.off", None)] {
        let Some(net) = cgal(name, angle) else { return };
        let surface = crate::Surface::new(&net).unwrap();
        for t in 0..net.triangles().len() {
            for (v, w) in [
                (0.0, 0.0),
                (1.0, 0.0),
                (0.0, 1.0),
                (0.5, 0.0),
                (0.5, 0.5),
                (0.0, 0.5),
                (1.0 / 3.0, 1.0 / 3.0),
            ] {
                let e = surface.eval(t, v, w).unwrap();
                assert!(
                    e.record().iter().all(|x| x.is_finite()),
                    "{name} triangle {t} at ({v}, {w})"
                );
                let k = surface.curvature(t, v, w).unwrap();
                assert!(
                    k.record().iter().all(|x| x.is_finite())
                        && k.mean.is_finite()
                        && k.gaussian.is_finite()
                );
                if let Ok(n) = surface.normal(t, v, w) {
                    assert!(
                        (n.length() - 1.0).abs() < 1e-12,
                        "{name} triangle {t} at ({v}, {w}): normal {n}"
                    );
                }
            }
        }
    }
}

/// Triangles whose three edges are all hard (a lone triangle, a tetrahedron
/// with every edge a crease): every kind of corner at once.
#[test]
fn all_hard_triangles() {
    let lone =
        ControlNet::from_arrays(vec![DVec3::ZERO, DVec3::X, DVec3::Y], &[[0, 1, 2]]).unwrap();
    let mut tetra = example("tetra", None);
    tetra.tag_by_angle(1.0).unwrap();
    let mut strip = example("open-disk", None);
    strip.tag_by_angle(0.0).unwrap();
    for net in [lone, tetra, strip] {
        assert!(check_evaluator(&net, 3) > 0);
    }
}

/// The normal exactly at a special vertex is the limit of the normals of
/// its sector as points approach it.
#[test]
fn vertex_normals_are_limits_of_sector_normals() {
    let mut dart = bicone(9);
    dart.tag_edge(0, 1).unwrap();
    let mut creased = bicone(9);
    for i in 0..9u32 {
        creased.tag_edge(10 + i, 10 + (i + 1) % 9).unwrap();
    }
    let cube = example("cube", Some(30.0));
    let disk = example("open-disk", None);
    let corner_of_kind = |net: &ControlNet, kind: VertexKind| {
        let kinds = net.vertex_kinds();
        (0..3 * net.triangles().len())
            .map(|i| (i / 3, i % 3))
            .find(|&(t, k)| {
                kinds[net.triangles()[t][k] as usize] == kind
                    && net.topology().valence(net.triangles()[t][k] as usize) != 6
            })
            .unwrap()
    };
    let cases = [
        (example("tetra", None), (0, 0)),
        (dart.clone(), (0, 0)),
        (
            creased.clone(),
            corner_of_kind(&creased, VertexKind::Crease),
        ),
        (cube.clone(), corner_of_kind(&cube, VertexKind::Corner)),
        (disk.clone(), corner_of_kind(&disk, VertexKind::Crease)),
    ];
    let params = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)];
    for (net, (t, corner)) in cases {
        let surface = crate::Surface::new(&net).unwrap();
        let (pc, pp, pq) = (
            params[corner],
            params[(corner + 1) % 3],
            params[(corner + 2) % 3],
        );
        let at = |h: f64| {
            (
                pc.0 + h * (pp.0 - pc.0) + h * (pq.0 - pc.0),
                pc.1 + h * (pp.1 - pc.1) + h * (pq.1 - pc.1),
            )
        };
        let n = surface.normal(t, pc.0, pc.1).unwrap();
        let angle = |k: i32| {
            let (v, w) = at(0.5f64.powi(k));
            surface.normal(t, v, w).unwrap().angle_between(n)
        };
        // Geometric convergence, slow at a dart (about 0.85 a level): a wrong
        // vertex normal would leave the angle stuck instead.
        let (near, nearer) = (angle(10), angle(40));
        assert!(
            nearer < 1e-2 && nearer <= near * 0.05 + 1e-12,
            "triangle {t}: {near} -> {nearer}"
        );
    }
}

/// Closer than 2^-256 a point is its special vertex: the exact limit, no
/// NaN, down to the smallest subnormal parameters.
#[test]
fn points_at_the_bottom_of_the_double_range() {
    let net = bicone(80);
    let surface = crate::Surface::new(&net).unwrap();
    let apex = net.limit_points()[0];
    for h in [1e-70, 1e-80, 1e-200, 1e-310, f64::from_bits(1)] {
        for (v, w) in [(h, 0.0), (h, h), (0.0, h)] {
            let e = surface.eval(0, v, w).unwrap();
            assert!(e.record().iter().all(|x| x.is_finite()), "{h}: {e:?}");
            assert!((e.x - apex).length() < 1e-14, "{h}");
            let k = surface.curvature(0, v, w).unwrap();
            assert!(k.record().iter().all(|x| x.is_finite()));
            assert!(surface.normal(0, v, w).unwrap().is_finite());
        }
    }
}
