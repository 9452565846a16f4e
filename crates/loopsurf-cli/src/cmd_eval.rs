//! `loopsurf eval`: lines `tri v w` on stdin, one line of 18 numbers
//! (X Xv Xw Xvv Xvw Xww) per query on stdout, written so they read back
//! bit-exact.

use crate::input::{Input, SurfaceOptions};
use crate::queries;
use loopsurf::Error;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    #[command(flatten)]
    surface: SurfaceOptions,
}

pub fn run(args: Args) -> Result<(), Error> {
    let net = args.input.load()?;
    let surface = args.surface.build(&net)?;
    queries::run(
        "tri v w",
        |[t, v, w]| {
            if t.fract() != 0.0 || !(0.0..=u32::MAX as f64).contains(&t) {
                return Err(Error::InvalidArgument(format!(
                    "triangle index {t} is not a whole number ≥ 0"
                )));
            }
            Ok(surface.eval(t as usize, v, w)?.record())
        },
        |out, record| queries::write_numbers(out, &record),
    )
}
