//! `ls_remesh`: the quality remesher through the C ABI.

use crate::mesh::{budget, flag};
use crate::status::LS_ERR_INVALID_ARGUMENT;
use crate::status::{input, output, read_options, run, write_defaults, Fail, Options};
use crate::surface::ls_surface;
use crate::trimesh::{c_ints, ls_trimesh};
use loopsurf::mesh::DEFAULT_ADAPT_TOLERANCE;
use loopsurf::remesh::{DEFAULT_GRADATION, DEFAULT_MAX_TRIANGLES};
use loopsurf::{Remesher, Surface, SurfaceMesh};
use std::ffi::c_int;

/// Options of `ls_remesh`: fill with `ls_remesh_options_default`, then
/// change what you need. Give a size, a tolerance, or both.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_remesh_options {
    /// `sizeof(ls_remesh_options)` as the caller was compiled with.
    pub struct_size: usize,
    /// Target edge length in model units (> 0), the cap when adapting; or
    /// 0 for none. Default 0.
    pub size: f64,
    /// Chord error bound relative to the bounding-box diagonal, in (0, 1),
    /// or 0 for none: it is measured after meshing and the sizes shrink
    /// where it is exceeded, a few rounds at most. Any tolerance sizes the
    /// edges from the exact principal curvatures. Default 1e-3.
    pub tolerance: f64,
    /// 1: sizes from the exact principal curvatures under the tolerance
    /// (1e-3 when none), capped by `size` when given; 0: `size` everywhere
    /// unless a tolerance is given. Default 1.
    pub adapt_curvature: c_int,
    /// The largest ratio of neighbouring sizes per edge when adapting
    /// (> 1). Default 1.3.
    pub gradation: f64,
    /// The most triangles the mesh may have (≥ 1); a density asking for
    /// more fails with LS_ERR_OVER_BUDGET, and `ls_last_error` says how
    /// many it asked for, before the memory is spent. Default 20 million
    /// (about 8 GB remeshing a small net whole; more in parts on a large
    /// net: docs/remesher.md, "The triangle budget").
    pub max_triangles: usize,
    /// Remesh in this many parts of the control net (METIS), each on its
    /// own thread, joined along interfaces meshed first and then moved;
    /// the mesh is the same for any thread count. 1 remeshes whole. Added
    /// after the first release: a caller compiled without it gets 1.
    /// Default 1.
    pub parts: usize,
    /// Threads this call may use: 0 for the library's pool (as many as
    /// `RAYON_NUM_THREADS` says, else one per core), N for at most N. The
    /// mesh is the same for any count. Added with `parts`. Default 0.
    pub threads: usize,
}

impl Options for ls_remesh_options {
    const FIRST_SIZE: usize = std::mem::offset_of!(ls_remesh_options, parts);
    fn defaults() -> Self {
        ls_remesh_options {
            struct_size: std::mem::size_of::<ls_remesh_options>(),
            size: 0.0,
            tolerance: DEFAULT_ADAPT_TOLERANCE,
            adapt_curvature: 1,
            gradation: DEFAULT_GRADATION,
            max_triangles: DEFAULT_MAX_TRIANGLES,
            parts: 1,
            threads: 0,
        }
    }
}

/// Writes the default options of `ls_remesh` into `options`.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh_options_default(options: *mut ls_remesh_options) -> c_int {
    write_defaults("ls_remesh_options_default", options)
}

