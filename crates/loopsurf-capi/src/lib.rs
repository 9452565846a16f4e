//! The C ABI of loopsurf: opaque handles, `int` status codes (0 success,
//! negative errors, EGADS style) and a thread-local error message.
//!
//! Every function checks every pointer, writes its outputs only on success,
//! and catches panics at the boundary: nothing unwinds into C and the
//! library never prints. A `const` handle is never mutated, and a built
//! surface may be queried from any number of threads at once. Indices are
//! 0-based. A call whose options may grow takes an options struct that
//! starts with `struct_size` and has a `*_default()` function. This crate
//! only translates: all geometry lives in `loopsurf`. `docs/c-api.md`
//! writes these conventions down.
//!
//! Each module is one stage of a handle's lifecycle, and
//! `include/loopsurf.h` has one section per stage, in lifecycle order:
//! `tests/header.rs` names the sections and their modules, generates the
//! header with cbindgen section by section, and fails when the committed
//! copy is stale.

#![allow(non_camel_case_types)]
// Raw pointers are validated by `status::input`/`output` before use; every
// exported function documents its pointer contract in the header instead.
#![allow(clippy::missing_safety_doc)]

mod buffers;
mod handles;

pub mod adapt;
pub mod closest;
pub mod evaluate;
pub mod fit;
pub mod mesh;
pub mod mesh_curve;
pub mod mesh_labels;
pub mod model;
pub mod net;
pub mod part;
pub mod part_surface;
pub mod partition;
pub mod project;
pub mod refine;
pub mod remesh;
pub mod remesh_job;
pub mod snap;
pub mod status;
pub mod stream;
pub mod surface;
pub mod trimesh;
pub mod trimesh_write;

pub use adapt::*;
pub use closest::*;
pub use evaluate::*;
pub use mesh::*;
pub use mesh_curve::*;
pub use mesh_labels::*;
pub use model::*;
pub use net::*;
pub use project::*;
pub use refine::*;
pub use remesh::*;
pub use remesh_job::*;
pub use snap::*;
pub use status::*;
pub use stream::*;
pub use surface::*;
pub use trimesh::*;
