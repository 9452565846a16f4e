//! Evaluation of the limit surface: positions and derivatives, normals and
//! principal curvatures at any (triangle, v, w), one point or many.

use crate::status::{input, output, run, Fail};
use crate::status::{LS_ERR_INDEX_OUT_OF_RANGE, LS_ERR_INVALID_ARGUMENT, LS_ERR_NOT_FINITE};
use crate::surface::ls_surface;
use loopsurf::Surface;
use rayon::prelude::*;
use std::ffi::c_int;

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
