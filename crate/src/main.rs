//! The spiralcam command-line tool.
//!
//! ```text
//! spiralcam plan JOB.json [--nc FILE] [--csv FILE] [--fts-csv FILE] [--report FILE]
//! spiralcam analyse JOB.json [--report FILE] [--maps PREFIX]
//! spiralcam sag JOB.json --at POINTS.csv
//! ```
//!
//! `plan` streams the path into the files asked for (each written to `FILE.partial` and renamed
//! when complete, so a failed run never leaves a truncated program) and prints the report as JSON
//! on standard output unless `--report` names a file. `analyse` plans the job and reports its
//! accuracy ([`spiralcam::analysis`]: linearization error, predicted form, tool angles) as JSON,
//! and with `--maps` writes its maps as `PREFIX-linearization.csv`, `PREFIX-form.csv`
//! (`x_mm,y_mm,error_um`) and `PREFIX-clearance.csv` (`x_mm,y_mm,required_clearance_deg`). `sag`
//! prints sag, gradient and second derivatives of the job's surface at each `x_mm,y_mm` row of a
//! CSV file. Data files a job names by path (scattered points, STEP files) are read relative to the
//! job file.

use spiralcam::analysis::Analysis;
use spiralcam::display::DisplayPath;
use spiralcam::job::Job;
use spiralcam::plan::{Planner, Sinks};
use spiralcam::progress::Progress;
use spiralcam::raster::Raster;
use std::fs::File;
use std::io::{BufWriter, IsTerminal, Write};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const USAGE: &str = "usage:
  spiralcam plan JOB.json [--nc FILE] [--csv FILE] [--fts-csv FILE] [--report FILE]
      plan the job; write the NC program, the point table (CSV), the fast tool servo's
      table (c_deg,x_mm,w_mm; split jobs) and the report (JSON, standard output when
      --report is not given); with strategy.split or machine limits the report carries
      the spectrum, the split and the axis checks
  spiralcam analyse JOB.json [--report FILE] [--maps PREFIX]
      the accuracy of the planned path: linearization error between NC points, the
      predicted machined form and the tool angles needed (JSON); --maps writes the maps
      as PREFIX-*.csv
  spiralcam sag JOB.json --at POINTS.csv
      print z, gradient and second derivatives of the job's surface at each x_mm,y_mm row
  spiralcam --version";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("plan") => plan(&args[1..]),
        Some("analyse") => analyse(&args[1..]),
        Some("sag") => sag(&args[1..]),
        Some("--version" | "-V") => {
            println!("spiralcam {}", env!("CARGO_PKG_VERSION"));
            Ok(())
        }
        Some("--help" | "-h") => {
            println!("{USAGE}");
            Ok(())
        }
        _ => Err(Failure::Usage(
            "expected a command: plan, analyse or sag".into(),
        )),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(m)) => {
            eprintln!("spiralcam: {m}\n{USAGE}");
            ExitCode::from(2)
        }
        Err(Failure::Run(m)) => {
            eprintln!("spiralcam: {m}");
            ExitCode::from(1)
        }
    }
}

enum Failure {
    Usage(String),
    Run(String),
}

fn run_err(e: impl std::fmt::Display) -> Failure {
    Failure::Run(e.to_string())
}

/// The job file and the `--flag value` options after it.
struct Args {
    job: PathBuf,
    options: Vec<(String, PathBuf)>,
}

fn parse(args: &[String], allowed: &[&str]) -> Result<Args, Failure> {
    let (job, rest) = args
        .split_first()
        .ok_or_else(|| Failure::Usage("missing JOB.json".into()))?;
    let mut options = Vec::new();
    let mut it = rest.iter();
    while let Some(flag) = it.next() {
        if !allowed.contains(&flag.as_str()) {
            return Err(Failure::Usage(format!("unknown option {flag}")));
        }
        let value = it
            .next()
            .ok_or_else(|| Failure::Usage(format!("{flag} needs a file name")))?;
        options.push((flag.clone(), PathBuf::from(value)));
    }
    Ok(Args {
        job: PathBuf::from(job),
        options,
    })
}

