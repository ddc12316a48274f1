//! The zoned asphere through the public API: sag against the zones' closed forms (the conic
//! written out plus `Σ A₂ᵢ·r²ⁱ` by `powi`, plus the offset, the zone chosen by radius), gradient
//! and Hessian against central differences away from the boundaries (proptest), the continuity
//! figures at each boundary against one-sided closed forms, the kinks on lines that cross the
//! boundary circles, the warning thresholds (1 nm, 1 µrad) and the report's warning, errors,
//! and planned paths through the gouge check with the boundaries as kinks.

mod common;

use common::{
    check_derivatives, check_example_jobs, check_planned_path, config, field_error, small_job,
};
use proptest::prelude::*;
use spiralcam::job::Job;
use spiralcam::plan::Planner;
use spiralcam::surface::zoned_asphere::ZoneSpec;
use spiralcam::surface::{Line, Surface, ZonedAsphere, ZonedAsphereSpec};
use std::f64::consts::PI;
use std::ops::ControlFlow;

/// Seed of this file's property tests.
const SEED: u64 = 1313;

/// A zone: outer radius, vertex radius, conic, A4 and A6, offset.
type Zone = (Option<f64>, f64, f64, [f64; 2], f64);

/// A zone's sag and radial slope written out at radius r.
fn closed(z: &Zone, r: f64) -> (f64, f64) {
    let (_, radius, k, [a4, a6], offset) = *z;
    let c = 1.0 / radius;
    let q = (1.0 - (1.0 + k) * c * c * r * r).sqrt();
    let sag = c * r * r / (1.0 + q) + a4 * r.powi(4) + a6 * r.powi(6) + offset;
    let slope = c * r / q + 4.0 * a4 * r.powi(3) + 6.0 * a6 * r.powi(5);
    (sag, slope)
}

fn build(zones: &[Zone]) -> ZonedAsphere {
    ZonedAsphere::new(&ZonedAsphereSpec {
        zones: zones
            .iter()
            .map(|&(outer, radius, conic, [a4, a6], offset)| ZoneSpec {
                outer_radius_mm: outer,
                radius_mm: Some(radius),
                curvature_per_mm: None,
                conic,
                coefficients: vec![a4, a6],
                offset_mm: offset,
            })
            .collect(),
    })
    .expect("valid zoned asphere")
}

/// Two to five zones out to 6 mm, each a conic (|R| 30…200 mm, k −2…1, inside 0.9 of its rim)
/// with A4, A6 of at most 5 µm at 6 mm and an offset of at most 10 µm.
fn zones() -> impl Strategy<Value = Vec<Zone>> {
    prop::collection::vec(
        (
            0.3..1.0f64,
            prop_oneof![30.0..200.0f64, -200.0..-30.0f64],
            -2.0..1.0f64,
            (-1.0..1.0f64, -1.0..1.0f64),
            -1e-2..1e-2f64,
        ),
        2..=5,
    )
    .prop_map(|raw| {
        let total: f64 = raw.iter().map(|z| z.0).sum();
        let mut outer = 0.0;
        let n = raw.len();
        raw.iter()
            .enumerate()
            .map(|(k, &(w, radius, conic, (a4, a6), offset))| {
                outer += 6.0 * w / total;
                let bound = (k + 1 < n).then_some(outer);
                (
                    bound,
                    radius,
                    conic,
                    [a4 * 5e-3 / 6f64.powi(4), a6 * 5e-3 / 6f64.powi(6)],
                    offset,
                )
            })
            .collect()
    })
}

/// The zone index holding r (boundaries belong to the inner zone).
fn zone_of(zones: &[Zone], r: f64) -> usize {
    zones
        .iter()
        .position(|z| z.0.is_none_or(|b| r <= b))
        .unwrap()
}

