//! The first pass's pieces split where the later passes do not reach:
//! the band within [`super::SHARED_RINGS`] edges of an interface, which
//! every process receives and the later passes remesh, and the interior,
//! which only the process that made it keeps. So no process holds the
//! whole mesh and the joins after each stage are the band's alone; the
//! finished mesh is the band's triangles and the interiors', numbered the
//! same way whichever process puts them together.
//!
//! The rim, the vertices the band and an interior share, stays pinned
//! through the later passes: they treat it as the border of the mesh.

use super::cuts::mesh_rings;
use super::join::sub_mesh;
use super::work::Piece;
use crate::error::{Error, Result};
use crate::mesh::SurfaceMesh;
use crate::topology::NONE;

/// A first-pass piece's triangles beyond the band: its mesh, and per
/// vertex its index among the piece's rim vertices or [`NONE`].
pub(super) struct Interior {
    pub(super) mesh: SurfaceMesh,
    pub(super) rim: Vec<u32>,
}

impl Interior {
    /// How many of its vertices are off the rim.
    pub(super) fn inner(&self) -> usize {
        self.rim.iter().filter(|&&r| r == NONE).count()
    }
}

/// `piece` split into its band, the triangles with a vertex less than
/// `rings` edges from a pinned (interface) vertex, and its interior, the
/// rest; and the band's vertices on the rim they share, in the interior's
/// order. A vertex at distance d from the interfaces in the joined mesh
/// is at distance d in its own piece (a shortest path leaves the nearest
/// interface vertex without crossing another), so each piece splits
/// alone where the whole would.
pub(super) fn split(piece: Piece, rings: usize) -> (Piece, Vec<u32>, Interior) {
    let mesh = &piece.mesh;
    let interface: Vec<bool> = piece.pinned.iter().map(|&g| g != NONE).collect();
    let near = mesh_rings(&mesh.triangles, &interface, rings.saturating_sub(1));
    let in_band: Vec<bool> = mesh
        .triangles
        .iter()
        .map(|tri| tri.iter().any(|&v| near[v as usize]))
        .collect();
    let n = mesh.triangles.len();
    let (band, band_ids) = sub_mesh(mesh, (0..n).filter(|&t| in_band[t]));
    let (inside, inside_ids) = sub_mesh(mesh, (0..n).filter(|&t| !in_band[t]));
    let mut at_band = vec![NONE; mesh.points.len()];
    for (i, &v) in band_ids.iter().enumerate() {
        at_band[v as usize] = i as u32;
    }
    let mut rim_vertices = Vec::new();
    let rim = inside_ids
        .iter()
        .map(|&v| match at_band[v as usize] {
            NONE => NONE,
            b => {
                rim_vertices.push(b);
                rim_vertices.len() as u32 - 1
            }
        })
        .collect();
    let band = Piece {
        mesh: band,
        pinned: band_ids.iter().map(|&v| piece.pinned[v as usize]).collect(),
        sizes: band_ids.iter().map(|&v| piece.sizes[v as usize]).collect(),
        shrunk: piece.shrunk,
    };
    (band, rim_vertices, Interior { mesh: inside, rim })
}

/// Where the finished mesh's vertices go: the band's first, in its order,
/// then each part's interior's off its rim, part by part.
pub(super) struct Numbering {
    /// Per part: the id of its interior's first vertex off the rim.
    pub(super) inner_first: Vec<usize>,
    /// Per part: the id among all rims of its first rim vertex.
    pub(super) rim_first: Vec<u32>,
    /// Per rim id: its vertex in the band.
    pub(super) rim_at: Vec<u32>,
}

impl Numbering {
    /// The numbering of a band of `band_vertices` vertices, whose vertex
    /// v is rim vertex `band_rim[v]` (or [`NONE`]), and interiors with
    /// `inner[p]` vertices off the rim and `rims[p]` on it.
    pub(super) fn new(
        band_vertices: usize,
        band_rim: &[u32],
        inner: &[usize],
        rims: &[usize],
    ) -> Numbering {
        let mut inner_first = Vec::with_capacity(inner.len());
        let mut next = band_vertices;
        for &n in inner {
            inner_first.push(next);
            next += n;
        }
        let mut rim_first = Vec::with_capacity(rims.len());
        let mut total = 0u32;
        for &n in rims {
            rim_first.push(total);
            total += n as u32;
        }
        let mut rim_at = vec![NONE; total as usize];
        for (v, &r) in band_rim.iter().enumerate().filter(|x| *x.1 != NONE) {
            rim_at[r as usize] = v as u32;
        }
        Numbering {
            inner_first,
            rim_first,
            rim_at,
        }
    }
}

