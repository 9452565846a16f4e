//! What a mesh is worth: angles and shape quality per triangle, curvature
//! per vertex, and the chord error re-measured with snap (the true distance
//! to the surface, not to the same-parameter point).

use super::by_chunks::{chunk_size, map_by_chunks};
use super::SurfaceMesh;
use crate::error::Result;
use crate::geometry::{area_normal, max_cosine};
use crate::snap::{project, FewSnaps};
use crate::surface::{Curvature, Surface};
use glam::DVec3;
use rayon::prelude::*;

/// Probes [`SurfaceMesh::snap_deviation`] snaps at a time, from the
/// largest bound down: enough to keep the threads busy, few enough that
/// it stops soon after the maximum is certain.
const SNAP_BATCH: usize = 256;

/// Shape of one output triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleQuality {
    /// Smallest angle, degrees.
    pub min_angle: f64,
    /// 4√3 · area / Σ edge² : 1 for equilateral, 0 for degenerate.
    pub shape: f64,
}

/// Summary over all triangles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshQuality {
    /// Smallest angle of any triangle, degrees.
    pub min_angle: f64,
    /// Mean over triangles of their smallest angle, degrees.
    pub mean_min_angle: f64,
    /// Smallest shape quality.
    pub min_shape: f64,
    /// Share of triangles whose smallest angle is below 20°, and 10°.
    pub below_20: f64,
    pub below_10: f64,
    /// Triangles below 20° whose smallest angle a feature forces: it sits
    /// between two hard edges, or at a corner (a vertex with other than two
    /// hard edges), where the input's own sector may be that narrow, or all
    /// three corners lie on hard edges (a triangle bridging crease curves
    /// that come closer than its size).
    pub below_20_at_features: usize,
    /// Edge lengths (each edge once): smallest, 5th percentile, median,
    /// 95th percentile, largest.
    pub edge_lengths: [f64; 5],
}

/// An output edge shorter than a length ([`SurfaceMesh::short_edges`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShortEdge {
    /// Its end vertices, the lower index first.
    pub ends: [u32; 2],
    pub length: f64,
    /// Whether a feature forces it: both ends lie on hard edges (two
    /// crease curves, or a curve and a corner, closer than the size).
    pub forced: bool,
}

fn triangle_quality(p: [DVec3; 3]) -> TriangleQuality {
    let min_angle = max_cosine(p[0], p[1], p[2])
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees();
    let area2 = area_normal(p).length();
    let squares: f64 = (0..3).map(|k| p[k].distance_squared(p[(k + 1) % 3])).sum();
    let shape = if squares > 0.0 {
        2.0 * 3f64.sqrt() * area2 / squares
    } else {
        0.0
    };
    TriangleQuality { min_angle, shape }
}

impl SurfaceMesh {
    /// Quality of every triangle, in triangle order.
    pub fn triangle_quality(&self) -> Vec<TriangleQuality> {
        self.triangles
            .par_iter()
            .map(|t| triangle_quality(t.map(|i| self.points[i as usize])))
            .collect()
    }

    /// The pairs of triangles that cross (meet anywhere but in the
    /// vertices and edges they share; see [`crate::geometry::crossings`]):
    /// a volume mesher refuses a surface with one.
    pub fn crossings(&self) -> Vec<[u32; 2]> {
        crate::geometry::crossings::crossings(&self.points, &self.triangles)
    }

    /// Minimum and mean angles and the worst shape.
    pub fn quality(&self) -> MeshQuality {
        let q = self.triangle_quality();
        let n = q.len().max(1) as f64;
        let share = |limit: f64| q.par_iter().filter(|q| q.min_angle < limit).count() as f64 / n;
        let mut lengths: Vec<f64> = self
            .unique_edges()
            .par_iter()
            .map(|&[a, b]| self.points[a as usize].distance(self.points[b as usize]))
            .collect();
        lengths.par_sort_unstable_by(f64::total_cmp);
        let at = |f: f64| {
            lengths
                .get(((lengths.len().max(1) - 1) as f64 * f).round() as usize)
                .copied()
                .unwrap_or(0.0)
        };
        let below_20_at_features = self.forced_small_angles(20.0);
        MeshQuality {
            below_20_at_features,
            min_angle: q.iter().map(|q| q.min_angle).fold(f64::INFINITY, f64::min),
            mean_min_angle: q.iter().map(|q| q.min_angle).sum::<f64>() / n,
            min_shape: q.iter().map(|q| q.shape).fold(f64::INFINITY, f64::min),
            below_20: share(20.0),
            below_10: share(10.0),
            edge_lengths: [at(0.0), at(0.05), at(0.5), at(0.95), at(1.0)],
        }
    }

