//! Viking-type Mars entry aeroshell, the legacy-geometry example of Persson, Aftosmis & Haines
//! §4: a surface of revolution whose control net has exactly two circles of
//! edges that a 30° dihedral-angle criterion marks hard.

use super::Example;
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// Maximum diameter, metres (Viking: 3.505 m).
const D: f64 = 3.5;
/// Nose radius, tangent to the forebody cone.
const NOSE_RADIUS: f64 = D / 4.0;
/// Forebody cone half-angle, degrees; the meridian makes 90° − 70° = 20°
/// with the plane normal to the axis.
const FORE_HALF_ANGLE: f64 = 70.0;
/// Shoulder torus radius (≈ D/23), tangent to forebody and first back cone.
const SHOULDER_RADIUS: f64 = 0.15;
/// Half-angle of the first back-shell cone, which starts at the shoulder.
const BACK1_HALF_ANGLE: f64 = 60.0;
/// Half-angle of the second back-shell cone.
const BACK2_HALF_ANGLE: f64 = 15.0;
/// Radius of the circle where the two back-shell cones meet.
const JUNCTION_RADIUS: f64 = 1.0;
/// Radius of the flat back face.
const BACK_FACE_RADIUS: f64 = 0.8;
/// Azimuthal segments.
const N: usize = 40;

/// Profile steps per piece. Each step on an arc turns the meridian by at most
/// 15°, which bounds the dihedral angle there (see [`viking`]).
const NOSE_STEPS: usize = 2;
const FORE_STEPS: usize = 4;
const SHOULDER_FRONT_STEPS: usize = 5;
const SHOULDER_BACK_STEPS: usize = 4;
const BACK1_STEPS: usize = 2;
const BACK2_STEPS: usize = 2;
const BACK_FACE_STEPS: usize = 3;

/// Viking-type aeroshell control net, 1680 triangles, axis = z, units metres.
///
/// Meridian profile, from the nose tip at the origin (flow from −z) back to
/// the flat back face at z ≈ 1.95:
/// - spherical nose, radius D/4 = 0.875, tangent to
/// - a 70° half-angle cone (the heat shield, 20° off the base plane), up to
/// - a shoulder torus of radius 0.15 m whose outermost circle is the
///   maximum diameter D = 3.5 m (at z ≈ 0.686), tangent to
/// - a 60° half-angle back-shell cone, down to radius 1.0 at z ≈ 1.21, then
/// - a 15° half-angle cone (a 45° concave bend), down to radius 0.8 at
///   z ≈ 1.95, closed by
/// - a flat circular back face (a 75° convex bend).
///
/// The back shell is a wide shallow cone followed by a short steep one, so
/// the bend between them is concave. The profile is revolved with N = 40
/// segments (rather than 48) so that 21 rings, enough for a finely stepped
/// shoulder, still give about 1700 triangles. The nose tip and the centre of
/// the back face are single pole vertices with triangle fans. Each quad
/// between rings is split along the same diagonal (i, j)–(i+1, j+1): the
/// four corners of such a quad are coplanar (an isosceles trapezoid), so the
/// diagonal never bends, and consistent diagonals give every ring vertex
/// valence 6 (5 on the rings next to a pole) where alternating them would
/// scatter valence-4 and valence-8 vertices over the whole surface.
///
/// Dihedral angles therefore come from two sources only. Across ring edges
/// they equal the profile's turning angle to within 0.1°: 10° at the nose,
/// at most 15° on the shoulder, 45° and 75° at the two bends. Across
/// meridional edges they are at most the azimuthal step 360°/N = 9°. So
/// exactly the two bend circles exceed 30°.
pub fn viking() -> Example {
    let rings = profile();
    let mut points = Vec::with_capacity(rings.len() * N + 2);
    points.push(DVec3::ZERO);
    for p in &rings {
        for j in 0..N {
            let t = TAU * j as f64 / N as f64;
            points.push(DVec3::new(p.x * t.cos(), p.x * t.sin(), p.y));
        }
    }
    let back = points.len() as u32;
    points.push(DVec3::new(0.0, 0.0, rings[rings.len() - 1].y));

    let v = |i: usize, j: usize| (1 + i * N + j % N) as u32;
    let mut tris = Vec::with_capacity(2 * N * rings.len());
    // Outward normal = azimuth direction × profile direction, so (j, j+1,
    // then the next ring) is counter-clockwise seen from outside.
    for j in 0..N {
        tris.push([0, v(0, j + 1), v(0, j)]);
    }
    for i in 0..rings.len() - 1 {
        for j in 0..N {
            tris.push([v(i, j), v(i, j + 1), v(i + 1, j + 1)]);
            tris.push([v(i, j), v(i + 1, j + 1), v(i + 1, j)]);
        }
    }
    let last = rings.len() - 1;
    for j in 0..N {
        tris.push([v(last, j), v(last, j + 1), back]);
    }
    Example {
        name: "viking",
        points,
        tris,
    }
}

