use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::DVec3;

use super::*;
use crate::error::Error;
use crate::io::lagrange::LagrangeMesh;
use crate::io::nodes_per_triangle;

/// A scratch file name unique to this process and test (tests remove
/// their files).
pub(crate) fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("loopsurf-io-{}-{name}", std::process::id()))
}

/// The node layouts gmsh documents for its Lagrange triangles
/// (reference manual, "Node ordering", the Triangle6 / Triangle10 /
/// Triangle15 pictures): node m of the order-k triangle sits at
/// (u, v) = (i/k, j/k). Vertices, then edges 0→1, 1→2, 2→0 each from
/// its first vertex, then the interior numbered like a triangle.
pub(crate) fn documented_lattice(k: usize) -> &'static [(usize, usize)] {
    match k {
        1 => &[(0, 0), (1, 0), (0, 1)],
        2 => &[(0, 0), (2, 0), (0, 2), (1, 0), (1, 1), (0, 1)],
        3 => &[
            (0, 0),
            (3, 0),
            (0, 3),
            (1, 0),
            (2, 0),
            (2, 1),
            (1, 2),
            (0, 2),
            (0, 1),
            (1, 1),
        ],
        4 => &[
            (0, 0),
            (4, 0),
            (0, 4),
            (1, 0),
            (2, 0),
            (3, 0),
            (3, 1),
            (2, 2),
            (1, 3),
            (0, 3),
            (0, 2),
            (0, 1),
            (1, 1),
            (2, 1),
            (1, 2),
        ],
        _ => unreachable!(),
    }
}

/// An order-k mesh of the unit square cut into 2 × 2 squares and 8
/// triangles, slightly curved, with edge nodes shared, two faces (ids
/// 0 and 3), lines on two sides (curves 2 and 0), three corners listed
/// out of node order, awkward doubles (−0.0, a subnormal, thirds) and
/// an unused node at the end.
pub(crate) fn fixture(k: usize) -> LagrangeMesh {
    let mut mesh = LagrangeMesh {
        order: k,
        ..Default::default()
    };
    let n = 2 * k as i64; // lattice points per side − 1
    let mut index: HashMap<(i64, i64), u32> = HashMap::new();
    let mut node = |mesh: &mut LagrangeMesh, p: (i64, i64)| -> u32 {
        *index.entry(p).or_insert_with(|| {
            let (x, y) = (p.0 as f64 / n as f64, p.1 as f64 / n as f64);
            let z = if p == (0, 0) {
                -0.0
            } else if p == (n, n) {
                1e-310
            } else {
                (3.0 * x * y).sin() / 3.0
            };
            mesh.nodes.push(DVec3::new(x, y, z));
            let i = mesh.nodes.len() as u32 - 1;
            mesh.params.push((i % 5, x / 3.0, y * std::f64::consts::PI));
            i
        })
    };
    let lattice = documented_lattice(k);
    for sx in 0..2 {
        for sy in 0..2 {
            let o = (sx * k as i64, sy * k as i64);
            let kk = k as i64;
            let corners = [[(0, 0), (kk, 0), (kk, kk)], [(0, 0), (kk, kk), (0, kk)]];
            for c in corners {
                let [a, b, d] = c.map(|(x, y)| (o.0 + x, o.1 + y));
                for &(i, j) in lattice {
                    let (i, j) = (i as i64, j as i64);
                    // a + (b − a) i/k + (d − a) j/k on the integer lattice.
                    let p = (
                        a.0 + ((b.0 - a.0) * i + (d.0 - a.0) * j) / kk,
                        a.1 + ((b.1 - a.1) * i + (d.1 - a.1) * j) / kk,
                    );
                    let id = node(&mut mesh, p);
                    mesh.triangles.push(id);
                }
                mesh.faces.push(if sx == 0 { 0 } else { 3 });
            }
        }
    }
    // Bottom side (curve 2) and left side (curve 0), ends first.
    for (curve, from, step) in [(2, (0, 0), (1, 0)), (0, (0, 2 * k as i64), (0, -1))] {
        for s in 0..2i64 {
            let at = |m: i64| {
                let t = s * k as i64 + m;
                (from.0 + step.0 * t, from.1 + step.1 * t)
            };
            let mut ids = vec![node(&mut mesh, at(0)), node(&mut mesh, at(k as i64))];
            ids.extend((1..k as i64).map(|m| node(&mut mesh, at(m))));
            mesh.lines.extend(ids);
            mesh.line_curves.push(curve);
        }
    }
    for (p, id) in [((n, 0), 0), ((0, 0), 1), ((0, n), 2)] {
        let i = node(&mut mesh, p);
        mesh.corners.push((i, id));
    }
    mesh.nodes.push(DVec3::new(2.0, 1.0 / 3.0, -1e300));
    mesh.params.push((7, 0.25, 0.5));
    mesh.validate().unwrap();
    mesh
}

