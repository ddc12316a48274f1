//! `spiralcam analyse`: the accuracy of the planned path, and its maps.

use crate::files::{OutputFile, Target, check_targets, write_file};
use crate::{Failure, bar, read_job, run_err};
use spiralcam::analysis::Analysis;
use spiralcam::analysis::linearization::{INTERVALS_PER_FEATURE, segment_error};
use spiralcam::field::{FieldError, short};
use spiralcam::parallel::workers;
use spiralcam::path::MAX_POINTS;
use spiralcam::plan::{PlanError, Planner};
use spiralcam::raster::Raster;
use spiralcam::report::duration;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The command's help.
pub const HELP: &str = "spiralcam analyse JOB.json [--report FILE] [--maps PREFIX] [--max-points N]
                         [--max-seconds S]

Plans the job and reports the accuracy of its path as JSON (standard output when --report
is not given): the linearization error between NC points, the predicted machined form, the
tool angles the surface needs and how far it is from a surface of revolution. --maps writes
PREFIX-linearization.csv, PREFIX-form.csv (x_mm,y_mm,error_um) and PREFIX-clearance.csv
(x_mm,y_mm,required_clearance_deg), 256 x 256 over the part.

The job is admitted first, as by plan: heights checked at probes along the path, at most
30 000 000 points walked (about half a minute on two cores for an asphere) unless
--max-points says otherwise, and at most 600 s of estimated time (the checks between two
points timed at places along the path) unless --max-seconds says otherwise.";

/// The most points `analyse` walks unless `--max-points` says otherwise: a 28.4 M-point
/// finishing path, about half a minute on two cores for an asphere (1 µs a point).
pub const DEFAULT_MAX_POINTS: u64 = 30_000_000;

/// The longest estimated analysis `analyse` starts unless `--max-seconds` says otherwise.
pub const DEFAULT_MAX_SECONDS: f64 = 600.0;

/// Samples per side of the maps `analyse --maps` writes.
const MAP_SIZE: usize = 256;

/// The maps: file suffix, column name.
const MAPS: [(&str, &str); 3] = [
    ("linearization", "error_um"),
    ("form", "error_um"),
    ("clearance", "required_clearance_deg"),
];

pub fn run(words: &[String]) -> Result<(), Failure> {
    let args = crate::args::parse(
        words,
        &["--report", "--maps", "--max-points", "--max-seconds"],
    )?;
    let max_points = args
        .positive("--max-points")?
        .map_or(DEFAULT_MAX_POINTS, |n| (n as u64).min(MAX_POINTS));
    let max_seconds = args
        .positive("--max-seconds")?
        .unwrap_or(DEFAULT_MAX_SECONDS);
    let map_path = |suffix: &str| {
        args.path("--maps").map(|prefix| {
            let mut p = prefix.as_os_str().to_owned();
            p.push(format!("-{suffix}.csv"));
            PathBuf::from(p)
        })
    };
    let mut targets: Vec<Target> = MAPS
        .iter()
        .filter_map(|(suffix, _)| {
            map_path(suffix).map(|path| Target {
                flag: "--maps",
                path,
            })
        })
        .collect();
    if let Some(p) = args.path("--report") {
        targets.push(Target {
            flag: "--report",
            path: p.to_path_buf(),
        });
    }
    check_targets(&targets, &[])?;
    let (job, inputs) = read_job(&args.job)?;
    check_targets(&targets, &inputs)?;
    let mut progress = bar::callback();
    let planner = Planner::with_progress(&job, &mut progress).map_err(run_err)?;
    admit(&planner, max_points, max_seconds).map_err(run_err)?;
    let analysis = Analysis::run(&planner, MAP_SIZE, &mut progress);
    bar::end();
    let analysis = analysis.map_err(run_err)?;
    let maps = [
        analysis.linearization_map(),
        &analysis.form_map(),
        analysis.clearance_map(),
    ];
    // Every map is written before any is renamed into place.
    let mut written = Vec::new();
    for ((suffix, column), map) in MAPS.iter().zip(maps) {
        if let Some(path) = map_path(suffix) {
            written.push(write_map(&path, map, column)?);
        }
    }
    for file in written {
        file.commit()?;
    }
    let json = analysis.to_json() + "\n";
    match args.path("--report") {
        Some(path) => write_file(path, json.as_bytes()),
        None => std::io::stdout()
            .write_all(json.as_bytes())
            .map_err(run_err),
    }
}

/// Segments of the path whose accuracy checks are timed for the estimate, spread in radius.
const TIMED_SEGMENTS: usize = 16;

const _: () = assert!(TIMED_SEGMENTS.is_power_of_two());

/// The most the timing of those segments takes, s (at least one is timed).
const TIMING_BUDGET_S: f64 = 2.0;

