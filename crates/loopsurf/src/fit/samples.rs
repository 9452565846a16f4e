//! Data between the input's vertices, where a CAD export has none.
//!
//! A CAD exporter puts its vertices on the true surface and nothing
//! between them: along a cylinder's slivers the nearest data are a whole
//! height apart, a filleted box's faces are two triangles each. Fitted to
//! the vertices alone, the surface between them is whatever the fairness
//! term makes it. But the vertices say more than where the surface is:
//! their neighbours say where it is going. Along every input edge longer
//! than the new net's spacing, this module predicts the true surface by the
//! cubic Hermite curve between the edge's ends whose end tangents are the
//! edge's direction projected onto the tangent planes there (as the curved
//! PN triangles of Vlachos, Peters, Boyd & Mitchell do): exact on a
//! straight ruling (a cylinder's or a cone's slivers, a flat face), and
//! within O(θ⁴) of a circular arc turning by θ.
//!
//! **Tangent planes.** The plane at a vertex is the least-squares plane
//! through it that best fits its neighbours in the sector of the edge
//! (the fan between two hard edges; the whole fan on a smooth vertex). The
//! fit weighs each neighbour by its distance, which is what a CAD
//! tessellation needs where a flat face meets a fillet tangentially: the
//! long edges on the flat face, exactly in its plane, decide the plane,
//! and the short ones on the fillet, off it by the chord tolerance only,
//! barely tilt it. An average of facet normals would tilt it by half the
//! fillet's angle step, and the long edges' predictions with it.
//!
//! **Hard edges** are predicted along the curve: the tangent at a crease
//! vertex is that of the circle through it and its two crease neighbours,
//! exact on circular and straight rims; at a corner or a crease's end the
//! chord's own direction. The same circle corrects the tangent planes
//! beside a crease ([`plane_normal`]), and at a smooth vertex the circle
//! through two of its neighbours opposite each other at about the same
//! distance does the same ([`opposite_circle`]): on a tangent seam, where
//! a cylinder or a flat face meets a fillet, that pair runs along the
//! seam.
//!
//! **Corners** (an apex, where a fan of slivers meets, or where creases
//! meet) have no tangent plane: an edge leaves a corner in the mean plane
//! of its own two triangles, which holds the edge, so along a cone's
//! rulings the prediction is the ruling itself. A least-squares plane of
//! the neighbours there tilted each ruling by the rim's sagitta and bent
//! it off the cone by a third of the chord tolerance.
//!
//! **Inside a triangle** larger than the net's spacing, the surface is
//! predicted from the three edge curves by Nielson's side-vertex method
//! ([`SideVertexPatch`]).

use crate::features::VertexKind;
use crate::net::ControlNet;
use crate::topology::Topology;
use faer::linalg::solvers::SelfAdjointEigen;
use glam::DVec3;

/// Predicted points between the input's vertices, and whether each lies on
/// a hard edge (fitted by the crease curves) or on the surface.
pub struct Samples {
    pub points: Vec<DVec3>,
    pub on_feature: Vec<bool>,
}

/// The samples of every edge of `input` longer than the new net's
/// `spacing`, about `spacing` apart along it, and of every triangle larger
/// than an equilateral one of that edge, about as dense inside it.
pub fn between_vertices(input: &ControlNet, spacing: f64) -> Samples {
    let topo = input.topology();
    let kinds = input.vertex_kinds();
    let points = input.points();
    let mut out = Samples {
        points: Vec::new(),
        on_feature: Vec::new(),
    };
    for (e, &[a, b]) in topo.edges().iter().enumerate() {
        let (pa, pb) = (points[a as usize], points[b as usize]);
        let count = ((pa.distance(pb) / spacing + 0.5).floor() as usize).saturating_sub(1);
        if count == 0 {
            continue;
        }
        let (da, db) = (
            derivative(input, &kinds, a, b),
            -derivative(input, &kinds, b, a),
        );
        for k in 1..=count {
            let s = k as f64 / (count + 1) as f64;
            out.points.push(hermite(pa, da, pb, db, s));
            out.on_feature.push(input.features().is_hard_edge(e));
        }
    }
    let equilateral = 3f64.sqrt() / 4.0 * spacing * spacing;
    for &t in topo.triangles() {
        let corners = t.map(|v| points[v as usize]);
        let n = (crate::geometry::area(corners) / equilateral)
            .sqrt()
            .round() as usize;
        if n < 3 {
            continue;
        }
        let patch = SideVertexPatch::new(input, &kinds, t);
        for i in 1..n - 1 {
            for j in 1..n - i {
                out.points
                    .push(patch.at(i as f64 / n as f64, j as f64 / n as f64));
                out.on_feature.push(false);
            }
        }
    }
    out
}

