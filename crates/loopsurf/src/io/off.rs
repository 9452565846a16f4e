//! Geomview OFF, hand-written so that every vertex and face keeps its line.
//!
//! Accepted: an optional `[ST][C][N]OFF` keyword (the extra per-vertex values
//! those prefixes announce, and per-face colours, are ignored), the counts
//! `nv nf [ne]` on the keyword's line or the next one, `#` comments and blank
//! lines anywhere. One vertex and one face per line, as every OFF writer in
//! practice produces; that is what makes line numbers meaningful. 4D/nD and
//! binary OFF are rejected with a clear message rather than misread.

use std::path::Path;

use glam::DVec3;

use super::text::{lines, next, parse, strip_comment};
use super::{capacity, push_face, read_bytes, MeshData, ParseOptions};
use crate::error::{Error, Result};

/// Reads an OFF file.
pub fn read_off(path: &Path, opts: &ParseOptions) -> Result<MeshData> {
    parse_off(&read_bytes(path)?, opts, path)
}

pub(crate) fn parse_off(data: &[u8], opts: &ParseOptions, path: &Path) -> Result<MeshData> {
    let malformed = |e: Error| e.in_file(path, None);
    let mut mesh = MeshData::default();
    let (mut first, mut counts_line) = (true, None);
    let (mut nv, mut nf, mut faces) = (0usize, 0usize, 0usize);
    let mut corners = Vec::new();
    for (line, raw) in lines(data) {
        let text = strip_comment(&raw);
        if text.is_empty() {
            continue;
        }
        let mut tokens = text.split_whitespace().peekable();
        if first {
            first = false;
            let keyword = tokens.peek().copied().unwrap_or("");
            if keyword.ends_with("OFF") {
                check_keyword(keyword, text, line).map_err(malformed)?;
                tokens.next();
                if tokens.peek().is_none() {
                    continue;
                }
            }
        }
        if counts_line.is_none() {
            nv = next(&mut tokens, line, "the vertex count").map_err(malformed)?;
            nf = next(&mut tokens, line, "the face count").map_err(malformed)?;
            counts_line = Some(line);
            mesh.points.reserve(capacity(nv, data.len(), 6));
            mesh.vertex_lines.reserve(capacity(nv, data.len(), 6));
            mesh.tris.reserve(capacity(nf, data.len(), 8));
            mesh.tri_lines.reserve(capacity(nf, data.len(), 8));
        } else if mesh.points.len() < nv {
            let mut xyz = [0.0; 3];
            for (c, name) in xyz.iter_mut().zip(["x", "y", "z"]) {
                *c = next(&mut tokens, line, &format!("vertex coordinate {name}"))
                    .map_err(malformed)?;
            }
            mesh.points.push(DVec3::from_array(xyz));
            mesh.vertex_lines.push(line);
        } else if faces < nf {
            let n: usize = next(&mut tokens, line, "the face's vertex count").map_err(malformed)?;
            if n < 3 {
                return Err(malformed(Error::Malformed {
                    line,
                    message: format!("face {faces} has {n} vertices; at least 3 are needed"),
                }));
            }
            corners.clear();
            for k in 0..n {
                let token = tokens.next().ok_or_else(|| {
                    malformed(Error::Malformed {
                        line,
                        message: format!("face {faces} announces {n} vertices but lists {k}"),
                    })
                })?;
                corners.push(parse(token, line, "a vertex index").map_err(malformed)?);
            }
            push_face(&mut mesh, faces, &corners, Some(line), opts, path)?;
            faces += 1;
        } else {
            break;
        }
    }
    match counts_line {
        Some(_) if mesh.points.len() == nv && faces == nf => Ok(mesh),
        Some(counts_line) => Err(Error::Truncated {
            message: format!(
                "line {counts_line} announces {nv} vertices and {nf} faces, \
                 but the file ends after {} vertices and {faces} faces",
                mesh.points.len()
            ),
        }
        .in_file(path, None)),
        None => Err(Error::Truncated {
            message: "no vertex and face counts found".into(),
        }
        .in_file(path, None)),
    }
}

/// Accepts `OFF` with the Geomview prefixes whose extra values we can skip;
/// rejects the variants whose data we would misread.
fn check_keyword(keyword: &str, text: &str, line: usize) -> Result<()> {
    let mut rest = keyword.strip_suffix("OFF").unwrap_or(keyword);
    for prefix in ["ST", "C", "N"] {
        rest = rest.strip_prefix(prefix).unwrap_or(rest);
    }
    let unsupported = |what: &str| Error::Malformed {
        line,
        message: format!("{what} OFF ({keyword:?}) is not supported"),
    };
    if rest.contains('4') || rest.contains('n') {
        return Err(unsupported("4D or n-dimensional"));
    }
    if !rest.is_empty() {
        return Err(Error::Malformed {
            line,
            message: format!("unknown OFF keyword {keyword:?}"),
        });
    }
    if text.split_whitespace().nth(1) == Some("BINARY") {
        return Err(unsupported("binary"));
    }
    Ok(())
}

/// Writes an OFF file with round-tripping coordinates.
pub fn write_off(path: &Path, points: &[DVec3], tris: &[[u32; 3]]) -> Result<()> {
    use std::io::Write;
    super::check_tris(points, tris)?;
    let mut w = super::create(path)?;
    let io = super::io_error(path);
    writeln!(w, "OFF\n{} {} 0", points.len(), tris.len()).map_err(&io)?;
    super::write_vertex_and_face_lines(&mut w, points, tris).map_err(&io)?;
    super::finish(w, path)
}
