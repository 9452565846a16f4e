//! The C ABI of loopsurf: opaque handles, `int` status codes (0 success,
//! negative errors, EGADS style) and a thread-local error message.
//!
//! Every function checks every pointer, writes its outputs only on success,
//! and catches panics at the boundary: nothing unwinds into C and the
//! library never prints. A `const` handle is never mutated, and a built
//! surface may be queried from any number of threads at once. Indices are
//! 0-based. This crate only translates: all geometry lives in `loopsurf`.
//!
//! `include/loopsurf.h` is generated from this crate by cbindgen
//! (`cbindgen.toml`); `tests/header.rs` fails when it is stale and rewrites
//! it with `LOOPSURF_BLESS=1`.

#![allow(non_camel_case_types)]
// Raw pointers are validated by `status::input`/`output` before use; every
// exported function documents its pointer contract in the header instead.
#![allow(clippy::missing_safety_doc)]

mod adapt;
mod buffers;
mod curve;
mod mesh;
mod model;
mod net;
mod project;
mod snap;
mod status;
mod surface;

pub use buffers::*;
pub use curve::*;
pub use mesh::*;
pub use net::*;
pub use project::*;
pub use snap::*;
pub use status::*;
pub use surface::*;

/// A control net being prepared: load or build it, tag its hard features,
/// then freeze it into an `ls_surface`.
pub struct ls_net(loopsurf::ControlNet);

/// An immutable limit surface, safe to query from many threads at once.
pub struct ls_surface(loopsurf::Surface);

/// Writes the library version (each pointer may be NULL).
#[no_mangle]
pub unsafe extern "C" fn ls_version(
    major: *mut std::ffi::c_int,
    minor: *mut std::ffi::c_int,
    patch: *mut std::ffi::c_int,
) {
    let parse = |s: &str| s.parse().unwrap_or(0);
    for (p, v) in [
        (major, env!("CARGO_PKG_VERSION_MAJOR")),
        (minor, env!("CARGO_PKG_VERSION_MINOR")),
        (patch, env!("CARGO_PKG_VERSION_PATCH")),
    ] {
        if !p.is_null() {
            *p = parse(v);
        }
    }
}
