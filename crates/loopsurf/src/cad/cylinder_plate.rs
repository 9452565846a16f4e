//! A vertical cylinder standing on a flat plate, joined by a fillet of
//! revolution (a concave quarter torus tangent to both): the blend a
//! mechanical part has at every boss. The plate's outer rim is a free
//! boundary (the part continues beyond what is modelled); the cylinder's
//! top disk meets its side at a sharp rim.

use super::profile::{Piece, Profile, Segment};
use super::revolved::Revolved;
use glam::DVec2;
use std::f64::consts::{FRAC_PI_2, PI};

/// Radius of the plate's free outer rim.
pub const PLATE_RADIUS: f64 = 1.5;
/// Radius of the cylinder.
pub const BOSS_RADIUS: f64 = 0.5;
/// Radius of the fillet between plate and cylinder.
pub const BOSS_FILLET: f64 = 0.2;
/// Height of the cylinder's top disk above the plate.
pub const BOSS_HEIGHT: f64 = 1.2;

/// The plate z = 0 out to ρ = 1.5, the fillet, the cylinder of radius 0.5
/// up to z = 1.2 and its top disk, tessellated with the chord tolerance
/// `chord` (relative to the diagonal) and the angle tolerance
/// `angle_degrees`.
pub fn cylinder_plate(chord: f64, angle_degrees: f64) -> Revolved {
    let (rp, rc, f, h) = (PLATE_RADIUS, BOSS_RADIUS, BOSS_FILLET, BOSS_HEIGHT);
    let line = Piece::line;
    let profile = Profile {
        pieces: vec![
            line(DVec2::new(rp, 0.0), DVec2::new(rc + f, 0.0)),
            // Clockwise from the plate up to the cylinder: the outward
            // normal points to the fillet's centre (a concave blend).
            Piece {
                segment: Segment::Arc {
                    centre: DVec2::new(rc + f, f),
                    radius: f,
                    from: -FRAC_PI_2,
                    to: -PI,
                },
                blend: true,
            },
            line(DVec2::new(rc, f), DVec2::new(rc, h)),
            line(DVec2::new(rc, h), DVec2::new(0.0, h)),
        ],
        closed: false,
    };
    let diagonal = (8.0 * rp * rp + h * h).sqrt();
    Revolved::swept("cyl-plate", profile, diagonal, chord, angle_degrees)
}
