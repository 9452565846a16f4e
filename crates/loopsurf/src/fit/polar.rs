//! The net around an apex: a polar grid whose rings close in on the tip.
//!
//! A corner vertex of a Loop net whose edges are all smooth stays put
//! while its ring shrinks towards it by 3/8 + cos(2π/n)/4 per step around
//! it but by 5/8 along the axis, so near the tip the height goes as the
//! radius to the power log(5/8) / log(3/8 + cos(2π/n)/4): 0.68 for six
//! triangles (a spike), 0.94 for sixteen, nearly the straight rulings of a
//! cone. Whatever is left of the spike is as wide as the apex's first
//! ring, and a cone's curvature grows as one over the distance to its
//! tip, so the net wants many triangles at the tip, rings that close in on
//! it geometrically, and no irregular vertex nearby but the apex and its
//! ring.
//!
//! The remesher closes a cone's tip, whose angles sum to little more than
//! 180°, with three or four triangles. Opening that fan by splitting the
//! edges facing the apex gave it sixteen triangles but left vertices of
//! valence 4 and 13 in its second ring, and the fit's worst distance to the
//! CAD cone of docs/fitting.md (1.9e-4 of the diagonal) sat beside them.
//! Here the disk of triangles around the apex is replaced by a polar grid:
//! the disk's boundary keeps its vertices, and rings of as many vertices
//! lie on the straight lines from the apex to them (a cone's rulings, on a
//! cone), at a half, a quarter, … of the way, strips of quads cut along
//! one diagonal between them (valence 6 on every ring but the apex's, 5),
//! and a fan at the apex. The same cone: 5.0e-5 at the worst, within
//! 3.3e-5 near its tip.

use glam::DVec3;
use std::collections::{HashMap, HashSet, VecDeque};

/// The fewest triangles the polar grid puts around an apex: the disk
/// grows ring by ring until its boundary has this many vertices. Measured
/// on the CAD cone of docs/fitting.md with rings halving towards the tip,
/// the fitted surface's worst distance to the true cone near the tip:
/// 8.3e-5 of the diagonal with twelve, 5.4e-5 with sixteen, 4.1e-5 with
/// nineteen, with the rest of the cone at 5.0e-5.
const APEX_VALENCE: usize = 16;

/// The most rings of the remeshed net the disk may span.
const MAX_DISK_RINGS: usize = 8;

/// The rings halve their distance to the apex, from half the disk's
/// radius, as long as they stay this fraction of the net's spacing from
/// it. Measured on the CAD cone of docs/fitting.md, the fitted surface's
/// worst distance to the true cone near the tip: 5.4e-5 of the diagonal
/// at a quarter (four rings inside a disk of four rings of the remeshed
/// net), 3.3e-5 at an eighth (five rings), 2.6e-5 at a sixteenth; the rest
/// of the cone is 5.0e-5 off.
const INNERMOST_RING: f64 = 0.125;

/// A net as arrays: points, triangles, interior hard edges and corners.
pub struct Grid {
    pub points: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    pub hard_edges: Vec<[u32; 2]>,
    pub corners: Vec<u32>,
}

/// `net` with a polar grid around each apex (a corner with no hard edge),
/// `spacing` being the net's, and the vertices the grids replaced dropped
/// (the others keep their order).
pub fn with_polar_apexes(mut net: Grid, spacing: f64) -> Grid {
    for c in net.corners.clone() {
        if !net.hard_edges.iter().any(|e| e.contains(&c)) {
            polar_apex(&mut net, c, spacing);
        }
    }
    let mut held = vec![false; net.points.len()];
    for &v in net.triangles.iter().flatten() {
        held[v as usize] = true;
    }
    let mut index = vec![u32::MAX; net.points.len()];
    let mut points = Vec::new();
    for (v, &p) in net.points.iter().enumerate() {
        if held[v] {
            index[v] = points.len() as u32;
            points.push(p);
        }
    }
    let renumber = |v: &u32| index[*v as usize];
    Grid {
        points,
        triangles: net
            .triangles
            .iter()
            .map(|t| t.each_ref().map(renumber))
            .collect(),
        hard_edges: net
            .hard_edges
            .iter()
            .map(|e| e.each_ref().map(renumber))
            .collect(),
        corners: net.corners.iter().map(renumber).collect(),
    }
}

