//! Hybrid FTS/SSS splitting: the compensated path z becomes a slide channel Z and a fast tool
//! servo channel W with `Z + W = z` (paper 000, "Evaluation of geometrical splitting for hybrid
//! FTS/SSS process": low-order frequencies to the slow slide servo, high-order ones to the FTS;
//! paper 002, "surface decomposition": a rotationally symmetric surface plus a freeform
//! remainder). In every mode Z is computed first and `W = z − Z` at the path points, so the two
//! add up to z to the rounding of one subtraction (1e-16 relative).
//!
//! **Symmetric** ([`SplitSpec::Symmetric`]): Z is the rotationally symmetric part S of
//! [`crate::dynamics::path_signal`] (the two-revolution triangle mean on the uniform angle grid,
//! interpolated back to the points), W the freeform residual. S differs from the azimuthal mean
//! by at most `|S″|·f²/12 + Σ|a_m″|·f²/(4π²m²)` (f the feed, a_m the amplitude of harmonic m,
//! ″ = d²/dρ²), which is what W carries besides the freeform part.
//!
//! **Low-pass** ([`SplitSpec::LowPass`]): Z is z through the zero-phase filter
//! `H(k) = 1/(1 + (k/k_c)^8)` (k the frequency, k_c the cutoff), the magnitude of a 4th-order
//! Butterworth filter run forwards and backwards (H(k_c) = ½, flat to 0.4 % below k_c/2, −48 dB
//! per octave above), applied in the frequency domain to the uniform grid of the path extended
//! by [`EXTENSION_REVS`] revolutions before the rim and at least as many after the centre (to
//! a length the FFT transforms fast, [`crate::dynamics::spectrum::fast_length`]). A surface is periodic
//! in θ, so the extension repeats the first (last) revolution of the non-symmetric residual on
//! the symmetric part continued along its tangent: the joins are continuous in value and slope
//! to within the change of the part over one revolution (a mirror image instead leaves a slope
//! kink, which the filter turns into a transient of about `slope/(2π·k_c)` in W: 0.1 mm for a
//! 0.5 mm tone of 6 cycles/rev at k_c = 9). The periodic FFT then joins the two extensions to
//! each other 16 revolutions from the path, where the filter's impulse response, decaying like
//! `e^(−2π·k_c·sin(π/8)·t)` over t revolutions, has fallen below 1e-8 even at the lowest automatic
//! cutoff of ½ cycle/rev. Real and even, H delays nothing. Z is interpolated linearly back to the
//! path points. A grid of more than [`SEGMENT_SAMPLES`] samples is filtered in segments of at
//! most that many (overlap-save): each segment's record carries the extended signal
//! [`SEGMENT_MARGIN_CYCLES`]`/k` revolutions (k the lowest cutoff applied), at least
//! [`SEGMENT_MARGIN_REVS`], beyond either side where it meets another, over which the impulse
//! response falls by 2e-17, so that a segment's samples are the whole record's to the
//! rounding of its own transform (to pm at cutoffs near the grid's Nyquist frequency). Z at
//! the points is read off each segment's channel in turn (a point whose grid interval ends in
//! the next segment reads that end there), to the bit the whole channel interpolated, which is
//! never made whole. At one cutoff (the low-pass split, and the automatic split's first trial
//! at its lowest) each segment is made, filtered and read before the next is made: one
//! segment's record is held beside the path. The automatic split's bisection holds the
//! segments' spectra, about one record of the grid, and one segment's channel at a time.
//!
//! **Automatic** ([`SplitSpec::Auto`], needs [`SplitLimits`]): the slide alone (`Z = z`,
//! `W = 0`) if z keeps within the slide's velocity, acceleration and bandwidth; otherwise the
//! lowest cutoff k* (cycles per revolution, in `[0.5, M/2]`, M the grid's samples per
//! revolution) for which W's peak-to-valley fits the FTS stroke, found by bisection on log k to
//! 0.1 % (W's PV falls as the cutoff rises: the bisection assumes it, and the k* returned always
//! satisfies the stroke, being the bracket's upper end). Z at k* is then checked against the
//! slide's velocity, acceleration and bandwidth (the cutoff, k*·n/60 Hz) and W against the
//! FTS's bandwidth and acceleration.
//!
//! **Checks and speed.** A channel's velocity and acceleration are its largest slope and curvature
//! against the spindle angle ([`PathSignal::angle_extremes`]) times ω and ω²; its bandwidth is the
//! highest significant frequency of its non-symmetric part, the channel at the points resampled
//! on the grid ([`crate::dynamics::spectrum::highest_significant_cycles_per_rev_at`]), in Hz;
//! the stroke is W's PV.
//! Every figure is computed once per revolution-angle, so at another speed n′ a velocity or
//! bandwidth scales by n′/n, an acceleration by (n′/n)², the stroke not at all. Where a check fails
//! the verdict is [`Verdict::Infeasible`] with the failing checks and the highest speed at which
//! every speed-dependent check passes for the same split geometry (cutoff in cycles per
//! revolution), `n·min((limit/value)^(1/p))` over the checks (p = 1 or 2), rounded down to three
//! significant digits; for the automatic split the larger of that speed for the slide alone and for
//! k*. No speed helps when the stroke fails.

use crate::dynamics::path_signal::{
    AngleExtremes, BLOCK_SAMPLES, PathSignal, SignalError, UniformSignal, extremes_at, first_past,
    hz, merged, omega, peak_to_valley, peak_to_valley_at, spread,
};
use crate::dynamics::real_transform::RealInverse;
use crate::dynamics::spectrum::{
    fast_length, forward_plan, highest_significant_cycles_per_rev_at, inverse_plan,
};
use crate::field::{FieldError, positive};
use crate::job::SplitSpec;
use crate::parallel::{both, fill_chunks, map_indices};
use rustfft::num_complex::Complex;
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::convert::Infallible;
use std::ops::Range;
use thiserror::Error;

/// Order of the Butterworth response whose square is the low-pass ([`response`]).
pub const BUTTERWORTH_ORDER: i32 = 4;

/// The lowest cutoff the automatic split tries, cycles per revolution.
pub const AUTO_MIN_CYCLES_PER_REV: f64 = 0.5;

/// Revolutions added before and after the path for the low-pass (module docs).
pub const EXTENSION_REVS: usize = 16;

/// Relative precision of the automatic cutoff.
pub const AUTO_PRECISION: f64 = 1e-3;

/// The machine's limits as the splitter uses them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SplitLimits {
    /// FTS stroke (largest PV of W), mm.
    pub fts_stroke_mm: f64,
    /// FTS bandwidth, Hz.
    pub fts_bandwidth_hz: f64,
    /// FTS acceleration, mm/s².
    pub fts_acceleration_mm_per_s2: f64,
    /// Z slide velocity, mm/s.
    pub slide_velocity_mm_per_s: f64,
    /// Z slide acceleration, mm/s².
    pub slide_acceleration_mm_per_s2: f64,
    /// Z slide bandwidth, Hz.
    pub slide_bandwidth_hz: f64,
}

/// A limit of [`SplitLimits`], named as its field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Limit {
    /// `fts_stroke_mm`: W's PV, mm.
    FtsStrokeMm,
    /// `fts_bandwidth_hz`: W's highest significant frequency, Hz.
    FtsBandwidthHz,
    /// `fts_acceleration_mm_per_s2`: W's largest acceleration, mm/s².
    FtsAccelerationMmPerS2,
    /// `slide_velocity_mm_per_s`: Z's largest velocity, mm/s.
    SlideVelocityMmPerS,
    /// `slide_acceleration_mm_per_s2`: Z's largest acceleration, mm/s².
    SlideAccelerationMmPerS2,
    /// `slide_bandwidth_hz`: the cutoff, or Z's highest significant frequency, Hz.
    SlideBandwidthHz,
}

