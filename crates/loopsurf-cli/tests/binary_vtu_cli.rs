//! `--binary` on the commands that write `.vtu`: the same mesh and arrays
//! as the ASCII file, read back by our reader and (where installed) by
//! meshio, in a smaller file.

mod support;

use loopsurf::io::{read_vtu, VtuMesh};
use std::path::Path;
use support::{loopsurf, scratch, text};

/// Runs `args` twice, writing `name` as ASCII then with `--binary`, and
/// gives both files read back and their sizes.
fn both(args: &[&str], name: &str) -> [(VtuMesh, u64); 2] {
    [false, true].map(|binary| {
        let path = scratch(&format!("{}-{name}", if binary { "bin" } else { "ascii" }));
        let mut argv = args.to_vec();
        argv.extend(["-o", path.to_str().unwrap()]);
        if binary {
            argv.push("--binary");
        }
        let out = loopsurf(&argv);
        assert!(out.status.success(), "{argv:?}: {}", text(&out.stderr));
        let xml = std::fs::read_to_string(&path).unwrap();
        let format = if binary { "binary" } else { "ascii" };
        assert!(xml.contains(&format!("format=\"{format}\"")), "{argv:?}");
        meshio_points(&path, binary);
        let mesh = read_vtu(&path).unwrap();
        let size = std::fs::metadata(&path).unwrap().len();
        std::fs::remove_file(&path).unwrap();
        (mesh, size)
    })
}

/// Same mesh, arrays and bits from both files; the binary one is smaller.
fn assert_same(args: &[&str], name: &str) {
    let [(ascii, ascii_size), (binary, binary_size)] = both(args, name);
    assert_eq!(ascii, binary, "{args:?}");
    let bits = |m: &VtuMesh| -> Vec<u64> {
        m.points
            .iter()
            .flat_map(|p| p.to_array())
            .map(f64::to_bits)
            .collect()
    };
    assert_eq!(bits(&ascii), bits(&binary), "{args:?}");
    assert!(
        binary_size < ascii_size,
        "{args:?}: {binary_size} >= {ascii_size} bytes"
    );
}

#[test]
fn mesh_writes_binary_vtu() {
    assert_same(
        &["mesh", "--example", "viking", "--hard-angle", "30"],
        "mesh.vtu",
    );
}

#[test]
fn curved_mesh_writes_binary_vtu() {
    let args = [
        "mesh",
        "--example",
        "viking",
        "--size",
        "0.1",
        "--order",
        "3",
    ];
    assert_same(&args, "p3.vtu");
}

#[test]
fn partition_and_topology_write_binary_vtu() {
    assert_same(
        &["partition", "--example", "viking", "--parts", "3"],
        "parts.vtu",
    );
    assert_same(
        &["topology", "--example", "viking", "--hard-angle", "30"],
        "topo.vtu",
    );
}

#[test]
fn refine_and_adapt_write_binary_vtu() {
    assert_same(&["refine", "--example", "viking", "-k", "1"], "refined.vtu");
    let adapt = [
        "adapt",
        "--example",
        "viking",
        "--angle",
        "11",
        "--levels",
        "1",
    ];
    assert_same(&adapt, "adapted.vtu");
}

#[test]
fn fit_and_interpolate_write_binary_vtu() {
    let fit = ["fit", "--example", "viking", "--tolerance", "0.01"];
    assert_same(&fit, "fitted.vtu");
    assert_same(&["interpolate", "--example", "viking"], "solved.vtu");
}

/// meshio reads `path` and finds as many points as our reader.
fn meshio_points(path: &Path, binary: bool) {
    let script = "import meshio, sys\nprint(len(meshio.read(sys.argv[1]).points))";
    let Ok(out) = std::process::Command::new("python3")
        .args(["-c", script, path.to_str().unwrap()])
        .output()
    else {
        return meshio_missing("python3 not found");
    };
    let stderr = text(&out.stderr);
    if stderr.contains("No module named 'meshio'") {
        return meshio_missing("meshio not installed");
    }
    assert!(
        out.status.success(),
        "meshio failed on {} (binary {binary}): {stderr}",
        path.display()
    );
    let count: usize = text(&out.stdout).trim().parse().unwrap();
    let ours = read_vtu(path).unwrap().points.len();
    assert_eq!(count, ours, "meshio's point count for {}", path.display());
}

/// A missing python3 or meshio fails the test, as missing data does,
/// unless `LOOPSURF_SKIP_DATA` asks to skip (and the skip is said).
/// `scripts/test.sh` installs meshio with pip.
fn meshio_missing(why: &str) {
    if std::env::var_os("LOOPSURF_SKIP_DATA").is_some() {
        println!("{why}: meshio check skipped (LOOPSURF_SKIP_DATA)");
        return;
    }
    panic!("{why}: the meshio check needs it (scripts/test.sh installs it; LOOPSURF_SKIP_DATA=1 skips)");
}
