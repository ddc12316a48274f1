//! `spiralcam correct`: a measured part in, a corrected job out
//! ([`spiralcam::analysis::correction`]).

use crate::files::{OutputFile, Target, check_targets, read_bytes};
use crate::{Failure, read_job, run_err};
use spiralcam::analysis::correction::{Correction, CorrectionSettings, MAX_GAIN};
use spiralcam::analysis::registration::{MeasuredKind, RegisterTerms};
use spiralcam::job::Job;
use spiralcam::raster::Raster;
use spiralcam::surface::measured::{self, MAX_FILE_BYTES, Mirror, Orientation};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The command's help.
pub const HELP: &str = "spiralcam correct JOB.json --measured FILE --kind error|height [--gain G]
                         [--register TERMS] [--rotate DEG] [--mirror x|y]
                         [--out CORRECTED.json] [--report FILE] [--maps PREFIX]

Registers the job's design to a measurement of the part, reports the residual and writes
the corrected job: the design minus G × the residual (G default 1, at most 2), a composite
surface whose correction term is a Zemax Grid Sag grid written beside CORRECTED.json as
CORRECTED.correction.dat (named in the job by its path relative to it). Correcting a
corrected job adds the new residual to its correction.

  --measured FILE  a CSV point cloud (x_mm,y_mm,z_mm header; _um, _nm accepted), a Zemax Grid
                   Sag .DAT, a Zygo .datx or a MetroPro .dat (crate/docs/measured-data.md)
  --kind           error: the file is measured − design; height: measured heights of the part
  --register TERMS piston and tilt always; power on request; decentre and clocking (height
                   only, the default there) where the design's shape tells them from tilt
  --rotate DEG     turn the data by a multiple of 90° counter-clockwise seen from the tool,
  --mirror x|y     after mirroring x → −x or y → −y (instrument frames differ from the lathe's)
  --report FILE    the report as JSON (standard output when not given): registration, residual
                   (PV, RMS, points, 37 Fringe Zernike terms), corrected (job file, predicted
                   residual after the re-cut), warnings
  --maps PREFIX    PREFIX-before.csv and PREFIX-after.csv: x_mm,y_mm,residual_um, 256 x 256

Every output is checked first and written only when the whole correction succeeded.
Exit status: 0 done, 1 the job or a file is wrong, 2 the command line is wrong.";

/// Samples per side of the maps.
const MAP_SIZE: usize = 256;

pub fn run(words: &[String]) -> Result<(), Failure> {
    let args = crate::args::parse(
        words,
        &[
            "--measured",
            "--kind",
            "--gain",
            "--register",
            "--rotate",
            "--mirror",
            "--out",
            "--report",
            "--maps",
        ],
    )?;
    let measured = args
        .path("--measured")
        .ok_or_else(|| Failure::Usage("correct needs --measured FILE".into()))?;
    let kind = match args.value("--kind") {
        Some("error") => MeasuredKind::Error,
        Some("height") => MeasuredKind::Height,
        Some(other) => {
            return Err(Failure::Usage(format!(
                "--kind {other}: expected error or height"
            )));
        }
        None => return Err(Failure::Usage("correct needs --kind error|height".into())),
    };
    let mut settings = CorrectionSettings::new(kind);
    settings.map_size = MAP_SIZE;
    if let Some(g) = args.positive("--gain")? {
        if g > MAX_GAIN {
            return Err(Failure::Usage(format!("--gain {g}: must lie in (0, 2]")));
        }
        settings.gain = g;
    }
    if let Some(list) = args.value("--register") {
        settings.terms = RegisterTerms::parse(list, kind)
            .map_err(|e| Failure::Usage(format!("--register {e}")))?;
    }
    let orientation = orientation(args.value("--rotate"), args.value("--mirror"))?;
    let targets = targets(&args);
    check_targets(&targets, &[measured.to_path_buf()])?;
    let (job, mut inputs) = read_job(&args.job)?;
    inputs.push(measured.to_path_buf());
    check_targets(&targets, &inputs)?;
    let name = measured.display().to_string();
    let bytes =
        read_bytes(measured, MAX_FILE_BYTES).map_err(|e| Failure::Run(format!("{name}: {e}")))?;
    let map = measured::read(&name, bytes)
        .map_err(run_err)?
        .oriented(orientation);
    let mut correction = Correction::run(&job, &map, &settings).map_err(run_err)?;
    // Everything is written under temporary names first, then renamed together.
    let mut written = Vec::new();
    if let Some(out) = args.path("--out") {
        let data = data_path(out);
        let job_text = corrected_job_text(&correction.corrected_job, &args.job, out, &data)?;
        written.push(text_file(
            &data,
            correction.correction_grid.to_dat().as_bytes(),
        )?);
        written.push(text_file(out, job_text.as_bytes())?);
        correction.report.corrected.job_file = Some(out.display().to_string());
        correction.report.corrected.data_file = Some(data.display().to_string());
    }
    if let Some(prefix) = args.path("--maps") {
        written.push(write_map(&map_path(prefix, "before"), &correction.before)?);
        written.push(write_map(&map_path(prefix, "after"), &correction.after)?);
    }
    for w in &correction.report.warnings {
        eprintln!("warning: {w}");
    }
    let json = correction.report_json() + "\n";
    let report = match args.path("--report") {
        Some(path) => {
            let mut f = OutputFile::create(path)?;
            f.writer
                .write_all(json.as_bytes())
                .map_err(|e| Failure::Run(format!("{}: {e}", path.display())))?;
            Some(f)
        }
        None => None,
    };
    for file in written.into_iter().chain(report) {
        file.commit()?;
    }
    if args.path("--report").is_none() {
        std::io::stdout()
            .write_all(json.as_bytes())
            .map_err(run_err)?;
    }
    Ok(())
}

/// The orientation of `--rotate` and `--mirror`.
fn orientation(rotate: Option<&str>, mirror: Option<&str>) -> Result<Orientation, Failure> {
    let deg = match rotate {
        None => 0,
        Some(t) => t.trim().parse::<i64>().map_err(|_| {
            Failure::Usage(format!(
                "--rotate {t}: must be a whole multiple of 90 (degrees)"
            ))
        })?,
    };
    let mirror = match mirror {
        None => Mirror::None,
        Some(t) => t
            .parse::<Mirror>()
            .map_err(|_| Failure::Usage(format!("--mirror {t}: expected x or y")))?,
    };
    Orientation::new(deg, mirror)
        .map_err(|_| Failure::Usage(format!("--rotate {deg}: must be a multiple of 90")))
}

/// The outputs the command line names, for [`check_targets`].
fn targets(args: &crate::args::Args) -> Vec<Target> {
    let mut t = Vec::new();
    if let Some(out) = args.path("--out") {
        t.push(Target {
            flag: "--out",
            path: out.to_path_buf(),
        });
        t.push(Target {
            flag: "--out",
            path: data_path(out),
        });
    }
    if let Some(prefix) = args.path("--maps") {
        for which in ["before", "after"] {
            t.push(Target {
                flag: "--maps",
                path: map_path(prefix, which),
            });
        }
    }
    if let Some(p) = args.path("--report") {
        t.push(Target {
            flag: "--report",
            path: p.to_path_buf(),
        });
    }
    t
}

/// The correction grid's file beside the corrected job: `NAME.correction.dat` for `NAME.json`.
fn data_path(out: &Path) -> PathBuf {
    let stem = out.file_stem().unwrap_or_default().to_string_lossy();
    out.with_file_name(format!("{stem}.correction.dat"))
}

/// `PREFIX-which.csv`.
fn map_path(prefix: &Path, which: &str) -> PathBuf {
    let mut p = prefix.as_os_str().to_owned();
    p.push(format!("-{which}.csv"));
    PathBuf::from(p)
}

/// The corrected job as JSON: its correction grid named by `data`'s file name (beside it), the
/// design's own data files by their paths relative to the corrected job's folder, their text
/// left out.
fn corrected_job_text(
    job: &Job,
    source: &Path,
    out: &Path,
    data: &Path,
) -> Result<String, Failure> {
    let mut job = job.clone();
    let source_dir = source.parent().unwrap_or(Path::new("."));
    let out_dir = match out.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let data_name = data
        .file_name()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned();
    for (_, file) in job.surface.data_files_mut() {
        match &file.path {
            Some(p) => {
                let rel = relative_to(&source_dir.join(p), out_dir);
                file.path = Some(rel.to_string_lossy().into_owned());
            }
            // The correction term's grid: written beside the job.
            None => file.path = Some(data_name.clone()),
        }
        file.text = None;
    }
    Ok(job.to_json() + "\n")
}

/// `target` as a path relative to the folder `dir` (both resolved), or as given when either
/// cannot be resolved.
fn relative_to(target: &Path, dir: &Path) -> PathBuf {
    let (Ok(t), Ok(d)) = (target.canonicalize(), dir.canonicalize()) else {
        return target.to_path_buf();
    };
    let (tc, dc): (Vec<_>, Vec<_>) = (t.components().collect(), d.components().collect());
    let common = tc.iter().zip(&dc).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..dc.len() {
        out.push("..");
    }
    for c in &tc[common..] {
        out.push(c);
    }
    out
}

/// A file with `bytes`, not yet renamed into place.
fn text_file(path: &Path, bytes: &[u8]) -> Result<OutputFile, Failure> {
    let mut f = OutputFile::create(path)?;
    f.writer
        .write_all(bytes)
        .map_err(|e| Failure::Run(format!("{}: {e}", path.display())))?;
    Ok(f)
}

/// The defined cells of `map` as `x_mm,y_mm,residual_um` rows, not yet renamed into place.
fn write_map(path: &Path, map: &Raster) -> Result<OutputFile, Failure> {
    let mut text = String::from("x_mm,y_mm,residual_um\n");
    for j in 0..map.size {
        for i in 0..map.size {
            let v = map.values[j * map.size + i];
            if !v.is_nan() {
                let (x, y) = map.position(i, j);
                text.push_str(&format!("{x:.6},{y:.6},{v:.6}\n"));
            }
        }
    }
    text_file(path, text.as_bytes())
}
