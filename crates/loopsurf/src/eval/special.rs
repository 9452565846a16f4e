//! Exact, constant-time evaluation next to one special vertex: irregular
//! valence, dart, crease, corner or boundary, any configuration.
//!
//! Seen from a triangle (c, p, q) of the once-refined net whose only special
//! corner is c, the surface splits into rings: after n more subdivisions the
//! point lies in one of three regular patches of the ring at level n. The
//! points they need are a fixed neighbourhood N of c, and one subdivision
//! step maps N to the same neighbourhood one level down by a local matrix A
//! (Stam 1998). Rather than writing A per configuration by hand, it is read
//! off by running the ordinary subdivision ([`crate::refine`]) on a small
//! local net carrying the real hard edges and corners, with basis vectors
//! for positions: the masks stay in one place, and every configuration,
//! including the ones nobody publishes (creases, darts, corners on Loop), is
//! covered by the same code.
//!
//! Constant time: A^n is applied as a few products with cached powers
//! (bounded by the range of doubles, whatever the point). Valence 3, whose
//! matrix is not diagonalisable, needs nothing special. For accuracy near c,
//! everything is done on the offsets from the limit point L of c: the
//! deflated matrix D = A − 1·l (l the limit mask of [`crate::rules`]) has
//! only decaying eigenvalues, so relative errors grow like n·ε instead of
//! swamping the vanishing differences that derivatives are made of.

use super::affine::{child, Affine};
use super::{box_spline, regular};
use crate::features::Features;
use crate::net::limit_positions;
use crate::refine::subdivide_points;
use crate::topology::{Topology, NONE};
use glam::DVec3;
use std::collections::HashMap;

/// Number of cached powers D^(2^j). Deeper rings apply the largest one
/// repeatedly.
pub const POWERS: usize = 7;

/// Points closer to the special vertex than 2^-MAX_RINGS (in parameter)
/// are the vertex: their position differs from its limit by far less than
/// round-off, while their derivatives, scaled by up to 4^rings, would leave
/// the range of doubles.
pub const MAX_RINGS: usize = 256;

/// The evaluation data of one local configuration, shared by every special
/// corner that looks the same.
#[derive(Debug)]
pub struct SpecialPatch {
    size: usize,
    /// Limit mask of c over the neighbourhood.
    limit: Vec<f64>,
    /// D^(2^j), row-major size × size.
    powers: Vec<Vec<f64>>,
    /// The regular patches of the first ring (children 1, 2, 3 of (c, p, q))
    /// as polynomial coefficients over the neighbourhood, 15 × size each,
    /// stored by column (see [`apply_columns`]).
    band: [Vec<f64>; 3],
    /// The same patches in Bernstein–Bézier form on their own triangles.
    band_bezier: [Vec<f64>; 3],
    /// Tangent masks of the sector at c (see [`sector_tangents`]).
    tangents: Option<[Vec<f64>; 2]>,
}

/// A special corner's configuration, in canonical local numbering.
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
pub struct Key {
    /// Local labels of p and q: around a boundary vertex the numbering
    /// starts at the boundary whatever p is, so the local nets of its
    /// corners coincide while their matrices differ.
    corner: [u32; 2],
    tris: Vec<[u32; 3]>,
    hard: Vec<[u32; 2]>,
    tagged: Vec<u32>,
}

/// The patch of triangle (c, p, q) and its neighbourhood, built alone
/// (tests look at one configuration at a time).
#[cfg(test)]
pub fn patch_at(
    topo: &Topology,
    features: &Features,
    corner: [u32; 3],
) -> (SpecialPatch, Vec<u32>) {
    let mut scratch = KeyScratch::default();
    Key::around_into(topo, features, corner, &mut scratch);
    let [c, p, q] = corner;
    (scratch.key().build(), neighbourhood(topo, c, p, q))
}

