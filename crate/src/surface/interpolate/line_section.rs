//! A scattered surface along one line as the polynomials it is between its kinks. Paper 004's
//! RBF with the L1 distance (eq 6, `r = |Δx| + |Δy|`) is a cubic polynomial in the line's
//! parameter t on every stretch that crosses neither a neighbour-set switch nor an axis line
//! of one of the set's points ([`super::rbf`], "Smoothness"): there each `rⱼ(t)` is linear,
//! `rⱼ = αⱼ + βⱼ·(t − m)`, and `φ(α + βτ) = φ(α) + φ′(α)·βτ + φ″(α)·β²τ²/2 − β³τ³` exactly
//! (φ‴ = −6). Those stretches are what [`crate::surface::Surface::slope_kinks`] reports, so
//! once a nose arc's line has been asked for its kinks, the compensation's samples of that
//! line — about 250 a point, both sides of every kink and the arc's grid — each cost a cubic
//! in Horner form instead of a neighbour lookup, a kept or new local system and its sum over
//! the neighbours ([`super::cache::radial_on_last_line`]).
//!
//! Each cubic is expanded about its stretch's midpoint m, so its powers of `t − m` stay below
//! the stretch's length and it agrees with the RBF evaluated at the point to the rounding of
//! either (the tests: within 1e-15 mm of sag). Within [`super::cache::SWITCH_BAND`] of a
//! switch or a chunk's end the section answers nothing, and the caller evaluates the surface
//! itself, whose kd-tree decides the side at a switch, as before.

use super::neighbours::Piece;
use crate::surface::Radial;
use std::cell::Cell;

/// A cubic in powers of `t − mid`: `k[0] + k[1]·τ + k[2]·τ² + k[3]·τ³`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cubic {
    /// The point it is expanded about.
    pub mid: f64,
    /// The coefficients of τ⁰ … τ³.
    pub k: [f64; 4],
}

impl Cubic {
    /// Its value, slope and second derivative at t.
    pub fn radial(&self, t: f64) -> Radial {
        let [_, k1, k2, k3] = self.k;
        let tau = t - self.mid;
        Radial {
            z: self.value(t),
            slope: k1 + tau * (2.0 * k2 + 3.0 * tau * k3),
            curvature_term: 2.0 * k2 + 6.0 * tau * k3,
        }
    }

    /// Its value at t (Horner's form, as [`Self::radial`] gives it).
    pub fn value(&self, t: f64) -> f64 {
        let [k0, k1, k2, k3] = self.k;
        let tau = t - self.mid;
        k0 + tau * (k1 + tau * (k2 + tau * k3))
    }

    /// Its lowest and highest values over `[lo, hi]`: at the ends and where its slope
    /// `k₁ + 2k₂τ + 3k₃τ²` vanishes inside.
    pub fn range_on(&self, lo: f64, hi: f64) -> [f64; 2] {
        let [_, k1, k2, k3] = self.k;
        let (a, b) = (self.value(lo), self.value(hi));
        let (mut low, mut high) = (a.min(b), a.max(b));
        for tau in quadratic_roots(k1, 2.0 * k2, 3.0 * k3) {
            let t = self.mid + tau;
            if t > lo && t < hi {
                let z = self.value(t);
                (low, high) = (low.min(z), high.max(z));
            }
        }
        [low, high]
    }
}

/// The real roots of `a + b·x + c·x²` (none where it is a nonzero constant or has none; the
/// linear root where c = 0), each from the form that does not cancel.
fn quadratic_roots(a: f64, b: f64, c: f64) -> impl Iterator<Item = f64> {
    let roots = if c == 0.0 {
        [(b != 0.0).then(|| -a / b), None]
    } else {
        let d = b * b - 4.0 * a * c;
        if d < 0.0 {
            [None, None]
        } else {
            let q = -0.5 * (b + b.signum() * d.sqrt());
            [Some(q / c), (q != 0.0).then(|| a / q)]
        }
    };
    roots.into_iter().flatten()
}

