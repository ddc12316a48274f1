//! The pipeline at the top of the layers: a job's [`ToolPath`] streamed through the writers
//! ([`crate::nc`]: NC program, CSV, the servo's table) and the report's running figures, after
//! the machine dynamics ([`crate::dynamics`]) where the job asks for them. Points are
//! compensated in batches of 16 384 on all cores (natively; one thread in the browser) and
//! handed in order to every sink, so memory stays flat whatever the point count and the output
//! does not depend on the number of threads; only the display copy
//! ([`crate::display::DisplayPath`]) keeps points, decimated to a fixed budget. A job without
//! passes or dynamics can also be planned in slices of its indices that join into the same
//! program, report and drawing ([`PlanSlice`], the page's workers).

pub mod admission;
pub mod analysis_admission;
mod program;
mod slice;

pub use admission::Limits;
pub use analysis_admission::AnalysisLimits;
pub use slice::PlanSlice;

use crate::display::DisplayPath;
use crate::dynamics::{Dynamics, DynamicsError};
use crate::field::FieldError;
use crate::job::{Compensation, Job, JobError, Sampling, SplitSpec};
use crate::nc::program::ChildFiles;
use crate::nc::{CsvWriter, FtsTableWriter, Header, NcError};
use crate::path::{PathError, PathPoint, hcaa};
use crate::progress::{Progress, ProgressFn};
use crate::report::{Report, Stats};
use crate::surface::UndefinedError;
use crate::tool::ToolPath;
use std::io::Write;
use std::ops::{ControlFlow, Deref};
use thiserror::Error;

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
    Split(#[from] crate::dynamics::split::SplitError),
    /// The slide heights given for a split path ended before the path (at this point).
    #[error("the split path has no slide height for point {0}: it was split from another plan")]
    SplitLength(u64),
}

impl From<FieldError> for PlanError {
    fn from(e: FieldError) -> Self {
        PlanError::Job(JobError::Field(e))
    }
}

impl From<PathError> for PlanError {
    fn from(e: PathError) -> Self {
        match e {
            PathError::Job(e) => PlanError::Job(e),
            PathError::Surface(e) => PlanError::Surface(e),
            PathError::Cancelled => PlanError::Cancelled,
        }
    }
}

impl From<DynamicsError> for PlanError {
    fn from(e: DynamicsError) -> Self {
        match e {
            DynamicsError::Path(e) => e.into(),
            DynamicsError::Split(e) => PlanError::Split(e),
        }
    }
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
    /// Where child programs go, for a job whose `program.max_program_bytes` the program
    /// exceeds; without it they are only counted.
    pub children: Option<&'a mut dyn ChildFiles>,
    /// The stem of the child programs' names (`STEM-1.nc`); default the job's name.
    pub child_stem: Option<String>,
    /// The servo's gridded table as PMAC text ([`crate::nc::fts_grid::write_pmac`]), written by
    /// [`Planner::run_with_dynamics`] for a split path.
    pub fts_grid: Option<&'a mut dyn Write>,
    /// The same grid as CSV ([`crate::nc::fts_grid::write_csv`]).
    pub fts_grid_csv: Option<&'a mut dyn Write>,
}

/// A checked job, ready to plan: its [`ToolPath`] (which it dereferences to) and the
/// pipeline that writes it.
#[derive(Debug)]
pub struct Planner {
    path: ToolPath,
}

impl Deref for Planner {
    type Target = ToolPath;

    fn deref(&self) -> &ToolPath {
        &self.path
    }
}

impl Planner {
    /// Validates the job and builds its stages.
    pub fn new(job: &Job) -> Result<Self, PlanError> {
        Ok(Self {
            path: ToolPath::new(job)?,
        })
    }

    /// [`Planner::new`] with the progress of the sampling's estimate (see
    /// [`ToolPath::with_progress`]), which may cancel.
    pub fn with_progress(job: &Job, progress: &mut ProgressFn) -> Result<Self, PlanError> {
        Ok(Self {
            path: ToolPath::with_progress(job, progress)?,
        })
    }

    /// The tool path.
    pub fn path(&self) -> &ToolPath {
        &self.path
    }

