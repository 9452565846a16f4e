//! Performance work on the evaluator must not change a single
//! bit of what it returns: 300 000 evaluations per mesh at seeded random
//! points (one in ten within 1e-9 of a corner, next to the special
//! vertices), their 18-number records folded into a hash, against the
//! hash the evaluator gave before that work began. A change of the
//! evaluator's arithmetic that is meant (a more accurate formula) updates
//! the constants below, and says so in its commit.

mod common;

use common::cgal_mesh;
use loopsurf::{ControlNet, Surface};

/// The seeded queries on `net`'s triangles.
fn queries(net: &ControlNet) -> Vec<(u32, f64, f64)> {
    let mut state = 12345u64;
    let mut random = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let n = net.triangles().len();
    (0..300_000)
        .map(|_| {
            let tri = (random() * n as f64) as usize % n;
            let (mut v, mut w) = (random(), random());
            if v + w > 1.0 {
                (v, w) = (1.0 - v, 1.0 - w);
            }
            if random() < 0.1 {
                (v, w) = (v * 1e-9, w * 1e-9);
            }
            (tri as u32, v, w)
        })
        .collect()
}

/// The records folded into one hash, in query order.
fn hash_of(records: impl Iterator<Item = [f64; 18]>) -> u64 {
    records
        .flatten()
        .fold(0u64, |hash, x| hash.rotate_left(7) ^ x.to_bits())
}

fn records_hash(net: &ControlNet) -> u64 {
    let surface = Surface::new(net).unwrap();
    hash_of(
        queries(net)
            .into_iter()
            .map(|(t, v, w)| surface.eval(t as usize, v, w).unwrap().record()),
    )
}

/// The same queries on a fresh surface, made by eight threads at once in
/// reverse order: patches are made on first use, by whichever thread gets
/// there first, and must not depend on which or when.
fn records_hash_in_parallel(net: &ControlNet) -> u64 {
    let surface = Surface::new(net).unwrap();
    let mut reversed = queries(net);
    reversed.reverse();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(8)
        .build()
        .unwrap();
    let mut records = pool.install(|| surface.eval_many(&reversed)).unwrap();
    records.reverse();
    hash_of(records.iter().map(|e| e.record()))
}

#[test]
fn evaluations_are_bit_identical_to_before_the_build_work() {
    let cases = [
        ("bunny00.off", None, 0x812636bd0881bd95u64),
        ("pig.off", Some(30.0), 0xa300dd1e5eb6c9cf),
        ("fandisk.off", Some(30.0), 0x787b6f66721b5d5e),
    ];
    for (name, angle, want) in cases {
        let path =
            cgal_mesh(name).unwrap_or_else(|| panic!("{name} not found: run scripts/test.sh"));
        let mut net = ControlNet::read(path).unwrap();
        if let Some(a) = angle {
            net.tag_by_angle(a).unwrap();
        }
        let got = records_hash(&net);
        assert_eq!(
            got, want,
            "{name}: evaluation records changed (hash {got:016x})"
        );
        let got = records_hash_in_parallel(&net);
        assert_eq!(
            got, want,
            "{name}: records made on eight threads in reverse order differ (hash {got:016x})"
        );
    }
}
