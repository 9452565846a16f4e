//! Exact evaluation of the model's curves (the limit crease and boundary
//! curves), their arc length, and projection onto them.
//!
//! A curve's parameter t runs over its chain, one unit per control edge
//! (DESIGN.md). The crease rules (edge ½ ½, vertex ⅛ ¾ ⅛) are those of the
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

use crate::error::{Error, Result};
use crate::features::VertexKind;
use crate::model::{runs, Curve};
use crate::parameters::{vertex_point, SurfacePoint, CORNERS};
use crate::snap::DEFAULT_TOLERANCE;
use crate::surface::{Derived, Surface, SurfaceMode, PARAMETER_TOLERANCE};
use crate::topology::NONE;
use glam::DVec3;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
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

    /// Its number in the model.
    pub fn index(&self) -> usize {
        self.index
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
}

/// A point of a curve nearest to a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveSnap {
    /// Its curve parameter.
    pub t: f64,
    /// X(t).
    pub point: DVec3,
    /// |X(t) − p|.
    pub distance: f64,
    /// A proven lower bound on the distance from p to the whole curve (0
    /// for a local projection, which proves nothing).
    pub lower_bound: f64,
}

/// 10-point Gauss–Legendre nodes and weights on [−1, 1] (positive half).
const GAUSS: [(f64, f64); 5] = [
    (0.148_874_338_981_631_22, 0.295_524_224_714_752_87),
    (0.433_395_394_129_247_2, 0.269_266_719_309_996_35),
    (0.679_409_568_299_024_4, 0.219_086_362_515_982_04),
    (0.865_063_366_688_984_5, 0.149_451_349_150_580_6),
    (0.973_906_528_517_171_7, 0.066_671_344_308_688_14),
];

impl<'s> LimitCurve<'s> {
    /// The arc length of curve `curve` between parameters t0 and t1
    /// (negative when t1 < t0), by adaptive Gauss–Legendre quadrature of
    /// |X′| to 1e-13 relative per unit segment.
    pub fn length(&self, t0: f64, t1: f64) -> Result<f64> {
        let c = self.curve;
        let (a, b) = (self.parameter(t0)?, self.parameter(t1)?);
        let (lo, hi, sign) = if a <= b { (a, b, 1.0) } else { (b, a, -1.0) };
        let n = c.len() as f64;
        let tip =
            |t: f64| (t == 0.0 && self.is_dart_tip(0)) || (t == n && self.is_dart_tip(c.len()));
        let mut total = 0.0;
        let mut k = lo.floor();
        while k < hi {
            let (x, y) = (lo.max(k), hi.min(k + 1.0));
            if y > x {
                total += if tip(x) {
                    self.length_to_tip(x, y)?
                } else if tip(y) {
                    self.length_to_tip(y, x)?
                } else {
                    self.segment_length(x, y, self.length_floor(), 0)?
                };
            }
            k += 1.0;
        }
        Ok(sign * total)
    }

    /// The length from a dart tip to `other` in the same segment. |X′|
    /// behaves like a power of the distance to the tip there, which
    /// adaptive quadrature would chase for forty halvings: instead the
    /// interval is cut into halves towards the tip, each smooth on its own
    /// scale, until the rest (bounded by its chord's multiple, taken as its
    /// chord) is below round-off of the sum.
    fn length_to_tip(&self, tip: f64, other: f64) -> Result<f64> {
        let x_tip = self.eval(tip)?.x;
        let mut total = 0.0;
        let mut far = other;
        for _ in 0..200 {
            let near = tip + 0.5 * (far - tip);
            let (a, b) = if near < far { (near, far) } else { (far, near) };
            // Each piece only needs to be good relative to the sum so far.
            let floor = self.length_floor().max(1e-15 * total);
            total += self.segment_length(a, b, floor, 0)?;
            far = near;
            let rest = (self.eval(far)?.x - x_tip).length();
            if rest <= 1e-14 * total {
                return Ok(total + rest);
            }
        }
        Ok(total)
    }

    /// ∫ |X′| over [a, b] inside one unit segment, halving until the halves
    /// agree with the whole to 1e-13 relative or to `floor` absolute (the
    /// round-off of positions, below which pieces near a dart tip never
    /// agree better).
    fn segment_length(&self, a: f64, b: f64, floor: f64, depth: u32) -> Result<f64> {
        let whole = self.gauss(a, b)?;
        let m = 0.5 * (a + b);
        let halves = self.gauss(a, m)? + self.gauss(m, b)?;
        if (whole - halves).abs() <= (1e-13 * halves.abs()).max(floor) || depth >= 40 {
            return Ok(halves);
        }
        Ok(self.segment_length(a, m, 0.5 * floor, depth + 1)?
            + self.segment_length(m, b, 0.5 * floor, depth + 1)?)
    }

