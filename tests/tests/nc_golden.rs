//! NC output: three small jobs in `tests/golden/` (one per dialect, both samplings, non-default
//! signs, wrapping, decimals and feed mode) are planned and compared byte for byte with their
//! golden programs, which `SPIRALCAM_BLESS=1` (re)writes; every program is also parsed back and
//! each block checked against the planned points (words, signs, wrapping, F), and the CSV of a
//! job is checked row by row against the plan.

mod common;

use common::{c_error, half_unit};
use spiralcam::job::Job;
use spiralcam::job::{Dialect, FeedMode};
use spiralcam::nc::ascii_comment;
use spiralcam::path::PathPoint;
use spiralcam::plan::{Planner, Sinks};
use std::collections::HashMap;
use std::f64::consts::TAU;
use std::ops::ControlFlow;
use std::path::PathBuf;

const BLESS: &str = "SPIRALCAM_BLESS";

fn golden(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join(file)
}

fn planner(name: &str) -> Planner {
    let path = golden(&format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let job = Job::from_json(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    Planner::new(&job).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The job's NC program and CSV, as `Planner::run` writes them.
fn run(p: &Planner) -> (Vec<u8>, Vec<u8>) {
    let (mut nc, mut csv) = (Vec::new(), Vec::new());
    let report = p
        .run_with_dynamics(
            Sinks {
                nc: Some(&mut nc),
                csv: Some(&mut csv),
                display: None,
                ..Default::default()
            },
            &mut |_| ControlFlow::Continue(()),
        )
        .expect("plan");
    assert_eq!(report.nc_bytes, nc.len() as u64);
    (nc, csv)
}

fn points(p: &Planner) -> Vec<PathPoint> {
    p.points().map(|r| r.expect("defined surface")).collect()
}

/// Compares the program of `name` with its golden file, or writes it under `SPIRALCAM_BLESS=1`.
fn check_golden(name: &str) {
    let p = planner(name);
    let (nc, _) = run(&p);
    let ext = p.job().output.style().extension;
    let path = golden(&format!("{name}.{ext}"));
    if std::env::var(BLESS).is_ok_and(|v| v == "1") {
        std::fs::write(&path, &nc).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        eprintln!(
            "{BLESS}=1: wrote {} ({} bytes); review it before committing",
            path.display(),
            nc.len()
        );
        return;
    }
    let expected = std::fs::read(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e}\nno golden program for job {name}: create it with \
             `{BLESS}=1 cargo test -p spiralcam-tests --test nc_golden`, then read it",
            path.display()
        )
    });
    if nc != expected {
        let got = String::from_utf8_lossy(&nc);
        let want = String::from_utf8_lossy(&expected);
        let (mut g, mut w) = (got.lines(), want.lines());
        let mut line = 1;
        let diff = loop {
            match (g.next(), w.next()) {
                (Some(a), Some(b)) if a == b => line += 1,
                (a, b) => break format!("line {line}:\n  golden: {b:?}\n  now:    {a:?}"),
            }
        };
        panic!(
            "{name}: the program differs from {} ({} bytes now, {} golden); first difference at \
             {diff}\nif the change is intended, run `{BLESS}=1 cargo test -p spiralcam-tests \
             --test nc_golden` and review the new file",
            path.display(),
            nc.len(),
            expected.len()
        );
    }
}

#[test]
fn iso_program_matches_its_golden_file() {
    check_golden("golden-iso");
}

#[test]
fn moore_program_matches_its_golden_file() {
    check_golden("golden-moore");
}

#[test]
fn precitech_program_matches_its_golden_file() {
    check_golden("golden-precitech");
}

#[test]
fn iso_program_with_passes_matches_its_golden_file() {
    check_golden("golden-program-iso");
}

#[test]
fn moore_program_with_passes_matches_its_golden_file() {
    check_golden("golden-program-moore");
}

#[test]
fn precitech_program_with_passes_matches_its_golden_file() {
    check_golden("golden-program-precitech");
}

#[test]
fn the_golden_programs_cover_loops_groups_and_a_split() {
    use spiralcam::job::LoopKind;
    let jobs: Vec<Job> = [
        "golden-program-iso",
        "golden-program-moore",
        "golden-program-precitech",
    ]
    .iter()
    .map(|n| planner(n).job().clone())
    .collect();
    let loops: Vec<LoopKind> = jobs
        .iter()
        .map(|j| j.program.as_ref().unwrap().loop_kind)
        .collect();
    assert_eq!(
        loops,
        [
            LoopKind::Controller,
            LoopKind::Unrolled,
            LoopKind::Controller
        ]
    );
    assert!(jobs[0].strategy.split.is_some());
    assert!(jobs[2].program.as_ref().unwrap().has_own_spirals());
    assert_eq!(jobs[1].output.feed_mode, FeedMode::BlockTimeS);
}

