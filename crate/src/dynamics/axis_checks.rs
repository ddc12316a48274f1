//! Axis checks: every point's axis velocities and accelerations against the machine model
//! ([`crate::job::machine`]), the block rate the path needs, the fast tool servo's stroke, the
//! cycle time, and the highest spindle speed that keeps every checked axis within its limits.
//!
//! **Timing.** The spindle turns at a constant n rev/min, ω = 2π·n/60 rad/s, and the NC feeds
//! in inverse time, so the block from point k to point k+1 lasts `Δt_k = |θ_{k+1} − θ_k|/ω`
//! (θ the cumulative polar angle, [`crate::path::PathPoint::theta`]); the cycle time is
//! `Σ Δt_k`, `|θ_last − θ_0|/ω` for the monotone θ of every planner sampling. All geometry is
//! fixed, so every figure is a derivative with respect to θ scaled by ω: velocities scale with
//! n, accelerations with n², the block rate with n.
//!
//! **Velocity** of each block: the divided difference `v_k = Δx_k/Δt_k`, the exact average
//! velocity of the linear move the controller makes, equal to the path's dx/dt at the block's
//! middle within `Δt²/24·max|x‴|`. It is reported at the block's end point (the NC block that
//! commands the move). **Acceleration** at an interior point: the second divided difference on
//! the non-uniform time grid, `a_k = 2·(v_k − v_{k−1})/(Δt_{k−1} + Δt_k)`: exact for a quadratic
//! on any grid, `x″ + (Δt_k − Δt_{k−1})/3·x‴ + O(Δt²)` in general, so second order where the
//! step is constant (error `Δt²/12·max|x⁗|`) and first order only where it jumps (zone
//! boundaries of HCAA sampling). The **block rate** the path needs is the largest `1/Δt_k`.
//! The **FTS stroke** used is max W − min W; it does not depend on n.
//!
//! **Conditioning.** The samples should be the path's unrounded f64 values: rounding to the NC's
//! q mm quantum would add up to `4q/Δθ²·ω²` of noise to each acceleration (e.g. q = 1 nm,
//! 720 points/rev and 800 rpm give 185 mm/s²). With unrounded values the rounding floor is
//! about `4ε·max|x|/Δθ²·ω²` (ε = 2.2e-16), negligible against any slide's limit; X on the
//! one-way spiral is linear in θ, so its computed acceleration is that floor, not a fault.
//! A block with Δθ = 0 takes no time: it cannot be written in inverse time, and it has no
//! velocity; such blocks are listed as `zero_time_blocks`, left out of the velocity and block
//! rate figures, and no acceleration is taken across them (a repeated point included: its
//! neighbours' blocks are taken alone). Samples with a non-finite value are skipped and
//! counted. An invalid spindle speed (not finite, ≤ 0; see
//! [`crate::job::MachineSpec::validate`]) gives non-finite figures, written as null.
//!
//! **Highest spindle speed.** With v, a and b the largest velocity, acceleration and block rate
//! at the job's speed n₀, a limit V, A or B holds up to `n₀·V/v`, `n₀·√(A/a)`, `n₀·B/b`; the
//! smallest of these over every checked limit is the highest feasible speed, and its limit
//! binds. A figure is counted as a violation when it exceeds its limit by more than
//! [`LIMIT_ROUNDING`] (relative), so that the path is reported within limits at that speed.
//!
//! Bandwidths are not checked here: the splitter ([`crate::job::machine`] limits, paper 000)
//! decides what each axis must follow in frequency.

use crate::job::MachineSpec;
use crate::path::Location;
use crate::path::PathPoint;
use serde::Serialize;
use std::borrow::Borrow;
use std::f64::consts::TAU;

/// Violations listed per axis and quantity; further ones are only counted.
pub const MAX_LISTED: usize = 100;

/// Relative excess over a limit below which a figure is not a violation: the rounding of
/// rescaling the figures to another spindle speed (a few ulp), with a wide margin.
pub const LIMIT_ROUNDING: f64 = 1e-12;

/// The machine axes at one path point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AxisSample {
    /// Cumulative polar angle, radians ([`PathPoint::theta`]).
    pub theta: f64,
    /// Radius on the part, mm, for locating findings.
    pub rho_mm: f64,
    /// X slide, mm.
    pub x_mm: f64,
    /// Z slide, mm.
    pub z_mm: f64,
    /// Fast tool servo W, mm; 0 when there is none.
    pub w_mm: f64,
}

impl AxisSample {
    /// The point at angle `theta` and radius `rho_mm` (X = ρ) of height `z_mm`: with
    /// `z_slide` the slide at it and the servo the rest (W = z − Z), else all on the slide.
    pub fn new(theta: f64, rho_mm: f64, z_mm: f64, z_slide: Option<f64>) -> Self {
        Self {
            theta,
            rho_mm,
            x_mm: rho_mm,
            z_mm: z_slide.unwrap_or(z_mm),
            w_mm: z_slide.map_or(0.0, |z| z_mm - z),
        }
    }

    /// The path point with all of Z on the slide (slow slide servo alone, W = 0).
    pub fn slide_only(p: &PathPoint) -> Self {
        Self::new(p.theta, p.rho, p.z, None)
    }
}

/// Where on the path: the sample's index and its place on the part.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SampleAt {
    /// Index of the sample (the path point).
    pub index: u64,
    /// Radius, mm.
    pub rho_mm: f64,
    /// Polar angle, degrees in [0, 360).
    pub theta_deg: f64,
}

impl SampleAt {
    // Not inlined: inlined, its remainder of the angle in degrees (a library call) was
    // computed for every sample of the axis checks, ahead of the rare branches that use it.
    #[inline(never)]
    fn new(index: usize, s: &AxisSample) -> Self {
        let at = Location::new(s.rho_mm, s.theta);
        Self {
            index: index as u64,
            rho_mm: at.rho_mm,
            theta_deg: at.theta_deg,
        }
    }
}

