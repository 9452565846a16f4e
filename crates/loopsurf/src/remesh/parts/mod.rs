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
//! **Then the interfaces are moved, as ParMmg does.** Next to a pinned
//! interface the first pass leaves a trace: the start's vertices there,
//! copied from the control net's shapes, never moved. A second partition,
//! whose cuts METIS is told to keep away from the first one's (dearer
//! next to them), cuts the band of the joined mesh within [`BAND_RINGS`]
//! edges of an old interface (each triangle to the part most of its
//! vertices' control triangles are in). Each part remeshes its piece of
//! the band once more, its new interface and the band's rim pinned; the
//! rest of the mesh, done, stays as it is. The new interfaces run through
//! vertices the first pass has already placed well. Where the second cut
//! must cross a first interface (two networks of cuts over one surface
//! cross), the first interface's vertices there are pinned again; a last
//! round remeshes the band around those crossings, each connected blob as
//! one uncut piece.
//!
//! **Each part sees only its own surface.** A part is remeshed on the
//! surface of its sub-net ([`crate::partition::Part`]): its triangles, the
//! triangles sharing a vertex with them (where a vertex next to the
//! interface may move, and where the start stores the interface's
//! points), and the halo that makes all of these evaluate bit for bit as
//! in the whole. Its sizes come from that surface too. So a part's piece is
//! a function of the start, the partition and the part alone: the same
//! bits whichever thread computes it, and whatever runs beside it.
//!
//! The files: [`cuts`] (which part a triangle goes to, shared vertices,
//! rings, fans, blobs), [`work`] (one part's sub-net, piece and remesh, and
//! the workers) and [`join`] (pieces into one mesh).

mod cuts;
mod join;
mod work;

use super::start;
use super::Remesher;
use crate::error::Result;
use crate::mesh::SurfaceMesh;
use crate::partition;
use crate::topology::NONE;
use cuts::{blobs, control_rings, majority, mesh_rings, shared_vertices};
use join::{join, kept, Joined};
use rayon::prelude::*;
use work::{remesh_pieces, PartWork};

/// The second pass remeshes the vertices within this many edges of a
/// first-pass interface.
const BAND_RINGS: usize = 4;

/// Where the second cut crossed a first interface, the vertices within
/// this many edges of the first interface's vertices it pinned are
/// remeshed once more. Four rings lifted fandisk in 8 parts to mean-min
/// 50.37° and eight to 50.52° (50.28° whole), joint in 4 parts from 49.90°
/// to 50.12° (49.95° whole).
const CROSSING_RINGS: usize = 8;

/// The second partition avoids cutting the control triangles within this
/// many vertex rings of those holding a first-pass interface vertex. Two
/// rings marked nearly all of pig's 891 triangles at K = 8, which left
/// METIS no choice: 1.5% of the triangles below 20° against 0.75% with
/// one ring.
const AVOID_RINGS: usize = 1;

/// [`Remesher::run`] in `k` parts (see the module doc).
pub(super) fn run(remesher: &Remesher, k: usize) -> Result<SurfaceMesh> {
    let (joined, on_interface) = first_pass(remesher, k)?;
    second_pass(remesher, k, &joined, &on_interface)
}

/// The first pass: the chart mesh cut along the control edges between
/// the parts of a partition, each piece remeshed with its interface
/// pinned, and joined; with, per vertex of the chart mesh, whether it is
/// on an interface.
fn first_pass(remesher: &Remesher, k: usize) -> Result<(Joined, Vec<bool>)> {
    let surface = remesher.surface;
    let net = surface.net();
    let first = partition::partition(net, k)?;
    let works: Vec<PartWork> = (0..k)
        .into_par_iter()
        .map(|p| PartWork::new(remesher, first.triangles(p), first.parts(), p as u32, None))
        .collect::<Result<_>>()?;
    let largest = works
        .iter()
        .map(|w| w.sizing.largest(|t| w.owned[t]))
        .fold(0.0, f64::max);
    let (adapt_to, budget) = (works[0].sizing.adapts_to(), &works[0].budget);
    let chart = start::chart_mesh(surface, largest, adapt_to, budget)?;
    let owner: Vec<u32> = chart
        .charts
        .iter()
        .map(|&c| first.parts()[c as usize])
        .collect();
    let shared = shared_vertices(&chart.triangles, &owner, chart.points.len());
    let pins: Vec<u32> = (0..chart.points.len() as u32)
        .map(|v| if shared[v as usize] { v } else { NONE })
        .collect();
    let parts: Vec<u32> = (0..k as u32).collect();
    let pieces = remesh_pieces(&works, &parts, &chart, &owner, &pins, None)?;
    drop(works);
    Ok((join(surface, &pieces)?, shared))
}

