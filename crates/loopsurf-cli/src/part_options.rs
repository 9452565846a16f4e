//! `--parts K --part P`: a command works on one part of the net as a
//! process of a K-way run would, building only that part's surface.

use loopsurf::partition::{self, Part, PartitionOptions};
use loopsurf::{ControlNet, Error, Partition};

/// Which part of a partitioned net to work on.
#[derive(clap::Args, Debug)]
pub struct PartOptions {
    /// Partition the control triangles into K parts (as `loopsurf
    /// partition` does) and work on one of them (--part): only its
    /// surface is built.
    #[arg(long, value_name = "K", requires = "part")]
    parts: Option<usize>,
    /// With --parts: the part to work on, 0 to K − 1.
    #[arg(long, value_name = "P", requires = "parts")]
    part: Option<usize>,
    /// With --parts: METIS's random seed, as `loopsurf partition --seed`.
    #[arg(
        long,
        value_name = "N",
        requires = "parts",
        allow_negative_numbers = true
    )]
    seed: Option<i32>,
}

/// One part, with the partition it comes from.
pub struct Selected {
    pub partition: Partition,
    pub part: Part,
    pub index: usize,
}

impl PartOptions {
    /// The chosen part of `net`, or `None` without --parts.
    pub fn select(&self, net: &ControlNet) -> Result<Option<Selected>, Error> {
        let (Some(k), Some(index)) = (self.parts, self.part) else {
            return Ok(None);
        };
        let mut opts = PartitionOptions::default();
        opts.seed = self.seed.unwrap_or(opts.seed);
        let partition = partition::partition_with(net, k, &opts)?;
        let part = partition::part(net, &partition, index)?;
        Ok(Some(Selected {
            partition,
            part,
            index,
        }))
    }
}

impl Selected {
    /// The local id of global triangle `t` when the part owns it; else an
    /// error naming its owner (or saying it does not exist).
    pub fn owned(&self, t: usize) -> Result<usize, Error> {
        let n = self.partition.parts().len();
        let owner = *self.partition.parts().get(t).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "triangle {t}: out of range (the net has {n} triangles)"
            ))
        })?;
        match self.part.local_triangle(t as u32) {
            Some(local) if self.part.is_owned(local) => Ok(local),
            _ => Err(Error::InvalidArgument(format!(
                "triangle {t} is owned by part {owner}, not by part {} of {}",
                self.index,
                self.partition.num_parts()
            ))),
        }
    }
}
