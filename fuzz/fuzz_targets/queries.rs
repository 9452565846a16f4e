//! The stdin query lines of `loopsurf eval` and `loopsurf snap` on
//! arbitrary bytes (the checks are in queries_case.rs). Replayed on stable
//! by crates/loopsurf-cli/tests/query_lines.rs, with the same module.
#![no_main]

mod queries_case;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| queries_case::replay(data));
