//! Cutting linearization error (`spiralcam::analysis::linearization`, paper 000): the error
//! `e(s) = Z_lin(s) − z*(s)` between the linear move of the machine and the compensated tool
//! height along each segment.
//!
//! - Brute force: for random aspheres, XY polynomials and sinusoidal grids, sharp and round
//!   tools (up to half the smallest concave radius of curvature, so that z* is smooth), coarse
//!   constant-angle paths (12–40 points per revolution, so that the errors are µm-sized), each
//!   segment's largest overcut and undercut equal those of e sampled at 10 001 points, refined
//!   around the (at most 8 highest) sampled local extremes within reach of the largest
//!   (`M·h²/8`, M twice the largest second difference over h²) by zooms of 200 samples over
//!   ±1 step until the spacing is below 1e-12 (no derivatives used). e is computed in the test
//!   from its definition (linear Z minus the compensated tip). Tolerance 1e-12 mm: both sides
//!   evaluate the same computed e, whose rounding (that of the compensated height, ≤ 1e-13 mm)
//!   is the floor; the zoomed oracle's own sampling error is below
//!   `|e′|·1e-12/2 + |e″|·1e-24/8`, ≤ 1e-13 mm for the |e′| < 0.2 mm seen (kinks included).
//!   The differences seen are below 1e-13 mm. Each reported extreme is also a value of e: the
//!   test's e at the reported s equals it within 1e-14 mm. The same check runs on a wavy
//!   sinusoid (several extremes of each sign per segment) and on a lens array, whose rims (and,
//!   with a round nose, the contact's jumps between lenslets) are kinks of e.
//! - Closed forms, to 1e-12 mm (rounding of sags of a few mm; the differences seen are below 1e-15
//!   mm): on a paraboloid with a sharp tool every segment's error is the parabola `Δρ²/(2R)·s(1 −
//!   s)` (z* depends on ρ alone, linear in s); on a concave sphere with a round tool the nose
//!   centre follows the sphere of radius R − r and the extreme lies where its slope equals the
//!   chord's; on a tilted flat `z = t·x` with a sharp tool, a segment at constant radius ρ centred
//!   on azimuth φ has `e(s) = t·ρ·[cos φ·(cos(Δθ/2) − cos(uΔθ)) − sin φ·(2u·sin(Δθ/2) −
//!   sin(uΔθ))]`, u = s − ½: at φ = 0 an overcut `t·ρ·(1 − cos(Δθ/2))` at mid-segment, at φ = π the
//!   same undercut, at φ = π/2 both, at `u = ±acos(2 sin(Δθ/2)/Δθ)/Δθ`.
//! - Derivatives: de/ds and d²e/ds² from the envelope theorem against central differences of e
//!   and of de/ds; the envelope theorem itself (∂z*/∂ρ_s = f_u and ∂z*/∂θ = ρ_c·f_v at the
//!   contact) against central differences of the compensated height.
//! - Rims: on paper 004's concave lens array, where the contact rides a rim (F′ ≠ 0 at the
//!   maximum), de/ds against Richardson-extrapolated central differences of e (the envelope
//!   theorem's slope is checked to be wrong there), and the extremes of segments over the rims
//!   against the dense brute force.
//! - Order: doubling the points per revolution divides the largest error by 4 (second order).
//! - The path check: `analyse` agrees with `segment_error` over every segment, its PV is the sum,
//!   the map holds the extremes, the JSON has no map; bad input gives errors, not panics or NaN.
//! - The accuracy analysis, which computes the segments on the workers (`for_each_pair`, the
//!   path in batches of 16 384 points), equals the check fed point by point, to the bit.

mod common;

use common::{
    RandomSurface, config, path_points, planner_of, random_asphere, random_sinusoid,
    random_xy_polynomial,
};
use proptest::prelude::*;
use spiralcam::analysis::Analysis;
use spiralcam::analysis::linearization::{
    LinearizationCheck, LinearizationReport, SegmentError, analyse, error_at, segment_error,
};
use spiralcam::path::PathPoint;
use spiralcam::plan::Planner;
use std::f64::consts::PI;
use std::ops::ControlFlow;

/// Seed of this file's property tests.
const SEED: u64 = 5005;
/// Dense samples along a segment.
const DENSE: usize = 10_000;
/// Agreement of an extreme with the brute force, mm (see the module docs).
const TOL: f64 = 1e-12;

