//! Quartic triangular Bézier patches: the form in which the snap search
//! holds a polynomial piece of the surface.
//!
//! Away from special vertices the limit surface is piecewise quartic (box
//! splines), and each piece the search visits lies in one polynomial. In
//! Bernstein–Bézier form its 15 coefficients bound everything the search
//! needs: the piece lies in their convex hull, each derivative in the hull of
//! their differences, and splitting the piece in four is exact (de Casteljau
//! through blossoms). The coefficients are found by interpolating 15 exact
//! surface points, so no stencil is written twice.
//!
//! Local coordinates: barycentric (λ0, λ1, λ2) = (1 − s − t, s, t) on the
//! piece's corners; coefficient (i, j, k), i + j + k = 4, sits at the domain
//! point (i, j, k) / 4.

use glam::DVec3;
use std::sync::OnceLock;

/// Number of coefficients of a triangular Bézier patch of degree `d`.
const fn count(d: usize) -> usize {
    (d + 1) * (d + 2) / 2
}

/// Index of coefficient (d − j − k, j, k) of degree `d`: rows of growing k.
const fn index(d: usize, j: usize, k: usize) -> usize {
    k * (d + 1) - k * (k.saturating_sub(1)) / 2 + j
}

/// The (j, k) of every coefficient of degree `d`, in index order.
fn multi_indices(d: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..=d).flat_map(move |k| (0..=d - k).map(move |j| (j, k)))
}

/// Bernstein polynomials of degree `d` at barycentric `l`, in index order:
/// multinomial × powers, the powers tabled once per call.
fn bernstein<const N: usize>(d: usize, l: [f64; 3]) -> [f64; N] {
    let powers = l.map(|x| {
        let mut p = [1.0; 7];
        for k in 1..=d {
            p[k] = p[k - 1] * x;
        }
        p
    });
    let weights = &tables().multinomials[d];
    let mut out = [0.0; N];
    let mut i = 0;
    for k in 0..=d {
        for j in 0..=d - k {
            out[i] = weights[i] * powers[0][d - j - k] * powers[1][j] * powers[2][k];
            i += 1;
        }
    }
    out
}

/// A quartic patch in Bernstein–Bézier form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Quartic(pub(crate) [DVec3; 15]);

/// The patch's derivative nets with respect to the local (s, t): first
/// derivatives are cubics, second derivatives quadratics.
pub(crate) struct Derivatives {
    pub(crate) s: [DVec3; 10],
    pub(crate) t: [DVec3; 10],
    pub(crate) ss: [DVec3; 6],
    pub(crate) st: [DVec3; 6],
    pub(crate) tt: [DVec3; 6],
}

/// Position and first derivatives at one point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Jet {
    pub(crate) x: DVec3,
    pub(crate) s: DVec3,
    pub(crate) t: DVec3,
}

impl Quartic {
    /// The domain points (i, j, k) / 4 as local (s, t), in index order.
    pub(crate) fn domain_points() -> [(f64, f64); 15] {
        let mut out = [(0.0, 0.0); 15];
        for (j, k) in multi_indices(4) {
            out[index(4, j, k)] = (j as f64 / 4.0, k as f64 / 4.0);
        }
        out
    }

    /// The four children of the piece, numbered as uniform refinement numbers
    /// triangles (and as the snap index numbers cells): child c < 3 at
    /// corner c, child 3 in the middle.
    pub(crate) fn split(&self) -> [Quartic; 4] {
        let tables = tables();
        std::array::from_fn(|c| {
            Quartic(std::array::from_fn(|r| {
                tables.split[c][r]
                    .iter()
                    .zip(&self.0)
                    .map(|(w, x)| *w * *x)
                    .sum()
            }))
        })
    }

    /// Child `c` alone (see [`Quartic::split`]).
    pub(crate) fn child(&self, c: usize) -> Quartic {
        let m = &tables().split[c];
        Quartic(std::array::from_fn(|r| {
            m[r].iter().zip(&self.0).map(|(w, x)| *w * *x).sum()
        }))
    }

