//! Every job is answered in bounded time, memory and disk (issue 11): the cases found from
//! outside, each with its answer — refused at once with the field, the figures and what would
//! do, or planned — and nothing left behind: a plan stopped by a signal, a usage error found
//! late, outputs that collide or cannot be written.

mod common;

use common::{Scratch, spiralcam, stderr, stdout};
use serde_json::{Value, json};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// An example job of `crate/jobs` as JSON.
fn example(name: &str) -> Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("jobs/{name}.json"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Runs `plan` on `job` written into `dir` with `--nc out.nc`; returns the exit code, the
/// message and the time it took.
fn plan(dir: &Scratch, job: &Value, extra: &[&str]) -> (Option<i32>, String, Duration) {
    let path = dir.write("job.json", &job.to_string());
    let nc = dir.path("out.nc");
    let start = Instant::now();
    let mut args = vec![
        "plan".to_string(),
        path.display().to_string(),
        "--nc".into(),
        nc.display().to_string(),
    ];
    args.extend(extra.iter().map(|s| s.to_string()));
    let o = spiralcam(&args);
    (o.status.code(), stderr(&o), start.elapsed())
}

/// `plan` refuses `job` within a second with exit 1 and a message containing `expected`, and
/// leaves only the job file.
fn refused(job: &Value, expected: &str) {
    let dir = Scratch::new("refused");
    let (code, message, took) = plan(&dir, job, &[]);
    assert_eq!(code, Some(1), "{message}");
    assert!(message.contains(expected), "{message}");
    assert!(took < Duration::from_secs(5), "{took:?}: {message}");
    assert_eq!(dir.files(), ["job.json"], "{message}");
}

#[test]
fn a_point_count_that_would_wrap_is_refused_with_the_feed_that_would_do() {
    let mut job = example("tilted-flat");
    for feed in [9.7e-17, 1e-300] {
        job["strategy"]["feed_mm_per_rev"] = json!(feed);
        refused(&job, "strategy.feed_mm_per_rev = ");
        // 360 points/rev over a 10 mm radius: 3.6e-6 mm/rev keeps the count under 1e9.
        refused(&job, "a feed of at least 3.600004e-6 mm/rev");
    }
    job["strategy"]["feed_mm_per_rev"] = json!(9.7e-17);
    refused(&job, "= 9.7e-17: gives about 3.71134e19 points");
}

#[test]
fn physical_nonsense_is_a_validation_error() {
    let mut job = example("sinusoid-grid");
    job["surface"]["wavelength_x_mm"] = json!(1e-9);
    refused(
        &job,
        "surface.wavelength_x_mm = 1e-9: must be a length of at least 1e-6 mm",
    );
    let mut job = example("sinusoid-grid");
    job["part"]["diameter_mm"] = json!(2.0);
    job["tool"]["nose_radius_mm"] = json!(90.0);
    refused(
        &job,
        "tool.nose_radius_mm = 90: must not exceed the part's diameter 2 mm",
    );
    for sampling in [
        json!({"type": "hcaa", "pv_tolerance_um": 1.0}),
        json!({"type": "constant_angle", "points_per_rev": 720}),
    ] {
        let mut job = example("zernike-standard");
        job["surface"]["norm_radius_mm"] = json!(1e-300);
        job["strategy"]["sampling"] = sampling;
        refused(&job, "surface.norm_radius_mm = 1e-300: must be a length");
    }
    let mut job = example("lens-array-paper004");
    job["machine"]["spindle_rpm"] = json!(1e308);
    refused(&job, "machine.spindle_rpm = 1e308: at most 100000 rev/min");
}

#[test]
fn an_estimate_too_costly_for_hcaa_is_refused_before_it_runs() {
    // A 1 µm sine on a 8 mm part: the first pass alone would compensate 512 circles of 65 536
    // samples three times.
    let mut job = example("sinusoid-grid");
    job["surface"]["wavelength_x_mm"] = json!(0.001);
    job["surface"]["wavelength_y_mm"] = json!(0.001);
    job["strategy"]["sampling"] = json!({"type": "hcaa", "pv_tolerance_um": 0.1});
    refused(&job, "strategy.sampling.type = ");
    refused(&job, "compensated heights in its first pass");
}

#[test]
fn a_job_whose_files_would_fill_the_disk_is_refused_with_their_sizes() {
    // Paper 004's lens array at 1800 points/rev and 10 nm feed: 9e8 points.
    let mut job = example("lens-array-paper004");
    job["strategy"]["feed_mm_per_rev"] = json!(1e-5);
    job["strategy"]["sampling"] = json!({"type": "constant_angle", "points_per_rev": 1800});
    refused(&job, "gives about 9e8 points and 47.");
    refused(
        &job,
        "above the limit of 4.00 GB (--max-output-gb raises it)",
    );
    // The limit can be lowered, and raised back.
    let dir = Scratch::new("limit");
    let small = example("lens-array-paper004");
    let (code, message, _) = plan(&dir, &small, &["--max-output-gb", "0.001"]);
    assert_eq!(code, Some(1), "{message}");
    assert!(message.contains("above the limit of 1.00 MB"), "{message}");
    let (code, message, _) = plan(&dir, &small, &["--max-points", "1000"]);
    assert_eq!(code, Some(1), "{message}");
    assert!(
        message.contains("at most 1000: a feed of at least"),
        "{message}"
    );
    assert_eq!(dir.files(), ["job.json"]);
}

#[test]
fn data_files_are_read_only_if_regular() {
    let dir = Scratch::new("devices");
    let mut job = example("scattered-lens-array");
    job["surface"]["data"]["path"] = json!("/dev/zero");
    let (code, message, took) = plan(&dir, &job, &[]);
    assert_eq!(code, Some(1), "{message}");
    assert!(
        message.contains("surface.data.path = /dev/zero: cannot be read: is not a regular file"),
        "{message}"
    );
    assert!(took < Duration::from_secs(5));
    // A FIFO with no writer would block a plain open.
    let fifo = dir.path("points.fifo");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    job["surface"]["data"]["path"] = json!("points.fifo");
    let (code, message, took) = plan(&dir, &job, &[]);
    assert_eq!(code, Some(1), "{message}");
    assert!(message.contains("is not a regular file"), "{message}");
    assert!(took < Duration::from_secs(5));
    // A directory.
    job["surface"]["data"]["path"] = json!(".");
    let (_, message, _) = plan(&dir, &job, &[]);
    assert!(message.contains("is a directory"), "{message}");
}

#[test]
fn string_fields_have_a_length_limit() {
    let mut job = example("lens-array-paper004");
    job["name"] = json!("x".repeat(5_000_000));
    refused(
        &job,
        "name = xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx… (5000000 characters)",
    );
    job["name"] = json!("x".repeat(128));
    let dir = Scratch::new("name");
    let (code, message, _) = plan(&dir, &job, &["--max-points", "1e9"]);
    assert_eq!(code, Some(0), "{message}");
}

/// Starts `plan` on a job long enough to stop (millions of points), waits until its first
/// temporary exists, sends `signal` and returns the exit code and the files left.
fn stopped_by(signal: &str) -> (Option<i32>, Vec<String>) {
    let dir = Scratch::new(&format!("signal-{signal}"));
    let mut job = example("lens-array-paper004");
    job["strategy"]["feed_mm_per_rev"] = json!(0.0005);
    let path = dir.write("job.json", &job.to_string());
    let mut child = Command::new(env!("CARGO_BIN_EXE_spiralcam"))
        .arg("plan")
        .arg(&path)
        .arg("--nc")
        .arg(dir.path("out.nc"))
        .arg("--csv")
        .arg(dir.path("out.csv"))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !dir.files().iter().any(|f| f.ends_with(".partial")) {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "no temporary appeared"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(200));
    let pid = child.id().to_string();
    assert!(
        Command::new("kill")
            .args([signal, &pid])
            .status()
            .unwrap()
            .success()
    );
    let stop = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(stop.elapsed() < Duration::from_secs(10), "not stopped");
        std::thread::sleep(Duration::from_millis(20));
    };
    (status.code(), dir.files())
}

