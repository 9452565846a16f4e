//! Slivers cut into well-shaped triangles, for the remesher's start.
//!
//! The chart mesher cuts a control triangle into copies of itself, which
//! is what a chart mesh promises. A CAD export's slivers (a ruled strip
//! 3 long and 0.04 wide) then start the remesher as slivers narrower
//! still: splitting their long edges keeps their shape, collapsing their
//! short ones would leave edges too long, and a thin lofted wing ran to
//! 12.5 million triangle slots where its sizes asked for 53 000.
//!
//! So for the remesher's start a sliver is cut by its edges' own lengths:
//! each side into as many segments as its length at the triangle's
//! spacing asks for (the finer neighbour's count where it shares the
//! side), the interior filled with a triangular lattice of that spacing
//! in the plane of its corners, and the points joined by a constrained
//! Delaunay triangulation (spade's). A strip narrower than the spacing is
//! then one row of triangles between its long sides.

use super::pattern::Pattern;
use crate::error::Result;
use crate::topology::Topology;
use glam::{DVec2, DVec3};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// A control triangle whose longest edge is this many times its shortest
/// (on the surface) is a sliver, cut by its edges' lengths: a lattice
/// would cut its short side this many times finer than its length asks.
/// Milder slivers and caps keep the lattice, whose copies the remesher's
/// passes reshape. Cut by their lengths wherever the smallest angle was
/// below 10°, pig's caps and short needles left 18 triangles below 20° that
/// its net does not force at 0.5% of its diagonal, against 16; from 20°
/// down, its adapted mesh missed the tolerance of 1e-3 (3.1e-3).
const SLIVER_ASPECT: f64 = 6.0;

/// Interior lattice points keep this many spacings from the sides: the
/// triangles between them and the sides' points are then no flatter than
/// about 45°.
const MARGIN: f64 = 0.5;

/// Which control triangles are slivers, with what their sides' segment
/// counts are computed from.
pub(super) struct Slivers {
    sliver: Vec<bool>,
    /// Per control edge: its length on the surface.
    lengths: Vec<f64>,
    /// Per control triangle: its longest edge's length.
    longest: Vec<f64>,
}

impl Slivers {
    /// None of the triangles (the chart mesher's own cuts).
    pub fn none(triangles: usize) -> Slivers {
        Slivers {
            sliver: vec![false; triangles],
            lengths: Vec::new(),
            longest: Vec::new(),
        }
    }

    /// The slivers among the triangles of `topo` whose edges are
    /// `lengths` long.
    pub fn find(topo: &Topology, lengths: Vec<f64>) -> Slivers {
        let edges = |es: &[u32; 3]| es.map(|e| lengths[e as usize]);
        let longest: Vec<f64> = topo
            .triangle_edges()
            .iter()
            .map(|es| edges(es).into_iter().fold(0.0, f64::max))
            .collect();
        let sliver = topo
            .triangle_edges()
            .iter()
            .zip(&longest)
            .map(|(es, &l)| l >= SLIVER_ASPECT * edges(es).into_iter().fold(l, f64::min))
            .collect();
        Slivers {
            sliver,
            lengths,
            longest,
        }
    }

    pub fn is_sliver(&self, t: usize) -> bool {
        self.sliver[t]
    }

    /// The segments triangle t at `level` asks of its edge e: `level` for
    /// a lattice triangle, the edge's length at the triangle's spacing
    /// (its longest edge over `level`) for a sliver.
    pub fn segments(&self, t: usize, e: usize, level: u32) -> u32 {
        if !self.sliver[t] {
            return level;
        }
        let spacing = self.longest[t] / level as f64;
        super::density::level(self.lengths[e] / spacing * (1.0 - 1e-9))
    }
}

