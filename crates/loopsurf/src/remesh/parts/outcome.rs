//! A task's outcome, and a rank's outcomes as bytes, so that an MPI job
//! can send them to every rank (`MPI_Allgatherv`): the frame of a surface
//! stream (magic, version, 64-bit counts, CRC-32) with its own magic.
//!
//! Layout of one outcome after the frame's header, little-endian; the tag
//! is 0 for a part's sizes, 1 for a remeshed piece, 2 for the band of a
//! first-pass piece:
//!
//! | bytes | content |
//! |---|---|
//! | 56 per vertex | x y z (f64), control triangle (u32), v w (f64), pinned start vertex or 0xffffffff (u32), target size (f64) |
//! | 16 per triangle | a b c (u32), model face (u32) |
//! | 12 per control-triangle value | control triangle (u32), value (f64): a piece's shrink factors, or the sizes of a part's own triangles where they follow curvature |
//! | 8 per number | the largest size, then the triangles expected; or the diagonal, then the chord error measured if any, then (a band) how many vertices its interior holds off the rim |
//! | 4 per rim vertex | a band's vertex (u32) that its interior shares, in the interior's order |
//!
//! A rank's outcomes are a u64 count, then per outcome its task (u64),
//! its length in bytes (u64) and the outcome. Every f64 travels as its
//! bits, so the receiver joins exactly what the sender computed.

use super::super::finish::without_curves;
use super::interior::Interior;
use super::work::{PartWork, Piece};
use crate::error::{Error, Result};
use crate::parameters::SurfacePoint;
use crate::stream::{seal, start, Frame, Reader};
use glam::DVec3;

const MAGIC: &[u8; 8] = b"LOOPTASK";
const SIZES: [u64; 5] = [56, 16, 12, 8, 4];
const NAMES: [&str; 5] = [
    "vertices",
    "triangles",
    "control-triangle values",
    "numbers",
    "rim vertices",
];
const SIZES_TAG: u32 = 0;
const PIECE: u32 = 1;
const BAND: u32 = 2;

/// What one task of a [`super::PartsJob`] stage computed.
pub struct TaskOutcome(pub(super) Outcome);

pub(super) enum Outcome {
    /// A part's sizes: the largest size it asks for, about how many
    /// triangles it asks for over its own control triangles (what its
    /// first-pass task weighs), where sizes follow curvature each of its
    /// own control triangles' size (global id, size), and its work where
    /// it was built here (not sent: the rank that built it keeps it for
    /// its first pass).
    Sizes {
        largest: f64,
        expected: f64,
        sizes: Vec<(u32, f64)>,
        work: Option<Box<PartWork>>,
    },
    Piece(Box<Piece>),
    /// A first-pass piece split where the later passes cannot reach
    /// ([`super::interior::split`]): its band, the band's vertices on the
    /// rim it shares with the interior (in the interior's order), how many
    /// vertices the interior holds off the rim, and the interior where it
    /// was made here (not sent: the rank that made it keeps it).
    Band {
        band: Box<Piece>,
        rim: Vec<u32>,
        inner: usize,
        interior: Option<Box<Interior>>,
    },
}

