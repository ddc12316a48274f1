//! Forbes' Qcon asphere (G. W. Forbes, "Shape specification for axially symmetric optical
//! surfaces", Opt. Express 15, 5218, 2007, eq 2.1 with the polynomials of section 2): a conic
//! plus a departure in sag, `z = c·r²/(1 + √(1 − (1+k)c²r²)) + u⁴·Σₘ aₘ·Qₘᶜᵒⁿ(u²)`, u = r/N,
//! aₘ in mm. The Qconₘ are the Jacobi polynomials `Pₘ^(0,4)(2x − 1)` (sag-orthogonal over the
//! disc, `Qconₘ(1) = 1`), summed by their recurrence ([`super::q_polynomials`]).
//!
//! Derivatives in s = r², ξ = s/N²: `(ξ²S)_s = (2ξS + ξ²S′)/N²`,
//! `(ξ²S)_ss = (2S + 4ξS′ + ξ²S″)/N⁴`, added to the conic's ([`super::asphere`]). Undefined
//! beyond the conic's rim; beyond u = 1 the polynomials continue.

use super::asphere::radial_at;
use super::q_polynomials::{
    QSum, check_coefficients, describe_coefficients, rotational_feature_length,
};
use super::q_section_bounds::section_term_bounds;
use super::{Asphere, AsphereSpec, Local, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, positive};
use serde::{Deserialize, Serialize};

/// Job entry of a Qcon asphere. Give exactly one of `radius_mm` and `curvature_per_mm`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QConSpec {
    /// Vertex radius of curvature, mm, non-zero.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_mm: Option<f64>,
    /// Vertex curvature c = 1/R, 1/mm; 0 for a plane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_per_mm: Option<f64>,
    /// Conic constant k; default 0.
    #[serde(default)]
    pub conic: f64,
    /// Normalisation radius N, mm, > 0: u = r/N.
    pub norm_radius_mm: f64,
    /// a₀, a₁, … of Qcon₀, Qcon₁, …, mm; at most 31.
    pub coefficients_mm: Vec<f64>,
}

/// A Qcon asphere, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct QCon {
    conic: Asphere,
    norm: f64,
    a: Vec<f64>,
    sum: QSum,
}

impl QCon {
    /// Checks a spec and builds the surface.
    pub fn new(spec: &QConSpec) -> Result<Self, FieldError> {
        let conic = Asphere::new(&AsphereSpec {
            radius_mm: spec.radius_mm,
            curvature_per_mm: spec.curvature_per_mm,
            conic: spec.conic,
            coefficients: Vec::new(),
        })?;
        let norm = positive("norm_radius_mm", spec.norm_radius_mm)?;
        check_coefficients("coefficients_mm", &spec.coefficients_mm)?;
        Ok(Self {
            conic,
            norm,
            a: spec.coefficients_mm.clone(),
            sum: QSum::qcon(&spec.coefficients_mm),
        })
    }

    /// `[z, z_s, z_ss]` at s = r².
    fn in_s(&self, s: f64) -> Result<[f64; 3], String> {
        let [z, zs, zss] = self.conic.in_s(s)?;
        let n2 = self.norm * self.norm;
        let xi = s / n2;
        let [p, p1, p2] = self.sum.eval(xi);
        Ok([
            z + xi * xi * p,
            zs + (2.0 * xi * p + xi * xi * p1) / n2,
            zss + (2.0 * p + 4.0 * xi * p1 + xi * xi * p2) / (n2 * n2),
        ])
    }
}

impl Surface for QCon {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        radial_at("Qcon asphere", x, y, self.in_s(x * x + y * y))
    }

    /// [`rotational_feature_length`] of the coefficients.
    fn feature_length_mm(&self) -> f64 {
        rotational_feature_length(self.norm, &self.a)
    }

    /// The conic's bounds plus the departure's `u⁴·S(u²)` ([`super::q_section_bounds`]).
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let [_, slope, curvature] =
            section_term_bounds(4, self.sum.degree(), self.norm, t, |x| self.sum.eval(x));
        self.conic.section_bounds(t)?.plus(slope, curvature)
    }

    fn describe(&self) -> String {
        format!(
            "Qcon asphere (Forbes 2007) on the conic {}, N {} mm [{}]",
            self.conic.shape(),
            self.norm,
            describe_coefficients(&self.a)
        )
    }
}
