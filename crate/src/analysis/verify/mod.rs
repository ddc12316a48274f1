//! A program from any system verified against the design (issue 14): `spiralcam verify` and
//! the page's "Open NC…". The program is read with the NC reader ([`crate::nc::reader`]) as a
//! controller would run it (loops, `G52` shifts, child programs), its positions taken to the
//! part's frame with the job's `output` conventions ([`frame`]), and every cutting move's
//! commanded tool tip compared with the ideal one: the one-way compensated tip of the job's
//! tool over the same (ρ, θ) ([`crate::tool::NoseCompensator`], paper 003 eqs 17–24 solved as a
//! maximum). One compensation a point; nothing of the program is kept.
//!
//! - A **cutting move** is a feed move (G1, G2, G3) that turns C; in a program that never
//!   turns C (2-D turning), a feed move in X ([`scan::CuttingRule`]). Its end is a cutting
//!   point (an arc's points every 5° of its sweep too); the deviation there is
//!   `z_program − z_tip(ρ, θ)`, positive where the program leaves material above the design,
//!   negative where it cuts into it. A 2-D program is compared at θ = 0 (its C as written).
//! - A **pass** is a run of consecutive cutting moves; anything else (a rapid, a plunge, a
//!   retract) ends it. Its stock is its mean deviation. The last pass is the one that leaves
//!   the surface: its deviation is the report's `deviation_um`, its points the deviation map,
//!   and the accuracy analyses follow it.
//! - **Accuracy**: the linearization error along the last pass's blocks
//!   ([`crate::analysis::linearization`], the blocks' own ends included, so it adds to the
//!   points' deviation the gap between them) and the predicted form of the last pass
//!   ([`crate::analysis::predicted_form`], on the job's radial step; not for 2-D programs).
//! - **Feeds and times** ([`timing`]), the machine's limits, the **collisions** of the moves
//!   that do not cut ([`collision`]) and **warnings** for what is read but not interpreted
//!   ([`warnings`]).
//!
//! The program is read twice: once to count its moves and passes ([`scan`]), once to verify.
//! Time is that of the reader plus one compensation per cutting point (plus the accuracy
//! analyses over the last pass, bounded by [`VerifySettings::max_accuracy_points`]); memory is
//! the reader's, the maps' and the bounded lists' ([`MAX_LISTED_PASSES`] passes,
//! [`collision::MAX_LISTED`] collisions, [`warnings::MAX_KINDS`] warnings, a display trace of
//! the last pass of at most [`VerifySettings::trace_points`] points: every k-th cutting point,
//! k = ⌈points of the last pass / trace points⌉, which the page draws over the surface coloured
//! by deviation).
//!
//! Assumed, and stated in the report: program coordinates are the part's (work offsets zero,
//! `G52` and `G92` applied as the reader does), C = 0 at θ = 0.

pub mod collision;
pub mod deviation;
pub mod error;
pub mod frame;
pub mod scan;
pub mod timing;
pub mod warnings;

pub use collision::{Collision, CollisionReport};
pub use deviation::{At, DeviationStats, DeviationSummary};
pub use error::VerifyError;
pub use frame::{PartFrame, PartPoint};
pub use scan::{CuttingRule, Scan};
pub use timing::{LimitCheck, TimingReport, Written};

use crate::analysis::linearization::{LinearizationCheck, LinearizationReport};
use crate::analysis::predicted_form::{FormPredictor, FormSettings, PredictedForm};
use crate::field::FieldError;
use crate::job::Compensation;
use crate::nc::reader::{
    CWrapping, EventKind, Location, MachineAxis, Move, MoveKind, Position, Reader, Step, Summary,
    Units,
};
use crate::path::{PathError, PathPoint};
use crate::progress::{PROGRESS_EVERY, Progress, ProgressFn, Stage};
use crate::raster::Raster;
use crate::tool::ToolPath;
use collision::fractions;
use scan::PassCount;
use serde::Serialize;
use timing::{MoveFigures, Timing};
use warnings::Warnings;

/// The most passes listed in the report (all are counted).
pub const MAX_LISTED_PASSES: usize = 1000;
/// Fraction of the cutting points that may lie beyond the part before the program is taken
/// for another part's.
pub const MAX_BEYOND_FRACTION: f64 = 0.1;
/// Largest sweep between the points compared along an arc, degrees.
const ARC_STEP_DEG: f64 = 5.0;