/// Replaces the triangles around apex `c` by a polar grid (see the module
/// doc), `spacing` being the net's. The disk is the triangles within some
/// rings of `c`; it stops growing before it would hold a hard edge, a
/// tagged corner, a boundary edge of the net or a boundary that is not a
/// single loop; when not even the first ring is such a disk, nothing
/// changes. The vertices inside the disk stay in `net.points`, held by no
/// triangle.
fn polar_apex(net: &mut Grid, c: u32, spacing: f64) {
    let Grid {
        points,
        triangles,
        hard_edges: hard,
        corners,
    } = net;
    let rings = graph_distance(triangles, c, MAX_DISK_RINGS);
    let mut best = None;
    for k in 1..=MAX_DISK_RINGS {
        match plain_disk(triangles, &rings, hard, corners, c, k) {
            Some(disk) => {
                let enough = disk.boundary.len() >= APEX_VALENCE;
                best = Some(disk);
                if enough {
                    break;
                }
            }
            None => break,
        }
    }
    let Some(disk) = best else {
        return;
    };
    let apex = points[c as usize];
    let radius = disk
        .boundary
        .iter()
        .map(|&b| points[b as usize].distance(apex))
        .sum::<f64>()
        / disk.boundary.len() as f64;
    let mut fractions = Vec::new();
    let mut t = 0.5;
    while t * radius >= INNERMOST_RING * spacing {
        fractions.push(t);
        t *= 0.5;
    }
    fractions.reverse();
    let mut grid: Vec<Vec<u32>> = fractions
        .iter()
        .map(|&t| {
            disk.boundary
                .iter()
                .map(|&b| {
                    points.push(apex + t * (points[b as usize] - apex));
                    (points.len() - 1) as u32
                })
                .collect()
        })
        .collect();
    let m = disk.boundary.len();
    grid.push(disk.boundary);
    let mut kept: Vec<[u32; 3]> = triangles
        .iter()
        .enumerate()
        .filter(|(i, _)| !disk.triangles.contains(i))
        .map(|(_, &tri)| tri)
        .collect();
    // The boundary runs along the disk's triangles, so each new triangle
    // turns the way the one it replaces did: outward edge first.
    for j in 0..m {
        kept.push([grid[0][j], grid[0][(j + 1) % m], c]);
    }
    for pair in grid.windows(2) {
        let (inner, outer) = (&pair[0], &pair[1]);
        for j in 0..m {
            let next = (j + 1) % m;
            kept.push([outer[j], outer[next], inner[next]]);
            kept.push([outer[j], inner[next], inner[j]]);
        }
    }
    *triangles = kept;
}

/// Each vertex within `max` edges of `c`, with its number of edges to it.
fn graph_distance(triangles: &[[u32; 3]], c: u32, max: usize) -> HashMap<u32, usize> {
    let mut neighbours: HashMap<u32, Vec<u32>> = HashMap::new();
    for tri in triangles {
        for k in 0..3 {
            neighbours
                .entry(tri[k])
                .or_default()
                .extend([tri[(k + 1) % 3], tri[(k + 2) % 3]]);
        }
    }
    let mut distance = HashMap::from([(c, 0)]);
    let mut queue = VecDeque::from([c]);
    while let Some(v) = queue.pop_front() {
        let d = distance[&v];
        if d == max {
            continue;
        }
        for &n in &neighbours[&v] {
            if let std::collections::hash_map::Entry::Vacant(e) = distance.entry(n) {
                e.insert(d + 1);
                queue.push_back(n);
            }
        }
    }
    distance
}

/// A disk of triangles around an apex.
struct Disk {
    /// Its triangles, by index.
    triangles: HashSet<usize>,
    /// Its boundary loop, turning as its triangles do.
    boundary: Vec<u32>,
}

