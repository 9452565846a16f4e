//! `loopsurf mesh`: the surface mesher, its output files and its summary.

use crate::curved_output::{self, CurvedFormat};
use crate::input::{Input, SurfaceOptions};
use indicatif::{ProgressBar, ProgressStyle};
use loopsurf::io::{self, DataArray};
use loopsurf::{Density, Error, Mesher, Remesher, Surface, SurfaceMesh};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    #[command(flatten)]
    surface: SurfaceOptions,
    /// Chord tolerance: every output triangle within EPS × the bounding-box
    /// diagonal of the surface (at centroids and edge midpoints). The
    /// remesher then sizes by curvature (as --adapt curvature), capped by
    /// --size if given.
    #[arg(long, value_name = "EPS", allow_hyphen_values = true)]
    tolerance: Option<f64>,
    /// Target edge length, in model units.
    #[arg(
        long,
        value_name = "H",
        conflicts_with = "uniform",
        allow_negative_numbers = true
    )]
    size: Option<f64>,
    /// Cut every control edge into N segments (N² triangles per control
    /// triangle; the chart mesher, implies --charts).
    #[arg(long, value_name = "N")]
    uniform: Option<u32>,
    /// The chart mesher: every output triangle inside one control triangle,
    /// shaped like it (fast; the triangles copy the control net's shapes).
    /// Without it, the quality remesher.
    #[arg(long)]
    charts: bool,
    /// Largest ratio of neighbouring sizes per edge where sizes vary
    /// (--adapt or --tolerance; remesher).
    #[arg(long, value_name = "G", default_value_t = loopsurf::remesh::DEFAULT_GRADATION)]
    gradation: f64,
    /// Let the density follow curvature, bounded by the tolerance (1e-3 if
    /// none is given) and, with --size, by the edge length. The remesher's
    /// default when neither --size nor --tolerance is given.
    #[arg(long, value_enum, value_name = "HOW")]
    adapt: Option<Adapt>,
    /// The most output triangles: a density asking for more stops with an
    /// error saying how many, before the memory is spent (default: 20
    /// million for the remesher, about 8 GB whole on a small net and more
    /// in parts on a large one; 200 million for --charts).
    #[arg(long, value_name = "N")]
    max_triangles: Option<usize>,
    /// Remesh in K parts of the control net (METIS), each on its own
    /// core, joined along the interfaces meshed first; the mesh is the
    /// same for any thread count (RAYON_NUM_THREADS). 1 remeshes whole.
    /// Default: one part per 30 000 triangles the sizes ask for (at most
    /// 64, each of at least 16 control triangles), rounded down to a
    /// power of two, whole below 60 000; the summary says how many.
    #[arg(long, value_name = "K", conflicts_with = "charts")]
    parts: Option<usize>,
    /// Skip the max–min angle edge swaps (--charts).
    #[arg(long)]
    no_swaps: bool,
    /// Skip re-measuring the chord error with snap (the true distance).
    #[arg(long)]
    no_verify: bool,
    /// Output file; the format follows the extension (.msh .vtu .obj .stl .tri .off .ply).
    #[arg(long, short = 'o', value_name = "OUT")]
    output: PathBuf,
    /// Curved Lagrange triangles of order K (1 to 4) with every node on the
    /// surface; K > 1 needs a .msh (gmsh 4.1) or .vtu (VTK Lagrange) output.
    #[arg(long, value_name = "K", default_value_t = 1)]
    order: usize,
    /// Write .msh in gmsh's binary format, and .vtu with inline binary
    /// (base64) arrays, instead of ASCII.
    #[arg(long)]
    binary: bool,
    /// Also write one `tri v w` line per output vertex, in output order.
    #[arg(long, value_name = "FILE")]
    write_params: Option<PathBuf>,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum Adapt {
    Curvature,
}

