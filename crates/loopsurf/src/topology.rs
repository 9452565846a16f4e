//! Connectivity of a triangulation: edges, edge–triangle adjacency, ordered
//! vertex rings and boundary loops. Knows nothing of positions.
//!
//! There is no valence limit anywhere: rings are stored in compressed
//! (CSR) arrays sized by the mesh itself.

use crate::error::{Error, Result};
use crate::sets::DisjointSets;
use rayon::prelude::*;
use std::sync::OnceLock;

/// Marks a missing triangle (the outside of a boundary edge).
pub use crate::geometry::NONE;

/// Fewest items per rayon task in per-element loops. Below twice this a
/// loop runs on the calling thread without touching the pool: the small
/// local nets of special configurations, built during an evaluation, then
/// neither wake workers nor let the evaluating thread steal other work
/// while it builds, and small nets refine without waking the pool.
pub(crate) const MIN_PER_TASK: usize = 4096;

/// Edges and adjacency of a manifold, consistently oriented triangulation.
#[derive(Debug)]
pub struct Topology {
    nverts: usize,
    tris: Vec<[u32; 3]>,
    /// Edge endpoints, smaller index first (every level keeps this, and
    /// [`Topology::refined`] relies on it). An input net numbers its edges
    /// in order of first appearance in the triangle list, so refined vertices
    /// (one per edge) follow the input's triangle order; a refined level
    /// numbers them as [`Topology::refined`] says.
    edges: Vec<[u32; 2]>,
    /// The one or two triangles of each edge; the second is [`NONE`] on a boundary.
    edge_tris: Vec<[u32; 2]>,
    /// Local edge i of a triangle joins corners i and i+1 (mod 3).
    tri_edges: Vec<[u32; 3]>,
    rings: OnceLock<Rings>,
}

/// Counter-clockwise fans and neighbour rings of every vertex (CSR).
#[derive(Debug)]
struct Rings {
    fan_start: Vec<u32>,
    fan: Vec<u32>,
    ring_start: Vec<u32>,
    ring: Vec<u32>,
}

impl Topology {
    /// Builds and validates the topology of `tris` over `nverts` vertices.
    ///
    /// Indices must already be in range and distinct within each triangle.
    /// Fails on non-manifold edges, inconsistently oriented neighbours and
    /// non-manifold vertices.
    pub(crate) fn new(nverts: usize, tris: Vec<[u32; 3]>) -> Result<Topology> {
        let (edges, edge_tris, tri_edges) = build_edges(&tris)?;
        let topo = Topology {
            nverts,
            tris,
            edges,
            edge_tris,
            tri_edges,
            rings: OnceLock::new(),
        };
        let rings = topo.build_rings()?;
        let _ = topo.rings.set(rings);
        // Two triangles on the same three corners close a "pillow": its
        // interior vertices have two neighbours and no tangent plane.
        if let Some(v) = (0..nverts).find(|&v| {
            !topo.is_boundary_vertex(v) && !topo.is_unreferenced(v) && topo.valence(v) < 3
        }) {
            return Err(Error::InteriorValenceTwo {
                vertex: v as u32,
                tris: topo.fan(v).to_vec(),
            });
        }
        Ok(topo)
    }

    /// The topology after one step of 1-to-4 triangle splitting, derived
    /// directly from this one (no searching): old vertex i keeps index i, the
    /// new vertex on edge e is `nverts + e`; triangle t has children
    /// `4t .. 4t+4` = (c0 m0 m2), (m0 c1 m1), (m2 m1 c2), (m1 m2 m0) where mᵢ
    /// is the midpoint of local edge i; edge e has halves `2e` (touching its
    /// first endpoint) and `2e+1`, and triangle t adds the interior edges
    /// `2E + 3t + i`.
    pub fn refined(&self) -> Topology {
        self.refined_with(MIN_PER_TASK)
    }

    /// [`Topology::refined`] on the calling thread alone: no task goes to
    /// the thread pool, so a caller may build it while other threads wait
    /// on a lock it holds (a pool thread waiting for it can never be
    /// holding a task it needs).
    pub(crate) fn refined_here(&self) -> Topology {
        self.refined_with(usize::MAX)
    }

