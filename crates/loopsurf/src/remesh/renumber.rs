//! Renumbering along a Z-order curve, so that the passes' walks stay in
//! cache.

use super::remeshing::Remeshing;
use crate::geometry::z_order;
use glam::DVec3;

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
        let at: Vec<DVec3> = live.iter().map(|&v| self.vertices[v as usize].x).collect();
        let order: Vec<u32> = z_order(&at).into_iter().map(|i| live[i as usize]).collect();
        self.mesh.renumber(&order);
        self.vertices = order.iter().map(|&v| self.vertices[v as usize]).collect();
        self.size = order.iter().map(|&v| self.size[v as usize]).collect();
        self.pinned = order.iter().map(|&v| self.pinned[v as usize]).collect();
        self.yields = order.iter().map(|&v| self.yields[v as usize]).collect();
        self.size_bound = order.iter().map(|&v| self.size_bound[v as usize]).collect();
    }
}
