//! The control net: vertex positions over a validated topology, with its
//! hard features. Everything a later stage relies on is checked here, once.

use crate::error::{Element, Error, Result};
use crate::features::{classify, Features, VertexKind};
use crate::geometry::{area, is_degenerate};
use crate::io::{self, MeshData};
use crate::repair::{self, ReadOptions, Repair, Repairs};
use crate::rules;
use crate::topology::Topology;
use glam::DVec3;
use std::path::Path;

/// A validated, manifold, consistently oriented triangulation with hard-edge
/// and corner tags: the control net of a Loop subdivision surface.
///
/// Vertices and triangles keep the order they were given in (0-based).
///
/// A clone shares the positions and the connectivity (neither changes
/// once built), so a surface built from a net holds no second copy of
/// them.
#[derive(Debug, Clone)]
pub struct ControlNet {
    points: std::sync::Arc<Vec<DVec3>>,
    topo: std::sync::Arc<Topology>,
    features: Features,
    welded: usize,
    repairs: Vec<Repair>,
}

impl ControlNet {
    /// Reads and validates a mesh file (.off .obj .ply .stl .tri).
    pub fn read(path: impl AsRef<Path>) -> Result<ControlNet> {
        Self::read_with(path, &ReadOptions::default())
    }

    /// [`ControlNet::read`] with options: splitting polygons, and the
    /// repairs of [`ReadOptions::repairs`], whose report
    /// [`ControlNet::repairs`] keeps. Validation errors name the file and,
    /// for text formats, the line.
    pub fn read_with(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<ControlNet> {
        let path = path.as_ref();
        let mut data = io::read_mesh(path, &opts.parse_options())?;
        Self::build(&mut data, &opts.repairs).map_err(|err| {
            let line = match err.element() {
                Some(Element::Triangle(t)) => data.tri_lines.get(t).copied(),
                Some(Element::Vertex(v)) => data.vertex_lines.get(v).copied(),
                None => None,
            };
            err.in_file(path, line)
        })
    }

    /// Builds a net from a reader's output.
    pub fn from_mesh_data(mut data: MeshData) -> Result<ControlNet> {
        Self::build(&mut data, &Repairs::default())
    }

    /// Builds a net from a reader's output after the given repairs.
    pub fn from_mesh_data_with(mut data: MeshData, repairs: &Repairs) -> Result<ControlNet> {
        Self::build(&mut data, repairs)
    }

    /// Repairs and validates `data`, taking its points; on error the line
    /// tables are left for the caller to locate the problem.
    fn build(data: &mut MeshData, repairs: &Repairs) -> Result<ControlNet> {
        let mut report = repair::apply(data, repairs)?;
        let points = std::mem::take(&mut data.points);
        let (mut net, degenerate) = Self::validate(points, &data.tris, repairs.allow_degenerate)?;
        if !degenerate.is_empty() {
            report.push(Repair::KeptDegenerate {
                triangles: degenerate,
            });
        }
        net.welded = data.welded;
        net.repairs = report;
        Ok(net)
    }

    /// Builds a net from coordinates and 0-based triangles.
    pub fn from_arrays(points: Vec<DVec3>, tris: &[[u32; 3]]) -> Result<ControlNet> {
        let wide: Vec<[i64; 3]> = tris.iter().map(|t| t.map(i64::from)).collect();
        Self::from_indices(points, &wide)
    }

    /// Validates everything loopsurf requires of a control net, in order:
    /// sizes, indices, coordinates, areas, then manifoldness and orientation.
    pub fn from_indices(points: Vec<DVec3>, tris: &[[i64; 3]]) -> Result<ControlNet> {
        Ok(Self::validate(points, tris, false)?.0)
    }

    /// [`ControlNet::from_indices`], optionally accepting zero-area
    /// triangles: then it also returns them.
    fn validate(
        points: Vec<DVec3>,
        tris: &[[i64; 3]],
        allow_degenerate: bool,
    ) -> Result<(ControlNet, Vec<usize>)> {
        let nverts = points.len();
        if nverts == 0 || tris.is_empty() {
            return Err(Error::EmptyMesh {
                nverts,
                ntris: tris.len(),
            });
        }
        if nverts >= u32::MAX as usize {
            return Err(Error::InvalidArgument(format!(
                "{nverts} vertices: at most {} are supported",
                u32::MAX - 1
            )));
        }
        let mut checked = Vec::with_capacity(tris.len());
        for (t, &verts) in tris.iter().enumerate() {
            if let Some(&index) = verts.iter().find(|&&i| i < 0 || i as usize >= nverts) {
                return Err(Error::IndexOutOfRange {
                    tri: t,
                    verts,
                    index,
                    nverts,
                });
            }
            let c = verts.map(|i| i as u32);
            if c[0] == c[1] || c[0] == c[2] || c[1] == c[2] {
                let index = if c[0] == c[1] || c[0] == c[2] {
                    c[0]
                } else {
                    c[1]
                };
                return Err(Error::RepeatedIndex {
                    tri: t,
                    verts: c,
                    index,
                });
            }
            checked.push(c);
        }
        if let Some((vertex, p)) = points.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(Error::NonFiniteCoordinate {
                vertex,
                coords: p.to_array(),
            });
        }
        let mut degenerate = Vec::new();
        for (t, c) in checked.iter().enumerate() {
            if is_degenerate(c.map(|i| points[i as usize])) {
                if !allow_degenerate {
                    return Err(Error::ZeroArea { tri: t, verts: *c });
                }
                degenerate.push(t);
            }
        }
        let topo = Topology::new(nverts, checked)?;
        let features = Features::new(&topo);
        let net = ControlNet {
            points: std::sync::Arc::new(points),
            topo: std::sync::Arc::new(topo),
            features,
            welded: 0,
            repairs: Vec::new(),
        };
        Ok((net, degenerate))
    }

