//! The concave-zone report (`reach::concave_zones`, `Planner::concave_zones`): a convex lens
//! array, whose lenslet feet are slope kinks no nose can fill, reports zones whose depth equals
//! an independent brute-force morphological closing of the radial section at the reported
//! angle (itself checked against the closed-form fillet of a circle and a line); the concave
//! paper 004 array with r = 0.5 mm reports none; a spherical bowl of radius smaller than the nose
//! reports one zone at the centre with the closed-form depth; a nose that fits reports none.
//!
//! The oracle is `common::Closing`, whose docs derive its accuracy: ~0.02 nm (checked against
//! closed forms to 0.05 nm, `common::ORACLE_TOL`); the library refines by golden-section search
//! to ~1e-11 mm. Depths are compared within 1 nm (`common::DEPTH_TOL`).

mod common;

use common::{Closing, DEPTH_TOL, ORACLE_TOL};
use spiralcam::job::Job;
use spiralcam::job::ToolSpec;
use spiralcam::plan::Planner;
use spiralcam::progress::ignore;
use spiralcam::surface::{Surface, SurfaceSpec};
use spiralcam::tool::NoseCompensator;
use spiralcam::tool::reach::{LISTED_DEPTH_MM, concave_zones};

fn surface(json: &str, part_radius: f64) -> Box<dyn Surface> {
    let spec: SurfaceSpec = serde_json::from_str(json).expect("surface JSON");
    spec.build(part_radius).expect("valid surface")
}

fn nose(r: f64, beta: f64, s: &dyn Surface, part_radius: f64) -> NoseCompensator {
    NoseCompensator::new(
        &ToolSpec {
            nose_radius_mm: r,
            included_angle_deg: beta,
            ..ToolSpec::with_nose_radius(0.0)
        },
        s.feature_length_mm(),
        part_radius,
    )
    .expect("valid tool")
}

/// The signed radial coordinates where the section at `theta_deg` crosses the rim (radius
/// `half`) of a lenslet centred at each of `centres`.
fn rim_crossings(centres: &[(f64, f64)], half: f64, theta_deg: f64) -> Vec<f64> {
    let (s, c) = theta_deg.to_radians().sin_cos();
    let mut out = Vec::new();
    for &(cx, cy) in centres {
        let along = cx * c + cy * s;
        let across = -cx * s + cy * c;
        let d2 = half * half - across * across;
        if d2 >= 0.0 {
            out.extend([along - d2.sqrt(), along + d2.sqrt()]);
        }
    }
    out
}

// A convex array of small lenslets: R 0.5 mm, aperture 0.2 mm, pitch 0.25 mm, Ø1 mm part.
const CONVEX: &str = r#"{"type":"lens_array","lens_radius_mm":0.5,"aperture_mm":0.2,"pitch_mm":0.25,"grid":"rectangular","form":"convex"}"#;
const CONVEX_PART: f64 = 0.5;
const CONVEX_R: f64 = 0.05;

/// The cut lenslet centres of [`CONVEX`]: lattice nodes with |c| + a/2 ≤ part radius.
fn convex_centres() -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in -3i32..=3 {
        for j in -3i32..=3 {
            let (cx, cy) = (0.25 * i as f64, 0.25 * j as f64);
            if cx.hypot(cy) + 0.1 <= CONVEX_PART {
                out.push((cx, cy));
            }
        }
    }
    out
}

#[test]
fn the_oracle_matches_the_closed_form_fillet_at_a_lenslet_foot() {
    // Section θ = 0 through the lenslet at (0.25, 0): its outer foot is at u_k = 0.35, land
    // beyond. The nose rests on the land (centre height r) and on the lenslet's sphere (centre
    // (0.25, −√(R² − a²/4)), radius R): its centre is at x_n with
    // (x_n − 0.25)² + (r + √(R² − a²/4))² = (R + r)², and the cut at the foot is
    // r − √(r² − (x_n − u_k)²) above the land.
    let s = surface(CONVEX, CONVEX_PART);
    let (big, half, r) = (0.5f64, 0.1f64, CONVEX_R);
    let rim_w = (big * big - half * half).sqrt();
    let x_n = 0.25 + ((big + r).powi(2) - (r + rim_w).powi(2)).sqrt();
    let u_k = 0.35;
    let closed = r - (r * r - (x_n - u_k).powi(2)).sqrt();
    let closing = Closing::new(s.as_ref(), 0.0, r, 100.0, CONVEX_PART, u_k);
    let brute = closing.residual(u_k);
    assert!(
        (brute - closed).abs() < ORACLE_TOL,
        "oracle {brute} vs closed form {closed}"
    );
    // ~0.24 µm: the depth the library should report for the sharpest feet.
    assert!((closed - 2.436e-4).abs() < 1e-6, "{closed}");
}

