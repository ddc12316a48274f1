//! The frequency analysis and the FTS/SSS split on planned paths, through the public API:
//! the instantaneous frequency of a sine grid against its closed form per radius band, a tilted
//! flat that the slide cuts alone, a sine grid beyond the slide's bandwidth that needs the FTS,
//! and `Z + W = z` on every path.

use spiralcam::dynamics::path_signal::PathSignal;
use spiralcam::dynamics::spectrum::{amplitude_spectrum, instantaneous_frequency};
use spiralcam::dynamics::split::{Limit, Split, SplitLimits, Verdict, split};
use spiralcam::job::Job;
use spiralcam::job::SplitSpec;
use spiralcam::plan::Planner;
use std::f64::consts::TAU;

/// The planned path of a job given as JSON.
fn path(json: &str) -> PathSignal {
    let job = Job::from_json(json).unwrap();
    let planner = Planner::new(&job).unwrap();
    PathSignal::from_points(planner.points().map(|p| p.unwrap()))
}

/// A sine grid along X only (λy = 10⁶ mm with a 90° phase: cos(2πy/λy) ≥ 1 − 4e-10 on the
/// part), wavelength `lambda_mm`, amplitude 2 µm, on an 8 mm part at 256 points/rev.
fn grid_job(lambda_mm: f64, feed_mm: f64) -> String {
    format!(
        r#"{{"name": "grid", "part": {{"diameter_mm": 8.0}},
        "surface": {{"type": "sinusoid", "amplitude_mm": 0.002, "wavelength_x_mm": {lambda_mm},
                     "wavelength_y_mm": 1e6, "phase_y_deg": 90.0}},
        "tool": {{"nose_radius_mm": 0.1, "included_angle_deg": 100.0}},
        "machine": {{"spindle_rpm": 300.0}},
        "strategy": {{"feed_mm_per_rev": {feed_mm},
                      "sampling": {{"type": "constant_angle", "points_per_rev": 256}}}}}}"#
    )
}

const LIMITS: SplitLimits = SplitLimits {
    fts_stroke_mm: 0.07,
    fts_bandwidth_hz: 700.0,
    fts_acceleration_mm_per_s2: 1e6,
    slide_velocity_mm_per_s: 100.0,
    slide_acceleration_mm_per_s2: 1e4,
    slide_bandwidth_hz: 20.0,
};

fn assert_adds_up(s: &PathSignal, out: &Split) {
    for (i, z) in s.z_mm.iter().enumerate() {
        let sum = out.z_slide_mm[i] + out.w_fts_mm[i];
        assert!((sum - z).abs() <= 1e-9, "point {i}: {sum} vs {z}");
    }
}

#[test]
fn the_instantaneous_frequency_of_a_sine_grid_rises_with_the_radius() {
    // Along a circle of radius ρ, z = A·sin(a·cos θ), a = 2πρ/λ, has the instantaneous
    // frequency a·|sin θ| cycles/rev. The reference per band is the median of that closed form
    // over the band's path points (the first and last revolution left out, as the analysis
    // does). The Hilbert estimate is meaningless where the frequency passes through zero, within
    // about 1/√a rad of θ = 0 and π (stationary phase): a fraction 4/(2π·√a) of each
    // revolution, which can move the median by that much in quantile, i.e. by
    // 0.64/√a ÷ (2·dP/ds) with dP/ds = (2/π)/√(1 − s²) = 0.90 at the median s = 0.71 of
    // |sin θ|: a relative 0.5/√a, at the band's middle radius. Bands with a < 4 (the centre)
    // are left out. The medians must also fall band by band towards the centre. The same at
    // HCAA, whose turns have fewer points towards the centre: each band's stretch is analysed
    // at its own rate.
    let constant_angle = grid_job(1.0, 0.05);
    let hcaa = constant_angle.replace(
        r#"{"type": "constant_angle", "points_per_rev": 256}"#,
        r#"{"type": "hcaa", "pv_tolerance_um": 0.05}"#,
    );
    assert_ne!(hcaa, constant_angle);
    for job in [constant_angle, hcaa] {
        sine_grid_bands_against_the_closed_form(&path(&job));
    }
}

