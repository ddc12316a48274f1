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

use common::{ChildBuffers, half_unit, passes_job_json};
use spiralcam::analysis::verify::{Verification, VerifyError, VerifySettings, verify};
use spiralcam::job::{Dialect, Job, Sampling};
use spiralcam::nc::reader::{Program, Reader, ReaderOptions, texts_beside};
use spiralcam::plan::{Planner, Sinks};
use spiralcam::progress::ignore;
use spiralcam::tool::ToolPath;
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

/// The child programs' texts.
fn texts(children: ChildBuffers) -> Vec<(String, String)> {
    children
        .0
        .into_iter()
        .map(|(n, t)| (n, String::from_utf8(t).expect("ascii")))
        .collect()
}

/// The shared test job with three passes in two groups (stock 11 µm: 6, 1, 0 left after them).
fn program_job(dialect: &str, loop_kind: &str, limit: Option<u64>) -> Job {
    Job::from_json(&passes_job_json("Verified", dialect, loop_kind, limit)).expect("job")
}

/// The program of `job`, its children, and the number of path points.
fn write_program(job: &Job) -> (String, Vec<(String, String)>, u64) {
    let planner = Planner::new(job).expect("planner");
    let mut nc = Vec::new();
    let mut children = ChildBuffers::default();
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
        texts(children),
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

/// A sphere of radius 20 mm on a Ø10 part, cut with a 0.5 mm nose (100°).
fn sphere_job(dialect: &str, x_sign: i8) -> Job {
    Job::from_json(&format!(
        r#"{{"name":"Sphere","part":{{"diameter_mm":10}},
            "surface":{{"type":"asphere","radius_mm":20}},
            "tool":{{"nose_radius_mm":0.5,"included_angle_deg":100}},
            "machine":{{"spindle_rpm":600}},
            "strategy":{{"feed_mm_per_rev":0.2,"sampling":{{"type":"constant_angle","points_per_rev":36}}}},
            "output":{{"dialect":"{dialect}","x_sign":{x_sign}}}}}"#
    ))
    .expect("sphere job")
}

const R_SPHERE: f64 = 20.0;
const R_NOSE: f64 = 0.5;

/// The tip over radius ρ of the sphere: the nose centre on the offset sphere of radius R − r
/// about (0, R), the tip r below it.
fn sphere_tip(rho: f64) -> f64 {
    R_SPHERE - ((R_SPHERE - R_NOSE).powi(2) - rho * rho).sqrt() - R_NOSE
}

/// Spiral blocks `X… Z… C…` from radius 4 to 0, 36 a turn, 0.2 mm a turn, Z the sphere's tip
/// plus `lift(k)` mm; C cumulative or wrapped.
fn sphere_blocks(prefix: &str, wrap: bool, x_sign: f64, lift: impl Fn(usize) -> f64) -> String {
    let mut out = String::new();
    for k in 1..=720 {
        let rho = 4.0 - k as f64 * 0.2 / 36.0;
        let c = k as f64 * 10.0;
        let c = if wrap { c.rem_euclid(360.0) } else { c };
        let z = sphere_tip(rho) + lift(k);
        out += &format!("{prefix}X{:.6} Z{z:.6} C{c:.5}\n", x_sign * rho);
    }
    out
}

/// The bound for hand-written programs of 6 decimals: half a digit of Z, of X times the
/// sphere's slope (< 0.21 within ρ ≤ 4), 1e-6 µm for the compensation. µm.
const HAND_TOL_UM: f64 = 0.5e-3 * 1.21 + 1e-6;

