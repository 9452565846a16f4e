//! Regular patches, crease and boundary phantoms included, against the
//! exact dyadic reference: limit positions of refined vertices.

use super::{box_spline, regular};
use crate::{examples, ControlNet, DVec3};
use std::path::PathBuf;

/// (patches with only real points, patches with phantoms) checked; panics
/// on any point off the reference by more than 1e-13 of the diagonal.
fn check_regular_patches(net: &ControlNet, levels: u32) -> (usize, usize) {
    let kinds = net.vertex_kinds();
    let stencils: Vec<Option<[regular::Source; 12]>> = (0..net.triangles().len())
        .map(|t| regular::stencil(net.topology(), net.features(), &kinds, t))
        .collect();
    let refined = net.refine_uniform(levels).unwrap();
    let limits = refined.limit_points();
    let diag = net.bbox_diagonal();
    let (mut plain, mut phantom) = (0, 0);
    for (origin, limit) in refined.origins().zip(&limits) {
        let Some(o) = origin else { continue };
        let Some(s) = &stencils[o.tri as usize] else {
            continue;
        };
        let wts = box_spline::weights(o.v, o.w)[0];
        let x: DVec3 = s
            .iter()
            .zip(wts)
            .map(|(p, w)| w * p.position(net.points()))
            .sum();
        let err = (x - *limit).length();
        assert!(
            err <= 1e-13 * diag,
            "patch {} at ({}, {}) off by {:e} of the diagonal: {s:?}",
            o.tri,
            o.v,
            o.w,
            err / diag
        );
        if s.iter()
            .any(|p| matches!(p, regular::Source::Phantom { .. }))
        {
            phantom += 1;
        } else {
            plain += 1;
        }
    }
    (plain, phantom)
}

fn example(name: &str, hard_angle: Option<f64>) -> ControlNet {
    let ex = examples::by_name(name).unwrap();
    let mut net = ControlNet::from_arrays(ex.points, &ex.tris).unwrap();
    if let Some(deg) = hard_angle {
        net.tag_by_angle(deg).unwrap();
    }
    net
}

#[test]
fn smooth_regular_patches_are_box_splines() {
    let (plain, phantom) = check_regular_patches(&example("torus", None), 3);
    assert!(plain > 10_000 && phantom == 0);
}

#[test]
fn crease_patches_use_reflected_phantoms() {
    let (plain, phantom) = check_regular_patches(&example("viking", Some(30.0)), 3);
    assert!(plain > 0 && phantom > 1000, "{plain} {phantom}");
}

#[test]
fn boundary_patches_use_reflected_phantoms() {
    let (plain, phantom) = check_regular_patches(&example("open-disk", None), 3);
    assert!(phantom > 0, "{plain} {phantom}");
}

#[test]
fn cgal_regular_patches() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../.cache/cgal/data/meshes");
    for (name, angle) in [
        ("fandisk.off", Some(40.0)),
        ("pig.off", None),
        ("bunny00.off", None),
    ] {
        let path = dir.join(name);
        if !path.exists() {
            assert!(
                std::env::var_os("LOOPSURF_REQUIRE_DATA").is_none(),
                "{} missing",
                path.display()
            );
            return;
        }
        let mut net = ControlNet::read(&path).unwrap();
        if let Some(deg) = angle {
            net.tag_by_angle(deg).unwrap();
        }
        let (plain, phantom) = check_regular_patches(&net, 2);
        eprintln!("{name}: {plain} plain, {phantom} phantom");
        assert!(plain > 0);
    }
}
