//! loopsurf: a legacy surface triangulation as the control net of a Loop
//! subdivision surface, queried like a CAD kernel.
//!
//! Layering, one way like OpenSubdiv's Sdc → Vtr → Far: a module uses only
//! the modules named before it in this list, which `tests/layering.rs`
//! reads and checks against every path in the sources.
//! 1. Foundations, using nothing of the crate: [`error`], [`examples`]
//!    (built-in nets as plain arrays), [`rules`] (every subdivision, limit
//!    and tangent mask), [`geometry`] (plain triangle measures and edge
//!    swaps) and the crate-private `sets` (disjoint sets, for fans,
//!    sectors and blobs).
//! 2. Files: [`io`] (formats, parse only) → [`repair`] (explicit fixes of
//!    what was parsed, and the options to read a net with them).
//! 3. The net: [`topology`] (connectivity only) → [`parameters`] (surface
//!    points as (triangle, v, w): corners, control vertices, moving between
//!    triangles) → [`features`] (hard edges and vertex kinds) → [`net`]
//!    (positions, validation, the limit operator; reading a file parses,
//!    repairs and validates here).
//! 4. On the net: [`refine`] (uniform subdivision), [`concave`] (corners
//!    whose sectors span more than 180°, and the seams that keep Loop's
//!    crease rules from folding the surface there), [`interpolate`]
//!    (control points whose limit passes through given points),
//!    [`model`] (corners, curves and faces of the hard features) and
//!    [`partition`] (the control triangles in K parts for K processes,
//!    with the halo each part needs).
//! 5. The surface: the crate-private `eval` (patches and special-vertex
//!    eigenstructure) → [`surface`] (exact evaluation at any triangle and
//!    parameters).
//! 6. On the surface: [`stream`] (a surface or a part as bytes), [`folds`]
//!    (where the geometry folds back on itself), [`snap`] (certified
//!    closest points) → [`curve`] (the model's curves in space, their
//!    length and projection) and [`partsurface`] (a part's surface:
//!    walks and closest points that say when the answer may lie in
//!    another part), and [`cad`] (CAD-like tessellations of analytic shapes
//!    with their exact surfaces, to measure a surrogate against the truth).
//! 7. Meshes: [`mesh`] (the chart mesher) → [`remesh`] (the quality
//!    remesher that starts from it), [`adapt`] (adaptive Loop subdivision,
//!    after Liu and Kondo) and [`fairness`] (how far the interpolating
//!    surface departs from the approximating one).
//! 8. Surrogates: [`fit`] (a new control net whose limit surface fits the
//!    input's vertices and feature lines, started from the remesher).
//!
//! No module adds methods to another module's type (checked too), so a
//! type's methods are all in its own module and a module's uses show in
//! its paths: a closest point is `snap::closest_point(&surface, p)`, a
//! curve `LimitCurve::new(&surface, c)?`. What a module above the surface
//! derives from it once (the snap index, the curves' lengths) the surface
//! keeps for it through a trait, without knowing what it is.

pub mod adapt;
pub mod cad;
pub mod concave;
pub mod curve;
pub mod error;
pub(crate) mod eval;
pub mod examples;
pub mod fairness;
pub mod features;
pub mod fit;
pub mod folds;
pub mod geometry;
pub mod interpolate;
pub mod io;
pub mod mesh;
pub mod model;
pub mod net;
pub mod parameters;
pub mod partition;
pub mod partsurface;
pub mod refine;
pub mod remesh;
pub mod repair;
pub mod rules;
mod sets;
pub mod snap;
pub mod stream;
pub mod surface;
pub mod topology;

pub use adapt::{Adapter, AdaptiveMesh};
pub use curve::LimitCurve;
pub use error::{Element, Error, Result};
pub use features::{Features, VertexKind};
pub use fit::{Fit, FitReport, Fitter};
pub use folds::Fold;
pub use glam::DVec3;
pub use mesh::{Density, Mesher, SurfaceMesh};
pub use net::ControlNet;
pub use parameters::SurfacePoint;
pub use partition::Partition;
pub use refine::Refinement;
pub use remesh::Remesher;
pub use snap::Snap;
pub use surface::{Curvature, Evaluation, Surface, SurfaceMode};
pub use topology::Topology;
