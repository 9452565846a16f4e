//! The meridian profile of a surface of revolution about the z axis, in
//! (ρ, z) coordinates, and the exact geometry that follows from it.
//!
//! The distance from a point p to a surface of revolution is the distance
//! from (ρ, z) of p to the profile curve in the half-plane ρ ≥ 0: the
//! distance to a point of the surface at azimuth φ′ grows with the angle
//! between φ′ and p's azimuth, so the nearest point lies in p's meridian
//! plane. Everything here is therefore plane geometry of lines and arcs.

use super::Feature;
use glam::{DVec2, DVec3};

/// One smooth piece of a profile, traversed with the outward side on the
/// right: the outward normal of the direction (ρ′, z′) is (z′, −ρ′).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Segment {
    /// The straight segment from `a` to `b`.
    Line { a: DVec2, b: DVec2 },
    /// The arc of the circle about `centre` from angle `from` to angle `to`
    /// (radians; counter-clockwise when `to > from`).
    Arc {
        centre: DVec2,
        radius: f64,
        from: f64,
        to: f64,
    },
}

impl Segment {
    /// The point at fraction t ∈ [0, 1] along the segment. A ρ within
    /// round-off of the axis is put exactly on it, so that poles are
    /// single points.
    pub fn point(&self, t: f64) -> DVec2 {
        let p = match *self {
            Segment::Line { a, b } => {
                if t == 1.0 {
                    b
                } else {
                    a + t * (b - a)
                }
            }
            Segment::Arc {
                centre,
                radius,
                from,
                to,
            } => {
                let angle = from + t * (to - from);
                centre + radius * DVec2::new(angle.cos(), angle.sin())
            }
        };
        if p.x.abs() < 1e-15 * (1.0 + p.length()) {
            DVec2::new(0.0, p.y)
        } else {
            p
        }
    }

    /// Unit tangent (direction of travel) at fraction t.
    pub fn tangent(&self, t: f64) -> DVec2 {
        match *self {
            Segment::Line { a, b } => (b - a).normalize(),
            Segment::Arc { from, to, .. } => {
                let angle = from + t * (to - from);
                DVec2::new(-angle.sin(), angle.cos()) * (to - from).signum()
            }
        }
    }

    /// Curvature of the profile, positive where it bends away from its
    /// outward (right-hand) normal: an arc traversed counter-clockwise
    /// (outward normal away from the centre) has +1/radius.
    pub fn curvature(&self) -> f64 {
        match *self {
            Segment::Line { .. } => 0.0,
            Segment::Arc {
                radius, from, to, ..
            } => (to - from).signum() / radius,
        }
    }

    /// The nearest point of the segment to `q`, as (point, fraction).
    pub fn closest(&self, q: DVec2) -> (DVec2, f64) {
        match *self {
            Segment::Line { a, b } => {
                let d = b - a;
                let t = ((q - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
                (self.point(t), t)
            }
            Segment::Arc {
                centre, from, to, ..
            } => {
                let r = q - centre;
                let (lo, hi) = (from.min(to), from.max(to));
                let mut candidates = vec![0.0, 1.0];
                if r.length_squared() > 0.0 {
                    // The ray's angle, brought into the arc's range if any
                    // turn of it falls there.
                    let angle = r.y.atan2(r.x);
                    let mut a = lo + (angle - lo).rem_euclid(std::f64::consts::TAU);
                    if a > hi {
                        a = f64::NAN;
                    }
                    if a.is_finite() {
                        candidates.push((a - from) / (to - from));
                    }
                }
                candidates
                    .into_iter()
                    .map(|t| (self.point(t), t))
                    .min_by(|x, y| x.0.distance(q).total_cmp(&y.0.distance(q)))
                    .unwrap()
            }
        }
    }

    /// How many equal pieces keep both the sagitta below `sagitta` and the
    /// turning of the tangent below `angle` (radians): one for a line.
    pub fn pieces(&self, sagitta: f64, angle: f64) -> usize {
        match *self {
            Segment::Line { .. } => 1,
            Segment::Arc {
                radius, from, to, ..
            } => {
                let sweep = (to - from).abs();
                let by_chord = 2.0 * (1.0 - sagitta / radius).clamp(-1.0, 1.0).acos();
                (sweep / angle).max(sweep / by_chord).ceil().max(1.0) as usize
            }
        }
    }
}

/// One piece of a profile and whether it is a blend (a fillet that joins
/// two other pieces with tangent continuity).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub segment: Segment,
    pub blend: bool,
}

impl Piece {
    /// A straight piece from `a` to `b`, no blend.
    pub fn line(a: DVec2, b: DVec2) -> Piece {
        Piece {
            segment: Segment::Line { a, b },
            blend: false,
        }
    }
}

/// A connected profile: pieces end to end, open (its ends on the axis, or
/// free as a boundary) or closed (a torus's tube).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    pub pieces: Vec<Piece>,
    pub closed: bool,
}