#[test]
fn a_signal_stops_the_plan_and_leaves_nothing_behind() {
    assert_eq!(
        stopped_by("-INT"),
        (Some(130), vec!["job.json".to_string()])
    );
    assert_eq!(
        stopped_by("-TERM"),
        (Some(143), vec!["job.json".to_string()])
    );
}

#[test]
fn outputs_are_checked_before_planning() {
    let dir = Scratch::new("outputs");
    let job = example("lens-array-paper004");
    let path = dir.write("job.json", &job.to_string());
    let job_arg = path.display().to_string();
    let file = |f: &str| dir.path(f).display().to_string();
    let run = |args: &[String]| {
        let start = Instant::now();
        let o = spiralcam(args);
        (o.status.code(), stderr(&o), start.elapsed())
    };
    let cases: Vec<(Vec<String>, i32, &str)> = vec![
        // The same file twice: the command line is wrong.
        (
            vec!["--nc".into(), file("x"), "--csv".into(), file("x")],
            2,
            "the same file as --nc",
        ),
        (
            vec!["--nc".into(), file("x.nc"), "--report".into(), file("x.nc")],
            2,
            "the same file as --nc",
        ),
        // The job itself as an output.
        (
            vec!["--nc".into(), job_arg.clone()],
            2,
            "is an input of the job",
        ),
        // A report in a folder that does not exist: refused before the plan writes the NC.
        (
            vec![
                "--nc".into(),
                file("a.nc"),
                "--report".into(),
                file("no/r.json"),
            ],
            1,
            "does not exist",
        ),
        // A directory.
        (
            vec!["--nc".into(), dir.0.display().to_string()],
            1,
            "is a directory",
        ),
        // --fts-csv on a job without a split: a usage error found before any file exists.
        (
            vec![
                "--nc".into(),
                file("a.nc"),
                "--fts-csv".into(),
                file("t.csv"),
            ],
            2,
            "--fts-csv needs a split path",
        ),
    ];
    for (extra, code, message) in cases {
        let mut args = vec!["plan".to_string(), job_arg.clone()];
        args.extend(extra.clone());
        let (got, text, took) = run(&args);
        assert_eq!(got, Some(code), "{extra:?}: {text}");
        assert!(text.contains(message), "{extra:?}: {text}");
        assert!(took < Duration::from_secs(5), "{extra:?}: {took:?}");
        assert_eq!(dir.files(), ["job.json"], "{extra:?}");
    }
    // A read-only file is refused, not replaced.
    let locked = dir.write("locked.nc", "keep me");
    let mut perms = std::fs::metadata(&locked).unwrap().permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(&locked, perms).unwrap();
    let (code, text, _) = run(&[
        "plan".into(),
        job_arg.clone(),
        "--nc".into(),
        file("locked.nc"),
    ]);
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("is read-only"), "{text}");
    assert_eq!(std::fs::read_to_string(&locked).unwrap(), "keep me");
}

