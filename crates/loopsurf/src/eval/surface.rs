//! The evaluator: the control net refined once, so that every triangle has
//! at most one special corner, and per triangle of that level either its
//! regular box-spline coefficients or its special corner's shared
//! configuration.
//!
//! Patches are made on first use, a block of control triangles at a time,
//! by whichever thread evaluates there first, and the refined net's
//! positions and connectivity they read are built with the first of them.
//! Building a surface then costs next to nothing (it shares the net's
//! positions and connectivity), a solver that reads only part of a large
//! net never pays for the rest, and a process that meshes a surface in
//! parts, each on its own sub-net's surface, never refines the whole.
//! What a patch holds does not depend on when or where it was made, so
//! results are the same bits whatever the order of evaluation.

use super::affine::Affine;
use super::affine::{child_containing, rotation};
use super::configurations::{ConfigurationTable, Configurations, CornerScratch};
use super::special::{neighbourhood_into, Cell, SpecialPatch};
use super::{box_spline, regular};
use crate::features::{Features, VertexKind};
use crate::net::ControlNet;
use crate::topology::Topology;
use glam::DVec3;
use rayon::prelude::*;
use std::cell::RefCell;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// How one triangle of the once-refined net is evaluated.
#[derive(Clone, Copy)]
enum Patch<'a> {
    /// A regular triangle's box-spline coefficients.
    Regular(&'a [DVec3; 15]),
    /// A triangle with a special corner.
    Special(&'a SpecialCorner),
}

/// A triangle whose corner `corner` is special: its shared configuration
/// and its neighbourhood in the once-refined net, by index and by position
/// (kept side by side: gathering them from the whole net at every point
/// was a cache miss each), and the coefficients of its first ring.
struct SpecialCorner {
    corner: u8,
    patch: Arc<SpecialPatch>,
    points: Box<[u32]>,
    positions: Box<[DVec3]>,
    /// The box-spline coefficients of the three cells of the first ring,
    /// three quarters of the triangle: there a point costs what a regular
    /// one does, where applying the configuration's band to the
    /// neighbourhood cost four times that.
    first_ring: Box<[[DVec3; 15]; 3]>,
}

impl SpecialCorner {
    /// The map from a control triangle's (v, w) in this child (which
    /// `to_child` maps to the child's parameters) to the corner's (s, t),
    /// and the cell of (v, w): `None` exactly at the special vertex, or
    /// closer than 2^-[`super::special::MAX_RINGS`] to it.
    #[inline]
    fn locate(&self, to_child: &Affine, v: f64, w: f64) -> (Affine, Option<Cell>) {
        let map = rotation(self.corner as usize).after(to_child);
        let (s, t) = map.apply(v, w);
        let cell = if s + t > 0.0 {
            Cell::locate(s, t)
        } else {
            None
        };
        (map, cell)
    }

    /// `f` of the coefficients of `cell` and the offset to add to its
    /// position: stored for the first ring, pushed down from the
    /// neighbourhood below it.
    #[inline]
    fn with_cell<R>(&self, cell: Cell, f: impl FnOnce(&[DVec3; 15], DVec3) -> R) -> R {
        if cell.rings == 0 {
            return f(&self.first_ring[cell.k - 1], DVec3::ZERO);
        }
        let (c, offset) = self.patch.cell_coefficients(&self.positions, cell);
        f(&c, offset)
    }

    /// The answer exactly at the special vertex.
    #[cold]
    fn at_vertex(&self, points: &[DVec3]) -> AtVertex {
        let around = &self.points;
        AtVertex {
            vertex: around[0],
            limit: self.patch.limit_point(points, around),
            normal: self.patch.normal_at_vertex(points, around),
        }
    }
}

/// X and its derivatives with respect to (v, w) from the coefficients and
/// offset of `cell`, which `map` and the cell's own map place.
#[inline]
fn eval_in_cell(c: &[DVec3; 15], offset: DVec3, cell: Cell, map: &Affine) -> [DVec3; 6] {
    let mut d = box_spline::eval_coefficients(c, cell.local.0, cell.local.1);
    d[0] += offset;
    map.pull_back(cell.pull_back(d))
}

/// X alone: the same bits as [`eval_in_cell`]'s.
#[inline]
fn point_in_cell(c: &[DVec3; 15], offset: DVec3, cell: Cell) -> DVec3 {
    box_spline::eval_point(c, cell.local.0, cell.local.1) + offset
}

/// Control triangles whose patches are made together. Memory is laid out
/// in the order patches are first made, and a block spans a few pages, so
/// a sweep in triangle order streams through memory however the blocks
/// were first reached. (Made one triangle at a time, a sweep after a pass
/// in random order ran a quarter slower than one after a sweep; with
/// blocks of 4, 10–18% slower; with 8, as fast.)
const BLOCK: usize = 8;

/// The patches of the children of a block of control triangles (4 per
/// triangle, in [`crate::topology::Topology::refined`]'s order), packed:
/// the coefficients of the regular ones side by side as in one table, so
/// that evaluation reads as little memory as when all were made up front.
struct Block {
    /// Per child, its index in `regular`, or [`SPECIAL`] plus its index in
    /// `special`.
    slots: [u8; 4 * BLOCK],
    regular: Box<[[DVec3; 15]]>,
    special: Box<[SpecialCorner]>,
}

const SPECIAL: u8 = 0x80;

impl Block {
    /// The patch of child `k` of the block's triangle `tri`.
    fn get(&self, tri: usize, k: usize) -> Patch<'_> {
        match self.slots[4 * (tri % BLOCK) + k] {
            i if i < SPECIAL => Patch::Regular(&self.regular[i as usize]),
            i => Patch::Special(&self.special[(i - SPECIAL) as usize]),
        }
    }
}

