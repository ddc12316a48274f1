//! The compensated path as a signal of the spindle angle, the common input of the frequency
//! analysis ([`crate::dynamics::spectrum`], paper 000 "Hybrid Hilbert transform/fast Fourier
//! transform methodology") and of the splitter
//! ([`crate::dynamics::split`](mod@crate::dynamics::split)).
//!
//! **Time.** The spindle turns at constant speed n and the path is sent with inverse-time feed,
//! so point i is reached at `t_i = φ_i/ω`, `φ_i = |θ_i − θ_0|`, `ω = 2π·n/60`. Everything here
//! is a function of φ; a speed only rescales it (k cycles per revolution is k·n/60 Hz, a slope
//! dz/dφ is a velocity ×ω, a curvature d²z/dφ² an acceleration ×ω²).
//!
//! **Uniform grid.** The FFT needs equal time steps; constant-arc and HCAA paths have angle steps
//! that change with the radius. [`PathSignal::uniform`] resamples the path onto `M` samples per
//! revolution, M the densest sampling of any revolution of the path (at least 8; at most enough for
//! 4 samples per path point over the whole path), so the grid's Nyquist frequency M/2 cycles/rev is
//! at least that of every part of the path. Samples are taken by linear interpolation in φ between
//! path points. That is exactly the motion the controller executes (C, X and Z linear in time
//! between blocks under inverse-time feed), so the grid adds no error to the commanded motion; the
//! commanded motion differs from the surface by the linearization error PVerr
//! ([`crate::analysis::linearization`]) that the sampling already bounds. With constant-angle
//! sampling the grid falls on the path points. A [`Stretch`] of the path
//! ([`PathSignal::stretch`]) is resampled the same way at the densest rate of its own turns:
//! the samples of the whole path's grid at that rate which it spans, to the bit.
//!
//! **Memory.** A path is held as its columns θ, ρ and z, 24 bytes a point, except where its
//! angles and radii are a function of the index (one-way compensation of a constant-angle
//! spiral, or of a spiral given as a list, [`PathSignal::for_spiral`]): then they are computed
//! again by the planner's own expression, or read from the spiral's list, whenever they are
//! read, and only z is held (8 bytes a point). A spiral walked by its step rule (one-way
//! compensation of a constant-arc, HCAA or adaptive spiral) has points that are no function of
//! their index, but each is the spiral's point at some φ (`ρ = b·φ`, `θ = θ₀ ± (φ₀ − φ)`), which
//! is recovered from the point to the bit ([`crate::path::WalkedRule::phi_of`]): φ and z are
//! held (16 bytes a point). The uniform grid's columns may be let go and
//! made again where they are used ([`UniformSignal::heights`], [`PathSignal::values_at`],
//! [`PathSignal::radii_at`] the grid's rate: the same expressions, so the same bits; the path
//! is checked once, when its grid is first made), and a residual is
//! taken in its record's memory ([`UniformSignal::subtract_symmetric_part`]), or made a block
//! at a time and rounded to single precision ([`UniformSignal::narrow_residual`]): the dynamics
//! hold at most one record of the grid in double precision beside the path, or two on a grid
//! of one low-pass segment ([`crate::dynamics::BYTES_PER_SAMPLE`]).
//!
//! **Rotationally symmetric part** (paper 002, "surface decomposition": a rotationally
//! symmetric surface cut by X, C and Z plus a freeform remainder). On a spiral each radius is
//! visited once per revolution, so the azimuthal mean at the radius of grid sample j is taken as
//! the triangle-weighted mean over the two revolutions centred on it,
//! `S_j = Σ_{|k|<M} (M − |k|)·z_{j+k} / M²` (a one-revolution moving mean applied twice). Its
//! response `(sin πν / (M·sin(πν/M)))²` has a double zero at every whole number ν of cycles
//! per revolution, so a harmonic `a_m(ρ)·cos(mθ)` whose amplitude changes linearly with the
//! radius leaves nothing in S, and with `ρ = R − f·φ/2π` the error of S as the azimuthal mean
//! is second order in the feed f: `|S − S_true| ≤ |S_true″|·f²/12 + Σ_m |a_m″|·f²/(4π²m²)`
//! (″ = d²/dρ²; a sphere of radius 40 mm at f = 5 µm: 0.05 nm). In the first and last
//! revolution, where the window does not fit, S is the polynomial through the means at the
//! three nearest full windows one revolution apart (two or one on a short path), extrapolated
//! by at most a revolution: exact for a sag quadratic in φ and, like the means themselves,
//! blind to whole harmonics with amplitudes linear in ρ (with two windows the extrapolation
//! errs by at most |S″|·f²). A path shorter than two revolutions gets the least-squares line
//! through all its samples.
//!
//! The residual `z − S` passes a tone of ν cycles per revolution with the gain
//! `1 − T(ν)`, `T(ν) = (sin πν / (M·sin(πν/M)))²` ([`residual_gain`]): 1 at whole ν, at
//! least 0.95 from ν = 1 on.

use crate::parallel::{fill_chunks, fill_each, map_indices, map_parts, read_ahead, workers};
use crate::path::{IndexedPoints, PathPoint, Spiral, WalkedRule};
use std::borrow::Cow;
use std::convert::Infallible;
use std::f64::consts::TAU;
use std::ops::Range;
use thiserror::Error;

/// Grid samples made at a time where a record of the grid is made a block at a time
/// ([`UniformSignal::narrow_residual`], [`UniformSignal::symmetric_part_at_points`]): 2 MiB.
pub const BLOCK_SAMPLES: usize = 1 << 18;

/// The smallest number of grid samples per revolution.
pub const MIN_SAMPLES_PER_REV: usize = 8;

/// The grid has at most this many samples per path point (and at least 4096 in all).
pub const MAX_GRID_PER_POINT: usize = 4;

/// The compensated path as three columns, one row per path point: the spindle angle θ as the
/// path gives it (turned cumulatively, radians; [`Self::theta`]), the radius ρ (X, mm;
/// [`Self::rho`]) and the commanded Z. The analysis reads the angle turned since the first
/// point, `|θ_i − θ_0|` ([`Self::angle`]), which must not decrease.
#[derive(Debug, Clone, Default)]
pub struct PathSignal {
    angles_radii: AnglesRadii,
    /// Commanded Z (the tool tip), mm.
    pub z_mm: Vec<f64>,
}

/// θ and ρ of the points: held (16 bytes a point); or, where every point is its spiral's
/// point of the same index (one-way compensation of a constant-angle spiral or of one given
/// as a list), its spiral's (nothing held); or, where every point is a point of a spiral
/// walked by its step rule (one-way compensation of a constant-arc, HCAA or adaptive spiral),
/// the spiral's point at the φ held for it (φ, 8 bytes a point) ([`PathSignal::for_spiral`]).
#[derive(Debug, Clone)]
enum AnglesRadii {
    Held {
        theta_rad: Vec<f64>,
        rho_mm: Vec<f64>,
    },
    Indexed(IndexedPoints),
    Walked {
        rule: WalkedRule,
        phi: Vec<f64>,
    },
}

impl Default for AnglesRadii {
    fn default() -> Self {
        AnglesRadii::Held {
            theta_rad: Vec::new(),
            rho_mm: Vec::new(),
        }
    }
}

/// A path that cannot be analysed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SignalError {
    /// Fewer than three points, or no angle turned.
    ///
    /// ```
    /// let s = spiralcam::dynamics::path_signal::PathSignal::default();
    /// assert_eq!(s.check().unwrap_err().to_string(),
    ///            "the path has 0 points over 0 rad: the analysis needs at least 3 points over a positive angle");
    /// ```
    #[error(
        "the path has {points} points over {span_rad} rad: the analysis needs at least 3 points over a positive angle"
    )]
    TooShort {
        /// Points in the path.
        points: usize,
        /// Angle turned, radians.
        span_rad: f64,
    },
    /// The columns have different lengths.
    ///
    /// ```
    /// let s = spiralcam::dynamics::path_signal::PathSignal::from_columns(vec![0.0, 1.0, 2.0], vec![1.0; 3], vec![0.0; 2]);
    /// assert!(s.check().unwrap_err().to_string().starts_with("the path's columns differ"));
    /// ```
    #[error(
        "the path's columns differ in length: {angles} angles, {radii} radii, {heights} heights"
    )]
    Ragged {
        /// Number of angles θ.
        angles: usize,
        /// Number of radii ρ.
        radii: usize,
        /// Length of `z_mm`.
        heights: usize,
    },
    /// A value is NaN or infinite.
    ///
    /// ```
    /// let s = spiralcam::dynamics::path_signal::PathSignal::from_columns(vec![0.0, 1.0, 2.0], vec![1.0; 3], vec![0.0, f64::NAN, 0.0]);
    /// assert_eq!(s.check().unwrap_err().to_string(), "the path has a value that is not finite at point 1");
    /// ```
    #[error("the path has a value that is not finite at point {index}")]
    NotFinite {
        /// The point.
        index: usize,
    },
    /// The spindle angle goes back (e.g. two-way compensation near the centre moves C against
    /// the spindle): time would run backwards.
    ///
    /// ```
    /// let s = spiralcam::dynamics::path_signal::PathSignal::from_columns(vec![0.0, 1.0, 0.5], vec![1.0; 3], vec![0.0; 3]);
    /// assert!(s.check().unwrap_err().to_string().starts_with("the spindle angle goes back at point 2"));
    /// ```
    #[error(
        "the spindle angle goes back at point {index}: the frequency analysis and the split need the angle to advance along the path"
    )]
    NotAdvancing {
        /// The point.
        index: usize,
    },
}

