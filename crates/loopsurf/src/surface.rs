//! The limit surface as a CAD kernel sees it: points, derivatives, normals
//! and curvature at any (triangle, v, w), exactly and in constant time.
//!
//! Parameterisation (docs/design.md): triangle t = (c0, c1, c2) of the control
//! net, weights (1 − v − w, v, w); derivatives are with respect to v and w.
//! A built surface is immutable, `Send` and `Sync`.

use crate::error::{Error, Result};
use crate::eval::surface::{AtVertex, ChartEvaluator, Evaluator};
use crate::eval::surface_normal;
use crate::net::ControlNet;
use crate::parameters::{clamp_to_triangle, CORNERS};
use crate::partition::Part;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::any::TypeId;

/// How far outside its triangle a point may lie and still be accepted (then
/// clamped): round-off, not extrapolation.
pub const PARAMETER_TOLERANCE: f64 = 1e-12;

/// The limit surface of a control net.
pub struct Surface {
    net: ControlNet,
    evaluator: Evaluator,
    mode: SurfaceMode,
    /// Displacement mode only: original point minus limit point, per vertex.
    displacement: Vec<DVec3>,
    /// What layers above build from the surface on first use, one slot
    /// per kind (the snap index on the first snap, an index of whole
    /// patches on the first chord-error check, the curves' lengths on the
    /// first length asked), so users who only evaluate never pay for
    /// them. A slot is claimed for its kind first and filled after, so
    /// that building one kind never waits on the building of another.
    derived: [DerivedSlot; DERIVED_KINDS],
    /// Corners, curves and faces, traced on first use.
    model: std::sync::OnceLock<crate::model::Model>,
}

/// How many kinds of [`Derived`] data a surface can hold.
const DERIVED_KINDS: usize = 3;

/// One kind of [`Derived`] data: the type it was claimed for, and the data
/// once built.
type DerivedSlot = std::sync::OnceLock<(TypeId, std::sync::OnceLock<Box<dyn Derived>>)>;

/// Data that a layer above the surface derives from it once and caches
/// with it (the snap index, the curves' lengths): the surface holds it
/// without knowing how it is built or what it is, so it does not depend on
/// the modules that use it.
pub(crate) trait Derived: std::any::Any + Send + Sync {
    /// Bytes it holds, counted in [`Surface::memory_bytes`].
    fn memory_bytes(&self) -> usize;
}

/// Which surface a control net defines (Persson, Aftosmis & Haines §3.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceMode {
    /// The Loop limit surface: smooth, near but not through the net's points.
    Approximating,
    /// The Loop limit surface of solved control points x′ with S∞ x′ = x:
    /// smooth and through the original points; [`Surface::net`] is the
    /// solved net (see [`crate::interpolate`]).
    Solve,
    /// The approximating surface plus, inside each triangle, the linear
    /// interpolation of its corners' displacements (original point minus
    /// limit point): through the original points exactly, but only C0
    /// across control edges. Second derivatives are those of the
    /// approximating surface (the added field is linear).
    Displacement,
}

/// Position and derivatives at one point, in the evaluation record's order (docs/design.md).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    pub x: DVec3,
    pub xv: DVec3,
    pub xw: DVec3,
    pub xvv: DVec3,
    pub xvw: DVec3,
    pub xww: DVec3,
    /// The point is exactly a special vertex (irregular, dart, crease or
    /// corner). The position is its exact limit position; the
    /// parametrisation is singular there (first derivatives vanish below
    /// valence 6 and diverge above), so all derivatives are reported as zero.
    pub at_special_vertex: bool,
}

impl Evaluation {
    /// The Gauss–Newton step towards a point at offset `d` from this one:
    /// the parameter change (dv, dw) whose image in the tangent plane,
    /// dv Xv + dw Xw, is nearest to `d`. `None` at a special vertex or
    /// where Xv and Xw are (nearly) parallel.
    pub(crate) fn tangent_step(&self, d: DVec3) -> Option<DVec2> {
        let (a, b, c) = (
            self.xv.length_squared(),
            self.xv.dot(self.xw),
            self.xw.length_squared(),
        );
        let det = a * c - b * b;
        if self.at_special_vertex || !(det > 1e-24 * a * c) {
            return None;
        }
        let (r, s) = (self.xv.dot(d), self.xw.dot(d));
        Some(DVec2::new(c * r - b * s, a * s - b * r) / det)
    }

