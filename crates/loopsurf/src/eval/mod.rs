//! The machinery behind [`crate::Surface`]: box-spline patches, regular
//! stencils with crease phantoms, and the local matrices of special
//! vertices, each tested against the exact dyadic reference.

pub mod affine;
pub mod box_spline;
mod configurations;
pub mod regular;
pub mod special;
pub mod surface;

#[cfg(test)]
mod tests;

use glam::DVec3;

/// The unit normal of the surface with tangents Xv and Xw (derivatives
/// along v and w, or the tangent masks' limits at a vertex): Xv × Xw over
/// its length. (v, w) run counter-clockwise about it like the corners c0
/// c1 c2 of the triangle, so it points to the side that
/// [`crate::geometry::area_normal`] gives the control triangle: outward on
/// a consistently oriented closed net. `None` where the tangents are
/// parallel, zero (the reported derivatives exactly at a special vertex)
/// or not finite.
#[inline]
pub(crate) fn surface_normal(xv: DVec3, xw: DVec3) -> Option<DVec3> {
    xv.cross(xw).try_normalize()
}
