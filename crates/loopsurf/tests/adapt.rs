//! Adaptive subdivision (Liu & Kondo) against what it promises: uniform Loop
//! exactly at angle 0, conforming and watertight at every angle and level,
//! dead triangles kept, hard edges kept as chains, the tolerance honoured,
//! and clear errors for bad values.

mod common;

use common::{cgal_mesh, example};
use loopsurf::refine::refine_uniform;
use loopsurf::Adapter;
use loopsurf::{AdaptiveMesh, ControlNet, Surface, SurfacePoint};
use std::collections::{HashMap, HashSet};

fn cgal(name: &str) -> Option<ControlNet> {
    Some(ControlNet::read(cgal_mesh(name)?).unwrap())
}

/// Where a dyadic point of the control net is, independent of the chart
/// that names it: a control vertex, a point on a control edge (its ends in
/// order, and the weight of the first in units of 2^-levels), or a point
/// inside a control triangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Site {
    Vertex(u32),
    Edge(u32, u32, u64),
    Inside(u32, u64, u64),
}

fn site(net: &ControlNet, p: SurfacePoint, levels: u32) -> Site {
    let scale = (1u64 << levels) as f64;
    let (i, j) = ((p.v * scale) as u64, (p.w * scale) as u64);
    assert_eq!((i as f64, j as f64), (p.v * scale, p.w * scale), "dyadic");
    let weights = [(1u64 << levels) - i - j, i, j];
    let c = net.triangles()[p.tri as usize];
    let nonzero: Vec<usize> = (0..3).filter(|&k| weights[k] > 0).collect();
    match nonzero[..] {
        [k] => Site::Vertex(c[k]),
        [a, b] => {
            let (a, b) = if c[a] < c[b] { (a, b) } else { (b, a) };
            Site::Edge(c[a], c[b], weights[a])
        }
        _ => Site::Inside(p.tri, i, j),
    }
}

/// Closed input → every edge in exactly two triangles, no directed edge
/// twice (consistent orientation), and the Euler characteristic kept. An
/// unsplit edge facing a split one (a T-junction) would be an edge with
/// one triangle.
fn check_watertight(input: &ControlNet, out: &AdaptiveMesh, what: &str) {
    let mut directed = HashSet::new();
    let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
    for tri in out.net.triangles() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            assert!(
                directed.insert((a, b)),
                "{what}: directed edge {a}->{b} twice"
            );
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let open = uses.values().filter(|&&n| n != 2).count();
    assert_eq!(open, 0, "{what}: {open} edges not in exactly two triangles");
    assert_eq!(
        out.net.topology().euler_characteristic(),
        input.topology().euler_characteristic(),
        "{what}: Euler characteristic"
    );
}

#[test]
fn angle_zero_is_uniform_loop_exactly() {
    let mut cases = vec![
        ("viking 30°", example("viking", Some(30.0))),
        ("torus", example("torus", None)),
        ("cube 30°", example("cube", Some(30.0))),
    ];
    cases.extend(cgal("fandisk.off").map(|mut n| {
        n.tag_by_angle(30.0).unwrap();
        ("fandisk 30°", n)
    }));
    for (what, net) in &cases {
        let levels = 3;
        let adaptive = Adapter::new(net).angle(0.0).levels(levels).run().unwrap();
        let uniform = refine_uniform(net, levels).unwrap();
        assert_eq!(
            adaptive.net.triangles().len(),
            uniform.net().triangles().len(),
            "{what}"
        );
        assert!(adaptive.dead.iter().all(|&d| !d), "{what}: nothing dies");
        let reference: HashMap<Site, usize> = uniform
            .origins()
            .enumerate()
            .map(|(v, o)| (site(net, o.unwrap(), levels), v))
            .collect();
        let tol = 1e-12 * net.bbox_diagonal();
        for (v, (&x, &p)) in adaptive
            .net
            .points()
            .iter()
            .zip(&adaptive.params)
            .enumerate()
        {
            let u = reference[&site(net, p, levels)];
            let d = x.distance(uniform.net().points()[u]);
            assert!(
                d <= tol,
                "{what}: vertex {v} is {d} from uniform vertex {u}"
            );
        }
        assert_eq!(
            adaptive.net.features().num_hard_edges(),
            uniform.net().features().num_hard_edges(),
            "{what}: hard edges"
        );
    }
}

