//! The `loopsurf` command as a user runs it: outputs, files, exit codes.

mod support;

use std::path::{Path, PathBuf};
use std::process::Output;
use support::{
    assert_clean_failure, assert_refused_without_writing, loopsurf, loopsurf_with_stdin, scratch,
    text,
};

#[test]
fn info_on_the_viking_finds_two_hard_circles() {
    let out = loopsurf(&["info", "--example", "viking", "--hard-angle", "30"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let s = text(&out.stdout);
    assert!(
        s.contains("Euler characteristic: 2 (closed, genus 0)"),
        "{s}"
    );
    assert!(s.contains("boundary loops: 0"), "{s}");
    assert!(s.contains("limit deviation"), "{s}");
    // Two circles of crease vertices, no corners.
    let hard = s.lines().find(|l| l.starts_with("hard edges:")).unwrap();
    let kinds = s.lines().find(|l| l.starts_with("vertex kinds:")).unwrap();
    assert!(
        kinds.contains("corner 0") && kinds.contains("dart 0"),
        "{kinds}"
    );
    let n: usize = hard.split_whitespace().nth(2).unwrap().parse().unwrap();
    let crease: usize = kinds
        .split("crease ")
        .nth(1)
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(n, crease, "closed circles have as many edges as vertices");
    assert!(n > 0);
}

#[test]
fn hard_edges_lists_boundary_and_tagged_edges() {
    let mesh = scratch("square.off");
    std::fs::write(
        &mesh,
        "OFF\n5 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 0.2\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n",
    )
    .unwrap();
    let tags = scratch("tags.txt");
    std::fs::write(&tags, "# the diagonal spoke\n4 0\n").unwrap();
    let out = loopsurf(&[
        "hard-edges",
        mesh.to_str().unwrap(),
        "--hard-edges",
        tags.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let mut lines: Vec<String> = text(&out.stdout).lines().map(String::from).collect();
    lines.sort();
    assert_eq!(lines, ["0 1", "0 3", "0 4", "1 2", "2 3"]);
}

#[test]
fn refine_writes_the_requested_format() {
    let out_path = scratch("torus2.obj");
    let out = loopsurf(&[
        "refine",
        "--example",
        "torus",
        "--levels",
        "2",
        "--limit",
        "-o",
        out_path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let net = loopsurf::ControlNet::read(&out_path).unwrap();
    let ex = loopsurf::examples::torus();
    assert_eq!(net.triangles().len(), 16 * ex.tris.len());
    let vtu = scratch("torus1.vtu");
    let out = loopsurf(&[
        "refine",
        "--example",
        "torus",
        "-k",
        "1",
        "-o",
        vtu.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let xml = std::fs::read_to_string(&vtu).unwrap();
    assert!(xml.contains("UnstructuredGrid") && xml.contains("Name=\"tri\""));
}

#[test]
fn bad_input_exits_2_with_one_line() {
    let bad = scratch("bad.off");
    std::fs::write(&bad, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n").unwrap();
    assert_clean_failure(&loopsurf(&["info", bad.to_str().unwrap()]), "bad.off:6");
    assert_clean_failure(
        &loopsurf(&["info", "/nonexistent/x.off"]),
        "/nonexistent/x.off",
    );
    assert_clean_failure(&loopsurf(&["info", "mesh.unknown"]), "mesh.unknown");
    assert_clean_failure(&loopsurf(&["info", "--example", "nope"]), "unknown example");
    assert_clean_failure(
        &loopsurf(&["info", "--example", "cube", "--hard-angle", "-5"]),
        "hard angle",
    );
    assert_refused_without_writing(
        &["refine", "--example", "cube", "-k", "99", "-o", "{out}"],
        "x.obj",
        "levels",
    );
    assert_clean_failure(&loopsurf(&["info"]), "MESH");
    for charts in [&[][..], &["--charts"][..]] {
        let mut args = vec!["mesh", "--example", "cube", "--size", "0.01"];
        args.extend(["--max-triangles", "1000", "-o", "{out}"]);
        args.extend(charts);
        assert_refused_without_writing(&args, "x.obj", "over the");
    }
    assert_clean_failure(&loopsurf(&["frobnicate"]), "frobnicate");
    let tags = scratch("tags_bad.txt");
    let with_tags = |content: &str| {
        std::fs::write(&tags, content).unwrap();
        loopsurf(&[
            "info",
            "--example",
            "cube",
            "--hard-edges",
            tags.to_str().unwrap(),
        ])
    };
    assert_clean_failure(&with_tags("0 1\n1 two\n"), "tags_bad.txt");
    assert_clean_failure(&with_tags("0 999999\n"), "tags_bad.txt:1");
}

/// Out of memory, the command ends like any other error: one line, exit
/// status 2, no file. The address space is capped (`ulimit -v`, 400 MB)
/// below what refining the Viking eight times needs (110 million
/// triangles, gigabytes), so an allocation fails; one thread, so that no
/// thread's start-up meets the cap first on a machine with many cores.
#[test]
fn running_out_of_memory_exits_2_with_one_line() {
    let out = scratch("out_of_memory.off");
    let _ = std::fs::remove_file(&out);
    let command = format!(
        "ulimit -v 400000 && exec '{}' refine --example viking --levels 8 -o '{}'",
        env!("CARGO_BIN_EXE_loopsurf"),
        out.display()
    );
    let run = std::process::Command::new("sh")
        .args(["-c", &command])
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .expect("sh runs");
    assert_clean_failure(&run, "out of memory: could not allocate");
    assert!(!out.exists(), "a command out of memory wrote {out:?}");
}

#[test]
fn eval_reads_back_bit_exact() {
    let queries = "0 0.25 0.25\n# a comment\n\n7 0 0\n12 0.1 0.8\n3 1 0\n";
    let out = loopsurf_with_stdin(
        &["eval", "--example", "cube", "--hard-angle", "30"],
        queries,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let ex = loopsurf::examples::cube();
    let mut net = loopsurf::ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
    net.tag_by_angle(30.0).unwrap();
    let surface = loopsurf::Surface::new(&net).unwrap();
    let expected = [
        (0, 0.25, 0.25),
        (7, 0.0, 0.0),
        (12, 0.1, 0.8),
        (3, 1.0, 0.0),
    ];
    let lines: Vec<String> = text(&out.stdout).lines().map(String::from).collect();
    assert_eq!(lines.len(), expected.len());
    for (line, &(t, v, w)) in lines.iter().zip(&expected) {
        let numbers: Vec<f64> = line
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        let record = surface.eval(t, v, w).unwrap().record();
        assert_eq!(numbers.len(), 18);
        for (a, b) in numbers.iter().zip(record) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
    }
}

#[test]
fn eval_rejects_bad_lines_by_number() {
    let out = loopsurf_with_stdin(&["eval", "--example", "sphere"], "0 0.1 0.1\n1 x 0\n");
    assert_clean_failure(&out, "line 2");
    let out = loopsurf_with_stdin(&["eval", "--example", "sphere"], "0 0.1 0.1\n\n1 0.9 0.9\n");
    assert_clean_failure(&out, "line 3");
    let out = loopsurf_with_stdin(&["eval", "--example", "sphere"], "99999 0.1 0.1\n");
    assert_clean_failure(&out, "line 1");
}

#[test]
fn interpolate_writes_a_net_whose_surface_passes_through_the_points() {
    let out_path = scratch("sphere-solved.off");
    let hard = scratch("sphere-solved.hard");
    let out = loopsurf(&[
        "interpolate",
        "--example",
        "sphere",
        "-o",
        out_path.to_str().unwrap(),
        "--write-hard-edges",
        hard.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let report = text(&out.stdout);
    assert!(
        report.contains("residual:") && report.contains("largest turn"),
        "{report}"
    );
    assert!(out.stderr.is_empty(), "a smooth sphere gives no warning");
    // The written net's limit surface interpolates the example's points:
    // evaluating it at a triangle corner gives the original vertex.
    let solved = loopsurf_with_stdin(&["eval", out_path.to_str().unwrap()], "0 0 0\n");
    let original = loopsurf_with_stdin(
        &["eval", "--example", "sphere", "--interpolate", "solve"],
        "0 0 0\n",
    );
    let first3 = |o: &Output| -> Vec<f64> {
        text(&o.stdout)
            .split_whitespace()
            .take(3)
            .map(|x| x.parse().unwrap())
            .collect()
    };
    let e = loopsurf::examples::by_name("sphere").unwrap();
    let p = e.points[e.tris[0][0] as usize].to_array();
    for got in [first3(&solved), first3(&original)] {
        for k in 0..3 {
            assert!((got[k] - p[k]).abs() < 1e-12, "{got:?} vs {p:?}");
        }
    }
    let displaced = loopsurf_with_stdin(
        &[
            "eval",
            "--example",
            "sphere",
            "--interpolate",
            "displacement",
        ],
        "0 0 0\n",
    );
    assert_eq!(
        first3(&displaced),
        p.to_vec(),
        "displacement is exact at corners"
    );
    assert_clean_failure(
        &loopsurf(&["eval", "--example", "sphere", "--interpolate", "bogus"]),
        "bogus",
    );
}

#[test]
fn snap_answers_read_back_bit_exact_and_bad_lines_are_named() {
    let out = loopsurf_with_stdin(
        &["snap", "--example", "torus"],
        "0.3 0.1 0.2\n# a comment\n\n40 -3 7\n",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 2);
    for (line, p) in lines.iter().zip([[0.3, 0.1, 0.2], [40.0, -3.0, 7.0]]) {
        let f: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(f.len(), 7, "{line}");
        let tri: usize = f[0].parse().unwrap();
        let n: Vec<f64> = f[1..].iter().map(|x| x.parse().unwrap()).collect();
        // The point is the surface at (tri, v, w), bit for bit, and the
        // distance is its distance to the query.
        let e = loopsurf_with_stdin(
            &["eval", "--example", "torus"],
            &format!("{tri} {:e} {:e}\n", n[0], n[1]),
        );
        let x: Vec<f64> = text(&e.stdout)
            .split_whitespace()
            .take(3)
            .map(|x| x.parse().unwrap())
            .collect();
        assert_eq!(x, n[2..5].to_vec());
        let d = ((x[0] - p[0]).powi(2) + (x[1] - p[1]).powi(2) + (x[2] - p[2]).powi(2)).sqrt();
        assert!((d - n[5]).abs() <= 1e-15 * d.max(1.0));
    }
    assert_clean_failure(
        &loopsurf_with_stdin(&["snap", "--example", "torus"], "0 0 0\n1 2\n"),
        "line 2",
    );
    assert_clean_failure(
        &loopsurf_with_stdin(&["snap", "--example", "torus"], "nan 0 0\n"),
        "line 1",
    );
}

/// `--certificate` adds the proven lower bound as an eighth column, within
/// the tolerance of the distance; a bad tolerance is one clear line.
#[test]
fn snap_certificate_is_an_eighth_column() {
    let input = "0.3 0.1 0.2\n40 -3 7\n";
    let plain = text(
        &loopsurf_with_stdin(
            &["snap", "--example", "viking", "--hard-angle", "30"],
            input,
        )
        .stdout,
    );
    for (tolerance, args) in [
        (
            1e-12,
            vec![
                "snap",
                "--example",
                "viking",
                "--hard-angle",
                "30",
                "--certificate",
            ],
        ),
        (
            1e-6,
            vec![
                "snap",
                "--example",
                "viking",
                "--hard-angle",
                "30",
                "--certificate",
                "--tolerance",
                "1e-6",
            ],
        ),
    ] {
        let out = loopsurf_with_stdin(&args, input);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let stdout = text(&out.stdout);
        // One answer per query, as without the certificate: a zip over no
        // lines would check nothing.
        assert_eq!(stdout.lines().count(), input.lines().count(), "{stdout}");
        assert_eq!(plain.lines().count(), input.lines().count(), "{plain}");
        for (line, plain) in stdout.lines().zip(plain.lines()) {
            let f: Vec<f64> = line
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            assert_eq!(f.len(), 8, "{line}");
            // The Viking's bounding-box diagonal is below 3.
            assert!(f[7] <= f[6] && f[6] - f[7] <= 3.0 * tolerance, "{line}");
            if tolerance == 1e-12 {
                assert!(line.starts_with(plain), "{line} vs {plain}");
            }
        }
    }
    for bad in ["0", "-1e-3", "2", "nan"] {
        let flag = format!("--tolerance={bad}");
        assert_clean_failure(
            &loopsurf_with_stdin(&["snap", "--example", "torus", &flag], "0 0 0\n"),
            "tolerance",
        );
    }
}

/// The README's main job: the remesher on the built-in Viking, with the
/// summary, the .vtu arrays and a params file that reads back bit-exact
/// (the remesher is deterministic); the chart mesher's .vtu also names
/// each triangle's control triangle.
#[test]
fn mesh_the_viking_writes_its_summary_and_files() {
    let vtu = scratch("viking.vtu");
    let params = scratch("viking.params");
    let out = loopsurf(&[
        "mesh",
        "--example",
        "viking",
        "--hard-angle",
        "30",
        "--adapt",
        "curvature",
        "-o",
        vtu.to_str().unwrap(),
        "--write-params",
        params.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let summary = text(&out.stdout);
    for needle in [
        "input: example:viking (842 vertices, 1680 triangles, 80 hard edges)",
        "triangles/s",
        "max deviation",
        "by snap",
        "angles: min",
        "below 20°",
        "below 10°",
        "edge lengths:",
        "short edges: none below 1e-6 × the smallest size asked for",
    ] {
        assert!(
            summary.contains(needle),
            "summary lacks '{needle}':\n{summary}"
        );
    }
    assert_angles_in_summary(&summary);
    assert_vtu_arrays(&vtu);
    assert_params_read_back_bit_exact(&params);
    assert_uniform_meshes_read_back();
    let charts = scratch("viking-charts.vtu");
    let out = loopsurf(&[
        "mesh",
        "--example",
        "viking",
        "--charts",
        "--size",
        "0.2",
        "--no-verify",
        "-o",
        charts.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let xml = std::fs::read_to_string(&charts).unwrap();
    assert!(xml.contains("Name=\"control_tri\""));
}

/// The quality the README promises of the Viking's adapted mesh, as the
/// summary states it: no angle below 20°, a mean smallest angle of 50°.
fn assert_angles_in_summary(summary: &str) {
    let number_after = |label: &str| -> f64 {
        let rest = &summary[summary.find(label).expect(label) + label.len()..];
        rest[..rest.find('°').expect("degrees")]
            .trim()
            .parse()
            .unwrap()
    };
    let (min, mean_min) = (
        number_after("angles: min"),
        number_after("per-triangle minima"),
    );
    assert!(
        min >= 20.0 && mean_min >= 50.0,
        "{min}° / {mean_min}°:\n{summary}"
    );
}

/// The remesher's .vtu names its point and cell arrays.
fn assert_vtu_arrays(vtu: &Path) {
    let xml = std::fs::read_to_string(vtu).unwrap();
    for name in [
        "tri",
        "v",
        "w",
        "mean_curvature",
        "gaussian_curvature",
        "face",
        "min_angle",
        "shape_quality",
    ] {
        assert!(
            xml.contains(&format!("Name=\"{name}\"")),
            "vtu lacks {name}"
        );
    }
}

/// Every params line evaluates to its vertex, read back bit-exact.
fn assert_params_read_back_bit_exact(params: &Path) {
    let ex = loopsurf::examples::by_name("viking").unwrap();
    let mut net = loopsurf::ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
    net.tag_by_angle(30.0).unwrap();
    let surface = loopsurf::Surface::new(&net).unwrap();
    let mesh = loopsurf::Remesher::new(&surface)
        .adapt_curvature(true)
        .run()
        .unwrap();
    let lines: Vec<String> = std::fs::read_to_string(params)
        .unwrap()
        .lines()
        .map(String::from)
        .collect();
    assert_eq!(lines.len(), mesh.points.len());
    for (line, p) in lines.iter().zip(&mesh.params) {
        let f: Vec<&str> = line.split(' ').collect();
        assert_eq!(f[0].parse::<u32>().unwrap(), p.tri);
        assert_eq!(f[1].parse::<f64>().unwrap().to_bits(), p.v.to_bits());
        assert_eq!(f[2].parse::<f64>().unwrap().to_bits(), p.w.to_bits());
    }
}

/// The chart mesher's uniform meshes as .obj, .stl and .tri read back
/// with all their triangles.
fn assert_uniform_meshes_read_back() {
    for ext in ["obj", "stl", "tri"] {
        let path = scratch(&format!("viking3.{ext}"));
        let out = loopsurf(&[
            "mesh",
            "--example",
            "viking",
            "--uniform",
            "3",
            "--no-verify",
            "-o",
            path.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let back = loopsurf::ControlNet::read(&path).unwrap();
        assert_eq!(back.triangles().len(), 9 * 1680, "{ext}");
    }
}

#[test]
fn mesh_rejects_bad_options_with_one_line() {
    let o = scratch("never.obj");
    let o = o.to_str().unwrap();
    let mesh = |extra: &[&str]| {
        let mut args = vec!["mesh", "--example", "cube", "-o", o];
        args.extend_from_slice(extra);
        loopsurf(&args)
    };
    assert_clean_failure(&mesh(&["--charts"]), "no density");
    assert_clean_failure(
        &mesh(&["--size", "0.5", "--order", "2"]),
        "order 2 needs a .msh or .vtu",
    );
    assert_clean_failure(&mesh(&["--size", "0.5", "--order", "5"]), "order 5");
    assert_clean_failure(&mesh(&["--tolerance", "0"]), "tolerance 0");
    assert_clean_failure(&mesh(&["--tolerance", "-1e-3"]), "tolerance");
    assert_clean_failure(&mesh(&["--size", "-2"]), "size -2");
    assert_clean_failure(&mesh(&["--uniform", "0"]), "uniform segment count 0");
    assert_clean_failure(&mesh(&["--uniform", "3", "--size", "1"]), "--size");
    assert_clean_failure(
        &mesh(&["--uniform", "3", "--adapt", "curvature"]),
        "exclude",
    );
    assert_clean_failure(&mesh(&["--adapt", "nonsense"]), "nonsense");
    assert_clean_failure(&mesh(&["--uniform", "100000"]), "at most");
    assert_refused_without_writing(
        &["mesh", "--example", "cube", "--uniform", "2", "-o", "{out}"],
        "x.unknown",
        "x.unknown",
    );
}

/// `loopsurf adapt`: the summary, a .vtu with parameters and dead flags, and
/// Liu & Kondo's Table 1 with `--report`.
#[test]
fn adapt_the_torus_writes_its_summary_and_report() {
    let vtu = scratch("torus-adapt.vtu");
    let out = loopsurf(&[
        "adapt",
        "--example",
        "torus",
        "--angle",
        "11",
        "--levels",
        "3",
        "-o",
        vtu.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let summary = text(&out.stdout);
    for needle in [
        "level 3: ",
        "% fewer",
        "triangles/s",
        "min angle",
        "max distance of the vertices to the limit surface",
    ] {
        assert!(
            summary.contains(needle),
            "'{needle}' missing from {summary}"
        );
    }
    let file = std::fs::read_to_string(&vtu).unwrap();
    for name in ["\"tri\"", "\"v\"", "\"w\"", "\"dead\""] {
        assert!(file.contains(name), "{name} missing from the .vtu");
    }
    let out = loopsurf(&["adapt", "--example", "torus", "--levels", "2", "--report"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let report = text(&out.stdout);
    for row in [
        "| uniform Loop |",
        "| CA = 7° |",
        "| CA = 11° |",
        "| CA = 22° |",
    ] {
        assert!(report.contains(row), "'{row}' missing from {report}");
    }
}

#[test]
fn adapt_rejects_bad_options_with_one_line() {
    let o = scratch("never-adapt.obj");
    let o = o.to_str().unwrap();
    let adapt = |extra: &[&str]| {
        let mut args = vec!["adapt", "--example", "cube", "-o", o];
        args.extend_from_slice(extra);
        loopsurf(&args)
    };
    assert_clean_failure(&adapt(&["--levels", "2"]), "no criterion");
    assert_clean_failure(&adapt(&["--angle", "-5", "--levels", "2"]), "angle -5");
    assert_clean_failure(&adapt(&["--angle", "5", "--levels", "11"]), "levels 11");
    assert_clean_failure(&adapt(&["--angle", "5"]), "--levels");
    assert_clean_failure(
        &adapt(&["--tolerance", "2", "--levels", "2"]),
        "tolerance 2",
    );
    assert_clean_failure(
        &loopsurf(&[
            "adapt",
            "--example",
            "cube",
            "--angle",
            "5",
            "--levels",
            "1",
        ]),
        "--output",
    );
}

#[test]
fn repairs_are_asked_for_and_reported() {
    // The octahedron with two triangles turned.
    let path = scratch("shuffled.off");
    std::fs::write(
        &path,
        "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n\
         3 0 4 2\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 2 1 5\n3 3 1 5\n3 0 3 5\n",
    )
    .unwrap();
    let file = path.to_str().unwrap();
    assert_clean_failure(&loopsurf(&["info", file]), "--orient");
    for flag in ["--orient", "--repair"] {
        let out = loopsurf(&["info", flag, file]);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let err = text(&out.stderr);
        assert_eq!(
            err.trim(),
            format!(
                "loopsurf: {file}: orient: flipped 2 of the 8 triangles of the piece of triangle 0 \
                 (closed: now facing outward)"
            )
        );
        assert!(text(&out.stdout).contains("Euler characteristic: 2"));
    }
    assert_clean_failure(
        &loopsurf(&["info", "--weld", "0.5", file]),
        "weld distance 0.5",
    );
}

#[test]
fn a_net_that_folds_back_is_named_in_a_warning() {
    // A strip whose second triangle lies folded back almost onto the first.
    let path = scratch("folded.off");
    std::fs::write(
        &path,
        "OFF\n4 2 0\n0 0 0\n1 0 0\n0.5 1 0\n0.5 1 0.001\n3 0 1 2\n3 1 0 3\n",
    )
    .unwrap();
    let file = path.to_str().unwrap();
    let out = loopsurf(&["info", file]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(
        err.contains(&format!(
            "loopsurf: {file}: warning: the net folds back on itself at 1 edge"
        )) && err.contains("vertices 0–1, between triangles 0 and 1"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
}

#[test]
fn a_mesh_of_a_folded_surface_says_where_it_folds() {
    // CGAL's hole.off (a box with a square hole), triangulated: at 40° its
    // faces fold over themselves beside the hole's rim.
    let path = scratch("hole.off");
    std::fs::write(&path, "OFF\n20 40 0\n10 10 10\n10 10 -10\n-10.0989 5.15251 5.15251\n10.1031 4.94845 4.94845\n-10.0989 5.15251 -5.15251\n10.1031 4.94845 -4.94845\n-10 10 10\n10 -10 10\n-10.0989 -5.15251 5.15251\n10.1031 -4.94845 4.94845\n-10 10 -10\n-10 -10 10\n0 -10.2041 0\n0 0 10.2041\n0 10.2041 0\n0 0 -10.2041\n-10 -10 -10\n10 -10 -10\n-10.0989 -5.15251 -5.15251\n10.1031 -4.94845 -4.94845\n3 13 7 0\n3 6 13 0\n3 6 0 14\n3 14 0 1\n3 1 0 3\n3 1 3 5\n3 7 9 3\n3 7 3 0\n3 11 7 13\n3 11 13 6\n3 17 19 9\n3 17 9 7\n3 12 17 7\n3 11 12 7\n3 8 11 6\n3 8 6 2\n3 4 2 6\n3 4 6 10\n3 10 6 14\n3 10 14 1\n3 17 1 5\n3 17 5 19\n3 10 1 15\n3 15 1 17\n3 5 4 18\n3 18 19 5\n3 3 2 4\n3 4 5 3\n3 8 2 3\n3 8 3 9\n3 18 8 9\n3 18 9 19\n3 16 12 11\n3 18 16 11\n3 18 11 8\n3 16 17 12\n3 16 15 17\n3 18 4 10\n3 18 10 16\n3 16 10 15\n").unwrap();
    let out_path = scratch("hole-mesh.off");
    let out = loopsurf(&[
        "mesh",
        path.to_str().unwrap(),
        "--hard-angle",
        "40",
        "--adapt",
        "curvature",
        "--no-verify",
        "-o",
        out_path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(
        err.contains("warning: triangles below 10° lie where the surface folds over itself, in ")
            && err.contains(" control triangles (4, 5, "),
        "{err}"
    );
}

#[test]
fn a_mesh_that_crosses_itself_says_so_and_names_a_crossing_net() {
    // Octahedra, the second shifted by a third of the first's size: their
    // nets and surfaces pierce each other. One alone is clean.
    let corners = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let faces = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    let off = |shifts: &[f64]| {
        let mut text = format!("OFF\n{} {} 0\n", 6 * shifts.len(), 8 * shifts.len());
        for &dx in shifts {
            for [x, y, z] in corners {
                text += &format!("{} {y} {z}\n", x + dx);
            }
        }
        for n in 0..shifts.len() {
            for f in faces.map(|f| f.map(|v| v + 6 * n)) {
                text += &format!("3 {} {} {}\n", f[0], f[1], f[2]);
            }
        }
        text
    };
    let mesh = |shifts: &[f64]| {
        let path = scratch("octahedra.off");
        std::fs::write(&path, off(shifts)).unwrap();
        let out_path = scratch("octahedra-mesh.off");
        let args = [
            "mesh",
            path.to_str().unwrap(),
            "--size",
            "0.1",
            "-o",
            out_path.to_str().unwrap(),
        ];
        let out = loopsurf(&args);
        assert!(out.status.success(), "{}", text(&out.stderr));
        (text(&out.stdout), text(&out.stderr))
    };
    let (stdout, err) = mesh(&[0.0, 0.6]);
    let pairs: usize = stdout
        .lines()
        .find_map(|l| l.strip_prefix("crossings: "))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no count of crossing pairs: {stdout}"));
    assert!(pairs > 0, "{stdout}");
    assert!(
        err.contains(&format!(
            "warning: the mesh crosses itself: {pairs} pairs of triangles meet"
        )) && err.contains("(the control net itself crosses in "),
        "{err}"
    );
    let (stdout, err) = mesh(&[0.0]);
    assert!(stdout.contains("crossings: none"), "{stdout}");
    assert!(!err.contains("crosses"), "{err}");
}

/// The values of the named array of a .vtu file, as text.
fn vtu_array(xml: &str, name: &str) -> Vec<String> {
    let start = xml
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("the .vtu lacks {name}"));
    let body = &xml[start..];
    let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
    body.split_whitespace().map(str::to_string).collect()
}

fn example_surface(name: &str, angle: Option<f64>) -> loopsurf::Surface {
    let ex = loopsurf::examples::by_name(name).unwrap();
    let mut net = loopsurf::ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
    if let Some(a) = angle {
        net.tag_by_angle(a).unwrap();
    }
    loopsurf::Surface::new(&net).unwrap()
}

/// `loopsurf topology` on the cube: 6 faces, 12 edges between 8 corners,
/// each edge's chain the library's (3 control edges along each cube edge
/// of the 3 × 3 grid), one loop per face; the .vtu labels the control
/// triangles with faces, the hard edges (line cells) with edges, and the
/// corner vertices with corners.
#[test]
fn topology_of_the_cube() {
    let vtu = scratch("cube-topology.vtu");
    let out = loopsurf(&[
        "topology",
        "--example",
        "cube",
        "--hard-angle",
        "30",
        "-o",
        vtu.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines[0], "faces 6 edges 12 corners 8");
    assert_eq!(lines.len(), 1 + 12 + 6, "{stdout}");
    let surface = example_surface("cube", Some(30.0));
    let model = surface.model();
    for (id, line) in lines[1..13].iter().enumerate() {
        let f: Vec<&str> = line.split(' ').collect();
        assert_eq!(&f[..2], ["edge", &id.to_string()[..]], "{line}");
        assert_eq!(f[2], "corners", "{line}");
        let corners: Vec<i64> = f[3..5].iter().map(|x| x.parse().unwrap()).collect();
        assert!(corners.iter().all(|&c| (0..8).contains(&c)), "{line}");
        assert_eq!(f[5], "chain", "{line}");
        let chain: Vec<u32> = f[6..].iter().map(|x| x.parse().unwrap()).collect();
        let curve = &model.curves()[id];
        assert_eq!(chain, curve.chain, "{line}");
        assert_eq!(chain.len(), 4, "{line}");
        // The chain runs from its first corner's vertex to its second's.
        assert_eq!(model.corners()[corners[0] as usize], chain[0], "{line}");
        assert_eq!(model.corners()[corners[1] as usize], chain[3], "{line}");
    }
    for (id, line) in lines[13..].iter().enumerate() {
        assert_eq!(*line, format!("face {id} triangles 18 loops 1"));
    }
    assert_cube_topology_vtu(&vtu, &surface);
    // Anything but a .vtu is refused before any work.
    assert_refused_without_writing(
        &["topology", "--example", "cube", "-o", "{out}"],
        "x.obj",
        "x.obj",
    );
}

/// The cube's topology .vtu: 108 control triangles labelled with their
/// faces, 36 hard edges (line cells) with their edges, 8 corner vertices
/// with their corners.
fn assert_cube_topology_vtu(vtu: &Path, surface: &loopsurf::Surface) {
    let model = surface.model();
    let xml = std::fs::read_to_string(vtu).unwrap();
    assert!(
        xml.contains("NumberOfPoints=\"56\" NumberOfCells=\"144\""),
        "108 triangles and 36 hard edges"
    );
    let types = vtu_array(&xml, "types");
    assert!(types[..108].iter().all(|t| t == "5") && types[108..].iter().all(|t| t == "3"));
    let offsets = vtu_array(&xml, "offsets");
    assert_eq!(offsets.last().unwrap(), &(3 * 108 + 2 * 36).to_string());
    let face: Vec<i32> = vtu_array(&xml, "face")
        .iter()
        .map(|x| x.parse().unwrap())
        .collect();
    let edge: Vec<i32> = vtu_array(&xml, "edge")
        .iter()
        .map(|x| x.parse().unwrap())
        .collect();
    let corner: Vec<i32> = vtu_array(&xml, "corner")
        .iter()
        .map(|x| x.parse().unwrap())
        .collect();
    for t in 0..108 {
        assert_eq!(face[t], model.face_of_triangle()[t] as i32);
        assert_eq!(edge[t], -1);
    }
    let connectivity: Vec<u32> = vtu_array(&xml, "connectivity")
        .iter()
        .map(|x| x.parse().unwrap())
        .collect();
    let topo = surface.net().topology();
    for l in 0..36 {
        assert_eq!(face[108 + l], -1);
        let (a, b) = (
            connectivity[3 * 108 + 2 * l],
            connectivity[3 * 108 + 2 * l + 1],
        );
        let e = topo.find_edge(a, b).expect("a control edge");
        assert_eq!(Some(edge[108 + l] as u32), model.curve_of_edge(e));
    }
    assert_eq!(corner.iter().filter(|&&c| c >= 0).count(), 8);
    for (id, &v) in model.corners().iter().enumerate() {
        assert_eq!(corner[v as usize], id as i32);
    }
}

/// The open disk's boundary is one closed edge: no corner, its chain
/// closing on its first vertex.
#[test]
fn topology_of_the_open_disk_is_one_closed_edge() {
    let out = loopsurf(&["topology", "--example", "open-disk"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines[0], "faces 1 edges 1 corners 0", "{stdout}");
    assert!(
        lines[1].starts_with("edge 0 corners -1 -1 chain "),
        "{stdout}"
    );
    let chain: Vec<&str> = lines[1].split(' ').skip(6).collect();
    assert!(chain.len() > 3);
    assert_eq!(chain[0], *chain.last().unwrap());
    assert_eq!(lines[2], "face 0 triangles 54 loops 1");
    assert_eq!(lines.len(), 3);
}

/// `eval --edge`: 9 numbers per `edge t` line, bit for bit the library's
/// curve evaluation; a bad line stops the run naming its number.
#[test]
fn eval_edge_reads_back_bit_exact() {
    let queries: Vec<(usize, f64)> = vec![
        (0, 0.0),
        (0, 1.0 / 3.0),
        (3, 2.75),
        (11, 3.0),
        (5, 1.0),
        (7, 0.1),
    ];
    let stdin: String = queries
        .iter()
        .map(|(c, t)| format!("{c} {t:e}  # edge {c}\n\n"))
        .collect();
    let out = loopsurf_with_stdin(
        &["eval", "--example", "cube", "--hard-angle", "30", "--edge"],
        &stdin,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let surface = example_surface("cube", Some(30.0));
    let lines: Vec<String> = text(&out.stdout).lines().map(String::from).collect();
    assert_eq!(lines.len(), queries.len());
    for (line, &(c, t)) in lines.iter().zip(&queries) {
        let numbers: Vec<f64> = line
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        let record = loopsurf::LimitCurve::new(&surface, c)
            .unwrap()
            .eval(t)
            .unwrap()
            .record();
        assert_eq!(numbers.len(), 9);
        for (a, b) in numbers.iter().zip(record) {
            assert_eq!(a.to_bits(), b.to_bits(), "edge {c} t {t}");
        }
    }
    // The closed loop of the open disk, around to its end.
    let disk = example_surface("open-disk", None);
    let n = disk.model().curves()[0].len() as f64;
    let out = loopsurf_with_stdin(
        &["eval", "--example", "open-disk", "--edge"],
        &format!("0 {n}\n0 0.5\n"),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let first: Vec<f64> = text(&out.stdout)
        .lines()
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    let record = loopsurf::LimitCurve::new(&disk, 0)
        .unwrap()
        .eval(n)
        .unwrap()
        .record();
    assert!(first
        .iter()
        .zip(record)
        .all(|(a, b)| a.to_bits() == b.to_bits()));

    let edge = |stdin: &str| {
        loopsurf_with_stdin(
            &["eval", "--example", "cube", "--hard-angle", "30", "--edge"],
            stdin,
        )
    };
    assert_clean_failure(&edge("0 0.5\n0 x\n"), "line 2");
    assert_clean_failure(&edge("0 0.5\n\n0 1 2\n"), "line 3");
    assert_clean_failure(&edge("# fine\n0 7\n"), "line 2");
    assert_clean_failure(&edge("12 0\n"), "line 1");
    assert_clean_failure(&edge("0.5 0\n"), "line 1");
    assert_clean_failure(&edge("0 nan\n"), "line 1");
}

/// `loopsurf mesh` labels its .vtu: per triangle the model face of its
/// chart, then one line cell per hard output edge with its model edge.
#[test]
fn mesh_vtu_carries_faces_and_edges() {
    let vtu = scratch("cube-mesh-labels.vtu");
    let out = loopsurf(&[
        "mesh",
        "--example",
        "cube",
        "--hard-angle",
        "30",
        "--uniform",
        "2",
        "--no-verify",
        "-o",
        vtu.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let surface = example_surface("cube", Some(30.0));
    let mesh = loopsurf::Mesher::new(&surface)
        .density(loopsurf::Density::Uniform(2))
        .run()
        .unwrap();
    let (nt, nl) = (mesh.triangles.len(), mesh.hard_edges.len());
    assert_eq!((nt, nl), (108 * 4, 36 * 2));
    let xml = std::fs::read_to_string(&vtu).unwrap();
    assert!(xml.contains(&format!("NumberOfCells=\"{}\"", nt + nl)));
    let ints = |name: &str| -> Vec<i32> {
        vtu_array(&xml, name)
            .iter()
            .map(|x| x.parse().unwrap())
            .collect()
    };
    let (face, edge, chart) = (ints("face"), ints("edge"), ints("control_tri"));
    let model = surface.model();
    for t in 0..nt {
        assert_eq!(face[t], model.face_of_triangle()[chart[t] as usize] as i32);
        assert_eq!(face[t], mesh.faces[t] as i32);
        assert_eq!(edge[t], -1);
    }
    for l in 0..nl {
        assert_eq!((face[nt + l], chart[nt + l]), (-1, -1));
        assert_eq!(edge[nt + l], mesh.hard_edge_curves[l] as i32);
    }
    let angles = vtu_array(&xml, "min_angle");
    assert!(angles[nt..].iter().all(|a| a == "-1"));
    assert_eq!(
        vtu_array(&xml, "types")[nt..],
        vec!["3".to_string(); nl][..]
    );
}

/// The command of docs/high-order.md: a curved P2 .msh of the Viking with its summary;
/// `curve` puts a chart mesh written as .off back on the surface (nothing
/// moves) and curves it to P3 in .vtu; a mesh of another model is refused
/// by its first vertex, with one line.
#[test]
fn curved_meshes_and_curving_another_mesh() {
    let msh = curved_viking_msh();
    curve_a_chart_mesh_to_p3();
    measure_a_p2_mesh_as_given(&msh);
    refuse_curving_onto_another_model(&msh);
}

/// `mesh --order 2` to .msh: the summary reports the order and the scaled
/// Jacobian, and the file is ASCII MSH 4.1.
fn curved_viking_msh() -> PathBuf {
    let msh = scratch("viking-p2.msh");
    let out = loopsurf(&[
        "mesh",
        "--example",
        "viking",
        "--hard-angle",
        "30",
        "--order",
        "2",
        "--no-verify",
        "-o",
        msh.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let summary = text(&out.stdout);
    assert!(
        summary.contains("order 2: ") && summary.contains("scaled Jacobian: min"),
        "{summary}"
    );
    let file = std::fs::read_to_string(&msh).unwrap();
    assert!(
        file.starts_with("$MeshFormat\n4.1 0 8\n"),
        "{}",
        &file[..40]
    );
    msh
}

/// A chart mesh of the Viking as .off, curved to P3 in .vtu by `curve`,
/// which finds its 160 hard edges and writes the params and the scaled
/// Jacobian.
fn curve_a_chart_mesh_to_p3() {
    let linear = scratch("viking-charts.off");
    let out = loopsurf(&[
        "mesh",
        "--example",
        "viking",
        "--hard-angle",
        "30",
        "--charts",
        "--uniform",
        "2",
        "--no-verify",
        "-o",
        linear.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let curved = scratch("viking-p3.vtu");
    let out = loopsurf(&[
        "curve",
        linear.to_str().unwrap(),
        "--example",
        "viking",
        "--hard-angle",
        "30",
        "--order",
        "3",
        "-o",
        curved.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let summary = text(&out.stdout);
    assert!(
        summary.contains("160 hard edges found") && summary.contains("order 3: "),
        "{summary}"
    );
    let xml = std::fs::read_to_string(&curved).unwrap();
    assert!(xml.contains("Name=\"loopsurf_params\"") && xml.contains("Name=\"scaled_jacobian\""));
}

/// `curve --measure`: our own P2 mesh, as given and curved again, is as
/// near (the numbers: order, distance, triangle, distance, triangle).
fn measure_a_p2_mesh_as_given(msh: &Path) {
    let again = scratch("viking-p2-again.msh");
    let out = loopsurf(&[
        "curve",
        msh.to_str().unwrap(),
        "--example",
        "viking",
        "--hard-angle",
        "30",
        "--measure",
        "-o",
        again.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let summary = text(&out.stdout);
    let line = summary
        .lines()
        .find(|l| l.starts_with("largest distance"))
        .expect(&summary);
    let numbers: Vec<f64> = line
        .split_whitespace()
        .filter_map(|w| w.trim_end_matches(',').parse::<f64>().ok())
        .collect();
    assert!(
        line.contains("input (order 2, as given)") && numbers.len() == 5,
        "{line}"
    );
    assert!(
        numbers[1] > 0.0 && (numbers[1] - numbers[3]).abs() <= 1e-3 * numbers[1],
        "{line}"
    );
}

/// A mesh of the Viking onto the sphere is refused by its first vertex,
/// and an output other than .msh or .vtu by its extension.
fn refuse_curving_onto_another_model(msh: &Path) {
    let other = scratch("never.msh");
    let out = loopsurf(&[
        "curve",
        msh.to_str().unwrap(),
        "--example",
        "sphere",
        "-o",
        other.to_str().unwrap(),
    ]);
    assert_clean_failure(&out, "vertex 0");
    assert_refused_without_writing(
        &[
            "curve",
            msh.to_str().unwrap(),
            "--example",
            "viking",
            "-o",
            "{out}",
        ],
        "x.obj",
        "must be .msh or .vtu",
    );
}

/// `--concave-seams` on the inner corner of an L-shaped flat face (CGAL
/// anchor's, in units of its bar's width; every vertex a corner), where
/// Loop's crease rules fold the surface 0.19 of the bar's width (2.5% of
/// the diagonal) into the notch: one seam, which adds nothing to the
/// surface (it stays in its plane, within round-off of the surface
/// before) and removes the flap.
#[test]
fn concave_seams_report_what_they_changed() {
    let net = scratch("concave_l.off");
    std::fs::write(
        &net,
        "OFF\n6 4 0\n-6 0 0\n-6 1 0\n0 0 0\n1 1 0\n0 -1.6 0\n1 -1.6 0\n\
         3 0 2 1\n3 2 3 1\n3 2 4 3\n3 4 5 3\n",
    )
    .unwrap();
    let corners = scratch("concave_l.corners");
    std::fs::write(&corners, "0\n1\n2\n3\n4\n5\n").unwrap();
    let (net, corners) = (net.to_str().unwrap(), corners.to_str().unwrap());
    let out = loopsurf(&["info", net, "--hard-vertices", corners, "--concave-seams"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    let line = err
        .lines()
        .find(|l| {
            l.contains(
                "seamed 1 folded concave corner, at vertices 2 by 2–3 (270.0° into 135.0° + 135.0°)",
            )
        })
        .unwrap_or_else(|| panic!("{err}"));
    let figures: Vec<f64> = line
        .split("within ")
        .skip(1)
        .map(|s| s.split_whitespace().next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(figures.len(), 2, "{line}");
    assert!(figures[0] <= 1e-12, "{line}");
    assert!((0.02..0.03).contains(&figures[1]), "{line}");
    assert!(!err.contains("left"), "{err}");
    // Without the flag, nothing is seamed or said.
    let out = loopsurf(&["info", net, "--hard-vertices", corners]);
    assert!(out.status.success());
    assert!(!text(&out.stderr).contains("seam"), "{}", text(&out.stderr));
}
