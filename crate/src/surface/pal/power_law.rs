//! The meridian's power addition curve (paper 003, section 2.1, eqs 9–11):
//!
//! `D(x) = D_F + (D_N − D_F)·Σ_{i=m}^{m+l−1} cᵢ·(x + L)ⁱ` on the corridor −L ≤ x ≤ h − L,
//!
//! with the l coefficients cᵢ from the linear system `Σ cᵢ·hⁱ = 1` (eq 10, D = D_N at N) and
//! `dᵏD/dxᵏ = 0` at x = h − L for k = 1 … l − 1 (eq 11); starting the sum at i = m makes the first
//! m − 1 derivatives vanish at F (eqs 7–8). The system is solved in the normalised variable
//! t = (x + L)/h, `p(t) = Σ aᵢ·tⁱ` with `aᵢ = cᵢ·hⁱ`, where it reads `Σ aᵢ = 1` and
//! `Σ C(i, k)·aᵢ = 0` (the k-th derivative at t = 1 divided by k!), an l × l system with entries
//! C(i, k) ≤ C(15, 7) = 6435, solved by LU with partial pivoting (nalgebra) and refined with
//! residuals summed in twice the working precision, so the coefficients are correct to an ulp
//! or two although the matrix's condition number reaches 1e10 for m = l = 8.
//!
//! The paper's polynomial is only meant between F and N: continued beyond them it swings by tens
//! of dioptres over a Ø70 lens. Outside the corridor the power stays at D_F (x ≤ −L) and D_N
//! (x ≥ h − L), the stable far and near zones the paper asks for; with m, l ≥ 3 the curve is C²
//! at both joins.
//!
//! The polynomial is summed from F on the upper half of the corridor and from N on the lower
//! half ([`PowerLaw`]), where the monomial sums are well conditioned.
//!
//! Independent check (tests): the solution is the regularised incomplete beta function
//! `p(t) = I_t(m, l)`, since `p′ ∝ t^(m−1)·(1 − t)^(l−1)` is the only polynomial of degree m + l − 2
//! with those zeros, giving `a_{m+j} = (−1)ʲ·C(l−1, j) / ((m + j)·B(m, l))`.

use nalgebra::{DMatrix, DVector};

/// One polynomial `Σ cᵢ·sⁱ` with its antiderivative from 0.
#[derive(Debug, Clone, PartialEq)]
struct Expansion {
    /// `c[i]` multiplies sⁱ.
    c: Vec<f64>,
    /// `q[i] = c[i]/(i+1)` multiplies sⁱ⁺¹ in the antiderivative.
    q: Vec<f64>,
}

impl Expansion {
    /// The solution of eqs 10–11 with `flat` vanishing derivatives at s = 0 and `other` at
    /// s = 1, as the coefficients of sⁱ, i = 0 … flat + other − 1.
    fn solve(flat: usize, other: usize) -> Option<Self> {
        let normalised = solve_normalised(flat, other)?;
        let mut c = vec![0.0; flat + other];
        c[flat..].copy_from_slice(&normalised);
        let q = c
            .iter()
            .enumerate()
            .map(|(i, ci)| ci / (i as f64 + 1.0))
            .collect();
        Some(Self { c, q })
    }

    /// The value and first two derivatives at s.
    fn at(&self, s: f64) -> [f64; 3] {
        horner2(&self.c, s)
    }

    /// The k-th derivative at s.
    fn derivative(&self, s: f64, k: usize) -> f64 {
        let mut sum = 0.0;
        for (i, ci) in self.c.iter().enumerate().skip(k).rev() {
            sum = sum * s + ci * falling(i, k);
        }
        sum
    }

    /// ∫₀ˢ of the polynomial.
    fn integral(&self, s: f64) -> f64 {
        let mut sum = 0.0;
        for qi in self.q.iter().rev() {
            sum = sum * s + qi;
        }
        sum * s
    }
}

