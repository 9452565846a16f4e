//! Arc length of a limit curve and its inverse, by adaptive Gauss–Legendre
//! quadrature of |X′|; the segment lengths are kept with the surface.

use super::LimitCurve;
use crate::error::{Error, Result};

/// 10-point Gauss–Legendre nodes and weights on [−1, 1] (positive half).
const GAUSS: [(f64, f64); 5] = [
    (0.148_874_338_981_631_22, 0.295_524_224_714_752_87),
    (0.433_395_394_129_247_2, 0.269_266_719_309_996_35),
    (0.679_409_568_299_024_4, 0.219_086_362_515_982_04),
    (0.865_063_366_688_984_5, 0.149_451_349_150_580_6),
    (0.973_906_528_517_171_7, 0.066_671_344_308_688_14),
];

impl<'s> LimitCurve<'s> {
    /// The arc length of curve `curve` between parameters t0 and t1
    /// (negative when t1 < t0), by adaptive Gauss–Legendre quadrature of
    /// |X′| to 1e-13 relative per unit segment.
    pub fn length(&self, t0: f64, t1: f64) -> Result<f64> {
        let c = self.curve;
        let (a, b) = (self.parameter(t0)?, self.parameter(t1)?);
        let (lo, hi, sign) = if a <= b { (a, b, 1.0) } else { (b, a, -1.0) };
        let n = c.len() as f64;
        let tip =
            |t: f64| (t == 0.0 && self.is_dart_tip(0)) || (t == n && self.is_dart_tip(c.len()));
        let mut total = 0.0;
        let mut k = lo.floor();
        while k < hi {
            let (x, y) = (lo.max(k), hi.min(k + 1.0));
            if y > x {
                total += if tip(x) {
                    self.length_to_tip(x, y)?
                } else if tip(y) {
                    self.length_to_tip(y, x)?
                } else {
                    self.segment_length(x, y, self.length_floor(), 0)?
                };
            }
            k += 1.0;
        }
        Ok(sign * total)
    }

    /// The length from a dart tip to `other` in the same segment. |X′|
    /// behaves like a power of the distance to the tip there, which
    /// adaptive quadrature would chase for forty halvings: instead the
    /// interval is cut into halves towards the tip, each smooth on its own
    /// scale, until the rest (bounded by its chord's multiple, taken as its
    /// chord) is below round-off of the sum.
    fn length_to_tip(&self, tip: f64, other: f64) -> Result<f64> {
        let x_tip = self.eval(tip)?.x;
        let mut total = 0.0;
        let mut far = other;
        for _ in 0..200 {
            let near = tip + 0.5 * (far - tip);
            let (a, b) = if near < far { (near, far) } else { (far, near) };
            // Each piece only needs to be good relative to the sum so far.
            let floor = self.length_floor().max(1e-15 * total);
            total += self.segment_length(a, b, floor, 0)?;
            far = near;
            let rest = (self.eval(far)?.x - x_tip).length();
            if rest <= 1e-14 * total {
                return Ok(total + rest);
            }
        }
        Ok(total)
    }

    /// ∫ |X′| over [a, b] inside one unit segment, halving until the halves
    /// agree with the whole to 1e-13 relative or to `floor` absolute (the
    /// round-off of positions, below which pieces near a dart tip never
    /// agree better).
    fn segment_length(&self, a: f64, b: f64, floor: f64, depth: u32) -> Result<f64> {
        let whole = self.gauss(a, b)?;
        let m = 0.5 * (a + b);
        let halves = self.gauss(a, m)? + self.gauss(m, b)?;
        if (whole - halves).abs() <= (1e-13 * halves.abs()).max(floor) || depth >= 40 {
            return Ok(halves);
        }
        Ok(self.segment_length(a, m, 0.5 * floor, depth + 1)?
            + self.segment_length(m, b, 0.5 * floor, depth + 1)?)
    }

    /// The absolute round-off of lengths on this surface.
    fn length_floor(&self) -> f64 {
        1e-15 * self.surface.net().bbox_diagonal()
    }

    fn gauss(&self, a: f64, b: f64) -> Result<f64> {
        let (h, m) = (0.5 * (b - a), 0.5 * (a + b));
        let mut sum = 0.0;
        for (x, w) in GAUSS {
            sum += w * self.eval(m - h * x)?.dx.length();
            sum += w * self.eval(m + h * x)?.dx.length();
        }
        Ok(h * sum)
    }

    /// The parameter t at arc length `s` from t = 0 along curve `curve`
    /// (0 ≤ s ≤ its length), so a mesher can place equally spaced points:
    /// the segment by cumulative lengths, then Newton on the length inside
    /// it, safeguarded by bisection.
    pub fn param_at_length(&self, s: f64) -> Result<f64> {
        let n = self.curve.len();
        let table = self.segment_lengths()?;
        let mut cumulative = 0.0;
        for k in 0..n {
            let seg = table[k];
            if s <= cumulative + seg || k + 1 == n {
                let target = s - cumulative;
                if !(target >= -1e-12 * seg && target <= seg * (1.0 + 1e-12)) || !s.is_finite() {
                    return Err(Error::InvalidArgument(format!(
                        "arc length {s}: outside [0, {}] of curve {}",
                        cumulative + seg,
                        self.index
                    )));
                }
                let (mut lo, mut hi) = (k as f64, k as f64 + 1.0);
                let mut t = lo + target / seg.max(f64::MIN_POSITIVE);
                for _ in 0..60 {
                    let f = self.length(k as f64, t)? - target;
                    if f.abs() <= 1e-14 * seg.max(f64::MIN_POSITIVE) {
                        break;
                    }
                    if f > 0.0 {
                        hi = t;
                    } else {
                        lo = t;
                    }
                    let speed = self.eval(t)?.dx.length();
                    let newton = t - f / speed;
                    t = if speed > 0.0 && newton > lo && newton < hi {
                        newton
                    } else {
                        0.5 * (lo + hi)
                    };
                }
                return Ok(t.clamp(k as f64, k as f64 + 1.0));
            }
            cumulative += seg;
        }
        unreachable!("a curve has at least one control edge")
    }

    /// The length of every unit segment, computed on first use and kept
    /// with the surface ([`super::CurveLengths`]).
    fn segment_lengths(&self) -> Result<&'s [f64]> {
        if let Some(table) = self.lengths.get() {
            return Ok(table);
        }
        let table = (0..self.curve.len())
            .map(|k| self.length(k as f64, k as f64 + 1.0))
            .collect::<Result<Vec<f64>>>()?;
        Ok(self.lengths.get_or_init(|| table))
    }
}
