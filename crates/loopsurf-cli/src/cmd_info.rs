//! `loopsurf info`: what the control net is made of, and how far its
//! vertices lie from the limit surface (Persson, Aftosmis & Haines's deviation figure).
//! With `--parts K --part P`: one line on that part alone, its owned and
//! halo triangles and the bytes its surface holds.

use crate::input::Input;
use crate::part_options::{PartOptions, Selected};
use loopsurf::partsurface::{self, PartSurface};
use loopsurf::{ControlNet, Error, VertexKind};
use std::collections::BTreeMap;
use std::io::Write;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    #[command(flatten)]
    part: PartOptions,
}

pub fn run(args: Args) -> Result<(), Error> {
    let net = args.input.load()?;
    if let Some(selected) = args.part.select(&net)? {
        let bytes = part_bytes(&net, &selected)?;
        let (part, k) = (&selected.part, selected.partition.num_parts());
        return crate::write_stdout(|out| {
            writeln!(
                out,
                "part {} of {k}: owned {} halo {} bytes {bytes}",
                selected.index,
                part.num_owned(),
                part.num_halo()
            )
        });
    }
    crate::write_stdout(|out| {
        writeln!(out, "mesh: {}", args.input.name())?;
        counts(out, &net)?;
        shape(out, &net)?;
        features(out, &net)?;
        limit_deviation(out, &net)
    })
}

/// The bytes a part's surface holds once every patch and the snap index
/// of its owned triangles are made (one snap makes them), with its
/// sub-net and maps.
fn part_bytes(net: &ControlNet, selected: &Selected) -> Result<usize, Error> {
    let part = selected.part.clone();
    let x = part.net().points()[0];
    let bounds = partsurface::bounds(net, &selected.partition);
    let surface = PartSurface::new(part, selected.index, bounds)?;
    surface.closest_point(x)?;
    Ok(surface.memory_bytes())
}

/// Vertices, triangles and edges, and the vertices no triangle uses or
/// that were welded.
fn counts(out: &mut dyn Write, net: &ControlNet) -> std::io::Result<()> {
    let topo = net.topology();
    let nv = topo.num_vertices();
    let unreferenced: Vec<usize> = (0..nv).filter(|&v| topo.is_unreferenced(v)).collect();
    writeln!(
        out,
        "vertices: {nv}  triangles: {}  edges: {}",
        topo.num_triangles(),
        topo.num_edges()
    )?;
    if !unreferenced.is_empty() {
        let shown: Vec<String> = unreferenced
            .iter()
            .take(10)
            .map(|v| v.to_string())
            .collect();
        let more = if unreferenced.len() > 10 { " ..." } else { "" };
        writeln!(
            out,
            "unreferenced vertices (kept, ignored): {} [{}{more}]",
            unreferenced.len(),
            shown.join(" ")
        )?;
    }
    if net.welded_vertices() > 0 {
        writeln!(
            out,
            "welded STL vertices (exactly equal coordinates): {}",
            net.welded_vertices()
        )?;
    }
    Ok(())
}

/// The valence histogram, the boundary loops and the Euler characteristic
/// (with the genus of a closed connected surface).
fn shape(out: &mut dyn Write, net: &ControlNet) -> std::io::Result<()> {
    let topo = net.topology();
    let nv = topo.num_vertices();
    let mut valences = BTreeMap::new();
    for v in (0..nv).filter(|&v| !topo.is_unreferenced(v)) {
        *valences.entry(topo.valence(v)).or_insert(0usize) += 1;
    }
    let hist: Vec<String> = valences.iter().map(|(k, n)| format!("{k}:{n}")).collect();
    writeln!(out, "valence histogram: {}", hist.join(" "))?;

    let loops = topo.boundary_loops();
    let lengths: Vec<String> = loops.iter().map(|l| l.len().to_string()).collect();
    writeln!(
        out,
        "boundary loops: {}{}",
        loops.len(),
        if loops.is_empty() {
            String::new()
        } else {
            format!(" (edges: {})", lengths.join(" "))
        }
    )?;
    let chi = topo.euler_characteristic();
    if loops.is_empty() && topo.num_components() == 1 {
        writeln!(
            out,
            "Euler characteristic: {chi} (closed, genus {})",
            (2 - chi) / 2
        )?;
    } else {
        writeln!(out, "Euler characteristic: {chi}")?;
    }
    Ok(())
}

/// The hard edges and the vertex kinds they make.
fn features(out: &mut dyn Write, net: &ControlNet) -> std::io::Result<()> {
    let topo = net.topology();
    let nv = topo.num_vertices();
    let boundary_edges = (0..topo.num_edges())
        .filter(|&e| topo.is_boundary_edge(e))
        .count();
    let hard = net.features().num_hard_edges();
    writeln!(
        out,
        "hard edges: {hard} ({boundary_edges} boundary, {} tagged)",
        hard - boundary_edges
    )?;
    let kinds = net.vertex_kinds();
    let count = |k: VertexKind| {
        (0..nv)
            .filter(|&v| kinds[v] == k && !topo.is_unreferenced(v))
            .count()
    };
    writeln!(
        out,
        "vertex kinds: smooth {}  dart {}  crease {}  corner {}",
        count(VertexKind::Smooth),
        count(VertexKind::Dart),
        count(VertexKind::Crease),
        count(VertexKind::Corner)
    )?;
    Ok(())
}

/// How far the control vertices lie from their limit points (the paper's
/// deviation figure), relative to the bounding-box diagonal.
fn limit_deviation(out: &mut dyn Write, net: &ControlNet) -> std::io::Result<()> {
    let topo = net.topology();
    let nv = topo.num_vertices();
    let diagonal = net.bbox_diagonal();
    let limits = net.limit_points();
    let deviations: Vec<f64> = (0..nv)
        .filter(|&v| !topo.is_unreferenced(v))
        .map(|v| (limits[v] - net.points()[v]).length())
        .collect();
    let mean = deviations.iter().sum::<f64>() / deviations.len() as f64;
    let max = deviations.iter().copied().fold(0.0, f64::max);
    writeln!(out, "bounding-box diagonal: {diagonal}")?;
    writeln!(
        out,
        "limit deviation of control vertices: mean {:.4}%  max {:.4}% of the diagonal",
        100.0 * mean / diagonal,
        100.0 * max / diagonal
    )?;
    Ok(())
}