/// The solved power law of one design.
///
/// With t = (x + L)/h the normalised addition is `p(t) = Σ aᵢ·tⁱ` (the paper's form, eq 9,
/// expanded about F). Near N that monomial sum cancels badly — for m = l = 8 its terms reach
/// 6e5 while p ≤ 1, which would put 1e-11 mm of noise on the sag — so for t > ½ the same
/// polynomial is evaluated from N: `p = 1 − Σ bᵢ·τⁱ`, τ = 1 − t, where the bᵢ solve the same
/// system with m and l exchanged (eq 9 written from N; the solution is unique, so both forms
/// are one polynomial and agree to rounding at t = ½). Each form is then summed where its
/// terms decay: over the orders 3 … 8, Σ|terms| ≤ 350 at t = ½ (m = l = 8), against 6e5 at
/// t = 1.
#[derive(Debug, Clone, PartialEq)]
pub struct PowerLaw {
    far_d: f64,
    addition_d: f64,
    far_x: f64,
    corridor: f64,
    /// p about F, in t (the paper's cᵢ·hⁱ).
    from_far: Expansion,
    /// 1 − p about N, in τ = 1 − t.
    from_near: Expansion,
    /// ∫ p dt over [0, 1].
    whole: f64,
}

impl PowerLaw {
    /// Solves eqs 10–11 for far power `far_d` (D), addition `addition_d` (D), corridor length h
    /// (mm, > 0), far point F at x = −`far_point_mm`, orders m, l ≥ 1. `None` if the system is
    /// singular (it is not for m, l ≥ 1: the beta-function solution exists and is unique).
    pub fn new(
        far_d: f64,
        addition_d: f64,
        corridor_mm: f64,
        far_point_mm: f64,
        m: usize,
        l: usize,
    ) -> Option<Self> {
        let from_far = Expansion::solve(m, l)?;
        let from_near = Expansion::solve(l, m)?;
        let whole = from_far.integral(0.5) + 0.5 - from_near.integral(0.5);
        Some(Self {
            far_d,
            addition_d,
            far_x: -far_point_mm,
            corridor: corridor_mm,
            from_far,
            from_near,
            whole,
        })
    }

    /// The paper's coefficients cᵢ = aᵢ/hⁱ of (x + L)ⁱ, mm⁻ⁱ, index i = 0 … m + l − 1.
    pub fn coefficients_per_mm(&self) -> Vec<f64> {
        self.from_far
            .c
            .iter()
            .enumerate()
            .map(|(i, ai)| ai / self.corridor.powi(i as i32))
            .collect()
    }

    /// Far power D_F, D.
    pub fn far_d(&self) -> f64 {
        self.far_d
    }

    /// Near power D_N = D_F + A, D.
    pub fn near_d(&self) -> f64 {
        self.far_d + self.addition_d
    }

    /// x of the far point F, mm.
    pub fn far_x(&self) -> f64 {
        self.far_x
    }

    /// x of the near point N, mm.
    pub fn near_x(&self) -> f64 {
        self.far_x + self.corridor
    }

    /// Corridor length h, mm.
    pub fn corridor(&self) -> f64 {
        self.corridor
    }

    /// D(x), dD/dx and d²D/dx² (D, D/mm, D/mm²).
    pub fn power(&self, x: f64) -> [f64; 3] {
        let t = (x - self.far_x) / self.corridor;
        let (a, h) = (self.addition_d, self.corridor);
        if t <= 0.0 {
            [self.far_d, 0.0, 0.0]
        } else if t <= 0.5 {
            let [p, dp, ddp] = self.from_far.at(t);
            [self.far_d + a * p, a * dp / h, a * ddp / (h * h)]
        } else if t < 1.0 {
            // dτ/dx = −1/h.
            let [q, dq, ddq] = self.from_near.at(1.0 - t);
            [self.near_d() - a * q, a * dq / h, -a * ddq / (h * h)]
        } else {
            [self.near_d(), 0.0, 0.0]
        }
    }

    /// The k-th derivative of D at x, D/mmᵏ (k = 0 gives D); the one-sided polynomial value
    /// at F and N.
    pub fn derivative(&self, x: f64, k: usize) -> f64 {
        let t = (x - self.far_x) / self.corridor;
        if k == 0 {
            return self.power(x)[0];
        }
        let scale = self.addition_d / self.corridor.powi(k as i32);
        if !(0.0..=1.0).contains(&t) {
            0.0
        } else if t <= 0.5 {
            scale * self.from_far.derivative(t, k)
        } else {
            // dᵏ/dxᵏ of −q(τ) = −(−1/h)ᵏ·q⁽ᵏ⁾.
            let sign = if k.is_multiple_of(2) { -1.0 } else { 1.0 };
            sign * scale * self.from_near.derivative(1.0 - t, k)
        }
    }

