//! Concave corners (`folds::seam_folded_concave_corners`) against the shape
//! they belong to: flat L-shaped faces, whose limit surface must stay
//! out of the L's notch. The surface is sampled by the net refined five times and
//! pushed to its limit points by the limit masks (no patch evaluation),
//! and judged by plain coordinates.

mod common;

use common::cgal_mesh;
use loopsurf::concave::concave_sectors;
use loopsurf::folds::seam_folded_concave_corners;
use loopsurf::refine::refine_uniform;
use loopsurf::{ControlNet, DVec3};

/// Tags every boundary vertex a corner, so the sides are straight crease
/// curves.
fn flat_net(points: &[[f64; 2]], tris: &[[u32; 3]]) -> ControlNet {
    let points = points.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect();
    let mut net = ControlNet::from_arrays(points, tris).unwrap();
    for v in 0..net.points().len() {
        if net.topology().is_boundary_vertex(v) {
            net.tag_vertex(v as u32).unwrap();
        }
    }
    net
}

/// The inner corner of one of CGAL anchor's L-shaped faces, in units of
/// its bar's width, with the inner corner at the origin and the notch in
/// x < 0, y < 0: a bar [−6, 1] × [0, 1], a leg [0, 1] × [−1.6, 0], four
/// triangles, two of them obtuse at the inner corner (125.5° and 135°).
fn anchor_l() -> ControlNet {
    let points = [
        [-6.0, 0.0],
        [-6.0, 1.0],
        [0.0, 0.0],
        [1.0, 1.0],
        [0.0, -1.6],
        [1.0, -1.6],
    ];
    flat_net(&points, &[[0, 2, 1], [2, 3, 1], [2, 4, 3], [4, 5, 3]])
}

/// An L of right triangles: [0, 2]² without (1, 2]², moved so that its
/// inner corner is at the origin (notch in x > 0, y > 0 before the move;
/// mirrored here into x < 0, y < 0), `n` squares a unit, each cut along
/// one diagonal.
fn grid_l(n: usize) -> ControlNet {
    let side = 2 * n + 1;
    let at = |i: usize, j: usize| [1.0 - i as f64 / n as f64, 1.0 - j as f64 / n as f64];
    let mut index = vec![u32::MAX; side * side];
    let mut points = Vec::new();
    let mut tris = Vec::new();
    for j in 0..2 * n {
        for i in 0..2 * n {
            if i >= n && j >= n {
                continue;
            }
            let square = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(i, j)| {
                let k = j * side + i;
                if index[k] == u32::MAX {
                    index[k] = points.len() as u32;
                    points.push(at(i, j));
                }
                index[k]
            });
            let [a, b, c, d] = square;
            // Mirrored through the corner: the order flips to stay counter-clockwise.
            tris.extend([[a, c, b], [a, d, c]]);
        }
    }
    flat_net(&points, &tris)
}

/// How far the limit surface (the net refined five times, at its limit
/// points) reaches into the notch x < 0, y < 0, and how far off its plane.
fn into_the_notch(net: &ControlNet) -> (f64, f64) {
    let refined = refine_uniform(net, 5).unwrap();
    let mut notch = f64::NEG_INFINITY;
    let mut off_plane: f64 = 0.0;
    for p in refined.limit_points() {
        notch = notch.max((-p.x).min(-p.y));
        off_plane = off_plane.max(p.z.abs());
    }
    (notch, off_plane)
}

#[test]
fn an_l_of_obtuse_triangles_folds_into_its_notch_until_seamed() {
    let mut net = anchor_l();
    let (before, _) = into_the_notch(&net);
    println!("anchor's L: {before:.3} into the notch");
    // 0.19 of the bar's width when measured (as on the anchor: 0.023 of
    // its 0.125).
    assert!(before > 0.1, "anchor's L: only {before} into the notch");
    check_seamed("anchor's L", &mut net);
}

/// An L of right triangles does not fold, and is not seamed.
#[test]
fn an_l_of_right_triangles_stays_out_of_its_notch_unseamed() {
    for n in [1, 2, 4] {
        let mut net = grid_l(n);
        let (before, _) = into_the_notch(&net);
        assert!(
            before <= 1e-12,
            "L of {n} squares a unit: {before:e} into the notch"
        );
        assert_eq!(concave_sectors(&net).len(), 1, "L of {n}");
        let hard = net.features().num_hard_edges();
        let folded = seam_folded_concave_corners(&mut net).unwrap();
        assert!(folded.is_empty(), "L of {n}: {folded:?}");
        assert_eq!(net.features().num_hard_edges(), hard);
    }
}

