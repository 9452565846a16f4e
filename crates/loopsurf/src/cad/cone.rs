//! A cone with its apex: strips from the base rim to the apex, so the apex
//! is a fan of slivers, and a sharp rim where the side meets the base disk.

use super::profile::{Piece, Profile};
use super::revolved::Revolved;
use glam::DVec2;

/// Radius of the base disk (at z = 0).
pub const CONE_RADIUS: f64 = 1.0;
/// Height of the apex above the base.
pub const CONE_HEIGHT: f64 = 1.5;

/// The closed cone, base disk of radius 1 at z = 0 and apex at z = 1.5,
/// tessellated with the chord tolerance `chord` (relative to the diagonal)
/// and the angle tolerance `angle_degrees`.
pub fn cone(chord: f64, angle_degrees: f64) -> Revolved {
    let (r, h) = (CONE_RADIUS, CONE_HEIGHT);
    let line = Piece::line;
    let profile = Profile {
        pieces: vec![
            line(DVec2::ZERO, DVec2::new(r, 0.0)),
            line(DVec2::new(r, 0.0), DVec2::new(0.0, h)),
        ],
        closed: false,
    };
    let diagonal = (8.0 * r * r + h * h).sqrt();
    Revolved::swept("cone", profile, diagonal, chord, angle_degrees)
}
