//! Which small angles of a mesh the input forces, decided from the input
//! alone: an angle below 20° is forced only at a corner of the model, in
//! a sector between two crease curves that the control net itself makes
//! narrow. The sector's angle is the one between the curves' control edges
//! at the corner (a crease curve leaves a corner along its first control
//! edge: the corner stays put and the next point of every refinement is
//! that edge's midpoint). Shares nothing with the meshers' own definition
//! (`MeshQuality::below_20_at_features`).

use loopsurf::{DVec3, Surface, SurfaceMesh};
use std::collections::HashMap;

/// A triangle below the limit: where its smallest angle is, and the input
/// sector there (`None` away from a model corner).
#[derive(Debug)]
pub struct SmallAngle {
    pub triangle: usize,
    pub degrees: f64,
    pub sector: Option<f64>,
}

impl SmallAngle {
    /// Whether the input forces it: it lies in a corner's sector that is
    /// itself narrower than `limit` degrees (every triangle there is).
    pub fn forced(&self, limit: f64) -> bool {
        self.sector.is_some_and(|s| s < limit)
    }
}

/// The small angles, one a line: triangle, angle, the input's sector.
pub fn list(small: &[&SmallAngle]) -> String {
    small
        .iter()
        .map(|s| match s.sector {
            Some(sector) => format!(
                "\n  triangle {}: {:.2}° in a sector of {sector:.2}°",
                s.triangle, s.degrees
            ),
            None => format!(
                "\n  triangle {}: {:.2}° away from corners",
                s.triangle, s.degrees
            ),
        })
        .collect()
}

/// The triangles whose smallest angle is below `limit` degrees, with the
/// input's sector at that corner.
pub fn small_angles(surface: &Surface, mesh: &SurfaceMesh, limit: f64) -> Vec<SmallAngle> {
    let net = surface.net();
    let diagonal = net.bbox_diagonal();
    let limits = net.limit_points();
    let corner_of: HashMap<u32, u32> = surface
        .model()
        .corners()
        .iter()
        .filter_map(|&c| {
            let x = limits[c as usize];
            let v =
                (0..mesh.points.len()).find(|&v| mesh.points[v].distance(x) <= 1e-12 * diagonal)?;
            Some((v as u32, c))
        })
        .collect();
    let across: HashMap<(u32, u32), usize> = mesh
        .triangles
        .iter()
        .enumerate()
        .flat_map(|(t, tri)| (0..3).map(move |k| ((tri[k], tri[(k + 1) % 3]), t)))
        .collect();
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let curve_of: HashMap<(u32, u32), u32> = (mesh.hard_edges.iter().zip(&mesh.hard_edge_curves))
        .map(|(e, &c)| (key(e[0], e[1]), c))
        .collect();
    let mut out = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let angle = |k: usize| angle_at(&mesh.points, tri, k);
        let k = (0..3)
            .min_by(|&a, &b| angle(a).total_cmp(&angle(b)))
            .unwrap();
        if angle(k) >= limit {
            continue;
        }
        let sector = corner_of.get(&tri[k]).and_then(|&c| {
            let bound = |forward| {
                sector_edge(
                    &mesh.points,
                    &mesh.triangles,
                    t,
                    k,
                    forward,
                    &across,
                    &curve_of,
                )
            };
            let (a, b) = (bound(true)?, bound(false)?);
            let d = |(x, curve, _): (u32, u32, f64)| {
                let chord = mesh.points[x as usize] - mesh.points[tri[k] as usize];
                curve_direction(surface, c, curve, chord)
            };
            let between = d(a).angle_between(d(b)).to_degrees();
            // The tangents' angle is at most 180°: the output fan tells a
            // reflex sector.
            let meshed = angle(k) + a.2 + b.2;
            Some(if meshed > 180.0 {
                360.0 - between
            } else {
                between
            })
        });
        out.push(SmallAngle {
            triangle: t,
            degrees: angle(k),
            sector,
        });
    }
    out
}

/// From corner `k` of triangle `t`, turning one way around that vertex
/// across soft edges, the first hard edge: its far vertex and its curve.
/// and the angles at the vertex of the triangles turned through (not `t`).
/// `None` at an open border, or when the fan closes without one.
fn sector_edge(
    points: &[DVec3],
    triangles: &[[u32; 3]],
    t: usize,
    k: usize,
    forward: bool,
    across: &HashMap<(u32, u32), usize>,
    curve_of: &HashMap<(u32, u32), u32>,
) -> Option<(u32, u32, f64)> {
    let v = triangles[t][k];
    let mut turned = 0.0;
    // The edge (v, x): the current triangle runs v → x (forward) or x → v.
    let mut x = triangles[t][if forward { (k + 1) % 3 } else { (k + 2) % 3 }];
    loop {
        if let Some(&c) = curve_of.get(&(v.min(x), v.max(x))) {
            return Some((x, c, turned));
        }
        let u = *across.get(&if forward { (x, v) } else { (v, x) })?;
        if u == t {
            return None;
        }
        let j = triangles[u].iter().position(|&y| y == v)?;
        turned += angle_at(points, &triangles[u], j);
        x = triangles[u][if forward { (j + 1) % 3 } else { (j + 2) % 3 }];
    }
}

/// The direction in which `curve` leaves control corner `c`: along its
/// first (or last) control edge; for a curve with both ends at `c`, the
/// end nearer the output edge's direction `chord`.
fn curve_direction(surface: &Surface, c: u32, curve: u32, chord: DVec3) -> DVec3 {
    let chain = &surface.model().curves()[curve as usize].chain;
    let p = surface.net().points();
    let n = chain.len() - 1;
    let ends = [(chain[0], chain[1]), (chain[n], chain[n - 1])];
    ends.iter()
        .filter(|e| e.0 == c)
        .map(|e| (p[e.1 as usize] - p[c as usize]).normalize())
        .max_by(|a, b| a.dot(chord).total_cmp(&b.dot(chord)))
        .expect("the curve ends at the corner")
}

/// The angle of triangle `tri` at its corner `k`, degrees.
fn angle_at(points: &[DVec3], tri: &[u32; 3], k: usize) -> f64 {
    let p = tri.map(|i| points[i as usize]);
    (p[(k + 1) % 3] - p[k])
        .angle_between(p[(k + 2) % 3] - p[k])
        .to_degrees()
}
