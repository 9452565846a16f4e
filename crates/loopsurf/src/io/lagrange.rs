//! The plain data a high-order (Lagrange) surface mesh file carries, shared
//! by the gmsh ([`super::write_msh`]) and VTK ([`super::write_vtu_lagrange`])
//! writers and what their readers give back.
//!
//! It lives in `io`, below the mesher, so that files can be read and
//! written without a surface; the mesher fills it in. Node order is gmsh's
//! (see [`LagrangeMesh::triangles`]); VTK's Lagrange cells use the same
//! order for orders 1 to 4 (checked against `vtkLagrangeTriangle`'s
//! barycentric indexing and gmsh's `getElementProperties`), so neither
//! writer permutes nodes.

use glam::DVec3;

use crate::error::{Error, Result};

/// The orders the files here carry: 1 (linear) to 4.
pub const MAX_LAGRANGE_ORDER: usize = 4;

/// Nodes of a Lagrange triangle of order k: (k + 1)(k + 2)/2.
pub fn nodes_per_triangle(order: usize) -> usize {
    (order + 1) * (order + 2) / 2
}

/// A Lagrange triangle surface mesh of order 1..=4 as files carry it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LagrangeMesh {
    /// 1, 2, 3 or 4.
    pub order: usize,
    pub nodes: Vec<DVec3>,
    /// [`nodes_per_triangle`]`(order)` = (k+1)(k+2)/2 node indices per
    /// triangle, 0-based, in gmsh's order: the 3 vertices, then each edge's
    /// inner nodes (edge 0→1, 1→2, 2→0, each from its first vertex towards
    /// its second), then the interior nodes (order 3: one; order 4: three,
    /// numbered like the vertices of a P1 triangle shrunk onto the interior
    /// lattice, as gmsh and VTK do).
    pub triangles: Vec<u32>,
    /// Per triangle: its face id (0-based); files carry it as the physical
    /// surface group `face + 1`.
    pub faces: Vec<u32>,
    /// Hard edges as Lagrange lines, `order + 1` node indices each, gmsh's
    /// line order: the two end nodes, then the inner nodes from the first
    /// end to the second.
    pub lines: Vec<u32>,
    /// Per line: its curve id (0-based); files carry it as the physical
    /// curve group `curve + 1`.
    pub line_curves: Vec<u32>,
    /// Nodes that are model corners, with their corner id (0-based); files
    /// carry the id as the physical point group `corner + 1`.
    pub corners: Vec<(u32, u32)>,
    /// Per node: (control triangle, v, w) on the loopsurf surface; empty
    /// when unknown.
    pub params: Vec<(u32, f64, f64)>,
}

impl LagrangeMesh {
    /// Node indices per triangle: [`nodes_per_triangle`]`(self.order)`.
    pub fn nodes_per_triangle(&self) -> usize {
        nodes_per_triangle(self.order)
    }

    /// Node indices per line: `order + 1`.
    pub fn nodes_per_line(&self) -> usize {
        self.order + 1
    }

    /// Number of triangles (from [`LagrangeMesh::faces`]).
    pub fn num_triangles(&self) -> usize {
        self.faces.len()
    }

    /// Number of lines (from [`LagrangeMesh::line_curves`]).
    pub fn num_lines(&self) -> usize {
        self.line_curves.len()
    }

    /// The node indices of triangle `t`, in gmsh's order. Panics when `t`
    /// is out of range, like slice indexing.
    pub fn triangle(&self, t: usize) -> &[u32] {
        let n = self.nodes_per_triangle();
        &self.triangles[n * t..n * (t + 1)]
    }

    /// The node indices of line `l`, ends first. Panics when `l` is out of
    /// range, like slice indexing.
    pub fn line(&self, l: usize) -> &[u32] {
        let n = self.nodes_per_line();
        &self.lines[n * l..n * (l + 1)]
    }

    /// Checks everything the writers rely on, so that no file we write is
    /// one other programs crash on: the order, every array's length, every
    /// index in range, finite coordinates and parameters, ids that fit the
    /// formats' signed 32-bit physical tags, and each corner node listed
    /// once (a corner is one gmsh point entity holding its one node).
    pub fn validate(&self) -> Result<()> {
        self.check_sizes()?;
        self.check_finite()?;
        self.check_indices()?;
        self.check_ids()?;
        self.check_corners()
    }

    /// The order, the node count, and every array's length.
    fn check_sizes(&self) -> Result<()> {
        let bad = |message: String| Err(Error::InvalidArgument(message));
        if !(1..=MAX_LAGRANGE_ORDER).contains(&self.order) {
            return bad(format!(
                "Lagrange mesh order {}: must be 1 to {MAX_LAGRANGE_ORDER}",
                self.order
            ));
        }
        let n = self.nodes.len();
        // gmsh's node tags are C ints in MSH 2.2 and in $NodeData.
        if n > i32::MAX as usize {
            return bad(format!(
                "{n} nodes: gmsh and VTK files hold at most {}",
                i32::MAX
            ));
        }
        let (npt, npl) = (self.nodes_per_triangle(), self.nodes_per_line());
        if self.triangles.len() != npt * self.faces.len() {
            return bad(format!(
                "{} triangle node indices for {} faces entries: order {} needs {npt} per triangle",
                self.triangles.len(),
                self.faces.len(),
                self.order
            ));
        }
        if self.lines.len() != npl * self.line_curves.len() {
            return bad(format!(
                "{} line node indices for {} line_curves entries: order {} needs {npl} per line",
                self.lines.len(),
                self.line_curves.len(),
                self.order
            ));
        }
        if !self.params.is_empty() && self.params.len() != n {
            return bad(format!(
                "{} params for {n} nodes: give one per node or none",
                self.params.len()
            ));
        }
        Ok(())
    }

