//! Adaptive Loop subdivision (Liu & Kondo): subdivision stops in
//! flat regions, so the triangle count grows where the shape needs it and
//! not ×4 everywhere.
//!
//! Each level runs Liu & Kondo's NLFC ([`classify`]: flat and dead vertices
//! by the conical angle, or by the distance to the exact limit surface),
//! splits what is alive ([`split`]: conforming by construction) and
//! realigns edges next to dead regions ([`realign`]). Every triangle keeps
//! the control triangle it lies in and its corners' dyadic (v, w) there, so
//! every output vertex knows where it sits on the limit surface.

mod classify;
mod realign;
mod split;

use crate::error::{Error, Result};
use crate::features::Features;
use crate::net::ControlNet;
use crate::parameters::{SurfacePoint, CORNERS};
use crate::snap::snap_near;
use crate::surface::{Surface, SurfaceMode};
use crate::topology::Topology;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// The most levels [`Adapter::levels`] accepts.
pub const MAX_ADAPT_LEVELS: u32 = 10;

/// An adaptive subdivision of a control net; configure it, then
/// [`Adapter::run`]. A vertex is flat when it passes every criterion set:
/// the conical angle, the distance to the limit surface, or both.
#[derive(Clone)]
pub struct Adapter<'a> {
    net: &'a ControlNet,
    levels: u32,
    angle: Option<f64>,
    tolerance: Option<(&'a Surface, f64)>,
    limit: Option<&'a Surface>,
    realign: bool,
    max_triangles: usize,
}

/// Counts after one level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LevelCount {
    pub vertices: usize,
    pub triangles: usize,
    /// Triangles whose three corners are dead: never split again.
    pub dead_triangles: usize,
}

/// The result of [`Adapter::run`].
#[derive(Debug, Clone)]
pub struct AdaptiveMesh {
    /// The refined net: positions, triangles (counter-clockwise like the
    /// input), hard edges and corners.
    pub net: ControlNet,
    /// Per vertex: its control triangle and dyadic (v, w).
    pub params: Vec<SurfacePoint>,
    /// Per vertex: dead (its neighbourhood was flat; no longer refined).
    pub dead: Vec<bool>,
    /// Counts of the input (index 0) and after every level.
    pub counts: Vec<LevelCount>,
}

/// A triangle's control triangle and its corners' (v, w) there.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FaceChart {
    pub tri: u32,
    pub q: [DVec2; 3],
}

/// One level of the hierarchy.
pub(crate) struct Level {
    pub net: ControlNet,
    pub charts: Vec<FaceChart>,
    pub dead: Vec<bool>,
}

/// A level in the making, before realignment and validation.
pub(crate) struct Parts {
    pub points: Vec<DVec3>,
    pub tris: Vec<[u32; 3]>,
    pub charts: Vec<FaceChart>,
    /// Per triangle: made by this level's splits (not a dead one kept).
    pub fresh: Vec<bool>,
    pub dead: Vec<bool>,
    /// Interior hard edges (boundary edges are hard anyway).
    pub hard: Vec<[u32; 2]>,
    pub corners: Vec<u32>,
}

impl Parts {
    /// Builds and validates the net (a failure here is a bug, reported as
    /// the topology error it is rather than a panic).
    fn into_level(self) -> Result<Level> {
        let topo = Topology::new(self.points.len(), self.tris)?;
        let mut features = Features::new(&topo);
        for &[a, b] in &self.hard {
            features.tag_edge(&topo, a, b)?;
        }
        for &v in &self.corners {
            features.tag_vertex(v)?;
        }
        Ok(Level {
            net: ControlNet::from_parts(self.points, topo, features),
            charts: self.charts,
            dead: self.dead,
        })
    }
}

