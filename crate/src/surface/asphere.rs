//! Even asphere: `z = c·r² / (1 + √(1 − (1+k)·c²·r²)) + Σ A₂ᵢ·r²ⁱ`, i = 2…10 (the ISO 10110-12
//! form; plane for c = 0 and no terms, sphere for k = 0, paraboloid for k = −1).
//!
//! Derivatives are taken in s = r²: `dz/ds = c / (2√q) + Σ i·A₂ᵢ·sⁱ⁻¹` and
//! `d²z/ds² = (1+k)·c³ / (4·q^{3/2}) + Σ i(i−1)·A₂ᵢ·sⁱ⁻²` with `q = 1 − (1+k)c²s`, then
//! `∂z/∂x = 2x·z_s`, `∂²z/∂x² = 2z_s + 4x²·z_ss`, `∂²z/∂x∂y = 4xy·z_ss`. The conic is undefined
//! where q ≤ 0 (beyond the hyperboloid's or ellipsoid's rim, where the slope turns vertical).

use super::{Local, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite};
use serde::{Deserialize, Serialize};

/// The largest number of polynomial terms: A4 … A20.
pub const MAX_TERMS: usize = 9;

/// Job entry of an even asphere. Give exactly one of `radius_mm` and `curvature_per_mm`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AsphereSpec {
    /// Vertex radius of curvature R, mm, non-zero; positive when the centre of curvature lies on
    /// +Z (the surface rises away from the axis). Use `curvature_per_mm: 0` for a plane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_mm: Option<f64>,
    /// Vertex curvature c = 1/R, 1/mm; 0 for a plane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_per_mm: Option<f64>,
    /// Conic constant k (0 sphere, −1 paraboloid, < −1 hyperboloid, > 0 oblate ellipsoid);
    /// default 0.
    #[serde(default)]
    pub conic: f64,
    /// Polynomial coefficients A4, A6, …, A20 of r⁴ … r²⁰ in mm^(1−2i); at most 9, default none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub coefficients: Vec<f64>,
}

/// An even asphere, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Asphere {
    c: f64,
    k: f64,
    /// `a[i]` multiplies `s^(i+2)`, s = r².
    a: Vec<f64>,
}

impl Asphere {
    /// Checks a spec and builds the surface.
    pub fn new(spec: &AsphereSpec) -> Result<Self, FieldError> {
        let c = match (spec.radius_mm, spec.curvature_per_mm) {
            (Some(r), None) if r.is_finite() && r != 0.0 => 1.0 / r,
            (Some(r), None) => {
                return Err(FieldError::new(
                    "radius_mm",
                    r,
                    "must be finite and non-zero (use curvature_per_mm: 0 for a plane)",
                ));
            }
            (None, Some(c)) => finite("curvature_per_mm", c)?,
            (Some(r), Some(_)) => {
                return Err(FieldError::new(
                    "radius_mm",
                    r,
                    "give radius_mm or curvature_per_mm, not both",
                ));
            }
            (None, None) => {
                return Err(FieldError::new(
                    "radius_mm",
                    "missing",
                    "give radius_mm or curvature_per_mm (0 for a plane)",
                ));
            }
        };
        let k = finite("conic", spec.conic)?;
        if spec.coefficients.len() > MAX_TERMS {
            return Err(FieldError::new(
                "coefficients",
                format!("{} terms", spec.coefficients.len()),
                format!("at most {MAX_TERMS} terms (A4 … A20)"),
            ));
        }
        for (i, &a) in spec.coefficients.iter().enumerate() {
            finite(&format!("coefficients[{i}] (A{})", 2 * i + 4), a)?;
        }
        Ok(Self {
            c,
            k,
            a: spec.coefficients.clone(),
        })
    }

    /// A sphere of vertex radius `radius_mm` (a spec with nothing else), checked as [`Self::new`]
    /// checks it.
    pub fn sphere(radius_mm: f64) -> Result<Self, FieldError> {
        Self::new(&AsphereSpec {
            radius_mm: Some(radius_mm),
            ..Default::default()
        })
    }

    /// A plane z = 0.
    pub fn plane() -> Self {
        Self {
            c: 0.0,
            k: 0.0,
            a: Vec::new(),
        }
    }

    /// The radius where the conic turns vertical, if any, mm.
    pub fn rim_radius_mm(&self) -> Option<f64> {
        let p = (1.0 + self.k) * self.c * self.c;
        (p > 0.0).then(|| (1.0 / p).sqrt())
    }

