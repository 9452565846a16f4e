//! The quartic box spline of a regular Loop patch (Persson, Aftosmis & Haines, eqs. 5–8):
//! twelve basis functions of (v, w) and their first and second derivatives.
//!
//! The control points are numbered as in their Fig. 6: the corners
//! c0 c1 c2 (at (v, w) = (0,0), (1,0), (0,1)), then the outer ring
//! counter-clockwise: x4 across c1–c2, x5 x6 around c2, x7 across c2–c0,
//! x8 x9 around c0, x10 across c0–c1, x11 x12 around c1.

use glam::DVec3;

/// Persson, Aftosmis & Haines's eq. (6), times 12: row i holds the coefficients of control point
/// i on the monomials of eq. (5).
#[rustfmt::skip]
const PHI: [[f64; 15]; 12] = [
    [6., 0., 0., -12., -12., -12., 8., 12., 12., 8., -1., -2., 0., -2., -1.],
    [1., 4., 2., 6., 6., 0., -4., -6., -12., -4., -1., -2., 0., 4., 2.],
    [1., 2., 4., 0., 6., 6., -4., -12., -6., -4., 2., 4., 0., -2., -1.],
    [0., 0., 0., 0., 0., 0., 2., 6., 6., 2., -1., -2., 0., -2., -1.],
    [0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 2., 1.],
    [0., 0., 0., 0., 0., 0., 0., 0., 0., 2., 0., 0., 0., -2., -1.],
    [1., -2., 2., 0., -6., 0., 2., 6., 0., -4., -1., -2., 0., 4., 2.],
    [1., -4., -2., 6., 6., 0., -4., -6., 0., 2., 1., 2., 0., -2., -1.],
    [1., -2., -4., 0., 6., 6., 2., 0., -6., -4., -1., -2., 0., 2., 1.],
    [1., 2., -2., 0., -6., 0., -4., 0., 6., 2., 2., 4., 0., -2., -1.],
    [0., 0., 0., 0., 0., 0., 2., 0., 0., 0., -1., -2., 0., 0., 0.],
    [0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 1., 2., 0., 0., 0.],
];

/// X, Xv, Xw, Xvv, Xvw, Xww at (v, w) of the patch with these control
/// points, straight from eqs. (5)–(8): the reference the fast paths are
/// tested against.
#[cfg(test)]
pub fn eval(control: &[DVec3; 12], v: f64, w: f64) -> [DVec3; 6] {
    weights(v, w).map(|row| control.iter().zip(&row).map(|(p, w)| *w * *p).sum())
}

/// The patch as a polynomial: its coefficients on the monomials of eq. (5).
/// Worth storing for patches evaluated many times.
pub fn coefficients(control: &[DVec3; 12]) -> [DVec3; 15] {
    std::array::from_fn(|j| {
        control
            .iter()
            .zip(&PHI)
            .map(|(x, row)| row[j] / 12.0 * *x)
            .sum()
    })
}

/// [`coefficients`] for control points that are themselves linear
/// combinations of `n` points: 12 rows of n weights in, 15 rows out.
pub fn coefficient_rows(control_rows: &[f64], n: usize) -> Vec<f64> {
    let mut out = vec![0.0; 15 * n];
    for (r, row) in PHI.iter().enumerate() {
        for (j, &phi) in row.iter().enumerate() {
            if phi != 0.0 {
                for col in 0..n {
                    out[j * n + col] += phi / 12.0 * control_rows[r * n + col];
                }
            }
        }
    }
    out
}

/// Exponents (of v, of w) of the monomials of eq. (5), in coefficient order.
const EXPONENTS: [(usize, usize); 15] = [
    (0, 0),
    (1, 0),
    (0, 1),
    (2, 0),
    (1, 1),
    (0, 2),
    (3, 0),
    (2, 1),
    (1, 2),
    (0, 3),
    (4, 0),
    (3, 1),
    (2, 2),
    (1, 3),
    (0, 4),
];

