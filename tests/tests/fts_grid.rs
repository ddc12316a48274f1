//! The servo's gridded table (`spiralcam plan --fts-table`) read back from its PMAC text and
//! interpolated here, independently of the crate's lookup, as the Turbo PMAC manual describes a
//! two-dimensional `DEFINE COMP` table: the header parsed, the entries (1/16 count, the origin's
//! implied 0 first) turned into mm, each path point's C and X turned into counts of the row and
//! column motors, rolled over into the spans and interpolated bilinearly between the four
//! entries around it. Against the planned W (the dynamics' split, signed as the program's word)
//! at every path point the error stays within the reported error (the two computations agree
//! to 1e-6 µm), which stays within the job's tolerance; the columns wrap at 360°, the table is
//! zero at its origin, the header's numbers are the job's, the CSV is the same grid, a tighter
//! tolerance gives a finer grid, X negative rolls over as it should, and bad options are
//! refused naming the field. On the example job `sinusoid-grid-fts.json` itself and on a
//! coarser variant for speed.

mod common;

use common::{coarse_grid_fts, example_job};
use spiralcam::dynamics::Dynamics;
use spiralcam::dynamics::fts_grid::{FtsGrid, FtsGridReport};
use spiralcam::job::{Compensation, Dialect, FtsGridSpec, Job};
use spiralcam::nc::fts_grid::{write_csv, write_pmac};
use spiralcam::plan::{Planner, Sinks};
use std::ops::ControlFlow;

/// The job's table options, or their defaults.
fn spec(job: &Job) -> FtsGridSpec {
    job.output.fts_grid.clone().unwrap_or_default()
}

/// A sized table and the planned path in machine coordinates: X mm, C degrees (cumulative),
/// W mm. With one-way compensation the path's X and C are the spiral's own (the nose centre
/// stays on the spiral), read here from the spiral rather than compensated a second time.
struct Run {
    grid: FtsGrid,
    points: Vec<[f64; 3]>,
}

fn run(job: &Job) -> Run {
    let planner = Planner::new(job).unwrap_or_else(|e| panic!("{}: {e}", job.name));
    let conv = job.output.conventions();
    let go = &mut |_| ControlFlow::Continue(());
    let d = Dynamics::run_with_grid(planner.path(), true, go).unwrap();
    let w = d.w_fts_mm.unwrap();
    assert_eq!(job.strategy.compensation, Compensation::OneWay);
    let points: Vec<[f64; 3]> = planner
        .spiral()
        .points()
        .zip(&w)
        .map(|(p, w)| {
            [
                conv.x_sign * p.rho,
                conv.c_sign * p.theta.to_degrees(),
                conv.z_sign * w,
            ]
        })
        .collect();
    assert_eq!(points.len(), w.len());
    Run {
        grid: d.fts_grid.expect("the grid"),
        points,
    }
}

/// The PMAC text of a grid.
fn pmac(grid: &FtsGrid) -> String {
    let mut out = Vec::new();
    write_pmac(&mut out, &grid.table, &grid.comments).unwrap();
    String::from_utf8(out).unwrap()
}

/// A PMAC table read back from its text.
#[derive(Debug)]
struct Table {
    owner: String,
    rows: usize,
    columns: usize,
    row_motor: String,
    column_motor: String,
    target: String,
    row_span: u64,
    column_span: u64,
    /// (rows + 1)·(columns + 1) entries, the origin's (implied) 0 first.
    entries: Vec<i64>,
}

impl Table {
    fn parse(text: &str) -> Table {
        let mut lines = text.lines().filter(|l| !l.starts_with(';'));
        let owner = lines.next().unwrap().to_string();
        let define = lines.next().unwrap();
        let args = define.strip_prefix("DEFINE COMP ").unwrap();
        let parts: Vec<&str> = args.split(',').collect();
        assert_eq!(parts.len(), 6, "{define}");
        let (rows, columns) = parts[0].split_once('.').unwrap();
        let mut entries = vec![0];
        for l in lines {
            assert!(l.len() < 255, "a line of {} characters", l.len());
            entries.extend(l.split_whitespace().map(|e| e.parse::<i64>().unwrap()));
        }
        let table = Table {
            owner,
            rows: rows.parse().unwrap(),
            columns: columns.parse().unwrap(),
            row_motor: parts[1].into(),
            column_motor: parts[2].into(),
            target: parts[3].into(),
            row_span: parts[4].parse().unwrap(),
            column_span: parts[5].parse().unwrap(),
            entries,
        };
        assert_eq!(
            table.entries.len(),
            (table.rows + 1) * (table.columns + 1),
            "(Rows+1)·(Columns+1) − 1 entries after the header"
        );
        table
    }

