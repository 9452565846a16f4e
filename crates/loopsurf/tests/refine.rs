//! Uniform refinement against references that share no code with it: the
//! uniform cubic B-spline on creases and boundaries, and the invariance of
//! limit positions under further refinement at irregular, dart, crease and
//! corner vertices (any wrong rule or mask breaks it). The quartic box
//! spline on regular triangles checks it too, in the evaluator's tests.

mod common;

use common::{bicone, cgal_mesh};
use loopsurf::refine::refine_uniform;
use loopsurf::{examples, ControlNet, DVec3, VertexKind};

/// Limit positions of the vertices of `net` must not change when the net is
/// refined further: vertex i keeps index i on every finer level.
fn assert_limit_invariant(net: &ControlNet, levels: u32, tol: f64) {
    let diag = net.bbox_diagonal();
    let coarse = net.limit_points();
    let fine = refine_uniform(net, levels).unwrap().limit_points();
    let worst = coarse
        .iter()
        .zip(&fine)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0, f64::max);
    assert!(
        worst <= tol * diag,
        "limit moved by {:e} of the diagonal",
        worst / diag
    );
}

#[test]
fn limits_are_invariant_on_every_vertex_kind() {
    // Valence 80 apexes; a dart at the top apex; a corner; a crease loop on
    // the lower ring, which also makes its vertices crease vertices.
    let n = 80;
    let mut net = bicone(n, false);
    net.tag_edge(0, 1).unwrap();
    net.tag_vertex(5).unwrap();
    for i in 0..n as u32 {
        net.tag_edge(1 + n as u32 + i, 1 + n as u32 + (i + 1) % n as u32)
            .unwrap();
    }
    // Three hard edges meet at the ring vertex 1 + n → corner without a tag.
    net.tag_edge(1, 1 + n as u32).unwrap();
    let kinds = net.vertex_kinds();
    assert_eq!(kinds[0], VertexKind::Dart);
    assert_eq!(kinds[5], VertexKind::Corner);
    assert_eq!(kinds[1 + n], VertexKind::Corner);
    assert_eq!(kinds[2 + n], VertexKind::Crease);
    assert_eq!(kinds[2 * n + 1], VertexKind::Smooth);
    assert_eq!(net.topology().valence(2 * n + 1), n);
    assert_limit_invariant(&net, 1, 1e-13);
    // Level-1 vertices (edge points) after two more levels.
    let level1 = refine_uniform(&net, 1).unwrap().into_net();
    assert_limit_invariant(&level1, 2, 1e-13);
}

#[test]
fn limits_are_invariant_with_boundaries() {
    let net = bicone(64, true);
    assert_eq!(net.topology().boundary_loops().len(), 1);
    assert_limit_invariant(&net, 2, 1e-13);
}

#[test]
fn limits_are_invariant_on_every_example() {
    for &name in examples::NAMES {
        let ex = examples::by_name(name).unwrap();
        let mut net = ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
        net.tag_by_angle(30.0).unwrap();
        assert_limit_invariant(&net, 2, 1e-13);
    }
}

#[test]
fn limits_are_invariant_on_cgal_meshes() {
    for (name, angle) in [
        ("fandisk.off", Some(40.0)),
        ("pig.off", None),
        ("cow.off", Some(60.0)),
    ] {
        let Some(path) = cgal_mesh(name) else { return };
        let mut net = ControlNet::read(&path).unwrap();
        if let Some(deg) = angle {
            assert!(net.tag_by_angle(deg).unwrap() > 0);
        }
        assert_limit_invariant(&net, 2, 1e-12);
    }
}

