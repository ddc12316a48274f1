//! HCAA and adaptive sampling (`spiralcam::path::hcaa`, paper 000 "HCAA method") through the public
//! API.
//!
//! - Closed forms: on a sphere with a sharp tool the height depends on ρ alone and along the
//!   spiral `d²z/dt² = b²·z_ρρ` (b = f/2π), so each band's step is
//!   `√(8·SAFETY·tol/(b²·z_ρρ))` at its outer edge, `z_ρρ = R²/(R² − ρ²)^{3/2}` (to 1 %: the
//!   second differences' O(h²)); on a cylinder `z = x²/(2R_c)` the height along a circle is
//!   `ρ²cos²θ/(2R_c)`, `max d²z/dθ² = ρ²/R_c`, so the step is `√(8·SAFETY·tol·R_c)/ρ`: a
//!   constant arc length, which HCAA picks over nearly the whole part.
//! - Dense verification: `linearization::analyse` over the whole path (each segment's extremes
//!   refined to 1e-13 mm) on an asphere with a round nose, a scaled-down compound eye (paper
//!   000's job at 1.2 mm diameter, feed 0.02 mm) and a lens array with lenslet rims (slope kinks:
//!   bounded by the kink rule of `hcaa`): the largest overcut and the largest undercut are each
//!   at most the tolerance, for HCAA, adaptive and the uniform constant-angle sampling
//!   `Bands::uniform_points_per_rev`; HCAA and adaptive need fewer points than uniform.
//! - The zoned spiral: starts at the outer radius, ends exactly at the centre, θ increases,
//!   every step obeys its zone's rule, the count hint is close.
//! - Fields: bad tolerances name `strategy.sampling.pv_tolerance_um`; the JSON is snake_case.

mod common;

use spiralcam::analysis::linearization::analyse;
use spiralcam::job::Job;
use spiralcam::job::{Direction, Sampling};
use spiralcam::path::hcaa::{self, SAFETY};
use spiralcam::path::spiral::{Spiral, Step, Zone};
use spiralcam::plan::Planner;
use std::f64::consts::{PI, TAU};

fn job(surface: &str, diameter: f64, nose: f64, feed: f64, sampling: &str) -> Job {
    Job::from_json(&format!(
        r#"{{"name":"t","part":{{"diameter_mm":{diameter}}},"surface":{surface},
        "tool":{{"nose_radius_mm":{nose},"included_angle_deg":100}},"machine":{{"spindle_rpm":100}},
        "strategy":{{"feed_mm_per_rev":{feed},"sampling":{sampling}}}}}"#
    ))
    .unwrap()
}

fn bands_of(j: &Job, tol_um: f64) -> hcaa::Bands {
    let mut j = j.clone();
    j.strategy.sampling = Sampling::ConstantAngle { points_per_rev: 3 };
    let p = Planner::new(&j).unwrap();
    hcaa::bands(
        p.surface(),
        &|rho, theta| p.tip_height(rho, theta),
        (
            j.outer_radius_mm(),
            j.strategy.feed_mm_per_rev,
            tol_um * 1e-3,
        ),
        &mut spiralcam::progress::ignore,
    )
    .unwrap()
}

#[test]
fn sphere_steps_follow_the_radial_curvature() {
    // A coarse feed, so that the feed's share of the error binds below 180°.
    let (rs, feed, tol_um): (f64, f64, f64) = (10.0, 1.0, 0.001);
    let j = job(
        r#"{"type":"asphere","radius_mm":10}"#,
        8.0,
        0.0,
        feed,
        r#"{"type":"constant_angle","points_per_rev":3}"#,
    );
    let bands = bands_of(&j, tol_um);
    let b = feed / TAU;
    for (i, &step) in bands.step_rad.iter().enumerate() {
        let rho = bands.edges_mm[i + 1];
        let zrr = rs * rs / (rs * rs - rho * rho).powf(1.5);
        let want = (8.0 * SAFETY * tol_um * 1e-3 / (b * b * zrr))
            .sqrt()
            .min(PI);
        assert!(
            (step / want - 1.0).abs() < 0.01,
            "band {i}: {step} vs {want}"
        );
    }
    // At a fine feed the sphere needs only the cap: two points per revolution (paper 000).
    let j = job(
        r#"{"type":"asphere","radius_mm":10}"#,
        8.0,
        0.0,
        0.01,
        r#"{"type":"constant_angle","points_per_rev":3}"#,
    );
    assert!(bands_of(&j, 0.1).step_rad.iter().all(|&s| s == PI));
}

