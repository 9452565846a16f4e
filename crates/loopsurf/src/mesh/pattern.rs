//! How one control triangle's parameter domain is triangulated, given the
//! number of segments on each of its sides and its own interior level N.
//!
//! Points (local numbering): the boundary first, side by side — corner s,
//! then the inner points of side s in the side's direction — then the
//! interior lattice points (i, j)/N with i, j ≥ 1 and i + j ≤ N − 1, row by
//! row. When every side has N segments the domain is the uniform lattice
//! triangulation (similar copies of the triangle). Otherwise the lattice
//! points one row in from the sides form an inner triangle, triangulated as
//! the lattice, and each side is zipped to the parallel side of the inner
//! triangle: the strip between them is a convex trapezoid in (v, w), so any
//! zipper is a valid triangulation, and the shorter 3D diagonal is taken at
//! every step. Sides carry at least N segments (an edge takes the finer of
//! its two triangles), so the strips only ever coarsen inwards.

use glam::{DVec2, DVec3};

/// The parameter of the point at fraction `t` along side `s`, which runs from
/// corner s to corner s + 1 (corners (0,0), (1,0), (0,1)).
pub(crate) fn side_param(s: usize, t: f64) -> DVec2 {
    match s {
        0 => DVec2::new(t, 0.0),
        1 => DVec2::new(1.0 - t, t),
        _ => DVec2::new(0.0, 1.0 - t),
    }
}

/// The segment counts of one control triangle: per side, and its interior
/// lattice level; and whether it is a sliver cut by its edges' lengths
/// instead ([`super::isotropic`], its spacing its longest side over the
/// level).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Pattern {
    pub sides: [u32; 3],
    pub level: u32,
    pub isotropic: bool,
}

impl Pattern {
    /// Number of boundary points (each side's start corner and inner points).
    pub fn boundary_len(&self) -> usize {
        self.sides.iter().map(|&n| n as usize).sum()
    }

    /// Local index of the first point of side s (its start corner).
    fn side_start(&self, s: usize) -> u32 {
        self.sides[..s].iter().sum()
    }

    /// Local indices of the three corners.
    pub fn corners(&self) -> [u32; 3] {
        [0, 1, 2].map(|s| self.side_start(s))
    }

    pub fn is_uniform(&self) -> bool {
        self.sides.iter().all(|&n| n == self.level)
    }

    /// The transition pattern with a level below 3 has no inner triangle: the
    /// sides are fanned to the centroid instead.
    fn centroid_fan(&self) -> bool {
        !self.is_uniform() && self.level < 3
    }

    /// Number of interior points.
    pub fn interior_len(&self) -> usize {
        if self.centroid_fan() {
            return 1;
        }
        let n = self.level as usize;
        n.saturating_sub(1) * n.saturating_sub(2) / 2
    }

    /// Parameters of the interior points, in local order after the boundary.
    pub fn interior_params(&self) -> Vec<DVec2> {
        if self.centroid_fan() {
            return vec![DVec2::splat(1.0 / 3.0)];
        }
        let n = self.level as usize;
        let inv = 1.0 / n as f64;
        let mut out = Vec::with_capacity(self.interior_len());
        for j in 1..n.saturating_sub(1) {
            for i in 1..n - j {
                out.push(DVec2::new(i as f64 * inv, j as f64 * inv));
            }
        }
        out
    }

    /// Parameters of the boundary points, side by side from each side's
    /// start corner.
    pub fn boundary_params(&self) -> Vec<DVec2> {
        let mut out = Vec::with_capacity(self.boundary_len() + self.interior_len());
        for s in 0..3 {
            let n = self.sides[s];
            out.extend((0..n).map(|k| side_param(s, k as f64 / n as f64)));
        }
        out
    }

    /// Parameters of every local point: boundary, then interior.
    pub fn params(&self) -> Vec<DVec2> {
        let mut out = self.boundary_params();
        out.extend(self.interior_params());
        debug_assert_eq!(out.len(), self.boundary_len() + self.interior_len());
        out
    }

    /// Local index of lattice point (i, j) of the uniform pattern.
    fn lattice(&self, i: u32, j: u32) -> u32 {
        let n = self.level;
        if j == 0 {
            i
        } else if i + j == n {
            n + j
        } else if i == 0 {
            2 * n + (n - j)
        } else {
            self.interior(i, j)
        }
    }

    /// Local index of interior lattice point (i, j), i, j ≥ 1, i + j < N.
    fn interior(&self, i: u32, j: u32) -> u32 {
        let n = self.level;
        let row_start = (j - 1) * (n - 1) - (j - 1) * j / 2;
        self.boundary_len() as u32 + row_start + (i - 1)
    }

    /// Index of the first transition-strip triangle in [`Pattern::triangles`]
    /// (the lattice triangles come first); none in a uniform pattern.
    pub fn strip_start(&self) -> usize {
        if self.is_uniform() {
            (self.level * self.level) as usize
        } else if self.centroid_fan() {
            0
        } else {
            ((self.level - 3) * (self.level - 3)) as usize
        }
    }