/// A stretch of a line where the section is one cubic.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stretch {
    /// Where it starts.
    start: f64,
    /// The start and end of its piece of the walk.
    piece: [f64; 2],
    /// The section there; `None` where the piece's system is singular.
    cubic: Option<Cubic>,
    /// The cubic's lowest and highest values over the stretch widened by [`WIDEN`].
    range: [f64; 2],
}

/// How far a stretch's range reaches beyond its ends, mm: more than the band about a switch
/// within which the surface itself answers, either side's polynomial
/// ([`super::cache::SWITCH_BAND`], 10⁻¹³ mm plus 10⁻¹⁵ of |t|, for |t| < 9 m).
pub const WIDEN: f64 = 1e-11;

impl Stretch {
    /// The stretch `[start, stop)` of `piece` whose section is `cubic`.
    fn new(start: f64, stop: f64, piece: [f64; 2], cubic: Option<Cubic>) -> Self {
        let range = cubic.map_or([f64::NAN; 2], |c| c.range_on(start - WIDEN, stop + WIDEN));
        Self {
            start,
            piece,
            cubic,
            range,
        }
    }
}

/// The stretches of `pieces` (the last ending at `end`), each piece cut at the `kinks` inside
/// it (ascending; others are skipped), each stretch's cubic `cubic(piece, midpoint)` (`None`
/// where the piece's system is singular), appended to `out`.
pub fn stretches(
    (pieces, end): (&[Piece], f64),
    kinks: &[f64],
    mut cubic: impl FnMut(&Piece, f64) -> Option<Cubic>,
    out: &mut Vec<Stretch>,
) {
    let mut next_kink = 0;
    for (k, piece) in pieces.iter().enumerate() {
        let piece_end = pieces.get(k + 1).map_or(end, |p| p.start);
        next_kink += kinks[next_kink..].partition_point(|&t| t <= piece.start);
        let inside = kinks[next_kink..].partition_point(|&t| t < piece_end);
        let cuts = &kinks[next_kink..next_kink + inside];
        let starts = std::iter::once(piece.start).chain(cuts.iter().copied());
        let ends = cuts.iter().copied().chain(std::iter::once(piece_end));
        for (start, stop) in starts.zip(ends) {
            let section = cubic(piece, 0.5 * (start + stop));
            out.push(Stretch::new(start, stop, [piece.start, piece_end], section));
        }
        next_kink += inside;
    }
}

/// The section of a surface along a line: stretches in order.
#[derive(Debug, Clone, PartialEq)]
pub struct LineSection {
    stretches: Vec<Stretch>,
    /// The stretch read last: the samples of a nose arc mostly ascend along the line.
    last: Cell<usize>,
}

impl LineSection {
    /// The section made of `stretches`, in order.
    pub fn new(stretches: Vec<Stretch>) -> Self {
        Self {
            stretches,
            last: Cell::new(0),
        }
    }

    /// Its stretches, for their memory.
    pub fn into_stretches(self) -> Vec<Stretch> {
        self.stretches
    }

    /// The section at t: `None` outside its stretches, within `band` of the ends of a piece of
    /// the walk (a neighbour-set switch, or a chunk's end), or on a piece whose system is
    /// singular.
    pub fn radial_at(&self, t: f64, band: f64) -> Option<Radial> {
        let k = self.stretch_at(t)?;
        self.last.set(k);
        let s = &self.stretches[k];
        let [lo, hi] = s.piece;
        if t - lo > band && hi - t > band {
            s.cubic.map(|c| c.radial(t))
        } else {
            None
        }
    }

