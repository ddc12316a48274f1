//! The real-input FFT of a long record in its own memory: the dynamics' transforms, whose
//! buffers are their peak memory ([`super::BYTES_PER_SAMPLE`]).
//!
//! A real record of even length L is a complex one of N = L/2 points (even samples the real
//! parts, odd ones the imaginary), transformed, then untangled by one pass over the pairs of bins
//! k and N − k (`X_k = E_k + w^k·O_k`, `X_{N−k} = conj(E_k − w^k·O_k)` with `E`, `O` the spectra
//! of the even and odd samples and `w = e^{−2πi/L}`; the inverse runs the pass backwards first).
//! The complex transform is Bailey's four-step algorithm ("FFTs in external or hierarchical
//! memory", 1990): the N points as n₁ rows of n₂ = r·n₁ (N = 2^a·3^b, r ∈ {1, 2, 3, 6}), a
//! transform of every column (gathered a few columns at a time), the twiddles `w_N^{j₂·k₁}`,
//! a transform of every row (`rustfft`'s plans of n₁ and n₂ points), and a transposition in
//! place (the rows' chunks put in order, then each square block transposed). Its tables hold
//! about √N entries: a twiddle `w^m` is the product of two, `w^{q·t}·w^s` with `m = q·t + s`.
//! So a transform holds its record, 8 bytes a sample, where `realfft` holds 16 with its output
//! and 12 more for its plan. Its bins agree with the direct sums (and `realfft`'s) to a few
//! units of the last place of the largest; not to the bit, so records shorter than
//! [`IN_PLACE_FROM`] samples, and odd lengths, stay on `realfft`.

use crate::parallel::{fill_chunks, workers};
use realfft::{ComplexToReal, FftError, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftDirection, FftNum, FftPlanner};
use std::sync::Arc;

/// The shortest record transformed in place (2²⁰ samples, 8 MiB): below it `realfft`'s plan and
/// output are small, and its results are kept to the bit.
pub const IN_PLACE_FROM: usize = 1 << 20;

/// Columns gathered at a time by the four-step transform's column pass (each row read in
/// 16 · 16 = 256 contiguous bytes).
const COLUMNS_AT_A_TIME: usize = 16;

/// Tiles of the square transposition, elements a side.
const TILE: usize = 16;

/// The forward real-input transform of `len` samples: bins 0 … len/2.
pub(crate) enum RealForward {
    /// By `realfft` (short or odd records).
    Planned(Arc<dyn RealToComplex<f64>>),
    /// In place.
    InPlace(InPlace),
}

/// The inverse real-input transform, unscaled, of `len` samples.
pub(crate) enum RealInverse {
    /// By `realfft` (short or odd records).
    Planned(Arc<dyn ComplexToReal<f64>>),
    /// In place.
    InPlace(InPlace),
}

impl RealForward {
    /// The transform of `len` samples: in place from [`IN_PLACE_FROM`] for even lengths.
    pub(crate) fn new(len: usize) -> Self {
        if in_place(len) {
            Self::InPlace(InPlace::new(len, FftDirection::Forward))
        } else {
            Self::Planned(RealFftPlanner::<f64>::new().plan_fft_forward(len))
        }
    }

    /// The record's length.
    pub(crate) fn len(&self) -> usize {
        match self {
            Self::Planned(p) => p.len(),
            Self::InPlace(p) => p.len(),
        }
    }

    /// The spectrum of `x` padded with zeros to [`Self::len`] samples, bins 0 … len/2, in
    /// `x`'s memory where the transform is in place.
    pub(crate) fn spectrum(&self, mut x: Vec<f64>) -> Vec<Complex<f64>> {
        let len = self.len();
        match self {
            Self::Planned(p) => {
                // Grown to the padded length exactly: `resize` alone would double the
                // record's capacity.
                x.reserve_exact(len.saturating_sub(x.len()));
                x.resize(len, 0.0);
                let mut out = p.make_output_vec();
                // Buffers sized by the plan itself: the transform cannot refuse them.
                let done = p.process(&mut x, &mut out);
                debug_assert!(done.is_ok());
                out
            }
            Self::InPlace(p) => p.spectrum(x),
        }
    }
}

