//! The odd asphere through the public API: sag against the definition written out (the conic's
//! closed form plus `Σ βₙ·rⁿ` by `powi`), OpticStudio's term order, gradient and Hessian
//! against central differences (proptest; at least 0.1 mm from the apex of a β1 cone, whose
//! derivatives grow like β1/rⁿ⁻¹ there: the differences' error h²/6·β1/r³ stays below 2e-9 at
//! 0.1 mm), the apex reported as a slope kink, errors, and planned
//! paths through the gouge check, with and without the cone.

mod common;

use common::{
    check_derivatives, check_example_jobs, check_planned_path, config, field_error, small_job,
};
use proptest::prelude::*;
use spiralcam::surface::{Line, OddAsphere, OddAsphereSpec, Surface};
use std::f64::consts::PI;

/// Seed of this file's property tests.
const SEED: u64 = 1008;

/// The definition written out.
fn reference(c: f64, k: f64, beta: &[f64], x: f64, y: f64) -> f64 {
    let r2 = x * x + y * y;
    let r = r2.sqrt();
    let conic = c * r2 / (1.0 + (1.0 - (1.0 + k) * c * c * r2).sqrt());
    conic
        + beta
            .iter()
            .enumerate()
            .map(|(i, b)| b * r.powi(i as i32 + 1))
            .sum::<f64>()
}

fn build(radius: f64, conic: f64, beta: &[f64]) -> OddAsphere {
    OddAsphere::new(&OddAsphereSpec {
        radius_mm: Some(radius),
        curvature_per_mm: None,
        conic,
        coefficients: beta.to_vec(),
    })
    .expect("valid odd asphere")
}

/// β1 … β8 of at most 20 µm each at r = 5 mm (OpticStudio's eight terms).
fn betas() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-1.0..1.0f64, 1..=8).prop_map(|v| {
        v.iter()
            .enumerate()
            .map(|(i, t)| t * 0.02 / 5f64.powi(i as i32 + 1))
            .collect()
    })
}

proptest! {
    #![proptest_config(config(128, SEED))]

    #[test]
    fn sag_is_the_conic_plus_every_power(
        radius in prop_oneof![10.0..200.0f64, -200.0..-10.0f64],
        conic in -3.0..1.0f64,
        beta in betas(),
        t in 0.0..1.0f64,
        phi in 0.0..2.0 * PI,
    ) {
        let s = build(radius, conic, &beta);
        let r = 5.0 * t.sqrt();
        let (x, y) = (r * phi.cos(), r * phi.sin());
        let want = reference(1.0 / radius, conic, &beta, x, y);
        let got = s.sag(x, y).unwrap();
        // Terms up to 20 µm and a conic sag below 1.3 mm summed in another order: a few ulps.
        prop_assert!((got - want).abs() <= 1e-15 + 4e-16 * want.abs(), "{got} vs {want}");
    }

    #[test]
    fn derivatives_match_finite_differences(
        radius in prop_oneof![10.0..200.0f64, -200.0..-10.0f64],
        conic in -3.0..1.0f64,
        beta in betas(),
        pts in prop::collection::vec((0.1..5.0f64, 0.0..2.0 * PI), 4),
    ) {
        let s = build(radius, conic, &beta);
        for (r, phi) in pts {
            check_derivatives(&s, r * phi.cos(), r * phi.sin())?;
        }
    }
}

#[test]
fn terms_follow_opticstudios_order() {
    // The public reader's check of ODDASPHE: CURV 0, PARM 1 0.002, PARM 2 -3e-6 → 0.009925 mm at
    // (3, 4); and β3 alone is r³.
    let plane = |beta: Vec<f64>| {
        OddAsphere::new(&OddAsphereSpec {
            curvature_per_mm: Some(0.0),
            coefficients: beta,
            ..Default::default()
        })
        .unwrap()
    };
    assert!((plane(vec![0.002, -3e-6]).sag(3.0, 4.0).unwrap() - 0.009925).abs() < 1e-15);
    assert!((plane(vec![0.0, 0.0, 1e-4]).sag(3.0, 4.0).unwrap() - 0.0125).abs() < 1e-15);
    // Without β1 the axis is smooth: r² and r³ are C² there (the Hessian of β2·r² is 2β2).
    let l = plane(vec![0.0, 1e-3, 2e-4]).local(0.0, 0.0).unwrap();
    assert_eq!(
        (l.zx, l.zy, l.zxx, l.zxy, l.zyy),
        (0.0, 0.0, 2e-3, 0.0, 2e-3)
    );
    // With β1 the apex is a kink on every section through the axis, at its parameter.
    let cone = plane(vec![1e-3]);
    let mut kinks = Vec::new();
    cone.slope_kinks(
        Line {
            x0: -3.0,
            y0: -4.0,
            c: 0.6,
            s: 0.8,
        },
        0.0,
        10.0,
        &mut kinks,
    );
    assert_eq!(kinks.len(), 1);
    assert!((kinks[0] - 5.0).abs() < 1e-15);
}

#[test]
fn bad_parameters_name_their_field() {
    let zeros = vec!["0"; 31].join(",");
    let cases = [
        (
            format!(r#"{{"type":"odd_asphere","radius_mm":50,"coefficients":[{zeros}]}}"#),
            "surface.coefficients",
            "31 terms",
        ),
        (
            r#"{"type":"odd_asphere","radius_mm":0}"#.to_string(),
            "surface.radius_mm",
            "0",
        ),
        (
            r#"{"type":"odd_asphere","conic":-1}"#.to_string(),
            "surface.radius_mm",
            "missing",
        ),
    ];
    for (json, field, value) in cases {
        let e = field_error(&json);
        assert_eq!((e.field.as_str(), e.value.as_str()), (field, value), "{e}");
    }
    let e = build(5.0, 0.0, &[]).local(4.0, 4.0).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("surface: odd asphere is undefined at radius"),
        "{e}"
    );
}

#[test]
fn planned_paths_touch_without_cutting() {
    // Smooth: r³ and r⁵ terms on a sphere. With a cone (β1 = 2e-3, a 0.11° slope): its apex is
    // the kink at ρ = 0 of every radial section, sampled as such.
    let none = |_: f64, _: f64| Vec::new();
    let smooth = small_job(
        "odd-smooth",
        r#"{"type":"odd_asphere","radius_mm":-40,"coefficients":[0,0,4e-4,0,-2e-5]}"#,
        3.0,
    );
    assert!(check_planned_path(&smooth, &none, 2000) > 200);
    let apex = |_: f64, _: f64| vec![0.0];
    let cone = small_job(
        "odd-cone",
        r#"{"type":"odd_asphere","radius_mm":60,"coefficients":[2e-3,0,1e-4]}"#,
        3.0,
    );
    assert!(check_planned_path(&cone, &apex, 2000) > 200);
    // A cone whose apex is a ridge (β1 < 0): the section bounds hold, so the contact is found
    // by the concave shortcut, the apex probed on either side.
    let ridge = small_job(
        "odd-ridge",
        r#"{"type":"odd_asphere","radius_mm":60,"coefficients":[-2e-3,0,1e-4]}"#,
        3.0,
    );
    assert!(check_planned_path(&ridge, &apex, 2000) > 200);
}

#[test]
fn the_example_job_builds() {
    check_example_jobs(&[("odd-asphere.json", "odd asphere R 50 mm")]);
}
