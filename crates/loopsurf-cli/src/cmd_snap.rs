//! `loopsurf snap`: lines `x y z` on stdin, one line `tri v w x y z
//! distance` per query on stdout — the closest point of the limit surface,
//! the global minimum of the distance, written so it reads back bit-exact.
//! With `--certificate` an eighth column gives the proven lower bound on
//! the distance to the surface.

use crate::input::{Input, SurfaceOptions};
use crate::queries;
use loopsurf::snap;
use loopsurf::{DVec3, Error};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    #[command(flatten)]
    surface: SurfaceOptions,
    /// Also write the certificate: a proven lower bound on the distance
    /// from the point to the whole surface (eighth column).
    #[arg(long)]
    certificate: bool,
    /// How close the certificate must come to the distance, as a fraction
    /// of the bounding-box diagonal (looser is faster).
    #[arg(long, value_name = "EPS", default_value_t = loopsurf::snap::DEFAULT_TOLERANCE)]
    tolerance: f64,
}

pub fn run(args: Args) -> Result<(), Error> {
    let net = args.input.load()?;
    let surface = args.surface.build(&net)?;
    let certificate = args.certificate;
    // A bad tolerance is reported before any input is read.
    snap::closest_point_within(&surface, net.points()[0], args.tolerance)?;
    queries::run(
        "x y z",
        |[x, y, z]| snap::closest_point_within(&surface, DVec3::new(x, y, z), args.tolerance),
        |out, s| {
            write!(out, "{} ", s.tri)?;
            let [x, y, z] = s.point.to_array();
            if certificate {
                queries::write_numbers(out, &[s.v, s.w, x, y, z, s.distance, s.lower_bound])
            } else {
                queries::write_numbers(out, &[s.v, s.w, x, y, z, s.distance])
            }
        },
    )
}