/// How to verify.
#[derive(Debug, Clone, PartialEq)]
pub struct VerifySettings {
    /// Samples per side of the deviation map (and of the accuracy maps).
    pub map_size: usize,
    /// A move that does not cut and comes more than this below the design is a collision, µm.
    pub collision_tolerance_um: f64,
    /// Run the linearization and predicted-form analyses over the last pass.
    pub accuracy: bool,
    /// The longest last pass the accuracy analyses follow, points (they cost tens of
    /// compensations a point): 2·10⁷ by default, about as long as the planner's own limit.
    pub max_accuracy_points: u64,
    /// The most points of the display trace (the last pass, every k-th point).
    pub trace_points: usize,
}

impl Default for VerifySettings {
    fn default() -> Self {
        Self {
            map_size: 256,
            collision_tolerance_um: 0.1,
            accuracy: true,
            max_accuracy_points: 20_000_000,
            trace_points: 200_000,
        }
    }
}

/// One pass of the program.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassSummary {
    /// Cutting points.
    pub points: u64,
    /// Its mean deviation: the stock it leaves above the design, µm.
    pub stock_um: f64,
    /// Its deviation.
    pub deviation_um: DeviationSummary,
    /// Where it starts.
    pub starts_at: Written,
}

/// What the reader found out about the program and how it was read.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProgramFacts {
    /// `mm` or `inch`, as the program states first (`mm (not stated)` when it never does).
    pub units: &'static str,
    /// How the program writes C: `wrapped`, `cumulative`, `undetermined` or `no C`.
    pub c: &'static str,
    /// Smallest and largest C written, degrees.
    pub c_range_deg: Option<(f64, f64)>,
    /// Feed moves with X < 0 and with X > 0.
    pub x_negative_moves: u64,
    /// See `x_negative_moves`.
    pub x_positive_moves: u64,
    /// Cutting points with the tool past the spindle axis (X on the other side than
    /// `output.x_sign` says).
    pub past_axis_points: u64,
    /// Axes commanded.
    pub axes: String,
    /// The dialect the text looks like, and why.
    pub dialect: Option<String>,
    /// What shows it.
    pub dialect_evidence: Vec<String>,
    /// The conventions read with (the job's `output`): X = x_sign·ρ, Z = z_sign·z, C =
    /// c_sign·θ, the servo's word adding to Z.
    pub x_sign: f64,
    /// See `x_sign`.
    pub z_sign: f64,
    /// See `x_sign`.
    pub c_sign: f64,
    /// The servo's word.
    pub servo_word: String,
}

/// A point of the display trace: a cutting point of the last pass, in the part's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TracePoint {
    /// x, mm.
    pub x: f64,
    /// y, mm.
    pub y: f64,
    /// The commanded tip's height, mm.
    pub z: f64,
    /// Its deviation, µm (positive: material left).
    pub deviation_um: f64,
}

/// The verification of a program against a job.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verification {
    /// The job's name.
    pub job: String,
    /// The program as read.
    pub program: ProgramFacts,
    /// Moves executed (every loop pass and call counted).
    pub blocks: u64,
    /// Lines read.
    pub lines_read: u64,
    /// Which moves cut.
    pub cutting_rule: &'static str,
    /// Cutting points compared.
    pub cutting_points: u64,
    /// Cutting points beyond the part (radius beyond `part.diameter_mm / 2` plus
    /// `strategy.overtravel_mm`), not compared.
    pub beyond_part_points: u64,
    /// The largest radius of a cutting point, mm.
    pub largest_radius_mm: f64,
    /// The passes, in order (the first [`MAX_LISTED_PASSES`]).
    pub passes: Vec<PassSummary>,
    /// Passes in all.
    pub pass_count: u64,
    /// The deviation of the last pass, µm.
    pub deviation_um: DeviationSummary,
    /// The deviation of every pass together, µm.
    pub all_passes_deviation_um: DeviationSummary,
    /// The linearization error along the last pass's blocks.
    pub linearization: Option<LinearizationReport>,
    /// The form the last pass leaves, predicted.
    pub predicted_form: Option<PredictedForm>,
    /// Feeds, block times, spindle speed, cycle time.
    pub timing: TimingReport,
    /// The job's machine limits against the program.
    pub axis_limits: Vec<LimitCheck>,
    /// Moves that do not cut and come below the design.
    pub collisions: CollisionReport,
    /// What was read but not interpreted, and what does not match the job.
    pub warnings: Vec<String>,
    /// What was assumed, and why an analysis is missing.
    pub notes: Vec<String>,
    /// The deviation of the last pass on a raster over the part, µm (the largest magnitude in
    /// each cell).
    #[serde(skip)]
    pub map: Raster,
    /// Every k-th cutting point of the last pass, in order, for display (at most
    /// [`VerifySettings::trace_points`]; k the least that keeps within it).
    #[serde(skip)]
    pub trace: Vec<TracePoint>,
}