    /// [`Topology::refined`], each loop split into tasks of at least
    /// `min_len` items.
    fn refined_with(&self, min_len: usize) -> Topology {
        // Every output slot is a pure function of its parent, so each array
        // is filled in place, in parallel, with no searching or scattering.
        let ne = self.edges.len();
        let nt = self.tris.len();
        let mut edges = vec![[0u32; 2]; 2 * ne + 3 * nt];
        let mut tris = vec![[0u32; 3]; 4 * nt];
        let mut tri_edges = vec![[0u32; 3]; 4 * nt];
        // Zero-filled allocations come straight from the OS; every slot is
        // overwritten below.
        let mut edge_tris = vec![[0u32; 2]; 2 * ne + 3 * nt];
        let (halves, inner) = edges.split_at_mut(2 * ne);
        self.fill_halves(halves, min_len);
        let (half_tris, inner_tris) = edge_tris.split_at_mut(2 * ne);
        self.fill_half_triangles(half_tris, min_len);
        inner_tris
            .par_chunks_mut(3)
            .with_min_len(min_len)
            .enumerate()
            .for_each(|(t, out)| {
                let t = t as u32;
                for (i, slot) in out.iter_mut().enumerate() {
                    *slot = [4 * t + i as u32, 4 * t + 3];
                }
            });
        self.fill_children(inner, &mut tris, &mut tri_edges, min_len);
        Topology {
            nverts: self.nverts + ne,
            tris,
            edges,
            edge_tris,
            tri_edges,
            rings: OnceLock::new(),
        }
    }

    /// The refined edges 2e and 2e + 1: edge e's halves, from each end to
    /// its midpoint vertex.
    fn fill_halves(&self, halves: &mut [[u32; 2]], min_len: usize) {
        let nv = self.nverts as u32;
        halves
            .par_chunks_mut(2)
            .with_min_len(min_len)
            .enumerate()
            .for_each(|(e, out)| {
                let [a, b] = self.edges[e];
                let m = nv + e as u32;
                out[0] = [a, m];
                out[1] = [b, m];
            });
    }

    /// The triangles of edge e's halves: the children at each end's corner
    /// of e's triangles.
    fn fill_half_triangles(&self, half_tris: &mut [[u32; 2]], min_len: usize) {
        half_tris
            .par_chunks_mut(2)
            .with_min_len(min_len)
            .enumerate()
            .for_each(|(e, out)| {
                // The half of edge e at vertex v lies in the children at v's
                // corner of e's triangles.
                let child = |t: u32, v: u32| match t {
                    NONE => NONE,
                    t => 4 * t + corner_of(self.tris[t as usize], v),
                };
                let [t0, t1] = self.edge_tris[e];
                for (h, &v) in self.edges[e].iter().enumerate() {
                    out[h] = [child(t0, v), child(t1, v)];
                }
            });
    }

    /// Each triangle's three interior edges and four children, with the
    /// children's edges.
    fn fill_children(
        &self,
        inner: &mut [[u32; 2]],
        tris: &mut [[u32; 3]],
        tri_edges: &mut [[u32; 3]],
        min_len: usize,
    ) {
        let nv = self.nverts as u32;
        let ne = self.edges.len();
        inner
            .par_chunks_mut(3)
            .zip(tris.par_chunks_mut(4))
            .zip(tri_edges.par_chunks_mut(4))
            .with_min_len(min_len)
            .enumerate()
            .for_each(|(t, ((inner_edges, child_tris), child_edges))| {
                let c = self.tris[t];
                let te = self.tri_edges[t];
                let m = te.map(|e| nv + e);
                // Edges store their smaller end first, so the half of local
                // edge i touching v is decided by comparing v with the other end.
                let half = |i: usize, v: u32| {
                    let other = if c[i] == v { c[(i + 1) % 3] } else { c[i] };
                    2 * te[i] + u32::from(v > other)
                };
                let first_inner = 2 * ne as u32 + 3 * t as u32;
                let inner = |i: u32| first_inner + i;
                // Interior edge i lies opposite corner i, in child i.
                inner_edges[0] = sorted(m[0], m[2]);
                inner_edges[1] = sorted(m[1], m[0]);
                inner_edges[2] = sorted(m[2], m[1]);
                child_tris[0] = [c[0], m[0], m[2]];
                child_edges[0] = [half(0, c[0]), inner(0), half(2, c[0])];
                child_tris[1] = [m[0], c[1], m[1]];
                child_edges[1] = [half(0, c[1]), half(1, c[1]), inner(1)];
                child_tris[2] = [m[2], m[1], c[2]];
                child_edges[2] = [inner(2), half(1, c[2]), half(2, c[2])];
                child_tris[3] = [m[1], m[2], m[0]];
                child_edges[3] = [inner(2), inner(0), inner(1)];
            });
    }

