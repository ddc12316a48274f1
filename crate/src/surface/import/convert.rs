//! From a file's lens units and coefficients to the families' specs in millimetres, shared by
//! the readers: a length is multiplied by s (the unit in mm), a curvature divided by it, and a
//! coefficient of rⁿ in lensunit^(1−n) multiplied by s^(1−n).
//!
//! Both design programs' even aspheres can carry a term in r² (OpticStudio's α1 on Even
//! Asphere, Zernike Sag, Grid Sag and Toroidal surfaces), which spiralcam's `asphere` lacks (its
//! polynomial starts at r⁴, ISO 10110-12). Such a surface becomes an `odd_asphere` with only
//! its even β: βₙ = α_{n/2} for even n, the same sum of powers of r; without α1 it stays an
//! `asphere`. A family whose base is an `asphere` spec (Zernike, Grid Sag) is then written as a
//! `composite` of that base and the family on a plane.

use crate::surface::composite::{CompositeSpec, TermSpec};
use crate::surface::{AsphereSpec, OddAsphereSpec, SurfaceSpec};

/// Millimetres per lens unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Scale(pub f64);

impl Scale {
    /// A length, mm.
    pub fn length(self, v: f64) -> f64 {
        v * self.0
    }

    /// A curvature, 1/mm.
    pub fn curvature(self, c: f64) -> f64 {
        c / self.0
    }

    /// The coefficient of rⁿ (or of a monomial of total degree n), mm^(1−n).
    pub fn coefficient(self, v: f64, n: i32) -> f64 {
        v * self.0.powi(1 - n)
    }
}

/// A conic of vertex curvature `c` (1/mm) and conic constant `k`: the radius when it is
/// finite, else the curvature 0 (a plane).
pub(crate) fn conic(c: f64, k: f64) -> AsphereSpec {
    if c == 0.0 {
        AsphereSpec {
            curvature_per_mm: Some(0.0),
            conic: k,
            ..Default::default()
        }
    } else {
        AsphereSpec {
            radius_mm: Some(1.0 / c),
            conic: k,
            ..Default::default()
        }
    }
}

/// An even asphere: a conic plus α1·r² + α2·r⁴ + … (α in mm^(1−2i)).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct EvenAsphere {
    /// The conic.
    pub conic: AsphereSpec,
    /// α1, α2, … of r², r⁴, …, mm^(1−2i).
    pub alpha: Vec<f64>,
}

impl EvenAsphere {
    /// The conic of `c`, `k` with the terms `alpha` (trailing zeros dropped).
    pub fn new(c: f64, k: f64, alpha: &[f64]) -> Self {
        let mut alpha = alpha.to_vec();
        while alpha.last() == Some(&0.0) {
            alpha.pop();
        }
        Self {
            conic: conic(c, k),
            alpha,
        }
    }

    /// As an `asphere` spec, when it has no r² term.
    pub fn as_asphere(&self) -> Option<AsphereSpec> {
        match self.alpha.first() {
            Some(&a) if a != 0.0 => None,
            _ => Some(AsphereSpec {
                coefficients: self.alpha.iter().skip(1).copied().collect(),
                ..self.conic.clone()
            }),
        }
    }

    /// The surface: an `asphere`, or an `odd_asphere` with βₙ = α_{n/2} when it has an r²
    /// term.
    pub fn spec(&self) -> SurfaceSpec {
        if let Some(a) = self.as_asphere() {
            return SurfaceSpec::Asphere(a);
        }
        let mut beta = vec![0.0; 2 * self.alpha.len()];
        for (i, &a) in self.alpha.iter().enumerate() {
            beta[2 * i + 1] = a;
        }
        SurfaceSpec::OddAsphere(OddAsphereSpec {
            radius_mm: self.conic.radius_mm,
            curvature_per_mm: self.conic.curvature_per_mm,
            conic: self.conic.conic,
            coefficients: beta,
        })
    }

    /// A family with an `asphere` base on this one, its terms decentred by `decentre_mm`:
    /// `family(base)` itself when this is an asphere and the decentre is zero, else a
    /// `composite` of this surface and `family(plane)` placed at the decentre.
    pub fn with_family(
        &self,
        decentre_mm: [f64; 2],
        family: impl Fn(AsphereSpec) -> SurfaceSpec,
    ) -> SurfaceSpec {
        if decentre_mm == [0.0, 0.0]
            && let Some(base) = self.as_asphere()
        {
            return family(base);
        }
        SurfaceSpec::Composite(CompositeSpec {
            base: Box::new(self.spec()),
            terms: vec![TermSpec {
                surface: family(conic(0.0, 0.0)),
                decenter_x_mm: decentre_mm[0],
                decenter_y_mm: decentre_mm[1],
                rotation_deg: 0.0,
                correction: false,
            }],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_r2_term_makes_an_odd_asphere_with_the_same_sag() {
        let e = EvenAsphere::new(1.0 / 40.0, -0.5, &[1e-3, 2e-6, -3e-9, 0.0]);
        assert_eq!(e.alpha.len(), 3);
        let s = e.spec().build(10.0).unwrap();
        let (x, y) = (3.0_f64, -4.0_f64);
        let r2 = x * x + y * y;
        let c = 1.0 / 40.0;
        let z = c * r2 / (1.0 + (1.0 - 0.5 * c * c * r2).sqrt()) + 1e-3 * r2 + 2e-6 * r2 * r2
            - 3e-9 * r2 * r2 * r2;
        assert!((s.sag(x, y).unwrap() - z).abs() < 1e-14);
        assert!(matches!(e.spec(), SurfaceSpec::OddAsphere(_)));
        let plain = EvenAsphere::new(0.0, 0.0, &[0.0, 2e-6]);
        assert_eq!(plain.as_asphere().unwrap().coefficients, vec![2e-6]);
        assert_eq!(Scale(25.4).coefficient(1.0, 4), 25.4f64.powi(-3));
    }
}
