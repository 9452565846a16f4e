//! `ls_net_from_arrays` with hostile arguments: zero counts, negative,
//! repeated and out-of-range indices, `i32::MIN`/`MAX`, NaN and infinite
//! coordinates, NULL pointers (the layout is in arrays_case.rs). It must
//! return the status of a problem the arguments have, never panic, and a
//! net it builds is freed (LeakSanitizer watches). Replayed on stable by
//! crates/loopsurf-capi/tests/hostile_arrays.rs, with the same module.
#![no_main]

mod arrays_case;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let case = arrays_case::decode(data);
    unsafe { arrays_case::check(&case) };
});
