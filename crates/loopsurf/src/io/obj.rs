//! Wavefront OBJ, hand-written: general OBJ loaders (tobj and friends)
//! re-index vertices per object or per material and lose the file's order,
//! which loopsurf promises to keep.
//!
//! Only `v` (x y z, optional w or colour ignored) and `f` are read; `f`
//! corners may be `a`, `a/b`, `a/b/c` or `a//c`, and negative indices count
//! back from the last vertex defined so far, per the OBJ specification.
//! Texture coordinates, normals, groups, materials, smoothing groups, lines
//! and points are skipped. A line ending in `\` continues on the next one.

use std::path::Path;

use glam::DVec3;

use super::text::{lines, next, parse, strip_comment};
use super::{push_face, read_bytes, MeshData, ParseOptions};
use crate::error::{Error, Result};

/// Reads an OBJ file.
pub fn read_obj(path: &Path, opts: &ParseOptions) -> Result<MeshData> {
    parse_obj(&read_bytes(path)?, opts, path)
}

pub(crate) fn parse_obj(data: &[u8], opts: &ParseOptions, path: &Path) -> Result<MeshData> {
    let malformed = |e: Error| e.in_file(path, None);
    let mut mesh = MeshData::default();
    let mut faces = 0usize;
    let mut corners = Vec::new();
    // A statement continued with `\` is joined and keeps its first line.
    let mut pending = String::new();
    let mut pending_line = 0;
    // The sentinel empty line flushes a continuation left open at the end.
    let sentinel = std::iter::once((0, std::borrow::Cow::Borrowed("")));
    for (line, raw) in lines(data).chain(sentinel) {
        let text = strip_comment(&raw);
        if pending.is_empty() {
            pending_line = line;
        }
        if let Some(head) = text.strip_suffix('\\') {
            pending.push_str(head);
            pending.push(' ');
            continue;
        }
        pending.push_str(text);
        let statement = std::mem::take(&mut pending);
        let line = pending_line;
        let mut tokens = statement.split_whitespace();
        match tokens.next() {
            Some("v") => {
                let mut xyz = [0.0; 3];
                for (c, name) in xyz.iter_mut().zip(["x", "y", "z"]) {
                    *c = next(&mut tokens, line, &format!("vertex coordinate {name}"))
                        .map_err(malformed)?;
                }
                mesh.points.push(DVec3::from_array(xyz));
                mesh.vertex_lines.push(line);
            }
            Some("f") => {
                corners.clear();
                for token in tokens {
                    let index = resolve(token, mesh.points.len(), line).map_err(malformed)?;
                    corners.push(index);
                }
                if corners.len() < 3 {
                    return Err(malformed(Error::Malformed {
                        line,
                        message: format!(
                            "face {faces} has {} vertices; at least 3 are needed",
                            corners.len()
                        ),
                    }));
                }
                push_face(&mut mesh, faces, &corners, Some(line), opts, path)?;
                faces += 1;
            }
            _ => {}
        }
    }
    Ok(mesh)
}

/// Turns an OBJ corner (`a`, `a/b`, `a/b/c`, `a//c`) into a 0-based vertex
/// index. A positive index past the vertices read so far is kept (OBJ allows
/// forward references; validation reports it if it stays out of range); zero
/// and relative indices reaching before the first vertex are errors here,
/// because no stored number could describe them honestly.
fn resolve(token: &str, defined: usize, line: usize) -> Result<i64> {
    let first = token.split('/').next().unwrap_or("");
    let index: i64 = parse(first, line, "a vertex index")?;
    let bad = |why: String| Error::Malformed {
        line,
        message: format!("vertex index {index} in {token:?}: {why}"),
    };
    match index {
        0 => Err(bad("OBJ indices start at 1".into())),
        i if i > 0 => Ok(i - 1),
        i => {
            let resolved = defined as i64 + i;
            if resolved < 0 {
                Err(bad(format!(
                    "reaches before the first vertex ({defined} defined so far)"
                )))
            } else {
                Ok(resolved)
            }
        }
    }
}

/// Writes an OBJ file (1-based indices) with round-tripping coordinates.
pub fn write_obj(path: &Path, points: &[DVec3], tris: &[[u32; 3]]) -> Result<()> {
    use std::io::Write;
    super::check_tris(points, tris)?;
    let mut w = super::create(path)?;
    let io = super::io_error(path);
    for &p in points {
        w.write_all(b"v ").map_err(&io)?;
        super::write_point(&mut w, p).map_err(&io)?;
        w.write_all(b"\n").map_err(&io)?;
    }
    for t in tris {
        writeln!(
            w,
            "f {} {} {}",
            u64::from(t[0]) + 1,
            u64::from(t[1]) + 1,
            u64::from(t[2]) + 1
        )
        .map_err(&io)?;
    }
    super::finish(w, path)
}
