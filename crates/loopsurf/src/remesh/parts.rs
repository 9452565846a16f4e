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
use crate::partition::{self, Part};
use crate::surface::Surface;
use crate::topology::NONE;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

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

/// One part being remeshed: its sub-net's surface and its sizes.
struct PartWork {
    part: Part,
    surface: Surface,
    /// Per local triangle: whether the part owns it.
    owned: Vec<bool>,
    /// Per local triangle: its face in the whole.
    whole_face: Vec<u32>,
    sizing: Sizing,
    tolerance: Option<f64>,
    budget: Budget,
    /// Per local triangle: the shrink factor its sizes start with.
    shrunk: Vec<f64>,
}

/// One part's piece of the mesh, in the whole's triangle ids, and each
/// vertex's pinned id (its index in the start) or [`NONE`]; and the
/// shrink factors its tolerance rounds left on its own control triangles
/// (global id, factor; where below 1).
struct Piece {
    mesh: SurfaceMesh,
    pinned: Vec<u32>,
    /// Each vertex's target size at the end.
    sizes: Vec<f64>,
    shrunk: Vec<(u32, f64)>,
}

/// The pieces joined: the mesh, per vertex its index in the start it was
/// pinned to or [`NONE`] and its target size, and per control triangle
/// the pieces' shrink factors.
struct Joined {
    mesh: SurfaceMesh,
    from: Vec<u32>,
    sizes: Vec<f64>,
    shrunk: Vec<f64>,
}

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

/// The triangles with a vertex in `band`, each connected set of them (by
/// band vertices) numbered: the number of each triangle ([`NONE`] outside
/// the band, numbered in triangle order), and how many.
fn blobs(triangles: &[[u32; 3]], band: &[bool]) -> (Vec<u32>, usize) {
    let mut class: Vec<usize> = (0..triangles.len()).collect();
    fn root(class: &mut [usize], mut c: usize) -> usize {
        while class[c] != c {
            class[c] = class[class[c]];
            c = class[c];
        }
        c
    }
    let mut first = vec![usize::MAX; band.len()];
    for (t, tri) in triangles.iter().enumerate() {
        for &v in tri.iter().filter(|&&v| band[v as usize]) {
            match first[v as usize] {
                usize::MAX => first[v as usize] = t,
                u => {
                    let (a, b) = (root(&mut class, u), root(&mut class, t));
                    class[a.max(b)] = a.min(b);
                }
            }
        }
    }
    let mut number = vec![NONE; triangles.len()];
    let mut owner = vec![NONE; triangles.len()];
    let mut count = 0;
    for (t, tri) in triangles.iter().enumerate() {
        if tri.iter().any(|&v| band[v as usize]) {
            let r = root(&mut class, t);
            if number[r] == NONE {
                number[r] = count;
                count += 1;
            }
            owner[t] = number[r];
        }
    }
    (owner, count as usize)
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

/// The triangles of `mesh` no part remeshes (`owner` [`NONE`]), as a
/// piece whose every vertex is pinned to itself, with `pass`'s shrink
/// factors.
fn kept(pass: &Joined, owner: &[u32]) -> Piece {
    let mesh = &pass.mesh;
    let mut local = vec![NONE; mesh.points.len()];
    let mut pinned = Vec::new();
    let mut triangles = Vec::new();
    let mut faces = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if owner[t] != NONE {
            continue;
        }
        triangles.push(tri.map(|v| {
            if local[v as usize] == NONE {
                local[v as usize] = pinned.len() as u32;
                pinned.push(v);
            }
            local[v as usize]
        }));
        faces.push(mesh.faces[t]);
    }
    let piece = SurfaceMesh {
        points: pinned.iter().map(|&v| mesh.points[v as usize]).collect(),
        params: pinned.iter().map(|&v| mesh.params[v as usize]).collect(),
        triangles,
        charts: Vec::new(),
        faces,
        hard_edges: Vec::new(),
        hard_edge_curves: Vec::new(),
        deviation: mesh.deviation,
        diagonal: mesh.diagonal,
    };
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

/// The pieces of `start` (triangle t in part `owner[t]`), each remeshed
/// on its part (`works[i]` on part `parts[i]`), vertex v pinned where
/// `pins[v]` is not [`NONE`], its size before grading at most `bounds[v]`
/// if given.
///
/// The pieces are the unit of parallel work: as many workers as the
/// current rayon pool has threads each take the next piece, largest
/// first, and remesh it on a pool of their own (one thread each when
/// there are at least as many pieces as threads). Run as nested rayon
/// jobs instead, the pieces' serial passes held up each other's joins:
/// bunny00 in 8 parts ran 1.6 times faster on two threads than on one.
fn remesh_pieces(
    works: &[PartWork],
    parts: &[u32],
    start: &SurfaceMesh,
    owner: &[u32],
    pins: &[u32],
    bounds: Option<&[f64]>,
) -> Result<Vec<Piece>> {
    let threads = rayon::current_num_threads();
    let workers = threads.min(works.len()).max(1);
    let inner = (threads / workers).max(1);
    let mut order: Vec<usize> = (0..works.len()).collect();
    let mut sizes = vec![0usize; parts.iter().map(|&p| p as usize + 1).max().unwrap_or(0)];
    for &p in owner.iter().filter(|&&p| p != NONE) {
        sizes[p as usize] += 1;
    }
    order.sort_by_key(|&i| std::cmp::Reverse(sizes[parts[i] as usize]));
    let next = AtomicUsize::new(0);
    let done: Vec<Mutex<Option<Result<Piece>>>> = works.iter().map(|_| Mutex::new(None)).collect();
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(inner).build();
                loop {
                    let Some(&i) = order.get(next.fetch_add(1, Ordering::Relaxed)) else {
                        break;
                    };
                    let piece = match &pool {
                        Ok(pool) => {
                            pool.install(|| works[i].remesh(start, owner, pins, bounds, parts[i]))
                        }
                        Err(e) => Err(Error::InvalidArgument(format!("no thread pool: {e}"))),
                    };
                    *done[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(piece);
                }
            });
        }
    });
    done.into_iter()
        .map(|m| {
            m.into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .unwrap_or_else(|| Err(Error::InvalidArgument("a piece was not remeshed".into())))
        })
        .collect()
}