    /// Number of vertices, including unreferenced ones.
    pub fn num_vertices(&self) -> usize {
        self.nverts
    }
    /// Number of triangles.
    pub fn num_triangles(&self) -> usize {
        self.tris.len()
    }
    /// Number of edges.
    pub fn num_edges(&self) -> usize {
        self.edges.len()
    }
    /// Triangles as vertex triples.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.tris
    }
    /// Edge endpoints, smaller index first.
    pub fn edges(&self) -> &[[u32; 2]] {
        &self.edges
    }
    /// The one or two triangles of each edge ([`NONE`] for the missing one).
    pub fn edge_triangles(&self) -> &[[u32; 2]] {
        &self.edge_tris
    }
    /// The three edges of each triangle; local edge i joins corners i, i+1.
    pub fn triangle_edges(&self) -> &[[u32; 3]] {
        &self.tri_edges
    }
    /// Whether edge e has only one triangle.
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.edge_tris[e][1] == NONE
    }
    /// The edge joining a and b, if there is one.
    pub fn find_edge(&self, a: u32, b: u32) -> Option<usize> {
        let rings = self.rings();
        let v = a as usize;
        let fan = &rings.fan[rings.fan_start[v] as usize..rings.fan_start[v + 1] as usize];
        fan.iter().find_map(|&t| {
            self.tri_edges[t as usize]
                .iter()
                .copied()
                .find(|&e| self.edges[e as usize] == sorted(a, b))
                .map(|e| e as usize)
        })
    }
    /// Number of connected pieces (triangles joined across edges).
    pub fn num_components(&self) -> usize {
        let mut seen = vec![false; self.tris.len()];
        let mut stack = Vec::new();
        let mut pieces = 0;
        for start in 0..self.tris.len() {
            if seen[start] {
                continue;
            }
            pieces += 1;
            seen[start] = true;
            stack.push(start);
            while let Some(t) = stack.pop() {
                for &e in &self.tri_edges[t] {
                    for &n in &self.edge_tris[e as usize] {
                        if n != NONE && !seen[n as usize] {
                            seen[n as usize] = true;
                            stack.push(n as usize);
                        }
                    }
                }
            }
        }
        pieces
    }

    /// Triangles around v in counter-clockwise order; on a boundary the fan
    /// starts at the triangle whose edge (v, next) is a boundary edge.
    pub fn fan(&self, v: usize) -> &[u32] {
        let r = self.rings();
        &r.fan[r.fan_start[v] as usize..r.fan_start[v + 1] as usize]
    }
    /// Neighbours of v in counter-clockwise order (the "one-ring"). Interior
    /// vertices have as many neighbours as triangles; boundary vertices one
    /// more, and their ring starts and ends on the boundary.
    pub fn ring(&self, v: usize) -> &[u32] {
        let r = self.rings();
        &r.ring[r.ring_start[v] as usize..r.ring_start[v + 1] as usize]
    }
    /// Bytes held, rings included once ordered.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of_val;
        let rings = self.rings.get().map_or(0, |r| {
            size_of_val(&r.fan_start[..])
                + size_of_val(&r.fan[..])
                + size_of_val(&r.ring_start[..])
                + size_of_val(&r.ring[..])
        });
        size_of_val(&self.tris[..])
            + size_of_val(&self.edges[..])
            + size_of_val(&self.edge_tris[..])
            + size_of_val(&self.tri_edges[..])
            + rings
    }
    /// Number of edges at v.
    pub fn valence(&self, v: usize) -> usize {
        self.ring(v).len()
    }
    /// Whether v lies on the boundary.
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        let r = self.rings();
        let nfan = r.fan_start[v + 1] - r.fan_start[v];
        let nring = r.ring_start[v + 1] - r.ring_start[v];
        nring > nfan
    }
    /// Whether no triangle uses v.
    pub fn is_unreferenced(&self, v: usize) -> bool {
        self.fan(v).is_empty()
    }

    /// Closed loops of boundary edges, each as its vertices in the order the
    /// triangles traverse them.
    pub fn boundary_loops(&self) -> Vec<Vec<u32>> {
        // On a manifold mesh each boundary vertex has exactly one outgoing
        // boundary edge, so following it traces every loop once.
        let mut next = vec![NONE; self.nverts];
        for (e, et) in self.edge_tris.iter().enumerate() {
            if et[1] == NONE {
                let t = et[0] as usize;
                let i = self.tri_edges[t]
                    .iter()
                    .position(|&x| x as usize == e)
                    .unwrap_or(0);
                next[self.tris[t][i] as usize] = self.tris[t][(i + 1) % 3];
            }
        }
        let mut seen = vec![false; self.nverts];
        let mut loops = Vec::new();
        for start in 0..self.nverts {
            if next[start] == NONE || seen[start] {
                continue;
            }
            let mut lp = Vec::new();
            let mut v = start;
            while !seen[v] {
                seen[v] = true;
                lp.push(v as u32);
                v = next[v] as usize;
            }
            loops.push(lp);
        }
        loops
    }

    /// V − E + F over the referenced vertices.
    pub fn euler_characteristic(&self) -> i64 {
        let used = (0..self.nverts)
            .filter(|&v| !self.is_unreferenced(v))
            .count();
        used as i64 - self.edges.len() as i64 + self.tris.len() as i64
    }

    /// The counter-clockwise rings of a few vertices, found in one pass over
    /// the triangles without building every vertex's ring (for refined
    /// levels, where only darts need one).
    pub fn rings_of(&self, vertices: &[u32]) -> Vec<Vec<u32>> {
        if let Some(r) = self.rings.get() {
            return vertices
                .iter()
                .map(|&v| {
                    r.ring[r.ring_start[v as usize] as usize..r.ring_start[v as usize + 1] as usize]
                        .to_vec()
                })
                .collect();
        }
        let mut slot = std::collections::HashMap::with_capacity(vertices.len());
        for (k, &v) in vertices.iter().enumerate() {
            slot.insert(v, k);
        }
        let mut around: Vec<Vec<(u32, u32, u32)>> = vec![Vec::new(); vertices.len()];
        for (t, c) in self.tris.iter().enumerate() {
            for i in 0..3 {
                if let Some(&k) = slot.get(&c[i]) {
                    around[k].push((c[(i + 1) % 3], c[(i + 2) % 3], t as u32));
                }
            }
        }
        vertices
            .iter()
            .zip(&mut around)
            .map(|(&v, a)| {
                let (mut fan, mut ring) = (Vec::new(), Vec::new());
                walk_fan(v, a, &mut Vec::new(), &mut fan, &mut ring)
                    .expect("a refined manifold triangulation has manifold vertices");
                ring
            })
            .collect()
    }

    /// Orders the rings of this topology, [`Topology::refined`] from
    /// `coarse`, from the coarse fans: each vertex's triangles are known
    /// without gathering them from the whole triangle list. The walk is
    /// [`walk_fan`]'s, so the rings are those ordering on first use would
    /// give.
    pub(crate) fn order_rings_from(&self, coarse: &Topology) {
        if self.rings.get().is_some() {
            return;
        }
        let nv = coarse.nverts as u32;
        let mut fan_start = Vec::with_capacity(self.nverts + 1);
        let mut ring_start = Vec::with_capacity(self.nverts + 1);
        let mut fan = Vec::with_capacity(self.tris.len() * 3);
        let mut ring = Vec::with_capacity(self.tris.len() * 3 + self.nverts / 8);
        let (mut around, mut prevs) = (Vec::new(), Vec::new());
        fan_start.push(0);
        ring_start.push(0);
        let mut walk = |v: u32, around: &mut Vec<(u32, u32, u32)>| {
            let ordered = walk_fan(v, around, &mut prevs, &mut fan, &mut ring).is_ok();
            fan_start.push(fan.len() as u32);
            ring_start.push(ring.len() as u32);
            ordered
        };
        // An old vertex lies in the child at its corner of each of its
        // triangles, between the midpoints of its two edges there.
        for v in 0..nv {
            around.clear();
            for &t in coarse.fan(v as usize) {
                let i = corner_of(coarse.tris[t as usize], v) as usize;
                let m = |k: usize| nv + coarse.tri_edges[t as usize][k];
                around.push((m(i), m((i + 2) % 3), 4 * t + i as u32));
            }
            if !walk(v, &mut around) {
                return;
            }
        }
        // The midpoint of edge e, local edge i of triangle t, lies in the
        // children at both ends of e and in the centre child.
        for (e, tris) in coarse.edge_tris.iter().enumerate() {
            around.clear();
            for &t in tris.iter().filter(|&&t| t != NONE) {
                let (c, te) = (coarse.tris[t as usize], coarse.tri_edges[t as usize]);
                let i = te.iter().position(|&x| x as usize == e).unwrap_or(0);
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                let m = |k: usize| nv + te[k];
                around.push((m(k), c[i], 4 * t + i as u32));
                around.push((c[j], m(j), 4 * t + j as u32));
                around.push((m(j), m(k), 4 * t + 3));
            }
            if !walk(nv + e as u32, &mut around) {
                return;
            }
        }
        let _ = self.rings.set(Rings {
            fan_start,
            fan,
            ring_start,
            ring,
        });
    }

    fn rings(&self) -> &Rings {
        self.rings.get_or_init(|| {
            self.build_rings()
                .expect("a refined manifold triangulation has manifold vertices")
        })
    }

    /// Orders the triangles around every vertex into one fan; a vertex whose
    /// triangles form more than one fan is non-manifold.
    fn build_rings(&self) -> Result<Rings> {
        let nv = self.nverts;
        let mut fan_start = vec![0u32; nv + 1];
        for c in &self.tris {
            for &v in c {
                fan_start[v as usize + 1] += 1;
            }
        }
        for v in 0..nv {
            fan_start[v + 1] += fan_start[v];
        }
        // Incident (next, prev, tri) per vertex, in triangle order.
        let mut incident = vec![(0u32, 0u32, 0u32); self.tris.len() * 3];
        let mut fill = fan_start.clone();
        for (t, c) in self.tris.iter().enumerate() {
            for i in 0..3 {
                let v = c[i] as usize;
                incident[fill[v] as usize] = (c[(i + 1) % 3], c[(i + 2) % 3], t as u32);
                fill[v] += 1;
            }
        }
        let mut fan = Vec::with_capacity(incident.len());
        let mut ring_start = Vec::with_capacity(nv + 1);
        let mut ring = Vec::with_capacity(incident.len() + nv / 8);
        ring_start.push(0u32);
        let (mut around, mut prevs) = (Vec::new(), Vec::new());
        for v in 0..nv {
            around.clear();
            around.extend_from_slice(&incident[fan_start[v] as usize..fan_start[v + 1] as usize]);
            walk_fan(v as u32, &mut around, &mut prevs, &mut fan, &mut ring)?;
            ring_start.push(ring.len() as u32);
        }
        Ok(Rings {
            fan_start,
            fan,
            ring_start,
            ring,
        })
    }
}

