//! `loopsurf hard-edges`: the hard edges, one `i j` line each.

use crate::input::Input;
use loopsurf::Error;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
}

pub fn run(args: Args) -> Result<(), Error> {
    let net = args.input.load()?;
    crate::write_stdout(|out| {
        for [a, b] in net.hard_edges() {
            writeln!(out, "{a} {b}")?;
        }
        Ok(())
    })
}
