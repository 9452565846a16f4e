//! `loopsurf fit`: a new control net whose limit surface passes within a
//! tolerance of the mesh's vertices, with creases on its feature lines
//! (`loopsurf::fit`), written with its hard edges and corners, and the
//! fit's report.

use crate::input::Input;
use loopsurf::fit::{Fit, Fitter};
use loopsurf::{io, ControlNet, Error};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    /// Control-edge length of the fitted net, model units (default 0.01 of
    /// the bounding-box diagonal; remeshed at twice it, subdivided once).
    #[arg(long, value_name = "H", allow_negative_numbers = true)]
    resolution: Option<f64>,
    /// Largest distance from the fitted surface to an input vertex, as a
    /// fraction of the bounding-box diagonal (default 1e-4); a fit that
    /// misses it is refused, naming the vertex.
    #[arg(long, value_name = "EPS", allow_negative_numbers = true)]
    tolerance: Option<f64>,
    /// Output file for the fitted control net (.obj .off .stl .tri .vtu).
    /// Its hard edges go next to it as OUT.hard-edges (`i j` lines, for
    /// --hard-edges) and its tagged corners, if any, as OUT.corners (for
    /// --hard-vertices).
    #[arg(long, short = 'o', value_name = "OUT")]
    output: PathBuf,
    /// Write .vtu with inline binary (base64) arrays instead of ASCII:
    /// about half the size, read by ParaView and meshio.
    #[arg(long)]
    binary: bool,
}

/// Runs a fit with the given options.
pub fn fit(
    net: &ControlNet,
    resolution: Option<f64>,
    tolerance: Option<f64>,
) -> Result<Fit, Error> {
    let mut fitter = Fitter::new(net);
    if let Some(h) = resolution {
        fitter = fitter.resolution(h);
    }
    if let Some(eps) = tolerance {
        fitter = fitter.tolerance(eps);
    }
    fitter.run()
}

/// The report as lines.
pub fn report_lines(fit: &Fit) -> Vec<String> {
    let r = &fit.report;
    vec![
        format!(
            "fitted net: {} control points, {} triangles, smallest angle {:.1}°; {} rounds in {:.2} s",
            r.control_vertices, r.control_triangles, r.min_angle, r.rounds, r.seconds
        ),
        format!(
            "kept as corners: {} apexes, {} crease kinks",
            r.apexes, r.kinks
        ),
        format!(
            "distance to the input vertices: max {:.2e} (vertex {}), mean {:.2e} of the diagonal",
            r.vertices.max, r.vertices.worst, r.vertices.mean
        ),
        format!(
            "distance to the input edge midpoints: max {:.2e} (edge {}), mean {:.2e} of the diagonal",
            r.midpoints.max, r.midpoints.worst, r.midpoints.mean
        ),
        format!(
            "largest turn of the normal across a control edge: {:.2}°; mean curvature from {:.4} to {:.4}",
            r.max_normal_turn, r.mean_curvature.0, r.mean_curvature.1
        ),
    ]
}

fn sibling(path: &Path, extension: &str) -> PathBuf {
    path.with_extension(extension)
}

fn write_lines(path: &Path, lines: impl Iterator<Item = String>) -> Result<(), Error> {
    let text: String = lines.map(|l| l + "\n").collect();
    std::fs::write(path, text).map_err(|source| Error::Io {
        path: path.to_owned(),
        source,
    })
}

pub fn run(args: Args) -> Result<(), Error> {
    io::check_writable(&args.output)?;
    let net = args.input.load()?;
    let fit = fit(&net, args.resolution, args.tolerance)?;
    let fitted = &fit.net;
    io::write_mesh_as(
        &args.output,
        fitted.points(),
        fitted.triangles(),
        args.binary,
    )?;
    let edges = sibling(&args.output, "hard-edges");
    write_lines(
        &edges,
        fitted.hard_edges().iter().map(|[a, b]| format!("{a} {b}")),
    )?;
    let corners: Vec<usize> = (0..fitted.points().len())
        .filter(|&v| fitted.features().is_tagged_vertex(v))
        .collect();
    if !corners.is_empty() {
        write_lines(
            &sibling(&args.output, "corners"),
            corners.iter().map(|v| v.to_string()),
        )?;
    }
    crate::write_stdout(|out| {
        for line in report_lines(&fit) {
            writeln!(out, "{line}")?;
        }
        writeln!(
            out,
            "wrote {} and {}",
            args.output.display(),
            edges.display()
        )
    })
}
