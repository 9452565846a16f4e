//! Surfaces: build, evaluate, curvature, normals, snap, free.

use crate::status::{input, output, run, run_void, Fail};
use crate::status::{LS_ERR_INDEX_OUT_OF_RANGE, LS_ERR_INVALID_ARGUMENT, LS_ERR_NOT_FINITE};
use crate::{ls_net, ls_surface};
use loopsurf::{DVec3, Surface, SurfaceMode};
use rayon::prelude::*;
use std::ffi::c_int;

/// Freezes a net into an immutable surface. The net is copied: it may be
/// changed or freed after. The build refines the net once; each triangle's
/// evaluation data is made the first time a query reaches it (any thread
/// may query at any time, and results do not depend on the order).
#[no_mangle]
pub unsafe extern "C" fn ls_surface_build(net: *const ls_net, out: *mut *mut ls_surface) -> c_int {
    run("ls_surface_build", || {
        let net = &input(net, "net")?.0;
        let out = output(out, "out")?;
        let surface = Surface::new(net)?;
        *out = Box::into_raw(Box::new(ls_surface(surface)));
        Ok(())
    })
}

/// `ls_surface_build_interpolating` mode: solve for new control points
/// whose smooth limit surface passes through the net's points.
pub const LS_INTERPOLATE_SOLVE: c_int = 1;
/// `ls_surface_build_interpolating` mode: the approximating surface plus a
/// linear correction per triangle, through the net's points exactly but
/// only C0 across edges.
pub const LS_INTERPOLATE_DISPLACEMENT: c_int = 2;

/// Like `ls_surface_build`, but the surface passes through the net's points
/// (seed 000 §3.3): `mode` is LS_INTERPOLATE_SOLVE or
/// LS_INTERPOLATE_DISPLACEMENT. Solving fails with LS_ERR_INVALID_ARGUMENT
/// if the net's limit operator is singular or too ill-conditioned.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_build_interpolating(
    net: *const ls_net,
    mode: c_int,
    out: *mut *mut ls_surface,
) -> c_int {
    run("ls_surface_build_interpolating", || {
        let net = &input(net, "net")?.0;
        let out = output(out, "out")?;
        let mode = match mode {
            LS_INTERPOLATE_SOLVE => SurfaceMode::Solve,
            LS_INTERPOLATE_DISPLACEMENT => SurfaceMode::Displacement,
            _ => {
                return Err(Fail::new(
                    LS_ERR_INVALID_ARGUMENT,
                    format!("mode {mode}: expected LS_INTERPOLATE_SOLVE (1) or LS_INTERPOLATE_DISPLACEMENT (2)"),
                ))
            }
        };
        let surface = Surface::with_mode(net, mode)?;
        *out = Box::into_raw(Box::new(ls_surface(surface)));
        Ok(())
    })
}

/// Writes the number of triangles of the surface's control net: valid
/// triangle indices are 0 to ntris − 1.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_num_triangles(
    surface: *const ls_surface,
    ntris: *mut usize,
) -> c_int {
    run("ls_surface_num_triangles", || {
        let surface = &input(surface, "surface")?.0;
        *output(ntris, "ntris")? = surface.net().triangles().len();
        Ok(())
    })
}

/// The control triangles whose patch of the limit surface folds over
/// itself (normals within it turning by more than 120°; coarse nets fold
/// next to corners, creases and irregular vertices of high valence, and no
/// mesh of a fold has good triangles that all face one way): `n` 0-based
/// indices, ascending, in a new array (allocated even when n = 0)
/// released with `ls_free_array`. Every patch is evaluated, about 150
/// times.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_folded_patches(
    surface: *const ls_surface,
    n: *mut usize,
    triangles: *mut *mut i32,
) -> c_int {
    run("ls_surface_folded_patches", || {
        let surface = &input(surface, "surface")?.0;
        let (n, triangles) = (output(n, "n")?, output(triangles, "triangles")?);
        let folded: Vec<i32> = loopsurf::folds::folded_patches(surface)
            .into_iter()
            .map(|t| t as i32)
            .collect();
        *triangles = crate::buffers::malloc_copy(&folded)?;
        *n = folded.len();
        Ok(())
    })
}

/// Checks a query's triangle index and numbers (the library checks the range
/// of (v, w)), so each failure gets its own status code.
pub(crate) fn query(surface: &Surface, tri: i32, v: f64, w: f64) -> Result<usize, Fail> {
    let n = surface.net().triangles().len();
    let t = usize::try_from(tri)
        .ok()
        .filter(|&t| t < n)
        .ok_or_else(|| {
            Fail::new(
                LS_ERR_INDEX_OUT_OF_RANGE,
                format!("triangle {tri}: out of range (the net has {n} triangles)"),
            )
        })?;
    if !v.is_finite() || !w.is_finite() {
        return Err(Fail::new(
            LS_ERR_NOT_FINITE,
            format!("point (v, w) = ({v}, {w}) of triangle {tri}: not a finite number"),
        ));
    }
    Ok(t)
}

/// The body of a query at one point that writes N numbers: checks the
/// pointers and the query, computes, then writes.
unsafe fn point_query<const N: usize>(
    name: &str,
    surface: *const ls_surface,
    tri: i32,
    v: f64,
    w: f64,
    (out, out_name): (*mut f64, &str),
    compute: impl FnOnce(&Surface, usize) -> Result<[f64; N], Fail>,
) -> c_int {
    run(name, || {
        let surface = &input(surface, "surface")?.0;
        let out = output(out, out_name)?;
        let t = query(surface, tri, v, w)?;
        let values = compute(surface, t)?;
        std::ptr::copy_nonoverlapping(values.as_ptr(), out, N);
        Ok(())
    })
}

