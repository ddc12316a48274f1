//! `spiralcam export-grid`: a job's surface written as a Zemax Grid Sag `.DAT`
//! ([`spiralcam::surface::grid_sag::export`]), so that the designer can load in the design
//! software the surface that will be cut.

use crate::files::{Target, check_targets, write_file};
use crate::{Failure, read_job, run_err};
use spiralcam::surface::PartDisc;
use spiralcam::surface::grid_sag::export::{GridExtent, sample};

/// The command's help.
pub const HELP: &str =
    "spiralcam export-grid JOB.json --nx N --ny N --out FILE.DAT [--half-width-mm W]

Writes the job's surface as a Zemax Grid Sag file: nx x ny points (each at least 5, at most
1024 x 1024 together) over a square centred on the part, each with the sag and its analytic
slopes and cross derivative, in millimetres; a point where the surface is undefined is
written without data. The surface is the design as the job defines it, in the design's own
frame: part.cut does not turn it (OpticStudio's frame), and with part.normal_axis_at_mm the
square is centred on that point.

  --half-width-mm W   half the square's side (default: 1.02 x the part's radius, so that the
                      grid also covers the spiral's first point, which may lie one angle step
                      outside the part)";

/// The default half-width over the part's radius.
const MARGIN: f64 = 1.02;

pub fn run(words: &[String]) -> Result<(), Failure> {
    let args = crate::args::parse(words, &["--nx", "--ny", "--out", "--half-width-mm"])?;
    let out = args
        .path("--out")
        .ok_or_else(|| Failure::Usage("export-grid needs --out FILE.DAT".into()))?;
    let need = |flag: &str| {
        args.whole(flag, 5)?
            .ok_or_else(|| Failure::Usage(format!("export-grid needs {flag} N")))
    };
    let (nx, ny) = (need("--nx")?, need("--ny")?);
    let half = args.positive("--half-width-mm")?;
    let targets = [Target {
        flag: "--out",
        path: out.to_path_buf(),
    }];
    check_targets(&targets, &[])?;
    let (job, inputs) = read_job(&args.job)?;
    check_targets(&targets, &inputs)?;
    job.validate().map_err(run_err)?;
    let [cx, cy] = job.part.normal_axis_at_mm.unwrap_or([0.0, 0.0]);
    let part = PartDisc {
        radius_mm: job.part_radius_mm(),
        x_mm: cx,
        y_mm: cy,
    };
    let surface = job
        .surface
        .build_in(part)
        .map_err(|e| run_err(e.within("surface")))?;
    let half = half.unwrap_or(MARGIN * job.part_radius_mm());
    let extent = GridExtent {
        nx,
        ny,
        half_width_x_mm: half,
        half_width_y_mm: half,
        centre_x_mm: cx,
        centre_y_mm: cy,
    };
    let grid = sample(surface.as_ref(), &extent).map_err(|e| {
        Failure::Usage(format!(
            "--{} {}: {}",
            e.field.replace("half_width_x_mm", "half-width-mm"),
            e.value,
            e.allowed
        ))
    })?;
    let missing = grid.nodes.iter().filter(|n| !n.valid).count();
    if missing == grid.nodes.len() {
        return Err(Failure::Run(format!(
            "the surface is undefined at every point of the {nx} x {ny} grid of half-width {half} mm"
        )));
    }
    write_file(out, grid.to_dat().as_bytes())?;
    println!(
        "wrote {}: {nx} x {ny} points, spacing {} x {} mm, square of half-width {half} mm centred \
         at ({cx}, {cy}) mm, {missing} points without data; surface: {}",
        out.display(),
        grid.dx_mm,
        grid.dy_mm,
        surface.describe()
    );
    Ok(())
}
