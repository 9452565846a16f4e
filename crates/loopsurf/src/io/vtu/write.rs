//! The `.vtu` writer: checks points, cells and arrays, then writes VTK XML
//! with ASCII or inline binary (base64) arrays.

use std::io::Write;
use std::path::Path;

use glam::DVec3;

use super::binary;
use super::{VTK_LAGRANGE_CURVE, VTK_LAGRANGE_TRIANGLE, VTK_LINE, VTK_TRIANGLE};
use crate::error::{Error, Result};
use crate::io::lagrange::LagrangeMesh;

/// The array names [`write_vtu_lagrange`] writes itself.
const RESERVED: [&str; 4] = ["loopsurf_params", "corner", "face", "curve"];

/// One named data array attached to points or cells.
#[derive(Debug, Clone, Copy)]
pub enum DataArray<'a> {
    /// One double per element (`Float64`).
    F64(&'a [f64]),
    /// One 32-bit integer per element (`Int32`), e.g. component IDs.
    I32(&'a [i32]),
    /// One 64-bit integer per element (`Int64`), e.g. global node ids.
    I64(&'a [i64]),
    /// One 3-vector per element (`Float64`, 3 components), e.g. normals.
    Vec3(&'a [DVec3]),
}

impl DataArray<'_> {
    fn len(&self) -> usize {
        match self {
            DataArray::F64(a) => a.len(),
            DataArray::I32(a) => a.len(),
            DataArray::I64(a) => a.len(),
            DataArray::Vec3(a) => a.len(),
        }
    }

    /// The values' little-endian bytes, as a binary DataArray holds them.
    fn le_bytes(&self) -> Vec<u8> {
        match self {
            DataArray::F64(a) => a.iter().flat_map(|x| x.to_le_bytes()).collect(),
            DataArray::I32(a) => a.iter().flat_map(|x| x.to_le_bytes()).collect(),
            DataArray::I64(a) => a.iter().flat_map(|x| x.to_le_bytes()).collect(),
            DataArray::Vec3(a) => a
                .iter()
                .flat_map(|p| p.to_array())
                .flat_map(|x| x.to_le_bytes())
                .collect(),
        }
    }

    /// The first non-finite value, if any.
    fn non_finite(&self) -> Option<usize> {
        match self {
            DataArray::F64(a) => a.iter().position(|x| !x.is_finite()),
            DataArray::I32(_) | DataArray::I64(_) => None,
            DataArray::Vec3(a) => a.iter().position(|v| !v.is_finite()),
        }
    }
}

/// Cells of one VTK type and size, back to back.
struct CellBlock<'a> {
    nodes: &'a [u32],
    per_cell: usize,
    vtk_type: u8,
}

impl CellBlock<'_> {
    fn len(&self) -> usize {
        self.nodes.len() / self.per_cell
    }
}

/// Writes a `.vtu` file with the given point and cell arrays. Every point
/// array must have one entry per point, every cell array one per triangle.
/// `binary` writes the arrays as inline base64 (VTK's `format="binary"`,
/// about half the size of ASCII) instead of text.
pub fn write_vtu(
    path: &Path,
    points: &[DVec3],
    tris: &[[u32; 3]],
    point_data: &[(&str, DataArray)],
    cell_data: &[(&str, DataArray)],
    binary: bool,
) -> Result<()> {
    write_vtu_with_lines(path, points, tris, &[], point_data, cell_data, binary)
}

