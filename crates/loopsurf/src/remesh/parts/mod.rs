//! Remeshing by parts: the control net split into K parts (METIS, as for
//! partitioned surfaces), each part remeshed on its own surface, and the
//! pieces joined along the interfaces they share.
//!
//! **The interfaces are meshed first, the same way from both sides.** The
//! start is planned over the whole control net from the net alone (chord
//! lengths) and the sizes the parts ask for ([`plan`]): a level per control
//! triangle, graded over the whole net, and an id for every start point two
//! parts share (a control vertex its index, then the inner points of each
//! edge between two parts). Each part then builds the chart mesh of its own
//! control triangles on its own sub-net's surface; a control edge's cut
//! depends only on the net and the levels, so the pieces meet vertex for
//! vertex, and no process builds the start of the whole surface. The
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
//! next to them), cuts the joined mesh within [`BAND_RINGS`]
//! edges of an old interface (each triangle to the part most of its
//! vertices' control triangles are in). Each part remeshes its piece of
//! the band once more, its new interface and the band's rim pinned; the
//! rest of the mesh, done, stays as it is. The new interfaces run through
//! vertices the first pass has already placed well. Where the second cut
//! must cross a first interface (two networks of cuts over one surface
//! cross), the first interface's vertices there are pinned again; so are
//! the corners where three pieces of the band pass meet (the second cut
//! at the band's rim, or three parts), whose triangles had every vertex
//! pinned. A further round remeshes the band around those crossings and
//! corners, each connected blob as one uncut piece. Last, the mesh around
//! each triangle still below [`TOUCH_UP_BELOW`] (at the pinned rims of
//! those pieces) is touched up, each blob uncut, by flips and relaxation
//! that make no triangle worse.
//!
//! **No process holds the whole mesh.** The later passes reach only so
//! far from the first interfaces, so each first-pass piece is split
//! [`SHARED_RINGS`] edges from them ([`interior`]): this shared band,
//! wider than any later pass reaches, goes to every process, which joins
//! the shared bands alike and runs the later passes on that mesh alone
//! (the "joined mesh" above); the piece's interior stays with the process
//! that made it. The rim between them stays pinned. The finished mesh is
//! the shared band's triangles as the last pass left them and the
//! interiors', numbered the same way on any process, so a rank hands out
//! its own piece with the whole mesh's node ids.
//!
//! **Each part sees only its own surface.** A part is remeshed on the
//! surface of its sub-net ([`crate::partition::Part`]): its triangles, the
//! triangles sharing a vertex with them (where a vertex next to the
//! interface may move), and the halo that makes all of these evaluate bit for bit as
//! in the whole. Its sizes come from that surface too. So a part's piece is
//! a function of the plan, the partition and the part alone: the same
//! bits whichever thread computes it, and whatever runs beside it.
//!
//! The files: [`job`] (the stages and their tasks, for threads and for
//! MPI ranks alike), [`plan`] (the first pass's start, planned over the
//! whole net), [`interior`] (a first-pass piece split into its band and
//! its interior, and the finished mesh put together from them),
//! [`outcome`] (a task's outcome as bytes), [`cuts`]
//! (which part a triangle goes to, shared vertices, rings, fans, blobs),
//! [`work`] (one part's sub-net, piece and remesh, and the workers) and
//! [`join`] (pieces into one mesh).

mod cuts;
mod interior;
mod job;
mod join;
mod outcome;
mod plan;
mod work;

use super::Remesher;
use crate::error::Result;
use crate::mesh::SurfaceMesh;
pub use job::PartsJob;
pub use outcome::{outcomes_from_bytes, outcomes_to_bytes, TaskOutcome};

/// A first-pass piece's vertices land in its part's control triangles and
/// those within this many vertex rings of them (which evaluate as in the
/// whole: their sub-net holds one ring more).
const FIRST_RINGS: usize = 1;

/// A later piece's vertices land in the control triangles its start's
/// vertices lie in and those within this many vertex rings of them. Its
/// piece is a thin band, where an edge's midpoint can lie beyond one ring
/// of control triangles of both its ends: with one ring, fandisk at 30°
/// in 8 parts (tolerance 9e-4) refused the splits of the same long edges
/// sweep after sweep (503 refusals of edges over twice their target, up
/// to 5.8 times; the whole run refuses none) and kept a 14.04° triangle;
/// with two, 4 such refusals and 23.52°, for no measurable time.
const LATER_RINGS: usize = 2;

/// The later passes see the first pass's mesh within this many edges of
/// an interface, which every process holds ([`interior`]); the rest stays
/// where it was made. The band pass reaches [`BAND_RINGS`] edges from an
/// interface and the crossings' blobs [`CROSSING_RINGS`] edges from a
/// vertex on one, the touch-up [`TOUCH_UP_RINGS`] more: the rim, pinned,
/// lies past them.
const SHARED_RINGS: usize = 16;

/// The second pass remeshes the vertices within this many edges of a
/// first-pass interface.
const BAND_RINGS: usize = 4;

/// Where the second cut crossed a first interface or three pieces met,
/// the vertices within this many edges of the vertices pinned there are
/// remeshed once more. Four rings lifted fandisk in 8 parts to mean-min
/// 50.37° and eight to 50.52° (50.28° whole), joint in 4 parts from 49.90°
/// to 50.12° (49.95° whole).
const CROSSING_RINGS: usize = 8;

/// After the passes, the triangles below this smallest angle (degrees)
/// are touched up ([`TOUCH_UP_RINGS`] edges around them): the rims of
/// the band and blob pieces are pinned, and leave a few such triangles
/// where the whole run has none.
const TOUCH_UP_BELOW: f64 = 35.0;

/// A touch-up moves the vertices within this many edges of a triangle
/// below [`TOUCH_UP_BELOW`].
const TOUCH_UP_RINGS: usize = 2;

/// The second partition avoids cutting the control triangles within this
/// many vertex rings of those holding a first-pass interface vertex. Two
/// rings marked nearly all of pig's 891 triangles at K = 8, which left
/// METIS no choice: 1.5% of the triangles below 20° against 0.75% with
/// one ring.
const AVOID_RINGS: usize = 1;

/// [`Remesher::run`] in `k` parts (see the module doc): every task of
/// every stage on this process's threads.
pub(super) fn run(remesher: &Remesher, k: usize) -> Result<SurfaceMesh> {
    let mut job = PartsJob::new(remesher.clone(), k)?;
    while !job.is_done() {
        let all: Vec<usize> = (0..job.tasks()).collect();
        let outcomes = job.run_tasks(&all)?;
        job.advance(outcomes)?;
    }
    job.into_mesh()
}
