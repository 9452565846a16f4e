use std::path::Path;

use glam::DVec3;

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
        false,
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
    let err = write_vtu_with_lines(&path, &points, &tris, &[[0, 4]], &[], &[], false).unwrap_err();
    assert!(err.to_string().contains("line 0"), "{err}");
    let err = write_vtu_with_lines(
        &path,
        &points,
        &tris,
        &lines,
        &[],
        &[("edge", DataArray::I32(&ids[..2]))],
        false,
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
        let vtk: Vec<(usize, usize)> = (0..crate::io::nodes_per_triangle(k))
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
            false,
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
    // An empty mesh (a rank's empty piece) has the arrays every mesh with
    // params has, ASCII and binary, and reads back empty.
    for binary in [false, true] {
        let path = scratch(&format!("empty{binary}.vtu"));
        let empty = crate::io::LagrangeMesh {
            order: 1,
            ..Default::default()
        };
        write_vtu_lagrange(&path, &empty, &[], &[], binary).unwrap();
        let read = read_vtu(&path).unwrap();
        let names: Vec<&str> = read.point_data.iter().map(|a| a.name.as_str()).collect();
        assert_eq!(names, ["loopsurf_params"]);
        assert_identical(&read.to_lagrange().unwrap(), &empty);
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
        false,
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
        false,
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
        msg.contains(&format!("bad.vtu:{line}:")) && msg.contains("damaged base64"),
        "{msg}"
    );
    let appended = PARAVIEW.replace(
        "  </UnstructuredGrid>",
        "  </UnstructuredGrid>\n<AppendedData encoding=\"raw\">_abc</AppendedData>",
    );
    assert!(vtu_err(&appended).contains("appended data is not read"));
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
        crate::io::damage(&mut data, &mut state, 3);
        if let Ok(m) = parse_vtu(&data, Path::new("damaged.vtu")) {
            let _ = m.to_lagrange();
        }
    }
}
