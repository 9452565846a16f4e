//! The local projection: Newton with walking from a guess, for points a
//! mesh generator or smoother has moved a little. Arguments and outputs as
//! `ls_snap_guess`'s; only the search differs (local, uncertified, fast).

use crate::closest::{guess, point, snap_outputs, write_snap};
use crate::evaluate::query;
use crate::status::{input, run};
use crate::surface::ls_surface;
use std::ffi::c_int;

/// The nearest LOCAL minimum of the distance to `xyz`, by Newton's method
/// with walking from the guess (`tri_guess`, `vw_guess`): no global search
/// and no certificate, for points a mesh generator or smoother has moved a
/// little, guessed from a neighbouring point. When the guess lies in
/// another basin of the distance, the answer is not the global closest
/// point (`ls_snap` is). Outputs as `ls_snap`'s, statuses as
/// `ls_snap_guess`'s (NULL pointer, triangle out of range, guess outside
/// its triangle, point not finite); nothing is written on failure.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn ls_project(
    surface: *const ls_surface,
    xyz: *const f64,
    tri_guess: i32,
    vw_guess: *const f64,
    tri: *mut i32,
    vw: *mut f64,
    xyz_out: *mut f64,
    distance: *mut f64,
) -> c_int {
    run("ls_project", || {
        let surface = &input(surface, "surface")?.0;
        let p = point(xyz)?;
        let (v, w) = guess(vw_guess)?;
        let outs = snap_outputs(tri, vw, xyz_out, distance)?;
        let t = query(surface, tri_guess, v, w)?;
        write_snap(outs, loopsurf::snap::project(surface, p, t, v, w)?);
        Ok(())
    })
}