    /// The unit normal Xv × Xw / |Xv × Xw| (see `eval::surface_normal`):
    /// outward on a consistently oriented closed net. `None` exactly at a
    /// special vertex, whose derivatives are reported as zero
    /// ([`Surface::normal`] gives the normal there from the tangent masks),
    /// and where Xv and Xw are parallel.
    pub fn normal(&self) -> Option<DVec3> {
        surface_normal(self.xv, self.xw)
    }

    /// X Xv Xw Xvv Xvw Xww as 18 numbers (EGADS `EG_evaluate` order).
    #[inline]
    pub fn record(&self) -> [f64; 18] {
        // Element by element: slice copies of three numbers became calls
        // to memcpy, a tenth of a regular evaluation.
        let d = [self.x, self.xv, self.xw, self.xvv, self.xvw, self.xww];
        std::array::from_fn(|i| d[i / 3][i % 3])
    }
}

/// Principal curvatures and directions (EGADS `EG_curvature` order), with
/// mean and Gaussian curvature. Curvatures are positive where the surface
/// bends away from its outward normal: a sphere of radius r has 1/r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvature {
    pub k1: f64,
    pub dir1: DVec3,
    pub k2: f64,
    pub dir2: DVec3,
    pub mean: f64,
    pub gaussian: f64,
    /// False exactly at a special vertex, where curvature is unbounded
    /// (valence 3 and ≥ 7) or depends on the direction (valence 4 and 5), or
    /// where the tangent plane degenerates; the numbers are then zero.
    /// Anywhere else the numbers are the exact curvature of the limit
    /// surface at that point, even if it grows without bound towards an
    /// irregular vertex.
    pub reliable: bool,
}

impl Curvature {
    /// k1 dir1 k2 dir2 as 8 numbers.
    pub fn record(&self) -> [f64; 8] {
        let mut out = [0.0; 8];
        out[0] = self.k1;
        out[1..4].copy_from_slice(&self.dir1.to_array());
        out[4] = self.k2;
        out[5..8].copy_from_slice(&self.dir2.to_array());
        out
    }
}

impl Surface {
    /// The limit surface of `net` (which is copied): refines its points
    /// once; the refined connectivity is built when the first query needs
    /// it, and each triangle's evaluation data when a query first reaches
    /// it. Fails only when the once-refined net would not fit 32-bit
    /// indices.
    pub fn new(net: &ControlNet) -> Result<Surface> {
        Self::with_mode(net, SurfaceMode::Approximating)
    }

    /// The surface of `net` in the given mode; `Solve` solves for new
    /// control points first ([`crate::interpolate::solve`]).
    pub fn with_mode(net: &ControlNet, mode: SurfaceMode) -> Result<Surface> {
        match mode {
            SurfaceMode::Solve => Self::from_net(crate::interpolate::solve(net)?, mode),
            _ => Self::from_net(net.clone(), mode),
        }
    }

    /// The surface of `part`'s sub-net as `whole` defines it: the same
    /// mode, and in displacement mode each vertex's displacement carried
    /// from `whole` (not measured again on the sub-net, where a vertex at
    /// its rim lacks part of its fan). So each triangle the part owns
    /// evaluates bit for bit as in `whole` (approximating alone, a
    /// displaced whole put its parts' points on the approximating surface,
    /// up to 3.5e-3 of the diagonal off on fandisk at 1%). It shares
    /// `whole`'s table of special-corner configurations: each depends only
    /// on the pattern of triangles, hard edges and tags around a corner,
    /// so the surfaces of many sub-nets of one net (the parts of a
    /// remeshing by parts) build each configuration once, and evaluate
    /// exactly as with a table of their own. Fails on a part of a net of
    /// another size.
    pub(crate) fn part_of(whole: &Surface, part: &Part) -> Result<Surface> {
        let size = [whole.net.points().len(), whole.net.triangles().len()];
        if part.whole_size() != size {
            return Err(Error::InvalidArgument(format!(
                "a part of a net of {:?} vertices and triangles, on a surface of {size:?}",
                part.whole_size()
            )));
        }
        let displacement = match whole.mode {
            SurfaceMode::Displacement => (part.global_vertices().iter())
                .map(|&g| whole.displacement[g as usize])
                .collect(),
            _ => Vec::new(),
        };
        let table = whole.evaluator.configuration_table().clone();
        Ok(Surface {
            evaluator: Evaluator::sharing(part.net(), table)?,
            net: part.net().clone(),
            mode: whole.mode,
            displacement,
            derived: Default::default(),
            model: std::sync::OnceLock::new(),
        })
    }

