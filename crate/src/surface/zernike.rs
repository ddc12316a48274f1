//! Zernike polynomial sag on an even-asphere base:
//! `z = asphere(x, y) + Σⱼ cⱼ·Zⱼ(ρ, φ)`, `ρ = r/N`, φ from +X towards +Y, N the normalisation
//! radius, every cⱼ in millimetres; the job names the convention, Standard or Fringe, never
//! guessed.
//!
//! - **Standard**: Noll's single index j = 1, 2, … (R. J. Noll, "Zernike polynomials and
//!   atmospheric turbulence", JOSA 66(3), 1976, p. 207, definition and Table I): within a radial
//!   order n the azimuthal orders m increase, and for m ≠ 0 an even j takes cos mφ, an odd j
//!   sin mφ. RMS-normalised: `Zⱼ = √(n+1)·Rₙ⁰(ρ)` for m = 0 and `√(2(n+1))·Rₙᵐ(ρ)·cos/sin(mφ)`
//!   else, so that `∫ Zⱼ² dA / π = 1` over the unit disc. This is Zemax OpticStudio's "Zernike
//!   Standard Sag", NOT the ANSI Z80.28 / OSA single index (which counts from j = 0 and orders m
//!   from −n to n). Up to n = 20: 231 terms.
//! - **Fringe**: the University of Arizona ordering of OpticStudio's "Zernike Fringe Sag"
//!   (J. C. Wyant and K. Creath, "Basic wavefront aberration theory for optical metrology",
//!   Applied Optics and Optical Engineering XI, 1992, the 37-term list): grouped by
//!   g = (n + m)/2, within a group m falls from g to 0 (n = 2g − m), cos before sin; term 37 is
//!   R₁₂⁰. Not normalised: every radial polynomial is 1 at ρ = 1. Up to 37 terms (beyond 37 the
//!   ordering is not standardised).
//!
//! The radial polynomial is Zernike's finite sum
//! `Rₙᵐ(ρ) = Σₖ (−1)ᵏ (n−k)! / (k! ((n+m)/2 − k)! ((n−m)/2 − k)!) · ρⁿ⁻²ᵏ` (Noll 1976). In
//! [`Zernike::new`] the whole sum is converted once into a polynomial in u = x/N, v = y/N, with
//! `ρᵐ·cos mφ = Re (u + iv)ᵐ`, `ρᵐ·sin mφ = Im (u + iv)ᵐ` and `ρ²ᵖ = (u² + v²)ᵖ` expanded
//! binomially; evaluating that polynomial and its derivatives from power tables (as
//! [`super::xy_polynomial`] does, with [`super::polynomial`], up to degree 20) is exact at ρ = 0, where the polar
//! derivatives are singular. Outside ρ = 1 the polynomial simply continues (OpticStudio does the
//! same with its "Extrapolate" flag set to 1; with 0 it drops the Zernike terms there, a step in
//! the sag that no tool can follow). Rounding: the monomial coefficients alternate in sign, and
//! at ρ ≤ 1 the rounding error of a term is at most about ε·√(2(n+1))·Σₖ|cₖ|·2^(m/2) times its
//! coefficient: 1e-14 at n = 4, 3e-12 at n = 10 and 3e-8 at n = 20 (measured against the stable
//! recurrence of the radial polynomials: 4e-15, 3e-13 and 2.5e-9), well under a nanometre for
//! any realistic coefficient. Crate docs: `crate/docs/zernike.md` lists both orderings.

use super::polynomial::{Bivariate, Dense};
use super::{Asphere, AsphereSpec, Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite, length};
use serde::{Deserialize, Serialize};

/// The highest radial order n of a Standard term.
pub const MAX_ORDER: usize = super::polynomial::MAX_DEGREE;
/// The number of Standard terms: all with n ≤ 20.
pub const MAX_STANDARD_TERMS: usize = (MAX_ORDER + 1) * (MAX_ORDER + 2) / 2;
/// The number of Fringe terms.
pub const MAX_FRINGE_TERMS: usize = 37;

/// Which single-index ordering and normalisation the coefficients follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Convention {
    /// Noll ordering from j = 1, RMS-normalised (OpticStudio "Zernike Standard"); 231 terms.
    Standard,
    /// University of Arizona ordering, un-normalised (OpticStudio "Zernike Fringe"); 37 terms.
    Fringe,
}

