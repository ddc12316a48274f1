//! The radial basis function interpolant of paper 004 (Nie et al., "RBF Interpolation
//! Algorithm for FTS Tool Path Generation", 2021), section 2: the kernel of eq 4,
//! `φ(r) = −r³ + 4r² + c` with `r = |Δx| + |Δy|`, solved over the n neighbours of the query
//! point (eq 5) and evaluated as `f(p) = Σ aⱼ φ(|p − pⱼ|)` (eq 6).
//!
//! **Units of r.** The paper does not say. With r in mm and neighbours 0.04 mm apart,
//! `−r³ + 4r²` is ~1e-2 against c and the system is nearly the rank-one matrix c·11ᵀ. Here
//! `ρ = r / s` with `s = rbf_scale × h`, h the data spacing (median nearest-neighbour distance):
//! with the default scale 1 the neighbours of a grid sit at ρ = 1, 2, 3 (φ = 3, 8, 9 + c), inside
//! the kernel's positive range ρ < 4 (it vanishes at 4 — the paper's "compact support").
//!
//! **Polynomial.** Eq 6 alone reproduces no polynomial, not even a constant: on the paper's
//! lens array (sag −44 µm) the mean error stays near 0.5 µm at every spacing, and on a smooth
//! surface it does not converge (docs/rbf-table2.md). Adding `c` to φ adds `c·Σaⱼ` to f; as
//! c → ∞ the solution tends to the interpolant with a constant term λ and the side condition
//! `Σaⱼ = 0` (then c drops out altogether). The `polynomial` option makes that explicit:
//! `none` is eqs 5–6 as printed (c matters), `constant` adds λ (the c → ∞ limit), `linear`
//! (the default) adds `λ₀ + λ₁·(x − x̄)/s + λ₂·(y − ȳ)/s` with `Σaⱼ = Σaⱼ(xⱼ − x̄) = Σaⱼ(yⱼ − ȳ)
//! = 0` (x̄, ȳ the neighbours' centroid), the usual augmentation of RBF interpolation
//! (Fasshauer, *Meshfree Approximation Methods with MATLAB*, 2007, ch. 6), which reproduces
//! planes exactly and gives second-order convergence.
//!
//! **Smoothness.** Off the lines x = xⱼ and y = yⱼ each term is a cubic polynomial in
//! (x, y), so f is a cubic polynomial on each cell of those lines (and, since
//! `∂²φ(|Δx|+|Δy|)/∂x² = ∂²/∂y² = φ″`, has f_xx = f_yy there). Across x = xⱼ (y ≠ yⱼ) the term
//! `φ(|x − xⱼ| + |y − yⱼ|)` has a corner: ∂f/∂x jumps by `2·aⱼ·φ′(|y − yⱼ|/s)/s`, which is
//! zero only at the data point itself (φ′(0) = 0). So the gradient is continuous at the data
//! points but not along the axis lines through them; those are slope kinks of every section
//! that crosses them (reported by `slope_kinks`). At a kink [`LocalRbf::local`] gives the
//! derivatives of the side towards +x (+y).

use super::line_section::Cubic;
use crate::surface::{Line, Local};
use nalgebra::{DMatrix, SMatrix, SVector};
use serde::{Deserialize, Serialize};

use super::neighbours::MAX_NEIGHBOURS;

/// The polynomial added to the RBF sum of eq 6.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Polynomial {
    /// Eq 6 as printed: `f = Σ aⱼ φ(rⱼ)`.
    None,
    /// A constant λ with `Σ aⱼ = 0`: the limit c → ∞ of eq 4.
    Constant,
    /// A plane with `Σ aⱼ = Σ aⱼ xⱼ = Σ aⱼ yⱼ = 0`: reproduces planes exactly.
    #[default]
    Linear,
}

impl Polynomial {
    /// Number of polynomial terms.
    pub fn terms(self) -> usize {
        match self {
            Polynomial::None => 0,
            Polynomial::Constant => 1,
            Polynomial::Linear => 3,
        }
    }
}

/// How r is measured between two points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Distance {
    /// `r = |Δx| + |Δy|`, eq 4 as printed (the default). Not positive definite on irregular
    /// points: its local systems can be solvable yet wild (see the module docs).
    #[default]
    L1,
    /// `r = √(Δx² + Δy²)`: with the plane term, −r³ is the polyharmonic cubic, conditionally
    /// positive definite of order 2, so the system is uniquely solvable for any points not on
    /// a line, and the interpolant is smooth across the axis lines (scipy's `cubic` kernel).
    Euclidean,
}

