//! Bivariate polynomials `P(u, v) = Σ aᵢⱼ·uⁱ·vʲ` of total degree ≤ 20 in normalised coordinates
//! u = x/N, v = y/N, evaluated with their first and second derivatives from power tables
//! (`[tⁿ, n·tⁿ⁻¹, n(n−1)·tⁿ⁻²]`), exact at the origin where polar forms are singular. Shared by
//! the XY polynomial and the Zernike families (a Zernike sum is converted into one such
//! polynomial once).

use super::Local;

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
