//! The hybrid FTS/SSS pipeline end to end (`Planner::run_with_dynamics`): a split program's
//! Z + W equals the single-channel program's Z digit for digit with the same X and C, the
//! servo's table repeats the program's C, X and W; a tilted flat is cut by the slide alone
//! (W ≡ 0); machine limits alone check the axes and leave the program byte-identical; an
//! infeasible split is reported (a warning naming the limit and the speed that would do, which
//! re-planned at that speed is feasible); a split the machine cannot make is refused naming the
//! field; and paper 000's
//! two-frequency case on the compound eye, each frequency put on its axis.

mod common;

use common::{coarse_grid_fts, example_job};
use spiralcam::dynamics::path_signal::PathSignal;
use spiralcam::dynamics::split::{Limit, Verdict};
use spiralcam::dynamics::{CALIBRATION_POINTS, Dynamics, grid_samples};
use spiralcam::job::Job;
use spiralcam::job::SplitSpec;
use spiralcam::job::machine::presets;
use spiralcam::plan::{Limits, Planner, Sinks};
use spiralcam::report::Outputs;
use spiralcam::report::Report;
use std::f64::consts::TAU;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicU64, Ordering};

/// Plans `job` with its dynamics; returns the report, the program and the servo's table.
fn plan(job: &Job) -> (Report, String, String) {
    let planner = Planner::new(job).unwrap_or_else(|e| panic!("{}: {e}", job.name));
    let (mut nc, mut table) = (Vec::new(), Vec::new());
    let sinks = Sinks {
        nc: Some(&mut nc),
        fts_table: Some(&mut table),
        ..Default::default()
    };
    let report = planner
        .run_with_dynamics(sinks, &mut |_| ControlFlow::Continue(()))
        .unwrap_or_else(|e| panic!("{}: {e}", job.name));
    let text = |b: Vec<u8>| String::from_utf8(b).unwrap();
    (report, text(nc), text(table))
}

/// Why `job` cannot be planned with its dynamics (it is read fine).
fn dynamics_error(job: &Job) -> String {
    Planner::new(job)
        .unwrap()
        .run_with_dynamics(Sinks::default(), &mut |_| ControlFlow::Continue(()))
        .unwrap_err()
        .to_string()
}

/// The integer value of a word (e.g. `Z-0.001234` at 6 decimals → −1234) in a block.
fn word(line: &str, letter: char) -> Option<i64> {
    let w = line.split_whitespace().find(|w| w.starts_with(letter))?;
    Some(w[1..].replace('.', "").parse().unwrap())
}

/// The feed blocks (`G1` with C) of a program.
fn blocks(nc: &str) -> Vec<&str> {
    nc.lines()
        .filter(|l| l.starts_with("G1") && l.contains('C'))
        .collect()
}

#[test]
fn a_split_program_adds_up_to_the_single_channel_program() {
    let job = coarse_grid_fts();
    let (report, nc, table) = plan(&job);
    let mut plain = job.clone();
    plain.strategy.split = None;
    let (_, single, empty) = plan(&plain);
    assert_eq!(empty, "", "no table without a split");
    let (split, single) = (blocks(&nc), blocks(&single));
    assert_eq!(split.len() as u64, report.points - 1);
    assert_eq!(split.len(), single.len());
    let mut moving = 0;
    // ISO's servo word is Y (a linear axis LinuxCNC reads).
    let servo = job.output.conventions().fts_word as char;
    for (s, p) in split.iter().zip(&single) {
        let (z, w) = (word(s, 'Z').unwrap(), word(s, servo).unwrap());
        assert_eq!(z + w, word(p, 'Z').unwrap(), "{s} | {p}");
        assert_eq!((word(s, 'X'), word(s, 'C')), (word(p, 'X'), word(p, 'C')));
        moving += usize::from(w != 0);
    }
    assert!(moving > split.len() / 2, "the servo carries the grid");
    // The table: a header, the plunge's point 0, then one row per block with its C, X and W.
    let rows: Vec<&str> = table.lines().collect();
    assert_eq!(rows[0], "c_deg,x_mm,w_mm");
    assert_eq!(rows.len() as u64, report.points + 1);
    for (row, s) in rows[2..].iter().zip(&split) {
        let v: Vec<i64> = row
            .split(',')
            .map(|f| f.replace('.', "").parse().unwrap())
            .collect();
        assert_eq!(
            v,
            [
                word(s, 'C').unwrap(),
                word(s, 'X').unwrap(),
                word(s, servo).unwrap()
            ]
        );
    }
    let dynamics = report.dynamics.expect("dynamics in the report");
    let split = dynamics.split.expect("the split in the report");
    assert!(matches!(
        split.verdict,
        Verdict::Feasible {
            slide_alone: false,
            ..
        }
    ));
    // The grid (2 µm amplitude, 4 µm PV) goes to the servo.
    assert!(
        (split.w_fts_pv_um - 4.0).abs() < 0.05,
        "{}",
        split.w_fts_pv_um
    );
    assert!(dynamics.axes.within_limits);
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    let profile = dynamics.channels.expect("channels for the page");
    assert!(profile.rho_mm.len() <= spiralcam::dynamics::PROFILE_BUCKETS);
    let swing = profile.w_max_um.iter().fold(0.0f64, |a, &b| a.max(b));
    assert!((swing - 2.0).abs() < 0.05, "{swing}");
}

