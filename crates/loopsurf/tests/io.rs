//! Readers and writers: every format and variant, round trips, bad input,
//! and the real meshes of CGAL's demo data when they are available.

use std::path::{Path, PathBuf};

use glam::DVec3;
use loopsurf::io::{
    read_mesh, write_mesh, write_tri_with_components, write_vtu, DataArray, MeshData, ParseOptions,
};
use loopsurf::Error;

#[path = "support/cgal_data.rs"]
mod cgal_data;

/// A fresh directory per test under the system temp dir.
fn dir(test: &str) -> PathBuf {
    let d = std::env::temp_dir()
        .join(format!("loopsurf-io-{}", std::process::id()))
        .join(test);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn put(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

fn read(p: &Path) -> loopsurf::Result<MeshData> {
    read_mesh(p, &ParseOptions::default())
}

fn read_tri_opts(p: &Path) -> loopsurf::Result<MeshData> {
    read_mesh(p, &ParseOptions { triangulate: true })
}

fn pts(m: &MeshData) -> Vec<[f64; 3]> {
    m.points.iter().map(|p| p.to_array()).collect()
}

/// The error's message must name the file.
fn names_file(err: &Error, p: &Path) {
    let msg = err.to_string();
    assert!(
        msg.contains(&p.display().to_string()),
        "{msg:?} does not name {p:?}"
    );
}

// ---------------------------------------------------------------- OFF

#[test]
fn off_with_comments_and_variants() {
    let d = dir("off_variants");
    let p = put(
        &d,
        "a.off",
        "# leading comment\n\nOFF # keyword\n# counts next\n4 2 0\n\
         0 0 0\n1 0 0 # v1\n\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3 255 0 0\n",
    );
    let m = read(&p).unwrap();
    assert_eq!(pts(&m)[1], [1.0, 0.0, 0.0]);
    assert_eq!(m.tris, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(m.vertex_lines, vec![6, 7, 9, 10]);
    assert_eq!(m.tri_lines, vec![11, 12]);

    // Counts on the keyword line, colours per vertex, CRLF line ends.
    let p = put(
        &d,
        "b.off",
        "COFF 3 1 0\r\n0 0 0 1 0 0 1\r\n1 0 0 0 1 0 1\r\n0 1 0 0 0 1 1\r\n3 2 1 0\r\n",
    );
    let m = read(&p).unwrap();
    assert_eq!(m.points.len(), 3);
    assert_eq!(m.tris, vec![[2, 1, 0]]);
    assert_eq!(m.tri_lines, vec![5]);

    // NOFF (normals after xyz), upper-case extension.
    let p = put(
        &d,
        "c.OFF",
        "NOFF\n3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
    );
    assert_eq!(read(&p).unwrap().points[2], DVec3::Y);
}

#[test]
fn off_polygons() {
    let d = dir("off_polygons");
    let text = "OFF\n5 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n-1 1 0\n5 0 1 2 3 4\n";
    let p = put(&d, "poly.off", text);
    let err = read(&p).unwrap_err();
    assert!(
        matches!(
            err.root(),
            Error::Polygon {
                face: 0,
                corners: 5
            }
        ),
        "{err}"
    );
    assert!(
        matches!(err, Error::InFile { line: Some(8), .. }),
        "{err:?}"
    );
    names_file(&err, &p);
    let m = read_tri_opts(&p).unwrap();
    assert_eq!(m.tris, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
    assert_eq!(m.tri_lines, vec![8, 8, 8]);

    let p = put(&d, "edge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
    let err = read_tri_opts(&p).unwrap_err();
    assert!(
        matches!(err.root(), Error::Malformed { line: 6, .. }),
        "{err}"
    );
}

#[test]
fn off_bad_input() {
    let d = dir("off_bad");
    let p = put(
        &d,
        "short.off",
        "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n",
    );
    let err = read(&p).unwrap_err();
    assert!(matches!(err.root(), Error::Truncated { .. }), "{err}");
    names_file(&err, &p);

    let p = put(
        &d,
        "number.off",
        "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1x 0\n3 0 1 2\n",
    );
    let err = read(&p).unwrap_err();
    assert!(
        matches!(err.root(), Error::Malformed { line: 5, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("line 5"), "{err}");
    names_file(&err, &p);

    let cases: [(&str, &[u8]); 10] = [
        ("empty.off", b""),
        ("nocounts.off", b"OFF\n# nothing\n"),
        ("negative.off", b"OFF\n-3 1 0\n"),
        (
            "huge.off",
            b"OFF\n18446744073709551615 18446744073709551615 0\n0 0 0\n",
        ),
        ("toolarge.off", b"OFF\n99999999999999999999999999 1 0\n"),
        ("fewidx.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
        (
            "badidx.off",
            b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n",
        ),
        ("binary.off", b"OFF false\n"),
        ("fourd.off", b"4OFF\n1 0 0\n0 0 0 0\n"),
        ("junk.off", &[0xff, 0xfe, 0, 1, 2]),
    ];
    for (name, text) in cases {
        let p = put(&d, name, text);
        let err = read(&p).unwrap_err();
        assert!(
            matches!(
                err.root(),
                Error::Malformed { .. } | Error::Truncated { .. }
            ),
            "{name}: {err}"
        );
        names_file(&err, &p);
    }

    // Out-of-range and negative indices are kept for validation to report.
    let p = put(
        &d,
        "range.off",
        "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 7\n",
    );
    assert_eq!(read(&p).unwrap().tris, vec![[0, -1, 7]]);
}

// ---------------------------------------------------------------- OBJ

#[test]
fn obj_forms_and_relative_indices() {
    let d = dir("obj_forms");
    let text = "# exported\nmtllib a.mtl\no thing\ng part\n\
                v 0 0 0\nv 1 0 0 1.0\nvt 0 0\nvn 0 0 1\nv 0 1 0\nv 0 0 1 0.5 0.5 0.5\n\
                usemtl red\ns 1\nf 1 2 3\nf 1/1 3/1 4/1\nf 1//1 2//1 4//1\nf -4/1/1 -1/1/1 -2/1/1\n\
                l 1 2\nf 2 \\\n 3 4\n";
    let p = put(&d, "a.obj", text);
    let m = read(&p).unwrap();
    assert_eq!(m.points.len(), 4);
    assert_eq!(m.points[3], DVec3::Z);
    assert_eq!(
        m.tris,
        vec![[0, 1, 2], [0, 2, 3], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    );
    assert_eq!(m.vertex_lines, vec![5, 6, 9, 10]);
    assert_eq!(m.tri_lines, vec![13, 14, 15, 16, 18]);
}

#[test]
fn obj_polygons_and_bad_indices() {
    let d = dir("obj_polygons");
    let p = put(
        &d,
        "quad.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1/1 3/1 4/1 2/1\n",
    );
    let err = read(&p).unwrap_err();
    assert!(
        matches!(
            err.root(),
            Error::Polygon {
                face: 1,
                corners: 4
            }
        ),
        "{err}"
    );
    names_file(&err, &p);
    assert!(err.to_string().contains(":6"), "{err}");
    let m = read_tri_opts(&p).unwrap();
    assert_eq!(m.tris, vec![[0, 1, 2], [0, 2, 3], [0, 3, 1]]);
    assert_eq!(m.tri_lines, vec![5, 6, 6]);

    for (name, text, line) in [
        ("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4),
        ("before.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n", 3),
        ("number.obj", "v 0 0 0\nv 1 0 zz\n", 2),
        ("short.obj", "v 0 0\n", 1),
        ("line.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", 3),
    ] {
        let p = put(&d, name, text);
        let err = read(&p).unwrap_err();
        assert!(
            matches!(err.root(), Error::Malformed { line: l, .. } if *l == line),
            "{name}: {err}"
        );
        assert!(err.to_string().contains(&format!("line {line}")), "{err}");
        names_file(&err, &p);
    }

    // Forward and out-of-range positive indices survive to validation.
    // A continuation on the last line still counts.
    let p = put(&d, "cont.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n3 \\");
    assert_eq!(read(&p).unwrap().tris, vec![[0, 1, 2]]);

    let p = put(&d, "fwd.obj", "f 1 2 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    assert_eq!(read(&p).unwrap().tris, vec![[0, 1, 8]]);
}

// ---------------------------------------------------------------- PLY

const PLY_POINTS: [[f32; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.5, 0.0, 0.0],
    [0.0, 2.25, 0.0],
    [0.0, 0.0, -3.125],
];

/// A binary PLY with float xyz plus an extra uchar property, uchar/int faces.
fn binary_ply(big: bool, faces: &[&[i32]]) -> Vec<u8> {
    let enc = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut b = format!(
        "ply\nformat {enc} 1.0\ncomment by hand\nelement vertex 4\nproperty float x\n\
         property float y\nproperty float z\nproperty uchar quality\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        faces.len()
    )
    .into_bytes();
    for p in PLY_POINTS {
        for c in p {
            b.extend(if big {
                c.to_be_bytes()
            } else {
                c.to_le_bytes()
            });
        }
        b.push(7);
    }
    for f in faces {
        b.push(f.len() as u8);
        for &i in *f {
            b.extend(if big {
                i.to_be_bytes()
            } else {
                i.to_le_bytes()
            });
        }
    }
    b
}

#[test]
fn ply_ascii() {
    let d = dir("ply_ascii");
    let text = "ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty double x\n\
                property double y\nproperty double z\nelement face 3\n\
                property list uchar uint vertex_index\nproperty uchar red\nend_header\n\
                0 0 0\n1.5 0 0\n0 2.25 0\n0 0 -3.125\n3 0 1 2 9\n3 0 2 3 9\n4 0 1 2 3 9\n";
    let p = put(&d, "a.ply", text);
    let err = read(&p).unwrap_err();
    assert!(
        matches!(
            err.root(),
            Error::Polygon {
                face: 2,
                corners: 4
            }
        ),
        "{err}"
    );
    assert!(
        matches!(err, Error::InFile { line: Some(18), .. }),
        "{err:?}"
    );
    let m = read_tri_opts(&p).unwrap();
    assert_eq!(pts(&m), PLY_POINTS.map(|p| p.map(f64::from)).to_vec());
    // The quad is split along its better diagonal (0-2), its best ear first.
    assert_eq!(m.tris, vec![[0, 1, 2], [0, 2, 3], [2, 3, 0], [0, 1, 2]]);
    assert_eq!(m.polygons.len(), 1);
    assert_eq!(m.polygons[0].first_triangle, 2);
    assert_eq!(m.vertex_lines, vec![12, 13, 14, 15]);
    assert_eq!(m.tri_lines, vec![16, 17, 18, 18]);
}

#[test]
fn ply_binary_both_endians() {
    let d = dir("ply_binary");
    for big in [false, true] {
        let p = put(
            &d,
            &format!("b{big}.ply"),
            binary_ply(big, &[&[0, 1, 2], &[0, 2, 3], &[3, 2, 1]]),
        );
        let m = read(&p).unwrap();
        assert_eq!(
            pts(&m),
            PLY_POINTS.map(|p| p.map(f64::from)).to_vec(),
            "big={big}"
        );
        assert_eq!(m.tris, vec![[0, 1, 2], [0, 2, 3], [3, 2, 1]]);
        assert!(m.vertex_lines.is_empty() && m.tri_lines.is_empty());

        let p = put(
            &d,
            &format!("q{big}.ply"),
            binary_ply(big, &[&[0, 1, 2], &[0, 1, 2, 3]]),
        );
        let err = read(&p).unwrap_err();
        assert!(
            matches!(
                err.root(),
                Error::Polygon {
                    face: 1,
                    corners: 4
                }
            ),
            "{err}"
        );
        names_file(&err, &p);
        assert_eq!(read_tri_opts(&p).unwrap().tris.len(), 3);

        let mut bytes = binary_ply(big, &[&[0, 1, 2], &[0, 2, 3]]);
        bytes.truncate(bytes.len() - 5);
        let p = put(&d, &format!("t{big}.ply"), bytes);
        let err = read(&p).unwrap_err();
        assert!(matches!(err.root(), Error::Truncated { .. }), "{err}");
        names_file(&err, &p);
    }
}

#[test]
fn ply_bad_headers_do_not_panic() {
    let d = dir("ply_bad");
    for (name, text) in [
        ("magic.ply", "plx\nformat ascii 1.0\nend_header\n"),
        ("noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"),
        ("huge.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nproperty float x\nend_header\n"),
        ("version.ply", "ply\nformat ascii 99999999999999999999999.0\nend_header\n"),
        ("noprops.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\nend_header\n"),
        ("noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n"),
        ("floatlist.ply", "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n"),
        ("dup.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\nend_header\n"),
        ("short.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n"),
        ("number.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 zero 0\n"),
        ("bigcount.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0"),
    ] {
        let p = put(&d, name, text);
        let err = read(&p).unwrap_err();
        assert!(
            matches!(err.root(), Error::Malformed { .. } | Error::Truncated { .. }),
            "{name}: {err}"
        );
        names_file(&err, &p);
    }
    let p = put(&d, "number2.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 zero 0\n");
    assert!(matches!(
        read(&p).unwrap_err().root(),
        Error::Malformed { line: 8, .. }
    ));
}

// ---------------------------------------------------------------- STL

/// Two triangles sharing an edge, the second listing a new corner first.
const STL_TRIS: [[[f32; 3]; 3]; 2] = [
    [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
    [[1.0, 1.0, 0.5], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]],
];

fn binary_stl(header: &[u8], tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut b = header.to_vec();
    b.resize(80, b' ');
    b.extend((tris.len() as u32).to_le_bytes());
    for t in tris {
        b.extend([0u8; 12]);
        for v in t {
            for c in v {
                b.extend(c.to_le_bytes());
            }
        }
        b.extend([0u8; 2]);
    }
    b
}

fn check_stl(m: &MeshData) {
    assert_eq!(
        pts(m),
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.5]
        ]
    );
    assert_eq!(m.tris, vec![[0, 1, 2], [3, 2, 1]]);
    assert_eq!(m.welded, 2);
}

#[test]
fn stl_binary() {
    let d = dir("stl_binary");
    // Headers starting with "solid" are common in binary files.
    for (i, header) in [b"exported".as_slice(), b"solid part"].iter().enumerate() {
        let p = put(&d, &format!("b{i}.stl"), binary_stl(header, &STL_TRIS));
        let m = read(&p).unwrap();
        check_stl(&m);
        assert!(m.vertex_lines.is_empty());
    }
    // -0.0 and 0.0 are the same coordinate.
    let mut tris = STL_TRIS;
    tris[1][1] = [-0.0, 1.0, 0.0];
    check_stl(&read(&put(&d, "negzero.stl", binary_stl(b"x", &tris))).unwrap());

    let mut bytes = binary_stl(b"solid x", &STL_TRIS);
    bytes.truncate(bytes.len() - 10);
    let p = put(&d, "short.stl", bytes);
    let err = read(&p).unwrap_err();
    assert!(matches!(err.root(), Error::Truncated { .. }), "{err}");
    names_file(&err, &p);
    let p = put(&d, "tiny.stl", [1u8, 2, 3]);
    assert!(matches!(
        read(&p).unwrap_err().root(),
        Error::Truncated { .. }
    ));
}

fn ascii_facet(t: &[[f32; 3]; 3]) -> String {
    let mut s = String::from("  facet normal 0 0 1\n    outer loop\n");
    for v in t {
        s += &format!("      vertex {:e} {:e} {:e}\n", v[0], v[1], v[2]);
    }
    s + "    endloop\n  endfacet\n"
}

#[test]
fn stl_ascii() {
    let d = dir("stl_ascii");
    let text = format!(
        "solid one\n{}{}endsolid one\n",
        ascii_facet(&STL_TRIS[0]),
        ascii_facet(&STL_TRIS[1])
    );
    check_stl(&read(&put(&d, "a.stl", &text)).unwrap());

    // A bare "solid" line, CRLF, and two solids in one file.
    let text = format!(
        "solid\r\n{}endsolid\r\nsolid second\r\n{}endsolid second\r\n",
        ascii_facet(&STL_TRIS[0]),
        ascii_facet(&STL_TRIS[1])
    );
    check_stl(&read(&put(&d, "b.stl", text)).unwrap());

    let text = format!(
        "solid x\n{}  facet normal 0 0 1\n    outer loop\n      vertex 1 2 zz\n",
        ascii_facet(&STL_TRIS[0])
    );
    let p = put(&d, "bad.stl", text);
    let err = read(&p).unwrap_err();
    assert!(
        matches!(err.root(), Error::Malformed { line: 9, .. }),
        "{err}"
    );
    names_file(&err, &p);

    let text = format!(
        "solid x\n{}  facet normal 0 0 1\n    outer loop\n",
        ascii_facet(&STL_TRIS[0])
    );
    let err = read(&put(&d, "short.stl", text)).unwrap_err();
    assert!(matches!(err.root(), Error::Truncated { .. }), "{err}");
}

// ---------------------------------------------------------------- Cart3D

const TRI_POINTS: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.1, 0.2, 1.0 / 3.0],
];
const TRI_TRIS: [[i64; 3]; 3] = [[0, 1, 2], [0, 1, 3], [1, 2, 3]];

#[test]
fn cart3d_ascii() {
    let d = dir("tri_ascii");
    let body = "4 3\n0 0 0\n1 0 0\n0 1 0\n0.1 0.2 0.3333333333333333\n1 2 3\n1 2 4\n2 3 4\n";
    let m = read(&put(&d, "a.tri", body)).unwrap();
    assert_eq!(pts(&m), TRI_POINTS.to_vec());
    assert_eq!(m.tris, TRI_TRIS.to_vec());
    assert_eq!(m.components, None);
    assert_eq!(m.vertex_lines, vec![2, 3, 4, 5]);
    assert_eq!(m.tri_lines, vec![6, 7, 8]);

    // nScalars on the header, IDs several per line, Fortran D exponents.
    let text = "4 3 1\n0 0 0\n1.0D+00 0 0\n0 1 0\n0.1 0.2 0.3333333333333333\n1 2 3\n1 2 4\n2 3 4\n7 7\n9\n0.5 0.5 0.5 0.5\n";
    let m = read(&put(&d, "b.tri", text)).unwrap();
    assert_eq!(pts(&m), TRI_POINTS.to_vec());
    assert_eq!(m.components, Some(vec![7, 7, 9]));

    for (name, text) in [
        ("short.tri", "4 3\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 2 3\n"),
        ("ids.tri", "3 2\n0 0 0\n1 0 0\n0 1 0\n1 2 3\n1 3 2\n5\n"),
        ("number.tri", "3 1\n0 0 0\n1 0 0\n0 1 q\n1 2 3\n"),
        ("header.tri", "three 1\n"),
        ("empty.tri", ""),
    ] {
        let p = put(&d, name, text);
        let err = read(&p).unwrap_err();
        assert!(
            matches!(
                err.root(),
                Error::Malformed { .. } | Error::Truncated { .. }
            ),
            "{name}: {err}"
        );
        names_file(&err, &p);
    }
    let err = read(&put(&d, "number2.tri", "3 1\n0 0 0\n1 0 0\n0 1 q\n1 2 3\n")).unwrap_err();
    assert!(
        matches!(err.root(), Error::Malformed { line: 4, .. }),
        "{err}"
    );
}

/// A Fortran-unformatted Cart3D file written by hand.
fn binary_tri(big: bool, double: bool, ids: bool) -> Vec<u8> {
    let int = |v: i32| {
        if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let mut out = Vec::new();
    let mut record = |payload: Vec<u8>| {
        out.extend(int(payload.len() as i32));
        out.extend(&payload);
        out.extend(int(payload.len() as i32));
    };
    record([int(4), int(3)].concat());
    let mut coords = Vec::new();
    for p in TRI_POINTS {
        for c in p {
            match (double, big) {
                (true, true) => coords.extend(c.to_be_bytes()),
                (true, false) => coords.extend(c.to_le_bytes()),
                (false, true) => coords.extend((c as f32).to_be_bytes()),
                (false, false) => coords.extend((c as f32).to_le_bytes()),
            }
        }
    }
    record(coords);
    record(
        TRI_TRIS
            .iter()
            .flatten()
            .flat_map(|&i| int(i as i32 + 1))
            .collect(),
    );
    if ids {
        record([int(1), int(2), int(2)].concat());
    }
    out
}

#[test]
fn cart3d_binary_variants() {
    let d = dir("tri_binary");
    for big in [false, true] {
        for double in [false, true] {
            for ids in [false, true] {
                let name = format!("{big}-{double}-{ids}.tri");
                let m = read(&put(&d, &name, binary_tri(big, double, ids))).unwrap();
                let want: Vec<[f64; 3]> = if double {
                    TRI_POINTS.to_vec()
                } else {
                    TRI_POINTS
                        .iter()
                        .map(|p| p.map(|c| c as f32 as f64))
                        .collect()
                };
                assert_eq!(pts(&m), want, "{name}");
                assert_eq!(m.tris, TRI_TRIS.to_vec(), "{name}");
                assert_eq!(m.components, ids.then(|| vec![1, 2, 2]), "{name}");
                assert!(m.vertex_lines.is_empty() && m.tri_lines.is_empty());
            }
        }
    }
}

#[test]
fn cart3d_binary_damage() {
    let d = dir("tri_damage");
    // Trailing marker of record 2 (f32, LE) changed.
    let mut bytes = binary_tri(false, false, true);
    let at = 16 + 4 + 48;
    bytes[at] ^= 1;
    let p = put(&d, "marker.tri", bytes);
    let err = read(&p).unwrap_err();
    assert!(err.to_string().contains("record 2"), "{err}");
    assert!(matches!(
        err.root(),
        Error::Truncated { .. } | Error::Malformed { .. }
    ));
    names_file(&err, &p);

    // Cut inside the index record.
    let mut bytes = binary_tri(true, true, false);
    bytes.truncate(bytes.len() - 6);
    let err = read(&put(&d, "cut.tri", bytes)).unwrap_err();
    assert!(err.to_string().contains("record 3"), "{err}");

    // Counts that do not match the coordinate record, and absurd counts.
    let mut bytes = binary_tri(false, true, false);
    bytes[4] = 5;
    let err = read(&put(&d, "counts.tri", bytes)).unwrap_err();
    assert!(err.to_string().contains("record 2"), "{err}");
    let mut bytes = 8i32.to_le_bytes().to_vec();
    bytes.extend(i32::MAX.to_le_bytes());
    bytes.extend(i32::MAX.to_le_bytes());
    bytes.extend(8i32.to_le_bytes());
    bytes.extend(i32::MAX.to_le_bytes());
    let err = read(&put(&d, "absurd.tri", bytes)).unwrap_err();
    assert!(
        matches!(
            err.root(),
            Error::Truncated { .. } | Error::Malformed { .. }
        ),
        "{err}"
    );
}

// ---------------------------------------------------------------- writers

/// Values that catch lossy formatting: thirds, tiny, huge, subnormal, -0.
fn awkward_points() -> Vec<DVec3> {
    vec![
        DVec3::new(0.0, -0.0, 1.0 / 3.0),
        DVec3::new(0.1, -2.0 / 7.0, 1e-300),
        DVec3::new(1e20, f64::MIN_POSITIVE, 5e-324),
        DVec3::new(123_456_789.123_456_79, -1e-7, std::f64::consts::PI),
        DVec3::new(-1.0e16, 9_999_999_999_999_998.0, 1e-5),
    ]
}

const OUT_TRIS: [[u32; 3]; 3] = [[0, 1, 2], [0, 2, 3], [3, 2, 4]];

fn same_bits(a: &[DVec3], b: &[DVec3]) {
    assert_eq!(a.len(), b.len());
    for (p, q) in a.iter().zip(b) {
        let bits = |v: &DVec3| v.to_array().map(f64::to_bits);
        assert_eq!(bits(p), bits(q), "{p:?} vs {q:?}");
    }
}

fn as_i64(t: &[[u32; 3]]) -> Vec<[i64; 3]> {
    t.iter().map(|t| t.map(i64::from)).collect()
}

#[test]
fn text_writers_round_trip_bit_exact() {
    let d = dir("round_trip");
    let points = awkward_points();
    for ext in ["obj", "off", "ply", "tri", "OBJ"] {
        let p = d.join(format!("m.{ext}"));
        write_mesh(&p, &points, &OUT_TRIS).unwrap();
        let m = read(&p).unwrap_or_else(|e| panic!("{ext}: {e}"));
        same_bits(&points, &m.points);
        assert_eq!(m.tris, as_i64(&OUT_TRIS), "{ext}");
    }
    let p = d.join("c.tri");
    write_tri_with_components(&p, &points, &OUT_TRIS, &[3, 1, 4]).unwrap();
    assert_eq!(read(&p).unwrap().components, Some(vec![3, 1, 4]));
    let err = write_tri_with_components(&p, &points, &OUT_TRIS, &[1]).unwrap_err();
    assert!(matches!(err, Error::InvalidArgument(_)));
}

#[test]
fn stl_writer_round_trips_in_single_precision() {
    let d = dir("stl_round_trip");
    let points = vec![
        DVec3::new(0.0, 0.0, 1.0 / 3.0),
        DVec3::new(0.1, -2.0 / 7.0, 1e-3),
        DVec3::new(1e20, 1.5, 2.5),
        DVec3::new(123_456_789.123_456_79, -1e-7, std::f64::consts::PI),
        DVec3::new(-7.0, 8.0, 9.0),
    ];
    let p = d.join("m.stl");
    write_mesh(&p, &points, &OUT_TRIS).unwrap();
    let m = read(&p).unwrap();
    let rounded: Vec<DVec3> = points.iter().map(|p| p.as_vec3().as_dvec3()).collect();
    same_bits(&rounded, &m.points);
    assert_eq!(m.tris, as_i64(&OUT_TRIS));
    assert_eq!(m.welded, 4);
}

#[test]
fn vtu_writer() {
    let d = dir("vtu");
    let points = awkward_points();
    let p = d.join("m.vtu");
    let k: Vec<f64> = (0..5).map(f64::from).collect();
    let n = vec![DVec3::Z; 5];
    let ids = [1, 2, 3];
    write_vtu(
        &p,
        &points,
        &OUT_TRIS,
        &[
            ("curvature", DataArray::F64(&k)),
            ("normal <n>", DataArray::Vec3(&n)),
        ],
        &[("component", DataArray::I32(&ids))],
        false,
    )
    .unwrap();
    let text = std::fs::read_to_string(&p).unwrap();
    for needle in [
        "type=\"UnstructuredGrid\"",
        "NumberOfPoints=\"5\" NumberOfCells=\"3\"",
        "type=\"Int64\" Name=\"connectivity\"",
        "type=\"Int64\" Name=\"offsets\"",
        "type=\"UInt8\" Name=\"types\"",
        "Name=\"normal &lt;n&gt;\" NumberOfComponents=\"3\"",
        "type=\"Int32\" Name=\"component\"",
        "          9\n",
        "          5\n",
    ] {
        assert!(text.contains(needle), "missing {needle:?}");
    }
    let opens = text.matches("<DataArray").count();
    assert_eq!(opens, text.matches("</DataArray>").count());
    assert_eq!(opens, 7);
    // Without data arrays: points, connectivity, offsets and types read back
    // (bit for bit: the numbers are written shortest round-trip).
    write_mesh(&d.join("plain.vtu"), &points, &OUT_TRIS).unwrap();
    let plain = std::fs::read_to_string(d.join("plain.vtu")).unwrap();
    assert!(plain.contains("NumberOfPoints=\"5\" NumberOfCells=\"3\""));
    assert_eq!(plain.matches("<DataArray").count(), 4);
    let array = |name: &str| -> Vec<String> {
        let start = plain
            .find(&format!("Name=\"{name}\""))
            .unwrap_or_else(|| panic!("{name}"));
        let body = &plain[start..];
        let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
        body.split_whitespace().map(str::to_string).collect()
    };
    let xyz: Vec<f64> = array("Points").iter().map(|x| x.parse().unwrap()).collect();
    let read_back: Vec<DVec3> = xyz
        .chunks(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]))
        .collect();
    same_bits(&points, &read_back);
    let connectivity: Vec<i64> = array("connectivity")
        .iter()
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(connectivity, as_i64(&OUT_TRIS).concat());
    assert_eq!(array("offsets"), ["3", "6", "9"]);
    assert_eq!(array("types"), ["5", "5", "5"]);

    let short = [1.0];
    let err = write_vtu(
        &p,
        &points,
        &OUT_TRIS,
        &[("k", DataArray::F64(&short))],
        &[],
        false,
    )
    .unwrap_err();
    assert!(matches!(err, Error::InvalidArgument(_)), "{err}");
    let err = write_vtu(
        &p,
        &points,
        &OUT_TRIS,
        &[],
        &[("c", DataArray::I32(&[1]))],
        false,
    )
    .unwrap_err();
    assert!(matches!(err, Error::InvalidArgument(_)), "{err}");
    let nan = [0.0, 1.0, f64::NAN, 0.0, 0.0];
    let err = write_vtu(
        &p,
        &points,
        &OUT_TRIS,
        &[("k", DataArray::F64(&nan))],
        &[],
        false,
    )
    .unwrap_err();
    assert!(matches!(err, Error::InvalidArgument(_)), "{err}");
}

#[test]
fn writers_reject_bad_indices() {
    let d = dir("writer_bad");
    for ext in ["obj", "off", "ply", "stl", "tri", "vtu"] {
        let err =
            write_mesh(&d.join(format!("m.{ext}")), &[DVec3::ZERO; 2], &[[0, 1, 2]]).unwrap_err();
        assert!(matches!(err, Error::InvalidArgument(_)), "{ext}: {err}");
    }
}

// ---------------------------------------------------------------- dispatch

#[test]
fn unknown_extension_and_missing_file() {
    let d = dir("dispatch");
    let p = put(&d, "mesh.xyz", "1 2 3\n");
    let err = read(&p).unwrap_err();
    assert!(matches!(err, Error::UnknownFormat { .. }));
    names_file(&err, &p);
    let p = put(&d, "noext", "OFF\n");
    assert!(matches!(read(&p).unwrap_err(), Error::UnknownFormat { .. }));
    let err = write_mesh(&d.join("out.xyz"), &[], &[]).unwrap_err();
    assert!(matches!(err, Error::UnknownFormat { .. }));

    let p = d.join("missing.off");
    let err = read(&p).unwrap_err();
    assert!(matches!(err, Error::Io { .. }), "{err}");
    names_file(&err, &p);
    let err = write_mesh(&d.join("no/such/dir.off"), &[], &[]).unwrap_err();
    assert!(matches!(err, Error::Io { .. }), "{err}");
}

// ---------------------------------------------------------------- real meshes

#[test]
fn cgal_demo_meshes() {
    let Some(dir) = cgal_data::cgal_dir() else {
        return;
    };
    for (name, nv, nt) in [
        ("pig.off", 468, 891),
        ("cow.off", 2904, 5804),
        ("fandisk.off", 6475, 12946),
        ("bunny00.off", 37706, 75408),
        ("sphere.ply", 162, 320),
        ("colored_tetra.ply", 4, 4),
    ] {
        let m = read(&dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((m.points.len(), m.tris.len()), (nv, nt), "{name}");
        assert_eq!(m.vertex_lines.len(), nv);
    }
    // pig.stl is a finer binary pig (header of spaces) with 16848 triangles.
    let m = read(&dir.join("pig.stl")).unwrap();
    assert_eq!(m.tris.len(), 16848);
    assert_eq!(m.welded, 3 * m.tris.len() - m.points.len());
    assert!(
        m.points.len() < m.tris.len(),
        "welding found shared corners"
    );
}
