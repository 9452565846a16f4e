//! `loopsurf adapt`: adaptive Loop subdivision (Liu & Kondo), its summary and
//! Liu & Kondo's Table 1 for any mesh (`--report`).

use crate::input::Input;
use loopsurf::io::{self, DataArray};
use loopsurf::Adapter;
use loopsurf::{AdaptiveMesh, ControlNet, Error, Surface};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    /// Conical-angle threshold, degrees: vertices whose face normals spread
    /// less are flat, and stop refining once all their neighbours are. 0 is
    /// uniform subdivision.
    #[arg(long, value_name = "CA", allow_hyphen_values = true)]
    angle: Option<f64>,
    /// Also (or instead) stop where the mesh is within EPS × the
    /// bounding-box diagonal of the exact limit surface.
    #[arg(long, value_name = "EPS", allow_hyphen_values = true)]
    tolerance: Option<f64>,
    /// Number of subdivision levels (at most 10).
    #[arg(long, short = 'k', value_name = "K")]
    levels: u32,
    /// Keep the split triangles as they come (no edge swaps next to dead regions).
    #[arg(long)]
    no_realign: bool,
    /// Move every output vertex to its limit position on the surface.
    #[arg(long)]
    limit: bool,
    /// Skip measuring the distance of the output vertices to the limit
    /// surface (a snap per vertex).
    #[arg(long)]
    no_verify: bool,
    /// Print Liu & Kondo's Table 1 for this mesh: triangles per level for
    /// uniform and CA 7°, 11°, 22° (and --angle), reductions, minimum
    /// angle and distance to the limit surface.
    #[arg(long)]
    report: bool,
    /// Output file; the format follows the extension (.vtu .obj .off .stl
    /// .tri .ply); `.vtu` carries each vertex's (tri, v, w) and dead flag.
    #[arg(
        long,
        short = 'o',
        value_name = "OUT",
        required_unless_present = "report"
    )]
    output: Option<PathBuf>,
    /// Write .vtu with inline binary (base64) arrays instead of ASCII:
    /// about half the size, read by ParaView and meshio.
    #[arg(long)]
    binary: bool,
}

/// What one run gives: the mesh, its time, the distance of its vertices to
/// the limit surface (snap; unless --no-verify) and its minimum angle.
struct Run {
    mesh: AdaptiveMesh,
    seconds: f64,
    distance: Option<f64>,
    min_angle: f64,
}

fn run_once(
    net: &ControlNet,
    surface: &Surface,
    angle: Option<f64>,
    tolerance: Option<f64>,
    args: &Args,
) -> Result<Run, Error> {
    // The surface is this net's limit surface: the conical angle at hard
    // edges measures against it instead of building its own.
    let mut adapter = Adapter::new(net)
        .levels(args.levels)
        .realign(!args.no_realign)
        .limit_surface(surface);
    if let Some(a) = angle {
        adapter = adapter.angle(a);
    }
    if let Some(t) = tolerance {
        adapter = adapter.tolerance(surface, t);
    }
    let start = Instant::now();
    let mesh = adapter.run()?;
    let seconds = start.elapsed().as_secs_f64();
    Ok(Run {
        distance: match args.no_verify {
            true => None,
            false => Some(mesh.max_surface_distance(surface)? / net.bbox_diagonal()),
        },
        min_angle: mesh.min_angle(),
        mesh,
        seconds,
    })
}

pub fn run(args: Args) -> Result<(), Error> {
    if let Some(out) = &args.output {
        io::check_writable(out)?;
    }
    let net = args.input.load()?;
    let surface = Surface::new(&net)?;
    let main = match args.output {
        Some(_) => Some(run_once(&net, &surface, args.angle, args.tolerance, &args)?),
        None => None,
    };
    let report = if args.report {
        let mut angles = vec![0.0, 7.0, 11.0, 22.0];
        angles.extend(args.angle.filter(|a| !angles.contains(a)));
        let runs = angles
            .iter()
            .map(|&a| Ok((a, run_once(&net, &surface, Some(a), None, &args)?)))
            .collect::<Result<Vec<_>, Error>>()?;
        Some(runs)
    } else {
        None
    };
    if let (Some(run), Some(path)) = (&main, &args.output) {
        write_output(path, &surface, &run.mesh, args.limit, args.binary)?;
    }
    crate::write_stdout(|out| {
        writeln!(out, "{}", args.input.describe(&net))?;
        let input_angle = loopsurf::mesh::min_angle(net.points(), net.triangles());
        if let Some(run) = &main {
            summary(out, &net, run, input_angle)?;
            writeln!(out, "wrote {}", args.output.as_ref().unwrap().display())?;
        }
        if let Some(runs) = &report {
            table(out, &net, runs)?;
            writeln!(out, "input min angle: {input_angle:.2}°")?;
        }
        Ok(())
    })
}