#[test]
fn a_tilted_flat_is_cut_by_the_slide_alone() {
    let mut job = example_job("tilted-flat.json");
    job.machine = presets()[2].machine(job.machine.spindle_rpm);
    job.strategy.split = Some(SplitSpec::Auto);
    job.output = Default::default();
    let (report, nc, _) = plan(&job);
    let blocks = blocks(&nc);
    assert!(!blocks.is_empty());
    let servo = job.output.conventions().fts_word as char;
    assert!(blocks.iter().all(|b| word(b, servo) == Some(0)), "W ≡ 0");
    let split = report.dynamics.unwrap().split.unwrap();
    assert!(matches!(
        split.verdict,
        Verdict::Feasible {
            slide_alone: true,
            ..
        }
    ));
    assert_eq!(split.w_fts_pv_um, 0.0);
}

#[test]
fn machine_limits_alone_check_the_axes_and_leave_the_program_unchanged() {
    let plain = example_job("lens-array-paper004.json");
    let mut limited = plain.clone();
    limited.machine = presets()[0].machine(plain.machine.spindle_rpm);
    let (with, nc_with, _) = plan(&limited);
    let (without, nc_without, _) = plan(&plain);
    assert_eq!(nc_with, nc_without);
    assert!(without.dynamics.is_none() && !without.to_json().contains("dynamics"));
    let axes = with.dynamics.expect("axis checks").axes;
    assert_eq!(axes.points, with.points);
    assert!((axes.cycle_time_s - with.cycle_time_s).abs() <= 1e-12 * with.cycle_time_s);
}

/// A 1 µm stroke forces the cutoff up into the grid's band, above the slide's 20 Hz: the split
/// is infeasible on the slide's bandwidth, the warning says so with the speed that would do,
/// and re-planned at that speed (rounded down by the splitter) the split is feasible.
#[test]
fn an_infeasible_split_is_reported_with_the_speed_that_would_do() {
    let mut job = coarse_grid_fts();
    if let Some(fts) = job.machine.fts.as_mut() {
        fts.stroke_um = 1.0;
    }
    let (report, _, _) = plan(&job);
    let split = report.dynamics.unwrap().split.unwrap();
    let Verdict::Infeasible {
        conflicts,
        feasible_spindle_rpm: Some(rpm),
        ..
    } = split.verdict
    else {
        panic!("{:?}", split.verdict)
    };
    let cutoff = split.cutoff_hz.unwrap();
    assert!(cutoff > 20.0, "{cutoff}");
    assert!(conflicts.iter().any(|c| c.limit == Limit::SlideBandwidthHz));
    // The splitter offers the larger of the speeds for this cutoff (at most 300·20/cutoff, the
    // slide's bandwidth) and for the slide alone (here the grid's highest frequency, ~170 Hz,
    // against 20 Hz): so at least the first, rounded down to 3 digits, and below 300.
    assert!(
        rpm >= 0.99 * 300.0 * 20.0 / cutoff && rpm < 300.0,
        "{rpm} at cutoff {cutoff}"
    );
    let warning = report
        .warnings
        .iter()
        .find(|w| w.starts_with("the split exceeds the machine"))
        .expect("a warning");
    assert!(
        warning.contains("machine.z_slide.bandwidth_hz"),
        "{warning}"
    );
    assert!(
        warning.contains(&format!("feasible at {rpm} rpm")),
        "{warning}"
    );
    job.machine.spindle_rpm = rpm;
    let (again, _, _) = plan(&job);
    let split = again.dynamics.unwrap().split.unwrap();
    assert!(
        matches!(split.verdict, Verdict::Feasible { .. }),
        "{:?}",
        split.verdict
    );
}

