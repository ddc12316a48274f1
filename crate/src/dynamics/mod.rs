//! The dynamics layer: a planned path as a signal of time at the spindle speed, against the
//! machine (paper 000, "Hybrid Hilbert transform/fast Fourier transform methodology for geometry
//! splitting"; paper 002's decomposition). It reads the tool path ([`crate::tool::ToolPath`])
//! and uses the layers below it.
//!
//! - [`path_signal`]: the path against the spindle angle, resampled on a uniform grid, and its
//!   rotationally symmetric part;
//! - [`spectrum`]: the amplitude spectrum (FFT) and the instantaneous frequency (Hilbert
//!   transform) per radius band;
//! - [`split`](mod@split): the split of the path between the Z slide and a fast tool servo W
//!   (symmetric, low-pass, automatic), with Z + W = z;
//! - [`axis_checks`]: every point's axis velocities and accelerations against the machine
//!   ([`crate::job::machine`]), the block rate, the servo stroke, the cycle time;
//! - [`fts_grid`]: the servo's share W resampled onto a grid of spindle angle × X, sized so that
//!   the controller's bilinear interpolation of the table reproduces W within the job's
//!   tolerance (a PMAC-style 2-D compensation table, [`crate::nc::fts_grid`]).
//!
//! - [`real_transform`]: the real-input FFT of a long record in its own memory.
//!
//! This module runs them over the whole path in memory (the FFTs need it: [`memory_bytes`],
//! the path's columns and [`BYTES_PER_SAMPLE`] a sample of its uniform grid at the peak, two
//! records of it; every transform takes a length with small factors,
//! [`spectrum::fast_length`]), before the NC program is written,
//! when the job asks for it: a `strategy.split`, or any limit in `machine` (slides, FTS, block
//! rate). The program is then written in a second pass with the slide's share `Z` and the
//! servo's `W` ([`crate::nc::NcWriter::point_split`]).

pub mod axis_checks;
pub mod fts_grid;
pub mod path_signal;
pub mod real_transform;
pub mod spectrum;
pub mod split;

use crate::dynamics::axis_checks::{AxisReport, AxisSample, check_axes};
use crate::dynamics::fts_grid::{FtsGrid, FtsGridReport, ServoPath};
use crate::dynamics::path_signal::{PathSignal, extremes, hz, peak_to_valley};
use crate::dynamics::spectrum::{
    BandFrequency, Spectrum, amplitude_spectrum_and_bands_on,
    highest_significant_cycles_per_rev_at, instantaneous_frequency_of,
};
use crate::dynamics::split::{Limit, SplitError, SplitLimits, Verdict, servo_share, split_on};
use crate::job::Job;
use crate::job::MachineSpec;
use crate::job::SplitSpec;
use crate::parallel::both;
use crate::path::PathError;
use crate::path::PathPoint;
use crate::progress::{Progress, Stage};
use crate::tool::ToolPath;
use serde::Serialize;
use std::cell::Cell;
use std::ops::ControlFlow;
use thiserror::Error;

