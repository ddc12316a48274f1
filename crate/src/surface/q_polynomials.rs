//! Forbes' Q polynomials in x = u² (u the normalised radius), with their first two derivatives
//! in x, by the three-term recurrences of Forbes' papers (never expanded into powers of x):
//!
//! - **Qbfs** (G. W. Forbes, "Shape specification for axially symmetric optical surfaces", Opt.
//!   Express 15, 5218, 2007): `u²(1 − u²)·Qₙ(u²)` orthonormal in slope, `(2/π)∫₀¹ f′g′ du/√(1 − u²)
//!   = δ`. Sums are evaluated as Forbes 2010 does ("Robust, efficient computational methods for
//!   axially symmetric optical aspheres", Opt. Express 18, 19700, eqs 2.6 and A.14–A.16, and the
//!   change of basis of its section 3): the coefficients aₙ are turned once into coefficients bₙ
//!   of the auxiliary polynomials `P₀ = 2`, `P₁ = 6 − 8x`, `Pₙ₊₁ = (2 − 4x)·Pₙ − Pₙ₋₁` (shifted
//!   Chebyshev polynomials of the third kind), `b_M = a_M/f_M`, `b_{M−1} = (a_{M−1} −
//!   g_{M−1}b_M)/f_{M−1}`, `bₙ = (aₙ − gₙbₙ₊₁ − hₙbₙ₊₂)/fₙ`, with `f₀ = 2`, `g₀ = −1/2`, `f₁ =
//!   √19/2`, `hₙ₋₂ = −n(n − 1)/(2fₙ₋₂)`, `gₙ₋₁ = −(1 + gₙ₋₂hₙ₋₂)/fₙ₋₁`, `fₙ = √(n(n + 1) + 3 −
//!   gₙ₋₁² − hₙ₋₂²)`; then `Σ aₙQₙ = Σ bₙPₙ` by the recurrence, differentiated term by term.
//! - **Qcon** (the same 2007 paper): `Qₙ(x) = Pₙ^(0,4)(2x − 1)`, the Jacobi polynomials
//!   orthogonal under the weight x⁴ on [0, 1] with `Qₙ(1) = 1`, by the Jacobi recurrence
//!   (Abramowitz & Stegun 22.7.1 with α = 0, β = 4): `2(n + 1)(n + 5)(2n + 4)·Pₙ₊₁ = (2n + 5)·[(2n +
//!   6)(2n + 4)·t − 16]·Pₙ − 2n(n + 4)(2n + 6)·Pₙ₋₁`, t = 2x − 1.
//! - **Q₂D** for m ≥ 1 (G. W. Forbes, "Characterizing the shape of freeform optics", Opt.
//!   Express 20, 2483, 2012, appendix A): `u^m·cos(mθ)·Qₙᵐ(u²)` orthonormal in gradient under
//!   the mean over θ of the same weighted radial integral. Auxiliary polynomials `P₀ᵐ = 1/2`,
//!   `P₁ᵐ = (m − 1/2) + (1 − m)x` (m ≥ 2), for m = 1 `P₁ = 1 − x/2`, `P₂ = (3 − 12x + 8x²)/6`,
//!   `P₃ = (5 − 60x + 120x² − 64x³)/10`, and beyond `Pₙ₊₁ = (Aₙ + Bₙx)·Pₙ − Cₙ·Pₙ₋₁` (eq A.3);
//!   `Q₀ = P₀/f₀`, `Qₙ = (Pₙ − gₙ₋₁Qₙ₋₁)/fₙ` with `f₀ = √F₀`, `fₙ = √(Fₙ − gₙ₋₁²)`, `gₙ = Gₙ/fₙ`
//!   from the closed forms Fₙᵐ (A.13), Gₙᵐ (A.15) and their factor γₙᵐ; sums by the change of
//!   basis `d_N = c_N/f_N`, `dₙ = (cₙ − gₙdₙ₊₁)/fₙ`, `Σ cₙQₙ = Σ dₙPₙ` (appendix B). The
//!   constants as G. Brandon Dube's prysm (`prysm/polynomials/qpoly.py`) transcribes them.
//!
//! The values are checked in `tests/tests/surface_forbes.rs` against an independent
//! construction from the definitions alone (exact Gram–Schmidt in rational arithmetic,
//! `tests/bench/qpoly_reference.py`, which also agrees with prysm to 4e-15) for n ≤ 6 and m ≤ 4,
//! and for orthonormality by exact quadrature to higher orders.

