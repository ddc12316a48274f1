//! Admission: what a job will cost, estimated before any point of its path is computed, and
//! checked against stated limits, so that a typo (a feed in metres, a pitch in microns) is
//! refused at once with the figures and the field to change instead of running for hours or
//! filling the disk.
//!
//! **Points**: the spiral's own count, in floating point ([`Spiral::point_count_estimate`]:
//! exact for constant angle, within a few points otherwise). **Bytes**: the writers themselves
//! format [`PROBES`] pairs of consecutive points spread evenly in radius ([`ToolPath::probe`])
//! into a byte counter; the mean block weighted by the path's points per mm of radius there,
//! times the points, plus the header, approach and end written once. The servo's gridded table
//! is sized only after the dynamics: its bound ([`crate::nc::fts_grid::max_bytes`] of
//! [`crate::dynamics::fts_grid::MAX_ENTRIES`]) stands for it. **Time**: with a clock,
//! the probe's runs are timed as they are compensated (shared out over the cores, each run's
//! time read on its own thread) and their blocks formatted again and timed on one thread;
//! compensation runs on every core, formatting on one, and a job with machine dynamics
//! computes its path twice and adds their analysis, timed on a synthetic path and scaled by
//! their grid's samples ([`dynamics::seconds_per_sample`], [`dynamics::grid_samples`]). The
//! concave-zone
//! report and the accuracy analysis are not in the estimate (they have their own bounds:
//! [`crate::tool::reach::MAX_MEASURED_ZONES`], and the analyses read the path once).
//!
//! [`Spiral::point_count_estimate`]: crate::path::Spiral::point_count_estimate
//! [`ToolPath::probe`]: crate::tool::ToolPath::probe

use super::{PlanError, Planner};
use crate::dynamics;
use crate::dynamics::path_signal::PathSignal;
use crate::field::{FieldError, feed_within, short};
use crate::job::{Compensation, SplitSpec};
use crate::nc::{CsvWriter, FtsTableWriter, NcWriter};
use crate::parallel::workers;
use crate::path::MAX_POINTS;
use crate::report::{Cost, Outputs, bytes, duration};
use crate::tool::Probe;

/// Pairs of consecutive points the estimate formats.
pub const PROBES: usize = 128;

/// The default limit on the files a plan writes together, bytes: 4 GB.
pub const DEFAULT_MAX_OUTPUT_BYTES: u64 = 4_000_000_000;

/// The bounds a job is admitted under.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Most points; at most [`MAX_POINTS`].
    pub max_points: u64,
    /// Most points when the machine dynamics run (they hold the path in memory); at most
    /// [`dynamics::MAX_POINTS`].
    pub max_dynamics_points: u64,
    /// Most memory the machine dynamics may hold, bytes (their estimate,
    /// [`crate::dynamics::memory_bytes`]: the path's columns and their grid, which a path whose
    /// densest turn is denser than the others makes larger than its points); `None`: not
    /// bounded beyond the points.
    pub max_dynamics_bytes: Option<u64>,
    /// Most bytes of the files written together.
    pub max_output_bytes: u64,
    /// Longest estimated time, seconds; `None`: not bounded.
    pub max_seconds: Option<f64>,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_points: MAX_POINTS,
            max_dynamics_points: dynamics::MAX_POINTS,
            max_dynamics_bytes: None,
            max_output_bytes: DEFAULT_MAX_OUTPUT_BYTES,
            max_seconds: None,
        }
    }
}

/// A writer that only counts.
#[derive(Debug, Default)]
struct ByteCount(u64);

