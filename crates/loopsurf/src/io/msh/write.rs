//! The MSH 4.1 writer, ASCII or binary: entities and node blocks laid out
//! as the module doc of `msh` describes, then every item written as text or
//! as the format's little-endian binary sizes.

use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;
use std::path::Path;

use glam::DVec3;

use super::{LINE_TYPES, PARAMS_VIEW, POINT_TYPE, TRIANGLE_TYPES};
use crate::error::Result;
use crate::io::lagrange::LagrangeMesh;

/// Writes a Lagrange triangle mesh as gmsh MSH 4.1, ASCII or binary; see
/// the module doc for what goes where. The mesh is validated first
/// ([`LagrangeMesh::validate`]).
pub fn write_msh(path: &Path, mesh: &LagrangeMesh, binary: bool) -> Result<()> {
    mesh.validate()?;
    let layout = Layout::new(mesh);
    let mut w = crate::io::create(path)?;
    let mut out = Out {
        w: &mut w,
        binary,
        first: true,
    };
    write_file(&mut out, mesh, &layout).map_err(crate::io::io_error(path))?;
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

        let node_blocks = node_blocks(mesh, &mut surfaces);
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
    surfaces: &mut Vec<Entity>,
) -> Vec<((i32, i32), std::ops::Range<u32>)> {
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
) -> std::io::Result<()> {
    write_format(o)?;
    write_physical_names(o, mesh, layout)?;
    write_entities(o, mesh, layout)?;
    write_nodes(o, mesh, layout)?;
    write_elements(o, mesh, layout)?;
    write_params(o, mesh)
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
) -> std::io::Result<()> {
    let ncorners = mesh.corners.len();
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
    Ok(())
}

/// `$Nodes`: the node blocks of the layout, tags then coordinates.
fn write_nodes<W: Write>(
    o: &mut Out<W>,
    mesh: &LagrangeMesh,
    layout: &Layout,
) -> std::io::Result<()> {
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
    Ok(())
}

/// `$Elements`: a point element per corner, then line blocks per curve
/// and triangle blocks per face, tagged in that order.
fn write_elements<W: Write>(
    o: &mut Out<W>,
    mesh: &LagrangeMesh,
    layout: &Layout,
) -> std::io::Result<()> {
    let k = mesh.order;
    let (npt, npl) = (mesh.nodes_per_triangle(), mesh.nodes_per_line());
    let (ncorners, nlines, ntris) = (mesh.corners.len(), mesh.num_lines(), mesh.num_triangles());
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
    Ok(())
}

/// `$NodeData`: the view of every node's surface parameters, if given.
fn write_params<W: Write>(o: &mut Out<W>, mesh: &LagrangeMesh) -> std::io::Result<()> {
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
