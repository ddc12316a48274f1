//! `spiralcam plan`: admits the job, then streams its path into the files asked for.

use crate::files::{ChildOutputs, OutputFile, Target, check_targets, write_file};
use crate::{Failure, bar, read_job, run_err};
use spiralcam::nc::program::ChildFiles;
use spiralcam::plan::{Limits, Planner, Sinks};
use spiralcam::report::Outputs;
use std::io::Write;
use std::time::Instant;

/// The command's help.
pub const HELP: &str =
    "spiralcam plan JOB.json [--nc FILE] [--csv FILE] [--fts-csv FILE] [--report FILE]
                        [--max-output-gb G] [--max-points N] [--max-seconds S]

Plans the job and writes the files asked for: the NC program, the point table (CSV), the
fast tool servo's table (c_deg,x_mm,w_mm; split jobs only) and the report (JSON; standard
output when --report is not given). With strategy.split or machine limits the report
carries the spectrum, the split and the axis checks.

Before any point is computed the job is admitted: its points, the size of each file and the
time are estimated and printed on standard error, and a job beyond the limits is refused
with the field to change:
  --max-output-gb G   the files written together, at most G GB (default 4)
  --max-points N      at most N points (default and largest 1e9)
  --max-seconds S     at most S seconds estimated (default: no limit)

Every output is checked first (not a directory, not read-only, not an input, all
different), written under a temporary name beside it and renamed when complete: a failed or
interrupted run (Ctrl-C) leaves nothing behind. Exit status: 0 done, 1 the job or a file is
wrong, 2 the command line is wrong, 130 interrupted.";

/// The options naming files, in the order they are written.
const FILES: [&str; 4] = ["--nc", "--csv", "--fts-csv", "--report"];

pub fn run(words: &[String]) -> Result<(), Failure> {
    let args = crate::args::parse(
        words,
        &[
            "--nc",
            "--csv",
            "--fts-csv",
            "--report",
            "--max-output-gb",
            "--max-points",
            "--max-seconds",
        ],
    )?;
    let mut limits = Limits::default();
    if let Some(gb) = args.positive("--max-output-gb")? {
        limits.max_output_bytes = (gb * 1e9) as u64;
    }
    if let Some(n) = args.positive("--max-points")? {
        limits.max_points = (n as u64).min(limits.max_points);
    }
    limits.max_seconds = args.positive("--max-seconds")?;
    let targets: Vec<Target> = FILES
        .iter()
        .filter_map(|&flag| {
            args.path(flag).map(|p| Target {
                flag,
                path: p.to_path_buf(),
            })
        })
        .collect();
    check_targets(&targets, &[])?;
    let (job, inputs) = read_job(&args.job)?;
    if args.path("--fts-csv").is_some() && job.strategy.split.is_none() {
        return Err(Failure::Usage(
            "--fts-csv needs a split path: set strategy.split in the job".into(),
        ));
    }
    check_targets(&targets, &inputs)?;
    let mut progress = bar::callback();
    let planner = Planner::with_progress(&job, &mut progress).map_err(run_err)?;
    let start = Instant::now();
    let clock = move || start.elapsed().as_secs_f64();
    let mut cost = planner.cost(Some(&clock)).map_err(run_err)?;
    let outputs = Outputs {
        nc: args.path("--nc").is_some(),
        csv: args.path("--csv").is_some(),
        fts_table: args.path("--fts-csv").is_some(),
    };
    eprintln!("spiralcam: {}", cost.summary(outputs));
    limits
        .check(&cost, outputs, job.strategy.feed_mm_per_rev)
        .map_err(run_err)?;
    let create = |flag: &str| args.path(flag).map(OutputFile::create).transpose();
    let (mut nc, mut csv, mut fts) = (create("--nc")?, create("--csv")?, create("--fts-csv")?);
    let mut children = args
        .path("--nc")
        .map(|main| ChildOutputs::beside(main, inputs.clone()));
    let sinks = Sinks {
        nc: nc.as_mut().map(|o| &mut o.writer as &mut dyn Write),
        csv: csv.as_mut().map(|o| &mut o.writer as &mut dyn Write),
        display: None,
        z_slide: None,
        fts_table: fts.as_mut().map(|o| &mut o.writer as &mut dyn Write),
        child_stem: children.as_ref().map(|c| c.stem.clone()),
        children: children.as_mut().map(|c| c as &mut dyn ChildFiles),
    };
    let planned = planner.run_with_dynamics(sinks, &mut progress);
    bar::end();
    let mut report = planned.map_err(run_err)?;
    cost.seconds = cost.seconds.map(|s| (s * 1e3).round() / 1e3);
    report.estimate = Some(cost);
    if let Some(children) = children {
        children.commit()?;
    }
    for output in [nc, csv, fts].into_iter().flatten() {
        output.commit()?;
    }
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    let json = report.to_json() + "\n";
    match args.path("--report") {
        Some(path) => write_file(path, json.as_bytes()),
        None => std::io::stdout()
            .write_all(json.as_bytes())
            .map_err(run_err),
    }
}
