//! Max–min angle edge swaps (Persson, Aftosmis & Haines §4) inside one control triangle.
//!
//! Only edges with a triangle on both sides inside the same control
//! triangle are swapped, so control edges (hard or not) stay fixed and every
//! output triangle keeps one chart. A swap must improve the smaller of the
//! two triangles' minimum angles in 3D, keep both triangles positively
//! oriented in (v, w) and pass the caller's check (the chord tolerance).
//! Each swap raises the sorted vector of all angles lexicographically, so
//! the loop terminates; a cap guards against round-off.

use super::{area_normal, max_cosine, NONE};
use glam::{DVec2, DVec3};

/// Minimum swaps an angle must gain (as a cosine) to count, against
/// round-off ping-pong.
const GAIN: f64 = 1e-9;

/// Swaps edges of `tris` until no swap improves the minimum angle.
/// `accept(t1, t2)` may veto a candidate pair of new triangles.
pub(crate) fn swap_edges(
    tris: &mut [[u32; 3]],
    params: &[DVec2],
    pos: &[DVec3],
    mut accept: impl FnMut([u32; 3], [u32; 3]) -> bool,
) {
    let mut opp = twins(tris);
    let mut stack: Vec<u32> = (0..opp.len() as u32)
        .filter(|&h| opp[h as usize] > h && opp[h as usize] != NONE)
        .collect();
    let mut budget = 8 * tris.len() + 64;
    while let Some(h) = stack.pop() {
        let g = opp[h as usize];
        if g == NONE || budget == 0 {
            continue;
        }
        let (t1, k1) = ((h / 3) as usize, (h % 3) as usize);
        let (t2, k2) = ((g / 3) as usize, (g % 3) as usize);
        let [a, b, c] = [0, 1, 2].map(|i| tris[t1][(k1 + i) % 3]);
        let d = tris[t2][(k2 + 2) % 3];
        let (n1, n2) = ([c, a, d], [d, b, c]);
        let p = |i: u32| pos[i as usize];
        let q = |i: u32| params[i as usize];
        let oriented = |t: [u32; 3]| (q(t[1]) - q(t[0])).perp_dot(q(t[2]) - q(t[0])) > 0.0;
        if !oriented(n1) || !oriented(n2) {
            continue;
        }
        let worst = |t: [u32; 3]| max_cosine(p(t[0]), p(t[1]), p(t[2]));
        let before = worst([a, b, c]).max(worst([b, a, d]));
        let after = worst(n1).max(worst(n2));
        let normal = |t: [u32; 3]| area_normal(t.map(p));
        if after >= before - GAIN || normal(n1).dot(normal(n2)) <= 0.0 || !accept(n1, n2) {
            continue;
        }
        budget -= 1;
        // Half-edges of the new triangles: c→a, a→d, d→c and d→b, b→c, c→d.
        let outer = [
            opp[3 * t1 + (k1 + 2) % 3],
            opp[3 * t2 + (k2 + 1) % 3],
            opp[3 * t2 + (k2 + 2) % 3],
            opp[3 * t1 + (k1 + 1) % 3],
        ];
        tris[t1] = n1;
        tris[t2] = n2;
        let slots = [3 * t1, 3 * t1 + 1, 3 * t2, 3 * t2 + 1];
        for (slot, o) in slots.into_iter().zip(outer) {
            opp[slot] = o;
            if o != NONE {
                opp[o as usize] = slot as u32;
                stack.push(slot as u32);
            }
        }
        opp[3 * t1 + 2] = (3 * t2 + 2) as u32;
        opp[3 * t2 + 2] = (3 * t1 + 2) as u32;
    }
}

/// The opposite half-edge of each half-edge 3t + k (from corner k to k + 1),
/// or [`NONE`] on the pattern's boundary.
fn twins(tris: &[[u32; 3]]) -> Vec<u32> {
    let mut keyed: Vec<(u64, u32)> = Vec::with_capacity(3 * tris.len());
    for (t, tri) in tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k] as u64, tri[(k + 1) % 3] as u64);
            keyed.push(((a.min(b) << 32) | a.max(b), (3 * t + k) as u32));
        }
    }
    keyed.sort_unstable();
    let mut opp = vec![NONE; keyed.len()];
    for pair in keyed.windows(2) {
        if pair[0].0 == pair[1].0 {
            opp[pair[0].1 as usize] = pair[1].1;
            opp[pair[1].1 as usize] = pair[0].1;
        }
    }
    opp
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A thin-diagonal quad is swapped to the better diagonal; a good one is
    /// left alone, and a veto is honoured.
    #[test]
    fn swaps_to_the_better_diagonal() {
        let params =
            [(0.0, 0.0), (4.0, 0.0), (4.2, 1.0), (0.2, 1.0)].map(|(x, y)| DVec2::new(x, y));
        let pos: Vec<DVec3> = params.iter().map(|p| p.extend(0.0)).collect();
        // Diagonal 0-2 is the long one: swap to 1-3.
        let mut tris = [[0, 1, 2], [0, 2, 3]];
        swap_edges(&mut tris, &params, &pos, |_, _| true);
        let mut sorted: Vec<[u32; 2]> = tris
            .iter()
            .flat_map(|t| (0..3).map(move |k| [t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])]))
            .collect();
        sorted.sort();
        assert!(
            sorted.contains(&[1, 3]) && !sorted.contains(&[0, 2]),
            "{tris:?}"
        );
        let again = tris;
        swap_edges(&mut tris, &params, &pos, |_, _| true);
        assert_eq!(tris, again);
        let mut vetoed = [[0, 1, 2], [0, 2, 3]];
        swap_edges(&mut vetoed, &params, &pos, |_, _| false);
        assert_eq!(vetoed, [[0, 1, 2], [0, 2, 3]]);
    }
}
