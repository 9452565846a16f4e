//! `ls_mesh`: the surface mesher through the C ABI.

use crate::buffers::{Blocks, MeshArrays};
use crate::ls_surface;
use crate::status::{input, output, run, Fail, LS_ERR_INVALID_ARGUMENT};
use loopsurf::{Density, Mesher};
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
        let outs = (
            output(nverts, "nverts")?,
            output(xyz, "xyz")?,
            output(ntris, "ntris")?,
            output(tris, "tris")?,
            output(vertex_tri, "vertex_tri")?,
            output(vertex_vw, "vertex_vw")?,
        );
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
        *outs.0 = mesh.points.len();
        *outs.1 = arrays.xyz;
        *outs.2 = mesh.triangles.len();
        *outs.3 = arrays.tris;
        *outs.4 = arrays.vertex_tri;
        *outs.5 = arrays.vertex_vw;
        if !tri_chart.is_null() {
            *tri_chart = charts_out;
        }
        if !tri_vw.is_null() {
            *tri_vw = corners_out;
        }
        Ok(())
    })
}
