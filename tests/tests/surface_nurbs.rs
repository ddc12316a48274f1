//! NURBS surfaces from a JSON control net through the public API.
//!
//! - Closed forms: an exact sphere cap as a rational net (inverse stereographic projection,
//!   three ways: one biquadratic Bézier patch, biquadratic with interior knots, bicubic on an
//!   unclamped uniform knot vector), polynomial paraboloids (bicubic on uneven knots with a linear
//!   parametrisation, degree 4 with a curved and sheared one), and a plane, all with nets built
//!   by blossoming (`nurbs_nets`), not by the library. Sag within 1e-12 mm, gradient within
//!   1e-13, Hessian within 1e-13 /mm (see [`SAG_TOL`]).
//! - Random freeform nets (proptest, fixed seed): derivatives against central finite
//!   differences, and the (u, v) inversion round trip.
//! - Errors: a face that does not cover the part, points outside it, folded and degenerate
//!   projections, bad JSON; the example job; a whole planned path through the brute-force gouge
//!   check.

mod common;
mod nurbs_nets;

use common::{check_derivatives, check_planned_path, config, example_job, local};
use nurbs_nets::{Poly, add, clamped, mul, polynomial_net, scale, sphere, sphere_cap, uniform};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use spiralcam::job::Job;
use spiralcam::plan::Planner;
use spiralcam::surface::{Nurbs, NurbsSpec, PartDisc, SectionBounds, Surface, SurfaceSpec};

/// Sag tolerance against closed forms, mm. The inversion stops at an XY residual of 1e-14 of
/// the face's size (≈ 6e-14 mm here), which moves the sag by at most |∇z|·6e-14 < 2e-14 mm;
/// evaluating a rational net of degree ≤ 4 rounds at a few 1e-15 of its coordinates (≤ 6 mm).
/// The largest error seen over 20 000 points of each net below is 1.4e-14 mm.
const SAG_TOL: f64 = 1e-12;
/// Slope tolerance: the same residual moves the slope by |H|·6e-14 < 1e-14 and the chain rule's
/// rounding is a few ε·|S_u|/|det J|; the largest error seen is 3.2e-15. A wrong term of the
/// chain rule (say the `z_x·∇²X` part of M) is 1e-3 or more on the curved parametrisation.
const SLOPE_TOL: f64 = 1e-13;
/// Curvature tolerance, 1/mm; the largest error seen is 5e-16.
const CURVATURE_TOL: f64 = 1e-13;

/// Seed of this file's property tests.
const SEED: u64 = 4242;

/// Sunflower points filling the disc of radius `radius` evenly, plus its rim.
fn disc_points(radius: f64, n: usize) -> Vec<(f64, f64)> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut out: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let r = radius * (i as f64 / (n - 1) as f64).sqrt();
            let (s, c) = (golden * i as f64).sin_cos();
            (r * c, r * s)
        })
        .collect();
    out.extend((0..64).map(|k| {
        let (s, c) = (k as f64 * std::f64::consts::TAU / 64.0).sin_cos();
        (radius * c, radius * s)
    }));
    out
}

/// Compares sag, gradient and Hessian with a closed form `[z, zx, zy, zxx, zxy, zyy]`.
fn check_closed_form(s: &dyn Surface, points: &[(f64, f64)], want: impl Fn(f64, f64) -> [f64; 6]) {
    let tols = [
        SAG_TOL,
        SLOPE_TOL,
        SLOPE_TOL,
        CURVATURE_TOL,
        CURVATURE_TOL,
        CURVATURE_TOL,
    ];
    let names = ["z", "zx", "zy", "zxx", "zxy", "zyy"];
    for &(x, y) in points {
        let l = local(s, x, y);
        let got = [l.z, l.zx, l.zy, l.zxx, l.zxy, l.zyy];
        let w = want(x, y);
        for k in 0..6 {
            assert!(
                (got[k] - w[k]).abs() <= tols[k],
                "{} at ({x}, {y}): {} {} vs {} (difference {:e})",
                s.describe(),
                names[k],
                got[k],
                w[k],
                (got[k] - w[k]).abs()
            );
        }
    }
}

fn build(spec: &NurbsSpec, part_radius: f64) -> Nurbs {
    Nurbs::new(spec, PartDisc::centred(part_radius)).unwrap_or_else(|e| panic!("{e}"))
}

/// Sphere radius and parameter half-width of the caps: the square [−a, a]² maps onto a cap
/// reaching 2Ra/(1 + a²) = 5.49 mm along the axes, beyond the 5 mm part.
const R: f64 = 20.0;
const A: f64 = 0.14;

