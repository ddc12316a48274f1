//! Two-way tool nose compensation (`strategy.compensation: "two_way"`): the spiral point is the
//! contact and the nose centre lies r along the surface normal; X and C are the centre's radius
//! and polar angle, Z the tip `centre z − r`.
//!
//! - Sphere of radius R (centre of curvature (0, 0, R)): the centre lies on the sphere of radius
//!   |R − r| about the same point, X = ρ_s·(R − r)/R and C = θ (closed form), within 1e-12 mm;
//!   the contact is the spiral point exactly.
//! - Flat: two-way equals one-way within 1e-12 mm.
//! - Brute force, smooth surfaces whose concave curvature radius exceeds r: the nose sphere
//!   about the centre passes through the contact (distance r within 1e-12 mm) and no surface
//!   point within r (in XY) of the contact is closer to the centre than r − 1e-12 mm (a 41 × 41
//!   grid); the nose arc in the radial plane of the centre (angle C, not θ) cuts nowhere deeper
//!   than 0.1 nm (`common::dense_gap`, 20 000 steps).
//! - Tilted flat (tilt τ, azimuth 0): the centre is `(ρ cos θ − k, ρ sin θ)`, k = r·sin τ, so
//!   X = √(ρ² − 2kρ cos θ + k²) and C = θ + atan2(k sin θ, ρ − k cos θ); the X reversals and
//!   the largest X acceleration counted from these by hand equal the report's (the acceleration
//!   to 1e-9 relative: second differences amplify 1e-16 mm rounding by 1/ΔC² ≈ 3e3).
//! - Loops: a concave sphere with R < r folds everywhere (one run, every point), R > r nowhere.
//! - One-way: an explicit `"one_way"` gives the default's NC bytes, and the job JSON does not
//!   mention the field (the golden NC tests are unchanged).

mod common;

use common::{TOUCH, dense_gap};
use spiralcam::job::Job;
use spiralcam::path::PathPoint;
use spiralcam::plan::{Planner, Sinks};
use spiralcam::report::Report;
use std::f64::consts::TAU;
use std::ops::ControlFlow;

fn job(surface: &str, diameter: f64, r: f64, feed: f64, n: u32, comp: &str) -> Job {
    let comp = if comp.is_empty() {
        String::new()
    } else {
        format!(r#", "compensation": "{comp}""#)
    };
    Job::from_json(&format!(
        r#"{{"name": "two-way", "part": {{"diameter_mm": {diameter}}}, "surface": {surface},
            "tool": {{"nose_radius_mm": {r}, "included_angle_deg": 120}},
            "machine": {{"spindle_rpm": 600}},
            "strategy": {{"feed_mm_per_rev": {feed},
                "sampling": {{"type": "constant_angle", "points_per_rev": {n}}}{comp}}}}}"#
    ))
    .expect("job")
}

fn plan(job: &Job) -> (Vec<PathPoint>, Report, Vec<u8>) {
    let p = Planner::new(job).expect("planner");
    let points: Vec<PathPoint> = p.points().map(|q| q.expect("point")).collect();
    let mut nc = Vec::new();
    let report = p
        .run(
            Sinks {
                nc: Some(&mut nc),
                ..Sinks::default()
            },
            &mut |_| ControlFlow::Continue(()),
        )
        .expect("plan");
    (points, report, nc)
}

fn spiral(job: &Job) -> Vec<(f64, f64)> {
    let p = Planner::new(job).expect("planner");
    p.spiral().points().map(|sp| (sp.rho, sp.theta)).collect()
}

