//! Explicit repairs of dirty triangulations, between reading a file and
//! validating it as a control net.
//!
//! Legacy files are often almost valid: an STL whose corners were written
//! with round-off, a mesh whose triangles were shuffled without regard to
//! orientation, two surfaces touching at a vertex. Each repair here is
//! asked for by name ([`Repairs`]), changes only what it must, and records
//! every change as a [`Repair`] that the caller shows to the user: nothing
//! changes silently. The order is fixed: weld (which may drop triangles),
//! orient, split non-manifold vertices. Zero-area triangles are not
//! repaired but accepted ([`Repairs::allow_degenerate`]): to Loop
//! subdivision they are harmless; only their normals, and so the dihedral
//! angles of their edges, are undefined, and `tag_by_angle` never tags
//! those edges (see `crate::geometry::is_degenerate`).
//!
//! Vertex indices stay those of the file: welded vertices stay in the list,
//! unreferenced, and split copies are appended. Triangles keep their order;
//! only welding can remove some, and says which.

use crate::error::{Error, Result};
use crate::io::{MeshData, ParseOptions};

mod orient;
mod split;
mod weld;

/// Which repairs to apply. The default applies none.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Repairs {
    /// Merge each vertex into the first earlier vertex within this distance,
    /// as a fraction of the bounding-box diagonal; drop the triangles this
    /// collapses or duplicates.
    pub weld: Option<f64>,
    /// Make the orientation consistent within each connected piece.
    pub orient: bool,
    /// Give a vertex where separate fans of triangles meet one copy per fan.
    pub split_nonmanifold: bool,
    /// Accept zero-area triangles (with a report) instead of refusing them.
    pub allow_degenerate: bool,
}

/// The weld distance `--repair` uses when no `--weld` is given, relative to
/// the diagonal: well above single-precision round-off in STL files (about
/// 1e-7 of the coordinates), well below any feature of a real model.
pub const DEFAULT_WELD: f64 = 1e-6;

impl Repairs {
    /// Every repair, welding at [`DEFAULT_WELD`].
    pub fn all() -> Repairs {
        Repairs {
            weld: Some(DEFAULT_WELD),
            orient: true,
            split_nonmanifold: true,
            allow_degenerate: true,
        }
    }

    /// Whether any repair is asked for.
    pub fn any(&self) -> bool {
        *self != Repairs::default()
    }
}

/// How to read a file into a control net ([`crate::ControlNet::read_with`]):
/// how to parse it, then which repairs to apply before validation. It
/// lives here, above [`crate::io`], because the parsers know nothing of
/// repairs.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ReadOptions {
    /// Split polygons into triangles ([`ParseOptions::triangulate`]).
    pub triangulate: bool,
    /// Repairs of the triangulation read, applied before validation.
    pub repairs: Repairs,
}

impl ReadOptions {
    /// Everything `--repair` turns on: split polygons and every repair.
    pub fn repair_all() -> ReadOptions {
        ReadOptions {
            triangulate: true,
            repairs: Repairs::all(),
        }
    }

    /// What the parser is asked to do.
    pub fn parse_options(&self) -> ParseOptions {
        ParseOptions {
            triangulate: self.triangulate,
        }
    }
}

/// One change a repair made, in words a user can act on (its `Display`).
#[derive(Debug, Clone, PartialEq)]
pub enum Repair {
    /// Vertices merged into an earlier one within `distance` (absolute).
    Welded { merged: usize, distance: f64 },
    /// Triangles removed after welding, as indices in the input order:
    /// those with two corners merged, and copies of an earlier triangle.
    DroppedTriangles {
        collapsed: Vec<usize>,
        duplicates: Vec<usize>,
    },
    /// A connected piece (numbered by its first triangle) whose triangles
    /// were turned so that all agree; `outward` when the piece is closed and
    /// the kept orientation is the one with positive volume.
    Reoriented {
        first_triangle: usize,
        triangles: usize,
        flipped: usize,
        outward: bool,
    },
    /// Non-manifold vertices, each given a new copy (appended) for every
    /// fan after its first: (vertex, its copies).
    SplitVertices { splits: Vec<(u32, Vec<u32>)> },
    /// Zero-area triangles kept as they are.
    KeptDegenerate { triangles: Vec<usize> },
}