impl TaskOutcome {
    /// The outcome as a checksummed byte stream.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::new();
        match &self.0 {
            Outcome::Sizes {
                largest,
                expected,
                sizes,
                ..
            } => {
                start(
                    &mut out,
                    MAGIC,
                    SIZES_TAG,
                    &[0, 0, sizes.len() as u64, 2, 0],
                );
                pairs(&mut out, sizes);
                f64s(&mut out, &[*largest, *expected]);
            }
            Outcome::Piece(piece) => write_piece(&mut out, PIECE, piece, &[], None),
            Outcome::Band {
                band, rim, inner, ..
            } => write_piece(&mut out, BAND, band, rim, Some(*inner)),
        }
        seal(out)
    }

    /// Rebuilds an outcome from [`TaskOutcome::to_bytes`] output; a
    /// truncated, damaged or foreign stream is an [`Error::Stream`].
    pub fn from_bytes(bytes: &[u8]) -> Result<TaskOutcome> {
        let frame = Frame {
            magic: MAGIC,
            what: "task outcome",
            sizes: &SIZES,
            names: &NAMES,
        };
        let (mut r, tag, counts) = frame.open(bytes)?;
        let [nv, nt, ns, nn, nr] = [0, 1, 2, 3, 4].map(|i| counts[i] as usize);
        match (tag, nn) {
            (SIZES_TAG, 2) if nv + nt + nr == 0 => {
                let sizes = (0..ns).map(|_| (r.u32(), r.f64())).collect();
                Ok(TaskOutcome(Outcome::Sizes {
                    sizes,
                    largest: r.f64(),
                    expected: r.f64(),
                    work: None,
                }))
            }
            (PIECE, 1 | 2) if nr == 0 => {
                let piece = read_piece(&mut r, [nv, nt, ns], nn == 2)?;
                Ok(TaskOutcome(Outcome::Piece(Box::new(piece))))
            }
            (BAND, 2 | 3) => {
                let band = read_piece(&mut r, [nv, nt, ns], nn == 3)?;
                let inner = r.u64();
                if inner > u32::MAX as u64 {
                    return Err(bad(format!(
                        "an interior of {inner} vertices: more than vertex ids can number"
                    )));
                }
                let inner = inner as usize;
                let rim = (0..nr).map(|_| r.u32()).collect::<Vec<_>>();
                if let Some(&v) = rim.iter().find(|&&v| v as usize >= nv) {
                    return Err(bad(format!("rim vertex {v} of a band of {nv}")));
                }
                Ok(TaskOutcome(Outcome::Band {
                    band: Box::new(band),
                    rim,
                    inner,
                    interior: None,
                }))
            }
            _ => Err(bad(format!(
                "tag {tag} with {nn} numbers and {nr} rim vertices: neither a largest size, a piece nor a band"
            ))),
        }
    }
}

/// `piece` after a frame's header with tag `tag`, then (a band) its
/// interior's count of vertices off the rim `inner` and its rim vertices
/// `rim`.
fn write_piece(out: &mut Vec<u8>, tag: u32, piece: &Piece, rim: &[u32], inner: Option<usize>) {
    let mesh = &piece.mesh;
    let numbers = 1 + mesh.deviation.is_some() as u64 + inner.is_some() as u64;
    let counts = [
        mesh.points.len() as u64,
        mesh.triangles.len() as u64,
        piece.shrunk.len() as u64,
        numbers,
        rim.len() as u64,
    ];
    start(out, MAGIC, tag, &counts);
    for (i, x) in mesh.points.iter().enumerate() {
        let at = mesh.params[i];
        f64s(out, &x.to_array());
        out.extend_from_slice(&at.tri.to_le_bytes());
        f64s(out, &[at.v, at.w]);
        out.extend_from_slice(&piece.pinned[i].to_le_bytes());
        f64s(out, &[piece.sizes[i]]);
    }
    for (tri, face) in mesh.triangles.iter().zip(&mesh.faces) {
        for i in tri.iter().chain([face]) {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }
    pairs(out, &piece.shrunk);
    f64s(out, &[mesh.diagonal]);
    if let Some(d) = mesh.deviation {
        f64s(out, &[d]);
    }
    if let Some(n) = inner {
        out.extend_from_slice(&(n as u64).to_le_bytes());
    }
    for v in rim {
        out.extend_from_slice(&v.to_le_bytes());
    }
}

/// A piece of `nv` vertices, `nt` triangles and `ns` shrink factors, and
/// a chord error measured where `measured`, as [`write_piece`] wrote it.
fn read_piece(r: &mut Reader, [nv, nt, ns]: [usize; 3], measured: bool) -> Result<Piece> {
    let mut points = Vec::with_capacity(nv);
    let mut params = Vec::with_capacity(nv);
    let mut pinned = Vec::with_capacity(nv);
    let mut sizes = Vec::with_capacity(nv);
    for _ in 0..nv {
        points.push(DVec3::new(r.f64(), r.f64(), r.f64()));
        let tri = r.u32();
        params.push(SurfacePoint {
            tri,
            v: r.f64(),
            w: r.f64(),
        });
        pinned.push(r.u32());
        sizes.push(r.f64());
    }
    let mut triangles = Vec::with_capacity(nt);
    let mut faces = Vec::with_capacity(nt);
    for t in 0..nt {
        let tri = [r.u32(), r.u32(), r.u32()];
        if let Some(&v) = tri.iter().find(|&&v| v as usize >= nv) {
            return Err(bad(format!(
                "triangle {t} names vertex {v} of a piece of {nv}"
            )));
        }
        triangles.push(tri);
        faces.push(r.u32());
    }
    let shrunk = (0..ns).map(|_| (r.u32(), r.f64())).collect();
    let diagonal = r.f64();
    let deviation = measured.then(|| r.f64());
    let mesh = without_curves(points, triangles, params, faces, deviation, diagonal);
    Ok(Piece {
        mesh,
        pinned,
        sizes,
        shrunk,
    })
}

/// A rank's outcomes, each with its task, as one buffer (see the module
/// doc).
pub fn outcomes_to_bytes(outcomes: &[(usize, &TaskOutcome)]) -> Vec<u8> {
    let mut out = (outcomes.len() as u64).to_le_bytes().to_vec();
    for (task, outcome) in outcomes {
        let bytes = outcome.to_bytes();
        out.extend_from_slice(&(*task as u64).to_le_bytes());
        out.extend_from_slice(&(bytes.len() as u64).to_le_bytes());
        out.extend_from_slice(&bytes);
    }
    out
}

/// The outcomes of [`outcomes_to_bytes`], each with its task.
pub fn outcomes_from_bytes(bytes: &[u8]) -> Result<Vec<(usize, TaskOutcome)>> {
    let mut at = 0usize;
    let n = word(bytes, &mut at, "the count")?;
    let mut outcomes = Vec::new();
    for _ in 0..n {
        let task = word(bytes, &mut at, "a task")? as usize;
        let len = word(bytes, &mut at, "a length")?;
        let start = at;
        let end = usize::try_from(len)
            .ok()
            .and_then(|l| start.checked_add(l))
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| {
                bad(format!(
                    "an outcome of {len} bytes at byte {start} runs past the end"
                ))
            })?;
        outcomes.push((task, TaskOutcome::from_bytes(&bytes[start..end])?));
        at = end;
    }
    if at != bytes.len() {
        return Err(bad(format!(
            "{} bytes after the last of {n} outcomes",
            bytes.len() - at
        )));
    }
    Ok(outcomes)
}

