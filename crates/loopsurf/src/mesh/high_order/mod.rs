//! Curved (Lagrange P2–P4) surface meshes whose every node lies exactly on
//! the limit surface, for DG and high-order FE codes that need curved
//! boundary elements (Persson, Aftosmis & Haines §1).
//!
//! An element's map is the Lagrange interpolant of exact surface points at
//! its nodes ([`lagrange`] has the node layout, gmsh's). The nodes are
//! placed in one of three ways, in this order of preference:
//!
//! 1. **On a crease or boundary curve**, an edge's nodes are on the exact
//!    curve: in a chart mesh at equispaced curve parameters t (the curve
//!    shares its parameterisation with the surface along each control
//!    edge, so this is what 2 gives there); otherwise the point of the
//!    curve nearest to the straight-sided node, as in 3.
//! 2. **In the element's chart**, for the chart mesher's elements (each
//!    inside one control triangle): equispaced in the chart's (v, w). The
//!    surface is one polynomial piece per control triangle away from
//!    special vertices, so such an element interpolates a polynomial and
//!    converges at the full order k + 1 (a regular patch is quartic: P4
//!    elements reproduce it to round-off).
//! 3. **Otherwise** (the remesher's elements, and meshes made elsewhere,
//!    span several control triangles) the node is the closest point of the
//!    surface to the corresponding node of the straight-sided triangle:
//!    the nearest of the local projections from the element's vertices,
//!    and the certified snap where that ends farther than a quarter of the
//!    shortest edge. The
//!    element map then interpolates the closest-point map, which is smooth
//!    wherever the surface is, so the orders hold there too. Interior
//!    nodes (P3, P4) start from the element its curved edges make
//!    ([`lagrange::interior_from_boundary`]) rather than from the flat
//!    triangle, so that they follow edges that bend strongly. The
//!    parameters are not used here even where the ends share a control
//!    triangle: next to an irregular vertex the parameterisation is so
//!    uneven that a parameter midpoint can lie an edge length off the
//!    chord. The projection never leaves the element's face
//!    ([`project_in_face`]): across a crease the other face may
//!    be nearer, and a node there would fold the element.
//!
//! Every edge's nodes are computed once and shared by the two triangles of
//! the edge, so the curved mesh is conforming bit for bit.

pub mod lagrange;
mod linear_input;
mod validity;

pub use lagrange::{nodes_per_triangle, MAX_ORDER};
pub use linear_input::{onto_surface, OntoSurface, DEFAULT_MAX_MOVE};
pub use validity::{Distance, Validity};

use super::SurfaceMesh;
use crate::curve::LimitCurve;
use crate::error::{Error, Result};
use crate::parameters::{reparameterize, SurfacePoint};
use crate::snap::{project_in_face, snap_near};
use crate::surface::{Surface, PARAMETER_TOLERANCE};
use glam::DVec3;
use rayon::prelude::*;

/// A curved surface mesh of Lagrange triangles.
#[derive(Debug, Clone)]
pub struct CurvedMesh {
    /// The polynomial order k (1 to [`MAX_ORDER`]).
    pub order: usize,
    /// Node positions, each exactly the surface at its parameters: first the
    /// linear mesh's vertices in their order, then the edge nodes, then the
    /// interior nodes.
    pub nodes: Vec<DVec3>,
    /// Per node: a control triangle and (v, w) where `eval` gives it
    /// (empty for a mesh read as it is: [`CurvedMesh::from_lagrange`]).
    pub params: Vec<SurfacePoint>,
    /// [`nodes_per_triangle`]`(order)` node indices per triangle, in gmsh's
    /// order ([`lagrange`]), triangles in the linear mesh's order.
    pub triangles: Vec<u32>,
    /// Per triangle: its model face.
    pub faces: Vec<u32>,
    /// The hard edges as Lagrange curves of `order + 1` nodes each: their
    /// two ends in the curve's direction, then the inner nodes from the
    /// first end to the second (gmsh's and VTK's line order).
    pub lines: Vec<u32>,
    /// Per line: its model curve.
    pub line_curves: Vec<u32>,
    /// Nodes at model corners, with the corner id.
    pub corners: Vec<(u32, u32)>,
    /// How many of the nodes are the linear mesh's vertices.
    pub vertices: usize,
    /// The net's bounding-box diagonal, for relative figures.
    pub diagonal: f64,
}

