//! The mesh argument every command shares: a file or a built-in example,
//! plus the hard-feature flags.

use loopsurf::repair::ReadOptions;
use loopsurf::{examples, ControlNet, Error, Surface, SurfaceMode};
use std::path::{Path, PathBuf};

/// Where the control net comes from and which features are hard.
#[derive(clap::Args, Debug)]
pub struct Input {
    /// Mesh file: .off, .obj, .ply, .stl or Cart3D .tri.
    #[arg(value_name = "MESH", required_unless_present = "example")]
    pub mesh: Option<PathBuf>,
    /// A built-in control net instead of a file (viking, sphere, torus, cube, ...).
    #[arg(long, value_name = "NAME", conflicts_with = "mesh")]
    pub example: Option<String>,
    /// Split polygons into triangles (ear clipping) instead of rejecting them.
    #[arg(long, conflicts_with = "example")]
    pub triangulate: bool,
    /// Merge each vertex into the first earlier vertex within EPS × the
    /// bounding-box diagonal (nearly equal STL corners); drops the triangles
    /// that collapse or repeat.
    #[arg(long, value_name = "EPS", conflicts_with = "example")]
    pub weld: Option<f64>,
    /// Make triangle orientation consistent in each connected piece
    /// (outward for closed pieces).
    #[arg(long, conflicts_with = "example")]
    pub orient: bool,
    /// Give a vertex where separate fans of triangles touch one copy per fan.
    #[arg(long, conflicts_with = "example")]
    pub split_nonmanifold: bool,
    /// Keep zero-area triangles instead of refusing them (their edges are
    /// never tagged by angle).
    #[arg(long, conflicts_with = "example")]
    pub allow_degenerate: bool,
    /// All of --triangulate --orient --split-nonmanifold --allow-degenerate
    /// and --weld 1e-6 (unless --weld says otherwise).
    #[arg(long, conflicts_with = "example")]
    pub repair: bool,
    /// Tag every edge whose dihedral angle exceeds DEG degrees as hard.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub hard_angle: Option<f64>,
    /// Tag the edges listed in FILE (lines `i j`, 0-based) as hard.
    #[arg(long, value_name = "FILE")]
    pub hard_edges: Option<PathBuf>,
    /// Tag the vertices listed in FILE (one 0-based index a line) as corners.
    #[arg(long, value_name = "FILE")]
    pub hard_vertices: Option<PathBuf>,
    /// Split every corner's sector that spans more than 195° (the inner
    /// corner of an L-shaped face) and whose surface folds there, past the
    /// corner, by tagging an edge of its fan hard; says which edges, which
    /// sectors it left, and how far the surface moved.
    #[arg(long)]
    pub concave_seams: bool,
}

impl Input {
    /// A name for reports: the file or `example:NAME`.
    pub fn name(&self) -> String {
        match (&self.mesh, &self.example) {
            (Some(p), _) => p.display().to_string(),
            (None, Some(e)) => format!("example:{e}"),
            (None, None) => String::new(),
        }
    }

    /// The line `mesh` and `adapt` open their summaries with.
    pub fn describe(&self, net: &ControlNet) -> String {
        format!(
            "input: {} ({} vertices, {} triangles, {} hard edges)",
            self.name(),
            net.points().len(),
            net.triangles().len(),
            net.features().num_hard_edges()
        )
    }

    /// The reading and repair flags as library options.
    fn read_options(&self) -> ReadOptions {
        let mut opts = if self.repair {
            ReadOptions::repair_all()
        } else {
            ReadOptions::default()
        };
        opts.triangulate |= self.triangulate;
        let r = &mut opts.repairs;
        r.orient |= self.orient;
        r.split_nonmanifold |= self.split_nonmanifold;
        r.allow_degenerate |= self.allow_degenerate;
        if self.weld.is_some() {
            r.weld = self.weld;
        }
        opts
    }

