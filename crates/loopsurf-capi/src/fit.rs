//! `ls_net_fit`: a fitted control net (`loopsurf::fit`) through the C ABI.

use crate::net::ls_net;
use crate::status::LS_ERR_INVALID_ARGUMENT;
use crate::status::{input, output, read_options, run, write_defaults, Fail, Options};
use loopsurf::fit::{DEFAULT_RESOLUTION, DEFAULT_TOLERANCE};
use loopsurf::Fitter;
use std::ffi::c_int;

/// Options of `ls_net_fit`: fill with `ls_fit_options_default`, then change
/// what you need.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_fit_options {
    /// `sizeof(ls_fit_options)` as the caller was compiled with.
    pub struct_size: usize,
    /// Control-edge length of the fitted net relative to the bounding-box
    /// diagonal, in (0, 1). Default 0.01.
    pub resolution: f64,
    /// The largest distance from the fitted limit surface to an input
    /// vertex, relative to the bounding-box diagonal (> 0); a fit that
    /// misses it fails with LS_ERR_INVALID_ARGUMENT and `ls_last_error`
    /// names the vertex and the distance. Default 1e-4.
    pub tolerance: f64,
}

impl Options for ls_fit_options {
    const FIRST_SIZE: usize = std::mem::size_of::<ls_fit_options>();
    fn defaults() -> Self {
        ls_fit_options {
            struct_size: std::mem::size_of::<ls_fit_options>(),
            resolution: DEFAULT_RESOLUTION,
            tolerance: DEFAULT_TOLERANCE,
        }
    }
}

/// Writes the default options of `ls_net_fit` into `options`.
#[no_mangle]
pub unsafe extern "C" fn ls_fit_options_default(options: *mut ls_fit_options) -> c_int {
    write_defaults("ls_fit_options_default", options)
}

/// A new control net whose (approximating) limit surface passes within
/// the tolerance of every vertex of `net`, for CAD tessellations whose own
/// limit surface shrinks the shape: `net`'s surface remeshed into
/// well-shaped triangles at the resolution, its hard edges and corners
/// carried over as tags of the new net (so its creases lie on `net`'s
/// feature lines), and the control points solved for in a few rounds of
/// least squares with a fairness term and parameter correction (see
/// docs/fitting.md). Tag `net`'s hard edges first (`ls_net_tag_by_angle`).
/// `options` may be NULL for the defaults.
///
/// On success `*out` is the new net (release it with `ls_net_free`; build
/// its surface with `ls_surface_build`). A tolerance the fit cannot meet
/// is LS_ERR_INVALID_ARGUMENT, never a worse net.
#[no_mangle]
pub unsafe extern "C" fn ls_net_fit(
    net: *const ls_net,
    options: *const ls_fit_options,
    out: *mut *mut ls_net,
) -> c_int {
    run("ls_net_fit", || {
        let net = &input(net, "net")?.0;
        let o = read_options(options, "options")?;
        let out = output(out, "out")?;
        let bad = |m: String| Err(Fail::new(LS_ERR_INVALID_ARGUMENT, m));
        if !(o.resolution > 0.0 && o.resolution < 1.0) {
            return bad(format!("resolution = {}: must lie in (0, 1)", o.resolution));
        }
        if !(o.tolerance.is_finite() && o.tolerance > 0.0) {
            return bad(format!("tolerance = {}: must be positive", o.tolerance));
        }
        let fit = Fitter::new(net)
            .resolution(o.resolution * net.bbox_diagonal())
            .tolerance(o.tolerance)
            .run()?;
        *out = Box::into_raw(Box::new(ls_net(fit.net)));
        Ok(())
    })
}
