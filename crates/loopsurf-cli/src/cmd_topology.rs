//! `loopsurf topology`: the model of the net's hard features (docs/design.md,
//! "The model") as text, and optionally as a .vtu of the control net
//! labelled with it.
//!
//! stdout: `faces F edges E corners C`, then per model edge (curve)
//! `edge ID corners A B chain v0 v1 ... vn` (corner ids, -1 -1 for a closed
//! loop; the n + 1 control vertices in parameter order, a closed loop
//! repeating its first), then per face `face ID triangles N loops L`.

use crate::input::{FitOptions, Input};
use loopsurf::io::{self, DataArray};
use loopsurf::model::Model;
use loopsurf::Error;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    #[command(flatten)]
    fit: FitOptions,
    /// Also write the control net as a .vtu: per triangle its `face`, one
    /// line cell per hard edge with its `edge` (curve) id, per vertex its
    /// `corner` id (-1 where none applies).
    #[arg(long, short = 'o', value_name = "OUT.vtu")]
    output: Option<PathBuf>,
    /// Write .vtu with inline binary (base64) arrays instead of ASCII:
    /// about half the size, read by ParaView and meshio.
    #[arg(long)]
    binary: bool,
}

pub fn run(args: Args) -> Result<(), Error> {
    if let Some(path) = &args.output {
        let is_vtu = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("vtu"));
        if !is_vtu {
            return Err(Error::InvalidArgument(format!(
                "{}: topology writes a .vtu file only",
                path.display()
            )));
        }
        io::check_writable(path)?;
    }
    let net = args.fit.apply(args.input.load()?)?;
    let model = Model::new(net.topology(), net.features());
    if let Some(path) = &args.output {
        write_vtu(path, &net, &model, args.binary)?;
    }
    crate::write_stdout(|out| {
        writeln!(
            out,
            "faces {} edges {} corners {}",
            model.faces().len(),
            model.curves().len(),
            model.corners().len()
        )?;
        for (id, curve) in model.curves().iter().enumerate() {
            let [a, b] = curve.corners.map_or([-1, -1], |c| c.map(i64::from));
            write!(out, "edge {id} corners {a} {b} chain")?;
            for v in &curve.chain {
                write!(out, " {v}")?;
            }
            writeln!(out)?;
        }
        for (id, face) in model.faces().iter().enumerate() {
            writeln!(
                out,
                "face {id} triangles {} loops {}",
                face.triangles.len(),
                face.loops.len()
            )?;
        }
        Ok(())
    })
}

/// The control net with the model's ids: triangles with their `face`, then
/// one line cell per hard control edge with its `edge` (curve) id; each
/// cell array holds -1 on the cells of the other kind. Per vertex its
/// `corner` id, or -1.
fn write_vtu(
    path: &Path,
    net: &loopsurf::ControlNet,
    model: &Model,
    binary: bool,
) -> Result<(), Error> {
    let topo = net.topology();
    let lines: Vec<(u32, [u32; 2])> = model
        .curves()
        .iter()
        .enumerate()
        .flat_map(|(c, curve)| {
            curve
                .chain
                .windows(2)
                .map(move |w| (c as u32, [w[0], w[1]]))
        })
        .collect();
    let nt = topo.num_triangles();
    let face: Vec<i32> = (model.face_of_triangle().iter().map(|&f| f as i32))
        .chain(std::iter::repeat(-1).take(lines.len()))
        .collect();
    let edge: Vec<i32> = std::iter::repeat(-1)
        .take(nt)
        .chain(lines.iter().map(|&(c, _)| c as i32))
        .collect();
    let mut corner = vec![-1i32; net.points().len()];
    for (id, &v) in model.corners().iter().enumerate() {
        corner[v as usize] = id as i32;
    }
    let segments: Vec<[u32; 2]> = lines.iter().map(|&(_, l)| l).collect();
    io::write_vtu_with_lines(
        path,
        net.points(),
        net.triangles(),
        &segments,
        &[("corner", DataArray::I32(&corner))],
        &[
            ("face", DataArray::I32(&face)),
            ("edge", DataArray::I32(&edge)),
        ],
        binary,
    )
}
