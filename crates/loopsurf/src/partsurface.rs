//! A part's surface, queried in the whole's triangle ids: evaluation of its
//! owned triangles (bit for bit the whole's, see
//! [`crate::partition::Part`]), local projection that says when its walk
//! leaves the part, and certified closest points over the owned triangles
//! that say which other parts may hold a nearer point.
//!
//! **Walks.** A walk stays on owned triangles, where every evaluation is
//! the whole's: as long as the whole's walk from the same start stays on
//! them too, the two are the same bits. Where the walk would step into a
//! triangle the part does not own, it stops on the edge or vertex it
//! reached, and the answer names the triangle it would have gone on into,
//! so a caller can hand the query to that triangle's owner. (The halo's
//! triangles are not walked: next to the rim their patches read a
//! boundary the whole does not have, so only owned ones are exact.)
//!
//! **Closest points and other parts.** The owned triangles' closest point
//! is certified as [`crate::snap::closest_point`]'s is. Whether another
//! part holds a nearer point is decided by boxes, not by the rim: the rim
//! belongs to the owned triangles, so it is never nearer than their closest
//! point, and another part can be nearer far from the rim (the other side
//! of a thin plate). A Loop surface lies in the convex hull of the control
//! points of its patches (every mask is a convex combination), so each
//! part's limit surface lies in the box of its needed vertices; a part
//! whose box is nearer than the answer may hold a nearer point, and no
//! other can.

use crate::error::{Error, Result};
use crate::net::ControlNet;
use crate::partition::{Part, Partition};
use crate::snap::{self, Snap, SnapIndex};
use crate::surface::{Derived, Surface};
use glam::DVec3;
use std::sync::OnceLock;

/// A box: its lowest and highest corners.
pub type Bounds = (DVec3, DVec3);

/// The limit surface of one part.
pub struct PartSurface {
    part: Part,
    surface: Surface,
    owned: Vec<bool>,
    /// Every part's bounds, by part, to tell which may hold a nearer point.
    bounds: Vec<Bounds>,
    /// This part's index among them.
    index: usize,
    snap_index: OnceLock<SnapIndex>,
}

/// A snap over a part: the answer, in the whole's triangle ids, and
/// whether it may not be the whole's.
#[derive(Debug, Clone, PartialEq)]
pub struct PartSnap {
    /// The answer, its `tri` a global triangle id.
    pub snap: Snap,
    /// A walk: the first global triangle the walk would have entered (or
    /// carried a step into) had the part owned it; the answer is then
    /// where it stopped, and may not be the whole's.
    pub left_at: Option<u32>,
    /// A closest point: the other parts whose surface may hold a nearer
    /// point (their bounds are nearer than the answer), ascending.
    pub nearer_parts: Vec<u32>,
}

impl PartSurface {
    /// The approximating surface of `part`, which is part `index` of a
    /// partition whose parts' [`bounds`] are `bounds`.
    pub fn new(part: Part, index: usize, bounds: Vec<Bounds>) -> Result<PartSurface> {
        if index >= bounds.len() {
            return Err(Error::InvalidArgument(format!(
                "part {index}: out of range ({} parts have bounds)",
                bounds.len()
            )));
        }
        let owned = (0..part.global_triangles().len())
            .map(|t| part.is_owned(t))
            .collect();
        Ok(PartSurface {
            surface: Surface::new(part.net())?,
            part,
            owned,
            bounds,
            index,
            snap_index: OnceLock::new(),
        })
    }

    /// The part.
    pub fn part(&self) -> &Part {
        &self.part
    }
    /// The surface of the part's sub-net (local triangle ids).
    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// The local id of global triangle `t` when the part owns it.
    pub fn owned_local(&self, t: u32) -> Result<usize> {
        match self.part.local_triangle(t) {
            Some(l) if self.owned[l] => Ok(l),
            _ => Err(Error::InvalidArgument(format!(
                "triangle {t}: not owned by part {}",
                self.index
            ))),
        }
    }

    /// The nearest local minimum of the distance to `p` from the guess
    /// (global triangle `tri`, owned, and v, w), as
    /// [`crate::snap::project`] walks, kept to the owned triangles (see
    /// the module's note on walks).
    pub fn project(&self, p: DVec3, tri: u32, v: f64, w: f64) -> Result<PartSnap> {
        let local = self.owned_local(tri)?;
        let (v, w) = snap::checked_start(&self.surface, p, local, v, w)?;
        // The first triangle the walk asks to enter and the part does not
        // own: from there on the whole's walk may differ.
        let refused = std::cell::Cell::new(None);
        let owned = |t: usize| {
            if !self.owned[t] && refused.get().is_none() {
                refused.set(Some(t));
            }
            self.owned[t]
        };
        let (snap, _) = snap::descend_confined(&self.surface, p, local, v, w, &owned);
        Ok(PartSnap {
            snap: self.global(snap),
            left_at: refused.get().map(|t| self.part.global_triangles()[t]),
            nearer_parts: Vec::new(),
        })
    }

    /// The closest point to `p` over the owned triangles, certified as
    /// [`crate::snap::closest_point`]'s, and the other parts whose bounds
    /// are nearer than it.
    pub fn closest_point(&self, p: DVec3) -> Result<PartSnap> {
        snap::check_point(p)?;
        let index = self.snap_index.get_or_init(|| {
            let whole = self.part.whole_size()[1];
            SnapIndex::over(&self.surface, Some(&self.owned), whole)
        });
        let owned = |t: usize| self.owned[t];
        let tolerance = snap::DEFAULT_TOLERANCE;
        let snap = snap::search_in(&self.surface, index, p, None, tolerance, &owned);
        let nearer_parts = (0..self.bounds.len())
            .filter(|&q| q != self.index && distance_to(self.bounds[q], p) < snap.distance)
            .map(|q| q as u32)
            .collect();
        Ok(PartSnap {
            snap: self.global(snap),
            left_at: None,
            nearer_parts,
        })
    }

    /// Bytes held: the part, its surface, and the owned triangles' snap
    /// index once built.
    pub fn memory_bytes(&self) -> usize {
        self.part.memory_bytes()
            + self.surface.memory_bytes()
            + self.owned.len()
            + self.snap_index.get().map_or(0, |i| i.memory_bytes())
    }

    /// A snap of the sub-net in global triangle ids.
    fn global(&self, mut snap: Snap) -> Snap {
        snap.tri = self.part.global_triangles()[snap.tri] as usize;
        snap
    }
}

/// Each part's bounds: the box of its needed vertices (the corners of its
/// triangles and their neighbours), which holds its limit surface.
pub fn bounds(net: &ControlNet, partition: &Partition) -> Vec<Bounds> {
    let topo = net.topology();
    let mut boxes = vec![(DVec3::INFINITY, DVec3::NEG_INFINITY); partition.num_parts()];
    for (t, &q) in partition.parts().iter().enumerate() {
        let b = &mut boxes[q as usize];
        for &c in &topo.triangles()[t] {
            let around = std::iter::once(c).chain(topo.ring(c as usize).iter().copied());
            for v in around {
                let x = net.points()[v as usize];
                *b = (b.0.min(x), b.1.max(x));
            }
        }
    }
    boxes
}

/// The distance from `p` to the box `b` (0 inside).
fn distance_to(b: Bounds, p: DVec3) -> f64 {
    (b.0 - p).max(p - b.1).max(DVec3::ZERO).length()
}