    fn entry(&self, row: usize, column: usize) -> i64 {
        self.entries[row * (self.columns + 1) + column]
    }

    /// The correction with the row motor at `a` counts and the column motor at `b`, 1/16
    /// count: each rolled over into its span, the column spacing RowSpan/Columns, the row
    /// spacing ColumnSpan/Rows, bilinear between the four entries.
    fn correction(&self, a: f64, b: f64) -> f64 {
        let col = a.rem_euclid(self.row_span as f64) * self.columns as f64 / self.row_span as f64;
        let row =
            b.rem_euclid(self.column_span as f64) * self.rows as f64 / self.column_span as f64;
        let k = (col.floor() as usize).min(self.columns - 1);
        let j = (row.floor() as usize).min(self.rows - 1);
        let (u, v) = (col - k as f64, row - j as f64);
        let e = |j, k| self.entry(j, k) as f64;
        (1.0 - v) * ((1.0 - u) * e(j, k) + u * e(j, k + 1))
            + v * ((1.0 - u) * e(j + 1, k) + u * e(j + 1, k + 1))
    }
}

/// The largest |table − W| over the path, µm, the table read back as the controller reads it
/// (C the row motor, X the column motor) plus the reported offset.
fn read_back_error(spec: &FtsGridSpec, report: &FtsGridReport, t: &Table, run: &Run) -> f64 {
    let offset_mm = report.w_offset_um * 1e-3;
    let mut worst = 0.0f64;
    for &[x, c, w] in &run.points {
        let a = c / 360.0 * spec.c_counts_per_rev as f64;
        let b = x * spec.x_counts_per_mm;
        let table_w = offset_mm + t.correction(a, b) / (16.0 * spec.w_counts_per_mm);
        worst = worst.max((table_w - w).abs());
    }
    worst * 1e3
}

/// Every check of a run's table against its job (module docs); returns the table read back.
fn check(job: &Job, run: &Run, text: &str) -> Table {
    let spec = spec(job);
    let r = &run.grid.report;
    let t = Table::parse(text);
    // The error read back: within the reported error, which is within the tolerance.
    let e = read_back_error(&spec, r, &t, run);
    assert!(e <= r.max_error_um + 1e-9, "{e} > {}", r.max_error_um);
    assert!(
        (e - r.max_error_um).abs() < 1e-6,
        "{e} vs {}",
        r.max_error_um
    );
    assert!(r.max_error_um <= spec.tolerance_um, "{r:?}");
    assert!(r.rms_error_um <= r.max_error_um);
    // The header's numbers are the job's: C the row motor over one turn, X the column motor.
    assert_eq!(t.owner, format!("#{}", spec.w_motor));
    let d = if spec.desired_position { "D" } else { "" };
    assert_eq!(t.row_motor, format!("#{}{d}", spec.c_motor));
    assert_eq!(t.column_motor, format!("#{}{d}", spec.x_motor));
    assert_eq!(t.target, format!("#{}", spec.w_motor));
    assert_eq!((t.rows, t.columns), (r.rows, r.columns));
    assert_eq!(t.row_span, spec.c_counts_per_rev);
    assert_eq!(t.row_span % t.columns as u64, 0, "whole counts a column");
    assert_eq!(t.column_span, r.x_span_counts);
    assert_eq!(t.column_span % t.rows as u64, 0, "whole counts a row");
    // X's span: the part, one row more (where X = 0 rolls over), not two.
    let spacing = (t.column_span / t.rows as u64) as f64;
    let x_max = run.points.iter().map(|p| p[0].abs()).fold(0.0, f64::max);
    let x_max_counts = x_max * spec.x_counts_per_mm;
    assert!(t.column_span as f64 >= x_max_counts + spacing, "{t:?}");
    assert!(
        (t.column_span as f64) < x_max_counts + 2.0 * spacing,
        "{t:?}"
    );
    assert!((r.x_spacing_mm - spacing / spec.x_counts_per_mm).abs() < 1e-15);
    // The columns wrap: the column at 360° is the column at 0°.
    for j in 0..=t.rows {
        assert_eq!(t.entry(j, t.columns), t.entry(j, 0), "row {j}");
    }
    // Zero at the origin: the first row is the centre (one point) on every column, and so is
    // the last row, X = 0 reached by rollover.
    for k in 0..=t.columns {
        assert_eq!(t.entry(0, k), 0, "column {k}");
        assert_eq!(t.entry(t.rows, k), 0, "column {k}");
    }
    t
}

