//! The ASCII .vtu reader on arbitrary bytes, then the Lagrange mesh it
//! yields: errors are fine; panics, hangs and runaway allocations are not.
#![no_main]

use libfuzzer_sys::fuzz_target;
use loopsurf::io::parse_vtu;

fuzz_target!(|data: &[u8]| {
    if let Ok(mesh) = parse_vtu(data, std::path::Path::new("input.vtu")) {
        let _ = mesh.to_lagrange();
    }
});