/// A Fanuc macro-B program repeating `blocks` (from line 14 on) `passes` times in a `WHILE`
/// loop, each pass `depth` mm deeper by a `G52 Z` shift that starts at `shift − depth` mm and
/// stops at 0.
fn fanuc_passes(passes: u32, depth: f64, shift: f64, blocks: &str) -> String {
    format!(
        "G71 G18 G90 G94\n#100 = {passes}\n#101 = {depth}\n#102 = {shift}\n#103 = 0\n\
         WHILE [#103 LT #100] DO 1\n#102 = [#102 - #101]\nIF [#102 LT 0] THEN #102 = 0\n\
         G52 Z[#102]\nG0 Z1.0\nG0 X4.0 C0\nG1 Z{:.6} F20\nG93 F0.001\n{blocks}G94\nG0 Z1.0\n\
         #103 = [#103 + 1]\nEND 1\nG52 Z0\nM30\n",
        sphere_tip(4.0)
    )
}

#[test]
fn a_fanuc_while_loop_with_a_g52_stock_and_a_gouging_block() {
    let job = sphere_job("moore", 1);
    // Three passes: stock 0.010, 0.004, 0 mm; block 100 of every pass 3 µm low.
    let blocks = sphere_blocks("", true, 1.0, |k| if k == 100 { -0.003 } else { 0.0 });
    let text = fanuc_passes(3, 0.006, 0.016, &blocks);
    let v = verify_text(&job, "lab.nc", &text, &[]).expect("verify");
    assert_eq!(v.pass_count, 3);
    let gouge_line = 14 + 99;
    for (pass, stock) in v.passes.iter().zip([10.0, 4.0, 0.0]) {
        assert_eq!(pass.points, 720);
        let d = &pass.deviation_um;
        assert!((d.max - stock).abs() <= HAND_TOL_UM, "{d:?}");
        assert!((d.min - (stock - 3.0)).abs() <= HAND_TOL_UM, "{d:?}");
        assert_eq!(d.min_at.as_ref().unwrap().line, gouge_line);
        // The mean: 719 points at the stock, one 3 µm below.
        assert!((pass.stock_um - (stock - 3.0 / 720.0)).abs() <= HAND_TOL_UM);
    }
    assert_eq!(v.deviation_um.min_at.as_ref().unwrap().line, gouge_line);
    // G93 F0.001 read as the job's inverse time: 60/0.001 s a block is not 600 rpm; the
    // job's reading is stated and the speed follows from it.
    let rpm = v.timing.spindle_rpm.unwrap();
    assert!((rpm.max - 10.0 / 360.0 / (60.0 / 0.001) * 60.0).abs() < 1e-12);
    assert_eq!(v.program.c, "wrapped");
    assert_eq!(v.collisions.count, 0, "{:?}", v.collisions);
}

#[test]
fn the_display_trace_is_every_kth_point_of_the_last_pass() {
    let job = sphere_job("moore", 1);
    // Two passes, 5 µm then 0 µm stock; block 96 of every pass 3 µm low.
    let blocks = sphere_blocks("", true, 1.0, |k| if k == 96 { -0.003 } else { 0.0 });
    let text = fanuc_passes(2, 0.005, 0.010, &blocks);
    let path = ToolPath::new(&job).expect("tool path");
    let mut open = || {
        Ok(Reader::new(
            Program::from_text("trace.nc", &text),
            ReaderOptions::default(),
        ))
    };
    // 720 points in the last pass, at most 100 drawn: every 8th, 90 points.
    let settings = VerifySettings {
        trace_points: 100,
        ..VerifySettings::default()
    };
    let v = verify(&path, &mut open, &settings, &mut ignore).expect("verify");
    assert_eq!(v.pass_count, 2);
    assert_eq!(v.trace.len(), 90);
    for (i, p) in v.trace.iter().enumerate() {
        // Block k of the spiral: ρ = 4 − 0.2·k/36, θ = 10k°, the tip on the offset sphere.
        let k = 8 * (i + 1);
        let rho = 4.0 - k as f64 * 0.2 / 36.0;
        let theta = (k as f64 * 10.0).to_radians();
        let lift_um = if k == 96 { -3.0 } else { 0.0 };
        assert!((p.x - rho * theta.cos()).abs() < 1e-6, "{i}: {p:?}");
        assert!((p.y - rho * theta.sin()).abs() < 1e-6, "{i}: {p:?}");
        let z = sphere_tip(rho) + lift_um * 1e-3;
        assert!((p.z - z).abs() <= 0.5e-6 + 1e-12, "{i}: {p:?} against {z}");
        // The last pass has no stock: the deviation is the lift alone.
        assert!(
            (p.deviation_um - lift_um).abs() <= HAND_TOL_UM,
            "{i}: {p:?}"
        );
    }
}

