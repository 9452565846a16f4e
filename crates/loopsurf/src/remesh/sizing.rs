//! The size field: a target edge length per vertex, uniform or from the
//! exact principal curvatures, graded so that neighbouring sizes differ by
//! at most the gradation factor per edge.
//!
//! A circle of radius R = 1/κ is met within ε by chords of length
//! √(8εR); an equilateral triangle of side L on a sphere of that radius
//! deviates by L²κ/6 at its centroid. Edges may reach 4/3 of their target
//! before they are split, so the curvature size is √(6ε/κ)·3/4 =
//! √(3.375ε/κ), taking κ as the largest principal curvature sampled over
//! a control triangle away from its corners and, on its hard sides, also
//! the curves' own curvature. Sizes live on the control triangles, in
//! parameter space, so they do not drift as the vertices move; each vertex
//! takes its own triangle's, or the size of the curvature at the vertex
//! itself where that is smaller (next to an irregular vertex, where the
//! curvature grows without bound), down to a quarter of the triangle's
//! on a patch that folds over itself.
//! The chord error is then measured, not trusted (see the module above),
//! and where it is exceeded the control triangles involved shrink their
//! size.

use super::connectivity::Connectivity;
use super::vertices::Vertex;
use crate::parameters::INTERIOR_SAMPLES;
use crate::surface::Surface;
use glam::DVec3;
use rayon::prelude::*;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::sync::OnceLock;

/// Size² · κ / ε for an equilateral triangle at 4/3 of its target size
/// to meet the tolerance at its centroid (see the module doc).
const CHORD_FACTOR: f64 = 6.0 * 9.0 / 16.0;

/// On a patch that folds over itself ([`crate::folds::is_folded`]), a vertex's
/// own curvature may make its size at most this factor smaller than its
/// control triangle's. There the curvature says nothing of the chord
/// error: in anchor.off's flat fans around vertices of valence 34, 22 and
/// 20 the surface wrinkles within 4e-7 of its plane, its normal flipping,
/// with curvatures of 300 (model units; the diagonal is 1.46). Unbounded, the
/// sizes ran away towards those vertices (42 434 triangles, 19% of them
/// below 20°, in 9.6 s); bounded on its folded patches, 17 274 triangles,
/// 0.23%, within the tolerance. Elsewhere the curvature at a vertex is
/// real and refines without this bound: bounded everywhere, anchor came
/// to 0.19% below 20° but joint.off grew from 12 260 to 1.1 million
/// triangles, its chord error missed next to irregular vertices and whole
/// control triangles shrunk instead.
const VERTEX_REFINEMENT: f64 = 4.0;

/// How the target edge length is set.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Sizing {
    /// One length everywhere.
    Uniform(f64),
    /// Per control triangle: √(3.375ε/κ) within [`floor`, cap]; graded by
    /// `gradation` over the mesh.
    Curvature {
        per_triangle: Vec<f64>,
        tolerance: f64,
        floor: f64,
        gradation: f64,
        /// Per control triangle, once asked: whether its patch folds
        /// ([`crate::folds::is_folded`]; see [`VERTEX_REFINEMENT`]).
        folded: Vec<OnceLock<bool>>,
    },
}

/// The larger principal curvature at (t, v, w), 0 where it is undefined
/// (at a special vertex).
fn curvature_at(surface: &Surface, t: usize, v: f64, w: f64) -> f64 {
    match surface.curvature(t, v, w) {
        Ok(c) if c.reliable => c.k1.abs().max(c.k2.abs()),
        _ => 0.0,
    }
}

/// A curve moving slower than this share of its chord per unit of t has
/// stopped dead (see [`largest_curvature`]).
const STOPPED: f64 = 0.01;

