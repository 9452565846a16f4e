//! Certificates for one polynomial piece: proving that the squared distance
//! f(s, t) = ½ |X(s, t) − p|² is convex over the piece, and lower bounds on
//! f there that follow.
//!
//! The Hessian of f is H = JᵀJ + Σ r · X₍₎ (r = X − p), a matrix of
//! polynomials of degree 6 on a quartic piece. In Bernstein form it is a
//! convex combination of 28 constant matrices, so the smallest of their
//! smallest eigenvalues, m, bounds H's from below over the whole piece. If
//! m > 0 then f is strongly convex on the piece, and for any point u of it
//! f ≥ f(u) + ∇f(u) · δ + ½ m |δ|², whose minimum over the piece's triangle
//! is a lower bound of f there. Taken at the centroid it often rules a piece
//! out without a solve; taken at the piece's minimiser it is that minimum to
//! round-off, so the search may close the piece.
//!
//! All of this is in the piece's own local coordinates: convexity does not
//! depend on an affine change of parameters, and next to a special vertex
//! the rings' pieces are regular patches at their own scale, where the
//! control triangle's (v, w) is singular.

use super::bezier::{hessian_net, Derivatives, Jet, Quartic};
use super::cell::closest_in_triangle;
use crate::parameters::CORNERS;
use glam::{DVec2, DVec3};

/// The quadratic model of f on a piece proven strongly convex, with the
/// curvature bound that holds over the whole piece.
pub(crate) struct Convex {
    /// Lower bound on the smallest eigenvalue of f's Hessian over the piece.
    m: f64,
}

/// Proves f convex over the piece `q` for the query `p`, or says it cannot.
///
/// The Hessian's entries Xs·Xs + r·Xss, Xs·Xt + r·Xst, Xt·Xt + r·Xtt are
/// polynomials of degree 6; written in Bernstein form (products of the
/// derivative nets, r = X − p having the coefficients b − p) the Hessian is
/// a convex combination of 28 symmetric matrices over the piece, and the
/// smallest eigenvalue, a concave function, is at least the smallest of
/// theirs.
pub(crate) fn convexity(q: &Quartic, d: &Derivatives, p: DVec3) -> Option<Convex> {
    let h = hessian_net(q, d, p);
    let (mut m, mut scale) = (f64::INFINITY, 0.0f64);
    for [a, b, c] in h {
        m = m.min(0.5 * (a + c) - (0.25 * (a - c) * (a - c) + b * b).sqrt());
        scale = scale.max(a.abs() + b.abs() + c.abs());
    }
    // A margin for the round-off in the sums above.
    (m > 1e-10 * scale).then_some(Convex { m })
}

impl Convex {
    /// A lower bound on f over the piece from the jet at local `u`: the
    /// minimum over the piece's triangle of f(u) + ∇f(u)·δ + ½ m |δ|².
    pub(crate) fn lower_bound(&self, jet: &Jet, u: DVec2, p: DVec3) -> f64 {
        let r = jet.x - p;
        let f = 0.5 * r.length_squared();
        let g = DVec2::new(r.dot(jet.s), r.dot(jet.t));
        // f + g·δ + ½m|δ|² = const + ½m |u + δ − centre|²: smallest at the
        // point of the triangle nearest to the centre (evaluated there, not
        // through the constant, which would cancel).
        let centre = u - g / self.m;
        let [c0, c1, c2] = CORNERS;
        let delta = closest_in_triangle(centre, c0, c1, c2) - u;
        f + g.dot(delta) + 0.5 * self.m * delta.length_squared()
    }

    /// The best lower bound on f over the piece this proof gives: at the
    /// piece's minimiser it is that minimum to round-off. Sequential
    /// quadratic steps from the centroid, each the exact minimum over the
    /// triangle of f's second-order model (its Hessian is positive definite
    /// all over the piece); the bound at each iterate is valid, so the walk
    /// stops as soon as one reaches `enough`. Returns the bound and where
    /// it was taken (local (s, t)).
    pub(crate) fn bound(
        &self,
        q: &Quartic,
        d: &Derivatives,
        p: DVec3,
        enough: f64,
    ) -> (f64, DVec2) {
        let mut u = DVec2::splat(1.0 / 3.0);
        let (mut best, mut at) = (f64::NEG_INFINITY, u);
        for _ in 0..8 {
            let jet = q.jet(d, u.x, u.y);
            let bound = self.lower_bound(&jet, u, p);
            if bound > best {
                (best, at) = (bound, u);
            }
            if best >= enough {
                break;
            }
            let r = jet.x - p;
            let g = DVec2::new(r.dot(jet.s), r.dot(jet.t));
            let [ss, st, tt] = q.second(d, u.x, u.y);
            let h = (
                jet.s.dot(jet.s) + r.dot(ss),
                jet.s.dot(jet.t) + r.dot(st),
                jet.t.dot(jet.t) + r.dot(tt),
            );
            let next = quadratic_minimum(u, g, h).unwrap_or(u);
            let step = (next - u).length();
            u = next;
            if step.is_nan() || step <= 1e-12 {
                break;
            }
        }
        (best, at)
    }
}

/// The minimum over the unit triangle of g·δ + ½ δᵀHδ around `u` (H =
/// [[a b] [b c]] positive definite): the Newton point if it lies inside,
/// else the best of the sides' one-dimensional minima.
fn quadratic_minimum(u: DVec2, g: DVec2, (a, b, c): (f64, f64, f64)) -> Option<DVec2> {
    let det = a * c - b * b;
    if det.is_nan() || det <= 0.0 {
        return None;
    }
    let newton = u - DVec2::new(c * g.x - b * g.y, a * g.y - b * g.x) / det;
    if newton.x >= 0.0 && newton.y >= 0.0 && newton.x + newton.y <= 1.0 {
        return Some(newton);
    }
    let model = |x: DVec2| {
        let e = x - u;
        g.dot(e) + 0.5 * (a * e.x * e.x + 2.0 * b * e.x * e.y + c * e.y * e.y)
    };
    (0..3)
        .map(|k| (CORNERS[k], CORNERS[(k + 1) % 3]))
        .map(|(from, to)| {
            // Along from + τ (to − from), τ in [0, 1].
            let e = to - from;
            let slope = g.dot(e)
                + (a * (from.x - u.x) * e.x
                    + b * ((from.x - u.x) * e.y + (from.y - u.y) * e.x)
                    + c * (from.y - u.y) * e.y);
            let curvature = a * e.x * e.x + 2.0 * b * e.x * e.y + c * e.y * e.y;
            let tau = if curvature > 0.0 {
                (-slope / curvature).clamp(0.0, 1.0)
            } else {
                0.0
            };
            from + tau * e
        })
        .min_by(|x, y| model(*x).total_cmp(&model(*y)))
}
