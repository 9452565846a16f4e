//! `ls_adapt`: adaptive Loop subdivision through the C ABI.

use crate::buffers::{levels_arg, Blocks, MeshArrays, MeshOutputs};
use crate::ls_surface;
use crate::status::{input, run, Fail, LS_ERR_INVALID_ARGUMENT};
use loopsurf::Adapter;
use std::ffi::c_int;

/// Adaptive Loop subdivision of the surface's control net, `levels` times
/// (0 to 10; see `loopsurf adapt`): refinement stops where the conical
/// angle of the face normals at every neighbour of a vertex is below
/// `angle` degrees (0 is uniform subdivision; negative: no angle
/// criterion), and/or where the mesh is within `tolerance` × the
/// bounding-box diagonal of the limit surface (0: none). At least one
/// criterion is needed. The result is conforming and keeps hard edges.
/// With `to_limit` nonzero every vertex is moved onto the limit surface.
///
/// Writes `nverts`, `xyz` (3 × nverts), `ntris`, `tris` (3 × ntris, 0-based,
/// counter-clockwise like the net) and, per vertex, `vertex_tri` (nverts)
/// and `vertex_vw` (2 × nverts): the control triangle and exact dyadic
/// (v, w) the vertex stands for, so `ls_evaluate(vertex_tri[i], vw[2i],
/// vw[2i+1])` is its limit position. Release every array with
/// `ls_free_array`.
#[no_mangle]
pub unsafe extern "C" fn ls_adapt(
    surface: *const ls_surface,
    angle: f64,
    tolerance: f64,
    levels: c_int,
    to_limit: c_int,
    nverts: *mut usize,
    xyz: *mut *mut f64,
    ntris: *mut usize,
    tris: *mut *mut i32,
    vertex_tri: *mut *mut i32,
    vertex_vw: *mut *mut f64,
) -> c_int {
    run("ls_adapt", || {
        let surface = &input(surface, "surface")?.0;
        let outs = MeshOutputs::check(nverts, xyz, ntris, tris, vertex_tri, vertex_vw)?;
        if angle.is_nan() || tolerance.is_nan() {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("angle = {angle}, tolerance = {tolerance}: NaN"),
            ));
        }
        let mut adapter = Adapter::new(surface.net()).levels(levels_arg(levels)?);
        if surface.mode() == loopsurf::SurfaceMode::Approximating {
            // The net's own limit surface: the conical angle at hard edges
            // measures against it instead of building one.
            adapter = adapter.limit_surface(surface);
        }
        if angle >= 0.0 {
            adapter = adapter.angle(angle);
        }
        if tolerance != 0.0 {
            adapter = adapter.tolerance(surface, tolerance);
        }
        let adapted = adapter.run()?;
        let limits;
        let points = if to_limit != 0 {
            limits = adapted.limit_points(surface)?;
            &limits[..]
        } else {
            adapted.net.points()
        };
        let mut blocks = Blocks::default();
        let arrays = MeshArrays::copy(
            &mut blocks,
            points,
            adapted.net.triangles(),
            &adapted.params,
        )?;
        blocks.hand_over();
        outs.write(arrays, points.len(), adapted.net.triangles().len());
        Ok(())
    })
}