/// Per vertex of a mesh: whether triangles of more than one part use it.
fn shared_vertices(triangles: &[[u32; 3]], owner: &[u32], n: usize) -> Vec<bool> {
    let mut first = vec![NONE; n];
    let mut shared = vec![false; n];
    for (tri, &p) in triangles.iter().zip(owner) {
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

/// The part most of a triangle's three votes name (the first vote's
/// when all differ).
fn majority([a, b, c]: [u32; 3]) -> u32 {
    if b == c {
        b
    } else {
        a
    }
}

/// Per mesh vertex: whether it lies within `rings` edges of a vertex
/// `seed` marks.
fn mesh_rings(triangles: &[[u32; 3]], seed: &[bool], rings: usize) -> Vec<bool> {
    let mut near = seed.to_vec();
    for _ in 0..rings {
        let mut next = near.clone();
        for tri in triangles {
            if tri.iter().any(|&v| near[v as usize]) {
                for &v in tri {
                    next[v as usize] = true;
                }
            }
        }
        near = next;
    }
    near
}

/// Per corner (3 per triangle) of a set of triangles: the fan it belongs
/// to, named by one of the fan's corners. Two corners at one vertex are in
/// one fan when a chain of triangles sharing edges at that vertex joins
/// them.
fn fans(triangles: &[[u32; 3]]) -> Vec<usize> {
    let mut class: Vec<usize> = (0..3 * triangles.len()).collect();
    fn root(class: &mut [usize], mut c: usize) -> usize {
        while class[c] != c {
            class[c] = class[class[c]];
            c = class[c];
        }
        c
    }
    let mut edges: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            // The corners of a and b in this triangle.
            let (ca, cb) = (3 * t + k, 3 * t + (k + 1) % 3);
            match edges.remove(&(b, a)) {
                // The neighbour across runs b → a: its corner at b, then a.
                Some(other) => {
                    let (ob, oa) = (other, 3 * (other / 3) + (other % 3 + 1) % 3);
                    for (x, y) in [(ca, oa), (cb, ob)] {
                        let (rx, ry) = (root(&mut class, x), root(&mut class, y));
                        class[rx.max(ry)] = rx.min(ry);
                    }
                }
                None => {
                    edges.insert((a, b), ca);
                }
            }
        }
    }
    (0..class.len()).map(|c| root(&mut class, c)).collect()
}

/// Per control triangle: whether it lies within `rings` vertex rings of
/// one of the triangles `seeds`.
fn control_rings(
    net: &crate::ControlNet,
    seeds: impl Iterator<Item = u32>,
    rings: usize,
) -> Vec<bool> {
    let topo = net.topology();
    let mut near = vec![false; net.triangles().len()];
    let mut front: Vec<u32> = seeds.collect();
    for t in &front {
        near[*t as usize] = true;
    }
    for _ in 0..rings {
        let mut next = Vec::new();
        for &t in &front {
            for &v in &net.triangles()[t as usize] {
                for &u in topo.fan(v as usize) {
                    if !near[u as usize] {
                        near[u as usize] = true;
                        next.push(u);
                    }
                }
            }
        }
        front = next;
    }
    near
}

