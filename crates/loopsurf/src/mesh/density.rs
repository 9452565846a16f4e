//! How finely each control triangle is cut: its lattice level N, from the
//! requested density (uniform count, edge length, chord tolerance, or
//! curvature), graded so that neighbours differ by at most a factor
//! [`GRADING`]. Each control edge then takes the finer level of its two
//! triangles (or more, when its own chords need it).

use crate::parameters::INTERIOR_SAMPLES;
use crate::surface::Surface;
use crate::topology::{Topology, NONE};
use crate::Result;
use glam::DVec3;

/// Largest ratio between the levels of two neighbouring control triangles:
/// the transition strip of the coarser one then never has to fan more than
/// two segments to one.
pub(crate) const GRADING: f64 = 2.0;

/// Per control triangle: an estimate of the chord error of its level-1
/// lattice (the control triangle itself), from the largest second
/// derivative along the lattice directions (1,0), (0,1) and (−1,1). The
/// lattice of level N then deviates by about `bend / N²`. The estimate only
/// starts the level; the chord error is measured afterwards and enforced.
pub(crate) fn bend(surface: &Surface, t: usize) -> Result<f64> {
    let mut worst: f64 = 0.0;
    for (v, w) in INTERIOR_SAMPLES {
        let e = surface.eval(t, v, w)?;
        // Only the normal part bends chords away from the surface (the
        // tangential part reparametrises it).
        let n = e.normal().unwrap_or_default();
        let along = [e.xvv, e.xww, e.xvv - 2.0 * e.xvw + e.xww];
        worst = along.iter().map(|d| d.dot(n).abs()).fold(worst, f64::max);
    }
    // Linear interpolation error at a triangle's centroid is at most a
    // sixth of the largest second derivative over its edge vectors.
    Ok(worst / 6.0)
}

/// Length of the limit curve over each control edge, from its end points and
/// midpoint (a lower bound close enough for sizing).
pub(crate) fn edge_length(ends: [DVec3; 2], mid: DVec3) -> f64 {
    ends[0].distance(mid) + mid.distance(ends[1])
}

/// The level needed for a chord error `bend / N²` of at most `tolerance`.
pub(crate) fn level_for_tolerance(bend: f64, tolerance: f64) -> u32 {
    level((bend / tolerance).sqrt())
}

/// A level from a real-valued count: at least 1, rounded up.
pub(crate) fn level(x: f64) -> u32 {
    if x.is_finite() {
        x.ceil().clamp(1.0, u32::MAX as f64 / 4.0) as u32
    } else {
        1
    }
}

/// Raises levels until no triangle is coarser than a neighbour by more than
/// [`GRADING`] (a worklist: each raise re-examines the raised triangle's
/// neighbours).
pub(crate) fn grade(topo: &Topology, levels: &mut [u32]) {
    let mut work: Vec<u32> = (0..levels.len() as u32).collect();
    while let Some(t) = work.pop() {
        let floor = level(levels[t as usize] as f64 / GRADING);
        for &e in &topo.triangle_edges()[t as usize] {
            for &n in &topo.edge_triangles()[e as usize] {
                if n != NONE && levels[n as usize] < floor {
                    levels[n as usize] = floor;
                    work.push(n);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ControlNet;

    #[test]
    fn grading_bounds_neighbour_ratios() {
        let ex = crate::examples::by_name("sphere").unwrap();
        let net = ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
        let topo = net.topology();
        let mut levels = vec![1; topo.num_triangles()];
        levels[0] = 64;
        grade(topo, &mut levels);
        for (e, pair) in topo.edge_triangles().iter().enumerate() {
            let [a, b] = pair.map(|t| levels[t as usize] as f64);
            assert!(a.max(b) <= GRADING * a.min(b), "edge {e}: {a} vs {b}");
        }
        assert_eq!(levels[0], 64);
    }
}
