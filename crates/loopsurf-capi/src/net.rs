//! Control nets: load, build from arrays, tag hard features, free.

pub use crate::handles::ls_net;
use crate::status::{input, input_mut, output, run, run_void, Fail};
use crate::status::{
    LS_ERR_INDEX_OUT_OF_RANGE, LS_ERR_INVALID_ARGUMENT, LS_ERR_NOT_FINITE, LS_ERR_NULL_POINTER,
};
use loopsurf::repair::ReadOptions;
use loopsurf::repair::Repairs;
use loopsurf::{ControlNet, DVec3};
use std::ffi::{c_char, c_int, CStr, OsStr};
use std::os::unix::ffi::OsStrExt;

/// Reads and validates a mesh file (.off .obj .ply .stl .tri, by extension)
/// into a new net. Errors name the file and, for text formats, the line.
#[no_mangle]
pub unsafe extern "C" fn ls_net_load(path: *const c_char, out: *mut *mut ls_net) -> c_int {
    run("ls_net_load", || {
        let path = CStr::from_ptr(input(path, "path")?);
        let out = output(out, "out")?;
        let net = ControlNet::read(OsStr::from_bytes(path.to_bytes()))?;
        *out = Box::into_raw(Box::new(ls_net(net)));
        Ok(())
    })
}

/// `ls_net_load_with` flag: split polygon faces into triangles (ear
/// clipping) instead of refusing them.
pub const LS_LOAD_TRIANGULATE: u32 = 1;
/// `ls_net_load_with` flag: merge each vertex on an open edge into the
/// first earlier one within `weld_eps` × the bounding-box diagonal.
pub const LS_LOAD_WELD: u32 = 2;
/// `ls_net_load_with` flag: make triangle orientation consistent in each
/// connected piece (outward for closed pieces).
pub const LS_LOAD_ORIENT: u32 = 4;
/// `ls_net_load_with` flag: give a vertex where separate fans of triangles
/// touch one copy per fan (copies are appended to the vertices).
pub const LS_LOAD_SPLIT_NONMANIFOLD: u32 = 8;
/// `ls_net_load_with` flag: keep zero-area triangles instead of refusing
/// them; their edges are never tagged by angle.
pub const LS_LOAD_ALLOW_DEGENERATE: u32 = 16;
/// `ls_net_load_with` flags: every repair (the CLI's `--repair`).
pub const LS_LOAD_REPAIR: u32 = 31;

/// [`ls_net_load`] with repairs of dirty files: `flags` is a sum of
/// `LS_LOAD_*`; `weld_eps` is the weld distance as a fraction of the
/// bounding-box diagonal, used with `LS_LOAD_WELD` (0 for the default,
/// 1e-6). What the repairs changed is read back with
/// `ls_net_repair_report`; nothing changes unless a flag asks for it.
#[no_mangle]
pub unsafe extern "C" fn ls_net_load_with(
    path: *const c_char,
    flags: u32,
    weld_eps: f64,
    out: *mut *mut ls_net,
) -> c_int {
    run("ls_net_load_with", || {
        let path = CStr::from_ptr(input(path, "path")?);
        let out = output(out, "out")?;
        if flags & !LS_LOAD_REPAIR != 0 {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!(
                    "flags {flags:#x}: unknown bits {:#x}",
                    flags & !LS_LOAD_REPAIR
                ),
            ));
        }
        let on = |flag: u32| flags & flag != 0;
        let weld = if weld_eps == 0.0 {
            loopsurf::repair::DEFAULT_WELD
        } else {
            weld_eps
        };
        let opts = ReadOptions {
            triangulate: on(LS_LOAD_TRIANGULATE),
            repairs: Repairs {
                weld: on(LS_LOAD_WELD).then_some(weld),
                orient: on(LS_LOAD_ORIENT),
                split_nonmanifold: on(LS_LOAD_SPLIT_NONMANIFOLD),
                allow_degenerate: on(LS_LOAD_ALLOW_DEGENERATE),
            },
        };
        let net = ControlNet::read_with(OsStr::from_bytes(path.to_bytes()), &opts)?;
        *out = Box::into_raw(Box::new(ls_net(net)));
        Ok(())
    })
}

/// What the repairs of `ls_net_load_with` changed, one line per repair
/// (`\n`-separated, empty when nothing changed), copied NUL-terminated
/// into `buf` of `size` bytes (truncated to fit; `buf` may be NULL when
/// `size` is 0). `needed` (may be NULL) receives the full length plus one:
/// call with size 0 to learn it.
#[no_mangle]
pub unsafe extern "C" fn ls_net_repair_report(
    net: *const ls_net,
    buf: *mut c_char,
    size: usize,
    needed: *mut usize,
) -> c_int {
    run("ls_net_repair_report", || {
        let net = &input(net, "net")?.0;
        let text: Vec<String> = net.repairs().iter().map(|r| r.to_string()).collect();
        let text = text.join("\n");
        if !needed.is_null() {
            *needed = text.len() + 1;
        }
        if size > 0 {
            let buf = output(buf, "buf")? as *mut c_char;
            // Truncated on a character boundary: the text is UTF-8.
            let mut n = text.len().min(size - 1);
            while !text.is_char_boundary(n) {
                n -= 1;
            }
            std::ptr::copy_nonoverlapping(text.as_ptr().cast::<c_char>(), buf, n);
            *buf.add(n) = 0;
        }
        Ok(())
    })
}

