//! A surface as bytes, for shipping to MPI ranks (`MPI_Bcast`) or caching.
//!
//! The stream holds what defines the limit surface — the control net's
//! points and triangles, its hard edges and tagged corners — not the
//! evaluator's tables: those are rebuilt on load, deterministically, so every
//! rank evaluates bit-identically to the sender. The stream stays small
//! (≈ 36 bytes per control vertex) and independent of evaluator internals.
//!
//! Layout, little-endian:
//!
//! | bytes | content |
//! |---|---|
//! | 8 | magic `LOOPSURF` |
//! | 4 | format version ([`FORMAT_VERSION`]) |
//! | 4 | surface mode: 0 approximating, 1 solved interpolating (the net stored is the solved one), 2 displacement |
//! | 4 × 8 | counts: vertices, triangles, hard edges, tagged vertices |
//! | 24 per vertex | x y z (f64) |
//! | 12 per triangle | c0 c1 c2 (u32) |
//! | 8 per hard edge | a b (u32) |
//! | 4 per tagged vertex | v (u32) |
//! | 4 | CRC-32 of everything before it |
//!
//! Loading checks the length against the counts before allocating, then the
//! checksum, then validates the net exactly like any other input: damaged
//! bytes give [`Error::Stream`], never a panic or a wrong surface.
//!
//! A part of a partitioned net ([`crate::partition::Part`]) has a stream of
//! its own in the same frame ([`part_to_bytes`], [`part_from_bytes`]).

use crate::error::{Error, Result};
use crate::net::ControlNet;
use crate::surface::{Surface, SurfaceMode};
use glam::DVec3;

const MAGIC: &[u8; 8] = b"LOOPSURF";
/// Version of the byte layout; bumped whenever it changes.
pub const FORMAT_VERSION: u32 = 1;
const MODES: [SurfaceMode; 3] = [
    SurfaceMode::Approximating,
    SurfaceMode::Solve,
    SurfaceMode::Displacement,
];
const HEADER_BYTES: usize = 8 + 4 + 4 + 4 * 8;

mod part;
pub use part::{part_from_bytes, part_to_bytes};
const CHECKSUM_BYTES: usize = 4;

/// The surface as a versioned, checksummed byte stream
/// (see [`from_bytes`]).
pub fn to_bytes(surface: &Surface) -> Vec<u8> {
    let net = surface.net();
    let body = NetBody::of(net);
    let mode = MODES
        .iter()
        .position(|&m| m == surface.mode())
        .expect("every mode listed") as u32;
    let mut out = Vec::with_capacity(HEADER_BYTES + body.len() + CHECKSUM_BYTES);
    start(&mut out, MAGIC, mode, &body.counts());
    body.write(&mut out, net);
    seal(out)
}

/// Rebuilds a surface from [`to_bytes`] output. Evaluations of
/// the result are bit-identical to those of the original.
pub fn from_bytes(bytes: &[u8]) -> Result<Surface> {
    let (net, mode) = read_net(bytes)?;
    Surface::from_net(net, mode)
}

fn bad(message: impl Into<String>) -> Error {
    Error::Stream {
        what: "surface",
        message: message.into(),
    }
}

/// Parses and validates the control net a stream describes.
fn read_net(bytes: &[u8]) -> Result<(ControlNet, SurfaceMode)> {
    let frame = Frame {
        magic: MAGIC,
        what: "surface",
        sizes: &NetBody::SIZES,
        names: &NetBody::NAMES,
    };
    let (mut r, tag, counts) = frame.open(bytes)?;
    let mode = *MODES
        .get(tag as usize)
        .ok_or_else(|| bad(format!("unknown surface mode {tag}")))?;
    let net = NetBody::read(&mut r, &counts).map_err(bad)?;
    Ok((net, mode))
}

/// What makes a net in a stream: points, triangles, hard edges, tagged
/// vertices, with their counts in the header.
pub(crate) struct NetBody {
    hard: Vec<[u32; 2]>,
    tagged: Vec<u32>,
    sizes: [usize; 2],
}