/// A planner for `surface` (JSON) on a part of radius `part_radius`, nose radius `r`, constant
/// angle sampling.
fn planner(surface: &str, part_radius: f64, r: f64, feed: f64, points_per_rev: u32) -> Planner {
    let json = format!(
        r#"{{"name":"lin","part":{{"diameter_mm":{}}},"surface":{surface},
        "tool":{{"nose_radius_mm":{r},"included_angle_deg":100}},"machine":{{"spindle_rpm":1000}},
        "strategy":{{"feed_mm_per_rev":{feed},"sampling":{{"type":"constant_angle","points_per_rev":{points_per_rev}}}}}}}"#,
        2.0 * part_radius
    );
    planner_of(&json)
}

/// e(s) from its definition, independently of the library.
fn error_direct(p: &Planner, a: &PathPoint, b: &PathPoint, s: f64) -> f64 {
    let rho = a.rho + s * (b.rho - a.rho);
    let theta = a.theta + s * (b.theta - a.theta);
    let (sn, c) = theta.sin_cos();
    let z = p
        .nose()
        .compensate(p.surface(), rho, c, sn)
        .unwrap_or_else(|e| panic!("{e}"))
        .z_tip;
    a.z + s * (b.z - a.z) - z
}

/// The largest σ·e over [0, 1] by brute force (see the module docs): (σ·e, s).
fn brute_force(e: &dyn Fn(f64) -> f64, dense: &[f64], sigma: f64) -> (f64, f64) {
    let n = dense.len() - 1;
    let h = 1.0 / n as f64;
    let v: Vec<f64> = dense.iter().map(|x| sigma * x).collect();
    let top = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    // With |e″| ≤ M, the maximum between samples exceeds the nearest sample by ≤ M·h²/8; M is
    // taken as twice the largest second difference over h².
    let m = (1..n)
        .map(|i| (v[i + 1] - 2.0 * v[i] + v[i - 1]).abs())
        .fold(0.0, f64::max);
    let reach = m / 4.0 + 1e-12;
    // Local maxima of the samples (not inside a plateau) within reach of the top, the 8
    // highest: at a cusp M is large and reach loose, and on flat land every sample ties.
    let mut candidates: Vec<usize> = (0..=n)
        .filter(|&i| {
            let left = if i > 0 { v[i - 1] } else { f64::NEG_INFINITY };
            let right = if i < n { v[i + 1] } else { f64::NEG_INFINITY };
            v[i] >= top - reach && v[i] >= left && v[i] >= right && (v[i] > left || v[i] > right)
        })
        .collect();
    candidates.sort_by(|&i, &j| v[j].total_cmp(&v[i]));
    candidates.truncate(8);
    let first_top = v.iter().position(|&x| x == top).unwrap_or(0);
    let mut best = (top, first_top as f64 * h);
    for i in candidates {
        let (mut lo, mut hi) = ((i as f64 - 1.0) * h, (i as f64 + 1.0) * h);
        let mut at = (v[i], i as f64 * h);
        loop {
            lo = lo.max(0.0);
            hi = hi.min(1.0);
            let step = (hi - lo) / 200.0;
            for k in 0..=200 {
                let s = lo + step * k as f64;
                let x = sigma * e(s);
                if x > at.0 {
                    at = (x, s);
                }
            }
            if step < 1e-12 {
                break;
            }
            (lo, hi) = (at.1 - step, at.1 + step);
        }
        if at.0 > best.0 {
            best = at;
        }
    }
    best
}

/// Checks the library's extremes of the segment a → b against the brute force.
fn check_segment(p: &Planner, a: &PathPoint, b: &PathPoint) -> Result<SegmentError, TestCaseError> {
    let lib = segment_error(p, a, b).map_err(|e| TestCaseError::fail(e.to_string()))?;
    let e = |s: f64| error_direct(p, a, b, s);
    let dense: Vec<f64> = (0..=DENSE).map(|i| e(i as f64 / DENSE as f64)).collect();
    let (max, s_max) = brute_force(&e, &dense, 1.0);
    let (min, s_min) = brute_force(&e, &dense, -1.0);
    let min = -min;
    let what = format!(
        "{} r {}: segment {} (ρ {}, θ {})",
        p.surface().describe(),
        p.nose().nose_radius(),
        a.index,
        a.rho,
        a.theta
    );
    prop_assert!(
        (lib.undercut.error_mm - max).abs() <= TOL,
        "{what}: undercut {:e} at s {} vs brute force {max:e} at s {s_max}",
        lib.undercut.error_mm,
        lib.undercut.s
    );
    prop_assert!(
        (lib.overcut.error_mm - min).abs() <= TOL,
        "{what}: overcut {:e} at s {} vs brute force {min:e} at s {s_min}",
        lib.overcut.error_mm,
        lib.overcut.s
    );
    prop_assert!(lib.undercut.error_mm >= 0.0 && lib.overcut.error_mm <= 0.0);
    for x in [lib.overcut, lib.undercut] {
        prop_assert!((0.0..=1.0).contains(&x.s), "{what}: s {}", x.s);
        prop_assert!(
            (e(x.s) - x.error_mm).abs() <= 1e-14,
            "{what}: e({}) = {:e}, reported {:e}",
            x.s,
            e(x.s),
            x.error_mm
        );
        prop_assert_eq!(x.rho, a.rho + x.s * (b.rho - a.rho));
        prop_assert_eq!(x.theta, a.theta + x.s * (b.theta - a.theta));
    }
    Ok(lib)
}

