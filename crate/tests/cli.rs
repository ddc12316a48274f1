//! The command-line tool, run as a process: `plan` writes the NC program, the CSV and the report
//! (the same bytes as the library, the report's figures consistent with the files and the plan),
//! prints the report without `--report`; `analyse` prints the library's accuracy figures and
//! writes its maps; `sag` prints the library's sag and derivatives; bad
//! values exit 1 naming the field, missing files exit 1 naming the file, usage errors exit 2
//! with the usage; a failed plan leaves no output (nor `.partial`) behind.

use spiralcam::analysis::Analysis;
use spiralcam::job::Job;
use spiralcam::plan::{Planner, Sinks};
use std::ffi::OsStr;
use std::ops::ControlFlow;

mod common;
use common::{Scratch, spiralcam, stderr, stdout};

/// A small job: a lens array on a Ø1.2 mm part, 241 points.
const JOB: &str = r#"{
  "name": "cli-small",
  "part": { "diameter_mm": 1.2 },
  "surface": { "type": "lens_array", "lens_radius_mm": 0.6, "aperture_mm": 0.3, "pitch_mm": 0.3,
               "grid": "rectangular", "form": "concave" },
  "tool": { "nose_radius_mm": 0.1 },
  "machine": { "spindle_rpm": 450.0 },
  "strategy": { "feed_mm_per_rev": 0.05, "sampling": { "type": "constant_angle", "points_per_rev": 20 } },
  "output": { "dialect": "moore" }
}"#;

/// The fields the report documents.
const REPORT_FIELDS: [&str; 23] = [
    "job",
    "surface",
    "dialect",
    "points",
    "revolutions",
    "start_radius_mm",
    "nc_bytes",
    "cycle_time_s",
    "max_dz_dtheta_um_per_deg",
    "max_dz_dtheta_at",
    "surface_pv_um",
    "z_min_mm",
    "z_max_mm",
    "arc_end_contacts",
    "concave_zones",
    "shallow_concave_zones",
    "x_reversals",
    "max_x_acceleration_mm_s2",
    "max_x_acceleration_at",
    "two_way_loops",
    "two_way_loop_points",
    "first_two_way_loop_at",
    "warnings",
];

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

/// Checks a report against the library's plan of the same job and the NC file's size.
fn check_report(report: &serde_json::Value, job: &Job, nc_bytes: u64) {
    let obj = report.as_object().expect("report object");
    for f in REPORT_FIELDS {
        assert!(obj.contains_key(f), "report lacks {f}: {report}");
    }
    let planner = Planner::new(job).unwrap();
    let pts: Vec<_> = planner.points().map(|p| p.unwrap()).collect();
    let num = |f: &str| {
        report[f]
            .as_f64()
            .unwrap_or_else(|| panic!("{f}: {report}"))
    };
    assert_eq!(report["job"], job.name.as_str());
    assert_eq!(report["dialect"], job.output.style().name);
    assert_eq!(report["surface"], planner.surface().describe().as_str());
    assert_eq!(report["points"].as_u64(), Some(pts.len() as u64));
    assert_eq!(report["nc_bytes"].as_u64(), Some(nc_bytes));
    let revolutions = num("revolutions");
    assert!(close(revolutions, planner.spiral().revolutions(), 1e-15));
    assert!(close(
        num("start_radius_mm"),
        planner.spiral().start_radius_mm(),
        1e-15
    ));
    // The cycle time is the spindle's turning time: revolutions / rpm, in seconds.
    let rpm = job.machine.spindle_rpm;
    assert!(
        close(num("cycle_time_s"), revolutions / rpm * 60.0, 1e-12),
        "{} vs {}",
        num("cycle_time_s"),
        revolutions / rpm * 60.0
    );
    let z_min = pts.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    let z_max = pts.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(num("z_min_mm"), z_min);
    assert_eq!(num("z_max_mm"), z_max);
    let s_min = pts
        .iter()
        .map(|p| p.contact[2])
        .fold(f64::INFINITY, f64::min);
    let s_max = pts
        .iter()
        .map(|p| p.contact[2])
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(close(num("surface_pv_um"), (s_max - s_min) * 1e3, 1e-12));
    let slope = pts
        .windows(2)
        .map(|w| ((w[1].z - w[0].z) / (w[1].theta - w[0].theta).to_degrees()).abs())
        .fold(0.0, f64::max);
    assert!(close(num("max_dz_dtheta_um_per_deg"), slope * 1e3, 1e-12));
    let arc_end = pts.iter().filter(|p| p.at_arc_end).count() as u64;
    assert_eq!(report["arc_end_contacts"].as_u64(), Some(arc_end));
    assert!(report["concave_zones"].is_array());
    assert!(report["warnings"].is_array());
}

