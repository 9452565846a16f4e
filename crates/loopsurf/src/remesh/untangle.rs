//! The last pass: where the mesh crosses itself, vertices removed until it
//! does not, so that it bounds a volume.
//!
//! **Why a mesh of a surface that does not cross itself can cross.** Next
//! to an irregular corner the limit surface can fold into a pleat thinner
//! than the chord tolerance (joint.off at its valence-16 corner: a Z-fold 5e-4
//! of the diagonal thick, its normal flipping). Every vertex lies on the
//! surface and every triangle faces the way the surface does at its
//! corners, so the triangles on the pleat's three layers follow it; being
//! straight, they cut through the layers next to them. The surface itself
//! is clean there (a chart mesh 128 to the control edge is).
//!
//! **The remedy.** A pleat within the tolerance need not be meshed: a
//! triangle spanning it is within the tolerance of the surface. So each
//! round finds the crossing pairs ([`crate::geometry::crossings`], exact),
//! and removes vertices of the crossing triangles (those in most pairs
//! first) by collapsing one of their edges, wherever the triangles made
//! cross fewer others than those removed, face one way among themselves
//! (or each the way the one it replaces did), lie within the chord
//! tolerance of the surface, and have no angle below both 20° and the
//! smallest of those removed. Where no removal helps, a round flips edges
//! of crossing triangles under the same conditions (at fins of a folded
//! net a vertex often cannot go, but the diagonal of its quad can turn:
//! mech-holes-shark's last 4 pairs went, homer's fold kept 3 of 10).
//! Where pairs are left, a second stage lifts
//! the angle floor for vertices on a fold of the surface under a chord
//! tolerance: the triangles there are as poor as the fold makes them.
//! Where the surface itself crosses, no removal helps; those pairs stay,
//! and the caller hears of them.

use super::connectivity::prev;
use super::remeshing::Remeshing;
use crate::geometry::area_normal;
use crate::geometry::crossings::{cross, crossings, Box3, BoxTree};
use crate::topology::NONE;
use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// The most rounds: each removes vertices in separate places, and the
/// crossings a removal leaves are found again by the next.
const ROUNDS: usize = 100;

/// cos 20°: a removal may make angles down to 20°, or down to the worst
/// it removes where that is smaller; on a fold under a tolerance, any
/// ([`Remeshing::on_fold`]). (Down to 5° everywhere, removals at pig.off's
/// fin made 20 more triangles below 20° at a uniform size; unbounded, one
/// of 1.1°, below CGAL's 4.3° there.)
const LEAST_COSINE: f64 = 0.939_692_620_785_908_4;

/// With no chord tolerance (a uniform size), a triangle made by a removal
/// may stand off the surface by this share of its longest side.
const OFF_SURFACE: f64 = 0.05;

