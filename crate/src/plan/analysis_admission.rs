//! Admission of an accuracy analysis ([`crate::analysis::Analysis`]), as [`super::admission`]
//! admits a plan: the job's cost estimated before any point is walked, and refused beyond stated
//! limits with the feed that would do. The analysis walks the path like a plan and checks every
//! segment between two points by samples along it ([`crate::analysis::linearization`]: 8 a
//! feature length of the surface, 4 to 4096 a segment) and refined points at its extremes, each
//! one compensation, whose cost depends on the surface far more than a planned point's does
//! (scattered data: each evaluation walks its own line, 190 µs against 23 µs a planned point).
//! So both are timed by the caller's clock: the plan's points at the probes
//! ([`Planner::cost`]), and [`TIMED_EVALUATIONS`] evaluations of the segments of
//! [`TIMED_SEGMENTS`] probes spread in radius, each segment's cost being its samples
//! ([`segment_intervals`]) and [`REFINING_EVALUATIONS`] such evaluations: timing whole segments
//! took seconds where one has 4096 samples.
//! The command line and the page admit an analysis through this one function.

use super::{PlanError, Planner};
use crate::analysis::linearization::{INTERVALS_PER_FEATURE, error_at, segment_intervals};
use crate::field::{FieldError, feed_within, short};
use crate::parallel::workers;
use crate::report::duration;

/// Segments of the path whose accuracy checks are timed for the estimate, spread in radius.
pub const TIMED_SEGMENTS: usize = 16;

const _: () = assert!(TIMED_SEGMENTS.is_power_of_two());

/// Evaluations of the error timed in each of those segments, at evenly spaced interior points.
pub const TIMED_EVALUATIONS: usize = 3;

/// Evaluations a segment's check takes besides its samples, refining its extremes: 3.9 a
/// segment measured on the scattered example, 1.4 on the paper 004 lens array.
pub const REFINING_EVALUATIONS: usize = 4;

/// The most the timing of those segments takes, s (at least one is timed).
pub const TIMING_BUDGET_S: f64 = 2.0;

/// The bounds an analysis is admitted under.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalysisLimits {
    /// Most points walked.
    pub max_points: u64,
    /// Longest estimated time, s.
    pub max_seconds: f64,
}

impl Default for AnalysisLimits {
    /// 30 M points (a 28.4 M-point finishing path, about half a minute on two cores for an
    /// asphere) and 600 s.
    fn default() -> Self {
        Self {
            max_points: 30_000_000,
            max_seconds: 600.0,
        }
    }
}

impl Planner {
    /// Admits an analysis of this job as a plan is admitted ([`Planner::cost`]: the surface
    /// defined and its heights finite and within reach at probes along the path), and refuses
    /// more than `limits.max_points` points or an estimated time above `limits.max_seconds`,
    /// naming the feed that would do (the time goes about as 1/f, as the points do). The time,
    /// by `clock` (seconds), is the plan's per point and the checks of a segment between two
    /// points, timed at up to [`TIMED_SEGMENTS`] probes in [`TIMING_BUDGET_S`], on every core.
    pub fn admit_analysis(
        &self,
        limits: AnalysisLimits,
        clock: &(dyn Fn() -> f64 + Sync),
    ) -> Result<(), PlanError> {
        let cost = self.cost(Some(clock))?;
        let feed = self.job().strategy.feed_mm_per_rev;
        let points = cost.points as f64;
        let refuse = |ratio: f64, what: String| -> Result<(), PlanError> {
            Err(FieldError::new(
                "strategy.feed_mm_per_rev",
                feed,
                format!(
                    "{what}: a feed of at least {} mm/rev keeps it under",
                    short(feed_within(feed, ratio))
                ),
            )
            .into())
        };
        let max_points = limits.max_points;
        if cost.points > max_points {
            let what = format!(
                "gives about {} points; analyse walks at most {max_points} (--max-points raises \
                 it)",
                short(points)
            );
            return refuse(points / max_points as f64, what);
        }
        // The analysis reads the path without the machine dynamics.
        let planning = cost.seconds.unwrap_or(0.0) - cost.dynamics_seconds.unwrap_or(0.0);
        let per_point = planning / points.max(1.0);
        let (cost, timed) = self.segment_seconds(clock)?;
        let seconds = points * (per_point + cost.segment / workers() as f64);
        let max_seconds = limits.max_seconds;
        if seconds > max_seconds {
            let places = if timed == 1 { "place" } else { "places" };
            let cores = match workers() {
                1 => "one core".to_string(),
                n => format!("{n} cores"),
            };
            let what = format!(
                "gives about {} points, about {} to analyse on {cores} (the checks between two \
                 points, {INTERVALS_PER_FEATURE} samples a feature length of {} mm or more and \
                 about {REFINING_EVALUATIONS} refining the extremes, take {} a segment on one \
                 core: {} an evaluation, timed at {timed} {places} along the path), above the \
                 limit of {max_seconds} s (--max-seconds raises it)",
                short(points),
                duration(seconds),
                short(self.surface().feature_length_mm()),
                time_words(cost.segment),
                time_words(cost.evaluation),
            );
            return refuse(seconds / max_seconds, what);
        }
        Ok(())
    }

