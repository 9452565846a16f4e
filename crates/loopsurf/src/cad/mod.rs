//! CAD-like tessellations of analytic shapes, with their exact surfaces.
//!
//! A CAD system writes STL by chord deflection (the sagitta of every facet
//! edge below a tolerance) and angle deflection (no facet edge turns the
//! true normal by more than an angle): long slivers along cylinders and
//! fillets, fans at poles, apexes and disk centres, every vertex exactly on
//! the true surface. These shapes reproduce that, and each one also knows
//! its true surface exactly ([`Analytic`]), so that a surrogate built from
//! the tessellation (the Loop limit surface, an interpolant, a fit) can be
//! measured against the truth rather than against another tessellation
//! ([`surrogate_distance`], [`facet_distance`], [`curvature_error`]).
//!
//! The reference distances are closed forms (a surface of revolution
//! reduces to the distance from a point to its profile in a meridian
//! plane; the filleted box is the offset of a box) and share no code with
//! the subdivision evaluation they measure.

use crate::examples::Example;
use crate::{ControlNet, Result};
use glam::DVec3;

mod cone;
mod cylinder;
mod cylinder_plate;
mod filleted_box;
mod measure;
mod profile;
mod revolved;
mod sphere;
pub mod tessellate;
mod torus;

pub use cone::{cone, CONE_HEIGHT, CONE_RADIUS};
pub use cylinder::{cylinder, CapStyle, CYLINDER_HEIGHT, CYLINDER_RADIUS};
pub use cylinder_plate::{cylinder_plate, BOSS_FILLET, BOSS_HEIGHT, BOSS_RADIUS, PLATE_RADIUS};
pub use filleted_box::{FilletedBox, BOX_FILLET, BOX_HALF};
pub use measure::{curvature_error, facet_distance, lattice, surrogate_distance, Deviation};
pub use profile::{Piece, Profile, Segment};
pub use revolved::Revolved;
pub use sphere::{sphere, SPHERE_RADIUS};
pub use torus::{torus, TORUS_MAJOR, TORUS_MINOR};

/// A true sharp feature of a shape: where its surface has no tangent
/// plane, or ends. Surrogates are expected to round or miss these, so
/// curvature checks keep away from them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Feature {
    /// A circle (a sharp rim or a boundary).
    Circle {
        centre: DVec3,
        /// Unit normal of the circle's plane.
        axis: DVec3,
        radius: f64,
    },
    /// An isolated singular point (a cone's apex).
    Point(DVec3),
}

impl Feature {
    /// `n` points along the feature, evenly spaced (closed: the first is
    /// not repeated), for code that wants polylines; a point is one point.
    pub fn polyline(&self, n: usize) -> Vec<DVec3> {
        match *self {
            Feature::Point(q) => vec![q],
            Feature::Circle {
                centre,
                axis,
                radius,
            } => {
                let u = axis.any_orthonormal_vector();
                let v = axis.cross(u);
                (0..n)
                    .map(|k| {
                        let phi = std::f64::consts::TAU * k as f64 / n as f64;
                        centre + radius * (phi.cos() * u + phi.sin() * v)
                    })
                    .collect()
            }
        }
    }

    /// Exact distance from `p` to the feature.
    pub fn distance(&self, p: DVec3) -> f64 {
        match *self {
            Feature::Point(q) => p.distance(q),
            Feature::Circle {
                centre,
                axis,
                radius,
            } => {
                let d = p - centre;
                let h = d.dot(axis);
                let rho = (d - h * axis).length();
                ((rho - radius).powi(2) + h * h).sqrt()
            }
        }
    }
}

/// The exact geometry of a shape, and its CAD-like tessellation.
///
/// Tolerances in the constructors are relative to [`Analytic::diagonal`],
/// the diagonal of the true surface's bounding box, as a CAD exporter's
/// deflection settings are relative to the model size.
pub trait Analytic: Sync {
    /// A short name for tables.
    fn name(&self) -> &'static str;
    /// The tessellation: vertices on the true surface, counter-clockwise
    /// outward triangles.
    fn tessellation(&self) -> &Example;
    /// Length of the true surface's bounding-box diagonal.
    fn diagonal(&self) -> f64;
    /// The chord tolerance the tessellation was made with, relative to the
    /// diagonal.
    fn chord(&self) -> f64;
    /// The point of the true surface (with its finite extent: rims, caps,
    /// boundaries) nearest to `p`.
    fn closest(&self, p: DVec3) -> DVec3;
    /// Unsigned distance from `p` to the true surface.
    fn distance(&self, p: DVec3) -> f64 {
        p.distance(self.closest(p))
    }
    /// The outward unit normal at `closest(p)`, where there is one (on a
    /// sharp rim, the normal of the side the closest point was found on).
    fn normal_at(&self, p: DVec3) -> Option<DVec3>;
    /// Mean curvature at `closest(p)`, positive where the surface bends away
    /// from its outward normal (a sphere of radius r has 1/r, as
    /// [`crate::Curvature::mean`]); `None` where it is not defined.
    fn mean_curvature_at(&self, p: DVec3) -> Option<f64>;
    /// The true sharp features: rims, boundaries, apexes.
    fn features(&self) -> Vec<Feature>;
    /// Whether `closest(p)` is on a blend (a fillet or a corner patch that
    /// joins other pieces with tangent continuity).
    fn is_blend(&self, p: DVec3) -> bool;
    /// How far `closest(p)` is from where the surface stops being C²:
    /// sharp features, boundaries, apexes and the tangent seams of blends.
    /// Zero on a blend itself (fillets and corner patches), so curvature
    /// checks that want plain analytic pieces skip blends and features.
    fn smooth_margin(&self, p: DVec3) -> f64;
    /// The tessellation as a control net, with no repairs.
    fn net(&self) -> Result<ControlNet> {
        let ex = self.tessellation();
        ControlNet::from_arrays(ex.points.clone(), &ex.tris)
    }
}

/// The six shapes at one chord tolerance (relative to the diagonal) and
/// angle tolerance (degrees), in table order.
pub fn all(chord: f64, angle_degrees: f64) -> Vec<Box<dyn Analytic>> {
    vec![
        Box::new(cylinder(chord, angle_degrees, CapStyle::Fan)),
        Box::new(sphere(chord, angle_degrees)),
        Box::new(torus(chord, angle_degrees)),
        Box::new(cone(chord, angle_degrees)),
        Box::new(FilletedBox::new(chord, angle_degrees)),
        Box::new(cylinder_plate(chord, angle_degrees)),
    ]
}
