//! Exact evaluation of the model's curves (the limit crease and boundary
//! curves), their arc length, and projection onto them.
//!
//! A curve's parameter t runs over its chain, one unit per control edge
//! (docs/design.md). The crease rules (edge ½ ½, vertex ⅛ ¾ ⅛) are those of the
//! uniform cubic B-spline, and a corner is fixed, so the limit curve is, on
//! each unit segment, the cubic B-spline segment of four chain points — at a
//! corner end with the phantom point 2P₀ − P₁, which makes the fixed-end
//! rule a B-spline rule; around a closed loop, periodically. Only next to a
//! dart tip (the crease ends inside a face) is it not: the tip moves by the
//! smooth rule, so the two segments whose B-spline support holds the tip
//! are evaluated on the surface instead, along the control edge, which is
//! exact too. At integer t the curve is the chain vertex's limit
//! (P₋ + 4P + P₊)/6, with tangent (P₊ − P₋)/2 and second derivative
//! P₋ − 2P + P₊: these depend on the three points alone (after one step the
//! vertex's curve neighbours are edge midpoints), darts or not. At a dart
//! tip itself the parameterisation is singular, as at any special vertex of
//! the surface: the position is exact and the derivatives are reported as
//! zero with `at_special_vertex` set.
//!
//! In displacement mode the surface adds, per triangle, the linear
//! interpolation of its corners' displacements; along an edge that is the
//! same from both sides, so the curve adds it too.
//!
//! This file holds the handle and evaluation; arc length is in `length`,
//! projection and closest points in `closest`.

mod closest;
mod length;

pub use closest::CurveSnap;

use crate::error::{Error, Result};
use crate::features::VertexKind;
use crate::model::{runs, Curve};
use crate::parameters::{vertex_point, SurfacePoint, CORNERS};
use crate::surface::{Derived, Surface, SurfaceMode, PARAMETER_TOLERANCE};
use crate::topology::NONE;
use glam::DVec3;
use std::sync::OnceLock;

/// Position and first and second derivatives with respect to t.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveEvaluation {
    pub x: DVec3,
    pub dx: DVec3,
    pub ddx: DVec3,
    /// t is a dart tip: the position is exact, the derivatives are zero
    /// (the parameterisation is singular there).
    pub at_special_vertex: bool,
}

impl CurveEvaluation {
    /// X X′ X″ as 9 numbers (the `eval --edge` and `ls_curve_evaluate`
    /// record).
    pub fn record(&self) -> [f64; 9] {
        let mut out = [0.0; 9];
        out[0..3].copy_from_slice(&self.x.to_array());
        out[3..6].copy_from_slice(&self.dx.to_array());
        out[6..9].copy_from_slice(&self.ddx.to_array());
        out
    }
}

/// Uniform cubic B-spline basis on [0, 1] and its first two derivatives.
fn bspline_basis(s: f64) -> [[f64; 4]; 3] {
    let r = 1.0 - s;
    [
        [
            r * r * r / 6.0,
            (3.0 * s * s * s - 6.0 * s * s + 4.0) / 6.0,
            (-3.0 * s * s * s + 3.0 * s * s + 3.0 * s + 1.0) / 6.0,
            s * s * s / 6.0,
        ],
        [
            -r * r / 2.0,
            (3.0 * s * s - 4.0 * s) / 2.0,
            (-3.0 * s * s + 2.0 * s + 1.0) / 2.0,
            s * s / 2.0,
        ],
        [r, 3.0 * s - 2.0, 1.0 - 3.0 * s, s],
    ]
}

/// One curve of a surface's model ([`Surface::model`]) as a curve in
/// space: its limit, arc length and projection. A handle is cheap to make
/// (`LimitCurve::new(&surface, c)?.eval(t)`); the lengths it integrates
/// are kept with the surface, so a later handle on the same curve finds
/// them.
#[derive(Clone, Copy)]
pub struct LimitCurve<'s> {
    surface: &'s Surface,
    index: usize,
    curve: &'s Curve,
    /// This curve's unit segment lengths, integrated on first use.
    lengths: &'s OnceLock<Vec<f64>>,
}

/// Per model curve, its unit segment lengths once integrated: placing many
/// points on one curve would otherwise integrate it again for each. The
/// surface keeps them ([`Derived`]) without knowing what they are.
struct CurveLengths(Vec<OnceLock<Vec<f64>>>);

