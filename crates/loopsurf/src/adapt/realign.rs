//! Local mesh realignment (Liu & Kondo §4.5, LMR), done as max–min angle
//! edge swaps.
//!
//! Liu & Kondo's LMR flips the new dead edges between live triangles (its
//! rule 1) and re-triangulates around new dead vertices (rule 2), because
//! its splits leave slivers where dead and live regions meet. Here the
//! splits are conforming by construction (see [`super::split`]), so
//! realignment is only about shape: an edge inside one control triangle
//! whose two triangles both have a dead corner is swapped while that
//! raises the smaller minimum angle of the two (the mesher's Lawson swaps,
//! [`crate::geometry::swap`]). Triangles with live corners only keep the
//! regular Loop connectivity that uniform subdivision has, so `--angle 0`
//! stays exactly uniform. Swaps
//! inside one chart keep each triangle's (v, w) map valid and hard edges
//! (which lie on control edges) untouched.

use super::Parts;
use crate::geometry::swap::swap_edges;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// Swaps edges between triangles with dead corners, in the charts this
/// level changed (the others were realigned when they last changed).
pub(crate) fn realign(parts: &mut Parts) {
    let (tris, charts, points, dead) = (&parts.tris, &parts.charts, &parts.points, &parts.dead);
    let fresh = &parts.fresh;
    let touches_dead = |f: u32| tris[f as usize].iter().any(|&v| dead[v as usize]);
    // The candidate triangles, grouped by chart.
    let mut order: Vec<u32> = (0..tris.len() as u32)
        .filter(|&f| touches_dead(f))
        .collect();
    order.sort_unstable_by_key(|&f| charts[f as usize].tri);
    let groups: Vec<&[u32]> = order
        .chunk_by(|&f, &g| charts[f as usize].tri == charts[g as usize].tri)
        .filter(|faces| faces.iter().any(|&f| fresh[f as usize]))
        .collect();
    let updates: Vec<(u32, [u32; 3], [DVec2; 3])> = groups
        .par_iter()
        .flat_map_iter(|faces| {
            // Local numbering of the chart's vertices: their sorted ids.
            let mut global: Vec<u32> = faces.iter().flat_map(|&f| tris[f as usize]).collect();
            global.sort_unstable();
            global.dedup();
            let local = |v: u32| global.binary_search(&v).expect("a chart vertex") as u32;
            let mut params = vec![DVec2::ZERO; global.len()];
            let mut local_tris: Vec<[u32; 3]> = faces
                .iter()
                .map(|&f| {
                    let (tri, q) = (tris[f as usize], charts[f as usize].q);
                    [0, 1, 2].map(|k| {
                        let i = local(tri[k]);
                        params[i as usize] = q[k];
                        i
                    })
                })
                .collect();
            let pos: Vec<DVec3> = global.iter().map(|&v| points[v as usize]).collect();
            swap_edges(&mut local_tris, &params, &pos, |_, _| true);
            faces
                .iter()
                .zip(local_tris)
                .map(|(&f, t)| {
                    (
                        f,
                        t.map(|i| global[i as usize]),
                        t.map(|i| params[i as usize]),
                    )
                })
                .collect::<Vec<_>>()
        })
        .collect();
    for (f, tri, q) in updates {
        parts.tris[f as usize] = tri;
        parts.charts[f as usize].q = q;
    }
}
