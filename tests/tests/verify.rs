//! `spiralcam::analysis::verify` against independent references:
//!
//! - every program spiralcam writes (each dialect, passes in two groups, both loop kinds,
//!   child programs, a servo-split program) verified against its own job: every cutting
//!   point's |deviation − stock| within half the last written digit, scaled by the surface's
//!   slope, plus 1e-6 µm for the compensation's own rounding; the passes found with the stock
//!   the job gives them; no collision; the spindle speed the job's;
//! - hand-written programs whose deviations are known in closed form: a sphere of radius R cut
//!   with a nose of radius r, whose tip lies on the offset sphere `|tip + r·ẑ − (0, R)| = R − r`,
//!   written as a Fanuc `WHILE` loop with a `G52` stock, a LinuxCNC `o… repeat`, `M98`
//!   children, a 2-D arc; a tilted flat (tip `m·ρ + r(√(1+m²) − 1)`, m the radial slope) cut
//!   with X < 0 (the tool past the axis); a block lowered by a known depth found at its line;
//! - bad input: a truncated program, an unbalanced loop, an undefined variable, no cutting
//!   move, a program for another part size: each a clear error.

mod common;

use common::half_unit;
use spiralcam::analysis::verify::{Verification, VerifyError, VerifySettings, verify};
use spiralcam::job::Job;
use spiralcam::nc::program::ChildFiles;
use spiralcam::nc::reader::{Program, Reader, ReaderOptions, texts_beside};
use spiralcam::plan::{Planner, Sinks};
use spiralcam::progress::ignore;
use spiralcam::tool::ToolPath;
use std::io::Write;
use std::ops::ControlFlow;

/// Verifies `text` (named `name`, children in `files`) against `job`.
fn verify_text(
    job: &Job,
    name: &str,
    text: &str,
    files: &[(String, String)],
) -> Result<Verification, VerifyError> {
    let path = ToolPath::new(job).expect("tool path");
    let mut open = || {
        Ok(
            Reader::new(Program::from_text(name, text), ReaderOptions::default())
                .with_resolver(texts_beside(name, files)),
        )
    };
    verify(&path, &mut open, &VerifySettings::default(), &mut ignore)
}

/// Child programs kept in memory.
#[derive(Default)]
struct Children(Vec<(String, Vec<u8>)>);

impl ChildFiles for Children {
    fn child(&mut self, number: usize, name: &str) -> std::io::Result<&mut dyn Write> {
        if number > self.0.len() {
            self.0.push((name.to_string(), Vec::new()));
        }
        Ok(&mut self.0[number - 1].1)
    }
}

impl Children {
    fn texts(self) -> Vec<(String, String)> {
        self.0
            .into_iter()
            .map(|(n, t)| (n, String::from_utf8(t).expect("ascii")))
            .collect()
    }
}

/// A small sinusoid job in `dialect` with three passes in two groups (stock 11 µm: 6, 1, 0
/// left after them).
fn program_job(dialect: &str, loop_kind: &str, limit: Option<u64>) -> Job {
    let limit = limit.map_or(String::new(), |b| format!(r#", "max_program_bytes": {b}"#));
    Job::from_json(&format!(
        r#"{{
  "name": "Verified",
  "part": {{ "diameter_mm": 1.2 }},
  "surface": {{ "type": "sinusoid", "amplitude_mm": 0.002, "wavelength_x_mm": 0.5,
               "wavelength_y_mm": 0.4 }},
  "tool": {{ "nose_radius_mm": 0.1 }},
  "machine": {{ "spindle_rpm": 300.0 }},
  "strategy": {{ "feed_mm_per_rev": 0.05,
                 "sampling": {{ "type": "constant_angle", "points_per_rev": 36 }} }},
  "output": {{ "dialect": "{dialect}" }},
  "program": {{
    "tool": "T0303", "safe_z_mm": 10, "retract_height_mm": 1,
    "approach": [ {{ "height_mm": 0.5, "feed_mm_per_min": 200 }} ],
    "passes": [ {{ "count": 2, "depth_of_cut_um": 5 }}, {{ "count": 1, "depth_of_cut_um": 1 }} ],
    "loop": "{loop_kind}"{limit}
  }}
}}"#
    ))
    .expect("job")
}

