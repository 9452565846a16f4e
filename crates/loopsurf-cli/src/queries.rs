//! The stdin → stdout loop shared by `eval` and `snap`: one query per line,
//! answered in parallel chunks, answers written in input order. A bad line
//! stops the run with an error naming its line number.

use loopsurf::Error;
use loopsurf_cli::parse_query;
pub use loopsurf_cli::write_numbers;
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
                if let Some(q) = parse_query::<N>(i + 1, &line, expected).map_err(invalid_data)? {
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