impl SpecialPatch {
    /// The box-spline coefficients of one cell, and the offset to add to
    /// the position (the limit point when the cell lies in a ring below the
    /// first, whose coefficients are taken relative to it). Everything an
    /// evaluation in the cell needs besides (u, v): callers that evaluate
    /// many points in one cell compute this once. `around` holds the
    /// positions of the neighbourhood.
    #[inline]
    pub fn cell_coefficients(&self, around: &[DVec3], cell: Cell) -> ([DVec3; 15], DVec3) {
        if cell.rings == 0 {
            // In the first ring the band rows apply to the points themselves
            // (three quarters of the corner triangle: no copy, no scratch).
            return (apply_columns(&self.band[cell.k - 1], around), DVec3::ZERO);
        }
        // The neighbourhood, and scratch for pushing it down, on the stack
        // for the usual valences.
        const INLINE: usize = 24;
        let n = self.size;
        let (mut inline, mut inline_next) = ([DVec3::ZERO; INLINE], [DVec3::ZERO; INLINE]);
        let (mut heap, mut heap_next) = (Vec::new(), Vec::new());
        let (mut y, mut next): (&mut [DVec3], &mut [DVec3]) = if n <= INLINE {
            (&mut inline[..n], &mut inline_next[..n])
        } else {
            heap.resize(n, DVec3::ZERO);
            heap_next.resize(n, DVec3::ZERO);
            (&mut heap, &mut heap_next)
        };
        // Below the first ring, the band rows apply to the offsets from the
        // limit point, pushed `rings` levels down with the cached powers.
        let limit: DVec3 = self.limit.iter().zip(around).map(|(w, p)| *w * *p).sum();
        for (y, p) in y.iter_mut().zip(around) {
            *y = *p - limit;
        }
        self.push_down(&mut y, &mut next, cell.rings);
        (self.band_coefficients(cell.k, y), limit)
    }

    /// The box-spline coefficients of sub-triangle `k` (1 to 3) of a ring
    /// from that ring's neighbourhood (as offsets from the limit point, the
    /// coefficients then being offsets too).
    pub fn band_coefficients(&self, k: usize, ring: &[DVec3]) -> [DVec3; 15] {
        apply_columns(&self.band[k - 1], ring)
    }

    /// [`SpecialPatch::band_coefficients`] in Bernstein–Bézier form on the
    /// sub-triangle ([`box_spline::bernstein`]).
    pub fn band_bezier(&self, k: usize, ring: &[DVec3]) -> [DVec3; 15] {
        apply_columns(&self.band_bezier[k - 1], ring)
    }

