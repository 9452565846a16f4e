//! Collapsing short edges, where the features allow and the result has no
//! edge a split would cut again.

use super::connectivity::{next, prev};
use super::remeshing::Remeshing;
use super::split::SPLIT_ABOVE;
use super::vertices::Kind;
use crate::topology::NONE;
use rayon::prelude::*;

/// Edges shorter than this times their target are collapsed (CGAL's and
/// PMP's bound, with [`SPLIT_ABOVE`] above).
pub(super) const COLLAPSE_BELOW: f64 = 4.0 / 5.0;

impl Remeshing<'_> {
    /// Collapses edges shorter than [`COLLAPSE_BELOW`] × their target where
    /// the features allow and no edge of the result exceeds
    /// [`SPLIT_ABOVE`] × its target. Returns the count.
    pub fn collapse_short(&mut self) -> usize {
        let is_short = |this: &Self, h: u32| {
            let (a, b) = (this.mesh.origin(h), this.mesh.dest(h));
            this.length(h) < COLLAPSE_BELOW * this.target(a, b)
        };
        // The short edges of the mesh as it is, found in parallel; each is
        // checked again when its turn comes, as earlier collapses may have
        // removed or lengthened it. (An edge that an earlier collapse
        // shortens waits for the next round.)
        let short: Vec<u32> = (0..self.mesh.num_half_edges())
            .into_par_iter()
            .filter(|&h| {
                let g = self.mesh.opposite(h);
                self.mesh.is_alive(h) && (g == NONE || h < g) && is_short(self, h)
            })
            .collect();
        let mut done = 0;
        for h in short {
            if !self.mesh.is_alive(h) || !is_short(self, h) {
                continue;
            }
            let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
            for remove in [a, b] {
                if self.can_collapse(h, remove) {
                    self.mesh.collapse(h, remove);
                    done += 1;
                    break;
                }
            }
        }
        done
    }

    /// Whether h's edge may collapse with `remove` merging into the other
    /// end (see [`Remeshing::collapse_short`]).
    fn can_collapse(&mut self, h: u32, remove: u32) -> bool {
        if !self.collapse_allowed(h, remove) {
            return false;
        }
        let keep = if self.mesh.origin(h) == remove {
            self.mesh.dest(h)
        } else {
            self.mesh.origin(h)
        };
        // The triangles around `remove` other than the two on the edge,
        // with `keep` in its place.
        let x = self.vertices[keep as usize].x;
        let outgoing: Vec<u32> = self.mesh.outgoing(remove).collect();
        let border_last = self
            .mesh
            .is_border_vertex(remove)
            .then(|| outgoing.last().map(|&l| self.mesh.origin(prev(l))))
            .flatten();
        let mut new = Vec::with_capacity(outgoing.len());
        let gone = self.vertices[remove as usize].x;
        for &e in &outgoing {
            let y = self.mesh.dest(e);
            // A new curve edge stands for the curve through `remove`: its
            // length is that path's, not its chord's, or a crease's
            // hairpin turn would be cut off by one short chord.
            let length = if self.mesh.edge_label[e as usize] != NONE {
                x.distance(gone) + gone.distance(self.vertices[y as usize].x)
            } else {
                x.distance(self.vertices[y as usize].x)
            };
            if y != keep && length > SPLIT_ABOVE * self.target(keep, y) {
                return false;
            }
            let z = self.mesh.origin(prev(e));
            if y != keep && z != keep {
                new.push(([keep, y, z], self.face(e), None));
            }
        }
        let old = outgoing
            .iter()
            .map(|&e| (self.mesh.corners(e), self.face(e), None));
        if !self.accept(new, old) {
            return false;
        }
        if let Some(y) = border_last {
            // The boundary through `remove`, as for curve edges above.
            let length = x.distance(gone) + gone.distance(self.vertices[y as usize].x);
            if y != keep && length > SPLIT_ABOVE * self.target(keep, y) {
                return false;
            }
        }
        true
    }

    /// Whether the features and the topology let h's edge collapse with
    /// `remove` merging into the other end: `remove` is neither pinned nor
    /// a corner, and on a curve only along it; no triangle would get two
    /// labelled sides on one edge; the mesh stays a manifold; every new
    /// edge may join its ends ([`Remeshing::may_join`]).
    pub(super) fn collapse_allowed(&mut self, h: u32, remove: u32) -> bool {
        let label = self.mesh.edge_label[h as usize];
        if self.is_pinned(remove) {
            return false;
        }
        match self.vertices[remove as usize].kind {
            Kind::Corner { .. } => return false,
            Kind::Curve { curve, .. } if label != curve => return false,
            Kind::Free if label != NONE => return false,
            _ => {}
        }
        // Two labelled sides of one triangle would merge into one edge.
        let g = self.mesh.opposite(h);
        for e in [h, g] {
            if e != NONE
                && self.mesh.edge_label[next(e) as usize] != NONE
                && self.mesh.edge_label[prev(e) as usize] != NONE
            {
                return false;
            }
        }
        let mut scratch = std::mem::take(&mut self.scratch);
        let topological = self.mesh.can_collapse(h, &mut scratch);
        let keep = if self.mesh.origin(h) == remove {
            self.mesh.dest(h)
        } else {
            self.mesh.origin(h)
        };
        let joins_new = topological && self.yields[keep as usize] && {
            self.mesh.neighbours(remove, &mut scratch[0]);
            scratch[0]
                .iter()
                .any(|&x| x != keep && !self.may_join(keep, x) && !self.mesh.joined(keep, x))
        };
        self.scratch = scratch;
        topological && !joins_new
    }
}