/// Why the dynamics of a path could not be computed.
#[derive(Debug, Error)]
pub enum DynamicsError {
    /// The path could not be planned, or the run was cancelled.
    #[error(transparent)]
    Path(#[from] PathError),
    /// The path cannot be split between the slide and the servo.
    #[error(transparent)]
    Split(#[from] SplitError),
}

impl From<crate::field::FieldError> for DynamicsError {
    fn from(e: crate::field::FieldError) -> Self {
        DynamicsError::Path(e.into())
    }
}

/// Bins of the spectrum kept for display (peaks survive the decimation).
pub const SPECTRUM_BINS: usize = 2048;

/// The most points the dynamics analyse: 3·10⁷, above a 28.4 M-point finishing path (measured
/// 0.80 GB of peak resident set at 28 400 001 points of the sine grid with the automatic split;
/// [`memory_bytes`] reckons 0.96 GB for a constant-angle path at this limit, 1.2 GB for an
/// HCAA or constant-arc one on a grid of as many samples, 1.44 GB where the angles and radii
/// are held; such paths' grids have more samples than points). The page admits fewer
/// ([`crate::plan::admission::Limits::max_dynamics_points`]): a tab's memory is smaller.
pub const MAX_POINTS: u64 = 30_000_000;

/// The dynamics' peak memory a sample of their uniform grid, beside the path's columns, bytes,
/// with some room: for a long grid, whose transforms run in place
/// ([`real_transform`]) in records of more than 32 MiB (a record that size is mapped and
/// unmapped whole, and grown in place). Measured with the automatic split on the sine grid
/// (`sinusoid-grid-fts.json`; `python3 tests/bench/dynamics.py`): 0.80 GB of peak resident set
/// at 28 400 001 points, 0.40 GB at 14 000 001, 19 bytes a sample beside the path's heights.
///
/// At the peak the dynamics hold the path's columns (24 bytes a point: θ, ρ, z; z alone, 8,
/// where the spiral gives θ and ρ by the index; z and the spiral's φ, 16, where it is walked by
/// its step rule: [`PathSignal::for_spiral`]) and at most two records of the grid, 8 bytes a
/// sample each: on a grid of up to [`split::SEGMENT_SAMPLES`] the low-pass's spectrum and one
/// trial channel (both of the grid extended by [`split::EXTENSION_REVS`] turns at either end:
/// [`record_samples`]). A longer grid is low-passed in segments, one at a time at one cutoff
/// and about one record in all for a bisection, and every other stage holds at most one
/// record beside the path's columns: the instantaneous frequency comes first, stretch by
/// stretch in records of a stretch's length ([`spectrum::instantaneous_frequency`]); the
/// spectrum takes the grid's heights, and X's figure then the radii; the low-pass's segments
/// give the slide's share at the points, the channel never made whole; the servo's and Z's
/// bandwidth figures then take W and Z resampled beside the slide's share. Every bandwidth
/// figure of a long grid is taken in single precision, 4 bytes a sample
/// ([`spectrum::highest_significant_cycles_per_rev_at`]). Every transform runs in its record's
/// memory, every residual and amplitude spectrum too. So the figure is room to spare for a long
/// grid: 0.96–0.98 GB of peak resident set measured on the 28.4 M-point HCAA sine grid (51 M
/// samples, 16 bytes a point) against 1.70 GB estimated; at the end the path, Z and W at the
/// points alone take 0.91 GB of it.
pub const BYTES_PER_SAMPLE: u64 = 24;

/// [`BYTES_PER_SAMPLE`] for a grid of at most [`MID_GRID_SAMPLES`] samples, whose records (at
/// most 32 MiB) the allocator may copy to grow and keep after they are let go: 31 bytes a
/// sample measured at 2 000 001 and 4 000 001 points of the sine grid (95 and 173 MB of peak
/// resident set), 33 at 3.8 M samples of an HCAA path (2 077 101 points, 189 MB).
pub const MID_BYTES_PER_SAMPLE: u64 = 40;

/// The largest grid [`MID_BYTES_PER_SAMPLE`] applies to: records of 32 MiB.
pub const MID_GRID_SAMPLES: f64 = 4_194_304.0;

/// [`BYTES_PER_SAMPLE`] for a grid whose transforms are shorter than
/// [`real_transform::IN_PLACE_FROM`], `realfft`'s: its output (8 bytes a sample) and plans (12
/// each) beside the record. 67 bytes a sample measured at 951 001 samples of an HCAA path
/// (519 276 points, 87 MiB of peak resident set; `python3 tests/bench/peak_memory.py`).
pub const SHORT_BYTES_PER_SAMPLE: u64 = 72;

/// The dynamics' memory a sample of a grid of `samples` samples ([`BYTES_PER_SAMPLE`],
/// [`MID_BYTES_PER_SAMPLE`] or [`SHORT_BYTES_PER_SAMPLE`]).
pub fn bytes_per_sample(samples: f64) -> u64 {
    let transform = spectrum::fast_length(samples.max(0.0) as usize, false);
    if transform < real_transform::IN_PLACE_FROM {
        SHORT_BYTES_PER_SAMPLE
    } else if samples <= MID_GRID_SAMPLES {
        MID_BYTES_PER_SAMPLE
    } else {
        BYTES_PER_SAMPLE
    }
}

/// The dynamics' peak memory, bytes, for a path of `points` points whose longest records have
/// `samples` samples ([`record_samples`] of its [`grid_samples`]): the path's columns,
/// `bytes_per_point` a point (24, or 8 or 16 where the spiral gives the angles and radii:
/// [`PathSignal::bytes_per_point`]), and [`bytes_per_sample`] a sample of those records, at
/// least one a point.
pub fn memory_bytes(points: u64, samples: f64, bytes_per_point: u64) -> u64 {
    let samples = samples.max(points as f64);
    points.saturating_mul(bytes_per_point) + (samples * bytes_per_sample(samples) as f64) as u64
}

/// Points of the synthetic path the dynamics' time is measured on ([`seconds_per_sample`]).
pub const CALIBRATION_POINTS: usize = 32_768;

/// The time the dynamics of `job` take a sample of their uniform grid on this machine, seconds
/// by `clock`: their analysis (every stage, with the job's machine and split), the quickest of
/// three runs on a synthetic constant-angle path of [`CALIBRATION_POINTS`] points, whose grid
/// has as many samples, times 1.3 for a long path's memory. The time a sample barely changes
/// with the path's length (0.45–0.64 µs measured from 131 072 to 28.4 M points of the sine grid
/// and 1.8 M of the lens array on this machine), so the estimate scales it by the grid's
/// samples ([`grid_samples`]). The path spirals inwards over the outer half of the part at
/// `points_per_rev` (held to 64 … 2048), a 1 µm tone of 2 and one of 24 cycles a revolution in
/// Z; `None` when the job's split cannot be made on it (a cutoff above its Nyquist frequency).
pub fn seconds_per_sample(
    job: &Job,
    points_per_rev: f64,
    clock: &(dyn Fn() -> f64 + Sync),
) -> Option<f64> {
    let n = CALIBRATION_POINTS;
    let per_rev = points_per_rev.clamp(64.0, (n / 16) as f64).round();
    let radius = job.part.diameter_mm / 2.0;
    let points: Vec<PathPoint> = (0..n)
        .map(|i| {
            let theta = std::f64::consts::TAU * i as f64 / per_rev;
            let rho = radius * (1.0 - 0.5 * i as f64 / n as f64);
            let z = 1e-3 * ((2.0 * theta).cos() + (24.0 * theta).sin());
            let (s, c) = theta.sin_cos();
            PathPoint {
                index: i as u64,
                rho,
                theta,
                z,
                contact: [rho * c, rho * s, z],
                contact_angle: 0.0,
                at_arc_end: false,
            }
        })
        .collect();
    // The quickest of three runs: the first also maps its buffers' pages, and a run on a
    // shared machine may be interrupted.
    let mut quickest = f64::INFINITY;
    for _ in 0..CALIBRATION_RUNS {
        let start = clock();
        Dynamics::of_points(job, &points).ok()?;
        quickest = quickest.min((clock() - start).max(0.0));
    }
    Some(quickest / n as f64 * LONG_RECORD_FACTOR)
}

/// How much longer a sample of a long path's dynamics takes than one of the calibration's,
/// whose buffers stay in the caches and whose pages are mapped once: 1.2–1.33 measured on this
/// machine (the sine grid example's 0.8 M points, the lens array's 4 M at constant arc, the
/// sine grid's 28.4 M).
const LONG_RECORD_FACTOR: f64 = 1.3;

/// Timed runs of the calibration path ([`seconds_per_sample`]).
const CALIBRATION_RUNS: usize = 3;

/// The samples the dynamics compute on for a path of `points` points over `revolutions` turns
/// whose densest turn has `densest_per_rev` points: its uniform grid by
/// [`PathSignal::uniform`]'s rule (the densest turn's step, at most
/// [`path_signal::MAX_GRID_PER_POINT`] samples a point), and at least the points themselves.
pub fn grid_samples(points: u64, revolutions: f64, densest_per_rev: f64) -> f64 {
    let n = points as f64;
    let per_rev = densest_per_rev
        .ceil()
        .max(path_signal::MIN_SAMPLES_PER_REV as f64);
    let budget = (path_signal::MAX_GRID_PER_POINT as f64 * n).max(4096.0);
    (per_rev * revolutions + 1.0).min(budget).max(n)
}

/// The samples of the dynamics' longest records for a uniform grid of `samples` samples over
/// `revolutions` turns: the grid's, or with a low-pass split (`low_pass`: `low_pass` or `auto`)
/// the low-pass's record, the grid extended by [`split::EXTENSION_REVS`] revolutions at either
/// end. The low-pass holds two records that long (its spectrum and a trial channel), so the
/// extension dominates on a path of few turns: 10 turns of 10⁶ points were 10 M samples on the
/// grid and 42 M in the low-pass's records (0.78 GB of peak resident set).
pub fn record_samples(samples: f64, revolutions: f64, low_pass: bool) -> f64 {
    if !low_pass || revolutions.is_nan() || revolutions <= 0.0 {
        return samples;
    }
    let per_rev = (samples - 1.0).max(0.0) / revolutions;
    samples + (2 * split::EXTENSION_REVS) as f64 * per_rev
}

/// Radius bands of the instantaneous frequency.
pub const FREQUENCY_BANDS: usize = 32;

/// What the dynamics found, for the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DynamicsReport {
    /// The amplitude spectrum of the path's non-symmetric part at the spindle speed.
    pub spectrum: Spectrum,
    /// Its instantaneous frequency per radius band, from the rim to the centre.
    pub instantaneous_frequency: Vec<BandFrequency>,
    /// The split, when the job asks for one.
    pub split: Option<SplitReport>,
    /// Every point's axis velocities and accelerations against the machine.
    pub axes: AxisReport,
    /// The slide's and the servo's channels along the path, for plots.
    pub channels: Option<ChannelProfile>,
    /// The frequencies the X and Z slides are asked to follow against their bandwidths.
    pub bandwidth: SlideBandwidths,
    /// The servo's gridded table, when it was asked for ([`Dynamics::run_with_grid`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fts_grid: Option<FtsGridReport>,
}

/// A slide's bandwidth against what its channel asks.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BandwidthCheck {
    /// The channel's highest significant frequency at the spindle speed, Hz (the highest at which
    /// the spectrum of its non-symmetric part reaches 1 % of its largest amplitude;
    /// [`crate::dynamics::spectrum::highest_significant_cycles_per_rev`]); `None` when the path
    /// cannot be analysed.
    pub needed_hz: Option<f64>,
    /// The slide's bandwidth, Hz; `None` when the job gives none.
    pub limit_hz: Option<f64>,
    /// Whether the slide follows it (true when either is unknown).
    pub within_limit: bool,
}