impl Verification {
    /// The figures as pretty JSON (the map and trace left out).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }
}

/// Opens the program afresh (it is read twice).
pub type Opener<'a, 'r> = dyn FnMut() -> Result<Reader<'r>, String> + 'a;

/// Verifies the program `open` gives against `tool_path`'s job (see the module docs);
/// `progress` sees the moves read ([`Stage::Scan`], then [`Stage::Verify`]) and may cancel.
pub fn verify(
    tool_path: &ToolPath,
    open: &mut Opener<'_, '_>,
    settings: &VerifySettings,
    progress: &mut ProgressFn,
) -> Result<Verification, VerifyError> {
    if tool_path.job().strategy.compensation == Compensation::TwoWay {
        return Err(FieldError::new(
            "strategy.compensation",
            "two_way",
            "verify compares with the one-way compensated tip (X on the spiral): set one_way",
        )
        .into());
    }
    let scan = scan::scan(open().map_err(VerifyError::Open)?, progress)?;
    if scan.passes.moves == 0 {
        return Err(VerifyError::NoCuttingMoves { moves: scan.moves });
    }
    let mut run = Run::new(tool_path, settings, scan);
    let mut reader = open().map_err(VerifyError::Open)?;
    run.from = reader.modal().position;
    run.c_from = run.frame.unwrap_c(run.from.c());
    while let Some(step) = reader.next_step()? {
        match step {
            Step::Move(m) => run.motion(&m)?,
            Step::Event(e) => {
                if let EventKind::Change(crate::nc::reader::Change::Spindle(s)) = e.kind {
                    run.timing.spindle(s);
                }
                run.warnings.event(&e.kind, &e.at);
            }
        }
        if run.blocks.is_multiple_of(PROGRESS_EVERY) && run.blocks > 0 && run.counted != run.blocks
        {
            run.counted = run.blocks;
            let p = Progress {
                stage: Stage::Verify,
                done: run.blocks,
                total: scan.moves,
            };
            if progress(p).is_break() {
                return Err(VerifyError::Cancelled);
            }
        }
    }
    let summary = reader.summary();
    run.finish(&summary)
}

/// The accuracy analyses of the last pass.
struct Accuracy<'t> {
    linearization: LinearizationCheck,
    form: Option<FormPredictor<'t>>,
}

/// A verification under way.
struct Run<'t> {
    tool_path: &'t ToolPath,
    settings: VerifySettings,
    scan: Scan,
    frame: PartFrame,
    timing: Timing,
    warnings: Warnings,
    notes: Vec<String>,
    collisions: CollisionReport,
    from: Position,
    c_from: f64,
    passes: PassCount,
    listed: Vec<PassSummary>,
    pass: DeviationStats,
    pass_start: Option<Written>,
    all: DeviationStats,
    last: DeviationStats,
    accuracy: Option<Accuracy<'t>>,
    accuracy_done: Option<(LinearizationReport, Option<PredictedForm>)>,
    map: Raster,
    trace: Vec<TracePoint>,
    stride: u64,
    blocks: u64,
    counted: u64,
    beyond: u64,
    largest_radius: f64,
    past_axis: u64,
    part_limit: f64,
    step_mm: f64,
    index: u64,
}

