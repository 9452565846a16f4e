//! Gives the shared library the SONAME it is installed under, so programs
//! linked against the installed `libloopsurf.so` find it at run time
//! whatever the Cargo artefact was called.
fn main() {
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux") {
        let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap_or_else(|_| "0".into());
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libloopsurf.so.{major}");
    }
}
