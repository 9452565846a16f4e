//! Every CGAL demo mesh, as a new user meets them: each loads
//! plainly, or loads with the option its refusal names, or is refused in
//! one line that says why. Loaded nets are evaluated; nothing may panic or
//! hang. `cargo test --release --test cgal_sweep -- --nocapture` prints the
//! table docs/repairs.md quotes.

mod common;

use loopsurf::repair::ReadOptions;
use loopsurf::snap;
use loopsurf::{ControlNet, Error, Surface};
use std::collections::BTreeMap;
use std::path::Path;
use std::time::{Duration, Instant};

/// The option a refusal points at, by the kind of error, if any does.
fn remedy(err: &Error, opts: &mut ReadOptions) -> Option<&'static str> {
    let r = &mut opts.repairs;
    let (flag, name) = match err.root() {
        Error::Polygon { .. } => (&mut opts.triangulate, "--triangulate"),
        Error::InconsistentOrientation { .. } => (&mut r.orient, "--orient"),
        Error::NonManifoldVertex { .. } => (&mut r.split_nonmanifold, "--split-nonmanifold"),
        Error::ZeroArea { .. } => (&mut r.allow_degenerate, "--allow-degenerate"),
        _ => return None,
    };
    // An option already on that did not help is no remedy.
    (!std::mem::replace(flag, true)).then_some(name)
}

/// Evaluates the net's surface at every triangle's centroid (up to 2000
/// triangles) and snaps one point near it.
fn evaluate(net: &ControlNet, name: &str) {
    let surface = Surface::new(net).unwrap_or_else(|e| panic!("{name}: {e}"));
    let diag = net.bbox_diagonal();
    let n = net.triangles().len();
    let step = n.div_ceil(2000).max(1);
    for t in (0..n).step_by(step) {
        let e = surface
            .eval(t, 1.0 / 3.0, 1.0 / 3.0)
            .unwrap_or_else(|e| panic!("{name}: triangle {t}: {e}"));
        assert!(
            e.x.is_finite() && e.xv.is_finite() && e.xw.is_finite(),
            "{name}: triangle {t}: {e:?}"
        );
    }
    // A point off the surface along its normal is no farther from it than
    // that offset.
    let (x, normal) = (
        surface.point(0, 0.25, 0.25).unwrap(),
        surface
            .normal(0, 0.25, 0.25)
            .unwrap_or_else(|e| panic!("{name}: {e}")),
    );
    let off = 1e-3 * diag;
    let snap =
        snap::closest_point(&surface, x + off * normal).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(snap.distance <= off * (1.0 + 1e-9), "{name}: {snap:?}");
}

#[test]
fn every_cgal_demo_mesh_loads_with_its_option_or_is_refused_in_one_line() {
    let Some(dir) = common::cgal_data::cgal_dir() else {
        return;
    };
    let names = demo_meshes(&dir);
    let mut outcome: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for name in &names {
        let path = dir.join(name);
        let start = Instant::now();
        let key = load_with_remedies(&path, name);
        // A guard against hangs, not a benchmark: the largest demo mesh
        // loads and evaluates in about a second.
        let took = start.elapsed();
        assert!(took < Duration::from_secs(10), "{name}: {took:?}");
        outcome.entry(key).or_default().push(name.clone());
    }
    println!("| outcome | meshes | examples |\n|---|---|---|");
    for (key, files) in &outcome {
        let examples: Vec<&str> = files.iter().take(4).map(String::as_str).collect();
        println!("| {key} | {} | {} |", files.len(), examples.join(", "));
    }
    // What the table in docs/repairs.md claims: only the point cloud is refused.
    let refused: Vec<&String> = outcome
        .iter()
        .filter(|(k, _)| k.starts_with("refused"))
        .flat_map(|(_, v)| v)
        .collect();
    assert_eq!(refused, vec!["b9.ply"], "{outcome:#?}");
    let plain = outcome.get("loads plain").map_or(0, Vec::len);
    assert!(plain >= 114, "{outcome:#?}");
}

/// The demo meshes in `dir` in a format we read, sorted: at least 140.
fn demo_meshes(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| {
            let ext = Path::new(n)
                .extension()
                .and_then(|e| e.to_str())
                .unwrap_or("");
            matches!(ext, "off" | "obj" | "ply" | "stl" | "tri")
        })
        .collect();
    names.sort();
    assert!(
        names.len() >= 140,
        "only {} meshes in {}",
        names.len(),
        dir.display()
    );
    names
}

/// Loads `path`, adding the option each refusal names until it loads or
/// no option helps, and checks the outcome: what the options changed is
/// reported, `--repair` alone does at least as well, and a refusal is
/// one line naming the file that `--repair` does not change. Returns the
/// outcome's line in the table.
fn load_with_remedies(path: &Path, name: &str) -> String {
    let mut opts = ReadOptions::default();
    let mut used = Vec::new();
    let result = loop {
        match ControlNet::read_with(path, &opts) {
            Ok(net) => break Ok(net),
            Err(err) => match remedy(&err, &mut opts) {
                Some(flag) => used.push(flag),
                None => break Err(err),
            },
        }
    };
    match result {
        Ok(net) => {
            evaluate(&net, name);
            // Every change the options made is reported.
            let changed = opts.repairs.orient
                || opts.repairs.split_nonmanifold
                || opts.repairs.allow_degenerate;
            assert_eq!(
                changed,
                !net.repairs().is_empty(),
                "{name}: {:?}",
                net.repairs()
            );
            // `--repair` alone does at least as well.
            let all = ControlNet::read_with(path, &ReadOptions::repair_all())
                .unwrap_or_else(|e| panic!("{name}: loads with {used:?} but not --repair: {e}"));
            evaluate(&all, name);
            if used.is_empty() {
                "loads plain".to_string()
            } else {
                format!("loads with {}", used.join(" "))
            }
        }
        Err(err) => {
            let msg = err.to_string();
            assert!(!msg.contains('\n'), "{name}: {msg}");
            assert!(msg.contains(name), "{name}: does not name the file: {msg}");
            // The same refusal under --repair: nothing we offer fixes it.
            assert!(ControlNet::read_with(path, &ReadOptions::repair_all()).is_err());
            let why = match err.root() {
                Error::EmptyMesh { ntris: 0, .. } => {
                    "refused: no triangles (a point cloud)".to_string()
                }
                other => format!("refused: {other}"),
            };
            why
        }
    }
}
