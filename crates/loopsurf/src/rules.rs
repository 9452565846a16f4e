//! Every Loop subdivision mask, in one place.
//!
//! These are pure weights: they know nothing of meshes. Callers gather the
//! neighbour positions a mask needs and apply the weights. The rules are
//! those of docs/design.md ("Subdivision rules"), which equal OpenSubdiv's Sdc rules
//! for Loop with `VTX_BOUNDARY_EDGE_ONLY` and infinitely sharp creases:
//!
//! * smooth and dart vertices: Loop's original β(n);
//! * crease vertices (exactly two hard edges): the cubic B-spline ⅛ ¾ ⅛;
//! * corners (more than two hard edges, or tagged): fixed;
//! * smooth edges 3/8 3/8 1/8 1/8, hard edges ½ ½.

use glam::DVec3;
use std::f64::consts::PI;

/// Loop's original vertex weight β(n) = (5/8 − (3/8 + ¼ cos 2π/n)²) / n.
///
/// Each of the n neighbours gets β; the vertex itself keeps 1 − nβ.
/// β(6) = 1/16, which makes regular regions quartic box splines.
pub fn loop_beta(valence: usize) -> f64 {
    // Refinement asks for β once per vertex per level: a table for the
    // common valences keeps cos() off that path.
    const TABLED: usize = 64;
    static TABLE: std::sync::OnceLock<[f64; TABLED]> = std::sync::OnceLock::new();
    let formula = |valence: usize| {
        let n = valence as f64;
        let c = 3.0 / 8.0 + 0.25 * (2.0 * PI / n).cos();
        (5.0 / 8.0 - c * c) / n
    };
    match valence {
        n if n < TABLED => TABLE.get_or_init(|| std::array::from_fn(formula))[n],
        n => formula(n),
    }
}

/// New position of a smooth (or dart) vertex of the given valence, from its
/// old position and the sum of its neighbours' old positions.
#[inline]
pub fn smooth_vertex(x: DVec3, neighbour_sum: DVec3, valence: usize) -> DVec3 {
    let beta = loop_beta(valence);
    (1.0 - valence as f64 * beta) * x + beta * neighbour_sum
}

/// New position of a crease vertex from its two neighbours along the crease
/// (passed as their sum): the cubic B-spline vertex rule ⅛ ¾ ⅛.
#[inline]
pub fn crease_vertex(x: DVec3, crease_neighbour_sum: DVec3) -> DVec3 {
    0.75 * x + 0.125 * crease_neighbour_sum
}

/// A corner does not move.
#[inline]
pub fn corner_vertex(x: DVec3) -> DVec3 {
    x
}

