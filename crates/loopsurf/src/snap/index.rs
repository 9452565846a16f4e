//! The snapping index: a bounding-volume hierarchy over the control
//! triangles' patches, and below each patch a quadtree of cells — the
//! pieces the patch falls into under a few uniform subdivision steps — each
//! node with a convex container of its piece of surface ([`CellBound`]).
//!
//! Why the containers hold: every Loop mask has non-negative weights summing
//! to one, so a patch lies in the convex hull of its support (the control
//! points of its corners' one-rings, Persson, Aftosmis & Haines §2); after one more step the
//! same holds for each of its four children, after two for each of its
//! sixteen grandchildren. So the piece of a triangle of the net refined
//! `deep` times lies in the hull of the twice-refined points around its
//! children's corners — the vertex points of those six vertices and the edge
//! points of the edges at them — which hugs the surface far closer than the
//! control points do; a cell's piece, the union of the deepest pieces below
//! it, lies in the hull of all of theirs.

use super::cell::{cell_corners, CellBound};
use crate::features::Features;
use crate::refine::subdivide_points;
use crate::surface::Surface;
use crate::topology::Topology;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// How finely the index cuts: (cell level, support depth). Patches are cut
/// into cells `level` times — at least once, since on a bumpy scan one
/// patch can hold two minima of the distance a search must tell apart (each
/// cell solve answers for one basin) — and the containers are built from
/// the support of the pieces `depth` ≥ `level` steps down: the deeper, the
/// tighter (their lateral slack halves per step) and the fewer cells a
/// query must solve, at four times the build work per step. Depth grows
/// while the twice-refined support stays under `SUPPORT_BUDGET` triangles,
/// and cells sit one level above it (pig, 891 triangles: depth 3, cells of
/// level 2; bunny00, 75 408: depth 1, level 1, 377 040 cells, 67 MB with the
/// hierarchy). Nets too large for one cut to fit `CELL_LIMIT` cells keep
/// whole patches.
const SUPPORT_BUDGET: usize = 1 << 20;
const CELL_LIMIT: usize = 1 << 21;
const MAX_DEPTH: u32 = 4;

fn cutting(triangles: usize) -> (u32, u32) {
    if 5 * triangles > CELL_LIMIT {
        return (0, 0);
    }
    let depth = (1..=MAX_DEPTH)
        .rev()
        .find(|&d| triangles << (2 * (d + 2)) <= SUPPORT_BUDGET)
        .unwrap_or(1);
    (depth.saturating_sub(1).max(1), depth)
}

/// What the search needs beyond the surface: built on the first snap.
pub(crate) struct SnapIndex {
    /// The patches' hierarchy; node 0 is the root.
    pub(crate) nodes: Vec<BoxNode>,
    /// The containers of every cell, coarsest level first; a level-k cell c
    /// (numbered as uniform refinement numbers triangles) is entry
    /// `level_start[k] + c`, its children are cells 4c … 4c + 3 of level k + 1.
    pub(crate) cells: Vec<CellBound>,
    pub(crate) level_start: Vec<usize>,
    /// Subdivision steps from control triangles to the finest cells.
    pub(crate) level: u32,
    /// The bounding-box diagonal of the net.
    pub(crate) diagonal: f64,
    /// The round-off allowance of the pieces below the cells: their Bézier
    /// coefficients are interpolated from evaluated points, each good to a
    /// few units in the last place of the coordinates.
    pub(crate) piece_pad: f64,
}

/// A node of the patches' hierarchy: an axis-aligned box around the
/// supports below it, and either two child nodes or one patch.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BoxNode {
    pub(crate) lo: DVec3,
    pub(crate) hi: DVec3,
    pub(crate) content: Content,
}

#[derive(Debug, Clone, Copy)]
pub(crate) enum Content {
    Children(u32, u32),
    Patch(u32),
}

impl BoxNode {
    /// Distance from p to the box (zero inside).
    pub(crate) fn distance(&self, p: DVec3) -> f64 {
        let d = (self.lo - p).max(p - self.hi).max(DVec3::ZERO);
        d.length()
    }
}

/// One level of a uniform refinement, owned.
struct Level {
    topo: Topology,
    features: Features,
    points: Vec<DVec3>,
}

impl Level {
    fn refine(topo: &Topology, features: &Features, points: &[DVec3]) -> Level {
        Level {
            topo: topo.refined(),
            features: features.refined(topo),
            points: subdivide_points(topo, features, points),
        }
    }
}

impl SnapIndex {
    pub(crate) fn new(surface: &Surface) -> SnapIndex {
        Self::over(surface, None, surface.net().triangles().len())
    }

