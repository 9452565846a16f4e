//! loopsurf: a legacy surface triangulation as the control net of a Loop
//! subdivision surface, queried like a CAD kernel.
//!
//! Layering (one-way, like OpenSubdiv's Sdc → Vtr → Far):
//! [`rules`] (pure masks) → [`topology`] (connectivity only) →
//! [`features`] (hard edges and vertex kinds) → [`net`] (positions) →
//! [`refine`] (uniform subdivision) and evaluation ([`surface`], exact at any
//! (triangle, v, w)), with [`stream`] to ship a surface as bytes. File formats live in [`io`], built-in shapes in
//! [`examples`].

pub mod adapt;
pub mod error;
pub(crate) mod eval;
pub mod examples;
pub mod features;
pub mod geometry;
pub mod interpolate;
pub mod io;
pub mod mesh;
pub mod net;
pub mod refine;
pub mod repair;
pub mod rules;
pub mod snap;
pub mod stream;
pub mod surface;
pub mod topology;

pub use adapt::{Adapter, AdaptiveMesh};
pub use error::{Element, Error, Result};
pub use features::{Features, VertexKind};
pub use glam::DVec3;
pub use mesh::{Density, Mesher, SurfaceMesh};
pub use net::ControlNet;
pub use refine::{Refinement, SurfacePoint};
pub use snap::Snap;
pub use surface::{Curvature, Evaluation, Surface, SurfaceMode};
pub use topology::Topology;
