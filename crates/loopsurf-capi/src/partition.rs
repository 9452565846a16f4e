//! `ls_net_partition`: the control triangles in K parts, one per process
//! (MPI rank), so that each rank can later hold only its share.

use crate::buffers::malloc_copy;
use crate::net::ls_net;
use crate::status::LS_ERR_INVALID_ARGUMENT;
use crate::status::{input, output, read_options, run, write_defaults, Fail, Options};
use loopsurf::partition::{partition_with, Partition, PartitionOptions};
use std::ffi::c_int;

/// Options of `ls_net_partition`: fill with
/// `ls_partition_options_default`, then change what you need.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ls_partition_options {
    /// `sizeof(ls_partition_options)` as the caller was compiled with.
    pub struct_size: usize,
    /// The number of parts K, 1 to the number of triangles. Default 1.
    pub parts: c_int,
    /// METIS's random seed: the same net, K and seed give the same parts.
    /// Default 1.
    pub seed: c_int,
}

impl Options for ls_partition_options {
    const FIRST_SIZE: usize = std::mem::size_of::<ls_partition_options>();
    fn defaults() -> Self {
        ls_partition_options {
            struct_size: std::mem::size_of::<ls_partition_options>(),
            parts: 1,
            seed: PartitionOptions::default().seed,
        }
    }
}

/// Writes the default options of `ls_net_partition` into `options`.
#[no_mangle]
pub unsafe extern "C" fn ls_partition_options_default(options: *mut ls_partition_options) -> c_int {
    write_defaults("ls_partition_options_default", options)
}

/// Splits the net's triangles into `options->parts` parts with METIS
/// (k-way on the triangles' edge adjacency): the largest part holds at most
/// 5 % over the mean (or ⌈ntris / K⌉ where that is more), each part is
/// connected where the net is, and few control edges lie between parts.
/// The same net, K and seed give the same parts on every thread count.
/// `options` may be NULL for the defaults (K = 1).
///
/// Writes `ntris`, a new array `part` (ntris entries, each triangle's part,
/// 0 to K − 1) to be released with `ls_free_array`, and `cut`, the number
/// of control edges between two parts. K below 1 or above the number of
/// triangles is `LS_ERR_INVALID_ARGUMENT`, and nothing is written.
#[no_mangle]
pub unsafe extern "C" fn ls_net_partition(
    net: *const ls_net,
    options: *const ls_partition_options,
    ntris: *mut usize,
    part: *mut *mut i32,
    cut: *mut usize,
) -> c_int {
    run("ls_net_partition", || {
        let net = &input(net, "net")?.0;
        let o = read_options(options, "options")?;
        let outs = (
            output(ntris, "ntris")?,
            output(part, "part")?,
            output(cut, "cut")?,
        );
        let p = partition_of(net, &o)?;
        let parts: Vec<i32> = p.parts().iter().map(|&q| q as i32).collect();
        let array = malloc_copy(&parts)?;
        *outs.0 = parts.len();
        *outs.1 = array;
        *outs.2 = p.edge_cut();
        Ok(())
    })
}

/// The net's partition as `options` asks (K and the seed); K below 1 is
/// `LS_ERR_INVALID_ARGUMENT`, as K above the triangle count is.
pub(crate) fn partition_of(
    net: &loopsurf::ControlNet,
    o: &ls_partition_options,
) -> Result<Partition, Fail> {
    let k = usize::try_from(o.parts).map_err(|_| {
        Fail::new(
            LS_ERR_INVALID_ARGUMENT,
            format!(
                "K = {}: must be between 1 and {}",
                o.parts,
                net.triangles().len()
            ),
        )
    })?;
    Ok(partition_with(net, k, &PartitionOptions { seed: o.seed })?)
}
