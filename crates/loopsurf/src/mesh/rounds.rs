//! The chart mesher's rounds: cut every control edge and triangle whose
//! pattern changed, and under a tolerance refine where the measured chord
//! error is missed, so that each round recomputes only what it must.

use super::density::{self, level};
use super::isotropic::Slivers;
use super::pattern::Pattern;
use super::{boundary_points, cut_edge, finer, EdgeCut, Mesher, TriangleCut};
use crate::error::Result;
use crate::parameters::SurfacePoint;
use crate::surface::Surface;
use crate::topology::{Topology, NONE};
use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// The cuts so far, per control edge and triangle, with what refinement
/// has learnt: each edge's floor (the segments its own chords need) and
/// each one's last (level, error), from which [`finer`] measures the rate
/// of convergence.
pub(super) struct Cuts {
    /// Per control triangle: whether it is cut at all (a planned piece
    /// cuts only its own triangles and their edges); `None`: every one.
    keep: Option<Vec<bool>>,
    edges: Vec<Option<EdgeCut>>,
    triangles: Vec<Option<TriangleCut>>,
    edge_floor: Vec<u32>,
    edge_history: Vec<Option<(u32, f64)>>,
    triangle_history: Vec<Option<(u32, f64)>>,
}

/// The segments control edge `e` is cut into at `levels`: the more of the
/// two its triangles ask (a lattice triangle its level, a sliver the
/// edge's length at its spacing).
pub(super) fn segments(topo: &Topology, levels: &[u32], slivers: &Slivers, e: usize) -> u32 {
    topo.edge_triangles()[e]
        .iter()
        .filter(|&&t| t != NONE)
        .map(|&t| slivers.segments(t as usize, e, levels[t as usize]))
        .max()
        .unwrap_or(1)
}

/// Counts cut triangles for a progress callback.
pub(super) struct Progress<'p> {
    done: AtomicU64,
    total: AtomicU64,
    report: &'p (dyn Fn(u64, u64) + Sync),
}

impl<'p> Progress<'p> {
    pub fn new(report: &'p (dyn Fn(u64, u64) + Sync)) -> Progress<'p> {
        Progress {
            done: AtomicU64::new(0),
            total: AtomicU64::new(0),
            report,
        }
    }

    /// `n` more triangles to cut.
    fn add(&self, n: usize) {
        self.total.fetch_add(n as u64, Ordering::Relaxed);
    }

    /// One more triangle cut; reported every 256.
    fn one_done(&self) {
        let n = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if n % 256 == 0 {
            (self.report)(n, self.total.load(Ordering::Relaxed));
        }
    }

    /// Reports everything done.
    pub fn finish(&self) {
        let n = self.done.load(Ordering::Relaxed);
        (self.report)(n, n);
    }
}

impl Cuts {
    /// Nothing cut yet, for `edges` control edges and `triangles` control
    /// triangles.
    pub fn new(edges: usize, triangles: usize) -> Cuts {
        Cuts {
            keep: None,
            edges: (0..edges).map(|_| None).collect(),
            triangles: (0..triangles).map(|_| None).collect(),
            edge_floor: vec![1u32; edges],
            edge_history: vec![None; edges],
            triangle_history: vec![None; triangles],
        }
    }

    /// Nothing cut yet, and only the control triangles t with `keep[t]`
    /// and their edges to cut, of the `edges` control edges.
    pub fn only(edges: usize, keep: Vec<bool>) -> Cuts {
        let mut cuts = Cuts::new(edges, keep.len());
        cuts.keep = Some(keep);
        cuts
    }

    /// Whether control triangle t is to be cut.
    fn kept(&self, t: usize) -> bool {
        self.keep.as_ref().map_or(true, |keep| keep[t])
    }

    /// The segments of each control edge: the more of the two its
    /// triangles ask at their levels (a lattice triangle its level, a
    /// sliver the edge's length at its spacing), or its floor if more
    /// still.
    pub fn edge_levels(&self, topo: &Topology, levels: &[u32], slivers: &Slivers) -> Vec<u32> {
        (0..self.edges.len())
            .map(|e| segments(topo, levels, slivers, e).max(self.edge_floor[e]))
            .collect()
    }