/// Orders one vertex's incident (next, prev, triangle) triples into a
/// counter-clockwise fan, appending its triangles to `fan` and its
/// neighbours to `ring`. Fails when they form more than one fan.
/// [`walk_fan`] by linear search, for the usual small fans: the same
/// start (a boundary, or the smallest `next`) and the same walk, without
/// sorting. False, having written nothing, when the fan is not one walk
/// (the caller then finds out why).
fn walk_small_fan(around: &[(u32, u32, u32)], fan: &mut Vec<u32>, ring: &mut Vec<u32>) -> bool {
    let n = around.len();
    let is_prev = |x: u32| around.iter().any(|a| a.1 == x);
    let find = |x: u32| around.iter().position(|a| a.0 == x);
    let boundary = around.iter().position(|a| !is_prev(a.0));
    let start = boundary.unwrap_or_else(|| (0..n).min_by_key(|&k| around[k].0).unwrap_or(0));
    let (fan_len, ring_len) = (fan.len(), ring.len());
    let walked = walk_from(around, start, boundary.is_some(), find, fan, ring);
    if walked != n {
        fan.truncate(fan_len);
        ring.truncate(ring_len);
    }
    walked == n
}

/// Walks a fan from triangle `start`: each triangle's `prev` is the `next`
/// of the one after it (found by `find`). Pushes the triangles and ring
/// vertices met (and the far end of a boundary fan) and returns how many
/// triangles it walked.
fn walk_from(
    around: &[(u32, u32, u32)],
    start: usize,
    boundary: bool,
    find: impl Fn(u32) -> Option<usize>,
    fan: &mut Vec<u32>,
    ring: &mut Vec<u32>,
) -> usize {
    let (mut k, mut walked) = (start, 0);
    loop {
        fan.push(around[k].2);
        ring.push(around[k].0);
        walked += 1;
        match find(around[k].1) {
            Some(j) if j != start && walked < around.len() => k = j,
            _ => break,
        }
    }
    if boundary {
        ring.push(around[k].1);
    }
    walked
}

