//! `ls_mesh_curve`: a linear surface mesh made by another tool, put onto
//! the surface and raised to curved Lagrange elements (`loopsurf curve`).

use crate::mesh_labels::slice;
use crate::status::{input, output, read_options, run, write_defaults, Fail, Options};
use crate::status::{LS_ERR_INDEX_OUT_OF_RANGE, LS_ERR_INVALID_ARGUMENT};
use crate::surface::ls_surface;
use crate::trimesh::{c_ints, ls_trimesh};
use loopsurf::mesh::high_order::{nodes_per_triangle, onto_surface, DEFAULT_MAX_MOVE, MAX_ORDER};
use loopsurf::DVec3;
use std::ffi::c_int;

/// Options of `ls_mesh_curve`: fill with `ls_mesh_curve_options_default`,
/// then change what you need.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_mesh_curve_options {
    /// `sizeof(ls_mesh_curve_options)` as the caller was compiled with.
    pub struct_size: usize,
    /// The order of the Lagrange triangles, 1 to 4. Default 2.
    pub order: c_int,
    /// How far a vertex may move onto the surface, relative to the
    /// bounding-box diagonal, in (0, 1]: a vertex farther from the surface
    /// is refused with an error naming it (another model, other units).
    /// Default 0.01.
    pub max_move: f64,
}

impl Options for ls_mesh_curve_options {
    const FIRST_SIZE: usize = std::mem::size_of::<ls_mesh_curve_options>();
    fn defaults() -> Self {
        ls_mesh_curve_options {
            struct_size: std::mem::size_of::<ls_mesh_curve_options>(),
            order: 2,
            max_move: DEFAULT_MAX_MOVE,
        }
    }
}

/// Writes the default options of `ls_mesh_curve` into `options`.
#[no_mangle]
pub unsafe extern "C" fn ls_mesh_curve_options_default(
    options: *mut ls_mesh_curve_options,
) -> c_int {
    write_defaults("ls_mesh_curve_options_default", options)
}

/// Curves a linear mesh made by another tool: its `nverts` vertices `xyz`
/// (3 × nverts) and `ntris` triangles `tris` (3 × ntris, 0-based,
/// counter-clockwise like the net). Every vertex goes to its certified
/// closest point on the surface, every triangle takes the model face of
/// its centroid's closest point, edges between two faces (or on the
/// boundary) onto their model curve, and each triangle becomes a Lagrange
/// triangle of the options' order with every node on the surface.
/// `options` may be NULL for the defaults.
///
/// On success `*mesh` is a new `ls_trimesh`: the input vertices are its
/// first nodes, in order; edge nodes are shared by both triangles of an
/// edge; it has node parameters, element faces, the largest vertex move
/// and the smallest scaled Jacobian. Release it with `ls_trimesh_free`.
#[no_mangle]
pub unsafe extern "C" fn ls_mesh_curve(
    surface: *const ls_surface,
    nverts: usize,
    xyz: *const f64,
    ntris: usize,
    tris: *const i32,
    options: *const ls_mesh_curve_options,
    mesh: *mut *mut ls_trimesh,
) -> c_int {
    run("ls_mesh_curve", || {
        let surface = &input(surface, "surface")?.0;
        let o = read_options(options, "options")?;
        let out = output(mesh, "mesh")?;
        let bad = |m: String| Fail::new(LS_ERR_INVALID_ARGUMENT, m);
        let order = usize::try_from(o.order)
            .ok()
            .filter(|k| (1..=MAX_ORDER).contains(k))
            .ok_or_else(|| bad(format!("order = {}: must be 1 to {MAX_ORDER}", o.order)))?;
        if !(o.max_move > 0.0 && o.max_move <= 1.0) {
            return Err(bad(format!(
                "max_move = {}: must lie in (0, 1]",
                o.max_move
            )));
        }
        let coords = slice(xyz, nverts, 3, "xyz")?;
        let indices = slice(tris, ntris, 3, "tris")?;
        let points: Vec<DVec3> = coords.chunks(3).map(DVec3::from_slice).collect();
        let triangles = indices
            .chunks(3)
            .enumerate()
            .map(|(t, c)| {
                let tri = [c[0], c[1], c[2]];
                match tri.iter().find(|&&i| i < 0 || i as usize >= nverts) {
                    Some(&i) => Err(Fail::new(
                        LS_ERR_INDEX_OUT_OF_RANGE,
                        format!("triangle {t} {tri:?} refers to vertex {i}, but there are {nverts} vertices"),
                    )),
                    None => Ok(tri.map(|i| i as u32)),
                }
            })
            .collect::<Result<Vec<_>, Fail>>()?;
        let onto = onto_surface(surface, &points, &triangles, o.max_move)?;
        let curved = onto.mesh.raise_order(surface, order)?;
        let mut result = ls_trimesh::new(
            &curved.nodes,
            curved.triangles.iter().copied(),
            &curved.params,
            nodes_per_triangle(curved.order),
        )?;
        result.element_face = Some(c_ints(&curved.faces));
        result.largest_move = Some(onto.largest_move);
        result.curved = Some(curved);
        result.hand_over(out);
        Ok(())
    })
}
