//! VTK XML UnstructuredGrid (`.vtu`), ASCII, for looking at results in
//! ParaView: a triangulation plus named per-point and per-cell arrays
//! (curvature, error fields, component IDs), curved (Lagrange) meshes, and
//! reading ASCII files back.
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
//! The reader ([`read_vtu`]) takes ASCII files: ours, and what ParaView
//! saves with "Data Mode: Ascii". Binary and appended data are refused
//! with a message saying so, rather than half-supported.

use std::io::Write;
use std::path::Path;

use glam::DVec3;

use super::lagrange::{triangle_order, LagrangeMesh};
use crate::error::{Error, Result};

/// VTK cell types this module writes or understands.
const VTK_LINE: u8 = 3;
const VTK_TRIANGLE: u8 = 5;
const VTK_QUADRATIC_EDGE: u8 = 21;
const VTK_QUADRATIC_TRIANGLE: u8 = 22;
const VTK_CUBIC_LINE: u8 = 35;
const VTK_LAGRANGE_CURVE: u8 = 68;
const VTK_LAGRANGE_TRIANGLE: u8 = 69;

/// The array names [`write_vtu_lagrange`] writes itself.
const RESERVED: [&str; 4] = ["loopsurf_params", "corner", "face", "curve"];

/// One named data array attached to points or cells.
#[derive(Debug, Clone, Copy)]
pub enum DataArray<'a> {
    /// One double per element (`Float64`).
    F64(&'a [f64]),
    /// One 32-bit integer per element (`Int32`), e.g. component IDs.
    I32(&'a [i32]),
    /// One 3-vector per element (`Float64`, 3 components), e.g. normals.
    Vec3(&'a [DVec3]),
}

impl DataArray<'_> {
    fn len(&self) -> usize {
        match self {
            DataArray::F64(a) => a.len(),
            DataArray::I32(a) => a.len(),
            DataArray::Vec3(a) => a.len(),
        }
    }

    /// The first non-finite value, if any.
    fn non_finite(&self) -> Option<usize> {
        match self {
            DataArray::F64(a) => a.iter().position(|x| !x.is_finite()),
            DataArray::I32(_) => None,
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
pub fn write_vtu(
    path: &Path,
    points: &[DVec3],
    tris: &[[u32; 3]],
    point_data: &[(&str, DataArray)],
    cell_data: &[(&str, DataArray)],
) -> Result<()> {
    write_vtu_with_lines(path, points, tris, &[], point_data, cell_data)
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
) -> Result<()> {
    super::check_tris(points, tris)?;
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
    write_checked(path, points, &blocks, point_data, cell_data)
}

/// Writes a curved mesh as VTK Lagrange cells: the triangles as
/// VTK_LAGRANGE_TRIANGLE (VTK_TRIANGLE for order 1), then the lines as
/// VTK_LAGRANGE_CURVE (VTK_LINE for order 1), nodes in the mesh's (gmsh's)
/// order, which is VTK's. ParaView draws them curved (raise "Nonlinear
/// Subdivision Level" to see it).
///
/// Besides the caller's arrays it always writes, so that [`read_vtu`] and
/// [`VtuMesh::to_lagrange`] give the mesh back:
/// - cell array `face` (Int32): the triangle's face id, −1 on lines;
/// - cell array `curve` (Int32): the line's curve id, −1 on triangles;
/// - point array `loopsurf_params` (Float64, 3 components: triangle, v, w)
///   when the mesh has params;
/// - point array `corner` (Int32): the corner id, −1 elsewhere, when the
///   mesh has corners.
///
/// Caller arrays come after these, must not reuse their names, and have one
/// entry per node (point data) or per cell, triangles first (cell data).
pub fn write_vtu_lagrange(
    path: &Path,
    mesh: &LagrangeMesh,
    point_data: &[(&str, DataArray)],
    cell_data: &[(&str, DataArray)],
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
    if !params.is_empty() {
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
    write_checked(path, &mesh.nodes, &blocks, &points_out, &cells_out)
}

/// Checks the arrays against the points and cells, then writes.
fn write_checked(
    path: &Path,
    points: &[DVec3],
    blocks: &[CellBlock],
    point_data: &[(&str, DataArray)],
    cell_data: &[(&str, DataArray)],
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
    let mut w = super::create(path)?;
    write_body(&mut w, points, blocks, point_data, cell_data).map_err(super::io_error(path))?;
    super::finish(w, path)
}

fn write_body(
    w: &mut impl Write,
    points: &[DVec3],
    blocks: &[CellBlock],
    point_data: &[(&str, DataArray)],
    cell_data: &[(&str, DataArray)],
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
            write_array(w, name, array)?;
        }
        writeln!(w, "      </{tag}>")?;
    }
    writeln!(w, "      <Points>")?;
    write_array(w, "Points", &DataArray::Vec3(points))?;
    writeln!(w, "      </Points>")?;
    writeln!(w, "      <Cells>")?;
    writeln!(
        w,
        "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
    )?;
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
    writeln!(
        w,
        "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
    )?;
    let mut end = 0;
    for block in blocks {
        for _ in 0..block.len() {
            end += block.per_cell as u64;
            writeln!(w, "          {end}")?;
        }
    }
    writeln!(w, "        </DataArray>")?;
    writeln!(
        w,
        "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">"
    )?;
    for block in blocks {
        for _ in 0..block.len() {
            writeln!(w, "          {}", block.vtk_type)?;
        }
    }
    writeln!(w, "        </DataArray>")?;
    writeln!(w, "      </Cells>")?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </UnstructuredGrid>")?;
    writeln!(w, "</VTKFile>")
}
fn write_array(w: &mut impl Write, name: &str, array: &DataArray) -> std::io::Result<()> {
    let (ty, comps) = match array {
        DataArray::F64(_) => ("Float64", 1),
        DataArray::I32(_) => ("Int32", 1),
        DataArray::Vec3(_) => ("Float64", 3),
    };
    writeln!(
        w,
        "        <DataArray type=\"{ty}\" Name=\"{}\" NumberOfComponents=\"{comps}\" format=\"ascii\">",
        xml_escape(name)
    )?;
    match array {
        DataArray::F64(a) => {
            for &x in *a {
                w.write_all(b"          ")?;
                super::write_f64(w, x)?;
                w.write_all(b"\n")?;
            }
        }
        DataArray::I32(a) => {
            for x in *a {
                writeln!(w, "          {x}")?;
            }
        }
        DataArray::Vec3(a) => {
            for &p in *a {
                w.write_all(b"          ")?;
                super::write_point(w, p)?;
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

// ---------------------------------------------------------------- reader

/// What [`read_vtu`] found in an ASCII `.vtu` file.
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
    /// and params from `loopsurf_params`: what [`write_vtu_lagrange`]
    /// writes, so its files come back identical but for the corners'
    /// order.
    pub fn to_lagrange(&self) -> Result<LagrangeMesh> {
        let bad = |message: String| Err(Error::InvalidArgument(message));
        let mut order = None;
        let mut mesh = LagrangeMesh {
            nodes: self.points.clone(),
            ..Default::default()
        };
        // A whole, non-negative id from a one-component array.
        let id_of = |array: Option<&VtuArray>, what: &str, i: usize| -> Result<u32> {
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
        };
        let (face, curve) = (self.cell_array("face"), self.cell_array("curve"));
        for c in 0..self.num_cells() {
            let (ty, nodes) = self.cell(c);
            let n = nodes.len();
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
                _ => continue,
            };
            let Some(k) = k else {
                return bad(format!(
                    "cell {c} of type {ty} has {n} points, which is no Lagrange cell of order 1 to 4"
                ));
            };
            if *order.get_or_insert(k) != k {
                return bad(format!(
                    "cell {c} is of order {k}, but the mesh is of order {}: \
                     a Lagrange mesh has one order",
                    order.unwrap_or(k)
                ));
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
                return bad(format!(
                    "point array \"loopsurf_params\" has {} components; (triangle, v, w) needs 3",
                    params.components
                ));
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

/// Reads an ASCII VTK XML UnstructuredGrid (`.vtu`) file.
pub fn read_vtu(path: &Path) -> Result<VtuMesh> {
    parse_vtu(&super::read_bytes(path)?, path)
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

/// A parse error: the byte offset it refers to and what is wrong.
type XmlError = (usize, String);

/// One XML tag.
struct Tag<'a> {
    name: &'a [u8],
    attrs: Vec<(&'a [u8], String)>,
    closing: bool,
    empty: bool,
    /// Offsets of `<` and just past `>`.
    start: usize,
    end: usize,
}

impl Tag<'_> {
    fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(n, _)| *n == name.as_bytes())
            .map(|(_, v)| v.as_str())
    }
}

fn find(data: &[u8], from: usize, what: &[u8]) -> Option<usize> {
    data.get(from..)?
        .windows(what.len())
        .position(|w| w == what)
        .map(|k| from + k)
}

/// The next tag at or after `pos`, skipping text, the XML declaration,
/// comments and DOCTYPE-like declarations.
fn next_tag(data: &[u8], mut pos: usize) -> Result<Option<Tag<'_>>, XmlError> {
    loop {
        let Some(start) = find(data, pos, b"<") else {
            return Ok(None);
        };
        let rest = &data[start..];
        let skip_to = |end: &[u8]| {
            find(data, start, end)
                .map(|k| k + end.len())
                .ok_or_else(|| (start, "an unterminated <? or <! construct".to_string()))
        };
        if rest.starts_with(b"<!--") {
            pos = skip_to(b"-->")?;
            continue;
        }
        if rest.starts_with(b"<?") {
            pos = skip_to(b"?>")?;
            continue;
        }
        if rest.starts_with(b"<!") {
            pos = skip_to(b">")?;
            continue;
        }
        let end = find(data, start, b">").ok_or((start, "a tag without its '>'".to_string()))?;
        let mut inner = &data[start + 1..end];
        let closing = inner.first() == Some(&b'/');
        if closing {
            inner = &inner[1..];
        }
        let empty = inner.last() == Some(&b'/');
        if empty {
            inner = &inner[..inner.len() - 1];
        }
        let name_end = inner
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(inner.len());
        let name = &inner[..name_end];
        if name.is_empty() {
            return Err((start, "a tag without a name".into()));
        }
        let attrs = attributes(&inner[name_end..]).map_err(|m| (start, m))?;
        return Ok(Some(Tag {
            name,
            attrs,
            closing,
            empty,
            start,
            end: end + 1,
        }));
    }
}

/// `name="value"` pairs (single or double quotes), entities decoded.
fn attributes(mut s: &[u8]) -> Result<Vec<(&[u8], String)>, String> {
    let mut out = Vec::new();
    loop {
        while s.first().is_some_and(u8::is_ascii_whitespace) {
            s = &s[1..];
        }
        if s.is_empty() {
            return Ok(out);
        }
        let eq = s
            .iter()
            .position(|&b| b == b'=')
            .ok_or_else(|| format!("attribute {} has no value", lossy(s)))?;
        let name = s[..eq].trim_ascii();
        let after = s[eq + 1..].trim_ascii_start();
        let quote = *after
            .first()
            .filter(|&&q| q == b'"' || q == b'\'')
            .ok_or_else(|| format!("attribute {} is not quoted", lossy(name)))?;
        let close = after[1..]
            .iter()
            .position(|&b| b == quote)
            .ok_or_else(|| format!("attribute {} has no closing quote", lossy(name)))?;
        out.push((name, unescape(&after[1..1 + close])));
        s = &after[close + 2..];
    }
}

fn lossy(s: &[u8]) -> String {
    let s = String::from_utf8_lossy(s);
    let short: String = s.chars().take(40).collect();
    format!("{short:?}")
}

fn unescape(s: &[u8]) -> String {
    String::from_utf8_lossy(s)
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

/// A DataArray's values as read, with where it starts.
struct RawArray {
    name: String,
    components: usize,
    values: Vec<f64>,
    at: usize,
}

/// The tags that may hold a DataArray we use.
#[derive(Clone, Copy, PartialEq)]
enum Parent {
    PointData,
    CellData,
    Points,
    Cells,
    Other,
}

fn parse_xml(data: &[u8]) -> Result<VtuMesh, XmlError> {
    let mut stack: Vec<(&[u8], usize)> = Vec::new();
    let mut seen_file = false;
    let mut piece: Option<(usize, usize, usize)> = None; // points, cells, where
    let (mut point_data, mut cell_data) = (Vec::new(), Vec::new());
    let mut points: Option<RawArray> = None;
    let (mut connectivity, mut offsets, mut types) = (None, None, None);
    let mut pos = 0;
    while let Some(tag) = next_tag(data, pos)? {
        pos = tag.end;
        if tag.closing {
            match stack.pop() {
                Some((open, _)) if open == tag.name => continue,
                Some((open, _)) => {
                    return Err((
                        tag.start,
                        format!(
                            "</{}> closes <{}>",
                            lossy(tag.name).trim_matches('"'),
                            lossy(open).trim_matches('"')
                        ),
                    ))
                }
                None => return Err((tag.start, "a closing tag with nothing open".into())),
            }
        }
        match tag.name {
            b"VTKFile" => {
                let ty = tag.attr("type").unwrap_or("");
                if ty != "UnstructuredGrid" {
                    return Err((
                        tag.start,
                        format!("a VTK {ty:?} file; only UnstructuredGrid (.vtu) is read"),
                    ));
                }
                seen_file = true;
            }
            b"Piece" => {
                if piece.is_some() {
                    return Err((
                        tag.start,
                        "a second Piece: only single-piece files are read (merge blocks in ParaView first)"
                            .into(),
                    ));
                }
                let count = |name: &str| -> Result<usize, XmlError> {
                    let v = tag.attr(name).unwrap_or("0");
                    v.trim()
                        .parse()
                        .map_err(|_| (tag.start, format!("Piece {name}={v:?} is not a count")))
                };
                piece = Some((count("NumberOfPoints")?, count("NumberOfCells")?, tag.start));
            }
            b"AppendedData" => {
                return Err((
                    tag.start,
                    "appended (raw or base64) data: only ASCII .vtu files are read; \
                     save as ASCII (ParaView: File > Save Data, Data Mode: Ascii)"
                        .into(),
                ))
            }
            b"DataArray" => {
                let parent = match stack.last().map(|&(n, _)| n) {
                    Some(b"PointData") => Parent::PointData,
                    Some(b"CellData") => Parent::CellData,
                    Some(b"Points") => Parent::Points,
                    Some(b"Cells") => Parent::Cells,
                    _ => Parent::Other,
                };
                let name = tag.attr("Name").unwrap_or("").to_string();
                let format = tag.attr("format").unwrap_or("ascii");
                if format != "ascii" {
                    return Err((
                        tag.start,
                        format!(
                            "DataArray {name:?} is {format}: only ASCII .vtu files are read; \
                             save as ASCII (ParaView: File > Save Data, Data Mode: Ascii)"
                        ),
                    ));
                }
                let components = match tag.attr("NumberOfComponents") {
                    None => 1,
                    Some(c) => c.trim().parse().ok().filter(|&c| c >= 1).ok_or_else(|| {
                        (
                            tag.start,
                            format!("DataArray {name:?}: NumberOfComponents={c:?}"),
                        )
                    })?,
                };
                let integer = tag.attr("type").is_some_and(|t| t.contains("Int"));
                let (values, end) = if tag.empty {
                    (Vec::new(), tag.end)
                } else {
                    array_values(data, tag.end, &name, integer)?
                };
                pos = end;
                let array = RawArray {
                    name,
                    components,
                    values,
                    at: tag.start,
                };
                match parent {
                    Parent::PointData => point_data.push(array),
                    Parent::CellData => cell_data.push(array),
                    Parent::Points => points = Some(array),
                    Parent::Cells => match array.name.as_str() {
                        "connectivity" => connectivity = Some(array),
                        "offsets" => offsets = Some(array),
                        "types" => types = Some(array),
                        _ => {}
                    },
                    Parent::Other => {}
                }
                continue; // its closing tag is consumed
            }
            _ => {}
        }
        if !tag.empty {
            stack.push((tag.name, tag.start));
        }
    }
    if let Some(&(open, at)) = stack.last() {
        return Err((
            at,
            format!("<{}> is never closed", lossy(open).trim_matches('"')),
        ));
    }
    if !seen_file {
        return Err((0, "not a VTK XML file: no <VTKFile> element".into()));
    }
    let Some((npoints, ncells, piece_at)) = piece else {
        return Err((data.len(), "no <Piece> element".into()));
    };
    assemble(
        npoints,
        ncells,
        piece_at,
        points,
        connectivity,
        offsets,
        types,
        point_data,
        cell_data,
    )
}

/// The numbers of a DataArray whose content starts at `from`, up to its
/// `</DataArray>`, skipping the InformationKey elements ParaView puts
/// there. Returns the values and the offset past the closing tag.
fn array_values(
    data: &[u8],
    from: usize,
    name: &str,
    integer: bool,
) -> Result<(Vec<f64>, usize), XmlError> {
    let mut values = Vec::new();
    let mut pos = from;
    loop {
        let lt = find(data, pos, b"<")
            .ok_or_else(|| (from, format!("DataArray {name:?} is never closed")))?;
        let text = &data[pos..lt];
        for token in text
            .split(|b| b.is_ascii_whitespace())
            .filter(|t| !t.is_empty())
        {
            let at = token.as_ptr() as usize - data.as_ptr() as usize;
            let s = std::str::from_utf8(token).ok();
            let x = if integer {
                s.and_then(|s| s.parse::<i64>().ok()).map(|i| i as f64)
            } else {
                s.and_then(|s| s.parse::<f64>().ok())
            };
            let x = x.ok_or_else(|| {
                let what = if integer { "an integer" } else { "a number" };
                (
                    at,
                    format!(
                        "DataArray {name:?}: expected {what}, found {}",
                        lossy(token)
                    ),
                )
            })?;
            values.push(x);
        }
        let tag = next_tag(data, lt)?
            .ok_or_else(|| (lt, format!("DataArray {name:?} is never closed")))?;
        if tag.closing && tag.name == b"DataArray" {
            return Ok((values, tag.end));
        }
        if tag.closing {
            return Err((tag.start, format!("DataArray {name:?} is never closed")));
        }
        pos = tag.end;
        if !tag.empty {
            // Skip the element (an InformationKey and its values).
            let mut close = b"</".to_vec();
            close.extend_from_slice(tag.name);
            let k = find(data, pos, &close).ok_or_else(|| {
                (
                    tag.start,
                    format!(
                        "<{}> inside DataArray {name:?} is never closed",
                        lossy(tag.name)
                    ),
                )
            })?;
            pos = find(data, k, b">").map_or(data.len(), |e| e + 1);
        }
    }
}

/// Checks counts and indices and builds the mesh.
#[allow(clippy::too_many_arguments)]
fn assemble(
    npoints: usize,
    ncells: usize,
    piece_at: usize,
    points: Option<RawArray>,
    connectivity: Option<RawArray>,
    offsets: Option<RawArray>,
    types: Option<RawArray>,
    point_data: Vec<RawArray>,
    cell_data: Vec<RawArray>,
) -> Result<VtuMesh, XmlError> {
    let mut mesh = VtuMesh::default();
    match points {
        Some(p) if p.components == 3 && p.values.len() == 3 * npoints => {
            mesh.points = p.values.chunks_exact(3).map(DVec3::from_slice).collect();
        }
        Some(p) => {
            return Err((
                p.at,
                format!(
                    "Points has {} values in {} components; NumberOfPoints={npoints} needs {} in 3",
                    p.values.len(),
                    p.components,
                    3 * npoints
                ),
            ))
        }
        None if npoints == 0 => {}
        None => {
            return Err((
                piece_at,
                format!("NumberOfPoints={npoints} but no <Points>"),
            ))
        }
    }
    if ncells > 0 {
        let need = |a: Option<RawArray>, what: &str| {
            a.ok_or_else(|| {
                (
                    piece_at,
                    format!("NumberOfCells={ncells} but no {what:?} array in <Cells>"),
                )
            })
        };
        let (conn, offs, tys) = (
            need(connectivity, "connectivity")?,
            need(offsets, "offsets")?,
            need(types, "types")?,
        );
        for a in [&offs, &tys] {
            if a.values.len() != ncells {
                return Err((
                    a.at,
                    format!(
                        "{:?} has {} values for NumberOfCells={ncells}",
                        a.name,
                        a.values.len()
                    ),
                ));
            }
        }
        for (c, &t) in tys.values.iter().enumerate() {
            if !(0.0..=255.0).contains(&t) {
                return Err((tys.at, format!("cell {c} has type {t}")));
            }
            mesh.cell_types.push(t as u8);
        }
        let mut last = 0;
        for (c, &o) in offs.values.iter().enumerate() {
            if !(o >= last as f64 && o <= conn.values.len() as f64) {
                return Err((
                    offs.at,
                    format!(
                        "offset {o} of cell {c} is not between the previous one ({last}) and \
                         the connectivity's length ({})",
                        conn.values.len()
                    ),
                ));
            }
            last = o as usize;
            mesh.offsets.push(last);
        }
        if last != conn.values.len() {
            return Err((
                offs.at,
                format!(
                    "the offsets end at {last}, the connectivity has {} values",
                    conn.values.len()
                ),
            ));
        }
        for (k, &i) in conn.values.iter().enumerate() {
            if !(i >= 0.0 && i < npoints as f64) {
                return Err((
                    conn.at,
                    format!("connectivity entry {k} is point {i}, but there are {npoints} points"),
                ));
            }
            mesh.connectivity.push(i as u32);
        }
    }
    for (arrays, n, kind, out) in [
        (point_data, npoints, "point", &mut mesh.point_data),
        (cell_data, ncells, "cell", &mut mesh.cell_data),
    ] {
        for a in arrays {
            if a.values.len() != a.components * n {
                return Err((
                    a.at,
                    format!(
                        "{kind} array {:?} has {} values; {n} {kind}s of {} components need {}",
                        a.name,
                        a.values.len(),
                        a.components,
                        a.components * n
                    ),
                ));
            }
            out.push(VtuArray {
                name: a.name,
                components: a.components,
                values: a.values,
            });
        }
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Line cells follow the triangles: connectivity, offsets and types
    /// continue, and cell arrays cover both; bad lines and short arrays are
    /// refused.
    #[test]
    fn triangles_then_lines() {
        let dir = std::env::temp_dir().join(format!("loopsurf-vtu-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("lines.vtu");
        let points = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE];
        let tris = [[0, 1, 2], [1, 3, 2]];
        let lines = [[0, 1], [1, 3]];
        let ids = [0, 0, 4, 7];
        write_vtu_with_lines(
            &path,
            &points,
            &tris,
            &lines,
            &[],
            &[("edge", DataArray::I32(&ids))],
        )
        .unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains("NumberOfPoints=\"4\" NumberOfCells=\"4\""));
        let array = |name: &str| -> Vec<String> {
            let body = &text[text.find(&format!("Name=\"{name}\"")).unwrap()..];
            let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
            body.split_whitespace().map(str::to_string).collect()
        };
        assert_eq!(
            array("connectivity"),
            ["0", "1", "2", "1", "3", "2", "0", "1", "1", "3"]
        );
        assert_eq!(array("offsets"), ["3", "6", "8", "10"]);
        assert_eq!(array("types"), ["5", "5", "3", "3"]);
        assert_eq!(array("edge"), ["0", "0", "4", "7"]);
        let err = write_vtu_with_lines(&path, &points, &tris, &[[0, 4]], &[], &[]).unwrap_err();
        assert!(err.to_string().contains("line 0"), "{err}");
        let err = write_vtu_with_lines(
            &path,
            &points,
            &tris,
            &lines,
            &[],
            &[("edge", DataArray::I32(&ids[..2]))],
        )
        .unwrap_err();
        assert!(err.to_string().contains("2 values for 4 cells"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    use crate::io::msh::tests::{assert_identical, documented_lattice, fixture, scratch};

    /// VTK's own numbering of Lagrange triangle points, translated from
    /// `vtkLagrangeTriangle::BarycentricIndex` (VTK 8.2 and later): the
    /// barycentric lattice index (b0, b1, b2) of point `index`, where
    /// (b0, b1) / order are the parametric coordinates (r, s).
    fn vtk_barycentric_index(mut index: usize, mut order: usize) -> [usize; 3] {
        let (mut max, mut min) = (order, 0);
        let mut b = [0; 3];
        while index != 0 && index >= 3 * order {
            index -= 3 * order;
            max -= 2;
            min += 1;
            order -= 3;
        }
        if index < 3 {
            b[index] = min;
            b[(index + 1) % 3] = min;
            b[(index + 2) % 3] = max;
        } else {
            index -= 3;
            let dim = index / (order - 1);
            let offset = index - dim * (order - 1);
            b[(dim + 1) % 3] = min;
            b[(dim + 2) % 3] = (max - 1) - offset;
            b[dim] = (min + 1) + offset;
        }
        b
    }

    /// VTK's Lagrange triangle numbers its points as gmsh does for orders
    /// 1 to 4 (for order 4 too: interior (1,1), (2,1), (1,2) in quarters),
    /// which is why the writer does not permute nodes. (VTK 9.7's
    /// `vtkLagrangeTriangle::GetParametricCoords` gives the same, checked
    /// by hand.)
    #[test]
    fn vtk_lagrange_triangle_order_is_gmsh_s() {
        for k in 1..=4 {
            let vtk: Vec<(usize, usize)> = (0..super::super::nodes_per_triangle(k))
                .map(|m| {
                    let b = vtk_barycentric_index(m, k);
                    (b[0], b[1])
                })
                .collect();
            assert_eq!(vtk, documented_lattice(k), "order {k}");
        }
    }

    /// Lagrange cells of every order, our arrays and the caller's, and back.
    #[test]
    fn lagrange_round_trip() {
        for k in 1..=4 {
            let mesh = fixture(k);
            let path = scratch(&format!("lagrange{k}.vtu"));
            let heights: Vec<f64> = mesh.nodes.iter().map(|p| p.z).collect();
            let ids: Vec<i32> = (0..(mesh.num_triangles() + mesh.num_lines()) as i32).collect();
            write_vtu_lagrange(
                &path,
                &mesh,
                &[("height", DataArray::F64(&heights))],
                &[("id", DataArray::I32(&ids))],
            )
            .unwrap();
            let read = read_vtu(&path).unwrap();
            let (tri, line) = if k == 1 { (5, 3) } else { (69, 68) };
            assert_eq!(read.num_cells(), 12);
            assert_eq!(read.cell(0), (tri, mesh.triangle(0)));
            assert_eq!(read.cell(8), (line, mesh.line(0)));
            let names: Vec<&str> = read.point_data.iter().map(|a| a.name.as_str()).collect();
            assert_eq!(names, ["loopsurf_params", "corner", "height"]);
            assert_eq!(read.point_array("height").unwrap().values, heights);
            let names: Vec<&str> = read.cell_data.iter().map(|a| a.name.as_str()).collect();
            assert_eq!(names, ["face", "curve", "id"]);
            assert_eq!(read.cell_array("face").unwrap().values[8], -1.0);
            let mut want = mesh.clone();
            want.corners.sort();
            assert_identical(&read.to_lagrange().unwrap(), &want);
            std::fs::remove_file(&path).unwrap();
        }
        // Reserved names are refused.
        let mesh = fixture(2);
        let faces = vec![0; 12];
        let err = write_vtu_lagrange(
            &scratch("clash.vtu"),
            &mesh,
            &[],
            &[("face", DataArray::I32(&faces))],
        )
        .unwrap_err();
        assert!(err.to_string().contains("\"face\" is written by"), "{err}");
    }

    /// What [`write_vtu_with_lines`] writes reads back too.
    #[test]
    fn linear_files_read_back() {
        let path = scratch("linear.vtu");
        let points = [DVec3::ZERO, DVec3::X, DVec3::new(0.1, 1.0 / 3.0, -0.0)];
        let curvature = [0.5, -1e-300, 7.0];
        write_vtu_with_lines(
            &path,
            &points,
            &[[0, 1, 2]],
            &[[0, 1]],
            &[("k", DataArray::F64(&curvature))],
            &[],
        )
        .unwrap();
        let read = read_vtu(&path).unwrap();
        assert_eq!(
            read.points[2].to_array().map(f64::to_bits),
            points[2].to_array().map(f64::to_bits)
        );
        assert_eq!(read.point_array("k").unwrap().values, curvature);
        assert_eq!(
            (read.cell(0), read.cell(1)),
            ((5, &[0, 1, 2][..]), (3, &[0, 1][..]))
        );
        let lag = read.to_lagrange().unwrap();
        assert_eq!(
            (lag.order, lag.faces.as_slice(), lag.line_curves.as_slice()),
            (1, &[0][..], &[0][..])
        );
        std::fs::remove_file(&path).unwrap();
    }

    /// An ASCII file the way ParaView 5 saves one: Float32 points, ranges,
    /// InformationKey elements inside arrays, FieldData, a comment, a
    /// vertex cell and a quadratic triangle (VTK_QUADRATIC_TRIANGLE).
    const PARAVIEW: &str = r#"<?xml version="1.0"?>
<!-- saved by hand, shaped like ParaView's output -->
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <UnstructuredGrid>
    <FieldData>
      <DataArray type="Float64" Name="TimeValue" NumberOfTuples="1" format="ascii" RangeMin="0" RangeMax="0">
        0
      </DataArray>
    </FieldData>
    <Piece NumberOfPoints="6"                    NumberOfCells="2"                   >
      <PointData Scalars="temp">
        <DataArray type="Float32" Name="temp" format="ascii" RangeMin="0" RangeMax="5">
          <InformationKey name="L2_NORM_RANGE" location="vtkDataArray" length="2">
            <Value index="0">
              0
            </Value>
            <Value index="1">
              5
            </Value>
          </InformationKey>
          0 1 2 3
          4 5
        </DataArray>
      </PointData>
      <CellData>
        <DataArray type="Int32" Name="face" format="ascii" RangeMin="2" RangeMax="2">
          2 -1
        </DataArray>
      </CellData>
      <Points>
        <DataArray type="Float32" Name="Points" NumberOfComponents="3" format="ascii" RangeMin="0" RangeMax="1">
          0 0 0 1 0 0 0 1 0
          0.5 0 0 0.5 0.5 0 0 0.5 0.25
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii" RangeMin="0" RangeMax="5">
          0 1 2 3 4 5 1
        </DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii" RangeMin="6" RangeMax="7">
          6 7
        </DataArray>
        <DataArray type="UInt8" Name="types" format="ascii" RangeMin="1" RangeMax="22">
          22 1
        </DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
"#;

    #[test]
    fn reads_paraview_ascii() {
        let read = parse_vtu(PARAVIEW.as_bytes(), Path::new("pv.vtu")).unwrap();
        assert_eq!(read.points[5], DVec3::new(0.0, 0.5, 0.25));
        assert_eq!(
            read.point_array("temp").unwrap().values,
            [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]
        );
        assert_eq!(read.cell(1), (1, &[1][..]));
        let lag = read.to_lagrange().unwrap();
        assert_eq!(
            (lag.order, lag.triangles.len(), lag.faces.as_slice()),
            (2, 6, &[2][..])
        );
        assert!(lag.lines.is_empty() && lag.corners.is_empty() && lag.params.is_empty());
    }

    /// The 1-based line of the first occurrence of `needle`.
    fn line_of(text: &str, needle: &str) -> usize {
        1 + text[..text.find(needle).unwrap()].matches('\n').count()
    }

    fn vtu_err(text: &str) -> String {
        parse_vtu(text.as_bytes(), Path::new("bad.vtu"))
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn errors_name_the_line() {
        let binary = PARAVIEW.replace(
            r#"Name="temp" format="ascii""#,
            r#"Name="temp" format="binary""#,
        );
        let msg = vtu_err(&binary);
        let line = line_of(&binary, "Name=\"temp\"");
        assert!(
            msg.contains(&format!("bad.vtu:{line}:")) && msg.contains("save as ASCII"),
            "{msg}"
        );
        let appended = PARAVIEW.replace(
            "  </UnstructuredGrid>",
            "  </UnstructuredGrid>\n<AppendedData encoding=\"raw\">_abc</AppendedData>",
        );
        assert!(vtu_err(&appended).contains("save as ASCII"));
        let index = PARAVIEW.replace("0 1 2 3 4 5 1\n", "0 1 2 3 4 5 6\n");
        let msg = vtu_err(&index);
        // Cell checks name the array's line.
        let line = line_of(&index, "Name=\"connectivity\"");
        assert!(
            msg.contains(&format!("bad.vtu:{line}:")) && msg.contains("entry 6 is point 6"),
            "{msg}"
        );
        let short = PARAVIEW.replace("          4 5\n", "");
        assert!(vtu_err(&short).contains("\"temp\" has 4 values"));
        let word = PARAVIEW.replace("6 7\n", "6 seven\n");
        let msg = vtu_err(&word);
        let line = line_of(&word, "6 seven");
        assert!(
            msg.contains(&format!("bad.vtu:{line}:")) && msg.contains("found \"seven\""),
            "{msg}"
        );
        let image = PARAVIEW.replace("type=\"UnstructuredGrid\"", "type=\"ImageData\"");
        assert!(vtu_err(&image).contains("only UnstructuredGrid"));
        assert!(vtu_err("").contains("no <VTKFile>"));
        // Every prefix short of the closing tag fails cleanly.
        for cut in 0..PARAVIEW.trim_end().len() {
            assert!(parse_vtu(&PARAVIEW.as_bytes()[..cut], Path::new("cut.vtu")).is_err());
        }
        let mut state = 0x2545f4914f6cdd1du64;
        for _ in 0..500 {
            let mut data = PARAVIEW.as_bytes().to_vec();
            for _ in 0..3 {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let at = (state % data.len() as u64) as usize;
                data[at] = (state >> 40) as u8;
            }
            if let Ok(m) = parse_vtu(&data, Path::new("damaged.vtu")) {
                let _ = m.to_lagrange();
            }
        }
    }
}
