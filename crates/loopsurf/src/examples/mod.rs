//! Built-in analytic control nets.
//!
//! These nets exist so that the CLI (`--example NAME`) and the tests have
//! meshes with known answers without reading files: a sphere (valences 5 and
//! 6), a torus (all valence 6, so every triangle is a regular box-spline
//! patch), a cube (90° hard edges and corners), a tetrahedron (valence 3, the
//! non-diagonalizable case), an open disk (a boundary) and the Viking
//! aeroshell of Persson, Aftosmis & Haines §4 (two circles of dihedral-angle hard edges).
//!
//! Every net is a manifold triangulation with consistently counter-clockwise
//! (outward-normal) triangles, no zero-area triangle and no duplicate
//! vertex; all but `open-disk` are closed. Indices are 0-based.
//!
//! [`crate::cad`] holds a different kind of net: analytic shapes
//! tessellated as a CAD exporter writes STL (slivers, fans, vertices on the
//! true surface), each with its exact surface, to measure surrogates
//! against the truth; it sits above the surface, which it measures.

use glam::DVec3;

mod bicone;
mod cube;
mod disk;
mod sphere;
mod tetra;
mod torus;
mod viking;

#[cfg(test)]
mod checks;

pub use bicone::bicone;
pub use cube::cube;
pub use disk::open_disk;
pub use sphere::sphere;
pub use tetra::tetra;
pub use torus::torus;
pub use viking::viking;

/// A built-in control net: vertices and counter-clockwise (outward-normal)
/// triangles, 0-based.
#[derive(Debug, Clone, PartialEq)]
pub struct Example {
    /// The name `by_name` accepts for this net.
    pub name: &'static str,
    /// Vertex positions.
    pub points: Vec<DVec3>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    pub tris: Vec<[u32; 3]>,
}

/// Names accepted by [`by_name`], in the order the CLI lists them.
pub const NAMES: &[&str] = &["viking", "sphere", "torus", "cube", "tetra", "open-disk"];

/// The example called `name` (one of [`NAMES`]), or `None`.
pub fn by_name(name: &str) -> Option<Example> {
    match name {
        "viking" => Some(viking()),
        "sphere" => Some(sphere()),
        "torus" => Some(torus()),
        "cube" => Some(cube()),
        "tetra" => Some(tetra()),
        "open-disk" => Some(open_disk()),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `NAMES` and `by_name` must not drift apart: the CLI lists one and
    /// calls the other.
    #[test]
    fn every_name_resolves_to_itself() {
        for &name in NAMES {
            let ex = by_name(name).unwrap_or_else(|| panic!("{name} not found"));
            assert_eq!(ex.name, name);
        }
        assert!(by_name("no-such-example").is_none());
    }
}
