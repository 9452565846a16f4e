//! gmsh `.msh` files: high-order (Lagrange) triangle surface meshes out, in
//! MSH 4.1 ASCII or binary, and in again from MSH 4.1 (ASCII, binary) or
//! 2.2 (ASCII, binary), which is what gmsh, meshio and most FE codes read
//! and write.
//!
//! What we write, following the format as gmsh documents it ("MSH file
//! format") and as gmsh 4.15 itself writes it:
//! - physical groups name the model: surface `face + 1` "`face_<id>`",
//!   curve `curve + 1` "`curve_<id>`", point `corner + 1` "`corner_<id>`";
//! - `$Entities` has one point entity per corner, one curve entity per
//!   curve id and one surface entity per face id, each with its physical
//!   group and a real bounding box (bounding-entity lists are empty: gmsh
//!   reads the file as a discrete model either way);
//! - every node sits on the lowest-dimensional entity it belongs to
//!   (corner, else the curve of the first line through it, else the face
//!   of the first triangle using it), so gmsh's own classification agrees;
//!   node tags are index + 1 (or, for a piece of a mesh shared out among
//!   ranks, the tags [`MshTags`] gives), and the nodes are written in index order,
//!   one block per run of consecutive nodes on one entity (gmsh merges the
//!   blocks of an entity): readers that ignore tags and take nodes and
//!   `$NodeData` values by position (meshio, which also insists on tags
//!   1..n in binary views) still pair every value with its node;
//! - element tags are consecutive from 1 (or from [`MshTags`]' first): the
//!   corners' point elements, then the
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
//!
//! The writer is in `write`; the reader is the [`MshMesh`] it returns
//! (`read`), a cursor over text tokens and binary items (`parser`) and the
//! readers of the sections (`sections`).

mod parser;
mod read;
mod sections;
#[cfg(test)]
pub(super) mod tests;
mod write;

pub use read::{parse_msh, read_msh, MshElement, MshMesh, MshNodeData, MshPhysicalName};
pub use write::{write_msh, write_msh_tagged, MshTags};

/// The name of the `$NodeData` view holding each node's (triangle, v, w).
pub const PARAMS_VIEW: &str = "loopsurf_params";

/// gmsh's element types of the complete Lagrange triangles of order 1..=4.
const TRIANGLE_TYPES: [i32; 4] = [2, 9, 21, 23];
/// gmsh's element types of the Lagrange lines of order 1..=4.
const LINE_TYPES: [i32; 4] = [1, 8, 26, 27];
/// gmsh's one-node point element.
const POINT_TYPE: i32 = 15;

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