#[test]
fn a_split_the_machine_cannot_make_is_refused_naming_the_field() {
    type Change = fn(&mut Job);
    let cases: [(Change, &str); 3] = [
        (
            |j| j.machine.fts = None,
            "strategy.split = set: needs a fast tool servo: machine.fts",
        ),
        (
            |j| j.machine.z_slide = None,
            "strategy.split.type = auto: needs the Z slide's limits: machine.z_slide",
        ),
        (
            |j| j.strategy.split = Some(SplitSpec::LowPass { cutoff_hz: -2.0 }),
            "strategy.split.cutoff_hz = -2: must be a finite number > 0",
        ),
    ];
    for (change, message) in cases {
        let mut job = coarse_grid_fts();
        change(&mut job);
        assert_eq!(Planner::new(&job).unwrap_err().to_string(), message);
    }
    // Above the path's Nyquist frequency (256 cycles/rev at 300 rpm: 1280 Hz) on the path.
    let mut job = coarse_grid_fts();
    job.strategy.split = Some(SplitSpec::LowPass { cutoff_hz: 2000.0 });
    let e = dynamics_error(&job);
    assert!(
        e.starts_with("strategy.split.cutoff_hz = 2000: must be a finite number in (0, 1280] Hz"),
        "{e}"
    );
}

/// The paper 000 compound eye (7 elements of 17 lenslets; ours, its dimensions did not survive)
/// at 60.98 rpm, where its six-fold element ring is paper 000's 6.098 Hz: the spectrum finds
/// the ring (6 cycles/rev) and the lenslets (42 cycles/rev, seven lenslets crossed per element;
/// the paper's 47.03 Hz is 7.71 per element), and a low-pass at 20 Hz puts the ring on the
/// slide and the lenslets on the servo: each channel keeps its own peak within the filter's
/// response (H = 1/(1 + (f/20)⁸): 0.99998 at 6.1 Hz, 0.0024 at 42.7 Hz) and loses the other's.
#[test]
fn the_compound_eye_splits_its_two_frequencies_onto_the_right_axes() {
    use spiralcam::dynamics::path_signal::PathSignal;
    use spiralcam::dynamics::spectrum::amplitude_spectrum;
    // The whole spectrum, undecimated, of one channel along the path.
    let channel_of = |points: &[spiralcam::path::PathPoint], v: &Vec<f64>| {
        let mut s = PathSignal::from_points(points.iter().copied());
        s.z_mm.clone_from(v);
        amplitude_spectrum(&s, 60.98, 1 << 20)
    };
    let mut job = example_job("compound-eye-paper000.json");
    job.machine = presets()[1].machine(60.98);
    job.strategy.feed_mm_per_rev = 0.05;
    job.strategy.sampling = spiralcam::job::Sampling::ConstantAngle {
        points_per_rev: 512,
    };
    job.strategy.split = Some(SplitSpec::LowPass { cutoff_hz: 20.0 });
    let planner = Planner::new(&job).unwrap();
    let points: Vec<_> = planner.points().map(|p| p.unwrap()).collect();
    let d = Dynamics::of_points(&job, &points).unwrap();
    let hz = |cpr: f64| cpr * 60.98 / 60.0;
    // The largest bin within 0.3 Hz (the same bins in every channel: same scalloping).
    let peak_near = |spectrum: &spiralcam::dynamics::spectrum::Spectrum, f: f64| {
        spectrum
            .freq_hz
            .iter()
            .zip(&spectrum.amplitude_um)
            .filter(|(g, _)| (*g - f).abs() < 0.3)
            .map(|(_, a)| *a)
            .fold(0.0, f64::max)
    };
    let whole = &channel_of(&points, &points.iter().map(|p| p.z).collect());
    let (ring, lenslets) = (peak_near(whole, hz(6.0)), peak_near(whole, hz(42.0)));
    assert!(
        ring > 1.0 && lenslets > 0.1,
        "ring {ring} µm, lenslets {lenslets} µm"
    );
    let z = channel_of(&points, d.z_slide_mm.as_ref().unwrap());
    let w = channel_of(&points, d.w_fts_mm.as_ref().unwrap());
    assert!((peak_near(&z, hz(6.0)) - ring).abs() < 0.01 * ring);
    assert!(peak_near(&z, hz(42.0)) < 0.01 * lenslets);
    assert!((peak_near(&w, hz(42.0)) - lenslets).abs() < 0.01 * lenslets);
    assert!(peak_near(&w, hz(6.0)) < 0.01 * ring);
}

