//! The fast tool servo's share W of a split path ([`split`](mod@crate::dynamics::split))
//! resampled onto a grid of spindle angle × X, sized so that the controller's bilinear
//! interpolation of the table reproduces the planned W at every path point within the job's
//! tolerance (`output.fts_grid.tolerance_um`), as a two-dimensional compensation table
//! ([`crate::nc::fts_grid::CompTable`], whose docs give the format and its conventions).
//!
//! Everything is in the program's machine coordinates: `C = c_sign·θ` (degrees, cumulative),
//! `X = x_sign·ρ`, `W = z_sign·(z − Z_slide)`, so the table sits on the motors as the program's
//! words do.
//!
//! **W between the path's revolutions.** Along each column's angle C_k the spiral crosses C_k
//! once a revolution; W and X there are interpolated linearly between the two path points
//! around the crossing (the controller moves linearly between blocks). A point on the spindle
//! axis (ρ below 1 pm: the centre, where the path ends) lies on every column. The column's
//! value at a row's X is interpolated linearly in X between two consecutive crossings of that
//! column (in path order) that bracket it; where several pairs bracket it (X reverses), the last
//! along the path counts. Beyond the outermost crossing of a column (the first pass), and inside
//! the innermost, W continues the line through the two crossings at that end, kept within the
//! column's range of W widened by its width either way (held where the end has a single
//! crossing): holding the value instead leaves a corner in W at the first pass, which bilinear
//! interpolation follows only to first order in the row spacing. A column the path never crosses (a path shorter than a revolution)
//! takes the values of the next column that it does; a path that crosses none gives zeros.
//! The column at 360° repeats the column at 0°. The controller's table is zero at its origin
//! (X = 0, C = 0, the centre), so the entries are W less W there, the offset, which the
//! servo's programmed position must supply.
//!
//! **Sizing.** The tolerance less the table's resolution (half of 1/16 count of W) is shared
//! between the two directions, each estimated on its own: along C, the linear interpolation of
//! W between consecutive column crossings against every path point between them; along X, the
//! table at each column's own angle against every crossing of that column. The columns (whole
//! divisors of the counts per revolution) and the row spacing (whole counts) are refined from a
//! coarse start, each step scaled by the square root of the error ratio (the error of linear
//! interpolation goes as the square of the spacing), until each direction meets its share; then
//! the table itself — quantized to whole 1/16 counts and read through the controller's
//! rolled-over bilinear lookup ([`crate::nc::fts_grid::CompTable::correction_at`]) — is checked
//! against W at every path point, and the shares are tightened until it meets the tolerance.
//! The figures reported (`max_error_um`, `rms_error_um`) are of that last check.
//!
//! **Bounds.** At most [`MAX_ENTRIES`] entries and [`MAX_CROSSINGS`] column crossings a pass;
//! a tolerance that would need more is refused naming `output.fts_grid.tolerance_um`, with the
//! figures and a tolerance that would do.

use crate::field::{FieldError, short};
use crate::job::FtsGridSpec;
use crate::nc::Conventions;
use crate::nc::fts_grid::{CompTable, MAX_ENTRY, Motors, write_csv, write_pmac};
use crate::path::Location;
use crate::progress::{Progress, Stage};
use serde::Serialize;
use std::ops::ControlFlow;

/// The most entries a table may have, `(rows + 1)·(columns + 1)`.
pub const MAX_ENTRIES: u64 = 1_000_000;

/// The most column crossings one pass over the path may find (revolutions × columns).
pub const MAX_CROSSINGS: u64 = 200_000_000;

/// Rounds of tightening after the first sizing.
const MAX_ROUNDS: usize = 8;

/// Steps of each direction's refinement.
const MAX_STEPS: usize = 48;

/// A point closer to the spindle axis lies on every column, mm.
const ON_AXIS_MM: f64 = 1e-9;

/// The field the sizing names.
const TOLERANCE: &str = "output.fts_grid.tolerance_um";

/// The path as the table sees it: the spindle angle, radius and servo share of every point.
#[derive(Debug, Clone, Copy)]
pub struct ServoPath<'a> {
    /// Cumulative angle θ of each point, radians.
    pub theta: &'a [f64],
    /// Radius ρ of each point, mm.
    pub rho: &'a [f64],
    /// The servo's share of each point's height, mm (z − Z_slide).
    pub w: &'a [f64],
}

/// The signs that put the path on the motors.
#[derive(Debug, Clone, Copy)]
struct Signs {
    c: f64,
    x: f64,
    z: f64,
}

/// The path in machine coordinates.
#[derive(Debug, Clone, Copy)]
struct Machine<'a> {
    path: ServoPath<'a>,
    signs: Signs,
}

