//! The first 37 Fringe Zernike terms of a residual, fitted by least squares: the figures an
//! optician reads a form error by (issue 15). The terms are the Zernike family's own
//! ([`crate::surface::zernike`]: University of Arizona ordering, un-normalised, every radial
//! polynomial 1 at ρ = 1; J. C. Wyant and K. Creath 1992), over the disc of radius N (the part
//! radius), so a coefficient is the term's sag at the rim, and a fitted residual can be written
//! into a `zernike` surface with `convention: fringe` and `norm_radius_mm: N` unchanged.
//!
//! **Evaluation.** Each term is `Rₙᵐ(ρ)·cos/sin(mφ) = [Σₖ cₖ·(ρ²)^((n−m)/2−k)]·Re/Im (u + iv)ᵐ`
//! with u = x/N, v = y/N and cₖ the family's [`radial_coefficients`]: a polynomial in u, v, exact
//! at the centre, 37 terms from one table of powers per point.
//!
//! **Fit.** The normal equations `Σ φφᵀ c = Σ φ z` over the points
//! ([`super::normal_equations`]), solved by Cholesky; where the points do not determine every
//! term (a measured area much smaller than the disc, a few profiles) the least-norm solution is
//! taken instead, and the fit says so.

use super::normal_equations::NormalEquations;
use crate::surface::zernike::{Azimuth, Convention, MAX_FRINGE_TERMS, radial_coefficients};
use serde::Serialize;

/// The number of Fringe terms fitted.
pub const FRINGE_TERMS: usize = MAX_FRINGE_TERMS;

/// One Fringe term prepared for evaluation: its azimuthal order, angular factor and the radial
/// coefficients by power of ρ², highest first.
#[derive(Debug, Clone)]
struct PreparedTerm {
    m: usize,
    azimuth: Azimuth,
    radial: Vec<f64>,
}

/// The 37 Fringe terms, ready to evaluate at a point.
#[derive(Debug, Clone)]
pub struct FringeBasis {
    terms: Vec<PreparedTerm>,
}

impl Default for FringeBasis {
    fn default() -> Self {
        Self::new()
    }
}

impl FringeBasis {
    /// The terms Z1 … Z37 of [`Convention::Fringe`].
    pub fn new() -> Self {
        let terms = (1..=FRINGE_TERMS)
            .filter_map(|j| Convention::Fringe.term(j))
            .map(|t| PreparedTerm {
                m: t.m,
                azimuth: t.azimuth,
                radial: radial_coefficients(t.n, t.m),
            })
            .collect();
        Self { terms }
    }

    /// The values of Z1 … Z37 at (u, v) = (x, y)/N into `out`.
    pub fn values(&self, u: f64, v: f64, out: &mut [f64; FRINGE_TERMS]) {
        let rho2 = u * u + v * v;
        let mut powers = [1.0; 8];
        for k in 1..powers.len() {
            powers[k] = powers[k - 1] * rho2;
        }
        // (u + iv)^m for m = 0 … 6.
        let mut re = [1.0; 7];
        let mut im = [0.0; 7];
        for m in 1..re.len() {
            re[m] = re[m - 1] * u - im[m - 1] * v;
            im[m] = re[m - 1] * v + im[m - 1] * u;
        }
        for (slot, t) in out.iter_mut().zip(&self.terms) {
            let top = t.radial.len() - 1;
            let radial: f64 = t
                .radial
                .iter()
                .enumerate()
                .map(|(k, c)| c * powers[top - k])
                .sum();
            *slot = radial
                * match t.azimuth {
                    Azimuth::Symmetric => 1.0,
                    Azimuth::Cos => re[t.m],
                    Azimuth::Sin => im[t.m],
                };
        }
    }
}

/// The fitted coefficients.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZernikeFit {
    /// The normalisation radius N, mm.
    pub norm_radius_mm: f64,
    /// Coefficients of Z1 … Z37, mm.
    pub coefficients_mm: Vec<f64>,
    /// Whether the points left some combination of terms undetermined (the least-norm solution
    /// was taken).
    pub underdetermined: bool,
}

