//! What the reader gives: [`VtuMesh`] and its arrays, the entry points, and
//! the conversion to a [`LagrangeMesh`].

use std::path::Path;

use glam::DVec3;

use super::grid::parse_xml;
use super::{
    VTK_CUBIC_LINE, VTK_LAGRANGE_CURVE, VTK_LAGRANGE_TRIANGLE, VTK_LINE, VTK_QUADRATIC_EDGE,
    VTK_QUADRATIC_TRIANGLE, VTK_TRIANGLE,
};
use crate::error::{Error, Result};
use crate::io::lagrange::{triangle_order, LagrangeMesh};

/// What [`read_vtu`] found in a `.vtu` file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct VtuMesh {
    pub points: Vec<DVec3>,
    /// Per cell its VTK type.
    pub cell_types: Vec<u8>,
    /// Per cell the end of its nodes in `connectivity` (VTK's offsets).
    pub offsets: Vec<usize>,
    /// Every cell's point indices, back to back.
    pub connectivity: Vec<u32>,
    /// The `PointData` arrays, in file order.
    pub point_data: Vec<VtuArray>,
    /// The `CellData` arrays, in file order.
    pub cell_data: Vec<VtuArray>,
}

/// A data array read from a `.vtu` file. Values of every type are kept as
/// f64 (integers exactly up to 2^53).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct VtuArray {
    pub name: String,
    pub components: usize,
    /// `components` values per point or cell.
    pub values: Vec<f64>,
}

impl VtuMesh {
    /// Number of cells.
    pub fn num_cells(&self) -> usize {
        self.cell_types.len()
    }

    /// Cell `c`: its VTK type and point indices. Panics when `c` is out of
    /// range, like slice indexing.
    pub fn cell(&self, c: usize) -> (u8, &[u32]) {
        let start = if c == 0 { 0 } else { self.offsets[c - 1] };
        (
            self.cell_types[c],
            &self.connectivity[start..self.offsets[c]],
        )
    }

    /// The point array called `name`, if any.
    pub fn point_array(&self, name: &str) -> Option<&VtuArray> {
        self.point_data.iter().find(|a| a.name == name)
    }

    /// The cell array called `name`, if any.
    pub fn cell_array(&self, name: &str) -> Option<&VtuArray> {
        self.cell_data.iter().find(|a| a.name == name)
    }

    /// The mesh as a [`LagrangeMesh`]: triangle cells (VTK_TRIANGLE,
    /// VTK_QUADRATIC_TRIANGLE, VTK_LAGRANGE_TRIANGLE) and line cells
    /// (VTK_LINE, VTK_QUADRATIC_EDGE, VTK_CUBIC_LINE, VTK_LAGRANGE_CURVE),
    /// all of one order, in cell order; other cells are skipped. Faces and
    /// curves come from the cell arrays `face` and `curve` (0 without
    /// them), corners from the point array `corner` (ascending node order)
    /// and params from `loopsurf_params`: what [`write_vtu_lagrange`](super::write_vtu_lagrange)
    /// writes, so its files come back identical but for the corners'
    /// order.
    pub fn to_lagrange(&self) -> Result<LagrangeMesh> {
        let mut order = None;
        let mut mesh = LagrangeMesh {
            nodes: self.points.clone(),
            ..Default::default()
        };
        let (face, curve) = (self.cell_array("face"), self.cell_array("curve"));
        for c in 0..self.num_cells() {
            let (ty, nodes) = self.cell(c);
            let Some((is_triangle, k)) = lagrange_cell(c, ty, nodes.len())? else {
                continue;
            };
            if *order.get_or_insert(k) != k {
                return Err(Error::InvalidArgument(format!(
                    "cell {c} is of order {k}, but the mesh is of order {}: \
                     a Lagrange mesh has one order",
                    order.unwrap_or(k)
                )));
            }
            if is_triangle {
                mesh.triangles.extend_from_slice(nodes);
                mesh.faces.push(id_of(face, "cell", c)?);
            } else {
                mesh.lines.extend_from_slice(nodes);
                mesh.line_curves.push(id_of(curve, "cell", c)?);
            }
        }
        mesh.order = order.unwrap_or(1);
        if let Some(corner) = self.point_array("corner") {
            for (i, &x) in corner.values.iter().step_by(corner.components).enumerate() {
                if x != -1.0 {
                    mesh.corners
                        .push((i as u32, id_of(Some(corner), "point", i)?));
                }
            }
        }
        if let Some(params) = self.point_array("loopsurf_params") {
            if params.components != 3 {
                return Err(Error::InvalidArgument(format!(
                    "point array \"loopsurf_params\" has {} components; (triangle, v, w) needs 3",
                    params.components
                )));
            }
            for (i, p) in params.values.chunks_exact(3).enumerate() {
                let t = id_of(Some(params), "point", i)?;
                mesh.params.push((t, p[1], p[2]));
            }
        }
        mesh.validate()?;
        Ok(mesh)
    }
}

