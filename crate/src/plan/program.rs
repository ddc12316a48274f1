//! The pipeline of a job with a `program` section ([`crate::job::program`]): the groups'
//! paths (a group with its own feed or speed is its own spiral), each streamed through the
//! program writer ([`crate::nc::program`]) once per body (once a group in a controller loop,
//! once a pass written out), the CSV, display, report and servo table from the finishing pass.
//!
//! Heights come first: each group's path is computed once to find its highest commanded Z,
//! which sets the default safe and retract heights and checks the ones the job gives (a retract
//! or approach below the part is refused, naming the field). Child programs are used when the
//! job's size limit is set and the estimate of the program ([`Planner::cost`]) exceeds 90 % of
//! it; the main program must then fit the limit too.

use super::{Extras, PlanError, Planner, Sinks};
use crate::field::{FieldError, short};
use crate::job::program::Pass;
use crate::job::{Job, LoopKind, ProgramSpec};
use crate::nc::Header;
use crate::nc::program::{GroupFrame, PassFrame, ProgramWriter};
use crate::path::PathError;
use crate::progress::{Progress, ProgressFn, Stage};
use crate::report::{PassReport, ProgramReport, Report};
use crate::tool::ToolPath;
use std::ops::ControlFlow;

/// A group's path and what the frame needs of it.
struct GroupPath<'a> {
    path: PathRef<'a>,
    rpm: f64,
    /// Highest commanded Z of the path (design frame), mm.
    z_max: f64,
    /// Z of its first point, mm.
    z_first: f64,
    points: u64,
}

/// The strategy's path, or a group's own.
enum PathRef<'a> {
    Strategy(&'a ToolPath),
    Own(Box<ToolPath>),
}

impl std::ops::Deref for PathRef<'_> {
    type Target = ToolPath;

    fn deref(&self) -> &ToolPath {
        match self {
            PathRef::Strategy(p) => p,
            PathRef::Own(p) => p,
        }
    }
}

impl Planner {
    /// [`Planner::run`] for a job with a `program` section (see the module docs).
    pub(super) fn run_program(
        &self,
        sinks: Sinks,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
        mut header: Header,
    ) -> Result<Report, PlanError> {
        let job = self.job();
        let Some(spec) = job.program.clone() else {
            unreachable!("run_program is called for jobs with a program section");
        };
        let passes = spec.pass_list();
        let groups = self.group_paths(&spec, progress)?;
        let stock = spec.stock_mm();
        let clearance = job.output.clearance_mm;
        let retract = |g: &GroupPath| spec.retract_height_mm.unwrap_or(g.z_max + clearance);
        let safe_z = spec.safe_z_mm.unwrap_or_else(|| {
            groups.iter().map(|g| g.z_max).fold(f64::MIN, f64::max) + stock + clearance
        });
        check_heights(&spec, &groups, (safe_z, stock, clearance))?;
        let child_limit = self.child_limit(&spec)?;
        header
            .lines
            .extend(program_lines(job, &spec, &groups, &passes));
        let stem = sinks.child_stem.clone().unwrap_or_else(|| job.name.clone());
        let mut counter = std::io::sink();
        let main: &mut dyn std::io::Write = match sinks.nc {
            Some(w) => w,
            None => &mut counter,
        };
        let mut writer = ProgramWriter::new(
            main,
            sinks
                .children
                .map(|c| c as &mut dyn crate::nc::program::ChildFiles),
            &job.output,
            &spec,
            (&header.lines, groups[0].rpm),
            &stem,
            safe_z,
            child_limit,
        )?;
        let mut extras = Extras::new(
            job,
            sinks.csv,
            sinks.fts_table,
            sinks.display,
            sinks.z_slide,
        )?;
        let last = passes.len() - 1;
        let mut pass_reports = Vec::new();
        for (g, group) in groups.iter().enumerate() {
            let in_group: Vec<(usize, &Pass)> = passes
                .iter()
                .enumerate()
                .filter(|(_, p)| p.group == g)
                .collect();
            let frame = GroupFrame {
                group: g,
                count: in_group.len() as u32,
                depth_mm: spec.passes.get(g).map_or(0.0, |p| p.depth_of_cut_um * 1e-3),
                stock_before_mm: in_group[0].1.stock_mm
                    + spec.passes.get(g).map_or(0.0, |p| p.depth_of_cut_um * 1e-3),
            };
            writer.set_rpm(&job.output, group.rpm);
            writer.begin_group(frame)?;
            let bodies: Vec<(usize, &Pass)> = match spec.loop_kind {
                LoopKind::Controller => vec![*in_group.last().unwrap_or(&in_group[0])],
                LoopKind::Unrolled => in_group.clone(),
            };
            for (k, pass) in bodies {
                let lift = match spec.loop_kind {
                    LoopKind::Controller => 0.0,
                    LoopKind::Unrolled => pass.stock_mm,
                };
                let finishing =
                    k == last || (spec.loop_kind == LoopKind::Controller && g + 1 == groups.len());
                self.write_body(
                    &mut writer,
                    &mut extras,
                    group,
                    (pass, lift, retract(group), finishing),
                    progress,
                )?;
            }
            writer.end_group(frame)?;
            for (_, p) in &in_group {
                pass_reports.push(PassReport {
                    group: g,
                    stock_left_mm: p.stock_mm,
                    feed_mm_per_rev: group.path.spiral().feed_mm(),
                    spindle_rpm: group.rpm,
                    points: group.points,
                    cutting_time_s: group.path.spiral().revolutions() * 60.0 / group.rpm,
                });
            }
        }
        let (main_bytes, children) = writer.finish()?;
        if let Some(limit) = spec.max_program_bytes
            && main_bytes > limit
        {
            return Err(FieldError::new(
                "program.max_program_bytes",
                limit,
                format!(
                    "the main program takes {main_bytes} bytes ({}): give a larger limit",
                    if children.is_empty() {
                        "the estimate kept it whole"
                    } else {
                        "its frame and calls"
                    }
                ),
            )
            .into());
        }
        let stats = extras.finish()?;
        let zones = self.path.concave_zones(progress)?;
        let final_path: &ToolPath = &groups[groups.len() - 1].path;
        let mut report = Report::new(final_path, &stats, main_bytes, zones);
        report.cycle_time_s = pass_reports.iter().map(|p| p.cutting_time_s).sum();
        report.program = Some(ProgramReport {
            stock_mm: stock,
            loop_kind: spec.loop_kind,
            safe_z_mm: safe_z,
            passes: pass_reports,
            children,
        });
        Ok(report)
    }