/// Same mesh, and every double the same bits.
pub(crate) fn assert_identical(a: &LagrangeMesh, b: &LagrangeMesh) {
    assert_eq!(a, b);
    for (p, q) in a.nodes.iter().zip(&b.nodes) {
        assert_eq!(
            p.to_array().map(f64::to_bits),
            q.to_array().map(f64::to_bits)
        );
    }
    for (p, q) in a.params.iter().zip(&b.params) {
        assert_eq!(
            (p.1.to_bits(), p.2.to_bits()),
            (q.1.to_bits(), q.2.to_bits())
        );
    }
}

#[test]
fn round_trip_every_order_ascii_and_binary() {
    for k in 1..=4 {
        let mesh = fixture(k);
        for binary in [false, true] {
            let path = scratch(&format!("rt{k}{binary}.msh"));
            write_msh(&path, &mesh, binary).unwrap();
            let read = read_msh(&path).unwrap();
            assert_eq!((read.version.as_str(), read.binary), ("4.1", binary));
            let tags: Vec<u64> = (1..=mesh.nodes.len() as u64).collect();
            assert_eq!(read.node_tags, tags);
            assert_eq!(read.triangles.len(), 8);
            assert!(read.triangles.iter().all(|e| e.order == k));
            assert_eq!(read.lines.len(), 4);
            assert_eq!(read.points.len(), 3);
            assert_eq!(read.skipped_elements, 0);
            assert_eq!(read.triangles[0].line.is_some(), !binary);
            // Physical groups and names as documented.
            let mut names: Vec<_> = read
                .physical_names
                .iter()
                .map(|p| (p.dim, p.tag, p.name.as_str()))
                .collect();
            names.sort();
            assert_eq!(
                names,
                [
                    (0, 1, "corner_0"),
                    (0, 2, "corner_1"),
                    (0, 3, "corner_2"),
                    (1, 1, "curve_0"),
                    (1, 3, "curve_2"),
                    (2, 1, "face_0"),
                    (2, 4, "face_3"),
                ]
            );
            assert!(read
                .triangles
                .iter()
                .all(|e| e.physical == e.entity && [1, 4].contains(&e.physical)));
            assert_eq!(read.node_data.len(), 1);
            assert_eq!(read.node_data[0].name, PARAMS_VIEW);
            assert_identical(&read.to_lagrange().unwrap(), &mesh);
            std::fs::remove_file(&path).unwrap();
        }
    }
}