    /// Builds the surface of `net` in `mode`, taking `net` as it is (for
    /// `Solve`, the already solved net).
    pub(crate) fn from_net(net: ControlNet, mode: SurfaceMode) -> Result<Surface> {
        let displacement = match mode {
            SurfaceMode::Displacement => {
                let limits = net.limit_points();
                net.points()
                    .iter()
                    .zip(limits)
                    .map(|(&x, l)| x - l)
                    .collect()
            }
            _ => Vec::new(),
        };
        Ok(Surface {
            evaluator: Evaluator::new(&net)?,
            net,
            mode,
            displacement,
            derived: Default::default(),
            model: std::sync::OnceLock::new(),
        })
    }

    /// The surface's derived data of type `T`, built by `build` on first
    /// use. Its slot is the first one claimed for `T`, or else the first
    /// unclaimed one (a claim never changes, so each kind has one slot
    /// even when threads race). More kinds than [`DERIVED_KINDS`] are a
    /// bug in loopsurf, caught here.
    pub(crate) fn derived<T: Derived>(&self, build: impl FnOnce(&Surface) -> T) -> &T {
        let kind = TypeId::of::<T>();
        let (_, slot) = self
            .derived
            .iter()
            .map(|slot| slot.get_or_init(|| (kind, std::sync::OnceLock::new())))
            .find(|(claimed, _)| *claimed == kind)
            .unwrap_or_else(|| {
                panic!("a surface caches at most {DERIVED_KINDS} kinds of derived data")
            });
        let data: &dyn std::any::Any = slot.get_or_init(|| Box::new(build(self))).as_ref();
        data.downcast_ref::<T>()
            .expect("a slot holds the kind it was claimed for")
    }

    /// The evaluator behind this surface (the approximating surface of its
    /// net, before any displacement).
    pub(crate) fn evaluator(&self) -> &Evaluator {
        &self.evaluator
    }

    /// The displacements of triangle `tri`'s corners (zero unless in
    /// displacement mode).
    pub(crate) fn displacements_of(&self, tri: usize) -> [DVec3; 3] {
        let c = self.net.triangles()[tri];
        c.map(|i| {
            self.displacement
                .get(i as usize)
                .copied()
                .unwrap_or(DVec3::ZERO)
        })
    }

    /// The corners, curves and faces of the net's hard features (see
    /// [`crate::model`]), traced on first use.
    pub fn model(&self) -> &crate::model::Model {
        self.model
            .get_or_init(|| crate::model::Model::new(self.net.topology(), self.net.features()))
    }

    /// The displacement of vertex `v` (zero unless in displacement mode).
    pub(crate) fn displacement_of(&self, v: u32) -> DVec3 {
        self.displacement
            .get(v as usize)
            .copied()
            .unwrap_or(DVec3::ZERO)
    }

    /// Which surface this is.
    pub fn mode(&self) -> SurfaceMode {
        self.mode
    }

    /// The control net.
    pub fn net(&self) -> &ControlNet {
        &self.net
    }

    /// Bytes the surface holds beyond its control net (per-triangle tables,
    /// the shared special-vertex configurations, and what layers above
    /// derived from it: the snapping index once a snap has built it, the
    /// curves' lengths once one was asked for).
    pub fn memory_bytes(&self) -> usize {
        self.evaluator.memory_bytes()
            + self
                .derived
                .iter()
                .filter_map(|slot| slot.get()?.1.get())
                .map(|d| d.memory_bytes())
                .sum::<usize>()
    }

    /// Number of distinct special-vertex configurations built so far (each
    /// is built the first time an evaluation needs it).
    pub fn configurations(&self) -> usize {
        self.evaluator.configurations()
    }