/// The nearest point of a profile: where, on which piece, at which fraction.
#[derive(Debug, Clone, Copy)]
pub struct Nearest {
    pub point: DVec2,
    pub piece: usize,
    pub t: f64,
}

impl Profile {
    /// The points a tessellation puts on the profile: each piece cut by
    /// [`Segment::pieces`], pieces sharing their end points (a closed
    /// profile does not repeat its first point). Each point comes with the
    /// piece it is inside of, or `None` where it ends a piece: a joint
    /// between two pieces or an end of the profile, which a B-rep has as
    /// an edge of its own.
    pub fn samples(&self, sagitta: f64, angle: f64) -> Vec<(DVec2, Option<usize>)> {
        let n = self.pieces.len();
        // A closed profile of one piece joins only itself: no edge there.
        let seamless = self.closed && n == 1;
        let start = if seamless { Some(0) } else { None };
        let mut out = vec![(self.pieces[0].segment.point(0.0), start)];
        for (k, piece) in self.pieces.iter().enumerate() {
            let cuts = piece.segment.pieces(sagitta, angle);
            out.extend((1..cuts).map(|c| (piece.segment.point(c as f64 / cuts as f64), Some(k))));
            out.push((piece.segment.point(1.0), None));
        }
        if self.closed {
            out.pop();
        }
        out
    }

    /// The nearest point of the profile to `q` in the (ρ, z) half-plane.
    pub fn nearest(&self, q: DVec2) -> Nearest {
        let mut best = Nearest {
            point: DVec2::splat(f64::INFINITY),
            piece: 0,
            t: 0.0,
        };
        for (k, piece) in self.pieces.iter().enumerate() {
            let (point, t) = piece.segment.closest(q);
            if point.distance(q) < best.point.distance(q) {
                best = Nearest { point, piece: k, t };
            }
        }
        best
    }

    /// (ρ, z) of a point and the unit radial direction of its meridian
    /// plane (the x axis for a point on the axis).
    pub fn meridian(p: DVec3) -> (DVec2, DVec3) {
        let rho = p.x.hypot(p.y);
        let radial = if rho > 0.0 {
            DVec3::new(p.x / rho, p.y / rho, 0.0)
        } else {
            DVec3::X
        };
        (DVec2::new(rho, p.z), radial)
    }

    /// The nearest point of the surface of revolution to `p`.
    pub fn closest(&self, p: DVec3) -> DVec3 {
        let (q, radial) = Self::meridian(p);
        let c = self.nearest(q).point;
        c.x * radial + DVec3::new(0.0, 0.0, c.y)
    }

    /// The outward unit normal at the nearest point to `p`; `None` at an
    /// apex.
    pub fn normal_at(&self, p: DVec3) -> Option<DVec3> {
        let (q, radial) = Self::meridian(p);
        let near = self.nearest(q);
        if self.is_apex(near.point) {
            return None;
        }
        let t = self.pieces[near.piece].segment.tangent(near.t);
        Some(t.y * radial + DVec3::new(0.0, 0.0, -t.x))
    }

    /// Mean curvature at the nearest point to `p`: the mean of the profile's
    /// curvature and the parallel's, n_ρ / ρ (Meusnier), which tends to the
    /// profile's own at a smooth pole.
    pub fn mean_curvature_at(&self, p: DVec3) -> Option<f64> {
        let (q, _) = Self::meridian(p);
        let near = self.nearest(q);
        if self.is_apex(near.point) {
            return None;
        }
        let segment = &self.pieces[near.piece].segment;
        let k1 = segment.curvature();
        let rho = near.point.x;
        let k2 = if rho > 1e-12 {
            segment.tangent(near.t).y / rho
        } else {
            k1
        };
        Some(0.5 * (k1 + k2))
    }

