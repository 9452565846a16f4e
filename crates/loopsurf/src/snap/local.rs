//! The local solve: the closest point of one triangle's patch, of one cell
//! of it, or (walking across edges and around vertices) of the surface near
//! a start, by projected Newton on f(v, w) = ½ |X(v, w) − p|².
//!
//! The full Hessian (with the curvature terms r · Xvv …) is used where it
//! is positive definite, so convergence near a minimiser is quadratic; where
//! it is not (far points, concave regions) it is shifted by a multiple of
//! JᵀJ until it is, which keeps every step a descent step without ignoring
//! the curvature. Steps are clipped to the region; on a side or at a corner
//! whose constraint is binding, the step is restricted to the side, so minima
//! on boundaries, hard edges and corners are found as exactly as interior
//! ones. At irregular vertices, where the parametrisation is singular,
//! stalled steps are stretched and the walk goes on around the vertex.
//!
//! The walk is the whole cost of a local projection (`snap::project`),
//! so it spends evaluations sparingly: a step that leaves a triangle across
//! a smooth edge is tried whole in the neighbour, and the solve stops once
//! the predicted gain is lost in the round-off of f (taking that last step,
//! evaluated for its position only).

use crate::parameters::{across_edge, clamp_to_triangle, SurfacePoint, CORNERS};
use crate::surface::{Chart, Evaluation, Surface};
use glam::{DVec2, DVec3};

/// A point of the surface with its parameters and distance to the query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Snap {
    /// Control triangle.
    pub tri: usize,
    /// Parameters in that triangle (weights 1 − v − w, v, w).
    pub v: f64,
    pub w: f64,
    /// The surface point `eval(tri, v, w).x`.
    pub point: DVec3,
    /// Its distance to the query point.
    pub distance: f64,
    /// A proven lower bound on the distance from the query point to the
    /// whole surface: `distance - lower_bound` is how far from the global
    /// minimum the answer can be at most. Global snaps certify it to their
    /// tolerance; a local projection proves nothing and sets it to 0.
    pub lower_bound: f64,
}

const MAX_ITERATIONS: usize = 60;
const MAX_HOPS: usize = 64;
/// Parameter steps below this are round-off: converged.
const STEP_TOLERANCE: f64 = 1e-15;
/// A Newton step this short is the last one needed (the parameter domain
/// has size 1; the error after it is of the order of its square).
const CONVERGED_STEP: f64 = 1e-7;
const MAX_HALVINGS: usize = 30;
/// A bound on the round-off of an evaluated surface point relative to the
/// size of the coordinates: the evaluator's sums lose a few units in the
/// last place; this allows some 45.
const POINT_ROUND_OFF: f64 = 1e-14;

/// The part of a triangle's parameter domain a solve stays in: the whole
/// triangle, or one cell of it. One constraint n · (v, w) ≥ c per side,
/// side i running from corner i to corner i + 1 (for the whole triangle,
/// its local edge i).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Region {
    corners: [DVec2; 3],
    sides: [(DVec2, f64); 3],
}

impl Region {
    pub(crate) const WHOLE: Region = Region {
        corners: CORNERS,
        sides: [
            (DVec2::new(0.0, 1.0), 0.0),    // w ≥ 0
            (DVec2::new(-1.0, -1.0), -1.0), // v + w ≤ 1
            (DVec2::new(1.0, 0.0), 0.0),    // v ≥ 0
        ],
    };

    /// The sub-triangle with these corners, counter-clockwise.
    pub(crate) fn new(corners: [DVec2; 3]) -> Region {
        let sides = [0, 1, 2].map(|i| {
            let d = corners[(i + 1) % 3] - corners[i];
            let n = DVec2::new(-d.y, d.x);
            (n, n.dot(corners[i]))
        });
        Region { corners, sides }
    }

    /// Whether `uv` rests on side k (to round-off).
    fn on_side(&self, k: usize, uv: DVec2) -> bool {
        let (n, c) = self.sides[k];
        n.dot(uv) - c <= 1e-15
    }

    /// The nearest point of the region (round-off repair).
    fn clamp(&self, uv: DVec2) -> DVec2 {
        if self.corners == CORNERS {
            return clamp_to_triangle(uv);
        }
        let [a, b, c] = self.corners;
        let q = super::cell::closest_in_triangle(uv, a, b, c);
        a + q.x * (b - a) + q.y * (c - a)
    }
}

