//! Splitting long edges, at their midpoints on the surface (or along their
//! curve).

use super::connectivity::prev;
use super::remeshing::Remeshing;
use super::vertices::Vertex;
use crate::topology::NONE;
use rayon::prelude::*;
use std::collections::HashSet;

/// Edges longer than this times their target are split (CGAL's and PMP's
/// bound; collapses stop at [`super::collapse::COLLAPSE_BELOW`]).
pub(super) const SPLIT_ABOVE: f64 = 4.0 / 3.0;

impl Remeshing<'_> {
    /// Splits every edge longer than [`SPLIT_ABOVE`] × its target, again
    /// and again until none is (or none can be), or until the mesh holds
    /// more than `limit` triangle slots (a bound on memory, checked
    /// after each sweep). Returns the count.
    ///
    /// An edge whose split was refused is tried again only once a
    /// triangle on it has changed (its opposite corners) or it is walked
    /// the other way (the midpoint's projection starts from the first
    /// end, and from one end it can stop on a feature where from the
    /// other it lands): on a surface that folds, refused splits are the
    /// many (mpi.off at 40°: some 5 000 in every sweep, a handful done,
    /// and each sweep placed every midpoint again). Making the split the
    /// same both ways, and the key with it, was tried: it changed which
    /// splits land on folded patches, and anchor.off came out 2.8–18%
    /// below 20° where this key gave 2.1% (both before crease triangles
    /// were checked at their centroid).
    pub fn split_long(&mut self, limit: usize) -> usize {
        let mut total = 0;
        let mut refused: HashSet<[u32; 4]> = HashSet::new();
        for _ in 0..32 {
            if self.triangle_slots() > limit {
                break;
            }
            let long: Vec<(u32, u32)> = self
                .edges()
                .filter(|&h| {
                    let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
                    self.length(h) > SPLIT_ABOVE * self.target(a, b)
                        && !self.is_frozen(h)
                        && !refused.contains(&self.edge_key(h))
                })
                .map(|h| (self.mesh.origin(h), self.mesh.dest(h)))
                .collect();
            let placed: Vec<Option<Vertex>> = long
                .par_iter()
                .map(|&(a, b)| self.mesh.find(a, b).and_then(|h| self.midpoint(h)))
                .collect();
            let mut done = 0;
            for (&(a, b), m) in long.iter().zip(placed) {
                let Some(h) = self.mesh.find(a, b) else {
                    continue;
                };
                let Some(m) = m else {
                    refused.insert(self.edge_key(h));
                    continue;
                };
                // The projected midpoint may lie on the other sheet of a
                // sharp fold inside one face (next to a crease that ends
                // in it): then halfway in the parameters of a control
                // triangle holding both ends.
                let m = if self.split_valid(h, &m) {
                    Some(m)
                } else if self.mesh.edge_label[h as usize] != NONE {
                    None
                } else {
                    let (va, vb) = (&self.vertices[a as usize], &self.vertices[b as usize]);
                    self.placer
                        .between_in(va, vb, self.face(h))
                        .filter(|m| self.split_valid(h, m))
                };
                if let Some(m) = m {
                    let id = self.mesh.add_vertex();
                    let size = self.target(a, b);
                    self.push_vertex(m, size);
                    self.mesh.split(h, id);
                    done += 1;
                } else {
                    refused.insert(self.edge_key(h));
                }
            }
            total += done;
            if done == 0 {
                break;
            }
        }
        total
    }

    /// An edge walked from its lower half-edge (as [`Remeshing::edges`]
    /// walks it, so the way its split is tried), with the corners opposite
    /// it: the same key, the same split of the same two triangles.
    fn edge_key(&self, h: u32) -> [u32; 4] {
        let o = self.mesh.opposite(h);
        let (h, o) = if o != NONE && o < h { (o, h) } else { (h, o) };
        let across = if o == NONE {
            NONE
        } else {
            self.mesh.origin(prev(o))
        };
        [
            self.mesh.origin(h),
            self.mesh.dest(h),
            self.mesh.origin(prev(h)),
            across,
        ]
    }

    /// Whether the four (or two) triangles of splitting h at m may replace
    /// the two (or one) on the edge.
    fn split_valid(&self, h: u32, m: &Vertex) -> bool {
        let id = self.vertices.len() as u32;
        let moved = Some((id, m));
        let sides: Vec<u32> = [h, self.mesh.opposite(h)]
            .into_iter()
            .filter(|&e| e != NONE)
            .collect();
        let new = sides.iter().flat_map(|&e| {
            let (a, b, c) = (
                self.mesh.origin(e),
                self.mesh.dest(e),
                self.mesh.origin(prev(e)),
            );
            let face = self.face(e);
            [([a, id, c], face, moved), ([id, b, c], face, moved)]
        });
        let old = sides
            .iter()
            .map(|&e| (self.mesh.corners(e), self.face(e), None));
        self.accept(new, old)
    }

    /// The new vertex at the middle of h's edge: on its curve if the edge is
    /// labelled, else on the surface in the edge's face.
    fn midpoint(&self, h: u32) -> Option<Vertex> {
        let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
        let (va, vb) = (&self.vertices[a as usize], &self.vertices[b as usize]);
        if self.mesh.edge_label[h as usize] != NONE {
            return self.curve_midpoint(h);
        }
        let face = self.face(h);
        let guess = if va.is_free() {
            va.at
        } else if vb.is_free() {
            vb.at
        } else {
            self.placer.guess_in(va, face)
        };
        // A projection that lands farther than half the edge from the
        // chord's midpoint went to another sheet of a folded surface.
        let (mid, reach) = (0.5 * (va.x + vb.x), 0.5 * va.x.distance(vb.x));
        self.placer
            .free(mid, guess, face)
            .filter(|m| m.x.distance(mid) <= reach)
            .or_else(|| self.placer.between_in(va, vb, face))
    }

    /// The curve vertex midway in t between the ends of h, when h runs
    /// along a curve: exact, and always between the ends (the point
    /// nearest the chord's midpoint need not be, where the curve turns
    /// sharply).
    fn curve_midpoint(&self, h: u32) -> Option<Vertex> {
        let label = self.mesh.edge_label[h as usize];
        if label == NONE {
            return None;
        }
        let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
        let (va, vb) = (&self.vertices[a as usize], &self.vertices[b as usize]);
        let ta = self.placer.t_on(va, label, None);
        let tb = self.placer.t_on(vb, label, ta);
        let ta = self.placer.t_on(va, label, tb).or(ta);
        let t = self.placer.mid_t(label, ta?, tb?);
        self.placer.at_curve(label, t).ok()
    }
}