fn sphere_caps() -> Vec<NurbsSpec> {
    vec![
        sphere_cap(R, 2, &clamped(2, -A, A, &[])),
        sphere_cap(R, 2, &clamped(2, -A, A, &[-0.3 * A, 0.05 * A, 0.6 * A])),
        sphere_cap(R, 3, &uniform(3, -A, A, 4)),
    ]
}

#[test]
fn rational_sphere_caps_match_the_sphere() {
    let points = disc_points(5.0, 2000);
    for spec in sphere_caps() {
        let s = build(&spec, 5.0);
        check_closed_form(&s, &points, |x, y| sphere(R, x, y));
    }
}

/// The radius of the paraboloids of [`paraboloids`], mm.
const R2: f64 = 30.0;

/// z = (x² + y²)/(2R₂) two ways: bicubic, linear in (u, v) on uneven knots (x = u, y = 1.2v);
/// degree 4, curved and sheared (x = u + 0.02uv + 0.01u², y = v − 0.02v² + 0.02u).
fn paraboloids() -> Vec<NurbsSpec> {
    let z_of = |x: &Poly, y: &Poly| scale(0.5 / R2, &add(&mul(x, x), &mul(y, y)));
    let (x, y): (Poly, Poly) = (vec![(1.0, 1, 0)], vec![(1.2, 0, 1)]);
    let z = z_of(&x, &y);
    let ku = clamped(3, -6.0, 6.0, &[-2.5, 0.5, 1.0, 4.0]);
    let kv = clamped(3, -5.0, 5.0, &[-1.0, 3.0]);
    let cubic = polynomial_net(3, 3, &ku, &kv, [&x, &y, &z]);
    let x: Poly = vec![(1.0, 1, 0), (0.02, 1, 1), (0.01, 2, 0)];
    let y: Poly = vec![(1.0, 0, 1), (-0.02, 0, 2), (0.02, 1, 0)];
    let z = z_of(&x, &y);
    let k = clamped(4, -8.0, 8.0, &[-3.0, 2.0]);
    let quartic = polynomial_net(4, 4, &k, &k, [&x, &y, &z]);
    vec![cubic, quartic]
}

#[test]
fn polynomial_paraboloids_match_the_closed_form() {
    // The exact Hessian is diag(1/R₂, 1/R₂).
    let paraboloid = |x: f64, y: f64| {
        [
            (x * x + y * y) / (2.0 * R2),
            x / R2,
            y / R2,
            1.0 / R2,
            0.0,
            1.0 / R2,
        ]
    };
    let points = disc_points(5.0, 2000);
    for spec in paraboloids() {
        let s = build(&spec, 5.0);
        check_closed_form(&s, &points, paraboloid);
    }
}

#[test]
fn a_plane_on_a_curved_parametrisation_is_exact() {
    // z = 0.05x − 0.1y + 0.2 with x = u + 0.05u², y = v: biquadratic, unclamped knots.
    let x: Poly = vec![(1.0, 1, 0), (0.05, 2, 0)];
    let y: Poly = vec![(1.0, 0, 1)];
    let z = add(&add(&scale(0.05, &x), &scale(-0.1, &y)), &vec![(0.2, 0, 0)]);
    let k = uniform(2, -5.0, 5.0, 5);
    let spec = polynomial_net(2, 2, &k, &k, [&x, &y, &z]);
    let s = build(&spec, 3.5);
    check_closed_form(&s, &disc_points(3.5, 500), |x, y| {
        [0.05 * x - 0.1 * y + 0.2, 0.05, -0.1, 0.0, 0.0, 0.0]
    });
}

/// The largest slope, and the least and largest Hessian eigenvalues, of `s` at `points`: what
/// its disc bounds must hold (every section's curvature lies between the eigenvalues).
fn sampled_extremes(s: &dyn Surface, points: &[(f64, f64)]) -> (f64, f64, f64) {
    let (mut slope, mut least, mut most) = (0.0f64, f64::INFINITY, f64::NEG_INFINITY);
    for &(x, y) in points {
        let l = local(s, x, y);
        let (mean, spread) = (0.5 * (l.zxx + l.zyy), (0.5 * (l.zxx - l.zyy)).hypot(l.zxy));
        slope = slope.max(l.zx.hypot(l.zy));
        least = least.min(mean - spread);
        most = most.max(mean + spread);
    }
    (slope, least, most)
}