    /// Pushes offsets from the limit point `rings` levels down with the
    /// cached powers of D: the largest one as often as needed, then the
    /// bits. `y` holds the result, `next` is scratch of the same length.
    fn push_down<'a>(&self, y: &mut &'a mut [DVec3], next: &mut &'a mut [DVec3], rings: usize) {
        let n = self.size;
        let apply = |power: &[f64], y: &mut &'a mut [DVec3], next: &mut &'a mut [DVec3]| {
            for (i, out) in next.iter_mut().enumerate() {
                *out = power[i * n..(i + 1) * n]
                    .iter()
                    .zip(y.iter())
                    .map(|(w, p)| *w * *p)
                    .sum();
            }
            std::mem::swap(y, next);
        };
        let top = 1usize << (POWERS - 1);
        let mut remaining = rings;
        while remaining >= 2 * top {
            apply(&self.powers[POWERS - 1], y, next);
            remaining -= top;
        }
        for (j, power) in self.powers.iter().enumerate() {
            if remaining >> j & 1 == 1 {
                apply(power, y, next);
            }
        }
    }

    /// The neighbourhood `rings` subdivision steps down (the corner
    /// triangle of that ring and the rings of its corners), as offsets from
    /// the limit point of c, with that limit point. All Loop masks being
    /// non-negative, the piece of surface over the ring's corner triangle
    /// lies in the convex hull of these points: the snap search bounds the
    /// region around c with them.
    pub fn ring_offsets(
        &self,
        points: &[DVec3],
        around: &[u32],
        rings: usize,
    ) -> (Vec<DVec3>, DVec3) {
        let limit = self.limit_point(points, around);
        let mut a: Vec<DVec3> = around.iter().map(|&i| points[i as usize] - limit).collect();
        let mut b = vec![DVec3::ZERO; a.len()];
        let (mut y, mut next) = (&mut a[..], &mut b[..]);
        self.push_down(&mut y, &mut next, rings);
        (y.to_vec(), limit)
    }

    /// [`SpecialPatch::ring_offsets`] one ring further down.
    pub fn next_ring(&self, offsets: &[DVec3]) -> Vec<DVec3> {
        let n = self.size;
        let d = &self.powers[0];
        (0..n)
            .map(|i| {
                d[i * n..(i + 1) * n]
                    .iter()
                    .zip(offsets)
                    .map(|(w, p)| *w * *p)
                    .sum()
            })
            .collect()
    }

    /// One subdivision step of the neighbourhood (for tests).
    #[cfg(test)]
    pub fn step(&self, points: &[DVec3]) -> Vec<DVec3> {
        let n = self.size;
        let limit: DVec3 = self.limit.iter().zip(points).map(|(w, p)| *w * *p).sum();
        let a = &self.powers[0];
        (0..n)
            .map(|i| {
                a[i * n..(i + 1) * n]
                    .iter()
                    .zip(points)
                    .map(|(w, p)| *w * (*p - limit))
                    .sum::<DVec3>()
                    + limit
            })
            .collect()
    }

    /// Bytes held by this configuration.
    pub fn memory_bytes(&self) -> usize {
        let floats = self.limit.len()
            + self.powers.iter().map(Vec::len).sum::<usize>()
            + self.band.iter().map(Vec::len).sum::<usize>()
            + self.band_bezier.iter().map(Vec::len).sum::<usize>()
            + self.tangents.iter().flatten().map(Vec::len).sum::<usize>();
        std::mem::size_of::<Self>() + floats * std::mem::size_of::<f64>()
    }

    /// The outward unit normal at c of the sector (c, p, q), exact, from the
    /// sector's tangent masks.
    pub fn normal_at_vertex(&self, points: &[DVec3], around: &[u32]) -> Option<DVec3> {
        let [t1, t2] = self.tangents.as_ref()?.each_ref().map(|row| {
            row.iter()
                .zip(around)
                .map(|(w, &i)| *w * points[i as usize])
                .sum::<DVec3>()
        });
        super::surface_normal(t1, t2)
    }

    /// The limit position of c from the positions of its neighbourhood.
    pub fn limit_point(&self, points: &[DVec3], around: &[u32]) -> DVec3 {
        self.limit
            .iter()
            .zip(around)
            .map(|(w, &i)| *w * points[i as usize])
            .sum()
    }
}

/// 15 rows of weights applied to the points of a neighbourhood, the rows
/// stored by column (the 15 weights of each point together, see
/// [`by_columns`]): each sum runs over the points in order, as a row's
/// would, and the 15 run side by side, which the compiler vectorises.
#[inline]
fn apply_columns(columns: &[f64], points: &[DVec3]) -> [DVec3; 15] {
    let (mut x, mut y, mut z) = ([0.0; 15], [0.0; 15], [0.0; 15]);
    for (w, p) in columns.chunks_exact(15).zip(points) {
        for r in 0..15 {
            x[r] += w[r] * p.x;
            y[r] += w[r] * p.y;
            z[r] += w[r] * p.z;
        }
    }
    std::array::from_fn(|r| DVec3::new(x[r], y[r], z[r]))
}

/// 15 rows of `n` weights, row-major, stored by column.
fn by_columns(rows: &[f64], n: usize) -> Vec<f64> {
    (0..n)
        .flat_map(|i| (0..15).map(move |r| rows[r * n + i]))
        .collect()
}

/// Where a point of a special corner triangle falls in the rings around
/// its special vertex: the ring (how many halvings of the parameter bring
/// it into the first), the regular sub-triangle k (1 to 3) of that ring,
/// and its parameters there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    pub rings: usize,
    pub k: usize,
    pub local: (f64, f64),
}

