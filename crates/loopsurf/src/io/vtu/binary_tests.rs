//! Binary (`format="binary"`) `.vtu`: what the writer writes reads back
//! bit for bit, hand-made files with known bytes parse, damage is refused.

use std::path::Path;

use glam::DVec3;

use super::*;
use crate::io::msh::tests::{assert_identical, fixture, scratch};

/// A linear mesh with lines and point and cell arrays, through the binary
/// writer and the reader: every bit the same.
#[test]
fn linear_binary_round_trip() {
    let path = scratch("binary-linear.vtu");
    let points = [
        DVec3::ZERO,
        DVec3::new(1.0 / 3.0, -0.0, 1e-310),
        DVec3::new(0.1, f64::MAX, -7.5),
        DVec3::ONE,
    ];
    let tris = [[0, 1, 2], [2, 3, 0]];
    let lines = [[0, 3]];
    let k = [0.5, -1e-300, 7.0, f64::MIN_POSITIVE];
    let normals = [DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_ONE];
    let ids = [i32::MIN, -1, i32::MAX];
    let global = [-(1i64 << 53), 0, 1 << 40, (1 << 53) - 1];
    write_vtu_with_lines(
        &path,
        &points,
        &tris,
        &lines,
        &[
            ("k", DataArray::F64(&k)),
            ("n", DataArray::Vec3(&normals)),
            ("global", DataArray::I64(&global)),
        ],
        &[("id", DataArray::I32(&ids))],
        true,
    )
    .unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("format=\"binary\"") && !text.contains("format=\"ascii\""));
    let read = read_vtu(&path).unwrap();
    let bits = |p: &[DVec3]| -> Vec<[u64; 3]> {
        p.iter().map(|p| p.to_array().map(f64::to_bits)).collect()
    };
    assert_eq!(bits(&read.points), bits(&points));
    assert_eq!(read.connectivity, [0, 1, 2, 2, 3, 0, 0, 3]);
    assert_eq!(read.offsets, [3, 6, 8]);
    assert_eq!(read.cell_types, [5, 5, 3]);
    let k_read: Vec<u64> = read
        .point_array("k")
        .unwrap()
        .values
        .iter()
        .map(|x| x.to_bits())
        .collect();
    assert_eq!(k_read, k.map(f64::to_bits));
    let n = read.point_array("n").unwrap();
    assert_eq!(n.components, 3);
    assert_eq!(
        n.values,
        [1., 0., 0., 0., 1., 0., 0., 0., 1., -1., -1., -1.]
    );
    let id = read.cell_array("id").unwrap();
    assert_eq!(id.values, ids.map(f64::from));
    let global_read = &read.point_array("global").unwrap().values;
    assert_eq!(*global_read, global.map(|x| x as f64));
    std::fs::remove_file(&path).unwrap();
}

/// Curved P2 and P3 meshes (and P1, P4) through the binary writer come
/// back identical, as they do from ASCII.
#[test]
fn lagrange_binary_round_trip() {
    for k in 1..=4 {
        let mesh = fixture(k);
        let path = scratch(&format!("binary-lagrange{k}.vtu"));
        write_vtu_lagrange(&path, &mesh, &[], &[], true).unwrap();
        let read = read_vtu(&path).unwrap();
        let mut want = mesh.clone();
        want.corners.sort();
        assert_identical(&read.to_lagrange().unwrap(), &want);
        std::fs::remove_file(&path).unwrap();
    }
}

/// A triangle written by hand: UInt32 byte counts, one joint base64 run
/// per array, Float32 points, Int32 cells, an Int16 and a UInt16 array,
/// and one Float64 array with its count and values as two runs (VTK's own
/// layout). The base64 was made with Python's `base64` and `struct`, apart
/// from the crate under test.
const HAND: &str = r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="3" NumberOfCells="1">
      <PointData>
        <DataArray type="Float64" Name="h" format="binary">
          GAAAAA==AAAAAAAA4D9Z8/jCH26lgQAAAAAAABxA
        </DataArray>
        <DataArray type="UInt16" Name="u" format="binary">
          BgAAAP//AAABAA==
        </DataArray>
      </PointData>
      <CellData>
        <DataArray type="Int16" Name="face" format="binary">AgAAAP7/</DataArray>
      </CellData>
      <Points>
        <DataArray type="Float32" Name="Points" NumberOfComponents="3" format="binary">
          JAAAAAAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAA==
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int32" Name="connectivity" format="binary">DAAAAAAAAAABAAAAAgAAAA==</DataArray>
        <DataArray type="Int32" Name="offsets" format="binary">BAAAAAMAAAA=</DataArray>
        <DataArray type="UInt8" Name="types" format="binary">AQAAAAU=</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
"#;

fn parse(text: &str) -> crate::error::Result<VtuMesh> {
    parse_vtu(text.as_bytes(), Path::new("bin.vtu"))
}

#[test]
fn reads_hand_made_binary() {
    let m = parse(HAND).unwrap();
    assert_eq!(m.points, [DVec3::ZERO, DVec3::X, DVec3::Y]);
    assert_eq!((m.cell(0), m.num_cells()), ((5, &[0, 1, 2][..]), 1));
    assert_eq!(m.point_array("h").unwrap().values, [0.5, -1e-300, 7.0]);
    assert_eq!(m.point_array("u").unwrap().values, [65535.0, 0.0, 1.0]);
    assert_eq!(m.cell_array("face").unwrap().values, [-2.0]);
    // UInt64 counts in two runs are what the writer writes: the round
    // trips above read them.
}

/// The 1-based line of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    1 + text[..text.find(needle).unwrap()].matches('\n').count()
}

/// Damaged base64, a wrong byte count, a ragged value size and
/// compression are refused, naming the element and its line.
#[test]
fn damaged_binary_is_refused() {
    let cases = [
        // A character outside base64.
        ("AgAAAP7/", "AgAA!P7/", "Name=\"face\"", "damaged base64"),
        // The count says 13 bytes, 12 follow.
        (
            "DAAAAAAAAAABAAAAAgAAAA==",
            "DQAAAAAAAAABAAAAAgAAAA==",
            "Name=\"connectivity\"",
            "says 13 bytes, the data has 12",
        ),
        // 3 bytes of Int16.
        (
            "AgAAAP7/",
            "AwAAAP7/AA==",
            "Name=\"face\"",
            "no whole number",
        ),
        (
            "byte_order=",
            "compressor=\"vtkZLibDataCompressor\" byte_order=",
            "<VTKFile",
            "compressed data is not read",
        ),
    ];
    for (from, to, at, what) in cases {
        let text = HAND.replacen(from, to, 1);
        let err = parse(&text).unwrap_err().to_string();
        let line = line_of(&text, at);
        assert!(
            err.contains(&format!("bin.vtu:{line}:")) && err.contains(what),
            "{from} -> {to}: {err}"
        );
    }
    // Truncated anywhere in the data: an error, never a panic.
    let data = "JAAAAAAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAA==";
    for cut in 0..data.len() {
        assert!(
            parse(&HAND.replace(data, &data[..cut])).is_err(),
            "cut {cut}"
        );
    }
}
