//! `spiralcam setup`: what a test cut shows turned into offsets
//! ([`spiralcam::analysis::setup`]).

use crate::files::{read_text, write_file};
use crate::{Failure, read_job, run_err};
use spiralcam::analysis::setup::SetupSpec;
use std::io::Write;

/// The command's help.
pub const HELP: &str = "spiralcam setup JOB.json --params SETUP.json [--report FILE]

Turns what a test cut of the job shows into offsets, from the job's design along +X
(crate/docs/correction.md gives the geometry). SETUP.json holds any of:
  {\"centre_post\": {\"diameter_um\": 12, \"shape\": \"cone\" | \"cylinder\"},
   \"profile\": {\"inner_radius_mm\": 2, \"outer_radius_mm\": 8, \"rise_um\": 0.35},
   \"radius\": {\"measured_mm\": 50.012, \"aperture_radius_mm\": 10}}
centre_post: the tool height (cone: above the centre, cylinder: below); profile: the X
offset from the rise of a W or M shaped form error between two radii; radius: the X
offset (XZ lathe) or the B-axis Z offset that a measured radius of curvature gives.
Prints the offsets as JSON (or writes them to --report). Exit status: 0 done, 1 the job
or SETUP.json is wrong, 2 the command line is wrong.";

/// The most bytes of SETUP.json.
const MAX_PARAMS_BYTES: u64 = 1 << 20;

pub fn run(words: &[String]) -> Result<(), Failure> {
    let args = crate::args::parse(words, &["--params", "--report"])?;
    let params = args
        .path("--params")
        .ok_or_else(|| Failure::Usage("setup needs --params SETUP.json".into()))?;
    if let Some(report) = args.path("--report") {
        let target = crate::files::Target {
            flag: "--report",
            path: report.to_path_buf(),
        };
        crate::files::check_targets(&[target], &[params.to_path_buf(), args.job.clone()])?;
    }
    let (job, _) = read_job(&args.job)?;
    job.validate().map_err(run_err)?;
    let surface = job.build_surface().map_err(run_err)?;
    let at = |e: String| Failure::Run(format!("{}: {e}", params.display()));
    let text = read_text(params, MAX_PARAMS_BYTES).map_err(at)?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let de = &mut serde_json::Deserializer::from_str(text);
    let spec: SetupSpec = serde_path_to_error::deserialize(de)
        .map_err(|e| at(format!("{}: {}", e.path(), e.inner())))?;
    let report = spec
        .offsets(surface.as_ref(), job.part_radius_mm())
        .map_err(|e| at(e.to_string()))?;
    let json = serde_json::to_string_pretty(&report).unwrap_or_default() + "\n";
    match args.path("--report") {
        Some(path) => write_file(path, json.as_bytes()),
        None => std::io::stdout()
            .write_all(json.as_bytes())
            .map_err(run_err),
    }
}
