//! Programs with a `program` section (issue 12): a program split into child programs, called
//! in order, cuts exactly what the single-file program cuts (its children's blocks, with the
//! calls replaced by them, give back the single file line for line), in every dialect and both
//! loop kinds; and the section's bad input is refused naming the field.

mod common;

use common::{ChildBuffers, passes_job_json};
use spiralcam::job::Job;
use spiralcam::nc::program::ChildFiles;
use spiralcam::plan::{Planner, Sinks};
use spiralcam::report::Report;
use std::ops::ControlFlow;

/// The test job with `limit`.
fn job_json(dialect: &str, loop_kind: &str, limit: Option<u64>) -> String {
    passes_job_json("Children", dialect, loop_kind, limit)
}

fn plan(json: &str, children: Option<&mut ChildBuffers>) -> (String, Report) {
    let job = Job::from_json(json).expect("job");
    let planner = Planner::new(&job).expect("planner");
    let mut nc = Vec::new();
    let report = planner
        .run(
            Sinks {
                nc: Some(&mut nc),
                children: children.map(|c| c as &mut dyn ChildFiles),
                ..Default::default()
            },
            &mut |_| ControlFlow::Continue(()),
        )
        .expect("plan");
    (String::from_utf8(nc).expect("ascii"), report)
}

/// The child number a line calls, if it is a call.
fn called(line: &str, children: &ChildBuffers) -> Option<usize> {
    if let Some(n) = line.strip_prefix("M98 P") {
        return Some(n.trim().parse().expect("M98 P number"));
    }
    let name = line.strip_prefix("o<")?.strip_suffix("> call")?;
    let c = children
        .0
        .iter()
        .position(|(file, _)| file.strip_suffix(".ngc") == Some(name))
        .unwrap_or_else(|| panic!("no child {name}"));
    Some(c + 1)
}

/// A child's body: its lines without the first (`O1`, `o<…> sub`) and the last (`M99`,
/// `o<…> endsub` and `M2`).
fn body(text: &str) -> Vec<&str> {
    let lines: Vec<&str> = text.lines().collect();
    let first = lines[0];
    assert!(
        first.starts_with('O') || first.ends_with("> sub"),
        "child's first line: {first}"
    );
    let tail = if first.starts_with('O') { 1 } else { 2 };
    lines[1..lines.len() - tail].to_vec()
}

fn splits_into_children_and_back(dialect: &str, loop_kind: &str) {
    let (single, single_report) = plan(&job_json(dialect, loop_kind, None), None);
    let limit = single.len() as u64 / 5;
    let mut children = ChildBuffers::default();
    let (main, report) = plan(
        &job_json(dialect, loop_kind, Some(limit)),
        Some(&mut children),
    );
    let program = report.program.expect("program report");
    assert!(
        children.0.len() >= 3,
        "{dialect}: {} children",
        children.0.len()
    );
    assert_eq!(program.children.len(), children.0.len());
    for (i, (name, text)) in children.0.iter().enumerate() {
        assert!(
            text.len() as u64 <= limit,
            "{name}: {} bytes > {limit}",
            text.len()
        );
        assert_eq!(program.children[i].bytes, text.len() as u64, "{name}");
        assert_eq!(program.children[i].name, *name);
    }
    assert!(main.len() as u64 <= limit, "main {} bytes", main.len());
    assert_eq!(report.nc_bytes, main.len() as u64);

    let mut calls = Vec::new();
    let mut rebuilt: Vec<String> = Vec::new();
    let mut child_starts = Vec::new();
    for line in main.lines() {
        match called(line, &children) {
            Some(n) => {
                calls.push(n);
                let text = std::str::from_utf8(&children.0[n - 1].1).expect("ascii");
                child_starts.push(rebuilt.len());
                rebuilt.extend(body(text).into_iter().map(str::to_string));
            }
            None => rebuilt.push(line.to_string()),
        }
    }
    let mut sorted = calls.clone();
    sorted.dedup();
    assert_eq!(
        sorted,
        (1..=children.0.len()).collect::<Vec<_>>(),
        "{dialect}: each child called, in order"
    );
    let single_lines: Vec<&str> = single.lines().collect();
    let differ: Vec<(usize, &str, &str)> = single_lines
        .iter()
        .zip(&rebuilt)
        .enumerate()
        .filter(|(i, (a, b))| {
            **a != b.as_str() && !(child_starts.contains(i) && modal_f_added(&single_lines, *i, b))
        })
        .map(|(i, (a, b))| (i + 1, *a, b.as_str()))
        .take(5)
        .collect();
    assert!(
        differ.is_empty(),
        "{dialect} {loop_kind}: lines differ: {differ:#?}"
    );
    assert_eq!(
        single_lines.len(),
        rebuilt.len(),
        "{dialect} {loop_kind}: line count"
    );
    assert_eq!(single_report.points, report.points);
}

