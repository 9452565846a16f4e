//! STL (ASCII and binary) through stl_io, with our own welding.
//!
//! STL stores every triangle with its own three corners, so shared vertices
//! must be recovered by welding exactly-equal coordinates: the one place
//! loopsurf does not keep file order verbatim. Vertices are numbered by
//! first appearance (triangle by triangle, corner by corner), which is also
//! what stl_io's `as_indexed_triangles` does; we weld ourselves only so that
//! `-0.0` and `0.0` count as the same coordinate.
//!
//! stl_io picks ASCII when the file starts with `"solid "`, which misreads
//! the many binary files whose 80-byte header starts with "solid", and
//! rejects ASCII files whose first line is a bare `solid`. We decide the
//! encoding ourselves (a binary file's size is exactly 84 + 50 n) and hand
//! stl_io data it will classify the same way. ASCII files holding several
//! `solid … endsolid` blocks are read block by block; stl_io would stop after
//! the first. stl_io parses ASCII coordinates as f32, like binary ones.

use std::collections::HashMap;
use std::io::Cursor;
use std::path::Path;

use glam::DVec3;
use stl_io::{Normal, Triangle, Vertex};

use super::{read_bytes, MeshData};
use crate::error::{Error, Result};
use crate::geometry::unit_normal;

/// Reads an STL file and welds identical corners; [`MeshData::welded`]
/// reports how many corners were merged away.
pub fn read_stl(path: &Path) -> Result<MeshData> {
    parse_stl(read_bytes(path)?, path)
}

/// [`read_stl`] of bytes already read; `path` names them in errors.
pub(crate) fn parse_stl(mut data: Vec<u8>, path: &Path) -> Result<MeshData> {
    let mut welder = Welder::default();
    if is_binary(&data) {
        read_binary(&mut data, &mut welder)
    } else {
        read_ascii(&data, &mut welder)
    }
    .map_err(|e| e.in_file(path, None))?;
    let mut mesh = welder.mesh;
    mesh.welded = 3 * mesh.tris.len() - mesh.points.len();
    Ok(mesh)
}

/// Merges corners with equal coordinates, numbering them by first appearance.
#[derive(Default)]
struct Welder {
    mesh: MeshData,
    index: HashMap<[u32; 3], i64>,
}

impl Welder {
    fn add(&mut self, t: &Triangle) {
        let mut tri = [0; 3];
        for (slot, v) in tri.iter_mut().zip(&t.vertices) {
            // Adding +0.0 turns -0.0 into +0.0 and leaves every other value alone.
            let key = v.0.map(|c| (c + 0.0).to_bits());
            let points = &mut self.mesh.points;
            *slot = *self.index.entry(key).or_insert_with(|| {
                points.push(DVec3::new(v[0].into(), v[1].into(), v[2].into()));
                points.len() as i64 - 1
            });
        }
        self.mesh.tris.push(tri);
    }
}

/// Binary when the size matches the triangle count in the header exactly,
/// or when the file does not look like text starting with `solid`.
fn is_binary(data: &[u8]) -> bool {
    if let Some(count) = data.get(80..84) {
        let n = u32::from_le_bytes([count[0], count[1], count[2], count[3]]);
        if 84 + 50 * u64::from(n) == data.len() as u64 {
            return true;
        }
    }
    let text = data.trim_ascii_start();
    let solid = text.starts_with(b"solid") && text.get(5).map_or(true, u8::is_ascii_whitespace);
    // Binary counts below 2^24 put a NUL at byte 83; ASCII STL has no
    // control characters besides line ends and tabs.
    let printable = data
        .iter()
        .take(1024)
        .all(|&b| b >= 32 && b != 127 || matches!(b, b'\t' | b'\n' | b'\r'));
    !(solid && printable)
}

