//! The explicit repairs of dirty files (docs/repairs.md): each fixes what it names,
//! reports it, and leaves a net the evaluator takes; without it the file is
//! refused with a message naming the option.

mod common;

use loopsurf::io::{write_off, write_stl};
use loopsurf::repair::{ReadOptions, Repair, Repairs};
use loopsurf::{examples, ControlNet, DVec3, Error, Surface};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("loopsurf-repair-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn with(repairs: Repairs) -> ReadOptions {
    ReadOptions {
        repairs,
        ..ReadOptions::default()
    }
}

/// Writes an ASCII STL whose every corner is moved by up to `jitter`, so
/// no two copies of a vertex are exactly equal.
fn jittered_stl(points: &[DVec3], tris: &[[u32; 3]], jitter: f64) -> PathBuf {
    let mut rng = common::Lcg(7);
    let mut s = String::from("solid jittered\n");
    for t in tris {
        s += "facet normal 0 0 0\nouter loop\n";
        for &i in t {
            let p = points[i as usize] + jitter * rng.direction();
            s += &format!("vertex {:e} {:e} {:e}\n", p.x, p.y, p.z);
        }
        s += "endloop\nendfacet\n";
    }
    s += "endsolid jittered\n";
    let path = scratch("jittered.stl");
    std::fs::write(&path, s).unwrap();
    path
}

#[test]
fn weld_closes_an_stl_whose_corners_carry_round_off() {
    let ex = examples::by_name("sphere").unwrap();
    // STL holds single precision: 1e-6 survives it.
    let path = jittered_stl(&ex.points, &ex.tris, 1e-6);
    // Plain: every triangle stands alone, the surface is a heap of open
    // patches.
    let soup = ControlNet::read(&path).unwrap();
    assert_eq!(soup.points().len(), 3 * ex.tris.len());
    let weld = Repairs {
        weld: Some(1e-5),
        ..Repairs::default()
    };
    let net = ControlNet::read_with(&path, &with(weld)).unwrap();
    assert_eq!(net.triangles().len(), ex.tris.len());
    let referenced = (0..net.points().len())
        .filter(|&v| !net.topology().is_unreferenced(v))
        .count();
    assert_eq!(referenced, ex.points.len());
    assert_eq!(net.topology().boundary_loops().len(), 0, "closed again");
    assert!(matches!(
        net.repairs(),
        [Repair::Welded { merged, .. }] if *merged == 3 * ex.tris.len() - ex.points.len()
    ));
    // The limit surface is the exact sphere's to the jitter's order.
    let exact =
        Surface::new(&ControlNet::from_arrays(ex.points.clone(), &ex.tris).unwrap()).unwrap();
    let welded = Surface::new(&net).unwrap();
    for t in 0..ex.tris.len() {
        let d = exact.point(t, 0.2, 0.3).unwrap() - welded.point(t, 0.2, 0.3).unwrap();
        assert!(d.length() < 3e-6, "triangle {t}: {d}");
    }
}

#[test]
fn orient_restores_a_shuffled_mesh() {
    let Some(pig) = common::cgal_mesh("pig.off") else {
        return;
    };
    let net = ControlNet::read(&pig).unwrap();
    let mut tris = net.triangles().to_vec();
    let turned: Vec<usize> = (0..tris.len()).filter(|t| t % 3 == 1).collect();
    for &t in &turned {
        tris[t].swap(1, 2);
    }
    let path = scratch("pig-shuffled.off");
    write_off(&path, net.points(), &tris).unwrap();
    let err = ControlNet::read(&path).unwrap_err();
    assert!(
        matches!(err.root(), Error::InconsistentOrientation { .. }),
        "{err}"
    );
    assert!(err.to_string().contains("--orient"), "{err}");

    let orient = Repairs {
        orient: true,
        ..Repairs::default()
    };
    let fixed = ControlNet::read_with(&path, &with(orient)).unwrap();
    // pig.off has holes: the majority's orientation is kept.
    let closed = net.topology().boundary_loops().is_empty();
    assert_eq!(fixed.triangles(), net.triangles());
    assert_eq!(
        fixed.repairs(),
        [Repair::Reoriented {
            first_triangle: 0,
            triangles: tris.len(),
            flipped: turned.len(),
            outward: closed
        }]
    );
}

