//! How faithful each surrogate surface is to the true CAD surface it was
//! exported from: six analytic shapes tessellated as a CAD exporter does
//! (chord and angle deflection), and the distance from the facets, the
//! approximating Loop surface and the two interpolants to the exact
//! surface, plus their mean-curvature error on the sphere, cylinder and
//! torus; and the same of the fitted surrogate ([`loopsurf::fit`]), a new
//! control net fitted to the tessellation's vertices; and how fair the
//! fit is: its surface remeshed at a tight tolerance against the surface of
//! a 16× finer tessellation. These are the tables of docs/fitting.md.
//!
//! `cargo run --release -p loopsurf --example surrogates`

use loopsurf::cad::{self, Analytic, CapStyle, Deviation};
use loopsurf::DVec3;
use loopsurf::{folds, ControlNet, Fitter, Remesher, Surface, SurfaceMode};
use std::time::Instant;

/// Chord tolerance of the tessellations, relative to the diagonal.
const CHORD: f64 = 5e-4;
/// Angle tolerance of the tessellations, degrees.
const ANGLE: f64 = 15.0;
/// Dihedral angle above which an edge is tagged as a crease.
const CREASE_ANGLE: f64 = 30.0;
/// Lattice steps per control triangle edge: 28 samples per triangle.
const LATTICE: usize = 6;
/// The chord tolerance the fitted surfaces are remeshed at, relative to
/// the diagonal.
const FAIR_TOLERANCE: f64 = 1e-4;
/// Curvature is compared this far (relative to the diagonal) from sharp
/// features and blend seams.
const MARGIN: f64 = 0.1;

/// The surrogates measured, in column order.
const MODES: [(&str, SurfaceMode); 3] = [
    ("approximating", SurfaceMode::Approximating),
    ("solve", SurfaceMode::Solve),
    ("displacement", SurfaceMode::Displacement),
];

fn cell(d: &Deviation) -> String {
    format!("{:.1e} / {:.1e}", d.max, d.mean)
}

fn percent(d: &Deviation) -> String {
    format!("{:.1}% / {:.2}%", 100.0 * d.max, 100.0 * d.mean)
}

/// Prints one row of the distance table for `net` (the tessellation of
/// `shape` with its features tagged) and returns the row's curvature
/// cells; a surrogate that cannot be built is a note.
fn row(
    shape: &dyn Analytic,
    name: &str,
    net: &ControlNet,
    notes: &mut Vec<String>,
) -> loopsurf::Result<Vec<String>> {
    let ex = shape.tessellation();
    let facets = cad::facet_distance(shape, &ex.points, &ex.tris, LATTICE);
    let mut cells = vec![cell(&facets)];
    let mut curvature = Vec::new();
    let surrogates = MODES
        .iter()
        .map(|&(label, mode)| (label, Surface::with_mode(net, mode)))
        .chain([("fit", fitted(net))]);
    for (label, surface) in surrogates {
        match surface {
            Ok(surface) => {
                cells.push(cell(&cad::surrogate_distance(shape, &surface, LATTICE)?));
                let k = cad::curvature_error(shape, &surface, LATTICE, MARGIN)?;
                curvature.push(k.map_or("—".to_string(), |d| percent(&d)));
            }
            Err(e) => {
                cells.push("failed".into());
                curvature.push("failed".into());
                notes.push(format!("{name} {label}: {e}"));
            }
        }
    }
    println!(
        "| {name} | {} | {} | {} |",
        ex.points.len(),
        ex.tris.len(),
        cells.join(" | ")
    );
    Ok(curvature)
}

