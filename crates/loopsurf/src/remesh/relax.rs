//! Tangential relaxation: each vertex towards the centroid of its
//! triangles (a curve vertex along its curve), kept only where its
//! triangles stay valid.

use super::connectivity::prev;
use super::remeshing::Remeshing;
use super::vertices::{Kind, Vertex};
use crate::geometry::area_normal;
use crate::topology::NONE;
use glam::DVec3;
use rayon::prelude::*;

impl Remeshing<'_> {
    /// Moves every free vertex towards the area-weighted centroid of its
    /// triangles within its tangent plane, and every curve vertex towards
    /// the middle of its two curve neighbours along the curve; each lands on
    /// the surface (curve) by projection and stays only if its triangles
    /// stay valid. Returns the number moved.
    pub fn relax(&mut self) -> usize {
        self.relax_with(None)
    }

    /// [`Remeshing::relax`] keeping only the moves that leave the smallest
    /// angle around the vertex no smaller.
    pub fn relax_guarded(&mut self) -> usize {
        // No cosine is below −1: the floor is each vertex's own worst.
        self.relax_with(Some(-1.0))
    }

    fn relax_with(&mut self, floor: Option<f64>) -> usize {
        let targets: Vec<Option<Vertex>> = (0..self.vertices.len() as u32)
            .into_par_iter()
            .map(|v| self.relaxed(v))
            .collect();
        self.apply_moves(targets, floor)
    }

    /// Applies moves (one per vertex, `None` for none) one by one against
    /// the mesh as it is by then: each only if [`Remeshing::accept`] takes
    /// its triangles and, with `floor`, none of them gets a smallest-angle
    /// cosine above it unless it had one already. Returns the number moved.
    pub(super) fn apply_moves(
        &mut self,
        targets: Vec<Option<Vertex>>,
        floor: Option<f64>,
    ) -> usize {
        let mut moved = 0;
        let mut around: Vec<([u32; 3], u32)> = Vec::new();
        for (v, target) in targets.into_iter().enumerate() {
            let Some(target) = target else { continue };
            let v = v as u32;
            around.clear();
            around.extend(
                self.mesh
                    .outgoing(v)
                    .map(|h| (self.mesh.corners(h), self.face(h))),
            );
            let worst = |moved| {
                around
                    .iter()
                    .map(|&(ids, _)| self.worst_cosine(ids, moved))
                    .fold(-1.0, f64::max)
            };
            let fair = floor.map_or(true, |f| worst(Some((v, &target))) <= worst(None).max(f));
            let ok = fair
                && self.accept(
                    around.iter().map(|&(ids, f)| (ids, f, Some((v, &target)))),
                    around.iter().map(|&(ids, f)| (ids, f, None)),
                );
            if ok {
                self.vertices[v as usize] = target;
                moved += 1;
            }
        }
        moved
    }

    /// Where relaxation would put vertex v, if anywhere.
    fn relaxed(&self, v: u32) -> Option<Vertex> {
        if !self.mesh.is_vertex_alive(v) || self.is_pinned(v) {
            return None;
        }
        let vertex = &self.vertices[v as usize];
        match vertex.kind {
            Kind::Corner { .. } => None,
            Kind::Free => self.relaxed_free(v, vertex),
            Kind::Curve { curve, t } => self.relaxed_on_curve(v, curve, t),
        }
    }

    /// Free vertex v moved towards the weighted centroid of its triangles
    /// within its tangent plane, and put on the surface.
    fn relaxed_free(&self, v: u32, vertex: &Vertex) -> Option<Vertex> {
        let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
        let mut face = NONE;
        for h in self.mesh.outgoing(v) {
            // Centroids weighted by area in units of the local
            // size: where sizes grade, plain area would pull every
            // vertex towards the coarse side.
            let ids = self.mesh.corners(h);
            let [a, b, c] = ids.map(|i| self.vertices[i as usize].x);
            let size = ids.iter().map(|&i| self.size[i as usize]).sum::<f64>() / 3.0;
            let w = area_normal([a, b, c]).length() / (size * size);
            sum += w * (a + b + c) / 3.0;
            weight += w;
            face = self.face(h);
        }
        if !(weight > 0.0) {
            return None;
        }
        let n = vertex.normal;
        let step = sum / weight - vertex.x;
        let target = vertex.x + step - n * n.dot(step);
        // As for a split: a landing far from the target is on
        // another sheet.
        let reach = step.length().max(1e-3 * self.size[v as usize]);
        self.placer
            .nudge(vertex, target, face)
            .filter(|m| m.x.distance(target) <= reach)
    }

    /// Curve vertex v (on `curve` at t) moved between its two neighbours
    /// along the curve.
    fn relaxed_on_curve(&self, v: u32, curve: u32, t: f64) -> Option<Vertex> {
        let mut ends = [DVec3::ZERO; 2];
        let mut sizes = [0.0; 2];
        let mut params = [None; 2];
        let mut count = 0;
        let mut visit = |h: u32, other: u32| {
            if self.mesh.edge_label[h as usize] == curve {
                if count < 2 {
                    let o = &self.vertices[other as usize];
                    ends[count] = o.x;
                    sizes[count] = self.size[other as usize];
                    params[count] = self.placer.t_on(o, curve, Some(t));
                }
                count += 1;
            }
        };
        let mut last = NONE;
        for h in self.mesh.outgoing(v) {
            visit(h, self.mesh.dest(h));
            last = h;
        }
        if self.mesh.is_border_vertex(v) {
            let p = prev(last);
            visit(p, self.mesh.origin(p));
        }
        let (2, [Some(t0), Some(t1)]) = (count, params) else {
            return None;
        };
        // It stays between its neighbours along the curve, near
        // the point of their chord that splits it as their sizes
        // ask (the midpoint where sizes are uniform); where that
        // slides it much nearer one than the other (down one arm
        // of a sharp turn of a boundary), at the point as far from
        // both.
        let [w0, w1] = sizes.map(|h| h + self.size[v as usize]);
        let near =
            self.placer
                .on_curve((w1 * ends[0] + w0 * ends[1]) / (w0 + w1), curve, t, t0, t1)?;
        let [d0, d1] = ends.map(|x| near.x.distance(x));
        let boundary = self.placer.surface.model().curves()[curve as usize]
            .faces
            .contains(&None);
        if !boundary || d0.min(d1) >= 0.5 * d0.max(d1) {
            Some(near)
        } else {
            self.placer.balanced_on_curve(curve, t, [t0, t1], ends)
        }
    }
}
