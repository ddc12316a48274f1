//! The spiralcam command-line tool.
//!
//! ```text
//! spiralcam plan JOB.json [--nc FILE] [--csv FILE] [--fts-csv FILE] [--fts-table FILE]
//!                         [--report FILE] [--max-output-gb G] [--max-points N] [--max-seconds S]
//! spiralcam analyse JOB.json [--report FILE] [--maps PREFIX] [--max-points N] [--max-seconds S]
//! spiralcam sag JOB.json --at POINTS.csv
//! spiralcam import DESIGN [--surface N] [--cut optic|mould] [--diameter-mm D] --out JOB.json
//! spiralcam export-grid JOB.json --nx N --ny N --out FILE.DAT [--half-width-mm W]
//! spiralcam correct JOB.json --measured FILE --kind error|height [--gain G] [--register TERMS]
//!                   [--rotate DEG] [--mirror x|y] [--out CORRECTED.json] [--report FILE]
//!                   [--maps PREFIX]
//! spiralcam setup JOB.json --params SETUP.json [--report FILE]
//! spiralcam verify JOB.json --nc PROGRAM [--report FILE] [--maps PREFIX] [--accept CODES]
//! ```
//!
//! Every job is admitted before work ([`spiralcam::plan::admission`]): its points, the size of
//! each file and the time are estimated and stated, and a job beyond the limits is refused with
//! the field to change. Files are read bounded and written so that nothing is left behind
//! ([`files`]); Ctrl-C or `kill` stop a run cleanly ([`cancel`]). Exit status: 0 done, 1 the job
//! or a file is wrong (the message names the field or the file), 2 the command line is wrong,
//! 128 + n stopped by signal n (130 for Ctrl-C).

mod analyse;
mod args;
mod bar;
mod cancel;
mod correct;
mod export_grid;
mod files;
mod import;
mod plan;
mod sag;
mod setup;
mod verify;

use spiralcam::job::Job;
use spiralcam::surface::data_file::MAX_DATA_BYTES;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const USAGE: &str = "usage:
  spiralcam plan JOB.json [--nc FILE] [--csv FILE] [--fts-csv FILE] [--fts-table FILE]
                          [--report FILE] [--max-output-gb G] [--max-points N] [--max-seconds S]
  spiralcam analyse JOB.json [--report FILE] [--maps PREFIX] [--max-points N] [--max-seconds S]
  spiralcam sag JOB.json --at POINTS.csv
  spiralcam import DESIGN [--surface N] [--cut optic|mould] [--diameter-mm D] --out JOB.json
  spiralcam export-grid JOB.json --nx N --ny N --out FILE.DAT [--half-width-mm W]
  spiralcam correct JOB.json --measured FILE --kind error|height [--gain G] [--register TERMS]
                    [--rotate DEG] [--mirror x|y] [--out CORRECTED.json] [--report FILE]
                    [--maps PREFIX]
  spiralcam setup JOB.json --params SETUP.json [--report FILE]
  spiralcam verify JOB.json --nc PROGRAM [--report FILE] [--maps PREFIX] [--accept CODES]
  spiralcam help [COMMAND] | COMMAND --help | --version";

/// The most a job file may weigh, bytes: it may carry its data files as text.
pub const MAX_JOB_BYTES: u64 = MAX_DATA_BYTES;

/// How a command failed.
#[derive(Debug)]
pub enum Failure {
    /// The command line is wrong: exit 2 with the usage.
    Usage(String),
    /// The job or a file is wrong: exit 1.
    Run(String),
    /// A signal stopped the run: exit 128 + the signal.
    Stopped,
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            Failure::Usage(m) | Failure::Run(m) => f.write_str(m),
            Failure::Stopped => f.write_str("stopped by a signal"),
        }
    }
}

/// A failure of the run from any error.
pub fn run_err(e: impl std::fmt::Display) -> Failure {
    if cancel::cancelled() {
        return Failure::Stopped;
    }
    Failure::Run(e.to_string())
}

fn main() -> ExitCode {
    cancel::install();
    let args: Vec<String> = std::env::args().skip(1).collect();
    let command = args.first().map(String::as_str);
    let rest = args.get(1..).unwrap_or(&[]);
    let result = match command {
        Some(
            "plan" | "analyse" | "sag" | "import" | "export-grid" | "correct" | "setup" | "verify",
        ) if args::wants_help(rest) => {
            help(command);
            Ok(())
        }
        Some("plan") => plan::run(rest),
        Some("analyse") => analyse::run(rest),
        Some("sag") => sag::run(rest),
        Some("import") => import::run(rest),
        Some("export-grid") => export_grid::run(rest),
        Some("correct") => correct::run(rest),
        Some("setup") => setup::run(rest),
        Some("verify") => verify::run(rest),
        Some("help") => {
            help(rest.first().map(String::as_str));
            Ok(())
        }
        Some("--help" | "-h") => {
            help(None);
            Ok(())
        }
        None => Err(Failure::Usage(
            "expected a command: plan, analyse, sag, import, export-grid, correct, setup or verify"
                .into(),
        )),
        Some("--version" | "-V") => {
            println!("spiralcam {}", env!("CARGO_PKG_VERSION"));
            Ok(())
        }
        Some(other) => Err(Failure::Usage(format!(
            "unknown command {other}: expected a command: plan, analyse, sag, import, export-grid, correct, setup or verify"
        ))),
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
        Err(Failure::Stopped) => {
            eprintln!("spiralcam: stopped; nothing written");
            ExitCode::from(u8::try_from(cancel::exit_code()).unwrap_or(1))
        }
    }
}

/// Prints the help of `command`, or the usage.
fn help(command: Option<&str>) {
    match command {
        Some("plan") => println!("{}", plan::HELP),
        Some("analyse") => println!("{}", analyse::HELP),
        Some("sag") => println!("{}", sag::HELP),
        Some("import") => println!("{}", import::HELP),
        Some("export-grid") => println!("{}", export_grid::HELP),
        Some("correct") => println!("{}", correct::HELP),
        Some("setup") => println!("{}", setup::HELP),
        Some("verify") => println!("{}", verify::HELP),
        _ => println!("{USAGE}"),
    }
}

/// Reads a job and the data files it names by path (relative to the job file), bounded
/// ([`files::read_text`]). Returns the job and the paths of the files it read.
pub fn read_job(path: &Path) -> Result<(Job, Vec<PathBuf>), Failure> {
    let at = |e: String| Failure::Run(format!("{}: {e}", path.display()));
    let text = files::read_text(path, MAX_JOB_BYTES).map_err(at)?;
    let mut job = Job::from_json(&text).map_err(|e| at(e.to_string()))?;
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut inputs = vec![path.to_path_buf()];
    job.load_files(|file| {
        let p = dir.join(file);
        let text = files::read_text(&p, MAX_DATA_BYTES);
        inputs.push(p);
        text
    })
    .map_err(|e| at(e.to_string()))?;
    Ok((job, inputs))
}