    /// The absolute round-off of lengths on this surface.
    fn length_floor(&self) -> f64 {
        1e-15 * self.surface.net().bbox_diagonal()
    }

    fn gauss(&self, a: f64, b: f64) -> Result<f64> {
        let (h, m) = (0.5 * (b - a), 0.5 * (a + b));
        let mut sum = 0.0;
        for (x, w) in GAUSS {
            sum += w * self.eval(m - h * x)?.dx.length();
            sum += w * self.eval(m + h * x)?.dx.length();
        }
        Ok(h * sum)
    }

    /// The parameter t at arc length `s` from t = 0 along curve `curve`
    /// (0 ≤ s ≤ its length), so a mesher can place equally spaced points:
    /// the segment by cumulative lengths, then Newton on the length inside
    /// it, safeguarded by bisection.
    pub fn param_at_length(&self, s: f64) -> Result<f64> {
        let n = self.curve.len();
        let table = self.segment_lengths()?;
        let mut cumulative = 0.0;
        for k in 0..n {
            let seg = table[k];
            if s <= cumulative + seg || k + 1 == n {
                let target = s - cumulative;
                if !(target >= -1e-12 * seg && target <= seg * (1.0 + 1e-12)) || !s.is_finite() {
                    return Err(Error::InvalidArgument(format!(
                        "arc length {s}: outside [0, {}] of curve {}",
                        cumulative + seg,
                        self.index
                    )));
                }
                let (mut lo, mut hi) = (k as f64, k as f64 + 1.0);
                let mut t = lo + target / seg.max(f64::MIN_POSITIVE);
                for _ in 0..60 {
                    let f = self.length(k as f64, t)? - target;
                    if f.abs() <= 1e-14 * seg.max(f64::MIN_POSITIVE) {
                        break;
                    }
                    if f > 0.0 {
                        hi = t;
                    } else {
                        lo = t;
                    }
                    let speed = self.eval(t)?.dx.length();
                    let newton = t - f / speed;
                    t = if speed > 0.0 && newton > lo && newton < hi {
                        newton
                    } else {
                        0.5 * (lo + hi)
                    };
                }
                return Ok(t.clamp(k as f64, k as f64 + 1.0));
            }
            cumulative += seg;
        }
        unreachable!("a curve has at least one control edge")
    }

    /// The length of every unit segment, computed on first use and kept
    /// with the surface ([`CurveLengths`]).
    fn segment_lengths(&self) -> Result<&'s [f64]> {
        if let Some(table) = self.lengths.get() {
            return Ok(table);
        }
        let table = (0..self.curve.len())
            .map(|k| self.length(k as f64, k as f64 + 1.0))
            .collect::<Result<Vec<f64>>>()?;
        Ok(self.lengths.get_or_init(|| table))
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

    /// Local projection of p onto curve `curve` from the guess t: Newton on
    /// (X − p)·X′ = 0 with step halving on the distance, across segments
    /// (around a closed loop too). Fast, and proves nothing
    /// (`lower_bound` = 0).
    pub fn project(&self, p: DVec3, t: f64) -> Result<CurveSnap> {
        if !p.is_finite() {
            return Err(Error::InvalidArgument(format!(
                "point {:?} is not finite",
                p.to_array()
            )));
        }
        let t = self.parameter(t)?;
        let (t, point) = self.descend(p, t)?;
        Ok(CurveSnap {
            t,
            point,
            distance: (point - p).length(),
            lower_bound: 0.0,
        })
    }

