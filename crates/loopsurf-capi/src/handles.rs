//! The opaque handles of the C ABI, declared first in the header so that
//! every section can use them: a net is prepared, frozen into a surface,
//! and meshes on the surface are handed over as `ls_trimesh`.

use loopsurf::mesh::high_order::CurvedMesh;
use loopsurf::{ControlNet, Surface};
use std::sync::OnceLock;

/// A control net being prepared: load or build it, tag its hard features,
/// then freeze it into an `ls_surface`.
pub struct ls_net(pub(crate) ControlNet);

/// An immutable limit surface, safe to query from many threads at once.
pub struct ls_surface(pub(crate) Surface);

/// One part of a partitioned net (`ls_net_part`, `ls_part_load`): its
/// triangles and their halo as a net of its own, with the whole's ids.
pub struct ls_part(pub(crate) loopsurf::partition::Part);

/// The limit surface of one part (`ls_part_surface_build`): walks and
/// closest points over its owned triangles, in the whole's triangle ids;
/// safe to query from many threads at once.
pub struct ls_part_surface(pub(crate) loopsurf::partsurface::PartSurface);

/// Remeshing in parts shared out among ranks (`ls_remesh_job_new`): the
/// current stage, this rank's outcomes of it and the bytes it sent.
pub struct ls_remesh_job {
    pub(crate) job: loopsurf::remesh::PartsJob<'static>,
    pub(crate) rank: usize,
    pub(crate) ranks: usize,
    pub(crate) pool: Option<rayon::ThreadPool>,
    pub(crate) own: Option<Vec<(usize, loopsurf::remesh::TaskOutcome)>>,
    pub(crate) sent: Vec<u8>,
}

/// A mesh on the surface, made by `ls_mesh`, `ls_remesh`, `ls_adapt` or
/// `ls_mesh_curve`; immutable, and safe to read from many threads at once.
pub struct ls_trimesh {
    pub(crate) nodes_per_element: usize,
    pub(crate) xyz: Vec<f64>,
    pub(crate) elements: Vec<i32>,
    pub(crate) node_tri: Vec<i32>,
    pub(crate) node_vw: Vec<f64>,
    pub(crate) element_face: Option<Vec<i32>>,
    pub(crate) element_chart: Option<Vec<i32>>,
    pub(crate) element_chart_vw: Option<Vec<f64>>,
    pub(crate) deviation: Option<f64>,
    pub(crate) largest_move: Option<f64>,
    /// The curved mesh, kept to measure its Jacobians when asked.
    pub(crate) curved: Option<CurvedMesh>,
    pub(crate) min_jacobian: OnceLock<f64>,
}
