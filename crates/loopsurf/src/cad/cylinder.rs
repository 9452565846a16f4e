//! A closed cylinder as CAD exports it: one strip of long slivers from the
//! bottom circle to the top one (a ruled surface needs no cut along its
//! rulings), and two planar disks whose rims are sharp edges. A disk is
//! closed either with a fan at its centre or, as many exporters do, with
//! a zigzag of its rim points alone.

use super::profile::{Piece, Profile};
use super::revolved::Revolved;
use super::tessellate::{angular_steps, revolve, within_chord, zigzag, Ring};
use crate::examples::Example;
use glam::DVec2;

/// Radius of the cylinder about the z axis.
pub const CYLINDER_RADIUS: f64 = 0.5;
/// Height: the disks are at z = 0 and z = 2.
pub const CYLINDER_HEIGHT: f64 = 2.0;

/// How the two disks are closed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CapStyle {
    /// A fan from a vertex at the disk's centre.
    Fan,
    /// Rim vertices only, cut in a zigzag: no vertex inside the disk.
    Zigzag,
}

/// The closed cylinder ρ ≤ 0.5, 0 ≤ z ≤ 2, tessellated with the chord
/// tolerance `chord` (relative to the diagonal) and the angle tolerance
/// `angle_degrees`, its disks closed as `caps` says.
pub fn cylinder(chord: f64, angle_degrees: f64, caps: CapStyle) -> Revolved {
    let (r, h) = (CYLINDER_RADIUS, CYLINDER_HEIGHT);
    let line = Piece::line;
    let profile = Profile {
        pieces: vec![
            line(DVec2::ZERO, DVec2::new(r, 0.0)),
            line(DVec2::new(r, 0.0), DVec2::new(r, h)),
            line(DVec2::new(r, h), DVec2::new(0.0, h)),
        ],
        closed: false,
    };
    let diagonal = (8.0 * r * r + h * h).sqrt();
    match caps {
        CapStyle::Fan => Revolved::swept("cylinder", profile, diagonal, chord, angle_degrees),
        CapStyle::Zigzag => {
            let angle = angle_degrees.to_radians();
            let tessellation = within_chord(
                chord * diagonal,
                |s| {
                    let side = [DVec2::new(r, 0.0), DVec2::new(r, h)];
                    let n = angular_steps(r, s, angle);
                    let (points, mut tris, rings) = revolve(&side, false, &[n, n]);
                    let (Ring::Ring(bottom), Ring::Ring(top)) = (&rings[0], &rings[1]) else {
                        unreachable!("both rims are off the axis")
                    };
                    // Counter-clockwise seen from outside: the top ring as
                    // swept, the bottom one reversed.
                    let reversed: Vec<u32> = bottom.iter().rev().copied().collect();
                    tris.extend(zigzag(top));
                    tris.extend(zigzag(&reversed));
                    Example {
                        name: "cylinder-zigzag",
                        points,
                        tris,
                    }
                },
                |p| profile.closest(p).distance(p),
            );
            Revolved::with_tessellation("cylinder-zigzag", profile, diagonal, chord, tessellation)
        }
    }
}
