//! Special-corner configurations shared by every corner of a surface that
//! looks the same, each built the first time an evaluation needs it.
//!
//! Building one (its local matrix powers) takes a fraction of a
//! millisecond, and a real net has a handful (smooth scans) to hundreds
//! (parts with creases) of distinct ones, so they are neither built up
//! front nor kept twice: any thread may ask, none waits for another, and
//! the first one stored is shared.
//!
//! A configuration depends only on the pattern of triangles, hard edges
//! and tags around a corner, never on positions, so the table may be
//! shared by several surfaces ([`ConfigurationTable`]): the parts of a
//! remeshing by parts each build the surface of their own sub-net, and on
//! a net with many creases rebuilding every configuration for each was a
//! third of their time.

use super::special::{Key, KeyScratch, SpecialPatch};
use crate::features::{Features, VertexKind};
use crate::topology::Topology;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

/// The configurations built so far, by key and (for a generic smooth
/// corner) by valence: what surfaces may share.
#[derive(Default)]
pub(crate) struct ConfigurationTable {
    by_key: Mutex<HashMap<Key, Arc<SpecialPatch>>>,
    /// The configuration of a generic smooth corner, by valence (see
    /// [`generic_smooth_valence`]): found without building its key.
    by_valence: Mutex<HashMap<usize, Arc<SpecialPatch>>>,
}

/// One surface's configurations: a table, its own or shared, and which of
/// its vertices are generic.
pub(super) struct Configurations {
    table: Arc<ConfigurationTable>,
    /// Per vertex of the refined net, [`generic_smooth_valence`] once
    /// known (each special vertex has as many corners as its valence):
    /// 0 not yet, 1 not generic, else the valence plus 2.
    generic: Box<[AtomicU8]>,
}

/// Buffers reused from one corner to the next on a thread.
#[derive(Default)]
pub(super) struct CornerScratch {
    key: KeyScratch,
    outer: Vec<u32>,
}

/// A poisoned table is still consistent: entries are only ever added whole.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl Configurations {
    /// The configurations of a refined net of `vertices` vertices, kept in
    /// `table`.
    pub fn new(vertices: usize, table: Arc<ConfigurationTable>) -> Configurations {
        Configurations {
            table,
            generic: (0..vertices).map(|_| AtomicU8::new(0)).collect(),
        }
    }

    /// The table the configurations are kept in.
    pub fn table(&self) -> &Arc<ConfigurationTable> {
        &self.table
    }

    /// [`generic_smooth_valence`] of `c`, computed once.
    fn generic_valence(
        &self,
        topo: &Topology,
        kinds: &[VertexKind],
        c: u32,
        outer: &mut Vec<u32>,
    ) -> Option<usize> {
        let known = &self.generic[c as usize];
        match known.load(Ordering::Relaxed) {
            0 => {
                let n = generic_smooth_valence(topo, kinds, c, outer);
                // Valences past 253 are not kept, only computed again.
                let code = n.map_or(Some(1), |n| u8::try_from(n + 2).ok());
                if let Some(code) = code {
                    known.store(code, Ordering::Relaxed);
                }
                n
            }
            1 => None,
            code => Some(code as usize - 2),
        }
    }

    /// The configuration of the corner triangle (c, p, q) whose corner c is
    /// special.
    pub fn of_corner(
        &self,
        topo: &Topology,
        features: &Features,
        kinds: &[VertexKind],
        corner: [u32; 3],
        scratch: &mut CornerScratch,
    ) -> Arc<SpecialPatch> {
        let generic = self.generic_valence(topo, kinds, corner[0], &mut scratch.outer);
        let table = &self.table;
        if let Some(patch) = generic.and_then(|n| lock(&table.by_valence).get(&n).cloned()) {
            return patch;
        }
        Key::around_into(topo, features, corner, &mut scratch.key);
        let key = scratch.key.key();
        let known = lock(&table.by_key).get(key).cloned();
        // Built with the table unlocked: other threads go on meanwhile, and
        // one racing to build the same keeps the first one stored.
        let patch = known.unwrap_or_else(|| {
            let built = Arc::new(key.build());
            lock(&table.by_key)
                .entry(key.clone())
                .or_insert(built)
                .clone()
        });
        if let Some(n) = generic {
            lock(&table.by_valence).insert(n, patch.clone());
        }
        patch
    }

    /// Number of distinct configurations built so far (by any surface
    /// sharing the table).
    pub fn len(&self) -> usize {
        lock(&self.table.by_key).len()
    }

    /// Bytes held by the configurations built so far (by any surface
    /// sharing the table), and the table of generic vertices.
    pub fn memory_bytes(&self) -> usize {
        self.generic.len()
            + lock(&self.table.by_key)
                .values()
                .map(|patch| patch.memory_bytes())
                .sum::<usize>()
    }
}

/// The valence N of c when c is a smooth vertex whose neighbours are all
/// smooth, of valence 6, and whose second ring is generic (the 2N outer
/// vertices distinct from each other and from c and its ring): then every
/// corner at c has the same configuration key, which depends on N alone
/// (the key reads only the triangles around c and its neighbours, their
/// hard edges and tags). After one refinement nearly every special corner
/// of a smooth net is one, so its key need not be built again.
fn generic_smooth_valence(
    topo: &Topology,
    kinds: &[VertexKind],
    c: u32,
    outer: &mut Vec<u32>,
) -> Option<usize> {
    if kinds[c as usize] != VertexKind::Smooth {
        return None;
    }
    let ring = topo.ring(c as usize);
    outer.clear();
    for &x in ring {
        if kinds[x as usize] != VertexKind::Smooth || topo.valence(x as usize) != 6 {
            return None;
        }
        let before = outer.len();
        outer.extend(
            topo.ring(x as usize)
                .iter()
                .filter(|&&y| y != c && !ring.contains(&y)),
        );
        // c and its two neighbours beside x, and three outer vertices.
        if outer.len() != before + 3 {
            return None;
        }
    }
    outer.sort_unstable();
    outer.dedup();
    // Each neighbour's outer vertices at its ends are those of the
    // neighbours beside it (across their shared edge from c): 2N distinct
    // ones when nothing else coincides.
    (outer.len() == 2 * ring.len()).then_some(ring.len())
}