    /// The lowest and highest values of the section over `[t0, t1]`: of each stretch's cubic
    /// over its part of the interval widened by [`WIDEN`] either way (samples within the
    /// switch band of a piece's end come from the surface itself, either side's polynomial);
    /// `None` where the stretches do not cover the interval or one there has no cubic.
    pub fn range_over(&self, t0: f64, t1: f64) -> Option<[f64; 2]> {
        let first = self.stretch_at(t0)?;
        let mut range = [f64::INFINITY, f64::NEG_INFINITY];
        for (k, s) in self.stretches.iter().enumerate().skip(first) {
            let next = self.stretches.get(k + 1).map(|n| n.start);
            let end = next.map_or(s.piece[1], |n| n.min(s.piece[1]));
            let cubic = s.cubic?;
            let [low, high] = if s.start >= t0 && end <= t1 {
                s.range
            } else {
                cubic.range_on(s.start.max(t0) - WIDEN, end.min(t1) + WIDEN)
            };
            range = [range[0].min(low), range[1].max(high)];
            if t1 <= end {
                self.last.set(k);
                return Some(range);
            }
            if next.is_none_or(|n| n > end) {
                return None;
            }
        }
        None
    }

    /// [`Self::range_over`] each interval between consecutive `ts` (ascending).
    pub fn ranges_over(&self, ts: &[f64]) -> Option<Vec<[f64; 2]>> {
        // Sized once: an `Option` collect cannot know its length.
        let mut ranges = Vec::with_capacity(ts.len().saturating_sub(1));
        for w in ts.windows(2) {
            ranges.push(self.range_over(w[0], w[1])?);
        }
        Some(ranges)
    }