    /// The edges shorter than `length`, each once, the shortest first
    /// (ties by their ends). A remesher's edge far below the size it was
    /// asked for is a degenerate one unless a feature forces it.
    pub fn short_edges(&self, length: f64) -> Vec<ShortEdge> {
        let degree = self.hard_degrees();
        let mut short: Vec<ShortEdge> = self
            .unique_edges()
            .into_par_iter()
            .map(|ends| ShortEdge {
                ends,
                length: self.points[ends[0] as usize].distance(self.points[ends[1] as usize]),
                forced: ends.iter().all(|&v| degree[v as usize] > 0),
            })
            .filter(|e| e.length < length)
            .collect();
        short.sort_by(|a, b| a.length.total_cmp(&b.length).then(a.ends.cmp(&b.ends)));
        short
    }

    /// Every edge once, as its ends (the lower first), in order.
    fn unique_edges(&self) -> Vec<[u32; 2]> {
        let mut edges: Vec<[u32; 2]> = self
            .triangles
            .par_iter()
            .flat_map_iter(|t| (0..3).map(move |k| [t[k], t[(k + 1) % 3]]))
            .map(|[a, b]| [a.min(b), a.max(b)])
            .collect();
        edges.par_sort_unstable();
        edges.dedup();
        edges
    }

    /// Per vertex: how many hard edges end at it (saturating).
    fn hard_degrees(&self) -> Vec<u8> {
        let mut degree = vec![0u8; self.points.len()];
        for &v in self.hard_edges.iter().flatten() {
            degree[v as usize] = degree[v as usize].saturating_add(1);
        }
        degree
    }

    /// The triangles whose smallest angle is below `limit` degrees and sits
    /// at a feature (see [`MeshQuality::below_20_at_features`]).
    fn forced_small_angles(&self, limit: f64) -> usize {
        let key = |a: u32, b: u32| (a.min(b), a.max(b));
        let hard: std::collections::HashSet<(u32, u32)> =
            self.hard_edges.iter().map(|e| key(e[0], e[1])).collect();
        let degree = self.hard_degrees();
        let cos_limit = limit.to_radians().cos();
        self.triangles
            .par_iter()
            .filter(|t| {
                let p = t.map(|i| self.points[i as usize]);
                // The corner with the smallest angle (largest cosine).
                let cosine = |k: usize| {
                    let (u, v) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
                    u.dot(v) / (u.length() * v.length())
                };
                let k = (0..3)
                    .max_by(|&a, &b| cosine(a).total_cmp(&cosine(b)))
                    .expect("three corners");
                if !(cosine(k) > cos_limit) {
                    return false;
                }
                let (v, a, b) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let corner = degree[v as usize] != 0 && degree[v as usize] != 2;
                let bridge = t.iter().all(|&u| degree[u as usize] > 0);
                corner || bridge || (hard.contains(&key(v, a)) && hard.contains(&key(v, b)))
            })
            .count()
    }

    /// Exact curvature at every vertex (unreliable, and zero, exactly at
    /// special vertices: see [`Curvature::reliable`]). On a large net,
    /// evaluated chunk by chunk ([`super::by_chunks`]): the same bits, but
    /// without making every patch of `surface` and keeping them.
    pub fn vertex_curvature(&self, surface: &Surface) -> Result<Vec<Curvature>> {
        let chunk = chunk_size(surface.net().triangles().len());
        map_by_chunks(surface, &self.params, chunk, |s, t, v, w| {
            s.curvature(t, v, w)
        })
    }

    /// The largest distance from the mesh to the surface at the centroid of
    /// every triangle and the midpoint of every edge, by snap (the global
    /// closest point, certified).
    ///
    /// Certifying every probe costs twice the meshing (bunny00 at 0.3%:
    /// 19 s against 9 s), and the maximum needs few of them: any surface
    /// point bounds a probe's distance from above. So every probe is first
    /// projected locally from its hint (the chart's parameters, or the
    /// surface point of its heaviest corner), which gives that bound;
    /// then, from the largest bound down, probes are snapped in batches
    /// until the next bound is no larger than the largest distance
    /// snapped. No probe left can be farther: the answer is the certified
    /// maximum, as if every probe were snapped. The few snaps search an
    /// index of whole patches ([`crate::snap::FewSnaps`]), built before
    /// them: the full index, built by the first of them inside the
    /// parallel loop on one thread while the others waited, took most of
    /// the check (bunny00 at 0.3% on two threads: 2.16 s for the check
    /// with it, 0.84 s with the index of whole patches).
    pub fn snap_deviation(&self, surface: &Surface) -> Result<f64> {
        let probes = self.probes(surface.net());
        let mut bounds: Vec<(f64, usize)> = probes
            .par_iter()
            .enumerate()
            .map(|(i, &(x, (tri, v, w)))| {
                let d =
                    project(surface, x, tri as usize, v, w).map_or(f64::INFINITY, |s| s.distance);
                (d, i)
            })
            .collect();
        bounds.par_sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let mut worst: f64 = 0.0;
        let mut snaps = None;
        for batch in bounds.chunks(SNAP_BATCH) {
            if batch[0].0 <= worst {
                break;
            }
            let snaps = snaps.get_or_insert_with(|| FewSnaps::new(surface));
            let snapped = batch
                .par_iter()
                .filter(|&&(bound, _)| bound > worst)
                .map(|&(_, i)| {
                    let (x, (tri, v, w)) = probes[i];
                    Ok(snaps.snap_near(x, tri as usize, v, w)?.distance)
                })
                .try_reduce(|| 0.0, |a, b| Ok(a.max(b)))?;
            worst = worst.max(snapped);
        }
        Ok(worst)
    }

