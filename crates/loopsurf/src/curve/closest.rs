//! Points of a limit curve nearest to a query point: local projection by
//! Newton from a guess, and the certified closest point by branch and
//! bound over the curve's Bézier pieces.

use super::LimitCurve;
use crate::error::{Error, Result};
use crate::snap::DEFAULT_TOLERANCE;
use crate::surface::SurfaceMode;
use glam::DVec3;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

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

impl<'s> LimitCurve<'s> {
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
