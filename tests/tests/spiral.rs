//! Spiral sampling through the public API: at constant angle the radial pitch is the feed at
//! every revolution, the angle steps are exactly 2π/N, the count is N·R′/f + 1 and the last point
//! is exactly at the centre; at constant arc the planar arc length between points (integrated
//! independently by Gauss–Legendre quadrature of √(ρ² + (dρ/dθ)²)) is ΔS wherever the angle cap
//! does not bind, the cap holds everywhere and the count hint is close; direction and start
//! angle are honoured; bad parameters name their field.

mod common;

use common::config;
use proptest::prelude::*;
use spiralcam::job::{Direction, Sampling};
use spiralcam::path::spiral::{Spiral, SpiralPoint, arc_length};
use std::f64::consts::TAU;

/// Seed of this file's property tests.
const SEED: u64 = 2002;

fn direction() -> impl Strategy<Value = Direction> {
    prop_oneof![Just(Direction::Ccw), Just(Direction::Cw)]
}

/// Rounding of an angle formed as `θ₀ ± Δ` with |Δ| up to `span`, rad: a few ulps of the
/// larger of the two.
fn angle_ulps(theta0: f64, span: f64) -> f64 {
    8.0 * f64::EPSILON * (theta0.abs() + span.abs() + TAU)
}

/// ∫ √(ρ(θ)² + b²) |dθ| over [t0, t1] for the spiral ρ(θ) = ρ_start − b·s·(θ − θ_start), by
/// 8-point Gauss–Legendre on 4 sub-intervals (the integrand is smooth, its relative error is far
/// below 1e-12 for these step sizes).
fn planar_arc(rho_of: impl Fn(f64) -> f64, b: f64, t0: f64, t1: f64) -> f64 {
    const X: [f64; 4] = [
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_3,
    ];
    const W: [f64; 4] = [
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_5,
        0.101_228_536_290_376_3,
    ];
    let pieces = 4;
    let h = (t1 - t0) / pieces as f64;
    let mut sum = 0.0;
    for p in 0..pieces {
        let mid = t0 + h * (p as f64 + 0.5);
        for (x, w) in X.iter().zip(W) {
            for sign in [-1.0, 1.0] {
                let t = mid + sign * x * h / 2.0;
                let rho = rho_of(t);
                sum += w * (rho * rho + b * b).sqrt();
            }
        }
    }
    (sum * h / 2.0).abs()
}

fn constant_angle_case() -> impl Strategy<Value = (f64, f64, u32, Direction, f64)> {
    (
        0.05..20.0f64,
        0.001..0.5f64,
        3u32..2000,
        direction(),
        -360.0..360.0f64, // the start angle's whole domain
    )
        .prop_filter(
            "at most 200 000 points, a feed at most the radius",
            |(r, f, n, _, _)| *n as f64 * r / f < 2e5 && f <= r,
        )
}

proptest! {
    #![proptest_config(config(48, SEED))]

    #[test]
    fn constant_angle_pitch_is_the_feed_and_steps_are_equal(
        (radius, feed, n, dir, start) in constant_angle_case()
    ) {
        let spiral = Spiral::new(radius, feed, &Sampling::ConstantAngle { points_per_rev: n }, dir, start)
            .unwrap();
        let pts: Vec<SpiralPoint> = spiral.points().collect();
        let nn = n as usize;
        let r1 = spiral.start_radius_mm();
        // R′ = K·f/N with K whole, at most one angle step outside R.
        let k = n as f64 * r1 / feed;
        prop_assert!((k - k.round()).abs() < 1e-9 * k.max(1.0), "N·R′/f = {k} is not whole");
        prop_assert!(r1 >= radius * (1.0 - 1e-15) && r1 < radius + feed / n as f64 + 1e-12,
            "start radius {r1} for R {radius}, f/N {}", feed / n as f64);
        prop_assert_eq!(pts.len() as u64, k.round() as u64 + 1);
        prop_assert_eq!(spiral.point_count_hint(), pts.len() as u64);
        prop_assert!((spiral.revolutions() - r1 / feed).abs() < 1e-12 * spiral.revolutions());

        // First point at R′ and the start angle; last exactly at the centre.
        prop_assert!((pts[0].rho - r1).abs() <= 1e-15 * r1);
        prop_assert_eq!(pts[0].theta, start.to_radians());
        prop_assert_eq!(pts.last().unwrap().rho, 0.0);

        let step = dir.sign() * TAU / n as f64;
        for (i, w) in pts.windows(2).enumerate() {
            let dt = w[1].theta - w[0].theta;
            let span = w[1].theta - pts[0].theta;
            prop_assert!((dt - step).abs() <= angle_ulps(pts[0].theta, span),
                "step {i}: Δθ {dt} vs {step}");
            prop_assert!(w[1].rho < w[0].rho, "ρ not decreasing at {i}");
        }
        // Radial pitch between points k and k + N: exactly the feed, at every revolution.
        for k in 0..pts.len().saturating_sub(nn) {
            let pitch = pts[k].rho - pts[k + nn].rho;
            prop_assert!((pitch - feed).abs() <= 1e-12, "pitch {pitch} at point {k}, feed {feed}");
        }
        // On the spiral ρ = R′ − f·|θ − θ₀|/2π.
        for p in &pts {
            let rho = r1 - feed * (p.theta - start.to_radians()).abs() / TAU;
            let ulps = angle_ulps(pts[0].theta, p.theta - pts[0].theta);
            prop_assert!((p.rho - rho).abs() <= 1e-12 + feed * ulps,
                "ρ {} vs {rho}", p.rho);
        }
    }
}