    /// The chord-error probes: each triangle's centroid and each edge's
    /// midpoint, with the hint their snap starts from (the same weights in
    /// the chart, or without charts the surface point of the heaviest
    /// corner).
    fn probes(&self, net: &crate::ControlNet) -> Vec<(DVec3, (u32, f64, f64))> {
        // Probes: (triangle, weights of its corners); each edge once.
        let mut edges: Vec<(u64, u32, u8)> = Vec::with_capacity(3 * self.triangles.len());
        for (t, tri) in self.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k] as u64, tri[(k + 1) % 3] as u64);
                edges.push(((a.min(b) << 32) | a.max(b), t as u32, k as u8));
            }
        }
        edges.par_sort_unstable();
        edges.dedup_by_key(|e| e.0);
        let centroids = (0..self.triangles.len())
            .into_par_iter()
            .map(|t| (t, [1.0 / 3.0; 3]));
        let midpoints = edges.par_iter().map(|&(_, t, k)| {
            let mut weights = [0.0; 3];
            weights[k as usize] = 0.5;
            weights[(k as usize + 1) % 3] = 0.5;
            (t as usize, weights)
        });
        centroids
            .chain(midpoints)
            .map(|(t, weights)| {
                let x: DVec3 = (0..3)
                    .map(|k| weights[k] * self.points[self.triangles[t][k] as usize])
                    .sum();
                let hint = if self.charts.is_empty() {
                    let k = (0..3).fold(0, |b, k| if weights[k] > weights[b] { k } else { b });
                    let p = self.params[self.triangles[t][k] as usize];
                    (p.tri, p.v, p.w)
                } else {
                    let params = self.triangle_params(net, t);
                    let v = (0..3).map(|k| weights[k] * params[k].v).sum::<f64>();
                    let w = (0..3).map(|k| weights[k] * params[k].w).sum::<f64>();
                    (params[0].tri, v, w)
                };
                (x, hint)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parameters::SurfacePoint;

    /// Two triangles over a unit square, one corner moved to within
    /// `gap` of another (vertex 2 next to vertex 1), and the hard edges
    /// given.
    fn square(gap: f64, hard_edges: Vec<[u32; 2]>) -> SurfaceMesh {
        let points = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, gap, 0.0), DVec3::Y];
        SurfaceMesh {
            params: vec![
                SurfacePoint {
                    tri: 0,
                    v: 0.0,
                    w: 0.0
                };
                points.len()
            ],
            points,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            charts: Vec::new(),
            faces: vec![0, 0],
            hard_edge_curves: vec![0; hard_edges.len()],
            hard_edges,
            deviation: None,
            diagonal: 2f64.sqrt(),
        }
    }

    #[test]
    fn short_edges_are_found_once_and_forced_only_between_hard_vertices() {
        let free = square(1e-9, Vec::new());
        let short = free.short_edges(1e-6);
        assert_eq!(short.len(), 1, "{short:?}");
        assert_eq!(short[0].ends, [1, 2]);
        assert_eq!(short[0].length, 1e-9);
        assert!(!short[0].forced);
        assert!(free.short_edges(1e-9).is_empty(), "strictly shorter only");
        // Both ends on hard edges (a crease along the side 0-1 and one
        // along 2-3): forced. One end only: not.
        let both = square(1e-9, vec![[0, 1], [2, 3]]);
        assert!(both.short_edges(1e-6)[0].forced);
        let one = square(1e-9, vec![[0, 1]]);
        assert!(!one.short_edges(1e-6)[0].forced);
        assert!(square(0.5, Vec::new()).short_edges(1e-6).is_empty());
    }
}
