//! Renumbering along a Z-order curve, so that the passes' walks stay in
//! cache.

use super::remeshing::Remeshing;
use glam::DVec3;
use rayon::prelude::*;

impl Remeshing<'_> {
    /// Drops dead vertices and triangles and renumbers both along a
    /// Z-order curve through the vertices' positions
    /// ([`Connectivity::renumber`]): splits append their vertices at the
    /// end and collapses leave holes, and after a round the passes' walks
    /// would jump across memory at every step.
    pub fn renumber(&mut self) {
        let live: Vec<u32> = (0..self.vertices.len() as u32)
            .filter(|&v| self.mesh.is_vertex_alive(v))
            .collect();
        let (lo, hi) = live.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &v| {
                let x = self.vertices[v as usize].x;
                (lo.min(x), hi.max(x))
            },
        );
        let scale = (Z_CELLS - 1.0) / (hi - lo).max_element().max(f64::MIN_POSITIVE);
        let mut keyed: Vec<(u64, u32)> = live
            .par_iter()
            .map(|&v| {
                let q = ((self.vertices[v as usize].x - lo) * scale).as_uvec3();
                (z_order(q.x) | z_order(q.y) << 1 | z_order(q.z) << 2, v)
            })
            .collect();
        keyed.par_sort_unstable();
        let order: Vec<u32> = keyed.into_iter().map(|(_, v)| v).collect();
        self.mesh.renumber(&order);
        self.vertices = order.iter().map(|&v| self.vertices[v as usize]).collect();
        self.size = order.iter().map(|&v| self.size[v as usize]).collect();
        self.pinned = order.iter().map(|&v| self.pinned[v as usize]).collect();
        self.yields = order.iter().map(|&v| self.yields[v as usize]).collect();
        self.size_bound = order.iter().map(|&v| self.size_bound[v as usize]).collect();
    }
}

/// Cells per axis of [`Remeshing::renumber`]'s Z-order grid (21 bits, so
/// that three interleaved fit in 64).
const Z_CELLS: f64 = (1u32 << 21) as f64;

/// The bits of x (below 2²¹) spread to every third bit.
fn z_order(x: u32) -> u64 {
    let mut x = x as u64 & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}