/// The bandwidth checks of both slides: X, and Z with its share of a split path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SlideBandwidths {
    /// The X slide.
    pub x: BandwidthCheck,
    /// The Z slide.
    pub z: BandwidthCheck,
}

impl BandwidthCheck {
    /// The check of a channel that needs `needed_hz` (unknown: `None`).
    fn of(needed_hz: Option<f64>, limit_hz: Option<f64>) -> Self {
        let within_limit = match (needed_hz, limit_hz) {
            (Some(n), Some(l)) => n <= l,
            _ => true,
        };
        Self {
            needed_hz,
            limit_hz,
            within_limit,
        }
    }
}

/// The two channels along the path in at most [`PROFILE_BUCKETS`] runs of consecutive points,
/// each with its range of radius and the lowest and highest Z and W in it (an envelope: a
/// servo channel oscillating faster than the buckets keeps its full swing).
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct ChannelProfile {
    /// Radius at the start of each run, mm.
    pub rho_mm: Vec<f64>,
    /// Lowest Z of the slide in each run, mm.
    pub z_min_mm: Vec<f64>,
    /// Highest Z of the slide in each run, mm.
    pub z_max_mm: Vec<f64>,
    /// Lowest W of the servo in each run, µm.
    pub w_min_um: Vec<f64>,
    /// Highest W of the servo in each run, µm.
    pub w_max_um: Vec<f64>,
}

