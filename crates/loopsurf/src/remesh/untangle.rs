//! The last passes: where the mesh crosses itself, vertices removed until
//! it does not, so that it bounds a volume; then slivers cleared.
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
//! A third lifts it everywhere, for a removal or flip that leaves no
//! crossing around it: at mech-holes-shark's fin, where the net folds
//! back by 172°, a vertex whose removal cleared 8 pairs made a 0.3°
//! triangle and the other stages kept it (10 pairs left, none after).
//! Where the surface itself crosses, no removal helps; those pairs stay,
//! and the caller hears of them.
//!
//! **Slivers last.** The same collapses, and flips, judged by the chord
//! tolerance and by facing one way among themselves rather than by the
//! surface normal at each vertex, then remove vertices of triangles below
//! 20° wherever that makes the worst angle around them better, crosses no
//! more triangles, and folds no new triangle back against a neighbour by
//! more than 120°. The passes before judge a triangle by the surface
//! normal at its free corners; on a fold or a wrinkle of the surface,
//! where that normal turns within a triangle, they keep slivers that a
//! triangle spanning the wrinkle within the tolerance replaces (joint.off
//! adapted: 0.83% of its triangles below 20° before, 0.10% after, its
//! smallest angle 0.05° → 3.4°). Without the fold limit joint came to
//! 0.03% and 12.7°, but gmsh refused the mesh ("overlapping facets"):
//! spanning a wrinkle had folded triangles nearly flat onto their
//! neighbours.

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

/// Changed triangles a query tests one by one before the box tree of a
/// round is built anew.
const REBUILD: usize = 512;

