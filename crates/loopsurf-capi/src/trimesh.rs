//! `ls_trimesh`: the mesh a meshing call hands over (`ls_mesh`,
//! `ls_remesh`, `ls_adapt`, `ls_mesh_curve`), with one accessor per array
//! or measure, so that outputs can be added without changing any call.
//!
//! A mesh is `nelements` triangles of `nodes_per_element` nodes each
//! (3 for straight triangles; 6, 10, 15 for Lagrange triangles of order 2
//! to 4 in gmsh's node order). Every node lies on the surface at its
//! (tri, v, w). Arrays are borrowed: they stay valid, unchanged, until
//! `ls_trimesh_free`.

pub use crate::handles::ls_trimesh;
use crate::status::{input, output, run, run_void, Fail, LS_ERR_UNSUPPORTED};
use loopsurf::{DVec3, SurfacePoint};
use std::ffi::c_int;
use std::sync::OnceLock;

impl ls_trimesh {
    /// A mesh of straight triangles; fails when it does not fit 32-bit
    /// indices.
    pub(crate) fn straight(
        points: &[DVec3],
        triangles: &[[u32; 3]],
        params: &[SurfacePoint],
    ) -> Result<ls_trimesh, Fail> {
        Self::new(points, triangles.iter().flatten().copied(), params, 3)
    }

    /// A mesh of `per` nodes an element, with none of the optional arrays.
    pub(crate) fn new(
        points: &[DVec3],
        elements: impl Iterator<Item = u32>,
        params: &[SurfacePoint],
        per: usize,
    ) -> Result<ls_trimesh, Fail> {
        if points.len() > i32::MAX as usize {
            return Err(Fail::new(
                crate::status::LS_ERR_INVALID_ARGUMENT,
                format!("{} nodes do not fit 32-bit indices", points.len()),
            ));
        }
        Ok(ls_trimesh {
            nodes_per_element: per,
            xyz: points.iter().flat_map(|p| p.to_array()).collect(),
            elements: elements.map(|i| i as i32).collect(),
            node_tri: params.iter().map(|p| p.tri as i32).collect(),
            node_vw: params.iter().flat_map(|p| [p.v, p.w]).collect(),
            element_face: None,
            element_chart: None,
            element_chart_vw: None,
            deviation: None,
            largest_move: None,
            curved: None,
            min_jacobian: OnceLock::new(),
        })
    }

    /// Hands the mesh to the caller through `out`.
    ///
    /// # Safety
    /// `out` was checked by `status::output`.
    pub(crate) unsafe fn hand_over(self, out: *mut *mut ls_trimesh) {
        *out = Box::into_raw(Box::new(self));
    }
}

/// Labels of a `u32` list as C ints.
pub(crate) fn c_ints(labels: &[u32]) -> Vec<i32> {
    labels.iter().map(|&x| x as i32).collect()
}

/// Writes a borrowed array, or says that this mesh has none.
unsafe fn borrow<T>(
    name: &str,
    mesh: *const ls_trimesh,
    out: *mut *const T,
    array: impl FnOnce(&ls_trimesh) -> Result<*const T, Fail>,
) -> c_int {
    run(name, || {
        let mesh = input(mesh, "mesh")?;
        let out = output(out, "out")?;
        *out = array(mesh)?;
        Ok(())
    })
}

/// Writes a measure of the mesh, or says that this mesh has none.
unsafe fn measure(
    name: &str,
    mesh: *const ls_trimesh,
    out: *mut f64,
    value: impl FnOnce(&ls_trimesh) -> Result<f64, Fail>,
) -> c_int {
    run(name, || {
        let mesh = input(mesh, "mesh")?;
        let out = output(out, "out")?;
        *out = value(mesh)?;
        Ok(())
    })
}

/// An optional array or measure this mesh lacks, and why.
fn absent(what: &str, why: &str) -> Fail {
    Fail::new(
        LS_ERR_UNSUPPORTED,
        format!("this mesh has no {what}: {why}"),
    )
}

/// Writes the sizes of the mesh: `nnodes` nodes, `nelements` elements,
/// `nodes_per_element` nodes each (3, 6, 10 or 15).
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_counts(
    mesh: *const ls_trimesh,
    nnodes: *mut usize,
    nelements: *mut usize,
    nodes_per_element: *mut usize,
) -> c_int {
    run("ls_trimesh_counts", || {
        let mesh = input(mesh, "mesh")?;
        let outs = (
            output(nnodes, "nnodes")?,
            output(nelements, "nelements")?,
            output(nodes_per_element, "nodes_per_element")?,
        );
        *outs.0 = mesh.xyz.len() / 3;
        *outs.1 = mesh.elements.len() / mesh.nodes_per_element;
        *outs.2 = mesh.nodes_per_element;
        Ok(())
    })
}

/// Points `*xyz` at the node coordinates (3 × nnodes).
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_xyz(mesh: *const ls_trimesh, xyz: *mut *const f64) -> c_int {
    borrow("ls_trimesh_xyz", mesh, xyz, |m| Ok(m.xyz.as_ptr()))
}