proptest! {
    #![proptest_config(config(128, SEED))]

    #[test]
    fn sag_is_the_zones_asphere_plus_its_offset(
        zones in zones(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 8),
    ) {
        let s = build(&zones);
        for (t, phi) in pts {
            let r = 6.0 * t.sqrt();
            let (x, y) = (r * phi.cos(), r * phi.sin());
            let want = closed(&zones[zone_of(&zones, r)], r).0;
            let got = s.sag(x, y).unwrap();
            prop_assert!((got - want).abs() <= 2e-15, "r {r}: {got} vs {want}");
        }
        // The continuity figures, from both zones' closed forms at each boundary.
        for (k, b) in s.boundaries().iter().enumerate() {
            let rb = zones[k].0.unwrap();
            prop_assert_eq!(b.radius_mm, rb);
            let ((z0, s0), (z1, s1)) = (closed(&zones[k], rb), closed(&zones[k + 1], rb));
            prop_assert!((b.step_mm - (z1 - z0)).abs() <= 4e-15);
            prop_assert!((b.slope_jump - (s1 - s0)).abs() <= 1e-14);
        }
    }

    #[test]
    fn derivatives_match_finite_differences_inside_each_zone(
        zones in zones(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 6),
    ) {
        let s = build(&zones);
        for (t, phi) in pts {
            let r = 6.0 * t.sqrt();
            // The differences must not straddle a boundary.
            if zones.iter().any(|z| z.0.is_some_and(|b| (b - r).abs() < 1e-4)) {
                continue;
            }
            check_derivatives(&s, r * phi.cos(), r * phi.sin())?;
        }
    }

    #[test]
    fn kinks_lie_on_the_boundary_circles(
        zones in zones(),
        (x0, y0, a) in (-3.0..3.0f64, -3.0..3.0f64, 0.0..PI),
    ) {
        let s = build(&zones);
        let line = Line { x0, y0, c: a.cos(), s: a.sin() };
        let mut kinks = Vec::new();
        s.slope_kinks(line, -20.0, 20.0, &mut kinks);
        // Every crossing of a boundary circle (the offsets make every boundary a kink here).
        let distance = (x0 * a.sin() - y0 * a.cos()).abs();
        let crossings = zones
            .iter()
            .filter_map(|z| z.0)
            .filter(|&b| b > distance)
            .count();
        prop_assert_eq!(kinks.len(), 2 * crossings);
        for t in kinks {
            let (x, y) = line.at(t);
            let r = x.hypot(y);
            prop_assert!(zones.iter().any(|z| z.0.is_some_and(|b| (b - r).abs() < 1e-12)), "{r}");
        }
    }
}

/// Two spheres meeting at r = 3 mm with the outer one lifted by `offset` and bent by `a4`.
fn pair(offset: f64, a4: f64) -> ZonedAsphere {
    let lift = (30.0 - (900.0f64 - 9.0).sqrt()) - (20.0 - (400.0f64 - 9.0).sqrt());
    build(&[
        (Some(3.0), 20.0, 0.0, [0.0, 0.0], 0.0),
        (None, 30.0, 0.0, [a4, 0.0], offset - lift - a4 * 81.0),
    ])
}

#[test]
fn warnings_follow_the_documented_thresholds() {
    // The slope of sphere R at r: r/√(R² − r²); an A4 term adds 4·A4·r³ = 108·A4 at r = 3.
    let matched = 3.0 / 391f64.sqrt() - 3.0 / 891f64.sqrt();
    let smooth = pair(0.0, matched / 108.0);
    let b = smooth.boundaries()[0];
    assert!(
        b.step_mm.abs() < 1e-15 && b.slope_jump.abs() < 1e-15,
        "{b:?}"
    );
    assert!(smooth.warnings().is_empty());
    for (offset, slope, warned) in [
        (0.5e-6, 0.5e-6, false),
        (2e-6, 0.0, true),
        (0.0, 2e-6, true),
        (0.0, -2e-6, true),
    ] {
        let s = pair(offset, (matched + slope) / 108.0);
        let b = s.boundaries()[0];
        assert!((b.step_mm - offset).abs() < 1e-14, "{b:?}");
        assert!((b.slope_jump - slope).abs() < 1e-12, "{b:?}");
        assert_eq!(!s.warnings().is_empty(), warned, "{offset} {slope}");
        // A boundary that differs at all is a kink.
        let mut kinks = Vec::new();
        s.slope_kinks(Line::radial(1.0, 0.0), 0.0, 5.0, &mut kinks);
        assert_eq!(kinks, vec![3.0]);
    }
    let concave = pair(0.0, (matched + 2e-6) / 108.0).warnings();
    assert!(concave[0].contains("concave corner"), "{concave:?}");
}

