//! An open net: a hexagonal patch of the regular triangular lattice lifted
//! onto a shallow paraboloid cap. Its rim is a boundary (always hard), with
//! valence-3 corners and valence-4 edge vertices, while every interior vertex
//! has valence 6; the cap keeps the surface curved so that boundary rules
//! are tested on something other than a plane.

use super::Example;
use glam::DVec3;
use std::collections::HashMap;

/// Lattice rings around the centre vertex.
const K: i32 = 3;
/// Height of the cap centre above the rim plane z = 0.
pub const CAP_HEIGHT: f64 = 0.25;

/// Hexagonal patch of circumradius 1 in x, y with z = 0.25 (1 − x² − y²),
/// 37 vertices, 54 triangles, normals pointing up (+z), 18 boundary edges.
pub fn open_disk() -> Example {
    let inside = |q: i32, r: i32| q.abs() <= K && r.abs() <= K && (q + r).abs() <= K;
    let mut index: HashMap<(i32, i32), u32> = HashMap::new();
    let mut points = Vec::new();
    for q in -K..=K {
        for r in -K..=K {
            if inside(q, r) {
                // Axial coordinates: q along (1, 0), r along (1/2, √3/2).
                let x = (q as f64 + 0.5 * r as f64) / K as f64;
                let y = 0.5 * 3f64.sqrt() * r as f64 / K as f64;
                index.insert((q, r), points.len() as u32);
                points.push(DVec3::new(x, y, CAP_HEIGHT * (1.0 - x * x - y * y)));
            }
        }
    }
    // The hexagon is convex, so a lattice triangle is in the patch exactly
    // when its three corners are. Both kinds are CCW seen from +z.
    let mut tris = Vec::new();
    for q in -K..=K {
        for r in -K..=K {
            for tri in [
                [(q, r), (q + 1, r), (q, r + 1)],
                [(q + 1, r), (q + 1, r + 1), (q, r + 1)],
            ] {
                if tri.iter().all(|&(a, b)| inside(a, b)) {
                    tris.push(tri.map(|c| index[&c]));
                }
            }
        }
    }
    Example {
        name: "open-disk",
        points,
        tris,
    }
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;

    #[test]
    fn open_disk_is_an_oriented_manifold_with_one_boundary_loop() {
        let ex = open_disk();
        check_elements(&ex);
        let k = K as usize;
        assert_eq!(
            (ex.points.len(), ex.tris.len()),
            (3 * k * (k + 1) + 1, 6 * k * k)
        );
        let (edges, boundary) = check_open_manifold(&ex);
        assert_eq!(boundary, 6 * k);
        assert_eq!(euler(&ex, edges), 1);
        assert!(ex.tris.iter().all(|&t| area_vector(&ex, t).z > 0.0));
    }

    #[test]
    fn open_disk_valences() {
        let v = valences(&open_disk());
        let count = |n| v.iter().filter(|&&x| x == n).count();
        let k = K as usize;
        assert_eq!(count(3), 6);
        assert_eq!(count(4), 6 * (k - 1));
        assert_eq!(count(6), 3 * k * (k - 1) + 1);
    }
}
