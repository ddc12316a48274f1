//! Composite surfaces (`crate/src/surface/composite.rs`): a base plus decentred, rotated terms.
//! The sag is checked against the closed forms of the parts evaluated at points moved and
//! rotated by hand, the gradient and Hessian against central finite differences, and a whole
//! planned path over a decentred, rotated lens array by the dense gouge check.

mod common;

use common::{check_derivatives, check_planned_path, config};
use proptest::prelude::*;
use spiralcam::job::Job;
use spiralcam::plan::Planner;
use spiralcam::surface::{Line, Surface, SurfaceSpec};
use std::f64::consts::TAU;

const SEED: u64 = 3141;

/// A composite of an even asphere (radius `r`, conic `k`) and two sinusoid terms, each placed
/// at (dx, dy) and turned by φ degrees.
#[derive(Debug, Clone)]
struct Case {
    r: f64,
    k: f64,
    /// (A, λx, λy, φx°, φy°, dx, dy, rotation°) per term.
    terms: Vec<[f64; 8]>,
}

impl Case {
    fn json(&self) -> String {
        let terms: Vec<String> = self
            .terms
            .iter()
            .map(|t| {
                format!(
                    r#"{{"surface":{{"type":"sinusoid","amplitude_mm":{},"wavelength_x_mm":{},
                    "wavelength_y_mm":{},"phase_x_deg":{},"phase_y_deg":{}}},
                    "decenter_x_mm":{},"decenter_y_mm":{},"rotation_deg":{}}}"#,
                    t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7]
                )
            })
            .collect();
        format!(
            r#"{{"type":"composite","base":{{"type":"asphere","radius_mm":{},"conic":{}}},
            "terms":[{}]}}"#,
            self.r,
            self.k,
            terms.join(",")
        )
    }

    fn build(&self) -> Box<dyn Surface> {
        let spec: SurfaceSpec = serde_json::from_str(&self.json()).expect("surface JSON");
        spec.build(5.0).unwrap_or_else(|e| panic!("{self:?}: {e}"))
    }

    /// The sag written out: the conic `c·ρ²/(1 + √(1 − (1 + k)c²ρ²))` plus each sinusoid
    /// `A·sin(2πu/λx + φx)·sin(2πv/λy + φy)` at (u, v) = R(−φ)·((x, y) − d).
    fn sag(&self, x: f64, y: f64) -> f64 {
        let c = 1.0 / self.r;
        let rho2 = x * x + y * y;
        let mut z = c * rho2 / (1.0 + (1.0 - (1.0 + self.k) * c * c * rho2).sqrt());
        for &[a, lx, ly, px, py, dx, dy, rot] in &self.terms {
            let (s, co) = rot.to_radians().sin_cos();
            let (ex, ey) = (x - dx, y - dy);
            let (u, v) = (co * ex + s * ey, -s * ex + co * ey);
            z +=
                a * (TAU * u / lx + px.to_radians()).sin() * (TAU * v / ly + py.to_radians()).sin();
        }
        z
    }
}

fn case() -> impl Strategy<Value = Case> {
    let term = (
        1e-4..2e-3f64,
        0.8..4.0f64,
        0.8..4.0f64,
        -180.0..180.0f64,
        -180.0..180.0f64,
        -2.0..2.0f64,
        -2.0..2.0f64,
        -180.0..180.0f64,
    )
        .prop_map(|(a, lx, ly, px, py, dx, dy, rot)| [a, lx, ly, px, py, dx, dy, rot]);
    (
        prop_oneof![20.0..200.0f64, -200.0..-20.0f64],
        -3.0..1.0f64,
        prop::collection::vec(term, 1..3),
    )
        .prop_map(|(r, k, terms)| Case { r, k, terms })
}

/// A point in the Ø10 mm part.
fn point() -> impl Strategy<Value = (f64, f64)> {
    (0.0..1.0f64, 0.0..TAU).prop_map(|(t, phi)| {
        let rho = 5.0 * t.sqrt();
        (rho * phi.cos(), rho * phi.sin())
    })
}

proptest! {
    #![proptest_config(config(256, SEED))]

    #[test]
    fn sag_is_the_base_plus_the_moved_terms(case in case(), (x, y) in point()) {
        // The parts are a few mm at most; their closed forms and the composite's own sum round
        // differently by a few ulps of the sag (≤ 1e-14 mm); 1e-12 mm leaves a margin.
        let s = case.build();
        let (z, expect) = (s.sag(x, y).unwrap(), case.sag(x, y));
        prop_assert!((z - expect).abs() < 1e-12, "sag {z} vs {expect} at ({x}, {y})");
        prop_assert_eq!(s.local(x, y).unwrap().z, z);
    }

    #[test]
    fn derivatives_match_finite_differences(case in case(), (x, y) in point()) {
        check_derivatives(case.build().as_ref(), x, y)?;
    }
}

/// A lens array decentred by (0.3, −0.2) mm and turned by 20° on a sphere, with a sinusoid.
const LENSLETS: &str = r#"{"type":"composite",
    "base":{"type":"asphere","radius_mm":30},
    "terms":[
      {"surface":{"type":"lens_array","lens_radius_mm":2.0,"aperture_mm":0.8,"pitch_mm":1.0,
                  "grid":"hexagonal","form":"convex"},
       "decenter_x_mm":0.3,"decenter_y_mm":-0.2,"rotation_deg":20},
      {"surface":{"type":"sinusoid","amplitude_mm":0.0005,"wavelength_x_mm":1.5,
                  "wavelength_y_mm":1.5}, "rotation_deg":-35}]}"#;

