//! Torus as a regular grid: every vertex has valence 6, so every triangle is
//! a regular (quartic box-spline) patch. Useful to test the regular-patch
//! evaluator against an exact reference with no extraordinary vertex at all.

use super::Example;
use glam::DVec3;
use std::f64::consts::TAU;

/// Major radius (centre of the tube to the z axis).
pub const MAJOR_RADIUS: f64 = 1.0;
/// Minor radius (tube radius).
pub const MINOR_RADIUS: f64 = 0.35;
/// Segments around the z axis.
const NU: usize = 24;
/// Segments around the tube.
const NV: usize = 12;

/// Torus about the z axis, R = 1, r = 0.35, 24 × 12 grid, 576 triangles.
///
/// Each grid quad is split along the same diagonal, (i, j)–(i+1, j+1):
/// with consistent diagonals every vertex gets valence 6, whereas
/// alternating them would give valences 4 and 8.
pub fn torus() -> Example {
    let idx = |i: usize, j: usize| ((i % NU) * NV + j % NV) as u32;
    let mut points = Vec::with_capacity(NU * NV);
    for i in 0..NU {
        let u = TAU * i as f64 / NU as f64;
        for j in 0..NV {
            let v = TAU * j as f64 / NV as f64;
            let rho = MAJOR_RADIUS + MINOR_RADIUS * v.cos();
            points.push(DVec3::new(
                rho * u.cos(),
                rho * u.sin(),
                MINOR_RADIUS * v.sin(),
            ));
        }
    }
    // ∂u × ∂v points away from the tube centre, so (u, then v) is CCW.
    let mut tris = Vec::with_capacity(2 * NU * NV);
    for i in 0..NU {
        for j in 0..NV {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    Example {
        name: "torus",
        points,
        tris,
    }
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;

    #[test]
    fn torus_is_a_closed_outward_genus_1_net() {
        let ex = torus();
        assert_eq!(ex.tris.len(), 2 * NU * NV);
        assert_eq!(check_closed_example(&ex), 0);
    }

    #[test]
    fn torus_is_all_valence_6() {
        assert!(valences(&torus()).iter().all(|&n| n == 6));
    }

    /// Outward means away from the tube's centre circle, not just a positive
    /// total volume.
    #[test]
    fn torus_normals_point_away_from_the_tube_axis() {
        let ex = torus();
        for &t in &ex.tris {
            let c = t.map(|i| ex.points[i as usize]).iter().sum::<DVec3>() / 3.0;
            let axis = DVec3::new(c.x, c.y, 0.0).normalize() * MAJOR_RADIUS;
            assert!(area_vector(&ex, t).dot(c - axis) > 0.0);
        }
    }
}
