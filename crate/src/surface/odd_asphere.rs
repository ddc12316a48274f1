//! Odd asphere: `z = c·r² / (1 + √(1 − (1+k)·c²·r²)) + Σₙ βₙ·rⁿ`, n = 1 … 30: the conic of
//! [`super::asphere`] plus every power of r, odd and even. This is OpticStudio's "Odd Asphere"
//! surface (`TYPE ODDASPHE` in a `.zmx`), whose parameters 1 … 8 are β1 … β8 in that order, β1
//! multiplying r¹ (OpticStudio User Guide, "Odd Asphere"; the order checked against a public
//! reader's test: `PARM 1 0.002`, `PARM 2 -3e-6` give 0.009925 mm at r = 5 mm, reproduced in the
//! tests below). βₙ is in mm^(1−n), no normalisation radius. OpticStudio stops at β8; terms up to
//! β30 are accepted here.
//!
//! Derivatives: with `f(r) = Σ βₙ rⁿ`, `q(r) = Σ_{n≥2} n·βₙ·rⁿ⁻²` (so `f′ = β₁ + q·r`) and
//! `e(r) = Σ_{n≥3} n(n−2)·βₙ·rⁿ⁻²` (= f″ − q), and the unit direction (c, s) = (x, y)/r:
//! `∂z/∂x = f′·c`, `∂²z/∂x² = q + e·c² + β₁·s²/r`, `∂²z/∂x∂y = (e − β₁/r)·c·s`,
//! `∂²z/∂y² = q + e·s² + β₁·c²/r`. Every term but β₁'s is smooth at the axis (q(0) = 2β₂, e(0) =
//! 0). β₁·r is a cone: its apex on the axis is a slope kink ([`Surface::slope_kinks`] reports
//! it on every section through the axis), and at r = 0 exactly its slope and curvature are taken
//! as 0 (the apex has none; the samplers evaluate either side of the kink).

use super::{Asphere, AsphereSpec, Line, Local, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite};
use serde::{Deserialize, Serialize};

/// The largest number of terms: β1 … β30.
pub const MAX_TERMS: usize = 30;

/// Distance from the axis within which a section is taken to pass through the cone's apex, mm.
const APEX_TOLERANCE: f64 = 1e-9;

/// Job entry of an odd asphere. Give exactly one of `radius_mm` and `curvature_per_mm`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OddAsphereSpec {
    /// Vertex radius of curvature R, mm, non-zero (as for an even asphere).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_mm: Option<f64>,
    /// Vertex curvature c = 1/R, 1/mm; 0 for a plane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_per_mm: Option<f64>,
    /// Conic constant k; default 0.
    #[serde(default)]
    pub conic: f64,
    /// β1, β2, … of r¹, r², … in mm^(1−n); at most 30, default none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub coefficients: Vec<f64>,
}

/// An odd asphere, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct OddAsphere {
    conic: Asphere,
    /// β1, β2, … (trailing zeros dropped).
    beta: Vec<f64>,
}

impl OddAsphere {
    /// Checks a spec and builds the surface.
    pub fn new(spec: &OddAsphereSpec) -> Result<Self, FieldError> {
        let conic = Asphere::new(&AsphereSpec {
            radius_mm: spec.radius_mm,
            curvature_per_mm: spec.curvature_per_mm,
            conic: spec.conic,
            coefficients: Vec::new(),
        })?;
        if spec.coefficients.len() > MAX_TERMS {
            return Err(FieldError::new(
                "coefficients",
                format!("{} terms", spec.coefficients.len()),
                format!("at most {MAX_TERMS} terms (β1 … β{MAX_TERMS})"),
            ));
        }
        for (i, &b) in spec.coefficients.iter().enumerate() {
            finite(&format!("coefficients[{i}] (β{})", i + 1), b)?;
        }
        let mut beta = spec.coefficients.clone();
        while beta.last() == Some(&0.0) {
            beta.pop();
        }
        Ok(Self { conic, beta })
    }