pub fn run(args: Args) -> Result<(), Error> {
    curved_output::check_output(&args.output, args.order)?;
    let net = args.input.load()?;
    let surface = args.surface.build(&net)?;
    let start = Instant::now();
    let charts = args.charts || args.uniform.is_some();
    let (mesh, parts, smallest) = if charts {
        (chart_mesh(&args, &surface)?, 1, None)
    } else {
        remesh(&args, &surface)?
    };
    let meshing = start.elapsed().as_secs_f64();
    let snapped = if args.no_verify {
        None
    } else {
        let spinner = ProgressBar::new_spinner().with_message("checking the chord error with snap");
        spinner.enable_steady_tick(std::time::Duration::from_millis(200));
        let d = mesh.snap_deviation(&surface)?;
        spinner.finish_and_clear();
        Some(d)
    };
    let crossings = mesh.crossings();
    let checked = start.elapsed().as_secs_f64();
    // A .msh and any order above 1 go out as Lagrange elements.
    let curved = if args.order > 1 || CurvedFormat::of(&args.output) == Some(CurvedFormat::Msh) {
        let curved = mesh.raise_order(&surface, args.order)?;
        let validity = curved.validity();
        curved_output::write_curved(&args.output, &curved, &validity, args.binary)?;
        Some((curved, validity))
    } else {
        write_output(&args.output, &surface, &mesh, args.binary)?;
        None
    };
    if let Some(path) = &args.write_params {
        write_params(path, &mesh)?;
    }
    let times = Times {
        meshing,
        checking: checked - meshing,
        total: start.elapsed().as_secs_f64(),
    };
    warn_of_surface_folds(&surface, &mesh);
    warn_of_crossings(&surface, &mesh, &crossings);
    crate::write_stdout(|out| {
        writeln!(out, "{}", args.input.describe(&net))?;
        summary(out, &mesh, &times, snapped)?;
        if let Some(size) = smallest {
            short_edges(out, &mesh, size)?;
        }
        if parts > 1 {
            let how = match args.parts {
                Some(_) => "as --parts asks",
                None => "one per 30 000 triangles the sizes ask for, down to a power of two; --parts 1 remeshes whole",
            };
            writeln!(out, "parts: {parts} ({how})")?;
        }
        writeln!(
            out,
            "crossings: {}",
            match crossings.len() {
                0 => "none (no two triangles meet but at the vertices and edges they share)"
                    .to_string(),
                n => format!("{n} pairs of triangles meet (see the warning)"),
            }
        )?;
        if let Some((curved, validity)) = &curved {
            curved_output::summary(out, curved, validity)?;
        }
        writeln!(out, "wrote {}", args.output.display())
    })
}

/// The quality remesher's mesh, with a spinner. With no density at all,
/// the curvature-adaptive mesh at the default tolerance: the mesh a user
/// asking for "a mesh" expects. Also the number of parts it was made in,
/// and the smallest size it asked for anywhere.
fn remesh(args: &Args, surface: &Surface) -> Result<(SurfaceMesh, usize, Option<f64>), Error> {
    let adapt = args.adapt.is_some() || (args.size.is_none() && args.tolerance.is_none());
    let mut remesher = Remesher::new(surface)
        .adapt_curvature(adapt)
        .gradation(args.gradation);
    if let Some(h) = args.size {
        remesher = remesher.size(h);
    }
    if let Some(eps) = args.tolerance {
        remesher = remesher.tolerance(eps);
    }
    if let Some(n) = args.max_triangles {
        remesher = remesher.max_triangles(n);
    }
    let parts = match args.parts {
        Some(k) => k,
        None => remesher.suggested_parts()?,
    };
    remesher = remesher.parts(parts);
    let spinner = ProgressBar::new_spinner().with_message("remeshing");
    spinner.enable_steady_tick(std::time::Duration::from_millis(200));
    let mesh = remesher.run()?;
    spinner.finish_and_clear();
    // The remesher returns its best mesh even where a few edges could
    // not meet the tolerance; say so rather than pass it silently.
    let wanted = args
        .tolerance
        .or(adapt.then_some(loopsurf::mesh::DEFAULT_ADAPT_TOLERANCE));
    if let (Some(eps), Some(d)) = (wanted, mesh.deviation) {
        if d > eps * mesh.diagonal {
            eprintln!(
                "loopsurf: warning: chord tolerance {eps:e} not reached: {:.3e} of the diagonal at worst (the mesh is written)",
                d / mesh.diagonal
            );
        }
    }
    Ok((mesh, parts, Some(remesher.smallest_size()?)))
}