impl<'t> Run<'t> {
    fn new(tool_path: &'t ToolPath, settings: &VerifySettings, scan: Scan) -> Self {
        let job = tool_path.job();
        let part = job.part_radius_mm();
        let stride = scan
            .passes
            .last
            .div_ceil(settings.trace_points.max(1) as u64)
            .max(1);
        Self {
            tool_path,
            settings: settings.clone(),
            scan,
            frame: PartFrame::new(&job.output),
            timing: Timing::new(job.output.feed_mode, &job.machine),
            warnings: Warnings::default(),
            notes: Vec::new(),
            collisions: CollisionReport::new(settings.collision_tolerance_um),
            from: Position::default(),
            c_from: 0.0,
            passes: PassCount::default(),
            listed: Vec::new(),
            pass: DeviationStats::default(),
            pass_start: None,
            all: DeviationStats::default(),
            last: DeviationStats::default(),
            accuracy: None,
            accuracy_done: None,
            map: Raster::over_part(part, settings.map_size),
            trace: Vec::new(),
            stride,
            blocks: 0,
            counted: 0,
            beyond: 0,
            largest_radius: 0.0,
            past_axis: 0,
            part_limit: job.outer_radius_mm().max(part) * (1.0 + 1e-9) + 1e-9,
            step_mm: (part / 256.0).max(1e-6),
            index: 0,
        }
    }

    fn is_last_pass(&self) -> bool {
        self.passes.passes == self.scan.passes.passes
    }

    /// A move read.
    fn motion(&mut self, m: &Move) -> Result<(), VerifyError> {
        self.blocks += 1;
        let cuts = self.scan.rule.cuts(&self.from, m);
        let c_to = self.frame.unwrap_c(m.target.c());
        let a = self.frame.part_point(&self.from, self.c_from);
        let b = self.frame.part_point(&m.target, c_to);
        let figures = MoveFigures {
            length_mm: linear_length(&self.from, &m.target),
            dx_mm: (m.target.x() - self.from.x()).abs(),
            dz_mm: (m.target.z() - self.from.z()).abs(),
            dc_deg: (c_to - self.c_from).abs(),
            rapid: m.kind == MoveKind::Rapid,
            cutting: cuts,
        };
        self.timing.add(&m.feed, &figures, &m.at);
        self.note_axes(m);
        let was_in_pass = self.pass_start.is_some();
        if self.passes.add(cuts) {
            self.start_pass(m, a)?;
        } else if !cuts && was_in_pass {
            self.end_pass();
        }
        if cuts {
            self.timing.servo_at(self.frame.servo_value(&m.target));
            self.cut(m, b)?;
        } else {
            self.check_collision(m, a, b)?;
        }
        self.from = m.target;
        self.c_from = c_to;
        Ok(())
    }

    /// Moves of axes the verification does not interpret.
    fn note_axes(&mut self, m: &Move) {
        for axis in [
            MachineAxis::Y,
            MachineAxis::A,
            MachineAxis::B,
            MachineAxis::U,
            MachineAxis::V,
            MachineAxis::W,
        ] {
            if Some(axis) != self.frame.servo() && m.words.contains(axis) {
                self.warnings.note(
                    format!(
                        "{}: an axis not interpreted (neither X, Z, C nor the servo's {})",
                        axis.letter(),
                        self.frame.servo().map_or('-', MachineAxis::letter)
                    ),
                    &m.at,
                );
            }
        }
    }

    fn start_pass(&mut self, m: &Move, a: PartPoint) -> Result<(), VerifyError> {
        self.pass = DeviationStats::default();
        self.pass_start = Some((&m.at).into());
        if self.is_last_pass() && self.settings.accuracy {
            self.start_accuracy(a, &m.at)?;
        }
        Ok(())
    }