thread_local! {
    /// Buffers for making special patches, reused on each thread.
    static SCRATCH: RefCell<Scratch> = RefCell::default();
}

#[derive(Default)]
struct Scratch {
    regular: Vec<[DVec3; 15]>,
    special: Vec<SpecialCorner>,
    around: Vec<u32>,
    corner: CornerScratch,
}

/// An evaluator of the limit surface of a control net. Keeps the
/// positions of the once-refined net and, per control triangle, its
/// children's patches once they are made.
pub struct Evaluator {
    /// The once-refined net's positions, refined with its connectivity
    /// (by [`Evaluator::maker`]): a surface that never makes a patch, as
    /// the whole surface on a process that meshes it in parts, never
    /// holds them (230 MB on a net of 4.8M triangles).
    points: OnceLock<Vec<DVec3>>,
    blocks: Box<[OnceLock<Block>]>,
    /// What making patches reads: built when the first patch is made,
    /// released once every patch is made (the refined net's connectivity
    /// is a fifth of a fully made surface).
    maker: Mutex<MakerState>,
    unmade: AtomicUsize,
    configurations: Configurations,
}

/// The maker's life: to be built from the control net's connectivity,
/// hard features and positions (shared with the net), built, then
/// released.
enum MakerState {
    Coarse {
        topo: Arc<Topology>,
        features: Features,
        points: Arc<Vec<DVec3>>,
    },
    Made(Arc<Maker>),
    Released,
}

/// The connectivity and hard features of the once-refined net.
struct Maker {
    topo: Topology,
    features: Features,
    kinds: Vec<VertexKind>,
}

impl Evaluator {
    pub fn new(net: &ControlNet) -> crate::Result<Evaluator> {
        Self::sharing(net, Arc::default())
    }

    /// The evaluator of `net`, keeping its special-corner configurations in
    /// `table` (which other evaluators may share: a configuration depends
    /// only on the pattern around its corner).
    pub(crate) fn sharing(
        net: &ControlNet,
        table: Arc<ConfigurationTable>,
    ) -> crate::Result<Evaluator> {
        let refined = crate::refine::once_refined_vertices(net)?;
        let configurations = Configurations::new(refined, table);
        let n = net.triangles().len();
        Ok(Evaluator {
            points: OnceLock::new(),
            blocks: (0..n.div_ceil(BLOCK)).map(|_| OnceLock::new()).collect(),
            maker: Mutex::new(MakerState::Coarse {
                topo: net.shared_topology(),
                features: net.features().clone(),
                points: net.shared_points(),
            }),
            unmade: AtomicUsize::new(n.div_ceil(BLOCK)),
            configurations,
        })
    }

    /// The table this evaluator keeps its configurations in.
    pub(crate) fn configuration_table(&self) -> &Arc<ConfigurationTable> {
        self.configurations.table()
    }