impl std::fmt::Display for Repair {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Repair::Welded { merged, distance } => write!(
                f,
                "weld: merged {merged} vertices into an earlier vertex within {distance:.3e}; \
                 they stay in the vertex list, unreferenced"
            ),
            Repair::DroppedTriangles {
                collapsed,
                duplicates,
            } => write!(
                f,
                "weld: dropped {} triangles that lost a corner ({}) and {} copies of an \
                 earlier triangle ({}); later triangles move up",
                collapsed.len(),
                list(collapsed),
                duplicates.len(),
                list(duplicates)
            ),
            Repair::Reoriented {
                first_triangle,
                triangles,
                flipped,
                outward,
            } => write!(
                f,
                "orient: flipped {flipped} of the {triangles} triangles of the piece of triangle \
                 {first_triangle}{}",
                if *outward {
                    " (closed: now facing outward)"
                } else {
                    " (open: the majority's orientation kept)"
                }
            ),
            Repair::SplitVertices { splits } => {
                let each: Vec<String> = splits
                    .iter()
                    .map(|(v, copies)| format!("{v} → {}", list(copies)))
                    .collect();
                write!(
                    f,
                    "split-nonmanifold: gave {} vertices where separate fans touch a copy per \
                     extra fan ({})",
                    splits.len(),
                    list(&each)
                )
            }
            Repair::KeptDegenerate { triangles } => write!(
                f,
                "degenerate: kept {} zero-area triangles ({}); their edges are never tagged by \
                 angle",
                triangles.len(),
                list(triangles)
            ),
        }
    }
}

/// Up to ten items, then how many more.
fn list<T: std::fmt::Display>(items: &[T]) -> String {
    let mut s: Vec<String> = items.iter().take(10).map(T::to_string).collect();
    if items.len() > 10 {
        s.push(format!("and {} more", items.len() - 10));
    }
    if s.is_empty() {
        "none".into()
    } else {
        s.join(", ")
    }
}

/// Applies the topological repairs of `repairs` to a reader's output, in
/// order, and returns what changed. Zero-area triangles are left to
/// validation, which accepts them under [`Repairs::allow_degenerate`].
pub fn apply(mesh: &mut MeshData, repairs: &Repairs) -> Result<Vec<Repair>> {
    let mut report = Vec::new();
    if let Some(eps) = repairs.weld {
        if !(eps > 0.0 && eps < 0.1) {
            return Err(Error::InvalidArgument(format!(
                "weld distance {eps}: must be above 0 and below 0.1 of the diagonal"
            )));
        }
        report.extend(weld::weld(mesh, eps));
    }
    if repairs.orient {
        report.extend(orient::orient(mesh)?);
    }
    if repairs.split_nonmanifold {
        report.extend(split::split_nonmanifold(mesh));
    }
    Ok(report)
}

/// The triangles sharing each undirected edge, as a list sorted by edge:
/// ([a, b] with a < b, triangle). Triangles with an index out of range or a
/// repeated corner are skipped: validation reports them.
fn edge_incidences(mesh: &MeshData) -> Vec<([u32; 2], u32)> {
    let n = mesh.points.len() as i64;
    let mut out = Vec::with_capacity(3 * mesh.tris.len());
    for (t, tri) in mesh.tris.iter().enumerate() {
        if tri.iter().any(|&i| i < 0 || i >= n)
            || tri[0] == tri[1]
            || tri[1] == tri[2]
            || tri[0] == tri[2]
        {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tri[k] as u32, tri[(k + 1) % 3] as u32);
            out.push(([a.min(b), a.max(b)], t as u32));
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reports_name_what_changed() {
        let r = Repair::Reoriented {
            first_triangle: 7,
            triangles: 20,
            flipped: 3,
            outward: true,
        };
        assert_eq!(
            r.to_string(),
            "orient: flipped 3 of the 20 triangles of the piece of triangle 7 (closed: now facing outward)"
        );
        let d = Repair::KeptDegenerate {
            triangles: (0..12).collect(),
        };
        assert!(d
            .to_string()
            .contains("12 zero-area triangles (0, 1, 2, 3, 4, 5, 6, 7, 8, 9, and 2 more)"));
    }

    #[test]
    fn weld_distance_is_checked() {
        let mut mesh = MeshData::default();
        for eps in [0.0, -1.0, 0.5, f64::NAN] {
            let repairs = Repairs {
                weld: Some(eps),
                ..Repairs::default()
            };
            assert!(matches!(
                apply(&mut mesh, &repairs),
                Err(Error::InvalidArgument(_))
            ));
        }
    }
}
