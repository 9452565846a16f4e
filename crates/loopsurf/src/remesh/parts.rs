//! Remeshing by parts: the control net split into K parts (METIS, as for
//! partitioned surfaces), each part remeshed on its own surface, and the
//! pieces joined along the interfaces they share.
//!
//! **The interfaces are meshed first, once.** The start is the chart mesh
//! of the whole surface: its points on a control edge are computed once
//! and shared by the triangles on both sides, so cut along the control
//! edges between parts its pieces already meet vertex for vertex. The
//! vertices on an interface are pinned: no pass moves or removes them, and
//! no pass splits an edge between two of them on a piece's border. Each
//! piece then runs the remesher's rounds, polish and tolerance rounds
//! alone, and the pieces join on the pinned vertices with no further
//! exchange.
//!
//! **Each part sees only its own surface.** A part is remeshed on the
//! surface of its sub-net ([`crate::partition::Part`]): its triangles, the
//! triangles sharing a vertex with them (where a vertex next to the
//! interface may move, and where the start stores the interface's
//! points), and the halo that makes all of these evaluate bit for bit as
//! in the whole. Its sizes come from that surface too. So a part's piece is
//! a function of the net, the partition and the part alone: the same bits
//! whichever thread (or process) computes it, and whatever runs beside it.

use super::budget::Budget;
use super::finish::finish;
use super::sizing::Sizing;
use super::vertices::Placer;
use super::{remesh, start, Remesher};
use crate::error::{Error, Result};
use crate::mesh::SurfaceMesh;
use crate::parameters::SurfacePoint;
use crate::partition::{self, Part, Partition};
use crate::surface::Surface;
use crate::topology::NONE;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// One part being remeshed: its sub-net's surface and its sizes.
struct PartWork {
    part: Part,
    surface: Surface,
    /// Per local triangle: whether the part owns it.
    owned: Vec<bool>,
    /// Per local triangle: whether it evaluates as in the whole (the
    /// owned ones and those sharing a vertex with them), where vertices
    /// may land.
    exact: Vec<bool>,
    sizing: Sizing,
    tolerance: Option<f64>,
    budget: Budget,
}

/// One part's piece of the mesh: local parameters and faces, and each
/// vertex's pinned id (its index in the start) or [`NONE`].
struct Piece {
    mesh: SurfaceMesh,
    pinned: Vec<u32>,
}

/// [`Remesher::run`] in `k` parts (see the module doc).
pub(super) fn run(remesher: &Remesher, k: usize) -> Result<SurfaceMesh> {
    let surface = remesher.surface;
    let net = surface.net();
    let partition = partition::partition(net, k)?;
    let works: Vec<PartWork> = (0..k)
        .into_par_iter()
        .map(|p| PartWork::new(remesher, &partition, p))
        .collect::<Result<_>>()?;
    let first = &works[0];
    let largest = works
        .iter()
        .map(|w| w.sizing.largest(|t| w.owned[t]))
        .fold(0.0, f64::max);
    let chart = start::chart_mesh(surface, largest, first.sizing.adapts_to(), &first.budget)?;
    let owner: Vec<u32> = chart
        .charts
        .iter()
        .map(|&c| partition.parts()[c as usize])
        .collect();
    let shared = shared_vertices(&chart, &owner);
    let pieces: Vec<Piece> = works
        .par_iter()
        .enumerate()
        .map(|(p, work)| work.remesh(&chart, &owner, &shared, p as u32))
        .collect::<Result<_>>()?;
    join(surface, &works, &pieces)
}

/// Per vertex of the start: whether triangles of more than one part use it.
fn shared_vertices(chart: &SurfaceMesh, owner: &[u32]) -> Vec<bool> {
    let mut first = vec![NONE; chart.points.len()];
    let mut shared = vec![false; chart.points.len()];
    for (tri, &p) in chart.triangles.iter().zip(owner) {
        for &v in tri {
            match first[v as usize] {
                NONE => first[v as usize] = p,
                q if q != p => shared[v as usize] = true,
                _ => {}
            }
        }
    }
    shared
}

impl PartWork {
    /// Part `p`: its triangles and those sharing a vertex with them as a
    /// sub-net, its surface and its sizes.
    fn new(remesher: &Remesher, partition: &Partition, p: usize) -> Result<PartWork> {
        let net = remesher.surface.net();
        let topo = net.topology();
        let mut near = vec![false; net.triangles().len()];
        for &t in partition.triangles(p) {
            for &v in &net.triangles()[t as usize] {
                for &u in topo.fan(v as usize) {
                    near[u as usize] = true;
                }
            }
        }
        let near: Vec<u32> = (0..near.len() as u32)
            .filter(|&t| near[t as usize])
            .collect();
        let part = Part::new(net, &near)?;
        let owned = part
            .global_triangles()
            .iter()
            .map(|&g| partition.parts()[g as usize] == p as u32)
            .collect();
        let exact = (0..part.global_triangles().len())
            .map(|t| part.is_owned(t))
            .collect();
        let surface = Surface::new(part.net())?;
        let (sizing, tolerance, budget) = remesher.sizing_on(&surface)?;
        Ok(PartWork {
            part,
            surface,
            owned,
            exact,
            sizing,
            tolerance,
            budget,
        })
    }