/// What a figure measures, with its unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// |velocity| of a block, mm/s.
    VelocityMmPerS,
    /// |acceleration| at a point, mm/s².
    AccelerationMmPerS2,
    /// Blocks per second, 1/Δt, Hz.
    BlockRateHz,
}

impl Quantity {
    /// How the figure scales with the spindle speed: n^power.
    fn power(self) -> i32 {
        match self {
            Quantity::AccelerationMmPerS2 => 2,
            _ => 1,
        }
    }
}

/// A figure over its limit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Violation {
    /// Where.
    #[serde(flatten)]
    pub at: SampleAt,
    /// What.
    pub quantity: Quantity,
    /// The figure, in the quantity's unit.
    pub value: f64,
    /// The limit, same unit.
    pub limit: f64,
}

/// The largest value of one quantity along the path and its violations.
#[derive(Debug, Clone)]
struct Tracker {
    quantity: Quantity,
    /// The job field of the limit, e.g. `machine.z_slide.velocity_mm_per_min`.
    field: &'static str,
    limit: Option<f64>,
    max: f64,
    at: Option<SampleAt>,
    listed: Vec<Violation>,
    count: u64,
}

impl Tracker {
    fn new(quantity: Quantity, field: &'static str, limit: Option<f64>) -> Self {
        Self {
            quantity,
            field,
            limit,
            max: 0.0,
            at: None,
            listed: Vec::new(),
            count: 0,
        }
    }

    fn add(&mut self, value: f64, index: usize, s: &AxisSample) {
        if value > self.max {
            self.max = value;
            self.at = Some(SampleAt::new(index, s));
        }
        if let Some(limit) = self.limit
            && value > limit * (1.0 + LIMIT_ROUNDING)
        {
            self.count += 1;
            if self.listed.len() < MAX_LISTED {
                self.listed.push(Violation {
                    at: SampleAt::new(index, s),
                    quantity: self.quantity,
                    value,
                    limit,
                });
            }
        }
    }

    /// The highest spindle speed that keeps this quantity within its limit, if it bounds it.
    fn speed_limit(&self, spindle_rpm: f64) -> Option<SpeedLimit> {
        let limit = self.limit?;
        if self.max <= 0.0 {
            return None;
        }
        let ratio = limit / self.max;
        let factor = if self.quantity.power() == 2 {
            ratio.sqrt()
        } else {
            ratio
        };
        Some(SpeedLimit {
            max_spindle_rpm: spindle_rpm * factor,
            binding_limit: self.field.to_string(),
            at: self.at,
        })
    }
}

/// Which axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Axis {
    /// The radial slide.
    X,
    /// The axial slide (slow slide servo).
    Z,
    /// The fast tool servo.
    W,
}

/// The motion of one axis against its limits.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisCheck {
    /// The axis.
    pub axis: Axis,
    /// Largest |velocity| of a block, mm/s.
    pub max_velocity_mm_per_s: f64,
    /// The same, mm/min.
    pub max_velocity_mm_per_min: f64,
    /// Where (the block's end point); `None` when the axis does not move.
    pub max_velocity_at: Option<SampleAt>,
    /// Velocity limit, mm/s; `None`: not checked.
    pub velocity_limit_mm_per_s: Option<f64>,
    /// Blocks over the velocity limit.
    pub velocity_violation_count: u64,
    /// The first [`MAX_LISTED`] of them, in path order.
    pub velocity_violations: Vec<Violation>,
    /// Largest |acceleration| at a point, mm/s².
    pub max_acceleration_mm_per_s2: f64,
    /// Where; `None` when the axis does not accelerate.
    pub max_acceleration_at: Option<SampleAt>,
    /// Acceleration limit, mm/s²; `None`: not checked.
    pub acceleration_limit_mm_per_s2: Option<f64>,
    /// Points over the acceleration limit.
    pub acceleration_violation_count: u64,
    /// The first [`MAX_LISTED`] of them, in path order.
    pub acceleration_violations: Vec<Violation>,
}

impl AxisCheck {
    fn new(axis: Axis, velocity: Tracker, acceleration: Tracker) -> Self {
        Self {
            axis,
            max_velocity_mm_per_s: velocity.max,
            max_velocity_mm_per_min: velocity.max * 60.0,
            max_velocity_at: velocity.at,
            velocity_limit_mm_per_s: velocity.limit,
            velocity_violation_count: velocity.count,
            velocity_violations: velocity.listed,
            max_acceleration_mm_per_s2: acceleration.max,
            max_acceleration_at: acceleration.at,
            acceleration_limit_mm_per_s2: acceleration.limit,
            acceleration_violation_count: acceleration.count,
            acceleration_violations: acceleration.listed,
        }
    }

    /// No violation of either limit.
    pub fn within_limits(&self) -> bool {
        self.velocity_violation_count == 0 && self.acceleration_violation_count == 0
    }
}

/// The block rate the path needs against the controller's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BlockRateCheck {
    /// Largest 1/Δt over the blocks, Hz.
    pub required_hz: f64,
    /// Where (the block's end point).
    pub at: Option<SampleAt>,
    /// The controller's rate, Hz; `None`: not checked.
    pub limit_hz: Option<f64>,
    /// Blocks faster than the limit.
    pub violation_count: u64,
    /// The first [`MAX_LISTED`] of them, in path order.
    pub violations: Vec<Violation>,
}

/// The FTS stroke the path uses against the servo's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StrokeCheck {
    /// max W − min W, µm.
    pub used_um: f64,
    /// Lowest W, mm.
    pub w_min_mm: f64,
    /// Highest W, mm.
    pub w_max_mm: f64,
    /// The servo's stroke, µm; `None`: the machine has no FTS.
    pub limit_um: Option<f64>,
    /// The stroke used fits (with no FTS: W does not move).
    pub within_limit: bool,
}

