//! The first pass's start, planned over the whole control net: each
//! control triangle's chart-mesh level, and an id for every start vertex
//! two parts share. Each part then meshes its own control triangles on
//! its own sub-net's surface ([`crate::mesh::planned_chart`]), so no
//! process builds the chart mesh of the whole surface, and the pieces
//! still meet vertex for vertex: a shared edge is cut into as many points
//! from both sides, at the same parameters.
//!
//! The levels are read from the control net (chord lengths, not the
//! limit curves' lengths, which need the surface) and the parts' sizes,
//! so every process plans alike from the sizes stage's outcomes.
//!
//! Every pass's start, this one's and the later passes' (a joined mesh),
//! names its pinned vertices by [`Pins`].

use super::cuts::lowest_part;
use crate::error::{Error, Result};
use crate::mesh::density::{grade, level};
use crate::mesh::{check_budget, chord_lengths, planned_edge_cuts, ChartPoint};
use crate::partition::Part;
use crate::topology::NONE;
use crate::ControlNet;

/// The first pass's start, planned (see the module doc).
pub(super) struct StartPlan {
    /// Per control triangle: its level, graded over the whole net.
    pub(super) levels: Vec<u32>,
    /// Per control vertex: whether triangles of two parts meet there.
    on_interface: Vec<bool>,
    /// Per control edge between two parts: the id of its first inner
    /// point (the others follow it, from the edge's first end vertex);
    /// [`NONE`] elsewhere.
    edge_first: Vec<u32>,
}

impl StartPlan {
    /// The plan for `net` cut into `parts` (per control triangle), control
    /// triangle t meshed at size `sizes[t]` and the chart mesh at most
    /// `allowance` triangles; and the pins of its start: a control vertex
    /// on an interface is pinned as its own index, and the inner points of
    /// the edges between two parts after all the vertices.
    pub(super) fn new(
        net: &ControlNet,
        parts: &[u32],
        sizes: &[f64],
        sliver_cuts: bool,
        allowance: usize,
    ) -> Result<(StartPlan, Pins)> {
        let topo = net.topology();
        let lengths = chord_lengths(net);
        let mut levels: Vec<u32> = topo
            .triangle_edges()
            .iter()
            .zip(sizes)
            .map(|(es, &h)| {
                let longest = es.iter().map(|&e| lengths[e as usize]).fold(0.0, f64::max);
                level(longest / h)
            })
            .collect();
        grade(topo, &mut levels);
        let cuts = planned_edge_cuts(net, &levels, sliver_cuts);
        check_budget(&levels, &cuts, allowance)?;
        let part_of = |t: u32| parts[t as usize];
        let mut id = Vec::with_capacity(net.points().len());
        let mut lowest = Vec::with_capacity(net.points().len());
        let mut on_interface = Vec::with_capacity(net.points().len());
        for v in 0..net.points().len() {
            let fan = topo.fan(v);
            let low = fan.iter().map(|&t| part_of(t)).min().unwrap_or(NONE);
            let shared = fan.iter().any(|&t| part_of(t) != low);
            on_interface.push(shared);
            id.push(if shared { v as u32 } else { NONE });
            lowest.push(low);
        }
        let mut edge_first = vec![NONE; cuts.len()];
        for (e, &[s, t]) in topo.edge_triangles().iter().enumerate() {
            if s == NONE || t == NONE || part_of(s) == part_of(t) {
                continue;
            }
            let first = id.len();
            let end = first + cuts[e] as usize - 1;
            if end >= NONE as usize {
                return Err(Error::InvalidArgument(format!(
                    "the parts' interfaces hold more than {NONE} start points"
                )));
            }
            edge_first[e] = first as u32;
            id.extend(first as u32..end as u32);
            lowest.resize(end, part_of(s).min(part_of(t)));
        }
        let kept = vec![false; id.len()];
        let plan = StartPlan {
            levels,
            on_interface,
            edge_first,
        };
        Ok((plan, Pins { id, lowest, kept }))
    }

    /// The pin id of `point` of `part`'s planned chart mesh (part of
    /// `net`), or [`NONE`] where no other part has it.
    pub(super) fn pin(&self, net: &ControlNet, part: &Part, point: ChartPoint) -> u32 {
        let global = |v: u32| part.global_vertices()[v as usize];
        match point {
            ChartPoint::Inside => NONE,
            ChartPoint::Vertex(v) => {
                let g = global(v);
                if self.on_interface[g as usize] {
                    g
                } else {
                    NONE
                }
            }
            ChartPoint::Edge { edge, index, of } => {
                let [a, b] = part.net().topology().edges()[edge as usize].map(global);
                let topo = net.topology();
                let Some(e) = topo.find_edge(a, b) else {
                    return NONE;
                };
                match self.edge_first[e] {
                    NONE => NONE,
                    first if topo.edges()[e][0] == a => first + index,
                    first => first + of - 1 - index,
                }
            }
        }
    }
}

