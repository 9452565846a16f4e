//! `loopsurf fit` and `--fit` as a user runs them: outputs, files, exit
//! codes, and the one-line refusals.

mod support;

use support::{assert_clean_failure, loopsurf_with_stdin, scratch, text};

/// The fitted net is written with its hard edges next to it, reads back
/// as a net with those edges, and the report is printed.
#[test]
fn fit_writes_the_net_its_hard_edges_and_the_report() {
    let out_path = scratch("cube.obj");
    let out_s = out_path.to_str().unwrap();
    let out = loopsurf_with_stdin(
        &[
            "fit",
            "--example",
            "cube",
            "--hard-angle",
            "30",
            "--tolerance",
            "1",
            "-o",
            out_s,
        ],
        "",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let s = text(&out.stdout);
    assert!(s.contains("distance to the input vertices: max"), "{s}");
    assert!(s.contains("largest turn of the normal"), "{s}");
    let edges = out_path.with_extension("hard-edges");
    let lines = std::fs::read_to_string(&edges).unwrap();
    assert!(lines.lines().count() >= 12, "{lines}");
    let info = loopsurf_with_stdin(
        &["info", out_s, "--hard-edges", edges.to_str().unwrap()],
        "",
    );
    assert!(info.status.success(), "{}", text(&info.stderr));
}

/// A tolerance the fit cannot meet, a resolution that is no length and a
/// non-manifold mesh are each one line and exit 2.
#[test]
fn fit_refuses_with_one_line() {
    let out = scratch("x.obj");
    let out = out.to_str().unwrap();
    let refused = loopsurf_with_stdin(
        &[
            "fit",
            "--example",
            "sphere",
            "--tolerance",
            "1e-12",
            "-o",
            out,
        ],
        "",
    );
    assert_clean_failure(&refused, "misses the tolerance 1.0e-12");
    let negative = loopsurf_with_stdin(
        &[
            "fit",
            "--example",
            "sphere",
            "--resolution",
            "-1",
            "-o",
            out,
        ],
        "",
    );
    assert_clean_failure(&negative, "resolution -1");
    let bad = scratch("nonmanifold.off");
    std::fs::write(
        &bad,
        "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n",
    )
    .unwrap();
    let nm = loopsurf_with_stdin(&["fit", bad.to_str().unwrap(), "-o", out], "");
    assert_clean_failure(&nm, "non-manifold edge");
}

/// `--fit` makes eval work on the fitted net: a corner of its triangle 0
/// is evaluated, and the fit's report goes to stderr.
#[test]
fn eval_on_the_fitted_net() {
    let out = loopsurf_with_stdin(
        &[
            "eval",
            "--example",
            "sphere",
            "--fit",
            "--fit-tolerance",
            "1",
        ],
        "0 0 0\n",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let numbers = text(&out.stdout).split_whitespace().count();
    assert_eq!(numbers, 18);
    assert!(text(&out.stderr).contains("loopsurf: fit: distance to the input vertices"));
}

/// An interpolant that folds says so, with what was measured, and points
/// to `--fit`: on the filleted box both interpolants fold (the box's
/// long fillet slivers), on the cylinder neither does, and the
/// approximating surface of the box is not warned about.
#[test]
fn interpolants_that_fold_point_to_fit() {
    use loopsurf::cad::Analytic;
    let write = |shape: &dyn Analytic, name: &str| {
        let path = scratch(name);
        let ex = shape.tessellation();
        loopsurf::io::write_obj(&path, &ex.points, &ex.tris).unwrap();
        path
    };
    let box_path = write(&loopsurf::cad::FilletedBox::new(5e-4, 15.0), "box.obj");
    let cylinder = loopsurf::cad::cylinder(5e-4, 15.0, loopsurf::cad::CapStyle::Fan);
    let cylinder_path = write(&cylinder, "cylinder.obj");
    let eval = |path: &std::path::Path, mode: Option<&str>| {
        let mut args = vec!["eval", path.to_str().unwrap(), "--hard-angle", "30"];
        if let Some(m) = mode {
            args.extend(["--interpolate", m]);
        }
        let out = loopsurf_with_stdin(&args, "0 0.25 0.25\n");
        assert!(out.status.success(), "{}", text(&out.stderr));
        text(&out.stderr)
    };
    for mode in ["solve", "displacement"] {
        let warned = eval(&box_path, Some(mode));
        assert!(warned.contains("folds over itself in"), "{mode}: {warned}");
        assert!(warned.contains("`--fit`"), "{mode}: {warned}");
        let quiet = eval(&cylinder_path, Some(mode));
        assert!(!quiet.contains("warning"), "{mode}: {quiet}");
    }
    let approximating = eval(&box_path, None);
    assert!(!approximating.contains("warning"), "{approximating}");
}
