//! Evaluation at many points of a large surface, chunk by chunk: the
//! control triangles cut into compact chunks (runs of a Z-order through
//! their centroids), each chunk evaluated on the surface of its own
//! sub-net ([`Surface::part_of`]), which is dropped when the
//! chunk is done. A triangle a chunk owns evaluates there bit for bit as
//! in the whole, so the answers are the whole's; but the whole surface's
//! patches, which it keeps once made, are never made. Evaluated on the
//! whole surface, the curvature at the 2.5 million vertices of a mesh of
//! bunny00 refined twice made every patch and kept them: `loopsurf mesh`
//! peaked at 4.6 GB writing the `.vtu`, against 2.2 GB chunk by chunk
//! (the same file, byte for byte), and the writing took 16.8 s against
//! 12.4 s.

use crate::error::Result;
use crate::geometry::z_order;
use crate::parameters::SurfacePoint;
use crate::partition::Part;
use crate::surface::Surface;
use glam::DVec3;
use rayon::prelude::*;

/// Control triangles per chunk: a chunk's surface, every patch made, holds
/// about 25 MB, and one is alive per thread.
const CHUNK_TRIANGLES: usize = 1 << 14;

/// Nets of up to this many control triangles are evaluated whole, their
/// patches kept: chunk by chunk costs about 1.25 times the time (bench
/// `eval`, two threads, curvature at the vertices of a chart mesh of 4
/// triangles per control triangle: bunny00 222 → 283 ms, keeping 234 MB
/// of patches whole; refined once, 301 632 control triangles, 632 → 789
/// ms, keeping 557 MB whole and 17 MB in chunks), which buys memory only
/// on a larger net. (Chunks of 2¹² to 2¹⁴ triangles took the same time,
/// 2¹⁶ 8% longer.)
const CHUNKED_ABOVE: usize = 1 << 18;

/// The chunk size [`map_by_chunks`] takes for a net of `n` control
/// triangles: the whole net up to [`CHUNKED_ABOVE`].
pub(crate) fn chunk_size(n: usize) -> usize {
    if n > CHUNKED_ABOVE {
        CHUNK_TRIANGLES
    } else {
        n
    }
}

