//! `loopsurf eval`: lines `tri v w` on stdin, one line of 18 numbers
//! (X Xv Xw Xvv Xvw Xww) per query on stdout, written so they read back
//! bit-exact. With `--edge`: lines `edge t` (a model edge, i.e. curve, of
//! `loopsurf topology`, and its parameter in [0, n]), 9 numbers X X′ X″ per
//! line.

use crate::input::{Input, SurfaceOptions};
use crate::queries;
use loopsurf::{Error, LimitCurve};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    #[command(flatten)]
    surface: SurfaceOptions,
    /// Evaluate model edges (curves, ids as `loopsurf topology` prints
    /// them) instead: lines `edge t`, t in [0, n] over the edge's n control
    /// edges, answered with X X' X'' (9 numbers).
    #[arg(long)]
    edge: bool,
}

pub fn run(args: Args) -> Result<(), Error> {
    let net = args.input.load()?;
    let surface = args.surface.build(&net)?;
    if args.edge {
        return queries::run(
            "edge t",
            |[c, t]| {
                let c = whole(c, "edge")?;
                Ok(LimitCurve::new(&surface, c)?.eval(t)?.record())
            },
            |out, record| queries::write_numbers(out, &record),
        );
    }
    queries::run(
        "tri v w",
        |[t, v, w]| Ok(surface.eval(whole(t, "triangle")?, v, w)?.record()),
        |out, record| queries::write_numbers(out, &record),
    )
}

/// An index read as a number: whole and ≥ 0.
fn whole(x: f64, what: &str) -> Result<usize, Error> {
    if x.fract() != 0.0 || !(0.0..=u32::MAX as f64).contains(&x) {
        return Err(Error::InvalidArgument(format!(
            "{what} index {x} is not a whole number ≥ 0"
        )));
    }
    Ok(x as usize)
}