impl RealInverse {
    /// The inverse transform of `len` samples: in place from [`IN_PLACE_FROM`] for even lengths.
    pub(crate) fn new(len: usize) -> Self {
        if in_place(len) {
            Self::InPlace(InPlace::new(len, FftDirection::Inverse))
        } else {
            Self::Planned(RealFftPlanner::<f64>::new().plan_fft_inverse(len))
        }
    }

    /// The record's length.
    pub(crate) fn len(&self) -> usize {
        match self {
            Self::Planned(p) => p.len(),
            Self::InPlace(p) => p.len(),
        }
    }

    /// The real record, unscaled (`len` times the record), whose spectrum is `bins` (0 … len/2),
    /// in `bins`' memory where the transform is in place. The imaginary parts of bins 0 and
    /// len/2 (that of a real record is 0) are ignored.
    pub(crate) fn record(&self, mut bins: Vec<Complex<f64>>) -> Vec<f64> {
        match self {
            Self::Planned(p) => {
                let mut out = p.make_output_vec();
                let done = p.process(&mut bins, &mut out);
                debug_assert!(matches!(done, Ok(()) | Err(FftError::InputValues(..))));
                out
            }
            Self::InPlace(p) => {
                bins.resize(p.len() / 2 + 1, Complex::new(0.0, 0.0));
                p.inverse(&mut bins);
                let mut x = as_real(bins);
                x.truncate(p.len());
                x
            }
        }
    }
}

/// The spectrum, bins 0 … len/2, of the single-precision record `x` padded with zeros to `len`
/// (even) samples, in `x`'s memory, by the transform in place in single precision: for a
/// bandwidth figure of a long record, which reads amplitudes against 1 % of the largest and
/// so needs neither double precision nor twice the memory (module docs).
pub(crate) fn narrow_spectrum(x: Vec<f32>, len: usize) -> Vec<Complex<f32>> {
    let len = len.max(2).next_multiple_of(2);
    InPlace::<f32>::new(len, FftDirection::Forward).spectrum(x)
}

/// Whether a record of `len` samples is transformed in place: from [`IN_PLACE_FROM`], even.
pub(crate) fn in_place(len: usize) -> bool {
    len >= IN_PLACE_FROM && len.is_multiple_of(2)
}

/// The real value `f(j, bins[j])` of every bin, in the bins' memory: value j is written over
/// the first half of bin j/2, after every bin it overwrites has been read. For an amplitude
/// spectrum held beside other records (8 bytes a bin where a copy would hold 24 with them).
pub(crate) fn real_values_of(
    bins: Vec<Complex<f64>>,
    f: impl Fn(usize, Complex<f64>) -> f64,
) -> Vec<f64> {
    let count = bins.len();
    let mut x = as_real(bins);
    for j in 0..count {
        let bin = Complex::new(x[2 * j], x[2 * j + 1]);
        x[j] = f(j, bin);
    }
    x.truncate(count);
    x.shrink_to_fit();
    x
}

/// `x` (an even number of samples) as complex numbers, in its memory where its capacity is
/// even (always, as [`RealForward::spectrum`] sizes it), else copied.
fn as_complex<T: FftNum + bytemuck::Pod>(x: Vec<T>) -> Vec<Complex<T>> {
    bytemuck::allocation::try_cast_vec(x).unwrap_or_else(|(_, x)| {
        x.chunks_exact(2)
            .map(|p| Complex::new(p[0], p[1]))
            .collect()
    })
}

/// `z` as its real and imaginary parts in turn, in its memory.
fn as_real<T: FftNum + bytemuck::Pod>(z: Vec<Complex<T>>) -> Vec<T> {
    bytemuck::allocation::try_cast_vec(z)
        .unwrap_or_else(|(_, z)| z.iter().flat_map(|c| [c.re, c.im]).collect())
}

/// A real-input transform of an even length in place: the complex four-step transform of half
/// the length and the pass that pairs its bins (module docs).
pub(crate) struct InPlace<T: FftNum = f64> {
    len: usize,
    half: FourStep<T>,
    /// `w_L^k` (conjugated for the inverse), k ≤ L/4.
    pairing: Twiddles<T>,
}