/// [`write_vtu`] with line cells (VTK_LINE) after the triangles, e.g. the
/// hard edges. Every cell array has one entry per cell, triangles first:
/// `tris.len() + lines.len()` of them.
pub fn write_vtu_with_lines(
    path: &Path,
    points: &[DVec3],
    tris: &[[u32; 3]],
    lines: &[[u32; 2]],
    point_data: &[(&str, DataArray)],
    cell_data: &[(&str, DataArray)],
    binary: bool,
) -> Result<()> {
    crate::io::check_tris(points, tris)?;
    for (l, line) in lines.iter().enumerate() {
        if let Some(&i) = line.iter().find(|&&i| i as usize >= points.len()) {
            return Err(Error::InvalidArgument(format!(
                "line {l} {line:?} refers to vertex {i}, but there are only {} points",
                points.len()
            )));
        }
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "point {i} {:?} is not finite; VTK cannot read it",
            points[i]
        )));
    }
    let blocks = [
        CellBlock {
            nodes: tris.as_flattened(),
            per_cell: 3,
            vtk_type: VTK_TRIANGLE,
        },
        CellBlock {
            nodes: lines.as_flattened(),
            per_cell: 2,
            vtk_type: VTK_LINE,
        },
    ];
    write_checked(path, points, &blocks, (point_data, cell_data), binary)
}

/// Writes a curved mesh as VTK Lagrange cells: the triangles as
/// VTK_LAGRANGE_TRIANGLE (VTK_TRIANGLE for order 1), then the lines as
/// VTK_LAGRANGE_CURVE (VTK_LINE for order 1), nodes in the mesh's (gmsh's)
/// order, which is VTK's. ParaView draws them curved (raise "Nonlinear
/// Subdivision Level" to see it).
///
/// Besides the caller's arrays it always writes, so that [`read_vtu`](super::read_vtu) and
/// [`VtuMesh::to_lagrange`](super::VtuMesh::to_lagrange) give the mesh back:
/// - cell array `face` (Int32): the triangle's face id, −1 on lines;
/// - cell array `curve` (Int32): the line's curve id, −1 on triangles;
/// - point array `loopsurf_params` (Float64, 3 components: triangle, v, w)
///   when the mesh has params (or no nodes);
/// - point array `corner` (Int32): the corner id, −1 elsewhere, when the
///   mesh has corners.
///
/// Caller arrays come after these, must not reuse their names, and have one
/// entry per node (point data) or per cell, triangles first (cell data).
/// `binary` as in [`write_vtu`].
pub fn write_vtu_lagrange(
    path: &Path,
    mesh: &LagrangeMesh,
    point_data: &[(&str, DataArray)],
    cell_data: &[(&str, DataArray)],
    binary: bool,
) -> Result<()> {
    mesh.validate()?;
    for (name, _) in point_data.iter().chain(cell_data) {
        if RESERVED.contains(name) {
            return Err(Error::InvalidArgument(format!(
                "array name {name:?} is written by write_vtu_lagrange itself; choose another"
            )));
        }
    }
    let (ntris, nlines) = (mesh.num_triangles(), mesh.num_lines());
    let params: Vec<DVec3> = mesh
        .params
        .iter()
        .map(|&(t, v, w)| DVec3::new(t as f64, v, w))
        .collect();
    let mut corner = Vec::new();
    if !mesh.corners.is_empty() {
        corner = vec![-1; mesh.nodes.len()];
        for &(node, id) in &mesh.corners {
            corner[node as usize] = id as i32;
        }
    }
    // Ids fit in i32: validate() checked they are below i32::MAX.
    let face: Vec<i32> = mesh
        .faces
        .iter()
        .map(|&f| f as i32)
        .chain(std::iter::repeat(-1).take(nlines))
        .collect();
    let curve: Vec<i32> = std::iter::repeat(-1)
        .take(ntris)
        .chain(mesh.line_curves.iter().map(|&c| c as i32))
        .collect();
    let mut points_out: Vec<(&str, DataArray)> = Vec::new();
    // An empty mesh has (no) params too: a rank's empty piece of a .pvtu
    // then has the arrays its other pieces have.
    if !params.is_empty() || mesh.nodes.is_empty() {
        points_out.push(("loopsurf_params", DataArray::Vec3(&params)));
    }
    if !corner.is_empty() {
        points_out.push(("corner", DataArray::I32(&corner)));
    }
    points_out.extend_from_slice(point_data);
    let mut cells_out = vec![
        ("face", DataArray::I32(&face)),
        ("curve", DataArray::I32(&curve)),
    ];
    cells_out.extend_from_slice(cell_data);
    let linear = mesh.order == 1;
    let blocks = [
        CellBlock {
            nodes: &mesh.triangles,
            per_cell: mesh.nodes_per_triangle(),
            vtk_type: if linear {
                VTK_TRIANGLE
            } else {
                VTK_LAGRANGE_TRIANGLE
            },
        },
        CellBlock {
            nodes: &mesh.lines,
            per_cell: mesh.nodes_per_line(),
            vtk_type: if linear { VTK_LINE } else { VTK_LAGRANGE_CURVE },
        },
    ];
    write_checked(
        path,
        &mesh.nodes,
        &blocks,
        (&points_out, &cells_out),
        binary,
    )
}