/// The quality remesher (the default of `loopsurf mesh`): near-equilateral
/// triangles on the limit surface, free across control triangles, so their
/// shapes do not copy the net's. Every node is the surface at its (tri,
/// v, w), corners stay, crease and boundary nodes lie on their exact
/// curves with chains of edges along them, and every triangle lies in one
/// model face. `options` may be NULL for the defaults.
///
/// On success `*mesh` is a new `ls_trimesh` of straight triangles with
/// node parameters, element faces and, under a tolerance, the measured
/// deviation (no element charts: a triangle may span several control
/// triangles); release it with `ls_trimesh_free`. `ls_mesh_hard_edges`
/// gives its edges along the curves.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh(
    surface: *const ls_surface,
    options: *const ls_remesh_options,
    mesh: *mut *mut ls_trimesh,
) -> c_int {
    run("ls_remesh", || {
        let surface = &input(surface, "surface")?.0;
        let o = read_options(options, "options")?;
        let out = output(mesh, "mesh")?;
        let remesher = remesher(surface, &o)?;
        let made = match pool(o.threads)? {
            None => remesher.run()?,
            Some(pool) => pool.install(|| remesher.run())?,
        };
        let result = trimesh_of(&made)?;
        result.hand_over(out);
        Ok(())
    })
}

/// The number of parts worth remeshing in with `options` (their `parts`
/// ignored): one per 30 000 triangles the sizes ask for over the whole
/// surface, at most 64 and with at least 16 control triangles each,
/// rounded down to a power of two; 1, whole, below 60 000. `loopsurf mesh` remeshes in that many unless
/// told. It depends on the surface and the options alone, never on the
/// threads, so the mesh is the same on any machine. `options` may be
/// NULL for the defaults. On success `*parts` is written.
#[no_mangle]
pub unsafe extern "C" fn ls_remesh_suggested_parts(
    surface: *const ls_surface,
    options: *const ls_remesh_options,
    parts: *mut usize,
) -> c_int {
    run("ls_remesh_suggested_parts", || {
        let surface = &input(surface, "surface")?.0;
        let o = ls_remesh_options {
            parts: 1,
            ..read_options(options, "options")?
        };
        let out = output(parts, "parts")?;
        let k = remesher(surface, &o)?.suggested_parts()?;
        *out = k;
        Ok(())
    })
}

/// The remesher `o` describes, its values checked.
pub(crate) fn remesher<'a>(
    surface: &'a Surface,
    o: &ls_remesh_options,
) -> Result<Remesher<'a>, Fail> {
    let bad = |m: String| Err(Fail::new(LS_ERR_INVALID_ARGUMENT, m));
    if !(o.size.is_finite() && o.size >= 0.0) {
        return bad(format!(
            "size = {}: must be positive, or 0 for none",
            o.size
        ));
    }
    if !(0.0..1.0).contains(&o.tolerance) {
        return bad(format!(
            "tolerance = {}: must lie in (0, 1), or be 0 for none",
            o.tolerance
        ));
    }
    if !(o.gradation.is_finite() && o.gradation > 1.0) {
        return bad(format!(
            "gradation = {}: must be greater than 1",
            o.gradation
        ));
    }
    if o.parts == 0 {
        return bad("parts = 0: must be at least 1".into());
    }
    let mut remesher = Remesher::new(surface)
        .parts(o.parts)
        .adapt_curvature(flag(o.adapt_curvature, "adapt_curvature")?)
        .gradation(o.gradation)
        .max_triangles(budget(o.max_triangles)?);
    if o.size != 0.0 {
        remesher = remesher.size(o.size);
    }
    if o.tolerance != 0.0 {
        remesher = remesher.tolerance(o.tolerance);
    }
    Ok(remesher)
}

/// A pool of `threads` threads, or none (0) for the library's own.
pub(crate) fn pool(threads: usize) -> Result<Option<rayon::ThreadPool>, Fail> {
    match threads {
        0 => Ok(None),
        n => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map(Some)
            .map_err(|e| Fail::new(LS_ERR_INVALID_ARGUMENT, format!("threads = {n}: {e}"))),
    }
}

/// A remeshed mesh as an `ls_trimesh`: straight triangles, node
/// parameters, element faces and the measured deviation.
pub(crate) fn trimesh_of(made: &SurfaceMesh) -> Result<ls_trimesh, Fail> {
    let mut result = ls_trimesh::straight(&made.points, &made.triangles, &made.params)?;
    result.element_face = Some(c_ints(&made.faces));
    result.deviation = made.deviation.map(|d| d / made.diagonal);
    Ok(result)
}
