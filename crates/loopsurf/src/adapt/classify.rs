//! Liu & Kondo's NLFC step (next level flags calculation): which vertices are
//! *flat*, and which become *dead*.
//!
//! Liu & Kondo, §4.2–4.4: the conical angle (CA) of a vertex is the largest
//! angle between the normals of the triangles meeting at it; the vertex is
//! flat when its CA is below the threshold, and dead when all its
//! neighbours are flat. Dead is final: a dead vertex is never classified
//! again, and the vertices later created next to it inherit its deadness
//! (see [`super::split`]).
//!
//! Hard features extend their method, which has none: the normals are compared
//! only within one smooth sector (triangles joined around the vertex by
//! soft edges), since the angle across a hard edge is the feature itself,
//! not a lack of resolution; at a crease vertex the turning of the crease
//! curve counts as well, so curved creases keep refining and straight ones
//! stop.
//!
//! Comparing control normals within a sector measures nothing when the
//! sector is one triangle (its spread is 0), which is common on legacy
//! meshes tagged by angle: a triangle whose two edges at a vertex are both
//! hard is a sector by itself there. Crease turning counts at crease
//! vertices only, not at corners. What bends such a triangle's limit is
//! then seen at its other corners or not at all: CGAL's
//! joint.off at `--hard-angle 30 --angle 11` died whole at level 1 though
//! the limit of its triangle 385, alone in its sector at corner 98, bends
//! 11.7° while the normals compared at its other corners spread 9°; and
//! tripod.off at `--hard-angle 5 --angle 7` kept its 44 flat triangles,
//! 2.2·10⁻³ of the diagonal off the limit surface.
//!
//! So at every vertex on a hard edge (boundary edges included, being hard)
//! the conical angle also takes, for each triangle of its fan, that
//! triangle's *bending* ([`bending`]): the widest angle between its own
//! normal and the exact limit normals sampled around its edges, each from
//! the triangle's own side of any hard edge. That is the limit surface's
//! real bending across the triangle, plus the triangle's tilt against it,
//! whatever the number of triangles in the sector. It is of the order κh,
//! like Liu & Kondo's angle between neighbouring normals (h the triangle's
//! size, κ the curvature), so it shrinks at the same rate level after
//! level, and on smooth nets it is 0.75–0.9 of Liu & Kondo's conical angle:
//! the threshold means the same with and without hard edges. Vertices on
//! no hard edge keep Liu & Kondo's conical angle exactly, and so do nets
//! without hard edges.

use super::FaceChart;
use crate::error::{Error, Result};
use crate::features::VertexKind;
use crate::geometry::{angle, unit_normal};
use crate::net::ControlNet;
use crate::sets::DisjointSets;
use crate::surface::Surface;
use crate::topology::{Topology, NONE};
use glam::DVec3;
use rayon::prelude::*;

/// Where [`bending`] samples the limit normal on each edge of a triangle,
/// as fractions of the edge from its first corner: near both ends and in
/// the middle, but not at the corners themselves. The samples stay a fixed
/// fraction of the triangle away from its corners so that the bending is
/// measured at the triangle's own scale. Corner sectors of Loop's rules can
/// leave the limit surface without a tangent plane at the corner, its
/// normal turning ever faster as the corner nears (built-in torus tagged at
/// 5°, triangle 7 at vertex 16: 4° off the triangle's normal 10⁻² of the
/// way to the centroid, 33° at 10⁻⁶, 105° at 10⁻⁹, finite differences of
/// positions agreeing); a sample at the corner would report that
/// microscopic twist as this triangle's bending at every level. The
/// tangent masks' normal exactly at a special vertex is also unreliable
/// (45° off on CGAL's flat cross.off tagged at 30°, triangle 5 at
/// vertex 7). An eighth in, what bending there is near a corner is seen
/// at the next level, where the corner's triangles are half as large.
const ALONG: [f64; 3] = [0.125, 0.5, 0.875];

