//! The tolerance rounds' measure and response: the chord error at every
//! centroid and edge midpoint, and where it exceeds the tolerance the
//! sizes of the control triangles there shrunk for the next round.

use super::remeshing::Remeshing;
use crate::parameters::SurfacePoint;
use crate::snap::FewSnaps;
use crate::topology::NONE;
use glam::DVec3;
use rayon::prelude::*;

/// A control triangle that shrank is stuck when its worst chord error
/// after that is still above this share of the one before.
const STUCK: f64 = 0.8;

/// The chord error of every triangle and edge as (its vertices, error):
/// the distance from its centroid or midpoint to the surface by local
/// projection (an upper bound of the true distance, and tight where the
/// guess is near) and, where that exceeds `tolerance`, by certified snap.
pub(super) fn chord_errors(work: &Remeshing, tolerance: f64) -> Vec<(Vec<u32>, f64)> {
    let mesh = &work.mesh;
    let probes: Vec<(u32, Vec<u32>)> = (0..mesh.num_half_edges())
        .filter(|&h| mesh.is_alive(h))
        .flat_map(|h| {
            let o = mesh.opposite(h);
            let edge = (o == NONE || h < o).then(|| (h, vec![mesh.origin(h), mesh.dest(h)]));
            let tri = (h % 3 == 0).then(|| (h, mesh.corners(h).to_vec()));
            edge.into_iter().chain(tri)
        })
        .collect();
    let surface = work.placer.surface;
    let mut measured: Vec<(DVec3, SurfacePoint, f64)> = probes
        .par_iter()
        .map(|(h, ids)| {
            let x = ids
                .iter()
                .map(|&i| work.vertices[i as usize].x)
                .sum::<DVec3>()
                / ids.len() as f64;
            let face = mesh.face[(h / 3) as usize];
            let guess = ids
                .iter()
                .map(|&i| &work.vertices[i as usize])
                .find(|v| v.is_free())
                .map(|v| v.at)
                .unwrap_or_else(|| work.placer.guess_in(&work.vertices[ids[0] as usize], face));
            let d = crate::snap::project(surface, x, guess.tri as usize, guess.v, guess.w)
                .map_or(f64::INFINITY, |s| s.distance);
            (x, guess, d)
        })
        .collect();
    // A local minimum may be the wrong one (across a fold or a crease):
    // where it misses, the certified snap decides.
    if measured.iter().any(|m| m.2 > tolerance) {
        let snaps = FewSnaps::new(surface);
        measured.par_iter_mut().for_each(|(x, at, d)| {
            if *d > tolerance {
                *d = snaps
                    .snap_near(*x, at.tri as usize, at.v, at.w)
                    .map_or(f64::INFINITY, |s| s.distance);
            }
        });
    }
    probes
        .into_iter()
        .zip(measured)
        .map(|((_, ids), m)| (ids, m.2))
        .collect()
}

/// Per control triangle, how much its sizes are shrunk, and its worst
/// chord error the last time it missed.
///
/// Each control triangle shrinks once a round, by the factor its worst
/// miss asks for: chord error falls with the square of the size. (Once per
/// miss would compound over the many probes of one triangle, down to the
/// floor.)
///
/// A control triangle whose worst miss did not fall after it shrank is
/// stuck, not too coarse (an edge that cannot be split where the surface
/// turns back within it, as at a cusp of a crease or on a patch that
/// folds): it shrinks no more. Shrinking on, mpi.off at 40° missed by the
/// same 0.2 in its triangles 76, 82 and 84 each round while the sizes
/// asked for ever more, from 75 thousand triangles to 29 million.
pub(super) struct Shrinking {
    factors: Vec<f64>,
    last_missed: Vec<f64>,
}

impl Shrinking {
    /// Nothing shrunk, for a net of `triangles` control triangles.
    pub fn new(triangles: usize) -> Shrinking {
        Shrinking {
            factors: vec![1.0; triangles],
            last_missed: vec![f64::INFINITY; triangles],
        }
    }

    /// Shrunk by `factors` already (a part carrying on from another
    /// part's tolerance rounds).
    pub fn from_factors(factors: Vec<f64>) -> Shrinking {
        Shrinking {
            last_missed: vec![f64::INFINITY; factors.len()],
            factors,
        }
    }

    /// The factor each control triangle's sizes are shrunk by.
    pub fn factors(&self) -> &[f64] {
        &self.factors
    }

    /// Shrinks the control triangles where `errors` exceed `tolerance`,
    /// but the stuck ones.
    pub fn shrink_where_missed(
        &mut self,
        work: &Remeshing,
        errors: &[(Vec<u32>, f64)],
        tolerance: f64,
    ) {
        let missed = self.worst_misses(work, errors, tolerance);
        let stuck: Vec<bool> = (0..self.factors.len())
            .map(|t| self.factors[t] < 1.0 && missed[t] > STUCK * self.last_missed[t])
            .collect();
        // (A triangle that did not miss this round is judged afresh.)
        self.last_missed = missed
            .iter()
            .map(|&e| if e > 0.0 { e } else { f64::INFINITY })
            .collect();
        let factor = round_factors(work, errors, tolerance, &stuck);
        for (s, f) in self.factors.iter_mut().zip(factor) {
            *s *= f;
        }
    }

    /// Per control triangle, the worst chord error above `tolerance` at
    /// one of its vertices' probes (0 where none).
    fn worst_misses(
        &self,
        work: &Remeshing,
        errors: &[(Vec<u32>, f64)],
        tolerance: f64,
    ) -> Vec<f64> {
        let mut missed = vec![0.0f64; self.factors.len()];
        for (ids, e) in errors.iter().filter(|(_, e)| *e > tolerance) {
            for &v in ids {
                let t = work.vertices[v as usize].at.tri as usize;
                missed[t] = missed[t].max(*e);
            }
        }
        missed
    }
}

/// This round's shrink factor of each control triangle: the smallest that
/// a miss at one of its vertices asks for, or at one of its neighbours'
/// (vertices relax across control edges, into sizes not shrunk); 1 where
/// none missed or the triangle is `stuck`.
fn round_factors(
    work: &Remeshing,
    errors: &[(Vec<u32>, f64)],
    tolerance: f64,
    stuck: &[bool],
) -> Vec<f64> {
    let mut factor = vec![1.0f64; stuck.len()];
    let topo = work.placer.surface.net().topology();
    for (ids, e) in errors.iter().filter(|(_, e)| *e > tolerance) {
        let f = (0.8 * (tolerance / e).sqrt()).max(0.25);
        for &v in ids {
            let t = work.vertices[v as usize].at.tri as usize;
            if stuck[t] {
                continue;
            }
            factor[t] = factor[t].min(f);
            for &e in &topo.triangle_edges()[t] {
                for &n in &topo.edge_triangles()[e as usize] {
                    if n != NONE {
                        factor[n as usize] = factor[n as usize].min(f);
                    }
                }
            }
        }
    }
    factor
}