/// Admits the job as `plan` does before walking it ([`Planner::cost`]: the surface defined and
/// its heights finite and within reach at probes along the path), and refuses more than
/// `max_points` points or an estimated time above `max_seconds`, naming the feed that would do
/// (the time goes about as 1/f, as the points do). The time is the plan's per point, timed at
/// the probes, and the checks of a segment between two points, timed at [`TIMED_SEGMENTS`]
/// places ([`segment_seconds`]), on every core.
fn admit(planner: &Planner, max_points: u64, max_seconds: f64) -> Result<(), PlanError> {
    let start = Instant::now();
    let clock = move || start.elapsed().as_secs_f64();
    let cost = planner.cost(Some(&clock))?;
    let feed = planner.job().strategy.feed_mm_per_rev;
    let points = cost.points as f64;
    let refuse = |ratio: f64, what: String| -> Result<(), PlanError> {
        Err(FieldError::new(
            "strategy.feed_mm_per_rev",
            feed,
            format!(
                "{what}: a feed of at least {} mm/rev keeps it under",
                short(feed * ratio * (1.0 + 1e-6))
            ),
        )
        .into())
    };
    if cost.points > max_points {
        let what = format!(
            "gives about {} points; analyse walks at most {max_points} (--max-points raises it)",
            short(points)
        );
        return refuse(points / max_points as f64, what);
    }
    let per_point = cost.seconds.unwrap_or(0.0) / points.max(1.0);
    let (per_segment, timed) = segment_seconds(planner)?;
    let seconds = points * (per_point + per_segment / workers() as f64);
    if seconds > max_seconds {
        let per_segment = match per_segment {
            s if s >= 1.0 => duration(s),
            s => format!("{:.3} ms", s * 1e3),
        };
        let places = if timed == 1 { "place" } else { "places" };
        let what = format!(
            "gives about {} points, about {} to analyse on {} cores (the checks between two \
             points, {INTERVALS_PER_FEATURE} samples a feature length of {} mm or more, take \
             {per_segment} a segment on one core, timed at {timed} {places} along the path), \
             above the limit of {max_seconds} s (--max-seconds raises it)",
            short(points),
            duration(seconds),
            workers(),
            short(planner.surface().feature_length_mm()),
        );
        return refuse(seconds / max_seconds, what);
    }
    Ok(())
}

/// The mean time of the accuracy checks of one segment between two path points, s, and how many
/// segments were timed: those of up to [`TIMED_SEGMENTS`] probes ([`Planner::probe`]), visited
/// in an order that spreads them in radius, until [`TIMING_BUDGET_S`] has passed; each weighted
/// by the path's points per mm of radius there. A segment whose check fails is the analysis's
/// error, given at once.
fn segment_seconds(planner: &Planner) -> Result<(f64, usize), PlanError> {
    let probes = planner.probe(TIMED_SEGMENTS)?;
    let n = probes.len();
    let start = Instant::now();
    let (mut weighted, mut weights, mut timed) = (0.0, 0.0, 0);
    // The probes in bit-reversed order: the visits jump across the radius rather than walk it,
    // so a timing cut short still spans it.
    let bits = TIMED_SEGMENTS.trailing_zeros();
    let order = (0..TIMED_SEGMENTS).map(|i| i.reverse_bits() >> (usize::BITS - bits));
    for k in order.filter(|&k| k < n) {
        let [_, a, b] = &probes[k].points;
        let began = Instant::now();
        segment_error(planner, a, b)?;
        let w = probes[k].per_mm;
        weighted += began.elapsed().as_secs_f64() * w;
        weights += w;
        timed += 1;
        if start.elapsed().as_secs_f64() > TIMING_BUDGET_S {
            break;
        }
    }
    let mean = if weights > 0.0 {
        weighted / weights
    } else {
        0.0
    };
    Ok((mean, timed))
}

/// Writes the defined samples of `map` as `x_mm,y_mm,<value>` rows, not yet renamed.
pub fn write_map(path: &Path, map: &Raster, value: &str) -> Result<OutputFile, Failure> {
    let mut out = OutputFile::create(path)?;
    let mut write = || -> std::io::Result<()> {
        writeln!(out.writer, "x_mm,y_mm,{value}")?;
        for j in 0..map.size {
            for i in 0..map.size {
                let v = map.values[j * map.size + i];
                if !v.is_nan() {
                    let (x, y) = map.position(i, j);
                    writeln!(out.writer, "{x:.6},{y:.6},{v:.6}")?;
                }
            }
        }
        Ok(())
    };
    write().map_err(|e| Failure::Run(format!("{}: {e}", path.display())))?;
    Ok(out)
}
