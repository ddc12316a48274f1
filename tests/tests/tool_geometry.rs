//! Critical tool angles and holder tilt (`spiralcam::tool::geometry`, paper 000 "Optimization of
//! tool geometry").
//!
//! - Tilted flat `z = t·x`: along the circle of radius ρ the slope along the motion is
//!   `∓t·sin θ` (ccw −, cw +), checked at every path point; the required clearance peaks at
//!   `atan t` where the surface falls fastest ahead of the tool (θ = 90° ccw, 270° cw; the
//!   paths sample whole degrees, so they hit those angles), the critical rake is `atan t − 90°`.
//!   Tolerance 1e-9°: both sides are atan of the same analytic gradient, rounding ~1e-14°.
//! - Holder tilt: with the default tool (10°) on a 20° flat the least tilt is exactly 10°; the
//!   tilted tool has no interference, 0.1° less has some; a rake too negative leaves no tilt.
//! - Sphere: no circumferential slope (required clearance 0 within 1e-9°, rounding of
//!   `−f_x sin θ + f_y cos θ`), radial slope `atan(ρ/√(R² − ρ²))` at the largest path radius,
//!   critical included angle twice that (1e-9°); an included angle below it is reported.
//! - Sinusoid: the slope along the motion against a central difference of the sag along the
//!   circle, arc step h = 1e-5 mm: truncation `h²/6·|f‴|` ≤ 3e-12 (|f‴| ≤ A·(2π/λ)³ ≈ 0.15
//!   mm⁻² for A = 2 µm, λ = 1.5 mm), rounding `ε·|f|/h` ≈ 1e-13, so the slopes agree to 1e-11
//!   and the angles (dα = dϕ/(1 + ϕ²) rad) within 1e-8°, the tolerance used.
//! - The JSON has no map; the map holds the required clearance.

mod common;

use common::{config, path_points, planner_of};
use proptest::prelude::*;
use spiralcam::job::ToolAngles;
use spiralcam::path::PathPoint;
use spiralcam::plan::Planner;
use spiralcam::tool::geometry::{PointAngles, ToolGeometryCheck, check};
use std::f64::consts::TAU;

/// Seed of this file's property tests.
const SEED: u64 = 5011;
/// Agreement of angles computed from the same analytic gradient, degrees (see the module docs).
const TOL: f64 = 1e-9;

fn planner(surface: &str, diameter: f64, direction: &str, included: f64) -> Planner {
    let json = format!(
        r#"{{"name":"tg","part":{{"diameter_mm":{diameter}}},"surface":{surface},
        "tool":{{"nose_radius_mm":0.5,"included_angle_deg":{included}}},"machine":{{"spindle_rpm":1000}},
        "strategy":{{"feed_mm_per_rev":0.5,"direction":"{direction}","start_angle_deg":0,
        "sampling":{{"type":"constant_angle","points_per_rev":360}}}}}}"#
    );
    planner_of(&json)
}

const FLAT: &str = r#"{"type":"tilted_flat","tilt_deg":20}"#;

#[test]
fn tilted_flat_slope_and_critical_clearance() {
    let t = 20f64.to_radians().tan();
    for (dir, sign, worst) in [("ccw", 1.0, 90.0), ("cw", -1.0, 270.0)] {
        let p = planner(FLAT, 10.0, dir, 100.0);
        for q in path_points(&p) {
            let (s, c) = q.theta.sin_cos();
            let l = p.surface().local(q.rho * c, q.rho * s).unwrap();
            let a = PointAngles::from_gradient(l.zx, l.zy, q.theta, sign);
            assert!((a.cutting_slope + sign * t * s).abs() < 1e-14, "{q:?}");
        }
        let r = check(&p, &ToolAngles::default(), 64).unwrap();
        assert!(
            (r.critical_clearance.deg - 20.0).abs() < TOL,
            "{dir}: {r:?}"
        );
        assert!(
            (r.critical_clearance.at.theta_deg - worst).abs() < 1e-6,
            "{dir}"
        );
        assert!((r.critical_rake.deg - (20.0 - 90.0)).abs() < TOL, "{dir}");
        assert!(r.clearance_interferences > 0 && !r.first_interferences.is_empty());
        assert_eq!(r.rake_interferences, 0);
        let (lo, hi) = r.map.range().unwrap();
        assert!(lo == 0.0 && (hi - 20.0).abs() < TOL);
        let json = serde_json::to_string(&r).unwrap();
        assert!(!json.contains("\"map\"") && json.contains("holder_tilt_deg"));
    }
}