/// Runs of points in a [`ChannelProfile`].
pub const PROFILE_BUCKETS: usize = 1024;

impl ChannelProfile {
    /// The profile of the channels `z` and `w` (mm) of the points whose radii are `rho(i)` (mm).
    pub fn of(rho: impl Fn(usize) -> f64, z: &[f64], w: &[f64]) -> Self {
        let n = z.len().min(w.len());
        let size = n.div_ceil(PROFILE_BUCKETS).max(1);
        let mut p = Self::default();
        for start in (0..n).step_by(size) {
            let end = (start + size).min(n);
            let (zl, zh) = extremes(z[start..end].iter().copied());
            let (wl, wh) = extremes(w[start..end].iter().copied());
            p.rho_mm.push(rho(start));
            p.z_min_mm.push(zl);
            p.z_max_mm.push(zh);
            p.w_min_um.push(wl * 1e3);
            p.w_max_um.push(wh * 1e3);
        }
        p
    }
}

/// The split, summarised.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SplitReport {
    /// How it was asked for.
    pub spec: SplitSpec,
    /// The low-pass cutoff, Hz (low-pass and automatic splits with the servo).
    pub cutoff_hz: Option<f64>,
    /// Peak-to-valley of the slide's channel Z, µm.
    pub z_slide_pv_um: f64,
    /// Peak-to-valley of the servo's channel W, µm.
    pub w_fts_pv_um: f64,
    /// The channels against the machine's limits.
    pub verdict: Verdict,
}