/// A small job on `surface` (Ø3 mm, r 0.1 mm, 30 revolutions of 72 points).
fn path_job(name: &str, surface: &str) -> String {
    format!(
        r#"{{"name":"{name}","part":{{"diameter_mm":3}},"surface":{surface},
        "tool":{{"nose_radius_mm":0.1,"included_angle_deg":100}},"machine":{{"spindle_rpm":500}},
        "strategy":{{"feed_mm_per_rev":0.05,"sampling":{{"type":"constant_angle","points_per_rev":72}}}}}}"#
    )
}

/// The surface of a spec, on the Ø3 mm part.
fn build(spec: &str) -> Box<dyn Surface> {
    serde_json::from_str::<SurfaceSpec>(spec)
        .unwrap()
        .build(1.5)
        .unwrap()
}

/// The slope kinks of `surface` along the radial section at (cos θ, sin θ), over the part.
fn radial_kinks(surface: &dyn Surface) -> impl Fn(f64, f64) -> Vec<f64> + '_ {
    move |c, s| {
        let mut out = Vec::new();
        surface.slope_kinks(Line::radial(c, s), -1.5, 1.5, &mut out);
        out
    }
}

#[test]
fn every_point_of_a_planned_path_over_placed_lenslets_touches_without_cutting() {
    let job = path_job("composite-path", LENSLETS);
    let surface = build(LENSLETS);
    // The rims of the placed lenslets along each radial section, where the slope jumps.
    let kinks = radial_kinks(surface.as_ref());
    // 2000 steps of the 100° arc keep the sampling bound K·Δa²/8 below 1e-8 mm (K ≈ 0.2 mm for
    // r = 0.1 mm, slopes ≤ 0.3, curvatures ≤ 0.5 /mm); check_planned_path asserts it.
    let n = check_planned_path(&job, &kinks, 2000);
    assert_eq!(n, 30 * 72 + 1);
}

/// Concave lenslets turned by 20° and a turned sinusoid on an asphere: every part bounds its
/// sections, so the sum does and the path comes from the concave shortcut, the rims (ridges)
/// probed; then the lenslets decentred, and convex.
#[test]
fn a_composite_of_bounded_parts_is_planned_by_the_shortcut_and_touches() {
    let surface = r#"{"type":"composite",
    "base":{"type":"asphere","radius_mm":30},
    "terms":[
      {"surface":{"type":"lens_array","lens_radius_mm":2.0,"aperture_mm":0.8,"pitch_mm":1.0,
                  "grid":"hexagonal","form":"concave"}, "rotation_deg":20},
      {"surface":{"type":"sinusoid","amplitude_mm":0.0005,"wavelength_x_mm":1.5,
                  "wavelength_y_mm":1.5}, "rotation_deg":-35}]}"#;
    let job = path_job("composite-bounded", surface);
    let planner = Planner::new(&Job::from_json(&job).unwrap()).unwrap();
    assert!(planner.path().concavity().is_some());
    let built = build(surface);
    assert_eq!(
        check_planned_path(&job, &radial_kinks(built.as_ref()), 2000),
        30 * 72 + 1
    );
    // Decentred, the lenslets' sections through the axis are bounded by their bounds on any
    // line (`Surface::disc_bounds`), the same for spheres wherever the line runs; convex, their
    // rims are valleys and the stretches between them are searched apart. Both still touch.
    let decentred = surface.replace(r#""rotation_deg":20"#, r#""decenter_x_mm":0.3"#);
    let placed = build(&decentred);
    assert_eq!(placed.section_bounds(1.5), built.section_bounds(1.5));
    let convex = decentred.replace("concave", "convex");
    for (name, surface, valleys) in [("decentred", &decentred, false), ("convex", &convex, true)] {
        let job = path_job(name, surface);
        let planner = Planner::new(&Job::from_json(&job).unwrap()).unwrap();
        assert_eq!(planner.path().concavity().map(|c| c.valleys), Some(valleys));
        let built = build(surface);
        assert_eq!(
            check_planned_path(&job, &radial_kinks(built.as_ref()), 2000),
            30 * 72 + 1
        );
    }
}

/// The slope kinks of a placed lens array are those of the unplaced one along the moved line.
#[test]
fn the_kinks_of_a_placed_term_are_the_rims_along_the_moved_line() {
    let spec: SurfaceSpec = serde_json::from_str(LENSLETS).unwrap();
    let surface = spec.build(1.5).unwrap();
    let theta = 0.7f64;
    let mut found = Vec::new();
    surface.slope_kinks(
        Line::radial(theta.cos(), theta.sin()),
        -1.5,
        1.5,
        &mut found,
    );
    assert!(!found.is_empty());
    // Each reported t is on a lenslet rim: in the array's frame, at distance 0.4 mm (half the
    // aperture) from the nearest lenslet centre of the hexagonal grid of pitch 1 mm.
    let (s20, c20) = 20f64.to_radians().sin_cos();
    for t in found {
        let (x, y) = (t * theta.cos() - 0.3, t * theta.sin() + 0.2);
        let (u, v) = (c20 * x + s20 * y, -s20 * x + c20 * y);
        let nearest = hex_centres(1.0, 4)
            .into_iter()
            .map(|(cx, cy)| (u - cx).hypot(v - cy))
            .fold(f64::INFINITY, f64::min);
        assert!(
            (nearest - 0.4).abs() < 1e-9,
            "t {t}: {nearest} from a centre"
        );
    }
}

/// Centres of a hexagonal grid of pitch p: rows y = j·p·√3/2, every other row shifted by p/2.
fn hex_centres(p: f64, k: i32) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for j in -k..=k {
        for i in -k..=k {
            let shift = if j.rem_euclid(2) == 1 { 0.5 * p } else { 0.0 };
            out.push((i as f64 * p + shift, j as f64 * p * 3f64.sqrt() / 2.0));
        }
    }
    out
}
