//! One level of adaptive Loop subdivision (Liu & Kondo §4.6, steps 2–3).
//!
//! An edge is dead when both its ends are dead and gets no new vertex; every
//! other edge gets one, placed by the Loop edge mask, and the new vertex is
//! dead when either end is. Old vertices move by the Loop vertex masks
//! unless dead (a dead vertex keeps its place: Liu & Kondo keep the density
//! and shape of dead regions). The masks are [`crate::rules`]'s, applied
//! through [`crate::refine::subdivide_points`], hard edges and corners
//! included.
//!
//! A triangle's split follows from its edges, so the two triangles of an
//! edge always agree and the result is conforming by construction: with
//! d dead corners, the number of split edges is 3 (d ≤ 1: the four
//! triangles of the regular split, Fig. 4(a)), 2 (d = 2: the corner
//! triangle at the live vertex, and the quad at the dead edge cut by its
//! better diagonal into two dead triangles, Fig. 4(b)), or 0 (d = 3: the
//! triangle is dead and stays). One split edge is impossible: it would need
//! two dead edges, which make all three corners dead.

use super::{FaceChart, Level, Parts};
use crate::geometry::max_cosine;
use crate::refine::subdivide_points;
use crate::topology::NONE;
use glam::{DVec2, DVec3};

/// Subdivides `level` once, `dead` being the flags of its NLFC.
pub(crate) fn subdivide(level: &Level, dead: &[bool]) -> Parts {
    let net = &level.net;
    let (topo, features) = (net.topology(), net.features());
    let nv = topo.num_vertices();
    let moved = subdivide_points(topo, features, net.points());
    let mut points: Vec<_> = (0..nv)
        .map(|v| if dead[v] { net.points()[v] } else { moved[v] })
        .collect();
    let mut next_dead = dead.to_vec();
    let mut edge_vertex = vec![NONE; topo.num_edges()];
    for (e, &[a, b]) in topo.edges().iter().enumerate() {
        let (da, db) = (dead[a as usize], dead[b as usize]);
        if !(da && db) {
            edge_vertex[e] = points.len() as u32;
            points.push(moved[nv + e]);
            next_dead.push(da || db);
        }
    }
    let (tris, charts, fresh) = split_triangles(level, &points, &edge_vertex);
    // Hard edges: both halves of a split one, the whole of a dead one.
    let mut hard = Vec::new();
    for (e, &[a, b]) in topo.edges().iter().enumerate() {
        if features.is_hard_edge(e) && !topo.is_boundary_edge(e) {
            match edge_vertex[e] {
                NONE => hard.push([a, b]),
                m => hard.extend([[a, m], [m, b]]),
            }
        }
    }
    let corners: Vec<u32> = (0..nv as u32)
        .filter(|&v| features.is_tagged_vertex(v as usize))
        .collect();
    Parts {
        points,
        tris,
        charts,
        fresh,
        dead: next_dead,
        hard,
        corners,
    }
}

/// Every triangle of `level` split by its edges' new vertices
/// (`edge_vertex`, `NONE` for a dead edge) as the module doc describes:
/// the triangles, their charts, and whether each chart is new.
fn split_triangles(
    level: &Level,
    points: &[DVec3],
    edge_vertex: &[u32],
) -> (Vec<[u32; 3]>, Vec<FaceChart>, Vec<bool>) {
    let topo = level.net.topology();
    let mut tris = Vec::with_capacity(4 * topo.num_triangles());
    let mut charts = Vec::with_capacity(4 * topo.num_triangles());
    let mut fresh = Vec::with_capacity(4 * topo.num_triangles());
    let mut push = |t: [u32; 3], q: [DVec2; 3], chart: &FaceChart| {
        tris.push(t);
        charts.push(FaceChart { tri: chart.tri, q });
        fresh.push(q != chart.q);
    };
    for (t, (&c, chart)) in topo.triangles().iter().zip(&level.charts).enumerate() {
        let m = topo.triangle_edges()[t].map(|e| edge_vertex[e as usize]);
        let q = chart.q;
        let mq = [0, 1, 2].map(|k| 0.5 * (q[k] + q[(k + 1) % 3]));
        match m.iter().filter(|&&x| x != NONE).count() {
            3 => {
                push([c[0], m[0], m[2]], [q[0], mq[0], mq[2]], chart);
                push([m[0], c[1], m[1]], [mq[0], q[1], mq[1]], chart);
                push([m[2], m[1], c[2]], [mq[2], mq[1], q[2]], chart);
                push([m[1], m[2], m[0]], [mq[1], mq[2], mq[0]], chart);
            }
            2 => {
                // Rotate so that the dead edge k joins a = c[k] and b = c[k+1].
                let k = m.iter().position(|&x| x == NONE).expect("one dead edge");
                let r = |i: usize| (k + i) % 3;
                let (a, b, cc) = (c[r(0)], c[r(1)], c[r(2)]);
                let (qa, qb, qc) = (q[r(0)], q[r(1)], q[r(2)]);
                let (mbc, mca) = (m[r(1)], m[r(2)]);
                let (qbc, qca) = (mq[r(1)], mq[r(2)]);
                push([mbc, cc, mca], [qbc, qc, qca], chart);
                // The quad a, b, mbc, mca: the diagonal whose two triangles
                // have the larger smallest angle.
                let worst = |t: [u32; 3]| {
                    let [x, y, z] = t.map(|i| points[i as usize]);
                    max_cosine(x, y, z)
                };
                let via_a = worst([a, b, mbc]).max(worst([a, mbc, mca]));
                let via_b = worst([a, b, mca]).max(worst([b, mbc, mca]));
                if via_a <= via_b {
                    push([a, b, mbc], [qa, qb, qbc], chart);
                    push([a, mbc, mca], [qa, qbc, qca], chart);
                } else {
                    push([a, b, mca], [qa, qb, qca], chart);
                    push([b, mbc, mca], [qb, qbc, qca], chart);
                }
            }
            _ => push(c, q, chart),
        }
    }
    (tris, charts, fresh)
}