/// The L of obtuse triangles with its leg turned so that the sector at
/// the inner corner spans `degrees`.
fn turned_anchor_l(degrees: f64) -> ControlNet {
    let a = (180.0 - degrees).to_radians();
    let d = DVec3::new(a.cos(), a.sin(), 0.0);
    let w = DVec3::new(-d.y, d.x, 0.0);
    let lower = d * 1.6;
    let outer = lower + w;
    // The leg's outer side meets the bar's top, y = 1.
    let top = outer + d * ((1.0 - outer.y) / d.y);
    let points = [
        [-6.0, 0.0],
        [-6.0, 1.0],
        [0.0, 0.0],
        [top.x, top.y],
        [lower.x, lower.y],
        [outer.x, outer.y],
    ];
    flat_net(&points, &[[0, 2, 1], [2, 3, 1], [2, 4, 3], [4, 5, 3]])
}

/// Nearly straight sectors are not concave; from 200° on, the L's fold
/// is found and seamed.
#[test]
fn sectors_fold_from_about_200_degrees() {
    for degrees in [185.0, 190.0] {
        assert!(
            concave_sectors(&turned_anchor_l(degrees)).is_empty(),
            "{degrees}°"
        );
    }
    for degrees in [225.0, 250.0] {
        let mut net = turned_anchor_l(degrees);
        let folded = seam_folded_concave_corners(&mut net).unwrap();
        assert_eq!(folded.len(), 1, "{degrees}°: {folded:?}");
        assert!(folded[0].seam.is_some(), "{degrees}°: {folded:?}");
    }
}

/// Seams the net's one concave corner (a flat 270° sector, halved) and
/// checks that its surface stays in its plane and out of the notch.
fn check_seamed(what: &str, net: &mut ControlNet) {
    let sectors = seam_folded_concave_corners(net).unwrap();
    assert_eq!(sectors.len(), 1, "{what}: {sectors:?}");
    let sector = &sectors[0];
    assert!((sector.degrees - 270.0).abs() < 1e-9, "{what}: {sector:?}");
    assert_eq!(sector.corner, 2);
    let (_, halves) = sector.seam.expect("the notch has a seam");
    assert!(
        halves.iter().all(|&h| h < 180.0 && h >= 40.0),
        "{what}: {sector:?}"
    );
    let (after, off_plane) = into_the_notch(net);
    assert!(
        after <= 1e-12 && off_plane == 0.0,
        "{what}, seamed: {after:e} into the notch, {off_plane:e} off the plane"
    );
    assert!(concave_sectors(net).is_empty(), "{what}");
}

/// A convex corner (the cube's) and a sector of exactly 180° (where a
/// crease meets a straight one) are not concave.
#[test]
fn convex_and_straight_sectors_are_left_alone() {
    assert!(concave_sectors(&common::example("cube", Some(30.0))).is_empty());
    // Every boundary vertex of the grid L is a corner: those along its
    // straight sides have sectors of 180°, and only the notch is concave.
    let sectors = concave_sectors(&grid_l(2));
    assert_eq!(sectors.len(), 1, "{sectors:?}");
    assert!((sectors[0].degrees - 270.0).abs() < 1e-9, "{sectors:?}");
}

/// CGAL's anchor at 30°: six inner corners of its L-shaped flat faces,
/// four of which fold. Two are split by an edge of their fans; two have
/// no edge that splits them without a narrow angle at its far end, and
/// are left.
#[test]
fn anchor_concave_corners() {
    // None only under LOOPSURF_SKIP_DATA.
    let Some(path) = cgal_mesh("anchor.off") else {
        return;
    };
    let mut net = ControlNet::read(path).unwrap();
    net.tag_by_angle(30.0).unwrap();
    assert_eq!(concave_sectors(&net).len(), 6);
    let sectors = seam_folded_concave_corners(&mut net).unwrap();
    let corners = |seamed: bool| -> Vec<u32> {
        sectors
            .iter()
            .filter(|s| s.seam.is_some() == seamed)
            .map(|s| s.corner)
            .collect()
    };
    let (seamed, left) = (corners(true), corners(false));
    println!("anchor: seamed {seamed:?}, left {left:?}");
    for s in &sectors {
        // Each of them is the inner corner of a flat L: 270°.
        assert!((s.degrees - 270.0).abs() < 1e-3, "{s:?}");
    }
    assert_eq!(seamed, [318, 368], "{sectors:?}");
    assert_eq!(left, [478, 481], "{sectors:?}");
}