/// Uniform periodic cubic B-spline through control polygon `p` at t (span units).
fn periodic_bspline(p: &[DVec3], t: f64) -> DVec3 {
    let n = p.len() as i64;
    let i = t.floor() as i64;
    let s = t - i as f64;
    let at = |k: i64| p[k.rem_euclid(n) as usize];
    let b = [
        (1.0 - s).powi(3) / 6.0,
        (3.0 * s.powi(3) - 6.0 * s * s + 4.0) / 6.0,
        (-3.0 * s.powi(3) + 3.0 * s * s + 3.0 * s + 1.0) / 6.0,
        s.powi(3) / 6.0,
    ];
    b[0] * at(i - 1) + b[1] * at(i) + b[2] * at(i + 1) + b[3] * at(i + 2)
}

/// The refined closed crease `coarse_loop` (as traced in the refined net
/// from the same first vertex) has the limit positions of the cubic B-spline.
fn assert_crease_is_bspline(net: &ControlNet, coarse_loop: &[u32], levels: u32, fine_loop: &[u32]) {
    let diag = net.bbox_diagonal();
    let refined = refine_uniform(net, levels).unwrap();
    let limits = refined.limit_points();
    let polygon: Vec<DVec3> = coarse_loop
        .iter()
        .map(|&v| net.points()[v as usize])
        .collect();
    let per_span = 1usize << levels;
    assert_eq!(fine_loop.len(), coarse_loop.len() * per_span);
    for (j, &v) in fine_loop.iter().enumerate() {
        let expected = periodic_bspline(&polygon, j as f64 / per_span as f64);
        let err = (limits[v as usize] - expected).length();
        assert!(
            err <= 1e-13 * diag,
            "crease point {j} off by {:e} of the diagonal",
            err / diag
        );
    }
}

#[test]
fn boundary_is_the_cubic_bspline_of_its_polygon() {
    let net = bicone(12, true);
    let coarse = net.topology().boundary_loops().remove(0);
    let levels = 3;
    let refined = refine_uniform(&net, levels).unwrap();
    let mut fine = refined.net().topology().boundary_loops().remove(0);
    let start = fine.iter().position(|&v| v == coarse[0]).unwrap();
    fine.rotate_left(start);
    assert_crease_is_bspline(&net, &coarse, levels, &fine);
}

#[test]
fn tagged_crease_loop_is_the_cubic_bspline_of_its_polygon() {
    // A loop of hard edges through smooth surface: the lower ring of a bicone.
    let n = 10u32;
    let mut net = bicone(n as usize, false);
    let ring: Vec<u32> = (0..n).map(|i| 1 + n + i).collect();
    for i in 0..n as usize {
        net.tag_edge(ring[i], ring[(i + 1) % n as usize]).unwrap();
    }
    let levels = 3;
    let refined = refine_uniform(&net, levels).unwrap();
    // Walk the refined crease: from each vertex, the hard neighbour not yet visited.
    let fine_net = refined.net();
    let mut fine = vec![ring[0]];
    let mut prev = u32::MAX;
    loop {
        let cur = *fine.last().unwrap();
        let hard = fine_net
            .features()
            .hard_neighbours(fine_net.topology(), cur as usize);
        assert_eq!(hard.len(), 2);
        // Go the way the coarse ring goes first.
        let next = if prev == u32::MAX {
            let toward = net.points()[ring[1] as usize] - net.points()[ring[0] as usize];
            *hard
                .iter()
                .max_by(|a, b| {
                    let da = (fine_net.points()[**a as usize] - fine_net.points()[cur as usize])
                        .dot(toward);
                    let db = (fine_net.points()[**b as usize] - fine_net.points()[cur as usize])
                        .dot(toward);
                    da.total_cmp(&db)
                })
                .unwrap()
        } else if hard[0] == prev {
            hard[1]
        } else {
            hard[0]
        };
        if next == ring[0] {
            break;
        }
        prev = cur;
        fine.push(next);
    }
    assert_crease_is_bspline(&net, &ring, levels, &fine);
}

