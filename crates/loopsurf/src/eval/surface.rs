//! The evaluator: the control net refined once, so that every triangle has
//! at most one special corner, and per triangle of that level either its
//! regular box-spline stencil or its special corner's cached configuration.

use super::affine::Affine;
use super::affine::{child_containing, rotation};
use super::special::{neighbourhood_into, Cache, Cell, Key, KeyScratch, SpecialPatch};
use super::{box_spline, regular};
use crate::net::ControlNet;
use crate::topology::NONE;
use glam::DVec3;
use rayon::prelude::*;
use std::sync::Arc;

/// How one triangle of the once-refined net is evaluated: an index into
/// one of the two tables, so that special triangles do not pay for the
/// space of regular ones.
#[derive(Debug, Clone, Copy)]
enum Patch {
    Regular(u32),
    Special(u32),
}

/// A triangle whose corner `corner` is special; `points` is its
/// neighbourhood in the once-refined net.
#[derive(Debug)]
struct SpecialCorner {
    corner: u8,
    patch: Arc<SpecialPatch>,
    points: Box<[u32]>,
}

/// An evaluator of the limit surface of a control net. Keeps only what
/// evaluation reads: the once-refined positions, box-spline coefficients of
/// regular triangles and the neighbourhoods of special corners.
pub struct Evaluator {
    points: Vec<DVec3>,
    patches: Vec<Patch>,
    regular: Vec<[DVec3; 15]>,
    special: Vec<SpecialCorner>,
    configurations: usize,
}

