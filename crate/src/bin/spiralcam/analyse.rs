//! `spiralcam analyse`: the accuracy of the planned path, and its maps.

use crate::files::{OutputFile, Target, check_targets, write_file};
use crate::{Failure, bar, read_job, run_err};
use spiralcam::analysis::Analysis;
use spiralcam::path::MAX_POINTS;
use spiralcam::plan::{AnalysisLimits, Planner};
use spiralcam::raster::Raster;
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
    let defaults = AnalysisLimits::default();
    let limits = AnalysisLimits {
        max_points: args
            .positive("--max-points")?
            .map_or(defaults.max_points, |n| (n as u64).min(MAX_POINTS)),
        max_seconds: args
            .positive("--max-seconds")?
            .unwrap_or(defaults.max_seconds),
    };
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
    let start = Instant::now();
    planner
        .admit_analysis(limits, &|| start.elapsed().as_secs_f64())
        .map_err(run_err)?;
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