impl Machine<'_> {
    fn len(&self) -> usize {
        self.path
            .theta
            .len()
            .min(self.path.rho.len())
            .min(self.path.w.len())
    }

    /// C of point `i`, degrees, cumulative.
    fn c(&self, i: usize) -> f64 {
        self.signs.c * self.path.theta[i].to_degrees()
    }

    /// ρ of point `i`, mm.
    fn rho(&self, i: usize) -> f64 {
        self.path.rho[i]
    }

    /// W of point `i`, mm, signed as the program's word.
    fn w(&self, i: usize) -> f64 {
        self.signs.z * self.path.w[i]
    }
}

/// Where the spiral crosses a column's angle.
#[derive(Debug, Clone, Copy)]
struct Crossing {
    /// The column, 0…columns − 1.
    column: usize,
    /// The angle, degrees, cumulative.
    c: f64,
    rho: f64,
    w: f64,
}

/// What a pass over the path meets, in path order.
#[derive(Debug, Clone, Copy)]
enum Event {
    /// A path point (its index), before the crossings of the segment it starts.
    Point(usize),
    /// A crossing of a column.
    Crossing(Crossing),
}

/// Calls `f` with every path point and every crossing of the columns (`columns` a turn) in
/// path order.
fn pass(m: &Machine, columns: usize, mut f: impl FnMut(Event)) {
    let n = m.len();
    let step = 360.0 / columns as f64;
    let column = |k: i64| k.rem_euclid(columns as i64) as usize;
    for i in 0..n {
        f(Event::Point(i));
        let c0 = m.c(i);
        if i + 1 == n {
            // The last point, when it lies on a column.
            let k = c0 / step;
            if (k - k.round()).abs() < 1e-9 {
                f(Event::Crossing(Crossing {
                    column: column(k.round() as i64),
                    c: c0,
                    rho: m.rho(i),
                    w: m.w(i),
                }));
            }
            break;
        }
        let c1 = m.c(i + 1);
        // Column angles in [c0, c1) going up, (c1, c0] going down.
        let (mut k, end, dk) = match c1.partial_cmp(&c0) {
            Some(std::cmp::Ordering::Greater) => {
                ((c0 / step).ceil() as i64, (c1 / step).ceil() as i64, 1)
            }
            Some(std::cmp::Ordering::Less) => {
                ((c0 / step).floor() as i64, (c1 / step).floor() as i64, -1)
            }
            _ => continue,
        };
        while k != end {
            let c = k as f64 * step;
            let t = (c - c0) / (c1 - c0);
            let lerp = |a: f64, b: f64| a + t * (b - a);
            f(Event::Crossing(Crossing {
                column: column(k),
                c,
                rho: lerp(m.rho(i), m.rho(i + 1)),
                w: lerp(m.w(i), m.w(i + 1)),
            }));
            k += dk;
        }
    }
}

/// The largest error of interpolating W linearly in C between consecutive crossings of
/// `columns` columns, over the path points between them, mm.
fn error_along_c(m: &Machine, columns: usize) -> f64 {
    let mut pending: Vec<usize> = Vec::new();
    let mut last: Option<Crossing> = None;
    let mut worst = 0.0f64;
    pass(m, columns, |e| match e {
        Event::Point(i) => pending.push(i),
        Event::Crossing(x) => {
            if let Some(a) = last {
                let dc = x.c - a.c;
                for &i in &pending {
                    let t = if dc != 0.0 { (m.c(i) - a.c) / dc } else { 0.5 };
                    worst = worst.max((a.w + t * (x.w - a.w) - m.w(i)).abs());
                }
            }
            pending.clear();
            last = Some(x);
        }
    });
    worst
}

/// The grid's shape: columns a turn, the rows' spacing and count.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Shape {
    columns: usize,
    x_spacing_counts: u64,
    rows: usize,
}

/// What the sizing needs of the path and the job.
struct Sizing<'a> {
    m: Machine<'a>,
    spec: &'a FtsGridSpec,
    x_negative: bool,
    /// The largest ρ, mm.
    rho_max: f64,
    /// Turns of the spindle over the path.
    turns: f64,
}