#[test]
fn a_convex_lens_array_reports_zones_as_deep_as_the_brute_force_closing() {
    let s = surface(CONVEX, CONVEX_PART);
    let n = nose(CONVEX_R, 100.0, s.as_ref(), CONVEX_PART);
    let reach = concave_zones(s.as_ref(), &n, CONVEX_PART, &mut ignore).unwrap();
    assert!(!reach.zones.is_empty(), "{reach:?}");
    assert_eq!(reach.unlisted_zones, 0);
    for w in reach.zones.windows(2) {
        assert!(w[0].depth_um >= w[1].depth_um, "not deepest first");
    }
    let centres = convex_centres();
    // Three zones at different feet (e.g. the rim of the central lenslet, an outer foot on an
    // axis, a foot on a diagonal).
    let mut checked: Vec<&spiralcam::tool::reach::ConcaveZone> = Vec::new();
    for z in &reach.zones {
        if checked.len() < 3
            && checked
                .iter()
                .all(|c| (c.at.rho_mm - z.at.rho_mm).abs() > 1e-3)
        {
            checked.push(z);
        }
    }
    assert_eq!(checked.len(), 3, "{:?}", reach.zones);
    for z in checked {
        assert!(z.slope_kink, "{z:?}");
        assert!(z.min_curvature_radius_mm < CONVEX_R, "{z:?}");
        assert!(z.depth_um >= LISTED_DEPTH_MM * 1e3);
        let (v, theta) = (z.at.rho_mm, z.at.theta_deg);
        // The deepest point is a lenslet foot on that section.
        let foot = rim_crossings(&centres, 0.1, theta)
            .into_iter()
            .min_by(|a, b| (a - v).abs().total_cmp(&(b - v).abs()))
            .expect("the section crosses a lenslet");
        assert!(
            (foot - v).abs() < 1e-6,
            "deepest at {v}, nearest foot {foot}"
        );
        assert!(
            z.rho_min_mm <= v + 0.01 && v - 0.01 <= z.rho_max_mm,
            "{z:?}"
        );
        let closing = Closing::new(s.as_ref(), theta, CONVEX_R, 100.0, CONVEX_PART, v);
        let brute = closing.residual(v);
        let depth = z.depth_um * 1e-3;
        assert!(
            (brute - depth).abs() <= DEPTH_TOL,
            "zone at {theta}°, ρ {v}: reported {depth} mm, brute force {brute} mm"
        );
        // And it is the deepest point around: the closing residual is smaller on both sides.
        for dv in [-5e-4, 5e-4] {
            let other = closing.residual(v + dv);
            assert!(
                other <= depth + DEPTH_TOL,
                "ρ {}: residual {other} > reported {depth}",
                v + dv
            );
        }
    }
    // The sections through a lenslet centre (θ = 0°, 90°, …) cross the feet most steeply.
    let deepest = &reach.zones[0];
    let r = CONVEX_R;
    let rim_w = (0.25f64 - 0.01).sqrt();
    let x_n = 0.25 + ((0.5 + r) * (0.5 + r) - (r + rim_w) * (r + rim_w)).sqrt();
    let closed = r - (r * r - (x_n - 0.35).powi(2)).sqrt();
    assert!(
        (deepest.depth_um * 1e-3 - closed).abs() <= DEPTH_TOL,
        "{} vs {closed}",
        deepest.depth_um * 1e-3
    );
}

#[test]
fn the_planner_reports_the_same_zones() {
    let job = format!(
        r#"{{"name":"convex-small","part":{{"diameter_mm":{}}},"surface":{CONVEX},
            "tool":{{"nose_radius_mm":{CONVEX_R}}},"machine":{{"spindle_rpm":1000}},
            "strategy":{{"feed_mm_per_rev":0.05,"sampling":{{"type":"constant_angle","points_per_rev":24}}}}}}"#,
        2.0 * CONVEX_PART
    );
    let planner = Planner::new(&Job::from_json(&job).unwrap()).unwrap();
    assert_eq!(planner.spiral().start_radius_mm(), CONVEX_PART);
    let s = surface(CONVEX, CONVEX_PART);
    let n = nose(CONVEX_R, 100.0, s.as_ref(), CONVEX_PART);
    let direct = concave_zones(s.as_ref(), &n, CONVEX_PART, &mut ignore).unwrap();
    assert_eq!(planner.concave_zones(&mut ignore).unwrap(), direct);
}