    /// The maker, built by the first caller with the refined positions
    /// (the others wait for it: both are built on the calling thread
    /// alone, never waiting on the pool nor evaluating, so a waiting
    /// thread holds nothing it needs), or `None` once released.
    fn maker(&self) -> Option<Arc<Maker>> {
        let mut state = self.maker.lock().unwrap_or_else(|e| e.into_inner());
        if let MakerState::Coarse {
            topo,
            features,
            points,
        } = &*state
        {
            let refined = crate::refine::subdivide_points_here(topo, features, points);
            // Set only here, under the lock, once.
            let _ = self.points.set(refined);
            *state = MakerState::Made(Arc::new(Maker::refine(topo, features)));
        }
        match &*state {
            MakerState::Made(maker) => Some(maker.clone()),
            _ => None,
        }
    }

    /// The patch of child `k` of control triangle `tri`.
    fn patch(&self, tri: usize, k: usize) -> Patch<'_> {
        match self.blocks[tri / BLOCK].get() {
            Some(block) => block.get(tri, k),
            None => self.make(tri / BLOCK).get(tri, k),
        }
    }

    /// Makes the patches of block `b`. Never waits for another thread's
    /// making (no lock is held while making; a thread waits only while
    /// [`Evaluator::maker`] is first built): two racing to make one block
    /// both make it and the first is kept, and a thread that steals work
    /// while making a configuration and meets this block again makes it
    /// once more instead of deadlocking.
    #[cold]
    #[inline(never)]
    fn make(&self, b: usize) -> &Block {
        let cell = &self.blocks[b];
        // Released only once every block was set: if it is gone, so is the
        // need.
        if let Some(maker) = self.maker() {
            let made = maker.block(b, self.refined_points(), &self.configurations);
            if cell.set(made).is_ok() && self.unmade.fetch_sub(1, Ordering::AcqRel) == 1 {
                *self.maker.lock().unwrap_or_else(|e| e.into_inner()) = MakerState::Released;
            }
        }
        cell.get()
            .expect("made above, or by another thread before the maker was released")
    }

    /// Makes every patch not made yet, in parallel and in triangle order:
    /// for a caller about to read them all (the snap index), which would
    /// otherwise make them one at a time in its own order.
    pub fn make_all(&self) {
        (0..self.blocks.len())
            .into_par_iter()
            .with_min_len(64)
            .for_each(|b| {
                self.patch(b * BLOCK, 0);
            });
    }

    /// Which kind of patch serves (v, w) of `tri` (for test messages).
    #[cfg(test)]
    pub fn describe(&self, tri: usize, v: f64, w: f64) -> String {
        let (k, _) = child_containing(v, w);
        match self.patch(tri, k) {
            Patch::Regular(_) => format!("child {k}: regular"),
            Patch::Special(s) => format!(
                "child {k}: special corner {}, neighbourhood {:?}",
                s.corner, s.points
            ),
        }
    }

    /// Bytes held: the once-refined net (its positions from the first
    /// patch made, its connectivity from then until every patch is made;
    /// before, a copy of the control net's hard features, its positions and
    /// connectivity being the net's), the patches made so far and each
    /// configuration built so far once.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let made: usize = self
            .blocks
            .iter()
            .filter_map(OnceLock::get)
            .map(|c| {
                c.regular.len() * size_of::<[DVec3; 15]>()
                    + c.special
                        .iter()
                        .map(|s| {
                            size_of::<SpecialCorner>()
                                + size_of::<[[DVec3; 15]; 3]>()
                                + s.points.len() * (size_of::<u32>() + size_of::<DVec3>())
                        })
                        .sum::<usize>()
            })
            .sum();
        let maker = match &*self.maker.lock().unwrap_or_else(|e| e.into_inner()) {
            MakerState::Coarse { features, .. } => features.memory_bytes(),
            MakerState::Made(m) => {
                m.topo.memory_bytes()
                    + m.features.memory_bytes()
                    + m.kinds.len() * size_of::<VertexKind>()
            }
            MakerState::Released => 0,
        };
        self.points.get().map_or(0, Vec::len) * size_of::<DVec3>()
            + maker
            + self.blocks.len() * size_of::<OnceLock<Block>>()
            + made
            + self.configurations.memory_bytes()
    }

    /// Number of distinct special-corner configurations built so far.
    pub fn configurations(&self) -> usize {
        self.configurations.len()
    }

    /// The special configuration of level-1 child `child` (0 to 2: the one
    /// at corner `child` of control triangle `tri`) with its neighbourhood
    /// in [`Evaluator::refined_points`], or `None` for a regular child.
    pub fn special_corner(&self, tri: usize, child: usize) -> Option<(&SpecialPatch, &[u32])> {
        match self.patch(tri, child) {
            Patch::Regular(_) => None,
            Patch::Special(s) => Some((&s.patch, &s.points)),
        }
    }

    /// The polynomial piece of the surface holding (v, w) of `tri` (which
    /// must not be a special vertex) in Bernstein–Bézier form on its own
    /// triangle ([`box_spline::bernstein`]), with the map from the control
    /// triangle's (v, w) to that triangle's parameters.
    pub fn bezier_at(&self, tri: usize, v: f64, w: f64) -> Option<([DVec3; 15], Affine)> {
        let (k, to_child) = child_containing(v, w);
        match self.patch(tri, k) {
            Patch::Regular(coefficients) => Some((box_spline::bernstein(coefficients), to_child)),
            Patch::Special(s) => {
                let (to_corner, cell) = s.locate(&to_child, v, w);
                let cell = cell?;
                let bezier = s.with_cell(cell, |c, offset| {
                    box_spline::bernstein(c).map(|x| x + offset)
                });
                Some((bezier, cell_map(cell).after(&to_corner)))
            }
        }
    }

    /// [`Evaluator::bezier_at`] for a point of a ring around the special
    /// corner of child `child` of `tri`, from that ring's neighbourhood
    /// (`ring`, offsets from the vertex's limit `limit`, as
    /// [`SpecialPatch::ring_offsets`] gives them): skips pushing the
    /// neighbourhood down, which a caller walking the rings has done.
    pub fn ring_bezier(
        &self,
        tri: usize,
        child: usize,
        (ring, limit): (&[DVec3], DVec3),
        (v, w): (f64, f64),
    ) -> Option<([DVec3; 15], Affine)> {
        let Patch::Special(s) = self.patch(tri, child) else {
            return None;
        };
        let to_corner = rotation(s.corner as usize).after(&super::affine::child(child));
        let (a, b) = to_corner.apply(v, w);
        let cell = Cell::locate(a, b)?;
        let bezier = s.patch.band_bezier(cell.k, ring).map(|x| x + limit);
        Some((bezier, cell_map(cell).after(&to_corner)))
    }

    /// The positions of the once-refined net (refined now if no patch
    /// was made yet).
    pub fn refined_points(&self) -> &[DVec3] {
        if self.points.get().is_none() {
            self.maker();
        }
        self.points
            .get()
            .expect("refined with the maker, before any patch and before it is released")
    }

    /// X alone at (v, w) of control triangle `tri`: the same bits as
    /// `eval(..)[0]` (or the vertex's limit), at a fraction of the cost on
    /// regular triangles.
    pub fn point(&self, tri: usize, v: f64, w: f64) -> DVec3 {
        let (k, to_child) = child_containing(v, w);
        match self.patch(tri, k) {
            Patch::Regular(coefficients) => {
                let (s, u) = to_child.apply(v, w);
                box_spline::eval_point(coefficients, s, u)
            }
            Patch::Special(special) => match special.locate(&to_child, v, w) {
                (_, Some(cell)) => special.with_cell(cell, |c, o| point_in_cell(c, o, cell)),
                (_, None) => special.at_vertex(self.refined_points()).limit,
            },
        }
    }

    /// X, Xv, Xw, Xvv, Xvw, Xww at (v, w) of control triangle `tri`, or,
    /// exactly at a special vertex, that vertex (of the refined net) and its
    /// exact limit position: the parametrisation is singular there.
    #[inline]
    pub fn eval(&self, tri: usize, v: f64, w: f64) -> Result<[DVec3; 6], AtVertex> {
        let (k, to_child) = child_containing(v, w);
        match self.patch(tri, k) {
            Patch::Regular(coefficients) => {
                let (s, u) = to_child.apply(v, w);
                let d = box_spline::eval_coefficients(coefficients, s, u);
                Ok(to_child.pull_back(d))
            }
            // Spelled out rather than through `with_cell`: its closure,
            // called twice there, was not inlined and cost 5% in copies.
            Patch::Special(special) => match special.locate(&to_child, v, w) {
                (map, Some(cell)) if cell.rings == 0 => {
                    let c = &special.first_ring[cell.k - 1];
                    Ok(eval_in_cell(c, DVec3::ZERO, cell, &map))
                }
                (map, Some(cell)) => {
                    let (c, offset) = special.patch.cell_coefficients(&special.positions, cell);
                    Ok(eval_in_cell(&c, offset, cell, &map))
                }
                (_, None) => Err(special.at_vertex(self.refined_points())),
            },
        }
    }
}