impl Cell {
    /// The cell of (s, t), s + t > 0; `None` closer than 2^-[`MAX_RINGS`]
    /// to the special vertex.
    pub fn locate(s: f64, t: f64) -> Option<Cell> {
        // Ring number: scale by 2 until the point lies in the first ring.
        let (mut s, mut t, mut rings) = (s, t, 0usize);
        while s + t < 0.5 {
            if rings == MAX_RINGS {
                return None;
            }
            s *= 2.0;
            t *= 2.0;
            rings += 1;
        }
        let k = if s >= 0.5 {
            1
        } else if t >= 0.5 {
            2
        } else {
            3
        };
        Some(Cell {
            rings,
            k,
            local: child(k).apply(s, t),
        })
    }

    /// Derivatives in the cell's (u, v) carried back to (s, t): through the
    /// child map and the 2^rings scaling.
    pub fn pull_back(&self, d: [DVec3; 6]) -> [DVec3; 6] {
        let scale = Affine {
            m: [
                [(self.rings as f64).exp2(), 0.0],
                [0.0, (self.rings as f64).exp2()],
            ],
            b: [0.0, 0.0],
        };
        child(self.k).after(&scale).pull_back(d)
    }
}

/// The neighbourhood N of a corner triangle (c, p, q): c, its ring, then
/// the rings of p and q, each ring counter-clockwise from a fixed neighbour
/// (boundary rings as they are, from the boundary).
pub(crate) fn neighbourhood(topo: &Topology, c: u32, p: u32, q: u32) -> Vec<u32> {
    let mut out = Vec::new();
    neighbourhood_into(topo, c, p, q, &mut out);
    out
}

/// [`neighbourhood`] into a reused buffer.
pub(crate) fn neighbourhood_into(topo: &Topology, c: u32, p: u32, q: u32, out: &mut Vec<u32>) {
    out.clear();
    out.push(c);
    for (v, from) in [(c, p), (p, c), (q, c)] {
        for x in ring_from(topo, v, from) {
            if !out.contains(&x) {
                out.push(x);
            }
        }
    }
}

/// The ring of v counter-clockwise from `from` (a boundary ring as it is).
fn ring_from(topo: &Topology, v: u32, from: u32) -> impl Iterator<Item = u32> + '_ {
    let ring = topo.ring(v as usize);
    let k = if topo.is_boundary_vertex(v as usize) {
        0
    } else {
        ring.iter().position(|&x| x == from).unwrap_or(0)
    };
    ring[k..].iter().chain(&ring[..k]).copied()
}

/// Scratch space and result of [`Key::around_into`]: the key's parts in
/// reused buffers, so that looking a configuration up allocates nothing.
#[derive(Default)]
pub struct KeyScratch {
    /// Local label of each labelled net vertex (its place in `global`).
    labels: HashMap<u32, u32>,
    global: Vec<u32>,
    fan: Vec<u32>,
    key: Key,
}

impl KeyScratch {
    /// The key last computed.
    pub fn key(&self) -> &Key {
        &self.key
    }
}