    /// z, z_s and z_ss as functions of s = r², or the reason there is none.
    pub(crate) fn in_s(&self, s: f64) -> Result<[f64; 3], String> {
        let (c, k) = (self.c, self.k);
        let q = 1.0 - (1.0 + k) * c * c * s;
        if q <= 0.0 {
            let rim = self.rim_radius_mm().unwrap_or(f64::INFINITY);
            return Err(format!(
                "beyond the conic's rim at radius {rim} mm, where 1 − (1+k)c²r² ≤ 0"
            ));
        }
        let w = q.sqrt();
        let mut z = c * s / (1.0 + w);
        let mut zs = c / (2.0 * w);
        let mut zss = (1.0 + k) * c * c * c / (4.0 * q * w);
        // Horner for P(s) = Σ a_i s^(i+2), with P' and P''.
        let (mut p, mut dp, mut ddp) = (0.0, 0.0, 0.0);
        for &a in self.a.iter().rev() {
            ddp = ddp * s + 2.0 * dp;
            dp = dp * s + p;
            p = p * s + a;
        }
        // P(s) = s² · Q(s) where Q = p: P' = 2sQ + s²Q', P'' = 2Q + 4sQ' + s²Q''.
        z += s * s * p;
        zs += 2.0 * s * p + s * s * dp;
        zss += 2.0 * p + 4.0 * s * dp + s * s * ddp;
        Ok([z, zs, zss])
    }

    /// The curvature c, 1/mm.
    pub fn curvature_per_mm(&self) -> f64 {
        self.c
    }

    /// The definition without the family's name: `R 40 mm, k -1.2, A4 1.5e-6` (`plane, k 0`).
    pub fn shape(&self) -> String {
        let r = radius_words(self.c, "plane");
        let terms: Vec<String> = self
            .a
            .iter()
            .enumerate()
            .map(|(i, a)| format!("A{} {a:e}", 2 * i + 4))
            .collect();
        format!(
            "{r}, k {}{}{}",
            self.k,
            if terms.is_empty() { "" } else { ", " },
            terms.join(", ")
        )
    }

    /// Whether the surface is the plane z = 0 (no curvature, no terms).
    pub fn is_plane(&self) -> bool {
        self.c == 0.0 && self.a.iter().all(|&a| a == 0.0)
    }
}

/// The local values at (x, y) of a surface of revolution given as z(s), s = r², by
/// `[z, dz/ds, d²z/ds²]`: `∂z/∂x = 2x·z_s`, `∂²z/∂x² = 2z_s + 4x²·z_ss`, `∂²z/∂x∂y = 4xy·z_ss`.
pub(crate) fn radial_local(x: f64, y: f64, [z, zs, zss]: [f64; 3]) -> Local {
    Local {
        z,
        zx: 2.0 * x * zs,
        zy: 2.0 * y * zs,
        zxx: 2.0 * zs + 4.0 * x * x * zss,
        zxy: 4.0 * x * y * zss,
        zyy: 2.0 * zs + 4.0 * y * y * zss,
    }
}

/// [`radial_local`] of a surface of revolution whose `z(s)` is `z`, or the surface named
/// `surface` undefined at (x, y) for the reason `z` gives.
pub(crate) fn radial_at(
    surface: &'static str,
    x: f64,
    y: f64,
    z: Result<[f64; 3], String>,
) -> Result<Local, UndefinedError> {
    z.map(|z| radial_local(x, y, z))
        .map_err(|reason| UndefinedError {
            surface,
            x_mm: x,
            y_mm: y,
            radius_mm: x.hypot(y),
            reason,
        })
}

impl Surface for Asphere {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        radial_at("even asphere", x, y, self.in_s(x * x + y * y))
    }

    fn feature_length_mm(&self) -> f64 {
        f64::INFINITY
    }

    /// On |t| ≤ T: the conic's `f′ = c·t/√q` grows with |t| and `f″ = c/q^{3/2}` is monotone
    /// in t² (q = 1 − (1+k)c²t² is linear in it), so their extremes lie at t = T and at
    /// t ∈ {0, T}; each term `A·t^n` adds at most `n·|A|·T^(n−1)` and `n(n−1)·|A|·T^(n−2)`.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let q = 1.0 - (1.0 + self.k) * self.c * self.c * t * t;
        if q.is_nan() || q <= 0.0 {
            return None;
        }
        let conic = self.c / (q * q.sqrt());
        let (mut slope, mut curvature) = (0.0, 0.0);
        // t^(n−2) for n = 4, 6, …: t², t⁴, …
        let mut t_n2 = t * t;
        for (i, a) in self.a.iter().enumerate() {
            let n = (2 * i + 4) as f64;
            slope += n * a.abs() * t_n2 * t;
            curvature += n * (n - 1.0) * a.abs() * t_n2;
            t_n2 *= t * t;
        }
        SectionBounds {
            max_slope: (self.c * t / q.sqrt()).abs(),
            max_curvature: self.c.max(conic),
            min_curvature: self.c.min(conic),
            has_ridges: false,
            has_valleys: false,
        }
        .plus(slope, curvature)
    }

    /// Its section bounds: a surface of revolution's gradient is `p′(ρ)` along the radius,
    /// and its Hessian's eigenvalues are `p″(ρ)` and `p′(ρ)/ρ`, the mean of p″ over [0, ρ]
    /// (p′(0) = 0), both within the sections' curvature bounds.
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.section_bounds(radius_mm)
    }

    fn describe(&self) -> String {
        format!("even asphere {}", self.shape())
    }
}

