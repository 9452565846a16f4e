//! Is a curved element usable, and how far is it from the surface?
//!
//! **Validity** is the scaled Jacobian, the figure gmsh reports as
//! minJ/maxJ. A surface element has no determinant of its own; J is the
//! area element x_ξ × x_η measured along the normal of the element's
//! straight-sided triangle, which is what turns negative where the element
//! folds over itself. Sampled at the quadrature points and the nodes, the
//! scaled Jacobian is min J / max |J|: 1 for a straight element, ≤ 0 for
//! an invalid one (a thin element on strong curvature).
//!
//! **Distance** is the geometric error of the curved mesh: its map at
//! interior sample points (never nodes, where it is zero by construction),
//! each snapped to the surface with the certified snap.

use super::lagrange::{basis, quadrature, reference_nodes, samples};
use super::CurvedMesh;
use crate::error::Result;
use crate::geometry::unit_normal;
use crate::snap::{closest_point, snap_near};
use crate::surface::Surface;
use glam::DVec3;
use rayon::prelude::*;

/// The scaled Jacobians of a curved mesh.
#[derive(Debug, Clone)]
pub struct Validity {
    /// Per triangle: min J / max |J| over its samples.
    pub scaled_jacobians: Vec<f64>,
    /// The smallest of them (1 for an empty mesh).
    pub min: f64,
    /// Triangles whose scaled Jacobian is at or below 0, ascending.
    pub invalid: Vec<u32>,
}

/// The largest distance from a curved mesh to the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distance {
    /// Model units.
    pub max: f64,
    /// The triangle where it is reached.
    pub triangle: u32,
}

/// Position and derivatives by ξ and η of the element with node positions
/// `nodes` at a point where the basis is `b` ([`basis`]).
fn apply(b: &[[f64; 3]], nodes: &[DVec3]) -> [DVec3; 3] {
    let mut out = [DVec3::ZERO; 3];
    for (b, &x) in b.iter().zip(nodes) {
        for d in 0..3 {
            out[d] += b[d] * x;
        }
    }
    out
}

impl CurvedMesh {
    /// The element's nodes as points.
    fn element_points(&self, t: usize) -> Vec<DVec3> {
        self.element(t)
            .iter()
            .map(|&i| self.nodes[i as usize])
            .collect()
    }

    /// Position and derivatives by ξ and η of triangle `t`'s map at (ξ, η)
    /// of the reference triangle.
    pub fn map(&self, t: usize, xi: f64, eta: f64) -> [DVec3; 3] {
        apply(&basis(self.order, xi, eta), &self.element_points(t))
    }

    /// The scaled Jacobian of every triangle (module doc).
    pub fn validity(&self) -> Validity {
        let mut at: Vec<[f64; 2]> = quadrature().iter().map(|q| [q[0], q[1]]).collect();
        at.extend(reference_nodes(self.order));
        let bases: Vec<_> = at.iter().map(|&[x, y]| basis(self.order, x, y)).collect();
        let scaled_jacobians: Vec<f64> = (0..self.len())
            .into_par_iter()
            .map(|t| {
                let x = self.element_points(t);
                let normal = unit_normal([x[0], x[1], x[2]]);
                let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
                for b in &bases {
                    let [_, dx, dy] = apply(b, &x);
                    let j = dx.cross(dy).dot(normal);
                    lo = lo.min(j);
                    hi = hi.max(j.abs());
                }
                if hi > 0.0 {
                    lo / hi
                } else {
                    0.0
                }
            })
            .collect();
        let min = scaled_jacobians.iter().copied().fold(1.0, f64::min);
        let invalid = (0..scaled_jacobians.len() as u32)
            .filter(|&t| scaled_jacobians[t as usize] <= 0.0)
            .collect();
        Validity {
            scaled_jacobians,
            min,
            invalid,
        }
    }

    /// The largest distance from the curved mesh to `surface`, over 15
    /// interior samples per triangle, each snapped with the certified snap
    /// (from the nearest node's parameters, so it is usually a
    /// confirmation; without parameters, as for a mesh read from another
    /// tool, from scratch).
    pub fn distance_to(&self, surface: &Surface) -> Result<Distance> {
        let samples = samples();
        let per = self.nodes_per_triangle();
        let bases: Vec<_> = samples
            .iter()
            .map(|&[x, y]| basis(self.order, x, y))
            .collect();
        crate::snap::build_index(surface);
        let worst = (0..self.len())
            .into_par_iter()
            .map(|t| {
                let ids = self.element(t);
                let points = self.element_points(t);
                let mut worst = 0.0f64;
                for b in &bases {
                    let [x, _, _] = apply(b, &points);
                    let nearest = (0..per).fold(0, |m, j| if b[j][0] > b[m][0] { j } else { m });
                    let snap = match self.params.get(ids[nearest] as usize) {
                        Some(p) => snap_near(surface, x, p.tri as usize, p.v, p.w)?,
                        None => closest_point(surface, x)?,
                    };
                    worst = worst.max(snap.distance);
                }
                Ok((worst, t as u32))
            })
            .collect::<Result<Vec<(f64, u32)>>>()?
            .into_iter()
            .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a });
        Ok(Distance {
            max: worst.0,
            triangle: worst.1,
        })
    }

    /// The area of the curved mesh, by the degree-6 quadrature of the
    /// area element |x_ξ × x_η|.
    pub fn area(&self) -> f64 {
        let quad = quadrature();
        let bases: Vec<_> = quad.iter().map(|q| basis(self.order, q[0], q[1])).collect();
        (0..self.len())
            .into_par_iter()
            .map(|t| {
                let x = self.element_points(t);
                quad.iter()
                    .zip(&bases)
                    .map(|(q, b)| {
                        let [_, dx, dy] = apply(b, &x);
                        q[2] * dx.cross(dy).length()
                    })
                    .sum::<f64>()
            })
            .sum()
    }
}
