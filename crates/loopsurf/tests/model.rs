//! The BRep model of the hard features: corners, curves and
//! faces on the built-in examples and CGAL's fandisk, and the invariants
//! every model keeps.

mod common;

use loopsurf::model::{Curve, Model};
use loopsurf::{examples, ControlNet};

fn net(name: &str, angle: Option<f64>) -> ControlNet {
    let e = examples::by_name(name).unwrap();
    let mut net = ControlNet::from_arrays(e.points, &e.tris).unwrap();
    if let Some(a) = angle {
        net.tag_by_angle(a).unwrap();
    }
    net
}

fn model(net: &ControlNet) -> Model {
    Model::new(net.topology(), net.features())
}

/// The invariants every model keeps: a partition of the net's cells,
/// and loops that close.
fn check(net: &ControlNet, m: &Model) {
    let topo = net.topology();
    // Every hard edge in exactly one curve, no soft edge in any.
    let mut count = vec![0; topo.num_edges()];
    for c in m.curves() {
        assert_eq!(c.chain.len(), c.len() + 1);
        for (k, &e) in c.edges.iter().enumerate() {
            count[e as usize] += 1;
            let mut ends = [c.chain[k], c.chain[k + 1]];
            ends.sort_unstable();
            assert_eq!(topo.edges()[e as usize], ends);
        }
        assert_eq!(c.is_closed(), c.chain[0] == c.chain[c.len()]);
    }
    for e in 0..topo.num_edges() {
        assert_eq!(
            count[e],
            usize::from(net.features().is_hard_edge(e)),
            "edge {e}"
        );
    }
    // Every triangle in exactly one face.
    let mut seen = vec![0; topo.num_triangles()];
    for (f, face) in m.faces().iter().enumerate() {
        for &t in &face.triangles {
            seen[t as usize] += 1;
            assert_eq!(m.face_of_triangle()[t as usize], f as u32);
        }
    }
    assert!(seen.iter().all(|&s| s == 1));
    check_faces_are_soft_components(net, m);
    // Loops close: each curve run ends where the next begins, and the
    // face is on the side the loop says.
    for (f, face) in m.faces().iter().enumerate() {
        for lp in &face.loops {
            for (i, &(c, fwd)) in lp.iter().enumerate() {
                let curve = &m.curves()[c as usize];
                let side = if fwd { 0 } else { 1 };
                assert_eq!(curve.faces[side], Some(f as u32), "face {f} curve {c}");
                let end = if fwd {
                    curve.chain[curve.len()]
                } else {
                    curve.chain[0]
                };
                let (d, dfwd) = lp[(i + 1) % lp.len()];
                let next = &m.curves()[d as usize];
                let start = if dfwd {
                    next.chain[0]
                } else {
                    next.chain[next.len()]
                };
                assert_eq!(end, start, "face {f}: loop {lp:?}");
            }
        }
    }
    // The partition's Euler characteristic: open faces (triangles,
    // soft edges, vertices on no curve), open curves (-1, a closed one
    // 0) and corners add up to the net's.
    let on_curve: std::collections::HashSet<u32> = m
        .curves()
        .iter()
        .flat_map(|c| c.chain.iter().copied())
        .collect();
    let inner_vertices = (0..topo.num_vertices())
        .filter(|&v| !topo.is_unreferenced(v) && !on_curve.contains(&(v as u32)))
        .filter(|&v| !m.corners().contains(&(v as u32)))
        .count() as i64;
    let soft = (0..topo.num_edges())
        .filter(|&e| !net.features().is_hard_edge(e))
        .count() as i64;
    let open_curves = m.curves().iter().filter(|c| !c.is_closed()).count() as i64;
    let chi = inner_vertices - soft + topo.num_triangles() as i64 - open_curves
        + m.corners().len() as i64;
    assert_eq!(chi, topo.euler_characteristic());
}

/// Faces are the components of the triangles joined across soft edges:
/// a soft edge's two triangles lie in one face, and each face is connected
/// across its soft edges (a flood fill written here, from the edges'
/// triangles and hard flags alone).
fn check_faces_are_soft_components(net: &ControlNet, m: &Model) {
    let topo = net.topology();
    let of = m.face_of_triangle();
    let mut across: Vec<Vec<u32>> = vec![Vec::new(); topo.num_triangles()];
    for (e, pair) in topo.edge_triangles().iter().enumerate() {
        let [a, b] = *pair;
        if a == u32::MAX || b == u32::MAX || net.features().is_hard_edge(e) {
            continue;
        }
        assert_eq!(
            of[a as usize], of[b as usize],
            "soft edge {e} joins two faces"
        );
        across[a as usize].push(b);
        across[b as usize].push(a);
    }
    for (f, face) in m.faces().iter().enumerate() {
        let mut reached = std::collections::HashSet::from([face.triangles[0]]);
        let mut stack = vec![face.triangles[0]];
        while let Some(t) = stack.pop() {
            for &u in &across[t as usize] {
                if reached.insert(u) {
                    stack.push(u);
                }
            }
        }
        assert_eq!(
            reached.len(),
            face.triangles.len(),
            "face {f} is not connected"
        );
    }
}

