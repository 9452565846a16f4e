//! Cart3D `.tri` surface triangulations, ASCII and Fortran-unformatted
//! binary (either endianness, single or double precision).
//!
//! ASCII: a line `nVerts nTris [nScalars]`, then 3·nVerts coordinates,
//! 3·nTris 1-based vertex indices and optionally nTris integer component
//! IDs. Cart3D reads these list-directed, so records may wrap across lines:
//! we read a token stream and give each vertex and triangle the line of its
//! first number. Anything after the component IDs (per-vertex scalars of
//! `.triq` files) is ignored.
//!
//! Binary: sequential Fortran records, each framed by a 4-byte length
//! before and after: (nVerts, nTris [, nScalars]), the coordinates, the
//! indices, optionally the component IDs. The first marker is 8 or 12,
//! which tells the endianness; the coordinate record's length (12 or 24
//! bytes per vertex) tells the precision. Lengths are checked against the
//! counts and the file size before anything is allocated.

use std::path::Path;

use glam::DVec3;

use super::text::{parse, Tokens};
use super::{capacity, read_bytes, MeshData};
use crate::error::{Error, Result};

/// Reads a Cart3D `.tri` file (ASCII or binary, detected from its first
/// four bytes). Indices become 0-based; component IDs go to
/// [`MeshData::components`].
pub fn read_tri(path: &Path) -> Result<MeshData> {
    parse_tri(&read_bytes(path)?, path)
}

/// [`read_tri`] of bytes already read; `path` names them in errors.
pub(crate) fn parse_tri(data: &[u8], path: &Path) -> Result<MeshData> {
    let head = data.get(..4).map(|b| [b[0], b[1], b[2], b[3]]);
    match head {
        Some(b) if matches!(i32::from_le_bytes(b), 8 | 12) => read_binary(data, false),
        Some(b) if matches!(i32::from_be_bytes(b), 8 | 12) => read_binary(data, true),
        _ => read_ascii(data),
    }
    .map_err(|e| e.in_file(path, None))
}

/// Accepts Fortran's `D` exponent (`1.0D+00`) as well as Rust's syntax.
fn parse_real(token: &str, line: usize, what: &str) -> Result<f64> {
    parse(token, line, what).or_else(|e| {
        let fixed = token.replace(['D', 'd'], "e");
        fixed.parse().map_err(|_| e)
    })
}

fn read_ascii(data: &[u8]) -> Result<MeshData> {
    let header_end = data.iter().position(|&b| b == b'\n').unwrap_or(data.len());
    let header = String::from_utf8_lossy(&data[..header_end]);
    let mut head = header.split_whitespace();
    let nv: usize = super::text::next(&mut head, 1, "the vertex count")?;
    let nt: usize = super::text::next(&mut head, 1, "the triangle count")?;
    let mut tokens = Tokens::new(data.get(header_end + 1..).unwrap_or(&[]), 2);
    let mut mesh = MeshData::default();
    let truncated = |tokens: &Tokens, what: String| Error::Truncated {
        message: format!(
            "line 1 announces {nv} vertices and {nt} triangles; \
             the data ends on line {} before {what}",
            tokens.last_line()
        ),
    };

    mesh.points.reserve(capacity(nv, data.len(), 6));
    mesh.vertex_lines.reserve(capacity(nv, data.len(), 6));
    for i in 0..nv {
        let mut xyz = [0.0; 3];
        for (c, name) in xyz.iter_mut().zip(["x", "y", "z"]) {
            let (line, token) = tokens
                .next_token()
                .ok_or_else(|| truncated(&tokens, format!("coordinate {name} of vertex {i}")))?;
            if name == "x" {
                mesh.vertex_lines.push(line);
            }
            *c = parse_real(&token, line, &format!("coordinate {name} of vertex {i}"))?;
        }
        mesh.points.push(DVec3::from_array(xyz));
    }

    mesh.tris.reserve(capacity(nt, data.len(), 6));
    mesh.tri_lines.reserve(capacity(nt, data.len(), 6));
    for t in 0..nt {
        let mut tri = [0i64; 3];
        for (k, slot) in tri.iter_mut().enumerate() {
            let (line, token) = tokens
                .next_token()
                .ok_or_else(|| truncated(&tokens, format!("index {k} of triangle {t}")))?;
            if k == 0 {
                mesh.tri_lines.push(line);
            }
            let index: i64 = parse(&token, line, &format!("index {k} of triangle {t}"))?;
            // 1-based in the file; 0 becomes -1, which validation reports.
            *slot = index.saturating_sub(1);
        }
        mesh.tris.push(tri);
    }

    // Component IDs are optional, but once they start they must all be there.
    if let Some((line, token)) = tokens.next_token() {
        let mut ids = Vec::with_capacity(capacity(nt, data.len(), 2));
        ids.push(parse(&token, line, "component ID of triangle 0")?);
        for t in 1..nt {
            let (line, token) = tokens
                .next_token()
                .ok_or_else(|| truncated(&tokens, format!("the component ID of triangle {t}")))?;
            ids.push(parse(
                &token,
                line,
                &format!("component ID of triangle {t}"),
            )?);
        }
        mesh.components = Some(ids);
    }
    Ok(mesh)
}