/// Orders the triangles `around` v, each as (next, prev, triangle)
/// counter-clockwise, into one fan, and pushes them and v's ring; fails
/// when they form more than one fan. `prevs` is scratch space.
fn walk_fan(
    v: u32,
    around: &mut [(u32, u32, u32)],
    prevs: &mut Vec<u32>,
    fan: &mut Vec<u32>,
    ring: &mut Vec<u32>,
) -> Result<()> {
    let n = around.len();
    if n == 0 {
        return Ok(());
    }
    if n <= 16 && walk_small_fan(around, fan, ring) {
        return Ok(());
    }
    walk_sorted_fan(v, around, prevs, fan, ring)
}

/// [`walk_fan`] for any fan: sorted, then walked by binary search.
fn walk_sorted_fan(
    v: u32,
    around: &mut [(u32, u32, u32)],
    prevs: &mut Vec<u32>,
    fan: &mut Vec<u32>,
    ring: &mut Vec<u32>,
) -> Result<()> {
    let n = around.len();
    // Sorted by `next`, the triangle following (next, prev) counter-clockwise
    // is the one whose `next` is our `prev`.
    around.sort_unstable();
    prevs.clear();
    prevs.extend(around.iter().map(|a| a.1));
    prevs.sort_unstable();
    let is_prev = |x: u32| prevs.binary_search(&x).is_ok();
    // A boundary fan starts where `next` is nobody's `prev`.
    let start = (0..n).find(|&k| !is_prev(around[k].0)).unwrap_or(0);
    let boundary = !is_prev(around[start].0);
    let find = |x: u32| around.binary_search_by_key(&x, |a| a.0).ok();
    let walked = walk_from(around, start, boundary, find, fan, ring);
    if walked != n {
        return Err(Error::NonManifoldVertex {
            vertex: v,
            ntris: n,
            fans: count_fans(around),
        });
    }
    Ok(())
}