/// The highest spindle speed within every checked limit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedLimit {
    /// Spindle speed, rev/min.
    pub max_spindle_rpm: f64,
    /// The job field of the limit that binds, e.g. `machine.z_slide.acceleration_mm_per_s2`.
    pub binding_limit: String,
    /// Where that limit is reached.
    pub at: Option<SampleAt>,
}

/// Everything [`check_axes`] finds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisReport {
    /// The spindle speed of the figures, rev/min.
    pub spindle_rpm: f64,
    /// Samples checked (non-finite ones left out).
    pub points: u64,
    /// Samples left out because a value was not finite.
    pub skipped_samples: u64,
    /// Spindle revolutions, Σ|Δθ|/2π.
    pub revolutions: f64,
    /// Cycle time at `spindle_rpm`, s.
    pub cycle_time_s: f64,
    /// The block rate.
    pub block_rate: BlockRateCheck,
    /// The X slide.
    pub x: AxisCheck,
    /// The Z slide.
    pub z: AxisCheck,
    /// The fast tool servo (acceleration checked; it has no velocity limit in the model).
    pub w: AxisCheck,
    /// The FTS stroke.
    pub fts_stroke: StrokeCheck,
    /// The highest spindle speed within every checked velocity, acceleration and block-rate
    /// limit and the limit that binds; `None` when no checked limit bounds the speed.
    pub max_spindle: Option<SpeedLimit>,
    /// Blocks with Δθ = 0 (see the module docs).
    pub zero_time_block_count: u64,
    /// The first [`MAX_LISTED`] of them (their end points).
    pub zero_time_blocks: Vec<SampleAt>,
    /// No violation, no zero-time block, the stroke fits.
    pub within_limits: bool,
    /// Findings in words, one a line.
    pub warnings: Vec<String>,
}

impl AxisReport {
    /// The report as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }
}

/// Velocity and acceleration trackers of one axis.
struct AxisTrackers {
    velocity: Tracker,
    acceleration: Tracker,
}

