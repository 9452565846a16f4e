//! `ls_trimesh_write`: a mesh on the surface to a gmsh `.msh` 4.1 or VTK
//! `.vtu` file, as `loopsurf mesh` writes it, whole or as one rank's piece
//! with the node ids of the whole mesh.

use crate::status::{input, read_options, run, write_defaults, Fail, Options};
use crate::status::{LS_ERR_INVALID_ARGUMENT, LS_ERR_UNSUPPORTED};
use crate::surface::ls_surface;
use crate::trimesh::ls_trimesh;
use loopsurf::io::{self, DataArray, LagrangeMesh, MshTags};
use loopsurf::mesh::SurfaceMesh;
use loopsurf::{DVec3, Surface, SurfacePoint};
use std::ffi::{c_char, c_int, CStr, OsStr};
use std::os::unix::ffi::OsStrExt;
use std::path::Path;

/// Options of `ls_trimesh_write`: fill with
/// `ls_trimesh_write_options_default`, then change what you need.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_trimesh_write_options {
    /// `sizeof(ls_trimesh_write_options)` as the caller was compiled with.
    pub struct_size: usize,
    /// Nonzero: `.msh` in gmsh's binary format, `.vtu` with inline binary
    /// (base64) arrays (on a 6k-triangle mesh, 0.86× and 0.62× the ASCII
    /// sizes). Default 0 (ASCII).
    pub binary: c_int,
    /// NULL (the default), or one id per node of the mesh, each at least 0
    /// and all distinct: the node's id in a whole mesh this mesh is a piece
    /// of (`ls_remesh_job_piece` gives them). `.msh` tags node i with
    /// `global_ids[i] + 1`; `.vtu` adds the point array `GlobalNodeId`
    /// (Int64). Pieces merged on them share the nodes on their borders.
    pub global_ids: *const i64,
    /// `.msh` only: the tag of the first element, the others following one
    /// by one (corner points, then lines, then triangles). Pieces written
    /// with ranges that do not overlap keep every element when merged;
    /// a piece has at most nnodes + 4 × nelements elements. Default 1.
    pub first_element_tag: i64,
}

impl Options for ls_trimesh_write_options {
    const FIRST_SIZE: usize = std::mem::size_of::<ls_trimesh_write_options>();
    fn defaults() -> Self {
        ls_trimesh_write_options {
            struct_size: std::mem::size_of::<ls_trimesh_write_options>(),
            binary: 0,
            global_ids: std::ptr::null(),
            first_element_tag: 1,
        }
    }
}

/// Writes the default options of `ls_trimesh_write` into `options`.
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_write_options_default(
    options: *mut ls_trimesh_write_options,
) -> c_int {
    write_defaults("ls_trimesh_write_options_default", options)
}

/// Writes `mesh`, which lies on `surface`, to `path`: gmsh MSH 4.1 for
/// `.msh`, VTK XML for `.vtu`, as `loopsurf mesh` writes them. Both carry
/// each triangle's model face, the hard edges as lines with their model
/// curve, the model corners, and each node's (triangle, v, w); curved
/// meshes go out as Lagrange elements. The mesh needs element faces
/// (every meshing call's mesh but `ls_adapt`'s has them). `options` may
/// be NULL for the defaults.
///
/// Errors say what is wrong: another extension, a mesh without faces,
/// node parameters outside this surface, repeated or negative global ids,
/// or the file (LS_ERR_IO, naming it). A file that fails partway may be
/// left incomplete.
#[no_mangle]
pub unsafe extern "C" fn ls_trimesh_write(
    mesh: *const ls_trimesh,
    surface: *const ls_surface,
    path: *const c_char,
    options: *const ls_trimesh_write_options,
) -> c_int {
    run("ls_trimesh_write", || {
        let mesh = input(mesh, "mesh")?;
        let surface = &input(surface, "surface")?.0;
        let path = CStr::from_ptr(input(path, "path")?);
        let path = Path::new(OsStr::from_bytes(path.to_bytes()));
        let o = read_options(options, "options")?;
        let format = Format::of(path)?;
        let ids = global_ids(mesh, &o)?;
        if o.first_element_tag < 1 {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!(
                    "first_element_tag = {}: gmsh's tags start at 1",
                    o.first_element_tag
                ),
            ));
        }
        let lagrange = lagrange_of(mesh, surface)?;
        let binary = o.binary != 0;
        match format {
            Format::Msh => {
                let tags: Option<Vec<u64>> =
                    ids.map(|ids| ids.iter().map(|&i| i as u64 + 1).collect());
                let tags = MshTags {
                    nodes: tags.as_deref(),
                    first_element: o.first_element_tag as u64,
                };
                io::write_msh_tagged(path, &lagrange, binary, tags)?
            }
            Format::Vtu => {
                let points: Vec<(&str, DataArray)> = ids
                    .map(|ids| ("GlobalNodeId", DataArray::I64(ids)))
                    .into_iter()
                    .collect();
                io::write_vtu_lagrange(path, &lagrange, &points, &[], binary)?
            }
        }
        Ok(())
    })
}

