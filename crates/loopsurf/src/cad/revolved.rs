//! A surface of revolution about the z axis with its tessellation: the
//! exact geometry of the cylinder, sphere, torus, cone and filleted
//! cylinder-on-plate, all given by a profile.

use super::profile::Profile;
use super::tessellate::{angular_steps, revolve, within_chord};
use super::{Analytic, Example, Feature};
use glam::DVec3;

/// A shape of revolution: its profile, size and tessellation.
#[derive(Debug, Clone)]
pub struct Revolved {
    pub name: &'static str,
    pub profile: Profile,
    diagonal: f64,
    chord: f64,
    tessellation: Example,
}

impl Revolved {
    /// Sweeps the whole profile (poles become fans), cut by chord and
    /// angle deflection: `chord` relative to `diagonal`, `angle_degrees` the
    /// largest turn of the true normal along a cut curve. Each piece of
    /// the profile is a face of a B-rep: its parallels all have the angular
    /// step of its widest one (so parallels near the axis get slivers and
    /// fans), while a joint between pieces is an edge cut by its own
    /// radius, and the rings on either side are stitched to it.
    pub fn swept(
        name: &'static str,
        profile: Profile,
        diagonal: f64,
        chord: f64,
        angle_degrees: f64,
    ) -> Revolved {
        let angle = angle_degrees.to_radians();
        let tessellation = within_chord(
            chord * diagonal,
            |s| {
                let samples = profile.samples(s, angle);
                let steps = Profile::ring_steps(&samples, |rho| angular_steps(rho, s, angle));
                let points: Vec<_> = samples.iter().map(|q| q.0).collect();
                let (points, tris, _) = revolve(&points, profile.closed, &steps);
                Example { name, points, tris }
            },
            |p| profile.closest(p).distance(p),
        );
        Self::with_tessellation(name, profile, diagonal, chord, tessellation)
    }

    /// A profile with a tessellation made some other way.
    pub fn with_tessellation(
        name: &'static str,
        profile: Profile,
        diagonal: f64,
        chord: f64,
        tessellation: Example,
    ) -> Revolved {
        Revolved {
            name,
            profile,
            diagonal,
            chord,
            tessellation,
        }
    }
}

impl Analytic for Revolved {
    fn name(&self) -> &'static str {
        self.name
    }
    fn tessellation(&self) -> &Example {
        &self.tessellation
    }
    fn diagonal(&self) -> f64 {
        self.diagonal
    }
    fn chord(&self) -> f64 {
        self.chord
    }
    fn closest(&self, p: DVec3) -> DVec3 {
        self.profile.closest(p)
    }
    fn normal_at(&self, p: DVec3) -> Option<DVec3> {
        self.profile.normal_at(p)
    }
    fn mean_curvature_at(&self, p: DVec3) -> Option<f64> {
        self.profile.mean_curvature_at(p)
    }
    fn features(&self) -> Vec<Feature> {
        self.profile.features()
    }
    fn is_blend(&self, p: DVec3) -> bool {
        self.profile.is_blend(p)
    }
    fn smooth_margin(&self, p: DVec3) -> f64 {
        self.profile.smooth_margin(p)
    }
}