impl Evaluator {
    pub fn new(net: &ControlNet) -> crate::Result<Evaluator> {
        let fine = net.refine_uniform(1)?.into_net();
        let (topo, features) = (fine.topology(), fine.features());
        let kinds = fine.vertex_kinds();
        // Per level-1 triangle, in parallel: a regular patch's coefficients,
        // or a special corner's neighbourhood and configuration, looked up
        // in a per-chunk table of the chunk's distinct keys without
        // allocating. Then, in order, configurations are shared through the
        // cache. Blocks of one chunk per thread bound the memory held in
        // between.
        // The regular variant is large, but only one block lives at a time.
        #[allow(clippy::large_enum_variant)]
        enum Prepared {
            Regular([DVec3; 15]),
            Special(u8, u32, Box<[u32]>),
        }
        #[derive(Default)]
        struct Scratch {
            labels: Vec<u32>,
            key: KeyScratch,
            around: Vec<u32>,
            table: std::collections::HashMap<u64, Vec<u32>>,
            keys: Vec<Key>,
            smooth: std::collections::HashMap<usize, u32>,
            outer: Vec<u32>,
        }
        let prepare = |t: usize, scratch: &mut Scratch| {
            if let Some(s) = regular::stencil(topo, features, &kinds, t) {
                let control = s.map(|p| p.position(fine.points()));
                return Prepared::Regular(box_spline::coefficients(&control));
            }
            // Child k < 3 of a control triangle has the control vertex at
            // its corner k; the centre child is always regular.
            let corner = t % 4;
            assert!(corner < 3, "centre children are regular");
            let c = topo.triangles()[t];
            let [c, p, q] = [c[corner], c[(corner + 1) % 3], c[(corner + 2) % 3]];
            neighbourhood_into(topo, c, p, q, &mut scratch.around);
            // Most special corners are a smooth vertex of valence N among
            // regular ones, whose key depends on N alone: built once.
            let generic = generic_smooth_valence(topo, &kinds, c, &mut scratch.outer);
            if let Some(&id) = generic.and_then(|n| scratch.smooth.get(&n)) {
                return Prepared::Special(corner as u8, id, Box::from(&scratch.around[..]));
            }
            // The label table has one slot per vertex of the refined net,
            // all NONE between uses: allocated on first need.
            if scratch.labels.is_empty() {
                scratch.labels = vec![NONE; topo.num_vertices()];
            }
            Key::around_into(
                topo,
                features,
                [c, p, q],
                &mut scratch.labels,
                &mut scratch.key,
            );
            let key = scratch.key.key();
            let ids = scratch.table.entry(key.fast_hash()).or_default();
            let id = match ids.iter().find(|&&i| scratch.keys[i as usize] == *key) {
                Some(&i) => i,
                None => {
                    scratch.keys.push(key.clone());
                    ids.push(scratch.keys.len() as u32 - 1);
                    scratch.keys.len() as u32 - 1
                }
            };
            if let Some(n) = generic {
                scratch.smooth.insert(n, id);
            }
            Prepared::Special(corner as u8, id, Box::from(&scratch.around[..]))
        };
        const CHUNK: usize = 8192;
        let block = CHUNK * rayon::current_num_threads();
        let ntris = topo.num_triangles();
        let mut cache = Cache::default();
        let (mut regular_patches, mut special) = (Vec::new(), Vec::new());
        let mut patches = Vec::with_capacity(ntris);
        // One label table per pool thread for the whole build: it has a
        // slot per refined vertex, and allocating (and the kernel zeroing)
        // it per chunk cost more than everything else on a 5M-triangle net.
        let tables: Vec<std::sync::Mutex<Vec<u32>>> = (0..rayon::current_num_threads())
            .map(|_| Default::default())
            .collect();
        for start in (0..ntris).step_by(block) {
            let prepared: Vec<(Vec<Prepared>, Vec<Key>)> = (start..(start + block).min(ntris))
                .collect::<Vec<_>>()
                .par_chunks(CHUNK)
                .map(|chunk| {
                    let table = &tables[rayon::current_thread_index().unwrap_or(0) % tables.len()];
                    let mut labels = table.lock().unwrap_or_else(|e| e.into_inner());
                    let mut scratch = Scratch {
                        labels: std::mem::take(&mut *labels),
                        ..Default::default()
                    };
                    let prepared = chunk.iter().map(|&t| prepare(t, &mut scratch)).collect();
                    *labels = scratch.labels;
                    (prepared, scratch.keys)
                })
                .collect();
            for (prepared, keys) in prepared {
                // Built on a pool thread: a configuration refines a small
                // local net with parallel loops, which called from outside
                // the pool would wake a worker for every one of them (on
                // pig, more time in futexes than in arithmetic).
                let shared: Vec<Arc<SpecialPatch>> =
                    rayon::scope(|_| keys.into_iter().map(|k| cache.get(k)).collect());
                patches.extend(prepared.into_iter().map(|p| match p {
                    Prepared::Regular(coefficients) => {
                        regular_patches.push(coefficients);
                        Patch::Regular(regular_patches.len() as u32 - 1)
                    }
                    Prepared::Special(corner, id, points) => {
                        special.push(SpecialCorner {
                            corner,
                            patch: shared[id as usize].clone(),
                            points,
                        });
                        Patch::Special(special.len() as u32 - 1)
                    }
                }));
            }
        }
        regular_patches.shrink_to_fit();
        special.shrink_to_fit();
        Ok(Evaluator {
            points: fine.points().to_vec(),
            patches,
            regular: regular_patches,
            special,
            configurations: cache.len(),
        })
    }

    /// Which kind of patch serves (v, w) of `tri` (for test messages).
    #[cfg(test)]
    pub fn describe(&self, tri: usize, v: f64, w: f64) -> String {
        let (k, _) = child_containing(v, w);
        match self.patches[4 * tri + k] {
            Patch::Regular(_) => format!("child {k}: regular"),
            Patch::Special(i) => {
                let s = &self.special[i as usize];
                format!(
                    "child {k}: special corner {}, neighbourhood {:?}",
                    s.corner, s.points
                )
            }
        }
    }

