//! The Lagrange triangle of order k on the reference triangle
//! (ξ, η) ∈ {ξ, η ≥ 0, ξ + η ≤ 1}: its nodes in gmsh's order, its basis
//! functions with their derivatives, and the quadrature the validity check
//! and the distance measure use. Pure arithmetic: nothing here knows about
//! surfaces.
//!
//! gmsh numbers a triangle's nodes recursively (and VTK's Lagrange triangle
//! agrees for orders 2 and 3): the three vertices, then the inner nodes of
//! edge 0→1, 1→2 and 2→0, each from its first vertex towards its second,
//! then the interior nodes, which are numbered the same way as a triangle
//! of order k − 3 shrunk onto the interior lattice.

/// Orders the high-order mesher writes (1, linear, to 4: what the file
/// formats carry), and the node count of each.
pub use crate::io::{nodes_per_triangle, MAX_LAGRANGE_ORDER as MAX_ORDER};

use glam::DVec3;

/// Lattice coordinates (i, j) of the nodes of the order-k triangle in
/// gmsh's order: node at (ξ, η) = (i/k, j/k).
pub fn lattice(k: usize) -> Vec<[usize; 2]> {
    if k == 0 {
        return vec![[0, 0]];
    }
    let mut out = vec![[0, 0], [k, 0], [0, k]];
    out.extend((1..k).map(|i| [i, 0]));
    out.extend((1..k).map(|i| [k - i, i]));
    out.extend((1..k).map(|i| [0, k - i]));
    if k >= 3 {
        // The interior is the order-(k − 3) lattice moved by (1, 1).
        out.extend(lattice(k - 3).into_iter().map(|[i, j]| [i + 1, j + 1]));
    }
    out
}

/// The reference coordinates (ξ, η) of the order-k nodes, in gmsh's order.
pub fn reference_nodes(k: usize) -> Vec<[f64; 2]> {
    lattice(k)
        .into_iter()
        .map(|[i, j]| [i as f64 / k as f64, j as f64 / k as f64])
        .collect()
}

/// P(λ) = Π_{a<n} (kλ − a)/(a + 1) and its derivative: the univariate
/// factor of the barycentric form of the equispaced Lagrange basis.
fn factor(n: usize, k: f64, lambda: f64) -> (f64, f64) {
    let (mut p, mut dp) = (1.0, 0.0);
    for a in 0..n {
        let a = a as f64;
        let f = (k * lambda - a) / (a + 1.0);
        let df = k / (a + 1.0);
        dp = dp * f + p * df;
        p *= f;
    }
    (p, dp)
}

/// The order-k basis at (ξ, η): per node (gmsh order) its value and its
/// derivatives by ξ and η. The basis function of lattice node (i, j) is
/// P_i(λ₁) P_j(λ₂) P_l(λ₀), l = k − i − j, with λ₀ = 1 − ξ − η, λ₁ = ξ,
/// λ₂ = η: it is 1 at its node and 0 at every other.
pub fn basis(k: usize, xi: f64, eta: f64) -> Vec<[f64; 3]> {
    let kf = k as f64;
    let l0 = 1.0 - xi - eta;
    lattice(k)
        .into_iter()
        .map(|[i, j]| {
            let (a, da) = factor(i, kf, xi);
            let (b, db) = factor(j, kf, eta);
            let (c, dc) = factor(k - i - j, kf, l0);
            [a * b * c, da * b * c - a * b * dc, a * db * c - a * b * dc]
        })
        .collect()
}

/// Where interior node (i, j) of an order-k element goes when only its
/// boundary nodes are known (`boundary`: the vertices, then the edge nodes,
/// in gmsh's order): for k = 3 the centroid value of the cubic that
/// reproduces every quadratic, Σ edge nodes / 4 − Σ vertices / 6; for k = 4
/// the quadratic element through the vertices and the edge midpoints;
/// otherwise (no interior) the flat point. Curving the interior with the
/// edges keeps an element whose edges bend strongly from folding over its
/// own interior node.
pub fn interior_from_boundary(k: usize, boundary: &[DVec3], [i, j]: [usize; 2]) -> Option<DVec3> {
    let vertices = &boundary[..3];
    match k {
        3 => {
            let edges: DVec3 = boundary[3..9].iter().sum();
            let corners: DVec3 = vertices.iter().sum();
            Some(edges / 4.0 - corners / 6.0)
        }
        4 => {
            // Edge s's middle node is its second of three.
            let mids = [boundary[4], boundary[7], boundary[10]];
            let quadratic: Vec<DVec3> = vertices.iter().chain(&mids).copied().collect();
            let (x, y) = (i as f64 / 4.0, j as f64 / 4.0);
            Some(
                basis(2, x, y)
                    .iter()
                    .zip(&quadratic)
                    .map(|(b, &p)| b[0] * p)
                    .sum(),
            )
        }
        _ => None,
    }
}

/// Four-point Gauss–Legendre on [0, 1]: nodes and weights.
const GAUSS_4: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
    (0.330_009_478_207_571_87, 0.326_072_577_431_273_07),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_07),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
];

