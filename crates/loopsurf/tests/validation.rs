//! One test per kind of bad input: each gets its own error kind, a message
//! naming the file, line or element and the indices, and never a panic.

use loopsurf::{ControlNet, DVec3, Error};

#[path = "support/cgal_data.rs"]
mod cgal_data;
use std::path::PathBuf;

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("loopsurf-validation-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Reads an OFF file made of the given body, expecting an error; returns it
/// with its message, which must name the file.
fn off_error(name: &str, body: &str) -> (Error, String) {
    let path = write(name, body);
    let err = ControlNet::read(&path).expect_err("bad input must be rejected");
    let msg = err.to_string();
    assert!(msg.contains(name), "message '{msg}' does not name the file");
    (err, msg)
}

const SQUARE: &str = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

#[test]
fn empty_mesh() {
    let (err, _) = off_error("empty.off", "OFF\n0 0 0\n");
    assert!(matches!(err.root(), Error::EmptyMesh { .. }));
    let err = ControlNet::from_arrays(vec![DVec3::ZERO], &[]).unwrap_err();
    assert!(matches!(
        err,
        Error::EmptyMesh {
            nverts: 1,
            ntris: 0
        }
    ));
}

#[test]
fn index_out_of_range() {
    let (err, msg) = off_error("range.off", &format!("{SQUARE}3 0 1 2\n3 0 2 7\n"));
    assert!(matches!(
        err.root(),
        Error::IndexOutOfRange {
            tri: 1,
            index: 7,
            nverts: 4,
            ..
        }
    ));
    assert!(msg.contains(":8:"), "line of the triangle in '{msg}'");
    let (err, _) = off_error("negative.off", &format!("{SQUARE}3 0 1 2\n3 0 2 -1\n"));
    assert!(matches!(
        err.root(),
        Error::IndexOutOfRange { index: -1, .. }
    ));
}

#[test]
fn repeated_index() {
    let (err, msg) = off_error("repeat.off", &format!("{SQUARE}3 0 1 2\n3 0 2 2\n"));
    assert!(matches!(
        err.root(),
        Error::RepeatedIndex {
            tri: 1,
            verts: [0, 2, 2],
            index: 2
        }
    ));
    assert!(msg.contains("[0, 2, 2]"));
}

#[test]
fn zero_area() {
    let body = "OFF\n4 2 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n3 0 1 3\n3 0 1 2\n";
    let (err, msg) = off_error("flat.off", body);
    assert!(matches!(
        err.root(),
        Error::ZeroArea {
            tri: 1,
            verts: [0, 1, 2]
        }
    ));
    assert!(msg.contains(":8:"));
}

#[test]
fn non_finite_coordinate() {
    let body = "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n";
    let (err, msg) = off_error("nan.off", body);
    assert!(matches!(
        err.root(),
        Error::NonFiniteCoordinate { vertex: 1, .. }
    ));
    assert!(msg.contains(":4:"), "line of the vertex in '{msg}'");
    let err = ControlNet::from_arrays(
        vec![DVec3::ZERO, DVec3::new(f64::INFINITY, 0.0, 0.0), DVec3::Y],
        &[[0, 1, 2]],
    )
    .unwrap_err();
    assert!(matches!(err, Error::NonFiniteCoordinate { vertex: 1, .. }));
}

#[test]
fn non_manifold_edge() {
    let body = "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 1 0 4\n";
    let (err, msg) = off_error("fin.off", body);
    match err.root() {
        Error::NonManifoldEdge { a: 0, b: 1, tris } => assert_eq!(tris.len(), 3),
        other => panic!("wrong kind: {other:?}"),
    }
    assert!(msg.contains("(0, 1)"));
    assert!(msg.contains("fin.off:10:"), "{msg}");
}

#[test]
fn non_manifold_vertex() {
    // Two triangles touching only at vertex 0 (a bow tie).
    let body = "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n-1 0 0\n-1 -1 0\n3 0 1 2\n3 0 3 4\n";
    let (err, _) = off_error("bowtie.off", body);
    assert!(matches!(
        err.root(),
        Error::NonManifoldVertex {
            vertex: 0,
            ntris: 2,
            fans: 2
        }
    ));
}

#[test]
fn inconsistent_orientation() {
    let (err, msg) = off_error("flip.off", &format!("{SQUARE}3 0 1 2\n3 0 3 2\n"));
    assert!(matches!(
        err.root(),
        Error::InconsistentOrientation { tris: [0, 1], .. }
    ));
    assert!(msg.contains("0 -> 2") || msg.contains("2 -> 0"), "{msg}");
    assert!(msg.contains("flip.off:8:"), "{msg}");
}

#[test]
fn truncated_file() {
    let (err, _) = off_error("short.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n");
    assert!(matches!(err.root(), Error::Truncated { .. }));
    let (err, _) = off_error("short_faces.off", &format!("{SQUARE}3 0 1 2\n"));
    assert!(matches!(err.root(), Error::Truncated { .. }));
}

#[test]
fn malformed_file() {
    let (err, msg) = off_error(
        "garbage.off",
        "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n",
    );
    assert!(matches!(err.root(), Error::Malformed { line: 4, .. }));
    assert!(msg.contains(":4") || msg.contains("line 4"), "{msg}");
}

#[test]
fn polygon_needs_triangulate() {
    let quad = SQUARE.replace("4 2 0", "4 1 0") + "4 0 1 2 3\n";
    let (err, msg) = off_error("quad.off", &quad);
    assert!(matches!(
        err.root(),
        Error::Polygon {
            face: 0,
            corners: 4
        }
    ));
    assert!(msg.contains(":7"), "{msg}");
    let path = write("quad_ok.off", &quad);
    let opts = loopsurf::repair::ReadOptions {
        triangulate: true,
        ..Default::default()
    };
    let net = ControlNet::read_with(&path, &opts).unwrap();
    assert_eq!(net.triangles(), &[[0, 1, 2], [0, 2, 3]]);
}

#[test]
fn unreferenced_vertices_are_kept() {
    let body = "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n9 9 9\n3 0 1 2\n3 0 2 3\n";
    let net = ControlNet::read(write("extra.off", body)).unwrap();
    assert_eq!(net.points().len(), 5);
    assert!(net.topology().is_unreferenced(4));
    assert_eq!(net.limit_points()[4], DVec3::splat(9.0));
}

#[test]
fn bad_feature_tags() {
    let mut net =
        ControlNet::read(write("tags.off", &format!("{SQUARE}3 0 1 2\n3 0 2 3\n"))).unwrap();
    assert!(matches!(net.tag_edge(1, 3), Err(Error::InvalidArgument(_))));
    assert!(matches!(
        net.tag_edge(0, 99),
        Err(Error::InvalidArgument(_))
    ));
    assert!(matches!(net.tag_vertex(4), Err(Error::InvalidArgument(_))));
    assert!(matches!(
        net.tag_by_angle(-1.0),
        Err(Error::InvalidArgument(_))
    ));
    assert!(matches!(
        net.tag_by_angle(f64::NAN),
        Err(Error::InvalidArgument(_))
    ));
    assert!(net.tag_edge(0, 2).unwrap());
    assert!(!net.tag_edge(2, 0).unwrap());
}

#[test]
fn cgal_pig_stl_is_non_manifold_after_welding() {
    // A real case: CGAL's pig.stl (binary, 16848 facets) welds into 8642
    // vertices, and vertex 90 then joins two separate fans of triangles.
    let Some(path) = cgal_data::cgal_file("pig.stl") else {
        return;
    };
    let err = ControlNet::read(&path).unwrap_err();
    assert!(
        matches!(
            err.root(),
            Error::NonManifoldVertex {
                vertex: 90,
                ntris: 5,
                fans: 2
            }
        ),
        "{err}"
    );
    let data = loopsurf::io::read_mesh(&path, &Default::default()).unwrap();
    assert_eq!((data.points.len(), data.tris.len()), (8642, 16848));
    assert_eq!(data.welded, 3 * 16848 - 8642);
}

#[test]
fn pillow_of_two_triangles() {
    let body = "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n";
    let (err, _) = off_error("pillow.off", body);
    assert!(
        matches!(err.root(), Error::InteriorValenceTwo { vertex: 0, .. }),
        "{err}"
    );
}
