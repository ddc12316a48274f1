//! The predicted form (`spiralcam::analysis::predicted_form`) against closed forms and brute force.
//!
//! - **Cusp height on a flat.** Two nose arcs of radius r, f apart, at the same height cross
//!   `r − √(r² − f²/4) = f²/(8r)·(1 + f²/(16r²) + …)` above their bottoms: the median and the
//!   largest cusp equal that within 2e-5 relative (the median's histogram bin is 1.5e-5 wide; the
//!   valleys, refined by a parabola through three samples, are exact to ~h⁴/r³ ≈ 1e-10 mm), and
//!   f²/(8r) within 1 % (the series term is 0.06 % at f = 0.05, r = 0.5).
//! - **Cusp height on a sphere** of radius R (R > 0 concave): the nose centres lie f apart
//!   radially on the sphere of radius R − r, so the contacts lie f·R/(R − r) apart and the cusp
//!   is `f²/(8r)·R/(R − r)/cos³φ` to first order (φ the slope angle; `cos⁻³φ ≤ 1.0006` on the
//!   Ø2 mm parts used), times the flat's series factor: checked within 0.2 %. Against the plain
//!   f²/(8r) the cusp is within 1 % for R = −50 mm (−0.9 %) and R = ±100 mm, but for R = +50 mm,
//!   r = 0.5 mm it is 1.01 % above by geometry (R/(R − r) = 1.0101): asserted as such.
//! - **Why the linearization error plays no part there.** On a surface of revolution the
//!   compensated tip height is a function z(ρ) of the radius alone, and along a segment ρ is
//!   linear in θ (ρ = R − f·θ/2π exactly), so the interpolated ρ* is exact and the interpolated z*
//!   is off by the chord error `z″·(f/N)²/8` ≤ 0.02·(0.05/360)²/8 ≈ 5e-11 mm with N = 360, seven
//!   orders below the cusps checked.
//! - **PV, mean and RMS on a flat** against the periodic scallop `e(u) = r − √(r² − u²)`,
//!   |u| ≤ f/2: PV its sagitta, mean `r − S` and RMS about the mean `√(r² − f²/12 − S²)` with
//!   `S = (1/f)·∫√(r² − u²) du = [(f/2)·√(r² − f²/4) + r²·asin(f/2r)]/f`. The RMS and mean are
//!   area-weighted sums over the radial samples (16 per feed), whose phase against the passes
//!   shifts by f/angles from one half-plane to the next, so the quadrature error averages out:
//!   checked within 0.1 % (found ~1e-4).
//! - **Brute force**: on a freeform (sinusoid) with a coarse constant-angle path whose NC points
//!   lie off the grid, every sample of a few radial sections equals the lowest of ALL the path's
//!   arcs through that half-plane and its opposite, interpolated by a direct loop over the
//!   segments, within 1e-12 mm.
//! - Settings and jobs that cannot be predicted give field errors; random small jobs give finite
//!   results with PV, RMS ≥ 0 and overcut ≤ 0.

mod common;

use common::config;
use proptest::prelude::*;
use spiralcam::analysis::predicted_form::{
    FormSettings, PredictedForm, SectionSample, predict, predict_section,
};
use spiralcam::job::Job;
use spiralcam::path::PathError;
use spiralcam::plan::Planner;
use std::f64::consts::TAU;

/// Seed of this file's property tests.
const SEED: u64 = 4006;
/// Nose radius of the closed-form checks, mm.
const R_NOSE: f64 = 0.5;

/// A planner for `surface` on a Ø2 mm part, r = 0.5 mm, β = 100°, feed `f`, `strategy`
/// holding the rest of the strategy's fields.
fn planner(surface: &str, f: f64, strategy: &str) -> Planner {
    let json = format!(
        r#"{{"name":"form","part":{{"diameter_mm":2}},"surface":{surface},
            "tool":{{"nose_radius_mm":{R_NOSE}}},"machine":{{"spindle_rpm":1000}},
            "strategy":{{"feed_mm_per_rev":{f},{strategy}}}}}"#
    );
    let job = Job::from_json(&json).unwrap_or_else(|e| panic!("{json}: {e}"));
    Planner::new(&job).unwrap_or_else(|e| panic!("{json}: {e}"))
}

fn form(planner: &Planner, angles: usize) -> PredictedForm {
    let settings = FormSettings {
        angles,
        radial_step_mm: None,
    };
    predict(planner, &settings, 64, |_| {}).unwrap_or_else(|e| panic!("{e}"))
}

const FLAT: &str = r#"{"type":"asphere","curvature_per_mm":0}"#;
const CONSTANT_ANGLE: &str = r#""sampling":{"type":"constant_angle","points_per_rev":360}"#;