/// Per triangle of `net` (a level, `charts` its triangles' places on the
/// control net of `surface`): its *bending*, the widest angle, radians,
/// between the planes normal to its own normal and to the limit normals at
/// [`ALONG`] its edges; 0 for the triangles not `wanted`. Missing limit
/// normals (no tangent plane) and degenerate triangles' normals are left
/// out.
///
/// Why these samples: the limit normals around the triangle's edges span
/// the surface's bending over the triangle itself, and its own normal adds
/// its tilt against the surface; on smooth nets the largest bending in a
/// vertex's fan is 0.75–0.9 times Liu & Kondo's conical angle there (sphere
/// 0.75–0.83, torus 0.87–0.90: see the tests), so one threshold serves
/// both. Nine normals per triangle, only in the fans of live vertices on
/// hard edges, keep it a small part of a level.
///
/// Why planes (angles folded into [0°, 90°]) rather than oriented normals:
/// Loop's corner rule can fold the limit surface flat onto itself next to
/// a corner (CGAL joint at 30°: triangle 163, up to 10⁻³ of the way from
/// vertex 129 to its centroid, the normal turned over there by positions'
/// finite differences too). That does not bend the shape; counted as 180°,
/// it would keep such corners refining.
fn bending(
    net: &ControlNet,
    charts: &[FaceChart],
    surface: &Surface,
    normals: &[DVec3],
    wanted: &[bool],
) -> Result<Vec<f64>> {
    (0..net.triangles().len())
        .into_par_iter()
        .map(|t| {
            if !wanted[t] {
                return Ok(0.0);
            }
            let (tri, q) = (charts[t].tri as usize, charts[t].q);
            let mut dirs = [DVec3::ZERO; 1 + 3 * ALONG.len()];
            dirs[0] = normals[t];
            for k in 0..3 {
                let (a, b) = (q[k], q[(k + 1) % 3]);
                for (i, s) in ALONG.into_iter().enumerate() {
                    let p = a + s * (b - a);
                    dirs[1 + ALONG.len() * k + i] = match surface.normal(tri, p.x, p.y) {
                        Ok(n) => n,
                        Err(Error::NoTangentPlane { .. }) => DVec3::ZERO,
                        Err(e) => return Err(e),
                    };
                }
            }
            let mut widest: f64 = 0.0;
            for (i, &a) in dirs.iter().enumerate() {
                for &b in &dirs[i + 1..] {
                    if a != DVec3::ZERO && b != DVec3::ZERO {
                        widest = widest.max(angle(a, b.dot(a).signum() * b));
                    }
                }
            }
            Ok(widest)
        })
        .collect()
}

/// The conical angle of every vertex but the `skip`ped ones (0 for
/// those), degrees. `limit` is the limit surface of the input net, which
/// `charts` map `net`'s triangles into; with it, vertices on hard edges
/// also take the bending of their fan's triangles (see the module notes).
pub(crate) fn conical_angles(
    net: &ControlNet,
    charts: &[FaceChart],
    skip: &[bool],
    limit: Option<&Surface>,
) -> Result<Vec<f64>> {
    let (topo, features, points) = (net.topology(), net.features(), net.points());
    let normals: Vec<DVec3> = topo
        .triangles()
        .par_iter()
        .map(|t| unit_normal(t.map(|i| points[i as usize])))
        .collect();
    let kinds = features.vertex_kinds(topo);
    // Vertices on a hard edge, still classified: theirs are the fans
    // whose triangles' bending is needed.
    let hard = features.hard_edge_counts(topo);
    let on_hard = |v: usize| !skip[v] && hard[v] > 0;
    let bend = match limit {
        Some(surface) if (0..hard.len()).any(on_hard) => {
            let wanted: Vec<bool> = topo
                .triangles()
                .par_iter()
                .map(|t| t.iter().any(|&c| on_hard(c as usize)))
                .collect();
            bending(net, charts, surface, &normals, &wanted)?
        }
        _ => Vec::new(),
    };
    Ok((0..topo.num_vertices())
        .into_par_iter()
        .map(|v| {
            if skip[v] {
                return 0.0;
            }
            let mut ca = widest_in_sectors(net, v, &normals);
            if kinds[v] == VertexKind::Crease {
                if let [a, b] = features.hard_neighbours(topo, v)[..] {
                    let p = points[v];
                    ca = ca.max(angle(p - points[a as usize], points[b as usize] - p));
                }
            }
            if !bend.is_empty() && hard[v] > 0 {
                for &t in topo.fan(v) {
                    ca = ca.max(bend[t as usize]);
                }
            }
            ca.to_degrees()
        })
        .collect())
}

