//! Exact evaluation of the limit surface (issue 3, being built): the parts
//! here are complete and tested against the dyadic reference; the public
//! evaluator that uses them is not there yet, hence the allowance below.
#![allow(dead_code)]

pub mod affine;
pub mod box_spline;
pub mod regular;
pub mod special;
pub mod surface;

#[cfg(test)]
mod tests;
