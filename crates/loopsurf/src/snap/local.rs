//! The local solve: the closest point of one triangle's patch (or, walking
//! across edges, of the surface near a start) by projected Newton on
//! f(v, w) = ½ |X(v, w) − p|² over the parameter triangle.
//!
//! The full Hessian (with the curvature terms r · Xvv …) is used where it
//! is positive definite, so convergence near a minimiser is quadratic; where
//! it is not (far points, concave regions) the Gauss–Newton matrix JᵀJ
//! keeps every step a descent step. Steps are clipped to the triangle; on
//! an edge or at a corner whose constraint is binding, the step is restricted
//! to the edge, so minima on boundaries, hard edges and corners are found as
//! exactly as interior ones.

use crate::surface::{Evaluation, Surface};
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
}

const MAX_ITERATIONS: usize = 60;
const MAX_HOPS: usize = 64;
/// Parameter steps below this are round-off: converged.
const STEP_TOLERANCE: f64 = 1e-15;
/// A Newton step this short is the last one needed (the parameter domain
/// has size 1; the error after it is of the order of its square).
const CONVERGED_STEP: f64 = 1e-7;
const MAX_HALVINGS: usize = 30;

/// The three constraints of the parameter triangle as n · (v, w) ≥ c,
/// indexed by the corner they are opposite to.
const CONSTRAINTS: [(DVec2, f64); 3] = [
    (DVec2::new(-1.0, -1.0), -1.0), // v + w ≤ 1: the edge c1–c2
    (DVec2::new(0.0, 1.0), 0.0),    // w ≥ 0: the edge c0–c1
    (DVec2::new(1.0, 0.0), 0.0),    // v ≥ 0: the edge c2–c0
];

/// Local edge index (edge i joins corners i and i + 1) of constraint k.
fn edge_of(k: usize) -> usize {
    [1, 0, 2][k]
}

/// Evaluates, moving a hair's breadth off a special vertex, where the
/// parametrisation is singular and all derivatives are reported as zero.
fn eval_at(surface: &Surface, tri: usize, uv: DVec2) -> (DVec2, Evaluation) {
    EVALS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let e = surface
        .eval(tri, uv.x, uv.y)
        .expect("parameters kept inside the triangle");
    if !e.at_special_vertex {
        return (uv, e);
    }
    let centre = DVec2::splat(1.0 / 3.0);
    let nudged = uv + 1e-9 * (centre - uv);
    let mut moved = surface.eval(tri, nudged.x, nudged.y).expect("inside");
    moved.x = e.x; // the exact point; derivatives from a hair away
    (uv, moved)
}

/// Minimises the distance to `p` starting from (tri, v, w). With `walk`, a
/// minimum on an interior edge whose descent continues across it moves into
/// the neighbouring triangle; without it the search stays in `tri`.
pub(crate) fn descend(surface: &Surface, p: DVec3, tri: usize, v: f64, w: f64, walk: bool) -> Snap {
    let (mut tri, mut uv) = (tri, DVec2::new(v, w));
    let mut hops = 0;
    loop {
        let (end, leaving) = descend_in(surface, p, tri, uv);
        match leaving {
            Some(edge) if walk && hops < MAX_HOPS => match across(surface, tri, edge, end) {
                Some((next, next_uv)) => {
                    tri = next;
                    uv = next_uv;
                    hops += 1;
                }
                None => return snap_at(surface, p, tri, end),
            },
            _ => return snap_at(surface, p, tri, end),
        }
    }
}

fn snap_at(surface: &Surface, p: DVec3, tri: usize, uv: DVec2) -> Snap {
    let x = surface.eval(tri, uv.x, uv.y).expect("inside").x;
    Snap {
        tri,
        v: uv.x,
        w: uv.y,
        point: x,
        distance: (x - p).length(),
    }
}