#[test]
fn adaptive_meshes_are_watertight_at_every_angle_and_level() {
    let mut cases = vec![
        ("sphere", example("sphere", None)),
        ("torus", example("torus", None)),
        ("viking 30°", example("viking", Some(30.0))),
    ];
    cases.extend(cgal("cow.off").map(|n| ("cow", n)));
    for (name, net) in &cases {
        for angle in [3.0, 11.0, 22.0] {
            for (levels, realign) in [(1, true), (3, true), (3, false), (4, true)] {
                let what = format!("{name} CA {angle} levels {levels} realign {realign}");
                let out = Adapter::new(net)
                    .angle(angle)
                    .levels(levels)
                    .realign(realign)
                    .run()
                    .unwrap();
                check_watertight(net, &out, &what);
                // Every vertex is where its parameters say: the same site
                // seen from every triangle that holds it.
                let mut seen: HashMap<u32, Site> = HashMap::new();
                for tri in out.net.triangles() {
                    for &v in tri {
                        let s = site(net, out.params[v as usize], levels);
                        assert_eq!(*seen.entry(v).or_insert(s), s, "{what}: vertex {v}");
                    }
                }
            }
        }
    }
}

#[test]
fn dead_triangles_are_kept_and_flat_regions_stop() {
    let Some(net) = cgal("cow.off") else { return };
    let coarse = Adapter::new(&net)
        .angle(11.0)
        .levels(2)
        .realign(false)
        .run()
        .unwrap();
    let fine = Adapter::new(&net)
        .angle(11.0)
        .levels(3)
        .realign(false)
        .run()
        .unwrap();
    let kept: HashSet<[u32; 3]> = fine.net.triangles().iter().copied().collect();
    let dead: Vec<[u32; 3]> = coarse
        .net
        .triangles()
        .iter()
        .copied()
        .filter(|t| t.iter().all(|&v| coarse.dead[v as usize]))
        .collect();
    assert!(
        dead.len() > 1000,
        "cow at 11° has dead triangles by level 2"
    );
    for t in &dead {
        assert!(kept.contains(t), "dead triangle {t:?} was split");
        for &v in t {
            assert_eq!(
                coarse.net.points()[v as usize],
                fine.net.points()[v as usize],
                "dead vertex {v} moved"
            );
        }
    }
    // Fewer triangles than uniform, more so at a larger angle and a deeper level.
    let uniform = |k: u32| net.triangles().len() * 4usize.pow(k);
    let ratio = |angle: f64, k: u32| {
        let out = Adapter::new(&net).angle(angle).levels(k).run().unwrap();
        1.0 - out.net.triangles().len() as f64 / uniform(k) as f64
    };
    let (r7, r11_3, r11_4, r22) = (
        ratio(7.0, 4),
        ratio(11.0, 3),
        ratio(11.0, 4),
        ratio(22.0, 4),
    );
    assert!(0.0 < r7 && r7 < r11_4 && r11_4 < r22, "{r7} {r11_4} {r22}");
    assert!(r11_3 < r11_4, "{r11_3} {r11_4}");
}

