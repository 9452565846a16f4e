//! Snapping: the closest point of the limit surface to any xyz — the
//! global minimum of the distance, not a local one.
//!
//! Every Loop mask has non-negative weights summing to one, so a
//! triangle's patch lies in the convex hull of its support: the control
//! points of its corners' one-rings (seed 000 §2). After a subdivision
//! step the same holds for each of its four children; after two steps, for
//! each of its sixteen grandchildren. So the patch lies in the hull of the
//! twice-refined points around its children's corners — the vertex points
//! of those six level-1 vertices and the edge points of the level-1 edges at
//! them — which hugs the surface far closer than the control points do. That
//! gives two rigorous lower bounds on the distance from p to a patch:
//!
//! * the distance to the axis-aligned box of the support, which an R-tree
//!   ([`rstar`]) visits in increasing order;
//! * a separating plane: for a unit direction n, no point of the hull is
//!   closer to p than n · p − maxₛ n · s. With n pointing from the patch's
//!   flat approximation to p this is nearly the true distance, and prunes
//!   the neighbours that boxes cannot.
//!
//! Branch and bound, best first: patches come out of the R-tree by box
//! distance, wait in a heap keyed by the larger of their two bounds, and get
//! the local projected-Newton solve ([`local`]) in that order until no
//! bound is below the best distance found.
//!
//! What is proven and what is not: the pruning is rigorous, so every patch
//! that could hold a nearer point is solved. Each solve finds a local
//! minimum of its patch, started at the projection onto the patch's flat
//! triangle — the patch's global minimum whenever its distance function has
//! one basin there, as it does on smooth patches at distances below their
//! radius of curvature. Displacement-mode patches, which the linear
//! correction can bend, get four more starts. The tests compare with a
//! dense brute-force reference on CGAL and synthetic meshes.

mod local;

pub use local::Snap;

use crate::error::{Error, Result};
use crate::surface::{Surface, SurfaceMode};
use glam::{DVec2, DVec3};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::RTree;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

type Leaf = GeomWithData<Rectangle<[f64; 3]>, u32>;

/// What the search needs beyond the surface: built on the first snap.
pub(crate) struct SnapIndex {
    tree: RTree<Leaf>,
    /// The surface point at every control vertex (corner of its triangles).
    anchors: Vec<DVec3>,
    /// The twice-refined points: level-1 vertices, then one per level-1 edge.
    refined: Vec<DVec3>,
    /// The once-refined topology's edges at each of its vertices (CSR).
    vertex_edge_start: Vec<u32>,
    vertex_edges: Vec<u32>,
    /// Vertices of the once-refined net.
    nv1: usize,
}