/// The largest slope and curvature of a channel against the spindle angle, with where they are.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AngleExtremes {
    /// Largest |dv/dφ| over the segments, mm/rad (× ω: velocity, mm/s).
    pub slope_mm_per_rad: f64,
    /// Point at the start of that segment.
    pub slope_at: usize,
    /// Largest |d²v/dφ²| over the interior points, mm/rad² (× ω²: acceleration, mm/s²).
    pub curvature_mm_per_rad2: f64,
    /// Point where it is.
    pub curvature_at: usize,
}

impl PathSignal {
    /// An empty signal with room for `n` points.
    pub fn with_capacity(n: usize) -> Self {
        Self {
            angles_radii: AnglesRadii::Held {
                theta_rad: Vec::with_capacity(n),
                rho_mm: Vec::with_capacity(n),
            },
            z_mm: Vec::with_capacity(n),
        }
    }

    /// An empty signal with room for `n` points of a path along `spiral`. Where the spiral's
    /// points are a function of their index ([`Spiral::indexed_points`]: constant angle, or a
    /// list the spiral holds), their angles and radii are not held while the points pushed are
    /// the spiral's own (point `i` at the spiral's point `i`, as one-way compensation leaves
    /// them): 8 bytes a point instead of 24. Where the spiral is walked by its step rule on the
    /// plane ([`Spiral::walked_rule`]: constant arc, HCAA, adaptive), each point's φ is held
    /// while the points pushed lie on the spiral ([`WalkedRule::phi_of`]): 16 bytes a point.
    /// The first point that is not (two-way compensation moves both) has them held from then
    /// on, those before it computed again, so the columns are always what was pushed.
    pub fn for_spiral(spiral: &Spiral, n: usize) -> Self {
        let angles_radii = match (spiral.indexed_points(), spiral.walked_rule()) {
            (Some(points), _) => AnglesRadii::Indexed(points),
            (None, Some(rule)) => AnglesRadii::Walked {
                rule,
                phi: Vec::with_capacity(n),
            },
            (None, None) => return Self::with_capacity(n),
        };
        Self {
            angles_radii,
            z_mm: Vec::with_capacity(n),
        }
    }

    /// The bytes a point of a path along `spiral` takes in [`Self::for_spiral`]'s signal
    /// where the points are the spiral's own (`on_spiral`: one-way compensation): 8 where
    /// the spiral gives them by the index, 16 where a point's φ is held, 24 where its θ, ρ and
    /// z are.
    pub fn bytes_per_point(spiral: &Spiral, on_spiral: bool) -> u64 {
        if !on_spiral {
            return 24;
        }
        // As `for_spiral` decides, the one place that does.
        match Self::for_spiral(spiral, 0).angles_radii {
            AnglesRadii::Held { .. } => 24,
            AnglesRadii::Indexed(_) => 8,
            AnglesRadii::Walked { .. } => 16,
        }
    }

    /// The signal of the columns θ (radians), ρ and z (mm), one value a point.
    pub fn from_columns(theta_rad: Vec<f64>, rho_mm: Vec<f64>, z_mm: Vec<f64>) -> Self {
        Self {
            angles_radii: AnglesRadii::Held { theta_rad, rho_mm },
            z_mm,
        }
    }

    /// The signal of a path's points.
    pub fn from_points(points: impl IntoIterator<Item = PathPoint>) -> Self {
        let mut s = Self::default();
        for p in points {
            s.push(&p);
        }
        s
    }

    /// Appends a point.
    pub fn push(&mut self, p: &PathPoint) {
        let i = self.z_mm.len();
        match &mut self.angles_radii {
            AnglesRadii::Held { theta_rad, rho_mm } => {
                theta_rad.push(p.theta);
                rho_mm.push(p.rho);
            }
            AnglesRadii::Indexed(points) => {
                let own = (i as u64 <= points.last()).then(|| points.at(i as u64));
                let same = own.is_some_and(|q| {
                    q.theta.to_bits() == p.theta.to_bits() && q.rho.to_bits() == p.rho.to_bits()
                });
                if !same {
                    self.hold_columns(p);
                }
            }
            AnglesRadii::Walked { rule, phi } => match rule.phi_of(p.theta, p.rho) {
                Some(x) => phi.push(x),
                None => self.hold_columns(p),
            },
        }
        self.z_mm.push(p.z);
    }

    /// Holds the angles and radii from now on: those of the points so far computed, then
    /// `p`'s.
    fn hold_columns(&mut self, p: &PathPoint) {
        let (i, n) = (self.z_mm.len(), self.z_mm.capacity());
        let (mut theta_rad, mut rho_mm) = (Vec::with_capacity(n), Vec::with_capacity(n));
        theta_rad.extend((0..i).map(|k| self.theta(k)));
        rho_mm.extend((0..i).map(|k| self.rho(k)));
        theta_rad.push(p.theta);
        rho_mm.push(p.rho);
        self.angles_radii = AnglesRadii::Held { theta_rad, rho_mm };
    }

    /// Whether the angles and radii are computed from the points' indices, not held
    /// ([`Self::for_spiral`]).
    pub fn is_indexed(&self) -> bool {
        matches!(self.angles_radii, AnglesRadii::Indexed(_))
    }

    /// Whether the angles and radii are computed from each point's φ on its spiral, φ alone
    /// held ([`Self::for_spiral`]).
    pub fn is_walked(&self) -> bool {
        matches!(self.angles_radii, AnglesRadii::Walked { .. })
    }

    /// The spindle angle θ of point `i`, radians.
    #[inline]
    pub fn theta(&self, i: usize) -> f64 {
        match &self.angles_radii {
            AnglesRadii::Held { theta_rad, .. } => theta_rad[i],
            AnglesRadii::Indexed(points) => points.at(i as u64).theta,
            AnglesRadii::Walked { rule, phi } => rule.at(phi[i]).theta,
        }
    }

    /// The radius ρ of point `i`, mm.
    #[inline]
    pub fn rho(&self, i: usize) -> f64 {
        match &self.angles_radii {
            AnglesRadii::Held { rho_mm, .. } => rho_mm[i],
            AnglesRadii::Indexed(points) => points.at(i as u64).rho,
            AnglesRadii::Walked { rule, phi } => rule.at(phi[i]).rho,
        }
    }

    /// The angles θ and radii ρ of every point as columns: borrowed where they are held,
    /// computed (16 bytes a point) where they are not.
    pub fn angles_and_radii(&self) -> (Cow<'_, [f64]>, Cow<'_, [f64]>) {
        match &self.angles_radii {
            AnglesRadii::Held { theta_rad, rho_mm } => {
                (Cow::Borrowed(theta_rad), Cow::Borrowed(rho_mm))
            }
            AnglesRadii::Indexed(_) | AnglesRadii::Walked { .. } => (
                (0..self.len()).map(|i| self.theta(i)).collect(),
                (0..self.len()).map(|i| self.rho(i)).collect(),
            ),
        }
    }

    /// The angle turned from the first point to point `i`, `|θ_i − θ_0|`, radians, whatever
    /// the direction.
    #[inline]
    pub fn angle(&self, i: usize) -> f64 {
        (self.theta(i) - self.theta(0)).abs()
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.z_mm.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.z_mm.is_empty()
    }

    /// Angle turned from the first point to the last, radians.
    pub fn span_rad(&self) -> f64 {
        match self.columns().0 {
            0 => 0.0,
            n => self.angle(n - 1),
        }
    }

    /// The numbers of angles and of radii: the points', unless held columns are ragged.
    fn columns(&self) -> (usize, usize) {
        match &self.angles_radii {
            AnglesRadii::Held { theta_rad, rho_mm } => (theta_rad.len(), rho_mm.len()),
            AnglesRadii::Indexed(_) => (self.len(), self.len()),
            AnglesRadii::Walked { phi, .. } => (phi.len(), phi.len()),
        }
    }

    /// Revolutions of the path.
    pub fn revolutions(&self) -> f64 {
        self.span_rad() / TAU
    }

    /// Duration of the path at `spindle_rpm`, seconds.
    pub fn duration_s(&self, spindle_rpm: f64) -> f64 {
        self.span_rad() / omega(spindle_rpm)
    }

