//! The surface mesher against what a mesh generator promises: conforming,
//! watertight, vertices exactly on the surface in every chart, hard-edge
//! chains kept, and the chord tolerance honoured as measured by snap (an
//! independent global closest-point search).

mod common;

use common::{cgal_mesh, chord_error_between_probes, example};
use loopsurf::{ControlNet, Density, LimitCurve, Mesher, Surface, SurfaceMesh};
use std::collections::HashMap;

fn cgal(name: &str, angle: Option<f64>) -> Option<ControlNet> {
    let mut net = ControlNet::read(cgal_mesh(name)?).unwrap();
    if let Some(a) = angle {
        net.tag_by_angle(a).unwrap();
    }
    Some(net)
}

/// Undirected edge → number of triangles, with a check that no directed
/// edge repeats (consistent orientation, no duplicate triangles).
fn edge_use(mesh: &SurfaceMesh) -> HashMap<(u32, u32), u32> {
    let mut directed = HashMap::new();
    let mut undirected = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        assert!(
            tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2],
            "triangle {t} {tri:?} repeats a vertex"
        );
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            assert!(
                directed.insert((a, b), t).is_none(),
                "directed edge {a}->{b} twice"
            );
            *undirected.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    undirected
}

/// Conforming and watertight wherever the net is: interior edges in two
/// triangles, open edges exactly the refinements of the net's boundary (so
/// there is no T-junction), and the Euler characteristic kept.
fn check_topology(net: &ControlNet, mesh: &SurfaceMesh, what: &str) {
    let uses = edge_use(mesh);
    let topo = net.topology();
    let control_open = (0..topo.num_edges())
        .filter(|&e| topo.is_boundary_edge(e))
        .count();
    let mut open = 0;
    for (&(a, b), &n) in &uses {
        assert!(n <= 2, "{what}: edge {a}-{b} in {n} triangles");
        if n == 1 {
            open += 1;
            // Both ends on a boundary curve of the net.
            for v in [a, b] {
                let p = mesh.params[v as usize];
                let on_side =
                    p.v.abs() < 1e-15 || p.w.abs() < 1e-15 || (1.0 - p.v - p.w).abs() < 1e-14;
                assert!(
                    on_side,
                    "{what}: open edge {a}-{b} leaves the control boundary at {v}"
                );
            }
        }
    }
    assert_eq!(
        open == 0,
        control_open == 0,
        "{what}: {open} open edges, the net has {control_open}"
    );
    let (v, e, f) = (
        mesh.points.len() as i64,
        uses.len() as i64,
        mesh.triangles.len() as i64,
    );
    assert_eq!(
        v - e + f,
        topo.euler_characteristic(),
        "{what}: Euler characteristic"
    );
}

/// Every vertex is the surface at its parameters, and at its parameters in
/// the chart of every triangle around it.
fn check_on_surface(surface: &Surface, mesh: &SurfaceMesh, what: &str) {
    let tol = 1e-12 * mesh.diagonal;
    for (i, p) in mesh.params.iter().enumerate() {
        let x = surface.eval(p.tri as usize, p.v, p.w).unwrap().x;
        assert!(
            x.distance(mesh.points[i]) <= tol,
            "{what}: vertex {i} off its parameters"
        );
    }
    for t in 0..mesh.triangles.len() {
        let params = mesh.triangle_params(surface.net(), t);
        for (k, p) in params.iter().enumerate() {
            assert_eq!(p.tri, mesh.charts[t]);
            let x = surface.eval(p.tri as usize, p.v, p.w).unwrap().x;
            let i = mesh.triangles[t][k] as usize;
            assert!(
                x.distance(mesh.points[i]) <= tol,
                "{what}: triangle {t} corner {k} off in its chart"
            );
        }
    }
}

/// Each hard control edge becomes a chain of output edges from one end to
/// the other, every chain vertex on that control edge (so on the crease).
fn check_hard_chains(net: &ControlNet, mesh: &SurfaceMesh, what: &str) {
    let uses = edge_use(mesh);
    for &[a, b] in &mesh.hard_edges {
        assert!(
            uses.contains_key(&(a.min(b), a.max(b))),
            "{what}: hard edge {a}-{b} is not a mesh edge"
        );
    }
    let mut next: HashMap<u32, Vec<u32>> = HashMap::new();
    for &[a, b] in &mesh.hard_edges {
        next.entry(a).or_default().push(b);
        next.entry(b).or_default().push(a);
    }
    let topo = net.topology();
    let mut covered = 0;
    for (e, &[a, b]) in topo.edges().iter().enumerate() {
        if !net.features().is_hard_edge(e) {
            continue;
        }
        // Control vertex i is output vertex i: every test net uses all its
        // vertices, and used control vertices come first, in order.
        let (mut prev, mut at, end) = (u32::MAX, a, b);
        let mut steps = 0;
        while at != end {
            let candidates: Vec<u32> = next[&at]
                .iter()
                .copied()
                .filter(|&n| n != prev && (n == end || on_control_edge(net, mesh, n, a, b)))
                .collect();
            assert_eq!(
                candidates.len(),
                1,
                "{what}: chain of hard edge {a}-{b} branches at {at}"
            );
            prev = at;
            at = candidates[0];
            steps += 1;
        }
        covered += steps;
    }
    assert_eq!(
        covered,
        mesh.hard_edges.len(),
        "{what}: hard output edges off the chains"
    );
}

