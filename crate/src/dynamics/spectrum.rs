//! Frequency analysis of the path along the spiral at a spindle speed (paper 000, "Hybrid
//! Hilbert transform/fast Fourier transform methodology for geometry splitting" and Figure 13):
//! the amplitude spectrum of z(t) by the FFT and the instantaneous frequency by the Hilbert
//! transform, per radius band.
//!
//! **What is analysed.** The raw z is dominated by the rotationally symmetric sag, a trend over
//! hundreds of revolutions whose content lies below one cycle per revolution and whose leakage
//! would hide everything else. Paper 000 analyses the increments dZ, which removes the trend but
//! weights every frequency by `2·sin(πf/f_s)` so that amplitudes are no longer heights. Here the
//! analysed signal is the non-symmetric residual `r = z − S` on the uniform angle grid
//! ([`crate::dynamics::path_signal`]: S the two-revolution triangle mean, which removes whole
//! harmonics exactly): the part of the path that the rotationally symmetric split (paper 002) would
//! leave to the FTS, in µm, with every frequency at its own amplitude. The symmetric part is
//! treated as DC.
//!
//! **Spectrum.** A Hann window over the whole record (sidelobes −31 dB, falling 18 dB per octave,
//! so the residual's remaining slow drift stays near 0 Hz), amplitude `2·|X_j|/Σw` (the amplitude
//! of a sine centred on a bin). Between bins the raw spectrum reads low by up to 15 % (Hann
//! scalloping, `sinc δ/(1 − δ²)` at offset δ = ½ bin); listed peaks are corrected with the exact
//! Hann three-bin relations: for a tone at bin k + δ the neighbours stand in the ratios `(1 − δ)/(2
//! + δ)` and `(1 + δ)/(2 − δ)` to bin k, which give `δ = 2(X₊ − X₋)/(X₋ + 2X₀ + X₊)` and the
//! amplitude `X₀·(1 − δ²)/sinc δ` (exact up to the tone's own image at −f, a relative 1/(2k)³ for a
//! tone k bins from 0). The record of N samples is padded with zeros to a [`fast_length`] L (at
//! most 1/8 longer: a length with a large prime factor would go through Bluestein's algorithm,
//! whose plan alone held 134 bytes a sample), so the spectrum is sampled every q = N/L of the
//! record's bins; the same response `W(d) = sinc d/(1 − d²)` then gives δ as the root of
//! `(W(δ − q) − W(δ + q))/(W(δ + q) + 2W(δ) + W(δ − q)) = (X₊ − X₋)/(X₋ + 2X₀ + X₊)` (rising in δ,
//! found by bisection; the closed form at q = 1) and the amplitude `X₀/W(δ)`. The peak is then
//! divided by the gain of the residual at that frequency
//! ([`crate::dynamics::path_signal::residual_gain`]; 1 at whole cycles per revolution, left out
//! below a gain of ½). Bin j of the padded record lies at `j·M/L` cycles per revolution (M samples
//! per revolution), `j·M/L·n/60` Hz: frequencies scale with the spindle speed, amplitudes do not.
//!
//! **Instantaneous frequency.** The analytic signal `r + i·H{r}`, the Hilbert transform H by
//! the FFT (the spectrum turned by −90° at positive frequencies and +90° at negative ones, its 0
//! and Nyquist bins removed: the analytic signal's spectrum is then the positive frequencies
//! doubled, the negative ones removed). A record cut off at its ends has a Hilbert
//! transform that errs like 1/d at d periods from the cut, over the whole record (1e-3 in the
//! middle of 30 revolutions of a tone with a mirror-image extension); so the first and last
//! revolution are rolled off by a raised cosine and the record is padded with at least
//! [`PAD_TAPERS`] as many zeros (two revolutions), to a length `2^a·3^b` ([`fast_length`]; the
//! FFT then joins the rim to the centre only through the zeros), and those two revolutions are
//! left out of the band figures (on records of three revolutions or more; shorter ones, not
//! rolled off, are padded with as many zeros as they have samples). Padding every record so,
//! as this module once did, left a tone's band medians where they were to 3.5e-8 (the roll-off's
//! own effect) and moved the 1 M-point sine grid's band figures by at most 8e-6 relative, at
//! twice the transform's memory, the dynamics' peak. The frequency between samples j
//! and j+1 is `arg(a_{j+1}·ā_j)/2π` cycles per sample (no phase unwrapping), weighted by the
//! envelope |a|. Per radius band the figure is the envelope-weighted median and 95th
//! percentile: where the signal is not narrow-band (a frequency crossing zero, two components
//! of equal size) the Hilbert frequency is meaningless for a short while and its envelope dips,
//! so weighted order statistics ignore it. A sine grid cut along a circle of radius ρ has the
//! instantaneous frequency `(2πρ/λ)·|sin θ|` cycles/rev: its median over a revolution is
//! `sin(π/4)·2πρ/λ`, its 95th percentile `sin(0.95·π/2)·2πρ/λ`.
//!
//! **Stretches.** The record is not the whole path: consecutive radius bands are taken together
//! until their points span [`MIN_STRETCH_REVS`] revolutions (the whole path where it is
//! shorter), and each such stretch, with a revolution more on either side for the roll-off, is
//! resampled at its own densest turn's rate ([`PathSignal::stretch`]) and analysed alone, on
//! the next free core. A constant-arc or HCAA path has its inner turns sampled at their own
//! rate, not at the rim's (about half the samples over the path, and records of a stretch's
//! length, not the path's: the dynamics' memory). A stretch's roll-off lies a revolution
//! outside its bands, as the whole record's does at its ends: a tone's figures stay within
//! 1e-9 (medians) and 1e-6 (95th percentiles) of its frequency, and a sine grid's within 5e-3
//! of the whole record's (`each_bands_stretch_gives_the_whole_records_figures`).
//!
//! **Transforms.** Every record here is real, so every transform is a real-input one
//! ([`crate::dynamics::real_transform`]: a record of even length L goes through a complex
//! transform of L/2 and one pass of twiddles), which keeps bins 0 … L/2 only, the others being
//! their conjugates: half the work of a complex transform. A long record (from
//! [`crate::dynamics::real_transform::IN_PLACE_FROM`] samples) is transformed in its own memory,
//! 8 bytes a sample, with tables of about √L entries; a short one by `realfft` (16 bytes a sample
//! with its output, and a plan of 12 whose making costs about as much as running it: records of
//! one length share a plan ([`amplitude_spectrum_and_bands_on`]) and, in the spectrum and
//! the bandwidth figures, a plan is made on a second core while its record is prepared; the
//! plans are deterministic, so the results are the same to the bit). A channel's bandwidth
//! figure on a long grid is taken in single precision, 4 bytes a sample
//! ([`highest_significant_cycles_per_rev_at`]): it reads where the amplitudes cross 1 % of the
//! largest, which f32's rounding (a few millionths of the largest) does not move but for a bin
//! that close to the threshold, and its residual is taken in double precision before it is
//! rounded, so the sag's millimetres do not swamp the micrometres analysed.

use crate::dynamics::path_signal::{
    BLOCK_SAMPLES, PathSignal, Stretch, UniformSignal, hz, residual_gain,
};
use crate::dynamics::real_transform::{
    self, RealForward, RealInverse, Twiddles, in_place, real_values_of,
};
use crate::parallel::{both, fill_chunks, fill_each, map_parts};
use rustfft::FftDirection;
use rustfft::num_complex::Complex;
use serde::Serialize;
use std::convert::Infallible;
use std::f64::consts::{PI, TAU};
use std::ops::Range;

/// The most peaks listed.
pub const MAX_PEAKS: usize = 8;

/// A peak is listed, and a frequency counts in [`highest_significant_cycles_per_rev`], when its
/// amplitude reaches this fraction of the largest in the spectrum (Hann's first sidelobe is
/// 2.7 %, but only within 3.5 bins of its peak).
pub const SIGNIFICANT_FRACTION: f64 = 0.01;