/// Meridian point at tangent angle `deg` on a convex arc: the tangent is
/// (cos, sin) of `deg`, measured from the +r direction toward +z.
fn on_arc(centre: DVec2, radius: f64, deg: f64) -> DVec2 {
    let (s, c) = deg.to_radians().sin_cos();
    centre + radius * DVec2::new(s, -c)
}

/// Points after `from` up to and including `to`, `steps` of them.
fn arc(centre: DVec2, radius: f64, from: f64, to: f64, steps: usize) -> Vec<DVec2> {
    let deg = |k: usize| from + (to - from) * k as f64 / steps as f64;
    (1..=steps)
        .map(|k| on_arc(centre, radius, deg(k)))
        .collect()
}

/// Points after `a` up to and including `b`, `steps` of them.
fn line(a: DVec2, b: DVec2, steps: usize) -> Vec<DVec2> {
    (1..=steps)
        .map(|k| a.lerp(b, k as f64 / steps as f64))
        .collect()
}

/// The key points of the meridian (r, z), in profile order.
struct Keys {
    nose_centre: DVec2,
    shoulder_centre: DVec2,
    /// Nose / forebody cone tangent point.
    fore_start: DVec2,
    /// Forebody cone / shoulder tangent point.
    fore_end: DVec2,
    /// Shoulder / first back cone tangent point.
    back1_start: DVec2,
    junction: DVec2,
    back_corner: DVec2,
}

fn keys() -> Keys {
    let fore = 90.0 - FORE_HALF_ANGLE;
    let nose_centre = DVec2::new(0.0, NOSE_RADIUS);
    let fore_start = on_arc(nose_centre, NOSE_RADIUS, fore);
    // The shoulder centre lies at r = D/2 − Rs and at distance Rs inside the
    // cone line through `fore_start` (unit normal n = (sin, −cos) of `fore`).
    let n = DVec2::new(fore.to_radians().sin(), -fore.to_radians().cos());
    let r = D / 2.0 - SHOULDER_RADIUS;
    let z = (r * n.x - n.dot(fore_start) + SHOULDER_RADIUS) / -n.y;
    let shoulder_centre = DVec2::new(r, z);
    let fore_end = on_arc(shoulder_centre, SHOULDER_RADIUS, fore);
    let back1_start = on_arc(shoulder_centre, SHOULDER_RADIUS, 90.0 + BACK1_HALF_ANGLE);
    // A cone of half-angle a, followed toward the back, runs along
    // (−sin a, cos a); walk each until it reaches its end radius.
    let walk = |p: DVec2, half_angle: f64, to_r: f64| {
        let (s, c) = half_angle.to_radians().sin_cos();
        p + (p.x - to_r) / s * DVec2::new(-s, c)
    };
    let junction = walk(back1_start, BACK1_HALF_ANGLE, JUNCTION_RADIUS);
    let back_corner = walk(junction, BACK2_HALF_ANGLE, BACK_FACE_RADIUS);
    Keys {
        nose_centre,
        shoulder_centre,
        fore_start,
        fore_end,
        back1_start,
        junction,
        back_corner,
    }
}