#[test]
fn a_linuxcnc_repeat_with_g52_and_a_collision_in_the_link() {
    let job = sphere_job("iso", 1);
    let blocks = sphere_blocks("G1 ", false, 1.0, |_| 0.0);
    // The link to the start of the first pass drops to Z −0.05 at X 2: below the sphere.
    let text = format!(
        "G21 G18 G90 G94\n#<stock> = 0.004\no100 repeat [2]\nG52 Z#<stock>\nG0 Z1.0\n\
         G0 X2.0 C0 Z-0.05\nG0 Z1.0\nG0 X4.0\nG1 Z{:.6} F20\nG93\n{}G94\nG0 Z1.0\n\
         #<stock> = [#<stock> - 0.004]\no100 endrepeat\nG52 Z0\nM2\n",
        sphere_tip(4.0),
        blocks.replace('\n', " F21600\n")
    );
    let v = verify_text(&job, "p.ngc", &text, &[]).expect("verify");
    assert_eq!(v.pass_count, 2);
    for (pass, stock) in v.passes.iter().zip([4.0, 0.0]) {
        let d = &pass.deviation_um;
        assert!(
            (d.min - stock).abs() <= HAND_TOL_UM && (d.max - stock).abs() <= HAND_TOL_UM,
            "{d:?}"
        );
    }
    // 10° a block at F 21600 (1/min): 600 rpm.
    let rpm = v.timing.spindle_rpm.unwrap();
    assert!((rpm.min - 600.0).abs() < 1e-9 && (rpm.max - 600.0).abs() < 1e-9);
    // The rapid to X2 Z−0.05 (+ stock): the sphere's tip there is sphere_tip(2) ≈ 0.1 mm
    // above; its deepest sample is its end.
    assert_eq!(v.collisions.count, 2, "{:?}", v.collisions);
    let first = &v.collisions.listed[0];
    assert_eq!(first.at.line, 6);
    let want = (sphere_tip(2.0) - (-0.05 + 0.004)) * 1e3;
    assert!(
        (first.depth_um - want).abs() < 1e-6,
        "{first:?} want {want}"
    );
}

#[test]
fn m98_children_beside_the_main_program() {
    let job = sphere_job("moore", 1);
    let all = sphere_blocks("", true, 1.0, |_| 0.0);
    let half: Vec<&str> = all.lines().collect();
    let child = |lines: &[&str]| format!("O1\n{}\nM99\n", lines.join("\n"));
    let files = vec![
        ("O0001.nc".to_string(), child(&half[..360])),
        (
            "O0002.nc".to_string(),
            child(&half[360..]).replacen("O1", "O2", 1),
        ),
    ];
    let text = format!(
        "G71 G18 G90\nG0 Z1.0\nG0 X4.0 C0\nG1 Z{:.6} F20\nG93 F0.001\nM98 P1\nM98 P2\nG94\n\
         G0 Z1.0\nM30\n",
        sphere_tip(4.0)
    );
    let v = verify_text(&job, "main.nc", &text, &files).expect("verify");
    assert_eq!(v.pass_count, 1);
    assert_eq!(v.cutting_points, 720);
    assert!(v.deviation_um.max.abs() <= HAND_TOL_UM && v.deviation_um.min.abs() <= HAND_TOL_UM);
    let files_seen: Vec<&str> = [&v.deviation_um.min_at, &v.deviation_um.max_at]
        .iter()
        .map(|a| a.as_ref().unwrap().file.as_str())
        .collect();
    assert!(
        files_seen.iter().all(|f| f.starts_with("O000")),
        "{files_seen:?}"
    );
}

