//! The spindle axis along the design's normal at a chosen point (`part.normal_axis_at_mm`,
//! paper 001's rotation axis `t`), through the public API: an off-axis sphere segment seen
//! along its normal is the sphere on its axis (closed form); random designs against a
//! bisection of the axis-parallel line with the design (an independent root finder on the sag
//! alone) and their derivatives against finite differences; slope kinks under a tilt against a
//! brute-force scan of the section's slope; a tilted lens array planned gouge-free; and the
//! surface-of-revolution survey, which finds the off-axis sphere of revolution about its normal
//! and not about Z.

mod common;

use common::{check_derivatives, check_planned_path, config, local, random_xy_polynomial};
use proptest::prelude::*;
use spiralcam::job::Job;
use spiralcam::path::space_spiral::survey;
use spiralcam::plan::Planner;
use spiralcam::surface::{Line, Surface};

/// A job around `surface` (JSON) on a part of radius `radius` with the axis at `at`.
fn job_json(surface: &str, radius: f64, at: [f64; 2]) -> String {
    format!(
        r#"{{"name":"axis","part":{{"diameter_mm":{},"normal_axis_at_mm":[{},{}]}},
            "surface":{surface},"tool":{{"nose_radius_mm":0.1}},"machine":{{"spindle_rpm":100}},
            "strategy":{{"feed_mm_per_rev":0.05,"sampling":{{"type":"constant_angle","points_per_rev":90}}}}}}"#,
        2.0 * radius,
        at[0],
        at[1]
    )
}

fn surface_of(json: &str) -> Box<dyn Surface> {
    let job = Job::from_json(json).unwrap_or_else(|e| panic!("{json}: {e}"));
    job.validate().unwrap();
    job.build_surface()
        .unwrap_or_else(|e| panic!("{json}: {e}"))
}

fn off_axis_sphere(radius: f64, distance: f64) -> String {
    format!(
        r#"{{"type":"off_axis_conic","parent":{{"radius_mm":{radius}}},"off_axis_distance_mm":{distance}}}"#
    )
}

/// Seen along its normal at the segment's centre, a segment of a sphere of radius R is the
/// sphere with its vertex on the axis: g = R − √(R² − ρ²) (sign of R kept), with
/// g_u = u/w, g_uu = (R² − v²)/w³, g_uv = uv/w³ (w = √(R² − ρ²), times sign R). Newton stops
/// at rounding, so 1e-12 mm on the sag; the derivatives are exact formulas, 1e-10.
#[test]
fn off_axis_sphere_segment_is_the_sphere_on_its_normal() {
    for (radius, distance) in [(20.0, 6.0), (-20.0, 6.0), (35.0, 12.5)] {
        let s = surface_of(&job_json(
            &off_axis_sphere(radius, distance),
            3.0,
            [0.0, 0.0],
        ));
        assert!(s.describe().contains("tilted"), "{}", s.describe());
        let r: f64 = radius;
        for (u, v) in [(0.0, 0.0), (1.0, 0.0), (-2.0, 1.5), (0.3, -2.9), (2.1, 2.0)] {
            let l = local(s.as_ref(), u, v);
            let w = (r * r - u * u - v * v).sqrt();
            let sign = r.signum();
            let z = sign * (r.abs() - w);
            assert!((l.z - z).abs() < 1e-12, "R {r} ({u}, {v}): {} vs {z}", l.z);
            let w3 = w * w * w;
            let expect = [
                sign * u / w,
                sign * v / w,
                sign * (r * r - v * v) / w3,
                sign * u * v / w3,
                sign * (r * r - u * u) / w3,
            ];
            let got = [l.zx, l.zy, l.zxx, l.zxy, l.zyy];
            for (g, e) in got.iter().zip(expect) {
                assert!(
                    (g - e).abs() < 1e-10,
                    "R {r} ({u}, {v}): {got:?} vs {expect:?}"
                );
            }
        }
    }
}

/// Where the design's normal is Z (a lenslet's apex), the axis only moves the apex to z = 0:
/// the same sag less the apex's, the same derivatives and kinks, exactly.
#[test]
fn an_axis_along_z_changes_nothing() {
    let array = r#"{"type":"lens_array","lens_radius_mm":2.84,"aperture_mm":1.0,"pitch_mm":1.0,"grid":"hexagonal","form":"concave"}"#;
    let moved = surface_of(&job_json(array, 2.0, [0.0, 0.0]));
    let plain = Job::from_json(&job_json(array, 2.0, [0.0, 0.0])).unwrap();
    let plain = plain.surface.build(2.0).unwrap();
    for (x, y) in [(0.0, 0.0), (0.4, -0.3), (1.7, 0.2), (-0.9, 1.1)] {
        let apex = plain.sag(0.0, 0.0).unwrap();
        let mut expect = local(plain.as_ref(), x, y);
        expect.z -= apex;
        assert_eq!(local(moved.as_ref(), x, y), expect);
        let line = Line {
            x0: x,
            y0: y,
            c: 0.6,
            s: 0.8,
        };
        let (mut a, mut b) = (Vec::new(), Vec::new());
        moved.slope_kinks(line, -1.0, 1.0, &mut a);
        plain.slope_kinks(line, -1.0, 1.0, &mut b);
        assert_eq!(a, b);
    }
}

