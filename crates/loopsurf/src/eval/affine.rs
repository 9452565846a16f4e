//! Affine changes of triangle parameters, and the chain rule that carries
//! derivatives back through them. Every step of evaluation (child
//! selection, corner rotation, the rings around a special vertex) is one.

use glam::DVec3;

/// (s, t) = M (v, w) + b.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    /// Rows: (∂s/∂v, ∂s/∂w), (∂t/∂v, ∂t/∂w).
    pub m: [[f64; 2]; 2],
    pub b: [f64; 2],
}

impl Affine {
    pub const IDENTITY: Affine = Affine {
        m: [[1.0, 0.0], [0.0, 1.0]],
        b: [0.0, 0.0],
    };

    #[inline]
    pub fn apply(&self, v: f64, w: f64) -> (f64, f64) {
        (
            self.m[0][0] * v + self.m[0][1] * w + self.b[0],
            self.m[1][0] * v + self.m[1][1] * w + self.b[1],
        )
    }

    /// `self` after `first`: (v, w) ↦ self(first(v, w)).
    pub fn after(&self, first: &Affine) -> Affine {
        let (a, f) = (&self.m, &first.m);
        let m = [
            [
                a[0][0] * f[0][0] + a[0][1] * f[1][0],
                a[0][0] * f[0][1] + a[0][1] * f[1][1],
            ],
            [
                a[1][0] * f[0][0] + a[1][1] * f[1][0],
                a[1][0] * f[0][1] + a[1][1] * f[1][1],
            ],
        ];
        let (b0, b1) = self.apply(first.b[0], first.b[1]);
        Affine { m, b: [b0, b1] }
    }

    /// Derivatives with respect to (s, t), in evaluation-record order
    /// (X, X_s, X_t, X_ss, X_st, X_tt), turned into derivatives with
    /// respect to (v, w).
    #[inline]
    pub fn pull_back(&self, d: [DVec3; 6]) -> [DVec3; 6] {
        let [[sv, sw], [tv, tw]] = self.m;
        let [x, xs, xt, xss, xst, xtt] = d;
        [
            x,
            xs * sv + xt * tv,
            xs * sw + xt * tw,
            xss * (sv * sv) + xst * (2.0 * sv * tv) + xtt * (tv * tv),
            xss * (sv * sw) + xst * (sv * tw + sw * tv) + xtt * (tv * tw),
            xss * (sw * sw) + xst * (2.0 * sw * tw) + xtt * (tw * tw),
        ]
    }
}

/// The parameters of child c (in [`crate::Topology::refined`]'s order) of a
/// triangle, as a map from the parent's (v, w).
pub fn child(c: usize) -> Affine {
    match c {
        0 => Affine {
            m: [[2.0, 0.0], [0.0, 2.0]],
            b: [0.0, 0.0],
        },
        1 => Affine {
            m: [[2.0, 0.0], [0.0, 2.0]],
            b: [-1.0, 0.0],
        },
        2 => Affine {
            m: [[2.0, 0.0], [0.0, 2.0]],
            b: [0.0, -1.0],
        },
        _ => Affine {
            m: [[-2.0, 0.0], [0.0, -2.0]],
            b: [1.0, 1.0],
        },
    }
}

/// The child of a triangle that holds (v, w), with its map.
#[inline]
pub fn child_containing(v: f64, w: f64) -> (usize, Affine) {
    let c = if v >= 0.5 {
        1
    } else if w >= 0.5 {
        2
    } else if v + w < 0.5 {
        0
    } else {
        3
    };
    (c, child(c))
}

/// The same triangle with its corners relabelled so that corner `k` comes
/// first (orientation kept): (c_k, c_k+1, c_k+2).
pub fn rotation(k: usize) -> Affine {
    match k % 3 {
        0 => Affine::IDENTITY,
        // Corners (c1, c2, c0): s = w, t = 1 − v − w.
        1 => Affine {
            m: [[0.0, 1.0], [-1.0, -1.0]],
            b: [0.0, 1.0],
        },
        // Corners (c2, c0, c1): s = 1 − v − w, t = v.
        _ => Affine {
            m: [[-1.0, -1.0], [1.0, 0.0]],
            b: [1.0, 0.0],
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn children_tile_the_parent() {
        // Each child's corners map to (0,0), (1,0), (0,1).
        let corners = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let (p0, p1, p2) = (corners[0], corners[1], corners[2]);
        let (m0, m1, m2) = (mid(p0, p1), mid(p1, p2), mid(p2, p0));
        let kids = [[p0, m0, m2], [m0, p1, m1], [m2, m1, p2], [m1, m2, m0]];
        for (c, kid) in kids.iter().enumerate() {
            for (k, p) in kid.iter().enumerate() {
                assert_eq!(
                    child(c).apply(p[0], p[1]),
                    (corners[k][0], corners[k][1]),
                    "child {c}"
                );
            }
        }
    }

    #[test]
    fn rotations_relabel_corners() {
        let corners = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)];
        for k in 0..3 {
            for i in 0..3 {
                let (v, w) = corners[(k + i) % 3];
                assert_eq!(rotation(k).apply(v, w), corners[i]);
            }
        }
        let r = rotation(1).after(&rotation(2));
        assert_eq!(r, Affine::IDENTITY);
    }
}
