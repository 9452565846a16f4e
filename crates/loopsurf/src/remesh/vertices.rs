//! The remesher's vertices: each is a point of the limit surface given by
//! its parameters, so that wherever a move lands it lands exactly on the
//! surface — the solve that finds the parameters may be approximate, the
//! point they give is not.
//!
//! A vertex is free (inside a model face; it moves on the surface by local
//! projection and stays in its face), on a curve (it moves along the exact
//! crease or boundary curve by curve projection), or a corner (it never
//! moves and is never removed).

use crate::error::Result;
use crate::parameters::{self, vertex_in, SurfacePoint};
use crate::surface::Surface;
use crate::topology::NONE;
use glam::DVec3;
use std::borrow::Cow;

/// Halvings of [`Placer::balanced_on_curve`]'s search: the curve vertex
/// lands within 2⁻²⁰ of its span from the balance point, far below what
/// relaxation needs.
const BISECTIONS: usize = 20;

/// What constrains a vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Kind {
    Free,
    /// On model curve `curve` at parameter t.
    Curve {
        curve: u32,
        t: f64,
    },
    /// A model corner: the control vertex `vertex`.
    Corner {
        vertex: u32,
    },
}

/// One vertex: its point, its surface parameters (`eval` of them is `x`),
/// its constraint, and for a free vertex the surface normal there (the
/// reference a triangle must not turn away from).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Vertex {
    pub x: DVec3,
    pub at: SurfacePoint,
    pub kind: Kind,
    pub normal: DVec3,
}

impl Vertex {
    pub fn is_free(&self) -> bool {
        self.kind == Kind::Free
    }
}

/// The surface and model queries the remesher moves vertices with.
pub(crate) struct Placer<'a> {
    pub surface: &'a Surface,
    /// The face of each control triangle a vertex may land in, [`NONE`]
    /// for one it may not.
    face_of: Cow<'a, [u32]>,
    /// The face each model face is in the mesh's terms, when they differ
    /// (a part's surface has faces of its own, its mesh the whole's).
    face_ids: Option<Vec<u32>>,
}

impl<'a> Placer<'a> {
    pub fn new(surface: &'a Surface) -> Placer<'a> {
        Placer {
            surface,
            face_of: Cow::Borrowed(surface.model().face_of_triangle()),
            face_ids: None,
        }
    }

    /// A placer for a part's sub-net, whose mesh names faces by the
    /// whole's ids (`whole_face` of each local control triangle):
    /// vertices land only in the control triangles `keep` lets through
    /// (those that evaluate as in the whole).
    pub fn within(
        surface: &'a Surface,
        whole_face: &[u32],
        keep: impl Fn(usize) -> bool,
    ) -> Placer<'a> {
        let model_faces = surface.model().face_of_triangle();
        let mut face_ids = vec![NONE; surface.model().faces().len()];
        for (t, &f) in model_faces.iter().enumerate() {
            face_ids[f as usize] = whole_face[t];
        }
        let face_of = (0..model_faces.len())
            .map(|t| if keep(t) { whole_face[t] } else { NONE })
            .collect();
        Placer {
            surface,
            face_of: Cow::Owned(face_of),
            face_ids: Some(face_ids),
        }
    }

    /// Model face `f` in the mesh's terms.
    fn mesh_face(&self, f: u32) -> u32 {
        match &self.face_ids {
            Some(ids) => ids[f as usize],
            None => f,
        }
    }

    /// A free vertex at the surface point nearest `target` locally, found
    /// from `guess`; `None` when that point lies in another face than
    /// `face` (the move would cross a crease) or has no tangent plane.
    pub fn free(&self, target: DVec3, guess: SurfacePoint, face: u32) -> Option<Vertex> {
        let snap = crate::snap::project(self.surface, target, guess.tri as usize, guess.v, guess.w)
            .ok()?;
        if self.face_of[snap.tri] != face || self.on_feature(snap.tri, snap.v, snap.w) {
            return None;
        }
        let normal = self.surface.normal(snap.tri, snap.v, snap.w).ok()?;
        if normal == DVec3::ZERO {
            return None;
        }
        Some(Vertex {
            x: snap.point,
            at: SurfacePoint {
                tri: snap.tri as u32,
                v: snap.v,
                w: snap.w,
            },
            kind: Kind::Free,
            normal,
        })
    }