/// A view of a binary file that reads Fortran records.
struct Records<'a> {
    data: &'a [u8],
    pos: usize,
    big: bool,
}

impl<'a> Records<'a> {
    fn word(&self, at: usize) -> Option<[u8; 4]> {
        let b = self.data.get(at..at.checked_add(4)?)?;
        Some([b[0], b[1], b[2], b[3]])
    }

    fn int(&self, b: [u8; 4]) -> i32 {
        if self.big {
            i32::from_be_bytes(b)
        } else {
            i32::from_le_bytes(b)
        }
    }

    /// The length announced by the next record's leading marker, if any.
    fn peek_len(&self) -> Option<i32> {
        self.word(self.pos).map(|b| self.int(b))
    }

    /// Reads record `n` (named `what` in messages), checking its leading
    /// marker against `expected` (any of them), the file size, and the
    /// trailing marker.
    fn record(&mut self, n: usize, what: &str, expected: &[u64]) -> Result<&'a [u8]> {
        let err = |message: String| Error::Truncated {
            message: format!("binary record {n} ({what}): {message}"),
        };
        let len = self
            .peek_len()
            .ok_or_else(|| err("the file ends before the record".into()))?;
        let want = || {
            let list: Vec<String> = expected.iter().map(u64::to_string).collect();
            list.join(" or ")
        };
        if len < 0 || !expected.contains(&(len as u64)) {
            return Err(err(format!(
                "the record marker says {len} bytes; the counts in record 1 need {}",
                want()
            )));
        }
        let len = len as usize;
        let start = self.pos + 4;
        let payload = self.data.get(start..start + len).ok_or_else(|| {
            err(format!(
                "the record needs {len} bytes but only {} remain",
                self.data.len() - start
            ))
        })?;
        let trailing = self
            .word(start + len)
            .ok_or_else(|| err("the file ends before the trailing record marker".into()))?;
        let trailing = self.int(trailing);
        if trailing as i64 != len as i64 {
            return Err(err(format!(
                "the leading record marker says {len} bytes but the trailing one says {trailing}"
            )));
        }
        self.pos = start + len + 4;
        Ok(payload)
    }

    fn ints(&self, payload: &'a [u8]) -> impl Iterator<Item = i32> + 'a {
        let big = self.big;
        payload.chunks_exact(4).map(move |c| {
            let b = [c[0], c[1], c[2], c[3]];
            if big {
                i32::from_be_bytes(b)
            } else {
                i32::from_le_bytes(b)
            }
        })
    }
}

