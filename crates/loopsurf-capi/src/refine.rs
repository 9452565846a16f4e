//! Uniform refinement of the control net, and where each refined vertex
//! lies on the surface.

use crate::buffers::malloc_copy;
use crate::status::{input, output, run, Fail, LS_ERR_INVALID_ARGUMENT};
use crate::surface::ls_surface;
use std::ffi::{c_int, c_void};

/// A level count from C: 0 or more (the library caps it).
pub(crate) fn levels_arg(levels: c_int) -> Result<u32, Fail> {
    u32::try_from(levels).map_err(|_| {
        Fail::new(
            LS_ERR_INVALID_ARGUMENT,
            format!("levels = {levels}: must be ≥ 0"),
        )
    })
}

/// Copies two arrays into fresh `malloc` blocks, both or neither.
unsafe fn malloc_pair<A: Copy, B: Copy>(a: &[A], b: &[B]) -> Result<(*mut A, *mut B), Fail> {
    let pa = malloc_copy(a)?;
    match malloc_copy(b) {
        Ok(pb) => Ok((pa, pb)),
        Err(fail) => {
            libc::free(pa as *mut c_void);
            Err(fail)
        }
    }
}

/// Refines the surface's control net `levels` times (0 to 12) by uniform
/// Loop subdivision with its hard edges and corners. With `to_limit`
/// nonzero, every vertex is moved to its exact limit position. Writes the
/// counts and two new arrays, `xyz` (3 × nverts) and `tris` (3 × ntris,
/// 0-based), to be released with `ls_free_array`. Numbering: the vertices of
/// level k keep their indices at level k + 1, the vertex on edge e follows
/// as nverts + e, and the children of triangle t are 4t to 4t + 3.
#[no_mangle]
pub unsafe extern "C" fn ls_refine(
    surface: *const ls_surface,
    levels: c_int,
    to_limit: c_int,
    nverts: *mut usize,
    xyz: *mut *mut f64,
    ntris: *mut usize,
    tris: *mut *mut i32,
) -> c_int {
    run("ls_refine", || {
        let surface = &input(surface, "surface")?.0;
        let outs = (
            output(nverts, "nverts")?,
            output(xyz, "xyz")?,
            output(ntris, "ntris")?,
            output(tris, "tris")?,
        );
        let levels = levels_arg(levels)?;
        let refined = loopsurf::refine::refine_uniform(surface.net(), levels)?;
        let net = refined.net();
        if net.points().len() > i32::MAX as usize {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("{} vertices do not fit 32-bit indices", net.points().len()),
            ));
        }
        let limits;
        let points = if to_limit != 0 {
            limits = refined.limit_points();
            &limits[..]
        } else {
            net.points()
        };
        // Copied straight into the caller's arrays: a DVec3 is three f64
        // (repr(C)), and indices below i32::MAX read the same as i32.
        let coords = std::slice::from_raw_parts(points.as_ptr() as *const f64, 3 * points.len());
        let triangles = net.triangles();
        let indices =
            std::slice::from_raw_parts(triangles.as_ptr() as *const i32, 3 * triangles.len());
        let (coords_out, tris_out) = malloc_pair(coords, indices)?;
        *outs.0 = points.len();
        *outs.1 = coords_out;
        *outs.2 = net.triangles().len();
        *outs.3 = tris_out;
        Ok(())
    })
}

/// Where every vertex of `ls_refine`'s output (same `levels`, same order)
/// lies on the surface: its control triangle (`tri`, nverts entries) and
/// exact dyadic (v, w) there (`vw`, 2 × nverts), so that
/// `ls_evaluate(tri[i], vw[2i], vw[2i+1])` is the limit of refined vertex i —
/// what a finite-element code needs to curve a refined mesh. Release both
/// arrays with `ls_free_array`.
#[no_mangle]
pub unsafe extern "C" fn ls_refine_origins(
    surface: *const ls_surface,
    levels: c_int,
    nverts: *mut usize,
    tri: *mut *mut i32,
    vw: *mut *mut f64,
) -> c_int {
    run("ls_refine_origins", || {
        let surface = &input(surface, "surface")?.0;
        let outs = (
            output(nverts, "nverts")?,
            output(tri, "tri")?,
            output(vw, "vw")?,
        );
        let levels = levels_arg(levels)?;
        let refined = loopsurf::refine::refine_uniform(surface.net(), levels)?;
        let mut tris = Vec::with_capacity(refined.net().points().len());
        let mut params = Vec::with_capacity(2 * tris.capacity());
        for origin in refined.origins() {
            // Unreferenced control vertices lie on no triangle.
            let (t, v, w) = origin.map_or((-1, f64::NAN, f64::NAN), |o| (o.tri as i32, o.v, o.w));
            tris.push(t);
            params.extend([v, w]);
        }
        let (tri_out, vw_out) = malloc_pair(&tris, &params)?;
        *outs.0 = tris.len();
        *outs.1 = tri_out;
        *outs.2 = vw_out;
        Ok(())
    })
}
