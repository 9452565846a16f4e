//! The model of a part: the whole model's faces, curves and corners (see
//! [`crate::model`]) as they meet the part, in the whole's ids, so that a
//! rank meshing its owned triangles names faces and curves as every other
//! rank does. The ids are decided by the whole (a face's id is its first
//! triangle's rank among faces in file order, and a face or curve may run
//! through many parts), so the part's model is read off the whole's, on
//! the process that holds the whole net.

use super::Part;
use crate::error::{Error, Result};
use crate::model::{Curve, Model};
use crate::net::ControlNet;
use crate::topology::NONE;

/// The whole model's ids on one part.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PartModel {
    /// The whole's face id of each local triangle (owned and halo).
    face_of_triangle: Vec<u32>,
    /// The whole's curve id of each local edge, `NONE` for a soft edge.
    curve_of_edge: Vec<u32>,
    /// The whole's faces holding an owned triangle, ascending.
    faces: Vec<u32>,
    /// The whole's curves through an owned triangle's edge, ascending,
    /// each with its chain and edges in the whole's ids.
    curves: Vec<(u32, Curve)>,
    /// The whole's corners at an owned triangle's corner: (corner id,
    /// local vertex), ascending.
    corners: Vec<(u32, u32)>,
}

impl PartModel {
    /// The model of `part`, a part of `net`, whose model is `whole`
    /// (`Surface::model`, or `Model::new(net.topology(), net.features())`).
    pub fn new(net: &ControlNet, whole: &Model, part: &Part) -> Result<PartModel> {
        let topo = net.topology();
        if part.whole_size() != [topo.num_vertices(), topo.num_triangles()] {
            return Err(Error::InvalidArgument(format!(
                "part of a net of {:?} vertices and triangles, not of this one's {:?}",
                part.whole_size(),
                [topo.num_vertices(), topo.num_triangles()]
            )));
        }
        let local = part.net().topology();
        let g = part.global_vertices();
        let curve_of_edge = local
            .edges()
            .iter()
            .map(|&[a, b]| {
                topo.find_edge(g[a as usize], g[b as usize])
                    .and_then(|e| whole.curve_of_edge(e))
                    .unwrap_or(NONE)
            })
            .collect::<Vec<u32>>();
        let face_of_triangle: Vec<u32> = part
            .global_triangles()
            .iter()
            .map(|&t| whole.face_of_triangle()[t as usize])
            .collect();
        let mut faces: Vec<u32> = part.owned().map(|t| face_of_triangle[t]).collect();
        let mut curves: Vec<u32> = part
            .owned()
            .flat_map(|t| local.triangle_edges()[t])
            .map(|e| curve_of_edge[e as usize])
            .filter(|&c| c != NONE)
            .collect();
        let mut corners: Vec<(u32, u32)> = part
            .owned()
            .flat_map(|t| local.triangles()[t])
            .filter_map(|v| {
                let id = whole.corners().binary_search(&g[v as usize]).ok()?;
                Some((id as u32, v))
            })
            .collect();
        for ids in [&mut faces, &mut curves] {
            ids.sort_unstable();
            ids.dedup();
        }
        corners.sort_unstable();
        corners.dedup();
        let curves = curves
            .into_iter()
            .map(|c| (c, whole.curves()[c as usize].clone()))
            .collect();
        Ok(PartModel {
            face_of_triangle,
            curve_of_edge,
            faces,
            curves,
            corners,
        })
    }

    /// The whole's face id of each local triangle.
    pub fn face_of_triangle(&self) -> &[u32] {
        &self.face_of_triangle
    }
    /// The whole's curve id of local edge `e` (an id in the part's net's
    /// topology), `None` for a soft edge.
    pub fn curve_of_edge(&self, e: usize) -> Option<u32> {
        self.curve_of_edge.get(e).copied().filter(|&c| c != NONE)
    }
    /// The whole's faces holding an owned triangle, ascending.
    pub fn faces(&self) -> &[u32] {
        &self.faces
    }
    /// The whole's curves through an edge of an owned triangle, ascending
    /// by id, each as the whole holds it (global vertex and edge ids).
    pub fn curves(&self) -> &[(u32, Curve)] {
        &self.curves
    }
    /// The whole's corners at a corner of an owned triangle: (corner id,
    /// local vertex), ascending.
    pub fn corners(&self) -> &[(u32, u32)] {
        &self.corners
    }
}
