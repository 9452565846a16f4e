//! The committed `include/loopsurf.h` must be what cbindgen generates from
//! the current sources. Run with `LOOPSURF_BLESS=1` to rewrite it.

use std::path::Path;

#[test]
fn committed_header_is_fresh() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let header = crate_dir.join("../../include/loopsurf.h");
    let config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).unwrap();
    let bindings = cbindgen::Builder::new()
        .with_crate(crate_dir)
        .with_config(config)
        .generate()
        .expect("cbindgen runs on the capi crate");
    let mut fresh = Vec::new();
    bindings.write(&mut fresh);
    if std::env::var_os("LOOPSURF_BLESS").is_some() {
        std::fs::create_dir_all(header.parent().unwrap()).unwrap();
        std::fs::write(&header, &fresh).unwrap();
    }
    let committed = std::fs::read(&header).unwrap_or_default();
    assert!(
        committed == fresh,
        "include/loopsurf.h is stale: regenerate it with \
         `LOOPSURF_BLESS=1 cargo test --release -p loopsurf-capi --test header`"
    );
}