/// The kernel's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RbfSettings {
    /// c of eq 4.
    pub c: f64,
    /// s: r is measured in units of s, mm.
    pub scale_mm: f64,
    /// The polynomial term.
    pub polynomial: Polynomial,
    /// How r is measured.
    pub distance: Distance,
}

impl RbfSettings {
    /// ρ = r/s between two points.
    fn rho(&self, p: [f64; 2], q: [f64; 2]) -> f64 {
        let (dx, dy) = (p[0] - q[0], p[1] - q[1]);
        match self.distance {
            Distance::L1 => (dx.abs() + dy.abs()) / self.scale_mm,
            Distance::Euclidean => (dx * dx + dy * dy).sqrt() / self.scale_mm,
        }
    }
}

/// φ(ρ), φ′(ρ), φ″(ρ) of eq 4: `−ρ³ + 4ρ² + c`.
pub fn kernel(rho: f64, c: f64) -> [f64; 3] {
    [
        rho * rho * (4.0 - rho) + c,
        rho * (8.0 - 3.0 * rho),
        8.0 - 6.0 * rho,
    ]
}

/// The local system of eq 5 for `centres`, with the polynomial block: the matrix
/// `[Φ P; Pᵀ 0]`, `Φᵢⱼ = φ(|pᵢ − pⱼ|₁ / s)`, `P = [1, (x − x̄)/s, (y − ȳ)/s]`.
pub fn system_matrix(centres: &[[f64; 2]], settings: &RbfSettings) -> DMatrix<f64> {
    let n = centres.len();
    let k = settings.polynomial.terms();
    let s = settings.scale_mm;
    let c0 = centroid(centres);
    DMatrix::from_fn(n + k, n + k, |i, j| match (i < n, j < n) {
        (true, true) => kernel(settings.rho(centres[i], centres[j]), settings.c)[0],
        (true, false) => poly_term(centres[i], c0, s, j - n),
        (false, true) => poly_term(centres[j], c0, s, i - n),
        (false, false) => 0.0,
    })
}

/// The polynomial basis: 1, (x − x̄)/s, (y − ȳ)/s.
fn poly_term(p: [f64; 2], c0: [f64; 2], s: f64, term: usize) -> f64 {
    match term {
        0 => 1.0,
        1 => (p[0] - c0[0]) / s,
        _ => (p[1] - c0[1]) / s,
    }
}

fn centroid(centres: &[[f64; 2]]) -> [f64; 2] {
    let n = centres.len().max(1) as f64;
    let (sx, sy) = centres
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p[0], b + p[1]));
    [sx / n, sy / n]
}

/// The 2-norm condition number of the local system (singular values by SVD).
pub fn condition_number(centres: &[[f64; 2]], settings: &RbfSettings) -> f64 {
    let sv = system_matrix(centres, settings).singular_values();
    let (lo, hi) = sv.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &v| {
        (lo.min(v), hi.max(v))
    });
    hi / lo
}

/// Pivot ratio of the LU factors below which a local system counts as singular.
pub const SINGULAR_PIVOTS: f64 = 1e-13;

/// The interpolant of one neighbour set.
#[derive(Debug, Clone, PartialEq)]
pub struct LocalRbf {
    centres: [[f64; 2]; MAX_NEIGHBOURS],
    a: [f64; MAX_NEIGHBOURS],
    n: usize,
    /// Polynomial coefficients λ₀, λ₁, λ₂ (unused ones zero).
    lambda: [f64; 3],
    centroid: [f64; 2],
    settings: RbfSettings,
}

