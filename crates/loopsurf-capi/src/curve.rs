//! `ls_curve`: a linear surface mesh made elsewhere, put onto the surface
//! and raised to curved Lagrange elements (`loopsurf curve`).

use crate::buffers::Blocks;
use crate::ls_surface;
use crate::status::{input, output, run, Fail, LS_ERR_INVALID_ARGUMENT};
use loopsurf::mesh::high_order::{onto_surface, DEFAULT_MAX_MOVE, MAX_ORDER};
use loopsurf::DVec3;
use std::ffi::c_int;

/// Curves a linear mesh made by another tool: its `nverts` vertices `xyz`
/// (3 × nverts) and `ntris` triangles `tris` (3 × ntris, 0-based,
/// counter-clockwise like the net). Every vertex goes to its certified
/// closest point on the surface, every triangle takes the model face of
/// its centroid's closest point, edges between two faces (or on the
/// boundary) onto their model curve, and each triangle becomes a Lagrange
/// triangle of order `order` (1 to 4) with every node on the surface.
///
/// `max_move` (relative to the bounding-box diagonal; 0 for the default,
/// 0.01) bounds how far a vertex may move: a vertex farther from the
/// surface is refused with an error naming it (another model, other
/// units).
///
/// Writes `nnodes`, `nodes_xyz` (3 × nnodes; the input vertices first, in
/// order), per node `node_tri` (nnodes) and `node_vw` (2 × nnodes) so
/// that `ls_evaluate(node_tri[i], vw[2i], vw[2i+1])` is node i, and
/// `elements` ((order + 1)(order + 2)/2 × ntris, 0-based node indices in
/// gmsh's order: 3 vertices, each edge's inner nodes from its first vertex
/// to its second, then the interior nodes; edge nodes shared by both
/// triangles of an edge). Release them with `ls_free_array`. Optional
/// (NULL to skip): `tri_face` (ntris, caller's array), the model face of
/// each triangle; `largest_move`, the largest vertex move in model units;
/// `min_scaled_jacobian`, the smallest scaled Jacobian (≤ 0: an element
/// folds; 1: straight). Nothing is written on failure.
#[no_mangle]
pub unsafe extern "C" fn ls_curve(
    surface: *const ls_surface,
    nverts: usize,
    xyz: *const f64,
    ntris: usize,
    tris: *const i32,
    order: c_int,
    max_move: f64,
    nnodes: *mut usize,
    nodes_xyz: *mut *mut f64,
    node_tri: *mut *mut i32,
    node_vw: *mut *mut f64,
    elements: *mut *mut i32,
    tri_face: *mut i32,
    largest_move: *mut f64,
    min_scaled_jacobian: *mut f64,
) -> c_int {
    run("ls_curve", || {
        let surface = &input(surface, "surface")?.0;
        let outs = (
            output(nnodes, "nnodes")?,
            output(nodes_xyz, "nodes_xyz")?,
            output(node_tri, "node_tri")?,
            output(node_vw, "node_vw")?,
            output(elements, "elements")?,
        );
        let bad = |m: String| Fail::new(LS_ERR_INVALID_ARGUMENT, m);
        let order = usize::try_from(order)
            .ok()
            .filter(|k| (1..=MAX_ORDER).contains(k))
            .ok_or_else(|| bad(format!("order = {order}: must be 1 to {MAX_ORDER}")))?;
        let max_move = if max_move == 0.0 {
            DEFAULT_MAX_MOVE
        } else {
            max_move
        };
        let coords = crate::mesh::slice(xyz, nverts, 3, "xyz")?;
        let indices = crate::mesh::slice(tris, ntris, 3, "tris")?;
        let points: Vec<DVec3> = coords.chunks(3).map(DVec3::from_slice).collect();
        let mut triangles = Vec::with_capacity(ntris);
        for (t, tri) in indices.chunks(3).enumerate() {
            let tri: [i32; 3] = [tri[0], tri[1], tri[2]];
            if let Some(&i) = tri.iter().find(|&&i| i < 0 || i as usize >= nverts) {
                return Err(bad(format!(
                    "triangle {t} {tri:?} refers to vertex {i}, but there are {nverts} vertices"
                )));
            }
            triangles.push(tri.map(|i| i as u32));
        }
        let onto = onto_surface(surface, &points, &triangles, max_move)?;
        let curved = onto.mesh.raise_order(surface, order)?;
        if curved.nodes.len() > i32::MAX as usize {
            return Err(bad(format!(
                "{} nodes do not fit 32-bit indices",
                curved.nodes.len()
            )));
        }
        let mut blocks = Blocks::default();
        let coords: Vec<f64> = curved.nodes.iter().flat_map(|p| p.to_array()).collect();
        let tri: Vec<i32> = curved.params.iter().map(|p| p.tri as i32).collect();
        let vw: Vec<f64> = curved.params.iter().flat_map(|p| [p.v, p.w]).collect();
        let elems: Vec<i32> = curved.triangles.iter().map(|&i| i as i32).collect();
        let ptrs = (
            blocks.copy(&coords)?,
            blocks.copy(&tri)?,
            blocks.copy(&vw)?,
            blocks.copy(&elems)?,
        );
        // Only when asked: it samples every element.
        let min_jacobian = (!min_scaled_jacobian.is_null()).then(|| curved.validity().min);
        blocks.hand_over();
        *outs.0 = curved.nodes.len();
        *outs.1 = ptrs.0;
        *outs.2 = ptrs.1;
        *outs.3 = ptrs.2;
        *outs.4 = ptrs.3;
        if !tri_face.is_null() && ntris > 0 {
            let faces: Vec<i32> = curved.faces.iter().map(|&f| f as i32).collect();
            std::ptr::copy_nonoverlapping(faces.as_ptr(), tri_face, ntris);
        }
        if !largest_move.is_null() {
            *largest_move = onto.largest_move;
        }
        if let Some(j) = min_jacobian {
            *min_scaled_jacobian = j;
        }
        Ok(())
    })
}