    /// The corner points (the surface at the piece's corners).
    pub(crate) fn corners(&self) -> [DVec3; 3] {
        [
            self.0[index(4, 0, 0)],
            self.0[index(4, 4, 0)],
            self.0[index(4, 0, 4)],
        ]
    }

    pub(crate) fn derivatives(&self) -> Derivatives {
        let b = |j: usize, k: usize| self.0[index(4, j, k)];
        let mut d = Derivatives {
            s: [DVec3::ZERO; 10],
            t: [DVec3::ZERO; 10],
            ss: [DVec3::ZERO; 6],
            st: [DVec3::ZERO; 6],
            tt: [DVec3::ZERO; 6],
        };
        for (j, k) in multi_indices(3) {
            let i = index(3, j, k);
            d.s[i] = 4.0 * (b(j + 1, k) - b(j, k));
            d.t[i] = 4.0 * (b(j, k + 1) - b(j, k));
        }
        for (j, k) in multi_indices(2) {
            let i = index(2, j, k);
            d.ss[i] = 12.0 * (b(j + 2, k) - 2.0 * b(j + 1, k) + b(j, k));
            d.st[i] = 12.0 * (b(j + 1, k + 1) - b(j + 1, k) - b(j, k + 1) + b(j, k));
            d.tt[i] = 12.0 * (b(j, k + 2) - 2.0 * b(j, k + 1) + b(j, k));
        }
        d
    }

    /// Position and first derivatives at local (s, t).
    pub(crate) fn jet(&self, d: &Derivatives, s: f64, t: f64) -> Jet {
        let l = [1.0 - s - t, s, t];
        let (b4, b3) = (bernstein::<15>(4, l), bernstein::<10>(3, l));
        let sum = |w: &[f64], x: &[DVec3]| w.iter().zip(x).map(|(w, x)| *w * *x).sum();
        Jet {
            x: sum(&b4, &self.0),
            s: sum(&b3, &d.s),
            t: sum(&b3, &d.t),
        }
    }

    /// The second derivatives Xss, Xst, Xtt at local (s, t).
    pub(crate) fn second(&self, d: &Derivatives, s: f64, t: f64) -> [DVec3; 3] {
        let b2 = bernstein::<6>(2, [1.0 - s - t, s, t]);
        [&d.ss, &d.st, &d.tt].map(|net| b2.iter().zip(net).map(|(w, x)| *w * *x).sum())
    }
}

/// The constant tables: multinomials, and the four subdivision matrices.
struct Tables {
    /// d! / (i! j! k!) per degree d ≤ 6, in index order.
    multinomials: [Vec<f64>; 7],
    split: [[[f64; 15]; 15]; 4],
}

/// The squared distance's Hessian over the piece in Bernstein form of
/// degree 6: its entries Xs·Xs + r·Xss, Xs·Xt + r·Xst, Xt·Xt + r·Xtt
/// (r = X − p) as 28 coefficients each. A product of Bernstein polynomials
/// is Bᵐ_α Bⁿ_β = C(m, α) C(n, β) / C(m + n, α + β) Bᵐ⁺ⁿ_(α+β): the factors'
/// coefficients are scaled by their multinomials, convolved, and the sums
/// divided by the product's.
pub(crate) fn hessian_net(q: &Quartic, d: &Derivatives, p: DVec3) -> [[f64; 3]; SEXTIC] {
    let m = &tables().multinomials;
    let scaled = |net: &[DVec3], deg: usize| -> [DVec3; 15] {
        let mut out = [DVec3::ZERO; 15];
        for (i, x) in net.iter().enumerate() {
            out[i] = *x * m[deg][i];
        }
        out
    };
    let (s, t) = (scaled(&d.s, 3), scaled(&d.t, 3));
    let (ss, st, tt) = (scaled(&d.ss, 2), scaled(&d.st, 2), scaled(&d.tt, 2));
    let mut r = scaled(&q.0, 4);
    for (i, x) in r.iter_mut().enumerate() {
        *x -= p * m[4][i];
    }
    let mut h = [[0.0; 3]; SEXTIC];
    // Coefficient a of a degree-`da` factor times coefficient b of a
    // degree-`db` one lands on coefficient α + β of the product.
    let mut convolve = |da: usize, db: usize, terms: &dyn Fn(usize, usize) -> [f64; 3]| {
        for (ja, ka) in multi_indices(da) {
            for (jb, kb) in multi_indices(db) {
                let e = &mut h[index(6, ja + jb, ka + kb)];
                let add = terms(index(da, ja, ka), index(db, jb, kb));
                for (x, y) in e.iter_mut().zip(add) {
                    *x += y;
                }
            }
        }
    };
    convolve(3, 3, &|a, b| {
        [s[a].dot(s[b]), s[a].dot(t[b]), t[a].dot(t[b])]
    });
    convolve(4, 2, &|a, b| {
        [r[a].dot(ss[b]), r[a].dot(st[b]), r[a].dot(tt[b])]
    });
    for (g, e) in h.iter_mut().enumerate() {
        let w = 1.0 / m[6][g];
        for x in e.iter_mut() {
            *x *= w;
        }
    }
    h
}

