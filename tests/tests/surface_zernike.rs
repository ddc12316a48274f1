//! Zernike sag through the public API.
//!
//! - The first 15 terms of both conventions and Fringe Z37, written out here by hand from the
//!   definitions (Noll 1976 Table I for Standard, the University of Arizona / OpticStudio Fringe
//!   list), at points inside and outside the unit disc and at its centre.
//! - Every term (231 Standard, 37 Fringe) against an independent implementation: the index maps
//!   enumerated in order (not inverted), and the radial polynomials from the recurrence
//!   `Rₙᵐ = ρ·(Rₙ₋₁^|m−1| + Rₙ₋₁^(m+1)) − Rₙ₋₂ᵐ` in polar coordinates (not the factorial sum
//!   expanded in x, y as the library does).
//! - Orthonormality of all 231 Standard terms (and orthogonality with the un-normalised norms
//!   `1/(2(n+1))`, `1/(n+1)` of the 37 Fringe terms) by a quadrature that is exact for them:
//!   Gauss–Legendre in t = ρ² (12 nodes, exact to degree 23 ≥ 20) times 48 equal angles (exact for
//!   trigonometric degree < 48, and m + m′ ≤ 40).
//! - Derivatives against central finite differences for random coefficient vectors (proptest),
//!   the base added, errors, the documentation's tables, and whole planned jobs through the
//!   brute-force gouge check.

mod common;

use common::{
    check_derivatives, check_example_jobs, check_planned_path, config, field_error, gauss_legendre,
    local, small_job,
};
use proptest::prelude::*;
use spiralcam::surface::zernike::Convention;
use spiralcam::surface::{
    Asphere, AsphereSpec, PartDisc, Surface, SurfaceSpec, Zernike, ZernikeSpec,
};
use std::f64::consts::{PI, TAU};

const EPS: f64 = f64::EPSILON;

/// Seed of this file's property tests.
const SEED: u64 = 3737;

fn plane() -> AsphereSpec {
    AsphereSpec {
        curvature_per_mm: Some(0.0),
        ..Default::default()
    }
}

fn build(convention: Convention, base: AsphereSpec, norm: f64, c: Vec<f64>) -> Zernike {
    Zernike::new(
        &ZernikeSpec {
            convention,
            base,
            norm_radius_mm: norm,
            coefficients_mm: c,
        },
        PartDisc::centred(norm),
    )
    .expect("valid Zernike surface")
}

/// Term j alone with coefficient 1 mm on a plane.
fn single(convention: Convention, j: usize, norm: f64) -> Zernike {
    let mut c = vec![0.0; j];
    c[j - 1] = 1.0;
    build(convention, plane(), norm, c)
}

/// Normalisation radius of the closed-form tests, mm.
const N: f64 = 3.7;

/// Points (ρ, φ) of the closed-form tests: the centre, inside the disc, its edge, and outside
/// it (where the polynomial continues), at angles off every symmetry axis and on some.
const POLAR: [(f64, f64); 9] = [
    (0.0, 0.0),
    (0.25, 0.3),
    (0.5, 1.9),
    (0.71, -2.4),
    (0.9, 4.0),
    (1.0, 0.0),
    (1.0, PI / 2.0),
    (1.15, 5.5),
    (1.2, 2.7),
];

/// Values of unit-coefficient terms of the first orders are O(0.1 … 10); their monomials at
/// ρ ≤ 1.2 are below 30 in size, so a few dozen roundings leave under 1e-13: 1e-12 (in units of
/// the coefficient) is tight, while a wrong sign, factor, angle or index changes a value by O(1).
const CLOSED_FORM_TOL: f64 = 1e-12;

/// A term written out by hand, in (ρ, φ) or in (u, v).
type Form = fn(f64, f64) -> f64;

