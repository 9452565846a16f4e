//! The text format of the query lines `loopsurf eval` and `loopsurf snap`
//! read on stdin and of the numbers they write, apart from the command
//! (src/main.rs, whose `queries` module runs the loop) so that it can be
//! fuzzed: fuzz/fuzz_targets/queries.rs, whose kept inputs
//! tests/query_lines.rs replays.

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