/// The largest curvature sampled in control triangle t: the principal
/// curvatures at interior samples (none exactly at a corner, where a
/// special vertex has none), and on each hard side the curve's own
/// curvature at nine points. Sampling over the whole triangle, not at the
/// mesh vertices, sees a bend that falls between vertices (a hairpin of a
/// boundary curve inside one edge). A curve sample where the curve has
/// stopped dead is left out, as the corners are: where a crease chain
/// turns back on itself the curve stops at the chain vertex (a cusp, its
/// curvature unbounded: mpi.off at 40°, speed 2.4e-3 against a chord of
/// 2.7, curvature 1.4e6 per unit at its vertex 39), and that one sample
/// shrank every triangle beside it to the size floor, asking for 8.6
/// million triangles on flat faces. (Leaving out every curve end instead
/// missed the tolerance on elephant-with-holes and femur, whose boundary
/// curves bend most at their chain vertices.)
fn largest_curvature(surface: &Surface, t: usize) -> f64 {
    let mut k: f64 = 0.0;
    // Samples away from the corners: next to an irregular corner the
    // curvature grows without bound, and one such sample would shrink the
    // whole triangle; the vertices' own curvature refines there instead.
    for (v, w) in INTERIOR_SAMPLES {
        if v.min(w).min(1.0 - v - w) < 0.1 {
            continue;
        }
        k = k.max(curvature_at(surface, t, v, w));
    }
    let model = surface.model();
    let topo = surface.net().topology();
    for &e in &topo.triangle_edges()[t] {
        let Some(curve) = model.curve_of_edge(e as usize) else {
            continue;
        };
        let c = &model.curves()[curve as usize];
        let Some(j) = c.edges.iter().position(|&x| x == e) else {
            continue;
        };
        let samples: Vec<_> = (0..=8)
            .filter_map(|i| {
                crate::curve::LimitCurve::new(surface, curve as usize)
                    .and_then(|c| c.eval(j as f64 + i as f64 / 8.0))
                    .ok()
            })
            .collect();
        let (Some(first), Some(last)) = (samples.first(), samples.last()) else {
            continue;
        };
        // Over one control edge t runs through 1: the speed is about the
        // chord's length, except where the curve stops dead.
        let stopped = STOPPED * first.x.distance(last.x);
        for x in &samples {
            let speed = x.dx.length();
            if !x.at_special_vertex && speed > stopped {
                k = k.max(x.dx.cross(x.ddx).length() / (speed * speed * speed));
            }
        }
    }
    k
}

impl Sizing {
    /// Curvature sizing under the chord tolerance `tolerance` (model
    /// units), sizes within [`floor`, `cap`].
    pub fn curvature(
        surface: &Surface,
        tolerance: f64,
        cap: f64,
        floor: f64,
        gradation: f64,
    ) -> Sizing {
        let per_triangle: Vec<f64> = (0..surface.net().triangles().len())
            .into_par_iter()
            .map(|t| {
                let k = largest_curvature(surface, t);
                if k > 0.0 {
                    (CHORD_FACTOR * tolerance / k).sqrt().clamp(floor, cap)
                } else {
                    cap
                }
            })
            .collect();
        Sizing::Curvature {
            folded: (0..per_triangle.len()).map(|_| OnceLock::new()).collect(),
            per_triangle,
            tolerance,
            floor,
            gradation,
        }
    }

    /// The largest size of the control triangles `keep` lets through
    /// (at most the cap of curvature sizing).
    pub fn largest(&self, keep: impl Fn(usize) -> bool) -> f64 {
        match self {
            Sizing::Uniform(h) => *h,
            Sizing::Curvature { per_triangle, .. } => per_triangle
                .iter()
                .enumerate()
                .filter(|&(t, _)| keep(t))
                .map(|(_, &h)| h)
                .fold(0.0, f64::max),
        }
    }

    /// Control triangle t's size, before grading.
    pub fn of_triangle(&self, t: usize) -> f64 {
        match self {
            Sizing::Uniform(h) => *h,
            Sizing::Curvature { per_triangle, .. } => per_triangle[t],
        }
    }