    /// Assembles a net whose topology is known to be valid (refinement output).
    pub(crate) fn from_parts(points: Vec<DVec3>, topo: Topology, features: Features) -> ControlNet {
        ControlNet {
            points: std::sync::Arc::new(points),
            topo: std::sync::Arc::new(topo),
            features,
            welded: 0,
            repairs: Vec::new(),
        }
    }

    /// The connectivity, shared.
    pub(crate) fn shared_topology(&self) -> std::sync::Arc<Topology> {
        self.topo.clone()
    }

    /// The vertex positions, shared.
    pub(crate) fn shared_points(&self) -> std::sync::Arc<Vec<DVec3>> {
        self.points.clone()
    }

    /// The same net (topology and hard features) with other vertex
    /// positions, one per vertex, taken as they are.
    pub(crate) fn with_points(&self, points: Vec<DVec3>) -> ControlNet {
        debug_assert_eq!(points.len(), self.points.len());
        ControlNet {
            points: std::sync::Arc::new(points),
            topo: self.topo.clone(),
            features: self.features.clone(),
            welded: self.welded,
            repairs: self.repairs.clone(),
        }
    }

    /// Vertex positions.
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }
    /// Triangles as 0-based vertex triples.
    pub fn triangles(&self) -> &[[u32; 3]] {
        self.topo.triangles()
    }
    /// Connectivity.
    pub fn topology(&self) -> &Topology {
        &self.topo
    }
    /// Hard-edge and corner tags.
    pub fn features(&self) -> &Features {
        &self.features
    }
    /// STL only: how many vertices were merged because their coordinates were equal.
    pub fn welded_vertices(&self) -> usize {
        self.welded
    }
    /// What the repairs asked for when reading changed, in order (empty
    /// when none were asked for or none were needed).
    pub fn repairs(&self) -> &[Repair] {
        &self.repairs
    }

    /// Tags the edge (a, b) hard; true if it was not hard before.
    pub fn tag_edge(&mut self, a: u32, b: u32) -> Result<bool> {
        self.features.tag_edge(&self.topo, a, b)
    }
    /// Tags vertex v as a corner; true if it was not tagged before.
    pub fn tag_vertex(&mut self, v: u32) -> Result<bool> {
        self.features.tag_vertex(v)
    }
    /// Tags every interior edge whose dihedral angle exceeds `degrees`;
    /// returns how many edges became hard. Edges of zero-area triangles
    /// (kept by [`Repairs::allow_degenerate`]) have no dihedral angle and
    /// are never tagged.
    pub fn tag_by_angle(&mut self, degrees: f64) -> Result<usize> {
        self.features
            .tag_by_angle(&self.topo, &self.points, degrees)
    }
    /// Hard edges as (i, j) with i < j, in edge order (first appearance in
    /// the triangle list), boundary edges included.
    pub fn hard_edges(&self) -> Vec<[u32; 2]> {
        let edges = self.topo.edges();
        (0..edges.len())
            .filter(|&e| self.features.is_hard_edge(e))
            .map(|e| edges[e])
            .collect()
    }
    /// The kind of every vertex (smooth, dart, crease, corner).
    pub fn vertex_kinds(&self) -> Vec<VertexKind> {
        self.features.vertex_kinds(&self.topo)
    }

    /// Length of the bounding-box diagonal of the referenced vertices: the
    /// model size that tolerances are relative to.
    pub fn bbox_diagonal(&self) -> f64 {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for c in self.triangles() {
            for &i in c {
                lo = lo.min(self.points[i as usize]);
                hi = hi.max(self.points[i as usize]);
            }
        }
        (hi - lo).length()
    }

    /// The total area of the control triangles: the limit surface's area
    /// to within the shrinking of subdivision, enough to tell how many
    /// triangles a size asks for before meshing.
    pub fn area(&self) -> f64 {
        self.triangles()
            .iter()
            .map(|c| area(c.map(|i| self.points[i as usize])))
            .sum()
    }

    /// Where every control vertex lands on the limit surface (its limit mask).
    pub fn limit_points(&self) -> Vec<DVec3> {
        limit_positions(&self.topo, &self.features, &self.points)
    }

    /// Limit tangents at control vertex v from the tangent masks.
    pub fn limit_tangents(&self, v: usize) -> Result<Tangents> {
        if v >= self.points.len() {
            return Err(Error::InvalidArgument(format!(
                "vertex {v}: index out of range (the net has {} vertices)",
                self.points.len()
            )));
        }
        let p = |i: u32| self.points[i as usize];
        Ok(match self.features.vertex_kind(&self.topo, v) {
            VertexKind::Smooth => {
                let ring = self.topo.ring(v);
                let (c, s) = rules::smooth_tangent_weights(ring.len());
                let t1 = ring.iter().zip(&c).map(|(&n, w)| *w * p(n)).sum();
                let t2 = ring.iter().zip(&s).map(|(&n, w)| *w * p(n)).sum();
                Tangents::Surface(t1, t2)
            }
            VertexKind::Crease => {
                let hard = self.features.hard_neighbours(&self.topo, v);
                Tangents::Crease(rules::crease_tangent(p(hard[0]), p(hard[1])))
            }
            VertexKind::Dart => Tangents::Dart,
            VertexKind::Corner => Tangents::Corner,
        })
    }
}

