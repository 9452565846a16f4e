//! Concave corners: where Loop's crease rules can fold the surface past
//! its own creases, and the seams that would stop it.
//!
//! At a corner the limit surface leaves along the crease curves that bound
//! each sector, and inside the sector the smooth rules average control
//! points from both of its sides. Where the sector spans more than 180°
//! (the inner corner of an L-shaped face, a notch) that average can land
//! in the notch: the patch runs past the corner's creases and folds back,
//! a flap that no mesh of the surface survives. Whether it does depends
//! on the triangles: CGAL's anchor, whose L-shaped faces are a few
//! triangles obtuse at the inner corner, reaches 1.6% of its diagonal into
//! the notch (a remesh at 1% then crosses itself 30 times, with angles
//! down to 2.2°), while an L of right triangles stays out. Biermann, Levin
//! & Zorin (2000) change the rules at such corners; the rules here are
//! OpenSubdiv's, so the net is changed instead, only when asked and only
//! where the surface folds (`folds::seam_folded_concave_corners`, which
//! needs the surface to tell).
//!
//! A *seam* is an edge of the sector's fan tagged hard, from the corner to
//! a vertex across the sector, so that each half spans less than 180° and
//! each is a sector of its own, bounded by the seam's crease curve. The
//! seam ends in a smooth vertex (which becomes a dart, on the same rule)
//! or in another corner, so no vertex changes its rule and no crease
//! curve changes. On a flat sector the surface stays in its plane; on a
//! curved one the seam is a crease, and the surface moves (the `loopsurf`
//! command measures how far).

use crate::features::VertexKind;
use crate::geometry;
use crate::net::ControlNet;
use crate::topology::corner_of;
use std::collections::HashMap;

/// A sector spanning more than this is concave, degrees. The L of obtuse
/// triangles in `tests/concave.rs`, its leg turned to make the sector
/// 185°, 190°, 200°, 225° and 270°, reaches 0, 0, 0.4%, 7% and 19% of
/// its bar's width into the notch: nearly straight sectors (CGAL's
/// cylinder_locally_refined has six of 180.2° to 186.9°) do not fold,
/// and a seam there only adds a feature line.
pub const CONCAVE_DEGREES: f64 = 195.0;

/// The smallest angle a seam may make with the sector's sides or with a
/// hard edge at its far end, degrees: a mesh must fit triangles of at
/// least 20° into every angle between hard edges, two of them here.
pub const MIN_SEAM_DEGREES: f64 = 40.0;

/// A sector of a corner's fan, between two consecutive hard edges, that
/// spans more than [`CONCAVE_DEGREES`].
#[derive(Debug, Clone, PartialEq)]
pub struct ConcaveSector {
    /// The corner.
    pub corner: u32,
    /// The sector's control triangles, in counter-clockwise order.
    pub triangles: Vec<u32>,
    /// The angles of those triangles at the corner, summed, degrees.
    pub degrees: f64,
    /// The edge to tag hard and the two angles it splits the sector into
    /// (degrees, in fan order); `None` when no edge of the fan splits it
    /// into two halves under 180° without an angle below
    /// [`MIN_SEAM_DEGREES`] and ending in a smooth vertex or a corner.
    pub seam: Option<([u32; 2], [f64; 2])>,
}

/// Every sector spanning more than [`CONCAVE_DEGREES`] at a corner of the
/// net, with the seam that would split it, in corner order. Sector angles
/// are those of the control triangles at the corner.
pub fn concave_sectors(net: &ControlNet) -> Vec<ConcaveSector> {
    let topo = net.topology();
    let kinds = net.vertex_kinds();
    let mut out = Vec::new();
    for v in 0..topo.num_vertices() {
        if kinds[v] != VertexKind::Corner || topo.is_unreferenced(v) {
            continue;
        }
        for sector in sectors(net, v as u32) {
            let total: f64 = sector.iter().map(|&(_, angle)| angle).sum();
            if total <= CONCAVE_DEGREES.to_radians() {
                continue;
            }
            out.push(ConcaveSector {
                corner: v as u32,
                triangles: sector.iter().map(|&(fan, _)| fan.triangle).collect(),
                degrees: total.to_degrees(),
                seam: best_seam(net, &kinds, v as u32, &sector, total),
            });
        }
    }
    out
}