impl Derived for CurveLengths {
    fn memory_bytes(&self) -> usize {
        self.0.capacity() * std::mem::size_of::<OnceLock<Vec<f64>>>()
            + self
                .0
                .iter()
                .filter_map(OnceLock::get)
                .map(|t| t.capacity() * std::mem::size_of::<f64>())
                .sum::<usize>()
    }
}

impl<'s> LimitCurve<'s> {
    /// Curve `index` of `surface`'s model, checked.
    pub fn new(surface: &'s Surface, index: usize) -> Result<LimitCurve<'s>> {
        let curves = surface.model().curves();
        let curve = curves.get(index).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "curve {index}: out of range (the model has {} curves)",
                curves.len()
            ))
        })?;
        let lengths = surface.derived(|s| {
            CurveLengths(
                (0..s.model().curves().len())
                    .map(|_| OnceLock::new())
                    .collect(),
            )
        });
        Ok(LimitCurve {
            surface,
            index,
            curve,
            lengths: &lengths.0[index],
        })
    }

    /// The model curve: its chain of control vertices, edges and faces.
    pub fn curve(&self) -> &'s Curve {
        self.curve
    }

    /// t checked against [0, n] (round-off beyond is clamped).
    fn parameter(&self, t: f64) -> Result<f64> {
        let n = self.curve.len() as f64;
        let slack = PARAMETER_TOLERANCE * n.max(1.0);
        if !t.is_finite() || t < -slack || t > n + slack {
            return Err(Error::InvalidArgument(format!(
                "curve parameter t = {t}: outside [0, {n}]"
            )));
        }
        Ok(t.clamp(0.0, n))
    }

    /// Chain point j of a curve, extended past open ends by the phantom
    /// points 2P₀ − P₁ and 2Pₙ − Pₙ₋₁, and periodically around a loop.
    fn chain_point(&self, j: isize) -> DVec3 {
        let curve = self.curve;
        let p = |i: usize| self.surface.net().points()[curve.chain[i] as usize];
        let n = curve.len() as isize;
        if curve.is_closed() {
            return p(j.rem_euclid(n) as usize);
        }
        if j < 0 {
            2.0 * p(0) - p(1)
        } else if j > n {
            2.0 * p(n as usize) - p(n as usize - 1)
        } else {
            p(j as usize)
        }
    }

    /// Whether chain vertex `j` of an open curve is a dart tip.
    fn is_dart_tip(&self, j: usize) -> bool {
        let curve = self.curve;
        !curve.is_closed()
            && (j == 0 || j == curve.len())
            && self
                .surface
                .net()
                .features()
                .vertex_kind(self.surface.net().topology(), curve.chain[j] as usize)
                == VertexKind::Dart
    }

    /// X(t), X′(t), X″(t) of curve `curve` of the model (see the module
    /// doc). t ∈ [0, n] for n control edges.
    pub fn eval(&self, t: f64) -> Result<CurveEvaluation> {
        let c = self.curve;
        let t = self.parameter(t)?;
        let n = c.len();
        let k = (t.floor() as usize).min(n - 1);
        let s = t - k as f64;
        let j = if s == 0.0 {
            Some(k)
        } else if s == 1.0 {
            Some(k + 1)
        } else {
            None
        };
        let mut e = match j {
            Some(j) if self.is_dart_tip(j) => {
                let x = self.limit_of_vertex(c.chain[j]);
                return Ok(CurveEvaluation {
                    x,
                    dx: DVec3::ZERO,
                    ddx: DVec3::ZERO,
                    at_special_vertex: true,
                });
            }
            Some(j) => {
                let (a, p, b) = (
                    self.chain_point(j as isize - 1),
                    self.chain_point(j as isize),
                    self.chain_point(j as isize + 1),
                );
                CurveEvaluation {
                    x: (a + 4.0 * p + b) / 6.0,
                    dx: (b - a) / 2.0,
                    ddx: a - 2.0 * p + b,
                    at_special_vertex: false,
                }
            }
            None if self.near_dart(k) => self.curve_on_surface(k, s)?,
            None => {
                let basis = bspline_basis(s);
                let pts = [-1isize, 0, 1, 2].map(|d| self.chain_point(k as isize + d));
                let comb = |w: &[f64; 4]| (0..4).map(|i| w[i] * pts[i]).sum::<DVec3>();
                CurveEvaluation {
                    x: comb(&basis[0]),
                    dx: comb(&basis[1]),
                    ddx: comb(&basis[2]),
                    at_special_vertex: false,
                }
            }
        };
        if self.surface.mode() == SurfaceMode::Displacement {
            let (da, db) = (
                self.surface.displacement_of(c.chain[k]),
                self.surface.displacement_of(c.chain[k + 1]),
            );
            e.x += (1.0 - s) * da + s * db;
            e.dx += db - da;
        }
        Ok(e)
    }

    /// Whether segment k's B-spline support holds a dart tip.
    fn near_dart(&self, k: usize) -> bool {
        let n = self.curve.len();
        (k <= 1 && self.is_dart_tip(0)) || (k + 2 >= n && self.is_dart_tip(n))
    }

    /// The approximating surface's limit position of control vertex v.
    fn limit_of_vertex(&self, v: u32) -> DVec3 {
        // The surface at a triangle corner is the vertex's exact limit.
        vertex_point(self.surface.net().topology(), v)
            .and_then(|p| self.surface.eval(p.tri as usize, p.v, p.w).ok())
            .map_or(DVec3::NAN, |e| e.x)
    }

    /// Segment k at s ∈ (0, 1) from the surface on the curve's left (or
    /// only) triangle along control edge k: the directional derivatives
    /// along the edge's direction in (v, w). Without displacement (added
    /// by the caller).
    fn curve_on_surface(&self, k: usize, s: f64) -> Result<CurveEvaluation> {
        let (tri, a, b) = self.edge_in_triangle(k);
        let (pa, pb) = (CORNERS[a], CORNERS[b]);
        let q = pa + s * (pb - pa);
        let d = pb - pa;
        let e = self.surface.eval_approximating(tri, q.x, q.y);
        Ok(CurveEvaluation {
            x: e.x,
            dx: d.x * e.xv + d.y * e.xw,
            ddx: d.x * d.x * e.xvv + 2.0 * d.x * d.y * e.xvw + d.y * d.y * e.xww,
            at_special_vertex: false,
        })
    }

    /// A triangle holding control edge k of the curve and the corners of
    /// chain[k] and chain[k + 1] in it.
    fn edge_in_triangle(&self, k: usize) -> (usize, usize, usize) {
        let c = self.curve;
        let topo = self.surface.net().topology();
        let [t0, t1] = topo.edge_triangles()[c.edges[k] as usize];
        let tri = if t0 != NONE { t0 } else { t1 };
        let corners = topo.triangles()[tri as usize];
        let at = |v: u32| corners.iter().position(|&x| x == v).unwrap_or(0);
        (tri as usize, at(c.chain[k]), at(c.chain[k + 1]))
    }

    /// The surface points of curve parameter t: (face, triangle, v, w) on
    /// each side of the curve (one for a boundary curve; a dart's slit has
    /// its face twice), in the order of [`Curve::faces`].
    pub fn surface_points(&self, t: f64) -> Result<Vec<(u32, SurfacePoint)>> {
        let c = self.curve;
        let t = self.parameter(t)?;
        let k = (t.floor() as usize).min(c.len() - 1);
        let s = t - k as f64;
        let topo = self.surface.net().topology();
        let face_of = self.surface.model().face_of_triangle();
        let mut out = Vec::new();
        for tri in topo.edge_triangles()[c.edges[k] as usize] {
            if tri == NONE {
                continue;
            }
            let corners = topo.triangles()[tri as usize];
            let uv = |v: u32| CORNERS[corners.iter().position(|&x| x == v).unwrap_or(0)];
            let (a, b) = (uv(c.chain[k]), uv(c.chain[k + 1]));
            let q = a + s * (b - a);
            let forward = runs(topo, tri, c.chain[k], c.chain[k + 1]);
            out.push((
                usize::from(!forward),
                face_of[tri as usize],
                SurfacePoint {
                    tri,
                    v: q.x,
                    w: q.y,
                },
            ));
        }
        out.sort_by_key(|x| x.0);
        Ok(out.into_iter().map(|(_, f, p)| (f, p)).collect())
    }
}