/// The library's NC program and CSV for a job.
fn library_output(job: &Job) -> (Vec<u8>, Vec<u8>) {
    let (mut nc, mut csv) = (Vec::new(), Vec::new());
    Planner::new(job)
        .unwrap()
        .run(
            Sinks {
                nc: Some(&mut nc),
                csv: Some(&mut csv),
                display: None,
                ..Default::default()
            },
            &mut |_| ControlFlow::Continue(()),
        )
        .unwrap();
    (nc, csv)
}

#[test]
fn plan_writes_the_program_the_table_and_the_report() {
    let dir = Scratch::new("plan");
    let job_path = dir.write("job.json", JOB);
    let (nc, csv, report) = (
        dir.path("out.nc"),
        dir.path("out.csv"),
        dir.path("report.json"),
    );
    let o = spiralcam(&[
        OsStr::new("plan"),
        job_path.as_os_str(),
        OsStr::new("--nc"),
        nc.as_os_str(),
        OsStr::new("--csv"),
        csv.as_os_str(),
        OsStr::new("--report"),
        report.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o), "", "the report went to its file");
    assert_eq!(
        dir.files(),
        ["job.json", "out.csv", "out.nc", "report.json"]
    );
    let job = Job::from_json(JOB).unwrap();
    let (lib_nc, lib_csv) = library_output(&job);
    assert!(
        std::fs::read(&nc).unwrap() == lib_nc,
        "NC differs from the library's"
    );
    assert!(
        std::fs::read(&csv).unwrap() == lib_csv,
        "CSV differs from the library's"
    );
    let text = std::fs::read_to_string(&report).unwrap();
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    check_report(&value, &job, std::fs::metadata(&nc).unwrap().len());
    let rows = std::fs::read_to_string(&csv).unwrap().lines().count() as u64 - 1;
    assert_eq!(value["points"].as_u64(), Some(rows));
}