#[test]
fn constant_angle_whole_revolutions_start_at_the_outer_radius() {
    // R/f = 250 revolutions exactly: no step outside R.
    let s = Spiral::new(
        5.0,
        0.02,
        &Sampling::ConstantAngle { points_per_rev: 72 },
        Direction::Ccw,
        0.0,
    )
    .unwrap();
    assert_eq!(s.start_radius_mm(), 5.0);
    assert_eq!(s.points().count(), 72 * 250 + 1);
    // 0.3/0.1 is 2.9999999999999996 in binary: still 3 revolutions, 3·N steps.
    let s = Spiral::new(
        0.3,
        0.1,
        &Sampling::ConstantAngle { points_per_rev: 10 },
        Direction::Ccw,
        0.0,
    )
    .unwrap();
    assert_eq!(s.points().count(), 31);
    assert!((s.start_radius_mm() - 0.3).abs() < 1e-15);
}

#[test]
fn direction_and_start_angle_are_honoured() {
    let sampling = Sampling::ConstantAngle { points_per_rev: 8 };
    let ccw: Vec<_> = Spiral::new(1.0, 0.5, &sampling, Direction::Ccw, 30.0)
        .unwrap()
        .points()
        .collect();
    let cw: Vec<_> = Spiral::new(1.0, 0.5, &sampling, Direction::Cw, 30.0)
        .unwrap()
        .points()
        .collect();
    assert_eq!(ccw.len(), 17);
    assert_eq!(cw.len(), 17);
    for (k, (a, b)) in ccw.iter().zip(&cw).enumerate() {
        let d = 45f64.to_radians() * k as f64;
        assert!((a.theta - (30f64.to_radians() + d)).abs() < 1e-14, "{k}");
        assert!((b.theta - (30f64.to_radians() - d)).abs() < 1e-14, "{k}");
        assert_eq!(a.rho, b.rho);
        assert!((a.rho - (1.0 - k as f64 / 16.0)).abs() < 1e-15);
    }
    // Seen from +Z, counter-clockwise means the first step turns from +X towards +Y.
    let first: Vec<_> = Spiral::new(1.0, 0.5, &sampling, Direction::Ccw, 0.0)
        .unwrap()
        .points()
        .take(2)
        .collect();
    assert!(first[1].theta.sin() > 0.0);
    let arc = Sampling::ConstantArc {
        arc_length_mm: 0.05,
        max_angle_step_deg: 5.0,
    };
    for (dir, sign) in [(Direction::Ccw, 1.0), (Direction::Cw, -1.0)] {
        let pts: Vec<_> = Spiral::new(1.0, 0.1, &arc, dir, -45.0)
            .unwrap()
            .points()
            .collect();
        assert_eq!(pts[0].theta, (-45f64).to_radians());
        assert!((pts[0].rho - 1.0).abs() <= 4.0 * f64::EPSILON);
        for w in pts.windows(2) {
            assert!(sign * (w[1].theta - w[0].theta) > 0.0);
        }
    }
}