/// The sagitta of a chord f of the nose: the cusp between two arcs at the same height, mm.
fn sagitta(f: f64) -> f64 {
    R_NOSE - (R_NOSE * R_NOSE - f * f / 4.0).sqrt()
}

fn relative(got_um: f64, want_mm: f64) -> f64 {
    got_um / (1e3 * want_mm) - 1.0
}

#[test]
fn cusp_height_on_a_flat_is_the_sagitta_of_the_feed() {
    let strategies = [
        CONSTANT_ANGLE.to_string(),
        // Off the grid, clockwise, and by arc length: the passes are interpolated.
        r#""sampling":{"type":"constant_angle","points_per_rev":250},"direction":"cw","start_angle_deg":0.37"#
            .to_string(),
        r#""sampling":{"type":"constant_arc","arc_length_mm":0.02,"max_angle_step_deg":2}"#
            .to_string(),
    ];
    for f in [0.01, 0.02, 0.05] {
        for (k, strategy) in strategies.iter().enumerate() {
            if f == 0.01 && k > 0 {
                continue; // runtime: the interpolated variants at the two larger feeds
            }
            let p = form(&planner(FLAT, f, strategy), 120);
            let at = format!("f {f}, {strategy}: {p:?}");
            assert!(p.cusps > 1000, "{at}");
            assert!(relative(p.cusp_height_um, sagitta(f)).abs() < 2e-5, "{at}");
            assert!(
                relative(p.cusp_height_max_um, sagitta(f)).abs() < 2e-5,
                "{at}"
            );
            assert!(
                relative(p.cusp_height_um, f * f / (8.0 * R_NOSE)).abs() < 0.01,
                "{at}"
            );
            // The tip follows the plane exactly: no overcut beyond the valley refinement.
            assert!(p.max_overcut_um <= 0.0 && p.max_overcut_um > -1e-5, "{at}");
        }
    }
}

#[test]
fn pv_mean_and_rms_on_a_flat_are_those_of_the_periodic_scallop() {
    for f in [0.02, 0.05] {
        let p = form(&planner(FLAT, f, CONSTANT_ANGLE), 360);
        let r = R_NOSE;
        let s = ((f / 2.0) * (r * r - f * f / 4.0).sqrt() + r * r * (f / (2.0 * r)).asin()) / f;
        let mean = r - s;
        let rms = (r * r - f * f / 12.0 - s * s).sqrt();
        let at = format!("f {f}: {p:?}, mean {mean:e}, rms {rms:e}");
        assert!(relative(p.pv_um, sagitta(f)).abs() < 1e-6, "{at}");
        assert!(relative(p.mean_um, mean).abs() < 1e-3, "{at}");
        assert!(relative(p.rms_um, rms).abs() < 1e-3, "{at}");
        // The centre: the passes either side of the axis are up to 1.5 f apart.
        assert!(p.centre_pv_um > p.pv_um, "{at}");
        assert!(
            p.centre_pv_um <= 1e3 * sagitta(1.5 * f) * (1.0 + 1e-9),
            "{at}"
        );
    }
}

