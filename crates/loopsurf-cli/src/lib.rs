//! The text format of the query lines `loopsurf eval` and `loopsurf snap`
//! read on stdin and of the numbers they write, apart from the command
//! (src/main.rs, whose `queries` module runs the loop) so that it can be
//! fuzzed: fuzz/fuzz_targets/queries.rs, whose kept inputs the tests below
//! replay.

use loopsurf::Error;
use std::io::Write;

/// One line of `N` numbers, or None for a blank or comment line; `line` is
/// its 1-based number and `expected` its shape (`"x y z"`), both for the
/// error message.
pub fn parse_query<const N: usize>(
    line: usize,
    text: &str,
    expected: &str,
) -> Result<Option<[f64; N]>, Error> {
    let content = text.split('#').next().unwrap_or("").trim();
    if content.is_empty() {
        return Ok(None);
    }
    let bad = || Error::Malformed {
        line,
        message: format!("expected `{expected}`, got '{content}'"),
    };
    let fields: Vec<&str> = content.split_whitespace().collect();
    if fields.len() != N {
        return Err(bad());
    }
    let mut out = [0.0; N];
    for (x, f) in out.iter_mut().zip(fields) {
        *x = f.parse::<f64>().map_err(|_| bad())?;
    }
    Ok(Some(out))
}

/// Writes numbers separated by spaces, each formatted to read back bit-exact.
pub fn write_numbers(out: &mut dyn Write, numbers: &[f64]) -> std::io::Result<()> {
    let text: Vec<String> = numbers.iter().map(|x| format!("{x:e}")).collect();
    writeln!(out, "{}", text.join(" "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// What fuzz/fuzz_targets/queries.rs does with one stdin line: an
    /// accepted line's numbers are written and read back bit-exact (NaN as
    /// NaN: `{:e}` drops its sign), a refused one names its line number.
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

    /// What the fuzz target does with one input: its lines as
    /// `BufRead::lines` yields them, for the shapes 2, 3 (eval, snap) and 4.
    fn replay(data: &[u8]) {
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
            let outcome = std::panic::catch_unwind(|| replay(&data));
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
        // The extremes read back bit-exact; a NaN reads back a NaN.
        for text in [
            "5e-324 -0 1.7976931348623157e308",
            "inf -infinity 2.2250738585072014e-308",
            "-nan 0.1 1e400",
        ] {
            replay(text.as_bytes());
        }
    }
}
