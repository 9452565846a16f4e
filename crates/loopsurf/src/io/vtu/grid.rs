//! The UnstructuredGrid in a `.vtu` file's tags: its piece, points, cells
//! and data arrays, read from the tags `xml` finds and checked against
//! each other.

use glam::DVec3;

use super::binary;
use super::xml::{find, lossy, next_tag, Tag, XmlError};
use super::{VtuArray, VtuMesh};

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

/// What the tags held, before the counts are checked against each other.
#[derive(Default)]
struct Found {
    seen_file: bool,
    /// The size in bytes of a binary array's byte count (`header_type`).
    header: Option<usize>,
    /// NumberOfPoints, NumberOfCells and where the Piece starts.
    piece: Option<(usize, usize, usize)>,
    point_data: Vec<RawArray>,
    cell_data: Vec<RawArray>,
    points: Option<RawArray>,
    connectivity: Option<RawArray>,
    offsets: Option<RawArray>,
    types: Option<RawArray>,
}

/// The mesh in a `.vtu` file's bytes: the tags walked with a stack of
/// open ones, the arrays we use kept by their parent, then checked and
/// built by [`assemble`].
pub(super) fn parse_xml(data: &[u8]) -> Result<VtuMesh, XmlError> {
    let mut stack: Vec<(&[u8], usize)> = Vec::new();
    let mut found = Found::default();
    let mut pos = 0;
    while let Some(tag) = next_tag(data, pos)? {
        pos = tag.end;
        if tag.closing {
            close(&mut stack, &tag)?;
            continue;
        }
        match tag.name {
            b"VTKFile" => found.file(&tag)?,
            b"Piece" => found.piece(&tag)?,
            b"AppendedData" => {
                return Err((
                    tag.start,
                    "<AppendedData>: appended data is not read, only ASCII and inline \
                     binary (base64) arrays; save with ParaView's Data Mode Ascii or Binary"
                        .into(),
                ))
            }
            b"DataArray" => {
                let (array, end) = data_array(data, &tag, found.header.unwrap_or(4))?;
                pos = end;
                found.keep(parent_of(&stack), array);
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
    if !found.seen_file {
        return Err((0, "not a VTK XML file: no <VTKFile> element".into()));
    }
    assemble(found, data.len())
}

/// Pops the element a closing tag closes; an error if it closes another
/// one, or none is open.
fn close(stack: &mut Vec<(&[u8], usize)>, tag: &Tag) -> Result<(), XmlError> {
    match stack.pop() {
        Some((open, _)) if open == tag.name => Ok(()),
        Some((open, _)) => Err((
            tag.start,
            format!(
                "</{}> closes <{}>",
                lossy(tag.name).trim_matches('"'),
                lossy(open).trim_matches('"')
            ),
        )),
        None => Err((tag.start, "a closing tag with nothing open".into())),
    }
}

/// The tag a DataArray sits in, among those we read.
fn parent_of(stack: &[(&[u8], usize)]) -> Parent {
    match stack.last().map(|&(n, _)| n) {
        Some(b"PointData") => Parent::PointData,
        Some(b"CellData") => Parent::CellData,
        Some(b"Points") => Parent::Points,
        Some(b"Cells") => Parent::Cells,
        _ => Parent::Other,
    }
}

/// The DataArray that `tag` opens, read to its closing tag: the array and
/// the offset past it. `header` is the size of a binary array's byte count.
fn data_array(data: &[u8], tag: &Tag, header: usize) -> Result<(RawArray, usize), XmlError> {
    let name = tag.attr("Name").unwrap_or("").to_string();
    let format = tag.attr("format").unwrap_or("ascii");
    if format != "ascii" && format != "binary" {
        return Err((
            tag.start,
            format!(
                "DataArray {name:?} is {format}: only ASCII and inline binary (base64) \
                 arrays are read; save with ParaView's Data Mode Ascii or Binary"
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
    let ty = tag.attr("type").unwrap_or("");
    let (text, end) = if tag.empty {
        (Vec::new(), tag.end)
    } else {
        array_text(data, tag.end, &name)?
    };
    let values = if format == "binary" {
        let joined: Vec<u8> = text
            .iter()
            .flat_map(|&(a, b)| &data[a..b])
            .copied()
            .collect();
        binary::decode(&joined, header)
            .and_then(|bytes| binary::values(&bytes, ty))
            .map_err(|m| (tag.start, format!("binary DataArray {name:?}: {m}")))?
    } else {
        ascii_values(data, &text, &name, ty.contains("Int"))?
    };
    let array = RawArray {
        name,
        components,
        values,
        at: tag.start,
    };
    Ok((array, end))
}

impl Found {
    /// The VTKFile element: an UnstructuredGrid, uncompressed, little
    /// endian, and the size of binary arrays' byte counts.
    fn file(&mut self, tag: &Tag) -> Result<(), XmlError> {
        let ty = tag.attr("type").unwrap_or("");
        if ty != "UnstructuredGrid" {
            return Err((
                tag.start,
                format!("a VTK {ty:?} file; only UnstructuredGrid (.vtu) is read"),
            ));
        }
        if let Some(c) = tag.attr("compressor") {
            return Err((
                tag.start,
                format!(
                    "<VTKFile compressor={c:?}>: compressed data is not read; \
                     save uncompressed (ParaView: Compressor Type None)"
                ),
            ));
        }
        let order = tag.attr("byte_order").unwrap_or("LittleEndian");
        if order != "LittleEndian" {
            return Err((
                tag.start,
                format!("<VTKFile byte_order={order:?}>: only LittleEndian is read"),
            ));
        }
        self.header = Some(match tag.attr("header_type").unwrap_or("UInt32") {
            "UInt32" => 4,
            "UInt64" => 8,
            h => {
                return Err((
                    tag.start,
                    format!("<VTKFile header_type={h:?}>: UInt32 or UInt64 expected"),
                ))
            }
        });
        self.seen_file = true;
        Ok(())
    }

    /// The Piece's counts; a second Piece is refused.
    fn piece(&mut self, tag: &Tag) -> Result<(), XmlError> {
        if self.piece.is_some() {
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
        self.piece = Some((count("NumberOfPoints")?, count("NumberOfCells")?, tag.start));
        Ok(())
    }

    /// Keeps an array read inside `parent`, if it is one we use.
    fn keep(&mut self, parent: Parent, array: RawArray) {
        match parent {
            Parent::PointData => self.point_data.push(array),
            Parent::CellData => self.cell_data.push(array),
            Parent::Points => self.points = Some(array),
            Parent::Cells => match array.name.as_str() {
                "connectivity" => self.connectivity = Some(array),
                "offsets" => self.offsets = Some(array),
                "types" => self.types = Some(array),
                _ => {}
            },
            Parent::Other => {}
        }
    }
}

/// The text of a DataArray whose content starts at `from`, up to its
/// `</DataArray>`, as byte ranges, skipping the InformationKey elements
/// ParaView puts there. Returns the ranges and the offset past the
/// closing tag.
fn array_text(
    data: &[u8],
    from: usize,
    name: &str,
) -> Result<(Vec<(usize, usize)>, usize), XmlError> {
    let mut text = Vec::new();
    let mut pos = from;
    loop {
        let lt = find(data, pos, b"<")
            .ok_or_else(|| (from, format!("DataArray {name:?} is never closed")))?;
        text.push((pos, lt));
        let tag = next_tag(data, lt)?
            .ok_or_else(|| (lt, format!("DataArray {name:?} is never closed")))?;
        if tag.closing && tag.name == b"DataArray" {
            return Ok((text, tag.end));
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

/// The whitespace-separated numbers in the `text` ranges of `data`.
fn ascii_values(
    data: &[u8],
    text: &[(usize, usize)],
    name: &str,
    integer: bool,
) -> Result<Vec<f64>, XmlError> {
    let mut values = Vec::new();
    for &(a, b) in text {
        for token in data[a..b]
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
    }
    Ok(values)
}

/// Checks counts and indices and builds the mesh; `len` is the file's
/// length (where a missing Piece is reported).
fn assemble(found: Found, len: usize) -> Result<VtuMesh, XmlError> {
    let Some((npoints, ncells, piece_at)) = found.piece else {
        return Err((len, "no <Piece> element".into()));
    };
    let mut mesh = VtuMesh::default();
    match found.points {
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
            need(found.connectivity, "connectivity")?,
            need(found.offsets, "offsets")?,
            need(found.types, "types")?,
        );
        cells(&mut mesh, npoints, ncells, conn, offs, tys)?;
    }
    for (arrays, n, kind, out) in [
        (found.point_data, npoints, "point", &mut mesh.point_data),
        (found.cell_data, ncells, "cell", &mut mesh.cell_data),
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

/// The cells' types, offsets and connectivity into `mesh`, each checked:
/// one type and offset per cell, offsets rising to the connectivity's
/// end, every entry a point.
fn cells(
    mesh: &mut VtuMesh,
    npoints: usize,
    ncells: usize,
    conn: RawArray,
    offs: RawArray,
    tys: RawArray,
) -> Result<(), XmlError> {
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
    Ok(())
}
