//! Disjoint sets (union-find) over 0..n: the fans around a vertex, the
//! sectors between creases, the connected blobs of a mesh.

/// A partition of 0..n into sets, joined one pair at a time.
pub(crate) struct DisjointSets {
    parent: Vec<usize>,
}

impl DisjointSets {
    /// n sets of one element each.
    pub fn new(n: usize) -> DisjointSets {
        DisjointSets {
            parent: (0..n).collect(),
        }
    }

    /// The root of i's set, the path to it halved on the way.
    pub fn root(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    /// Joins the sets of a and b under the smaller root, so that the roots
    /// (and whatever is numbered by them) do not depend on the order of
    /// the joins.
    pub fn unite(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.root(a), self.root(b));
        self.parent[ra.max(rb)] = ra.min(rb);
    }
}

#[cfg(test)]
mod tests {
    use super::DisjointSets;

    #[test]
    fn joins_are_transitive_and_the_root_is_the_smallest() {
        let mut s = DisjointSets::new(6);
        s.unite(4, 2);
        s.unite(5, 4);
        s.unite(1, 3);
        assert_eq!([0, 1, 2, 3, 4, 5].map(|i| s.root(i)), [0, 1, 2, 1, 2, 2]);
        s.unite(3, 5);
        assert_eq!([0, 1, 2, 3, 4, 5].map(|i| s.root(i)), [0, 1, 1, 1, 1, 1]);
    }
}
