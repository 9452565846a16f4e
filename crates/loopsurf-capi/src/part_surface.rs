//! A part's surface (`ls_part_surface`): local projection that says where
//! its walk left the part, and certified closest points over the owned
//! triangles that say which other parts may hold a nearer point, so that
//! a rank can hand a query on to the owner. Triangle ids are the whole
//! net's.

use crate::buffers::malloc_copy;
use crate::closest::{guess, point, snap_outputs, write_snap};
use crate::handles::{ls_part, ls_part_surface};
use crate::net::ls_net;
use crate::partition::{ls_partition_options, partition_of};
use crate::status::{input, output, read_options, run, run_void, Fail, LS_ERR_INVALID_ARGUMENT};
use loopsurf::partsurface::{bounds, Bounds, PartSurface};
use loopsurf::DVec3;
use std::ffi::c_int;

/// The handle is documented as safe to query from many threads at once.
const _: fn() = || {
    fn shared<T: Send + Sync>() {}
    shared::<PartSurface>();
};

/// Partitions the net as `ls_net_partition` does (`options` may be NULL
/// for K = 1) and writes K to `nparts` and a new array `bounds` of 6 K
/// doubles, to be released with `ls_free_array`: part q's box is its
/// lowest corner (x, y, z) at `bounds[6q]` and its highest at
/// `bounds[6q + 3]`. A part's limit surface lies in its box (the box of
/// the control points its patches read), which is what lets a closest
/// point over one part tell which other parts may hold a nearer one.
/// Rank 0 can send these 6 K doubles to every rank with its part.
#[no_mangle]
pub unsafe extern "C" fn ls_net_part_bounds(
    net: *const ls_net,
    options: *const ls_partition_options,
    nparts: *mut usize,
    bounds_out: *mut *mut f64,
) -> c_int {
    run("ls_net_part_bounds", || {
        let net = &input(net, "net")?.0;
        let o = read_options(options, "options")?;
        let outs = (output(nparts, "nparts")?, output(bounds_out, "bounds")?);
        let boxes = bounds(net, &partition_of(net, &o)?);
        let flat: Vec<f64> = boxes
            .iter()
            .flat_map(|(lo, hi)| lo.to_array().into_iter().chain(hi.to_array()))
            .collect();
        *outs.1 = malloc_copy(&flat)?;
        *outs.0 = boxes.len();
        Ok(())
    })
}

/// Builds the limit surface of `part`, which is part `index` of the
/// `nparts` parts whose boxes are `bounds` (6 × nparts doubles, as
/// `ls_net_part_bounds` writes them), and writes it as a new
/// `ls_part_surface`, to be released with `ls_part_surface_free`. The
/// part is copied: it may be freed at once. An index outside 0 to
/// nparts − 1 is `LS_ERR_INVALID_ARGUMENT`, and nothing is written.
#[no_mangle]
pub unsafe extern "C" fn ls_part_surface_build(
    part: *const ls_part,
    index: c_int,
    nparts: usize,
    bounds: *const f64,
    out: *mut *mut ls_part_surface,
) -> c_int {
    run("ls_part_surface_build", || {
        let part = &input(part, "part")?.0;
        input(bounds, "bounds")?;
        let out = output(out, "out")?;
        let flat = std::slice::from_raw_parts(bounds, 6 * nparts);
        let boxes: Vec<Bounds> = flat
            .chunks_exact(6)
            .map(|b| (DVec3::from_slice(&b[..3]), DVec3::from_slice(&b[3..])))
            .collect();
        let index = usize::try_from(index).map_err(|_| {
            Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("part {index}: must not be negative"),
            )
        })?;
        let surface = PartSurface::new(part.clone(), index, boxes)?;
        *out = Box::into_raw(Box::new(ls_part_surface(surface)));
        Ok(())
    })
}

