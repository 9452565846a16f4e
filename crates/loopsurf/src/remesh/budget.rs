//! The triangle budget: the most triangles a remesh may build, checked
//! before the memory is spent — from the net's area before the start mesh,
//! from the sizes before each round's splits, and by the splits' own count
//! as they go.

use super::remeshing::Remeshing;
use super::sizing::Sizing;
use crate::error::Error;
use crate::geometry::area;
use crate::ControlNet;
use crate::Result;
use rayon::prelude::*;

/// The remeshed edges average shorter than their targets (they lie within
/// [4/5, 4/3] of them, most below 1): a finished mesh has 1.18–1.22 times
/// the triangles its sizes' areas say (pig at 0.5%, pig 40° and fandisk
/// at 1e-4 adapted, the Viking adapted).
const EDGES_SHORT_BY: f64 = 1.2;

/// The chart mesher's start is denser than the remesher's output (about
/// 3× at the same size, the Viking at 1%: 75 840 against 24 752): its
/// budget is this many times the remesher's.
const START_BUDGET: usize = 4;

/// The area of an equilateral triangle of side `h`.
fn equilateral(h: f64) -> f64 {
    0.25 * 3f64.sqrt() * h * h
}

/// About how many triangles `sizing` asks for over `net` before grading
/// and any tolerance round: each control triangle's area over that of an
/// equilateral triangle of its size, times [`EDGES_SHORT_BY`]. The terms
/// are added in triangle order, not by rayon's reduction, whose order
/// follows the threads: the count is the same bits on any thread count.
pub(crate) fn expected_over_net(net: &ControlNet, sizing: &Sizing) -> f64 {
    expected_over(net, sizing, |_| true)
}

/// [`expected_over_net`] over the control triangles t with `keep(t)`.
pub(crate) fn expected_over(
    net: &ControlNet,
    sizing: &Sizing,
    keep: impl Fn(usize) -> bool + Sync,
) -> f64 {
    let per_triangle: Vec<f64> = net
        .triangles()
        .par_iter()
        .enumerate()
        .map(|(t, tri)| {
            if keep(t) {
                area(tri.map(|v| net.points()[v as usize])) / equilateral(sizing.of_triangle(t))
            } else {
                0.0
            }
        })
        .collect();
    EDGES_SHORT_BY * per_triangle.iter().sum::<f64>()
}

/// The most triangles a remesh may build.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Budget {
    max_triangles: usize,
}

impl Budget {
    /// A budget of `max_triangles`, which must be at least 1.
    pub fn new(max_triangles: usize) -> Result<Budget> {
        if max_triangles == 0 {
            return Err(Error::InvalidArgument(
                "max_triangles 0: must be at least 1".into(),
            ));
        }
        Ok(Budget { max_triangles })
    }

    /// The triangles the chart mesh the remesher starts from may have.
    pub fn start_allowance(&self) -> usize {
        self.max_triangles.saturating_mul(START_BUDGET)
    }

    /// What the start mesh was for, for an error met while building it.
    pub fn start_context(&self) -> String {
        format!(
            "the chart mesh the remesher starts from (allowed {START_BUDGET} × the budget of {} triangles)",
            self.max_triangles
        )
    }

    /// Refuses a uniform size `h` on a net of area `area` (near the
    /// surface's) that asks for more triangles than the budget, before the
    /// start mesh is built.
    pub fn check_uniform(&self, area: f64, h: f64) -> Result<()> {
        self.check(EDGES_SHORT_BY * area / equilateral(h))
    }

    /// Refuses an `expected` count of triangles over the budget.
    pub fn check(&self, expected: f64) -> Result<()> {
        if expected > self.max_triangles as f64 {
            return Err(Error::OverBudget {
                needed: expected,
                limit: self.max_triangles,
                message: format!(
                    "the requested density needs about {expected:.3e} triangles, over the budget of {}: loosen the tolerance, raise the size or raise the budget",
                    self.max_triangles
                ),
            });
        }
        Ok(())
    }

    /// The triangle slots the splits of a mesh with `slots` of them may
    /// reach.
    ///
    /// The expected count is from the mesh as it is; the splits are
    /// bounded too, by triangle slots (dead ones too), which bound the
    /// memory: splits adding more than the whole budget run away. (Not the
    /// slots alone: the mesh they start from may be denser than its sizes
    /// in places until the collapses, and fandisk at 1e-4 with a budget of
    /// 30 000 once held 60 000 after its first splits.)
    pub fn split_limit(&self, slots: usize) -> usize {
        slots.saturating_add(self.max_triangles)
    }

    /// Refuses splits that left `slots` triangle slots, over their `limit`,
    /// where the sizes ask for about `expected` triangles.
    pub fn check_splits(
        &self,
        slots: usize,
        limit: usize,
        expected: impl Fn() -> f64,
    ) -> Result<()> {
        if slots > limit {
            let expected = expected();
            return Err(Error::OverBudget {
                needed: expected,
                limit: self.max_triangles,
                message: format!(
                    "the splits ran past {limit} triangles where the sizes ask for about {expected:.3e} (the surface may fold over itself): loosen the tolerance, raise the size or raise the budget of {}",
                    self.max_triangles
                ),
            });
        }
        Ok(())
    }
}

impl Remeshing<'_> {
    /// The number of triangles the sizes ask for: each live triangle's
    /// area over that of an equilateral triangle of its corners' mean
    /// size, times [`EDGES_SHORT_BY`]. Cheap, and known before the splits
    /// that would build them.
    pub fn expected_triangles(&self) -> f64 {
        EDGES_SHORT_BY
            * (0..self.mesh.num_half_edges() / 3)
                .into_par_iter()
                .map(|t| 3 * t)
                .filter(|&h| self.mesh.is_alive(h))
                .map(|h| {
                    let c = self.mesh.corners(h);
                    let p = c.map(|v| self.vertices[v as usize].x);
                    let s = c.iter().map(|&v| self.size[v as usize]).sum::<f64>() / 3.0;
                    area(p) / equilateral(s)
                })
                .sum::<f64>()
    }

    /// The triangle slots the mesh holds, dead ones too.
    pub fn triangle_slots(&self) -> usize {
        self.mesh.num_half_edges() as usize / 3
    }
}
