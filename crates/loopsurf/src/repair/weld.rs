//! `--weld EPS`: vertices that are nearly, not exactly, equal.
//!
//! Only vertices on open edges (edges of one triangle) are welded: a crack
//! between parts that should meet shows up as open edges on both sides,
//! while vertices inside the surface are connected already, and merging
//! those would collapse small triangles rather than close a crack.
//!
//! Greedy in file order, so the result does not depend on hashing: each
//! vertex merges into the first earlier *kept* vertex within the distance,
//! or is kept itself. Kept vertices are at least the distance apart, so a
//! grid of cells that size holds a bounded number of them per cell and the
//! weld is linear. (Not transitive on purpose: a chain of points each close
//! to the next does not collapse into one.)

use std::collections::HashMap;

use glam::DVec3;

use super::{edge_incidences, Repair};
use crate::io::MeshData;

/// Welds `mesh` at `eps` × its bounding-box diagonal, then drops the
/// triangles welding collapsed (two corners merged, or listed twice in the
/// file: a repeated vertex is a weld already made) or duplicated (the same
/// three corners as an earlier triangle, in either orientation).
pub(super) fn weld(mesh: &mut MeshData, eps: f64) -> Vec<Repair> {
    let distance = eps * diagonal(&mesh.points);
    let mut open = vec![false; mesh.points.len()];
    let incid = edge_incidences(mesh);
    for (k, &(edge, _)) in incid.iter().enumerate() {
        let alone =
            (k == 0 || incid[k - 1].0 != edge) && incid.get(k + 1).map_or(true, |x| x.0 != edge);
        if alone {
            for v in edge {
                open[v as usize] = true;
            }
        }
    }
    let target = merge_targets(&mesh.points, &open, distance);
    let merged = target.iter().enumerate().filter(|&(i, &t)| t != i).count();
    let mut report = Vec::new();
    let repeats = |t: &[i64; 3]| t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if merged == 0 && !mesh.tris.iter().any(repeats) {
        return report;
    }
    if merged > 0 {
        report.push(Repair::Welded { merged, distance });
    }
    for tri in &mut mesh.tris {
        for i in tri.iter_mut() {
            if let Some(&t) = usize::try_from(*i).ok().and_then(|i| target.get(i)) {
                *i = t as i64;
            }
        }
    }
    let (mut collapsed, mut duplicates) = (Vec::new(), Vec::new());
    let mut seen = std::collections::HashSet::new();
    let keep: Vec<bool> = mesh
        .tris
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            if repeats(tri) {
                collapsed.push(t);
                return false;
            }
            let mut key = *tri;
            key.sort_unstable();
            if !seen.insert(key) {
                duplicates.push(t);
                return false;
            }
            true
        })
        .collect();
    if !collapsed.is_empty() || !duplicates.is_empty() {
        retain_triangles(mesh, &keep);
        report.push(Repair::DroppedTriangles {
            collapsed,
            duplicates,
        });
    }
    report
}

/// For every vertex, the vertex it merges into (itself if kept); only the
/// `candidates` take part.
fn merge_targets(points: &[DVec3], candidates: &[bool], distance: f64) -> Vec<usize> {
    let mut target: Vec<usize> = (0..points.len()).collect();
    if distance <= 0.0 || !distance.is_finite() {
        return target;
    }
    let cell = |p: DVec3| (p / distance).floor().as_i64vec3().to_array();
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, &p) in points.iter().enumerate() {
        if !candidates[i] || !p.is_finite() {
            continue; // a non-finite point: validation names it
        }
        let c = cell(p);
        let mut found: Option<usize> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let key = [c[0] + dx, c[1] + dy, c[2] + dz];
                    for &k in grid.get(&key).into_iter().flatten() {
                        if points[k].distance(p) <= distance && found.map_or(true, |f| k < f) {
                            found = Some(k);
                        }
                    }
                }
            }
        }
        match found {
            Some(k) => target[i] = k,
            None => grid.entry(c).or_default().push(i),
        }
    }
    target
}

/// The bounding-box diagonal of the finite points.
fn diagonal(points: &[DVec3]) -> f64 {
    let finite = points.iter().filter(|p| p.is_finite());
    let lo = finite.clone().fold(DVec3::INFINITY, |a, &p| a.min(p));
    let hi = finite.fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
    if lo.x <= hi.x {
        (hi - lo).length()
    } else {
        0.0
    }
}

/// Keeps the triangles marked in `keep`, with their lines and components.
fn retain_triangles(mesh: &mut MeshData, keep: &[bool]) {
    fn retain<T>(v: &mut Vec<T>, keep: &[bool]) {
        if v.len() == keep.len() {
            let mut k = keep.iter();
            v.retain(|_| *k.next().unwrap_or(&true));
        }
    }
    retain(&mut mesh.tris, keep);
    retain(&mut mesh.tri_lines, keep);
    if let Some(c) = &mut mesh.components {
        retain(c, keep);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(points: &[[f64; 3]], tris: &[[i64; 3]]) -> MeshData {
        MeshData {
            points: points.iter().map(|&p| DVec3::from_array(p)).collect(),
            tris: tris.to_vec(),
            tri_lines: (1..=tris.len()).collect(),
            ..MeshData::default()
        }
    }

    #[test]
    fn near_corners_merge_into_the_first_and_collapsed_triangles_go() {
        // Two triangles of a square and two copies of the first, one with
        // corners 1 and 2 written with round-off (4 and 5), one collapsed.
        let mut m = mesh(
            &[
                [0., 0., 0.],
                [1., 0., 0.],
                [1., 1., 0.],
                [0., 1., 0.],
                [1. + 1e-9, 0., 0.],
                [1., 1., 1e-9],
            ],
            &[[0, 1, 2], [0, 4, 5], [1, 4, 2], [0, 2, 3]],
        );
        let report = weld(&mut m, 1e-6);
        assert_eq!(m.tris, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.tri_lines, vec![1, 4]);
        assert!(
            matches!(report[0], Repair::Welded { merged: 2, distance } if (distance - 1e-6 * 2f64.sqrt()).abs() < 1e-12)
        );
        assert_eq!(
            report[1],
            Repair::DroppedTriangles {
                collapsed: vec![2],
                duplicates: vec![1]
            }
        );
        // The vertex list is untouched.
        assert_eq!(m.points.len(), 6);
    }

    #[test]
    fn chains_do_not_collapse() {
        let points: Vec<DVec3> = (0..5).map(|i| DVec3::new(0.6 * i as f64, 0., 0.)).collect();
        // distance 1: 1 → 0, 2 kept (1.2 from 0), 3 → 2, 4 kept.
        assert_eq!(merge_targets(&points, &[true; 5], 1.0), vec![0, 0, 2, 2, 4]);
    }

    #[test]
    fn inner_vertices_are_never_merged() {
        // A square fanned around vertex 4, which lies 1e-9 from corner 0:
        // a tiny but real edge inside the surface, not a crack.
        let mut m = mesh(
            &[
                [0., 0., 0.],
                [1., 0., 0.],
                [1., 1., 0.],
                [0., 1., 0.],
                [1e-9, 1e-9, 0.],
            ],
            &[[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
        );
        let before = m.tris.clone();
        assert!(weld(&mut m, 1e-6).is_empty());
        assert_eq!(m.tris, before);
    }
}
