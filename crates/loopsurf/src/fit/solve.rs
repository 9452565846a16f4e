//! One least-squares solve: data rows A with targets b, the fairness
//! matrix FᵀF weighted by λ (on the displacement from a reference net), and a proximal weight μ towards the current
//! control points (it keeps the system definite where neither data nor
//! fairness reaches, a corner without data, and is too small to bias the
//! fit: 1e-13 of the data weight).
//!
//! The normal equations (AᵀA + λFᵀF + μI) x = Aᵀb + λFᵀF x_ref + μx₀ are symmetric
//! positive definite and sparse (a row couples the two-ring of one control
//! triangle), so faer's sparse Cholesky factors them once for the three
//! coordinates; its fill-reducing ordering keeps the cost near linear in
//! the net for surface meshes.

use super::rows::Row;
use crate::error::{Error, Result};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use glam::DVec3;

/// The proximal weight, per control point, relative to one data row.
pub const PROXIMAL: f64 = 1e-13;

/// Solves for the control points; `current` gives their number and the
/// proximal anchor; the fairness term measures x − `reference`.
pub fn solve(
    rows: &[&Row],
    targets: &[DVec3],
    fairness: &SparseColMat<usize, f64>,
    lambda: f64,
    reference: &[DVec3],
    current: &[DVec3],
) -> Result<Vec<DVec3>> {
    let (m, n) = (rows.len(), current.len());
    let mut a = Vec::new();
    let mut at = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        for &(j, w) in row.iter() {
            a.push(Triplet::new(i, j as usize, w));
            at.push(Triplet::new(j as usize, i, w));
        }
    }
    let build = |r, c, t: &[Triplet<usize, usize, f64>]| {
        SparseColMat::<usize, f64>::try_new_from_triplets(r, c, t)
            .map_err(|e| Error::InvalidArgument(format!("fit: data rows: {e:?}")))
    };
    let (a, at) = (build(m, n, &a)?, build(n, m, &at)?);
    let ata = faer::sparse::linalg::matmul::sparse_sparse_matmul(
        at.as_ref(),
        a.as_ref(),
        1.0,
        faer::Par::Seq,
    )
    .map_err(|e| Error::InvalidArgument(format!("fit: normal equations: {e:?}")))?;
    let mut triplets = Vec::with_capacity(ata.compute_nnz() + fairness.compute_nnz() + n);
    let mut push = |mat: &SparseColMat<usize, f64>, scale: f64| {
        for j in 0..mat.ncols() {
            let range = mat.col_range(j);
            let rows = &mat.row_idx()[range.clone()];
            let vals = &mat.val()[range];
            for (&i, &v) in rows.iter().zip(vals) {
                triplets.push(Triplet::new(i, j, scale * v));
            }
        }
    };
    push(&ata, 1.0);
    push(fairness, lambda);
    triplets.extend((0..n).map(|i| Triplet::new(i, i, PROXIMAL)));
    let normal = build(n, n, &triplets)?;
    let llt = normal.sp_cholesky(faer::Side::Lower).map_err(|e| {
        Error::InvalidArgument(format!(
            "fit: the normal equations are not definite ({e:?})"
        ))
    })?;
    let mut rhs = faer::Mat::<f64>::from_fn(n, 3, |i, k| PROXIMAL * current[i][k]);
    for (row, t) in rows.iter().zip(targets) {
        for &(j, w) in row.iter() {
            for k in 0..3 {
                rhs[(j as usize, k)] += w * t[k];
            }
        }
    }
    // λ FᵀF x_ref, so that the fairness term measures x − x_ref.
    for (j, r) in reference.iter().enumerate() {
        let range = fairness.col_range(j);
        let rows = &fairness.row_idx()[range.clone()];
        let vals = &fairness.val()[range];
        for (&i, &v) in rows.iter().zip(vals) {
            for k in 0..3 {
                rhs[(i, k)] += lambda * v * r[k];
            }
        }
    }
    llt.solve_in_place(rhs.as_mut());
    let x: Vec<DVec3> = (0..n)
        .map(|i| DVec3::new(rhs[(i, 0)], rhs[(i, 1)], rhs[(i, 2)]))
        .collect();
    if x.iter().any(|p| !p.is_finite()) {
        return Err(Error::InvalidArgument(
            "fit: the solve gave non-finite control points".into(),
        ));
    }
    Ok(x)
}