#[test]
fn cylinder_gives_constant_arc() {
    // z = 0.01·(x/1)² : R_c = 50 mm.
    let surface = r#"{"type":"xy_polynomial","base":{"radius_mm":1000},"norm_radius_mm":1,"terms":[{"x":2,"y":0,"coefficient_mm":0.01}]}"#;
    let tol_um = 1.0;
    let j = job(
        surface,
        6.0,
        0.0,
        0.01,
        r#"{"type":"constant_angle","points_per_rev":3}"#,
    );
    let bands = bands_of(&j, tol_um);
    let ds = (8.0 * SAFETY * tol_um * 1e-3 * 50.0).sqrt();
    for (i, &step) in bands.step_rad.iter().enumerate().skip(1) {
        let want = (ds / bands.edges_mm[i + 1]).min(PI);
        assert!(
            (step / want - 1.0).abs() < 0.01,
            "band {i}: {step} vs {want}"
        );
    }
    let h = bands.hcaa();
    assert!(h.arc_length_mm <= ds && h.arc_length_mm > 0.8 * ds, "{h:?}");
    assert!(
        h.outer_transition_mm >= 2.4 && h.inner_transition_mm < 1.0,
        "{h:?}"
    );
}

/// Plans `j` with `sampling`, checks PVerr ≤ tol both ways, returns the point count.
fn verified(j: &Job, sampling: Sampling, tol_um: f64) -> u64 {
    let mut j = j.clone();
    j.strategy.sampling = sampling.clone();
    let p = Planner::new(&j).unwrap();
    let lin = analyse(&p, 8, |_| ()).unwrap();
    assert!(
        lin.max_overcut_um <= tol_um && lin.max_undercut_um <= tol_um,
        "{sampling:?}: overcut {} µm at {:?}, undercut {} µm at {:?}",
        lin.max_overcut_um,
        lin.max_overcut_at,
        lin.max_undercut_um,
        lin.max_undercut_at
    );
    lin.segments + 1
}

fn all_three(j: &Job, tol_um: f64) -> (u64, u64, u64) {
    let n = bands_of(j, tol_um).uniform_points_per_rev();
    let hcaa = verified(
        j,
        Sampling::Hcaa {
            pv_tolerance_um: tol_um,
        },
        tol_um,
    );
    let adaptive = verified(
        j,
        Sampling::Adaptive {
            pv_tolerance_um: tol_um,
        },
        tol_um,
    );
    let uniform = verified(j, Sampling::ConstantAngle { points_per_rev: n }, tol_um);
    (hcaa, adaptive, uniform)
}

#[test]
fn asphere_holds_the_tolerance() {
    let j = job(
        r#"{"type":"asphere","radius_mm":8,"conic":-1.2,"coefficients":[1.5e-4]}"#,
        4.0,
        0.5,
        0.01,
        r#"{"type":"constant_angle","points_per_rev":3}"#,
    );
    let (h, a, u) = all_three(&j, 0.1);
    assert!(h <= u && a <= u, "{h} {a} {u}");
}

#[test]
fn compound_eye_holds_the_tolerance_with_fewer_points() {
    let mut j = common::example_job("compound-eye-paper000.json");
    j.part.diameter_mm = 1.2;
    j.strategy.feed_mm_per_rev = 0.02;
    let (h, a, u) = all_three(&j, 1.0);
    assert!(h < u && a < u, "{h} {a} {u}");
}

#[test]
fn lens_array_rims_hold_the_tolerance() {
    // Lenslets of 1 mm pitch touching: rims (slope kinks) at |x|, |y| = 0.5, 1.5 mm.
    let surface = r#"{"type":"lens_array","lens_radius_mm":2.84,"aperture_mm":1.0,"pitch_mm":1.0,"grid":"rectangular","form":"concave"}"#;
    let j = job(
        surface,
        2.4,
        0.5,
        0.05,
        r#"{"type":"constant_angle","points_per_rev":3}"#,
    );
    let (h, a, u) = all_three(&j, 1.0);
    assert!(h <= u && a <= u, "{h} {a} {u}");
}