    /// Position and first and second derivatives at (v, w) of triangle `tri`.
    #[inline(always)]
    pub fn eval(&self, tri: usize, v: f64, w: f64) -> Result<Evaluation> {
        let (v, w) = self.check(tri, v, w)?;
        // Returned where it is made: binding it first cost two copies
        // (calls to memcpy) per evaluation.
        if self.displacement.is_empty() {
            return Ok(self.eval_approximating(tri, v, w));
        }
        Ok(self.displaced(tri, v, w, self.eval_approximating(tri, v, w)))
    }

    /// `eval(tri, v, w)?.record()`, the C ABI's answer, built straight
    /// from the evaluator's result: going through an [`Evaluation`] cost
    /// the C path 5% in copies.
    #[inline(always)]
    pub fn eval_record(&self, tri: usize, v: f64, w: f64) -> Result<[f64; 18]> {
        let (v, w) = self.check(tri, v, w)?;
        if !self.displacement.is_empty() {
            return Ok(self
                .displaced(tri, v, w, self.eval_approximating(tri, v, w))
                .record());
        }
        Ok(match self.evaluator.eval(tri, v, w) {
            Ok(d) => std::array::from_fn(|i| d[i / 3][i % 3]),
            Err(at) => {
                let mut r = [0.0; 18];
                r[..3].copy_from_slice(&at.limit.to_array());
                r
            }
        })
    }

    /// The position alone at (v, w) of triangle `tri`, bit-identical to
    /// `eval(tri, v, w)?.x` and several times cheaper (meshers and
    /// samplers that only place points).
    pub fn point(&self, tri: usize, v: f64, w: f64) -> Result<DVec3> {
        let (v, w) = self.check(tri, v, w)?;
        Ok(self.displaced_point(tri, v, w, self.evaluator.point(tri, v, w)))
    }