/// Evaluates, moving a hair's breadth off a special vertex, where the
/// parametrisation is singular and all derivatives are reported as zero.
/// A non-finite point (a step from a degenerate flat triangle or a folded
/// patch) is taken at the triangle's centre instead: the descent then goes
/// on from a point of the surface rather than failing.
fn eval_at(chart: &mut Chart, uv: DVec2) -> Evaluation {
    let uv = if uv.is_finite() {
        uv
    } else {
        DVec2::splat(1.0 / 3.0)
    };
    let e = chart
        .eval(uv.x, uv.y)
        .expect("parameters kept inside the triangle");
    if !e.at_special_vertex {
        return e;
    }
    let centre = DVec2::splat(1.0 / 3.0);
    let nudged = uv + 1e-9 * (centre - uv);
    let mut moved = chart.eval(nudged.x, nudged.y).expect("inside");
    moved.x = e.x; // the exact point; derivatives from a hair away
    moved
}

/// Minimises the distance to `p` starting from (tri, v, w): a local
/// minimum of the distance over the surface, and whether the last solve
/// converged. A minimum on an interior edge whose descent continues across
/// it moves into the neighbouring triangle, one at a corner into the
/// steepest triangle of the vertex's fan; the walk ends where a hop gains
/// nothing (a minimum on the edge itself, as on a crease) or at a boundary.
pub(crate) fn descend(surface: &Surface, p: DVec3, tri: usize, v: f64, w: f64) -> (Snap, bool) {
    descend_walking(surface, p, tri, v, w, false)
}

/// [`descend`], never walking out of the model face of `tri` when
/// `in_face` is set: across a hard edge the walk stops on it, so minima on
/// the face's curves are constrained minima of the face.
pub(crate) fn descend_walking(
    surface: &Surface,
    p: DVec3,
    tri: usize,
    v: f64,
    w: f64,
    in_face: bool,
) -> (Snap, bool) {
    if !in_face {
        return descend_confined(surface, p, tri, v, w, &|_| true);
    }
    // Only a walk kept in its face needs the model (built on first use).
    let faces = surface.model().face_of_triangle();
    let face = faces[tri];
    descend_confined(surface, p, tri, v, w, &|t| faces[t] == face)
}

/// Which triangles a walk may enter.
pub(crate) type Allowed<'a> = dyn Fn(usize) -> bool + 'a;

/// [`descend`] over the triangles `allowed` admits (`tri` among them):
/// an edge into any other is walked like a boundary, the solve converging
/// on it, and the walk ends where it would go on into one. Every triangle
/// the walk would enter or carry a step into is asked first.
pub(crate) fn descend_confined(
    surface: &Surface,
    p: DVec3,
    tri: usize,
    v: f64,
    w: f64,
    allowed: &Allowed,
) -> (Snap, bool) {
    let mut start = Start::new(surface, tri, DVec2::new(v, w));
    let mut best: Option<(Snap, bool)> = None;
    // Whether this solve goes on with a step carried into its triangle.
    let mut carried = false;
    for _ in 0..=MAX_HOPS {
        let tri = start.tri;
        let exit = descend_in(surface, p, start, &Region::WHOLE, Some(allowed));
        let (end, x, leaving, converged) = match exit {
            Exit::Stopped {
                uv,
                x,
                leaving,
                converged,
            } => (uv, x, leaving, converged),
            Exit::Carried(next) => {
                // Nearer than where the solve began (the step passed the
                // descent test), so nearer than anything found before.
                best = Some((snap_at(next.tri, next.uv, next.e.x, p), false));
                (start, carried) = (next, true);
                continue;
            }
        };
        let here = snap_at(tri, end, x, p);
        // A hop that gains nothing ends the walk; a carried step's solve
        // is one descent, which may end level with its start only where
        // that was already the minimum (to round-off).
        if !carried && best.is_some_and(|(b, _)| b.distance <= here.distance) {
            break;
        }
        best = Some((here, converged));
        carried = false;
        // At a corner the descent may go on in any triangle of the fan. At
        // an irregular vertex the parametrisation is singular and Newton
        // stalls next to the corner instead, where its steps shrink with
        // the derivatives' blow-up: that counts as the corner too.
        let next = match leaving {
            Some(edge) => across(surface, tri, edge, end),
            None => (0..3)
                .find(|&k| (end - CORNERS[k]).abs().max_element() < 1e-6)
                .and_then(|k| downhill_around(surface, p, tri, k)),
        };
        match next.filter(|&(next, _)| allowed(next)) {
            Some((next, next_uv)) => start = Start::new(surface, next, next_uv),
            None => break,
        }
    }
    best.expect("at least one descent")
}

