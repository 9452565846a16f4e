//! The model labels of any mesh on the surface, given as arrays: the face
//! of each triangle and the edges along the model's curves.

use crate::buffers::Blocks;
use crate::evaluate::query;
use crate::status::{input, output, run, Fail, LS_ERR_INDEX_OUT_OF_RANGE, LS_ERR_INVALID_ARGUMENT};
use crate::surface::ls_surface;
use loopsurf::SurfacePoint;
use std::ffi::c_int;

/// Borrows `per × n` values; NULL (unless n is 0) and sizes beyond memory
/// are errors. No reference is made from `p` before the size is known good.
pub(crate) unsafe fn slice<'a, T>(
    p: *const T,
    n: usize,
    per: usize,
    what: &str,
) -> Result<&'a [T], Fail> {
    if n == 0 {
        return Ok(&[]);
    }
    input(p, what)?;
    let len = n
        .checked_mul(per)
        .filter(|len| len.saturating_mul(std::mem::size_of::<T>()) <= isize::MAX as usize)
        .ok_or_else(|| {
            Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("{what}: {n} × {per} is too large"),
            )
        })?;
    Ok(std::slice::from_raw_parts(p, len))
}

/// The model face of every triangle of a mesh on the surface: triangle i,
/// inside control triangle `tri_chart[i]` (ls_mesh's `tri_chart`), lies in
/// face `tri_face[i]`, the face of its chart. Faces are the model's
/// (`ls_model_*`): maximal sets of control triangles connected across soft
/// edges, numbered by their first control triangle. `tri_face` is the
/// caller's array of `ntris` values, written only on success; the arrays
/// may be NULL when `ntris` is 0.
#[no_mangle]
pub unsafe extern "C" fn ls_mesh_face_labels(
    surface: *const ls_surface,
    ntris: usize,
    tri_chart: *const i32,
    tri_face: *mut i32,
) -> c_int {
    run("ls_mesh_face_labels", || {
        let surface = &input(surface, "surface")?.0;
        let charts = slice(tri_chart, ntris, 1, "tri_chart")?;
        if ntris == 0 {
            return Ok(());
        }
        let tri_face = output(tri_face, "tri_face")?;
        let faces = surface.model().face_of_triangle();
        let labels: Vec<i32> = charts
            .iter()
            .enumerate()
            .map(|(i, &c)| {
                usize::try_from(c)
                    .ok()
                    .and_then(|c| faces.get(c))
                    .map(|&f| f as i32)
                    .ok_or_else(|| {
                        Fail::new(
                            LS_ERR_INDEX_OUT_OF_RANGE,
                            format!(
                                "triangle {i}: chart {c} out of range (the net has {} triangles)",
                                faces.len()
                            ),
                        )
                    })
            })
            .collect::<Result<_, _>>()?;
        std::ptr::copy_nonoverlapping(labels.as_ptr(), tri_face, ntris);
        Ok(())
    })
}

/// The hard edges of a mesh on the surface, with their model curves: the
/// mesh edges whose two ends lie on the same model curve (on its control
/// edges or at its chain vertices, by their (tri, v, w)) and are neighbours
/// along it among the mesh's vertices on that curve. For the output of
/// ls_mesh and ls_remesh these are exactly the output edges along the
/// net's hard edges.
///
/// Input: the mesh as ls_mesh or ls_remesh writes it: `nverts` vertices with their
/// control triangle `vertex_tri` (nverts) and (v, w) `vertex_vw` (2 ×
/// nverts), and `ntris` triangles `tris` (3 × ntris, 0-based).
///
/// Writes `nhard` and new arrays `pairs` (2 × nhard vertex indices) and
/// `curves` (nhard curve ids, as `ls_model_*` number curves) and, unless
/// NULL, `curve_t` (2 × nhard): the curve parameters t of each pair's two
/// vertices, the curve (`ls_curve_evaluate`) at t being the vertex. Each
/// pair runs the way its curve does (t increasing, but for a closed
/// curve's edge across its start), and the pairs are
/// ordered by curve and then by t, so that a curve's edges follow one
/// another from its start to its end. Release the arrays with
/// `ls_free_array`; nothing is written on failure.
#[no_mangle]
pub unsafe extern "C" fn ls_mesh_hard_edges(
    surface: *const ls_surface,
    nverts: usize,
    vertex_tri: *const i32,
    vertex_vw: *const f64,
    ntris: usize,
    tris: *const i32,
    nhard: *mut usize,
    pairs: *mut *mut i32,
    curves: *mut *mut i32,
    curve_t: *mut *mut f64,
) -> c_int {
    run("ls_mesh_hard_edges", || {
        let surface = &input(surface, "surface")?.0;
        let vertex_tri = slice(vertex_tri, nverts, 1, "vertex_tri")?;
        let vertex_vw = slice(vertex_vw, nverts, 2, "vertex_vw")?;
        let tris = slice(tris, ntris, 3, "tris")?;
        let outs = (
            output(nhard, "nhard")?,
            output(pairs, "pairs")?,
            output(curves, "curves")?,
        );
        let params: Vec<SurfacePoint> = (0..nverts)
            .map(|i| {
                let (v, w) = (vertex_vw[2 * i], vertex_vw[2 * i + 1]);
                let at = |fail: Fail| fail.context(&format!("vertex {i}"));
                let t = query(surface, vertex_tri[i], v, w).map_err(at)?;
                surface.validate(t, v, w).map_err(|e| at(Fail::from(e)))?;
                Ok(SurfacePoint {
                    tri: t as u32,
                    v,
                    w,
                })
            })
            .collect::<Result<_, Fail>>()?;
        let triangles: Vec<[u32; 3]> = tris
            .chunks_exact(3)
            .enumerate()
            .map(|(t, c)| {
                let index = |&x: &i32| {
                    u32::try_from(x).ok().filter(|&x| (x as usize) < nverts).ok_or_else(|| {
                        Fail::new(
                            LS_ERR_INDEX_OUT_OF_RANGE,
                            format!(
                                "triangle {t} ({}, {}, {}): vertex {x} out of range (nverts = {nverts})",
                                c[0], c[1], c[2]
                            ),
                        )
                    })
                };
                Ok([index(&c[0])?, index(&c[1])?, index(&c[2])?])
            })
            .collect::<Result<_, Fail>>()?;
        let found = loopsurf::mesh::curve_edges(surface, &params, &triangles)?;
        let flat_pairs: Vec<i32> = found.pairs.iter().flatten().map(|&i| i as i32).collect();
        let ids: Vec<i32> = found.curves.iter().map(|&c| c as i32).collect();
        let mut blocks = Blocks::default();
        let pairs_out = blocks.copy(&flat_pairs)?;
        let curves_out = blocks.copy(&ids)?;
        let t_out = if curve_t.is_null() {
            std::ptr::null_mut()
        } else {
            let t: Vec<f64> = found.params.iter().flatten().copied().collect();
            blocks.copy(&t)?
        };
        blocks.hand_over();
        *outs.0 = found.pairs.len();
        *outs.1 = pairs_out;
        *outs.2 = curves_out;
        if !curve_t.is_null() {
            *curve_t = t_out;
        }
        Ok(())
    })
}