fn check_closed_forms(convention: Convention, forms: &[Form]) {
    for (i, form) in forms.iter().enumerate() {
        let j = i + 1;
        let s = single(convention, j, N);
        for &(rho, phi) in &POLAR {
            let (x, y) = (N * rho * phi.cos(), N * rho * phi.sin());
            let got = local(&s, x, y).z;
            let want = form(rho, phi);
            assert!(
                (got - want).abs() <= CLOSED_FORM_TOL,
                "{convention:?} Z{j} at ρ {rho} φ {phi}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn standard_terms_1_to_15_are_nolls() {
    let forms: [Form; 15] = [
        |_, _| 1.0,
        |r, p| 2.0 * r * p.cos(),
        |r, p| 2.0 * r * p.sin(),
        |r, _| 3f64.sqrt() * (2.0 * r * r - 1.0),
        |r, p| 6f64.sqrt() * r * r * (2.0 * p).sin(),
        |r, p| 6f64.sqrt() * r * r * (2.0 * p).cos(),
        |r, p| 8f64.sqrt() * (3.0 * r.powi(3) - 2.0 * r) * p.sin(),
        |r, p| 8f64.sqrt() * (3.0 * r.powi(3) - 2.0 * r) * p.cos(),
        |r, p| 8f64.sqrt() * r.powi(3) * (3.0 * p).sin(),
        |r, p| 8f64.sqrt() * r.powi(3) * (3.0 * p).cos(),
        |r, _| 5f64.sqrt() * (6.0 * r.powi(4) - 6.0 * r * r + 1.0),
        |r, p| 10f64.sqrt() * (4.0 * r.powi(4) - 3.0 * r * r) * (2.0 * p).cos(),
        |r, p| 10f64.sqrt() * (4.0 * r.powi(4) - 3.0 * r * r) * (2.0 * p).sin(),
        |r, p| 10f64.sqrt() * r.powi(4) * (4.0 * p).cos(),
        |r, p| 10f64.sqrt() * r.powi(4) * (4.0 * p).sin(),
    ];
    check_closed_forms(Convention::Standard, &forms);
    // The same terms in Cartesian form, u = x/N, v = y/N: Z5 = √6·2uv, Z6 = √6·(u² − v²),
    // Z8 = √8·(3(u² + v²) − 2)·u, Z10 = √8·(u³ − 3uv²), Z14 = √10·(u⁴ − 6u²v² + v⁴).
    let cartesian: [(usize, Form); 5] = [
        (5, |u, v| 6f64.sqrt() * 2.0 * u * v),
        (6, |u, v| 6f64.sqrt() * (u * u - v * v)),
        (8, |u, v| 8f64.sqrt() * (3.0 * (u * u + v * v) - 2.0) * u),
        (10, |u, v| 8f64.sqrt() * (u.powi(3) - 3.0 * u * v * v)),
        (14, |u, v| {
            10f64.sqrt() * (u.powi(4) - 6.0 * u * u * v * v + v.powi(4))
        }),
    ];
    for (j, form) in cartesian {
        let s = single(Convention::Standard, j, N);
        for (x, y) in [(0.4, -1.3), (2.9, 1.1), (-3.0, -2.5), (0.0, 3.7)] {
            let (got, want) = (local(&s, x, y).z, form(x / N, y / N));
            assert!(
                (got - want).abs() <= CLOSED_FORM_TOL,
                "Z{j} ({x}, {y}): {got} vs {want}"
            );
        }
    }
}

#[test]
fn fringe_terms_1_to_15_are_the_arizona_list() {
    let forms: [Form; 15] = [
        |_, _| 1.0,
        |r, p| r * p.cos(),
        |r, p| r * p.sin(),
        |r, _| 2.0 * r * r - 1.0,
        |r, p| r * r * (2.0 * p).cos(),
        |r, p| r * r * (2.0 * p).sin(),
        |r, p| (3.0 * r.powi(3) - 2.0 * r) * p.cos(),
        |r, p| (3.0 * r.powi(3) - 2.0 * r) * p.sin(),
        |r, _| 6.0 * r.powi(4) - 6.0 * r * r + 1.0,
        |r, p| r.powi(3) * (3.0 * p).cos(),
        |r, p| r.powi(3) * (3.0 * p).sin(),
        |r, p| (4.0 * r.powi(4) - 3.0 * r * r) * (2.0 * p).cos(),
        |r, p| (4.0 * r.powi(4) - 3.0 * r * r) * (2.0 * p).sin(),
        |r, p| (10.0 * r.powi(5) - 12.0 * r.powi(3) + 3.0 * r) * p.cos(),
        |r, p| (10.0 * r.powi(5) - 12.0 * r.powi(3) + 3.0 * r) * p.sin(),
    ];
    check_closed_forms(Convention::Fringe, &forms);
}

#[test]
fn fringe_term_37_is_r_12_0() {
    // Z37 = 924ρ¹² − 2772ρ¹⁰ + 3150ρ⁸ − 1680ρ⁶ + 420ρ⁴ − 42ρ² + 1, and 1 at ρ = 1.
    let s = single(Convention::Fringe, 37, N);
    for &(rho, phi) in &POLAR {
        let r2: f64 = rho * rho;
        let want = 924.0 * r2.powi(6) - 2772.0 * r2.powi(5) + 3150.0 * r2.powi(4)
            - 1680.0 * r2.powi(3)
            + 420.0 * r2 * r2
            - 42.0 * r2
            + 1.0;
        let got = local(&s, N * rho * phi.cos(), N * rho * phi.sin()).z;
        // Monomials up to 924·1.2¹² ≈ 8200 cancel to O(1): 64ε·Σ|terms|, below 1e-10.
        let sum = 924.0 * r2.powi(6)
            + 2772.0 * r2.powi(5)
            + 3150.0 * r2.powi(4)
            + 1680.0 * r2.powi(3)
            + 420.0 * r2 * r2
            + 42.0 * r2
            + 1.0;
        assert!(
            (got - want).abs() <= 64.0 * EPS * sum,
            "ρ {rho} φ {phi}: {got} vs {want}"
        );
    }
    let edge = local(&s, N, 0.0).z;
    assert!((edge - 1.0).abs() <= 64.0 * EPS * 9009.0, "{edge}");
}

// ---------------------------------------------------------------------------------------------
// Every term against an independent implementation

/// The angular factor of a term.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Angle {
    Symmetric,
    Cos,
    Sin,
}

/// Noll's list, enumerated: within order n the azimuthal orders m = n mod 2, …, n; m = 0 takes
/// one index, m > 0 two consecutive ones, the even one cos mφ and the odd one sin mφ.
fn noll_list() -> Vec<(usize, usize, Angle)> {
    let mut out = Vec::new();
    for n in 0..=20 {
        for m in (n % 2..=n).step_by(2) {
            if m == 0 {
                out.push((n, 0, Angle::Symmetric));
            } else {
                let j = out.len() + 1;
                let (first, second) = if j % 2 == 0 {
                    (Angle::Cos, Angle::Sin)
                } else {
                    (Angle::Sin, Angle::Cos)
                };
                out.push((n, m, first));
                out.push((n, m, second));
            }
        }
    }
    out
}

/// The Fringe list: groups g = (n + m)/2 = 0 … 5 with m falling from g to 0 (cos, then sin),
/// then R₁₂⁰.
fn fringe_list() -> Vec<(usize, usize, Angle)> {
    let mut out = Vec::new();
    for g in 0..=5 {
        for m in (0..=g).rev() {
            let n = 2 * g - m;
            if m == 0 {
                out.push((n, 0, Angle::Symmetric));
            } else {
                out.push((n, m, Angle::Cos));
                out.push((n, m, Angle::Sin));
            }
        }
    }
    out.push((12, 0, Angle::Symmetric));
    out
}

/// `R[n][m]` for n, m ≤ 20 at ρ from the recurrence
/// `Rₙᵐ = ρ·(Rₙ₋₁^|m−1| + Rₙ₋₁^(m+1)) − Rₙ₋₂ᵐ`, R₀⁰ = 1 (zero where m > n or n − m is odd).
fn radial_table(rho: f64) -> Vec<Vec<f64>> {
    let mut r = vec![vec![0.0; 22]; 21];
    r[0][0] = 1.0;
    for n in 1..=20 {
        for m in (n % 2..=n).step_by(2) {
            let below = if n >= 2 { r[n - 2][m] } else { 0.0 };
            r[n][m] = rho * (r[n - 1][m.abs_diff(1)] + r[n - 1][m + 1]) - below;
        }
    }
    r
}

/// Standard normalisation √(n+1) (m = 0) or √(2(n+1)).
fn rms_norm(n: usize, m: usize) -> f64 {
    if m == 0 {
        ((n + 1) as f64).sqrt()
    } else {
        (2.0 * (n + 1) as f64).sqrt()
    }
}

/// A rounding bound of the library's expansion in u, v at ρ ≤ 1: the sum of the absolute values
/// of its monomials is at most `Σₖ|cₖ|·2^(m/2)` (|Re, Im (u+iv)ᵐ| expanded ≤ (|u|+|v|)ᵐ), cₖ the
/// factorial-sum coefficients, computed here in floating point.
fn monomial_bound(n: usize, m: usize) -> f64 {
    let f = |k: usize| (1..=k).map(|i| i as f64).product::<f64>();
    let sum: f64 = (0..=(n - m) / 2)
        .map(|k| f(n - k) / (f(k) * f((n + m) / 2 - k) * f((n - m) / 2 - k)))
        .sum();
    sum * 2f64.powf(m as f64 / 2.0)
}

fn reference(term: (usize, usize, Angle), scale: f64, rho: f64, phi: f64) -> f64 {
    let (n, m, angle) = term;
    let r = radial_table(rho)[n][m];
    let a = match angle {
        Angle::Symmetric => 1.0,
        Angle::Cos => (m as f64 * phi).cos(),
        Angle::Sin => (m as f64 * phi).sin(),
    };
    scale * r * a
}

#[test]
fn every_term_matches_the_recurrence() {
    let pts: Vec<(f64, f64)> = [0.0, 0.2, 0.55, 0.8, 0.97, 1.0]
        .iter()
        .flat_map(|&rho| [0.0, 0.7, 2.2, -1.3, PI / 2.0].map(move |phi| (rho, phi)))
        .collect();
    let lists = [
        (Convention::Standard, noll_list(), true),
        (Convention::Fringe, fringe_list(), false),
    ];
    for (convention, list, normalised) in lists {
        assert_eq!(list.len(), convention.max_terms());
        for (i, &term) in list.iter().enumerate() {
            let (n, m, angle) = term;
            let j = i + 1;
            let t = convention.term(j).expect("listed term");
            assert_eq!((t.n, t.m), (n, m), "{convention:?} Z{j}");
            let scale = if normalised { rms_norm(n, m) } else { 1.0 };
            let s = single(convention, j, 2.0);
            // The library's rounding, ε·bound (see `monomial_bound`; observed 10 times below it
            // at every order), plus the recurrence's (a few ε per step, |R| ≤ 1 on the disc):
            // 4ε·(bound + n).
            let tol = 4.0 * EPS * scale * (monomial_bound(n, m) + n as f64);
            for &(rho, phi) in &pts {
                let got = local(&s, 2.0 * rho * phi.cos(), 2.0 * rho * phi.sin()).z;
                let want = reference(term, scale, rho, phi);
                assert!(
                    (got - want).abs() <= tol,
                    "{convention:?} Z{j} ({n}, {m}, {angle:?}) at ρ {rho} φ {phi}: {got} vs \
                     {want}, tolerance {tol:e}"
                );
            }
        }
    }
}

/// The quadrature nodes (x, y) on the unit disc and weights w with `Σ w·f ≈ ∫ f dA / π`.
fn disc_quadrature() -> Vec<(f64, f64, f64)> {
    let angles = 48;
    let mut out = Vec::new();
    for (t, wt) in gauss_legendre(12) {
        let rho = t.sqrt();
        for l in 0..angles {
            let phi = TAU * l as f64 / angles as f64;
            // dA = ρ dρ dφ = ½ dt dφ: ∫∫ f ½ dt dφ / π = Σ wt·(2π/M)·½/π·f = Σ wt/M·f.
            out.push((rho * phi.cos(), rho * phi.sin(), wt / angles as f64));
        }
    }
    out
}

/// `G[j][k] = ∫ Zⱼ·Zₖ dA / π` over the unit disc for all terms of a convention (N = 1).
fn gram(convention: Convention) -> Vec<Vec<f64>> {
    let nodes = disc_quadrature();
    // Rows √w·Zⱼ(node), so that G = A·Aᵀ.
    let rows: Vec<Vec<f64>> = (1..=convention.max_terms())
        .map(|j| {
            let s = single(convention, j, 1.0);
            nodes
                .iter()
                .map(|&(x, y, w)| w.sqrt() * local(&s, x, y).z)
                .collect()
        })
        .collect();
    let dot = |a: &[f64], b: &[f64]| -> f64 {
        let mut sum = 0.0;
        for i in 0..a.len() {
            sum += a[i] * b[i];
        }
        sum
    };
    let k = rows.len();
    let mut g = vec![vec![0.0; k]; k];
    for i in 0..k {
        for j in i..k {
            g[i][j] = dot(&rows[i], &rows[j]);
            g[j][i] = g[i][j];
        }
    }
    g
}

#[test]
fn the_quadrature_is_exact_for_the_disc() {
    // ∫ dA/π = 1, ∫ ρ²⁰ dA/π = 2/22, ∫ x²y² dA/π = 1/24.
    let q = disc_quadrature();
    let total: f64 = q.iter().map(|p| p.2).sum();
    assert!((total - 1.0).abs() < 1e-14);
    let r20: f64 = q
        .iter()
        .map(|&(x, y, w)| w * (x * x + y * y).powi(10))
        .sum();
    assert!((r20 - 1.0 / 11.0).abs() < 1e-14, "{r20}");
    let x2y2: f64 = q.iter().map(|&(x, y, w)| w * x * x * y * y).sum();
    assert!((x2y2 - 1.0 / 24.0).abs() < 1e-14, "{x2y2}");
}

#[test]
fn standard_terms_are_orthonormal_over_the_unit_disc() {
    // ∫ Zⱼ² dA/π = 1 and ∫ Zⱼ·Zₖ dA/π = 0 for all 231 × 231 pairs. Tolerance: each value
    // carries the expansion's rounding, under 4ε·√(2(n+1))·bound(n, m) (see every_term_…), and
    // is at most √(2(n+1)) in size (|Rₙᵐ| ≤ 1), so a product errs by at most the cross sum; plus
    // 1e-13 for the 576-node sum.
    let g = gram(Convention::Standard);
    let list = noll_list();
    let err = |(n, m, _): (usize, usize, Angle)| 4.0 * EPS * rms_norm(n, m) * monomial_bound(n, m);
    for (j, row) in g.iter().enumerate() {
        for (k, &v) in row.iter().enumerate() {
            let want = if j == k { 1.0 } else { 0.0 };
            let (a, b) = (list[j], list[k]);
            let tol = err(a) * rms_norm(b.0, b.1) + err(b) * rms_norm(a.0, a.1) + 1e-13;
            assert!(
                (v - want).abs() <= tol,
                "Z{} · Z{}: {v} vs {want} (tolerance {tol:e})",
                j + 1,
                k + 1
            );
        }
    }
    // The lower orders are orthonormal to 1e-13.
    for (j, row) in g.iter().take(66).enumerate() {
        for (k, v) in row.iter().take(66).enumerate() {
            let want = if j == k { 1.0 } else { 0.0 };
            assert!((v - want).abs() < 1e-13, "Z{} · Z{}: {v}", j + 1, k + 1);
        }
    }
}

#[test]
fn fringe_terms_are_orthogonal_and_not_normalised() {
    // ∫ Rₙᵐ(ρ)² ρ dρ = 1/(2(n+1)) and ∫ cos²(mφ) dφ = π (m > 0) or 2π: the mean square is
    // 1/(2(n+1)) for m > 0 and 1/(n+1) for m = 0 (1/13 for Z37).
    let g = gram(Convention::Fringe);
    let list = fringe_list();
    for (j, row) in g.iter().enumerate() {
        let (n, m, _) = list[j];
        for (k, &v) in row.iter().enumerate() {
            let want = match (j == k, m) {
                (false, _) => 0.0,
                (true, 0) => 1.0 / (n + 1) as f64,
                (true, _) => 0.5 / (n + 1) as f64,
            };
            // Values at most 1 on the disc; Z37's monomials sum to 9009: 1e-11 covers 64ε·9009·2.
            assert!(
                (v - want).abs() < 1e-11,
                "Z{} · Z{}: {v} vs {want}",
                j + 1,
                k + 1
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Base, continuation, derivatives

#[test]
fn the_sum_is_added_to_the_base_asphere() {
    // Sphere R 50, k −0.5, A4 2e-6, N 4, Standard Z4 0.002 + Z7 −0.001 + Fringe likewise.
    let base = AsphereSpec {
        radius_mm: Some(50.0),
        conic: -0.5,
        coefficients: vec![2e-6],
        ..Default::default()
    };
    let asphere = Asphere::new(&base).unwrap();
    let standard = build(
        Convention::Standard,
        base.clone(),
        4.0,
        vec![0.0, 0.0, 0.0, 0.002, 0.0, 0.0, -0.001],
    );
    let fringe = build(
        Convention::Fringe,
        base,
        4.0,
        vec![0.0, 0.0, 0.0, 0.002, 0.0, 0.0, -0.001],
    );
    for (x, y) in [(0.0, 0.0), (1.0, 2.0), (-3.0, 1.5), (3.5, -3.5)] {
        let (u, v) = (x / 4.0, y / 4.0);
        let r2: f64 = u * u + v * v;
        let b = asphere.sag(x, y).unwrap();
        // Standard Z4 = √3(2ρ² − 1), Z7 = √8(3ρ³ − 2ρ)·sin φ = √8(3ρ² − 2)·v.
        let zs =
            b + 0.002 * 3f64.sqrt() * (2.0 * r2 - 1.0) - 0.001 * 8f64.sqrt() * (3.0 * r2 - 2.0) * v;
        // Fringe Z4 = 2ρ² − 1, Z7 = (3ρ² − 2)·u.
        let zf = b + 0.002 * (2.0 * r2 - 1.0) - 0.001 * (3.0 * r2 - 2.0) * u;
        // Sags below 1 mm summed in another order: 1e-15 mm.
        assert!(
            (standard.sag(x, y).unwrap() - zs).abs() < 1e-15,
            "({x}, {y})"
        );
        assert!((fringe.sag(x, y).unwrap() - zf).abs() < 1e-15, "({x}, {y})");
    }
    // The base keeps its domain: R 50, k −0.5 has its rim at 50/√0.5.
    let e = standard.local(80.0, 0.0).unwrap_err();
    assert!(e.to_string().contains("radius 80 mm"), "{e}");
}

#[test]
fn outside_the_normalisation_radius_the_polynomial_continues() {
    // Fringe Z9 = 6ρ⁴ − 6ρ² + 1 at ρ = 2 is 73, and the slope keeps rising: d/dρ = 24ρ³ − 12ρ.
    let s = single(Convention::Fringe, 9, 1.5);
    let l = local(&s, 3.0, 0.0);
    assert!((l.z - 73.0).abs() < 1e-12, "{}", l.z);
    assert!((l.zx - (24.0 * 8.0 - 24.0) / 1.5).abs() < 1e-12, "{}", l.zx);
}

#[derive(Debug, Clone)]
struct Case {
    convention: Convention,
    radius: f64,
    conic: f64,
    norm: f64,
    coefficients: Vec<f64>,
}

/// A random surface: a sphere or conic base (R ±20…200 mm, rim well outside N), N 1…10 mm, and
/// coefficients `u·1 µm·(3/(n+1))³`: realistic sizes, smaller for higher orders so that the
/// finite differences' truncation error (derivatives grow like n²/N per order) stays within the
/// tolerance, as in a real surface.
fn case() -> impl Strategy<Value = Case> {
    let conv = prop_oneof![Just(Convention::Standard), Just(Convention::Fringe)];
    (
        conv,
        prop_oneof![20.0..200.0f64, -200.0..-20.0f64],
        -2.0..0.5f64,
        1.0..10.0f64,
        prop::collection::vec(-1.0..1.0f64, 1..=231),
    )
        .prop_map(|(convention, radius, conic, norm, unit)| {
            let coefficients = unit
                .iter()
                .take(convention.max_terms())
                .enumerate()
                .map(|(i, u)| {
                    let n = convention.term(i + 1).expect("term").n as f64;
                    u * 1e-3 * (3.0 / (n + 1.0)).powi(3)
                })
                .collect();
            Case {
                convention,
                radius,
                conic,
                norm,
                coefficients,
            }
        })
}

impl Case {
    fn build(&self) -> Zernike {
        build(
            self.convention,
            AsphereSpec {
                radius_mm: Some(self.radius),
                conic: self.conic,
                ..Default::default()
            },
            self.norm,
            self.coefficients.clone(),
        )
    }
}

proptest! {
    #![proptest_config(config(96, SEED))]

    #[test]
    fn derivatives_match_finite_differences(
        case in case(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..TAU), 3),
    ) {
        let s = case.build();
        for (t, phi) in pts {
            // Inside 1.1·N: the polynomial continues, but its growth outside is not a surface
            // anyone makes.
            let rho = 1.1 * case.norm * t.sqrt();
            check_derivatives(&s, rho * phi.cos(), rho * phi.sin())?;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Errors, documentation, jobs

#[test]
fn bad_parameters_name_their_field() {
    let zeros = |k: usize| vec!["0"; k].join(",");
    let cases = [
        (
            format!(
                r#"{{"type":"zernike","convention":"fringe","base":{{"radius_mm":50}},"norm_radius_mm":5,"coefficients_mm":[{}]}}"#,
                zeros(38)
            ),
            "surface.coefficients_mm",
            "38 terms",
            "at most 37 for fringe",
        ),
        (
            format!(
                r#"{{"type":"zernike","convention":"standard","base":{{"radius_mm":50}},"norm_radius_mm":5,"coefficients_mm":[{}]}}"#,
                zeros(232)
            ),
            "surface.coefficients_mm",
            "232 terms",
            "at most 231 for standard",
        ),
        (
            r#"{"type":"zernike","convention":"standard","base":{"radius_mm":50},"norm_radius_mm":0,"coefficients_mm":[]}"#.to_string(),
            "surface.norm_radius_mm",
            "0",
            "must be a length of at least 1e-6 mm",
        ),
        (
            r#"{"type":"zernike","convention":"fringe","base":{"radius_mm":50},"norm_radius_mm":-2,"coefficients_mm":[1e-3]}"#.to_string(),
            "surface.norm_radius_mm",
            "-2",
            "must be a length of at least 1e-6 mm",
        ),
        (
            r#"{"type":"zernike","convention":"fringe","base":{"conic":-1},"norm_radius_mm":2,"coefficients_mm":[]}"#.to_string(),
            "surface.base.radius_mm",
            "missing",
            "give radius_mm",
        ),
    ];
    for (json, field, value, allowed) in cases {
        let e = field_error(&json);
        assert_eq!(e.field, field, "{json}: {e}");
        assert_eq!(e.value, value, "{json}: {e}");
        assert!(e.allowed.starts_with(allowed), "{json}: {e}");
    }
    // 37 Fringe and 231 Standard terms are fine.
    for (conv, k) in [("fringe", 37), ("standard", 231)] {
        let json = format!(
            r#"{{"type":"zernike","convention":"{conv}","base":{{"radius_mm":50}},"norm_radius_mm":5,"coefficients_mm":[{}]}}"#,
            zeros(k)
        );
        let spec: SurfaceSpec = serde_json::from_str(&json).unwrap();
        assert!(spec.build(5.0).is_ok(), "{conv} {k}");
    }
    // The convention must be named, and only the two are known.
    for (json, needle) in [
        (
            r#"{"type":"zernike","base":{"radius_mm":50},"norm_radius_mm":5,"coefficients_mm":[]}"#,
            "missing field `convention`",
        ),
        (
            r#"{"type":"zernike","convention":"noll","base":{"radius_mm":50},"norm_radius_mm":5,"coefficients_mm":[]}"#,
            "unknown variant `noll`",
        ),
        (
            r#"{"type":"zernike","convention":"ansi","base":{"radius_mm":50},"norm_radius_mm":5,"coefficients_mm":[]}"#,
            "expected `standard` or `fringe`",
        ),
        (
            r#"{"type":"zernike","convention":"fringe","base":{"radius_mm":50},"norm_radius_mm":5,"coefficients":[]}"#,
            "unknown field `coefficients`",
        ),
    ] {
        let e = serde_json::from_str::<SurfaceSpec>(json)
            .unwrap_err()
            .to_string();
        assert!(e.contains(needle), "{json}: {e}");
    }
    // Non-finite coefficients (only through the Rust API) name their index and term.
    let e = Zernike::new(
        &ZernikeSpec {
            convention: Convention::Fringe,
            base: plane(),
            norm_radius_mm: 2.0,
            coefficients_mm: vec![0.0, 0.0, 0.0, 0.0, f64::INFINITY],
        },
        PartDisc::centred(2.0),
    )
    .unwrap_err();
    assert_eq!(e.field, "coefficients_mm[4] (Z5)");
    assert_eq!(e.value, "inf");
}

#[test]
fn the_documentation_tables_match_the_definitions() {
    // crate/docs/zernike.md lists j, n, m and the angular factor of every Standard term up to
    // j = 66 and of all 37 Fringe terms; they must agree with the lists enumerated above.
    let path = format!("{}/../crate/docs/zernike.md", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut section = "";
    let mut rows: Vec<(&str, usize, usize, usize, &str)> = Vec::new();
    for line in text.lines() {
        if line.starts_with("## ") {
            section = line;
        }
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() < 6 {
            continue;
        }
        let (Ok(j), Ok(n), Ok(m)) = (
            cells[1].parse::<usize>(),
            cells[2].parse::<usize>(),
            cells[3].parse::<usize>(),
        ) else {
            continue;
        };
        rows.push((section, j, n, m, cells[4]));
    }
    let mut counts = [0, 0];
    for (section, j, n, m, angle) in rows {
        let (list, which) = if section.contains("Standard") {
            (noll_list(), 0)
        } else if section.contains("Fringe") {
            (fringe_list(), 1)
        } else {
            panic!("table row outside a Standard or Fringe section: {section}");
        };
        let (ln, lm, la) = list[j - 1];
        let la = match la {
            Angle::Symmetric => "—",
            Angle::Cos => "cos",
            Angle::Sin => "sin",
        };
        assert_eq!((n, m, angle), (ln, lm, la), "{section}: j {j}");
        assert_eq!(j, counts[which] + 1, "{section}: rows in order");
        counts[which] += 1;
    }
    assert!(counts[0] >= 37, "{counts:?}");
    assert_eq!(counts[1], 37);
}

#[test]
fn planned_paths_touch_without_cutting() {
    // Few-µm astigmatism, coma, trefoil and spherical terms on a sphere and on a plane: slopes
    // below 0.1 and curvatures below 0.1 mm⁻¹ keep the sampling bound of 2000 nose-angle steps
    // (K·Δa²/8 with K ≤ 0.13 mm, Δa = 1.75/2000) near 0.012 nm, under the 0.02 nm asserted.
    let none = |_: f64, _: f64| Vec::new();
    let standard = small_job(
        "zernike-standard",
        r#"{"type":"zernike","convention":"standard","base":{"radius_mm":-30},"norm_radius_mm":1.5,
            "coefficients_mm":[0,0,0,0,0.002,-0.003,0.0015,0,0.002,0,0.001]}"#,
        3.0,
    );
    let fringe = small_job(
        "zernike-fringe",
        r#"{"type":"zernike","convention":"fringe","base":{"curvature_per_mm":0},"norm_radius_mm":1.5,
            "coefficients_mm":[0,0.001,0,0,0.003,0,0,-0.002,0,0.002,0,0,0,0,0,0.0005]}"#,
        3.0,
    );
    for j in [standard, fringe] {
        let n = check_planned_path(&j, &none, 2000);
        assert!(n > 200, "{n} points");
    }
}

#[test]
fn the_example_jobs_build() {
    check_example_jobs(&[
        ("zernike-standard.json", "Standard (Noll"),
        ("zernike-fringe.json", "Fringe"),
    ]);
}