/// The dynamics of a path, and the slide's share of every point when it is split.
#[derive(Debug, Clone, PartialEq)]
pub struct Dynamics {
    /// The figures.
    pub report: DynamicsReport,
    /// Z of the slide at every point, mm, when the path is split.
    pub z_slide_mm: Option<Vec<f64>>,
    /// W of the servo at every point, mm, when the path is split.
    pub w_fts_mm: Option<Vec<f64>>,
    /// The servo's gridded table, when it was asked for and the path is split.
    pub fts_grid: Option<FtsGrid>,
}

/// Whether `job` asks for the dynamics: a split, or a limit of the machine to check.
pub fn wanted(job: &Job) -> bool {
    let m = &job.machine;
    job.strategy.split.is_some()
        || m.block_rate_hz.is_some()
        || m.x_slide.is_some()
        || m.z_slide.is_some()
        || m.fts.is_some()
}

/// The machine's limits in the splitter's units, when it has a Z slide and a servo.
pub fn split_limits(m: &MachineSpec) -> Option<SplitLimits> {
    let (z, fts) = (m.z_slide.as_ref()?, m.fts.as_ref()?);
    Some(SplitLimits {
        fts_stroke_mm: fts.stroke_mm(),
        fts_bandwidth_hz: fts.bandwidth_hz,
        fts_acceleration_mm_per_s2: fts.acceleration_mm_per_s2(),
        slide_velocity_mm_per_s: z.velocity_mm_per_s(),
        slide_acceleration_mm_per_s2: z.acceleration_mm_per_s2,
        slide_bandwidth_hz: z.bandwidth_hz,
    })
}

fn pv_um(values: &[f64]) -> f64 {
    peak_to_valley(values.iter().copied()) * 1e3
}

/// The job field of a splitter's limit, with the splitter's unit where it differs.
pub fn job_field(limit: Limit) -> &'static str {
    match limit {
        Limit::FtsStrokeMm => "machine.fts.stroke_um (as mm)",
        Limit::FtsBandwidthHz => "machine.fts.bandwidth_hz",
        Limit::FtsAccelerationMmPerS2 => "machine.fts.acceleration_m_per_s2 (as mm/s²)",
        Limit::SlideVelocityMmPerS => "machine.z_slide.velocity_mm_per_min (as mm/s)",
        Limit::SlideAccelerationMmPerS2 => "machine.z_slide.acceleration_mm_per_s2",
        Limit::SlideBandwidthHz => "machine.z_slide.bandwidth_hz",
    }
}

impl DynamicsReport {
    /// What the program's header says of the split: cutoff, the channels' PV and the verdict.
    pub fn header_lines(&self) -> Vec<String> {
        let Some(s) = &self.split else {
            return Vec::new();
        };
        let cutoff = match s.cutoff_hz {
            Some(hz) => format!("cutoff {hz:.4} Hz"),
            None => "no cutoff".to_string(),
        };
        let verdict = match &s.verdict {
            Verdict::Unchecked => "not checked against the machine".to_string(),
            Verdict::Feasible {
                slide_alone: true, ..
            } => "within the machine's limits, the slide alone".to_string(),
            Verdict::Feasible { .. } => "within the machine's limits".to_string(),
            Verdict::Infeasible { .. } => {
                "EXCEEDS the machine's limits (see the report)".to_string()
            }
        };
        vec![format!(
            "split: {cutoff}, Z PV {:.4} um, servo PV {:.4} um, {verdict}",
            s.z_slide_pv_um, s.w_fts_pv_um
        )]
    }