    /// The profile's end points (open profiles only).
    fn ends(&self) -> Vec<(DVec2, DVec2)> {
        if self.closed {
            return vec![];
        }
        let (first, last) = (self.pieces[0].segment, self.pieces.last().unwrap().segment);
        vec![
            (first.point(0.0), first.tangent(0.0)),
            (last.point(1.0), last.tangent(1.0)),
        ]
    }

    /// An end on the axis where the profile meets the axis at an angle: a
    /// cone's apex.
    fn is_apex(&self, q: DVec2) -> bool {
        self.ends()
            .iter()
            .any(|&(e, t)| e.x == 0.0 && t.y.abs() > 1e-9 && e.distance(q) == 0.0)
    }

    /// The joints between consecutive pieces: (point, sharp, at a blend).
    fn joints(&self) -> Vec<(DVec2, bool, bool)> {
        let n = self.pieces.len();
        let count = if self.closed { n } else { n - 1 };
        (0..count)
            .map(|k| {
                let (a, b) = (self.pieces[k], self.pieces[(k + 1) % n]);
                let sharp = a
                    .segment
                    .tangent(1.0)
                    .angle_to(b.segment.tangent(0.0))
                    .abs()
                    > 1e-9;
                (a.segment.point(1.0), sharp, a.blend || b.blend)
            })
            .collect()
    }

    /// Sharp rims, free boundary ends and apexes, as features about the z
    /// axis.
    pub fn features(&self) -> Vec<Feature> {
        let lift = |q: DVec2| {
            if q.x == 0.0 {
                Feature::Point(DVec3::new(0.0, 0.0, q.y))
            } else {
                Feature::Circle {
                    centre: DVec3::new(0.0, 0.0, q.y),
                    axis: DVec3::Z,
                    radius: q.x,
                }
            }
        };
        let mut out: Vec<Feature> = self
            .joints()
            .into_iter()
            .filter(|j| j.1)
            .map(|j| lift(j.0))
            .collect();
        for (e, t) in self.ends() {
            if e.x > 0.0 || t.y.abs() > 1e-9 {
                out.push(lift(e));
            }
        }
        out
    }

    /// Whether the nearest point to `p` is on a blend piece.
    pub fn is_blend(&self, p: DVec3) -> bool {
        let (q, _) = Self::meridian(p);
        self.pieces[self.nearest(q).piece].blend
    }

    /// Distance in the meridian plane from the nearest point to `p` to the
    /// nearest feature or blend seam; zero on a blend.
    pub fn smooth_margin(&self, p: DVec3) -> f64 {
        let (q, _) = Self::meridian(p);
        let near = self.nearest(q);
        if self.pieces[near.piece].blend {
            return 0.0;
        }
        let mut special: Vec<DVec2> = self
            .joints()
            .into_iter()
            .filter(|j| j.1 || j.2)
            .map(|j| j.0)
            .collect();
        for (e, t) in self.ends() {
            if e.x > 0.0 || t.y.abs() > 1e-9 {
                special.push(e);
            }
        }
        special
            .iter()
            .map(|s| s.distance(near.point))
            .fold(f64::INFINITY, f64::min)
    }

    /// The angular steps of every sample's ring (0 on the axis), as a B-rep
    /// exporter cuts them: an edge (a joint or an end) by its own radius,
    /// the rings inside a piece (one face) all alike, by the piece's
    /// largest radius, ends included.
    pub fn ring_steps(
        samples: &[(DVec2, Option<usize>)],
        steps: impl Fn(f64) -> usize,
    ) -> Vec<usize> {
        let n = samples.len();
        samples
            .iter()
            .map(|&(q, piece)| match piece {
                _ if q.x == 0.0 => 0,
                None => steps(q.x),
                Some(k) => {
                    // The piece's samples and the edges that bound it.
                    let mut rho: f64 = 0.0;
                    for (i, s) in samples.iter().enumerate() {
                        if s.1 == Some(k) {
                            let (prev, next) = (&samples[(i + n - 1) % n], &samples[(i + 1) % n]);
                            rho = rho.max(s.0.x).max(prev.0.x).max(next.0.x);
                        }
                    }
                    steps(rho)
                }
            })
            .collect()
    }
}
