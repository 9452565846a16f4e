//! The new control net: well-shaped triangles at the chosen size on the
//! input's approximating surface, with the input's features carried over.
//!
//! The input is a CAD tessellation of slivers and fans, a poor control net
//! (Loop's masks assume roughly equilateral rings); its approximating
//! surface is smooth, lies within a few chord tolerances of the true
//! shape, and has the input's hard edges as crease curves. The remesher
//! ([`crate::Remesher`]) puts near-equilateral triangles on it with the
//! crease curves as chains of edges and corners kept, so tagging those
//! chains hard and those corners on the new net makes its creases follow
//! the input's feature lines from the start (Hoppe et al.'s piecewise
//! smooth reconstruction starts the same way, from a mesh with its sharp
//! edges tagged). The positions are only a start: the solve moves them.

use crate::error::Result;
use crate::net::ControlNet;
use crate::remesh::Remesher;
use crate::surface::Surface;

/// The remeshed control net of `input` (its features already tagged) with
/// edges of about `size` (model units).
pub fn control_net(input: &ControlNet, size: f64) -> Result<ControlNet> {
    let surface = Surface::new(input)?;
    let mesh = Remesher::new(&surface)
        .size(size)
        .run()
        .map_err(|e| e.during("fit: remeshing the input's surface"))?;
    let mut net = ControlNet::from_arrays(mesh.points.clone(), &mesh.triangles)
        .map_err(|e| e.during("fit: the remeshed control net"))?;
    for &[a, b] in &mesh.hard_edges {
        net.tag_edge(a, b)?;
    }
    // A tagged input corner on a smooth or crease vertex is not implied by
    // the hard-edge count: carry the tag over where a new vertex sits on it.
    let topo = input.topology();
    for (i, p) in mesh.params.iter().enumerate() {
        let corner = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
            .iter()
            .position(|&(v, w)| p.v == v && p.w == w);
        if let Some(k) = corner {
            let vertex = topo.triangles()[p.tri as usize][k] as usize;
            if input.features().is_tagged_vertex(vertex) {
                net.tag_vertex(i as u32)?;
            }
        }
    }
    Ok(net)
}
