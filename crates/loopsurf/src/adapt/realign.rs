//! Local mesh realignment (seed 001 §4.5, LMR), done as max–min angle
//! edge swaps.
//!
//! The seed's LMR flips the new dead edges between live triangles (its
//! rule 1) and re-triangulates around new dead vertices (rule 2), because
//! its splits leave slivers where dead and live regions meet. Here the
//! splits are conforming by construction (see [`super::split`]), so
//! realignment is only about shape: an edge inside one control triangle
//! whose two triangles have a dead corner is swapped while that raises the
//! smaller minimum angle of the two (the mesher's Lawson swaps,
//! [`crate::mesh::swap`]). Where all four corners are live the mesh keeps
//! the regular Loop connectivity that uniform subdivision has, so
//! `--angle 0` stays exactly uniform. Swaps
//! inside one chart keep each triangle's (v, w) map valid and hard edges
//! (which lie on control edges) untouched.

use super::Parts;
use crate::mesh::swap::swap_edges;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::collections::HashMap;

/// Swaps edges at dead vertices, chart by chart.
pub(crate) fn realign(parts: &mut Parts) {
    let mut order: Vec<u32> = (0..parts.tris.len() as u32).collect();
    order.sort_by_key(|&f| parts.charts[f as usize].tri);
    let (tris, charts, points, dead) = (&parts.tris, &parts.charts, &parts.points, &parts.dead);
    let groups: Vec<&[u32]> = order
        .chunk_by(|&f, &g| charts[f as usize].tri == charts[g as usize].tri)
        .filter(|faces| {
            faces
                .iter()
                .any(|&f| tris[f as usize].iter().any(|&v| dead[v as usize]))
        })
        .collect();
    let updates: Vec<(u32, [u32; 3], [DVec2; 3])> = groups
        .par_iter()
        .flat_map_iter(|faces| {
            // Local numbering of the chart's vertices.
            let mut local: HashMap<u32, u32> = HashMap::new();
            let (mut global, mut params, mut pos): (Vec<u32>, Vec<DVec2>, Vec<DVec3>) =
                Default::default();
            let mut local_tris: Vec<[u32; 3]> = faces
                .iter()
                .map(|&f| {
                    let (tri, q) = (tris[f as usize], charts[f as usize].q);
                    [0, 1, 2].map(|k| {
                        *local.entry(tri[k]).or_insert_with(|| {
                            global.push(tri[k]);
                            params.push(q[k]);
                            pos.push(points[tri[k] as usize]);
                            global.len() as u32 - 1
                        })
                    })
                })
                .collect();
            swap_edges(&mut local_tris, &params, &pos, |n1, n2| {
                n1.iter()
                    .chain(&n2)
                    .any(|&i| dead[global[i as usize] as usize])
            });
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