    /// A free vertex moved towards `target` (a small tangential step) by
    /// one Gauss–Newton step in its own control triangle: two evaluations
    /// instead of a projection's walk, which is what relaxation needs — the
    /// point lands exactly on the surface whatever the step's accuracy.
    /// Falls back to [`Placer::free`] where the step leaves the triangle
    /// or the parametrisation is singular.
    pub fn nudge(&self, v: &Vertex, target: DVec3, face: u32) -> Option<Vertex> {
        let s = self.surface;
        let tri = v.at.tri as usize;
        let quick = || -> Option<Vertex> {
            let e = s.eval(tri, v.at.v, v.at.w).ok()?;
            let step = e.tangent_step(target - e.x)?;
            let (nv, nw) = (v.at.v + step.x, v.at.w + step.y);
            if !(nv > 0.0 && nw > 0.0 && nv + nw < 1.0) {
                return None;
            }
            let f = s.eval(tri, nv, nw).ok()?;
            let normal = f.normal().filter(|_| !f.at_special_vertex)?;
            Some(Vertex {
                x: f.x,
                at: SurfacePoint {
                    tri: v.at.tri,
                    v: nv,
                    w: nw,
                },
                kind: Kind::Free,
                normal,
            })
        };
        quick().or_else(|| self.free(target, v.at, face))
    }

    /// Whether (tri, v, w) lies on a hard control edge or at a vertex with
    /// one (within round-off): a free vertex there would sit on a curve
    /// without being one of its vertices, and make a flat triangle with
    /// the curve's chain (a local projection stops on a crease, clamped).
    fn on_feature(&self, tri: usize, v: f64, w: f64) -> bool {
        let net = self.surface.net();
        let topo = net.topology();
        let features = net.features();
        let weights = SurfacePoint {
            tri: tri as u32,
            v,
            w,
        }
        .weights();
        let zero = weights.map(|x| x.abs() <= 1e-12);
        let corners = net.triangles()[tri];
        (0..3).any(|z| {
            // Side (z + 1, z + 2) is the one without corner z.
            zero[z] && features.is_hard_edge(topo.triangle_edges()[tri][(z + 1) % 3] as usize)
        }) || (0..3).any(|k| {
            zero[(k + 1) % 3]
                && zero[(k + 2) % 3]
                && (features.is_tagged_vertex(corners[k] as usize)
                    || features.hard_neighbours(topo, corners[k] as usize).len() > 0)
        })
    }

    /// A vertex on curve `curve` strictly between parameters t0 and t1 (its
    /// neighbours along the curve), near `target`: the local projection of
    /// `target` from `t` when it stays between them, else (a curve that
    /// turns sharply between them, where the nearest point may lie next to
    /// an end) the parameter midway, whichever is nearer `target`.
    pub fn on_curve(&self, target: DVec3, curve: u32, t: f64, t0: f64, t1: f64) -> Option<Vertex> {
        let mid = self.mid_t(curve, t0, t1);
        let halfway = self.at_curve(curve, mid).ok()?;
        let projected = crate::curve::LimitCurve::new(self.surface, curve as usize)
            .and_then(|c| c.project(target, t))
            .ok()
            .filter(|s| self.between(curve, s.t, t0, t1, mid))
            .and_then(|s| self.at_curve(curve, s.t).ok());
        Some(match projected {
            Some(p) if p.x.distance(target) < halfway.x.distance(target) => p,
            _ => halfway,
        })
    }

    /// The vertex on curve `curve` between its neighbours along it (at
    /// parameters t0 and t1, positions x0 and x1) that is as far from one
    /// as from the other, on the arc through its own t: found by bisection
    /// on the difference of the two distances, which runs from negative at
    /// t0 to positive at t1. Where the curve turns sharply between the
    /// neighbours, this stays at the turn; the projection of their chord's
    /// midpoint would slide down one arm, and a later collapse would cut
    /// the turn off.
    pub fn balanced_on_curve(
        &self,
        curve: u32,
        t: f64,
        [t0, t1]: [f64; 2],
        [x0, x1]: [DVec3; 2],
    ) -> Option<Vertex> {
        let c = &self.surface.model().curves()[curve as usize];
        let n = c.len() as f64;
        let span = if c.is_closed() {
            let forward = (t1 - t0).rem_euclid(n);
            if (t - t0).rem_euclid(n) < forward {
                forward
            } else {
                forward - n
            }
        } else {
            t1 - t0
        };
        let at = |s: f64| {
            let t = t0 + s * span;
            self.at_curve(curve, if c.is_closed() { t.rem_euclid(n) } else { t })
                .ok()
        };
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (lo + hi);
            let x = at(mid)?.x;
            if x.distance(x0) < x.distance(x1) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        at(0.5 * (lo + hi))
    }

    /// The vertex at parameter t of a curve: its surface point on the
    /// curve's first side, and the point evaluated there (so that the
    /// vertex is exactly `eval` of its parameters).
    pub fn at_curve(&self, curve: u32, t: f64) -> Result<Vertex> {
        let sides =
            crate::curve::LimitCurve::new(self.surface, curve as usize)?.surface_points(t)?;
        let at = sides[0].1;
        Ok(Vertex {
            x: self.surface.point(at.tri as usize, at.v, at.w)?,
            at,
            kind: Kind::Curve { curve, t },
            normal: DVec3::ZERO,
        })
    }