/// The triangles holding a vertex fewer than `k` edges from `c`, when
/// they are a plain disk: no hard edge, no other corner inside, every
/// inside vertex's star whole, and a boundary that is one loop.
fn plain_disk(
    triangles: &[[u32; 3]],
    distance: &HashMap<u32, usize>,
    hard: &[[u32; 2]],
    corners: &[u32],
    c: u32,
    k: usize,
) -> Option<Disk> {
    let inside = |v: u32| distance.get(&v).is_some_and(|&d| d < k);
    let disk: HashSet<usize> = (0..triangles.len())
        .filter(|&i| triangles[i].iter().any(|&v| inside(v)))
        .collect();
    let directed: HashSet<(u32, u32)> = disk
        .iter()
        .flat_map(|&i| {
            let t = triangles[i];
            [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]
        })
        .collect();
    let has_hard = hard
        .iter()
        .any(|&[a, b]| directed.contains(&(a, b)) || directed.contains(&(b, a)));
    if has_hard || corners.iter().any(|&v| v != c && inside(v)) {
        return None;
    }
    let mut next: HashMap<u32, u32> = HashMap::new();
    for &(a, b) in &directed {
        if !directed.contains(&(b, a)) && next.insert(a, b).is_some() {
            return None;
        }
    }
    // An inside vertex on the boundary is on the net's own boundary.
    let start = *next.keys().min()?;
    if next.keys().any(|&v| inside(v)) {
        return None;
    }
    let mut boundary = vec![start];
    let mut v = next[&start];
    while v != start && boundary.len() <= next.len() {
        boundary.push(v);
        v = next[&v];
    }
    (boundary.len() == next.len()).then_some(Disk {
        triangles: disk,
        boundary,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat hexagonal patch of the triangular lattice, `n` rings of
    /// unit edges around the origin (vertex 0).
    fn hexagon(n: i32) -> Grid {
        let mut index = HashMap::new();
        let mut points = Vec::new();
        let at =
            |i: i32, j: i32| DVec3::new(i as f64 + 0.5 * j as f64, 0.75f64.sqrt() * j as f64, 0.0);
        let inside = |i: i32, j: i32| i.abs() <= n && j.abs() <= n && (i + j).abs() <= n;
        let mut order: Vec<(i32, i32)> = (-n..=n)
            .flat_map(|i| (-n..=n).map(move |j| (i, j)))
            .filter(|&(i, j)| inside(i, j))
            .collect();
        order.sort_by_key(|&(i, j)| (i.abs() + j.abs() + (i + j).abs(), i, j));
        for (i, j) in order {
            index.insert((i, j), points.len() as u32);
            points.push(at(i, j));
        }
        let mut triangles = Vec::new();
        for (&(i, j), &a) in &index {
            if let (Some(&b), Some(&c)) = (index.get(&(i + 1, j)), index.get(&(i, j + 1))) {
                triangles.push([a, b, c]);
            }
            if let (Some(&b), Some(&c)) = (index.get(&(i + 1, j)), index.get(&(i + 1, j - 1))) {
                triangles.push([a, c, b]);
            }
        }
        triangles.sort();
        Grid {
            points,
            triangles,
            hard_edges: Vec::new(),
            corners: vec![0],
        }
    }

    fn valences(grid: &Grid) -> Vec<usize> {
        let mut v = vec![0; grid.points.len()];
        for &i in grid.triangles.iter().flatten() {
            v[i as usize] += 1;
        }
        v
    }

    /// Signed area of the triangles, seen from +z.
    fn area(grid: &Grid) -> f64 {
        grid.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| grid.points[v as usize]);
                0.5 * (b - a).cross(c - a).z
            })
            .sum()
    }

    #[test]
    fn grid_covers_the_disk_with_regular_rings() {
        let before = hexagon(5);
        let area_before = area(&before);
        let after = with_polar_apexes(hexagon(5), 1.0);
        // Still a manifold, consistently oriented net covering the same
        // region: the flat patch's area is unchanged and nothing flips.
        crate::topology::Topology::new(after.points.len(), after.triangles.clone())
            .expect("a valid net");
        assert!((area(&after) - area_before).abs() < 1e-9 * area_before);
        for t in &after.triangles {
            let [a, b, c] = t.map(|v| after.points[v as usize]);
            assert!((b - a).cross(c - a).z > 0.0, "a flipped triangle");
        }
        // The disk stops at the third ring, the first with 16 or more
        // vertices (18), 2.8 from the apex on average; its rings halve
        // towards the apex down to an eighth of the spacing: 1.4, 0.7,
        // 0.35, 0.175 (0.0875 would be beyond), so four rings of 18
        // replace the 6 + 12 vertices inside.
        let valence = valences(&after);
        assert_eq!(valence[0], 18);
        assert_eq!(after.points.len(), before.points.len() - 18 + 4 * 18);
        // The new vertices come innermost ring first: that ring meets the
        // apex alone inwards (valence 5), the others two vertices each way.
        let first = before.points.len() - 18;
        assert!((first..first + 18).all(|v| valence[v] == 5), "{valence:?}");
        assert!(
            (first + 18..after.points.len()).all(|v| valence[v] == 6),
            "{valence:?}"
        );
        assert_eq!(after.corners, vec![0]);
    }

    #[test]
    fn a_hard_edge_near_the_apex_stops_the_disk() {
        let mut net = hexagon(5);
        // A hard edge between two vertices of the second ring.
        let second: Vec<u32> = (7..19).collect();
        let a = second[0];
        let b = *net
            .triangles
            .iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .find(|&(x, y)| x == a && second.contains(&y))
            .map(|(_, y)| y)
            .as_ref()
            .expect("a second-ring edge");
        net.hard_edges.push([a, b]);
        let after = with_polar_apexes(net, 1.0);
        // Only the first ring's disk (the apex's star) is plain: six round.
        assert_eq!(valences(&after)[0], 6);
        assert!(after
            .hard_edges
            .iter()
            .all(|e| e.iter().all(|&v| (v as usize) < after.points.len())));
    }
}
