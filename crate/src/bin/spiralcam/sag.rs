//! `spiralcam sag`: the job's surface, sag and derivatives, at the points of a CSV file.

use crate::files::read_text;
use crate::{Failure, read_job, run_err};
use spiralcam::field::short;
use spiralcam::surface::data_file::MAX_DATA_BYTES;
use std::io::{BufWriter, Write};

/// The command's help.
pub const HELP: &str = "spiralcam sag JOB.json --at POINTS.csv

Prints, for each x_mm,y_mm row of POINTS.csv (a header row and # comments are skipped),
x_mm,y_mm,z_mm,dz_dx,dz_dy,d2z_dx2_per_mm,d2z_dxdy_per_mm,d2z_dy2_per_mm of the job's
surface, in the spindle's frame. A point where the surface is undefined or not finite is
an error (exit 1) naming the line.";

pub fn run(words: &[String]) -> Result<(), Failure> {
    let args = crate::args::parse(words, &["--at"])?;
    let at = args
        .path("--at")
        .ok_or_else(|| Failure::Usage("sag needs --at POINTS.csv".into()))?;
    let (job, _) = read_job(&args.job)?;
    job.validate().map_err(run_err)?;
    let surface = job.build_surface().map_err(run_err)?;
    let text = read_text(at, MAX_DATA_BYTES)
        .map_err(|e| Failure::Run(format!("{}: {e}", at.display())))?;
    let mut out = BufWriter::new(std::io::stdout().lock());
    let header = "x_mm,y_mm,z_mm,dz_dx,dz_dy,d2z_dx2_per_mm,d2z_dxdy_per_mm,d2z_dy2_per_mm";
    writeln!(out, "{header}").map_err(run_err)?;
    for (n, line) in text.lines().enumerate() {
        let line = line.trim().trim_start_matches('\u{feff}');
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let at_line =
            |what: String| Failure::Run(format!("{} line {}: {what}", at.display(), n + 1));
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
                return Err(at_line(format!(
                    "expected two numbers x_mm,y_mm, got {line:?}"
                )));
            }
        };
        let l = surface.local(x, y).map_err(|e| at_line(e.to_string()))?;
        let values = [l.z, l.zx, l.zy, l.zxx, l.zxy, l.zyy];
        if values.iter().any(|v| !v.is_finite()) {
            return Err(at_line(format!(
                "the surface is not finite at x = {}, y = {} (z = {}): no value to print",
                short(x),
                short(y),
                short(l.z)
            )));
        }
        writeln!(
            out,
            "{x},{y},{:.15e},{:.15e},{:.15e},{:.15e},{:.15e},{:.15e}",
            l.z, l.zx, l.zy, l.zxx, l.zxy, l.zyy
        )
        .map_err(run_err)?;
    }
    out.flush().map_err(run_err)
}