#[test]
fn cusp_height_on_spheres_follows_the_contact_spacing() {
    // (R, f, within 1 % of the plain f²/(8r)?)
    let cases = [
        (50.0, 0.01, false),
        (50.0, 0.05, false),
        (-50.0, 0.01, true),
        (-50.0, 0.02, true),
        (-50.0, 0.05, true),
        (100.0, 0.02, true),
        (-100.0, 0.05, true),
    ];
    for (big, f, plain) in cases {
        let surface = format!(r#"{{"type":"asphere","radius_mm":{big}}}"#);
        // Start off the grid: passes are interpolated.
        let strategy = format!("{CONSTANT_ANGLE},\"start_angle_deg\":0.7");
        let p = form(&planner(&surface, f, &strategy), 120);
        let corrected = sagitta(f) * big / (big - R_NOSE);
        let naive = relative(p.cusp_height_um, f * f / (8.0 * R_NOSE));
        let at = format!("R {big}, f {f}: {p:?}, naive {naive:e}");
        assert!(p.cusps > 1000, "{at}");
        assert!(relative(p.cusp_height_um, corrected).abs() < 2e-3, "{at}");
        if plain {
            assert!(naive.abs() < 0.01, "{at}");
        } else {
            assert!(naive > 0.01 && naive < 0.012, "{at}");
        }
        assert!(p.max_overcut_um > -1e-5, "{at}");
    }
}

/// The lowest arc over ρ on the half-plane at `phi` by a direct loop over every segment of the
/// path, for the half-plane and its opposite (at −ρ*).
fn brute_force_height(path: &[(f64, f64, f64)], phi: f64, rho: f64, r: f64, w: f64) -> f64 {
    let mut best = f64::INFINITY;
    for pair in path.windows(2) {
        let ((t0, r0, z0), (t1, r1, z1)) = (pair[0], pair[1]);
        for (target, sign) in [(phi, 1.0), (phi + TAU / 2.0, -1.0)] {
            let (lo, hi) = (t0.min(t1), t0.max(t1));
            let mut m = ((lo - target) / TAU).floor() - 1.0;
            while target + m * TAU <= hi + 1e-12 {
                let theta = target + m * TAU;
                if theta >= lo - 1e-12 && t1 != t0 {
                    let t = ((theta - t0) / (t1 - t0)).clamp(0.0, 1.0);
                    let u = sign * (r0 + t * (r1 - r0));
                    let c = z0 + t * (z1 - z0) + r;
                    if (rho - u).abs() <= w {
                        best = best.min(c - (r * r - (rho - u) * (rho - u)).sqrt());
                    }
                }
                m += 1.0;
            }
        }
    }
    best
}

#[test]
fn sections_equal_the_lowest_of_all_arcs_by_brute_force() {
    let json = r#"{"name":"sine","part":{"diameter_mm":2},
        "surface":{"type":"sinusoid","amplitude_mm":0.002,"wavelength_x_mm":0.9,"wavelength_y_mm":1.3,"phase_x_deg":20},
        "tool":{"nose_radius_mm":0.2,"included_angle_deg":80},"machine":{"spindle_rpm":1000},
        "strategy":{"feed_mm_per_rev":0.04,"sampling":{"type":"constant_angle","points_per_rev":24},"start_angle_deg":3.7}}"#;
    let job = Job::from_json(json).unwrap();
    let planner = Planner::new(&job).unwrap();
    let (r, w) = (0.2, 0.2 * 40f64.to_radians().sin());
    let path: Vec<(f64, f64, f64)> = planner
        .points()
        .map(|p| p.map(|p| (p.theta, p.rho, p.z)).unwrap())
        .collect();
    let settings = FormSettings {
        angles: 360,
        radial_step_mm: Some(0.04 / 8.0),
    };
    let surface = planner.surface();
    let mut checked = 0;
    for angle in [0, 7, 90, 181, 359] {
        let phi = TAU * angle as f64 / 360.0;
        let section: Vec<SectionSample> = predict_section(&planner, &settings, angle).unwrap();
        // From the centre to the first pass through this half-plane.
        let first = path
            .windows(2)
            .find_map(|s| {
                let (a, b) = (s[0].0, s[1].0);
                let turns = ((a - phi) / TAU).ceil();
                let theta = phi + turns * TAU;
                (theta < b).then(|| s[0].1 + (theta - a) / (b - a) * (s[1].1 - s[0].1))
            })
            .unwrap();
        assert_eq!(section[0].rho_mm, 0.0);
        let last = section.last().unwrap().rho_mm;
        assert!(last <= first && last > first - 0.005, "{last} vs {first}");
        for s in &section {
            let want = brute_force_height(&path, phi, s.rho_mm, r, w);
            assert!(
                (s.machined_mm - want).abs() < 1e-12,
                "angle {angle}, ρ {}: {} vs {want}",
                s.rho_mm,
                s.machined_mm
            );
            let (sn, cs) = phi.sin_cos();
            let sag = surface.sag(s.rho_mm * cs, s.rho_mm * sn).unwrap();
            // (φ rounds differently here: 2π·j/360 against the library's (2π/360)·j.)
            assert!(
                (s.design_mm - sag).abs() < 1e-15,
                "{} vs {sag}",
                s.design_mm
            );
            checked += 1;
        }
    }
    assert!(checked > 800, "{checked}");
    // The coarse path gouges between NC points (linearization), and the prediction sees it.
    let p = predict(&planner, &settings, 32, |_| {}).unwrap();
    assert!(p.max_overcut_um < -1e-3, "{p:?}");
}

#[test]
fn bad_settings_and_jobs_name_their_field() {
    let p = planner(FLAT, 0.05, CONSTANT_ANGLE);
    let field = |e: PathError| match e {
        PathError::Job(spiralcam::job::JobError::Field(e)) => e.field,
        e => panic!("{e}"),
    };
    for (angles, step) in [(7, None), (2, None), (360, Some(0.02)), (360, Some(-1.0))] {
        let s = FormSettings {
            angles,
            radial_step_mm: step,
        };
        let e = field(predict(&p, &s, 16, |_| {}).unwrap_err());
        let want = if step.is_some() {
            "form.radial_step_mm"
        } else {
            "form.angles"
        };
        assert_eq!(e, want);
    }
    let e = predict_section(&p, &FormSettings::default(), 360).unwrap_err();
    assert_eq!(field(e), "form.angle");
    // Feed at the nose's chord 2·0.5·sin 50° = 0.766 mm: the cuts do not overlap.
    let wide = planner(FLAT, 0.8, CONSTANT_ANGLE);
    let e = predict(&wide, &FormSettings::default(), 16, |_| {}).unwrap_err();
    assert_eq!(field(e), "strategy.feed_mm_per_rev");
    let sharp = Planner::new(
        &Job::from_json(
            r#"{"name":"sharp","part":{"diameter_mm":2},"surface":{"type":"asphere","curvature_per_mm":0},
                "tool":{"nose_radius_mm":0},"machine":{"spindle_rpm":1000},
                "strategy":{"feed_mm_per_rev":0.01,"sampling":{"type":"constant_angle","points_per_rev":36}}}"#,
        )
        .unwrap(),
    )
    .unwrap();
    let e = predict(&sharp, &FormSettings::default(), 16, |_| {}).unwrap_err();
    assert_eq!(field(e), "tool.nose_radius_mm");
}