/// Limit positions of every vertex of a net given by its parts: the limit
/// operator [`limit_mask_entries`] applied to `points`. Linear in `points`:
/// the evaluator also runs it on basis vectors to read off masks.
pub(crate) fn limit_positions(
    topo: &Topology,
    features: &Features,
    points: &[DVec3],
) -> Vec<DVec3> {
    let mut limits = vec![DVec3::ZERO; points.len()];
    for (v, u, w) in limit_mask_entries(topo, features) {
        limits[v as usize] += w * points[u as usize];
    }
    limits
}

/// The limit operator S∞ as sparse rows `(vertex, neighbour, weight)`, the
/// one place the limit masks of every vertex kind are assembled (from
/// [`rules`]): applied by [`limit_positions`], inverted by
/// [`crate::interpolate::solve`].
pub(crate) fn limit_mask_entries(topo: &Topology, features: &Features) -> Vec<(u32, u32, f64)> {
    let n = topo.num_vertices();
    let zeros = vec![DVec3::ZERO; n];
    let sums = NeighbourSums::new(topo, features, &zeros);
    let mut entries = Vec::with_capacity(7 * n);
    let mut dart_masks = std::collections::HashMap::new();
    for v in 0..n as u32 {
        let ring = topo.ring(v as usize);
        let hard = || features.hard_neighbours(topo, v as usize);
        match sums.kind(features, v as usize) {
            VertexKind::Smooth => {
                let (own, each) = rules::smooth_limit_weights(ring.len());
                entries.push((v, v, own));
                entries.extend(ring.iter().map(|&u| (v, u, each)));
            }
            VertexKind::Crease => {
                let (own, each) = rules::CREASE_LIMIT_WEIGHTS;
                entries.push((v, v, own));
                entries.extend(hard().into_iter().map(|u| (v, u, each)));
            }
            VertexKind::Corner => entries.push((v, v, 1.0)),
            VertexKind::Dart => {
                let k = ring.len();
                let (own, weights) = dart_masks
                    .entry(k)
                    .or_insert_with(|| rules::dart_limit_weights(k));
                let across = hard()[0];
                let at = ring.iter().position(|&u| u == across).unwrap_or(0);
                entries.push((v, v, *own));
                entries.extend((0..k).map(|j| (v, ring[j], weights[(j + k - at) % k])));
            }
        }
    }
    entries
}

