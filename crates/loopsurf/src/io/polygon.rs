//! Splitting polygon faces into triangles (`--triangulate`).
//!
//! A fan from the first corner is only right for convex polygons: on a
//! non-convex one (CGAL's `mpi.off` has them) fan triangles overlap, fold or
//! have zero area. Readers therefore fan-split while parsing (so every
//! triangle has its slot and its line), and [`clip_ears`] replaces each fan
//! once all points are known, by ear clipping in the polygon's own plane:
//! always cutting off the corner whose triangle has the largest smallest
//! angle, so quads take their better diagonal. Ear clipping works for any
//! simple polygon, convex or not; a polygon with no ear (self-intersecting,
//! or all corners on a line) keeps its fan, and validation then reports
//! what is wrong with it.

use glam::{DVec2, DVec3};

use super::MeshData;
use crate::geometry::max_cosine;

/// Above this many corners the fan is kept: ear clipping costs O(n³) and a
/// polygon that large is not a legacy surface facet.
const MAX_CORNERS: usize = 256;

/// One polygon face that was fan-split while reading.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Polygon {
    /// Index of its first triangle in [`MeshData::tris`]; the polygon owns
    /// `corners.len() - 2` consecutive triangles from there.
    pub first_triangle: usize,
    /// Its corners as read, 0-based.
    pub corners: Vec<i64>,
}

/// Re-triangulates every polygon of `mesh` by ear clipping (see the module
/// doc), in place: each polygon keeps the same triangle slots.
pub(super) fn clip_ears(mesh: &mut MeshData) {
    for poly in &mesh.polygons {
        let n = poly.corners.len();
        if n <= 3 || n > MAX_CORNERS {
            continue;
        }
        let Some(points) = poly
            .corners
            .iter()
            .map(|&i| {
                usize::try_from(i)
                    .ok()
                    .and_then(|i| mesh.points.get(i))
                    .copied()
            })
            .collect::<Option<Vec<DVec3>>>()
        else {
            continue; // a bad index: validation names it
        };
        if let Some(tris) = triangulate(&points) {
            for (k, t) in tris.iter().enumerate() {
                mesh.tris[poly.first_triangle + k] = t.map(|c| poly.corners[c]);
            }
        }
    }
}

/// Triangles (as corner positions 0..n) of the polygon through `points`,
/// or None when it has no ear at some step.
fn triangulate(points: &[DVec3]) -> Option<Vec<[usize; 3]>> {
    let n = points.len();
    // Newell's normal: the polygon's area vector, robust for non-planar
    // and non-convex polygons; corners run counter-clockwise about it.
    let normal = (0..n).fold(DVec3::ZERO, |acc, i| {
        acc + points[i].cross(points[(i + 1) % n])
    });
    let normal = normal.try_normalize()?;
    let u = normal.any_orthonormal_vector();
    let v = normal.cross(u);
    let flat: Vec<DVec2> = points
        .iter()
        .map(|&p| DVec2::new(p.dot(u), p.dot(v)))
        .collect();
    let mut ring: Vec<usize> = (0..n).collect();
    let mut tris = Vec::with_capacity(n - 2);
    while ring.len() > 3 {
        let m = ring.len();
        let mut best: Option<(f64, usize)> = None;
        // Starting at the second corner makes ties (a square) fall to the
        // fan's first triangle.
        for k in (1..=m).map(|k| k % m) {
            let [a, b, c] = [ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]];
            if !is_ear(&flat, &ring, [a, b, c]) {
                continue;
            }
            let quality = -max_cosine(points[a], points[b], points[c]);
            if best.map_or(true, |(q, _)| quality > q + 1e-9) {
                best = Some((quality, k));
            }
        }
        let (_, k) = best?;
        let m = ring.len();
        tris.push([ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]]);
        ring.remove(k);
    }
    tris.push([ring[0], ring[1], ring[2]]);
    Some(tris)
}