/// Ring points (r, z) from the nose to the back face, without the two poles.
fn profile() -> Vec<DVec2> {
    let k = keys();
    let fore = 90.0 - FORE_HALF_ANGLE;
    let mut p = arc(k.nose_centre, NOSE_RADIUS, 0.0, fore, NOSE_STEPS);
    p.extend(line(k.fore_start, k.fore_end, FORE_STEPS));
    p.extend(arc(
        k.shoulder_centre,
        SHOULDER_RADIUS,
        fore,
        90.0,
        SHOULDER_FRONT_STEPS,
    ));
    let back1 = 90.0 + BACK1_HALF_ANGLE;
    p.extend(arc(
        k.shoulder_centre,
        SHOULDER_RADIUS,
        90.0,
        back1,
        SHOULDER_BACK_STEPS,
    ));
    p.extend(line(k.back1_start, k.junction, BACK1_STEPS));
    p.extend(line(k.junction, k.back_corner, BACK2_STEPS));
    let centre = DVec2::new(0.0, k.back_corner.y);
    p.extend(line(k.back_corner, centre, BACK_FACE_STEPS));
    p.pop(); // the back-face centre is the pole, not a ring
    p
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;
    use std::collections::HashMap;

    #[test]
    fn viking_is_a_closed_outward_genus_0_net() {
        let ex = viking();
        assert!(
            (1500..=1900).contains(&ex.tris.len()),
            "{} triangles",
            ex.tris.len()
        );
        assert_eq!(check_closed_example(&ex), 2);
    }

    #[test]
    fn viking_max_diameter_is_d() {
        let ex = viking();
        let dmax = ex
            .points
            .iter()
            .map(|p| 2.0 * p.truncate().length())
            .fold(0.0, f64::max);
        assert!((dmax - D).abs() < 1e-12, "max diameter {dmax}");
    }

    /// The forebody cone really is tangent to nose and shoulder, at 20° from
    /// the base plane.
    #[test]
    fn viking_forebody_is_a_tangent_70_degree_cone() {
        let k = keys();
        let fore = (90.0 - FORE_HALF_ANGLE).to_radians();
        let dir = DVec2::new(fore.cos(), fore.sin());
        let chord = k.fore_end - k.fore_start;
        assert!(chord.perp_dot(dir).abs() < 1e-14 && chord.dot(dir) > 1.0);
        assert!((k.fore_start.distance(k.nose_centre) - NOSE_RADIUS).abs() < 1e-14);
        let rs = k.fore_end.distance(k.shoulder_centre);
        assert!((rs - SHOULDER_RADIUS).abs() < 1e-14);
        assert!(k.back1_start.x > k.junction.x && k.junction.x > k.back_corner.x);
    }

    /// Exactly two circles of N edges exceed 30°, at the cone junction and at
    /// the back-face corner; every other edge, nose and shoulder included,
    /// stays at or below 20°.
    #[test]
    fn viking_hard_edges_are_exactly_two_circles() {
        let ex = viking();
        let k = keys();
        let angles = dihedral_angles(&ex);
        let (hard, soft): (Vec<&(u32, u32, f64)>, Vec<_>) = angles.iter().partition(|e| e.2 > 30.0);
        let max_soft = soft.iter().map(|e| e.2).fold(0.0, f64::max);
        let min_hard = hard.iter().map(|e| e.2).fold(180.0, f64::min);
        println!(
            "viking: {} triangles, max soft {max_soft:.3}°, min hard {min_hard:.3}°",
            ex.tris.len()
        );
        assert!(max_soft <= 20.0, "max soft dihedral {max_soft}");
        assert!(min_hard >= 40.0, "min hard dihedral {min_hard}");
        assert_eq!(hard.len(), 2 * N);

        // Sort the hard edges onto the two bend circles: both ends must lie
        // at the (r, z) of the junction or of the back-face corner.
        let mut circles: [Vec<(u32, u32)>; 2] = Default::default();
        let rz = |i: u32| {
            let p = ex.points[i as usize];
            DVec2::new(p.truncate().length(), p.z)
        };
        for &&(a, b, _) in &hard {
            let c = [k.junction, k.back_corner]
                .iter()
                .position(|&at| rz(a).distance(at) < 1e-12 && rz(b).distance(at) < 1e-12)
                .unwrap_or_else(|| panic!("hard edge {a}-{b} is on neither bend circle"));
            circles[c].push((a, b));
        }
        for edges in &circles {
            assert_eq!(edges.len(), N);
            // N edges, every vertex in two of them, connected: one closed loop.
            let mut nb: HashMap<u32, Vec<u32>> = HashMap::new();
            for &(a, b) in edges {
                nb.entry(a).or_default().push(b);
                nb.entry(b).or_default().push(a);
            }
            assert!(nb.len() == N && nb.values().all(|v| v.len() == 2));
            let (start, mut prev, mut cur, mut len) = (edges[0].0, edges[0].0, edges[0].1, 1);
            while cur != start {
                let next = if nb[&cur][0] == prev {
                    nb[&cur][1]
                } else {
                    nb[&cur][0]
                };
                (prev, cur, len) = (cur, next, len + 1);
            }
            assert_eq!(len, N);
        }
    }
}
