//! `spiralcam verify` run as a process: a program `spiralcam plan` wrote (Moore style, child
//! programs beside it, a controller loop of two passes) verified against its job: the report's
//! passes, stock and deviation within half the last digit, the map written; a truncated program
//! exits 1 naming its file and line with nothing written; a missing `--nc` exits 2.

use std::ffi::OsStr;

mod common;
use common::{Scratch, spiralcam, stderr};

const JOB: &str = r#"{
  "name": "cli-verify",
  "part": { "diameter_mm": 2.0 },
  "surface": { "type": "asphere", "radius_mm": 12.0, "conic": -0.5 },
  "tool": { "nose_radius_mm": 0.2 },
  "machine": { "spindle_rpm": 450.0 },
  "strategy": { "feed_mm_per_rev": 0.02, "sampling": { "type": "constant_angle", "points_per_rev": 90 } },
  "output": { "dialect": "moore" },
  "program": { "passes": [ { "count": 2, "depth_of_cut_um": 4 } ], "loop": "controller",
               "max_program_bytes": 20000 }
}"#;

#[test]
fn verify_reports_the_passes_and_writes_the_map() {
    let dir = Scratch::new("cli-verify");
    let job = dir.write("job.json", JOB);
    let nc = dir.path("prog.nc");
    let out = spiralcam(&[
        OsStr::new("plan"),
        job.as_os_str(),
        "--nc".as_ref(),
        nc.as_os_str(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        dir.path("prog-1.nc").exists(),
        "children beside the program"
    );
    let report = dir.path("r.json");
    let maps = dir.path("m");
    let out = spiralcam(&[
        OsStr::new("verify"),
        job.as_os_str(),
        "--nc".as_ref(),
        nc.as_os_str(),
        "--report".as_ref(),
        report.as_os_str(),
        "--maps".as_ref(),
        maps.as_os_str(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).expect("report")).expect("json");
    assert_eq!(r["pass_count"], 2);
    // Half a nanometre of Z, and of X times the asphere's slope (< 0.1 within Ø2).
    let tol = 0.5e-3 * 1.1 + 1e-6;
    for (pass, stock) in r["passes"].as_array().unwrap().iter().zip([4.0, 0.0]) {
        let d = &pass["deviation_um"];
        for k in ["min", "max"] {
            let v = d[k].as_f64().unwrap();
            assert!((v - stock).abs() <= tol, "{k} {v} stock {stock}");
        }
    }
    assert_eq!(r["collisions"]["count"], 0);
    let map = std::fs::read_to_string(dir.path("m-deviation.csv")).expect("map");
    assert!(map.starts_with("x_mm,y_mm,deviation_um\n"));
    let rows: Vec<f64> = map
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
        .collect();
    assert!(
        rows.len() > 1000 && rows.iter().all(|v| v.abs() <= tol),
        "{}",
        rows.len()
    );
}

#[test]
fn a_truncated_program_exits_1_and_a_missing_nc_exits_2() {
    let dir = Scratch::new("cli-verify-bad");
    let job = dir.write("job.json", JOB);
    let nc = dir.write(
        "cut.nc",
        "G71 G18 G90\nG0 Z1\nG0 X1 C0\nG1 Z0 F10\nC10 X0.99 Z0\n",
    );
    let report = dir.path("r.json");
    let out = spiralcam(&[
        OsStr::new("verify"),
        job.as_os_str(),
        "--nc".as_ref(),
        nc.as_os_str(),
        "--report".as_ref(),
        report.as_os_str(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let e = stderr(&out);
    assert!(e.contains("cut.nc"), "{e}");
    assert!(!report.exists());
    let out = spiralcam(&[OsStr::new("verify"), job.as_os_str()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--nc"));
}
