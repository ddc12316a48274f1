//! The measured tool edge (`tool.waviness`, issue 15): the one-way compensation with the edge
//! radius r(a) = r + δ(a), against references that do not use the library's compensation.
//!
//! - A constant δ is exactly a nose of radius r + δ: every path point (tip height, contact)
//!   within 1e-12 mm, and the predicted form's figures within 1e-6 µm.
//! - A linear δ(a) on a sphere and on a tilted flat against a brute-force maximum of
//!   `F(a) = f(ρ_s + R(a)·sin a) + R(a)·cos a` over 400 001 nose angles, R(a) written out here as
//!   the line (not read from the library): the tip within 1e-10 mm (the sampled maximum is within
//!   `F″·Δa²/8 < 3e-12` mm of the true one).
//! - A wavy edge (0.3 µm·sin 9a) on a sinusoidal grid: the gouge check of every path point with
//!   the measured edge, the gap `z_c − R(a)·cos a − f(ρ_s + R(a)·sin a)` sampled at 4 000 nose
//!   angles plus the contact: it touches within 0.1 nm and cuts nowhere deeper than 0.1 nm once
//!   the sampling bound (`K·Δa²/8`, K from the bounds of R, R′, R″ and the sampled |f′|, |f″|
//!   doubled) is subtracted.
//! - Refusals: two-way compensation with a measured edge, and a non-convex edge in the predicted
//!   form, each naming `tool.waviness`.

mod common;

use common::{TOUCH, path_points, planner_of, small_job};
use spiralcam::analysis::predicted_form::{FormSettings, predict};
use spiralcam::job::{ToolSpec, WavinessSpec};
use spiralcam::surface::{Surface, SurfaceSpec};
use spiralcam::tool::{NoseCompensator, Waviness};

/// A job on a concave sphere R 20, Ø6, with the tool `tool` (JSON).
fn sphere_job(tool: &str) -> String {
    format!(
        r#"{{"name":"wavy","part":{{"diameter_mm":6}},
            "surface":{{"type":"asphere","radius_mm":20}},
            "tool":{tool},"machine":{{"spindle_rpm":300}},
            "strategy":{{"feed_mm_per_rev":0.02,"sampling":{{"type":"constant_angle","points_per_rev":90}}}}}}"#
    )
}