fn constant_arc_case() -> impl Strategy<Value = (f64, f64, f64, f64, Direction, f64)> {
    (
        0.05..10.0f64,
        0.002..0.3f64,
        0.002..0.3f64,
        0.05..90.0f64,
        direction(),
        -360.0..360.0f64,
    )
        .prop_filter("at most 100 000 points", |&(r, f, ds, cap, dir, start)| {
            Spiral::new(
                r,
                f,
                &Sampling::ConstantArc {
                    arc_length_mm: ds,
                    max_angle_step_deg: cap,
                },
                dir,
                start,
            )
            .map(|s| s.point_count_hint() < 100_000)
            .unwrap_or(false)
        })
}

/// Relative accuracy of the arc length of a step. Newton solves S(φ) to ~1e-15 relative; θ is
/// formed as θ₀ ± (φ₀ − φ) with φ₀ = τR/f, so it carries ~2ε·φ₀ rad of rounding, i.e.
/// 2ε·τR²/f mm on a step of ΔS: under 1e-10 relative for the cases drawn (R²/(f·ΔS) < 3·10⁴,
/// as the point count is capped at 10⁵). The quadrature is exact to ~1e-14. 1e-8 leaves margin.
const ARC_REL: f64 = 1e-8;

proptest! {
    #![proptest_config(config(48, SEED))]

    #[test]
    fn constant_arc_steps_are_the_arc_length_or_the_angle_cap(
        (radius, feed, ds, cap_deg, dir, start) in constant_arc_case()
    ) {
        let sampling = Sampling::ConstantArc { arc_length_mm: ds, max_angle_step_deg: cap_deg };
        let spiral = Spiral::new(radius, feed, &sampling, dir, start).unwrap();
        let pts: Vec<SpiralPoint> = spiral.points().collect();
        let b = feed / TAU;
        let cap = cap_deg.to_radians();
        let t0 = start.to_radians();
        let s = dir.sign();
        let rho_of = |t: f64| radius - b * s * (t - t0);

        // ρ₀ = b·(R/b): R to an ulp or two.
        prop_assert!((pts[0].rho - radius).abs() <= 4.0 * f64::EPSILON * radius);
        prop_assert_eq!(pts[0].theta, t0);
        prop_assert_eq!(pts.last().unwrap().rho, 0.0);
        prop_assert_eq!(spiral.start_radius_mm(), radius);
        prop_assert!((spiral.revolutions() - radius / feed).abs() <= 1e-12 * spiral.revolutions());

        // θ = θ₀ ± (φ₀ − φ) with φ₀ = R/b: rounding is relative to φ₀.
        let ulps = angle_ulps(t0, radius / b);
        let mut uncapped = 0;
        let last = pts.len() - 2;
        for (i, w) in pts.windows(2).enumerate() {
            let (a, c) = (w[0], w[1]);
            // On the spiral.
            let tol_rho = 1e-12 * radius.max(1.0) + b * ulps;
            prop_assert!((c.rho - rho_of(c.theta)).abs() <= tol_rho,
                "point {}: ρ {} vs {}", i + 1, c.rho, rho_of(c.theta));
            let dt = (c.theta - a.theta) * s;
            prop_assert!(dt > 0.0, "θ does not advance at step {i}");
            // The cap everywhere, the last step included.
            prop_assert!(dt <= cap + ulps, "step {i}: Δθ {dt} > cap {cap}");
            let arc = planar_arc(rho_of, b, a.theta, c.theta);
            let capped = (dt - cap).abs() <= ulps;
            if i == last || capped {
                prop_assert!(arc <= ds * (1.0 + ARC_REL),
                    "step {i} (capped {capped}, last {}): arc {arc} > ΔS {ds}", i == last);
            } else {
                uncapped += 1;
                prop_assert!((arc - ds).abs() <= ARC_REL * ds,
                    "step {i} of {}: arc {arc} vs ΔS {ds} (Δθ {dt}, cap {cap}, ρ {})",
                    pts.len() - 1, a.rho);
            }
        }
        // Wherever ΔS/ρ is well under the cap the steps are of length ΔS, so some steps must
        // have been checked against ΔS when the outer radius allows it.
        if ds / radius < 0.5 * cap && arc_length(b, radius / b) > 4.0 * ds {
            prop_assert!(uncapped > 0);
        }
        let hint = spiral.point_count_hint() as i64;
        prop_assert!((hint - pts.len() as i64).abs() <= 3,
            "hint {hint}, points {}", pts.len());
    }
}