#[test]
fn an_existing_output_is_replaced_only_when_the_new_one_is_complete() {
    let dir = Scratch::new("replace");
    let old = dir.write("out.nc", "the old program");
    // A job that fails on the surface after planning starts: the old program stays.
    let mut job = example("lens-array-paper004");
    job["surface"] = json!({"type": "asphere", "radius_mm": 4.0});
    let (code, message, _) = plan(&dir, &job, &[]);
    assert_eq!(code, Some(1), "{message}");
    assert_eq!(std::fs::read_to_string(&old).unwrap(), "the old program");
    assert_eq!(dir.files(), ["job.json", "out.nc"]);
    let (code, message, _) = plan(&dir, &example("lens-array-paper004"), &[]);
    assert_eq!(code, Some(0), "{message}");
    assert!(
        std::fs::read_to_string(&old)
            .unwrap()
            .starts_with("(spiralcam")
    );
}

#[test]
fn a_fifo_is_written_in_place_and_stays_a_fifo() {
    use std::os::unix::fs::FileTypeExt;
    let dir = Scratch::new("fifo-out");
    let fifo = dir.path("out.fifo");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let job = dir.write("job.json", &example("tilted-flat").to_string());
    let o = spiralcam(&[
        "plan".to_string(),
        job.display().to_string(),
        "--nc".into(),
        fifo.display().to_string(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(reader.join().unwrap()).unwrap();
    assert!(
        text.starts_with("(spiralcam") && text.trim_end().ends_with("M30"),
        "{text:.200}"
    );
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
}

#[test]
fn messages_name_the_field_in_short_form() {
    let dir = Scratch::new("messages");
    // Inside a surface family, the field itself.
    let mut job = example("sinusoid-grid");
    job["surface"]["phase_y_deg"] = json!("a");
    refused(
        &job,
        "job: surface.phase_y_deg: invalid type: string \"a\", expected f64",
    );
    let mut job = example("zernike-standard");
    job["surface"]["base"]["radius_mm"] = json!("fifty");
    refused(
        &job,
        "job: surface.base.radius_mm: invalid type: string \"fifty\"",
    );
    // A byte-order mark is accepted.
    let text = format!("\u{feff}{}", example("tilted-flat"));
    let path = dir.write("bom.json", &text);
    let o = spiralcam(&["plan".to_string(), path.display().to_string()]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A job must be an object.
    let path = dir.write("array.json", "[\"a\", {\"diameter_mm\": 10}]");
    let o = spiralcam(&["plan".to_string(), path.display().to_string()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("job: must be a JSON object {…}, not an array"));
    // `--help` after a command is help, not a file.
    for command in ["plan", "analyse", "sag"] {
        let o = spiralcam(&[command, "--help"]);
        assert!(o.status.success(), "{command}");
        assert!(stdout(&o).starts_with(&format!("spiralcam {command} JOB.json")));
    }
    // `sag` refuses a point it cannot evaluate.
    let job = dir.write("job.json", &example("asphere-f20").to_string());
    let at = dir.write("at.csv", "x_mm,y_mm\n1,2\n1e200,0\n");
    let o = spiralcam(&[
        "sag".to_string(),
        job.display().to_string(),
        "--at".into(),
        at.display().to_string(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    assert!(
        stderr(&o).contains("at.csv line 3: the surface is not finite at x = 1e200, y = 0"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn analyse_admits_its_job_like_plan() {
    // Found by fuzzing `analyse`: it walked a path of overflowing heights for minutes, and any
    // number of points, where `plan` refuses both at once.
    let dir = Scratch::new("analyse-admission");
    let analyse = |job: &Value, extra: &[&str]| {
        let path = dir.write("job.json", &job.to_string());
        let mut args = vec!["analyse".to_string(), path.display().to_string()];
        args.extend(extra.iter().map(|s| s.to_string()));
        let start = Instant::now();
        let o = spiralcam(&args);
        (o.status.code(), stderr(&o), start.elapsed())
    };
    let mut job = example("q-bfs");
    job["surface"]["norm_radius_mm"] = json!(0.0006);
    let (code, message, took) = analyse(&job, &[]);
    assert_eq!(code, Some(1), "{message}");
    assert!(
        message.contains("spiralcam: surface = a height of"),
        "{message}"
    );
    assert!(took < Duration::from_secs(5), "{took:?}");
    let mut job = example("asphere-f20");
    job["strategy"]["feed_mm_per_rev"] = json!(0.00002);
    let (code, message, took) = analyse(&job, &[]);
    assert_eq!(code, Some(1), "{message}");
    assert!(
        message.contains(
            "strategy.feed_mm_per_rev = 0.00002: gives about 1.8e8 points; analyse walks at most \
             30000000 (--max-points raises it): a feed of at least 0.0001200001 mm/rev"
        ),
        "{message}"
    );
    assert!(took < Duration::from_secs(5), "{took:?}");
    // The limit is the command line's: 720 001 points refused under 100, walked by default.
    let job = example("asphere-f20");
    let (code, message, _) = analyse(&job, &["--max-points", "100"]);
    assert_eq!(code, Some(1), "{message}");
    assert!(
        message.contains("gives about 720001 points; analyse walks at most 100"),
        "{message}"
    );
    // A surface whose features are far below the nose: 8 samples a feature between points,
    // 4096 a segment (hours).
    let mut fine = example("composite-asphere-lenslets");
    fine["strategy"]["feed_mm_per_rev"] = json!(0.3);
    fine["surface"]["terms"][1]["surface"]["wavelength_x_mm"] = json!(0.00025);
    let (code, message, took) = analyse(&fine, &[]);
    assert_eq!(code, Some(1), "{message}");
    assert!(
        message.contains("8 samples a feature length of 6.25e-5 mm or more")
            && message.contains(" h to analyse on ")
            && message.contains("above the limit of 600 s (--max-seconds raises it)"),
        "{message}"
    );
    assert!(took < Duration::from_secs(5), "{took:?}");
    // Scattered data, whose samples between points each walk their own line: 137 s on two
    // cores, which the plan's time per point put at 4 s; the segments' checks are timed.
    let mut scattered = example("scattered-lens-array");
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/scattered-lens-array.csv");
    scattered["surface"]["data"]["path"] = json!(data);
    let (code, message, took) = analyse(&scattered, &["--max-seconds", "30"]);
    assert_eq!(code, Some(1), "{message}");
    assert!(
        message.contains("gives about 180001 points, about ")
            && message.contains("timed at 16 places along the path), above the limit of 30 s"),
        "{message}"
    );
    assert!(took < Duration::from_secs(10), "{took:?}");
    let report = dir.path("r.json").display().to_string();
    let (code, message, _) = analyse(&job, &["--report", &report]);
    assert_eq!(code, Some(0), "{message}");
}
