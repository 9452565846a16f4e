//! A part as a control net of its own: the triangles a process owns, the
//! halo their exact evaluation needs, and the maps back to the whole.
//!
//! **Why the sub-net evaluates its owned triangles bit for bit as the
//! whole does.** A Loop patch of control triangle t reads the once-refined
//! positions of t's corners and of the edges at them, and the special
//! configuration of a corner reads the refined vertices of its ring; all
//! of these come from the closed 1-rings of the needed vertices (the
//! corners of owned triangles and their neighbours), whose whole fans the
//! halo carries. What else decides a bit is the ORDER of sums and walks:
//! a vertex's neighbour sums run over its edges in edge order (first
//! appearance in the triangle list), and a fan walk starts at the smallest
//! neighbour index. The sub-net keeps the whole's triangle order and
//! vertex order (local ids ascend with global ids), so every edge at a
//! needed vertex first appears in the same triangle as in the whole, and
//! every comparison between indices comes out the same.
//!
//! **The rim.** A vertex of the halo that is not needed has only part of
//! its fan here, and in the sub-net it reads as a boundary vertex; no rule
//! of an owned triangle reads it, and the part keeps its kind and boundary
//! status in the whole ([`Part::vertex_kind`], [`Part::is_boundary_vertex`]).
//! Where its triangles here form several separate fans (the halo touches
//! it from two sides), it becomes one local vertex per fan, all with the
//! same global id, so that the sub-net stays manifold.

use crate::error::{Error, Result};
use crate::features::{Features, VertexKind};
use crate::net::ControlNet;
use crate::topology::Topology;
use std::collections::HashMap;

/// A part of a control net: its owned triangles and their halo as a net of
/// its own, with global ids.
#[derive(Debug, Clone)]
pub struct Part {
    pub(crate) net: ControlNet,
    /// Global id of each local triangle, ascending.
    pub(crate) triangles: Vec<u32>,
    /// Global id of each local vertex, non-decreasing (a rim vertex split
    /// into several fans repeats its id).
    pub(crate) vertices: Vec<u32>,
    /// Whether each local triangle is owned (the others are the halo).
    pub(crate) owned: Vec<bool>,
    /// Each local vertex's kind in the whole.
    pub(crate) kinds: Vec<VertexKind>,
    /// Whether each local vertex is on the whole's boundary.
    pub(crate) boundary: Vec<bool>,
    /// The whole's vertex and triangle counts.
    pub(crate) whole: [usize; 2],
}

impl Part {
    /// The part owning the triangles `owned` (global ids, in any order) of
    /// `net`, with their halo. Fails on an empty set, an id out of range
    /// or an id given twice.
    pub fn new(net: &ControlNet, owned: &[u32]) -> Result<Part> {
        let is_owned = owned_flags(net.triangles().len(), owned)?;
        let topo = net.topology();
        let needed = needed_vertices(topo, owned);
        let triangles = sub_triangles(topo, &needed);
        let (vertices, corners) = split_rim(topo, &needed, &triangles);
        let local = Topology::new(vertices.len(), corners)?;
        let features = carried_features(net, &local, &vertices)?;
        let points = vertices.iter().map(|&g| net.points()[g as usize]).collect();
        let whole_kind = |&g: &u32| net.features().vertex_kind(topo, g as usize);
        Ok(Part {
            owned: triangles.iter().map(|&t| is_owned[t as usize]).collect(),
            kinds: vertices.iter().map(whole_kind).collect(),
            boundary: vertices
                .iter()
                .map(|&g| topo.is_boundary_vertex(g as usize))
                .collect(),
            net: ControlNet::from_parts(points, local, features),
            triangles,
            vertices,
            whole: [net.points().len(), net.triangles().len()],
        })
    }