/// The point and the cell arrays.
type Arrays<'a, 'b> = (
    &'a [(&'b str, DataArray<'b>)],
    &'a [(&'b str, DataArray<'b>)],
);

/// Checks the arrays against the points and cells, then writes.
fn write_checked(
    path: &Path,
    points: &[DVec3],
    blocks: &[CellBlock],
    (point_data, cell_data): Arrays,
    binary: bool,
) -> Result<()> {
    let ncells: usize = blocks.iter().map(CellBlock::len).sum();
    for (kind, arrays, n) in [
        ("point", point_data, points.len()),
        ("cell", cell_data, ncells),
    ] {
        for (name, array) in arrays {
            if array.len() != n {
                return Err(Error::InvalidArgument(format!(
                    "{kind} array {name:?} has {} values for {n} {kind}s",
                    array.len()
                )));
            }
            if let Some(i) = array.non_finite() {
                return Err(Error::InvalidArgument(format!(
                    "{kind} array {name:?} has a non-finite value at {i}; VTK cannot read it"
                )));
            }
        }
    }
    let mut w = crate::io::create(path)?;
    write_body(&mut w, points, blocks, (point_data, cell_data), binary)
        .map_err(crate::io::io_error(path))?;
    crate::io::finish(w, path)
}

fn write_body(
    w: &mut impl Write,
    points: &[DVec3],
    blocks: &[CellBlock],
    (point_data, cell_data): Arrays,
    binary: bool,
) -> std::io::Result<()> {
    let ncells: usize = blocks.iter().map(CellBlock::len).sum();
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(
        w,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">"
    )?;
    writeln!(w, "  <UnstructuredGrid>")?;
    writeln!(
        w,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{ncells}\">",
        points.len(),
    )?;
    for (tag, arrays) in [("PointData", point_data), ("CellData", cell_data)] {
        writeln!(w, "      <{tag}>")?;
        for (name, array) in arrays {
            write_array(w, name, array, binary)?;
        }
        writeln!(w, "      </{tag}>")?;
    }
    writeln!(w, "      <Points>")?;
    write_array(w, "Points", &DataArray::Vec3(points), binary)?;
    writeln!(w, "      </Points>")?;
    writeln!(w, "      <Cells>")?;
    if binary {
        write_cells_binary(w, blocks)?;
    } else {
        write_cells_ascii(w, blocks)?;
    }
    writeln!(w, "      </Cells>")?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </UnstructuredGrid>")?;
    writeln!(w, "</VTKFile>")
}

/// Each cell's end in the connectivity (VTK's offsets).
fn offsets<'a>(blocks: &'a [CellBlock]) -> impl Iterator<Item = u64> + 'a {
    blocks
        .iter()
        .flat_map(|b| std::iter::repeat(b.per_cell as u64).take(b.len()))
        .scan(0, |end, n| {
            *end += n;
            Some(*end)
        })
}

/// Each cell's VTK type.
fn types<'a>(blocks: &'a [CellBlock]) -> impl Iterator<Item = u8> + 'a {
    blocks
        .iter()
        .flat_map(|b| std::iter::repeat(b.vtk_type).take(b.len()))
}