#[test]
fn constant_arc_total_length_matches_the_closed_form() {
    // The sum of the steps is the spiral's length S(R/b) − S(0): an independent check of the
    // closed form used by the sampler (trapezoid on a dense polyline of the spiral).
    let (radius, feed, ds) = (2.0, 0.05, 0.01);
    let b = feed / TAU;
    let spiral = Spiral::new(
        radius,
        feed,
        &Sampling::ConstantArc {
            arc_length_mm: ds,
            max_angle_step_deg: 90.0,
        },
        Direction::Ccw,
        0.0,
    )
    .unwrap();
    let pts: Vec<_> = spiral.points().collect();
    let phi = radius / b;
    let n = 2_000_000;
    let mut length = 0.0;
    let (mut px, mut py) = (radius, 0.0);
    for k in 1..=n {
        let t = phi * k as f64 / n as f64;
        let rho = radius - b * t;
        let (x, y) = (rho * t.cos(), rho * t.sin());
        length += (x - px).hypot(y - py);
        (px, py) = (x, y);
    }
    // Chord error of the polyline: ~ (Δφ)²/24 relative, Δφ = φ/n ≈ 6e-4 → 2e-8.
    assert!(
        (length - arc_length(b, phi)).abs() < 1e-7 * length,
        "{length} vs {}",
        arc_length(b, phi)
    );
    // Steps of ΔS except the capped ones near the centre and the last: the count follows.
    let steps = pts.len() - 1;
    assert!(
        (steps as f64 - length / ds).abs() < 10.0,
        "{steps} steps for {} mm",
        length
    );
}

#[test]
fn bad_parameters_name_their_field() {
    let angle = |n| Sampling::ConstantAngle { points_per_rev: n };
    let arc = |ds, cap| Sampling::ConstantArc {
        arc_length_mm: ds,
        max_angle_step_deg: cap,
    };
    let cases = [
        (1.0, 0.1, angle(2), 0.0, "sampling.points_per_rev"),
        (1.0, 0.1, angle(1_000_001), 0.0, "sampling.points_per_rev"),
        (1.0, 0.1, arc(0.0, 1.0), 0.0, "sampling.arc_length_mm"),
        (1.0, 0.1, arc(f64::NAN, 1.0), 0.0, "sampling.arc_length_mm"),
        (1.0, 0.1, arc(0.01, 0.0), 0.0, "sampling.max_angle_step_deg"),
        (
            1.0,
            0.1,
            arc(0.01, 90.5),
            0.0,
            "sampling.max_angle_step_deg",
        ),
        (
            1.0,
            0.1,
            arc(0.01, f64::NAN),
            0.0,
            "sampling.max_angle_step_deg",
        ),
        (0.0, 0.1, angle(10), 0.0, "outer_radius_mm"),
        (1.0, -0.1, angle(10), 0.0, "feed_mm_per_rev"),
        (1.0, f64::INFINITY, angle(10), 0.0, "feed_mm_per_rev"),
        (1.0, 0.1, angle(10), f64::NAN, "start_angle_deg"),
        // An angle past a turn either way: 1e300° once reached the NC writer as C = 1.7e298.
        (1.0, 0.1, angle(10), 360.5, "start_angle_deg"),
        (1.0, 0.1, angle(10), -1e300, "start_angle_deg"),
    ];
    for (r, f, s, start, field) in cases {
        let e = Spiral::new(r, f, &s, Direction::Ccw, start).unwrap_err();
        assert_eq!(e.field, field, "{s:?}: {e}");
    }
    assert!(Spiral::new(1.0, 0.1, &angle(3), Direction::Cw, 0.0).is_ok());
    assert!(Spiral::new(1.0, 0.1, &angle(1_000_000), Direction::Cw, 0.0).is_ok());
    assert!(Spiral::new(1.0, 0.1, &arc(0.01, 90.0), Direction::Cw, 0.0).is_ok());
    for start in [-360.0, 360.0] {
        assert!(Spiral::new(1.0, 0.1, &angle(10), Direction::Cw, start).is_ok());
    }
}