impl CurvedMesh {
    /// Nodes per triangle.
    pub fn nodes_per_triangle(&self) -> usize {
        nodes_per_triangle(self.order)
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.faces.len()
    }

    /// Whether there is no triangle.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }

    /// The node indices of triangle `t`, in gmsh's order.
    pub fn element(&self, t: usize) -> &[u32] {
        let n = self.nodes_per_triangle();
        &self.triangles[n * t..n * (t + 1)]
    }

    /// A mesh read from a file, as it is: its nodes need not lie on any
    /// surface, and carry no parameters (so only [`CurvedMesh::validity`],
    /// [`CurvedMesh::distance_to`] and [`CurvedMesh::area`] apply).
    pub fn from_lagrange(mesh: &crate::io::LagrangeMesh, diagonal: f64) -> CurvedMesh {
        CurvedMesh {
            order: mesh.order,
            nodes: mesh.nodes.clone(),
            params: Vec::new(),
            triangles: mesh.triangles.clone(),
            faces: mesh.faces.clone(),
            lines: mesh.lines.clone(),
            line_curves: mesh.line_curves.clone(),
            corners: mesh.corners.clone(),
            vertices: 0,
            diagonal,
        }
    }

    /// The mesh as the file writers take it.
    pub fn to_lagrange(&self) -> crate::io::LagrangeMesh {
        crate::io::LagrangeMesh {
            order: self.order,
            nodes: self.nodes.clone(),
            triangles: self.triangles.clone(),
            faces: self.faces.clone(),
            lines: self.lines.clone(),
            line_curves: self.line_curves.clone(),
            corners: self.corners.clone(),
            params: self.params.iter().map(|p| (p.tri, p.v, p.w)).collect(),
        }
    }
}

/// A node found: its position and parameters.
type Node = (DVec3, SurfacePoint);

impl SurfaceMesh {
    /// This mesh with every triangle raised to a Lagrange triangle of order
    /// `order` (1 to [`MAX_ORDER`]) on the exact surface; see the module
    /// doc for where the nodes go. The vertices stay the first nodes, in
    /// order, bit for bit.
    pub fn raise_order(&self, surface: &Surface, order: usize) -> Result<CurvedMesh> {
        self.check_raisable(order)?;
        let curve_edges = self.curve_edges(surface)?;
        let k = order;
        let placer = Placer {
            surface,
            mesh: self,
        };
        let edges = Edges::new(&self.triangles, k);
        let hard = hard_edges(surface, &edges, &curve_edges);
        let edge_nodes = edge_nodes(&placer, &edges, &hard, k)?;
        let lattice = lagrange::lattice(k);
        let interior = &lattice[(3 * k).min(lattice.len())..];
        let interior_nodes = self.interior_nodes(&placer, &edges, &edge_nodes, interior, k)?;

        let nv = self.points.len();
        let edge_base = nv;
        let interior_base = nv + edge_nodes.len();
        let per = nodes_per_triangle(k);
        let mut triangles = Vec::with_capacity(per * self.triangles.len());
        for (t, tri) in self.triangles.iter().enumerate() {
            triangles.extend(tri);
            for s in 0..3 {
                let along = edges.along(tri[s], tri[(s + 1) % 3]);
                triangles.extend(along.map(|i| (edge_base + i) as u32));
            }
            let first = interior_base + t * interior.len();
            triangles.extend((first..first + interior.len()).map(|i| i as u32));
        }
        let mut lines = Vec::with_capacity((k + 1) * curve_edges.pairs.len());
        for &[a, b] in &curve_edges.pairs {
            lines.extend([a, b]);
            lines.extend(edges.along(a, b).map(|i| (edge_base + i) as u32));
        }

        let mut nodes = self.points.clone();
        let mut params = self.params.clone();
        for (x, p) in edge_nodes.into_iter().chain(interior_nodes) {
            nodes.push(x);
            params.push(p);
        }
        Ok(CurvedMesh {
            order: k,
            nodes,
            params,
            triangles,
            faces: self.faces.clone(),
            lines,
            line_curves: curve_edges.curves,
            corners: corners(surface, &self.params),
            vertices: nv,
            diagonal: self.diagonal,
        })
    }