impl std::io::Write for ByteCount {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0 += buf.len() as u64;
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Mean bytes per point of each output over the probes, and the program's fixed part.
struct Weights {
    nc_block: f64,
    nc_fixed: u64,
    csv_row: f64,
    fts_row: f64,
}

impl Planner {
    /// The cost of this job ([`Cost`]); `clock` (seconds, any origin) times the estimate where
    /// the caller has one. Errors: the surface undefined where a probe falls, or a word that
    /// cannot be written there (a height that is not finite), before any output exists.
    pub fn cost(&self, clock: Option<&(dyn Fn() -> f64 + Sync)>) -> Result<Cost, PlanError> {
        let path_points = self.spiral().point_count_hint();
        let (written, computed) = program_factors(self.job());
        let points = (path_points as f64 * written).round() as u64;
        let passes = if dynamics::wanted(self.job()) { 2 } else { 1 };
        // With a clock, the probes' warm points timed: (clock, their seconds).
        let (probes, timed) = match clock {
            None => (self.probe(PROBES)?, None),
            Some(now) => {
                let (probes, warm) = self.probe_timed(PROBES, now)?;
                (probes, Some((now, warm)))
            }
        };
        check_heights(&probes)?;
        let w = self.weights(&probes)?;
        let seconds = match timed {
            None => None,
            Some((now, warm)) => {
                let per_point = |t: f64| t.max(0.0) / (2 * PROBES) as f64;
                let compensate = per_point(warm) * passes as f64 / workers() as f64;
                let n = path_points as f64;
                Some(n * computed * compensate + n * written * self.block_seconds(&probes, now)?)
            }
        };
        // The samples of the dynamics' grid: the densest turn's points from the probes' steps
        // (points per mm × the feed) on every turn. Their analysis is timed on this machine and
        // scaled by them; their memory goes with them and the path's columns.
        let feed = self.job().strategy.feed_mm_per_rev;
        let densest = probes.iter().map(|p| p.per_mm * feed).fold(0.0, f64::max);
        let samples = (passes == 2)
            .then(|| dynamics::grid_samples(path_points, self.spiral().revolutions(), densest));
        let dynamics_seconds = match (timed, samples) {
            (Some((now, _)), Some(samples)) => {
                dynamics::seconds_per_sample(self.job(), densest, now).map(|s| s * samples)
            }
            _ => None,
        };
        // The angles and radii are not held where the spiral gives them (by the index, or
        // from a point's φ) and one-way compensation leaves them as they are.
        let on_spiral = self.job().strategy.compensation != Compensation::TwoWay;
        let bytes_per_point = PathSignal::bytes_per_point(self.spiral(), on_spiral);
        let seconds = seconds.map(|s| s + dynamics_seconds.unwrap_or(0.0));
        let split = self.job().strategy.split.is_some();
        let low_pass = matches!(
            self.job().strategy.split,
            Some(SplitSpec::LowPass { .. } | SplitSpec::Auto)
        );
        let n = path_points as f64;
        Ok(Cost {
            points,
            passes,
            nc_bytes: w.nc_fixed + (w.nc_block * written * (n - 1.0).max(0.0)) as u64,
            csv_bytes: crate::nc::csv::HEADER.len() as u64 + (w.csv_row * n) as u64,
            fts_table_bytes: split
                .then(|| crate::nc::fts_table::HEADER.len() as u64 + (w.fts_row * n) as u64),
            dynamics_samples: samples.map(|s| s as u64),
            dynamics_memory_bytes: samples.map(|s| {
                let records = dynamics::record_samples(s, self.spiral().revolutions(), low_pass);
                dynamics::memory_bytes(path_points, records, bytes_per_point)
            }),
            fts_grid_bytes: split
                .then(|| crate::nc::fts_grid::max_bytes(dynamics::fts_grid::MAX_ENTRIES)),
            seconds,
            dynamics_seconds,
        })
    }