impl Maker {
    /// The connectivity, hard features and vertex kinds of the control
    /// net `topo` refined once, built on the calling thread alone.
    fn refine(topo: &Topology, features: &Features) -> Maker {
        let fine = topo.refined_here();
        fine.order_rings_from(topo);
        let features = features.refined(topo);
        let kinds = features.vertex_kinds(&fine);
        Maker {
            topo: fine,
            features,
            kinds,
        }
    }

    /// The patches of block `b`.
    fn block(&self, b: usize, points: &[DVec3], configurations: &Configurations) -> Block {
        // Taken out, not borrowed: a thread that steals work while making
        // a configuration may come back here.
        let mut scratch = SCRATCH.with(RefCell::take);
        // Gathered in reused buffers, then boxed at their size.
        let (mut regular, mut special) = (
            std::mem::take(&mut scratch.regular),
            std::mem::take(&mut scratch.special),
        );
        // Slots of level-1 triangles past the end (in the last block) are
        // never read.
        let children = 4 * b * BLOCK..(4 * (b + 1) * BLOCK).min(self.topo.num_triangles());
        let mut slots = [0; 4 * BLOCK];
        for (slot, t) in slots.iter_mut().zip(children) {
            *slot = match self.patch(t, points, configurations, &mut scratch) {
                Ok(coefficients) => {
                    regular.push(coefficients);
                    regular.len() as u8 - 1
                }
                Err(corner) => {
                    special.push(corner);
                    SPECIAL + special.len() as u8 - 1
                }
            };
        }
        let block = Block {
            slots,
            regular: regular.drain(..).collect(),
            special: special.drain(..).collect(),
        };
        (scratch.regular, scratch.special) = (regular, special);
        SCRATCH.with(|s| s.replace(scratch));
        block
    }