/// The file formats `ls_trimesh_write` writes, by extension.
enum Format {
    Msh,
    Vtu,
}

impl Format {
    fn of(path: &Path) -> Result<Format, Fail> {
        let ext = path
            .extension()
            .and_then(OsStr::to_str)
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("msh") => Ok(Format::Msh),
            Some("vtu") => Ok(Format::Vtu),
            _ => Err(Fail::new(
                LS_ERR_UNSUPPORTED,
                format!("{}: ls_trimesh_write writes .msh or .vtu", path.display()),
            )),
        }
    }
}

/// The caller's global ids, checked: one per node, none negative, all
/// distinct.
unsafe fn global_ids<'a>(
    mesh: &ls_trimesh,
    o: &ls_trimesh_write_options,
) -> Result<Option<&'a [i64]>, Fail> {
    if o.global_ids.is_null() {
        return Ok(None);
    }
    let n = mesh.xyz.len() / 3;
    let ids = std::slice::from_raw_parts(o.global_ids, n);
    let bad = |m: String| Err(Fail::new(LS_ERR_INVALID_ARGUMENT, m));
    if let Some(i) = ids.iter().position(|&id| id < 0) {
        return bad(format!("global_ids[{i}] = {} is negative", ids[i]));
    }
    if let Some((a, b)) = io::repeated(ids) {
        return bad(format!(
            "global_ids[{a}] and global_ids[{b}] are both {}",
            ids[a]
        ));
    }
    Ok(Some(ids))
}

/// The mesh as the file writers take it: a curved mesh as it is, a
/// straight one raised to order 1 on the surface, which finds its hard
/// edges, curves and corners as `loopsurf mesh` does.
fn lagrange_of(mesh: &ls_trimesh, surface: &Surface) -> Result<LagrangeMesh, Fail> {
    if let Some(curved) = &mesh.curved {
        return Ok(curved.to_lagrange());
    }
    let faces = mesh.element_face.as_ref().ok_or_else(|| {
        Fail::new(
            LS_ERR_UNSUPPORTED,
            "this mesh has no element faces to write (ls_adapt's mesh has none)",
        )
    })?;
    let straight = SurfaceMesh {
        points: mesh.xyz.chunks(3).map(DVec3::from_slice).collect(),
        triangles: mesh
            .elements
            .chunks(3)
            .map(|t| [t[0] as u32, t[1] as u32, t[2] as u32])
            .collect(),
        params: (mesh.node_tri.iter().zip(mesh.node_vw.chunks(2)))
            .map(|(&tri, vw)| SurfacePoint {
                tri: tri as u32,
                v: vw[0],
                w: vw[1],
            })
            .collect(),
        charts: Vec::new(),
        faces: faces.iter().map(|&f| f as u32).collect(),
        hard_edges: Vec::new(),
        hard_edge_curves: Vec::new(),
        deviation: None,
        diagonal: surface.net().bbox_diagonal(),
    };
    Ok(straight.raise_order(surface, 1)?.to_lagrange())
}