/// The CSV of `grid` against its table `t` read back: the columns' angles, the rows' X and
/// W = offset + entry in mm, to the CSV's 1 pm.
fn check_csv(grid: &FtsGrid, csv: &str, t: &Table, spec: &FtsGridSpec, x_sign: f64) {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "x_mm/c_deg");
    assert_eq!(header.len(), t.columns + 2);
    for (k, c) in header[1..].iter().enumerate() {
        let c: f64 = c.parse().unwrap();
        assert!(
            (c - 360.0 * k as f64 / t.columns as f64).abs() < 5e-10,
            "{k}"
        );
    }
    let spacing = t.column_span as f64 / t.rows as f64 / spec.x_counts_per_mm;
    let offset = grid.report.w_offset_um * 1e-3;
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), t.rows + 1);
    for (j, line) in rows.iter().enumerate() {
        let values: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        let x = match j {
            0 => 0.0,
            j if j == t.rows => 0.0,
            j if x_sign > 0.0 => j as f64 * spacing,
            j => j as f64 * spacing - t.column_span as f64 / spec.x_counts_per_mm,
        };
        assert!((values[0] - x).abs() < 5e-10, "row {j}: {}", values[0]);
        for k in 0..=t.columns {
            let w = offset + t.entry(j, k) as f64 / (16.0 * spec.w_counts_per_mm);
            assert!((values[k + 1] - w).abs() < 5.1e-10, "row {j}, column {k}");
        }
    }
}

#[test]
fn the_example_jobs_table_read_back_reproduces_the_planned_w() {
    let job = example_job("sinusoid-grid-fts.json");
    let run = run(&job);
    let text = pmac(&run.grid);
    check(&job, &run, &text);
    let r = &run.grid.report;
    eprintln!(
        "{}: {} rows × {} columns ({} entries, {} × {} mm apart), max error {:.4} µm, RMS \
         {:.4} µm (tolerance {} µm), PMAC {} bytes, CSV {} bytes",
        job.name,
        r.rows,
        r.columns,
        r.entries,
        r.c_spacing_deg,
        r.x_spacing_mm,
        r.max_error_um,
        r.rms_error_um,
        r.tolerance_um,
        r.pmac_bytes,
        r.csv_bytes
    );
    assert_eq!(r.pmac_bytes, text.len() as u64);
}

#[test]
fn the_planners_files_are_the_table_and_its_csv() {
    let job = coarse_grid_fts();
    let run = run(&job);
    let planner = Planner::new(&job).unwrap();
    let (mut text, mut csv) = (Vec::new(), Vec::new());
    let sinks = Sinks {
        fts_grid: Some(&mut text),
        fts_grid_csv: Some(&mut csv),
        ..Default::default()
    };
    let report = planner
        .run_with_dynamics(sinks, &mut |_| ControlFlow::Continue(()))
        .unwrap();
    let figures = report.dynamics.unwrap().fts_grid.unwrap();
    assert_eq!(figures, run.grid.report);
    let text = String::from_utf8(text).unwrap();
    assert_eq!(text, pmac(&run.grid));
    let csv = String::from_utf8(csv).unwrap();
    assert_eq!(figures.csv_bytes, csv.len() as u64);
    let mut written = Vec::new();
    write_csv(&mut written, &run.grid.table).unwrap();
    assert_eq!(csv.as_bytes(), written);
    let t = check(&job, &run, &text);
    check_csv(&run.grid, &csv, &t, &spec(&job), 1.0);
    assert!(text.starts_with("; spiralcam "), "{text}");
    assert!(text.contains("; job sinusoid-grid-fts\n"), "{text}");
}