/// Cell c of VTK type `ty` with n points as a Lagrange cell: whether it is
/// a triangle (else a line) and its order; `None` for a type that is
/// neither, an error for a triangle or line type with a count no order
/// has.
fn lagrange_cell(c: usize, ty: u8, n: usize) -> Result<Option<(bool, usize)>> {
    let (is_triangle, k) = match ty {
        VTK_TRIANGLE if n == 3 => (true, Some(1)),
        VTK_QUADRATIC_TRIANGLE if n == 6 => (true, Some(2)),
        VTK_LAGRANGE_TRIANGLE => (true, triangle_order(n)),
        VTK_LINE if n == 2 => (false, Some(1)),
        VTK_QUADRATIC_EDGE if n == 3 => (false, Some(2)),
        VTK_CUBIC_LINE if n == 4 => (false, Some(3)),
        VTK_LAGRANGE_CURVE if (2..=5).contains(&n) => (false, Some(n - 1)),
        VTK_TRIANGLE
        | VTK_QUADRATIC_TRIANGLE
        | VTK_LINE
        | VTK_QUADRATIC_EDGE
        | VTK_CUBIC_LINE
        | VTK_LAGRANGE_CURVE => (false, None),
        _ => return Ok(None),
    };
    let Some(k) = k else {
        return Err(Error::InvalidArgument(format!(
            "cell {c} of type {ty} has {n} points, which is no Lagrange cell of order 1 to 4"
        )));
    };
    Ok(Some((is_triangle, k)))
}

/// A whole, non-negative id from entry i of a one-component array (0
/// without the array); `what` names the entry in the error.
fn id_of(array: Option<&VtuArray>, what: &str, i: usize) -> Result<u32> {
    let Some(a) = array else { return Ok(0) };
    let x = a.values[i * a.components];
    if x >= 0.0 && x <= u32::MAX as f64 && x.fract() == 0.0 {
        Ok(x as u32)
    } else {
        Err(Error::InvalidArgument(format!(
            "{what} {i}: array {:?} gives {x}, not an id",
            a.name
        )))
    }
}

/// Reads a VTK XML UnstructuredGrid (`.vtu`) file with ASCII or inline
/// binary (base64, uncompressed) arrays.
pub fn read_vtu(path: &Path) -> Result<VtuMesh> {
    parse_vtu(&crate::io::read_bytes(path)?, path)
}

/// [`read_vtu`] of bytes already in memory; `path` names the source in
/// errors.
pub fn parse_vtu(data: &[u8], path: &Path) -> Result<VtuMesh> {
    let line_of = |at: usize| {
        1 + data[..at.min(data.len())]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
    };
    parse_xml(data).map_err(|(at, message)| {
        let line = line_of(at);
        Error::Malformed { line, message }.in_file(path, Some(line))
    })
}
