//! A job's surface written as a Zemax Grid Sag `.DAT` (issue 13, part 3, until the command line
//! has `export-grid`): nx × ny points over the square of the given half-width about the axis,
//! with the surface's analytic slopes and cross derivative, points where it is undefined
//! without data ([`spiralcam::surface::grid_sag::export`]).
//!
//! `cargo run --release -p spiralcam --example export_grid -- JOB NX NY HALF_WIDTH_MM OUT.DAT`
//!
//! `crate/jobs/grid-sag.dat` (the example Grid Sag job's data) is
//! `… -- crate/jobs/zernike-standard.json 33 33 6.4 crate/jobs/grid-sag.dat`.

use spiralcam::job::Job;
use spiralcam::surface::grid_sag::export::{GridExtent, sample};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [job, nx, ny, half, out] = args.as_slice() else {
        return Err("usage: export_grid JOB NX NY HALF_WIDTH_MM OUT.DAT".into());
    };
    let dir = std::path::Path::new(job)
        .parent()
        .unwrap_or(std::path::Path::new("."));
    let mut job = Job::from_json(&std::fs::read_to_string(job)?)?;
    job.load_files(|p| std::fs::read_to_string(dir.join(p)).map_err(|e| e.to_string()))?;
    let surface = job.build_surface()?;
    let grid = sample(
        surface.as_ref(),
        &GridExtent::square(nx.parse()?, ny.parse()?, half.parse()?),
    )?;
    std::fs::write(out, grid.to_dat())?;
    println!(
        "{out}: {} × {} points of {}",
        grid.nx,
        grid.ny,
        surface.describe()
    );
    Ok(())
}
