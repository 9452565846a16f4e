//! Mesh files in and out. Readers keep the file's vertex and triangle order
//! (0-based); they only parse. Validation of the triangulation happens in
//! [`crate::ControlNet`], which maps element errors back to file lines using
//! the line tables readers record here.
//!
//! Every reader error names the file: format errors are wrapped in
//! [`Error::InFile`] (with the line where one is known), operating-system
//! errors are [`Error::Io`]. No reader trusts a count announced in a header
//! for allocation beyond what the file size can hold, and none panics on bad
//! input.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use glam::DVec3;

use crate::error::{Error, Result};

mod cart3d;
mod lagrange;
mod msh;
mod obj;
mod off;
mod ply;
mod polygon;
mod stl;
mod text;
mod vtu;

pub use cart3d::{read_tri, write_tri, write_tri_with_components};
pub use lagrange::{nodes_per_triangle, LagrangeMesh, MAX_LAGRANGE_ORDER};
pub use msh::{
    parse_msh, read_msh, write_msh, write_msh_tagged, MshElement, MshMesh, MshNodeData,
    MshPhysicalName, MshTags, PARAMS_VIEW,
};
pub use obj::{read_obj, write_obj};
pub use off::{read_off, write_off};
pub use ply::{read_ply, write_ply};
pub use polygon::Polygon;
pub use stl::{read_stl, write_stl};
pub use vtu::{
    parse_vtu, read_vtu, write_vtu, write_vtu_lagrange, write_vtu_with_lines, DataArray, VtuArray,
    VtuMesh,
};

/// What a reader found in a file, before any validation.
#[derive(Debug, Clone, Default)]
pub struct MeshData {
    /// Vertex coordinates in file order.
    pub points: Vec<DVec3>,
    /// Triangles as 0-based vertex indices in file order. Signed and wide so
    /// that a negative or out-of-range index survives to validation, which
    /// reports it with its triangle.
    pub tris: Vec<[i64; 3]>,
    /// 1-based line of each vertex (text formats; empty for binary ones).
    pub vertex_lines: Vec<usize>,
    /// 1-based line of each triangle (text formats; empty for binary ones).
    pub tri_lines: Vec<usize>,
    /// STL only: how many vertices were merged because their coordinates were
    /// exactly equal.
    pub welded: usize,
    /// Cart3D only: the component ID of each triangle, when the file has them.
    pub components: Option<Vec<i32>>,
    /// The polygon faces split into triangles under
    /// [`ParseOptions::triangulate`], in file order.
    pub polygons: Vec<Polygon>,
}

/// Options that change how files are parsed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ParseOptions {
    /// Split polygons into triangles (by ear clipping, so non-convex ones
    /// too) instead of rejecting them.
    pub triangulate: bool,
}

/// The file formats loopsurf knows, named by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Off,
    Obj,
    Ply,
    Stl,
    Tri,
    Vtu,
}

impl Format {
    /// The format an extension names (case-insensitive), if any.
    fn of(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "off" => Format::Off,
            "obj" => Format::Obj,
            "ply" => Format::Ply,
            "stl" => Format::Stl,
            "tri" => Format::Tri,
            "vtu" => Format::Vtu,
            _ => return None,
        })
    }
}

/// Reads a surface triangulation, choosing the format from the extension
/// (`.off`, `.obj`, `.ply`, `.stl`, `.tri`; case-insensitive).
pub fn read_mesh(path: &Path, opts: &ParseOptions) -> Result<MeshData> {
    // An unknown extension is refused before the file is read.
    if matches!(Format::of(path), None | Some(Format::Vtu)) {
        return Err(Error::UnknownFormat {
            path: path.to_path_buf(),
        });
    }
    parse_mesh(read_bytes(path)?, path, opts)
}

/// [`read_mesh`] of bytes already in memory (a file received over MPI, a
/// fuzzer's input): the format is the one `path`'s extension names, and
/// `path` names the source in errors; nothing is read from disk.
pub fn parse_mesh(data: Vec<u8>, path: &Path, opts: &ParseOptions) -> Result<MeshData> {
    let mut mesh = match Format::of(path) {
        Some(Format::Off) => off::parse_off(&data, opts, path),
        Some(Format::Obj) => obj::parse_obj(&data, opts, path),
        Some(Format::Ply) => ply::parse_ply(&data, opts, path),
        Some(Format::Stl) => stl::parse_stl(data, path),
        Some(Format::Tri) => cart3d::parse_tri(&data, path),
        Some(Format::Vtu) | None => Err(Error::UnknownFormat {
            path: path.to_path_buf(),
        }),
    }?;
    polygon::clip_ears(&mut mesh);
    Ok(mesh)
}