/// A surface drawn at random: JSON, part radius and the largest nose radius for which the
/// compensated height stays smooth (r below half the smallest concave radius of curvature).
#[derive(Debug, Clone)]
struct Case {
    json: String,
    part_radius: f64,
    max_r: f64,
}

/// A common random surface with nose radii up to half its smallest radius of curvature (0.5 mm
/// at most).
fn case(s: RandomSurface) -> Case {
    Case {
        json: s.json,
        part_radius: s.part_radius,
        max_r: 0.5_f64.min(0.5 / s.curvature),
    }
}

fn any_case() -> impl Strategy<Value = Case> {
    prop_oneof![
        random_asphere(0.8),
        random_xy_polynomial(),
        random_sinusoid(0.5..3.0, 1.0..4.0)
    ]
    .prop_map(case)
}

/// A planner for a case: nose radius `r_frac·max_r` (0 when `r_frac` is 0), `points_per_rev`
/// points per revolution, `revs` revolutions.
fn case_planner(case: &Case, r_frac: f64, points_per_rev: u32, revs: f64) -> Planner {
    planner(
        &case.json,
        case.part_radius,
        r_frac * case.max_r,
        case.part_radius / revs,
        points_per_rev,
    )
}

/// Sharp tool, or a round one of 2 % … 100 % of the case's largest smooth radius.
fn r_frac() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), 0.02..1.0f64]
}