impl PartWork {
    /// A part covering the control triangles `cover` (and those sharing a
    /// vertex with them) as a sub-net, its surface and its sizes, shrunk
    /// by `shrunk` per global triangle (if given); it owns the triangles t
    /// with `parts[t] == p`.
    fn new(
        remesher: &Remesher,
        cover: &[u32],
        parts: &[u32],
        p: u32,
        shrunk: Option<&[f64]>,
    ) -> Result<PartWork> {
        let net = remesher.surface.net();
        let topo = net.topology();
        let mut near = vec![false; net.triangles().len()];
        for &t in cover {
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
            .map(|&g| parts[g as usize] == p)
            .collect();
        let faces = remesher.surface.model().face_of_triangle();
        let whole_face = part
            .global_triangles()
            .iter()
            .map(|&g| faces[g as usize])
            .collect();
        let surface = Surface::new(part.net())?;
        let (sizing, tolerance, budget) = remesher.sizing_on(&surface)?;
        let shrunk = part
            .global_triangles()
            .iter()
            .map(|&g| shrunk.map_or(1.0, |s| s[g as usize]))
            .collect();
        Ok(PartWork {
            shrunk,
            part,
            surface,
            owned,
            whole_face,
            sizing,
            tolerance,
            budget,
        })
    }

    /// Remeshes part `p`'s piece of `start` (whose triangle t part
    /// `owner[t]` owns), vertex v pinned where `pins[v]` is not [`NONE`].
    /// Vertices land only in the triangles that evaluate as in the whole
    /// (the part's [`Part`] owns them).
    fn remesh(
        &self,
        start: &SurfaceMesh,
        owner: &[u32],
        pins: &[u32],
        bounds: Option<&[f64]>,
        p: u32,
    ) -> Result<Piece> {
        let (piece, ids) = self.start_piece(start, owner, p)?;
        let placer = Placer::within(&self.surface, &self.whole_face, |t| self.part.is_owned(t));
        let mut work = start::start_from(placer, &piece)?;
        for (i, &g) in ids.iter().enumerate() {
            work.pinned[i] = pins[g as usize];
            if let (true, Some(bounds)) = (work.is_pinned(i as u32), bounds) {
                work.size_bound[i] = bounds[g as usize];
            }
        }
        let shrunk = Some(self.shrunk.clone());
        let (deviation, factors) = remesh(
            &mut work,
            &self.sizing,
            self.tolerance,
            &self.budget,
            shrunk,
        )?;
        let (mut mesh, kept) = finish(&work, deviation);
        let pinned = kept.iter().map(|&v| work.pinned[v as usize]).collect();
        let sizes = kept.iter().map(|&v| work.size[v as usize]).collect();
        let globals = self.part.global_triangles();
        for at in &mut mesh.params {
            at.tri = globals[at.tri as usize];
        }
        let shrunk = (0..globals.len())
            .filter(|&t| self.owned[t] && factors[t] < 1.0)
            .map(|t| (globals[t], factors[t]))
            .collect();
        Ok(Piece {
            mesh,
            pinned,
            sizes,
            shrunk,
        })
    }

    /// Part `p`'s triangles of `start` in local terms (faces stay the
    /// whole's), and the start's id of each of its vertices. Where the
    /// piece's triangles at a vertex form several fans (the piece touches
    /// itself there), each fan has its own copy; such a vertex is on an
    /// interface, pinned, and the copies join again.
    fn start_piece(
        &self,
        start: &SurfaceMesh,
        owner: &[u32],
        p: u32,
    ) -> Result<(SurfaceMesh, Vec<u32>)> {
        let mine: Vec<usize> = (0..start.triangles.len())
            .filter(|&t| owner[t] == p as u32)
            .collect();
        let fans = fans(&mine.iter().map(|&t| start.triangles[t]).collect::<Vec<_>>());
        let mut local = HashMap::new();
        let mut ids = Vec::new();
        let mut triangles = Vec::with_capacity(mine.len());
        for (i, &t) in mine.iter().enumerate() {
            let tri = start.triangles[t];
            triangles.push([0, 1, 2].map(|k| {
                *local.entry(fans[3 * i + k]).or_insert_with(|| {
                    ids.push(tri[k]);
                    ids.len() as u32 - 1
                })
            }));
        }
        let params = ids
            .iter()
            .map(|&v| {
                let at = start.params[v as usize];
                Ok(SurfacePoint {
                    tri: self.local(at.tri)?,
                    ..at
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let piece = SurfaceMesh {
            points: ids.iter().map(|&v| start.points[v as usize]).collect(),
            triangles,
            params,
            charts: Vec::new(),
            faces: mine.iter().map(|&t| start.faces[t]).collect(),
            hard_edges: Vec::new(),
            hard_edge_curves: Vec::new(),
            deviation: None,
            diagonal: start.diagonal,
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
/// ids, and the whole's curves.
fn join(surface: &Surface, pieces: &[Piece]) -> Result<Joined> {
    let mut points: Vec<DVec3> = Vec::new();
    let mut params: Vec<SurfacePoint> = Vec::new();
    let mut from: Vec<u32> = Vec::new();
    let mut sizes: Vec<f64> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut faces: Vec<u32> = Vec::new();
    let mut at_pinned: HashMap<u32, u32> = HashMap::new();
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
                    g => *at_pinned.entry(g).or_insert_with(add),
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
    let mesh = SurfaceMesh {
        points,
        triangles,
        params,
        charts: Vec::new(),
        faces,
        hard_edges: curves.pairs,
        hard_edge_curves: curves.curves,
        deviation,
        diagonal: surface.net().bbox_diagonal(),
    };
    Ok(Joined {
        mesh,
        from,
        sizes,
        shrunk,
    })
}
