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
//!
//! The remeshed net is then subdivided once by Loop's rules
//! ([`crate::refine::refine_uniform`]), which halves its edges without
//! adding an irregular vertex. Beside an irregular vertex a Loop surface
//! cannot bend differently in two directions (it is forced umbilic below
//! valence 6, its curvature unbounded above), and a remesher puts
//! irregular vertices wherever it likes, by area; a subdivided net has a
//! quarter of them for the same spacing, each affecting a ring half as
//! wide. Measured on the CAD shapes of docs/fitting.md, worst distance to
//! the true surface at the same final spacing of 0.0075 of the diagonal:
//! torus 3.9e-5 remeshed, 1.8e-5 remeshed at twice that and subdivided;
//! filleted box 6.2e-5 and 6.0e-5; at the same net size (remeshed at 0.015,
//! or at 0.03 and subdivided) the torus 6.3e-5 and 4.9e-5, the sphere
//! 1.3e-5 and 5.7e-6.

use super::polar::{with_polar_apexes, Grid};
use crate::error::Result;
use crate::net::ControlNet;
use crate::refine::refine_uniform;
use crate::remesh::Remesher;
use crate::surface::Surface;

/// The control net of `input` (its features already tagged) with edges of
/// about `size` (model units): remeshed at twice the size, subdivided once.
pub fn control_net(input: &ControlNet, size: f64) -> Result<ControlNet> {
    let surface = Surface::new(input)?;
    let mesh = Remesher::new(&surface)
        .size(2.0 * size)
        .lattice_start()
        .run()
        .map_err(|e| e.during("fit: remeshing the input's surface"))?;
    // A tagged input corner on a smooth or crease vertex is not implied by
    // the hard-edge count: carry the tag over where a new vertex sits on it.
    let topo = input.topology();
    let corners: Vec<u32> = mesh
        .params
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            let k = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
                .iter()
                .position(|&(v, w)| p.v == v && p.w == w)?;
            let vertex = topo.triangles()[p.tri as usize][k] as usize;
            input
                .features()
                .is_tagged_vertex(vertex)
                .then_some(i as u32)
        })
        .collect();
    let Grid {
        points,
        triangles,
        hard_edges,
        corners,
    } = with_polar_apexes(
        Grid {
            points: mesh.points.clone(),
            triangles: mesh.triangles.clone(),
            hard_edges: mesh.hard_edges.clone(),
            corners,
        },
        size,
    );
    let mut net = ControlNet::from_arrays(points, &triangles)
        .map_err(|e| e.during("fit: the remeshed control net"))?;
    for &[a, b] in &hard_edges {
        net.tag_edge(a, b)?;
    }
    for &c in &corners {
        net.tag_vertex(c)?;
    }
    Ok(refine_uniform(&net, 1)?.into_net())
}