fn sine_grid_bands_against_the_closed_form(s: &PathSignal) {
    let rpm = 300.0;
    let bands = instantaneous_frequency(s, rpm, 8);
    assert_eq!(bands.len(), 8);
    for b in &bands {
        let mut reference: Vec<f64> = (0..s.len())
            .filter(|&i| {
                let (r, a) = (s.rho(i), s.angle(i));
                r <= b.rho_outer_mm && r > b.rho_inner_mm && a >= TAU && a <= s.span_rad() - TAU
            })
            .map(|i| TAU * s.rho(i) * s.angle(i).sin().abs() * rpm / 60.0)
            .collect();
        reference.sort_by(f64::total_cmp);
        let median = reference[reference.len() / 2];
        let a = TAU * 0.5 * (b.rho_outer_mm + b.rho_inner_mm);
        if a >= 4.0 {
            let tol = 0.5 / a.sqrt();
            assert!(
                (b.median_hz - median).abs() <= tol * median,
                "{b:?}: reference {median}, tolerance {tol}"
            );
        }
        // The envelope is the amplitude, 2 µm (the nose changes z by r·f′²/2 ≈ 8 nm).
        assert!((b.amplitude_um - 2.0).abs() < 0.1, "{b:?}");
    }
    assert!(
        bands.windows(2).all(|w| w[1].median_hz < w[0].median_hz),
        "{bands:?}"
    );
}

#[test]
fn a_tilted_flat_is_cut_by_the_slide_alone() {
    // tilted-flat.json at a coarser feed: one cycle per revolution, 8.3 Hz at 500 rpm, inside
    // the slide's 20 Hz; velocity t·R·ω = 0.46 mm/s, acceleration t·R·ω² = 24 mm/s².
    let json = include_str!("../../crate/jobs/tilted-flat.json")
        .replace("\"feed_mm_per_rev\": 0.02", "\"feed_mm_per_rev\": 0.2");
    let s = path(&json);
    let out = split(&s, &SplitSpec::Auto, 500.0, Some(&LIMITS)).unwrap();
    assert!(
        matches!(
            out.verdict,
            Verdict::Feasible {
                slide_alone: true,
                ..
            }
        ),
        "{:?}",
        out.verdict
    );
    assert!(out.w_fts_mm.iter().all(|w| *w == 0.0));
    assert_adds_up(&s, &out);
    let top = amplitude_spectrum(&s, 500.0, 256).peaks[0];
    // Whole-revolution tone: 1 cycle/rev within the line's width of a 50-revolution record
    // (its amplitude falls linearly to 0 at the centre: 1/50 cycle/rev).
    assert!((top.cycles_per_rev - 1.0).abs() < 0.02, "{top:?}");
}

#[test]
fn a_sine_grid_beyond_the_slide_bandwidth_goes_to_the_fts() {
    // Up to 2π·4·√2 = 36 cycles/rev, 180 Hz at 300 rpm, beyond the slide's 20 Hz; its PV of
    // 4 µm fits the 70 µm stroke at the lowest cutoff tried, ½ cycle/rev = 2.5 Hz.
    let s = path(&grid_job(1.0, 0.05));
    let alone = split(
        &s,
        &SplitSpec::Auto,
        300.0,
        Some(&SplitLimits {
            fts_stroke_mm: 1e-6,
            ..LIMITS
        }),
    )
    .unwrap();
    let Verdict::Infeasible { conflicts, .. } = &alone.verdict else {
        panic!("{:?}", alone.verdict)
    };
    assert!(
        conflicts.iter().any(|c| c.limit == Limit::SlideBandwidthHz),
        "{conflicts:?}"
    );
    let out = split(&s, &SplitSpec::Auto, 300.0, Some(&LIMITS)).unwrap();
    assert!(
        matches!(
            out.verdict,
            Verdict::Feasible {
                slide_alone: false,
                ..
            }
        ),
        "{:?}",
        out.verdict
    );
    assert_eq!(out.cutoff_hz, Some(2.5));
    let pv = |v: &[f64]| {
        v.iter().copied().fold(f64::MIN, f64::max) - v.iter().copied().fold(f64::MAX, f64::min)
    };
    assert!(
        pv(&out.w_fts_mm) > 0.0038 && pv(&out.w_fts_mm) <= 0.07,
        "{}",
        pv(&out.w_fts_mm)
    );
    assert_adds_up(&s, &out);
    for spec in [SplitSpec::Symmetric, SplitSpec::LowPass { cutoff_hz: 40.0 }] {
        assert_adds_up(&s, &split(&s, &spec, 300.0, None).unwrap());
    }
}
