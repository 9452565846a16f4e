//! Where the tests find CGAL's demo meshes (Debian's libcgal-demo, a test
//! dependency): the cache `scripts/test.sh` extracts into, extracted here
//! from the package if it is missing. A test that needs them fails when
//! neither is there — unless `LOOPSURF_SKIP_DATA=1` says to skip them, which
//! each skipping test then reports. Shared by the integration tests
//! (`tests/common.rs`) and the library's unit tests (by `#[path]`).

#![allow(dead_code)] // each includer uses what it needs

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The package's archive of demo data.
const ARCHIVE: &str = "/usr/share/doc/libcgal-dev/data.tar.gz";

/// The directory of the demo meshes, or `None` when the data is absent and
/// `LOOPSURF_SKIP_DATA` is set. Panics, saying what to do, when it is
/// absent otherwise.
pub fn cgal_dir() -> Option<PathBuf> {
    static DIR: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let found = DIR.get_or_init(|| {
        let cache = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../.cache/cgal");
        let meshes = cache.join("data/meshes");
        if meshes.join("bunny00.off").exists() {
            return Ok(meshes);
        }
        if Path::new(ARCHIVE).exists() {
            std::fs::create_dir_all(&cache).map_err(|e| format!("{}: {e}", cache.display()))?;
            let status = std::process::Command::new("tar")
                .arg("-xzf")
                .arg(ARCHIVE)
                .arg("-C")
                .arg(&cache)
                .arg("data/meshes")
                .status()
                .map_err(|e| format!("tar: {e}"))?;
            if status.success() && meshes.join("bunny00.off").exists() {
                return Ok(meshes);
            }
            return Err(format!(
                "extracting {ARCHIVE} into {} failed",
                cache.display()
            ));
        }
        Err(format!(
            "the CGAL demo meshes are missing: neither {} nor {ARCHIVE} exists \
             (install libcgal-demo, as scripts/test.sh does, or set LOOPSURF_SKIP_DATA=1 \
             to skip the tests that need them)",
            meshes.display()
        ))
    });
    match found {
        Ok(dir) => Some(dir.clone()),
        Err(why) if std::env::var_os("LOOPSURF_SKIP_DATA").is_some() => {
            eprintln!("skipping (LOOPSURF_SKIP_DATA): {why}");
            None
        }
        Err(why) => panic!("{why}"),
    }
}

/// One demo mesh; a file missing from present data is a failure.
pub fn cgal_file(name: &str) -> Option<PathBuf> {
    let path = cgal_dir()?.join(name);
    assert!(
        path.exists(),
        "{}: not among the CGAL demo meshes",
        path.display()
    );
    Some(path)
}