fn read_binary(data: &[u8], big: bool) -> Result<MeshData> {
    let mut rec = Records { data, pos: 0, big };
    let counts = rec.record(1, "counts", &[8, 12])?;
    let counts: Vec<i32> = rec.ints(counts).collect();
    let (nv, nt) = (counts[0], counts[1]);
    if nv < 0 || nt < 0 {
        return Err(Error::Truncated {
            message: format!("binary record 1 announces {nv} vertices and {nt} triangles"),
        });
    }
    let (nv, nt) = (nv as u64, nt as u64);

    let coords = rec.record(2, "vertex coordinates", &[12 * nv, 24 * nv])?;
    let double = nv > 0 && coords.len() as u64 == 24 * nv;
    let points = if double {
        coords
            .chunks_exact(24)
            .map(|v| DVec3::from_array(std::array::from_fn(|k| real64(&v[8 * k..8 * k + 8], big))))
            .collect()
    } else {
        coords
            .chunks_exact(12)
            .map(|v| DVec3::from_array(std::array::from_fn(|k| real32(&v[4 * k..4 * k + 4], big))))
            .collect()
    };

    let indices = rec.record(3, "triangle indices", &[12 * nt])?;
    let flat: Vec<i32> = rec.ints(indices).collect();
    let tris = flat
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]].map(|i| i64::from(i) - 1))
        .collect();
    let mut mesh = MeshData {
        points,
        tris,
        ..MeshData::default()
    };

    // An optional fourth record of exactly nTris integers holds the
    // component IDs; anything else after the indices (scalars) is ignored.
    if rec.peek_len().map(i64::from) == Some(4 * nt as i64) {
        let ids = rec.record(4, "component IDs", &[4 * nt])?;
        mesh.components = Some(rec.ints(ids).collect());
    }
    Ok(mesh)
}

fn real32(b: &[u8], big: bool) -> f64 {
    let b = [b[0], b[1], b[2], b[3]];
    f64::from(if big {
        f32::from_be_bytes(b)
    } else {
        f32::from_le_bytes(b)
    })
}

fn real64(b: &[u8], big: bool) -> f64 {
    let b = [b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]];
    if big {
        f64::from_be_bytes(b)
    } else {
        f64::from_le_bytes(b)
    }
}

/// Writes an ASCII Cart3D file (1-based indices, no component IDs).
pub fn write_tri(path: &Path, points: &[DVec3], tris: &[[u32; 3]]) -> Result<()> {
    write_tri_impl(path, points, tris, None)
}

/// Writes an ASCII Cart3D file with one component ID per triangle, the way
/// Cart3D tags boundary patches.
pub fn write_tri_with_components(
    path: &Path,
    points: &[DVec3],
    tris: &[[u32; 3]],
    components: &[i32],
) -> Result<()> {
    if components.len() != tris.len() {
        return Err(Error::InvalidArgument(format!(
            "{} component IDs for {} triangles",
            components.len(),
            tris.len()
        )));
    }
    write_tri_impl(path, points, tris, Some(components))
}

fn write_tri_impl(
    path: &Path,
    points: &[DVec3],
    tris: &[[u32; 3]],
    components: Option<&[i32]>,
) -> Result<()> {
    use std::io::Write;
    super::check_tris(points, tris)?;
    let mut w = super::create(path)?;
    let io = super::io_error(path);
    writeln!(w, "{} {}", points.len(), tris.len()).map_err(&io)?;
    for &p in points {
        super::write_point(&mut w, p).map_err(&io)?;
        w.write_all(b"\n").map_err(&io)?;
    }
    for t in tris {
        let [a, b, c] = t.map(|i| u64::from(i) + 1);
        writeln!(w, "{a} {b} {c}").map_err(&io)?;
    }
    for id in components.unwrap_or(&[]) {
        writeln!(w, "{id}").map_err(&io)?;
    }
    super::finish(w, path)
}
