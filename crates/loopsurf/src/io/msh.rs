//! gmsh `.msh` files: high-order (Lagrange) triangle surface meshes out, in
//! MSH 4.1 ASCII or binary, and in again from MSH 4.1 (ASCII, binary) or
//! 2.2 (ASCII, binary), which is what gmsh, meshio and most FE codes read
//! and write.
//!
//! What we write, following the format as gmsh documents it ("MSH file
//! format") and as gmsh 4.15 itself writes it:
//! - physical groups name the model: surface `face + 1` "face_<id>",
//!   curve `curve + 1` "curve_<id>", point `corner + 1` "corner_<id>";
//! - `$Entities` has one point entity per corner, one curve entity per
//!   curve id and one surface entity per face id, each with its physical
//!   group and a real bounding box (bounding-entity lists are empty: gmsh
//!   reads the file as a discrete model either way);
//! - every node sits on the lowest-dimensional entity it belongs to
//!   (corner, else the curve of the first line through it, else the face
//!   of the first triangle using it), so gmsh's own classification agrees;
//!   node tags are index + 1, and the nodes are written in index order,
//!   one block per run of consecutive nodes on one entity (gmsh merges the
//!   blocks of an entity): readers that ignore tags and take nodes and
//!   `$NodeData` values by position (meshio, which also insists on tags
//!   1..n in binary views) still pair every value with its node;
//! - element tags are consecutive: the corners' point elements, then the
//!   lines, then the triangles, each in the mesh's order, so that reading
//!   back and sorting by tag ([`MshMesh::to_lagrange`]) restores the order
//!   even though elements are grouped by entity;
//! - the per-node surface parameters go in a `$NodeData` view
//!   "loopsurf_params" of 3 components (triangle, v, w), which gmsh shows
//!   as a vector field and other readers ignore.
//!
//! ASCII doubles round-trip bit for bit; binary is little-endian (the
//! format's "one" marker says so to readers on other hosts).
//!
//! The reader is general enough for files gmsh and meshio write: sections
//! it does not use (`$Periodic`, `$ElementData`, `$InterpolationScheme`,
//! ...) are skipped, as are elements other than triangles, lines and
//! points. Like every reader here it never panics, trusts no count for
//! allocation beyond what the remaining bytes can hold, and names the line
//! (ASCII) or byte offset (binary) of every error.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::io::Write;
use std::path::Path;

use glam::DVec3;

use super::lagrange::LagrangeMesh;
use crate::error::{Error, Result};

/// The name of the `$NodeData` view holding each node's (triangle, v, w).
pub const PARAMS_VIEW: &str = "loopsurf_params";

/// gmsh's element types of the complete Lagrange triangles of order 1..=4.
const TRIANGLE_TYPES: [i32; 4] = [2, 9, 21, 23];
/// gmsh's element types of the Lagrange lines of order 1..=4.
const LINE_TYPES: [i32; 4] = [1, 8, 26, 27];
/// gmsh's one-node point element.
const POINT_TYPE: i32 = 15;

// ---------------------------------------------------------------- writer

/// Writes a Lagrange triangle mesh as gmsh MSH 4.1, ASCII or binary; see
/// the module doc for what goes where. The mesh is validated first
/// ([`LagrangeMesh::validate`]).
pub fn write_msh(path: &Path, mesh: &LagrangeMesh, binary: bool) -> Result<()> {
    mesh.validate()?;
    let layout = Layout::new(mesh);
    let mut w = super::create(path)?;
    let mut out = Out {
        w: &mut w,
        binary,
        first: true,
    };
    write_file(&mut out, mesh, &layout).map_err(super::io_error(path))?;
    super::finish(w, path)
}

/// Axis-aligned bounds of some nodes.
#[derive(Debug, Clone, Copy)]
struct Bounds {
    min: DVec3,
    max: DVec3,
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        min: DVec3::INFINITY,
        max: DVec3::NEG_INFINITY,
    };

    fn add(&mut self, p: DVec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    /// The bounds, or a point at the origin when nothing was added (an
    /// entity without nodes must still have finite numbers).
    fn finite(&self) -> (DVec3, DVec3) {
        if self.min.x > self.max.x {
            (DVec3::ZERO, DVec3::ZERO)
        } else {
            (self.min, self.max)
        }
    }
}

/// An entity we write: its tag, physical tag (0 for none) and bounds.
struct Entity {
    tag: i32,
    physical: i32,
    bounds: Bounds,
}

/// Where every node and element goes in the file.
struct Layout {
    /// Curve entities (tag = curve + 1), ascending.
    curves: Vec<Entity>,
    /// Surface entities (tag = face + 1), ascending, then the one holding
    /// nodes no element uses, if any.
    surfaces: Vec<Entity>,
    /// Node blocks: runs of consecutive node indices on one entity
    /// (dim, tag), in index order.
    node_blocks: Vec<((i32, i32), std::ops::Range<u32>)>,
    /// Line indices per curve id, in mesh order.
    lines_by_curve: BTreeMap<u32, Vec<usize>>,
    /// Triangle indices per face id, in mesh order.
    tris_by_face: BTreeMap<u32, Vec<usize>>,
}

impl Layout {
    fn new(mesh: &LagrangeMesh) -> Layout {
        let (npt, npl) = (mesh.nodes_per_triangle(), mesh.nodes_per_line());
        let mut lines_by_curve: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
        for (l, &c) in mesh.line_curves.iter().enumerate() {
            lines_by_curve.entry(c).or_default().push(l);
        }
        let mut tris_by_face: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
        for (t, &f) in mesh.faces.iter().enumerate() {
            tris_by_face.entry(f).or_default().push(t);
        }
        let entity = |id: u32, elements: &[usize], nodes: &[u32], per: usize| {
            let mut bounds = Bounds::EMPTY;
            for &e in elements {
                for &i in &nodes[e * per..(e + 1) * per] {
                    bounds.add(mesh.nodes[i as usize]);
                }
            }
            Entity {
                tag: id as i32 + 1,
                physical: id as i32 + 1,
                bounds,
            }
        };
        let curves: Vec<Entity> = lines_by_curve
            .iter()
            .map(|(&c, ls)| entity(c, ls, &mesh.lines, npl))
            .collect();
        let mut surfaces: Vec<Entity> = tris_by_face
            .iter()
            .map(|(&f, ts)| entity(f, ts, &mesh.triangles, npt))
            .collect();

        // Each node on its lowest-dimensional entity.
        let mut home: Vec<Option<(i32, i32)>> = vec![None; mesh.nodes.len()];
        for (k, &(node, _)) in mesh.corners.iter().enumerate() {
            home[node as usize] = Some((0, k as i32 + 1));
        }
        for (l, &c) in mesh.line_curves.iter().enumerate() {
            for &i in mesh.line(l) {
                home[i as usize].get_or_insert((1, c as i32 + 1));
            }
        }
        for (t, &f) in mesh.faces.iter().enumerate() {
            for &i in mesh.triangle(t) {
                home[i as usize].get_or_insert((2, f as i32 + 1));
            }
        }
        // Nodes no element uses still need an entity: a surface of their
        // own, without a physical group, at the first free tag.
        if home.iter().any(Option::is_none) {
            let used: BTreeSet<i32> = surfaces.iter().map(|s| s.tag).collect();
            let tag = (1..).find(|t| !used.contains(t)).unwrap_or(1);
            let mut bounds = Bounds::EMPTY;
            for (i, h) in home.iter_mut().enumerate() {
                if h.is_none() {
                    *h = Some((2, tag));
                    bounds.add(mesh.nodes[i]);
                }
            }
            surfaces.push(Entity {
                tag,
                physical: 0,
                bounds,
            });
        }
        let mut node_blocks: Vec<((i32, i32), std::ops::Range<u32>)> = Vec::new();
        for (i, h) in home.iter().enumerate() {
            let (key, i) = (h.unwrap_or((2, 1)), i as u32);
            match node_blocks.last_mut() {
                Some((k, run)) if *k == key => run.end = i + 1,
                _ => node_blocks.push((key, i..i + 1)),
            }
        }
        Layout {
            curves,
            surfaces,
            node_blocks,
            lines_by_curve,
            tris_by_face,
        }
    }
}

/// Writes the MSH 4.1 items one at a time, as text (space-separated,
/// one record per line) or as the binary sizes the format prescribes:
/// int = 4 bytes, size_t = 8, double = 8, little-endian.
struct Out<'a, W: Write> {
    w: &'a mut W,
    binary: bool,
    /// Nothing written on the current text line yet.
    first: bool,
}

