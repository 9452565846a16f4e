//! `loopsurf interpolate`: control points whose limit surface passes
//! through the mesh's points, written to a file, with a fairness report.

use crate::input::Input;
use loopsurf::fairness::fairness;
use loopsurf::interpolate::solve;
use loopsurf::{io, Error};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    /// Output file for the solved net; the format follows the extension
    /// (.obj .off .stl .tri .vtu). Vertices and triangles keep their order.
    #[arg(long, short = 'o', value_name = "OUT")]
    output: PathBuf,
    /// Also write the hard edges (`i j` lines, for --hard-edges): the solved
    /// net's dihedral angles differ, so --hard-angle would not find the same ones.
    #[arg(long, value_name = "FILE")]
    write_hard_edges: Option<PathBuf>,
    /// Write .vtu with inline binary (base64) arrays instead of ASCII:
    /// about half the size, read by ParaView and meshio.
    #[arg(long)]
    binary: bool,
}

pub fn run(args: Args) -> Result<(), Error> {
    io::check_writable(&args.output)?;
    let net = args.input.load()?;
    let start = Instant::now();
    let solved = solve(&net)?;
    let seconds = start.elapsed().as_secs_f64();
    io::write_mesh_as(
        &args.output,
        solved.points(),
        solved.triangles(),
        args.binary,
    )?;
    if let Some(path) = &args.write_hard_edges {
        let text: String = net
            .hard_edges()
            .iter()
            .map(|[a, b]| format!("{a} {b}\n"))
            .collect();
        std::fs::write(path, text).map_err(|source| Error::Io {
            path: path.clone(),
            source,
        })?;
    }
    let report = fairness(&net, &solved)?;
    crate::write_stdout(|out| {
        writeln!(
            out,
            "solved {} control points in {seconds:.3} s (sparse LU); wrote {}",
            net.points().len(),
            args.output.display()
        )?;
        writeln!(
            out,
            "residual: {:.2e} of the bounding-box diagonal",
            report.residual
        )?;
        writeln!(
            out,
            "largest move of a control point: {:.3} of its mean edge length (vertex {})",
            report.max_displacement, report.max_displacement_vertex
        )?;
        writeln!(
            out,
            "largest turn of the normal at an original point: {:.2}° (vertex {})",
            report.max_normal_change, report.max_normal_change_vertex
        )
    })?;
    for warning in report.warnings() {
        eprintln!("loopsurf: warning: {warning}");
    }
    Ok(())
}