/// New vertex on a smooth edge (a, b) whose two triangles have the opposite
/// vertices c and d: 3/8 (a + b) + 1/8 (c + d).
#[inline]
pub fn smooth_edge(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> DVec3 {
    0.375 * (a + b) + 0.125 * (c + d)
}

/// New vertex on a hard (crease or boundary) edge: the midpoint.
#[inline]
pub fn hard_edge(a: DVec3, b: DVec3) -> DVec3 {
    0.5 * (a + b)
}

/// ω = 3 / (8 β(n)), the weight of the vertex itself in the smooth limit
/// mask. ω(6) = 6.
pub fn limit_omega(valence: usize) -> f64 {
    3.0 / (8.0 * loop_beta(valence))
}

/// Limit mask of a smooth vertex, (ω x + Σ xᵢ) / (ω + n), as the weight of
/// the vertex and of each neighbour.
pub fn smooth_limit_weights(valence: usize) -> (f64, f64) {
    let omega = limit_omega(valence);
    let total = omega + valence as f64;
    (omega / total, 1.0 / total)
}

/// Limit mask of a crease vertex, the cubic B-spline ⅙ ⅔ ⅙: the weight of
/// the vertex and of each of its two crease neighbours. A corner's limit is
/// the vertex itself (weight 1).
pub const CREASE_LIMIT_WEIGHTS: (f64, f64) = (4.0 / 6.0, 1.0 / 6.0);

/// Limit mask of a dart: a smooth vertex with exactly one hard edge.
///
/// The dart keeps the smooth vertex rule, but the midpoint rule ½ ½ on its
/// hard edge changes its one-ring subdivision matrix, so the smooth limit
/// mask is no longer that matrix's left eigenvector. The exact mask is the
/// left eigenvector for eigenvalue 1, computed here by iterating l ← l·S
/// from the vertex's own row (S^k converges to the rank-one limit matrix).
/// Returns the weight of the vertex and of its ring neighbours, with ring
/// position 0 the neighbour across the hard edge (the ring is cyclic, so
/// the orientation does not matter: the mask is symmetric about that edge).
///
/// OpenSubdiv applies the smooth limit mask at darts, so its limit points
/// differ from these (exact) ones there.
pub fn dart_limit_weights(valence: usize) -> (f64, Vec<f64>) {
    let n = valence;
    if n == 0 {
        return (1.0, Vec::new());
    }
    let beta = loop_beta(n);
    let mut vertex = 1.0;
    let mut ring = vec![0.0; n];
    let mut next = vec![0.0; n];
    // The subdominant eigenvalue is below 0.7 for every valence, so a few
    // hundred steps reach round-off; stop as soon as nothing changes.
    for _ in 0..10_000 {
        let hard_share = 0.5 * ring[0];
        let smooth_sum: f64 = ring[1..].iter().sum();
        let new_vertex = vertex * (1.0 - n as f64 * beta) + 0.375 * smooth_sum + hard_share;
        for j in 0..n {
            let smooth = |i: usize| if i == 0 { 0.0 } else { ring[i] };
            let (prev, succ) = ((j + n - 1) % n, (j + 1) % n);
            next[j] = vertex * beta
                + if j == 0 { hard_share } else { 0.375 * ring[j] }
                + 0.125 * (smooth(prev) + smooth(succ));
        }
        let change = (new_vertex - vertex).abs().max(
            next.iter()
                .zip(&ring)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max),
        );
        vertex = new_vertex;
        std::mem::swap(&mut ring, &mut next);
        // Geometric convergence: what is left is below round-off.
        if change <= 1e-16 {
            break;
        }
    }
    (vertex, ring)
}

/// Weights of the two limit tangent masks of a smooth vertex (Persson, Aftosmis & Haines
/// eq. 4): t₁ = Σ cos(2πi/n) xᵢ, t₂ = Σ sin(2πi/n) xᵢ over the neighbours in
/// counter-clockwise order. The vertex itself has weight 0 in both. Their
/// cross product t₁ × t₂ points along the outward normal.
pub fn smooth_tangent_weights(valence: usize) -> (Vec<f64>, Vec<f64>) {
    let n = valence as f64;
    (0..valence)
        .map(|i| {
            let a = 2.0 * PI * i as f64 / n;
            (a.cos(), a.sin())
        })
        .unzip()
}

