//! Triangle connectivity that changes in place: half-edges stored three per
//! triangle (half-edge `3t + i` runs from corner i of triangle t to corner
//! i + 1), each with its opposite, and the three local operations of
//! isotropic remeshing — split, collapse, flip — each in constant time.
//!
//! Dead triangles keep their slots (corner `NONE`) until [`Connectivity::
//! triangles`] compacts; dead vertices keep their index. Every half-edge
//! carries a label that moves with its edge (the model curve of a feature
//! edge, or `NONE`), every triangle one (its model face).
//!
//! Each vertex remembers one outgoing half-edge, and on a border (an edge
//! with one triangle) the one without an opposite, so that turning
//! counter-clockwise from it meets every outgoing half-edge before the
//! border stops it.

use crate::topology::NONE;
use std::collections::HashMap;

#[inline]
pub(crate) fn next(h: u32) -> u32 {
    if h % 3 == 2 {
        h - 2
    } else {
        h + 1
    }
}

#[inline]
pub(crate) fn prev(h: u32) -> u32 {
    if h % 3 == 0 {
        h + 2
    } else {
        h - 1
    }
}

#[derive(Debug, Clone)]
pub(crate) struct Connectivity {
    /// Origin vertex of each half-edge; `NONE` for a dead triangle's.
    origin: Vec<u32>,
    /// Opposite half-edge, `NONE` on a border.
    opposite: Vec<u32>,
    /// Per half-edge: the label of its edge (equal on both halves).
    pub(crate) edge_label: Vec<u32>,
    /// Per triangle: its label.
    pub(crate) face: Vec<u32>,
    /// Per vertex: an outgoing half-edge (the border one on a border),
    /// `NONE` for a dead vertex.
    out: Vec<u32>,
}

/// Why connectivity could not be built.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum BuildError {
    /// Two triangles run the same directed edge (a non-manifold or
    /// inconsistently oriented input).
    RepeatedEdge([u32; 2]),
    /// A vertex whose triangles form more than one fan.
    NonManifoldVertex(u32),
}

impl Connectivity {
    /// From triangles over `num_vertices` vertices (every one referenced),
    /// edge labels by vertex pair (unordered; unlisted edges `NONE`), and
    /// one face label per triangle.
    pub(crate) fn new(
        num_vertices: usize,
        triangles: &[[u32; 3]],
        edge_labels: &HashMap<(u32, u32), u32>,
        face: Vec<u32>,
    ) -> Result<Connectivity, BuildError> {
        let origin: Vec<u32> = triangles.iter().flatten().copied().collect();
        // Half-edges sorted by their undirected edge (then direction): the
        // two halves of an inner edge end up side by side.
        let mut keyed: Vec<(u64, u32)> = (0..origin.len() as u32)
            .map(|h| {
                let (a, b) = (origin[h as usize], origin[next(h) as usize]);
                let key = ((a.min(b) as u64) << 32) | a.max(b) as u64;
                (key << 1 | (a > b) as u64, h)
            })
            .collect();
        keyed.sort_unstable();
        let mut opposite = vec![NONE; origin.len()];
        let mut edge_label = vec![NONE; origin.len()];
        for run in keyed.chunk_by(|x, y| x.0 >> 1 == y.0 >> 1) {
            let key = run[0].0 >> 1;
            let (a, b) = ((key >> 32) as u32, key as u32);
            match run {
                [_] => {}
                [x, y] if x.0 != y.0 => {
                    opposite[x.1 as usize] = y.1;
                    opposite[y.1 as usize] = x.1;
                }
                // Two in one direction, or a third triangle on the edge.
                [_, y, ..] => {
                    let y = y.1;
                    return Err(BuildError::RepeatedEdge([
                        origin[y as usize],
                        origin[next(y) as usize],
                    ]));
                }
                [] => unreachable!("chunks are not empty"),
            }
            if let Some(&l) = edge_labels.get(&(a, b)) {
                for &(_, e) in run {
                    edge_label[e as usize] = l;
                }
            }
        }
        let mut out = vec![NONE; num_vertices];
        for h in 0..origin.len() as u32 {
            let v = origin[h as usize] as usize;
            if out[v] == NONE || opposite[h as usize] == NONE {
                out[v] = h;
            }
        }
        let mut mesh = Connectivity {
            origin,
            opposite,
            edge_label,
            face,
            out,
        };
        // One fan per vertex: turning around it meets all its half-edges.
        let mut seen = vec![0u32; num_vertices];
        for v in 0..num_vertices as u32 {
            if mesh.out[v as usize] != NONE {
                seen[v as usize] = mesh.outgoing(v).count() as u32;
            }
        }
        let mut total = vec![0u32; num_vertices];
        for &v in &mesh.origin {
            total[v as usize] += 1;
        }
        if let Some(v) = (0..num_vertices).find(|&v| seen[v] != total[v]) {
            return Err(BuildError::NonManifoldVertex(v as u32));
        }
        mesh.origin.shrink_to_fit();
        Ok(mesh)
    }

