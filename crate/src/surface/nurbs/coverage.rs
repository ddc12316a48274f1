//! Whether a face covers the part: the part disc is probed on a polar grid (the centre, 64 rings
//! of 256 points, and 1024 points on the rim), ring by ring outwards, and the first point where
//! the face has no single-valued sag is reported. Between probes the face cannot end unseen by
//! more than the probe spacing: 2π·R/256 ≈ 0.025·R across, R/64 radially.

use super::inverse::Miss;
use crate::surface::PartDisc;

/// Rings between the centre and the rim.
const RINGS: usize = 64;
/// Points on each inner ring.
const SPOKES: usize = 256;
/// Points on the rim.
const RIM: usize = 1024;

/// A part point the face does not serve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gap {
    /// Distance from the part's centre, mm.
    pub radius: f64,
    /// Polar angle about the part's centre, degrees.
    pub angle_deg: f64,
    /// Where, mm.
    pub x: f64,
    /// Where, mm.
    pub y: f64,
    /// Why.
    pub miss: Miss,
}

/// The first probe of the part disc, from the centre outwards, where `probe` fails.
pub fn first_gap(part: PartDisc, probe: impl Fn(f64, f64) -> Result<(), Miss>) -> Option<Gap> {
    for ring in 0..=RINGS {
        let radius = part.radius_mm * ring as f64 / RINGS as f64;
        let spokes = match ring {
            0 => 1,
            RINGS => RIM,
            _ => SPOKES,
        };
        for k in 0..spokes {
            let angle = std::f64::consts::TAU * k as f64 / spokes as f64;
            let (s, c) = angle.sin_cos();
            let (x, y) = (part.x_mm + radius * c, part.y_mm + radius * s);
            if let Err(miss) = probe(x, y) {
                return Some(Gap {
                    radius,
                    angle_deg: angle.to_degrees(),
                    x,
                    y,
                    miss,
                });
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_gap_is_the_innermost() {
        // A "face" covering the square |x|, |y| ≤ 3 for a part of radius 4 centred at (1, 0):
        // the innermost probe outside is at radius 2 on the +x spoke (x = 3 is still inside).
        let part = PartDisc {
            radius_mm: 4.0,
            x_mm: 1.0,
            y_mm: 0.0,
        };
        let gap = first_gap(part, |x, y| {
            if x.abs() <= 3.0 && y.abs() <= 3.0 {
                Ok(())
            } else {
                Err(Miss::Uncovered { residual: 1.0 })
            }
        })
        .unwrap();
        assert_eq!(gap.angle_deg, 0.0);
        assert!((gap.radius - 2.0625).abs() < 1e-12, "{gap:?}");
        assert!(first_gap(part, |_, _| Ok(())).is_none());
    }
}