impl Args {
    fn get(&self, flag: &str) -> Option<&Path> {
        self.options
            .iter()
            .rev()
            .find(|(f, _)| f == flag)
            .map(|(_, p)| p.as_path())
    }
}

/// Reads a job and the data files it names by path (relative to the job file).
fn read_job(path: &Path) -> Result<Job, Failure> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Failure::Run(format!("{}: {e}", path.display())))?;
    let mut job =
        Job::from_json(&text).map_err(|e| Failure::Run(format!("{}: {e}", path.display())))?;
    let dir = path.parent().unwrap_or(Path::new("."));
    job.load_files(|file| std::fs::read_to_string(dir.join(file)).map_err(|e| e.to_string()))
        .map_err(|e| Failure::Run(format!("{}: {e}", path.display())))?;
    Ok(job)
}

/// A file written under a temporary name and renamed into place on success.
struct Output {
    path: PathBuf,
    partial: PathBuf,
    writer: BufWriter<File>,
}

impl Output {
    fn create(path: &Path) -> Result<Self, Failure> {
        let mut partial = path.as_os_str().to_owned();
        partial.push(".partial");
        let partial = PathBuf::from(partial);
        let file = File::create(&partial)
            .map_err(|e| Failure::Run(format!("{}: {e}", partial.display())))?;
        Ok(Self {
            path: path.to_owned(),
            partial,
            writer: BufWriter::with_capacity(1 << 16, file),
        })
    }

    fn commit(mut self) -> Result<(), Failure> {
        self.writer.flush().map_err(run_err)?;
        std::fs::rename(&self.partial, &self.path)
            .map_err(|e| Failure::Run(format!("{}: {e}", self.path.display())))
    }

    fn discard(self) {
        drop(self.writer);
        let _ = std::fs::remove_file(&self.partial);
    }
}

fn plan(args: &[String]) -> Result<(), Failure> {
    let args = parse(args, &["--nc", "--csv", "--fts-csv", "--report"])?;
    let job = read_job(&args.job)?;
    let planner = Planner::new(&job).map_err(run_err)?;
    let mut nc = args.get("--nc").map(Output::create).transpose()?;
    let mut csv = args.get("--csv").map(Output::create).transpose()?;
    if args.get("--fts-csv").is_some() && job.strategy.split.is_none() {
        return Err(Failure::Usage(
            "--fts-csv needs a split path: set strategy.split in the job".into(),
        ));
    }
    let mut fts = args.get("--fts-csv").map(Output::create).transpose()?;
    let tty = std::io::stderr().is_terminal();
    let mut progress = |p: Progress| {
        if tty {
            progress_bar(p);
        }
        ControlFlow::Continue(())
    };
    let sinks = Sinks {
        nc: nc.as_mut().map(|o| &mut o.writer as &mut dyn Write),
        csv: csv.as_mut().map(|o| &mut o.writer as &mut dyn Write),
        display: None::<&mut DisplayPath>,
        z_slide: None,
        fts_table: fts.as_mut().map(|o| &mut o.writer as &mut dyn Write),
    };
    let result = planner.run_with_dynamics(sinks, &mut progress);
    if tty {
        eprintln!();
    }
    let report = match result {
        Ok(r) => r,
        Err(e) => {
            for output in [nc, csv, fts].into_iter().flatten() {
                output.discard();
            }
            return Err(run_err(e));
        }
    };
    nc.map(Output::commit).transpose()?;
    csv.map(Output::commit).transpose()?;
    fts.map(Output::commit).transpose()?;
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    write_report(args.get("--report"), report.to_json() + "\n")
}