impl AxisTrackers {
    fn new(fields: [&'static str; 2], velocity_mm_per_s: Option<f64>, acc: Option<f64>) -> Self {
        Self {
            velocity: Tracker::new(Quantity::VelocityMmPerS, fields[0], velocity_mm_per_s),
            acceleration: Tracker::new(Quantity::AccelerationMmPerS2, fields[1], acc),
        }
    }
}

/// One block between consecutive finite samples with Δθ > 0: its angle step and the slopes
/// dX/dθ, dZ/dθ, dW/dθ, mm/rad.
#[derive(Debug, Clone, Copy)]
struct Block {
    dtheta: f64,
    slopes: [f64; 3],
}

impl Block {
    fn between(a: &AxisSample, b: &AxisSample) -> Option<Self> {
        let dtheta = (b.theta - a.theta).abs();
        (dtheta > 0.0).then(|| Self {
            dtheta,
            slopes: [
                (b.x_mm - a.x_mm) / dtheta,
                (b.z_mm - a.z_mm) / dtheta,
                (b.w_mm - a.w_mm) / dtheta,
            ],
        })
    }
}

/// Checks the axes of `samples` (the path in order: a slice, or computed on the fly) against
/// `machine` at its spindle speed; see the module docs for the method. Never panics; O(1)
/// memory besides the lists.
///
/// ```
/// use spiralcam::dynamics::axis_checks::{AxisSample, check_axes};
/// use spiralcam::job::MachineSpec;
/// // One revolution in 4 steps at 60 rpm (1 s), X from 1 mm to 0.
/// let s: Vec<_> = (0..5).map(|k| {
///     let theta = k as f64 * std::f64::consts::FRAC_PI_2;
///     let x = 1.0 - k as f64 / 4.0;
///     AxisSample { theta, rho_mm: x, x_mm: x, z_mm: 0.0, w_mm: 0.0 }
/// }).collect();
/// let r = check_axes(&s, &MachineSpec::spindle_only(60.0));
/// assert!((r.cycle_time_s - 1.0).abs() < 1e-15);
/// assert!((r.x.max_velocity_mm_per_s - 1.0).abs() < 1e-15);
/// assert!((r.block_rate.required_hz - 4.0).abs() < 1e-12);
/// ```
pub fn check_axes(
    samples: impl IntoIterator<Item = impl Borrow<AxisSample>>,
    machine: &MachineSpec,
) -> AxisReport {
    let omega = machine.spindle_rpm / 60.0 * TAU;
    let slide = |s: Option<&crate::job::machine::SlideSpec>| {
        (
            s.map(|s| s.velocity_mm_per_s()),
            s.map(|s| s.acceleration_mm_per_s2),
        )
    };
    let (xv, xa) = slide(machine.x_slide.as_ref());
    let (zv, za) = slide(machine.z_slide.as_ref());
    let wa = machine.fts.map(|f| f.acceleration_mm_per_s2());
    let mut axes = [
        AxisTrackers::new(
            [
                "machine.x_slide.velocity_mm_per_min",
                "machine.x_slide.acceleration_mm_per_s2",
            ],
            xv,
            xa,
        ),
        AxisTrackers::new(
            [
                "machine.z_slide.velocity_mm_per_min",
                "machine.z_slide.acceleration_mm_per_s2",
            ],
            zv,
            za,
        ),
        AxisTrackers::new(["", "machine.fts.acceleration_m_per_s2"], None, wa),
    ];
    let mut rate = Tracker::new(
        Quantity::BlockRateHz,
        "machine.block_rate_hz",
        machine.block_rate_hz,
    );
    let (mut points, mut skipped, mut total_angle) = (0u64, 0u64, 0.0);
    let (mut w_min, mut w_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut zero_time, mut zero_time_count) = (Vec::new(), 0u64);
    // The last finite sample and the block that ended there (None after a zero-time block).
    let mut last: Option<(usize, AxisSample, Option<Block>)> = None;
    for (i, s) in samples.into_iter().enumerate() {
        let s = *s.borrow();
        if ![s.theta, s.rho_mm, s.x_mm, s.z_mm, s.w_mm]
            .iter()
            .all(|v| v.is_finite())
        {
            skipped += 1;
            continue;
        }
        points += 1;
        w_min = w_min.min(s.w_mm);
        w_max = w_max.max(s.w_mm);
        let Some((j, prev, before)) = last else {
            last = Some((i, s, None));
            continue;
        };
        let block = Block::between(&prev, &s);
        match block {
            None => {
                zero_time_count += 1;
                if zero_time.len() < MAX_LISTED {
                    zero_time.push(SampleAt::new(i, &s));
                }
            }
            Some(b) => {
                total_angle += b.dtheta;
                rate.add(omega / b.dtheta, i, &s);
                for (axis, slope) in axes.iter_mut().zip(b.slopes) {
                    axis.velocity.add(slope.abs() * omega, i, &s);
                }
                if let Some(a) = before {
                    let h = (a.dtheta + b.dtheta) / 2.0;
                    for (axis, (s1, s2)) in axes.iter_mut().zip(a.slopes.iter().zip(b.slopes)) {
                        let acc = ((s2 - s1) / h).abs() * omega * omega;
                        axis.acceleration.add(acc, j, &prev);
                    }
                }
            }
        }
        last = Some((i, s, block));
    }
    let [x, z, w] = axes;
    let used_mm = if w_max >= w_min { w_max - w_min } else { 0.0 };
    let fts_stroke = StrokeCheck {
        used_um: used_mm * 1e3,
        w_min_mm: if points > 0 { w_min } else { 0.0 },
        w_max_mm: if points > 0 { w_max } else { 0.0 },
        limit_um: machine.fts.map(|f| f.stroke_um),
        within_limit: match machine.fts {
            Some(f) => used_mm * 1e3 <= f.stroke_um * (1.0 + LIMIT_ROUNDING),
            None => used_mm == 0.0,
        },
    };
    let max_spindle = [
        &x.velocity,
        &x.acceleration,
        &z.velocity,
        &z.acceleration,
        &w.acceleration,
        &rate,
    ]
    .into_iter()
    .filter_map(|t| t.speed_limit(machine.spindle_rpm))
    .min_by(|a, b| a.max_spindle_rpm.total_cmp(&b.max_spindle_rpm));
    let x = AxisCheck::new(Axis::X, x.velocity, x.acceleration);
    let z = AxisCheck::new(Axis::Z, z.velocity, z.acceleration);
    let w = AxisCheck::new(Axis::W, w.velocity, w.acceleration);
    let block_rate = BlockRateCheck {
        required_hz: rate.max,
        at: rate.at,
        limit_hz: rate.limit,
        violation_count: rate.count,
        violations: rate.listed,
    };
    let within_limits = x.within_limits()
        && z.within_limits()
        && w.within_limits()
        && block_rate.violation_count == 0
        && fts_stroke.within_limit
        && zero_time_count == 0;
    let mut report = AxisReport {
        spindle_rpm: machine.spindle_rpm,
        points,
        skipped_samples: skipped,
        revolutions: total_angle / TAU,
        cycle_time_s: total_angle / omega,
        block_rate,
        x,
        z,
        w,
        fts_stroke,
        max_spindle,
        zero_time_block_count: zero_time_count,
        zero_time_blocks: zero_time,
        within_limits,
        warnings: Vec::new(),
    };
    report.warnings = warnings(&report);
    report
}

/// The findings of a report in words.
fn warnings(r: &AxisReport) -> Vec<String> {
    let mut out = Vec::new();
    let place = |at: Option<SampleAt>| {
        at.map_or(String::new(), |a| {
            format!(
                " at point {}, radius {:.4} mm, angle {:.2} deg",
                a.index, a.rho_mm, a.theta_deg
            )
        })
    };
    for axis in [&r.x, &r.z, &r.w] {
        if let (n @ 1.., Some(limit)) =
            (axis.velocity_violation_count, axis.velocity_limit_mm_per_s)
        {
            out.push(format!(
                "{:?} velocity exceeds {:.4} mm/s in {n} blocks: up to {:.4} mm/s{}",
                axis.axis,
                limit,
                axis.max_velocity_mm_per_s,
                place(axis.max_velocity_at)
            ));
        }
        if let (n @ 1.., Some(limit)) = (
            axis.acceleration_violation_count,
            axis.acceleration_limit_mm_per_s2,
        ) {
            out.push(format!(
                "{:?} acceleration exceeds {:.4} mm/s2 at {n} points: up to {:.4} mm/s2{}",
                axis.axis,
                limit,
                axis.max_acceleration_mm_per_s2,
                place(axis.max_acceleration_at)
            ));
        }
    }
    let b = &r.block_rate;
    if let (n @ 1.., Some(limit)) = (b.violation_count, b.limit_hz) {
        out.push(format!(
            "the path needs {:.1} blocks/s, over the controller's {limit} in {n} blocks{}",
            b.required_hz,
            place(b.at)
        ));
    }
    let s = &r.fts_stroke;
    if !s.within_limit {
        out.push(match s.limit_um {
            Some(limit) => format!(
                "the W axis needs a stroke of {:.4} um, over the FTS's {limit} um",
                s.used_um
            ),
            None => format!(
                "the W axis moves {:.4} um but the machine has no fast tool servo",
                s.used_um
            ),
        });
    }
    if r.zero_time_block_count > 0 {
        out.push(format!(
            "{} blocks have no angle step (zero time): they cannot be fed in inverse time; first{}",
            r.zero_time_block_count,
            place(r.zero_time_blocks.first().copied())
        ));
    }
    if let Some(m) = &r.max_spindle
        && m.max_spindle_rpm < r.spindle_rpm
    {
        out.push(format!(
            "the highest spindle speed within every limit is {:.3} rpm ({} binds)",
            m.max_spindle_rpm, m.binding_limit
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::surface::UndefinedError;
    use crate::tool::ToolPath;

    /// The planner's whole path as [`AxisSample::slide_only`] samples.
    fn slide_only_samples(planner: &ToolPath) -> Result<Vec<AxisSample>, UndefinedError> {
        planner
            .points()
            .map(|p| p.map(|p| AxisSample::slide_only(&p)))
            .collect()
    }
    use crate::job::Job;
    use crate::job::machine::{FtsSpec, SlideSpec, presets};
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngSeed};

    const EPS: f64 = f64::EPSILON;

    fn omega(rpm: f64) -> f64 {
        rpm / 60.0 * TAU
    }

    /// `revs` revolutions of `n` equal steps h = 2π/n from θ = phase·h, the spiral
    /// X = ρ = 5 − 0.01·θ/2π, and (z, w) from `zw(θ)`.
    fn samples(
        n: usize,
        revs: usize,
        phase: f64,
        zw: impl Fn(f64) -> (f64, f64),
    ) -> Vec<AxisSample> {
        let h = TAU / n as f64;
        (0..=n * revs)
            .map(|i| {
                let theta = (i as f64 + phase) * h;
                let rho = 5.0 - 0.01 * theta / TAU;
                let (z, w) = zw(theta);
                AxisSample {
                    theta,
                    rho_mm: rho,
                    x_mm: rho,
                    z_mm: z,
                    w_mm: w,
                }
            })
            .collect()
    }

    /// A machine that checks every limit, all far out of reach.
    fn unlimited(rpm: f64) -> MachineSpec {
        let slide = SlideSpec {
            velocity_mm_per_min: 1e12,
            acceleration_mm_per_s2: 1e12,
            bandwidth_hz: 1e12,
        };
        MachineSpec {
            spindle_rpm: rpm,
            block_rate_hz: Some(1e12),
            x_slide: Some(slide),
            z_slide: Some(slide),
            fts: Some(FtsSpec {
                stroke_um: 1e12,
                bandwidth_hz: 1e12,
                acceleration_m_per_s2: 1e12,
            }),
        }
    }

    /// z = A sin kθ sampled so that a block's middle lies on a peak of dz/dθ: the divided
    /// difference is exactly `A·k·cos(kθ_m)·sin(u)/u` (u = k·h/2, a trig identity), so the
    /// largest velocity is `A·k·ω·sin(u)/u`, asserted to 1e-10 (the rounding of Δz, ~1e-13
    /// relative); the continuous A·k·ω is within its second-order bound `u²/6`. X = ρ on the
    /// spiral moves at exactly f·n/60 mm/s, and its acceleration is the rounding floor
    /// `4ε·max|X|/h²·ω²` (module docs), asserted with a factor 4 of margin.
    #[test]
    fn sinusoid_velocity_matches_the_closed_form() {
        let (n, k, a, rpm) = (720, 5.0, 0.002, 600.0);
        let s = samples(n, 3, -0.5, |t| (a * (k * t).sin(), 0.0));
        let r = check_axes(&s, &MachineSpec::spindle_only(rpm));
        let w = omega(rpm);
        let u = k * TAU / n as f64 / 2.0;
        let exact = a * k * w * u.sin() / u;
        assert!((r.z.max_velocity_mm_per_s / exact - 1.0).abs() < 1e-10);
        let continuous = a * k * w;
        assert!((0.0..=continuous * u * u / 6.0).contains(&(continuous - exact)));
        assert!((r.z.max_velocity_mm_per_min - 60.0 * r.z.max_velocity_mm_per_s).abs() < 1e-12);
        // Reported at the block's end: its middle is h/2 earlier, on a peak of |cos kθ|.
        let at = r.z.max_velocity_at.unwrap();
        let middle = at.theta_deg.to_radians() - TAU / n as f64 / 2.0;
        assert!((k * middle).sin().abs() < 1e-9, "{at:?}");
        // X rounds to ε·5 mm at each end of a step of 0.01/720 mm.
        let h = TAU / n as f64;
        let x_rounding = 4.0 * EPS * 5.0 / (0.01 * h / TAU);
        assert!((r.x.max_velocity_mm_per_s / (0.01 * rpm / 60.0) - 1.0).abs() < x_rounding);
        assert!(r.x.max_acceleration_mm_per_s2 <= 16.0 * EPS * 5.0 / (h * h) * w * w);
        assert_eq!(
            (r.w.max_velocity_mm_per_s, r.w.max_velocity_at),
            (0.0, None)
        );
        assert!(r.within_limits && r.max_spindle.is_none());
    }

    /// z = A sin kθ sampled on a peak (k·36·h = π/2): the second difference is exactly
    /// `−A·k²·sin(kθ)·(sin u/u)²`, so the largest acceleration is `A·k²·ω²·(sin u/u)²`, asserted
    /// to 1e-10 (rounding ~4ε/(k·h)² ≈ 5e-13 relative); the continuous A·k²·ω² is within its
    /// second-order bound `u²/3`, and it is reported at a point on a peak.
    #[test]
    fn sinusoid_acceleration_matches_the_closed_form() {
        let (n, k, a, rpm) = (720, 5.0, 0.002, 600.0);
        let s = samples(n, 3, 0.0, |t| (0.0, a * (k * t).sin()));
        let r = check_axes(&s, &MachineSpec::spindle_only(rpm));
        let w = omega(rpm);
        let u = k * TAU / n as f64 / 2.0;
        let exact = a * k * k * w * w * (u.sin() / u).powi(2);
        assert!((r.w.max_acceleration_mm_per_s2 / exact - 1.0).abs() < 1e-10);
        let continuous = a * k * k * w * w;
        assert!((0.0..=continuous * u * u / 3.0).contains(&(continuous - exact)));
        let at = r.w.max_acceleration_at.unwrap();
        assert!((k * at.theta_deg.to_radians()).cos().abs() < 1e-9, "{at:?}");
        assert_eq!(r.z.max_acceleration_mm_per_s2, 0.0);
        // W moves, and the machine has no FTS.
        assert!(!r.fts_stroke.within_limit && !r.within_limits);
        assert!((r.fts_stroke.used_um - 2e3 * a).abs() < 1e-12);
        assert!(r.warnings.iter().any(|w| w.contains("no fast tool servo")));
    }

    proptest! {
        #![proptest_config(Config {
            cases: 64, rng_seed: RngSeed::Fixed(5005), failure_persistence: None,
            ..Config::default()
        })]

        /// On any grid, the second divided difference of a quadratic is exact: every axis
        /// `c·θ² + b·θ` has acceleration 2|c|·ω² at every point. Tolerance 1e-7 relative: the
        /// rounding of the slopes, ~4ε·max|x|/h_min² ≈ 1e-8 relative for these ranges.
        #[test]
        fn quadratics_are_exact_on_any_grid(
            steps in prop::collection::vec(0.001..0.1f64, 2..50),
            c in prop::array::uniform3(-1.0..1.0f64),
            b in prop::array::uniform3(-1.0..1.0f64),
            rpm in 10.0..5000.0f64,
        ) {
            let mut theta = 0.0;
            let mut s = Vec::new();
            for step in std::iter::once(0.0).chain(steps) {
                theta += step;
                let q = |k: usize| c[k] * theta * theta + b[k] * theta;
                s.push(AxisSample { theta, rho_mm: 1.0, x_mm: q(0), z_mm: q(1), w_mm: q(2) });
            }
            let r = check_axes(&s, &MachineSpec::spindle_only(rpm));
            let w2 = omega(rpm).powi(2);
            for (axis, c) in [&r.x, &r.z, &r.w].into_iter().zip(c) {
                let exact = 2.0 * c.abs() * w2;
                prop_assert!((axis.max_acceleration_mm_per_s2 - exact).abs() <= 1e-7 * exact);
            }
        }
    }