    /// The box-spline coefficients of triangle `t` of the once-refined
    /// net, or its special corner.
    fn patch(
        &self,
        t: usize,
        points: &[DVec3],
        configurations: &Configurations,
        scratch: &mut Scratch,
    ) -> Result<[DVec3; 15], SpecialCorner> {
        let (topo, features) = (&self.topo, &self.features);
        if let Some(s) = regular::stencil(topo, features, &self.kinds, t) {
            let control = s.map(|p| p.position(points));
            return Ok(box_spline::coefficients(&control));
        }
        // Child k < 3 of a control triangle has the control vertex at its
        // corner k; the centre child is always regular.
        let corner = t % 4;
        debug_assert!(corner < 3, "centre children are regular");
        let c = topo.triangles()[t];
        let [c, p, q] = [c[corner], c[(corner + 1) % 3], c[(corner + 2) % 3]];
        neighbourhood_into(topo, c, p, q, &mut scratch.around);
        let patch =
            configurations.of_corner(topo, features, &self.kinds, [c, p, q], &mut scratch.corner);
        let positions: Box<[DVec3]> = scratch.around.iter().map(|&i| points[i as usize]).collect();
        Err(SpecialCorner {
            corner: corner as u8,
            first_ring: Box::new([1, 2, 3].map(|k| patch.band_coefficients(k, &positions))),
            patch,
            points: Box::from(&scratch.around[..]),
            positions,
        })
    }
}

/// Evaluation inside one control triangle that remembers the coefficients
/// of every special cell it visits below the first ring. There most of an
/// evaluation's cost is pushing the neighbourhood down to the point's ring;
/// a mesher evaluating thousands of points in one triangle pays it once per
/// ring instead of once per point. Results are bit-identical to
/// [`Evaluator::eval`] and [`Evaluator::point`].
pub struct ChartEvaluator<'a> {
    evaluator: &'a Evaluator,
    tri: usize,
    cells: Vec<CachedCell>,
}

/// The coefficients and position offset of one special cell, keyed by the
/// level-1 child it lies in, its ring and its sub-triangle.
struct CachedCell {
    key: (usize, usize, usize),
    coefficients: [DVec3; 15],
    offset: DVec3,
}