/// The band's triangles `band_tris` and the interiors `interiors` (part,
/// interior) as one mesh without curves, and each of its vertices' id in
/// the finished mesh (`numbering`). With every band triangle and every
/// part's interior, in part order, it is the finished mesh, its vertices
/// in the order of their ids.
pub(super) fn assemble(
    band: &SurfaceMesh,
    band_tris: impl Iterator<Item = usize>,
    interiors: &[(usize, &Interior)],
    numbering: &Numbering,
) -> Result<(SurfaceMesh, Vec<u32>)> {
    let band_tris: Vec<usize> = band_tris.collect();
    let mut used = vec![false; band.points.len()];
    for &t in &band_tris {
        for v in band.triangles[t] {
            used[v as usize] = true;
        }
    }
    for (p, interior) in interiors {
        for &r in interior.rim.iter().filter(|&&r| r != NONE) {
            let v = rim_vertex(numbering, *p, r)?;
            used[v as usize] = true;
        }
    }
    // The band's vertices first, in their order; then each interior's.
    let mut local = vec![NONE; band.points.len()];
    let mut ids: Vec<u32> = Vec::new();
    for v in (0..band.points.len()).filter(|&v| used[v]) {
        local[v] = ids.len() as u32;
        ids.push(v as u32);
    }
    let mut points: Vec<_> = ids.iter().map(|&v| band.points[v as usize]).collect();
    let mut params: Vec<_> = ids.iter().map(|&v| band.params[v as usize]).collect();
    let mut triangles: Vec<[u32; 3]> = band_tris
        .iter()
        .map(|&t| band.triangles[t].map(|v| local[v as usize]))
        .collect();
    let mut faces: Vec<u32> = band_tris.iter().map(|&t| band.faces[t]).collect();
    for (p, interior) in interiors {
        let mesh = &interior.mesh;
        let mut inner = 0;
        let index = interior
            .rim
            .iter()
            .enumerate()
            .map(|(i, &r)| {
                if r != NONE {
                    return Ok(local[rim_vertex(numbering, *p, r)? as usize]);
                }
                points.push(mesh.points[i]);
                params.push(mesh.params[i]);
                ids.push((numbering.inner_first[*p] + inner) as u32);
                inner += 1;
                Ok(ids.len() as u32 - 1)
            })
            .collect::<Result<Vec<u32>>>()?;
        triangles.extend(mesh.triangles.iter().map(|t| t.map(|v| index[v as usize])));
        faces.extend_from_slice(&mesh.faces);
    }
    let mesh = super::super::finish::without_curves(
        points,
        triangles,
        params,
        faces,
        band.deviation,
        band.diagonal,
    );
    Ok((mesh, ids))
}

