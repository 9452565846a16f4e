//! Where a triangle mesh crosses itself: the pairs of triangles that meet
//! anywhere but in the vertices and edges they share. A volume mesher
//! (TetGen, gmsh) refuses a surface with one such pair, so a mesh that is
//! to bound a volume is checked with this before it is handed on.
//!
//! **Exact.** Every decision is a sign of Shewchuk's adaptive orientation
//! predicates (the `robust` crate): a pair of triangles a hair apart, the
//! common case next to a fold, is told from a pair that touches. The
//! semantics are those of CGAL's `self_intersections`: triangles that
//! share an edge cross when they fold onto each other (coplanar, on one
//! side of the edge); triangles that share a vertex cross when they meet
//! anywhere else; other triangles cross when they meet at all, touching
//! included (two vertices at one point are a crossing).
//!
//! **Fast.** Candidate pairs come from a bounding-box tree over the
//! triangles, queried in parallel; the answer is sorted, so it is the same
//! for any thread count. Most candidates are neighbours, which a
//! floating-point test with a wide margin tells apart first (a side of
//! one whose plane has the other beyond it); only what it cannot settle
//! goes to the exact predicates, whose slow path coplanar neighbours on a
//! flat face would take (fandisk's 343 386 triangles at 0.4%: 0.51 s on
//! one thread, 1.44 s without it).

use super::{area_normal, largest_axis};
use glam::DVec3;
use rayon::prelude::*;
use robust::{orient2d, orient3d, Coord, Coord3D};

/// The pairs `[i, j]`, i < j, of `triangles` (indices into `points`) that
/// cross (see the module doc), in ascending order.
pub fn crossings(points: &[DVec3], triangles: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let boxes: Vec<Box3> = triangles
        .iter()
        .map(|t| Box3::of(t.map(|v| points[v as usize])))
        .collect();
    let tree = BoxTree::new(&boxes);
    let mut pairs: Vec<[u32; 2]> = (0..triangles.len())
        .into_par_iter()
        .flat_map_iter(|i| {
            let mut found = Vec::new();
            tree.overlapping(&boxes[i], |j| {
                if j > i && cross(points, triangles[i], triangles[j]) {
                    found.push([i as u32, j as u32]);
                }
            });
            found
        })
        .collect();
    pairs.sort_unstable();
    pairs
}

