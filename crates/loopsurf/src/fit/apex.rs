//! Apexes: the tips of cones, found so that the fit keeps them sharp.
//!
//! A CAD exporter closes a cone with a fan of slivers to its apex. Every
//! edge of the fan turns by one angle step only, so no dihedral-angle
//! threshold marks the apex, and Loop's rules, taking it for a smooth
//! vertex of high valence, round it off along the whole length of the
//! slivers. What marks it is that the facets around it all face away
//! from their mean, as no smooth point's do: the tangent cone is no
//! plane.

use crate::features::VertexKind;
use crate::geometry::unit_normal;
use crate::net::ControlNet;

/// An untagged vertex is an apex when every facet around it turns from the
/// facets' mean normal by more than this: the least turn a crease's two
/// sides show at the default hard angle (30°), in every direction.
pub const APEX_ANGLE_DEGREES: f64 = 15.0;

/// The interior vertices of `net` with no hard edge whose facets all turn
/// from their mean normal by more than [`APEX_ANGLE_DEGREES`].
pub fn apexes(net: &ControlNet) -> Vec<u32> {
    let topo = net.topology();
    let kinds = net.vertex_kinds();
    let cos = APEX_ANGLE_DEGREES.to_radians().cos();
    (0..topo.num_vertices() as u32)
        .filter(|&v| {
            let v = v as usize;
            if kinds[v] != VertexKind::Smooth || topo.is_unreferenced(v) {
                return false;
            }
            let normals: Vec<_> = topo
                .fan(v)
                .iter()
                .map(|&t| {
                    unit_normal(topo.triangles()[t as usize].map(|i| net.points()[i as usize]))
                })
                .collect();
            let mean = normals
                .iter()
                .copied()
                .sum::<glam::DVec3>()
                .normalize_or_zero();
            mean != glam::DVec3::ZERO && normals.iter().all(|n| n.dot(mean) < cos)
        })
        .collect()
}