/// Which corner of triangle c is vertex v (v must be one of them).
pub(crate) fn corner_of(c: [u32; 3], v: u32) -> u32 {
    if c[0] == v {
        0
    } else if c[1] == v {
        1
    } else {
        2
    }
}

fn sorted(a: u32, b: u32) -> [u32; 2] {
    if a < b {
        [a, b]
    } else {
        [b, a]
    }
}

/// Number of separate fans among a vertex's incident (next, prev, tri) triples.
fn count_fans(around: &[(u32, u32, u32)]) -> usize {
    // Triangles joined by a shared spoke (prev of one = next of other).
    let n = around.len();
    let mut fans = DisjointSets::new(n);
    for i in 0..n {
        for j in 0..n {
            if around[i].1 == around[j].0 {
                fans.unite(i, j);
            }
        }
    }
    (0..n).filter(|&i| fans.root(i) == i).count()
}

type EdgeArrays = (Vec<[u32; 2]>, Vec<[u32; 2]>, Vec<[u32; 3]>);

/// Finds the edges by sorting the triangles' half-edges on their endpoints,
/// and checks that each edge has one or two triangles traversing it in
/// opposite directions.
fn build_edges(tris: &[[u32; 3]]) -> Result<EdgeArrays> {
    let order = sorted_half_edges(tris);
    let (groups, group_of_slot) = group_half_edges(tris, &order)?;
    // Edges numbered in order of their first half-edge.
    let nslots = tris.len() * 3;
    let mut id_of_group = vec![NONE; groups.len()];
    let mut edges = Vec::with_capacity(groups.len());
    let mut edge_tris = Vec::with_capacity(groups.len());
    let mut tri_edges = vec![[0u32; 3]; tris.len()];
    for slot in 0..nslots {
        let g = group_of_slot[slot] as usize;
        if id_of_group[g] == NONE {
            id_of_group[g] = edges.len() as u32;
            let (start, len) = groups[g];
            let k = order[start].0;
            edges.push([(k >> 32) as u32, k as u32]);
            let t0 = order[start].1 / 3;
            let t1 = if len == 2 {
                order[start + 1].1 / 3
            } else {
                NONE
            };
            edge_tris.push([t0.min(t1), if len == 2 { t0.max(t1) } else { NONE }]);
        }
        tri_edges[slot / 3][slot % 3] = id_of_group[g];
    }
    Ok((edges, edge_tris, tri_edges))
}