/// Monomial coefficients to Bernstein–Bézier coefficients on the patch's
/// own triangle (v, w ≥ 0, v + w ≤ 1): vᵃwᵇ = λ1ᵃ λ2ᵇ (λ0 + λ1 + λ2)⁴⁻ᵃ⁻ᵇ,
/// so its coefficient on λ0ⁱλ1ʲλ2ᵏ is a ratio of multinomials. Rows follow
/// the snap search's Bézier order: coefficient (i, j, k) (powers of
/// 1 − v − w, v, w) at index 5k − k(k − 1)/2 + j.
fn to_bernstein() -> &'static [[f64; 15]; 15] {
    static MATRIX: std::sync::OnceLock<[[f64; 15]; 15]> = std::sync::OnceLock::new();
    MATRIX.get_or_init(|| {
        let f = |n: usize| (1..=n).product::<usize>() as f64;
        let multinomial = |i: usize, j: usize, k: usize| f(i + j + k) / (f(i) * f(j) * f(k));
        let mut m = [[0.0; 15]; 15];
        let mut row = 0;
        for k in 0..=4 {
            for j in 0..=4 - k {
                let i = 4 - j - k;
                for (col, &(a, b)) in EXPONENTS.iter().enumerate() {
                    if j >= a && k >= b {
                        m[row][col] = multinomial(i, j - a, k - b) / multinomial(i, j, k);
                    }
                }
                row += 1;
            }
        }
        m
    })
}

/// The patch given by [`coefficients`] in Bernstein–Bézier form on its own
/// triangle (see [`to_bernstein`] for the order).
pub fn bernstein(c: &[DVec3; 15]) -> [DVec3; 15] {
    let m = to_bernstein();
    std::array::from_fn(|r| m[r].iter().zip(c).map(|(w, x)| *w * *x).sum())
}

/// [`bernstein`] for coefficients that are linear combinations of `n`
/// points: 15 rows of n weights in, 15 rows out.
pub fn bernstein_rows(rows: &[f64], n: usize) -> Vec<f64> {
    let m = to_bernstein();
    let mut out = vec![0.0; 15 * n];
    for (r, weights) in m.iter().enumerate() {
        for (j, &w) in weights.iter().enumerate() {
            if w != 0.0 {
                for col in 0..n {
                    out[r * n + col] += w * rows[j * n + col];
                }
            }
        }
    }
    out
}

/// X alone at (v, w) of a patch given by [`coefficients`]: a sixth of the
/// work of [`eval_coefficients`], for callers that only place points.
pub fn eval_point(c: &[DVec3; 15], v: f64, w: f64) -> DVec3 {
    let (v2, vw, w2) = (v * v, v * w, w * w);
    let (v3, v2w, vw2, w3) = (v2 * v, v2 * w, v * w2, w2 * w);
    c[0] + c[1] * v
        + c[2] * w
        + c[3] * v2
        + c[4] * vw
        + c[5] * w2
        + c[6] * v3
        + c[7] * v2w
        + c[8] * vw2
        + c[9] * w3
        + c[10] * (v2 * v2)
        + c[11] * (v3 * w)
        + c[12] * (v2 * w2)
        + c[13] * (v * w3)
        + c[14] * (w2 * w2)
}

/// X, Xv, Xw, Xvv, Xvw, Xww at (v, w) of a patch given by [`coefficients`].
/// Written out term by term: the derivatives of the monomials are mostly
/// zero, and skipping them is most of the cost of an evaluation.
pub fn eval_coefficients(c: &[DVec3; 15], v: f64, w: f64) -> [DVec3; 6] {
    let (v2, vw, w2) = (v * v, v * w, w * w);
    let (v3, v2w, vw2, w3) = (v2 * v, v2 * w, v * w2, w2 * w);
    [
        eval_point(c, v, w),
        c[1] + c[3] * (2.0 * v)
            + c[4] * w
            + c[6] * (3.0 * v2)
            + c[7] * (2.0 * vw)
            + c[8] * w2
            + c[10] * (4.0 * v3)
            + c[11] * (3.0 * v2w)
            + c[12] * (2.0 * vw2)
            + c[13] * w3,
        c[2] + c[4] * v
            + c[5] * (2.0 * w)
            + c[7] * v2
            + c[8] * (2.0 * vw)
            + c[9] * (3.0 * w2)
            + c[11] * v3
            + c[12] * (2.0 * v2w)
            + c[13] * (3.0 * vw2)
            + c[14] * (4.0 * w3),
        c[3] * 2.0
            + c[6] * (6.0 * v)
            + c[7] * (2.0 * w)
            + c[10] * (12.0 * v2)
            + c[11] * (6.0 * vw)
            + c[12] * (2.0 * w2),
        c[4] + c[7] * (2.0 * v)
            + c[8] * (2.0 * w)
            + c[11] * (3.0 * v2)
            + c[12] * (4.0 * vw)
            + c[13] * (3.0 * w2),
        c[5] * 2.0
            + c[8] * (2.0 * v)
            + c[9] * (6.0 * w)
            + c[12] * (2.0 * v2)
            + c[13] * (6.0 * vw)
            + c[14] * (12.0 * w2),
    ]
}

