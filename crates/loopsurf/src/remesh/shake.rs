//! Shaking free vertices off a fixed point of the other passes.

use super::remeshing::Remeshing;
use super::vertices::Vertex;
use rayon::prelude::*;

/// A shake may not make a triangle's smallest angle smaller than acos of
/// this (30°), unless it was smaller already.
const SHAKE_WORST_COSINE: f64 = 0.866;

impl Remeshing<'_> {
    /// Shakes every free vertex by up to `amount` of its target size in a
    /// pseudo-random tangent direction (fixed by its index, so the result
    /// is deterministic). A start copied from a lattice of right triangles
    /// (a flat CAD face's chart) is a fixed point of the other passes —
    /// valence 6 everywhere, every vertex at its centroid, every diagonal
    /// co-circular — at 45° triangles; shaken, the flips and relaxation
    /// find the equilateral arrangement. Returns the number moved.
    pub fn shake(&mut self, amount: f64) -> usize {
        let moves: Vec<Option<Vertex>> = (0..self.vertices.len() as u32)
            .into_par_iter()
            .map(|v| {
                let vertex = &self.vertices[v as usize];
                if !self.mesh.is_vertex_alive(v) || !vertex.is_free() || self.is_pinned(v) {
                    return None;
                }
                let face = self.face(self.mesh.outgoing(v).next()?);
                // A splitmix64 hash of the index: an angle and a radius.
                let mut z = (v as u64).wrapping_add(0x9e3779b97f4a7c15);
                z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
                z ^= z >> 31;
                let angle = (z & 0xffff_ffff) as f64 / 4294967296.0 * std::f64::consts::TAU;
                let radius = (z >> 32) as f64 / 4294967296.0 * amount * self.size[v as usize];
                let n = vertex.normal;
                let e1 = n.any_orthonormal_vector();
                let e2 = n.cross(e1);
                let target = vertex.x + radius * (angle.cos() * e1 + angle.sin() * e2);
                self.placer.nudge(vertex, target, face)
            })
            .collect();
        // A shake may worsen angles, but not below 30°.
        self.apply_moves(moves, Some(SHAKE_WORST_COSINE))
    }
}