    /// The part, its maps checked against its net (a part read from a
    /// stream).
    pub(crate) fn checked(self) -> Result<Part> {
        let bad = |what: &str| Err(Error::InvalidArgument(what.to_string()));
        let (triangles, vertices, whole) = (&self.triangles, &self.vertices, self.whole);
        let nv = self.net.points().len();
        if triangles.len() != self.net.triangles().len() || self.owned.len() != triangles.len() {
            return bad("the triangle maps do not match the net's triangles");
        }
        if [vertices.len(), self.kinds.len(), self.boundary.len()] != [nv; 3] {
            return bad("the vertex maps do not match the net's vertices");
        }
        if !triangles.windows(2).all(|w| w[0] < w[1])
            || triangles.last().is_some_and(|&t| t as usize >= whole[1])
        {
            return bad("global triangle ids must ascend and lie in the whole");
        }
        if !vertices.windows(2).all(|w| w[0] <= w[1])
            || vertices.last().is_some_and(|&v| v as usize >= whole[0])
        {
            return bad("global vertex ids must not descend and must lie in the whole");
        }
        if !self.owned.contains(&true) {
            return bad("no owned triangle");
        }
        Ok(self)
    }

    /// The sub-net: owned and halo triangles in global order.
    pub fn net(&self) -> &ControlNet {
        &self.net
    }
    /// Global id of each local triangle, ascending.
    pub fn global_triangles(&self) -> &[u32] {
        &self.triangles
    }
    /// Global id of each local vertex, non-decreasing.
    pub fn global_vertices(&self) -> &[u32] {
        &self.vertices
    }
    /// The local id of global triangle `t`, if the part holds it (owned
    /// or halo).
    pub fn local_triangle(&self, t: u32) -> Option<usize> {
        self.triangles.binary_search(&t).ok()
    }
    /// The local ids of global vertex `v`: none, one, or one per fan of a
    /// rim vertex split here.
    pub fn local_vertices(&self, v: u32) -> std::ops::Range<usize> {
        let start = self.vertices.partition_point(|&g| g < v);
        start..self.vertices.partition_point(|&g| g <= v)
    }
    /// Whether local triangle `t` is owned (not halo).
    pub fn is_owned(&self, t: usize) -> bool {
        self.owned[t]
    }
    /// Local ids of the owned triangles, ascending.
    pub fn owned(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.owned.len()).filter(|&t| self.owned[t])
    }
    /// Number of owned triangles.
    pub fn num_owned(&self) -> usize {
        self.owned.iter().filter(|&&o| o).count()
    }
    /// Number of halo triangles.
    pub fn num_halo(&self) -> usize {
        self.owned.len() - self.num_owned()
    }
    /// The kind local vertex `v` has in the whole (on the rim, not the
    /// sub-net's boundary kind).
    pub fn vertex_kind(&self, v: usize) -> VertexKind {
        self.kinds[v]
    }
    /// Each local vertex's kind in the whole.
    pub fn vertex_kinds(&self) -> &[VertexKind] {
        &self.kinds
    }
    /// Whether local vertex `v` is on the whole's boundary.
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        self.boundary[v]
    }
    /// The whole's vertex and triangle counts.
    pub fn whole_size(&self) -> [usize; 2] {
        self.whole
    }

    /// Bytes held: the sub-net and the maps.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of_val;
        let net = &self.net;
        size_of_val(net.points())
            + net.topology().memory_bytes()
            + net.features().memory_bytes()
            + size_of_val(&self.triangles[..])
            + size_of_val(&self.vertices[..])
            + size_of_val(&self.owned[..])
            + size_of_val(&self.kinds[..])
            + size_of_val(&self.boundary[..])
    }
}

/// Which of `n` triangles are owned; fails on an empty set, an id out of
/// range or one given twice.
fn owned_flags(n: usize, owned: &[u32]) -> Result<Vec<bool>> {
    if owned.is_empty() {
        return Err(Error::InvalidArgument(
            "a part needs at least one triangle".into(),
        ));
    }
    let mut flags = vec![false; n];
    for &t in owned {
        let slot = flags.get_mut(t as usize).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "part triangle {t}: out of range (the net has {n} triangles)"
            ))
        })?;
        if std::mem::replace(slot, true) {
            return Err(Error::InvalidArgument(format!(
                "part triangle {t}: given twice"
            )));
        }
    }
    Ok(flags)
}

