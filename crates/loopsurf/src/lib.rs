//! loopsurf: a legacy surface triangulation as the control net of a Loop
//! subdivision surface, queried like a CAD kernel.
//!
//! Layering (one-way, like OpenSubdiv's Sdc → Vtr → Far; a module imports
//! only from the ones before it):
//! 1. [`rules`] (every subdivision, limit and tangent mask) and
//!    [`geometry`] (plain triangle measures and edge swaps);
//! 2. [`io`] (file formats, parse only) and [`repair`] (explicit fixes of
//!    dirty triangulations);
//! 3. [`topology`] (connectivity only) → [`parameters`] (surface points
//!    as (triangle, v, w): corners, control vertices, moving between
//!    triangles) → [`features`] (hard edges and vertex kinds) → [`net`]
//!    (positions, validation, the limit operator);
//! 4. [`model`] (corners, curves and faces of the hard features),
//!    [`refine`] (uniform subdivision) and [`interpolate`] (solving for
//!    control points whose limit passes through given points);
//! 5. [`surface`] (exact evaluation at any (triangle, v, w), built on the
//!    crate-private `eval`), with [`stream`] to ship a surface as bytes;
//! 6. [`curve`] (the model's exact curves) and [`snap`] (closest points;
//!    its index is cached by the surface through a trait, so the surface
//!    does not know it), then [`mesh`] (the chart mesher), [`remesh`] (the quality remesher
//!    that starts from it), [`adapt`] and [`fairness`], which use
//!    everything below.
//!
//! Built-in shapes live in [`examples`]; errors in [`error`].

pub mod adapt;
pub mod curve;
pub mod error;
pub(crate) mod eval;
pub mod examples;
pub mod fairness;
pub mod features;
pub mod folds;
pub mod geometry;
pub mod interpolate;
pub mod io;
pub mod mesh;
pub mod model;
pub mod net;
pub mod parameters;
pub mod refine;
pub mod remesh;
pub mod repair;
pub mod rules;
pub mod snap;
pub mod stream;
pub mod surface;
pub mod topology;

pub use adapt::{Adapter, AdaptiveMesh};
pub use curve::LimitCurve;
pub use error::{Element, Error, Result};
pub use features::{Features, VertexKind};
pub use folds::Fold;
pub use glam::DVec3;
pub use mesh::{Density, Mesher, SurfaceMesh};
pub use net::ControlNet;
pub use parameters::SurfacePoint;
pub use refine::Refinement;
pub use remesh::Remesher;
pub use snap::Snap;
pub use surface::{Curvature, Evaluation, Surface, SurfaceMode};
pub use topology::Topology;