/// The fitted surrogate of `net` at the default resolution, with its
/// report on stderr. The tolerance is lifted so that a fit that misses the
/// default one is measured too: the report's vertex distance says whether
/// it did.
fn fitted(net: &ControlNet) -> loopsurf::Result<Surface> {
    let fit = Fitter::new(net).tolerance(1.0).run()?;
    let r = &fit.report;
    eprintln!(
        "fit: {} control triangles, vertices {:.1e} / {:.1e}, midpoints {:.1e} / {:.1e}, \
         normal turn {:.1}°, min angle {:.1}°, {:.2} s",
        r.control_triangles,
        r.vertices.max,
        r.vertices.mean,
        r.midpoints.max,
        r.midpoints.mean,
        r.max_normal_turn,
        r.min_angle,
        r.seconds
    );
    Surface::new(&fit.net)
}

/// Relative mean-curvature error of a surface of the unit sphere on the
/// samples whose latitude is in [lo, hi) degrees (either hemisphere).
fn latitude_band(surface: &Surface, lo: f64, hi: f64) -> Option<Deviation> {
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0usize);
    for t in 0..surface.net().triangles().len() {
        for &(v, w) in &cad::lattice(LATTICE) {
            let (Ok(k), Ok(x)) = (surface.curvature(t, v, w), surface.point(t, v, w)) else {
                continue;
            };
            let latitude = (x.z / x.length())
                .clamp(-1.0, 1.0)
                .asin()
                .abs()
                .to_degrees();
            if k.reliable && latitude >= lo && latitude < hi {
                let e = (k.mean - 1.0 / cad::SPHERE_RADIUS).abs() * cad::SPHERE_RADIUS;
                max = max.max(e);
                sum += e;
                n += 1;
            }
        }
    }
    (n > 0).then(|| Deviation {
        max,
        mean: sum / n as f64,
        samples: n,
    })
}

fn main() -> loopsurf::Result<()> {
    let start = Instant::now();
    let shapes = cad::all(CHORD, ANGLE);
    println!(
        "Tessellations: chord {CHORD:e} of the diagonal, angle {ANGLE}°; creases tagged above {CREASE_ANGLE}°; \
         {} samples per control triangle.\n",
        cad::lattice(LATTICE).len()
    );
    let curvature_rows = distance_table(&shapes)?;
    curvature_table(curvature_rows);
    sphere_by_latitude(shapes[1].as_ref())?;
    finer_facets_table();
    fairness_table(&shapes)?;
    convergence_table(&shapes)?;
    fit_timing()?;
    println!("\n({:.1} s)", start.elapsed().as_secs_f64());
    Ok(())
}

/// The distance of every surrogate of every shape (and of two variants: the
/// fan-free caps, and the cone's apex, which no dihedral angle marks,
/// tagged as a corner by hand); the curvature cells of the shapes whose
/// curvature is checked.
fn distance_table(
    shapes: &[Box<dyn Analytic>],
) -> loopsurf::Result<Vec<(&'static str, Vec<String>)>> {
    println!("Distance to the true surface, max / mean, relative to the bounding-box diagonal:\n");
    println!(
        "| shape | vertices | triangles | facets | approximating | solve | displacement | fit |"
    );
    println!("|---|---:|---:|---|---|---|---|---|");
    let mut curvature_rows = Vec::new();
    let mut notes = Vec::new();
    for shape in shapes {
        let mut net = shape.net()?;
        net.tag_by_angle(CREASE_ANGLE)?;
        let curvature = row(shape.as_ref(), shape.name(), &net, &mut notes)?;
        if matches!(shape.name(), "sphere" | "cylinder" | "torus") {
            curvature_rows.push((shape.name(), curvature));
        }
    }
    let zigzag = cad::cylinder(CHORD, ANGLE, CapStyle::Zigzag);
    let mut net = zigzag.net()?;
    net.tag_by_angle(CREASE_ANGLE)?;
    row(&zigzag, "cylinder, zigzag caps", &net, &mut notes)?;
    let cone = cad::cone(CHORD, ANGLE);
    let mut net = cone.net()?;
    net.tag_by_angle(CREASE_ANGLE)?;
    tag_apex(&mut net)?;
    row(&cone, "cone, apex tagged", &net, &mut notes)?;
    for note in &notes {
        println!("\n{note}");
    }
    Ok(curvature_rows)
}

