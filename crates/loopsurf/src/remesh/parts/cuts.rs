//! The graph work of remeshing by parts: which vertices two parts share,
//! which triangle goes to which part, rings around vertices and control
//! triangles, fans at a vertex and connected blobs.

use crate::net::ControlNet;
use crate::sets::DisjointSets;
use crate::topology::NONE;
use std::collections::HashMap;

/// Per vertex of a mesh: how many pieces meet there, counted up to 3,
/// each part one piece and the triangles no part takes ([`NONE`]) one
/// more.
pub(super) fn pieces_meeting(triangles: &[[u32; 3]], owner: &[u32], n: usize) -> Vec<u8> {
    let mut seen = vec![[0u32; 2]; n];
    let mut count = vec![0u8; n];
    for (tri, &p) in triangles.iter().zip(owner) {
        for &v in tri {
            let (seen, count) = (&mut seen[v as usize], &mut count[v as usize]);
            let known = &seen[..(*count as usize).min(2)];
            if *count < 3 && !known.contains(&p) {
                if *count < 2 {
                    seen[*count as usize] = p;
                }
                *count += 1;
            }
        }
    }
    count
}

/// Per vertex of a mesh: the lowest part whose triangles use it
/// ([`NONE`] where none does).
pub(super) fn lowest_part(triangles: &[[u32; 3]], owner: &[u32], n: usize) -> Vec<u32> {
    let mut lowest = vec![NONE; n];
    for (tri, &p) in triangles.iter().zip(owner) {
        for &v in tri {
            lowest[v as usize] = lowest[v as usize].min(p);
        }
    }
    lowest
}

/// The part most of a triangle's three votes name (the first vote's
/// when all differ).
pub(super) fn majority([a, b, c]: [u32; 3]) -> u32 {
    if b == c {
        b
    } else {
        a
    }
}

/// Per mesh vertex: whether it lies within `rings` edges of a vertex
/// `seed` marks.
pub(super) fn mesh_rings(triangles: &[[u32; 3]], seed: &[bool], rings: usize) -> Vec<bool> {
    let mut near = seed.to_vec();
    for _ in 0..rings {
        let mut next = near.clone();
        for tri in triangles {
            if tri.iter().any(|&v| near[v as usize]) {
                for &v in tri {
                    next[v as usize] = true;
                }
            }
        }
        near = next;
    }
    near
}

/// Per control triangle: whether it lies within `rings` vertex rings of
/// one of the triangles `seeds`.
pub(super) fn control_rings(
    net: &ControlNet,
    seeds: impl Iterator<Item = u32>,
    rings: usize,
) -> Vec<bool> {
    let topo = net.topology();
    let mut near = vec![false; net.triangles().len()];
    let mut front: Vec<u32> = seeds.collect();
    for t in &front {
        near[*t as usize] = true;
    }
    for _ in 0..rings {
        let mut next = Vec::new();
        for &t in &front {
            for &v in &net.triangles()[t as usize] {
                for &u in topo.fan(v as usize) {
                    if !near[u as usize] {
                        near[u as usize] = true;
                        next.push(u);
                    }
                }
            }
        }
        front = next;
    }
    near
}

/// Per corner (3 per triangle) of a set of triangles: the fan it belongs
/// to, named by one of the fan's corners. Two corners at one vertex are in
/// one fan when a chain of triangles sharing edges at that vertex joins
/// them.
pub(super) fn fans(triangles: &[[u32; 3]]) -> Vec<usize> {
    let mut class = DisjointSets::new(3 * triangles.len());
    let mut edges: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            // The corners of a and b in this triangle.
            let (ca, cb) = (3 * t + k, 3 * t + (k + 1) % 3);
            match edges.remove(&(b, a)) {
                // The neighbour across runs b → a: its corner at b, then a.
                Some(other) => {
                    let (ob, oa) = (other, 3 * (other / 3) + (other % 3 + 1) % 3);
                    class.unite(ca, oa);
                    class.unite(cb, ob);
                }
                None => {
                    edges.insert((a, b), ca);
                }
            }
        }
    }
    (0..3 * triangles.len()).map(|c| class.root(c)).collect()
}

/// The triangles with a vertex in `band`, each connected set of them (by
/// band vertices) numbered: the number of each triangle ([`NONE`] outside
/// the band, numbered in triangle order), and how many.
pub(super) fn blobs(triangles: &[[u32; 3]], band: &[bool]) -> (Vec<u32>, usize) {
    let mut class = DisjointSets::new(triangles.len());
    let mut first = vec![usize::MAX; band.len()];
    for (t, tri) in triangles.iter().enumerate() {
        for &v in tri.iter().filter(|&&v| band[v as usize]) {
            match first[v as usize] {
                usize::MAX => first[v as usize] = t,
                u => class.unite(u, t),
            }
        }
    }
    let mut number = vec![NONE; triangles.len()];
    let mut owner = vec![NONE; triangles.len()];
    let mut count = 0;
    for (t, tri) in triangles.iter().enumerate() {
        if tri.iter().any(|&v| band[v as usize]) {
            let r = class.root(t);
            if number[r] == NONE {
                number[r] = count;
                count += 1;
            }
            owner[t] = number[r];
        }
    }
    (owner, count as usize)
}

#[cfg(test)]
mod tests {
    use super::{lowest_part, pieces_meeting};
    use crate::topology::NONE;

    #[test]
    fn pieces_meet_at_shared_vertices_and_corners() {
        // Three triangles in a row: part 0, part 1, and one no part takes.
        let triangles = [[0, 1, 2], [1, 3, 2], [2, 3, 4]];
        let owner = [0, 1, NONE];
        assert_eq!(pieces_meeting(&triangles, &owner, 5), vec![1, 2, 3, 2, 1]);
        assert_eq!(lowest_part(&triangles, &owner, 5), vec![0, 0, 0, 1, NONE]);
        // One part twice counts once; a fourth piece still counts 3.
        let triangles = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
        assert_eq!(pieces_meeting(&triangles, &[5, 5, 7, 9], 6)[0], 3);
        assert_eq!(pieces_meeting(&triangles, &[5, 6, 7, 8], 6)[0], 3);
        assert_eq!(pieces_meeting(&triangles, &[5, 6, 5, 6], 6)[0], 2);
    }
}
