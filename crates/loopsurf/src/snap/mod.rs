//! Snapping: the closest point of the limit surface to any xyz — the
//! global minimum of the distance, not a local one.
//!
//! Branch and bound, best first. The index ([`index`]) is a box hierarchy
//! over the control triangles' patches and, below each patch, a quadtree of
//! cells (the pieces its subdivided triangles cover), every node with a
//! convex container of its piece of surface ([`cell`]). Nodes wait in a heap
//! keyed by a lower bound on the distance to what they hold — box distance,
//! then container distance — and are opened in that order. The first finest
//! cell reached gets a projected-Newton solve ([`local`]) that walks across
//! triangles to a local minimum of the surface; every later cell whose
//! bound is still below the best distance gets a solve confined to the cell,
//! and only if that beats the best does it walk on. The search stops when
//! no bound is below the best distance.
//!
//! What is proven and what is not: the pruning is rigorous, so every cell
//! that could hold a nearer point is solved. Each solve finds a local
//! minimum of the distance over its cell (Newton with the full Hessian,
//! shifted where it is indefinite, steps confined to the cell) — the cell's
//! minimum whenever the distance has one basin there. Cells are small (a
//! patch cut 1–3 times), so that is a far weaker assumption than one basin
//! per patch, which the pig's concave folds and the bunny's scan bumps
//! break for points within 1% of the model size. The tests compare with a
//! dense brute-force reference on CGAL and synthetic meshes.

mod cell;
mod index;
mod local;

use index::Content;
pub(crate) use index::SnapIndex;
pub use local::Snap;

use crate::error::{Error, Result};
use crate::surface::Surface;
use glam::DVec3;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

impl Surface {
    /// The point of the surface nearest to `p` (the global minimum of the
    /// distance), with its triangle and parameters. Where several points are
    /// equally near, one of them.
    pub fn closest_point(&self, p: DVec3) -> Result<Snap> {
        check_point(p)?;
        Ok(self.search(p, None))
    }

    /// [`Surface::closest_point`] starting from a point known to be near
    /// the answer (a neighbouring query's result, say): the local solve
    /// walks from the hint across triangles, then the global search runs
    /// with that distance as its bound — usually only confirming it.
    pub fn snap_near(&self, p: DVec3, tri: usize, v: f64, w: f64) -> Result<Snap> {
        check_point(p)?;
        // Validates the hint (and clamps round-off) like any query.
        self.eval(tri, v, w)?;
        let (v, w) = (v.max(0.0), w.max(0.0));
        let (v, w) = if v + w > 1.0 {
            (v / (v + w), w / (v + w))
        } else {
            (v, w)
        };
        let seed = local::descend(self, p, tri, v, w);
        Ok(self.search(p, Some(seed)))
    }

    /// Best-first branch and bound from an optional first candidate.
    /// The seed comes with whether its solve converged: only a converged
    /// local minimum stands for its cell.
    fn search(&self, p: DVec3, seed: Option<(Snap, bool)>) -> Snap {
        let index = self.snap_index();
        let mut best = seed.map(|(s, _)| s);
        let mut best_distance = best.map_or(f64::INFINITY, |b| b.distance);
        // Nodes to open with a lower bound on the distance to what they hold.
        let mut pending: BinaryHeap<Reverse<(Bound, Item)>> = BinaryHeap::with_capacity(64);
        pending.push(Reverse((Bound(index.nodes[0].distance(p)), Item::Node(0))));
        // The finest cells of the local minima found so far: a handful.
        let mut minima: Vec<usize> = seed
            .filter(|&(_, converged)| converged)
            .map(|(s, _)| index.cell_at(s.tri, s.v, s.w))
            .into_iter()
            .collect();
        while let Some(Reverse((Bound(bound), item))) = pending.pop() {
            // A point on the surface to round-off cannot be beaten: no
            // distance is below zero.
            if bound >= best_distance || best_distance <= index.round_off {
                break;
            }
            let mut push = |bound: f64, item: Item| {
                if bound < best_distance {
                    pending.push(Reverse((Bound(bound), item)));
                }
            };
            match item {
                Item::Node(i) => match index.nodes[i as usize].content {
                    Content::Children(l, r) => {
                        for c in [l, r] {
                            push(index.nodes[c as usize].distance(p), Item::Node(c));
                        }
                    }
                    Content::Patch(t) => {
                        let b = index.cell(0, t as usize).lower_bound(p, best_distance);
                        push(b.max(bound), Item::Cell(0, t));
                    }
                },
                Item::Cell(k, c) if k < index.level => {
                    for child in 4 * c..4 * c + 4 {
                        let b = index
                            .cell(k + 1, child as usize)
                            .lower_bound(p, best_distance);
                        push(b.max(bound), Item::Cell(k + 1, child));
                    }
                }
                Item::Cell(_, cell) => {
                    let cell = cell as usize;
                    // A local minimum already found in this cell is its
                    // minimum (one basin per cell).
                    if minima.contains(&cell) {
                        continue;
                    }
                    let (tri, uv) = index.start(cell, p);
                    // The first solve walks to a local minimum of the
                    // surface; later ones only need the cell's own minimum,
                    // and walk on from it if it beats the best.
                    let (found, converged) = if best.is_none() {
                        local::descend(self, p, tri, uv.x, uv.y)
                    } else {
                        let region = local::Region::new(index.cell_corners(cell));
                        let (own, converged) = local::descend_within(self, p, tri, uv, &region);
                        if converged && own.distance >= best_distance {
                            continue;
                        }
                        local::descend(self, p, tri, own.v, own.w)
                    };
                    if converged {
                        minima.push(index.cell_at(found.tri, found.v, found.w));
                    }
                    if found.distance < best_distance {
                        best_distance = found.distance;
                        best = Some(found);
                    }
                }
            }
        }
        best.expect("a surface has at least one triangle")
    }
}

/// What the search opens next: a node of the patches' hierarchy, or a cell
/// (level, index) of a patch's quadtree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Item {
    Node(u32),
    Cell(u32, u32),
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

fn check_point(p: DVec3) -> Result<()> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!(
            "snap: the point {:?} is not finite",
            p.to_array()
        )))
    }
}
