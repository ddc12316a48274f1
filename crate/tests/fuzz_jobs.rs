//! A fuzz harness over the command line (issue 11): the example jobs, mutated (numbers to
//! extremes, subnormals, huge and tiny values, wrong types, missing and unknown fields), each
//! planned by `spiralcam plan` with its outputs and bounds (`--max-points`, `--max-seconds`,
//! `--max-output-gb`), and analysed by `spiralcam analyse` under the same point and time limits. Every
//! case must end in a few seconds with exit 0 (the files written, no NaN or infinity in them)
//! or exit 1 with a message naming a field of the job or a file, and leave nothing behind but
//! the files it was asked for.
//!
//! A fixed budget runs in the test command (`SPIRALCAM_FUZZ_CASES`, default 64 cases planned
//! and 32 analysed, seed `SPIRALCAM_FUZZ_SEED`, default 11); set them to run longer. The
//! slowest case is printed.

mod common;

use common::Scratch;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The longest a case may take (a debug build of the tool, on a shared machine).
const CASE_LIMIT: Duration = Duration::from_secs(20);

/// The bounds every case is planned under.
const BOUNDS: [&str; 6] = [
    "--max-points",
    "20000",
    "--max-seconds",
    "2",
    "--max-output-gb",
    "0.05",
];

/// A small deterministic generator (SplitMix64).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn jobs_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs")
}

/// The example jobs, by file name.
fn examples() -> Vec<(String, Value)> {
    let mut out: Vec<(String, Value)> = std::fs::read_dir(jobs_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                serde_json::from_str(&text).unwrap(),
            )
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Paths to every value in `v` (object keys and array indices).
fn paths(v: &Value, at: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    out.push(at.clone());
    match v {
        Value::Object(map) => {
            for (k, child) in map {
                at.push(k.clone());
                paths(child, at, out);
                at.pop();
            }
        }
        Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                at.push(i.to_string());
                paths(child, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

fn at_mut<'a>(v: &'a mut Value, path: &[String]) -> &'a mut Value {
    path.iter().fold(v, |v, k| match v {
        Value::Object(map) => map.get_mut(k).unwrap(),
        Value::Array(items) => &mut items[k.parse::<usize>().unwrap()],
        _ => unreachable!("paths lead through containers"),
    })
}

/// An extreme or wrong value, or a scaled copy of `old`.
fn replacement(rng: &mut Rng, old: &Value) -> Value {
    let extremes = [
        json!(0),
        json!(-0.0),
        json!(-1),
        json!(1e-300),
        json!(5e-324),
        json!(9.7e-17),
        json!(1e-9),
        json!(1e300),
        json!(-1e308),
        json!(f64::MAX),
        json!(4_294_967_296u64),
        json!(18_446_744_073_709_551_615u64),
        json!(2.5),
        json!("x"),
        json!(""),
        json!(true),
        Value::Null,
        json!([]),
        json!({}),
        json!([1e300, -1e300]),
    ];
    // Numbers are scaled more often than replaced, so that many cases stay valid and reach
    // the planner.
    match (old.as_f64(), rng.below(10)) {
        (Some(x), 0..7) => {
            let k = rng.below(25) as i32 - 12;
            let y = x * 10f64.powi(k);
            // An integer field keeps an integer where the scaled value is one.
            match (old.is_u64(), y.fract() == 0.0 && (0.0..1e19).contains(&y)) {
                (true, true) => json!(y as u64),
                _ => json!(y),
            }
        }
        _ => extremes[rng.below(extremes.len())].clone(),
    }
}

/// One mutation of `job`: a value replaced, a field removed, or an unknown field added.
fn mutate(rng: &mut Rng, job: &mut Value) -> String {
    let mut all = Vec::new();
    paths(job, &mut Vec::new(), &mut all);
    let path = all[rng.below(all.len())].clone();
    let target = at_mut(job, &path);
    let name = path.join(".");
    match rng.below(12) {
        0 if target.is_object() => {
            target
                .as_object_mut()
                .unwrap()
                .insert("bogus_field".into(), json!(1));
            format!("{name}.bogus_field added")
        }
        1 if !path.is_empty() => {
            let (last, parent) = path.split_last().unwrap();
            match at_mut(job, parent) {
                Value::Object(map) => {
                    map.remove(last);
                }
                Value::Array(items) => {
                    items.remove(last.parse::<usize>().unwrap());
                }
                _ => {}
            }
            format!("{name} removed")
        }
        _ => {
            let new = replacement(rng, target);
            let said = format!("{name} = {new}");
            *target = new;
            said
        }
    }
}

/// Whether `message` names a field of the job or a file.
fn names_a_field(message: &str, job_path: &Path) -> bool {
    let sections = [
        "name", "part", "surface", "tool", "machine", "strategy", "output",
    ];
    let field = sections.iter().any(|s| {
        message.match_indices(s).any(|(i, _)| {
            let before = message[..i].chars().next_back();
            let rest = &message[i + s.len()..];
            let rest = rest.trim_start_matches(|c: char| {
                c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '[' | ']')
            });
            !before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_')
                && (rest.starts_with(" = ") || rest.starts_with(": "))
        })
    });
    field || message.contains(&job_path.display().to_string())
}

struct Case {
    what: String,
    took: Duration,
    code: Option<i32>,
    message: String,
}

/// The command a case runs: `plan` with its three outputs under [`BOUNDS`], or `analyse` with
/// its report under the same point and time limits.
#[derive(Clone, Copy, PartialEq)]
enum Run {
    Plan,
    Analyse,
}

impl Run {
    /// The files a successful run writes, in name order.
    fn outputs(self) -> &'static [&'static str] {
        match self {
            Run::Plan => &["out.csv", "out.nc", "rep.json"],
            Run::Analyse => &["rep.json"],
        }
    }

    fn args(self, out: impl Fn(&str) -> PathBuf) -> Vec<String> {
        let path = |f: &str| out(f).display().to_string();
        match self {
            Run::Plan => {
                let mut a = Vec::new();
                for (flag, f) in [
                    ("--nc", "out.nc"),
                    ("--csv", "out.csv"),
                    ("--report", "rep.json"),
                ] {
                    a.extend([flag.to_string(), path(f)]);
                }
                a.extend(BOUNDS.iter().map(|b| b.to_string()));
                a
            }
            Run::Analyse => vec![
                "--report".into(),
                path("rep.json"),
                "--max-points".into(),
                BOUNDS[1].into(),
                "--max-seconds".into(),
                BOUNDS[3].into(),
            ],
        }
    }
}

