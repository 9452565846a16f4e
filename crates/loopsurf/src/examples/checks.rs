//! Test-only mesh checks shared by the example tests.
//!
//! They are written from scratch (not with the crate's topology module) so
//! the examples are checked independently of the code they will test.

use super::Example;
use glam::DVec3;
use std::collections::HashMap;

/// Largest bounding-box extent, the length scale for tolerances.
pub fn scale(ex: &Example) -> f64 {
    let (mut lo, mut hi) = (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN));
    for &p in &ex.points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    (hi - lo).max_element()
}

/// Unnormalized normal (twice the area vector) of triangle `t`.
pub fn area_vector(ex: &Example, t: [u32; 3]) -> DVec3 {
    let [a, b, c] = t.map(|i| ex.points[i as usize]);
    (b - a).cross(c - a)
}

/// Indices in range, every vertex used, no zero-area triangle, no two
/// vertices at the same place, all coordinates finite.
pub fn check_elements(ex: &Example) {
    let n = ex.points.len();
    assert!(n >= 4 && !ex.tris.is_empty(), "{}: empty", ex.name);
    assert!(
        ex.points.iter().all(|p| p.is_finite()),
        "{}: non-finite",
        ex.name
    );
    let s = scale(ex);
    let mut used = vec![false; n];
    for (k, &t) in ex.tris.iter().enumerate() {
        for i in t {
            assert!(
                (i as usize) < n,
                "{}: triangle {k} index {i} out of range",
                ex.name
            );
            used[i as usize] = true;
        }
        let area = 0.5 * area_vector(ex, t).length();
        assert!(
            area > 1e-6 * s * s,
            "{}: triangle {k} {t:?} degenerate",
            ex.name
        );
    }
    assert!(used.iter().all(|&u| u), "{}: unused vertex", ex.name);
    for i in 0..n {
        for j in i + 1..n {
            let d = ex.points[i].distance(ex.points[j]);
            assert!(d > 1e-9 * s, "{}: vertices {i} and {j} coincide", ex.name);
        }
    }
}

/// Directed edge -> triangle, asserting that no directed edge is used twice
/// (which would mean inconsistent orientation or a non-manifold edge).
pub fn directed_edges(ex: &Example) -> HashMap<(u32, u32), usize> {
    let mut map = HashMap::new();
    for (k, &[a, b, c]) in ex.tris.iter().enumerate() {
        for e in [(a, b), (b, c), (c, a)] {
            let old = map.insert(e, k);
            assert!(old.is_none(), "{}: directed edge {e:?} used twice", ex.name);
        }
    }
    map
}

/// Closed, manifold, consistently oriented: every directed edge once and its
/// reverse once, and the triangles around each vertex form one fan (no
/// pinched vertices). Returns the number of undirected edges.
pub fn check_closed_manifold(ex: &Example) -> usize {
    let de = directed_edges(ex);
    for &(a, b) in de.keys() {
        assert!(
            de.contains_key(&(b, a)),
            "{}: edge ({a},{b}) has one side",
            ex.name
        );
    }
    check_vertex_fans(ex, &de);
    de.len() / 2
}

/// Manifold with boundary, consistently oriented: every directed edge at
/// most once, the boundary edges (no reverse) form exactly one loop, and
/// each vertex has one fan. Returns (undirected edges, boundary edges).
pub fn check_open_manifold(ex: &Example) -> (usize, usize) {
    let de = directed_edges(ex);
    let mut next: HashMap<u32, u32> = HashMap::new();
    for &(a, b) in de.keys() {
        if !de.contains_key(&(b, a)) {
            assert!(
                next.insert(a, b).is_none(),
                "{}: boundary pinched at {a}",
                ex.name
            );
        }
    }
    let nb = next.len();
    assert!(nb >= 3, "{}: no boundary", ex.name);
    let start = *next.keys().next().unwrap();
    let (mut v, mut len) = (start, 0);
    loop {
        v = next[&v];
        len += 1;
        if v == start {
            break;
        }
        assert!(len <= nb, "{}: boundary is not a loop", ex.name);
    }
    assert_eq!(len, nb, "{}: boundary has more than one loop", ex.name);
    check_vertex_fans(ex, &de);
    ((de.len() + nb) / 2, nb)
}

/// The triangles (v, a, b) around each vertex v, chained by a -> b, must form
/// a single path or cycle.
fn check_vertex_fans(ex: &Example, de: &HashMap<(u32, u32), usize>) {
    let mut link: Vec<HashMap<u32, u32>> = vec![HashMap::new(); ex.points.len()];
    for &[a, b, c] in &ex.tris {
        link[a as usize].insert(b, c);
        link[b as usize].insert(c, a);
        link[c as usize].insert(a, b);
    }
    for (v, l) in link.iter().enumerate() {
        // Start at the fan's first triangle: one whose incoming link vertex is
        // not another triangle's outgoing one (boundary), else anywhere.
        let start = l
            .keys()
            .copied()
            .find(|&a| !de.contains_key(&(a, v as u32)))
            .unwrap_or_else(|| *l.keys().next().unwrap());
        let (mut a, mut seen) = (start, 0);
        while let Some(&b) = l.get(&a) {
            seen += 1;
            a = b;
            if a == start || seen > l.len() {
                break;
            }
        }
        assert_eq!(seen, l.len(), "{}: vertex {v} is not a single fan", ex.name);
    }
}

/// V - E + F.
pub fn euler(ex: &Example, edges: usize) -> i64 {
    ex.points.len() as i64 - edges as i64 + ex.tris.len() as i64
}

/// Enclosed volume by the divergence theorem; positive when outward.
pub fn signed_volume(ex: &Example) -> f64 {
    ex.tris
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| ex.points[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// Number of edges at each vertex.
pub fn valences(ex: &Example) -> Vec<usize> {
    let mut nb: Vec<Vec<u32>> = vec![Vec::new(); ex.points.len()];
    for &[a, b, c] in &ex.tris {
        for (p, q) in [(a, b), (b, c), (c, a)] {
            nb[p as usize].push(q);
            nb[q as usize].push(p);
        }
    }
    nb.into_iter()
        .map(|mut v| {
            v.sort_unstable();
            v.dedup();
            v.len()
        })
        .collect()
}

/// Dihedral angle in degrees (angle between the two triangle normals) of
/// every interior edge, as (a, b, angle) with a < b.
pub fn dihedral_angles(ex: &Example) -> Vec<(u32, u32, f64)> {
    let de = directed_edges(ex);
    let mut out = Vec::new();
    for (&(a, b), &t0) in &de {
        if a < b {
            if let Some(&t1) = de.get(&(b, a)) {
                let n0 = area_vector(ex, ex.tris[t0]).normalize();
                let n1 = area_vector(ex, ex.tris[t1]).normalize();
                out.push((a, b, n0.dot(n1).clamp(-1.0, 1.0).acos().to_degrees()));
            }
        }
    }
    out
}

/// The checks every closed example must pass; returns the Euler
/// characteristic.
pub fn check_closed_example(ex: &Example) -> i64 {
    check_elements(ex);
    let edges = check_closed_manifold(ex);
    let vol = signed_volume(ex);
    assert!(vol > 0.0, "{}: inward orientation, volume {vol}", ex.name);
    euler(ex, edges)
}