    fn start_accuracy(&mut self, a: PartPoint, at: &Location) -> Result<(), VerifyError> {
        let tp = self.tool_path;
        if self.scan.passes.last > self.settings.max_accuracy_points {
            self.notes.push(format!(
                "no linearization or predicted form: the last pass has {} points, more than \
                 the {} the accuracy analyses follow",
                self.scan.passes.last, self.settings.max_accuracy_points
            ));
            return Ok(());
        }
        let form = if self.scan.rule == CuttingRule::MovesX {
            self.notes
                .push("no predicted form: a 2-D program turns no C".to_string());
            None
        } else {
            match FormPredictor::new(tp, &FormSettings::default(), self.settings.map_size) {
                Ok(f) => Some(f),
                Err(PathError::Job(e)) => {
                    self.notes.push(format!("no predicted form: {e}"));
                    None
                }
                Err(e) => return Err(e.into()),
            }
        };
        self.accuracy = Some(Accuracy {
            linearization: LinearizationCheck::new(tp, self.settings.map_size),
            form,
        });
        if a.rho <= self.part_limit {
            let p = self.path_point(a, at)?.0;
            self.push_accuracy(&p)?;
        }
        Ok(())
    }

    fn push_accuracy(&mut self, p: &PathPoint) -> Result<(), VerifyError> {
        if let Some(acc) = self.accuracy.as_mut() {
            acc.linearization
                .add(self.tool_path, p)
                .map_err(|source| VerifyError::Surface { line: 0, source })?;
            if let Some(f) = acc.form.as_mut() {
                f.push(p)?;
            }
        }
        Ok(())
    }

    fn end_pass(&mut self) {
        let start = self.pass_start.take();
        if self.listed.len() < MAX_LISTED_PASSES
            && let Some(starts_at) = start
        {
            self.listed.push(PassSummary {
                points: self.pass.points(),
                stock_um: self.pass.mean(),
                deviation_um: self.pass.summary(),
                starts_at,
            });
        }
        if self.is_last_pass() {
            self.last = self.pass.clone();
            if let Some(acc) = self.accuracy.take() {
                let form = acc.form.map(FormPredictor::finish).transpose();
                match form {
                    Ok(form) => self.accuracy_done = Some((acc.linearization.finish(), form)),
                    Err(e) => self.notes.push(format!("no predicted form: {e}")),
                }
            }
        }
    }

    /// The compensated path point at `q`, and its ideal tip height.
    fn path_point(&self, q: PartPoint, at: &Location) -> Result<(PathPoint, f64), VerifyError> {
        let tp = self.tool_path;
        let (s, c) = q.theta.sin_cos();
        let contact = tp
            .nose()
            .compensate_from(tp.surface(), tp.concavity(), q.rho, c, s, None)
            .map_err(|source| VerifyError::Surface {
                line: at.line,
                source,
            })?;
        Ok((
            PathPoint {
                index: self.index,
                rho: q.rho,
                theta: q.theta,
                z: q.z,
                contact: [contact.rho * c, contact.rho * s, contact.z],
                contact_angle: contact.angle,
                at_arc_end: contact.at_arc_end,
            },
            contact.z_tip,
        ))
    }

    /// The cutting points of a cutting move from `a` to `b`.
    fn cut(&mut self, m: &Move, b: PartPoint) -> Result<(), VerifyError> {
        match m.kind {
            MoveKind::Arc {
                clockwise,
                centre_x,
                centre_z,
            } => {
                for q in arc_points(&self.from, m, (clockwise, centre_x, centre_z)) {
                    let p = self.frame.part_point(&q, self.frame.continuous_c());
                    self.cutting_point(p, &m.at)?;
                }
                Ok(())
            }
            _ => self.cutting_point(b, &m.at),
        }
    }

    fn cutting_point(&mut self, q: PartPoint, at: &Location) -> Result<(), VerifyError> {
        self.largest_radius = self.largest_radius.max(q.rho);
        if q.rho > self.part_limit {
            self.beyond += 1;
            return Ok(());
        }
        self.past_axis += u64::from(q.past_axis);
        let (p, ideal) = self.path_point(q, at)?;
        self.index += 1;
        let um = (q.z - ideal) * 1e3;
        self.pass.add(um, q.rho, q.theta, at);
        self.all.add(um, q.rho, q.theta, at);
        let (s, c) = q.theta.sin_cos();
        if self.is_last_pass() {
            self.map.keep_largest(q.rho * c, q.rho * s, um);
            self.push_accuracy(&p)?;
        }
        if self.is_last_pass()
            && self.pass.points().is_multiple_of(self.stride)
            && self.trace.len() < self.settings.trace_points
        {
            self.trace.push(TracePoint {
                x: q.rho * c,
                y: q.rho * s,
                z: q.z,
                deviation_um: um,
            });
        }
        Ok(())
    }