impl SnapIndex {
    pub(crate) fn new(surface: &Surface) -> SnapIndex {
        let net = surface.net();
        let mut anchors = vec![DVec3::ZERO; net.points().len()];
        for (t, c) in net.triangles().iter().enumerate() {
            for (k, (v, w)) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].into_iter().enumerate() {
                anchors[c[k] as usize] = surface.eval(t, v, w).expect("corners are inside").x;
            }
        }
        let (topo, features) = (net.topology(), net.features());
        let topo1 = topo.refined();
        let features1 = features.refined(topo);
        let points1 = crate::refine::subdivide_points(topo, features, net.points());
        let refined = crate::refine::subdivide_points(&topo1, &features1, &points1);
        let nv1 = topo1.num_vertices();
        let mut vertex_edge_start = vec![0u32; nv1 + 1];
        for &[a, b] in topo1.edges() {
            vertex_edge_start[a as usize + 1] += 1;
            vertex_edge_start[b as usize + 1] += 1;
        }
        for v in 0..nv1 {
            vertex_edge_start[v + 1] += vertex_edge_start[v];
        }
        let mut fill = vertex_edge_start.clone();
        let mut vertex_edges = vec![0u32; 2 * topo1.edges().len()];
        for (e, &[a, b]) in topo1.edges().iter().enumerate() {
            for v in [a, b] {
                vertex_edges[fill[v as usize] as usize] = e as u32;
                fill[v as usize] += 1;
            }
        }
        let mut index = SnapIndex {
            tree: RTree::new(),
            anchors,
            refined,
            vertex_edge_start,
            vertex_edges,
            nv1,
        };
        // Boxes are padded by round-off so that evaluated points, computed
        // in floating point, never fall outside them.
        let pad = 1e-12 * net.bbox_diagonal();
        let leaves: Vec<Leaf> = (0..net.triangles().len())
            .map(|t| {
                let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
                index.for_each_support_point(surface, t, |s| {
                    lo = lo.min(s);
                    hi = hi.max(s);
                });
                let (dlo, dhi) = displacement_box(surface, t);
                let rect = Rectangle::from_corners(
                    (lo + dlo - pad).to_array(),
                    (hi + dhi + pad).to_array(),
                );
                GeomWithData::new(rect, t as u32)
            })
            .collect();
        index.tree = RTree::bulk_load(leaves);
        index
    }

    /// Calls `f` with every twice-refined point whose hull holds the patch
    /// of `tri`: for each corner of its four children (its own corners and
    /// the level-1 vertices on its edges), the vertex point and the edge
    /// points of the level-1 edges there (some more than once).
    fn for_each_support_point(&self, surface: &Surface, tri: usize, mut f: impl FnMut(DVec3)) {
        let net = surface.net();
        let nv = net.points().len();
        let corners = net.triangles()[tri].map(|c| c as usize);
        let mids = net.topology().triangle_edges()[tri].map(|e| nv + e as usize);
        for u in corners.into_iter().chain(mids) {
            f(self.refined[u]);
            let edges = self.vertex_edge_start[u] as usize..self.vertex_edge_start[u + 1] as usize;
            for &e in &self.vertex_edges[edges] {
                f(self.refined[self.nv1 + e as usize]);
            }
        }
    }

    /// Where the Newton solve in triangle `tri` starts: the parameters of
    /// the point of the flat triangle through its corner surface points
    /// nearest to p.
    ///
    /// The start is pulled a twentieth of the way to the centre: at a corner
    /// that is an irregular vertex the parametrisation is singular, and
    /// Newton would crawl away from it by small factors per step.
    fn start(&self, surface: &Surface, tri: usize, p: DVec3) -> DVec2 {
        let c = surface.net().triangles()[tri].map(|i| self.anchors[i as usize]);
        let uv = closest_on_flat_triangle(c, p);
        0.95 * uv + 0.05 * DVec2::splat(1.0 / 3.0)
    }

    /// A rigorous lower bound on the distance from p to the patch of `tri`:
    /// the separating plane whose normal points from the patch's flat
    /// approximation towards p.
    fn plane_bound(&self, surface: &Surface, tri: usize, p: DVec3) -> f64 {
        let c = surface.net().triangles()[tri].map(|i| self.anchors[i as usize]);
        let uv = closest_on_flat_triangle(c, p);
        let q = (1.0 - uv.x - uv.y) * c[0] + uv.x * c[1] + uv.y * c[2];
        let Some(n) = (p - q).try_normalize() else {
            return 0.0;
        };
        let mut reach = f64::NEG_INFINITY;
        self.for_each_support_point(surface, tri, |s| reach = reach.max(n.dot(s)));
        let d = surface.displacements_of(tri);
        reach += d
            .iter()
            .map(|d| n.dot(*d))
            .fold(f64::NEG_INFINITY, f64::max);
        n.dot(p) - reach
    }
}

/// The box of the three corner displacements (zero unless the surface is
/// in displacement mode): the displaced patch lies in the support box
/// plus this box.
fn displacement_box(surface: &Surface, tri: usize) -> (DVec3, DVec3) {
    let d = surface.displacements_of(tri);
    (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]))
}

/// Parameters (v, w) of the point of triangle c nearest to p.
fn closest_on_flat_triangle(c: [DVec3; 3], p: DVec3) -> DVec2 {
    let (e1, e2, r) = (c[1] - c[0], c[2] - c[0], p - c[0]);
    let (a, b, cc) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d, e) = (e1.dot(r), e2.dot(r));
    let det = a * cc - b * b;
    let centre = DVec2::splat(1.0 / 3.0);
    if det.abs() <= f64::EPSILON * a * cc || !det.is_finite() {
        return centre;
    }
    let uv = DVec2::new(cc * d - b * e, a * e - b * d) / det;
    if uv.x >= 0.0 && uv.y >= 0.0 && uv.x + uv.y <= 1.0 {
        return uv;
    }
    // Outside: the nearest point of the three edges.
    let on_segment = |from: DVec2, to: DVec2| {
        let (x0, x1) = (
            c[0] + from.x * e1 + from.y * e2,
            c[0] + to.x * e1 + to.y * e2,
        );
        let s = ((p - x0).dot(x1 - x0) / (x1 - x0).length_squared()).clamp(0.0, 1.0);
        let uv = from + s * (to - from);
        let x = x0 + s * (x1 - x0);
        ((x - p).length_squared(), uv)
    };
    let corners = [DVec2::ZERO, DVec2::X, DVec2::Y];
    (0..3)
        .map(|k| on_segment(corners[k], corners[(k + 1) % 3]))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, uv)| uv)
        .unwrap_or(centre)
}