    /// Newton descent of |X(t) − p|² from t, returning the local minimiser.
    fn descend(&self, p: DVec3, mut t: f64) -> Result<(f64, DVec3)> {
        let c = self.curve;
        let n = c.len() as f64;
        let wrap = |t: f64| {
            if c.is_closed() {
                t.rem_euclid(n)
            } else {
                t.clamp(0.0, n)
            }
        };
        let mut e = self.eval(t)?;
        let mut f = (e.x - p).length_squared();
        for _ in 0..100 {
            let g = (e.x - p).dot(e.dx);
            let h = e.dx.length_squared() + (e.x - p).dot(e.ddx);
            let mut step = if h > 0.0 { -g / h } else { -g.signum() * 0.25 };
            if !step.is_finite() || e.at_special_vertex {
                step = if e.at_special_vertex {
                    1e-3 * if t > 0.5 * n { -1.0 } else { 1.0 }
                } else {
                    0.0
                };
            }
            step = step.clamp(-1.0, 1.0);
            let mut moved = false;
            for _ in 0..40 {
                let t1 = wrap(t + step);
                let e1 = self.eval(t1)?;
                let f1 = (e1.x - p).length_squared();
                if f1 < f {
                    t = t1;
                    e = e1;
                    f = f1;
                    moved = true;
                    break;
                }
                step *= 0.5;
            }
            if !moved || step.abs() <= 1e-15 * n.max(1.0) {
                break;
            }
        }
        Ok((t, e.x))
    }

    /// The point of the curve nearest to p, global and proven within
    /// [`DEFAULT_TOLERANCE`] × the diagonal (see
    /// [`LimitCurve::closest_point_within`]).
    pub fn closest_point(&self, p: DVec3) -> Result<CurveSnap> {
        self.closest_point_within(p, DEFAULT_TOLERANCE)
    }

    /// The global nearest point of curve `curve` to p with a certificate:
    /// branch and bound over the curve's pieces. A B-spline segment is a
    /// cubic Bézier curve inside the hull (here the box) of its four
    /// control points, split by de Casteljau until the box's distance
    /// closes it against the best point found (local Newton from each
    /// piece). A segment next to a dart tip is not polynomial: it is
    /// bounded by the box of the control points its limit is a convex
    /// combination of (the rings of its two end vertices), sampled and
    /// solved for, and not split; its bound is the weaker one then.
    pub fn closest_point_within(&self, p: DVec3, tolerance: f64) -> Result<CurveSnap> {
        if !p.is_finite() {
            return Err(Error::InvalidArgument(format!(
                "point {:?} is not finite",
                p.to_array()
            )));
        }
        if !(tolerance > 0.0 && tolerance.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "tolerance {tolerance}: must be positive"
            )));
        }
        let tol = 0.99 * tolerance * self.surface.net().bbox_diagonal();
        let mut best = CurveSnap {
            t: 0.0,
            point: DVec3::NAN,
            distance: f64::INFINITY,
            lower_bound: 0.0,
        };
        let mut pieces = self.pieces(p);
        let mut closed_bound = f64::INFINITY;
        let mut splits = 0;
        while let Some((bound, (k, s0, s1, b))) = pieces.pop() {
            if bound >= best.distance - tol {
                // The nearest remaining piece closes, and all after it.
                closed_bound = closed_bound.min(bound);
                break;
            }
            let Some(b) = b else {
                // Sampled, then solved from the nearest sample only.
                self.consider(p, self.nearest_sample(k, p)?, &mut best)?;
                closed_bound = closed_bound.min(bound);
                continue;
            };
            if splits >= 20_000 || s1 - s0 < 1e-15 {
                closed_bound = closed_bound.min(bound);
                continue;
            }
            // Where |B − p|² is proven convex over the piece its minimum is
            // the piece's bound, found by golden section.
            if let Some((s, d)) = convex_minimum(&b, p) {
                let t = k as f64 + s0 + s * (s1 - s0);
                let x = self.eval(t)?.x;
                if (x - p).length() < best.distance {
                    best = CurveSnap {
                        t,
                        point: x,
                        distance: (x - p).length(),
                        lower_bound: 0.0,
                    };
                }
                closed_bound = closed_bound
                    .min(d - 1e-14 * (self.surface.net().bbox_diagonal() + p.abs().max_element()));
                continue;
            }
            splits += 1;
            self.consider(p, k as f64 + 0.5 * (s0 + s1), &mut best)?;
            let (l, r) = split_bezier(&b);
            let m = 0.5 * (s0 + s1);
            pieces.push(box_distance(p, &l), (k, s0, m, Some(l)));
            pieces.push(box_distance(p, &r), (k, m, s1, Some(r)));
        }
        best.lower_bound = closed_bound.min(best.distance);
        Ok(best)
    }

    /// Every segment as a piece to search for the point nearest p: a
    /// polynomial one with its Bézier points, one next to a dart tip
    /// bounded by its control hull.
    fn pieces(&self, p: DVec3) -> Pieces {
        let mut pieces = Pieces::default();
        for k in 0..self.curve.len() {
            if self.near_dart(k) {
                let bound = box_distance(p, &self.segment_support(k));
                pieces.push(bound, (k, 0.0, 1.0, None));
            } else {
                let b = self.bezier_of_segment(k);
                pieces.push(box_distance(p, &b), (k, 0.0, 1.0, Some(b)));
            }
        }
        pieces
    }

    /// The parameter of segment k's sample nearest p, of 17 evenly spaced
    /// (the first of equals).
    fn nearest_sample(&self, k: usize, p: DVec3) -> Result<f64> {
        let mut nearest = (f64::INFINITY, k as f64);
        for j in 0..=16 {
            let t = k as f64 + j as f64 / 16.0;
            let d = (self.eval(t)?.x - p).length();
            if d < nearest.0 {
                nearest = (d, t);
            }
        }
        Ok(nearest.1)
    }

    /// Local Newton towards p from parameter t; its end replaces `best`
    /// if nearer.
    fn consider(&self, p: DVec3, t: f64, best: &mut CurveSnap) -> Result<()> {
        let (t, x) = self.descend(p, t)?;
        let d = (x - p).length();
        if d < best.distance {
            *best = CurveSnap {
                t,
                point: x,
                distance: d,
                lower_bound: 0.0,
            };
        }
        Ok(())
    }

    /// The cubic Bézier points of B-spline segment k (displacement added).
    fn bezier_of_segment(&self, k: usize) -> [DVec3; 4] {
        let c = self.curve;
        let [p0, p1, p2, p3] = [-1isize, 0, 1, 2].map(|d| self.chain_point(k as isize + d));
        let mut b = [
            (p0 + 4.0 * p1 + p2) / 6.0,
            (2.0 * p1 + p2) / 3.0,
            (p1 + 2.0 * p2) / 3.0,
            (p1 + 4.0 * p2 + p3) / 6.0,
        ];
        if self.surface.mode() == SurfaceMode::Displacement {
            let (da, db) = (
                self.surface.displacement_of(c.chain[k]),
                self.surface.displacement_of(c.chain[k + 1]),
            );
            for (i, x) in b.iter_mut().enumerate() {
                let s = i as f64 / 3.0;
                *x += (1.0 - s) * da + s * db;
            }
        }
        b
    }

    /// Control points whose convex hull holds segment k's limit: the two
    /// rings around its end vertices (a superset of the 1-rings of both
    /// adjacent triangles' corners; every Loop mask is a convex
    /// combination), shifted by the end displacements in displacement mode.
    fn segment_support(&self, k: usize) -> Vec<DVec3> {
        let c = self.curve;
        let topo = self.surface.net().topology();
        let pts = self.surface.net().points();
        let mut out = Vec::new();
        for v in [c.chain[k], c.chain[k + 1]] {
            out.push(pts[v as usize]);
            for &u in topo.ring(v as usize) {
                out.extend(topo.ring(u as usize).iter().map(|&w| pts[w as usize]));
            }
        }
        if self.surface.mode() == SurfaceMode::Displacement {
            let (da, db) = (
                self.surface.displacement_of(c.chain[k]),
                self.surface.displacement_of(c.chain[k + 1]),
            );
            out = out.iter().flat_map(|&x| [x + da, x + db]).collect();
        }
        out
    }
}

