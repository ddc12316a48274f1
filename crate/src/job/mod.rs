//! The job layer: one JSON document that says everything the planner needs (README "Job
//! format", crate/docs/job-format.md), as spec types with their defaults and checks. It uses
//! only the field helpers and the surface families' own specs ([`crate::surface::SurfaceSpec`]:
//! each family's parameters live beside its maths), so every layer above may read a job.
//!
//! Units are in the field names (`_mm`, `_deg`, `_rpm`). Unknown fields are rejected, so a typo
//! is an error rather than a silently ignored setting. [`Job::from_json`] parses and
//! [`Job::validate`] checks the values no single stage owns; the stages check their own fields
//! (the samplers the sampling, the compensator the tool) when they are built. Every error
//! names the field.
//!
//! - [`tool`]: `tool` (nose radius, included, rake and clearance angles, measured edge waviness);
//! - [`strategy`]: `strategy` (feed, sampling, direction, compensation, split);
//! - [`machine`]: `machine` (spindle, slides, servo, block rate) and the example presets;
//! - [`output`]: `output` (dialect, decimals, signs, feed mode, approach);
//! - [`format`](mod@format): `format` (the version of the job format; only 1 is read);
//! - [`fts_grid`]: `output.fts_grid` (the servo's gridded table: tolerance, counts, motors);
//! - [`program`]: `program` (set-up words, heights, approach, passes, loop, child programs);
//! - [`cut`]: `part.cut` (the optic or a mould, the design's frame or turned 180° about Y);
//! - [`design`]: a job from a designer's file ([`crate::surface::import`]).

pub mod cut;
pub mod design;
pub mod format;
pub mod fts_grid;
pub mod machine;
pub mod output;
pub mod program;
pub mod strategy;
pub mod tool;

pub use cut::{CutSpec, Frame, Piece};
pub use fts_grid::FtsGridSpec;
pub use machine::MachineSpec;
pub use output::{Dialect, FeedMode, OutputSpec};
pub use program::{LoopKind, PassGroup, ProgramSpec};
pub use strategy::{Compensation, Direction, Sampling, SplitSpec, StrategySpec};
pub use tool::{ToolAngles, ToolSpec, WavinessSpec};

use crate::field::{FieldError, finite, join_path, non_negative, positive};
use crate::surface::{PartDisc, Reframed, Surface, SurfaceSpec, Turned};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// The longest job name: it names the output files and is written into the program's header.
pub const MAX_NAME_CHARS: usize = 128;

/// The largest part diameter accepted, mm (10 m): beyond every machine, and small enough that a
/// path's point count, sags and probes stay finite numbers.
pub const MAX_PART_DIAMETER_MM: f64 = 10_000.0;

/// The example job for the paper 004 lens array, planned by the page on load.
pub const DEFAULT_JOB: &str = include_str!("../../jobs/lens-array-paper004.json");

/// A whole job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Job {
    /// The version of the job format ([`format`](mod@format)): absent or 1; other values are refused.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub format: Option<u32>,
    /// Name, used in NC headers and for output file names; letters, digits, `-`, `_`, `.`.
    pub name: String,
    /// The blank.
    pub part: PartSpec,
    /// The surface to cut.
    pub surface: SurfaceSpec,
    /// The tool.
    pub tool: ToolSpec,
    /// The machine.
    pub machine: MachineSpec,
    /// How the path is laid.
    pub strategy: StrategySpec,
    /// What is written.
    #[serde(default)]
    pub output: OutputSpec,
    /// The program around the path: set-up words, approach, passes, loops, child programs;
    /// absent, one spiral ([`program`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub program: Option<ProgramSpec>,
}

/// The blank.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PartSpec {
    /// Diameter of the part, mm, > 0, about the spindle axis.
    pub diameter_mm: f64,
    /// The spindle axis: absent, the design's Z through its origin; `[x, y]` (mm, design
    /// coordinates), the design's normal at that point (paper 001's rotation axis `t`), the part
    /// being mounted with that point on the axis ([`crate::surface::Reframed`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal_axis_at_mm: Option<[f64; 2]>,
    /// What is cut and in which frame ([`cut`]): absent, the design's frame, nothing stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cut: Option<CutSpec>,
    /// What lies beyond the part's edge (its radius): `none` (default: no material; the nose's
    /// arc is cut at the edge) or `surface` (the design continues, as on a blank larger than the
    /// clear aperture: the arc rests on it there too).
    #[serde(default, skip_serializing_if = "BeyondEdge::is_none")]
    pub beyond_edge: BeyondEdge,
}