    /// Refuses an order out of range and, as the fields are public (a mesh
    /// put together by hand is checked before it is indexed), counts that
    /// do not match; parameters and indices are checked by
    /// [`SurfaceMesh::curve_edges`].
    fn check_raisable(&self, order: usize) -> Result<()> {
        if !(1..=MAX_ORDER).contains(&order) {
            return Err(Error::InvalidArgument(format!(
                "order {order}: must be 1 to {MAX_ORDER}"
            )));
        }
        let counts = [
            ("params", self.params.len(), self.points.len(), "points"),
            ("faces", self.faces.len(), self.triangles.len(), "triangles"),
        ];
        for (what, n, want, of) in counts {
            if n != want {
                return Err(Error::InvalidArgument(format!(
                    "{n} {what} for {want} {of}"
                )));
            }
        }
        if !self.charts.is_empty() && self.charts.len() != self.triangles.len() {
            return Err(Error::InvalidArgument(format!(
                "{} charts for {} triangles (give one per triangle, or none)",
                self.charts.len(),
                self.triangles.len()
            )));
        }
        Ok(())
    }

    /// The interior nodes of every element, triangle by triangle, each
    /// placed from its lattice point and its element's boundary nodes.
    fn interior_nodes(
        &self,
        placer: &Placer,
        edges: &Edges,
        edge_nodes: &[Node],
        interior: &[[usize; 2]],
        k: usize,
    ) -> Result<Vec<Node>> {
        Ok((0..self.triangles.len())
            .into_par_iter()
            .map(|t| {
                let tri = self.triangles[t];
                // The element's edge nodes so far, in its own order.
                let mut boundary: Vec<DVec3> =
                    tri.iter().map(|&v| self.points[v as usize]).collect();
                for s in 0..3 {
                    let along = edges.along(tri[s], tri[(s + 1) % 3]);
                    boundary.extend(along.map(|i| edge_nodes[i].0));
                }
                interior
                    .iter()
                    .map(|&[i, j]| {
                        let (x, y) = (i as f64 / k as f64, j as f64 / k as f64);
                        let target = lagrange::interior_from_boundary(k, &boundary, [i, j]);
                        placer.between(&tri, &[1.0 - x - y, x, y], t, target)
                    })
                    .collect::<Result<Vec<Node>>>()
            })
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .flatten()
            .collect())
    }
}

/// The mesh's unique edges, each from its lower vertex to its higher, with
/// a triangle of each, and where their inner nodes lie among the edge
/// nodes.
struct Edges {
    /// (lower << 32 | higher, a triangle on it), sorted.
    sides: Vec<(u64, u32)>,
    /// Inner nodes per edge: the order less one.
    inner: usize,
}

impl Edges {
    fn new(triangles: &[[u32; 3]], order: usize) -> Edges {
        let mut sides: Vec<(u64, u32)> = Vec::with_capacity(3 * triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            for s in 0..3 {
                let (a, b) = (tri[s] as u64, tri[(s + 1) % 3] as u64);
                sides.push(((a.min(b) << 32) | a.max(b), t as u32));
            }
        }
        sides.sort_unstable();
        sides.dedup_by_key(|s| s.0);
        Edges {
            sides,
            inner: order.saturating_sub(1),
        }
    }

    /// The index of edge a–b.
    fn index(&self, a: u32, b: u32) -> usize {
        let key = ((a.min(b) as u64) << 32) | a.max(b) as u64;
        self.sides
            .binary_search_by_key(&key, |s| s.0)
            .expect("every side was listed")
    }

    /// The indices, among the edge nodes, of edge (a, b)'s inner nodes
    /// from a to b (they are stored from the lower vertex to the higher).
    fn along(&self, a: u32, b: u32) -> impl Iterator<Item = usize> {
        let inner = self.inner;
        let first = self.index(a, b) * inner;
        (0..inner).map(move |i| {
            if a < b {
                first + i
            } else {
                first + inner - 1 - i
            }
        })
    }
}