    /// Reads or builds the net, reports the repairs made (stderr), and
    /// applies the feature flags.
    pub fn load(&self) -> Result<ControlNet, Error> {
        let mut net = match (&self.mesh, &self.example) {
            (Some(path), _) => {
                let net = ControlNet::read_with(path, &self.read_options())?;
                for change in net.repairs() {
                    eprintln!("loopsurf: {}: {change}", path.display());
                }
                net
            }
            (None, Some(name)) => {
                let ex = examples::by_name(name).ok_or_else(|| {
                    Error::InvalidArgument(format!(
                        "unknown example '{name}' (known: {})",
                        examples::NAMES.join(", ")
                    ))
                })?;
                ControlNet::from_arrays(ex.points, &ex.tris)?
            }
            (None, None) => return Err(Error::InvalidArgument("no mesh given".into())),
        };
        warn_of_folds(&net, &self.name());
        if let Some(deg) = self.hard_angle {
            net.tag_by_angle(deg)?;
        }
        if let Some(path) = &self.hard_edges {
            for (line, fields) in read_index_lines(path)? {
                let [a, b] = fields[..] else {
                    return Err(located(path, line, "expected two vertex indices `i j`"));
                };
                net.tag_edge(a, b)
                    .map_err(|e| e.in_file(path, Some(line)))?;
            }
        }
        if let Some(path) = &self.hard_vertices {
            for (line, fields) in read_index_lines(path)? {
                let [v] = fields[..] else {
                    return Err(located(path, line, "expected one vertex index"));
                };
                net.tag_vertex(v).map_err(|e| e.in_file(path, Some(line)))?;
            }
        }
        if self.concave_seams {
            let before = net.clone();
            let sectors = loopsurf::folds::seam_folded_concave_corners(&mut net)?;
            for line in seam_report(&sectors, &before, &net)? {
                eprintln!("loopsurf: {}: {line}", self.name());
            }
        }
        Ok(net)
    }
}

/// Says on stderr where the net folds back on itself (normals turning by
/// more than [`FOLD_DEGREES`]): not an error, since the surface is well
/// defined, but the fin it makes there spoils any mesh of it, and the user
/// should know why before looking at one.
fn warn_of_folds(net: &ControlNet, name: &str) {
    let folds = loopsurf::folds::folded_edges(net, FOLD_DEGREES);
    let Some(worst) = folds.first() else { return };
    let [a, b] = worst.edge;
    let [s, t] = worst.triangles;
    eprintln!(
        "loopsurf: {name}: warning: the net folds back on itself at {} edge{} (worst: vertices {a}–{b}, between triangles {s} and {t}, normals turning by {:.1}°); the surface has a fin there, and triangles on it will be poor",
        folds.len(),
        if folds.len() == 1 { "" } else { "s" },
        worst.degrees
    );
}

/// What `--concave-seams` did: a line for the seams, with how far the
/// surface moved ([`seam_moves`]), and one for the folded sectors left as
/// they were; or one saying that nothing folds.
fn seam_report(
    sectors: &[loopsurf::concave::ConcaveSector],
    before: &ControlNet,
    after: &ControlNet,
) -> Result<Vec<String>, Error> {
    let list = |items: Vec<String>| {
        let shown = items.iter().take(8).cloned().collect::<Vec<_>>().join(", ");
        if items.len() > 8 {
            format!("{shown}, ...")
        } else {
            shown
        }
    };
    let plural = |n: usize| if n == 1 { "" } else { "s" };
    let seamed: Vec<String> = sectors
        .iter()
        .filter_map(|s| {
            let ([a, b], [x, y]) = s.seam?;
            Some(format!(
                "{} by {a}–{b} ({:.1}° into {x:.1}° + {y:.1}°)",
                s.corner, s.degrees
            ))
        })
        .collect();
    let left: Vec<String> = sectors
        .iter()
        .filter(|s| s.seam.is_none())
        .map(|s| format!("{} ({:.1}°)", s.corner, s.degrees))
        .collect();
    let mut lines = Vec::new();
    if sectors.is_empty() {
        lines.push("nothing to seam: no concave corner's surface folds".to_string());
    }
    if !seamed.is_empty() {
        let (away, back) = seam_moves(sectors, before, after)?;
        lines.push(format!(
            "seamed {} folded concave corner{}, at vertices {}; the seamed surface lies within {away:.1e} of the diagonal of the surface before, and the surface before within {back:.1e} of it (as far as the flaps the seams removed reached)",
            seamed.len(),
            plural(seamed.len()),
            list(seamed.clone()),
        ));
    }
    if !left.is_empty() {
        lines.push(format!(
            "left {} folded concave corner{} unseamed, no edge of the fan splitting the sector without an angle below {}° or a vertex changing its rule: vertices {}",
            left.len(),
            plural(left.len()),
            loopsurf::concave::MIN_SEAM_DEGREES,
            list(left)
        ));
    }
    Ok(lines)
}