/// What lies beyond the part's edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BeyondEdge {
    /// No material: the nose's arc is cut at the edge.
    #[default]
    None,
    /// The design continues.
    Surface,
}

impl BeyondEdge {
    /// Whether this is the default, no material beyond the edge.
    pub fn is_none(&self) -> bool {
        *self == BeyondEdge::None
    }
}

/// A job that cannot be read.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum JobError {
    /// The text is not a job document: bad JSON, a missing or unknown field, a wrong type.
    ///
    /// ```
    /// let e = spiralcam::job::Job::from_json("{\"name\": 1}").unwrap_err();
    /// assert!(e.to_string().starts_with("job: "));
    /// ```
    #[error("job: {0}")]
    Syntax(String),
    /// A field has a value outside its range.
    ///
    /// ```
    /// let mut job = spiralcam::job::Job::default_job();
    /// job.part.diameter_mm = -1.0;
    /// assert_eq!(job.validate().unwrap_err().to_string(),
    ///            "part.diameter_mm = -1: must be a finite number > 0");
    /// ```
    #[error(transparent)]
    Field(#[from] FieldError),
}

impl Job {
    /// Parses a job document (checks syntax and field names, not values).
    /// A UTF-8 byte-order mark in front of the text is skipped; JSON syntax errors give the line
    /// and column.
    ///
    /// ```
    /// let e = spiralcam::job::Job::from_json("[\"a\", 1]").unwrap_err();
    /// assert_eq!(e.to_string(), "job: must be a JSON object {…}, not an array");
    /// ```
    pub fn from_json(text: &str) -> Result<Self, JobError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        // A first pass: JSON syntax, and no key twice (a later reader would keep the last).
        let de = &mut serde_json::Deserializer::from_str(text);
        serde_path_to_error::deserialize::<_, UniqueKeys>(de).map_err(syntax)?;
        // serde would read an array as the job's fields in order.
        let kind = match text.trim_start().chars().next() {
            Some('{') => None,
            Some('[') => Some("an array"),
            Some('"') => Some("a string"),
            Some('t' | 'f') => Some("a boolean"),
            Some('n') => Some("null"),
            _ => Some("a number"),
        };
        if let Some(kind) = kind {
            return Err(JobError::Syntax(format!(
                "must be a JSON object {{…}}, not {kind}"
            )));
        }
        // The version first: a newer job may hold fields this version does not know.
        format::FormatHeader::check(text)?;
        Self::deserialize_from(&mut serde_json::Deserializer::from_str(text))
    }

    /// Reads a job from any serde deserializer (JSON text, a JavaScript object on the page);
    /// errors name the path of the offending field, inside a surface family too
    /// (`job: surface.phase_y_deg: invalid type: string "a", expected f64`).
    pub fn deserialize_from<'de, D: serde::Deserializer<'de>>(de: D) -> Result<Self, JobError>
    where
        D::Error: std::fmt::Display,
    {
        let job: Self = serde_path_to_error::deserialize(de).map_err(syntax)?;
        if let Some(v) = job.format {
            format::check_format(&serde_json::Value::from(v))?;
        }
        Ok(job)
    }

    /// The page's default job: paper 004's lens array.
    pub fn default_job() -> Self {
        match Self::from_json(DEFAULT_JOB) {
            Ok(job) => job,
            Err(e) => unreachable!("the bundled default job is valid: {e}"),
        }
    }

    /// The job as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Part radius, mm.
    pub fn part_radius_mm(&self) -> f64 {
        self.part.diameter_mm / 2.0
    }

    /// The surface as the spindle sees it: the design, or with `part.normal_axis_at_mm` the
    /// design seen along its normal there, then turned 180° about Y when `part.cut.frame` is
    /// `turned` ([`Turned`]). The design's features (lenslets kept, checks against the part)
    /// are laid out over the part disc about that point.
    pub fn build_surface(&self) -> Result<Box<dyn Surface>, FieldError> {
        let design = self.design_surface()?;
        match self.part.cut {
            Some(CutSpec {
                frame: Frame::Turned,
                ..
            }) => Ok(Box::new(Turned::new(design))),
            _ => Ok(design),
        }
    }

    /// The surface in the design's frame: the spindle's view before `part.cut` turns it.
    pub fn design_surface(&self) -> Result<Box<dyn Surface>, FieldError> {
        let radius_mm = self.part_radius_mm();
        let Some([x_mm, y_mm]) = self.part.normal_axis_at_mm else {
            return self.surface.build(radius_mm);
        };
        let disc = PartDisc {
            radius_mm,
            x_mm,
            y_mm,
        };
        let design = self
            .surface
            .build_in(disc)
            .map_err(|e| e.within("surface"))?;
        match Reframed::new(design, x_mm, y_mm) {
            Ok(s) => Ok(Box::new(s)),
            Err(e) => Err(FieldError::new(
                "part.normal_axis_at_mm",
                format!("[{x_mm}, {y_mm}]"),
                format!("must be a point where the surface is defined: {e}"),
            )),
        }
    }

    /// Radius where the spiral starts, mm (before rounding to whole steps).
    pub fn outer_radius_mm(&self) -> f64 {
        let inside = self
            .strategy
            .outer_radius_mm
            .unwrap_or_else(|| self.part_radius_mm());
        inside + self.strategy.overtravel_mm
    }

    /// What lies beyond the part's edge and where the spiral starts, for headers and reports.
    pub fn edge_description(&self) -> String {
        let edge = match self.part.beyond_edge {
            BeyondEdge::None => "no material beyond the part's edge (the nose's arc is cut there)",
            BeyondEdge::Surface => "the design continues beyond the part's edge",
        };
        format!(
            "{edge}; the spiral starts {} mm outside the part's radius",
            crate::field::short(self.strategy.overtravel_mm)
        )
    }

    /// Where the material ends for the nose's arc, mm: the part's radius, or nowhere when the
    /// design continues beyond the edge (`part.beyond_edge`).
    pub fn material_radius_mm(&self) -> f64 {
        match self.part.beyond_edge {
            BeyondEdge::None => self.part_radius_mm(),
            BeyondEdge::Surface => f64::INFINITY,
        }
    }

    /// Reads the data files the job names by path (scattered points, STEP files) with `read`,
    /// which maps a path as written in the job to its contents or a message; the command line
    /// reads relative to the job file. Files given as text are left as they are.
    pub fn load_files(
        &mut self,
        mut read: impl FnMut(&str) -> Result<String, String>,
    ) -> Result<(), JobError> {
        for (field, file) in self.surface.data_files_mut() {
            file.check(&format!("surface.{field}"))?;
            if let (None, Some(path)) = (&file.text, &file.path) {
                let text = read(path).map_err(|e| {
                    FieldError::new(
                        format!("surface.{field}.path"),
                        path,
                        format!("cannot be read: {e}"),
                    )
                })?;
                file.text = Some(text);
            }
        }
        Ok(())
    }

    /// A split needs a servo, and the automatic one the Z slide's limits too; a cutoff is a
    /// positive number (its upper bound, the path's Nyquist frequency, is checked on the path).
    fn validate_split(&self) -> Result<(), FieldError> {
        let Some(split) = &self.strategy.split else {
            return Ok(());
        };
        if self.machine.fts.is_none() {
            return Err(FieldError::new(
                "strategy.split",
                "set",
                "needs a fast tool servo: machine.fts",
            ));
        }
        match split {
            SplitSpec::LowPass { cutoff_hz } => {
                positive("strategy.split.cutoff_hz", *cutoff_hz)?;
            }
            SplitSpec::Auto if self.machine.z_slide.is_none() => {
                return Err(FieldError::new(
                    "strategy.split.type",
                    "auto",
                    "needs the Z slide's limits: machine.z_slide",
                ));
            }
            _ => {}
        }
        Ok(())
    }

    /// Checks the values that no single module owns.
    pub fn validate(&self) -> Result<(), JobError> {
        if self.name.is_empty()
            || self.name.len() > MAX_NAME_CHARS
            || !self
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
        {
            let shown: String = self.name.chars().take(40).collect();
            let shown = if shown.len() < self.name.len() {
                format!("{shown}… ({} characters)", self.name.chars().count())
            } else {
                shown
            };
            return Err(FieldError::new(
                "name",
                shown,
                format!("letters, digits, '-', '_' or '.', 1 to {MAX_NAME_CHARS} characters"),
            )
            .into());
        }
        positive("part.diameter_mm", self.part.diameter_mm)?;
        if self.part.diameter_mm > MAX_PART_DIAMETER_MM {
            return Err(FieldError::new(
                "part.diameter_mm",
                self.part.diameter_mm,
                format!(
                    "must be at most {MAX_PART_DIAMETER_MM} mm (the largest diamond-turning \
                     machines swing about 2 m)"
                ),
            )
            .into());
        }
        let r = self.tool.nose_radius_mm;
        if r > self.part.diameter_mm {
            return Err(FieldError::new(
                "tool.nose_radius_mm",
                r,
                format!(
                    "must not exceed the part's diameter {} mm (part.diameter_mm): a nose larger \
                     than the part",
                    self.part.diameter_mm
                ),
            )
            .into());
        }

        if let Some([x, y]) = self.part.normal_axis_at_mm {
            finite("part.normal_axis_at_mm[0]", x)?;
            finite("part.normal_axis_at_mm[1]", y)?;
        }
        self.machine.validate().map_err(|e| e.within("machine"))?;
        self.validate_split()?;
        if let Some(r) = self.strategy.outer_radius_mm {
            positive("strategy.outer_radius_mm", r)?;
            if r > self.part_radius_mm() {
                return Err(FieldError::new(
                    "strategy.outer_radius_mm",
                    r,
                    format!(
                        "must not exceed the part radius {} mm",
                        self.part_radius_mm()
                    ),
                )
                .into());
            }
        }
        non_negative("strategy.overtravel_mm", self.strategy.overtravel_mm)?;
        if self.strategy.overtravel_mm > self.part_radius_mm() {
            return Err(FieldError::new(
                "strategy.overtravel_mm",
                self.strategy.overtravel_mm,
                format!("at most the part's radius {} mm", self.part_radius_mm()),
            )
            .into());
        }
        self.output.validate().map_err(|e| e.within("output"))?;
        if let Some(program) = &self.program {
            program.validate().map_err(|e| e.within("program"))?;
            if self.output.dialect == Dialect::Iso {
                for (field, m) in [
                    ("c_axis_on", &program.c_axis_on),
                    ("c_axis_off", &program.c_axis_off),
                ] {
                    if let Some(m) = m.as_ref().filter(|m| m.contains('.')) {
                        return Err(FieldError::new(
                            format!("program.{field}"),
                            format!("{m:?}"),
                            "a whole M word in the ISO dialect: LinuxCNC reads no decimal M codes",
                        )
                        .into());
                    }
                }
            }
            if self.strategy.split.is_some() && program.has_own_spirals() {
                return Err(FieldError::new(
                    "program.passes",
                    "a group with its own feed_mm_per_rev or spindle_rpm",
                    "not with strategy.split: the split is made for the strategy's spiral; give \
                     every pass the strategy's feed and the machine's speed",
                )
                .into());
            }
        }
        Ok(())
    }
}