/// `f(surface, tri, v, w)` at each of `at` on `surface`, in order: on a
/// net of at most `chunk` triangles on `surface` itself, on a larger one
/// chunk by chunk of `chunk` triangles (see the module doc), each point on
/// its chunk's surface at its local triangle.
pub(crate) fn map_by_chunks<T, F>(
    surface: &Surface,
    at: &[SurfacePoint],
    chunk: usize,
    f: F,
) -> Result<Vec<T>>
where
    T: Send,
    F: Fn(&Surface, usize, f64, f64) -> Result<T> + Sync,
{
    let net = surface.net();
    let n = net.triangles().len();
    let chunk = chunk.max(1);
    // Checked on the whole first, so that an error names the point's own
    // triangle, not its chunk's local one.
    (at.par_iter()).try_for_each(|p| surface.validate(p.tri as usize, p.v, p.w))?;
    if n <= chunk || at.is_empty() {
        return (at.par_iter())
            .map(|p| f(surface, p.tri as usize, p.v, p.w))
            .collect();
    }
    let points = net.points();
    let centroids: Vec<DVec3> = (net.triangles().par_iter())
        .map(|t| (points[t[0] as usize] + points[t[1] as usize] + points[t[2] as usize]) / 3.0)
        .collect();
    let order = z_order(&centroids);
    drop(centroids);
    let mut chunk_of = vec![0u32; n];
    for (i, &t) in order.iter().enumerate() {
        chunk_of[t as usize] = (i / chunk) as u32;
    }
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); n.div_ceil(chunk)];
    for (i, p) in at.iter().enumerate() {
        members[chunk_of[p.tri as usize] as usize].push(i as u32);
    }
    drop(chunk_of);
    let done: Vec<Vec<(u32, T)>> = (members.par_iter().enumerate())
        .filter(|(_, m)| !m.is_empty())
        .map(|(c, m)| {
            let owned = &order[c * chunk..((c + 1) * chunk).min(n)];
            let part = Part::new(net, owned)?;
            let local = Surface::part_of(surface, &part)?;
            m.iter()
                .map(|&i| {
                    let p = at[i as usize];
                    let t = (part.local_triangle(p.tri))
                        .expect("the chunk owns the triangles of its points");
                    Ok((i, f(&local, t, p.v, p.w)?))
                })
                .collect()
        })
        .collect::<Result<_>>()?;
    let mut out: Vec<Option<T>> = (0..at.len()).map(|_| None).collect();
    for (i, x) in done.into_iter().flatten() {
        out[i as usize] = Some(x);
    }
    Ok(out
        .into_iter()
        .map(|x| x.expect("every point is in one chunk"))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::{chunk_size, map_by_chunks, CHUNKED_ABOVE, CHUNK_TRIANGLES};
    use crate::parameters::SurfacePoint;
    use crate::surface::{Surface, SurfaceMode};
    use crate::ControlNet;

    /// Nets up to the threshold in one chunk, larger ones in chunks.
    #[test]
    fn small_nets_are_evaluated_whole() {
        assert_eq!(chunk_size(1000), 1000);
        assert_eq!(chunk_size(CHUNKED_ABOVE), CHUNKED_ABOVE);
        assert_eq!(chunk_size(CHUNKED_ABOVE + 1), CHUNK_TRIANGLES);
    }

    /// On the Viking (creased at 30°, a corner tagged) in chunks of 40
    /// triangles, in every mode: the curvature, point and derivatives at
    /// points inside triangles, on their edges and at their corners are
    /// the whole surface's, bit for bit; a point out of its triangle, or
    /// on a triangle out of range, is refused naming its own triangle
    /// (the last one: no chunk's local id is the same).
    #[test]
    fn chunks_evaluate_as_the_whole() {
        let ex = crate::examples::viking();
        let mut net = ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
        net.tag_by_angle(30.0).unwrap();
        net.tag_vertex(5).unwrap();
        let n = net.triangles().len();
        assert!(n > 10 * 40, "{n} triangles: too few chunks");
        let mut at = Vec::new();
        for t in 0..n as u32 {
            // A low-discrepancy spread of points over each triangle.
            let (v, w) = ((t as f64 * 0.618034).fract(), (t as f64 * 0.754878).fract());
            let (v, w) = if v + w > 1.0 {
                (1.0 - v, 1.0 - w)
            } else {
                (v, w)
            };
            for (v, w) in [(v, w), (v, 0.0), (0.0, w), (0.0, 0.0), (1.0, 0.0)] {
                at.push(SurfacePoint { tri: t, v, w });
            }
        }
        for mode in [
            SurfaceMode::Approximating,
            SurfaceMode::Displacement,
            SurfaceMode::Solve,
        ] {
            let surface = Surface::with_mode(&net, mode).unwrap();
            let bits = |s: &Surface, t: usize, v: f64, w: f64| {
                let e = s.eval(t, v, w)?;
                let k = s.curvature(t, v, w)?;
                Ok([e.x, e.xv, e.xw, e.xvv, e.xvw, e.xww]
                    .iter()
                    .flat_map(|d| d.to_array())
                    .chain([k.mean, k.gaussian, k.k1, k.k2])
                    .map(f64::to_bits)
                    .collect::<Vec<u64>>())
            };
            let chunked = map_by_chunks(&surface, &at, 40, bits).unwrap();
            for (p, got) in at.iter().zip(&chunked) {
                let whole = bits(&surface, p.tri as usize, p.v, p.w).unwrap();
                assert_eq!(*got, whole, "{mode:?} at {p:?}");
            }
        }
        let surface = Surface::new(&net).unwrap();
        for (tri, v) in [(n as u32, 0.2), (n as u32 - 1, 0.9)] {
            let mut points = at[..10].to_vec();
            points.push(SurfacePoint { tri, v, w: 0.2 });
            let err = map_by_chunks(&surface, &points, 40, |s, t, v, w| s.point(t, v, w))
                .unwrap_err()
                .to_string();
            assert!(err.contains(&format!("triangle {tri}")), "{err}");
        }
    }
}