    /// The last stretch starting at or before t, searched from the one read last: steps that
    /// double until they pass t (either way), then bisection between the last two. The samples
    /// of a nose arc ascend a stretch or a few at a time and its refinements step back one, so
    /// most take a comparison or two instead of a bisection of the whole section.
    fn stretch_at(&self, t: f64) -> Option<usize> {
        let before = |k: usize| self.stretches[k].start <= t;
        let n = self.stretches.len();
        let last = self.last.get().min(n.checked_sub(1)?);
        let (lo, hi) = if before(last) {
            let (mut lo, mut step) = (last, 1);
            while lo + step < n && before(lo + step) {
                lo += step;
                step *= 2;
            }
            (lo, (lo + step).min(n))
        } else {
            let (mut hi, mut step) = (last, 1);
            while hi >= step && !before(hi - step) {
                hi -= step;
                step *= 2;
            }
            if hi >= step {
                (hi - step, hi)
            } else if before(0) {
                (0, hi)
            } else {
                return None;
            }
        };
        Some(lo + self.stretches[lo + 1..hi].partition_point(|s| s.start <= t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stretch_found_from_the_last_read_is_the_bisections() {
        // 200 stretches of uneven lengths; t walking up and down by small and large steps,
        // jumping across the whole section, landing on starts exactly and falling outside:
        // the stretch found from the hint is the plain bisection's every time.
        let starts: Vec<f64> = (0..200)
            .map(|k| k as f64 * 0.01 + 0.003 * ((k * 7) as f64).sin())
            .collect();
        let section = LineSection::new(
            starts
                .iter()
                .map(|&start| Stretch::new(start, start + 0.01, [start, start + 0.01], None))
                .collect(),
        );
        let mut ts: Vec<f64> = (0..3000)
            .map(|i| 1.0 + 1.05 * ((i as f64) * 0.0021).sin() + 0.02 * ((i * 13) as f64).cos())
            .collect();
        ts.extend(starts.iter().rev().copied());
        ts.extend([
            -1.0,
            5.0,
            starts[0],
            -1e-9,
            starts[199],
            0.5,
            starts[100] - 1e-15,
        ]);
        for &t in &ts {
            let expected = starts.partition_point(|&s| s <= t).checked_sub(1);
            assert_eq!(section.stretch_at(t), expected, "t = {t}");
            if let Some(k) = expected {
                section.last.set(k);
            }
        }
        let empty = LineSection::new(Vec::new());
        assert_eq!(empty.stretch_at(0.0), None);
    }

    #[test]
    fn a_cubics_range_is_the_dense_samples_range() {
        // Cubics with two, one (a double root: an inflection) and no stationary points, a
        // quadratic and a line, over intervals holding none, one or both of them: the range
        // holds every one of 100 001 samples and is reached by one within 1e-9 mm (the
        // samples' spacing, 1.4e-5 mm, puts an interior extreme up to ~1e-10 mm beyond them).
        let cubics = [
            [0.1, -0.3, 0.2, 1.0],
            [0.0, 0.0, 0.0, 2.0],
            [-0.2, 0.5, 0.1, 0.3],
            [0.3, 0.2, -1.5, 0.0],
            [0.05, -0.4, 0.0, 0.0],
        ];
        for k in cubics {
            let c = Cubic { mid: 0.7, k };
            for [lo, hi] in [
                [0.0, 1.4],
                [0.65, 0.75],
                [0.9, 1.3],
                [-0.5, 0.71],
                [0.7, 0.7],
            ] {
                let [low, high] = c.range_on(lo, hi);
                let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
                for i in 0..=100_000 {
                    let z = c.radial(lo + (hi - lo) * i as f64 / 100_000.0).z;
                    assert!(z >= low - 1e-15 && z <= high + 1e-15, "{k:?} [{lo}, {hi}]");
                    (min, max) = (min.min(z), max.max(z));
                }
                assert!(min - low < 1e-9 && high - max < 1e-9, "{k:?} [{lo}, {hi}]");
            }
        }
    }

    #[test]
    fn a_sections_range_covers_its_stretches_or_says_none() {
        // Three stretches on two pieces, with a gap after the second piece: the range of an
        // interval is that of the stretches' samples over it (within the widening), none where
        // it reaches the gap, starts before the first stretch or meets a singular piece.
        let cubic = |k: [f64; 4], mid| Some(Cubic { mid, k });
        let section = LineSection::new(vec![
            Stretch::new(0.0, 1.0, [0.0, 2.0], cubic([0.0, 1.0, 0.0, 0.0], 0.5)),
            Stretch::new(1.0, 2.0, [0.0, 2.0], cubic([1.0, 0.0, -1.0, 0.0], 1.5)),
            Stretch::new(2.0, 3.0, [2.0, 3.0], cubic([2.0, 0.0, 0.0, 1.0], 2.5)),
            Stretch::new(3.5, 4.0, [3.5, 4.0], None),
        ]);
        let dense = |t0: f64, t1: f64| {
            let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
            for i in 0..=100_000 {
                let t = t0 + (t1 - t0) * i as f64 / 100_000.0;
                let k = section.stretch_at(t).unwrap();
                let z = section.stretches[k].cubic.unwrap().radial(t).z;
                (min, max) = (min.min(z), max.max(z));
            }
            [min, max]
        };
        for [t0, t1] in [[0.2, 0.4], [0.2, 1.7], [0.9, 2.9], [1.5, 1.5], [0.0, 3.0]] {
            let [low, high] = section.range_over(t0, t1).unwrap();
            let [min, max] = dense(t0, t1);
            assert!(low <= min + 1e-15 && high >= max - 1e-15, "[{t0}, {t1}]");
            assert!(min - low < 1e-9 && high - max < 1e-9, "[{t0}, {t1}]");
        }
        // Each stretch is widened by WIDEN: the first rises with slope 1.
        let [low, high] = section.range_over(0.2, 0.4).unwrap();
        assert!((low + 0.3 + WIDEN).abs() < 1e-16 && (high + 0.1 - WIDEN).abs() < 1e-16);
        let ts = [0.2, 0.4, 1.7, 2.9];
        let each: Vec<_> = ts
            .windows(2)
            .map(|w| section.range_over(w[0], w[1]))
            .collect();
        assert_eq!(section.ranges_over(&ts), each.into_iter().collect());
        assert_eq!(section.ranges_over(&[0.2, 2.9, 3.2]), None);
        for [t0, t1] in [[2.5, 3.2], [-0.1, 0.5], [3.6, 3.7], [2.9, 3.6]] {
            assert_eq!(section.range_over(t0, t1), None, "[{t0}, {t1}]");
        }
    }
}