/// Zeros after the record of the Hilbert transform, in roll-off lengths (module docs).
pub const PAD_TAPERS: usize = 2;

/// Amplitudes below this, mm, are rounding (1 pm).
const NEGLIGIBLE_MM: f64 = 1e-9;

/// The amplitude spectrum of the non-symmetric part of the path at a spindle speed.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct Spectrum {
    /// Spindle speed, rev/min.
    pub spindle_rpm: f64,
    /// Bin spacing before decimation, Hz.
    pub resolution_hz: f64,
    /// Frequencies, Hz, ascending (each the frequency of the largest bin of its group when
    /// decimated).
    pub freq_hz: Vec<f64>,
    /// Amplitudes, µm (the largest of each group when decimated, so peaks survive).
    pub amplitude_um: Vec<f64>,
    /// The largest peaks, largest first, at most [`MAX_PEAKS`], corrected between bins.
    pub peaks: Vec<Peak>,
}

/// A peak of the spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Peak {
    /// Frequency, Hz.
    pub freq_hz: f64,
    /// The same in cycles per revolution (independent of the speed).
    pub cycles_per_rev: f64,
    /// Amplitude, µm.
    pub amplitude_um: f64,
}

/// The instantaneous frequency in one radius band.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BandFrequency {
    /// Outer radius of the band, mm.
    pub rho_outer_mm: f64,
    /// Inner radius of the band, mm.
    pub rho_inner_mm: f64,
    /// Envelope-weighted median of the instantaneous frequency, Hz.
    pub median_hz: f64,
    /// Envelope-weighted 95th percentile, Hz.
    pub p95_hz: f64,
    /// Median envelope (local amplitude), µm.
    pub amplitude_um: f64,
}

/// The Hann amplitude spectrum of `x` (N samples) padded with zeros to `len ≥ N` samples,
/// bins 0 … len/2 (bin j at j/len cycles per sample), in the unit of `x`. A longer `len` samples
/// the same spectrum more finely (every N/len of the record's bins). `x` is let go before the
/// transform.
pub fn hann_amplitudes(x: Vec<f64>, len: usize) -> Vec<f64> {
    if x.len() < 2 {
        return Vec::new();
    }
    let len = len.max(x.len());
    hann_amplitudes_by(&forward_plan(len), x)
}

/// [`hann_amplitudes`] padded to the length of the transform `forward` (at least `x`'s).
fn hann_amplitudes_by(forward: &RealForward, mut x: Vec<f64>) -> Vec<f64> {
    let n = x.len();
    if n < 2 {
        return Vec::new();
    }
    let gain = apply_hann(&mut x);
    real_values_of(forward.spectrum(x), |j, c| {
        modulus(c) * if j == 0 { 1.0 } else { 2.0 } / gain
    })
}

/// |c| as `√(re² + im²)`, within an ulp or two of `Complex::norm`, whose `hypot` guards
/// against squares that overflow or underflow at several times the cost: the bins here are
/// sums of at most 2³² heights in mm, whose squares overflow only past 10¹⁴⁴ mm and underflow
/// only below 10⁻¹⁵⁴ mm (read as 0 either way). The spectrum takes them one bin after another
/// on one core (0.3 s of `hypot` on the 28.4 M-point HCAA job under perf).
fn modulus(c: Complex<f64>) -> f64 {
    (c.re * c.re + c.im * c.im).sqrt()
}

/// The Hann window applied to `x` in place, on the cores, and its sum (its gain), added up in
/// order beside them.
fn apply_hann(x: &mut [f64]) -> f64 {
    let n = x.len();
    let window = Hann::new(n);
    let (gain, Ok(())) = both(
        || window.from(0).take(n).fold(0.0, |gain, w| gain + w),
        || {
            fill_chunks(x, |first, part| {
                for (v, w) in part.iter_mut().zip(window.from(first)) {
                    *v *= w;
                }
                Ok::<(), Infallible>(())
            })
        },
    );
    gain
}

/// The Hann window of `n` samples, `0.5 − 0.5·cos(2πj/n)`, a sample after another: its cosines
/// are the real parts of the powers of `e^{2πi/n}` from two tables of about √n entries
/// ([`Twiddles`]), a complex product a sample instead of a cosine: within 10⁻¹⁵ of libm's
/// `0.5 − 0.5·cos(2πj/n)` (`the_hann_window_is_its_cosines`; the rounding of that cosine's own
/// argument is as large).
struct Hann(Twiddles<f64>);

impl Hann {
    fn new(n: usize) -> Self {
        Self(Twiddles::new(n, n, FftDirection::Forward))
    }

    /// The window at samples `first`, `first + 1`, … (below n).
    fn from(&self, first: usize) -> impl Iterator<Item = f64> + '_ {
        self.0.from(first).map(|w| 0.5 - 0.5 * w.re)
    }
}

/// The forward real-input transform of `len` samples ([`RealForward`]: in place for long
/// records). Making `realfft`'s plan for a short record costs about as much as running it (its
/// twiddle factors, a sine and cosine each), so the callers here make it on a second core while
/// they prepare the record ([`both`]), and share it between records of one length; a transform
/// in place makes its tables (about √L entries) at once.
pub(crate) fn forward_plan(len: usize) -> RealForward {
    RealForward::new(len)
}

/// The inverse real-input transform of `len` samples (made as [`forward_plan`]).
pub(crate) fn inverse_plan(len: usize) -> RealInverse {
    RealInverse::new(len)
}

/// The non-symmetric residual of `values` (one a sample of `grid`), computed in their place.
fn residual_of(grid: &UniformSignal, mut values: Vec<f64>) -> Vec<f64> {
    grid.subtract_symmetric_part(&mut values);
    values
}

/// Peaks of an amplitude spectrum sampled every `q` of the record's bins (q ≤ 1: a record
/// padded with zeros): local maxima over ±2 samples (Hann's main lobe), at least
/// [`SIGNIFICANT_FRACTION`] of the largest, refined between samples; (sample + δ, amplitude).
fn peaks(a: &[f64], q: f64) -> Vec<(f64, f64)> {
    let top = a.iter().copied().fold(0.0, f64::max);
    let floor = significant_floor(top);
    let mut found: Vec<(f64, f64)> = (1..a.len().saturating_sub(1))
        .filter(|&j| {
            a[j] >= floor
                && (j.saturating_sub(2)..=(j + 2).min(a.len() - 1))
                    .all(|i| i == j || a[i] < a[j] || (a[i] == a[j] && i > j))
        })
        .map(|j| refine(a[j - 1], a[j], a[j + 1], j, q))
        .collect();
    found.sort_by(|p, q| q.1.total_cmp(&p.1));
    found.truncate(MAX_PEAKS);
    found
}

/// The Hann window's amplitude response `sinc d/(1 − d²)` at `d` of the record's bins from a
/// tone (1 at the tone, ½ one bin away), for |d| < 2.
fn hann_response(d: f64) -> f64 {
    let d = d.abs();
    if d == 0.0 {
        1.0
    } else if d < 0.5 {
        (PI * d).sin() / (PI * d * (1.0 - d * d))
    } else {
        // sin πd = sin π(1 − d): no 0/0 at d = 1.
        let e = 1.0 - d;
        if e == 0.0 {
            0.5
        } else {
            (PI * e).sin() / (PI * e * d * (1.0 + d))
        }
    }
}

