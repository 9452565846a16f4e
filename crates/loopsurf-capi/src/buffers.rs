//! Functions that hand arrays to the caller (refinement, surface streams)
//! and the matching frees. Arrays come from `malloc`, so C's `free` also
//! releases them; `ls_free_array` and `ls_free_bytes` exist for languages
//! without direct access to the C allocator (Fortran).

use crate::ls_surface;
use crate::status::{input, output, run, Fail};
use crate::status::{LS_ERR_INTERNAL, LS_ERR_INVALID_ARGUMENT};
use loopsurf::refine::refine_uniform;
use std::ffi::{c_int, c_void};

/// Copies `data` into a fresh `malloc` block (never NULL on success).
pub(crate) unsafe fn malloc_copy<T: Copy>(data: &[T]) -> Result<*mut T, Fail> {
    let bytes = std::mem::size_of_val(data).max(1);
    let p = libc::malloc(bytes) as *mut T;
    if p.is_null() {
        return Err(Fail::new(
            LS_ERR_INTERNAL,
            format!("out of memory ({bytes} bytes)"),
        ));
    }
    std::ptr::copy_nonoverlapping(data.as_ptr(), p, data.len());
    Ok(p)
}

/// `malloc` blocks under construction: freed again on drop unless handed
/// over, so a function that fails half-way leaks nothing.
#[derive(Default)]
pub(crate) struct Blocks(Vec<*mut c_void>);

impl Blocks {
    pub(crate) unsafe fn copy<T: Copy>(&mut self, data: &[T]) -> Result<*mut T, Fail> {
        let p = malloc_copy(data)?;
        self.0.push(p as *mut c_void);
        Ok(p)
    }

    /// The caller now owns every block.
    pub(crate) fn hand_over(mut self) {
        self.0.clear();
    }
}

impl Drop for Blocks {
    fn drop(&mut self) {
        for &p in &self.0 {
            unsafe { libc::free(p) };
        }
    }
}

const _: () = assert!(std::mem::size_of::<loopsurf::DVec3>() == 3 * std::mem::size_of::<f64>());

/// A mesh on the surface as caller-owned arrays: `xyz` (3 × nverts), `tris`
/// (3 × ntris, 0-based), and per vertex its control triangle and (v, w).
pub(crate) struct MeshArrays {
    pub xyz: *mut f64,
    pub tris: *mut i32,
    pub vertex_tri: *mut i32,
    pub vertex_vw: *mut f64,
}

impl MeshArrays {
    /// Copies a mesh into `blocks`; fails when it does not fit 32-bit indices.
    pub(crate) unsafe fn copy(
        blocks: &mut Blocks,
        points: &[loopsurf::DVec3],
        triangles: &[[u32; 3]],
        params: &[loopsurf::SurfacePoint],
    ) -> Result<MeshArrays, Fail> {
        if points.len() > i32::MAX as usize {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("{} vertices do not fit 32-bit indices", points.len()),
            ));
        }
        let coords: Vec<f64> = points.iter().flat_map(|p| p.to_array()).collect();
        let indices: Vec<i32> = triangles.iter().flatten().map(|&i| i as i32).collect();
        let tri: Vec<i32> = params.iter().map(|p| p.tri as i32).collect();
        let vw: Vec<f64> = params.iter().flat_map(|p| [p.v, p.w]).collect();
        Ok(MeshArrays {
            xyz: blocks.copy(&coords)?,
            tris: blocks.copy(&indices)?,
            vertex_tri: blocks.copy(&tri)?,
            vertex_vw: blocks.copy(&vw)?,
        })
    }
}

/// The six outputs of a function that hands over a mesh on the surface
/// (`ls_mesh`, `ls_remesh`, `ls_adapt`): checked non-NULL before any work,
/// written only once everything succeeded.
pub(crate) struct MeshOutputs {
    nverts: *mut usize,
    xyz: *mut *mut f64,
    ntris: *mut usize,
    tris: *mut *mut i32,
    vertex_tri: *mut *mut i32,
    vertex_vw: *mut *mut f64,
}

impl MeshOutputs {
    pub(crate) fn check(
        nverts: *mut usize,
        xyz: *mut *mut f64,
        ntris: *mut usize,
        tris: *mut *mut i32,
        vertex_tri: *mut *mut i32,
        vertex_vw: *mut *mut f64,
    ) -> Result<MeshOutputs, Fail> {
        Ok(MeshOutputs {
            nverts: output(nverts, "nverts")?,
            xyz: output(xyz, "xyz")?,
            ntris: output(ntris, "ntris")?,
            tris: output(tris, "tris")?,
            vertex_tri: output(vertex_tri, "vertex_tri")?,
            vertex_vw: output(vertex_vw, "vertex_vw")?,
        })
    }

    /// Hands `arrays` (of `nverts` vertices and `ntris` triangles) to the
    /// caller; after [`Blocks::hand_over`].
    pub(crate) unsafe fn write(self, arrays: MeshArrays, nverts: usize, ntris: usize) {
        *self.nverts = nverts;
        *self.xyz = arrays.xyz;
        *self.ntris = ntris;
        *self.tris = arrays.tris;
        *self.vertex_tri = arrays.vertex_tri;
        *self.vertex_vw = arrays.vertex_vw;
    }
}

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
        let refined = refine_uniform(surface.net(), levels)?;
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
        let refined = refine_uniform(surface.net(), levels)?;
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

/// Frees an array returned by `ls_refine`, `ls_refine_origins` or
/// `ls_net_hard_edges` (NULL is ignored).
#[no_mangle]
pub unsafe extern "C" fn ls_free_array(array: *mut c_void) {
    libc::free(array);
}

/// The surface as a versioned, checksummed byte stream, e.g. for
/// `MPI_Bcast` to every rank: writes a new buffer and its length, to be
/// released with `ls_free_bytes`. `ls_surface_load` turns it back into a
/// surface that evaluates bit-identically.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_save(
    surface: *const ls_surface,
    bytes: *mut *mut u8,
    n: *mut usize,
) -> c_int {
    run("ls_surface_save", || {
        let surface = &input(surface, "surface")?.0;
        let (bytes, n) = (output(bytes, "bytes")?, output(n, "n")?);
        let stream = loopsurf::stream::to_bytes(surface);
        *bytes = malloc_copy(&stream)?;
        *n = stream.len();
        Ok(())
    })
}

/// Frees a buffer returned by `ls_surface_save` (NULL is ignored); `n` is
/// its length, accepted for symmetry and not needed.
#[no_mangle]
pub unsafe extern "C" fn ls_free_bytes(bytes: *mut u8, n: usize) {
    let _ = n;
    libc::free(bytes as *mut c_void);
}

/// Rebuilds a surface from `n` bytes written by `ls_surface_save` (on any
/// rank or machine of the same byte order). Truncated, damaged or foreign
/// bytes give LS_ERR_BAD_STREAM.
#[no_mangle]
pub unsafe extern "C" fn ls_surface_load(
    bytes: *const u8,
    n: usize,
    out: *mut *mut ls_surface,
) -> c_int {
    run("ls_surface_load", || {
        input(bytes, "bytes")?;
        let out = output(out, "out")?;
        let stream = std::slice::from_raw_parts(bytes, n);
        let surface = loopsurf::stream::from_bytes(stream)?;
        *out = Box::into_raw(Box::new(ls_surface(surface)));
        Ok(())
    })
}