/// The u64 at byte `at`, which moves past it; `what` names it for the
/// error when the bytes end first.
fn word(bytes: &[u8], at: &mut usize, what: &str) -> Result<u64> {
    let end = at.checked_add(8).filter(|&e| e <= bytes.len());
    let end = end.ok_or_else(|| {
        bad(format!(
            "{} bytes of outcomes end where {what} should be, at byte {at}",
            bytes.len()
        ))
    })?;
    let x = u64::from_le_bytes(bytes[*at..end].try_into().expect("8 bytes"));
    *at = end;
    Ok(x)
}

/// (control triangle, value) pairs.
fn pairs(out: &mut Vec<u8>, pairs: &[(u32, f64)]) {
    for &(t, x) in pairs {
        out.extend_from_slice(&t.to_le_bytes());
        f64s(out, &[x]);
    }
}

fn f64s(out: &mut Vec<u8>, xs: &[f64]) {
    for x in xs {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

fn bad(message: String) -> Error {
    Error::Stream {
        what: "task outcome",
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::{seal, start, TaskOutcome, BAND, MAGIC};

    /// A band of no vertices whose numbers are the diagonal and `inner`,
    /// with the rim vertices `rim`, checksummed as a sender would.
    fn band(inner: u64, rim: &[u32]) -> Vec<u8> {
        let mut out = Vec::new();
        start(&mut out, MAGIC, BAND, &[0, 0, 0, 2, rim.len() as u64]);
        out.extend_from_slice(&1.0f64.to_le_bytes());
        out.extend_from_slice(&inner.to_le_bytes());
        for v in rim {
            out.extend_from_slice(&v.to_le_bytes());
        }
        seal(out)
    }

    #[test]
    fn a_band_naming_what_it_cannot_hold_is_refused() {
        assert!(TaskOutcome::from_bytes(&band(7, &[])).is_ok());
        let err = TaskOutcome::from_bytes(&band(1 << 40, &[]))
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("more than vertex ids can number"), "{err}");
        let err = TaskOutcome::from_bytes(&band(7, &[0]))
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("rim vertex 0 of a band of 0"), "{err}");
    }
}
