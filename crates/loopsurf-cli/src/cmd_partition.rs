//! `loopsurf partition`: the control triangles in K parts for K processes,
//! with the edge cut and each part's halo, optionally written as a `part`
//! cell field on the control net.

use crate::input::Input;
use loopsurf::io::{self, DataArray};
use loopsurf::{partition, Error, Partition};
use std::io::Write;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    input: Input,
    /// Number of parts K (1 to the number of triangles).
    #[arg(long, value_name = "K")]
    parts: usize,
    /// METIS's random seed: the same seed gives the same parts.
    #[arg(long, value_name = "N", default_value_t = partition::PartitionOptions::default().seed, allow_negative_numbers = true)]
    seed: i32,
    /// Write the control net with each triangle's part as the cell field `part` (.vtu).
    #[arg(short = 'o', long = "output", value_name = "OUT.vtu")]
    output: Option<PathBuf>,
    /// Write .vtu with inline binary (base64) arrays instead of ASCII:
    /// about half the size, read by ParaView and meshio.
    #[arg(long)]
    binary: bool,
}

pub fn run(args: Args) -> Result<(), Error> {
    // A wrong output name is refused before any work.
    if let Some(path) = &args.output {
        if !path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("vtu"))
        {
            return Err(Error::InvalidArgument(format!(
                "{}: the part field is written as .vtu only",
                path.display()
            )));
        }
    }
    let net = args.input.load()?;
    let opts = partition::PartitionOptions { seed: args.seed };
    let parts = partition::partition_with(&net, args.parts, &opts)?;
    if let Some(path) = &args.output {
        let part: Vec<i32> = parts.parts().iter().map(|&p| p as i32).collect();
        io::write_vtu(
            path,
            net.points(),
            net.triangles(),
            &[],
            &[("part", DataArray::I32(&part))],
            args.binary,
        )?;
    }
    crate::write_stdout(|out| summary(out, &parts))
}

/// The first line is the whole partition at a glance; then one line a part.
fn summary(out: &mut dyn Write, p: &Partition) -> std::io::Result<()> {
    writeln!(
        out,
        "parts {} triangles {} cut {} largest {} halo {}",
        p.num_parts(),
        p.parts().len(),
        p.edge_cut(),
        p.largest(),
        p.largest_halo()
    )?;
    for q in 0..p.num_parts() {
        writeln!(
            out,
            "part {q} triangles {} halo {}",
            p.triangles(q).len(),
            p.halo(q).len()
        )?;
    }
    Ok(())
}