#[test]
fn holder_tilt_clears_exactly_the_flat() {
    let p = planner(FLAT, 10.0, "ccw", 100.0);
    let tool = ToolAngles::default();
    let r = check(&p, &tool, 16).unwrap();
    let lambda = r.holder_tilt_deg.expect("a tilt exists");
    assert!(
        (lambda - (r.critical_clearance.deg - tool.clearance_deg)).abs() < 1e-12,
        "{r:?}"
    );
    assert!((lambda - 10.0).abs() < TOL);
    let tilted = check(&p, &tool.tilted(lambda), 16).unwrap();
    assert_eq!(tilted.clearance_interferences, 0, "{tilted:?}");
    assert_eq!(tilted.holder_tilt_deg, Some(0.0));
    assert_eq!(tilted.verdict, "the tool clears the surface");
    let short = check(&p, &tool.tilted(lambda - 0.1), 16).unwrap();
    assert!(short.clearance_interferences > 0);
    // Rake −65°: λmax = −65° − (−70°) = 5° < the 15° the 5° flank needs.
    let steep = ToolAngles {
        rake_deg: -65.0,
        clearance_deg: 5.0,
    };
    let none = check(&p, &steep, 16).unwrap();
    assert_eq!(none.holder_tilt_deg, None, "{none:?}");
    assert!(
        none.holder_tilt_note.contains("λmax"),
        "{}",
        none.holder_tilt_note
    );
    // Rake −75° already meets the rising flank: no tilt.
    let worse = check(
        &p,
        &ToolAngles {
            rake_deg: -75.0,
            clearance_deg: 30.0,
        },
        16,
    )
    .unwrap();
    assert!(worse.rake_interferences > 0 && worse.holder_tilt_deg.is_none());
}

#[test]
fn sphere_radial_slope_gives_the_included_angle() {
    for (radius, included, ok) in [(20.0, 100.0, true), (6.0, 100.0, false)] {
        let s = format!(r#"{{"type":"asphere","radius_mm":{radius}}}"#);
        let p = planner(&s, 10.0, "cw", included);
        let rho_max = path_points(&p).iter().map(|q| q.rho).fold(0.0, f64::max);
        let expect = (rho_max / (radius * radius - rho_max * rho_max).sqrt())
            .atan()
            .to_degrees();
        let r = check(&p, &ToolAngles::default(), 32).unwrap();
        assert!(r.critical_clearance.deg < TOL, "{r:?}");
        assert_eq!(r.clearance_interferences, 0);
        assert!((r.critical_outward_half.deg - expect).abs() < TOL, "{r:?}");
        assert!((r.critical_outward_half.at.rho_mm - rho_max).abs() < 1e-12);
        assert!(r.critical_inward_half.deg < TOL);
        assert!((r.critical_included_angle_deg - 2.0 * expect).abs() < TOL);
        assert_eq!(
            r.verdict == "the tool clears the surface",
            ok,
            "{}",
            r.verdict
        );
        assert_eq!(r.verdict.contains("included angle"), !ok);
    }
}

proptest! {
    #![proptest_config(config(64, SEED))]

    #[test]
    fn sinusoid_slope_matches_a_finite_difference_along_the_motion(
        rho in 0.1f64..4.0,
        theta in 0.0f64..TAU,
        ccw in any::<bool>(),
    ) {
        let dir = if ccw { "ccw" } else { "cw" };
        let sign = if ccw { 1.0 } else { -1.0 };
        let p = planner(
            r#"{"type":"sinusoid","amplitude_mm":0.002,"wavelength_x_mm":1.5,"wavelength_y_mm":2.0}"#,
            10.0, dir, 100.0,
        );
        let h = 1e-5;
        let dt = h / rho;
        let sag = |t: f64| p.surface().sag(rho * t.cos(), rho * t.sin()).unwrap();
        let slope = (sag(theta + sign * dt) - sag(theta - sign * dt)) / (2.0 * h);
        let mut c = ToolGeometryCheck::new(&p, &ToolAngles::default(), 16);
        c.add(&p, &PathPoint { rho, theta, ..PathPoint::default() }).unwrap();
        let r = c.finish();
        let clearance = (-slope).max(0.0).atan().to_degrees();
        let rake = slope.max(0.0).atan().to_degrees() - 90.0;
        prop_assert!((r.critical_clearance.deg - clearance).abs() < 1e-8, "{} {}", r.critical_clearance.deg, clearance);
        prop_assert!((r.critical_rake.deg - rake).abs() < 1e-8, "{} {}", r.critical_rake.deg, rake);
    }
}
