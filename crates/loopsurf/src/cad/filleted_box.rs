//! A box with every edge rounded: six flat faces, twelve quarter-cylinder
//! fillets and eight spherical-octant corners, all joined with tangent
//! continuity (blends, not creases). Its true surface is the set of points
//! at the fillet radius from a smaller box, so distances are closed forms.
//!
//! Tessellated as a B-rep exporter does, face by face on shared edge
//! points: a flat face has only its four corners (two triangles), a fillet
//! is one strip of slivers along its whole length, a corner is a
//! triangular lattice whose border points are the fillets' arc points.

use super::tessellate::{within_chord, Welder};
use super::{Analytic, Example, Feature};
use glam::DVec3;
use std::f64::consts::FRAC_PI_2;

/// Half the box's extents.
pub const BOX_HALF: DVec3 = DVec3::new(1.0, 0.75, 0.5);
/// Radius of the fillets and corner spheres.
pub const BOX_FILLET: f64 = 0.2;

/// The filleted box and its tessellation.
#[derive(Debug, Clone)]
pub struct FilletedBox {
    /// Half-extents of the inner box whose offset is the surface.
    inner: DVec3,
    fillet: f64,
    chord: f64,
    tessellation: Example,
}

impl FilletedBox {
    /// The box [−1, 1] × [−0.75, 0.75] × [−0.5, 0.5] with fillets of
    /// radius 0.2, tessellated with the chord tolerance `chord` (relative
    /// to the diagonal) and the angle tolerance `angle_degrees`.
    pub fn new(chord: f64, angle_degrees: f64) -> FilletedBox {
        let mut shape = FilletedBox {
            inner: BOX_HALF - DVec3::splat(BOX_FILLET),
            fillet: BOX_FILLET,
            chord,
            tessellation: Example {
                name: "filleted-box",
                points: vec![],
                tris: vec![],
            },
        };
        let angle = angle_degrees.to_radians();
        let arc = |s: f64| {
            let by_chord = 2.0 * (1.0 - s / BOX_FILLET).clamp(-1.0, 1.0).acos();
            (FRAC_PI_2 / angle)
                .max(FRAC_PI_2 / by_chord)
                .ceil()
                .max(1.0) as usize
        };
        shape.tessellation = within_chord(
            chord * shape.diagonal(),
            |s| shape.build(arc(s)),
            |p| shape.distance(p),
        );
        shape
    }

    /// Offset direction of lattice point (i, j, k), i + j + k = m, of a
    /// corner octant with signs `sign`: the border points are at equal
    /// angles, as on the fillets' arcs.
    fn corner_direction(sign: DVec3, i: usize, j: usize, k: usize, m: usize) -> DVec3 {
        let s = |n: usize| (FRAC_PI_2 * n as f64 / m as f64).sin();
        (sign * DVec3::new(s(i), s(j), s(k))).normalize()
    }