/// Sixteen quadrature points (ξ, η, weight) on the reference triangle,
/// exact for polynomials of degree 6 (area 1/2): the collapsed (Duffy)
/// product of 4-point Gauss rules, ξ = u, η = s(1 − u), weight w_u w_s
/// (1 − u). Degree 6 covers the Jacobian of a P4 element, the highest
/// order written, whose derivative products are of degree 6.
pub fn quadrature() -> Vec<[f64; 3]> {
    let mut out = Vec::with_capacity(16);
    for (u, wu) in GAUSS_4 {
        for (s, ws) in GAUSS_4 {
            out.push([u, s * (1.0 - u), wu * ws * (1.0 - u)]);
        }
    }
    out
}

/// Interior sample points of the reference triangle where the distance to
/// the surface is measured: the lattice of order 7 without its boundary
/// (15 points). 7 is prime to every order written, so no sample is a node,
/// where the error vanishes by construction.
pub fn samples() -> Vec<[f64; 2]> {
    let m = 7;
    let mut out = Vec::new();
    for j in 1..m {
        for i in 1..m - j {
            out.push([i as f64 / m as f64, j as f64 / m as f64]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The layouts gmsh documents ("Node ordering", high-order triangles):
    /// written out by hand for orders 2 and 3, independent of [`lattice`].
    #[test]
    fn node_order_is_gmsh_s() {
        let p2 = [[0, 0], [2, 0], [0, 2], [1, 0], [1, 1], [0, 1]];
        assert_eq!(lattice(2), p2);
        let p3 = [
            [0, 0],
            [3, 0],
            [0, 3],
            [1, 0],
            [2, 0],
            [2, 1],
            [1, 2],
            [0, 2],
            [0, 1],
            [1, 1],
        ];
        assert_eq!(lattice(3), p3);
        let p4_interior = [[1, 1], [2, 1], [1, 2]];
        assert_eq!(lattice(4)[12..], p4_interior);
        for k in 1..=MAX_ORDER {
            let mut sorted = lattice(k);
            assert_eq!(sorted.len(), nodes_per_triangle(k));
            sorted.sort();
            sorted.dedup();
            assert_eq!(
                sorted.len(),
                nodes_per_triangle(k),
                "order {k}: a node twice"
            );
        }
    }

    /// Each basis function is 1 at its node and 0 at the others; the basis
    /// reproduces x and y with exact derivatives (a partition of unity
    /// whose derivatives sum to zero).
    #[test]
    fn basis_is_nodal_and_reproduces_linears() {
        for k in 1..=MAX_ORDER {
            let nodes = reference_nodes(k);
            for (n, &[x, y]) in nodes.iter().enumerate() {
                for (m, b) in basis(k, x, y).iter().enumerate() {
                    let want = (n == m) as u8 as f64;
                    assert!(
                        (b[0] - want).abs() < 1e-13,
                        "order {k} node {n} basis {m}: {b:?}"
                    );
                }
            }
            for &[x, y, _] in &quadrature() {
                let b = basis(k, x, y);
                let sum = |f: &dyn Fn(usize) -> f64, d: usize| {
                    b.iter().enumerate().map(|(n, b)| b[d] * f(n)).sum::<f64>()
                };
                let one = |_: usize| 1.0;
                let xs = |n: usize| nodes[n][0];
                let ys = |n: usize| nodes[n][1];
                assert!((sum(&one, 0) - 1.0).abs() < 1e-13);
                assert!(sum(&one, 1).abs() < 1e-12 && sum(&one, 2).abs() < 1e-12);
                assert!((sum(&xs, 0) - x).abs() < 1e-13 && (sum(&ys, 0) - y).abs() < 1e-13);
                assert!((sum(&xs, 1) - 1.0).abs() < 1e-12 && sum(&xs, 2).abs() < 1e-12);
                assert!(sum(&ys, 1).abs() < 1e-12 && (sum(&ys, 2) - 1.0).abs() < 1e-12);
            }
        }
    }

    /// The interior guesses reproduce a quadratic map exactly: boundary
    /// nodes of a quadratic give its interior values.
    #[test]
    fn interior_from_boundary_reproduces_quadratics() {
        let f = |x: f64, y: f64| DVec3::new(x + 0.3 * y * y, y - 0.7 * x * y, 0.2 * x * x - y);
        for k in [3, 4] {
            let nodes = reference_nodes(k);
            let boundary: Vec<DVec3> = nodes[..3 * k].iter().map(|&[x, y]| f(x, y)).collect();
            for (&[i, j], &[x, y]) in lattice(k)[3 * k..].iter().zip(&nodes[3 * k..]) {
                let got = interior_from_boundary(k, &boundary, [i, j]).unwrap();
                assert!(
                    got.distance(f(x, y)) < 1e-14,
                    "order {k} node ({i}, {j}): {got} vs {}",
                    f(x, y)
                );
            }
        }
    }

    /// The quadrature integrates ξ^a η^b exactly to degree 6: the exact
    /// value is a! b! / (a + b + 2)!.
    #[test]
    fn quadrature_is_exact_to_degree_6() {
        let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
        for a in 0..=6u32 {
            for b in 0..=6 - a {
                let q: f64 = quadrature()
                    .iter()
                    .map(|&[x, y, w]| w * x.powi(a as i32) * y.powi(b as i32))
                    .sum();
                let exact = fact(a) * fact(b) / fact(a + b + 2);
                assert!((q - exact).abs() < 1e-15, "ξ^{a} η^{b}: {q} vs {exact}");
            }
        }
        let samples = samples();
        assert_eq!(samples.len(), 15);
        assert!(samples
            .iter()
            .all(|&[x, y]| x > 0.0 && y > 0.0 && x + y < 1.0));
    }
}
