//! The control triangles split into K parts, so that each of K processes
//! (MPI ranks) can hold and evaluate only its share of the surface.
//!
//! The graph handed to METIS is the dual graph of the control net: one
//! vertex per control triangle, one edge per control edge shared by two
//! triangles. Its edge cut is the number of control edges between parts,
//! which is what the ranks' interfaces cost. METIS's multilevel k-way
//! partitioner is asked for parts within 3 % of the mean (so that the 5 %
//! promised here holds with room), contiguous where the net is connected;
//! where contiguity still costs the balance (parts of a dozen triangles),
//! `rebalance` evens the parts out.
//!
//! **Halo.** Evaluating control triangle t exactly needs every control
//! vertex within one edge of one of t's three corners (the closed 1-rings
//! of its corners: the Loop patch of t). The halo of a part is every
//! triangle that is not in the part and uses (as a corner) at least one
//! vertex that some triangle of the part needs. Those triangles, with the
//! part's own, carry all control vertices the part needs together with the
//! connectivity around them, so a rank can build its sub-net from them.
//!
//! **Determinism.** METIS draws random numbers; a fixed random seed (the
//! options' `seed`) makes the parts a function of the net, K and the seed.
//! METIS runs serially whatever the thread count, and calls are serialized
//! here because the vendored METIS draws from the C library's `rand()`,
//! whose state is global: two partitions at once would disturb each other.
//! The same `rand()` is why the parts are reproducible on every machine
//! with the same C library (glibc on Linux), but may differ, equally valid,
//! under another C library (musl, macOS, Windows).

use crate::error::{Error, Result};
use crate::net::ControlNet;
use crate::topology::{Topology, NONE};
use std::sync::Mutex;

mod part;
mod part_model;
mod rebalance;

pub use part::Part;
pub use part_model::PartModel;

/// Largest part allowed, relative to the mean part.
pub const MAX_IMBALANCE: f64 = 1.05;

/// Imbalances asked of METIS in turn (its `ufactor`, in thousandths over
/// the mean): contiguity can cost balance, so a miss is retried tighter.
const UFACTORS: [i32; 3] = [30, 10, 1];

/// Serializes METIS calls: see the module's note on determinism.
static METIS: Mutex<()> = Mutex::new(());

/// How to partition.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PartitionOptions {
    /// METIS's random seed: the same seed gives the same parts.
    pub seed: i32,
}

impl Default for PartitionOptions {
    fn default() -> Self {
        PartitionOptions { seed: 1 }
    }
}

/// Control triangles in parts, with what each part needs of the others.
#[derive(Debug, Clone)]
pub struct Partition {
    part: Vec<u32>,
    nparts: usize,
    cut: usize,
    members: Vec<Vec<u32>>,
    halos: Vec<Vec<u32>>,
}

/// [`partition_with`] with the default options.
pub fn partition(net: &ControlNet, k: usize) -> Result<Partition> {
    partition_with(net, k, &PartitionOptions::default())
}

/// Splits the net's triangles into `k` parts: balanced (the largest part
/// holds at most [`MAX_IMBALANCE`] × the mean, or ⌈N / k⌉ triangles where
/// that is more), each part connected where the net is connected, few
/// control edges between parts. `k` = 1 puts everything in part 0 without
/// METIS. A net of several pieces is partitioned as a whole, and a part may
/// then span pieces.
pub fn partition_with(net: &ControlNet, k: usize, opts: &PartitionOptions) -> Result<Partition> {
    let topo = net.topology();
    let n = topo.num_triangles();
    if k == 0 || k > n {
        return Err(Error::InvalidArgument(format!(
            "cannot partition {n} triangles into K = {k} parts: K must be between 1 and {n}"
        )));
    }
    let part = if k == 1 {
        vec![0; n]
    } else {
        metis_parts(topo, k, opts.seed, None)?
    };
    Ok(Partition::from_parts(topo, part, k))
}

/// How much more a cut next to a triangle that [`partition_avoiding`]
/// avoids costs than one elsewhere.
const AVOIDED_CUT: i32 = 100;

/// [`partition`] with cuts next to the triangles `avoid` marks made
/// [`AVOIDED_CUT`] times dearer (METIS's edge weights), so the parts'
/// interfaces run elsewhere where they can: a second partition whose
/// interfaces keep away from a first one's.
pub(crate) fn partition_avoiding(net: &ControlNet, k: usize, avoid: &[bool]) -> Result<Partition> {
    let topo = net.topology();
    let n = topo.num_triangles();
    if k <= 1 || k > n {
        return partition(net, k);
    }
    let weight = |a: u32, b: u32| {
        if avoid[a as usize] || avoid[b as usize] {
            AVOIDED_CUT
        } else {
            1
        }
    };
    let part = metis_parts(topo, k, PartitionOptions::default().seed, Some(&weight))?;
    Ok(Partition::from_parts(topo, part, k))
}

