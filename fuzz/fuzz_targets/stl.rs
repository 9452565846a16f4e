//! The .stl reader on arbitrary bytes, then the net it yields and, when it
//! is small, its surface: errors are fine; panics, hangs and runaway
//! allocations are not. Replayed on stable by
//! crates/loopsurf/tests/fuzz_regressions.rs, which does the same.
#![no_main]

use libfuzzer_sys::fuzz_target;
use loopsurf::io::{parse_mesh, ParseOptions};
use loopsurf::repair::Repairs;
use loopsurf::{ControlNet, Surface};

fuzz_target!(|data: &[u8]| {
    // Plain, split polygons, and every repair (which parse untrusted data too).
    for (triangulate, repairs) in [(false, Repairs::default()), (true, Repairs::default()), (true, Repairs::all())] {
        let opts = ParseOptions { triangulate };
        let Ok(mesh) = parse_mesh(data.to_vec(), std::path::Path::new("input.stl"), &opts) else {
            continue;
        };
        if let Ok(net) = ControlNet::from_mesh_data_with(mesh, &repairs) {
            if net.triangles().len() <= 64 {
                let _ = Surface::new(&net);
            }
        }
    }
});