#[test]
fn x_past_the_axis_on_a_tilted_flat() {
    // z = tan τ·x: along the radial line at θ the slope is m = tan τ·cos θ, and the one-way
    // tip is m·ρ + r(√(1 + m²) − 1) (the nose touches where tan a = m, within its 50°).
    let job = Job::from_json(
        r#"{"name":"Flat","part":{"diameter_mm":10},
            "surface":{"type":"tilted_flat","tilt_deg":5},
            "tool":{"nose_radius_mm":0.5,"included_angle_deg":100},
            "machine":{"spindle_rpm":600},
            "strategy":{"feed_mm_per_rev":0.2,"sampling":{"type":"constant_angle","points_per_rev":36}}}"#,
    )
    .expect("job");
    let t = 5f64.to_radians().tan();
    let tip = |rho: f64, theta: f64| {
        let m = t * theta.cos();
        m * rho + R_NOSE * ((1.0 + m * m).sqrt() - 1.0)
    };
    // The tool past the axis: X = −ρ at C cuts the point (ρ, C + 180°).
    let mut blocks = String::new();
    for k in 1..=540 {
        let rho = 4.0 - k as f64 * 0.2 / 36.0;
        let c = k as f64 * 10.0;
        let z = tip(rho, (c + 180.0).to_radians());
        blocks += &format!("G1 X{:.6} Z{z:.6} C{c:.5} F21600\n", -rho);
    }
    let text = format!(
        "G21 G18 G90\nG0 Z1\nG0 X-4 C0\nG1 Z{:.6} F20\nG93\n{blocks}G94\nG0 Z1\nM2\n",
        tip(4.0, std::f64::consts::PI)
    );
    let v = verify_text(&job, "minus.ngc", &text, &[]).expect("verify");
    assert_eq!(v.cutting_points, 540);
    assert_eq!(v.program.past_axis_points, 540);
    let tol = 0.5e-3 * (1.0 + t) + 1e-6;
    assert!(
        v.deviation_um.min.abs() <= tol && v.deviation_um.max.abs() <= tol,
        "{:?}",
        v.deviation_um
    );
    assert!(
        v.warnings
            .iter()
            .any(|w| w.contains("past the spindle axis"))
    );
}

#[test]
fn a_2d_turning_program_along_the_offset_sphere() {
    let job = sphere_job("iso", 1);
    // The tip's circle: centre (X 0, Z R − r), radius R − r; from X 4 to the axis, G3 in G18
    // (the angle from +Z towards +X grows to 180°). Then the same again 2 µm higher by G52.
    let z0 = sphere_tip(4.0);
    let k = (R_SPHERE - R_NOSE) - z0;
    let text = format!(
        "G21 G18 G90 G94\nG0 Z1\nG0 X4\nG1 Z{z0:.6} F20\nG3 X0 Z0 I-4 K{k:.6} F10\nG0 Z1\n\
         G52 Z0.002\nG0 X4\nG1 Z{z0:.6} F20\nG3 X0 Z0 I-4 K{k:.6} F10\nG0 Z1\nG52 Z0\nM2\n"
    );
    let v = verify_text(&job, "profile.ngc", &text, &[]).expect("verify");
    assert!(v.cutting_rule.starts_with("feed moves in X"));
    assert_eq!(v.pass_count, 2);
    // The sweep is asin(4/19.5) ≈ 11.8°: three points every ≤ 5°.
    for pass in &v.passes {
        assert_eq!(pass.points, 3);
    }
    let tol = 0.5e-3 * 1.21 + 1e-6;
    let first = &v.passes[0].deviation_um;
    let last = &v.passes[1].deviation_um;
    assert!(
        first.max.abs() <= tol && first.min.abs() <= tol,
        "{first:?}"
    );
    assert!(
        (last.max - 2.0).abs() <= tol && (last.min - 2.0).abs() <= tol,
        "{last:?}"
    );
    assert!(v.predicted_form.is_none());
    assert!(v.linearization.is_some());
}

