//! Figures of HCAA, adaptive and uniform constant-angle sampling (paper 000, "HCAA method"):
//! points and NC size at PVtol 1 µm and 0.1 µm on the compound eye and the lens array jobs, and
//! the linearization error of each path checked by `linearization::analyse`.
//!
//! `cargo run --release -p spiralcam --example hcaa_figures [scale] [job]`: `scale` (default 1)
//! multiplies the part diameter, to get figures quickly on a smaller part; `job` (a part of the
//! file name, e.g. `lens`) limits the run to one job.

use spiralcam::analysis::linearization::analyse;
use spiralcam::job::Job;
use spiralcam::job::Sampling;
use spiralcam::path::hcaa;
use spiralcam::plan::{Planner, Sinks};
use std::ops::ControlFlow;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scale: f64 = std::env::args().nth(1).map_or(Ok(1.0), |s| s.parse())?;
    let only = std::env::args().nth(2).unwrap_or_default();
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/jobs/");
    println!("job | PVtol µm | sampling | points | NC bytes | overcut µm | undercut µm | zones");
    let jobs = ["compound-eye-paper000.json", "lens-array-paper004.json"];
    for name in jobs.into_iter().filter(|n| n.contains(&only)) {
        let mut job = Job::from_json(&std::fs::read_to_string(format!("{dir}{name}"))?)?;
        job.part.diameter_mm *= scale;
        for tol in [1.0, 0.1] {
            let mut rows = vec![
                (
                    "hcaa",
                    Sampling::Hcaa {
                        pv_tolerance_um: tol,
                    },
                ),
                (
                    "adaptive",
                    Sampling::Adaptive {
                        pv_tolerance_um: tol,
                    },
                ),
            ];
            job.strategy.sampling = rows[1].1.clone();
            let p = Planner::new(&job)?;
            let bands = hcaa::bands(
                p.surface(),
                &|rho, theta| p.tip_height(rho, theta),
                (
                    job.outer_radius_mm(),
                    job.strategy.feed_mm_per_rev,
                    tol * 1e-3,
                ),
                &mut spiralcam::progress::ignore,
            )?;
            let h = bands.hcaa();
            let n = bands.uniform_points_per_rev();
            rows.push(("uniform", Sampling::ConstantAngle { points_per_rev: n }));
            for (label, sampling) in rows {
                job.strategy.sampling = sampling;
                let p = Planner::new(&job)?;
                let report = p.run(Sinks::default(), &mut |_| ControlFlow::Continue(()))?;
                let lin = analyse(&p, 16, |_| ())?;
                let zones = match label {
                    "hcaa" => format!(
                        "r1 {:.4} mm, r2 {:.4} mm, outer {:.3}°, ΔS {:.5} mm, inner {:.3}°",
                        h.outer_transition_mm,
                        h.inner_transition_mm,
                        h.outer_step_rad.to_degrees(),
                        h.arc_length_mm,
                        h.inner_step_rad.to_degrees()
                    ),
                    "adaptive" => format!("{} zones", p.spiral().zones().len()),
                    _ => format!("{n} points/rev"),
                };
                println!(
                    "{} | {tol} | {label} | {} | {} | {:.4} | {:.4} | {zones}",
                    job.name,
                    lin.segments + 1,
                    report.nc_bytes,
                    lin.max_overcut_um,
                    lin.max_undercut_um
                );
            }
        }
    }
    Ok(())
}