fn on_control_edge(net: &ControlNet, mesh: &SurfaceMesh, v: u32, a: u32, b: u32) -> bool {
    let p = mesh.params[v as usize];
    let tri = net.triangles()[p.tri as usize];
    let weights = [1.0 - p.v - p.w, p.v, p.w];
    (0..3).all(|k| tri[k] == a || tri[k] == b || weights[k].abs() < 1e-14)
        && tri.contains(&a)
        && tri.contains(&b)
}

fn check_all(net: &ControlNet, surface: &Surface, mesh: &SurfaceMesh, what: &str) {
    check_topology(net, mesh, what);
    check_on_surface(surface, mesh, what);
    check_hard_chains(net, mesh, what);
}

#[test]
fn examples_mesh_conforming_on_the_surface_with_hard_chains() {
    for (name, angle) in [
        ("viking", Some(30.0)),
        ("sphere", None),
        ("torus", None),
        ("cube", Some(30.0)),
        ("open-disk", None),
        ("tetra", Some(30.0)),
    ] {
        let net = example(name, angle);
        let surface = Surface::new(&net).unwrap();
        for (density, mesh) in three_meshes(&surface) {
            check_all(&net, &surface, &mesh, &format!("{name} {density:?}"));
        }
    }
}

#[test]
fn uniform_mode_cuts_every_triangle_into_n_squared() {
    let net = example("viking", Some(30.0));
    let surface = Surface::new(&net).unwrap();
    for n in [1, 2, 5] {
        let mesh = Mesher::new(&surface)
            .density(Density::Uniform(n))
            .run()
            .unwrap();
        assert_eq!(
            mesh.triangles.len(),
            net.triangles().len() * (n * n) as usize
        );
        assert_eq!(mesh.hard_edges.len(), 80 * n as usize);
        assert_eq!(mesh.deviation, None, "nothing to enforce, nothing measured");
    }
}

#[test]
fn tolerance_is_honoured_on_viking_pig_and_fandisk() {
    let mut cases = vec![("viking", example("viking", Some(30.0)))];
    if let Some(net) = cgal("pig.off", None) {
        cases.push(("pig", net));
    }
    // Hard edges on a curved, irregular net: projections that leave the
    // triangle far beyond its long side.
    if let Some(net) = cgal("pig.off", Some(30.0)) {
        cases.push(("pig 30°", net));
    }
    if let Some(net) = cgal("fandisk.off", Some(30.0)) {
        cases.push(("fandisk", net));
    }
    for (name, net) in &cases {
        let surface = Surface::new(net).unwrap();
        for (tol, adapt) in [(1e-3, true), (2e-3, false)] {
            let what = format!("{name} tolerance {tol} adapt={adapt}");
            let mesher = Mesher::new(&surface)
                .density(Density::FromTolerance)
                .tolerance(tol)
                .adapt_curvature(adapt);
            let mesh = mesher.run().unwrap();
            let deviation = mesh.deviation.expect("measured under a tolerance");
            let bound = tol * mesh.diagonal;
            assert!(
                deviation <= bound,
                "{what}: chord error {} > {bound}",
                deviation
            );
            // Snap measures the true distance from each centroid and edge
            // midpoint to the surface: never more than the chord error.
            let snapped = mesh.snap_deviation(&surface).unwrap();
            assert!(
                snapped <= deviation * (1.0 + 1e-9) + 1e-13 * mesh.diagonal,
                "{what}: snap {snapped} > measured {}",
                deviation
            );
            // And between those probes, at points the mesher never uses.
            let (between, worst) =
                chord_error_between_probes(&surface, &mesh.points, &mesh.triangles, 4);
            assert!(
                between <= bound,
                "{what}: chord error {between} > {bound} between the probes, at triangle {worst}"
            );
            check_all(net, &surface, &mesh, &what);
            let q = mesh.quality();
            eprintln!(
                "{what}: {} triangles, chord error {:.2e} (snap {:.2e}, between probes {:.2e}) of the diagonal, min angle {:.1}°, mean min angle {:.1}°",
                mesh.triangles.len(),
                deviation / mesh.diagonal,
                snapped / mesh.diagonal,
                between / mesh.diagonal,
                q.min_angle,
                q.mean_min_angle
            );
        }
    }
}