/// An output edge shorter than this fraction of the smallest size asked
/// for is named in the summary: two vertices that nearly coincide.
const SHORT_EDGE: f64 = 1e-6;

/// The summary's line on edges shorter than [`SHORT_EDGE`] × `size` (the
/// smallest size the remesher asked for): none, or how many, how many a
/// feature forces (both ends on hard edges), and the shortest by its
/// vertices and place.
fn short_edges(out: &mut dyn Write, mesh: &SurfaceMesh, size: f64) -> std::io::Result<()> {
    let limit = SHORT_EDGE * size;
    let short = mesh.short_edges(limit);
    let Some(first) = short.first() else {
        return writeln!(
            out,
            "short edges: none below {SHORT_EDGE:e} × the smallest size asked for ({limit:.4e})"
        );
    };
    let forced = short.iter().filter(|e| e.forced).count();
    let [a, b] = first.ends;
    let at = mesh.points[a as usize];
    writeln!(
        out,
        "short edges: {} below {SHORT_EDGE:e} × the smallest size asked for ({limit:.4e}), {forced} of them forced by features (both ends on hard edges); the shortest, {:.3e} long, joins vertices {a} and {b} at ({:.6}, {:.6}, {:.6})",
        short.len(),
        first.length,
        at.x,
        at.y,
        at.z
    )
}

/// Where the time went, in seconds from the start of meshing: the
/// meshing, the chord-error check by snap, and all of it (writing too).
struct Times {
    meshing: f64,
    checking: f64,
    total: f64,
}

/// The mesh's size, speed, chord error (the bound measured while meshing
/// and the one by snap, where known), angles and edge lengths.
fn summary(
    out: &mut dyn Write,
    mesh: &SurfaceMesh,
    times: &Times,
    snapped: Option<f64>,
) -> std::io::Result<()> {
    let quality = mesh.quality();
    let relative = |d: f64| d / mesh.diagonal;
    writeln!(
        out,
        "output: {} vertices, {} triangles, {} hard edges in {:.3} s (meshing {:.3} s, {:.2}M triangles/s; checking {:.3} s; writing {:.3} s)",
        mesh.points.len(),
        mesh.triangles.len(),
        mesh.hard_edges.len(),
        times.total,
        times.meshing,
        mesh.triangles.len() as f64 / times.meshing.max(1e-12) / 1e6,
        times.checking,
        times.total - times.meshing - times.checking
    )?;
    let line = match (mesh.deviation, snapped) {
        (Some(b), Some(s)) => format!(
            "{:.3e} of the diagonal (bound), {:.3e} by snap",
            relative(b),
            relative(s)
        ),
        (Some(b), None) => format!("{:.3e} of the diagonal (bound)", relative(b)),
        (None, Some(s)) => format!("{:.3e} of the diagonal by snap", relative(s)),
        (None, None) => "not measured (no --tolerance, and --no-verify)".into(),
    };
    writeln!(out, "max deviation: {line}")?;
    writeln!(
        out,
        "angles: min {:.2}°, mean of per-triangle minima {:.2}°, {:.3}% of triangles below 20° ({} of them forced by features: at a corner, between hard edges, or with every corner on one), {:.3}% below 10°",
        quality.min_angle,
        quality.mean_min_angle,
        100.0 * quality.below_20,
        quality.below_20_at_features,
        100.0 * quality.below_10
    )?;
    writeln!(
        out,
        "edge lengths: {:.4e} to {:.4e}, 90% within {:.4e} to {:.4e}, median {:.4e}",
        quality.edge_lengths[0],
        quality.edge_lengths[4],
        quality.edge_lengths[1],
        quality.edge_lengths[3],
        quality.edge_lengths[2]
    )
}