    /// Each group's path: the strategy's, or its own for a group with its own feed or speed;
    /// with its highest Z from a first pass over it.
    fn group_paths(
        &self,
        spec: &ProgramSpec,
        progress: &mut ProgressFn,
    ) -> Result<Vec<GroupPath<'_>>, PlanError> {
        let job = self.job();
        let groups = spec.passes.len().max(1);
        let mut out = Vec::with_capacity(groups);
        for g in 0..groups {
            let own = spec
                .passes
                .get(g)
                .filter(|p| p.feed_mm_per_rev.is_some() || p.spindle_rpm.is_some());
            let path = match own {
                None => PathRef::Strategy(&self.path),
                Some(p) => {
                    let mut j: Job = job.clone();
                    if let Some(f) = p.feed_mm_per_rev {
                        j.strategy.feed_mm_per_rev = f;
                    }
                    if let Some(n) = p.spindle_rpm {
                        j.machine.spindle_rpm = n;
                    }
                    let path = ToolPath::with_progress(&j, progress).map_err(|e| match e {
                        PathError::Job(crate::job::JobError::Field(f)) => {
                            PathError::from(FieldError::new(
                                format!("program.passes[{g}]"),
                                format!(
                                    "feed {}, speed {}",
                                    short(j.strategy.feed_mm_per_rev),
                                    short(j.machine.spindle_rpm)
                                ),
                                format!("the group's spiral cannot be laid: {f}"),
                            ))
                        }
                        other => other,
                    })?;
                    PathRef::Own(Box::new(path))
                }
            };
            let (mut z_max, mut z_first) = (f64::MIN, None);
            let points = path.for_each_point(Stage::Path, progress, &mut |p, _| {
                z_max = z_max.max(p.z);
                z_first.get_or_insert(p.z);
                Ok::<(), PathError>(())
            })?;
            let rpm = path.job().machine.spindle_rpm;
            out.push(GroupPath {
                path,
                rpm,
                z_max,
                z_first: z_first.unwrap_or(0.0),
                points,
            });
        }
        Ok(out)
    }

    /// The size of the child programs, when the program is to be split into them.
    fn child_limit(&self, spec: &ProgramSpec) -> Result<Option<u64>, PlanError> {
        let Some(limit) = spec.max_program_bytes else {
            return Ok(None);
        };
        let cost = self.cost(None)?;
        Ok((cost.nc_bytes as f64 > 0.9 * limit as f64).then_some(limit))
    }

    /// One pass body: the frame's link and approach, every point, the retract.
    fn write_body(
        &self,
        writer: &mut ProgramWriter,
        extras: &mut Extras,
        group: &GroupPath,
        (pass, lift, retract, finishing): (&Pass, f64, f64, bool),
        progress: &mut ProgressFn,
    ) -> Result<(), PlanError> {
        let path = &group.path;
        let mut first = None;
        path.for_each_point(Stage::Path, progress, &mut |p, folds| {
            // A split path has one spiral for every pass (job validation).
            let slide = extras.slide(p)?;
            match first {
                None => {
                    let words = writer.words(p, slide, lift)?;
                    writer.begin_pass(
                        pass,
                        PassFrame {
                            lift_mm: lift,
                            first: words,
                            first_z_mm: p.z,
                            first_theta: p.theta,
                            retract_mm: retract,
                        },
                    )?;
                    first = Some(p.index);
                }
                Some(_) => writer.point(p, slide)?,
            }
            if finishing {
                extras.point(p, folds)?;
            }
            Ok::<(), PlanError>(())
        })?;
        writer.end_pass(retract)?;
        Ok(())
    }
}