use crate::field::{FieldError, finite};

/// The highest order n of a term (each family), and the highest azimuthal order m of Q₂D.
pub const MAX_ORDER: usize = 30;

/// Checks the coefficients a₀, a₁, … of a Q sum given at `field`: at most [`MAX_ORDER`] + 1,
/// each finite; errors name the index (`coefficients_mm[3] (a3)`).
pub(crate) fn check_coefficients(field: &str, a: &[f64]) -> Result<(), FieldError> {
    if a.len() > MAX_ORDER + 1 {
        return Err(FieldError::new(
            field,
            format!("{} terms", a.len()),
            format!("at most {} terms (a0 … a{MAX_ORDER})", MAX_ORDER + 1),
        ));
    }
    for (n, &c) in a.iter().enumerate() {
        finite(&format!("{field}[{n}] (a{n})"), c)?;
    }
    Ok(())
}

/// The non-zero coefficients for a description: `a0 1e-3, a2 -4e-4`.
pub(crate) fn describe_coefficients(a: &[f64]) -> String {
    let terms: Vec<String> = a
        .iter()
        .enumerate()
        .filter(|(_, c)| **c != 0.0)
        .map(|(n, c)| format!("a{n} {c:e}"))
        .collect();
    terms.join(", ")
}

/// The feature length of a term of degree d in x = u² over a normalisation radius N:
/// `1.5·N/d²`. The slope of a term `u²(1 − u²)Qbfsₙ(u²)`, `u⁴Qconₙ(u²)` or `u^m·Qₙᵐ(u²)` (degree
/// n + 2, n + 2 or n + m/2 in x) changes sign, along a section through the axis, no closer
/// than that (its zeros crowd towards u = 1 like those of a Chebyshev polynomial, about
/// 2.5/d² apart at n = 30; the unit test checks the bound for every n ≤ 30, m ≤ 30).
pub fn feature_length(norm: f64, degree_in_x: f64) -> f64 {
    1.5 * norm / (degree_in_x * degree_in_x)
}

/// [`feature_length`] of a rotationally symmetric sum (Qbfs or Qcon) with coefficients `a`:
/// its highest order n present has degree n + 2 in u²; no terms, no feature.
pub fn rotational_feature_length(norm: f64, a: &[f64]) -> f64 {
    match a.iter().rposition(|&c| c != 0.0) {
        Some(n) => feature_length(norm, n as f64 + 2.0),
        None => f64::INFINITY,
    }
}

/// A value with its first and second derivatives in x: `[p, dp/dx, d²p/dx²]`.
pub type Jet1 = [f64; 3];

/// The jet of `x(1 − x)·S(x)` (Qbfs's envelope `u²(1 − u²)` times a sum) from S's jet at x.
pub fn envelope(x: f64, [p, p1, p2]: Jet1) -> Jet1 {
    let env = x * (1.0 - x);
    [
        env * p,
        (1.0 - 2.0 * x) * p + env * p1,
        -2.0 * p + 2.0 * (1.0 - 2.0 * x) * p1 + env * p2,
    ]
}

/// A family of polynomials pₙ(x): the first few given by their monomial coefficients, the rest
/// by `pₙ = (αₙ + βₙ·x)·pₙ₋₁ − γₙ·pₙ₋₂`.
#[derive(Debug, Clone, PartialEq)]
struct Recurrence {
    /// Monomial coefficients of p₀, p₁, …
    seeds: Vec<Vec<f64>>,
    /// (αₙ, βₙ, γₙ) for n = seeds.len(), seeds.len() + 1, …
    steps: Vec<(f64, f64, f64)>,
}

/// A polynomial given by its monomial coefficients, with two derivatives at x.
fn monomials(c: &[f64], x: f64) -> Jet1 {
    let (mut p, mut d1, mut d2) = (0.0, 0.0, 0.0);
    for &a in c.iter().rev() {
        d2 = d2 * x + 2.0 * d1;
        d1 = d1 * x + p;
        p = p * x + a;
    }
    [p, d1, d2]
}