    /// Checks that the columns agree, every value is finite, the angle never goes back and the
    /// path has at least 3 points over a positive angle.
    pub fn check(&self) -> Result<(), SignalError> {
        let ((a, r), z) = (self.columns(), self.z_mm.len());
        if a != r || a != z {
            return Err(SignalError::Ragged {
                angles: a,
                radii: r,
                heights: z,
            });
        }
        let finite = |i: usize| {
            self.theta(i).is_finite() && self.rho(i).is_finite() && self.z_mm[i].is_finite()
        };
        // The first point not finite, and the first whose angle goes back, over parts of the
        // path on the cores.
        let back = |&i: &usize| i > 0 && self.angle(i) < self.angle(i - 1);
        let first_in = |points: Range<usize>| match points.clone().find(|&i| !finite(i)) {
            Some(i) => (Some(i), None),
            None => (None, points.clone().find(back)),
        };
        let parts = map_parts(z, first_in);
        if let Some(index) = parts.iter().find_map(|p| p.0) {
            return Err(SignalError::NotFinite { index });
        }
        if let Some(i) = parts.iter().find_map(|p| p.1) {
            return Err(SignalError::NotAdvancing { index: i });
        }
        let span_rad = self.span_rad();
        if self.len() < 3 || span_rad <= 0.0 {
            return Err(SignalError::TooShort {
                points: self.len(),
                span_rad,
            });
        }
        Ok(())
    }

    /// Samples per revolution of the uniform grid: the densest revolution of the path (its
    /// mean step), at least [`MIN_SAMPLES_PER_REV`], at most what keeps the grid within
    /// [`MAX_GRID_PER_POINT`] samples per path point.
    fn samples_per_rev(&self) -> usize {
        self.samples_per_rev_of(0..self.len())
    }

    /// [`Self::samples_per_rev`] of the points `points` alone: the densest of their
    /// revolutions (counted from the first point of the path, the last and first of them
    /// partial), within [`MAX_GRID_PER_POINT`] samples a point of theirs over their angle.
    fn samples_per_rev_of(&self, points: Range<usize>) -> usize {
        let mut densest = MIN_SAMPLES_PER_REV as f64;
        let mut first = points.start;
        while first < points.end {
            let rev = (self.angle(first) / TAU).floor();
            let last = first_past(first, points.end, |i| (self.angle(i) / TAU).floor() <= rev) - 1;
            let span = self.angle(last) - self.angle(first);
            if last > first && span > 0.0 {
                densest = densest.max(TAU * (last - first) as f64 / span);
            }
            first = last + 1;
        }
        let budget = (MAX_GRID_PER_POINT * points.len()).max(4096) as f64;
        let span = match points.len() {
            0 => 0.0,
            _ => self.angle(points.end - 1) - self.angle(points.start),
        };
        let cap = (budget * TAU / span.max(f64::MIN_POSITIVE)).floor();
        (densest - 1e-6)
            .ceil()
            .min(cap)
            .max(MIN_SAMPLES_PER_REV as f64) as usize
    }

    /// The stretch of the path from angle `from_rad` to `to_rad` (turned since the first
    /// point) on a uniform grid of its own: the densest sampling of the points in it and of
    /// one beyond either end (the rule of [`Self::uniform`]'s rate, on them alone), and the
    /// samples of that grid from the last at or before `from_rad` to the first at or after
    /// `to_rad`, within the path's span. A path that cannot be resampled (fewer than two
    /// points) has an empty stretch.
    pub fn stretch(&self, from_rad: f64, to_rad: f64) -> Stretch {
        let n = self.columns().0.min(self.len());
        if n < 2 {
            return Stretch::default();
        }
        let first = first_past(0, n, |i| self.angle(i) < from_rad).saturating_sub(1);
        let last = first_past(first, n, |i| self.angle(i) <= to_rad).min(n - 1);
        let m = self.samples_per_rev_of(first..last + 1);
        let step = TAU / m as f64;
        let count = grid_count(self.span_rad(), step);
        // The quotients rounded, then mended where a product falls on the wrong side.
        let mut lo = ((from_rad / step).floor().max(0.0) as usize).min(count - 1);
        if lo > 0 && lo as f64 * step > from_rad {
            lo -= 1;
        }
        let mut hi = ((to_rad / step).ceil().max(0.0) as usize).clamp(lo, count - 1);
        if hi + 1 < count && (hi as f64 * step) < to_rad {
            hi += 1;
        }
        Stretch {
            samples_per_rev: m,
            first: lo,
            len: hi - lo + 1,
        }
    }

    /// `value(i)` of the points at the samples of `stretch` ([`Self::stretch`]): to the bit
    /// what [`Self::values_at`] its rate gives at those samples.
    pub fn stretch_values(
        &self,
        stretch: &Stretch,
        value: impl Fn(usize) -> f64 + Sync,
    ) -> Vec<f64> {
        match self.len() >= 2 && stretch.samples_per_rev > 0 {
            true => self.resample_samples(value, stretch.samples_per_rev, stretch.samples()),
            false => Vec::new(),
        }
    }

    /// The path resampled at equal angle steps (see the module docs).
    pub fn uniform(&self) -> Result<UniformSignal, SignalError> {
        self.check()?;
        Ok(self.uniform_checked())
    }

    /// [`Self::uniform`] of a path already checked ([`Self::check`]).
    pub(crate) fn uniform_checked(&self) -> UniformSignal {
        let m = self.samples_per_rev();
        let z_mm = self.resample(|i| self.z_mm[i], m);
        UniformSignal {
            samples_per_rev: m,
            samples: z_mm.len(),
            z_mm,
        }
    }

    /// `values` (one per point) on the grid of [`Self::uniform`]; empty when the path cannot be
    /// resampled. The slide's share of a split path is analysed on the path's own grid this
    /// way, without a copy of the path.
    pub fn uniform_values(&self, values: &[f64]) -> Vec<f64> {
        match self.check() {
            Ok(()) => self.values_at(self.samples_per_rev(), values),
            Err(_) => Vec::new(),
        }
    }

    /// The radii at `samples_per_rev` samples a revolution: with the
    /// [`UniformSignal::samples_per_rev`] of the grid [`Self::uniform`] made of this path, that
    /// grid's radii to the bit, without checking the path again (a pass over it) or finding M
    /// again (another).
    pub fn radii_at(&self, samples_per_rev: usize) -> Vec<f64> {
        self.values_at_by(samples_per_rev, |i| self.rho(i))
    }

    /// `values` (one per point) at `samples_per_rev` samples a revolution:
    /// [`Self::uniform_values`] without the check, as [`Self::radii_at`]; empty when there is
    /// not one value a point.
    pub fn values_at(&self, samples_per_rev: usize, values: &[f64]) -> Vec<f64> {
        match values.len() == self.len() {
            true => self.values_at_by(samples_per_rev, |i| values[i]),
            false => Vec::new(),
        }
    }

    /// [`Self::resample`] where it has the two points and the positive rate it needs (else
    /// empty).
    pub(crate) fn values_at_by(
        &self,
        samples_per_rev: usize,
        value: impl Fn(usize) -> f64 + Sync,
    ) -> Vec<f64> {
        match self.len() >= 2 && samples_per_rev > 0 {
            true => self.resample(value, samples_per_rev),
            false => Vec::new(),
        }
    }

    /// The values `value(i)` of the points linearly interpolated at `m` samples per revolution
    /// from the first point.
    fn resample(&self, value: impl Fn(usize) -> f64 + Sync, m: usize) -> Vec<f64> {
        let count = grid_count(self.span_rad(), TAU / m as f64);
        self.resample_samples(value, m, 0..count)
    }

    /// [`Self::resample`]'s samples `samples` alone, to the bit: in contiguous parts on
    /// [`workers`] threads, each part walking from the interval the walk from the first point
    /// would stop at for its first sample.
    fn resample_samples(
        &self,
        value: impl Fn(usize) -> f64 + Sync,
        m: usize,
        samples: Range<usize>,
    ) -> Vec<f64> {
        let mut out = vec![0.0; samples.len()];
        self.resample_with(value, m, samples.start, &mut out, |slot, v| *slot = v);
        out
    }

    /// The samples `first … first + out.len() − 1` of [`Self::resample`], each handed to
    /// `set(slot, value)` with its slot of `out`, in contiguous parts on [`workers`] threads.
    pub(crate) fn resample_with(
        &self,
        value: impl Fn(usize) -> f64 + Sync,
        m: usize,
        first: usize,
        out: &mut [f64],
        set: impl Fn(&mut f64, f64) + Sync,
    ) {
        let Ok(()) = fill_chunks(out, |start, part| {
            self.resample_into(&value, m, first + start, part, &set);
            Ok::<(), Infallible>(())
        });
    }

