//! Folds of the geometry (`folds::folded_edges`, `folds::folded_patches`)
//! against an independent reference: the facets of the dyadic refinement
//! (docs/design.md), whose vertices are pushed to the limit by their limit
//! masks, with no evaluation of the patches involved.

mod common;

use common::{cgal_mesh, example};
use loopsurf::refine::refine_uniform;
use loopsurf::repair::ReadOptions;
use loopsurf::{ControlNet, Surface};
use std::collections::{BTreeSet, HashMap};

/// The control triangles whose facets of the net refined `levels` times
/// (at their limit points; only facets with every vertex inside their
/// control triangle, as `folded_patches` keeps 1/32 from the sides) turn
/// by more than 120° from one another.
fn facets_that_turn_back(net: &ControlNet, levels: u32) -> BTreeSet<usize> {
    let refined = refine_uniform(net, levels).unwrap();
    let points = refined.limit_points();
    let full = (1u32 << levels) as f64;
    let inside = |v: u32| {
        let o = refined.origin(v as usize)?;
        let (i, j) = (o.v * full, o.w * full);
        (i > 0.5 && j > 0.5 && i + j < full - 0.5).then_some(o.tri as usize)
    };
    let mut normals: HashMap<usize, Vec<loopsurf::DVec3>> = HashMap::new();
    for t in refined.net().triangles() {
        // Facets inside their control triangle, off its sides.
        let parents = t.map(inside);
        let Some(parent) = parents[0] else {
            continue;
        };
        if parents.iter().any(|&p| p != Some(parent)) {
            continue;
        }
        let [a, b, c] = t.map(|v| points[v as usize]);
        if let Some(n) = (b - a).cross(c - a).try_normalize() {
            normals.entry(parent).or_default().push(n);
        }
    }
    normals
        .into_iter()
        .filter(|(_, ns)| ns.iter().any(|a| ns.iter().any(|b| a.dot(*b) < -0.5)))
        .map(|(t, _)| t)
        .collect()
}

#[test]
fn folded_patches_are_where_the_refined_facets_turn_back() {
    // hole.off (a box with a square hole, quads) at 40°: the faces fold
    // next to the hole's rim.
    let mut nets = Vec::new();
    if let Some(path) = cgal_mesh("hole.off") {
        let opts = ReadOptions {
            triangulate: true,
            ..ReadOptions::default()
        };
        let mut net = ControlNet::read_with(path, &opts).unwrap();
        net.tag_by_angle(40.0).unwrap();
        nets.push(("hole (40°)", net, Some(true)));
    }
    nets.push(("viking (30°)", example("viking", Some(30.0)), Some(false)));
    nets.push(("cube (30°)", example("cube", Some(30.0)), Some(false)));
    // Smooth pig folds too, in two patches (43 and 46, between its
    // vertices 72 and 73).
    if let Some(path) = cgal_mesh("pig.off") {
        nets.push(("pig (smooth)", ControlNet::read(path).unwrap(), None));
    }
    for (name, net, folds) in nets {
        let surface = Surface::new(&net).unwrap();
        let found: BTreeSet<usize> = loopsurf::folds::folded_patches(&surface)
            .into_iter()
            .collect();
        let reference = facets_that_turn_back(&net, 5);
        println!("{name}: folded patches {found:?}, refined facets turning back in {reference:?}");
        if let Some(folds) = folds {
            assert_eq!(!found.is_empty(), folds, "{name}: {found:?}");
        }
        assert_eq!(found, reference, "{name}");
    }
}