impl<'a> ChartEvaluator<'a> {
    pub fn new(evaluator: &'a Evaluator, tri: usize) -> Self {
        ChartEvaluator {
            evaluator,
            tri,
            cells: Vec::new(),
        }
    }

    /// The cell of (v, w) in special child `child` (`to_child` maps to
    /// its parameters), the map from (v, w) to the corner's (s, t), and
    /// the cell's coefficients and offset: the first ring's as stored,
    /// a deeper cell's pushed down on its first visit and kept. `Err`
    /// exactly at the vertex, `None` in a regular child.
    #[allow(clippy::type_complexity)]
    fn special(
        &mut self,
        child: usize,
        to_child: Affine,
        v: f64,
        w: f64,
    ) -> Option<Result<(Cell, Affine, &[DVec3; 15], DVec3), AtVertex>> {
        let Patch::Special(special) = self.evaluator.patch(self.tri, child) else {
            return None;
        };
        let (map, cell) = special.locate(&to_child, v, w);
        let Some(cell) = cell else {
            return Some(Err(special.at_vertex(self.evaluator.refined_points())));
        };
        if cell.rings == 0 {
            return Some(Ok((
                cell,
                map,
                &special.first_ring[cell.k - 1],
                DVec3::ZERO,
            )));
        }
        let key = (child, cell.rings, cell.k);
        let slot = match self.cells.iter().position(|c| c.key == key) {
            Some(slot) => slot,
            None => {
                let (coefficients, offset) =
                    special.patch.cell_coefficients(&special.positions, cell);
                self.cells.push(CachedCell {
                    key,
                    coefficients,
                    offset,
                });
                self.cells.len() - 1
            }
        };
        let cached = &self.cells[slot];
        Some(Ok((cell, map, &cached.coefficients, cached.offset)))
    }

    /// X at (v, w); like [`Evaluator::point`].
    pub fn point(&mut self, v: f64, w: f64) -> DVec3 {
        let (k, to_child) = child_containing(v, w);
        let tri = self.tri;
        match self.special(k, to_child, v, w) {
            None => self.evaluator.point(tri, v, w),
            Some(Ok((cell, _, c, offset))) => point_in_cell(c, offset, cell),
            Some(Err(at)) => at.limit,
        }
    }

    /// X and its derivatives at (v, w); like [`Evaluator::eval`].
    pub fn eval(&mut self, v: f64, w: f64) -> Result<[DVec3; 6], AtVertex> {
        let (k, to_child) = child_containing(v, w);
        let tri = self.tri;
        match self.special(k, to_child, v, w) {
            None => self.evaluator.eval(tri, v, w),
            Some(found) => found.map(|(cell, map, c, offset)| eval_in_cell(c, offset, cell, &map)),
        }
    }
}

/// The map from a special corner's (s, t) to the parameters of `cell`.
fn cell_map(cell: Cell) -> Affine {
    let scale = (cell.rings as f64).exp2();
    super::affine::child(cell.k).after(&Affine {
        m: [[scale, 0.0], [0.0, scale]],
        b: [0.0, 0.0],
    })
}

/// An evaluation that landed exactly on a special vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtVertex {
    /// The vertex in the once-refined net (control vertices keep their index).
    pub vertex: u32,
    /// Its exact limit position.
    pub limit: DVec3,
    /// The outward unit normal there of the sector the triangle lies in,
    /// when the sector has a tangent plane.
    pub normal: Option<DVec3>,
}

#[cfg(test)]
mod tests {
    use super::Evaluator;
    use crate::refine::refine_uniform;
    use crate::ControlNet;

    /// Building refines nothing: the once-refined positions come with the
    /// first patch (a surface never evaluated, as the whole surface on a
    /// process meshing it in parts, never holds them), and they are the
    /// net refined once, crease rules included.
    #[test]
    fn positions_are_refined_with_the_first_patch() {
        let ex = crate::examples::viking();
        let mut net = ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
        net.tag_by_angle(30.0).unwrap();
        let evaluator = Evaluator::new(&net).unwrap();
        assert!(evaluator.points.get().is_none(), "refined when built");
        evaluator.point(0, 0.2, 0.3);
        let refined = refine_uniform(&net, 1).unwrap();
        assert_eq!(
            evaluator.points.get().map(Vec::as_slice),
            Some(refined.net().points()),
            "not the net refined once"
        );
    }
}