/// A start's pinned vertices: per vertex its pinned id (itself) or
/// [`NONE`], the lowest part holding it (which alone may join two
/// pinned vertices anew:
/// [`Remeshing::may_join`](super::super::remeshing::Remeshing::may_join)),
/// and whether a triangle no part remeshes holds it. That kept piece comes
/// before every part: it may already join two of its vertices, so no part
/// may (bull.off with its concave corners seamed, in 4 parts: part 0 cut
/// a corner between two vertices that kept triangles joined, and the
/// joined mesh held that edge four times).
pub(super) struct Pins {
    pub(super) id: Vec<u32>,
    pub(super) lowest: Vec<u32>,
    pub(super) kept: Vec<bool>,
}

impl Pins {
    /// The `n` vertices of a start whose triangle t part `owner[t]` holds,
    /// pinned where `pinned(v)`.
    pub(super) fn new(
        triangles: &[[u32; 3]],
        owner: &[u32],
        n: usize,
        pinned: impl Fn(usize) -> bool,
    ) -> Pins {
        let mut kept = vec![false; n];
        for (tri, _) in triangles.iter().zip(owner).filter(|(_, &p)| p == NONE) {
            for &v in tri {
                kept[v as usize] = true;
            }
        }
        Pins {
            id: (0..n as u32)
                .map(|v| if pinned(v as usize) { v } else { NONE })
                .collect(),
            lowest: lowest_part(triangles, owner, n),
            kept,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::cuts::control_rings;
    use super::StartPlan;
    use crate::mesh::{planned_chart, ChartPoint};
    use crate::partition::{partition, Part};
    use crate::surface::Surface;
    use crate::topology::NONE;
    use crate::{examples, ControlNet};
    use std::collections::{BTreeSet, HashMap};

    type Bits = [u64; 3];

    fn bits(x: glam::DVec3) -> Bits {
        [x.x.to_bits(), x.y.to_bits(), x.z.to_bits()]
    }

    /// Each part's own chart mesh, on its own sub-net, gives every point it
    /// shares the bits every other part holding it gives, and together they
    /// are the points the chart mesh of the whole surface at the same levels
    /// has on the control vertices and edges between two parts.
    #[test]
    fn parts_cut_their_shared_points_as_the_whole_does() {
        let e = examples::by_name("viking").unwrap();
        let mut net = ControlNet::from_arrays(e.points, &e.tris).unwrap();
        net.tag_by_angle(30.0).unwrap();
        let whole = Surface::new(&net).unwrap();
        let topo = net.topology();
        let parts = partition(&net, 4).unwrap().parts().to_vec();
        // Sizes that vary from triangle to triangle, so levels differ
        // across the interfaces.
        let d = net.bbox_diagonal();
        let sizes: Vec<f64> = (0..parts.len())
            .map(|t| d * (0.01 + 0.01 * (t % 4) as f64))
            .collect();
        let (plan, pins) = StartPlan::new(&net, &parts, &sizes, true, usize::MAX).unwrap();

        // The reference: the whole surface's chart mesh at the plan's
        // levels, its points on a vertex or edge where two parts meet.
        let all = vec![true; parts.len()];
        let (chart, sources) = planned_chart(&whole, &plan.levels, &all, true).unwrap();
        let meets = |tris: &mut dyn Iterator<Item = u32>| {
            let set: BTreeSet<u32> = tris
                .filter(|&t| t != NONE)
                .map(|t| parts[t as usize])
                .collect();
            set.len() >= 2
        };
        let expected: BTreeSet<Bits> = sources
            .iter()
            .zip(&chart.points)
            .filter(|(s, _)| match **s {
                ChartPoint::Vertex(v) => meets(&mut topo.fan(v as usize).iter().copied()),
                ChartPoint::Edge { edge, .. } => {
                    meets(&mut topo.edge_triangles()[edge as usize].iter().copied())
                }
                ChartPoint::Inside => false,
            })
            .map(|(_, &x)| bits(x))
            .collect();
        assert!(expected.len() > 20, "{} shared points", expected.len());

        let mut seen: HashMap<u32, (Bits, usize)> = HashMap::new();
        for p in 0..4u32 {
            let cover = (0..parts.len() as u32).filter(|&t| parts[t as usize] == p);
            let near = control_rings(&net, cover, 1);
            let near: Vec<u32> = (0..near.len() as u32)
                .filter(|&t| near[t as usize])
                .collect();
            let part = Part::new(&net, &near).unwrap();
            let surface = Surface::new(part.net()).unwrap();
            let globals = part.global_triangles();
            let levels: Vec<u32> = globals.iter().map(|&g| plan.levels[g as usize]).collect();
            let keep: Vec<bool> = globals.iter().map(|&g| parts[g as usize] == p).collect();
            let (chart, sources) = planned_chart(&surface, &levels, &keep, true).unwrap();
            for (&source, &x) in sources.iter().zip(&chart.points) {
                let id = plan.pin(&net, &part, source);
                if id == NONE {
                    continue;
                }
                assert_ne!(pins.id[id as usize], NONE, "part {p}: id {id} not pinned");
                let entry = seen.entry(id).or_insert((bits(x), 0));
                assert_eq!(entry.0, bits(x), "part {p}: point {id} differs");
                entry.1 += 1;
            }
        }
        assert!(
            seen.values().all(|&(_, n)| n >= 2),
            "a shared point seen once"
        );
        let got: BTreeSet<Bits> = seen.values().map(|&(x, _)| x).collect();
        assert_eq!(got, expected);
    }
}
