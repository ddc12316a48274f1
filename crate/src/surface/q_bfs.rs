//! Forbes' Qbfs asphere (G. W. Forbes, "Shape specification for axially symmetric optical
//! surfaces", Opt. Express 15, 5218, 2007, eq 2.2 with the polynomials of section 3): a
//! best-fit sphere plus a departure measured along its normal,
//! `z = c·r²/(1 + √(1 − c²r²)) + u²(1 − u²)/√(1 − c²r²) · Σₘ aₘ·Qₘᵇᶠˢ(u²)`, u = r/N,
//! N the normalisation radius, every aₘ in mm (aₘ is the rms normal slope of its term, times N).
//! The polynomials and their sum come from [`super::q_polynomials`] (Forbes 2010's recurrence
//! and change of basis, never a power series).
//!
//! Derivatives in s = r², ξ = s/N²: with `A = ξ(1 − ξ)·S(ξ)` and `g = (1 − c²s)^(−1/2)`,
//! `A_s = [(1 − 2ξ)S + ξ(1 − ξ)S′]/N²`, `A_ss = [−2S + 2(1 − 2ξ)S′ + ξ(1 − ξ)S″]/N⁴`,
//! `g_s = c²g³/2`, `g_ss = 3c⁴g⁵/4`, and `(Ag)_s = A_s·g + A·g_s` and so on; then x and y
//! as for any surface of revolution. Undefined where c²r² ≥ 1 (the sphere's rim). Beyond u = 1
//! the polynomials continue (they are defined on the disc; a part larger than N is cut on their
//! extension, as design software that extrapolates does).

use super::asphere::radial_at;
use super::q_polynomials::{
    QSum, check_coefficients, describe_coefficients, envelope, rotational_feature_length,
};
use super::q_section_bounds::{along_sphere_normal, section_term_bounds};
use super::{Asphere, AsphereSpec, Local, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, positive};
use serde::{Deserialize, Serialize};

/// Job entry of a Qbfs asphere. Give exactly one of `radius_mm` and `curvature_per_mm`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QBfsSpec {
    /// Radius of the best-fit sphere, mm, non-zero.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_mm: Option<f64>,
    /// Its curvature c = 1/R, 1/mm; 0 for a plane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_per_mm: Option<f64>,
    /// Normalisation radius N, mm, > 0: u = r/N.
    pub norm_radius_mm: f64,
    /// a₀, a₁, … of Qbfs₀, Qbfs₁, …, mm; at most 31.
    pub coefficients_mm: Vec<f64>,
}

/// A Qbfs asphere, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct QBfs {
    sphere: Asphere,
    c: f64,
    norm: f64,
    a: Vec<f64>,
    sum: QSum,
}

impl QBfs {
    /// Checks a spec and builds the surface.
    pub fn new(spec: &QBfsSpec) -> Result<Self, FieldError> {
        let sphere = Asphere::new(&AsphereSpec {
            radius_mm: spec.radius_mm,
            curvature_per_mm: spec.curvature_per_mm,
            ..Default::default()
        })?;
        let norm = positive("norm_radius_mm", spec.norm_radius_mm)?;
        check_coefficients("coefficients_mm", &spec.coefficients_mm)?;
        Ok(Self {
            c: sphere.curvature_per_mm(),
            sphere,
            norm,
            a: spec.coefficients_mm.clone(),
            sum: QSum::qbfs(&spec.coefficients_mm),
        })
    }

    /// `[z, z_s, z_ss]` at s = r².
    fn in_s(&self, s: f64) -> Result<[f64; 3], String> {
        let [z, zs, zss] = self.sphere.in_s(s)?;
        let n2 = self.norm * self.norm;
        let xi = s / n2;
        let [a, a_x, a_xx] = envelope(xi, self.sum.eval(xi));
        let (a_s, a_ss) = (a_x / n2, a_xx / (n2 * n2));
        let c2 = self.c * self.c;
        let g = 1.0 / (1.0 - c2 * s).sqrt();
        let g3 = g * g * g;
        let g_s = 0.5 * c2 * g3;
        let g_ss = 0.75 * c2 * c2 * g3 * g * g;
        Ok([
            z + a * g,
            zs + a_s * g + a * g_s,
            zss + a_ss * g + 2.0 * a_s * g_s + a * g_ss,
        ])
    }
}

impl Surface for QBfs {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        radial_at("Qbfs asphere", x, y, self.in_s(x * x + y * y))
    }

    /// [`rotational_feature_length`] of the coefficients.
    fn feature_length_mm(&self) -> f64 {
        rotational_feature_length(self.norm, &self.a)
    }

    /// The sphere's bounds plus those of the departure `u²(1 − u²)·S(u²)` along its normal
    /// ([`super::q_section_bounds`]).
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let a = section_term_bounds(0, self.sum.degree() + 2, self.norm, t, |x| {
            envelope(x, self.sum.eval(x))
        });
        let (slope, curvature) = along_sphere_normal(self.c, t, a)?;
        self.sphere.section_bounds(t)?.plus(slope, curvature)
    }

    fn describe(&self) -> String {
        let sphere = self.sphere.shape();
        format!(
            "Qbfs asphere (Forbes 2007) on the sphere {}, N {} mm [{}]",
            sphere.strip_suffix(", k 0").unwrap_or(&sphere),
            self.norm,
            describe_coefficients(&self.a)
        )
    }
}