/// The dynamics of a constant-angle path with one-way compensation hold its heights alone,
/// the angles and radii computed from the index being the planned ones to the bit
/// (`PathSignal::for_spiral`), and find the same as with every column held.
#[test]
fn the_dynamics_of_a_constant_angle_path_hold_its_heights_alone_and_find_the_same() {
    let job = coarse_grid_fts();
    let planner = Planner::new(&job).unwrap();
    let points: Vec<_> = planner.points().map(|p| p.unwrap()).collect();
    let mut indexed = PathSignal::for_spiral(planner.path().spiral(), points.len());
    points.iter().for_each(|p| indexed.push(p));
    assert!(indexed.is_indexed());
    assert_eq!(
        PathSignal::bytes_per_point(planner.path().spiral(), true),
        8
    );
    assert_eq!(
        PathSignal::bytes_per_point(planner.path().spiral(), false),
        24
    );
    for (i, p) in points.iter().enumerate() {
        let got = [indexed.theta(i), indexed.rho(i)].map(f64::to_bits);
        assert_eq!(got, [p.theta, p.rho].map(f64::to_bits), "point {i}");
    }
    let run = Dynamics::run(planner.path(), &mut |_| ControlFlow::Continue(())).unwrap();
    assert_eq!(run, Dynamics::of_points(&job, &points).unwrap());
}

/// The dynamics of HCAA and constant-arc paths with one-way compensation hold each point's φ
/// on its spiral beside its height, the angles and radii computed from φ being the planned ones
/// to the bit (`PathSignal::for_spiral`), and find the same as with every column held; with
/// two-way compensation (the points moved off the spiral) every column is held.
#[test]
fn the_dynamics_of_a_walked_path_hold_its_phi_and_heights_and_find_the_same() {
    use spiralcam::job::{Compensation, Sampling};
    let hcaa = Sampling::Hcaa {
        pv_tolerance_um: 0.1,
    };
    let arc = Sampling::ConstantArc {
        arc_length_mm: 0.05,
        max_angle_step_deg: 10.0,
    };
    for (sampling, compensation) in [
        (hcaa, Compensation::OneWay),
        (arc.clone(), Compensation::OneWay),
        (arc, Compensation::TwoWay),
    ] {
        let mut job = coarse_grid_fts();
        job.strategy.sampling = sampling.clone();
        job.strategy.compensation = compensation;
        let planner = Planner::new(&job).unwrap();
        let points: Vec<_> = planner.points().map(|p| p.unwrap()).collect();
        let mut walked = PathSignal::for_spiral(planner.path().spiral(), points.len());
        points.iter().for_each(|p| walked.push(p));
        let one_way = compensation == Compensation::OneWay;
        assert_eq!(walked.is_walked(), one_way, "{sampling:?} {compensation:?}");
        let spiral = planner.path().spiral();
        assert_eq!(
            PathSignal::bytes_per_point(spiral, one_way),
            if one_way { 16 } else { 24 }
        );
        for (i, p) in points.iter().enumerate() {
            let got = [walked.theta(i), walked.rho(i), walked.z_mm[i]].map(f64::to_bits);
            assert_eq!(got, [p.theta, p.rho, p.z].map(f64::to_bits), "point {i}");
        }
        let run = Dynamics::run(planner.path(), &mut |_| ControlFlow::Continue(())).unwrap();
        assert_eq!(run, Dynamics::of_points(&job, &points).unwrap());
    }
}

