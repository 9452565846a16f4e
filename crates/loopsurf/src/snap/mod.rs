//! Snapping: the closest point of the limit surface to any xyz — the
//! global minimum of the distance, certified by a proven lower bound.
//!
//! Branch and bound, best first. The index ([`index`]) is a box hierarchy
//! over the control triangles' patches and, below each patch, a quadtree of
//! cells, every node with a convex container of its piece of surface
//! ([`cell`]). Below the index's finest cells the search goes on in pieces
//! ([`piece`]): dyadic triangles in one polynomial of the surface, held in
//! Bézier form, or the corner regions of special vertices. Everything waits
//! in one heap keyed by a lower bound on the distance to what it holds, and
//! is opened in that order.
//!
//! A piece is closed — it cannot hold a point nearer than the best found by
//! more than the tolerance — in one of two ways. Its container's bound
//! reaches the best distance less the tolerance; or the squared distance is
//! proven convex over it ([`certify`]), so that the piece has one minimum,
//! found by a confined Newton solve ([`local`]) and bounded from below to
//! round-off. Any other piece is split, and its children's containers are
//! tighter (to second order in their size). Nothing is assumed about the
//! number of minima: constrained minima on hard edges, corners and
//! boundaries are answers like any other, and next to special vertices,
//! where the parametrisation is singular, the corner regions shrink
//! geometrically until their bounds close them.
//!
//! Each special vertex opened is itself a candidate: when it is the answer,
//! no ring around it could prove that alone.
//!
//! The certificate is the smallest bound of all that was closed; it goes
//! out with the answer as [`Snap::lower_bound`]. Where the tolerance cannot
//! be reached, the search stops and reports the weaker bound it proved:
//! past [`MAX_SPLITS`] splits (a point at the focus of a sphere, where a
//! whole region is nearest), and past `MAX_LEVEL` halvings of the
//! parameters — met within about 1e-8 of the diagonal from a vertex of
//! valence 40 or more, whose rings shrink by only 0.6 a step (the gap stays
//! below 1e-10 there), and near special vertices of a displaced surface,
//! whose linear displacement the corner regions bound to first order only.

mod bezier;
mod cell;
mod certify;
mod index;
mod local;
mod piece;
mod project;

use index::Content;
pub(crate) use index::SnapIndex;
pub(crate) use local::descend_confined;
pub use local::Snap;
use piece::{Piece, Shape};
pub(crate) use project::checked_start;
pub use project::{project, project_in_face};

use crate::error::{Error, Result};
use crate::surface::Surface;
use glam::{DVec2, DVec3};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The default certificate tolerance, relative to the bounding-box
/// diagonal: the answer is within this of the global minimum, proven.
pub const DEFAULT_TOLERANCE: f64 = 1e-12;

/// Pieces split per query before the search gives up on the tolerance.
pub const MAX_SPLITS: usize = 4096;

/// Pieces deeper than this are closed by their container: their size in
/// parameters (2⁻⁴⁴ ≈ 6e-14) is a few hundred units in the last place of
/// the coordinates near 1, where finer dyadic triangles stop being exact.
const MAX_LEVEL: u32 = 44;

/// The point of the surface nearest to `p` (the global minimum of the
/// distance), with its triangle and parameters and a proven lower bound
/// on the distance within [`DEFAULT_TOLERANCE`] × diagonal of it. Where
/// several points are equally near, one of them.
pub fn closest_point(surface: &Surface, p: DVec3) -> Result<Snap> {
    closest_point_within(surface, p, DEFAULT_TOLERANCE)
}

/// [`closest_point`] with a certificate tolerance of
/// `tolerance` × diagonal: the search stops once no region it has not
/// closed could hold a point nearer by more than that. Looser is
/// faster.
pub fn closest_point_within(surface: &Surface, p: DVec3, tolerance: f64) -> Result<Snap> {
    check_point(p)?;
    check_tolerance(tolerance)?;
    Ok(search(surface, p, None, tolerance))
}

