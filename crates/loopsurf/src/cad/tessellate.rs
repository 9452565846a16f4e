//! What a CAD exporter does to a face: cut curves by chord and angle
//! deflection, sweep the cuts around an axis, close disks with fans or
//! strips, and check the result against the tolerance.

use crate::examples::Example;
use glam::{DVec2, DVec3};
use std::collections::HashMap;
use std::f64::consts::TAU;

/// How many equal angular steps keep a circle of radius `rho` within
/// `sagitta` of its chords and every step below `angle` (radians). At
/// least 3, so that a circle is a polygon.
pub fn angular_steps(rho: f64, sagitta: f64, angle: f64) -> usize {
    let by_chord = 2.0 * (1.0 - sagitta / rho).clamp(-1.0, 1.0).acos();
    (TAU / angle).max(TAU / by_chord).ceil().max(3.0) as usize
}

/// The vertices a profile point becomes: one on the axis, or a ring.
#[derive(Debug, Clone, PartialEq)]
pub enum Ring {
    Pole(u32),
    Ring(Vec<u32>),
}

/// Sweeps profile points (ρ, z) around the z axis, point k in `steps[k]`
/// equal angles (0 on the axis): a ring of vertices per point off the
/// axis, one vertex per point on it. Consecutive rings of the same count
/// are joined by quads cut along the same diagonal (the long slivers of a
/// cylinder), rings of different counts are stitched in order of angle,
/// and a ring next to a pole becomes a fan. The profile's outward side
/// must be on its right, so that the triangles are counter-clockwise seen
/// from outside.
pub fn revolve(
    profile: &[DVec2],
    closed: bool,
    steps: &[usize],
) -> (Vec<DVec3>, Vec<[u32; 3]>, Vec<Ring>) {
    let mut points = Vec::new();
    let rings: Vec<Ring> = profile
        .iter()
        .zip(steps)
        .map(|(q, &n)| {
            let first = points.len() as u32;
            if q.x == 0.0 {
                points.push(DVec3::new(0.0, 0.0, q.y));
                return Ring::Pole(first);
            }
            points.extend((0..n).map(|j| {
                let phi = TAU * j as f64 / n as f64;
                DVec3::new(q.x * phi.cos(), q.x * phi.sin(), q.y)
            }));
            Ring::Ring((first..first + n as u32).collect())
        })
        .collect();
    let mut tris = Vec::new();
    let bands = if closed { rings.len() } else { rings.len() - 1 };
    for i in 0..bands {
        band(&rings[i], &rings[(i + 1) % rings.len()], &mut tris);
    }
    (points, tris, rings)
}

/// The triangles between two consecutive rings, `a` then `b` along the
/// profile; (φ, then along the profile) is counter-clockwise outside.
fn band(a: &Ring, b: &Ring, tris: &mut Vec<[u32; 3]>) {
    match (a, b) {
        (Ring::Ring(a), Ring::Ring(b)) if a.len() == b.len() => {
            let n = a.len();
            for j in 0..n {
                let k = (j + 1) % n;
                tris.push([a[j], a[k], b[k]]);
                tris.push([a[j], b[k], b[j]]);
            }
        }
        (Ring::Ring(a), Ring::Ring(b)) => {
            // Both rings start at φ = 0; advance the one whose next vertex
            // comes first.
            let (na, nb) = (a.len(), b.len());
            let (mut i, mut j) = (0, 0);
            while i < na || j < nb {
                let next_a = (i + 1) as f64 / na as f64;
                let next_b = (j + 1) as f64 / nb as f64;
                if j == nb || (i < na && next_a <= next_b) {
                    tris.push([a[i], a[(i + 1) % na], b[j % nb]]);
                    i += 1;
                } else {
                    tris.push([a[i % na], b[(j + 1) % nb], b[j]]);
                    j += 1;
                }
            }
        }
        (Ring::Pole(p), Ring::Ring(b)) => {
            let n = b.len();
            tris.extend((0..n).map(|j| [*p, b[(j + 1) % n], b[j]]));
        }
        (Ring::Ring(a), Ring::Pole(p)) => {
            let n = a.len();
            tris.extend((0..n).map(|j| [a[j], a[(j + 1) % n], *p]));
        }
        (Ring::Pole(_), Ring::Pole(_)) => {}
    }
}

/// A convex polygon (vertices counter-clockwise as seen from the side the
/// triangles should face) cut into a zigzag strip from its own vertices:
/// the fan-free way CAD exporters close a planar disk, all slivers.
pub fn zigzag(ring: &[u32]) -> Vec<[u32; 3]> {
    let n = ring.len();
    let mut tris = vec![[ring[0], ring[1], ring[n - 1]]];
    let (mut l, mut r) = (1, n - 1);
    let mut left = true;
    while r - l > 1 {
        if left {
            tris.push([ring[l], ring[l + 1], ring[r]]);
            l += 1;
        } else {
            tris.push([ring[l], ring[r - 1], ring[r]]);
            r -= 1;
        }
        left = !left;
    }
    tris
}

/// The largest distance from an edge midpoint or a centroid to the true
/// surface: the chord deflection the tessellation achieves (a facet of a
/// doubly curved patch strays farthest near its centroid, not on its
/// edges).
pub fn max_deflection(ex: &Example, distance: impl Fn(DVec3) -> f64) -> f64 {
    let mut worst: f64 = 0.0;
    for t in &ex.tris {
        let [a, b, c] = t.map(|i| ex.points[i as usize]);
        for p in [
            0.5 * (a + b),
            0.5 * (b + c),
            0.5 * (c + a),
            (a + b + c) / 3.0,
        ] {
            worst = worst.max(distance(p));
        }
    }
    worst
}

/// Builds with the curve deflection `chord` first and tightens it until
/// every facet's edge midpoints and centroid, diagonals included, are
/// within `chord` of the true surface: cutting each curve to the tolerance does not bound the
/// diagonals across two curved directions, and an exporter's promise is
/// about the facets.
pub fn within_chord(
    chord: f64,
    build: impl Fn(f64) -> Example,
    distance: impl Fn(DVec3) -> f64,
) -> Example {
    let mut target = chord;
    for _ in 0..60 {
        let ex = build(target);
        if max_deflection(&ex, &distance) <= chord {
            return ex;
        }
        target *= 0.8;
    }
    panic!("no tessellation within chord {chord}");
}

/// Merges vertices that several patches compute, each in its own way, at
/// the same place (the patches of a B-rep share their edges' points, but
/// not their round-off).
pub struct Welder {
    quantum: f64,
    index: HashMap<[i64; 3], u32>,
    pub points: Vec<DVec3>,
}

impl Welder {
    /// Points closer than about `quantum` become one.
    pub fn new(quantum: f64) -> Welder {
        Welder {
            quantum,
            index: HashMap::new(),
            points: Vec::new(),
        }
    }

    /// The index of `p`, new or merged with an earlier one.
    pub fn vertex(&mut self, p: DVec3) -> u32 {
        let key = (p / self.quantum).round().to_array().map(|c| c as i64);
        let points = &mut self.points;
        *self.index.entry(key).or_insert_with(|| {
            points.push(p);
            (points.len() - 1) as u32
        })
    }
}