impl Recurrence {
    /// `Σ dₙ·pₙ(x)` with its derivatives, n = 0 … d.len() − 1.
    fn sum(&self, d: &[f64], x: f64) -> Jet1 {
        let mut total = [0.0; 3];
        let (mut prev, mut cur) = ([0.0; 3], [0.0; 3]);
        for (n, &dn) in d.iter().enumerate() {
            let next = match self.seeds.get(n) {
                Some(c) => monomials(c, x),
                None => {
                    let (a, b, g) = self.steps[n - self.seeds.len()];
                    let lin = a + b * x;
                    [
                        lin * cur[0] - g * prev[0],
                        b * cur[0] + lin * cur[1] - g * prev[1],
                        2.0 * b * cur[1] + lin * cur[2] - g * prev[2],
                    ]
                }
            };
            prev = cur;
            cur = next;
            for k in 0..3 {
                total[k] += dn * cur[k];
            }
        }
        total
    }
}

/// A sum `Σ aₙ·Qₙ(x)` of one of the Q families, ready to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct QSum {
    recurrence: Recurrence,
    /// The coefficients in the auxiliary basis.
    d: Vec<f64>,
}

impl QSum {
    /// `[S, S′, S″]` at x = u².
    pub fn eval(&self, x: f64) -> Jet1 {
        self.recurrence.sum(&self.d, x)
    }

    /// Whether every coefficient is zero.
    pub fn is_zero(&self) -> bool {
        self.d.iter().all(|&d| d == 0.0)
    }

    /// The degree of the sum in x (at most that of its last term; 0 for none).
    pub fn degree(&self) -> usize {
        self.d.len().saturating_sub(1)
    }

    /// `Σ aₙ·Qbfsₙ(x)` for a = `a` (at most [`MAX_ORDER`] + 1 terms).
    pub fn qbfs(a: &[f64]) -> Self {
        let (f, g, h) = qbfs_constants(a.len());
        let mut b = vec![0.0; a.len()];
        for n in (0..a.len()).rev() {
            let next = b.get(n + 1).copied().unwrap_or(0.0);
            let after = b.get(n + 2).copied().unwrap_or(0.0);
            b[n] = (a[n] - g[n] * next - h[n] * after) / f[n];
        }
        Self {
            recurrence: Recurrence {
                seeds: vec![vec![2.0], vec![6.0, -8.0]],
                steps: vec![(2.0, -4.0, 1.0); a.len().saturating_sub(2)],
            },
            d: b,
        }
    }

    /// `Σ aₙ·Qconₙ(x)`.
    pub fn qcon(a: &[f64]) -> Self {
        // P_{n+1} = (A_n t + B_n) P_n − C_n P_{n−1}, t = 2x − 1: α = B_n − A_n, β = 2A_n.
        let steps = (0..a.len().saturating_sub(1))
            .map(|n| {
                let n = n as f64;
                let den = (n + 1.0) * (n + 5.0) * (n + 2.0);
                let big_a = (2.0 * n + 5.0) * (n + 3.0) / ((n + 1.0) * (n + 5.0));
                let big_b = -4.0 * (2.0 * n + 5.0) / den;
                let big_c = n * (n + 4.0) * (n + 3.0) / den;
                (big_b - big_a, 2.0 * big_a, big_c)
            })
            .collect();
        Self {
            recurrence: Recurrence {
                seeds: vec![vec![1.0]],
                steps,
            },
            d: a.to_vec(),
        }
    }

    /// `Σ cₙ·Qₙᵐ(x)` of the freeform set for azimuthal order 1 ≤ m ≤ [`MAX_ORDER`].
    pub fn q2d(m: usize, c: &[f64]) -> Self {
        let (f, g) = q2d_constants(m, c.len());
        let mut d = vec![0.0; c.len()];
        for n in (0..c.len()).rev() {
            let next = d.get(n + 1).copied().unwrap_or(0.0);
            d[n] = (c[n] - g[n] * next) / f[n];
        }
        let mf = m as f64;
        let seeds = if m == 1 {
            vec![
                vec![0.5],
                vec![1.0, -0.5],
                vec![0.5, -2.0, 4.0 / 3.0],
                vec![0.5, -6.0, 12.0, -6.4],
            ]
        } else {
            vec![vec![0.5], vec![mf - 0.5, 1.0 - mf]]
        };
        let steps = (seeds.len()..c.len().max(seeds.len()))
            .map(|n| q2d_abc(n - 1, m))
            .collect();
        Self {
            recurrence: Recurrence { seeds, steps },
            d,
        }
    }
}

