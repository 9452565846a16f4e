//! The mesh being remeshed, and the small queries every pass shares.
//!
//! The passes (Botsch & Kobbelt 2004, as in CGAL's and PMP's remeshers)
//! each have their file: [`super::split`], [`super::collapse`],
//! [`super::flip`], [`super::relax`], [`super::caps`], [`super::shake`],
//! with [`super::renumber`] between rounds. The expensive part, placing a
//! vertex on the surface, runs in parallel over a whole pass's candidates
//! from the mesh as it was; the changes are then applied one by one, each
//! checked against the mesh as it is by then ([`super::validity`]).

use super::connectivity::{prev, Connectivity};
use super::vertices::{Placer, Vertex};
use crate::topology::NONE;
use glam::DVec3;

/// The mesh being remeshed.
pub(crate) struct Remeshing<'a> {
    pub placer: Placer<'a>,
    pub mesh: Connectivity,
    pub vertices: Vec<Vertex>,
    pub size: Vec<f64>,
    /// Per vertex: the id it keeps in the whole mesh if it is pinned (a
    /// vertex on an interface between parts, which both sides share and
    /// neither may move or remove), else [`NONE`].
    pub pinned: Vec<u32>,
    /// Per vertex: whether it is pinned and a part before this piece's in
    /// the order of parts, or the triangles no part remeshes, hold it too
    /// ([`Remeshing::may_join`]).
    pub yields: Vec<bool>,
    /// Per vertex: a bound on its size before grading (infinite but where
    /// the size around a pinned vertex is known from before: grading is
    /// not local, and a piece alone would not see what shrank it).
    pub size_bound: Vec<f64>,
    /// [`Connectivity::can_collapse`]'s work space, kept between calls.
    pub(super) scratch: [Vec<u32>; 2],
}

/// A vertex about to change: its id and its new state.
pub(super) type Moved<'v> = Option<(u32, &'v Vertex)>;

impl<'a> Remeshing<'a> {
    pub fn new(placer: Placer<'a>, mesh: Connectivity, vertices: Vec<Vertex>) -> Remeshing<'a> {
        let size = vec![f64::INFINITY; vertices.len()];
        let pinned = vec![NONE; vertices.len()];
        let yields = vec![false; vertices.len()];
        let size_bound = vec![f64::INFINITY; vertices.len()];
        Remeshing {
            size_bound,
            placer,
            mesh,
            vertices,
            size,
            pinned,
            yields,
            scratch: [Vec::new(), Vec::new()],
        }
    }
}

impl Remeshing<'_> {
    /// The target length of edge a–b: the mean of its ends' sizes.
    pub(super) fn target(&self, a: u32, b: u32) -> f64 {
        0.5 * (self.size[a as usize] + self.size[b as usize])
    }

    /// Whether v is pinned (see [`Remeshing::pinned`]).
    pub(super) fn is_pinned(&self, v: u32) -> bool {
        self.pinned[v as usize] != NONE
    }

    /// Whether h's edge is frozen: a border edge between two pinned
    /// vertices, an interface between parts that both sides mesh alike.
    pub(super) fn is_frozen(&self, h: u32) -> bool {
        self.mesh.opposite(h) == NONE
            && self.is_pinned(self.mesh.origin(h))
            && self.is_pinned(self.mesh.dest(h))
    }

    /// Whether a new edge may join a and b. Two pieces that meet on pinned
    /// vertices could each join the same two anew, one from each side, and
    /// their union would hold that edge four times: where a surface folds,
    /// both sides of an interface see the same corner as convex and cut
    /// it (anchor.off in 3 and 4 parts did). So of the pieces holding
    /// both, only the first in the order of parts may: not where both
    /// yield. Forbidding every such edge instead left pig's fin at 1.3°
    /// in 8 parts (5.8° whole).
    pub(super) fn may_join(&self, a: u32, b: u32) -> bool {
        !(self.yields[a as usize] && self.yields[b as usize])
    }

    /// Whether h's edge may be flipped: [`Connectivity::can_flip`], and the
    /// new edge may join its ends ([`Remeshing::may_join`]).
    pub(super) fn may_flip(&self, h: u32) -> bool {
        if !self.mesh.can_flip(h) {
            return false;
        }
        let g = self.mesh.opposite(h);
        self.may_join(self.mesh.origin(prev(h)), self.mesh.origin(prev(g)))
    }

    /// Appends a new (unpinned) vertex of target size `size`.
    pub(super) fn push_vertex(&mut self, v: Vertex, size: f64) {
        self.vertices.push(v);
        self.size.push(size);
        self.pinned.push(NONE);
        self.yields.push(false);
        self.size_bound.push(f64::INFINITY);
    }

    /// The position of v, or of its new state if it is the one `moved`.
    pub(super) fn point(&self, v: u32, moved: Moved) -> DVec3 {
        match moved {
            Some((m, x)) if m == v => x.x,
            _ => self.vertices[v as usize].x,
        }
    }

    /// The length of h's edge.
    pub(super) fn length(&self, h: u32) -> f64 {
        let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
        self.vertices[a as usize]
            .x
            .distance(self.vertices[b as usize].x)
    }

    /// Each live edge once: its half-edge with the larger opposite, or the
    /// border one.
    pub(super) fn edges(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.mesh.num_half_edges()).filter(move |&h| {
            self.mesh.is_alive(h) && {
                let o = self.mesh.opposite(h);
                o == NONE || h < o
            }
        })
    }

    /// The face of the triangle of half-edge h.
    pub(super) fn face(&self, h: u32) -> u32 {
        self.mesh.face[(h / 3) as usize]
    }
}
