//! The planner: job → surface → spiral ([`spiral`]) → one-way compensation → NC, CSV and
//! report, as one stream. [`Planner::points`] yields the path one point at a time;
//! [`Planner::run`] compensates batches of 16 384 points on all cores (natively; one thread in
//! the browser) and hands them in order to every sink, so memory stays flat whatever the point
//! count and the output does not depend on the number of threads; only the display copy
//! ([`crate::display::DisplayPath`]) keeps points, decimated to a fixed budget.

use crate::compensate::{Compensation, NoseCompensator};
use crate::display::DisplayPath;
use crate::field::FieldError;
use crate::job::{Job, JobError, StrategySpec};
use crate::nc::{CsvWriter, FtsTableWriter, Header, NcError, NcWriter};
use crate::reach::{self, Reach};
use crate::report::{Report, Stats};
use crate::spiral::{Sampling, Spiral, SpiralPoint};
use crate::split::SplitSpec;
use crate::surface::{Surface, UndefinedError};
use std::io::Write;
use std::ops::ControlFlow;
use thiserror::Error;

/// One point of the tool path.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PathPoint {
    /// Position along the path, from 0.
    pub index: u64,
    /// Radius of the tool (X on the spiral), mm.
    pub rho: f64,
    /// Polar angle on the part, radians, cumulative.
    pub theta: f64,
    /// Commanded Z: the tool tip (nose centre − r), mm.
    pub z: f64,
    /// Where the nose touches the surface (x, y, z), mm.
    pub contact: [f64; 3],
    /// Nose angle of the contact, radians.
    pub contact_angle: f64,
    /// The contact is at an end of the nose arc (see [`crate::compensate::Contact`]).
    pub at_arc_end: bool,
}

