//! A part as bytes ([`crate::partition::Part`]), for sending each MPI rank
//! only its own: the frame of a surface stream (magic, version, 64-bit
//! counts, CRC-32), a different magic, the part's sub-net as a surface
//! stream holds a net, then the maps to the whole.
//!
//! Layout after the net's sections, little-endian:
//!
//! | bytes | content |
//! |---|---|
//! | 4 per vertex | global vertex id (u32) |
//! | 1 per vertex | kind in the whole: 0 smooth, 1 dart, 2 crease, 3 corner |
//! | 1 per vertex | 1 when on the whole's boundary, else 0 |
//! | 4 per triangle | global triangle id (u32) |
//! | 1 per triangle | 1 when owned, 0 when halo |
//!
//! The counts are the net's four (vertices, triangles, hard edges, tagged
//! vertices) and the whole's vertex and triangle counts; the tag is 0.
//! A stream of a part of 2 GiB and more is one buffer like any other: a
//! sender splits it into messages, not the format.

use super::{seal, start, Frame, NetBody, Reader};
use crate::error::{Error, Result};
use crate::features::VertexKind;
use crate::partition::Part;

const MAGIC: &[u8; 8] = b"LOOPPART";
const KINDS: [VertexKind; 4] = [
    VertexKind::Smooth,
    VertexKind::Dart,
    VertexKind::Crease,
    VertexKind::Corner,
];
/// Bytes per item of each count: the net's, with the maps added to its
/// vertices and triangles; the whole's counts have no items.
const SIZES: [u64; 6] = [24 + 4 + 1 + 1, 12 + 4 + 1, 8, 4, 0, 0];
const NAMES: [&str; 6] = [
    "vertices",
    "triangles",
    "hard edges",
    "tagged vertices",
    "vertices in the whole",
    "triangles in the whole",
];

/// The part as a versioned, checksummed byte stream (see
/// [`part_from_bytes`]).
pub fn part_to_bytes(part: &Part) -> Vec<u8> {
    let net = part.net();
    let body = NetBody::of(net);
    let [nv, nt] = [net.points().len(), net.triangles().len()];
    let mut counts = body.counts().to_vec();
    counts.extend(part.whole_size().map(|n| n as u64));
    let mut out = Vec::with_capacity(16 + 8 * 6 + body.len() + 6 * nv + 5 * nt + 4);
    start(&mut out, MAGIC, 0, &counts);
    body.write(&mut out, net);
    for &g in part.global_vertices() {
        out.extend_from_slice(&g.to_le_bytes());
    }
    for &k in part.vertex_kinds() {
        out.push(
            KINDS
                .iter()
                .position(|&x| x == k)
                .expect("every kind listed") as u8,
        );
    }
    out.extend((0..nv).map(|v| part.is_boundary_vertex(v) as u8));
    for &g in part.global_triangles() {
        out.extend_from_slice(&g.to_le_bytes());
    }
    out.extend((0..nt).map(|t| part.is_owned(t) as u8));
    seal(out)
}

/// Rebuilds a part from [`part_to_bytes`] output: the same sub-net, maps
/// and owned set, so that its surface evaluates bit for bit as the
/// sender's. A truncated, damaged or foreign stream is an
/// [`Error::Stream`].
pub fn part_from_bytes(bytes: &[u8]) -> Result<Part> {
    let frame = Frame {
        magic: MAGIC,
        what: "part",
        sizes: &SIZES,
        names: &NAMES,
    };
    let bad = |message: String| Error::Stream {
        what: "part",
        message,
    };
    let (mut r, _, counts) = frame.open(bytes)?;
    let net = NetBody::read(&mut r, &counts).map_err(bad)?;
    let [nv, nt] = [counts[0], counts[1]].map(|n| n as usize);
    let whole = [counts[4], counts[5]].map(|n| n as usize);
    let vertices: Vec<u32> = (0..nv).map(|_| r.u32()).collect();
    let kinds = (0..nv)
        .map(|_| {
            let k = r.u8();
            KINDS
                .get(k as usize)
                .copied()
                .ok_or_else(|| bad(format!("unknown vertex kind {k}")))
        })
        .collect::<Result<_>>()?;
    let boundary = flags(&mut r, nv).map_err(bad)?;
    let triangles: Vec<u32> = (0..nt).map(|_| r.u32()).collect();
    let owned = flags(&mut r, nt).map_err(bad)?;
    let part = Part {
        net,
        triangles,
        vertices,
        owned,
        kinds,
        boundary,
        whole,
    };
    part.checked().map_err(|e| {
        bad(match e {
            Error::InvalidArgument(m) => m,
            other => other.to_string(),
        })
    })
}

/// `n` bytes, each 0 or 1.
fn flags(r: &mut Reader, n: usize) -> std::result::Result<Vec<bool>, String> {
    (0..n)
        .map(|_| match r.u8() {
            0 => Ok(false),
            1 => Ok(true),
            x => Err(format!("flag byte {x}: neither 0 nor 1")),
        })
        .collect()
}
