//! `--split-nonmanifold`: one copy of a vertex per fan, as OpenSubdiv's
//! topology refiner treats a vertex where separate fans of triangles touch
//! (two cones tip to tip, two surfaces sharing a point). The fans are the
//! groups of the vertex's triangles joined by edges through the vertex; the
//! fan holding the vertex's first triangle keeps its index, every other fan
//! gets a copy at the same position, appended to the vertex list.

use super::{edge_incidences, Repair};
use crate::io::MeshData;
use crate::sets::DisjointSets;

/// Splits every non-manifold vertex of `mesh`, and says which.
pub(super) fn split_nonmanifold(mesh: &mut MeshData) -> Option<Repair> {
    let nverts = mesh.points.len();
    // Union-find over triangle corners: corner 3t + k is vertex tris[t][k]
    // in triangle t. Two corners of one vertex join when their triangles
    // share an edge through that vertex.
    let mut fans = DisjointSets::new(3 * mesh.tris.len());
    let corner = |t: u32, v: u32| {
        let tri = &mesh.tris[t as usize];
        3 * t as usize + tri.iter().position(|&i| i == i64::from(v)).unwrap_or(0)
    };
    let incid = edge_incidences(mesh);
    for pair in incid.windows(2) {
        let ((e0, t0), (e1, t1)) = (pair[0], pair[1]);
        if e0 == e1 {
            for v in e0 {
                fans.unite(corner(t0, v), corner(t1, v));
            }
        }
    }
    // The corners of each vertex, in triangle order. A triangle listing a
    // vertex twice is left to validation (or to the weld, which drops it):
    // its corners are no fan, and copies would make it a separate piece of
    // zero area with two corners on one point.
    let mut corners: Vec<Vec<usize>> = vec![Vec::new(); nverts];
    let valid = |t: &[i64; 3]| {
        t.iter().all(|&i| i >= 0 && (i as usize) < nverts)
            && t[0] != t[1]
            && t[1] != t[2]
            && t[0] != t[2]
    };
    for t in 0..mesh.tris.len() {
        if valid(&mesh.tris[t]) {
            for k in 0..3 {
                corners[mesh.tris[t][k] as usize].push(3 * t + k);
            }
        }
    }
    let mut splits = Vec::new();
    for v in 0..nverts {
        // The vertex's fans (union-find roots) in order of first corner.
        let mut firsts: Vec<(usize, usize)> =
            corners[v].iter().map(|&c| (fans.root(c), c)).collect();
        firsts.sort_unstable();
        firsts.dedup_by_key(|f| f.0);
        if firsts.len() < 2 {
            continue;
        }
        firsts.sort_unstable_by_key(|f| f.1);
        let roots: Vec<usize> = firsts.iter().map(|f| f.0).collect();
        let mut by_root: Vec<(usize, usize)> =
            roots.iter().enumerate().map(|(f, &r)| (r, f)).collect();
        by_root.sort_unstable();
        let copies: Vec<u32> = roots[1..]
            .iter()
            .map(|_| {
                mesh.points.push(mesh.points[v]);
                if let Some(&line) = mesh.vertex_lines.get(v) {
                    mesh.vertex_lines.push(line);
                }
                (mesh.points.len() - 1) as u32
            })
            .collect();
        for &c in &corners[v] {
            let r = fans.root(c);
            if let Ok(k) = by_root.binary_search_by_key(&r, |x| x.0) {
                let f = by_root[k].1;
                if f > 0 {
                    mesh.tris[c / 3][c % 3] = i64::from(copies[f - 1]);
                }
            }
        }
        splits.push((v as u32, copies));
    }
    (!splits.is_empty()).then_some(Repair::SplitVertices { splits })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn two_fans_touching_at_a_vertex_get_a_vertex_each() {
        // Two triangles meeting only at vertex 0 (a bow tie), and a third
        // joined to the first across edge 0-2: fans {0, 2} and {1}.
        let mut m = MeshData {
            points: vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::Y,
                -DVec3::X,
                -DVec3::Y,
                DVec3::new(1.0, 1.0, 0.0),
            ],
            tris: vec![[0, 1, 2], [0, 3, 4], [0, 2, 5]],
            vertex_lines: vec![3, 4, 5, 6, 7, 8],
            ..MeshData::default()
        };
        let report = split_nonmanifold(&mut m);
        assert_eq!(m.tris, vec![[0, 1, 2], [6, 3, 4], [0, 2, 5]]);
        assert_eq!(m.points[6], DVec3::ZERO);
        assert_eq!(m.vertex_lines[6], 3);
        assert_eq!(
            report,
            Some(Repair::SplitVertices {
                splits: vec![(0, vec![6])]
            })
        );
    }

    #[test]
    fn a_triangle_listing_a_vertex_twice_is_left_to_validation() {
        // A tetrahedron and a fifth triangle repeating vertex 0: no copies.
        let mut m = MeshData {
            points: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            tris: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 0, 1]],
            ..MeshData::default()
        };
        assert_eq!(split_nonmanifold(&mut m), None);
        assert_eq!(m.tris[4], [0, 0, 1]);
    }

    #[test]
    fn manifold_meshes_are_untouched() {
        let mut m = MeshData {
            points: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            tris: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
            ..MeshData::default()
        };
        assert_eq!(split_nonmanifold(&mut m), None);
    }
}