#[test]
fn the_dynamics_refuse_a_path_too_long_to_hold() {
    let mut job = coarse_grid_fts();
    job.strategy.feed_mm_per_rev = 0.00005; // 80 000 revolutions of 512 points
    let e = dynamics_error(&job);
    let limit = spiralcam::dynamics::MAX_POINTS;
    assert!(
        e.starts_with(&format!(
            "strategy.sampling = 40960001 points: at most {limit} points"
        )),
        "{e}"
    );
}

/// A 28.4 M-point finishing path with a split is admitted on the command line's limits, and
/// refused where fewer points are allowed (the page's), naming the feed that would do.
#[test]
fn a_finishing_path_of_28_4_m_points_is_admitted_with_its_dynamics() {
    let mut job = coarse_grid_fts();
    // 4 mm of radius at 512 points a revolution: 28 400 001 points at 4/55 468.75 mm/rev.
    job.strategy.feed_mm_per_rev = 4.0 / 55_468.75;
    let planner = Planner::new(&job).unwrap();
    let cost = planner.cost(None).unwrap();
    assert_eq!((cost.points, cost.passes), (28_400_001, 2));
    let outputs = Outputs {
        nc: true,
        ..Outputs::default()
    };
    let feed = job.strategy.feed_mm_per_rev;
    Limits::default().check(&cost, outputs, feed).unwrap();
    let page = Limits {
        max_dynamics_points: 17_000_000,
        ..Limits::default()
    };
    let e = page.check(&cost, outputs, feed).unwrap_err().to_string();
    assert!(
        e.contains("hold the path in memory and take at most 17000000"),
        "{e}"
    );
    // The feed that would do: 28 400 001 / 17 000 000 of this one, rounded up.
    assert_feed_named(&e, feed * 28_400_001.0 / 17_000_000.0);
}

/// The refusal `e` names a feed of at least `least`, rounded up to a few digits.
fn assert_feed_named(e: &str, least: f64) {
    let said: f64 = e
        .split("a feed of at least ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no feed named: {e}"));
    assert!(least <= said && said <= least * (1.0 + 1e-5), "{e}");
}

