//! Bivariate polynomials `P(u, v) = Σ aᵢⱼ·uⁱ·vʲ` of total degree ≤ 20 in normalised coordinates
//! u = x/N, v = y/N, evaluated with their first and second derivatives from power tables
//! (`[tⁿ, n·tⁿ⁻¹, n(n−1)·tⁿ⁻²]`), exact at the origin where polar forms are singular. Shared by
//! the XY polynomial and the Zernike families (a Zernike sum is converted into one such
//! polynomial once).

use super::{Local, SectionBounds, Surface};

/// The highest total degree.
pub const MAX_DEGREE: usize = 20;

/// Dense coefficients `a[i][j]` of uⁱvʲ.
pub type Dense = [[f64; MAX_DEGREE + 1]; MAX_DEGREE + 1];

/// A polynomial kept as its non-zero terms.
#[derive(Debug, Clone, PartialEq)]
pub struct Bivariate {
    /// (i, j, aᵢⱼ).
    terms: Vec<(usize, usize, f64)>,
    degree: usize,
}

impl Bivariate {
    /// From (i, j, aᵢⱼ) terms with i + j ≤ [`MAX_DEGREE`] (checked by the caller).
    pub fn new(terms: Vec<(usize, usize, f64)>) -> Self {
        let degree = terms.iter().map(|&(i, j, _)| i + j).max().unwrap_or(0);
        Self { terms, degree }
    }

    /// From dense coefficients, keeping the non-zero ones.
    pub fn from_dense(a: &Dense) -> Self {
        let mut terms = Vec::new();
        for (i, row) in a.iter().enumerate() {
            for (j, &c) in row.iter().enumerate() {
                if c != 0.0 {
                    terms.push((i, j, c));
                }
            }
        }
        Self::new(terms)
    }

    /// The total degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The non-zero terms (i, j, aᵢⱼ), as given.
    pub fn terms(&self) -> &[(usize, usize, f64)] {
        &self.terms
    }

    /// Bounds on the radial sections `t ↦ P(t·cos θ/N, t·sin θ/N)` over |t| ≤ `radius` mm and
    /// every θ, N = `norm`: (largest |d/dt|, largest |d²/dt²|). Term by term,
    /// `aᵢⱼ·cosⁱθ·sinʲθ·(t/N)ⁿ` (n = i + j) has |d/dt| ≤ |aᵢⱼ|·mᵢⱼ·n·(R/N)ⁿ⁻¹/N and
    /// |d²/dt²| ≤ |aᵢⱼ|·mᵢⱼ·n(n−1)·(R/N)ⁿ⁻²/N², with `mᵢⱼ = max|cosⁱθ·sinʲθ| = √(iⁱ·jʲ/nⁿ)`
    /// (at tan²θ = j/i). Loose where terms of one degree cancel (a Zernike polynomial's
    /// monomials): the bound then fails the concavity test and the arc is searched in full.
    pub fn section_bounds(&self, radius: f64, norm: f64) -> (f64, f64) {
        let ratio = radius.abs() / norm;
        let (mut slope, mut curvature) = (0.0, 0.0);
        for &(i, j, a) in &self.terms {
            let n = i + j;
            if n == 0 {
                continue;
            }
            let (fi, fj, fn_) = (i as f64, j as f64, n as f64);
            let m = (fi.powi(i as i32) * fj.powi(j as i32) / fn_.powi(n as i32)).sqrt();
            let scaled = a.abs() * m * fn_ / norm;
            slope += scaled * ratio.powi(n as i32 - 1);
            if n >= 2 {
                curvature += scaled * (fn_ - 1.0) * ratio.powi(n as i32 - 2) / norm;
            }
        }
        (slope, curvature)
    }

    /// The [`SectionBounds`] of `base` + P(x/N, y/N) over the disc of `radius` mm: the base's
    /// plus [`Bivariate::section_bounds`] ([`SectionBounds::plus`]); `None` where the base gives
    /// none.
    pub fn section_bounds_on(
        &self,
        base: &dyn Surface,
        radius: f64,
        norm: f64,
    ) -> Option<SectionBounds> {
        let (slope, curvature) = self.section_bounds(radius, norm);
        base.section_bounds(radius)?.plus(slope, curvature)
    }

    /// `[P, P_u, P_v, P_uu, P_uv, P_vv]` at (u, v).
    pub fn eval(&self, u: f64, v: f64) -> [f64; 6] {
        let (pu, pv) = (powers(u, self.degree), powers(v, self.degree));
        let mut out = [0.0; 6];
        for &(i, j, c) in &self.terms {
            let ([u0, u1, u2], [v0, v1, v2]) = (pu[i], pv[j]);
            out[0] += c * u0 * v0;
            out[1] += c * u1 * v0;
            out[2] += c * u0 * v1;
            out[3] += c * u2 * v0;
            out[4] += c * u1 * v1;
            out[5] += c * u0 * v2;
        }
        out
    }

