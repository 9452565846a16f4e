//! Distances and curvature errors of a surrogate against a shape's true
//! surface, on a lattice of points in every control triangle.
//!
//! The surrogate is only evaluated ([`Surface::point`],
//! [`Surface::curvature`]); the reference is the shape's closed form
//! ([`Analytic`]), so what is measured and what measures share no code.

use super::Analytic;
use crate::{Result, Surface};
use glam::DVec3;
use rayon::prelude::*;

/// Largest and mean value over the samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deviation {
    pub max: f64,
    pub mean: f64,
    /// How many samples were measured.
    pub samples: usize,
}

impl Deviation {
    fn of(values: impl Iterator<Item = f64>) -> Deviation {
        let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0usize);
        for v in values {
            max = max.max(v);
            sum += v;
            n += 1;
        }
        Deviation {
            max,
            mean: if n > 0 { sum / n as f64 } else { 0.0 },
            samples: n,
        }
    }
}

/// The points (v, w) = (i/n, j/n), i + j ≤ n, of a triangle: corners,
/// edges and inside ((n + 1)(n + 2)/2 of them; n = 6 gives 28).
pub fn lattice(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity((n + 1) * (n + 2) / 2);
    for i in 0..=n {
        for j in 0..=n - i {
            out.push((i as f64 / n as f64, j as f64 / n as f64));
        }
    }
    out
}

/// Distance from the surrogate `surface` to the true surface of `shape`,
/// relative to the shape's diagonal, sampled on `lattice(n)` of every
/// control triangle. One-sided: how far the surrogate strays, not how much
/// of the true surface it misses.
pub fn surrogate_distance(shape: &dyn Analytic, surface: &Surface, n: usize) -> Result<Deviation> {
    let points = lattice(n);
    let per_tri: Vec<Vec<f64>> = (0..surface.net().triangles().len())
        .into_par_iter()
        .map(|t| {
            points
                .iter()
                .map(|&(v, w)| Ok(shape.distance(surface.point(t, v, w)?)))
                .collect::<Result<Vec<f64>>>()
        })
        .collect::<Result<_>>()?;
    let diagonal = shape.diagonal();
    Ok(Deviation::of(
        per_tri.into_iter().flatten().map(|d| d / diagonal),
    ))
}

/// Distance from the flat facets of `points`/`tris` to the true surface of
/// `shape`, relative to its diagonal, sampled as [`surrogate_distance`]
/// samples a surface.
pub fn facet_distance(
    shape: &dyn Analytic,
    points: &[DVec3],
    tris: &[[u32; 3]],
    n: usize,
) -> Deviation {
    let lattice = lattice(n);
    let diagonal = shape.diagonal();
    let per_tri: Vec<Vec<f64>> = tris
        .par_iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| points[i as usize]);
            lattice
                .iter()
                .map(|&(v, w)| shape.distance((1.0 - v - w) * a + v * b + w * c) / diagonal)
                .collect()
        })
        .collect();
    Deviation::of(per_tri.into_iter().flatten())
}

/// Relative error of the surrogate's mean curvature, |H − H_true| / |H_true|,
/// on `lattice(n)` of every control triangle, where the surrogate has a
/// curvature (not exactly at a special vertex) and the true surface is
/// farther than `margin` (relative to the diagonal) from its features and
/// blend seams and not on a blend ([`Analytic::smooth_margin`]), and its
/// mean curvature is not zero. `None` when no sample qualifies.
pub fn curvature_error(
    shape: &dyn Analytic,
    surface: &Surface,
    n: usize,
    margin: f64,
) -> Result<Option<Deviation>> {
    let points = lattice(n);
    let limit = margin * shape.diagonal();
    let per_tri: Vec<Vec<f64>> = (0..surface.net().triangles().len())
        .into_par_iter()
        .map(|t| {
            let mut out = Vec::new();
            for &(v, w) in &points {
                let k = surface.curvature(t, v, w)?;
                if !k.reliable {
                    continue;
                }
                let x = surface.point(t, v, w)?;
                if shape.smooth_margin(x) <= limit {
                    continue;
                }
                match shape.mean_curvature_at(x) {
                    Some(h) if h.abs() > 1e-12 => out.push((k.mean - h).abs() / h.abs()),
                    _ => {}
                }
            }
            Ok(out)
        })
        .collect::<Result<_>>()?;
    let d = Deviation::of(per_tri.into_iter().flatten());
    Ok((d.samples > 0).then_some(d))
}