fn centre(p: &PathPoint, r: f64) -> [f64; 3] {
    let (s, c) = p.theta.sin_cos();
    [p.rho * c, p.rho * s, p.z + r]
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[test]
fn on_a_sphere_the_centre_lies_on_the_offset_sphere() {
    for (big, r) in [(20.0, 0.5), (-15.0, 0.3), (8.0, 1.0)] {
        let surface = format!(r#"{{"type": "asphere", "radius_mm": {big}}}"#);
        let j = job(&surface, 10.0, r, 0.05, 360, "two_way");
        let (points, report, _) = plan(&j);
        let sp = spiral(&j);
        assert_eq!(points.len(), sp.len());
        let planner = Planner::new(&j).unwrap();
        for (p, &(rho, theta)) in points.iter().zip(&sp) {
            let (s, c) = theta.sin_cos();
            let sag = planner.surface().sag(rho * c, rho * s).unwrap();
            assert_eq!(p.contact, [rho * c, rho * s, sag], "contact at {rho}");
            let ctr = centre(p, r);
            let d = dist(ctr, [0.0, 0.0, big]);
            assert!(
                (d - (big - r).abs()).abs() < 1e-12,
                "R {big}, ρ {rho}: |centre − O| {d}"
            );
            assert!((p.rho - rho * (big - r) / big).abs() < 1e-12, "X at {rho}");
            if rho > 0.0 {
                assert!((p.theta - theta).abs() < 1e-12, "C at {rho}");
            }
        }
        assert_eq!(report.x_reversals, 0);
        assert_eq!(report.two_way_loops, 0);
    }
}

#[test]
fn on_a_flat_two_way_equals_one_way() {
    let surface = r#"{"type": "asphere", "curvature_per_mm": 0}"#;
    let (one, r1, _) = plan(&job(surface, 6.0, 0.4, 0.1, 200, ""));
    let (two, r2, _) = plan(&job(surface, 6.0, 0.4, 0.1, 200, "two_way"));
    assert_eq!(one.len(), two.len());
    for (a, b) in one.iter().zip(&two) {
        assert!((a.rho - b.rho).abs() < 1e-12, "X {} {}", a.rho, b.rho);
        assert!(
            (a.theta - b.theta).abs() < 1e-12,
            "C {} {}",
            a.theta,
            b.theta
        );
        assert!((a.z - b.z).abs() < 1e-12, "Z {} {}", a.z, b.z);
        for k in 0..3 {
            assert!((a.contact[k] - b.contact[k]).abs() < 1e-12);
        }
    }
    assert_eq!((r1.x_reversals, r2.x_reversals), (0, 0));
    assert_eq!((r1.two_way_loops, r2.two_way_loops), (0, 0));
    assert!(r1.max_x_acceleration_mm_s2 < 1e-6);
}

#[test]
fn the_nose_touches_at_the_contact_and_does_not_cut_nearby() {
    let r = 0.2;
    for surface in [
        r#"{"type": "sinusoid", "amplitude_mm": 0.002, "wavelength_x_mm": 1.3, "wavelength_y_mm": 0.9, "phase_x_deg": 20}"#,
        r#"{"type": "asphere", "radius_mm": -6, "conic": -0.5, "coefficients": [1e-4]}"#,
        r#"{"type": "asphere", "radius_mm": 5}"#,
    ] {
        let j = job(surface, 4.0, r, 0.1, 90, "two_way");
        let planner = Planner::new(&j).unwrap();
        let s = planner.surface();
        let (points, report, _) = plan(&j);
        assert_eq!(report.two_way_loops, 0, "{surface}");
        for p in points.iter().step_by(7) {
            let ctr = centre(p, r);
            let at = format!("{surface}: point {}", p.index);
            assert!((dist(ctr, p.contact) - r).abs() < 1e-12, "{at}");
            // The nose sphere: no surface point near the contact lies inside it.
            let m = 20;
            for i in -m..=m {
                for k in -m..=m {
                    let x = p.contact[0] + r * i as f64 / m as f64;
                    let y = p.contact[1] + r * k as f64 / m as f64;
                    let z = s.sag(x, y).unwrap();
                    let d = dist(ctr, [x, y, z]);
                    assert!(d >= r - 1e-12, "{at}: cuts {:e} mm at ({x}, {y})", r - d);
                }
            }
            // The nose arc in the radial plane of the centre (angle C).
            let gap = dense_gap(
                s,
                r,
                60f64.to_radians(),
                1e3,
                p.rho,
                p.theta,
                p.z + r,
                &[],
                20_000,
            );
            assert!(
                gap.min - gap.bound >= -TOUCH,
                "{at}: arc cuts {:e} mm",
                -gap.min
            );
            assert!(gap.bound < 0.2 * TOUCH, "{at}: bound {:e}", gap.bound);
        }
    }
}

#[test]
fn x_reversals_and_acceleration_on_a_tilted_flat_match_the_closed_form() {
    let (tilt, r, rpm) = (10f64, 0.5, 600.0);
    let surface = format!(r#"{{"type": "tilted_flat", "tilt_deg": {tilt}}}"#);
    let j = job(&surface, 2.0, r, 0.05, 360, "two_way");
    let (points, report, _) = plan(&j);
    let sp = spiral(&j);
    let k = r * tilt.to_radians().sin();
    let closed: Vec<(f64, f64)> = sp
        .iter()
        .map(|&(rho, th)| {
            let x = (rho * rho - 2.0 * k * rho * th.cos() + k * k).sqrt();
            let c = th + (k * th.sin()).atan2(rho - k * th.cos());
            (x, c)
        })
        .collect();
    for (p, &(x, c)) in points.iter().zip(&closed) {
        assert!((p.rho - x).abs() < 1e-12, "X {} vs {x}", p.rho);
        assert!((p.theta - c).abs() < 1e-12, "C {} vs {c}", p.theta);
    }
    // By hand: sign changes of ΔX, and the largest second difference over C steps.
    let (mut reversals, mut last) = (0u64, 0.0f64);
    for w in closed.windows(2) {
        let dx = w[1].0 - w[0].0;
        if dx != 0.0 {
            if last != 0.0 && dx.signum() != last {
                reversals += 1;
            }
            last = dx.signum();
        }
    }
    let omega = rpm / 60.0 * TAU;
    let accel = closed
        .windows(3)
        .map(|w| {
            let (h1, h2) = ((w[1].1 - w[0].1).abs(), (w[2].1 - w[1].1).abs());
            (2.0 * ((w[2].0 - w[1].0) / h2 - (w[1].0 - w[0].0) / h1) / (h1 + h2)).abs()
                * omega
                * omega
        })
        .fold(0.0, f64::max);
    let revs = sp.len() as f64 / 360.0;
    // Away from the axis X rises and falls once a turn (sin θ ≈ f/(2πk) twice a turn).
    assert!(reversals as f64 > 1.5 * revs, "{reversals} in {revs} turns");
    assert_eq!(report.x_reversals, reversals);
    assert!(
        (report.max_x_acceleration_mm_s2 - accel).abs() < 1e-9 * accel,
        "{} vs {accel}",
        report.max_x_acceleration_mm_s2
    );
    // One-way keeps X on the spiral: no reversal.
    let (_, one, _) = plan(&job(&surface, 2.0, r, 0.05, 360, "one_way"));
    assert_eq!(one.x_reversals, 0);
}

#[test]
fn loops_are_reported_where_the_concave_radius_is_below_r() {
    let surface = r#"{"type": "asphere", "radius_mm": 1.0}"#;
    let (points, folded, _) = plan(&job(surface, 1.6, 1.2, 0.05, 100, "two_way"));
    assert_eq!(folded.two_way_loops, 1);
    assert_eq!(folded.two_way_loop_points, points.len() as u64);
    let first = folded.first_two_way_loop_at.expect("first loop");
    assert!((first.rho_mm - points[0].rho).abs() < 1e-12);
    assert!(folded.warnings.iter().any(|w| w.contains("loop")));
    let (_, fine, _) = plan(&job(surface, 1.6, 0.5, 0.05, 100, "two_way"));
    assert_eq!((fine.two_way_loops, fine.two_way_loop_points), (0, 0));
    assert!(fine.first_two_way_loop_at.is_none());
    // One-way cannot loop.
    let (_, one, _) = plan(&job(surface, 1.6, 1.2, 0.05, 100, "one_way"));
    assert_eq!(one.two_way_loops, 0);
}

#[test]
fn one_way_is_the_default_and_unchanged() {
    let surface = r#"{"type": "asphere", "radius_mm": 12, "conic": -1}"#;
    let default = job(surface, 8.0, 0.3, 0.02, 180, "");
    let explicit = job(surface, 8.0, 0.3, 0.02, 180, "one_way");
    assert_eq!(default, explicit);
    assert!(!default.to_json().contains("compensation"));
    assert_eq!(plan(&default).2, plan(&explicit).2);
    let two = job(surface, 8.0, 0.3, 0.02, 180, "two_way");
    assert!(two.to_json().contains(r#""compensation": "two_way""#));
    let nc = String::from_utf8(plan(&two).2).unwrap();
    assert!(nc.contains("two-way compensation"));
    let e = Job::from_json(&default.to_json().replace(
        r#""feed_mm_per_rev""#,
        r#""compensation": "both", "feed_mm_per_rev""#,
    ))
    .unwrap_err();
    assert!(e.to_string().contains("strategy.compensation"), "{e}");
}
