//! `spiralcam plan`: admits the job, then streams its path into the files asked for.

use crate::files::{ChildOutputs, OutputFile, Target, check_targets, write_file};
use crate::{Failure, bar, read_job, run_err};
use spiralcam::nc::program::ChildFiles;
use spiralcam::plan::{Limits, Planner, Sinks};
use spiralcam::report::Outputs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The command's help.
pub const HELP: &str =
    "spiralcam plan JOB.json [--nc FILE] [--csv FILE] [--fts-csv FILE] [--fts-table FILE]
                        [--report FILE] [--max-output-gb G] [--max-points N] [--max-seconds S]

Plans the job and writes the files asked for: the NC program, the point table (CSV), the
fast tool servo's table (c_deg,x_mm,w_mm; split jobs only), its gridded table (W over
spindle angle x X as a PMAC 2-D compensation table, DEFINE COMP, and the same grid as CSV
beside it, FILE with the extension .csv; split jobs only; output.fts_grid sets its
tolerance, counts and motors) and the report (JSON; standard output when --report is not
given). With strategy.split or machine limits the report carries the spectrum, the split
and the axis checks, and with --fts-table the grid's size and interpolation error.

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
const FILES: [&str; 5] = ["--nc", "--csv", "--fts-csv", "--fts-table", "--report"];

/// What names the CSV beside the gridded table, in messages.
const GRID_CSV: &str = "--fts-table (its CSV)";

/// The writer of an output, as a sink.
fn writer(o: &mut OutputFile) -> &mut dyn Write {
    &mut o.writer
}

/// The CSV beside the gridded table `table`: its name with the extension `.csv`.
pub fn grid_csv_path(table: &Path) -> PathBuf {
    table.with_extension("csv")
}

pub fn run(words: &[String]) -> Result<(), Failure> {
    let args = crate::args::parse(
        words,
        &[
            "--nc",
            "--csv",
            "--fts-csv",
            "--fts-table",
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
    let mut targets: Vec<Target> = FILES
        .iter()
        .filter_map(|&flag| {
            args.path(flag).map(|p| Target {
                flag,
                path: p.to_path_buf(),
            })
        })
        .collect();
    let grid_csv = args.path("--fts-table").map(grid_csv_path);
    if let Some(path) = &grid_csv {
        targets.push(Target {
            flag: GRID_CSV,
            path: path.clone(),
        });
    }
    check_targets(&targets, &[])?;
    let (job, inputs) = read_job(&args.job)?;
    for flag in ["--fts-csv", "--fts-table"] {
        if args.path(flag).is_some() && job.strategy.split.is_none() {
            return Err(Failure::Usage(format!(
                "{flag} needs a split path: set strategy.split in the job"
            )));
        }
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
        fts_grid: args.path("--fts-table").is_some(),
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
    let mut grid = create("--fts-table")?;
    let mut grid_csv = grid_csv.as_deref().map(OutputFile::create).transpose()?;
    let sinks = Sinks {
        nc: nc.as_mut().map(writer),
        csv: csv.as_mut().map(writer),
        display: None,
        z_slide: None,
        child_stem: children.as_ref().map(|c| c.stem.clone()),
        children: children.as_mut().map(|c| c as &mut dyn ChildFiles),
        fts_table: fts.as_mut().map(writer),
        fts_grid: grid.as_mut().map(writer),
        fts_grid_csv: grid_csv.as_mut().map(writer),
    };
    let planned = planner.run_with_dynamics(sinks, &mut progress);
    bar::end();
    let mut report = planned.map_err(run_err)?;
    cost.seconds = cost.seconds.map(|s| (s * 1e3).round() / 1e3);
    cost.dynamics_seconds = cost.dynamics_seconds.map(|s| (s * 1e3).round() / 1e3);
    report.estimate = Some(cost);
    if let Some(children) = children {
        children.commit()?;
    }
    for output in [nc, csv, fts, grid, grid_csv].into_iter().flatten() {
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
