//! VTK XML UnstructuredGrid (`.vtu`), ASCII, for looking at results in
//! ParaView: a triangulation plus named per-point and per-cell arrays
//! (curvature, error fields, component IDs).
//!
//! Hand-written because the subset is tiny: Points as Float64 triples,
//! Cells as Int64 connectivity and offsets with UInt8 type 5 (VTK_TRIANGLE)
//! and, after the triangles, optionally type 3 (VTK_LINE) for edges such
//! as the hard ones: one piece of mixed cells, which ParaView shows
//! together and splits with "Extract Cells By Type" or a threshold on a
//! cell array.
//! VTK's ASCII reader cannot parse `nan` or `inf`, so non-finite values are
//! refused instead of producing a file ParaView chokes on.

use std::io::Write;
use std::path::Path;

use glam::DVec3;

use crate::error::{Error, Result};

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
    for (kind, arrays, n) in [
        ("point", point_data, points.len()),
        ("cell", cell_data, tris.len() + lines.len()),
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
    write_body(&mut w, points, tris, lines, point_data, cell_data)
        .map_err(super::io_error(path))?;
    super::finish(w, path)
}

fn write_body(
    w: &mut impl Write,
    points: &[DVec3],
    tris: &[[u32; 3]],
    lines: &[[u32; 2]],
    point_data: &[(&str, DataArray)],
    cell_data: &[(&str, DataArray)],
) -> std::io::Result<()> {
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(
        w,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">"
    )?;
    writeln!(w, "  <UnstructuredGrid>")?;
    writeln!(
        w,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        points.len(),
        tris.len() + lines.len()
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
    for t in tris {
        writeln!(w, "          {} {} {}", t[0], t[1], t[2])?;
    }
    for l in lines {
        writeln!(w, "          {} {}", l[0], l[1])?;
    }
    writeln!(w, "        </DataArray>")?;
    writeln!(
        w,
        "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
    )?;
    for k in 1..=tris.len() as u64 {
        writeln!(w, "          {}", 3 * k)?;
    }
    let end = 3 * tris.len() as u64;
    for k in 1..=lines.len() as u64 {
        writeln!(w, "          {}", end + 2 * k)?;
    }
    writeln!(w, "        </DataArray>")?;
    writeln!(
        w,
        "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">"
    )?;
    for _ in tris {
        writeln!(w, "          5")?;
    }
    for _ in lines {
        writeln!(w, "          3")?;
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
}