/// [`closest_point`] starting from a point known to be near
/// the answer (a neighbouring query's result, say): the local solve
/// walks from the hint across triangles, then the global search runs
/// with that distance as its bound — usually only confirming it.
pub fn snap_near(surface: &Surface, p: DVec3, tri: usize, v: f64, w: f64) -> Result<Snap> {
    snap_near_in(surface, surface.derived(SnapIndex::new), p, tri, v, w)
}

/// [`snap_near`] over `index`.
fn snap_near_in(
    surface: &Surface,
    index: &SnapIndex,
    p: DVec3,
    tri: usize,
    v: f64,
    w: f64,
) -> Result<Snap> {
    check_point(p)?;
    let (v, w) = checked_guess(surface, tri, v, w)?;
    let seed = local::descend(surface, p, tri, v, w);
    Ok(search_in(
        surface,
        index,
        p,
        Some(seed.0),
        DEFAULT_TOLERANCE,
        &|_| true,
    ))
}

/// Builds the surface's snap index now, on the current rayon pool, unless
/// a snap has built it already. The first snap builds it otherwise, and
/// in a parallel loop of snaps every other worker of the pool would wait
/// for the one building it instead of helping: bunny00's index took
/// 1.27 s on two threads so, 0.71 s built before the loop. Call it before
/// such a loop.
pub fn build_index(surface: &Surface) {
    surface.derived(SnapIndex::new);
}

/// Certified snaps for the few queries that local projection cannot
/// settle among many it does (a chord-error check certifies only the
/// probes that could hold the maximum). They search an index of whole
/// patches, cached on the surface beside the full one: it builds in a
/// quarter of the time (bunny00: 0.42 s against 1.6 s on one thread) and
/// answers each query more slowly, which a few hundred queries do not
/// feel. Always that index, even where the full one is built, so that
/// an answer does not depend on which snaps ran before. Make one before
/// the parallel loop of its snaps (see [`build_index`]).
pub(crate) struct FewSnaps<'a> {
    surface: &'a Surface,
    index: &'a SnapIndex,
}

/// The cache's own kind for the index of whole patches.
struct WholePatches(SnapIndex);

impl crate::surface::Derived for WholePatches {
    fn memory_bytes(&self) -> usize {
        crate::surface::Derived::memory_bytes(&self.0)
    }
}

