//! The data and where each datum sits on the current surface (parameter
//! correction, as in Hoppe et al.: between solves every datum is projected
//! again onto the surface just solved).
//!
//! The data are the input's vertices, exactly on the true surface in a
//! CAD export. Those on the input's hard edges and corners are fitted by
//! the new net's crease curves (whose limit is the cubic B-spline of the
//! crease polygon, independent of the faces beside it); the others by the
//! surface.
//!
//! A datum's row is the limit position of the level-k refined vertex r
//! nearest its footpoint ([`super::rows`]). The offset between that dyadic
//! point and the footpoint is carried on the right-hand side from the
//! current surface: the target of row r is S(r) + (p − S(u)), with S the
//! current surface, u the datum's footpoint and p the datum. At a fixed
//! point of the rounds the surface passes through p at u itself; what is
//! left after the last round is how much S(r) − S(u) changes in one
//! solve, which the rounds drive down, and which the report measures by
//! certified closest points, never by these rows.
//!
//! Footpoints on the surface: certified closest points the first round
//! ([`crate::snap::closest_point_within`]), local projections from the
//! previous footpoint after ([`crate::snap::project`]). On crease curves:
//! the nearest refined crease vertex, and the projection onto the crease
//! polygon of the finest level around it (spacing h/2ᵏ, so its chord error
//! is 1/4ᵏ of the crease's own).
//!
//! A row depends only on the net's connectivity, and most data keep their
//! row vertex from one round to the next: rows are kept across rounds and
//! only those of vertices met for the first time are built.

use super::rows::{apply, Row, Rows};
use super::samples::between_vertices;
use crate::error::Result;
use crate::features::VertexKind;
use crate::net::ControlNet;
use crate::snap;
use crate::surface::Surface;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// The weight of an input corner in the least squares against one datum
/// elsewhere. A corner vertex of the new net is where its limit surface
/// is, and the input's corner is exact, but the data around it pull the
/// other way where Loop's surface cannot follow them (a cone's tip is a
/// cusp of Loop's, not a cone point). Measured with data at half the
/// spacing of a net remeshed at 0.015 of the diagonal: at weight 1 the
/// fitted cone's tip sat 1.7e-4 of the diagonal from the true apex and the
/// fitted fandisk 3.0e-5 from its crease fold; at 10, 4.4e-5 and 5.1e-6
/// (at 100 about the same); on the default net now, 4.2e-5 and 5.2e-6.
pub const CORNER_WEIGHT: f64 = 10.0;

/// The data of one fit.
pub struct Data {
    /// Data points, the input vertices first, then the points predicted
    /// between them ([`super::samples`]), and whether each lies on a
    /// feature.
    pub points: Vec<DVec3>,
    /// The input vertex of each of the first data.
    pub vertices: Vec<usize>,
    pub on_feature: Vec<bool>,
    /// Each datum's weight in the least squares: [`CORNER_WEIGHT`] at the
    /// input's corners, 1 elsewhere.
    pub weights: Vec<f64>,
    /// Each surface datum's footpoint (tri, v, w) on the current surface.
    footpoints: Vec<Option<(usize, f64, f64)>>,
    /// The rows built so far, by finest vertex.
    rows: HashMap<u32, Row>,
}

/// A datum located: its footpoint on the surface (none on a crease), the
/// finest vertex of its row, and the offset of its target from that
/// vertex's limit position.
type Located = (Option<(usize, f64, f64)>, u32, DVec3);

/// Every datum's equation: the finest vertex whose row it takes
/// ([`Data::row`]), and the row's target.
pub struct Equations {
    pub vertices: Vec<u32>,
    pub targets: Vec<DVec3>,
}

impl Data {
    /// Every referenced vertex of `input`, split by kind, and the points
    /// predicted between them about `spacing` apart.
    pub fn new(input: &ControlNet, spacing: f64) -> Data {
        let kinds = input.vertex_kinds();
        let topo = input.topology();
        let used: Vec<usize> = (0..input.points().len())
            .filter(|&v| !topo.is_unreferenced(v))
            .collect();
        let samples = between_vertices(input, spacing);
        let mut points: Vec<DVec3> = used.iter().map(|&v| input.points()[v]).collect();
        let mut on_feature: Vec<bool> = used
            .iter()
            .map(|&v| matches!(kinds[v], VertexKind::Crease | VertexKind::Corner))
            .collect();
        let mut weights: Vec<f64> = used
            .iter()
            .map(|&v| {
                if kinds[v] == VertexKind::Corner {
                    CORNER_WEIGHT
                } else {
                    1.0
                }
            })
            .collect();
        weights.resize(used.len() + samples.points.len(), 1.0);
        points.extend(samples.points);
        on_feature.extend(samples.on_feature);
        Data {
            weights,
            footpoints: vec![None; points.len()],
            points,
            vertices: used,
            on_feature,
            rows: HashMap::new(),
        }
    }

