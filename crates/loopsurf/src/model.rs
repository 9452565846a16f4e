//! The BRep view of a control net for mesh generators: corners, curves and
//! faces, named by stable 0-based ids (DESIGN.md, "The model").
//!
//! - **Corners** are the vertices the crease rules fix or end at: tagged
//!   vertices and vertices with other than two hard edges (so boundary
//!   corners, crease junctions, and the tips of darts). A dart's crease ends
//!   inside a face: its tip is a corner, its curve has that face on both
//!   sides, and the face's loop runs out along the curve and back (a slit).
//!   A tagged vertex with no hard edge is a corner on no curve.
//! - **Curves** are maximal chains of hard edges whose inner vertices have
//!   exactly two hard edges and are not tagged, ending at corners, or closed
//!   loops without any corner.
//! - **Faces** are maximal sets of triangles connected across soft edges.
//!
//! Ids follow file order: corners by vertex index, curves by their first
//! hard edge in edge order (edges number by first appearance in the
//! triangle list), faces by their first triangle. A curve runs the way the
//! first triangle of its first edge traverses that edge, so that triangle's
//! face has the curve forward in its loop; a closed curve starts at that
//! edge.
//!
//! Everything here is connectivity: built from the net in linear time,
//! before any evaluation. Curve evaluation lives in [`crate::curve`].

use crate::features::{Features, VertexKind};
use crate::topology::{Topology, NONE};

/// One model edge (a crease curve, a boundary curve or a closed loop).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Curve {
    /// Control vertices in parameter order: n + 1 of them for n control
    /// edges; a closed curve repeats its first vertex at the end.
    pub chain: Vec<u32>,
    /// The control edges (ids in [`Topology::edges`]), edge k joining
    /// `chain[k]` and `chain[k + 1]`.
    pub edges: Vec<u32>,
    /// Corner ids at t = 0 and t = n; `None` for a closed loop.
    pub corners: Option<[u32; 2]>,
    /// The face on the curve's left (its triangles traverse the chain
    /// forward) and on its right (backward); `None` where there is no
    /// triangle (a boundary). A dart's slit has the same face on both sides.
    pub faces: [Option<u32>; 2],
}

impl Curve {
    /// Number of control edges n: the parameter runs over [0, n].
    pub fn len(&self) -> usize {
        self.edges.len()
    }

    /// Whether the curve is a closed loop (no corner).
    pub fn is_closed(&self) -> bool {
        self.corners.is_none()
    }
}

/// One model face: the triangles and the loops of curves around them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Face {
    /// Control triangles, ascending.
    pub triangles: Vec<u32>,
    /// Bounding loops: curves in the order the face's triangles traverse
    /// its boundary (counter-clockwise seen from outside), each with
    /// `true` when traversed in the curve's own direction.
    pub loops: Vec<Vec<(u32, bool)>>,
}

/// Corners, curves and faces of a control net with its hard features.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Model {
    corners: Vec<u32>,
    curves: Vec<Curve>,
    faces: Vec<Face>,
    face_of_triangle: Vec<u32>,
    curve_of_edge: Vec<u32>,
}

impl Model {
    /// The model of `topo` with hard edges and tags `features`.
    pub fn new(topo: &Topology, features: &Features) -> Model {
        let kinds = features.vertex_kinds(topo);
        let corner_vertex = |v: usize| {
            !topo.is_unreferenced(v) && matches!(kinds[v], VertexKind::Corner | VertexKind::Dart)
        };
        let corners: Vec<u32> = (0..topo.num_vertices())
            .filter(|&v| corner_vertex(v))
            .map(|v| v as u32)
            .collect();
        let mut corner_id = vec![NONE; topo.num_vertices()];
        for (id, &v) in corners.iter().enumerate() {
            corner_id[v as usize] = id as u32;
        }
        let (face_of_triangle, mut faces) = faces_of(topo, features);
        let curves = curves_of(topo, features, &corner_id, &face_of_triangle);
        let mut curve_of_edge = vec![NONE; topo.num_edges()];
        let mut edge_pos = vec![NONE; topo.num_edges()];
        for (c, curve) in curves.iter().enumerate() {
            for (k, &e) in curve.edges.iter().enumerate() {
                curve_of_edge[e as usize] = c as u32;
                edge_pos[e as usize] = k as u32;
            }
        }
        for (f, face) in faces.iter_mut().enumerate() {
            face.loops = loops_of(
                topo,
                &face_of_triangle,
                &curve_of_edge,
                &edge_pos,
                &curves,
                f as u32,
            );
        }
        Model {
            corners,
            curves,
            faces,
            face_of_triangle,
            curve_of_edge,
        }
    }