fn read_binary(data: &mut [u8], welder: &mut Welder) -> Result<()> {
    let Some(count) = data.get(80..84) else {
        return Err(Error::Truncated {
            message: format!(
                "a binary STL needs an 84-byte header; the file has {} bytes",
                data.len()
            ),
        });
    };
    let n = u32::from_le_bytes([count[0], count[1], count[2], count[3]]);
    let need = 84 + 50 * u64::from(n);
    if (data.len() as u64) < need {
        return Err(Error::Truncated {
            message: format!(
                "the binary STL header announces {n} triangles ({need} bytes), \
                 but the file has {} bytes",
                data.len()
            ),
        });
    }
    // The header text is meaningless; blanking it keeps stl_io from
    // mistaking a header that starts with "solid" for ASCII.
    data[0] = 0;
    let mut cursor = Cursor::new(&data[..need as usize]);
    let triangles = stl_io::create_stl_reader(&mut cursor).map_err(|e| Error::Truncated {
        message: format!("binary STL: {e}"),
    })?;
    for (k, t) in triangles.enumerate() {
        let t = t.map_err(|e| Error::Truncated {
            message: format!("binary STL triangle {k}: {e}"),
        })?;
        welder.add(&t);
    }
    Ok(())
}

fn read_ascii(data: &[u8], welder: &mut Welder) -> Result<()> {
    // Each block runs from a line whose first word is `solid` to the next.
    let mut starts = Vec::new();
    let mut offset = 0;
    for (i, line) in data.split(|&b| b == b'\n').enumerate() {
        let lead = line.len() - line.trim_ascii_start().len();
        let word = line[lead..].split(u8::is_ascii_whitespace).next();
        if word == Some(b"solid".as_slice()) {
            starts.push((offset + lead, i + 1));
        }
        offset += line.len() + 1;
    }
    for (b, &(start, first_line)) in starts.iter().enumerate() {
        let end = starts.get(b + 1).map_or(data.len(), |&(s, _)| s);
        let mut block = data[start..end].to_vec();
        // stl_io wants "solid " with a space even when the solid is unnamed.
        match block.get(5) {
            Some(b'\t') => block[5] = b' ',
            Some(b' ') => {}
            _ => block.insert(5, b' '),
        }
        let mut cursor = Cursor::new(block);
        let triangles = stl_io::create_stl_reader(&mut cursor).map_err(|e| Error::Malformed {
            line: first_line,
            message: e.to_string(),
        })?;
        for (k, t) in triangles.enumerate() {
            match t {
                Ok(t) => welder.add(&t),
                Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
                    return Err(Error::Truncated {
                        message: format!(
                            "the solid on line {first_line} ends inside triangle {}: {e}",
                            welder.mesh.tris.len()
                        ),
                    })
                }
                Err(e) => {
                    return Err(Error::Malformed {
                        line: facet_line(&data[start..end], first_line, k),
                        message: format!("triangle {}: {e}", welder.mesh.tris.len()),
                    })
                }
            }
        }
    }
    Ok(())
}

/// The line where facet `k` of a block starts: the first non-blank line
/// after the k-th `endfacet` (or after `solid` for k = 0). stl_io does not
/// report lines, but it fails inside the facet after the last good one.
fn facet_line(block: &[u8], first_line: usize, k: usize) -> usize {
    let mut ends = 0;
    let mut last = first_line;
    for (i, line) in block.split(|&b| b == b'\n').enumerate() {
        let line_no = first_line + i;
        let word = line.split(u8::is_ascii_whitespace).find(|w| !w.is_empty());
        let Some(word) = word else { continue };
        last = line_no;
        if i > 0 && ends == k {
            return line_no;
        }
        if word == b"endfacet" {
            ends += 1;
        }
    }
    last
}

/// Writes a binary STL (single precision, as the format demands) with
/// facet normals from the corner positions.
pub fn write_stl(path: &Path, points: &[DVec3], tris: &[[u32; 3]]) -> Result<()> {
    super::check_tris(points, tris)?;
    if u32::try_from(tris.len()).is_err() {
        return Err(Error::InvalidArgument(format!(
            "binary STL holds at most {} triangles, not {}",
            u32::MAX,
            tris.len()
        )));
    }
    let vertex = |i: u32| Vertex::new(points[i as usize].as_vec3().to_array());
    let triangles = tris.iter().map(|t| Triangle {
        normal: Normal::new(
            unit_normal(t.map(|i| points[i as usize]))
                .as_vec3()
                .to_array(),
        ),
        vertices: t.map(vertex),
    });
    let mut w = super::create(path)?;
    stl_io::write_stl(&mut w, triangles).map_err(super::io_error(path))?;
    super::finish(w, path)
}
