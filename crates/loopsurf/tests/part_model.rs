//! The model of a part against the whole's: every owned triangle's face
//! id is the whole's, every edge of an owned triangle on a whole curve
//! (found from the curves' chains, not from edge ids) carries that
//! curve's id and no other edge carries one, the corners at owned
//! triangles are the whole's, and the parts together name every face,
//! curve and corner of the whole.

mod common;

use common::cgal_mesh;
use loopsurf::partition::{part, partition, PartModel};
use loopsurf::{ControlNet, Surface};
use std::collections::{BTreeSet, HashMap};

fn nets() -> Vec<(&'static str, ControlNet, usize)> {
    let mut nets = vec![("viking", common::example("viking", Some(30.0)), 7)];
    for (name, angle, k) in [("pig", 40.0, 7), ("fandisk", 30.0, 16)] {
        if let Some(path) = cgal_mesh(&format!("{name}.off")) {
            let mut net = ControlNet::read(path).unwrap();
            net.tag_by_angle(angle).unwrap();
            nets.push((name, net, k));
        }
    }
    assert!(
        nets.len() == 3 || std::env::var_os("LOOPSURF_SKIP_DATA").is_some(),
        "pig.off or fandisk.off is missing"
    );
    nets
}

/// Each whole curve's control edges as unordered global vertex pairs.
fn curve_of_pair(surface: &Surface) -> HashMap<(u32, u32), u32> {
    let mut pairs = HashMap::new();
    for (c, curve) in surface.model().curves().iter().enumerate() {
        for w in curve.chain.windows(2) {
            pairs.insert((w[0].min(w[1]), w[0].max(w[1])), c as u32);
        }
    }
    pairs
}

#[test]
fn a_parts_model_carries_the_wholes_ids() {
    for (name, net, k) in nets() {
        let surface = Surface::new(&net).unwrap();
        let whole = surface.model();
        let pairs = curve_of_pair(&surface);
        let partition = partition(&net, k).unwrap();
        let (mut faces, mut curves, mut corners) =
            (BTreeSet::new(), BTreeSet::new(), BTreeSet::new());
        for p in 0..k {
            let part = part(&net, &partition, p).unwrap();
            let model = PartModel::new(&net, whole, &part).unwrap();
            let (local, g) = (part.net().topology(), part.global_vertices());
            for t in part.owned() {
                let global = part.global_triangles()[t] as usize;
                assert_eq!(
                    model.face_of_triangle()[t],
                    whole.face_of_triangle()[global],
                    "{name} {p}"
                );
                assert!(model.faces().contains(&whole.face_of_triangle()[global]));
                for (i, &e) in local.triangle_edges()[t].iter().enumerate() {
                    let [a, b] = [local.triangles()[t][i], local.triangles()[t][(i + 1) % 3]];
                    let (ga, gb) = (g[a as usize], g[b as usize]);
                    let expected = pairs.get(&(ga.min(gb), ga.max(gb))).copied();
                    assert_eq!(
                        model.curve_of_edge(e as usize),
                        expected,
                        "{name} part {p} edge {ga}-{gb}"
                    );
                    if let Some(c) = expected {
                        let found = model.curves().iter().find(|(id, _)| *id == c);
                        assert_eq!(found.map(|f| &f.1), Some(&whole.curves()[c as usize]));
                    }
                }
            }
            for &(id, v) in model.corners() {
                assert_eq!(
                    whole.corners()[id as usize],
                    g[v as usize],
                    "{name} part {p}"
                );
                assert!(part.owned().any(|t| local.triangles()[t].contains(&v)));
            }
            faces.extend(model.faces().iter().copied());
            curves.extend(model.curves().iter().map(|c| c.0));
            corners.extend(model.corners().iter().map(|c| c.0));
        }
        assert_eq!(
            faces.len(),
            whole.faces().len(),
            "{name}: every face in some part"
        );
        assert_eq!(curves.len(), whole.curves().len(), "{name}: every curve");
        assert!(
            whole.faces().len() > 1 && whole.curves().len() > 1,
            "{name}: a model to compare"
        );
        let referenced = whole
            .corners()
            .iter()
            .filter(|&&v| !net.topology().is_unreferenced(v as usize));
        assert_eq!(corners.len(), referenced.count(), "{name}: every corner");
    }
}

#[test]
fn a_part_of_another_net_is_refused() {
    let viking = common::example("viking", Some(30.0));
    let other = common::bicone(8, false);
    let partition = partition(&viking, 3).unwrap();
    let piece = part(&viking, &partition, 1).unwrap();
    let model = Surface::new(&other).unwrap().model().clone();
    let err = PartModel::new(&other, &model, &piece).unwrap_err();
    assert!(err.to_string().contains("not of this one"), "{err}");
}
