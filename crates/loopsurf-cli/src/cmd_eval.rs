//! `loopsurf eval`: lines `tri v w` on stdin, one line of 18 numbers
//! (X Xv Xw Xvv Xvw Xww) per query on stdout, written so they read back
//! bit-exact.

use crate::input::{Input, SurfaceOptions};
use loopsurf::Error;
use rayon::prelude::*;
use std::io::BufRead;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    #[command(flatten)]
    surface: SurfaceOptions,
}

/// Queries evaluated together (in parallel) before their results are written.
const CHUNK: usize = 1 << 16;

pub fn run(args: Args) -> Result<(), Error> {
    let net = args.input.load()?;
    let surface = args.surface.build(&net)?;
    let stdin = std::io::stdin();
    let mut lines = stdin.lock().lines().enumerate();
    crate::write_stdout(|out| {
        let mut chunk: Vec<(usize, u32, f64, f64)> = Vec::with_capacity(CHUNK);
        loop {
            chunk.clear();
            for (i, line) in lines.by_ref() {
                let line = line?;
                if let Some(q) = parse(i + 1, &line).map_err(invalid_data)? {
                    chunk.push(q);
                    if chunk.len() == CHUNK {
                        break;
                    }
                }
            }
            if chunk.is_empty() {
                return Ok(());
            }
            let results: Vec<Result<[f64; 18], Error>> = chunk
                .par_iter()
                .map(|&(line, t, v, w)| {
                    surface
                        .eval(t as usize, v, w)
                        .map(|e| e.record())
                        .map_err(|e| Error::Malformed {
                            line,
                            message: e.to_string(),
                        })
                })
                .collect();
            for r in results {
                let record = r.map_err(invalid_data)?;
                let text: Vec<String> = record.iter().map(|x| format!("{x:e}")).collect();
                writeln!(out, "{}", text.join(" "))?;
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

/// A query line `tri v w`; blank lines and `#` comments are skipped.
fn parse(line: usize, text: &str) -> Result<Option<(usize, u32, f64, f64)>, Error> {
    let content = text.split('#').next().unwrap_or("").trim();
    if content.is_empty() {
        return Ok(None);
    }
    let bad = || Error::Malformed {
        line,
        message: format!("expected `tri v w`, got '{content}'"),
    };
    let mut fields = content.split_whitespace();
    let (Some(t), Some(v), Some(w), None) =
        (fields.next(), fields.next(), fields.next(), fields.next())
    else {
        return Err(bad());
    };
    let t = t.parse::<u32>().map_err(|_| bad())?;
    let (v, w) = (
        v.parse::<f64>().map_err(|_| bad())?,
        w.parse::<f64>().map_err(|_| bad())?,
    );
    Ok(Some((line, t, v, w)))
}
