//! The limit surface as a linear map of the control points, row by row.
//!
//! The rows are those of the limit positions of the level-k refined
//! vertices: S∞ Sₖ₋₁ ⋯ S₀, each Sₗ one step of Loop subdivision (the
//! masks of [`crate::rules`], read off by linearity, so they live only
//! there) and S∞ the limit masks of [`crate::net::limit_mask_entries`].
//! Every factor is a sparse linear map, so a row is exact (no fitting of
//! the evaluator), has the support of the control triangle's two-ring,
//! and is built the same way for every vertex kind: regular, special,
//! crease, dart and corner. We chose these over the evaluator's
//! box-spline rows because they are exact at every vertex kind without
//! the special patches' eigen-machinery; the price is that a row sits at
//! a dyadic parameter (i/2ᵏ, j/2ᵏ), not at a data point's own, which the
//! caller makes up for on the right-hand side (see [`super::data`]).

use crate::features::{Features, VertexKind};
use crate::net::{limit_mask_entries, ControlNet};
use crate::refine::refine_uniform;
use crate::rules;
use crate::topology::Topology;
use crate::Result;
use glam::DVec3;
use rayon::prelude::*;

/// Refinement levels of the rows: dyadic spacing h/8 on a net of edge h.
pub const LEVELS: u32 = 3;

/// A sparse row: (control vertex, weight).
pub type Row = Vec<(u32, f64)>;

/// The subdivision operators of each level, the finest level's topology
/// and tags, and its limit masks: everything a row is made of.
pub struct Rows {
    /// Sₗ as rows over level-l vertices, for l = 0 … k−1.
    steps: Vec<Vec<Row>>,
    /// S∞ on the finest level, one row per finest vertex.
    limit: Vec<Row>,
    /// Vertex counts per level, 0 … k.
    sizes: Vec<usize>,
    /// The finest level's connectivity and tags.
    pub fine: ControlNet,
}

impl Rows {
    /// The operators of `net` refined [`LEVELS`] times.
    pub fn new(net: &ControlNet) -> Result<Rows> {
        let mut steps = Vec::new();
        let mut sizes = vec![net.points().len()];
        let mut current = net.clone();
        for _ in 0..LEVELS {
            steps.push(step_rows(current.topology(), current.features()));
            current = refine_uniform(&current, 1)?.into_net();
            sizes.push(current.points().len());
        }
        let mut limit = vec![Vec::new(); current.points().len()];
        for (v, u, w) in limit_mask_entries(current.topology(), current.features()) {
            limit[v as usize].push((u, w));
        }
        Ok(Rows {
            steps,
            limit,
            sizes,
            fine: current,
        })
    }

    /// The row of finest vertex `r`'s limit position over the control
    /// points of the base net, in increasing order of control vertex.
    /// `scratch` is a dense accumulator as long as the largest level, all
    /// zeros on entry and on exit.
    pub fn row(&self, r: u32, scratch: &mut Vec<f64>) -> Row {
        let mut row = self.limit[r as usize].clone();
        for l in (0..self.steps.len()).rev() {
            scratch.resize(self.sizes[l].max(scratch.len()), 0.0);
            let mut touched = Vec::with_capacity(4 * row.len());
            for &(j, w) in &row {
                for &(i, s) in &self.steps[l][j as usize] {
                    if scratch[i as usize] == 0.0 {
                        touched.push(i);
                    }
                    scratch[i as usize] += w * s;
                }
            }
            row = touched
                .into_iter()
                .map(|i| (i, std::mem::take(&mut scratch[i as usize])))
                .filter(|&(_, w)| w != 0.0)
                .collect();
        }
        row.sort_unstable_by_key(|&(i, _)| i);
        row
    }

    /// Rows of many finest vertices, in parallel.
    pub fn rows(&self, vertices: &[u32]) -> Vec<Row> {
        vertices
            .par_iter()
            .map_init(Vec::new, |scratch, &r| self.row(r, scratch))
            .collect()
    }

    /// The finest vertex nearest (in parameters) to (v, w) of base triangle
    /// `tri`: descend to the level-k triangle holding it (child c of
    /// triangle t is 4t + c, its corners in [`Topology::refined`]'s order)
    /// and take its corner with the largest barycentric weight.
    pub fn nearest_vertex(&self, tri: usize, v: f64, w: f64) -> u32 {
        let (mut t, mut v, mut w) = (tri, v, w);
        for _ in 0..self.steps.len() {
            let (c, map) = crate::eval::affine::child_containing(v, w);
            (v, w) = map.apply(v, w);
            t = 4 * t + c;
        }
        let corners = self.fine.triangles()[t];
        let weights = [1.0 - v - w, v, w];
        let k = (0..3)
            .max_by(|&a, &b| weights[a].total_cmp(&weights[b]))
            .unwrap_or(0);
        corners[k]
    }
}