impl ZernikeFit {
    /// Fits Z1 … Z37 over the disc of radius `norm_radius_mm` to `points` (x, y, z in mm).
    /// With fewer points than terms every coefficient is determined only in the least-norm
    /// sense ([`ZernikeFit::underdetermined`]).
    pub fn fit(points: &[[f64; 3]], norm_radius_mm: f64) -> Self {
        let basis = FringeBasis::new();
        let sums = NormalEquations::accumulate(points.len(), FRINGE_TERMS, |i, a, b| {
            let [x, y, z] = points[i];
            let mut phi = [0.0; FRINGE_TERMS];
            basis.values(x / norm_radius_mm, y / norm_radius_mm, &mut phi);
            a.copy_from_slice(&phi);
            *b = z;
            Ok::<(), ()>(())
        });
        let (coefficients, underdetermined) = match sums {
            Ok(s) => s.solve(),
            Err(()) => (nalgebra::DVector::zeros(FRINGE_TERMS), true),
        };
        Self {
            norm_radius_mm,
            coefficients_mm: coefficients.iter().copied().collect(),
            underdetermined,
        }
    }

    /// The fitted sum at (x, y), mm.
    pub fn value(&self, basis: &FringeBasis, x: f64, y: f64) -> f64 {
        let mut phi = [0.0; FRINGE_TERMS];
        basis.values(x / self.norm_radius_mm, y / self.norm_radius_mm, &mut phi);
        phi.iter()
            .zip(&self.coefficients_mm)
            .map(|(p, c)| p * c)
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{PartDisc, Surface, Zernike, ZernikeSpec};

    #[test]
    fn terms_are_the_zernike_familys_own() {
        let basis = FringeBasis::new();
        let mut phi = [0.0; FRINGE_TERMS];
        for j in 1..=FRINGE_TERMS {
            let mut c = vec![0.0; j];
            c[j - 1] = 1.0;
            let z = Zernike::new(
                &ZernikeSpec {
                    convention: Convention::Fringe,
                    base: crate::surface::AsphereSpec {
                        curvature_per_mm: Some(0.0),
                        ..Default::default()
                    },
                    norm_radius_mm: 3.0,
                    coefficients_mm: c,
                },
                PartDisc::centred(3.0),
            )
            .unwrap();
            for &(x, y) in &[(0.0, 0.0), (1.2, -0.7), (-2.9, 0.3), (0.4, 2.5)] {
                basis.values(x / 3.0, y / 3.0, &mut phi);
                let want = z.sag(x, y).unwrap();
                assert!((phi[j - 1] - want).abs() < 1e-12, "Z{j} at ({x}, {y})");
            }
        }
    }

    #[test]
    fn a_sum_of_terms_is_recovered_exactly() {
        let want: Vec<f64> = (0..FRINGE_TERMS)
            .map(|j| 1e-4 * ((j * 7919) % 13) as f64 - 6e-4)
            .collect();
        let fit0 = ZernikeFit {
            norm_radius_mm: 5.0,
            coefficients_mm: want.clone(),
            underdetermined: false,
        };
        let basis = FringeBasis::new();
        let mut points = Vec::new();
        for j in -40..=40 {
            for i in -40..=40 {
                let (x, y) = (i as f64 * 0.12, j as f64 * 0.12);
                if x.hypot(y) <= 5.0 {
                    points.push([x, y, fit0.value(&basis, x, y)]);
                }
            }
        }
        let fit = ZernikeFit::fit(&points, 5.0);
        assert!(!fit.underdetermined);
        for (a, b) in fit.coefficients_mm.iter().zip(&want) {
            assert!((a - b).abs() < 1e-13, "{a} vs {b}");
        }
        // A line of points determines only part of it: the least-norm answer, flagged.
        let line: Vec<[f64; 3]> = (0..50).map(|i| [i as f64 * 0.1, 0.0, 1e-3]).collect();
        assert!(ZernikeFit::fit(&line, 5.0).underdetermined);
    }
}