    /// What an operator must read before cutting: the axis checks' warnings and a split that
    /// exceeds the machine, with the speed that would do.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = self.axes.warnings.clone();
        for (axis, b) in [("x", self.bandwidth.x), ("z", self.bandwidth.z)] {
            if let (false, Some(n), Some(l)) = (b.within_limit, b.needed_hz, b.limit_hz) {
                out.push(format!(
                    "the {} slide must follow {n:.3} Hz, above machine.{axis}_slide.bandwidth_hz \
                     = {l} Hz: lower the spindle speed to {:.1} rpm or less{}",
                    axis.to_uppercase(),
                    self.axes.spindle_rpm * l / n,
                    if axis == "z" {
                        ", or split the path with a fast tool servo"
                    } else {
                        ""
                    }
                ));
            }
        }
        if let Some(SplitReport {
            verdict:
                Verdict::Infeasible {
                    conflicts,
                    feasible_spindle_rpm,
                    ..
                },
            ..
        }) = &self.split
        {
            let what: Vec<String> = conflicts
                .iter()
                .map(|c| format!("{} {} > {}", job_field(c.limit), c.value, c.allowed))
                .collect();
            let speed = match feasible_spindle_rpm {
                Some(n) => format!("feasible at {n} rpm or less"),
                None => "no spindle speed makes it feasible (the stroke)".to_string(),
            };
            out.push(format!(
                "the split exceeds the machine: {}; {speed}",
                what.join(", ")
            ));
        }
        out
    }
}