/// The documented frame, built here from the design's normal at P.
fn frame(design: &dyn Surface, at: [f64; 2]) -> ([f64; 3], [[f64; 3]; 3]) {
    let l = local(design, at[0], at[1]);
    let e3 = l.normal();
    let x = [1.0 - e3[0] * e3[0], -e3[0] * e3[1], -e3[0] * e3[2]];
    let n = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    let e1 = [x[0] / n, x[1] / n, x[2] / n];
    let e2 = [
        e3[1] * e1[2] - e3[2] * e1[1],
        e3[2] * e1[0] - e3[0] * e1[2],
        e3[0] * e1[1] - e3[1] * e1[0],
    ];
    ([at[0], at[1], l.z], [e1, e2, e3])
}

/// Where the line `(u, v) + s·e₃` meets the design: a scan of `h(s)` for a sign change, then
/// bisection to the last bit (sag only; no derivatives, no Newton).
fn bisected_height(design: &dyn Surface, at: [f64; 2], u: f64, v: f64) -> f64 {
    let (o, [e1, e2, e3]) = frame(design, at);
    let h = |s: f64| {
        let p = |k: usize| o[k] + u * e1[k] + v * e2[k] + s * e3[k];
        p(2) - design.sag(p(0), p(1)).unwrap()
    };
    let (mut lo, mut hi) = (-2.0, -2.0);
    for k in 1..=4000 {
        hi = -2.0 + k as f64 * 1e-3;
        if h(lo).signum() != h(hi).signum() {
            break;
        }
        lo = hi;
    }
    assert!(
        h(lo).signum() != h(hi).signum(),
        "no crossing at ({u}, {v})"
    );
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid == lo || mid == hi {
            break;
        }
        if h(mid).signum() == h(lo).signum() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

proptest! {
    #![proptest_config(config(24, 0x6e6f726d))]

    /// Random XY polynomials (slopes ≤ ~0.3) with the axis at a random point of the inner half:
    /// the sag agrees with the bisection to 1e-11 mm (both stop at rounding of sags ≤ 1 mm),
    /// the derivatives with central finite differences (the common tolerances).
    #[test]
    fn random_designs_match_bisection_and_finite_differences(
        design in random_xy_polynomial(),
        (ax, ay, u, v) in (-0.5..0.5f64, -0.5..0.5f64, -0.5..0.5f64, -0.5..0.5f64),
    ) {
        let r = design.part_radius;
        let at = [ax * r, ay * r];
        let job = Job::from_json(&job_json(&design.json, r, at)).unwrap();
        let reframed = job.build_surface().unwrap();
        let plain = job.surface.build(r).unwrap();
        let (u, v) = (u * r, v * r);
        let expect = bisected_height(plain.as_ref(), at, u, v);
        let got = local(reframed.as_ref(), u, v).z;
        prop_assert!((got - expect).abs() < 1e-11, "({u}, {v}): {got} vs {expect}");
        check_derivatives(reframed.as_ref(), u, v)?;
    }
}

/// A rectangular lens array (pitch 1 mm, lenslets R 2.84 mm meeting at their rims) seen along
/// the normal at (0.3, 0.2) mm, tilted 7.2°: every slope jump found by a dense scan of the
/// section's slope along random lines (step 2 µm; a rim jump is ≥ 0.1, the smooth change per
/// step ≤ 1e-3) is reported within 4 µm, and every reported kink is such a jump.
#[test]
fn tilted_kinks_match_a_brute_force_scan() {
    let array = r#"{"type":"lens_array","lens_radius_mm":2.84,"aperture_mm":1.0,"pitch_mm":1.0,"grid":"rectangular","form":"convex"}"#;
    let s = surface_of(&job_json(array, 2.0, [0.3, 0.2]));
    assert!(s.describe().contains("tilted 7."), "{}", s.describe());
    let step = 2e-6;
    let radial = 112.25957748827528f64 % std::f64::consts::TAU;
    for (k, angle) in [0.0f64, 0.7, 1.9, 2.6, 4.0, radial].iter().enumerate() {
        let k0 = if k == 5 { 0.0 } else { k as f64 };
        let line = Line {
            x0: 0.05 * k0,
            y0: -0.03 * k0,
            c: angle.cos(),
            s: angle.sin(),
        };
        let (t0, t1) = (-1.5, 1.5);
        let mut reported = Vec::new();
        s.slope_kinks(line, t0, t1, &mut reported);
        let n = ((t1 - t0) / step) as usize;
        let g: Vec<f64> = (0..=n)
            .map(|i| {
                let (x, y) = line.at(t0 + i as f64 * step);
                s.sag(x, y).unwrap()
            })
            .collect();
        let mut jumps = Vec::new();
        for i in 1..n {
            let change = (g[i + 1] - 2.0 * g[i] + g[i - 1]) / step;
            if change.abs() > 0.02 {
                jumps.push(t0 + i as f64 * step);
            }
        }
        assert!(!jumps.is_empty(), "line {k}: the scan finds the rims");
        for j in &jumps {
            assert!(
                reported.iter().any(|t| (t - j).abs() <= 2.0 * step),
                "line {k}: jump at {j} not reported ({reported:?})"
            );
        }
        for t in &reported {
            assert!(
                jumps.iter().any(|j| (t - j).abs() <= 2.0 * step),
                "line {k}: kink {t} is no jump ({jumps:?})"
            );
        }
    }
}

/// The same tilted lens array planned: every point touches the design within 0.1 nm and cuts
/// nowhere (the common dense check, with both sides of each reported kink sampled).
#[test]
fn tilted_lens_array_plans_gouge_free() {
    let array = r#"{"type":"lens_array","lens_radius_mm":2.84,"aperture_mm":1.0,"pitch_mm":1.0,"grid":"rectangular","form":"convex"}"#;
    let json = job_json(array, 1.2, [0.3, 0.2]);
    // The lenslets' bounds on every line carry over to the tilted frame, their rims still
    // valleys: the nose height is searched stretch by stretch between them.
    let planner = Planner::new(&Job::from_json(&json).unwrap()).unwrap();
    assert!(planner.path().concavity().is_some_and(|c| c.valleys));
    let s = surface_of(&json);
    let kinks = |c: f64, sn: f64| {
        let mut out = Vec::new();
        s.slope_kinks(Line::radial(c, sn), -1.2, 1.2, &mut out);
        out
    };
    assert!(check_planned_path(&json, &kinks, 4000) > 2000);
}

/// An off-axis paraboloid segment and a sphere seen along their normals: the design's bounds
/// over a disc carry over to the tilted frame (`Surface::section_bounds` of the reframed
/// surface), so the path comes from the concave shortcut; every point touches within 0.1 nm.
#[test]
fn tilted_smooth_designs_plan_by_the_shortcut_and_touch() {
    let none = |_: f64, _: f64| Vec::new();
    let paraboloid = r#"{"type":"off_axis_conic","parent":{"radius_mm":30,"conic":-1},"off_axis_distance_mm":8}"#;
    for json in [
        job_json(paraboloid, 2.0, [0.0, 0.0]),
        job_json(&off_axis_sphere(-25.0, 0.0), 2.0, [3.0, -1.0]),
    ] {
        let planner = Planner::new(&Job::from_json(&json).unwrap()).unwrap();
        assert!(planner.path().concavity().is_some(), "{json}");
        assert!(check_planned_path(&json, &none, 4000) > 2000);
    }
}

/// About Z the off-axis sphere segment is tilted (max α ≈ 17°, not of quasi-revolution);
/// about its normal it is a sphere of revolution: the base fit leaves < 1e-4 µm, max α < 1e-3°.
#[test]
fn survey_finds_the_sphere_about_its_normal() {
    let sphere = off_axis_sphere(20.0, 6.0);
    let plain = Job::from_json(&job_json(&sphere, 3.0, [0.0, 0.0])).unwrap();
    let about_z = survey(plain.surface.build(3.0).unwrap().as_ref(), 3.0, 0.05).unwrap();
    assert!(about_z.quasi_revolution.max_alpha_deg > 10.0, "{about_z:?}");
    assert!(!about_z.quasi_revolution.is_quasi_revolution, "{about_z:?}");
    let about_normal = survey(surface_of(&plain.to_json()).as_ref(), 3.0, 0.05).unwrap();
    assert!(about_normal.base_fit_max_um < 1e-4, "{about_normal:?}");
    assert!(
        about_normal.quasi_revolution.max_alpha_deg < 1e-3,
        "{about_normal:?}"
    );
    assert!(about_normal.quasi_revolution.is_quasi_revolution);
}

/// A point where the design is undefined, or not a number, is refused naming the field.
#[test]
fn bad_axis_points_are_refused() {
    let sphere = r#"{"type":"asphere","radius_mm":5.0}"#;
    let job = Job::from_json(&job_json(sphere, 2.0, [6.0, 0.0])).unwrap();
    let e = job.build_surface().unwrap_err().to_string();
    assert!(e.starts_with("part.normal_axis_at_mm = [6, 0]"), "{e}");
    let text = job_json(sphere, 2.0, [0.0, 0.0]).replace("[0,0]", "[1e999,0]");
    let e = Job::from_json(&text).map(|j| j.validate());
    assert!(matches!(e, Ok(Err(_)) | Err(_)), "{e:?}");
}

#[test]
fn the_example_job_builds() {
    common::check_example_jobs(&[(
        "off-axis-parabola-normal-axis.json",
        "on a spindle axis along its normal",
    )]);
}