    /// [`Self::resample_with`] of one part, on the calling thread.
    fn resample_into(
        &self,
        value: impl Fn(usize) -> f64,
        m: usize,
        first: usize,
        out: &mut [f64],
        set: impl Fn(&mut f64, f64),
    ) {
        let step = TAU / m as f64;
        // The interval k … k + 1 with its ends' angles and values, read again only as k moves:
        // for the first sample, the interval the walk from the first point would stop at.
        let start = first as f64 * step;
        let mut k = (first_past(1, self.len(), |i| self.angle(i) < start) - 1).min(self.len() - 2);
        let (mut a0, mut a1) = (self.angle(k), self.angle(k + 1));
        let (mut v0, mut v1) = (value(k), value(k + 1));
        for (j, slot) in (first..).zip(out.iter_mut()) {
            let phi = j as f64 * step;
            while k + 2 < self.len() && a1 < phi {
                k += 1;
                (a0, v0) = (a1, v1);
                (a1, v1) = (self.angle(k + 1), value(k + 1));
            }
            let t = if a1 > a0 {
                ((phi - a0) / (a1 - a0)).clamp(0.0, 1.0)
            } else {
                1.0
            };
            set(slot, v0 + t * (v1 - v0));
        }
    }

    /// The largest slope and curvature of `values` (one per point) against the spindle angle,
    /// by the finite differences of the piecewise-linear motion: the slope of each segment, and
    /// at each interior point the change of slope over half the two segments
    /// (`2·(s_{i+½} − s_{i−½})/(φ_{i+1} − φ_{i−1})`, exact for a parabola). Segments of zero
    /// angle are skipped.
    pub fn angle_extremes(&self, values: &[f64]) -> AngleExtremes {
        let n = values.len().min(self.columns().0);
        let mut e = AngleExtremes::default();
        let mut prev: Option<(f64, f64)> = None; // (slope, angle step) of the segment before
        for i in 0..n.saturating_sub(1) {
            let da = self.angle(i + 1) - self.angle(i);
            if da <= 0.0 {
                continue;
            }
            let s = (values[i + 1] - values[i]) / da;
            if s.abs() > e.slope_mm_per_rad {
                e.slope_mm_per_rad = s.abs();
                e.slope_at = i;
            }
            if let Some((s0, da0)) = prev {
                let c = 2.0 * (s - s0) / (da + da0);
                if c.abs() > e.curvature_mm_per_rad2 {
                    e.curvature_mm_per_rad2 = c.abs();
                    e.curvature_at = i;
                }
            }
            prev = Some((s, da));
        }
        e
    }
}

/// The samples of a grid of angle step `step` from 0 over `span_rad`: every step within it
/// (a millionth of a step of slack), at least two.
fn grid_count(span_rad: f64, step: f64) -> usize {
    ((span_rad / step + 1e-6).floor() as usize + 1).max(2)
}

/// A stretch of a path on a uniform grid of its own ([`PathSignal::stretch`]): the samples
/// `first … first + len − 1` of the path's grid at `samples_per_rev`, sample j at
/// `φ_j = j·2π/samples_per_rev` from the first point.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stretch {
    /// Samples per revolution M.
    pub samples_per_rev: usize,
    /// The first sample's number on the path's grid at M.
    pub first: usize,
    /// Number of samples.
    pub len: usize,
}

impl Stretch {
    /// The samples' numbers on the path's grid at M.
    pub fn samples(&self) -> Range<usize> {
        self.first..self.first + self.len
    }

    /// The samples of a grid of the stretch's rate as [`UniformSignal`] (no columns held): its
    /// symmetric part and the like are computed as for a whole path's grid.
    pub fn grid(&self) -> UniformSignal {
        UniformSignal {
            samples_per_rev: self.samples_per_rev,
            samples: self.len,
            z_mm: Vec::new(),
        }
    }
}

/// The first index in `from..to` where `before` stops holding (`to` if it never does), for a
/// `before` that holds up to some index and not after it (a binary search).
pub(crate) fn first_past(from: usize, to: usize, before: impl Fn(usize) -> bool) -> usize {
    let (mut lo, mut hi) = (from, to);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if before(mid) { lo = mid + 1 } else { hi = mid }
    }
    lo
}

/// The gain of the non-symmetric residual `z − S` for a tone of `cycles_per_rev` on a grid of
/// `samples_per_rev` (module docs).
pub fn residual_gain(cycles_per_rev: f64, samples_per_rev: usize) -> f64 {
    let m = samples_per_rev as f64;
    let x = std::f64::consts::PI * cycles_per_rev;
    let den = m * (x / m).sin();
    if den.abs() < 1e-300 {
        return 0.0;
    }
    1.0 - (x.sin() / den).powi(2)
}

/// The smallest and largest of `values`; `(∞, −∞)` for none.
pub fn extremes(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
}

/// [`extremes`] of `value(i)` for `i` in `0..n`, in contiguous parts on [`workers`] threads
/// (the smallest and largest do not depend on the order they are met in).
pub fn extremes_at(n: usize, value: impl Fn(usize) -> f64 + Sync) -> (f64, f64) {
    let parts = workers().clamp(1, n.max(1));
    let size = n.div_ceil(parts);
    let mut found = vec![(f64::INFINITY, f64::NEG_INFINITY); parts];
    let Ok(()) = fill_each(&mut found, |k| {
        Ok::<_, Infallible>(extremes((k * size..n.min((k + 1) * size)).map(&value)))
    });
    merged(found)
}

/// The smallest and largest of the `(smallest, largest)` found in parts (a part with no
/// values found `(∞, −∞)`).
pub(crate) fn merged(parts: impl IntoIterator<Item = (f64, f64)>) -> (f64, f64) {
    (parts.into_iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (lo, hi)| {
        (a.min(lo), b.max(hi))
    })
}

/// [`peak_to_valley`] of `value(i)` for `i` in `0..n` ([`extremes_at`]).
pub fn peak_to_valley_at(n: usize, value: impl Fn(usize) -> f64 + Sync) -> f64 {
    spread(extremes_at(n, value))
}

/// Largest minus smallest of `values` (0 for none).
pub fn peak_to_valley(values: impl IntoIterator<Item = f64>) -> f64 {
    spread(extremes(values))
}

/// Largest minus smallest of `(smallest, largest)` (0 for none).
pub(crate) fn spread((lo, hi): (f64, f64)) -> f64 {
    if hi >= lo { hi - lo } else { 0.0 }
}

/// Angular speed of the spindle, rad/s.
pub fn omega(spindle_rpm: f64) -> f64 {
    TAU * spindle_rpm / 60.0
}

/// Hertz of `cycles_per_rev` cycles per revolution at `spindle_rpm`.
pub fn hz(cycles_per_rev: f64, spindle_rpm: f64) -> f64 {
    cycles_per_rev * spindle_rpm / 60.0
}

/// A path resampled at `samples_per_rev` equal angle steps from its first point:
/// sample j lies at `φ_j = j·2π/samples_per_rev`.
#[derive(Debug, Clone, PartialEq)]
pub struct UniformSignal {
    /// Samples per revolution M.
    pub samples_per_rev: usize,
    /// Number of samples, whether or not the columns below are held.
    samples: usize,
    /// Z at the samples, mm (the dynamics let it go where they can make it again:
    /// [`PathSignal::values_at`] of the path's heights). The radii are made where they are
    /// used ([`PathSignal::radii_at`]).
    pub z_mm: Vec<f64>,
}