    /// The time by `clock` of one NC block: each probe run's second and third blocks, written
    /// by a writer that takes its first point as context (as a slice's writer does), without
    /// the header and end that each run's writer in [`Self::weights`] adds (timed with them, a
    /// block seemed twenty times dearer).
    fn block_seconds(&self, probes: &[Probe], clock: &dyn Fn() -> f64) -> Result<f64, PlanError> {
        let job = self.job();
        let split = job.strategy.split.is_some();
        let mut count = ByteCount::default();
        let start = clock();
        for [a, b, c] in probes.iter().map(|p| &p.points) {
            let mut w = NcWriter::resume(&mut count, &job.output, job.machine.spindle_rpm);
            w.context(a, split.then_some(a.z))?;
            for q in [b, c] {
                match split {
                    true => w.point_split(q, q.z)?,
                    false => w.point(q)?,
                }
            }
        }
        let blocks = (2 * probes.len()).max(1) as f64;
        Ok((clock() - start).max(0.0) / blocks)
    }

    /// The writers' bytes per point at the probes, weighted by the path's density there.
    fn weights(&self, probes: &[Probe]) -> Result<Weights, PlanError> {
        let job = self.job();
        let conv = job.output.conventions();
        let split = job.strategy.split.is_some();
        let header = self.header();
        let (mut nc, mut csv, mut fts, mut total) = (0.0, 0.0, 0.0, 0.0);
        let mut fixed = 0;
        for (k, p) in probes.iter().enumerate() {
            // The third block: dialects that write F only when it changes omit it there when
            // the step is constant, as they do along the path.
            let [a, b0, b] = &p.points;
            let mut count = ByteCount::default();
            let mut w = NcWriter::new(&mut count, &job.output, &header)?;
            let write = |w: &mut NcWriter<&mut ByteCount>, q| match split {
                true => w.point_split(q, q.z),
                false => w.point(q),
            };
            write(&mut w, a)?;
            let after_a = w.bytes();
            write(&mut w, b0)?;
            let before = w.bytes();
            write(&mut w, b)?;
            let block = w.bytes() - before;
            let end = w.finish()?;
            if k == 0 {
                // Header, preamble, approach and end: all but the two blocks.
                fixed = end - (before - after_a) - block;
            }
            let mut rows = ByteCount::default();
            CsvWriter::new(&mut rows, conv)?.point(b)?;
            let csv_row = rows.0 - crate::nc::csv::HEADER.len() as u64;
            let mut table = ByteCount::default();
            FtsTableWriter::new(&mut table, conv)?.point(b, b.z)?;
            let fts_row = table.0 - crate::nc::fts_table::HEADER.len() as u64;
            nc += p.per_mm * block as f64;
            csv += p.per_mm * csv_row as f64;
            fts += p.per_mm * fts_row as f64;
            total += p.per_mm;
        }
        let mean = |sum: f64| if total > 0.0 { sum / total } else { 0.0 };
        Ok(Weights {
            nc_block: mean(nc),
            nc_fixed: fixed,
            csv_row: mean(csv),
            fts_row: mean(fts),
        })
    }
}

/// The largest commanded height accepted, mm: no lathe's Z axis travels further.
pub const MAX_HEIGHT_MM: f64 = 1000.0;

/// Refuses a path whose heights at the probes are not finite or beyond [`MAX_HEIGHT_MM`]: a
/// surface whose parameters make its sag overflow (a coefficient of 1e308, a normalisation
/// radius far below the part) is named before anything is written.
fn check_heights(probes: &[Probe]) -> Result<(), FieldError> {
    for p in probes.iter().flat_map(|p| &p.points) {
        for z in [p.z, p.contact[2]] {
            if z.is_nan() || z.abs() > MAX_HEIGHT_MM {
                return Err(FieldError::new(
                    "surface",
                    format!(
                        "a height of {} mm at radius {} mm, angle {}°",
                        short(z),
                        short(p.rho),
                        short(p.theta.to_degrees().rem_euclid(360.0))
                    ),
                    format!(
                        "the sag over the part must be finite and within ±{MAX_HEIGHT_MM} mm \
                         (no lathe's Z travels further): check the surface's parameters"
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// How many times the strategy's path is written and computed for `job`'s program, relative
/// to the path: every body a program writes (one a group in a controller loop, one a pass
/// written out), a group with its own feed scaled by the count's 1/f, and once more a group for
/// its heights ([`crate::plan::Planner::run`]). (1, 1) without a `program` section.
fn program_factors(job: &crate::job::Job) -> (f64, f64) {
    let Some(spec) = &job.program else {
        return (1.0, 1.0);
    };
    if spec.passes.is_empty() {
        return (1.0, 2.0);
    }
    let feed = job.strategy.feed_mm_per_rev;
    let (mut written, mut computed) = (0.0, 0.0);
    for g in &spec.passes {
        let ratio = feed / g.feed_mm_per_rev.unwrap_or(feed);
        let bodies = match spec.loop_kind {
            crate::job::LoopKind::Controller => 1.0,
            crate::job::LoopKind::Unrolled => g.count as f64,
        };
        written += ratio * bodies;
        computed += ratio * (bodies + 1.0);
    }
    (written, computed)
}

impl Limits {
    /// Refuses a job whose `cost` is beyond these limits, naming the field to change and the
    /// value that would do: the feed, since every count and size goes as 1/f.
    pub fn check(&self, cost: &Cost, outputs: Outputs, feed: f64) -> Result<(), FieldError> {
        let limits = self;
        let field = "strategy.feed_mm_per_rev";
        let at_least = |ratio: f64| short(feed_within(feed, ratio));
        let points = cost.points as f64;
        if cost.points > limits.max_points {
            return Err(FieldError::new(
                field,
                feed,
                format!(
                    "gives about {} points; at most {}: a feed of at least {} mm/rev keeps this \
                     part under the limit",
                    short(points),
                    limits.max_points,
                    at_least(points / limits.max_points as f64)
                ),
            ));
        }
        if cost.passes == 2 && cost.points > limits.max_dynamics_points {
            return Err(FieldError::new(
                field,
                feed,
                format!(
                    "gives about {} points; the machine dynamics (a split or machine limits) hold \
                     the path in memory and take at most {}: a feed of at least {} mm/rev",
                    short(points),
                    limits.max_dynamics_points,
                    at_least(points / limits.max_dynamics_points as f64)
                ),
            ));
        }
        // Their memory goes with the samples of their grid too (both go as 1/f; the
        // low-pass's extension, 2·16 turns at the grid's rate, does not, so on a path of a few
        // turns the feed named may still be refused, with a larger one named then).
        let held = cost.dynamics_memory_bytes.filter(|_| cost.passes == 2);
        if let (Some(max), Some(held)) = (limits.max_dynamics_bytes, held)
            && held > max
        {
            return Err(FieldError::new(
                field,
                feed,
                format!(
                    "gives about {} points and a grid of {} samples, which the machine dynamics \
                     hold in memory: about {}, above {}: a feed of at least {} mm/rev",
                    short(points),
                    short(cost.dynamics_samples.unwrap_or(cost.points) as f64),
                    bytes(held),
                    bytes(max),
                    at_least(held as f64 / max as f64)
                ),
            ));
        }
        let size = cost.output_bytes(outputs);
        if size > limits.max_output_bytes {
            return Err(FieldError::new(
                field,
                feed,
                format!(
                    "gives about {} points and {} of files ({}), above the limit of {} \
                     (--max-output-gb raises it): a feed of at least {} mm/rev keeps them under it",
                    short(points),
                    bytes(size),
                    cost.summary(outputs),
                    bytes(limits.max_output_bytes),
                    at_least(size as f64 / limits.max_output_bytes as f64)
                ),
            ));
        }
        if let (Some(s), Some(max)) = (cost.seconds, limits.max_seconds)
            && s > max
        {
            return Err(FieldError::new(
                field,
                feed,
                format!(
                    "gives about {} points, about {} to plan, above the limit of {}: a feed of \
                     at least {} mm/rev keeps it under",
                    short(points),
                    duration(s),
                    duration(max),
                    at_least(s / max)
                ),
            ));
        }
        Ok(())
    }
}