impl NetBody {
    /// Bytes per item of each count.
    const SIZES: [u64; 4] = [24, 12, 8, 4];
    const NAMES: [&'static str; 4] = ["vertices", "triangles", "hard edges", "tagged vertices"];

    pub fn of(net: &ControlNet) -> NetBody {
        let tagged = (0..net.points().len() as u32)
            .filter(|&v| net.features().is_tagged_vertex(v as usize))
            .collect();
        NetBody {
            hard: net.hard_edges(),
            tagged,
            sizes: [net.points().len(), net.triangles().len()],
        }
    }

    pub fn counts(&self) -> [u64; 4] {
        let [v, t] = self.sizes;
        [v, t, self.hard.len(), self.tagged.len()].map(|n| n as u64)
    }

    /// Bytes of the body.
    pub fn len(&self) -> usize {
        let counts = self.counts();
        (0..4).map(|i| (Self::SIZES[i] * counts[i]) as usize).sum()
    }

    pub fn write(&self, out: &mut Vec<u8>, net: &ControlNet) {
        for p in net.points() {
            for c in p.to_array() {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        let indices = net.triangles().iter().flatten();
        for i in indices
            .chain(self.hard.iter().flatten())
            .chain(&self.tagged)
        {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }

    /// Reads and validates the net of the first four `counts`; the
    /// message says what is wrong.
    pub fn read(r: &mut Reader, counts: &[u64]) -> std::result::Result<ControlNet, String> {
        // The length check bounds every count by the stream size.
        let [nverts, ntris, nhard, ntagged] = [0, 1, 2, 3].map(|i| counts[i] as usize);
        let points: Vec<DVec3> = (0..nverts)
            .map(|_| DVec3::new(r.f64(), r.f64(), r.f64()))
            .collect();
        let tris: Vec<[u32; 3]> = (0..ntris).map(|_| [r.u32(), r.u32(), r.u32()]).collect();
        let hard: Vec<[u32; 2]> = (0..nhard).map(|_| [r.u32(), r.u32()]).collect();
        let tagged: Vec<u32> = (0..ntagged).map(|_| r.u32()).collect();
        let invalid = |e: Error| format!("describes an invalid net: {e}");
        let mut net = ControlNet::from_arrays(points, &tris).map_err(invalid)?;
        for [a, b] in hard {
            net.tag_edge(a, b).map_err(invalid)?;
        }
        for v in tagged {
            net.tag_vertex(v).map_err(invalid)?;
        }
        Ok(net)
    }
}

/// Starts a stream: magic, version, a tag (the surface mode) and the counts.
pub(crate) fn start(out: &mut Vec<u8>, magic: &[u8; 8], tag: u32, counts: &[u64]) {
    out.extend_from_slice(magic);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&tag.to_le_bytes());
    for count in counts {
        out.extend_from_slice(&count.to_le_bytes());
    }
}

/// Ends a stream with the checksum of everything before it.
pub(crate) fn seal(mut out: Vec<u8>) -> Vec<u8> {
    let crc = crc32fast::hash(&out);
    out.extend_from_slice(&crc.to_le_bytes());
    out
}

/// The frame every stream shares: magic, version, a tag, 64-bit counts,
/// a body whose length the counts fix, and a CRC-32 of all before it.
pub(crate) struct Frame<'a> {
    pub magic: &'a [u8; 8],
    /// "surface" or "part", for messages.
    pub what: &'static str,
    /// Bytes per item of each count.
    pub sizes: &'a [u64],
    /// Each count's name, for messages.
    pub names: &'a [&'static str],
}

impl Frame<'_> {
    /// Checks the magic, version, length against the counts (before
    /// anything is allocated) and checksum; returns a reader at the body,
    /// the tag and the counts.
    pub fn open<'b>(&self, bytes: &'b [u8]) -> Result<(Reader<'b>, u32, Vec<u64>)> {
        let what = self.what;
        let bad = |message: String| Error::Stream { what, message };
        let header = 16 + 8 * self.sizes.len();
        if bytes.len() < header + CHECKSUM_BYTES {
            return Err(bad(format!(
                "{} bytes: too short for a loopsurf {what} (at least {} bytes)",
                bytes.len(),
                header + CHECKSUM_BYTES
            )));
        }
        if &bytes[..8] != self.magic {
            return Err(bad(format!("not a loopsurf {what} (bad magic number)")));
        }
        let mut r = Reader { bytes, pos: 8 };
        let version = r.u32();
        if version != FORMAT_VERSION {
            return Err(bad(format!(
                "format version {version}; this library reads version {FORMAT_VERSION}"
            )));
        }
        let tag = r.u32();
        let counts: Vec<u64> = self.sizes.iter().map(|_| r.u64()).collect();
        let expected = self
            .sizes
            .iter()
            .zip(&counts)
            .try_fold((header + CHECKSUM_BYTES) as u64, |sum, (size, n)| {
                n.checked_mul(*size).and_then(|b| b.checked_add(sum))
            });
        if expected != Some(bytes.len() as u64) {
            let announced: Vec<String> = counts
                .iter()
                .zip(self.names)
                .map(|(n, name)| format!("{n} {name}"))
                .collect();
            return Err(bad(format!(
                "{} bytes, but its header announces {} (truncated or damaged)",
                bytes.len(),
                announced.join(", ")
            )));
        }
        let body = bytes.len() - CHECKSUM_BYTES;
        let stored = u32::from_le_bytes(bytes[body..].try_into().expect("4 bytes"));
        if crc32fast::hash(&bytes[..body]) != stored {
            return Err(bad("checksum mismatch (damaged in transit)".into()));
        }
        Ok((r, tag, counts))
    }
}