/// The half-edge slots (3t + k runs from corner k of triangle t) keyed by
/// their sorted ends, smaller << 32 | larger, and sorted by key: a
/// counting sort on the smaller vertex, then each bucket (a vertex's few
/// edges) sorted on its own. The same order as a full sort, in linear
/// time; this is most of building a topology.
fn sorted_half_edges(tris: &[[u32; 3]]) -> Vec<(u64, u32)> {
    let nslots = tris.len() * 3;
    let key = |slot: usize| {
        let c = tris[slot / 3];
        let [a, b] = sorted(c[slot % 3], c[(slot + 1) % 3]);
        (a as u64) << 32 | b as u64
    };
    let nverts = tris.iter().flatten().max().map_or(0, |&v| v as usize + 1);
    let mut start = vec![0u32; nverts + 1];
    for s in 0..nslots {
        start[(key(s) >> 32) as usize + 1] += 1;
    }
    for v in 0..nverts {
        start[v + 1] += start[v];
    }
    let mut order: Vec<(u64, u32)> = vec![(0, 0); nslots];
    let mut next = start.clone();
    for s in 0..nslots {
        let k = key(s);
        let at = &mut next[(k >> 32) as usize];
        order[*at as usize] = (k, s as u32);
        *at += 1;
    }
    for v in 0..nverts {
        order[start[v] as usize..start[v + 1] as usize].sort_unstable();
    }
    order
}

/// Runs of half-edges with the same ends, as (start, length) in the
/// sorted order, and the run of each half-edge slot.
type Groups = (Vec<(usize, usize)>, Vec<u32>);