    /// Cuts every control edge not yet cut into its `cuts_per_edge`.
    pub fn cut_edges(
        &mut self,
        surface: &Surface,
        cuts_per_edge: &[u32],
        corners: &[(SurfacePoint, DVec3)],
        tolerance: Option<f64>,
    ) -> Result<()> {
        let topo = surface.net().topology();
        let dirty: Vec<usize> = (0..self.edges.len())
            .filter(|&e| {
                topo.edge_triangles()[e]
                    .iter()
                    .any(|&t| t != NONE && self.kept(t as usize))
            })
            .filter(|&e| {
                self.edges[e]
                    .as_ref()
                    .map_or(true, |c| c.points.len() + 1 != cuts_per_edge[e] as usize)
            })
            .collect();
        let fresh: Vec<(usize, EdgeCut)> = dirty
            .par_iter()
            .map(|&e| {
                Ok((
                    e,
                    cut_edge(surface, e, cuts_per_edge[e], corners, tolerance)?,
                ))
            })
            .collect::<Result<_>>()?;
        for (e, cut) in fresh {
            self.edges[e] = Some(cut);
        }
        Ok(())
    }

    /// Cuts every control triangle whose pattern changed, its sides from
    /// the edges' cuts.
    pub fn cut_triangles(
        &mut self,
        mesher: &Mesher,
        levels: &[u32],
        cuts_per_edge: &[u32],
        slivers: &Slivers,
        corners: &[(SurfacePoint, DVec3)],
        tolerance: Option<f64>,
        progress: &Progress,
    ) -> Result<()> {
        let surface = mesher.surface;
        let topo = surface.net().topology();
        let pattern_of = |t: usize| Pattern {
            sides: topo.triangle_edges()[t].map(|e| cuts_per_edge[e as usize]),
            level: levels[t],
            isotropic: slivers.is_sliver(t),
        };
        let dirty: Vec<usize> = (0..self.triangles.len())
            .filter(|&t| self.kept(t))
            .filter(|&t| {
                self.triangles[t]
                    .as_ref()
                    .map_or(true, |c| c.pattern != pattern_of(t))
            })
            .collect();
        progress.add(dirty.len());
        let edge_cuts = &self.edges;
        let fresh: Vec<(usize, TriangleCut)> = dirty
            .par_iter()
            .map(|&t| {
                let boundary = boundary_points(surface, t, &pattern_of(t), corners, edge_cuts);
                let cut = mesher.cut_triangle(t, pattern_of(t), boundary, tolerance)?;
                progress.one_done();
                Ok((t, cut))
            })
            .collect::<Result<_>>()?;
        for (t, cut) in fresh {
            self.triangles[t] = Some(cut);
        }
        Ok(())
    }

    /// Raises the levels (and edge floors) wherever a cut's chord error
    /// exceeds `tolerance`; whether any did.
    pub fn refine_where_missed(
        &mut self,
        topo: &Topology,
        tolerance: f64,
        levels: &mut [u32],
        cuts_per_edge: &[u32],
    ) -> bool {
        let mut violated = false;
        for (e, cut) in self.edges.iter().enumerate() {
            let Some(cut) = cut else { continue };
            if cut.deviation > tolerance {
                self.edge_floor[e] = finer(
                    cuts_per_edge[e],
                    cut.deviation,
                    tolerance,
                    &mut self.edge_history[e],
                );
                violated = true;
                // Keep the triangles on both sides within the grading
                // of their side, or their strips would fan.
                let floor = level(self.edge_floor[e] as f64 / density::GRADING);
                for &t in &topo.edge_triangles()[e] {
                    if t != NONE {
                        levels[t as usize] = levels[t as usize].max(floor);
                    }
                }
            }
        }
        for (t, cut) in self.triangles.iter().enumerate() {
            let Some(cut) = cut else { continue };
            if cut.deviation > tolerance {
                levels[t] = finer(
                    levels[t],
                    cut.deviation,
                    tolerance,
                    &mut self.triangle_history[t],
                );
                violated = true;
            }
        }
        violated
    }

    /// The largest chord error of any cut.
    pub fn worst(&self) -> f64 {
        (self.edges.iter().flatten().map(|c| c.deviation))
            .chain(self.triangles.iter().flatten().map(|c| c.deviation))
            .fold(0.0, f64::max)
    }

    /// The cuts: every one made, or those of the triangles kept and their
    /// edges ([`Cuts::only`]).
    pub fn into_cuts(self) -> (Vec<Option<EdgeCut>>, Vec<Option<TriangleCut>>) {
        (self.edges, self.triangles)
    }
}
