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
const CHECKSUM_BYTES: usize = 4;

/// The surface as a versioned, checksummed byte stream
/// (see [`from_bytes`]).
pub fn to_bytes(surface: &Surface) -> Vec<u8> {
    let net = surface.net();
    let hard = net.hard_edges();
    let tagged: Vec<u32> = (0..net.points().len() as u32)
        .filter(|&v| net.features().is_tagged_vertex(v as usize))
        .collect();
    let len = HEADER_BYTES
        + 24 * net.points().len()
        + 12 * net.triangles().len()
        + 8 * hard.len()
        + 4 * tagged.len()
        + CHECKSUM_BYTES;
    let mut out = Vec::with_capacity(len);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    let mode = MODES
        .iter()
        .position(|&m| m == surface.mode())
        .expect("every mode listed") as u32;
    out.extend_from_slice(&mode.to_le_bytes());
    for count in [
        net.points().len(),
        net.triangles().len(),
        hard.len(),
        tagged.len(),
    ] {
        out.extend_from_slice(&(count as u64).to_le_bytes());
    }
    for p in net.points() {
        for c in p.to_array() {
            out.extend_from_slice(&c.to_le_bytes());
        }
    }
    let indices = net.triangles().iter().flatten();
    for i in indices.chain(hard.iter().flatten()).chain(&tagged) {
        out.extend_from_slice(&i.to_le_bytes());
    }
    let crc = crc32fast::hash(&out);
    out.extend_from_slice(&crc.to_le_bytes());
    debug_assert_eq!(out.len(), len);
    out
}

/// Rebuilds a surface from [`to_bytes`] output. Evaluations of
/// the result are bit-identical to those of the original.
pub fn from_bytes(bytes: &[u8]) -> Result<Surface> {
    let (net, mode) = read_net(bytes)?;
    Surface::from_net(net, mode)
}

fn bad(message: impl Into<String>) -> Error {
    Error::Stream {
        message: message.into(),
    }
}

/// Parses and validates the control net a stream describes.
fn read_net(bytes: &[u8]) -> Result<(ControlNet, SurfaceMode)> {
    if bytes.len() < HEADER_BYTES + CHECKSUM_BYTES {
        return Err(bad(format!(
            "{} bytes: too short for a loopsurf surface (at least {} bytes)",
            bytes.len(),
            HEADER_BYTES + CHECKSUM_BYTES
        )));
    }
    if &bytes[..8] != MAGIC {
        return Err(bad("not a loopsurf surface (bad magic number)"));
    }
    let mut r = Reader { bytes, pos: 8 };
    let version = r.u32();
    if version != FORMAT_VERSION {
        return Err(bad(format!(
            "format version {version}; this library reads version {FORMAT_VERSION}"
        )));
    }
    let mode = r.u32();
    let mode = *MODES
        .get(mode as usize)
        .ok_or_else(|| bad(format!("unknown surface mode {mode}")))?;
    let counts = [r.u64(), r.u64(), r.u64(), r.u64()];
    let expected = [24u64, 12, 8, 4]
        .iter()
        .zip(counts)
        .try_fold((HEADER_BYTES + CHECKSUM_BYTES) as u64, |sum, (size, n)| {
            n.checked_mul(*size).and_then(|b| b.checked_add(sum))
        });
    if expected != Some(bytes.len() as u64) {
        return Err(bad(format!(
            "{} bytes, but its header announces {} vertices, {} triangles, {} hard edges and {} tagged vertices (truncated or damaged)",
            bytes.len(),
            counts[0],
            counts[1],
            counts[2],
            counts[3]
        )));
    }
    let body = bytes.len() - CHECKSUM_BYTES;
    let stored = u32::from_le_bytes(bytes[body..].try_into().expect("4 bytes"));
    if crc32fast::hash(&bytes[..body]) != stored {
        return Err(bad("checksum mismatch (damaged in transit)"));
    }
    // The length check bounds every count by the stream size.
    let [nverts, ntris, nhard, ntagged] = counts.map(|n| n as usize);
    let points: Vec<DVec3> = (0..nverts)
        .map(|_| DVec3::new(r.f64(), r.f64(), r.f64()))
        .collect();
    let tris: Vec<[u32; 3]> = (0..ntris).map(|_| [r.u32(), r.u32(), r.u32()]).collect();
    let hard: Vec<[u32; 2]> = (0..nhard).map(|_| [r.u32(), r.u32()]).collect();
    let tagged: Vec<u32> = (0..ntagged).map(|_| r.u32()).collect();
    let invalid = |e: Error| bad(format!("describes an invalid net: {e}"));
    let mut net = ControlNet::from_arrays(points, &tris).map_err(invalid)?;
    for [a, b] in hard {
        net.tag_edge(a, b).map_err(invalid)?;
    }
    for v in tagged {
        net.tag_vertex(v).map_err(invalid)?;
    }
    Ok((net, mode))
}

/// Sequential little-endian reads; callers have checked the length.
struct Reader<'a> {
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
    fn u32(&mut self) -> u32 {
        u32::from_le_bytes(self.take())
    }
    fn u64(&mut self) -> u64 {
        u64::from_le_bytes(self.take())
    }
    fn f64(&mut self) -> f64 {
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