/// The Hann three-sample estimate of a tone's position and amplitude from the samples `below`,
/// `at` and `above` at sample `j` of a spectrum sampled every `q` of the record's bins (module
/// docs): the tone's offset δ from `at`, in the record's bins, is where the three responses
/// stand in the samples' ratio `(X₊ − X₋)/(X₋ + 2X₀ + X₊)` (a function rising with δ over
/// ±q/2, found by bisection; `2δ` itself when q = 1); the amplitude is `X₀` over the response
/// at δ. Returns (j + δ/q, amplitude).
fn refine(below: f64, at: f64, above: f64, j: usize, q: f64) -> (f64, f64) {
    let ratio = (above - below) / (below + 2.0 * at + above);
    let of = |d: f64| {
        let (b, c, a) = (hann_response(d + q), hann_response(d), hann_response(d - q));
        (a - b) / (b + 2.0 * c + a)
    };
    let (mut lo, mut hi) = (-0.5 * q, 0.5 * q);
    let d = if ratio <= of(lo) {
        lo
    } else if ratio >= of(hi) {
        hi
    } else {
        while hi - lo > 1e-15 {
            let mid = 0.5 * (lo + hi);
            if of(mid) < ratio { lo = mid } else { hi = mid }
        }
        0.5 * (lo + hi)
    };
    (j as f64 + d / q, at / hann_response(d))
}

/// The amplitude spectrum of the path's non-symmetric part at `spindle_rpm`, decimated to at
/// most `max_bins` bins for display (each group keeps its largest bin); empty when the path
/// cannot be analysed ([`PathSignal::check`]) or the speed is not a positive number.
pub fn amplitude_spectrum(signal: &PathSignal, spindle_rpm: f64, max_bins: usize) -> Spectrum {
    signal.uniform().map_or_else(
        |_| Spectrum::default(),
        |grid| amplitude_spectrum_on(&grid, spindle_rpm, max_bins),
    )
}

/// [`amplitude_spectrum`] of a signal's uniform grid ([`PathSignal::uniform`]).
pub fn amplitude_spectrum_on(grid: &UniformSignal, spindle_rpm: f64, max_bins: usize) -> Spectrum {
    amplitude_spectrum_and_band_on(grid, spindle_rpm, max_bins).0
}

/// [`amplitude_spectrum_on`], and the highest significant frequency of the grid's heights,
/// cycles per revolution, read off the same amplitudes: what
/// [`highest_significant_cycles_per_rev`] of `grid.z_mm` gives, to the bit, without its
/// transform (`None` where the speed is not a positive number).
pub fn amplitude_spectrum_and_band_on(
    grid: &UniformSignal,
    spindle_rpm: f64,
    max_bins: usize,
) -> (Spectrum, Option<f64>) {
    amplitude_spectrum_of(grid, grid.z_mm.clone(), spindle_rpm, max_bins)
}

/// [`amplitude_spectrum_and_band_on`] of the grid's heights `heights` (as `grid.z_mm`), handed
/// over: the transform takes their memory.
fn amplitude_spectrum_of(
    grid: &UniformSignal,
    heights: Vec<f64>,
    spindle_rpm: f64,
    max_bins: usize,
) -> (Spectrum, Option<f64>) {
    if !positive_speed(spindle_rpm) {
        return (Spectrum::default(), None);
    }
    let len = fast_length(grid.len(), false);
    let (r, forward) = both(|| residual_of(grid, heights), || forward_plan(len));
    let a = hann_amplitudes_by(&forward, r);
    drop(forward);
    spectrum_of(grid, &a, len, spindle_rpm, max_bins)
}

/// [`amplitude_spectrum_and_band_on`] of the grid's heights `heights` (as `grid.z_mm`), and
/// [`highest_significant_cycles_per_rev_at`] of `value(i)` at the points of `signal` (the path
/// the grid was made from), each to the bit. Short records are made one after the other and
/// transformed on two cores by one transform of their common length, made on a second core
/// while the heights' residual is taken. A long record (transformed in place,
/// [`crate::dynamics::real_transform::IN_PLACE_FROM`] samples or more) is taken one at a time:
/// the heights' spectrum first, then the values' figure in single precision once the heights'
/// record is let go (the dynamics' peak holds one record of the grid, not two).
pub fn amplitude_spectrum_and_bands_on(
    signal: &PathSignal,
    grid: &UniformSignal,
    heights: Vec<f64>,
    value: impl Fn(usize) -> f64 + Sync,
    spindle_rpm: f64,
    max_bins: usize,
) -> (Spectrum, Option<f64>, f64) {
    let len = fast_length(grid.len(), false);
    if in_place(len) || heights.len() != grid.len() {
        let (spectrum, band) = amplitude_spectrum_of(grid, heights, spindle_rpm, max_bins);
        let values_band = highest_significant_cycles_per_rev_at(signal, grid, value);
        return (spectrum, band, values_band);
    }
    let per_rev = grid.samples_per_rev;
    let values = signal.values_at_by(per_rev, value);
    if values.len() != grid.len() {
        let (spectrum, band) = amplitude_spectrum_of(grid, heights, spindle_rpm, max_bins);
        return (
            spectrum,
            band,
            highest_significant_cycles_per_rev(grid, values),
        );
    }
    let heights_residual =
        |heights| positive_speed(spindle_rpm).then(|| residual_of(grid, heights));
    let ((heights, values), forward) = both(
        || (heights_residual(heights), residual_of(grid, values)),
        || forward_plan(len),
    );
    let ((spectrum, band), values_band) = both(
        || match heights {
            Some(r) => spectrum_of(
                grid,
                &hann_amplitudes_by(&forward, r),
                len,
                spindle_rpm,
                max_bins,
            ),
            None => (Spectrum::default(), None),
        },
        || highest_significant_of(&hann_amplitudes_by(&forward, values), per_rev, len),
    );
    (spectrum, band, values_band)
}

/// The spectrum of the Hann amplitudes `a` of the heights' residual on `grid` padded to `len`
/// samples, decimated to `max_bins`, and the heights' highest significant frequency.
fn spectrum_of(
    grid: &UniformSignal,
    a: &[f64],
    len: usize,
    spindle_rpm: f64,
    max_bins: usize,
) -> (Spectrum, Option<f64>) {
    let (samples, per_rev) = (grid.len(), grid.samples_per_rev);
    let band = highest_significant_of(a, per_rev, len);
    let cpr_per_bin = per_rev as f64 / len as f64;
    let to_hz = |bin: f64| hz(bin * cpr_per_bin, spindle_rpm);
    let group = a.len().div_ceil(max_bins.max(1)).max(1);
    let (mut freq_hz, mut amplitude_um) = (Vec::new(), Vec::new());
    if max_bins > 0 {
        for (g, chunk) in a.chunks(group).enumerate() {
            let (k, v) = chunk
                .iter()
                .enumerate()
                .fold(
                    (0, f64::MIN),
                    |best, (k, &v)| if v > best.1 { (k, v) } else { best },
                );
            freq_hz.push(to_hz((g * group + k) as f64));
            amplitude_um.push(v * 1e3);
        }
    }
    let spectrum = Spectrum {
        spindle_rpm,
        resolution_hz: to_hz(1.0),
        freq_hz,
        amplitude_um,
        peaks: peaks(a, samples as f64 / len as f64)
            .into_iter()
            .map(|(bin, amp)| {
                let gain = residual_gain(bin * cpr_per_bin, per_rev);
                Peak {
                    freq_hz: to_hz(bin),
                    cycles_per_rev: bin * cpr_per_bin,
                    amplitude_um: amp * 1e3 / if gain >= 0.5 { gain } else { 1.0 },
                }
            })
            .collect(),
    };
    (spectrum, Some(band))
}

/// The highest frequency, cycles per revolution, at which the Hann spectrum of the
/// non-symmetric part of `values` (one per grid sample) reaches [`SIGNIFICANT_FRACTION`] of its
/// largest amplitude (and 1 pm); 0 when there is none. The bandwidth figure of a channel. The
/// record is padded to a [`fast_length`] (at most 1/8 longer, so the spectrum is sampled a
/// little more finely than its bins, and the transform is not Bluestein's). `values` are
/// handed over: the transform takes their memory. Its plan is made after their residual, so
/// the two are never held together ([`highest_significant_cycles_per_rev_beside`] makes it on
/// a second core while the values are made, where the dynamics have the memory to spare).
pub fn highest_significant_cycles_per_rev(grid: &UniformSignal, values: Vec<f64>) -> f64 {
    let len = fast_length(values.len(), false);
    let a = hann_amplitudes(residual_of(grid, values), len);
    highest_significant_of(&a, grid.samples_per_rev, len)
}

