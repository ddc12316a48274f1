//! The Chebyshev surface through the public API: sag against the trigonometric closed form of
//! the Chebyshev polynomials (Tₙ(t) = cos(n·arccos t) inside [−1, 1], ±cosh(n·arccosh |t|)
//! outside, where the surface continues), gradient and Hessian against central differences
//! (proptest), the default half-widths and the warning of a part beyond them, errors, and a
//! planned path through the gouge check.

mod common;

use common::{check_derivatives, check_example_jobs, check_planned_path, config, field_error};
use proptest::prelude::*;
use spiralcam::surface::chebyshev::ChebyshevTerm;
use spiralcam::surface::{AsphereSpec, Chebyshev, ChebyshevSpec, PartDisc, Surface};

/// Seed of this file's property tests.
const SEED: u64 = 1410;

/// Tₙ(t) by the trigonometric and hyperbolic forms.
fn t_closed(n: u32, t: f64) -> f64 {
    let n = n as f64;
    if t.abs() <= 1.0 {
        (n * t.acos()).cos()
    } else {
        let sign = if t < 0.0 && n % 2.0 == 1.0 { -1.0 } else { 1.0 };
        sign * (n * t.abs().acosh()).cosh()
    }
}

fn build(radius: f64, hx: f64, hy: f64, terms: &[(u32, u32, f64)]) -> Chebyshev {
    Chebyshev::new(
        &ChebyshevSpec {
            base: AsphereSpec {
                radius_mm: Some(radius),
                ..Default::default()
            },
            half_width_x_mm: Some(hx),
            half_width_y_mm: Some(hy),
            terms: terms
                .iter()
                .map(|&(x, y, c)| ChebyshevTerm {
                    x,
                    y,
                    coefficient_mm: c,
                })
                .collect(),
        },
        PartDisc::centred(hx.min(hy)),
    )
    .expect("valid Chebyshev surface")
}

/// Up to 12 terms of orders ≤ 14 (OpticStudio's range) of at most 5 µm.
fn terms() -> impl Strategy<Value = Vec<(u32, u32, f64)>> {
    prop::collection::vec((0u32..=14, 0u32..=14, -5e-3..5e-3f64), 1..12).prop_map(|raw| {
        let mut out: Vec<(u32, u32, f64)> = Vec::new();
        for t in raw {
            if !out.iter().any(|u| u.0 == t.0 && u.1 == t.1) {
                out.push(t);
            }
        }
        out
    })
}

proptest! {
    #![proptest_config(config(128, SEED))]

    #[test]
    fn sag_is_the_base_plus_the_products(
        radius in prop_oneof![20.0..200.0f64, -200.0..-20.0f64],
        hx in 2.0..8.0f64,
        hy in 2.0..8.0f64,
        terms in terms(),
        (u, v) in (-1.1..1.1f64, -1.1..1.1f64),
    ) {
        let s = build(radius, hx, hy, &terms);
        let (x, y) = (u * hx, v * hy);
        let r2 = x * x + y * y;
        let c = 1.0 / radius;
        let base = c * r2 / (1.0 + (1.0 - c * c * r2).sqrt());
        let sum: f64 = terms.iter().map(|&(i, j, k)| k * t_closed(i, u) * t_closed(j, v)).sum();
        let got = s.sag(x, y).unwrap();
        // |Tₙ| ≤ 1 inside and ≤ cosh(14·acosh 1.1) ≈ 1e4 at 1.1: the recurrence and the closed
        // forms differ by rounding, ~1e-15 of the largest product inside, 1e-11 outside.
        let scale = terms.iter().map(|t| t.2.abs()).sum::<f64>();
        let tol = if u.abs() <= 1.0 && v.abs() <= 1.0 { 1e-13 * scale } else { 1e-9 * scale };
        prop_assert!((got - base - sum).abs() <= tol + 1e-15, "{} vs {}", got, base + sum);
    }

    #[test]
    fn derivatives_match_finite_differences(
        radius in prop_oneof![20.0..200.0f64, -200.0..-20.0f64],
        hx in 2.0..8.0f64,
        hy in 2.0..8.0f64,
        terms in terms(),
        pts in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 4),
    ) {
        let s = build(radius, hx, hy, &terms);
        for (u, v) in pts {
            check_derivatives(&s, u * hx, v * hy)?;
        }
    }
}

#[test]
fn half_widths_default_to_the_part_and_a_larger_part_is_a_warning() {
    let json = r#"{"type":"chebyshev","base":{"curvature_per_mm":0},"terms":[{"x":2,"y":3,"coefficient_mm":0.001}]}"#;
    let spec: spiralcam::surface::SurfaceSpec = serde_json::from_str(json).unwrap();
    let s = spec.build(4.0).unwrap();
    // X0 = Y0 = 4: at (4, −4) both normalised coordinates are ±1, T2(1)·T3(−1) = −1.
    assert!((s.sag(4.0, -4.0).unwrap() + 0.001).abs() < 1e-16);
    assert!(s.warnings().is_empty());
    let narrow =
        r#"{"type":"chebyshev","base":{"curvature_per_mm":0},"half_width_x_mm":3,"terms":[]}"#;
    let spec: spiralcam::surface::SurfaceSpec = serde_json::from_str(narrow).unwrap();
    let w = spec.build(4.0).unwrap().warnings();
    assert_eq!(w.len(), 1);
    assert!(w[0].contains("|x/X0| = 1.3333, |y/Y0| = 1.0000"), "{w:?}");
}

#[test]
fn bad_parameters_name_their_field() {
    let cases = [
        (
            r#"{"type":"chebyshev","base":{"radius_mm":50},"terms":[{"x":21,"y":0,"coefficient_mm":1}]}"#,
            "surface.terms[0].x",
            "21",
        ),
        (
            r#"{"type":"chebyshev","base":{"radius_mm":50},"terms":[{"x":1,"y":2,"coefficient_mm":1},{"x":1,"y":2,"coefficient_mm":2}]}"#,
            "surface.terms[1]",
            "x1 y2",
        ),
        (
            r#"{"type":"chebyshev","base":{"radius_mm":50},"half_width_y_mm":-1,"terms":[]}"#,
            "surface.half_width_y_mm",
            "-1",
        ),
        (
            r#"{"type":"chebyshev","base":{"radius_mm":0},"terms":[]}"#,
            "surface.base.radius_mm",
            "0",
        ),
    ];
    for (json, field, value) in cases {
        let e = field_error(json);
        assert_eq!((e.field.as_str(), e.value.as_str()), (field, value), "{e}");
    }
}

#[test]
fn a_planned_path_touches_without_cutting() {
    // A few µm of T2, T3 products on a sphere, Ø3 part (X0 = Y0 = 1.5): slopes below 0.05.
    let job = r#"{"name":"chebyshev","part":{"diameter_mm":3},
        "surface":{"type":"chebyshev","base":{"radius_mm":-40},"terms":[
            {"x":2,"y":0,"coefficient_mm":0.002},{"x":1,"y":2,"coefficient_mm":-0.0015},
            {"x":3,"y":3,"coefficient_mm":0.0005}]},
        "tool":{"nose_radius_mm":0.1,"included_angle_deg":100},"machine":{"spindle_rpm":300},
        "strategy":{"feed_mm_per_rev":0.15,"sampling":{"type":"constant_angle","points_per_rev":24}}}"#;
    let none = |_: f64, _: f64| Vec::new();
    assert!(check_planned_path(job, &none, 2000) > 200);
}

#[test]
fn the_example_job_builds() {
    check_example_jobs(&[("chebyshev-freeform.json", "Chebyshev polynomial, X0 6 mm")]);
}