impl Limit {
    /// How the value scales with the spindle speed: value ∝ n^p.
    pub fn speed_power(self) -> i32 {
        match self {
            Limit::FtsStrokeMm => 0,
            Limit::FtsBandwidthHz | Limit::SlideVelocityMmPerS | Limit::SlideBandwidthHz => 1,
            Limit::FtsAccelerationMmPerS2 | Limit::SlideAccelerationMmPerS2 => 2,
        }
    }

    /// The limit's value in `limits`.
    pub fn of(self, limits: &SplitLimits) -> f64 {
        match self {
            Limit::FtsStrokeMm => limits.fts_stroke_mm,
            Limit::FtsBandwidthHz => limits.fts_bandwidth_hz,
            Limit::FtsAccelerationMmPerS2 => limits.fts_acceleration_mm_per_s2,
            Limit::SlideVelocityMmPerS => limits.slide_velocity_mm_per_s,
            Limit::SlideAccelerationMmPerS2 => limits.slide_acceleration_mm_per_s2,
            Limit::SlideBandwidthHz => limits.slide_bandwidth_hz,
        }
    }
}

/// One channel figure against its limit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Check {
    /// Which limit.
    pub limit: Limit,
    /// The channel's figure, in the limit's unit.
    pub value: f64,
    /// The limit.
    pub allowed: f64,
    /// Radius where the figure is reached, mm, where it has one place.
    pub at_rho_mm: Option<f64>,
}

impl Check {
    /// Whether the figure is within the limit.
    pub fn passes(&self) -> bool {
        self.value <= self.allowed
    }
}

/// What the split means for the machine.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum Verdict {
    /// No limits were given.
    Unchecked,
    /// Every check passes.
    Feasible {
        /// W is zero: the slide cuts alone.
        slide_alone: bool,
        /// The checks.
        checks: Vec<Check>,
    },
    /// Some check fails.
    Infeasible {
        /// The failing checks.
        conflicts: Vec<Check>,
        /// All checks.
        checks: Vec<Check>,
        /// The highest spindle speed at which the split passes, rev/min; `None` when no speed
        /// helps (the stroke).
        feasible_spindle_rpm: Option<f64>,
    },
}

/// The two channels, one value per path point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Split {
    /// Slide channel Z, mm.
    pub z_slide_mm: Vec<f64>,
    /// FTS channel W = z − Z, mm.
    pub w_fts_mm: Vec<f64>,
    /// The low-pass cutoff, Hz (low-pass and automatic hybrid splits).
    pub cutoff_hz: Option<f64>,
    /// The checks against the limits.
    pub verdict: Verdict,
}

/// A split that cannot be made.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SplitError {
    /// A setting is out of range.
    ///
    /// ```
    /// use spiralcam::dynamics::split::split;
    /// use spiralcam::job::SplitSpec;
    /// let s = spiralcam::dynamics::path_signal::PathSignal::from_columns(vec![0.0, 1.0, 2.0], vec![1.0; 3], vec![0.0; 3]);
    /// let e = split(&s, &SplitSpec::LowPass { cutoff_hz: -1.0 }, 60.0, None).unwrap_err();
    /// assert!(e.to_string().starts_with("strategy.split.cutoff_hz = -1: must be"));
    /// ```
    #[error(transparent)]
    Field(#[from] FieldError),
    /// The path cannot be analysed.
    ///
    /// ```
    /// use spiralcam::dynamics::split::split;
    /// use spiralcam::job::SplitSpec;
    /// let e = split(&Default::default(), &SplitSpec::Symmetric, 60.0, None).unwrap_err();
    /// assert!(e.to_string().starts_with("the path has 0 points"));
    /// ```
    #[error(transparent)]
    Signal(#[from] SignalError),
}

/// The servo's share W = z − Z of the path's heights `z` with the slide's `slide`, mm.
pub fn servo_share(z: &[f64], slide: &[f64]) -> Vec<f64> {
    map_indices(z.len().min(slide.len()), |i| z[i] - slide[i])
}

/// The low-pass response at frequency `k` for cutoff `k_c` (any one unit).
pub fn response(k: f64, k_c: f64) -> f64 {
    1.0 / (1.0 + (k / k_c).abs().powi(2 * BUTTERWORTH_ORDER))
}

/// Grid samples a segment of the low-pass gives at most (module docs; records of about
/// 32 MiB): a longer grid is filtered segment by segment, so that a filter at one cutoff holds
/// one segment at a time and the automatic split's bisection the segments' spectra (about one
/// record of the grid in all) and one segment's channel at a time, never a channel of the whole
/// grid.
pub const SEGMENT_SAMPLES: usize = 1 << 22;

/// The margin of signal either side of a segment's samples where it meets another,
/// revolutions, is `SEGMENT_MARGIN_CYCLES / k_c` at the lowest cutoff `k_c` (cycles per
/// revolution) the filter is applied at, over which its impulse response falls by
/// `e^(−2π·sin(π/8)·16)` = 2e-17 (module docs), and at least [`SEGMENT_MARGIN_REVS`].
pub const SEGMENT_MARGIN_CYCLES: f64 = 16.0;

/// The least margin where segments meet, revolutions: the automatic split's at its lowest
/// cutoff. A cutoff near the grid's Nyquist frequency leaves the response cut off there, whose
/// impulse response decays only as 1/t²: a few pm over this margin
/// (`a_filter_in_segments_is_the_whole_records`).
pub const SEGMENT_MARGIN_REVS: usize = 2 * EXTENSION_REVS;

/// The zero-phase low-pass of one grid signal at any cutoff: the (real-input) FFT of the
/// extended signal is taken once, and its inverse planned once; a grid longer than
/// [`SEGMENT_SAMPLES`] in segments of it (module docs).
struct LowPass {
    segments: Vec<Segment>,
    samples: usize,
    samples_per_rev: usize,
}

/// A segment of [`LowPass`]: the spectrum of the extended signal's samples `start … start +
/// len − 1` (grid numbers, negative before the first), whose filtered samples `core` it gives.
struct Segment {
    /// Bins 0 … len/2 of the record's spectrum.
    spectrum: Vec<Complex<f64>>,
    /// The inverse transform, of the record's length.
    inverse: RealInverse,
    /// The grid number of the record's first sample.
    start: isize,
    /// The grid samples it gives.
    core: Range<usize>,
}

impl LowPass {
    /// The filter of `heights`, one a sample of `grid` (the grid of `signal`), for cutoffs of
    /// at least `lowest_cpr` cycles per revolution: its segments ([`Making`]), all held.
    fn new(signal: &PathSignal, grid: &UniformSignal, heights: Vec<f64>, lowest_cpr: f64) -> Self {
        Self::in_segments(signal, grid, heights, lowest_cpr, SEGMENT_SAMPLES)
    }

    /// [`Self::new`] in segments of at most `most` samples (or 8 margins).
    fn in_segments(
        signal: &PathSignal,
        grid: &UniformSignal,
        heights: Vec<f64>,
        lowest_cpr: f64,
        most: usize,
    ) -> Self {
        Self {
            segments: Making::new(signal, grid, heights, lowest_cpr, most).collect(),
            samples: grid.len(),
            samples_per_rev: grid.samples_per_rev,
        }
    }

    /// Z at the points of `signal` (on `grid`) with the slide's `heights` filtered at `k_c`
    /// cycles per revolution alone: [`Self::into_points`] of [`Self::new`] to the bit, each
    /// segment made and read at its points before the next is made, so that no more than one
    /// segment's spectrum is held.
    fn points(signal: &PathSignal, grid: &UniformSignal, heights: Vec<f64>, k_c: f64) -> Vec<f64> {
        Self::points_in_segments(signal, grid, heights, k_c, SEGMENT_SAMPLES)
    }

    /// [`Self::points`] in segments of at most `most` samples (or 8 margins).
    fn points_in_segments(
        signal: &PathSignal,
        grid: &UniformSignal,
        heights: Vec<f64>,
        k_c: f64,
        most: usize,
    ) -> Vec<f64> {
        let segments = Making::new(signal, grid, heights, k_c, most);
        points_of(segments, signal, grid, k_c)
    }

    /// The peak-to-valley of the servo's share `z − Z` at the points of `signal` (on `grid`)
    /// with the slide's Z filtered at `k_c`: each segment's channel made in turn (its transform
    /// on every core) and read at the points whose grid interval starts in its core (on every
    /// core), so that one segment's channel is held beside the spectra.
    fn servo_peak_to_valley(&self, signal: &PathSignal, grid: &UniformSignal, k_c: f64) -> f64 {
        let n = self.samples;
        let interval = |i: usize| grid.interval(n, signal.angle(i));
        let found = self.segments.iter().map(|segment| {
            let channel = segment.channel(self.samples_per_rev, k_c);
            let at = |j: usize| channel[(j as isize - segment.start) as usize];
            let starts_before = |j: usize| move |i: usize| interval(i).0 < j;
            let first = first_past(0, signal.len(), starts_before(segment.core.start));
            let last = first_past(first, signal.len(), starts_before(segment.core.end));
            extremes_at(last - first, |k| {
                let (j, t) = interval(first + k);
                signal.z_mm[first + k] - (at(j) + t * (at(j + 1) - at(j)))
            })
        });
        spread(merged(found))
    }

    /// The filtered grid signal at cutoff `k_c` cycles per revolution, made whole: the reference
    /// the tests hold [`Self::into_points`] and the trials to.
    #[cfg(test)]
    fn into_channel(self, k_c: f64) -> Vec<f64> {
        let mut out: Vec<f64> = Vec::new();
        for segment in self.segments {
            let skip = (segment.core.start as isize - segment.start) as usize;
            let core = segment.core.len();
            let channel = segment.into_channel(self.samples_per_rev, k_c);
            out.extend_from_slice(&channel[skip..skip + core]);
        }
        out
    }

    /// Z at the points of `signal` (on `grid`) with the slide filtered at `k_c` cycles per
    /// revolution ([`points_of`]), each segment's spectrum let go once read.
    fn into_points(self, signal: &PathSignal, grid: &UniformSignal, k_c: f64) -> Vec<f64> {
        points_of(self.segments.into_iter(), signal, grid, k_c)
    }
}

/// Z at the points of `signal` (on `grid`) with the slide filtered at `k_c` cycles per
/// revolution, from the low-pass's `segments` in order, to the bit
/// [`UniformSignal::interpolate`] of the whole filtered grid signal: each segment's channel
/// made in its spectrum's memory and read at the points whose grid interval starts in its
/// core (where the interval ends in the next core, its end is read there). The grid signal is
/// never held whole.
fn points_of(
    segments: impl Iterator<Item = Segment>,
    signal: &PathSignal,
    grid: &UniformSignal,
    k_c: f64,
) -> Vec<f64> {
    let (n, m) = (grid.len(), grid.samples_per_rev);
    let interval = |i: usize| grid.interval(n, signal.angle(i));
    let mut z: Vec<f64> = Vec::with_capacity(signal.len());
    // Points in a core's last interval: their slot, the sample at the interval's start and the
    // fraction of the step past it.
    let mut pending: Vec<(usize, f64, f64)> = Vec::new();
    for segment in segments {
        let (start, core) = (segment.start, segment.core.clone());
        let channel = segment.into_channel(m, k_c);
        let at = |j: usize| channel[(j as isize - start) as usize];
        for (i, v, t) in pending.drain(..) {
            z[i] = v + t * (at(core.start) - v);
        }
        let from = z.len();
        let starts_before = |j: usize| move |i: usize| interval(i).0 < j;
        let inner = first_past(
            from,
            signal.len(),
            starts_before(core.end.saturating_sub(1)),
        );
        let to = first_past(inner, signal.len(), starts_before(core.end));
        z.resize(to, 0.0);
        let Ok(()) = fill_chunks(&mut z[from..inner], |offset, part| {
            for (i, slot) in (from + offset..).zip(part.iter_mut()) {
                let (j, t) = interval(i);
                *slot = at(j) + t * (at(j + 1) - at(j));
            }
            Ok::<(), Infallible>(())
        });
        pending.extend((inner..to).map(|i| {
            let (j, t) = interval(i);
            (i, at(j), t)
        }));
    }
    z
}

/// The low-pass's segments of a grid signal, made one at a time in order
/// ([`LowPass::in_segments`]): the whole record extended in the heights' memory, or for a
/// longer grid each segment made from the path ([`PathSignal::values_at`]'s samples, to the
/// bit) once the heights' ends are read and the heights let go.
struct Making<'a> {
    signal: &'a PathSignal,
    samples_per_rev: usize,
    ends: Ends,
    /// The heights, where the grid is one record.
    whole: Option<Vec<f64>>,
    layout: std::vec::IntoIter<(isize, usize, Range<usize>)>,
}