impl UniformSignal {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.samples
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.samples == 0
    }

    /// The heights at the samples: [`Self::z_mm`], or where they were let go (left empty) made
    /// again from `signal`, the path this grid was made from ([`PathSignal::values_at`]: the
    /// same values to the bit).
    pub fn heights(&self, signal: &PathSignal) -> Cow<'_, [f64]> {
        if self.z_mm.len() == self.samples {
            Cow::Borrowed(&self.z_mm)
        } else {
            Cow::Owned(signal.values_at(self.samples_per_rev, &signal.z_mm))
        }
    }

    /// Angle step, radians.
    pub fn step_rad(&self) -> f64 {
        TAU / self.samples_per_rev as f64
    }

    /// The rotationally symmetric part of `values` (one per sample; see the module docs).
    pub fn symmetric_part(&self, values: &[f64]) -> Vec<f64> {
        let (n, m) = (values.len(), self.samples_per_rev);
        if n < 2 * m - 1 {
            return least_squares_line(values);
        }
        let mut out = vec![0.0; n];
        let mut ends = EndMeans::new(n, m);
        triangle_means(
            n,
            m,
            |j| values[j],
            |c, mean, _| {
                out[c] = mean;
                ends.offer(c, mean);
            },
        );
        let at = ends.extrapolation();
        for (j, v) in out.iter_mut().enumerate() {
            if let Some(e) = at(j) {
                *v = e;
            }
        }
        out
    }

    /// The first and the last `count` values of [`Self::symmetric_part`] of `values`, to the
    /// bit, without the part between them.
    pub fn symmetric_part_at_ends(&self, values: &[f64], count: usize) -> (Vec<f64>, Vec<f64>) {
        let (n, m) = (values.len(), self.samples_per_rev);
        let count = count.min(n);
        if n < 2 * m - 1 {
            let line = least_squares_line(values);
            return (line[..count].to_vec(), line[n - count..].to_vec());
        }
        let (mut head, mut tail) = (vec![0.0; count], vec![0.0; count]);
        let mut ends = EndMeans::new(n, m);
        triangle_means(
            n,
            m,
            |j| values[j],
            |c, mean, _| {
                if c < count {
                    head[c] = mean;
                }
                if c + count >= n {
                    tail[c + count - n] = mean;
                }
                ends.offer(c, mean);
            },
        );
        let at = ends.extrapolation();
        let samples = (0..count).chain(n - count..n);
        for (j, v) in samples.zip(head.iter_mut().chain(tail.iter_mut())) {
            if let Some(e) = at(j) {
                *v = e;
            }
        }
        (head, tail)
    }

    /// `values` less their [`Self::symmetric_part`], in their place, to the bit: each mean is
    /// subtracted as the running sums hand it over, and the ends (polynomials through three
    /// means each) last, so the record is never held twice.
    pub fn subtract_symmetric_part(&self, values: &mut [f64]) {
        let (n, m) = (values.len(), self.samples_per_rev);
        if n < 2 * m - 1 {
            let line = least_squares_line(values);
            values.iter_mut().zip(&line).for_each(|(v, s)| *v -= s);
            return;
        }
        let mut ends = EndMeans::new(n, m);
        let cells = std::cell::Cell::from_mut(values).as_slice_of_cells();
        // Each mean is subtracted as it is handed over with its sample: the running sums read
        // no sample up to its centre again.
        triangle_means(
            n,
            m,
            |j| cells[j].get(),
            |c, mean, sample| {
                ends.offer(c, mean);
                cells[c].set(sample - mean);
            },
        );
        let at = ends.extrapolation();
        for (j, v) in values.iter_mut().enumerate() {
            if let Some(e) = at(j) {
                *v -= e;
            }
        }
    }

    /// [`Self::symmetric_part`] of the heights of `signal` (the path this grid was made from)
    /// interpolated at its points ([`Self::interpolate`]), to the bit, without a record of the
    /// grid: the heights are made `block` at a time ([`PathSignal::values_at`]'s samples) and
    /// the triangle means run over them twice, first for the means the ends are extrapolated
    /// from, then handing the symmetric part over sample by sample, each point's value made
    /// once both ends of its grid interval are known. The symmetric split's Z at the points.
    pub fn symmetric_part_at_points(&self, signal: &PathSignal, block: usize) -> Vec<f64> {
        let (n, m) = (self.samples, self.samples_per_rev);
        if n < 2 * m - 1 || signal.len() < 2 {
            let symmetric = self.symmetric_part(&self.heights(signal));
            return map_indices(signal.len(), |i| {
                self.interpolate(&symmetric, signal.angle(i))
            });
        }
        let fill = |first: usize, out: &mut [f64]| {
            signal.resample_with(|i| signal.z_mm[i], m, first, out, |slot, v| *slot = v);
        };
        let block = block.max(m);
        let means = |each: &mut dyn FnMut(usize, f64)| {
            read_ahead(n, block, fill, |source| {
                let mut window = Window::new(n, m + 1, block, source);
                triangle_means(n, m, |j| window.value(j), |c, mean, _| each(c, mean));
            });
        };
        let mut ends = EndMeans::new(n, m);
        means(&mut |c, mean| ends.offer(c, mean));
        let at = ends.extrapolation();
        let mut z = Vec::with_capacity(signal.len());
        // The part at the sample before, and the next point's interval.
        let mut before = 0.0;
        let mut point = (0..signal.len())
            .map(|i| self.interval(n, signal.angle(i)))
            .peekable();
        let mut hand = |j: usize, part: f64| {
            while let Some(&(_, t)) = point.peek().filter(|&&(k, _)| k < j) {
                z.push(before + t * (part - before));
                point.next();
            }
            before = part;
        };
        for j in 0..m - 1 {
            hand(j, at(j).unwrap_or(0.0));
        }
        means(&mut |c, mean| hand(c, mean));
        for j in n - m + 1..n {
            hand(j, at(j).unwrap_or(0.0));
        }
        z
    }

    /// [`Self::subtract_symmetric_part`] of the `n` samples that `fill(first, block)` writes
    /// (the samples `first …` in `block`), each rounded to single precision: to the bit the
    /// double-precision residual rounded. The samples are made `block` at a time, the next
    /// blocks on a second core while the triangle means run ([`read_ahead`]), and held a block
    /// and a revolution at a time (the means read a revolution back), so that only the
    /// single-precision record is held whole: for a bandwidth figure of a long grid.
    pub fn narrow_residual(
        &self,
        n: usize,
        block: usize,
        fill: impl Fn(usize, &mut [f64]) + Sync,
    ) -> Vec<f32> {
        let m = self.samples_per_rev;
        if n < 2 * m - 1 {
            let mut values = vec![0.0; n];
            fill(0, &mut values);
            self.subtract_symmetric_part(&mut values);
            return values.into_iter().map(|v| v as f32).collect();
        }
        let block = block.max(m);
        read_ahead(n, block, fill, |source| {
            let mut window = Window::new(n, m + 1, block, source);
            let head: Vec<f64> = (0..m - 1).map(|j| window.value(j)).collect();
            let mut out = vec![0.0f32; n];
            let mut ends = EndMeans::new(n, m);
            triangle_means(
                n,
                m,
                |j| window.value(j),
                |c, mean, sample| {
                    ends.offer(c, mean);
                    out[c] = (sample - mean) as f32;
                },
            );
            let at = ends.extrapolation();
            for j in (0..m - 1).chain(n - m + 1..n) {
                if let Some(e) = at(j) {
                    let v = head.get(j).copied().unwrap_or_else(|| window.value(j));
                    out[j] = (v - e) as f32;
                }
            }
            out
        })
    }

    /// `values` on the grid, linearly interpolated at the path's angles (the last grid interval
    /// extended by at most one step past the grid's end).
    pub fn at_path(&self, values: &[f64], angle_rad: &[f64]) -> Vec<f64> {
        angle_rad
            .iter()
            .map(|&a| self.interpolate(values, a))
            .collect()
    }

    /// `values` on the grid, linearly interpolated at the angle `angle_rad` as [`Self::at_path`]
    /// does (0 for no values).
    pub fn interpolate(&self, values: &[f64], angle_rad: f64) -> f64 {
        let n = values.len();
        if n < 2 {
            return values.first().copied().unwrap_or(0.0);
        }
        let (j, t) = self.interval(n, angle_rad);
        values[j] + t * (values[j + 1] - values[j])
    }

    /// The interval `j … j + 1` of a grid of `n ≥ 2` samples [`Self::interpolate`] reads at the
    /// angle `angle_rad`, and the fraction `t` of a step past sample j.
    pub fn interval(&self, n: usize, angle_rad: f64) -> (usize, f64) {
        let x = angle_rad / self.step_rad();
        let j = (x.floor().max(0.0) as usize).min(n - 2);
        (j, x - j as f64)
    }
}

/// The two-revolution triangle means of the `n` samples `value(j)` (`m` a revolution, n ≥
/// 2m − 1) at the centres m − 1 … n − m, handed to `each(centre, mean, sample)` in order with
/// the centre's sample. One-revolution moving sums B_i (of samples i … i + M − 1), then their
/// moving sums (B_k … B_{k+M−1}): the triangle of half-width M around sample k + M − 1, by
/// running sums (rounding grows like √n·ε, not n²·ε as with prefix sums of prefix sums). Each
/// B_i leaves the second sum M after it entered, so one revolution of them is kept, in a ring
/// (slot i mod M), not the whole record. Once the mean at a centre c is handed over, no
/// sample up to c is read again.
fn triangle_means(
    n: usize,
    m: usize,
    mut value: impl FnMut(usize) -> f64,
    mut each: impl FnMut(usize, f64, f64),
) {
    let base = value(0);
    let mut ring = Vec::with_capacity(m);
    let mut sum: f64 = (0..m).map(|j| value(j) - base).sum();
    ring.push(sum);
    for j in m..2 * m - 1 {
        sum += value(j) - value(j - m);
        ring.push(sum);
    }
    let mut sum2: f64 = ring.iter().sum();
    let norm = (m * m) as f64;
    // The sample at the centre is the one the next step's sum lets go (j − M = c).
    let mut centre = value(m - 1);
    each(m - 1, base + sum2 / norm, centre);
    // B_{k−1}'s slot, (k − 1) mod M, counted round rather than divided for.
    let mut slot = 0;
    for k in 1..=n + 1 - 2 * m {
        // B_{k+M−1} in, B_{k−1} out.
        let j = k + 2 * m - 2;
        sum += value(j) - centre;
        sum2 += sum - ring[slot];
        ring[slot] = sum;
        slot = if slot + 1 == m { 0 } else { slot + 1 };
        let c = k + m - 1;
        centre = value(c);
        each(c, base + sum2 / norm, centre);
    }
}

