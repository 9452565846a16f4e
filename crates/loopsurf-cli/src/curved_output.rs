//! Curved meshes out, for `mesh --order K` and `curve`: gmsh `.msh` 4.1
//! (ASCII, or binary with `--binary`) or VTK `.vtu` with Lagrange cells,
//! and the summary lines about their validity.

use loopsurf::io::{self, DataArray};
use loopsurf::mesh::high_order::{CurvedMesh, Validity};
use loopsurf::Error;
use std::io::Write;
use std::path::Path;

/// The formats that carry curved elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurvedFormat {
    Msh,
    Vtu,
}

impl CurvedFormat {
    /// The curved format `path`'s extension names, if any.
    pub fn of(path: &Path) -> Option<CurvedFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "msh" => Some(CurvedFormat::Msh),
            "vtu" => Some(CurvedFormat::Vtu),
            _ => None,
        }
    }
}

/// Refuses, before any work, an output that cannot carry order `order`.
pub fn check_output(path: &Path, order: usize) -> Result<(), Error> {
    if CurvedFormat::of(path).is_some() {
        return Ok(());
    }
    if order > 1 {
        return Err(Error::InvalidArgument(format!(
            "{}: order {order} needs a .msh or .vtu output (other formats hold flat triangles only)",
            path.display()
        )));
    }
    io::check_writable(path)
}

/// Writes the curved mesh. The `.vtu` carries per node `loopsurf_params`
/// (tri, v, w) and `corner`, and per cell the model `face` and `curve`
/// ([`io::write_vtu_lagrange`]) and the `scaled_jacobian` (triangles; 1 on
/// the lines).
pub fn write_curved(
    path: &Path,
    curved: &CurvedMesh,
    validity: &Validity,
    binary: bool,
) -> Result<(), Error> {
    let lagrange = curved.to_lagrange();
    match CurvedFormat::of(path) {
        Some(CurvedFormat::Msh) => io::write_msh(path, &lagrange, binary),
        Some(CurvedFormat::Vtu) => {
            let jacobian: Vec<f64> = validity
                .scaled_jacobians
                .iter()
                .copied()
                .chain(std::iter::repeat(1.0).take(curved.line_curves.len()))
                .collect();
            io::write_vtu_lagrange(
                path,
                &lagrange,
                &[],
                &[("scaled_jacobian", DataArray::F64(&jacobian))],
                binary,
            )
        }
        None => Err(Error::InvalidArgument(format!(
            "{}: curved elements go to .msh or .vtu",
            path.display()
        ))),
    }
}

/// The summary's lines on a curved mesh: nodes, and the scaled Jacobian
/// with the invalid elements named (the first ten).
pub fn summary(
    out: &mut dyn Write,
    curved: &CurvedMesh,
    validity: &Validity,
) -> std::io::Result<()> {
    writeln!(
        out,
        "order {}: {} nodes ({} per triangle), {} curved hard-edge lines",
        curved.order,
        curved.nodes.len(),
        curved.nodes_per_triangle(),
        curved.line_curves.len()
    )?;
    let named: Vec<String> = validity
        .invalid
        .iter()
        .take(10)
        .map(|t| t.to_string())
        .collect();
    let more = if validity.invalid.len() > named.len() {
        ", …"
    } else {
        ""
    };
    writeln!(
        out,
        "scaled Jacobian: min {:.4}, {} elements at or below 0{}",
        validity.min,
        validity.invalid.len(),
        if named.is_empty() {
            String::new()
        } else {
            format!(
                " (triangles {}{more}: too curved for their size; refine there)",
                named.join(", ")
            )
        }
    )
}
