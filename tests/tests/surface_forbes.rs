//! Forbes' Q polynomials and the `q_bfs`, `q_con` and `q_2d` surfaces through the public API.
//!
//! - The polynomials (`q_polynomials`, Forbes' recurrences) against an independent construction
//!   from their definitions: exact Gram–Schmidt in rational arithmetic for m = 0 … 4, n = 0 … 6
//!   (`tests/bench/qpoly_reference.py`, whose values also agree with prysm's implementation to
//!   4e-15; fixture `tests/golden/qpoly_reference.json`), values and first derivatives within
//!   1e-12 (relative to 1 + |value|: the recurrences and the rational reference differ by
//!   rounding only, 6e-15 seen).
//! - The first terms as closed forms: Qbfs₀, Qbfs₁, Qbfs₄ and Qcon₀ … Qcon₄ as printed in Forbes
//!   2007 (as we recall them; each also agrees with the reference), Qbfs₂, Qbfs₃ and Q₀ᵐ, Q₁ᵐ
//!   (m = 1, 2) written out from the definition's normalisation (the paper's printed forms of
//!   these could not be consulted here).
//! - Orthonormality by exact quadrature for orders up to 30: Qbfs in slope and Qₙᵐ in
//!   gradient with the weight 1/√(1 − u²) (Gauss–Chebyshev: u = sin t, equal steps in t).
//! - The surfaces' sag against the closed forms (sphere or conic plus the departure written out),
//!   gradient and Hessian against central differences (proptest), errors, feature lengths
//!   against the slope reversals of every term, and planned paths through the gouge check.

mod common;

use common::{
    check_derivatives, check_example_jobs, check_planned_path, config, field_error, gauss_legendre,
    small_job,
};
use proptest::prelude::*;
use spiralcam::job::Job;
use spiralcam::plan::Planner;
use spiralcam::surface::q_2d::Q2dTerm;
use spiralcam::surface::q_polynomials::{MAX_ORDER, QSum, q2d, qbfs, qcon};
use spiralcam::surface::{Q2d, Q2dSpec, QBfs, QBfsSpec, QCon, QConSpec, Surface};
use std::f64::consts::PI;

/// Seed of this file's property tests.
const SEED: u64 = 2007;

// ---------------------------------------------------------------------------------------------
// The polynomials