fn analyse(args: &[String]) -> Result<(), Failure> {
    let args = parse(args, &["--report", "--maps"])?;
    let job = read_job(&args.job)?;
    let planner = Planner::new(&job).map_err(run_err)?;
    let tty = std::io::stderr().is_terminal();
    let mut progress = |p: Progress| {
        if tty {
            progress_bar(p);
        }
        ControlFlow::Continue(())
    };
    let analysis = Analysis::run(&planner, MAP_SIZE, &mut progress).map_err(run_err);
    if tty {
        eprintln!();
    }
    let analysis = analysis?;
    if let Some(prefix) = args.get("--maps") {
        let name = |what: &str| {
            let mut p = prefix.as_os_str().to_owned();
            p.push(format!("-{what}.csv"));
            PathBuf::from(p)
        };
        write_map(
            &name("linearization"),
            analysis.linearization_map(),
            "error_um",
        )?;
        write_map(&name("form"), &analysis.form_map(), "error_um")?;
        write_map(
            &name("clearance"),
            analysis.clearance_map(),
            "required_clearance_deg",
        )?;
    }
    write_report(args.get("--report"), analysis.to_json() + "\n")
}

/// Samples per side of the maps `analyse --maps` writes.
const MAP_SIZE: usize = 256;

/// Writes the defined samples of `map` as `x_mm,y_mm,<value>` rows.
fn write_map(path: &Path, map: &Raster, value: &str) -> Result<(), Failure> {
    let mut out = Output::create(path)?;
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
    match write() {
        Ok(()) => out.commit(),
        Err(e) => {
            out.discard();
            Err(Failure::Run(format!("{}: {e}", path.display())))
        }
    }
}

/// Writes a JSON report to `path`, or to standard output.
fn write_report(path: Option<&Path>, json: String) -> Result<(), Failure> {
    match path {
        Some(path) => {
            std::fs::write(path, json).map_err(|e| Failure::Run(format!("{}: {e}", path.display())))
        }
        None => std::io::stdout()
            .write_all(json.as_bytes())
            .map_err(run_err),
    }
}

fn progress_bar(p: Progress) {
    let frac = if p.total > 0 {
        (p.done as f64 / p.total as f64).min(1.0)
    } else {
        1.0
    };
    let filled = (frac * 40.0) as usize;
    eprint!(
        "\rplanning [{}{}] {:5.1} % {}/{} points",
        "#".repeat(filled),
        ".".repeat(40 - filled),
        frac * 100.0,
        p.done,
        p.total
    );
}

fn sag(args: &[String]) -> Result<(), Failure> {
    let args = parse(args, &["--at"])?;
    let at = args
        .get("--at")
        .ok_or_else(|| Failure::Usage("sag needs --at POINTS.csv".into()))?;
    let job = read_job(&args.job)?;
    job.validate().map_err(run_err)?;
    let surface = job.build_surface().map_err(run_err)?;
    let text =
        std::fs::read_to_string(at).map_err(|e| Failure::Run(format!("{}: {e}", at.display())))?;
    let mut out = BufWriter::new(std::io::stdout().lock());
    let header = "x_mm,y_mm,z_mm,dz_dx,dz_dy,d2z_dx2_per_mm,d2z_dxdy_per_mm,d2z_dy2_per_mm";
    writeln!(out, "{header}").map_err(run_err)?;
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let parsed: Option<Vec<f64>> = fields
            .iter()
            .take(2)
            .map(|f| f.parse::<f64>().ok())
            .collect();
        let (x, y) = match parsed.as_deref() {
            Some(&[x, y]) if x.is_finite() && y.is_finite() => (x, y),
            _ if n == 0 => continue, // a header row
            _ => {
                return Err(Failure::Run(format!(
                    "{} line {}: expected two numbers x_mm,y_mm, got {line:?}",
                    at.display(),
                    n + 1
                )));
            }
        };
        let l = surface.local(x, y).map_err(run_err)?;
        writeln!(
            out,
            "{x},{y},{:.15e},{:.15e},{:.15e},{:.15e},{:.15e},{:.15e}",
            l.z, l.zx, l.zy, l.zxx, l.zxy, l.zyy
        )
        .map_err(run_err)?;
    }
    out.flush().map_err(run_err)
}
