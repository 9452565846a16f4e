//! Unit icosphere: an icosahedron whose faces are split 4-to-1 twice, with
//! the new vertices pushed onto the unit sphere.
//!
//! Two splits give 162 vertices and 320 triangles: the 12 original vertices
//! keep valence 5 and all others have valence 6, so the net mixes regular
//! triangles with the mildest extraordinary vertex.

use super::Example;
use glam::DVec3;
use std::collections::HashMap;

/// Number of 4-to-1 splits of the icosahedron.
const LEVELS: usize = 2;

/// Icosphere of radius 1 centred at the origin (162 vertices, 320 triangles).
pub fn sphere() -> Example {
    let (mut points, mut tris) = icosahedron();
    for _ in 0..LEVELS {
        tris = split(&mut points, &tris);
    }
    Example {
        name: "sphere",
        points,
        tris,
    }
}

/// The regular icosahedron on the unit sphere, outward-oriented.
fn icosahedron() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let g = (1.0 + 5f64.sqrt()) / 2.0;
    let points = [
        (-1.0, g, 0.0),
        (1.0, g, 0.0),
        (-1.0, -g, 0.0),
        (1.0, -g, 0.0),
        (0.0, -1.0, g),
        (0.0, 1.0, g),
        (0.0, -1.0, -g),
        (0.0, 1.0, -g),
        (g, 0.0, -1.0),
        (g, 0.0, 1.0),
        (-g, 0.0, -1.0),
        (-g, 0.0, 1.0),
    ]
    .map(|(x, y, z)| DVec3::new(x, y, z).normalize())
    .to_vec();
    let tris = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    (points, tris)
}

/// Split every triangle into four, sharing one new vertex per edge, and put
/// the new vertices on the unit sphere. Orientation is inherited.
fn split(points: &mut Vec<DVec3>, tris: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
    let mut midpoint = |a: u32, b: u32| -> u32 {
        *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
            let p = (points[a as usize] + points[b as usize]).normalize();
            points.push(p);
            (points.len() - 1) as u32
        })
    };
    let mut out = Vec::with_capacity(4 * tris.len());
    for &[a, b, c] in tris {
        let (ab, bc, ca) = (midpoint(a, b), midpoint(b, c), midpoint(c, a));
        out.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;

    #[test]
    fn sphere_is_a_closed_outward_genus_0_net() {
        let ex = sphere();
        assert_eq!((ex.points.len(), ex.tris.len()), (162, 320));
        assert_eq!(check_closed_example(&ex), 2);
        assert!(ex.points.iter().all(|p| (p.length() - 1.0).abs() < 1e-14));
    }

    #[test]
    fn sphere_valences_are_5_and_6() {
        let v = valences(&sphere());
        assert_eq!(v.iter().filter(|&&n| n == 5).count(), 12);
        assert_eq!(v.iter().filter(|&&n| n == 6).count(), 150);
    }
}