    /// The tilted flat of `crate/jobs/tilted-flat.json` on a 4 mm part, the spiral from
    /// 1.99 mm (so that the nose, 0.5 mm, touches the part inside its edge everywhere).
    fn tilted_flat_job() -> Job {
        let mut job = Job::from_json(include_str!("../../jobs/tilted-flat.json")).unwrap();
        job.part.diameter_mm = 4.0;
        job.strategy.outer_radius_mm = Some(1.99);
        job
    }

    /// One-way compensation of the plane z = ρ·tanτ·cos(θ − β) in the radial section at θ (a
    /// line of slope s = tanτ·cos(θ − β)) puts the tip at `ρ·s + r·(√(1 + s²) − 1)`; with
    /// ρ(θ) falling f per revolution, dz/dθ is `−f/2π·s + ρ·s′ + r·s·s′/√(1 + s²)`.
    fn tilted_flat_z(job: &Job, rho: f64, theta: f64) -> (f64, f64) {
        let crate::surface::SurfaceSpec::TiltedFlat(spec) = &job.surface else {
            unreachable!()
        };
        let (t, b) = (
            spec.tilt_deg.to_radians().tan(),
            spec.azimuth_deg.to_radians(),
        );
        let r = job.tool.nose_radius_mm;
        let (s, ds) = (t * (theta - b).cos(), -t * (theta - b).sin());
        let root = (1.0 + s * s).sqrt();
        let z = rho * s + r * (root - 1.0);
        let dz = -job.strategy.feed_mm_per_rev / TAU * s + rho * ds + r * s * ds / root;
        (z, dz)
    }