impl<'a> Adapter<'a> {
    /// An adapter of `net`: no levels yet, realignment on.
    pub fn new(net: &'a ControlNet) -> Adapter<'a> {
        Adapter {
            net,
            levels: 0,
            angle: None,
            tolerance: None,
            limit: None,
            realign: true,
            max_triangles: 200_000_000,
        }
    }

    /// Number of subdivision levels (at most [`MAX_ADAPT_LEVELS`]).
    pub fn levels(mut self, levels: u32) -> Self {
        self.levels = levels;
        self
    }

    /// The conical-angle threshold, degrees in [0, 180): a vertex whose
    /// normals spread less is flat. 0 is uniform subdivision. At a vertex
    /// on a hard edge the normals are compared within each smooth sector,
    /// and the limit surface's bending across each triangle of the fan
    /// counts too, so that one-triangle sectors are measured (see
    /// `classify`; nets without hard edges follow Liu & Kondo exactly).
    pub fn angle(mut self, degrees: f64) -> Self {
        self.angle = Some(degrees);
        self
    }

    /// Flat also (or instead) means: the vertex and the midpoints of its
    /// edges are within `relative` × bounding-box diagonal of `surface`
    /// (the limit surface of this net) at their parameters.
    pub fn tolerance(mut self, surface: &'a Surface, relative: f64) -> Self {
        self.tolerance = Some((surface, relative));
        self
    }

    /// The limit surface of this net (`Surface::new` of it), which the
    /// conical angle at hard edges compares the levels with (see
    /// `classify`). Without it, [`Adapter::run`] uses the tolerance's
    /// surface when that is this one, or builds its own when the net has
    /// hard edges (boundaries included) and an angle is set: on nets with
    /// thousands of hard edges that build costs more than the subdivision,
    /// so callers that hold the surface anyway should pass it.
    pub fn limit_surface(mut self, surface: &'a Surface) -> Self {
        self.limit = Some(surface);
        self
    }

    /// Whether to swap edges next to dead regions for better angles (on by
    /// default).
    pub fn realign(mut self, realign: bool) -> Self {
        self.realign = realign;
        self
    }

    /// Refuse to produce more triangles than this (default 200 million).
    pub fn max_triangles(mut self, max: usize) -> Self {
        self.max_triangles = max;
        self
    }

    fn check(&self) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidArgument(m));
        if self.levels > MAX_ADAPT_LEVELS {
            return bad(format!(
                "levels {}: at most {MAX_ADAPT_LEVELS} are supported",
                self.levels
            ));
        }
        match (self.angle, self.tolerance) {
            (None, None) => return bad("no criterion: give a conical angle or a tolerance".into()),
            (Some(a), _) if !(0.0..180.0).contains(&a) => {
                return bad(format!(
                    "angle {a}: must be at least 0 and below 180 degrees"
                ))
            }
            (_, Some((_, t))) if !(t.is_finite() && t > 0.0 && t < 1.0) => {
                return bad(format!(
                    "tolerance {t}: must be a fraction of the diagonal in (0, 1)"
                ))
            }
            (_, Some((surface, _))) if surface.net().triangles() != self.net.triangles() => {
                return bad("the tolerance's surface is not this net's".into())
            }
            _ if self.limit.is_some_and(|s| !is_limit_of(s, self.net)) => {
                return bad(
                    "the limit surface is not this net's (Surface::new of the same net)".into(),
                )
            }
            _ => {}
        }
        Ok(())
    }

    /// Subdivides.
    pub fn run(&self) -> Result<AdaptiveMesh> {
        self.check()?;
        let net = self.net;
        let tolerance = self.tolerance.map(|(s, t)| (s, t * net.bbox_diagonal()));
        // The conical angle at hard edges compares with the limit surface
        // of this net (Loop's, as the levels approach it): the one given,
        // or the tolerance's when it is that one, else one built here, only
        // when needed.
        let own;
        let limit = match (self.angle, self.tolerance) {
            (None, _) => None,
            _ if net.features().num_hard_edges() == 0 => None,
            _ if self.limit.is_some() => self.limit,
            (_, Some((s, _))) if is_limit_of(s, net) => Some(s),
            _ => {
                own = Surface::new(net)?;
                Some(&own)
            }
        };
        let mut level = Level {
            net: net.clone(),
            charts: (0..net.triangles().len() as u32)
                .map(|tri| FaceChart { tri, q: CORNERS })
                .collect(),
            dead: vec![false; net.points().len()],
        };
        let mut counts = vec![count(&level)];
        for _ in 0..self.levels {
            level = self.next_level(&level, limit, tolerance)?;
            counts.push(count(&level));
        }
        Ok(AdaptiveMesh {
            params: vertex_params(&level),
            net: level.net,
            dead: level.dead,
            counts,
        })
    }

    /// One level on: the vertices that die (flat, or dead already), and
    /// the triangles split around the living ones. A level that could go
    /// over the triangle budget is refused first.
    fn next_level(
        &self,
        level: &Level,
        limit: Option<&Surface>,
        tolerance: Option<(&Surface, f64)>,
    ) -> Result<Level> {
        let current = level.net.triangles().len();
        if 4 * current > self.max_triangles {
            return Err(Error::OverBudget {
                needed: (4 * current) as f64,
                limit: self.max_triangles,
                message: format!(
                    "the next level could reach {} triangles, over the limit of {}",
                    4 * current,
                    self.max_triangles
                ),
            });
        }
        let mut flat: Vec<bool> = match self.angle {
            Some(a) => classify::conical_angles(&level.net, &level.charts, &level.dead, limit)?
                .into_iter()
                .map(|ca| ca < a)
                .collect(),
            None => vec![true; level.dead.len()],
        };
        // Under a tolerance a vertex must itself be within it to die
        // (Liu & Kondo ask only its neighbours to be flat), or the
        // frozen dead vertices could stay farther than promised.
        let mut within = vec![true; flat.len()];
        if let Some((surface, tol)) = tolerance {
            let errors = classify::surface_errors(&level.net, &level.charts, surface)?;
            for ((f, w), e) in flat.iter_mut().zip(&mut within).zip(errors) {
                *w = e <= tol;
                *f &= *w;
            }
        }
        for (f, &d) in flat.iter_mut().zip(&level.dead) {
            *f |= d;
        }
        let dead = classify::next_dead(level.net.topology(), &level.dead, &flat, &within);
        let mut parts = split::subdivide(level, &dead);
        if self.realign {
            realign::realign(&mut parts);
        }
        parts.into_level()
    }
}

