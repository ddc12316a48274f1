//! The deviation's figures over a set of points, accumulated in one pass with bounded memory:
//! count, smallest and largest with where they are, mean and root mean square (sums kept in
//! compensated form, Neumaier's variant of Kahan summation, so that 10⁷ points of nanometres
//! lose nothing to rounding).

use crate::nc::reader::Location;
use serde::Serialize;
use std::sync::Arc;

/// Where a deviation is: on the part and in the program.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct At {
    /// Radius, mm.
    pub rho_mm: f64,
    /// Polar angle, degrees in [0, 360).
    pub theta_deg: f64,
    /// The program's file.
    pub file: String,
    /// Its line, from 1.
    pub line: u64,
}

/// A point and where it is written, before it is turned into an [`At`].
#[derive(Debug, Clone)]
struct Place {
    rho: f64,
    theta: f64,
    file: Arc<str>,
    line: u64,
}

impl Place {
    fn at(&self) -> At {
        At {
            rho_mm: self.rho,
            theta_deg: self.theta.to_degrees().rem_euclid(360.0),
            file: self.file.to_string(),
            line: self.line,
        }
    }
}

/// A compensated sum (Neumaier).
#[derive(Debug, Clone, Copy, Default)]
struct Sum {
    sum: f64,
    carry: f64,
}

impl Sum {
    fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.carry += (self.sum - t) + x;
        } else {
            self.carry += (x - t) + self.sum;
        }
        self.sum = t;
    }

    fn value(&self) -> f64 {
        self.sum + self.carry
    }
}

/// The deviation's figures, µm (positive: material left above the design; negative: the
/// program cuts into it).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeviationSummary {
    /// Points compared.
    pub points: u64,
    /// Smallest deviation, µm.
    pub min: f64,
    /// Largest deviation, µm.
    pub max: f64,
    /// Mean, µm.
    pub mean: f64,
    /// Root mean square, µm.
    pub rms: f64,
    /// Where the smallest is.
    pub min_at: Option<At>,
    /// Where the largest is.
    pub max_at: Option<At>,
}

/// Accumulates deviations.
#[derive(Debug, Clone, Default)]
pub struct DeviationStats {
    points: u64,
    sum: Sum,
    squares: Sum,
    min: Option<(f64, Place)>,
    max: Option<(f64, Place)>,
}

impl DeviationStats {
    /// Adds the deviation `um` (µm) of the point at (ρ, θ) written at `at`.
    pub fn add(&mut self, um: f64, rho: f64, theta: f64, at: &Location) {
        self.points += 1;
        self.sum.add(um);
        self.squares.add(um * um);
        let place = || Place {
            rho,
            theta,
            file: at.file.clone(),
            line: at.line,
        };
        if self.min.as_ref().is_none_or(|m| um < m.0) {
            self.min = Some((um, place()));
        }
        if self.max.as_ref().is_none_or(|m| um > m.0) {
            self.max = Some((um, place()));
        }
    }

    /// Points added.
    pub fn points(&self) -> u64 {
        self.points
    }

    /// The mean, µm (0 without points).
    pub fn mean(&self) -> f64 {
        if self.points == 0 {
            0.0
        } else {
            self.sum.value() / self.points as f64
        }
    }

    /// The figures (zeros and no places without points).
    pub fn summary(&self) -> DeviationSummary {
        let n = self.points.max(1) as f64;
        DeviationSummary {
            points: self.points,
            min: self.min.as_ref().map_or(0.0, |m| m.0),
            max: self.max.as_ref().map_or(0.0, |m| m.0),
            mean: self.mean(),
            rms: (self.squares.value() / n).max(0.0).sqrt(),
            min_at: self.min.as_ref().map(|m| m.1.at()),
            max_at: self.max.as_ref().map(|m| m.1.at()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_match_a_direct_computation() {
        let at = Location {
            file: Arc::from("p.nc"),
            line: 3,
        };
        let mut s = DeviationStats::default();
        let values: Vec<f64> = (0..1001)
            .map(|k| ((k as f64) * 0.37).sin() + 0.25)
            .collect();
        for (k, &v) in values.iter().enumerate() {
            s.add(v, k as f64, 0.0, &at);
        }
        let r = s.summary();
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let rms = (values.iter().map(|v| v * v).sum::<f64>() / n).sqrt();
        assert!((r.mean - mean).abs() < 1e-14 && (r.rms - rms).abs() < 1e-14);
        let (imin, min) = values
            .iter()
            .enumerate()
            .fold((0, f64::MAX), |a, (i, &v)| if v < a.1 { (i, v) } else { a });
        assert_eq!(r.min, min);
        assert_eq!(r.min_at.unwrap().rho_mm, imin as f64);
        assert_eq!(r.points, 1001);
        assert_eq!(DeviationStats::default().summary().min_at, None);
    }
}