#[test]
fn the_map_holds_cell_means_inside_the_part() {
    let p = form(&planner(FLAT, 0.02, CONSTANT_ANGLE), 360);
    let m = &p.map;
    assert_eq!(m.size, 64);
    let hi = p.pv_um.max(p.centre_pv_um);
    for j in 0..m.size {
        for i in 0..m.size {
            let (x, y) = m.position(i, j);
            let v = m.values[j * m.size + i];
            let rho = x.hypot(y);
            if rho > 1.0 + m.step_mm {
                assert!(v.is_nan(), "({x}, {y}): {v}");
            } else if rho < 1.0 - 0.02 - m.step_mm {
                assert!(
                    v.is_finite() && v >= p.max_overcut_um && v <= hi,
                    "({x}, {y}): {v}"
                );
            }
        }
    }
}

/// A random small job: asphere, tool, feed below the chord, either sampling and direction.
fn small_job() -> impl Strategy<Value = (String, usize)> {
    (
        prop_oneof![Just(0.0), 1.0 / 40.0..1.0 / 5.0, -1.0 / 5.0..-1.0 / 40.0],
        0.05..1.0f64,
        30.0..180.0f64,
        0.05..0.95f64,
        0.2..1.5f64,
        prop_oneof![
            (3u32..200).prop_map(|n| format!(
                r#"{{"type":"constant_angle","points_per_rev":{n}}}"#
            )),
            (0.005..0.2f64, 1.0..30.0f64).prop_map(|(s, c)| format!(
                r#"{{"type":"constant_arc","arc_length_mm":{s},"max_angle_step_deg":{c}}}"#
            )),
        ],
        any::<bool>(),
        0.0..360.0f64,
        (2usize..60).prop_map(|n| 2 * n),
    )
        .prop_map(
            |(c, r, beta, feed_ratio, part, sampling, cw, start, angles)| {
                // A nose larger than the part is refused (tool.nose_radius_mm).
                let r = r.min(2.0 * part);
                let w = r * (beta / 2.0).to_radians().sin();
                // A feed at most the part radius (strategy.feed_mm_per_rev).
                let f = (2.0 * w * feed_ratio).max(part / 40.0).min(1.9 * w).min(part);
                let dir = if cw { "cw" } else { "ccw" };
                (
                    format!(
                        r#"{{"name":"random","part":{{"diameter_mm":{}}},
                        "surface":{{"type":"asphere","curvature_per_mm":{c},"coefficients":[1e-4]}},
                        "tool":{{"nose_radius_mm":{r},"included_angle_deg":{beta}}},"machine":{{"spindle_rpm":1000}},
                        "strategy":{{"feed_mm_per_rev":{f},"sampling":{sampling},"direction":"{dir}","start_angle_deg":{start}}}}}"#,
                        2.0 * part
                    ),
                    angles,
                )
            },
        )
}

proptest! {
    #![proptest_config(config(24, SEED))]

    #[test]
    fn random_jobs_give_finite_results((json, angles) in small_job()) {
        let job = Job::from_json(&json).unwrap();
        let planner = Planner::new(&job).unwrap();
        let settings = FormSettings { angles, radial_step_mm: None };
        let mut calls = 0;
        let p = predict(&planner, &settings, 24, |_| calls += 1).unwrap();
        prop_assert!(calls >= 1);
        for v in [p.pv_um, p.rms_um, p.mean_um, p.cusp_height_um, p.cusp_height_max_um,
                  p.max_overcut_um, p.centre_pv_um] {
            prop_assert!(v.is_finite(), "{json}: {p:?}");
        }
        prop_assert!(p.pv_um >= 0.0 && p.rms_um >= 0.0 && p.max_overcut_um <= 0.0);
        prop_assert!(p.cusp_height_um <= p.cusp_height_max_um);
        prop_assert!(p.samples > 0, "{json}: {p:?}");
        prop_assert!(p.map.values.iter().all(|v| v.is_nan() || v.is_finite()));
        prop_assert!(serde_json::to_string(&p).unwrap().contains("\"cusp_height_um\""));
    }
}
