//! Where a fit misses its tolerance: the net refined around the input
//! vertices it missed, and fitted again.
//!
//! The net's spacing is one length for the whole input, and some inputs
//! hold a feature narrower than it: CGAL's fandisk has a thin wedge of face
//! inside the fold of a crease, about one control spacing wide, and its fit
//! at the default resolution passed 2.9e-4 of the diagonal from a vertex
//! there, three times the tolerance (a net twice as fine everywhere passes
//! at four times the control triangles). One level of Liu & Kondo's
//! adaptive Loop subdivision ([`crate::adapt`]) around the missed vertices
//! halves the spacing there alone, adding no irregular vertex but where
//! the refined region meets the rest; the fitted positions, refined, start
//! the next fit. Fandisk then passes 7.5e-5 from its vertices, for 9%
//! more control triangles. Refining every place the fit passed farther
//! than 5e-5 of the diagonal from its data, whether or not it missed the
//! tolerance, was measured on the CAD shapes of docs/fitting.md and made
//! them no closer: a fit that meets its tolerance is left as it is.

use crate::adapt::subdivide_where;
use crate::error::Result;
use crate::net::ControlNet;
use crate::snap::Snap;

/// The most refinements a fit takes before it gives up and says where it
/// missed.
pub const MAX_REFINEMENTS: usize = 3;

/// Refinement never takes the net past this many times the triangles it
/// started with: a tolerance missed nearly everywhere asks for a smaller
/// resolution, which the refusal says, not for the net refined piece by
/// piece. CGAL's elephant and cow, fitted at the default tolerance, pass
/// farther than half of it from 42% and 51% of their vertices (10 and 15
/// times it at the worst); refined twice they meet it, at 3.8 and 4.5
/// times the control triangles.
pub const MAX_GROWTH: usize = 8;

/// The net is refined within this many rings of the control triangles
/// holding the closest points of the input vertices missed by more than
/// [`NEAR_MISS`] of the tolerance.
const RINGS: usize = 2;

/// A vertex farther than this fraction of the tolerance counts as missed
/// when choosing where to refine, so that its neighbours, which the next
/// fit may push out, are refined with it.
const NEAR_MISS: f64 = 0.5;

/// `fitted` refined once around the input vertices whose closest points
/// `snaps` are farther than [`NEAR_MISS`] of `tolerance` (a distance in
/// model units).
pub fn refine_around_misses(
    fitted: &ControlNet,
    snaps: &[Snap],
    tolerance: f64,
) -> Result<ControlNet> {
    let topo = fitted.topology();
    let mut near = vec![false; fitted.points().len()];
    let mut front: Vec<u32> = snaps
        .iter()
        .filter(|s| s.distance > NEAR_MISS * tolerance)
        .flat_map(|s| topo.triangles()[s.tri])
        .collect();
    for &v in &front {
        near[v as usize] = true;
    }
    for _ in 0..RINGS {
        let mut next = Vec::new();
        for v in front {
            for &n in topo.ring(v as usize) {
                if !near[n as usize] {
                    near[n as usize] = true;
                    next.push(n);
                }
            }
        }
        front = next;
    }
    subdivide_where(fitted, |v| near[v])
}
