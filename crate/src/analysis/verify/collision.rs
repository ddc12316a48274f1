//! Moves that do not cut (rapids, the approach, the plunge, retracts and links) checked
//! against the design: each is sampled along its straight line in X, Z (with the servo's W)
//! and continuous C, at least every degree of C and every 1/256 of the part's radius, at most
//! [`MAX_SAMPLES`] samples; a sample whose tool tip lies more than the tolerance below the
//! compensated tip height there (the one-way nose touching the design) is a collision. Only
//! the design counts as material: stock left by earlier passes is not.

use super::deviation::At;
use serde::Serialize;

/// The most samples of one move.
pub const MAX_SAMPLES: usize = 64;
/// The most collisions listed (all are counted).
pub const MAX_LISTED: usize = 100;

/// A move that comes below the design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Collision {
    /// `rapid` or `feed`.
    pub kind: &'static str,
    /// How far below the design its deepest sample goes, µm.
    pub depth_um: f64,
    /// Where.
    pub at: At,
}

/// The collisions of a program.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct CollisionReport {
    /// Moves checked.
    pub moves_checked: u64,
    /// Tolerance, µm: a move deeper than this below the design is a collision.
    pub tolerance_um: f64,
    /// Moves that collide.
    pub count: u64,
    /// The deepest, µm (0 without).
    pub deepest_um: f64,
    /// The first [`MAX_LISTED`].
    pub listed: Vec<Collision>,
}

impl CollisionReport {
    /// An empty report with `tolerance_um`.
    pub fn new(tolerance_um: f64) -> Self {
        Self {
            tolerance_um,
            ..Self::default()
        }
    }

    /// Adds a checked move with its deepest sample (`None`: none below the tolerance).
    pub fn add(&mut self, deepest: Option<Collision>) {
        self.moves_checked += 1;
        if let Some(c) = deepest {
            self.count += 1;
            self.deepest_um = self.deepest_um.max(c.depth_um);
            if self.listed.len() < MAX_LISTED {
                self.listed.push(c);
            }
        }
    }
}

/// Samples of a move from `a` to `b` (radius, Δθ degrees as moved): the fractions `s` ∈ (0, 1]
/// along it.
pub fn fractions(drho_mm: f64, dtheta_deg: f64, step_mm: f64) -> impl Iterator<Item = f64> {
    let by_angle = dtheta_deg.abs();
    let by_radius = drho_mm.abs() / step_mm;
    let n = by_angle.max(by_radius).ceil();
    let n = if n.is_finite() {
        (n as usize).clamp(1, MAX_SAMPLES)
    } else {
        MAX_SAMPLES
    };
    (1..=n).map(move |k| k as f64 / n as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_cover_the_move_and_are_bounded() {
        let s: Vec<f64> = fractions(0.0, 2.5, 0.01).collect();
        assert_eq!(s, vec![1.0 / 3.0, 2.0 / 3.0, 1.0]);
        assert_eq!(fractions(5.0, 0.0, 0.01).count(), MAX_SAMPLES);
        assert_eq!(fractions(0.0, 0.0, 0.01).collect::<Vec<_>>(), vec![1.0]);
    }
}