impl Key {
    /// The triangles around c and its neighbours, renumbered canonically
    /// from (c, p), with their hard edges and corner tags: everything the
    /// rules of c and its ring read, and all the patch (c, p, q) depends on.
    /// The key lands in `scratch`, whose buffers are reused: no allocation
    /// per corner once they have grown.
    pub fn around_into(
        topo: &Topology,
        features: &Features,
        [c, p, q]: [u32; 3],
        scratch: &mut KeyScratch,
    ) {
        // Label c, its ring from p, then each ring vertex's neighbours in
        // ring order from its smallest-labelled neighbour: a numbering that
        // depends on the configuration only.
        fn label(labels: &mut HashMap<u32, u32>, global: &mut Vec<u32>, g: u32) {
            labels.entry(g).or_insert_with(|| {
                global.push(g);
                global.len() as u32 - 1
            });
        }
        let KeyScratch {
            labels,
            global,
            fan,
            key,
        } = scratch;
        labels.clear();
        global.clear();
        label(labels, global, c);
        for x in ring_from(topo, c, p) {
            label(labels, global, x);
        }
        // The ring of c is global[1..inner] (its vertices are distinct).
        let inner = global.len();
        for i in 1..inner {
            let x = global[i];
            let ring = topo.ring(x as usize);
            let from = *ring
                .iter()
                .min_by_key(|&&r| labels.get(&r).copied().unwrap_or(NONE))
                .unwrap_or(&c);
            for y in ring_from(topo, x, from) {
                label(labels, global, y);
            }
        }
        let label_of = |g: u32| labels.get(&g).copied().unwrap_or(NONE);
        let is_inner = |l: u32| (l as usize) < inner;
        fan.clear();
        for &v in &global[..inner] {
            fan.extend_from_slice(topo.fan(v as usize));
        }
        fan.sort_unstable();
        fan.dedup();
        let (tris, hard, tagged) = (&mut key.tris, &mut key.hard, &mut key.tagged);
        tris.clear();
        hard.clear();
        tagged.clear();
        for &t in fan.iter() {
            let g = topo.triangles()[t as usize];
            let l = g.map(label_of);
            for (i, &e) in topo.triangle_edges()[t as usize].iter().enumerate() {
                let (a, b) = (l[i].min(l[(i + 1) % 3]), l[i].max(l[(i + 1) % 3]));
                if (is_inner(a) || is_inner(b)) && features.is_hard_edge(e as usize) {
                    hard.push([a, b]);
                }
            }
            // Rotate so the smallest label leads; then sort: canonical.
            let k = (0..3).min_by_key(|&i| l[i]).unwrap_or(0);
            tris.push([l[k], l[(k + 1) % 3], l[(k + 2) % 3]]);
        }
        tris.sort_unstable();
        hard.sort_unstable();
        hard.dedup();
        tagged.extend(
            (0..inner as u32).filter(|&l| features.is_tagged_vertex(global[l as usize] as usize)),
        );
        key.corner = [p, q].map(label_of);
    }

    /// The matrices of this configuration.
    pub(super) fn build(&self) -> SpecialPatch {
        let n0 = 1 + self.tris.iter().flatten().copied().max().unwrap_or(0) as usize;
        let topo = &Topology::new(n0, self.tris.clone())
            .expect("the local net of a manifold net is manifold");
        let mut features = Features::new(topo);
        for &[a, b] in &self.hard {
            let _ = features.tag_edge(topo, a, b);
        }
        for &v in &self.tagged {
            let _ = features.tag_vertex(v);
        }
        let [lp, lq] = self.corner;
        let (s, limit_rows) = subdivision_matrix(topo, &features, [0, lp, lq]);
        let fine_topo = topo.refined();
        let fine_features = features.refined(topo);
        let mid =
            |a: u32, b: u32| n0 as u32 + topo.find_edge(a, b).expect("edge of (c, p, q)") as u32;
        let coarse_n = neighbourhood(topo, 0, lp, lq);
        let fine_n = neighbourhood(&fine_topo, 0, mid(0, lp), mid(0, lq));
        assert_eq!(coarse_n.len(), fine_n.len(), "neighbourhoods of one shape");
        let size = coarse_n.len();
        let restrict = |row: &[f64]| restrict(row, &coarse_n);
        let a: Vec<f64> = fine_n
            .iter()
            .flat_map(|&i| restrict(&s[i as usize * n0..(i as usize + 1) * n0]))
            .collect();
        // Band patches: children 1..3 of the local (c, p, q).
        let t = self
            .tris
            .iter()
            .position(|&t| t == [0, lp, lq])
            .expect("(c, p, q) in the local net");
        let kinds = fine_features.vertex_kinds(&fine_topo);
        let band: [Vec<f64>; 3] = std::array::from_fn(|k| {
            let stencil = regular::stencil(&fine_topo, &fine_features, &kinds, 4 * t + k + 1)
                .expect("the first ring around a special vertex is regular");
            stencil
                .iter()
                .flat_map(|src| {
                    let row = |i: u32| &s[i as usize * n0..(i as usize + 1) * n0];
                    let full: Vec<f64> = match *src {
                        regular::Source::Vertex(i) => row(i).to_vec(),
                        regular::Source::Phantom { a, b, minus } => (0..n0)
                            .map(|j| row(a)[j] + row(b)[j] - row(minus)[j])
                            .collect(),
                    };
                    restrict(&full)
                })
                .collect::<Vec<f64>>()
        });
        let band = band.map(|rows| box_spline::coefficient_rows(&rows, size));
        let band_bezier = std::array::from_fn(|k| box_spline::bernstein_rows(&band[k], size));
        // Limit mask of c: the left eigenvector of A for eigenvalue 1.
        let limit = restrict(&limit_rows[0]);
        let powers = deflated_powers(a, &limit, size);
        // D^32 drives the tangent iteration: high enough to converge in a
        // few hundred steps even at valence 80, low enough that no mode of
        // the sector (eigenvalues down to 1/4) underflows between the
        // normalisations.
        let tangents = sector_tangents(
            &powers[5],
            restrict(&limit_rows[1]),
            restrict(&limit_rows[2]),
            size,
        );
        SpecialPatch {
            size,
            limit,
            powers,
            band: band.map(|rows| by_columns(&rows, size)),
            band_bezier: band_bezier.map(|rows| by_columns(&rows, size)),
            tangents,
        }
    }
}