impl<'a> Making<'a> {
    /// The segments of `heights`, one a sample of `grid` (the grid of `signal`), for cutoffs of
    /// at least `lowest_cpr` cycles per revolution, of at most `most` samples (or 8 margins).
    fn new(
        signal: &'a PathSignal,
        grid: &UniformSignal,
        heights: Vec<f64>,
        lowest_cpr: f64,
        most: usize,
    ) -> Self {
        let m = grid.samples_per_rev;
        let revs = (SEGMENT_MARGIN_CYCLES / lowest_cpr).ceil() as usize;
        let margin = revs.max(SEGMENT_MARGIN_REVS) * m;
        let layout = segments(grid.len(), m, margin, most);
        Self {
            signal,
            samples_per_rev: m,
            ends: Ends::of(grid, &heights),
            whole: (layout.len() == 1).then_some(heights),
            layout: layout.into_iter(),
        }
    }
}

impl Iterator for Making<'_> {
    type Item = Segment;

    fn next(&mut self) -> Option<Segment> {
        let part = self.layout.next()?;
        let (ends, m) = (&self.ends, self.samples_per_rev);
        Some(match self.whole.take() {
            Some(heights) => {
                let (head, n) = (part.0.unsigned_abs(), heights.len());
                let tail = part.1 - n - head;
                Segment::of(|| ends.extend(heights, head, tail), &part)
            }
            None => Segment::of(|| ends.record(self.signal, m, part.0, part.1), &part),
        })
    }
}

impl Segment {
    /// The record filtered at cutoff `k_c` cycles per revolution, on a grid of
    /// `samples_per_rev` (the whole record).
    fn channel(&self, samples_per_rev: usize, k_c: f64) -> Vec<f64> {
        self.filtered(self.spectrum.clone(), samples_per_rev, k_c)
    }

    /// [`Self::channel`] made in the spectrum's memory.
    fn into_channel(mut self, samples_per_rev: usize, k_c: f64) -> Vec<f64> {
        let spectrum = std::mem::take(&mut self.spectrum);
        self.filtered(spectrum, samples_per_rev, k_c)
    }

    /// The record whose spectrum is `bins` filtered at `k_c`, in their memory.
    fn filtered(&self, mut bins: Vec<Complex<f64>>, samples_per_rev: usize, k_c: f64) -> Vec<f64> {
        let len = self.inverse.len();
        let cpr_per_bin = samples_per_rev as f64 / len as f64;
        for (j, c) in bins.iter_mut().enumerate() {
            *c = *c * response(j as f64 * cpr_per_bin, k_c) / len as f64;
        }
        self.inverse.record(bins)
    }

    /// The segment of the extended signal's record that `make` gives, laid out as `(start,
    /// len, core)`.
    fn of(
        make: impl FnOnce() -> Vec<f64>,
        (start, len, core): &(isize, usize, Range<usize>),
    ) -> Self {
        // The record made while its transform is made on a second core, then transformed
        // while the inverse is made there.
        let (record, forward) = both(make, || forward_plan(*len));
        debug_assert_eq!(record.len(), *len);
        let (spectrum, inverse) = both(|| forward.spectrum(record), || inverse_plan(*len));
        Self {
            spectrum,
            inverse,
            start: *start,
            core: core.clone(),
        }
    }
}