/// [`highest_significant_cycles_per_rev`] of the values `make` gives, one a grid sample
/// (`samples` of them expected), to the bit: they are made and their residual taken while the
/// transform is made on a second core. For a channel's figure where the dynamics hold less than
/// at their peak: the transform's plan (12 bytes a sample) is held beside the making.
pub fn highest_significant_cycles_per_rev_beside(
    grid: &UniformSignal,
    samples: usize,
    make: impl FnOnce() -> Vec<f64>,
) -> f64 {
    let (r, forward) = both(
        || residual_of(grid, make()),
        || forward_plan(fast_length(samples, false)),
    );
    let len = fast_length(r.len(), false);
    let a = if forward.len() == len {
        hann_amplitudes_by(&forward, r)
    } else {
        drop(forward);
        hann_amplitudes(r, len)
    };
    highest_significant_of(&a, grid.samples_per_rev, len)
}

/// [`highest_significant_cycles_per_rev`] of the Hann amplitudes `a` of a record of
/// `samples_per_rev` padded to `len`.
fn highest_significant_of(a: &[f64], samples_per_rev: usize, len: usize) -> f64 {
    let top = a.iter().copied().fold(0.0, f64::max);
    let floor = significant_floor(top);
    a.iter()
        .rposition(|&v| v >= floor)
        .map_or(0.0, |j| j as f64 * samples_per_rev as f64 / len as f64)
}

/// [`highest_significant_cycles_per_rev`] of `value(i)` at the points of `signal` resampled on
/// its `grid` ([`PathSignal::values_at`]'s samples): a channel's bandwidth figure. A grid whose
/// transform runs in place (from [`real_transform::IN_PLACE_FROM`] samples) is held in single
/// precision, 4 bytes a sample: its residual made a block at a time
/// ([`UniformSignal::narrow_residual`], [`BLOCK_SAMPLES`]) and transformed in its memory by the
/// transform of [`real_transform`] in f32. Its amplitudes are those
/// of double precision within a few millionths of the largest, so the figure is the same
/// unless a bin's amplitude lies that close to [`SIGNIFICANT_FRACTION`] of the largest
/// (`a_long_grids_figure_in_single_precision_is_the_double_ones`). A shorter grid's figure is
/// [`highest_significant_cycles_per_rev_beside`]'s, to the bit.
pub fn highest_significant_cycles_per_rev_at(
    signal: &PathSignal,
    grid: &UniformSignal,
    value: impl Fn(usize) -> f64 + Sync,
) -> f64 {
    let (n, m) = (grid.len(), grid.samples_per_rev);
    let fill = |first: usize, block: &mut [f64]| {
        signal.resample_with(&value, m, first, block, |slot, v| *slot = v);
    };
    if !in_place(fast_length(n, false)) || signal.len() < 2 {
        return highest_significant_cycles_per_rev_beside(grid, n, || {
            signal.values_at_by(m, &value)
        });
    }
    let len = fast_length(n, true);
    let mut residual = grid.narrow_residual(n, BLOCK_SAMPLES, fill);
    let window = Hann::new(n);
    let Ok(()) = fill_chunks(&mut residual, |first, part| {
        for (v, w) in part.iter_mut().zip(window.from(first)) {
            *v = (f64::from(*v) * w) as f32;
        }
        Ok::<(), Infallible>(())
    });
    let bins = real_transform::narrow_spectrum(residual, len);
    // Squared amplitudes, in units of the window's gain (n/2 exactly: its cosines sum to 0).
    let squared = |j: usize| {
        let (re, im) = (f64::from(bins[j].re), f64::from(bins[j].im));
        (re * re + im * im) * if j == 0 { 1.0 } else { 4.0 }
    };
    let gain = n as f64 / 2.0;
    let top = (0..bins.len()).map(squared).fold(0.0, f64::max).sqrt() / gain;
    let floor = significant_floor(top) * gain;
    (0..bins.len())
        .rev()
        .find(|&j| squared(j) >= floor * floor)
        .map_or(0.0, |j| j as f64 * m as f64 / len as f64)
}

/// The smallest amplitude that counts beside the largest, `top`: [`SIGNIFICANT_FRACTION`] of
/// it, and 1 pm.
fn significant_floor(top: f64) -> f64 {
    (SIGNIFICANT_FRACTION * top).max(NEGLIGIBLE_MM)
}

/// The smallest length `2^a·3^b ≥ n` (even when `even`): rustfft transforms such lengths by
/// its radix-2/3 kernels; a length with a large prime factor (a path of 1 000 001 points has
/// 9 901) goes through Bluestein's algorithm, about five times slower and with scratch and
/// twiddles of four times the length. Consecutive such lengths differ by at most 1/8 above
/// 2¹⁰, so the padding costs little.
pub fn fast_length(n: usize, even: bool) -> usize {
    let least = if even { 2 } else { 1 };
    let mut best = usize::MAX;
    let mut three = 1usize;
    loop {
        best = best.min(three * n.div_ceil(three).next_power_of_two().max(least));
        if three >= n {
            return best;
        }
        three *= 3;
    }
}

/// The analytic signal of `x`, `x + i·H{x}` as its real and imaginary parts, with H the
/// Hilbert transform by the FFT (the
/// spectrum of `x` turned by −90° at positive frequencies, +90° at negative ones, its 0 and
/// Nyquist bins removed; by real-input transforms), the first and last `taper` samples rolled off
/// by a raised cosine and the record padded with [`PAD_TAPERS`] times as many zeros or more
/// (with as many as it has samples if `taper` is 0), to a [`fast_length`] (module docs).
pub fn analytic_signal(mut x: Vec<f64>, taper: usize) -> (Vec<f64>, Vec<f64>) {
    let forward = forward_plan(analytic_length(x.len(), taper));
    roll_off(&mut x, taper);
    let hilbert = hilbert_by(forward, x.clone());
    (x, hilbert)
}

/// The length of the transforms of [`analytic_signal`] for `n` samples rolled off over `taper`.
fn analytic_length(n: usize, taper: usize) -> usize {
    let taper = taper.min(n / 2);
    if taper > 0 {
        fast_length(n + PAD_TAPERS * taper, true)
    } else {
        fast_length(2 * n, true)
    }
}

/// The first and last `taper` samples of `x` rolled off by a raised cosine, in place.
fn roll_off(x: &mut [f64], taper: usize) {
    let n = x.len();
    let taper = taper.min(n / 2);
    for (j, v) in x.iter_mut().enumerate() {
        let d = j.min(n - 1 - j);
        if d < taper {
            *v *= 0.5 - 0.5 * (std::f64::consts::PI * (d as f64 + 0.5) / taper as f64).cos();
        }
    }
}

/// The Hilbert transform of the rolled-off record `rolled` by the transform `forward` of its
/// padded length ([`analytic_length`]), in the record's memory; `forward` is let go before the
/// inverse transform is made.
fn hilbert_by(forward: RealForward, rolled: Vec<f64>) -> Vec<f64> {
    let (n, len) = (rolled.len(), forward.len());
    let mut bins = forward.spectrum(rolled);
    drop(forward);
    let half = len / 2;
    for (j, c) in bins.iter_mut().enumerate() {
        *c = if j == 0 || j == half {
            Complex::new(0.0, 0.0)
        } else {
            Complex::new(c.im, -c.re) / len as f64
        };
    }
    let mut hilbert = inverse_plan(len).record(bins);
    hilbert.truncate(n);
    hilbert
}

