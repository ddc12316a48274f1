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
        let [k0, k1, k2, k3] = self.k;
        let tau = t - self.mid;
        Radial {
            z: k0 + tau * (k1 + tau * (k2 + tau * k3)),
            slope: k1 + tau * (2.0 * k2 + 3.0 * tau * k3),
            curvature_term: 2.0 * k2 + 6.0 * tau * k3,
        }
    }
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
            out.push(Stretch {
                start,
                piece: [piece.start, piece_end],
                cubic: cubic(piece, 0.5 * (start + stop)),
            });
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
                .map(|&start| Stretch {
                    start,
                    piece: [start, start + 0.01],
                    cubic: None,
                })
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
}