/// A piece's tags: nodes by the tags given, elements from an offset,
/// corner points named by their node's tag; it reads back as the same
/// mesh, in ASCII and binary. Tags that are 0, repeated, too many or too
/// large for a view are refused, and nothing is written.
#[test]
fn tagged_pieces_keep_their_tags() {
    let mesh = fixture(2);
    let n = mesh.nodes.len() as u64;
    // Gapped and increasing: the reader, which orders nodes by tag, gives
    // them back in the mesh's order.
    let nodes: Vec<u64> = (0..n).map(|i| 1_000_000 + 7 * i).collect();
    let tags = MshTags {
        nodes: Some(&nodes),
        first_element: 501,
    };
    for binary in [false, true] {
        let path = scratch(&format!("tagged{binary}.msh"));
        write_msh_tagged(&path, &mesh, binary, tags).unwrap();
        let read = read_msh(&path).unwrap();
        assert_eq!(read.node_tags, nodes);
        let mut elements: Vec<u64> = (read.points.iter())
            .chain(&read.lines)
            .chain(&read.triangles)
            .map(|e| e.tag)
            .collect();
        elements.sort_unstable();
        assert_eq!(elements, (501..501 + 3 + 4 + 8).collect::<Vec<u64>>());
        for e in &read.points {
            assert_eq!(e.entity as u64, nodes[e.nodes[0] as usize]);
        }
        assert_identical(&read.to_lagrange().unwrap(), &mesh);
        std::fs::remove_file(&path).unwrap();
    }
    // Decreasing: every tag still names its node.
    let reversed: Vec<u64> = nodes.iter().rev().copied().collect();
    let path = scratch("tagged-reversed.msh");
    let tags = MshTags {
        nodes: Some(&reversed),
        first_element: 1,
    };
    write_msh_tagged(&path, &mesh, false, tags).unwrap();
    let read = read_msh(&path).unwrap();
    for (tag, p) in read.node_tags.iter().zip(&read.nodes) {
        let i = reversed.iter().position(|t| t == tag).unwrap();
        assert_eq!(*p, mesh.nodes[i]);
    }
    std::fs::remove_file(&path).unwrap();
    let refused = |nodes: &[u64], first_element: u64, what: &str| {
        let path = scratch("refused.msh");
        let tags = MshTags {
            nodes: Some(nodes),
            first_element,
        };
        let err = write_msh_tagged(&path, &mesh, false, tags).unwrap_err();
        assert!(err.to_string().contains(what), "{err}");
        assert!(!path.exists());
    };
    let mut twice = nodes.clone();
    twice[5] = twice[2];
    refused(&twice, 1, "nodes 2 and 5 have the same tag");
    let mut zero = nodes.clone();
    zero[3] = 0;
    refused(&zero, 1, "node 3's tag is 0");
    let mut wide = nodes.clone();
    wide[4] = 1 << 40;
    refused(&wide, 1, "32-bit");
    refused(&nodes[1..], 1, "tags for");
    refused(&nodes, 0, "first element tag is 0");
    refused(&nodes, u64::MAX - 3, "pass the largest tag");
}

/// Without params there is no view; a mesh with nothing but nodes
/// still makes a file gmsh's format allows.
#[test]
fn round_trip_without_params_and_elements() {
    let mut mesh = fixture(2);
    mesh.params.clear();
    let only_nodes = LagrangeMesh {
        order: 1,
        nodes: vec![DVec3::X, DVec3::Y],
        ..Default::default()
    };
    for (m, name) in [(&mesh, "noparams"), (&only_nodes, "onlynodes")] {
        for binary in [false, true] {
            let path = scratch(&format!("{name}{binary}.msh"));
            write_msh(&path, m, binary).unwrap();
            let read = read_msh(&path).unwrap();
            assert!(read.node_data.is_empty());
            assert_identical(&read.to_lagrange().unwrap(), m);
            std::fs::remove_file(&path).unwrap();
        }
    }
    let mut bad = mesh.clone();
    bad.order = 3;
    let err = write_msh(&scratch("bad.msh"), &bad, false).unwrap_err();
    assert!(err.to_string().contains("order 3 needs 10"), "{err}");
}

/// The written P1–P4 elements of the straight reference triangle put
/// node m where gmsh's manual draws it (see [`documented_lattice`]),
/// e.g. P3: node 3 at (1/3, 0), 5 at (2/3, 1/3), 9 at (1/3, 1/3).
#[test]
fn reference_triangle_node_layout() {
    let documented_p3 = [
        (0.0, 0.0),
        (1.0, 0.0),
        (0.0, 1.0),
        (1.0 / 3.0, 0.0),
        (2.0 / 3.0, 0.0),
        (2.0 / 3.0, 1.0 / 3.0),
        (1.0 / 3.0, 2.0 / 3.0),
        (0.0, 2.0 / 3.0),
        (0.0, 1.0 / 3.0),
        (1.0 / 3.0, 1.0 / 3.0),
    ];
    for (m, &(i, j)) in documented_lattice(3).iter().enumerate() {
        assert_eq!((i as f64 / 3.0, j as f64 / 3.0), documented_p3[m]);
    }
    for k in 1..=4 {
        let lattice = documented_lattice(k);
        assert_eq!(lattice.len(), nodes_per_triangle(k));
        // Nodes stored in reverse, so the element's indices are not
        // simply 0, 1, 2, ...
        let npt = lattice.len();
        let mesh = LagrangeMesh {
            order: k,
            nodes: lattice
                .iter()
                .rev()
                .map(|&(i, j)| DVec3::new(i as f64 / k as f64, j as f64 / k as f64, 0.0))
                .collect(),
            triangles: (0..npt as u32).rev().collect(),
            faces: vec![0],
            ..Default::default()
        };
        for binary in [false, true] {
            let path = scratch(&format!("ref{k}{binary}.msh"));
            write_msh(&path, &mesh, binary).unwrap();
            let read = read_msh(&path).unwrap();
            let tri = &read.triangles[0];
            assert_eq!(tri.order, k);
            for (m, &(i, j)) in lattice.iter().enumerate() {
                let p = read.nodes[tri.nodes[m] as usize];
                assert_eq!((p.x, p.y), (i as f64 / k as f64, j as f64 / k as f64));
            }
        }
        // The ASCII element line itself: type, then tag and node tags.
        let text = std::fs::read_to_string(scratch(&format!("ref{k}false.msh"))).unwrap();
        let ty = TRIANGLE_TYPES[k - 1];
        assert!(text.contains(&format!("\n2 1 {ty} 1\n1 ")), "{text}");
        for binary in [false, true] {
            std::fs::remove_file(scratch(&format!("ref{k}{binary}.msh"))).unwrap();
        }
    }
}