/// The interior points (parameters and limit points, in order after the
/// boundary) and the triangles (local indices, counter-clockwise in
/// (v, w)) of a sliver cut by `pattern`'s side counts, its spacing its
/// longest side over the level. `boundary` holds the boundary points'
/// limit points; `eval` gives the limit point at (v, w).
///
/// The interior points are placed on a lattice in the plane of the
/// corners and taken to (v, w) by the affine map, which next to an
/// irregular vertex is far from the surface's own parametrisation (a
/// valence-56 fan's 6° sector is 60° in (v, w)): so the points are joined
/// where they really are, by a Delaunay triangulation of their limit
/// points projected onto that plane, not of their parameters.
///
/// `None` where the triangulation does not tile the triangle (a control
/// triangle of no area, a surface that is no graph over the plane): the
/// caller cuts it as a lattice.
pub(super) fn triangulate(
    pattern: &Pattern,
    boundary: &[DVec3],
    mut eval: impl FnMut(DVec2) -> Result<DVec3>,
) -> Result<Option<Cut>> {
    let corners = pattern.corners().map(|i| boundary[i as usize]);
    let [a, b3, c3] = corners;
    let (ab, ac) = (b3 - a, c3 - a);
    let len_b = ab.length();
    let normal = ab.cross(ac);
    if !(len_b > 0.0 && normal.length() > 1e-12 * len_b * len_b) {
        return Ok(None);
    }
    let x_axis = ab / len_b;
    let y_axis = normal.normalize().cross(x_axis);
    let project = |p: DVec3| DVec2::new((p - a).dot(x_axis), (p - a).dot(y_axis));
    let (b, c) = (project(b3), project(c3));
    let from_plane = |p: DVec2| {
        let w = p.y / c.y;
        DVec2::new((p.x - w * c.x) / b.x, w)
    };
    let longest = b.length().max(c.length()).max((c - b).length());
    let h = longest / pattern.level.max(1) as f64;
    let mut params = Vec::new();
    let mut points = Vec::new();
    for p in lattice(b, c, h, MARGIN) {
        let q = from_plane(p);
        let x = eval(q)?;
        // Where the parametrisation moved it near a side, or out, it goes.
        if lattice_inside(b, c, project(x), 0.5 * MARGIN * h) {
            params.push(q);
            points.push(x);
        }
    }
    let nb = pattern.boundary_len();
    let mut side_of = Vec::with_capacity(nb);
    for s in 0..3 {
        side_of.extend(std::iter::repeat(s).take(pattern.sides[s] as usize));
    }
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let mut handles = Vec::with_capacity(nb + points.len());
    for x in boundary[..nb].iter().chain(&points) {
        let p = project(*x);
        match cdt.insert(Point2::new(p.x, p.y)) {
            Ok(h) => handles.push(h),
            Err(_) => return Ok(None),
        }
    }
    if cdt.num_vertices() != handles.len() {
        return Ok(None);
    }
    for k in 0..nb {
        if cdt
            .try_add_constraint(handles[k], handles[(k + 1) % nb])
            .is_empty()
        {
            return Ok(None);
        }
    }
    let local: std::collections::HashMap<_, u32> = handles
        .iter()
        .enumerate()
        .map(|(i, h)| (*h, i as u32))
        .collect();
    // Corner s + 1 ends side s; any other boundary point is on its own
    // side alone.
    let corner = pattern.corners();
    let on_side = |i: u32, s: usize| {
        (i as usize) < nb && (side_of[i as usize] == s || corner[(s + 1) % 3] == i)
    };
    let mut tris = Vec::new();
    for face in cdt.inner_faces() {
        let t = face.vertices().map(|v| local[&v.fix()]);
        if !(0..3).any(|s| t.iter().all(|&i| on_side(i, s))) {
            tris.push(t);
        }
    }
    // A tiling of a polygon of nb sides holding ni points has nb + 2 ni − 2
    // triangles; its triangles keep their orientation in (v, w).
    let interior = params.len();
    let mut all = pattern.boundary_params();
    all.extend(params);
    let tiles = tris.len() == nb + 2 * interior - 2
        && tris.iter().all(|t| {
            let [p, q, r] = t.map(|i| all[i as usize]);
            (q - p).perp_dot(r - p) > 0.0
        });
    Ok(tiles.then_some(Cut {
        params: all,
        points,
        tris,
    }))
}

/// A sliver's cut ([`triangulate`]): the parameters of its boundary and
/// interior points, its interior points' limit points, and its triangles
/// over both.
pub(super) struct Cut {
    pub params: Vec<DVec2>,
    pub points: Vec<DVec3>,
    pub tris: Vec<[u32; 3]>,
}

/// Whether `p` lies inside the triangle (0, b, c) at least `margin` from
/// each side (the triangle counter-clockwise).
fn lattice_inside(b: DVec2, c: DVec2, p: DVec2, margin: f64) -> bool {
    [(DVec2::ZERO, b), (b, c), (c, DVec2::ZERO)]
        .iter()
        .all(|&(u, v)| {
            let d = v - u;
            d.perp_dot(p - u) / d.length() >= margin
        })
}