    /// Evaluation confined to triangle `tri`, caching what points of the
    /// triangle share (see [`ChartEvaluator`]).
    pub(crate) fn chart(&self, tri: usize) -> Result<Chart<'_>> {
        self.check(tri, 0.0, 0.0)?;
        Ok(Chart {
            surface: self,
            tri,
            inner: ChartEvaluator::new(&self.evaluator, tri),
        })
    }

    /// Adds the displacement field of triangle `tri` to a position.
    pub(crate) fn displaced_point(&self, tri: usize, v: f64, w: f64, x: DVec3) -> DVec3 {
        if self.displacement.is_empty() {
            return x;
        }
        let c = self.net.triangles()[tri].map(|i| i as usize);
        if let Some(k) = corner_at(v, w) {
            return self.net.points()[c[k]];
        }
        let d = c.map(|i| self.displacement[i]);
        x + ((1.0 - v - w) * d[0] + v * d[1] + w * d[2])
    }

    /// Adds the linear displacement field of triangle `tri` to `e`. At a
    /// corner the position is the original point itself, bit for bit.
    fn displaced(&self, tri: usize, v: f64, w: f64, mut e: Evaluation) -> Evaluation {
        let c = self.net.triangles()[tri].map(|i| i as usize);
        let d = c.map(|i| self.displacement[i]);
        e.x += (1.0 - v - w) * d[0] + v * d[1] + w * d[2];
        if let Some(k) = corner_at(v, w) {
            e.x = self.net.points()[c[k]];
        }
        if !e.at_special_vertex {
            e.xv += d[1] - d[0];
            e.xw += d[2] - d[0];
        }
        e
    }

    /// The approximating surface at a checked (v, w).
    #[inline]
    pub(crate) fn eval_approximating(&self, tri: usize, v: f64, w: f64) -> Evaluation {
        evaluation_of(self.evaluator.eval(tri, v, w))
    }

    /// Evaluates many points in parallel; fails on the first bad query.
    pub fn eval_many(&self, queries: &[(u32, f64, f64)]) -> Result<Vec<Evaluation>> {
        queries
            .par_iter()
            .map(|&(t, v, w)| self.eval(t as usize, v, w))
            .collect()
    }

    /// The unit outward normal. Exactly at a special vertex it is the normal
    /// of the limit surface there, from the tangent masks of the triangle's
    /// sector: one-sided at creases and corners, where each sector has its
    /// own tangent plane.
    ///
    /// In displacement mode the surface is only C0 at special vertices;
    /// exactly there the normal of the approximating surface is returned.
    pub fn normal(&self, tri: usize, v: f64, w: f64) -> Result<DVec3> {
        let (v, w) = self.check(tri, v, w)?;
        match self.evaluator.eval(tri, v, w) {
            Ok(_) if !self.displacement.is_empty() => {
                Ok(self.eval(tri, v, w)?.normal().unwrap_or_default())
            }
            Ok(d) => Ok(surface_normal(d[1], d[2]).unwrap_or_default()),
            Err(at) => self.vertex_normal(tri, v, w, at.vertex, at.normal),
        }
    }

    /// The normal exactly at a special vertex, from the sector's tangent
    /// masks, checked against the surface itself just inside the triangle.
    /// The masks come from the dominant pair of modes of the vertex's local
    /// matrix; at a corner whose creases share the eigenvalue ½, or next to
    /// a sector whose own mode dominates (a reflex sector), that pair mixes
    /// modes of other sectors and the normal can be off or reversed (CGAL's
    /// cross.off at 30°: 45°; joint: 180°), and the normals inside do not
    /// approach it. Then the normal is the limit of the sector's normals
    /// approached from inside, when they settle (to 1e-9 at 2⁻²⁰, 2⁻⁴⁰
    /// and 2⁻⁶⁰ of the way), and otherwise there is no tangent plane to claim.
    fn vertex_normal(
        &self,
        tri: usize,
        v: f64,
        w: f64,
        vertex: u32,
        masked: Option<DVec3>,
    ) -> Result<DVec3> {
        let inside = |h: f64| -> Option<DVec3> {
            let (a, b) = (v + h * (1.0 / 3.0 - v), w + h * (1.0 / 3.0 - w));
            let d = self.evaluator.eval(tri, a, b).ok()?;
            surface_normal(d[1], d[2])
        };
        let none = Error::NoTangentPlane {
            vertex,
            kind: "special",
        };
        let depths = [20, 40, 60].map(|k| inside(0.5f64.powi(k)));
        let [Some(n20), Some(n40), Some(n60)] = depths else {
            return masked.ok_or(none);
        };
        // The masks are right when the normals inside approach them: close
        // by 2^-60 (darts converge at about 0.85 a level), or closing in
        // all the way down (high valences converge very slowly: 0.998 a
        // level at valence 80).
        let approaching = |n: &DVec3| {
            let (a20, a40, a60) = (
                n.angle_between(n20),
                n.angle_between(n40),
                n.angle_between(n60),
            );
            a60 < 1e-2 || (a40 < a20 * (1.0 - 1e-6) && a60 < a40 * (1.0 - 1e-6))
        };
        if let Some(n) = masked.filter(approaching) {
            return Ok(n);
        }
        // Otherwise the sector's normals must have settled; where they keep
        // turning or flip (a reflex sector whose limit surface folds at the
        // corner) there is no tangent plane.
        if n20.angle_between(n40) < 1e-9 && n40.angle_between(n60) < 1e-9 {
            Ok(n60)
        } else {
            Err(none)
        }
    }

    /// Principal curvatures and directions, mean and Gaussian curvature.
    pub fn curvature(&self, tri: usize, v: f64, w: f64) -> Result<Curvature> {
        let e = self.eval(tri, v, w)?;
        Ok(curvature_of(&e))
    }

    /// Checks a query without evaluating it: `eval(tri, v, w)` succeeds
    /// exactly when this does (batch callers validate everything first so
    /// that they write no output on failure).
    pub fn validate(&self, tri: usize, v: f64, w: f64) -> Result<()> {
        self.check(tri, v, w).map(|_| ())
    }

    /// Validates a query; clamps round-off excursions into the triangle.
    #[inline]
    fn check(&self, tri: usize, v: f64, w: f64) -> Result<(f64, f64)> {
        let bad = |reason| Err(Error::BadParameter { tri, v, w, reason });
        if tri >= self.net.triangles().len() {
            return Err(Error::InvalidArgument(format!(
                "triangle {tri}: out of range (the net has {} triangles)",
                self.net.triangles().len()
            )));
        }
        if !v.is_finite() || !w.is_finite() {
            return bad("not a finite number");
        }
        let tol = PARAMETER_TOLERANCE;
        if v < -tol || w < -tol || v + w > 1.0 + tol {
            return bad("outside the triangle (v ≥ 0, w ≥ 0, v + w ≤ 1)");
        }
        Ok(clamp_to_triangle(DVec2::new(v, w)).into())
    }
}