impl<T: FftNum> InPlace<T> {
    /// The transform of `len` (even) samples in `direction`.
    pub(crate) fn new(len: usize, direction: FftDirection) -> Self {
        let n = len / 2;
        Self {
            len,
            half: FourStep::new(n, direction),
            pairing: Twiddles::new(len, n / 2 + 1, direction),
        }
    }

    fn len(&self) -> usize {
        self.len
    }

    /// Bins 0 … N of `x` padded with zeros to the transform's length, in `x`'s memory.
    fn spectrum(&self, mut x: Vec<T>) -> Vec<Complex<T>>
    where
        T: bytemuck::Pod,
    {
        // Two samples more: the Nyquist bin.
        let len = self.len;
        x.truncate(len);
        x.reserve_exact(len + 2 - x.len());
        x.resize(len + 2, T::zero());
        let mut bins = as_complex(x);
        self.forward(&mut bins);
        bins
    }

    /// Bins 0 … N of the real record held in `z` (N + 1 complex numbers, the last one spare).
    fn forward(&self, z: &mut [Complex<T>]) {
        let n = self.len / 2;
        self.half.process(&mut z[..n]);
        let z0 = z[0];
        z[0] = Complex::new(z0.re + z0.im, T::zero());
        z[n] = Complex::new(z0.re - z0.im, T::zero());
        let half = T::from_f64(0.5).unwrap_or_else(T::zero);
        for (k, w) in (1..=n / 2).zip(self.pairing.from(1)) {
            let (a, b) = (z[k], z[n - k].conj());
            let even = (a + b) * half;
            let odd = (a - b) * Complex::new(T::zero(), -half);
            let turned = w * odd;
            z[k] = even + turned;
            z[n - k] = (even - turned).conj();
        }
    }

    /// The real record, unscaled, of bins 0 … N held in `z`, as N complex numbers (the last
    /// entry of `z` is then free).
    fn inverse(&self, z: &mut [Complex<T>]) {
        let n = self.len / 2;
        let (first, last) = (z[0].re, z[n].re);
        z[0] = Complex::new(first + last, first - last);
        for (k, w) in (1..=n / 2).zip(self.pairing.from(1)) {
            let (a, b) = (z[k], z[n - k].conj());
            let even = a + b;
            let odd = (a - b) * w * Complex::new(T::zero(), T::one());
            z[k] = even + odd;
            z[n - k] = (even - odd).conj();
        }
        self.half.process(&mut z[..n]);
    }
}

/// `e^{∓2πi·m/n}` for `m < count` from two tables of about √count entries: `m = q·t + s`,
/// `w^m = coarse[q]·fine[s]`.
pub(crate) struct Twiddles<T> {
    step: usize,
    fine: Vec<Complex<T>>,
    coarse: Vec<Complex<T>>,
}

impl<T: FftNum> Twiddles<T> {
    /// The powers `w^m`, `m < count`, of `w = e^{∓2πi/n}` (− forward).
    pub(crate) fn new(n: usize, count: usize, direction: FftDirection) -> Self {
        let step = (count as f64).sqrt().ceil().max(1.0) as usize;
        let sign = match direction {
            FftDirection::Forward => -1.0,
            FftDirection::Inverse => 1.0,
        };
        let w = |m: usize| {
            let (s, c) = (sign * std::f64::consts::TAU * m as f64 / n as f64).sin_cos();
            Complex::new(narrow(c), narrow(s))
        };
        Self {
            step,
            fine: (0..step).map(w).collect(),
            coarse: (0..count.div_ceil(step)).map(|q| w(q * step)).collect(),
        }
    }

    /// `w^m` for m = `first`, `first` + 1, …, each `coarse[q]·fine[s]` with `m = q·t + s`
    /// stepped (no division after the first).
    pub(crate) fn from(&self, first: usize) -> impl Iterator<Item = Complex<T>> + '_ {
        let (mut q, mut s) = (first / self.step, first % self.step);
        std::iter::from_fn(move || {
            let w = self.coarse[q] * self.fine[s];
            s += 1;
            if s == self.step {
                (q, s) = (q + 1, 0);
            }
            Some(w)
        })
    }
}

