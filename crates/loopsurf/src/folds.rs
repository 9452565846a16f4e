//! Where the geometry folds back on itself, found so that users hear of
//! it before they look at a mesh of it: edges where the control net
//! folds ([`folded_edges`]), and control triangles whose patch of the
//! limit surface folds over itself ([`folded_patches`]). Neither
//! is an error (the surface is well defined), but no mesh of a fold has
//! good triangles that all face one way. Where a patch folds at a concave
//! corner, [`seam_folded_concave_corners`] splits the corner's sector.

use crate::concave::{concave_sectors, ConcaveSector};
use crate::error::Result;
use crate::features::dihedral_angle;
use crate::net::ControlNet;
use crate::surface::Surface;
use glam::DVec3;
use rayon::prelude::*;

/// An edge where the net folds back on itself ([`folded_edges`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fold {
    /// Its vertices, i < j.
    pub edge: [u32; 2],
    /// Its two triangles.
    pub triangles: [u32; 2],
    /// How far their normals turn, in degrees (180: folded flat).
    pub degrees: f64,
}

/// The interior edges where the net folds back on itself: the normals
/// of their two triangles turn by more than `degrees` (150 finds
/// pig.off's near-degenerate triangle 534, folded back between its
/// neighbours), largest turn first. The limit surface has a fin along
/// such an edge, which a hard angle below the turn makes a crease; a
/// mesh of the fin has poor triangles whatever the mesher, so callers
/// warn (the `loopsurf` command does) rather than refuse.
pub fn folded_edges(net: &ControlNet, degrees: f64) -> Vec<Fold> {
    let threshold = degrees.to_radians();
    let mut folds: Vec<Fold> = (0..net.topology().num_edges())
        .filter_map(|e| {
            let angle = dihedral_angle(net.topology(), net.points(), e)?;
            (angle > threshold).then(|| Fold {
                edge: net.topology().edges()[e],
                triangles: net.topology().edge_triangles()[e],
                degrees: angle.to_degrees(),
            })
        })
        .collect();
    folds.sort_by(|a, b| b.degrees.total_cmp(&a.degrees));
    folds
}

/// Samples per side of [`folded_patches`]'s grid.
const GRID: usize = 16;

/// How far the grid keeps from the sides of the control triangle, in its
/// parameters: right at an irregular vertex the normal may turn within a
/// vanishing neighbourhood, too small to matter to any mesh (kept 0.005
/// from the sides, the grid found two more such patches on smooth pig).
const INSET: f64 = 1.0 / 32.0;

/// Two normals of one patch further apart than this cosine (120°) make a
/// fold: a patch is a piece of a smooth surface one control triangle
/// wide, and turns far less on any net whose surface does not fold.
const FOLD_COSINE: f64 = -0.5;

/// The control triangles whose patch folds over itself: the surface
/// normals at two points of its grid (16 to a side, 1/32 in from the
/// sides, where creases and special vertices are) turn by more than
/// 120°. Coarse nets fold next to corners, creases and irregular
/// vertices of high valence: hole.off's faces beside its rim at 40°
/// (the normal turns from −x to +x within 0.1 of the crease),
/// anchor.off's flat faces at the inner corners of their L shapes (the
/// normal flips ±y within 4e-7 of its plane; see [`crate::concave`]),
/// pig.off next to its folded needle; none on the Viking, fandisk or CAD
/// cubes. Every patch is evaluated, 153 times: on large nets, ask
/// [`is_folded`] where a mesh shows trouble.
pub fn folded_patches(surface: &Surface) -> Vec<usize> {
    (0..surface.net().triangles().len())
        .into_par_iter()
        .filter(|&t| is_folded(surface, t))
        .collect()
}