/// One triangle of a corner's fan: (corner, next, prev) counter-clockwise.
#[derive(Debug, Clone, Copy)]
struct FanTriangle {
    triangle: u32,
    next: u32,
    prev: u32,
}

/// The sectors of corner v: runs of its fan between hard edges, each
/// triangle with its angle at v (radians).
fn sectors(net: &ControlNet, v: u32) -> Vec<Vec<(FanTriangle, f64)>> {
    let topo = net.topology();
    let points = net.points();
    let fan: Vec<FanTriangle> = topo
        .fan(v as usize)
        .iter()
        .map(|&t| {
            let c = topo.triangles()[t as usize];
            let k = corner_of(c, v) as usize;
            FanTriangle {
                triangle: t,
                next: c[(k + 1) % 3],
                prev: c[(k + 2) % 3],
            }
        })
        .collect();
    let by_next: HashMap<u32, usize> = fan.iter().enumerate().map(|(i, f)| (f.next, i)).collect();
    let corner = points[v as usize];
    let angle = |f: &FanTriangle| {
        geometry::angle(
            points[f.next as usize] - corner,
            points[f.prev as usize] - corner,
        )
    };
    let is_hard = |u: u32| net.features().is_hard_between(topo, v, u);
    let mut out = Vec::new();
    for start in fan.iter().filter(|f| is_hard(f.next)) {
        let mut sector = vec![(*start, angle(start))];
        let mut here = *start;
        while !is_hard(here.prev) {
            let Some(&i) = by_next.get(&here.prev) else {
                break;
            };
            here = fan[i];
            sector.push((here, angle(&here)));
        }
        out.push(sector);
    }
    out
}

/// The inner edge of the sector (spanning `total` radians) that splits it
/// most evenly into two halves under 180°, neither half nor any angle the edge makes with a
/// hard edge at its far end below [`MIN_SEAM_DEGREES`], ending in a smooth
/// vertex or a corner (whose rules a seam leaves as they were).
fn best_seam(
    net: &ControlNet,
    kinds: &[VertexKind],
    v: u32,
    sector: &[(FanTriangle, f64)],
    total: f64,
) -> Option<([u32; 2], [f64; 2])> {
    let least = MIN_SEAM_DEGREES.to_radians();
    let half = std::f64::consts::PI;
    let mut before = 0.0;
    let mut best: Option<(f64, [u32; 2], [f64; 2])> = None;
    for &(fan, angle) in &sector[..sector.len() - 1] {
        before += angle;
        let after = total - before;
        let fits = before < half && after < half && before >= least && after >= least;
        let keeps_rule = matches!(
            kinds[fan.prev as usize],
            VertexKind::Smooth | VertexKind::Corner
        );
        if fits && keeps_rule && far_end_angle(net, v, fan.prev) >= least {
            let imbalance = (before - after).abs();
            if best.as_ref().is_none_or(|b| imbalance < b.0) {
                best = Some((
                    imbalance,
                    [v.min(fan.prev), v.max(fan.prev)],
                    [before.to_degrees(), after.to_degrees()],
                ));
            }
        }
    }
    best.map(|(_, edge, halves)| (edge, halves))
}

/// The smallest angle at u between the edge (u, v) and a hard edge at u.
fn far_end_angle(net: &ControlNet, v: u32, u: u32) -> f64 {
    let points = net.points();
    let at = points[u as usize];
    let along = points[v as usize] - at;
    net.features()
        .hard_neighbours(net.topology(), u as usize)
        .iter()
        .map(|&w| geometry::angle(along, points[w as usize] - at))
        .fold(std::f64::consts::PI, f64::min)
}