/// The cubic Hermite curve from `a` (derivative `da`) to `b` (derivative
/// `db`) at parameter s in [0, 1].
fn hermite(a: DVec3, da: DVec3, b: DVec3, db: DVec3, s: f64) -> DVec3 {
    let (s2, s3) = (s * s, s * s * s);
    (2.0 * s3 - 3.0 * s2 + 1.0) * a
        + (s3 - 2.0 * s2 + s) * da
        + (-2.0 * s3 + 3.0 * s2) * b
        + (s3 - s2) * db
}

/// The derivative at `a` of the predicted curve of the edge to `b` (over
/// the parameter from 0 at `a` to 1 at `b`): the edge projected onto the
/// tangent plane at `a` (as PN triangles do), or along a hard edge the
/// crease's tangent at `a`, as long as the edge.
fn derivative(input: &ControlNet, kinds: &[VertexKind], a: u32, b: u32) -> DVec3 {
    let topo = input.topology();
    let d = input.points()[b as usize] - input.points()[a as usize];
    if input.features().is_hard_between(topo, a, b) {
        return d.length() * crease_tangent(input, kinds, a, b);
    }
    in_plane(d, Some(plane_normal(topo, input, kinds, a, b)))
}

/// `v` projected onto the plane of unit normal `n`; `v` itself where there
/// is no plane.
fn in_plane(v: DVec3, n: Option<DVec3>) -> DVec3 {
    n.map_or(v, |n| v - v.dot(n) * n)
}

/// The surface inside a control triangle predicted from its three edge
/// curves, by Nielson's side-vertex method: from each corner a radial
/// Hermite curve runs to the point of the opposite edge's curve, leaving
/// the corner in the plane of its two edge curves and arriving in the
/// tangent plane interpolated along that edge; the three radial curves are
/// blended with weights that make each edge's own curve exact on it.
///
/// Why not the cubic Bézier triangle of the same edges (Vlachos et al.'s
/// PN triangles): its centre control point has quadratic precision only,
/// and a CAD sliver is anything but small: inside the fan of slivers at a
/// cone's apex it strays by a fifth of the chord tolerance, more than the
/// facets do on average. The radial curve from
/// an apex is the ruling itself, exactly.
struct SideVertexPatch {
    corners: [DVec3; 3],
    /// `derivative[i][0]` along the edge from corner i to i + 1,
    /// `derivative[i][1]` along it from i + 1 to i (pointing back).
    derivative: [[DVec3; 2]; 3],
    /// The unit normal at each corner of the plane of its two edge
    /// curves, none at a corner vertex (an apex has no tangent plane).
    normal: [Option<DVec3>; 3],
}

impl SideVertexPatch {
    fn new(input: &ControlNet, kinds: &[VertexKind], t: [u32; 3]) -> SideVertexPatch {
        let corners = t.map(|v| input.points()[v as usize]);
        let derivative = [0, 1, 2].map(|i| {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            [
                derivative(input, kinds, a, b),
                derivative(input, kinds, b, a),
            ]
        });
        let normal = [0, 1, 2].map(|i| {
            let out = derivative[i][0];
            let back = derivative[(i + 2) % 3][1];
            (kinds[t[i] as usize] != VertexKind::Corner)
                .then(|| out.cross(back).try_normalize())
                .flatten()
        });
        SideVertexPatch {
            corners,
            derivative,
            normal,
        }
    }

    /// The edge curve from corner i to corner i + 1 at parameter u, and its
    /// interpolated unit normal there (none if neither end has one).
    fn edge(&self, i: usize, u: f64) -> (DVec3, Option<DVec3>) {
        let j = (i + 1) % 3;
        let [da, db] = self.derivative[i];
        let point = hermite(self.corners[i], da, self.corners[j], -db, u);
        let normal = match (self.normal[i], self.normal[j]) {
            (Some(a), Some(b)) => ((1.0 - u) * a + u * b).try_normalize(),
            (Some(n), None) | (None, Some(n)) => Some(n),
            (None, None) => None,
        };
        (point, normal)
    }

    /// The point at barycentric (1 − v − w, v, w), inside the triangle.
    fn at(&self, v: f64, w: f64) -> DVec3 {
        let b = [1.0 - v - w, v, w];
        let mut sum = DVec3::ZERO;
        let mut total = 0.0;
        for i in 0..3 {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let weight = b[j] * b[k];
            if weight <= 0.0 {
                continue;
            }
            // The point of the opposite edge (j to k) seen from corner i.
            let (q, nq) = self.edge(j, b[k] / (b[j] + b[k]));
            let chord = q - self.corners[i];
            let (leave, arrive) = (in_plane(chord, self.normal[i]), in_plane(chord, nq));
            sum += weight * hermite(self.corners[i], leave, q, arrive, 1.0 - b[i]);
            total += weight;
        }
        sum / total
    }
}