/// Sequential little-endian reads; callers have checked the length.
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> [u8; N] {
        let out = self.bytes[self.pos..self.pos + N]
            .try_into()
            .expect("length checked against the header");
        self.pos += N;
        out
    }
    pub fn u8(&mut self) -> u8 {
        u8::from_le_bytes(self.take())
    }
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes(self.take())
    }
    pub fn u64(&mut self) -> u64 {
        u64::from_le_bytes(self.take())
    }
    pub fn f64(&mut self) -> f64 {
        f64::from_le_bytes(self.take())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::examples;

    fn net(name: &str) -> ControlNet {
        let e = examples::by_name(name).unwrap();
        ControlNet::from_arrays(e.points, &e.tris).unwrap()
    }

    fn viking() -> Surface {
        let mut net = net("viking");
        net.tag_by_angle(30.0).unwrap();
        net.tag_vertex(5).unwrap();
        Surface::new(&net).unwrap()
    }

    #[test]
    fn round_trip_is_bit_identical() {
        let s = viking();
        let bytes = to_bytes(&s);
        let t = from_bytes(&bytes).unwrap();
        assert_eq!(t.net().hard_edges(), s.net().hard_edges());
        assert_eq!(t.net().vertex_kinds(), s.net().vertex_kinds());
        assert_eq!(to_bytes(&t), bytes);
        for tri in (0..s.net().triangles().len()).step_by(7) {
            for (v, w) in [(0.1, 0.2), (0.0, 0.0), (0.5, 0.5), (1.0 / 3.0, 0.25)] {
                let (a, b) = (s.eval(tri, v, w).unwrap(), t.eval(tri, v, w).unwrap());
                assert_eq!(a.record().map(f64::to_bits), b.record().map(f64::to_bits));
            }
        }
    }

    #[test]
    fn every_mode_round_trips() {
        let mut net = net("viking");
        net.tag_by_angle(30.0).unwrap();
        for mode in MODES {
            let s = Surface::with_mode(&net, mode).unwrap();
            let t = from_bytes(&to_bytes(&s)).unwrap();
            assert_eq!(t.mode(), mode);
            let (a, b) = (s.eval(7, 0.2, 0.3).unwrap(), t.eval(7, 0.2, 0.3).unwrap());
            assert_eq!(a.record().map(f64::to_bits), b.record().map(f64::to_bits));
        }
    }

    #[test]
    fn every_truncation_and_every_flipped_byte_is_an_error() {
        let mut net = net("tetra");
        net.tag_vertex(0).unwrap();
        let bytes = to_bytes(&Surface::new(&net).unwrap());
        let stream_error = |b: &[u8]| matches!(from_bytes(b), Err(Error::Stream { .. }));
        for n in 0..bytes.len() {
            assert!(stream_error(&bytes[..n]), "truncated to {n} bytes");
        }
        for i in 0..bytes.len() {
            let mut damaged = bytes.clone();
            damaged[i] ^= 0x5a;
            assert!(stream_error(&damaged), "byte {i} flipped");
        }
    }

    #[test]
    fn a_valid_checksum_over_an_invalid_net_is_still_rejected() {
        let bytes = to_bytes(&viking());
        // Point triangle 0's first corner at a vertex that does not exist,
        // then re-seal the stream so only validation can catch it.
        let mut forged = bytes.clone();
        let at = HEADER_BYTES + 24 * 842;
        forged[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
        let body = forged.len() - CHECKSUM_BYTES;
        let crc = crc32fast::hash(&forged[..body]);
        forged[body..].copy_from_slice(&crc.to_le_bytes());
        let err = from_bytes(&forged).err().unwrap().to_string();
        assert!(
            err.contains("invalid net") && err.contains("triangle 0"),
            "{err}"
        );
    }

    #[test]
    fn huge_counts_do_not_allocate() {
        let mut bytes = to_bytes(&viking());
        bytes[16..24].copy_from_slice(&u64::MAX.to_le_bytes());
        assert!(matches!(from_bytes(&bytes), Err(Error::Stream { .. })));
    }
}