impl Dynamics {
    /// Computes `path` into memory and analyses it (module docs); `progress` as for
    /// [`ToolPath::for_each_point`].
    pub fn run(
        path: &ToolPath,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<Self, DynamicsError> {
        Self::run_with_grid(path, false, progress)
    }

    /// [`Self::run`], and with `grid` and a split path the servo's gridded table
    /// ([`fts_grid`]) with the job's options (`output.fts_grid`, or their defaults).
    pub fn run_with_grid(
        path: &ToolPath,
        grid: bool,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<Self, DynamicsError> {
        let total = path.spiral().point_count_hint();
        if total > MAX_POINTS {
            return Err(crate::field::FieldError::new(
                "strategy.sampling",
                format!("{total} points"),
                format!(
                    "at most {MAX_POINTS} points when the machine dynamics run (a split or \
                     machine limits): they hold the path and its uniform grid in memory"
                ),
            )
            .into());
        }
        // The path as the dynamics keep it: three columns, 24 bytes a point rather than a
        // whole [`PathPoint`]; its heights alone (8) where the spiral gives the angles and
        // radii by the index, with each point's φ (16) where it gives them from φ.
        let capacity = usize::try_from(total).unwrap_or(0);
        let mut signal = PathSignal::for_spiral(path.spiral(), capacity);
        path.for_each_point(Stage::Dynamics, progress, &mut |p, _| {
            signal.push(p);
            Ok::<(), DynamicsError>(())
        })?;
        let mut dynamics = Self::of_signal(path.job(), &signal)?;
        if let (true, Some(w)) = (grid, &dynamics.w_fts_mm) {
            let job = path.job();
            let (theta, rho) = signal.angles_and_radii();
            let servo = ServoPath {
                theta: &theta,
                rho: &rho,
                w,
            };
            let spec = job.output.fts_grid.clone().unwrap_or_default();
            let conv = job.output.conventions();
            let built = FtsGrid::build(&job.name, servo, &spec, &conv, progress)?;
            let grid = built.ok_or(PathError::Cancelled)?;
            dynamics.report.fts_grid = Some(grid.report.clone());
            dynamics.fts_grid = Some(grid);
        }
        Ok(dynamics)
    }

    /// The dynamics of the planned `points` of `job`.
    pub fn of_points(job: &Job, points: &[PathPoint]) -> Result<Self, SplitError> {
        let mut signal = PathSignal::with_capacity(points.len());
        for p in points {
            signal.push(p);
        }
        Self::of_signal(job, &signal)
    }

    fn of_signal(job: &Job, signal: &PathSignal) -> Result<Self, SplitError> {
        let machine = &job.machine;
        let rpm = machine.spindle_rpm;
        // The instantaneous frequency first, band by band on stretches of their own, before
        // the grid's heights are held.
        let checked = signal.check();
        let instantaneous_frequency = match checked {
            Ok(()) => instantaneous_frequency_of(signal, rpm, FREQUENCY_BANDS),
            Err(_) => Vec::new(),
        };
        // The path on its uniform grid, resampled once for every analysis below. The grid's
        // heights are handed to the first analysis that takes them and made again for the
        // others ([`PathSignal::values_at`] the grid's rate, to the bit), not held beside the
        // transforms.
        let mut uniform = checked.map(|()| signal.uniform_checked());
        let per_rev = uniform.as_ref().map_or(0, |g| g.samples_per_rev);
        let held = Cell::new(uniform.as_mut().ok().map(|g| std::mem::take(&mut g.z_mm)));
        let heights = || {
            let first = held.take();
            first.unwrap_or_else(|| signal.values_at(per_rev, &signal.z_mm))
        };
        // The spectrum with Z's highest significant frequency read off it (cycles a
        // revolution), and X's bandwidth figure of the radii resampled on the grid, made once
        // the spectrum has let its record go (on a short grid, one transform of their length
        // for both).
        let (spectrum, z_band_cpr, x_needed_hz) = match uniform.as_ref() {
            Ok(g) => {
                let radius = |i: usize| signal.rho(i);
                let (s, z_band, x_band) = amplitude_spectrum_and_bands_on(
                    signal,
                    g,
                    heights(),
                    radius,
                    rpm,
                    SPECTRUM_BINS,
                );
                (s, z_band, Some(hz(x_band, rpm)))
            }
            Err(_) => (Spectrum::default(), None, None),
        };
        // The servo's share is let go once its figures are in the report, and made again at
        // the end ([`servo_share`], to the bit): it is not held beside Z's figure.
        let (split_report, z_slide) = match &job.strategy.split {
            None => (None, None),
            Some(spec) => {
                let limits = split_limits(machine);
                let s = split_on(signal, &uniform, z_band_cpr, spec, rpm, limits.as_ref())?;
                let report = SplitReport {
                    spec: spec.clone(),
                    cutoff_hz: s.cutoff_hz,
                    z_slide_pv_um: pv_um(&s.z_slide_mm),
                    w_fts_pv_um: pv_um(&s.w_fts_mm),
                    verdict: s.verdict,
                };
                (Some(report), Some(s.z_slide_mm))
            }
        };
        // A split path's Z figure takes the slide's share resampled on the grid: the grid's own
        // heights are let go first.
        if let Ok(g) = uniform.as_mut() {
            g.z_mm = Vec::new();
        }
        let grid = uniform.as_ref().ok();
        let samples = (0..signal.len()).map(|i| {
            let slide = z_slide.as_ref().and_then(|z| z.get(i)).copied();
            AxisSample::new(signal.theta(i), signal.rho(i), signal.z_mm[i], slide)
        });
        // The axis checks (a pass over the points) beside Z's bandwidth figure (a transform of
        // the slide's Z on the grid: the path's, or its share of a split path resampled alike).
        let (axes, z_needed_hz) = both(
            || check_axes(samples, machine),
            || {
                grid.map(|g| {
                    let cpr = match (&z_slide, z_band_cpr) {
                        (Some(z), _) => highest_significant_cycles_per_rev_at(signal, g, |i| z[i]),
                        (None, Some(k)) => k,
                        (None, None) => {
                            highest_significant_cycles_per_rev_at(signal, g, |i| signal.z_mm[i])
                        }
                    };
                    hz(cpr, rpm)
                })
            },
        );
        let bandwidth = SlideBandwidths {
            x: BandwidthCheck::of(x_needed_hz, machine.x_slide.map(|s| s.bandwidth_hz)),
            z: BandwidthCheck::of(z_needed_hz, machine.z_slide.map(|s| s.bandwidth_hz)),
        };
        let w_fts = z_slide.as_ref().map(|z| servo_share(&signal.z_mm, z));
        let channels = match (&z_slide, &w_fts) {
            (Some(z), Some(w)) => Some(ChannelProfile::of(|i| signal.rho(i), z, w)),
            _ => None,
        };
        Ok(Self {
            report: DynamicsReport {
                spectrum,
                instantaneous_frequency,
                split: split_report,
                axes,
                channels,
                bandwidth,
                fts_grid: None,
            },
            z_slide_mm: z_slide,
            w_fts_mm: w_fts,
            fts_grid: None,
        })
    }
}
