//! Kinks: crease vertices where the crease turns sharply, found so that the
//! fit keeps them sharp.
//!
//! Two hard edges meeting at a vertex make it a crease vertex, and Loop's
//! crease rule makes the crease a cubic B-spline through it: right along a
//! feature curve, whose polyline turns by an angle step of the export at
//! each vertex, wrong where the curve itself has a corner that only two
//! hard edges meet, as where a crease folds back on itself. CGAL's
//! fandisk has one, turning by 161° (every other crease vertex there turns
//! by 23° at most): the fit rounded it off, passing 1.3e-4, 4.7e-5 and
//! 3.6e-4 of the diagonal from it at resolutions of 0.015, 0.0075 and
//! 0.005; kept as a corner, 5.5e-6, 4.7e-6 and 1.2e-7.

use crate::features::VertexKind;
use crate::net::ControlNet;

/// A crease vertex is a kink when its crease turns by more than this: a
/// feature curve sampled this coarsely would have eight segments a full
/// turn, coarser than a CAD export's angle tolerance (15° to 30°).
pub const KINK_ANGLE_DEGREES: f64 = 45.0;

/// The crease vertices of `net` whose two hard edges turn by more than
/// [`KINK_ANGLE_DEGREES`].
pub fn kinks(net: &ControlNet) -> Vec<u32> {
    let topo = net.topology();
    let kinds = net.vertex_kinds();
    let p = net.points();
    let cos = KINK_ANGLE_DEGREES.to_radians().cos();
    (0..topo.num_vertices())
        .filter(|&v| kinds[v] == VertexKind::Crease)
        .filter(|&v| {
            let [a, b] = match net.features().hard_neighbours(topo, v)[..] {
                [a, b] => [a, b].map(|u| p[u as usize]),
                _ => return false,
            };
            let (into, out) = (p[v] - a, b - p[v]);
            into.dot(out) < cos * into.length() * out.length()
        })
        .map(|v| v as u32)
        .collect()
}