    /// The triangles, counter-clockwise in (v, w) like the control triangle.
    /// `pos` holds the 3D position of every local point (for the zipper).
    pub fn triangles(&self, pos: &[DVec3]) -> Vec<[u32; 3]> {
        let mut tris = Vec::new();
        if self.is_uniform() {
            self.lattice_triangles(0, self.level, &mut tris, |p, i, j| p.lattice(i, j));
            return tris;
        }
        let inner: [Vec<u32>; 3] = if self.centroid_fan() {
            let c = self.boundary_len() as u32;
            [vec![c], vec![c], vec![c]]
        } else {
            let n = self.level;
            self.lattice_triangles(1, n - 3, &mut tris, |p, i, j| p.interior(i, j));
            [
                (1..=n - 2).map(|i| self.interior(i, 1)).collect(),
                (1..=n - 2).map(|j| self.interior(n - 1 - j, j)).collect(),
                (1..=n - 2).rev().map(|j| self.interior(1, j)).collect(),
            ]
        };
        let nb = self.boundary_len() as u32;
        for (s, inner) in inner.iter().enumerate() {
            let start = self.side_start(s);
            let outer: Vec<u32> = (0..=self.sides[s]).map(|k| (start + k) % nb).collect();
            zip(&outer, inner, pos, &mut tris);
        }
        tris
    }

    /// The lattice triangles of the sub-triangle with corner (first, first)
    /// and `segments` segments a side, at lattice level N.
    fn lattice_triangles(
        &self,
        first: u32,
        segments: u32,
        tris: &mut Vec<[u32; 3]>,
        index: impl Fn(&Self, u32, u32) -> u32,
    ) {
        let top = first + segments;
        for j in first..top {
            for i in first..top + first - j {
                let (a, b, c) = (
                    index(self, i, j),
                    index(self, i + 1, j),
                    index(self, i, j + 1),
                );
                tris.push([a, b, c]);
                if i + j + 1 < top + first {
                    tris.push([b, index(self, i + 1, j + 1), c]);
                }
            }
        }
    }
}

/// Triangulates the strip between an outer chain and the parallel inner
/// chain (same direction, inner on the left), taking the shorter 3D
/// diagonal at each step: the chains advance in step, so no point fans out
/// further than the ratio of their segment counts requires. (Choosing by
/// angle instead is myopic: it can fan one corner to a whole chain.)
fn zip(outer: &[u32], inner: &[u32], pos: &[DVec3], tris: &mut Vec<[u32; 3]>) {
    let (mut a, mut b) = (0, 0);
    let (na, nb) = (outer.len() - 1, inner.len() - 1);
    let p = |k: usize| pos[outer[k] as usize];
    let q = |k: usize| pos[inner[k] as usize];
    while a < na || b < nb {
        let advance_outer = if a == na {
            false
        } else if b == nb {
            true
        } else {
            p(a + 1).distance_squared(q(b)) <= p(a).distance_squared(q(b + 1))
        };
        if advance_outer {
            tris.push([outer[a], outer[a + 1], inner[b]]);
            a += 1;
        } else {
            tris.push([outer[a], inner[b + 1], inner[b]]);
            b += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(p: &[DVec2], t: [u32; 3]) -> f64 {
        let [a, b, c] = t.map(|i| p[i as usize]);
        (b - a).perp_dot(c - a) / 2.0
    }

    /// Every pattern tiles the parameter triangle: positive areas summing to
    /// 1/2, every point used, every edge shared by at most two triangles and
    /// boundary edges exactly the side segments.
    #[test]
    fn patterns_tile_the_triangle() {
        for level in 1..9 {
            for extra in [
                [0, 0, 0],
                [1, 0, 0],
                [0, 2, 5],
                [3, 3, 1],
                [level, 0, 2 * level],
            ] {
                let sides = [0, 1, 2].map(|s| level + extra[s]);
                let p = Pattern {
                    sides,
                    level,
                    isotropic: false,
                };
                let params = p.params();
                let pos: Vec<DVec3> = params.iter().map(|q| q.extend(0.0)).collect();
                let tris = p.triangles(&pos);
                let strips = p.strip_start();
                assert!(strips <= tris.len(), "{p:?}");
                if p.is_uniform() {
                    assert_eq!(strips, tris.len());
                }
                let total: f64 = tris.iter().map(|&t| area(&params, t)).sum();
                assert!((total - 0.5).abs() < 1e-12, "{p:?}: area {total}");
                for &t in &tris {
                    assert!(
                        area(&params, t) > 1e-6 / (level * level) as f64,
                        "{p:?} {t:?}"
                    );
                }
                let mut edges = std::collections::HashMap::new();
                for t in &tris {
                    for k in 0..3 {
                        *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
                    }
                }
                let nb = p.boundary_len() as u32;
                for (&(a, b), &count) in &edges {
                    assert_eq!(count, 1, "{p:?}: directed edge {a}-{b} twice");
                    if !edges.contains_key(&(b, a)) {
                        assert!(a < nb && b == (a + 1) % nb, "{p:?}: open edge {a}-{b}");
                    }
                }
                let boundary = edges.keys().filter(|(a, b)| !edges.contains_key(&(*b, *a)));
                assert_eq!(boundary.count(), nb as usize, "{p:?}");
            }
        }
    }
}