/// The points of a triangular lattice of spacing `h`, one row along the
/// side from the origin to `b`, that lie inside the triangle (0, b, c) at
/// least `margin` × `h` from each side.
fn lattice(b: DVec2, c: DVec2, h: f64, margin: f64) -> Vec<DVec2> {
    let (lo, hi) = (b.min(c).min(DVec2::ZERO), b.max(c).max(DVec2::ZERO));
    let row = 0.5 * 3f64.sqrt() * h;
    let mut out = Vec::new();
    let rows = (hi.y / row).floor() as i64;
    for j in 1..=rows {
        let y = j as f64 * row;
        let shift = if j % 2 == 1 { 0.5 * h } else { 0.0 };
        let first = ((lo.x - shift) / h).floor() as i64;
        let last = ((hi.x - shift) / h).ceil() as i64;
        for i in first..=last {
            let p = DVec2::new(i as f64 * h + shift, y);
            if lattice_inside(b, c, p, margin * h) {
                out.push(p);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::max_cosine;

    fn area(p: &[DVec2], t: [u32; 3]) -> f64 {
        let [a, b, c] = t.map(|i| p[i as usize]);
        0.5 * (b - a).perp_dot(c - a)
    }

    /// The cut of a flat control triangle with corners `corners` (the
    /// surface its plane, so (v, w) maps affinely).
    fn cut(corners: [DVec3; 3], sides: [u32; 3], level: u32) -> Option<(Vec<DVec2>, Cut)> {
        let pattern = Pattern {
            sides,
            level,
            isotropic: true,
        };
        let x = |q: DVec2| {
            corners[0] + q.x * (corners[1] - corners[0]) + q.y * (corners[2] - corners[0])
        };
        let boundary: Vec<DVec3> = pattern.boundary_params().into_iter().map(x).collect();
        let cut = triangulate(&pattern, &boundary, |q| Ok(x(q))).unwrap()?;
        Some((cut.params.clone(), cut))
    }

    /// A strip 3 long and 0.04 wide, and a wide sliver, cut by their sides'
    /// lengths: the triangles tile the parameter triangle (their areas add
    /// up to its half, none inverted), every point is used, no triangle is
    /// flatter than the sliver itself, and most are far rounder than its
    /// copies would be.
    #[test]
    fn slivers_are_tiled_by_well_shaped_triangles() {
        for (corners, sides, level) in [
            (
                [
                    DVec3::ZERO,
                    DVec3::new(3.0, 0.0, 0.0),
                    DVec3::new(3.0, 0.04, 0.0),
                ],
                [60, 1, 60],
                60,
            ),
            (
                [
                    DVec3::ZERO,
                    DVec3::new(2.0, 0.0, 0.0),
                    DVec3::new(1.7, 0.5, 0.1),
                ],
                [20, 7, 13],
                20,
            ),
        ] {
            let (params, cut) = cut(corners, sides, level).expect("a tiling");
            let total: f64 = cut.tris.iter().map(|&t| area(&params, t)).sum();
            assert!((total - 0.5).abs() < 1e-12, "areas add up to {total}");
            assert!(cut.tris.iter().all(|&t| area(&params, t) > 0.0));
            let used: std::collections::HashSet<u32> = cut.tris.iter().flatten().copied().collect();
            assert_eq!(used.len(), params.len());
            let x = |q: DVec2| {
                corners[0] + q.x * (corners[1] - corners[0]) + q.y * (corners[2] - corners[0])
            };
            let angle = |[a, b, c]: [DVec3; 3]| max_cosine(a, b, c).acos().to_degrees();
            let mut angles: Vec<f64> = cut
                .tris
                .iter()
                .map(|t| angle(t.map(|i| x(params[i as usize]))))
                .collect();
            angles.sort_by(f64::total_cmp);
            assert!(
                angles[0] >= angle(corners) - 1e-9,
                "smallest {}°",
                angles[0]
            );
            let median = angles[angles.len() / 2];
            assert!(median > 20.0, "median {median}°");
        }
    }

    /// A triangle of no area gives no tiling (the caller cuts a lattice).
    #[test]
    fn a_flat_triangle_is_left_to_the_lattice() {
        assert!(cut([DVec3::ZERO, DVec3::X, DVec3::X * 0.5], [4, 2, 2], 4).is_none());
    }
}