/// The osculating circle of the crease at crease vertex `a`, through it
/// and its two crease neighbours: its unit tangent at `a` (either way)
/// and its curvature vector there; none where `a` is not on exactly one
/// crease.
fn crease_circle(input: &ControlNet, kinds: &[VertexKind], a: u32) -> Option<(DVec3, DVec3)> {
    if kinds[a as usize] != VertexKind::Crease {
        return None;
    }
    let hard = input
        .features()
        .hard_neighbours(input.topology(), a as usize);
    let [n0, n2] = hard[..] else {
        return None;
    };
    let points = input.points();
    let p = points[a as usize];
    circle_through(points[n0 as usize] - p, points[n2 as usize] - p)
}

/// The circle through a point and two others at offsets `d0` and `d2`
/// from it: its unit tangent at the point (either way) and its curvature
/// vector there. Inverted about the point, the circle is a line through
/// the images of the other two: parallel to the tangent, at 1/(2R) from
/// it towards the centre.
fn circle_through(d0: DVec3, d2: DVec3) -> Option<(DVec3, DVec3)> {
    let (i0, i2) = (d0 / d0.length_squared(), d2 / d2.length_squared());
    let t = (i2 - i0).try_normalize()?;
    Some((t, 2.0 * (i0 - i0.dot(t) * t)))
}

/// Neighbours as far apart as this (cosine of the angle between them) or
/// farther count as opposite.
const OPPOSITE: f64 = -0.94;
/// The most one arm of an opposite pair may exceed the other.
const BALANCED: f64 = 1.5;

/// At a smooth vertex, the circle through it and the pair of its ring's
/// neighbours most nearly opposite each other, when the pair is opposite
/// and balanced ([`OPPOSITE`], [`BALANCED`]): a curve of the surface
/// through the vertex, to second order, as a crease is. Where a cylinder
/// meets a fillet, the seam's own circle is such a pair; its tangent is
/// exact, and sweeping the other neighbours along it leaves the long
/// rulings to decide the plane, which the fillet's short edges tilted by
/// 0.3° in a plain least-squares plane, and bent every curve predicted
/// from the seam to the rim by 1.8e-4 of the diagonal. An unbalanced pair
/// (a long flat edge against a short one on a blend) would put the
/// curvature jump between them into the tangent: none is taken.
fn opposite_circle(topo: &Topology, points: &[DVec3], a: u32) -> Option<(DVec3, DVec3)> {
    let p = points[a as usize];
    let ring: Vec<DVec3> = topo
        .ring(a as usize)
        .iter()
        .map(|&n| points[n as usize] - p)
        .collect();
    let mut best: Option<(f64, usize, usize)> = None;
    for i in 0..ring.len() {
        for j in i + 1..ring.len() {
            let (li, lj) = (ring[i].length(), ring[j].length());
            if li.max(lj) > BALANCED * li.min(lj) {
                continue;
            }
            let cos = ring[i].dot(ring[j]) / (li * lj);
            if cos <= OPPOSITE && best.map_or(true, |b| cos < b.0) {
                best = Some((cos, i, j));
            }
        }
    }
    let (_, i, j) = best?;
    circle_through(ring[i], ring[j])
}

/// The unit tangent at vertex `a` of the hard edge towards `b`, pointing
/// towards `b`: the crease circle's, or the chord's where there is none.
fn crease_tangent(input: &ControlNet, kinds: &[VertexKind], a: u32, b: u32) -> DVec3 {
    let chord = (input.points()[b as usize] - input.points()[a as usize]).normalize();
    match crease_circle(input, kinds, a) {
        Some((t, _)) if t.dot(chord) < 0.0 => -t,
        Some((t, _)) => t,
        None => chord,
    }
}