    /// The tilted flat planned through [`Planner`]: its Z is the closed form above to 1e-12 mm
    /// (the compensator's rounding); the largest Z velocity is the largest `|dz/dθ|·ω` at the
    /// blocks' middles within the chord error `ω·h²/24·max|z‴|`; it lies at the rim, where
    /// `ρ·tanτ·ω` gives it within the terms the closed form adds (feed `f/2π·tanτ`, nose
    /// `r·tan²τ`) and the sampling (`h²/8` for the nearest block to the peak, `h²/24` chord);
    /// the acceleration likewise is `ρ·tanτ·ω²`. The cycle time is revolutions × 60/n.
    #[test]
    fn tilted_flat_z_velocity_is_rho_tan_tilt_omega() {
        let job = tilted_flat_job();
        let planner = ToolPath::new(&job).unwrap();
        let s = slide_only_samples(&planner).unwrap();
        for p in &s {
            assert!((p.z_mm - tilted_flat_z(&job, p.rho_mm, p.theta).0).abs() < 1e-12);
        }
        let rpm = job.machine.spindle_rpm;
        let r = check_axes(&s, &MachineSpec::spindle_only(rpm));
        let w = omega(rpm);
        let expected_cycle = planner.spiral().revolutions() * 60.0 / rpm;
        assert!((r.cycle_time_s / expected_cycle - 1.0).abs() < 1e-12);
        let tan = 0.05f64.to_radians().tan();
        let (f, nose, h) = (0.02, 0.5, TAU / 360.0);
        let start = s[0].rho_mm;
        let third = tan * (start + 3.0 * f / TAU) + 8.0 * nose * tan * tan;
        let brute = s
            .windows(2)
            .map(|p| {
                let (rho, theta) = (
                    (p[0].rho_mm + p[1].rho_mm) / 2.0,
                    (p[0].theta + p[1].theta) / 2.0,
                );
                tilted_flat_z(&job, rho, theta).1.abs() * w
            })
            .fold(0.0, f64::max);
        assert!((r.z.max_velocity_mm_per_s - brute).abs() <= w * h * h / 24.0 * third);
        let at = r.z.max_velocity_at.unwrap();
        assert!(at.index <= 360 && at.rho_mm >= start - f, "{at:?}");
        let near = |value: f64, ideal: f64, slack: f64| (value - ideal).abs() <= slack;
        let slack = tan * (f / TAU + nose * tan + at.rho_mm * h * h / 8.0 + start * h * h / 24.0);
        assert!(near(
            r.z.max_velocity_mm_per_s,
            at.rho_mm * tan * w,
            slack * w
        ));
        let at = r.z.max_acceleration_at.unwrap();
        let slack =
            tan * (2.0 * f / TAU + 2.0 * nose * tan + start * h * h / 8.0 + start * h * h / 12.0);
        assert!(at.index <= 360, "{at:?}");
        assert!(near(
            r.z.max_acceleration_mm_per_s2,
            at.rho_mm * tan * w * w,
            slack * w * w
        ));
    }

