//! ISO programs read back by an independent interpreter, LinuxCNC's `rs274 -g`: it must accept
//! every program (exit 0, nothing on stderr but its "executing" banner), make one
//! STRAIGHT_FEED per path point (the plunge onto point 0, then one per further point) at the
//! planned X = x_sign·ρ, Z = z_sign·z, C = c_sign·θ (cumulative degrees), and put the approach
//! and retract traverses at the clearance above the first and last points. rs274 prints canon
//! calls with 4 decimals, so they are compared within 5e-5 plus half a unit of the written
//! decimals; an instrumented copy with `(DEBUG,#5420 #5422 #5425)` after every G1 line makes it
//! print the X, Z, C it parsed with 6 decimals, compared within half a written unit (+1e-9).
//! LinuxCNC's DEBUG prints any |value| < 1e-4 as 0.000000, so each of those lines is followed by
//! a second message of the same parameters offset by 1000 mm (X, Z) and 100 000° (C), which
//! keeps all 6 decimals of small values: both are checked.

mod common;

use common::half_unit;
use spiralcam::job::Job;
use spiralcam::path::PathPoint;
use spiralcam::plan::{PlanError, Planner, Sinks};
use spiralcam::progress::Stage;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::process::Command;

const RS274: &str = "/usr/bin/rs274";

/// rs274 prints canon arguments with 4 decimals.
const PRINTED: f64 = 5e-5;