impl<W: Write> Out<'_, W> {
    fn sep(&mut self) -> std::io::Result<()> {
        if !self.first {
            self.w.write_all(b" ")?;
        }
        self.first = false;
        Ok(())
    }

    fn size(&mut self, x: u64) -> std::io::Result<()> {
        if self.binary {
            return self.w.write_all(&x.to_le_bytes());
        }
        self.sep()?;
        write!(self.w, "{x}")
    }

    fn int(&mut self, x: i32) -> std::io::Result<()> {
        if self.binary {
            return self.w.write_all(&x.to_le_bytes());
        }
        self.sep()?;
        write!(self.w, "{x}")
    }

    fn real(&mut self, x: f64) -> std::io::Result<()> {
        if self.binary {
            return self.w.write_all(&x.to_le_bytes());
        }
        self.sep()?;
        super::write_f64(self.w, x)
    }

    fn point(&mut self, p: DVec3) -> std::io::Result<()> {
        self.real(p.x)?;
        self.real(p.y)?;
        self.real(p.z)
    }

    /// Ends a record: a newline in text, nothing in binary.
    fn eol(&mut self) -> std::io::Result<()> {
        self.first = true;
        if self.binary {
            Ok(())
        } else {
            self.w.write_all(b"\n")
        }
    }

    /// A line of text, in either mode (section keywords and the ASCII
    /// headers of binary files).
    fn text(&mut self, s: &str) -> std::io::Result<()> {
        self.first = true;
        writeln!(self.w, "{s}")
    }

    /// Closes a section: binary payloads end with a newline before the
    /// `$End` keyword, as gmsh writes them.
    fn end(&mut self, name: &str) -> std::io::Result<()> {
        if self.binary {
            self.w.write_all(b"\n")?;
        }
        self.text(&format!("$End{name}"))
    }
}

fn write_file<W: Write>(
    o: &mut Out<W>,
    mesh: &LagrangeMesh,
    layout: &Layout,
) -> std::io::Result<()> {
    let k = mesh.order;
    let (npt, npl) = (mesh.nodes_per_triangle(), mesh.nodes_per_line());
    let (ncorners, nlines, ntris) = (mesh.corners.len(), mesh.num_lines(), mesh.num_triangles());

    o.text("$MeshFormat")?;
    if o.binary {
        o.text("4.1 1 8")?;
        o.w.write_all(&1i32.to_le_bytes())?;
        o.w.write_all(b"\n")?;
    } else {
        o.text("4.1 0 8")?;
    }
    o.text("$EndMeshFormat")?;

    // Physical names are text in both modes.
    let corner_ids: BTreeSet<u32> = mesh.corners.iter().map(|&(_, id)| id).collect();
    let names = corner_ids.len() + layout.curves.len() + layout.tris_by_face.len();
    if names > 0 {
        o.text("$PhysicalNames")?;
        o.text(&names.to_string())?;
        for id in &corner_ids {
            o.text(&format!("0 {} \"corner_{id}\"", id + 1))?;
        }
        for &c in layout.lines_by_curve.keys() {
            o.text(&format!("1 {} \"curve_{c}\"", c + 1))?;
        }
        for &f in layout.tris_by_face.keys() {
            o.text(&format!("2 {} \"face_{f}\"", f + 1))?;
        }
        o.text("$EndPhysicalNames")?;
    }

    o.text("$Entities")?;
    o.size(ncorners as u64)?;
    o.size(layout.curves.len() as u64)?;
    o.size(layout.surfaces.len() as u64)?;
    o.size(0)?;
    o.eol()?;
    for (j, &(node, id)) in mesh.corners.iter().enumerate() {
        o.int(j as i32 + 1)?;
        o.point(mesh.nodes[node as usize])?;
        o.size(1)?;
        o.int(id as i32 + 1)?;
        o.eol()?;
    }
    for e in layout.curves.iter().chain(&layout.surfaces) {
        let (min, max) = e.bounds.finite();
        o.int(e.tag)?;
        o.point(min)?;
        o.point(max)?;
        if e.physical > 0 {
            o.size(1)?;
            o.int(e.physical)?;
        } else {
            o.size(0)?;
        }
        o.size(0)?; // no bounding points / curves
        o.eol()?;
    }
    o.end("Entities")?;

    let n = mesh.nodes.len() as u64;
    o.text("$Nodes")?;
    o.size(layout.node_blocks.len() as u64)?;
    o.size(n)?;
    o.size(n.min(1))?;
    o.size(n)?;
    o.eol()?;
    for ((dim, tag), nodes) in &layout.node_blocks {
        o.int(*dim)?;
        o.int(*tag)?;
        o.int(0)?;
        o.size(nodes.len() as u64)?;
        o.eol()?;
        for i in nodes.clone() {
            o.size(i as u64 + 1)?;
            o.eol()?;
        }
        for i in nodes.clone() {
            o.point(mesh.nodes[i as usize])?;
            o.eol()?;
        }
    }
    o.end("Nodes")?;

    let total = (ncorners + nlines + ntris) as u64;
    let blocks = ncorners + layout.lines_by_curve.len() + layout.tris_by_face.len();
    o.text("$Elements")?;
    o.size(blocks as u64)?;
    o.size(total)?;
    o.size(total.min(1))?;
    o.size(total)?;
    o.eol()?;
    for (j, &(node, _)) in mesh.corners.iter().enumerate() {
        for x in [0, j as i32 + 1, POINT_TYPE] {
            o.int(x)?;
        }
        o.size(1)?;
        o.eol()?;
        o.size(j as u64 + 1)?;
        o.size(node as u64 + 1)?;
        o.eol()?;
    }
    let groups = [
        (
            1,
            LINE_TYPES[k - 1],
            &layout.lines_by_curve,
            &mesh.lines,
            npl,
            ncorners,
        ),
        (
            2,
            TRIANGLE_TYPES[k - 1],
            &layout.tris_by_face,
            &mesh.triangles,
            npt,
            ncorners + nlines,
        ),
    ];
    for (dim, ty, by_id, nodes, per, first_tag) in groups {
        for (&id, elements) in by_id {
            for x in [dim, id as i32 + 1, ty] {
                o.int(x)?;
            }
            o.size(elements.len() as u64)?;
            o.eol()?;
            for &e in elements {
                o.size((first_tag + e) as u64 + 1)?;
                for &i in &nodes[e * per..(e + 1) * per] {
                    o.size(i as u64 + 1)?;
                }
                o.eol()?;
            }
        }
    }
    o.end("Elements")?;

    if !mesh.params.is_empty() {
        // The header of a view is text in both modes.
        o.text("$NodeData")?;
        o.text("1")?;
        o.text(&format!("\"{PARAMS_VIEW}\""))?;
        o.text("1")?;
        o.text("0")?;
        o.text("3")?;
        o.text("0")?;
        o.text("3")?;
        o.text(&mesh.nodes.len().to_string())?;
        for (i, &(tri, v, w)) in mesh.params.iter().enumerate() {
            // The node tag of a view entry is an int, even in binary 4.1.
            o.int(i as i32 + 1)?;
            o.real(tri as f64)?;
            o.real(v)?;
            o.real(w)?;
            o.eol()?;
        }
        o.end("NodeData")?;
    }
    Ok(())
}

// ---------------------------------------------------------------- reader

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
    parse_msh(&super::read_bytes(path)?, path)
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
    /// node. Files [`write_msh`] wrote come back identical.
    pub fn to_lagrange(&self) -> Result<LagrangeMesh> {
        let bad = |message: String| Err(Error::InvalidArgument(message));
        let place = |e: &MshElement| match e.line {
            Some(l) => format!("element {} (line {l})", e.tag),
            None => format!("element {}", e.tag),
        };
        let order = self
            .triangles
            .first()
            .or(self.lines.first())
            .map_or(1, |e| e.order);
        for (kind, elements) in [("triangle", &self.triangles), ("line", &self.lines)] {
            if let Some(e) = elements.iter().find(|e| e.order != order) {
                return bad(format!(
                    "{} is a {kind} of order {}, but the mesh is of order {order}: \
                     a Lagrange mesh has one order",
                    place(e),
                    e.order
                ));
            }
        }
        let id = |e: &MshElement| -> u32 {
            if e.physical > 0 {
                e.physical as u32 - 1
            } else if e.entity > 0 {
                e.entity as u32 - 1
            } else {
                0
            }
        };
        let mut mesh = LagrangeMesh {
            order,
            nodes: self.nodes.clone(),
            ..Default::default()
        };
        for e in by_tag(&self.triangles) {
            mesh.triangles.extend_from_slice(&e.nodes);
            mesh.faces.push(id(e));
        }
        for e in by_tag(&self.lines) {
            mesh.lines.extend_from_slice(&e.nodes);
            mesh.line_curves.push(id(e));
        }
        let mut seen = BTreeSet::new();
        for e in by_tag(&self.points) {
            if let Some(&node) = e.nodes.first() {
                if seen.insert(node) {
                    mesh.corners.push((node, id(e)));
                }
            }
        }
        if let Some(view) = self.node_data.iter().find(|d| d.name == PARAMS_VIEW) {
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
            mesh.params = params.into_iter().flatten().collect();
        }
        mesh.validate()?;
        Ok(mesh)
    }
}