#[test]
fn the_report_carries_the_warning() {
    let job = spiralcam::job::Job::from_json(&small_job(
        "zoned",
        r#"{"type":"zoned_asphere","zones":[{"outer_radius_mm":0.8,"radius_mm":30},
            {"radius_mm":-30,"offset_mm":0.0213}]}"#,
        3.0,
    ))
    .unwrap();
    let report = spiralcam::plan::Planner::new(&job)
        .unwrap()
        .run(spiralcam::plan::Sinks::default(), &mut |_| {
            ControlFlow::Continue(())
        })
        .unwrap();
    assert!(
        report
            .warnings
            .iter()
            .any(|w| w.starts_with("zoned asphere: at the zone boundary r = 0.8 mm")),
        "{:?}",
        report.warnings
    );
    assert!(report.surface.contains("boundaries [at 0.8 mm step"));
}

#[test]
fn bad_parameters_name_their_field() {
    let cases = [
        (
            r#"{"type":"zoned_asphere","zones":[]}"#,
            "surface.zones",
            "0 zones",
        ),
        (
            r#"{"type":"zoned_asphere","zones":[{"radius_mm":20},{"radius_mm":30}]}"#,
            "surface.zones[0].outer_radius_mm",
            "missing",
        ),
        (
            r#"{"type":"zoned_asphere","zones":[{"outer_radius_mm":2,"radius_mm":20},{"outer_radius_mm":2,"radius_mm":30}]}"#,
            "surface.zones[1].outer_radius_mm",
            "2",
        ),
        (
            r#"{"type":"zoned_asphere","zones":[{"outer_radius_mm":2,"radius_mm":20},{"curvature_per_mm":0,"coefficients":[1,2,3,4,5,6,7,8,9,10]}]}"#,
            "surface.zones[1].coefficients",
            "10 terms",
        ),
        (
            r#"{"type":"zoned_asphere","zones":[{"outer_radius_mm":6,"radius_mm":5}]}"#,
            "surface.zones[0].conic",
            "0",
        ),
    ];
    for (json, field, value) in cases {
        let e = field_error(json);
        assert_eq!((e.field.as_str(), e.value.as_str()), (field, value), "{e}");
    }
    // Beyond a bounded last zone the surface is undefined.
    let s = build(&[
        (Some(2.0), 20.0, 0.0, [0.0, 0.0], 0.0),
        (Some(4.0), 30.0, 0.0, [0.0, 0.0], 0.0),
    ]);
    let e = s.local(3.0, 3.0).unwrap_err();
    assert!(
        e.to_string()
            .contains("beyond the outermost zone's outer radius 4 mm"),
        "{e}"
    );
}

#[test]
fn planned_paths_touch_without_cutting() {
    // Three zones meeting in value with convex and concave slope jumps, and a 2 µm step: the
    // boundary circles at 0.6 and 1.1 mm are the kinks of every radial section.
    let kinks = |_: f64, _: f64| vec![-1.1, -0.6, 0.6, 1.1];
    let continuous = small_job(
        "zoned",
        r#"{"type":"zoned_asphere","zones":[{"outer_radius_mm":0.6,"radius_mm":40,"conic":-1},
            {"outer_radius_mm":1.1,"radius_mm":50,"conic":-1,"offset_mm":0.0009},
            {"radius_mm":40,"conic":-1,"offset_mm":-0.002125}]}"#,
        3.0,
    );
    assert!(check_planned_path(&continuous, &kinks, 2000) > 200);
    let stepped = small_job(
        "zoned-step",
        r#"{"type":"zoned_asphere","zones":[{"outer_radius_mm":0.6,"radius_mm":-30},
            {"outer_radius_mm":1.1,"radius_mm":-30,"offset_mm":0.002},{"radius_mm":-35}]}"#,
        3.0,
    );
    assert!(check_planned_path(&stepped, &kinks, 2000) > 200);
    // Ridges only (the slope drops outwards at both boundaries): the section bounds hold, so
    // the contacts come from the concave shortcut, the boundaries probed.
    let ridges = small_job(
        "zoned-ridges",
        r#"{"type":"zoned_asphere","zones":[{"outer_radius_mm":0.6,"radius_mm":40,"conic":-1},
            {"outer_radius_mm":1.1,"radius_mm":50,"conic":-1,"offset_mm":0.0009},
            {"radius_mm":60,"conic":-1,"offset_mm":0.002916666666666667}]}"#,
        3.0,
    );
    let planner = Planner::new(&Job::from_json(&ridges).unwrap()).unwrap();
    assert!(planner.path().concavity().is_some());
    assert!(check_planned_path(&ridges, &kinks, 2000) > 200);
}

#[test]
fn the_example_job_builds() {
    check_example_jobs(&[("zoned-asphere.json", "zoned asphere, 3 zones")]);
}