fn error_of(job: &Job, text: &str) -> String {
    match verify_text(job, "bad.nc", text, &[]) {
        Ok(v) => panic!("no error: {}", v.to_json()),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_programs_are_refused_with_a_clear_message() {
    let job = sphere_job("iso", 1);
    let e = error_of(&job, "G21 G18\nG0 Z1\nG1 X1 C10 Z0.1 F10\n");
    assert!(
        e.contains("bad.nc") && e.to_lowercase().contains("end"),
        "{e}"
    );
    let e = error_of(
        &job,
        "G21\n#1 = 5\nWHILE [#1 LT 2] DO 1\nG1 X1 C[#1] F10\n#1 = [#1+1]\nM2\n",
    );
    assert!(e.contains("bad.nc") && e.contains("DO 1"), "{e}");
    let e = error_of(&job, "G21\nG1 X1 Z[#7] C10 F10\nM2\n");
    assert!(e.contains("bad.nc:2") || e.contains("line 2"), "{e}");
    assert!(e.contains("#7"), "{e}");
    let e = error_of(&job, "G21\nG0 X1 C10\nG1 Z0.1 F10\nM2\n");
    assert!(
        e.starts_with("the program has 2 moves and none cuts"),
        "{e}"
    );
    // A program for a Ø20 part against the Ø10 job.
    let mut big = String::from("G21 G18 G90\nG0 Z1\nG0 X10 C0\nG1 Z0 F10\nG93\n");
    for k in 1..=360 {
        big += &format!("G1 X{:.6} Z0 C{} F1000\n", 10.0 - k as f64 * 0.02, k * 10);
    }
    big += "G94\nM2\n";
    let e = error_of(&job, &big);
    assert!(
        e.contains("part.diameter_mm") && e.contains("another part size"),
        "{e}"
    );
}

/// A split program (the slide's Z and the servo's word, `Y` in ISO and `W` in the Moore style)
/// verifies against its own job: the verifier adds the servo's share to Z, and Z + servo equals
/// the single-channel Z digit for digit, so the deviation is within the written tolerance.
#[test]
fn a_split_program_verifies_against_its_own_job() {
    for dialect in [Dialect::Iso, Dialect::Moore] {
        let mut job = common::coarse_grid_fts();
        job.strategy.feed_mm_per_rev = 0.1;
        job.strategy.sampling = Sampling::ConstantAngle {
            points_per_rev: 128,
        };
        job.output.dialect = dialect;
        let planner = Planner::new(&job).expect("planner");
        let mut nc = Vec::new();
        planner
            .run_with_dynamics(
                Sinks {
                    nc: Some(&mut nc),
                    ..Default::default()
                },
                &mut |_| ControlFlow::Continue(()),
            )
            .expect("plan");
        let text = String::from_utf8(nc).expect("ascii");
        let word = if dialect == Dialect::Iso { " Y" } else { " W" };
        assert!(text.contains(word), "{dialect:?}: the servo's word");
        let v = verify_text(&job, "split.nc", &text, &[]).expect("verify");
        // The sine grid's largest slope: 2π·a·√(1/λx² + 1/λy²), a = 2 µm, λ = 1 mm.
        let slope = std::f64::consts::TAU * 0.002 * 2f64.sqrt();
        let tol = written_tolerance_um(&job, slope);
        let d = &v.deviation_um;
        assert!(
            d.min.abs() <= tol && d.max.abs() <= tol,
            "{dialect:?}: {d:?} (tolerance {tol} µm)"
        );
        assert_eq!(
            v.cutting_points,
            planner.points().count() as u64 - 1,
            "{dialect:?}"
        );
    }
}