/// Part `p` of `partition` as a net of its own ([`Part`]): its triangles
/// and their halo, with global ids.
pub fn part(net: &ControlNet, partition: &Partition, p: usize) -> Result<Part> {
    let k = partition.num_parts();
    if p >= k {
        return Err(Error::InvalidArgument(format!(
            "part {p}: out of range (the partition has K = {k} parts, 0 to {})",
            k - 1
        )));
    }
    if partition.parts().len() != net.triangles().len() {
        return Err(Error::InvalidArgument(format!(
            "the partition covers {} triangles, the net has {}",
            partition.parts().len(),
            net.triangles().len()
        )));
    }
    Part::new(net, partition.triangles(p))
}

/// The most triangles a part may hold: 5 % over the mean, or the fewest
/// that any split of `n` into `k` parts must have in one part.
pub fn max_part_size(n: usize, k: usize) -> usize {
    let allowed = (MAX_IMBALANCE * n as f64 / k as f64).floor() as usize;
    allowed.max(n.div_ceil(k))
}

/// The dual graph in compressed rows: triangle t's neighbours across its
/// local edges 0, 1, 2 (in that order, so the graph is a function of the
/// net), boundary edges left out.
pub fn dual_graph(topo: &Topology) -> (Vec<u32>, Vec<u32>) {
    let edge_tris = topo.edge_triangles();
    let mut start = Vec::with_capacity(topo.num_triangles() + 1);
    let mut adj = Vec::with_capacity(3 * topo.num_triangles());
    start.push(0);
    for (t, edges) in topo.triangle_edges().iter().enumerate() {
        for &e in edges {
            let [a, b] = edge_tris[e as usize];
            let other = if a as usize == t { b } else { a };
            if other != NONE {
                adj.push(other);
            }
        }
        start.push(adj.len() as u32);
    }
    (start, adj)
}

/// True when every triangle is reached from triangle 0 across edges.
fn is_connected(start: &[u32], adj: &[u32]) -> bool {
    let n = start.len() - 1;
    let mut seen = vec![false; n];
    let mut stack = vec![0usize];
    seen[0] = true;
    let mut reached = 1;
    while let Some(t) = stack.pop() {
        for &s in &adj[start[t] as usize..start[t + 1] as usize] {
            if !seen[s as usize] {
                seen[s as usize] = true;
                reached += 1;
                stack.push(s as usize);
            }
        }
    }
    reached == n
}

/// METIS k-way on the dual graph. A part over [`max_part_size`] is evened
/// out by moving border triangles ([`rebalance`]); if that fails, METIS is
/// asked again with a tighter imbalance.
fn metis_parts(
    topo: &Topology,
    k: usize,
    seed: i32,
    weight: Option<&dyn Fn(u32, u32) -> i32>,
) -> Result<Vec<u32>> {
    let (start, adj) = dual_graph(topo);
    let too_large = || {
        Error::InvalidArgument(format!(
            "{} triangles are too many for METIS's 32-bit indices",
            topo.num_triangles()
        ))
    };
    let xadj: Vec<i32> = start
        .iter()
        .map(|&x| i32::try_from(x))
        .collect::<Result<_, _>>()
        .map_err(|_| too_large())?;
    let adjncy: Vec<i32> = adj.iter().map(|&x| x as i32).collect();
    let adjwgt: Option<Vec<i32>> = weight.map(|w| {
        (0..start.len() - 1)
            .flat_map(|t| (start[t]..start[t + 1]).map(move |i| (t as u32, i)))
            .map(|(t, i)| w(t, adj[i as usize]))
            .collect()
    });
    // METIS refuses (and prints) a contiguity request on a disconnected graph.
    let contig = is_connected(&start, &adj);
    let n = topo.num_triangles();
    let limit = max_part_size(n, k);
    let mut largest = 0;
    for ufactor in UFACTORS {
        let mut part = run_metis(&xadj, &adjncy, adjwgt.as_deref(), k, seed, ufactor, contig)?;
        largest = largest_part(&part, k);
        if largest <= limit || rebalance::rebalance(&start, &adj, &mut part, k, limit, contig) {
            return Ok(part);
        }
    }
    Err(Error::InvalidArgument(format!(
        "METIS could not balance {n} triangles into K = {k} parts: the largest part has {largest} triangles, over the {limit} allowed (5 % over the mean)"
    )))
}