/// The nodes of every gmsh element type of fixed size (as gmsh 4.15's
/// `getElementProperties` lists them), so that elements of types we do not
/// use can be skipped, in binary files too.
const TYPE_NODES: &[(i32, u16)] = &[
    (1, 2),
    (2, 3),
    (3, 4),
    (4, 4),
    (5, 8),
    (6, 6),
    (7, 5),
    (8, 3),
    (9, 6),
    (10, 9),
    (11, 10),
    (12, 27),
    (13, 18),
    (14, 14),
    (15, 1),
    (16, 8),
    (17, 20),
    (18, 15),
    (19, 13),
    (20, 9),
    (21, 10),
    (22, 12),
    (23, 15),
    (24, 15),
    (25, 21),
    (26, 4),
    (27, 5),
    (28, 6),
    (29, 20),
    (30, 35),
    (31, 56),
    (32, 22),
    (33, 28),
    (36, 16),
    (37, 25),
    (38, 36),
    (39, 12),
    (40, 16),
    (41, 20),
    (42, 28),
    (43, 36),
    (44, 45),
    (45, 55),
    (46, 66),
    (47, 49),
    (48, 64),
    (49, 81),
    (50, 100),
    (51, 121),
    (52, 18),
    (53, 21),
    (54, 24),
    (55, 27),
    (56, 30),
    (57, 24),
    (58, 28),
    (59, 32),
    (60, 36),
    (61, 40),
    (62, 7),
    (63, 8),
    (64, 9),
    (65, 10),
    (66, 11),
    (71, 84),
    (72, 120),
    (73, 165),
    (74, 220),
    (75, 286),
    (79, 34),
    (80, 40),
    (81, 46),
    (82, 52),
    (83, 58),
    (84, 1),
    (85, 1),
    (86, 1),
    (87, 1),
    (88, 1),
    (89, 1),
    (92, 64),
    (93, 125),
    (94, 216),
    (95, 343),
    (96, 512),
    (97, 729),
    (98, 1000),
    (99, 32),
    (100, 44),
    (101, 56),
    (102, 68),
    (103, 80),
    (104, 92),
    (105, 104),
    (118, 30),
    (119, 55),
    (120, 91),
    (121, 140),
    (122, 204),
    (123, 285),
    (124, 385),
    (125, 21),
    (126, 29),
    (127, 37),
    (128, 45),
    (129, 53),
    (130, 61),
    (131, 69),
    (132, 1),
    (137, 16),
];

fn type_nodes(ty: i32) -> Option<usize> {
    TYPE_NODES
        .iter()
        .find(|&&(t, _)| t == ty)
        .map(|&(_, n)| n as usize)
}

/// What an element type is to us.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Triangle(usize),
    Line(usize),
    Point,
    Other,
}

fn kind_of(ty: i32) -> Kind {
    if let Some(k) = TRIANGLE_TYPES.iter().position(|&t| t == ty) {
        Kind::Triangle(k + 1)
    } else if let Some(k) = LINE_TYPES.iter().position(|&t| t == ty) {
        Kind::Line(k + 1)
    } else if ty == POINT_TYPE {
        Kind::Point
    } else {
        Kind::Other
    }
}

/// A node as read, before tags become indices.
struct RawNode {
    tag: u64,
    xyz: DVec3,
    place: usize,
}

/// An element as read, before node tags become indices.
struct RawElement {
    tag: u64,
    kind: Kind,
    /// (dim, entity tag) for MSH 4.1, (-1, elementary tag) for 2.2.
    entity: (i32, i32),
    /// MSH 2.2's physical tag; MSH 4.1 looks it up in `$Entities`.
    physical: i32,
    /// Range in `Parser::element_nodes`.
    first: usize,
    count: usize,
    place: usize,
}

/// A `$NodeData` section as read.
struct RawNodeData {
    name: String,
    time: f64,
    time_step: i64,
    components: usize,
    /// (node tag, place) per entry.
    tags: Vec<(u64, usize)>,
    values: Vec<f64>,
}

/// The MSH format families we read.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Version {
    V2,
    V41,
}

/// A cursor over the file: whitespace-separated text tokens with their
/// line, or little-endian binary items with their offset.
struct Parser<'a> {
    data: &'a [u8],
    path: &'a Path,
    pos: usize,
    /// The line `pos` is on (meaningful before binary data).
    line: usize,
    /// Where the last token or item started: its line and byte offset.
    item_line: usize,
    item_pos: usize,
    /// The file is binary: places are byte offsets, not lines.
    binary: bool,
    /// Currently inside a binary payload.
    in_binary: bool,
    version: Version,
    /// The section being read and what in it, for messages.
    section: &'static str,
    context: String,

    version_text: String,
    physical_names: Vec<MshPhysicalName>,
    /// (dim, entity tag) → first physical tag.
    entity_physical: HashMap<(i32, i32), i32>,
    nodes: Vec<RawNode>,
    elements: Vec<RawElement>,
    element_nodes: Vec<u64>,
    skipped: usize,
    node_data: Vec<RawNodeData>,
}

/// Up to 40 characters of a token, for messages.
fn shown(token: &[u8]) -> String {
    let s = String::from_utf8_lossy(token);
    if s.chars().count() > 40 {
        format!("{:?}...", s.chars().take(40).collect::<String>())
    } else {
        format!("{s:?}")
    }
}

impl<'a> Parser<'a> {
    fn new(data: &'a [u8], path: &'a Path) -> Self {
        Parser {
            data,
            path,
            pos: 0,
            line: 1,
            item_line: 1,
            item_pos: 0,
            binary: false,
            in_binary: false,
            version: Version::V41,
            section: "the file",
            context: String::new(),
            version_text: String::new(),
            physical_names: Vec::new(),
            entity_physical: HashMap::new(),
            nodes: Vec::new(),
            elements: Vec::new(),
            element_nodes: Vec::new(),
            skipped: 0,
            node_data: Vec::new(),
        }
    }

    // ---- places and errors

    /// The place of the last item: a line (text files) or byte offset.
    fn place(&self) -> usize {
        if self.binary {
            self.item_pos
        } else {
            self.item_line
        }
    }

    /// An error at a place [`Parser::place`] gave.
    fn error_at(&self, place: usize, message: String) -> Error {
        if self.binary {
            Error::InvalidArgument(format!("byte {place}: {message}")).in_file(self.path, None)
        } else {
            Error::Malformed {
                line: place,
                message,
            }
            .in_file(self.path, Some(place))
        }
    }