/// The chart mesher's mesh, with a progress bar over control triangles.
fn chart_mesh(args: &Args, surface: &loopsurf::Surface) -> Result<SurfaceMesh, Error> {
    let density = match (args.uniform, args.size) {
        (Some(n), _) => Density::Uniform(n),
        (None, Some(h)) => Density::Size(h),
        (None, None) => Density::FromTolerance,
    };
    let mut mesher = Mesher::new(surface)
        .density(density)
        .adapt_curvature(args.adapt.is_some())
        .swaps(!args.no_swaps);
    if let Some(eps) = args.tolerance {
        mesher = mesher.tolerance(eps);
    }
    if let Some(n) = args.max_triangles {
        mesher = mesher.max_triangles(n);
    }
    let bar = ProgressBar::new(surface.net().triangles().len() as u64).with_style(
        ProgressStyle::with_template("meshing {bar:40} {pos}/{len} control triangles")
            .expect("valid template"),
    );
    let mesh = mesher.run_with_progress(&|done, total| {
        bar.set_length(total);
        bar.set_position(done);
    })?;
    bar.finish_and_clear();
    Ok(mesh)
}

/// The mesh in OUT's format; `.vtu` carries per-vertex parameters and
/// curvature, per triangle its chart, quality and model `face`, and after
/// the triangles one line cell per hard output edge with its model `edge`
/// (curve) id, as `loopsurf topology` writes them. Each cell array holds -1
/// on the cells it does not describe (`edge` on triangles; the others on
/// the lines).
/// `binary` as in [`io::write_vtu`].
fn write_output(
    path: &Path,
    surface: &loopsurf::Surface,
    mesh: &SurfaceMesh,
    binary: bool,
) -> Result<(), Error> {
    let is_vtu = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("vtu"));
    if !is_vtu {
        return io::write_mesh(path, &mesh.points, &mesh.triangles);
    }
    let tri: Vec<i32> = mesh.params.iter().map(|p| p.tri as i32).collect();
    let v: Vec<f64> = mesh.params.iter().map(|p| p.v).collect();
    let w: Vec<f64> = mesh.params.iter().map(|p| p.w).collect();
    let curvature = mesh.vertex_curvature(surface)?;
    let mean: Vec<f64> = curvature.iter().map(|c| c.mean).collect();
    let gaussian: Vec<f64> = curvature.iter().map(|c| c.gaussian).collect();
    let reliable: Vec<i32> = curvature.iter().map(|c| c.reliable as i32).collect();
    let lines = mesh.hard_edges.len();
    let pad_i32 = |values: Vec<i32>| -> Vec<i32> {
        values
            .into_iter()
            .chain(std::iter::repeat(-1).take(lines))
            .collect()
    };
    let pad_f64 = |values: Vec<f64>| -> Vec<f64> {
        values
            .into_iter()
            .chain(std::iter::repeat(-1.0).take(lines))
            .collect()
    };
    let chart = pad_i32(mesh.charts.iter().map(|&c| c as i32).collect());
    let face = pad_i32(mesh.faces.iter().map(|&f| f as i32).collect());
    let edge: Vec<i32> = std::iter::repeat(-1)
        .take(mesh.triangles.len())
        .chain(mesh.hard_edge_curves.iter().map(|&c| c as i32))
        .collect();
    let quality = mesh.triangle_quality();
    let min_angle = pad_f64(quality.iter().map(|q| q.min_angle).collect());
    let shape = pad_f64(quality.iter().map(|q| q.shape).collect());
    let mut cells = vec![
        ("face", DataArray::I32(&face)),
        ("edge", DataArray::I32(&edge)),
        ("min_angle", DataArray::F64(&min_angle)),
        ("shape_quality", DataArray::F64(&shape)),
    ];
    // The remesher's triangles span control triangles: no chart to name.
    if !mesh.charts.is_empty() {
        cells.insert(0, ("control_tri", DataArray::I32(&chart)));
    }
    io::write_vtu_with_lines(
        path,
        &mesh.points,
        &mesh.triangles,
        &mesh.hard_edges,
        &[
            ("tri", DataArray::I32(&tri)),
            ("v", DataArray::F64(&v)),
            ("w", DataArray::F64(&w)),
            ("mean_curvature", DataArray::F64(&mean)),
            ("gaussian_curvature", DataArray::F64(&gaussian)),
            ("curvature_reliable", DataArray::I32(&reliable)),
        ],
        &cells,
        binary,
    )
}

/// One `tri v w` line per vertex; Rust's shortest round-trip formatting
/// reads back bit-exact.
fn write_params(path: &Path, mesh: &SurfaceMesh) -> Result<(), Error> {
    let io_error = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::create(path).map_err(io_error)?;
    let mut out = std::io::BufWriter::new(file);
    for p in &mesh.params {
        writeln!(out, "{} {} {}", p.tri, p.v, p.w).map_err(io_error)?;
    }
    out.flush().map_err(io_error)
}

