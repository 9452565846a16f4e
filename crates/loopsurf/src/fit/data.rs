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

use super::rows::{apply, Row, Rows};
use super::samples::between_vertices;
use crate::error::Result;
use crate::features::VertexKind;
use crate::net::ControlNet;
use crate::snap;
use crate::surface::Surface;
use glam::DVec3;
use rayon::prelude::*;

/// The data of one fit.
pub struct Data {
    /// Data points, the input vertices first, then the points predicted
    /// between them ([`super::samples`]), and whether each lies on a
    /// feature.
    pub points: Vec<DVec3>,
    /// The input vertex of each of the first data.
    pub vertices: Vec<usize>,
    pub on_feature: Vec<bool>,
    /// Each surface datum's footpoint (tri, v, w) on the current surface.
    footpoints: Vec<Option<(usize, f64, f64)>>,
}

/// A datum located: its footpoint on the surface (none on a crease), the
/// finest vertex of its row, and the row's target.
type Located = (Option<(usize, f64, f64)>, u32, DVec3);

/// One datum's row and target.
pub struct Equation {
    pub vertex: u32,
    pub target: DVec3,
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
        points.extend(samples.points);
        on_feature.extend(samples.on_feature);
        Data {
            footpoints: vec![None; points.len()],
            points,
            vertices: used,
            on_feature,
        }
    }

    /// The equations of every datum on the surface of control points `x`
    /// (its `surface` and the finest limit positions `fine` built from
    /// them), updating the footpoints.
    pub fn equations(
        &mut self,
        surface: &Surface,
        rows: &Rows,
        crease: &Crease,
        x: &[DVec3],
    ) -> Result<Vec<Equation>> {
        let located: Vec<Result<Located>> = self
            .points
            .par_iter()
            .zip(&self.on_feature)
            .zip(&self.footpoints)
            .map_init(Vec::new, |scratch, ((&p, &feature), &foot)| {
                if feature && !crease.vertices.is_empty() {
                    let (r, q) = crease.locate(p);
                    return Ok((None, r, q));
                }
                let s = match foot {
                    None => snap::closest_point_within(surface, p, 1e-9)?,
                    Some((t, v, w)) => snap::project(surface, p, t, v, w)?,
                };
                let r = rows.nearest_vertex(s.tri, s.v, s.w);
                let sr = apply(&rows.row(r, scratch), x);
                Ok((Some((s.tri, s.v, s.w)), r, sr + (p - s.point)))
            })
            .collect();
        let mut out = Vec::with_capacity(located.len());
        for (i, l) in located.into_iter().enumerate() {
            let (foot, vertex, target) = l?;
            self.footpoints[i] = foot;
            out.push(Equation { vertex, target });
        }
        Ok(out)
    }
}

/// The crease polygon of the finest level: its vertices, their limit
/// positions and their crease neighbours.
pub struct Crease {
    vertices: Vec<u32>,
    limits: Vec<DVec3>,
    /// Per crease vertex: the positions (in `vertices`) of its crease
    /// neighbours.
    neighbours: Vec<Vec<usize>>,
}

impl Crease {
    /// The finest crease and corner vertices of `rows` with their limit
    /// positions for control points `x`.
    pub fn new(rows: &Rows, x: &[DVec3]) -> Crease {
        let fine = &rows.fine;
        let kinds = fine.vertex_kinds();
        let vertices: Vec<u32> = (0..kinds.len() as u32)
            .filter(|&v| matches!(kinds[v as usize], VertexKind::Crease | VertexKind::Corner))
            .collect();
        let index: std::collections::HashMap<u32, usize> =
            vertices.iter().enumerate().map(|(i, &v)| (v, i)).collect();
        let limits = rows.rows(&vertices).iter().map(|r| apply(r, x)).collect();
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
            limits,
            neighbours,
        }
    }

    /// The finest crease vertex nearest `p` and the target of its row:
    /// its limit position moved by the offset from the crease polygon to p.
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
        (self.vertices[i], s + (p - q))
    }
}

/// Rows of the equations' vertices, computed once per distinct vertex.
pub fn rows_of(rows: &Rows, equations: &[Equation]) -> (Vec<Row>, Vec<usize>) {
    let mut distinct: Vec<u32> = equations.iter().map(|e| e.vertex).collect();
    distinct.sort_unstable();
    distinct.dedup();
    let computed = rows.rows(&distinct);
    let at = equations
        .iter()
        .map(|e| distinct.binary_search(&e.vertex).expect("listed"))
        .collect();
    (computed, at)
}