/// Samples `lo … lo + len − 1` of a record of `n` made on demand by `fill(first, block)`, in
/// order: a sample past the end makes the next `block` samples, keeping the `back` before it.
struct Window<F> {
    fill: F,
    n: usize,
    back: usize,
    block: usize,
    lo: usize,
    held: Vec<f64>,
}

impl<F: FnMut(usize, &mut [f64])> Window<F> {
    fn new(n: usize, back: usize, block: usize, fill: F) -> Self {
        let block = block.clamp(1, n.max(1));
        Self {
            fill,
            n,
            back,
            block,
            lo: 0,
            held: Vec::with_capacity(back.saturating_add(block)),
        }
    }

    /// Sample `j`: at least the `back` samples before the latest one made.
    #[inline]
    fn value(&mut self, j: usize) -> f64 {
        if j >= self.lo + self.held.len() {
            self.advance(j);
        }
        self.held[j - self.lo]
    }

    /// Makes the block from sample `j` on, keeping the `back` samples before it.
    #[cold]
    fn advance(&mut self, j: usize) {
        let end = self.lo + self.held.len();
        let lo = j.saturating_sub(self.back).clamp(self.lo, end);
        self.held.drain(..lo - self.lo);
        self.held.resize((j + self.block).min(self.n) - lo, 0.0);
        (self.fill)(end, &mut self.held[end - lo..]);
        self.lo = lo;
    }
}

/// The symmetric part's means at the centres its ends are extrapolated from, kept as
/// [`triangle_means`] hands them over (`n` samples, `m` a revolution): up to three one
/// revolution apart from the first centre m − 1 on, and from the last n − m back.
struct EndMeans {
    n: usize,
    m: usize,
    /// Those centres in increasing order: the next to keep is `wanted[kept.len()]`.
    wanted: Vec<usize>,
    kept: Vec<(usize, f64)>,
}

impl EndMeans {
    fn new(n: usize, m: usize) -> Self {
        let (first, last) = (m - 1, n - m);
        let mut wanted: Vec<usize> = (0..3)
            .flat_map(|i| [first + i * m, last.wrapping_sub(i * m)])
            .filter(|c| (first..=last).contains(c))
            .collect();
        wanted.sort_unstable();
        wanted.dedup();
        Self {
            n,
            m,
            wanted,
            kept: Vec::with_capacity(6),
        }
    }

    /// Keeps the mean at centre `c` if an end is extrapolated from it. The centres come in
    /// order, each once ([`triangle_means`]), so one comparison a centre.
    fn offer(&mut self, c: usize, mean: f64) {
        if self.wanted.get(self.kept.len()) == Some(&c) {
            self.kept.push((c, mean));
        }
    }

    /// The symmetric part at sample j before the first centre or after the last (the
    /// polynomial through the means at the three centres nearest that end), `None` between.
    fn extrapolation(&self) -> impl Fn(usize) -> Option<f64> + '_ {
        let (m, first, last) = (self.m, self.m - 1, self.n - self.m);
        let mean = |c: usize| self.kept.iter().find(|k| k.0 == c).map_or(0.0, |k| k.1);
        let centres = |from: usize, towards_end: bool| -> Vec<(f64, f64)> {
            (0..3)
                .map(|i| {
                    if towards_end {
                        from as isize + (i * m) as isize
                    } else {
                        from as isize - (i * m) as isize
                    }
                })
                .filter(|&c| c >= first as isize && c <= last as isize)
                .map(|c| (c as f64, mean(c as usize)))
                .collect()
        };
        let (head, tail) = (centres(first, true), centres(last, false));
        move |j| {
            if j < first {
                Some(lagrange(&head, j as f64))
            } else if j > last {
                Some(lagrange(&tail, j as f64))
            } else {
                None
            }
        }
    }
}

/// The polynomial through `points` (x, y) evaluated at `x` (Lagrange's form; 0 for none).
fn lagrange(points: &[(f64, f64)], x: f64) -> f64 {
    points
        .iter()
        .enumerate()
        .map(|(i, &(xi, yi))| {
            let others = points.iter().enumerate().filter(|(k, _)| *k != i);
            yi * others
                .map(|(_, &(xk, _))| (x - xk) / (xi - xk))
                .product::<f64>()
        })
        .sum()
}