/// Which corner of its triangle (v, w) is exactly, if any.
fn corner_at(v: f64, w: f64) -> Option<usize> {
    CORNERS.iter().position(|&c| c == DVec2::new(v, w))
}

/// An evaluator result as an [`Evaluation`]: exactly at a special vertex,
/// its limit and zero derivatives.
#[inline]
fn evaluation_of(r: std::result::Result<[DVec3; 6], AtVertex>) -> Evaluation {
    match r {
        Ok([x, xv, xw, xvv, xvw, xww]) => Evaluation {
            x,
            xv,
            xw,
            xvv,
            xvw,
            xww,
            at_special_vertex: false,
        },
        Err(at) => Evaluation {
            x: at.limit,
            xv: DVec3::ZERO,
            xw: DVec3::ZERO,
            xvv: DVec3::ZERO,
            xvw: DVec3::ZERO,
            xww: DVec3::ZERO,
            at_special_vertex: true,
        },
    }
}

/// [`Surface::point`] and [`Surface::eval`] for many points of one
/// triangle, bit-identical to them.
pub(crate) struct Chart<'a> {
    surface: &'a Surface,
    tri: usize,
    inner: ChartEvaluator<'a>,
}

impl Chart<'_> {
    pub fn point(&mut self, v: f64, w: f64) -> Result<DVec3> {
        let (v, w) = self.surface.check(self.tri, v, w)?;
        let x = self.inner.point(v, w);
        Ok(self.surface.displaced_point(self.tri, v, w, x))
    }

    pub fn eval(&mut self, v: f64, w: f64) -> Result<Evaluation> {
        let (v, w) = self.surface.check(self.tri, v, w)?;
        let e = evaluation_of(self.inner.eval(v, w));
        Ok(if self.surface.displacement.is_empty() {
            e
        } else {
            self.surface.displaced(self.tri, v, w, e)
        })
    }
}