    /// The row of finest vertex `r`, built by [`Data::equations`].
    pub fn row(&self, r: u32) -> &Row {
        &self.rows[&r]
    }

    /// The equations of every datum on the surface of control points `x`
    /// (`surface`, and `crease` at `x`), updating the footpoints.
    pub fn equations(
        &mut self,
        surface: &Surface,
        rows: &Rows,
        crease: &Crease,
        x: &[DVec3],
    ) -> Result<Equations> {
        let located: Vec<Result<Located>> = self
            .points
            .par_iter()
            .zip(&self.on_feature)
            .zip(&self.footpoints)
            .map(|((&p, &feature), &foot)| {
                if feature && !crease.vertices.is_empty() {
                    let (r, offset) = crease.locate(p);
                    return Ok((None, r, offset));
                }
                let s = match foot {
                    None => snap::closest_point_within(surface, p, 1e-9)?,
                    Some((t, v, w)) => snap::project(surface, p, t, v, w)?,
                };
                let r = rows.nearest_vertex(s.tri, s.v, s.w);
                Ok((Some((s.tri, s.v, s.w)), r, p - s.point))
            })
            .collect();
        let mut vertices = Vec::with_capacity(located.len());
        let mut offsets = Vec::with_capacity(located.len());
        for (i, l) in located.into_iter().enumerate() {
            let (foot, vertex, offset) = l?;
            self.footpoints[i] = foot;
            vertices.push(vertex);
            offsets.push(offset);
        }
        let mut new: Vec<u32> = vertices
            .iter()
            .copied()
            .filter(|r| !self.rows.contains_key(r))
            .collect();
        new.sort_unstable();
        new.dedup();
        let built = rows.rows(&new);
        self.rows.extend(new.into_iter().zip(built));
        let targets = vertices
            .par_iter()
            .zip(&offsets)
            .map(|(r, &offset)| apply(&self.rows[r], x) + offset)
            .collect();
        Ok(Equations { vertices, targets })
    }
}

/// The crease polygon of the finest level: its vertices, their rows, their
/// limit positions for the current control points, and their crease
/// neighbours.
pub struct Crease {
    vertices: Vec<u32>,
    rows: Vec<Row>,
    limits: Vec<DVec3>,
    /// Per crease vertex: the positions (in `vertices`) of its crease
    /// neighbours.
    neighbours: Vec<Vec<usize>>,
}

impl Crease {
    /// The finest crease and corner vertices of `rows` (their limit
    /// positions set by [`Crease::at`]).
    pub fn new(rows: &Rows) -> Crease {
        let fine = &rows.fine;
        let kinds = fine.vertex_kinds();
        let vertices: Vec<u32> = (0..kinds.len() as u32)
            .filter(|&v| matches!(kinds[v as usize], VertexKind::Crease | VertexKind::Corner))
            .collect();
        let index: HashMap<u32, usize> =
            vertices.iter().enumerate().map(|(i, &v)| (v, i)).collect();
        let crease_rows = rows.rows(&vertices);
        let neighbours = vertices
            .iter()
            .map(|&v| {
                fine.features()
                    .hard_neighbours(fine.topology(), v as usize)
                    .iter()
                    .filter_map(|u| index.get(u).copied())
                    .collect()
            })
            .collect();
        Crease {
            vertices,
            rows: crease_rows,
            limits: Vec::new(),
            neighbours,
        }
    }

    /// Sets the limit positions for control points `x`.
    pub fn at(&mut self, x: &[DVec3]) {
        self.limits = self.rows.par_iter().map(|r| apply(r, x)).collect();
    }

    /// The finest crease vertex nearest `p` and the offset of its row's
    /// target from its limit position: from the crease polygon to p.
    fn locate(&self, p: DVec3) -> (u32, DVec3) {
        let (i, _) = self
            .limits
            .iter()
            .enumerate()
            .map(|(i, l)| (i, l.distance_squared(p)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .expect("a crease vertex");
        let s = self.limits[i];
        let mut q = s;
        for &j in &self.neighbours[i] {
            let e = self.limits[j] - s;
            let t = ((p - s).dot(e) / e.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 0.5);
            let c = s + t * e;
            if c.distance_squared(p) < q.distance_squared(p) {
                q = c;
            }
        }
        (self.vertices[i], p - q)
    }
}
