//! Stanford PLY through ply-rs (ASCII, binary little and big endian).
//!
//! ply-rs parses the header and decodes one element at a time; we drive the
//! element loop ourselves so that ASCII elements keep their line numbers,
//! a short file is reported as truncated, and only vertex coordinates and
//! face lists are kept in memory. Before ply-rs sees the header we check
//! what its grammar would panic on (counts that overflow u64) and what would
//! make its element loop run away (elements without properties), and we
//! reject duplicate names, which it would silently merge.

use std::collections::HashSet;
use std::path::Path;

use glam::DVec3;
use ply_rs::parser::Parser;
use ply_rs::ply::{
    ElementDef, Encoding, Header, Property, PropertyAccess, PropertyType, ScalarType,
};

use super::{capacity, push_face, read_bytes, MeshData, ParseOptions};
use crate::error::{Error, Result};

/// Reads a PLY file: element `vertex` (x, y, z of any numeric type) and
/// element `face` (list `vertex_indices` or `vertex_index` of any integer
/// type). Other elements and properties are skipped.
pub fn read_ply(path: &Path, opts: &ParseOptions) -> Result<MeshData> {
    parse_ply(&read_bytes(path)?, opts, path)
}

/// The two properties we keep from any element; ply-rs hands us each
/// property by name and we drop the rest on the floor.
#[derive(Default)]
struct Elem {
    xyz: [f64; 3],
    vertex_indices: Vec<i64>,
    vertex_index: Vec<i64>,
}

impl PropertyAccess for Elem {
    fn new() -> Self {
        Elem::default()
    }

    fn set_property(&mut self, name: String, property: Property) {
        match name.as_str() {
            "x" => self.xyz[0] = scalar(&property),
            "y" => self.xyz[1] = scalar(&property),
            "z" => self.xyz[2] = scalar(&property),
            "vertex_indices" => self.vertex_indices = list(property),
            "vertex_index" => self.vertex_index = list(property),
            _ => {}
        }
    }
}

/// Any numeric scalar as f64 (exact for every PLY type). The header check
/// guarantees x, y, z are scalars.
fn scalar(p: &Property) -> f64 {
    match *p {
        Property::Char(v) => v.into(),
        Property::UChar(v) => v.into(),
        Property::Short(v) => v.into(),
        Property::UShort(v) => v.into(),
        Property::Int(v) => v.into(),
        Property::UInt(v) => v.into(),
        Property::Float(v) => v.into(),
        Property::Double(v) => v,
        _ => f64::NAN,
    }
}

/// Any integer list as i64. The header check guarantees an integer list.
fn list(p: Property) -> Vec<i64> {
    fn wide<T: Into<i64>>(v: Vec<T>) -> Vec<i64> {
        v.into_iter().map(Into::into).collect()
    }
    match p {
        Property::ListChar(v) => wide(v),
        Property::ListUChar(v) => wide(v),
        Property::ListShort(v) => wide(v),
        Property::ListUShort(v) => wide(v),
        Property::ListInt(v) => wide(v),
        Property::ListUInt(v) => wide(v),
        _ => Vec::new(),
    }
}

/// Receives each decoded element: its definition, its index among the
/// elements of that name, the element, and its line (ASCII only).
type Sink<'a> = dyn FnMut(&ElementDef, usize, Elem, Option<usize>) -> Result<()> + 'a;

/// What our own pass over the header learned.
struct HeaderScan {
    /// Byte offset just past the `end_header` line.
    end: usize,
    /// Number of header lines, `end_header` included.
    lines: usize,
    /// The line declaring each element, in header order.
    element_lines: Vec<(String, usize)>,
}