/// Curvature from the first and second fundamental forms.
fn curvature_of(e: &Evaluation) -> Curvature {
    let unreliable = Curvature {
        k1: 0.0,
        dir1: DVec3::ZERO,
        k2: 0.0,
        dir2: DVec3::ZERO,
        mean: 0.0,
        gaussian: 0.0,
        reliable: false,
    };
    let (ee, ff, gg) = (e.xv.dot(e.xv), e.xv.dot(e.xw), e.xw.dot(e.xw));
    let det = ee * gg - ff * ff;
    // A degenerate or non-finite tangent plane (NaN counts as degenerate).
    let is_degenerate = det.is_nan() || det <= f64::EPSILON * ee * gg;
    let n = match e.normal() {
        Some(n) if !e.at_special_vertex && !is_degenerate => n,
        _ => return unreliable,
    };
    // Sign: positive where the surface bends away from the outward normal.
    let (l, m, nn) = (-e.xvv.dot(n), -e.xvw.dot(n), -e.xww.dot(n));
    let gaussian = (l * nn - m * m) / det;
    let mean = (ee * nn - 2.0 * ff * m + gg * l) / (2.0 * det);
    let disc = (mean * mean - gaussian).max(0.0).sqrt();
    let (k1, k2) = (mean + disc, mean - disc);
    // Principal direction of k1: (II − k1 I)(a, b) = 0, from the better
    // conditioned row. Near an umbilic (k1 ≈ k2 to round-off) every
    // direction is principal.
    let (a11, a12, a22) = (l - k1 * ee, m - k1 * ff, nn - k1 * gg);
    let (a, b) = if a11.abs() + a12.abs() >= a12.abs() + a22.abs() {
        (-a12, a11)
    } else {
        (a22, -a12)
    };
    let umbilic = disc <= f64::EPSILON.sqrt() * (k1.abs() + k2.abs());
    let dir1 = match (a * e.xv + b * e.xw).try_normalize() {
        Some(d) if !umbilic => d,
        _ => e.xv.normalize(),
    };
    let curvature = Curvature {
        k1,
        dir1,
        k2,
        dir2: n.cross(dir1),
        mean,
        gaussian,
        reliable: true,
    };
    if curvature.record().iter().all(|x| x.is_finite()) && mean.is_finite() && gaussian.is_finite()
    {
        curvature
    } else {
        unreliable
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere() -> ControlNet {
        let ex = crate::examples::sphere();
        ControlNet::from_arrays(ex.points, &ex.tris).unwrap()
    }

    #[test]
    fn bad_queries_are_errors() {
        let s = Surface::new(&sphere()).unwrap();
        assert!(matches!(
            s.eval(9999, 0.1, 0.1),
            Err(Error::InvalidArgument(_))
        ));
        assert!(matches!(
            s.eval(0, f64::NAN, 0.1),
            Err(Error::BadParameter { .. })
        ));
        assert!(matches!(
            s.eval(0, -0.01, 0.1),
            Err(Error::BadParameter { .. })
        ));
        assert!(matches!(
            s.eval(0, 0.6, 0.5),
            Err(Error::BadParameter { .. })
        ));
        assert!(s.eval(0, -1e-14, 1.0 + 1e-14).is_ok());
    }

    #[test]
    fn no_nan_at_any_corner() {
        let mut net = crate::examples::by_name("cube")
            .map(|e| ControlNet::from_arrays(e.points, &e.tris).unwrap())
            .unwrap();
        net.tag_by_angle(30.0).unwrap();
        for net in [sphere(), net] {
            let s = Surface::new(&net).unwrap();
            for t in 0..net.triangles().len() {
                for (v, w) in [
                    (0.0, 0.0),
                    (1.0, 0.0),
                    (0.0, 1.0),
                    (0.5, 0.5),
                    (1.0 / 3.0, 1.0 / 3.0),
                ] {
                    let e = s.eval(t, v, w).unwrap();
                    assert!(e.record().iter().all(|x| x.is_finite()));
                    let k = s.curvature(t, v, w).unwrap();
                    assert!(k.record().iter().all(|x| x.is_finite()) && k.mean.is_finite());
                }
            }
        }
    }

    #[test]
    fn eval_many_equals_one_by_one() {
        let s = Surface::new(&sphere()).unwrap();
        let queries: Vec<(u32, f64, f64)> =
            (0..320).map(|t| (t, 0.1 + 0.001 * t as f64, 0.3)).collect();
        let many = s.eval_many(&queries).unwrap();
        for (q, e) in queries.iter().zip(&many) {
            assert_eq!(*e, s.eval(q.0 as usize, q.1, q.2).unwrap());
        }
        let mut bad = queries.clone();
        bad[77].1 = f64::NAN;
        assert!(matches!(
            s.eval_many(&bad),
            Err(Error::BadParameter { tri: 77, .. })
        ));
    }

    #[test]
    fn the_surface_is_send_and_sync() {
        fn check<T: Send + Sync>() {}
        check::<Surface>();
    }

    #[test]
    fn sphere_like_surface_has_positive_curvature_and_outward_normals() {
        let net = sphere();
        let s = Surface::new(&net).unwrap();
        for t in 0..net.triangles().len() {
            let e = s.eval(t, 0.3, 0.3).unwrap();
            let n = s.normal(t, 0.3, 0.3).unwrap();
            assert!(n.dot(e.x) > 0.9 * e.x.length());
            let k = s.curvature(t, 0.3, 0.3).unwrap();
            assert!(
                k.reliable && k.k1 >= k.k2 && k.k2 > 0.5 && k.k1 < 2.0,
                "{k:?}"
            );
            assert!((k.dir1.dot(n)).abs() < 1e-12 && (k.dir2.dot(n)).abs() < 1e-12);
            assert!((k.gaussian - k.k1 * k.k2).abs() < 1e-12);
        }
        // At the twelve valence-5 vertices: exact limit position, normal from
        // the tangent masks, curvature flagged.
        let topo = net.topology();
        for v in (0..net.points().len()).filter(|&v| topo.valence(v) == 5) {
            let t = topo.fan(v)[0] as usize;
            let k = topo.triangles()[t]
                .iter()
                .position(|&c| c as usize == v)
                .unwrap();
            let (pv, pw) = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)][k];
            let e = s.eval(t, pv, pw).unwrap();
            assert!(e.at_special_vertex);
            assert!((e.x - net.limit_points()[v]).length() < 1e-15);
            let n = s.normal(t, pv, pw).unwrap();
            assert!(
                n.dot(e.x.normalize()) > 1.0 - 1e-12,
                "symmetric vertex: radial normal"
            );
            assert!(!s.curvature(t, pv, pw).unwrap().reliable);
        }
    }
}