#[test]
fn adaptive_meshes_are_denser_where_curved_and_swaps_help() {
    let net = example("viking", Some(30.0));
    let surface = Surface::new(&net).unwrap();
    let tolerance = |adapt| {
        Mesher::new(&surface)
            .density(Density::FromTolerance)
            .tolerance(1e-3)
            .adapt_curvature(adapt)
    };
    let uniform = tolerance(false).run().unwrap();
    let adaptive = tolerance(true).run().unwrap();
    assert!(
        adaptive.triangles.len() < uniform.triangles.len(),
        "{} vs {}",
        adaptive.triangles.len(),
        uniform.triangles.len()
    );
    let unswapped = tolerance(true).swaps(false).run().unwrap();
    assert!(adaptive.quality().mean_min_angle >= unswapped.quality().mean_min_angle);
    assert!(adaptive.quality().min_angle >= unswapped.quality().min_angle - 1e-9);
}

#[test]
fn bad_options_are_clear_errors() {
    let net = example("tetra", None);
    let surface = Surface::new(&net).unwrap();
    let cases: Vec<(Mesher, &str)> = vec![
        (
            Mesher::new(&surface).density(Density::Uniform(0)),
            "at least 1",
        ),
        (
            Mesher::new(&surface).density(Density::Size(-1.0)),
            "positive",
        ),
        (
            Mesher::new(&surface).density(Density::Size(f64::NAN)),
            "positive",
        ),
        (
            Mesher::new(&surface)
                .density(Density::FromTolerance)
                .tolerance(0.0),
            "strictly between",
        ),
        (
            Mesher::new(&surface)
                .density(Density::FromTolerance)
                .tolerance(2.0),
            "strictly between",
        ),
        (
            Mesher::new(&surface).density(Density::FromTolerance),
            "no density",
        ),
        (
            Mesher::new(&surface)
                .density(Density::Uniform(4))
                .adapt_curvature(true),
            "exclude",
        ),
        (
            Mesher::new(&surface)
                .density(Density::Uniform(100))
                .max_triangles(1000),
            "over the limit",
        ),
    ];
    for (mesher, expected) in cases {
        let err = mesher.run().unwrap_err().to_string();
        assert!(
            err.contains(expected),
            "{err:?} should mention {expected:?}"
        );
    }
}

/// A CAD-like net of creases and corners up to valence 34 (CGAL anchor):
/// next to such vertices the parameterisation drifts far along the
/// surface, and a chord error that counted the drift (one projection step
/// instead of a converged one) asked for 2.3 million triangles at 1e-3.
#[test]
fn crease_and_corner_nets_stay_within_a_sane_count() {
    let Some(net) = cgal("anchor.off", Some(30.0)) else {
        return;
    };
    let surface = Surface::new(&net).unwrap();
    let mesh = Mesher::new(&surface)
        .tolerance(1e-3)
        .adapt_curvature(true)
        .run()
        .unwrap();
    assert!(mesh.deviation.unwrap() <= 1e-3 * mesh.diagonal);
    assert!(
        mesh.triangles.len() < 150_000,
        "{} triangles for 1050 control triangles",
        mesh.triangles.len()
    );
}

/// Whether output vertex `v` lies on the control edge x-y: its only
/// nonzero weights are at x or y (a vertex at a control vertex is stored in
/// any triangle of its fan).
fn lies_on(net: &ControlNet, mesh: &SurfaceMesh, v: u32, x: u32, y: u32) -> bool {
    let p = mesh.params[v as usize];
    let tri = net.triangles()[p.tri as usize];
    let weights = [1.0 - p.v - p.w, p.v, p.w];
    (0..3).all(|k| tri[k] == x || tri[k] == y || weights[k].abs() < 1e-14)
}