    /// The chord tolerance that curvature sizing sizes under (model
    /// units); `None` for a uniform size.
    pub fn adapts_to(&self) -> Option<f64> {
        match self {
            Sizing::Uniform(_) => None,
            Sizing::Curvature { tolerance, .. } => Some(*tolerance),
        }
    }

    /// The target size of every vertex (dead ones included, ignored):
    /// its control triangle's, times that triangle's `shrink` factor (where
    /// the chord error was too large), at most its `bound`, graded.
    pub fn sizes(
        &self,
        surface: &Surface,
        mesh: &Connectivity,
        vertices: &[Vertex],
        shrink: &[f64],
        bound: &[f64],
    ) -> Vec<f64> {
        match self {
            // No tolerance: nothing shrinks.
            Sizing::Uniform(h) => vec![*h; vertices.len()],
            Sizing::Curvature {
                per_triangle,
                tolerance,
                floor,
                gradation,
                folded,
            } => {
                let mut size: Vec<f64> = vertices
                    .par_iter()
                    .zip(bound)
                    .map(|(v, &bound)| {
                        let t = v.at.tri as usize;
                        let k = curvature_at(surface, t, v.at.v, v.at.w);
                        let own = (CHORD_FACTOR * tolerance / k).sqrt();
                        let least = per_triangle[t] / VERTEX_REFINEMENT;
                        let own = if own < least
                            && *folded[t].get_or_init(|| crate::folds::is_folded(surface, t))
                        {
                            least
                        } else {
                            own
                        };
                        (per_triangle[t].min(own) * shrink[t])
                            .max(*floor)
                            .min(bound)
                    })
                    .collect();
                grade(mesh, vertices, &mut size, *gradation);
                smooth_down(mesh, &mut size);
                size
            }
        }
    }
}

/// Rounds of [`smooth_down`].
const SMOOTHING: usize = 3;

/// Lowers each size to the mean of its neighbours' where that is smaller,
/// a few times: grading alone leaves a size field with a kink at every
/// control triangle's border (each has its own size), and triangles
/// across a kink cannot all be equilateral. Only lowering keeps the chord
/// tolerance.
fn smooth_down(mesh: &Connectivity, size: &mut [f64]) {
    let mut ring = Vec::new();
    for _ in 0..SMOOTHING {
        let old = size.to_vec();
        for v in 0..size.len() as u32 {
            if !mesh.is_vertex_alive(v) {
                continue;
            }
            mesh.neighbours(v, &mut ring);
            if !ring.is_empty() {
                let mean = ring.iter().map(|&u| old[u as usize]).sum::<f64>() / ring.len() as f64;
                size[v as usize] = size[v as usize].min(mean);
            }
        }
    }
}

/// Limits sizes along edges: h(v) ≤ h(u) + (g − 1)|uv|, smallest first
/// (Dijkstra over the mesh), so a size grows by at most the factor g over
/// one edge of its own length.
fn grade(mesh: &Connectivity, vertices: &[Vertex], size: &mut [f64], gradation: f64) {
    let slope = gradation - 1.0;
    let mut heap: BinaryHeap<Reverse<(u64, u32)>> = (0..vertices.len() as u32)
        .filter(|&v| mesh.is_vertex_alive(v))
        .map(|v| Reverse((size[v as usize].to_bits(), v)))
        .collect();
    let mut ring = Vec::new();
    while let Some(Reverse((bits, u))) = heap.pop() {
        let h = f64::from_bits(bits);
        if h > size[u as usize] {
            continue;
        }
        let x: DVec3 = vertices[u as usize].x;
        mesh.neighbours(u, &mut ring);
        for &v in &ring {
            let limit = h + slope * x.distance(vertices[v as usize].x);
            if limit < size[v as usize] {
                size[v as usize] = limit;
                heap.push(Reverse((limit.to_bits(), v)));
            }
        }
    }
}