/// `s`'s disc bounds over `radius`, asserted to hold at dense points of the disc and to be
/// its section bounds; with the sampled extremes (slope, least and largest eigenvalue).
fn assert_disc_bounds_hold(s: &dyn Surface, radius: f64) -> (SectionBounds, (f64, f64, f64)) {
    let b = s.disc_bounds(radius).expect("disc bounds");
    assert_eq!(s.section_bounds(radius), Some(b));
    let sampled = sampled_extremes(s, &disc_points(radius, 20_000));
    let (slope, least, most) = sampled;
    assert!(
        slope <= b.max_slope && least >= b.min_curvature && most <= b.max_curvature,
        "{b:?} against sampled {sampled:?}"
    );
    assert!(!b.has_ridges);
    (b, sampled)
}

#[test]
fn disc_bounds_hold_and_are_near_the_extremes_on_the_closed_forms() {
    // The sphere caps (rational; slope 0.258 and eigenvalues 0.050 … 0.055 /mm over r 5) and the
    // paraboloids (polynomial; slope 0.167, both eigenvalues 1/30 /mm): the bounds from the
    // nets' Bézier pieces hold at 20 000 points of the disc and its rim, and stay within 10 % of
    // the slope and of the eigenvalues (pieces are halved until their gradient varies by at most
    // 0.01 + 2 % and their Hessian by 0.01 /mm + 5 %; on whole knot cells the bounds were 2–3
    // times the extremes).
    let nets = sphere_caps().into_iter().chain(paraboloids());
    for spec in nets {
        let (b, (slope, least, most)) = assert_disc_bounds_hold(&build(&spec, 5.0), 5.0);
        assert!(b.max_slope <= 1.1 * slope, "{b:?} {slope}");
        assert!(b.max_curvature <= 1.1 * most, "{b:?} {most}");
        assert!(b.min_curvature >= 0.9 * least, "{b:?} {least}");
    }
}

// ---------------------------------------------------------------------------------------------
// Random freeform nets

/// A bicubic net over about [−6, 6]² on uneven clamped knots: control points on the Greville
/// abscissae moved by up to ±0.15 mm in x and y, z a paraboloid plus up to ±50 µm of freeform
/// departure, weights in [0.7, 1.4] or none.
fn freeform() -> impl Strategy<Value = NurbsSpec> {
    (
        prop::collection::vec(-1.0..1.0f64, 3 * 49),
        prop::collection::vec(0.7..1.4f64, 49),
        any::<bool>(),
        (-0.8..0.8f64, -0.8..0.8f64),
    )
        .prop_map(|(moves, weights, rational, (ku, kv))| {
            let knots_u = clamped(3, -6.0, 6.0, &[-3.0 + ku, ku, 3.0 + ku]);
            let knots_v = clamped(3, -6.0, 6.0, &[-3.0 + kv, kv, 3.0 + kv]);
            let greville = |k: &[f64], i: usize| (k[i + 1] + k[i + 2] + k[i + 3]) / 3.0;
            let control_points = (0..7)
                .map(|i| {
                    (0..7)
                        .map(|j| {
                            let m = &moves[3 * (7 * i + j)..];
                            let (x, y) = (greville(&knots_u, i), greville(&knots_v, j));
                            let z = (x * x + y * y) / 80.0 + 0.05 * m[2];
                            [x + 0.15 * m[0], y + 0.15 * m[1], z]
                        })
                        .collect()
                })
                .collect();
            let weights = rational.then(|| weights.chunks(7).map(|r| r.to_vec()).collect());
            NurbsSpec {
                degree_u: 3,
                degree_v: 3,
                knots_u,
                knots_v,
                control_points,
                weights,
                allow_uncovered: false,
            }
        })
}

proptest! {
    #![proptest_config(config(48, SEED))]

    #[test]
    fn freeform_derivatives_match_finite_differences(
        spec in freeform(),
        points in prop::collection::vec((0.0..1.0f64, 0.0..std::f64::consts::TAU), 4),
    ) {
        // Coverage is tested below; skipping its 17 000 probes keeps this test fast.
        let s = build(&NurbsSpec { allow_uncovered: true, ..spec }, 5.0);
        for (t, phi) in points {
            let r = 5.0 * t.sqrt();
            check_derivatives(&s, r * phi.cos(), r * phi.sin())?;
        }
    }

    #[test]
    fn parameters_round_trip(
        spec in freeform(),
        uvs in prop::collection::vec((0.0..=1.0f64, 0.0..=1.0f64), 8),
    ) {
        // Parameter error = J⁻¹·(XY residual ≤ 6e-14 mm), |J⁻¹| ≲ 2 here; the sag at the
        // point must be S_z itself up to the same residual times the slope (< 0.3).
        let s = build(&NurbsSpec { allow_uncovered: true, ..spec }, 5.0);
        let [u0, u1, v0, v1] = s.domain();
        for (a, b) in uvs {
            let (u, v) = (u0 + a * (u1 - u0), v0 + b * (v1 - v0));
            let [x, y, z] = s.point(u, v);
            let (pu, pv) = s.parameters(x, y).map_err(|e| TestCaseError::fail(e.to_string()))?;
            prop_assert!((pu - u).abs() <= 1e-12 && (pv - v).abs() <= 1e-12,
                "({u}, {v}) → ({x}, {y}) → ({pu}, {pv})");
            let sag = local(&s, x, y).z;
            prop_assert!((sag - z).abs() <= 1e-13, "sag {sag} vs S_z {z}");
        }
    }
}