/// Qbfsₙ(x) alone with its derivatives.
pub fn qbfs(n: usize, x: f64) -> Jet1 {
    QSum::qbfs(&unit(n)).eval(x)
}

/// Qconₙ(x) alone with its derivatives.
pub fn qcon(n: usize, x: f64) -> Jet1 {
    QSum::qcon(&unit(n)).eval(x)
}

/// Qₙᵐ(x) of the freeform set (m ≥ 1) alone with its derivatives; m = 0 is [`qbfs`].
pub fn q2d(m: usize, n: usize, x: f64) -> Jet1 {
    if m == 0 {
        qbfs(n, x)
    } else {
        QSum::q2d(m, &unit(n)).eval(x)
    }
}

fn unit(n: usize) -> Vec<f64> {
    let mut a = vec![0.0; n + 1];
    a[n] = 1.0;
    a
}

/// Forbes 2010's fₙ, gₙ, hₙ for n < len (A.14–A.16): `f₀ = 2`, `g₀ = −1/2`, and for k ≥ 1
/// `fₖ = √(k(k + 1) + 3 − gₖ₋₁² − hₖ₋₂²)` (h₋₁ = 0, so f₁ = √19/2), `gₖ = −(1 + gₖ₋₁hₖ₋₁)/fₖ`;
/// `hₖ = −(k + 2)(k + 1)/(2fₖ)`.
fn qbfs_constants(len: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let len = len.max(1);
    let (mut f, mut g, mut h) = (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
    for k in 0..len {
        let kf = k as f64;
        if k == 0 {
            f[0] = 2.0;
            g[0] = -0.5;
        } else {
            let h2 = if k >= 2 { h[k - 2] } else { 0.0 };
            f[k] = (kf * (kf + 1.0) + 3.0 - g[k - 1] * g[k - 1] - h2 * h2).sqrt();
            g[k] = -(1.0 + g[k - 1] * h[k - 1]) / f[k];
        }
        h[k] = -(kf + 2.0) * (kf + 1.0) / (2.0 * f[k]);
    }
    (f, g, h)
}

/// γₙᵐ of Forbes 2012 (the factor of A.13 and A.15), m ≥ 2, n ≥ 1.
fn q2d_gamma(n: usize, m: usize) -> f64 {
    let (nf, mf) = (n as f64, m as f64);
    if n == 1 {
        // γ₁² = 3/8, γ₁ᵐ = (2m − 1)/(2(m − 2))·γ₁ᵐ⁻¹.
        (3..=m).fold(0.375, |g, k| {
            let k = k as f64;
            g * (2.0 * k - 1.0) / (2.0 * (k - 2.0))
        })
    } else {
        nf * (2.0 * mf + 2.0 * nf - 3.0) / ((mf + nf - 3.0) * (2.0 * nf - 1.0))
            * q2d_gamma(n - 1, m)
    }
}

/// `(2m − 3)!! / (2^(m+1)·(m − 1)!)` for m ≥ 1 ((−1)!! = 1), by the ratio of successive m.
fn q2d_r(m: usize) -> f64 {
    (2..=m).fold(0.25, |r, k| {
        let k = k as f64;
        r * (2.0 * k - 3.0) / (2.0 * (k - 1.0))
    })
}

/// Fₙᵐ (A.13).
fn q2d_big_f(n: usize, m: usize) -> f64 {
    let (nf, mf) = (n as f64, m as f64);
    match (n, m) {
        (0, _) => mf * mf * q2d_r(m),
        (_, 1) => {
            let extra = if n == 1 { 11.0 / 32.0 } else { 0.0 };
            (4.0 * (nf - 1.0).powi(2) * nf * nf + 1.0) / (8.0 * (2.0 * nf - 1.0).powi(2)) + extra
        }
        _ => {
            let chi = mf + nf - 2.0;
            let num = 2.0 * nf * chi * (3.0 - 5.0 * mf + 4.0 * nf * chi)
                + mf * mf * (3.0 - mf + 4.0 * nf * chi);
            let den = (mf + 2.0 * nf - 3.0)
                * (mf + 2.0 * nf - 2.0)
                * (mf + 2.0 * nf - 1.0)
                * (2.0 * nf - 1.0);
            num / den * q2d_gamma(n, m)
        }
    }
}

/// Gₙᵐ (A.15).
fn q2d_big_g(n: usize, m: usize) -> f64 {
    let (nf, mf) = (n as f64, m as f64);
    match (n, m) {
        (0, _) => (2.0 * mf - 1.0) * q2d_r(m),
        (_, 1) => {
            let extra = if n == 1 { 1.0 / 24.0 } else { 0.0 };
            -(2.0 * nf * nf - 1.0) * (nf * nf - 1.0) / (8.0 * (4.0 * nf * nf - 1.0)) - extra
        }
        _ => {
            let num = (2.0 * nf * (mf + nf - 1.0) - mf) * (nf + 1.0) * (2.0 * mf + 2.0 * nf - 1.0);
            let den =
                (mf + 2.0 * nf - 2.0) * (mf + 2.0 * nf - 1.0) * (mf + 2.0 * nf) * (2.0 * nf + 1.0);
            -num / den * q2d_gamma(n, m)
        }
    }
}

/// fₙᵐ and gₙᵐ for n < len.
fn q2d_constants(m: usize, len: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut f, mut g): (Vec<f64>, Vec<f64>) = (Vec::with_capacity(len), Vec::with_capacity(len));
    for n in 0..len.max(1) {
        let fn_ = if n == 0 {
            q2d_big_f(0, m).sqrt()
        } else {
            (q2d_big_f(n, m) - g[n - 1] * g[n - 1]).sqrt()
        };
        f.push(fn_);
        g.push(q2d_big_g(n, m) / fn_);
    }
    (f, g)
}

