//! `loopsurf refine`: uniform Loop refinement written to a file.

use crate::input::Input;
use loopsurf::io::{self, DataArray};
use loopsurf::refine::refine_uniform;
use loopsurf::Error;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    /// Number of refinement levels (each multiplies the triangles by four).
    #[arg(long, short = 'k', value_name = "K")]
    levels: u32,
    /// Move every refined vertex to its limit position on the surface.
    #[arg(long)]
    limit: bool,
    /// Output file; the format follows the extension (.obj .off .stl .tri .vtu).
    #[arg(long, short = 'o', value_name = "OUT")]
    output: PathBuf,
    /// Write .vtu with inline binary (base64) arrays instead of ASCII:
    /// about half the size, read by ParaView and meshio.
    #[arg(long)]
    binary: bool,
}

pub fn run(args: Args) -> Result<(), Error> {
    io::check_writable(&args.output)?;
    let net = args.input.load()?;
    let start = Instant::now();
    let refined = refine_uniform(&net, args.levels)?;
    let refined_net = refined.net();
    let seconds = start.elapsed().as_secs_f64();
    let points = if args.limit {
        refined.limit_points()
    } else {
        refined_net.points().to_vec()
    };
    let tris = refined_net.triangles();
    let is_vtu = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("vtu"));
    if is_vtu {
        // Where each vertex sits on the control net, for ParaView.
        let origins: Vec<_> = refined.origins().collect();
        let tri: Vec<i32> = origins
            .iter()
            .map(|o| o.map_or(-1, |o| o.tri as i32))
            .collect();
        let v: Vec<f64> = origins.iter().map(|o| o.map_or(-1.0, |o| o.v)).collect();
        let w: Vec<f64> = origins.iter().map(|o| o.map_or(-1.0, |o| o.w)).collect();
        let shift = 2 * args.levels;
        let control: Vec<i32> = (0..tris.len()).map(|t| (t >> shift) as i32).collect();
        io::write_vtu(
            &args.output,
            &points,
            tris,
            &[
                ("tri", DataArray::I32(&tri)),
                ("v", DataArray::F64(&v)),
                ("w", DataArray::F64(&w)),
            ],
            &[("control_tri", DataArray::I32(&control))],
            args.binary,
        )?;
    } else {
        io::write_mesh_as(&args.output, &points, tris, args.binary)?;
    }
    eprintln!(
        "refined {} levels{}: {} vertices, {} triangles, {} hard edges in {:.3} s ({:.2}M triangles/s); wrote {}",
        args.levels,
        if args.limit { " (limit positions)" } else { "" },
        points.len(),
        tris.len(),
        refined_net.features().num_hard_edges(),
        seconds,
        tris.len() as f64 / seconds.max(1e-12) / 1e6,
        args.output.display()
    );
    Ok(())
}