/// Whether `rebuilt`, the first block of a child, is line `i` of the single program with the
/// feed in effect there written again (a child's first block carries F: a controller need not
/// keep a modal F across a call).
fn modal_f_added(single: &[&str], i: usize, rebuilt: &str) -> bool {
    let Some(extra) = rebuilt.strip_prefix(single[i]) else {
        return false;
    };
    let modal = single[..i]
        .iter()
        .rev()
        .find_map(|l| l.split_whitespace().find(|w| w.starts_with('F')));
    modal.is_some_and(|f| extra == format!(" {f}"))
}

#[test]
fn children_in_call_order_are_the_single_program_moore() {
    splits_into_children_and_back("moore", "controller");
    splits_into_children_and_back("moore", "unrolled");
}

#[test]
fn children_in_call_order_are_the_single_program_precitech() {
    splits_into_children_and_back("precitech", "controller");
}

#[test]
fn children_in_call_order_are_the_single_program_iso() {
    splits_into_children_and_back("iso", "controller");
    splits_into_children_and_back("iso", "unrolled");
}

/// The job's error, as text, with `program` replaced by `section`.
fn refused(section: &str) -> String {
    let json = job_json("moore", "controller", None);
    let start = json.find(r#""program""#).expect("program");
    let json = format!("{}\"program\": {section}\n}}", &json[..start]);
    match Job::from_json(&json).map(|job| Planner::new(&job).map(|p| plan_error(&p))) {
        Err(e) => e.to_string(),
        Ok(Err(e)) => e.to_string(),
        Ok(Ok(e)) => e,
    }
}

fn plan_error(planner: &Planner) -> String {
    match planner.run(Sinks::default(), &mut |_| ControlFlow::Continue(())) {
        Ok(_) => "accepted".to_string(),
        Err(e) => e.to_string(),
    }
}

fn assert_refused(section: &str, field: &str, says: &str) {
    let e = refused(section);
    assert!(
        e.contains(field) && e.contains(says),
        "{section}: expected {field} / {says}, got: {e}"
    );
}

#[test]
fn bad_program_sections_are_refused_naming_the_field() {
    assert_refused(r#"{ "passes": [] }"#, "program.passes", "no passes");
    assert_refused(
        r#"{ "passes": [ { "count": 0, "depth_of_cut_um": 5 } ] }"#,
        "program.passes[0].count",
        "0",
    );
    assert_refused(
        r#"{ "passes": [ { "count": 1, "depth_of_cut_um": -5 } ] }"#,
        "program.passes[0].depth_of_cut_um",
        "-5",
    );
    assert_refused(
        r#"{ "approach": [ { "height_mm": 0.1, "feed_mm_per_min": 100 },
                         { "height_mm": 0.5, "feed_mm_per_min": 20 } ] }"#,
        "program.approach[1].height_mm",
        "0.5",
    );
    assert_refused(
        r#"{ "approach": [ { "height_mm": -0.5, "feed_mm_per_min": 100 } ] }"#,
        "program.approach[0].height_mm",
        "-0.5",
    );
    assert_refused(
        r#"{ "max_program_bytes": 100 }"#,
        "program.max_program_bytes",
        "100",
    );
    assert_refused(r#"{ "tool": "X3" }"#, "program.tool", "X3");
    assert_refused(r#"{ "c_axis_on": "M2a" }"#, "program.c_axis_on", "M2a");
    assert_refused(r#"{ "work_offset": "G60" }"#, "program.work_offset", "G60");
    assert_refused(r#"{ "loop": "twice" }"#, "loop", "twice");
    assert_refused(
        r#"{ "retract_height_mm": -1 }"#,
        "program.retract_height_mm",
        "-1",
    );
    assert_refused(
        r#"{ "safe_z_mm": 0.0001, "retract_height_mm": 1 }"#,
        "program.safe_z_mm",
        "0.0001",
    );
    // A sensible section is accepted (the tests above refuse for their own reason).
    assert_eq!(refused(r#"{ "tool": "T0303" }"#), "accepted");
}