/// One row of the fixture: family, m, n, Q(x) and dQ/dx(x) at the fixture's x.
type Row = (&'static str, usize, usize, Vec<f64>, Vec<f64>);

/// The fixture: x values and its rows.
struct Reference {
    x: Vec<f64>,
    rows: Vec<Row>,
}

fn reference() -> Reference {
    let path = format!("{}/golden/qpoly_reference.json", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let v: serde_json::Value = serde_json::from_str(&text).expect("fixture JSON");
    let list = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .expect("a list")
            .iter()
            .map(|x| x.as_f64().expect("a number"))
            .collect()
    };
    let mut rows = Vec::new();
    for family in ["qbfs", "qcon", "q2d"] {
        for row in v[family].as_array().expect("rows") {
            let m = row["m"].as_u64().unwrap_or(0) as usize;
            let n = row["n"].as_u64().expect("n") as usize;
            rows.push((family, m, n, list(&row["q"]), list(&row["dq_dx"])));
        }
    }
    Reference {
        x: list(&v["x"]),
        rows,
    }
}

#[test]
fn polynomials_match_the_gram_schmidt_reference() {
    let r = reference();
    // Every (m, n) of the brief: m = 0 … 4 (m = 0 is Qbfs), n = 0 … 6, and Qcon n = 0 … 6.
    assert_eq!(r.rows.len(), 7 + 7 + 4 * 7);
    for (family, m, n, q, dq) in &r.rows {
        for (k, &x) in r.x.iter().enumerate() {
            let got = match *family {
                "qbfs" => qbfs(*n, x),
                "qcon" => qcon(*n, x),
                _ => q2d(*m, *n, x),
            };
            for (what, g, want) in [("Q", got[0], q[k]), ("dQ/dx", got[1], dq[k])] {
                assert!(
                    (g - want).abs() <= 1e-12 * (1.0 + want.abs()),
                    "{family} m {m} n {n} {what} at x {x}: {g} vs {want}"
                );
            }
        }
    }
}

#[test]
fn first_terms_match_their_closed_forms() {
    // Forbes 2007: Qbfs₀ = 1, Qbfs₁ = (13 − 16x)/√19, Qbfs₄ = [7737 − 16x(4653 − 2x(7381 −
    // 8x(1168 − 509x)))]/(3√131831); Qbfs₂ and Qbfs₃ from the definition (exact Gram–Schmidt:
    // norms² 5/608 and 509/655360 of the monic polynomials).
    let bfs: [fn(f64) -> f64; 5] = [
        |_| 1.0,
        |x| (13.0 - 16.0 * x) / 19f64.sqrt(),
        |x| (29.0 - 4.0 * x * (25.0 - 19.0 * x)) / 47.5f64.sqrt(),
        |x| (207.0 - 4.0 * x * (315.0 - x * (577.0 - 320.0 * x))) / 1272.5f64.sqrt(),
        |x| {
            (7737.0 - 16.0 * x * (4653.0 - 2.0 * x * (7381.0 - 8.0 * x * (1168.0 - 509.0 * x))))
                / (3.0 * 131831f64.sqrt())
        },
    ];
    // Forbes 2007: Qcon₀ … Qcon₄.
    let con: [fn(f64) -> f64; 5] = [
        |_| 1.0,
        |x| -(5.0 - 6.0 * x),
        |x| 15.0 - 14.0 * x * (3.0 - 2.0 * x),
        |x| -(35.0 - 12.0 * x * (14.0 - x * (21.0 - 10.0 * x))),
        |x| 70.0 - 3.0 * x * (168.0 - 5.0 * x * (84.0 - 11.0 * x * (8.0 - 3.0 * x))),
    ];
    // Qₙᵐ for n = 0, 1 from the definition: Q₀¹ = 1, Q₁¹ = √(8/7)(1 − x), Q₀² = 1/√2,
    // Q₁² = (9 − 8x)/√38.
    type Closed = (usize, usize, fn(f64) -> f64);
    let freeform: [Closed; 4] = [
        (1, 0, |_| 1.0),
        (1, 1, |x| (8.0f64 / 7.0).sqrt() * (1.0 - x)),
        (2, 0, |_| 0.5f64.sqrt()),
        (2, 1, |x| (9.0 - 8.0 * x) / 38f64.sqrt()),
    ];
    for &x in &[0.0, 0.1, 0.33, 0.5, 0.8, 1.0, 1.25] {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * (1.0 + b.abs());
        for (n, f) in bfs.iter().enumerate() {
            assert!(close(qbfs(n, x)[0], f(x)), "Qbfs{n} at {x}");
        }
        for (n, f) in con.iter().enumerate() {
            assert!(close(qcon(n, x)[0], f(x)), "Qcon{n} at {x}");
        }
        for &(m, n, f) in &freeform {
            assert!(close(q2d(m, n, x)[0], f(x)), "Q{n}^{m} at {x}");
        }
    }
}

/// Gauss–Chebyshev nodes of (2/π)∫₀¹ g(u) du/√(1 − u²) = mean over t ∈ (0, π/2) of g(sin t):
/// equal steps in t, exact for the even polynomials in u of degree < 4·K here.
fn chebyshev_nodes(k: usize) -> Vec<f64> {
    (0..k)
        .map(|i| ((i as f64 + 0.5) * PI / 2.0 / k as f64).sin())
        .collect()
}

/// The radial slope of a term and its angular part: for m = 0, d/du [u²(1 − u²)Q(u²)]; for
/// m ≥ 1, (d/du [u^m Q(u²)], m·u^(m−1)·Q(u²)).
fn gradient_parts(m: usize, n: usize, u: f64) -> (f64, f64) {
    let x = u * u;
    let [q, dq, _] = q2d(m, n, x);
    if m == 0 {
        (2.0 * u * ((1.0 - 2.0 * x) * q + x * (1.0 - x) * dq), 0.0)
    } else {
        let um1 = u.powi(m as i32 - 1);
        let mf = m as f64;
        (um1 * (mf * q + 2.0 * x * dq), mf * um1 * q)
    }
}

#[test]
fn the_polynomials_are_orthonormal_to_order_30() {
    // Qbfs: <f, g> = (2/π)∫ f′g′ du/√(1 − u²); Qₙᵐ: the mean over θ of ∇f·∇g with the same
    // weight, ½[f′g′ + m²fg/u²] for the radial parts. Terms up to degree 2·30 + 30 in u, so 200
    // nodes are exact (to rounding, ~1e-13 seen).
    let nodes = chebyshev_nodes(200);
    let orders = [0, 1, 2, 5, 11, 20, MAX_ORDER];
    for m in [0, 1, 2, 3, 7, 16, MAX_ORDER] {
        for &n1 in &orders {
            for &n2 in &orders {
                let mean: f64 = nodes
                    .iter()
                    .map(|&u| {
                        let (a1, a2) = gradient_parts(m, n1, u);
                        let (b1, b2) = gradient_parts(m, n2, u);
                        if m == 0 {
                            a1 * b1
                        } else {
                            0.5 * (a1 * b1 + a2 * b2)
                        }
                    })
                    .sum::<f64>()
                    / nodes.len() as f64;
                let want = if n1 == n2 { 1.0 } else { 0.0 };
                assert!(
                    (mean - want).abs() < 1e-11,
                    "m {m}, n {n1} and {n2}: {mean}"
                );
            }
        }
    }
    // Qcon: ∫₀¹ x⁴·Qₘ·Qₙ dx = δ/(2n + 5) (the Jacobi norm for α = 0, β = 4 on [0, 1]), by
    // Gauss–Legendre with 40 nodes, exact to degree 79 ≥ 4 + 2·30.
    let gl = gauss_legendre(40);
    for n1 in [0, 1, 4, 9, 17, MAX_ORDER] {
        for n2 in [0, 1, 4, 9, 17, MAX_ORDER] {
            let integral: f64 = gl
                .iter()
                .map(|&(x, w)| w * x.powi(4) * qcon(n1, x)[0] * qcon(n2, x)[0])
                .sum();
            let want = if n1 == n2 {
                1.0 / (2.0 * n1 as f64 + 5.0)
            } else {
                0.0
            };
            assert!(
                (integral - want).abs() < 1e-12,
                "Qcon {n1} {n2}: {integral} vs {want}"
            );
        }
        assert!((qcon(n1, 1.0)[0] - 1.0).abs() < 1e-12);
    }
}

/// The radial factor f(u) = u^k·S(u²) of a term with S = `q`, and its slope for signed u:
/// `u^(k−1)·(k·S + 2x·S′)`.
fn slope_of(k: i32, q: &QSum, u: f64) -> f64 {
    let x = u * u;
    let [s, ds, _] = q.eval(x);
    u.powi(k - 1) * (k as f64 * s + 2.0 * x * ds)
}

#[test]
fn feature_lengths_stay_below_every_terms_slope_reversals() {
    // Along a section through the axis a term is f(u) = u²(1 − u²)Qbfsₙ(u²), u⁴Qconₙ(u²) or
    // u^m·Qₙᵐ(u²) (signed u); its slope changes sign no closer than the feature length
    // 1.5/d² (d its degree in u²; N = 1) on [−1, 1], sampled every 1e-4.
    let steps = 20_000;
    let check = |what: &str, d: f64, slope: &dyn Fn(f64) -> f64| {
        let mut last = f64::NEG_INFINITY;
        let mut prev = slope(-1.0);
        for i in 1..=steps {
            let u = -1.0 + 2.0 * i as f64 / steps as f64;
            let s = slope(u);
            if s * prev < 0.0 || (s == 0.0 && prev != 0.0) {
                assert!(u - last >= 1.5 / (d * d), "{what}: {last} → {u}");
                last = u;
            }
            prev = s;
        }
    };
    for n in 0..=MAX_ORDER {
        let mut unit = vec![0.0; n + 1];
        unit[n] = 1.0;
        let d = n as f64 + 2.0;
        // u²(1 − u²)·Q = u²·Q − u⁴·Q.
        let bfs = QSum::qbfs(&unit);
        check(&format!("Qbfs{n}"), d, &|u| {
            slope_of(2, &bfs, u) - slope_of(4, &bfs, u)
        });
        let con = QSum::qcon(&unit);
        check(&format!("Qcon{n}"), d, &|u| slope_of(4, &con, u));
        for m in [1, 2, 3, 6, 15, MAX_ORDER] {
            let q = QSum::q2d(m, &unit);
            let d = n as f64 + m as f64 / 2.0;
            check(&format!("Q{n}^{m}"), d, &|u| slope_of(m as i32, &q, u));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The surfaces' sag

fn q_bfs(radius: f64, norm: f64, a: &[f64]) -> QBfs {
    QBfs::new(&QBfsSpec {
        radius_mm: Some(radius),
        curvature_per_mm: None,
        norm_radius_mm: norm,
        coefficients_mm: a.to_vec(),
    })
    .expect("valid q_bfs")
}

fn q_con(radius: f64, conic: f64, norm: f64, a: &[f64]) -> QCon {
    QCon::new(&QConSpec {
        radius_mm: Some(radius),
        curvature_per_mm: None,
        conic,
        norm_radius_mm: norm,
        coefficients_mm: a.to_vec(),
    })
    .expect("valid q_con")
}

fn q_2d(radius: f64, norm: f64, terms: &[(u32, u32, f64, f64)]) -> Q2d {
    Q2d::new(&Q2dSpec {
        radius_mm: Some(radius),
        curvature_per_mm: None,
        norm_radius_mm: norm,
        terms: terms
            .iter()
            .map(|&(n, m, a, b)| Q2dTerm {
                n,
                m,
                a_mm: a,
                b_mm: b,
            })
            .collect(),
    })
    .expect("valid q_2d")
}

/// Points (x, y) inside 1.2·N, off every symmetry axis and on some.
fn points(norm: f64) -> Vec<(f64, f64)> {
    [
        (0.0, 0.0),
        (0.3, 0.4),
        (0.5, 1.9),
        (0.71, -2.4),
        (1.0, 0.0),
        (1.0, 2.0),
        (1.2, 4.0),
    ]
    .iter()
    .map(|&(u, phi)| (norm * u * f64::cos(phi), norm * u * f64::sin(phi)))
    .collect()
}

/// Sags of a few mm summed in different orders: a few ulps of the sphere's sag.
const SAG_TOL: f64 = 1e-13;

#[test]
fn q_bfs_is_the_sphere_plus_the_normal_departure() {
    let (radius, norm) = (-35.0, 6.0);
    let a = [0.02, -0.004, 0.0015, -0.0005, 0.0002];
    let s = q_bfs(radius, norm, &a);
    let c = 1.0 / radius;
    for (x, y) in points(norm) {
        let r2 = x * x + y * y;
        let phi = (1.0 - c * c * r2).sqrt();
        let sphere = c * r2 / (1.0 + phi);
        let xi = r2 / (norm * norm);
        let sum: f64 = a
            .iter()
            .enumerate()
            .map(|(n, an)| an * qbfs(n, xi)[0])
            .sum();
        let want = sphere + xi * (1.0 - xi) / phi * sum;
        let got = s.sag(x, y).unwrap();
        assert!((got - want).abs() < SAG_TOL, "({x}, {y}): {got} vs {want}");
    }
    // a0 alone at u = 1/√2 (x = 1/2): the departure is a0/4 along the normal, / φ in sag.
    let s = q_bfs(radius, norm, &[0.01]);
    let r2: f64 = norm * norm / 2.0;
    let phi = (1.0 - r2 / (radius * radius)).sqrt();
    let z = r2 / radius / (1.0 + phi) + 0.0025 / phi;
    assert!((s.sag(r2.sqrt(), 0.0).unwrap() - z).abs() < SAG_TOL);
}

#[test]
fn q_con_is_the_conic_plus_the_sag_departure() {
    let (radius, conic, norm) = (40.0, -1.7, 5.0);
    let a = [0.01, -0.003, 0.001, -0.0003, 0.0001];
    let s = q_con(radius, conic, norm, &a);
    let c = 1.0 / radius;
    for (x, y) in points(norm) {
        let r2 = x * x + y * y;
        let conic_sag = c * r2 / (1.0 + (1.0 - (1.0 + conic) * c * c * r2).sqrt());
        let xi = r2 / (norm * norm);
        let sum: f64 = a
            .iter()
            .enumerate()
            .map(|(n, an)| an * qcon(n, xi)[0])
            .sum();
        let want = conic_sag + xi * xi * sum;
        let got = s.sag(x, y).unwrap();
        assert!((got - want).abs() < SAG_TOL, "({x}, {y}): {got} vs {want}");
    }
    // At u = 1 every Qcon is 1: the departure is Σ aₙ.
    let edge = s.sag(norm, 0.0).unwrap();
    let conic_sag = c * 25.0 / (1.0 + (1.0 + 0.7 * c * c * 25.0).sqrt());
    assert!((edge - conic_sag - a.iter().sum::<f64>()).abs() < SAG_TOL);
}

#[test]
fn q_2d_terms_carry_their_angles_and_the_normal_factor() {
    let (radius, norm) = (60.0, 4.0);
    let terms = [
        (0, 0, 0.004, 0.0),
        (1, 0, -0.001, 0.0),
        (0, 1, 0.002, -0.001),
        (1, 1, 0.0007, 0.0),
        (0, 2, 0.003, 0.0),
        (1, 2, 0.0, 0.0008),
        (0, 3, 0.0005, 0.0004),
        (4, 3, -0.0002, 0.0001),
    ];
    let s = q_2d(radius, norm, &terms);
    let c = 1.0 / radius;
    for (x, y) in points(norm) {
        let r2 = x * x + y * y;
        let phi = (1.0 - c * c * r2).sqrt();
        let (u, theta) = (r2.sqrt() / norm, y.atan2(x));
        let xi = u * u;
        let bracket: f64 = terms
            .iter()
            .map(|&(n, m, a, b)| {
                let (n, m) = (n as usize, m as usize);
                let q = q2d(m, n, xi)[0];
                if m == 0 {
                    xi * (1.0 - xi) * a * q
                } else {
                    let mt = m as f64 * theta;
                    u.powi(m as i32) * (a * mt.cos() + b * mt.sin()) * q
                }
            })
            .sum();
        let want = c * r2 / (1.0 + phi) + bracket / phi;
        let got = s.sag(x, y).unwrap();
        assert!((got - want).abs() < SAG_TOL, "({x}, {y}): {got} vs {want}");
    }
    // Tilt Q₀¹ = 1 on a plane: z = a·x/N + b·y/N exactly, gradient (a, b)/N.
    let tilt = Q2d::new(&Q2dSpec {
        radius_mm: None,
        curvature_per_mm: Some(0.0),
        norm_radius_mm: 2.0,
        terms: vec![Q2dTerm {
            n: 0,
            m: 1,
            a_mm: 0.01,
            b_mm: -0.02,
        }],
    })
    .unwrap();
    let l = tilt.local(0.3, -0.7).unwrap();
    assert!((l.z - (0.01 * 0.15 - 0.02 * -0.35)).abs() < 1e-17);
    assert_eq!(
        (l.zx, l.zy, l.zxx, l.zxy, l.zyy),
        (0.005, -0.01, 0.0, 0.0, 0.0)
    );
}

#[test]
fn the_rim_of_the_sphere_is_an_error() {
    let e = q_bfs(5.0, 3.0, &[0.001]).local(3.0, 4.5).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("surface: Qbfs asphere is undefined"),
        "{e}"
    );
    let e = q_con(5.0, 0.5, 3.0, &[0.001]).local(4.5, 0.0).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("surface: Qcon asphere is undefined"),
        "{e}"
    );
    let e = q_2d(5.0, 3.0, &[(0, 2, 0.001, 0.0)])
        .local(0.0, 5.5)
        .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("surface: Q2D freeform is undefined"),
        "{e}"
    );
}

// ---------------------------------------------------------------------------------------------
// Derivatives

/// Coefficients of at most 20 µm, falling with the order (a smooth departure).
fn coefficients(max_len: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-1.0..1.0f64, 1..=max_len).prop_map(|v| {
        v.iter()
            .enumerate()
            .map(|(n, c)| c * 2e-2 / (1.0 + n as f64).powi(2))
            .collect()
    })
}