    pub(crate) fn num_half_edges(&self) -> u32 {
        self.origin.len() as u32
    }

    #[cfg(test)]
    pub(crate) fn num_vertices(&self) -> usize {
        self.out.len()
    }

    #[inline]
    pub(crate) fn origin(&self, h: u32) -> u32 {
        self.origin[h as usize]
    }

    #[inline]
    pub(crate) fn dest(&self, h: u32) -> u32 {
        self.origin[next(h) as usize]
    }

    #[inline]
    pub(crate) fn opposite(&self, h: u32) -> u32 {
        self.opposite[h as usize]
    }

    /// Whether half-edge h belongs to a live triangle.
    #[inline]
    pub(crate) fn is_alive(&self, h: u32) -> bool {
        self.origin[h as usize] != NONE
    }

    pub(crate) fn is_vertex_alive(&self, v: u32) -> bool {
        self.out[v as usize] != NONE
    }

    /// The triangle's corners, from half-edge h's origin.
    pub(crate) fn corners(&self, h: u32) -> [u32; 3] {
        [self.origin(h), self.dest(h), self.origin(prev(h))]
    }

    /// Whether the vertex lies on a border.
    pub(crate) fn is_border_vertex(&self, v: u32) -> bool {
        self.opposite(self.out[v as usize]) == NONE
    }