/// S, one subdivision step of the local net as a row-major matrix (fine
/// vertices by coarse ones), and the limit masks of `corners` (c, p and q;
/// rows of the limit operator): both found by subdividing the basis
/// vectors, three at a time (x, y, z).
fn subdivision_matrix(
    topo: &Topology,
    features: &Features,
    corners: [u32; 3],
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let n0 = topo.num_vertices();
    let fine = topo.num_vertices() + topo.num_edges();
    let mut s = vec![0.0; fine * n0];
    let mut limit_rows = vec![vec![0.0; n0]; 3];
    for first in (0..n0).step_by(3) {
        let basis: Vec<DVec3> = (0..n0)
            .map(|j| {
                let mut e = DVec3::ZERO;
                if j >= first && j < first + 3 {
                    e[j - first] = 1.0;
                }
                e
            })
            .collect();
        for (i, x) in subdivide_points(topo, features, &basis).iter().enumerate() {
            for d in 0..3 {
                if first + d < n0 {
                    s[i * n0 + first + d] = x[d];
                }
            }
        }
        let limits = limit_positions(topo, features, &basis);
        for (row, v) in limit_rows.iter_mut().zip(corners) {
            for d in 0..3 {
                if first + d < n0 {
                    row[first + d] = limits[v as usize][d];
                }
            }
        }
    }
    (s, limit_rows)
}

/// A row of S restricted to the neighbourhood `coarse_n`; the rules never
/// read outside it (checked).
fn restrict(row: &[f64], coarse_n: &[u32]) -> Vec<f64> {
    let picked: Vec<f64> = coarse_n.iter().map(|&j| row[j as usize]).collect();
    let outside =
        row.iter().map(|w| w.abs()).sum::<f64>() - picked.iter().map(|w| w.abs()).sum::<f64>();
    assert!(
        outside.abs() < 1e-12,
        "a rule reads outside the neighbourhood {coarse_n:?}: {row:?}"
    );
    picked
}

/// D = A − 1·limit (A deflated of its eigenvalue 1) and its powers D^(2^j)
/// for j below [`POWERS`], by repeated squaring.
fn deflated_powers(a: Vec<f64>, limit: &[f64], size: usize) -> Vec<Vec<f64>> {
    let mut deflated = a;
    for i in 0..size {
        for j in 0..size {
            deflated[i * size + j] -= limit[j];
        }
    }
    let mut powers = vec![deflated];
    for j in 1..POWERS {
        let last = &powers[j - 1];
        powers.push(matmul(last, last, size));
    }
    powers
}