    /// The tessellation with `m` steps on every quarter arc.
    fn build(&self, m: usize) -> Example {
        let mut weld = Welder::new(1e-9 * self.diagonal());
        let mut tris: Vec<[u32; 3]> = Vec::new();
        let (inner, f) = (self.inner, self.fillet);
        // Orient each triangle outward: away from the inner box, which is
        // convex, so the offset direction at the centroid is outward.
        let mut push = |weld: &mut Welder, p: [DVec3; 3]| {
            let t = p.map(|x| weld.vertex(x));
            let c = (p[0] + p[1] + p[2]) / 3.0;
            let out = c - c.clamp(-inner, inner);
            if (p[1] - p[0]).cross(p[2] - p[0]).dot(out) > 0.0 {
                tris.push(t);
            } else {
                tris.push([t[0], t[2], t[1]]);
            }
        };
        let signs: Vec<f64> = vec![-1.0, 1.0];
        for axis in 0..3 {
            let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
            for &sa in &signs {
                // Flat face: its four corners.
                let corner = |sb: f64, sc: f64| {
                    let mut p = DVec3::ZERO;
                    p[axis] = sa * (inner[axis] + f);
                    p[b] = sb * inner[b];
                    p[c] = sc * inner[c];
                    p
                };
                let q = [
                    corner(-1., -1.),
                    corner(1., -1.),
                    corner(1., 1.),
                    corner(-1., 1.),
                ];
                push(&mut weld, [q[0], q[1], q[2]]);
                push(&mut weld, [q[0], q[2], q[3]]);
                // Fillet along `axis` between the faces normal to b and c.
                for &sb in &signs {
                    let point = |l: f64, n: usize| {
                        let d = Self::corner_direction(DVec3::ONE, n, m - n, 0, m);
                        let mut p = DVec3::ZERO;
                        p[axis] = l * inner[axis];
                        p[b] = sa * (inner[b] + f * d.x);
                        p[c] = sb * (inner[c] + f * d.y);
                        p
                    };
                    for n in 0..m {
                        let (p0, p1) = (point(-1.0, n), point(-1.0, n + 1));
                        let (q0, q1) = (point(1.0, n), point(1.0, n + 1));
                        push(&mut weld, [p0, q0, q1]);
                        push(&mut weld, [p0, q1, p1]);
                    }
                }
            }
        }
        // Corners: the lattice i + j + k = m of each octant.
        for sx in [-1.0, 1.0] {
            for sy in [-1.0, 1.0] {
                for sz in [-1.0, 1.0] {
                    let sign = DVec3::new(sx, sy, sz);
                    let centre = sign * inner;
                    let at = |i: usize, j: usize| {
                        centre + f * Self::corner_direction(sign, i, j, m - i - j, m)
                    };
                    for i in 0..m {
                        for j in 0..m - i {
                            push(&mut weld, [at(i, j), at(i + 1, j), at(i, j + 1)]);
                            if i + j + 2 <= m {
                                push(&mut weld, [at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                            }
                        }
                    }
                }
            }
        }
        Example {
            name: "filleted-box",
            points: weld.points,
            tris,
        }
    }

    /// q = |p| − inner per axis: which pieces p is over (faces where one
    /// component is positive, fillets two, corners three).
    fn excess(&self, p: DVec3) -> DVec3 {
        p.abs() - self.inner
    }
}

impl Analytic for FilletedBox {
    fn name(&self) -> &'static str {
        "filleted box"
    }
    fn tessellation(&self) -> &Example {
        &self.tessellation
    }
    fn diagonal(&self) -> f64 {
        2.0 * (self.inner + DVec3::splat(self.fillet)).length()
    }
    fn chord(&self) -> f64 {
        self.chord
    }
    /// Outside the inner box, the offset of its nearest point (an offset
    /// of a convex set keeps nearest points on the same normal); inside,
    /// the nearest face straight out.
    fn closest(&self, p: DVec3) -> DVec3 {
        let c = p.clamp(-self.inner, self.inner);
        if let Some(n) = (p - c).try_normalize() {
            return c + self.fillet * n;
        }
        let q = self.excess(p);
        let axis = if q.x >= q.y && q.x >= q.z {
            0
        } else if q.y >= q.z {
            1
        } else {
            2
        };
        let mut out = p;
        let side = if p[axis] < 0.0 { -1.0 } else { 1.0 };
        out[axis] = side * (self.inner[axis] + self.fillet);
        out
    }
    fn normal_at(&self, p: DVec3) -> Option<DVec3> {
        let x = self.closest(p);
        let c = x.clamp(-self.inner, self.inner);
        (x - c).try_normalize()
    }
    fn mean_curvature_at(&self, p: DVec3) -> Option<f64> {
        let x = self.closest(p);
        let over = self
            .excess(x)
            .to_array()
            .iter()
            .filter(|&&e| e > 1e-12)
            .count();
        Some(match over {
            0 | 1 => 0.0,
            2 => 0.5 / self.fillet,
            _ => 1.0 / self.fillet,
        })
    }
    /// No sharp features: every edge and corner is blended.
    fn features(&self) -> Vec<Feature> {
        vec![]
    }
    /// Fillets (two components of the closest point beyond the inner box)
    /// and corners (three).
    fn is_blend(&self, p: DVec3) -> bool {
        let q = self.excess(self.closest(p));
        q.to_array().iter().filter(|&&e| e > 1e-12).count() >= 2
    }
    fn smooth_margin(&self, p: DVec3) -> f64 {
        if self.is_blend(p) {
            return 0.0;
        }
        let q = self.excess(self.closest(p));
        // On a flat face: the distance to its tangent lines.
        q.to_array()
            .iter()
            .filter(|&&e| e <= 1e-12)
            .map(|e| -e)
            .fold(f64::INFINITY, f64::min)
    }
}
