//! Curved (Lagrange P1–P4) meshes on the exact surface (docs/high-order.md): nodes on
//! the surface, shared edge nodes, gmsh's node order, convergence orders,
//! crease nodes on their curves, validity, curving a mesh made elsewhere,
//! and the files read back. References share no code with the placement:
//! `eval` at the stored parameters, the certified snap and curve snap,
//! and node layouts written out from gmsh's documentation.

mod common;

use common::{cgal_mesh, example};
use loopsurf::io;
use loopsurf::mesh::high_order::{onto_surface, CurvedMesh, DEFAULT_MAX_MOVE};
use loopsurf::{ControlNet, DVec3, Density, LimitCurve, Mesher, Remesher, Surface, SurfaceMesh};
use std::collections::HashMap;

/// Every node is `eval` of its parameters to 1e-12 of the diagonal.
fn check_on_surface(name: &str, surface: &Surface, curved: &CurvedMesh) {
    let diagonal = surface.net().bbox_diagonal();
    for (i, (p, x)) in curved.params.iter().zip(&curved.nodes).enumerate() {
        let at = surface.point(p.tri as usize, p.v, p.w).unwrap();
        assert!(
            at.distance(*x) <= 1e-12 * diagonal,
            "{name}: node {i} is {:e} off its parameters",
            at.distance(*x)
        );
    }
}

/// Each edge's inner nodes are the same nodes, reversed, in both of its
/// triangles: the curved mesh is conforming.
fn check_shared_edges(name: &str, curved: &CurvedMesh) {
    let k = curved.order;
    let mut seen: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
    for t in 0..curved.len() {
        let e = curved.element(t);
        for s in 0..3 {
            let (a, b) = (e[s], e[(s + 1) % 3]);
            let inner: Vec<u32> = e[3 + s * (k - 1)..3 + (s + 1) * (k - 1)].to_vec();
            if let Some(other) = seen.get(&(b, a)) {
                let reversed: Vec<u32> = other.iter().rev().copied().collect();
                assert_eq!(inner, reversed, "{name}: edge {a}-{b} of triangle {t}");
            }
            seen.insert((a, b), inner);
        }
    }
}

/// gmsh's layouts ("Node ordering" in its reference manual), as
/// barycentric lattice points (i, j) of (ξ, η) = (i/k, j/k).
fn gmsh_layout(k: usize) -> Vec<[usize; 2]> {
    match k {
        1 => vec![[0, 0], [1, 0], [0, 1]],
        2 => vec![[0, 0], [2, 0], [0, 2], [1, 0], [1, 1], [0, 1]],
        3 => vec![
            [0, 0],
            [3, 0],
            [0, 3],
            [1, 0],
            [2, 0],
            [2, 1],
            [1, 2],
            [0, 2],
            [0, 1],
            [1, 1],
        ],
        4 => vec![
            [0, 0],
            [4, 0],
            [0, 4],
            [1, 0],
            [2, 0],
            [3, 0],
            [3, 1],
            [2, 2],
            [1, 3],
            [0, 3],
            [0, 2],
            [0, 1],
            [1, 1],
            [2, 1],
            [1, 2],
        ],
        _ => unreachable!(),
    }
}

/// The Lagrange basis function of lattice node `(i, j)` of order `k` at
/// (ξ, η): the product over the three barycentric coordinates of the
/// polynomials vanishing on the lattice lines below the node's.
fn lagrange(k: usize, [i, j]: [usize; 2], xi: f64, eta: f64) -> f64 {
    let factor = |n: usize, x: f64| {
        (0..n)
            .map(|a| (k as f64 * x - a as f64) / (n - a) as f64)
            .product::<f64>()
    };
    factor(i, xi) * factor(j, eta) * factor(k - i - j, 1.0 - xi - eta)
}