/// Tangent masks of the sector (c, p, q) at c: a basis of the row space that
/// the chords from c's limit to the limits of p and q, pushed n levels down,
/// tend to as n grows. Orthogonal iteration with a high power D^m of the
/// deflated matrix; QR with a positive diagonal keeps the orientation of
/// (chord to p, chord to q), so t₁ × t₂ is the outward normal. Exact to
/// round-off: each step shrinks the error by (λ₃/λ₂)^m.
///
/// At high valences λ₃/λ₂ is close to one (1 − 1.7e-4 at valence 334, a
/// CAD sphere's pole): D^32 would need thousands of steps of a dense
/// product the size of the neighbourhood. So when D^32 has not settled in
/// [`STEPS`] steps (every valence up to about 80 settles in a few hundred),
/// the basis is brought near its limit (a change below 1e-12) by powers
/// squared in turn (each scaled by a power of two, which is exact, to keep
/// its modes in range: those far below λ₂ underflow, which only speeds the
/// iteration), then settled by D^32 itself, whose round-off is lower than
/// a high power's. Measured at valence 334: settled in 0.3 s, where D^32
/// alone ran its 4096 steps in 1.1 s without settling (and no normal was
/// claimed there).
/// `None` when the chords collapse onto one line or the iteration does not
/// settle: then no normal is claimed.
fn sector_tangents(
    power: &[f64],
    to_p: Vec<f64>,
    to_q: Vec<f64>,
    n: usize,
) -> Option<[Vec<f64>; 2]> {
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let orthonormal = |a: Vec<f64>, b: Vec<f64>| -> Option<[Vec<f64>; 2]> {
        let na = dot(&a, &a).sqrt();
        let a: Vec<f64> = a.iter().map(|x| x / na).collect();
        let proj = dot(&a, &b);
        let b: Vec<f64> = b.iter().zip(&a).map(|(y, x)| y - proj * x).collect();
        let nb = dot(&b, &b).sqrt();
        (na > 1e-280 && nb > 1e-12 * na).then(|| [a, b.iter().map(|y| y / nb).collect()])
    };
    // Up to `steps` steps with `power`: whether the change fell below
    // `settled`.
    let iterate = |power: &[f64], basis: &mut [Vec<f64>; 2], steps: usize, settled: f64| {
        let times = |row: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|j| (0..n).map(|i| row[i] * power[i * n + j]).sum())
                .collect()
        };
        for _ in 0..steps {
            let next = orthonormal(times(&basis[0]), times(&basis[1]))?;
            let change = next[0]
                .iter()
                .zip(&basis[0])
                .chain(next[1].iter().zip(&basis[1]))
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max);
            *basis = next;
            if change < settled {
                return Some(true);
            }
        }
        Some(false)
    };
    let mut basis = orthonormal(to_p, to_q)?;
    if iterate(power, &mut basis, STEPS, 1e-15)? {
        return Some(basis);
    }
    let mut high = power.to_vec();
    for _ in 0..MAX_SQUARINGS {
        high = matmul(&high, &high, n);
        let largest = high.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
        if largest == 0.0 || !largest.is_finite() {
            return None;
        }
        let scale = (-largest.log2().floor()).exp2();
        high.iter_mut().for_each(|x| *x *= scale);
        if iterate(&high, &mut basis, 8, 1e-12)? {
            break;
        }
    }
    iterate(power, &mut basis, STEPS, 1e-15)?.then_some(basis)
}

/// Steps of D^32 at most, before squaring and after.
const STEPS: usize = 512;

/// Squarings of the power at most (up to D^(32·2¹²), eight steps each):
/// enough for λ₃/λ₂ up to about 1 − 3e-5 (a smooth valence of about 900).
const MAX_SQUARINGS: usize = 12;

/// The product of two row-major n × n matrices. Written out rather than
/// faer's: the evaluator's results must stay bit for bit what they are
/// (tests/eval_bits.rs), and its powers are made with this.
fn matmul(a: &[f64], b: &[f64], n: usize) -> Vec<f64> {
    let mut c = vec![0.0; n * n];
    for i in 0..n {
        for k in 0..n {
            let aik = a[i * n + k];
            if aik != 0.0 {
                for j in 0..n {
                    c[i * n + j] += aik * b[k * n + j];
                }
            }
        }
    }
    c
}