/// A scratch directory of this test process for one job.
fn scratch(job: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("spiralcam-rs274-{}-{job}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `rs274 -g` on a program and returns its output after checking it succeeded cleanly.
/// rs274 maps `$HOME/.tool.mmap` shared and truncates it on start, so concurrent runs with one
/// HOME crash each other (SIGBUS): each run gets the program's own directory as HOME.
fn interpret(path: &Path) -> String {
    if !Path::new(RS274).exists() {
        panic!(
            "{RS274} is missing: install linuxcnc-uspace (tests/run.sh does) to read the ISO \
             programs back"
        );
    }
    let home = path.parent().expect("program in a directory");
    // A tool table with the tool the programs' T words name (T0303), so rs274 accepts them.
    let table = home.join("tools.tbl");
    std::fs::write(&table, "T303 P3 Z0 D0.1 ;diamond\n").unwrap();
    let out = Command::new(RS274)
        .env("HOME", home)
        .current_dir(home)
        .arg("-t")
        .arg(&table)
        .arg("-g")
        .arg(path)
        .output()
        .unwrap_or_else(|e| panic!("running {RS274}: {e}"));
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let errors: Vec<&str> = stderr
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && *l != "executing")
        .collect();
    assert!(
        out.status.success() && errors.is_empty(),
        "rs274 -g {}: {}\n{}\n{}",
        path.display(),
        out.status,
        errors.join("\n"),
        stdout.lines().rev().take(5).collect::<Vec<_>>().join("\n")
    );
    assert!(stdout.contains("PROGRAM_END()"), "no PROGRAM_END");
    stdout
}

/// The arguments of every canon call `name(…)` in rs274's output.
fn calls(stdout: &str, name: &str) -> Vec<Vec<f64>> {
    let open = format!("{name}(");
    stdout
        .lines()
        .filter_map(|l| {
            let start = l.find(&open)? + open.len();
            let end = l[start..].find(')')? + start;
            Some(
                l[start..end]
                    .split(',')
                    .map(|v| v.trim().parse().unwrap_or_else(|e| panic!("{l}: {e}")))
                    .collect(),
            )
        })
        .collect()
}

/// The texts of every MESSAGE("…").
fn messages(stdout: &str) -> Vec<Vec<f64>> {
    stdout
        .lines()
        .filter_map(|l| {
            let start = l.find("MESSAGE(\"")? + 9;
            let end = l[start..].find('"')? + start;
            Some(
                l[start..end]
                    .split_whitespace()
                    .map(|v| v.parse().unwrap_or_else(|e| panic!("{l}: {e}")))
                    .collect(),
            )
        })
        .collect()
}

/// Plans the job, writes its program and an instrumented copy, reads both back and checks them.
fn check(job_json: &str) {
    let job = Job::from_json(job_json).expect("job JSON");
    assert_eq!(job.output.dialect, spiralcam::job::Dialect::Iso);
    let planner = Planner::new(&job).expect("valid job");
    let pts: Vec<PathPoint> = planner.points().map(|p| p.unwrap()).collect();
    let mut nc = Vec::new();
    planner
        .run(
            Sinks {
                nc: Some(&mut nc),
                ..Default::default()
            },
            &mut |_| ControlFlow::Continue(()),
        )
        .expect("plan");
    let text = String::from_utf8(nc).unwrap();
    let dir = scratch(&job.name);
    let plain = dir.join(format!("{}.ngc", job.name));
    std::fs::write(&plain, &text).unwrap();
    let mut debug = String::new();
    for l in text.lines() {
        debug.push_str(l);
        debug.push('\n');
        if l.starts_with("G1") {
            debug.push_str("(DEBUG,#5420 #5422 #5425)\n");
            debug.push_str("#1=[#5420+1000]\n#2=[#5422+1000]\n#3=[#5425+100000]\n");
            debug.push_str("(DEBUG,#1 #2 #3)\n");
        }
    }
    let instrumented = dir.join(format!("{}-debug.ngc", job.name));
    std::fs::write(&instrumented, &debug).unwrap();

    let conv = job.output.conventions();
    assert!(!conv.wrap_c, "the ISO check expects cumulative C");
    let (dxz, dc) = (conv.decimals_xz, conv.decimals_c);
    assert!(dxz <= 6 && dc <= 6, "DEBUG prints 6 decimals");
    let planned = |p: &PathPoint, lift: f64| {
        (
            conv.x_sign * p.rho,
            conv.z_sign * (p.z + lift),
            conv.c_sign * p.theta.to_degrees(),
        )
    };
    let name = &job.name;

    // The plain program: feeds and traverses at 4 decimals.
    let out = interpret(&plain);
    let feeds = calls(&out, "STRAIGHT_FEED");
    assert_eq!(
        feeds.len(),
        pts.len(),
        "{name}: one STRAIGHT_FEED per point"
    );
    let tol_xz = PRINTED + half_unit(dxz);
    let tol_c = PRINTED + half_unit(dc);
    for (k, (f, p)) in feeds.iter().zip(&pts).enumerate() {
        let (x, z, c) = planned(p, 0.0);
        assert_eq!(f.len(), 6, "{name}: {f:?}");
        assert!(
            (f[0] - x).abs() <= tol_xz && (f[2] - z).abs() <= tol_xz && (f[5] - c).abs() <= tol_c,
            "{name}: feed {k} {f:?}, planned X {x} Z {z} C {c}"
        );
        assert_eq!(
            (f[1], f[3], f[4]),
            (0.0, 0.0, 0.0),
            "{name}: feed {k} {f:?}"
        );
    }
    let traverses = calls(&out, "STRAIGHT_TRAVERSE");
    assert_eq!(traverses.len(), 3, "{name}: approach (2) and retract (1)");
    let clearance = job.output.clearance_mm;
    let (first, last) = (&pts[0], pts.last().unwrap());
    let (x0, z0, c0) = planned(first, clearance);
    let (x1, z1, c1) = planned(last, clearance);
    // Rapid to the clearance height above point 0, then across to X₀, C₀ at that height.
    assert!(
        (traverses[0][2] - z0).abs() <= tol_xz,
        "{name}: {traverses:?}"
    );
    let t = &traverses[1];
    assert!(
        (t[0] - x0).abs() <= tol_xz && (t[2] - z0).abs() <= tol_xz && (t[5] - c0).abs() <= tol_c,
        "{name}: approach {t:?} vs X {x0} Z {z0} C {c0}"
    );
    // Retract straight up from the last point.
    let t = &traverses[2];
    assert!(
        (t[0] - x1).abs() <= tol_xz && (t[2] - z1).abs() <= tol_xz && (t[5] - c1).abs() <= tol_c,
        "{name}: retract {t:?} vs X {x1} Z {z1} C {c1}"
    );
    // The clearance really is above the path (in part coordinates).
    assert!(conv.z_sign * (traverses[0][2] - feeds[0][2]) > 0.5 * clearance);

    // The instrumented copy: the parsed words at 6 decimals.
    let out = interpret(&instrumented);
    assert_eq!(
        calls(&out, "STRAIGHT_FEED"),
        feeds,
        "{name}: DEBUG changed the moves"
    );
    let msgs = messages(&out);
    assert_eq!(
        msgs.len(),
        2 * pts.len(),
        "{name}: two DEBUG lines per G1 line"
    );
    for (k, (m, p)) in msgs.chunks(2).zip(&pts).enumerate() {
        let (x, z, c) = planned(p, 0.0);
        let (plain, offset) = (&m[0], &m[1]);
        assert!(plain.len() == 3 && offset.len() == 3, "{name}: {m:?}");
        // DEBUG prints |v| < 1e-4 as zero: such values compare with 0 within 1e-4.
        let near = |printed: f64, want: f64, d: u32| {
            (printed - want).abs() <= half_unit(d)
                || (printed == 0.0 && want.abs() < 1e-4 + half_unit(d))
        };
        assert!(
            near(plain[0], x, dxz) && near(plain[1], z, dxz) && near(plain[2], c, dc),
            "{name}: point {k}: parsed X Z C {plain:?}, planned {x} {z} {c}"
        );
        let parsed = [
            offset[0] - 1000.0,
            offset[1] - 1000.0,
            offset[2] - 100_000.0,
        ];
        // The offset adds at most 1e-11 of rounding (16 digits of 1e5).
        assert!(
            (parsed[0] - x).abs() <= half_unit(dxz) + 1e-10
                && (parsed[1] - z).abs() <= half_unit(dxz) + 1e-10
                && (parsed[2] - c).abs() <= half_unit(dc) + 1e-10,
            "{name}: point {k}: parsed X Z C {parsed:?}, planned {x} {z} {c}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_golden_iso_program_reads_back() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("golden/golden-iso.json");
    check(&std::fs::read_to_string(path).unwrap());
}

#[test]
fn a_constant_arc_program_with_negative_c_reads_back() {
    // Clockwise with C negated: C increases; F changes on every block.
    check(
        r#"{"name":"rs274-arc","part":{"diameter_mm":1.6},
            "surface":{"type":"sinusoid","amplitude_mm":0.003,"wavelength_x_mm":0.7,"wavelength_y_mm":1.1,
                       "phase_y_deg":45},
            "tool":{"nose_radius_mm":0.08},"machine":{"spindle_rpm":750},
            "strategy":{"feed_mm_per_rev":0.1,"direction":"cw","start_angle_deg":200,
                        "sampling":{"type":"constant_arc","arc_length_mm":0.06,"max_angle_step_deg":12}},
            "output":{"dialect":"iso","c_sign":-1,"clearance_mm":0.25}}"#,
    );
}

#[test]
fn a_lens_array_program_with_mirrored_x_and_z_reads_back() {
    // X and Z negated, 5 decimals, per-minute feed: the words still land where planned.
    check(
        r#"{"name":"rs274-lens","part":{"diameter_mm":1.4},
            "surface":{"type":"lens_array","lens_radius_mm":0.8,"aperture_mm":0.3,"pitch_mm":0.3,
                       "grid":"rectangular","form":"concave"},
            "tool":{"nose_radius_mm":0.1},"machine":{"spindle_rpm":400},
            "strategy":{"feed_mm_per_rev":0.05,"sampling":{"type":"constant_angle","points_per_rev":20}},
            "output":{"dialect":"iso","x_sign":-1,"z_sign":-1,"decimals_xz":5,"decimals_c":3,
                      "feed_mode":"per_minute","feed_mm_per_min":30}}"#,
    );
}

/// A program split between the slide and a fast tool servo (`NcWriter::point_split`, the servo
/// on an arbitrary 5-per-revolution share of up to 20 µm) reads back with the servo's word:
/// standalone rs274 knows only the axes X Y Z A B C, so the servo takes `A` here (`W`, the
/// default, is refused by it as an unknown axis). Every feed's Z is the slide's share and its
/// A the servo's, each within the printed 4 decimals, and the parsed words (DEBUG #5422, #5423)
/// add up to the single-channel Z within half a written unit.
#[test]
fn a_split_program_reads_back_with_the_servo_word() {
    let mut job = common::example_job("tilted-flat.json");
    job.name = "split".into();
    job.output = spiralcam::job::OutputSpec {
        fts_word: Some("A".into()),
        ..Default::default()
    };
    let slide = |p: &PathPoint| p.z - 0.02 * (0.5 + 0.5 * (5.0 * p.theta).sin());
    let (pts, text) = common::split_program(&job, slide);
    let mut debug = String::new();
    for l in text.lines() {
        debug.push_str(l);
        debug.push('\n');
        if l.starts_with("G1") {
            debug.push_str("#1=[#5422+1000]\n#2=[#5423+1000]\n(DEBUG,#1 #2)\n");
        }
    }
    let dir = scratch(&job.name);
    let path = dir.join("split-debug.ngc");
    std::fs::write(&path, &debug).unwrap();
    let out = interpret(&path);
    let conv = job.output.conventions();
    let half = half_unit(conv.decimals_xz);
    let feeds = calls(&out, "STRAIGHT_FEED");
    assert_eq!(feeds.len(), pts.len());
    for (f, p) in feeds.iter().zip(&pts) {
        let (z, w) = (conv.z_sign * slide(p), conv.z_sign * (p.z - slide(p)));
        assert!((f[2] - z).abs() <= PRINTED + 2.0 * half, "{f:?} vs Z {z}");
        assert!((f[3] - w).abs() <= PRINTED + 2.0 * half, "{f:?} vs A {w}");
    }
    let msgs = messages(&out);
    assert_eq!(msgs.len(), pts.len());
    for (m, p) in msgs.iter().zip(&pts) {
        let sum = (m[0] - 1000.0) + (m[1] - 1000.0);
        // Z and the whole are each rounded once (half a unit), the offsets add 1e-10.
        assert!(
            (sum - conv.z_sign * p.z).abs() <= half + 1e-10,
            "parsed Z + A {sum}, planned {}",
            p.z
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The moves of rs274's output in order, each with the machine position (the canon position
/// plus the G92/G52 offset in force: canon calls are in the program's frame) and the feed
/// rate in force.
fn machine_feeds(stdout: &str) -> Vec<([f64; 6], f64)> {
    let (mut offset, mut rate) = ([0.0; 6], 0.0);
    let mut out = Vec::new();
    for line in stdout.lines() {
        let args = |name: &str| -> Option<Vec<f64>> {
            let start = line.find(&format!("{name}("))? + name.len() + 1;
            let end = line[start..].find(')')? + start;
            Some(
                line[start..end]
                    .split(',')
                    .map(|v| v.trim().parse().unwrap())
                    .collect(),
            )
        };
        if let Some(a) = args("SET_G92_OFFSET") {
            offset.copy_from_slice(&a[..6]);
        } else if let Some(a) = args("SET_FEED_RATE") {
            rate = a[0];
        } else if let Some(a) = args("STRAIGHT_FEED") {
            let mut m = [0.0; 6];
            for k in 0..6 {
                m[k] = a[k] + offset[k];
            }
            out.push((m, rate));
        }
    }
    out
}

/// A program with passes in a controller loop (ISO: `o100 repeat`, `#<stock>`, `G52 Z`), a
/// staged approach and a split, read back by rs274: every pass's feeds cut the design raised by
/// the stock left after it (Z + Y, the slide's and the servo's shares, to the printed
/// precision), and each approach's feeds come in order at their heights above the first point.
#[test]
fn a_program_with_passes_in_a_controller_loop_reads_back() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("golden/golden-program-iso.json");
    let job = Job::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    let planner = Planner::new(&job).unwrap();
    let pts: Vec<PathPoint> = planner.points().map(|p| p.unwrap()).collect();
    let mut nc = Vec::new();
    planner
        .run_with_dynamics(
            Sinks {
                nc: Some(&mut nc),
                ..Default::default()
            },
            &mut |_| ControlFlow::Continue(()),
        )
        .unwrap();
    let dir = scratch("passes");
    let file = dir.join("passes.ngc");
    std::fs::write(&file, &nc).unwrap();
    let feeds = machine_feeds(&interpret(&file));
    let spec = job.program.as_ref().unwrap();
    let passes = spec.pass_list();
    let steps = spec.approach.len() + 1;
    assert_eq!(feeds.len(), passes.len() * (steps + pts.len() - 1));
    let tol = PRINTED + 2.0 * half_unit(job.output.decimals_xz);
    for (k, pass) in passes.iter().enumerate() {
        let body = &feeds[k * (steps + pts.len() - 1)..][..steps + pts.len() - 1];
        // The approach: each step at its feed, the plunge at the plunge feed, onto point 0.
        let z0 = pts[0].z + pass.stock_mm;
        for (s, step) in spec.approach.iter().enumerate() {
            assert!(
                (body[s].0[2] - (z0 + step.height_mm)).abs() <= tol,
                "pass {k}: {:?}",
                body[s]
            );
            assert_eq!(body[s].1, step.feed_mm_per_min, "pass {k}, step {s}");
        }
        let plunge = &body[steps - 1];
        assert_eq!(plunge.1, job.output.plunge_feed_mm_per_min);
        // Z and Y are each printed to 4 decimals: their sum is within twice that.
        let sum_tol = tol + PRINTED;
        assert!(
            (plunge.0[2] + plunge.0[1] - z0).abs() <= sum_tol,
            "pass {k}: plunge {plunge:?}"
        );
        // The cut: Z + Y (slide + servo) is the design raised by the stock.
        for (f, p) in body[steps..].iter().zip(&pts[1..]) {
            let z = f.0[2] + f.0[1];
            assert!(
                (z - (p.z + pass.stock_mm)).abs() <= sum_tol,
                "pass {k}: {f:?} vs z {} + stock {}",
                p.z,
                pass.stock_mm
            );
            assert!((f.0[0] - p.rho).abs() <= tol && (f.0[5] - p.theta.to_degrees()).abs() <= 1e-4);
        }
    }
    // The stock left after each pass: 0.006, 0.001, 0 mm.
    let stock: Vec<f64> = passes.iter().map(|p| p.stock_mm).collect();
    assert!(
        (stock[0] - 0.006).abs() < 1e-12 && (stock[1] - 0.001).abs() < 1e-12 && stock[2] == 0.0
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `job` with at most about 20 revolutions of at most 90 points (a few thousand points, so that
/// the debug build plans even the scattered example in seconds).
fn coarsen(job: &mut spiralcam::job::Job) {
    use spiralcam::job::Sampling;
    let radius = job.outer_radius_mm();
    let feed = &mut job.strategy.feed_mm_per_rev;
    *feed = feed.max(radius / 20.0).min(radius);
    match &mut job.strategy.sampling {
        Sampling::ConstantAngle { points_per_rev } => *points_per_rev = (*points_per_rev).min(90),
        Sampling::ConstantArc { arc_length_mm, .. } => {
            *arc_length_mm = arc_length_mm.max(std::f64::consts::TAU * radius / 90.0)
        }
        _ => {}
    }
}

/// Every example job's ISO program (coarsened to a few thousand points, planned as the command
/// line does, with the machine dynamics and a split where the job has them) is read by rs274
/// without an error and makes one feed per point; no line is longer than LinuxCNC reads (252
/// characters: rs274 refuses 253 and more as "Command too long").
#[test]
fn every_example_job_reads_back() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../crate/jobs");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json"))
        .collect();
    names.sort();
    for name in names {
        let mut job = common::example_job(&name);
        job.output.dialect = spiralcam::job::Dialect::Iso;
        job.output.wrap_c = None;
        job.output.x_sign = None;
        coarsen(&mut job);
        let planner = Planner::new(&job).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut nc = Vec::new();
        // The program is whole when the concave-zone report starts: stop there (the report
        // is not what this test reads, and it takes minutes on the scattered example in a
        // debug build).
        let result = planner.run_with_dynamics(
            Sinks {
                nc: Some(&mut nc),
                ..Default::default()
            },
            &mut |p| match p.stage {
                Stage::Zones => ControlFlow::Break(()),
                _ => ControlFlow::Continue(()),
            },
        );
        match result {
            Ok(_) | Err(PlanError::Cancelled) => {}
            Err(e) => panic!("{name}: {e}"),
        }
        let points = planner.points().count() as u64;
        let text = String::from_utf8(nc).unwrap();
        let longest = text.lines().map(str::len).max().unwrap_or(0);
        assert!(longest <= 252, "{name}: a line of {longest} characters");
        let folder = scratch(&format!("example-{}", name.trim_end_matches(".json")));
        let file = folder.join("program.ngc");
        std::fs::write(&file, &text).unwrap();
        let feeds = machine_feeds(&interpret(&file));
        assert_eq!(feeds.len() as u64, points, "{name}: one feed per point");
        if job.strategy.split.is_some() {
            assert!(
                feeds.iter().any(|f| f.0[1] != 0.0),
                "{name}: the servo (Y) moves"
            );
        }
        let _ = std::fs::remove_dir_all(&folder);
    }
}