/// A job that cannot be read, named by the path of the offending field (a path carried inside
/// a surface's message joined on: [`join_path`]).
fn syntax<E: std::fmt::Display>(e: serde_path_to_error::Error<E>) -> JobError {
    let (path, message) = join_path(&e.path().to_string(), &e.inner().to_string());
    match path.as_str() {
        "." | "" => JobError::Syntax(message),
        _ => JobError::Syntax(format!("{path}: {message}")),
    }
}

/// Any JSON value whose objects have no key twice: a first pass over a job's text, since a
/// [`serde_json::Value`] keeps the last of two equal keys without a word.
struct UniqueKeys;

impl<'de> serde::Deserialize<'de> for UniqueKeys {
    fn deserialize<D: serde::Deserializer<'de>>(de: D) -> Result<Self, D::Error> {
        de.deserialize_any(UniqueKeys)
    }
}

impl<'de> serde::de::Visitor<'de> for UniqueKeys {
    type Value = UniqueKeys;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Self, A::Error> {
        let mut seen = std::collections::HashSet::new();
        while let Some(key) = map.next_key::<String>()? {
            if !seen.insert(key.clone()) {
                return Err(serde::de::Error::custom(format!("duplicate field `{key}`")));
            }
            map.next_value::<UniqueKeys>()?;
        }
        Ok(UniqueKeys)
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Self, A::Error> {
        while seq.next_element::<UniqueKeys>()?.is_some() {}
        Ok(UniqueKeys)
    }

    fn visit_bool<E>(self, _: bool) -> Result<Self, E> {
        Ok(UniqueKeys)
    }

    fn visit_i64<E>(self, _: i64) -> Result<Self, E> {
        Ok(UniqueKeys)
    }

    fn visit_u64<E>(self, _: u64) -> Result<Self, E> {
        Ok(UniqueKeys)
    }

    fn visit_f64<E>(self, _: f64) -> Result<Self, E> {
        Ok(UniqueKeys)
    }

    fn visit_str<E>(self, _: &str) -> Result<Self, E> {
        Ok(UniqueKeys)
    }

    fn visit_unit<E>(self) -> Result<Self, E> {
        Ok(UniqueKeys)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::Value;

    /// The job error for a surface, in a job that is otherwise the default.
    fn job_error(surface: &str) -> String {
        let mut job: Value = serde_json::from_str(&Job::default_job().to_json()).unwrap();
        job["surface"] = serde_json::from_str(surface).unwrap();
        Job::from_json(&job.to_string()).unwrap_err().to_string()
    }

    #[test]
    fn errors_inside_a_surface_name_their_full_path() {
        // An asphere base or parent is an asphere spec without a "type".
        let e = job_error(
            r#"{"type":"xy_polynomial","base":{"type":"asphere","radius_mm":80},"norm_radius_mm":6,"terms":[]}"#,
        );
        assert!(
            e.starts_with("job: surface.base.type: unknown field `type`"),
            "{e}"
        );
        let e = job_error(
            r#"{"type":"off_axis_conic","parent":{"type":"asphere","radius_mm":80},"off_axis_distance_mm":5}"#,
        );
        assert!(
            e.starts_with("job: surface.parent.type: unknown field `type`"),
            "{e}"
        );
        // Inside a list, and a surface inside a composite's term.
        let e = job_error(
            r#"{"type":"xy_polynomial","base":{"radius_mm":80},"norm_radius_mm":6,"terms":[{"x":1,"y":0,"coefficient_mm":"a"}]}"#,
        );
        assert!(
            e.starts_with("job: surface.terms[0].coefficient_mm: invalid type"),
            "{e}"
        );
        let e = job_error(
            r#"{"type":"composite","base":{"type":"asphere","radius_mm":50},"terms":[{"surface":
                {"type":"zernike","convention":"fringe","base":{"type":"asphere"},"norm_radius_mm":2,"coefficients_mm":[]}}]}"#,
        );
        assert!(
            e.starts_with("job: surface.terms[0].surface.base.type: unknown field `type`"),
            "{e}"
        );
        // The same with "type" not first (the object is buffered).
        let e = job_error(
            r#"{"base":{"radius_mm":80,"type":"asphere"},"type":"xy_polynomial","norm_radius_mm":6,"terms":[]}"#,
        );
        assert!(
            e.starts_with("job: surface.base.type: unknown field `type`"),
            "{e}"
        );
        let e = job_error(
            r#"{"terms":[{"surface":{"base":{"type":"asphere"},"type":"zernike","convention":"fringe","norm_radius_mm":2,"coefficients_mm":[]}}],
                "type":"composite","base":{"type":"asphere","radius_mm":50}}"#,
        );
        assert!(
            e.starts_with("job: surface.terms[0].surface.base.type: unknown field `type`"),
            "{e}"
        );
        // The surface's own fields and family.
        let e = job_error(r#"{"type":"asphere","radius_mm":80,"colour":"red"}"#);
        assert!(
            e.starts_with("job: surface.colour: unknown field `colour`"),
            "{e}"
        );
        let e = job_error(r#"{"type":"torus"}"#);
        assert!(
            e.starts_with("job: surface: unknown variant `torus`"),
            "{e}"
        );
    }

    #[test]
    fn a_part_beyond_every_machine_is_refused_by_its_diameter() {
        // Found from outside: 1.8e308 mm was refused by the feed ("inf points").
        let mut job = Job::default_job();
        job.part.diameter_mm = MAX_PART_DIAMETER_MM;
        job.validate().unwrap();
        for d in [MAX_PART_DIAMETER_MM * (1.0 + 1e-15), f64::MAX] {
            job.part.diameter_mm = d;
            let e = job.validate().unwrap_err().to_string();
            assert!(
                e.starts_with("part.diameter_mm = ") && e.contains("must be at most 10000 mm"),
                "{e}"
            );
        }
    }

    #[test]
    fn default_job_round_trips_and_validates() {
        let job = Job::default_job();
        job.validate().unwrap();
        assert_eq!(Job::from_json(&job.to_json()).unwrap(), job);
    }

    #[test]
    fn unknown_fields_are_rejected_with_their_name() {
        let text = DEFAULT_JOB.replacen("\"spindle_rpm\"", "\"spindle_rmp\"", 1);
        let e = Job::from_json(&text).unwrap_err().to_string();
        assert!(e.contains("spindle_rmp"), "{e}");
    }

    #[test]
    fn type_errors_name_the_path() {
        let text = DEFAULT_JOB.replacen("\"points_per_rev\": 720", "\"points_per_rev\": -3", 1);
        let e = Job::from_json(&text).unwrap_err().to_string();
        // Internally tagged enums buffer their content, so the path ends at the enum.
        assert!(
            e.starts_with("job: strategy.sampling: invalid value: integer `-3`, expected u32"),
            "{e}"
        );
    }

    #[test]
    fn bad_names_are_rejected() {
        let mut job = Job::default_job();
        job.name = "a b".into();
        assert!(
            job.validate()
                .unwrap_err()
                .to_string()
                .starts_with("name = a b")
        );
    }
}
