//! The stdin → stdout loop shared by `eval` and `snap`: one query per line,
//! answered in parallel chunks, answers written in input order. A bad line
//! stops the run with an error naming its line number.

use loopsurf::Error;
use rayon::prelude::*;
use std::io::{BufRead, Write};

/// Queries answered together (in parallel) before their results are written.
const CHUNK: usize = 1 << 16;

/// Reads `expected`-shaped lines of `N` numbers from stdin (blank lines and
/// `#` comments skipped), answers each with `answer`, writes each answer
/// with `write`.
pub fn run<const N: usize, R: Send>(
    expected: &str,
    answer: impl Fn([f64; N]) -> Result<R, Error> + Sync,
    write: impl Fn(&mut dyn Write, R) -> std::io::Result<()>,
) -> Result<(), Error> {
    let stdin = std::io::stdin();
    let mut lines = stdin.lock().lines().enumerate();
    crate::write_stdout(|out| {
        let mut chunk: Vec<(usize, [f64; N])> = Vec::with_capacity(CHUNK);
        loop {
            chunk.clear();
            for (i, line) in lines.by_ref() {
                let line = line?;
                if let Some(q) = parse::<N>(i + 1, &line, expected).map_err(invalid_data)? {
                    chunk.push((i + 1, q));
                    if chunk.len() == CHUNK {
                        break;
                    }
                }
            }
            if chunk.is_empty() {
                return Ok(());
            }
            let results: Vec<Result<R, Error>> = chunk
                .par_iter()
                .map(|&(line, q)| {
                    answer(q).map_err(|e| Error::Malformed {
                        line,
                        message: e.to_string(),
                    })
                })
                .collect();
            for r in results {
                write(out, r.map_err(invalid_data)?)?;
            }
        }
    })
    .map_err(|e| match e {
        // A bad line is reported as itself, not as a failed write.
        Error::Io { source, .. } if source.kind() == std::io::ErrorKind::InvalidData => source
            .into_inner()
            .and_then(|inner| inner.downcast::<Error>().ok())
            .map(|b| b.in_file("<stdin>", None))
            .unwrap_or_else(|| Error::InvalidArgument("bad input".into())),
        other => other,
    })
}

fn invalid_data(e: Error) -> std::io::Error {
    std::io::Error::new(std::io::ErrorKind::InvalidData, e)
}

/// One line of N numbers, or None for a blank or comment line.
fn parse<const N: usize>(
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