/// The runs of equal keys in `order`, as (start, length), and each slot's
/// run; a run of more than two half-edges is a non-manifold edge, and two
/// running the same way an inconsistent orientation.
fn group_half_edges(tris: &[[u32; 3]], order: &[(u64, u32)]) -> Result<Groups> {
    let mut group_of_slot = vec![0u32; tris.len() * 3];
    let mut groups: Vec<(usize, usize)> = Vec::new(); // (start, len) in `order`
    let mut i = 0;
    while i < order.len() {
        let mut j = i + 1;
        while j < order.len() && order[j].0 == order[i].0 {
            j += 1;
        }
        let run = &order[i..j];
        let tri_of = |s: u32| s / 3;
        let dir = |s: u32| {
            let c = tris[s as usize / 3];
            let k = s as usize % 3;
            (c[k], c[(k + 1) % 3])
        };
        if run.len() > 2 {
            let (a, b) = dir(run[0].1);
            let [a, b] = sorted(a, b);
            return Err(Error::NonManifoldEdge {
                a,
                b,
                tris: run.iter().map(|r| tri_of(r.1)).collect(),
            });
        }
        if run.len() == 2 && dir(run[0].1) == dir(run[1].1) {
            let (a, b) = dir(run[0].1);
            return Err(Error::InconsistentOrientation {
                a,
                b,
                tris: [tri_of(run[0].1), tri_of(run[1].1)],
            });
        }
        for r in run {
            group_of_slot[r.1 as usize] = groups.len() as u32;
        }
        groups.push((i, j - i));
        i = j;
    }
    Ok((groups, group_of_slot))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<[u32; 3]> {
        vec![[0, 1, 2], [0, 2, 3]]
    }

    /// A 4 × 4 grid of squares, each cut in two: 25 vertices, open.
    fn grid() -> Vec<[u32; 3]> {
        (0..4u32)
            .flat_map(|i| (0..4u32).map(move |j| (i, j)))
            .flat_map(|(i, j)| {
                let at = |a: u32, b: u32| 5 * a + b;
                [
                    [at(i, j), at(i + 1, j), at(i + 1, j + 1)],
                    [at(i, j), at(i + 1, j + 1), at(i, j + 1)],
                ]
            })
            .collect()
    }

    /// Two apices of valence n over an n-gon, numbered last.
    fn bipyramid(n: u32) -> Vec<[u32; 3]> {
        (0..n)
            .flat_map(|i| [[i, (i + 1) % n, n], [(i + 1) % n, i, n + 1]])
            .collect()
    }

    /// Both walks, on every vertex of `tris`, give the same fan and ring.
    fn assert_walks_agree(tris: &[[u32; 3]]) {
        let nv = 1 + tris.iter().flatten().max().copied().unwrap_or(0) as usize;
        let mut incident = vec![Vec::new(); nv];
        for (t, c) in tris.iter().enumerate() {
            for i in 0..3 {
                incident[c[i] as usize].push((c[(i + 1) % 3], c[(i + 2) % 3], t as u32));
            }
        }
        let mut small_walks = 0;
        for (v, around) in incident.iter_mut().enumerate() {
            let (mut fan, mut ring) = (Vec::new(), Vec::new());
            if !walk_small_fan(around, &mut fan, &mut ring) {
                continue;
            }
            small_walks += 1;
            let (mut sorted_fan, mut sorted_ring) = (Vec::new(), Vec::new());
            walk_sorted_fan(
                v as u32,
                around,
                &mut Vec::new(),
                &mut sorted_fan,
                &mut sorted_ring,
            )
            .unwrap();
            assert_eq!((fan, ring), (sorted_fan, sorted_ring), "vertex {v}");
        }
        assert!(small_walks > 0);
    }

    #[test]
    fn refined_rings_from_the_coarse_fans_are_the_walked_ones() {
        let tetra = Topology::new(4, vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]).unwrap();
        let coarse = [
            tetra.refined(),
            Topology::new(25, grid()).unwrap(),
            Topology::new(22, bipyramid(20)).unwrap(),
        ];
        for (case, coarse) in coarse.iter().enumerate() {
            coarse.rings();
            let fine = coarse.refined();
            fine.order_rings_from(coarse);
            let walked = Topology::new(fine.num_vertices(), fine.triangles().to_vec()).unwrap();
            let (a, b) = (fine.rings(), walked.rings());
            assert_eq!(
                (&a.fan_start, &a.fan, &a.ring_start, &a.ring),
                (&b.fan_start, &b.fan, &b.ring_start, &b.ring),
                "case {case}"
            );
        }
    }

    #[test]
    fn small_fans_walk_as_sorted_ones() {
        // Closed, refined (valences 3 and 6, shuffled numbering).
        let tetra = Topology::new(4, vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]).unwrap();
        assert_walks_agree(tetra.refined().refined().triangles());
        // Open: a 4 × 4 grid of squares, each cut in two.
        assert_walks_agree(&grid());
        // A bipyramid: two apices of valence 12, numbered last.
        assert_walks_agree(&bipyramid(12));
    }

    #[test]
    fn square_edges_rings_loops() {
        let t = Topology::new(4, square()).unwrap();
        assert_eq!(t.num_edges(), 5);
        assert_eq!(t.edges()[0], [0, 1]);
        assert_eq!(t.euler_characteristic(), 1);
        assert_eq!(t.boundary_loops(), vec![vec![0, 1, 2, 3]]);
        assert_eq!(t.ring(0), &[1, 2, 3]);
        assert_eq!(t.fan(0), &[0, 1]);
        assert!(t.is_boundary_vertex(0));
        assert_eq!(t.find_edge(2, 0), Some(2));
        assert_eq!(t.find_edge(1, 3), None);
    }

    #[test]
    fn tetrahedron_is_closed() {
        let t = Topology::new(4, vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]).unwrap();
        assert_eq!(t.euler_characteristic(), 2);
        assert!(t.boundary_loops().is_empty());
        for v in 0..4 {
            assert_eq!(t.valence(v), 3);
            assert!(!t.is_boundary_vertex(v));
        }
    }

    #[test]
    fn refined_square_is_consistent() {
        let t = Topology::new(4, square()).unwrap().refined();
        let again = Topology::new(t.num_vertices(), t.triangles().to_vec()).unwrap();
        assert_eq!(t.num_edges(), again.num_edges());
        assert_eq!(t.num_triangles(), 8);
        assert_eq!(again.euler_characteristic(), 1);
        for (e, &[a, b]) in t.edges().iter().enumerate() {
            assert_eq!(
                again.find_edge(a, b).map(|f| again.edges()[f]),
                Some([a, b])
            );
            for &tri in t.edge_triangles()[e].iter().filter(|&&x| x != NONE) {
                assert!(t.triangles()[tri as usize].contains(&a));
                assert!(t.triangles()[tri as usize].contains(&b));
            }
        }
    }
}
