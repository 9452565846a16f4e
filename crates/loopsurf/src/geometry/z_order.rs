//! Points ordered along a Z-order (Morton) curve, so that neighbours in
//! the order are mostly neighbours in space: the remesher renumbers its
//! vertices this way to keep its walks in cache, and the surface's
//! evaluation by chunks cuts the control triangles into compact chunks.

use glam::DVec3;
use rayon::prelude::*;

/// Cells per axis of the Z-order grid (21 bits, so that three interleaved
/// fit in 64).
const Z_CELLS: f64 = (1u32 << 21) as f64;

/// The indices of `points` in Z-order over the grid of [`Z_CELLS`] cells
/// per axis spanning their bounding box; points in one cell by index.
pub fn z_order(points: &[DVec3]) -> Vec<u32> {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &x| (lo.min(x), hi.max(x)),
    );
    let scale = (Z_CELLS - 1.0) / (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let mut keyed: Vec<(u64, u32)> = (points.par_iter().enumerate())
        .map(|(i, &x)| {
            let q = ((x - lo) * scale).as_uvec3();
            (spread(q.x) | spread(q.y) << 1 | spread(q.z) << 2, i as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// The bits of x (below 2²¹) spread to every third bit.
fn spread(x: u32) -> u64 {
    let mut x = x as u64 & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

#[cfg(test)]
mod tests {
    use super::z_order;
    use glam::DVec3;

    /// The eight corners of a cube come in Morton order (x the lowest
    /// bit), whatever order they are given in; equal points by index.
    #[test]
    fn corners_of_a_cube_come_in_morton_order() {
        let corner = |k: u32| DVec3::new((k & 1) as f64, (k >> 1 & 1) as f64, (k >> 2 & 1) as f64);
        let given = [5, 3, 0, 7, 6, 1, 4, 2];
        let points: Vec<DVec3> = given.iter().map(|&k| corner(k)).collect();
        let order: Vec<u32> = z_order(&points)
            .iter()
            .map(|&i| given[i as usize])
            .collect();
        assert_eq!(order, (0..8).collect::<Vec<u32>>());
        assert_eq!(z_order(&[DVec3::ONE; 3]), vec![0, 1, 2]);
        assert!(z_order(&[]).is_empty());
    }
}