/// The angular factor of a term.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Azimuth {
    /// m = 0: rotationally symmetric, no angular factor.
    Symmetric,
    /// cos mφ.
    Cos,
    /// sin mφ.
    Sin,
}

/// One Zernike term: radial order n, azimuthal order m ≥ 0 and its angular factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Term {
    /// Radial order n.
    pub n: usize,
    /// Azimuthal order m, 0 ≤ m ≤ n, n − m even.
    pub m: usize,
    /// cos mφ, sin mφ, or symmetric for m = 0.
    pub azimuth: Azimuth,
}

impl Convention {
    /// The number of terms the convention defines here.
    pub fn max_terms(self) -> usize {
        match self {
            Convention::Standard => MAX_STANDARD_TERMS,
            Convention::Fringe => MAX_FRINGE_TERMS,
        }
    }

    /// Term j (from 1), or `None` beyond [`Convention::max_terms`].
    pub fn term(self, j: usize) -> Option<Term> {
        if j == 0 || j > self.max_terms() {
            return None;
        }
        Some(match self {
            Convention::Standard => noll(j),
            Convention::Fringe => fringe(j),
        })
    }

    /// The factor in front of `Rₙᵐ(ρ)·cos/sin(mφ)`.
    pub fn normalisation(self, t: Term) -> f64 {
        match (self, t.m) {
            (Convention::Fringe, _) => 1.0,
            (Convention::Standard, 0) => ((t.n + 1) as f64).sqrt(),
            (Convention::Standard, _) => (2.0 * (t.n + 1) as f64).sqrt(),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Convention::Standard => "Standard (Noll, RMS-normalised)",
            Convention::Fringe => "Fringe (University of Arizona, un-normalised)",
        }
    }
}

/// Noll's term j: order n holds j = n(n+1)/2 + 1 … (n+1)(n+2)/2, with |m| rising in pairs
/// (0, 2, 2, 4, 4, … for even n; 1, 1, 3, 3, … for odd n); even j is cos, odd j sin.
fn noll(j: usize) -> Term {
    let mut n = 0;
    while (n + 1) * (n + 2) / 2 < j {
        n += 1;
    }
    let k = j - n * (n + 1) / 2 - 1;
    let m = if n % 2 == 0 {
        2 * k.div_ceil(2)
    } else {
        2 * (k / 2) + 1
    };
    let azimuth = match (m, j % 2) {
        (0, _) => Azimuth::Symmetric,
        (_, 0) => Azimuth::Cos,
        _ => Azimuth::Sin,
    };
    Term { n, m, azimuth }
}

/// Fringe term j ≤ 37: group g = ⌊√(j − 1)⌋ holds j = g² + 1 … (g + 1)², m = g, g, g − 1,
/// g − 1, …, 0 with cos before sin; term 37 starts group 6 with R₁₂⁰ alone.
fn fringe(j: usize) -> Term {
    if j == MAX_FRINGE_TERMS {
        return Term {
            n: 12,
            m: 0,
            azimuth: Azimuth::Symmetric,
        };
    }
    let mut g = 0;
    while (g + 1) * (g + 1) < j {
        g += 1;
    }
    let r = j - 1 - g * g;
    let m = g - r / 2;
    let azimuth = match (m, r % 2) {
        (0, _) => Azimuth::Symmetric,
        (_, 0) => Azimuth::Cos,
        _ => Azimuth::Sin,
    };
    Term {
        n: 2 * g - m,
        m,
        azimuth,
    }
}

/// n! exactly (n ≤ 20 < 21, since 20! < 2⁶³).
fn factorial(n: usize) -> u64 {
    (1..=n as u64).product()
}

fn binomial(n: usize, k: usize) -> f64 {
    (factorial(n) / (factorial(k) * factorial(n - k))) as f64
}

/// The coefficients cₖ of `Rₙᵐ(ρ) = Σₖ cₖ·ρⁿ⁻²ᵏ`, k = 0 … (n − m)/2, exact integers.
pub fn radial_coefficients(n: usize, m: usize) -> Vec<f64> {
    let (a, b) = ((n + m) / 2, (n - m) / 2);
    (0..=b)
        .map(|k| {
            let c = factorial(n - k) / (factorial(k) * factorial(a - k) * factorial(b - k));
            if k % 2 == 0 { c as f64 } else { -(c as f64) }
        })
        .collect()
}