#[test]
fn zoned_spiral_obeys_its_zones() {
    let zones = [
        Zone {
            inner_radius_mm: 3.0,
            step: Step::Angle { step_rad: 0.5 },
        },
        Zone {
            inner_radius_mm: 0.4,
            step: Step::Arc {
                arc_length_mm: 0.05,
                max_step_rad: PI,
            },
        },
        Zone {
            inner_radius_mm: 0.0,
            step: Step::Angle { step_rad: 1.0 },
        },
    ];
    let s = Sampling::Hcaa {
        pv_tolerance_um: 1.0,
    };
    let sp = Spiral::with_zones(5.0, 0.1, &s, &zones, Direction::Ccw, 10.0).unwrap();
    let pts: Vec<_> = sp.points().collect();
    assert_eq!(pts[0].rho, 5.0);
    assert_eq!(pts[0].theta, 10f64.to_radians());
    assert_eq!(pts.last().unwrap().rho, 0.0);
    let b = 0.1 / TAU;
    for w in pts.windows(2) {
        let d = w[1].theta - w[0].theta;
        assert!(d > 0.0);
        assert!((w[0].rho - w[1].rho - b * d).abs() < 1e-12);
        if w[1].rho >= 3.0 {
            assert!(d <= 0.5 + 1e-12);
        } else if w[0].rho <= 0.4 {
            assert!(d <= 1.0 + 1e-12);
        }
        if w[0].rho <= 3.0 && w[1].rho >= 0.4 {
            // Chord along the spiral ≤ arc ≤ ΔS.
            let (a, c) = (w[0], w[1]);
            let chord = (a.rho * a.rho + c.rho * c.rho - 2.0 * a.rho * c.rho * d.cos()).sqrt();
            assert!(chord <= 0.05 + 1e-9, "{chord}");
        }
    }
    let hint = sp.point_count_hint() as f64;
    assert!(
        (hint - pts.len() as f64).abs() <= 5.0 + 0.01 * hint,
        "{hint} {}",
        pts.len()
    );
}

#[test]
fn fields_and_json() {
    let j = job(
        r#"{"type":"asphere","radius_mm":10}"#,
        4.0,
        0.0,
        0.01,
        r#"{"type":"hcaa","pv_tolerance_um":0.5}"#,
    );
    assert_eq!(
        j.strategy.sampling,
        Sampling::Hcaa {
            pv_tolerance_um: 0.5
        }
    );
    let json = serde_json::to_string(&Sampling::Adaptive {
        pv_tolerance_um: 2.0,
    })
    .unwrap();
    assert_eq!(json, r#"{"type":"adaptive","pv_tolerance_um":2.0}"#);
    for bad in ["0", "-1", "1e9"] {
        let j = job(
            r#"{"type":"asphere","radius_mm":10}"#,
            4.0,
            0.0,
            0.01,
            &format!(r#"{{"type":"adaptive","pv_tolerance_um":{bad}}}"#),
        );
        let e = Planner::new(&j).unwrap_err().to_string();
        assert!(e.starts_with("strategy.sampling.pv_tolerance_um"), "{e}");
    }
    let e = Spiral::new(
        4.0,
        0.01,
        &Sampling::Hcaa {
            pv_tolerance_um: 1.0,
        },
        Direction::Ccw,
        0.0,
    )
    .unwrap_err();
    assert_eq!(e.field, "sampling.type");
    // The header names the zones.
    let p = Planner::new(&j_with(r#"{"type":"hcaa","pv_tolerance_um":1}"#)).unwrap();
    assert!(p.header().lines.iter().any(|l| l.contains("hcaa pv 1 um")));
}

fn j_with(sampling: &str) -> Job {
    job(
        r#"{"type":"asphere","radius_mm":10}"#,
        4.0,
        0.0,
        0.01,
        sampling,
    )
}

/// The step estimate is that of one-way compensation: a two-way job with hcaa is refused.
#[test]
fn hcaa_with_two_way_compensation_is_refused_naming_the_field() {
    let job = r#"{"name":"hcaa-two-way","part":{"diameter_mm":2},
        "surface":{"type":"asphere","radius_mm":20},
        "tool":{"nose_radius_mm":0.1},"machine":{"spindle_rpm":500},
        "strategy":{"feed_mm_per_rev":0.05,"compensation":"two_way",
                    "sampling":{"type":"hcaa","pv_tolerance_um":1}}}"#;
    let job = spiralcam::job::Job::from_json(job).unwrap();
    let Err(e) = spiralcam::plan::Planner::new(&job) else {
        panic!("a two-way job with hcaa was accepted");
    };
    assert!(
        e.to_string().starts_with("strategy.sampling.type = hcaa:"),
        "{e}"
    );
}