#[test]
fn orient_refuses_a_moebius_band_naming_a_triangle_and_its_line() {
    // The five-vertex Möbius band: triangles (i, i+1, i+2) mod 5.
    let mut s = String::from("OFF\n5 5 0\n");
    for i in 0..5 {
        let a = i as f64 * std::f64::consts::TAU / 5.0;
        s += &format!("{} {} {}\n", a.cos(), a.sin(), (i % 2) as f64 * 0.3);
    }
    for i in 0..5 {
        s += &format!("3 {} {} {}\n", i, (i + 1) % 5, (i + 2) % 5);
    }
    let path = scratch("moebius.off");
    std::fs::write(&path, s).unwrap();
    let orient = Repairs {
        orient: true,
        ..Repairs::default()
    };
    let err = ControlNet::read_with(&path, &with(orient)).unwrap_err();
    let Error::NonOrientable { tri, .. } = err.root() else {
        panic!("{err}");
    };
    // Triangle t is on line 8 + t of the file.
    let line = format!("moebius.off:{}:", 8 + tri);
    assert!(err.to_string().contains(&line), "{err}");
}

#[test]
fn split_nonmanifold_separates_two_tetrahedra_touching_at_a_tip() {
    let tetra = examples::by_name("tetra").unwrap();
    // The second tetrahedron is the first mirrored through its vertex 0.
    let tip = tetra.points[0];
    let mut points = tetra.points.clone();
    points.extend(tetra.points[1..].iter().map(|&p| 2.0 * tip - p));
    let remap = |i: u32| if i == 0 { 0 } else { i + 3 };
    let mut tris = tetra.tris.clone();
    // Mirroring turns orientation; swap two corners to keep it outward.
    tris.extend(
        tetra
            .tris
            .iter()
            .map(|t| [remap(t[0]), remap(t[2]), remap(t[1])]),
    );
    let path = scratch("bowtie.stl");
    write_stl(&path, &points, &tris).unwrap();
    let err = ControlNet::read(&path).unwrap_err();
    assert!(
        matches!(err.root(), Error::NonManifoldVertex { .. }),
        "{err}"
    );
    assert!(err.to_string().contains("--split-nonmanifold"), "{err}");

    let split = Repairs {
        split_nonmanifold: true,
        ..Repairs::default()
    };
    let net = ControlNet::read_with(&path, &with(split)).unwrap();
    let [Repair::SplitVertices { splits }] = net.repairs() else {
        panic!("{:?}", net.repairs());
    };
    assert_eq!(splits.len(), 1);
    let (v, copies) = &splits[0];
    assert_eq!(copies.len(), 1);
    assert_eq!(net.points()[copies[0] as usize], net.points()[*v as usize]);
    // Two closed pieces: each vertex is a regular tetrahedron's again, and
    // the limit surface is a pair of blobs meeting at no point.
    let surface = Surface::new(&net).unwrap();
    let c = surface.point(0, 1.0 / 3.0, 1.0 / 3.0).unwrap();
    assert!(c.is_finite());
    let limits = net.limit_points();
    assert!(limits[*v as usize].distance(limits[copies[0] as usize]) > 0.1);
}

#[test]
fn degenerate_triangles_are_kept_on_request_and_never_tagged_by_angle() {
    // A flat square fanned around its centre, with a sliver of zero area
    // (to round-off) on one side whose computed normal leans 45°.
    let body = "OFF\n6 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 0\n0.5 1e-15 1e-15\n\
                3 0 5 4\n3 5 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n3 0 1 5\n";
    let path = scratch("sliver.off");
    std::fs::write(&path, body).unwrap();
    let err = ControlNet::read(&path).unwrap_err();
    assert!(
        matches!(err.root(), Error::ZeroArea { tri: 5, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("sliver.off:14:"), "{err}");
    assert!(err.to_string().contains("--allow-degenerate"), "{err}");

    let keep = Repairs {
        allow_degenerate: true,
        ..Repairs::default()
    };
    let mut net = ControlNet::read_with(&path, &with(keep)).unwrap();
    assert_eq!(
        net.repairs(),
        [Repair::KeptDegenerate { triangles: vec![5] }]
    );
    // Every other edge is flat; the sliver's edges have no angle.
    assert_eq!(net.tag_by_angle(1.0).unwrap(), 0);
    let surface = Surface::new(&net).unwrap();
    for t in 0..net.triangles().len() {
        let n = surface.normal(t, 0.3, 0.3).unwrap();
        assert!((n.z.abs() - 1.0).abs() < 1e-6, "triangle {t}: {n}");
    }
}