/// Frees a part's surface (NULL is ignored).
#[no_mangle]
pub unsafe extern "C" fn ls_part_surface_free(surface: *mut ls_part_surface) {
    if !surface.is_null() {
        run_void("ls_part_surface_free", || drop(Box::from_raw(surface)));
    }
}

/// Writes the bytes the part's surface holds: its sub-net and maps, the
/// patches made so far and the snap index of its owned triangles once a
/// closest point has built it (a closest point makes every patch).
#[no_mangle]
pub unsafe extern "C" fn ls_part_surface_bytes(
    surface: *const ls_part_surface,
    bytes: *mut usize,
) -> c_int {
    run("ls_part_surface_bytes", || {
        let surface = &input(surface, "surface")?.0;
        *output(bytes, "bytes")? = surface.memory_bytes();
        Ok(())
    })
}

/// `ls_project` on the part, from a guess on a triangle it owns
/// (`tri_guess`, a global id): the walk stays on the owned triangles,
/// where every evaluation is the whole's. Writes the answer as
/// `ls_project` does (`tri` a global id) and `left_at`: −1 when the walk
/// never asked for a triangle the part does not own, and the answer is
/// then the whole surface's `ls_project` bit for bit; otherwise the
/// first such triangle (global id), where the walk stopped, and the
/// query can go on at that triangle's owner. A guess on a triangle the
/// part does not own is `LS_ERR_INVALID_ARGUMENT`; nothing is written on
/// failure.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn ls_part_project(
    surface: *const ls_part_surface,
    xyz: *const f64,
    tri_guess: i32,
    vw_guess: *const f64,
    tri: *mut i32,
    vw: *mut f64,
    xyz_out: *mut f64,
    distance: *mut f64,
    left_at: *mut i32,
) -> c_int {
    run("ls_part_project", || {
        let surface = &input(surface, "surface")?.0;
        let p = point(xyz)?;
        let (v, w) = guess(vw_guess)?;
        let outs = snap_outputs(tri, vw, xyz_out, distance)?;
        let left_at = output(left_at, "left_at")?;
        let t = u32::try_from(tri_guess).map_err(|_| {
            Fail::new(
                LS_ERR_INVALID_ARGUMENT,
                format!("triangle {tri_guess}: negative"),
            )
        })?;
        let answer = surface.project(p, t, v, w)?;
        write_snap(outs, answer.snap);
        *left_at = answer.left_at.map_or(-1, |t| t as i32);
        Ok(())
    })
}

/// The closest point to `xyz` over the part's owned triangles, certified
/// as `ls_snap`'s: writes it as `ls_snap` does (`tri` a global id), and
/// the other parts whose boxes are nearer than it, which alone may hold a
/// nearer point: their count to `n_nearer` and the first
/// min(count, capacity) of them, ascending, to `nearer` (which may be
/// NULL when capacity is 0; K − 1 entries always suffice). A count of 0
/// certifies the answer as the whole surface's closest point; otherwise
/// the whole's is the nearest of the answers of this part and those
/// parts. Nothing is written on failure.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn ls_part_closest_point(
    surface: *const ls_part_surface,
    xyz: *const f64,
    tri: *mut i32,
    vw: *mut f64,
    xyz_out: *mut f64,
    distance: *mut f64,
    capacity: usize,
    nearer: *mut i32,
    n_nearer: *mut usize,
) -> c_int {
    run("ls_part_closest_point", || {
        let surface = &input(surface, "surface")?.0;
        let p = point(xyz)?;
        let outs = snap_outputs(tri, vw, xyz_out, distance)?;
        let n_nearer = output(n_nearer, "n_nearer")?;
        if capacity > 0 {
            output(nearer, "nearer")?;
        }
        let answer = surface.closest_point(p)?;
        write_snap(outs, answer.snap);
        for (i, &q) in answer.nearer_parts.iter().take(capacity).enumerate() {
            *nearer.add(i) = q as i32;
        }
        *n_nearer = answer.nearer_parts.len();
        Ok(())
    })
}
