//! Unit cube with each face an n × n grid: the simplest net with hard
//! features. The 12 cube edges have 90° dihedral angles (crease curves), the
//! 8 corners meet three of them (corner vertices), and every face interior is
//! flat, so the exact limit surface is known there.

use super::Example;
use glam::DVec3;
use std::collections::HashMap;

/// Grid cells along each cube edge.
const N: u32 = 3;

/// The cube [0,1]³, each face a 3 × 3 grid of squares split along the same
/// diagonal (56 vertices, 108 triangles).
pub fn cube() -> Example {
    let mut index: HashMap<[u32; 3], u32> = HashMap::new();
    let mut points = Vec::new();
    let mut vertex = |l: [u32; 3]| -> u32 {
        *index.entry(l).or_insert_with(|| {
            points.push(DVec3::from_array(l.map(|c| c as f64 / N as f64)));
            (points.len() - 1) as u32
        })
    };
    let mut tris = Vec::with_capacity(12 * (N * N) as usize);
    for axis in 0..3 {
        // (u, v, axis) is a cyclic permutation, so e_u × e_v = e_axis.
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in [0, N] {
            let lattice = |i: u32, j: u32| {
                let mut l = [0; 3];
                (l[axis], l[u], l[v]) = (side, i, j);
                l
            };
            for i in 0..N {
                for j in 0..N {
                    let a = vertex(lattice(i, j));
                    let b = vertex(lattice(i + 1, j));
                    let c = vertex(lattice(i + 1, j + 1));
                    let d = vertex(lattice(i, j + 1));
                    // (u, then v) is CCW seen from +axis: right for the far
                    // face, reversed for the face at 0.
                    if side == N {
                        tris.extend([[a, b, c], [a, c, d]]);
                    } else {
                        tris.extend([[a, c, b], [a, d, c]]);
                    }
                }
            }
        }
    }
    Example {
        name: "cube",
        points,
        tris,
    }
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;

    #[test]
    fn cube_is_a_closed_outward_genus_0_net() {
        let ex = cube();
        assert_eq!((ex.points.len(), ex.tris.len()), (56, 108));
        assert_eq!(check_closed_example(&ex), 2);
        assert!((signed_volume(&ex) - 1.0).abs() < 1e-14);
    }

    /// Faces are flat and the only bends are the 12 cube edges, 90° each.
    #[test]
    fn cube_dihedral_angles_are_0_or_90() {
        let ex = cube();
        let angles = dihedral_angles(&ex);
        let sharp = angles.iter().filter(|e| (e.2 - 90.0).abs() < 1e-9).count();
        let flat = angles.iter().filter(|e| e.2.abs() < 1e-6).count();
        assert_eq!(sharp, 12 * N as usize);
        assert_eq!(sharp + flat, angles.len());
    }
}