/// A piece of a curve to search: segment k over [s0, s1], with its cubic
/// Bézier points, or a whole dart segment (`None`: bounded by its control
/// hull, sampled when it can matter).
type Piece = (usize, f64, f64, Option<[DVec3; 4]>);

/// The pieces still to search, nearest lower bound first. Distances are
/// non-negative, so their bits order like them.
#[derive(Default)]
struct Pieces {
    heap: BinaryHeap<Reverse<(u64, usize)>>,
    pieces: Vec<Piece>,
}

impl Pieces {
    fn push(&mut self, bound: f64, piece: Piece) {
        self.pieces.push(piece);
        self.heap
            .push(Reverse((bound.to_bits(), self.pieces.len() - 1)));
    }

    /// The piece of least bound, with its bound.
    fn pop(&mut self) -> Option<(f64, Piece)> {
        let Reverse((bits, i)) = self.heap.pop()?;
        Some((f64::from_bits(bits), self.pieces[i]))
    }
}

/// Distance from p to the axis-aligned box of `points`.
fn box_distance(p: DVec3, points: &[DVec3]) -> f64 {
    let lo = points.iter().fold(DVec3::INFINITY, |a, &x| a.min(x));
    let hi = points.iter().fold(DVec3::NEG_INFINITY, |a, &x| a.max(x));
    (lo - p).max(p - hi).max(DVec3::ZERO).length()
}