impl<'a> FewSnaps<'a> {
    pub(crate) fn new(surface: &'a Surface) -> FewSnaps<'a> {
        let index = &surface
            .derived(|s| WholePatches(SnapIndex::whole_patches(s)))
            .0;
        FewSnaps { surface, index }
    }

    /// [`snap_near`] through the index of whole patches.
    pub(crate) fn snap_near(&self, p: DVec3, tri: usize, v: f64, w: f64) -> Result<Snap> {
        snap_near_in(self.surface, self.index, p, tri, v, w)
    }
}

/// A guess (tri, v, w), validated like any query and with round-off
/// outside the triangle clamped.
fn checked_guess(surface: &Surface, tri: usize, v: f64, w: f64) -> Result<(f64, f64)> {
    surface.eval(tri, v, w)?;
    let (v, w) = (v.max(0.0), w.max(0.0));
    Ok(if v + w > 1.0 {
        (v / (v + w), w / (v + w))
    } else {
        (v, w)
    })
}

/// Best-first branch and bound from an optional first candidate.
fn search(surface: &Surface, p: DVec3, seed: Option<Snap>, tolerance: f64) -> Snap {
    let index = surface.derived(SnapIndex::new);
    search_in(surface, index, p, seed, tolerance, &|_| true)
}

/// [`search`] over the patches of `index` (those of the triangles
/// `allowed` admits, see [`SnapIndex::over`]), every walk kept to them.
pub(crate) fn search_in(
    surface: &Surface,
    index: &SnapIndex,
    p: DVec3,
    seed: Option<Snap>,
    tolerance: f64,
    allowed: &local::Allowed,
) -> Snap {
    let mut search = Search {
        surface,
        allowed,
        p,
        // A little tighter: near 1e-12 of the diagonal the round-off of
        // the distances themselves (1e-16 of their size) must not let
        // the gap exceed what was asked for.
        tolerance: tolerance * index.diagonal * 0.99,
        pad: index.piece_pad,
        best: seed,
        best_distance: seed.map_or(f64::INFINITY, |b| b.distance),
        closed: f64::INFINITY,
        pending: BinaryHeap::with_capacity(64),
        next: None,
        pieces: Vec::new(),
        splits: 0,
    };
    search.offer(index.nodes[0].distance(p), Item::Node(0));
    while let Some((bound, item)) = search.take() {
        if bound >= search.best_distance - search.tolerance || search.splits > MAX_SPLITS {
            // Nothing left is below this bound.
            search.close(bound);
            break;
        }
        match item {
            Item::Node(i) => match index.nodes[i as usize].content {
                Content::Children(l, r) => {
                    for c in [l, r] {
                        search.offer(index.nodes[c as usize].distance(p), Item::Node(c));
                    }
                }
                Content::Patch(t) => {
                    let b = index
                        .cell(0, t as usize)
                        .lower_bound(p, search.best_distance);
                    search.offer(b.max(bound), Item::Cell(0, t));
                }
            },
            Item::Cell(k, c) if k < index.level => {
                for child in 4 * c..4 * c + 4 {
                    let b = index
                        .cell(k + 1, child as usize)
                        .lower_bound(p, search.best_distance);
                    search.offer(b.max(bound), Item::Cell(k + 1, child));
                }
            }
            Item::Cell(_, cell) => {
                let cell = cell as usize;
                if search.best.is_none() {
                    // The first solve walks to a local minimum of the
                    // surface: a good bound to prune with.
                    let (tri, uv) = index.start(cell, p);
                    let (walked, _) = local::descend_confined(surface, p, tri, uv.x, uv.y, allowed);
                    search.improve(walked);
                }
                // Pieces start one level below whole control triangles.
                let level = index.level.max(1);
                let first = cell << (2 * (level - index.level));
                for piece in first..first + (1 << (2 * (level - index.level))) {
                    let (tri, corners) = cell::cell_corners(piece, level);
                    let piece = Piece::new(surface, tri, level, corners);
                    // A special corner's region is bounded more tightly by
                    // the cell's container than by its own: split it now.
                    // A polynomial's Bézier hull is tighter: queue it.
                    match piece.shape {
                        Shape::Corner { .. } => search.open(piece, bound),
                        Shape::Poly(_) => search.add(piece, bound),
                    }
                }
            }
            Item::Piece(i) => {
                let piece = search.pieces[i as usize].take().expect("opened once");
                search.open(piece, bound);
            }
        }
    }
    let mut best = search.best.expect("a surface has at least one triangle");
    best.lower_bound = search.closed.min(best.distance).max(0.0);
    best
}

/// The state of one query's search.
struct Search<'a> {
    surface: &'a Surface,
    /// The triangles walks may enter.
    allowed: &'a local::Allowed<'a>,
    p: DVec3,
    /// Absolute tolerance of the certificate.
    tolerance: f64,
    /// Round-off allowance of the pieces' containers and bounds.
    pad: f64,
    best: Option<Snap>,
    best_distance: f64,
    /// The smallest lower bound of everything closed so far.
    closed: f64,
    pending: BinaryHeap<Reverse<(Bound, Item)>>,
    /// An item to open next, held out of the heap: no bound there is
    /// smaller. Following the nearest child directly saves a push and a
    /// pop for every step down the hierarchy.
    next: Option<(f64, Item)>,
    /// Pieces waiting in the heap (taken when opened).
    pieces: Vec<Option<Piece>>,
    splits: usize,
}

