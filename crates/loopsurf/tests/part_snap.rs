//! Walks and closest points on a part, against the whole surface: a walk
//! from an owned triangle near the part's rim is the whole's bit for bit
//! unless it says it left the part, and it says so whenever the whole's
//! answer is not owned; a part's closest point is certified over its owned
//! triangles, the parts' answers meet at the whole's, and every part whose
//! answer is farther names the owner of the whole's answer among the parts
//! that may hold a nearer point.

mod common;

use common::{cgal_mesh, Lcg};
use loopsurf::partition::{part, partition};
use loopsurf::partsurface::{bounds, PartSurface};
use loopsurf::{snap, ControlNet, Surface};

fn nets() -> Vec<(&'static str, ControlNet, usize)> {
    let mut nets = vec![("viking", common::example("viking", Some(30.0)), 6)];
    if let Some(path) = cgal_mesh("pig.off") {
        let mut pig = ControlNet::read(path).unwrap();
        pig.tag_by_angle(40.0).unwrap();
        nets.push(("pig", pig, 7));
    }
    assert!(
        nets.len() == 2 || std::env::var_os("LOOPSURF_SKIP_DATA").is_some(),
        "pig.off is missing"
    );
    nets
}

/// The parts of `net` in `k` as part surfaces, with each triangle's owner.
fn parts(net: &ControlNet, k: usize) -> (Vec<PartSurface>, Vec<u32>) {
    let partition = partition(net, k).unwrap();
    let boxes = bounds(net, &partition);
    let surfaces = (0..k)
        .map(|p| PartSurface::new(part(net, &partition, p).unwrap(), p, boxes.clone()).unwrap())
        .collect();
    (surfaces, partition.parts().to_vec())
}

fn bits(s: &snap::Snap) -> [u64; 5] {
    [
        s.tri as u64,
        s.v.to_bits(),
        s.w.to_bits(),
        s.point
            .to_array()
            .map(f64::to_bits)
            .iter()
            .fold(0, |a, b| a ^ b),
        s.distance.to_bits(),
    ]
}

/// Owned triangles with a corner on another part's triangle.
fn rim_triangles(net: &ControlNet, owner: &[u32], p: u32) -> Vec<usize> {
    let topo = net.topology();
    (0..owner.len())
        .filter(|&t| owner[t] == p)
        .filter(|&t| {
            net.triangles()[t]
                .iter()
                .any(|&c| topo.fan(c as usize).iter().any(|&s| owner[s as usize] != p))
        })
        .collect()
}

#[test]
fn walks_near_rims_are_the_wholes_or_say_they_left() {
    let (mut same, mut left) = (0, 0);
    for (name, net, k) in nets() {
        let whole = Surface::new(&net).unwrap();
        let (surfaces, owner) = parts(&net, k);
        let mut rng = Lcg(7);
        let size = net.bbox_diagonal();
        for (p, ps) in surfaces.iter().enumerate() {
            for t in rim_triangles(&net, &owner, p as u32).into_iter().step_by(3) {
                // A target off a point of a triangle around t's corners
                // (often another part's), from t's centre.
                let c = net.triangles()[t][(rng.next() * 3.0) as usize] as usize;
                let fan = net.topology().fan(c);
                let s = fan[(rng.next() * fan.len() as f64) as usize] as usize;
                let x = whole.eval(s, 0.3 * rng.next(), 0.3 * rng.next()).unwrap().x;
                let target = x + 1e-3 * size * rng.direction();
                let expected = snap::project(&whole, target, t, 1.0 / 3.0, 1.0 / 3.0).unwrap();
                let got = ps.project(target, t as u32, 1.0 / 3.0, 1.0 / 3.0).unwrap();
                if owner[expected.tri] != p as u32 {
                    assert!(
                        got.left_at.is_some(),
                        "{name} part {p}: from {t} to {target}"
                    );
                }
                match got.left_at {
                    None => {
                        assert_eq!(bits(&got.snap), bits(&expected), "{name} part {p} from {t}");
                        same += 1;
                    }
                    Some(u) => {
                        assert_ne!(owner[u as usize], p as u32);
                        assert_eq!(owner[got.snap.tri], p as u32);
                        left += 1;
                    }
                }
            }
        }
    }
    // Both answers were met.
    assert!(same > 20 && left > 20, "{same} the whole's, {left} left");
}

#[test]
fn closest_points_over_parts_meet_at_the_wholes() {
    for (name, net, k) in nets() {
        let whole = Surface::new(&net).unwrap();
        let (surfaces, owner) = parts(&net, k);
        let size = net.bbox_diagonal();
        // The certificates' tolerance, twice: each side may be off by one.
        let tol = 2e-12 * size;
        let mut rng = Lcg(11);
        for i in 0..40 {
            let t = (rng.next() * owner.len() as f64) as usize;
            let x = whole.eval(t, 0.3, 0.3).unwrap().x;
            let p = x + (0.002 + 0.05 * rng.next()) * size * rng.direction();
            let expected = snap::closest_point(&whole, p).unwrap();
            let answers: Vec<_> = surfaces
                .iter()
                .map(|s| s.closest_point(p).unwrap())
                .collect();
            let best = answers
                .iter()
                .map(|a| a.snap.distance)
                .fold(f64::INFINITY, f64::min);
            assert!((best - expected.distance).abs() <= tol, "{name} point {i}");
            let home = owner[expected.tri];
            for (q, a) in answers.iter().enumerate() {
                assert_eq!(owner[a.snap.tri], q as u32, "{name}: an owned answer");
                assert!(a.snap.distance >= expected.distance - tol);
                assert!(a.snap.lower_bound <= a.snap.distance);
                if a.snap.distance > expected.distance + tol {
                    assert!(
                        a.nearer_parts.contains(&home),
                        "{name} point {i}: part {q} does not name part {home}"
                    );
                }
            }
        }
    }
}
