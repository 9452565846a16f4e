//! Hard features: which edges are creases and which vertices are corners,
//! and the resulting kind of every vertex (docs/design.md, "Subdivision rules").
//!
//! Boundary edges are always hard. A vertex's kind follows from the number
//! of hard edges at it: none → smooth, one → dart (smooth rule), two →
//! crease, more → corner; a tagged vertex is a corner whatever its edges.

use crate::error::{Error, Result};
use crate::geometry;
use crate::topology::{Topology, NONE};
use glam::DVec3;

/// How a vertex is subdivided and where its limit lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VertexKind {
    /// No hard edge: Loop's smooth rule.
    Smooth,
    /// Exactly one hard edge: the crease fades out here; smooth rule.
    Dart,
    /// Exactly two hard edges: cubic B-spline rule along the crease.
    Crease,
    /// More than two hard edges, or tagged: fixed. Unreferenced vertices
    /// are also classified as corners, since nothing moves them (reports
    /// such as `loopsurf info` count them separately).
    Corner,
}

impl VertexKind {
    /// Lower-case name for reports.
    pub fn name(self) -> &'static str {
        match self {
            VertexKind::Smooth => "smooth",
            VertexKind::Dart => "dart",
            VertexKind::Crease => "crease",
            VertexKind::Corner => "corner",
        }
    }
}

/// Hard-edge and corner tags of one triangulation.
#[derive(Debug, Clone)]
pub struct Features {
    hard_edge: Vec<bool>,
    tagged_vertex: Vec<bool>,
}

impl Features {
    /// No tags yet; boundary edges are hard from the start.
    pub(crate) fn new(topo: &Topology) -> Features {
        Features {
            hard_edge: (0..topo.num_edges())
                .map(|e| topo.is_boundary_edge(e))
                .collect(),
            tagged_vertex: vec![false; topo.num_vertices()],
        }
    }

    /// Whether edge e is hard (tagged or on the boundary).
    pub fn is_hard_edge(&self, e: usize) -> bool {
        self.hard_edge[e]
    }
    /// Bytes held.
    pub fn memory_bytes(&self) -> usize {
        self.hard_edge.len() + self.tagged_vertex.len()
    }
    /// Whether vertex v was tagged hard (a corner).
    pub fn is_tagged_vertex(&self, v: usize) -> bool {
        self.tagged_vertex[v]
    }
    /// Number of hard edges, boundary edges included.
    pub fn num_hard_edges(&self) -> usize {
        self.hard_edge.iter().filter(|&&h| h).count()
    }

    /// Tags the edge joining a and b as hard. Returns whether it was not hard
    /// before. Fails when a and b are not joined by an edge.
    pub(crate) fn tag_edge(&mut self, topo: &Topology, a: u32, b: u32) -> Result<bool> {
        let n = topo.num_vertices();
        if a as usize >= n || b as usize >= n {
            return Err(Error::InvalidArgument(format!(
                "hard edge ({a}, {b}): vertex index out of range (the net has {n} vertices)"
            )));
        }
        let e = topo.find_edge(a, b).ok_or_else(|| {
            Error::InvalidArgument(format!("hard edge ({a}, {b}): no such edge in the net"))
        })?;
        Ok(!std::mem::replace(&mut self.hard_edge[e], true))
    }