    /// The free vertex halfway between a and b in the parameters of a
    /// control triangle of `face` holding both (where the projection of
    /// the 3D midpoint leaves the face, as it may across a sharply folded
    /// crease); `None` when no control triangle holds both.
    pub fn between_in(&self, a: &Vertex, b: &Vertex, face: u32) -> Option<Vertex> {
        let (pa, pb) = (self.guess_in(a, face), self.guess_in(b, face));
        let net = self.surface.net();
        let pb = parameters::reparameterize(net.topology(), pb, pa.tri)?;
        let at = SurfacePoint {
            tri: pa.tri,
            v: 0.5 * (pa.v + pb.v),
            w: 0.5 * (pa.w + pb.w),
        };
        let normal = self.surface.normal(at.tri as usize, at.v, at.w).ok()?;
        Some(Vertex {
            x: self.surface.point(at.tri as usize, at.v, at.w).ok()?,
            at,
            kind: Kind::Free,
            normal,
        })
    }

    /// Parameters of vertex `v` usable as a projection guess in face
    /// `face`: a curve or corner vertex is on several faces' boundaries and
    /// stores one; here it is re-expressed on `face`'s side.
    pub fn guess_in(&self, v: &Vertex, face: u32) -> SurfacePoint {
        match v.kind {
            Kind::Free => v.at,
            Kind::Curve { curve, t } => crate::curve::LimitCurve::new(self.surface, curve as usize)
                .and_then(|c| c.surface_points(t))
                .ok()
                .and_then(|sides| {
                    sides
                        .into_iter()
                        .find(|s| self.mesh_face(s.0) == face)
                        .map(|s| s.1)
                })
                .unwrap_or(v.at),
            Kind::Corner { vertex } => {
                let topo = self.surface.net().topology();
                topo.fan(vertex as usize)
                    .iter()
                    .find(|&&t| self.face_of[t as usize] == face)
                    .map(|&t| vertex_in(topo, t, vertex).unwrap_or(SurfacePoint::corner(t, 0)))
                    .unwrap_or(v.at)
            }
        }
    }

    /// The parameter on `curve` of a vertex known to lie on it: its own t,
    /// or for a corner the end of the curve it is (the end nearer `near`
    /// when the curve starts and ends at that corner).
    pub fn t_on(&self, v: &Vertex, curve: u32, near: Option<f64>) -> Option<f64> {
        match v.kind {
            Kind::Curve { curve: c, t } if c == curve => Some(t),
            Kind::Corner { vertex } => {
                let c = &self.surface.model().curves()[curve as usize];
                let n = c.len() as f64;
                let (first, last) = (c.chain[0], *c.chain.last().expect("a chain"));
                match (first == vertex, last == vertex) {
                    (true, true) => Some(match near {
                        Some(s) if s > 0.5 * n => n,
                        _ => 0.0,
                    }),
                    (true, false) => Some(0.0),
                    (false, true) => Some(n),
                    _ => None,
                }
            }
            _ => None,
        }
    }

    /// Whether t lies strictly between a and b on `curve`, seen from
    /// `from` (around a closed curve, on the arc through `from`).
    pub fn between(&self, curve: u32, t: f64, a: f64, b: f64, from: f64) -> bool {
        let c = &self.surface.model().curves()[curve as usize];
        let n = c.len() as f64;
        let rel = |x: f64| {
            if c.is_closed() {
                let d = (x - from).rem_euclid(n);
                if d > 0.5 * n {
                    d - n
                } else {
                    d
                }
            } else {
                x - from
            }
        };
        let (t, a, b) = (rel(t), rel(a), rel(b));
        a.min(b) < t && t < a.max(b)
    }

    /// The parameter midway between a and b on `curve` (around a closed
    /// curve, the short way).
    pub fn mid_t(&self, curve: u32, a: f64, b: f64) -> f64 {
        let c = &self.surface.model().curves()[curve as usize];
        let n = c.len() as f64;
        if c.is_closed() && (a - b).abs() > 0.5 * n {
            (0.5 * (a + b + n)).rem_euclid(n)
        } else {
            0.5 * (a + b)
        }
    }

    /// The corner vertex of control vertex `vertex`, placed at its limit.
    pub fn corner(&self, vertex: u32, at: SurfacePoint) -> Result<Vertex> {
        Ok(Vertex {
            x: self.surface.point(at.tri as usize, at.v, at.w)?,
            at,
            kind: Kind::Corner { vertex },
            normal: DVec3::ZERO,
        })
    }
}