/// Exact position and derivatives at (v, w) of triangle `tri` (barycentric
/// weights 1 − v − w, v, w on its corners): 18 doubles X, Xv, Xw, Xvv, Xvw,
/// Xww. Exactly at an irregular, crease, dart or corner vertex the
/// parametrisation is singular: X is the limit position and the derivatives
/// are 0 (use `ls_normal` for the normal there).
#[no_mangle]
pub unsafe extern "C" fn ls_evaluate(
    surface: *const ls_surface,
    tri: i32,
    v: f64,
    w: f64,
    result: *mut f64,
) -> c_int {
    point_query(
        "ls_evaluate",
        surface,
        tri,
        v,
        w,
        (result, "result"),
        |s, t| Ok(s.eval_record(t, v, w)?),
    )
}

/// `ls_evaluate` for n points at once, in parallel: triangle `tri[i]` at
/// (`vw[2i]`, `vw[2i+1]`) gives `results[18i .. 18i+18]`. Fails on the first
/// bad query (the message names its position) and then writes nothing.
/// The pointers may be NULL only when n is 0.
#[no_mangle]
pub unsafe extern "C" fn ls_evaluate_many(
    surface: *const ls_surface,
    n: usize,
    tri: *const i32,
    vw: *const f64,
    results: *mut f64,
) -> c_int {
    run("ls_evaluate_many", || {
        let surface = &input(surface, "surface")?.0;
        if n == 0 {
            return Ok(());
        }
        input(tri, "tri")?;
        input(vw, "vw")?;
        let results = output(results, "results")?;
        let too_large = || Fail::new(LS_ERR_INVALID_ARGUMENT, format!("n = {n} is too large"));
        let len = n
            .checked_mul(18)
            .filter(|l| *l <= isize::MAX as usize / 8)
            .ok_or_else(too_large)?;
        let tri = std::slice::from_raw_parts(tri, n);
        let vw = std::slice::from_raw_parts(vw, 2 * n);
        let check = |i: usize| {
            let (v, w) = (vw[2 * i], vw[2 * i + 1]);
            let t = query(surface, tri[i], v, w)?;
            surface.validate(t, v, w)?;
            Ok::<usize, Fail>(t)
        };
        // Validate every query first, so that nothing is written unless
        // all succeed; the first bad one is reported with its position.
        if let Some(bad) = (0..n).into_par_iter().find_first(|&i| check(i).is_err()) {
            if let Err(fail) = check(bad) {
                return Err(fail.context(&format!("query {bad}")));
            }
        }
        // Then evaluate in runs of queries (a task per query cost 5% on
        // one thread).
        const RUN: usize = 256;
        let results = std::slice::from_raw_parts_mut(results, len);
        results
            .par_chunks_mut(18 * RUN)
            .enumerate()
            .try_for_each(|(run, out)| {
                for (j, out) in out.chunks_exact_mut(18).enumerate() {
                    let i = run * RUN + j;
                    let t = tri[i] as usize; // validated above
                    out.copy_from_slice(&surface.eval_record(t, vw[2 * i], vw[2 * i + 1])?);
                }
                Ok::<(), Fail>(())
            })?;
        Ok(())
    })
}

/// The unit outward normal at (v, w) of triangle `tri` (3 doubles). Exactly
/// at a special vertex it is the limit normal there, one-sided at creases
/// and corners (each sector has its own tangent plane).
#[no_mangle]
pub unsafe extern "C" fn ls_normal(
    surface: *const ls_surface,
    tri: i32,
    v: f64,
    w: f64,
    normal: *mut f64,
) -> c_int {
    point_query(
        "ls_normal",
        surface,
        tri,
        v,
        w,
        (normal, "normal"),
        |s, t| Ok(s.normal(t, v, w)?.to_array()),
    )
}

/// Principal curvatures and directions at (v, w) of triangle `tri`: 8
/// doubles k1, dir1 (3), k2, dir2 (3), k1 ≥ k2, positive where the surface
/// bends away from its outward normal (a sphere of radius r gives 1/r).
/// Exactly at a special vertex, where curvature is unbounded or depends on
/// the direction, all 8 are 0.
#[no_mangle]
pub unsafe extern "C" fn ls_curvature(
    surface: *const ls_surface,
    tri: i32,
    v: f64,
    w: f64,
    result: *mut f64,
) -> c_int {
    point_query(
        "ls_curvature",
        surface,
        tri,
        v,
        w,
        (result, "result"),
        |s, t| Ok(s.curvature(t, v, w)?.record()),
    )
}

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
        input(vw_guess, "vw_guess")?;
        let (v, w) = (*vw_guess, *vw_guess.add(1));
        let outs = snap_outputs(tri, vw, xyz_out, distance)?;
        let t = query(surface, tri_guess, v, w)?;
        write_snap(outs, loopsurf::snap::snap_near(surface, p, t, v, w)?);
        Ok(())
    })
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

/// Frees a surface (NULL is ignored). No other thread may still use it.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_free(surface: *mut ls_surface) {
    if !surface.is_null() {
        run_void("ls_surface_free", || drop(Box::from_raw(surface)));
    }
}
