//! `ls_mesh` and `ls_remesh`: the chart mesher and the quality remesher
//! through the C ABI, and the model labels of a mesh on the surface
//! (`ls_mesh_face_labels`, `ls_mesh_hard_edges`).
//!
//! The labels are separate functions over ls_mesh's arrays rather than
//! more outputs of ls_mesh (13 arguments already): they keep ls_mesh as it
//! is, cost nothing to callers who do not want them, and apply to any mesh
//! whose vertices carry their (tri, v, w), e.g. ls_adapt's.

use crate::buffers::{Blocks, MeshArrays, MeshOutputs};
use crate::ls_surface;
use crate::status::{input, output, run, Fail, LS_ERR_INDEX_OUT_OF_RANGE, LS_ERR_INVALID_ARGUMENT};
use loopsurf::remesh::DEFAULT_GRADATION;
use loopsurf::{Density, Mesher, Remesher, SurfacePoint};
use std::ffi::c_int;

/// Meshes the limit surface (see `loopsurf mesh`). Density: `uniform` N ≥ 1
/// cuts every control edge into N segments, else `size` > 0 is a target
/// edge length in model units, else the tolerance alone decides (pass 0 for
/// the ones not used). `tolerance` in (0, 1), relative to the bounding-box
/// diagonal, bounds the chord error (0: none). `adapt_curvature` nonzero lets
/// the density follow curvature, bounded by the tolerance (1e-3 when 0).
///
/// Writes `nverts`, `xyz` (3 × nverts), `ntris`, `tris` (3 × ntris, 0-based,
/// counter-clockwise like the net) and, per vertex, `vertex_tri` (nverts)
/// and `vertex_vw` (2 × nverts): `ls_evaluate(vertex_tri[i], vw[2i],
/// vw[2i+1])` is vertex i. Optional (NULL to skip): `tri_chart` (ntris), the
/// control triangle holding each output triangle, and `tri_vw` (6 × ntris),
/// its corners' (v, w) in that control triangle — the map a high-order code
/// curves the triangle with. Release every array with `ls_free_array`.
#[no_mangle]
pub unsafe extern "C" fn ls_mesh(
    surface: *const ls_surface,
    uniform: c_int,
    size: f64,
    tolerance: f64,
    adapt_curvature: c_int,
    nverts: *mut usize,
    xyz: *mut *mut f64,
    ntris: *mut usize,
    tris: *mut *mut i32,
    vertex_tri: *mut *mut i32,
    vertex_vw: *mut *mut f64,
    tri_chart: *mut *mut i32,
    tri_vw: *mut *mut f64,
) -> c_int {
    run("ls_mesh", || {
        let surface = &input(surface, "surface")?.0;
        let outs = MeshOutputs::check(nverts, xyz, ntris, tris, vertex_tri, vertex_vw)?;
        let bad = |m: String| Err(Fail::new(LS_ERR_INVALID_ARGUMENT, m));
        if uniform < 0 {
            return bad(format!("uniform = {uniform}: must be ≥ 1, or 0 for none"));
        }
        if size != 0.0 && uniform != 0 {
            return bad("uniform and size exclude each other: pass 0 for one".into());
        }
        if tolerance < 0.0 || size < 0.0 {
            return bad(format!(
                "size = {size}, tolerance = {tolerance}: must be positive, or 0 for none"
            ));
        }
        let density = if uniform > 0 {
            Density::Uniform(uniform as u32)
        } else if size != 0.0 {
            Density::Size(size)
        } else {
            Density::FromTolerance
        };
        let mut mesher = Mesher::new(surface)
            .density(density)
            .adapt_curvature(adapt_curvature != 0);
        if tolerance != 0.0 {
            mesher = mesher.tolerance(tolerance);
        }
        let mesh = mesher.run()?;
        let mut blocks = Blocks::default();
        let arrays = MeshArrays::copy(&mut blocks, &mesh.points, &mesh.triangles, &mesh.params)?;
        let charts_out = if tri_chart.is_null() {
            std::ptr::null_mut()
        } else {
            let chart: Vec<i32> = mesh.charts.iter().map(|&c| c as i32).collect();
            blocks.copy(&chart)?
        };
        let corners_out = if tri_vw.is_null() {
            std::ptr::null_mut()
        } else {
            let net = surface.net();
            let corners: Vec<f64> = (0..mesh.triangles.len())
                .flat_map(|t| {
                    mesh.triangle_params(net, t)
                        .into_iter()
                        .flat_map(|p| [p.v, p.w])
                })
                .collect();
            blocks.copy(&corners)?
        };
        blocks.hand_over();
        outs.write(arrays, mesh.points.len(), mesh.triangles.len());
        if !tri_chart.is_null() {
            *tri_chart = charts_out;
        }
        if !tri_vw.is_null() {
            *tri_vw = corners_out;
        }
        Ok(())
    })
}