    /// Corners as control-vertex indices; a corner's id is its position.
    pub fn corners(&self) -> &[u32] {
        &self.corners
    }
    /// Curves by id.
    pub fn curves(&self) -> &[Curve] {
        &self.curves
    }
    /// Faces by id.
    pub fn faces(&self) -> &[Face] {
        &self.faces
    }
    /// The face id of every control triangle.
    pub fn face_of_triangle(&self) -> &[u32] {
        &self.face_of_triangle
    }
    /// The curve id of every control edge, `None` for soft edges.
    pub fn curve_of_edge(&self, e: usize) -> Option<u32> {
        self.curve_of_edge.get(e).copied().filter(|&c| c != NONE)
    }
}

/// Flood fill across soft edges, in triangle order.
fn faces_of(topo: &Topology, features: &Features) -> (Vec<u32>, Vec<Face>) {
    let nt = topo.num_triangles();
    let mut face_of = vec![NONE; nt];
    let mut faces = Vec::new();
    for seed in 0..nt {
        if face_of[seed] != NONE {
            continue;
        }
        let id = faces.len() as u32;
        face_of[seed] = id;
        let mut triangles = vec![seed as u32];
        let mut k = 0;
        while k < triangles.len() {
            let t = triangles[k] as usize;
            k += 1;
            for &e in &topo.triangle_edges()[t] {
                if features.is_hard_edge(e as usize) {
                    continue;
                }
                for u in topo.edge_triangles()[e as usize] {
                    if u != NONE && face_of[u as usize] == NONE {
                        face_of[u as usize] = id;
                        triangles.push(u);
                    }
                }
            }
        }
        triangles.sort_unstable();
        faces.push(Face {
            triangles,
            loops: Vec::new(),
        });
    }
    (face_of, faces)
}

/// Whether triangle `t` runs from a to b.
pub(crate) fn runs(topo: &Topology, t: u32, a: u32, b: u32) -> bool {
    let c = topo.triangles()[t as usize];
    (0..3).any(|k| c[k] == a && c[(k + 1) % 3] == b)
}

/// Traces every curve, in order of its first hard edge.
fn curves_of(
    topo: &Topology,
    features: &Features,
    corner_id: &[u32],
    face_of: &[u32],
) -> Vec<Curve> {
    let ne = topo.num_edges();
    // The hard edges at each vertex (at most two at a non-corner).
    let mut hard_at: Vec<Vec<u32>> = vec![Vec::new(); topo.num_vertices()];
    for e in 0..ne {
        if features.is_hard_edge(e) {
            for v in topo.edges()[e] {
                hard_at[v as usize].push(e as u32);
            }
        }
    }
    let other_end = |e: u32, v: u32| {
        let [a, b] = topo.edges()[e as usize];
        if a == v {
            b
        } else {
            a
        }
    };
    // From vertex v, having arrived by edge e: the next edge, unless v ends
    // the curve.
    let next_edge = |v: u32, e: u32| -> Option<u32> {
        if corner_id[v as usize] != NONE {
            return None;
        }
        hard_at[v as usize].iter().copied().find(|&x| x != e)
    };
    let mut seen = vec![false; ne];
    let mut curves = Vec::new();
    for first in 0..ne as u32 {
        if !features.is_hard_edge(first as usize) || seen[first as usize] {
            continue;
        }
        // Direction: as the edge's first triangle runs it.
        let [a, b] = topo.edges()[first as usize];
        let t0 = topo.edge_triangles()[first as usize][0];
        let (start, end) = if runs(topo, t0, a, b) { (a, b) } else { (b, a) };
        // Forward from `end`.
        let mut chain = vec![start, end];
        let mut edges = vec![first];
        seen[first as usize] = true;
        let (mut v, mut e) = (end, first);
        let mut closed = false;
        while let Some(x) = next_edge(v, e) {
            if x == first {
                closed = true;
                break;
            }
            seen[x as usize] = true;
            v = other_end(x, v);
            e = x;
            chain.push(v);
            edges.push(x);
        }
        if !closed {
            // Backward from `start`, prepended.
            let (mut back_v, mut back_e) = (start, first);
            let (mut pre_chain, mut pre_edges) = (Vec::new(), Vec::new());
            while let Some(x) = next_edge(back_v, back_e) {
                seen[x as usize] = true;
                back_v = other_end(x, back_v);
                back_e = x;
                pre_chain.push(back_v);
                pre_edges.push(x);
            }
            pre_chain.reverse();
            pre_edges.reverse();
            pre_chain.extend(chain);
            pre_edges.extend(edges);
            chain = pre_chain;
            edges = pre_edges;
        }
        let corners = (!closed).then(|| {
            [
                corner_id[chain[0] as usize],
                corner_id[*chain.last().unwrap_or(&chain[0]) as usize],
            ]
        });
        // Left: the triangle of the first edge that runs it forward.
        let side = |forward: bool| {
            let e = edges[0] as usize;
            let (p, q) = (chain[0], chain[1]);
            topo.edge_triangles()[e]
                .into_iter()
                .filter(|&t| t != NONE)
                .find(|&t| runs(topo, t, p, q) == forward)
                .map(|t| face_of[t as usize])
        };
        let faces = [side(true), side(false)];
        curves.push(Curve {
            chain,
            edges,
            corners,
            faces,
        });
    }
    curves
}