    /// Checks a move that does not cut against the design.
    fn check_collision(&mut self, m: &Move, a: PartPoint, b: PartPoint) -> Result<(), VerifyError> {
        let tp = self.tool_path;
        let limit = self
            .part_limit
            .min(tp.job().material_radius_mm() + tp.nose().nose_radius());
        let mut deepest: Option<Collision> = None;
        let from = self.from;
        let c0 = self.c_from;
        let dc = self.frame.continuous_c() - c0;
        for s in fractions(b.rho - a.rho, dc, self.step_mm) {
            let mut p = from;
            for (k, v) in p.0.iter_mut().enumerate() {
                *v += s * (m.target.0[k] - from.0[k]);
            }
            let q = self.frame.part_point(&p, c0 + s * dc);
            if q.rho > limit {
                continue;
            }
            let Ok(ideal) = tp.tip_height(q.rho, q.theta) else {
                self.warnings.note(
                    "a move that does not cut passes where the design is undefined: not checked \
                     there"
                        .to_string(),
                    &m.at,
                );
                continue;
            };
            let depth = (ideal - q.z) * 1e3;
            if depth > self.settings.collision_tolerance_um
                && deepest.as_ref().is_none_or(|d| depth > d.depth_um)
            {
                deepest = Some(Collision {
                    kind: if m.kind == MoveKind::Rapid {
                        "rapid"
                    } else {
                        "feed"
                    },
                    depth_um: depth,
                    at: At {
                        rho_mm: q.rho,
                        theta_deg: q.theta.to_degrees().rem_euclid(360.0),
                        file: m.at.file.to_string(),
                        line: m.at.line,
                    },
                });
            }
        }
        self.collisions.add(deepest);
        Ok(())
    }

    fn finish(mut self, summary: &Summary) -> Result<Verification, VerifyError> {
        if self.pass_start.is_some() {
            self.end_pass();
        }
        let points = self.all.points() + self.beyond;
        if self.beyond as f64 > MAX_BEYOND_FRACTION * points as f64 || self.all.points() == 0 {
            return Err(VerifyError::OtherPart {
                beyond: self.beyond,
                points,
                largest_radius_mm: self.largest_radius,
                part_radius_mm: self.part_limit,
            });
        }
        let job = self.tool_path.job();
        self.conventions_against(summary);
        if self.beyond > 0 {
            self.notes.push(format!(
                "{} cutting points beyond the part's radius ({:.6} mm) were not compared",
                self.beyond, self.part_limit
            ));
        }
        if self.largest_radius < 0.5 * job.part_radius_mm() {
            self.notes.push(format!(
                "the program cuts out to a radius of {:.6} mm only, of the part's {:.6} mm",
                self.largest_radius,
                job.part_radius_mm()
            ));
        }
        self.notes.push(
            "program coordinates are taken as the part's: work offsets zero, G52/G92 applied; \
             rapids are left out of the cycle time"
                .to_string(),
        );
        let conv = job.output.conventions();
        let (linearization, predicted_form) = match self.accuracy_done.take() {
            Some((l, f)) => (Some(l), f),
            None => (None, None),
        };
        Ok(Verification {
            job: job.name.clone(),
            program: ProgramFacts {
                units: match summary.units {
                    Some(Units::Millimetres) => "mm",
                    Some(Units::Inches) => "inch",
                    None => "mm (not stated)",
                },
                c: match summary.c {
                    CWrapping::NoC => "no C",
                    CWrapping::Wrapped => "wrapped",
                    CWrapping::Cumulative => "cumulative",
                    CWrapping::Undetermined => "undetermined",
                },
                c_range_deg: summary.c_range,
                x_negative_moves: summary.x_negative,
                x_positive_moves: summary.x_positive,
                past_axis_points: self.past_axis,
                axes: summary.axes.letters(),
                dialect: summary
                    .dialect
                    .dialect
                    .map(|d| format!("{d:?}").to_lowercase()),
                dialect_evidence: summary.dialect.evidence.clone(),
                x_sign: conv.x_sign,
                z_sign: conv.z_sign,
                c_sign: conv.c_sign,
                servo_word: (conv.fts_word as char).to_string(),
            },
            blocks: self.blocks,
            lines_read: summary.lines_read,
            cutting_rule: self.scan.rule.describe(),
            cutting_points: self.all.points(),
            beyond_part_points: self.beyond,
            largest_radius_mm: self.largest_radius,
            passes: self.listed,
            pass_count: self.passes.passes,
            deviation_um: self.last.summary(),
            all_passes_deviation_um: self.all.summary(),
            linearization,
            predicted_form,
            timing: self.timing.report(),
            axis_limits: self.timing.limits(),
            collisions: self.collisions,
            warnings: self.warnings.lines(),
            notes: self.notes,
            map: self.map,
            trace: self.trace,
        })
    }

