//! The BRep view of a control net for mesh generators: corners, curves and
//! faces, named by stable 0-based ids (docs/design.md, "The model").
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
    let mut tracer = Tracer::new(topo, features, corner_id);
    let mut curves = Vec::new();
    for first in 0..topo.num_edges() as u32 {
        if !features.is_hard_edge(first as usize) || tracer.seen[first as usize] {
            continue;
        }
        curves.push(tracer.trace(first, face_of));
    }
    curves
}

/// Follows hard edges from vertex to vertex, each edge once.
struct Tracer<'a> {
    topo: &'a Topology,
    corner_id: &'a [u32],
    /// The hard edges at each vertex (at most two at a non-corner).
    hard_at: Vec<Vec<u32>>,
    /// The edges already on a curve.
    seen: Vec<bool>,
}

impl<'a> Tracer<'a> {
    fn new(topo: &'a Topology, features: &Features, corner_id: &'a [u32]) -> Tracer<'a> {
        let ne = topo.num_edges();
        let mut hard_at: Vec<Vec<u32>> = vec![Vec::new(); topo.num_vertices()];
        for e in 0..ne {
            if features.is_hard_edge(e) {
                for v in topo.edges()[e] {
                    hard_at[v as usize].push(e as u32);
                }
            }
        }
        Tracer {
            topo,
            corner_id,
            hard_at,
            seen: vec![false; ne],
        }
    }

    /// The curve through hard edge `first`, directed as the edge's first
    /// triangle runs it: forward from its end and, unless that closes,
    /// backward from its start.
    fn trace(&mut self, first: u32, face_of: &[u32]) -> Curve {
        let topo = self.topo;
        let [a, b] = topo.edges()[first as usize];
        let t0 = topo.edge_triangles()[first as usize][0];
        let (start, end) = if runs(topo, t0, a, b) { (a, b) } else { (b, a) };
        let mut chain = vec![start, end];
        let mut edges = vec![first];
        self.seen[first as usize] = true;
        let (ahead, ahead_edges, closed) = self.walk(end, first, Some(first));
        chain.extend(ahead);
        edges.extend(ahead_edges);
        if !closed {
            // Backward from `start`, prepended.
            let (mut pre_chain, mut pre_edges, _) = self.walk(start, first, None);
            pre_chain.reverse();
            pre_edges.reverse();
            pre_chain.extend(chain);
            pre_edges.extend(edges);
            chain = pre_chain;
            edges = pre_edges;
        }
        let corners = (!closed).then(|| {
            [
                self.corner_id[chain[0] as usize],
                self.corner_id[*chain.last().unwrap_or(&chain[0]) as usize],
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
        Curve {
            chain,
            edges,
            corners,
            faces,
        }
    }

    /// From vertex v, having arrived by edge e, the vertices and edges on
    /// until the curve ends (at a corner or an end of the hard edges) or
    /// comes back to edge `closing` (then the last value is true).
    fn walk(&mut self, mut v: u32, mut e: u32, closing: Option<u32>) -> (Vec<u32>, Vec<u32>, bool) {
        let (mut chain, mut edges) = (Vec::new(), Vec::new());
        while let Some(x) = self.next_edge(v, e) {
            if Some(x) == closing {
                return (chain, edges, true);
            }
            self.seen[x as usize] = true;
            v = self.other_end(x, v);
            e = x;
            chain.push(v);
            edges.push(x);
        }
        (chain, edges, false)
    }

    /// From vertex v, having arrived by edge e: the next edge, unless v
    /// ends the curve.
    fn next_edge(&self, v: u32, e: u32) -> Option<u32> {
        if self.corner_id[v as usize] != NONE {
            return None;
        }
        self.hard_at[v as usize].iter().copied().find(|&x| x != e)
    }

    /// The end of edge e that is not v.
    fn other_end(&self, e: u32, v: u32) -> u32 {
        let [a, b] = self.topo.edges()[e as usize];
        if a == v {
            b
        } else {
            a
        }
    }
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