/// Refuses a safe height, retract height or approach that does not clear the passes.
fn check_heights(
    spec: &ProgramSpec,
    groups: &[GroupPath],
    (safe_z, stock, clearance): (f64, f64, f64),
) -> Result<(), FieldError> {
    let top = groups.iter().map(|g| g.z_max).fold(f64::MIN, f64::max);
    if spec.safe_z_mm.is_some() && safe_z <= top + stock {
        return Err(FieldError::new(
            "program.safe_z_mm",
            safe_z,
            format!(
                "must clear the highest point of the first pass, {} mm (the path's top {} mm \
                 plus the stock {} mm)",
                short(top + stock),
                short(top),
                short(stock)
            ),
        ));
    }
    if let Some(r) = spec.retract_height_mm
        && r <= top
    {
        return Err(FieldError::new(
            "program.retract_height_mm",
            r,
            format!("must clear the pass's highest point, {} mm", short(top)),
        ));
    }
    if let Some(first) = spec.approach.first() {
        for g in groups {
            let retract = spec.retract_height_mm.unwrap_or(g.z_max + clearance);
            if g.z_first + first.height_mm >= retract {
                return Err(FieldError::new(
                    "program.approach[0].height_mm",
                    first.height_mm,
                    format!(
                        "must start below the retract height {} mm: at most {} mm above the \
                         first point ({} mm)",
                        short(retract),
                        short(retract - g.z_first),
                        short(g.z_first)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The header's lines about the program: passes, loop, feed meaning and cycle time, edge.
fn program_lines(
    job: &Job,
    spec: &ProgramSpec,
    groups: &[GroupPath],
    passes: &[Pass],
) -> Vec<String> {
    let mut lines = Vec::new();
    let described: Vec<String> = if spec.passes.is_empty() {
        vec!["one pass".into()]
    } else {
        spec.passes
            .iter()
            .enumerate()
            .map(|(g, p)| {
                format!(
                    "{} x {} um at {} mm/rev, {} rpm",
                    p.count,
                    short(p.depth_of_cut_um),
                    short(groups[g].path.spiral().feed_mm()),
                    short(groups[g].rpm)
                )
            })
            .collect()
    };
    lines.push(format!(
        "passes: {}; stock {} mm; {}",
        described.join(", "),
        short(spec.stock_mm()),
        match spec.loop_kind {
            LoopKind::Controller =>
                "one body a group, repeated by the controller with a G52 Z shift",
            LoopKind::Unrolled => "every pass written out",
        }
    ));
    let cutting: f64 = passes
        .iter()
        .map(|p| {
            let g = &groups[p.group];
            g.path.spiral().revolutions() * 60.0 / g.rpm
        })
        .sum();
    lines.push(format!(
        "{}: the spindle turns at the job's speed; cutting time {} s in all",
        job.output.feed_mode.meaning(),
        short((cutting * 10.0).round() / 10.0)
    ));
    lines.push(job.edge_description());
    lines
}
