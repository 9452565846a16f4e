//! The MSH 4.1 writer, ASCII or binary: entities and node blocks laid out
//! as the module doc of `msh` describes, then every item written as text or
//! as the format's little-endian binary sizes.

use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;
use std::path::Path;

use glam::DVec3;

use super::{LINE_TYPES, PARAMS_VIEW, POINT_TYPE, TRIANGLE_TYPES};
use crate::error::{Error, Result};
use crate::io::lagrange::LagrangeMesh;

/// Writes a Lagrange triangle mesh as gmsh MSH 4.1, ASCII or binary; see
/// the module doc for what goes where. The mesh is validated first
/// ([`LagrangeMesh::validate`]).
pub fn write_msh(path: &Path, mesh: &LagrangeMesh, binary: bool) -> Result<()> {
    write_msh_tagged(path, mesh, binary, MshTags::default())
}

/// The tags a file gives its nodes and elements. By default node i is
/// tag i + 1 and the elements are tagged 1, 2, ... A piece of a mesh
/// shared out among ranks instead tags its nodes with their ids in the
/// whole mesh (plus one) and its elements from an offset of its own, so
/// that the pieces merged on their tags (gmsh merges files that way)
/// share the nodes on their borders and keep every element.
#[derive(Debug, Clone, Copy)]
pub struct MshTags<'a> {
    /// One tag per node, at least 1 and all distinct; `None` for index + 1.
    pub nodes: Option<&'a [u64]>,
    /// The tag of the first element; the others follow it one by one.
    pub first_element: u64,
}

impl Default for MshTags<'_> {
    fn default() -> Self {
        MshTags {
            nodes: None,
            first_element: 1,
        }
    }
}

impl MshTags<'_> {
    /// Node i's tag.
    fn node(&self, i: u32) -> u64 {
        self.nodes.map_or(i as u64 + 1, |t| t[i as usize])
    }

    /// The tag of the point entity of the j-th corner, at `node`: j + 1,
    /// or with node tags given, the node's tag, which names the same
    /// point in every piece.
    fn corner_entity(&self, j: usize, node: u32) -> i32 {
        match self.nodes {
            None => j as i32 + 1,
            Some(t) => t[node as usize] as i32,
        }
    }

    /// Checks the tags against the mesh: one per node, distinct, at least
    /// 1, and small enough for a `$NodeData` view's 32-bit node tags when
    /// the mesh has surface parameters to write in one.
    fn check(&self, mesh: &LagrangeMesh) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidArgument(m));
        if self.first_element == 0 {
            return bad("the first element tag is 0: gmsh's tags start at 1".into());
        }
        let elements = (mesh.corners.len() + mesh.num_lines() + mesh.num_triangles()) as u64;
        if self.first_element.checked_add(elements).is_none() {
            return bad(format!(
                "{elements} elements from tag {} pass the largest tag",
                self.first_element
            ));
        }
        let Some(tags) = self.nodes else {
            return Ok(());
        };
        if tags.len() != mesh.nodes.len() {
            return bad(format!(
                "{} node tags for {} nodes",
                tags.len(),
                mesh.nodes.len()
            ));
        }
        if let Some(i) = tags.iter().position(|&t| t == 0) {
            return bad(format!("node {i}'s tag is 0: gmsh's tags start at 1"));
        }
        // Views and point entities have 32-bit tags.
        let int = i32::MAX as u64;
        let view = !mesh.params.is_empty();
        if let Some(i) = (0..tags.len()).find(|&i| view && tags[i] > int) {
            return bad(format!(
                "node {i}'s tag {} passes {int}, and the $NodeData view of surface parameters has 32-bit node tags",
                tags[i]
            ));
        }
        if let Some(&(node, _)) = mesh.corners.iter().find(|&&(n, _)| tags[n as usize] > int) {
            return bad(format!(
                "corner node {node}'s tag {} passes {int}, and it names a point entity, whose tags are 32-bit",
                tags[node as usize]
            ));
        }
        if let Some((a, b)) = crate::io::repeated(tags) {
            return bad(format!("nodes {a} and {b} have the same tag {}", tags[a]));
        }
        Ok(())
    }
}

/// [`write_msh`] with the node and element tags of `tags`.
pub fn write_msh_tagged(
    path: &Path,
    mesh: &LagrangeMesh,
    binary: bool,
    tags: MshTags,
) -> Result<()> {
    mesh.validate()?;
    tags.check(mesh)?;
    let layout = Layout::new(mesh, &tags);
    let mut w = crate::io::create(path)?;
    let mut out = Out {
        w: &mut w,
        binary,
        first: true,
    };
    write_file(&mut out, mesh, &layout, &tags).map_err(crate::io::io_error(path))?;
    crate::io::finish(w, path)
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
    fn new(mesh: &LagrangeMesh, tags: &MshTags) -> Layout {
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

        let node_blocks = node_blocks(mesh, tags, &mut surfaces);
        Layout {
            curves,
            surfaces,
            node_blocks,
            lines_by_curve,
            tris_by_face,
        }
    }
}

