//! VTK XML UnstructuredGrid (`.vtu`), ASCII or with inline binary arrays,
//! for looking at results in ParaView: a triangulation plus named
//! per-point and per-cell arrays (curvature, error fields, component IDs),
//! curved (Lagrange) meshes, and reading such files back.
//!
//! Hand-written because the subset is tiny: Points as Float64 triples,
//! Cells as Int64 connectivity and offsets with UInt8 type 5 (VTK_TRIANGLE)
//! and, after the triangles, optionally type 3 (VTK_LINE) for edges such
//! as the hard ones: one piece of mixed cells, which ParaView shows
//! together and splits with "Extract Cells By Type" or a threshold on a
//! cell array. Curved meshes ([`write_vtu_lagrange`]) use
//! VTK_LAGRANGE_TRIANGLE (69) and VTK_LAGRANGE_CURVE (68) instead, whose
//! point order is gmsh's for orders 1 to 4 (`vtkLagrangeTriangle`'s
//! barycentric indexing numbers the order-4 interior points (1,1), (2,1),
//! (1,2) in quarters, as gmsh does), so nodes are written as they are.
//! VTK's ASCII reader cannot parse `nan` or `inf`, so non-finite values are
//! refused instead of producing a file ParaView chokes on.
//!
//! With `binary` the writers put every array inline as base64
//! (`format="binary"`, UInt64 byte counts; see `binary` for why not raw
//! appended data): about half the size of ASCII, the same bits.
//!
//! The reader ([`read_vtu`]) takes ASCII and inline binary arrays
//! (UInt32 or UInt64 byte counts): ours, and what ParaView saves with
//! "Data Mode" Ascii or Binary, uncompressed. Appended and compressed data
//! are refused with a message saying so, rather than half-supported.
//!
//! The writer is in `write`; the reader is the [`VtuMesh`] it returns
//! (`read`), a small XML tag scanner (`xml`), the base64 arrays
//! (`binary`) and the UnstructuredGrid built from its tags (`grid`).

mod binary;
#[cfg(test)]
mod binary_tests;
mod grid;
mod read;
#[cfg(test)]
mod tests;
mod write;
mod xml;

pub use read::{parse_vtu, read_vtu, VtuArray, VtuMesh};
pub use write::{write_vtu, write_vtu_lagrange, write_vtu_with_lines, DataArray};

/// VTK cell types this module writes or understands.
const VTK_LINE: u8 = 3;
const VTK_TRIANGLE: u8 = 5;
const VTK_QUADRATIC_EDGE: u8 = 21;
const VTK_QUADRATIC_TRIANGLE: u8 = 22;
const VTK_CUBIC_LINE: u8 = 35;
const VTK_LAGRANGE_CURVE: u8 = 68;
const VTK_LAGRANGE_TRIANGLE: u8 = 69;