/// The band's vertex that is part `p`'s rim vertex `r`.
fn rim_vertex(numbering: &Numbering, p: usize, r: u32) -> Result<u32> {
    let id = numbering.rim_first[p] as usize + r as usize;
    match numbering.rim_at.get(id) {
        Some(&v) if v != NONE => Ok(v),
        _ => Err(Error::InvalidArgument(format!(
            "part {p}'s rim vertex {r} is not in the band the later passes left"
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::finish::without_curves;
    use super::super::work::Piece;
    use super::{assemble, split, Numbering};
    use crate::parameters::SurfacePoint;
    use crate::topology::NONE;
    use glam::DVec3;

    /// A strip of `n` × `n` squares, each cut in two, whose left column
    /// is pinned (the interface): a vertex in column c is c edges from it.
    fn strip(n: u32) -> Piece {
        let at = |i: u32, j: u32| i * (n + 1) + j;
        let mut triangles = Vec::new();
        for i in 0..n {
            for j in 0..n {
                triangles.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
            }
        }
        let count = (n + 1) * (n + 1);
        let points: Vec<DVec3> = (0..count)
            .map(|v| DVec3::new((v % (n + 1)) as f64, (v / (n + 1)) as f64, 0.0))
            .collect();
        let params = (0..count)
            .map(|v| SurfacePoint {
                tri: v,
                v: 0.0,
                w: 0.0,
            })
            .collect();
        let faces = vec![0; triangles.len()];
        Piece {
            mesh: without_curves(points, triangles, params, faces, Some(0.5), 1.0),
            pinned: (0..count)
                .map(|v| if v % (n + 1) == 0 { v } else { NONE })
                .collect(),
            sizes: vec![1.0; count as usize],
            shrunk: vec![(3, 0.5)],
        }
    }

    /// The band is the triangles with a corner less than the rings from
    /// the pinned column (by column, not by the rings the split grows),
    /// the rim the column between; put together again, band and interior
    /// are the piece, each triangle once at its own points.
    #[test]
    fn a_piece_splits_at_its_rings_and_assembles_whole() {
        let (n, rings) = (8u32, 3usize);
        let piece = strip(n);
        let column = |p: DVec3| p.x as usize;
        let corners = |m: &crate::mesh::SurfaceMesh, t: [u32; 3]| {
            let mut c = t.map(|v| m.points[v as usize].to_array().map(|x| x as i64));
            c.sort();
            c
        };
        let mut expected_band: Vec<_> = (piece.mesh.triangles.iter())
            .filter(|t| {
                t.iter()
                    .any(|&v| column(piece.mesh.points[v as usize]) < rings)
            })
            .map(|&t| corners(&piece.mesh, t))
            .collect();
        let mut everything: Vec<_> = (piece.mesh.triangles.iter())
            .map(|&t| corners(&piece.mesh, t))
            .collect();
        let (band, rim, interior) = split(strip(n), rings);

        let mut got_band: Vec<_> = (band.mesh.triangles.iter())
            .map(|&t| corners(&band.mesh, t))
            .collect();
        expected_band.sort();
        got_band.sort();
        assert_eq!(got_band, expected_band);
        assert_eq!(band.shrunk, vec![(3, 0.5)]);
        assert_eq!(rim.len(), (n + 1) as usize);
        for &v in &rim {
            assert_eq!(column(band.mesh.points[v as usize]), rings);
        }
        assert_eq!(
            interior.inner(),
            ((n + 1) * (n + 1 - rings as u32 - 1)) as usize
        );
        for (v, &p) in band.pinned.iter().enumerate() {
            let on_interface = column(band.mesh.points[v]) == 0;
            assert_eq!(p != NONE, on_interface, "vertex {v}");
        }

        // The band as the last pass would leave it: rim id r at rim[r].
        let mut band_rim = vec![NONE; band.mesh.points.len()];
        for (r, &v) in rim.iter().enumerate() {
            band_rim[v as usize] = r as u32;
        }
        let numbering = Numbering::new(
            band.mesh.points.len(),
            &band_rim,
            &[interior.inner()],
            &[rim.len()],
        );
        let all = 0..band.mesh.triangles.len();
        let (whole, ids) = assemble(&band.mesh, all, &[(0, &interior)], &numbering).unwrap();
        assert_eq!(ids, (0..whole.points.len() as u32).collect::<Vec<_>>());
        assert_eq!(whole.points.len(), ((n + 1) * (n + 1)) as usize);
        assert_eq!(whole.deviation, Some(0.5));
        let mut got: Vec<_> = whole
            .triangles
            .iter()
            .map(|&t| corners(&whole, t))
            .collect();
        got.sort();
        everything.sort();
        assert_eq!(got, everything);
        // Oriented as before: every triangle's normal still points up.
        for t in &whole.triangles {
            let [a, b, c] = t.map(|v| whole.points[v as usize]);
            assert!((b - a).cross(c - a).z > 0.0);
        }
        // The interior alone, as a rank would hold it: its rim from the band.
        let (own, own_ids) = assemble(
            &band.mesh,
            std::iter::empty(),
            &[(0, &interior)],
            &numbering,
        )
        .unwrap();
        assert_eq!(own.triangles.len(), interior.mesh.triangles.len());
        for (i, &g) in own_ids.iter().enumerate() {
            assert_eq!(own.points[i], whole.points[g as usize]);
        }
    }
}
