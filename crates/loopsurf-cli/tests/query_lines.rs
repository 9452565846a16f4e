//! The query-line parser of `loopsurf eval` and `loopsurf snap`: its
//! contract, and the kept inputs of its fuzz target replayed with the
//! target's own checks.

#[path = "../../../fuzz/fuzz_targets/queries_case.rs"]
mod queries_case;

use loopsurf_cli::parse_query;
use std::path::Path;

#[test]
fn query_lines_replay_their_fuzz_inputs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let mut files = Vec::new();
    for kind in ["corpus", "regressions"] {
        if let Ok(dir) = std::fs::read_dir(root.join(kind).join("queries")) {
            files.extend(dir.map(|e| e.unwrap().path()));
        }
    }
    files.sort();
    assert!(
        !files.is_empty(),
        "no fuzz inputs kept (fuzz/corpus/queries)"
    );
    for file in files {
        let data = std::fs::read(&file).unwrap();
        let outcome = std::panic::catch_unwind(|| queries_case::replay(&data));
        assert!(outcome.is_ok(), "{} panicked", file.display());
    }
}

#[test]
fn query_lines() {
    let parse3 = |text| parse_query::<3>(7, text, "x y z");
    assert_eq!(parse3("  # only a comment").unwrap(), None);
    assert_eq!(parse3(" \t\r").unwrap(), None);
    assert_eq!(
        parse3("1 -2.5e3\t+.5 # tail").unwrap(),
        Some([1.0, -2500.0, 0.5])
    );
    assert_eq!(parse3("1 2 3#4 5").unwrap(), Some([1.0, 2.0, 3.0]));
    for bad in ["1 2", "1 2 3 4", "1 2 x", "1 2 0x10", "1 2 1_0"] {
        let err = parse3(bad).expect_err(bad).to_string();
        assert!(err.starts_with("line 7: expected `x y z`, got '"), "{err}");
    }
    // The extremes parse to exactly these bit patterns (the smallest
    // subnormal, a negative zero, the largest finite, the infinities, the
    // smallest normal, an overflow to infinity), and then read back
    // bit-exact through the printed form; a NaN reads back a NaN.
    for (text, bits) in [
        (
            "5e-324 -0 1.7976931348623157e308",
            [
                0x0000_0000_0000_0001,
                0x8000_0000_0000_0000,
                0x7fef_ffff_ffff_ffff,
            ],
        ),
        (
            "inf -infinity 2.2250738585072014e-308",
            [
                0x7ff0_0000_0000_0000,
                0xfff0_0000_0000_0000,
                0x0010_0000_0000_0000,
            ],
        ),
        (
            "0.1 -2.5e3 1e400",
            [
                0x3fb9_9999_9999_999a,
                0xc0a3_8800_0000_0000,
                0x7ff0_0000_0000_0000,
            ],
        ),
    ] {
        let parsed = parse3(text).unwrap().unwrap().map(f64::to_bits);
        let hex = |b: [u64; 3]| b.map(|x| format!("{x:#018x}"));
        assert_eq!(hex(parsed), hex(bits), "{text}");
        queries_case::replay(text.as_bytes());
    }
    let nan = parse3("-nan 0.1 nan").unwrap().unwrap();
    assert!(nan[0].is_nan() && nan[2].is_nan(), "{nan:?}");
    queries_case::replay(b"-nan 0.1 1e400");
}