/// Whether the corner b of (a, b, c) is strictly convex and no other remaining corner
/// lies in or on the triangle (corners at the same place as a, b or c are
/// the polygon touching itself there, not in the way).
fn is_ear(flat: &[DVec2], ring: &[usize], [a, b, c]: [usize; 3]) -> bool {
    let (pa, pb, pc) = (flat[a], flat[b], flat[c]);
    // Strictly convex beyond round-off: a corner on the line through its
    // neighbours would cut off a zero-area triangle.
    let (ab, bc) = (pb - pa, pc - pb);
    if ab.perp_dot(bc) <= 1e-12 * ab.length() * bc.length() {
        return false;
    }
    // Outside one side by more than round-off: a corner on a side (within
    // round-off) blocks the ear, or the last triangle would have zero area.
    let outside = |p: DVec2, from: DVec2, to: DVec2| {
        let (side, q) = (to - from, p - from);
        side.perp_dot(q) < -1e-12 * side.length() * q.length()
    };
    ring.iter().all(|&j| {
        let p = flat[j];
        j == a
            || j == b
            || j == c
            || p == pa
            || p == pb
            || p == pc
            || outside(p, pa, pb)
            || outside(p, pb, pc)
            || outside(p, pc, pa)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(points: &[DVec3], tris: &[[usize; 3]]) -> f64 {
        tris.iter()
            .map(|&[a, b, c]| 0.5 * (points[b] - points[a]).cross(points[c] - points[a]).z)
            .sum()
    }

    #[test]
    fn non_convex_polygon_is_covered_without_overlap() {
        // An L shape whose first corner is the reflex one's neighbour: the
        // fan from corner 0 would leave the polygon.
        let l: Vec<DVec3> = [[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]]
            .iter()
            .map(|p| DVec3::new(p[0], p[1], 0.0))
            .collect();
        let rotated: Vec<DVec3> = (0..6).map(|i| l[(i + 3) % 6]).collect();
        for poly in [l, rotated] {
            let tris = triangulate(&poly).unwrap();
            assert_eq!(tris.len(), 4);
            // Every triangle counter-clockwise, and together exactly the
            // polygon's area (3): no overlap, no fold.
            for &[a, b, c] in &tris {
                let z = (poly[b] - poly[a]).cross(poly[c] - poly[a]).z;
                assert!(z > 0.0, "{tris:?}");
            }
            assert!((area(&poly, &tris) - 3.0).abs() < 1e-14);
        }
    }

    #[test]
    fn quad_takes_its_better_diagonal_and_square_keeps_the_fan() {
        // A kite: the diagonal 0-2 makes two flat triangles (175° in the
        // middle), the diagonal 1-3 two twice as sharp-free ones.
        let kite =
            [[0., 0.], [5., -0.2], [10., 0.], [5., 0.2]].map(|p| DVec3::new(p[0], p[1], 0.0));
        let tris = triangulate(&kite).unwrap();
        let uses = |a, b| tris.iter().all(|t| t.contains(&a) && t.contains(&b));
        assert!(uses(1, 3), "{tris:?}");
        let square = [[0., 0.], [1., 0.], [1., 1.], [0., 1.]].map(|p| DVec3::new(p[0], p[1], 0.0));
        assert_eq!(triangulate(&square).unwrap(), vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn collinear_polygon_has_no_ear() {
        let line = [0., 1., 2., 3.].map(|x| DVec3::new(x, 0.0, 0.0));
        assert!(triangulate(&line).is_none());
    }

    #[test]
    fn corner_on_another_side_blocks_the_ear() {
        // A hexagon of CGAL's mpi.off: corner 4 lies on the segment from
        // corner 0 to corner 3, so clipping (0, 1, 3) would leave the
        // zero-area triangle (0, 3, 4) for last.
        let hexagon = [
            [-10.008, 6.02406, -10.008],
            [-9.99992, 10.0401, -9.99992],
            [-5.99996, 10.0321, -9.99994],
            [-6.00478, 6.02406, -10.008],
            [-6.02406, 6.02406, -10.008],
            [-6.02406, 6.01927, -10.008],
        ]
        .map(DVec3::from_array);
        let tris = triangulate(&hexagon).unwrap();
        for &[a, b, c] in &tris {
            let n = (hexagon[b] - hexagon[a]).cross(hexagon[c] - hexagon[a]);
            // All on the polygon's side (it turns clockwise seen from +z)
            // and far from zero area.
            assert!(n.z < -1e-3, "{tris:?}: {n}");
        }
    }
}
