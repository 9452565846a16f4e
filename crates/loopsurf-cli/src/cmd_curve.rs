//! `loopsurf curve`: a linear surface mesh made by another tool (gmsh, a
//! CAD mesher, an earlier `loopsurf mesh`) put onto the exact surface and
//! raised to curved Lagrange elements.

use crate::curved_output;
use crate::input::{Input, SurfaceOptions};
use loopsurf::io::{self, LagrangeMesh, ParseOptions};
use loopsurf::mesh::high_order::{onto_surface, CurvedMesh, DEFAULT_MAX_MOVE};
use loopsurf::{DVec3, Error};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The linear mesh to curve: .msh (gmsh 4.1 or 2.2; of higher-order
    /// elements only the corners are used, renumbered in node order), .vtu,
    /// .obj, .off, .stl or .ply.
    #[arg(value_name = "LINEAR_MESH")]
    linear: PathBuf,
    /// The control net whose surface the mesh is curved onto.
    #[arg(long, value_name = "NET", required_unless_present = "example")]
    net: Option<PathBuf>,
    /// A built-in control net instead of --net (viking, sphere, torus, ...).
    #[arg(long, value_name = "NAME", conflicts_with = "net")]
    example: Option<String>,
    /// Tag every edge of the net whose dihedral angle exceeds DEG degrees
    /// as hard (as when the linear mesh was made).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    hard_angle: Option<f64>,
    /// Tag the net's edges listed in FILE (lines `i j`, 0-based) as hard.
    #[arg(long, value_name = "FILE")]
    hard_edges: Option<PathBuf>,
    /// Tag the net's vertices listed in FILE (one 0-based index a line) as corners.
    #[arg(long, value_name = "FILE")]
    hard_vertices: Option<PathBuf>,
    /// Split the net's concave corners by seams, as `loopsurf mesh --concave-seams`.
    #[arg(long)]
    concave_seams: bool,
    #[command(flatten)]
    surface: SurfaceOptions,
    /// Order of the curved elements (1 to 4).
    #[arg(long, value_name = "K", default_value_t = 2)]
    order: usize,
    /// Refuse when a vertex lies farther than this fraction of the net's
    /// bounding-box diagonal from the surface (the wrong model or units).
    #[arg(long, value_name = "FRACTION", default_value_t = DEFAULT_MAX_MOVE)]
    max_move: f64,
    /// Output file: .msh (gmsh 4.1) or .vtu (VTK Lagrange cells).
    #[arg(long, short = 'o', value_name = "OUT")]
    output: PathBuf,
    /// Write .msh in gmsh's binary format, and .vtu with inline binary
    /// (base64) arrays, instead of ASCII.
    #[arg(long)]
    binary: bool,
    /// Also measure the largest distance to the surface of the input mesh
    /// as it is (its own nodes: a .msh or .vtu of any order) and of the
    /// curved one, at 15 interior points per element by certified snap.
    #[arg(long)]
    measure: bool,
}

pub fn run(args: Args) -> Result<(), Error> {
    if curved_output::CurvedFormat::of(&args.output).is_none() {
        return Err(Error::InvalidArgument(format!(
            "{}: the output must be .msh or .vtu",
            args.output.display()
        )));
    }
    let input = Input {
        mesh: args.net.clone(),
        example: args.example.clone(),
        triangulate: false,
        weld: None,
        orient: false,
        split_nonmanifold: false,
        allow_degenerate: false,
        repair: false,
        hard_angle: args.hard_angle,
        hard_edges: args.hard_edges.clone(),
        hard_vertices: args.hard_vertices.clone(),
        concave_seams: args.concave_seams,
    };
    let net = input.load()?;
    let given = read_given(&args.linear)?;
    let (points, triangles) = corners_of(&given);
    let surface = args.surface.build(&net)?;
    let start = Instant::now();
    let onto = onto_surface(&surface, &points, &triangles, args.max_move)?;
    let curved = onto.mesh.raise_order(&surface, args.order)?;
    let seconds = start.elapsed().as_secs_f64();
    let validity = curved.validity();
    curved_output::write_curved(&args.output, &curved, &validity, args.binary)?;
    let diagonal = net.bbox_diagonal();
    let measured = if args.measure {
        let before = CurvedMesh::from_lagrange(&given, diagonal).distance_to(&surface)?;
        Some((given.order, before, curved.distance_to(&surface)?))
    } else {
        None
    };
    crate::write_stdout(|out| {
        writeln!(out, "{}", input.describe(&net))?;
        writeln!(
            out,
            "linear mesh: {} ({} vertices, {} triangles), {} faces, {} hard edges found",
            args.linear.display(),
            points.len(),
            triangles.len(),
            {
                let mut f = onto.mesh.faces.clone();
                f.sort_unstable();
                f.dedup();
                f.len()
            },
            onto.mesh.hard_edges.len()
        )?;
        writeln!(
            out,
            "largest vertex move: {:.3e} ({:.3e} of the diagonal) at vertex {}",
            onto.largest_move,
            onto.largest_move / diagonal,
            onto.largest_move_vertex
        )?;
        writeln!(out, "curved in {seconds:.3} s")?;
        if let Some((order, before, after)) = measured {
            writeln!(
                out,
                "largest distance to the surface: input (order {order}, as given) {:.3e} of the diagonal at triangle {}, curved {:.3e} at triangle {}",
                before.max / diagonal,
                before.triangle,
                after.max / diagonal,
                after.triangle
            )?;
        }
        curved_output::summary(out, &curved, &validity)?;
        writeln!(out, "wrote {}", args.output.display())
    })
}

/// The mesh in a file in any format `curve` reads, as it is (a flat
/// format gives order 1).
fn read_given(path: &Path) -> Result<LagrangeMesh, Error> {
    match curved_output::CurvedFormat::of(path) {
        Some(curved_output::CurvedFormat::Msh) => io::read_msh(path)?.to_lagrange(),
        Some(curved_output::CurvedFormat::Vtu) => io::read_vtu(path)?.to_lagrange(),
        None => {
            let data = io::read_mesh(path, &ParseOptions::default())?;
            let n = data.points.len() as i64;
            let mut triangles = Vec::with_capacity(3 * data.tris.len());
            for (t, tri) in data.tris.iter().enumerate() {
                if let Some(&i) = tri.iter().find(|&&i| i < 0 || i >= n) {
                    return Err(Error::InvalidArgument(format!(
                        "triangle {t} refers to vertex {i}, but there are {n} vertices"
                    ))
                    .in_file(path, data.tri_lines.get(t).copied()));
                }
                triangles.extend(tri.map(|i| i as u32));
            }
            Ok(LagrangeMesh {
                order: 1,
                faces: vec![0; data.tris.len()],
                nodes: data.points,
                triangles,
                ..Default::default()
            })
        }
    }
}

/// The vertices and flat triangles of a mesh: of curved elements, their
/// corners, numbered in the file's node order (edge and interior nodes
/// are dropped: they are placed anew).
fn corners_of(mesh: &LagrangeMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let per = mesh.nodes_per_triangle();
    let mut index = vec![u32::MAX; mesh.nodes.len()];
    for e in mesh.triangles.chunks(per) {
        for &i in &e[..3] {
            index[i as usize] = 0;
        }
    }
    let mut points = Vec::new();
    for (i, slot) in index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = points.len() as u32;
            points.push(mesh.nodes[i]);
        }
    }
    let tris = mesh
        .triangles
        .chunks(per)
        .map(|e| [e[0], e[1], e[2]].map(|i| index[i as usize]))
        .collect();
    (points, tris)
}
