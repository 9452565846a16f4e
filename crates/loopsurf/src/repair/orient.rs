//! `--orient`: one consistent orientation per connected piece.
//!
//! Triangles are joined across manifold edges (exactly two triangles); a
//! breadth-first walk from each piece's first triangle decides, for every
//! other triangle, whether it must turn to agree with its neighbour. A
//! piece where that decision contradicts itself is non-orientable (a
//! Möbius band) and is refused. A consistent piece is left alone, even if
//! it faces inward: only broken orientation is repaired. A piece that had
//! to be fixed is oriented outward when it is closed (positive enclosed
//! volume, the convention of docs/design.md), else as most of its triangles were.

use super::{edge_incidences, Repair};
use crate::error::{Error, Result};
use crate::io::MeshData;

/// Orients every piece of `mesh` in place; one report per changed piece.
pub(super) fn orient(mesh: &mut MeshData) -> Result<Vec<Repair>> {
    let (neighbours, boundary) = neighbours_across_edges(mesh);
    let ntris = mesh.tris.len();
    let mut flip: Vec<Option<bool>> = vec![None; ntris];
    let mut report = Vec::new();
    for first in 0..ntris {
        if flip[first].is_some() {
            continue;
        }
        let piece = walk_piece(first, &neighbours, &mut flip)?;
        let turned = piece.iter().filter(|&&t| flip[t] == Some(true)).count();
        if turned == 0 {
            continue;
        }
        let closed =
            piece.iter().all(|&t| !boundary[t]) && piece.iter().all(|&t| neighbours[t].len() == 3);
        let invert = if closed {
            volume(mesh, &piece, &flip) < 0.0
        } else {
            2 * turned > piece.len()
        };
        let mut flipped = 0;
        for &t in &piece {
            if flip[t] != Some(invert) {
                mesh.tris[t].swap(1, 2);
                flipped += 1;
            }
        }
        report.push(Repair::Reoriented {
            first_triangle: first,
            triangles: piece.len(),
            flipped,
            outward: closed,
        });
    }
    Ok(report)
}

/// Each triangle's neighbours across manifold edges, with whether the pair
/// traverses the shared edge the same way (then exactly one of them must
/// turn), and whether it has an edge of another count of triangles.
fn neighbours_across_edges(mesh: &MeshData) -> (Vec<Vec<(u32, bool)>>, Vec<bool>) {
    let incid = edge_incidences(mesh);
    let ntris = mesh.tris.len();
    let mut neighbours: Vec<Vec<(u32, bool)>> = vec![Vec::new(); ntris];
    let mut boundary = vec![false; ntris];
    let mut i = 0;
    while i < incid.len() {
        let j = i + incid[i..].iter().take_while(|x| x.0 == incid[i].0).count();
        let [a, b] = incid[i].0;
        match &incid[i..j] {
            [(_, t1), (_, t2)] => {
                let same =
                    runs(&mesh.tris[*t1 as usize], a, b) == runs(&mesh.tris[*t2 as usize], a, b);
                neighbours[*t1 as usize].push((*t2, same));
                neighbours[*t2 as usize].push((*t1, same));
            }
            others => others
                .iter()
                .for_each(|&(_, t)| boundary[t as usize] = true),
        }
        i = j;
    }
    (neighbours, boundary)
}

/// The piece of triangle `first`, breadth first, each triangle's `flip`
/// decided to agree with the neighbour it was reached from (`first` kept
/// as it is); a contradiction is a non-orientable piece.
fn walk_piece(
    first: usize,
    neighbours: &[Vec<(u32, bool)>],
    flip: &mut [Option<bool>],
) -> Result<Vec<usize>> {
    flip[first] = Some(false);
    let mut piece = vec![first];
    let mut k = 0;
    while k < piece.len() {
        let t = piece[k];
        k += 1;
        let ft = flip[t].unwrap_or(false);
        for &(u, same) in &neighbours[t] {
            let want = ft ^ same;
            match flip[u as usize] {
                None => {
                    flip[u as usize] = Some(want);
                    piece.push(u as usize);
                }
                Some(f) if f != want => {
                    return Err(Error::NonOrientable {
                        tri: u as usize,
                        first_triangle: first,
                    })
                }
                Some(_) => {}
            }
        }
    }
    Ok(piece)
}

/// Whether triangle `tri` runs from a to b (rather than b to a).
fn runs(tri: &[i64; 3], a: u32, b: u32) -> bool {
    let k = tri.iter().position(|&i| i == i64::from(a)).unwrap_or(0);
    tri[(k + 1) % 3] == i64::from(b)
}

/// Six times the volume the piece encloses with the orientation `flip`
/// gives it.
fn volume(mesh: &MeshData, piece: &[usize], flip: &[Option<bool>]) -> f64 {
    piece
        .iter()
        .map(|&t| {
            let [a, b, c] = mesh.tris[t].map(|i| mesh.points[i as usize]);
            let v = a.dot(b.cross(c));
            if flip[t] == Some(true) {
                -v
            } else {
                v
            }
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// The unit tetrahedron, outward, with triangles `turn`ed.
    fn tetra(turn: &[usize]) -> MeshData {
        let mut tris = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        for &t in turn {
            tris[t].swap(1, 2);
        }
        MeshData {
            points: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            tris,
            ..MeshData::default()
        }
    }

    #[test]
    fn closed_piece_ends_outward_whichever_triangles_were_turned() {
        let outward = tetra(&[]).tris;
        for turn in [vec![0], vec![1, 2, 3], vec![0, 1]] {
            let mut m = tetra(&turn);
            let report = orient(&mut m).unwrap();
            assert_eq!(m.tris, outward, "turned {turn:?}");
            assert_eq!(
                report,
                vec![Repair::Reoriented {
                    first_triangle: 0,
                    triangles: 4,
                    flipped: turn.len(),
                    outward: true
                }]
            );
        }
    }

    #[test]
    fn consistent_pieces_are_left_alone_even_inward() {
        let mut m = tetra(&[0, 1, 2, 3]);
        let before = m.tris.clone();
        assert!(orient(&mut m).unwrap().is_empty());
        assert_eq!(m.tris, before);
    }

    #[test]
    fn open_piece_keeps_the_majority() {
        // A fan of three triangles around vertex 0, the middle one turned.
        let mut m = MeshData {
            points: vec![DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y],
            tris: vec![[0, 1, 2], [0, 3, 2], [0, 3, 4]],
            ..MeshData::default()
        };
        let report = orient(&mut m).unwrap();
        assert_eq!(m.tris, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
        assert!(matches!(
            report[..],
            [Repair::Reoriented {
                flipped: 1,
                outward: false,
                ..
            }]
        ));
    }

    #[test]
    fn moebius_band_is_refused_naming_a_triangle() {
        // Five triangles (i, i+1, i+2) around a loop of five vertices: the
        // smallest Möbius band (its boundary edges {i, i+2} form one cycle).
        let tris: Vec<[i64; 3]> = (0..5).map(|i| [i, (i + 1) % 5, (i + 2) % 5]).collect();
        let points = (0..5)
            .map(|i| DVec3::new(i as f64, (i * i % 3) as f64, (i % 2) as f64))
            .collect();
        let mut m = MeshData {
            points,
            tris,
            ..MeshData::default()
        };
        let err = orient(&mut m).unwrap_err();
        assert!(
            matches!(
                err,
                Error::NonOrientable {
                    first_triangle: 0,
                    ..
                }
            ),
            "{err}"
        );
    }
}