/// Whether control triangle t's patch folds over itself (see
/// [`folded_patches`]); false for a triangle out of range.
pub fn is_folded(surface: &Surface, t: usize) -> bool {
    let normals: Vec<DVec3> = (0..=GRID)
        .flat_map(|i| (0..=GRID - i).map(move |j| (i, j)))
        .filter_map(|(i, j)| {
            let at = |k: usize| INSET + (1.0 - 3.0 * INSET) * k as f64 / GRID as f64;
            surface.normal(t, at(i), at(j)).ok()
        })
        .filter(|n| *n != DVec3::ZERO)
        .collect();
    turns_back(&normals)
}

/// Whether two of `normals` are further apart than [`FOLD_COSINE`], by
/// two farthest-point steps (from the first normal to the one furthest
/// from it, then to the one furthest from that): linear, not quadratic,
/// in the samples, and exact for normals spread along one arc, as across
/// a fold.
fn turns_back(normals: &[DVec3]) -> bool {
    let furthest = |from: DVec3| {
        normals
            .iter()
            .copied()
            .min_by(|a, b| a.dot(from).total_cmp(&b.dot(from)))
    };
    let Some(&first) = normals.first() else {
        return false;
    };
    let Some(b) = furthest(first) else {
        return false;
    };
    let c = furthest(b).unwrap_or(b);
    first.dot(b) < FOLD_COSINE || b.dot(c) < FOLD_COSINE
}

#[cfg(test)]
mod tests {
    use super::folded_edges;
    use crate::examples;
    use crate::net::ControlNet;

    /// Folds are found by the turn of the normals across an edge: none
    /// on a flat strip, every edge of a tetrahedron (109.47°) at 100° but
    /// none at 150°, and the edge of a strip whose second triangle is
    /// folded back almost onto the first.
    #[test]
    fn folds_are_edges_whose_normals_turn_back() {
        let strip = |z: f64, y: f64| {
            let points = [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.5, 1.0, 0.0],
                [0.5, y, z],
            ];
            let points = points.map(glam::DVec3::from).to_vec();
            ControlNet::from_arrays(points, &[[0, 1, 2], [1, 0, 3]]).unwrap()
        };
        assert!(folded_edges(&strip(0.0, -1.0), 1.0).is_empty());
        let folded = folded_edges(&strip(1e-3, 1.0), 150.0);
        assert_eq!(folded.len(), 1);
        assert_eq!(folded[0].edge, [0, 1]);
        assert_eq!(folded[0].triangles, [0, 1]);
        assert!((folded[0].degrees - 180.0).abs() < 0.1, "{folded:?}");
        let e = examples::by_name("tetra").unwrap();
        let tetra = ControlNet::from_arrays(e.points, &e.tris).unwrap();
        assert!(folded_edges(&tetra, 150.0).is_empty());
        let all = folded_edges(&tetra, 100.0);
        assert_eq!(all.len(), 6);
        let regular = 180.0 - (1.0f64 / 3.0).acos().to_degrees();
        assert!(
            all.iter().all(|f| (f.degrees - regular).abs() < 1e-9),
            "{all:?}"
        );
    }
}

/// Seams the concave corners whose sectors fold: among
/// [`concave_sectors`], those with a patch that folds over itself
/// ([`is_folded`], on the surface of the net as it is) get their seam
/// tagged hard. Returns those folded sectors, seamed or not (then their
/// `seam` is `None`: no edge of the fan splits them well). Sectors that
/// do not fold are left alone, since a seam there changes nothing but
/// adds a feature line to every mesh. Call it after the other tags.
pub fn seam_folded_concave_corners(net: &mut ControlNet) -> Result<Vec<ConcaveSector>> {
    let sectors = concave_sectors(net);
    if sectors.is_empty() {
        return Ok(sectors);
    }
    let surface = Surface::new(net)?;
    let folded: Vec<ConcaveSector> = sectors
        .into_iter()
        .filter(|s| s.triangles.iter().any(|&t| is_folded(&surface, t as usize)))
        .collect();
    for ([a, b], _) in folded.iter().filter_map(|s| s.seam) {
        net.tag_edge(a, b)?;
    }
    Ok(folded)
}