/// The low-pass's records for a grid of `n` samples at `m` a revolution with `margin` samples
/// where segments meet: `(first sample, length, core)` each, the grid numbers of a record's
/// first sample and of the samples it gives. One record of the whole grid with
/// [`EXTENSION_REVS`] revolutions before and at least as many after, up to `most` samples
/// (or 8 margins); else equal cores of at most that many, each with the margin either side
/// where it meets another and that extension at the grid's ends.
fn segments(n: usize, m: usize, margin: usize, most: usize) -> Vec<(isize, usize, Range<usize>)> {
    let head = EXTENSION_REVS * m;
    let most = most.max(8 * margin);
    if n <= most {
        return vec![(-(head as isize), fast_length(n + 2 * head, false), 0..n)];
    }
    let count = n.div_ceil(most);
    let size = n.div_ceil(count);
    (0..count)
        .map(|k| {
            let core = k * size..n.min((k + 1) * size);
            let before = if k == 0 { head } else { margin };
            let after = if k + 1 == count { head } else { margin };
            let len = fast_length(core.len() + before + after, false);
            (core.start as isize - before as isize, len, core)
        })
        .collect()
}

/// What extends a grid signal beyond its ends (module docs): the non-symmetric residual of
/// its first (last) revolution, on the symmetric part continued along its tangent. Only the
/// symmetric part's first and last revolution are made.
struct Ends {
    samples: usize,
    rev: usize,
    /// The residual of samples 0 … rev − 1.
    head: Vec<f64>,
    /// The residual of samples n − rev … n − 1.
    tail: Vec<f64>,
    /// The symmetric part at samples 0 and n − 1.
    bases: (f64, f64),
    /// Its slopes over the first and the last revolution, a sample.
    slopes: (f64, f64),
}

impl Ends {
    /// The ends of the grid signal `x`.
    fn of(grid: &UniformSignal, x: &[f64]) -> Self {
        let (n, m) = (x.len(), grid.samples_per_rev);
        let rev = m.min(n - 1).max(1);
        // The symmetric part at samples 0 … rev and n − 1 − rev … n − 1.
        let (head_sym, tail_sym) = grid.symmetric_part_at_ends(x, rev + 1);
        let sym_end = |j: usize| tail_sym[j + rev + 1 - n];
        Self {
            samples: n,
            rev,
            head: (0..rev).map(|j| x[j] - head_sym[j]).collect(),
            tail: (n - rev..n).map(|j| x[j] - sym_end(j)).collect(),
            bases: (head_sym[0], sym_end(n - 1)),
            slopes: (
                (head_sym[rev] - head_sym[0]) / rev as f64,
                (sym_end(n - 1) - sym_end(n - 1 - rev)) / rev as f64,
            ),
        }
    }

    /// The extended signal at grid number `j` outside `0 … n − 1`: before the first sample,
    /// the residual one (or more) whole revolutions in; after the last, one (or more) back.
    fn value(&self, j: isize) -> f64 {
        let (n, rev) = (self.samples, self.rev);
        if j < 0 {
            let back = j.unsigned_abs();
            let k = (rev - back % rev) % rev;
            self.head[k] + self.bases.0 - self.slopes.0 * back as f64
        } else {
            let ahead = j as usize + 1 - n;
            let k = rev - 1 - (rev - ahead % rev) % rev;
            self.tail[k] + self.bases.1 + self.slopes.1 * ahead as f64
        }
    }

    /// The grid signal `x` with `e` samples added before and `tail` after. The record grows in
    /// `x`'s memory (a long one is remapped, not copied), its samples moved up by `e`.
    fn extend(&self, mut x: Vec<f64>, e: usize, tail: usize) -> Vec<f64> {
        let n = x.len();
        x.reserve_exact(e + tail);
        x.resize(n + e + tail, 0.0);
        x.copy_within(0..n, e);
        self.fill_outside(&mut x, -(e as isize));
        x
    }

    /// The extended signal's samples `start … start + len − 1`: the grid's from the path
    /// (`signal` at `m` a revolution), the others by [`Self::value`].
    fn record(&self, signal: &PathSignal, m: usize, start: isize, len: usize) -> Vec<f64> {
        let mut out = vec![0.0; len];
        let n = self.samples as isize;
        let (lo, hi) = (start.max(0), (start + len as isize).min(n));
        if lo < hi {
            let within = &mut out[(lo - start) as usize..(hi - start) as usize];
            let height = |i: usize| signal.z_mm[i];
            signal.resample_with(height, m, lo as usize, within, |v, h| *v = h);
        }
        self.fill_outside(&mut out, start);
        out
    }

    /// Every sample of `record` (grid numbers from `start`) outside the grid by [`Self::value`].
    fn fill_outside(&self, record: &mut [f64], start: isize) {
        let n = self.samples as isize;
        for (j, v) in (start..).zip(record.iter_mut()) {
            if j < 0 || j >= n {
                *v = self.value(j);
            }
        }
    }
}

/// Splits `signal` at `spindle_rpm` as `spec` says, checking the channels against `limits` when
/// given (module docs).
pub fn split(
    signal: &PathSignal,
    spec: &SplitSpec,
    spindle_rpm: f64,
    limits: Option<&SplitLimits>,
) -> Result<Split, SplitError> {
    split_on(signal, &signal.uniform(), None, spec, spindle_rpm, limits)
}

/// [`split`] with the signal's uniform grid given ([`PathSignal::uniform`]), so that a caller
/// analysing the signal otherwise resamples it once, and where known the highest significant
/// frequency of the grid's heights, cycles per revolution (`z_band_cpr`, as
/// [`crate::dynamics::spectrum::amplitude_spectrum_and_band_on`] gives it with the spectrum),
/// which the automatic split then does not transform again.
pub fn split_on(
    signal: &PathSignal,
    grid: &Result<UniformSignal, SignalError>,
    z_band_cpr: Option<f64>,
    spec: &SplitSpec,
    spindle_rpm: f64,
    limits: Option<&SplitLimits>,
) -> Result<Split, SplitError> {
    positive("machine.spindle_rpm", spindle_rpm)?;
    if let Some(l) = limits {
        validate(l)?;
    }
    let grid = grid.as_ref().map_err(Clone::clone)?;
    let ctx = Context {
        signal,
        grid,
        z_band_cpr,
        rpm: spindle_rpm,
    };
    match spec {
        SplitSpec::Symmetric => {
            let z = grid.symmetric_part_at_points(signal, BLOCK_SAMPLES);
            Ok(ctx.finish(z, None, limits, None))
        }
        SplitSpec::LowPass { cutoff_hz } => {
            let nyquist = hz(grid.samples_per_rev as f64 / 2.0, spindle_rpm);
            if !(cutoff_hz.is_finite() && *cutoff_hz > 0.0 && *cutoff_hz <= nyquist) {
                return Err(FieldError::new(
                    "strategy.split.cutoff_hz",
                    cutoff_hz,
                    format!(
                        "must be a finite number in (0, {nyquist}] Hz (the Nyquist frequency of the path at {spindle_rpm} rpm)"
                    ),
                )
                .into());
            }
            let k_c = cutoff_hz * 60.0 / spindle_rpm;
            let z = LowPass::points(signal, grid, ctx.heights().into_owned(), k_c);
            Ok(ctx.finish(z, Some(k_c), limits, None))
        }
        SplitSpec::Auto => {
            let Some(limits) = limits else {
                return Err(FieldError::new(
                    "strategy.split.type",
                    "auto",
                    "needs the machine's slide and FTS limits",
                )
                .into());
            };
            Ok(ctx.auto(limits))
        }
    }
}