    /// An error about the last item read, naming the section.
    fn bad(&self, message: impl std::fmt::Display) -> Error {
        let context = if self.context.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.context)
        };
        self.error_at(
            self.place(),
            format!("{}{context}: {message}", self.section),
        )
    }

    /// The file ends before `what`.
    fn truncated(&self, what: &str) -> Error {
        let context = if self.context.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.context)
        };
        if self.binary {
            Error::Truncated {
                message: format!(
                    "{}{context}: the file ends at byte {} before {what}",
                    self.section,
                    self.data.len()
                ),
            }
            .in_file(self.path, None)
        } else {
            Error::Truncated {
                message: format!("{}{context}: the file ends before {what}", self.section),
            }
            // The last line with data on it.
            .in_file(self.path, Some(self.item_line))
        }
    }

    /// Bytes left: what bounds any announced count.
    fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }

    // ---- text

    fn skip_whitespace(&mut self) {
        while let Some(&b) = self.data.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
    }

    fn token(&mut self) -> Option<&'a [u8]> {
        self.skip_whitespace();
        if self.pos == self.data.len() {
            return None;
        }
        let start = self.pos;
        (self.item_line, self.item_pos) = (self.line, start);
        while self.pos < self.data.len() && !self.data[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        Some(&self.data[start..self.pos])
    }

    /// The next text token parsed as a `T`.
    fn text<T: std::str::FromStr>(&mut self, what: &str) -> Result<T> {
        let token = self.token().ok_or_else(|| self.truncated(what))?;
        std::str::from_utf8(token)
            .ok()
            .and_then(|s| s.parse().ok())
            .ok_or_else(|| self.bad(format!("expected {what}, found {}", shown(token))))
    }

    /// The rest of the current line (without its end), consuming the end.
    fn rest_of_line(&mut self) -> &'a [u8] {
        let start = self.pos;
        let end = self.data[start..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(self.data.len(), |k| start + k);
        self.pos = (end + 1).min(self.data.len());
        if end < self.data.len() {
            self.line += 1;
        }
        let line = &self.data[start..end];
        line.strip_suffix(b"\r").unwrap_or(line)
    }

    /// Ends a text line before binary data: only blanks may remain on it.
    fn end_line(&mut self) -> Result<()> {
        let rest = self.rest_of_line();
        if rest.iter().all(u8::is_ascii_whitespace) {
            Ok(())
        } else {
            Err(self.bad(format!("unexpected {} before binary data", shown(rest))))
        }
    }

    /// A quoted string tag on its own line (quotes optional).
    fn string_line(&mut self, what: &str) -> Result<String> {
        self.skip_whitespace();
        if self.pos == self.data.len() {
            return Err(self.truncated(what));
        }
        (self.item_line, self.item_pos) = (self.line, self.pos);
        let line = String::from_utf8_lossy(self.rest_of_line())
            .trim()
            .to_string();
        let unquoted = line
            .strip_prefix('"')
            .and_then(|s| s.strip_suffix('"'))
            .unwrap_or(&line);
        Ok(unquoted.to_string())
    }

    /// Expects `$End<name>` next.
    fn expect_end(&mut self, name: &str) -> Result<()> {
        let want = format!("$End{name}");
        match self.token() {
            Some(t) if t == want.as_bytes() => Ok(()),
            Some(t) if self.pos == self.data.len() && want.as_bytes().starts_with(t) => {
                Err(self.truncated(&want))
            }
            Some(t) => Err(self.bad(format!(
                "expected {want}, found {} (more data than announced?)",
                shown(t)
            ))),
            None => Err(self.truncated(&want)),
        }
    }

    /// Skips a section we do not use, up to its `$End` line.
    fn skip_section(&mut self, name: &[u8]) -> Result<()> {
        let mut end = b"$End".to_vec();
        end.extend_from_slice(name);
        let found = self.data[self.pos..]
            .windows(end.len())
            .position(|w| w == end.as_slice());
        let Some(k) = found else {
            return Err(self.truncated(&format!("${}", String::from_utf8_lossy(&end[1..]))));
        };
        let stop = self.pos + k + end.len();
        self.line += self.data[self.pos..stop]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        self.pos = stop;
        Ok(())
    }

    // ---- binary

    fn bytes<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        self.item_pos = self.pos;
        let Some(b) = self.data.get(self.pos..self.pos + N) else {
            return Err(self.truncated(what));
        };
        let mut a = [0; N];
        a.copy_from_slice(b);
        self.pos += N;
        Ok(a)
    }

    // ---- items, text or binary as the section is

    fn size(&mut self, what: &str) -> Result<u64> {
        if self.in_binary {
            self.bytes::<8>(what).map(u64::from_le_bytes)
        } else {
            self.text(what)
        }
    }

    fn int(&mut self, what: &str) -> Result<i32> {
        if self.in_binary {
            self.bytes::<4>(what).map(i32::from_le_bytes)
        } else {
            self.text(what)
        }
    }

    fn real(&mut self, what: &str) -> Result<f64> {
        if self.in_binary {
            self.bytes::<8>(what).map(f64::from_le_bytes)
        } else {
            self.text(what)
        }
    }

    /// A count or index as usize, refusing what does not fit.
    fn count(&mut self, what: &str) -> Result<usize> {
        let n = self.size(what)?;
        usize::try_from(n).map_err(|_| self.bad(format!("{what} {n} is too large")))
    }

    /// An MSH 2.2 tag or count: an int in binary files, text otherwise;
    /// negative ones are refused.
    fn int_count(&mut self, what: &str) -> Result<usize> {
        let n: i64 = if self.in_binary {
            self.int(what)? as i64
        } else {
            self.text(what)?
        };
        usize::try_from(n).map_err(|_| self.bad(format!("{what} {n} is negative")))
    }

    /// Starts the payload of a section that is binary in binary files.
    fn begin_payload(&mut self) -> Result<()> {
        if self.binary {
            self.end_line()?;
            self.in_binary = true;
        }
        Ok(())
    }

    fn end_payload(&mut self, name: &str) -> Result<()> {
        self.in_binary = false;
        self.context.clear();
        self.expect_end(name)
    }

    // ---- sections

    fn parse(mut self) -> Result<MshMesh> {
        match self.token() {
            Some(b"$MeshFormat") => self.mesh_format()?,
            Some(b"$NOD") | Some(b"$NOE") => {
                return Err(self.bad("MSH 1.0 is not supported: re-save as MSH 4.1 or 2.2"))
            }
            Some(t) => {
                return Err(self.bad(format!(
                    "not a gmsh .msh file: expected $MeshFormat, found {}",
                    shown(t)
                )))
            }
            None => return Err(self.truncated("$MeshFormat")),
        }
        while let Some(token) = self.token() {
            self.section = match token {
                b"$PhysicalNames" => "$PhysicalNames",
                b"$Entities" => "$Entities",
                b"$Nodes" => "$Nodes",
                b"$Elements" => "$Elements",
                b"$NodeData" => "$NodeData",
                _ => "the file",
            };
            match token {
                b"$PhysicalNames" => self.physical_names_section()?,
                b"$Entities" if self.version == Version::V41 => self.entities()?,
                b"$Nodes" => match self.version {
                    Version::V41 => self.nodes_41()?,
                    Version::V2 => self.nodes_2()?,
                },
                b"$Elements" => match self.version {
                    Version::V41 => self.elements_41()?,
                    Version::V2 => self.elements_2()?,
                },
                b"$NodeData" => self.node_data_section()?,
                b"$MeshFormat" => return Err(self.bad("a second $MeshFormat section")),
                _ if token.starts_with(b"$End") => {
                    return Err(self.bad(format!("{} closes no open section", shown(token))))
                }
                _ if token.starts_with(b"$") => self.skip_section(&token[1..])?,
                _ => {
                    return Err(self.bad(format!(
                        "expected a section keyword such as $Nodes, found {}",
                        shown(token)
                    )))
                }
            }
            self.section = "the file";
        }
        self.resolve()
    }

    fn mesh_format(&mut self) -> Result<()> {
        self.section = "$MeshFormat";
        let version: String = self.text("the version number")?;
        self.version_text = version.clone();
        self.version = match version.as_str() {
            "4.1" => Version::V41,
            v if v.starts_with("4") => {
                return Err(self.bad(format!(
                    "MSH {v} is not supported: re-save as MSH 4.1 (gmsh -format msh41) or 2.2"
                )))
            }
            v if v.starts_with("2") => Version::V2,
            v => return Err(self.bad(format!("MSH version {v} is not supported (4.1 or 2.2)"))),
        };
        let file_type: i32 = self.text("the file type (0 ASCII, 1 binary)")?;
        if !(0..=1).contains(&file_type) {
            return Err(self.bad(format!(
                "file type {file_type}: must be 0 (ASCII) or 1 (binary)"
            )));
        }
        let data_size: i32 = self.text("the data size")?;
        if data_size != 8 {
            return Err(self.bad(format!("data size {data_size}: only 8 is supported")));
        }
        if file_type == 1 {
            self.end_line()?;
            self.binary = true;
            let one = i32::from_le_bytes(self.bytes::<4>("the binary one")?);
            if one != 1 {
                return Err(self.bad(if one.swap_bytes() == 1 {
                    "a big-endian binary file: re-save it as ASCII or on a little-endian host"
                        .to_string()
                } else {
                    format!("the binary one marker reads {one}")
                }));
            }
        }
        self.expect_end("MeshFormat")
    }

    fn physical_names_section(&mut self) -> Result<()> {
        let n: usize = self.text("the number of physical names")?;
        self.physical_names
            .reserve(super::capacity(n, self.remaining(), 6));
        for _ in 0..n {
            let dim: i32 = self.text("a physical dimension")?;
            let tag: i32 = self.text("a physical tag")?;
            let name = self.string_line("a physical name")?;
            self.physical_names.push(MshPhysicalName { dim, tag, name });
        }
        self.expect_end("PhysicalNames")
    }

    fn entities(&mut self) -> Result<()> {
        self.begin_payload()?;
        let mut counts = [0usize; 4];
        for (c, what) in counts.iter_mut().zip([
            "the number of points",
            "the number of curves",
            "the number of surfaces",
            "the number of volumes",
        ]) {
            *c = self.count(what)?;
        }
        for (dim, &n) in counts.iter().enumerate() {
            for j in 0..n {
                self.context = format!("entity {j} of dimension {dim}");
                let tag = self.int("an entity tag")?;
                let reals = if dim == 0 { 3 } else { 6 };
                for _ in 0..reals {
                    self.real("a bounding-box coordinate")?;
                }
                let nphys = self.count("the number of physical tags")?;
                let mut first = 0;
                for k in 0..nphys {
                    let p = self.int("a physical tag")?;
                    if k == 0 {
                        first = p;
                    }
                }
                self.entity_physical.insert((dim as i32, tag), first);
                if dim > 0 {
                    let nbound = self.count("the number of bounding entities")?;
                    for _ in 0..nbound {
                        self.int("a bounding entity tag")?;
                    }
                }
            }
        }
        self.end_payload("Entities")
    }

    fn nodes_41(&mut self) -> Result<()> {
        self.begin_payload()?;
        let blocks = self.count("the number of entity blocks")?;
        let total = self.count("the number of nodes")?;
        self.count("the smallest node tag")?;
        self.count("the largest node tag")?;
        let first = self.nodes.len();
        self.nodes.reserve(super::capacity(
            total,
            self.remaining(),
            if self.binary { 32 } else { 8 },
        ));
        let mut tags = Vec::new();
        for b in 0..blocks {
            self.context = format!("block {b} of {blocks}");
            let dim = self.int("an entity dimension")?;
            let entity = self.int("an entity tag")?;
            let parametric = self.int("the parametric flag")?;
            let n = self.count("the number of nodes in the block")?;
            if !(0..=3).contains(&dim) {
                return Err(self.bad(format!("entity dimension {dim}")));
            }
            self.context = format!("block {b} of {blocks}, entity ({dim}, {entity}), {n} nodes");
            let extra = if parametric != 0 { dim as usize } else { 0 };
            tags.clear();
            tags.reserve(super::capacity(n, self.remaining(), 2));
            for _ in 0..n {
                let tag = self.size("a node tag")?;
                tags.push((tag, self.place()));
            }
            for &(tag, place) in &tags {
                let mut xyz = [0.0; 3];
                for c in &mut xyz {
                    *c = self.real("a node coordinate")?;
                }
                for _ in 0..extra {
                    self.real("a parametric coordinate")?;
                }
                self.nodes.push(RawNode {
                    tag,
                    xyz: DVec3::from_array(xyz),
                    place,
                });
            }
        }
        let read = self.nodes.len() - first;
        if read != total {
            return Err(self.bad(format!(
                "the header announces {total} nodes, the blocks hold {read}"
            )));
        }
        self.end_payload("Nodes")
    }

    fn nodes_2(&mut self) -> Result<()> {
        let n: usize = self.text("the number of nodes")?;
        self.begin_payload()?;
        self.nodes.reserve(super::capacity(
            n,
            self.remaining(),
            if self.binary { 28 } else { 8 },
        ));
        self.context = format!("{n} nodes");
        for _ in 0..n {
            let tag = self.int_count("a node tag")? as u64;
            let place = self.place();
            let mut xyz = [0.0; 3];
            for c in &mut xyz {
                *c = self.real("a node coordinate")?;
            }
            self.nodes.push(RawNode {
                tag,
                xyz: DVec3::from_array(xyz),
                place,
            });
        }
        self.end_payload("Nodes")
    }

    /// Reads one element's node tags (its tag and entity already read).
    fn element(
        &mut self,
        tag: u64,
        ty: i32,
        entity: (i32, i32),
        physical: i32,
        place: usize,
    ) -> Result<()> {
        let Some(n) = type_nodes(ty) else {
            // Text files have one element per line: skip the rest of it.
            if self.in_binary {
                return Err(self.bad(format!(
                    "element {tag} has type {ty}, whose node count is unknown: \
                     a binary file cannot be read past it"
                )));
            }
            self.rest_of_line();
            self.skipped += 1;
            return Ok(());
        };
        let kind = kind_of(ty);
        let first = self.element_nodes.len();
        for _ in 0..n {
            let t = if self.version == Version::V2 {
                self.int_count("a node tag")? as u64
            } else {
                self.size("a node tag")?
            };
            if kind != Kind::Other {
                self.element_nodes.push(t);
            }
        }
        if kind == Kind::Other {
            self.skipped += 1;
        } else {
            self.elements.push(RawElement {
                tag,
                kind,
                entity,
                physical,
                first,
                count: n,
                place,
            });
        }
        Ok(())
    }

    fn elements_41(&mut self) -> Result<()> {
        self.begin_payload()?;
        let blocks = self.count("the number of entity blocks")?;
        let total = self.count("the number of elements")?;
        self.count("the smallest element tag")?;
        self.count("the largest element tag")?;
        let mut read = 0usize;
        for b in 0..blocks {
            self.context = format!("block {b} of {blocks}");
            let dim = self.int("an entity dimension")?;
            let entity = self.int("an entity tag")?;
            let ty = self.int("an element type")?;
            let n = self.count("the number of elements in the block")?;
            self.context = format!(
                "block {b} of {blocks}, entity ({dim}, {entity}), {n} elements of type {ty}"
            );
            for _ in 0..n {
                let tag = self.size("an element tag")?;
                let place = self.place();
                self.element(tag, ty, (dim, entity), 0, place)?;
            }
            read += n;
        }
        if read != total {
            return Err(self.bad(format!(
                "the header announces {total} elements, the blocks hold {read}"
            )));
        }
        self.end_payload("Elements")
    }

    fn elements_2(&mut self) -> Result<()> {
        let total: usize = self.text("the number of elements")?;
        self.begin_payload()?;
        self.context = format!("{total} elements");
        let mut tags = Vec::new();
        let mut read = 0;
        while read < total {
            // Binary files group elements under (type, count, tags) headers;
            // text files give them per element.
            let (ty, count, ntags) = if self.in_binary {
                let ty = self.int("an element type")?;
                let count = self.int_count("an element count")?;
                let ntags = self.int_count("a number of tags")?;
                if count == 0 || count > total - read {
                    return Err(self.bad(format!(
                        "a block of {count} elements, but {} remain of the {total} announced",
                        total - read
                    )));
                }
                (ty, count, ntags)
            } else {
                (0, 1, 0)
            };
            for _ in 0..count {
                let tag = self.int_count("an element tag")? as u64;
                let place = self.place();
                let (ty, ntags) = if self.in_binary {
                    (ty, ntags)
                } else {
                    let ty = self.text("an element type")?;
                    (ty, self.int_count("a number of tags")?)
                };
                tags.clear();
                for _ in 0..ntags {
                    let t: i64 = if self.in_binary {
                        self.int("a tag")? as i64
                    } else {
                        self.text("a tag")?
                    };
                    tags.push(t.clamp(i32::MIN as i64, i32::MAX as i64) as i32);
                }
                let physical = tags.first().copied().unwrap_or(0);
                let entity = tags.get(1).copied().unwrap_or(0);
                self.element(tag, ty, (-1, entity), physical, place)?;
            }
            read += count;
        }
        self.end_payload("Elements")
    }

    fn node_data_section(&mut self) -> Result<()> {
        let nstrings: usize = self.text("the number of string tags")?;
        let mut name = String::new();
        for k in 0..nstrings {
            let s = self.string_line("a string tag")?;
            if k == 0 {
                name = s;
            }
        }
        let nreals: usize = self.text("the number of real tags")?;
        let mut time = 0.0;
        for k in 0..nreals {
            let r: f64 = self.text("a real tag")?;
            if k == 0 {
                time = r;
            }
        }
        let nints: usize = self.text("the number of integer tags")?;
        let mut ints = Vec::with_capacity(nints.min(8));
        for _ in 0..nints {
            ints.push(self.text::<i64>("an integer tag")?);
            // Only the first few mean anything; bound what we keep.
            ints.truncate(8);
        }
        let &[time_step, components, n, ..] = ints.as_slice() else {
            return Err(self.bad(format!(
                "view {name:?} has {nints} integer tags; time step, components and count are needed"
            )));
        };
        let components = usize::try_from(components)
            .ok()
            .filter(|&c| (1..=1000).contains(&c))
            .ok_or_else(|| self.bad(format!("view {name:?}: {components} components")))?;
        let n = usize::try_from(n).map_err(|_| self.bad(format!("view {name:?}: {n} values")))?;
        self.begin_payload()?;
        self.context = format!("view {name:?}, {n} nodes of {components} values");
        let per = if self.binary {
            4 + 8 * components
        } else {
            2 * components + 2
        };
        let mut view = RawNodeData {
            name,
            time,
            time_step,
            components,
            tags: Vec::with_capacity(super::capacity(n, self.remaining(), per)),
            values: Vec::with_capacity(super::capacity(n * components, self.remaining(), per)),
        };
        for _ in 0..n {
            // The node tag of a view entry is an int in binary, even in 4.1.
            let tag = if self.in_binary {
                self.int_count("a node tag")? as u64
            } else {
                self.text("a node tag")?
            };
            view.tags.push((tag, self.place()));
            for _ in 0..components {
                view.values.push(self.real("a value")?);
            }
        }
        self.node_data.push(view);
        self.end_payload("NodeData")
    }

    // ---- tags to indices

    fn resolve(self) -> Result<MshMesh> {
        let n = self.nodes.len();
        if n > u32::MAX as usize {
            return Err(self.error_at(self.place(), format!("{n} nodes: at most 2^32 - 1")));
        }
        let mut order: Vec<u32> = (0..n as u32).collect();
        order.sort_by_key(|&i| (self.nodes[i as usize].tag, i));
        for w in order.windows(2) {
            let (a, b) = (&self.nodes[w[0] as usize], &self.nodes[w[1] as usize]);
            if a.tag == b.tag {
                let first = if self.binary { "byte" } else { "line" };
                return Err(self.error_at(
                    b.place,
                    format!(
                        "node tag {} is defined twice (first at {first} {})",
                        b.tag, a.place
                    ),
                ));
            }
        }
        let node_tags: Vec<u64> = order.iter().map(|&i| self.nodes[i as usize].tag).collect();
        let nodes: Vec<DVec3> = order.iter().map(|&i| self.nodes[i as usize].xyz).collect();
        // Tags 1..=n (gmsh's usual numbering) map without a search.
        let dense = node_tags
            .iter()
            .enumerate()
            .all(|(i, &t)| t == i as u64 + 1);
        let index = |tag: u64| -> Option<u32> {
            if dense {
                (tag >= 1 && tag <= n as u64).then(|| tag as u32 - 1)
            } else {
                node_tags.binary_search(&tag).ok().map(|i| i as u32)
            }
        };

        let mut mesh = MshMesh {
            version: self.version_text.clone(),
            binary: self.binary,
            skipped_elements: self.skipped,
            physical_names: self.physical_names.clone(),
            ..Default::default()
        };
        for e in &self.elements {
            let mut element = MshElement {
                tag: e.tag,
                order: match e.kind {
                    Kind::Triangle(k) | Kind::Line(k) => k,
                    _ => 0,
                },
                nodes: Vec::with_capacity(e.count),
                physical: e.physical,
                entity: e.entity.1,
                line: (!self.binary).then_some(e.place),
            };
            if self.version == Version::V41 {
                element.physical = self.entity_physical.get(&e.entity).copied().unwrap_or(0);
            }
            for &t in &self.element_nodes[e.first..e.first + e.count] {
                let i = index(t).ok_or_else(|| {
                    self.error_at(
                        e.place,
                        format!(
                            "element {} refers to node tag {t}, which no $Nodes section defines",
                            e.tag
                        ),
                    )
                })?;
                element.nodes.push(i);
            }
            match e.kind {
                Kind::Triangle(_) => mesh.triangles.push(element),
                Kind::Line(_) => mesh.lines.push(element),
                _ => mesh.points.push(element),
            }
        }
        for view in &self.node_data {
            let mut nodes = Vec::with_capacity(view.tags.len());
            for &(t, place) in &view.tags {
                let i = index(t).ok_or_else(|| {
                    self.error_at(
                        place,
                        format!(
                            "view {:?} gives a value for node tag {t}, which no $Nodes section defines",
                            view.name
                        ),
                    )
                })?;
                nodes.push(i);
            }
            mesh.node_data.push(MshNodeData {
                name: view.name.clone(),
                time: view.time,
                time_step: view.time_step,
                components: view.components,
                nodes,
                values: view.values.clone(),
            });
        }
        mesh.nodes = nodes;
        mesh.node_tags = node_tags;
        Ok(mesh)
    }
}