/// The snap of the point `x` at `uv` of `tri`.
fn snap_at(tri: usize, uv: DVec2, x: DVec3, p: DVec3) -> Snap {
    Snap {
        tri,
        v: uv.x,
        w: uv.y,
        point: x,
        distance: (x - p).length(),
        lower_bound: 0.0,
    }
}

/// The nearest point to `p` of the region of triangle `tri` (a local
/// minimum of the distance there), from `start`, and whether the solve
/// converged; no walking.
pub(crate) fn descend_within(
    surface: &Surface,
    p: DVec3,
    tri: usize,
    start: DVec2,
    region: &Region,
) -> (Snap, bool) {
    let start = Start::new(surface, tri, start);
    match descend_in(surface, p, start, region, None) {
        Exit::Stopped {
            uv, x, converged, ..
        } => (snap_at(tri, uv, x, p), converged),
        Exit::Carried(_) => unreachable!("only walks carry steps across edges"),
    }
}

/// Where a solve starts: a point of a triangle, evaluated in the
/// triangle's chart (by the neighbour that carried a step into it, or
/// afresh).
struct Start<'a> {
    tri: usize,
    chart: Chart<'a>,
    uv: DVec2,
    e: Evaluation,
}

impl<'a> Start<'a> {
    fn new(surface: &'a Surface, tri: usize, uv: DVec2) -> Start<'a> {
        let mut chart = surface.chart(tri).expect("a triangle of the net");
        let e = eval_at(&mut chart, uv);
        Start { tri, chart, uv, e }
    }
}

/// How a solve in one triangle ended.
enum Exit<'a> {
    /// At a minimiser of the region (or out of iterations): its parameters
    /// and point, the local edge the descent would cross if it rests on
    /// one, and whether it converged.
    Stopped {
        uv: DVec2,
        x: DVec3,
        leaving: Option<usize>,
        converged: bool,
    },
    /// A step went on across a smooth edge: the walk continues from its
    /// end in the neighbour.
    Carried(Start<'a>),
}

impl Exit<'_> {
    /// Stopped at a minimiser, converged.
    fn converged(uv: DVec2, x: DVec3, leaving: Option<usize>) -> Self {
        Exit::Stopped {
            uv,
            x,
            leaving,
            converged: true,
        }
    }
}

/// At a corner where the descent in `tri` stopped, the triangle around the
/// vertex into which the distance still decreases fastest, with the
/// vertex's parameters there: a minimum is not proven by one triangle of
/// the fan, and the edge walk only reaches the two beside it.
fn downhill_around(
    surface: &Surface,
    p: DVec3,
    tri: usize,
    corner: usize,
) -> Option<(usize, DVec2)> {
    let topo = surface.net().topology();
    let vertex = topo.triangles()[tri][corner];
    let mut steepest: Option<(f64, usize, DVec2)> = None;
    for &t in topo.fan(vertex as usize) {
        let t = t as usize;
        if t == tri {
            continue;
        }
        let k = topo.triangles()[t].iter().position(|&c| c == vertex)?;
        let at = CORNERS[k];
        let e = eval_at(&mut surface.chart(t).ok()?, at);
        let r = e.x - p;
        let g = DVec2::new(r.dot(e.xv), r.dot(e.xw));
        // The slope along each side from the corner, per unit of length on
        // the surface; the fan's sector is the cone of the two sides.
        for to in [CORNERS[(k + 1) % 3], CORNERS[(k + 2) % 3]] {
            let d = to - at;
            let length = (d.x * e.xv + d.y * e.xw).length();
            let slope = g.dot(d) / length;
            if slope < 0.0 && steepest.map_or(true, |s| slope < s.0) {
                steepest = Some((slope, t, at));
            }
        }
    }
    steepest.map(|(_, t, at)| (t, at))
}