    /// Warnings where what the program shows differs from the job's conventions.
    fn conventions_against(&mut self, summary: &Summary) {
        let job = self.tool_path.job();
        let start = Location {
            file: std::sync::Arc::from(""),
            line: 0,
        };
        let conv = job.output.conventions();
        let c = match summary.c {
            CWrapping::Wrapped if !conv.wrap_c => Some("wraps C to [0, 360)"),
            CWrapping::Cumulative if conv.wrap_c => Some("writes C cumulative"),
            _ => None,
        };
        if let Some(c) = c {
            self.warnings.note(
                format!(
                    "the program {c}, the job's output says otherwise: read either way \
                     (C is unwrapped)"
                ),
                &start,
            );
        }
        if summary.units.is_none() {
            self.warnings.note(
                "the program never states its units (G20/G21, G70/G71): millimetres assumed"
                    .to_string(),
                &start,
            );
        }
        if summary.mixed_units {
            self.warnings
                .note("the program uses both inch and mm".to_string(), &start);
        }
        let points = self.all.points().max(1);
        if self.past_axis * 2 > points {
            self.warnings.note(
                format!(
                    "{} of {} cutting points have the tool past the spindle axis: check \
                     output.x_sign (now {})",
                    self.past_axis, points, conv.x_sign
                ),
                &start,
            );
        }
        if let Some(d) = summary.dialect.dialect
            && d != job.output.dialect
        {
            self.warnings.note(
                format!(
                    "the program looks like {:?}, the job's output.dialect is {:?}: read \
                     with the job's signs",
                    d, job.output.dialect
                ),
                &start,
            );
        }
    }
}

/// Length of a move in the linear axes, mm.
fn linear_length(a: &Position, b: &Position) -> f64 {
    MachineAxis::ALL
        .iter()
        .filter(|x| !x.is_rotary())
        .map(|&x| (b.get(x) - a.get(x)).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Machine positions along an arc in the Z-X plane from `from` to `m.target`, every
/// [`ARC_STEP_DEG`] of its sweep at most, its end included.
fn arc_points(from: &Position, m: &Move, (clockwise, cx, cz): (bool, f64, f64)) -> Vec<Position> {
    // Angles in the (Z, X) plane, G18: Z is the abscissa, X the ordinate.
    let a0 = (from.x() - cx).atan2(from.z() - cz);
    let a1 = (m.target.x() - cx).atan2(m.target.z() - cz);
    let r0 = (from.x() - cx).hypot(from.z() - cz);
    let r1 = (m.target.x() - cx).hypot(m.target.z() - cz);
    // G2 is clockwise seen from +Y, looking down on the Z-X plane: the angle from Z to X
    // decreases (RS274/NGC, G18).
    let tau = std::f64::consts::TAU;
    let mut sweep = a1 - a0;
    if clockwise {
        if sweep >= 0.0 {
            sweep -= tau;
        }
    } else if sweep <= 0.0 {
        sweep += tau;
    }
    let n = ((sweep.abs().to_degrees() / ARC_STEP_DEG).ceil() as usize).clamp(1, 72);
    (1..=n)
        .map(|k| {
            let s = k as f64 / n as f64;
            if k == n {
                return m.target;
            }
            let ang = a0 + s * sweep;
            let r = r0 + s * (r1 - r0);
            let mut p = *from;
            for (i, v) in p.0.iter_mut().enumerate() {
                *v += s * (m.target.0[i] - from.0[i]);
            }
            p.0[0] = cx + r * ang.sin();
            p.0[2] = cz + r * ang.cos();
            p
        })
        .collect()
}