/// cos 120°: slivers are cleared only by triangles that turn from their
/// neighbours by at most this, or no more than before.
const SHARPEST_FOLD: f64 = -0.5;

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
        // tolerance; then without it anywhere, for removals that clear
        // every crossing around them. With the first two stages alone,
        // mech-holes-shark kept 4 pairs at its fin; 15 with the floor
        // everywhere, 28 with it lifted on folds from the start (joint.off:
        // 7, 0 and 0). A clean mesh is searched once.
        let mut worst: f64 = 0.0;
        let mut last = None;
        for floor in [Floor::Everywhere, Floor::OffFolds, Floor::Nowhere] {
            let (made, left) = self.untangle_rounds(tolerance, floor, &mut last);
            worst = worst.max(made);
            if left == 0 || tolerance.is_none() {
                break;
            }
        }
        worst
    }

    /// Rounds of [`Remeshing::untangle`], the angle floor kept where
    /// `floor` says: the largest chord error of a triangle made, and how
    /// many pairs the last search found (more may be left where its
    /// round removed none). `last` is the search before and the triangle
    /// slots changed since, which the next search starts from (and is
    /// left so for the next stage).
    fn untangle_rounds(
        &mut self,
        tolerance: Option<f64>,
        floor: Floor,
        last: &mut Option<(Near, HashSet<u32>)>,
    ) -> (f64, usize) {
        let mut worst: f64 = 0.0;
        let mut left = 0;
        for _ in 0..ROUNDS {
            let near = match last.take() {
                Some((before, changed)) => {
                    let near = Near::since(self, &before, &changed);
                    // The unit tests check it against a full search.
                    #[cfg(test)]
                    assert_eq!(
                        near.pairs,
                        Near::of(self).pairs,
                        "a search since the last round"
                    );
                    near
                }
                None => Near::of(self),
            };
            let mut changed: HashSet<u32> = HashSet::new();
            let pairs = &near.pairs;
            left = pairs.len();
            if pairs.is_empty() {
                break;
            }
            // The candidates: vertices of crossing triangles, those in
            // most pairs first.
            let mut per_vertex: HashMap<u32, usize> = HashMap::new();
            for &[i, j] in pairs {
                for t in [i, j] {
                    for v in near.triangles[t as usize] {
                        *per_vertex.entry(v).or_default() += 1;
                    }
                }
            }
            let mut candidates: Vec<(usize, u32)> =
                per_vertex.iter().map(|(&v, &n)| (n, v)).collect();
            candidates.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
            let mut busy: HashSet<u32> = HashSet::new();
            let mut removed = 0;
            for (_, v) in candidates {
                if busy.contains(&v) || !self.mesh.is_vertex_alive(v) {
                    continue;
                }
                if let Some((h, chord)) = self.best_removal(v, &near, tolerance, floor) {
                    let mut ring = Vec::new();
                    self.mesh.neighbours(v, &mut ring);
                    busy.extend(ring);
                    changed.extend(self.mesh.outgoing(v).map(|e| e / 3));
                    self.mesh.collapse(h, v);
                    worst = worst.max(chord);
                    removed += 1;
                }
            }
            if removed == 0 {
                let flipped = self.flip_crossings(&near, tolerance, floor);
                removed = flipped.len() / 2;
                changed.extend(flipped);
            }
            *last = Some((near, changed));
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
        tolerance: Option<f64>,
        floor: Floor,
    ) -> Option<(u32, f64)> {
        let outgoing: Vec<u32> = self.mesh.outgoing(v).collect();
        let old: HashSet<u32> = outgoing.iter().map(|&e| e / 3).collect();
        let before = near.before(&old);
        let least = if self.lifted(floor, &[v]) {
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
            let (new, replaced) = self.collapsed(v, &outgoing, keep);
            let Some(chord) = self.acceptable(&new, &replaced, keep, tolerance) else {
                continue;
            };
            let after = near.after(self, &new, &old);
            if !floor.helps(before, after) {
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
            if quality > before_quality.max(least) {
                continue;
            }
            if best.map_or(true, |b| (after, quality) < (b.0, b.1)) {
                best = Some((after, quality, h, chord));
            }
        }
        best.map(|b| (b.2, b.3))
    }

    /// Removes vertices of triangles below 20° where a collapse makes the
    /// worst angle around them better, under a removal's conditions of
    /// chord and facing (see the module doc), crossing no more triangles
    /// than before. Returns the largest chord error of a triangle it made.
    pub fn clear_slivers(&mut self, tolerance: Option<f64>) -> f64 {
        const BELOW: f64 = LEAST_COSINE;
        let mut worst: f64 = 0.0;
        // After the first round, only where the last one changed something
        // can a vertex that could not go before go now.
        let mut dirty: Option<HashSet<u32>> = None;
        // Built when a removal first needs to count crossings, and kept
        // across rounds: every change is noted in it, so its counts are
        // those of the mesh as it is (built anew for each of the many
        // small rounds at pig's fin, it took 6% of a run's samples).
        let mut near: Option<Near> = None;
        for _ in 0..ROUNDS {
            let mut candidates: Vec<u32> = Vec::new();
            for t in 0..self.mesh.num_half_edges() / 3 {
                if !self.mesh.is_alive(3 * t) {
                    continue;
                }
                let tri = self.mesh.corners(3 * t);
                if self.worst_cosine(tri, None) <= BELOW || !is_dirty(&dirty, tri) {
                    continue;
                }
                candidates.extend(tri);
            }
            candidates.sort_unstable();
            candidates.dedup();
            if candidates.is_empty() {
                break;
            }
            let mut touched: Vec<u32> = Vec::new();
            let mut removed = 0;
            for v in candidates {
                if !self.mesh.is_vertex_alive(v) {
                    continue;
                }
                let outgoing: Vec<u32> = self.mesh.outgoing(v).collect();
                let old: HashSet<u32> = outgoing.iter().map(|&e| e / 3).collect();
                // The crossings v's triangles are in, counted when needed.
                let mut crossed: Option<usize> = None;
                let before = outgoing
                    .iter()
                    .map(|&e| self.worst_cosine(self.mesh.corners(e), None))
                    .fold(f64::NEG_INFINITY, f64::max);
                let mut best: Option<(f64, u32, f64)> = None;
                for &h in &outgoing {
                    if !self.collapse_allowed(h, v) {
                        continue;
                    }
                    let keep = self.mesh.dest(h);
                    let (new, replaced) = self.collapsed(v, &outgoing, keep);
                    // The cheap test first: the angles.
                    let quality = new
                        .iter()
                        .map(|&t| self.worst_cosine(t, None))
                        .fold(f64::NEG_INFINITY, f64::max);
                    if quality >= before || best.is_some_and(|b| quality >= b.0) {
                        continue;
                    }
                    let Some(chord) = self.acceptable(&new, &replaced, keep, tolerance) else {
                        continue;
                    };
                    if !self.folds_no_sharper(&new, &replaced, &old) {
                        continue;
                    }
                    let near = near.get_or_insert_with(|| Near::boxes_of(self));
                    let crossed = *crossed.get_or_insert_with(|| {
                        let around: Vec<[u32; 3]> =
                            old.iter().map(|&t| self.mesh.corners(3 * t)).collect();
                        near.after(self, &around, &old)
                    });
                    if near.after(self, &new, &old) <= crossed {
                        best = Some((quality, h, chord));
                    }
                }
                if let Some((_, h, chord)) = best {
                    self.mesh.collapse(h, v);
                    if let Some(near) = &mut near {
                        near.note(self, old.iter().copied());
                    }
                    touched.extend(&old);
                    worst = worst.max(chord);
                    removed += 1;
                }
            }
            if removed == 0 {
                removed = self.flip_slivers(&mut near, tolerance, BELOW, &dirty, &mut touched);
            }
            if removed == 0 {
                // Settled where things changed: once more everywhere, or done.
                match dirty.take() {
                    Some(_) => continue,
                    None => break,
                }
            }
            // The vertices within two rings of a change.
            let mut ring = Vec::new();
            let mut near_change: HashSet<u32> = HashSet::new();
            for &t in touched.iter().filter(|&&t| self.mesh.is_alive(3 * t)) {
                for v in self.mesh.corners(3 * t) {
                    self.mesh.neighbours(v, &mut ring);
                    near_change.insert(v);
                    near_change.extend(&ring);
                }
            }
            dirty = Some(near_change);
        }
        worst
    }

    /// Flips inner unlabelled edges of triangles whose worst angle's
    /// cosine exceeds `below` where the two new triangles' worst angle is
    /// better, under a removal's conditions of chord and facing, crossing
    /// no more triangles than before. Returns how many.
    fn flip_slivers(
        &mut self,
        near: &mut Option<Near>,
        tolerance: Option<f64>,
        below: f64,
        dirty: &Option<HashSet<u32>>,
        touched: &mut Vec<u32>,
    ) -> usize {
        let mut flipped = 0;
        for h in 0..self.mesh.num_half_edges() {
            let g = self.mesh.opposite(h);
            if !self.mesh.is_alive(h) || g == NONE || self.mesh.edge_label[h as usize] != NONE {
                continue;
            }
            let [a, b, c] = self.mesh.corners(h);
            if !is_dirty(dirty, [a, b, c]) {
                continue;
            }
            let d = self.mesh.origin(prev(g));
            let replaced = [[a, b, c], [b, a, d]];
            let was = self
                .worst_cosine(replaced[0], None)
                .max(self.worst_cosine(replaced[1], None));
            if was <= below || !self.may_flip(h) {
                continue;
            }
            let new = [[c, a, d], [c, d, b]];
            let now = self
                .worst_cosine(new[0], None)
                .max(self.worst_cosine(new[1], None));
            if now >= was || self.acceptable(&new, &replaced, c, tolerance).is_none() {
                continue;
            }
            let old: HashSet<u32> = [h / 3, g / 3].into();
            let near = near.get_or_insert_with(|| Near::boxes_of(self));
            let crossed = near.after(self, &replaced, &old);
            if near.after(self, &new, &old) > crossed {
                continue;
            }
            self.mesh.flip(h);
            near.note(self, [h / 3, g / 3]);
            touched.extend([h / 3, g / 3]);
            flipped += 1;
        }
        flipped
    }

    /// Whether triangles `new`, replacing `replaced` (and the mesh's
    /// slots `old`), fold against their neighbours no more sharply than
    /// [`SHARPEST_FOLD`] allows, or than `replaced` did. A fold near flat
    /// is no crossing, but volume meshers take its two triangles for
    /// overlapping facets (gmsh refused joint.off's mesh so).
    fn folds_no_sharper(
        &self,
        new: &[[u32; 3]],
        replaced: &[[u32; 3]],
        old: &HashSet<u32>,
    ) -> bool {
        let after = self.sharpest_fold(new, old);
        after >= SHARPEST_FOLD || after >= self.sharpest_fold(replaced, old)
    }

    /// The smallest cosine between the unit normal of a triangle of
    /// `tris` and that of a triangle across one of its edges: another of
    /// `tris`, or one of the mesh's outside `old` (1 with none).
    fn sharpest_fold(&self, tris: &[[u32; 3]], old: &HashSet<u32>) -> f64 {
        let normal =
            |t: [u32; 3]| area_normal(t.map(|v| self.vertices[v as usize].x)).normalize_or_zero();
        let mut worst: f64 = 1.0;
        for (i, &t) in tris.iter().enumerate() {
            let n = normal(t);
            for k in 0..3 {
                let (p, q) = (t[k], t[(k + 1) % 3]);
                for (j, &u) in tris.iter().enumerate() {
                    if j != i && (0..3).any(|m| u[m] == q && u[(m + 1) % 3] == p) {
                        worst = worst.min(n.dot(normal(u)));
                    }
                }
                if let Some(h) = self.mesh.find(q, p) {
                    if !old.contains(&(h / 3)) {
                        worst = worst.min(n.dot(normal(self.mesh.corners(h))));
                    }
                }
            }
        }
        worst
    }

    /// Flips edges of crossing triangles where the two new triangles cross
    /// fewer others than the two old ones did, under the conditions of a
    /// removal (see the module doc). Returns the slots of the triangles
    /// flipped (two a flip).
    fn flip_crossings(
        &mut self,
        near: &Near,
        tolerance: Option<f64>,
        floor: Floor,
    ) -> HashSet<u32> {
        let mut slots: Vec<u32> = near.per_slot.keys().copied().collect();
        slots.sort_unstable();
        let mut busy: HashSet<u32> = HashSet::new();
        for t in slots {
            for h in 3 * t..3 * t + 3 {
                let g = self.mesh.opposite(h);
                if !self.mesh.is_alive(h)
                    || g == NONE
                    || self.mesh.edge_label[h as usize] != NONE
                    || busy.contains(&(h / 3))
                    || busy.contains(&(g / 3))
                    || !self.may_flip(h)
                {
                    continue;
                }
                let [a, b, c] = self.mesh.corners(h);
                let d = self.mesh.origin(prev(g));
                let old: HashSet<u32> = [h / 3, g / 3].into();
                let before = near.before(&old);
                let new = [[c, a, d], [c, d, b]];
                let replaced = [[a, b, c], [b, a, d]];
                let Some(_) = self.acceptable(&new, &replaced, c, tolerance) else {
                    continue;
                };
                let after = near.after(self, &new, &old);
                if !floor.helps(before, after) {
                    continue;
                }
                let least = if self.lifted(floor, &[a, b, c, d]) {
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
                if now > was.max(least) {
                    continue;
                }
                self.mesh.flip(h);
                busy.extend([h / 3, g / 3]);
            }
        }
        busy
    }

    /// Collapsing v (whose half-edges are `outgoing`) into `keep`: each
    /// triangle around v that survives, with keep for v, and the triangle
    /// it replaces.
    fn collapsed(&self, v: u32, outgoing: &[u32], keep: u32) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
        outgoing
            .iter()
            .map(|&e| (self.mesh.dest(e), self.mesh.origin(prev(e))))
            .filter(|&(y, z)| y != keep && z != keep)
            .map(|(y, z)| ([keep, y, z], [v, y, z]))
            .unzip()
    }

    /// Whether `floor` lifts the angle floor for a change moving vertices
    /// `vs`.
    fn lifted(&self, floor: Floor, vs: &[u32]) -> bool {
        match floor {
            Floor::Everywhere => false,
            Floor::OffFolds => vs.iter().any(|&v| self.on_fold(v)),
            Floor::Nowhere => true,
        }
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

/// Where a round of [`Remeshing::untangle`] keeps its angle floor (no
/// angle made below both 20° and the worst replaced).
#[derive(Clone, Copy)]
enum Floor {
    Everywhere,
    /// Lifted on folds of the surface ([`Remeshing::on_fold`]).
    OffFolds,
    /// Lifted everywhere, but only for a removal or flip whose triangles
    /// cross none at all: a thin triangle is a poor element, a crossing
    /// one a surface no volume mesher takes, and where the surface itself
    /// crosses (anchor.off's fans) a removal that only thins the pairs
    /// buys nothing and left a 0.15° triangle.
    Nowhere,
}

impl Floor {
    /// Whether a change that leaves `after` crossings where there were
    /// `before` may be made at all: fewer, and none with the floor lifted
    /// everywhere.
    fn helps(self, before: usize, after: usize) -> bool {
        after < before && (after == 0 || !matches!(self, Floor::Nowhere))
    }
}

/// Whether triangle `tri` has a corner in `dirty`, or there is no such
/// set yet (every triangle is).
fn is_dirty(dirty: &Option<HashSet<u32>>, tri: [u32; 3]) -> bool {
    dirty
        .as_ref()
        .map_or(true, |d| tri.iter().any(|v| d.contains(v)))
}

/// The mesh as it was when built (for [`Remeshing::untangle`], as a round
/// found it): its live triangles (by slot), the tree of their boxes and
/// the pairs that cross, to count the crossings of triangles that would
/// replace some of them; with the slots noted as changed since.
struct Near {
    tree: BoxTree,
    /// Per tree item: its triangle's slot, and its corners.
    slots: Vec<u32>,
    triangles: Vec<[u32; 3]>,
    points: Vec<DVec3>,
    pairs: Vec<[u32; 2]>,
    /// Crossing pairs per triangle slot.
    per_slot: HashMap<u32, usize>,
    /// Slots whose triangles changed since the tree was built, each
    /// tested as it is now (its old box may not hold it).
    changed: Vec<u32>,
    changed_set: HashSet<u32>,
}

impl Near {
    /// The mesh now, with its crossing pairs.
    fn of(work: &Remeshing) -> Near {
        let mut near = Near::boxes_of(work);
        near.pairs = crossings(&near.points, &near.triangles);
        near.count_pairs();
        near
    }

    /// The mesh now, with its crossing pairs, found from `before` (an
    /// earlier search) and the slots `changed` since: a pair of two
    /// triangles neither of which changed is one as before, so only the
    /// changed ones are searched anew. The same pairs as [`Near::of`]
    /// finds, in the same order: on pig, the rounds after the first took
    /// 0.10 to 0.15 s each on one thread, a fifth of its remeshing.
    fn since(work: &Remeshing, before: &Near, changed: &HashSet<u32>) -> Near {
        #[cfg(test)]
        tests::SINCE.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let mut near = Near::boxes_of(work);
        let mut index = vec![NONE; (work.mesh.num_half_edges() / 3) as usize];
        for (i, &s) in near.slots.iter().enumerate() {
            index[s as usize] = i as u32;
        }
        let slot = |i: u32| before.slots[i as usize];
        let mut pairs: Vec<[u32; 2]> = before
            .pairs
            .iter()
            .filter(|p| p.iter().all(|&i| !changed.contains(&slot(i))))
            .map(|p| p.map(|i| index[slot(i) as usize]))
            .map(|[i, j]| [i.min(j), i.max(j)])
            .collect();
        let mut fresh: Vec<u32> = changed
            .iter()
            .map(|&s| index[s as usize])
            .filter(|&i| i != NONE)
            .collect();
        fresh.sort_unstable();
        let is_fresh = |i: usize| changed.contains(&near.slots[i]);
        for &i in &fresh {
            let t = near.triangles[i as usize];
            let bounds = Box3::of(t.map(|v| near.points[v as usize]));
            near.tree.overlapping(&bounds, |j| {
                // A pair of two changed triangles once, from its lower.
                if j == i as usize || (is_fresh(j) && j < i as usize) {
                    return;
                }
                let (a, b) = (j.min(i as usize), j.max(i as usize));
                if cross(&near.points, near.triangles[a], near.triangles[b]) {
                    pairs.push([a as u32, b as u32]);
                }
            });
        }
        pairs.sort_unstable();
        near.pairs = pairs;
        near.count_pairs();
        near
    }

    /// Per slot: its crossing pairs.
    fn count_pairs(&mut self) {
        for &[i, j] in &self.pairs {
            for t in [i, j] {
                *self.per_slot.entry(self.slots[t as usize]).or_default() += 1;
            }
        }
    }

    /// The mesh now, its pairs not searched (none listed): for counting
    /// the crossings of some triangles only.
    fn boxes_of(work: &Remeshing) -> Near {
        let slots: Vec<u32> = (0..work.mesh.num_half_edges() / 3)
            .filter(|&t| work.mesh.is_alive(3 * t))
            .collect();
        let triangles: Vec<[u32; 3]> = slots.iter().map(|&t| work.mesh.corners(3 * t)).collect();
        let points: Vec<DVec3> = work.vertices.iter().map(|v| v.x).collect();
        let boxes: Vec<Box3> = triangles
            .iter()
            .map(|t| Box3::of(t.map(|v| points[v as usize])))
            .collect();
        Near {
            tree: BoxTree::new(&boxes),
            slots,
            triangles,
            points,
            pairs: Vec::new(),
            per_slot: HashMap::new(),
            changed: Vec::new(),
            changed_set: HashSet::new(),
        }
    }

    /// Notes that the triangles in `slots` changed; past [`REBUILD`] such,
    /// the tree is built anew on the mesh as it is (each query tests every
    /// changed triangle).
    fn note(&mut self, work: &Remeshing, slots: impl IntoIterator<Item = u32>) {
        for s in slots {
            if self.changed_set.insert(s) {
                self.changed.push(s);
            }
        }
        if self.changed.len() > REBUILD {
            *self = Near::boxes_of(work);
        }
    }

    /// The crossing pairs the triangle slots `old` are in (a pair of two
    /// of them counted twice).
    fn before(&self, old: &HashSet<u32>) -> usize {
        old.iter()
            .map(|t| self.per_slot.get(t).copied().unwrap_or(0))
            .sum()
    }

    /// The crossings triangles `new` would be in, replacing slots `old`:
    /// with the mesh as it is now, and among themselves.
    fn after(&self, work: &Remeshing, new: &[[u32; 3]], old: &HashSet<u32>) -> usize {
        let now = |s: u32| work.mesh.is_alive(3 * s).then(|| work.mesh.corners(3 * s));
        let mut after = 0;
        for (i, t) in new.iter().enumerate() {
            after += self.crossing(t, old, now);
            after += new[i + 1..]
                .iter()
                .filter(|u| cross(&self.points, *t, **u))
                .count();
        }
        after
    }

    /// How many of the round's triangles `t` crosses, leaving out those
    /// in `old` (about to go), as they are now (`now` gives a slot's
    /// corners, `None` once it is gone). A triangle an earlier removal of
    /// the round changed is tested as it is now: found by its old box,
    /// or, if listed in `changed`, wherever it is; one that left its box
    /// unlisted is caught by the next round.
    fn crossing(
        &self,
        t: &[u32; 3],
        old: &HashSet<u32>,
        now: impl Fn(u32) -> Option<[u32; 3]>,
    ) -> usize {
        let mut count = 0;
        let mut test = |slot: u32| {
            if let Some(corners) = now(slot) {
                if cross(&self.points, *t, corners) {
                    count += 1;
                }
            }
        };
        let bounds = Box3::of(t.map(|v| self.points[v as usize]));
        self.tree.overlapping(&bounds, |i| {
            let slot = self.slots[i];
            if !old.contains(&slot) && !self.changed_set.contains(&slot) {
                test(slot);
            }
        });
        for &slot in self.changed.iter().filter(|s| !old.contains(s)) {
            let here = now(slot).map(|c| Box3::of(c.map(|v| self.points[v as usize])));
            if here.is_some_and(|b| b.overlaps(&bounds)) {
                test(slot);
            }
        }
        count
    }
}

#[cfg(test)]
#[path = "../../tests/support/cgal_data.rs"]
mod cgal_data;

#[cfg(test)]
mod tests {
    use crate::{ControlNet, Remesher, Surface};
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// How many searches started from the one before.
    pub(super) static SINCE: AtomicUsize = AtomicUsize::new(0);

    use super::cgal_data;

    /// Every round's search, started from the one before and the
    /// triangles changed since, finds the pairs a search of the whole mesh
    /// finds, in the same order (the assertion in `untangle_rounds`, built
    /// into this test binary only): on mech-holes-shark adapted at 40°,
    /// whose fin takes all three stages and several rounds, and on pig at
    /// a uniform size, whose net crosses itself.
    #[test]
    fn a_search_since_the_last_round_finds_what_a_full_search_finds() {
        for (name, angle, relative) in [
            ("mech-holes-shark.off", 40.0, None),
            ("pig.off", 40.0, Some(0.005)),
        ] {
            let Some(path) = cgal_data::cgal_file(name) else {
                continue;
            };
            let mut net = ControlNet::read(&path).unwrap();
            net.tag_by_angle(angle).unwrap();
            let surface = Surface::new(&net).unwrap();
            let remesher = match relative {
                Some(r) => Remesher::new(&surface).size(r * net.bbox_diagonal()),
                None => Remesher::new(&surface).adapt_curvature(true),
            };
            let before = SINCE.load(Ordering::Relaxed);
            let mesh = remesher.parts(1).run().unwrap();
            assert!(!mesh.triangles.is_empty(), "{name}");
            assert!(
                SINCE.load(Ordering::Relaxed) > before,
                "{name}: no search started from the one before"
            );
        }
    }
}