/// Sparse dot product of a row with points.
pub fn apply(row: &Row, points: &[DVec3]) -> DVec3 {
    row.iter().map(|&(i, w)| w * points[i as usize]).sum()
}

/// One step of Loop subdivision as rows over the coarse vertices, numbered
/// as [`crate::refine`] numbers the refined vertices (old vertices first,
/// then one per edge). The weights are read off the rules by linearity.
fn step_rows(topo: &Topology, features: &Features) -> Vec<Row> {
    let n = topo.num_vertices();
    let x = |f: DVec3| f.x;
    let mut rows: Vec<Row> = (0..n)
        .into_par_iter()
        .map(|v| match features.vertex_kind(topo, v) {
            VertexKind::Smooth | VertexKind::Dart => {
                let ring = topo.ring(v);
                let k = ring.len();
                let own = x(rules::smooth_vertex(DVec3::X, DVec3::ZERO, k));
                let each = x(rules::smooth_vertex(DVec3::ZERO, DVec3::X, k));
                std::iter::once((v as u32, own))
                    .chain(ring.iter().map(|&u| (u, each)))
                    .collect()
            }
            VertexKind::Crease => {
                let own = x(rules::crease_vertex(DVec3::X, DVec3::ZERO));
                let each = x(rules::crease_vertex(DVec3::ZERO, DVec3::X));
                std::iter::once((v as u32, own))
                    .chain(
                        features
                            .hard_neighbours(topo, v)
                            .into_iter()
                            .map(|u| (u, each)),
                    )
                    .collect()
            }
            VertexKind::Corner => vec![(v as u32, x(rules::corner_vertex(DVec3::X)))],
        })
        .collect();
    let hard = x(rules::hard_edge(DVec3::X, DVec3::ZERO));
    let near = x(rules::smooth_edge(
        DVec3::X,
        DVec3::ZERO,
        DVec3::ZERO,
        DVec3::ZERO,
    ));
    let far = x(rules::smooth_edge(
        DVec3::ZERO,
        DVec3::ZERO,
        DVec3::X,
        DVec3::ZERO,
    ));
    rows.extend((0..topo.num_edges()).map(|e| {
        let [a, b] = topo.edges()[e];
        if features.is_hard_edge(e) {
            vec![(a, hard), (b, hard)]
        } else {
            let [t0, t1] = topo.edge_triangles()[e];
            let opposite = |t: u32| {
                let [c0, c1, c2] = topo.triangles()[t as usize];
                c0 ^ c1 ^ c2 ^ a ^ b
            };
            vec![
                (a, near),
                (b, near),
                (opposite(t0), far),
                (opposite(t1), far),
            ]
        }
    }));
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::examples;

    /// The rows applied to the control points are the refined net's limit
    /// points, on a net with creases, corners and irregular vertices.
    #[test]
    fn rows_are_the_refined_limit_points() {
        let e = examples::by_name("viking").unwrap();
        let mut net = ControlNet::from_arrays(e.points, &e.tris).unwrap();
        net.tag_by_angle(30.0).unwrap();
        net.tag_vertex(3).unwrap();
        let rows = Rows::new(&net).unwrap();
        let fine = refine_uniform(&net, LEVELS).unwrap();
        let limits = fine.limit_points();
        let all: Vec<u32> = (0..limits.len() as u32).collect();
        for (r, row) in rows.rows(&all).iter().enumerate() {
            let d = (apply(row, net.points()) - limits[r]).length();
            assert!(d <= 1e-12 * net.bbox_diagonal(), "vertex {r}: {d}");
        }
    }

    /// The nearest finest vertex of a parameter point is a corner of the
    /// dyadic triangle holding it: its limit point is near the surface
    /// point there (within the triangle's size).
    #[test]
    fn nearest_vertex_is_near() {
        let e = examples::by_name("viking").unwrap();
        let net = ControlNet::from_arrays(e.points, &e.tris).unwrap();
        let rows = Rows::new(&net).unwrap();
        let surface = crate::Surface::new(&net).unwrap();
        let limits = rows.fine.limit_points();
        let mut scratch = Vec::new();
        for t in (0..net.triangles().len()).step_by(7) {
            for &(v, w) in &[(0.1, 0.2), (0.7, 0.05), (0.3, 0.6), (0.0, 0.0), (0.5, 0.5)] {
                let r = rows.nearest_vertex(t, v, w);
                let at = surface.point(t, v, w).unwrap();
                let c = net.triangles()[t].map(|i| net.points()[i as usize]);
                let size = (c[0] - c[1]).length().max((c[1] - c[2]).length());
                let d = (limits[r as usize] - at).length();
                assert!(d <= 0.2 * size, "tri {t} ({v}, {w}): {d} of {size}");
                let sr = apply(&rows.row(r, &mut scratch), net.points());
                assert!((sr - limits[r as usize]).length() <= 1e-12);
            }
        }
    }
}
