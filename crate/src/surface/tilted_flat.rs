//! Tilted flat: the plane `z = tan τ·(x·cos β + y·sin β)` through the vertex, tilted by τ
//! about the axis perpendicular to the azimuth β of steepest ascent.
//!
//! Seen from the spindle, its sag along the spiral is a single sine per revolution,
//! `z(ρ, θ) = ρ·tan τ·cos(θ − β)`: the simplest test case for the FTS/SSS splitter (DESIGN.md,
//! "Splitting"). The gradient `tan τ·(cos β, sin β)` is exact and the Hessian is zero.

use super::{Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite};
use serde::{Deserialize, Serialize};

/// Job entry of a tilted flat.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TiltedFlatSpec {
    /// Tilt τ, degrees, with |τ| < 90: the angle between the plane and the XY plane. Positive
    /// τ makes the plane rise (towards +Z, the tool) in the direction β.
    pub tilt_deg: f64,
    /// Azimuth β of the direction of steepest ascent in the XY plane, degrees from +X towards
    /// +Y, any finite value; default 0 (the plane rises towards +X).
    #[serde(default)]
    pub azimuth_deg: f64,
}

/// A tilted flat, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct TiltedFlat {
    tilt_deg: f64,
    azimuth_deg: f64,
    /// ∂z/∂x = tan τ·cos β.
    gx: f64,
    /// ∂z/∂y = tan τ·sin β.
    gy: f64,
}

impl TiltedFlat {
    /// Checks a spec and builds the surface (the part disc is not needed: a plane is defined
    /// everywhere).
    pub fn new(spec: &TiltedFlatSpec, _part: PartDisc) -> Result<Self, FieldError> {
        let tilt = finite("tilt_deg", spec.tilt_deg)?;
        if tilt.abs() >= 90.0 {
            return Err(FieldError::new(
                "tilt_deg",
                tilt,
                "must lie in (−90, 90): at 90° the plane is vertical and has no sag",
            ));
        }
        let azimuth = finite("azimuth_deg", spec.azimuth_deg)?;
        let t = tilt.to_radians().tan();
        let (s, c) = azimuth.to_radians().sin_cos();
        Ok(Self {
            tilt_deg: tilt,
            azimuth_deg: azimuth,
            gx: t * c,
            gy: t * s,
        })
    }

    /// The constant gradient `(∂z/∂x, ∂z/∂y)`.
    pub fn gradient(&self) -> (f64, f64) {
        (self.gx, self.gy)
    }
}

impl Surface for TiltedFlat {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        Ok(Local {
            z: self.gx * x + self.gy * y,
            zx: self.gx,
            zy: self.gy,
            ..Local::default()
        })
    }

    fn feature_length_mm(&self) -> f64 {
        f64::INFINITY
    }

    /// A radial section's slope is the gradient along its direction, at most |tan τ| (reached
    /// towards the azimuth); its curvature is 0.
    fn section_bounds(&self, _radius_mm: f64) -> Option<SectionBounds> {
        Some(SectionBounds {
            max_slope: self.gx.hypot(self.gy) * (1.0 + 1e-12),
            ..SectionBounds::FLAT
        })
    }

    /// Its section bounds, which hold for any line.
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.section_bounds(radius_mm)
    }

    fn describe(&self) -> String {
        format!(
            "tilted flat: tilt {}°, rising fastest towards azimuth {}°",
            self.tilt_deg, self.azimuth_deg
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::section_bounds::assert_bounds_hold;

    fn flat(tilt_deg: f64, azimuth_deg: f64) -> Result<TiltedFlat, FieldError> {
        TiltedFlat::new(
            &TiltedFlatSpec {
                tilt_deg,
                azimuth_deg,
            },
            PartDisc::centred(10.0),
        )
    }

    #[test]
    fn a_45_degree_tilt_towards_y_rises_one_for_one() {
        let s = flat(45.0, 90.0).unwrap();
        let l = s.local(3.0, 2.0).unwrap();
        // tan 45° = 1 and cos 90° = 6e-17 in floating point: z = y to a few ulps.
        assert!((l.z - 2.0).abs() < 1e-15, "{}", l.z);
        assert!((l.zy - 1.0).abs() < 1e-15 && l.zx.abs() < 1e-16);
        assert_eq!((l.zxx, l.zxy, l.zyy), (0.0, 0.0, 0.0));
    }

    #[test]
    fn section_bounds_are_the_tilt() {
        for (tilt, azimuth) in [(0.05, 0.0), (-30.0, 200.0), (10.0, 45.0)] {
            let s = flat(tilt, azimuth).unwrap();
            let (b, slope, curvature) = assert_bounds_hold(&s, 5.0, 3600, 10);
            let tan = f64::tan(f64::to_radians(tilt)).abs();
            assert!((b.max_slope - tan).abs() <= 1e-11 * tan);
            assert!(slope > (1.0 - 1e-6) * tan && curvature == 0.0 && b.max_curvature == 0.0);
        }
    }

    #[test]
    fn vertical_planes_are_rejected() {
        for t in [90.0, -90.0, 135.0, f64::NAN] {
            assert_eq!(flat(t, 0.0).unwrap_err().field, "tilt_deg", "{t}");
        }
        assert_eq!(flat(1.0, f64::INFINITY).unwrap_err().field, "azimuth_deg");
        assert!(flat(89.9, 0.0).is_ok());
    }
}