/// Tangent of a crease vertex along its crease, from the crease neighbour it
/// comes from (`prev`) to the one it goes to (`next`): the derivative of the
/// limit cubic B-spline at the vertex, up to the factor ½ per parameter unit.
#[inline]
pub fn crease_tangent(prev: DVec3, next: DVec3) -> DVec3 {
    next - prev
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beta_regular_is_one_sixteenth() {
        assert!((loop_beta(6) - 1.0 / 16.0).abs() < 1e-17);
        assert!((limit_omega(6) - 6.0).abs() < 1e-14);
    }

    #[test]
    fn beta_valence_three_by_hand() {
        // cos(2π/3) = −½: (5/8 − (3/8 − 1/8)²)/3 = (5/8 − 1/16)/3 = 3/16.
        assert!((loop_beta(3) - 3.0 / 16.0).abs() < 1e-16);
    }

    #[test]
    fn masks_are_affine() {
        // Every mask must reproduce a constant: apply it to points all equal to p.
        let p = DVec3::new(1.5, -2.0, 0.25);
        for n in [3, 4, 5, 6, 7, 12, 64, 300] {
            assert!((smooth_vertex(p, n as f64 * p, n) - p).length() < 1e-13);
            let (own, each) = smooth_limit_weights(n);
            assert!((own + n as f64 * each - 1.0).abs() < 1e-15);
            let (c, s) = smooth_tangent_weights(n);
            assert!(c.iter().sum::<f64>().abs() < 1e-12);
            assert!(s.iter().sum::<f64>().abs() < 1e-12);
        }
        assert_eq!(crease_vertex(p, 2.0 * p), p);
        assert_eq!(CREASE_LIMIT_WEIGHTS.0 + 2.0 * CREASE_LIMIT_WEIGHTS.1, 1.0);
        assert_eq!(smooth_edge(p, p, p, p), p);
        assert_eq!(hard_edge(p, p), p);
        assert_eq!(corner_vertex(p), p);
    }

    #[test]
    fn hand_computed_values() {
        let x = DVec3::ZERO;
        let s = DVec3::new(6.0, 12.0, 18.0);
        // Regular: 10/16·0 + 1/16·s.
        assert_eq!(smooth_vertex(x, s, 6), s / 16.0);
        // Regular limit: (6·x + Σ xᵢ) / 12.
        let (own, each) = smooth_limit_weights(6);
        assert!((own - 0.5).abs() < 1e-15 && (each - 1.0 / 12.0).abs() < 1e-16);
        assert_eq!(
            crease_vertex(DVec3::X * 8.0, DVec3::Y * 8.0),
            DVec3::new(6.0, 1.0, 0.0)
        );
        assert_eq!(
            smooth_edge(
                DVec3::X * 8.0,
                DVec3::Y * 8.0,
                DVec3::Z * 8.0,
                DVec3::ONE * 8.0
            ),
            DVec3::new(4.0, 4.0, 2.0)
        );
        assert_eq!(hard_edge(DVec3::X, DVec3::Y), DVec3::new(0.5, 0.5, 0.0));
    }

    #[test]
    fn limit_masks_are_fixed_points_of_the_curve_rules() {
        // The crease limit mask is the left eigenvector of the cubic B-spline
        // subdivision matrix: applying it before or after one step agrees.
        let (a, x, b) = (
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0, 3.0, 0.5),
            DVec3::new(2.5, 0.0, 1.0),
        );
        let (a1, x1, b1) = (hard_edge(a, x), crease_vertex(x, a + b), hard_edge(x, b));
        let (own, each) = CREASE_LIMIT_WEIGHTS;
        let limit = |x: DVec3, sum: DVec3| own * x + each * sum;
        assert!((limit(x, a + b) - limit(x1, a1 + b1)).length() < 1e-15);
    }

    #[test]
    fn tangents_of_a_regular_planar_ring() {
        // Hexagon around the origin in the xy-plane: t1 ∥ x, t2 ∥ y.
        let ring: Vec<DVec3> = (0..6)
            .map(|i| {
                let a = 2.0 * PI * i as f64 / 6.0;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let (c, s) = smooth_tangent_weights(6);
        let t1: DVec3 = ring.iter().zip(&c).map(|(p, w)| *p * *w).sum();
        let t2: DVec3 = ring.iter().zip(&s).map(|(p, w)| *p * *w).sum();
        assert!((t1 - DVec3::new(3.0, 0.0, 0.0)).length() < 1e-14);
        assert!((t2 - DVec3::new(0.0, 3.0, 0.0)).length() < 1e-14);
        assert!(t1.cross(t2).z > 0.0);
        assert_eq!(
            crease_tangent(DVec3::X, DVec3::Y),
            DVec3::new(-1.0, 1.0, 0.0)
        );
    }

    #[test]
    fn dart_mask_is_a_left_eigenvector() {
        for n in [3, 4, 6, 9, 80] {
            let (a, ring) = dart_limit_weights(n);
            assert!((a + ring.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            // Symmetric about the hard edge.
            for j in 1..n {
                assert!((ring[j] - ring[n - j]).abs() < 1e-15);
            }
            // One more step of the dart's subdivision leaves it unchanged:
            // check on random ring positions.
            let x: Vec<DVec3> = (0..=n)
                .map(|i| DVec3::new((i as f64 * 1.3).sin(), (i as f64 * 0.7).cos(), i as f64))
                .collect();
            let (v, nb) = (x[0], &x[1..]);
            let sum: DVec3 = nb.iter().sum();
            let v1 = smooth_vertex(v, sum, n);
            let nb1: Vec<DVec3> = (0..n)
                .map(|j| {
                    if j == 0 {
                        hard_edge(v, nb[0])
                    } else {
                        smooth_edge(v, nb[j], nb[(j + n - 1) % n], nb[(j + 1) % n])
                    }
                })
                .collect();
            let apply = |v: DVec3, nb: &[DVec3]| {
                a * v + nb.iter().zip(&ring).map(|(p, w)| *p * *w).sum::<DVec3>()
            };
            assert!(
                (apply(v, nb) - apply(v1, &nb1)).length() < 1e-13,
                "valence {n}"
            );
        }
    }
}
