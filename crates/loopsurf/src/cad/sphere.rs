//! A sphere tessellated the UV way: parallels and meridians, fans of
//! slivers at the two poles (a meridian step is the same angle at the pole
//! as at the equator).

use super::profile::{Piece, Profile, Segment};
use super::revolved::Revolved;
use glam::DVec2;
use std::f64::consts::FRAC_PI_2;

/// Radius of the sphere about the origin.
pub const SPHERE_RADIUS: f64 = 1.0;

/// The unit sphere, tessellated with the chord tolerance `chord` (relative
/// to the diagonal) and the angle tolerance `angle_degrees`.
pub fn sphere(chord: f64, angle_degrees: f64) -> Revolved {
    let r = SPHERE_RADIUS;
    let profile = Profile {
        pieces: vec![Piece {
            segment: Segment::Arc {
                centre: DVec2::ZERO,
                radius: r,
                from: -FRAC_PI_2,
                to: FRAC_PI_2,
            },
            blend: false,
        }],
        closed: false,
    };
    Revolved::swept(
        "sphere",
        profile,
        2.0 * 3f64.sqrt() * r,
        chord,
        angle_degrees,
    )
}