/// Elements in tag order (stable, so equal tags keep file order).
fn by_tag(elements: &[MshElement]) -> Vec<&MshElement> {
    let mut sorted: Vec<&MshElement> = elements.iter().collect();
    sorted.sort_by_key(|e| e.tag);
    sorted
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::io::nodes_per_triangle;
    use std::path::PathBuf;

    /// A scratch file name unique to this process and test (tests remove
    /// their files).
    pub(crate) fn scratch(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("loopsurf-io-{}-{name}", std::process::id()))
    }

    /// The node layouts gmsh documents for its Lagrange triangles
    /// (reference manual, "Node ordering", the Triangle6 / Triangle10 /
    /// Triangle15 pictures): node m of the order-k triangle sits at
    /// (u, v) = (i/k, j/k). Vertices, then edges 0→1, 1→2, 2→0 each from
    /// its first vertex, then the interior numbered like a triangle.
    pub(crate) fn documented_lattice(k: usize) -> &'static [(usize, usize)] {
        match k {
            1 => &[(0, 0), (1, 0), (0, 1)],
            2 => &[(0, 0), (2, 0), (0, 2), (1, 0), (1, 1), (0, 1)],
            3 => &[
                (0, 0),
                (3, 0),
                (0, 3),
                (1, 0),
                (2, 0),
                (2, 1),
                (1, 2),
                (0, 2),
                (0, 1),
                (1, 1),
            ],
            4 => &[
                (0, 0),
                (4, 0),
                (0, 4),
                (1, 0),
                (2, 0),
                (3, 0),
                (3, 1),
                (2, 2),
                (1, 3),
                (0, 3),
                (0, 2),
                (0, 1),
                (1, 1),
                (2, 1),
                (1, 2),
            ],
            _ => unreachable!(),
        }
    }

    /// An order-k mesh of the unit square cut into 2 × 2 squares and 8
    /// triangles, slightly curved, with edge nodes shared, two faces (ids
    /// 0 and 3), lines on two sides (curves 2 and 0), three corners listed
    /// out of node order, awkward doubles (−0.0, a subnormal, thirds) and
    /// an unused node at the end.
    pub(crate) fn fixture(k: usize) -> LagrangeMesh {
        let mut mesh = LagrangeMesh {
            order: k,
            ..Default::default()
        };
        let n = 2 * k as i64; // lattice points per side − 1
        let mut index: HashMap<(i64, i64), u32> = HashMap::new();
        let mut node = |mesh: &mut LagrangeMesh, p: (i64, i64)| -> u32 {
            *index.entry(p).or_insert_with(|| {
                let (x, y) = (p.0 as f64 / n as f64, p.1 as f64 / n as f64);
                let z = if p == (0, 0) {
                    -0.0
                } else if p == (n, n) {
                    1e-310
                } else {
                    (3.0 * x * y).sin() / 3.0
                };
                mesh.nodes.push(DVec3::new(x, y, z));
                let i = mesh.nodes.len() as u32 - 1;
                mesh.params.push((i % 5, x / 3.0, y * std::f64::consts::PI));
                i
            })
        };
        let lattice = documented_lattice(k);
        for sx in 0..2 {
            for sy in 0..2 {
                let o = (sx * k as i64, sy * k as i64);
                let kk = k as i64;
                let corners = [[(0, 0), (kk, 0), (kk, kk)], [(0, 0), (kk, kk), (0, kk)]];
                for c in corners {
                    let [a, b, d] = c.map(|(x, y)| (o.0 + x, o.1 + y));
                    for &(i, j) in lattice {
                        let (i, j) = (i as i64, j as i64);
                        // a + (b − a) i/k + (d − a) j/k on the integer lattice.
                        let p = (
                            a.0 + ((b.0 - a.0) * i + (d.0 - a.0) * j) / kk,
                            a.1 + ((b.1 - a.1) * i + (d.1 - a.1) * j) / kk,
                        );
                        let id = node(&mut mesh, p);
                        mesh.triangles.push(id);
                    }
                    mesh.faces.push(if sx == 0 { 0 } else { 3 });
                }
            }
        }
        // Bottom side (curve 2) and left side (curve 0), ends first.
        for (curve, from, step) in [(2, (0, 0), (1, 0)), (0, (0, 2 * k as i64), (0, -1))] {
            for s in 0..2i64 {
                let at = |m: i64| {
                    let t = s * k as i64 + m;
                    (from.0 + step.0 * t, from.1 + step.1 * t)
                };
                let mut ids = vec![node(&mut mesh, at(0)), node(&mut mesh, at(k as i64))];
                ids.extend((1..k as i64).map(|m| node(&mut mesh, at(m))));
                mesh.lines.extend(ids);
                mesh.line_curves.push(curve);
            }
        }
        for (p, id) in [((n, 0), 0), ((0, 0), 1), ((0, n), 2)] {
            let i = node(&mut mesh, p);
            mesh.corners.push((i, id));
        }
        mesh.nodes.push(DVec3::new(2.0, 1.0 / 3.0, -1e300));
        mesh.params.push((7, 0.25, 0.5));
        mesh.validate().unwrap();
        mesh
    }

    /// Same mesh, and every double the same bits.
    pub(crate) fn assert_identical(a: &LagrangeMesh, b: &LagrangeMesh) {
        assert_eq!(a, b);
        for (p, q) in a.nodes.iter().zip(&b.nodes) {
            assert_eq!(
                p.to_array().map(f64::to_bits),
                q.to_array().map(f64::to_bits)
            );
        }
        for (p, q) in a.params.iter().zip(&b.params) {
            assert_eq!(
                (p.1.to_bits(), p.2.to_bits()),
                (q.1.to_bits(), q.2.to_bits())
            );
        }
    }

    #[test]
    fn round_trip_every_order_ascii_and_binary() {
        for k in 1..=4 {
            let mesh = fixture(k);
            for binary in [false, true] {
                let path = scratch(&format!("rt{k}{binary}.msh"));
                write_msh(&path, &mesh, binary).unwrap();
                let read = read_msh(&path).unwrap();
                assert_eq!((read.version.as_str(), read.binary), ("4.1", binary));
                let tags: Vec<u64> = (1..=mesh.nodes.len() as u64).collect();
                assert_eq!(read.node_tags, tags);
                assert_eq!(read.triangles.len(), 8);
                assert!(read.triangles.iter().all(|e| e.order == k));
                assert_eq!(read.lines.len(), 4);
                assert_eq!(read.points.len(), 3);
                assert_eq!(read.skipped_elements, 0);
                assert_eq!(read.triangles[0].line.is_some(), !binary);
                // Physical groups and names as documented.
                let mut names: Vec<_> = read
                    .physical_names
                    .iter()
                    .map(|p| (p.dim, p.tag, p.name.as_str()))
                    .collect();
                names.sort();
                assert_eq!(
                    names,
                    [
                        (0, 1, "corner_0"),
                        (0, 2, "corner_1"),
                        (0, 3, "corner_2"),
                        (1, 1, "curve_0"),
                        (1, 3, "curve_2"),
                        (2, 1, "face_0"),
                        (2, 4, "face_3"),
                    ]
                );
                assert!(read
                    .triangles
                    .iter()
                    .all(|e| e.physical == e.entity && [1, 4].contains(&e.physical)));
                assert_eq!(read.node_data.len(), 1);
                assert_eq!(read.node_data[0].name, PARAMS_VIEW);
                assert_identical(&read.to_lagrange().unwrap(), &mesh);
                std::fs::remove_file(&path).unwrap();
            }
        }
    }

    /// Without params there is no view; a mesh with nothing but nodes
    /// still makes a file gmsh's format allows.
    #[test]
    fn round_trip_without_params_and_elements() {
        let mut mesh = fixture(2);
        mesh.params.clear();
        let only_nodes = LagrangeMesh {
            order: 1,
            nodes: vec![DVec3::X, DVec3::Y],
            ..Default::default()
        };
        for (m, name) in [(&mesh, "noparams"), (&only_nodes, "onlynodes")] {
            for binary in [false, true] {
                let path = scratch(&format!("{name}{binary}.msh"));
                write_msh(&path, m, binary).unwrap();
                let read = read_msh(&path).unwrap();
                assert!(read.node_data.is_empty());
                assert_identical(&read.to_lagrange().unwrap(), m);
                std::fs::remove_file(&path).unwrap();
            }
        }
        let mut bad = mesh.clone();
        bad.order = 3;
        let err = write_msh(&scratch("bad.msh"), &bad, false).unwrap_err();
        assert!(err.to_string().contains("order 3 needs 10"), "{err}");
    }

    /// The written P1–P4 elements of the straight reference triangle put
    /// node m where gmsh's manual draws it (see [`documented_lattice`]),
    /// e.g. P3: node 3 at (1/3, 0), 5 at (2/3, 1/3), 9 at (1/3, 1/3).
    #[test]
    fn reference_triangle_node_layout() {
        let documented_p3 = [
            (0.0, 0.0),
            (1.0, 0.0),
            (0.0, 1.0),
            (1.0 / 3.0, 0.0),
            (2.0 / 3.0, 0.0),
            (2.0 / 3.0, 1.0 / 3.0),
            (1.0 / 3.0, 2.0 / 3.0),
            (0.0, 2.0 / 3.0),
            (0.0, 1.0 / 3.0),
            (1.0 / 3.0, 1.0 / 3.0),
        ];
        for (m, &(i, j)) in documented_lattice(3).iter().enumerate() {
            assert_eq!((i as f64 / 3.0, j as f64 / 3.0), documented_p3[m]);
        }
        for k in 1..=4 {
            let lattice = documented_lattice(k);
            assert_eq!(lattice.len(), nodes_per_triangle(k));
            // Nodes stored in reverse, so the element's indices are not
            // simply 0, 1, 2, ...
            let npt = lattice.len();
            let mesh = LagrangeMesh {
                order: k,
                nodes: lattice
                    .iter()
                    .rev()
                    .map(|&(i, j)| DVec3::new(i as f64 / k as f64, j as f64 / k as f64, 0.0))
                    .collect(),
                triangles: (0..npt as u32).rev().collect(),
                faces: vec![0],
                ..Default::default()
            };
            for binary in [false, true] {
                let path = scratch(&format!("ref{k}{binary}.msh"));
                write_msh(&path, &mesh, binary).unwrap();
                let read = read_msh(&path).unwrap();
                let tri = &read.triangles[0];
                assert_eq!(tri.order, k);
                for (m, &(i, j)) in lattice.iter().enumerate() {
                    let p = read.nodes[tri.nodes[m] as usize];
                    assert_eq!((p.x, p.y), (i as f64 / k as f64, j as f64 / k as f64));
                }
            }
            // The ASCII element line itself: type, then tag and node tags.
            let text = std::fs::read_to_string(scratch(&format!("ref{k}false.msh"))).unwrap();
            let ty = TRIANGLE_TYPES[k - 1];
            assert!(text.contains(&format!("\n2 1 {ty} 1\n1 ")), "{text}");
            for binary in [false, true] {
                std::fs::remove_file(scratch(&format!("ref{k}{binary}.msh"))).unwrap();
            }
        }
    }

    /// What gmsh 4.15 writes for a P2 triangle with a physical curve and
    /// point, with a `$Periodic` and an `$ElementData` section added.
    const GMSH_41: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 4 "bottom"