impl LocalRbf {
    /// Solves eq 5 (with the polynomial block) for heights `z` at `centres`; `Err` with the
    /// smallest-to-largest LU pivot ratio when the system is singular.
    pub fn solve(centres: &[[f64; 2]], z: &[f64], settings: &RbfSettings) -> Result<Self, f64> {
        let n = centres.len().min(MAX_NEIGHBOURS);
        let k = settings.polynomial.terms();
        let c0 = centroid(&centres[..n]);
        let s = settings.scale_mm;
        let entry = |i: usize, j: usize| match (i < n, j < n) {
            (true, true) => kernel(settings.rho(centres[i], centres[j]), settings.c)[0],
            (true, false) => poly_term(centres[i], c0, s, j - n),
            (false, true) => poly_term(centres[j], c0, s, i - n),
            (false, false) => 0.0,
        };
        let rhs = |i: usize| if i < n { z[i] } else { 0.0 };
        let mut sol = [0.0; MAX_NEIGHBOURS + 3];
        solve_sized(n + k, entry, rhs, &mut sol)?;
        let mut this = Self {
            centres: [[0.0; 2]; MAX_NEIGHBOURS],
            a: [0.0; MAX_NEIGHBOURS],
            n,
            lambda: [0.0; 3],
            centroid: c0,
            settings: *settings,
        };
        this.centres[..n].copy_from_slice(&centres[..n]);
        this.a[..n].copy_from_slice(&sol[..n]);
        this.lambda[..k].copy_from_slice(&sol[n..n + k]);
        Ok(this)
    }

    /// The coefficients aⱼ of eq 5, in the order of the centres.
    pub fn coefficients(&self) -> &[f64] {
        &self.a[..self.n]
    }

    /// The polynomial part and its gradient at (x, y).
    fn polynomial(&self, x: f64, y: f64) -> [f64; 3] {
        let s = self.settings.scale_mm;
        let [l0, l1, l2] = self.lambda;
        let (u, v) = ((x - self.centroid[0]) / s, (y - self.centroid[1]) / s);
        [l0 + l1 * u + l2 * v, l1 / s, l2 / s]
    }

    /// f of eq 6 at (x, y), mm.
    pub fn value(&self, x: f64, y: f64) -> f64 {
        let sum: f64 = (0..self.n)
            .map(|j| {
                let rho = self.settings.rho([x, y], self.centres[j]);
                self.a[j] * (rho * rho * (4.0 - rho) + self.settings.c)
            })
            .sum();
        sum + self.polynomial(x, y)[0]
    }

    /// f with its gradient and Hessian at (x, y) (the +x, +y side on an axis line).
    pub fn local(&self, x: f64, y: f64) -> Local {
        let s = self.settings.scale_mm;
        let [pz, px, py] = self.polynomial(x, y);
        let mut l = Local {
            z: pz,
            zx: px,
            zy: py,
            ..Local::default()
        };
        for j in 0..self.n {
            let p = self.centres[j];
            let (dx, dy) = (x - p[0], y - p[1]);
            let a = self.a[j];
            let [f, fx, fy, fxx, fxy, fyy] = match self.settings.distance {
                Distance::L1 => l1_term(dx, dy, s, self.settings.c),
                Distance::Euclidean => euclidean_term(dx, dy, s, self.settings.c),
            };
            l.z += a * f;
            l.zx += a * fx;
            l.zy += a * fy;
            l.zxx += a * fxx;
            l.zxy += a * fxy;
            l.zyy += a * fyy;
        }
        l
    }
}

impl LocalRbf {
    /// The L1 interpolant along `line` as the cubic in powers of `t − mid` it is on the
    /// stretch about `mid` that crosses no axis line of a centre (each `ρⱼ` linear there,
    /// [`super::line_section`]); the side of an axis line through `mid` itself as
    /// [`LocalRbf::local`] takes it. `None` for the Euclidean distance (no polynomial).
    pub fn cubic_along(&self, line: Line, mid: f64) -> Option<Cubic> {
        if self.settings.distance != Distance::L1 {
            return None;
        }
        let s = self.settings.scale_mm;
        let (x, y) = line.at(mid);
        let [pz, px, py] = self.polynomial(x, y);
        let mut k = [pz, px * line.c + py * line.s, 0.0, 0.0];
        for j in 0..self.n {
            let p = self.centres[j];
            let (dx, dy) = (x - p[0], y - p[1]);
            let beta = (sign(dx) * line.c + sign(dy) * line.s) / s;
            let [f, f1, f2] = kernel((dx.abs() + dy.abs()) / s, self.settings.c);
            let a = self.a[j];
            k[0] += a * f;
            k[1] += a * f1 * beta;
            k[2] += a * f2 * beta * beta * 0.5;
            k[3] -= a * beta * beta * beta;
        }
        Some(Cubic { mid, k })
    }
}