    /// Adds `P(x/N, y/N)` and its x, y derivatives to `l`.
    pub fn add_to(&self, l: &mut Local, x: f64, y: f64, norm: f64) {
        let [p, pu, pv, puu, puv, pvv] = self.eval(x / norm, y / norm);
        let n2 = norm * norm;
        l.z += p;
        l.zx += pu / norm;
        l.zy += pv / norm;
        l.zxx += puu / n2;
        l.zxy += puv / n2;
        l.zyy += pvv / n2;
    }
}

/// `[tⁿ, n·tⁿ⁻¹, n(n−1)·tⁿ⁻²]` for n = 0 … `degree` (the rest zero).
fn powers(t: f64, degree: usize) -> [[f64; 3]; MAX_DEGREE + 1] {
    let mut p = [[0.0; 3]; MAX_DEGREE + 1];
    p[0][0] = 1.0;
    for n in 1..=degree.min(MAX_DEGREE) {
        let nf = n as f64;
        p[n][0] = p[n - 1][0] * t;
        p[n][1] = nf * p[n - 1][0];
        p[n][2] = nf * p[n - 1][1];
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest |d/dt| and |d²/dt²| of `t ↦ P(t·cos θ/N, t·sin θ/N)` over 720 angles and
    /// |t| ≤ R, sampled.
    fn sampled(p: &Bivariate, radius: f64, norm: f64) -> (f64, f64) {
        let (mut d1, mut d2) = (0.0f64, 0.0f64);
        for k in 0..720 {
            let (s, c) = (std::f64::consts::TAU * k as f64 / 720.0).sin_cos();
            for i in 0..=2000 {
                let t = radius * (i as f64 / 1000.0 - 1.0);
                let [_, pu, pv, puu, puv, pvv] = p.eval(t * c / norm, t * s / norm);
                d1 = d1.max(((pu * c + pv * s) / norm).abs());
                d2 =
                    d2.max(((puu * c * c + 2.0 * puv * c * s + pvv * s * s) / (norm * norm)).abs());
            }
        }
        (d1, d2)
    }

    #[test]
    fn section_bounds_cover_dense_sections_and_one_term_reaches_them() {
        let (radius, norm) = (4.0, 3.0);
        let mixed = Bivariate::new(vec![
            (2, 1, 3e-3),
            (0, 4, -2e-3),
            (1, 0, 1e-3),
            (5, 3, 4e-4),
            (0, 10, -1e-4),
            (6, 0, 2e-4),
            (0, 0, 7.0),
        ]);
        let (slope, curvature) = mixed.section_bounds(radius, norm);
        let (d1, d2) = sampled(&mixed, radius, norm);
        assert!(
            d1 <= slope && d2 <= curvature,
            "{d1} {slope} {d2} {curvature}"
        );
        // A single term's bound is its maximum, at tan²θ = j/i and |t| = R.
        let single = Bivariate::new(vec![(2, 1, -3e-3)]);
        let (slope, curvature) = single.section_bounds(radius, norm);
        let (d1, d2) = sampled(&single, radius, norm);
        assert!(d1 <= slope && d1 > 0.9999 * slope, "{d1} {slope}");
        assert!(
            d2 <= curvature && d2 > 0.9999 * curvature,
            "{d2} {curvature}"
        );
    }

    #[test]
    fn evaluates_a_hand_written_polynomial_and_its_derivatives() {
        // P = 3u²v − 2v⁴ + u: P_u = 6uv + 1, P_v = 3u² − 8v³, P_uu = 6v, P_uv = 6u, P_vv = −24v².
        let p = Bivariate::new(vec![(2, 1, 3.0), (0, 4, -2.0), (1, 0, 1.0)]);
        let (u, v) = (0.3, -0.7);
        let e = p.eval(u, v);
        let want = [
            3.0 * u * u * v - 2.0 * v.powi(4) + u,
            6.0 * u * v + 1.0,
            3.0 * u * u - 8.0 * v.powi(3),
            6.0 * v,
            6.0 * u,
            -24.0 * v * v,
        ];
        for k in 0..6 {
            assert!(
                (e[k] - want[k]).abs() < 1e-15,
                "{k}: {} vs {}",
                e[k],
                want[k]
            );
        }
        assert_eq!(p.degree(), 4);
    }
}