    /// Finite coordinates and parameters.
    fn check_finite(&self) -> Result<()> {
        let bad = |message: String| Err(Error::InvalidArgument(message));
        if let Some(i) = self.nodes.iter().position(|p| !p.is_finite()) {
            return bad(format!(
                "node {i} {:?} is not finite",
                self.nodes[i].to_array()
            ));
        }
        if let Some(i) = self
            .params
            .iter()
            .position(|&(_, v, w)| !v.is_finite() || !w.is_finite())
        {
            return bad(format!(
                "node {i}'s params {:?} are not finite",
                self.params[i]
            ));
        }
        Ok(())
    }

    /// Every element's node indices in range.
    fn check_indices(&self) -> Result<()> {
        let n = self.nodes.len();
        let (npt, npl) = (self.nodes_per_triangle(), self.nodes_per_line());
        for (kind, nodes, per) in [
            ("triangle", &self.triangles, npt),
            ("line", &self.lines, npl),
        ] {
            if let Some(k) = nodes.iter().position(|&i| i as usize >= n) {
                let e = k / per;
                return Err(Error::InvalidArgument(format!(
                    "{kind} {e} {:?} refers to node {}, but there are only {n} nodes",
                    &nodes[e * per..(e + 1) * per],
                    nodes[k]
                )));
            }
        }
        Ok(())
    }

    /// Face and curve ids that fit a gmsh physical tag.
    fn check_ids(&self) -> Result<()> {
        let bad = |message: String| Err(Error::InvalidArgument(message));
        // Physical tags are id + 1 and C ints.
        for (kind, ids) in [("face", &self.faces), ("curve", &self.line_curves)] {
            if let Some(k) = ids.iter().position(|&id| too_big_for_a_tag(id)) {
                return bad(format!(
                    "{kind} id {} (entry {k}) is too large for a gmsh physical tag",
                    ids[k]
                ));
            }
        }
        Ok(())
    }

    /// Each corner a node, its id fit for a physical tag, and no node a
    /// corner twice.
    fn check_corners(&self) -> Result<()> {
        let bad = |message: String| Err(Error::InvalidArgument(message));
        let n = self.nodes.len();
        let mut seen = std::collections::HashMap::with_capacity(self.corners.len());
        for (k, &(node, id)) in self.corners.iter().enumerate() {
            if node as usize >= n {
                return bad(format!(
                    "corner entry {k} is node {node}, but there are only {n} nodes"
                ));
            }
            if too_big_for_a_tag(id) {
                return bad(format!(
                    "corner id {id} (entry {k}) is too large for a gmsh physical tag"
                ));
            }
            if let Some(first) = seen.insert(node, k) {
                return bad(format!(
                    "node {node} is listed as a corner twice (entries {first} and {k})"
                ));
            }
        }
        Ok(())
    }
}

/// Whether id + 1 (the physical tag, a C int) overflows.
fn too_big_for_a_tag(id: u32) -> bool {
    id >= i32::MAX as u32
}

/// Triangle orders by node count: `Some(k)` when `n` is
/// [`nodes_per_triangle`]`(k)` for k in 1..=4.
pub(super) fn triangle_order(n: usize) -> Option<usize> {
    (1..=MAX_LAGRANGE_ORDER).find(|&k| nodes_per_triangle(k) == n)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p2() -> LagrangeMesh {
        LagrangeMesh {
            order: 2,
            nodes: vec![DVec3::ZERO; 6],
            triangles: vec![0, 1, 2, 3, 4, 5],
            faces: vec![0],
            lines: vec![0, 1, 3],
            line_curves: vec![0],
            corners: vec![(0, 0)],
            params: vec![],
        }
    }

    #[test]
    fn counts() {
        assert_eq!(
            (1..=4).map(nodes_per_triangle).collect::<Vec<_>>(),
            [3, 6, 10, 15]
        );
        assert_eq!(triangle_order(10), Some(3));
        assert_eq!(triangle_order(7), None);
        let m = p2();
        assert_eq!((m.num_triangles(), m.num_lines()), (1, 1));
        assert_eq!(m.triangle(0), [0, 1, 2, 3, 4, 5]);
        assert_eq!(m.line(0), [0, 1, 3]);
    }

    /// Each broken invariant is named.
    #[test]
    fn validate_names_the_problem() {
        p2().validate().unwrap();
        type Break = fn(&mut LagrangeMesh);
        let cases: Vec<(Break, &str)> = vec![
            (|m| m.order = 5, "order 5"),
            (|m| m.faces.push(0), "order 2 needs 6 per triangle"),
            (|m| m.lines.push(0), "order 2 needs 3 per line"),
            (|m| m.triangles[4] = 6, "triangle 0"),
            (|m| m.lines[2] = 9, "refers to node 9"),
            (|m| m.nodes[3].y = f64::NAN, "node 3"),
            (|m| m.params = vec![(0, 0.0, 0.0)], "1 params for 6 nodes"),
            (|m| m.params = vec![(0, 0.0, f64::INFINITY); 6], "params"),
            (|m| m.faces[0] = u32::MAX, "face id"),
            (|m| m.corners.push((0, 1)), "corner twice"),
            (|m| m.corners.push((6, 1)), "corner entry 1 is node 6"),
        ];
        for (break_it, message) in cases {
            let mut m = p2();
            break_it(&mut m);
            let err = m.validate().unwrap_err().to_string();
            assert!(err.contains(message), "{err:?} should say {message:?}");
        }
    }
}