impl Sizing<'_> {
    /// The shape with `columns` and a row spacing of `spacing` counts.
    fn shape(&self, columns: usize, spacing: u64) -> Shape {
        let cells = (self.rho_max * self.spec.x_counts_per_mm / spacing as f64).ceil() as usize;
        // One row more, past the part: the span's end, where X = 0 rolls over.
        let rows = cells.max(1) + 1;
        Shape {
            columns,
            x_spacing_counts: spacing,
            rows,
        }
    }

    /// Refuses a shape beyond the bounds, naming the tolerance.
    fn check(&self, s: Shape) -> Result<(), FieldError> {
        let entries = (s.rows as u64 + 1) * (s.columns as u64 + 1);
        let crossings = ((self.turns + 1.0) * s.columns as f64) as u64;
        let tol = self.spec.tolerance_um;
        let (what, over) = if entries > MAX_ENTRIES {
            (
                format!(
                    "a table of at least {entries} entries ({} rows × {} columns), above the \
                     most written, {MAX_ENTRIES}",
                    s.rows, s.columns
                ),
                entries as f64 / MAX_ENTRIES as f64,
            )
        } else if crossings > MAX_CROSSINGS {
            (
                format!(
                    "at least {crossings} column crossings a pass ({} columns × {:.0} turns), \
                     above the most, {MAX_CROSSINGS}",
                    s.columns, self.turns
                ),
                crossings as f64 / MAX_CROSSINGS as f64,
            )
        } else {
            return Ok(());
        };
        Err(FieldError::new(
            TOLERANCE,
            tol,
            format!(
                "needs {what}, to reproduce W within it: a tolerance of about {} µm or more",
                short(tol * over * 1.05)
            ),
        ))
    }

    /// The table of shape `s`: W resampled onto it and quantized.
    fn table(&self, s: Shape) -> Result<CompTable, FieldError> {
        self.check(s)?;
        let spec = self.spec;
        let mut t = CompTable {
            rows: s.rows,
            columns: s.columns,
            x_spacing_counts: s.x_spacing_counts,
            x_counts_per_mm: spec.x_counts_per_mm,
            c_counts_per_rev: spec.c_counts_per_rev,
            w_counts_per_mm: spec.w_counts_per_mm,
            x_negative: self.x_negative,
            entries: Vec::new(),
            w_offset_mm: 0.0,
            motors: Motors {
                x: spec.x_motor,
                c: spec.c_motor,
                w: spec.w_motor,
                desired_position: spec.desired_position,
            },
        };
        let rho: Vec<f64> = (0..=s.rows).map(|j| t.row_x_mm(j).abs()).collect();
        let values = resample(&self.m, &rho, s.columns);
        t.w_offset_mm = values[0];
        let per_mm = 16.0 * spec.w_counts_per_mm;
        let mut entries = Vec::with_capacity(values.len());
        for v in &values {
            let e = ((v - t.w_offset_mm) * per_mm).round();
            if e.abs() > MAX_ENTRY as f64 {
                let (lo, hi) = values
                    .iter()
                    .fold((f64::MAX, f64::MIN), |(l, h), &v| (l.min(v), h.max(v)));
                return Err(FieldError::new(
                    "output.fts_grid.w_counts_per_mm",
                    spec.w_counts_per_mm,
                    format!(
                        "W spans {} to {} µm about its value at the origin, {} µm: beyond the \
                         table's entries of ±{MAX_ENTRY} sixteenths of a count; at most {} counts \
                         per mm",
                        short((lo - t.w_offset_mm) * 1e3),
                        short((hi - t.w_offset_mm) * 1e3),
                        short(t.w_offset_mm * 1e3),
                        short(MAX_ENTRY as f64 / 16.0 / (hi - lo).max(1e-300))
                    ),
                ));
            }
            entries.push(e as i64);
        }
        entries[0] = 0;
        t.entries = entries;
        Ok(t)
    }

    /// The largest error of the table along X: at each column's own angle, against every
    /// crossing of that column, mm.
    fn error_along_x(&self, t: &CompTable) -> f64 {
        let spacing = t.c_spacing_counts() as f64;
        let per_mm = 16.0 * t.w_counts_per_mm;
        let mut worst = 0.0f64;
        pass(&self.m, t.columns, |e| {
            if let Event::Crossing(x) = e {
                let xc = self.m.signs.x * x.rho * t.x_counts_per_mm;
                let w = t.w_offset_mm + t.correction_at(xc, x.column as f64 * spacing) / per_mm;
                worst = worst.max((w - x.w).abs());
            }
        });
        worst
    }

    /// The smallest column count, from `from` up, that divides the counts per revolution (see
    /// [`crate::nc::fts_grid`]).
    fn columns_from(&self, from: usize) -> Result<usize, FieldError> {
        let cpr = self.spec.c_counts_per_rev;
        let most = (MAX_ENTRIES / 2) as usize;
        (from.max(1)..=most)
            .find(|&n| cpr.is_multiple_of(n as u64))
            .ok_or_else(|| {
                FieldError::new(
                    "output.fts_grid.c_counts_per_rev",
                    cpr,
                    format!(
                        "has no divisor from {from} to {most}: the columns must split a turn \
                         into whole counts"
                    ),
                )
            })
    }
}

