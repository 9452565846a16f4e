//! Edge flips: towards valence 6 (4 on a border), and for the largest
//! smallest angle. Curve edges are never flipped.

use super::connectivity::prev;
use super::remeshing::Remeshing;
use super::split::SPLIT_ABOVE;
use crate::topology::NONE;

/// A valence flip may not make the worse triangle's smallest angle smaller
/// than acos of this (about 25°), unless it improves it.
const FLIP_WORST_COSINE: f64 = 0.906;

impl Remeshing<'_> {
    /// The valence a vertex should have: 6 inside, 4 on a border.
    fn ideal_valence(&self, v: u32) -> i64 {
        if self.mesh.is_border_vertex(v) {
            4
        } else {
            6
        }
    }

    /// Flips unlabelled edges where that brings the four vertices' valences
    /// nearer their ideal and both new triangles are valid. Returns the count.
    pub fn equalize_valences(&mut self) -> usize {
        // Valences and ideals once, then kept up to date by each flip (its
        // edge's ends lose one, the opposite corners gain one).
        let (mut valence, ideal): (Vec<i64>, Vec<i64>) = (0..self.vertices.len() as u32)
            .map(|v| {
                if self.mesh.is_vertex_alive(v) {
                    (self.mesh.valence(v) as i64, self.ideal_valence(v))
                } else {
                    (0, 0)
                }
            })
            .unzip();
        let mut done = 0;
        for h in 0..self.mesh.num_half_edges() {
            if !self.inner_unlabelled(h) {
                continue;
            }
            let g = self.mesh.opposite(h);
            let [a, b, c] = self.mesh.corners(h);
            let d = self.mesh.origin(prev(g));
            let deviation =
                |v: u32, change: i64| (valence[v as usize] + change - ideal[v as usize]).abs();
            let before = deviation(a, 0) + deviation(b, 0) + deviation(c, 0) + deviation(d, 0);
            let after = deviation(a, -1) + deviation(b, -1) + deviation(c, 1) + deviation(d, 1);
            if after >= before {
                continue;
            }
            // Valence is worth a worse angle only up to a point.
            let (old, new) = self.flip_cosines([a, b, c, d]);
            if new > old.max(FLIP_WORST_COSINE) {
                continue;
            }
            if self.flip_allowed(h) {
                self.mesh.flip(h);
                for (v, change) in [(a, -1), (b, -1), (c, 1), (d, 1)] {
                    valence[v as usize] += change;
                }
                done += 1;
            }
        }
        done
    }

    /// Flips unlabelled edges while that enlarges the smaller of the two
    /// triangles' smallest angles (the max–min angle criterion, which is
    /// Delaunay's in the plane). Returns the count.
    pub fn flip_for_angles(&mut self) -> usize {
        // A worklist: every edge once, then the outer sides of each flipped
        // pair, which are the only edges whose criterion the flip changed.
        let mut work: Vec<u32> = (0..self.mesh.num_half_edges())
            .rev()
            .filter(|&h| self.inner_unlabelled(h))
            .collect();
        let mut done = 0;
        let budget = 8 * work.len();
        let mut visited = 0;
        while let Some(h) = work.pop() {
            visited += 1;
            if visited > budget {
                break;
            }
            let h = match self.mesh.opposite(h) {
                g if g != NONE && g < h => g,
                _ => h,
            };
            if !self.inner_unlabelled(h) {
                continue;
            }
            let g = self.mesh.opposite(h);
            let [a, b, c] = self.mesh.corners(h);
            let d = self.mesh.origin(prev(g));
            let (old, new) = self.flip_cosines([a, b, c, d]);
            if new < old - 1e-9 && self.flip_allowed(h) {
                let (s, u) = (h - h % 3, g - g % 3);
                self.mesh.flip(h);
                // After the flip, s and s + 2, u and u + 1 are the quad's sides.
                work.extend_from_slice(&[s, s + 2, u, u + 1]);
                done += 1;
            }
        }
        done
    }

    /// A live inner unlabelled edge, taken once (cheap: tested first).
    fn inner_unlabelled(&self, h: u32) -> bool {
        if !self.mesh.is_alive(h) {
            return false;
        }
        let g = self.mesh.opposite(h);
        g != NONE && h < g && self.mesh.edge_label[h as usize] == NONE
    }

    /// Whether flipping h keeps the mesh simple, makes no edge longer than
    /// a split allows, and makes valid triangles.
    fn flip_allowed(&self, h: u32) -> bool {
        if !self.may_flip(h) {
            return false;
        }
        let g = self.mesh.opposite(h);
        let (c, d) = (self.mesh.origin(prev(h)), self.mesh.origin(prev(g)));
        let length = self.vertices[c as usize]
            .x
            .distance(self.vertices[d as usize].x);
        length <= SPLIT_ABOVE * self.target(c, d) && self.flip_valid(h)
    }

    fn flip_valid(&self, h: u32) -> bool {
        let g = self.mesh.opposite(h);
        let [a, b, c] = self.mesh.corners(h);
        let d = self.mesh.origin(prev(g));
        let face = self.face(h);
        self.accept(
            [([a, d, c], face, None), ([d, b, c], face, None)],
            [([a, b, c], face, None), ([b, a, d], face, None)],
        )
    }

    /// The worse smallest-angle cosine of the two triangles (a, b, c) and
    /// (b, a, d) on edge a–b, and of the two after flipping it to c–d.
    fn flip_cosines(&self, [a, b, c, d]: [u32; 4]) -> (f64, f64) {
        let old = self
            .worst_cosine([a, b, c], None)
            .max(self.worst_cosine([b, a, d], None));
        let new = self
            .worst_cosine([a, d, c], None)
            .max(self.worst_cosine([d, b, c], None));
        (old, new)
    }
}
