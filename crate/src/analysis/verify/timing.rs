//! Feeds, block times, the spindle speed and the cycle time of a program, and its moves against
//! the job's machine (`machine`): slide velocities, the block rate, the servo's stroke.
//!
//! A feed move's time follows from its feed mode: under `G93` from F as the job's
//! `output.feed_mode` reads it ([`crate::job::FeedMode`]: `1/F` minutes, RS274/NGC's inverse
//! time, by default; F seconds or F minutes for the block-time readings); under `G94` the
//! distance over F in mm/min (the length in X, Z and the servo's axis, or, for a move of C alone,
//! degrees over F in degrees/min, as LinuxCNC does); under `G95` the distance over F·S, S the
//! last spindle speed written (the job's `machine.spindle_rpm` before any). The spindle speed
//! of a cutting block is its ΔC over its time. Rapids have no programmed time: they are counted
//! and measured, and left out of the cycle time. Accelerations are not checked here (the
//! planned path's are, by [`crate::dynamics::axis_checks`]).

use crate::job::{FeedMode, MachineSpec};
use crate::nc::reader::{Feed, FeedRateMode, Location};
use serde::Serialize;

/// A range of values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Range {
    /// Smallest.
    pub min: f64,
    /// Largest.
    pub max: f64,
    /// Mean.
    pub mean: f64,
}

/// Accumulates a [`Range`].
#[derive(Debug, Clone, Copy, Default)]
struct RangeAcc {
    n: u64,
    sum: f64,
    min: f64,
    max: f64,
}

impl RangeAcc {
    fn add(&mut self, v: f64) {
        if self.n == 0 {
            (self.min, self.max) = (v, v);
        }
        self.n += 1;
        self.sum += v;
        self.min = self.min.min(v);
        self.max = self.max.max(v);
    }

    fn range(&self) -> Option<Range> {
        (self.n > 0).then(|| Range {
            min: self.min,
            max: self.max,
            mean: self.sum / self.n as f64,
        })
    }
}

/// The program's feeds and times.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimingReport {
    /// How `G93`'s F was read (the job's `output.feed_mode`).
    pub g93_reading: &'static str,
    /// The feed modes of the cutting moves: `G93`, `G94`, `G95`.
    pub cutting_feed_modes: Vec<&'static str>,
    /// F of the cutting moves as written.
    pub cutting_feed: Option<Range>,
    /// Time of a cutting block, s.
    pub block_time_s: Option<Range>,
    /// Spindle speed of the cutting blocks from their ΔC and time, rev/min.
    pub spindle_rpm: Option<Range>,
    /// The S words written, rev/min.
    pub spindle_s_words: Option<Range>,
    /// Time of the cutting moves, s.
    pub cutting_time_s: f64,
    /// Time of the other feed moves (approach, plunge, retract at feed), s.
    pub other_feed_time_s: f64,
    /// Rapid moves: how many and how long in all, mm (left out of the cycle time).
    pub rapid_moves: u64,
    /// Length of the rapids, mm.
    pub rapid_length_mm: f64,
    /// Cutting and other feed moves, s.
    pub cycle_time_s: f64,
    /// Feed moves whose time is unknown (no F yet in their mode).
    pub moves_without_feed: u64,
}

/// A line of the program.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Written {
    /// The file.
    pub file: String,
    /// The line, from 1.
    pub line: u64,
}

impl From<&Location> for Written {
    fn from(at: &Location) -> Self {
        Self {
            file: at.file.to_string(),
            line: at.line,
        }
    }
}

/// A limit of the machine checked against the program's moves.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LimitCheck {
    /// The job's field.
    pub field: &'static str,
    /// Its value.
    pub limit: f64,
    /// The program's largest value of it.
    pub largest: f64,
    /// Moves beyond it.
    pub moves_beyond: u64,
    /// The first move beyond it.
    pub first_beyond: Option<Written>,
}

/// A move's figures for the timing.
#[derive(Debug, Clone, Copy)]
pub struct MoveFigures {
    /// Length in the linear axes (X, Z and the servo), mm.
    pub length_mm: f64,
    /// |ΔX|, |ΔZ| (the slide alone), mm.
    pub dx_mm: f64,
    /// See `dx_mm`.
    pub dz_mm: f64,
    /// |ΔC|, degrees (unwrapped).
    pub dc_deg: f64,
    /// A rapid.
    pub rapid: bool,
    /// A cutting move.
    pub cutting: bool,
}