/// Whether triangles `s` and `t` (vertex ids into `points`) cross.
pub(crate) fn cross(points: &[DVec3], s: [u32; 3], t: [u32; 3]) -> bool {
    let p = |v: u32| points[v as usize];
    // The corners the triangles share, as (index in s, index in t): most
    // pairs the tree offers are neighbours, so no allocation here.
    let mut shared = [(0, 0); 9];
    let mut count = 0;
    for (i, a) in s.iter().enumerate() {
        for (j, b) in t.iter().enumerate() {
            if a == b {
                shared[count] = (i, j);
                count += 1;
            }
        }
    }
    match shared[..count] {
        [] => {
            let (a, b) = (s.map(p), t.map(p));
            let sides = |x: [DVec3; 3], y: [DVec3; 3]| {
                let normal = area_normal(x);
                (0..3).any(|k| side_separates(x, normal, k, &y))
            };
            if sides(a, b) || sides(b, a) {
                return false;
            }
            if strictly_beside(a, &b) || strictly_beside(b, &a) {
                return false;
            }
            edges(a).any(|(x, y)| segment_meets_triangle(x, y, b))
                || edges(b).any(|(x, y)| segment_meets_triangle(x, y, a))
        }
        // Beyond their common corner the triangles meet only where one's
        // opposite side meets the other (the planes' common line runs
        // through the corner; whichever triangle ends nearer on it ends on
        // its opposite side, inside the other).
        [(i, j)] => {
            let (a, b) = (s.map(p), t.map(p));
            // Either's other corners strictly on one side of the other's
            // plane: the planes' common line leaves that triangle at once.
            let others = |x: [DVec3; 3], k: usize| [x[(k + 1) % 3], x[(k + 2) % 3]];
            // A side through the common corner that has the other
            // triangle's other corners beyond it (neighbours in a fan,
            // flat or not), decided in floating point with a margin.
            let sides = |x: [DVec3; 3], k: usize, y: &[DVec3; 2]| {
                let normal = area_normal(x);
                side_separates(x, normal, k, y) || side_separates(x, normal, (k + 2) % 3, y)
            };
            if sides(a, i, &others(b, j)) || sides(b, j, &others(a, i)) {
                return false;
            }
            if strictly_beside(a, &others(b, j)) || strictly_beside(b, &others(a, i)) {
                return false;
            }
            segment_meets_triangle(a[(i + 1) % 3], a[(i + 2) % 3], b)
                || segment_meets_triangle(b[(j + 1) % 3], b[(j + 2) % 3], a)
        }
        // Beyond their common edge they meet only folded flat onto it.
        [(i0, _), (i1, _)] => {
            let k = 3 - i0 - i1;
            let (x, y) = (p(s[i0]), p(s[i1]));
            let (a, b) = (
                p(s[k]),
                p(t.into_iter().find(|v| !s.contains(v)).unwrap_or(t[0])),
            );
            // On opposite sides of the edge (as in any fan; flat faces
            // would otherwise take the exact predicates' slow path):
            // folded flat onto each other their normals would agree.
            let (n1, n2) = ((y - x).cross(a - x), (y - x).cross(b - x));
            if n1.dot(n2) < -MARGIN * n1.length() * n2.length() {
                return false;
            }
            if orient3d(c3(x), c3(y), c3(a), c3(b)) != 0.0 {
                return false;
            }
            let drop = dominant_axis(x, y, a);
            let side = |q| orient2d(c2(x, drop), c2(y, drop), c2(q, drop));
            side(a) * side(b) > 0.0
        }
        // The same triangle twice.
        _ => true,
    }
}

/// The share of a product of lengths that a floating-point sign test must
/// clear to be trusted: far above the few units of round-off in the
/// last place that a cross and a dot product make.
const MARGIN: f64 = 1e-9;

/// Whether the plane through side k of triangle `t` (from corner k to the
/// next), square to `t` (whose [`area_normal`] is `normal`), has all of
/// `points` strictly on the side away from its third corner: then `t` (on
/// that corner's side, or on the plane) and the triangle of those points
/// meet at most in what lies on that plane. A floating-point test that
/// answers yes only with [`MARGIN`] to spare, so never wrongly; no
/// otherwise (then the exact tests decide).
fn side_separates(t: [DVec3; 3], normal: DVec3, k: usize, points: &[DVec3]) -> bool {
    let (c, u, w) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
    let m = (u - c).cross(normal);
    let scale = m.length();
    let toward = m.dot(w - c);
    if !(toward.abs() > MARGIN * scale * (w - c).length()) {
        return false;
    }
    points.iter().all(|&x| {
        let away = -toward.signum() * m.dot(x - c);
        away > MARGIN * scale * (x - c).length()
    })
}

/// Whether `points` all lie strictly on one side of triangle `t`'s plane
/// (false for a triangle without area, whose plane is not defined).
fn strictly_beside(t: [DVec3; 3], points: &[DVec3]) -> bool {
    let side = |q: &DVec3| orient3d(c3(t[0]), c3(t[1]), c3(t[2]), c3(*q));
    let mut sides = points.iter().map(side);
    match sides.next() {
        Some(first) if first > 0.0 => sides.all(|o| o > 0.0),
        Some(first) if first < 0.0 => sides.all(|o| o < 0.0),
        _ => false,
    }
}

/// The three sides of a triangle.
fn edges(t: [DVec3; 3]) -> impl Iterator<Item = (DVec3, DVec3)> {
    (0..3).map(move |k| (t[k], t[(k + 1) % 3]))
}

