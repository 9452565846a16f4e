//! The `loopsurf` command: translates arguments into library calls and
//! library results into text. No geometry lives here.

mod cmd_adapt;
mod cmd_curve;
mod cmd_eval;
mod cmd_fit;
mod cmd_hard_edges;
mod cmd_info;
mod cmd_interpolate;
mod cmd_mesh;
mod cmd_partition;
mod cmd_refine;
mod cmd_snap;
mod cmd_topology;
mod curved_output;
mod input;
mod out_of_memory;
mod part_options;
mod queries;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[global_allocator]
static ALLOCATOR: out_of_memory::ExitWhenExhausted = out_of_memory::ExitWhenExhausted;

/// Exact Loop subdivision surfaces from legacy triangulations.
#[derive(Parser)]
#[command(name = "loopsurf", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Counts, valences, boundaries, hard features and the limit deviation of a control net.
    Info(cmd_info::Args),
    /// Prints every hard edge (boundary edges included) as a line `i j`, i < j, 0-based.
    HardEdges(cmd_hard_edges::Args),
    /// Uniform Loop refinement; the output format follows OUT's extension.
    Refine(cmd_refine::Args),
    /// Adaptive Loop subdivision by conical angle (Liu & Kondo) or distance to the limit surface; conforming.
    Adapt(cmd_adapt::Args),
    /// Exact evaluation: reads `tri v w` lines on stdin, writes X Xv Xw Xvv Xvw Xww (18 numbers) per line;
    /// with --edge, `edge t` lines and X X' X'' (9 numbers) of that model edge (curve).
    Eval(cmd_eval::Args),
    /// Solves for control points whose limit surface passes through the mesh's points; writes them and a fairness report.
    Interpolate(cmd_interpolate::Args),
    /// Fits a new, well-shaped control net whose limit surface passes within a tolerance of the mesh's vertices,
    /// creases on its feature lines; writes it with its hard edges and prints the fit's report.
    Fit(cmd_fit::Args),
    /// The surface mesher: a triangulation of the limit surface within a tolerance, hard edges kept;
    /// curved (P2–P4) with --order.
    Mesh(cmd_mesh::Args),
    /// Curves another tool's linear mesh: its vertices snapped onto the surface, high-order nodes on it.
    Curve(cmd_curve::Args),
    /// Closest points: reads `x y z` lines on stdin, writes `tri v w x y z distance` per line.
    Snap(cmd_snap::Args),
    /// The model of the hard features: faces, edges (curves) with their corners and control-vertex chains.
    Topology(cmd_topology::Args),
    /// The control triangles in K parts (METIS) for K processes: edge cut, part sizes and halos.
    Partition(cmd_partition::Args),
}

/// Runs `write` against a buffered, locked stdout. A reader that stops
/// early (`| head`) is not an error; any other write failure is.
pub fn write_stdout(
    write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> Result<(), loopsurf::Error> {
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    match write(&mut out).and_then(|()| std::io::Write::flush(&mut out)) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(loopsurf::Error::Io {
            path: "<stdout>".into(),
            source: e,
        }),
        _ => Ok(()),
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(err) if !err.use_stderr() => {
            // --help and --version.
            let _ = err.print();
            return ExitCode::SUCCESS;
        }
        Err(err) => {
            // One line, like every other error: clap's message without its
            // usage and help hints.
            let text = err.to_string();
            let message: Vec<&str> = text
                .lines()
                .take_while(|l| !l.is_empty() && !l.starts_with("Usage:"))
                .map(str::trim)
                .collect();
            eprintln!(
                "loopsurf: {}",
                message.join(" ").trim_start_matches("error: ")
            );
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Command::Info(args) => cmd_info::run(args),
        Command::HardEdges(args) => cmd_hard_edges::run(args),
        Command::Refine(args) => cmd_refine::run(args),
        Command::Adapt(args) => cmd_adapt::run(args),
        Command::Eval(args) => cmd_eval::run(args),
        Command::Interpolate(args) => cmd_interpolate::run(args),
        Command::Fit(args) => cmd_fit::run(args),
        Command::Snap(args) => cmd_snap::run(args),
        Command::Mesh(args) => cmd_mesh::run(args),
        Command::Curve(args) => cmd_curve::run(args),
        Command::Topology(args) => cmd_topology::run(args),
        Command::Partition(args) => cmd_partition::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("loopsurf: {err}");
            ExitCode::from(2)
        }
    }
}