    /// The header comments of the NC program.
    pub fn header(&self) -> Header {
        let j = self.job();
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
                hcaa::describe(&j.strategy.sampling, pv_tolerance_um, self.spiral().zones())
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
                format!("surface: {}", self.surface().describe()),
                format!(
                    "part diameter {} mm; spiral from radius {:.6} mm to the centre",
                    j.part.diameter_mm,
                    self.spiral().start_radius_mm()
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
                    self.spiral().revolutions()
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
        if let Some(cut) = j.part.cut {
            header.lines.insert(3, format!("cut: {}", cut.describe()));
        }
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
        // A job with a program states these with its passes (plan/program.rs); a one-spiral
        // program states them where they are not today's defaults.
        if j.program.is_none() {
            if matches!(
                j.output.feed_mode,
                crate::job::FeedMode::BlockTimeS | crate::job::FeedMode::BlockTimeMin
            ) {
                header.lines.push(format!(
                    "{}: the spindle turns at {} rpm; cutting time {} s",
                    j.output.feed_mode.meaning(),
                    j.machine.spindle_rpm,
                    crate::field::short(
                        (self.spiral().revolutions() * 600.0 / j.machine.spindle_rpm).round()
                            / 10.0
                    )
                ));
            }
            if !j.part.beyond_edge.is_none() || j.strategy.overtravel_mm > 0.0 {
                header.lines.push(j.edge_description());
            }
        }
        header
    }

    /// Plans the whole path as [`Self::run`] does, after the machine dynamics when the job asks
    /// for them ([`crate::dynamics::wanted`]): a first pass plans the path into memory,
    /// analyses and splits it, the second writes it with the slide's share and the servo's
    /// word (and the servo's table). The report carries the dynamics; the progress runs twice.
    /// With a split path and a sink for the gridded table (or `output.fts_grid` in the job),
    /// the grid is sized after the dynamics ([`crate::dynamics::fts_grid`]), written, and its
    /// figures reported (`dynamics.fts_grid`).
    pub fn run_with_dynamics(
        &self,
        sinks: Sinks,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<Report, PlanError> {
        if !crate::dynamics::wanted(self.job()) {
            return self.run(sinks, progress);
        }
        let Sinks {
            nc,
            csv,
            display,
            fts_table,
            children,
            child_stem,
            fts_grid,
            fts_grid_csv,
            ..
        } = sinks;
        let grid =
            fts_grid.is_some() || fts_grid_csv.is_some() || self.job().output.fts_grid.is_some();
        let dynamics = Dynamics::run_with_grid(&self.path, grid, progress)?;
        if let Some(g) = &dynamics.fts_grid {
            if let Some(out) = fts_grid {
                crate::nc::fts_grid::write_pmac(out, &g.table, &g.comments)?;
            }
            if let Some(out) = fts_grid_csv {
                crate::nc::fts_grid::write_csv(out, &g.table)?;
            }
        }
        let sinks = Sinks {
            nc: nc.map(|w| w as &mut dyn Write),
            csv: csv.map(|w| w as &mut dyn Write),
            display,
            z_slide: dynamics.z_slide_mm.as_deref(),
            fts_table: fts_table.map(|w| w as &mut dyn Write),
            children: children.map(|c| c as &mut dyn ChildFiles),
            child_stem,
            ..Default::default()
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
    /// `progress` is called every [`crate::progress::PROGRESS_EVERY`] points and at the end;
    /// returning `ControlFlow::Break` cancels.
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
        if self.job().program.is_some() {
            return self.run_program(sinks, progress, header);
        }
        let slice = self.walk(0..u64::MAX, Some(&header), sinks, progress)?;
        self.report_of(&slice.stats, slice.nc_bytes, progress)
    }

    /// The report of a path whose figures are `stats` and whose program has `nc_bytes`: the
    /// concave zones are searched here.
    pub fn report_of(
        &self,
        stats: &Stats,
        nc_bytes: u64,
        progress: &mut ProgressFn,
    ) -> Result<Report, PlanError> {
        let zones = self.path.concave_zones(progress)?;
        Ok(Report::new(&self.path, stats, nc_bytes, zones))
    }
}

/// What the finishing path streams into besides the program: the CSV, the servo's table, the
/// display's copy and the report's figures.
struct Extras<'a> {
    csv: Option<CsvWriter<&'a mut dyn Write>>,
    fts_table: Option<FtsTableWriter<&'a mut dyn Write>>,
    display: Option<&'a mut DisplayPath>,
    z_slide: Option<&'a [f64]>,
    stats: Stats,
}

impl<'a> Extras<'a> {
    fn new(
        job: &Job,
        csv: Option<&'a mut dyn Write>,
        fts_table: Option<&'a mut dyn Write>,
        display: Option<&'a mut DisplayPath>,
        z_slide: Option<&'a [f64]>,
    ) -> Result<Self, PlanError> {
        let conv = job.output.conventions();
        Ok(Self {
            csv: csv.map(|w| CsvWriter::new(w, conv)).transpose()?,
            fts_table: match z_slide {
                Some(_) => fts_table
                    .map(|w| FtsTableWriter::new(w, conv))
                    .transpose()?,
                None => None,
            },
            display,
            z_slide,
            stats: Stats::default(),
        })
    }

    /// The slide's share of `p`'s height when the path is split.
    fn slide(&self, p: &PathPoint) -> Result<Option<f64>, PlanError> {
        slide_of(self.z_slide, p)
    }

    fn point(&mut self, p: &PathPoint, folds: bool) -> Result<(), PlanError> {
        self.stats.add(p);
        if folds {
            self.stats.add_loop_point(p);
        }
        self.copies(p)
    }

    /// Takes the figures of the points after those seen so far (a batch's, gathered apart).
    fn merge(&mut self, later: Stats) {
        self.stats = std::mem::take(&mut self.stats).merge(later);
    }

    /// Whether any of the CSV, the servo's table and the display's copy is wanted.
    fn copies_wanted(&self) -> bool {
        self.csv.is_some() || self.fts_table.is_some() || self.display.is_some()
    }

    /// Writes `p` into the CSV, the servo's table and the display's copy.
    fn copies(&mut self, p: &PathPoint) -> Result<(), PlanError> {
        if let Some(z) = self.slide(p)?
            && let Some(t) = self.fts_table.as_mut()
        {
            t.point(p, z)?;
        }
        if let Some(csv) = self.csv.as_mut() {
            csv.point(p)?;
        }
        if let Some(d) = self.display.as_deref_mut() {
            d.push(p);
        }
        Ok(())
    }

    fn finish(self) -> Result<Stats, PlanError> {
        if let Some(csv) = self.csv {
            csv.finish()?;
        }
        if let Some(t) = self.fts_table {
            t.finish()?;
        }
        Ok(self.stats)
    }
}

/// The slide's share of `p`'s height in `z_slide` (the split path's), if the path is split.
fn slide_of(z_slide: Option<&[f64]>, p: &PathPoint) -> Result<Option<f64>, PlanError> {
    match z_slide.map(|z| z.get(p.index as usize)) {
        None => Ok(None),
        Some(Some(&z)) => Ok(Some(z)),
        Some(None) => Err(PlanError::SplitLength(p.index)),
    }
}