/// Where |B − p|² is convex over s ∈ [0, 1] — proven by the Bernstein
/// coefficients of its second derivative (a degree-6 polynomial's, all
/// non-negative) — its minimiser s and a lower bound on |B − p| over the
/// piece; None otherwise.
fn convex_minimum(b: &[DVec3; 4], p: DVec3) -> Option<(f64, f64)> {
    let q = b.map(|x| x - p);
    // |B − p|² in Bernstein form of degree 6: c_k = Σ_{i+j=k} C(3,i) C(3,j)
    // q_i·q_j / C(6,k).
    const C3: [f64; 4] = [1.0, 3.0, 3.0, 1.0];
    const C6: [f64; 7] = [1.0, 6.0, 15.0, 20.0, 15.0, 6.0, 1.0];
    let mut c = [0.0; 7];
    for i in 0..4 {
        for j in 0..4 {
            c[i + j] += C3[i] * C3[j] * q[i].dot(q[j]);
        }
    }
    for k in 0..7 {
        c[k] /= C6[k];
    }
    let convex = (0..5).all(|k| c[k + 2] - 2.0 * c[k + 1] + c[k] >= 0.0);
    if !convex {
        return None;
    }
    // The minimiser: the root of g = (B − p)·B′ (increasing, as f = |B − p|²
    // is convex), by Newton safeguarded by bisection, all in geometric
    // terms (no cancellation in f itself).
    let at = |s: f64| {
        let r = 1.0 - s;
        let x =
            r * r * r * b[0] + 3.0 * r * r * s * b[1] + 3.0 * r * s * s * b[2] + s * s * s * b[3];
        let d1 =
            3.0 * (r * r * (b[1] - b[0]) + 2.0 * r * s * (b[2] - b[1]) + s * s * (b[3] - b[2]));
        let d2 = 6.0 * (r * (b[2] - 2.0 * b[1] + b[0]) + s * (b[3] - 2.0 * b[2] + b[1]));
        (x - p, d1, d2)
    };
    let g = |s: f64| {
        let (x, d1, _) = at(s);
        x.dot(d1)
    };
    let s = if g(0.0) >= 0.0 {
        0.0
    } else if g(1.0) <= 0.0 {
        1.0
    } else {
        let (mut lo, mut hi, mut s) = (0.0f64, 1.0f64, 0.5f64);
        for _ in 0..100 {
            let (x, d1, d2) = at(s);
            let gs = x.dot(d1);
            if gs < 0.0 {
                lo = s;
            } else {
                hi = s;
            }
            let slope = d1.length_squared() + x.dot(d2);
            let newton = s - gs / slope;
            let next = if slope > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if (next - s).abs() <= 1e-17 || hi - lo <= 1e-17 {
                s = next;
                break;
            }
            s = next;
        }
        s
    };
    // f is convex: above its tangent at s, whose lowest point on [0, 1]
    // is at the end the slope falls towards (f′ = 2g).
    let (x, d1, _) = at(s);
    let slope = 2.0 * x.dot(d1);
    let lower = x.length_squared()
        - if slope >= 0.0 {
            slope * s
        } else {
            -slope * (1.0 - s)
        };
    Some((s, lower.max(0.0).sqrt()))
}

/// De Casteljau at ½.
fn split_bezier(b: &[DVec3; 4]) -> ([DVec3; 4], [DVec3; 4]) {
    let m = |a: DVec3, b: DVec3| 0.5 * (a + b);
    let (a1, b1, c1) = (m(b[0], b[1]), m(b[1], b[2]), m(b[2], b[3]));
    let (a2, b2) = (m(a1, b1), m(b1, c1));
    let mid = m(a2, b2);
    ([b[0], a1, a2, mid], [mid, b2, c1, b[3]])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn convex_minimum_of_a_straight_segment() {
        let b = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0].map(|x| DVec3::new(x, 0.0, 0.0));
        for (p, s_expected, d) in [
            (DVec3::new(0.25, 1.0, 0.0), 0.25, 1.0),
            (DVec3::new(-1.0, 0.0, 0.0), 0.0, 1.0),
            (DVec3::new(3.0, 4.0, 0.0), 1.0, 2f64.hypot(4.0)),
        ] {
            let (s, lower) = convex_minimum(&b, p).unwrap();
            assert!((s - s_expected).abs() < 1e-15, "{p}: {s}");
            assert!(lower <= d && lower > d - 1e-12, "{p}: {lower} vs {d}");
        }
    }
}
