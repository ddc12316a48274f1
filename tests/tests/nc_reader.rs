//! The NC reader (`spiralcam::nc::reader`) against independent references:
//!
//! - the golden programs of `tests/golden/`, streamed from disk: every feed move equals the
//!   plan's point (`Planner::points`, the same points `nc_golden.rs` checks the programs
//!   against) within half a unit of the written decimals (+1e-9), the approach and retract at
//!   the clearance, the feeds as written;
//! - hand-written programs in the styles the reader must take (a lab's Moore-style pass loop
//!   with `#` variables and a `G52 Z[#8]` shift per pass, the Precitech style with X < 0,
//!   `M98` children, LinuxCNC o-word loops and calls, 2-D turning with arcs, words without
//!   spaces and both kinds of comments), whose moves the test computes itself from the
//!   program's numbers (within 1e-12 mm);
//! - LinuxCNC's interpreter `rs274 -g` on ISO programs with loops, variables, G52, G10/G55,
//!   G92, G7, G53, inch units, arcs, `M98` children and A/Y words: the same moves, rs274's
//!   canon positions (printed with 4 decimals, in program coordinates) turned into machine
//!   positions with the offsets it prints, within 6e-5 of a program unit;
//! - bad input: each a clear error with the file, line and text, never a panic; a property
//!   test feeds mutated programs and checks the reader stops within its bounds.

mod common;

use common::{c_error, half_unit};
use proptest::prelude::*;
use spiralcam::job::{Dialect, FeedMode, Job};
use spiralcam::nc::reader::{
    CWrapping, Change, Code, Event, EventKind, FeedRateMode, InitialMotion, Move, MoveKind,
    OffsetTable, Position, Problem, Program, ProgramRef, ReadError, Reader, ReaderOptions, Step,
    Summary, Units, files_beside,
};
use spiralcam::path::PathPoint;
use spiralcam::plan::Planner;
use std::collections::HashMap;
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// What a program did.
#[derive(Debug)]
struct Run {
    moves: Vec<Move>,
    events: Vec<Event>,
    summary: Summary,
}

impl Run {
    fn event_kinds(&self) -> Vec<&EventKind> {
        self.events.iter().map(|e| &e.kind).collect()
    }
}

fn run(mut reader: Reader<'_>) -> Result<Run, ReadError> {
    let (mut moves, mut events) = (Vec::new(), Vec::new());
    while let Some(step) = reader.next_step()? {
        match step {
            Step::Move(m) => moves.push(m),
            Step::Event(e) => events.push(e),
        }
    }
    Ok(Run {
        moves,
        events,
        summary: reader.summary(),
    })
}

fn read_with(name: &str, text: &str, options: ReaderOptions) -> Result<Run, ReadError> {
    run(Reader::new(Program::from_text(name, text), options))
}