/// Fails with [`Error::UnknownFormat`] unless [`write_mesh`] can write `path`'s
/// extension: lets a command refuse a bad output name before long work.
pub fn check_writable(path: &Path) -> Result<()> {
    match Format::of(path) {
        Some(_) => Ok(()),
        None => Err(Error::UnknownFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// Writes a triangulation, choosing the format from the extension: `.obj`,
/// `.off`, `.ply` (ASCII, double), `.stl` (binary, single precision), `.tri`
/// (ASCII Cart3D) or `.vtu` (VTK XML, no data arrays). Text formats write
/// every coordinate with enough digits to read back bit-exact.
pub fn write_mesh(path: &Path, points: &[DVec3], tris: &[[u32; 3]]) -> Result<()> {
    write_mesh_as(path, points, tris, false)
}

/// [`write_mesh`], with `.vtu` arrays in inline binary (base64) when
/// `binary_vtu` is set; the other formats are as [`write_mesh`] writes
/// them.
pub fn write_mesh_as(
    path: &Path,
    points: &[DVec3],
    tris: &[[u32; 3]],
    binary_vtu: bool,
) -> Result<()> {
    match Format::of(path) {
        Some(Format::Off) => write_off(path, points, tris),
        Some(Format::Obj) => write_obj(path, points, tris),
        Some(Format::Ply) => write_ply(path, points, tris),
        Some(Format::Stl) => write_stl(path, points, tris),
        Some(Format::Tri) => write_tri(path, points, tris),
        Some(Format::Vtu) => write_vtu(path, points, tris, &[], &[], binary_vtu),
        None => Err(Error::UnknownFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// Reads a whole file; the readers parse from memory so they can look at the
/// file size before trusting any announced count.
fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Appends one face of a text or binary file, fan-splitting polygons from
/// their first corner when asked to (and recording them, for
/// [`polygon::clip_ears`] to redo once all points are known). Every triangle
/// of a split polygon records the polygon's line so validation errors point
/// at the file.
/// Callers reject faces with fewer than three corners themselves, because
/// only they know how to name the place.
fn push_face(
    mesh: &mut MeshData,
    face: usize,
    corners: &[i64],
    line: Option<usize>,
    opts: &ParseOptions,
    path: &Path,
) -> Result<()> {
    if corners.len() > 3 && !opts.triangulate {
        return Err(Error::Polygon {
            face,
            corners: corners.len(),
        }
        .in_file(path, line));
    }
    if corners.len() > 3 {
        mesh.polygons.push(Polygon {
            first_triangle: mesh.tris.len(),
            corners: corners.to_vec(),
        });
    }
    for k in 1..corners.len().saturating_sub(1) {
        mesh.tris.push([corners[0], corners[k], corners[k + 1]]);
        if let Some(line) = line {
            mesh.tri_lines.push(line);
        }
    }
    Ok(())
}

/// A capacity that a header count may ask for, bounded by what a file of
/// `bytes` bytes can hold at `min_size` bytes per item: a lying header must
/// not make us allocate gigabytes.
fn capacity(count: usize, bytes: usize, min_size: usize) -> usize {
    count.min(bytes / min_size.max(1))
}

/// Opens a file for writing behind a buffer.
fn create(path: &Path) -> Result<BufWriter<File>> {
    File::create(path)
        .map(BufWriter::new)
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
}

/// Two positions holding the same value, if any (the lowest value
/// repeated, its first two positions): for checking ids that must be
/// distinct.
pub fn repeated<T: Ord + Copy>(values: &[T]) -> Option<(usize, usize)> {
    let mut sorted: Vec<(T, usize)> = values.iter().copied().zip(0..).collect();
    sorted.sort_unstable();
    sorted
        .windows(2)
        .find(|w| w[0].0 == w[1].0)
        .map(|w| (w[0].1, w[1].1))
}

/// Turns a write error into an [`Error::Io`] naming the file.
fn io_error(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |source| Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Flushes a writer, naming the file on failure (a full disk shows up here).
fn finish(mut w: impl Write, path: &Path) -> Result<()> {
    w.flush().map_err(io_error(path))
}

/// Rejects triangles that refer past the point array: writers would
/// otherwise produce files that other programs crash on.
pub(crate) fn check_tris(points: &[DVec3], tris: &[[u32; 3]]) -> Result<()> {
    for (t, tri) in tris.iter().enumerate() {
        if let Some(&i) = tri.iter().find(|&&i| i as usize >= points.len()) {
            return Err(Error::InvalidArgument(format!(
                "triangle {t} {tri:?} refers to vertex {i}, but there are only {} points",
                points.len()
            )));
        }
    }
    Ok(())
}

/// Writes an f64 so that parsing the text gives back the same bits. Rust's
/// `Display` and `LowerExp` both print the shortest round-tripping digits;
/// plain notation reads best for ordinary magnitudes, exponent notation keeps
/// tiny and huge numbers short.
fn write_f64(w: &mut impl Write, x: f64) -> std::io::Result<()> {
    let a = x.abs();
    if x == 0.0 || (1e-5..1e16).contains(&a) {
        write!(w, "{x}")
    } else {
        write!(w, "{x:e}")
    }
}

/// Writes a point as three space-separated round-tripping numbers.
/// The body shared by OFF and ASCII PLY: one `x y z` line per vertex, then
/// one `3 i j k` line per triangle.
fn write_vertex_and_face_lines(
    w: &mut impl Write,
    points: &[DVec3],
    tris: &[[u32; 3]],
) -> std::io::Result<()> {
    for &p in points {
        write_point(w, p)?;
        w.write_all(b"\n")?;
    }
    for t in tris {
        writeln!(w, "3 {} {} {}", t[0], t[1], t[2])?;
    }
    Ok(())
}

fn write_point(w: &mut impl Write, p: DVec3) -> std::io::Result<()> {
    write_f64(w, p.x)?;
    w.write_all(b" ")?;
    write_f64(w, p.y)?;
    w.write_all(b" ")?;
    write_f64(w, p.z)
}

/// Overwrites `count` bytes of `data` at places and with values drawn from
/// `state` (xorshift): the damage the readers' robustness tests feed them.
#[cfg(test)]
pub(crate) fn damage(data: &mut [u8], state: &mut u64, count: usize) {
    for _ in 0..count {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        let at = (*state % data.len() as u64) as usize;
        data[at] = (*state >> 32) as u8;
    }
}