/// The instantaneous frequency of the path's non-symmetric part at `spindle_rpm` in `bands`
/// equal radius bands from the outer radius to the centre (at most 65 536; bands without
/// points are left out), each band on its own stretch of the path (module docs); empty when
/// the path cannot be analysed or the speed is not a positive number.
pub fn instantaneous_frequency(
    signal: &PathSignal,
    spindle_rpm: f64,
    bands: usize,
) -> Vec<BandFrequency> {
    match signal.check() {
        Ok(()) => instantaneous_frequency_of(signal, spindle_rpm, bands),
        Err(_) => Vec::new(),
    }
}

/// The least angle a stretch of [`instantaneous_frequency`] spans between its margins,
/// revolutions: consecutive bands are taken together up to it.
pub const MIN_STRETCH_REVS: f64 = 8.0;

/// [`instantaneous_frequency`] of a path already checked ([`PathSignal::check`]). The bands are
/// gathered into stretches of at least [`MIN_STRETCH_REVS`] (the whole path where it is
/// shorter), analysed on the next free core each, at its own rate.
pub(crate) fn instantaneous_frequency_of(
    signal: &PathSignal,
    spindle_rpm: f64,
    bands: usize,
) -> Vec<BandFrequency> {
    let bands = RadiusBands::of(signal, bands);
    if !positive_speed(spindle_rpm) || bands.count == 0 || signal.len() < 2 {
        return Vec::new();
    }
    let stretches = bands.stretches(signal);
    let figures = |k: usize| {
        let (ref members, from, to) = stretches[k];
        Ok::<_, Infallible>(stretch_frequencies(
            signal,
            signal.stretch(from, to),
            &bands,
            members,
            spindle_rpm,
        ))
    };
    let mut out = vec![Vec::new(); stretches.len()];
    let Ok(()) = fill_each(&mut out, figures);
    out.into_iter().flatten().collect()
}

/// Equal radius bands from the path's outer radius (its points' largest) to the centre.
struct RadiusBands {
    count: usize,
    rho_max: f64,
    width: f64,
}

impl RadiusBands {
    fn of(signal: &PathSignal, count: usize) -> Self {
        let largest = |points: Range<usize>| points.map(|i| signal.rho(i)).fold(0.0, f64::max);
        let rho_max = map_parts(signal.len(), largest)
            .into_iter()
            .fold(0.0, f64::max);
        let count = count.min(1 << 16);
        let width = if count > 0 {
            rho_max / count as f64
        } else {
            0.0
        };
        Self {
            count,
            rho_max,
            width,
        }
    }

    /// The band of radius `rho`.
    fn of_radius(&self, rho: f64) -> usize {
        if self.width > 0.0 {
            (((self.rho_max - rho) / self.width).floor().max(0.0) as usize).min(self.count - 1)
        } else {
            0
        }
    }

    /// The bands met, gathered in stretches of consecutive bands: each stretch's bands and
    /// the angles of the points before its first point and after its last (whatever their
    /// band), widened by a revolution either side for the roll-off.
    fn stretches(&self, signal: &PathSignal) -> Vec<(Vec<usize>, f64, f64)> {
        let n = signal.len();
        // Each band's first and last point, over parts of the path on the cores.
        let reach_in = |points: Range<usize>| {
            let mut reach = vec![(usize::MAX, 0); self.count];
            for i in points {
                let r = &mut reach[self.of_radius(signal.rho(i))];
                *r = (r.0.min(i), i);
            }
            reach
        };
        let mut reach = vec![(usize::MAX, 0); self.count];
        for part in map_parts(n, reach_in) {
            for (r, p) in reach.iter_mut().zip(part) {
                *r = (r.0.min(p.0), r.1.max(p.1));
            }
        }
        let angle = |i: usize| signal.angle(i.min(n - 1));
        // A stretch's bands and its first and last point.
        type Gathered = (Vec<usize>, usize, usize);
        let short = |s: &Gathered| angle(s.2) - angle(s.1) < MIN_STRETCH_REVS * TAU;
        let join = |s: &mut Gathered, members: &[usize], lo: usize, hi: usize| {
            s.0.extend_from_slice(members);
            (s.1, s.2) = (s.1.min(lo), s.2.max(hi));
        };
        let mut out: Vec<Gathered> = Vec::new();
        for (b, (first, last)) in reach.into_iter().enumerate() {
            if first == usize::MAX {
                continue;
            }
            let (first, last) = (first.saturating_sub(1), last + 1);
            match out.last_mut() {
                Some(s) if short(s) => join(s, &[b], first, last),
                _ => out.push((vec![b], first, last)),
            }
        }
        // A short last stretch joins the one before.
        if out.len() >= 2 && out.last().is_some_and(short) {
            let (members, lo, hi) = out.pop().expect("two stretches");
            join(out.last_mut().expect("one left"), &members, lo, hi);
        }
        out.into_iter()
            .map(|(members, lo, hi)| (members, angle(lo) - TAU, angle(hi) + TAU))
            .collect()
    }
}

/// The figures of the bands `members` on `stretch` of the path: its residual on the stretch's
/// grid, the first and last revolution rolled off (on a stretch of three revolutions or more),
/// its analytic signal, and each band's pairs of samples between the roll-offs (a pair's band
/// by the radius midway).
fn stretch_frequencies(
    signal: &PathSignal,
    stretch: Stretch,
    bands: &RadiusBands,
    members: &[usize],
    spindle_rpm: f64,
) -> Vec<BandFrequency> {
    let (grid, m) = (stretch.grid(), stretch.samples_per_rev);
    let skip = if stretch.len >= 3 * m { m } else { 0 };
    // Each pair's band (2 bytes a pair), read off the radii before the records are made.
    let radii = signal.stretch_values(&stretch, |i| signal.rho(i));
    let band: Vec<u16> = (radii.windows(2))
        .map(|r| bands.of_radius(0.5 * (r[0] + r[1])) as u16)
        .collect();
    drop(radii);
    let band_of = |j: usize| band[j] as usize;
    let mut re = residual_of(&grid, signal.stretch_values(&stretch, |i| signal.z_mm[i]));
    roll_off(&mut re, skip);
    let im = hilbert_by(forward_plan(analytic_length(re.len(), skip)), re.clone());
    // Each band's first and last pair between the roll-offs.
    let mut reach = vec![(usize::MAX, 0); bands.count];
    for j in skip..re.len().saturating_sub(1 + skip) {
        let r = &mut reach[band_of(j)];
        *r = (r.0.min(j), j);
    }
    // (frequency Hz, envelope) of pair j, the envelope from the two samples' moduli `near`
    // and that of sample j + 1.
    let frequency = |j: usize, near: f64| {
        let (a, b) = (
            Complex::new(re[j], im[j]),
            Complex::new(re[j + 1], im[j + 1]),
        );
        let (turn, far) = ((b * a.conj()).arg() / TAU, modulus(b));
        ((hz(turn * m as f64, spindle_rpm), 0.5 * (near + far)), far)
    };
    let figures = |b: usize| {
        // Consecutive pairs share a sample: its modulus is taken once.
        let mut v: Vec<(f64, f64)> = Vec::new();
        let mut shared: Option<(usize, f64)> = None;
        let (first, last) = reach[b];
        for j in (first..=last).filter(|&j| band_of(j) == b) {
            let near = match shared {
                Some((k, modulus)) if k == j => modulus,
                _ => modulus(Complex::new(re[j], im[j])),
            };
            let (pair, far) = frequency(j, near);
            v.push(pair);
            shared = Some((j + 1, far));
        }
        if v.is_empty() {
            return None;
        }
        let mut env: Vec<f64> = v.iter().map(|e| e.1).collect();
        let middle = env.len() / 2;
        let (_, median_envelope, _) = env.select_nth_unstable_by(middle, f64::total_cmp);
        // Equal frequencies are one value to the quantiles: their order does not matter.
        v.sort_unstable_by(|p, q| p.0.total_cmp(&q.0));
        Some(BandFrequency {
            rho_outer_mm: bands.rho_max - b as f64 * bands.width,
            rho_inner_mm: bands.rho_max - (b + 1) as f64 * bands.width,
            median_hz: weighted_quantile(&v, 0.5),
            p95_hz: weighted_quantile(&v, 0.95),
            amplitude_um: *median_envelope * 1e3,
        })
    };
    members.iter().filter_map(|&b| figures(b)).collect()
}