fn read(name: &str, text: &str) -> Run {
    read_with(name, text, ReaderOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The machine position with X, Z and C set (the other axes at their start, 0).
fn xzc(x: f64, z: f64, c: f64) -> Position {
    let mut p = Position::default();
    (p.0[0], p.0[2], p.0[5]) = (x, z, c);
    p
}

/// Asserts a move's target X, Z, C within `tol` (mm, degrees).
fn assert_at(m: &Move, want: Position, tol: f64, what: &str) {
    for (axis, i) in [("X", 0), ("Y", 1), ("Z", 2), ("C", 5), ("W", 8)] {
        assert!(
            (m.target.0[i] - want.0[i]).abs() <= tol,
            "{what}: {axis} {} ≠ {} (line {})",
            m.target.0[i],
            want.0[i],
            m.at.line
        );
    }
}

// ---------------------------------------------------------------------------------------
// The golden programs.

fn golden(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join(file)
}

#[test]
fn every_golden_program_reads_back_as_the_plans_points() {
    for name in ["golden-iso", "golden-moore", "golden-precitech"] {
        let job_text = std::fs::read_to_string(golden(&format!("{name}.json"))).unwrap();
        let job = Job::from_json(&job_text).unwrap();
        let planner = Planner::new(&job).unwrap();
        let pts: Vec<PathPoint> = planner.points().map(|p| p.unwrap()).collect();
        let path = golden(&format!("{name}.{}", job.output.style().extension));
        // Streamed from disk, and from memory: the same steps.
        let r = run(Reader::new(
            Program::open(&path).unwrap(),
            ReaderOptions::default(),
        ))
        .unwrap_or_else(|e| panic!("{e}"));
        let text = std::fs::read_to_string(&path).unwrap();
        let same = read(&path.display().to_string(), &text);
        assert_eq!(r.moves, same.moves, "{name}");
        assert_eq!(r.events, same.events, "{name}");

        let conv = job.output.conventions();
        let (hxz, hc) = (half_unit(conv.decimals_xz), half_unit(conv.decimals_c));
        let machine_c = |p: &PathPoint| {
            let c = conv.c_sign * p.theta.to_degrees();
            if conv.wrap_c { c.rem_euclid(360.0) } else { c }
        };
        let feeds: Vec<&Move> = r
            .moves
            .iter()
            .filter(|m| m.kind == MoveKind::Linear)
            .collect();
        assert_eq!(feeds.len(), pts.len(), "{name}: a feed move per point");
        for (k, (m, p)) in feeds.iter().zip(&pts).enumerate() {
            let at = format!("{name} point {k}");
            assert!((m.target.x() - conv.x_sign * p.rho).abs() <= hxz, "{at}: X");
            assert!((m.target.z() - conv.z_sign * p.z).abs() <= hxz, "{at}: Z");
            assert!(
                c_error(m.target.c(), machine_c(p), conv.wrap_c) <= hc,
                "{at}: C {} vs {}",
                m.target.c(),
                machine_c(p)
            );
            let f = m.feed.f.expect("a feed");
            if k == 0 {
                assert_eq!(m.feed.mode, FeedRateMode::PerMinute, "{at}");
                assert_eq!(f, job.output.plunge_feed_mm_per_min, "{at}");
            } else if job.output.feed_mode == FeedMode::InverseTime {
                assert_eq!(m.feed.mode, FeedRateMode::InverseTime, "{at}");
                let want = job.machine.spindle_rpm * TAU / (p.theta - pts[k - 1].theta).abs();
                assert!(
                    (f - want).abs() <= half_unit(3) + 1e-12 * want,
                    "{at}: F {f} vs {want}"
                );
            } else {
                assert_eq!(f, job.output.feed_mm_per_min.unwrap(), "{at}");
            }
        }
        // Approach: up to the clearance above point 0, across to X₀ C₀; retract from the last.
        let rapids: Vec<&Move> = r
            .moves
            .iter()
            .filter(|m| m.kind == MoveKind::Rapid)
            .collect();
        assert_eq!(rapids.len(), 3, "{name}");
        let clear = job.output.clearance_mm;
        let (first, last) = (&pts[0], pts.last().unwrap());
        assert!((rapids[0].target.z() - conv.z_sign * (first.z + clear)).abs() <= hxz);
        assert!((rapids[1].target.x() - conv.x_sign * first.rho).abs() <= hxz);
        assert!(c_error(rapids[1].target.c(), machine_c(first), conv.wrap_c) <= hc);
        assert!((rapids[2].target.z() - conv.z_sign * (last.z + clear)).abs() <= hxz);
        assert!((rapids[2].target.x() - conv.x_sign * last.rho).abs() <= hxz);
        // The order: approach, feeds, retract.
        let kinds: Vec<MoveKind> = r.moves.iter().map(|m| m.kind).collect();
        assert_eq!(kinds[..2], [MoveKind::Rapid, MoveKind::Rapid], "{name}");
        assert_eq!(kinds.last(), Some(&MoveKind::Rapid), "{name}");

        let s = &r.summary;
        assert_eq!(s.units, Some(Units::Millimetres), "{name}");
        let wrap = if conv.wrap_c {
            CWrapping::Wrapped
        } else {
            CWrapping::Cumulative
        };
        assert_eq!(s.c, wrap, "{name}");
        assert_eq!(s.dialect.dialect, Some(job.output.dialect), "{name}");
        let end = style_end(job.output.dialect);
        assert_eq!(
            r.events.last().map(|e| &e.kind),
            Some(&EventKind::End(end.into())),
            "{name}"
        );
        assert_eq!(s.lines_read, text.lines().count() as u64, "{name}");
    }
}

fn style_end(d: Dialect) -> &'static str {
    match d {
        Dialect::Iso => "M2",
        _ => "M30",
    }
}

/// A program split between the slide and a fast tool servo (`NcWriter::point_split`, the servo
/// on an arbitrary 5-per-revolution share of up to 20 µm, as in `rs274.rs`): the reader gives
/// the servo's axis W beside Z, the slide's share, and Z + W is the single-channel Z to half a
/// written unit.
#[test]
fn a_split_program_reads_back_with_the_servo_axis() {
    let mut job = common::example_job("tilted-flat.json");
    job.output = spiralcam::job::OutputSpec {
        fts_word: Some("W".into()),
        ..Default::default()
    };
    let slide = |p: &PathPoint| p.z - 0.02 * (0.5 + 0.5 * (5.0 * p.theta).sin());
    let (pts, nc) = common::split_program(&job, slide);
    let r = read("split.ngc", &nc);
    let conv = job.output.conventions();
    let half = half_unit(conv.decimals_xz);
    let feeds: Vec<&Move> = r
        .moves
        .iter()
        .filter(|m| m.kind == MoveKind::Linear)
        .collect();
    assert_eq!(feeds.len(), pts.len());
    for (m, p) in feeds.iter().zip(&pts) {
        let w = m.target.get(spiralcam::nc::reader::MachineAxis::W);
        assert!(
            (m.target.z() - conv.z_sign * slide(p)).abs() <= half,
            "Z {m:?}"
        );
        assert!(
            (w - conv.z_sign * (p.z - slide(p))).abs() <= 2.0 * half,
            "W {m:?}"
        );
        assert!(
            (m.target.z() + w - conv.z_sign * p.z).abs() <= half,
            "Z + W {m:?}"
        );
    }
    assert_eq!(r.summary.axes.letters(), "XZCW");
}

// ---------------------------------------------------------------------------------------
// Hand-written programs; expected moves computed here from the program's own numbers.

/// A slow-slide-servo program shaped as a lab's Moore Nanotech program (issue 12's description):
/// variables at the top, a modal line with the machine's own codes, a work offset, the tool, a
/// WHILE loop whose every pass shifts Z by `G52 Z[#8]`, a staged approach with an unbracketed
/// sum (`z0+0.1`), the cut under `G93 F[#555]`, the counter, `END 2`.
const LAB_MOORE: &str = "%
(LAB STYLE: 3 PASSES, 2 UM DEPTH OF CUT)
#100=3 (PASSES)
#103=0.002 (DEPTH OF CUT MM)
#555=0.25 (INVERSE TIME FEED)
#8=0.006 (STOCK ABOVE THE DESIGN)
G52 G63 G71 G103 G40 G18 G90
G55
T0303
M80
G94 Z20 F500
M26.1
#5=0
WHILE[#5 LT #100] DO 2
#8 = #8 - #103
G52 X0 Y0 Z[#8]
G94 X1.2 F300
G93 F1 C0
G94 Z5 F500
Z1 F200
z0+0.1 F20
z0 F1
G93 F[#555]
C90.0 X0.9 Z-0.001
C180.0 X0.6 Z-0.002
C270.0 X0.3 Z-0.001
C0.0 X0.0 Z0.0
G94 Z5 F200
#5=[#5+1]
END 2
G94 Z20 F800
M29
M30
%
";

fn lab_options() -> ReaderOptions {
    let mut offsets = OffsetTable::default();
    offsets.0[1] = xzc(0.001, -12.5, 0.0);
    ReaderOptions {
        offsets,
        initial_motion: InitialMotion::Linear,
        accepted_codes: vec![Code::parse("G63").unwrap(), Code::parse("G103").unwrap()],
        ..Default::default()
    }
}

#[test]
fn a_lab_style_moore_pass_loop_shifts_each_pass_by_g52() {
    let r = read_with("lab.nc", LAB_MOORE, lab_options()).unwrap_or_else(|e| panic!("{e}"));
    // G55 = (X 0.001, Z -12.5); G52 Z = stock left after the pass: 6 µm − 2 µm per pass.
    let (ox, oz) = (0.001, -12.5);
    let mut want: Vec<(Position, FeedRateMode, f64)> =
        vec![(xzc(0.0, 20.0 + oz, 0.0), FeedRateMode::PerMinute, 500.0)];
    let mut x = 0.0;
    for pass in 1..=3 {
        let shift = 0.006 - 0.002 * pass as f64;
        let z = |v: f64| v + oz + shift;
        x = 1.2 + ox;
        let per_min = FeedRateMode::PerMinute;
        want.push((xzc(x, want.last().unwrap().0.z(), 0.0), per_min, 300.0));
        want.push((
            xzc(x, want.last().unwrap().0.z(), 0.0),
            FeedRateMode::InverseTime,
            1.0,
        ));
        for (zz, f) in [(5.0, 500.0), (1.0, 200.0), (0.1, 20.0), (0.0, 1.0)] {
            want.push((xzc(x, z(zz), 0.0), per_min, f));
        }
        for (c, xx, zz) in [
            (90.0, 0.9, -0.001),
            (180.0, 0.6, -0.002),
            (270.0, 0.3, -0.001),
            (0.0, 0.0, 0.0),
        ] {
            x = xx + ox;
            want.push((xzc(x, z(zz), c), FeedRateMode::InverseTime, 0.25));
        }
        want.push((xzc(x, z(5.0), 0.0), per_min, 200.0));
    }
    want.push((xzc(x, 20.0 + oz, 0.0), FeedRateMode::PerMinute, 800.0));
    assert_eq!(r.moves.len(), want.len());
    for (k, (m, (p, mode, f))) in r.moves.iter().zip(&want).enumerate() {
        assert_eq!(m.kind, MoveKind::Linear, "move {k}");
        assert_at(m, *p, 1e-12, &format!("move {k}"));
        assert_eq!((m.feed.mode, m.feed.f), (*mode, Some(*f)), "move {k}");
    }
    // The last pass cuts the design: its cutting blocks carry no shift.
    let last_cut = &r.moves[r.moves.len() - 4];
    assert_eq!(last_cut.at.line, 26);
    assert!((last_cut.target.z() - (-0.001 + oz)).abs() < 1e-12);
    // The tool, the machine's M codes, the accepted codes and the end are reported.
    let kinds = r.event_kinds();
    assert!(kinds.contains(&&EventKind::Change(Change::Tool(303))));
    for m in ["M80", "M26.1", "M29"] {
        let code = Code::parse(m).unwrap();
        assert!(kinds.contains(&&EventKind::Change(Change::M(code))), "{m}");
    }
    assert!(kinds.contains(&&EventKind::Change(Change::Accepted(
        Code::parse("G103").unwrap()
    ))));
    assert!(kinds.contains(&&EventKind::Comment("DEPTH OF CUT MM".into())));
    assert_eq!(kinds.last(), Some(&&EventKind::End("M30".into())));
    let s = &r.summary;
    assert_eq!(s.dialect.dialect, Some(Dialect::Moore), "{:?}", s.dialect);
    // C270 → C0 crosses 0° in one block: wrapped.
    assert_eq!(s.c, CWrapping::Wrapped);
    // Without the accepted codes, G63 is an error naming it; without G1 at start, the first
    // axis word is.
    let e = read_with(
        "lab.nc",
        LAB_MOORE,
        ReaderOptions {
            accepted_codes: vec![],
            ..lab_options()
        },
    )
    .unwrap_err();
    assert!(
        matches!(&e.problem, Problem::Unknown(t) if t.starts_with("G63")),
        "{e}"
    );
    assert_eq!(
        (e.line, e.text.as_str()),
        (7, "G52 G63 G71 G103 G40 G18 G90")
    );
    let e = read_with(
        "lab.nc",
        LAB_MOORE,
        ReaderOptions {
            initial_motion: InitialMotion::None,
            ..lab_options()
        },
    )
    .unwrap_err();
    assert_eq!(e.line, 11, "{e}");
    assert!(e.to_string().contains("initial_motion"), "{e}");
}

#[test]
fn a_precitech_style_program_with_x_past_the_axis() {
    let text = "(PRECITECH STYLE, TOOL ON THE -X SIDE)
G71 G18 G90 G40 G94
G0 Z1.0
G0 X-0.5 C90.0
G1 Z0.0 F50.0
F12.5
G1 X-0.4 Z-0.01 C180.0
G1 X-0.3 Z-0.02 C270.0
G1 X-0.2 Z-0.03 C360.0
G1 X-0.1 Z-0.04 C450.0
G1 X0.0 Z-0.05 C540.0
G1 X0.05 Z-0.05 C585.0
G0 Z1.0
M30
";
    let r = read("pt.nc", text);
    let feeds: Vec<&Move> = r
        .moves
        .iter()
        .filter(|m| m.kind == MoveKind::Linear)
        .collect();
    let want = [
        (-0.5, 0.0, 90.0),
        (-0.4, -0.01, 180.0),
        (-0.3, -0.02, 270.0),
        (-0.2, -0.03, 360.0),
        (-0.1, -0.04, 450.0),
        (0.0, -0.05, 540.0),
        (0.05, -0.05, 585.0),
    ];
    assert_eq!(feeds.len(), want.len());
    for (m, &(x, z, c)) in feeds.iter().zip(&want) {
        assert_at(m, xzc(x, z, c), 1e-12, "precitech");
    }
    assert_eq!(feeds[0].feed.f, Some(50.0));
    assert!(feeds[1..].iter().all(|m| m.feed.f == Some(12.5)));
    let s = &r.summary;
    assert_eq!((s.x_negative, s.x_positive), (5, 1));
    assert_eq!(s.c, CWrapping::Cumulative);
    assert_eq!(s.c_range, Some((90.0, 585.0)));
    assert_eq!(s.dialect.dialect, Some(Dialect::Precitech));
}

const MAIN_WITH_CHILDREN: &str = "%
O1000 (MAIN)
G71 G18 G90 G94
G0 X1.0 Z1.0 C0
M98 P1001
M98 P1002 L2
M98 P2000
G0 Z1.0
M30
O2000 (A CHILD IN THE SAME FILE)
G1 X0.1 Z0.0 F10
M99
%
";

const CHILD_1001: &str = "%\nO1001\nG1 X0.9 Z0.0 F20\nC90 X0.8 Z-0.01\nM99\n%\n";
const CHILD_1002: &str = "G91\nG1 X-0.1 C90\nG90\nM99\n";

fn children(r: ProgramRef<'_>) -> Result<Option<Program<'static>>, String> {
    Ok(match r {
        ProgramRef::Number(1001) => Some(Program::from_text("O1001.nc", CHILD_1001)),
        ProgramRef::Number(1002) => Some(Program::from_text("O1002.nc", CHILD_1002)),
        _ => None,
    })
}

fn check_children_run(r: &Run) {
    let want = [
        ("main", 1.0, 1.0, 0.0),
        ("O1001.nc", 0.9, 0.0, 0.0),
        ("O1001.nc", 0.8, -0.01, 90.0),
        ("O1002.nc", 0.7, -0.01, 180.0),
        ("O1002.nc", 0.6, -0.01, 270.0),
        ("main", 0.1, 0.0, 270.0),
        ("main", 0.1, 1.0, 270.0),
    ];
    assert_eq!(r.moves.len(), want.len());
    for (m, &(file, x, z, c)) in r.moves.iter().zip(&want) {
        assert!(m.at.file.ends_with(file), "{} vs {file}", m.at.file);
        assert_at(m, xzc(x, z, c), 1e-12, file);
    }
    let calls: Vec<(String, u64)> = r
        .events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Call { program, repeats } => Some((program.to_string(), *repeats)),
            _ => None,
        })
        .collect();
    assert_eq!(calls.len(), 3);
    assert_eq!(calls[1].1, 2);
    assert!(calls[2].0.ends_with("O2000"), "{calls:?}");
    let returns = r
        .event_kinds()
        .iter()
        .filter(|k| ***k == EventKind::Return)
        .count();
    assert_eq!(returns, 3);
}

#[test]
fn m98_children_from_the_resolver_and_from_the_same_file() {
    let reader = Reader::new(
        Program::from_text("main", MAIN_WITH_CHILDREN),
        ReaderOptions::default(),
    )
    .with_resolver(children);
    check_children_run(&run(reader).unwrap_or_else(|e| panic!("{e}")));
    // Without the resolver, P1001 is not found: the message names the program and the file.
    let e = read_with("main", MAIN_WITH_CHILDREN, ReaderOptions::default()).unwrap_err();
    assert!(matches!(e.problem, Problem::Subprogram(_)), "{e}");
    assert_eq!((e.line, e.text.as_str()), (5, "M98 P1001"));
    assert!(e.to_string().contains("P1001"), "{e}");
}

#[test]
fn m98_children_are_found_beside_the_main_file_on_disk() {
    let dir = std::env::temp_dir().join(format!("spiralcam-ncreader-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let main = dir.join("main.nc");
    std::fs::write(&main, MAIN_WITH_CHILDREN).unwrap();
    std::fs::write(dir.join("O1001.nc"), CHILD_1001).unwrap();
    std::fs::write(dir.join("1002"), CHILD_1002).unwrap();
    let reader = Reader::new(Program::open(&main).unwrap(), ReaderOptions::default())
        .with_resolver(files_beside(&main));
    let r = run(reader).unwrap_or_else(|e| panic!("{e}"));
    // The same run, the children named by their files.
    let files: Vec<String> = r
        .moves
        .iter()
        .map(|m| {
            Path::new(&*m.at.file)
                .file_name()
                .unwrap()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    assert_eq!(
        files,
        [
            "main.nc", "O1001.nc", "O1001.nc", "1002", "1002", "main.nc", "main.nc"
        ]
    );
    // Two files that could both be P1002: an error listing them.
    std::fs::write(dir.join("O1002.nc"), "M99\n").unwrap();
    let reader = Reader::new(Program::open(&main).unwrap(), ReaderOptions::default())
        .with_resolver(files_beside(&main));
    let e = run(reader).unwrap_err();
    assert!(e.to_string().contains("several files"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn iso_o_word_loops_and_calls() {
    let text = "G21 G18 G90
#<depth> = 0
o100 repeat [3]
  #<depth> = [#<depth> - 0.01]
  o<pass> call [#<depth>] [2]
o100 endrepeat
o<finish> call
M2
o<pass> sub
  G1 X#2 Z#1 F100
  G1 X0 Z#1
o<pass> endsub
";
    let finish = |r: ProgramRef<'_>| -> Result<Option<Program<'static>>, String> {
        Ok((r == ProgramRef::Name("finish")).then(|| {
            Program::from_text("finish.ngc", "o<finish> sub\nG0 Z5\no<finish> endsub\nM2\n")
        }))
    };
    let reader = Reader::new(
        Program::from_text("iso.ngc", text),
        ReaderOptions::default(),
    )
    .with_resolver(finish);
    let r = run(reader).unwrap_or_else(|e| panic!("{e}"));
    let mut want = Vec::new();
    for pass in 1..=3 {
        let z = -0.01 * pass as f64;
        want.push(xzc(2.0, z, 0.0));
        want.push(xzc(0.0, z, 0.0));
    }
    want.push(xzc(0.0, 5.0, 0.0));
    assert_eq!(r.moves.len(), want.len());
    for (m, w) in r.moves.iter().zip(&want) {
        assert_at(m, *w, 1e-12, "o-word program");
    }
    assert_eq!(r.moves[0].at.line, 10);
    assert_eq!(&*r.moves[6].at.file, "finish.ngc");
    assert_eq!(r.summary.dialect.dialect, Some(Dialect::Iso));
}

/// A sub called many times is looked for once: the calling file is read to its end once, the
/// sub's own file once, then every call seeks to the body.
#[test]
fn repeated_calls_do_not_read_the_files_again() {
    let main = format!(
        "G21 G0 X0\no1 repeat [200]\no<kid> call\no1 endrepeat\nM2\n{}",
        "(filler)\n".repeat(1000)
    );
    let kid = |r: ProgramRef<'_>| -> Result<Option<Program<'static>>, String> {
        Ok((r == ProgramRef::Name("kid"))
            .then(|| Program::from_text("kid.ngc", "o<kid> sub\nG1 X1 F1\no<kid> endsub\n")))
    };
    let reader = Reader::new(
        Program::from_text("main.ngc", main),
        ReaderOptions::default(),
    )
    .with_resolver(kid);
    let r = run(reader).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.moves.len(), 201);
    // 5 lines of the main program, 2 a pass, the main file and the sub's file read once
    // (1005 + 3), 2 lines of the body a call.
    let want = 5 + 2 * 199 + 1005 + 3 + 2 * 200;
    assert!(
        r.summary.lines_read <= want as u64,
        "{} lines",
        r.summary.lines_read
    );
}

/// The two centres of the circles of radius `r` through `a` and `b`, in (z, x).
fn centres(a: (f64, f64), b: (f64, f64), r: f64) -> [(f64, f64); 2] {
    let (dz, dx) = (b.0 - a.0, b.1 - a.1);
    let d = dz.hypot(dx);
    let h = (r * r - d * d / 4.0).sqrt();
    let mid = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
    let (uz, ux) = (-dx / d, dz / d);
    [
        (mid.0 + h * uz, mid.1 + h * ux),
        (mid.0 - h * uz, mid.1 - h * ux),
    ]
}

/// The signed angle swept from `a` to `b` about `c`, in (z, x), positive counter-clockwise
/// with z to the right and x up, the way `turn` goes (+1 G3, −1 G2).
fn sweep(c: (f64, f64), a: (f64, f64), b: (f64, f64), turn: f64) -> f64 {
    let t0 = (a.1 - c.1).atan2(a.0 - c.0);
    let t1 = (b.1 - c.1).atan2(b.0 - c.0);
    let mut s = t1 - t0;
    if turn > 0.0 && s <= 0.0 {
        s += TAU;
    }
    if turn < 0.0 && s >= 0.0 {
        s -= TAU;
    }
    s
}

#[test]
fn a_2d_turning_program_with_arcs() {
    let text = "(2-D TURNING: X AND Z ONLY)
G18 G21 G90 G94
G0 X6 Z2
G1 Z0 F100
G1 X5
G2 X3 Z-2 R2
G1 Z-4
G3 X5 Z-6 I2 K0
G0 X7
G0 Z2
M30
";
    let r = read("turn.nc", text);
    let want = [
        (6.0, 2.0),
        (6.0, 0.0),
        (5.0, 0.0),
        (3.0, -2.0),
        (3.0, -4.0),
        (5.0, -6.0),
        (7.0, -6.0),
        (7.0, 2.0),
    ];
    assert_eq!(r.moves.len(), want.len());
    for (m, &(x, z)) in r.moves.iter().zip(&want) {
        assert_at(m, xzc(x, z, 0.0), 1e-12, "turning");
    }
    // G2 R2 from (z 0, x 5) to (z −2, x 3): of the two circles through both points, the one
    // swept clockwise by less than half a turn.
    let MoveKind::Arc {
        clockwise,
        centre_x,
        centre_z,
    } = r.moves[3].kind
    else {
        panic!("{:?}", r.moves[3].kind)
    };
    assert!(clockwise);
    let (a, b) = ((0.0, 5.0), (-2.0, 3.0));
    let c = centres(a, b, 2.0)
        .into_iter()
        .find(|&c| sweep(c, a, b, -1.0).abs() <= std::f64::consts::PI)
        .unwrap();
    assert!(
        (centre_z - c.0).abs() < 1e-12 && (centre_x - c.1).abs() < 1e-12,
        "{c:?}"
    );
    // G3 I2 K0 from (z −4, x 3): centre (z −4, x 5), three quarters of a turn.
    let MoveKind::Arc {
        clockwise,
        centre_x,
        centre_z,
    } = r.moves[5].kind
    else {
        panic!()
    };
    assert!(!clockwise);
    assert_eq!((centre_x, centre_z), (5.0, -4.0));
    let s = sweep((-4.0, 5.0), (-4.0, 3.0), (-6.0, 5.0), 1.0);
    assert!((s - 1.5 * std::f64::consts::PI).abs() < 1e-12);
    assert_eq!(r.summary.c, CWrapping::NoC);
    assert_eq!(r.summary.axes.letters(), "XZ");
    assert_eq!(r.summary.arc_moves, 2);
    // An arc out of the Z-X plane, or moving C, is refused with the reason.
    for (bad, why) in [
        ("G17 G2 X1 Y1 I1 J0", "G18"),
        ("G2 X3 Z-2 C10 R2", "only X and Z"),
        ("G2 X3 Z-2 I5 K5", "radius"),
    ] {
        let t = format!("G21 G0 X5 Z0\n{bad}\nM2\n");
        let e = read_with("arc.nc", &t, ReaderOptions::default()).unwrap_err();
        assert!(e.to_string().contains(why), "{bad}: {e}");
        assert_eq!(e.line, 2, "{e}");
    }
}

#[test]
fn words_without_spaces_cases_comments_percent_n_words_and_block_delete() {
    let text = "%
; a semicolon comment line
N10 G21G18G90G94 (modal line)
N20 g0x1.5z1c0
N30 G1Z0F100 ; trailing comment
/N40 G1 X9 (deleted block)
N50 X9.0Z0.04C10
N60 x -0.5 z -0.02 c 2 0
N70 M2
%
this text after the closing percent is not read (
";
    for skip in [false, true] {
        let r = read_with(
            "words.ngc",
            text,
            ReaderOptions {
                skip_block_delete: skip,
                ..Default::default()
            },
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let mut want = vec![(1.5, 1.0, 0.0), (1.5, 0.0, 0.0)];
        if !skip {
            want.push((9.0, 0.0, 0.0));
        }
        want.extend([(9.0, 0.04, 10.0), (-0.5, -0.02, 20.0)]);
        let got: Vec<(f64, f64, f64)> = r
            .moves
            .iter()
            .map(|m| (m.target.x(), m.target.z(), m.target.c()))
            .collect();
        assert_eq!(got, want, "skip {skip}");
        let comments: Vec<&str> = r
            .events
            .iter()
            .filter_map(|e| match &e.kind {
                EventKind::Comment(c) => Some(c.as_str()),
                _ => None,
            })
            .collect();
        assert_eq!(
            comments,
            [
                "a semicolon comment line",
                "modal line",
                "trailing comment",
                "deleted block"
            ]
        );
        assert!(
            r.event_kinds()
                .contains(&&EventKind::BlockDelete { executed: !skip })
        );
        assert_eq!(r.event_kinds().last(), Some(&&EventKind::End("M2".into())));
    }
    // A closing % ends a program without M2; a byte-order mark and CR LF ends are no text.
    let r = read("pct.ngc", "\u{feff}%\r\nG0 X1\r\n%\r\nnot read\n");
    assert_eq!(r.event_kinds().last(), Some(&&EventKind::End("%".into())));
    assert_eq!(r.moves.len(), 1);
}

#[test]
fn fanuc_if_goto_then_and_nested_while_loops() {
    // Two nested loops, a conditional jump out of the inner one and an IF … THEN setting.
    let text = "G71 G18 G90
#1 = 0
WHILE [#1 LT 3] DO 1
#2 = 0
WHILE [#2 LT 5] DO 2
IF [#2 GE 2] GOTO 50
G1 X[#1] Z[-#2] F10
#2 = #2 + 1
END 2
N50 #1 = #1 + 1
IF [#1 EQ 2] THEN #3 = 7
END 1
G1 X#3 Z0
#4 = 0
N80 #4 = #4 + 1
G1 Z#4
IF [#4 LT 3] GOTO 80
M30
";
    let r = read("fanuc.nc", text);
    let mut want = Vec::new();
    for i in 0..3 {
        for j in 0..2 {
            want.push((i as f64, -(j as f64)));
        }
    }
    want.push((7.0, 0.0));
    for k in 1..=3 {
        want.push((7.0, k as f64));
    }
    let got: Vec<(f64, f64)> = r
        .moves
        .iter()
        .map(|m| (m.target.x(), m.target.z()))
        .collect();
    assert_eq!(got, want);
    assert_eq!(r.summary.dialect.dialect, Some(Dialect::Precitech));
    // A computed GOTO goes where its value says each time.
    let text = "G71 G18 G90\n#1 = 0\nN10 #1 = #1 + 1\n#5 = 20\nIF [#1 EQ 2] THEN #5 = 30\n\
                GOTO #5\nN20 G1 X#1 Z0 F1\nGOTO 10\nN30 G1 X#1 Z1\nM30\n";
    let r = read("computed.nc", text);
    let got: Vec<(f64, f64)> = r
        .moves
        .iter()
        .map(|m| (m.target.x(), m.target.z()))
        .collect();
    assert_eq!(got, [(1.0, 0.0), (2.0, 1.0)]);
    // Jumping into a loop is refused.
    let e = read_with(
        "into.nc",
        "G71 G1 X0 F1\nGOTO 5\nWHILE [1 EQ 1] DO 1\nN5 X1\nEND 1\nM30\n",
        ReaderOptions::default(),
    )
    .unwrap_err();
    assert!(matches!(e.problem, Problem::Unbalanced(_)), "{e}");
    assert!(e.to_string().contains("into a loop"), "{e}");
}

#[test]
fn feeds_keep_their_mode_and_units() {
    let text = "G21 G18 G90
G94 G1 X1 F100
G93
G1 X2
G1 X3 F5
X4
G20 G95 G1 X0.5 F0.01
G94 G1 X0.6 F2
M2
";
    let r = read("feeds.ngc", text);
    let feeds: Vec<(FeedRateMode, Option<f64>)> =
        r.moves.iter().map(|m| (m.feed.mode, m.feed.f)).collect();
    assert_eq!(
        feeds,
        [
            (FeedRateMode::PerMinute, Some(100.0)),
            // After G93 the old F (mm/min) means nothing: unknown until given.
            (FeedRateMode::InverseTime, None),
            (FeedRateMode::InverseTime, Some(5.0)),
            (FeedRateMode::InverseTime, Some(5.0)),
            // F on the line that sets inches is read in the units before (LinuxCNC sets the
            // feed before the units: rs274 prints SET_FEED_RATE before USE_LENGTH_UNITS).
            (FeedRateMode::PerRevolution, Some(0.01)),
            // Then inches: F in mm per minute.
            (FeedRateMode::PerMinute, Some(2.0 * 25.4)),
        ]
    );
    assert_eq!(r.moves[4].target.x(), 0.5 * 25.4);
    assert_eq!(r.summary.units, Some(Units::Millimetres));
    assert!(r.summary.mixed_units);
}

// ---------------------------------------------------------------------------------------
// Against LinuxCNC's rs274.

const RS274: &str = "/usr/bin/rs274";

/// rs274's moves as machine positions: (kind, position, arc centre (x, z)).
type CanonMove = (MoveKind, Position);

/// Runs `rs274 -g` and turns its canon calls into machine positions in mm: the printed position
/// (program coordinates, in the program's units at the time) plus the G5x and G92 offsets it
/// printed last (in the units of their time: rs274 does not print them again when the units
/// change), lengths × 25.4 in inch mode.
fn rs274_moves(dir: &Path, name: &str, text: &str) -> Vec<CanonMove> {
    if !Path::new(RS274).exists() {
        panic!(
            "{RS274} is missing: install linuxcnc-uspace (tests/run.sh does) to compare the \
             reader with LinuxCNC's interpreter"
        );
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let out = Command::new(RS274)
        .env("HOME", dir)
        .arg("-g")
        .arg(&path)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success()
            && stderr
                .lines()
                .all(|l| l.trim().is_empty() || l.trim() == "executing"),
        "rs274 {name}: {stderr}"
    );
    let mut scale = 1.0;
    let (mut g5x, mut g92) = ([0.0; 6], [0.0; 6]);
    let mut moves = Vec::new();
    for line in stdout.lines() {
        let Some(open) = line.find('(') else { continue };
        let call = line[..open].split_whitespace().last().unwrap_or("");
        let args: Vec<f64> = line[open + 1..line.rfind(')').unwrap_or(line.len())]
            .split(',')
            .filter_map(|a| a.trim().parse().ok())
            .collect();
        let length = |i: usize| if i < 3 { scale } else { 1.0 };
        let machine =
            |i: usize, v: f64, g5x: &[f64; 6], g92: &[f64; 6]| v * length(i) + g5x[i] + g92[i];
        match call {
            "USE_LENGTH_UNITS" => {
                scale = if line.contains("INCHES") { 25.4 } else { 1.0 };
            }
            "SET_G5X_OFFSET" => {
                for i in 0..6 {
                    g5x[i] = args[i + 1] * length(i);
                }
            }
            "SET_G92_OFFSET" => {
                for i in 0..6 {
                    g92[i] = args[i] * length(i);
                }
            }
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => {
                let mut p = Position::default();
                for (i, slot) in [0, 1, 2, 3, 4, 5].into_iter().enumerate() {
                    p.0[slot] = machine(i, args[i], &g5x, &g92);
                }
                let kind = if call == "STRAIGHT_FEED" {
                    MoveKind::Linear
                } else {
                    MoveKind::Rapid
                };
                moves.push((kind, p));
            }
            "ARC_FEED" => {
                // G18: first = Z, second = X; then rotation, Y, A, B, C.
                let mut p = Position::default();
                p.0[2] = machine(2, args[0], &g5x, &g92);
                p.0[0] = machine(0, args[1], &g5x, &g92);
                p.0[1] = machine(1, args[5], &g5x, &g92);
                p.0[5] = machine(5, args[8], &g5x, &g92);
                let kind = MoveKind::Arc {
                    clockwise: args[4] < 0.0,
                    centre_x: machine(0, args[3], &g5x, &g92),
                    centre_z: machine(2, args[2], &g5x, &g92),
                };
                moves.push((kind, p));
            }
            _ => {}
        }
    }
    moves
}

fn compare_with_rs274(name: &str, text: &str, tol: f64) {
    // rs274 maps $HOME/.tool.mmap: each run gets its own directory as HOME (see rs274.rs).
    let dir = std::env::temp_dir().join(format!(
        "spiralcam-rs274-reader-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let theirs = rs274_moves(&dir, name, text);
    let ours = read(name, text);
    assert_eq!(ours.moves.len(), theirs.len(), "{name}: number of moves");
    for (k, (m, (kind, p))) in ours.moves.iter().zip(&theirs).enumerate() {
        let at = format!("{name} move {k} (line {})", m.at.line);
        for i in 0..6 {
            assert!(
                (m.target.0[i] - p.0[i]).abs() <= tol,
                "{at}: axis {i}: ours {:?}, rs274 {:?}",
                m.target,
                p
            );
        }
        match (m.kind, kind) {
            (
                MoveKind::Arc {
                    clockwise,
                    centre_x,
                    centre_z,
                },
                MoveKind::Arc {
                    clockwise: c2,
                    centre_x: x2,
                    centre_z: z2,
                },
            ) => {
                assert_eq!(clockwise, *c2, "{at}");
                assert!(
                    (centre_x - x2).abs() <= tol && (centre_z - z2).abs() <= tol,
                    "{at}"
                );
            }
            (a, b) => assert_eq!(a, *b, "{at}"),
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// rs274 prints 4 decimals: half a unit of the 4th, plus the offsets' own rounding.
const CANON: f64 = 6e-5;

#[test]
fn iso_loops_variables_and_g52_read_as_rs274_reads_them() {
    let text = "%
(ISO program with loops, variables, G52 and a work offset)
G21 G18 G90 G40 G94
G10 L2 P2 X0.5 Z-1.25 C10
G55
#<passes> = 3
#<doc> = 0.002
#1 = 0
#8 = 0
G0 Z5
o100 while [#1 LT #<passes>]
  #8 = [#8 - #<doc>]
  G52 Z#8
  G0 X2.0 C0
  G1 Z0.1 F200
  o101 repeat [4]
    G1 X[2.0 - #1*0.1] Z[0.01*SIN[#1*30 + 15]] C[#1*90+45] F100
  o101 endrepeat
  o102 if [#1 EQ 1]
    G1 X1.5 Z0.02
  o102 elseif [#1 EQ 2]
    G1 X1.4 Z0.03
  o102 else
    G1 X1.3 Z0.04
  o102 endif
  o<pass> call [#1] [0.5]
  G0 Z5
  #1 = [#1 + 1]
o100 endwhile
G52 Z0
G0 X2 Z0
G2 X1 Z-1 I-1 K0
G3 X2 Z0 R1
G2 X1.5 Z-0.5 R-0.5
G0 Z5
M2
o<pass> sub
  G1 X[1 + #1 * #2] Z-0.001 C[#1*7.5]
  o<pass> return
o<pass> endsub
%
";
    compare_with_rs274("loops.ngc", text, CANON);
}

#[test]
fn inch_units_do_loops_g92_g7_and_g53_read_as_rs274_reads_them() {
    let text = "G20 G18 G90 G94
G10 L2 P3 X0.1 Z-0.5
G56
G0 X1 Z1 C0
#1 = 0
o200 do
  #1 = [#1 + 1]
  o202 if [#1 EQ 5]
    o200 break
  o202 endif
  o201 if [#1 EQ 2]
    o200 continue
  o201 endif
  G1 X[1 - #1 * 0.05] Z[-0.001 * #1] C[#1 * 36] F2
o200 while [#1 LT 10]
G91 G1 X-0.1 Z-0.01 C45
G90
G92 X0 Z0
G1 X0.1 Z0.1
G92.1
G7 G1 X1.0
G8
G10 L20 P3 Z0.25
G1 Z0
G53 G0 Z2
G21 G1 X10 Z-3
M2
";
    compare_with_rs274("inch.ngc", text, CANON * 25.4);
}

#[test]
fn m98_children_named_globals_and_extra_axes_read_as_rs274_reads_them() {
    // LinuxCNC 2.9 runs Fanuc-style M98 P… L… with the O… program in the same file.
    let text = "G21 G18 G90 G94
G0 X1 Y0.5 Z1 A0 C0
#<_step> = 0.05
M98 P100 L3
o1 repeat [2]
  G1 X[1 + #<_step>] A[#<_step>*10] F10
  #<_step> = [#<_step> * 2]
o1 endrepeat
G0 Z2
M2
O100
G91 G1 X-0.1 Z-0.01 C30 F5
G90
M99
";
    compare_with_rs274("m98.ngc", text, CANON);
}

#[test]
fn the_golden_iso_program_reads_as_rs274_reads_it() {
    let text = std::fs::read_to_string(golden("golden-iso.ngc")).unwrap();
    compare_with_rs274("golden-iso.ngc", &text, CANON);
}

// ---------------------------------------------------------------------------------------
// Bad input.

fn error_of(text: &str) -> ReadError {
    error_with(text, ReaderOptions::default())
}

fn error_with(text: &str, options: ReaderOptions) -> ReadError {
    match read_with("bad.nc", text, options) {
        Ok(r) => panic!("read without error: {} moves", r.moves.len()),
        Err(e) => e,
    }
}

#[test]
fn a_truncated_program_is_reported() {
    let full = std::fs::read_to_string(golden("golden-moore.nc")).unwrap();
    let lines: Vec<&str> = full.lines().collect();
    // Cut after line 100, and in the middle of line 101's number.
    for text in [
        lines[..100].join("\n") + "\n",
        lines[..100].join("\n") + "\nC12.3",
    ] {
        let e = error_of(&text);
        assert!(matches!(e.problem, Problem::Truncated(_)), "{e}");
        assert!(
            e.to_string().contains("without M2, M30 or a closing %"),
            "{e}"
        );
        assert!(e.line == 100 || e.line == 101, "{e}");
    }
    // A child that ends without M99.
    let reader = Reader::new(
        Program::from_text("main", "G0 X1\nM98 P7\nM30\n"),
        ReaderOptions::default(),
    )
    .with_resolver(|_| Ok(Some(Program::from_text("O0007", "G1 X2 F1\n"))));
    let e = run(reader).unwrap_err();
    assert_eq!(
        e.to_string(),
        "O0007:1: truncated: program 7 ends after line 1 without M99"
    );
}

#[test]
fn unbalanced_loops_and_ifs_are_reported() {
    for (text, line, says) in [
        (
            "G0 X1\nWHILE [1 LT 2] DO 1\nG1 X2 F1\n",
            3,
            "ends inside WHILE … DO 1 opened on line 2",
        ),
        (
            "G0 X1\nWHILE [1 GT 2] DO 1\nG1 X2 F1\nM30\n",
            2,
            "WHILE … DO 1 (line 2) is never closed",
        ),
        ("G0 X1\nEND 1\nM30\n", 2, "END 1 without WHILE … DO 1"),
        (
            "G0 X1\nWHILE [1 LT 2] DO 1\nEND 2\nM30\n",
            3,
            "the innermost open loop is WHILE … DO 1",
        ),
        (
            "G0 X1\no1 while [0]\nG1 X2\nM2\n",
            2,
            "o1 while (line 2) is never closed",
        ),
        (
            "G0 X1\no1 endwhile\nM2\n",
            2,
            "o1 endwhile without an open o1 while",
        ),
        (
            "G0 X1\no1 if [0]\nG1 X2\nM2\n",
            2,
            "o1 if (line 2) is never closed",
        ),
        ("G0 X1\no1 else\nM2\n", 2, "o1 else without an open o1 if"),
        ("G0 X1\no1 break\nM2\n", 2, "o1 break outside a loop"),
        ("G0 X1\no<s> endsub\nM2\n", 2, "endsub outside a call"),
        ("G0 X1\nGOTO 9\nM30\n", 2, "no line N9"),
        ("G0 X1\nM99\n", 2, "M99 in the main program"),
    ] {
        let e = error_of(text);
        assert!(e.to_string().contains(says), "{text:?}: {e}");
        assert_eq!(e.line, line, "{text:?}: {e}");
        assert!(
            matches!(e.problem, Problem::Unbalanced(_) | Problem::Unsupported(_)),
            "{e}"
        );
    }
}

#[test]
fn undefined_variables_unknown_words_and_programs_without_motion_are_reported() {
    let e = error_of("G21\n#1 = #2 + 1\nG1 X#1 F1\nM2\n");
    assert_eq!(
        e.to_string(),
        "bad.nc:2: #2 is read before it is set (`#1 = #2 + 1`)"
    );
    let e = error_of("G21\nG1 X#<depth> F1\nM2\n");
    assert_eq!(e.problem, Problem::Undefined("#<depth>".into()));
    let e = error_of("G21 G0 X1\nG1 X2 Q3 F1\nM2\n");
    assert_eq!(
        e.to_string(),
        "bad.nc:2: syntax: Q3 is used by nothing on its line (`G1 X2 Q3 F1`)"
    );
    let e = error_of("G21 G0 X1\nG1 X2 E0.5 F1\nM2\n");
    assert_eq!(e.problem, Problem::Unknown("the word E0.5".into()));
    let e = error_of("G21 G0 X1\nG12 X2\nM2\n");
    assert!(
        matches!(&e.problem, Problem::Unknown(t) if t.starts_with("G12 ")),
        "{e}"
    );
    let e = error_of("G21 G0 X1\nG1 X2 (open\nM2\n");
    assert_eq!(
        e.problem,
        Problem::Syntax("a comment `(` is not closed on its line".into())
    );
    for refused in ["G41 G1 X1 F1", "G43 H1", "G28", "G81 X1 Z1 R1", "G33 Z1 K1"] {
        let e = error_of(&format!("G21 G0 X0\n{refused}\nM2\n"));
        assert!(
            matches!(e.problem, Problem::Unsupported(_)),
            "{refused}: {e}"
        );
    }
    let e = error_of("(nothing but modes)\nG21 G90 G94\nM2\n");
    assert_eq!(e.to_string(), "bad.nc:0: the program makes no move");
    let e = error_of("G21 G0 X1\nG1 X[1/[2-2]] F1\nM2\n");
    assert!(matches!(e.problem, Problem::Arithmetic(_)), "{e}");
}

#[test]
fn runaway_loops_and_other_limits_stop_with_a_clear_error() {
    let small = ReaderOptions {
        max_loop_iterations: 1000,
        ..Default::default()
    };
    let e = error_with(
        "G0 X1\nWHILE [1 EQ 1] DO 1\nG1 X2 F1\nEND 1\nM30\n",
        small.clone(),
    );
    assert_eq!(
        e.to_string(),
        "bad.nc:2: limit: the passes of WHILE … DO 1 (line 2) exceeds 1000: a runaway loop? \
         the cap is ReaderOptions::max_loop_iterations (`WHILE [1 EQ 1] DO 1`)"
    );
    let e = error_with("G0 X1\nN5 G1 X2 F1\nGOTO 5\nM30\n", small.clone());
    assert!(e.to_string().contains("backward jumps of GOTO 5"), "{e}");
    let e = error_with("G0 X1\no1 do\no1 while [1]\nM2\n", small.clone());
    assert!(e.to_string().contains("passes of o1 do"), "{e}");
    // A repeat count past the cap is refused before it runs, with the default cap too.
    let e = error_of("G0 X1\no1 repeat [1000000000]\no1 endrepeat\nM2\n");
    assert!(
        e.to_string()
            .contains("o1 repeat [1000000000] exceeds 10000000"),
        "{e}"
    );
    let e = error_of("G0 X1\nM98 P1 L99999999\nM30\nO1\nM99\n");
    assert!(e.to_string().contains("repeat count L99999999"), "{e}");
    // The total of lines read.
    let e = error_with(
        "G0 X1\nWHILE [1 EQ 1] DO 1\nG1 X2 F1\nEND 1\nM30\n",
        ReaderOptions {
            max_lines: 500,
            ..Default::default()
        },
    );
    assert!(e.to_string().contains("the lines read exceeds 500"), "{e}");
    // A program calling itself: the call depth.
    let e = error_of("G0 X1\nM98 P1\nM30\nO1\nM98 P1\nM99\n");
    assert!(e.to_string().contains("call nesting exceeds 16"), "{e}");
    let e = error_of("G0 X1\no<r> call\nM2\no<r> sub\no<r> call\no<r> endsub\n");
    assert!(e.to_string().contains("call nesting exceeds 16"), "{e}");
    // Deep brackets, a long line.
    let deep = format!("G0 X{}1{}\nM2\n", "[".repeat(40), "]".repeat(40));
    assert!(matches!(error_of(&deep).problem, Problem::Limit { .. }));
    let long = format!("G0 X1 ({})\nM2\n", "x".repeat(5000));
    let e = error_of(&long);
    assert!(
        e.to_string().contains("the length of line 1 exceeds 4096"),
        "{e}"
    );
}

// ---------------------------------------------------------------------------------------
// Mutated programs: never a panic, always within the bounds.

/// Programs the mutations start from.
fn seeds() -> Vec<String> {
    let golden_head: String = std::fs::read_to_string(golden("golden-moore.nc"))
        .unwrap()
        .lines()
        .take(40)
        .map(|l| format!("{l}\n"))
        .collect::<String>()
        + "M30\n";
    vec![
        golden_head,
        LAB_MOORE.to_string(),
        MAIN_WITH_CHILDREN.to_string(),
        "G21 G18\n#1=0\no1 while [#1 LT 3]\no2 if [#1 EQ 1]\nG1 X#1 Z[#1*2] F10\no2 else\nG0 X1\no2 endif\n#1=[#1+1]\no1 endwhile\no<s> call [1]\nM2\no<s> sub\nG1 X#1\no<s> endsub\n".into(),
        "G71 G18 G90\n#1 = 0\nN10 #1 = #1 + 1\nG1 X#1 Z0 F1\nIF [#1 LT 4] GOTO 10\nG2 X0 Z-1 R2\nM30\n".into(),
    ]
}

/// Tokens the mutations insert.
const TOKENS: &[&str] = &[
    "[",
    "]",
    "#",
    "#1",
    "=",
    "(",
    ")",
    ";",
    "%",
    "/",
    "\n",
    " ",
    "WHILE [1 EQ 1] DO 1\n",
    "END 1\n",
    "GOTO 10\n",
    "N10",
    "M99\n",
    "M98 P1\n",
    "M98 P1000 L5\n",
    "o1 while [1]\n",
    "o1 endwhile\n",
    "o1 endif\n",
    "o<s> call\n",
    "o<s> sub\n",
    "G91",
    "G2",
    "G52 Z1",
    "X",
    "**",
    "SQRT[",
    "1e5",
    "-",
    ".",
    "0",
    "9999999999",
    "F",
    "IF [1] THEN",
    "\u{b5}",
    "\t",
];

fn mutate(seed: &str, edits: &[(usize, usize, usize)]) -> String {
    let mut b: Vec<u8> = seed.as_bytes().to_vec();
    for &(kind, at, n) in edits {
        let at = at % (b.len() + 1);
        match kind % 3 {
            0 => {
                let end = (at + n % 8).min(b.len());
                b.drain(at..end);
            }
            1 => {
                let t = TOKENS[n % TOKENS.len()].as_bytes();
                b.splice(at..at, t.iter().copied());
            }
            _ => {
                if at < b.len() {
                    b[at] = (n % 128) as u8;
                }
            }
        }
    }
    String::from_utf8_lossy(&b).into_owned()
}

proptest! {
    #![proptest_config(common::config(1000, 0x6e63_7265_6164))]

    #[test]
    fn mutated_programs_never_panic_and_stay_within_the_bounds(
        seed in 0usize..5,
        edits in prop::collection::vec((0usize..3, 0usize..4000, 0usize..1000), 1..4),
    ) {
        let seeds = seeds();
        let text = mutate(&seeds[seed], &edits);
        let options = ReaderOptions {
            max_lines: 20_000,
            max_loop_iterations: 500,
            ..lab_options()
        };
        let resolver_text = text.clone();
        let started = Instant::now();
        let mut reader = Reader::new(Program::from_text("m.nc", &text), options)
            .with_resolver(move |_| Ok(Some(Program::from_text("child.nc", resolver_text.clone()))));
        let mut steps = 0u64;
        let end = loop {
            match reader.next_step() {
                Ok(Some(_)) => steps += 1,
                Ok(None) => break None,
                Err(e) => break Some(e),
            }
        };
        let s = reader.summary();
        prop_assert!(s.lines_read <= 20_000, "{} lines", s.lines_read);
        prop_assert!(started.elapsed() < Duration::from_secs(5), "{:?}", started.elapsed());
        if let Some(e) = end {
            // Errors name a file and quote at most one line.
            prop_assert!(!e.to_string().is_empty());
            prop_assert!(!e.text.contains('\n'));
        } else {
            prop_assert!(steps > 0);
        }
        // After the end or an error the reader stays finished.
        prop_assert!(matches!(reader.next_step(), Ok(None)));
    }
}

#[test]
fn summary_counts_match_the_moves() {
    let r = read(
        "golden-moore.nc",
        &std::fs::read_to_string(golden("golden-moore.nc")).unwrap(),
    );
    let s = &r.summary;
    let count = |k: fn(&MoveKind) -> bool| r.moves.iter().filter(|m| k(&m.kind)).count() as u64;
    assert_eq!(s.rapid_moves, count(|k| *k == MoveKind::Rapid));
    assert_eq!(s.linear_moves, count(|k| *k == MoveKind::Linear));
    let mut by_line: HashMap<u64, usize> = HashMap::new();
    for m in &r.moves {
        *by_line.entry(m.at.line).or_default() += 1;
    }
    // A program without loops moves at most once per line.
    assert!(by_line.values().all(|&n| n == 1));
}
