//! A plan in slices (`Planner::run_slice`, what the page's Web Workers each run) against the
//! whole walk (`Planner::run`): the slices' program texts concatenated are the program byte for
//! byte, their figures merged (`Stats::merge`) are the walk's, field for field, and so is the
//! report; the display copies merged are the walk's segments. The seams are put where the
//! context matters: right after the first point and the approach, inside and at the edge of a
//! warm-start run, across a batch of the workers, at the path's last points and past its end.

mod common;

use common::planner_of;
use spiralcam::display::DisplayPath;
use spiralcam::job::Job;
use spiralcam::plan::{PlanSlice, Planner, Sinks};
use spiralcam::progress::ignore;
use spiralcam::report::Stats;

/// The program, the report and the display segments of the whole walk.
fn whole(planner: &Planner) -> (Vec<u8>, String, Vec<f32>) {
    let mut nc = Vec::new();
    let mut display = display_of(planner);
    let sinks = Sinks {
        nc: Some(&mut nc),
        display: Some(&mut display),
        ..Default::default()
    };
    let report = planner.run(sinks, &mut ignore).unwrap();
    (nc, report.to_json(), display.segments)
}

fn display_of(planner: &Planner) -> DisplayPath {
    let spiral = planner.spiral();
    DisplayPath::new(spiral.point_count_hint(), spiral.revolutions(), 3_000)
}

/// The same from slices between `seams` (the last slice runs to the end), and the merged
/// figures.
fn sliced(planner: &Planner, seams: &[u64]) -> (Vec<u8>, String, Vec<f32>, Stats) {
    let theta0 = planner.first_point().unwrap().theta;
    let (mut nc, mut stats, mut display, mut bytes) =
        (Vec::new(), Stats::default(), None::<DisplayPath>, 0);
    let mut ended = false;
    for (k, &first) in seams.iter().enumerate() {
        let end = seams.get(k + 1).copied().unwrap_or(u64::MAX);
        let mut part = display_of(planner).starting_at(first, theta0);
        let slice = planner
            .run_slice(first..end, Some(&mut nc), Some(&mut part), &mut ignore)
            .unwrap();
        // The figures travel between the page's workers as JSON.
        let slice: PlanSlice =
            serde_json::from_str(&serde_json::to_string(&slice).unwrap()).unwrap();
        assert!(
            !ended || slice.stats.points == 0,
            "a slice after the end has points"
        );
        ended |= slice.ended;
        let part = {
            let mut d: DisplayPath =
                serde_json::from_str(&serde_json::to_string(&part).unwrap()).unwrap();
            d.segments = part.segments;
            d
        };
        assert_eq!(slice.first, first);
        stats = stats.merge(slice.stats);
        display = Some(match display {
            None => part,
            Some(d) => d.merge(part),
        });
        bytes += slice.nc_bytes;
    }
    assert!(ended, "the last slice ends the path");
    assert_eq!(bytes, nc.len() as u64);
    let report = planner.report_of(&stats, bytes, &mut ignore).unwrap();
    (nc, report.to_json(), display.unwrap().segments, stats)
}

fn check(name: &str, json: &str) {
    let planner = planner_of(json);
    let n = planner.spiral().point_count_hint();
    let (nc, report, segments) = whole(&planner);
    let seam_sets: Vec<Vec<u64>> = vec![
        vec![0],
        vec![0, 1],
        vec![0, 2, 3, 63, 64, 65, 129],
        vec![0, 5, 16_384 + 7, n - 2],
        vec![0, n / 3, n - 1, n, n + 10],
        vec![0, 100, 101, 102, n / 2 + 31],
    ];
    let (_, _, _, one) = sliced(&planner, &[0]);
    for mut seams in seam_sets {
        // On a path shorter than a batch the seam past 16 384 falls after the end.
        seams.sort_unstable();
        let (s_nc, s_report, s_segments, stats) = sliced(&planner, &seams);
        assert!(s_nc == nc, "{name} {seams:?}: program differs");
        assert!(s_report == report, "{name} {seams:?}: report");
        assert_eq!(s_segments, segments, "{name} {seams:?}: display");
        assert_eq!(stats, one, "{name} {seams:?}: figures");
    }
}

