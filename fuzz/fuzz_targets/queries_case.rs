//! What the `queries` fuzz target checks on one input, shared with the
//! stable replay (crates/loopsurf-cli/tests/query_lines.rs includes this
//! file): the input's lines as `BufRead::lines` yields them, parsed for the
//! shapes 2, 3 (eval, snap) and 4. A refused line's error names its
//! number; an accepted line's numbers are written by the command's
//! `write_numbers` and read back bit-exact (a NaN as a NaN: `{:e}` does not
//! print its sign).

use loopsurf_cli::{parse_query, write_numbers};

/// Checks every line of `data`; panics on a violation.
pub fn replay(data: &[u8]) {
    for (i, line) in data.split(|&b| b == b'\n').enumerate() {
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        let Ok(text) = std::str::from_utf8(line) else {
            continue;
        };
        check::<2>(i + 1, text);
        check::<3>(i + 1, text);
        check::<4>(i + 1, text);
    }
}

fn check<const N: usize>(line: usize, text: &str) {
    match parse_query::<N>(line, text, "shape") {
        Ok(None) => {}
        Ok(Some(numbers)) => {
            let mut out = Vec::new();
            write_numbers(&mut out, &numbers).unwrap();
            let printed = String::from_utf8(out).unwrap();
            let printed = printed.strip_suffix('\n').unwrap();
            assert!(!printed.contains('\n'), "{printed:?}");
            let again = parse_query::<N>(line, printed, "shape").unwrap().unwrap();
            for (x, y) in numbers.iter().zip(again) {
                assert!(
                    x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()),
                    "{text:?}: {x:e} read back as {y:e}"
                );
            }
        }
        Err(err) => assert!(err.to_string().starts_with(&format!("line {line}: "))),
    }
}
