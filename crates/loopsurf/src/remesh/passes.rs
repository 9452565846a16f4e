//! The passes of isotropic remeshing (Botsch & Kobbelt 2004, as in CGAL's
//! and PMP's remeshers) with every vertex on the exact surface: split long
//! edges, collapse short ones, flip towards valence 6, relax tangentially,
//! and finally flip for the largest smallest angle.
//!
//! The expensive part, placing a vertex on the surface, runs in parallel
//! over a whole pass's candidates from the mesh as it was; the changes are
//! then applied one by one, each checked against the mesh as it is by then.
//! A change is applied only if every triangle it makes is valid: not
//! degenerate, and facing the way the surface does at its free vertices
//! (the normal of the surface there, not of neighbouring triangles, so
//! that folds cannot creep in step by step).

use super::connectivity::{next, prev, Connectivity};
use super::vertices::{Kind, Placer, Vertex};
use crate::geometry::max_cosine;
use crate::topology::NONE;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashSet;

/// Edges longer than this times their target are split…
pub(crate) const SPLIT_ABOVE: f64 = 4.0 / 3.0;
/// …and shorter than this collapsed (CGAL's and PMP's bounds).
pub(crate) const COLLAPSE_BELOW: f64 = 4.0 / 5.0;
/// The remeshed edges average shorter than their targets (they lie within
/// [4/5, 4/3] of them, most below 1): a finished mesh has 1.18–1.22 times
/// the triangles its sizes' areas say (pig at 0.5%, pig 40° and fandisk
/// at 1e-4 adapted, the Viking adapted).
pub(crate) const EDGES_SHORT_BY: f64 = 1.2;
/// A triangle may tilt against the surface normal at its free vertices by
/// at most acos of this (about 78°).
const MIN_COSINE: f64 = 0.2;

/// The mesh being remeshed.
pub(crate) struct Remeshing<'a> {
    pub placer: Placer<'a>,
    pub mesh: Connectivity,
    pub vertices: Vec<Vertex>,
    pub size: Vec<f64>,
    scratch: [Vec<u32>; 2],
}

/// A vertex about to change: its id and its new state.
type Moved<'v> = Option<(u32, &'v Vertex)>;

impl<'a> Remeshing<'a> {
    pub fn new(placer: Placer<'a>, mesh: Connectivity, vertices: Vec<Vertex>) -> Remeshing<'a> {
        let size = vec![f64::INFINITY; vertices.len()];
        Remeshing {
            placer,
            mesh,
            vertices,
            size,
            scratch: [Vec::new(), Vec::new()],
        }
    }

    /// Drops dead vertices and triangles and renumbers both along a
    /// Z-order curve through the vertices' positions
    /// ([`Connectivity::renumber`]): splits append their vertices at the
    /// end and collapses leave holes, and after a round the passes' walks
    /// would jump across memory at every step.
    pub fn renumber(&mut self) {
        let live: Vec<u32> = (0..self.vertices.len() as u32)
            .filter(|&v| self.mesh.is_vertex_alive(v))
            .collect();
        let (lo, hi) = live.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &v| {
                let x = self.vertices[v as usize].x;
                (lo.min(x), hi.max(x))
            },
        );
        let scale = (Z_CELLS - 1.0) / (hi - lo).max_element().max(f64::MIN_POSITIVE);
        let mut keyed: Vec<(u64, u32)> = live
            .par_iter()
            .map(|&v| {
                let q = ((self.vertices[v as usize].x - lo) * scale).as_uvec3();
                (z_order(q.x) | z_order(q.y) << 1 | z_order(q.z) << 2, v)
            })
            .collect();
        keyed.par_sort_unstable();
        let order: Vec<u32> = keyed.into_iter().map(|(_, v)| v).collect();
        self.mesh.renumber(&order);
        self.vertices = order.iter().map(|&v| self.vertices[v as usize]).collect();
        self.size = order.iter().map(|&v| self.size[v as usize]).collect();
    }

    fn target(&self, a: u32, b: u32) -> f64 {
        0.5 * (self.size[a as usize] + self.size[b as usize])
    }