fn job(dialect: &str, sampling: &str, compensation: &str, surface: &str, r: f64) -> String {
    // The two-way jobs search the whole arc at every point: a smaller part keeps them quick.
    let diameter = if compensation == "two_way" { 1.6 } else { 3.0 };
    format!(
        r#"{{"name":"slices","part":{{"diameter_mm":{diameter}}},"surface":{surface},
            "tool":{{"nose_radius_mm":{r}}},"machine":{{"spindle_rpm":500}},
            "strategy":{{"feed_mm_per_rev":0.01,"sampling":{sampling},"compensation":"{compensation}"}},
            "output":{{"dialect":"{dialect}"}}}}"#
    )
}

const LENS_ARRAY: &str = r#"{"type":"lens_array","lens_radius_mm":2.84,"aperture_mm":1.0,
    "pitch_mm":1.0,"grid":"rectangular","form":"concave"}"#;
const SINUSOID: &str =
    r#"{"type":"sinusoid","amplitude_mm":0.01,"wavelength_x_mm":0.3,"wavelength_y_mm":0.25}"#;

#[test]
fn slices_join_into_the_whole_program_report_and_drawing() {
    let angle = r#"{"type":"constant_angle","points_per_rev":120}"#;
    let arc = r#"{"type":"constant_arc","arc_length_mm":0.02,"max_angle_step_deg":5}"#;
    check(
        "ISO, lens array",
        &job("iso", angle, "one_way", LENS_ARRAY, 0.2),
    );
    // Moore writes F only when it changes: constant arc changes it along the path.
    check("Moore, arc", &job("moore", arc, "one_way", LENS_ARRAY, 0.2));
    // Two-way over a sinusoid whose troughs are tighter than the nose: runs of loop points
    // and X reversals across the seams.
    check(
        "two-way loops",
        &job("precitech", angle, "two_way", SINUSOID, 0.5),
    );
}

#[test]
fn two_way_slices_cut_through_loop_runs() {
    let planner = planner_of(&job(
        "iso",
        r#"{"type":"constant_angle","points_per_rev":120}"#,
        "two_way",
        SINUSOID,
        0.5,
    ));
    let report = planner.run(Sinks::default(), &mut ignore).unwrap();
    assert!(report.two_way_loops > 3, "{} loops", report.two_way_loops);
    assert!(report.x_reversals > 3, "{} reversals", report.x_reversals);
    // A seam at every point: every run of loop points and every reversal straddles one.
    let n = planner.spiral().point_count_hint();
    let every: Vec<u64> = (0..n.min(400)).collect();
    let head = planner.run_slice(0..400, None, None, &mut ignore).unwrap();
    let head = planner.report_of(&head.stats, 0, &mut ignore).unwrap();
    assert!(
        head.two_way_loops > 3 && head.x_reversals > 3,
        "the first 400 points hold {} loops and {} reversals",
        head.two_way_loops,
        head.x_reversals
    );
    let (_, _, _, stats) = sliced(&planner, &every);
    assert_eq!(stats, sliced(&planner, &[0]).3);
}

#[test]
fn jobs_that_need_the_whole_path_are_refused_in_slices() {
    let planner = planner_of(&common::passes_job_json(
        "passes",
        "iso",
        "controller",
        None,
    ));
    let e = planner
        .run_slice(0..10, None, None, &mut ignore)
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "program = sliced: a program with passes is written in one piece"
    );
    let split = common::coarse_grid_fts();
    let planner = Planner::new(&split).unwrap();
    assert_eq!(
        planner.slicing(),
        Err("the machine dynamics need the whole path at once")
    );
    let mut space = Job::from_json(&job(
        "iso",
        r#"{"type":"space_spiral","points_per_rev":36}"#,
        "one_way",
        LENS_ARRAY,
        0.2,
    ))
    .unwrap();
    space.part.diameter_mm = 1.0;
    assert!(
        Planner::new(&space)
            .unwrap()
            .slicing()
            .unwrap_err()
            .contains("space spiral")
    );
    assert_eq!(
        planner_of(&job(
            "iso",
            r#"{"type":"constant_angle","points_per_rev":36}"#,
            "two_way",
            SINUSOID,
            0.2
        ))
        .slicing(),
        Ok(())
    );
}
