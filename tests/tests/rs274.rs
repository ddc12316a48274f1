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
use spiralcam::plan::{Planner, Sinks};
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
    let out = Command::new(RS274)
        .env("HOME", home)
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
