//! The fairness term, on the displacement d of the control points from the
//! start net ([`super::start`]): the thin plate |U² d|² (Kobbelt's
//! umbrella², as Marinov & Kobbelt use for Loop control nets) plus a tenth
//! of the membrane |U d|², U the umbrella operator; along creases U takes
//! only the crease's own two neighbours (second differences of the crease
//! polygon, so a crease bends like a curve and is not pulled towards the
//! faces beside it), and at corners it is absent: they go where the data
//! put them.
//!
//! Why the displacement and not the positions: the membrane of the
//! positions pulls every vertex to the centroid of its ring and shrinks a
//! curved shape, and the thin plate of the positions vanishes on neither
//! a sphere nor a cylinder, so both bend the surface where data are
//! sparse. The start net already has the shape, within a few of the
//! input's chord errors; what the fit adds is a correction, and that is
//! what should be smooth. Why both terms: alone, the thin plate lets a
//! data-free region (a flat face of the filleted box, two input triangles)
//! bulge at almost no cost, since its energy of a bump of width L over
//! edges h scales as (h/L)⁴ (measured: 0.16 of the diagonal), and the
//! membrane alone interpolates the correction harmonically, with a kink at
//! every datum. The net comes from a remesher with near-equilateral
//! triangles, so uniform weights suffice.

use crate::features::VertexKind;
use crate::net::ControlNet;
use faer::sparse::{SparseColMat, Triplet};

/// The umbrella operator U of `net` as triplets (row, column, weight):
/// x_v minus the mean of its ring (smooth and dart vertices) or of its
/// two crease neighbours (crease vertices); a zero row at corners.
fn umbrella(net: &ControlNet) -> Vec<Triplet<usize, usize, f64>> {
    let (topo, features) = (net.topology(), net.features());
    let kinds = net.vertex_kinds();
    let mut out = Vec::with_capacity(8 * kinds.len());
    for (v, kind) in kinds.iter().enumerate() {
        let neighbours: Vec<u32> = match kind {
            VertexKind::Smooth | VertexKind::Dart => topo.ring(v).to_vec(),
            VertexKind::Crease => features.hard_neighbours(topo, v),
            VertexKind::Corner => continue,
        };
        if neighbours.is_empty() {
            continue;
        }
        out.push(Triplet::new(v, v, 1.0));
        let each = -1.0 / neighbours.len() as f64;
        out.extend(
            neighbours
                .iter()
                .map(|&u| Triplet::new(v, u as usize, each)),
        );
    }
    out
}

/// The weight of the membrane |U d|² against the thin plate |U² d|².
pub const MEMBRANE: f64 = 0.1;

/// MEMBRANE·UᵀU + (U²)ᵀU², the normal-equation matrix of the fairness
/// energy, by faer's sparse products.
pub fn normal_matrix(net: &ControlNet) -> SparseColMat<usize, f64> {
    let n = net.points().len();
    let u = umbrella(net);
    let ut: Vec<_> = u
        .iter()
        .map(|t| Triplet::new(t.col, t.row, t.val))
        .collect();
    let build = |t: &[Triplet<usize, usize, f64>]| {
        SparseColMat::<usize, f64>::try_new_from_triplets(n, n, t).expect("indices in range")
    };
    let (u, ut) = (build(&u), build(&ut));
    let product = |a: &SparseColMat<usize, f64>, b: &SparseColMat<usize, f64>| {
        faer::sparse::linalg::matmul::sparse_sparse_matmul(
            a.as_ref(),
            b.as_ref(),
            1.0,
            faer::Par::Seq,
        )
        .expect("memory for the fairness matrix")
    };
    let membrane = product(&ut, &u);
    let plate = product(&product(&ut, &ut), &product(&u, &u));
    let mut t = Vec::new();
    for (m, scale) in [(&membrane, MEMBRANE), (&plate, 1.0)] {
        for j in 0..m.ncols() {
            let range = m.col_range(j);
            for (&i, &v) in m.row_idx()[range.clone()].iter().zip(&m.val()[range]) {
                t.push(Triplet::new(i, j, scale * v));
            }
        }
    }
    build(&t)
}
