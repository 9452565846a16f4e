//! What the reader gives: [`MshMesh`] and its parts, the entry points, and
//! the conversion to a [`LagrangeMesh`].

use std::collections::BTreeSet;
use std::path::Path;

use glam::DVec3;

use super::parser::Parser;
use super::PARAMS_VIEW;
use crate::error::{Error, Result};
use crate::io::lagrange::LagrangeMesh;

/// What [`read_msh`] found in a gmsh file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MshMesh {
    /// The format version as the file states it ("4.1", "2.2", ...).
    pub version: String,
    /// Whether the file is binary.
    pub binary: bool,
    /// Node coordinates, in ascending node-tag order: node `i` has tag
    /// `node_tags[i]`, and elements refer to nodes by these dense indices.
    pub nodes: Vec<DVec3>,
    /// The nodes' tags in the file, ascending.
    pub node_tags: Vec<u64>,
    /// Complete Lagrange triangles of orders 1..=4 (types 2, 9, 21, 23),
    /// in file order.
    pub triangles: Vec<MshElement>,
    /// Lagrange lines of orders 1..=4 (types 1, 8, 26, 27), in file order.
    pub lines: Vec<MshElement>,
    /// Point elements (type 15), in file order.
    pub points: Vec<MshElement>,
    /// How many elements of other types (quads, tets, P5 triangles, ...)
    /// were skipped.
    pub skipped_elements: usize,
    /// `$PhysicalNames` entries.
    pub physical_names: Vec<MshPhysicalName>,
    /// `$NodeData` views, in file order (one per time step).
    pub node_data: Vec<MshNodeData>,
}

/// One element of [`MshMesh`].
#[derive(Debug, Clone, PartialEq)]
pub struct MshElement {
    /// The element's tag in the file.
    pub tag: u64,
    /// Its Lagrange order (0 for points).
    pub order: usize,
    /// Its nodes as dense 0-based indices into [`MshMesh::nodes`], in
    /// gmsh's order.
    pub nodes: Vec<u32>,
    /// MSH 4.1: the first physical tag of its entity, 0 when the entity
    /// has none (or the file has no `$Entities`); MSH 2.2: its first tag.
    pub physical: i32,
    /// The tag of its entity (MSH 2.2: its second tag, or 0).
    pub entity: i32,
    /// The line it is on (ASCII files).
    pub line: Option<usize>,
}

/// A `$PhysicalNames` entry.
#[derive(Debug, Clone, PartialEq)]
pub struct MshPhysicalName {
    pub dim: i32,
    pub tag: i32,
    pub name: String,
}

/// A `$NodeData` section: one time step of a view.
#[derive(Debug, Clone, PartialEq)]
pub struct MshNodeData {
    /// The first string tag: the view's name.
    pub name: String,
    /// The first real tag: the time (0 when absent).
    pub time: f64,
    /// The first integer tag: the time step.
    pub time_step: i64,
    /// Values per node.
    pub components: usize,
    /// The nodes given, as dense indices into [`MshMesh::nodes`], in file
    /// order.
    pub nodes: Vec<u32>,
    /// `components` values per entry of `nodes`.
    pub values: Vec<f64>,
}

impl MshNodeData {
    /// The values of entry `k` (node `self.nodes[k]`).
    pub fn entry(&self, k: usize) -> &[f64] {
        &self.values[k * self.components..(k + 1) * self.components]
    }
}

/// Reads a gmsh `.msh` file, MSH 4.1 (ASCII or binary) or 2.2 (ASCII or
/// binary).
pub fn read_msh(path: &Path) -> Result<MshMesh> {
    parse_msh(&crate::io::read_bytes(path)?, path)
}

/// [`read_msh`] of bytes already in memory; `path` names the source in
/// errors.
pub fn parse_msh(data: &[u8], path: &Path) -> Result<MshMesh> {
    Parser::new(data, path).parse()
}