/// A point of the disc of radius 1.2·N.
fn disc_point(norm: f64, t: f64, phi: f64) -> (f64, f64) {
    let r = 1.2 * norm * t.sqrt();
    (r * phi.cos(), r * phi.sin())
}

proptest! {
    #![proptest_config(config(96, SEED))]

    #[test]
    fn q_bfs_derivatives_match_finite_differences(
        radius in prop_oneof![20.0..200.0f64, -200.0..-20.0f64],
        norm in 1.0..6.0f64,
        a in coefficients(12),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 4),
    ) {
        let s = q_bfs(radius, norm, &a);
        for (t, phi) in pts {
            let (x, y) = disc_point(norm, t, phi);
            check_derivatives(&s, x, y)?;
        }
    }

    #[test]
    fn q_con_derivatives_match_finite_differences(
        radius in prop_oneof![20.0..200.0f64, -200.0..-20.0f64],
        conic in -3.0..1.0f64,
        norm in 1.0..6.0f64,
        a in coefficients(12),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 4),
    ) {
        let s = q_con(radius, conic, norm, &a);
        for (t, phi) in pts {
            let (x, y) = disc_point(norm, t, phi);
            check_derivatives(&s, x, y)?;
        }
    }

    #[test]
    fn q_2d_derivatives_match_finite_differences(
        radius in prop_oneof![20.0..200.0f64, -200.0..-20.0f64],
        norm in 1.0..6.0f64,
        raw in prop::collection::vec((0u32..8, 0u32..7, -1.0..1.0f64, -1.0..1.0f64), 1..10),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 4),
    ) {
        let mut terms: Vec<(u32, u32, f64, f64)> = Vec::new();
        for (n, m, a, b) in raw {
            if !terms.iter().any(|t| t.0 == n && t.1 == m) {
                let scale = 5e-3 / (1.0 + (n + m) as f64).powi(2);
                terms.push((n, m, a * scale, if m == 0 { 0.0 } else { b * scale }));
            }
        }
        let s = q_2d(radius, norm, &terms);
        for (t, phi) in pts {
            let (x, y) = disc_point(norm, t, phi);
            check_derivatives(&s, x, y)?;
        }
        // On the axis too, where the harmonic derivatives are exact.
        check_derivatives(&s, 0.0, 0.0)?;
    }
}