#[cfg(test)]
mod sharing_tests {
    use super::*;

    /// A sub-net's surface sharing the whole's configurations evaluates
    /// bit for bit as one with a table of its own, near and at special
    /// vertices and on creases, and adds what it builds to the shared
    /// table.
    #[test]
    fn shared_configurations_evaluate_as_own_ones() {
        let ex = crate::examples::viking();
        let mut net = ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
        net.tag_by_angle(30.0).unwrap();
        net.tag_vertex(5).unwrap();
        let whole = Surface::new(&net).unwrap();
        let half: Vec<u32> = (0..net.triangles().len() as u32 / 2).collect();
        let part = crate::partition::Part::new(&net, &half).unwrap();
        let own = Surface::new(part.net()).unwrap();
        let shared = Surface::part_of(&whole, &part).unwrap();
        let mut params = vec![(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.25, 0.5)];
        for k in 1..=8 {
            let f = 0.5f64.powi(3 * k);
            params.extend([(f, 0.0), (f, f), (1.0 - f, 0.0), (0.0, 1.0 - 2.0 * f)]);
        }
        for t in 0..part.net().triangles().len() {
            for &(v, w) in &params {
                let (a, b) = (own.eval(t, v, w), shared.eval(t, v, w));
                match (a, b) {
                    (Ok(a), Ok(b)) => {
                        let bits = |e: &Evaluation| {
                            [e.x, e.xv, e.xw, e.xvv, e.xvw, e.xww]
                                .map(|d| d.to_array().map(f64::to_bits))
                        };
                        assert_eq!(bits(&a), bits(&b), "{t} {v} {w}");
                    }
                    (a, b) => assert_eq!(a.is_ok(), b.is_ok(), "{t} {v} {w}"),
                }
            }
        }
        let built = own.evaluator().configurations();
        assert!(built >= 3, "{built} configurations");
        assert_eq!(
            shared.evaluator().configurations(),
            whole.evaluator().configurations()
        );
        assert!(whole.evaluator().configurations() >= built);
    }
}

#[cfg(test)]
mod point_tests {
    use super::*;

    /// `point` and a chart's `point`/`eval` are shortcuts of `eval`: the
    /// same bits everywhere, near and exactly at special vertices, on
    /// creases and in displacement mode.
    #[test]
    fn point_chart_and_record_match_eval_bit_for_bit() {
        let mut params = vec![
            (0.0, 0.0),
            (1.0, 0.0),
            (0.0, 1.0),
            (0.5, 0.5),
            (0.5, 0.0),
            (0.0, 0.5),
        ];
        for k in 1..=12 {
            let f = 0.5f64.powi(3 * k);
            params.extend([(f, 0.0), (f, f), (1.0 - f, 0.0), (0.3 * f, 1.0 - 2.0 * f)]);
        }
        for i in 0..=7 {
            for j in 0..=7 - i {
                params.push((i as f64 / 7.0, j as f64 / 7.0));
            }
        }
        for (name, angle, mode) in [
            ("viking", Some(30.0), SurfaceMode::Approximating),
            ("sphere", None, SurfaceMode::Approximating),
            ("cube", Some(30.0), SurfaceMode::Displacement),
        ] {
            let ex = crate::examples::by_name(name).unwrap();
            let mut net = ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
            if let Some(a) = angle {
                net.tag_by_angle(a).unwrap();
            }
            let surface = Surface::with_mode(&net, mode).unwrap();
            for t in 0..net.triangles().len() {
                let mut chart = surface.chart(t).unwrap();
                for &(v, w) in &params {
                    let e = surface.eval(t, v, w).unwrap();
                    assert_eq!(
                        surface.point(t, v, w).unwrap(),
                        e.x,
                        "{name} {t} ({v}, {w})"
                    );
                    assert_eq!(chart.point(v, w).unwrap(), e.x, "{name} {t} ({v}, {w})");
                    assert_eq!(chart.eval(v, w).unwrap(), e, "{name} {t} ({v}, {w})");
                    let record = surface.eval_record(t, v, w).unwrap();
                    assert_eq!(record.map(f64::to_bits), e.record().map(f64::to_bits));
                }
            }
        }
    }
}