/// The loops of face `f`: its boundary half-edges (hard edges as its
/// triangles run them) chained around the face, then grouped by curve.
fn loops_of(
    topo: &Topology,
    face_of: &[u32],
    curve_of_edge: &[u32],
    edge_pos: &[u32],
    curves: &[Curve],
    f: u32,
) -> Vec<Vec<(u32, bool)>> {
    // Half-edges (triangle, local edge k: corner k to corner k + 1) on hard
    // edges, in triangle order.
    let tris = topo.triangles();
    let mut half: Vec<(u32, usize)> = Vec::new();
    for (t, _) in face_of.iter().enumerate().filter(|&(_, &g)| g == f) {
        for k in 0..3 {
            let e = topo.triangle_edges()[t][k];
            if curve_of_edge[e as usize] != NONE {
                half.push((t as u32, k));
            }
        }
    }
    let index = |h: (u32, usize)| half.binary_search(&h).ok();
    // The next boundary half-edge after (t, k) around its end vertex,
    // turning through the face's triangles across soft edges.
    let next = |(t, k): (u32, usize)| -> (u32, usize) {
        let (mut t, mut k) = (t, (k + 1) % 3);
        loop {
            let e = topo.triangle_edges()[t as usize][k];
            if curve_of_edge[e as usize] != NONE {
                return (t, k);
            }
            // Cross the soft edge (v → w) to the triangle running w → v,
            // whose next half-edge leaves v again.
            let [u0, u1] = topo.edge_triangles()[e as usize];
            let u = if u0 == t { u1 } else { u0 };
            let v = tris[t as usize][k];
            let j = (0..3).find(|&j| tris[u as usize][j] == v).unwrap_or(0);
            t = u;
            k = j;
        }
    };
    let mut used = vec![false; half.len()];
    let mut loops = Vec::new();
    for i in 0..half.len() {
        if used[i] {
            continue;
        }
        let mut cycle = Vec::new();
        let mut h = half[i];
        while let Some(j) = index(h).filter(|&j| !used[j]) {
            used[j] = true;
            cycle.push(h);
            h = next(h);
        }
        // Each traversal of a curve starts at one of its ends (its inner
        // vertices have two hard edges, so the walk stays on it): a run is
        // (curve, forward) from such a start to the next.
        let step = |(t, k): (u32, usize)| {
            let e = topo.triangle_edges()[t as usize][k] as usize;
            let curve = &curves[curve_of_edge[e] as usize];
            let pos = edge_pos[e] as usize;
            let a = tris[t as usize][k];
            let forward = curve.chain[pos] == a;
            let start = if forward {
                pos == 0
            } else {
                pos + 1 == curve.len()
            };
            ((curve_of_edge[e], forward), start)
        };
        let steps: Vec<((u32, bool), bool)> = cycle.iter().map(|&h| step(h)).collect();
        loops.push(steps.iter().filter(|s| s.1).map(|s| s.0).collect());
    }
    loops
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::examples;
    use crate::net::ControlNet;

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
}