/// The smallest scaled Jacobian of a curved mesh, computed here: the
/// elements' maps from gmsh's layout and [`lagrange`], their derivatives
/// by central differences, at a 12 × 12 lattice of each triangle (not the
/// product's samples), against the normal of the corner nodes' plane.
fn min_scaled_jacobian(curved: &CurvedMesh) -> f64 {
    let k = curved.order;
    let layout = gmsh_layout(k);
    let per = layout.len();
    let n = 12;
    let mut min = f64::INFINITY;
    for element in curved.triangles.chunks(per) {
        let x: Vec<DVec3> = element.iter().map(|&i| curved.nodes[i as usize]).collect();
        let map = |xi: f64, eta: f64| -> DVec3 {
            (layout.iter().zip(&x))
                .map(|(&node, &p)| lagrange(k, node, xi, eta) * p)
                .sum()
        };
        let normal = (x[1] - x[0]).cross(x[2] - x[0]).normalize();
        let h = 1e-6;
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for a in 0..=n {
            for b in 0..=n - a {
                let (xi, eta) = (a as f64 / n as f64, b as f64 / n as f64);
                let dxi = (map(xi + h, eta) - map(xi - h, eta)) / (2.0 * h);
                let deta = (map(xi, eta + h) - map(xi, eta - h)) / (2.0 * h);
                let j = dxi.cross(deta).dot(normal);
                lo = lo.min(j);
                hi = hi.max(j.abs());
            }
        }
        min = min.min(lo / hi);
    }
    min
}

/// Chart meshes of the torus (a regular net: one quartic per control
/// triangle) converge at order k + 1, and P4 elements reproduce the
/// quartic pieces to round-off. The chart elements' nodes sit at gmsh's
/// layout in the chart's parameters.
#[test]
fn torus_chart_meshes_converge_at_order_k_plus_one() {
    let net = example("torus", None);
    let surface = Surface::new(&net).unwrap();
    let diagonal = net.bbox_diagonal();
    for k in 1..=4 {
        let mut errors = Vec::new();
        for n in [2, 4, 8] {
            let mesh = Mesher::new(&surface)
                .density(Density::Uniform(n))
                .run()
                .unwrap();
            let curved = mesh.raise_order(&surface, k).unwrap();
            assert_eq!(curved.nodes[..mesh.points.len()], mesh.points[..]);
            check_on_surface("torus", &surface, &curved);
            check_shared_edges("torus", &curved);
            let layout = gmsh_layout(k);
            for t in (0..curved.len()).step_by(97) {
                let corners = mesh.triangle_params(&net, t);
                for (node, [i, j]) in curved.element(t).iter().zip(&layout) {
                    let (x, y) = (*i as f64 / k as f64, *j as f64 / k as f64);
                    let v = (1.0 - x - y) * corners[0].v + x * corners[1].v + y * corners[2].v;
                    let w = (1.0 - x - y) * corners[0].w + x * corners[1].w + y * corners[2].w;
                    let at = surface.point(corners[0].tri as usize, v, w).unwrap();
                    let d = at.distance(curved.nodes[*node as usize]);
                    assert!(
                        d <= 1e-13 * diagonal,
                        "order {k} triangle {t}: node {node} off gmsh's layout by {d:e}"
                    );
                    // The element map interpolates its nodes.
                    let mapped = curved.map(t, x, y)[0];
                    assert!(mapped.distance(curved.nodes[*node as usize]) <= 1e-13 * diagonal);
                }
            }
            let validity = curved.validity();
            assert!(
                validity.invalid.is_empty() && validity.min > 0.8,
                "order {k} n {n}: {}",
                validity.min
            );
            errors.push(curved.distance_to(&surface).unwrap().max / diagonal);
        }
        println!("torus, order {k}: max distance {errors:?} at n = 2, 4, 8");
        if k == 4 {
            assert!(
                errors.iter().all(|&e| e < 1e-13),
                "P4 must be exact: {errors:?}"
            );
            continue;
        }
        let rate = (errors[1] / errors[2]).log2();
        assert!(
            (rate - (k + 1) as f64).abs() <= 0.3,
            "order {k}: rate {rate:.2}, expected {}",
            k + 1
        );
    }
}