/// Per edge, if hard: its curve and the t of its lower and higher vertex.
fn hard_edges(
    surface: &Surface,
    edges: &Edges,
    curve_edges: &super::CurveEdges,
) -> Vec<Option<(u32, [f64; 2])>> {
    let mut hard: Vec<Option<(u32, [f64; 2])>> = vec![None; edges.sides.len()];
    for ((&[a, b], &c), &[ta, tb]) in curve_edges
        .pairs
        .iter()
        .zip(&curve_edges.curves)
        .zip(&curve_edges.params)
    {
        let n = surface.model().curves()[c as usize].len() as f64;
        // A closed curve's edge across its start runs from t near n
        // to t near 0: continue past n instead.
        let tb = if tb < ta { tb + n } else { tb };
        let ts = if a < b { [ta, tb] } else { [tb, ta] };
        hard[edges.index(a, b)] = Some((c, ts));
    }
    hard
}

/// The inner nodes of every edge, edge by edge from its lower vertex: on
/// its curve if hard, else placed between its ends.
fn edge_nodes(
    placer: &Placer,
    edges: &Edges,
    hard: &[Option<(u32, [f64; 2])>],
    k: usize,
) -> Result<Vec<Node>> {
    Ok(edges
        .sides
        .par_iter()
        .zip(hard.par_iter())
        .map(|(&(key, t), hard)| {
            let (a, b) = ((key >> 32) as u32, key as u32);
            (1..k)
                .map(|i| {
                    let s = i as f64 / k as f64;
                    match hard {
                        Some((c, ts)) => placer.on_curve(*c, *ts, s, [a, b]),
                        None => placer.between(&[a, b], &[1.0 - s, s], t as usize, None),
                    }
                })
                .collect::<Result<Vec<Node>>>()
        })
        .collect::<Result<Vec<_>>>()?
        .into_iter()
        .flatten()
        .collect())
}

/// The vertices at model corners, with their corner ids.
fn corners(surface: &Surface, params: &[SurfacePoint]) -> Vec<(u32, u32)> {
    let net = surface.net();
    let corners = surface.model().corners();
    params
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            let weights = p.weights();
            let live: Vec<usize> = (0..3)
                .filter(|&k| weights[k].abs() > PARAMETER_TOLERANCE)
                .collect();
            let &[k] = live.as_slice() else {
                return None;
            };
            let vertex = net.triangles()[p.tri as usize][k];
            let id = corners.binary_search(&vertex).ok()?;
            Some((i as u32, id as u32))
        })
        .collect()
}

/// Places nodes of one linear mesh on the surface.
struct Placer<'a> {
    surface: &'a Surface,
    mesh: &'a SurfaceMesh,
}