/// The monomials of eq. (5) and their derivatives, differentiated by hand.
#[cfg(test)]
fn monomials(v: f64, w: f64) -> [[f64; 15]; 6] {
    let (v2, w2, v3, w3) = (v * v, w * w, v * v * v, w * w * w);
    #[rustfmt::skip]
    let m = [
        [1., v, w, v2, v * w, w2, v3, v2 * w, v * w2, w3, v2 * v2, v3 * w, v2 * w2, v * w3, w2 * w2],
        [0., 1., 0., 2. * v, w, 0., 3. * v2, 2. * v * w, w2, 0., 4. * v3, 3. * v2 * w, 2. * v * w2, w3, 0.],
        [0., 0., 1., 0., v, 2. * w, 0., v2, 2. * v * w, 3. * w2, 0., v3, 2. * v2 * w, 3. * v * w2, 4. * w3],
        [0., 0., 0., 2., 0., 0., 6. * v, 2. * w, 0., 0., 12. * v2, 6. * v * w, 2. * w2, 0., 0.],
        [0., 0., 0., 0., 1., 0., 0., 2. * v, 2. * w, 0., 0., 3. * v2, 4. * v * w, 3. * w2, 0.],
        [0., 0., 0., 0., 0., 2., 0., 0., 2. * v, 6. * w, 0., 0., 2. * v2, 6. * v * w, 12. * w2],
    ];
    m
}

/// Weights of the twelve control points for X, Xv, Xw, Xvv, Xvw, Xww at
/// (v, w), in the evaluation record's order (docs/design.md).
#[cfg(test)]
pub fn weights(v: f64, w: f64) -> [[f64; 12]; 6] {
    let mut out = [[0.0; 12]; 6];
    for (d, mono) in monomials(v, w).iter().enumerate() {
        for (i, row) in PHI.iter().enumerate() {
            out[d][i] = row.iter().zip(mono).map(|(a, b)| a * b).sum::<f64>() / 12.0;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_of_unity_and_derivatives_sum_to_zero() {
        for &(v, w) in &[
            (0.0, 0.0),
            (1.0, 0.0),
            (0.0, 1.0),
            (0.3, 0.2),
            (0.5, 0.5),
            (0.1, 0.85),
        ] {
            let wts = weights(v, w);
            assert!((wts[0].iter().sum::<f64>() - 1.0).abs() < 1e-15);
            for derivative in &wts[1..] {
                assert!(derivative.iter().sum::<f64>().abs() < 1e-14);
            }
        }
    }

    #[test]
    #[allow(clippy::needless_range_loop)] // i indexes five arrays at once
    fn derivatives_match_central_differences() {
        let (v, w, h) = (0.27, 0.31, 1e-5);
        let at = |v, w| weights(v, w);
        let c = at(v, w);
        for i in 0..12 {
            let dv = (at(v + h, w)[0][i] - at(v - h, w)[0][i]) / (2.0 * h);
            let dw = (at(v, w + h)[0][i] - at(v, w - h)[0][i]) / (2.0 * h);
            let dvv = (at(v + h, w)[1][i] - at(v - h, w)[1][i]) / (2.0 * h);
            let dvw = (at(v, w + h)[1][i] - at(v, w - h)[1][i]) / (2.0 * h);
            let dww = (at(v, w + h)[2][i] - at(v, w - h)[2][i]) / (2.0 * h);
            for (got, want) in [
                (c[1][i], dv),
                (c[2][i], dw),
                (c[3][i], dvv),
                (c[4][i], dvw),
                (c[5][i], dww),
            ] {
                assert!((got - want).abs() < 1e-9, "point {i}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn coefficients_agree_with_the_weights() {
        let control: [DVec3; 12] =
            std::array::from_fn(|i| DVec3::new(i as f64, (i * i) as f64 * 0.1, (i as f64).sin()));
        let c = coefficients(&control);
        for (v, w) in [(0.21, 0.37), (0.0, 0.0), (1.0, 0.0), (0.0, 1.0)] {
            for (got, want) in eval_coefficients(&c, v, w).iter().zip(eval(&control, v, w)) {
                assert!((*got - want).length() < 1e-13);
            }
        }
    }

    #[test]
    fn corners_take_the_regular_limit_mask() {
        // At a corner: ½ on the corner, 1/12 on each of its six neighbours.
        let at_c0 = weights(0.0, 0.0)[0];
        assert!((at_c0[0] - 0.5).abs() < 1e-15);
        for i in [1, 2, 6, 7, 8, 9] {
            assert!((at_c0[i] - 1.0 / 12.0).abs() < 1e-15, "x{}", i + 1);
        }
    }
}
