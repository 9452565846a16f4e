//! The sections of a `.msh` file, read through the [`Parser`] cursor, and
//! the final step from node tags to dense indices.

use glam::DVec3;

use super::parser::{shown, Parser, RawElement, RawNode, RawNodeData, Version};
use super::{kind_of, type_nodes, Kind, MshElement, MshMesh, MshNodeData, MshPhysicalName};
use crate::error::Result;

impl Parser<'_> {
    pub(super) fn parse(mut self) -> Result<MshMesh> {
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
            .reserve(crate::io::capacity(n, self.remaining(), 6));
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
        self.nodes.reserve(crate::io::capacity(
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
            tags.reserve(crate::io::capacity(n, self.remaining(), 2));
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
        self.nodes.reserve(crate::io::capacity(
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
            tags: Vec::with_capacity(crate::io::capacity(n, self.remaining(), per)),
            values: Vec::with_capacity(crate::io::capacity(n * components, self.remaining(), per)),
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

    /// The mesh with every node tag turned into a node index: nodes in
    /// tag order, elements and views referring to them.
    fn resolve(self) -> Result<MshMesh> {
        let order = self.nodes_by_tag()?;
        let node_tags: Vec<u64> = order.iter().map(|&i| self.nodes[i as usize].tag).collect();
        let nodes: Vec<DVec3> = order.iter().map(|&i| self.nodes[i as usize].xyz).collect();
        let index = NodeIndex::new(node_tags);
        let mut mesh = MshMesh {
            version: self.version_text.clone(),
            binary: self.binary,
            skipped_elements: self.skipped,
            physical_names: self.physical_names.clone(),
            ..Default::default()
        };
        for e in &self.elements {
            let element = self.resolve_element(e, &index)?;
            match e.kind {
                Kind::Triangle(_) => mesh.triangles.push(element),
                Kind::Line(_) => mesh.lines.push(element),
                _ => mesh.points.push(element),
            }
        }
        for view in &self.node_data {
            mesh.node_data.push(self.resolve_view(view, &index)?);
        }
        mesh.nodes = nodes;
        mesh.node_tags = index.tags;
        Ok(mesh)
    }

    /// The nodes' indices in the order of their tags; a tag defined twice
    /// is an error.
    fn nodes_by_tag(&self) -> Result<Vec<u32>> {
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
        Ok(order)
    }

    /// An element with its node tags turned into indices.
    fn resolve_element(&self, e: &RawElement, index: &NodeIndex) -> Result<MshElement> {
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
            let i = index.of(t).ok_or_else(|| {
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
        Ok(element)
    }

    /// A view with its node tags turned into indices.
    fn resolve_view(&self, view: &RawNodeData, index: &NodeIndex) -> Result<MshNodeData> {
        let mut nodes = Vec::with_capacity(view.tags.len());
        for &(t, place) in &view.tags {
            let i = index.of(t).ok_or_else(|| {
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
        Ok(MshNodeData {
            name: view.name.clone(),
            time: view.time,
            time_step: view.time_step,
            components: view.components,
            nodes,
            values: view.values.clone(),
        })
    }
}

/// Node tags, sorted, to node indices.
struct NodeIndex {
    tags: Vec<u64>,
    /// Tags 1..=n (gmsh's usual numbering) map without a search.
    dense: bool,
}

impl NodeIndex {
    fn new(tags: Vec<u64>) -> NodeIndex {
        let dense = tags.iter().enumerate().all(|(i, &t)| t == i as u64 + 1);
        NodeIndex { tags, dense }
    }

    /// The index of node `tag`, if some node has it.
    fn of(&self, tag: u64) -> Option<u32> {
        if self.dense {
            let n = self.tags.len();
            (tag >= 1 && tag <= n as u64).then(|| tag as u32 - 1)
        } else {
            self.tags.binary_search(&tag).ok().map(|i| i as u32)
        }
    }
}