/// What gmsh 4.15 writes for a P2 triangle with a physical curve and
/// point, with a `$Periodic` and an `$ElementData` section added.
const GMSH_41: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 4 "bottom"
2 7 "skin"
$EndPhysicalNames
$Entities
3 3 1 0
1 0 0 0 0 
2 1 0 0 1 9 
3 0 1 0 0 
1 0 0 0 1 0 0 1 4 2 1 -2 
2 0 0 0 1 1 0 0 2 2 -3 
3 0 0 0 0 1 0 0 2 3 -1 
1 0 0 0 1 1 0 1 7 3 1 2 3 
$EndEntities
$Nodes
7 6 1 6
0 1 0 1
1
0 0 0
0 2 0 1
2
1 0 0
0 3 0 1
3
0 1 0
1 1 0 1
4
0.4999999999986718 0 0
1 2 0 1
5
0.5000000000013293 0.4999999999986707 0
1 3 0 1
6
0 0.5000000000013304 0
2 1 0 0
$EndNodes
$Elements
4 4 1 4
0 2 15 1
1 2 
1 1 8 1
2 1 2 4 
2 1 9 1
3 1 2 3 4 5 6 
2 1 3 1
4 1 2 5 6
$EndElements
$Periodic
1
1 3 1
16 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1
1
3 1
$EndPeriodic
$ElementData
1
"quality"
1
0
3
0
1
1
3 0.5
$EndElementData
"#;

#[test]
fn reads_what_gmsh_writes_41() {
    let path = Path::new("gmsh41.msh");
    let m = parse_msh(GMSH_41.as_bytes(), path).unwrap();
    assert_eq!(m.version, "4.1");
    assert_eq!(m.nodes.len(), 6);
    assert_eq!(m.nodes[3], DVec3::new(0.4999999999986718, 0.0, 0.0));
    assert_eq!(m.skipped_elements, 1); // the quad
    assert_eq!(m.triangles.len(), 1);
    let t = &m.triangles[0];
    assert_eq!((t.tag, t.order, t.physical, t.entity), (3, 2, 7, 1));
    assert_eq!(t.nodes, [0, 1, 2, 3, 4, 5]);
    assert_eq!(t.line, Some(48));
    let l = &m.lines[0];
    assert_eq!(
        (l.order, l.physical, l.nodes.as_slice()),
        (2, 4, &[0, 1, 3][..])
    );
    assert_eq!((m.points[0].physical, m.points[0].nodes[0]), (9, 1));
    assert_eq!(m.physical_names[1].name, "skin");
    let lag = m.to_lagrange().unwrap();
    assert_eq!((lag.order, lag.faces.as_slice()), (2, &[6][..]));
    assert_eq!(lag.line_curves, [3]);
    assert_eq!(lag.corners, [(1, 8)]);
    assert!(lag.params.is_empty());
}

/// The same mesh as gmsh 4.15 writes it in MSH 2.2, with a `$Periodic`
/// section, a quad, node tags out of order and a view.
const GMSH_22: &str = r#"$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 4 "bottom"
2 7 "skin"
$EndPhysicalNames
$Nodes
6
1 0 0 0
2 1 0 0
3 0 1 0
5 0.5000000000013293 0.4999999999986707 0
4 0.4999999999986718 0 0
60 0 0.5000000000013304 0
$EndNodes
$Periodic
1
1 3 1
1
3 1
$EndPeriodic
$Elements
4
1 15 2 9 2 2
2 8 2 4 1 1 2 4
3 9 2 7 1 1 2 3 4 5 60
4 3 2 0 1 1 2 5 60
$EndElements
$NodeData
1
"loopsurf_params"
1
0.0
3
0
3
6
1 0 0 0
2 0 1 0
3 0 0 1
4 0 0.5 0
5 0 0.5 0.5
60 0 0 0.5
$EndNodeData
"#;