/// Accumulates the timing and the machine's limits.
#[derive(Debug, Clone)]
pub struct Timing {
    reading: FeedMode,
    default_rpm: f64,
    s_word: Option<f64>,
    machine: MachineSpec,
    modes: [bool; 3],
    feed: RangeAcc,
    block: RangeAcc,
    rpm: RangeAcc,
    s_words: RangeAcc,
    cutting_s: f64,
    other_s: f64,
    rapids: u64,
    rapid_mm: f64,
    no_feed: u64,
    /// x velocity, z velocity, block rate: largest, beyond, first beyond.
    limits: [(f64, u64, Option<Written>); 3],
    servo: Option<(f64, f64)>,
}

impl Timing {
    /// Timing read with the job's G93 reading `reading` on `machine`.
    pub fn new(reading: FeedMode, machine: &MachineSpec) -> Self {
        Self {
            reading,
            default_rpm: machine.spindle_rpm,
            s_word: None,
            machine: machine.clone(),
            modes: [false; 3],
            feed: RangeAcc::default(),
            block: RangeAcc::default(),
            rpm: RangeAcc::default(),
            s_words: RangeAcc::default(),
            cutting_s: 0.0,
            other_s: 0.0,
            rapids: 0,
            rapid_mm: 0.0,
            no_feed: 0,
            limits: [(0.0, 0, None), (0.0, 0, None), (0.0, 0, None)],
            servo: None,
        }
    }

    /// An S word.
    pub fn spindle(&mut self, rpm: f64) {
        self.s_word = Some(rpm);
        self.s_words.add(rpm);
    }

    /// The servo's value at a cutting point, mm.
    pub fn servo_at(&mut self, w: f64) {
        self.servo = Some(self.servo.map_or((w, w), |(a, b)| (a.min(w), b.max(w))));
    }

    /// The time of a feed move, s, if its feed is known.
    pub fn block_time_s(&self, feed: &Feed, m: &MoveFigures) -> Option<f64> {
        let f = feed.f.filter(|f| *f > 0.0 && f.is_finite())?;
        let t = match feed.mode {
            FeedRateMode::InverseTime => match self.reading {
                FeedMode::BlockTimeS => f,
                FeedMode::BlockTimeMin => 60.0 * f,
                FeedMode::InverseTime | FeedMode::PerMinute => 60.0 / f,
            },
            FeedRateMode::PerMinute if m.length_mm > 0.0 => 60.0 * m.length_mm / f,
            FeedRateMode::PerMinute => 60.0 * m.dc_deg / f,
            FeedRateMode::PerRevolution => {
                60.0 * m.length_mm / (f * self.s_word.unwrap_or(self.default_rpm))
            }
        };
        Some(t)
    }

    /// Adds a move written at `at` under `feed`.
    pub fn add(&mut self, feed: &Feed, m: &MoveFigures, at: &Location) {
        if m.rapid {
            self.rapids += 1;
            self.rapid_mm += m.length_mm;
            return;
        }
        let Some(t) = self.block_time_s(feed, m) else {
            self.no_feed += 1;
            return;
        };
        if m.cutting {
            self.modes[feed.mode as usize] = true;
            self.feed.add(feed.f.unwrap_or(0.0));
            self.block.add(t);
            self.cutting_s += t;
            if m.dc_deg > 0.0 && t > 0.0 {
                self.rpm.add(m.dc_deg / 360.0 * 60.0 / t);
            }
        } else {
            self.other_s += t;
        }
        if t > 0.0 {
            let values = [m.dx_mm / t * 60.0, m.dz_mm / t * 60.0, 1.0 / t];
            let limits = self.limit_values();
            for ((acc, v), limit) in self.limits.iter_mut().zip(values).zip(limits) {
                acc.0 = acc.0.max(v);
                if limit.is_some_and(|l| v > l) {
                    acc.1 += 1;
                    if acc.2.is_none() {
                        acc.2 = Some(at.into());
                    }
                }
            }
        }
    }

    fn limit_values(&self) -> [Option<f64>; 3] {
        let m = &self.machine;
        [
            m.x_slide.map(|s| s.velocity_mm_per_min),
            m.z_slide.map(|s| s.velocity_mm_per_min),
            m.block_rate_hz,
        ]
    }