// ---------------------------------------------------------------------------------------------
// Errors, jobs

#[test]
fn bad_parameters_name_their_field() {
    let zeros = |k: usize| vec!["0"; k].join(",");
    let cases: Vec<(String, &str, &str)> = vec![
        (
            format!(
                r#"{{"type":"q_bfs","radius_mm":50,"norm_radius_mm":5,"coefficients_mm":[{}]}}"#,
                zeros(32)
            ),
            "surface.coefficients_mm",
            "at most 31 terms",
        ),
        (
            r#"{"type":"q_bfs","radius_mm":50,"curvature_per_mm":0.02,"norm_radius_mm":5,"coefficients_mm":[]}"#.into(),
            "surface.radius_mm",
            "give radius_mm or curvature_per_mm, not both",
        ),
        (
            r#"{"type":"q_con","radius_mm":50,"norm_radius_mm":0,"coefficients_mm":[]}"#.into(),
            "surface.norm_radius_mm",
            "must be a finite number > 0",
        ),
        (
            r#"{"type":"q_con","norm_radius_mm":3,"coefficients_mm":[]}"#.into(),
            "surface.radius_mm",
            "give radius_mm or curvature_per_mm",
        ),
        (
            r#"{"type":"q_2d","radius_mm":50,"norm_radius_mm":5,"terms":[{"n":31,"m":0,"a_mm":1e-3}]}"#.into(),
            "surface.terms[0].n",
            "must lie in 0 … 30",
        ),
        (
            r#"{"type":"q_2d","radius_mm":50,"norm_radius_mm":5,"terms":[{"n":1,"m":2,"a_mm":1e-3},{"n":1,"m":2,"b_mm":1e-3}]}"#.into(),
            "surface.terms[1]",
            "each (n, m) at most once",
        ),
        (
            r#"{"type":"q_2d","radius_mm":50,"norm_radius_mm":5,"terms":[{"n":1,"m":0,"b_mm":1e-3}]}"#.into(),
            "surface.terms[0].b_mm",
            "must be 0 for m = 0",
        ),
    ];
    for (json, field, allowed) in cases {
        let e = field_error(&json);
        assert_eq!(e.field, field, "{json}: {e}");
        assert!(e.allowed.starts_with(allowed), "{json}: {e}");
    }
    let e = QBfs::new(&QBfsSpec {
        radius_mm: Some(20.0),
        curvature_per_mm: None,
        norm_radius_mm: 2.0,
        coefficients_mm: vec![0.0, f64::NAN],
    })
    .unwrap_err();
    assert_eq!(e.field, "coefficients_mm[1] (a1)");
    for json in [
        r#"{"type":"q_2d","radius_mm":50,"norm_radius_mm":5,"terms":[{"n":1,"m":2,"c_mm":1}]}"#,
        r#"{"type":"q_bfs","radius_mm":50,"norm_radius_mm":5,"coefficients":[]}"#,
    ] {
        let e = serde_json::from_str::<spiralcam::surface::SurfaceSpec>(json).unwrap_err();
        assert!(e.to_string().contains("unknown field"), "{json}: {e}");
    }
}

