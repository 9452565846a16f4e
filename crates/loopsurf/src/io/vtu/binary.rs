//! VTK's inline binary DataArrays (`format="binary"`): base64 of a byte
//! count (the VTKFile's `header_type`, UInt32 or UInt64) followed by the
//! raw little-endian values.
//!
//! Inline base64 rather than raw appended data: it keeps the file valid
//! XML, which every VTK XML reader (ParaView, meshio, VTK's Python) takes,
//! and costs a third more than raw bytes, still about half of ASCII. The
//! writer encodes the count and the values as two base64 runs, as VTK and
//! meshio do; the reader takes that and a single joint run.

use base64::engine::general_purpose::STANDARD;
use base64::Engine;

/// `data` as a binary DataArray's text: the UInt64 byte count and the
/// bytes, each base64-encoded.
pub(super) fn encode(data: &[u8]) -> String {
    let mut out = STANDARD.encode((data.len() as u64).to_le_bytes());
    STANDARD.encode_string(data, &mut out);
    out
}

/// The data bytes of a binary DataArray's text (whitespace ignored),
/// checked against the byte count in front; `header` is that count's size
/// in bytes (4 for UInt32, 8 for UInt64). Errors say what is wrong; the
/// caller says where.
pub(super) fn decode(text: &[u8], header: usize) -> Result<Vec<u8>, String> {
    let chars: Vec<u8> = text
        .iter()
        .copied()
        .filter(|b| !b.is_ascii_whitespace())
        .collect();
    // A count encoded on its own ends in '=' padding (4 and 8 bytes are
    // not multiples of 3); a joint run has padding at its end only.
    let head = header.div_ceil(3) * 4;
    let mut bytes = if chars.len() > head && chars[head - 1] == b'=' {
        let mut b = decode64(&chars[..head])?;
        b.extend(decode64(&chars[head..])?);
        b
    } else {
        decode64(&chars)?
    };
    if bytes.len() < header {
        return Err(format!(
            "{} bytes decoded, fewer than the {header}-byte count in front",
            bytes.len()
        ));
    }
    let mut count = [0u8; 8];
    count[..header].copy_from_slice(&bytes[..header]);
    let count = u64::from_le_bytes(count);
    bytes.drain(..header);
    if count != bytes.len() as u64 {
        return Err(format!(
            "the byte count in front says {count} bytes, the data has {}",
            bytes.len()
        ));
    }
    Ok(bytes)
}

fn decode64(chars: &[u8]) -> Result<Vec<u8>, String> {
    STANDARD
        .decode(chars)
        .map_err(|e| format!("damaged base64 ({e})"))
}

/// The values of a binary DataArray of VTK type `ty`, as f64 (integers
/// exactly up to 2^53, as the ASCII reader keeps them).
pub(super) fn values(bytes: &[u8], ty: &str) -> Result<Vec<f64>, String> {
    let (size, read) = reader(ty).ok_or_else(|| format!("type {ty:?} is not read in binary"))?;
    if bytes.len() % size != 0 {
        return Err(format!(
            "{} bytes are no whole number of {size}-byte {ty} values",
            bytes.len()
        ));
    }
    Ok(bytes.chunks_exact(size).map(read).collect())
}

/// Reads one little-endian value of a VTK type as f64.
type ReadValue = fn(&[u8]) -> f64;

/// A VTK type's size and its reading.
fn reader(ty: &str) -> Option<(usize, ReadValue)> {
    Some(match ty {
        "Float32" => (4, |b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64),
        "Float64" => (8, |b| f64::from_le_bytes(widen(b))),
        "Int8" => (1, signed),
        "Int16" => (2, signed),
        "Int32" => (4, signed),
        "Int64" => (8, signed),
        "UInt8" | "UInt16" | "UInt32" | "UInt64" => {
            let size = ty[4..].parse::<usize>().ok()? / 8;
            (size, |b| u64::from_le_bytes(widen(b)) as f64)
        }
        _ => return None,
    })
}

/// Up to 8 little-endian bytes, zero-extended.
fn widen(b: &[u8]) -> [u8; 8] {
    let mut a = [0u8; 8];
    a[..b.len()].copy_from_slice(b);
    a
}

/// A little-endian integer of 1 to 8 bytes, sign-extended.
fn signed(b: &[u8]) -> f64 {
    let shift = 64 - 8 * b.len() as u32;
    ((i64::from_le_bytes(widen(b)) << shift) >> shift) as f64
}