#[test]
fn refinement_keeps_indices_and_features() {
    let mut net = bicone(8, true);
    net.tag_vertex(0).unwrap();
    let r = refine_uniform(&net, 2).unwrap();
    let (nv, ne, nt) = (
        net.points().len(),
        net.topology().num_edges(),
        net.triangles().len(),
    );
    assert_eq!(r.net().triangles().len(), 16 * nt);
    // Level 1 adds one vertex per edge; level 2 one per level-1 edge.
    let ne1 = 2 * ne + 3 * nt;
    assert_eq!(r.net().points().len(), nv + ne + ne1);
    assert_eq!(r.origins().len(), r.net().points().len());
    // The apex is still a fixed corner, the boundary still hard.
    assert_eq!(r.net().points()[0], net.points()[0]);
    assert_eq!(r.net().vertex_kinds()[0], VertexKind::Corner);
    let boundary = r.net().topology().boundary_loops()[0].len();
    assert_eq!(boundary, 4 * 8);
    assert_eq!(r.net().features().num_hard_edges(), 4 * 8);
    // Original vertices sit at triangle corners.
    for v in 0..nv {
        let o = r.origin(v).unwrap();
        let c = net.triangles()[o.tri as usize];
        let corner =
            [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)][c.iter().position(|&x| x as usize == v).unwrap()];
        assert_eq!((o.v, o.w), corner);
    }
    // Children of triangle t are 4t..4t+4 and share its orientation.
    let tri_normal = |n: &ControlNet, t: usize| {
        let [a, b, c] = n.triangles()[t].map(|i| n.points()[i as usize]);
        (b - a).cross(c - a)
    };
    let one = refine_uniform(&net, 1).unwrap().into_net();
    for t in 0..nt {
        for k in 0..4 {
            assert!(tri_normal(&one, 4 * t + k).dot(tri_normal(&net, t)) > 0.0);
        }
    }
    assert!(refine_uniform(&net, loopsurf::refine::MAX_LEVELS + 1).is_err());
}

/// Largest sine of the angle between the tangent plane of the masks at
/// vertex `v` and the chords from its limit point to its neighbours' limit
/// points after `levels` refinements: it must shrink towards zero.
fn chord_tilt(net: &ControlNet, v: usize, levels: u32) -> f64 {
    let loopsurf::net::Tangents::Surface(t1, t2) = net.limit_tangents(v).unwrap() else {
        panic!("vertex {v} has no tangent masks");
    };
    let normal = t1.cross(t2).normalize();
    let refined = refine_uniform(net, levels).unwrap();
    let limits = refined.limit_points();
    refined
        .net()
        .topology()
        .ring(v)
        .iter()
        .map(|&n| {
            let chord = limits[n as usize] - limits[v];
            (chord.dot(normal) / chord.length()).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn smooth_tangent_masks_span_the_limit_tangent_plane() {
    let net = bicone(9, false);
    // Slow for valence 9 (the tilt falls like (λ₂/λ₁)ᵏ ≈ 0.74ᵏ), but a wrong
    // plane would leave it constant.
    let (coarse, fine) = (chord_tilt(&net, 0, 2), chord_tilt(&net, 0, 7));
    assert!(
        fine < coarse / 6.0 && fine < 0.04,
        "tilt {coarse} -> {fine}"
    );
    // Outward: the apex normal points up, away from the body.
    let loopsurf::net::Tangents::Surface(t1, t2) = net.limit_tangents(0).unwrap() else {
        panic!()
    };
    assert!(t1.cross(t2).z > 0.0);
    assert!(net.limit_tangents(net.points().len()).is_err());
    // The crease mask is the cubic B-spline's derivative at the node.
    let mut net = bicone(9, false);
    for i in 0..9u32 {
        net.tag_edge(10 + i, 10 + (i + 1) % 9).unwrap();
    }
    let loopsurf::net::Tangents::Crease(t) = net.limit_tangents(10).unwrap() else {
        panic!()
    };
    let p = |i: usize| net.points()[i];
    assert!(t.cross(p(11) - p(18)).length() < 1e-14 * t.length() * (p(11) - p(18)).length());
}