proptest! {
    #![proptest_config(config(24, SEED))]

    #[test]
    fn extremes_match_the_dense_brute_force(
        case in any_case(),
        r_frac in r_frac(),
        points_per_rev in 12u32..=40,
        revs in 2.0..4.0f64,
        at in 0.0..1.0f64,
    ) {
        let p = case_planner(&case, r_frac, points_per_rev, revs);
        let pts = path_points(&p);
        let k = ((at * (pts.len() - 1) as f64) as usize).min(pts.len() - 2);
        check_segment(&p, &pts[k], &pts[k + 1])?;
    }

    #[test]
    fn the_slope_and_curvature_are_the_derivatives_of_the_error(
        case in any_case(),
        r_frac in r_frac(),
        points_per_rev in 12u32..=40,
        at in 0.0..1.0f64,
        s in 0.05..0.95f64,
    ) {
        let p = case_planner(&case, r_frac, points_per_rev, 3.0);
        let pts = path_points(&p);
        let k = ((at * (pts.len() - 1) as f64) as usize).min(pts.len() - 2);
        let (a, b) = (&pts[k], &pts[k + 1]);
        let at_s = |s: f64| error_at(&p, a, b, s).unwrap_or_else(|e| panic!("{e}"));
        let x = at_s(s);
        // The library starts the contact search between the ends' contacts, the definition
        // from a = 0: where the surface proves the nose height concave (asphere, XY polynomial,
        // sinusoid) both find the one maximum, equal to the rounding of the heights (a few ulps
        // of |z| + r).
        let direct = error_direct(&p, a, b, s);
        let ulps = 16.0 * f64::EPSILON * (a.z.abs().max(b.z.abs()) + p.nose().nose_radius());
        prop_assert!(
            (x.error_mm - direct).abs() <= ulps,
            "{}: e {:e} vs {direct:e}", p.surface().describe(), x.error_mm
        );
        // Central differences with h = 1e-4 in s: truncation h²/6·|e‴| (of de/ds) and
        // h²/6·|e⁗| (of d²e/ds², from the analytic de/ds), 1.7e-9 times derivatives that stay
        // below 0.1 mm for these µm-sized errors; rounding of e (~1e-16 of sags of a few mm)
        // over h, 1e-12 mm. The differences seen are below 5e-8 of the value; a wrong or
        // missing term (the contact's slide along the nose, the part-edge case) is O(1).
        let h = 1e-4;
        let (xp, xm) = (at_s(s + h), at_s(s - h));
        let fd = (xp.error_mm - xm.error_mm) / (2.0 * h);
        prop_assert!(
            (fd - x.slope_mm).abs() <= 1e-10 + 1e-5 * x.slope_mm.abs(),
            "{}: de/ds {:e} vs finite difference {fd:e}", p.surface().describe(), x.slope_mm
        );
        let fd2 = (xp.slope_mm - xm.slope_mm) / (2.0 * h);
        prop_assert!(
            (fd2 - x.curvature_mm).abs() <= 1e-10 + 1e-5 * x.curvature_mm.abs(),
            "{}: d²e/ds² {:e} vs finite difference {fd2:e}", p.surface().describe(), x.curvature_mm
        );
    }

    #[test]
    fn the_compensated_height_has_the_gradient_of_the_surface_at_the_contact(
        case in any_case(),
        r_frac in r_frac(),
        t in 0.0..0.9f64,
        theta in 0.0..6.3f64,
    ) {
        // Envelope theorem: z*(ρ_s, θ) = max_a F(a; ρ_s, θ), so ∂z*/∂ρ_s = f_u and
        // ∂z*/∂θ = ρ_c·f_v at the contact Q = ρ_c·(cos θ, sin θ), while the nose stays clear of
        // the part edge.
        let p = case_planner(&case, r_frac, 16, 3.0);
        let r = p.nose().nose_radius();
        let rho = t * (case.part_radius - r);
        let z = |rho: f64, theta: f64| {
            let (s, c) = theta.sin_cos();
            p.nose().compensate(p.surface(), rho, c, s).unwrap_or_else(|e| panic!("{e}"))
        };
        let contact = z(rho, theta);
        let (s, c) = theta.sin_cos();
        let l = p.surface().local(contact.rho * c, contact.rho * s).unwrap();
        let f_u = l.zx * c + l.zy * s;
        let f_v = -l.zx * s + l.zy * c;
        // h = 1e-5 mm (radians): truncation h²/6·|z‴| < 2e-11 for |z‴| < 1, rounding of
        // heights of a few mm (1e-15) over 2h, 5e-11; the differences seen are below 3e-11.
        let h = 1e-5;
        let d_rho = (z(rho + h, theta).z_tip - z(rho - h, theta).z_tip) / (2.0 * h);
        let d_theta = (z(rho, theta + h).z_tip - z(rho, theta - h).z_tip) / (2.0 * h);
        prop_assert!((d_rho - f_u).abs() <= 2e-10, "∂z*/∂ρ {d_rho:e} vs f_u {f_u:e}");
        prop_assert!(
            (d_theta - contact.rho * f_v).abs() <= 2e-10,
            "∂z*/∂θ {d_theta:e} vs ρ_c·f_v {:e}", contact.rho * f_v
        );
    }
}

#[test]
fn wavy_segments_with_many_extremes_match_the_brute_force() {
    // A sinusoidal grid of 0.3 × 0.4 mm wavelengths under segments of 12 points per revolution,
    // ~0.4 mm long: several overcuts and undercuts per segment, found only by sampling at the
    // surface's feature length and refining each.
    let json = r#"{"type":"sinusoid","amplitude_mm":0.001,"wavelength_x_mm":0.3,"wavelength_y_mm":0.4,"phase_x_deg":20}"#;
    for r in [0.0, 0.05] {
        let p = planner(json, 1.5, r, 0.5, 12);
        let pts = path_points(&p);
        for k in [2, 8, 14] {
            let e = check_segment(&p, &pts[k], &pts[k + 1]).unwrap_or_else(|e| panic!("{e}"));
            assert!(
                e.overcut.error_mm < -1e-5 && e.undercut.error_mm > 1e-5,
                "{e:?}"
            );
        }
    }
}