/// The needed vertices: the corners of the owned triangles and their
/// neighbours.
fn needed_vertices(topo: &Topology, owned: &[u32]) -> Vec<bool> {
    let mut needed = vec![false; topo.num_vertices()];
    for &t in owned {
        for &c in &topo.triangles()[t as usize] {
            needed[c as usize] = true;
            for &n in topo.ring(c as usize) {
                needed[n as usize] = true;
            }
        }
    }
    needed
}

/// Every triangle with a needed corner (the owned ones among them),
/// ascending.
fn sub_triangles(topo: &Topology, needed: &[bool]) -> Vec<u32> {
    let mut tris: Vec<u32> = (0..topo.num_vertices())
        .filter(|&v| needed[v])
        .flat_map(|v| topo.fan(v).iter().copied())
        .collect();
    tris.sort_unstable();
    tris.dedup();
    tris
}

/// The local vertices (their global ids, ascending, a rim vertex once per
/// fan it has among `tris`) and the local corners of `tris`.
fn split_rim(topo: &Topology, needed: &[bool], tris: &[u32]) -> (Vec<u32>, Vec<[u32; 3]>) {
    let mut used: Vec<u32> = tris
        .iter()
        .flat_map(|&t| topo.triangles()[t as usize])
        .collect();
    used.sort_unstable();
    used.dedup();
    let present = |t: u32| tris.binary_search(&t).is_ok();
    // Per used vertex its first local id; per (triangle, rim vertex) of a
    // split vertex, which of its fans the triangle is in.
    let mut first: HashMap<u32, u32> = HashMap::with_capacity(used.len());
    let mut piece: HashMap<(u32, u32), u32> = HashMap::new();
    let mut vertices = Vec::with_capacity(used.len());
    for &v in &used {
        first.insert(v, vertices.len() as u32);
        let pieces = if needed[v as usize] {
            1
        } else {
            fan_pieces(topo, v, present, &mut piece)
        };
        vertices.extend(std::iter::repeat(v).take(pieces as usize));
    }
    let corners = tris
        .iter()
        .map(|&t| {
            topo.triangles()[t as usize]
                .map(|c| first[&c] + piece.get(&(t, c)).copied().unwrap_or(0))
        })
        .collect();
    (vertices, corners)
}

/// The separate fans of rim vertex v among the present triangles: counts
/// them and, when there are several, records each triangle's fan in
/// `piece`. An interior vertex's fan is a cycle, so a run may wrap around.
fn fan_pieces(
    topo: &Topology,
    v: u32,
    present: impl Fn(u32) -> bool,
    piece: &mut HashMap<(u32, u32), u32>,
) -> u32 {
    let fan = topo.fan(v as usize);
    let n = fan.len();
    let Some(gap) = (0..n).find(|&i| !present(fan[i])) else {
        return 1;
    };
    // Walk from just after a gap (a boundary fan from its start, where the
    // boundary is the gap), so that a run is never cut in two.
    let start = if topo.is_boundary_vertex(v as usize) {
        0
    } else {
        gap + 1
    };
    let (mut runs, mut inside, mut members) = (0u32, false, Vec::new());
    for i in 0..n {
        let t = fan[(start + i) % n];
        match (present(t), inside) {
            (true, false) => {
                runs += 1;
                inside = true;
                members.push((t, runs - 1));
            }
            (true, true) => members.push((t, runs - 1)),
            (false, _) => inside = false,
        }
    }
    if runs > 1 {
        piece.extend(members.into_iter().map(|(t, r)| ((t, v), r)));
    }
    runs
}

/// The whole's hard edges and corner tags on the sub-net (whose own
/// boundary edges, the rim's, are hard as every boundary edge is).
fn carried_features(net: &ControlNet, local: &Topology, vertices: &[u32]) -> Result<Features> {
    let (whole, tags) = (net.topology(), net.features());
    let mut features = Features::new(local);
    for &[a, b] in local.edges() {
        let global = whole.find_edge(vertices[a as usize], vertices[b as usize]);
        if global.is_some_and(|e| tags.is_hard_edge(e)) {
            features.tag_edge(local, a, b)?;
        }
    }
    for (v, &g) in vertices.iter().enumerate() {
        if tags.is_tagged_vertex(g as usize) {
            features.tag_vertex(v as u32)?;
        }
    }
    Ok(features)
}