/// The unit normal (up to sign) of the tangent plane at vertex `a` in the
/// sector holding the edge to `b` (module doc). On a crease the plane holds
/// the crease's tangent t, and each neighbour is first moved back along
/// the crease's circle by its offset along t: the surface beside a rim is
/// swept along it, to second order, so what is left of the neighbour's
/// offset says how the plane turns about t, free of the crease's own
/// curvature (which would tilt a plain least-squares plane by the rim's
/// sagitta over the neighbour's distance). A smooth vertex with an
/// opposite, balanced pair of neighbours is treated the same way along the
/// circle through them ([`opposite_circle`]); any other, by the plain
/// least-squares plane.
fn plane_normal(
    topo: &Topology,
    input: &ControlNet,
    kinds: &[VertexKind],
    a: u32,
    b: u32,
) -> DVec3 {
    let points = input.points();
    if kinds[a as usize] == VertexKind::Corner {
        return edge_plane_normal(topo, points, a, b);
    }
    let p = points[a as usize];
    let offsets = sector(topo, input, a, b)
        .into_iter()
        .map(|n| points[n as usize] - p);
    let circle = crease_circle(input, kinds, a).or_else(|| {
        (kinds[a as usize] == VertexKind::Smooth)
            .then(|| opposite_circle(topo, points, a))
            .flatten()
    });
    match circle {
        Some((t, curvature)) => {
            let swept = offsets.map(|d| {
                let s = d.dot(t);
                d - s * t - 0.5 * s * s * curvature
            });
            normal_about(t, swept)
        }
        None => least_squares_normal(offsets),
    }
}

/// The mean unit normal of the triangles beside edge (a, b). At a corner
/// (an apex, where a fan of slivers meets) no plane fits the vertex's
/// neighbours, but each triangle beside the edge holds the edge: the edge
/// lies in their mean plane, so the predicted curve leaves the corner along
/// the edge itself, which is exact on a cone's rulings.
fn edge_plane_normal(topo: &Topology, points: &[DVec3], a: u32, b: u32) -> DVec3 {
    let Some(e) = topo.find_edge(a, b) else {
        return DVec3::ZERO;
    };
    topo.edge_triangles()[e]
        .iter()
        .filter(|&&t| t != crate::topology::NONE)
        .map(|&t| {
            let corners = topo.triangles()[t as usize].map(|v| points[v as usize]);
            crate::geometry::area_normal(corners).normalize_or(DVec3::ZERO)
        })
        .sum::<DVec3>()
        .normalize_or(DVec3::ZERO)
}

/// The unit normal of the plane through the origin nearest (least squares)
/// to `offsets`.
fn least_squares_normal(offsets: impl Iterator<Item = DVec3>) -> DVec3 {
    let mut m = [[0.0f64; 3]; 3];
    for d in offsets {
        for (i, row) in m.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x += d[i] * d[j];
            }
        }
    }
    let mat = faer::Mat::<f64>::from_fn(3, 3, |i, j| m[i][j]);
    match SelfAdjointEigen::new(mat.as_ref(), faer::Side::Lower) {
        // Eigenvalues ascending: the first vector is the plane's normal.
        Ok(evd) => {
            let u = evd.U();
            DVec3::new(u[(0, 0)], u[(1, 0)], u[(2, 0)]).normalize_or(DVec3::ZERO)
        }
        Err(_) => DVec3::ZERO,
    }
}

/// The unit normal, perpendicular to unit `axis`, of the plane holding the
/// axis nearest (least squares) to `offsets` (taken perpendicular to it).
fn normal_about(axis: DVec3, offsets: impl Iterator<Item = DVec3>) -> DVec3 {
    let (e1, e2) = axis.any_orthonormal_pair();
    let (mut c11, mut c12, mut c22) = (0.0, 0.0, 0.0);
    for d in offsets {
        let (x, y) = (d.dot(e1), d.dot(e2));
        c11 += x * x;
        c12 += x * y;
        c22 += y * y;
    }
    // The offsets' major axis in the (e1, e2) plane lies in the tangent
    // plane; the normal is perpendicular to it.
    let major = 0.5 * (2.0 * c12).atan2(c11 - c22);
    -major.sin() * e1 + major.cos() * e2
}

/// The neighbours of `a` in the sector of the edge to `b`: from the ring
/// position of `b` both ways up to the first hard edge (included) or the
/// boundary.
fn sector(topo: &Topology, input: &ControlNet, a: u32, b: u32) -> Vec<u32> {
    let ring = topo.ring(a as usize);
    let n = ring.len();
    let Some(j) = ring.iter().position(|&x| x == b) else {
        return vec![b];
    };
    let closed = !topo.is_boundary_vertex(a as usize);
    let step = |i: usize, forward: bool| -> Option<usize> {
        match (forward, closed) {
            (true, true) => Some((i + 1) % n),
            (false, true) => Some((i + n - 1) % n),
            (true, false) => (i + 1 < n).then_some(i + 1),
            (false, false) => i.checked_sub(1),
        }
    };
    let is_hard = |i: usize| input.features().is_hard_between(topo, a, ring[i]);
    let mut out = vec![b];
    for forward in [true, false] {
        let mut i = j;
        while let Some(next) = step(i, forward) {
            if next == j {
                break;
            }
            out.push(ring[next]);
            if is_hard(next) {
                break;
            }
            i = next;
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}