fn largest_part(part: &[u32], k: usize) -> usize {
    let mut sizes = vec![0usize; k];
    for &p in part {
        sizes[p as usize] += 1;
    }
    sizes.into_iter().max().unwrap_or(0)
}

/// One METIS k-way call, under the lock.
fn run_metis(
    xadj: &[i32],
    adjncy: &[i32],
    adjwgt: Option<&[i32]>,
    k: usize,
    seed: i32,
    ufactor: i32,
    contig: bool,
) -> Result<Vec<u32>> {
    let mut part = vec![0i32; xadj.len() - 1];
    let fail = |e: &dyn std::fmt::Display| Error::InvalidArgument(format!("METIS: {e}"));
    let mut graph = metis::Graph::new(1, k as i32, xadj, adjncy).map_err(|e| fail(&e))?;
    if let Some(w) = adjwgt {
        graph = graph.set_adjwgt(w);
    }
    let graph = graph
        .set_option(metis::option::Seed(seed))
        .set_option(metis::option::UFactor(ufactor))
        .set_option(metis::option::Contig(contig));
    let _lock = METIS.lock().unwrap_or_else(|e| e.into_inner());
    graph.part_kway(&mut part).map_err(|e| fail(&e))?;
    Ok(part.into_iter().map(|p| p as u32).collect())
}

impl Partition {
    /// The partition given by each triangle's part (all below `nparts`):
    /// counts the cut and gathers the parts and their halos.
    pub fn from_parts(topo: &Topology, part: Vec<u32>, nparts: usize) -> Partition {
        assert_eq!(part.len(), topo.num_triangles());
        let cut = topo
            .edge_triangles()
            .iter()
            .filter(|[a, b]| *b != NONE && part[*a as usize] != part[*b as usize])
            .count();
        let mut members = vec![Vec::new(); nparts];
        for (t, &p) in part.iter().enumerate() {
            members[p as usize].push(t as u32);
        }
        let halos = halos(topo, &part, nparts);
        Partition {
            part,
            nparts,
            cut,
            members,
            halos,
        }
    }

    /// Number of parts (K).
    pub fn num_parts(&self) -> usize {
        self.nparts
    }
    /// Each triangle's part, in triangle order.
    pub fn parts(&self) -> &[u32] {
        &self.part
    }
    /// Number of control edges between two parts.
    pub fn edge_cut(&self) -> usize {
        self.cut
    }
    /// The triangles of part `p`, ascending.
    pub fn triangles(&self, p: usize) -> &[u32] {
        &self.members[p]
    }
    /// The halo of part `p` (see the module's definition), ascending.
    pub fn halo(&self, p: usize) -> &[u32] {
        &self.halos[p]
    }
    /// Triangle count of the largest part.
    pub fn largest(&self) -> usize {
        self.members.iter().map(Vec::len).max().unwrap_or(0)
    }
    /// Triangle count of the largest halo.
    pub fn largest_halo(&self) -> usize {
        self.halos.iter().map(Vec::len).max().unwrap_or(0)
    }
}

/// Every part's halo. A vertex is needed by the parts owning a triangle
/// around it or around one of its neighbours; a triangle is then in the
/// halo of every part, other than its own, that needs one of its corners.
fn halos(topo: &Topology, part: &[u32], nparts: usize) -> Vec<Vec<u32>> {
    let nv = topo.num_vertices();
    let touching: Vec<Vec<u32>> = (0..nv)
        .map(|v| sorted_set(topo.fan(v).iter().map(|&t| part[t as usize])))
        .collect();
    let needing: Vec<Vec<u32>> = (0..nv)
        .map(|v| {
            let near = std::iter::once(v as u32).chain(topo.ring(v).iter().copied());
            sorted_set(near.flat_map(|u| touching[u as usize].iter().copied()))
        })
        .collect();
    let mut halos = vec![Vec::new(); nparts];
    for (t, corners) in topo.triangles().iter().enumerate() {
        let own = part[t];
        let parts = sorted_set(
            corners
                .iter()
                .flat_map(|&c| needing[c as usize].iter().copied()),
        );
        for p in parts.into_iter().filter(|&p| p != own) {
            halos[p as usize].push(t as u32);
        }
    }
    halos
}

fn sorted_set(items: impl Iterator<Item = u32>) -> Vec<u32> {
    let mut v: Vec<u32> = items.collect();
    v.sort_unstable();
    v.dedup();
    v
}