/// Builds a net from `nverts` points (`xyz`, 3 × nverts doubles) and
/// `ntris` counter-clockwise triangles (`tris`, 3 × ntris 0-based indices),
/// validated like a file. The arrays are copied.
#[no_mangle]
pub unsafe extern "C" fn ls_net_from_arrays(
    nverts: usize,
    xyz: *const f64,
    ntris: usize,
    tris: *const i32,
    out: *mut *mut ls_net,
) -> c_int {
    run("ls_net_from_arrays", || {
        let xyz = array(xyz, nverts, "xyz")?;
        let tris = array(tris, ntris, "tris")?;
        let out = output(out, "out")?;
        let points = xyz
            .chunks_exact(3)
            .map(|p| DVec3::new(p[0], p[1], p[2]))
            .collect();
        let tris: Vec<[i64; 3]> = tris
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]].map(i64::from))
            .collect();
        let net = ControlNet::from_indices(points, &tris)?;
        *out = Box::into_raw(Box::new(ls_net(net)));
        Ok(())
    })
}

/// Borrows `3 × n` values; NULL and sizes beyond memory are errors. No
/// reference is made from `p` before the size is known good (with n = 0 a
/// caller may pass a pointer past the end of its data).
unsafe fn array<'a, T>(p: *const T, n: usize, what: &str) -> Result<&'a [T], Fail> {
    if p.is_null() {
        return Err(Fail::new(LS_ERR_NULL_POINTER, format!("{what} is NULL")));
    }
    let len = n
        .checked_mul(3)
        .filter(|len| len.saturating_mul(std::mem::size_of::<T>()) <= isize::MAX as usize)
        .ok_or_else(|| {
            Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("{what}: {n} × 3 is too large"),
            )
        })?;
    Ok(std::slice::from_raw_parts(p, len))
}

/// A vertex index of `net`, or an out-of-range error naming it.
pub(crate) fn vertex_index(net: &ControlNet, v: i32, what: &str) -> Result<u32, Fail> {
    let n = net.points().len();
    u32::try_from(v)
        .ok()
        .filter(|&i| (i as usize) < n)
        .ok_or_else(|| {
            Fail::new(
                LS_ERR_INDEX_OUT_OF_RANGE,
                format!("{what} {v}: out of range (the net has {n} vertices)"),
            )
        })
}

/// Tags the edge between vertices a and b hard (crease rules). An edge that
/// is already hard is not an error; (a, b) not being an edge is.
#[no_mangle]
pub unsafe extern "C" fn ls_net_tag_edge(net: *mut ls_net, a: i32, b: i32) -> c_int {
    run("ls_net_tag_edge", || {
        let net = &mut input_mut(net, "net")?.0;
        let (a, b) = (
            vertex_index(net, a, "vertex")?,
            vertex_index(net, b, "vertex")?,
        );
        net.tag_edge(a, b)?;
        Ok(())
    })
}

/// Tags vertex v as a corner: it stays fixed (its limit is itself).
#[no_mangle]
pub unsafe extern "C" fn ls_net_tag_vertex(net: *mut ls_net, v: i32) -> c_int {
    run("ls_net_tag_vertex", || {
        let net = &mut input_mut(net, "net")?.0;
        let v = vertex_index(net, v, "vertex")?;
        net.tag_vertex(v)?;
        Ok(())
    })
}

/// Tags hard every interior edge whose dihedral angle (between the normals
/// of its two triangles) exceeds `degrees` (0 to 180). Writes how many
/// edges became hard to `ntagged` unless it is NULL.
#[no_mangle]
pub unsafe extern "C" fn ls_net_tag_by_angle(
    net: *mut ls_net,
    degrees: f64,
    ntagged: *mut usize,
) -> c_int {
    run("ls_net_tag_by_angle", || {
        let net = &mut input_mut(net, "net")?.0;
        if !degrees.is_finite() {
            return Err(Fail::new(
                LS_ERR_NOT_FINITE,
                format!("angle {degrees} is not finite"),
            ));
        }
        let n = net.tag_by_angle(degrees)?;
        if !ntagged.is_null() {
            *ntagged = n;
        }
        Ok(())
    })
}