/// The complex transform of `n₁·n₂` points in place (module docs).
struct FourStep<T> {
    n1: usize,
    n2: usize,
    columns: Arc<dyn Fft<T>>,
    rows: Arc<dyn Fft<T>>,
    twiddles: Twiddles<T>,
}

impl<T: FftNum> FourStep<T> {
    fn new(n: usize, direction: FftDirection) -> Self {
        let (n1, n2) = rows_and_columns(n);
        let mut planner = FftPlanner::new();
        Self {
            n1,
            n2,
            columns: planner.plan_fft(n1, direction),
            rows: planner.plan_fft(n2, direction),
            twiddles: Twiddles::new(n, n, direction),
        }
    }

    /// The transform of `data` (n₁·n₂ points) in place, in natural order.
    fn process(&self, data: &mut [Complex<T>]) {
        self.column_pass(data);
        self.row_pass(data);
        transpose(data, self.n1, self.n2);
    }

    /// Every column transformed (over the row index j₁ → k₁) and turned by `w^{j₂·k₁}`, the
    /// columns shared among the workers in contiguous ranges.
    fn column_pass(&self, data: &mut [Complex<T>]) {
        let (n1, n2) = (self.n1, self.n2);
        let width = n2.div_ceil(workers()).max(1);
        let mut parts: Vec<(usize, Vec<&mut [Complex<T>]>)> = (0..n2.div_ceil(width))
            .map(|p| (p * width, Vec::with_capacity(n1)))
            .collect();
        for row in data.chunks_exact_mut(n2) {
            for (slot, (_, cut)) in row.chunks_mut(width).zip(parts.iter_mut()) {
                cut.push(slot);
            }
        }
        let Ok(()) = fill_chunks(&mut parts, |_, mine| {
            for (first, rows) in mine.iter_mut() {
                self.columns_of(*first, rows);
            }
            Ok::<(), std::convert::Infallible>(())
        });
    }

    /// The column pass over the columns `first …` held in `rows` (each row's share).
    fn columns_of(&self, first: usize, rows: &mut [&mut [Complex<T>]]) {
        let n1 = self.n1;
        let count = rows.first().map_or(0, |r| r.len());
        let mut block = vec![Complex::new(T::zero(), T::zero()); n1 * COLUMNS_AT_A_TIME.min(count)];
        let mut scratch =
            vec![Complex::new(T::zero(), T::zero()); self.columns.get_inplace_scratch_len()];
        let t = self.twiddles.step;
        for c0 in (0..count).step_by(COLUMNS_AT_A_TIME) {
            let w = COLUMNS_AT_A_TIME.min(count - c0);
            let block = &mut block[..w * n1];
            for (j1, row) in rows.iter().enumerate() {
                for (c, v) in row[c0..c0 + w].iter().enumerate() {
                    block[c * n1 + j1] = *v;
                }
            }
            self.columns.process_with_scratch(block, &mut scratch);
            for (c, column) in block.chunks_exact_mut(n1).enumerate() {
                // w^{j₂·k₁} with the index j₂·k₁ = q·t + s stepped along k₁.
                let j2 = first + c0 + c;
                let (dq, ds) = (j2 / t, j2 % t);
                let (mut q, mut s) = (0, 0);
                for v in column.iter_mut() {
                    *v = *v * (self.twiddles.coarse[q] * self.twiddles.fine[s]);
                    s += ds;
                    q += dq;
                    if s >= t {
                        s -= t;
                        q += 1;
                    }
                }
            }
            for (k1, row) in rows.iter_mut().enumerate() {
                for (c, v) in row[c0..c0 + w].iter_mut().enumerate() {
                    *v = block[c * n1 + k1];
                }
            }
        }
    }

    /// Every row transformed (over the column index j₂ → k₂), the rows shared among the workers.
    fn row_pass(&self, data: &mut [Complex<T>]) {
        let rows_each = self.n1.div_ceil(workers()).max(1);
        let mut parts: Vec<&mut [Complex<T>]> = data.chunks_mut(rows_each * self.n2).collect();
        let Ok(()) = fill_chunks(&mut parts, |_, mine| {
            let mut scratch =
                vec![Complex::new(T::zero(), T::zero()); self.rows.get_inplace_scratch_len()];
            for part in mine.iter_mut() {
                self.rows.process_with_scratch(part, &mut scratch);
            }
            Ok::<(), std::convert::Infallible>(())
        });
    }
}