#[test]
fn a_constant_deviation_is_a_larger_nose_exactly() {
    let wavy = planner_of(&sphere_job(
        r#"{"nose_radius_mm":0.1,"waviness":{"angle_deg":[-60,-5,20,60],"deviation_um":[0.4,0.4,0.4,0.4]}}"#,
    ));
    let larger = planner_of(&sphere_job(r#"{"nose_radius_mm":0.1004}"#));
    let (a, b) = (path_points(&wavy), path_points(&larger));
    assert_eq!(a.len(), b.len());
    for (p, q) in a.iter().zip(&b) {
        assert_eq!((p.rho, p.theta), (q.rho, q.theta));
        assert!(
            (p.z - q.z).abs() < 1e-12,
            "point {}: {} vs {}",
            p.index,
            p.z,
            q.z
        );
        for k in 0..3 {
            assert!(
                (p.contact[k] - q.contact[k]).abs() < 1e-9,
                "point {}",
                p.index
            );
        }
    }
    let settings = FormSettings::default();
    let fa = predict(&wavy, &settings, 0, |_| {}).unwrap();
    let fb = predict(&larger, &settings, 0, |_| {}).unwrap();
    for (x, y) in [
        (fa.pv_um, fb.pv_um),
        (fa.rms_um, fb.rms_um),
        (fa.cusp_height_um, fb.cusp_height_um),
        (fa.max_overcut_um, fb.max_overcut_um),
    ] {
        assert!((x - y).abs() < 1e-6, "{fa:?}\n{fb:?}");
    }
    assert_eq!(fa.samples, fb.samples);
    assert!(fa.cusp_height_um > 0.0);
}

/// δ(a) = 0.1 + 0.004·a µm, a in degrees.
fn linear_deviation_um(a_deg: f64) -> f64 {
    0.1 + 0.004 * a_deg
}

/// The tip height of the brute-force maximum over `n + 1` nose angles in [−β/2, β/2].
fn brute_tip(
    surface: &dyn Surface,
    r: f64,
    beta_deg: f64,
    rho_s: f64,
    theta: f64,
    n: usize,
) -> f64 {
    let (s, c) = theta.sin_cos();
    let half = (beta_deg / 2.0).to_radians();
    let radius = |a: f64| r + 1e-3 * linear_deviation_um(a.to_degrees());
    let mut best = f64::NEG_INFINITY;
    for i in 0..=n {
        let a = -half + 2.0 * half * i as f64 / n as f64;
        let big_r = radius(a);
        let rho = rho_s + big_r * a.sin();
        let f = surface.sag(rho * c, rho * s).unwrap() + big_r * a.cos();
        best = best.max(f);
    }
    best - radius(0.0)
}

#[test]
fn a_linear_deviation_matches_a_brute_force_maximum_on_a_sphere_and_a_tilted_flat() {
    let angles = [-55.0, -30.0, -2.0, 17.0, 55.0];
    let tool = ToolSpec {
        waviness: Some(WavinessSpec {
            angle_deg: angles.to_vec(),
            deviation_um: angles.iter().map(|&a| linear_deviation_um(a)).collect(),
        }),
        ..ToolSpec::with_nose_radius(0.5)
    };
    let surfaces = [
        r#"{"type":"asphere","radius_mm":20}"#,
        r#"{"type":"asphere","radius_mm":-15,"conic":-0.6}"#,
        r#"{"type":"tilted_flat","tilt_deg":20,"azimuth_deg":30}"#,
    ];
    for json in surfaces {
        let spec: SurfaceSpec = serde_json::from_str(json).unwrap();
        let surface = spec.build(10.0).unwrap();
        let nose = NoseCompensator::new(&tool, surface.feature_length_mm(), 10.0).unwrap();
        for &rho_s in &[0.0, 1.3, 4.0, 7.5] {
            for &theta in &[0.0, 1.1, 3.5] {
                let (s, c) = f64::sin_cos(theta);
                let got = nose
                    .compensate(surface.as_ref(), rho_s, c, s)
                    .unwrap()
                    .z_tip;
                let want = brute_tip(surface.as_ref(), 0.5, 100.0, rho_s, theta, 400_000);
                assert!(
                    (got - want).abs() < 1e-10,
                    "{json} ρ {rho_s} θ {theta}: {got} vs brute force {want} ({:e})",
                    got - want
                );
            }
        }
    }
}

#[test]
fn a_wavy_edge_leaves_a_gouge_free_path() {
    let angles: Vec<f64> = (-30..=30).map(|k| 2.0 * k as f64).collect();
    let deviations: Vec<String> = angles
        .iter()
        .map(|a: &f64| format!("{:.6}", 0.3 * (9.0 * a.to_radians()).sin()))
        .collect();
    let angle_list: Vec<String> = angles.iter().map(|a| a.to_string()).collect();
    let surface = r#"{"type":"sinusoid","amplitude_mm":0.002,"wavelength_x_mm":1.5,"wavelength_y_mm":2.0,"phase_x_deg":20,"phase_y_deg":50}"#;
    let json = small_job("wavy-gouge", surface, 4.0).replace(
        r#""tool":{"nose_radius_mm":0.1,"included_angle_deg":100}"#,
        &format!(
            r#""tool":{{"nose_radius_mm":0.1,"included_angle_deg":100,"waviness":{{"angle_deg":[{}],"deviation_um":[{}]}}}}"#,
            angle_list.join(","),
            deviations.join(",")
        ),
    );
    let planner = planner_of(&json);
    let edge = planner.nose().waviness().expect("the job's edge").clone();
    let tip = edge.radius(0.0)[0];
    let surface = planner.surface();
    let limit = planner.job().part_radius_mm();
    let half = 50f64.to_radians();
    let samples = 4000;
    let da = 2.0 * half / samples as f64;
    // Bounds of R, R′, R″ over the arc (sampled densely, doubled).
    let (mut r_max, mut r1_max, mut r2_max): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for i in 0..=20 * samples {
        let [rr, r1, r2] = edge.radius(-half + 2.0 * half * i as f64 / (20 * samples) as f64);
        r_max = r_max.max(rr);
        r1_max = r1_max.max(2.0 * r1.abs());
        r2_max = r2_max.max(2.0 * r2.abs());
    }
    let mut checked = 0;
    for p in path_points(&planner) {
        let (s, c) = p.theta.sin_cos();
        let z_c = p.z + tip;
        let contact = p.contact[0] * c + p.contact[1] * s;
        let mut angles: Vec<f64> = (0..=samples).map(|i| -half + da * i as f64).collect();
        angles.push(edge.angle_at_offset(contact - p.rho));
        let (mut min, mut at) = (f64::INFINITY, 0.0);
        let (mut f1, mut f2): (f64, f64) = (0.0, 0.0);
        for a in angles {
            let rr = edge.radius(a)[0];
            let rho = p.rho + rr * a.sin();
            if rho.abs() > limit {
                continue;
            }
            let l = surface.local(rho * c, rho * s).unwrap().radial(c, s);
            let gap = z_c - rr * a.cos() - l.z;
            if gap < min {
                (min, at) = (gap, a);
            }
            f1 = f1.max(2.0 * l.slope.abs());
            f2 = f2.max(2.0 * l.curvature_term.abs());
        }
        let (u1, u2) = (r_max + r1_max, r2_max + 2.0 * r1_max + r_max);
        let k = u2 + f2 * u1 * u1 + f1 * u2;
        let bound = k * da * da / 8.0;
        assert!(bound < 0.2 * TOUCH, "point {}: bound {bound:e}", p.index);
        assert!(
            min <= TOUCH,
            "point {}: does not touch, gap {min:e}",
            p.index
        );
        assert!(
            min - bound >= -TOUCH,
            "point {} (ρ {}, θ {}): the measured edge cuts {:e} mm at a = {at}",
            p.index,
            p.rho,
            p.theta,
            -min
        );
        checked += 1;
    }
    assert_eq!(checked, planner.spiral().point_count_hint());
}

#[test]
fn two_way_compensation_and_a_concave_edge_are_refused_by_name() {
    let tool = r#"{"nose_radius_mm":0.1,"waviness":{"angle_deg":[-60,60],"deviation_um":[0,0.1]}}"#;
    let job = sphere_job(tool).replace(r#""sampling""#, r#""compensation":"two_way","sampling""#);
    let e = spiralcam::plan::Planner::new(&spiralcam::job::Job::from_json(&job).unwrap())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("tool.waviness = set: is used by the one-way"),
        "{e}"
    );
    // A sharp bump of 3 µm over 2° bends the 0.1 mm edge inwards: it still compensates, but the
    // predicted form needs a convex edge.
    let bump = r#"{"nose_radius_mm":0.1,"waviness":{"angle_deg":[-60,-1,0,1,60],"deviation_um":[0,0,3,0,0]}}"#;
    let planner = planner_of(&sphere_job(bump));
    assert!(
        Waviness::new(
            planner.job().tool.waviness.as_ref().unwrap(),
            0.1,
            50f64.to_radians()
        )
        .unwrap()
        .first_concave(-0.8, 0.8)
        .is_some()
    );
    let e = predict(&planner, &FormSettings::default(), 0, |_| {})
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("tool.waviness = the measured edge near a = "),
        "{e}"
    );
}
