//! `ls_mesh`: the chart mesher through the C ABI — each control
//! triangle cut into a conforming pattern, so every output triangle lies
//! in one control triangle (its chart).

use crate::status::LS_ERR_INVALID_ARGUMENT;
use crate::status::{input, output, read_options, run, write_defaults, Fail, Options};
use crate::surface::ls_surface;
use crate::trimesh::{c_ints, ls_trimesh};
use loopsurf::mesh::DEFAULT_ADAPT_TOLERANCE;
use loopsurf::{Density, Mesher};
use std::ffi::c_int;

/// The chart mesher's default triangle budget: 200 million.
const MESH_MAX_TRIANGLES: usize = 200_000_000;

/// Options of `ls_mesh`: fill with `ls_mesh_options_default`, then change
/// what you need. The density comes from `uniform`, else `size`, else the
/// tolerance alone.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_mesh_options {
    /// `sizeof(ls_mesh_options)` as the caller was compiled with.
    pub struct_size: usize,
    /// Cut every control edge into this many segments (≥ 1), or 0 for
    /// none. Default 0.
    pub uniform: c_int,
    /// Target edge length in model units (> 0), or 0 for none; excludes
    /// `uniform`. Default 0.
    pub size: f64,
    /// Chord error bound, relative to the bounding-box diagonal, in
    /// (0, 1), or 0 for none. Default 1e-3.
    pub tolerance: f64,
    /// 1: the density follows curvature, bounded by the tolerance (1e-3
    /// when none); 0: it does not. Default 1.
    pub adapt_curvature: c_int,
    /// The most triangles the mesh may have (≥ 1); a density asking for
    /// more fails with LS_ERR_OVER_BUDGET before the memory is spent.
    /// Default 200 million.
    pub max_triangles: usize,
}

impl Options for ls_mesh_options {
    const FIRST_SIZE: usize = std::mem::size_of::<ls_mesh_options>();
    fn defaults() -> Self {
        ls_mesh_options {
            struct_size: std::mem::size_of::<ls_mesh_options>(),
            uniform: 0,
            size: 0.0,
            tolerance: DEFAULT_ADAPT_TOLERANCE,
            adapt_curvature: 1,
            max_triangles: MESH_MAX_TRIANGLES,
        }
    }
}

/// Writes the default options of `ls_mesh` into `options`.
#[no_mangle]
pub unsafe extern "C" fn ls_mesh_options_default(options: *mut ls_mesh_options) -> c_int {
    write_defaults("ls_mesh_options_default", options)
}

/// A 0-or-1 flag of an options struct.
pub(crate) fn flag(value: c_int, name: &str) -> Result<bool, Fail> {
    match value {
        0 => Ok(false),
        1 => Ok(true),
        _ => Err(Fail::new(
            LS_ERR_INVALID_ARGUMENT,
            format!("{name} = {value}: must be 0 or 1"),
        )),
    }
}

/// A triangle budget of an options struct.
pub(crate) fn budget(max_triangles: usize) -> Result<usize, Fail> {
    if max_triangles == 0 {
        return Err(Fail::new(
            LS_ERR_INVALID_ARGUMENT,
            "max_triangles = 0: must be at least 1",
        ));
    }
    Ok(max_triangles)
}

/// Meshes the limit surface with the chart mesher (`loopsurf mesh
/// --chart`): every triangle lies in one control triangle, and every
/// vertex is the surface at its (tri, v, w). `options` may be NULL for the
/// defaults. On success `*mesh` is a new `ls_trimesh` of straight
/// triangles with node parameters, element faces and element charts;
/// release it with `ls_trimesh_free`.
#[no_mangle]
pub unsafe extern "C" fn ls_mesh(
    surface: *const ls_surface,
    options: *const ls_mesh_options,
    mesh: *mut *mut ls_trimesh,
) -> c_int {
    run("ls_mesh", || {
        let surface = &input(surface, "surface")?.0;
        let o = read_options(options, "options")?;
        let out = output(mesh, "mesh")?;
        let bad = |m: String| Err(Fail::new(LS_ERR_INVALID_ARGUMENT, m));
        if o.uniform < 0 {
            return bad(format!(
                "uniform = {}: must be ≥ 1, or 0 for none",
                o.uniform
            ));
        }
        if o.size != 0.0 && o.uniform != 0 {
            return bad("uniform and size exclude each other: set one to 0".into());
        }
        if !(o.tolerance >= 0.0 && o.size >= 0.0) {
            return bad(format!(
                "size = {}, tolerance = {}: must be positive, or 0 for none",
                o.size, o.tolerance
            ));
        }
        let density = if o.uniform > 0 {
            Density::Uniform(o.uniform as u32)
        } else if o.size != 0.0 {
            Density::Size(o.size)
        } else {
            Density::FromTolerance
        };
        let mut mesher = Mesher::new(surface)
            .density(density)
            .adapt_curvature(flag(o.adapt_curvature, "adapt_curvature")?)
            .max_triangles(budget(o.max_triangles)?);
        if o.tolerance != 0.0 {
            mesher = mesher.tolerance(o.tolerance);
        }
        let made = mesher.run()?;
        let net = surface.net();
        let mut result = ls_trimesh::straight(&made.points, &made.triangles, &made.params)?;
        result.element_face = Some(c_ints(&made.faces));
        result.element_chart = Some(c_ints(&made.charts));
        result.element_chart_vw = Some(
            (0..made.triangles.len())
                .flat_map(|t| {
                    made.triangle_params(net, t)
                        .into_iter()
                        .flat_map(|p| [p.v, p.w])
                })
                .collect(),
        );
        result.hand_over(out);
        Ok(())
    })
}