/// Projected Newton inside one triangle, from an evaluated start: stops at
/// the minimiser found (see [`Exit::Stopped`]), or hands a step on to a
/// neighbour.
///
/// When walking (`walk` says into which triangles: the region is the whole
/// triangle and the caller goes on across edges), a step that leaves the triangle across a smooth edge is
/// carried into the neighbour ([`carry`]); if it cannot be (it reaches past
/// the neighbour too, or does not descend there), the step is cut short at
/// the edge and, if Newton still wants to cross, the solve ends there,
/// unconverged, for the caller to continue in the neighbour: sliding along
/// the edge to the constrained minimum first only to leave it costs several
/// evaluations. Across hard edges and boundaries, where the minimum may be
/// that constrained one, the solve converges on the edge as it does in a
/// cell.
fn descend_in<'a>(
    surface: &'a Surface,
    p: DVec3,
    start: Start<'a>,
    region: &Region,
    walk: Option<&Allowed>,
) -> Exit<'a> {
    let Start {
        tri,
        mut chart,
        mut uv,
        mut e,
    } = start;
    let stopped = Exit::converged;
    let mut f = 0.5 * (e.x - p).length_squared();
    // Whether the last step stopped short at the region's boundary.
    let mut clipped = false;
    for _ in 0..MAX_ITERATIONS {
        let r = e.x - p;
        let g = DVec2::new(r.dot(e.xv), r.dot(e.xw));
        let active = [0, 1, 2].map(|k| region.on_side(k, uv));
        let (newton, step) = descent_step(&e, r, g, region, active);
        let crossing = crossing_side(region, active, g);
        // Newton would leave across a smooth edge after a step cut short
        // there: the neighbour goes on.
        let newton_leaves = |k: usize| region.sides[k].0.dot(newton) < 0.0;
        let passable = |k: usize| walk.is_some_and(|a| is_passable(surface, tri, k, a));
        let hand_on = crossing.is_some_and(|k| newton_leaves(k) && passable(k));
        if clipped && hand_on {
            return stopped(uv, e.x, crossing);
        }
        let Some(step) = step.filter(|s| s.is_finite() && *s != DVec2::ZERO) else {
            return stopped(uv, e.x, crossing);
        };
        // The longest feasible multiple of the step, up to the whole step.
        let reach = step_reach(region, uv, step, 1.0);
        // Close to a minimiser Newton converges quadratically: a step this
        // small, or one whose predicted gain is lost in the round-off of f
        // (where comparing values of f tells nothing), leaves an error
        // below round-off, so take it and stop ([`last_step`]).
        let slope = g.dot(step).min(0.0);
        let length = reach * step.length();
        if length <= CONVERGED_STEP || -reach * slope <= f_round_off(e.x, p) {
            match last_step(&mut chart, p, region, &e, (uv, step), (reach, f)) {
                LastStep::Stretched(t_uv, t_f) => {
                    uv = t_uv;
                    e = eval_at(&mut chart, uv);
                    f = t_f;
                    continue;
                }
                LastStep::Stop(uv, x) => return stopped(uv, x, crossing),
            }
        }
        // Walking, a step that leaves the triangle across a smooth edge is
        // tried whole in the neighbour: stopping at the edge would cost an
        // evaluation there on each side.
        if let (Some(allowed), true) = (walk, reach < 1.0) {
            if let Some(next) = carry(surface, p, tri, uv + step, f + 1e-4 * slope, allowed) {
                return Exit::Carried(next);
            }
        }
        let moved = backtrack(&mut chart, p, region, (uv, step), (reach, f, slope));
        let Some((t_uv, t_e, t_f, alpha)) = moved.filter(|m| m.0 != uv) else {
            return stopped(uv, e.x, crossing); // no decrease left: round-off floor
        };
        (uv, e, f) = (t_uv, t_e, t_f);
        clipped = reach < 1.0 && alpha >= reach;
    }
    Exit::Stopped {
        uv,
        x: e.x,
        leaving: None,
        converged: false,
    }
}