pub(crate) const SEXTIC: usize = count(6);

fn tables() -> &'static Tables {
    static TABLES: OnceLock<Tables> = OnceLock::new();
    TABLES.get_or_init(|| {
        let factorial = |n: usize| (1..=n).product::<usize>() as f64;
        let multinomials = std::array::from_fn(|d| {
            multi_indices(d)
                .map(|(j, k)| factorial(d) / (factorial(d - j - k) * factorial(j) * factorial(k)))
                .collect()
        });
        // Child c's coefficient (i, j, k) is the blossom at its corners taken
        // i, j and k times.
        let (c0, c1, c2) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        let mid =
            |a: [f64; 3], b: [f64; 3]| std::array::from_fn::<f64, 3, _>(|i| 0.5 * (a[i] + b[i]));
        let (m0, m1, m2) = (mid(c0, c1), mid(c1, c2), mid(c2, c0));
        let children = [[c0, m0, m2], [m0, c1, m1], [m2, m1, c2], [m1, m2, m0]];
        let split = children.map(|corners| {
            let mut matrix = [[0.0; 15]; 15];
            for (j, k) in multi_indices(4) {
                let i = 4 - j - k;
                let mut args = Vec::with_capacity(4);
                args.extend(std::iter::repeat(corners[0]).take(i));
                args.extend(std::iter::repeat(corners[1]).take(j));
                args.extend(std::iter::repeat(corners[2]).take(k));
                for (col, entry) in matrix[index(4, j, k)].iter_mut().enumerate() {
                    let mut unit = [0.0; 15];
                    unit[col] = 1.0;
                    *entry = blossom(&unit, &args);
                }
            }
            matrix
        });
        Tables {
            multinomials,
            split,
        }
    })
}