    /// Bytes held: the tables, the special-corner neighbourhoods and each
    /// shared configuration once.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let mut seen = std::collections::HashSet::new();
        let shared: usize = self
            .special
            .iter()
            .filter(|s| seen.insert(Arc::as_ptr(&s.patch)))
            .map(|s| s.patch.memory_bytes())
            .sum();
        self.points.capacity() * size_of::<DVec3>()
            + self.patches.capacity() * size_of::<Patch>()
            + self.regular.capacity() * size_of::<[DVec3; 15]>()
            + self.special.capacity() * size_of::<SpecialCorner>()
            + self
                .special
                .iter()
                .map(|s| s.points.len() * size_of::<u32>())
                .sum::<usize>()
            + shared
    }

    /// Number of distinct special-corner configurations built.
    pub fn configurations(&self) -> usize {
        self.configurations
    }

    /// The special configuration of level-1 child `child` (0 to 2: the one
    /// at corner `child` of control triangle `tri`) with its neighbourhood
    /// in [`Evaluator::refined_points`], or `None` for a regular child.
    pub fn special_corner(&self, tri: usize, child: usize) -> Option<(&SpecialPatch, &[u32])> {
        match self.patches[4 * tri + child] {
            Patch::Regular(_) => None,
            Patch::Special(i) => {
                let s = &self.special[i as usize];
                Some((&s.patch, &s.points))
            }
        }
    }

    /// The polynomial piece of the surface holding (v, w) of `tri` (which
    /// must not be a special vertex) in Bernstein–Bézier form on its own
    /// triangle ([`box_spline::bernstein`]), with the map from the control
    /// triangle's (v, w) to that triangle's parameters.
    pub fn bezier_at(&self, tri: usize, v: f64, w: f64) -> Option<([DVec3; 15], Affine)> {
        let (k, to_child) = child_containing(v, w);
        match self.patches[4 * tri + k] {
            Patch::Regular(i) => Some((box_spline::bernstein(&self.regular[i as usize]), to_child)),
            Patch::Special(i) => {
                let s = &self.special[i as usize];
                let to_corner = rotation(s.corner as usize).after(&to_child);
                let (a, b) = to_corner.apply(v, w);
                let cell = Cell::locate(a, b)?;
                let (c, offset) = s.patch.cell_coefficients(&self.points, &s.points, cell);
                let bezier = box_spline::bernstein(&c).map(|x| x + offset);
                Some((bezier, cell_map(cell).after(&to_corner)))
            }
        }
    }

    /// [`Evaluator::bezier_at`] for a point of a ring around the special
    /// corner of child `child` of `tri`, from that ring's neighbourhood
    /// (`ring`, offsets from the vertex's limit `limit`, as
    /// [`SpecialPatch::ring_offsets`] gives them): skips pushing the
    /// neighbourhood down, which a caller walking the rings has done.
    pub fn ring_bezier(
        &self,
        tri: usize,
        child: usize,
        (ring, limit): (&[DVec3], DVec3),
        (v, w): (f64, f64),
    ) -> Option<([DVec3; 15], Affine)> {
        let Patch::Special(i) = self.patches[4 * tri + child] else {
            return None;
        };
        let s = &self.special[i as usize];
        let to_corner = rotation(s.corner as usize).after(&super::affine::child(child));
        let (a, b) = to_corner.apply(v, w);
        let cell = Cell::locate(a, b)?;
        let bezier = s.patch.band_bezier(cell.k, ring).map(|x| x + limit);
        Some((bezier, cell_map(cell).after(&to_corner)))
    }

    /// The positions of the once-refined net.
    pub fn refined_points(&self) -> &[DVec3] {
        &self.points
    }

    /// X alone at (v, w) of control triangle `tri`: the same bits as
    /// `eval(..)[0]` (or the vertex's limit), at a fraction of the cost on
    /// regular triangles.
    pub fn point(&self, tri: usize, v: f64, w: f64) -> DVec3 {
        let (k, to_child) = child_containing(v, w);
        match self.patches[4 * tri + k] {
            Patch::Regular(i) => {
                let (s, u) = to_child.apply(v, w);
                box_spline::eval_point(&self.regular[i as usize], s, u)
            }
            Patch::Special(_) => match self.eval(tri, v, w) {
                Ok(d) => d[0],
                Err(at) => at.limit,
            },
        }
    }

    /// X, Xv, Xw, Xvv, Xvw, Xww at (v, w) of control triangle `tri`, or,
    /// exactly at a special vertex, that vertex (of the refined net) and its
    /// exact limit position: the parametrisation is singular there.
    pub fn eval(&self, tri: usize, v: f64, w: f64) -> Result<[DVec3; 6], AtVertex> {
        let (k, to_child) = child_containing(v, w);
        let t = 4 * tri + k;
        let points = &self.points;
        match self.patches[t] {
            Patch::Regular(i) => {
                let (s, u) = to_child.apply(v, w);
                let d = box_spline::eval_coefficients(&self.regular[i as usize], s, u);
                Ok(to_child.pull_back(d))
            }
            Patch::Special(i) => {
                let SpecialCorner {
                    corner,
                    patch,
                    points: around,
                } = &self.special[i as usize];
                let map = rotation(*corner as usize).after(&to_child);
                let (s, u) = map.apply(v, w);
                let at_vertex = || AtVertex {
                    vertex: around[0],
                    limit: patch.limit_point(points, around),
                    normal: patch.normal_at_vertex(points, around),
                };
                if s + u <= 0.0 {
                    return Err(at_vertex());
                }
                match patch.eval(points, around, s, u) {
                    Some(d) => Ok(map.pull_back(d)),
                    None => Err(at_vertex()),
                }
            }
        }
    }
}