    /// The feeds and times.
    pub fn report(&self) -> TimingReport {
        const MODES: [&str; 3] = ["G93", "G94", "G95"];
        TimingReport {
            g93_reading: self.reading.meaning(),
            cutting_feed_modes: MODES
                .iter()
                .zip(self.modes)
                .filter_map(|(m, on)| on.then_some(*m))
                .collect(),
            cutting_feed: self.feed.range(),
            block_time_s: self.block.range(),
            spindle_rpm: self.rpm.range(),
            spindle_s_words: self.s_words.range(),
            cutting_time_s: self.cutting_s,
            other_feed_time_s: self.other_s,
            rapid_moves: self.rapids,
            rapid_length_mm: self.rapid_mm,
            cycle_time_s: self.cutting_s + self.other_s,
            moves_without_feed: self.no_feed,
        }
    }

    /// The machine's limits that the job gives, against the program.
    pub fn limits(&self) -> Vec<LimitCheck> {
        const FIELDS: [&str; 3] = [
            "machine.x_slide.velocity_mm_per_min",
            "machine.z_slide.velocity_mm_per_min",
            "machine.block_rate_hz",
        ];
        let mut out: Vec<LimitCheck> = FIELDS
            .iter()
            .zip(self.limit_values())
            .zip(&self.limits)
            .filter_map(|((field, limit), acc)| {
                limit.map(|limit| LimitCheck {
                    field,
                    limit,
                    largest: acc.0,
                    moves_beyond: acc.1,
                    first_beyond: acc.2.clone(),
                })
            })
            .collect();
        if let (Some(fts), Some((lo, hi))) = (self.machine.fts, self.servo) {
            let stroke = (hi - lo) * 1e3;
            out.push(LimitCheck {
                field: "machine.fts.stroke_um",
                limit: fts.stroke_um,
                largest: stroke,
                moves_beyond: u64::from(stroke > fts.stroke_um),
                first_beyond: None,
            });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::Job;
    use std::sync::Arc;

    fn figures(length_mm: f64, dc_deg: f64) -> MoveFigures {
        MoveFigures {
            length_mm,
            dx_mm: length_mm,
            dz_mm: 0.0,
            dc_deg,
            rapid: false,
            cutting: true,
        }
    }

    #[test]
    fn block_times_follow_the_feed_mode_and_its_reading() {
        let machine = Job::default_job().machine;
        let t = Timing::new(FeedMode::InverseTime, &machine);
        let g93 = Feed {
            mode: FeedRateMode::InverseTime,
            f: Some(288_000.0),
        };
        // 1 degree at 800 rpm: 360·800/1 = 288000 per minute.
        let s = t.block_time_s(&g93, &figures(0.0, 1.0)).unwrap();
        assert!((s - 60.0 / 288_000.0).abs() < 1e-18);
        let t = Timing::new(FeedMode::BlockTimeS, &machine);
        let g93s = Feed {
            mode: FeedRateMode::InverseTime,
            f: Some(0.001),
        };
        assert_eq!(t.block_time_s(&g93s, &figures(0.0, 1.0)), Some(0.001));
        let g94 = Feed {
            mode: FeedRateMode::PerMinute,
            f: Some(30.0),
        };
        assert_eq!(t.block_time_s(&g94, &figures(0.5, 0.0)), Some(1.0));
        assert_eq!(t.block_time_s(&g94, &figures(0.0, 90.0)), Some(180.0));
        let none = Feed {
            mode: FeedRateMode::PerMinute,
            f: None,
        };
        assert_eq!(t.block_time_s(&none, &figures(1.0, 0.0)), None);
    }

    #[test]
    fn spindle_speed_and_block_rate_come_from_the_cutting_blocks() {
        let mut machine = Job::default_job().machine;
        machine.block_rate_hz = Some(1000.0);
        let mut t = Timing::new(FeedMode::InverseTime, &machine);
        let at = Location {
            file: Arc::from("p"),
            line: 9,
        };
        // 2 degrees in 1/1200 s: 1/180 rev in 1/1200 s = 400 rpm, 1200 blocks/s.
        let feed = Feed {
            mode: FeedRateMode::InverseTime,
            f: Some(72_000.0),
        };
        t.add(&feed, &figures(0.001, 2.0), &at);
        let r = t.report();
        assert!((r.spindle_rpm.unwrap().max - 400.0).abs() < 1e-9);
        let limits = t.limits();
        assert_eq!(limits.len(), 1);
        assert!((limits[0].largest - 1200.0).abs() < 1e-9);
        assert_eq!(limits[0].moves_beyond, 1);
        assert_eq!(limits[0].first_beyond.as_ref().unwrap().line, 9);
    }
}
