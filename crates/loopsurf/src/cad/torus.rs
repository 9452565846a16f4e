//! A torus swept the CAD way: a closed profile circle turned about the z
//! axis, the angular step set by the outer equator.

use super::profile::{Piece, Profile, Segment};
use super::revolved::Revolved;
use glam::DVec2;
use std::f64::consts::PI;

/// Distance from the z axis to the tube's centre circle.
pub const TORUS_MAJOR: f64 = 1.0;
/// Radius of the tube.
pub const TORUS_MINOR: f64 = 0.35;

/// The torus R = 1, r = 0.35 about the z axis, tessellated with the chord
/// tolerance `chord` (relative to the diagonal) and the angle tolerance
/// `angle_degrees`.
pub fn torus(chord: f64, angle_degrees: f64) -> Revolved {
    let (big, small) = (TORUS_MAJOR, TORUS_MINOR);
    let profile = Profile {
        pieces: vec![Piece {
            // Counter-clockwise: the outward normal points away from the
            // tube's centre.
            segment: Segment::Arc {
                centre: DVec2::new(big, 0.0),
                radius: small,
                from: -PI,
                to: PI,
            },
            blend: false,
        }],
        closed: true,
    };
    let side = 2.0 * (big + small);
    let diagonal = (2.0 * side * side + 4.0 * small * small).sqrt();
    Revolved::swept("torus", profile, diagonal, chord, angle_degrees)
}