    /// Remeshes part `p`'s piece of the start `chart` (whose triangle t
    /// part `owner[t]` owns), its `shared` vertices pinned.
    fn remesh(&self, chart: &SurfaceMesh, owner: &[u32], shared: &[bool], p: u32) -> Result<Piece> {
        let (start, ids) = self.start_piece(chart, owner, p)?;
        let placer = Placer::within(&self.surface, |t| self.exact[t]);
        let mut work = start::start_from(placer, &start)?;
        for (i, &g) in ids.iter().enumerate() {
            if shared[g as usize] {
                work.pinned[i] = g;
            }
        }
        let deviation = remesh(&mut work, &self.sizing, self.tolerance, &self.budget)?;
        let (mesh, pinned) = finish(&work, deviation);
        Ok(Piece { mesh, pinned })
    }

    /// Part `p`'s triangles of the start in local terms, and the start's
    /// id of each of its vertices.
    fn start_piece(
        &self,
        chart: &SurfaceMesh,
        owner: &[u32],
        p: u32,
    ) -> Result<(SurfaceMesh, Vec<u32>)> {
        let mut local = HashMap::new();
        let mut ids = Vec::new();
        let mut triangles = Vec::new();
        let mut charts = Vec::new();
        for (t, tri) in chart.triangles.iter().enumerate() {
            if owner[t] != p {
                continue;
            }
            triangles.push(tri.map(|v| {
                *local.entry(v).or_insert_with(|| {
                    ids.push(v);
                    ids.len() as u32 - 1
                })
            }));
            charts.push(self.local(chart.charts[t])?);
        }
        let params = ids
            .iter()
            .map(|&v| {
                let at = chart.params[v as usize];
                Ok(SurfacePoint {
                    tri: self.local(at.tri)?,
                    ..at
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let faces = crate::mesh::face_labels(self.surface.model(), &charts)?;
        let piece = SurfaceMesh {
            points: ids.iter().map(|&v| chart.points[v as usize]).collect(),
            triangles,
            params,
            charts,
            faces,
            hard_edges: Vec::new(),
            hard_edge_curves: Vec::new(),
            deviation: None,
            diagonal: chart.diagonal,
        };
        Ok((piece, ids))
    }

    /// The local id of global triangle `t`, which the part must hold.
    fn local(&self, t: u32) -> Result<u32> {
        self.part
            .local_triangle(t)
            .map(|l| l as u32)
            .ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "the start's triangle {t} lies outside the part that meshes next to it"
                ))
            })
    }
}

/// The pieces joined on their pinned vertices, in the whole's triangle
/// ids, faces and curves.
fn join(surface: &Surface, works: &[PartWork], pieces: &[Piece]) -> Result<SurfaceMesh> {
    let whole_faces = surface.model().face_of_triangle();
    let mut points: Vec<DVec3> = Vec::new();
    let mut params: Vec<SurfacePoint> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut faces: Vec<u32> = Vec::new();
    let mut at_pinned: HashMap<u32, u32> = HashMap::new();
    let mut deviation: Option<f64> = None;
    for (work, piece) in works.iter().zip(pieces) {
        let globals = work.part.global_triangles();
        // Each local face's face in the whole, from a triangle in it.
        let local_faces = work.surface.model().face_of_triangle();
        let mut face_map = vec![
            NONE;
            local_faces
                .iter()
                .map(|&f| f as usize + 1)
                .max()
                .unwrap_or(0)
        ];
        for (t, &f) in local_faces.iter().enumerate() {
            if work.owned[t] || face_map[f as usize] == NONE {
                face_map[f as usize] = whole_faces[globals[t] as usize];
            }
        }
        let mesh = &piece.mesh;
        let index: Vec<u32> = (0..mesh.points.len())
            .map(|i| {
                let mut add = || {
                    let at = mesh.params[i];
                    points.push(mesh.points[i]);
                    params.push(SurfacePoint {
                        tri: globals[at.tri as usize],
                        ..at
                    });
                    points.len() as u32 - 1
                };
                match piece.pinned[i] {
                    NONE => add(),
                    g => *at_pinned.entry(g).or_insert_with(add),
                }
            })
            .collect();
        triangles.extend(mesh.triangles.iter().map(|t| t.map(|v| index[v as usize])));
        faces.extend(mesh.faces.iter().map(|&f| face_map[f as usize]));
        if let Some(d) = mesh.deviation {
            deviation = Some(deviation.map_or(d, |e: f64| e.max(d)));
        }
    }
    let curves = crate::mesh::curve_edges(surface, &params, &triangles)?;
    Ok(SurfaceMesh {
        points,
        triangles,
        params,
        charts: Vec::new(),
        faces,
        hard_edges: curves.pairs,
        hard_edge_curves: curves.curves,
        deviation,
        diagonal: surface.net().bbox_diagonal(),
    })
}
