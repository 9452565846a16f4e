//! Whether a change may be applied: every triangle it makes must be valid,
//! not degenerate, and facing the way the surface does at its free
//! vertices (the normal of the surface there, not of neighbouring
//! triangles, so that folds cannot creep in step by step).

use super::remeshing::{Moved, Remeshing};
use crate::geometry::{area_normal, max_cosine};
use glam::DVec3;

/// A triangle may tilt against the surface normal at its free vertices by
/// at most acos of this (about 78°).
const MIN_COSINE: f64 = 0.2;

/// A triangle with no free corner whose centroid lies farther than this
/// times its longest side from the surface spans off its face.
const OFF_SURFACE: f64 = 0.2;

impl Remeshing<'_> {
    /// How well triangle `ids` (of face `face`), with `moved` in place,
    /// faces the way the surface does: the smallest cosine between its
    /// normal and the surface normal at its free vertices (and, with a
    /// corner on a feature, at its centroid's projection) or, with none
    /// free, at its first corner that has one seen from the face; −∞ if
    /// degenerate.
    fn alignment(&self, ids: [u32; 3], face: u32, moved: Moved) -> f64 {
        let p = ids.map(|v| self.point(v, moved));
        let n = area_normal(p);
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
    pub(super) fn accept<'v>(
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

    /// The smallest angle's cosine (larger is worse) of triangle `ids`.
    pub(super) fn worst_cosine(&self, ids: [u32; 3], moved: Moved) -> f64 {
        let [a, b, c] = ids.map(|v| self.point(v, moved));
        max_cosine(a, b, c)
    }
}