/// The widest angle (radians) between the unit `normals` of two triangles
/// at vertex v in one smooth sector (triangles joined around v by soft
/// edges).
fn widest_in_sectors(net: &ControlNet, v: usize, normals: &[DVec3]) -> f64 {
    let (topo, features) = (net.topology(), net.features());
    let fan = topo.fan(v);
    // Sector of each fan triangle: union over soft edges at v.
    let mut sector = DisjointSets::new(fan.len());
    for (i, &t) in fan.iter().enumerate() {
        for &e in &topo.triangle_edges()[t as usize] {
            let [a, b] = topo.edges()[e as usize];
            if (a as usize != v && b as usize != v) || features.is_hard_edge(e as usize) {
                continue;
            }
            let [t0, t1] = topo.edge_triangles()[e as usize];
            let other = if t0 == t { t1 } else { t0 };
            if other == NONE {
                continue;
            }
            if let Some(j) = fan.iter().position(|&f| f == other) {
                sector.unite(i, j);
            }
        }
    }
    // The widest pair: the smallest cosine between unit normals.
    let mut cos: f64 = 1.0;
    for i in 0..fan.len() {
        for j in i + 1..fan.len() {
            if sector.root(i) == sector.root(j) {
                cos = cos.min(normals[fan[i] as usize].dot(normals[fan[j] as usize]));
            }
        }
    }
    cos.clamp(-1.0, 1.0).acos()
}

/// How far every vertex's neighbourhood is from the limit surface, model
/// units: the larger of the vertex's distance to the surface at its own
/// parameters and, for each edge at it, the distance of the edge's
/// midpoint to the surface at the midpoint's parameters (a cheap
/// proxy for the distance of the refined mesh to the surface).
pub(crate) fn surface_errors(
    net: &ControlNet,
    charts: &[FaceChart],
    surface: &Surface,
) -> Result<Vec<f64>> {
    let (topo, tris, points) = (net.topology(), net.triangles(), net.points());
    // The surface at corner k of triangle t, or at the midpoint of its side k.
    let at = |t: usize, k: usize, mid: bool| {
        let (chart, q) = (charts[t], charts[t].q);
        let p = if mid {
            0.5 * (q[k] + q[(k + 1) % 3])
        } else {
            q[k]
        };
        surface.point(chart.tri as usize, p.x, p.y)
    };
    // Each vertex once, from the first triangle of its fan.
    let mut out: Vec<f64> = (0..points.len())
        .into_par_iter()
        .map(|v| match topo.fan(v).first() {
            None => Ok(0.0),
            Some(&t) => {
                let k = tris[t as usize]
                    .iter()
                    .position(|&c| c as usize == v)
                    .expect("in its fan");
                Ok(points[v].distance(at(t as usize, k, false)?))
            }
        })
        .collect::<Result<_>>()?;
    // Each edge once, from its first triangle.
    let edges: Vec<f64> = (0..topo.num_edges())
        .into_par_iter()
        .map(|e| {
            let t = topo.edge_triangles()[e][0] as usize;
            let k = topo.triangle_edges()[t]
                .iter()
                .position(|&x| x as usize == e)
                .expect("its edge");
            let [a, b] = topo.edges()[e].map(|v| points[v as usize]);
            Ok((0.5 * (a + b)).distance(at(t, k, true)?))
        })
        .collect::<Result<_>>()?;
    for (&[a, b], &err) in topo.edges().iter().zip(&edges) {
        for v in [a, b] {
            out[v as usize] = out[v as usize].max(err);
        }
    }
    Ok(out)
}

