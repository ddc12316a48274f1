//! The command line's words: a command, the job file, `--flag value` options, `--help`.

use crate::Failure;
use std::path::{Path, PathBuf};

/// The job file and the options after it.
pub struct Args {
    /// The job file.
    pub job: PathBuf,
    options: Vec<(String, String)>,
}

/// Parses `args` (after the command): the job file, then options from `allowed`, each with a
/// value. `--help` anywhere is answered by the caller before this ([`wants_help`]).
pub fn parse(args: &[String], allowed: &[&str]) -> Result<Args, Failure> {
    parse_with(args, allowed, "JOB.json")
}

/// [`parse`] with the first word named `first` in messages (`DESIGN`).
pub fn parse_with(args: &[String], allowed: &[&str], first: &str) -> Result<Args, Failure> {
    let (job, rest) = args
        .split_first()
        .ok_or_else(|| Failure::Usage(format!("missing {first}")))?;
    if job.starts_with("--") {
        return Err(Failure::Usage(format!(
            "expected {first} before the options, got {job}"
        )));
    }
    let mut options: Vec<(String, String)> = Vec::new();
    let mut it = rest.iter();
    while let Some(flag) = it.next() {
        if !allowed.contains(&flag.as_str()) {
            return Err(Failure::Usage(format!(
                "unknown option {flag} (this command takes {})",
                allowed.join(", ")
            )));
        }
        if options.iter().any(|(f, _)| f == flag) {
            return Err(Failure::Usage(format!("{flag} given twice")));
        }
        let what = match flag.as_str() {
            "--cut" => "optic or mould",
            "--surface" | "--nx" | "--ny" => "a whole number",
            f if f.starts_with("--max-") || f.ends_with("-mm") => "a number",
            "--gain" | "--rotate" => "a number",
            "--kind" => "error or height",
            "--register" => "a list of terms",
            "--mirror" => "x or y",
            "--params" => "a JSON file",
            _ => "a file name",
        };
        let value = it
            .next()
            .ok_or_else(|| Failure::Usage(format!("{flag} needs {what}")))?;
        options.push((flag.clone(), value.clone()));
    }
    Ok(Args {
        job: PathBuf::from(job),
        options,
    })
}

/// Whether the words ask for help.
pub fn wants_help(args: &[String]) -> bool {
    args.iter().any(|a| a == "--help" || a == "-h")
}

impl Args {
    /// The value of `flag` as a path.
    pub fn path(&self, flag: &str) -> Option<&Path> {
        self.value(flag).map(Path::new)
    }

    /// The value of `flag`.
    pub fn value(&self, flag: &str) -> Option<&str> {
        self.options
            .iter()
            .find(|(f, _)| f == flag)
            .map(|(_, v)| v.as_str())
    }

    /// The value of `flag` as a whole number from `min`, or a usage error naming it.
    pub fn whole(&self, flag: &str, min: usize) -> Result<Option<usize>, Failure> {
        let Some(text) = self.value(flag) else {
            return Ok(None);
        };
        match text.parse::<usize>() {
            Ok(v) if v >= min => Ok(Some(v)),
            _ => Err(Failure::Usage(format!(
                "{flag} {text}: must be a whole number ≥ {min}"
            ))),
        }
    }

    /// The value of `flag` as a positive number, or a usage error naming it.
    pub fn positive(&self, flag: &str) -> Result<Option<f64>, Failure> {
        let Some(text) = self.value(flag) else {
            return Ok(None);
        };
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() && v > 0.0 => Ok(Some(v)),
            _ => Err(Failure::Usage(format!(
                "{flag} {text}: must be a number > 0"
            ))),
        }
    }
}
