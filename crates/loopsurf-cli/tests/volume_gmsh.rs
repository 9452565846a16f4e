//! A real client of the main job: gmsh (from PyPI) tetrahedralizes the
//! volume that `loopsurf mesh`'s output bounds, adapted and at a uniform
//! size, for the closed peer cases (pig is open: it bounds no volume). A
//! surface mesh whose triangles cross each other is refused ("PLC Error:
//! A segment and a facet intersect"), as joint.off's adapted mesh was
//! before the remesher's last pass. anchor.off's surface crosses itself
//! at the inner corners of its L-shaped faces unless they are seamed
//! (`--concave-seams`), which it is here.

mod support;

#[path = "../../loopsurf/tests/support/cgal_data.rs"]
mod cgal_data;

use support::{loopsurf, scratch, text};

/// Meshes `input` (tagged at `angle`, with `extra` arguments) to STL and
/// has gmsh tetrahedralize it; returns gmsh's tetrahedron count.
fn tetrahedra(name: &str, angle: &str, extra: &[&str]) -> Option<usize> {
    let input = cgal_data::cgal_file(name)?;
    let stl = scratch(&format!("volume-{name}-{}.stl", extra.len()));
    let mut args = vec!["mesh", input.to_str().unwrap(), "-o", stl.to_str().unwrap()];
    if !angle.is_empty() {
        args.extend(["--hard-angle", angle]);
    }
    args.extend(extra);
    let out = loopsurf(&args);
    assert!(out.status.success(), "{name}: {}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("crossings: none"),
        "{name} {extra:?}: {}",
        text(&out.stdout)
    );
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scripts/gmsh_volume.py");
    let run = std::process::Command::new("python3")
        .args([script, stl.to_str().unwrap()])
        .output();
    let run = match run {
        Ok(run) if run.status.success() => run,
        Ok(run) if text(&run.stderr).contains("No module named 'gmsh'") => return gmsh_missing(),
        Ok(run) => panic!("gmsh refused {name} {extra:?}: {}", text(&run.stderr)),
        Err(_) => return gmsh_missing(),
    };
    Some(
        text(&run.stdout)
            .trim()
            .parse()
            .expect("a tetrahedron count"),
    )
}

/// A missing python3 or gmsh fails the test, as missing data does, unless
/// `LOOPSURF_SKIP_DATA` asks to skip (and the skip is said).
/// `scripts/test.sh` installs gmsh with pip.
fn gmsh_missing() -> Option<usize> {
    if std::env::var_os("LOOPSURF_SKIP_DATA").is_some() {
        println!("gmsh check skipped (LOOPSURF_SKIP_DATA)");
        return None;
    }
    panic!("the volume test needs python3 with gmsh (scripts/test.sh installs it; LOOPSURF_SKIP_DATA=1 skips)");
}

#[test]
fn gmsh_tetrahedralizes_the_adapted_meshes() {
    for (name, angle, extra) in [
        ("joint.off", "30", &[][..]),
        ("fandisk.off", "30", &[]),
        ("anchor.off", "30", &["--concave-seams"]),
    ] {
        if let Some(n) = tetrahedra(name, angle, extra) {
            assert!(n > 1000, "{name}: {n} tetrahedra");
        }
    }
}

#[test]
fn gmsh_tetrahedralizes_the_uniform_meshes() {
    // About 1% of each diagonal (1.57, 1.45, 1.46).
    for (name, angle, extra) in [
        ("joint.off", "30", &["--size", "0.016"][..]),
        ("fandisk.off", "30", &["--size", "0.015"]),
        ("anchor.off", "30", &["--size", "0.0146", "--concave-seams"]),
    ] {
        if let Some(n) = tetrahedra(name, angle, extra) {
            assert!(n > 1000, "{name}: {n} tetrahedra");
        }
    }
}