/// The remesher's elements span control triangles; their nodes come from
/// the closest-point map. On the Viking with its creases: nodes on the
/// surface, inner nodes of hard-edge lines on their curves (certified
/// curve snap), conforming, and the error falling with the order.
#[test]
fn remeshed_viking_curves_onto_surface_and_creases() {
    let net = example("viking", Some(30.0));
    let surface = Surface::new(&net).unwrap();
    let diagonal = net.bbox_diagonal();
    let mesh = Remesher::new(&surface).size(0.02 * diagonal).run().unwrap();
    let mut errors = Vec::new();
    for k in 1..=3 {
        let curved = mesh.raise_order(&surface, k).unwrap();
        check_on_surface("viking", &surface, &curved);
        check_shared_edges("viking", &curved);
        assert_eq!(curved.line_curves.len(), mesh.hard_edges.len());
        for (line, &c) in curved.lines.chunks(k + 1).zip(&curved.line_curves) {
            for &node in &line[2..] {
                let x = curved.nodes[node as usize];
                let snap = LimitCurve::new(&surface, c as usize)
                    .unwrap()
                    .closest_point(x)
                    .unwrap();
                assert!(
                    snap.distance <= 1e-9 * diagonal,
                    "node {node} is {:e} off curve {c}",
                    snap.distance
                );
            }
        }
        let corners: Vec<u32> = curved.corners.iter().map(|c| c.1).collect();
        assert_eq!(corners.len(), surface.model().corners().len());
        let validity = curved.validity();
        let ours = min_scaled_jacobian(&curved);
        println!(
            "viking at 2%, order {k}: min scaled Jacobian {:.3} ({ours:.3} on the test's lattice), {} invalid",
            validity.min,
            validity.invalid.len()
        );
        // 1, 0.919 and 0.612 by the product's samples when measured
        // (2026-12-01), 1, 0.919 and 0.587 by the test's own denser ones
        // (whose differences are good to about 1e-8): no element near
        // inversion.
        let floor = [1.0 - 1e-6, 0.9, 0.55][k - 1];
        assert!(validity.invalid.is_empty(), "{:?}", validity.invalid);
        assert!(
            validity.min >= floor && ours >= floor,
            "viking, order {k}: scaled Jacobian {} / {ours} below {floor}",
            validity.min
        );
        errors.push(curved.distance_to(&surface).unwrap().max / diagonal);
    }
    println!("viking at 2%: max distance {errors:?} for P1, P2, P3");
    assert!(
        errors[1] < 0.25 * errors[0] && errors[2] < errors[1],
        "{errors:?}"
    );
}

