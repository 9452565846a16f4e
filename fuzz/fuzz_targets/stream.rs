//! `stream::from_bytes` (what an MPI rank receives) on arbitrary bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = loopsurf::stream::from_bytes(data);
});