/// n₁ and n₂ = r·n₁ with n₁·n₂ = n (n = 2^a·3^b; r = 2^{a mod 2}·3^{b mod 2}).
fn rows_and_columns(n: usize) -> (usize, usize) {
    let (mut rest, mut n1) = (n, 1);
    for f in [2, 3] {
        while rest % (f * f) == 0 {
            rest /= f * f;
            n1 *= f;
        }
    }
    (n1, n / n1)
}

/// The n₁ × n₂ matrix `data` (n₂ = r·n₁, row-major) transposed in place: chunk (k₁, s) of n₁
/// elements moved to chunk (s, k₁), then each square block of n₁ × n₁ transposed.
fn transpose<T: FftNum>(data: &mut [Complex<T>], n1: usize, n2: usize) {
    let r = n2 / n1;
    if r > 1 {
        // The chunk to land at d comes from `from(d)`; cycles followed with one chunk aside.
        let chunks = n1 * r;
        let from = |d: usize| (d % n1) * r + d / n1;
        let mut done = vec![false; chunks];
        let mut aside = vec![Complex::new(T::zero(), T::zero()); n1];
        for start in 0..chunks {
            if done[start] || from(start) == start {
                continue;
            }
            aside.copy_from_slice(&data[start * n1..(start + 1) * n1]);
            let mut d = start;
            loop {
                done[d] = true;
                let s = from(d);
                if s == start {
                    data[d * n1..(d + 1) * n1].copy_from_slice(&aside);
                    break;
                }
                data.copy_within(s * n1..(s + 1) * n1, d * n1);
                d = s;
            }
        }
    }
    let mut blocks: Vec<&mut [Complex<T>]> = data.chunks_exact_mut(n1 * n1).collect();
    let Ok(()) = fill_chunks(&mut blocks, |_, mine| {
        for block in mine.iter_mut() {
            transpose_square(block, n1);
        }
        Ok::<(), std::convert::Infallible>(())
    });
}

/// The n × n matrix `a` transposed in place, tile by tile.
fn transpose_square<T: Copy>(a: &mut [Complex<T>], n: usize) {
    for i0 in (0..n).step_by(TILE) {
        for j0 in (i0..n).step_by(TILE) {
            for i in i0..(i0 + TILE).min(n) {
                let from = if i0 == j0 { i + 1 } else { j0 };
                for j in from..(j0 + TILE).min(n) {
                    a.swap(i * n + j, j * n + i);
                }
            }
        }
    }
}

