//! Sinusoidal grid `z = A·sin(2πx/λx + φx)·sin(2πy/λy + φy)`: the classic FTS test surface,
//! a product of two sines whose derivatives follow by the chain rule
//! (`∂z/∂x = A·kx·cos(u)·sin(v)`, `∂²z/∂x² = −kx²·z`, `∂²z/∂x∂y = A·kx·ky·cos(u)·cos(v)`).

use super::{Local, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite, length};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Job entry of a sinusoidal grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SinusoidSpec {
    /// Amplitude A, mm (the surface spans ±A).
    pub amplitude_mm: f64,
    /// Wavelength along X, mm, > 0.
    pub wavelength_x_mm: f64,
    /// Wavelength along Y, mm, > 0.
    pub wavelength_y_mm: f64,
    /// Phase along X, degrees; default 0.
    #[serde(default)]
    pub phase_x_deg: f64,
    /// Phase along Y, degrees; default 0.
    #[serde(default)]
    pub phase_y_deg: f64,
}

/// A sinusoidal grid, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Sinusoid {
    a: f64,
    kx: f64,
    ky: f64,
    px: f64,
    py: f64,
    feature: f64,
}

impl Sinusoid {
    /// Checks a spec and builds the surface.
    pub fn new(spec: &SinusoidSpec) -> Result<Self, FieldError> {
        let a = finite("amplitude_mm", spec.amplitude_mm)?;
        let lx = length("wavelength_x_mm", spec.wavelength_x_mm)?;
        let ly = length("wavelength_y_mm", spec.wavelength_y_mm)?;
        let px = finite("phase_x_deg", spec.phase_x_deg)?.to_radians();
        let py = finite("phase_y_deg", spec.phase_y_deg)?.to_radians();
        Ok(Self {
            a,
            kx: TAU / lx,
            ky: TAU / ly,
            px,
            py,
            feature: lx.min(ly) / 4.0,
        })
    }
}

impl Surface for Sinusoid {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let (su, cu) = (self.kx * x + self.px).sin_cos();
        let (sv, cv) = (self.ky * y + self.py).sin_cos();
        let (a, kx, ky) = (self.a, self.kx, self.ky);
        let z = a * su * sv;
        Ok(Local {
            z,
            zx: a * kx * cu * sv,
            zy: a * ky * su * cv,
            zxx: -kx * kx * z,
            zxy: a * kx * ky * cu * cv,
            zyy: -ky * ky * z,
        })
    }

    fn feature_length_mm(&self) -> f64 {
        self.feature
    }

    /// Along the direction w = (cos θ, sin θ), with w′ = (kx·cos θ, ky·sin θ) and the phases
    /// u, v: the slope `A·(w′₁·cos u·sin v + w′₂·sin u·cos v)` is at most |A|·|w′| (Cauchy–Schwarz:
    /// `(cos u·sin v)² + (sin u·cos v)² ≤ 1`), and the curvature `A·w′ᵀ·M·w′`, M =
    /// `[[−sin u·sin v, cos u·cos v], [cos u·cos v, −sin u·sin v]]` with eigenvalues
    /// `cos(u + v)` and `−cos(u − v)`, at most |A|·|w′|²; |w′| ≤ max(kx, ky). Both are reached
    /// (along the axis of the shorter wavelength), on any disc; there are no kinks.
    fn section_bounds(&self, _radius_mm: f64) -> Option<SectionBounds> {
        let k = self.kx.max(self.ky);
        let slope = self.a.abs() * k;
        SectionBounds::FLAT.plus(slope, slope * k)
    }

    /// The section bounds: their derivation holds for every direction and phase, so on any
    /// line (|∇z| ≤ |A|·k, the Hessian's eigenvalues within ±|A|·k²).
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.section_bounds(radius_mm)
    }

    fn describe(&self) -> String {
        format!(
            "sinusoidal grid A {} mm, λx {} mm, λy {} mm, φx {}°, φy {}°",
            self.a,
            TAU / self.kx,
            TAU / self.ky,
            self.px.to_degrees(),
            self.py.to_degrees()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::section_bounds::assert_bounds_hold;

    #[test]
    fn section_bounds_hold_on_dense_sections_and_are_reached() {
        for (a, lx, ly, px, py) in [
            (0.002, 1.0, 2.0, 10.0, 90.0),
            (-0.01, 0.7, 0.5, 33.0, -20.0),
            (0.005, 1.0, 1.0, 0.0, 0.0),
        ] {
            let s = Sinusoid::new(&SinusoidSpec {
                amplitude_mm: a,
                wavelength_x_mm: lx,
                wavelength_y_mm: ly,
                phase_x_deg: px,
                phase_y_deg: py,
            })
            .unwrap();
            let (b, slope, curvature) = assert_bounds_hold(&s, 4.0, 360, 4000);
            // Along the axis of the shorter wavelength both are reached (to the sampling).
            assert!(
                slope > 0.995 * b.max_slope && curvature > 0.99 * b.max_curvature,
                "{b:?} {slope} {curvature}"
            );
        }
    }

    #[test]
    fn sag_is_the_product_of_sines() {
        let spec = SinusoidSpec {
            amplitude_mm: 0.002,
            wavelength_x_mm: 1.0,
            wavelength_y_mm: 2.0,
            phase_x_deg: 90.0,
            phase_y_deg: 0.0,
        };
        let s = Sinusoid::new(&spec).unwrap();
        // x = 0: sin(90°) = 1; y = 0.5: sin(π/2) = 1.
        assert!((s.local(0.0, 0.5).unwrap().z - 0.002).abs() < 1e-18);
        assert!(s.local(0.25, 0.5).unwrap().z.abs() < 1e-18);
        let bad = SinusoidSpec {
            wavelength_y_mm: 0.0,
            ..spec
        };
        assert_eq!(Sinusoid::new(&bad).unwrap_err().field, "wavelength_y_mm");
    }
}