#[test]
fn reads_what_gmsh_writes_22() {
    let m = parse_msh(GMSH_22.as_bytes(), Path::new("gmsh22.msh")).unwrap();
    assert_eq!(m.version, "2.2");
    assert_eq!(m.node_tags, [1, 2, 3, 4, 5, 60]);
    assert_eq!(
        m.nodes[4],
        DVec3::new(0.5000000000013293, 0.4999999999986707, 0.0)
    );
    let t = &m.triangles[0];
    assert_eq!((t.order, t.physical, t.entity), (2, 7, 1));
    assert_eq!(t.nodes, [0, 1, 2, 3, 4, 5]);
    assert_eq!(m.skipped_elements, 1);
    let lag = m.to_lagrange().unwrap();
    assert_eq!(lag.corners, [(1, 8)]);
    assert_eq!(lag.params[4], (0, 0.5, 0.5));
    assert_eq!(lag.params[5], (0, 0.0, 0.5));
}

/// MSH 2.2 binary as the manual describes it: int node tags, element
/// blocks under (type, count, number of tags) headers.
#[test]
fn reads_binary_22() {
    let mut f = b"$MeshFormat\n2.2 1 8\n".to_vec();
    f.extend(1i32.to_le_bytes());
    f.extend(b"\n$EndMeshFormat\n$Nodes\n3\n");
    for (tag, p) in [
        (1i32, [0.0, 0.0, 0.0]),
        (2, [1.0, 0.0, 0.0]),
        (3, [0.0, 1.0, -0.0]),
    ] {
        f.extend(tag.to_le_bytes());
        for x in p {
            f.extend(f64::to_le_bytes(x));
        }
    }
    f.extend(b"\n$EndNodes\n$Elements\n2\n");
    // (type, count, number of tags), then per element its tag, tags
    // (physical, elementary) and nodes.
    for x in [15i32, 1, 2, 1, 5, 4, 1] {
        f.extend(x.to_le_bytes());
    }
    for x in [2i32, 1, 2, 2, 8, 6, 1, 3, 2] {
        f.extend(x.to_le_bytes());
    }
    f.extend(b"\n$EndElements\n");
    let m = parse_msh(&f, Path::new("b22.msh")).unwrap();
    assert!(m.binary);
    assert_eq!(m.nodes[2].z.to_bits(), (-0.0f64).to_bits());
    assert_eq!(m.points[0].physical, 5);
    let t = &m.triangles[0];
    assert_eq!(
        (t.tag, t.physical, t.entity, t.nodes.as_slice()),
        (2, 8, 6, &[0, 2, 1][..])
    );
}

fn err_of(data: &[u8]) -> String {
    parse_msh(data, Path::new("bad.msh"))
        .unwrap_err()
        .to_string()
}

#[test]
fn errors_name_line_or_byte() {
    let path = scratch("trunc.msh");
    truncated_files_fail_cleanly(&path);
    text_errors_name_their_line();
    binary_errors_name_their_byte(&path);
    std::fs::remove_file(&path).unwrap();
}

/// Truncated: every prefix of a good file (written to `path`) fails
/// cleanly or reads; half a file is an error naming the file, and the
/// line or byte.
fn truncated_files_fail_cleanly(path: &Path) {
    for binary in [false, true] {
        write_msh(path, &fixture(2), binary).unwrap();
        let data = std::fs::read(path).unwrap();
        for cut in 0..data.len() {
            let _ = parse_msh(&data[..cut], path);
        }
        let err = parse_msh(&data[..data.len() / 2], path).unwrap_err();
        assert!(matches!(err.root(), Error::Truncated { .. }), "{err}");
        let msg = err.to_string();
        assert!(msg.contains("trunc.msh"), "{msg}");
        if binary {
            assert!(msg.contains("at byte"), "{msg}");
        } else {
            assert!(msg.contains("trunc.msh:"), "{msg}");
        }
    }
}

