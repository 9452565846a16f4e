//! The evaluator: the control net refined once, so that every triangle has
//! at most one special corner, and per triangle of that level either its
//! regular box-spline stencil or its special corner's cached configuration.

use super::affine::{child_containing, rotation};
use super::special::{Cache, SpecialPatch};
use super::{box_spline, regular};
use crate::net::ControlNet;
use glam::DVec3;
use std::sync::Arc;

/// How one triangle of the once-refined net is evaluated.
// Nearly every patch is regular: storing its coefficients inline keeps an
// evaluation to one memory region, where boxing them would add a pointer chase.
#[allow(clippy::large_enum_variant)]
#[derive(Debug)]
enum Patch {
    /// A box spline, stored as its polynomial coefficients.
    Regular([DVec3; 15]),
    /// Corner `corner` is special; `points` is its neighbourhood.
    Special {
        corner: u8,
        patch: Arc<SpecialPatch>,
        points: Vec<u32>,
    },
}

/// An evaluator of the limit surface of a control net.
pub struct Evaluator {
    fine: ControlNet,
    patches: Vec<Patch>,
    configurations: usize,
}

impl Evaluator {
    pub fn new(net: &ControlNet) -> Evaluator {
        let fine = net
            .refine_uniform(1)
            .expect("one level always fits")
            .into_net();
        let (topo, features) = (fine.topology(), fine.features());
        let kinds = fine.vertex_kinds();
        let mut cache = Cache::default();
        let patches = (0..topo.num_triangles())
            .map(|t| {
                if let Some(s) = regular::stencil(topo, features, &kinds, t) {
                    let control = s.map(|p| p.position(fine.points()));
                    return Patch::Regular(box_spline::coefficients(&control));
                }
                // Child k < 3 of a control triangle has the control vertex
                // at its corner k; the centre child is always regular.
                let corner = t % 4;
                assert!(corner < 3, "centre children are regular");
                let c = topo.triangles()[t];
                let (patch, points) = cache.patch(
                    topo,
                    features,
                    [c[corner], c[(corner + 1) % 3], c[(corner + 2) % 3]],
                );
                Patch::Special {
                    corner: corner as u8,
                    patch,
                    points,
                }
            })
            .collect();
        Evaluator {
            fine,
            patches,
            configurations: cache.len(),
        }
    }

    /// Which kind of patch serves (v, w) of `tri` (for test messages).
    #[cfg(test)]
    pub fn describe(&self, tri: usize, v: f64, w: f64) -> String {
        let (k, _) = child_containing(v, w);
        let t = 4 * tri + k;
        let c = self.fine.triangles()[t];
        let kinds = self.fine.vertex_kinds();
        let what = match &self.patches[t] {
            Patch::Regular(_) => "regular".to_string(),
            Patch::Special { corner, points, .. } => {
                format!("special corner {corner}, neighbourhood {points:?}")
            }
        };
        format!(
            "child {k} {c:?} kinds {:?} valences {:?}: {what}",
            c.map(|x| kinds[x as usize]),
            c.map(|x| self.fine.topology().valence(x as usize))
        )
    }

    /// Number of distinct special-corner configurations built.
    pub fn configurations(&self) -> usize {
        self.configurations
    }

    /// X, Xv, Xw, Xvv, Xvw, Xww at (v, w) of control triangle `tri`, or,
    /// exactly at a special vertex, that vertex (of the refined net) and its
    /// exact limit position: the parametrisation is singular there.
    pub fn eval(&self, tri: usize, v: f64, w: f64) -> Result<[DVec3; 6], AtVertex> {
        let (k, to_child) = child_containing(v, w);
        let t = 4 * tri + k;
        let points = self.fine.points();
        match &self.patches[t] {
            Patch::Regular(coefficients) => {
                let (s, u) = to_child.apply(v, w);
                let d = box_spline::eval_coefficients(coefficients, s, u);
                Ok(to_child.pull_back(d))
            }
            Patch::Special {
                corner,
                patch,
                points: around,
            } => {
                let map = rotation(*corner as usize).after(&to_child);
                let (s, u) = map.apply(v, w);
                if s + u <= 0.0 {
                    return Err(AtVertex {
                        vertex: around[0],
                        limit: patch.limit_point(points, around),
                        normal: patch.normal_at_vertex(points, around),
                    });
                }
                Ok(map.pull_back(patch.eval(points, around, s, u)))
            }
        }
    }
}

/// An evaluation that landed exactly on a special vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtVertex {
    /// The vertex in the once-refined net (control vertices keep their index).
    pub vertex: u32,
    /// Its exact limit position.
    pub limit: DVec3,
    /// The outward unit normal there of the sector the triangle lies in.
    pub normal: DVec3,
}