#[test]
fn hard_edges_stay_hard_chains() {
    let net = example("viking", Some(30.0));
    let out = Adapter::new(&net).angle(11.0).levels(4).run().unwrap();
    let topo = out.net.topology();
    let hard: Vec<[u32; 2]> = out.net.hard_edges();
    let mut next: HashMap<u32, Vec<u32>> = HashMap::new();
    for &[a, b] in &hard {
        next.entry(a).or_default().push(b);
        next.entry(b).or_default().push(a);
    }
    // Each control hard edge is a path of output hard edges whose inner
    // vertices all sit on that control edge.
    let on_edge = |v: u32, a: u32, b: u32| match site(&net, out.params[v as usize], 4) {
        Site::Edge(x, y, _) => (x, y) == (a.min(b), a.max(b)),
        Site::Vertex(x) => x == a || x == b,
        Site::Inside(..) => false,
    };
    let mut covered = 0;
    for [a, b] in net.hard_edges() {
        let (mut prev, mut at, mut steps) = (u32::MAX, a, 0);
        while at != b {
            let step = next[&at]
                .iter()
                .copied()
                .find(|&n| n != prev && on_edge(n, a, b))
                .unwrap_or_else(|| panic!("hard chain {a}-{b} broken at {at}"));
            (prev, at, steps) = (at, step, steps + 1);
            assert!(steps <= 16, "hard chain {a}-{b} too long");
        }
        covered += steps;
    }
    assert_eq!(
        covered,
        hard.len(),
        "every output hard edge is on a control hard edge"
    );
    assert!(topo.num_edges() > hard.len());
}

#[test]
fn tolerance_bounds_the_distance_to_the_limit_surface() {
    let mut cases = vec![("viking 30°", example("viking", Some(30.0)))];
    cases.extend(cgal("elephant.off").map(|n| ("elephant", n)));
    for (what, net) in &cases {
        let surface = Surface::new(net).unwrap();
        let tol = 1e-3;
        let out = Adapter::new(net)
            .tolerance(&surface, tol)
            .levels(6)
            .run()
            .unwrap();
        let uniform = net.triangles().len() * 4usize.pow(6);
        assert!(out.net.triangles().len() < uniform / 4, "{what}: adaptive");
        // Dead vertices were within the tolerance when they died and have
        // not moved; live ones are at level 6 (≈ 4^-6 of the control
        // distance).
        let diag = net.bbox_diagonal();
        let dead_max = out
            .net
            .points()
            .iter()
            .zip(&out.params)
            .zip(&out.dead)
            .filter(|(_, &d)| d)
            .map(|((&x, p), _)| x.distance(surface.point(p.tri as usize, p.v, p.w).unwrap()))
            .fold(0.0, f64::max);
        assert!(
            dead_max <= tol * diag,
            "{what}: dead vertex {} of the diagonal away",
            dead_max / diag
        );
        let snapped = out.max_surface_distance(&surface).unwrap();
        assert!(
            snapped <= tol * diag,
            "{what}: {} of the diagonal",
            snapped / diag
        );
        // Exactly on the surface when pushed there.
        let limit = out.limit_points(&surface).unwrap();
        for (x, p) in limit.iter().zip(&out.params) {
            let e = surface.eval(p.tri as usize, p.v, p.w).unwrap();
            assert_eq!(*x, e.x);
        }
    }
}

#[test]
fn bad_values_are_clear_errors() {
    let net = example("sphere", None);
    let other = Surface::new(&example("torus", None)).unwrap();
    let surface = Surface::new(&net).unwrap();
    let err = |a: loopsurf::Adapter| a.run().unwrap_err().to_string();
    assert!(err(Adapter::new(&net).angle(-1.0).levels(2)).contains("angle -1"));
    assert!(err(Adapter::new(&net).angle(f64::NAN).levels(2)).contains("angle NaN"));
    assert!(err(Adapter::new(&net).angle(180.0).levels(2)).contains("below 180"));
    assert!(err(Adapter::new(&net).angle(5.0).levels(11)).contains("levels 11: at most 10"));
    assert!(err(Adapter::new(&net).levels(2)).contains("no criterion"));
    assert!(err(Adapter::new(&net).tolerance(&surface, 0.0).levels(2)).contains("tolerance 0"));
    assert!(err(Adapter::new(&net).tolerance(&other, 1e-3).levels(2)).contains("not this net's"));
    assert!(
        err(Adapter::new(&net).angle(0.0).levels(3).max_triangles(1000)).contains("over the limit")
    );
}