/// `values[j·(columns + 1) + k]`: W at radius `rho[j]` on column k (module docs), mm.
fn resample(m: &Machine, rho: &[f64], columns: usize) -> Vec<f64> {
    let mut columns_of = Columns::new(rho, columns);
    let mut on_axis = false;
    pass(m, columns, |e| match e {
        Event::Point(i) => {
            // A run of points on the axis counts once, at its first point.
            let here = m.rho(i) < ON_AXIS_MM;
            if here && !on_axis {
                for k in 0..columns {
                    columns_of.add(k, 0.0, m.w(i));
                }
            }
            on_axis = here;
        }
        Event::Crossing(x) => columns_of.add(x.column, x.rho, x.w),
    });
    columns_of.finish()
}

/// The columns being filled from their crossings.
struct Columns {
    /// Rows' radii, mm.
    rho: Vec<f64>,
    /// (radius, row) by radius.
    order: Vec<(f64, usize)>,
    columns: usize,
    values: Vec<f64>,
    /// Each column's last crossing (ρ, W).
    last: Vec<Option<(f64, f64)>>,
    /// Each column's ends.
    ends: Vec<Ends>,
}

/// A column's two outermost and two innermost crossings (ρ, W), and its range of W.
#[derive(Debug, Clone, Copy)]
struct Ends {
    outer: [(f64, f64); 2],
    inner: [(f64, f64); 2],
    low: f64,
    high: f64,
}

impl Default for Ends {
    fn default() -> Self {
        Self {
            outer: [(f64::NEG_INFINITY, 0.0); 2],
            inner: [(f64::INFINITY, 0.0); 2],
            low: f64::INFINITY,
            high: f64::NEG_INFINITY,
        }
    }
}

impl Ends {
    fn crossed(&self) -> bool {
        self.low <= self.high
    }

    fn add(&mut self, r: f64, w: f64) {
        (self.low, self.high) = (self.low.min(w), self.high.max(w));
        let [o0, o1] = self.outer;
        if r > o0.0 {
            self.outer = [(r, w), o0];
        } else if r > o1.0 && r < o0.0 {
            self.outer[1] = (r, w);
        }
        let [i0, i1] = self.inner;
        if r < i0.0 {
            self.inner = [(r, w), i0];
        } else if r < i1.0 && r > i0.0 {
            self.inner[1] = (r, w);
        }
    }

    /// W at `r` beyond the crossings: on the line through the two crossings at that end,
    /// kept within the column's range of W widened by its width on either side (a bound for
    /// crossings nearly at the same radius); held where the end has one crossing.
    fn beyond(&self, r: f64) -> f64 {
        let [a, b] = if r >= self.outer[0].0 {
            self.outer
        } else {
            self.inner
        };
        if !b.0.is_finite() {
            return a.1;
        }
        let w = a.1 + (r - a.0) * (b.1 - a.1) / (b.0 - a.0);
        let width = self.high - self.low;
        w.clamp(self.low - width, self.high + width)
    }
}

impl Columns {
    fn new(rho: &[f64], columns: usize) -> Self {
        let mut order: Vec<(f64, usize)> = rho.iter().copied().zip(0..).collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        Self {
            rho: rho.to_vec(),
            order,
            columns,
            values: vec![f64::NAN; rho.len() * (columns + 1)],
            last: vec![None; columns],
            ends: vec![Ends::default(); columns],
        }
    }

    /// A crossing of column `k` at radius `r` with W = `w`: the rows between it and the
    /// column's previous crossing are interpolated.
    fn add(&mut self, k: usize, r: f64, w: f64) {
        let width = self.columns + 1;
        if let Some((r0, w0)) = self.last[k] {
            let (lo, hi) = (r0.min(r), r0.max(r));
            let from = self.order.partition_point(|&(x, _)| x < lo);
            for &(x, j) in self.order[from..].iter().take_while(|&&(x, _)| x <= hi) {
                let t = if hi > lo { (x - r0) / (r - r0) } else { 1.0 };
                self.values[j * width + k] = w0 + t * (w - w0);
            }
        }
        self.last[k] = Some((r, w));
        self.ends[k].add(r, w);
    }

