//! Local projection from a guess: what a mesh generator or smoother needs
//! for a vertex it has moved a little (EGADS's inverse evaluation with a
//! guess). Newton with walking across triangles, no global search, no
//! certificate — fast because it proves nothing.

use super::{check_point, local, Snap};
use crate::error::Result;
use crate::surface::Surface;
use glam::DVec3;

/// The nearest LOCAL minimum of the distance to `p`, found by Newton's
/// method from the guess (tri, v, w), walking across edges and around
/// vertices (minima on hard edges, corners and boundaries included).
///
/// The answer is local: when the guess lies in another basin of the
/// distance than the global closest point, it is not that point. Use it
/// for points near the surface with a guess from a neighbouring point
/// (a mesh vertex moved by a smoother, a new edge midpoint);
/// [`closest_point`](super::closest_point) is the global, certified answer.
/// `lower_bound` is 0: nothing is proven.
///
/// Errors, as for [`snap_near`](super::snap_near): a point that is not finite
/// ([`Error::InvalidArgument`](crate::Error::InvalidArgument)), a
/// triangle out of range, or a guess (v, w) outside its triangle
/// ([`Error::BadParameter`](crate::Error::BadParameter)); round-off
/// outside it is clamped.
pub fn project(surface: &Surface, p: DVec3, tri: usize, v: f64, w: f64) -> Result<Snap> {
    project_walking(surface, p, tri, v, w, false)
}

/// [`project`] that stays in the model face of the guess's
/// triangle: where the descent would cross a hard edge it stops on it,
/// so the answer is the nearest local minimum over that face alone
/// (its curves included). A curved element's node must lie on the
/// element's own face, even where the other side of a crease is nearer.
pub fn project_in_face(surface: &Surface, p: DVec3, tri: usize, v: f64, w: f64) -> Result<Snap> {
    project_walking(surface, p, tri, v, w, true)
}

fn project_walking(
    surface: &Surface,
    p: DVec3,
    tri: usize,
    v: f64,
    w: f64,
    in_face: bool,
) -> Result<Snap> {
    let (v, w) = checked_start(surface, p, tri, v, w)?;
    Ok(local::descend_walking(surface, p, tri, v, w, in_face).0)
}

/// A walk's point and guess checked, the guess with round-off outside its
/// triangle clamped. Checked like `snap_near`'s guess, without evaluating
/// it: the descent's first evaluation is the guess's.
pub(crate) fn checked_start(
    surface: &Surface,
    p: DVec3,
    tri: usize,
    v: f64,
    w: f64,
) -> Result<(f64, f64)> {
    check_point(p)?;
    surface.validate(tri, v, w)?;
    let (v, w) = (v.max(0.0), w.max(0.0));
    Ok(if v + w > 1.0 {
        (v / (v + w), w / (v + w))
    } else {
        (v, w)
    })
}