/// `[φ, φ_x, φ_y, φ_xx, φ_xy, φ_yy]` of `φ((|dx| + |dy|)/s)` (the +x, +y side on an axis
/// line).
fn l1_term(dx: f64, dy: f64, s: f64, c: f64) -> [f64; 6] {
    let (sx, sy) = (sign(dx), sign(dy));
    let [f, f1, f2] = kernel((dx.abs() + dy.abs()) / s, c);
    let h = f2 / (s * s);
    [f, f1 * sx / s, f1 * sy / s, h, h * sx * sy, h]
}

/// `[φ, φ_x, φ_y, φ_xx, φ_xy, φ_yy]` of `φ(ρ)`, `ρ = √(dx² + dy²)/s`: with `φ′(ρ)/ρ = 8 − 3ρ`,
/// `φ_x = (8 − 3ρ)·dx/s²` and `φ_xx = (8 − 3ρ)/s² − 3·dx²/(s⁴ρ)`, `φ_xy = −3·dx·dy/(s⁴ρ)`;
/// the last terms are bounded and tend to 0 at ρ = 0 (φ is C² there, not C³). The root is
/// taken of the sum of squares, not by `hypot`, which guards against overflows that distances
/// between data points never reach and took a fifth of the time of planning on this kernel.
fn euclidean_term(dx: f64, dy: f64, s: f64, c: f64) -> [f64; 6] {
    let s2 = s * s;
    let rho = (dx * dx + dy * dy).sqrt() / s;
    let f = kernel(rho, c)[0];
    let g = (8.0 - 3.0 * rho) / s2;
    let k = if rho > 0.0 {
        3.0 / (s2 * s2 * rho)
    } else {
        0.0
    };
    [
        f,
        g * dx,
        g * dy,
        g - k * dx * dx,
        -k * dx * dy,
        g - k * dy * dy,
    ]
}

/// Solves the `d × d` system with entries `a(i, j)` and right-hand side `b(i)` into `out` by
/// LU with partial pivoting on a stack matrix of that size (nalgebra's fixed-size LU); `Err`
/// with the smallest-to-largest pivot ratio when it is below [`SINGULAR_PIVOTS`].
fn solve_sized(
    d: usize,
    a: impl Fn(usize, usize) -> f64,
    b: impl Fn(usize) -> f64,
    out: &mut [f64],
) -> Result<(), f64> {
    macro_rules! sized {
        ($($n:literal)*) => {
            match d {
                $($n => {
                    let lu = SMatrix::<f64, $n, $n>::from_fn(&a).lu();
                    let u = lu.u();
                    check_pivots((0..$n).map(|i| u[(i, i)]))?;
                    let x = lu.solve(&SVector::<f64, $n>::from_fn(|i, _| b(i))).ok_or(0.0)?;
                    out[..$n].copy_from_slice(x.as_slice());
                    Ok(())
                })*
                _ => Err(0.0),
            }
        };
    }
    sized!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19)
}

/// `Err` with the smallest-to-largest ratio of the pivots when it is below
/// [`SINGULAR_PIVOTS`].
fn check_pivots(pivots: impl Iterator<Item = f64>) -> Result<(), f64> {
    let (lo, hi) = pivots.fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
        (lo.min(p.abs()), hi.max(p.abs()))
    });
    let ratio = lo / hi;
    if ratio > SINGULAR_PIVOTS {
        Ok(())
    } else {
        Err(ratio)
    }
}