impl Search<'_> {
    /// Queues `item` with its lower bound, or closes it if the bound is
    /// within the tolerance of the best distance.
    fn offer(&mut self, bound: f64, item: Item) {
        if bound >= self.best_distance - self.tolerance {
            self.close(bound);
            return;
        }
        let top = self
            .pending
            .peek()
            .map_or(f64::INFINITY, |Reverse((Bound(b), _))| *b);
        match self.next {
            None if bound <= top => self.next = Some((bound, item)),
            Some((held, held_item)) if bound < held => {
                self.pending.push(Reverse((Bound(held), held_item)));
                self.next = Some((bound, item));
            }
            _ => self.pending.push(Reverse((Bound(bound), item))),
        }
    }

    /// The item with the smallest bound.
    fn take(&mut self) -> Option<(f64, Item)> {
        self.next.take().or_else(|| {
            self.pending
                .pop()
                .map(|Reverse((Bound(b), item))| (b, item))
        })
    }

    fn close(&mut self, bound: f64) {
        self.closed = self.closed.min(bound);
    }

    fn improve(&mut self, found: Snap) {
        if found.distance < self.best_distance {
            self.best_distance = found.distance;
            self.best = Some(found);
        }
    }

    /// Queues a piece under its container's bound (at least its parent's).
    fn add(&mut self, piece: Piece, parent: f64) {
        let bound = piece
            .container(self.surface, self.pad)
            .lower_bound(self.p, self.best_distance)
            .max(parent);
        if bound >= self.best_distance - self.tolerance {
            self.close(bound);
            return;
        }
        self.pieces.push(Some(piece));
        self.offer(bound, Item::Piece(self.pieces.len() as u32 - 1));
    }

    /// A piece whose container does not rule it out: closed by a convexity
    /// certificate, or searched for a nearer point and split.
    fn open(&mut self, piece: Piece, bound: f64) {
        if let Shape::Poly(q) = &piece.shape {
            let d = q.derivatives();
            match certify::convexity(q, &d, self.p) {
                Some(convex) => {
                    if let Some(closing) = self.certify(&piece, q, &d, &convex) {
                        self.close(closing.max(bound));
                        return;
                    }
                }
                // Several minima may share the piece: the nearest one's
                // basin is found while splitting, but a local minimum now
                // prunes the others' pieces sooner.
                None => {
                    self.solve(&piece, q, None);
                }
            }
        }
        if let Shape::Corner { at, .. } = piece.shape {
            // The special vertex itself is a candidate: when it is the
            // answer, no ring around it could prove that to the tolerance.
            let uv = piece.corners[at];
            let x = self
                .surface
                .point(piece.tri, uv.x, uv.y)
                .expect("a corner of the triangle");
            self.improve(Snap {
                tri: piece.tri,
                v: uv.x,
                w: uv.y,
                point: x,
                distance: (x - self.p).length(),
                lower_bound: 0.0,
            });
        }
        if piece.level >= MAX_LEVEL {
            self.close(bound);
            return;
        }
        self.splits += 1;
        for child in piece.split(self.surface) {
            self.add(child, bound);
        }
    }

    /// The minimum of the distance over the piece (a local one where it is
    /// not convex), from the point of its flat triangle nearest to p; a
    /// nearer point than the best walks on across the piece's sides.
    fn solve(&mut self, piece: &Piece, q: &bezier::Quartic, start: Option<DVec2>) -> Snap {
        let p = self.p;
        let [a, b, c] = q.corners();
        let centre = DVec2::splat(1.0 / 3.0);
        // A piece whose flat triangle is degenerate starts at its centre.
        let start = start.unwrap_or_else(|| {
            let near = cell::closest_in_triangle(p, a, b, c);
            piece.global(if near.is_finite() {
                0.95 * near + 0.05 * centre
            } else {
                centre
            })
        });
        let region = local::Region::new(piece.corners);
        let (own, _) = local::descend_within(self.surface, p, piece.tri, start, &region);
        if own.distance < self.best_distance {
            let (walked, _) =
                local::descend_confined(self.surface, p, piece.tri, own.v, own.w, self.allowed);
            self.improve(own);
            self.improve(walked);
        }
        own
    }

    /// For a polynomial piece over which the squared distance is proven
    /// convex: a lower bound on the distance to the piece, within the
    /// tolerance of the best distance. The piece's minimum is found in its
    /// own polynomial first; only when it beats the best is it solved for
    /// on the surface. `None` when the piece must be split (round-off left
    /// the bound short of the tolerance).
    fn certify(
        &mut self,
        piece: &Piece,
        q: &bezier::Quartic,
        d: &bezier::Derivatives,
        convex: &certify::Convex,
    ) -> Option<f64> {
        let p = self.p;
        let pad = self.pad;
        let distance = |f: f64| (2.0 * f.max(0.0)).sqrt() - pad;
        // The piece's minimum, in its own polynomial: if it is no nearer than
        // the best, the piece is closed without touching the evaluator.
        let threshold = self.best_distance - self.tolerance + pad;
        let enough = if threshold > 0.0 {
            0.5 * threshold * threshold
        } else {
            0.0
        };
        let (bound, u) = convex.bound(q, d, p, enough);
        let bound = distance(bound);
        if bound >= self.best_distance - self.tolerance {
            return Some(bound);
        }
        // It holds a nearer point: solve for it exactly (and walk on).
        let own = self.solve(piece, q, Some(piece.global(u)));
        let u = piece.local(DVec2::new(own.v, own.w));
        let at = distance(convex.lower_bound(&q.jet(d, u.x, u.y), u, p));
        (at >= self.best_distance - self.tolerance).then_some(at)
    }
}