/// Adds `scale·Rₙᵐ(ρ)·cos/sin(mφ)` in u, v to `a`: the product of
/// `Σₖ cₖ·(u² + v²)^((n−m)/2 − k)` and `Re/Im (u + iv)ᵐ = Re/Im Σₗ C(m, l)·uᵐ⁻ˡ·iˡ·vˡ`, whose
/// real part takes the even l and the imaginary part the odd l, each with the sign
/// `(−1)^⌊l/2⌋` of iˡ.
fn add_term(a: &mut Dense, t: Term, scale: f64) {
    let first_l = if t.azimuth == Azimuth::Sin { 1 } else { 0 };
    for (k, ck) in radial_coefficients(t.n, t.m).into_iter().enumerate() {
        let p = (t.n - t.m) / 2 - k;
        for q in 0..=p {
            let radial = scale * ck * binomial(p, q);
            for l in (first_l..=t.m).step_by(2) {
                let sign = if (l / 2) % 2 == 0 { 1.0 } else { -1.0 };
                a[2 * q + t.m - l][2 * (p - q) + l] += sign * radial * binomial(t.m, l);
            }
        }
    }
}

/// Job entry of a Zernike surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ZernikeSpec {
    /// `standard` (Noll, RMS-normalised, up to 231 terms) or `fringe` (University of Arizona,
    /// un-normalised, up to 37 terms); required.
    pub convention: Convention,
    /// The base asphere (use `{"curvature_per_mm": 0}` for a plane).
    pub base: AsphereSpec,
    /// Normalisation radius N, mm, > 0: ρ = r/N.
    pub norm_radius_mm: f64,
    /// Coefficients c₁, c₂, … of Z₁, Z₂, … in index order, mm; missing trailing terms are 0.
    pub coefficients_mm: Vec<f64>,
}

/// A Zernike surface, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Zernike {
    convention: Convention,
    base: Asphere,
    norm: f64,
    coefficients: Vec<f64>,
    poly: Bivariate,
    /// Highest radial order with a non-zero coefficient.
    order: usize,
}

impl Zernike {
    /// Checks a spec and builds the surface (the part disc is not needed).
    pub fn new(spec: &ZernikeSpec, _part: PartDisc) -> Result<Self, FieldError> {
        let base = Asphere::new(&spec.base).map_err(|e| e.within("base"))?;
        let norm = length("norm_radius_mm", spec.norm_radius_mm)?;
        let conv = spec.convention;
        let max = conv.max_terms();
        if spec.coefficients_mm.len() > max {
            let allowed = match conv {
                Convention::Standard => format!(
                    "at most {max} for standard (Noll Z1 … Z{max}, radial order n ≤ {MAX_ORDER})"
                ),
                Convention::Fringe => format!(
                    "at most {max} for fringe (Z1 … Z{max}; beyond 37 the Fringe ordering is \
                     not standardised)"
                ),
            };
            return Err(FieldError::new(
                "coefficients_mm",
                format!("{} terms", spec.coefficients_mm.len()),
                allowed,
            ));
        }
        let mut dense = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
        let mut order = 0;
        for (i, &c) in spec.coefficients_mm.iter().enumerate() {
            finite(&format!("coefficients_mm[{i}] (Z{})", i + 1), c)?;
            let Some(t) = conv.term(i + 1) else {
                continue;
            };
            if c != 0.0 {
                add_term(&mut dense, t, c * conv.normalisation(t));
                order = order.max(t.n);
            }
        }
        Ok(Self {
            convention: conv,
            base,
            norm,
            coefficients: spec.coefficients_mm.clone(),
            poly: Bivariate::from_dense(&dense),
            order,
        })
    }

    /// The highest radial order n with a non-zero coefficient.
    pub fn radial_order(&self) -> usize {
        self.order
    }
}