    /// ∫ D dx from F to x, D·mm (exact: the antiderivative of each piece).
    pub fn integral_from_far(&self, x: f64) -> f64 {
        let dx = x - self.far_x;
        let t = dx / self.corridor;
        let (a, h) = (self.addition_d, self.corridor);
        let far = self.far_d * dx;
        if t <= 0.0 {
            far
        } else if t <= 0.5 {
            far + a * h * self.from_far.integral(t)
        } else if t < 1.0 {
            // ∫₀ᵗ p = ∫₀¹ p − ∫ₜ¹ (1 − q(1 − s)) ds = whole − (1 − t) + Q(1 − t).
            let tau = 1.0 - t;
            far + a * h * (self.whole - tau + self.from_near.integral(tau))
        } else {
            far + a * (h * self.whole + (dx - h))
        }
    }
}

/// Solves `Σ aᵢ = 1`, `Σ C(i, k)·aᵢ = 0` (k = 1 … l−1) for aᵢ, i = m … m+l−1.
fn solve_normalised(m: usize, l: usize) -> Option<Vec<f64>> {
    let matrix = DMatrix::from_fn(l, l, |k, j| binomial(m + j, k));
    let mut rhs = DVector::zeros(l);
    rhs[0] = 1.0;
    let lu = matrix.clone().lu();
    let mut solution = lu.solve(&rhs)?;
    // Iterative refinement with residuals accurate to about ε² of their terms (the matrix holds
    // exact integers, so each product splits exactly): the forward error falls by a factor
    // cond·ε ≲ 1e-7 a step, down to rounding of the coefficients themselves.
    for _ in 0..REFINEMENTS {
        let residual = DVector::from_fn(l, |k, _| {
            let row: Vec<f64> = (0..l).map(|j| matrix[(k, j)]).collect();
            accurate_residual(rhs[k], &row, solution.as_slice())
        });
        solution += lu.solve(&residual)?;
    }
    solution
        .iter()
        .all(|v| v.is_finite())
        .then(|| solution.iter().copied().collect())
}

/// Refinement steps of the solve.
const REFINEMENTS: usize = 3;

/// `b − Σ aⱼ·xⱼ` in twice the working precision (Ogita, Rump & Oishi 2005, "Accurate sum and
/// dot product", Algorithm Dot2: error-free products by FMA and sums by TwoSum).
fn accurate_residual(b: f64, a: &[f64], x: &[f64]) -> f64 {
    let (mut sum, mut err) = (b, 0.0);
    for (aj, xj) in a.iter().zip(x) {
        let p = -aj * xj;
        let p_err = (-aj).mul_add(*xj, -p);
        let s = sum + p;
        let bb = s - sum;
        let s_err = (sum - (s - bb)) + (p - bb);
        sum = s;
        err += s_err + p_err;
    }
    sum + err
}

/// C(n, k) as a float.
fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// n(n−1)…(n−k+1).
fn falling(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64)
}

