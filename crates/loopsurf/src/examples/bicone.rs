//! A wavy bicone: two apexes of any valence, for high-valence and boundary
//! tests.

use super::Example;
use glam::DVec3;
use std::f64::consts::TAU;

/// Two apexes of valence `n` joined by two wavy rings of `n` vertices;
/// closed. With `open`, the bottom apex is left out and the lower ring is a
/// boundary loop. Vertex 0 is the top apex, 1..=n the upper ring, n+1..=2n
/// the lower ring and 2n+1 the bottom apex.
pub fn bicone(n: usize, open: bool) -> Example {
    let mut points = vec![DVec3::new(0.1, -0.05, 1.3)];
    for ring in 0..2 {
        for i in 0..n {
            let a = TAU * (i as f64 + 0.5 * ring as f64) / n as f64;
            let r = 1.0 + 0.15 * (3.0 * a).sin() + 0.05 * ring as f64;
            let z = 0.4 - 0.8 * ring as f64 + 0.1 * (2.0 * a).cos();
            points.push(DVec3::new(r * a.cos(), r * a.sin(), z));
        }
    }
    let top_ring = |i: usize| 1 + (i % n) as u32;
    let low_ring = |i: usize| 1 + n as u32 + (i % n) as u32;
    let mut tris = Vec::new();
    for i in 0..n {
        tris.push([0, top_ring(i), top_ring(i + 1)]);
        tris.push([top_ring(i), low_ring(i), top_ring(i + 1)]);
        tris.push([top_ring(i + 1), low_ring(i), low_ring(i + 1)]);
    }
    if !open {
        let bottom = points.len() as u32;
        points.push(DVec3::new(-0.05, 0.1, -1.2));
        for i in 0..n {
            tris.push([bottom, low_ring(i + 1), low_ring(i)]);
        }
    }
    Example {
        name: "bicone",
        points,
        tris,
    }
}