/// `x` in the transform's float type (f64 itself, or rounded to f32).
fn narrow<T: FftNum>(x: f64) -> T {
    T::from_f64(x).unwrap_or_else(T::zero)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pseudo-random samples in [−1, 1).
    fn noise(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (s >> 11) as f64 / (1u64 << 52) as f64 - 1.0
            })
            .collect()
    }

    #[test]
    fn rows_and_columns_are_a_square_times_a_small_factor() {
        for (n, rc) in [
            (1, (1, 1)),
            (2, (1, 2)),
            (6, (1, 6)),
            (36, (6, 6)),
            (1 << 20, (1 << 10, 1 << 10)),
            (3 << 21, (1 << 10, 6 << 10)),
            (27 << 4, (12, 36)),
        ] {
            assert_eq!(rows_and_columns(n), rc, "{n}");
        }
    }

    #[test]
    fn the_transposition_in_place_moves_every_element() {
        for (n1, n2) in [(1, 1), (4, 4), (5, 10), (17, 51), (16, 96), (33, 33)] {
            let mut a: Vec<Complex<f64>> =
                (0..n1 * n2).map(|i| Complex::new(i as f64, 0.0)).collect();
            transpose(&mut a, n1, n2);
            for k2 in 0..n2 {
                for k1 in 0..n1 {
                    assert_eq!(a[k2 * n1 + k1].re, (k1 * n2 + k2) as f64, "{n1}×{n2}");
                }
            }
        }
    }

    /// Forward and inverse in place against the direct sums, at lengths whose halves have
    /// every shape of rows and columns (r = 1, 2, 3, 6), within a few units of the last place
    /// of the largest bin.
    #[test]
    fn transforms_in_place_are_the_direct_sums() {
        for len in [2, 4, 6, 12, 36, 72, 96, 288, 864, 1152, 2592] {
            let x = noise(len, len as u64);
            let forward = InPlace::new(len, FftDirection::Forward);
            let mut z = as_complex({
                let mut v = x.clone();
                v.extend([0.0, 0.0]);
                v
            });
            forward.forward(&mut z);
            let scale: f64 = x.iter().map(|v| v.abs()).sum();
            for (k, got) in z.iter().enumerate() {
                let want = x
                    .iter()
                    .enumerate()
                    .fold(Complex::new(0.0, 0.0), |s, (j, v)| {
                        let a = -std::f64::consts::TAU * ((j * k) % len) as f64 / len as f64;
                        s + Complex::new(a.cos(), a.sin()) * v
                    });
                assert!((got - want).norm() < 1e-14 * scale, "{len}: bin {k}");
            }
            let inverse = InPlace::new(len, FftDirection::Inverse);
            inverse.inverse(&mut z);
            let back = as_real(z);
            for (j, v) in x.iter().enumerate() {
                assert!(
                    (back[j] / len as f64 - v).abs() < 1e-14,
                    "{len}: sample {j}"
                );
            }
        }
    }

    /// The single-precision transform in place is the double-precision one within f32's
    /// rounding: every bin within 1e-6 of the largest, at lengths of every shape of rows and
    /// columns and one of 2¹⁷, the record padded.
    #[test]
    fn a_narrow_spectrum_is_the_double_one_within_single_precision() {
        for len in [36, 96, 2592, 1 << 17] {
            let x: Vec<f64> = noise(len - 5, 11)
                .into_iter()
                .map(|v| f64::from(v as f32))
                .collect();
            let double = RealForward::InPlace(InPlace::new(len, FftDirection::Forward));
            let want = double.spectrum(x.clone());
            let got = narrow_spectrum(x.iter().map(|&v| v as f32).collect(), len);
            assert_eq!(got.len(), want.len());
            let top = want.iter().map(|c| c.norm()).fold(0.0, f64::max);
            let worst = (got.iter().zip(&want))
                .map(|(g, w)| (Complex::new(f64::from(g.re), f64::from(g.im)) - w).norm())
                .fold(0.0, f64::max);
            assert!(worst < 1e-6 * top, "{len}: {worst} against {top}");
        }
    }

    #[test]
    fn real_values_are_written_over_their_bins_in_order() {
        let bins: Vec<Complex<f64>> = (0..7)
            .map(|j| Complex::new(j as f64, -2.0 * j as f64))
            .collect();
        let values = real_values_of(bins.clone(), |j, c| c.norm() + j as f64);
        assert_eq!(values.len(), 7);
        for (j, (v, c)) in values.iter().zip(&bins).enumerate() {
            assert_eq!(v.to_bits(), (c.norm() + j as f64).to_bits());
        }
    }

    /// The public transforms in place agree with `realfft`'s above the threshold, the record
    /// padded, and give back the record.
    #[test]
    fn in_place_and_realfft_agree_on_a_long_record() {
        let len = IN_PLACE_FROM * 3 / 2;
        let x = noise(len - 1000, 7);
        let ours = RealForward::new(len);
        assert!(matches!(ours, RealForward::InPlace(_)));
        let theirs = RealFftPlanner::<f64>::new().plan_fft_forward(len);
        let a = ours.spectrum(x.clone());
        let b = RealForward::Planned(theirs).spectrum(x.clone());
        assert_eq!(a.len(), b.len());
        let top = b.iter().map(|c| c.norm()).fold(0.0, f64::max);
        let worst = a
            .iter()
            .zip(&b)
            .map(|(p, q)| (p - q).norm())
            .fold(0.0, f64::max);
        assert!(worst < 1e-13 * top, "{worst} against {top}");
        let back = RealInverse::new(len).record(a);
        assert_eq!(back.len(), len);
        for (j, v) in back.iter().enumerate() {
            let want = x.get(j).copied().unwrap_or(0.0);
            assert!((v / len as f64 - want).abs() < 1e-13, "sample {j}");
        }
    }
}