proptest! {
    // The bounds take about 0.4 s a net in a debug build: fewer cases than above.
    #![proptest_config(config(8, SEED))]

    #[test]
    fn freeform_disc_bounds_hold(spec in freeform()) {
        // Random bicubic nets (half of them rational) over the 5 mm disc: given, and holding at
        // 2 000 points of it.
        let s = build(&NurbsSpec { allow_uncovered: true, ..spec }, 5.0);
        let b = s.disc_bounds(5.0);
        prop_assert!(b.is_some());
        let b = b.unwrap();
        let (slope, least, most) = sampled_extremes(&s, &disc_points(5.0, 2000));
        prop_assert!(
            slope <= b.max_slope && least >= b.min_curvature && most <= b.max_curvature,
            "{:?} against {} {} {}", b, slope, least, most
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Errors

fn json_spec(spec: &NurbsSpec) -> String {
    serde_json::to_string(&SurfaceSpec::Nurbs(spec.clone())).unwrap()
}

#[test]
fn a_face_smaller_than_the_part_is_refused_naming_the_first_uncovered_point() {
    // The bilinear square [−2, 2]² for a part of radius 2.5: the first probe outside lies on
    // the +x spoke of ring 52 of 64, radius 2.5·52/64 = 2.03125 mm.
    let spec = square(2.0);
    let json = json_spec(&spec);
    let surface: SurfaceSpec = serde_json::from_str(&json).unwrap();
    let e = surface.build(2.5).unwrap_err();
    assert_eq!(e.field, "surface.control_points");
    assert!(e.value.contains("x in [-2.0000, 2.0000] mm"), "{e}");
    assert!(
        e.allowed
            .contains("first uncovered at radius 2.0312 mm, angle 0.00°"),
        "{e}"
    );
    assert!(e.allowed.contains("does not cover this point"), "{e}");
    assert!(surface.build(1.99).is_ok());
}

#[test]
fn with_allow_uncovered_points_off_the_face_are_undefined() {
    let mut spec = square(2.0);
    spec.allow_uncovered = true;
    let s = build(&spec, 3.0);
    let e = s.local(0.0, -2.5).unwrap_err();
    assert_eq!(e.surface, "NURBS surface");
    assert_eq!(e.radius_mm, 2.5);
    assert!(e.to_string().contains("radius 2.5 mm"), "{e}");
    assert!(
        e.to_string().contains("the face does not cover this point"),
        "{e}"
    );
    assert!((local(&s, 1.9, -1.9).z - 0.1 * 1.9).abs() < 1e-15);
}

/// The bilinear plane z = 0.1x over [−h, h]².
fn square(h: f64) -> NurbsSpec {
    NurbsSpec {
        degree_u: 1,
        degree_v: 1,
        knots_u: vec![0.0, 0.0, 1.0, 1.0],
        knots_v: vec![0.0, 0.0, 1.0, 1.0],
        control_points: vec![
            vec![[-h, -h, -0.1 * h], [-h, h, -0.1 * h]],
            vec![[h, -h, 0.1 * h], [h, h, 0.1 * h]],
        ],
        weights: None,
        allow_uncovered: false,
    }
}

#[test]
fn a_folded_face_is_refused() {
    // x along u has control values −3, 4, −4, 3 (cubic, one span): x_u = 3(30u² − 30u + 7)
    // changes sign twice, the face folds over itself.
    let row = |x: f64| vec![[x, -3.0, 0.0], [x, 3.0, 0.0]];
    let spec = NurbsSpec {
        degree_u: 3,
        degree_v: 1,
        knots_u: clamped(3, 0.0, 1.0, &[]),
        knots_v: clamped(1, 0.0, 1.0, &[]),
        control_points: vec![row(-3.0), row(4.0), row(-4.0), row(3.0)],
        weights: None,
        allow_uncovered: false,
    };
    let e = Nurbs::new(&spec, PartDisc::centred(1.0)).unwrap_err();
    assert_eq!(e.field, "control_points");
    assert!(e.allowed.contains("folds or degenerates"), "{e}");
    assert!(e.allowed.contains("not be single valued"), "{e}");
}

#[test]
fn a_face_with_a_pole_is_refused_as_degenerate() {
    // A bilinear "triangle": the row at u = 0 collapses to one point, det J = 0 along it.
    let spec = NurbsSpec {
        degree_u: 1,
        degree_v: 1,
        knots_u: clamped(1, 0.0, 1.0, &[]),
        knots_v: clamped(1, 0.0, 1.0, &[]),
        control_points: vec![
            vec![[-3.0, 0.0, 0.0], [-3.0, 0.0, 0.0]],
            vec![[3.0, -3.0, 0.0], [3.0, 3.0, 0.0]],
        ],
        weights: None,
        allow_uncovered: true,
    };
    let e = Nurbs::new(&spec, PartDisc::centred(1.0)).unwrap_err();
    assert!(e.allowed.contains("(u, v) = (0, "), "{e}");
}

#[test]
fn bad_json_names_the_field() {
    let good = json_spec(&square(2.0));
    let read: SurfaceSpec = serde_json::from_str(&good).unwrap();
    assert_eq!(read, SurfaceSpec::Nurbs(square(2.0)));
    // Weights and allow_uncovered are optional and left out when they have their defaults.
    assert!(
        !good.contains("weights") && !good.contains("allow_uncovered"),
        "{good}"
    );
    let unknown = good.replacen("\"degree_u\"", "\"colour\":1,\"degree_u\"", 1);
    let e = serde_json::from_str::<SurfaceSpec>(&unknown).unwrap_err();
    assert!(e.to_string().contains("colour"), "{e}");
    let negative = good.replacen("\"degree_u\":1", "\"degree_u\":-1", 1);
    assert!(serde_json::from_str::<SurfaceSpec>(&negative).is_err());
    let short_point = good.replacen("[-2.0,-2.0,-0.2]", "[-2.0,-2.0]", 1);
    assert_ne!(short_point, good);
    assert!(serde_json::from_str::<SurfaceSpec>(&short_point).is_err());
    let mut spec = square(2.0);
    spec.knots_u = vec![0.0, 0.5, 0.2, 1.0];
    let e = SurfaceSpec::Nurbs(spec).build(1.0).unwrap_err();
    assert_eq!(e.field, "surface.knots_u[2]");
}

// ---------------------------------------------------------------------------------------------
// Jobs

#[test]
fn the_example_job_builds_and_is_smooth() {
    let job = example_job("nurbs-freeform.json");
    let planner = Planner::new(&job).unwrap_or_else(|e| panic!("{e}"));
    let s = planner.surface();
    assert!(
        s.describe().starts_with("NURBS surface degree 3 × 3"),
        "{}",
        s.describe()
    );
    for (x, y) in disc_points(job.part_radius_mm(), 40) {
        check_derivatives(s, x, y).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn a_planned_freeform_path_touches_without_cutting() {
    // A 1.2 mm part cut from a random freeform net shrunk to a quarter in x and y (50 µm of
    // departure over 0.75 mm spans), 0.1 mm nose: 145 points.
    let mut runner = proptest::test_runner::TestRunner::new(config(1, SEED));
    let spec = freeform().new_tree(&mut runner).unwrap().current();
    let surface = json_spec(&shrink(&spec, 1.0 / 4.0));
    let job = format!(
        r#"{{"name":"nurbs-path","part":{{"diameter_mm":1.2}},"surface":{surface},
            "tool":{{"nose_radius_mm":0.1}},"machine":{{"spindle_rpm":500}},
            "strategy":{{"feed_mm_per_rev":0.1,"sampling":{{"type":"constant_angle","points_per_rev":24}}}}}}"#
    );
    // The net bounds the sections (`Surface::section_bounds`): the contacts come from the
    // concave shortcut, held to the same check.
    let planner = Planner::new(&Job::from_json(&job).unwrap()).unwrap();
    assert!(planner.path().concavity().is_some());
    // 2000 steps of the nose angle keep the sampling bound K·Δa²/8 near 1e-8 mm.
    let n = check_planned_path(&job, &|_, _| Vec::new(), 2000);
    assert_eq!(n, 145);
}

/// The net scaled by `f` in x and y (z unchanged): a smaller part with steeper features.
fn shrink(spec: &NurbsSpec, f: f64) -> NurbsSpec {
    let mut out = spec.clone();
    for row in &mut out.control_points {
        for p in row {
            p[0] *= f;
            p[1] *= f;
        }
    }
    out
}
