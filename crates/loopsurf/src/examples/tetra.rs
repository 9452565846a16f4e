//! Regular tetrahedron: every vertex has valence 3, the case whose local
//! subdivision matrix is not diagonalizable (docs/design.md, what "exact" means), so
//! evaluators need it as a test case.

use super::Example;
use glam::DVec3;

/// Regular tetrahedron inscribed in the unit sphere, centred at the origin
/// (vertices at alternate corners of the cube [-1,1]³, scaled by 1/√3).
pub fn tetra() -> Example {
    let s = 1.0 / 3f64.sqrt();
    let points = [
        (1.0, 1.0, 1.0),
        (1.0, -1.0, -1.0),
        (-1.0, 1.0, -1.0),
        (-1.0, -1.0, 1.0),
    ]
    .map(|(x, y, z)| DVec3::new(x, y, z) * s)
    .to_vec();
    // Each face lists its vertices CCW seen from outside, i.e. opposite
    // the omitted vertex.
    let tris = vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
    Example {
        name: "tetra",
        points,
        tris,
    }
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;

    #[test]
    fn tetra_is_a_closed_outward_genus_0_net() {
        let ex = tetra();
        assert_eq!(check_closed_example(&ex), 2);
        assert!(valences(&ex).iter().all(|&n| n == 3));
        assert!(ex.points.iter().all(|p| (p.length() - 1.0).abs() < 1e-15));
    }
}