/// The Newton step from the point with residual `r` and gradient `g` (the
/// Hessian shifted where it is not positive definite), and the step to
/// take: Newton's if it keeps to the `active` sides' half-planes, else the
/// best descent along one of them, if any.
fn descent_step(
    e: &Evaluation,
    r: DVec3,
    g: DVec2,
    region: &Region,
    active: [bool; 3],
) -> (DVec2, Option<DVec2>) {
    let (full, gauss_newton) = hessians(e, r);
    let (a, b, c) = if positive_definite(full) {
        full
    } else {
        shifted(full, gauss_newton)
    };
    let feasible = |s: DVec2| (0..3).all(|k| !active[k] || region.sides[k].0.dot(s) >= 0.0);
    let newton = solve2(a, b, c, -g);
    let step = if feasible(newton) {
        Some(newton)
    } else {
        // Along an active edge, in whichever direction descends.
        (0..3)
            .filter(|&k| active[k])
            .filter_map(|k| {
                let d = DVec2::new(region.sides[k].0.y, -region.sides[k].0.x);
                let along = |(a, b, c): (f64, f64, f64)| {
                    d.x * d.x * a + 2.0 * d.x * d.y * b + d.y * d.y * c
                };
                let curvature = Some(along(full))
                    .filter(|&k| k > 0.0)
                    .unwrap_or_else(|| along(gauss_newton).max(f64::MIN_POSITIVE));
                let s = -g.dot(d) / curvature * d;
                (feasible(s) && g.dot(s) < 0.0).then_some(s)
            })
            .min_by(|s, t| g.dot(*s).total_cmp(&g.dot(*t)))
    };
    (newton, step)
}

/// The side the descent would cross, when the point rests on exactly one
/// side and the gradient points out through it.
fn crossing_side(region: &Region, active: [bool; 3], g: DVec2) -> Option<usize> {
    match active {
        [true, false, false] => Some(0),
        [false, true, false] => Some(1),
        [false, false, true] => Some(2),
        _ => None,
    }
    .filter(|&k| region.sides[k].0.dot(g) > 0.0)
}

/// What [`last_step`] decided.
enum LastStep {
    /// The step was stretched to this point and value: go on from there.
    Stretched(DVec2, f64),
    /// Stop at this point (parameters and position).
    Stop(DVec2, DVec3),
}

/// The last step of a converged solve, `alpha` times `step` from `uv`
/// where f is `f`: taken if it loses no more than round-off (its end is
/// the better stationary point even where the distances tie to the last
/// bits). Unless the point is not stationary at
/// all: next to an irregular vertex the derivatives blow up or vanish and
/// Newton's steps shrink while the distance still falls — there the step
/// is stretched and the solve goes on.
fn last_step(
    chart: &mut Chart,
    p: DVec3,
    region: &Region,
    e: &Evaluation,
    (uv, step): (DVec2, DVec2),
    (alpha, f): (f64, f64),
) -> LastStep {
    let length = alpha * step.length();
    let noise = f_round_off(e.x, p);
    let r = e.x - p;
    let at_corner = CORNERS.iter().any(|c| (uv - *c).abs().max_element() < 1e-3);
    if at_corner && !is_stationary(e, r) {
        let room = step_reach(region, uv, step, f64::INFINITY);
        let stretched = (room > alpha)
            .then(|| stretch(chart, p, region, (uv, step), (alpha, room), f))
            .flatten();
        if let Some((t_uv, t_f)) = stretched {
            return LastStep::Stretched(t_uv, t_f);
        }
    }
    if length <= STEP_TOLERANCE {
        return LastStep::Stop(uv, e.x);
    }
    let t_uv = region.clamp(uv + alpha * step);
    let t_x = chart.point(t_uv.x, t_uv.y).expect("inside");
    if 0.5 * (t_x - p).length_squared() <= f + noise {
        return LastStep::Stop(t_uv, t_x);
    }
    LastStep::Stop(uv, e.x)
}