#[test]
fn cube_has_eight_corners_twelve_curves_six_faces() {
    let net = net("cube", Some(30.0));
    let m = model(&net);
    check(&net, &m);
    assert_eq!(
        (m.corners().len(), m.curves().len(), m.faces().len()),
        (8, 12, 6)
    );
    for face in m.faces() {
        assert_eq!(face.loops.len(), 1);
        assert_eq!(face.loops[0].len(), 4);
    }
    for c in m.curves() {
        assert!(c.corners.is_some() && c.faces[0].is_some() && c.faces[1].is_some());
        assert_ne!(c.faces[0], c.faces[1]);
    }
}

#[test]
fn open_disk_has_one_closed_boundary_curve() {
    let net = net("open-disk", None);
    let m = model(&net);
    check(&net, &m);
    assert_eq!(
        (m.corners().len(), m.curves().len(), m.faces().len()),
        (0, 1, 1)
    );
    let c = &m.curves()[0];
    assert!(c.is_closed());
    // Its first edge's triangle runs it forward: the face is on its left.
    assert_eq!(c.faces, [Some(0), None]);
    assert_eq!(m.faces()[0].loops, vec![vec![(0, true)]]);
}

#[test]
fn a_dart_crease_is_a_slit_inside_its_face() {
    let mut net = net("sphere", None);
    let [a, b, c] = net.triangles()[0];
    net.tag_edge(a, b).unwrap();
    net.tag_edge(b, c).unwrap();
    let m = model(&net);
    check(&net, &m);
    // a and c are dart tips (corners); b is a crease vertex between.
    let mut tips = vec![a, c];
    tips.sort_unstable();
    assert_eq!(m.corners(), tips);
    assert_eq!((m.curves().len(), m.faces().len()), (1, 1));
    let curve = &m.curves()[0];
    assert_eq!(curve.len(), 2);
    assert_eq!(curve.chain[1], b);
    assert_eq!(curve.faces, [Some(0), Some(0)]);
    let lp = &m.faces()[0].loops;
    assert_eq!(lp.len(), 1);
    let mut runs = lp[0].clone();
    runs.sort_unstable();
    assert_eq!(runs, vec![(0, false), (0, true)]);
}

#[test]
fn viking_has_two_closed_crease_loops_and_three_faces() {
    let net = net("viking", Some(30.0));
    let m = model(&net);
    check(&net, &m);
    assert_eq!(
        (m.corners().len(), m.curves().len(), m.faces().len()),
        (0, 2, 3)
    );
    assert!(m.curves().iter().all(Curve::is_closed));
    // The middle face is bounded by both loops, the caps by one each.
    let mut loops: Vec<usize> = m.faces().iter().map(|f| f.loops.len()).collect();
    loops.sort_unstable();
    assert_eq!(loops, vec![1, 1, 2]);
}

#[test]
fn ids_follow_file_order() {
    let net = net("cube", Some(30.0));
    let m = model(&net);
    let firsts: Vec<u32> = m
        .curves()
        .iter()
        .map(|c| c.edges.iter().copied().min().unwrap())
        .collect();
    let mut sorted = firsts.clone();
    sorted.sort_unstable();
    assert_eq!(firsts, sorted);
    let faces: Vec<u32> = m.faces().iter().map(|f| f.triangles[0]).collect();
    assert!(faces.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(m.faces()[0].triangles[0], 0);
}

#[test]
fn fandisk_model_keeps_the_invariants() {
    let Some(path) = common::cgal_mesh("fandisk.off") else {
        return;
    };
    let mut net = ControlNet::read(path).unwrap();
    net.tag_by_angle(30.0).unwrap();
    let m = model(&net);
    check(&net, &m);
    assert!(m.faces().len() > 10 && m.curves().len() > 10 && !m.corners().is_empty());
    // Every corner ends a curve or stands alone as a tagged vertex.
    for (id, _) in m.corners().iter().enumerate() {
        let ends = m
            .curves()
            .iter()
            .filter(|c| {
                c.corners
                    .is_some_and(|[a, b]| a == id as u32 || b == id as u32)
            })
            .count();
        assert!(ends > 0, "corner {id} ends no curve");
    }
}
