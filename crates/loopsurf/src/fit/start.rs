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

use crate::error::Result;
use crate::net::ControlNet;
use crate::refine::refine_uniform;
use crate::remesh::Remesher;
use crate::surface::Surface;
use glam::DVec3;

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
    let (mut points, mut triangles) = (mesh.points.clone(), mesh.triangles.clone());
    for &c in &corners {
        open_apex_fan(&mut points, &mut triangles, &mesh.hard_edges, c);
    }
    let mut net = ControlNet::from_arrays(points, &triangles)
        .map_err(|e| e.during("fit: the remeshed control net"))?;
    for &[a, b] in &mesh.hard_edges {
        net.tag_edge(a, b)?;
    }
    for &c in &corners {
        net.tag_vertex(c)?;
    }
    Ok(refine_uniform(&net, 1)?.into_net())
}

/// The fewest triangles the fit wants around an apex (a tagged corner with
/// no hard edge).
///
/// Why many: a corner vertex of a Loop net whose edges are all smooth stays
/// put while its ring shrinks towards it by 3/8 + cos(2π/n)/4 per step
/// around it but by 5/8 along the axis, so near the tip the height goes as
/// the radius to the power log(5/8) / log(3/8 + cos(2π/n)/4): 0.68 for six
/// triangles (a spike), 0.94 for sixteen (nearly the cone a CAD apex is).
/// Measured on the CAD cone of docs/fitting.md, the fitted surface's worst
/// distance to the true cone: 9.4e-4 of the diagonal with six, 6.0e-4
/// with sixteen, 6.5e-4 with thirty-two.
const APEX_VALENCE: usize = 16;

/// Splits the edges facing corner `c`, round by round, until at least
/// [`APEX_VALENCE`] triangles meet there, when `c` is an apex (no hard
/// edge at it). The remesher closes a cone's tip, whose angles sum to
/// little more than 180°, with three or four triangles; each round of
/// splits doubles them (and halves the triangles across the split edges).
fn open_apex_fan(
    points: &mut Vec<DVec3>,
    triangles: &mut Vec<[u32; 3]>,
    hard: &[[u32; 2]],
    c: u32,
) {
    let is_hard = |a: u32, b: u32| {
        hard.iter()
            .any(|&[x, y]| (x, y) == (a, b) || (x, y) == (b, a))
    };
    loop {
        let fan: Vec<[u32; 3]> = triangles
            .iter()
            .copied()
            .filter(|t| t.contains(&c))
            .collect();
        if fan.len() >= APEX_VALENCE
            || fan
                .iter()
                .any(|t| t.iter().any(|&v| v != c && is_hard(c, v)))
        {
            return;
        }
        let before = triangles.len();
        for t in fan {
            let k = t.iter().position(|&v| v == c).expect("in the fan");
            let (a, b) = (t[(k + 1) % 3], t[(k + 2) % 3]);
            if is_hard(a, b) {
                continue;
            }
            let m = points.len() as u32;
            points.push(0.5 * (points[a as usize] + points[b as usize]));
            split_edge(triangles, a, b, m);
        }
        if triangles.len() == before {
            return;
        }
    }
}

/// Splits edge (a, b) at new vertex m in every triangle holding it,
/// keeping each triangle's orientation.
fn split_edge(triangles: &mut Vec<[u32; 3]>, a: u32, b: u32, m: u32) {
    let mut added = Vec::new();
    for t in triangles.iter_mut() {
        for k in 0..3 {
            let (x, y, z) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            if (y, z) == (a, b) || (y, z) == (b, a) {
                *t = [x, y, m];
                added.push([x, m, z]);
                break;
            }
        }
    }
    triangles.extend(added);
}