/// The quality remesher (the default of `loopsurf mesh`): near-equilateral
/// triangles on the limit surface, free across control triangles, so their
/// shapes do not copy the net's. Every vertex is the surface at its (tri,
/// v, w), corners stay, crease and boundary vertices lie on their exact
/// curves with chains of edges along them, and every triangle lies in one
/// model face.
///
/// Density: `size` > 0 is the target edge length in model units (0: none).
/// `tolerance` in (0, 1), relative to the bounding-box diagonal, bounds the
/// chord error (0: none): it is measured after meshing and the sizes shrink
/// where it is exceeded, a few rounds at most. `adapt_curvature` 1 sizes
/// the edges from the exact principal curvatures under the tolerance (1e-3
/// when 0), capped by `size` when given; 0 keeps `size` everywhere unless
/// a tolerance is given: any tolerance adapts to curvature the same way. `gradation` > 1 bounds the
/// ratio of neighbouring sizes per edge when adapting (0: the default, 1.3).
///
/// Writes `nverts`, `xyz` (3 × nverts), `ntris`, `tris` (3 × ntris, 0-based,
/// counter-clockwise like the net) and, per vertex, `vertex_tri` (nverts)
/// and `vertex_vw` (2 × nverts): `ls_evaluate(vertex_tri[i], vw[2i],
/// vw[2i+1])` is vertex i. Optional (NULL to skip): `tri_face` (ntris), the
/// model face of each triangle (as `ls_model_*` number faces), and
/// `deviation`, the largest chord error measured, relative to the diagonal
/// (compare it with `tolerance`: a few edges may be stuck longer, e.g. at
/// a cusp), or -1 when no tolerance applied (`tolerance` and
/// `adapt_curvature` both 0). There is no `tri_chart`: a triangle may span
/// several control triangles. Release every array with `ls_free_array`;
/// nothing is written on failure.
///
/// Budget: a density asking for more than 20 million triangles (about
/// 8 GB while remeshing) fails with `LS_ERR_INVALID_ARGUMENT`, and
/// `ls_last_error` says how many it asked for, before the memory is spent.
///
/// Hard edges: `ls_mesh_hard_edges` on this mesh gives its edges along the
/// curves, with their curves and parameters, from `vertex_tri`,
/// `vertex_vw` and `tris` alone.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh(
    surface: *const ls_surface,
    size: f64,
    tolerance: f64,
    adapt_curvature: c_int,
    gradation: f64,
    nverts: *mut usize,
    xyz: *mut *mut f64,
    ntris: *mut usize,
    tris: *mut *mut i32,
    vertex_tri: *mut *mut i32,
    vertex_vw: *mut *mut f64,
    tri_face: *mut *mut i32,
    deviation: *mut f64,
) -> c_int {
    run("ls_remesh", || {
        let surface = &input(surface, "surface")?.0;
        let outs = MeshOutputs::check(nverts, xyz, ntris, tris, vertex_tri, vertex_vw)?;
        let bad = |m: String| Err(Fail::new(LS_ERR_INVALID_ARGUMENT, m));
        if !(size.is_finite() && size >= 0.0) {
            return bad(format!("size = {size}: must be positive, or 0 for none"));
        }
        if !(0.0..1.0).contains(&tolerance) {
            return bad(format!(
                "tolerance = {tolerance}: must lie in (0, 1), or be 0 for none"
            ));
        }
        let adapt = match adapt_curvature {
            0 => false,
            1 => true,
            _ => {
                return bad(format!(
                    "adapt_curvature = {adapt_curvature}: must be 0 or 1"
                ))
            }
        };
        let gradation = if gradation == 0.0 {
            DEFAULT_GRADATION
        } else if gradation.is_finite() && gradation > 1.0 {
            gradation
        } else {
            return bad(format!(
                "gradation = {gradation}: must be greater than 1, or 0 for the default"
            ));
        };
        let mut remesher = Remesher::new(surface)
            .adapt_curvature(adapt)
            .gradation(gradation);
        if size != 0.0 {
            remesher = remesher.size(size);
        }
        if tolerance != 0.0 {
            remesher = remesher.tolerance(tolerance);
        }
        let mesh = remesher.run()?;
        let mut blocks = Blocks::default();
        let arrays = MeshArrays::copy(&mut blocks, &mesh.points, &mesh.triangles, &mesh.params)?;
        let faces_out = if tri_face.is_null() {
            std::ptr::null_mut()
        } else {
            let faces: Vec<i32> = mesh.faces.iter().map(|&f| f as i32).collect();
            blocks.copy(&faces)?
        };
        blocks.hand_over();
        outs.write(arrays, mesh.points.len(), mesh.triangles.len());
        if !tri_face.is_null() {
            *tri_face = faces_out;
        }
        if !deviation.is_null() {
            *deviation = mesh.deviation.map_or(-1.0, |d| d / mesh.diagonal);
        }
        Ok(())
    })
}

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
                let t = crate::surface::query(surface, vertex_tri[i], v, w).map_err(at)?;
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