    /// The mean time by `clock` of the accuracy checks of one segment between two path points
    /// and of one evaluation in them, s, and how many segments were timed: those of up to
    /// [`TIMED_SEGMENTS`] probes ([`crate::tool::ToolPath::probe`]), visited in an order that
    /// spreads them in radius, until [`TIMING_BUDGET_S`] has passed; each weighted by the path's
    /// points per mm of radius there. A segment whose check fails is the analysis's error, given
    /// at once.
    fn segment_seconds(&self, clock: &dyn Fn() -> f64) -> Result<(SegmentCost, usize), PlanError> {
        let probes = self.probe(TIMED_SEGMENTS)?;
        let n = probes.len();
        let start = clock();
        let (mut segment, mut evaluation, mut weights, mut timed) = (0.0, 0.0, 0.0, 0);
        // The probes in bit-reversed order: the visits jump across the radius rather than walk
        // it, so a timing cut short still spans it.
        let bits = TIMED_SEGMENTS.trailing_zeros();
        let order = (0..TIMED_SEGMENTS).map(|i| i.reverse_bits() >> (usize::BITS - bits));
        for k in order.filter(|&k| k < n) {
            let [_, a, b] = &probes[k].points;
            let samples = segment_intervals(self, a, b)? - 1;
            let mut took = 0.0;
            for i in 1..=TIMED_EVALUATIONS {
                let began = clock();
                error_at(self, a, b, i as f64 / (TIMED_EVALUATIONS + 1) as f64)?;
                took += (clock() - began).max(0.0);
            }
            let each = took / TIMED_EVALUATIONS as f64;
            let w = probes[k].per_mm;
            evaluation += each * w;
            segment += each * (samples + REFINING_EVALUATIONS) as f64 * w;
            weights += w;
            timed += 1;
            if clock() - start > TIMING_BUDGET_S {
                break;
            }
        }
        let mean = |total: f64| if weights > 0.0 { total / weights } else { 0.0 };
        let cost = SegmentCost {
            segment: mean(segment),
            evaluation: mean(evaluation),
        };
        Ok((cost, timed))
    }
}

/// The time of one segment's accuracy checks and of one evaluation in them, s.
struct SegmentCost {
    segment: f64,
    evaluation: f64,
}

/// A time in words: milliseconds below a second, else [`duration`]'s.
fn time_words(s: f64) -> String {
    if s >= 1.0 {
        duration(s)
    } else {
        format!("{:.3} ms", s * 1e3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::Job;
    use std::sync::atomic::{AtomicU64, Ordering};

    /// A clock that moves `step` seconds at every reading (by any thread).
    fn ticking(step: f64) -> impl Fn() -> f64 + Sync {
        let readings = AtomicU64::new(0);
        move || (readings.fetch_add(1, Ordering::Relaxed) + 1) as f64 * step
    }

    #[test]
    fn the_timed_checks_decide_and_the_refusal_says_why() {
        let planner = Planner::new(&Job::default_job()).unwrap();
        let limits = AnalysisLimits::default();
        // A microsecond a reading: every probe timed, far under 600 s.
        planner.admit_analysis(limits, &ticking(1e-6)).unwrap();
        // A second a reading: each evaluation takes 1 s between its two readings, and the
        // timing stops after the first segment (7 s of its 2 s budget gone).
        let e = planner
            .admit_analysis(limits, &ticking(1.0))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("strategy.feed_mm_per_rev = ")
                && e.contains("1.00 s an evaluation, timed at 1 place along the path")
                && e.contains("above the limit of 600 s"),
            "{e}"
        );
        // The points limit first, with the feed that keeps under it.
        let points = planner.spiral().point_count_hint();
        let few = AnalysisLimits {
            max_points: points / 2,
            ..limits
        };
        let e = planner
            .admit_analysis(few, &ticking(1e-6))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(&format!("analyse walks at most {}", points / 2)),
            "{e}"
        );
    }
}