/// The least-squares straight line through `values` (against the index), at each index.
fn least_squares_line(values: &[f64]) -> Vec<f64> {
    let n = values.len() as f64;
    let mid = (n - 1.0) / 2.0;
    let mean = values.iter().sum::<f64>() / n.max(1.0);
    let (mut num, mut den) = (0.0, 0.0);
    for (j, v) in values.iter().enumerate() {
        num += (j as f64 - mid) * (v - mean);
        den += (j as f64 - mid).powi(2);
    }
    let slope = if den > 0.0 { num / den } else { 0.0 };
    (0..values.len())
        .map(|j| mean + slope * (j as f64 - mid))
        .collect()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A synthetic spiral of `revs` revolutions, `per_rev` points each, from radius `r0`
    /// inward by `feed` per revolution, with height `z(ρ, θ)`.
    pub(crate) fn spiral(
        revs: f64,
        per_rev: usize,
        r0: f64,
        feed: f64,
        z: impl Fn(f64, f64) -> f64,
    ) -> PathSignal {
        let count = (revs * per_rev as f64).round() as usize + 1;
        let (mut theta, mut radius, mut height) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..count {
            let phi = k as f64 * TAU / per_rev as f64;
            let rho = r0 - feed * phi / TAU;
            theta.push(phi);
            radius.push(rho);
            height.push(z(rho, phi));
        }
        PathSignal::from_columns(theta, radius, height)
    }

    /// A spiral of `revs` revolutions from radius `r0` inward by `feed` a revolution at a
    /// constant arc step `arc` (the points of a revolution falling with its radius, at least
    /// 16), with height `z(ρ, θ)`.
    pub(crate) fn arc_spiral(
        revs: f64,
        r0: f64,
        feed: f64,
        arc: f64,
        z: impl Fn(f64, f64) -> f64,
    ) -> PathSignal {
        let (mut theta, mut radius, mut height) = (Vec::new(), Vec::new(), Vec::new());
        let mut phi = 0.0;
        while phi <= revs * TAU {
            let rho = r0 - feed * phi / TAU;
            theta.push(phi);
            radius.push(rho);
            height.push(z(rho, phi));
            phi += (arc / rho).min(TAU / 16.0);
        }
        PathSignal::from_columns(theta, radius, height)
    }

    #[test]
    fn a_stretch_is_its_rates_grid_to_the_bit() {
        // A constant-arc spiral (2094 points on its outer turn, 523 on its inner) and a
        // constant-angle one: a stretch's samples are those of the whole grid at its rate, its
        // rate that of its own densest turn (and of the points just beyond it), and it covers
        // the angles asked for.
        let z = |r: f64, t: f64| 1e-3 * (5.0 * t).sin() + 0.01 * r * r;
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for s in [
            arc_spiral(60.0, 4.0, 0.05, 0.012, z),
            spiral(20.0, 300, 2.0, 0.05, z),
        ] {
            let whole = s.samples_per_rev();
            let span = s.span_rad();
            for (a, b) in [(-0.01, 0.03), (0.3, 0.45), (0.8, 0.95), (-0.1, 2.0)] {
                let (from, to) = (a * span, b * span);
                let st = s.stretch(from, to);
                let m = st.samples_per_rev;
                let step = TAU / m as f64;
                let grid = s.values_at(m, &s.z_mm);
                assert_eq!(
                    bits(&s.stretch_values(&st, |i| s.z_mm[i])),
                    bits(&grid[st.samples()])
                );
                let radii = s.radii_at(m);
                assert_eq!(
                    bits(&s.stretch_values(&st, |i| s.rho(i))),
                    bits(&radii[st.samples()])
                );
                let (lo, hi) = (
                    st.first as f64 * step,
                    (st.first + st.len - 1) as f64 * step,
                );
                assert!(
                    lo <= from.max(0.0) && (hi >= to || st.samples().end == grid.len()),
                    "{lo} {hi} {from} {to} {st:?} {}",
                    grid.len()
                );
                // At least as many samples a turn as any whole turn within the stretch has
                // points (less one), no more than the closest pair of points there would ask.
                let inside = |i: &usize| s.angle(*i) >= from - TAU && s.angle(*i) <= to + TAU;
                let mut turns = std::collections::BTreeMap::new();
                for i in (0..s.len()).filter(inside) {
                    *turns
                        .entry((s.angle(i) / TAU).floor() as i64)
                        .or_insert(0usize) += 1;
                }
                let whole_turns = turns.iter().filter(|(t, _)| {
                    (**t as f64) * TAU >= from.max(0.0) && (**t + 1) as f64 * TAU <= to
                });
                let most = whole_turns.map(|(_, c)| *c).max().unwrap_or(0);
                let closest = (1..s.len())
                    .filter(inside)
                    .map(|i| TAU / (s.angle(i) - s.angle(i - 1)))
                    .fold(0.0, f64::max);
                assert!(
                    m + 1 >= most && m as f64 <= closest + 1.0,
                    "{from}..{to}: {m}, {most}, {closest}, {whole}"
                );
            }
            if s.span_rad() > 100.0 * TAU / 2.0 {
                // At constant arc a turn has 2πρ/ΔS points: the stretch of turns 55–60, from
                // ρ = 1.25 mm inward, is sampled at most at the rate of ρ = 1.3 mm, not at the
                // rim's.
                let inner = s.stretch(55.0 * TAU, 60.0 * TAU).samples_per_rev;
                assert!(
                    inner as f64 <= TAU * 1.3 / 0.012 + 1.0,
                    "{inner} against {whole}"
                );
                assert!(whole as f64 >= TAU * 3.95 / 0.012, "{whole}");
            }
        }
    }

    #[test]
    fn an_indexed_signal_holds_the_columns_from_the_first_point_off_its_spiral() {
        use crate::job::{Direction, Sampling};
        use crate::path::SpiralPoint;
        let angle = Sampling::ConstantAngle { points_per_rev: 50 };
        let spiral = Spiral::new(2.0, 0.1, &angle, Direction::Cw, 30.0).unwrap();
        let point = |sp: SpiralPoint, z: f64| PathPoint {
            index: 0,
            rho: sp.rho,
            theta: sp.theta,
            z,
            contact: [0.0; 3],
            contact_angle: 0.0,
            at_arc_end: false,
        };
        let own: Vec<PathPoint> = (spiral.points().enumerate())
            .map(|(i, sp)| point(sp, 1e-3 * i as f64))
            .collect();
        assert_eq!(own.len(), 1001);
        let signal_of = |points: &[PathPoint]| {
            let mut s = PathSignal::for_spiral(&spiral, points.len());
            points.iter().for_each(|p| s.push(p));
            for (i, p) in points.iter().enumerate() {
                let got = [s.theta(i), s.rho(i), s.z_mm[i]].map(f64::to_bits);
                assert_eq!(got, [p.theta, p.rho, p.z].map(f64::to_bits), "point {i}");
            }
            s
        };
        // The spiral's own points: their angles and radii computed from the index are the
        // iterator's, to the bit, and only the heights are held.
        assert!(signal_of(&own).is_indexed());
        // A point moved (as two-way compensation moves them), or one past the spiral's last:
        // the columns are held from there on, those before computed again.
        let mut moved = own.clone();
        moved[700].rho += 1e-9;
        assert!(!signal_of(&moved).is_indexed());
        let mut longer = own.clone();
        longer.push(own[1000]);
        assert!(!signal_of(&longer).is_indexed());
        // A spiral given as a list: its points read from the list it holds, to the bit.
        let list: Vec<SpiralPoint> = spiral.points().collect();
        let listed = Spiral::from_points(0.1, &angle, list).unwrap();
        let mut s = PathSignal::for_spiral(&listed, own.len());
        own.iter().for_each(|p| s.push(p));
        assert!(s.is_indexed());
        for (i, p) in own.iter().enumerate() {
            assert_eq!([s.theta(i), s.rho(i)], [p.theta, p.rho], "listed point {i}");
        }
        // A spiral walked by its step rule has its columns held from the start.
        let arc = Sampling::ConstantArc {
            arc_length_mm: 0.01,
            max_angle_step_deg: 5.0,
        };
        let arc = Spiral::new(2.0, 0.1, &arc, Direction::Ccw, 0.0).unwrap();
        assert!(!PathSignal::for_spiral(&arc, 0).is_indexed());
    }

    #[test]
    fn constant_angle_paths_sample_onto_themselves() {
        let s = spiral(5.0, 100, 2.0, 0.1, |r, t| r * r + (3.0 * t).sin());
        let u = s.uniform().unwrap();
        assert_eq!(u.samples_per_rev, 100);
        assert_eq!(u.len(), s.len());
        for (a, b) in u.z_mm.iter().zip(&s.z_mm) {
            assert!((a - b).abs() < 1e-12, "{a} {b}");
        }
    }

    #[test]
    fn uneven_paths_are_interpolated_linearly_at_their_densest_rate() {
        // Steps of 0.01 rad for the first revolution, 0.05 rad after: M = ⌈2π/0.01⌉ = 629.
        let mut theta = Vec::new();
        let mut phi = 0.0;
        while phi < 3.0 * TAU {
            theta.push(phi);
            phi += if phi < TAU { 0.01 } else { 0.05 };
        }
        let (rho, z) = (vec![1.0; theta.len()], theta.iter().map(|a| 2.0 * a + 1.0));
        let s = PathSignal::from_columns(theta.clone(), rho, z.collect());
        let u = s.uniform().unwrap();
        assert_eq!(u.samples_per_rev, 629);
        // A linear z is reproduced exactly by linear interpolation (to rounding).
        for (j, z) in u.z_mm.iter().enumerate() {
            assert!((z - (2.0 * j as f64 * u.step_rad() + 1.0)).abs() < 1e-12);
        }
        // θ starts at 0 here: it is the angle turned.
        let back = u.at_path(&u.z_mm, &theta);
        for (a, b) in back.iter().zip(&s.z_mm) {
            assert!((a - b).abs() < 1e-12);
        }
        // Any other column lands on the same grid: a quadratic in angle is interpolated
        // linearly between the two points around each sample.
        let q: Vec<f64> = theta.iter().map(|a| a * a).collect();
        let on_grid = s.uniform_values(&q);
        assert_eq!(on_grid.len(), u.len());
        for (j, v) in on_grid.iter().enumerate() {
            let phi = j as f64 * u.step_rad();
            let k = theta.partition_point(|a| *a < phi).clamp(1, s.len() - 1);
            let (a0, a1) = (theta[k - 1], theta[k]);
            let linear = a0 * a0 + (phi - a0) / (a1 - a0) * (a1 * a1 - a0 * a0);
            assert!(
                (v - linear).abs() < 1e-12,
                "sample {j}: {v} against {linear}"
            );
        }
        assert!(s.uniform_values(&q[1..]).is_empty());
        // At the grid's rate, unchecked: the same bits, radii and heights as the grid's own.
        let m = u.samples_per_rev;
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&s.values_at(m, &q)), bits(&on_grid));
        assert_eq!(bits(&s.values_at(m, &s.z_mm)), bits(&u.z_mm));
        let radii = s.values_at(m, &(0..s.len()).map(|i| s.rho(i)).collect::<Vec<_>>());
        assert_eq!(bits(&s.radii_at(m)), bits(&radii));
        assert!(s.values_at(m, &q[1..]).is_empty());
        assert!(PathSignal::default().radii_at(m).is_empty());
        assert!(s.radii_at(0).is_empty());
    }

    #[test]
    fn bad_columns_are_errors_not_panics() {
        let mut s = spiral(1.0, 10, 1.0, 0.1, |_, _| 0.0);
        s.z_mm.pop();
        assert!(matches!(s.uniform(), Err(SignalError::Ragged { .. })));
        let one = spiral(0.0, 10, 1.0, 0.1, |_, _| 0.0);
        assert!(matches!(
            one.uniform(),
            Err(SignalError::TooShort { points: 1, .. })
        ));
    }

    #[test]
    fn symmetric_part_keeps_one_revolution_of_sums_to_the_bit() {
        // Against the same running sums with every one-revolution sum kept (as this module
        // once did), bit for bit, at lengths from the shortest it takes (2M − 1) up, on values
        // whose sums round differently in another order.
        let whole_record = |values: &[f64], m: usize| -> Vec<f64> {
            let (n, base) = (values.len(), values[0]);
            let mut boxcar = Vec::new();
            let mut sum: f64 = values[..m].iter().map(|v| v - base).sum();
            boxcar.push(sum);
            for j in m..n {
                sum += values[j] - values[j - m];
                boxcar.push(sum);
            }
            let mut out = vec![f64::NAN; n];
            let mut sum2: f64 = boxcar[..m].iter().sum();
            for (k, j) in (m - 1..=n - m).enumerate() {
                if k > 0 {
                    sum2 += boxcar[k + m - 1] - boxcar[k - 1];
                }
                out[j] = base + sum2 / (m * m) as f64;
            }
            out
        };
        for m in [1, 2, 3, 8, 13] {
            let grid = UniformSignal {
                samples_per_rev: m,
                samples: 0,
                z_mm: Vec::new(),
            };
            for n in [2 * m - 1, 2 * m, 5 * m + 3, 40 * m + 1] {
                let values: Vec<f64> = (0..n)
                    .map(|j| 1e3 * ((j * j) as f64 * 0.37).sin() + 0.1 * j as f64)
                    .collect();
                let ours = grid.symmetric_part(&values);
                let theirs = whole_record(&values, m);
                for j in m - 1..=n - m {
                    assert_eq!(
                        ours[j].to_bits(),
                        theirs[j].to_bits(),
                        "M {m}, n {n}, sample {j}"
                    );
                }
                // Subtracted in place, ends and all: the residual of the part, to the bit.
                let mut residual = values.clone();
                grid.subtract_symmetric_part(&mut residual);
                for j in 0..n {
                    assert_eq!(
                        residual[j].to_bits(),
                        (values[j] - ours[j]).to_bits(),
                        "in place: M {m}, n {n}, sample {j}"
                    );
                }
                // Its ends alone, as long as a revolution and as long as the record.
                for count in [m + 1, n] {
                    let (head, tail) = grid.symmetric_part_at_ends(&values, count);
                    let count = count.min(n);
                    for k in 0..count {
                        assert_eq!(
                            head[k].to_bits(),
                            ours[k].to_bits(),
                            "head: M {m}, n {n}, {k}"
                        );
                        let j = n - count + k;
                        assert_eq!(
                            tail[k].to_bits(),
                            ours[j].to_bits(),
                            "tail: M {m}, n {n}, {j}"
                        );
                    }
                }
            }
            // Shorter than two revolutions: less the least-squares line, in place alike.
            let short: Vec<f64> = (0..m.max(2)).map(|j| (j * j) as f64).collect();
            let mut residual = short.clone();
            grid.subtract_symmetric_part(&mut residual);
            let line = grid.symmetric_part(&short);
            for j in 0..short.len() {
                assert_eq!(residual[j].to_bits(), (short[j] - line[j]).to_bits());
            }
            let (head, tail) = grid.symmetric_part_at_ends(&short, 1);
            assert_eq!([head[0], tail[0]], [line[0], line[short.len() - 1]]);
        }
    }

    #[test]
    fn symmetric_part_removes_whole_harmonics_with_linear_amplitudes() {
        // z = S(ρ) + a(ρ)·cos(3θ) + b(ρ)·sin(θ) with S quadratic and a, b linear in ρ: the
        // double zeros of the triangle response leave only S's own smoothing, the triangle's
        // variance (M² − 1)/6 samples² times ½S″·(f/M)², i.e. S″·f²·(1 − 1/M²)/12 (module
        // docs), a constant here; the quadratic extrapolation at the ends is exact for it.
        let sag = |r: f64| r * r;
        let s = spiral(6.0, 64, 3.0, 0.1, |r, t| {
            sag(r) + 0.5 * r * (3.0 * t).cos() + (1.0 - 0.2 * r) * t.sin()
        });
        let u = s.uniform().unwrap();
        let sym = u.symmetric_part(&u.z_mm);
        let radii = s.radii_at(u.samples_per_rev);
        let smoothing = 2.0 * 0.1f64.powi(2) * (1.0 - 1.0 / 64f64.powi(2)) / 12.0;
        for (j, v) in sym.iter().enumerate() {
            let want = sag(radii[j]) + smoothing;
            // Running sums of 385 values below 10: rounding far below 1e-12.
            assert!((v - want).abs() < 1e-12, "sample {j}: {v} vs {want}");
        }
    }

    #[test]
    fn resampling_in_parts_is_the_serial_walk_to_the_bit() {
        // Uneven steps (the walk's interval changes at every kind of place): the grid made in
        // parts on the cores, a part walking from its own first sample, is the one walk from
        // the first point, at the path's own rate and at others.
        let mut theta = Vec::new();
        let mut phi = 0.0;
        for k in 0..20_000 {
            theta.push(phi);
            phi += 1e-3 * (1.0 + (k % 7) as f64);
        }
        let z: Vec<f64> = theta.iter().map(|a| (3.0 * a).sin() + 0.1 * a).collect();
        let s = PathSignal::from_columns(theta.clone(), vec![1.0; theta.len()], z.clone());
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for m in [s.samples_per_rev(), 97, 5000] {
            let count = grid_count(s.span_rad(), TAU / m as f64);
            let mut serial = vec![0.0; count];
            s.resample_into(|i| z[i], m, 0, &mut serial, |v, x| *v = x);
            assert_eq!(bits(&s.values_at(m, &z)), bits(&serial), "{m} a revolution");
        }
    }

    #[test]
    fn a_residual_in_single_precision_is_the_double_one_rounded_to_the_bit() {
        // A sag of millimetres with tones of micrometres on it, made in blocks from under a
        // revolution to the whole record: each sample is the double-precision residual (taken
        // in place) rounded, the extrapolated ends included, and each is made once. A record
        // shorter than two revolutions has the straight line taken off, as in place.
        let m = 64;
        let value = |j: usize| {
            let a = j as f64 * TAU / m as f64;
            4.5 - 2e-4 * a * a.sqrt() + 1e-3 * (5.0 * a).sin() + 2e-4 * (29.3 * a).cos()
        };
        for n in [2 * m - 2, 2 * m - 1, 5 * m + 3, 40_000] {
            let grid = UniformSignal {
                samples_per_rev: m,
                samples: n,
                z_mm: Vec::new(),
            };
            let mut double: Vec<f64> = (0..n).map(value).collect();
            grid.subtract_symmetric_part(&mut double);
            for block in [1, m / 2, m, 1000, n, usize::MAX] {
                let made = std::sync::atomic::AtomicUsize::new(0);
                let fill = |first: usize, out: &mut [f64]| {
                    let ordering = std::sync::atomic::Ordering::Relaxed;
                    assert_eq!(first, made.load(ordering), "blocks in order");
                    made.store(first + out.len(), ordering);
                    for (j, v) in (first..).zip(out.iter_mut()) {
                        *v = value(j);
                    }
                };
                let narrow = grid.narrow_residual(n, block, fill);
                let made = made.into_inner();
                assert_eq!((narrow.len(), made), (n, n), "n {n}, block {block}");
                for (j, (a, b)) in narrow.iter().zip(&double).enumerate() {
                    let want = (*b as f32).to_bits();
                    assert_eq!(a.to_bits(), want, "n {n}, block {block}: sample {j}");
                }
            }
        }
    }

    #[test]
    fn the_symmetric_part_at_the_points_is_the_records_interpolated_to_the_bit() {
        // A constant-arc spiral (points between the samples, denser and sparser than the grid)
        // of 300 turns and of one: made a block at a time, the symmetric part at every point
        // is that of the whole record of heights interpolated there, ends included.
        let z = |r: f64, t: f64| 0.3 * r * r + 1e-3 * (5.0 * t).sin() + 2e-4 * (29.0 * t).cos();
        for revs in [300.0, 1.0] {
            let s = arc_spiral(revs, 4.0, 0.004, 0.3, z);
            let g = s.uniform().unwrap();
            let symmetric = g.symmetric_part(&g.z_mm);
            for block in [1, 500, usize::MAX] {
                let at = g.symmetric_part_at_points(&s, block);
                assert_eq!(at.len(), s.len(), "{revs} turns, block {block}");
                for (i, v) in at.iter().enumerate() {
                    let want = g.interpolate(&symmetric, s.angle(i)).to_bits();
                    assert_eq!(v.to_bits(), want, "{revs} turns, block {block}: point {i}");
                }
            }
        }
    }

    #[test]
    fn extremes_found_in_parts_are_those_of_one_pass() {
        for n in [0, 1, 2, 3, 1001] {
            let value = |i: usize| ((i * 7919) % 1013) as f64 - 500.0 + 0.25 * i as f64;
            let one_pass = extremes((0..n).map(value));
            assert_eq!(extremes_at(n, value), one_pass, "{n} values");
            assert_eq!(
                peak_to_valley_at(n, value),
                peak_to_valley((0..n).map(value))
            );
        }
        assert_eq!(peak_to_valley_at(0, |_| 1.0), 0.0);
    }

    #[test]
    fn extremes_of_a_sine_against_its_derivatives() {
        // v = sin(2φ): slope 2, curvature 4; chord and second differences at 1000 points/rev
        // are within (2·Δφ)²/6 ≈ 3e-5 relative of them.
        let s = spiral(2.0, 1000, 1.0, 0.0, |_, t| (2.0 * t).sin());
        let e = s.angle_extremes(&s.z_mm);
        assert!((e.slope_mm_per_rad - 2.0).abs() < 2.0 * 3e-5);
        assert!((e.curvature_mm_per_rad2 - 4.0).abs() < 4.0 * 3e-5);
        // The largest slope is where cos(2φ) = ±1: φ a multiple of π/2, points 0, 250, ….
        assert_eq!(e.slope_at % 250, 0);
    }
}