/// (αₙ, βₙ, γₙ) of `Pₙ₊₁ = (Aₙ + Bₙx)·Pₙ − Cₙ·Pₙ₋₁` (A.3).
fn q2d_abc(n: usize, m: usize) -> (f64, f64, f64) {
    let (nf, mf) = (n as f64, m as f64);
    let d = (4.0 * nf * nf - 1.0) * (mf + nf - 2.0) * (mf + 2.0 * nf - 3.0);
    let a = (2.0 * nf - 1.0)
        * (mf + 2.0 * nf - 2.0)
        * (4.0 * nf * (mf + nf - 2.0) + (mf - 3.0) * (2.0 * mf - 1.0))
        / d;
    let b = -2.0
        * (2.0 * nf - 1.0)
        * (mf + 2.0 * nf - 3.0)
        * (mf + 2.0 * nf - 2.0)
        * (mf + 2.0 * nf - 1.0)
        / d;
    let c = nf * (2.0 * nf - 3.0) * (mf + 2.0 * nf - 1.0) * (2.0 * mf + 2.0 * nf - 3.0) / d;
    (a, b, c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_terms_are_the_papers_closed_forms() {
        for &x in &[0.0, 0.3, 0.77, 1.0, 1.1] {
            let close = |a: f64, b: f64| (a - b).abs() < 1e-13 * (1.0 + b.abs());
            assert!(close(qbfs(0, x)[0], 1.0));
            assert!(close(qbfs(1, x)[0], (13.0 - 16.0 * x) / 19f64.sqrt()));
            assert!(close(qbfs(1, x)[1], -16.0 / 19f64.sqrt()));
            assert!(close(qcon(1, x)[0], -(5.0 - 6.0 * x)));
            assert!(close(qcon(2, x)[0], 15.0 - 14.0 * x * (3.0 - 2.0 * x)));
            assert!(close(q2d(1, 0, x)[0], 1.0));
            assert!(close(q2d(2, 0, x)[0], 0.5f64.sqrt()));
        }
    }

    #[test]
    fn sums_are_sums_of_terms() {
        let a = [0.3, -0.2, 0.1, 0.05, -0.02];
        for (sum, term) in [
            (QSum::qbfs(&a), qbfs as fn(usize, f64) -> Jet1),
            (QSum::qcon(&a), qcon),
        ] {
            for &x in &[0.1, 0.6, 1.0] {
                for (k, s) in sum.eval(x).iter().enumerate() {
                    let direct: f64 = a.iter().enumerate().map(|(n, c)| c * term(n, x)[k]).sum();
                    assert!((s - direct).abs() < 1e-12, "{k} {x}");
                }
            }
        }
        for m in 1..5 {
            let s = QSum::q2d(m, &a).eval(0.45);
            let direct: f64 = a
                .iter()
                .enumerate()
                .map(|(n, c)| c * q2d(m, n, 0.45)[0])
                .sum();
            assert!((s[0] - direct).abs() < 1e-12, "m {m}");
        }
    }
}