/// The second pass over the first one's mesh `pass`, whose vertices came
/// from the start's `on_interface` ones where `pass.from` says: the band
/// around the interfaces, cut along a second partition that keeps away
/// from them, each piece remeshed with its new interface and its rim
/// pinned; the rest of the mesh stays as it is. Then the crossings: where
/// the second cut had to cross a first interface, the band around the
/// first-interface vertices it pinned again is remeshed once more, each
/// connected blob of it as one piece, uncut.
fn second_pass(
    remesher: &Remesher,
    k: usize,
    pass: &Joined,
    on_interface: &[bool],
) -> Result<SurfaceMesh> {
    let net = remesher.surface.net();
    let mesh = &pass.mesh;
    let old: Vec<bool> = pass
        .from
        .iter()
        .map(|&g| g != NONE && on_interface[g as usize])
        .collect();
    let old_tris = mesh
        .params
        .iter()
        .zip(&old)
        .filter(|x| *x.1)
        .map(|x| x.0.tri);
    let avoid = control_rings(net, old_tris, AVOID_RINGS);
    let second = partition::partition_avoiding(net, k, &avoid)?;
    let band = mesh_rings(&mesh.triangles, &old, BAND_RINGS);
    let owner: Vec<u32> = mesh
        .triangles
        .iter()
        .map(|tri| {
            if tri.iter().any(|&v| band[v as usize]) {
                majority(tri.map(|v| second.parts()[mesh.params[v as usize].tri as usize]))
            } else {
                NONE
            }
        })
        .collect();
    let (moved, shared) = remesh_band(remesher, pass, &band, &owner, k, second.parts())?;
    // The first interface's vertices the second cut pinned again.
    let again: Vec<bool> = moved
        .from
        .iter()
        .map(|&g| g != NONE && old[g as usize] && shared[g as usize])
        .collect();
    if !again.contains(&true) {
        return Ok(moved.mesh);
    }
    let mesh = &moved.mesh;
    let band = mesh_rings(&mesh.triangles, &again, CROSSING_RINGS);
    let (owner, blobs) = blobs(&mesh.triangles, &band);
    let nobody = vec![NONE; net.triangles().len()];
    Ok(
        remesh_band(remesher, &moved, &band, &owner, blobs, &nobody)?
            .0
            .mesh,
    )
}

/// The triangles of `pass.mesh` that `owner` gives a part (of `k`; the
/// others, [`NONE`], stay) remeshed, each part's piece alone on a sub-net
/// of its own, with every vertex outside `band` and every vertex two
/// parts share pinned, and joined; with, per vertex of `pass.mesh`,
/// whether it was so shared. Part p's sub-net owns (for its shrink
/// factors) the control triangles t with `control_owner[t] == p`.
fn remesh_band(
    remesher: &Remesher,
    pass: &Joined,
    band: &[bool],
    owner: &[u32],
    k: usize,
    control_owner: &[u32],
) -> Result<(Joined, Vec<bool>)> {
    let mesh = &pass.mesh;
    let shared = shared_vertices(&mesh.triangles, owner, mesh.points.len());
    let pins: Vec<u32> = (0..mesh.points.len() as u32)
        .map(|v| {
            if shared[v as usize] || !band[v as usize] {
                v
            } else {
                NONE
            }
        })
        .collect();
    let mut cover: Vec<Vec<u32>> = vec![Vec::new(); k];
    for (tri, &p) in mesh.triangles.iter().zip(owner) {
        if p != NONE {
            cover[p as usize].extend(tri.map(|v| mesh.params[v as usize].tri));
        }
    }
    let parts: Vec<u32> = (0..k as u32)
        .filter(|&p| !cover[p as usize].is_empty())
        .collect();
    let works: Vec<PartWork> = parts
        .par_iter()
        .map(|&p| {
            PartWork::new(
                remesher,
                &cover[p as usize],
                control_owner,
                p,
                Some(&pass.shrunk),
            )
        })
        .collect::<Result<_>>()?;
    let mut pieces = vec![kept(pass, owner)];
    pieces.extend(remesh_pieces(
        &works,
        &parts,
        mesh,
        owner,
        &pins,
        Some(&pass.sizes),
    )?);
    Ok((join(remesher.surface, &pieces)?, shared))
}
