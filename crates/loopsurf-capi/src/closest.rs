//! Closest points: the certified global snap from a point, and from a
//! guess; the arguments and outputs `ls_project` and `ls_snap_certified`
//! share.

use crate::evaluate::query;
use crate::status::{input, output, run, Fail, LS_ERR_NOT_FINITE};
use crate::surface::ls_surface;
use loopsurf::DVec3;
use std::ffi::c_int;

/// The closest point of the limit surface to `xyz` (the global minimum of
/// the distance, also at hard edges, corners and boundaries): writes its
/// triangle, (v, w), position and distance. Certified to 1e-12 of the
/// bounding-box diagonal; `ls_snap_certified` returns the certificate and
/// takes a tolerance.
#[no_mangle]
pub unsafe extern "C" fn ls_snap(
    surface: *const ls_surface,
    xyz: *const f64,
    tri: *mut i32,
    vw: *mut f64,
    xyz_out: *mut f64,
    distance: *mut f64,
) -> c_int {
    run("ls_snap", || {
        let surface = &input(surface, "surface")?.0;
        let p = point(xyz)?;
        let outs = snap_outputs(tri, vw, xyz_out, distance)?;
        write_snap(outs, loopsurf::snap::closest_point(surface, p)?);
        Ok(())
    })
}

/// `ls_snap` starting from a guess (`tri_guess`, `vw_guess`) near the
/// answer, such as a neighbouring point's result: faster, and still the
/// global closest point.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn ls_snap_guess(
    surface: *const ls_surface,
    xyz: *const f64,
    tri_guess: i32,
    vw_guess: *const f64,
    tri: *mut i32,
    vw: *mut f64,
    xyz_out: *mut f64,
    distance: *mut f64,
) -> c_int {
    run("ls_snap_guess", || {
        let surface = &input(surface, "surface")?.0;
        let p = point(xyz)?;
        let (v, w) = guess(vw_guess)?;
        let outs = snap_outputs(tri, vw, xyz_out, distance)?;
        let t = query(surface, tri_guess, v, w)?;
        write_snap(outs, loopsurf::snap::snap_near(surface, p, t, v, w)?);
        Ok(())
    })
}

/// Reads a guess's (v, w).
pub(crate) unsafe fn guess(vw_guess: *const f64) -> Result<(f64, f64), Fail> {
    input(vw_guess, "vw_guess")?;
    Ok((*vw_guess, *vw_guess.add(1)))
}

pub(crate) type SnapOutputs = (*mut i32, *mut f64, *mut f64, *mut f64);

/// Reads a query point; NaN or infinite coordinates are errors.
pub(crate) unsafe fn point(xyz: *const f64) -> Result<DVec3, Fail> {
    input(xyz, "xyz")?;
    let p = DVec3::new(*xyz, *xyz.add(1), *xyz.add(2));
    if !p.is_finite() {
        return Err(Fail::new(
            LS_ERR_NOT_FINITE,
            format!("point {:?} is not finite", p.to_array()),
        ));
    }
    Ok(p)
}

pub(crate) fn snap_outputs(
    tri: *mut i32,
    vw: *mut f64,
    xyz_out: *mut f64,
    distance: *mut f64,
) -> Result<SnapOutputs, Fail> {
    Ok((
        output(tri, "tri")?,
        output(vw, "vw")?,
        output(xyz_out, "xyz_out")?,
        output(distance, "distance")?,
    ))
}

pub(crate) unsafe fn write_snap((tri, vw, xyz, distance): SnapOutputs, s: loopsurf::Snap) {
    *tri = s.tri as i32;
    *vw = s.v;
    *vw.add(1) = s.w;
    std::ptr::copy_nonoverlapping(s.point.to_array().as_ptr(), xyz, 3);
    *distance = s.distance;
}