/// Limit tangents at a control vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tangents {
    /// Smooth or dart vertex: two tangents (Persson, Aftosmis & Haines eq. 4); t₁ × t₂ is the
    /// outward normal direction.
    Surface(DVec3, DVec3),
    /// Crease vertex: the tangent of the crease curve, from one crease
    /// neighbour to the other in ring order.
    Crease(DVec3),
    /// A dart has a tangent plane, but no closed-form mask gives it: the ½ ½
    /// rule on its hard edge breaks the symmetry eq. 4 relies on. The
    /// evaluator computes it from the dart's local matrix
    /// ([`crate::Surface::normal`]).
    Dart,
    /// A corner has no tangent plane.
    Corner,
}

/// Per-vertex sums of neighbour positions and counts of edges, gathered in
/// one pass over the edges: everything a vertex or limit mask needs,
/// including the vertex's kind.
pub(crate) struct NeighbourSums {
    /// Σ of all neighbours.
    pub all: Vec<DVec3>,
    /// Σ of the neighbours across hard edges.
    pub hard: Vec<DVec3>,
    /// Number of neighbours.
    pub valence: Vec<u32>,
    /// Number of hard edges.
    pub hard_count: Vec<u32>,
}

impl NeighbourSums {
    pub fn new(topo: &Topology, features: &Features, points: &[DVec3]) -> NeighbourSums {
        let n = points.len();
        let mut s = NeighbourSums {
            all: vec![DVec3::ZERO; n],
            hard: vec![DVec3::ZERO; n],
            valence: vec![0; n],
            hard_count: vec![0; n],
        };
        for (e, &[a, b]) in topo.edges().iter().enumerate() {
            let (a, b) = (a as usize, b as usize);
            s.all[a] += points[b];
            s.all[b] += points[a];
            s.valence[a] += 1;
            s.valence[b] += 1;
            if features.is_hard_edge(e) {
                s.hard[a] += points[b];
                s.hard[b] += points[a];
                s.hard_count[a] += 1;
                s.hard_count[b] += 1;
            }
        }
        s
    }

    /// The kind of vertex v (the same as [`Features::vertex_kinds`]).
    pub fn kind(&self, features: &Features, v: usize) -> VertexKind {
        classify(
            features.is_tagged_vertex(v),
            self.valence[v],
            self.hard_count[v],
        )
    }
}

#[cfg(test)]
mod tests {
    use crate::examples;
    use crate::net::ControlNet;
    use crate::refine::refine_uniform;

    fn net(name: &str) -> ControlNet {
        let e = examples::by_name(name).unwrap();
        ControlNet::from_arrays(e.points, &e.tris).unwrap()
    }

    /// A limit mask is a left eigenvector of the subdivision matrix for
    /// eigenvalue 1: one step of subdivision (the rules, applied by
    /// `refine`, which keeps old vertex i at index i) does not move any
    /// vertex's limit point. Wrong weights for any vertex kind break this.
    #[test]
    fn limit_points_do_not_move_under_subdivision() {
        let mut darts = net("sphere");
        let [a, b, _] = darts.triangles()[0];
        darts.tag_edge(a, b).unwrap(); // one hard edge: both ends are darts
        let mut cube = net("cube");
        cube.tag_by_angle(30.0).unwrap();
        let mut viking = net("viking");
        viking.tag_by_angle(30.0).unwrap();
        viking.tag_vertex(3).unwrap();
        for (name, net) in [
            ("darts", darts),
            ("cube", cube),
            ("viking", viking),
            ("tetra", net("tetra")),
            ("open-disk", net("open-disk")),
        ] {
            let before = net.limit_points();
            let after = refine_uniform(&net, 1).unwrap().net().limit_points();
            for (v, (a, b)) in before.iter().zip(&after).enumerate() {
                assert!(
                    (*a - *b).length() <= 1e-14 * net.bbox_diagonal(),
                    "{name}: vertex {v}: {a} then {b}"
                );
            }
        }
    }
}