#[test]
fn x_negative_rolls_over_and_reads_back_alike() {
    // Precitech style: X = −ρ, so the X motor's positions −S…0 roll over to 0…S.
    let mut job = coarse_grid_fts();
    job.output.dialect = Dialect::Precitech;
    assert_eq!(job.output.conventions().x_sign, -1.0);
    job.output.fts_grid = Some(FtsGridSpec {
        x_motor: 2,
        c_motor: 5,
        w_motor: 7,
        x_counts_per_mm: 262_144.0,
        c_counts_per_rev: 1 << 22,
        w_counts_per_mm: 500_000.0,
        desired_position: true,
        ..Default::default()
    });
    let run = run(&job);
    let text = pmac(&run.grid);
    assert!(text.contains(",#5D,#2D,#7,4194304,"), "{text}");
    let t = check(&job, &run, &text);
    let mut csv = Vec::new();
    write_csv(&mut csv, &run.grid.table).unwrap();
    check_csv(
        &run.grid,
        &String::from_utf8(csv).unwrap(),
        &t,
        &spec(&job),
        -1.0,
    );
}

#[test]
fn a_tighter_tolerance_gives_a_finer_grid() {
    let mut job = coarse_grid_fts();
    let mut last: Option<FtsGridReport> = None;
    for tolerance_um in [0.2, 0.05, 0.02] {
        job.output.fts_grid = Some(FtsGridSpec {
            tolerance_um,
            ..Default::default()
        });
        let run = run(&job);
        check(&job, &run, &pmac(&run.grid));
        let r = run.grid.report;
        if let Some(l) = last {
            assert!(r.entries > l.entries, "{tolerance_um}: {r:?} after {l:?}");
            assert!(r.rows >= l.rows && r.columns >= l.columns);
            assert!(r.max_error_um < l.max_error_um);
        }
        last = Some(r);
    }
}

/// Why `job` cannot be planned with its table (the message).
fn refusal(job: &Job) -> String {
    let planner = match Planner::new(job) {
        Ok(p) => p,
        Err(e) => return e.to_string(),
    };
    let sinks = Sinks {
        fts_grid: Some(&mut std::io::sink()),
        ..Default::default()
    };
    planner
        .run_with_dynamics(sinks, &mut |_| ControlFlow::Continue(()))
        .unwrap_err()
        .to_string()
}

#[test]
fn bad_options_are_refused_naming_the_field() {
    let with = |grid: &str| {
        let mut job: serde_json::Value =
            serde_json::from_str(&coarse_grid_fts().to_json()).unwrap();
        job["output"]["fts_grid"] = serde_json::from_str(grid).unwrap();
        match Job::from_json(&job.to_string()) {
            Ok(job) => refusal(&job),
            Err(e) => e.to_string(),
        }
    };
    assert_eq!(
        with(r#"{"tolerance_um": 0}"#),
        "output.fts_grid.tolerance_um = 0: must be a finite number > 0"
    );
    assert_eq!(
        with(r#"{"c_motor": 1}"#),
        "output.fts_grid.c_motor = 1: must differ from output.fts_grid.x_motor: the table's two \
         source motors"
    );
    assert_eq!(
        with(r#"{"w_motor": 40}"#),
        "output.fts_grid.w_motor = 40: must be a motor number in [1, 32]"
    );
    assert!(
        with(r#"{"x_counts_per_mm": -1}"#)
            .starts_with("output.fts_grid.x_counts_per_mm = -1: must be a finite number > 0")
    );
    let e = with(r#"{"tolerance": 1}"#);
    assert!(
        e.starts_with("job: output.fts_grid.tolerance: unknown field `tolerance`"),
        "{e}"
    );
    let e = with(r#"{"c_counts_per_rev": 1.5}"#);
    assert!(
        e.starts_with("job: output.fts_grid.c_counts_per_rev"),
        "{e}"
    );
    // Bounded: a tolerance that would need more than a million entries.
    let e = with(r#"{"tolerance_um": 0.001}"#);
    assert!(
        e.starts_with("output.fts_grid.tolerance_um = 0.001: needs a table of at least"),
        "{e}"
    );
    assert!(e.contains("above the most written, 1000000"), "{e}");
}