/// Projected Newton inside one triangle. Returns the minimiser found and,
/// if it sits on one edge and the descent direction crosses it, that local
/// edge.
fn descend_in(surface: &Surface, p: DVec3, tri: usize, start: DVec2) -> (DVec2, Option<usize>) {
    let (mut uv, mut e) = eval_at(surface, tri, start);
    let mut f = 0.5 * (e.x - p).length_squared();
    for _ in 0..MAX_ITERATIONS {
        let r = e.x - p;
        let g = DVec2::new(r.dot(e.xv), r.dot(e.xw));
        let (full, gauss_newton) = hessians(&e, r);
        let (a, b, c) = if positive_definite(full) {
            full
        } else {
            gauss_newton
        };
        let active: Vec<usize> = (0..3)
            .filter(|&k| CONSTRAINTS[k].0.dot(uv) - CONSTRAINTS[k].1 <= 1e-15)
            .collect();
        let feasible = |s: DVec2| active.iter().all(|&k| CONSTRAINTS[k].0.dot(s) >= 0.0);
        let newton = solve2(a, b, c, -g);
        let step = if feasible(newton) {
            Some(newton)
        } else {
            // Along an active edge, in whichever direction descends.
            active
                .iter()
                .filter_map(|&k| {
                    let d = DVec2::new(CONSTRAINTS[k].0.y, -CONSTRAINTS[k].0.x);
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
        // The edge the descent would cross, when the point rests on one edge.
        let crossing = match active[..] {
            [k] if CONSTRAINTS[k].0.dot(g) > 0.0 => Some(edge_of(k)),
            _ => None,
        };
        let Some(step) = step.filter(|s| s.is_finite() && s.length() > STEP_TOLERANCE) else {
            return (uv, crossing);
        };
        // Longest feasible fraction of the step.
        let mut alpha: f64 = 1.0;
        for (n, off) in CONSTRAINTS {
            let rate = n.dot(step);
            if rate < 0.0 {
                alpha = alpha.min(((off - n.dot(uv)) / rate).max(0.0));
            }
        }
        // Close to a minimiser Newton converges quadratically: a step this
        // small, or one whose predicted gain is at round-off level, leaves
        // an error below round-off, so take it and stop.
        let slope = g.dot(step).min(0.0);
        if alpha * step.length() <= CONVERGED_STEP || -alpha * slope <= 1e-14 * f {
            let (t_uv, t_e) = eval_at(surface, tri, clamp(uv + alpha * step));
            if (t_e.x - p).length_squared() <= 2.0 * f {
                return (t_uv, crossing);
            }
            return (uv, crossing);
        }
        // Backtrack until f decreases enough (Armijo).
        let mut moved = None;
        for _ in 0..MAX_HALVINGS {
            let (t_uv, t_e) = eval_at(surface, tri, clamp(uv + alpha * step));
            let t_f = 0.5 * (t_e.x - p).length_squared();
            if t_f <= f + 1e-4 * alpha * slope {
                moved = Some((t_uv, t_e, t_f));
                break;
            }
            alpha *= 0.5;
        }
        let Some((t_uv, t_e, t_f)) = moved.filter(|m| m.0 != uv) else {
            return (uv, crossing); // no decrease left: round-off floor
        };
        (uv, e, f) = (t_uv, t_e, t_f);
    }
    (uv, None)
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

/// The nearest point of the parameter triangle (round-off repair).
fn clamp(uv: DVec2) -> DVec2 {
    let (v, w) = (uv.x.max(0.0), uv.y.max(0.0));
    let excess = (v + w - 1.0).max(0.0);
    DVec2::new((v - excess / 2.0).max(0.0), (w - excess / 2.0).max(0.0))
}

/// The same surface point seen from the triangle across local edge `edge`,
/// or None on a boundary.
fn across(surface: &Surface, tri: usize, edge: usize, uv: DVec2) -> Option<(usize, DVec2)> {
    let topo = surface.net().topology();
    let e = topo.triangle_edges()[tri][edge] as usize;
    if topo.is_boundary_edge(e) {
        return None;
    }
    let [t0, t1] = topo.edge_triangles()[e];
    let next = if t0 as usize == tri { t1 } else { t0 } as usize;
    let here = topo.triangles()[tri];
    let there = topo.triangles()[next];
    // Barycentric weights of the point in `tri`, moved to `next` by vertex.
    let weights = [1.0 - uv.x - uv.y, uv.x, uv.y];
    let mut moved = [0.0; 3];
    for (k, &corner) in here.iter().enumerate() {
        if let Some(j) = there.iter().position(|&c| c == corner) {
            moved[j] = weights[k];
        }
    }
    Some((next, clamp(DVec2::new(moved[1], moved[2]))))
}

pub static EVALS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