    /// With the Z slide limited to half the rim's velocity, the violations are the blocks where
    /// the closed-form |dz/dθ|·ω at the block's middle exceeds the limit (counted by brute
    /// force, ±1e-4 relative for the chord error, 2.6e-5 at the threshold), they lie outside
    /// half the start radius, and the first is in the first revolution where |sin(θ − β)| > ½.
    #[test]
    fn tilted_flat_violations_are_at_the_rim() {
        let job = tilted_flat_job();
        let planner = ToolPath::new(&job).unwrap();
        let s = slide_only_samples(&planner).unwrap();
        let rpm = job.machine.spindle_rpm;
        let w = omega(rpm);
        let tan = 0.05f64.to_radians().tan();
        let start = s[0].rho_mm;
        let limit = 0.5 * start * tan * w;
        let mut machine = MachineSpec::spindle_only(rpm);
        machine.z_slide = Some(SlideSpec {
            velocity_mm_per_min: limit * 60.0,
            acceleration_mm_per_s2: 1e9,
            bandwidth_hz: 10.0,
        });
        let r = check_axes(&s, &machine);
        let over = |factor: f64| {
            s.windows(2)
                .filter(|p| {
                    let (rho, theta) = (
                        (p[0].rho_mm + p[1].rho_mm) / 2.0,
                        (p[0].theta + p[1].theta) / 2.0,
                    );
                    tilted_flat_z(&job, rho, theta).1.abs() * w > limit * factor
                })
                .count() as u64
        };
        let count = r.z.velocity_violation_count;
        assert!(
            over(1.0 + 1e-4) <= count && count <= over(1.0 - 1e-4),
            "{count}"
        );
        assert!(count > 1000 && r.z.velocity_violations.len() == MAX_LISTED);
        for v in &r.z.velocity_violations {
            assert!(v.at.rho_mm >= 0.5 * start * (1.0 - 1e-3), "{v:?}");
            assert!(v.value > limit && v.limit == limit);
            assert_eq!(v.quantity, Quantity::VelocityMmPerS);
        }
        let first = r.z.velocity_violations[0].at;
        assert!(first.index < 360 && (first.theta_deg.to_radians()).sin().abs() > 0.49);
        assert!(!r.within_limits && r.warnings[0].starts_with("Z velocity exceeds"));
        let m = r.max_spindle.unwrap();
        assert_eq!(m.binding_limit, "machine.z_slide.velocity_mm_per_min");
        assert!(m.max_spindle_rpm < rpm * 0.51);
    }