fn uniform_count(net: &ControlNet, level: usize) -> usize {
    net.triangles().len() << (2 * level)
}

fn summary(
    out: &mut dyn Write,
    net: &ControlNet,
    run: &Run,
    input_angle: f64,
) -> std::io::Result<()> {
    let mesh = &run.mesh;
    for (level, c) in mesh.counts.iter().enumerate().skip(1) {
        let uniform = uniform_count(net, level);
        writeln!(
            out,
            "level {level}: {} triangles, {} dead (uniform {uniform}: {:.2}% fewer)",
            c.triangles,
            c.dead_triangles,
            100.0 * (1.0 - c.triangles as f64 / uniform as f64)
        )?;
    }
    let n = mesh.net.triangles().len();
    writeln!(
        out,
        "output: {} vertices, {n} triangles, {} hard edges in {:.3} s ({:.2}M triangles/s)",
        mesh.net.points().len(),
        mesh.net.features().num_hard_edges(),
        run.seconds,
        n as f64 / run.seconds.max(1e-12) / 1e6
    )?;
    writeln!(
        out,
        "min angle: {:.2}° (input: {input_angle:.2}°)",
        run.min_angle
    )?;
    match run.distance {
        Some(d) => writeln!(
            out,
            "max distance of the vertices to the limit surface: {d:.3e} of the diagonal (by snap)"
        ),
        None => Ok(()),
    }
}

/// Liu & Kondo's Table 1: triangles per level, reductions against uniform,
/// and the last level's minimum angle and distance to the surface.
fn table(out: &mut dyn Write, net: &ControlNet, runs: &[(f64, Run)]) -> std::io::Result<()> {
    let levels = runs[0].1.mesh.counts.len() - 1;
    write!(out, "| |")?;
    for level in 1..=levels {
        write!(out, " level {level} |")?;
    }
    writeln!(out, " min angle | max distance to the limit surface |")?;
    writeln!(out, "|---|{}---|---|", "---|".repeat(levels))?;
    for (angle, run) in runs {
        let counts = &run.mesh.counts;
        if *angle == 0.0 {
            write!(out, "| uniform Loop |")?;
        } else {
            write!(out, "| CA = {angle}° |")?;
        }
        for (level, c) in counts.iter().enumerate().skip(1) {
            let reduction = 1.0 - c.triangles as f64 / uniform_count(net, level) as f64;
            if *angle == 0.0 {
                write!(out, " {} |", c.triangles)?;
            } else {
                write!(out, " {} ({:.2}% fewer) |", c.triangles, 100.0 * reduction)?;
            }
        }
        let distance = run
            .distance
            .map_or("not measured".into(), |d| format!("{d:.2e}"));
        writeln!(out, " {:.2}° | {distance} |", run.min_angle)?;
    }
    Ok(())
}

/// The mesh in OUT's format; `.vtu` adds per-vertex (tri, v, w) and dead
/// flags and per-cell dead flags and minimum angles.
fn write_output(
    path: &Path,
    surface: &Surface,
    mesh: &AdaptiveMesh,
    limit: bool,
    binary: bool,
) -> Result<(), Error> {
    let points = if limit {
        mesh.limit_points(surface)?
    } else {
        mesh.net.points().to_vec()
    };
    let tris = mesh.net.triangles();
    let is_vtu = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("vtu"));
    if !is_vtu {
        return io::write_mesh(path, &points, tris);
    }
    let tri: Vec<i32> = mesh.params.iter().map(|p| p.tri as i32).collect();
    let v: Vec<f64> = mesh.params.iter().map(|p| p.v).collect();
    let w: Vec<f64> = mesh.params.iter().map(|p| p.w).collect();
    let dead: Vec<i32> = mesh.dead.iter().map(|&d| d as i32).collect();
    let dead_cell: Vec<i32> = tris
        .iter()
        .map(|t| t.iter().all(|&i| mesh.dead[i as usize]) as i32)
        .collect();
    io::write_vtu(
        path,
        &points,
        tris,
        &[
            ("tri", DataArray::I32(&tri)),
            ("v", DataArray::F64(&v)),
            ("w", DataArray::F64(&w)),
            ("dead", DataArray::I32(&dead)),
        ],
        &[("dead", DataArray::I32(&dead_cell))],
        binary,
    )
}