/// Backtracks from the multiple `alpha` of `step` at `uv`, halving, until
/// f falls enough below `f` for the `slope` (Armijo): the point, its
/// evaluation, its f and the multiple taken; `None` if no halving does.
fn backtrack(
    chart: &mut Chart,
    p: DVec3,
    region: &Region,
    (uv, step): (DVec2, DVec2),
    (mut alpha, f, slope): (f64, f64, f64),
) -> Option<(DVec2, Evaluation, f64, f64)> {
    for _ in 0..MAX_HALVINGS {
        let t_uv = region.clamp(uv + alpha * step);
        let t_e = eval_at(chart, t_uv);
        let t_f = 0.5 * (t_e.x - p).length_squared();
        if t_f <= f + 1e-4 * alpha * slope {
            return Some((t_uv, t_e, t_f, alpha));
        }
        alpha *= 0.5;
    }
    None
}

/// The longest multiple t ≤ `cap` of `step` with uv + t·step in the
/// region. Sides that the step does not reach before `cap` cost no
/// division: near a minimiser, with `cap` the whole step, that is all of
/// them.
fn step_reach(region: &Region, uv: DVec2, step: DVec2, cap: f64) -> f64 {
    let mut reach = cap;
    for (n, off) in region.sides {
        let rate = n.dot(step);
        let slack = (n.dot(uv) - off).max(0.0);
        if rate * reach < -slack {
            reach = slack / -rate;
        }
    }
    reach
}

/// The point at `target` (parameters of `tri` beyond one of its smooth
/// edges), evaluated in the triangle across that edge, if it lies in it
/// and f = ½|X − p|² there is at most `enough`.
///
/// Laid out as a parallelogram ([`across_edge`]), the two triangles share
/// one smooth parametrisation (the subdivision of one is that of the other
/// continued), so a Newton step of one is a Newton step of the other —
/// away from special vertices, and on surfaces without a displacement
/// field, which kinks at every edge; the descent test guards those.
fn carry<'a>(
    surface: &'a Surface,
    p: DVec3,
    tri: usize,
    target: DVec2,
    enough: f64,
    allowed: &Allowed,
) -> Option<Start<'a>> {
    let here = SurfacePoint {
        tri: tri as u32,
        v: target.x,
        w: target.y,
    };
    let weights = here.weights();
    // Beyond exactly one side: the one opposite the negative weight.
    let mut negative = (0..3).filter(|&i| weights[i] < 0.0);
    let (Some(far), None) = (negative.next(), negative.next()) else {
        return None;
    };
    let edge = (far + 1) % 3; // local edge k joins corners k and k + 1
    if !is_passable(surface, tri, edge, allowed) {
        return None;
    }
    let there = across_edge(surface.net().topology(), here, edge)?;
    if there.weights().iter().any(|&b| b < 0.0) {
        return None; // beyond the neighbour as well
    }
    let start = Start::new(
        surface,
        there.tri as usize,
        Region::WHOLE.clamp(DVec2::new(there.v, there.w)),
    );
    (0.5 * (start.e.x - p).length_squared() <= enough).then_some(start)
}

/// The round-off of f = ½|x − p|² as evaluated: that of the point, times
/// the distance. Differences of f below it are noise.
fn f_round_off(x: DVec3, p: DVec3) -> f64 {
    let eps = POINT_ROUND_OFF * x.abs().max(p.abs()).max_element();
    eps * ((x - p).length() + eps)
}

/// Whether local edge `k` of `tri` joins it smoothly (neither hard nor on
/// the boundary) to a neighbour a walk may enter.
fn is_passable(surface: &Surface, tri: usize, k: usize, allowed: &Allowed) -> bool {
    let net = surface.net();
    let topo = net.topology();
    let edge = topo.triangle_edges()[tri][k] as usize;
    let [a, b] = topo.edge_triangles()[edge];
    let other = if a as usize == tri { b } else { a };
    !net.features().is_hard_edge(edge) && allowed(other as usize)
}

/// Whether the residual r = X − p is normal to the surface (within a
/// millionth of a radian): nearly a stationary point of the distance,
/// whatever the parametrisation does.
fn is_stationary(e: &Evaluation, r: DVec3) -> bool {
    let Some(n) = e.normal() else {
        return true;
    };
    let tangential = r - r.dot(n) * n;
    tangential.length() <= 1e-6 * r.length()
}