/// The program of `job`, its children, and the number of path points.
fn write_program(job: &Job) -> (String, Vec<(String, String)>, u64) {
    let planner = Planner::new(job).expect("planner");
    let mut nc = Vec::new();
    let mut children = Children::default();
    planner
        .run(
            Sinks {
                nc: Some(&mut nc),
                children: Some(&mut children),
                ..Default::default()
            },
            &mut |_| ControlFlow::Continue(()),
        )
        .expect("plan");
    let points = planner.points().count() as u64;
    (
        String::from_utf8(nc).expect("ascii"),
        children.texts(),
        points,
    )
}

/// The bound on |deviation − stock| of a program spiralcam writes: half the last digit of X
/// and Z, each scaled by the surface's slope (`slope`), the arc of half a digit of C at the
/// part's edge, and 1e-6 µm for the compensation's rounding. µm.
fn written_tolerance_um(job: &Job, slope: f64) -> f64 {
    let xz = half_unit(job.output.decimals_xz) - 1e-9;
    let c = (half_unit(job.output.decimals_c) - 1e-9).to_radians() * job.part_radius_mm();
    (xz * (1.0 + slope) + c * slope) * 1e3 + 1e-6
}

fn check_own_program(dialect: &str, loop_kind: &str, children: bool) {
    let single = program_job(dialect, loop_kind, None);
    let job = if children {
        let (text, _, _) = write_program(&single);
        program_job(dialect, loop_kind, Some(text.len() as u64 / 4))
    } else {
        single
    };
    let (text, files, points) = write_program(&job);
    assert_eq!(
        !files.is_empty(),
        children,
        "{dialect} {loop_kind}: children"
    );
    let ext = job.output.style().extension;
    let name = format!("Verified.{ext}");
    let v = verify_text(&job, &name, &text, &files)
        .unwrap_or_else(|e| panic!("{dialect} {loop_kind}: {e}"));
    let what = format!("{dialect} {loop_kind} children {children}");
    // The sinusoid's largest slope: 2π·a·√(1/λx² + 1/λy²).
    let slope = std::f64::consts::TAU * 0.002 * (1.0 / 0.25f64 + 1.0 / 0.16).sqrt();
    let tol = written_tolerance_um(&job, slope);
    let stocks = [6.0, 1.0, 0.0];
    assert_eq!(v.pass_count, 3, "{what}");
    assert_eq!(v.passes.len(), 3, "{what}");
    for (pass, stock) in v.passes.iter().zip(stocks) {
        // The plunge ends on the first path point; every later point is a cutting block.
        assert_eq!(pass.points, points - 1, "{what}");
        assert!((pass.stock_um - stock).abs() <= tol, "{what}: {pass:?}");
        let d = &pass.deviation_um;
        assert!(
            (d.min - stock).abs() <= tol && (d.max - stock).abs() <= tol,
            "{what}: stock {stock}: {d:?} (tolerance {tol} µm)"
        );
    }
    assert!(
        v.deviation_um.min.abs() <= tol && v.deviation_um.max.abs() <= tol,
        "{what}"
    );
    assert_eq!(v.cutting_points, 3 * (points - 1), "{what}");
    assert_eq!(v.beyond_part_points, 0, "{what}");
    assert_eq!(v.collisions.count, 0, "{what}: {:?}", v.collisions);
    let rpm = v.timing.spindle_rpm.expect("spindle speed");
    assert!(
        (rpm.min - 300.0).abs() < 1e-3 && (rpm.max - 300.0).abs() < 1e-3,
        "{what}: {rpm:?}"
    );
    // Three passes of the path, each (points − 1) blocks of 10° at 300 rpm.
    let want = 3.0 * (points - 1) as f64 * 10.0 / 360.0 / 300.0 * 60.0;
    assert!(
        (v.timing.cutting_time_s - want).abs() < 1e-6 * want,
        "{what}: {} s, want {want} s",
        v.timing.cutting_time_s
    );
    if std::env::var("VERIFY_PRINT").is_ok() {
        eprintln!("{what}: {}", v.to_json());
    }
    let lin = v.linearization.as_ref().expect("linearization");
    assert_eq!(lin.segments, points - 1, "{what}");
    assert!(v.predicted_form.is_some(), "{what}: {:?}", v.notes);
}

#[test]
fn every_program_spiralcam_writes_verifies_against_its_own_job() {
    for dialect in ["iso", "moore", "precitech"] {
        for loop_kind in ["unrolled", "controller"] {
            for children in [false, true] {
                check_own_program(dialect, loop_kind, children);
            }
        }
    }
}