/// Text files: a huge announced count, an undefined node, counts that
/// disagree with the blocks, bad numbers, repeated tags and files that
/// are no MSH 4.1, each named by its line.
fn text_errors_name_their_line() {
    let ascii = |body: &str| format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n{body}");

    // A huge announced count and a short file: a clear error at once.
    let huge = ascii("$Nodes\n1 999999999999999 1 999999999999999\n2 1 0 999999999999999\n1\n2\n");
    let msg = err_of(huge.as_bytes());
    assert!(msg.contains("bad.msh:8: truncated file: $Nodes"), "{msg}");
    assert!(msg.contains("999999999999999 nodes"), "{msg}");

    // An element naming a node no block defines.
    let undefined = ascii(
        "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n\
         $Elements\n1 1 1 1\n2 1 2 1\n17 1 2 99\n$EndElements\n",
    );
    let msg = err_of(undefined.as_bytes());
    assert!(msg.contains("bad.msh:17:"), "{msg}");
    assert!(msg.contains("element 17 refers to node tag 99"), "{msg}");

    // Counts that disagree with the blocks, bad numbers, repeated tags.
    let miscount = ascii("$Nodes\n1 4 1 3\n2 1 0 1\n1\n0 0 0\n$EndNodes\n");
    assert!(err_of(miscount.as_bytes()).contains("announces 4 nodes, the blocks hold 1"));
    let extra = ascii("$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0 0 7\n$EndNodes\n");
    assert!(err_of(extra.as_bytes()).contains("expected $EndNodes, found \"7\""));
    let word = ascii("$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 zero 0\n$EndNodes\n");
    let msg = err_of(word.as_bytes());
    assert!(
        msg.contains(":8:") && msg.contains("found \"zero\""),
        "{msg}"
    );
    let twice = ascii("$Nodes\n1 2 1 1\n2 1 0 2\n1\n1\n0 0 0\n0 0 0\n$EndNodes\n");
    let msg = err_of(twice.as_bytes());
    assert!(
        msg.contains("node tag 1 is defined twice (first at line 7)"),
        "{msg}"
    );
    assert!(err_of(b"solid x\n").contains("not a gmsh .msh file"));
    assert!(err_of(b"$MeshFormat\n4 0 8\n$EndMeshFormat\n").contains("re-save"));
    assert!(err_of(b"").contains("truncated"));
}

/// Binary files (written to `path`): a patched count and a patched node
/// tag, named by offset.
fn binary_errors_name_their_byte(path: &Path) {
    write_msh(path, &fixture(1), true).unwrap();
    let good = std::fs::read(path).unwrap();
    let nodes = good.windows(7).position(|w| w == b"$Nodes\n").unwrap() + 7;
    let mut data = good.clone();
    // The first block's node count (after 4 size_t and 3 ints).
    let at = nodes + 32 + 12;
    data[at..at + 8].copy_from_slice(&(u64::MAX / 4).to_le_bytes());
    let msg = parse_msh(&data, path).unwrap_err().to_string();
    assert!(msg.contains("the file ends at byte"), "{msg}");
    let elements = good.windows(10).position(|w| w == b"$Elements\n").unwrap() + 10;
    let mut data = good.clone();
    // The first element's node tag (after 4 size_t, 3 ints, a size_t
    // and the element tag).
    let at = elements + 32 + 12 + 8 + 8;
    data[at..at + 8].copy_from_slice(&12345u64.to_le_bytes());
    let msg = parse_msh(&data, path).unwrap_err().to_string();
    assert!(
        msg.contains(&format!(
            "byte {}: element 1 refers to node tag 12345",
            at - 8
        )),
        "{msg}"
    );
}

/// Damaged files (bytes flipped all over a good one) end in a result
/// or an error, never a panic.
#[test]
fn damaged_files_do_not_panic() {
    let path = scratch("damaged.msh");
    for binary in [false, true] {
        write_msh(&path, &fixture(3), binary).unwrap();
        let good = std::fs::read(&path).unwrap();
        let mut state = 0x9e3779b97f4a7c15u64;
        for _ in 0..300 {
            let mut data = good.clone();
            crate::io::damage(&mut data, &mut state, 4);
            if let Ok(m) = parse_msh(&data, &path) {
                let _ = m.to_lagrange();
            }
        }
    }
    std::fs::remove_file(&path).unwrap();
}
