//! `remesh::outcomes_from_bytes` (what a rank receives from the others in
//! a job of remeshing by parts) on arbitrary bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = loopsurf::remesh::outcomes_from_bytes(data);
});