/// What the search opens next: a node of the patches' hierarchy, a cell
/// (level, index) of a patch's quadtree, or a piece below the finest cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Item {
    Node(u32),
    Cell(u32, u32),
    Piece(u32),
}

/// A distance bound, ordered (never NaN: points and nets are finite).
#[derive(Clone, Copy, PartialEq)]
struct Bound(f64);
impl Eq for Bound {}
impl PartialOrd for Bound {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Bound {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

pub(crate) fn check_point(p: DVec3) -> Result<()> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!(
            "snap: the point {:?} is not finite",
            p.to_array()
        )))
    }
}

fn check_tolerance(tolerance: f64) -> Result<()> {
    if tolerance > 0.0 && tolerance < 1.0 {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!(
            "snap: the certificate tolerance {tolerance} is not in (0, 1) (a fraction of the bounding-box diagonal)"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::{closest_point, FewSnaps};
    use crate::{examples, ControlNet, Surface};
    use glam::DVec3;

    /// The index of whole patches gives the certified answer the full
    /// index gives: around a torus and a cube with its edges hard, at
    /// points near and far, started from a far-off guess.
    #[test]
    fn whole_patches_answer_as_the_full_index() {
        for (ex, hard) in [(examples::torus(), false), (examples::cube(), true)] {
            let mut net = ControlNet::from_arrays(ex.points.clone(), &ex.tris).unwrap();
            if hard {
                net.tag_by_angle(30.0).unwrap();
            }
            let surface = Surface::new(&net).unwrap();
            let few = FewSnaps::new(&surface);
            let (lo, hi) = ex
                .points
                .iter()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &p| {
                    (l.min(p), h.max(p))
                });
            let diagonal = net.bbox_diagonal();
            let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
            let mut unit = || {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (seed >> 11) as f64 / (1u64 << 53) as f64
            };
            for _ in 0..300 {
                let t = DVec3::new(unit(), unit(), unit()) * 1.4 - 0.2;
                let p = lo + t * (hi - lo);
                let full = closest_point(&surface, p).unwrap();
                let whole = few.snap_near(p, 0, 0.2, 0.2).unwrap();
                assert!(
                    (full.distance - whole.distance).abs() <= 2e-12 * diagonal,
                    "{}: at {p}: {} by the full index, {} by whole patches",
                    ex.name,
                    full.distance,
                    whole.distance
                );
                assert!(whole.lower_bound <= full.distance + 1e-12 * diagonal);
            }
        }
    }
}