/// A path whose densest turn is denser than the others (constant arc: the rim's) has more
/// samples on the dynamics' grid than points: the estimate counts them (within 2 % of the grid
/// the dynamics compute on), its memory goes with them (beside 16 bytes a point: the heights
/// and each point's φ), and a memory bound refuses on them,
/// naming a feed that would do; the points alone would have been admitted.
#[test]
fn the_dynamics_memory_goes_with_the_samples_of_their_grid() {
    let mut job = coarse_grid_fts();
    job.strategy.sampling = spiralcam::job::Sampling::ConstantArc {
        arc_length_mm: 0.05,
        max_angle_step_deg: 10.0,
    };
    let planner = Planner::new(&job).unwrap();
    let cost = planner.cost(None).unwrap();
    let points: Vec<_> = planner.points().map(|p| p.unwrap()).collect();
    let grid = PathSignal::from_points(points.iter().copied())
        .uniform()
        .unwrap()
        .len() as f64;
    let samples = cost.dynamics_samples.unwrap() as f64;
    assert!(samples > 1.5 * cost.points as f64, "{cost:?}");
    assert!(
        (samples - grid).abs() <= 0.02 * grid,
        "{samples} against {grid}"
    );
    let held = cost.dynamics_memory_bytes.unwrap();
    // The path's heights and each point's φ on its spiral (one-way compensation), and the
    // low-pass's records of the automatic split: the grid extended by 16 turns at either end
    // at the grid's rate.
    let columns = 16 * cost.points;
    let turns = planner.spiral().revolutions();
    let records = spiralcam::dynamics::record_samples(samples, turns, true);
    let per_rev = (grid - 1.0) / turns;
    assert!(
        ((records - samples) / (32.0 * per_rev) - 1.0).abs() < 0.02,
        "{records} {samples} {per_rev}"
    );
    let per_sample = spiralcam::dynamics::bytes_per_sample(records) as f64;
    let grid_bytes = (held - columns) as f64;
    assert!(
        grid_bytes >= per_sample * (records - 1.0) && grid_bytes <= per_sample * records,
        "{cost:?}"
    );
    // A bound between the points' share and the whole: refused on the grid.
    let outputs = Outputs {
        nc: true,
        ..Outputs::default()
    };
    let feed = job.strategy.feed_mm_per_rev;
    let points_only = spiralcam::dynamics::memory_bytes(cost.points, 0.0, 16);
    let bound = Limits {
        max_dynamics_bytes: Some((points_only + held) / 2),
        ..Limits::default()
    };
    let e = bound.check(&cost, outputs, feed).unwrap_err().to_string();
    assert!(
        e.contains(" samples, which the machine dynamics hold in memory"),
        "{e}"
    );
    assert_feed_named(&e, feed * held as f64 / ((points_only + held) / 2) as f64);
    let roomy = Limits {
        max_dynamics_bytes: Some(held),
        ..Limits::default()
    };
    roomy.check(&cost, outputs, feed).unwrap();
}

/// On a path of few turns the low-pass's records, the grid extended by 16 turns at either
/// end, outweigh the grid: 4 turns of 512 points are 2 049 samples on the grid and 18 433 in
/// each of the low-pass's records, and the estimate holds them (it held the grid alone, a
/// ninth of them, before).
#[test]
fn the_dynamics_memory_counts_the_low_pass_records_on_a_path_of_few_turns() {
    let mut job = coarse_grid_fts();
    job.strategy.feed_mm_per_rev = 1.0;
    let cost = Planner::new(&job).unwrap().cost(None).unwrap();
    let grid = cost.dynamics_samples.unwrap() as f64;
    assert_eq!(grid, 4.0 * 512.0 + 1.0);
    let records = grid + 32.0 * 512.0;
    let per_sample = spiralcam::dynamics::bytes_per_sample(records);
    let held = cost.dynamics_memory_bytes.unwrap();
    assert_eq!(held, 8 * cost.points + per_sample * records as u64);
    // Without a low-pass (the symmetric split) the grid alone.
    job.strategy.split = Some(spiralcam::job::SplitSpec::Symmetric);
    let cost = Planner::new(&job).unwrap().cost(None).unwrap();
    let per_sample = spiralcam::dynamics::bytes_per_sample(grid);
    assert_eq!(
        cost.dynamics_memory_bytes.unwrap(),
        8 * cost.points + per_sample * grid as u64
    );
}

/// The dynamics' grid as the estimate counts it ([`grid_samples`]) against the grid they
/// compute on (`PathSignal::uniform`): a constant-angle path (exactly), and a constant-arc
/// one, densest at the rim (within 1 %: the estimate takes the rim's step, the grid the mean
/// of the first turn).
#[test]
fn the_dynamics_estimate_counts_the_samples_of_their_grid() {
    let signal = |angles: Vec<f64>| {
        let n = angles.len();
        PathSignal::from_columns(angles, vec![1.0; n], vec![0.0; n])
    };
    let steady = signal((0..=50_000).map(|i| TAU * i as f64 / 500.0).collect());
    let grid = steady.uniform().unwrap().z_mm.len() as f64;
    assert_eq!(grid, grid_samples(50_001, 100.0, 500.0));
    // 0.01 mm arcs from 5 mm inwards at 0.05 mm a turn: 3 142 points on the outer turn.
    let (feed, arc) = (0.05, 0.01);
    let mut angles = vec![0.0];
    loop {
        let theta = *angles.last().unwrap();
        let rho = 5.0 - feed * theta / TAU;
        if rho < 0.5 {
            break;
        }
        angles.push(theta + (arc / rho).min(1f64.to_radians()));
    }
    let (n, turns) = (angles.len(), angles.last().unwrap() / TAU);
    let grid = signal(angles).uniform().unwrap().z_mm.len() as f64;
    let counted = grid_samples(n as u64, turns, TAU * 5.0 / arc);
    assert!((counted / grid - 1.0).abs() < 0.01, "{counted} vs {grid}");
    assert!(
        grid > 1.5 * n as f64,
        "the grid is denser than the path: {grid} vs {n}"
    );
}