2 7 "skin"
$EndPhysicalNames
$Entities
3 3 1 0
1 0 0 0 0 
2 1 0 0 1 9 
3 0 1 0 0 
1 0 0 0 1 0 0 1 4 2 1 -2 
2 0 0 0 1 1 0 0 2 2 -3 
3 0 0 0 0 1 0 0 2 3 -1 
1 0 0 0 1 1 0 1 7 3 1 2 3 
$EndEntities
$Nodes
7 6 1 6
0 1 0 1
1
0 0 0
0 2 0 1
2
1 0 0
0 3 0 1
3
0 1 0
1 1 0 1
4
0.4999999999986718 0 0
1 2 0 1
5
0.5000000000013293 0.4999999999986707 0
1 3 0 1
6
0 0.5000000000013304 0
2 1 0 0
$EndNodes
$Elements
4 4 1 4
0 2 15 1
1 2 
1 1 8 1
2 1 2 4 
2 1 9 1
3 1 2 3 4 5 6 
2 1 3 1
4 1 2 5 6
$EndElements
$Periodic
1
1 3 1
16 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1
1
3 1
$EndPeriodic
$ElementData
1
"quality"
1
0
3
0
1
1
3 0.5
$EndElementData
"#;

    #[test]
    fn reads_what_gmsh_writes_41() {
        let path = Path::new("gmsh41.msh");
        let m = parse_msh(GMSH_41.as_bytes(), path).unwrap();
        assert_eq!(m.version, "4.1");
        assert_eq!(m.nodes.len(), 6);
        assert_eq!(m.nodes[3], DVec3::new(0.4999999999986718, 0.0, 0.0));
        assert_eq!(m.skipped_elements, 1); // the quad
        assert_eq!(m.triangles.len(), 1);
        let t = &m.triangles[0];
        assert_eq!((t.tag, t.order, t.physical, t.entity), (3, 2, 7, 1));
        assert_eq!(t.nodes, [0, 1, 2, 3, 4, 5]);
        assert_eq!(t.line, Some(48));
        let l = &m.lines[0];
        assert_eq!(
            (l.order, l.physical, l.nodes.as_slice()),
            (2, 4, &[0, 1, 3][..])
        );
        assert_eq!((m.points[0].physical, m.points[0].nodes[0]), (9, 1));
        assert_eq!(m.physical_names[1].name, "skin");
        let lag = m.to_lagrange().unwrap();
        assert_eq!((lag.order, lag.faces.as_slice()), (2, &[6][..]));
        assert_eq!(lag.line_curves, [3]);
        assert_eq!(lag.corners, [(1, 8)]);
        assert!(lag.params.is_empty());
    }

    /// The same mesh as gmsh 4.15 writes it in MSH 2.2, with a `$Periodic`
    /// section, a quad, node tags out of order and a view.
    const GMSH_22: &str = r#"$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 4 "bottom"