/// The model labels of a mesh: every triangle carries the face of its
/// chart; every hard output edge carries the curve of a control edge both
/// its ends lie on; `curve_edges` finds the same edges from the vertices'
/// parameters alone, oriented and ordered along their curves, with curve
/// parameters at which the curve is the vertex.
fn check_labels(net: &ControlNet, surface: &Surface, mesh: &SurfaceMesh, what: &str) {
    let model = surface.model();
    assert_eq!(mesh.faces.len(), mesh.triangles.len(), "{what}");
    for (t, &f) in mesh.faces.iter().enumerate() {
        assert_eq!(
            f,
            model.face_of_triangle()[mesh.charts[t] as usize],
            "{what}: triangle {t}"
        );
    }
    assert_eq!(
        loopsurf::mesh::face_labels(model, &mesh.charts).unwrap(),
        mesh.faces,
        "{what}"
    );
    assert_eq!(mesh.hard_edge_curves.len(), mesh.hard_edges.len(), "{what}");
    let mut labelled = HashMap::new();
    for (&[a, b], &c) in mesh.hard_edges.iter().zip(&mesh.hard_edge_curves) {
        let curve = &model.curves()[c as usize];
        let on_curve = curve
            .chain
            .windows(2)
            .any(|w| lies_on(net, mesh, a, w[0], w[1]) && lies_on(net, mesh, b, w[0], w[1]));
        assert!(on_curve, "{what}: hard edge {a}-{b} off curve {c}");
        labelled.insert((a.min(b), a.max(b)), c);
    }
    let found = mesh.curve_edges(surface).unwrap();
    assert_eq!(found.pairs.len(), mesh.hard_edges.len(), "{what}");
    let tol = 1e-11 * mesh.diagonal;
    for (i, (&[a, b], &c)) in found.pairs.iter().zip(&found.curves).enumerate() {
        assert_eq!(
            labelled.get(&(a.min(b), a.max(b))),
            Some(&c),
            "{what}: {a}-{b}"
        );
        let [ta, tb] = found.params[i];
        assert!(ta < tb, "{what}: {a}-{b} runs against its curve");
        for (v, t) in [(a, ta), (b, tb)] {
            let x = LimitCurve::new(surface, c as usize)
                .unwrap()
                .eval(t)
                .unwrap()
                .x;
            assert!(
                x.distance(mesh.points[v as usize]) <= tol,
                "{what}: vertex {v} is not curve {c} at t = {t}"
            );
        }
        // Ordered along the curve: the next edge of the same curve starts
        // where this one ends.
        if i + 1 < found.pairs.len() && found.curves[i + 1] == c {
            assert_eq!(found.pairs[i + 1][0], b, "{what}: curve {c} breaks at {b}");
            assert_eq!(found.params[i + 1][0], tb, "{what}");
        }
    }
    // Every curve is covered from t = 0 to t = n.
    for (c, curve) in model.curves().iter().enumerate() {
        let mine: Vec<usize> = (0..found.curves.len())
            .filter(|&i| found.curves[i] == c as u32)
            .collect();
        assert!(!mine.is_empty(), "{what}: curve {c} has no output edge");
        assert_eq!(found.params[mine[0]][0], 0.0, "{what}: curve {c}");
        assert_eq!(
            found.params[*mine.last().unwrap()][1],
            curve.len() as f64,
            "{what}: curve {c}"
        );
    }
}

#[test]
fn meshes_carry_faces_and_curves_of_the_model() {
    let mut cases: Vec<(String, ControlNet)> = [
        ("cube", Some(30.0)),
        ("open-disk", None),
        ("viking", Some(30.0)),
        ("tetra", Some(30.0)),
        ("torus", None),
    ]
    .into_iter()
    .map(|(name, angle)| (name.to_string(), example(name, angle)))
    .collect();
    if let Some(net) = cgal("fandisk.off", Some(30.0)) {
        cases.push(("fandisk 30°".into(), net));
    }
    for (name, net) in &cases {
        let surface = Surface::new(net).unwrap();
        for (density, mesh) in three_meshes(&surface) {
            check_labels(net, &surface, &mesh, &format!("{name} {density:?}"));
        }
    }
    // Hostile inputs to the free function are errors naming the element.
    let net = example("cube", Some(30.0));
    let surface = Surface::new(&net).unwrap();
    let p = |tri, v, w| loopsurf::SurfacePoint { tri, v, w };
    let err = loopsurf::mesh::curve_edges(&surface, &[p(1_000_000, 0.0, 0.0)], &[]).unwrap_err();
    assert!(err.to_string().contains("vertex 0"), "{err}");
    let err = loopsurf::mesh::curve_edges(&surface, &[p(0, 0.7, 0.7)], &[]).unwrap_err();
    assert!(matches!(err, loopsurf::Error::BadParameter { .. }), "{err}");
    let err = loopsurf::mesh::curve_edges(&surface, &[p(0, 0.0, 0.0)], &[[0, 0, 1]]).unwrap_err();
    assert!(err.to_string().contains("triangle 0"), "{err}");
    let err = loopsurf::mesh::face_labels(surface.model(), &[0, 1000]).unwrap_err();
    assert!(err.to_string().contains("chart 1000"), "{err}");
}

/// The surface meshed three ways: every control triangle whole, cut in
/// nine, and graded by curvature under the default tolerance.
fn three_meshes(surface: &Surface) -> Vec<(Density, SurfaceMesh)> {
    [
        (Density::Uniform(1), false),
        (Density::Uniform(3), false),
        (Density::FromTolerance, true),
    ]
    .into_iter()
    .map(|(density, adapt)| {
        let mesh = Mesher::new(surface)
            .density(density)
            .adapt_curvature(adapt)
            .run()
            .unwrap();
        (density, mesh)
    })
    .collect()
}