impl Surface {
    /// The point of the surface nearest to `p` (the global minimum of the
    /// distance), with its triangle and parameters. Where several points are
    /// equally near, one of them.
    pub fn closest_point(&self, p: DVec3) -> Result<Snap> {
        check_point(p)?;
        Ok(self.search(p, None))
    }

    /// [`Surface::closest_point`] starting from a point known to be near
    /// the answer (a neighbouring query's result, say): the local solve
    /// walks from the hint across triangles, then the global search runs
    /// with that distance as its bound — usually only confirming it.
    pub fn snap_near(&self, p: DVec3, tri: usize, v: f64, w: f64) -> Result<Snap> {
        check_point(p)?;
        // Validates the hint (and clamps round-off) like any query.
        self.eval(tri, v, w)?;
        let (v, w) = (v.max(0.0), w.max(0.0));
        let (v, w) = if v + w > 1.0 {
            (v / (v + w), w / (v + w))
        } else {
            (v, w)
        };
        let seed = local::descend(self, p, tri, v, w, true);
        Ok(self.search(p, Some(seed)))
    }

    /// Best-first branch and bound from an optional first candidate.
    fn search(&self, p: DVec3, seed: Option<Snap>) -> Snap {
        let index = self.snap_index();
        let mut best = seed;
        let mut boxes = index
            .tree
            .nearest_neighbor_iter_with_distance_2(&p.to_array());
        let mut next_box = boxes.next();
        // Patches with their lower bound, nearest first.
        let mut pending: BinaryHeap<Reverse<(Bound, u32)>> = BinaryHeap::new();
        loop {
            let best_distance = best.map_or(f64::INFINITY, |b| b.distance);
            // Every patch whose box is nearer than the nearest pending bound
            // must be bounded before that one is taken.
            while let Some((leaf, box_d2)) = next_box {
                let top = pending.peek().map_or(f64::INFINITY, |Reverse((b, _))| b.0);
                let box_distance = box_d2.sqrt();
                if box_distance >= top.min(best_distance) {
                    break;
                }
                let tri = leaf.data;
                let bound = index.plane_bound(self, tri as usize, p).max(box_distance);
                if bound < best_distance {
                    pending.push(Reverse((Bound(bound), tri)));
                }
                next_box = boxes.next();
            }
            let Some(Reverse((Bound(bound), tri))) = pending.pop() else {
                break;
            };
            if bound >= best_distance {
                break;
            }
            let uv = index.start(self, tri as usize, p);
            // A displaced patch (C0 across edges, bent by the linear
            // correction) can hold several local minima: start also from
            // the centre of each quarter.
            let extra: &[[f64; 2]] = match self.mode() {
                SurfaceMode::Displacement => &QUARTER_CENTRES,
                _ => &[],
            };
            for start in std::iter::once([uv.x, uv.y]).chain(extra.iter().copied()) {
                let found = local::descend(self, p, tri as usize, start[0], start[1], false);
                if best.map_or(true, |b| found.distance < b.distance) {
                    best = Some(found);
                }
            }
        }
        best.expect("a surface has at least one triangle")
    }
}

/// The centroids of the four children of the parameter triangle.
const QUARTER_CENTRES: [[f64; 2]; 4] = [
    [1.0 / 6.0, 1.0 / 6.0],
    [2.0 / 3.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0],
    [1.0 / 3.0, 1.0 / 3.0],
];

/// A distance bound, ordered (never NaN: points and nets are finite).
#[derive(Clone, Copy, PartialEq)]
struct Bound(f64);
impl Eq for Bound {}
impl PartialOrd for Bound {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Bound {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

fn check_point(p: DVec3) -> Result<()> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!(
            "snap: the point {:?} is not finite",
            p.to_array()
        )))
    }
}