/// How far the surface moved where the seams changed it, as shares of the
/// diagonal: the farthest of the seamed surface's points from the surface
/// before (what the seams added or moved; 0 on flat sectors), and the
/// farthest of the points before from the seamed surface (the flaps
/// pulled back). Points at the 10 parameters of the lattice of sixths
/// inside each control triangle with a vertex within two rings of a seam
/// (the reach of Loop's masks); distances by certified closest points.
fn seam_moves(
    sectors: &[loopsurf::concave::ConcaveSector],
    before: &ControlNet,
    after: &ControlNet,
) -> Result<(f64, f64), Error> {
    let topo = after.topology();
    let mut near = vec![false; topo.num_vertices()];
    let mut frontier: Vec<u32> = sectors
        .iter()
        .filter_map(|s| s.seam)
        .flat_map(|(e, _)| e)
        .collect();
    for _ in 0..2 {
        let mut next = Vec::new();
        for v in frontier {
            for &n in topo.ring(v as usize) {
                if !near[n as usize] {
                    near[n as usize] = true;
                    next.push(n);
                }
            }
        }
        frontier = next;
    }
    let triangles: Vec<usize> = (0..topo.num_triangles())
        .filter(|&t| topo.triangles()[t].iter().any(|&v| near[v as usize]))
        .collect();
    let (old, new) = (Surface::new(before)?, Surface::new(after)?);
    let farthest = |from: &Surface, to: &Surface| -> Result<f64, Error> {
        let mut far: f64 = 0.0;
        for &t in &triangles {
            for i in 1..5 {
                for j in 1..=5 - i {
                    let (v, w) = (i as f64 / 6.0, j as f64 / 6.0);
                    let p = from.point(t, v, w)?;
                    far = far.max(loopsurf::snap::closest_point(to, p)?.distance);
                }
            }
        }
        Ok(far / before.bbox_diagonal())
    };
    Ok((farthest(&new, &old)?, farthest(&old, &new)?))
}

/// Normals turning by more than this across an edge are a fold.
const FOLD_DEGREES: f64 = 150.0;

fn located(path: &Path, line: usize, message: &str) -> Error {
    Error::Malformed {
        line,
        message: message.into(),
    }
    .in_file(path, None)
}

/// Non-blank, non-comment lines of a file of indices, with their line numbers.
fn read_index_lines(path: &Path) -> Result<Vec<(usize, Vec<u32>)>, Error> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.to_owned(),
        source,
    })?;
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let fields = content
            .split_whitespace()
            .map(|f| f.parse::<u32>())
            .collect::<Result<Vec<_>, _>>()
            .map_err(|_| {
                located(
                    path,
                    i + 1,
                    &format!("'{content}' is not a list of vertex indices"),
                )
            })?;
        out.push((i + 1, fields));
    }
    Ok(out)
}

/// Which surface the commands that evaluate build from the net.
#[derive(clap::Args, Debug)]
pub struct SurfaceOptions {
    /// Make the surface pass through the mesh's points: `solve` (new
    /// control points whose smooth limit surface interpolates) or
    /// `displacement` (the approximating surface plus a linear correction
    /// per triangle; C0 across edges).
    #[arg(long, value_enum, value_name = "HOW", conflicts_with = "fit")]
    interpolate: Option<Interpolate>,
    #[command(flatten)]
    fit: FitOptions,
}