#[test]
fn planned_paths_touch_without_cutting() {
    // Departures of a few µm on spheres of |R| ≥ 30 mm: slopes below 0.05 and curvatures below
    // 0.05 mm⁻¹ keep the sampling bound of 2000 nose-angle steps near 0.012 nm.
    let none = |_: f64, _: f64| Vec::new();
    let jobs = [
        small_job(
            "q-bfs",
            r#"{"type":"q_bfs","radius_mm":-30,"norm_radius_mm":1.5,"coefficients_mm":[0.003,-0.001,0.0005]}"#,
            3.0,
        ),
        small_job(
            "q-con",
            r#"{"type":"q_con","radius_mm":40,"conic":-2,"norm_radius_mm":1.5,"coefficients_mm":[0.002,0.001,-0.0005]}"#,
            3.0,
        ),
        small_job(
            "q-2d",
            r#"{"type":"q_2d","curvature_per_mm":0,"norm_radius_mm":1.5,"terms":[
                {"n":0,"m":0,"a_mm":0.002},{"n":0,"m":2,"a_mm":0.002,"b_mm":-0.001},
                {"n":1,"m":1,"a_mm":0.0008},{"n":0,"m":3,"b_mm":0.0006}]}"#,
            3.0,
        ),
    ];
    for j in jobs {
        // The surfaces' section bounds prove the nose height concave: the contacts come from
        // the concave shortcut (`Surface::section_bounds`), held to the same check.
        let planner = Planner::new(&Job::from_json(&j).unwrap()).unwrap();
        assert!(planner.path().concavity().is_some(), "{j}");
        let n = check_planned_path(&j, &none, 2000);
        assert!(n > 200, "{n} points");
    }
}

#[test]
fn the_example_jobs_build() {
    check_example_jobs(&[
        ("q-bfs.json", "Qbfs asphere (Forbes 2007)"),
        ("q-con.json", "Qcon asphere (Forbes 2007)"),
        ("q-2d-freeform.json", "Q2D freeform (Forbes 2012)"),
    ]);
}