/// The sign of d with sign(0) = +1: derivatives on an axis line are those of the + side.
fn sign(d: f64) -> f64 {
    if d < 0.0 { -1.0 } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(polynomial: Polynomial, c: f64) -> RbfSettings {
        RbfSettings {
            c,
            scale_mm: 0.04,
            polynomial,
            distance: Distance::L1,
        }
    }

    /// Eight neighbours of the query (0.013, 0.027) on a 0.04 mm grid, with heights.
    fn stencil() -> (Vec<[f64; 2]>, Vec<f64>) {
        let h = 0.04;
        let c: Vec<[f64; 2]> = [
            (0, 0),
            (1, 0),
            (0, 1),
            (1, 1),
            (-1, 0),
            (0, -1),
            (-1, 1),
            (1, -1),
        ]
        .iter()
        .map(|&(i, j)| [i as f64 * h, j as f64 * h])
        .collect();
        let z = c
            .iter()
            .map(|p| 1e-3 * (3.0 * p[0] - 2.0 * p[1]).sin() + 0.02 * p[0] * p[1])
            .collect();
        (c, z)
    }

    #[test]
    fn kernel_derivatives_are_those_of_the_cubic() {
        for &rho in &[0.0, 0.3, 1.0, 2.5, 3.9] {
            let [f, f1, f2] = kernel(rho, 0.7);
            assert_eq!(f, -rho * rho * rho + 4.0 * rho * rho + 0.7);
            let e = 1e-6;
            let fd1 = (kernel(rho + e, 0.7)[0] - kernel(rho - e, 0.7)[0]) / (2.0 * e);
            let fd2 = (kernel(rho + e, 0.7)[1] - kernel(rho - e, 0.7)[1]) / (2.0 * e);
            assert!((f1 - fd1).abs() < 1e-8 && (f2 - fd2).abs() < 1e-8, "{rho}");
        }
        // Zero at ρ = 4 (c = 0): the end of the positive range.
        assert_eq!(kernel(4.0, 0.0)[0], 0.0);
    }

    #[test]
    fn interpolates_its_centres_for_every_polynomial() {
        let (c, z) = stencil();
        for poly in [Polynomial::None, Polynomial::Constant, Polynomial::Linear] {
            let f = LocalRbf::solve(&c, &z, &settings(poly, 1.0)).unwrap();
            for (p, zj) in c.iter().zip(&z) {
                assert!((f.value(p[0], p[1]) - zj).abs() < 1e-15, "{poly:?}");
                assert!((f.local(p[0], p[1]).z - zj).abs() < 1e-15, "{poly:?}");
            }
        }
    }

    #[test]
    fn linear_polynomial_reproduces_planes_and_constant_is_the_large_c_limit() {
        let (c, _) = stencil();
        let plane: Vec<f64> = c.iter().map(|p| 0.3 + 0.1 * p[0] - 0.25 * p[1]).collect();
        let f = LocalRbf::solve(&c, &plane, &settings(Polynomial::Linear, 0.0)).unwrap();
        let (x, y) = (0.013, 0.027);
        assert!((f.value(x, y) - (0.3 + 0.1 * x - 0.25 * y)).abs() < 1e-15);
        let l = f.local(x, y);
        assert!(
            (l.zx - 0.1).abs() < 1e-12 && (l.zy + 0.25).abs() < 1e-12,
            "{l:?}"
        );
        // Constant data: the constant polynomial gives it exactly; eq 6 alone does not.
        let one = vec![1.0; c.len()];
        let f = LocalRbf::solve(&c, &one, &settings(Polynomial::Constant, 0.0)).unwrap();
        assert!((f.value(x, y) - 1.0).abs() < 1e-15);
        let f = LocalRbf::solve(&c, &one, &settings(Polynomial::None, 0.0)).unwrap();
        assert!((f.value(x, y) - 1.0).abs() > 1e-3, "{}", f.value(x, y));
        // As c grows, eq 6 tends to the constant-augmented interpolant (error ~ 1/c).
        let (_, z) = stencil();
        let limit = LocalRbf::solve(&c, &z, &settings(Polynomial::Constant, 0.0)).unwrap();
        let gap = |cc: f64| {
            let f = LocalRbf::solve(&c, &z, &settings(Polynomial::None, cc)).unwrap();
            (f.value(x, y) - limit.value(x, y)).abs()
        };
        let (g1, g2) = (gap(1e2), gap(1e4));
        assert!(g2 < g1 * 0.02 && g2 < 1e-9, "{g1:e} {g2:e}");
        // And c has no effect with a constant term (Σaⱼ = 0).
        let f = LocalRbf::solve(&c, &z, &settings(Polynomial::Constant, 50.0)).unwrap();
        assert!((f.value(x, y) - limit.value(x, y)).abs() < 1e-15);
    }

    #[test]
    fn derivatives_match_finite_differences_off_the_axis_lines() {
        let (c, z) = stencil();
        for poly in [Polynomial::None, Polynomial::Linear] {
            let f = LocalRbf::solve(&c, &z, &settings(poly, 2.0)).unwrap();
            // Points at least 2e-3 mm from every x = xⱼ and y = yⱼ line (multiples of 0.04).
            for &(x, y) in &[(0.013, 0.027), (-0.021, 0.0051), (0.047, -0.031)] {
                let l = f.local(x, y);
                let e = 1e-6;
                let fx = (f.value(x + e, y) - f.value(x - e, y)) / (2.0 * e);
                let fy = (f.value(x, y + e) - f.value(x, y - e)) / (2.0 * e);
                let d = |g: fn(&Local) -> f64, dx: f64, dy: f64| {
                    (g(&f.local(x + dx, y + dy)) - g(&f.local(x - dx, y - dy))) / (2.0 * e)
                };
                // Central differences of a cubic: error e²·|f‴|/6 ≈ 1e-12·|a|·6/s³.
                assert!(
                    (l.zx - fx).abs() < 1e-8 && (l.zy - fy).abs() < 1e-8,
                    "{l:?}"
                );
                assert!((l.zxx - d(|l| l.zx, e, 0.0)).abs() < 1e-6, "{poly:?} zxx");
                assert!((l.zxy - d(|l| l.zx, 0.0, e)).abs() < 1e-6, "{poly:?} zxy");
                assert!((l.zyy - d(|l| l.zy, 0.0, e)).abs() < 1e-6, "{poly:?} zyy");
                assert!(
                    (l.zxx - l.zyy).abs() < 1e-9,
                    "f_xx = f_yy between the lines"
                );
            }
        }
    }

    #[test]
    fn the_slope_jumps_across_an_axis_line_but_not_at_the_data_point() {
        let (c, z) = stencil();
        let st = settings(Polynomial::Linear, 0.0);
        let f = LocalRbf::solve(&c, &z, &st).unwrap();
        // Across x = 0 at y = 0.027: ∂f/∂x jumps by Σ 2·aⱼ·φ′(|y − yⱼ|/s)/s over the centres
        // on that line, (0, 0), (0, h) and (0, −h).
        let y = 0.027;
        let e = 1e-7;
        let left = (f.value(0.0, y) - f.value(-e, y)) / e;
        let right = (f.value(e, y) - f.value(0.0, y)) / e;
        let a = f.coefficients();
        let expect: f64 = c
            .iter()
            .zip(a)
            .filter(|(p, _)| p[0] == 0.0)
            .map(|(p, aj)| 2.0 * aj * kernel((y - p[1]).abs() / st.scale_mm, 0.0)[1] / st.scale_mm)
            .sum();
        assert!(expect.abs() > 1e-4, "a visible jump: {expect}");
        // One-sided differences of a cubic: error e·|f″| ≈ 1e-7 × 10.
        assert!(
            (right - left - expect).abs() < 1e-5,
            "{} vs {expect}",
            right - left
        );
        // Centres that share no axis line: at the centre (0, 0) the one-sided slopes agree
        // (φ′(0) = 0), on its axis line away from it they do not.
        let lone: [[f64; 2]; 5] = [
            [0.0, 0.0],
            [0.05, 0.013],
            [-0.031, 0.047],
            [0.022, -0.052],
            [-0.043, -0.017],
        ];
        let zl: Vec<f64> = lone
            .iter()
            .map(|p| (7.0 * p[0]).sin() * 1e-3 + p[1] * p[1])
            .collect();
        let f = LocalRbf::solve(&lone, &zl, &st).unwrap();
        let left = (f.value(0.0, 0.0) - f.value(-e, 0.0)) / e;
        let right = (f.value(e, 0.0) - f.value(0.0, 0.0)) / e;
        assert!((right - left).abs() < 1e-5, "{left} {right}");
        let left = (f.value(0.0, 0.02) - f.value(-e, 0.02)) / e;
        let right = (f.value(e, 0.02) - f.value(0.0, 0.02)) / e;
        let expect = 2.0 * f.coefficients()[0] * kernel(0.02 / 0.04, 0.0)[1] / 0.04;
        assert!(
            (right - left - expect).abs() < 1e-5,
            "{} vs {expect}",
            right - left
        );
    }

    #[test]
    fn singular_systems_are_reported() {
        // ρ = 4 between neighbours (s = h/2 on a grid): φ vanishes and the system is singular.
        let c: Vec<[f64; 2]> = [(0, 0), (1, 0), (0, 1), (1, 1)]
            .iter()
            .map(|&(i, j)| [i as f64, j as f64])
            .collect();
        let st = RbfSettings {
            c: 0.0,
            scale_mm: 0.5,
            polynomial: Polynomial::None,
            distance: Distance::L1,
        };
        // Φ = [[0, 8, 8, 0], [8, 0, 0, 8], …]: rank 2.
        assert!(LocalRbf::solve(&c, &[1.0, 2.0, 3.0, 4.0], &st).is_err());
        assert!(condition_number(&c, &st) > 1e15);
    }
}