fn write_cells_ascii(w: &mut impl Write, blocks: &[CellBlock]) -> std::io::Result<()> {
    open_array(w, "Int64", "connectivity", None, false)?;
    for block in blocks {
        for cell in block.nodes.chunks_exact(block.per_cell) {
            w.write_all(b"         ")?;
            for i in cell {
                write!(w, " {i}")?;
            }
            w.write_all(b"\n")?;
        }
    }
    writeln!(w, "        </DataArray>")?;
    open_array(w, "Int64", "offsets", None, false)?;
    for end in offsets(blocks) {
        writeln!(w, "          {end}")?;
    }
    writeln!(w, "        </DataArray>")?;
    open_array(w, "UInt8", "types", None, false)?;
    for t in types(blocks) {
        writeln!(w, "          {t}")?;
    }
    writeln!(w, "        </DataArray>")
}

/// Connectivity and offsets as Int64 (as in ASCII, so the reader's
/// counts need no second width), types as UInt8.
fn write_cells_binary(w: &mut impl Write, blocks: &[CellBlock]) -> std::io::Result<()> {
    let conn: Vec<u8> = blocks
        .iter()
        .flat_map(|b| b.nodes.iter().flat_map(|&i| (i as i64).to_le_bytes()))
        .collect();
    let offs: Vec<u8> = offsets(blocks)
        .flat_map(|e| (e as i64).to_le_bytes())
        .collect();
    let tys: Vec<u8> = types(blocks).collect();
    for (ty, name, bytes) in [
        ("Int64", "connectivity", conn),
        ("Int64", "offsets", offs),
        ("UInt8", "types", tys),
    ] {
        open_array(w, ty, name, None, true)?;
        write_encoded(w, &bytes)?;
    }
    Ok(())
}

/// A DataArray's opening tag; `components` is written when given.
fn open_array(
    w: &mut impl Write,
    ty: &str,
    name: &str,
    components: Option<usize>,
    binary: bool,
) -> std::io::Result<()> {
    let comps = components.map_or(String::new(), |c| format!(" NumberOfComponents=\"{c}\""));
    let format = if binary { "binary" } else { "ascii" };
    writeln!(
        w,
        "        <DataArray type=\"{ty}\" Name=\"{}\"{comps} format=\"{format}\">",
        xml_escape(name)
    )
}

/// A binary array's content, one base64 line, and its closing tag.
fn write_encoded(w: &mut impl Write, bytes: &[u8]) -> std::io::Result<()> {
    writeln!(w, "          {}", binary::encode(bytes))?;
    writeln!(w, "        </DataArray>")
}

fn write_array(
    w: &mut impl Write,
    name: &str,
    array: &DataArray,
    binary: bool,
) -> std::io::Result<()> {
    let (ty, comps) = match array {
        DataArray::F64(_) => ("Float64", 1),
        DataArray::I32(_) => ("Int32", 1),
        DataArray::I64(_) => ("Int64", 1),
        DataArray::Vec3(_) => ("Float64", 3),
    };
    open_array(w, ty, name, Some(comps), binary)?;
    if binary {
        return write_encoded(w, &array.le_bytes());
    }
    match array {
        DataArray::F64(a) => {
            for &x in *a {
                w.write_all(b"          ")?;
                crate::io::write_f64(w, x)?;
                w.write_all(b"\n")?;
            }
        }
        DataArray::I32(a) => {
            for x in *a {
                writeln!(w, "          {x}")?;
            }
        }
        DataArray::I64(a) => {
            for x in *a {
                writeln!(w, "          {x}")?;
            }
        }
        DataArray::Vec3(a) => {
            for &p in *a {
                w.write_all(b"          ")?;
                crate::io::write_point(w, p)?;
                w.write_all(b"\n")?;
            }
        }
    }
    writeln!(w, "        </DataArray>")
}

/// Array names are user text inside an XML attribute.
fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}