/// Says on stderr where triangles below 10° lie on patches of the surface
/// that fold over themselves ([`loopsurf::folds::is_folded`]): no mesh of a fold
/// is good, and the user should look at the control net there rather than
/// at the mesher. Only the control triangles under such triangles are
/// checked, so a good mesh costs nothing.
fn warn_of_surface_folds(surface: &Surface, mesh: &SurfaceMesh) {
    let mut suspects: Vec<usize> = mesh
        .triangle_quality()
        .iter()
        .zip(&mesh.triangles)
        .filter(|(q, _)| q.min_angle < 10.0)
        .flat_map(|(_, t)| t.map(|v| mesh.params[v as usize].tri as usize))
        .collect();
    suspects.sort_unstable();
    suspects.dedup();
    let folded: Vec<usize> = suspects
        .into_iter()
        .filter(|&t| loopsurf::folds::is_folded(surface, t))
        .collect();
    if folded.is_empty() {
        return;
    }
    let shown: Vec<String> = folded.iter().take(8).map(|t| t.to_string()).collect();
    // Folds beside a concave corner are what --concave-seams is for.
    let corners: Vec<String> = loopsurf::concave::concave_sectors(surface.net())
        .iter()
        .filter(|s| s.seam.is_some())
        .filter(|s| s.triangles.iter().any(|&t| folded.contains(&(t as usize))))
        .map(|s| s.corner.to_string())
        .collect();
    let hint = match corners.len() {
        0 => "look at the net's corners, creases and irregular vertices there".to_string(),
        1 => format!(
            "the fold beside the concave corner at vertex {} is what --concave-seams splits",
            corners[0]
        ),
        _ => format!(
            "the folds beside the concave corners at vertices {} are what --concave-seams splits",
            corners.join(", ")
        ),
    };
    eprintln!(
        "loopsurf: warning: triangles below 10° lie where the surface folds over itself, in {} control triangle{} ({}{}): no mesh of a fold is good; {hint}",
        folded.len(),
        if folded.len() == 1 { "" } else { "s" },
        shown.join(", "),
        if folded.len() > 8 { ", ..." } else { "" }
    );
}

/// Says on stderr where the mesh crosses itself, so that the user hears
/// it before a volume mesher refuses the surface: how many pairs of
/// triangles meet, where the first few lie (their control triangles), and
/// whether the control net crosses itself too (then its surface most
/// likely does, and the input is what to look at).
fn warn_of_crossings(surface: &Surface, mesh: &SurfaceMesh, crossings: &[[u32; 2]]) {
    if crossings.is_empty() {
        return;
    }
    let net = surface.net();
    let in_net = loopsurf::geometry::crossings::crossings(net.points(), net.triangles()).len();
    let net_too = match in_net {
        0 => String::new(),
        n => format!(
            " (the control net itself crosses in {n} pair{})",
            if n == 1 { "" } else { "s" }
        ),
    };
    let mut under: Vec<u32> = crossings
        .iter()
        .flatten()
        .flat_map(|&t| mesh.triangles[t as usize].map(|v| mesh.params[v as usize].tri))
        .collect();
    under.sort_unstable();
    under.dedup();
    let shown: Vec<String> = under.iter().take(8).map(|t| t.to_string()).collect();
    let [a, b] = crossings[0];
    let at = mesh.triangles[a as usize]
        .iter()
        .map(|&v| mesh.points[v as usize])
        .sum::<loopsurf::DVec3>()
        / 3.0;
    eprintln!(
        "loopsurf: warning: the mesh crosses itself: {} pair{} of triangles meet (the first, {a} and {b}, near ({:.6}, {:.6}, {:.6})), over control triangle{} {}{}{net_too}; a volume mesher will refuse it",
        crossings.len(),
        if crossings.len() == 1 { "" } else { "s" },
        at.x,
        at.y,
        at.z,
        if under.len() == 1 { "" } else { "s" },
        shown.join(", "),
        if under.len() > 8 { ", ..." } else { "" }
    );
}