#[test]
fn the_golden_jobs_cover_dialects_samplings_and_options() {
    use spiralcam::job::Sampling;
    let jobs: Vec<Job> = ["golden-iso", "golden-moore", "golden-precitech"]
        .iter()
        .map(|n| planner(n).job().clone())
        .collect();
    let dialects: Vec<Dialect> = jobs.iter().map(|j| j.output.dialect).collect();
    assert_eq!(dialects, [Dialect::Iso, Dialect::Moore, Dialect::Precitech]);
    assert!(
        jobs.iter()
            .any(|j| matches!(j.strategy.sampling, Sampling::ConstantArc { .. }))
    );
    assert!(
        jobs.iter()
            .any(|j| matches!(j.strategy.sampling, Sampling::ConstantAngle { .. }))
    );
    // Moore: C negated (and wrapped by default); Precitech: X positive, Z negated, C cumulative.
    let moore = jobs[1].output.conventions();
    assert_eq!((moore.c_sign, moore.wrap_c), (-1.0, true));
    let precitech = jobs[2].output.conventions();
    assert_eq!(
        (precitech.x_sign, precitech.z_sign, precitech.wrap_c),
        (1.0, -1.0, false)
    );
    assert_eq!(jobs[2].output.feed_mode, FeedMode::PerMinute);
}

/// A block's words: letter → value text.
fn words(line: &str) -> HashMap<char, String> {
    line.split_whitespace()
        .map(|w| {
            let mut c = w.chars();
            let letter = c.next().expect("word");
            (letter, c.as_str().to_string())
        })
        .collect()
}

/// Parses a word's value and checks it has exactly `decimals` digits after the point.
fn value(w: &HashMap<char, String>, letter: char, decimals: u32, line: &str) -> f64 {
    let text = w
        .get(&letter)
        .unwrap_or_else(|| panic!("no {letter} in {line:?}"));
    let frac = text.split('.').nth(1).map_or(0, str::len);
    assert_eq!(frac, decimals as usize, "{letter}{text} in {line:?}");
    text.parse()
        .unwrap_or_else(|e| panic!("{letter}{text} in {line:?}: {e}"))
}

/// The machine C of θ: c_sign·θ in degrees, wrapped to [0, 360) if asked.
fn machine_c(theta: f64, c_sign: f64, wrap: bool) -> f64 {
    let c = c_sign * theta.to_degrees();
    if wrap { c.rem_euclid(360.0) } else { c }
}