/// The blossom of the quartic with scalar coefficients `b` at the four
/// barycentric arguments: de Casteljau with a different point per step.
fn blossom(b: &[f64; 15], args: &[[f64; 3]]) -> f64 {
    let mut net = b.to_vec();
    for (step, l) in args.iter().enumerate() {
        let d = 4 - step;
        let mut next = vec![0.0; count(d - 1)];
        for (j, k) in multi_indices(d - 1) {
            next[index(d - 1, j, k)] = l[0] * net[index(d, j, k)]
                + l[1] * net[index(d, j + 1, k)]
                + l[2] * net[index(d, j, k + 1)];
        }
        net = next;
    }
    net[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quartic with arbitrary monomial coefficients (box-spline order),
    /// and its jet by hand.
    fn poly(s: f64, t: f64) -> [DVec3; 6] {
        let a = DVec3::new(0.3, -1.2, 0.7);
        let b = DVec3::new(-0.4, 0.25, 1.1);
        let c = DVec3::new(0.9, 0.1, -0.6);
        let x = a * (s * s * s * t) + b * (t * t * t * t) + c * (s * s) + DVec3::new(s, t, 1.0);
        let xs = a * (3.0 * s * s * t) + c * (2.0 * s) + DVec3::X;
        let xt = a * (s * s * s) + b * (4.0 * t * t * t) + DVec3::Y;
        let xss = a * (6.0 * s * t) + c * 2.0;
        let xst = a * (3.0 * s * s);
        let xtt = b * (12.0 * t * t);
        [x, xs, xt, xss, xst, xtt]
    }

    fn bezier() -> Quartic {
        let mut m = [DVec3::ZERO; 15];
        m[0] = DVec3::Z;
        m[1] = DVec3::X;
        m[2] = DVec3::Y;
        m[3] = DVec3::new(0.9, 0.1, -0.6); // s²
        m[11] = DVec3::new(0.3, -1.2, 0.7); // s³t
        m[14] = DVec3::new(-0.4, 0.25, 1.1); // t⁴
        Quartic(crate::eval::box_spline::bernstein(&m))
    }

    #[test]
    fn bernstein_form_reproduces_quartics_and_their_derivatives() {
        let q = bezier();
        let d = q.derivatives();
        for (s, t) in [(0.1, 0.2), (0.7, 0.05), (0.0, 1.0), (0.33, 0.33)] {
            let jet = q.jet(&d, s, t);
            let [ss, st, tt] = q.second(&d, s, t);
            let want = poly(s, t);
            let got = [jet.x, jet.s, jet.t, ss, st, tt];
            for (g, w) in got.iter().zip(want) {
                assert!((*g - w).length() < 1e-13, "({s}, {t}): {g} vs {w}");
            }
        }
    }

    /// The Hessian's Bernstein form takes the values of the Hessian
    /// computed from the jet.
    #[test]
    fn hessian_net_is_the_hessian() {
        let q = bezier();
        let d = q.derivatives();
        let p = DVec3::new(0.2, -0.4, 1.7);
        let h = hessian_net(&q, &d, p);
        for (s, t) in [(0.1, 0.2), (0.7, 0.05), (0.0, 1.0), (0.33, 0.33)] {
            let b6 = bernstein::<SEXTIC>(6, [1.0 - s - t, s, t]);
            let got: [f64; 3] =
                std::array::from_fn(|e| b6.iter().zip(&h).map(|(w, x)| w * x[e]).sum());
            let jet = q.jet(&d, s, t);
            let [ss, st, tt] = q.second(&d, s, t);
            let r = jet.x - p;
            let want = [
                jet.s.dot(jet.s) + r.dot(ss),
                jet.s.dot(jet.t) + r.dot(st),
                jet.t.dot(jet.t) + r.dot(tt),
            ];
            for e in 0..3 {
                assert!(
                    (got[e] - want[e]).abs() < 1e-12,
                    "({s}, {t}): {got:?} vs {want:?}"
                );
            }
        }
    }

    #[test]
    fn children_are_the_parent_on_their_triangles() {
        let q = bezier();
        let d = q.derivatives();
        let children = q.split();
        for (c, child) in children.iter().enumerate() {
            assert_eq!(*child, q.child(c));
        }
        // Child corners in the parent's (s, t).
        let (c0, c1, c2) = ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0));
        let mid = |a: (f64, f64), b: (f64, f64)| ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
        let (m0, m1, m2) = (mid(c0, c1), mid(c1, c2), mid(c2, c0));
        let corners = [[c0, m0, m2], [m0, c1, m1], [m2, m1, c2], [m1, m2, m0]];
        for (child, [a, b, c]) in children.iter().zip(corners) {
            let dc = child.derivatives();
            for (s, t) in [(0.2, 0.3), (0.6, 0.1), (1.0, 0.0)] {
                let at = (
                    a.0 + s * (b.0 - a.0) + t * (c.0 - a.0),
                    a.1 + s * (b.1 - a.1) + t * (c.1 - a.1),
                );
                let x = child.jet(&dc, s, t).x;
                assert!((x - q.jet(&d, at.0, at.1).x).length() < 1e-14);
            }
        }
        // The hull property: every coefficient of a child is a convex
        // combination of the parent's, so the children's hulls nest.
        for m in &tables().split {
            for row in m {
                assert!(row.iter().all(|&w| w >= -1e-15));
                assert!((row.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            }
        }
    }
}