    /// Tags vertex v as a corner. Returns whether it was not tagged before.
    pub(crate) fn tag_vertex(&mut self, v: u32) -> Result<bool> {
        let n = self.tagged_vertex.len();
        let slot = self.tagged_vertex.get_mut(v as usize).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "hard vertex {v}: index out of range (the net has {n} vertices)"
            ))
        })?;
        Ok(!std::mem::replace(slot, true))
    }

    /// Tags every interior edge whose two triangle normals make an angle of
    /// more than `degrees`, except edges of zero-area triangles, which have
    /// no normal. Returns how many edges became hard.
    pub(crate) fn tag_by_angle(
        &mut self,
        topo: &Topology,
        points: &[DVec3],
        degrees: f64,
    ) -> Result<usize> {
        if !(0.0..=180.0).contains(&degrees) {
            return Err(Error::InvalidArgument(format!(
                "hard angle {degrees}: must be between 0 and 180 degrees"
            )));
        }
        let threshold = degrees.to_radians();
        let mut tagged = 0;
        for e in 0..topo.num_edges() {
            if self.hard_edge[e] {
                continue;
            }
            if dihedral_angle(topo, points, e).is_some_and(|angle| angle > threshold) {
                self.hard_edge[e] = true;
                tagged += 1;
            }
        }
        Ok(tagged)
    }

    /// Number of hard edges at every vertex.
    pub fn hard_edge_counts(&self, topo: &Topology) -> Vec<u32> {
        let mut count = vec![0u32; topo.num_vertices()];
        for (e, &[a, b]) in topo.edges().iter().enumerate() {
            if self.hard_edge[e] {
                count[a as usize] += 1;
                count[b as usize] += 1;
            }
        }
        count
    }

    /// The kind of every vertex.
    pub fn vertex_kinds(&self, topo: &Topology) -> Vec<VertexKind> {
        // Counted from the edge list, so refined levels need no vertex rings.
        let mut degree = vec![0u32; topo.num_vertices()];
        for &[a, b] in topo.edges() {
            degree[a as usize] += 1;
            degree[b as usize] += 1;
        }
        self.hard_edge_counts(topo)
            .into_iter()
            .zip(degree)
            .enumerate()
            .map(|(v, (hard, degree))| classify(self.tagged_vertex[v], degree, hard))
            .collect()
    }

    /// Whether a and b are joined by a hard edge (false where no edge
    /// joins them).
    pub fn is_hard_between(&self, topo: &Topology, a: u32, b: u32) -> bool {
        topo.find_edge(a, b).is_some_and(|e| self.hard_edge[e])
    }

    /// The neighbours of v across hard edges, in ring order.
    pub fn hard_neighbours(&self, topo: &Topology, v: usize) -> Vec<u32> {
        topo.ring(v)
            .iter()
            .copied()
            .filter(|&n| self.is_hard_between(topo, v as u32, n))
            .collect()
    }

    /// The kind of one vertex (for per-vertex queries; [`Self::vertex_kinds`]
    /// does all vertices in one pass).
    pub fn vertex_kind(&self, topo: &Topology, v: usize) -> VertexKind {
        let degree = topo.ring(v).len() as u32;
        classify(
            self.tagged_vertex[v],
            degree,
            self.hard_neighbours(topo, v).len() as u32,
        )
    }

    /// The tags after one step of [`Topology::refined`]: both halves of a hard
    /// edge are hard, interior edges are not; old vertices keep their tags.
    pub fn refined(&self, coarse: &Topology) -> Features {
        let mut hard_edge =
            Vec::with_capacity(2 * self.hard_edge.len() + 3 * coarse.num_triangles());
        for &h in &self.hard_edge {
            hard_edge.push(h);
            hard_edge.push(h);
        }
        hard_edge.resize(hard_edge.len() + 3 * coarse.num_triangles(), false);
        let mut tagged_vertex = self.tagged_vertex.clone();
        tagged_vertex.resize(coarse.num_vertices() + coarse.num_edges(), false);
        Features {
            hard_edge,
            tagged_vertex,
        }
    }
}

/// The classification (docs/design.md) from a vertex's tag, number of edges and
/// number of hard edges.
pub(crate) fn classify(tagged: bool, degree: u32, hard: u32) -> VertexKind {
    if tagged || degree == 0 {
        return VertexKind::Corner;
    }
    match hard {
        0 => VertexKind::Smooth,
        1 => VertexKind::Dart,
        2 => VertexKind::Crease,
        _ => VertexKind::Corner,
    }
}

/// The dihedral angle (radians, [`geometry::dihedral_angle`]) of interior
/// edge e's two triangles. `None` on a boundary, or where a triangle has
/// zero area (no normal).
pub(crate) fn dihedral_angle(topo: &Topology, points: &[DVec3], e: usize) -> Option<f64> {
    let [t0, t1] = topo.edge_triangles()[e];
    if t0 == NONE || t1 == NONE {
        return None;
    }
    let corners = |t: u32| topo.triangles()[t as usize].map(|i| points[i as usize]);
    geometry::dihedral_angle(corners(t0), corners(t1))
}