/// A split job: the program (with W), the servo's table, its gridded table (PMAC text and the
/// CSV beside it) and the report with its dynamics are the library's `run_with_dynamics`
/// output, byte for byte.
#[test]
fn plan_writes_the_split_program_and_the_servo_tables() {
    let mut job = Job::from_json(JOB).unwrap();
    job.machine = spiralcam::job::machine::presets()[2].machine(job.machine.spindle_rpm);
    job.strategy.split = Some(spiralcam::job::SplitSpec::Auto);
    let dir = Scratch::new("split");
    let job_path = dir.write("job.json", &job.to_json());
    let (nc, fts, report) = (dir.path("out.nc"), dir.path("fts.csv"), dir.path("r.json"));
    let grid = dir.path("grid.pmc");
    let o = spiralcam(&[
        OsStr::new("plan"),
        job_path.as_os_str(),
        OsStr::new("--nc"),
        nc.as_os_str(),
        OsStr::new("--fts-csv"),
        fts.as_os_str(),
        OsStr::new("--fts-table"),
        grid.as_os_str(),
        OsStr::new("--report"),
        report.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (mut lib_nc, mut lib_fts) = (Vec::new(), Vec::new());
    let (mut lib_grid, mut lib_grid_csv) = (Vec::new(), Vec::new());
    let lib_report = Planner::new(&job)
        .unwrap()
        .run_with_dynamics(
            Sinks {
                nc: Some(&mut lib_nc),
                fts_table: Some(&mut lib_fts),
                fts_grid: Some(&mut lib_grid),
                fts_grid_csv: Some(&mut lib_grid_csv),
                ..Default::default()
            },
            &mut |_| ControlFlow::Continue(()),
        )
        .unwrap();
    assert!(std::fs::read(&nc).unwrap() == lib_nc, "NC differs");
    assert!(
        std::fs::read(&fts).unwrap() == lib_fts,
        "servo table differs"
    );
    assert!(std::fs::read(&grid).unwrap() == lib_grid, "grid differs");
    assert!(
        std::fs::read(dir.path("grid.csv")).unwrap() == lib_grid_csv,
        "grid CSV differs"
    );
    let figures = &lib_report.dynamics.as_ref().unwrap().fts_grid;
    let figures = figures.as_ref().expect("the grid's figures");
    assert_eq!(figures.pmac_bytes, lib_grid.len() as u64);
    assert_eq!(figures.csv_bytes, lib_grid_csv.len() as u64);
    assert!(String::from_utf8(lib_nc).unwrap().contains(" W"));
    // The command line's report is the library's, with the estimate it was admitted on.
    let mut written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let estimate = written.as_object_mut().unwrap().remove("estimate");
    assert_eq!(estimate.unwrap()["points"], lib_report.points);
    let library: serde_json::Value = serde_json::from_str(&lib_report.to_json()).unwrap();
    assert!(written == library, "the reports differ");
}

#[test]
fn plan_without_report_prints_it() {
    let dir = Scratch::new("stdout");
    let job_path = dir.write("job.json", JOB);
    let o = spiralcam(&[OsStr::new("plan"), job_path.as_os_str()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let value: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("report JSON");
    let job = Job::from_json(JOB).unwrap();
    // Without --nc the program is still generated, into a counter: its size is the library's.
    check_report(&value, &job, library_output(&job).0.len() as u64);
    assert_eq!(dir.files(), ["job.json"]);
}

#[test]
fn analyse_prints_the_library_figures_and_writes_the_maps() {
    let dir = Scratch::new("analyse");
    let job_path = dir.write("job.json", JOB);
    let prefix = dir.path("acc");
    let o = spiralcam(&[
        OsStr::new("analyse"),
        job_path.as_os_str(),
        OsStr::new("--maps"),
        prefix.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let printed: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("analysis JSON");
    let job = Job::from_json(JOB).unwrap();
    let planner = Planner::new(&job).unwrap();
    // The command line's maps have 256 samples per side.
    let analysis = Analysis::run(&planner, 256, &mut |_| ControlFlow::Continue(())).unwrap();
    let expected: serde_json::Value = serde_json::from_str(&analysis.to_json()).unwrap();
    assert_eq!(printed, expected);
    assert_eq!(printed["linearization"]["segments"], 240);
    assert!(
        printed["predicted_form"]["cusp_height_um"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    let form = analysis.form_map();
    let maps = [
        (
            "acc-linearization.csv",
            "error_um",
            analysis.linearization_map(),
        ),
        ("acc-form.csv", "error_um", &*form),
        (
            "acc-clearance.csv",
            "required_clearance_deg",
            analysis.clearance_map(),
        ),
    ];
    for (file, value, map) in maps {
        let text = std::fs::read_to_string(dir.path(file)).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some(format!("x_mm,y_mm,{value}").as_str()));
        let rows: Vec<Vec<f64>> = lines
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect();
        let defined = map.values.iter().filter(|v| !v.is_nan()).count();
        assert!(defined > 0, "{file}: empty map");
        assert_eq!(rows.len(), defined, "{file}");
        // Each row is a defined sample at its position, printed to 6 decimals.
        for r in &rows {
            let k = map.index_of(r[0], r[1]).unwrap();
            assert!((map.values[k] - r[2]).abs() <= 5e-7, "{file}: {r:?}");
        }
    }
}

#[test]
fn sag_prints_the_library_values() {
    let dir = Scratch::new("sag");
    let job = r#"{"name":"sag","part":{"diameter_mm":8},
        "surface":{"type":"xy_polynomial","base":{"radius_mm":-30,"conic":-0.5},"norm_radius_mm":4,
                   "terms":[{"x":2,"y":1,"coefficient_mm":0.003},{"x":0,"y":3,"coefficient_mm":-0.001}]},
        "tool":{"nose_radius_mm":0.2},"machine":{"spindle_rpm":100},
        "strategy":{"feed_mm_per_rev":0.01,"sampling":{"type":"constant_angle","points_per_rev":100}}}"#;
    let job_path = dir.write("job.json", job);
    let points = [
        (0.0, 0.0),
        (1.25, -2.5),
        (-3.0, 0.7),
        (3.9, 0.1),
        (1e-3, -1e-3),
    ];
    let mut csv = String::from("x_mm,y_mm\n# a comment\n\n");
    for (x, y) in points {
        csv.push_str(&format!("{x}, {y}\n"));
    }
    let at = dir.write("points.csv", &csv);
    let o = spiralcam(&[
        OsStr::new("sag"),
        job_path.as_os_str(),
        OsStr::new("--at"),
        at.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let mut lines = out.lines();
    assert_eq!(
        lines.next(),
        Some("x_mm,y_mm,z_mm,dz_dx,dz_dy,d2z_dx2_per_mm,d2z_dxdy_per_mm,d2z_dy2_per_mm")
    );
    let surface = Job::from_json(job)
        .unwrap()
        .surface
        .build(4.0)
        .expect("surface");
    let mut n = 0;
    for (line, (x, y)) in lines.zip(points) {
        let v: Vec<f64> = line.split(',').map(|f| f.parse().unwrap()).collect();
        assert_eq!((v[0], v[1]), (x, y), "{line}");
        let l = surface.local(x, y).unwrap();
        let lib = [l.z, l.zx, l.zy, l.zxx, l.zxy, l.zyy];
        for (printed, want) in v[2..].iter().zip(lib) {
            // 16 significant digits ({:.15e}): within half a unit of the 16th.
            assert!(
                (printed - want).abs() <= 1e-15 * want.abs(),
                "({x}, {y}): printed {printed}, library {want}"
            );
        }
        n += 1;
    }
    assert_eq!(n, points.len());
    // A point where the surface is undefined fails, naming the radius.
    let bad = dir.write("bad.csv", "x_mm,y_mm\n1,1\n40,0\n");
    let sphere = dir.write(
        "sphere.json",
        &job.replace(
            r#""base":{"radius_mm":-30,"conic":-0.5}"#,
            r#""base":{"radius_mm":-30}"#,
        ),
    );
    let o = spiralcam(&[
        OsStr::new("sag"),
        sphere.as_os_str(),
        OsStr::new("--at"),
        bad.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("undefined at radius 40 mm"),
        "{}",
        stderr(&o)
    );
    let garbage = dir.write("garbage.csv", "x_mm,y_mm\n1,2\nthree,4\n");
    let o = spiralcam(&[
        OsStr::new("sag"),
        job_path.as_os_str(),
        OsStr::new("--at"),
        garbage.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("line 3"), "{}", stderr(&o));
}

/// Runs `plan` on a job and expects exit 1 with `message` on stderr.
fn expect_failure(dir: &Scratch, job: &str, message: &str) {
    let job_path = dir.write("bad.json", job);
    let nc = dir.path("bad.nc");
    let o = spiralcam(&[
        OsStr::new("plan"),
        job_path.as_os_str(),
        OsStr::new("--nc"),
        nc.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{message}: {}", stderr(&o));
    assert!(
        stderr(&o).contains(message),
        "expected {message:?} in {:?}",
        stderr(&o)
    );
    assert!(!nc.exists());
}

#[test]
fn bad_values_exit_1_naming_the_field() {
    let dir = Scratch::new("fields");
    let cases = [
        (
            JOB.replace(r#""nose_radius_mm": 0.1"#, r#""nose_radius_mm": -1"#),
            "tool.nose_radius_mm = -1: must be a finite number ≥ 0",
        ),
        (
            JOB.replace(r#""diameter_mm": 1.2"#, r#""diameter_mm": 0"#),
            "part.diameter_mm = 0: must be a finite number > 0",
        ),
        (
            JOB.replace(r#""feed_mm_per_rev": 0.05"#, r#""feed_mm_per_rev": -0.05"#),
            "strategy.feed_mm_per_rev = -0.05",
        ),
        (
            JOB.replace(r#""points_per_rev": 20"#, r#""points_per_rev": 2"#),
            "strategy.sampling.points_per_rev = 2",
        ),
        (
            JOB.replace(r#""aperture_mm": 0.3"#, r#""aperture_mm": 0.5"#),
            "surface.aperture_mm = 0.5",
        ),
        (
            JOB.replace(
                r#""dialect": "moore""#,
                r#""dialect": "moore", "x_sign": 3"#,
            ),
            "output.x_sign = 3: must be 1 or -1",
        ),
        (
            JOB.replace(r#""spindle_rpm": 450.0"#, r#""spindle_rpm": 0"#),
            "machine.spindle_rpm = 0",
        ),
        (
            JOB.replace(r#""nose_radius_mm""#, r#""nose_radius""#),
            "unknown field `nose_radius`",
        ),
    ];
    for (job, message) in cases {
        expect_failure(&dir, &job, message);
    }
    // The syntax error names the file.
    expect_failure(&dir, "{ not json", "bad.json: job: ");
    assert_eq!(dir.files(), ["bad.json"]);
}

/// A gridded table finer than its bound: exit 1 naming the tolerance, and no file left behind.
#[test]
fn a_grid_beyond_its_bound_exits_1_leaving_nothing() {
    let mut job = Job::from_json(JOB).unwrap();
    job.machine = spiralcam::job::machine::presets()[2].machine(job.machine.spindle_rpm);
    job.strategy.split = Some(spiralcam::job::SplitSpec::Auto);
    job.output.fts_grid = Some(spiralcam::job::FtsGridSpec {
        tolerance_um: 1e-4,
        ..Default::default()
    });
    let dir = Scratch::new("grid-bound");
    let job_path = dir.write("job.json", &job.to_json());
    let (nc, grid) = (dir.path("out.nc"), dir.path("grid.pmc"));
    let o = spiralcam(&[
        OsStr::new("plan"),
        job_path.as_os_str(),
        OsStr::new("--nc"),
        nc.as_os_str(),
        OsStr::new("--fts-table"),
        grid.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("output.fts_grid.tolerance_um = 0.0001: needs "),
        "{}",
        stderr(&o)
    );
    assert_eq!(dir.files(), ["job.json"]);
}

#[test]
fn missing_files_exit_1_naming_the_file() {
    let dir = Scratch::new("missing");
    let absent = dir.path("absent.json");
    let o = spiralcam(&[OsStr::new("plan"), absent.as_os_str()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains(&absent.display().to_string()),
        "{}",
        stderr(&o)
    );
    let job_path = dir.write("job.json", JOB);
    let points = dir.path("absent.csv");
    let o = spiralcam(&[
        OsStr::new("sag"),
        job_path.as_os_str(),
        OsStr::new("--at"),
        points.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains(&points.display().to_string()),
        "{}",
        stderr(&o)
    );
    // An output in a directory that does not exist.
    let nowhere = dir.path("no/such/dir/out.nc");
    let o = spiralcam(&[
        OsStr::new("plan"),
        job_path.as_os_str(),
        OsStr::new("--nc"),
        nowhere.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("no/such/dir/out.nc"), "{}", stderr(&o));
}

#[test]
fn usage_errors_exit_2_with_the_usage() {
    let dir = Scratch::new("usage");
    let job = dir.write("job.json", JOB);
    let job = job.to_str().unwrap();
    let cases: [(&[&str], &str); 10] = [
        (&[], "expected a command"),
        (&["frobnicate"], "expected a command"),
        (&["plan"], "missing JOB.json"),
        (&["plan", job, "--bogus", "x"], "unknown option --bogus"),
        (&["plan", job, "--nc"], "--nc needs a file name"),
        (&["sag", job], "sag needs --at"),
        (&["sag", job, "--nc", "x"], "unknown option --nc"),
        (
            &["plan", job, "--fts-csv", "t.csv"],
            "--fts-csv needs a split path",
        ),
        (
            &["plan", job, "--fts-table", "t.pmc"],
            "--fts-table needs a split path",
        ),
        (
            &["plan", job, "--fts-table", "t.csv"],
            "--fts-table (its CSV) t.csv: the same file as --fts-table",
        ),
    ];
    for (args, message) in cases {
        let o = spiralcam(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert!(e.contains(message), "{args:?}: {e}");
        assert!(e.contains("usage:"), "{args:?}: {e}");
        assert!(e.contains("spiralcam plan JOB.json"), "{args:?}: {e}");
    }
    assert_eq!(dir.files(), ["job.json"]);
    let o = spiralcam(&["--help"]);
    assert!(o.status.success());
    assert!(stdout(&o).contains("usage:"));
    let o = spiralcam(&["--version"]);
    assert!(o.status.success());
    assert_eq!(
        stdout(&o).trim(),
        format!("spiralcam {}", env!("CARGO_PKG_VERSION"))
    );
}

#[test]
fn a_failed_plan_leaves_no_output_behind() {
    // A sphere of radius 4 mm on a Ø10 mm part: undefined from the first point on.
    let dir = Scratch::new("failed");
    let job = JOB
        .replace(r#""diameter_mm": 1.2"#, r#""diameter_mm": 10"#)
        .replace(
            r#"{ "type": "lens_array", "lens_radius_mm": 0.6, "aperture_mm": 0.3, "pitch_mm": 0.3,
               "grid": "rectangular", "form": "concave" }"#,
            r#"{ "type": "asphere", "radius_mm": 4 }"#,
        );
    assert!(job.contains("asphere"));
    let job_path = dir.write("job.json", &job);
    let (nc, csv, report) = (
        dir.path("out.nc"),
        dir.path("out.csv"),
        dir.path("report.json"),
    );
    let args = [
        OsStr::new("plan"),
        job_path.as_os_str(),
        OsStr::new("--nc"),
        nc.as_os_str(),
        OsStr::new("--csv"),
        csv.as_os_str(),
        OsStr::new("--report"),
        report.as_os_str(),
    ];
    let o = spiralcam(&args);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("even asphere is undefined at radius"), "{e}");
    assert!(e.contains("rim at radius 4 mm"), "{e}");
    assert_eq!(dir.files(), ["job.json"], "no output, no .partial");
    // A program already there is left as it was.
    std::fs::write(&nc, "previous program\n").unwrap();
    let o = spiralcam(&args);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(std::fs::read_to_string(&nc).unwrap(), "previous program\n");
    assert_eq!(dir.files(), ["job.json", "out.nc"]);
}
