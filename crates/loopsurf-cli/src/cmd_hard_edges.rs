//! `loopsurf hard-edges`: the hard edges, one `i j` line each.

use crate::input::Input;
use loopsurf::Error;
use std::io::Write;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
}

pub fn run(args: Args) -> Result<(), Error> {
    let net = args.input.load()?;
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    for [a, b] in net.hard_edges() {
        // A closed pipe (e.g. `| head`) is not an error worth reporting.
        if writeln!(out, "{a} {b}").is_err() {
            return Ok(());
        }
    }
    let _ = out.flush();
    Ok(())
}
