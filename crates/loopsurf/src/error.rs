//! One error type for the whole library.
//!
//! Every variant carries enough context to find the problem: the element
//! (triangle or vertex index) and the offending indices or values. Errors
//! found while reading a file are wrapped in [`Error::InFile`], which adds the
//! file name and, for text formats, the line the element came from.
//! [`Error::root`] strips that wrapper so callers (and tests) can match on the
//! kind.

use std::path::PathBuf;

/// The result type used throughout loopsurf.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in loopsurf.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The operating system refused to read or write a file.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// The file extension names no format loopsurf knows.
    #[error("{}: unknown mesh format (expected .off, .obj, .ply, .stl or .tri; .vtu for output)", path.display())]
    UnknownFormat { path: PathBuf },
    /// A line or record that does not parse.
    #[error("line {line}: {message}")]
    Malformed { line: usize, message: String },
    /// The file ends before the data its header announced.
    #[error("truncated file: {message}")]
    Truncated { message: String },
    /// A face with more than three vertices where only triangles are accepted.
    #[error("face {face} has {corners} vertices; only triangles are accepted (--triangulate, LS_LOAD_TRIANGULATE in C, splits polygons)")]
    Polygon { face: usize, corners: usize },
    /// No vertices or no triangles.
    #[error("empty mesh: {nverts} vertices, {ntris} triangles")]
    EmptyMesh { nverts: usize, ntris: usize },
    /// A triangle refers to a vertex that does not exist.
    #[error(
        "triangle {tri} {verts:?} refers to vertex {index}, but there are only {nverts} vertices"
    )]
    IndexOutOfRange {
        tri: usize,
        verts: [i64; 3],
        index: i64,
        nverts: usize,
    },
    /// A triangle uses the same vertex twice.
    #[error(
        "triangle {tri} {verts:?} repeats vertex {index} (--weld, LS_LOAD_WELD in C, drops it)"
    )]
    RepeatedIndex {
        tri: usize,
        verts: [u32; 3],
        index: u32,
    },
    /// A triangle whose corners are collinear (to round-off).
    #[error("triangle {tri} {verts:?} has zero area (--allow-degenerate, LS_LOAD_ALLOW_DEGENERATE in C, keeps it)")]
    ZeroArea { tri: usize, verts: [u32; 3] },
    /// A coordinate that is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate {coords:?}")]
    NonFiniteCoordinate { vertex: usize, coords: [f64; 3] },
    /// An edge shared by three or more triangles.
    #[error("non-manifold edge ({a}, {b}): shared by triangles {tris:?}")]
    NonManifoldEdge { a: u32, b: u32, tris: Vec<u32> },
    /// A vertex where two or more fans of triangles touch at a single point.
    #[error("non-manifold vertex {vertex}: its {ntris} triangles form {fans} separate fans (--split-nonmanifold, LS_LOAD_SPLIT_NONMANIFOLD in C, splits it)")]
    NonManifoldVertex {
        vertex: u32,
        ntris: usize,
        fans: usize,
    },
    /// An interior vertex with only two neighbours: two triangles on the same
    /// three corners, which no tangent plane or Loop rule makes sense of.
    #[error("interior vertex {vertex} has only two neighbours (triangles {tris:?} share all three corners)")]
    InteriorValenceTwo { vertex: u32, tris: Vec<u32> },
    /// Two neighbouring triangles traverse their shared edge in the same direction.
    #[error(
        "inconsistently oriented neighbours: triangles {tris:?} both traverse edge {a} -> {b} (--orient, LS_LOAD_ORIENT in C, repairs it)"
    )]
    InconsistentOrientation { a: u32, b: u32, tris: [u32; 2] },
    /// A connected piece that no choice of triangle orientations makes
    /// consistent (a Möbius band), found by `--orient`.
    #[error("the piece of triangle {first_triangle} is not orientable: triangle {tri} closes a twisted loop")]
    NonOrientable { tri: usize, first_triangle: usize },
    /// An evaluation point that is not a point of its triangle: NaN, or
    /// outside beyond round-off (v < 0, w < 0 or v + w > 1).
    #[error("point (v, w) = ({v}, {w}) of triangle {tri}: {reason}")]
    BadParameter {
        tri: usize,
        v: f64,
        w: f64,
        reason: &'static str,
    },
    /// A query that needs a tangent plane where the surface has none that
    /// loopsurf can give exactly yet (a corner, or exactly at a crease, dart
    /// or corner vertex).
    #[error("no tangent plane at vertex {vertex} ({kind} vertex) of the refined net")]
    NoTangentPlane { vertex: u32, kind: &'static str },
    /// A surface or part stream ([`crate::stream::from_bytes`],
    /// [`crate::stream::part_from_bytes`]) that is truncated, damaged, of
    /// another format version, or describes an invalid net; `what` says
    /// which ("surface" or "part").
    #[error("{what} stream: {message}")]
    Stream { what: &'static str, message: String },
    /// A caller-supplied argument that makes no sense (unknown edge, bad level count, ...).
    #[error("{0}")]
    InvalidArgument(String),
    /// A request whose output would pass its triangle budget, refused
    /// before the memory is spent: `needed` is the estimate, `limit` the
    /// budget, and the message says what to loosen.
    #[error("{message}")]
    OverBudget {
        needed: f64,
        limit: usize,
        message: String,
    },
    /// A fitted surface that misses its tolerance: the input vertex
    /// farthest from it and the distance, both relative to the diagonal.
    #[error("the fitted surface misses the tolerance {tolerance:.1e} (of the diagonal) by {:.1}×: input vertex {vertex} is {distance:.2e} from it; a smaller --resolution gives the fit more control points", distance / tolerance)]
    FitTolerance {
        vertex: usize,
        distance: f64,
        tolerance: f64,
    },
    /// An error met while doing a larger task, which `context` names; its
    /// kind is the source's ([`Error::root`] strips this wrapper).
    #[error("{context}: {source}")]
    During {
        context: String,
        #[source]
        source: Box<Error>,
    },
    /// An error found in a file: names the file and, where known, the line.
    #[error("{}{}: {source}", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
    InFile {
        path: PathBuf,
        line: Option<usize>,
        #[source]
        source: Box<Error>,
    },
}

impl Error {
    /// The error with any [`Error::InFile`] and [`Error::During`] wrappers
    /// removed: the kind of problem.
    pub fn root(&self) -> &Error {
        match self {
            Error::InFile { source, .. } | Error::During { source, .. } => source.root(),
            other => other,
        }
    }

    /// Wraps the error with the file it was found in (and the line, if known).
    pub fn in_file(self, path: impl Into<PathBuf>, line: Option<usize>) -> Error {
        match self {
            // Already located: keep the more precise inner location.
            Error::InFile { .. } | Error::Io { .. } | Error::UnknownFormat { .. } => self,
            other => Error::InFile {
                path: path.into(),
                line,
                source: Box::new(other),
            },
        }
    }

    /// The same error, said to have happened while doing `context`; its
    /// kind stays the same.
    pub fn during(self, context: impl Into<String>) -> Error {
        Error::During {
            context: context.into(),
            source: Box::new(self),
        }
    }

    /// The triangle or vertex an error names, so a reader can map it to a line.
    pub fn element(&self) -> Option<Element> {
        match self.root() {
            Error::IndexOutOfRange { tri, .. }
            | Error::RepeatedIndex { tri, .. }
            | Error::ZeroArea { tri, .. }
            | Error::NonOrientable { tri, .. } => Some(Element::Triangle(*tri)),
            Error::NonFiniteCoordinate { vertex, .. } => Some(Element::Vertex(*vertex)),
            // The last triangle named is the one that broke the rule.
            Error::NonManifoldEdge { tris, .. } => {
                tris.last().map(|&t| Element::Triangle(t as usize))
            }
            Error::InconsistentOrientation { tris, .. } => {
                Some(Element::Triangle(tris[1] as usize))
            }
            Error::InteriorValenceTwo { tris, .. } => {
                tris.last().map(|&t| Element::Triangle(t as usize))
            }
            Error::NonManifoldVertex { vertex, .. } => Some(Element::Vertex(*vertex as usize)),
            _ => None,
        }
    }
}

/// A mesh element an error refers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    Vertex(usize),
    Triangle(usize),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wrapped error keeps its kind, and says both where and what.
    #[test]
    fn during_keeps_the_kind() {
        let inner = Error::OverBudget {
            needed: 2e6,
            limit: 1000,
            message: "the requested density needs about 2e6 triangles".into(),
        };
        let err = inner.during("the start mesh").in_file("a.off", Some(3));
        assert!(matches!(err.root(), Error::OverBudget { limit: 1000, .. }));
        assert_eq!(
            err.to_string(),
            "a.off:3: the start mesh: the requested density needs about 2e6 triangles"
        );
    }
}