/// `onto_surface` (`loopsurf curve`) on a chart mesh of fandisk written to
/// a file and read back: nothing moves, and the hard edges are found again;
/// on a perturbed copy: every vertex back on the surface, creases on their
/// curves, moves as large as the perturbation; a vertex moved a diagonal
/// away is refused by name.
#[test]
fn curving_a_mesh_made_elsewhere() {
    let Some(path) = cgal_mesh("fandisk.off") else {
        panic!("fandisk.off not found: run scripts/test.sh, which fetches CGAL's meshes");
    };
    let mut net = ControlNet::read(path).unwrap();
    net.tag_by_angle(30.0).unwrap();
    let surface = Surface::new(&net).unwrap();
    let diagonal = net.bbox_diagonal();
    let mesh = Mesher::new(&surface)
        .density(Density::Uniform(2))
        .run()
        .unwrap();
    let dir = std::env::temp_dir().join(format!("loopsurf-curve-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("charts.off");
    io::write_mesh(&file, &mesh.points, &mesh.triangles).unwrap();
    let read = io::read_off(&file, &io::ParseOptions::default()).unwrap();
    let tris: Vec<[u32; 3]> = read.tris.iter().map(|t| t.map(|i| i as u32)).collect();
    let points = &read.points;
    put_back_unmoved(&surface, &mesh, points, &tris);
    put_back_from_a_perturbed_copy(&surface, &mesh, points, &tris);
    let mut far = points.clone();
    far[17] += DVec3::X * diagonal;
    let err = onto_surface(&surface, &far, &tris, DEFAULT_MAX_MOVE)
        .err()
        .expect("a vertex a diagonal away is refused")
        .to_string();
    assert!(
        err.contains("vertex 17") && err.contains("allowed move"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The chart mesh `mesh` as read back (`points`, `tris`) put onto the
/// surface: nothing moves, the faces and hard edges are the mesher's, and
/// raised to P2 every node is on the surface.
fn put_back_unmoved(surface: &Surface, mesh: &SurfaceMesh, points: &[DVec3], tris: &[[u32; 3]]) {
    let diagonal = surface.net().bbox_diagonal();
    let onto = onto_surface(surface, points, tris, DEFAULT_MAX_MOVE).unwrap();
    assert!(
        onto.largest_move <= 1e-10 * diagonal,
        "moved {:e}",
        onto.largest_move
    );
    assert_eq!(onto.mesh.faces, mesh.faces);
    check_hard_edges(
        surface,
        &mesh.hard_edges,
        &mesh.hard_edge_curves,
        &onto.mesh.hard_edges,
    );
    let curved = onto.mesh.raise_order(surface, 2).unwrap();
    check_on_surface("fandisk", surface, &curved);
}

/// A copy of `points` perturbed by 1e-4 of the diagonal put onto the
/// surface: moves as large as the perturbation, the hard edges found
/// again, and raised to P3 every node on the surface and every line node
/// on its curve.
fn put_back_from_a_perturbed_copy(
    surface: &Surface,
    mesh: &SurfaceMesh,
    points: &[DVec3],
    tris: &[[u32; 3]],
) {
    let diagonal = surface.net().bbox_diagonal();
    let bump = 1e-4 * diagonal;
    let moved: Vec<DVec3> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let s = (i as f64 * 0.618_033_988_7).fract();
            *p + bump * DVec3::new((7.0 * s).sin(), (11.0 * s).cos(), (13.0 * s).sin())
                / 3f64.sqrt()
        })
        .collect();
    let onto = onto_surface(surface, &moved, tris, DEFAULT_MAX_MOVE).unwrap();
    assert!(
        onto.largest_move <= 2.0 * bump,
        "moved {:e}",
        onto.largest_move
    );
    check_hard_edges(
        surface,
        &mesh.hard_edges,
        &mesh.hard_edge_curves,
        &onto.mesh.hard_edges,
    );
    let curved = onto.mesh.raise_order(surface, 3).unwrap();
    check_on_surface("perturbed fandisk", surface, &curved);
    check_shared_edges("perturbed fandisk", &curved);
    for (line, &c) in curved.lines.chunks(4).zip(&curved.line_curves) {
        for &node in line {
            let snap = LimitCurve::new(surface, c as usize)
                .unwrap()
                .closest_point(curved.nodes[node as usize])
                .unwrap();
            assert!(
                snap.distance <= 1e-9 * diagonal,
                "node {node} off curve {c}"
            );
        }
    }
}

/// The hard edges found on a mesh put onto the surface are the mesher's,
/// but for edges along a curve with one face on both sides (a dart's
/// slit), which no change of face reveals.
fn check_hard_edges(surface: &Surface, made: &[[u32; 2]], curves: &[u32], found: &[[u32; 2]]) {
    let key = |[a, b]: [u32; 2]| (a.min(b), a.max(b));
    let made: HashMap<(u32, u32), u32> = made
        .iter()
        .zip(curves)
        .map(|(&e, &c)| (key(e), c))
        .collect();
    let found: std::collections::HashSet<(u32, u32)> = found.iter().map(|&e| key(e)).collect();
    for e in &found {
        assert!(
            made.contains_key(e),
            "edge {e:?} found, but not a hard edge of the mesher's"
        );
    }
    for (e, &c) in &made {
        let faces = surface.model().curves()[c as usize].faces;
        assert!(
            found.contains(e) || faces[0] == faces[1],
            "hard edge {e:?} of curve {c} not found"
        );
    }
}

/// The curved mesh survives .msh (ASCII and binary) and .vtu bit for bit:
/// nodes, parameters, elements, faces, lines and corners. Where Python's
/// meshio is installed, it reads the files too.
#[test]
fn curved_files_read_back_exactly() {
    let net = example("viking", Some(30.0));
    let surface = Surface::new(&net).unwrap();
    let mesh = Remesher::new(&surface)
        .size(0.03 * net.bbox_diagonal())
        .run()
        .unwrap();
    let dir = std::env::temp_dir().join(format!("loopsurf-msh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for k in 1..=4 {
        let lagrange = mesh.raise_order(&surface, k).unwrap().to_lagrange();
        for binary in [false, true] {
            let path = dir.join(format!("viking-p{k}-{binary}.msh"));
            io::write_msh(&path, &lagrange, binary).unwrap();
            let back = io::read_msh(&path).unwrap().to_lagrange().unwrap();
            assert_eq!(back, lagrange, "order {k}, binary {binary}");
            meshio_reads(&path, lagrange.faces.len());
        }
        let path = dir.join(format!("viking-p{k}.vtu"));
        io::write_vtu_lagrange(&path, &lagrange, &[], &[], false).unwrap();
        let back = io::read_vtu(&path).unwrap().to_lagrange().unwrap();
        assert_eq!(back.nodes, lagrange.nodes, "order {k} vtu");
        assert_eq!(back.triangles, lagrange.triangles, "order {k} vtu");
        assert_eq!(back.params, lagrange.params, "order {k} vtu");
        meshio_reads(&path, lagrange.faces.len());
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// meshio reads `path` and finds `triangles` triangles.
fn meshio_reads(path: &std::path::Path, triangles: usize) {
    let script = format!(
        "import meshio, sys\nm = meshio.read(sys.argv[1])\nprint(sum(len(c.data) for c in m.cells if 'triangle' in c.type.lower()))"
    );
    let Ok(out) = std::process::Command::new("python3")
        .args(["-c", &script, path.to_str().unwrap()])
        .output()
    else {
        return meshio_missing("python3 not found");
    };
    let stderr = String::from_utf8_lossy(&out.stderr);
    if stderr.contains("No module named 'meshio'") {
        return meshio_missing("meshio not installed");
    }
    assert!(
        out.status.success(),
        "meshio failed on {}: {stderr}",
        path.display()
    );
    let count: usize = String::from_utf8_lossy(&out.stdout).trim().parse().unwrap();
    assert_eq!(
        count,
        triangles,
        "meshio's triangle count for {}",
        path.display()
    );
}

/// Bad orders and inconsistent meshes are refused by name, never a panic.
#[test]
fn bad_input_is_refused_by_name() {
    let net = example("cube", None);
    let surface = Surface::new(&net).unwrap();
    let mesh = Mesher::new(&surface)
        .density(Density::Uniform(1))
        .run()
        .unwrap();
    let message = |m: &loopsurf::SurfaceMesh, k: usize| {
        m.raise_order(&surface, k)
            .err()
            .expect("refused")
            .to_string()
    };
    assert!(message(&mesh, 0).contains("order 0"));
    assert!(message(&mesh, 5).contains("order 5"));
    let mut bad = mesh.clone();
    bad.faces.pop();
    assert!(message(&bad, 2).contains("faces"));
    let mut bad = mesh.clone();
    bad.params.pop();
    assert!(message(&bad, 2).contains("params"));
    let mut bad = mesh.clone();
    bad.charts.pop();
    assert!(message(&bad, 2).contains("charts"));
    let mut bad = mesh.clone();
    bad.triangles[0][1] = 10_000;
    assert!(message(&bad, 2).contains("10000"));
    let mut bad = mesh;
    bad.params[3].v = 2.0;
    let m = message(&bad, 2);
    assert!(m.contains("(v, w) = (2, 1)"), "{m}");
}

/// A missing python3 or meshio fails the test, as missing data does,
/// unless `LOOPSURF_SKIP_DATA` asks to skip (and the skip is said).
/// `scripts/test.sh` installs meshio with pip.
fn meshio_missing(why: &str) {
    if std::env::var_os("LOOPSURF_SKIP_DATA").is_some() {
        println!("{why}: meshio check skipped (LOOPSURF_SKIP_DATA)");
        return;
    }
    panic!("{why}: the meshio check needs it (scripts/test.sh installs it; LOOPSURF_SKIP_DATA=1 skips)");
}