    fn point(&self, v: u32, moved: Moved) -> DVec3 {
        match moved {
            Some((m, x)) if m == v => x.x,
            _ => self.vertices[v as usize].x,
        }
    }

    fn length(&self, h: u32) -> f64 {
        let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
        self.vertices[a as usize]
            .x
            .distance(self.vertices[b as usize].x)
    }

    /// The curve vertex midway in t between the ends of h, when h runs
    /// along a curve: exact, and always between the ends (the point
    /// nearest the chord's midpoint need not be, where the curve turns
    /// sharply).
    fn curve_midpoint(&self, h: u32) -> Option<Vertex> {
        let label = self.mesh.edge_label[h as usize];
        if label == NONE {
            return None;
        }
        let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
        let (va, vb) = (&self.vertices[a as usize], &self.vertices[b as usize]);
        let ta = self.placer.t_on(va, label, None);
        let tb = self.placer.t_on(vb, label, ta);
        let ta = self.placer.t_on(va, label, tb).or(ta);
        let t = self.placer.mid_t(label, ta?, tb?);
        self.placer.at_curve(label, t).ok()
    }

    /// Each live edge once: its half-edge with the larger opposite, or the
    /// border one.
    fn edges(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.mesh.num_half_edges()).filter(move |&h| {
            self.mesh.is_alive(h) && {
                let o = self.mesh.opposite(h);
                o == NONE || h < o
            }
        })
    }

    /// How well triangle `ids` (of face `face`), with `moved` in place,
    /// faces the way the surface does: the smallest cosine between its
    /// normal and the surface normal at its free vertices (and, with a
    /// corner on a feature, at its centroid's projection) or, with none
    /// free, at its first corner that has one seen from the face; −∞ if
    /// degenerate.
    fn alignment(&self, ids: [u32; 3], face: u32, moved: Moved) -> f64 {
        let p = ids.map(|v| self.point(v, moved));
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let scale = (0..3)
            .map(|k| p[k].distance_squared(p[(k + 1) % 3]))
            .fold(0.0, f64::max);
        if !(n.length() > 1e-12 * scale) {
            return f64::NEG_INFINITY;
        }
        let n = n.normalize();
        let vertex = |v: u32| match moved {
            Some((m, x)) if m == v => x,
            _ => &self.vertices[v as usize],
        };
        let free = ids
            .iter()
            .map(|&v| vertex(v))
            .filter(|v| v.is_free() && v.normal != DVec3::ZERO)
            .map(|v| v.normal.dot(n))
            .reduce(f64::min);
        if let Some(worst) = free {
            if ids.iter().all(|&v| vertex(v).is_free()) {
                return worst;
            }
            // A corner on a feature: between it and the free ones the
            // surface may turn further than their normals show (next to
            // pig's triangle 556, all three of whose sides are creases, a
            // triangle stood on the surface, its free corners' normals
            // within 25° of its own and the surface's at its centroid at
            // 91°). So also the normal at the centroid's projection.
            let s = self.placer.surface;
            let from = ids.iter().map(|&v| vertex(v)).find(|v| v.is_free());
            let centroid = from.and_then(|v| {
                crate::snap::project(
                    s,
                    (p[0] + p[1] + p[2]) / 3.0,
                    v.at.tri as usize,
                    v.at.v,
                    v.at.w,
                )
                .ok()
            });
            let at_centroid = centroid
                .and_then(|c| s.normal(c.tri, c.v, c.w).ok())
                .filter(|m| *m != DVec3::ZERO)
                .map_or(1.0, |m| m.dot(n));
            return worst.min(at_centroid);
        }
        // No free corner: a triangle whose corners all lie on features can
        // span what its face does not (across a re-entrant corner of a flat
        // face), and there its centroid lies far off the surface.
        let s = self.placer.surface;
        let at = self.placer.guess_in(vertex(ids[0]), face);
        let off = crate::snap::project(s, (p[0] + p[1] + p[2]) / 3.0, at.tri as usize, at.v, at.w)
            .map_or(0.0, |snap| snap.distance);
        if off * off > OFF_SURFACE * OFF_SURFACE * scale {
            return f64::NEG_INFINITY;
        }
        ids.iter()
            .find_map(|&v| {
                let at = self.placer.guess_in(vertex(v), face);
                s.normal(at.tri as usize, at.v, at.w)
                    .ok()
                    .filter(|m| *m != DVec3::ZERO)
                    .map(|m| m.dot(n))
            })
            .unwrap_or(1.0)
    }

    /// Whether triangles `new` may replace triangles `old` (each as ids,
    /// face, moved vertex): none degenerate, and each facing within
    /// [`MIN_COSINE`] of the surface — or no worse than the worst it
    /// replaces, so that a poor start can only improve.
    fn accept<'v>(
        &self,
        new: impl IntoIterator<Item = ([u32; 3], u32, Moved<'v>)>,
        old: impl IntoIterator<Item = ([u32; 3], u32, Moved<'v>)>,
    ) -> bool {
        let fresh = self.worst_alignment(new);
        if fresh >= MIN_COSINE {
            return true;
        }
        fresh > f64::NEG_INFINITY && fresh >= self.worst_alignment(old)
    }

    /// The smallest [`Remeshing::alignment`] of triangles `tris`.
    fn worst_alignment<'v>(
        &self,
        tris: impl IntoIterator<Item = ([u32; 3], u32, Moved<'v>)>,
    ) -> f64 {
        let mut worst = f64::INFINITY;
        for (ids, face, moved) in tris {
            worst = worst.min(self.alignment(ids, face, moved));
        }
        worst
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

    /// The smallest angle's cosine (larger is worse) of triangle `ids`.
    fn worst_cosine(&self, ids: [u32; 3], moved: Moved) -> f64 {
        let [a, b, c] = ids.map(|v| self.point(v, moved));
        max_cosine(a, b, c)
    }

    /// The face of the triangle of half-edge h.
    fn face(&self, h: u32) -> u32 {
        self.mesh.face[(h / 3) as usize]
    }

    /// The new vertex at the middle of h's edge: on its curve if the edge is
    /// labelled, else on the surface in the edge's face.
    fn midpoint(&self, h: u32) -> Option<Vertex> {
        let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
        let (va, vb) = (&self.vertices[a as usize], &self.vertices[b as usize]);
        if self.mesh.edge_label[h as usize] != NONE {
            return self.curve_midpoint(h);
        }
        let face = self.face(h);
        let guess = if va.is_free() {
            va.at
        } else if vb.is_free() {
            vb.at
        } else {
            self.placer.guess_in(va, face)
        };
        // A projection that lands farther than half the edge from the
        // chord's midpoint went to another sheet of a folded surface.
        let (mid, reach) = (0.5 * (va.x + vb.x), 0.5 * va.x.distance(vb.x));
        self.placer
            .free(mid, guess, face)
            .filter(|m| m.x.distance(mid) <= reach)
            .or_else(|| self.placer.between_in(va, vb, face))
    }

    /// The number of triangles the sizes ask for: each live triangle's
    /// area over that of an equilateral triangle of its corners' mean
    /// size, times [`EDGES_SHORT_BY`]. Cheap, and known before the splits
    /// that would build them.
    pub fn expected_triangles(&self) -> f64 {
        EDGES_SHORT_BY
            * (0..self.mesh.num_half_edges() / 3)
                .into_par_iter()
                .map(|t| 3 * t)
                .filter(|&h| self.mesh.is_alive(h))
                .map(|h| {
                    let c = self.mesh.corners(h);
                    let p = c.map(|v| self.vertices[v as usize].x);
                    let s = c.iter().map(|&v| self.size[v as usize]).sum::<f64>() / 3.0;
                    let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
                    area / (0.25 * 3f64.sqrt() * s * s)
                })
                .sum::<f64>()
    }

    /// Splits every edge longer than [`SPLIT_ABOVE`] × its target, again
    /// and again until none is (or none can be), or until the mesh holds
    /// more than `limit` triangle slots (a bound on memory, checked
    /// after each sweep). Returns the count.
    ///
    /// An edge whose split was refused is tried again only once a
    /// triangle on it has changed (its opposite corners) or it is walked
    /// the other way (the midpoint's projection starts from the first
    /// end, and from one end it can stop on a feature where from the
    /// other it lands): on a surface that folds, refused splits are the
    /// many (mpi.off at 40°: some 5 000 in every sweep, a handful done,
    /// and each sweep placed every midpoint again). Making the split the
    /// same both ways, and the key with it, was tried: it changed which
    /// splits land on folded patches, and anchor.off came out 2.8–18%
    /// below 20° where this key gave 2.1% (both before crease triangles
    /// were checked at their centroid).
    pub fn split_long(&mut self, limit: usize) -> usize {
        let mut total = 0;
        let mut refused: HashSet<[u32; 4]> = HashSet::new();
        for _ in 0..32 {
            if self.mesh.num_half_edges() as usize / 3 > limit {
                break;
            }
            let long: Vec<(u32, u32)> = self
                .edges()
                .filter(|&h| {
                    let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
                    self.length(h) > SPLIT_ABOVE * self.target(a, b)
                        && !refused.contains(&self.edge_key(h))
                })
                .map(|h| (self.mesh.origin(h), self.mesh.dest(h)))
                .collect();
            let placed: Vec<Option<Vertex>> = long
                .par_iter()
                .map(|&(a, b)| self.mesh.find(a, b).and_then(|h| self.midpoint(h)))
                .collect();
            let mut done = 0;
            for (&(a, b), m) in long.iter().zip(placed) {
                let Some(h) = self.mesh.find(a, b) else {
                    continue;
                };
                let Some(m) = m else {
                    refused.insert(self.edge_key(h));
                    continue;
                };
                // The projected midpoint may lie on the other sheet of a
                // sharp fold inside one face (next to a crease that ends
                // in it): then halfway in the parameters of a control
                // triangle holding both ends.
                let m = if self.split_valid(h, &m) {
                    Some(m)
                } else if self.mesh.edge_label[h as usize] != NONE {
                    None
                } else {
                    let (va, vb) = (&self.vertices[a as usize], &self.vertices[b as usize]);
                    self.placer
                        .between_in(va, vb, self.face(h))
                        .filter(|m| self.split_valid(h, m))
                };
                if let Some(m) = m {
                    let id = self.mesh.add_vertex();
                    self.vertices.push(m);
                    self.size.push(self.target(a, b));
                    self.mesh.split(h, id);
                    done += 1;
                } else {
                    refused.insert(self.edge_key(h));
                }
            }
            total += done;
            if done == 0 {
                break;
            }
        }
        total
    }

    /// An edge walked from its lower half-edge (as [`Remeshing::edges`]
    /// walks it, so the way its split is tried), with the corners opposite
    /// it: the same key, the same split of the same two triangles.
    fn edge_key(&self, h: u32) -> [u32; 4] {
        let o = self.mesh.opposite(h);
        let (h, o) = if o != NONE && o < h { (o, h) } else { (h, o) };
        let across = if o == NONE {
            NONE
        } else {
            self.mesh.origin(prev(o))
        };
        [
            self.mesh.origin(h),
            self.mesh.dest(h),
            self.mesh.origin(prev(h)),
            across,
        ]
    }

    /// Whether the four (or two) triangles of splitting h at m may replace
    /// the two (or one) on the edge.
    fn split_valid(&self, h: u32, m: &Vertex) -> bool {
        let id = self.vertices.len() as u32;
        let moved = Some((id, m));
        let sides: Vec<u32> = [h, self.mesh.opposite(h)]
            .into_iter()
            .filter(|&e| e != NONE)
            .collect();
        let new = sides.iter().flat_map(|&e| {
            let (a, b, c) = (
                self.mesh.origin(e),
                self.mesh.dest(e),
                self.mesh.origin(prev(e)),
            );
            let face = self.face(e);
            [([a, id, c], face, moved), ([id, b, c], face, moved)]
        });
        let old = sides
            .iter()
            .map(|&e| (self.mesh.corners(e), self.face(e), None));
        self.accept(new, old)
    }

    /// Collapses edges shorter than [`COLLAPSE_BELOW`] × their target where
    /// the features allow and no edge of the result exceeds
    /// [`SPLIT_ABOVE`] × its target. Returns the count.
    pub fn collapse_short(&mut self) -> usize {
        let is_short = |this: &Self, h: u32| {
            let (a, b) = (this.mesh.origin(h), this.mesh.dest(h));
            this.length(h) < COLLAPSE_BELOW * this.target(a, b)
        };
        // The short edges of the mesh as it is, found in parallel; each is
        // checked again when its turn comes, as earlier collapses may have
        // removed or lengthened it. (An edge that an earlier collapse
        // shortens waits for the next round.)
        let short: Vec<u32> = (0..self.mesh.num_half_edges())
            .into_par_iter()
            .filter(|&h| {
                let g = self.mesh.opposite(h);
                self.mesh.is_alive(h) && (g == NONE || h < g) && is_short(self, h)
            })
            .collect();
        let mut done = 0;
        for h in short {
            if !self.mesh.is_alive(h) || !is_short(self, h) {
                continue;
            }
            let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
            for remove in [a, b] {
                if self.can_collapse(h, remove) {
                    self.mesh.collapse(h, remove);
                    done += 1;
                    break;
                }
            }
        }
        done
    }

    /// Whether h's edge may collapse with `remove` merging into the other
    /// end (see [`Remeshing::collapse_short`]).
    fn can_collapse(&mut self, h: u32, remove: u32) -> bool {
        let label = self.mesh.edge_label[h as usize];
        let keep = if self.mesh.origin(h) == remove {
            self.mesh.dest(h)
        } else {
            self.mesh.origin(h)
        };
        match self.vertices[remove as usize].kind {
            Kind::Corner { .. } => return false,
            Kind::Curve { curve, .. } if label != curve => return false,
            Kind::Free if label != NONE => return false,
            _ => {}
        }
        // Two labelled sides of one triangle would merge into one edge.
        let g = self.mesh.opposite(h);
        for e in [h, g] {
            if e != NONE
                && self.mesh.edge_label[next(e) as usize] != NONE
                && self.mesh.edge_label[prev(e) as usize] != NONE
            {
                return false;
            }
        }
        let mut scratch = std::mem::take(&mut self.scratch);
        let topological = self.mesh.can_collapse(h, &mut scratch);
        self.scratch = scratch;
        if !topological {
            return false;
        }
        // The triangles around `remove` other than the two on the edge,
        // with `keep` in its place.
        let x = self.vertices[keep as usize].x;
        let outgoing: Vec<u32> = self.mesh.outgoing(remove).collect();
        let border_last = self
            .mesh
            .is_border_vertex(remove)
            .then(|| outgoing.last().map(|&l| self.mesh.origin(prev(l))))
            .flatten();
        let mut new = Vec::with_capacity(outgoing.len());
        let gone = self.vertices[remove as usize].x;
        for &e in &outgoing {
            let y = self.mesh.dest(e);
            // A new curve edge stands for the curve through `remove`: its
            // length is that path's, not its chord's, or a crease's
            // hairpin turn would be cut off by one short chord.
            let length = if self.mesh.edge_label[e as usize] != NONE {
                x.distance(gone) + gone.distance(self.vertices[y as usize].x)
            } else {
                x.distance(self.vertices[y as usize].x)
            };
            if y != keep && length > SPLIT_ABOVE * self.target(keep, y) {
                return false;
            }
            let z = self.mesh.origin(prev(e));
            if y != keep && z != keep {
                new.push(([keep, y, z], self.face(e), None));
            }
        }
        let old = outgoing
            .iter()
            .map(|&e| (self.mesh.corners(e), self.face(e), None));
        if !self.accept(new, old) {
            return false;
        }
        if let Some(y) = border_last {
            // The boundary through `remove`, as for curve edges above.
            let length = x.distance(gone) + gone.distance(self.vertices[y as usize].x);
            if y != keep && length > SPLIT_ABOVE * self.target(keep, y) {
                return false;
            }
        }
        true
    }

    /// Removes caps: a free vertex v whose angle in a triangle (a, b, v) is
    /// above [`CAP_ANGLE`], opposite a curve edge (a, b), sits too near the
    /// curve for any flip (the edge is fixed) or relaxation to make the
    /// triangle good. The curve edge is split at its point nearest v, and v
    /// merges into that new curve vertex: the cap vanishes, and v's other
    /// triangles take the curve vertex for v. Done only where the result
    /// passes the usual acceptance against the triangles it replaces.
    pub fn remove_caps(&mut self) -> usize {
        let cos_cap = CAP_ANGLE.to_radians().cos();
        let mut done = 0;
        for h in 0..self.mesh.num_half_edges() {
            if !self.mesh.is_alive(h) || self.mesh.edge_label[h as usize] == NONE {
                continue;
            }
            let (a, b, v) = (
                self.mesh.origin(h),
                self.mesh.dest(h),
                self.mesh.origin(prev(h)),
            );
            if !self.vertices[v as usize].is_free() {
                continue;
            }
            let [xa, xb, xv] = [a, b, v].map(|i| self.vertices[i as usize].x);
            let (u, w) = (xa - xv, xb - xv);
            if u.dot(w) / (u.length() * w.length()) > cos_cap {
                continue;
            }
            if self.remove_cap(h, v) {
                done += 1;
            }
        }
        done
    }

    /// [`Remeshing::remove_caps`] on the cap of half-edge h (a → b) with
    /// free corner v.
    fn remove_cap(&mut self, h: u32, v: u32) -> bool {
        let label = self.mesh.edge_label[h as usize];
        let (a, b) = (self.mesh.origin(h), self.mesh.dest(h));
        let (va, vb) = (&self.vertices[a as usize], &self.vertices[b as usize]);
        let ta = self.placer.t_on(va, label, None);
        let tb = self.placer.t_on(vb, label, ta);
        let ta = self.placer.t_on(va, label, tb).or(ta);
        let (Some(ta), Some(tb)) = (ta, tb) else {
            return false;
        };
        let mid = self.placer.mid_t(label, ta, tb);
        let x = self.vertices[v as usize].x;
        let Some(m) = self.placer.on_curve(x, label, mid, ta, tb) else {
            return false;
        };
        // The link condition after the split: v and the corner across the
        // curve must not be joined already.
        let g = self.mesh.opposite(h);
        let across = (g != NONE).then(|| self.mesh.origin(prev(g)));
        if across.is_some_and(|w| self.mesh.joined(v, w)) || self.mesh.is_border_vertex(v) {
            return false;
        }
        // a and b each lose their edge to v.
        if self.mesh.valence(a) <= 3 || self.mesh.valence(b) <= 3 {
            return false;
        }
        let id = self.vertices.len() as u32;
        let moved = Some((id, &m));
        let mut new = Vec::new();
        let mut old = Vec::new();
        for e in self.mesh.outgoing(v) {
            let tri = self.mesh.corners(e);
            old.push((tri, self.face(e), None));
            if tri.contains(&a) && tri.contains(&b) {
                continue;
            }
            new.push((
                tri.map(|x| if x == v { id } else { x }),
                self.face(e),
                moved,
            ));
        }
        if let Some(w) = across {
            let face = self.face(g);
            old.push((self.mesh.corners(g), face, None));
            new.push(([b, id, w], face, moved));
            new.push(([id, a, w], face, moved));
        }
        if !self.accept(new, old) {
            return false;
        }
        let size = self.size[v as usize];
        let id = self.mesh.add_vertex();
        self.vertices.push(m);
        self.size.push(size);
        self.mesh.split(h, id);
        let Some(e) = self.mesh.find(v, id) else {
            unreachable!("the split joins v to the new vertex");
        };
        self.mesh.collapse(e, v);
        true
    }

    /// The valence a vertex should have: 6 inside, 4 on a border.    /// The valence a vertex should have: 6 inside, 4 on a border.
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
        if !self.mesh.can_flip(h) {
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

    /// Shakes every free vertex by up to `amount` of its target size in a
    /// pseudo-random tangent direction (fixed by its index, so the result
    /// is deterministic). A start copied from a lattice of right triangles
    /// (a flat CAD face's chart) is a fixed point of the other passes —
    /// valence 6 everywhere, every vertex at its centroid, every diagonal
    /// co-circular — at 45° triangles; shaken, the flips and relaxation
    /// find the equilateral arrangement. Returns the number moved.
    pub fn shake(&mut self, amount: f64) -> usize {
        let moves: Vec<Option<Vertex>> = (0..self.vertices.len() as u32)
            .into_par_iter()
            .map(|v| {
                let vertex = &self.vertices[v as usize];
                if !self.mesh.is_vertex_alive(v) || !vertex.is_free() {
                    return None;
                }
                let face = self.face(self.mesh.outgoing(v).next()?);
                // A splitmix64 hash of the index: an angle and a radius.
                let mut z = (v as u64).wrapping_add(0x9e3779b97f4a7c15);
                z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
                z ^= z >> 31;
                let angle = (z & 0xffff_ffff) as f64 / 4294967296.0 * std::f64::consts::TAU;
                let radius = (z >> 32) as f64 / 4294967296.0 * amount * self.size[v as usize];
                let n = vertex.normal;
                let e1 = n.any_orthonormal_vector();
                let e2 = n.cross(e1);
                let target = vertex.x + radius * (angle.cos() * e1 + angle.sin() * e2);
                self.placer.nudge(vertex, target, face)
            })
            .collect();
        // A shake may worsen angles, but not below 30°.
        self.apply_moves(moves, Some(SHAKE_WORST_COSINE))
    }

    /// Moves every free vertex towards the area-weighted centroid of its
    /// triangles within its tangent plane, and every curve vertex towards
    /// the middle of its two curve neighbours along the curve; each lands on
    /// the surface (curve) by projection and stays only if its triangles
    /// stay valid. Returns the number moved.
    pub fn relax(&mut self) -> usize {
        self.relax_with(None)
    }

    /// [`Remeshing::relax`] keeping only the moves that leave the smallest
    /// angle around the vertex no smaller.
    pub fn relax_guarded(&mut self) -> usize {
        // No cosine is below −1: the floor is each vertex's own worst.
        self.relax_with(Some(-1.0))
    }

    fn relax_with(&mut self, floor: Option<f64>) -> usize {
        let targets: Vec<Option<Vertex>> = (0..self.vertices.len() as u32)
            .into_par_iter()
            .map(|v| self.relaxed(v))
            .collect();
        self.apply_moves(targets, floor)
    }

    /// Applies moves (one per vertex, `None` for none) one by one against
    /// the mesh as it is by then: each only if [`Remeshing::accept`] takes
    /// its triangles and, with `floor`, none of them gets a smallest-angle
    /// cosine above it unless it had one already. Returns the number moved.
    fn apply_moves(&mut self, targets: Vec<Option<Vertex>>, floor: Option<f64>) -> usize {
        let mut moved = 0;
        let mut around: Vec<([u32; 3], u32)> = Vec::new();
        for (v, target) in targets.into_iter().enumerate() {
            let Some(target) = target else { continue };
            let v = v as u32;
            around.clear();
            around.extend(
                self.mesh
                    .outgoing(v)
                    .map(|h| (self.mesh.corners(h), self.face(h))),
            );
            let worst = |moved| {
                around
                    .iter()
                    .map(|&(ids, _)| self.worst_cosine(ids, moved))
                    .fold(-1.0, f64::max)
            };
            let fair = floor.map_or(true, |f| worst(Some((v, &target))) <= worst(None).max(f));
            let ok = fair
                && self.accept(
                    around.iter().map(|&(ids, f)| (ids, f, Some((v, &target)))),
                    around.iter().map(|&(ids, f)| (ids, f, None)),
                );
            if ok {
                self.vertices[v as usize] = target;
                moved += 1;
            }
        }
        moved
    }

    /// Where relaxation would put vertex v, if anywhere.
    fn relaxed(&self, v: u32) -> Option<Vertex> {
        if !self.mesh.is_vertex_alive(v) {
            return None;
        }
        let vertex = &self.vertices[v as usize];
        match vertex.kind {
            Kind::Corner { .. } => None,
            Kind::Free => {
                let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
                let mut face = NONE;
                for h in self.mesh.outgoing(v) {
                    // Centroids weighted by area in units of the local
                    // size: where sizes grade, plain area would pull every
                    // vertex towards the coarse side.
                    let ids = self.mesh.corners(h);
                    let [a, b, c] = ids.map(|i| self.vertices[i as usize].x);
                    let size = ids.iter().map(|&i| self.size[i as usize]).sum::<f64>() / 3.0;
                    let w = (b - a).cross(c - a).length() / (size * size);
                    sum += w * (a + b + c) / 3.0;
                    weight += w;
                    face = self.face(h);
                }
                if !(weight > 0.0) {
                    return None;
                }
                let n = vertex.normal;
                let step = sum / weight - vertex.x;
                let target = vertex.x + step - n * n.dot(step);
                // As for a split: a landing far from the target is on
                // another sheet.
                let reach = step.length().max(1e-3 * self.size[v as usize]);
                self.placer
                    .nudge(vertex, target, face)
                    .filter(|m| m.x.distance(target) <= reach)
            }
            Kind::Curve { curve, t } => {
                let mut ends = [DVec3::ZERO; 2];
                let mut sizes = [0.0; 2];
                let mut params = [None; 2];
                let mut count = 0;
                let mut visit = |h: u32, other: u32| {
                    if self.mesh.edge_label[h as usize] == curve {
                        if count < 2 {
                            let o = &self.vertices[other as usize];
                            ends[count] = o.x;
                            sizes[count] = self.size[other as usize];
                            params[count] = self.placer.t_on(o, curve, Some(t));
                        }
                        count += 1;
                    }
                };
                let mut last = NONE;
                for h in self.mesh.outgoing(v) {
                    visit(h, self.mesh.dest(h));
                    last = h;
                }
                if self.mesh.is_border_vertex(v) {
                    let p = prev(last);
                    visit(p, self.mesh.origin(p));
                }
                let (2, [Some(t0), Some(t1)]) = (count, params) else {
                    return None;
                };
                // It stays between its neighbours along the curve, near
                // the point of their chord that splits it as their sizes
                // ask (the midpoint where sizes are uniform); where that
                // slides it much nearer one than the other (down one arm
                // of a sharp turn of a boundary), at the point as far from
                // both.
                let [w0, w1] = sizes.map(|h| h + self.size[v as usize]);
                let near = self.placer.on_curve(
                    (w1 * ends[0] + w0 * ends[1]) / (w0 + w1),
                    curve,
                    t,
                    t0,
                    t1,
                )?;
                let [d0, d1] = ends.map(|x| near.x.distance(x));
                let boundary = self.placer.surface.model().curves()[curve as usize]
                    .faces
                    .contains(&None);
                if !boundary || d0.min(d1) >= 0.5 * d0.max(d1) {
                    Some(near)
                } else {
                    self.placer.balanced_on_curve(curve, t, [t0, t1], ends)
                }
            }
        }
    }
}

/// A triangle with no free corner whose centroid lies farther than this
/// times its longest side from the surface spans off its face.
const OFF_SURFACE: f64 = 0.2;

/// A free vertex with an angle above this (degrees) opposite a curve edge
/// is a cap ([`Remeshing::remove_caps`]).
const CAP_ANGLE: f64 = 120.0;

/// A shake may not make a triangle's smallest angle smaller than acos of
/// this (30°), unless it was smaller already.
const SHAKE_WORST_COSINE: f64 = 0.866;

/// A valence flip may not make the worse triangle's smallest angle smaller
/// than acos of this (about 25°), unless it improves it.
const FLIP_WORST_COSINE: f64 = 0.906;

/// Cells per axis of [`Remeshing::renumber`]'s Z-order grid (21 bits, so
/// that three interleaved fit in 64).
const Z_CELLS: f64 = (1u32 << 21) as f64;

/// The bits of x (below 2²¹) spread to every third bit.
fn z_order(x: u32) -> u64 {
    let mut x = x as u64 & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}