/// Each vertex of the last level as a point of the original net: a corner
/// of the face chart of a triangle holding it.
fn vertex_params(level: &Level) -> Vec<SurfacePoint> {
    let mut params = vec![
        SurfacePoint {
            tri: 0,
            v: 0.0,
            w: 0.0
        };
        level.net.points().len()
    ];
    for (tri, chart) in level.net.triangles().iter().zip(&level.charts) {
        for k in 0..3 {
            params[tri[k] as usize] = SurfacePoint {
                tri: chart.tri,
                v: chart.q[k].x,
                w: chart.q[k].y,
            };
        }
    }
    params
}

/// Whether `surface` is the Loop limit surface of `net`: approximating,
/// same points, same hard edges and corners (the tolerance asks only for
/// the same triangles).
fn is_limit_of(surface: &Surface, net: &ControlNet) -> bool {
    let other = surface.net();
    let tagged = |n: &ControlNet| -> Vec<bool> {
        (0..n.points().len())
            .map(|v| n.features().is_tagged_vertex(v))
            .collect()
    };
    surface.mode() == SurfaceMode::Approximating
        && other.points() == net.points()
        && other.triangles() == net.triangles()
        && other.hard_edges() == net.hard_edges()
        && tagged(other) == tagged(net)
}

fn count(level: &Level) -> LevelCount {
    let tris = level.net.triangles();
    LevelCount {
        vertices: level.net.points().len(),
        triangles: tris.len(),
        dead_triangles: tris
            .iter()
            .filter(|t| t.iter().all(|&v| level.dead[v as usize]))
            .count(),
    }
}

impl AdaptiveMesh {
    /// The smallest angle of any triangle, degrees.
    pub fn min_angle(&self) -> f64 {
        crate::mesh::min_angle(self.net.points(), self.net.triangles())
    }

    /// Every vertex moved to the limit surface at its parameters (`surface`
    /// must be the input net's).
    pub fn limit_points(&self, surface: &Surface) -> Result<Vec<DVec3>> {
        self.params
            .par_iter()
            .map(|p| surface.point(p.tri as usize, p.v, p.w))
            .collect()
    }

    /// The largest distance of a vertex to the limit surface (global
    /// closest point, started at the vertex's parameters).
    pub fn max_surface_distance(&self, surface: &Surface) -> Result<f64> {
        crate::snap::build_index(surface);
        self.net
            .points()
            .par_iter()
            .zip(&self.params)
            .map(|(&x, p)| Ok(snap_near(surface, x, p.tri as usize, p.v, p.w)?.distance))
            .try_reduce(|| 0.0, |a, b| Ok(a.max(b)))
    }
}
