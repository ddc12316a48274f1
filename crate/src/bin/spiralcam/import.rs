//! `spiralcam import`: a job from a designer's file (`.zmx`, `.seq`, Grid Sag `.DAT`), with the
//! data files it needs written beside it.

use crate::files::{OutputFile, Target, check_targets, read_bytes, read_text};
use crate::{Failure, run_err};
use spiralcam::job::Piece;
use spiralcam::job::design::{DesignChoice, DesignError, job_from_design};
use spiralcam::surface::data_file::MAX_DATA_BYTES;
use spiralcam::surface::import::{MAX_DESIGN_BYTES, read_design};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The command's help.
pub const HELP: &str =
    "spiralcam import DESIGN [--surface N] [--cut optic|mould] [--diameter-mm D] --out JOB.json

Reads a designer's file (an OpticStudio .zmx, a CODE V .seq or a Zemax Grid Sag .DAT) and
writes a job for one of its surfaces, ready for `spiralcam plan`; the rest of the job takes
the example defaults (tool, machine, strategy, output). A Grid Sag's grid is written beside
the job as JOB.grid.DAT and named by that path. The command prints what it read (types,
coefficients as in the file and in mm, normalisation radius, semi-diameter, units, media)
to compare with the prescription report.

  --surface N       the surface's number in the file (default: the only surface between
                    object and image)
  --cut optic       the optic's own surface, cut from the air side (a mirror's default)
  --cut mould       a mould insert forming the surface, cut from the glass side;
                    a refracting surface needs one of the two. The design is turned 180°
                    about Y (x -> -x, z -> -z, a rotation, never a mirror) when the tool
                    comes from its -Z side; the job (part.cut) and the NC header say so.
  --diameter-mm D   the part's diameter (default: twice the file's semi-diameter, DIAM or CIR)

Exit status: 0 done, 1 the file cannot give a job (the message says what to choose or fix),
2 the command line is wrong.";

/// The piece a `--cut` value names.
fn piece(text: Option<&str>) -> Result<Option<Piece>, Failure> {
    match text {
        None => Ok(None),
        Some("optic") => Ok(Some(Piece::Optic)),
        Some("mould" | "mold") => Ok(Some(Piece::Mould)),
        Some(t) => Err(Failure::Usage(format!("--cut {t}: must be optic or mould"))),
    }
}

/// The error with the option that answers it.
fn with_option(e: DesignError) -> Failure {
    let hint = match &e {
        DesignError::NoSuchSurface { .. } | DesignError::ChooseSurface { .. } => " (--surface N)",
        DesignError::ChoosePiece { .. } => " (--cut optic or --cut mould)",
        DesignError::NoDiameter { .. } | DesignError::ApertureDecentred { .. } => {
            " (--diameter-mm D)"
        }
        _ => "",
    };
    run_err(format!("{e}{hint}"))
}

/// `JOB.grid.DAT` (`JOB.grid-2.DAT` for a second grid) beside the job.
fn data_target(out: &Path, k: usize) -> PathBuf {
    let stem = out.file_stem().unwrap_or_default().to_string_lossy();
    let name = if k == 0 {
        format!("{stem}.grid.DAT")
    } else {
        format!("{stem}.grid-{}.DAT", k + 1)
    };
    out.with_file_name(name)
}

fn write_error(path: &Path, e: std::io::Error) -> Failure {
    Failure::Run(format!("{}: {e}", path.display()))
}

pub fn run(words: &[String]) -> Result<(), Failure> {
    let args = crate::args::parse_with(
        words,
        &["--surface", "--cut", "--diameter-mm", "--out"],
        "DESIGN",
    )?;
    let out = args
        .path("--out")
        .ok_or_else(|| Failure::Usage("import needs --out JOB.json".into()))?
        .to_path_buf();
    let choice = DesignChoice {
        surface: args.whole("--surface", 0)?,
        piece: piece(args.value("--cut"))?,
        diameter_mm: args.positive("--diameter-mm")?,
    };
    let design_path = args.job.clone();
    let out_target = [Target {
        flag: "--out",
        path: out.clone(),
    }];
    check_targets(&out_target, std::slice::from_ref(&design_path))?;
    let at = |e: String| Failure::Run(format!("{}: {e}", design_path.display()));
    let bytes = read_bytes(&design_path, MAX_DESIGN_BYTES).map_err(at)?;
    let name = design_path.display().to_string();
    let design = read_design(&name, &bytes).map_err(run_err)?;
    let dir = design_path.parent().unwrap_or(Path::new("."));
    let mut inputs = vec![design_path.clone()];
    let read = |file: &str| {
        let p = dir.join(file);
        let text = read_text(&p, MAX_DATA_BYTES).map_err(|e| format!("{}: {e}", p.display()));
        inputs.push(p);
        text
    };
    let mut made = job_from_design(&design, &choice, read).map_err(with_option)?;
    let mut targets = out_target.to_vec();
    let mut data = Vec::new();
    for (k, (_, file)) in made.job.surface.data_files_mut().into_iter().enumerate() {
        let path = data_target(&out, k);
        let name = path
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        data.push((path.clone(), file.text.take().unwrap_or_default()));
        file.path = Some(name);
        targets.push(Target {
            flag: "--out",
            path,
        });
    }
    check_targets(&targets, &inputs)?;
    let mut job_file = OutputFile::create(&out)?;
    job_file
        .writer
        .write_all((made.job.to_json() + "\n").as_bytes())
        .map_err(|e| write_error(&out, e))?;
    let mut data_files = Vec::new();
    for (path, text) in &data {
        let mut f = OutputFile::create(path)?;
        f.writer
            .write_all(text.as_bytes())
            .map_err(|e| write_error(path, e))?;
        data_files.push(f);
    }
    let mut stdout = std::io::stdout().lock();
    for line in &made.listing {
        writeln!(stdout, "{line}").map_err(run_err)?;
    }
    job_file.commit()?;
    writeln!(stdout, "wrote {}", out.display()).map_err(run_err)?;
    for (f, (path, _)) in data_files.into_iter().zip(&data) {
        f.commit()?;
        writeln!(stdout, "wrote {}", path.display()).map_err(run_err)?;
    }
    Ok(())
}
