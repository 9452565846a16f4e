//! Removing caps: triangles with a near-flat angle at a free vertex facing
//! a curve edge, which no flip or relaxation can open.

use super::connectivity::prev;
use super::remeshing::Remeshing;
use crate::topology::NONE;

/// A free vertex with an angle above this (degrees) opposite a curve edge
/// is a cap ([`Remeshing::remove_caps`]).
const CAP_ANGLE: f64 = 120.0;

impl Remeshing<'_> {
    /// Removes caps: a free vertex v whose angle in a triangle (a, b, v) is
    /// above [`CAP_ANGLE`], opposite a curve edge (a, b), sits too near the
    /// curve for any flip (the edge is fixed) or relaxation to make the
    /// triangle good. The curve edge is split at its point nearest v, and v
    /// merges into that new curve vertex: the cap vanishes, and v's other
    /// triangles take the curve vertex for v. Done only where the result
    /// passes the usual acceptance against the triangles it replaces.
    pub fn remove_caps(&mut self) -> usize {
        let cos_cap = CAP_ANGLE.to_radians().cos();
        let mut done = 0;
        for h in 0..self.mesh.num_half_edges() {
            if !self.mesh.is_alive(h)
                || self.mesh.edge_label[h as usize] == NONE
                || self.is_frozen(h)
            {
                continue;
            }
            let (a, b, v) = (
                self.mesh.origin(h),
                self.mesh.dest(h),
                self.mesh.origin(prev(h)),
            );
            if !self.vertices[v as usize].is_free() || self.is_pinned(v) {
                continue;
            }
            let [xa, xb, xv] = [a, b, v].map(|i| self.vertices[i as usize].x);
            let (u, w) = (xa - xv, xb - xv);
            if u.dot(w) / (u.length() * w.length()) > cos_cap {
                continue;
            }
            if self.remove_cap(h, v) {
                done += 1;
            }
        }
        done
    }

    /// [`Remeshing::remove_caps`] on the cap of half-edge h (a → b) with
    /// free corner v.
    fn remove_cap(&mut self, h: u32, v: u32) -> bool {
        let label = self.mesh.edge_label[h as usize];
        let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
        let (va, vb) = (&self.vertices[a as usize], &self.vertices[b as usize]);
        let ta = self.placer.t_on(va, label, None);
        let tb = self.placer.t_on(vb, label, ta);
        let ta = self.placer.t_on(va, label, tb).or(ta);
        let (Some(ta), Some(tb)) = (ta, tb) else {
            return false;
        };
        let mid = self.placer.mid_t(label, ta, tb);
        let x = self.vertices[v as usize].x;
        let Some(m) = self.placer.on_curve(x, label, mid, ta, tb) else {
            return false;
        };
        // The link condition after the split: v and the corner across the
        // curve must not be joined already.
        let g = self.mesh.opposite(h);
        let across = (g != NONE).then(|| self.mesh.origin(prev(g)));
        if across.is_some_and(|w| self.mesh.joined(v, w)) || self.mesh.is_border_vertex(v) {
            return false;
        }
        // a and b each lose their edge to v.
        if self.mesh.valence(a) <= 3 || self.mesh.valence(b) <= 3 {
            return false;
        }
        let id = self.vertices.len() as u32;
        let moved = Some((id, &m));
        let mut new = Vec::new();
        let mut old = Vec::new();
        for e in self.mesh.outgoing(v) {
            let tri = self.mesh.corners(e);
            old.push((tri, self.face(e), None));
            if tri.contains(&a) && tri.contains(&b) {
                continue;
            }
            new.push((
                tri.map(|x| if x == v { id } else { x }),
                self.face(e),
                moved,
            ));
        }
        if let Some(w) = across {
            let face = self.face(g);
            old.push((self.mesh.corners(g), face, None));
            new.push(([b, id, w], face, moved));
            new.push(([id, a, w], face, moved));
        }
        if !self.accept(new, old) {
            return false;
        }
        let size = self.size[v as usize];
        let id = self.mesh.add_vertex();
        self.push_vertex(m, size);
        self.mesh.split(h, id);
        let Some(e) = self.mesh.find(v, id) else {
            unreachable!("the split joins v to the new vertex");
        };
        self.mesh.collapse(e, v);
        true
    }
}