/// Reads a program back line by line and checks every line against the plan.
fn check_program(name: &str) {
    let p = planner(name);
    let job = p.job().clone();
    let (nc, _) = run(&p);
    let text = String::from_utf8(nc).expect("ASCII program");
    assert!(text.is_ascii(), "{name}: not ASCII");
    let pts = points(&p);
    let style = job.output.style();
    let conv = job.output.conventions();
    let (dxz, dc) = (conv.decimals_xz, conv.decimals_c);
    let inverse = job.output.feed_mode == FeedMode::InverseTime;
    let mut lines = text.lines();
    let mut next = || lines.next().expect("program ended early");

    // Header comments: the planner's header, ASCII, one per line.
    for h in p.header().lines {
        assert_eq!(next(), format!("({})", ascii_comment(&h)), "{name}");
    }
    for l in style.preamble {
        assert_eq!(next(), *l, "{name}");
    }
    let (first, last) = (pts[0], *pts.last().unwrap());
    let clearance = job.output.clearance_mm;
    // Approach: rapid to the clearance height, rapid to X₀ C₀, plunge at the plunge feed.
    let l = next();
    assert!(l.starts_with("G0 Z"), "{name}: {l}");
    let z = value(&words(&l[3..]), 'Z', dxz, l);
    assert!(
        (z - conv.z_sign * (first.z + clearance)).abs() <= half_unit(dxz),
        "{l}"
    );
    let l = next();
    let w = words(&l[3..]);
    assert!(l.starts_with("G0 ") && w.len() == 2, "{name}: {l}");
    assert!((value(&w, 'X', dxz, l) - conv.x_sign * first.rho).abs() <= half_unit(dxz));
    let c0 = machine_c(first.theta, conv.c_sign, conv.wrap_c);
    assert!(
        c_error(value(&w, 'C', dc, l), c0, conv.wrap_c) <= half_unit(dc),
        "{l}"
    );
    let l = next();
    let w = words(&l[3..]);
    assert!(l.starts_with("G1 Z"), "{name}: {l}");
    assert!((value(&w, 'Z', dxz, l) - conv.z_sign * first.z).abs() <= half_unit(dxz));
    assert_eq!(
        value(&w, 'F', 3, l),
        job.output.plunge_feed_mm_per_min,
        "{l}"
    );
    let l = next();
    if inverse {
        assert_eq!(l, "G93", "{name}");
    } else {
        let f = job.output.feed_mm_per_min.unwrap();
        assert!(
            (value(&words(l), 'F', 3, l) - f).abs() <= half_unit(3),
            "{l}"
        );
    }

    // One block per further point, words in the dialect's order.
    let mut last_f: Option<String> = None;
    for pair in pts.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let l = next();
        let body = l
            .strip_prefix(style.block_prefix)
            .unwrap_or_else(|| panic!("{name}: {l:?} lacks {:?}", style.block_prefix));
        let w = words(body);
        let letters: String = body.split_whitespace().map(|t| &t[..1]).collect();
        let order: String = style
            .words
            .iter()
            .map(|a| format!("{a:?}"))
            .collect::<String>();
        assert!(
            letters.starts_with(&order),
            "{name}: {l:?} not in {order} order"
        );
        assert!(
            (value(&w, 'X', dxz, l) - conv.x_sign * b.rho).abs() <= half_unit(dxz),
            "{l}"
        );
        assert!(
            (value(&w, 'Z', dxz, l) - conv.z_sign * b.z).abs() <= half_unit(dxz),
            "{l}"
        );
        let c = machine_c(b.theta, conv.c_sign, conv.wrap_c);
        assert!(
            c_error(value(&w, 'C', dc, l), c, conv.wrap_c) <= half_unit(dc),
            "{l}: C {c}"
        );
        if conv.wrap_c {
            let v = value(&w, 'C', dc, l);
            assert!((0.0..360.0).contains(&v), "{l}: C not wrapped");
        }
        match (inverse, w.get(&'F')) {
            (false, f) => assert!(f.is_none(), "{name}: F in per-minute block {l:?}"),
            (true, f) => {
                // Inverse time: 1/(block time in min) = rpm·2π/|Δθ|.
                let expect = job.machine.spindle_rpm * TAU / (b.theta - a.theta).abs();
                match f {
                    Some(text) => {
                        let fv = value(&w, 'F', 3, l);
                        assert!(
                            (fv - expect).abs() <= half_unit(3) + 1e-12 * expect,
                            "{l}: F {expect}"
                        );
                        assert!(
                            style.feed_every_block || last_f.as_deref() != Some(text.as_str()),
                            "{name}: repeated F in {l:?}"
                        );
                        last_f = Some(text.clone());
                    }
                    None => {
                        assert!(!style.feed_every_block, "{name}: F missing in {l:?}");
                        let prev: f64 = last_f.as_deref().expect("an F before").parse().unwrap();
                        assert!(
                            (prev - expect).abs() <= half_unit(3) + 1e-12 * expect,
                            "{l}: F {expect} omitted"
                        );
                    }
                }
            }
        }
    }
    // Retract and end.
    if inverse {
        assert_eq!(next(), "G94", "{name}");
    }
    let l = next();
    assert!(l.starts_with("G0 Z"), "{name}: {l}");
    let z = value(&words(&l[3..]), 'Z', dxz, l);
    assert!(
        (z - conv.z_sign * (last.z + clearance)).abs() <= half_unit(dxz),
        "{l}"
    );
    for e in style.end {
        assert_eq!(next(), *e, "{name}");
    }
    assert_eq!(lines.next(), None, "{name}: text after the end");
}

#[test]
fn every_block_of_the_golden_programs_matches_the_plan() {
    for name in ["golden-iso", "golden-moore", "golden-precitech"] {
        check_program(name);
    }
}

#[test]
fn the_csv_matches_the_plan_row_by_row() {
    for name in ["golden-moore", "golden-precitech"] {
        let p = planner(name);
        let conv = p.job().output.conventions();
        let (_, csv) = run(&p);
        let text = String::from_utf8(csv).unwrap();
        let mut rows = text.lines();
        assert_eq!(
            rows.next(),
            Some("c_deg,x_mm,z_mm,rho_mm,theta_rad,xc_mm,yc_mm,zc_mm")
        );
        let pts = points(&p);
        let mut n = 0;
        for (row, pt) in rows.zip(&pts) {
            let v: Vec<f64> = row
                .split(',')
                .map(|f| f.parse().unwrap_or_else(|e| panic!("{row}: {e}")))
                .collect();
            assert_eq!(v.len(), 8, "{row}");
            let (dxz, dc) = (conv.decimals_xz, conv.decimals_c);
            let c = machine_c(pt.theta, conv.c_sign, conv.wrap_c);
            assert!(
                c_error(v[0], c, conv.wrap_c) <= half_unit(dc),
                "{name} {row}: C {c}"
            );
            let expect = [
                (1, conv.x_sign * pt.rho, dxz),
                (2, conv.z_sign * pt.z, dxz),
                (3, pt.rho, dxz),
                (4, pt.theta, 9),
                (5, pt.contact[0], dxz),
                (6, pt.contact[1], dxz),
                (7, pt.contact[2], dxz),
            ];
            for (i, e, d) in expect {
                assert!(
                    (v[i] - e).abs() <= half_unit(d),
                    "{name} row {n} column {i}: {} vs {e}",
                    v[i]
                );
            }
            // The contact lies on the radial line of the point.
            let (s, cth) = pt.theta.sin_cos();
            assert!((pt.contact[0] * s - pt.contact[1] * cth).abs() < 1e-12);
            n += 1;
        }
        assert_eq!(n, pts.len(), "{name}: rows");
        assert_eq!(text.lines().count(), pts.len() + 1);
    }
}