impl Placer<'_> {
    /// The node at fraction `s` of the curve edge from vertex `ends[0]`
    /// (curve parameter `ts[0]`) to `ends[1]` (`ts[1]`): in a chart mesh
    /// the curve at the interpolated t (which is the chart's parameter
    /// along its control edge); otherwise the point of the curve nearest
    /// to the straight-sided node, between the ends. Equispaced t would not
    /// do there: next to a dart's tip the curve's speed falls to zero, and
    /// a node at the middle t sits next to the tip and folds the element.
    fn on_curve(&self, curve: u32, ts: [f64; 2], s: f64, ends: [u32; 2]) -> Result<Node> {
        let limit = LimitCurve::new(self.surface, curve as usize)?;
        let c = limit.curve();
        let n = c.len() as f64;
        let wrap = |t: f64| if c.is_closed() { t.rem_euclid(n) } else { t };
        let guess = ts[0] + s * (ts[1] - ts[0]);
        let mut t = guess;
        if self.mesh.charts.is_empty() {
            let [xa, xb] = ends.map(|i| self.mesh.points[i as usize]);
            let snap = limit.project(xa + s * (xb - xa), wrap(guess))?;
            // Back on the unwrapped side of the guess, and between the ends.
            let mut projected = snap.t;
            if c.is_closed() {
                projected += n * ((guess - projected) / n).round();
            }
            let (lo, hi) = (ts[0].min(ts[1]), ts[0].max(ts[1]));
            if lo < projected && projected < hi {
                t = projected;
            }
        }
        let sides = limit.surface_points(wrap(t))?;
        let p = sides[0].1;
        Ok((self.surface.point(p.tri as usize, p.v, p.w)?, p))
    }

    /// The point with barycentric `weights` on `vertices` (of triangle
    /// `t`): equispaced in one control triangle's parameters when all the
    /// vertices can be expressed in it, else the closest point to `target`
    /// (by default the straight-sided point; module doc, 2 and 3), in `t`'s
    /// face either way.
    fn between(
        &self,
        vertices: &[u32],
        weights: &[f64],
        t: usize,
        target: Option<DVec3>,
    ) -> Result<Node> {
        let mesh = self.mesh;
        let surface = self.surface;
        let net = surface.net();
        let face_of = surface.model().face_of_triangle();
        let face = mesh.faces[t];
        let params: Vec<SurfacePoint> = vertices.iter().map(|&i| mesh.params[i as usize]).collect();
        let chart = mesh.charts.get(t).copied();
        let in_chart = chart.and_then(|c| {
            params
                .iter()
                .map(|&p| reparameterize(net.topology(), p, c))
                .collect::<Option<Vec<SurfacePoint>>>()
                .map(|uv| (c, uv))
        });
        if let Some((c, uv)) = in_chart {
            let (mut v, mut w) = (0.0, 0.0);
            for (q, &s) in uv.iter().zip(weights) {
                v += s * q.v;
                w += s * q.w;
            }
            let p = SurfacePoint { tri: c, v, w };
            return Ok((surface.point(c as usize, v, w)?, p));
        }
        let flat: DVec3 = target.unwrap_or_else(|| {
            vertices
                .iter()
                .zip(weights)
                .map(|(&i, &s)| s * mesh.points[i as usize])
                .sum()
        });
        // Local projections from every vertex seen from the face, nearest
        // kept: next to an irregular vertex a descent from one corner can
        // stall in a far local minimum that another corner's avoids.
        let mut order: Vec<usize> = (0..weights.len()).collect();
        order.sort_by(|&a, &b| weights[b].total_cmp(&weights[a]));
        let guesses: Vec<SurfacePoint> = order
            .iter()
            .filter_map(|&j| in_face(surface, params[j], face))
            .collect();
        let Some(&first) = guesses.first() else {
            return Err(Error::InvalidArgument(format!(
                "triangle {t}: none of its vertices {vertices:?} lies on its face {face}"
            )));
        };
        let mut snap = project_in_face(surface, flat, first.tri as usize, first.v, first.w)?;
        for g in &guesses[1..] {
            let other = project_in_face(surface, flat, g.tri as usize, g.v, g.w)?;
            if other.distance < snap.distance {
                snap = other;
            }
        }
        let shortest = (0..vertices.len())
            .map(|j| {
                let (a, b) = (vertices[j], vertices[(j + 1) % vertices.len()]);
                (mesh.points[a as usize] - mesh.points[b as usize]).length()
            })
            .fold(f64::INFINITY, f64::min);
        if snap.distance > 0.25 * shortest {
            // Still far: the global minimum, if it is on this face.
            let global = snap_near(surface, flat, first.tri as usize, first.v, first.w)?;
            if face_of[global.tri] == face && global.distance < snap.distance {
                snap = global;
            }
        }
        let p = SurfacePoint {
            tri: snap.tri as u32,
            v: snap.v,
            w: snap.w,
        };
        Ok((snap.point, p))
    }
}

/// Surface point `p` seen from a control triangle of model face `face`:
/// itself, or re-expressed in a triangle of the face around its control
/// vertices when it lies on a crease or corner. `None` when no triangle of
/// the face holds it.
fn in_face(surface: &Surface, p: SurfacePoint, face: u32) -> Option<SurfacePoint> {
    let face_of = surface.model().face_of_triangle();
    if face_of[p.tri as usize] == face {
        return Some(p);
    }
    let net = surface.net();
    let topo = net.topology();
    net.triangles()[p.tri as usize]
        .iter()
        .flat_map(|&x| topo.fan(x as usize))
        .filter(|&&c| face_of[c as usize] == face)
        .find_map(|&c| reparameterize(topo, p, c))
}