/// Runs one mutated job in `dir`; checks what it leaves and returns what happened.
fn run_case(dir: &Scratch, job: &Value, what: String, run: Run) -> Case {
    let job_path = dir.write("job.json", &job.to_string());
    let out = |f: &str| dir.path(f);
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_spiralcam"))
        .arg(match run {
            Run::Plan => "plan",
            Run::Analyse => "analyse",
        })
        .arg(&job_path)
        .args(run.args(out))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > CASE_LIMIT * 3 {
            let _ = child.kill();
            panic!("{what}: still running after {:?}", start.elapsed());
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let took = start.elapsed();
    let mut message = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut message).unwrap();
    let code = status.code();
    let mut files = dir.files();
    files.retain(|f| f != "job.json" && !is_data_file(f));
    match code {
        Some(0) => {
            assert_eq!(files, run.outputs(), "{what}: {message}");
            for f in ["out.nc", "out.csv"]
                .into_iter()
                .filter(|_| run == Run::Plan)
            {
                let text = std::fs::read_to_string(out(f)).unwrap();
                let bad = text.contains("NaN") || text.contains("inf");
                assert!(!bad, "{what}: {f} holds a non-finite number");
            }
            let report: Value =
                serde_json::from_str(&std::fs::read_to_string(out("rep.json")).unwrap()).unwrap();
            match run {
                Run::Plan => {
                    assert!(report["points"].as_u64().is_some_and(|n| n >= 2), "{what}")
                }
                Run::Analyse => assert!(report["linearization"].is_object(), "{what}"),
            }
            for f in run.outputs() {
                std::fs::remove_file(out(f)).unwrap();
            }
        }
        Some(1) => {
            assert!(files.is_empty(), "{what}: left {files:?}: {message}");
            assert!(names_a_field(&message, &job_path), "{what}: {message}");
        }
        _ => panic!("{what}: exit {code:?}: {message}"),
    }
    assert!(took < CASE_LIMIT, "{what}: {took:?}: {message}");
    Case {
        what,
        took,
        code,
        message,
    }
}