impl Remeshing<'_> {
    /// Removes vertices where the mesh crosses itself (see the module
    /// doc), keeping every new triangle within `tolerance` (model units)
    /// of the surface. Returns the largest chord error of a triangle it
    /// made (0 if none).
    pub fn untangle(&mut self, tolerance: Option<f64>) -> f64 {
        // First with the angle floor everywhere; then, for what is left,
        // without it on folds (see [`Remeshing::on_fold`]), under a
        // tolerance. In that order mech-holes-shark keeps 4 pairs at its
        // fin; 15 with the floor everywhere, 28 with it lifted on folds
        // from the start (joint.off: 7, 0 and 0).
        // A clean mesh is searched once.
        let (strict, left) = self.untangle_rounds(tolerance, false);
        if left == 0 || tolerance.is_none() {
            return strict;
        }
        strict.max(self.untangle_rounds(tolerance, true).0)
    }

    /// Rounds of [`Remeshing::untangle`], the angle floor lifted on folds
    /// if `on_folds`: the largest chord error of a triangle made, and how
    /// many pairs the last search found (more may be left where its
    /// round removed none).
    fn untangle_rounds(&mut self, tolerance: Option<f64>, on_folds: bool) -> (f64, usize) {
        let mut worst: f64 = 0.0;
        let mut left = 0;
        for _ in 0..ROUNDS {
            let slots: Vec<u32> = (0..self.mesh.num_half_edges() / 3)
                .filter(|&t| self.mesh.is_alive(3 * t))
                .collect();
            let triangles: Vec<[u32; 3]> =
                slots.iter().map(|&t| self.mesh.corners(3 * t)).collect();
            let points: Vec<DVec3> = self.vertices.iter().map(|v| v.x).collect();
            let pairs = crossings(&points, &triangles);
            left = pairs.len();
            if pairs.is_empty() {
                break;
            }
            // Crossings per triangle slot, and the candidates: vertices of
            // crossing triangles, those in most pairs first.
            let mut per_slot: HashMap<u32, usize> = HashMap::new();
            let mut per_vertex: HashMap<u32, usize> = HashMap::new();
            for &[i, j] in &pairs {
                for t in [i, j] {
                    *per_slot.entry(slots[t as usize]).or_default() += 1;
                    for v in triangles[t as usize] {
                        *per_vertex.entry(v).or_default() += 1;
                    }
                }
            }
            let mut candidates: Vec<(usize, u32)> =
                per_vertex.iter().map(|(&v, &n)| (n, v)).collect();
            candidates.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
            let boxes: Vec<Box3> = triangles
                .iter()
                .map(|t| Box3::of(t.map(|v| points[v as usize])))
                .collect();
            let tree = BoxTree::new(&boxes);
            let near = Near {
                tree: &tree,
                slots: &slots,
                points: &points,
            };
            let mut busy: HashSet<u32> = HashSet::new();
            let mut removed = 0;
            for (_, v) in candidates {
                if busy.contains(&v) || !self.mesh.is_vertex_alive(v) {
                    continue;
                }
                if let Some((h, chord)) =
                    self.best_removal(v, &near, &per_slot, tolerance, on_folds)
                {
                    let mut ring = Vec::new();
                    self.mesh.neighbours(v, &mut ring);
                    busy.extend(ring);
                    self.mesh.collapse(h, v);
                    worst = worst.max(chord);
                    removed += 1;
                }
            }
            if removed == 0 {
                removed = self.flip_crossings(&per_slot, &near, tolerance, on_folds);
            }
            if removed == 0 {
                break;
            }
        }
        (worst, left)
    }

    /// The collapse of an edge out of `v` that removes v best: its
    /// half-edge and the chord error of the triangles it makes, if any
    /// collapse crosses fewer triangles than v's do now and keeps the
    /// conditions of the module doc.
    fn best_removal(
        &mut self,
        v: u32,
        near: &Near,
        per_slot: &HashMap<u32, usize>,
        tolerance: Option<f64>,
        on_folds: bool,
    ) -> Option<(u32, f64)> {
        let outgoing: Vec<u32> = self.mesh.outgoing(v).collect();
        let old: HashSet<u32> = outgoing.iter().map(|&e| e / 3).collect();
        let before: usize = old
            .iter()
            .map(|t| per_slot.get(t).copied().unwrap_or(0))
            .sum();
        let floor = if on_folds && self.on_fold(v) {
            f64::INFINITY
        } else {
            LEAST_COSINE
        };
        let mut best: Option<(usize, f64, u32, f64)> = None;
        for &h in &outgoing {
            if !self.collapse_allowed(h, v) {
                continue;
            }
            let keep = self.mesh.dest(h);
            // Each triangle around v that survives, with keep for v: the
            // new triangle and the one it replaces.
            let (new, replaced): (Vec<[u32; 3]>, Vec<[u32; 3]>) = outgoing
                .iter()
                .map(|&e| (self.mesh.dest(e), self.mesh.origin(prev(e))))
                .filter(|&(y, z)| y != keep && z != keep)
                .map(|(y, z)| ([keep, y, z], [v, y, z]))
                .unzip();
            let Some(chord) = self.acceptable(&new, &replaced, keep, tolerance) else {
                continue;
            };
            let mut after = 0;
            for (i, t) in new.iter().enumerate() {
                after += near.crossing(t, &old, |s| {
                    self.mesh.is_alive(3 * s).then(|| self.mesh.corners(3 * s))
                });
                after += new[i + 1..]
                    .iter()
                    .filter(|u| cross(near.points, *t, **u))
                    .count();
            }
            if after >= before {
                continue;
            }
            // The smallest angle's cosine (larger is worse): a removal
            // makes no angle below both 20° and the worst it replaces.
            let worst_of = |tris: &mut dyn Iterator<Item = [u32; 3]>| {
                tris.map(|t| self.worst_cosine(t, None))
                    .fold(f64::NEG_INFINITY, f64::max)
            };
            let quality = worst_of(&mut new.iter().copied());
            let before_quality = worst_of(&mut outgoing.iter().map(|&e| self.mesh.corners(e)));
            if quality > before_quality.max(floor) {
                continue;
            }
            if best.map_or(true, |b| (after, quality) < (b.0, b.1)) {
                best = Some((after, quality, h, chord));
            }
        }
        best.map(|b| (b.2, b.3))
    }

    /// Flips edges of crossing triangles where the two new triangles cross
    /// fewer others than the two old ones did, under the conditions of a
    /// removal (see the module doc). Returns how many.
    fn flip_crossings(
        &mut self,
        per_slot: &HashMap<u32, usize>,
        near: &Near,
        tolerance: Option<f64>,
        on_folds: bool,
    ) -> usize {
        let mut slots: Vec<u32> = per_slot.keys().copied().collect();
        slots.sort_unstable();
        let mut busy: HashSet<u32> = HashSet::new();
        let mut flipped = 0;
        for t in slots {
            for h in 3 * t..3 * t + 3 {
                let g = self.mesh.opposite(h);
                if !self.mesh.is_alive(h)
                    || g == NONE
                    || self.mesh.edge_label[h as usize] != NONE
                    || busy.contains(&(h / 3))
                    || busy.contains(&(g / 3))
                    || !self.mesh.can_flip(h)
                {
                    continue;
                }
                let [a, b, c] = self.mesh.corners(h);
                let d = self.mesh.origin(prev(g));
                let old: HashSet<u32> = [h / 3, g / 3].into();
                let before: usize = old
                    .iter()
                    .map(|s| per_slot.get(s).copied().unwrap_or(0))
                    .sum();
                let new = [[c, a, d], [c, d, b]];
                let replaced = [[a, b, c], [b, a, d]];
                let Some(_) = self.acceptable(&new, &replaced, c, tolerance) else {
                    continue;
                };
                let after: usize = new
                    .iter()
                    .map(|t| {
                        near.crossing(t, &old, |s| {
                            self.mesh.is_alive(3 * s).then(|| self.mesh.corners(3 * s))
                        })
                    })
                    .sum::<usize>()
                    + cross(near.points, new[0], new[1]) as usize;
                if after >= before {
                    continue;
                }
                let floor = if on_folds && [a, b, c, d].iter().any(|&v| self.on_fold(v)) {
                    f64::INFINITY
                } else {
                    LEAST_COSINE
                };
                let (was, now) = (
                    self.worst_cosine(replaced[0], None)
                        .max(self.worst_cosine(replaced[1], None)),
                    self.worst_cosine(new[0], None)
                        .max(self.worst_cosine(new[1], None)),
                );
                if now > was.max(floor) {
                    continue;
                }
                self.mesh.flip(h);
                busy.extend([h / 3, g / 3]);
                flipped += 1;
            }
        }
        flipped
    }

    /// Whether free vertex v sits on a fold of the surface: its normal and
    /// a free neighbour's point apart (more than 90°). There the triangles
    /// are as poor as the fold makes them whatever is done, and a pleat
    /// within the tolerance is better spanned than meshed.
    fn on_fold(&self, v: u32) -> bool {
        let here = &self.vertices[v as usize];
        if !here.is_free() {
            return false;
        }
        let mut ring = Vec::new();
        self.mesh.neighbours(v, &mut ring);
        ring.iter().any(|&u| {
            let u = &self.vertices[u as usize];
            u.is_free() && u.normal.dot(here.normal) < 0.0
        })
    }

    /// Whether triangles `new` (around `keep`) may replace `replaced`
    /// (the same with v for keep): none degenerate; all facing one way,
    /// or else each facing the way the one it replaces did (a removal
    /// then turns no triangle over: it cannot fold what was flat, and may
    /// leave a fold it does not undo);
    /// each within the chord tolerance of the surface at its centroid and
    /// the midpoints of its new sides (or, with none, within
    /// [`OFF_SURFACE`] of its longest side).
    /// Returns their largest chord error.
    fn acceptable(
        &self,
        new: &[[u32; 3]],
        replaced: &[[u32; 3]],
        keep: u32,
        tolerance: Option<f64>,
    ) -> Option<f64> {
        let corners = |t: &[u32; 3]| t.map(|v| self.vertices[v as usize].x);
        let normals: Vec<DVec3> = new.iter().map(|t| area_normal(corners(t))).collect();
        let total: DVec3 = normals.iter().sum();
        let one_way = normals.iter().all(|n| n.dot(total) > 0.0);
        let mut worst: f64 = 0.0;
        let at = self.vertices[keep as usize].at;
        for ((t, r), n) in new.iter().zip(replaced).zip(&normals) {
            let p = corners(t);
            let longest = (0..3)
                .map(|k| p[k].distance(p[(k + 1) % 3]))
                .fold(0.0, f64::max);
            let as_before = n.dot(area_normal(corners(r))) > 0.0;
            if !(n.length() > 1e-12 * longest * longest) || !(one_way || as_before) {
                return None;
            }
            // The centroid and the midpoints of the two new sides (keep's),
            // the probes the remesher's chord error is measured at; local
            // projection bounds the distance from above.
            for probe in [
                (p[0] + p[1] + p[2]) / 3.0,
                0.5 * (p[0] + p[1]),
                0.5 * (p[0] + p[2]),
            ] {
                let snap =
                    crate::snap::project(self.placer.surface, probe, at.tri as usize, at.v, at.w)
                        .ok()?;
                if snap.distance > tolerance.unwrap_or(OFF_SURFACE * longest) {
                    return None;
                }
                worst = worst.max(snap.distance);
            }
        }
        Some(worst)
    }
}

/// The mesh as a round found it, to count crossings of a new triangle.
struct Near<'n> {
    tree: &'n BoxTree,
    /// Per tree item: its triangle's slot.
    slots: &'n [u32],
    points: &'n [DVec3],
}

impl Near<'_> {
    /// How many of the round's triangles `t` crosses, leaving out those
    /// in `old` (about to go), as they are now (`now` gives a slot's
    /// corners, `None` once it is gone). A triangle an earlier removal of
    /// the round changed is tested as it is now, found by its old box;
    /// one that left its box is caught by the next round.
    fn crossing(
        &self,
        t: &[u32; 3],
        old: &HashSet<u32>,
        now: impl Fn(u32) -> Option<[u32; 3]>,
    ) -> usize {
        let mut count = 0;
        let bounds = Box3::of(t.map(|v| self.points[v as usize]));
        self.tree.overlapping(&bounds, |i| {
            let slot = self.slots[i];
            if old.contains(&slot) {
                return;
            }
            if let Some(corners) = now(slot) {
                if cross(self.points, *t, corners) {
                    count += 1;
                }
            }
        });
        count
    }
}