pub(crate) fn parse_ply(data: &[u8], opts: &ParseOptions, path: &Path) -> Result<MeshData> {
    let located = |e: Error| e.in_file(path, None);
    let scan = scan_header(data).map_err(located)?;
    let parser = Parser::<Elem>::new();
    let header = parser
        .read_header(&mut &data[..scan.end])
        .map_err(|e| header_error(&parser, data, &scan, e))
        .map_err(located)?;
    let element_line = |name: &str| {
        scan.element_lines
            .iter()
            .find(|(n, _)| n == name)
            .map_or(1, |&(_, l)| l)
    };
    let face_list = check_elements(&header, &element_line).map_err(located)?;

    let mut mesh = MeshData::default();
    let payload = &data[scan.end..];
    let nv = header.elements.get("vertex").map_or(0, |e| e.count);
    let nf = header.elements.get("face").map_or(0, |e| e.count);
    mesh.points.reserve(capacity(nv, payload.len(), 3));
    mesh.tris.reserve(capacity(nf, payload.len(), 4));
    let mut sink = |def: &ElementDef, j: usize, elem: Elem, line: Option<usize>| {
        match def.name.as_str() {
            "vertex" => {
                mesh.points.push(DVec3::from_array(elem.xyz));
                mesh.vertex_lines.extend(line);
                Ok(())
            }
            "face" => {
                let corners = match face_list {
                    "vertex_indices" => elem.vertex_indices,
                    _ => elem.vertex_index,
                };
                if corners.len() < 3 {
                    // Binary files have no line to name; the face index does.
                    let err = match line {
                        Some(line) => Error::Malformed {
                            line,
                            message: format!(
                                "face {j} has {} vertices; at least 3 are needed",
                                corners.len()
                            ),
                        },
                        None => Error::Polygon {
                            face: j,
                            corners: corners.len(),
                        },
                    };
                    return Err(err.in_file(path, line));
                }
                push_face(&mut mesh, j, &corners, line, opts, path)
            }
            _ => Ok(()),
        }
    };
    match header.encoding {
        Encoding::Ascii => read_ascii(&parser, &header, payload, scan.lines, &mut sink),
        Encoding::BinaryLittleEndian | Encoding::BinaryBigEndian => {
            read_binary(&parser, &header, payload, &mut sink)
        }
    }
    .map_err(located)?;
    Ok(mesh)
}

/// Walks the header lines before ply-rs does (see the module comment).
fn scan_header(data: &[u8]) -> Result<HeaderScan> {
    let mut offset = 0;
    let mut element_lines: Vec<(String, usize)> = Vec::new();
    let mut properties = HashSet::new();
    for (i, raw) in data.split(|&b| b == b'\n').enumerate() {
        let line = i + 1;
        offset += raw.len() + 1;
        let malformed = |message: String| Error::Malformed { line, message };
        let text = std::str::from_utf8(raw)
            .map_err(|_| malformed("PLY header line is not text".into()))?
            .trim_end_matches('\r');
        if line == 1 && text.trim_end() != "ply" {
            return Err(malformed(
                "not a PLY file: the first line must be \"ply\"".into(),
            ));
        }
        if text.starts_with("element") || text.starts_with("format") {
            for run in text.split(|c: char| !c.is_ascii_digit()) {
                if !run.is_empty() && run.parse::<u64>().is_err() {
                    return Err(malformed(format!("number {run} is too large")));
                }
            }
        }
        let tokens: Vec<&str> = text.split_whitespace().collect();
        match tokens.as_slice() {
            ["end_header"] => {
                return Ok(HeaderScan {
                    end: offset.min(data.len()),
                    lines: line,
                    element_lines,
                })
            }
            ["element", name, ..] => {
                if element_lines.iter().any(|(n, _)| n == name) {
                    return Err(malformed(format!("element {name:?} is declared twice")));
                }
                element_lines.push((name.to_string(), line));
                properties.clear();
            }
            ["property", .., name] => {
                if !properties.insert(name.to_string()) {
                    return Err(malformed(format!("property {name:?} is declared twice")));
                }
                if let ["property", "list", count_type, ..] = tokens.as_slice() {
                    if matches!(*count_type, "float" | "double" | "float32" | "float64") {
                        return Err(malformed(format!(
                            "list length type {count_type:?} is not an integer type"
                        )));
                    }
                }
            }
            _ => {}
        }
    }
    Err(Error::Truncated {
        message: "PLY header has no end_header line".into(),
    })
}

/// Locates a header line ply-rs refused, by asking it about each line.
fn header_error(parser: &Parser<Elem>, data: &[u8], scan: &HeaderScan, e: std::io::Error) -> Error {
    let header = String::from_utf8_lossy(&data[..scan.end]);
    let bad = header
        .split('\n')
        .enumerate()
        .find(|(_, l)| parser.read_header_line(l).is_err());
    match bad {
        Some((i, text)) => Error::Malformed {
            line: i + 1,
            message: format!("cannot parse PLY header line {:?}", text.trim_end()),
        },
        None => Error::Malformed {
            line: scan.lines,
            message: one_line(&e.to_string()),
        },
    }
}

