//! `loopsurf snap`: lines `x y z` on stdin, one line `tri v w x y z
//! distance` per query on stdout — the closest point of the limit surface,
//! written so it reads back bit-exact.

use crate::input::{Input, SurfaceOptions};
use crate::queries;
use loopsurf::{DVec3, Error};

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
        "x y z",
        |[x, y, z]| surface.closest_point(DVec3::new(x, y, z)),
        |out, s| {
            write!(out, "{} ", s.tri)?;
            let [x, y, z] = s.point.to_array();
            queries::write_numbers(out, &[s.v, s.w, x, y, z, s.distance])
        },
    )
}
