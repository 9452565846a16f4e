//! Interpolating surfaces (Persson, Aftosmis & Haines §3.3): the Loop surface through the
//! original points.
//!
//! [`solve`] finds control points x′ with S∞ x′ = x, where S∞ is the limit
//! operator (every vertex's limit mask: smooth, dart, crease, corner), so
//! the smooth Loop surface of x′ passes through every original point. S∞ is
//! sparse (one row per vertex, its one-ring) and nonsymmetric (the masks
//! of neighbouring vertices of different valence differ), so it is solved
//! with faer's sparse LU: a direct method, exact to round-off in one
//! factorisation for all three coordinates, with no convergence to tune
//! (the valence-3 and dart rows are not diagonally dominant, which rules
//! out plain Jacobi or Gauss–Seidel). One step of iterative refinement
//! brings the residual down to round-off.
//!
//! The solved net can wiggle where the original one is irregular — the
//! Persson, Aftosmis & Haines's Figs. 9–10 show cusps — so [`crate::fairness`] measures it.
//! This module works on nets only, below [`crate::surface`], whose `Solve`
//! mode calls [`solve`].

use crate::error::{Error, Result};
use crate::net::{limit_mask_entries, limit_positions, ControlNet};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use glam::DVec3;

/// Control points whose limit surface passes through the points of `net`
/// (same connectivity and hard features). The residual |S∞ x′ − x| is at
/// round-off: below 1e-12 of the bounding-box diagonal, or an error.
pub fn solve(net: &ControlNet) -> Result<ControlNet> {
    let (topo, features) = (net.topology(), net.features());
    let n = net.points().len();
    let triplets: Vec<Triplet<usize, usize, f64>> = limit_mask_entries(topo, features)
        .into_iter()
        .map(|(r, c, w)| Triplet::new(r as usize, c as usize, w))
        .collect();
    let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| Error::InvalidArgument(format!("limit operator: {e:?}")))?;
    let lu = matrix.sp_lu().map_err(|e| {
        Error::InvalidArgument(format!(
            "the limit operator of this net is singular ({e:?}): no interpolating control net exists"
        ))
    })?;
    let target = net.points();
    let mut solved = vec![DVec3::ZERO; n];
    let mut residual: Vec<DVec3> = target.to_vec();
    let diagonal = net.bbox_diagonal();
    let max_residual = |r: &[DVec3]| r.iter().map(|d| d.length()).fold(0.0, f64::max);
    // Solve, then refine: x′ += S∞⁻¹ (x − S∞ x′).
    for _ in 0..3 {
        let mut rhs = faer::Mat::<f64>::from_fn(n, 3, |i, j| residual[i][j]);
        lu.solve_in_place(rhs.as_mut());
        for (i, x) in solved.iter_mut().enumerate() {
            *x += DVec3::new(rhs[(i, 0)], rhs[(i, 1)], rhs[(i, 2)]);
        }
        let limits = limit_positions(topo, features, &solved);
        residual = target.iter().zip(&limits).map(|(&x, &l)| x - l).collect();
        if max_residual(&residual) <= 1e-14 * diagonal {
            break;
        }
    }
    let worst = max_residual(&residual);
    if worst.is_nan() || worst > 1e-12 * diagonal {
        return Err(Error::InvalidArgument(format!(
            "the limit operator of this net is too ill-conditioned: residual {:.3e} of the diagonal",
            worst / diagonal
        )));
    }
    Ok(net.with_points(solved))
}