/// Splits every corner's sector that spans more than 195° (the inner
/// corner of an L-shaped face) where Loop's crease rules fold the surface
/// past the corner's creases (a patch of the sector folds over itself) by
/// tagging hard the edge of its fan that halves it best, when one makes
/// no angle below 40° with the sector's sides or the hard edges at its
/// far end and ends in a smooth vertex or another corner (so no vertex
/// changes its rule). Call it after the other tags. Writes how many folded
/// sectors were seamed and how many were left (no such edge), each unless
/// NULL. The seams are among `ls_net_hard_edges` afterwards.
#[no_mangle]
pub unsafe extern "C" fn ls_net_seam_concave_corners(
    net: *mut ls_net,
    nseamed: *mut usize,
    nleft: *mut usize,
) -> c_int {
    run("ls_net_seam_concave_corners", || {
        let net = &mut input_mut(net, "net")?.0;
        let sectors = loopsurf::folds::seam_folded_concave_corners(net)?;
        let seamed = sectors.iter().filter(|s| s.seam.is_some()).count();
        for (out, n) in [(nseamed, seamed), (nleft, sectors.len() - seamed)] {
            if !out.is_null() {
                *out = n;
            }
        }
        Ok(())
    })
}

/// Writes the numbers of vertices, triangles and hard edges (boundary
/// edges included); each output may be NULL.
#[no_mangle]
pub unsafe extern "C" fn ls_net_counts(
    net: *const ls_net,
    nverts: *mut usize,
    ntris: *mut usize,
    nhard_edges: *mut usize,
) -> c_int {
    run("ls_net_counts", || {
        let net = &input(net, "net")?.0;
        let counts = [
            net.points().len(),
            net.triangles().len(),
            net.features().num_hard_edges(),
        ];
        for (p, n) in [nverts, ntris, nhard_edges].into_iter().zip(counts) {
            if !p.is_null() {
                *p = n;
            }
        }
        Ok(())
    })
}

/// The hard edges (boundary edges included) as `n` pairs of 0-based vertex
/// indices i < j in a new array of 2 × n, released with `ls_free_array`.
#[no_mangle]
pub unsafe extern "C" fn ls_net_hard_edges(
    net: *const ls_net,
    n: *mut usize,
    pairs: *mut *mut i32,
) -> c_int {
    run("ls_net_hard_edges", || {
        let net = &input(net, "net")?.0;
        let (n, pairs) = (output(n, "n")?, output(pairs, "pairs")?);
        let flat: Vec<i32> = net
            .hard_edges()
            .iter()
            .flatten()
            .map(|&i| i as i32)
            .collect();
        *pairs = crate::buffers::malloc_copy(&flat)?;
        *n = flat.len() / 2;
        Ok(())
    })
}

/// The edges where the net folds back on itself: the normals of their two
/// triangles turn by more than `degrees` (0 to 180; 150 finds pig.off's
/// needle, folded back at 178.8°). Their limit surface has a fin there,
/// and no mesh of it is good. `n` folds, worst first, in new arrays
/// (allocated even when n = 0) released with `ls_free_array`: `edges` the
/// vertex pairs i < j (2 × n), `triangles` the two triangles of each
/// (2 × n), `turns` the angles in degrees (n).
#[no_mangle]
pub unsafe extern "C" fn ls_net_folds(
    net: *const ls_net,
    degrees: f64,
    n: *mut usize,
    edges: *mut *mut i32,
    triangles: *mut *mut i32,
    turns: *mut *mut f64,
) -> c_int {
    run("ls_net_folds", || {
        let net = &input(net, "net")?.0;
        let n = output(n, "n")?;
        let (edges, triangles) = (output(edges, "edges")?, output(triangles, "triangles")?);
        let turns = output(turns, "turns")?;
        if !(0.0..=180.0).contains(&degrees) {
            return Err(Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("degrees {degrees}: must be between 0 and 180"),
            ));
        }
        let folds = loopsurf::folds::folded_edges(net, degrees);
        let pairs: Vec<i32> = folds
            .iter()
            .flat_map(|f| f.edge)
            .map(|i| i as i32)
            .collect();
        let tris: Vec<i32> = folds
            .iter()
            .flat_map(|f| f.triangles)
            .map(|t| t as i32)
            .collect();
        let angles: Vec<f64> = folds.iter().map(|f| f.degrees).collect();
        let mut blocks = crate::buffers::Blocks::default();
        let arrays = (
            blocks.copy(&pairs)?,
            blocks.copy(&tris)?,
            blocks.copy(&angles)?,
        );
        blocks.hand_over();
        (*edges, *triangles, *turns) = arrays;
        *n = folds.len();
        Ok(())
    })
}

/// Frees a net (NULL is ignored). Surfaces built from it stay valid.
#[no_mangle]
pub unsafe extern "C" fn ls_net_free(net: *mut ls_net) {
    if !net.is_null() {
        run_void("ls_net_free", || drop(Box::from_raw(net)));
    }
}
