//! The Grid Sag figures of issue 13: for example jobs, the surface written as a 101 × 101 Zemax
//! Grid Sag `.DAT` over the part's square (the part radius plus 2 %, as `spiralcam export-grid`
//! does) with its analytic derivatives, read back as `grid_sag` once with the file's
//! derivatives and once with them zeroed (so that they are computed, not-a-knot splines), the
//! largest sag error against the job's closed form over a 201 × 201 sweep of the part off the
//! grid points, and the rate of `Surface::local` (sag, gradient and Hessian) on the grid,
//! one thread, repeated for about a second: along a spiral over the part (the planner's order:
//! each point in the cell of the one before or beside it) and at 10 000 sunflower points
//! (each far from the one before: a cache miss a lookup, the worst order).
//!
//! `cargo run --release -p spiralcam --example grid_figures [JOB.json …]` (default: the example
//! freeforms: XY polynomial, Zernike Standard, Q-2D, Chebyshev, and the sine grid, whose 1 mm
//! period is 8 grid steps, to show a surface the grid barely resolves).

use spiralcam::job::Job;
use spiralcam::surface::grid_sag::dat::GridData;
use spiralcam::surface::grid_sag::export::{GridExtent, sample};
use spiralcam::surface::{DataFile, GridSag, GridSagSpec, Surface};
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

/// Grid points per side.
const N: usize = 101;

/// The grid of `text` on a plane.
fn grid_sag(text: String) -> Result<GridSag, Box<dyn std::error::Error>> {
    Ok(GridSag::new(&GridSagSpec {
        data: DataFile {
            path: None,
            text: Some(text),
        },
        base: None,
    })?)
}

/// The largest |grid − exact| over a 201 × 201 sweep of the disc of radius `r`, mm.
fn largest_error(grid: &dyn Surface, exact: &dyn Surface, r: f64) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..=200 {
        for j in 0..=200 {
            let x = -r + 2.0 * r * (i as f64 + 0.37) / 201.0;
            let y = -r + 2.0 * r * (j as f64 + 0.61) / 201.0;
            if x.hypot(y) <= r
                && let (Ok(g), Ok(e)) = (grid.sag(x, y), exact.sag(x, y))
            {
                worst = worst.max((g - e).abs());
            }
        }
    }
    worst
}

/// 10 000 sunflower points over radius `r`: each far from the one before, so every lookup
/// misses the cache (the cells of a 101 × 101 grid weigh 1.3 MB).
fn sunflower(r: f64) -> Vec<(f64, f64)> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..10_000)
        .map(|i| {
            let rho = 0.999 * r * ((i as f64 + 0.5) / 10_000.0).sqrt();
            let (sn, cs) = (golden * i as f64).sin_cos();
            (rho * cs, rho * sn)
        })
        .collect()
}

/// The planner's order: a spiral from radius `r` to the centre, 0.01 mm a turn, 360 points a
/// turn (each point in the cell of the one before or beside it).
fn spiral(r: f64) -> Vec<(f64, f64)> {
    let per_rev = 360.0;
    let n = (r / 0.01 * per_rev) as usize;
    (0..=n)
        .map(|i| {
            let theta = std::f64::consts::TAU * i as f64 / per_rev;
            let rho = 0.999 * r * (1.0 - i as f64 / n as f64);
            (rho * theta.cos(), rho * theta.sin())
        })
        .collect()
}

/// `Surface::local` evaluations per second at `points`, repeated for about a second.
fn rate(s: &dyn Surface, points: &[(f64, f64)]) -> f64 {
    let (mut count, start) = (0usize, Instant::now());
    let mut sum = 0.0;
    while start.elapsed().as_secs_f64() < 1.0 {
        for &(x, y) in points {
            if let Ok(l) = s.local(x, y) {
                sum += l.z + l.zx + l.zy + l.zxx + l.zxy + l.zyy;
            }
        }
        count += points.len();
    }
    black_box(sum);
    count as f64 / start.elapsed().as_secs_f64()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs");
    let mut jobs: Vec<String> = std::env::args().skip(1).collect();
    if jobs.is_empty() {
        jobs = [
            "xy-polynomial-freeform.json",
            "zernike-standard.json",
            "q-2d-freeform.json",
            "chebyshev-freeform.json",
            "sinusoid-grid.json",
        ]
        .iter()
        .map(|f| dir.join(f).display().to_string())
        .collect();
    }
    for file in jobs {
        let mut job = Job::from_json(&std::fs::read_to_string(&file)?)?;
        let here = Path::new(&file).parent().unwrap_or(Path::new("."));
        job.load_files(|p| std::fs::read_to_string(here.join(p)).map_err(|e| e.to_string()))?;
        let exact = job.build_surface()?;
        let r = job.part_radius_mm();
        let grid = sample(exact.as_ref(), &GridExtent::square(N, N, 1.02 * r))?;
        let from_file = grid_sag(grid.to_dat())?;
        let mut zeroed = GridData::parse(&grid.to_dat())?;
        for n in &mut zeroed.nodes {
            (n.dz_dx, n.dz_dy, n.d2z_dxdy_per_mm) = (0.0, 0.0, 0.0);
        }
        let computed = grid_sag(zeroed.to_dat())?;
        println!(
            "{} (Ø{} mm, {N} × {N}, h {:.4} mm): largest sag error {:.3e} nm with the file's \
             derivatives, {:.3e} nm with computed ones; grid {:.1} M evaluations/s along the \
             spiral, {:.1} M/s at sunflower points (the closed form {:.1} M/s, {:.1} M/s)",
            job.name,
            2.0 * r,
            grid.dx_mm,
            largest_error(&from_file, exact.as_ref(), r) * 1e6,
            largest_error(&computed, exact.as_ref(), r) * 1e6,
            rate(&from_file, &spiral(r)) / 1e6,
            rate(&from_file, &sunflower(r)) / 1e6,
            rate(exact.as_ref(), &spiral(r)) / 1e6,
            rate(exact.as_ref(), &sunflower(r)) / 1e6
        );
    }
    Ok(())
}