/// Why a plan failed.
#[derive(Debug, Error)]
pub enum PlanError {
    /// The job is malformed or has a value out of range.
    ///
    /// ```
    /// let mut job = spiralcam::job::Job::default_job();
    /// job.tool.nose_radius_mm = -1.0;
    /// let e = spiralcam::plan::Planner::new(&job).unwrap_err();
    /// assert!(e.to_string().starts_with("tool.nose_radius_mm = -1"));
    /// ```
    #[error(transparent)]
    Job(#[from] JobError),
    /// The surface has no value where the path needs one.
    ///
    /// ```
    /// let mut job = spiralcam::job::Job::default_job();
    /// job.surface = serde_json::from_str(r#"{"type":"asphere","radius_mm":4}"#).unwrap();
    /// let e = spiralcam::plan::Planner::new(&job).unwrap().run(
    ///     spiralcam::plan::Sinks::default(), &mut |_| std::ops::ControlFlow::Continue(())).unwrap_err();
    /// assert!(e.to_string().contains("even asphere is undefined at radius"));
    /// ```
    #[error(transparent)]
    Surface(#[from] UndefinedError),
    /// An output could not be written.
    ///
    /// ```
    /// let e = spiralcam::plan::PlanError::from(spiralcam::nc::NcError::from(std::io::Error::other("full")));
    /// assert_eq!(e.to_string(), "writing: full");
    /// ```
    #[error(transparent)]
    Output(#[from] NcError),
    /// The progress callback asked to stop.
    ///
    /// ```
    /// assert_eq!(spiralcam::plan::PlanError::Cancelled.to_string(), "cancelled");
    /// ```
    #[error("cancelled")]
    Cancelled,
    /// The path cannot be split between the slide and the servo.
    #[error(transparent)]
    Split(#[from] crate::split::SplitError),
    /// The slide heights given for a split path ended before the path (at this point).
    #[error("the split path has no slide height for point {0}: it was split from another plan")]
    SplitLength(u64),
}

impl From<FieldError> for PlanError {
    fn from(e: FieldError) -> Self {
        PlanError::Job(JobError::Field(e))
    }
}

/// Progress of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Points done.
    pub done: u64,
    /// Points expected (exact for constant angle sampling).
    pub total: u64,
}

/// Where a run's output goes; each is optional.
#[derive(Default)]
pub struct Sinks<'a> {
    /// The NC program.
    pub nc: Option<&'a mut dyn Write>,
    /// The CSV table.
    pub csv: Option<&'a mut dyn Write>,
    /// The decimated copy for display.
    pub display: Option<&'a mut DisplayPath>,
    /// The slide's share Z of every point's height, mm, for a path split with a fast tool
    /// servo ([`crate::dynamics::Dynamics`]): the program then carries the servo's word too.
    pub z_slide: Option<&'a [f64]>,
    /// The servo's table (`c_deg,x_mm,w_mm`), written when `z_slide` is given.
    pub fts_table: Option<&'a mut dyn Write>,
}

/// How often the progress callback is called, in points.
pub const PROGRESS_EVERY: u64 = 65_536;

/// Points compensated per batch before they are written: bounds the memory of a run.
const BATCH: usize = 16_384;

/// Threads for parallel work (a batch to compensate, the circles of [`crate::hcaa::bands`]):
/// every core natively, one in the browser.
pub(crate) fn workers() -> usize {
    if cfg!(target_arch = "wasm32") {
        1
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    }
}

/// The spiral of a strategy on `surface`, by the builder of its sampling: [`Spiral::new`] for
/// constant angle and constant arc, [`crate::hcaa::spiral`] for `hcaa` and `adaptive`,
/// [`crate::space_spiral::spiral`] for `space_spiral`. Field errors are named from `strategy`.
pub fn spiral(
    outer_radius_mm: f64,
    strategy: &StrategySpec,
    surface: &dyn Surface,
    nose: &NoseCompensator,
) -> Result<Spiral, PlanError> {
    let st = strategy;
    let within = |e: FieldError| PlanError::from(e.within("strategy"));
    match st.sampling {
        Sampling::ConstantAngle { .. } | Sampling::ConstantArc { .. } => Spiral::new(
            outer_radius_mm,
            st.feed_mm_per_rev,
            &st.sampling,
            st.direction,
            st.start_angle_deg,
        )
        .map_err(within),
        Sampling::Hcaa { .. } | Sampling::Adaptive { .. } => {
            crate::hcaa::spiral(outer_radius_mm, st, surface, nose)
        }
        Sampling::SpaceSpiral {
            points_per_rev,
            base_spans,
        } => crate::space_spiral::spiral(outer_radius_mm, st, surface, points_per_rev, base_spans)
            .map_err(within),
    }
}

/// A checked job, ready to plan.
#[derive(Debug)]
pub struct Planner {
    job: Job,
    surface: Box<dyn Surface>,
    spiral: Spiral,
    nose: NoseCompensator,
}

impl Planner {
    /// Validates the job and builds its stages.
    pub fn new(job: &Job) -> Result<Self, PlanError> {
        job.validate()?;
        let surface = job.build_surface()?;
        // The material ends at the part edge, wherever the spiral starts.
        let nose =
            NoseCompensator::new(&job.tool, surface.feature_length_mm(), job.part_radius_mm())
                .map_err(|e| e.within("tool"))?;
        let spiral = spiral(
            job.outer_radius_mm(),
            &job.strategy,
            surface.as_ref(),
            &nose,
        )?;
        Ok(Self {
            job: job.clone(),
            surface,
            spiral,
            nose,
        })
    }

    /// The job.
    pub fn job(&self) -> &Job {
        &self.job
    }

    /// The surface.
    pub fn surface(&self) -> &dyn Surface {
        self.surface.as_ref()
    }

    /// The spiral.
    pub fn spiral(&self) -> &Spiral {
        &self.spiral
    }

    /// The compensator.
    pub fn nose(&self) -> &NoseCompensator {
        &self.nose
    }

    /// The compensated path, streamed.
    pub fn points(&self) -> impl Iterator<Item = Result<PathPoint, UndefinedError>> + '_ {
        self.spiral
            .points()
            .enumerate()
            .map(move |(i, sp)| Ok(self.path_point(i as u64, sp)?.0))
    }

    /// The compensated path point of the `index`-th spiral point, and whether the two-way
    /// offset folds there (a loop; always false one-way). Two-way, `rho` and `theta` are the
    /// nose centre's X and C ([`NoseCompensator::compensate_two_way`]).
    fn path_point(&self, index: u64, sp: SpiralPoint) -> Result<(PathPoint, bool), UndefinedError> {
        let (s, c) = sp.theta.sin_cos();
        if self.job.strategy.compensation == Compensation::TwoWay {
            let t = self
                .nose
                .compensate_two_way(self.surface.as_ref(), sp.rho, c, s)?;
            return Ok((
                PathPoint {
                    index,
                    rho: t.x,
                    theta: sp.theta + t.c_offset,
                    z: t.z_tip,
                    contact: t.contact,
                    contact_angle: t.angle,
                    at_arc_end: t.at_arc_end,
                },
                t.folds,
            ));
        }
        let contact = self.nose.compensate(self.surface.as_ref(), sp.rho, c, s)?;
        Ok((
            PathPoint {
                index,
                rho: sp.rho,
                theta: sp.theta,
                z: contact.z_tip,
                contact: [contact.rho * c, contact.rho * s, contact.z],
                contact_angle: contact.angle,
                at_arc_end: contact.at_arc_end,
            },
            false,
        ))
    }

    /// Compensates a batch of spiral points starting at path index `first` into `out`, in
    /// order, split over the machine's cores (one thread on wasm32). Each point is computed
    /// alone, so the result is the same whatever the split; the first error in path order wins.
    fn compensate_batch(
        &self,
        first: u64,
        input: &[SpiralPoint],
        out: &mut Vec<(PathPoint, bool)>,
    ) -> Result<(), UndefinedError> {
        out.clear();
        out.resize(input.len(), (PathPoint::default(), false));
        let chunk = input.len().div_ceil(workers()).max(1);
        let fill = |k: usize,
                    points: &[SpiralPoint],
                    slots: &mut [(PathPoint, bool)]|
         -> Result<(), UndefinedError> {
            for (j, (sp, slot)) in points.iter().zip(slots).enumerate() {
                *slot = self.path_point(first + (k * chunk + j) as u64, *sp)?;
            }
            Ok(())
        };
        let mut parts = input.chunks(chunk).zip(out.chunks_mut(chunk)).enumerate();
        if chunk == input.len() {
            return parts.try_for_each(|(k, (p, o))| fill(k, p, o));
        }
        std::thread::scope(|scope| {
            let fill = &fill;
            let handles: Vec<_> = parts
                .map(|(k, (p, o))| scope.spawn(move || fill(k, p, o)))
                .collect();
            handles
                .into_iter()
                .try_for_each(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
        })
    }

    /// The header comments of the NC program.
    pub fn header(&self) -> Header {
        let j = &self.job;
        let conv = j.output.conventions();
        let sampling = match j.strategy.sampling {
            Sampling::ConstantAngle { points_per_rev } => {
                format!("constant angle, {points_per_rev} points/rev")
            }
            Sampling::ConstantArc {
                arc_length_mm,
                max_angle_step_deg,
            } => {
                format!(
                    "constant arc {arc_length_mm} mm, angle step at most {max_angle_step_deg} deg"
                )
            }
            Sampling::Hcaa { pv_tolerance_um } | Sampling::Adaptive { pv_tolerance_um } => {
                crate::hcaa::describe(&j.strategy.sampling, pv_tolerance_um, self.spiral.zones())
            }
            Sampling::SpaceSpiral {
                points_per_rev,
                base_spans,
            } => format!(
                "space spiral (paper 001), {points_per_rev} points/rev, passes f apart along the meridian of a base surface of revolution ({base_spans} spans), projected along its normal"
            ),
        };
        let sign = |s: f64| if s > 0.0 { "+" } else { "-" };
        let compensation = match j.strategy.compensation {
            Compensation::OneWay => "one-way compensation",
            Compensation::TwoWay => {
                "two-way compensation (contact on the spiral, nose centre on the surface normal, X and C of the centre)"
            }
        };
        let mut header = Header {
            lines: vec![
                format!(
                    "spiralcam {} - {}",
                    env!("CARGO_PKG_VERSION"),
                    j.output.style().name
                ),
                format!("job {}", j.name),
                format!("surface: {}", self.surface.describe()),
                format!(
                    "part diameter {} mm; spiral from radius {:.6} mm to the centre",
                    j.part.diameter_mm,
                    self.spiral.start_radius_mm()
                ),
                format!(
                    "tool nose radius {} mm, included angle {} deg; {compensation}; Z is the tool tip = nose centre - r",
                    j.tool.nose_radius_mm, j.tool.included_angle_deg
                ),
                format!(
                    "feed {} mm/rev, {}, {:?}, start angle {} deg, {:.3} revolutions",
                    j.strategy.feed_mm_per_rev,
                    sampling,
                    j.strategy.direction,
                    j.strategy.start_angle_deg,
                    self.spiral.revolutions()
                )
                .to_lowercase(),
                format!("spindle {} rpm", j.machine.spindle_rpm),
                format!(
                    "X = {}rho mm, Z = {}z mm, C = {}theta deg{}",
                    sign(conv.x_sign),
                    sign(conv.z_sign),
                    sign(conv.c_sign),
                    if conv.wrap_c {
                        " wrapped to 0 <= C < 360"
                    } else {
                        " cumulative"
                    }
                ),
            ],
            spindle_rpm: j.machine.spindle_rpm,
        };
        if let Some(split) = &j.strategy.split {
            let how = match split {
                SplitSpec::Symmetric => "the rotationally symmetric part on Z".to_string(),
                SplitSpec::LowPass { cutoff_hz } => {
                    format!("zero-phase low-pass at {cutoff_hz} Hz on Z")
                }
                SplitSpec::Auto => "automatic cutoff (see the report)".to_string(),
            };
            header.lines.push(format!(
                "split between the Z slide and the fast tool servo {}: {how}, the rest on {}; Z + {} = the tool tip",
                conv.fts_word as char, conv.fts_word as char, conv.fts_word as char
            ));
        }
        header
    }

    /// Zones where the nose cannot reach the surface (see [`crate::reach`]).
    pub fn concave_zones(&self) -> Result<Reach, UndefinedError> {
        reach::concave_zones(
            self.surface.as_ref(),
            &self.nose,
            self.spiral.start_radius_mm(),
        )
    }

    /// Plans every point in order, compensating batches of 16 384 points on every core, and
    /// hands each to `visit` with whether the two-way offset folds there; `progress` is called
    /// every [`PROGRESS_EVERY`] points and at the end (`Break` cancels). Returns the count.
    pub fn for_each_point(
        &self,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
        visit: &mut dyn FnMut(&PathPoint, bool) -> Result<(), PlanError>,
    ) -> Result<u64, PlanError> {
        let total = self.spiral.point_count_hint();
        let mut done = 0u64;
        let mut spiral = self.spiral.points();
        let (mut input, mut output) = (Vec::with_capacity(BATCH), Vec::with_capacity(BATCH));
        loop {
            input.clear();
            input.extend(spiral.by_ref().take(BATCH));
            if input.is_empty() {
                break;
            }
            self.compensate_batch(done, &input, &mut output)?;
            for (p, folds) in &output {
                visit(p, *folds)?;
                done += 1;
                if done.is_multiple_of(PROGRESS_EVERY)
                    && progress(Progress { done, total }).is_break()
                {
                    return Err(PlanError::Cancelled);
                }
            }
        }
        let _ = progress(Progress { done, total: done });
        Ok(done)
    }

    /// Plans the whole path as [`Self::run`] does, after the machine dynamics when the job asks
    /// for them ([`crate::dynamics::wanted`]): a first pass plans the path into memory,
    /// analyses and splits it, the second writes it with the slide's share and the servo's
    /// word (and the servo's table). The report carries the dynamics; the progress runs twice.
    pub fn run_with_dynamics(
        &self,
        sinks: Sinks,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<Report, PlanError> {
        if !crate::dynamics::wanted(&self.job) {
            return self.run(sinks, progress);
        }
        let dynamics = crate::dynamics::Dynamics::run(self, progress)?;
        let Sinks {
            nc,
            csv,
            display,
            fts_table,
            ..
        } = sinks;
        let sinks = Sinks {
            nc: nc.map(|w| w as &mut dyn Write),
            csv: csv.map(|w| w as &mut dyn Write),
            display,
            z_slide: dynamics.z_slide_mm.as_deref(),
            fts_table: fts_table.map(|w| w as &mut dyn Write),
        };
        let mut header = self.header();
        header.lines.extend(dynamics.report.header_lines());
        let mut report = self.run_with_header(sinks, progress, header)?;
        report.warnings.extend(dynamics.report.warnings());
        report.dynamics = Some(dynamics.report);
        Ok(report)
    }

    /// Plans the whole path into the sinks and returns the report. The NC program is always
    /// generated (into a byte counter when no sink is given) so the report can state its size.
    /// `progress` is called every [`PROGRESS_EVERY`] points and at the end; returning
    /// `ControlFlow::Break` cancels.
    pub fn run(
        &self,
        sinks: Sinks,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<Report, PlanError> {
        self.run_with_header(sinks, progress, self.header())
    }

    /// [`Self::run`] with the program's header given.
    fn run_with_header(
        &self,
        sinks: Sinks,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
        header: Header,
    ) -> Result<Report, PlanError> {
        let mut counter = std::io::sink();
        let nc_out: &mut dyn Write = match sinks.nc {
            Some(w) => w,
            None => &mut counter,
        };
        let mut nc = NcWriter::new(nc_out, &self.job.output, &header)?;
        let conv = self.job.output.conventions();
        let mut csv = sinks.csv.map(|w| CsvWriter::new(w, conv)).transpose()?;
        let z_slide = sinks.z_slide;
        let mut fts_table = match z_slide {
            Some(_) => sinks
                .fts_table
                .map(|w| FtsTableWriter::new(w, conv))
                .transpose()?,
            None => None,
        };
        let mut display = sinks.display;
        let mut stats = Stats::default();
        self.for_each_point(progress, &mut |p, folds| {
            match z_slide.map(|z| z.get(p.index as usize)) {
                None => nc.point(p)?,
                Some(Some(&z)) => {
                    nc.point_split(p, z)?;
                    if let Some(t) = fts_table.as_mut() {
                        t.point(p, z)?;
                    }
                }
                Some(None) => return Err(PlanError::SplitLength(p.index)),
            }
            if let Some(csv) = csv.as_mut() {
                csv.point(p)?;
            }
            if let Some(d) = display.as_deref_mut() {
                d.push(p);
            }
            stats.add(p);
            if folds {
                stats.add_loop_point(p);
            }
            Ok(())
        })?;
        let nc_bytes = nc.finish()?;
        if let Some(csv) = csv {
            csv.finish()?;
        }
        if let Some(t) = fts_table {
            t.finish()?;
        }
        let zones = self.concave_zones()?;
        Ok(Report::new(self, &stats, nc_bytes, zones))
    }
}