/// Evaluation inside one control triangle that remembers the coefficients
/// of every special cell it visits. Near a special vertex most of an
/// evaluation's cost is pushing the neighbourhood down to the point's ring;
/// a mesher evaluating thousands of points in one triangle pays it once per
/// ring instead of once per point. Results are bit-identical to
/// [`Evaluator::eval`] and [`Evaluator::point`].
pub struct ChartEvaluator<'a> {
    evaluator: &'a Evaluator,
    tri: usize,
    cells: Vec<CachedCell>,
}

/// The coefficients and position offset of one special cell, keyed by the
/// level-1 child it lies in, its ring and its sub-triangle.
struct CachedCell {
    key: (usize, usize, usize),
    coefficients: [DVec3; 15],
    offset: DVec3,
}

impl<'a> ChartEvaluator<'a> {
    pub fn new(evaluator: &'a Evaluator, tri: usize) -> Self {
        ChartEvaluator {
            evaluator,
            tri,
            cells: Vec::new(),
        }
    }

    /// The special corner's cell of (v, w), its coefficients and the map
    /// from (v, w) to the corner's (s, t); `Err` exactly at the vertex.
    fn special(
        &mut self,
        child: usize,
        i: u32,
        to_child: Affine,
        v: f64,
        w: f64,
    ) -> Result<(Cell, Affine, usize), AtVertex> {
        let SpecialCorner {
            corner,
            patch,
            points: around,
        } = &self.evaluator.special[i as usize];
        let map = rotation(*corner as usize).after(&to_child);
        let (s, u) = map.apply(v, w);
        let at_vertex = || AtVertex {
            vertex: around[0],
            limit: patch.limit_point(&self.evaluator.points, around),
            normal: patch.normal_at_vertex(&self.evaluator.points, around),
        };
        if s + u <= 0.0 {
            return Err(at_vertex());
        }
        let cell = Cell::locate(s, u).ok_or_else(at_vertex)?;
        let key = (child, cell.rings, cell.k);
        let slot = match self.cells.iter().position(|c| c.key == key) {
            Some(slot) => slot,
            None => {
                let (c, offset) = patch.cell_coefficients(&self.evaluator.points, around, cell);
                self.cells.push(CachedCell {
                    key,
                    coefficients: c,
                    offset,
                });
                self.cells.len() - 1
            }
        };
        Ok((cell, map, slot))
    }