/// Whether the closed segment pq meets the closed triangle `t`.
fn segment_meets_triangle(p: DVec3, q: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let (op, oq) = (
        orient3d(c3(a), c3(b), c3(c), c3(p)),
        orient3d(c3(a), c3(b), c3(c), c3(q)),
    );
    if op == 0.0 && oq == 0.0 {
        return coplanar_segment_meets_triangle(p, q, [a, b, c]);
    }
    if (op > 0.0 && oq > 0.0) || (op < 0.0 && oq < 0.0) {
        return false;
    }
    // The segment reaches the plane: where it does lies in the triangle
    // when the line pq passes all three sides the same way round.
    let sides = [(a, b), (b, c), (c, a)].map(|(x, y)| orient3d(c3(p), c3(q), c3(x), c3(y)));
    !(sides.iter().any(|&o| o < 0.0) && sides.iter().any(|&o| o > 0.0))
}

/// [`segment_meets_triangle`] when all five points lie in one plane:
/// in 2D, dropping the coordinate that plane is steepest along.
fn coplanar_segment_meets_triangle(p: DVec3, q: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    // A triangle with no area: any axis the segment does not run along.
    let drop = dominant_axis(a, b, c).or(Some(least_axis(q - p)));
    let [p, q, a, b, c] = [p, q, a, b, c].map(|x| c2(x, drop));
    let inside = |x: Coord<f64>| {
        let o = [(a, b), (b, c), (c, a)].map(|(u, v)| orient2d(u, v, x));
        !(o.iter().any(|&s| s < 0.0) && o.iter().any(|&s| s > 0.0))
    };
    inside(p)
        || inside(q)
        || [(a, b), (b, c), (c, a)]
            .iter()
            .any(|&(u, v)| segments_meet_2d(p, q, u, v))
}

/// Whether the closed segments pq and uv of the plane meet.
fn segments_meet_2d(p: Coord<f64>, q: Coord<f64>, u: Coord<f64>, v: Coord<f64>) -> bool {
    let (d1, d2) = (orient2d(p, q, u), orient2d(p, q, v));
    let (d3, d4) = (orient2d(u, v, p), orient2d(u, v, q));
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return true;
    }
    let within = |x: Coord<f64>, y: Coord<f64>, z: Coord<f64>| {
        z.x >= x.x.min(y.x) && z.x <= x.x.max(y.x) && z.y >= x.y.min(y.y) && z.y <= x.y.max(y.y)
    };
    (d1 == 0.0 && within(p, q, u))
        || (d2 == 0.0 && within(p, q, v))
        || (d3 == 0.0 && within(u, v, p))
        || (d4 == 0.0 && within(u, v, q))
}

/// The axis the normal of triangle (a, b, c) is largest along: dropping
/// it projects the triangle without flattening it. `None` when the
/// triangle has no area in floating point.
fn dominant_axis(a: DVec3, b: DVec3, c: DVec3) -> Option<usize> {
    let n = area_normal([a, b, c]).abs();
    (n != DVec3::ZERO).then(|| largest_axis(n))
}

/// The axis a direction is smallest along (dropping it keeps a segment a
/// segment).
fn least_axis(d: DVec3) -> usize {
    largest_axis(-d.abs())
}

fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// `p` with coordinate `drop` left out (the first two kept when `None`).
fn c2(p: DVec3, drop: Option<usize>) -> Coord<f64> {
    match drop {
        Some(0) => Coord { x: p.y, y: p.z },
        Some(1) => Coord { x: p.z, y: p.x },
        _ => Coord { x: p.x, y: p.y },
    }
}

/// An axis-aligned box, closed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Box3 {
    lo: DVec3,
    hi: DVec3,
}

impl Box3 {
    pub(crate) fn of(t: [DVec3; 3]) -> Box3 {
        Box3 {
            lo: t[0].min(t[1]).min(t[2]),
            hi: t[0].max(t[1]).max(t[2]),
        }
    }

