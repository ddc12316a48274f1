//! `spiralcam verify`: a program from any system checked against the job's design
//! ([`spiralcam::analysis::verify`]).

use crate::analyse::write_map;
use crate::files::{Target, check_targets, write_file};
use crate::{Failure, bar, read_job, run_err};
use spiralcam::analysis::verify::{VerifySettings, verify};
use spiralcam::nc::reader::{Code, Program, Reader, ReaderOptions, files_beside};
use spiralcam::tool::ToolPath;
use std::io::Write;
use std::path::PathBuf;

/// The command's help.
pub const HELP: &str = "spiralcam verify JOB.json --nc PROGRAM [--report FILE] [--maps PREFIX]
                        [--accept CODES]

Reads PROGRAM as a controller would (loops, variables, G52 shifts, child programs M98 P…
or o<…> call found beside it) with the job's output conventions (signs of X, Z and C; the
servo's word adds to Z; C wrapped or cumulative is detected) and compares every cutting
point (a feed move that turns C; without C, a feed move in X) with the one-way compensated
tip of the job's tool over the design. The report (JSON, standard output without --report):
blocks, cutting points, passes with their stock, the deviation of the last pass and of
each (min, max, rms and where; positive: material left, negative: cut into the design),
the linearization error and predicted form of the last pass, feeds, block times, spindle
speed and cycle time, collisions of the moves that do not cut, the machine's limits, and
warnings for what was read but not interpreted.

  --maps PREFIX   PREFIX-deviation.csv: x_mm,y_mm,deviation_um of the last pass, 256 x 256
                  over the part (the largest magnitude in each cell)
  --accept CODES  controller codes to accept without effect, comma-separated (G63,G103)

Exit status: 0 done, 1 the job, the program or a file is wrong, 2 the command line is wrong.";

/// Samples per side of the map.
const MAP_SIZE: usize = 256;

pub fn run(words: &[String]) -> Result<(), Failure> {
    let args = crate::args::parse(words, &["--nc", "--report", "--maps", "--accept"])?;
    let program = args
        .path("--nc")
        .ok_or_else(|| Failure::Usage("verify needs --nc PROGRAM".into()))?
        .to_path_buf();
    let mut options = ReaderOptions::default();
    if let Some(list) = args.value("--accept") {
        for code in list.split(',').filter(|c| !c.trim().is_empty()) {
            options
                .accepted_codes
                .push(Code::parse(code).ok_or_else(|| {
                    Failure::Usage(format!(
                        "--accept: {code} is not a G or M code (such as G63 or M26.1)"
                    ))
                })?);
        }
    }
    let map_path = args.path("--maps").map(|prefix| {
        let mut p = prefix.as_os_str().to_owned();
        p.push("-deviation.csv");
        PathBuf::from(p)
    });
    let mut targets: Vec<Target> = map_path
        .iter()
        .map(|p| Target {
            flag: "--maps",
            path: p.clone(),
        })
        .collect();
    if let Some(p) = args.path("--report") {
        targets.push(Target {
            flag: "--report",
            path: p.to_path_buf(),
        });
    }
    let (job, mut inputs) = read_job(&args.job)?;
    inputs.push(program.clone());
    check_targets(&targets, &inputs)?;
    let mut progress = bar::callback();
    let tool_path = ToolPath::with_progress(&job, &mut progress).map_err(run_err)?;
    let mut open = || -> Result<Reader<'static>, String> {
        let main = Program::open(&program).map_err(|e| format!("{}: {e}", program.display()))?;
        Ok(Reader::new(main, options.clone()).with_resolver(files_beside(&program)))
    };
    let result = verify(
        &tool_path,
        &mut open,
        &VerifySettings {
            map_size: MAP_SIZE,
            ..VerifySettings::default()
        },
        &mut progress,
    );
    bar::end();
    let v = result.map_err(run_err)?;
    if let Some(path) = &map_path {
        write_map(path, &v.map, "deviation_um")?.commit()?;
    }
    let json = v.to_json() + "\n";
    match args.path("--report") {
        Some(path) => write_file(path, json.as_bytes()),
        None => std::io::stdout()
            .write_all(json.as_bytes())
            .map_err(run_err),
    }
}
