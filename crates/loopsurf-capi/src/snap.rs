//! The certified snap with options and a result record, so that both can
//! grow without breaking callers (`struct_size` says which fields a caller
//! knows). `ls_snap` and `ls_snap_guess` stay as they were, and are
//! certified too, at the default tolerance.

use crate::closest::point;
use crate::status::LS_ERR_INVALID_ARGUMENT;
use crate::status::{input, output, read_options, run, write_defaults, Fail, Options};
use crate::surface::ls_surface;
use std::ffi::c_int;

/// Options of `ls_snap_certified`: fill with `ls_snap_options_default`,
/// then change what you need.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_snap_options {
    /// `sizeof(ls_snap_options)` as the caller was compiled with.
    pub struct_size: usize,
    /// How close the certificate must come to the distance, as a fraction
    /// of the control net's bounding-box diagonal, in (0, 1); default 1e-12.
    /// Looser is faster.
    pub tolerance: f64,
}

/// The answer of `ls_snap_certified`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_snap_result {
    /// `sizeof(ls_snap_result)` as the caller was compiled with: set it
    /// before the call; fields beyond it are not written.
    pub struct_size: usize,
    /// Control triangle (0-based) and parameters of the closest point.
    pub tri: i32,
    pub vw: [f64; 2],
    /// The closest point, the surface at (tri, v, w) bit for bit.
    pub xyz: [f64; 3],
    /// Its distance to the query point.
    pub distance: f64,
    /// A proven lower bound on the distance from the query point to the
    /// whole surface: distance - lower_bound <= tolerance * diagonal.
    pub lower_bound: f64,
}

impl Options for ls_snap_options {
    const FIRST_SIZE: usize = std::mem::size_of::<ls_snap_options>();
    fn defaults() -> Self {
        ls_snap_options {
            struct_size: std::mem::size_of::<ls_snap_options>(),
            tolerance: loopsurf::snap::DEFAULT_TOLERANCE,
        }
    }
}

/// Writes the default options (tolerance 1e-12) into `options`.
#[no_mangle]
pub unsafe extern "C" fn ls_snap_options_default(options: *mut ls_snap_options) -> c_int {
    write_defaults("ls_snap_options_default", options)
}

/// The closest point of the limit surface to `xyz` — the global minimum of
/// the distance — with a proven lower bound on the distance to the whole
/// surface (the certificate). `options` may be NULL for the defaults.
#[no_mangle]
pub unsafe extern "C" fn ls_snap_certified(
    surface: *const ls_surface,
    xyz: *const f64,
    options: *const ls_snap_options,
    result: *mut ls_snap_result,
) -> c_int {
    run("ls_snap_certified", || {
        let surface = &input(surface, "surface")?.0;
        let p = point(xyz)?;
        let tolerance = read_options(options, "options")?.tolerance;
        let result = output(result, "result")?;
        known_size::<ls_snap_result>((*result).struct_size, "result")?;
        let s = loopsurf::snap::closest_point_within(surface, p, tolerance)?;
        *result = ls_snap_result {
            struct_size: (*result).struct_size,
            tri: s.tri as i32,
            vw: [s.v, s.w],
            xyz: s.point.to_array(),
            distance: s.distance,
            lower_bound: s.lower_bound,
        };
        Ok(())
    })
}

/// A struct from a caller compiled against this version or a later one
/// (which may have added fields at the end).
fn known_size<T>(struct_size: usize, what: &str) -> Result<(), Fail> {
    if struct_size < std::mem::size_of::<T>() {
        return Err(Fail::new(
            LS_ERR_INVALID_ARGUMENT,
            format!(
                "{what}: struct_size {struct_size} is smaller than this library's {} (set it to sizeof, or fill the options with ls_snap_options_default)",
                std::mem::size_of::<T>()
            ),
        ));
    }
    Ok(())
}