fn is_data_file(name: &str) -> bool {
    name.ends_with(".csv") && name != "out.csv" || name.ends_with(".step")
}

#[test]
fn mutated_example_jobs_end_quickly_and_cleanly() {
    fuzz(Run::Plan, 64);
}

/// `analyse` of the same mutations (it once walked a path of overflowing heights for minutes:
/// it admits its job as `plan` does now).
#[test]
fn mutated_example_jobs_are_analysed_quickly_and_cleanly() {
    fuzz(Run::Analyse, 32);
}

/// Runs `SPIRALCAM_FUZZ_CASES` (default `default_cases`) mutated example jobs through `run`.
fn fuzz(run: Run, default_cases: u64) {
    let cases = env_number("SPIRALCAM_FUZZ_CASES", default_cases);
    let mut rng = Rng(env_number("SPIRALCAM_FUZZ_SEED", 11));
    let examples = examples();
    let dir = Scratch::new(match run {
        Run::Plan => "fuzz-plan",
        Run::Analyse => "fuzz-analyse",
    });
    for data in std::fs::read_dir(jobs_dir()).unwrap() {
        let p = data.unwrap().path();
        if p.extension().is_some_and(|e| e == "csv" || e == "step") {
            std::fs::copy(&p, dir.path(&p.file_name().unwrap().to_string_lossy())).unwrap();
        }
    }
    let mut done: Vec<Case> = Vec::new();
    for k in 0..cases {
        let (name, job) = &examples[rng.below(examples.len())];
        let mut job = job.clone();
        let mut said = Vec::new();
        // Two cases in three start from the job coarsened to a few thousand points, so that
        // the mutations reach the planner rather than the point limit.
        if rng.below(3) > 0 {
            let feed = &mut job["strategy"]["feed_mm_per_rev"];
            *feed = json!(feed.as_f64().unwrap() * 60.0);
            said.push("feed × 60".to_string());
        }
        for _ in 0..1 + rng.below(2) {
            said.push(mutate(&mut rng, &mut job));
        }
        done.push(run_case(
            &dir,
            &job,
            format!("case {k}, {name}: {}", said.join("; ")),
            run,
        ));
    }
    let planned = done.iter().filter(|c| c.code == Some(0)).count();
    // What the refusals named, most often first.
    let mut named: std::collections::BTreeMap<String, usize> = Default::default();
    for c in done.iter().filter(|c| c.code == Some(1)) {
        let line = c.message.lines().last().unwrap_or("");
        let field = line
            .trim_start_matches("spiralcam: ")
            .split([' ', ':'])
            .next()
            .unwrap_or("")
            .to_string();
        let field = match field.ends_with(".json") {
            true => format!("job: {}", line.split(": ").nth(3).unwrap_or("")),
            false => field,
        };
        *named.entry(field).or_default() += 1;
    }
    let mut named: Vec<_> = named.into_iter().collect();
    named.sort_by_key(|n| std::cmp::Reverse(n.1));
    println!("refusals by what they name: {named:?}");
    let slowest = done.iter().max_by_key(|c| c.took).unwrap();
    println!(
        "{} cases: {planned} done, {} refused naming a field; slowest {:.2} s ({}; {})",
        done.len(),
        done.len() - planned,
        slowest.took.as_secs_f64(),
        slowest.what,
        slowest.message.lines().last().unwrap_or("")
    );
}