/// The `q`-quantile of values sorted ascending with weights: the first value where the
/// cumulative weight reaches q of the total (the plain quantile when all weights are 0).
fn weighted_quantile(sorted: &[(f64, f64)], q: f64) -> f64 {
    let total: f64 = sorted.iter().map(|p| p.1).sum();
    if total <= 0.0 {
        return sorted
            .get(((sorted.len() as f64 * q) as usize).min(sorted.len().saturating_sub(1)))
            .map_or(0.0, |p| p.0);
    }
    let mut acc = 0.0;
    for &(v, w) in sorted {
        acc += w;
        if acc >= q * total {
            return v;
        }
    }
    sorted.last().map_or(0.0, |p| p.0)
}

/// Whether the signal can be analysed at `spindle_rpm`: a positive finite speed.
fn positive_speed(spindle_rpm: f64) -> bool {
    spindle_rpm.is_finite() && spindle_rpm > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::path_signal::tests::{arc_spiral, spiral};

    #[test]
    fn the_hann_window_is_its_cosines() {
        // Lengths with a square table (10⁶), without (odd, prime), short ones, from the start
        // and from an offset into the coarse table (as the chunks of a long record start); the
        // largest difference found is 8.9e-16.
        for n in [2usize, 3, 7, 1000, 65_537, 1_000_000, 1_048_583] {
            let window = Hann::new(n);
            for first in [0, n / 3, n - 1] {
                let (mut count, mut worst) = (0, 0.0f64);
                for (j, w) in (first..n).zip(window.from(first)) {
                    let libm = 0.5 - 0.5 * (TAU * j as f64 / n as f64).cos();
                    worst = worst.max((w - libm).abs());
                    count += 1;
                }
                assert_eq!(count, n - first);
                assert!(worst <= 1e-15, "n {n} from {first}: {worst:e}");
            }
        }
    }

    #[test]
    fn the_spectrum_gives_the_heights_band_figure_to_the_bit() {
        // Tones of 3, 17.5 and 40 cycles a revolution with amplitudes 1, 0.02 and 0.004 µm
        // (the last below 1 % of the largest: the figure is 17.5's, within the window's
        // spread), then a flat record (no significant frequency: 0).
        let tones = |_: f64, t: f64| {
            1e-3 * (3.0 * t).sin() + 2e-5 * (17.5 * t).cos() + 4e-6 * (40.0 * t).sin()
        };
        for z in [&tones as &dyn Fn(f64, f64) -> f64, &|_, _| 0.0] {
            let s = spiral(40.0, 128, 4.0, 0.01, z);
            let g = s.uniform().unwrap();
            let rho = s.radii_at(g.samples_per_rev);
            let (spectrum, band) = amplitude_spectrum_and_band_on(&g, 600.0, 256);
            let own = highest_significant_cycles_per_rev(&g, g.z_mm.clone());
            assert_eq!(band.map(f64::to_bits), Some(own.to_bits()));
            // The same with the radii's figure beside it, by one shared transform on two
            // cores, and each figure with its transform made beside its record: to the bit.
            let radii = highest_significant_cycles_per_rev(&g, rho.clone());
            let radius = |i: usize| s.rho(i);
            let both = amplitude_spectrum_and_bands_on(&s, &g, g.z_mm.clone(), radius, 600.0, 256);
            assert_eq!(both.0, spectrum);
            assert_eq!(both.1.map(f64::to_bits), band.map(f64::to_bits));
            assert_eq!(both.2.to_bits(), radii.to_bits());
            for values in [&g.z_mm, &rho] {
                let serial = highest_significant_cycles_per_rev(&g, values.clone());
                let beside =
                    highest_significant_cycles_per_rev_beside(&g, g.len(), || values.clone());
                assert_eq!(beside.to_bits(), serial.to_bits());
            }
        }
        let s = spiral(40.0, 128, 4.0, 0.01, tones);
        let g = s.uniform().unwrap();
        let rho = s.radii_at(g.samples_per_rev);
        let k = amplitude_spectrum_and_band_on(&g, 600.0, 256).1.unwrap();
        assert!((k - 17.5).abs() < 0.3, "{k}");
        assert_eq!(amplitude_spectrum_and_band_on(&g, 0.0, 256).1, None);
        // Without a speed there is no spectrum, but the other figure still is.
        let radius = |i: usize| s.rho(i);
        let (none, no_band, radii) =
            amplitude_spectrum_and_bands_on(&s, &g, g.z_mm.clone(), radius, 0.0, 256);
        assert_eq!((none, no_band), (Spectrum::default(), None));
        let own = highest_significant_cycles_per_rev(&g, rho);
        assert_eq!(radii.to_bits(), own.to_bits());
    }

    #[test]
    fn a_long_grids_spectrum_and_radii_figure_one_at_a_time_are_each_alone_to_the_bit() {
        // A grid of 2²⁰ + 1 samples (a transform in place): the spectrum, then the radii's
        // figure in single precision, each the same as made alone (and the radii's the double
        // one's).
        let tones = |_: f64, t: f64| 1e-3 * (3.0 * t).sin() + 2e-5 * (17.5 * t).cos();
        let s = spiral(8.0, 1 << 17, 4.0, 0.01, tones);
        let g = s.uniform().unwrap();
        assert!(in_place(fast_length(g.len(), false)));
        let radius = |i: usize| s.rho(i);
        let (spectrum, band) = amplitude_spectrum_and_band_on(&g, 600.0, 256);
        let radii = highest_significant_cycles_per_rev_at(&s, &g, radius);
        let (one, one_band, one_radii) =
            amplitude_spectrum_and_bands_on(&s, &g, g.z_mm.clone(), radius, 600.0, 256);
        assert_eq!(one, spectrum);
        assert_eq!(one_band.map(f64::to_bits), band.map(f64::to_bits));
        assert_eq!(one_radii.to_bits(), radii.to_bits());
        let double = highest_significant_cycles_per_rev(&g, s.radii_at(g.samples_per_rev));
        assert_eq!(one_radii, double);
        assert!((band.unwrap() - 17.5).abs() < 0.3, "{band:?}");
    }

    #[test]
    fn a_long_grids_figure_in_single_precision_is_the_double_ones() {
        // 1.1 M grid samples (transformed in place, padded to an even 2^a·3^b): a spiral sag of
        // millimetres with tones of 1 µm at 5, 0.2 µm at 29.3 and 5 nm at 61 cycles a turn
        // (below 1 % of the largest). The figure of the heights, and of the tones alone, made
        // in single precision is the double-precision one, and lies at 29.3 cycles a turn
        // (the Hann lobe's few bins above it).
        let z = |r: f64, t: f64| {
            0.3 * r * r + 1e-3 * (5.0 * t).sin() + 2e-4 * (29.3 * t).cos() + 5e-6 * (61.0 * t).sin()
        };
        let s = spiral(4300.0, 256, 4.0, 0.0009, z);
        let g = s.uniform().unwrap();
        let n = g.len();
        assert!(in_place(fast_length(n, false)));
        let tones: Vec<f64> = (0..s.len())
            .map(|i| s.z_mm[i] - 0.3 * s.rho(i) * s.rho(i))
            .collect();
        for values in [&s.z_mm, &tones] {
            let narrow = highest_significant_cycles_per_rev_at(&s, &g, |i| values[i]);
            let double = highest_significant_cycles_per_rev(&g, s.values_at(256, values));
            assert_eq!(narrow, double);
            assert!((29.3..29.31).contains(&narrow), "{narrow} cycles a turn");
        }
    }

    #[test]
    fn real_transforms_are_the_direct_sums() {
        // Against the DFT summed term by term, for odd and even lengths and records padded
        // with zeros; the inverse gives the record back, len times.
        for (n, len) in [
            (1, 1),
            (2, 2),
            (5, 5),
            (6, 9),
            (7, 8),
            (12, 12),
            (13, 27),
            (20, 24),
        ] {
            let x: Vec<f64> = (0..n).map(|j| ((j * j) as f64 * 0.7).sin() + 0.1).collect();
            let bins = forward_plan(len).spectrum(x.clone());
            assert_eq!(bins.len(), len / 2 + 1);
            for (k, b) in bins.iter().enumerate() {
                let direct: Complex<f64> = (x.iter().enumerate())
                    .map(|(j, v)| v * Complex::from_polar(1.0, -TAU * (j * k) as f64 / len as f64))
                    .sum();
                assert!((b - direct).norm() < 1e-13, "n {n}, len {len}, bin {k}");
            }
            let back = inverse_plan(len).record(bins);
            for (j, v) in back.iter().enumerate() {
                let want = x.get(j).copied().unwrap_or(0.0) * len as f64;
                assert!((v - want).abs() < 1e-12, "n {n}, len {len}, sample {j}");
            }
        }
    }

    #[test]
    fn fast_lengths_are_the_smallest_products_of_twos_and_threes() {
        // Every 2^a·3^b up to 2^40, sorted: the brute-force reference.
        let mut smooth: Vec<usize> = (0..=40u32)
            .flat_map(|a| (0..=26u32).map(move |b| (a, b)))
            .filter_map(|(a, b)| 2usize.checked_pow(a)?.checked_mul(3usize.checked_pow(b)?))
            .filter(|&v| v <= 1 << 40)
            .collect();
        smooth.sort_unstable();
        let first = |n: usize, even: bool| {
            *smooth
                .iter()
                .find(|&&v| v >= n && (!even || v % 2 == 0))
                .unwrap()
        };
        let sizes = (0..5000).chain([1_000_001, 1_032_001, 2_000_002, 28_581_761, (1 << 40) - 1]);
        for n in sizes {
            assert_eq!(fast_length(n, false), first(n, false), "n = {n}");
            assert_eq!(fast_length(n, true), first(n, true), "n = {n}, even");
        }
        // At most 1/8 of padding above 2^10 (the module's claim).
        for n in 1024..200_000 {
            assert!(
                fast_length(n, true) as f64 <= n as f64 * 1.125 + 2.0,
                "n = {n}"
            );
        }
    }

    #[test]
    fn a_tone_between_bins_is_found_at_k_n_over_60_with_its_amplitude() {
        // z = A·sin(kθ), k = 7.3 cycles/rev over N = 2593 samples of M = 64 per revolution:
        // the tone sits at bin k·N/M = 295.77, 0.23 bin off a bin centre. The three-bin
        // correction is exact up to the image at −f (1/(2·296)³ relative) and the finite-N
        // terms of the window (O(1/N²)), and the residual's gain at 7.3 cycles/rev (0.9987) is
        // divided out; 1e-4 relative holds both with room.
        let (a, k, rpm) = (0.003, 7.3, 480.0);
        let s = spiral(40.5, 64, 5.0, 0.01, |_, t| a * (k * t).sin());
        let sp = amplitude_spectrum(&s, rpm, 1000);
        let p = sp.peaks[0];
        assert!(
            (p.freq_hz - k * rpm / 60.0).abs() < 1e-4 * k * rpm / 60.0,
            "{p:?}"
        );
        assert!((p.amplitude_um - a * 1e3).abs() < 1e-4 * a * 1e3, "{p:?}");
        assert!((p.cycles_per_rev - k).abs() < 1e-4 * k);
        // The raw (decimated) spectrum reads within Hann's scalloping loss, 15 %, of A.
        let top = sp.amplitude_um.iter().copied().fold(0.0, f64::max);
        assert!(top <= a * 1e3 * 1.0001 && top >= a * 1e3 * 0.85, "{top}");
        assert!(sp.freq_hz.len() <= 1000);
        // Doubling the speed doubles the frequencies, not the amplitudes.
        let fast = amplitude_spectrum(&s, 2.0 * rpm, 1000).peaks[0];
        assert!((fast.freq_hz - 2.0 * p.freq_hz).abs() < 1e-9 * p.freq_hz);
        assert!((fast.amplitude_um - p.amplitude_um).abs() < 1e-12);
    }

    #[test]
    fn tones_in_a_padded_record_keep_their_frequency_and_amplitude() {
        // Records of prime length (2593, 2119 samples) are padded to 2916 and 2187 samples, so
        // the spectrum is sampled every 0.889 and 0.969 of the record's bins, and tones at
        // whole, half and odd fractions of a cycle per revolution sit anywhere between the
        // samples. Measured: frequency within 5e-10, amplitude within 3.1e-7 relative (the
        // tone's image at −f and the window's finite-N terms); 1e-8 and 1e-6 hold them.
        for (revs, k) in [
            (40.5, 7.3),
            (40.5, 7.31),
            (40.5, 7.35),
            (40.5, 7.0),
            (33.1, 11.77),
            (33.1, 11.5),
        ] {
            let (a, rpm) = (0.003, 60.0);
            let s = spiral(revs, 64, 5.0, 0.01, |_, t| a * (k * t).sin());
            let n = s.len();
            assert!(fast_length(n, false) > n, "{n} is not padded");
            let p = amplitude_spectrum(&s, rpm, 1000).peaks[0];
            assert!((p.cycles_per_rev - k).abs() < 1e-8 * k, "k {k}: {p:?}");
            assert!(
                (p.amplitude_um - a * 1e3).abs() < 1e-6 * a * 1e3,
                "k {k}: {p:?}"
            );
        }
    }

    #[test]
    fn the_three_sample_estimate_inverts_the_hann_response() {
        // At the record's own bins (q = 1) the estimate is the closed form δ = 2(X₊ − X₋)/(X₋ +
        // 2X₀ + X₊); between them it returns the offset and amplitude that made the samples.
        let closed = |b: f64, c: f64, a: f64| 2.0 * (a - b) / (b + 2.0 * c + a);
        for q in [1.0, 0.97, 0.889] {
            for i in -10..=10 {
                let d = 0.049 * q * i as f64;
                let amp = 2.5;
                let x = |o: f64| amp * hann_response(d + o);
                let (b, c, a) = (x(q), x(0.0), x(-q));
                let (pos, found) = refine(b, c, a, 100, q);
                assert!((pos - (100.0 + d / q)).abs() < 1e-12, "q {q} d {d}: {pos}");
                assert!((found - amp).abs() < 1e-12, "q {q} d {d}: {found}");
                if q == 1.0 {
                    assert!((closed(b, c, a) - d).abs() < 1e-12, "q 1 d {d}");
                }
            }
        }
        // The response itself: 1 at the tone, ½ one bin away, 0 two bins away, continuous
        // through the reflected branch at ½.
        assert_eq!(hann_response(0.0), 1.0);
        assert_eq!(hann_response(-1.0), 0.5);
        assert!(hann_response(2.0 - 1e-12).abs() < 1e-11);
        let half = |d: f64| (PI * d).sin() / (PI * d * (1.0 - d * d));
        for d in [0.5 - 1e-9, 0.5 + 1e-9, 0.7, 1.3, 1.0 + 1e-7] {
            assert!((hann_response(d) - half(d)).abs() < 1e-9, "{d}");
        }
    }

    #[test]
    fn two_frequencies_near_paper_000_are_both_found() {
        // Paper 000 Figure 13: 6.098 Hz and 47.03 Hz. At 60 rpm, 6 and 47 cycles/rev give 6 Hz
        // and 47 Hz. N = 12801 samples of M = 256 per revolution put them at bins 300.02 and
        // 2350.18; the corrected amplitudes are exact up to the images and the O(1/N²) terms
        // of the window, below 1e-6 relative. Their sidelobes stay under the 1 % listing
        // threshold, so exactly two peaks are listed.
        let s = spiral(50.0, 256, 5.0, 0.005, |r, t| {
            r * r * 0.01 + 0.2 * (6.0 * t).sin() + 0.01 * (47.0 * t).cos()
        });
        let sp = amplitude_spectrum(&s, 60.0, 512);
        let mut found: Vec<Peak> = sp.peaks.iter().copied().take(2).collect();
        found.sort_by(|p, q| p.freq_hz.total_cmp(&q.freq_hz));
        assert_eq!(sp.peaks.len(), 2, "{:?}", sp.peaks);
        assert!(
            (found[0].freq_hz - 6.0).abs() < 1e-6 && (found[1].freq_hz - 47.0).abs() < 1e-6,
            "{found:?}"
        );
        assert!(
            (found[0].amplitude_um - 200.0).abs() < 200.0 * 1e-6,
            "{found:?}"
        );
        assert!(
            (found[1].amplitude_um - 10.0).abs() < 10.0 * 1e-6,
            "{found:?}"
        );
    }

    #[test]
    fn instantaneous_frequency_of_a_tone_is_k_n_over_60() {
        // A pure tone is narrow-band everywhere: the Hilbert frequency is exact but for the
        // roll-off at the ends, whose raised cosine has a jump in its second derivative; its
        // effect on the analytic signal outside the two left-out revolutions was measured at
        // 2e-8 relative on the medians and 6.5e-6 on the 95th percentiles (a mirror-image
        // extension instead gave 1.3e-5 and 4e-3), hence 1e-7 and 1e-5.
        let (k, rpm) = (12.0, 300.0);
        let s = spiral(30.0, 128, 3.0, 0.1, |_, t| 0.001 * (k * t + 0.3).sin());
        let bands = instantaneous_frequency(&s, rpm, 5);
        assert_eq!(bands.len(), 5);
        for b in &bands {
            assert!(
                (b.median_hz - k * rpm / 60.0).abs() < 1e-7 * k * rpm / 60.0,
                "{b:?}"
            );
            assert!(
                (b.p95_hz - k * rpm / 60.0).abs() < 1e-5 * k * rpm / 60.0,
                "{b:?}"
            );
            assert!((b.amplitude_um - 1.0).abs() < 1e-7, "{b:?}");
        }
        assert!((bands[0].rho_outer_mm - 3.0).abs() < 1e-12 && bands[4].rho_inner_mm.abs() < 1e-12);
    }

    /// The figures of `bands` bands with the whole path one stretch: one record at the
    /// path's densest rate, as the dynamics analysed it before bands had stretches of their
    /// own.
    fn whole_record(s: &PathSignal, rpm: f64, bands: usize) -> Vec<BandFrequency> {
        let b = RadiusBands::of(s, bands);
        let all: Vec<usize> = (0..bands).collect();
        stretch_frequencies(s, s.stretch(-TAU, s.span_rad() + TAU), &b, &all, rpm)
    }

    #[test]
    fn each_bands_stretch_gives_a_tones_frequency() {
        // A tone of k = 24 cycles a revolution, 1 µm, on 60 revolutions in 16 bands. At
        // constant angle (2048 points a turn) every band's figures are the tone's within the
        // tolerances of the whole record's test above (measured 1.3e-9, 8.1e-7 and 1.3e-9:
        // a stretch's roll-offs lie a revolution outside its bands). At constant arc (12 µm,
        // 2094 down to 523 points a turn) the motion is the piecewise-linear interpolation of
        // the tone, whose frequency ripples by the order of (πk/N)² (2.1e-2 at N = 523) and
        // whose amplitude falls by sinc²(πk/N) at most, N the band's sparsest turn: measured
        // 2.1e-3 on the medians and 2.2e-2 on the 95th percentiles at the innermost band
        // (the whole record at the densest turn's rate: 5.3e-4 and 5.9e-2).
        let (k, rpm) = (24.0, 300.0);
        let hz = k * rpm / 60.0;
        let z = |_: f64, t: f64| 0.001 * (k * t + 0.3).sin();
        for b in instantaneous_frequency(&spiral(60.0, 2048, 4.0, 0.05, z), rpm, 16) {
            assert!((b.median_hz / hz - 1.0).abs() < 1e-7, "{b:?}");
            assert!((b.p95_hz / hz - 1.0).abs() < 1e-5, "{b:?}");
            assert!((b.amplitude_um - 1.0).abs() < 1e-7, "{b:?}");
        }
        let arc = 0.012;
        let bands = instantaneous_frequency(&arc_spiral(60.0, 4.0, 0.05, arc, z), rpm, 16);
        assert_eq!(bands.len(), 12);
        for b in bands {
            let x = PI * k * arc / (TAU * b.rho_inner_mm.max(1.0));
            assert!((b.median_hz / hz - 1.0).abs() < 3e-3, "{b:?}");
            assert!((b.p95_hz / hz - 1.0).abs() < 3e-2, "{b:?}");
            let sinc = x.sin() / x;
            assert!(
                b.amplitude_um <= 1.0 && b.amplitude_um >= sinc * sinc,
                "{b:?}"
            );
        }
    }

    #[test]
    fn each_bands_stretch_gives_the_whole_records_figures() {
        // A sine grid (λ 0.5 mm, 2 µm) with a 24-cycle tone of 0.5 µm and a sag, at constant
        // angle and at constant arc (the outer revolutions four times as dense as the inner
        // ones), 60 revolutions in 16 bands: the stretches' figures against the whole
        // record's. The sine grid is not narrow-band where its frequency passes through zero,
        // so both are estimates of the same weighted quantiles that the roll-offs a revolution
        // outside each band, and at constant arc the rates, move: measured 4.3e-4 at most at
        // constant angle; 2.4e-3 on the medians, 4.9e-3 on the 95th percentiles and 8.6e-4 on
        // the envelopes at constant arc, against the 0.5/√a of tests/tests/split.rs (6 % and
        // more here) within which the method gives a sine grid's median at all.
        let z = |r: f64, t: f64| {
            2e-3 * (TAU * r * t.cos() / 0.5).sin() + 5e-4 * (24.0 * t).sin() + 0.01 * r * r
        };
        let (rpm, bands) = (300.0, 16);
        for (s, tolerance) in [
            (spiral(60.0, 2048, 4.0, 0.05, z), (1e-3, 1e-3, 1e-3)),
            (arc_spiral(60.0, 4.0, 0.05, 0.012, z), (5e-3, 1e-2, 2e-3)),
        ] {
            let (by_stretch, whole) = (
                instantaneous_frequency(&s, rpm, bands),
                whole_record(&s, rpm, bands),
            );
            assert_eq!(by_stretch.len(), whole.len());
            for (a, b) in by_stretch.iter().zip(&whole) {
                for (x, y, within) in [
                    (a.median_hz, b.median_hz, tolerance.0),
                    (a.p95_hz, b.p95_hz, tolerance.1),
                    (a.amplitude_um, b.amplitude_um, tolerance.2),
                ] {
                    assert!((x / y - 1.0).abs() < within, "{a:?} against {b:?}");
                }
                assert_eq!(
                    (a.rho_outer_mm, a.rho_inner_mm),
                    (b.rho_outer_mm, b.rho_inner_mm)
                );
            }
        }
    }

    #[test]
    fn bad_input_gives_empty_results() {
        let s = spiral(3.0, 16, 1.0, 0.1, |_, t| t.sin());
        assert!(amplitude_spectrum(&s, f64::NAN, 10).peaks.is_empty());
        assert!(instantaneous_frequency(&s, -1.0, 3).is_empty());
        assert!(instantaneous_frequency(&PathSignal::default(), 100.0, 3).is_empty());
        assert!(amplitude_spectrum(&s, 100.0, 0).freq_hz.is_empty());
    }
}