/// Checks that the elements we read have the properties we need, and
/// returns the name of the face list property.
fn check_elements(header: &Header, element_line: &dyn Fn(&str) -> usize) -> Result<&'static str> {
    for def in header.elements.values() {
        if def.count > 0 && def.properties.is_empty() {
            return Err(Error::Malformed {
                line: element_line(&def.name),
                message: format!("element {:?} has no properties", def.name),
            });
        }
    }
    if let Some(def) = header.elements.get("vertex") {
        for c in ["x", "y", "z"] {
            if !matches!(
                def.properties.get(c).map(|p| &p.data_type),
                Some(PropertyType::Scalar(_))
            ) {
                return Err(Error::Malformed {
                    line: element_line("vertex"),
                    message: format!("element \"vertex\" needs a scalar property {c:?}"),
                });
            }
        }
    }
    let Some(def) = header.elements.get("face") else {
        return Ok("vertex_indices");
    };
    for name in ["vertex_indices", "vertex_index"] {
        match def.properties.get(name).map(|p| &p.data_type) {
            Some(PropertyType::List(_, item)) if is_integer(item) => return Ok(name),
            Some(_) => {
                return Err(Error::Malformed {
                    line: element_line("face"),
                    message: format!("face property {name:?} must be a list of integers"),
                })
            }
            None => {}
        }
    }
    Err(Error::Malformed {
        line: element_line("face"),
        message: "element \"face\" has no list property \"vertex_indices\" or \"vertex_index\""
            .into(),
    })
}

fn is_integer(t: &ScalarType) -> bool {
    !matches!(t, ScalarType::Float | ScalarType::Double)
}

/// One element per line, as ply-rs's ASCII decoder expects; blank lines are
/// skipped. `first_line` is the number of the last header line.
fn read_ascii(
    parser: &Parser<Elem>,
    header: &Header,
    payload: &[u8],
    header_lines: usize,
    sink: &mut Sink,
) -> Result<()> {
    let mut lines = super::text::lines(payload)
        .map(|(i, text)| (i + header_lines, text))
        .filter(|(_, text)| !text.trim().is_empty());
    for def in header.elements.values() {
        for j in 0..def.count {
            let Some((line, text)) = lines.next() else {
                return Err(Error::Truncated {
                    message: format!(
                        "the file ends at element {:?} {j}; the header announces {}",
                        def.name, def.count
                    ),
                });
            };
            let elem = parser
                .read_ascii_element(&text, def)
                .map_err(|e| Error::Malformed {
                    line,
                    message: format!("element {:?} {j}: {}", def.name, one_line(&e.to_string())),
                })?;
            sink(def, j, elem, Some(line))?;
        }
    }
    Ok(())
}

/// Binary elements back to back. ply-rs only fails here when the data ends
/// (the header check rules out everything else), so any failure is reported
/// as truncation at the element it happened in.
fn read_binary(
    parser: &Parser<Elem>,
    header: &Header,
    mut payload: &[u8],
    sink: &mut Sink,
) -> Result<()> {
    let big = header.encoding == Encoding::BinaryBigEndian;
    for def in header.elements.values() {
        for j in 0..def.count {
            let elem = if big {
                parser.read_big_endian_element(&mut payload, def)
            } else {
                parser.read_little_endian_element(&mut payload, def)
            }
            .map_err(|_| Error::Truncated {
                message: format!(
                    "binary data ends inside element {:?} {j}; the header announces {}",
                    def.name, def.count
                ),
            })?;
            sink(def, j, elem, None)?;
        }
    }
    Ok(())
}

/// ply-rs messages span several indented lines; ours are one line.
fn one_line(message: &str) -> String {
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Writes an ASCII PLY file with double coordinates (round-tripping digits).
pub fn write_ply(path: &Path, points: &[DVec3], tris: &[[u32; 3]]) -> Result<()> {
    use std::io::Write;
    super::check_tris(points, tris)?;
    let mut w = super::create(path)?;
    let io = super::io_error(path);
    // `int` indices are what every PLY reader knows; `uint` only when needed.
    let index_type = if points.len() <= i32::MAX as usize {
        "int"
    } else {
        "uint"
    };
    write!(
        w,
        "ply\nformat ascii 1.0\ncomment written by loopsurf\n\
         element vertex {}\nproperty double x\nproperty double y\nproperty double z\n\
         element face {}\nproperty list uchar {index_type} vertex_indices\nend_header\n",
        points.len(),
        tris.len()
    )
    .map_err(&io)?;
    super::write_vertex_and_face_lines(&mut w, points, tris).map_err(&io)?;
    super::finish(w, path)
}
