//! Interpolating surfaces (seed 000 §3.3): the Loop surface through the
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
//! paper's Figs. 9–10 show cusps — so [`fairness`] measures it.

use crate::error::{Error, Result};
use crate::net::{limit_mask_entries, limit_positions, ControlNet};
use crate::surface::{Surface, SurfaceMode};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use glam::DVec3;

/// The fairness report warns when a control point moves by more than this
/// fraction of the mean length of its edges.
pub const DISPLACEMENT_WARNING: f64 = 1.0;
/// The fairness report warns when the normal at an original point turns by
/// more than this many degrees between the two surfaces.
pub const NORMAL_WARNING_DEGREES: f64 = 15.0;

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

/// How far the interpolating surface departs from the approximating one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FairnessReport {
    /// max |S∞ x′ − x| over the vertices, relative to the bounding-box diagonal.
    pub residual: f64,
    /// max |x′ − x| / (mean length of the vertex's edges in the original net).
    pub max_displacement: f64,
    /// The vertex where it occurs.
    pub max_displacement_vertex: usize,
    /// Largest angle, in degrees, between the normals of the approximating
    /// surface (at the limit point of a vertex) and of the interpolating one
    /// (at the original point), over every vertex with a tangent plane, one
    /// sector per vertex at creases and corners.
    pub max_normal_change: f64,
    /// The vertex where it occurs.
    pub max_normal_change_vertex: usize,
}

impl FairnessReport {
    /// One line per threshold exceeded ([`DISPLACEMENT_WARNING`],
    /// [`NORMAL_WARNING_DEGREES`]); empty when the solved net looks fair.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.max_displacement > DISPLACEMENT_WARNING {
            out.push(format!(
                "vertex {} moves by {:.2} times its mean edge length (warning above {DISPLACEMENT_WARNING}): the interpolating surface may wiggle or cusp there",
                self.max_displacement_vertex, self.max_displacement
            ));
        }
        if self.max_normal_change > NORMAL_WARNING_DEGREES {
            out.push(format!(
                "the normal at vertex {} turns by {:.1}° (warning above {NORMAL_WARNING_DEGREES}°): the interpolating surface may fold there",
                self.max_normal_change_vertex, self.max_normal_change
            ));
        }
        out
    }
}

/// Compares the approximating surface of `original` with the interpolating
/// surface of `solved` (the output of [`solve`] for `original`).
pub fn fairness(original: &ControlNet, solved: &ControlNet) -> Result<FairnessReport> {
    if solved.triangles() != original.triangles() {
        return Err(Error::InvalidArgument(
            "fairness: the solved net must have the original's triangles".into(),
        ));
    }
    let topo = original.topology();
    let (x, x1) = (original.points(), solved.points());
    let limits = solved.limit_points();
    let diagonal = original.bbox_diagonal();
    let residual = x
        .iter()
        .zip(&limits)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0, f64::max);
    let mut report = FairnessReport {
        residual: residual / diagonal,
        max_displacement: 0.0,
        max_displacement_vertex: 0,
        max_normal_change: 0.0,
        max_normal_change_vertex: 0,
    };
    for v in 0..x.len() {
        let ring = topo.ring(v);
        if ring.is_empty() {
            continue; // an unreferenced vertex: fixed, and no edge to compare with
        }
        let mean_edge = ring
            .iter()
            .map(|&u| (x[u as usize] - x[v]).length())
            .sum::<f64>()
            / ring.len() as f64;
        let moved = (x1[v] - x[v]).length() / mean_edge;
        if moved > report.max_displacement {
            report.max_displacement = moved;
            report.max_displacement_vertex = v;
        }
    }
    let before = Surface::from_net(original.clone(), SurfaceMode::Approximating)?;
    let after = Surface::from_net(solved.clone(), SurfaceMode::Solve)?;
    for (v, (tri, [cv, cw])) in corner_parameters(original).into_iter().enumerate() {
        let (Ok(a), Ok(b)) = (before.normal(tri, cv, cw), after.normal(tri, cv, cw)) else {
            continue; // no tangent plane (a corner vertex's sector may have none)
        };
        let angle = a.angle_between(b).to_degrees();
        if angle > report.max_normal_change {
            report.max_normal_change = angle;
            report.max_normal_change_vertex = v;
        }
    }
    Ok(report)
}

/// For every vertex, one triangle that has it as a corner and the corner's
/// (v, w).
fn corner_parameters(net: &ControlNet) -> Vec<(usize, [f64; 2])> {
    let mut out = vec![(usize::MAX, [0.0; 2]); net.points().len()];
    for (t, c) in net.triangles().iter().enumerate().rev() {
        for (k, &i) in c.iter().enumerate() {
            out[i as usize] = (t, [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]][k]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::examples;

    fn net(name: &str) -> ControlNet {
        let e = examples::by_name(name).unwrap();
        ControlNet::from_arrays(e.points, &e.tris).unwrap()
    }

    #[test]
    fn mask_entries_agree_with_the_limit_positions() {
        let mut darts = net("sphere");
        let [a, b, _] = darts.triangles()[0];
        darts.tag_edge(a, b).unwrap(); // one hard edge: both ends are darts
        let mut cube = net("cube");
        cube.tag_by_angle(30.0).unwrap();
        let mut viking = net("viking");
        viking.tag_by_angle(30.0).unwrap();
        viking.tag_vertex(3).unwrap();
        for (name, net) in [
            ("darts", darts),
            ("cube", cube),
            ("viking", viking),
            ("tetra", net("tetra")),
            ("open-disk", net("open-disk")),
        ] {
            let limits = net.limit_points();
            let mut applied = vec![DVec3::ZERO; limits.len()];
            for (r, c, w) in limit_mask_entries(net.topology(), net.features()) {
                applied[r as usize] += w * net.points()[c as usize];
            }
            for (a, b) in applied.iter().zip(&limits) {
                assert!((*a - *b).length() <= 1e-14 * net.bbox_diagonal(), "{name}");
            }
        }
    }
}