#[test]
fn kinks_are_bracketed_and_bisected() {
    // A convex lens array: the sag has slope kinks at the lenslet rims, and with a round nose
    // the compensated height has kinks where the contact jumps between lenslets. e′ jumps
    // through 0 there, so the extreme is a cusp between samples that bisection closes in on.
    let json = r#"{"type":"lens_array","lens_radius_mm":0.6,"aperture_mm":0.4,"pitch_mm":0.5,"grid":"rectangular","form":"convex"}"#;
    for r in [0.0, 0.05] {
        let p = planner(json, 1.2, r, 0.3, 16);
        let pts = path_points(&p);
        for k in [3, 9, 20] {
            check_segment(&p, &pts[k], &pts[k + 1]).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}

/// Paper 004's concave lens array (R 2.84 mm, 1 mm lenslets, pitch 1 mm) on a Ø6 mm part, a
/// 0.5 mm nose: its rims are ridges, and a nose astride one touches the ridge itself.
fn concave_lens_array(feed: f64, points_per_rev: u32) -> Planner {
    let json = r#"{"type":"lens_array","lens_radius_mm":2.84,"aperture_mm":1.0,"pitch_mm":1.0,"grid":"rectangular","form":"concave"}"#;
    planner(json, 3.0, 0.5, feed, points_per_rev)
}

/// Whether the contact of the nose over (ρ, θ) is pinned on a slope kink: the surface's radial
/// slope there differs from tan a (at a smooth maximum of F they are equal).
fn pinned_on_a_rim(p: &Planner, rho: f64, theta: f64) -> bool {
    let (s, c) = theta.sin_cos();
    let contact = p.nose().compensate(p.surface(), rho, c, s).unwrap();
    let l = p.surface().local(contact.rho * c, contact.rho * s).unwrap();
    !contact.at_arc_end && (l.zx * c + l.zy * s - contact.angle.tan()).abs() > 1e-4
}

#[test]
fn on_a_lenslet_rim_the_slope_is_the_derivative_of_the_error() {
    // Where the contact sits on a rim, F′ ≠ 0 at the maximum and the envelope theorem's slope
    // `Δz − Δρ·f_u − ρ_c·Δθ·f_v` misses the contact's motion along the ridge; de/ds follows
    // the ridge instead (its crossing with the section moves by −ρ_c·Δθ·Δf_v/Δf_u, Δf the
    // gradient's jump). Against central differences of e where the contact stays on the rim
    // over ±h, h = 1e-4, Richardson-extrapolated from h and h/2 (e‴ reaches ~20 mm on a rim,
    // so the plain difference's truncation h²/6·|e‴| would be 3e-8 mm; the extrapolation's is
    // of order h⁴); the side of the kink each height is taken from (F below its peak by
    // |F′|·10⁻¹² rad, |F′| ≤ 0.2 mm) adds at most 4e-12/h·5/3 ≈ 7e-9 mm. The differences seen
    // are below 1e-10 mm; the envelope theorem's slope is off by more than 1e-6 at most points.
    let p = concave_lens_array(0.05, 90);
    let pts = path_points(&p);
    let h = 1e-4;
    let (mut checked, mut envelope_off) = (0, 0);
    for w in pts.windows(2).step_by(7) {
        let (a, b) = (&w[0], &w[1]);
        let (drho, dtheta) = (b.rho - a.rho, b.theta - a.theta);
        for k in 1..10 {
            let s = k as f64 / 10.0;
            let pinned = [s - h, s, s + h]
                .iter()
                .all(|&t| pinned_on_a_rim(&p, a.rho + t * drho, a.theta + t * dtheta));
            if !pinned {
                continue;
            }
            let at = |t: f64| error_at(&p, a, b, t).unwrap_or_else(|e| panic!("{e}"));
            let central = |h: f64| (at(s + h).error_mm - at(s - h).error_mm) / (2.0 * h);
            let fd = (4.0 * central(0.5 * h) - central(h)) / 3.0;
            let x = at(s);
            assert!(
                (fd - x.slope_mm).abs() <= 1e-8 + 1e-5 * x.slope_mm.abs(),
                "segment {} s {s}: de/ds {:e} vs finite difference {fd:e}",
                a.index,
                x.slope_mm
            );
            let theta = a.theta + s * dtheta;
            let (sn, c) = theta.sin_cos();
            let contact = p
                .nose()
                .compensate(p.surface(), a.rho + s * drho, c, sn)
                .unwrap();
            let l = p
                .surface()
                .local(contact.rho * c, contact.rho * sn)
                .unwrap();
            let (f_u, f_v) = (l.zx * c + l.zy * sn, -l.zx * sn + l.zy * c);
            let envelope = (b.z - a.z) - drho * f_u - contact.rho * dtheta * f_v;
            if (envelope - fd).abs() > 1e-6 {
                envelope_off += 1;
            }
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked} points on rims");
    assert!(envelope_off * 2 > checked, "{envelope_off} of {checked}");
}

#[test]
fn segments_over_concave_lenslet_rims_match_the_brute_force() {
    // The extremes of e where the contact rides a rim of a concave lens array (the concave
    // shortcut of the compensation) or jumps between rims: e′ along the ridge is known, so the
    // refinement closes in by secant steps instead of bisecting on a wrong slope.
    let p = concave_lens_array(0.05, 90);
    let pts = path_points(&p);
    let mut on_rims = 0;
    for w in pts.windows(2).skip(40).step_by(37) {
        let (a, b) = (&w[0], &w[1]);
        if (1..8).any(|k| {
            let s = k as f64 / 8.0;
            pinned_on_a_rim(
                &p,
                a.rho + s * (b.rho - a.rho),
                a.theta + s * (b.theta - a.theta),
            )
        }) {
            on_rims += 1;
        }
        check_segment(&p, a, b).unwrap_or_else(|e| panic!("{e}"));
    }
    assert!(on_rims >= 10, "{on_rims} segments with a contact on a rim");
}

/// A path point of a sharp tool at (ρ, θ) on `p`'s surface.
fn point(p: &Planner, index: u64, rho: f64, theta: f64) -> PathPoint {
    let (s, c) = theta.sin_cos();
    let contact = p.nose().compensate(p.surface(), rho, c, s).unwrap();
    PathPoint {
        index,
        rho,
        theta,
        z: contact.z_tip,
        contact: [contact.rho * c, contact.rho * s, contact.z],
        contact_angle: contact.angle,
        at_arc_end: contact.at_arc_end,
    }
}

#[test]
fn a_paraboloid_gives_the_radial_chord_error() {
    // z = ρ²/(2R): along a segment z* = (ρ_a + sΔρ)²/(2R) and e(s) = Δρ²/(2R)·s(1 − s), an
    // undercut Δρ²/(8R) at s = ½ and no overcut, Δρ = f/N on every segment.
    let (big, feed, n) = (10.0, 0.6, 12);
    let p = planner(
        &format!(r#"{{"type":"asphere","radius_mm":{big},"conic":-1}}"#),
        3.0,
        0.0,
        feed,
        n,
    );
    let pts = path_points(&p);
    let d_rho = feed / n as f64;
    let expect = d_rho * d_rho / (8.0 * big);
    for w in pts.windows(2) {
        let err = segment_error(&p, &w[0], &w[1]).unwrap();
        assert!(
            (err.undercut.error_mm - expect).abs() <= TOL,
            "{} vs {expect}",
            err.undercut.error_mm
        );
        assert!((err.undercut.s - 0.5).abs() <= 1e-6, "{}", err.undercut.s);
        assert!(err.overcut.error_mm >= -TOL);
    }
    let report = analyse(&p, 64, |_| {}).unwrap();
    assert!((report.max_undercut_um - expect * 1e3).abs() <= TOL * 1e3);
    assert!(report.max_overcut_um <= TOL * 1e3);
    assert_eq!(report.segments, pts.len() as u64 - 1);
}

#[test]
fn a_round_tool_on_a_sphere_follows_the_offset_sphere() {
    // Concave sphere R, nose r: the tip is z*(ρ) = R − √((R − r)² − ρ²) − r, a function of ρ
    // alone, so e(s) = chord − z*(ρ(s)) is largest where z*′(ρ) = ρ/√((R − r)² − ρ²) equals the
    // chord's slope m = Δz/Δρ: ρ* = m(R − r)/√(1 + m²).
    let (big, r) = (8.0, 0.4);
    let p = planner(
        &format!(r#"{{"type":"asphere","radius_mm":{big}}}"#),
        3.0,
        r,
        0.5,
        16,
    );
    let tip = |rho: f64| big - ((big - r).powi(2) - rho * rho).sqrt() - r;
    let pts = path_points(&p);
    let mut checked = 0;
    for w in pts.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        // Away from the part edge, where the arc is whole.
        if a.rho > 3.0 - r {
            continue;
        }
        let m = (tip(b.rho) - tip(a.rho)) / (b.rho - a.rho);
        let rho = m * (big - r) / (1.0 + m * m).sqrt();
        let expect = tip(a.rho) + (rho - a.rho) * m - tip(rho);
        let err = segment_error(&p, a, b).unwrap();
        assert!(
            (err.undercut.error_mm - expect).abs() <= TOL,
            "ρ {}: {:e} vs {expect:e}",
            a.rho,
            err.undercut.error_mm
        );
        assert!(err.overcut.error_mm >= -TOL);
        checked += 1;
    }
    assert!(checked > 50);
}

#[test]
fn a_tilted_flat_gives_the_circumferential_chord_error() {
    // z = t·x with a sharp tool, segments at constant radius ρ centred on azimuth φ (see the
    // module docs).
    let t = (0.5f64).to_radians().tan();
    let p = planner(
        r#"{"type":"tilted_flat","tilt_deg":0.5}"#,
        5.0,
        0.0,
        0.5,
        12,
    );
    let (rho, dt) = (4.0, (20.0f64).to_radians());
    let seg = |phi: f64| {
        let a = point(&p, 0, rho, phi - dt / 2.0);
        let b = point(&p, 1, rho, phi + dt / 2.0);
        segment_error(&p, &a, &b).unwrap()
    };
    // The refinement stops once the height still to gain is below 1e-13 mm, which leaves s
    // within √(2·1e-13/|e″|) of the extreme: |e″| ≥ 4e-4 mm here, so within 2.3e-5.
    let s_tol = 3e-5;
    let chord = t * rho * (1.0 - (dt / 2.0).cos());
    let at_zero = seg(0.0);
    assert!((at_zero.overcut.error_mm + chord).abs() <= TOL);
    assert!((at_zero.overcut.s - 0.5).abs() <= s_tol);
    assert!(at_zero.undercut.error_mm.abs() <= TOL);
    let at_pi = seg(PI);
    assert!((at_pi.undercut.error_mm - chord).abs() <= TOL);
    assert!((at_pi.undercut.s - 0.5).abs() <= s_tol);
    assert!(at_pi.overcut.error_mm.abs() <= TOL);
    // φ = π/2: e(u) = t·ρ·(sin(uΔθ) − 2u·sin(Δθ/2)), odd in u: both signs.
    let u = (2.0 * (dt / 2.0).sin() / dt).acos() / dt;
    let peak = t * rho * ((u * dt).sin() - 2.0 * u * (dt / 2.0).sin());
    let inflection = seg(PI / 2.0);
    assert!(peak > 0.0);
    assert!((inflection.undercut.error_mm - peak).abs() <= TOL);
    assert!((inflection.overcut.error_mm + peak).abs() <= TOL);
    assert!((inflection.undercut.s - (0.5 + u)).abs() <= s_tol);
    assert!((inflection.overcut.s - (0.5 - u)).abs() <= s_tol);
}

#[test]
fn the_error_is_of_second_order_in_the_angle_step() {
    // Doubling N halves Δθ and Δρ = f/N: the chord errors fall by 4. The relative correction
    // is O(Δθ²) (1e-4 at N = 120) and the worst segment of the denser path lies up to a step
    // away from the coarser one's, where the error differs by ~0.1 %: within 1 % of 4. With a
    // round nose the worst overcut is on the first revolution, where the arc is cut at the part
    // edge and the contact sits on the edge, and moves with N; the undercut is compared there.
    let flat = r#"{"type":"tilted_flat","tilt_deg":1.0,"azimuth_deg":30}"#;
    let poly = r#"{"type":"xy_polynomial","base":{"radius_mm":50},"norm_radius_mm":2,"terms":[{"x":2,"y":1,"coefficient_mm":0.002},{"x":0,"y":3,"coefficient_mm":-0.001}]}"#;
    for (json, r) in [(flat, 0.0), (poly, 0.0), (poly, 0.1)] {
        let worst = |n: u32| {
            let rep = analyse(&planner(json, 2.0, r, 0.2, n), 16, |_| {}).unwrap();
            if r == 0.0 {
                rep.max_overcut_um.max(rep.max_undercut_um)
            } else {
                rep.max_undercut_um
            }
        };
        let ratio = worst(120) / worst(240);
        assert!((ratio - 4.0).abs() < 0.04, "{json} r {r}: ratio {ratio}");
    }
}

/// Asserts two reports equal to the bit; the map holds NaN, which compares unequal, so it is
/// compared by bits.
fn assert_same_report(a: &LinearizationReport, b: &LinearizationReport) {
    let bits =
        |r: &spiralcam::raster::Raster| r.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a.map), bits(&b.map));
    let (mut a, mut b) = (a.clone(), b.clone());
    (a.map.values, b.map.values) = (Vec::new(), Vec::new());
    assert_eq!(a, b);
}

#[test]
fn the_path_check_agrees_with_each_segment() {
    let p = planner(
        r#"{"type":"sinusoid","amplitude_mm":0.002,"wavelength_x_mm":1.5,"wavelength_y_mm":2.0}"#,
        2.0,
        0.05,
        0.25,
        24,
    );
    let pts = path_points(&p);
    let (mut over, mut under) = (0.0f64, 0.0f64);
    let mut check = LinearizationCheck::new(&p, 32);
    for (i, q) in pts.iter().enumerate() {
        check.add(&p, q).unwrap();
        if i > 0 {
            let e = segment_error(&p, &pts[i - 1], q).unwrap();
            over = over.max(-e.overcut.error_mm);
            under = under.max(e.undercut.error_mm);
        }
    }
    let from_check = check.finish();
    let mut calls = Vec::new();
    let report = analyse(&p, 32, |n| calls.push(n)).unwrap();
    assert_same_report(&report, &from_check);
    assert_eq!(calls.last(), Some(&(pts.len() as u64)));
    assert_eq!(report.segments, pts.len() as u64 - 1);
    assert_eq!(report.max_overcut_um, over * 1e3);
    assert_eq!(report.max_undercut_um, under * 1e3);
    assert!(over > 0.0 && under > 0.0);
    assert_eq!(report.pv_um, report.max_overcut_um + report.max_undercut_um);
    let worst = if over > under {
        report.max_overcut_at
    } else {
        report.max_undercut_at
    };
    assert_eq!(report.worst_at, worst);
    // The map's extremes are the report's, with their signs.
    let (lo, hi) = report.map.range().unwrap();
    assert_eq!(lo, -report.max_overcut_um);
    assert_eq!(hi, report.max_undercut_um);
    let json = serde_json::to_value(&report).unwrap();
    assert!(json.get("map").is_none());
    assert_eq!(json["segments"], report.segments);
}

#[test]
fn the_analysis_on_the_workers_equals_the_check_point_by_point() {
    // 20 001 points: two batches of the workers, the second starting from the first's last.
    let p = planner(
        r#"{"type":"sinusoid","amplitude_mm":0.002,"wavelength_x_mm":0.7,"wavelength_y_mm":0.9}"#,
        1.0,
        0.05,
        0.004,
        80,
    );
    let pts = path_points(&p);
    assert_eq!(pts.len(), 20_001);
    let mut check = LinearizationCheck::new(&p, 48);
    for q in &pts {
        check.add(&p, q).unwrap();
    }
    let by_point = check.finish();
    let mut stages = 0;
    let analysis = Analysis::run(&p, 48, &mut |_| {
        stages += 1;
        ControlFlow::Continue(())
    })
    .unwrap();
    assert!(stages > 0);
    let on_workers = analysis.linearization;
    assert_same_report(&on_workers, &by_point);
    assert_eq!(on_workers.segments, 20_000);
    assert!(on_workers.max_overcut_um > 0.0 && on_workers.max_undercut_um > 0.0);
}

#[test]
fn degenerate_input_gives_errors_or_zeros_never_nan() {
    let p = planner(r#"{"type":"asphere","radius_mm":20}"#, 3.0, 0.2, 0.5, 12);
    let a = point(&p, 0, 2.0, 0.3);
    // The same point twice: no move, no error.
    let e = segment_error(&p, &a, &a).unwrap();
    assert_eq!((e.overcut.error_mm, e.undercut.error_mm), (0.0, 0.0));
    // Non-finite input is refused.
    let mut bad = a;
    bad.z = f64::NAN;
    assert!(segment_error(&p, &a, &bad).is_err());
    bad = a;
    bad.theta = f64::INFINITY;
    assert!(segment_error(&p, &bad, &a).is_err());
    assert!(error_at(&p, &a, &a, f64::NAN).is_err());
    // A huge angle step stays finite (the sample count is capped).
    let far = point(&p, 1, 1.0, 1e4);
    let e = segment_error(&p, &a, &far).unwrap();
    assert!(e.overcut.error_mm.is_finite() && e.undercut.error_mm.is_finite());
    // An empty check reports zeros.
    let r = LinearizationCheck::new(&p, 8).finish();
    assert_eq!((r.segments, r.pv_um), (0, 0.0));
    assert!(r.max_overcut_at.rho_mm.is_finite());
}