/// Doubles a step along `step` from multiple `alpha` (up to `reach`, the
/// region's boundary) while the distance keeps falling; the stretched point
/// and its f, if it gains on both the start and the plain step.
fn stretch(
    chart: &mut Chart,
    p: DVec3,
    region: &Region,
    (uv, step): (DVec2, DVec2),
    (alpha, reach): (f64, f64),
    f: f64,
) -> Option<(DVec2, f64)> {
    let f_at = |chart: &mut Chart, t: f64| {
        let at = region.clamp(uv + t * step);
        let x = chart.point(at.x, at.y).expect("clamped inside");
        0.5 * (x - p).length_squared()
    };
    let (mut t, mut best) = (alpha, f_at(chart, alpha));
    for _ in 0..64 {
        let longer = (2.0 * t).min(reach);
        if longer <= t {
            break;
        }
        let f_longer = f_at(chart, longer);
        if f_longer >= best {
            break;
        }
        (t, best) = (longer, f_longer);
    }
    (t > alpha && best < f).then(|| (region.clamp(uv + t * step), best))
}

/// The Hessian of ½|X − p|² (JᵀJ plus the curvature terms r · X₍₎) and
/// its Gauss–Newton part JᵀJ, which is positive semi-definite: where the
/// full one is not (far or concave-side points), the Gauss–Newton matrix
/// still gives descent directions.
fn hessians(e: &Evaluation, r: DVec3) -> ((f64, f64, f64), (f64, f64, f64)) {
    let gn = (e.xv.dot(e.xv), e.xv.dot(e.xw), e.xw.dot(e.xw));
    let full = (
        gn.0 + r.dot(e.xvv),
        gn.1 + r.dot(e.xvw),
        gn.2 + r.dot(e.xww),
    );
    (full, gn)
}

/// Where the Hessian H is not positive definite (far points, concave
/// regions, near a focal point), H + μ G with G = JᵀJ the metric, shifted
/// just enough that its smallest eigenvalue relative to G is ¼. Plain
/// Gauss–Newton (G alone) ignores the curvature altogether: across a stiff
/// direction it overshoots and along a soft one it crawls, and a far point
/// over a bumpy scan then zig-zags for dozens of steps.
fn shifted(h: (f64, f64, f64), g: (f64, f64, f64)) -> (f64, f64, f64) {
    // det(H − λ G) = 0, a quadratic in λ.
    let qa = g.0 * g.2 - g.1 * g.1;
    let qb = -(h.0 * g.2 + h.2 * g.0 - 2.0 * h.1 * g.1);
    let qc = h.0 * h.2 - h.1 * h.1;
    if qa.is_nan() || qa <= 0.0 {
        return g;
    }
    let lowest = (-qb - (qb * qb - 4.0 * qa * qc).max(0.0).sqrt()) / (2.0 * qa);
    let mu = (0.25 - lowest).max(0.0);
    if !mu.is_finite() {
        return g;
    }
    (h.0 + mu * g.0, h.1 + mu * g.1, h.2 + mu * g.2)
}

fn positive_definite((a, b, c): (f64, f64, f64)) -> bool {
    a > 0.0 && a * c - b * b > 1e-12 * (a * c).abs()
}

/// Solves [[a b] [b c]] x = rhs (falls back to a gradient step if singular).
fn solve2(a: f64, b: f64, c: f64, rhs: DVec2) -> DVec2 {
    let det = a * c - b * b;
    if det.abs() > 1e-300 && det.is_finite() {
        DVec2::new(c * rhs.x - b * rhs.y, a * rhs.y - b * rhs.x) / det
    } else {
        let scale = a.max(c).max(f64::MIN_POSITIVE);
        rhs / scale
    }
}

/// The point `uv` of local edge `edge` of `tri` seen from the triangle
/// across that edge ([`across_edge`]), or None on a boundary.
fn across(surface: &Surface, tri: usize, edge: usize, uv: DVec2) -> Option<(usize, DVec2)> {
    let p = SurfacePoint {
        tri: tri as u32,
        v: uv.x,
        w: uv.y,
    };
    let q = across_edge(surface.net().topology(), p, edge)?;
    Some((q.tri as usize, Region::WHOLE.clamp(DVec2::new(q.v, q.w))))
}