    fn union(&self, other: &Box3) -> Box3 {
        Box3 {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }

    pub(crate) fn overlaps(&self, other: &Box3) -> bool {
        self.lo.cmple(other.hi).all() && other.lo.cmple(self.hi).all()
    }
}

/// Items per leaf of [`BoxTree`].
const LEAF: usize = 4;

/// Subtrees of more items than this are built on two threads.
const SIDE_BY_SIDE: usize = 1 << 14;

/// A bounding-box tree over boxes, split at the median of their centres
/// along the longest side: nodes in depth-first order, each with its box
/// and its range of `order` (a leaf) or its two children.
pub(crate) struct BoxTree {
    order: Vec<usize>,
    nodes: Vec<Node>,
}

struct Node {
    bounds: Box3,
    /// Items `order[start..end]` below this node.
    start: usize,
    end: usize,
    /// The second child's index (the first follows this node); 0 for a leaf.
    second: usize,
}

/// The nodes over `order` (which start at item `start` of the whole
/// order), each node's second child counted from the first node. The
/// halves of a large subtree are built side by side and joined: every
/// step is the one a serial build takes, so the tree is the same bits on
/// any thread count (the union of boxes is exact in any order).
fn subtree(boxes: &[Box3], order: &mut [usize], start: usize) -> Vec<Node> {
    if order.len() <= SIDE_BY_SIDE {
        let mut nodes = Vec::with_capacity(2 * order.len() / LEAF + 1);
        build(boxes, order, start, &mut nodes);
        return nodes;
    }
    let (bounds, mid) = split(boxes, order);
    let (low, high) = order.split_at_mut(mid);
    let (first, second) = rayon::join(
        || subtree(boxes, low, start),
        || subtree(boxes, high, start + mid),
    );
    let shift = 1 + first.len();
    let mut nodes = Vec::with_capacity(shift + second.len());
    nodes.push(Node {
        bounds,
        start,
        end: start + order.len(),
        second: shift,
    });
    let moved = |offset: usize| {
        move |n: Node| Node {
            second: if n.second == 0 { 0 } else { n.second + offset },
            ..n
        }
    };
    nodes.extend(first.into_iter().map(moved(1)));
    nodes.extend(second.into_iter().map(moved(shift)));
    nodes
}

/// [`subtree`] on one thread, pushed onto `nodes`; the index of its root.
fn build(boxes: &[Box3], order: &mut [usize], start: usize, nodes: &mut Vec<Node>) -> usize {
    let at = nodes.len();
    let (bounds, mid) = split(boxes, order);
    nodes.push(Node {
        bounds,
        start,
        end: start + order.len(),
        second: 0,
    });
    if order.len() > LEAF {
        let (low, high) = order.split_at_mut(mid);
        build(boxes, low, start, nodes);
        nodes[at].second = build(boxes, high, start + mid, nodes);
    }
    at
}

/// The bounds of the boxes `order` names, and where a node over them
/// splits: `order` rearranged about its median centre along the bounds'
/// longest side (left as it is for a leaf).
fn split(boxes: &[Box3], order: &mut [usize]) -> (Box3, usize) {
    let bounds = order
        .iter()
        .map(|&i| boxes[i])
        .reduce(|a, b| a.union(&b))
        .unwrap_or(Box3 {
            lo: DVec3::ZERO,
            hi: DVec3::ZERO,
        });
    let mid = order.len() / 2;
    if order.len() > LEAF {
        let axis = largest_axis(bounds.hi - bounds.lo);
        let centre = |i: &usize| boxes[*i].lo[axis] + boxes[*i].hi[axis];
        order.select_nth_unstable_by(mid, |a, b| centre(a).total_cmp(&centre(b)));
    }
    (bounds, mid)
}

impl BoxTree {
    pub(crate) fn new(boxes: &[Box3]) -> BoxTree {
        let mut order: Vec<usize> = (0..boxes.len()).collect();
        let nodes = if boxes.is_empty() {
            Vec::new()
        } else {
            subtree(boxes, &mut order, 0)
        };
        BoxTree { order, nodes }
    }

