//! One least-squares solve: data rows A with targets b and weights W, the
//! fairness matrix FᵀF weighted by λ (on the displacement from a reference
//! net), and a proximal weight μ towards the current control points (it
//! keeps the system definite where neither data nor fairness reaches, a
//! corner without data, and is too small to bias the fit: 1e-13 of the
//! data weight).
//!
//! The normal equations (AᵀWA + λFᵀF + μI) x = AᵀWb + λFᵀF x_ref + μx₀ are
//! symmetric positive definite and sparse (a row couples the two-ring of
//! one control triangle), so faer's sparse Cholesky factors them once for
//! the three coordinates; its fill-reducing ordering keeps the cost near
//! linear in the net for surface meshes. The rows come sorted by control
//! vertex, so A is laid out row by row as it stands and every sum is a
//! merge of sorted columns: nothing is sorted here.

use super::rows::Row;
use crate::error::{Error, Result};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, SparseRowMat, SymbolicSparseColMat, SymbolicSparseRowMat};
use glam::DVec3;

/// The proximal weight, per control point, relative to one data row.
pub const PROXIMAL: f64 = 1e-13;

/// Solves for the control points; `current` gives their number and the
/// proximal anchor; the fairness term measures x − `reference`. Each row
/// lists its control vertices in increasing order, each once, and counts
/// `weights` times its own.
pub fn solve(
    rows: &[&Row],
    targets: &[DVec3],
    weights: &[f64],
    fairness: &SparseColMat<usize, f64>,
    lambda: f64,
    reference: &[DVec3],
    current: &[DVec3],
) -> Result<Vec<DVec3>> {
    let (m, n) = (rows.len(), current.len());
    let mut row_ptr = Vec::with_capacity(m + 1);
    let mut col_idx = Vec::new();
    let mut val = Vec::new();
    row_ptr.push(0);
    for (row, &weight) in rows.iter().zip(weights) {
        let scale = weight.sqrt();
        for &(j, w) in row.iter() {
            col_idx.push(j as usize);
            val.push(scale * w);
        }
        row_ptr.push(col_idx.len());
    }
    let a = SparseRowMat::new(
        SymbolicSparseRowMat::new_checked(m, n, row_ptr, None, col_idx),
        val,
    );
    let a_by_columns = a
        .as_ref()
        .to_col_major()
        .map_err(|e| failed("data rows", e))?;
    let ata = faer::sparse::linalg::matmul::sparse_sparse_matmul(
        a.as_ref().transpose(),
        a_by_columns.as_ref(),
        1.0,
        faer::Par::Seq,
    )
    .map_err(|e| failed("normal equations", e))?;
    let sum = |x: Option<&f64>, y: Option<&f64>, scale: f64| {
        x.copied().unwrap_or(0.0) + scale * y.copied().unwrap_or(0.0)
    };
    let proximal = SparseColMat::new(
        SymbolicSparseColMat::new_checked(n, n, (0..=n).collect(), None, (0..n).collect()),
        vec![PROXIMAL; n],
    );
    let normal =
        faer::sparse::ops::binary_op(ata.as_ref(), fairness.as_ref(), |x, y| sum(x, y, lambda))
            .and_then(|m| {
                faer::sparse::ops::binary_op(m.as_ref(), proximal.as_ref(), |x, y| sum(x, y, 1.0))
            })
            .map_err(|e| failed("normal equations", e))?;
    let llt = normal
        .sp_cholesky(faer::Side::Lower)
        .map_err(|e| failed("the normal equations are not definite", e))?;
    let mut rhs = faer::Mat::<f64>::from_fn(n, 3, |i, k| PROXIMAL * current[i][k]);
    for ((row, t), &weight) in rows.iter().zip(targets).zip(weights) {
        for &(j, w) in row.iter() {
            for k in 0..3 {
                rhs[(j as usize, k)] += weight * w * t[k];
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

/// A solve that could not be set up or factored, and why.
fn failed(what: &str, e: impl std::fmt::Debug) -> Error {
    Error::InvalidArgument(format!("fit: {what} ({e:?})"))
}
