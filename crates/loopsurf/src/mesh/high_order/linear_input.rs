//! A linear surface mesh made by another tool, put onto the surface so that
//! it can be curved (`loopsurf curve`): the usual high-order workflow is a
//! linear mesh from gmsh, raised to order 2 afterwards.
//!
//! 1. Every vertex goes to its certified closest point. A vertex farther
//!    than the allowed move is refused by name: a mesh of another model, or
//!    in other units, must not be curved onto this one.
//! 2. Every triangle takes the face of the closest point to its centroid.
//! 3. An edge between triangles of two faces, or on the boundary, lies on a
//!    model curve: the one between those two faces (the nearest, where
//!    several are). Its vertices move onto that curve (certified curve
//!    snap), and a vertex on edges of two curves onto the nearest corner of
//!    theirs, so that hard edges become chains of output edges.
//!
//! A dart's crease has one face on both sides, so edges along it are not
//! found and their nodes are placed like any others.

use super::super::SurfaceMesh;
use crate::curve::LimitCurve;
use crate::error::{Error, Result};
use crate::parameters::{vertex_point, SurfacePoint};
use crate::snap::{closest_point, snap_near};
use crate::surface::Surface;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// The largest vertex move allowed by default, relative to the net's
/// bounding-box diagonal.
pub const DEFAULT_MAX_MOVE: f64 = 0.01;

/// A linear mesh put onto the surface.
#[derive(Debug, Clone)]
pub struct OntoSurface {
    /// The mesh, its vertices on the surface, with faces and hard edges.
    pub mesh: SurfaceMesh,
    /// The largest distance a vertex moved (model units) and that vertex.
    pub largest_move: f64,
    pub largest_move_vertex: usize,
}

/// `points` and `triangles` (0-based, counter-clockwise like the net) put
/// onto `surface` as the module doc describes; `max_move` is the largest
/// move allowed, relative to the diagonal.
pub fn onto_surface(
    surface: &Surface,
    points: &[DVec3],
    triangles: &[[u32; 3]],
    max_move: f64,
) -> Result<OntoSurface> {
    check_input(points, triangles, max_move)?;
    let limit = MoveLimit {
        max_move,
        diagonal: surface.net().bbox_diagonal(),
    };
    let (mut params, mut moved) = snap_vertices(surface, points, &limit)?;
    let faces = triangle_faces(surface, triangles, &moved, &params)?;
    let feature_edges = feature_edges(triangles, &faces);
    let vertex_curves = vertex_curves(surface, points.len(), &feature_edges, &moved)?;
    for (i, sp) in place_on_curves(surface, points, &vertex_curves)? {
        params[i] = sp;
        moved[i] = surface.point(sp.tri as usize, sp.v, sp.w)?;
    }
    let (largest_move_vertex, largest_move) = (0..points.len())
        .map(|i| (i, (moved[i] - points[i]).length()))
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    if largest_move > limit.allowed() {
        return Err(limit.refuse(
            points,
            largest_move_vertex,
            largest_move,
            "nearest model curve or corner",
        ));
    }

    let edges = super::super::labels::curve_edges(surface, &params, triangles)?;
    Ok(OntoSurface {
        mesh: SurfaceMesh {
            points: moved,
            triangles: triangles.to_vec(),
            params,
            charts: Vec::new(),
            faces,
            hard_edges: edges.pairs,
            hard_edge_curves: edges.curves,
            deviation: None,
            diagonal: limit.diagonal,
        },
        largest_move,
        largest_move_vertex,
    })
}

/// The faces on an edge's two sides; a second side arrives later.
type Sides = [Option<u32>; 2];

/// How far a vertex may move: `max_move` of the diagonal.
struct MoveLimit {
    max_move: f64,
    diagonal: f64,
}

impl MoveLimit {
    /// The largest move allowed, in model units.
    fn allowed(&self) -> f64 {
        self.max_move * self.diagonal
    }

    /// The error of vertex i of `points` moving `d` to the `what`.
    fn refuse(&self, points: &[DVec3], i: usize, d: f64, what: &str) -> Error {
        let (max_move, diagonal) = (self.max_move, self.diagonal);
        Error::InvalidArgument(format!(
            "vertex {i} at {:?} is {d:.3e} from the {what} ({:.2e} of the diagonal), more than the allowed move {max_move:e}: is it a mesh of this model, in the same units?",
            points[i].to_array(),
            d / diagonal
        ))
    }
}

/// Refuses a move limit that is not positive, an empty mesh, and bad
/// triangles or points.
fn check_input(points: &[DVec3], triangles: &[[u32; 3]], max_move: f64) -> Result<()> {
    if !(max_move.is_finite() && max_move > 0.0) {
        return Err(Error::InvalidArgument(format!(
            "max move {max_move}: must be positive (a fraction of the diagonal)"
        )));
    }
    if triangles.is_empty() {
        return Err(Error::InvalidArgument("the mesh has no triangle".into()));
    }
    crate::io::check_tris(points, triangles)?;
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "vertex {i} {:?} is not finite",
            points[i].to_array()
        )));
    }
    Ok(())
}

/// Every vertex at its certified closest point: its parameters and the
/// point. A vertex farther than the limit is refused.
fn snap_vertices(
    surface: &Surface,
    points: &[DVec3],
    limit: &MoveLimit,
) -> Result<(Vec<SurfacePoint>, Vec<DVec3>)> {
    crate::snap::build_index(surface);
    let snaps = points
        .par_iter()
        .map(|&p| closest_point(surface, p))
        .collect::<Result<Vec<_>>>()?;
    let params: Vec<SurfacePoint> = snaps
        .iter()
        .map(|s| SurfacePoint {
            tri: s.tri as u32,
            v: s.v,
            w: s.w,
        })
        .collect();
    let moved: Vec<DVec3> = snaps.iter().map(|s| s.point).collect();
    if let Some(i) = (0..points.len()).find(|&i| snaps[i].distance > limit.allowed()) {
        return Err(limit.refuse(points, i, snaps[i].distance, "surface"));
    }
    Ok((params, moved))
}

