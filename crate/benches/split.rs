//! Frequency analysis and splitting of a 1 M point path: the amplitude spectrum, the Hilbert
//! instantaneous frequency per band, and the automatic split with its checks, on a synthetic
//! spiral of 1000 revolutions × 1000 points (a sag, 6 and 47 cycles per revolution, the
//! paper 000 case) at 60 rpm. Before timing it prints the frequencies found on that path and on
//! the paper 000 compound eye job (`crate/jobs/compound-eye-paper000.json`, planned as it is).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use spiralcam::dynamics::path_signal::PathSignal;
use spiralcam::dynamics::spectrum::{amplitude_spectrum, instantaneous_frequency};
use spiralcam::dynamics::split::{SplitLimits, split};
use spiralcam::job::Job;
use spiralcam::job::SplitSpec;
use spiralcam::plan::Planner;
use std::f64::consts::TAU;
use std::hint::black_box;

const LIMITS: SplitLimits = SplitLimits {
    fts_stroke_mm: 0.07,
    fts_bandwidth_hz: 700.0,
    fts_acceleration_mm_per_s2: 1e6,
    slide_velocity_mm_per_s: 100.0,
    slide_acceleration_mm_per_s2: 1e4,
    slide_bandwidth_hz: 20.0,
};

/// 1000 revolutions of 1000 points from radius 5 mm to the centre.
fn two_frequencies() -> PathSignal {
    let (mut theta, mut radius, mut height) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..=1_000_000u32 {
        let phi = f64::from(k) * TAU / 1000.0;
        let rho = 5.0 * (1.0 - phi / (1000.0 * TAU));
        theta.push(phi);
        radius.push(rho);
        height.push(rho * rho / 80.0 + 0.5 * (6.0 * phi).sin() + 0.02 * (47.0 * phi).cos());
    }
    PathSignal::from_columns(theta, radius, height)
}

fn report(name: &str, s: &PathSignal, rpm: f64) {
    let sp = amplitude_spectrum(s, rpm, 2048);
    println!(
        "{name}: {} points, {:.0} revolutions, {rpm} rpm",
        s.len(),
        s.revolutions()
    );
    for p in &sp.peaks {
        println!(
            "  peak {:.4} Hz ({:.4} cycles/rev), {:.4} µm",
            p.freq_hz, p.cycles_per_rev, p.amplitude_um
        );
    }
    for b in instantaneous_frequency(s, rpm, 5) {
        println!(
            "  band {:.2}–{:.2} mm: median {:.3} Hz, p95 {:.3} Hz, amplitude {:.4} µm",
            b.rho_outer_mm, b.rho_inner_mm, b.median_hz, b.p95_hz, b.amplitude_um
        );
    }
}

fn split_1m(c: &mut Criterion) {
    let s = two_frequencies();
    report("two frequencies", &s, 60.0);
    if let Ok(job) = Job::from_json(include_str!("../jobs/compound-eye-paper000.json"))
        && let Ok(planner) = Planner::new(&job)
    {
        let eye = PathSignal::from_points(planner.points().map_while(Result::ok));
        report(
            "compound eye (paper 000 job)",
            &eye,
            job.machine.spindle_rpm,
        );
    }
    let mut group = c.benchmark_group("split_1M");
    group.sample_size(10);
    group.throughput(Throughput::Elements(s.len() as u64));
    group.bench_function("spectrum", |b| {
        b.iter(|| black_box(amplitude_spectrum(&s, 60.0, 2048)))
    });
    group.bench_function("instantaneous_frequency", |b| {
        b.iter(|| black_box(instantaneous_frequency(&s, 60.0, 16)))
    });
    group.bench_function("auto_split_and_checks", |b| {
        b.iter(|| black_box(split(&s, &SplitSpec::Auto, 60.0, Some(&LIMITS))))
    });
    group.finish();
}

criterion_group!(benches, split_1m);
criterion_main!(benches);