/// p(t), p′(t), p″(t) for `p = Σ a[i]·tⁱ`.
fn horner2(a: &[f64], t: f64) -> [f64; 3] {
    let (mut p, mut dp, mut ddp) = (0.0, 0.0, 0.0);
    for &ai in a.iter().rev() {
        ddp = ddp * t + 2.0 * dp;
        dp = dp * t + p;
        p = p * t + ai;
    }
    [p, dp, ddp]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// a_{m+j} = (−1)ʲ·C(l−1, j)/((m+j)·B(m, l)), B(m, l) = (m−1)!(l−1)!/(m+l−1)!: the
    /// incomplete beta function written out by hand.
    fn beta_coefficients(m: usize, l: usize) -> Vec<f64> {
        let fact = |n: usize| (1..=n).fold(1.0, |acc, i| acc * i as f64);
        let beta = fact(m - 1) * fact(l - 1) / fact(m + l - 1);
        (0..l)
            .map(|j| {
                let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
                sign * binomial(l - 1, j) / ((m + j) as f64 * beta)
            })
            .collect()
    }

    #[test]
    fn the_solve_is_the_incomplete_beta_function() {
        // The refined solve is accurate to an ulp or two of the largest coefficient and the
        // closed form has at most four roundings (factorials up to 15! are exact): 1e-15 of the
        // largest coefficient (measured: 2e-16).
        for m in 1..=8 {
            for l in 1..=8 {
                let law = PowerLaw::new(1.0, 2.0, 30.0, 10.0, m, l).unwrap();
                // From F with orders (m, l), from N with (l, m).
                for (c, first, other) in [(&law.from_far.c, m, l), (&law.from_near.c, l, m)] {
                    let expect = beta_coefficients(first, other);
                    let scale = expect.iter().fold(0.0f64, |s, v| s.max(v.abs()));
                    for (j, e) in expect.iter().enumerate() {
                        let got = c[first + j];
                        assert!(
                            (got - e).abs() <= 1e-15 * scale,
                            "m {m} l {l} coefficient {}: {got} vs {e}",
                            first + j
                        );
                    }
                    assert!(c[..first].iter().all(|&v| v == 0.0));
                }
            }
        }
        // m = l = 3: the quintic smoothstep 10t³ − 15t⁴ + 6t⁵.
        let law = PowerLaw::new(0.0, 1.0, 1.0, 0.0, 3, 3).unwrap();
        for (got, e) in law.from_far.c[3..].iter().zip([10.0, -15.0, 6.0]) {
            assert!((got - e).abs() < 1e-13, "{got} vs {e}");
        }
    }

    /// The rounding bound of a sum of products: (number of terms + 20)·ε·Σ|terms| covers the
    /// summation (γ_{n−1}), each term's products and powers (≤ 17 roundings), and the residual
    /// left by the refined LU solve (≈ ε·Σ|terms|, measured).
    fn rounding(terms: &[f64]) -> f64 {
        (terms.len() as f64 + 20.0) * f64::EPSILON * terms.iter().map(|t| t.abs()).sum::<f64>()
    }

    #[test]
    fn eqs_10_and_11_hold_in_the_papers_units() {
        // Residuals of eq 10 (Σ cᵢhⁱ − 1) and eq 11 (Σ cᵢ·i!/(i−k)!·h^(i−k)) from the cᵢ in
        // mm⁻ⁱ, against the rounding bound of each sum (terms up to 6e5 for m = l = 8).
        for m in ORDERS_TESTED {
            for l in ORDERS_TESTED {
                let (h, big_l) = (12.0 + 3.0 * l as f64, 4.0 - m as f64);
                let law = PowerLaw::new(1.0, 2.0, h, big_l, m, l).unwrap();
                let c = law.coefficients_per_mm();
                let terms: Vec<f64> = c
                    .iter()
                    .enumerate()
                    .map(|(i, ci)| ci * h.powi(i as i32))
                    .collect();
                let eq10 = terms.iter().sum::<f64>() - 1.0;
                assert!(
                    eq10.abs() <= rounding(&terms),
                    "m {m} l {l}: eq 10 residual {eq10:e}"
                );
                for k in 1..l {
                    let terms: Vec<f64> = c
                        .iter()
                        .enumerate()
                        .skip(k)
                        .map(|(i, ci)| ci * falling(i, k) * h.powi((i - k) as i32))
                        .collect();
                    let sum: f64 = terms.iter().sum();
                    assert!(
                        sum.abs() <= rounding(&terms),
                        "m {m} l {l} eq 11 k {k}: {sum:e}"
                    );
                }
            }
        }
    }

    const ORDERS_TESTED: [usize; 6] = [3, 4, 5, 6, 7, 8];

    #[test]
    fn power_hits_the_far_and_near_values_and_flattens_there() {
        for m in ORDERS_TESTED {
            for l in ORDERS_TESTED {
                let law = PowerLaw::new(1.0, 2.0, 30.0, 10.0, m, l).unwrap();
                // At F and N the pieces outside the corridor answer: exact by construction.
                assert_eq!(law.power(-10.0), [1.0, 0.0, 0.0]);
                assert_eq!(law.power(20.0), [3.0, 0.0, 0.0]);
                // Just inside N the polynomial meets D_N to the rounding of Σaᵢ (p(1 − δ) =
                // 1 − O(δˡ)).
                let just_inside = law.power(20.0 - 1e-9)[0];
                let tol = 2.0 * rounding(&law.from_near.c);
                assert!(
                    (just_inside - 3.0).abs() <= tol,
                    "m {m} l {l}: {just_inside}"
                );
                // Derivatives 1 … m−1 at F vanish exactly (no terms below tᵐ); 1 … l−1 at N to
                // the rounding of their sums; the next ones do not vanish.
                for k in 1..m {
                    assert_eq!(law.derivative(-10.0, k), 0.0, "m {m} k {k}");
                }
                assert!(law.derivative(-10.0, m).abs() > 1e-3 * 2.0 / 30f64.powi(m as i32));
                // Summed from N, whose expansion has no terms below τˡ: exact zeros there too.
                for k in 1..l {
                    assert_eq!(law.derivative(20.0, k), 0.0, "l {l} k {k}");
                }
                assert!(law.derivative(20.0, l).abs() > 1e-3 * 2.0 / 30f64.powi(l as i32));
            }
        }
    }

    #[test]
    fn the_two_expansions_are_one_polynomial() {
        // p(t) from F and 1 − q(1 − t) from N, with derivatives, over the whole corridor: equal
        // to the rounding of the larger monomial sum (the one summed where it is ill
        // conditioned), which they must be since eqs 10–11 have one solution.
        for (m, l) in [(3, 3), (3, 7), (8, 4), (8, 8)] {
            let law = PowerLaw::new(0.0, 1.0, 1.0, 0.0, m, l).unwrap();
            for i in 0..=20 {
                let t = i as f64 / 20.0;
                let far = law.from_far.at(t);
                let near = law.from_near.at(1.0 - t);
                let from_near = [1.0 - near[0], near[1], -near[2]];
                let terms = |c: &[f64], s: f64, k: usize| -> Vec<f64> {
                    c.iter()
                        .enumerate()
                        .skip(k)
                        .map(|(i, ci)| ci * falling(i, k) * s.powi((i - k) as i32))
                        .collect()
                };
                for k in 0..3 {
                    let tol = rounding(&terms(&law.from_far.c, t, k))
                        + rounding(&terms(&law.from_near.c, 1.0 - t, k));
                    assert!(
                        (far[k] - from_near[k]).abs() <= tol,
                        "m {m} l {l} t {t} k {k}: {} vs {}",
                        far[k],
                        from_near[k]
                    );
                }
            }
            // The ∫₀¹ p of the beta function: 1 − E[Beta(m, l)] = l/(m + l).
            let whole = l as f64 / (m + l) as f64;
            assert!(
                (law.whole - whole).abs() < 1e-13,
                "{} vs {whole}",
                law.whole
            );
        }
    }

    #[test]
    fn derivatives_and_integral_match_differences_and_quadrature() {
        let law = PowerLaw::new(-2.0, 2.5, 24.0, 6.0, 3, 4).unwrap();
        let h = 1e-4;
        for x in [-5.9, -3.0, 0.0, 7.5, 17.9] {
            let [d, d1, d2] = law.power(x);
            let fd1 = (law.power(x + h)[0] - law.power(x - h)[0]) / (2.0 * h);
            let fd2 = (law.power(x + h)[1] - law.power(x - h)[1]) / (2.0 * h);
            assert!((d1 - fd1).abs() < 1e-9, "{x}: {d1} vs {fd1}");
            assert!((d2 - fd2).abs() < 1e-9, "{x}: {d2} vs {fd2}");
            assert_eq!(law.derivative(x, 0), d);
            assert!((law.derivative(x, 1) - d1).abs() < 1e-15);
            assert!((law.derivative(x, 2) - d2).abs() < 1e-15);
        }
        // ∫ from F by the midpoint rule with 2e5 steps (error ≲ (b−a)·Δ²/24·|D″| ≈ 1e-11).
        for x in [-20.0, -6.0, 1.0, 18.0, 40.0] {
            let (a, n) = (-6.0, 200_000);
            let step = (x - a) / n as f64;
            let mid: f64 = (0..n)
                .map(|i| law.power(a + (i as f64 + 0.5) * step)[0] * step)
                .sum();
            let exact = law.integral_from_far(x);
            assert!((exact - mid).abs() < 1e-8, "{x}: {exact} vs {mid}");
        }
    }
}