    /// The index of the patches of the triangles `only` marks (all when
    /// `None`): a part's owned triangles, searched without its halo. Its
    /// cells are cut as for a net of `size` triangles: a part's as its
    /// whole's, so that K parts hold about what the whole would (a part
    /// cut for its own size would take finer cells than the whole).
    pub(crate) fn over(surface: &Surface, only: Option<&[bool]>, size: usize) -> SnapIndex {
        let (level, deep) = cutting(size);
        Self::cut(surface, only, level, deep)
    }

    /// The index of every patch uncut, its containers from the net's own
    /// twice-refined points: the quickest to build, for a few queries
    /// ([`super::FewSnaps`]).
    pub(crate) fn whole_patches(surface: &Surface) -> SnapIndex {
        Self::cut(surface, None, 0, 0)
    }

    /// The index of the patches `only` marks, cut into cells `level`
    /// times, their containers from the pieces `deep` steps down.
    fn cut(surface: &Surface, only: Option<&[bool]>, level: u32, deep: u32) -> SnapIndex {
        let net = surface.net();
        let nt = net.triangles().len();
        // Every cell below reads its patches.
        surface.evaluator().make_all();
        // The net refined `deep`, `deep` + 1 and `deep` + 2 times.
        let mut cut: Option<Level> = None;
        for _ in 0..deep {
            cut = Some(match &cut {
                None => Level::refine(net.topology(), net.features(), net.points()),
                Some(l) => Level::refine(&l.topo, &l.features, &l.points),
            });
        }
        let (topo, features, points) = match &cut {
            None => (net.topology(), net.features(), net.points()),
            Some(l) => (&l.topo, &l.features, &l.points[..]),
        };
        let once = Level::refine(topo, features, points);
        let twice = subdivide_points(&once.topo, &once.features, &once.points);
        let support = Support::new(topo, &once.topo, twice);

        // Containers and boxes are grown by round-off so that evaluated
        // points, computed in floating point, never fall outside them.
        let pad = 1e-12 * net.bbox_diagonal();
        let mut level_start = vec![0];
        for k in 0..=level {
            level_start.push(level_start[k as usize] + (nt << (2 * k)));
        }
        let cells: Vec<CellBound> = (0..=level)
            .flat_map(|k| (0..nt << (2 * k)).map(move |c| (k, c)))
            .collect::<Vec<_>>()
            .into_par_iter()
            .map_init(Vec::new, |points, (k, c)| {
                // The pieces of depth `deep` below cell c of level k.
                support.gather_all(c << (2 * (deep - k))..(c + 1) << (2 * (deep - k)), points);
                let (tri, uv) = cell_corners(c, k);
                let corners = uv.map(|q| surface.point(tri, q.x, q.y).expect("corners are inside"));
                CellBound::new(corners, points.iter().copied(), pad)
                    .shifted(surface.displacements_of(tri))
            })
            .collect();
        let boxes: Vec<(DVec3, DVec3)> = (0..nt)
            .into_par_iter()
            .map_init(Vec::new, |points, t| {
                support.gather_all(t << (2 * deep)..(t + 1) << (2 * deep), points);
                let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
                for &s in points.iter() {
                    lo = lo.min(s);
                    hi = hi.max(s);
                }
                // The displaced piece lies in the box plus the box of the shifts.
                let d = surface.displacements_of(t);
                let (dlo, dhi) = (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]));
                (lo + dlo - pad, hi + dhi + pad)
            })
            .collect();
        let patches = (0..nt as u32).filter(|&t| only.map_or(true, |o| o[t as usize]));
        SnapIndex {
            nodes: hierarchy(&boxes, patches.collect()),
            cells,
            level_start,
            level,
            diagonal: net.bbox_diagonal(),
            piece_pad: 1e-14 * (net.bbox_diagonal() + magnitude(net.points())),
        }
    }

    /// The container of cell `c` of level `k`.
    pub(crate) fn cell(&self, k: u32, c: usize) -> &CellBound {
        &self.cells[self.level_start[k as usize] + c]
    }

    /// The control triangle of finest cell `cell` and where a local solve
    /// for `p` should start there: the parameters of the point of the
    /// cell's flat triangle nearest to p.
    ///
    /// The start is pulled a twentieth of the way to the cell's centre: at a
    /// corner that is an irregular vertex the parametrisation is singular,
    /// and Newton would crawl away from it by small factors per step.
    pub(crate) fn start(&self, cell: usize, p: DVec3) -> (usize, DVec2) {
        let (tri, [a, b, c]) = cell_corners(cell, self.level);
        let q = self.cell(self.level, cell).nearest(p);
        let uv = a + q.x * (b - a) + q.y * (c - a);
        (tri, 0.95 * uv + 0.05 * (a + b + c) / 3.0)
    }
}

/// The largest absolute coordinate of the points.
fn magnitude(points: &[DVec3]) -> f64 {
    points
        .iter()
        .map(|x| x.abs().max_element())
        .fold(0.0, f64::max)
}

