//! Pieces joined into one mesh on their pinned vertices, and the part of
//! a mesh that a pass leaves as it is, as a piece of its own.

use super::super::finish::without_curves;
use super::work::Piece;
use crate::error::Result;
use crate::mesh::SurfaceMesh;
use crate::parameters::SurfacePoint;
use crate::surface::Surface;
use crate::topology::NONE;
use glam::DVec3;

/// The pieces joined: the mesh, per vertex its index in the start it was
/// pinned to or [`NONE`] and its target size, and per control triangle
/// the pieces' shrink factors; and per vertex its id on the rim the band
/// shares with the first pass's interiors, or [`NONE`]
/// ([`super::interior`]: the job sets it, a join knows no rim).
pub(super) struct Joined {
    pub(super) mesh: SurfaceMesh,
    pub(super) from: Vec<u32>,
    pub(super) sizes: Vec<f64>,
    pub(super) shrunk: Vec<f64>,
    pub(super) rim: Vec<u32>,
}

/// The triangles of `mesh` no part remeshes (`owner` [`NONE`]), as a
/// piece whose every vertex is pinned to itself, with `pass`'s shrink
/// factors.
pub(super) fn kept(pass: &Joined, owner: &[u32]) -> Piece {
    let mesh = &pass.mesh;
    let (piece, pinned) = sub_mesh(
        mesh,
        (0..mesh.triangles.len()).filter(|&t| owner[t] == NONE),
    );
    Piece {
        mesh: piece,
        sizes: pinned.iter().map(|&v| pass.sizes[v as usize]).collect(),
        pinned,
        shrunk: (0..pass.shrunk.len() as u32)
            .filter(|&t| pass.shrunk[t as usize] < 1.0)
            .map(|t| (t, pass.shrunk[t as usize]))
            .collect(),
    }
}

/// The triangles `tris` of `mesh` as a mesh of their own (no curves),
/// and each of its vertices' index in `mesh`.
pub(super) fn sub_mesh(
    mesh: &SurfaceMesh,
    tris: impl Iterator<Item = usize>,
) -> (SurfaceMesh, Vec<u32>) {
    let mut local = vec![NONE; mesh.points.len()];
    let mut ids = Vec::new();
    let mut triangles = Vec::new();
    let mut faces = Vec::new();
    for t in tris {
        triangles.push(mesh.triangles[t].map(|v| {
            if local[v as usize] == NONE {
                local[v as usize] = ids.len() as u32;
                ids.push(v);
            }
            local[v as usize]
        }));
        faces.push(mesh.faces[t]);
    }
    let sub = without_curves(
        ids.iter().map(|&v| mesh.points[v as usize]).collect(),
        triangles,
        ids.iter().map(|&v| mesh.params[v as usize]).collect(),
        faces,
        mesh.deviation,
        mesh.diagonal,
    );
    (sub, ids)
}

/// The pieces joined on their pinned vertices, in the whole's triangle
/// ids, and the whole's curves.
pub(super) fn join(surface: &Surface, pieces: &[Piece]) -> Result<Joined> {
    let mut points: Vec<DVec3> = Vec::new();
    let mut params: Vec<SurfacePoint> = Vec::new();
    let mut from: Vec<u32> = Vec::new();
    let mut sizes: Vec<f64> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut faces: Vec<u32> = Vec::new();
    // Per pinned id: its vertex in the joined mesh, or NONE.
    let ids = pieces
        .iter()
        .flat_map(|p| p.pinned.iter().copied().filter(|&g| g != NONE).max())
        .max()
        .map_or(0, |g| g as usize + 1);
    let mut at_pinned = vec![NONE; ids];
    let mut deviation: Option<f64> = None;
    let mut shrunk = vec![1.0; surface.net().triangles().len()];
    for piece in pieces {
        for &(t, f) in &piece.shrunk {
            shrunk[t as usize] = f;
        }
        let mesh = &piece.mesh;
        let index: Vec<u32> = (0..mesh.points.len())
            .map(|i| {
                let mut add = || {
                    points.push(mesh.points[i]);
                    params.push(mesh.params[i]);
                    from.push(piece.pinned[i]);
                    sizes.push(piece.sizes[i]);
                    points.len() as u32 - 1
                };
                match piece.pinned[i] {
                    NONE => add(),
                    g => {
                        if at_pinned[g as usize] == NONE {
                            at_pinned[g as usize] = add();
                        }
                        at_pinned[g as usize]
                    }
                }
            })
            .collect();
        triangles.extend(mesh.triangles.iter().map(|t| t.map(|v| index[v as usize])));
        faces.extend_from_slice(&mesh.faces);
        if let Some(d) = mesh.deviation {
            deviation = Some(deviation.map_or(d, |e: f64| e.max(d)));
        }
    }
    let curves = crate::mesh::curve_edges(surface, &params, &triangles)?;
    let diagonal = surface.net().bbox_diagonal();
    let mut mesh = without_curves(points, triangles, params, faces, deviation, diagonal);
    mesh.hard_edges = curves.pairs;
    mesh.hard_edge_curves = curves.curves;
    Ok(Joined {
        rim: vec![NONE; mesh.points.len()],
        mesh,
        from,
        sizes,
        shrunk,
    })
}
