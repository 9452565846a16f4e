//! `ls_adapt`: adaptive Loop subdivision (Liu & Kondo's conical-angle
//! criterion, and a distance to the limit surface) through the C ABI.

use crate::mesh::{budget, flag};
use crate::refine::levels_arg;
use crate::status::LS_ERR_INVALID_ARGUMENT;
use crate::status::{input, output, read_options, run, write_defaults, Fail, Options};
use crate::surface::ls_surface;
use crate::trimesh::ls_trimesh;
use std::ffi::c_int;

/// The adaptive subdivider's default triangle budget: 200 million.
const ADAPT_MAX_TRIANGLES: usize = 200_000_000;

/// Options of `ls_adapt`: fill with `ls_adapt_options_default`, then
/// change what you need. At least one criterion (angle or tolerance) is
/// needed.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_adapt_options {
    /// `sizeof(ls_adapt_options)` as the caller was compiled with.
    pub struct_size: usize,
    /// Refinement stops where the conical angle of the face normals at
    /// every neighbour of a vertex is below this many degrees, in
    /// [0, 180) (0: uniform subdivision); negative: no angle criterion.
    /// Default 10.
    pub angle: f64,
    /// Refinement also stops where the mesh is within this fraction of
    /// the bounding-box diagonal of the limit surface, in (0, 1); 0: no
    /// such criterion. Default 0.
    pub tolerance: f64,
    /// Subdivision levels, 0 to 10. Default 3.
    pub levels: c_int,
    /// 1: every vertex is moved onto the limit surface; 0: vertices stay
    /// where subdivision puts them. Default 0.
    pub to_limit: c_int,
    /// The most triangles a level may reach (≥ 1); a level that could
    /// pass it fails with LS_ERR_OVER_BUDGET before it is built. Default
    /// 200 million.
    pub max_triangles: usize,
}

impl Options for ls_adapt_options {
    const FIRST_SIZE: usize = std::mem::size_of::<ls_adapt_options>();
    fn defaults() -> Self {
        ls_adapt_options {
            struct_size: std::mem::size_of::<ls_adapt_options>(),
            angle: 10.0,
            tolerance: 0.0,
            levels: 3,
            to_limit: 0,
            max_triangles: ADAPT_MAX_TRIANGLES,
        }
    }
}

/// Writes the default options of `ls_adapt` into `options`.
#[no_mangle]
pub unsafe extern "C" fn ls_adapt_options_default(options: *mut ls_adapt_options) -> c_int {
    write_defaults("ls_adapt_options_default", options)
}

/// Adaptive Loop subdivision of the surface's control net (see `loopsurf
/// adapt`): conforming, with the hard edges kept. `options` may be NULL
/// for the defaults. On success `*mesh` is a new `ls_trimesh` of straight
/// triangles whose node parameters are the control triangle and exact
/// dyadic (v, w) each vertex stands for (`ls_evaluate` there is its limit
/// position); release it with `ls_trimesh_free`.
#[no_mangle]
pub unsafe extern "C" fn ls_adapt(
    surface: *const ls_surface,
    options: *const ls_adapt_options,
    mesh: *mut *mut ls_trimesh,
) -> c_int {
    run("ls_adapt", || {
        let surface = &input(surface, "surface")?.0;
        let o = read_options(options, "options")?;
        let out = output(mesh, "mesh")?;
        if o.angle.is_nan() || o.tolerance.is_nan() {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("angle = {}, tolerance = {}: NaN", o.angle, o.tolerance),
            ));
        }
        let mut adapter = loopsurf::Adapter::new(surface.net())
            .levels(levels_arg(o.levels)?)
            .max_triangles(budget(o.max_triangles)?);
        if surface.mode() == loopsurf::SurfaceMode::Approximating {
            // The net's own limit surface: the conical angle at hard edges
            // measures against it instead of building one.
            adapter = adapter.limit_surface(surface);
        }
        if o.angle >= 0.0 {
            adapter = adapter.angle(o.angle);
        }
        if o.tolerance != 0.0 {
            adapter = adapter.tolerance(surface, o.tolerance);
        }
        let to_limit = flag(o.to_limit, "to_limit")?;
        let adapted = adapter.run()?;
        let limits;
        let points = if to_limit {
            limits = adapted.limit_points(surface)?;
            &limits[..]
        } else {
            adapted.net.points()
        };
        ls_trimesh::straight(points, adapted.net.triangles(), &adapted.params)?.hand_over(out);
        Ok(())
    })
}