/// Points `*elements` at the elements (nodes_per_element × nelements,
/// 0-based node indices, counter-clockwise like the net; curved elements
/// in gmsh's node order: 3 vertices, each edge's inner nodes from its
/// first vertex to its second, then the interior nodes).
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_elements(
    mesh: *const ls_trimesh,
    elements: *mut *const i32,
) -> c_int {
    borrow("ls_trimesh_elements", mesh, elements, |m| {
        Ok(m.elements.as_ptr())
    })
}

/// Points `*node_tri` (nnodes) and `*node_vw` (2 × nnodes) at where each
/// node lies on the surface: `ls_evaluate(node_tri[i], node_vw[2i],
/// node_vw[2i+1])` is node i.
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_node_params(
    mesh: *const ls_trimesh,
    node_tri: *mut *const i32,
    node_vw: *mut *const f64,
) -> c_int {
    run("ls_trimesh_node_params", || {
        let mesh = input(mesh, "mesh")?;
        let outs = (output(node_tri, "node_tri")?, output(node_vw, "node_vw")?);
        *outs.0 = mesh.node_tri.as_ptr();
        *outs.1 = mesh.node_vw.as_ptr();
        Ok(())
    })
}

/// Points `*face` at the model face of each element (nelements; faces
/// numbered as `ls_model_*` numbers them). Every mesh but `ls_adapt`'s has
/// it; there, LS_ERR_UNSUPPORTED.
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_element_faces(
    mesh: *const ls_trimesh,
    face: *mut *const i32,
) -> c_int {
    borrow("ls_trimesh_element_faces", mesh, face, |m| {
        m.element_face
            .as_ref()
            .map(|f| f.as_ptr())
            .ok_or_else(|| absent("element faces", "use ls_mesh_face_labels"))
    })
}

/// Points `*chart` (nelements) and `*chart_vw` (6 × nelements) at the
/// control triangle holding each element and its corners' (v, w) in that
/// triangle: the map a high-order code curves the element with. Only
/// `ls_mesh`'s elements lie each in one control triangle; on other meshes
/// LS_ERR_UNSUPPORTED.
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_element_charts(
    mesh: *const ls_trimesh,
    chart: *mut *const i32,
    chart_vw: *mut *const f64,
) -> c_int {
    run("ls_trimesh_element_charts", || {
        let mesh = input(mesh, "mesh")?;
        let outs = (output(chart, "chart")?, output(chart_vw, "chart_vw")?);
        let why = "its elements may span several control triangles (only ls_mesh's lie in one)";
        match (&mesh.element_chart, &mesh.element_chart_vw) {
            (Some(c), Some(vw)) => {
                *outs.0 = c.as_ptr();
                *outs.1 = vw.as_ptr();
                Ok(())
            }
            _ => Err(absent("element charts", why)),
        }
    })
}

/// Writes the largest chord error measured, relative to the bounding-box
/// diagonal: `ls_remesh`'s under a tolerance (compare it with the
/// tolerance: a few edges may be stuck longer, e.g. at a cusp). Other
/// meshes, or `ls_remesh` without a tolerance: LS_ERR_UNSUPPORTED.
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_deviation(
    mesh: *const ls_trimesh,
    deviation: *mut f64,
) -> c_int {
    measure("ls_trimesh_deviation", mesh, deviation, |m| {
        m.deviation.ok_or_else(|| {
            absent(
                "measured deviation",
                "only ls_remesh under a tolerance measures it",
            )
        })
    })
}

/// Writes the largest distance, in model units, that `ls_mesh_curve` moved
/// an input vertex to put it on the surface; other meshes:
/// LS_ERR_UNSUPPORTED.
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_largest_move(
    mesh: *const ls_trimesh,
    largest_move: *mut f64,
) -> c_int {
    measure("ls_trimesh_largest_move", mesh, largest_move, |m| {
        m.largest_move
            .ok_or_else(|| absent("vertex moves", "only ls_mesh_curve moves vertices"))
    })
}

/// Writes the smallest scaled Jacobian of `ls_mesh_curve`'s elements
/// (≤ 0: an element folds; 1: straight). Sampled over every element on
/// the first call, then remembered. Other meshes: LS_ERR_UNSUPPORTED.
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_min_scaled_jacobian(
    mesh: *const ls_trimesh,
    min_scaled_jacobian: *mut f64,
) -> c_int {
    measure(
        "ls_trimesh_min_scaled_jacobian",
        mesh,
        min_scaled_jacobian,
        |m| {
            let curved = m
                .curved
                .as_ref()
                .ok_or_else(|| absent("curved elements", "only ls_mesh_curve makes them"))?;
            Ok(*m.min_jacobian.get_or_init(|| curved.validity().min))
        },
    )
}

/// Releases a mesh and every array borrowed from it (NULL is ignored).
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_free(mesh: *mut ls_trimesh) {
    run_void("ls_trimesh_free", || {
        if !mesh.is_null() {
            drop(Box::from_raw(mesh));
        }
    });
}