    /// X at (v, w); like [`Evaluator::point`].
    pub fn point(&mut self, v: f64, w: f64) -> DVec3 {
        let (k, to_child) = child_containing(v, w);
        match self.evaluator.patches[4 * self.tri + k] {
            Patch::Regular(i) => {
                let (s, u) = to_child.apply(v, w);
                box_spline::eval_point(&self.evaluator.regular[i as usize], s, u)
            }
            Patch::Special(i) => match self.special(k, i, to_child, v, w) {
                Ok((cell, _, slot)) => {
                    let CachedCell {
                        coefficients: c,
                        offset,
                        ..
                    } = &self.cells[slot];
                    let offset = *offset;
                    box_spline::eval_point(c, cell.local.0, cell.local.1) + offset
                }
                Err(at) => at.limit,
            },
        }
    }

    /// X and its derivatives at (v, w); like [`Evaluator::eval`].
    pub fn eval(&mut self, v: f64, w: f64) -> Result<[DVec3; 6], AtVertex> {
        let (k, to_child) = child_containing(v, w);
        match self.evaluator.patches[4 * self.tri + k] {
            Patch::Regular(_) => self.evaluator.eval(self.tri, v, w),
            Patch::Special(i) => {
                let (cell, map, slot) = self.special(k, i, to_child, v, w)?;
                let CachedCell {
                    coefficients: c,
                    offset,
                    ..
                } = &self.cells[slot];
                let offset = *offset;
                let mut d = box_spline::eval_coefficients(c, cell.local.0, cell.local.1);
                d[0] += offset;
                Ok(map.pull_back(cell.pull_back(d)))
            }
        }
    }
}

/// The map from a special corner's (s, t) to the parameters of `cell`.
fn cell_map(cell: Cell) -> Affine {
    let scale = (cell.rings as f64).exp2();
    super::affine::child(cell.k).after(&Affine {
        m: [[scale, 0.0], [0.0, scale]],
        b: [0.0, 0.0],
    })
}

/// An evaluation that landed exactly on a special vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtVertex {
    /// The vertex in the once-refined net (control vertices keep their index).
    pub vertex: u32,
    /// Its exact limit position.
    pub limit: DVec3,
    /// The outward unit normal there of the sector the triangle lies in,
    /// when the sector has a tangent plane.
    pub normal: Option<DVec3>,
}

/// The valence N of c when c is a smooth vertex whose neighbours are all
/// smooth, of valence 6, and whose second ring is generic (the 2N outer
/// vertices distinct from each other and from c and its ring): then every
/// corner at c has the same configuration key, which depends on N alone
/// (the key reads only the triangles around c and its neighbours, their
/// hard edges and tags). After one refinement nearly every special corner
/// of a smooth net is one, so its key need not be built again.
fn generic_smooth_valence(
    topo: &crate::topology::Topology,
    kinds: &[crate::features::VertexKind],
    c: u32,
    outer: &mut Vec<u32>,
) -> Option<usize> {
    use crate::features::VertexKind::Smooth;
    if kinds[c as usize] != Smooth {
        return None;
    }
    let ring = topo.ring(c as usize);
    outer.clear();
    for &x in ring {
        if kinds[x as usize] != Smooth || topo.valence(x as usize) != 6 {
            return None;
        }
        let before = outer.len();
        outer.extend(
            topo.ring(x as usize)
                .iter()
                .filter(|&&y| y != c && !ring.contains(&y)),
        );
        // c and its two neighbours beside x, and three outer vertices.
        if outer.len() != before + 3 {
            return None;
        }
    }
    outer.sort_unstable();
    outer.dedup();
    // Each neighbour's outer vertices at its ends are those of the
    // neighbours beside it (across their shared edge from c): 2N distinct
    // ones when nothing else coincides.
    (outer.len() == 2 * ring.len()).then_some(ring.len())
}