/// Each node on its lowest-dimensional entity (nodes no element uses on a
/// surface of their own, added to `surfaces`), as runs of consecutive
/// node indices.
fn node_blocks(
    mesh: &LagrangeMesh,
    tags: &MshTags,
    surfaces: &mut Vec<Entity>,
) -> Vec<((i32, i32), std::ops::Range<u32>)> {
    // Each node on its lowest-dimensional entity.
    let mut home: Vec<Option<(i32, i32)>> = vec![None; mesh.nodes.len()];
    for (k, &(node, _)) in mesh.corners.iter().enumerate() {
        home[node as usize] = Some((0, tags.corner_entity(k, node)));
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
    node_blocks
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
        crate::io::write_f64(self.w, x)
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

/// The file, section by section.
fn write_file<W: Write>(
    o: &mut Out<W>,
    mesh: &LagrangeMesh,
    layout: &Layout,
    tags: &MshTags,
) -> std::io::Result<()> {
    write_format(o)?;
    write_physical_names(o, mesh, layout)?;
    write_entities(o, mesh, layout, tags)?;
    write_nodes(o, mesh, layout, tags)?;
    write_elements(o, mesh, layout, tags)?;
    write_params(o, mesh, tags)
}

/// `$MeshFormat`: version 4.1, text or binary (with its endianness
/// check, the integer 1).
fn write_format<W: Write>(o: &mut Out<W>) -> std::io::Result<()> {
    o.text("$MeshFormat")?;
    if o.binary {
        o.text("4.1 1 8")?;
        o.w.write_all(&1i32.to_le_bytes())?;
        o.w.write_all(b"\n")?;
    } else {
        o.text("4.1 0 8")?;
    }
    o.text("$EndMeshFormat")?;
    Ok(())
}

/// `$PhysicalNames`: corner_i, curve_i and face_i for the groups used.
fn write_physical_names<W: Write>(
    o: &mut Out<W>,
    mesh: &LagrangeMesh,
    layout: &Layout,
) -> std::io::Result<()> {
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
    Ok(())
}

/// `$Entities`: a point per corner, then the curves and surfaces with
/// their bounds and physical groups.
fn write_entities<W: Write>(
    o: &mut Out<W>,
    mesh: &LagrangeMesh,
    layout: &Layout,
    tags: &MshTags,
) -> std::io::Result<()> {
    let ncorners = mesh.corners.len();
    o.text("$Entities")?;
    o.size(ncorners as u64)?;
    o.size(layout.curves.len() as u64)?;
    o.size(layout.surfaces.len() as u64)?;
    o.size(0)?;
    o.eol()?;
    for (j, &(node, id)) in mesh.corners.iter().enumerate() {
        o.int(tags.corner_entity(j, node))?;
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
    Ok(())
}

/// `$Nodes`: the node blocks of the layout, tags then coordinates.
fn write_nodes<W: Write>(
    o: &mut Out<W>,
    mesh: &LagrangeMesh,
    layout: &Layout,
    tags: &MshTags,
) -> std::io::Result<()> {
    let n = mesh.nodes.len() as u32;
    let (min, max) = (0..n)
        .map(|i| tags.node(i))
        .fold((u64::MAX, 0), |(lo, hi), t| (lo.min(t), hi.max(t)));
    o.text("$Nodes")?;
    o.size(layout.node_blocks.len() as u64)?;
    o.size(n as u64)?;
    o.size(if n == 0 { 0 } else { min })?;
    o.size(max)?;
    o.eol()?;
    for ((dim, tag), nodes) in &layout.node_blocks {
        o.int(*dim)?;
        o.int(*tag)?;
        o.int(0)?;
        o.size(nodes.len() as u64)?;
        o.eol()?;
        for i in nodes.clone() {
            o.size(tags.node(i))?;
            o.eol()?;
        }
        for i in nodes.clone() {
            o.point(mesh.nodes[i as usize])?;
            o.eol()?;
        }
    }
    o.end("Nodes")?;
    Ok(())
}

/// `$Elements`: a point element per corner, then line blocks per curve
/// and triangle blocks per face, tagged in that order.
fn write_elements<W: Write>(
    o: &mut Out<W>,
    mesh: &LagrangeMesh,
    layout: &Layout,
    tags: &MshTags,
) -> std::io::Result<()> {
    let k = mesh.order;
    let (npt, npl) = (mesh.nodes_per_triangle(), mesh.nodes_per_line());
    let (ncorners, nlines, ntris) = (mesh.corners.len(), mesh.num_lines(), mesh.num_triangles());
    let total = (ncorners + nlines + ntris) as u64;
    let blocks = ncorners + layout.lines_by_curve.len() + layout.tris_by_face.len();
    // Element e (corners, lines, then triangles) is tag first + e.
    let first = tags.first_element;
    o.text("$Elements")?;
    o.size(blocks as u64)?;
    o.size(total)?;
    o.size(if total == 0 { 0 } else { first })?;
    o.size(if total == 0 { 0 } else { first + total - 1 })?;
    o.eol()?;
    for (j, &(node, _)) in mesh.corners.iter().enumerate() {
        for x in [0, tags.corner_entity(j, node), POINT_TYPE] {
            o.int(x)?;
        }
        o.size(1)?;
        o.eol()?;
        o.size(first + j as u64)?;
        o.size(tags.node(node))?;
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
                o.size(first + (first_tag + e) as u64)?;
                for &i in &nodes[e * per..(e + 1) * per] {
                    o.size(tags.node(i))?;
                }
                o.eol()?;
            }
        }
    }
    o.end("Elements")?;
    Ok(())
}

/// `$NodeData`: the view of every node's surface parameters, if given.
fn write_params<W: Write>(
    o: &mut Out<W>,
    mesh: &LagrangeMesh,
    tags: &MshTags,
) -> std::io::Result<()> {
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
            // The node tag of a view entry is an int, even in binary 4.1
            // (MshTags::check keeps the tags within it).
            o.int(tags.node(i as u32) as i32)?;
            o.real(tri as f64)?;
            o.real(v)?;
            o.real(w)?;
            o.eol()?;
        }
        o.end("NodeData")?;
    }
    Ok(())
}