    /// The values, with the cells no pair of crossings reached filled (module docs).
    fn finish(mut self) -> Vec<f64> {
        let (width, columns) = (self.columns + 1, self.columns);
        for (k, ends) in self.ends.iter().enumerate().filter(|(_, e)| e.crossed()) {
            for (j, &r) in self.rho.iter().enumerate() {
                let v = &mut self.values[j * width + k];
                if v.is_nan() {
                    *v = ends.beyond(r);
                }
            }
        }
        let crossed = |k: usize| self.ends[k].crossed();
        if let Some(first) = (0..columns).find(|&k| crossed(k)) {
            for k in (0..columns).filter(|&k| !crossed(k)) {
                let from = (1..=columns)
                    .map(|d| (k + d) % columns)
                    .find(|&q| crossed(q))
                    .unwrap_or(first);
                for j in 0..self.rho.len() {
                    self.values[j * width + k] = self.values[j * width + from];
                }
            }
        }
        for j in 0..self.rho.len() {
            self.values[j * width + columns] = self.values[j * width];
        }
        // A path that crosses no column at all.
        for v in self.values.iter_mut().filter(|v| v.is_nan()) {
            *v = 0.0;
        }
        self.values
    }
}

/// What the table is, for the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FtsGridReport {
    /// Intervals along X (the `rows` of `DEFINE COMP rows.columns`); the grid has one row more.
    pub rows: usize,
    /// Intervals along C (`columns`); the grid has one column more, the last at 360°.
    pub columns: usize,
    /// Entries in the table, `(rows + 1)·(columns + 1)`.
    pub entries: u64,
    /// Spacing of the rows, mm.
    pub x_spacing_mm: f64,
    /// Spacing of the columns, degrees.
    pub c_spacing_deg: f64,
    /// The rows' span, counts of X.
    pub x_span_counts: u64,
    /// The rows' span, mm.
    pub x_span_mm: f64,
    /// The columns' span, counts of C: one revolution.
    pub c_span_counts: u64,
    /// W at the table's origin, µm: the servo's programmed position the table adds to.
    pub w_offset_um: f64,
    /// The tolerance asked, µm.
    pub tolerance_um: f64,
    /// The table's resolution, µm: half of 1/16 count of W.
    pub resolution_um: f64,
    /// Largest |table − W| over the path points, µm (the table as written, through the
    /// controller's bilinear lookup).
    pub max_error_um: f64,
    /// Its root mean square over the path points, µm.
    pub rms_error_um: f64,
    /// Where the largest error is (X and C of the point).
    pub max_error_at: Location,
    /// Size of the PMAC text, bytes.
    pub pmac_bytes: u64,
    /// Size of the CSV, bytes.
    pub csv_bytes: u64,
}

/// A sized table with its figures and the comments of its file.
#[derive(Debug, Clone, PartialEq)]
pub struct FtsGrid {
    /// The table.
    pub table: CompTable,
    /// Its figures.
    pub report: FtsGridReport,
    /// The comment lines that head its PMAC text.
    pub comments: Vec<String>,
}

/// The errors of `table` at every point: largest, RMS and where, mm.
fn errors(m: &Machine, t: &CompTable) -> (f64, f64, Location) {
    let (mut worst, mut sum, mut at) = (0.0f64, 0.0, 0);
    for i in 0..m.len() {
        let e = (t.w_mm_at(m.signs.x * m.rho(i), m.c(i)) - m.w(i)).abs();
        sum += e * e;
        if e > worst {
            (worst, at) = (e, i);
        }
    }
    let n = m.len().max(1) as f64;
    let loc = match m.len() {
        0 => Location::new(0.0, 0.0),
        _ => Location::new(m.signs.x * m.rho(at), m.c(at).to_radians()),
    };
    (worst, (sum / n).sqrt(), loc)
}

