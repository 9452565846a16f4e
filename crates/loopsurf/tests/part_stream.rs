//! A part travels on its own: its stream rebuilds the same part (the same
//! bytes again, the same maps, the same bits from its surface), and a
//! truncated, damaged or foreign stream is a clear error.

mod common;

use loopsurf::partition::{part, partition, Part};
use loopsurf::stream::{part_from_bytes, part_to_bytes, to_bytes};
use loopsurf::{Error, Surface};

fn viking_part(k: usize, p: usize) -> Part {
    let mut net = common::example("viking", Some(30.0));
    net.tag_vertex(5).unwrap();
    part(&net, &partition(&net, k).unwrap(), p).unwrap()
}

#[test]
fn a_part_round_trips_bit_for_bit() {
    for p in 0..3 {
        let sent = viking_part(3, p);
        let bytes = part_to_bytes(&sent);
        let got = part_from_bytes(&bytes).unwrap();
        assert_eq!(part_to_bytes(&got), bytes);
        assert_eq!(got.global_triangles(), sent.global_triangles());
        assert_eq!(got.global_vertices(), sent.global_vertices());
        assert_eq!(got.vertex_kinds(), sent.vertex_kinds());
        assert_eq!(got.whole_size(), sent.whole_size());
        assert_eq!(
            got.owned().collect::<Vec<_>>(),
            sent.owned().collect::<Vec<_>>()
        );
        assert_eq!(got.net().hard_edges(), sent.net().hard_edges());
        let (a, b) = (
            Surface::new(sent.net()).unwrap(),
            Surface::new(got.net()).unwrap(),
        );
        for t in sent.owned() {
            for (v, w) in [(0.0, 0.0), (0.2, 0.3), (1.0, 0.0), (0.5, 0.5)] {
                let (x, y) = (a.eval(t, v, w).unwrap(), b.eval(t, v, w).unwrap());
                assert_eq!(x.record().map(f64::to_bits), y.record().map(f64::to_bits));
            }
        }
    }
}

#[test]
fn every_truncation_and_flipped_byte_is_a_part_stream_error() {
    let bytes = part_to_bytes(&viking_part(16, 3));
    let refused = |b: &[u8]| match part_from_bytes(b) {
        Err(e @ Error::Stream { .. }) => e.to_string().starts_with("part stream: "),
        _ => false,
    };
    // Every length short of the whole, a few hundred of them spread out,
    // and every byte of the header and the last maps flipped.
    let step = (bytes.len() / 300).max(1);
    for n in (0..bytes.len()).step_by(step) {
        assert!(refused(&bytes[..n]), "truncated to {n} bytes");
    }
    let tail = bytes.len().saturating_sub(400);
    for i in (0..64).chain(tail..bytes.len()) {
        let mut damaged = bytes.clone();
        damaged[i] ^= 0x5a;
        assert!(refused(&damaged), "byte {i} flipped");
    }
}

#[test]
fn a_surface_stream_is_not_a_part() {
    let net = common::example("viking", Some(30.0));
    let surface = to_bytes(&Surface::new(&net).unwrap());
    let err = part_from_bytes(&surface).err().unwrap().to_string();
    assert!(err.contains("not a loopsurf part"), "{err}");
}

/// Forged maps under a valid checksum are still refused, naming them.
#[test]
fn forged_maps_are_refused() {
    let bytes = part_to_bytes(&viking_part(4, 1));
    let n = bytes.len();
    let reseal = |mut b: Vec<u8>| {
        let crc = crc32(&b[..n - 4]);
        b[n - 4..].copy_from_slice(&crc.to_le_bytes());
        b
    };
    // The last byte before the checksum is the last triangle's owned flag.
    let mut forged = bytes.clone();
    forged[n - 5] = 7;
    let err = part_from_bytes(&reseal(forged)).err().unwrap().to_string();
    assert!(err.contains("flag byte 7"), "{err}");
}

/// CRC-32 (IEEE), bit by bit: the stream's checksum, computed apart from
/// the library.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}