impl MshMesh {
    /// The mesh as a [`LagrangeMesh`]: every triangle and line of one order;
    /// triangles, lines and corners (the point elements, one per node) in
    /// element-tag order; a triangle's face is its physical tag − 1, or its
    /// entity tag − 1 when it has no physical group (0 when it has
    /// neither), and likewise a line's curve and a corner's id; per-node
    /// params from the "loopsurf_params" view, which must then cover every
    /// node. Files [`write_msh`](super::write_msh) wrote come back identical.
    pub fn to_lagrange(&self) -> Result<LagrangeMesh> {
        let order = self.one_order()?;
        let mut mesh = LagrangeMesh {
            order,
            nodes: self.nodes.clone(),
            ..Default::default()
        };
        for e in by_tag(&self.triangles) {
            mesh.triangles.extend_from_slice(&e.nodes);
            mesh.faces.push(label(e));
        }
        for e in by_tag(&self.lines) {
            mesh.lines.extend_from_slice(&e.nodes);
            mesh.line_curves.push(label(e));
        }
        let mut seen = BTreeSet::new();
        for e in by_tag(&self.points) {
            if let Some(&node) = e.nodes.first() {
                if seen.insert(node) {
                    mesh.corners.push((node, label(e)));
                }
            }
        }
        if let Some(view) = self.node_data.iter().find(|d| d.name == PARAMS_VIEW) {
            mesh.params = self.params_from(view)?;
        }
        mesh.validate()?;
        Ok(mesh)
    }

    /// The order of every triangle and line (that of the first triangle,
    /// or line; 1 with neither); an element of another order is refused.
    fn one_order(&self) -> Result<usize> {
        let order = self
            .triangles
            .first()
            .or(self.lines.first())
            .map_or(1, |e| e.order);
        for (kind, elements) in [("triangle", &self.triangles), ("line", &self.lines)] {
            if let Some(e) = elements.iter().find(|e| e.order != order) {
                let place = match e.line {
                    Some(l) => format!("element {} (line {l})", e.tag),
                    None => format!("element {}", e.tag),
                };
                return Err(Error::InvalidArgument(format!(
                    "{place} is a {kind} of order {}, but the mesh is of order {order}: \
                     a Lagrange mesh has one order",
                    e.order
                )));
            }
        }
        Ok(order)
    }

    /// Every node's (triangle, v, w) from the params view, which must give
    /// three components for every node.
    fn params_from(&self, view: &MshNodeData) -> Result<Vec<(u32, f64, f64)>> {
        let bad = |message: String| Err(Error::InvalidArgument(message));
        if view.components != 3 {
            return bad(format!(
                "view {PARAMS_VIEW:?} has {} components; (triangle, v, w) needs 3",
                view.components
            ));
        }
        let mut params = vec![None; self.nodes.len()];
        for (k, &node) in view.nodes.iter().enumerate() {
            let &[t, v, w] = view.entry(k) else {
                unreachable!("3 components")
            };
            if !(t >= 0.0 && t <= u32::MAX as f64 && t.fract() == 0.0) {
                return bad(format!(
                    "view {PARAMS_VIEW:?} gives node tag {} the triangle {t}, \
                     which is not a triangle index",
                    self.node_tags[node as usize]
                ));
            }
            params[node as usize] = Some((t as u32, v, w));
        }
        let given = params.iter().filter(|p| p.is_some()).count();
        if given != params.len() {
            return bad(format!(
                "view {PARAMS_VIEW:?} gives {given} of the {} nodes; it must give all",
                params.len()
            ));
        }
        Ok(params.into_iter().flatten().collect())
    }
}

/// An element's label: its physical tag − 1, or its entity tag − 1 when
/// it has no physical group, 0 when it has neither.
fn label(e: &MshElement) -> u32 {
    if e.physical > 0 {
        e.physical as u32 - 1
    } else if e.entity > 0 {
        e.entity as u32 - 1
    } else {
        0
    }
}

/// Elements in tag order (stable, so equal tags keep file order).
fn by_tag(elements: &[MshElement]) -> Vec<&MshElement> {
    let mut sorted: Vec<&MshElement> = elements.iter().collect();
    sorted.sort_by_key(|e| e.tag);
    sorted
}
