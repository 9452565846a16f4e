//! `loopsurf eval`: lines `tri v w` on stdin, one line of 18 numbers
//! (X Xv Xw Xvv Xvw Xww) per query on stdout, written so they read back
//! bit-exact. With `--edge`: lines `edge t` (a model edge, i.e. curve, of
//! `loopsurf topology`, and its parameter in [0, n]), 9 numbers X X′ X″ per
//! line. With `--parts K --part P`: only part P's surface is built, and
//! triangles are given by their ids in the whole net; one the part does not
//! own is an error naming its owner.

use crate::input::{Input, SurfaceOptions};
use crate::part_options::PartOptions;
use crate::queries;
use loopsurf::{Error, LimitCurve};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    #[command(flatten)]
    surface: SurfaceOptions,
    #[command(flatten)]
    part: PartOptions,
    /// Evaluate model edges (curves, ids as `loopsurf topology` prints
    /// them) instead: lines `edge t`, t in [0, n] over the edge's n control
    /// edges, answered with X X' X'' (9 numbers).
    #[arg(long, conflicts_with = "parts")]
    edge: bool,
}

pub fn run(args: Args) -> Result<(), Error> {
    let net = args.input.load()?;
    if let Some(selected) = args.part.select(&net)? {
        // Global triangle ids in, the part's own surface behind them.
        let surface = args.surface.build_part(selected.part.net())?;
        return queries::run(
            "tri v w",
            |[t, v, w]| {
                let local = selected.owned(whole(t, "triangle")?)?;
                Ok(surface.eval(local, v, w)?.record())
            },
            |out, record| queries::write_numbers(out, &record),
        );
    }
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