    /// Each limit in turn made to bind (the others far out of reach): the speed found is
    /// `n₀·V/v`, `n₀·√(A/a)` or `n₀·B/b`; re-running at that speed meets the binding limit to
    /// 1e-9 relative with no violation, and 1e-6 faster violates it.
    #[test]
    fn highest_speed_meets_the_binding_limit() {
        let rpm = 600.0;
        let s = samples(720, 3, 0.0, |t| {
            (0.002 * (3.0 * t).sin(), 0.0005 * (40.0 * t).sin())
        });
        let base = check_axes(&s, &unlimited(rpm));
        assert!(base.within_limits);
        type Set = fn(&mut MachineSpec, &AxisReport);
        let cases: [(&str, f64, Set); 5] = [
            ("machine.x_slide.velocity_mm_per_min", 1.0, |m, r| {
                m.x_slide.as_mut().unwrap().velocity_mm_per_min = 0.5 * r.x.max_velocity_mm_per_min
            }),
            ("machine.z_slide.velocity_mm_per_min", 1.0, |m, r| {
                m.z_slide.as_mut().unwrap().velocity_mm_per_min = 0.3 * r.z.max_velocity_mm_per_min
            }),
            ("machine.z_slide.acceleration_mm_per_s2", 2.0, |m, r| {
                m.z_slide.as_mut().unwrap().acceleration_mm_per_s2 =
                    0.2 * r.z.max_acceleration_mm_per_s2
            }),
            ("machine.fts.acceleration_m_per_s2", 2.0, |m, r| {
                m.fts.as_mut().unwrap().acceleration_m_per_s2 =
                    3.0 * r.w.max_acceleration_mm_per_s2 * 1e-3
            }),
            ("machine.block_rate_hz", 1.0, |m, r| {
                m.block_rate_hz = Some(0.7 * r.block_rate.required_hz)
            }),
        ];
        for (field, power, set) in cases {
            let mut machine = unlimited(rpm);
            set(&mut machine, &base);
            let r = check_axes(&s, &machine);
            let m = r.max_spindle.clone().unwrap();
            assert_eq!(m.binding_limit, field);
            let ratio = |r: &AxisReport| match field {
                "machine.x_slide.velocity_mm_per_min" => {
                    r.x.max_velocity_mm_per_s / r.x.velocity_limit_mm_per_s.unwrap()
                }
                "machine.z_slide.velocity_mm_per_min" => {
                    r.z.max_velocity_mm_per_s / r.z.velocity_limit_mm_per_s.unwrap()
                }
                "machine.z_slide.acceleration_mm_per_s2" => {
                    r.z.max_acceleration_mm_per_s2 / r.z.acceleration_limit_mm_per_s2.unwrap()
                }
                "machine.fts.acceleration_m_per_s2" => {
                    r.w.max_acceleration_mm_per_s2 / r.w.acceleration_limit_mm_per_s2.unwrap()
                }
                _ => r.block_rate.required_hz / r.block_rate.limit_hz.unwrap(),
            };
            // The closed form from the figures at n₀.
            let expected = rpm * (1.0 / ratio(&r)).powf(1.0 / power);
            assert!(
                (m.max_spindle_rpm / expected - 1.0).abs() < 1e-12,
                "{field}"
            );
            let mut at_max = machine.clone();
            at_max.spindle_rpm = m.max_spindle_rpm;
            let again = check_axes(&s, &at_max);
            assert!((ratio(&again) - 1.0).abs() < 1e-9, "{field}");
            assert!(again.within_limits, "{field}: {:?}", again.warnings);
            assert!(again.warnings.is_empty(), "{field}: {:?}", again.warnings);
            at_max.spindle_rpm *= 1.0 + 1e-6;
            assert!(!check_axes(&s, &at_max).within_limits, "{field}");
        }
    }

    /// A repeated point is a zero-time block: counted, located, left out of the velocities
    /// (which equal those of the path without it) and of the accelerations on either side; a
    /// sample with a NaN is skipped; no input panics.
    #[test]
    fn zero_time_blocks_and_bad_samples_are_reported() {
        let clean = samples(36, 2, 0.0, |t| (0.01 * t.sin(), 0.0));
        let mut s = clean.clone();
        s.insert(10, s[9]);
        s.insert(
            20,
            AxisSample {
                z_mm: f64::NAN,
                ..s[19]
            },
        );
        let machine = presets()[0].machine(100.0);
        let r = check_axes(&s, &machine);
        let c = check_axes(&clean, &machine);
        assert_eq!((r.points, r.skipped_samples), (clean.len() as u64 + 1, 1));
        assert_eq!(r.zero_time_block_count, 1);
        assert_eq!(r.zero_time_blocks[0].index, 10);
        assert_eq!(r.z.max_velocity_mm_per_s, c.z.max_velocity_mm_per_s);
        assert_eq!(r.cycle_time_s, c.cycle_time_s);
        assert!(c.within_limits && !r.within_limits);
        assert!(r.warnings.iter().any(|w| w.contains("zero time")));
        for few in [&s[..0], &s[..1]] {
            let r = check_axes(few, &machine);
            assert_eq!(
                (r.cycle_time_s, r.block_rate.at, r.max_spindle),
                (0.0, None, None)
            );
            assert!(r.within_limits);
        }
        // Non-finite spindle speed: figures are not finite, nothing panics.
        let r = check_axes(&s, &MachineSpec::spindle_only(f64::NAN));
        assert!(!r.cycle_time_s.is_finite());
        assert!(r.to_json().contains("\"cycle_time_s\": null"));
    }

    /// The stroke used is max W − min W, 2B for a sine sampled on its peaks, against the
    /// FTS's: within at 70 µm for B = 30 µm, over at 50 µm.
    #[test]
    fn fts_stroke_is_checked() {
        let b = 0.03;
        let s = samples(360, 1, 0.0, |t| (0.0, b * (2.0 * t).sin()));
        let mut machine = presets()[2].machine(60.0);
        let r = check_axes(&s, &machine);
        assert!((r.fts_stroke.used_um - 60.0).abs() < 1e-9);
        assert!(r.fts_stroke.within_limit && r.fts_stroke.limit_um == Some(70.0));
        machine.fts.as_mut().unwrap().stroke_um = 50.0;
        let r = check_axes(&s, &machine);
        assert!(!r.fts_stroke.within_limit && !r.within_limits);
        assert!(
            r.warnings
                .iter()
                .any(|w| w.contains("over the FTS's 50 um"))
        );
    }

    /// The listed violations stop at [`MAX_LISTED`], in path order, and the count is the brute
    /// force count of blocks over the limit.
    #[test]
    fn violations_are_listed_up_to_the_cap_and_counted() {
        let s = samples(100, 5, 0.0, |t| (0.01 * t.sin(), 0.0));
        let mut machine = MachineSpec::spindle_only(300.0);
        machine.block_rate_hz = Some(1.0);
        machine.x_slide = presets()[0].x_slide.into();
        let r = check_axes(&s, &machine);
        assert_eq!(r.block_rate.violation_count, 500);
        assert_eq!(r.block_rate.violations.len(), MAX_LISTED);
        assert!(
            r.block_rate
                .violations
                .windows(2)
                .all(|v| v[0].at.index < v[1].at.index)
        );
        assert_eq!(r.block_rate.violations[0].at.index, 1);
        let required = 300.0 / 60.0 * 100.0;
        assert!((r.block_rate.required_hz / required - 1.0).abs() < 1e-9);
        assert_eq!(r.x.velocity_violation_count, 0);
        assert!(r.to_json().contains("\"quantity\": \"block_rate_hz\""));
    }
}
