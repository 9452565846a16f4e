//! The gmsh .msh reader (MSH 4.1 and 2.2, ASCII and binary) on arbitrary
//! bytes, then the Lagrange mesh it yields: errors are fine; panics, hangs
//! and runaway allocations are not.
#![no_main]

use libfuzzer_sys::fuzz_target;
use loopsurf::io::parse_msh;

fuzz_target!(|data: &[u8]| {
    if let Ok(mesh) = parse_msh(data, std::path::Path::new("input.msh")) {
        let _ = mesh.to_lagrange();
    }
});