    /// The outgoing half-edges of v, counter-clockwise from its stored one.
    pub(crate) fn outgoing(&self, v: u32) -> Outgoing<'_> {
        let first = self.out[v as usize];
        Outgoing {
            mesh: self,
            first,
            next: first,
        }
    }

    /// The neighbours of v (each once): the destinations of its outgoing
    /// half-edges and, on a border, the origin of the last one's previous.
    pub(crate) fn neighbours(&self, v: u32, into: &mut Vec<u32>) {
        into.clear();
        let mut last = NONE;
        for h in self.outgoing(v) {
            into.push(self.dest(h));
            last = h;
        }
        if self.is_border_vertex(v) && last != NONE {
            into.push(self.origin(prev(last)));
        }
    }

    pub(crate) fn valence(&self, v: u32) -> usize {
        self.outgoing(v).count() + self.is_border_vertex(v) as usize
    }

    /// The half-edge from a to b, if any.
    pub(crate) fn find(&self, a: u32, b: u32) -> Option<u32> {
        self.outgoing(a).find(|&h| self.dest(h) == b)
    }

    /// Whether a and b are joined by an edge in either direction.
    pub(crate) fn joined(&self, a: u32, b: u32) -> bool {
        self.find(a, b).is_some() || self.find(b, a).is_some()
    }

    /// Stores, for v, its border half-edge if it has one: turns clockwise
    /// from `from` (an outgoing half-edge of v) until the border.
    fn settle(&mut self, v: u32, from: u32) {
        let mut h = from;
        loop {
            let o = self.opposite(h);
            if o == NONE {
                break;
            }
            h = next(o);
            if h == from {
                break;
            }
        }
        self.out[v as usize] = h;
    }

    fn link(&mut self, a: u32, b: u32) {
        if a != NONE {
            self.opposite[a as usize] = b;
        }
        if b != NONE {
            self.opposite[b as usize] = a;
        }
    }

    /// Appends a triangle with these corners, no opposites, labels NONE,
    /// and returns its first half-edge.
    fn push_triangle(&mut self, corners: [u32; 3], face: u32) -> u32 {
        let h = self.origin.len() as u32;
        self.origin.extend_from_slice(&corners);
        self.opposite.extend_from_slice(&[NONE; 3]);
        self.edge_label.extend_from_slice(&[NONE; 3]);
        self.face.push(face);
        h
    }

    /// Adds a vertex with no triangle yet (for [`Connectivity::split`]).
    pub(crate) fn add_vertex(&mut self) -> u32 {
        self.out.push(NONE);
        (self.out.len() - 1) as u32
    }

    /// Splits the edge of half-edge h (a → b) at the new vertex m: each
    /// triangle (a, b, c) on it becomes (a, m, c) and (m, b, c). Both halves
    /// keep the edge's label; the new edges to c get `NONE`.
    pub(crate) fn split(&mut self, h: u32, m: u32) {
        let g = self.opposite(h);
        let (a, b) = (self.origin(h), self.dest(h));
        let h2 = self.split_side(h, m);
        let label = self.edge_label[h as usize];
        self.edge_label[h2 as usize] = label;
        if g != NONE {
            let g2 = self.split_side(g, m);
            self.edge_label[g2 as usize] = label;
            // h: a → m pairs with g2: m → a; g: b → m with h2: m → b.
            self.link(h, g2);
            self.link(g, h2);
        }
        self.out[m as usize] = h2;
        self.settle(m, h2);
        for v in [a, b] {
            let o = self.out[v as usize];
            self.settle(v, o);
        }
    }

    /// The half of [`Connectivity::split`] in h's triangle (a, b, c):
    /// returns the new triangle's half-edge m → b.
    fn split_side(&mut self, h: u32, m: u32) -> u32 {
        let (b, c) = (self.dest(h), self.origin(prev(h)));
        let hn = next(h);
        let (outer, label) = (self.opposite(hn), self.edge_label[hn as usize]);
        let face = self.face[(h / 3) as usize];
        let t = self.push_triangle([m, b, c], face);
        // (m, b, c): t = m → b, t + 1 = b → c (the old hn's edge), t + 2 = c → m.
        self.origin[hn as usize] = m;
        self.edge_label[hn as usize] = NONE;
        self.link(t + 1, outer);
        self.edge_label[(t + 1) as usize] = label;
        self.link(hn, t + 2);
        if self.out[b as usize] == hn {
            self.out[b as usize] = t + 1;
        }
        t
    }

    /// Whether collapsing h's edge (either end into the other) keeps the
    /// mesh a manifold of the same topology: r and k share no neighbour but
    /// the triangles' third corners (the link condition), a border vertex
    /// goes only along its border, the third corners keep a valence of at
    /// least 3 (2 on a border), and no triangle folds onto another.
    pub(crate) fn can_collapse(&self, h: u32, scratch: &mut [Vec<u32>; 2]) -> bool {
        let g = self.opposite(h);
        let (r, k) = (self.origin(h), self.dest(h));
        if g == NONE {
            // A border edge: r must not be on another border pass.
        } else if self.is_border_vertex(r) && self.is_border_vertex(k) {
            return false;
        }
        let c = self.origin(prev(h));
        let d = if g == NONE {
            NONE
        } else {
            self.origin(prev(g))
        };
        for x in [c, d] {
            if x == NONE {
                continue;
            }
            let floor = if self.is_border_vertex(x) { 2 } else { 3 };
            if self.valence(x) <= floor {
                return false;
            }
        }
        let [ring_r, ring_k] = scratch;
        self.neighbours(r, ring_r);
        self.neighbours(k, ring_k);
        let shared = ring_r
            .iter()
            .filter(|x| ring_k.contains(x))
            .all(|&x| x == c || x == d);
        if !shared {
            return false;
        }
        // A one-triangle mesh piece, or a border triangle whose two other
        // sides are border edges, would lose its last triangle.
        !(g == NONE && self.opposite(next(h)) == NONE && self.opposite(prev(h)) == NONE)
    }

    /// Collapses h's edge: its end `r` merges into the other end k, and the
    /// one or two triangles on the edge vanish, their other two sides each
    /// becoming one edge, whose label is whichever side had one (the caller
    /// makes sure not both). Check [`Connectivity::can_collapse`] first.
    pub(crate) fn collapse(&mut self, h: u32, r: u32) {
        let g = self.opposite(h);
        let k = if self.origin(h) == r {
            self.dest(h)
        } else {
            self.origin(h)
        };
        let moved: Vec<u32> = self.outgoing(r).collect();
        for e in moved {
            self.origin[e as usize] = k;
        }
        let mut touched = vec![k];
        for e in [h, g] {
            if e == NONE {
                continue;
            }
            // Triangle (x, y, z) with e = x → y; its sides y → z and z → x
            // become one edge between their outer neighbours.
            let (en, ep) = (next(e), prev(e));
            let (on, op) = (self.opposite(en), self.opposite(ep));
            let label = match self.edge_label[en as usize] {
                NONE => self.edge_label[ep as usize],
                l => l,
            };
            self.link(on, op);
            for o in [on, op] {
                if o != NONE {
                    self.edge_label[o as usize] = label;
                }
            }
            // After the relabelling above, op runs k → z and on z → k (in
            // both triangles): whichever survives gives k and z an
            // outgoing half-edge.
            let z = self.origin(ep);
            self.out[z as usize] = if on != NONE { on } else { next(op) };
            self.out[k as usize] = if op != NONE { op } else { next(on) };
            touched.push(z);
            let t = e - e % 3;
            for i in t..t + 3 {
                self.origin[i as usize] = NONE;
                self.opposite[i as usize] = NONE;
            }
        }
        self.out[r as usize] = NONE;
        for v in touched {
            let o = self.out[v as usize];
            self.settle(v, o);
        }
    }

    /// Whether h's edge may be flipped: an inner edge whose two opposite
    /// corners are not already joined.
    pub(crate) fn can_flip(&self, h: u32) -> bool {
        let g = self.opposite(h);
        if g == NONE {
            return false;
        }
        let (c, d) = (self.origin(prev(h)), self.origin(prev(g)));
        c != d && !self.joined(c, d)
    }

    /// Flips h's edge (a, b) between triangles (a, b, c) and (b, a, d) to
    /// (c, d): the triangles become (a, d, c) and (d, b, c). The new edge
    /// is unlabelled (flip only unlabelled edges).
    pub(crate) fn flip(&mut self, h: u32) {
        let g = self.opposite(h);
        let (a, b, c, d) = (
            self.origin(h),
            self.dest(h),
            self.origin(prev(h)),
            self.origin(prev(g)),
        );
        let outer = |m: &Self, e: u32| (m.opposite(e), m.edge_label[e as usize]);
        let ad = outer(self, next(g));
        let db = outer(self, prev(g));
        let bc = outer(self, next(h));
        let ca = outer(self, prev(h));
        let (s, u) = (h - h % 3, g - g % 3);
        let set = |m: &mut Self, e: u32, from: u32, (o, l): (u32, u32)| {
            m.origin[e as usize] = from;
            m.edge_label[e as usize] = l;
            m.link(e, o);
        };
        // (a, d, c) in s: a → d, d → c, c → a; (d, b, c) in u: d → b, b → c, c → d.
        set(self, s, a, ad);
        set(self, s + 2, c, ca);
        set(self, u, d, db);
        set(self, u + 1, b, bc);
        self.origin[(s + 1) as usize] = d;
        self.origin[(u + 2) as usize] = c;
        self.edge_label[(s + 1) as usize] = NONE;
        self.edge_label[(u + 2) as usize] = NONE;
        self.link(s + 1, u + 2);
        for (v, e) in [(a, s), (c, s + 2), (d, u), (b, u + 1)] {
            self.settle(v, e);
        }
    }

    /// Drops dead slots and renumbers: `order` lists the live vertices in
    /// their new order (vertex `order[i]` becomes i), and triangles follow
    /// in the order of their smallest new corner. The passes walk the mesh
    /// by index and touch each element's neighbours, so an order in which
    /// neighbours are near in memory keeps those walks in cache.
    pub(crate) fn renumber(&mut self, order: &[u32]) {
        let mut new_vertex = vec![NONE; self.out.len()];
        for (i, &v) in order.iter().enumerate() {
            new_vertex[v as usize] = i as u32;
        }
        let mut triangles: Vec<(u32, u32)> = (0..self.face.len() as u32)
            .filter(|&t| self.is_alive(3 * t))
            .map(|t| {
                let first = self.corners(3 * t).map(|v| new_vertex[v as usize]);
                (first.into_iter().min().unwrap_or(NONE), t)
            })
            .collect();
        triangles.sort_unstable();
        let mut new_half = vec![NONE; self.origin.len()];
        for (i, &(_, t)) in triangles.iter().enumerate() {
            for k in 0..3 {
                new_half[(3 * t + k) as usize] = 3 * i as u32 + k;
            }
        }
        let map = |h: u32| {
            if h == NONE {
                NONE
            } else {
                new_half[h as usize]
            }
        };
        let half_edges = triangles.iter().flat_map(|&(_, t)| 3 * t..3 * t + 3);
        let origin = half_edges
            .clone()
            .map(|h| new_vertex[self.origin[h as usize] as usize])
            .collect();
        let opposite = half_edges
            .clone()
            .map(|h| map(self.opposite[h as usize]))
            .collect();
        let edge_label = half_edges.map(|h| self.edge_label[h as usize]).collect();
        let face = triangles
            .iter()
            .map(|&(_, t)| self.face[t as usize])
            .collect();
        let out = order.iter().map(|&v| map(self.out[v as usize])).collect();
        *self = Connectivity {
            origin,
            opposite,
            edge_label,
            face,
            out,
        };
    }

    /// The live triangles in slot order, with their face labels and a map
    /// from vertex to its compacted index (`NONE` for dead vertices).
    pub(crate) fn compact(&self) -> (Vec<[u32; 3]>, Vec<u32>, Vec<u32>) {
        let mut index = vec![NONE; self.out.len()];
        let mut count = 0;
        for (v, slot) in index.iter_mut().enumerate() {
            if self.out[v] != NONE {
                *slot = count;
                count += 1;
            }
        }
        let mut triangles = Vec::new();
        let mut faces = Vec::new();
        for t in 0..self.face.len() {
            let h = 3 * t as u32;
            if self.is_alive(h) {
                triangles.push(self.corners(h).map(|v| index[v as usize]));
                faces.push(self.face[t]);
            }
        }
        (triangles, faces, index)
    }
}