/// The estimate's time includes the dynamics', timed by the clock on the calibration path and
/// scaled by the grid's samples: with a clock that moves 1 µs at each reading, each timed run
/// takes one tick, so the dynamics take 1.3 µs / 32 768 a sample of their grid (1.3 for a long
/// path's memory).
#[test]
fn the_estimate_times_the_dynamics_on_this_machine() {
    let readings = AtomicU64::new(0);
    let clock = move || (readings.fetch_add(1, Ordering::Relaxed) + 1) as f64 * 1e-6;
    let job = coarse_grid_fts();
    let planner = Planner::new(&job).unwrap();
    let cost = planner.cost(Some(&clock)).unwrap();
    let samples = grid_samples(cost.points, 4.0 / 0.02, 512.0);
    let dynamics = cost.dynamics_seconds.unwrap();
    let want = samples * 1.3e-6 / CALIBRATION_POINTS as f64;
    assert!(
        (dynamics / want - 1.0).abs() < 0.005,
        "{dynamics} vs {want}"
    );
    assert!(cost.seconds.unwrap() > dynamics);
    // Not estimated without a clock (the page), nor without the dynamics.
    assert_eq!(planner.cost(None).unwrap().dynamics_seconds, None);
    let mut plain = job.clone();
    plain.strategy.split = None;
    plain.machine = spiralcam::job::MachineSpec::spindle_only(job.machine.spindle_rpm);
    let cost = Planner::new(&plain).unwrap().cost(Some(&clock)).unwrap();
    assert_eq!((cost.passes, cost.dynamics_seconds), (1, None));
}

/// The slides' bandwidths: a tilted flat asks Z for one cycle per revolution (n/60 Hz; its
/// amplitude grows along the path, so the Hann spectrum's main lobe spreads it over a few bins
/// of 1/revolutions of a cycle: within 4 bins, 4 % here) and X for nothing (X is linear in the
/// angle); above the Z slide's 20 Hz the report warns with the speed that would do, 20·60 rpm
/// within the same 4 %.
#[test]
fn the_slides_bandwidths_are_checked() {
    let mut job = example_job("tilted-flat.json");
    job.strategy.feed_mm_per_rev = 0.1; // 100 revolutions
    for (rpm, within) in [(500.0, true), (1500.0, false)] {
        job.machine = presets()[0].machine(rpm);
        let (report, _, _) = plan(&job);
        let b = report.dynamics.unwrap().bandwidth;
        let needed = b.z.needed_hz.unwrap();
        let bins = 4.0 * rpm / 60.0 / 100.0;
        assert!(
            (needed - rpm / 60.0).abs() <= bins,
            "{rpm} rpm: Z needs {needed} Hz"
        );
        assert_eq!(b.z.limit_hz, Some(20.0));
        assert_eq!(b.z.within_limit, within);
        assert_eq!(b.x.needed_hz, Some(0.0), "X is linear in the angle");
        let warning = report.warnings.iter().find(|w| w.contains("bandwidth_hz"));
        assert_eq!(warning.is_none(), within, "{:?}", report.warnings);
        if let Some(w) = warning {
            let speed = 20.0 / needed * rpm;
            assert!(w.contains(&format!("{speed:.1} rpm or less")), "{w}");
            assert!((speed - 1200.0).abs() <= 0.04 * 1200.0, "{speed}");
        }
    }
}
