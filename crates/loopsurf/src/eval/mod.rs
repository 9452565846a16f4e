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
