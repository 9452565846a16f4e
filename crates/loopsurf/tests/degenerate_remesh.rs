//! Zero-area control triangles, as CAD exports write them, loaded with
//! the repairs of `--repair` and remeshed: no two output vertices on one
//! point, no sliver. A triangle that lists a vertex twice is dropped by
//! the weld (split-nonmanifold once gave its corners copies of their own:
//! a separate piece of zero area, two corners on one point, which the
//! remesher filled with triangles of 0°, edges of length 0). A copy of a
//! vertex splitting an edge (two zero-area triangles, kept) is harmless to
//! the surface and to its mesh.

mod common;

use loopsurf::io::write_off;
use loopsurf::repair::{ReadOptions, Repair, Repairs};
use loopsurf::{examples, ControlNet, DVec3, Error, Remesher, Surface, SurfaceMesh};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("loopsurf-degenerate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// `net` remeshed adapted (default tolerance) and at the size `h`: no two
/// vertices nearer than 1e-6 h, every edge at least a quarter of `h` at
/// the size, and no angle below 20°.
fn check_remeshes(name: &str, net: &ControlNet) {
    let surface = Surface::new(net).unwrap();
    let h = 0.02 * net.bbox_diagonal();
    let sized = Remesher::new(&surface).size(h).run().unwrap();
    let adapted = Remesher::new(&surface).adapt_curvature(true).run().unwrap();
    for (what, mesh, shortest) in [("size", &sized, 0.25 * h), ("adapted", &adapted, 1e-6 * h)] {
        let q = SurfaceMesh::quality(mesh);
        let closest = common::closest_vertices(&mesh.points);
        println!(
            "{name}, {what}: {} triangles, closest vertices {:.3e} h, shortest edge {:.3e} h, min {:.2}°",
            mesh.triangles.len(),
            closest / h,
            q.edge_lengths[0] / h,
            q.min_angle
        );
        assert!(
            closest >= 1e-6 * h,
            "{name}, {what}: vertices {closest:e} apart"
        );
        assert!(
            q.edge_lengths[0] >= shortest,
            "{name}, {what}: edge {:e}",
            q.edge_lengths[0]
        );
        assert!(
            q.min_angle >= 20.0,
            "{name}, {what}: min angle {}",
            q.min_angle
        );
    }
}

/// The octahedron with a ninth triangle that lists vertex 0 twice.
fn octahedron_with_a_repeated_vertex() -> PathBuf {
    let path = scratch("repeated-vertex.off");
    std::fs::write(
        &path,
        "OFF\n6 9 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n\
         3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n3 0 0 2\n",
    )
    .unwrap();
    path
}

#[test]
fn a_triangle_listing_a_vertex_twice_is_dropped_by_the_weld() {
    let path = octahedron_with_a_repeated_vertex();
    let net = ControlNet::read_with(&path, &ReadOptions::repair_all()).unwrap();
    assert_eq!(
        net.repairs(),
        [Repair::DroppedTriangles {
            collapsed: vec![8],
            duplicates: vec![]
        }]
    );
    assert_eq!(net.triangles().len(), 8);
    check_remeshes("octahedron, repeated vertex", &net);
    // Without the weld it is refused, naming the option that drops it.
    let keep = ReadOptions {
        repairs: Repairs {
            split_nonmanifold: true,
            allow_degenerate: true,
            ..Repairs::default()
        },
        ..ReadOptions::default()
    };
    let err = ControlNet::read_with(&path, &keep).unwrap_err();
    assert!(
        matches!(
            err.root(),
            Error::RepeatedIndex {
                tri: 8,
                index: 0,
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("--weld"), "{err}");
}

/// `points`, `tris` with edge `(a, b)` split by a copy of `a`'s position:
/// its two triangles become four, two of them of zero area.
fn split_by_a_copy(
    points: &[DVec3],
    tris: &[[u32; 3]],
    a: u32,
    b: u32,
) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut points = points.to_vec();
    let d = points.len() as u32;
    points.push(points[a as usize]);
    let mut out = Vec::new();
    for &t in tris {
        let k =
            (0..3).find(|&k| [t[k], t[(k + 1) % 3]] == [a, b] || [t[k], t[(k + 1) % 3]] == [b, a]);
        match k {
            None => out.push(t),
            Some(k) => {
                let (x, y, z) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                out.extend([[x, d, z], [d, y, z]]);
            }
        }
    }
    (points, out)
}

#[test]
fn a_vertex_repeated_inside_a_smooth_surface_remeshes_clean() {
    for name in ["sphere", "torus"] {
        let e = examples::by_name(name).unwrap();
        let [a, b, _] = e.tris[3];
        let (points, tris) = split_by_a_copy(&e.points, &e.tris, a, b);
        let path = scratch(&format!("{name}-repeated.off"));
        write_off(&path, &points, &tris).unwrap();
        let net = ControlNet::read_with(&path, &ReadOptions::repair_all()).unwrap();
        assert!(
            matches!(&net.repairs()[..], [Repair::KeptDegenerate { triangles }] if triangles.len() == 2),
            "{name}: {:?}",
            net.repairs()
        );
        check_remeshes(name, &net);
    }
}