2 7 "skin"
$EndPhysicalNames
$Nodes
6
1 0 0 0
2 1 0 0
3 0 1 0
5 0.5000000000013293 0.4999999999986707 0
4 0.4999999999986718 0 0
60 0 0.5000000000013304 0
$EndNodes
$Periodic
1
1 3 1
1
3 1
$EndPeriodic
$Elements
4
1 15 2 9 2 2
2 8 2 4 1 1 2 4
3 9 2 7 1 1 2 3 4 5 60
4 3 2 0 1 1 2 5 60
$EndElements
$NodeData
1
"loopsurf_params"
1
0.0
3
0
3
6
1 0 0 0
2 0 1 0
3 0 0 1
4 0 0.5 0
5 0 0.5 0.5
60 0 0 0.5
$EndNodeData
"#;

    #[test]
    fn reads_what_gmsh_writes_22() {
        let m = parse_msh(GMSH_22.as_bytes(), Path::new("gmsh22.msh")).unwrap();
        assert_eq!(m.version, "2.2");
        assert_eq!(m.node_tags, [1, 2, 3, 4, 5, 60]);
        assert_eq!(
            m.nodes[4],
            DVec3::new(0.5000000000013293, 0.4999999999986707, 0.0)
        );
        let t = &m.triangles[0];
        assert_eq!((t.order, t.physical, t.entity), (2, 7, 1));
        assert_eq!(t.nodes, [0, 1, 2, 3, 4, 5]);
        assert_eq!(m.skipped_elements, 1);
        let lag = m.to_lagrange().unwrap();
        assert_eq!(lag.corners, [(1, 8)]);
        assert_eq!(lag.params[4], (0, 0.5, 0.5));
        assert_eq!(lag.params[5], (0, 0.0, 0.5));
    }

    /// MSH 2.2 binary as the manual describes it: int node tags, element
    /// blocks under (type, count, number of tags) headers.
    #[test]
    fn reads_binary_22() {
        let mut f = b"$MeshFormat\n2.2 1 8\n".to_vec();
        f.extend(1i32.to_le_bytes());
        f.extend(b"\n$EndMeshFormat\n$Nodes\n3\n");
        for (tag, p) in [
            (1i32, [0.0, 0.0, 0.0]),
            (2, [1.0, 0.0, 0.0]),
            (3, [0.0, 1.0, -0.0]),
        ] {
            f.extend(tag.to_le_bytes());
            for x in p {
                f.extend(f64::to_le_bytes(x));
            }
        }
        f.extend(b"\n$EndNodes\n$Elements\n2\n");
        // (type, count, number of tags), then per element its tag, tags
        // (physical, elementary) and nodes.
        for x in [15i32, 1, 2, 1, 5, 4, 1] {
            f.extend(x.to_le_bytes());
        }
        for x in [2i32, 1, 2, 2, 8, 6, 1, 3, 2] {
            f.extend(x.to_le_bytes());
        }
        f.extend(b"\n$EndElements\n");
        let m = parse_msh(&f, Path::new("b22.msh")).unwrap();
        assert!(m.binary);
        assert_eq!(m.nodes[2].z.to_bits(), (-0.0f64).to_bits());
        assert_eq!(m.points[0].physical, 5);
        let t = &m.triangles[0];
        assert_eq!(
            (t.tag, t.physical, t.entity, t.nodes.as_slice()),
            (2, 8, 6, &[0, 2, 1][..])
        );
    }

    fn err_of(data: &[u8]) -> String {
        parse_msh(data, Path::new("bad.msh"))
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn errors_name_line_or_byte() {
        // Truncated: every prefix of a good file fails cleanly or reads.
        let path = scratch("trunc.msh");
        for binary in [false, true] {
            write_msh(&path, &fixture(2), binary).unwrap();
            let data = std::fs::read(&path).unwrap();
            for cut in 0..data.len() {
                let _ = parse_msh(&data[..cut], &path);
            }
            let err = parse_msh(&data[..data.len() / 2], &path).unwrap_err();
            assert!(matches!(err.root(), Error::Truncated { .. }), "{err}");
            let msg = err.to_string();
            assert!(msg.contains("trunc.msh"), "{msg}");
            if binary {
                assert!(msg.contains("at byte"), "{msg}");
            } else {
                assert!(msg.contains("trunc.msh:"), "{msg}");
            }
        }
        let ascii = |body: &str| format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n{body}");

        // A huge announced count and a short file: a clear error at once.
        let huge =
            ascii("$Nodes\n1 999999999999999 1 999999999999999\n2 1 0 999999999999999\n1\n2\n");
        let msg = err_of(huge.as_bytes());
        assert!(msg.contains("bad.msh:8: truncated file: $Nodes"), "{msg}");
        assert!(msg.contains("999999999999999 nodes"), "{msg}");

        // An element naming a node no block defines.
        let undefined = ascii(
            "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n\
             $Elements\n1 1 1 1\n2 1 2 1\n17 1 2 99\n$EndElements\n",
        );
        let msg = err_of(undefined.as_bytes());
        assert!(msg.contains("bad.msh:17:"), "{msg}");
        assert!(msg.contains("element 17 refers to node tag 99"), "{msg}");

        // Counts that disagree with the blocks, bad numbers, repeated tags.
        let miscount = ascii("$Nodes\n1 4 1 3\n2 1 0 1\n1\n0 0 0\n$EndNodes\n");
        assert!(err_of(miscount.as_bytes()).contains("announces 4 nodes, the blocks hold 1"));
        let extra = ascii("$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0 0 7\n$EndNodes\n");
        assert!(err_of(extra.as_bytes()).contains("expected $EndNodes, found \"7\""));
        let word = ascii("$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 zero 0\n$EndNodes\n");
        let msg = err_of(word.as_bytes());
        assert!(
            msg.contains(":8:") && msg.contains("found \"zero\""),
            "{msg}"
        );
        let twice = ascii("$Nodes\n1 2 1 1\n2 1 0 2\n1\n1\n0 0 0\n0 0 0\n$EndNodes\n");
        let msg = err_of(twice.as_bytes());
        assert!(
            msg.contains("node tag 1 is defined twice (first at line 7)"),
            "{msg}"
        );
        assert!(err_of(b"solid x\n").contains("not a gmsh .msh file"));
        assert!(err_of(b"$MeshFormat\n4 0 8\n$EndMeshFormat\n").contains("re-save"));
        assert!(err_of(b"").contains("truncated"));

        // Binary: a patched count and a patched node tag, named by offset.
        write_msh(&path, &fixture(1), true).unwrap();
        let good = std::fs::read(&path).unwrap();
        let nodes = good.windows(7).position(|w| w == b"$Nodes\n").unwrap() + 7;
        let mut data = good.clone();
        // The first block's node count (after 4 size_t and 3 ints).
        let at = nodes + 32 + 12;
        data[at..at + 8].copy_from_slice(&(u64::MAX / 4).to_le_bytes());
        let msg = parse_msh(&data, &path).unwrap_err().to_string();
        assert!(msg.contains("the file ends at byte"), "{msg}");
        let elements = good.windows(10).position(|w| w == b"$Elements\n").unwrap() + 10;
        let mut data = good.clone();
        // The first element's node tag (after 4 size_t, 3 ints, a size_t
        // and the element tag).
        let at = elements + 32 + 12 + 8 + 8;
        data[at..at + 8].copy_from_slice(&12345u64.to_le_bytes());
        let msg = parse_msh(&data, &path).unwrap_err().to_string();
        assert!(
            msg.contains(&format!(
                "byte {}: element 1 refers to node tag 12345",
                at - 8
            )),
            "{msg}"
        );
        std::fs::remove_file(&path).unwrap();
    }

    /// Damaged files (bytes flipped all over a good one) end in a result
    /// or an error, never a panic.
    #[test]
    fn damaged_files_do_not_panic() {
        let path = scratch("damaged.msh");
        for binary in [false, true] {
            write_msh(&path, &fixture(3), binary).unwrap();
            let good = std::fs::read(&path).unwrap();
            let mut state = 0x9e3779b97f4a7c15u64;
            for _ in 0..300 {
                let mut data = good.clone();
                for _ in 0..4 {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    let at = (state % data.len() as u64) as usize;
                    data[at] = (state >> 32) as u8;
                }
                if let Ok(m) = parse_msh(&data, &path) {
                    let _ = m.to_lagrange();
                }
            }
        }
        std::fs::remove_file(&path).unwrap();
    }
}