/// The dead flags after this level's NLFC: dead stays dead, and a vertex
/// dies when every neighbour is flat and it may (`allowed`).
pub(crate) fn next_dead(
    topo: &Topology,
    dead: &[bool],
    flat: &[bool],
    allowed: &[bool],
) -> Vec<bool> {
    (0..topo.num_vertices())
        .into_par_iter()
        .map(|v| dead[v] || (allowed[v] && topo.ring(v).iter().all(|&u| flat[u as usize])))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parameters::CORNERS;

    fn example(name: &str) -> ControlNet {
        let ex = crate::examples::by_name(name).unwrap();
        ControlNet::from_arrays(ex.points, &ex.tris).unwrap()
    }

    /// Level 0: every triangle its own control triangle.
    fn charts(net: &ControlNet) -> Vec<FaceChart> {
        (0..net.triangles().len() as u32)
            .map(|tri| FaceChart { tri, q: CORNERS })
            .collect()
    }

    /// The bending is on Liu & Kondo's scale: on smooth nets (no hard edge, so
    /// every fan is one sector and their angle is meaningful) the
    /// widest bending in each vertex's fan is 0.7–0.95 of its conical
    /// angle, at every vertex. A measure off by a factor would make one
    /// threshold mean two things.
    #[test]
    fn bending_matches_the_plain_angle_on_smooth_nets() {
        for (name, lo, hi) in [("sphere", 0.72, 0.86), ("torus", 0.84, 0.93)] {
            let net = example(name);
            let (surface, charts) = (Surface::new(&net).unwrap(), charts(&net));
            let skip = vec![false; net.points().len()];
            let plain = conical_angles(&net, &charts, &skip, None).unwrap();
            let normals: Vec<DVec3> = net
                .triangles()
                .iter()
                .map(|t| unit_normal(t.map(|i| net.points()[i as usize])))
                .collect();
            let all = vec![true; net.triangles().len()];
            let bend = bending(&net, &charts, &surface, &normals, &all).unwrap();
            for (v, &ca) in plain.iter().enumerate() {
                assert!(ca > 5.0, "{name}: vertex {v} is curved ({ca}°)");
                let widest = net
                    .topology()
                    .fan(v)
                    .iter()
                    .map(|&t| bend[t as usize].to_degrees())
                    .fold(0.0, f64::max);
                let ratio = widest / ca;
                assert!(
                    (lo..=hi).contains(&ratio),
                    "{name}: vertex {v}: bending {widest}° against the plain angle {ca}°"
                );
            }
        }
    }

    /// Without hard edges the limit surface changes nothing: Liu & Kondo's
    /// conical angle, bit for bit.
    #[test]
    fn nets_without_hard_edges_keep_the_plain_angle() {
        for name in ["sphere", "torus", "viking"] {
            let net = example(name);
            assert_eq!(net.features().num_hard_edges(), 0, "{name}");
            let (surface, charts) = (Surface::new(&net).unwrap(), charts(&net));
            let skip: Vec<bool> = (0..net.points().len()).map(|v| v % 7 == 0).collect();
            let plain = conical_angles(&net, &charts, &skip, None).unwrap();
            let with = conical_angles(&net, &charts, &skip, Some(&surface)).unwrap();
            assert_eq!(plain, with, "{name}");
        }
    }

    /// A triangle alone in its sector at a vertex (both its edges there
    /// hard) adds nothing to Liu & Kondo's angle, however its limit bends; its
    /// bending does. The sphere with every edge at vertex 0 tagged: the
    /// vertex becomes a corner whose five sectors are one triangle each, the
    /// surface there is as curved as before, and it must count about as
    /// much as Liu & Kondo's angle of the untagged vertex (18.6°).
    #[test]
    fn one_triangle_sectors_count_their_limit_bending() {
        let plain = example("sphere");
        let mut net = plain.clone();
        let v = 0usize;
        for &u in &plain.topology().ring(v).to_vec() {
            net.tag_edge(v as u32, u).unwrap();
        }
        assert_eq!(net.vertex_kinds()[v], VertexKind::Corner);
        let (surface, charts) = (Surface::new(&net).unwrap(), charts(&net));
        let skip = vec![false; net.points().len()];
        let untagged = conical_angles(&plain, &charts, &skip, None).unwrap();
        let plain = conical_angles(&net, &charts, &skip, None).unwrap();
        let with = conical_angles(&net, &charts, &skip, Some(&surface)).unwrap();
        assert_eq!(plain[v], 0.0, "every sector at the corner is one triangle");
        let ratio = with[v] / untagged[v];
        assert!(
            (0.72..=0.9).contains(&ratio),
            "{}° against {}° untagged",
            with[v],
            untagged[v]
        );
        for (u, (&s, &w)) in plain.iter().zip(&with).enumerate() {
            assert!(w >= s, "vertex {u}: {w}° below the plain angle {s}°");
        }
    }
}