    /// Calls `found` with every item whose box overlaps `query`.
    pub(crate) fn overlapping(&self, query: &Box3, mut found: impl FnMut(usize)) {
        // Depth-first: the stack holds at most one node per level, and a
        // median split of u32-many items has fewer than 64 levels.
        let mut stack = [0usize; 64];
        let mut depth = 1;
        while depth > 0 {
            depth -= 1;
            let n = stack[depth];
            let Some(node) = self.nodes.get(n) else {
                continue;
            };
            if !node.bounds.overlaps(query) {
                continue;
            }
            if node.second == 0 {
                self.order[node.start..node.end]
                    .iter()
                    .for_each(|&i| found(i));
            } else {
                stack[depth] = node.second;
                stack[depth + 1] = n + 1;
                depth += 2;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pairs(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> Vec<[u32; 2]> {
        let points: Vec<DVec3> = points.iter().map(|&p| DVec3::from(p)).collect();
        crossings(&points, triangles)
    }

    #[test]
    fn apart_touching_and_piercing() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            // A triangle standing on the first, its foot at (0.25, 0.25, 0).
            [0.25, 0.25, 0.0],
            [0.25, 0.25, 1.0],
            [0.5, 0.5, 1.0],
            // The same, lifted a hair above.
            [0.25, 0.25, 1e-300],
            // The same, pushed through.
            [0.25, 0.25, -1e-300],
        ];
        assert_eq!(pairs(&p, &[[0, 1, 2], [3, 4, 5]]), vec![[0, 1]]);
        assert!(pairs(&p, &[[0, 1, 2], [6, 4, 5]]).is_empty());
        assert_eq!(pairs(&p, &[[0, 1, 2], [7, 4, 5]]), vec![[0, 1]]);
    }

    #[test]
    fn neighbours_cross_only_when_folded_onto_each_other() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],   // across the edge 1–2: flat, no crossing
            [0.2, 0.2, 0.0],   // folded back onto triangle 0 across 1–2
            [1.0, 1.0, 1e-12], // folded up, barely
        ];
        assert!(pairs(&p, &[[0, 1, 2], [2, 1, 3]]).is_empty());
        assert_eq!(pairs(&p, &[[0, 1, 2], [2, 1, 4]]), vec![[0, 1]]);
        assert!(pairs(&p, &[[0, 1, 2], [2, 1, 5]]).is_empty());
    }

    #[test]
    fn a_shared_corner_crosses_only_where_the_triangles_meet_elsewhere() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            // Through the first triangle from its corner 0 upwards: apart.
            [0.5, 0.0, 1.0],
            [0.0, 0.5, 1.0],
            // Down through it from corner 0: it cuts the first triangle
            // along a segment from the corner.
            [0.5, 0.5, 1.0],
            [0.5, 0.5, -1.0],
            // Flat, overlapping the first in its own plane.
            [0.3, 0.6, 0.0],
        ];
        assert!(pairs(&p, &[[0, 1, 2], [0, 3, 4]]).is_empty());
        assert_eq!(pairs(&p, &[[0, 1, 2], [0, 5, 6]]), vec![[0, 1]]);
        assert_eq!(pairs(&p, &[[0, 1, 2], [0, 7, 1]]), vec![[0, 1]]);
    }

    #[test]
    fn two_vertices_at_one_point_cross() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
        ];
        assert_eq!(pairs(&p, &[[0, 1, 2], [3, 4, 5]]), vec![[0, 1]]);
    }

    #[test]
    fn many_apart_none_crossing() {
        // A folded strip of 200 triangles, no two crossing: the tree must
        // not invent pairs; then one triangle pushed through the strip.
        let mut p = Vec::new();
        for i in 0..101 {
            let x = i as f64 * 0.01;
            p.push([x, 0.0, (x * 40.0).sin() * 0.1]);
            p.push([x, 1.0, (x * 40.0).sin() * 0.1]);
        }
        let mut t: Vec<[u32; 3]> = (0..100u32)
            .flat_map(|i| {
                [
                    [2 * i, 2 * i + 2, 2 * i + 1],
                    [2 * i + 1, 2 * i + 2, 2 * i + 3],
                ]
            })
            .collect();
        assert!(pairs(&p, &t).is_empty());
        let n = p.len() as u32;
        p.extend([[0.5, 0.5, -1.0], [0.52, 0.5, 1.0], [0.5, 0.52, 1.0]]);
        t.push([n, n + 1, n + 2]);
        assert!(!pairs(&p, &t).is_empty());
        assert!(pairs(&p, &t).iter().all(|&[_, j]| j == 200));
    }
}