/// "R … mm" for the curvature `c` (1/mm), or `flat` for none; a curvature so small that its
/// radius is beyond the largest double (a radius of 1.8e308 mm read as 1/R, subnormal) is
/// named by its curvature rather than printed as an infinite radius.
pub(crate) fn radius_words(c: f64, flat: &str) -> String {
    let r = 1.0 / c;
    if c == 0.0 {
        flat.to_string()
    } else if r.is_finite() {
        format!("R {r} mm")
    } else {
        format!("{flat} to within a curvature of {c:e} /mm")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn section_bounds_hold_on_dense_sections_and_are_tight() {
        // Against the radial derivatives sampled densely to the disc's edge; for a bare conic
        // the bounds are the extremes themselves (within 0.1 %).
        for (r, k, a, edge) in [
            (40.0, -1.2, vec![1.5e-6, -2e-9], 5.0),
            (-8.0, 0.5, vec![-1e-4], 3.0),
            (12.0, 0.0, vec![], 4.0),
        ] {
            let bare = a.is_empty();
            let s = Asphere::new(&AsphereSpec {
                radius_mm: Some(r),
                conic: k,
                coefficients: a,
                ..Default::default()
            })
            .unwrap();
            let b = s.section_bounds(edge).unwrap();
            let (mut slope, mut curv) = (0.0f64, f64::NEG_INFINITY);
            for i in 0..=50_000 {
                let l = s
                    .local(edge * i as f64 / 50_000.0, 0.0)
                    .unwrap()
                    .radial(1.0, 0.0);
                slope = slope.max(l.slope.abs());
                curv = curv.max(l.curvature_term);
            }
            assert!(slope <= b.max_slope, "R {r}: {slope} vs {}", b.max_slope);
            assert!(
                curv <= b.max_curvature,
                "R {r}: {curv} vs {}",
                b.max_curvature
            );
            if bare {
                assert!(slope >= 0.999 * b.max_slope, "R {r}: {slope}");
                assert!(
                    curv >= b.max_curvature - 1e-3 * b.max_curvature.abs(),
                    "R {r}"
                );
            }
        }
        // Beyond the conic's rim there is none.
        assert!(Asphere::sphere(4.0).unwrap().section_bounds(5.0).is_none());
    }

    #[test]
    fn sphere_matches_closed_form() {
        let s = Asphere::sphere(20.0).unwrap();
        for &(x, y) in &[(0.0, 0.0), (3.0, -4.0), (10.0, 12.0), (-15.0, 5.0)] {
            let r2: f64 = x * x + y * y;
            let z = 20.0 - (400.0 - r2).sqrt();
            assert!((s.local(x, y).unwrap().z - z).abs() < 1e-13, "{x} {y}");
        }
        // Negative radius: the mirror image.
        let mirror = Asphere::sphere(-20.0).unwrap().local(3.0, 4.0).unwrap().z;
        assert!((mirror + 20.0 - (400.0f64 - 25.0).sqrt()).abs() < 1e-13);
    }

    #[test]
    fn paraboloid_and_polynomial_match_closed_form() {
        let spec = AsphereSpec {
            radius_mm: Some(50.0),
            conic: -1.0,
            coefficients: vec![1e-5, -2e-8, 3e-11],
            ..Default::default()
        };
        let s = Asphere::new(&spec).unwrap();
        let (x, y) = (6.0, -8.0);
        let r2: f64 = 100.0;
        let z = r2 / 100.0 + 1e-5 * r2.powi(2) - 2e-8 * r2.powi(3) + 3e-11 * r2.powi(4);
        assert!((s.local(x, y).unwrap().z - z).abs() < 1e-14);
    }

    #[test]
    fn beyond_the_rim_is_an_error_naming_the_radius() {
        let e = Asphere::sphere(5.0).unwrap().local(3.0, 4.0).unwrap_err();
        assert_eq!(e.radius_mm, 5.0);
        assert!(e.to_string().contains("even asphere"), "{e}");
    }

    #[test]
    fn spec_errors_name_the_field() {
        let both = AsphereSpec {
            radius_mm: Some(1.0),
            curvature_per_mm: Some(1.0),
            ..Default::default()
        };
        assert_eq!(Asphere::new(&both).unwrap_err().field, "radius_mm");
        let zero = AsphereSpec {
            radius_mm: Some(0.0),
            ..Default::default()
        };
        assert!(
            Asphere::new(&zero)
                .unwrap_err()
                .allowed
                .contains("non-zero")
        );
        let many = AsphereSpec {
            curvature_per_mm: Some(0.0),
            coefficients: vec![0.0; 10],
            ..Default::default()
        };
        assert_eq!(Asphere::new(&many).unwrap_err().field, "coefficients");
        let nan = AsphereSpec {
            curvature_per_mm: Some(0.0),
            coefficients: vec![0.0, f64::NAN],
            ..Default::default()
        };
        assert_eq!(
            Asphere::new(&nan).unwrap_err().field,
            "coefficients[1] (A6)"
        );
    }
}