#[test]
fn the_concave_paper004_array_reports_no_zone() {
    // Dimples of R 2.84 mm > r = 0.5 mm, and their rims are convex kinks: the nose reaches
    // everything.
    let job = Job::default_job();
    assert_eq!(job.tool.nose_radius_mm, 0.5);
    assert!(matches!(job.surface, SurfaceSpec::LensArray(_)));
    let planner = Planner::new(&job).unwrap();
    let reach = planner.concave_zones(&mut ignore).unwrap();
    assert!(reach.zones.is_empty(), "{:?}", reach.zones);
    assert_eq!(reach.unlisted_zones, 0);
    let spec = spiralcam::surface::LensArraySpec::paper004();
    let s = SurfaceSpec::LensArray(spec).build(5.0).unwrap();
    let n = nose(0.5, 100.0, s.as_ref(), 5.0);
    assert!(
        concave_zones(s.as_ref(), &n, 5.0, &mut ignore)
            .unwrap()
            .zones
            .is_empty()
    );
}

#[test]
fn a_bowl_smaller_than_the_nose_reports_a_zone_at_the_centre() {
    // Sphere R 0.3 mm on a Ø0.4 mm part, nose r 0.5 mm: the nose cannot get into the bowl. Over
    // the centre it rests on the part's edge (the arc reaches 0.38 mm > 0.2 mm), so the depth
    // there is f(R_p) + √(r² − R_p²) − r.
    let (bowl, part, r) = (0.3f64, 0.2f64, 0.5f64);
    let json = format!(r#"{{"type":"asphere","radius_mm":{bowl}}}"#);
    let s = surface(&json, part);
    let n = nose(r, 100.0, s.as_ref(), part);
    let reach = concave_zones(s.as_ref(), &n, part, &mut ignore).unwrap();
    assert_eq!(reach.zones.len(), 1, "{reach:?}");
    let z = &reach.zones[0];
    assert_eq!(z.rho_min_mm, 0.0);
    assert!((z.rho_max_mm - part).abs() < 1e-12, "{z:?}");
    assert_eq!((z.theta_to_deg - z.theta_from_deg + 360.0) % 360.0, 359.0);
    assert!(!z.slope_kink);
    assert!((z.min_curvature_radius_mm - bowl).abs() < 1e-9, "{z:?}");
    assert!(z.at.rho_mm < 1e-4, "deepest at ρ {}", z.at.rho_mm);
    let sag_edge = bowl - (bowl * bowl - part * part).sqrt();
    let closed = sag_edge + (r * r - part * part).sqrt() - r;
    let depth = z.depth_um * 1e-3;
    assert!((depth - closed).abs() <= DEPTH_TOL, "{depth} vs {closed}");
    let closing = Closing::new(s.as_ref(), z.at.theta_deg, r, 100.0, part, z.at.rho_mm);
    let brute = closing.residual(z.at.rho_mm);
    assert!(
        (brute - closed).abs() < ORACLE_TOL,
        "oracle {brute} vs {closed}"
    );
    assert!((brute - depth).abs() <= DEPTH_TOL);
}

#[test]
fn noses_that_fit_report_no_zone() {
    // The same bowl with r 0.2 mm < 0.3 mm, a convex sphere, a plane, and a sharp tool.
    let cases = [
        (r#"{"type":"asphere","radius_mm":0.3}"#, 0.2, 0.2),
        (r#"{"type":"asphere","radius_mm":-0.3}"#, 0.2, 1.0),
        (r#"{"type":"asphere","curvature_per_mm":0}"#, 2.0, 1.0),
        (CONVEX, CONVEX_PART, 0.0),
    ];
    for (json, part, r) in cases {
        let s = surface(json, part);
        let n = nose(r, 100.0, s.as_ref(), part);
        let reach = concave_zones(s.as_ref(), &n, part, &mut ignore).unwrap();
        assert!(reach.zones.is_empty(), "{json} r {r}: {:?}", reach.zones);
        assert_eq!(reach.shallow_zones, 0, "{json} r {r}");
    }
}