/// Each triangle's face: the face of the closest point to its centroid.
fn triangle_faces(
    surface: &Surface,
    triangles: &[[u32; 3]],
    moved: &[DVec3],
    params: &[SurfacePoint],
) -> Result<Vec<u32>> {
    let face_of = surface.model().face_of_triangle();
    crate::snap::build_index(surface);
    triangles
        .par_iter()
        .map(|tri| {
            let centroid = tri.iter().map(|&i| moved[i as usize]).sum::<DVec3>() / 3.0;
            let p = params[tri[0] as usize];
            let snap = snap_near(surface, centroid, p.tri as usize, p.v, p.w)?;
            Ok(face_of[snap.tri])
        })
        .collect()
}

/// The edges between triangles of two faces, or on the boundary, with the
/// faces on their sides, in edge order.
fn feature_edges(triangles: &[[u32; 3]], faces: &[u32]) -> Vec<((u32, u32), Sides)> {
    let mut sides: HashMap<(u32, u32), Sides> = HashMap::new();
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let entry = sides.entry((a.min(b), a.max(b))).or_insert([None, None]);
            entry[usize::from(entry[0].is_some())] = Some(faces[t]);
        }
    }
    let mut feature_edges: Vec<((u32, u32), Sides)> =
        sides.into_iter().filter(|(_, f)| f[0] != f[1]).collect();
    feature_edges.sort_unstable_by_key(|e| e.0);
    feature_edges
}

/// Per vertex, the curves of the feature edges at it: each edge's curve is
/// the one between its two faces (the nearest to its midpoint, where
/// several are).
fn vertex_curves(
    surface: &Surface,
    vertices: usize,
    feature_edges: &[((u32, u32), Sides)],
    moved: &[DVec3],
) -> Result<Vec<Vec<u32>>> {
    let mut between: HashMap<Sides, Vec<u32>> = HashMap::new();
    for (c, curve) in surface.model().curves().iter().enumerate() {
        let mut pair = curve.faces;
        pair.sort();
        between.entry(pair).or_default().push(c as u32);
    }
    let mut vertex_curves: Vec<Vec<u32>> = vec![Vec::new(); vertices];
    for &((a, b), mut pair) in feature_edges {
        pair.sort();
        let candidates = between.get(&pair).map_or(&[][..], |c| &c[..]);
        let mid = 0.5 * (moved[a as usize] + moved[b as usize]);
        let curve = match candidates {
            [] => {
                return Err(Error::InvalidArgument(format!(
                    "edge ({a}, {b}) separates faces {:?} and {:?}, which no curve of the model separates: are the hard edges flagged as when this mesh was made (--hard-angle)?",
                    pair[0], pair[1]
                )))
            }
            [c] => *c,
            _ => nearest_curve(surface, candidates, mid)?,
        };
        for v in [a, b] {
            let list = &mut vertex_curves[v as usize];
            if !list.contains(&curve) {
                list.push(curve);
            }
        }
    }
    Ok(vertex_curves)
}

/// Of `candidates`, the curve nearest `p` (the first of equals).
fn nearest_curve(surface: &Surface, candidates: &[u32], p: DVec3) -> Result<u32> {
    let mut best = (f64::INFINITY, candidates[0]);
    for &c in candidates {
        let d = LimitCurve::new(surface, c as usize)?
            .closest_point(p)?
            .distance;
        if d < best.0 {
            best = (d, c);
        }
    }
    Ok(best.1)
}

/// The vertices on feature edges, placed: onto their one curve, or with
/// several onto the nearest corner of theirs.
fn place_on_curves(
    surface: &Surface,
    points: &[DVec3],
    vertex_curves: &[Vec<u32>],
) -> Result<Vec<(usize, SurfacePoint)>> {
    vertex_curves
        .par_iter()
        .enumerate()
        .filter(|(_, c)| !c.is_empty())
        .map(|(i, list)| {
            let p = points[i];
            if let [c] = list.as_slice() {
                let curve = LimitCurve::new(surface, *c as usize)?;
                let snap = curve.closest_point(p)?;
                let (_, sp) = curve.surface_points(snap.t)?[0];
                return Ok((i, sp));
            }
            let Some(x) = nearest_corner(surface, list, p) else {
                return Err(Error::InvalidArgument(format!(
                    "vertex {i} lies on edges of curves {list:?}, which meet at no corner"
                )));
            };
            let topo = surface.net().topology();
            let at = vertex_point(topo, x).expect("a model corner lies on a triangle");
            Ok((i, at))
        })
        .collect()
}

/// Of the corners of `curves`, the control vertex nearest `p` (the first
/// of equals), if they have any.
fn nearest_corner(surface: &Surface, curves: &[u32], p: DVec3) -> Option<u32> {
    let (net, model) = (surface.net(), surface.model());
    let mut best: Option<(f64, u32)> = None;
    for &c in curves {
        for corner in model.curves()[c as usize].corners.into_iter().flatten() {
            let x = model.corners()[corner as usize];
            let d = (net.points()[x as usize] - p).length();
            if best.map_or(true, |b| d < b.0) {
                best = Some((d, x));
            }
        }
    }
    best.map(|(_, x)| x)
}