/// Checks that every limit is a positive finite number.
fn validate(l: &SplitLimits) -> Result<(), FieldError> {
    positive("fts_stroke_mm", l.fts_stroke_mm)?;
    positive("fts_bandwidth_hz", l.fts_bandwidth_hz)?;
    positive("fts_acceleration_mm_per_s2", l.fts_acceleration_mm_per_s2)?;
    positive("slide_velocity_mm_per_s", l.slide_velocity_mm_per_s)?;
    positive(
        "slide_acceleration_mm_per_s2",
        l.slide_acceleration_mm_per_s2,
    )?;
    positive("slide_bandwidth_hz", l.slide_bandwidth_hz)?;
    Ok(())
}

/// The slide's and the servo's extremes along the path, and the servo's peak-to-valley, mm.
#[derive(Debug, PartialEq)]
struct Motion {
    z: AngleExtremes,
    w: AngleExtremes,
    w_pv_mm: f64,
}

/// A signal, its grid (with its heights' highest significant frequency where known) and the
/// speed.
struct Context<'a> {
    signal: &'a PathSignal,
    grid: &'a UniformSignal,
    z_band_cpr: Option<f64>,
    rpm: f64,
}

impl Context<'_> {
    /// The grid's heights: its own, or made again from the path's where the dynamics let them
    /// go ([`UniformSignal::heights`]).
    fn heights(&self) -> Cow<'_, [f64]> {
        self.grid.heights(self.signal)
    }

    /// The split with the slide's share `z` at the points: W = z − Z, and the verdict against
    /// `limits` (`other_rpm` a feasible speed found for another split). The channels'
    /// bandwidth figures come first, each a transform of the channel at the points resampled
    /// on the grid ([`Self::bandwidths`]), before W is made at the points.
    fn finish(
        &self,
        z: Vec<f64>,
        cutoff_cpr: Option<f64>,
        limits: Option<&SplitLimits>,
        other_rpm: Option<f64>,
    ) -> Split {
        let s = self.signal;
        let bandwidths = limits.map(|_| {
            let w_is_zero = (0..s.len()).all(|i| s.z_mm[i] - z[i] == 0.0);
            self.bandwidths(&z, cutoff_cpr, w_is_zero)
        });
        let w = servo_share(&s.z_mm, &z);
        let verdict = match (limits, bandwidths) {
            (Some(l), Some(b)) => verdict(self.checks(&z, &w, b, l), self.rpm, other_rpm),
            _ => Verdict::Unchecked,
        };
        Split {
            z_slide_mm: z,
            w_fts_mm: w,
            cutoff_hz: cutoff_cpr.map(|k| hz(k, self.rpm)),
            verdict,
        }
    }

    /// The automatic split (module docs).
    fn auto(&self, limits: &SplitLimits) -> Split {
        let z = &self.signal.z_mm;
        // The slide's bandwidth figure (known, or a transform on the grid) beside its pass over
        // the points.
        let (bandwidths, motion) = both(
            || match self.z_band_cpr {
                Some(k) => (hz(k, self.rpm), 0.0),
                None => self.bandwidths(z, None, true),
            },
            || self.motion_alone(z),
        );
        let alone = self.checks_of(motion, bandwidths, limits);
        if alone.iter().all(Check::passes) {
            return Split {
                z_slide_mm: z.clone(),
                w_fts_mm: vec![0.0; z.len()],
                cutoff_hz: None,
                verdict: Verdict::Feasible {
                    slide_alone: true,
                    checks: alone,
                },
            };
        }
        // The filter's spectrum is let go before the checks' own transforms.
        let (k, z_grid) = self.lowest_cutoff(limits.fts_stroke_mm);
        let alone_rpm = feasible_rpm(&alone, self.rpm);
        self.finish(z_grid, Some(k), Some(limits), alone_rpm)
    }

    /// The lowest cutoff, cycles per revolution, in [[`AUTO_MIN_CYCLES_PER_REV`], M/2] at which
    /// W fits `stroke_mm` (M/2 when none does: the stroke check then fails), and the slide's
    /// share at the points at that cutoff. The lowest is tried first, a segment at a time
    /// ([`LowPass::points`]): it is the answer where the path's non-symmetric part fits the
    /// stroke. Otherwise the filter is made for the bisection, whose trials hold its spectra
    /// and one segment's channel at a time ([`LowPass::servo_peak_to_valley`], the same
    /// figure to the bit); Z at the cutoff found is made from the spectra at the end
    /// ([`LowPass::into_points`]).
    fn lowest_cutoff(&self, stroke_mm: f64) -> (f64, Vec<f64>) {
        let (s, grid) = (self.signal, self.grid);
        let (mut lo, mut hi) = (AUTO_MIN_CYCLES_PER_REV, grid.samples_per_rev as f64 / 2.0);
        let at_lo = LowPass::points(s, grid, self.heights().into_owned(), lo);
        if peak_to_valley_at(s.len(), |i| s.z_mm[i] - at_lo[i]) <= stroke_mm {
            return (lo, at_lo);
        }
        drop(at_lo);
        let filter = LowPass::new(s, grid, self.heights().into_owned(), lo);
        let fits = |k: f64| filter.servo_peak_to_valley(s, grid, k) <= stroke_mm;
        if !fits(hi) {
            return (hi, filter.into_points(s, grid, hi));
        }
        while hi / lo > 1.0 + AUTO_PRECISION {
            let mid = (lo * hi).sqrt();
            if fits(mid) { hi = mid } else { lo = mid }
        }
        (hi, filter.into_points(s, grid, hi))
    }

    /// The bandwidth figures, Hz, of the slide's share `z` at the points and of the servo's:
    /// the slide's is the cutoff when there is one, else Z's highest significant frequency;
    /// the servo's is that of W = z − Z, 0 when W is 0 at every point (`w_is_zero`). Each is
    /// the channel at the points resampled on the grid
    /// ([`highest_significant_cycles_per_rev_at`]: in single precision on a long grid).
    fn bandwidths(&self, z: &[f64], cutoff_cpr: Option<f64>, w_is_zero: bool) -> (f64, f64) {
        let s = self.signal;
        let band = |value: &(dyn Fn(usize) -> f64 + Sync)| {
            hz(
                highest_significant_cycles_per_rev_at(s, self.grid, value),
                self.rpm,
            )
        };
        let slide = match cutoff_cpr {
            Some(k) => hz(k, self.rpm),
            None => band(&|i| z[i]),
        };
        let fts = if w_is_zero {
            0.0
        } else {
            band(&|i| s.z_mm[i] - z[i])
        };
        (slide, fts)
    }

    /// The six checks of the slide channel `z` and the FTS channel `w` (per point), with the
    /// bandwidth figures `(slide, servo)` of [`Self::bandwidths`].
    fn checks(&self, z: &[f64], w: &[f64], bandwidths: (f64, f64), l: &SplitLimits) -> Vec<Check> {
        self.checks_of(self.motion(z, w), bandwidths, l)
    }

    /// What the checks read of the channels `z` and `w` at the points: their largest slopes and
    /// curvatures against the spindle angle, and W's peak-to-valley, mm.
    fn motion(&self, z: &[f64], w: &[f64]) -> Motion {
        let s = self.signal;
        let (z, (w, w_pv_mm)) = both(
            || s.angle_extremes(z),
            || (s.angle_extremes(w), peak_to_valley(w.iter().copied())),
        );
        Motion { z, w, w_pv_mm }
    }

    /// [`Self::motion`] of the slide cutting `z` alone, without a servo channel of zeros: W's
    /// slopes, curvatures and peak-to-valley are 0, found at the first point, as
    /// [`PathSignal::angle_extremes`] and [`peak_to_valley`] find them for zeros.
    fn motion_alone(&self, z: &[f64]) -> Motion {
        Motion {
            z: self.signal.angle_extremes(z),
            w: AngleExtremes::default(),
            w_pv_mm: 0.0,
        }
    }

    /// [`Self::checks`] of the channels' `motion`.
    fn checks_of(
        &self,
        motion: Motion,
        (slide_hz, fts_hz): (f64, f64),
        l: &SplitLimits,
    ) -> Vec<Check> {
        let s = self.signal;
        let om = omega(self.rpm);
        let (ez, ew) = (motion.z, motion.w);
        let rho = |i: usize| (i < s.len()).then(|| s.rho(i));
        let check = |limit: Limit, value: f64, at: Option<f64>| Check {
            limit,
            value,
            allowed: limit.of(l),
            at_rho_mm: at,
        };
        vec![
            check(
                Limit::SlideVelocityMmPerS,
                ez.slope_mm_per_rad * om,
                rho(ez.slope_at),
            ),
            check(
                Limit::SlideAccelerationMmPerS2,
                ez.curvature_mm_per_rad2 * om * om,
                rho(ez.curvature_at),
            ),
            check(Limit::SlideBandwidthHz, slide_hz, None),
            check(Limit::FtsStrokeMm, motion.w_pv_mm, None),
            check(Limit::FtsBandwidthHz, fts_hz, None),
            check(
                Limit::FtsAccelerationMmPerS2,
                ew.curvature_mm_per_rad2 * om * om,
                rho(ew.curvature_at),
            ),
        ]
    }
}