/// Tags the cone's apex, known from its construction, as a corner.
fn tag_apex(net: &mut ControlNet) -> loopsurf::Result<()> {
    let apex = DVec3::new(0.0, 0.0, cad::CONE_HEIGHT);
    let index = net
        .points()
        .iter()
        .position(|&p| p == apex)
        .expect("the apex is a vertex");
    net.tag_vertex(index as u32)?;
    Ok(())
}

/// The mean-curvature error of each surrogate, away from features.
fn curvature_table(rows: Vec<(&'static str, Vec<String>)>) {
    println!(
        "\nMean-curvature error |H − H_true| / |H_true|, max / mean, farther than {MARGIN} of the diagonal \
         from rims and blend seams:\n"
    );
    println!("| shape | approximating | solve | displacement | fit |");
    println!("|---|---|---|---|---|");
    for (name, cells) in rows {
        println!("| {name} | {} |", cells.join(" | "));
    }
}

/// The sphere's curvature error by latitude band: its poles are vertices of
/// high valence, where the surrogates differ most.
fn sphere_by_latitude(sphere: &dyn Analytic) -> loopsurf::Result<()> {
    let ex = sphere.tessellation();
    let mut valence = vec![0usize; ex.points.len()];
    ex.tris
        .iter()
        .flatten()
        .for_each(|&i| valence[i as usize] += 1);
    println!(
        "\nThe sphere's mean-curvature error by latitude, max / mean (the poles are vertices of \
         valence {}):\n",
        valence.iter().max().unwrap()
    );
    println!("| latitude | approximating | solve | displacement | fit |");
    println!("|---|---|---|---|---|");
    let mut net = sphere.net()?;
    net.tag_by_angle(CREASE_ANGLE)?;
    let mut surfaces: Vec<Option<Surface>> = MODES
        .iter()
        .map(|&(_, mode)| Surface::with_mode(&net, mode).ok())
        .collect();
    surfaces.push(fitted(&net).ok());
    for (lo, hi) in [(0.0, 60.0), (60.0, 80.0), (80.0, 90.1)] {
        let cells: Vec<String> = surfaces
            .iter()
            .map(|s| match s {
                Some(s) => latitude_band(s, lo, hi).map_or("—".into(), |d| percent(&d)),
                None => "failed".into(),
            })
            .collect();
        println!("| {lo}°–{}° | {} |", hi.min(90.0), cells.join(" | "));
    }
    Ok(())
}

/// The facets of tessellations 16× finer: how close a denser input gets.
fn finer_facets_table() {
    println!(
        "\nThe same shapes at chord {:e} (16× finer), facets only:\n",
        CHORD / 16.0
    );
    println!("| shape | vertices | triangles | facets |");
    println!("|---|---:|---:|---|");
    for shape in cad::all(CHORD / 16.0, ANGLE) {
        let ex = shape.tessellation();
        let facets = cad::facet_distance(shape.as_ref(), &ex.points, &ex.tris, LATTICE);
        println!(
            "| {} | {} | {} | {} |",
            shape.name(),
            ex.points.len(),
            ex.tris.len(),
            cell(&facets)
        );
    }
}

/// The fitted surfaces remeshed at the chord tolerance [`FAIR_TOLERANCE`],
/// against the approximating surface of the 16× finer tessellation (a
/// stand-in for the true surface, the cone's apex tagged by hand): a
/// surface that wiggles needs more triangles for the same tolerance, and
/// folds.
fn fairness_table(shapes: &[Box<dyn Analytic>]) -> loopsurf::Result<()> {
    println!(
        "\nRemeshed at tolerance {FAIR_TOLERANCE:e} (`Remesher::tolerance`): the fit against the \
         approximating surface of the 16× finer tessellation:\n"
    );
    println!("| shape | fit: triangles | mean-min | min angle | folded patches | finer: triangles | ratio |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for (shape, finer) in shapes.iter().zip(cad::all(CHORD / 16.0, ANGLE)) {
        let mut net = shape.net()?;
        net.tag_by_angle(CREASE_ANGLE)?;
        let fit = fitted(&net)?;
        let mesh = Remesher::new(&fit).tolerance(FAIR_TOLERANCE).run()?;
        let q = mesh.quality();
        let mut fine = finer.net()?;
        fine.tag_by_angle(CREASE_ANGLE)?;
        if finer.name() == "cone" {
            tag_apex(&mut fine)?;
        }
        let reference = Remesher::new(&Surface::new(&fine)?)
            .tolerance(FAIR_TOLERANCE)
            .run()?;
        println!(
            "| {} | {} | {:.2}° | {:.1}° | {} | {} | {:.2} |",
            shape.name(),
            mesh.triangles.len(),
            q.mean_min_angle,
            q.min_angle,
            folds::folded_patches(&fit).len(),
            reference.triangles.len(),
            mesh.triangles.len() as f64 / reference.triangles.len() as f64
        );
    }
    Ok(())
}

/// Curved meshes of the fitted sphere and torus against the exact
/// surfaces: the largest distance of P1, P2 and P3 triangles (remeshed at
/// 16% to 2% of the diagonal) at the points (i/7, j/7) of every element,
/// which no order's nodes hit, and the order the two coarsest show (the
/// finer ones reach the fit's own distance, the floor).
fn convergence_table(shapes: &[Box<dyn Analytic>]) -> loopsurf::Result<()> {
    println!(
        "\nCurved meshes of the fitted surfaces: largest distance to the exact surface, relative to \
         the diagonal (the fit's own distance is its floor):\n"
    );
    println!("| shape | order | h = 16% | h = 8% | h = 4% | h = 2% | order seen |");
    println!("|---|---|---:|---:|---:|---:|---:|");
    for shape in shapes
        .iter()
        .filter(|s| matches!(s.name(), "sphere" | "torus"))
    {
        let fit = fitted(&shape.net()?)?;
        let diagonal = shape.diagonal();
        let meshes: Vec<_> = [0.16, 0.08, 0.04, 0.02]
            .iter()
            .map(|h| Remesher::new(&fit).size(h * diagonal).run())
            .collect::<loopsurf::Result<_>>()?;
        for order in 1..=3 {
            let errors: Vec<f64> = meshes
                .iter()
                .map(|m| {
                    let curved = m.raise_order(&fit, order)?;
                    let worst = (0..curved.len())
                        .flat_map(|t| {
                            cad::lattice(7)
                                .into_iter()
                                .map(move |(xi, eta)| (t, xi, eta))
                        })
                        .map(|(t, xi, eta)| shape.distance(curved.map(t, xi, eta)[0]))
                        .fold(0.0, f64::max);
                    Ok(worst / diagonal)
                })
                .collect::<loopsurf::Result<_>>()?;
            let cells: Vec<String> = errors.iter().map(|e| format!("{e:.1e}")).collect();
            println!(
                "| {} | P{order} | {} | {:.1} |",
                shape.name(),
                cells.join(" | "),
                (errors[0] / errors[1]).log2()
            );
        }
    }
    Ok(())
}

/// The time to fit a 100k-triangle input: the sphere at the finer chord.
fn fit_timing() -> loopsurf::Result<()> {
    let fine = cad::sphere(CHORD / 16.0, ANGLE);
    let net = fine.net()?;
    let clock = Instant::now();
    let fit = Fitter::new(&net).tolerance(1.0).run()?;
    println!(
        "\nFit of the sphere at chord {:e}: {} triangles in {:.1} s; vertices {:.1e} / {:.1e}.",
        CHORD / 16.0,
        net.triangles().len(),
        clock.elapsed().as_secs_f64(),
        fit.report.vertices.max,
        fit.report.vertices.mean
    );
    Ok(())
}