    /// `[f, q, e]` at r (see the module docs), by Horner's rule from the highest power.
    fn terms(&self, r: f64) -> [f64; 3] {
        let (mut f, mut q, mut e) = (0.0, 0.0, 0.0);
        for (i, &b) in self.beta.iter().enumerate().rev() {
            let n = (i + 1) as f64;
            f = f * r + b;
            if i >= 1 {
                q = q * r + n * b;
            }
            if i >= 2 {
                e = e * r + n * (n - 2.0) * b;
            }
        }
        // The loops gave Σ βₙ·rⁿ⁻¹ and Σ n(n−2)·βₙ·rⁿ⁻³: one more factor r each.
        [f * r, q, e * r]
    }

    fn beta1(&self) -> f64 {
        self.beta.first().copied().unwrap_or(0.0)
    }
}

impl Surface for OddAsphere {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let mut l = self.conic.local(x, y).map_err(|e| UndefinedError {
            surface: "odd asphere",
            ..e
        })?;
        let r = x.hypot(y);
        let [f, q, e] = self.terms(r);
        l.z += f;
        if r == 0.0 {
            // The apex: β1's cone has no slope or curvature there; q(0) = 2β2 is isotropic.
            l.zxx += q;
            l.zyy += q;
            return Ok(l);
        }
        let (c, s) = (x / r, y / r);
        let b1 = self.beta1();
        let slope = b1 + q * r;
        let cone = b1 / r;
        l.zx += slope * c;
        l.zy += slope * s;
        l.zxx += q + e * c * c + cone * s * s;
        l.zxy += (e - cone) * c * s;
        l.zyy += q + e * s * s + cone * c * c;
        Ok(l)
    }

    fn feature_length_mm(&self) -> f64 {
        f64::INFINITY
    }

    /// The cone's apex, where a section through the axis crosses it (β1 ≠ 0).
    fn slope_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        if self.beta1() == 0.0 {
            return;
        }
        let t = -(line.x0 * line.c + line.y0 * line.s);
        let miss = (line.x0 * line.s - line.y0 * line.c).abs();
        if miss <= APEX_TOLERANCE && t > t0 && t < t1 {
            out.push(t);
        }
    }

    /// The apex's distance, less the tolerance within which a line is taken to pass through
    /// it (the kink is reported at the line's point nearest the axis); none without β₁.
    fn kink_free_radius(&self, x: f64, y: f64) -> f64 {
        if self.beta1() == 0.0 {
            return f64::INFINITY;
        }
        ((x * x + y * y).sqrt() - APEX_TOLERANCE).max(0.0)
    }

    /// The conic's bounds plus each term's on a section through the axis: `|d/dt βₙ·|t|ⁿ| ≤
    /// n·|βₙ|·Rⁿ⁻¹` and `d²/dt² ≤ n(n−1)·|βₙ|·Rⁿ⁻²`. β₁'s apex is a ridge for β₁ < 0; for
    /// β₁ > 0 it is a valley (the slope rises across it), so there are none.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        if self.beta1() > 0.0 {
            return None;
        }
        let r = radius_mm.abs();
        let (mut slope, mut curvature) = (0.0, 0.0);
        for (i, beta) in self.beta.iter().enumerate() {
            let (n, a) = ((i + 1) as f64, beta.abs());
            slope += n * a * r.powi(i as i32);
            if i >= 1 {
                curvature += n * (n - 1.0) * a * r.powi(i as i32 - 1);
            }
        }
        let apex = self.beta1() != 0.0;
        Some(
            self.conic
                .section_bounds(radius_mm)?
                .plus(slope, curvature)?
                .with_ridges(apex),
        )
    }

    fn describe(&self) -> String {
        let terms: Vec<String> = self
            .beta
            .iter()
            .enumerate()
            .filter(|(_, b)| **b != 0.0)
            .map(|(i, b)| format!("β{} {b:e}", i + 1))
            .collect();
        format!(
            "odd asphere {}{}{}",
            self.conic.shape(),
            if terms.is_empty() { "" } else { ", " },
            terms.join(", ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn odd(radius: Option<f64>, conic: f64, coefficients: Vec<f64>) -> OddAsphere {
        OddAsphere::new(&OddAsphereSpec {
            radius_mm: radius,
            curvature_per_mm: radius.is_none().then_some(0.0),
            conic,
            coefficients,
        })
        .unwrap()
    }

    #[test]
    fn section_bounds_hold_on_dense_sections_and_a_cone_valley_has_none() {
        for (radius, conic, b) in [
            (Some(40.0), -0.5, vec![-1e-3, -2e-4, 3e-5, -4e-6, 5e-7]),
            (None, 0.0, vec![0.0, 0.0, 2e-4, 0.0, -1e-6]),
        ] {
            let s = odd(radius, conic, b);
            crate::surface::section_bounds::assert_bounds_hold(&s, 5.0, 90, 20_000);
        }
        // β1 > 0: a cone whose apex is a valley.
        assert!(odd(None, 0.0, vec![1e-3]).section_bounds(5.0).is_none());
    }

    #[test]
    fn zemax_term_order_beta1_multiplies_r() {
        // The public reader's check: CURV 0, PARM 1 0.002, PARM 2 -3e-6, sag at (3, 4).
        let s = odd(None, 0.0, vec![0.002, -3e-6]);
        assert!((s.sag(3.0, 4.0).unwrap() - 0.009925).abs() < 1e-15);
    }

    #[test]
    fn every_power_is_added_to_the_conic() {
        let b = vec![1e-3, -2e-4, 3e-5, -4e-6, 5e-7];
        let s = odd(Some(40.0), -0.5, b.clone());
        let (x, y): (f64, f64) = (2.5, -1.5);
        let r = x.hypot(y);
        let c: f64 = 1.0 / 40.0;
        let conic = c * r * r / (1.0 + (1.0 - 0.5 * c * c * r * r).sqrt());
        let poly: f64 = b
            .iter()
            .enumerate()
            .map(|(i, b)| b * r.powi(i as i32 + 1))
            .sum();
        assert!((s.sag(x, y).unwrap() - conic - poly).abs() < 1e-15);
    }

    #[test]
    fn the_apex_is_a_kink_only_with_beta1() {
        let radial = Line::radial(0.6, 0.8);
        let mut out = Vec::new();
        odd(None, 0.0, vec![0.0, 1e-3, 1e-4]).slope_kinks(radial, -1.0, 1.0, &mut out);
        assert!(out.is_empty());
        odd(None, 0.0, vec![1e-3]).slope_kinks(radial, -1.0, 1.0, &mut out);
        assert_eq!(out, vec![0.0]);
        // A line that misses the axis has a smooth section.
        out.clear();
        let off = Line {
            x0: 0.0,
            y0: 0.1,
            c: 1.0,
            s: 0.0,
        };
        odd(None, 0.0, vec![1e-3]).slope_kinks(off, -1.0, 1.0, &mut out);
        assert!(out.is_empty());
        // At the apex: the β2 curvature, no cone slope.
        let l = odd(None, 0.0, vec![1e-3, 2e-3, 1e-4])
            .local(0.0, 0.0)
            .unwrap();
        assert_eq!((l.z, l.zx, l.zy, l.zxy), (0.0, 0.0, 0.0, 0.0));
        assert_eq!((l.zxx, l.zyy), (4e-3, 4e-3));
    }

    #[test]
    fn spec_errors_name_the_field() {
        let e = OddAsphere::new(&OddAsphereSpec {
            curvature_per_mm: Some(0.0),
            coefficients: vec![0.0; 31],
            ..Default::default()
        })
        .unwrap_err();
        assert_eq!(e.field, "coefficients");
        let e = OddAsphere::new(&OddAsphereSpec {
            curvature_per_mm: Some(0.0),
            coefficients: vec![0.0, 0.0, f64::NAN],
            ..Default::default()
        })
        .unwrap_err();
        assert_eq!(e.field, "coefficients[2] (β3)");
        let e = OddAsphere::new(&OddAsphereSpec::default()).unwrap_err();
        assert_eq!(e.field, "radius_mm");
    }
}