/// `--fit`: the commands work on the fitted control net (`loopsurf fit`)
/// instead of the mesh itself; triangle indices then refer to it.
#[derive(clap::Args, Debug)]
pub struct FitOptions {
    /// Fit a new control net to the mesh's vertices first (as `loopsurf
    /// fit` does) and use its surface; triangle indices refer to the
    /// fitted net. Its report goes to stderr.
    #[arg(long)]
    fit: bool,
    /// With --fit: the fitted net's control-edge length, model units.
    #[arg(long, value_name = "H", requires = "fit")]
    fit_resolution: Option<f64>,
    /// With --fit: the largest distance to an input vertex, as a fraction of
    /// the bounding-box diagonal (default 1e-4).
    #[arg(long, value_name = "EPS", requires = "fit")]
    fit_tolerance: Option<f64>,
}

impl FitOptions {
    /// The fitted net of `net` with --fit, else `net` itself.
    pub fn apply(&self, net: ControlNet) -> Result<ControlNet, Error> {
        if !self.fit {
            return Ok(net);
        }
        let fit = crate::cmd_fit::fit(&net, self.fit_resolution, self.fit_tolerance)?;
        for line in crate::cmd_fit::report_lines(&fit) {
            eprintln!("loopsurf: fit: {line}");
        }
        Ok(fit.net)
    }
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum Interpolate {
    Solve,
    Displacement,
}

impl SurfaceOptions {
    /// Builds the surface of `net` in the chosen mode (of the fitted net
    /// with --fit).
    pub fn build(&self, net: &ControlNet) -> Result<Surface, Error> {
        if self.fit.fit {
            return Surface::new(&self.fit.apply(net.clone())?);
        }
        let (mode, name) = match self.interpolate {
            None => return Surface::new(net),
            Some(Interpolate::Solve) => (SurfaceMode::Solve, "solved"),
            Some(Interpolate::Displacement) => (SurfaceMode::Displacement, "displacement"),
        };
        let surface = Surface::with_mode(net, mode)?;
        warn_of_wiggles(net, &surface, name)?;
        Ok(surface)
    }

    /// The surface of a part's sub-net: approximating or displaced, which
    /// are decided triangle by triangle; solving and fitting change every
    /// control point from the whole net, so a part alone cannot give them.
    pub fn build_part(&self, net: &ControlNet) -> Result<Surface, Error> {
        if self.fit.fit || matches!(self.interpolate, Some(Interpolate::Solve)) {
            return Err(Error::InvalidArgument(
                "--fit and --interpolate solve change every control point from the whole net: not available with --parts".into(),
            ));
        }
        self.build(net)
    }
}

/// Says on stderr, with what was measured, where an interpolating surface
/// wiggles or folds, and points to `--fit`. Interpolants pass through the
/// mesh's points but, on the long triangles of CAD exports, swing between
/// them (docs/fitting.md measures up to 140 times the facets' distance);
/// a fitted net stays near the points without passing through them.
fn warn_of_wiggles(net: &ControlNet, surface: &Surface, name: &str) -> Result<(), Error> {
    let mut findings = Vec::new();
    if surface.mode() == SurfaceMode::Solve {
        findings = loopsurf::fairness::fairness(net, surface.net())?.warnings();
    }
    let folded = loopsurf::folds::folded_patches(surface);
    if let Some(first) = folded.first() {
        findings.push(format!(
            "the surface folds over itself in {} control triangle{} (first: {first})",
            folded.len(),
            if folded.len() == 1 { "" } else { "s" }
        ));
    }
    for finding in &findings {
        eprintln!("loopsurf: warning: {name} surface: {finding}");
    }
    if !findings.is_empty() {
        eprintln!(
            "loopsurf: warning: {name} surface: it wiggles between the mesh's points; `--fit` fits a fair surface near them instead (docs/fitting.md)"
        );
    }
    Ok(())
}