impl FtsGrid {
    /// Sizes and fills the table of `path`'s W for the options `spec` and the program's
    /// conventions `conv` (module docs), for the job named `job`; `progress` sees the passes
    /// over the path ([`Stage::FtsGrid`]) and may cancel (`Ok(None)`).
    pub fn build(
        job: &str,
        path: ServoPath,
        spec: &FtsGridSpec,
        conv: &Conventions,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<Option<Self>, FieldError> {
        let m = Machine {
            path,
            signs: Signs {
                c: conv.c_sign,
                x: conv.x_sign,
                z: conv.z_sign,
            },
        };
        let n = m.len();
        if let Some(i) = (0..n).find(|&i| m.rho(i).is_nan() || m.rho(i) < -ON_AXIS_MM) {
            return Err(FieldError::new(
                "strategy.compensation",
                format!("a radius of {} mm at point {i}", short(m.rho(i))),
                "a table indexed by X needs the path on one side of the spindle axis: it rolls \
                 over where X changes sign",
            ));
        }
        let rho_max = (0..n).map(|i| m.rho(i)).fold(0.0, f64::max);
        let turns = match n {
            0 => 0.0,
            _ => (m.c(n - 1) - m.c(0)).abs() / 360.0,
        };
        let sizing = Sizing {
            m,
            spec,
            x_negative: conv.x_sign < 0.0,
            rho_max,
            turns,
        };
        let budget = (spec.tolerance_um - spec.resolution_um()) * 1e-3;
        let total = (MAX_ROUNDS * (2 * MAX_STEPS + 1)) as u64;
        let mut passes = 0u64;
        let mut tick = |progress: &mut dyn FnMut(Progress) -> ControlFlow<()>| {
            passes += 1;
            progress(Progress {
                stage: Stage::FtsGrid,
                done: passes,
                total,
            })
        };
        let mut share = 1.0;
        let mut columns = 16;
        let mut spacing = ((rho_max * spec.x_counts_per_mm / 16.0).ceil() as u64).max(1);
        for _ in 0..MAX_ROUNDS {
            let target = share * budget / 2.0;
            columns = sizing.columns_from(columns)?;
            for _ in 0..MAX_STEPS {
                sizing.check(sizing.shape(columns, spacing))?;
                if tick(progress).is_break() {
                    return Ok(None);
                }
                let e = error_along_c(&sizing.m, columns);
                if e <= target {
                    break;
                }
                let next = (columns as f64 * (e / target).sqrt() * 1.02).ceil() as usize;
                columns = sizing.columns_from(next.max(columns + 1))?;
            }
            let mut table = sizing.table(sizing.shape(columns, spacing))?;
            for _ in 0..MAX_STEPS {
                if tick(progress).is_break() {
                    return Ok(None);
                }
                let e = sizing.error_along_x(&table);
                if e <= target || spacing == 1 {
                    break;
                }
                let next = (spacing as f64 * (target / e).sqrt() / 1.02).floor() as u64;
                spacing = next.clamp(1, spacing - 1);
                table = sizing.table(sizing.shape(columns, spacing))?;
            }
            if tick(progress).is_break() {
                return Ok(None);
            }
            let (worst, rms, at) = errors(&sizing.m, &table);
            if worst <= spec.tolerance_um * 1e-3 {
                return Ok(Some(Self::of(job, table, spec, worst, rms, at)?));
            }
            share *= (0.9 * budget / worst).clamp(0.25, 0.8);
        }
        Err(FieldError::new(
            TOLERANCE,
            spec.tolerance_um,
            format!(
                "was not met after {MAX_ROUNDS} refinements ({columns} columns, rows {} apart): \
                 W is too rough for a table at this tolerance",
                short(spacing as f64 / spec.x_counts_per_mm)
            ),
        ))
    }

    /// The grid of a finished table, with its figures.
    fn of(
        job: &str,
        table: CompTable,
        spec: &FtsGridSpec,
        worst: f64,
        rms: f64,
        at: Location,
    ) -> Result<Self, FieldError> {
        let io = |e: crate::nc::NcError| {
            FieldError::new(
                "output.fts_grid",
                "the table",
                format!("cannot be written: {e}"),
            )
        };
        let mut sink = std::io::sink();
        let csv_bytes = write_csv(&mut sink, &table).map_err(io)?;
        let mut report = FtsGridReport {
            rows: table.rows,
            columns: table.columns,
            entries: (table.rows as u64 + 1) * (table.columns as u64 + 1),
            x_spacing_mm: table.x_spacing_counts as f64 / table.x_counts_per_mm,
            c_spacing_deg: 360.0 / table.columns as f64,
            x_span_counts: table.x_span_counts(),
            x_span_mm: table.x_span_counts() as f64 / table.x_counts_per_mm,
            c_span_counts: table.c_counts_per_rev,
            w_offset_um: table.w_offset_mm * 1e3,
            tolerance_um: spec.tolerance_um,
            resolution_um: spec.resolution_um(),
            max_error_um: worst * 1e3,
            rms_error_um: rms * 1e3,
            max_error_at: at,
            pmac_bytes: 0,
            csv_bytes,
        };
        let comments = report.comments(job, &table);
        report.pmac_bytes = write_pmac(&mut sink, &table, &comments).map_err(io)?;
        Ok(Self {
            table,
            report,
            comments,
        })
    }
}

impl FtsGridReport {
    /// The comments that head the PMAC text: what the table is and how it sits on the motors.
    fn comments(&self, job: &str, t: &CompTable) -> Vec<String> {
        let m = t.motors;
        vec![
            format!(
                "spiralcam {}: the fast tool servo's W as a 2-D compensation table",
                env!("CARGO_PKG_VERSION")
            ),
            format!("job {job}"),
            format!(
                "rows: X (motor #{}, {} counts/mm), {} rows {} mm apart over {} counts{}",
                m.x,
                t.x_counts_per_mm,
                self.rows + 1,
                short(self.x_spacing_mm),
                self.x_span_counts,
                if t.x_negative {
                    " (X negative: rolled over, row 0 is X = 0)"
                } else {
                    ""
                }
            ),
            format!(
                "columns: C (motor #{}, {} counts/rev), {} columns {} deg apart, the last at \
                 360 deg",
                m.c,
                t.c_counts_per_rev,
                self.columns + 1,
                short(self.c_spacing_deg)
            ),
            format!(
                "entries: W (motor #{}) in 1/16 count at {} counts/mm, less W at the origin, \
                 {:.6} um: program the servo there",
                m.w, t.w_counts_per_mm, self.w_offset_um
            ),
            format!(
                "bilinear error against the planned W over the path: max {:.6} um, RMS {:.6} um \
                 (tolerance {} um)",
                self.max_error_um, self.rms_error_um, self.tolerance_um
            ),
            "enable with I51=1; COMP tables are defined from the highest-numbered motor down"
                .to_string(),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::OutputSpec;
    use std::f64::consts::TAU;

    /// A spiral from radius `r0` to the centre, `per_rev` points a turn, `f` mm a turn, and
    /// W = `w(ρ, θ)` at its points: (θ, ρ, W).
    fn spiral(
        r0: f64,
        f: f64,
        per_rev: usize,
        w: impl Fn(f64, f64) -> f64,
    ) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let n = (r0 / f * per_rev as f64).round() as usize;
        let theta: Vec<f64> = (0..=n).map(|i| TAU * i as f64 / per_rev as f64).collect();
        let rho: Vec<f64> = (0..=n)
            .map(|i| (r0 - f * i as f64 / per_rev as f64).max(0.0))
            .collect();
        let w = theta.iter().zip(&rho).map(|(&t, &r)| w(r, t)).collect();
        (theta, rho, w)
    }

    fn conventions(x_sign: i8, c_sign: i8) -> Conventions {
        OutputSpec {
            x_sign: Some(x_sign),
            c_sign: Some(c_sign),
            ..OutputSpec::default()
        }
        .conventions()
    }

    fn build(
        path: &(Vec<f64>, Vec<f64>, Vec<f64>),
        spec: &FtsGridSpec,
        conv: &Conventions,
    ) -> Result<FtsGrid, FieldError> {
        let servo = ServoPath {
            theta: &path.0,
            rho: &path.1,
            w: &path.2,
        };
        FtsGrid::build("test", servo, spec, conv, &mut crate::progress::ignore)
            .map(|g| g.expect("not cancelled"))
    }

    #[test]
    fn a_w_linear_in_radius_is_reproduced_to_the_resolution_on_either_side() {
        // W = a + b·ρ: linear along every column, constant along every row, so any grid holds
        // it exactly, the rows past the first pass included (extrapolated on the same line).
        let (a, b) = (3e-4, 2e-3);
        let path = spiral(2.0, 0.01, 90, |r, _| a + b * r);
        let spec = FtsGridSpec::default();
        for (x_sign, c_sign) in [(1, 1), (-1, 1), (1, -1), (-1, -1)] {
            let g = build(&path, &spec, &conventions(x_sign, c_sign)).unwrap();
            let t = &g.table;
            assert_eq!(t.x_negative, x_sign < 0);
            assert_eq!(t.w_offset_mm, a, "W at the centre");
            for j in 0..=t.rows {
                let rho = t.row_x_mm(j).abs();
                let expected = (b * rho * 16.0 * spec.w_counts_per_mm).round() as i64;
                for k in 0..=t.columns {
                    assert!(
                        (t.entry(j, k) - expected).abs() <= 1,
                        "{x_sign} {c_sign}: {j} {k} {} {expected}",
                        t.entry(j, k)
                    );
                }
            }
            // The centre is zero at both ends of the span; the span covers the part and a row.
            assert_eq!(t.row_x_mm(0), 0.0);
            assert_eq!(t.row_x_mm(t.rows), 0.0);
            let beyond = t.row_x_mm(if x_sign > 0 { t.rows - 1 } else { 1 }).abs();
            assert!(beyond >= 2.0, "{beyond}");
            assert!(g.report.max_error_um <= 2.0 * spec.resolution_um() + 1e-9);
        }
    }

    /// W with `m` waves a turn, growing with the radius, µm-sized.
    fn waves(m: f64) -> impl Fn(f64, f64) -> f64 {
        move |r: f64, t: f64| 1e-3 * r * (m * t).cos() + 2e-4 * r * r
    }

    #[test]
    fn the_table_meets_its_tolerance_wraps_and_a_tighter_one_is_finer() {
        let path = spiral(3.0, 0.02, 256, waves(5.0));
        let mut entries = 0;
        for tolerance_um in [0.05, 0.01] {
            let spec = FtsGridSpec {
                tolerance_um,
                ..Default::default()
            };
            let g = build(&path, &spec, &conventions(1, 1)).unwrap();
            let (r, t) = (&g.report, &g.table);
            assert!(r.max_error_um <= tolerance_um, "{r:?}");
            assert!(r.rms_error_um <= r.max_error_um);
            assert!(r.entries > entries, "{r:?}");
            entries = r.entries;
            assert_eq!(r.entries, (t.rows as u64 + 1) * (t.columns as u64 + 1));
            assert_eq!(t.entries.len() as u64, r.entries);
            assert_eq!(r.c_span_counts, spec.c_counts_per_rev);
            assert_eq!(spec.c_counts_per_rev % t.columns as u64, 0);
            for j in 0..=t.rows {
                assert_eq!(t.entry(j, t.columns), t.entry(j, 0), "row {j} wraps");
            }
            // The first row is the centre, one point: W there on every column, zero after
            // the offset.
            assert!((0..=t.columns).all(|k| t.entry(0, k) == 0));
            // The errors recomputed at every point.
            let worst = (0..path.0.len())
                .map(|i| {
                    let w = t.w_mm_at(path.1[i], path.0[i].to_degrees());
                    (w - path.2[i]).abs()
                })
                .fold(0.0, f64::max);
            assert!((worst * 1e3 - r.max_error_um).abs() < 1e-12, "{worst}");
        }
    }

    #[test]
    fn every_column_is_crossed_once_a_turn() {
        let path = spiral(1.0, 0.1, 37, |_, _| 0.0);
        let m = Machine {
            path: ServoPath {
                theta: &path.0,
                rho: &path.1,
                w: &path.2,
            },
            signs: Signs {
                c: -1.0,
                x: 1.0,
                z: 1.0,
            },
        };
        // 10 turns from C = 0 down to −3600°: every column angle in (−3600, 0] once, the last
        // point on column 0 included.
        let mut angles = Vec::new();
        pass(&m, 12, |e| {
            if let Event::Crossing(x) = e {
                let column = (x.c / 30.0).round().rem_euclid(12.0) as usize;
                assert_eq!(x.column, column, "{x:?}");
                let turns = -x.c / 360.0;
                assert!((x.rho - (1.0 - 0.1 * turns)).abs() < 1e-12, "{x:?}");
                angles.push(x.c);
            }
        });
        let expected: Vec<f64> = (0..=120).map(|k| -30.0 * k as f64).collect();
        assert_eq!(angles.len(), expected.len());
        for (a, e) in angles.iter().zip(&expected) {
            assert!((a - e).abs() < 1e-9, "{a} {e}");
        }
    }

    #[test]
    fn beyond_its_bounds_the_table_is_refused_naming_the_field() {
        let path = spiral(3.0, 0.02, 256, waves(40.0));
        let spec = FtsGridSpec {
            tolerance_um: 1e-4,
            ..Default::default()
        };
        let e = build(&path, &spec, &conventions(1, 1)).unwrap_err();
        assert_eq!(e.field, "output.fts_grid.tolerance_um");
        assert!(
            e.allowed.starts_with("needs a table of at least"),
            "{}",
            e.allowed
        );
        assert!(e.allowed.contains("µm or more"), "{}", e.allowed);
        let spec = FtsGridSpec {
            w_counts_per_mm: 1e12,
            tolerance_um: 1.0,
            ..Default::default()
        };
        let e = build(&path, &spec, &conventions(1, 1)).unwrap_err();
        assert_eq!(e.field, "output.fts_grid.w_counts_per_mm");
        assert!(e.allowed.contains("beyond the table's entries"), "{e}");
        let mut negative = spiral(1.0, 0.1, 37, |_, _| 0.0);
        negative.1[5] = -0.01;
        let e = build(&negative, &FtsGridSpec::default(), &conventions(1, 1)).unwrap_err();
        assert_eq!(e.field, "strategy.compensation");
    }

    #[test]
    fn a_cancelled_sizing_stops() {
        let path = spiral(1.0, 0.1, 37, |r, _| r);
        let servo = ServoPath {
            theta: &path.0,
            rho: &path.1,
            w: &path.2,
        };
        let spec = FtsGridSpec::default();
        let mut stop = |_| ControlFlow::Break(());
        let g = FtsGrid::build("test", servo, &spec, &conventions(1, 1), &mut stop).unwrap();
        assert!(g.is_none());
    }
}