impl Surface for Zernike {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let mut l = self.base.local(x, y)?;
        let n = self.norm;
        self.poly.add_to(&mut l, x, y, n);
        Ok(l)
    }

    /// N/(2·n_max) for the highest radial order n_max ≥ 2 present (the base's below that: piston
    /// and tilt have no feature). Rₙᵐ has its extrema closest together near ρ = 1, where the
    /// zeros of `Rₙ⁰(ρ) = P_(n/2)(2ρ² − 1)` are about 12/n² apart in ρ: more than 1/(2n) for
    /// every n ≤ 20, so N/(2n) does not step over a slope reversal of any single term.
    /// The base asphere's bounds plus the polynomial's, term by term
    /// ([`Bivariate::section_bounds_on`]).
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.poly
            .section_bounds_on(&self.base, radius_mm, self.norm)
    }

    fn feature_length_mm(&self) -> f64 {
        if self.order < 2 {
            self.base.feature_length_mm()
        } else {
            (self.norm / (2 * self.order) as f64).min(self.base.feature_length_mm())
        }
    }

    fn describe(&self) -> String {
        let terms: Vec<String> = self
            .coefficients
            .iter()
            .enumerate()
            .filter(|(_, c)| **c != 0.0)
            .map(|(i, c)| format!("Z{} {c:e}", i + 1))
            .collect();
        format!(
            "Zernike {} sag, N {} mm [{}] on {}",
            self.convention.name(),
            self.norm,
            terms.join(", "),
            self.base.describe()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn zernike(convention: Convention, coefficients_mm: Vec<f64>) -> Result<Zernike, FieldError> {
        Zernike::new(
            &ZernikeSpec {
                convention,
                base: AsphereSpec {
                    curvature_per_mm: Some(0.0),
                    ..Default::default()
                },
                norm_radius_mm: 2.0,
                coefficients_mm,
            },
            PartDisc::centred(2.0),
        )
    }

    #[test]
    fn section_bounds_hold_on_dense_sections() {
        // Low orders (the example jobs'), and a single high order whose monomials cancel: its
        // bound holds but is far from tight.
        let low = zernike(
            Convention::Fringe,
            vec![0.0, 0.0, 0.0, 0.0, 0.003, 0.002, 0.0, -0.0025, 0.0, 0.002],
        )
        .unwrap();
        let high = zernike(Convention::Standard, unit(45)).unwrap();
        for s in [low, high] {
            crate::surface::section_bounds::assert_bounds_hold(&s, 2.0, 360, 2000);
        }
    }

    fn unit(j: usize) -> Vec<f64> {
        let mut c = vec![0.0; j];
        c[j - 1] = 1.0;
        c
    }

    #[test]
    fn index_maps_start_as_in_the_tables() {
        let t = |n, m, azimuth| Term { n, m, azimuth };
        use Azimuth::*;
        let noll = [
            t(0, 0, Symmetric),
            t(1, 1, Cos),
            t(1, 1, Sin),
            t(2, 0, Symmetric),
            t(2, 2, Sin),
            t(2, 2, Cos),
            t(3, 1, Sin),
            t(3, 1, Cos),
            t(3, 3, Sin),
            t(3, 3, Cos),
            t(4, 0, Symmetric),
        ];
        for (j, e) in noll.iter().enumerate() {
            assert_eq!(Convention::Standard.term(j + 1), Some(*e), "Noll {}", j + 1);
        }
        let fringe = [
            t(0, 0, Symmetric),
            t(1, 1, Cos),
            t(1, 1, Sin),
            t(2, 0, Symmetric),
            t(2, 2, Cos),
            t(2, 2, Sin),
            t(3, 1, Cos),
            t(3, 1, Sin),
            t(4, 0, Symmetric),
            t(3, 3, Cos),
        ];
        for (j, e) in fringe.iter().enumerate() {
            assert_eq!(Convention::Fringe.term(j + 1), Some(*e), "Fringe {}", j + 1);
        }
        assert_eq!(Convention::Fringe.term(36), Some(t(10, 0, Symmetric)));
        assert_eq!(Convention::Fringe.term(37), Some(t(12, 0, Symmetric)));
        assert_eq!(Convention::Fringe.term(38), None);
        assert_eq!(Convention::Standard.term(231), Some(t(20, 20, Sin)));
        assert_eq!(Convention::Standard.term(232), None);
        assert_eq!(Convention::Standard.term(0), None);
    }

    #[test]
    fn every_term_is_once_in_each_convention() {
        for conv in [Convention::Standard, Convention::Fringe] {
            let terms: Vec<Term> = (1..=conv.max_terms())
                .map(|j| conv.term(j).unwrap())
                .collect();
            for (a, t) in terms.iter().enumerate() {
                assert!(t.m <= t.n && (t.n - t.m) % 2 == 0, "{conv:?} {t:?}");
                assert_eq!(t.m == 0, t.azimuth == Azimuth::Symmetric, "{conv:?} {t:?}");
                assert!(!terms[..a].contains(t), "{conv:?} {t:?} twice");
            }
        }
    }

    #[test]
    fn radial_coefficients_are_zernikes_sums() {
        // R₄⁰ = 6ρ⁴ − 6ρ² + 1, R₅¹ = 10ρ⁵ − 12ρ³ + 3ρ, R₁₂⁰ (Fringe Z37) by hand.
        assert_eq!(radial_coefficients(4, 0), vec![6.0, -6.0, 1.0]);
        assert_eq!(radial_coefficients(5, 1), vec![10.0, -12.0, 3.0]);
        assert_eq!(
            radial_coefficients(12, 0),
            vec![924.0, -2772.0, 3150.0, -1680.0, 420.0, -42.0, 1.0]
        );
        // Every Rₙᵐ(1) = 1.
        for n in 0..=MAX_ORDER {
            for m in (n % 2..=n).step_by(2) {
                assert_eq!(
                    radial_coefficients(n, m).iter().sum::<f64>(),
                    1.0,
                    "{n} {m}"
                );
            }
        }
    }

    #[test]
    fn a_term_is_exact_at_the_centre() {
        // Standard Z4 = √3(2ρ² − 1): −√3 at ρ = 0 with zero slope and curvature 4√3/N².
        let s = zernike(Convention::Standard, unit(4)).unwrap();
        let l = s.local(0.0, 0.0).unwrap();
        assert_eq!(l.z, -(3f64.sqrt()));
        assert_eq!((l.zx, l.zy, l.zxy), (0.0, 0.0, 0.0));
        assert!((l.zxx - 4.0 * 3f64.sqrt() / 4.0).abs() < 1e-15);
        assert_eq!(s.radial_order(), 2);
        assert_eq!(s.feature_length_mm(), 0.5);
        // Tilt alone has no feature.
        assert_eq!(
            zernike(Convention::Fringe, unit(3))
                .unwrap()
                .feature_length_mm(),
            f64::INFINITY
        );
    }

    #[test]
    fn the_feature_length_is_below_the_slope_reversals_of_every_term() {
        // Along a line through the axis a term is `Rₙᵐ(|t|)·(±1)` = `Σₖ cₖ·tⁿ⁻²ᵏ` for t in
        // [−1, 1]; its slope changes sign at least 1/(2n) apart (sampled on a fine grid).
        let steps = 10_000;
        for n in 2..=MAX_ORDER {
            for m in (n % 2..=n).step_by(2) {
                let c = radial_coefficients(n, m);
                let slope = |t: f64| -> f64 {
                    c.iter()
                        .enumerate()
                        .filter(|(k, _)| n > 2 * k)
                        .map(|(k, ck)| ck * (n - 2 * k) as f64 * t.powi((n - 2 * k - 1) as i32))
                        .sum()
                };
                let mut last = f64::NEG_INFINITY;
                let mut prev = slope(-1.0);
                for i in 1..=steps {
                    let t = -1.0 + 2.0 * i as f64 / steps as f64;
                    let s = slope(t);
                    if s * prev < 0.0 || (s == 0.0 && prev != 0.0) {
                        assert!(t - last >= 0.5 / n as f64, "n {n} m {m}: {last} → {t}");
                        last = t;
                    }
                    prev = s;
                }
            }
        }
    }

    #[test]
    fn coefficient_errors_name_index_and_limit() {
        let e = zernike(Convention::Fringe, vec![0.0; 38]).unwrap_err();
        assert_eq!(e.field, "coefficients_mm");
        assert!(e.allowed.starts_with("at most 37 for fringe"), "{e}");
        assert!(zernike(Convention::Fringe, vec![0.0; 37]).is_ok());
        let e = zernike(Convention::Standard, vec![0.0; 232]).unwrap_err();
        assert!(e.allowed.starts_with("at most 231 for standard"), "{e}");
        let e = zernike(Convention::Standard, vec![0.0, 0.0, f64::NAN]).unwrap_err();
        assert_eq!(e.field, "coefficients_mm[2] (Z3)");
    }
}
