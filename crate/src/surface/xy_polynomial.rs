//! XY polynomial on an asphere base: `z = asphere(x, y) + Σ cᵢⱼ·(x/N)ⁱ·(y/N)ʲ`, i + j ≤ 10,
//! with normalisation radius N so that every coefficient is in millimetres.
//!
//! Derivatives term by term: `∂/∂x (x/N)ⁱ = (i/N)(x/N)ⁱ⁻¹`. Zemax's "Extended Polynomial" uses
//! the same normalised monomials; its plain "XY polynomial" uses un-normalised ones, which are
//! these with N = 1.

use super::polynomial::Bivariate;
use super::{Asphere, AsphereSpec, Local, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite, length};
use serde::{Deserialize, Serialize};

/// The highest total degree i + j.
pub const MAX_DEGREE: u32 = 10;

/// One term `coefficient_mm · (x/N)^x · (y/N)^y`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct XyTerm {
    /// Power of x/N, 0…10.
    pub x: u32,
    /// Power of y/N, 0…10 − x.
    pub y: u32,
    /// Coefficient, mm.
    pub coefficient_mm: f64,
}

/// Job entry of an XY polynomial surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct XyPolynomialSpec {
    /// The base asphere (use `{"curvature_per_mm": 0}` for none).
    pub base: AsphereSpec,
    /// Normalisation radius N, mm, > 0.
    pub norm_radius_mm: f64,
    /// The terms; each (x, y) pair at most once, x + y ≤ 10.
    pub terms: Vec<XyTerm>,
}

/// An XY polynomial surface, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct XyPolynomial {
    base: Asphere,
    norm: f64,
    poly: Bivariate,
}

impl XyPolynomial {
    /// Checks a spec and builds the surface.
    pub fn new(spec: &XyPolynomialSpec) -> Result<Self, FieldError> {
        let base = Asphere::new(&spec.base).map_err(|e| e.within("base"))?;
        let norm = length("norm_radius_mm", spec.norm_radius_mm)?;
        let mut terms = Vec::with_capacity(spec.terms.len());
        for (n, t) in spec.terms.iter().enumerate() {
            let field = format!("terms[{n}]");
            // In u64: two u32 powers may add up past u32::MAX.
            if u64::from(t.x) + u64::from(t.y) > u64::from(MAX_DEGREE) {
                return Err(FieldError::new(
                    field,
                    format!("x{} y{}", t.x, t.y),
                    format!("the total degree x + y must be ≤ {MAX_DEGREE}"),
                ));
            }
            if spec.terms[..n].iter().any(|u| u.x == t.x && u.y == t.y) {
                return Err(FieldError::new(
                    field,
                    format!("x{} y{}", t.x, t.y),
                    "each term at most once",
                ));
            }
            let c = finite(&format!("{field}.coefficient_mm"), t.coefficient_mm)?;
            terms.push((t.x as usize, t.y as usize, c));
        }
        Ok(Self {
            base,
            norm,
            poly: Bivariate::new(terms),
        })
    }

    fn degree(&self) -> usize {
        self.poly.degree()
    }
}

impl Surface for XyPolynomial {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let mut l = self.base.local(x, y)?;
        self.poly.add_to(&mut l, x, y, self.norm);
        Ok(l)
    }

    /// The base asphere's bounds plus the polynomial's, term by term
    /// ([`Bivariate::section_bounds_on`]).
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.poly
            .section_bounds_on(&self.base, radius_mm, self.norm)
    }

    fn feature_length_mm(&self) -> f64 {
        match self.degree() {
            0 => self.base.feature_length_mm(),
            d => self.norm / d as f64,
        }
    }

    fn describe(&self) -> String {
        let terms: Vec<String> = self
            .poly
            .terms()
            .iter()
            .map(|(i, j, c)| format!("x{i}y{j} {c:e}"))
            .collect();
        format!(
            "XY polynomial N {} mm [{}] on {}",
            self.norm,
            terms.join(", "),
            self.base.describe()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(terms: Vec<XyTerm>) -> XyPolynomialSpec {
        XyPolynomialSpec {
            base: AsphereSpec {
                radius_mm: Some(100.0),
                ..Default::default()
            },
            norm_radius_mm: 5.0,
            terms,
        }
    }

    #[test]
    fn section_bounds_are_the_base_and_the_terms_and_hold_on_dense_sections() {
        let t = |x, y, c| XyTerm {
            x,
            y,
            coefficient_mm: c,
        };
        let s = XyPolynomial::new(&spec(vec![
            t(2, 0, 0.004),
            t(0, 2, -0.004),
            t(2, 1, 0.0015),
            t(0, 3, 5e-4),
        ]))
        .unwrap();
        let (b, _, _) = crate::surface::section_bounds::assert_bounds_hold(&s, 6.0, 360, 2000);
        let base = s.base.section_bounds(6.0).unwrap();
        assert!(b.max_slope > base.max_slope && b.max_curvature > base.max_curvature);
        // No base bounds, no bounds (a sphere smaller than the disc).
        let mut small = spec(vec![t(1, 1, 1e-3)]);
        small.base.radius_mm = Some(4.0);
        assert!(
            XyPolynomial::new(&small)
                .unwrap()
                .section_bounds(6.0)
                .is_none()
        );
    }

    #[test]
    fn terms_add_to_the_base_as_written_by_hand() {
        let t = |x, y, c| XyTerm {
            x,
            y,
            coefficient_mm: c,
        };
        let s = XyPolynomial::new(&spec(vec![t(2, 1, 0.003), t(0, 4, -0.001), t(10, 0, 1e-4)]))
            .unwrap();
        let (x, y) = (1.5, -2.5);
        let (u, v) = (x / 5.0, y / 5.0);
        // The sphere in its cancellation-free form s / (R + √(R² − s)).
        let r2 = x * x + y * y;
        let base = r2 / (100.0 + (100.0f64 * 100.0 - r2).sqrt());
        let z = base + 0.003 * u * u * v - 0.001 * v.powi(4) + 1e-4 * u.powi(10);
        let got = s.local(x, y).unwrap().z;
        assert!((got - z).abs() < 1e-15, "{got} vs {z}");
    }

    #[test]
    fn bad_terms_are_rejected_with_their_index() {
        let t = |x, y| XyTerm {
            x,
            y,
            coefficient_mm: 1.0,
        };
        let e = XyPolynomial::new(&spec(vec![t(6, 5)])).unwrap_err();
        assert_eq!(
            e.to_string(),
            "terms[0] = x6 y5: the total degree x + y must be ≤ 10"
        );
        // Powers whose sum wraps around in u32 are refused too, not taken for degree 0.
        let e = XyPolynomial::new(&spec(vec![t(1, 1), t(u32::MAX, 1)])).unwrap_err();
        assert_eq!(e.field, "terms[1]");
        assert_eq!(
            XyPolynomial::new(&spec(vec![t(1, 1), t(1, 1)]))
                .unwrap_err()
                .field,
            "terms[1]"
        );
        let mut s = spec(vec![]);
        s.norm_radius_mm = 0.0;
        assert_eq!(XyPolynomial::new(&s).unwrap_err().field, "norm_radius_mm");
    }
}