/// The verdict of `checks` at `rpm`; `other_rpm` a feasible speed found for another split.
fn verdict(checks: Vec<Check>, rpm: f64, other_rpm: Option<f64>) -> Verdict {
    if checks.iter().all(Check::passes) {
        return Verdict::Feasible {
            slide_alone: false,
            checks,
        };
    }
    let own = feasible_rpm(&checks, rpm);
    let best = match (own, other_rpm) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    };
    Verdict::Infeasible {
        conflicts: checks.iter().copied().filter(|c| !c.passes()).collect(),
        checks,
        feasible_spindle_rpm: best,
    }
}

/// The highest speed at which every check passes (module docs); `None` when a check that does
/// not depend on the speed fails.
fn feasible_rpm(checks: &[Check], rpm: f64) -> Option<f64> {
    let mut ratio = f64::INFINITY;
    for c in checks {
        let p = c.limit.speed_power();
        if p == 0 {
            if !c.passes() {
                return None;
            }
        } else if c.value > 0.0 {
            ratio = ratio.min((c.allowed / c.value).powf(1.0 / p as f64));
        }
    }
    ratio.is_finite().then(|| round_down(rpm * ratio, 3))
}

/// `x` rounded down to `digits` significant digits.
fn round_down(x: f64, digits: i32) -> f64 {
    if x <= 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(digits - 1 - x.log10().floor() as i32);
    (x * scale).floor() / scale
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::path_signal::tests::{arc_spiral, spiral};
    use std::f64::consts::TAU;

    /// Amplitude of the tone of `k` cycles/rev in `v` over the points from revolution
    /// `skip` up to (not including) revolution `revs − skip` (projection on sin and cos,
    /// exact for whole frequencies over whole revolutions of equal steps).
    fn tone(s: &PathSignal, v: &[f64], k: f64, skip: f64) -> f64 {
        let inside = |a: f64| a >= skip * TAU - 1e-9 && a < s.span_rad() - skip * TAU - 1e-9;
        let (mut c, mut d, mut n) = (0.0f64, 0.0f64, 0.0);
        let angles = (0..s.len()).map(|i| s.theta(i));
        for (a, x) in angles.zip(v).filter(|(a, _)| inside(*a)) {
            c += x * (k * a).cos();
            d += x * (k * a).sin();
            n += 1.0;
        }
        2.0 * (c * c + d * d).sqrt() / n
    }

    fn limits() -> SplitLimits {
        SplitLimits {
            fts_stroke_mm: 0.07,
            fts_bandwidth_hz: 700.0,
            fts_acceleration_mm_per_s2: 1e6,
            slide_velocity_mm_per_s: 100.0,
            slide_acceleration_mm_per_s2: 1e5,
            slide_bandwidth_hz: 20.0,
        }
    }

    fn two_tones(r: f64, t: f64) -> f64 {
        0.1 + 0.5 * (6.0 * t).sin() + 0.02 * (47.0 * t).cos() + 0.0 * r
    }

    fn assert_adds_up(s: &PathSignal, out: &Split) {
        for (i, z) in s.z_mm.iter().enumerate() {
            let sum = out.z_slide_mm[i] + out.w_fts_mm[i];
            assert!((sum - z).abs() <= 1e-9, "point {i}: {sum} vs {z}");
        }
    }

    #[test]
    fn the_slide_alone_moves_as_with_a_servo_of_zeros() {
        // Against `motion` with W held as zeros, on a path whose Z has slopes and curvatures,
        // and on a flat one (every figure 0, at the first point).
        for z in [two_tones as fn(f64, f64) -> f64, |_, _| 0.25] {
            let s = spiral(4.0, 64, 4.0, 0.05, z);
            let grid = s.uniform().unwrap();
            let ctx = Context {
                signal: &s,
                grid: &grid,
                z_band_cpr: None,
                rpm: 60.0,
            };
            let zeros = vec![0.0; s.len()];
            assert_eq!(ctx.motion_alone(&s.z_mm), ctx.motion(&s.z_mm, &zeros));
        }
    }

    #[test]
    fn low_pass_puts_each_tone_where_its_response_says() {
        // Tones of 6 and 47 cycles/rev, cutoff at their geometric mean k_c: Z holds
        // A·H(k/k_c), W the rest. With the even extension the ends carry a slope kink whose
        // effect decays like the Butterworth impulse response, e^(−2π·k_c·sin(π/8)·t) per
        // revolution t: below 1e-20 after the 3 revolutions left out, so the projections agree
        // with the formula to rounding (1e-9 relative allowed).
        let s = spiral(20.0, 256, 4.0, 0.05, two_tones);
        let k_c = (6.0f64 * 47.0).sqrt();
        let rpm = 60.0;
        let out = split(&s, &SplitSpec::LowPass { cutoff_hz: k_c }, rpm, None).unwrap();
        assert_adds_up(&s, &out);
        for (k, a) in [(6.0, 0.5), (47.0, 0.02)] {
            let h = response(k, k_c);
            let (z, w) = (
                tone(&s, &out.z_slide_mm, k, 3.0),
                tone(&s, &out.w_fts_mm, k, 3.0),
            );
            assert!((z - a * h).abs() < 1e-9 * a, "Z at {k}: {z} vs {}", a * h);
            assert!((w - a * (1.0 - h)).abs() < 1e-9 * a, "W at {k}: {w}");
        }
        assert_eq!(out.cutoff_hz, Some(k_c));
        assert_eq!(out.verdict, Verdict::Unchecked);
    }

    #[test]
    fn segments_tile_the_grid_with_their_margins() {
        let (m, margin) = (64, 2048);
        for n in [100, 16_384, 16_385, 50_000, 131_073] {
            let layout = segments(n, m, margin, 16_384);
            let head = (EXTENSION_REVS * m) as isize;
            assert_eq!(layout.len(), n.div_ceil(16_384), "{n} samples");
            let mut next = 0;
            for (k, (start, len, core)) in layout.iter().enumerate() {
                assert_eq!(core.start, next);
                next = core.end;
                assert!(core.len() <= 16_384);
                let before = if k == 0 { head } else { margin as isize };
                let after = if k + 1 == layout.len() {
                    head
                } else {
                    margin as isize
                };
                assert_eq!(*start, core.start as isize - before);
                assert!(*start + *len as isize >= core.end as isize + after);
                assert_eq!(*len, fast_length(*len, false));
            }
            assert_eq!(next, n);
        }
        // Margins of more than an eighth of the most a segment gives widen the segments.
        assert_eq!(segments(50_000, m, 4096, 16_384).len(), 2);
    }

    #[test]
    fn a_filter_in_segments_is_the_whole_records() {
        // 1500 turns of 64 samples (96 001, eight segments of at most 16 384 samples with
        // margins of 32 turns): a spiral sag of 4.5 mm with tones riding on it. At each
        // cutoff well below the grid's Nyquist frequency (32 cycles a turn) the segments'
        // channel is the whole record's to 1e-12 mm where they meet (beyond 32 turns of
        // either end; 1e-14 measured). Nearer the ends each has the extensions' own error,
        // about e^(−2π·sin(π/8)·16·k) of the sag's jump where the record wraps (module docs,
        // 4.4e-9 at k = ½). At 20 cycles a turn the response is cut off at the Nyquist
        // frequency at 2 % of its peak, and the impulse response of that kink decays only as
        // 1/t²: the two differ by 3.5e-9 mm where the segments meet, 2.8e-8 mm near the ends.
        // Everywhere within 0.1 nm, and so are the servo's PVs.
        let z = |r: f64, t: f64| 0.3 * r * r + 1e-3 * (5.0 * t).sin() + 2e-4 * (29.0 * t).cos();
        let s = spiral(1500.0, 64, 4.0, 0.002, z);
        let g = s.uniform().unwrap();
        for lowest in [AUTO_MIN_CYCLES_PER_REV, 2.0] {
            let whole = || LowPass::in_segments(&s, &g, g.z_mm.clone(), lowest, usize::MAX);
            let parts = || LowPass::in_segments(&s, &g, g.z_mm.clone(), lowest, 16_384);
            assert_eq!(whole().segments.len(), 1);
            let count = parts().segments.len();
            assert!((6..=12).contains(&count), "{count} segments");
            for k in [lowest, 3.0, 20.0] {
                let pv = |f: LowPass| f.servo_peak_to_valley(&s, &g, k);
                let (pa, pb) = (pv(whole()), pv(parts()));
                let (a, b) = (whole().into_channel(k), parts().into_channel(k));
                assert_eq!(a.len(), g.len());
                assert_eq!(b.len(), g.len());
                let ends = 2 * EXTENSION_REVS * g.samples_per_rev;
                let apart =
                    |range: Range<usize>| range.map(|j| (a[j] - b[j]).abs()).fold(0.0, f64::max);
                let (inner, all) = (apart(ends..g.len() - ends), apart(0..g.len()));
                let meet = if k <= 3.0 { 1e-12 } else { 1e-8 };
                assert!(inner <= meet, "k {k}: {inner} mm where the segments meet");
                assert!(all <= 1e-7, "k {k}: {all} mm");
                assert!((pa - pb).abs() <= 1e-7, "k {k}: PV {pa} against {pb}");
            }
        }
    }

    #[test]
    fn z_at_the_points_is_the_whole_channel_read_there_to_the_bit() {
        // A constant-arc spiral (points between grid samples) filtered whole and in segments,
        // the spectra held or made one at a time: Z at the points is the whole filtered grid
        // signal interpolated there, to the bit, points in a core's last interval included.
        let z = |r: f64, t: f64| 0.3 * r * r + 1e-3 * (5.0 * t).sin() + 2e-4 * (29.0 * t).cos();
        let s = arc_spiral(900.0, 4.0, 0.004, 0.5, z);
        let g = s.uniform().unwrap();
        for most in [usize::MAX, 16_384] {
            let filter = || LowPass::in_segments(&s, &g, g.z_mm.clone(), 0.5, most);
            let count = filter().segments.len();
            assert_eq!(count == 1, most == usize::MAX, "{count} segments");
            for k in [0.5, 7.0] {
                let channel = filter().into_channel(k);
                assert_eq!(channel.len(), g.len());
                let held = filter().into_points(&s, &g, k);
                let one_by_one = LowPass::points_in_segments(&s, &g, g.z_mm.clone(), k, most);
                for z in [held, one_by_one] {
                    assert_eq!(z.len(), s.len());
                    for (i, v) in z.iter().enumerate() {
                        let want = g.interpolate(&channel, s.angle(i)).to_bits();
                        assert_eq!(v.to_bits(), want, "{count} segments, k {k}: point {i}");
                    }
                }
            }
        }
    }

    #[test]
    fn the_response_at_the_cutoff_is_one_half() {
        // H(k_c) = 1/(1 + 1) for any order: a tone at the cutoff splits in two equal halves.
        let s = spiral(12.0, 256, 2.0, 0.05, |_, t| 0.004 * (10.0 * t).sin());
        let out = split(&s, &SplitSpec::LowPass { cutoff_hz: 50.0 }, 300.0, None).unwrap();
        let z = tone(&s, &out.z_slide_mm, 10.0, 3.0);
        assert!((z - 0.002).abs() < 1e-12, "{z}");
        assert_eq!(response(3.0, 3.0), 0.5);
        assert!((response(6.0, 3.0) - 1.0 / 257.0).abs() < 1e-15);
    }

    #[test]
    fn the_low_pass_has_no_delay() {
        // A Gaussian bump in the middle of the path: a zero-phase filter keeps it symmetric
        // about its centre (to rounding), a causal one would shift it.
        let centre = 10.0 * TAU;
        let s = spiral(20.0, 200, 4.0, 0.05, |_, t| {
            0.01 * (-((t - centre) / 0.5).powi(2)).exp()
        });
        let out = split(&s, &SplitSpec::LowPass { cutoff_hz: 1.0 }, 60.0, None).unwrap();
        let mid = 2000; // point at the centre: 10 revolutions × 200
        assert!((s.angle(mid) - centre).abs() < 1e-9);
        for d in 1..600 {
            let (a, b) = (out.z_slide_mm[mid + d], out.z_slide_mm[mid - d]);
            assert!((a - b).abs() < 1e-15, "±{d}: {a} {b}");
        }
        let top = out.z_slide_mm.iter().copied().fold(f64::MIN, f64::max);
        assert_eq!(top, out.z_slide_mm[mid]);
    }

    #[test]
    fn symmetric_split_leaves_the_freeform_part_to_the_fts() {
        // z = sag(ρ) + freeform: W is the freeform part, to the symmetric part's error
        // S″·f²(1 − 1/M²)/12 with S″ = 0.02 (module docs of path_signal), 4e-6 here, constant.
        let s = spiral(10.0, 128, 3.0, 0.05, |r, t| {
            0.01 * r * r + 0.003 * r * (2.0 * t).cos()
        });
        let out = split(&s, &SplitSpec::Symmetric, 100.0, None).unwrap();
        assert_adds_up(&s, &out);
        let bias = 0.02 * 0.05f64.powi(2) * (1.0 - 1.0 / 128f64.powi(2)) / 12.0;
        for i in 0..s.len() {
            let (r, t) = (s.rho(i), s.angle(i));
            let want = 0.003 * r * (2.0 * t).cos() - bias;
            assert!(
                (out.w_fts_mm[i] - want).abs() < 1e-12,
                "{i}: {} {want}",
                out.w_fts_mm[i]
            );
        }
    }

    #[test]
    fn settings_out_of_range_are_named_errors() {
        let s = spiral(4.0, 64, 1.0, 0.1, two_tones);
        let msg = |spec: SplitSpec, l: Option<&SplitLimits>| {
            split(&s, &spec, 60.0, l).unwrap_err().to_string()
        };
        // 64 points/rev at 60 rpm: Nyquist 32 Hz.
        assert_eq!(
            msg(SplitSpec::LowPass { cutoff_hz: 33.0 }, None),
            "strategy.split.cutoff_hz = 33: must be a finite number in (0, 32] Hz (the Nyquist frequency of the path at 60 rpm)"
        );
        assert!(
            msg(
                SplitSpec::LowPass {
                    cutoff_hz: f64::NAN
                },
                None
            )
            .starts_with("strategy.split.cutoff_hz = NaN")
        );
        assert!(
            msg(SplitSpec::LowPass { cutoff_hz: 0.0 }, None)
                .starts_with("strategy.split.cutoff_hz = 0")
        );
        assert_eq!(
            msg(SplitSpec::Auto, None),
            "strategy.split.type = auto: needs the machine's slide and FTS limits"
        );
        let bad = SplitLimits {
            fts_stroke_mm: -1.0,
            ..limits()
        };
        assert!(msg(SplitSpec::Auto, Some(&bad)).starts_with("fts_stroke_mm = -1"));
        let e = split(&s, &SplitSpec::Symmetric, 0.0, None)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("machine.spindle_rpm = 0"));
    }

    #[test]
    fn a_tilted_flat_stays_on_the_slide() {
        // z = t·ρ·cos θ: one cycle per revolution, velocity t·R·ω at most (at the rim),
        // acceleration about t·R·ω²; both far inside the limits, 1 cycle/rev = 8.3 Hz at
        // 500 rpm inside 20 Hz.
        let t = 0.05f64.to_radians().tan();
        let s = spiral(50.0, 360, 10.0, 0.2, |r, a| t * r * a.cos());
        let out = split(&s, &SplitSpec::Auto, 500.0, Some(&limits())).unwrap();
        assert!(out.w_fts_mm.iter().all(|w| *w == 0.0));
        assert_eq!(out.z_slide_mm, s.z_mm);
        let Verdict::Feasible {
            slide_alone: true,
            checks,
        } = &out.verdict
        else {
            panic!("{:?}", out.verdict)
        };
        // dz/dφ = −t·(b·cos φ + ρ·sin φ), b = f/2π: largest at the first φ = π/2, where
        // ρ = R − f/4, as t·√(ρ² + b²) (b²/2ρ² = 5e-6 relative); the chord slope reads it
        // low by Δ²/24 = 1.3e-5 (Δ = 1°). So t·(R − f/4)·ω within 1e-4 relative.
        let om = TAU * 500.0 / 60.0;
        let v = checks[0].value;
        let want = t * (10.0 - 0.2 / 4.0) * om;
        assert!((v - want).abs() < 1e-4 * want, "{v} vs {want}");
        // The acceleration: d²z/dφ² = t·(2b·sin φ − ρ·cos φ), largest at the first interior
        // point (φ = Δ, ρ = R − b·Δ; φ = 0 has no second difference), read by the second
        // difference within Δ²/12 = 2.5e-5 relative.
        let acc = checks[1].value;
        let (d, b) = (1f64.to_radians(), 0.2 / TAU);
        let want = t * ((10.0 - b * d) * d.cos() - 2.0 * b * d.sin()) * om * om;
        assert!((acc - want).abs() < 1e-4 * want, "{acc} vs {want}");
        // One cycle per revolution, 8.33 Hz, to the reach of the Hann sidelobes above the 1 %
        // threshold: 3.5 bins of 1/50 cycle/rev (0.17 Hz).
        let bw = checks[2].value;

        assert!(
            (bw - 500.0 / 60.0).abs() <= 3.5 * 500.0 / 60.0 / 50.0,
            "{bw}"
        );
    }

    #[test]
    fn content_beyond_the_slide_bandwidth_goes_to_the_fts() {
        // 6 and 47 cycles/rev at 60 rpm: 47 Hz is beyond the slide's 20 Hz, so the slide alone
        // fails; the 1 mm PV of the 6 Hz tone is beyond the 70 µm stroke, so the cutoff must
        // keep most of it on Z: (6/k)^8 ≲ (70 − 40)/1000 puts k* near 9.3 cycles/rev.
        let s = spiral(20.0, 256, 4.0, 0.05, two_tones);
        let out = split(&s, &SplitSpec::Auto, 60.0, Some(&limits())).unwrap();
        assert_adds_up(&s, &out);
        let Verdict::Feasible {
            slide_alone: false,
            checks,
        } = &out.verdict
        else {
            panic!("{:?}", out.verdict)
        };
        let fc = out.cutoff_hz.unwrap();
        assert!(fc > 6.0 && fc < 20.0, "{fc}");
        let pv = |v: &[f64]| peak_to_valley(v.iter().copied());
        assert!(pv(&out.w_fts_mm) <= 0.07 && checks[3].value == pv(&out.w_fts_mm));
        // The lowest such cutoff, to the search's precision.
        let lower = split(
            &s,
            &SplitSpec::LowPass {
                cutoff_hz: fc / (1.0 + 2.0 * AUTO_PRECISION),
            },
            60.0,
            None,
        )
        .unwrap();
        assert!(pv(&lower.w_fts_mm) > 0.07);
        // Each tone where the response at k* puts it (as in the low-pass test).
        for (k, a) in [(6.0, 0.5), (47.0, 0.02)] {
            let h = response(k, fc);
            assert!((tone(&s, &out.z_slide_mm, k, 3.0) - a * h).abs() < 1e-9 * a);
            assert!((tone(&s, &out.w_fts_mm, k, 3.0) - a * (1.0 - h)).abs() < 1e-9 * a);
        }
    }

    #[test]
    fn an_infeasible_split_says_why_and_which_speed_would_do() {
        // As above with a slide of 3 Hz: at 60 rpm the cutoff k* ≈ 9.3 Hz exceeds it, and no
        // other check is near its limit (Z: 6·0.5·ω = 19 mm/s of 100, 36·0.5·ω² = 710 mm/s² of
        // 1e5; W: 47 Hz of 700, 47²·0.02·ω² = 1.7e3 mm/s² of 1e6). The bandwidth scales with
        // n, so the speed is 60·3/k* rpm (k* in Hz at 60 rpm = cycles/rev), rounded down to three
        // digits; the slide alone would need 60·3/47 = 3.8 rpm, lower.
        let s = spiral(20.0, 256, 4.0, 0.05, two_tones);
        let slow_slide = SplitLimits {
            slide_bandwidth_hz: 3.0,
            ..limits()
        };
        let out = split(&s, &SplitSpec::Auto, 60.0, Some(&slow_slide)).unwrap();
        assert_adds_up(&s, &out);
        let k_star = out.cutoff_hz.unwrap();
        let Verdict::Infeasible {
            conflicts,
            feasible_spindle_rpm: Some(rpm),
            ..
        } = &out.verdict
        else {
            panic!("{:?}", out.verdict)
        };
        assert_eq!(conflicts.len(), 1, "{conflicts:?}");
        assert_eq!(conflicts[0].limit, Limit::SlideBandwidthHz);
        assert_eq!((conflicts[0].value, conflicts[0].allowed), (k_star, 3.0));
        let by_hand = 60.0 * 3.0 / k_star;
        assert!(
            *rpm <= by_hand && *rpm > by_hand * (1.0 - 1e-2),
            "{rpm} vs {by_hand}"
        );
        // At that speed the same geometry passes.
        let again = split(&s, &SplitSpec::Auto, *rpm, Some(&slow_slide)).unwrap();
        assert!(
            matches!(
                again.verdict,
                Verdict::Feasible {
                    slide_alone: false,
                    ..
                }
            ),
            "{:?}",
            again.verdict
        );
        assert!((again.cutoff_hz.unwrap() * 60.0 / rpm - k_star).abs() < 1e-9 * k_star);
        // A stroke smaller than the 47 cycles/rev tone's PV (40 µm) pushes the cutoff above
        // 47 cycles/rev (both tones on the slide): 60·3/k* is now below the slide alone's
        // 60·3/47 rpm (its bandwidth figure, within the spectrum's reach of 3.5 bins), which
        // is the speed offered.
        let short = SplitLimits {
            fts_stroke_mm: 0.01,
            ..slow_slide
        };
        let out = split(&s, &SplitSpec::Auto, 60.0, Some(&short)).unwrap();
        let k = out.cutoff_hz.unwrap();
        let Verdict::Infeasible {
            feasible_spindle_rpm: Some(slower),
            ..
        } = out.verdict
        else {
            panic!("{:?}", out.verdict)
        };
        assert!(
            k > 47.0 && 180.0 / k < slower && slower < *rpm,
            "{k} {slower}"
        );
        let alone = 180.0 / 47.0;
        assert!(
            (slower - alone).abs() < alone * 3.5 / 20.0 / 47.0 + 0.01,
            "{slower}"
        );
    }
}