/// Counter-clockwise walk over a vertex's outgoing half-edges.
pub(crate) struct Outgoing<'a> {
    mesh: &'a Connectivity,
    first: u32,
    next: u32,
}

impl Iterator for Outgoing<'_> {
    type Item = u32;
    fn next(&mut self) -> Option<u32> {
        let h = self.next;
        if h == NONE {
            return None;
        }
        let o = self.mesh.opposite(prev(h));
        self.next = if o == self.first { NONE } else { o };
        Some(h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hexagon fan around vertex 0 (vertices 1..=6 on the rim), with
    /// every structural invariant checked after each operation.
    fn fan() -> Connectivity {
        let tris: Vec<[u32; 3]> = (0..6).map(|i| [0, 1 + i, 1 + (i + 1) % 6]).collect();
        Connectivity::new(7, &tris, &HashMap::new(), vec![0; 6]).unwrap()
    }

    fn check(m: &Connectivity) {
        for h in 0..m.num_half_edges() {
            if !m.is_alive(h) {
                continue;
            }
            let o = m.opposite(h);
            if o != NONE {
                assert!(m.is_alive(o));
                assert_eq!(m.opposite(o), h);
                assert_eq!(m.origin(o), m.dest(h));
                assert_eq!(m.dest(o), m.origin(h));
                assert_eq!(m.edge_label[o as usize], m.edge_label[h as usize]);
            }
        }
        for v in 0..m.num_vertices() as u32 {
            if !m.is_vertex_alive(v) {
                continue;
            }
            let total = (0..m.num_half_edges())
                .filter(|&h| m.is_alive(h) && m.origin(h) == v)
                .count();
            assert_eq!(m.outgoing(v).count(), total, "vertex {v}");
            assert!(m.outgoing(v).all(|h| m.origin(h) == v));
            let border = (0..m.num_half_edges())
                .any(|h| m.is_alive(h) && m.origin(h) == v && m.opposite(h) == NONE);
            assert_eq!(m.is_border_vertex(v), border, "vertex {v}");
        }
    }

    #[test]
    fn renumbering_drops_the_dead_and_keeps_the_mesh() {
        let mut m = fan();
        // Label a rim edge and give the triangles distinct faces, so that
        // both labels are seen to travel with their elements.
        m.face = (10..16).collect();
        let h = m.find(1, 2).unwrap();
        m.edge_label[h as usize] = 7;
        let spoke = m.find(0, 4).unwrap();
        m.collapse(spoke, 4);
        check(&m);
        let before: Vec<([u32; 3], u32)> = (0..m.face.len() as u32)
            .filter(|&t| m.is_alive(3 * t))
            .map(|t| (m.corners(3 * t), m.face[t as usize]))
            .collect();
        // Vertex 4 is dead; the others in reverse.
        let order = [6, 5, 3, 2, 1, 0];
        m.renumber(&order);
        check(&m);
        assert_eq!(m.num_vertices(), 6);
        assert_eq!(m.num_half_edges() as usize, 3 * before.len());
        let old = |v: u32| order[v as usize];
        // The same triangles (up to rotation), with their faces.
        let mut after: Vec<([u32; 3], u32)> = (0..m.face.len() as u32)
            .map(|t| (m.corners(3 * t).map(old), m.face[t as usize]))
            .collect();
        let canonical = |(c, f): ([u32; 3], u32)| {
            let k = (0..3).min_by_key(|&k| c[k]).unwrap();
            ([c[k], c[(k + 1) % 3], c[(k + 2) % 3]], f)
        };
        let mut before: Vec<_> = before.into_iter().map(canonical).collect();
        after = after.into_iter().map(canonical).collect();
        before.sort();
        after.sort();
        assert_eq!(before, after);
        let rim = m.find(4, 3).unwrap();
        assert_eq!(
            m.edge_label[rim as usize], 7,
            "the label moved with its edge"
        );
        // Triangles follow their smallest new corner.
        let firsts: Vec<u32> = (0..m.face.len() as u32)
            .map(|t| m.corners(3 * t).into_iter().min().unwrap())
            .collect();
        assert!(firsts.windows(2).all(|w| w[0] <= w[1]));
    }

    fn euler(m: &Connectivity) -> i64 {
        let (tris, _, index) = m.compact();
        let v = index.iter().filter(|&&i| i != NONE).count() as i64;
        let halves = 3 * tris.len() as i64;
        let border = (0..m.num_half_edges())
            .filter(|&h| m.is_alive(h) && m.opposite(h) == NONE)
            .count() as i64;
        let e = (halves + border) / 2;
        v - e + tris.len() as i64
    }

    #[test]
    fn split_flip_collapse_keep_a_disc() {
        let mut m = fan();
        check(&m);
        assert_eq!(euler(&m), 1);
        // Split an inner spoke and a rim (border) edge.
        let spoke = m.find(0, 1).unwrap();
        let x = m.add_vertex();
        m.split(spoke, x);
        check(&m);
        let rim = m.find(3, 4).unwrap();
        let y = m.add_vertex();
        m.split(rim, y);
        check(&m);
        assert_eq!(m.compact().0.len(), 9);
        assert_eq!(euler(&m), 1);
        // Flip a spoke next to the split.
        let h = m.find(0, 2).unwrap();
        assert!(m.can_flip(h));
        m.flip(h);
        check(&m);
        assert!(m.joined(x, 3));
        assert_eq!(euler(&m), 1);
        // Collapse the new rim vertex back along the border, then x into 0.
        let mut scratch = [Vec::new(), Vec::new()];
        let h = m.find(y, 4).unwrap();
        assert!(m.can_collapse(h, &mut scratch));
        m.collapse(h, m.origin(h));
        check(&m);
        assert_eq!(euler(&m), 1);
        let h = m.find(x, 0).or_else(|| m.find(0, x)).unwrap();
        let h = if m.origin(h) == x { h } else { m.opposite(h) };
        if m.can_collapse(h, &mut scratch) {
            m.collapse(h, m.origin(h));
            check(&m);
            assert_eq!(euler(&m), 1);
        }
    }

    #[test]
    fn link_condition_refuses_pinching() {
        // A border-to-border chord across the fan's centre must not
        // collapse (both ends on the border, the edge inside).
        let m = fan();
        let mut scratch = [Vec::new(), Vec::new()];
        let h = m.find(1, 2).unwrap();
        // 1 → 2 is a rim (border) edge: allowed.
        assert!(m.can_collapse(h, &mut scratch));
        let spoke = m.find(0, 1).unwrap();
        // 0 is inner, 1 on the border: allowed from 0's side.
        assert!(m.can_collapse(spoke, &mut scratch));
        // Valence-3 corner: a tetrahedron's edge cannot collapse.
        let tet = [[0, 2, 1], [0, 3, 2], [0, 1, 3], [1, 2, 3]];
        let t = Connectivity::new(4, &tet, &HashMap::new(), vec![0; 4]).unwrap();
        check(&t);
        let h = t.find(0, 1).unwrap();
        assert!(!t.can_collapse(h, &mut scratch));
        assert!(!t.can_flip(h));
    }

    #[test]
    fn repeated_and_nonmanifold_edges_are_refused() {
        let same_way = [[0, 1, 2], [0, 1, 3]];
        assert_eq!(
            Connectivity::new(4, &same_way, &HashMap::new(), vec![0; 2]).unwrap_err(),
            BuildError::RepeatedEdge([0, 1])
        );
        let three = [[0, 1, 2], [1, 0, 3], [1, 0, 4]];
        assert!(Connectivity::new(5, &three, &HashMap::new(), vec![0; 3]).is_err());
        // Two fans touching at vertex 0.
        let bowtie = [[0, 1, 2], [0, 3, 4]];
        assert_eq!(
            Connectivity::new(5, &bowtie, &HashMap::new(), vec![0; 2]).unwrap_err(),
            BuildError::NonManifoldVertex(0)
        );
    }

    #[test]
    fn closed_surface_survives_many_random_operations() {
        // An octahedron refined by splits, then flips and collapses in a
        // fixed pseudo-random order: the invariants and χ = 2 hold throughout.
        let tris = [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        let mut m = Connectivity::new(6, &tris, &HashMap::new(), vec![0; 8]).unwrap();
        let mut seed = 12345u64;
        let mut rand = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut scratch = [Vec::new(), Vec::new()];
        for step in 0..3000 {
            let h = (rand() % m.num_half_edges() as u64) as u32;
            if !m.is_alive(h) {
                continue;
            }
            match step % 3 {
                0 => {
                    let v = m.add_vertex();
                    m.split(h, v);
                }
                1 if m.can_flip(h) => m.flip(h),
                2 if m.can_collapse(h, &mut scratch) => {
                    let r = if rand() % 2 == 0 {
                        m.origin(h)
                    } else {
                        m.dest(h)
                    };
                    m.collapse(h, r)
                }
                _ => {}
            }
            check(&m);
            assert_eq!(euler(&m), 2, "step {step}");
        }
    }
}