/// A binary hierarchy of the boxes of `patches` (at least one), split at
/// the median of the box centres along the widest extent of the centres,
/// one patch a leaf.
/// Hand-rolled rather than an R-tree crate's: the search keeps tree nodes
/// and the cells below the leaves in one heap, which an R-tree's own
/// nearest-neighbour iterator cannot (with `rstar` feeding the cells, the
/// pig's random points ran at 47k/s; with one heap, 88k/s).
fn hierarchy(boxes: &[(DVec3, DVec3)], mut patches: Vec<u32>) -> Vec<BoxNode> {
    fn build(boxes: &[(DVec3, DVec3)], patches: &mut [u32], nodes: &mut Vec<BoxNode>) -> u32 {
        let (lo, hi) = patches
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &t| {
                (lo.min(boxes[t as usize].0), hi.max(boxes[t as usize].1))
            });
        let at = nodes.len();
        nodes.push(BoxNode {
            lo,
            hi,
            content: Content::Patch(patches[0]),
        });
        if patches.len() > 1 {
            let centre = |t: u32| boxes[t as usize].0 + boxes[t as usize].1;
            let (clo, chi) = patches
                .iter()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &t| {
                    (lo.min(centre(t)), hi.max(centre(t)))
                });
            let axis = crate::geometry::largest_axis(chi - clo);
            let half = patches.len() / 2;
            patches
                .select_nth_unstable_by(half, |&a, &b| centre(a)[axis].total_cmp(&centre(b)[axis]));
            let (left, right) = patches.split_at_mut(half);
            let l = build(boxes, left, nodes);
            let r = build(boxes, right, nodes);
            nodes[at].content = Content::Children(l, r);
        }
        at as u32
    }
    let mut nodes = Vec::with_capacity(2 * patches.len());
    build(boxes, &mut patches, &mut nodes);
    nodes
}

/// The twice-refined points whose hull holds each deepest piece.
struct Support<'a> {
    /// The deepest pieces' triangulation (the net `deep` times refined).
    topo: &'a Topology,
    /// Vertices of the once-refined net.
    nv1: usize,
    /// The once-refined net's edges at each of its vertices (CSR).
    vertex_edge_start: Vec<u32>,
    vertex_edges: Vec<u32>,
    /// The twice-refined points: once-refined vertices first, then one per
    /// once-refined edge.
    points: Vec<DVec3>,
}

impl<'a> Support<'a> {
    fn new(topo: &'a Topology, topo1: &Topology, points: Vec<DVec3>) -> Support<'a> {
        let nv1 = topo1.num_vertices();
        let mut vertex_edge_start = vec![0u32; nv1 + 1];
        for &[a, b] in topo1.edges() {
            vertex_edge_start[a as usize + 1] += 1;
            vertex_edge_start[b as usize + 1] += 1;
        }
        for v in 0..nv1 {
            vertex_edge_start[v + 1] += vertex_edge_start[v];
        }
        let mut fill = vertex_edge_start.clone();
        let mut vertex_edges = vec![0u32; 2 * topo1.edges().len()];
        for (e, &[a, b]) in topo1.edges().iter().enumerate() {
            for v in [a, b] {
                vertex_edges[fill[v as usize] as usize] = e as u32;
                fill[v as usize] += 1;
            }
        }
        Support {
            topo,
            nv1,
            vertex_edge_start,
            vertex_edges,
            points,
        }
    }

    /// Appends to `out`, for each corner of the piece's four children (its
    /// own corners and the once-refined vertices on its sides), the vertex
    /// point and the edge points of the once-refined edges there (some more
    /// than once).
    fn gather(&self, piece: usize, out: &mut Vec<DVec3>) {
        let nv = self.topo.num_vertices();
        let corners = self.topo.triangles()[piece].map(|c| c as usize);
        let mids = self.topo.triangle_edges()[piece].map(|e| nv + e as usize);
        for u in corners.into_iter().chain(mids) {
            out.push(self.points[u]);
            let edges = self.vertex_edge_start[u] as usize..self.vertex_edge_start[u + 1] as usize;
            for &e in &self.vertex_edges[edges] {
                out.push(self.points[self.nv1 + e as usize]);
            }
        }
    }

    /// [`Support::gather`] for a run of pieces, into a cleared `out`.
    fn gather_all(&self, pieces: std::ops::Range<usize>, out: &mut Vec<DVec3>) {
        out.clear();
        for piece in pieces {
            self.gather(piece, out);
        }
    }
}

/// The surface caches its index without knowing what it is.
impl crate::surface::Derived for SnapIndex {
    fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        self.nodes.capacity() * size_of::<BoxNode>()
            + self.cells.capacity() * size_of::<CellBound>()
            + self.level_start.capacity() * size_of::<usize>()
    }
}
