//! The analysis layer: the accuracy of a planned path, read from its tool path
//! ([`crate::tool::ToolPath`]) with the layers below it.
//!
//! - [`linearization`]: the cutting linearization error between NC points (paper 000, PVerr);
//! - [`predicted_form`]: the machined form predicted from the nose swept along the path;
//! - [`power_map`]: mean power and cylinder of a surface (paper 003's maps);
//!
//! and the closed loop of issue 15, from a measured part back to a corrected job:
//!
//! - [`registration`]: the design registered to measured data by least squares (piston, tilt,
//!   power; decentre and clocking where the design's shape tells them from tilt);
//! - [`residual`]: the residual on a grid over the part, from local fits of the measured points;
//! - [`extension`]: the residual continued smoothly where nothing was measured (minimum
//!   curvature);
//! - [`zernike_fit`]: its first 37 Fringe Zernike terms ([`normal_equations`]: the least squares
//!   of both);
//! - [`correction`]: the whole correction: design − gain × residual as a job, and the residual
//!   predicted after the re-cut;
//! - [`setup`]: the set-up errors a test cut shows (tool height, X offset, radius) turned into
//!   offsets;
//!
//! and a program from any system read back and checked against the design (issue 14):
//!
//! - [`verify`]: the deviation of every cutting point from the one-way compensated tip, per
//!   pass, with the accuracy analyses of the last pass, feeds and times, collisions and the
//!   machine's limits (`spiralcam verify`, the page's Open NC…).
//!
//! This module is the accuracy report ([`Analysis`]): in one pass over the path the
//! linearization error, the predicted form, the tool angles the surface asks for
//! ([`crate::tool::geometry`], paper 000), and how far the part is from a surface of revolution
//! with the pass spacing the space spiral would give ([`crate::path::space_spiral::survey`],
//! paper 001). The command line prints it as JSON (`spiralcam analyse`); the page shows its
//! figures and maps. The pass runs on every core: the path and each segment's linearization
//! error are computed on the workers ([`crate::tool::ToolPath::for_each_pair`]), the rest follows
//! the path in order on the calling thread; the figures are the same on any number of threads.
//!
//! The analyses assume one-way compensation (X on the spiral); a two-way job is refused.
//!
//! The two measure different things: the linearization error is found at its extremes on every
//! segment; the predicted form samples the path where it crosses 360 half-planes through the
//! axis, so it sees the linearization error only at those crossings (with constant-angle
//! sampling of 720 points per revolution the half-planes fall on NC points, where it is zero),
//! and adds what the linearization check leaves out: the cusps between passes and the nose's
//! envelope.

pub mod correction;
pub mod extension;
pub mod linearization;
pub mod normal_equations;
pub mod power_map;
pub mod predicted_form;
pub mod registration;
pub mod residual;
pub mod setup;
pub mod verify;
pub mod zernike_fit;

use crate::analysis::linearization::{LinearizationCheck, LinearizationReport, error_ending_at};
use crate::analysis::predicted_form::{FormPredictor, FormSettings, PredictedForm};
use crate::field::FieldError;
use crate::job::Compensation;
use crate::path::PathError;
use crate::path::space_spiral::{Survey, survey};
use crate::progress::{Progress, Stage};
use crate::raster::Raster;
use crate::tool::ToolPath;
use crate::tool::geometry::{ToolGeometryCheck, ToolGeometryReport};
use serde::Serialize;
use std::borrow::Cow;
use std::ops::ControlFlow;

/// Both analyses of one path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Analysis {
    /// The job's name.
    pub job: String,
    /// The linearization error between consecutive NC points.
    pub linearization: LinearizationReport,
    /// The predicted machined form; `None` where it cannot be predicted (see `notes`).
    pub predicted_form: Option<PredictedForm>,
    /// Critical tool angles, interference with the job's tool and the holder tilt that clears it.
    pub tool_geometry: ToolGeometryReport,
    /// How close the part is to a surface of revolution and the pass spacing of the space
    /// spiral against Z projection (paper 001); `None` where it cannot be computed (see `notes`).
    pub revolution: Option<Survey>,
    /// Why an analysis is missing.
    pub notes: Vec<String>,
}

impl Analysis {
    /// Runs both analyses over `tool_path`'s path with maps of `map_size` × `map_size` samples;
    /// `progress` sees the points read and may stop the run ([`PathError::Cancelled`]).
    pub fn run(
        tool_path: &ToolPath,
        map_size: usize,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<Self, PathError> {
        if tool_path.job().strategy.compensation == Compensation::TwoWay {
            return Err(FieldError::new(
                "strategy.compensation",
                "two_way",
                "the accuracy analysis covers one-way compensation only (X on the spiral)",
            )
            .into());
        }
        let mut linearization = LinearizationCheck::new(tool_path, map_size);
        let angles = tool_path
            .job()
            .tool
            .angles()
            .map_err(|e| e.within("tool"))?;
        let mut tool_geometry = ToolGeometryCheck::new(tool_path, &angles, map_size);
        let mut notes = Vec::new();
        let mut form = match FormPredictor::new(tool_path, &FormSettings::default(), map_size) {
            Ok(f) => Some(f),
            Err(PathError::Job(e)) => {
                notes.push(format!("no predicted form: {e}"));
                None
            }
            Err(e) => return Err(e),
        };
        // The path and each segment's linearization error on the workers; the tool geometry
        // and the swept form (which follow the path in order) on this thread.
        tool_path.for_each_pair(
            Stage::Analysis,
            progress,
            |a, b| Ok::<_, PathError>(error_ending_at(tool_path, a, b)?),
            &mut |p, _, segment| {
                if let Some(segment) = segment {
                    linearization.take(segment);
                }
                tool_geometry.add(tool_path, p)?;
                if let Some(f) = form.as_mut() {
                    f.push(p)?;
                }
                Ok(())
            },
        )?;
        let job = tool_path.job();
        let revolution = match survey(
            tool_path.surface(),
            job.part_radius_mm(),
            job.strategy.feed_mm_per_rev,
        ) {
            Ok(s) => Some(s),
            Err(e) => {
                notes.push(format!("no surface-of-revolution survey: {e}"));
                None
            }
        };
        Ok(Self {
            job: tool_path.job().name.clone(),
            linearization: linearization.finish(),
            predicted_form: form.map(FormPredictor::finish).transpose()?,
            tool_geometry: tool_geometry.finish(),
            revolution,
            notes,
        })
    }

    /// The figures as pretty JSON (the maps left out).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }

    /// The linearization error map, µm.
    pub fn linearization_map(&self) -> &Raster {
        &self.linearization.map
    }

    /// The clearance angle the surface requires, degrees.
    pub fn clearance_map(&self) -> &Raster {
        &self.tool_geometry.map
    }

    /// The predicted form error map, µm (all NaN, on the linearization map's grid, without a
    /// prediction).
    pub fn form_map(&self) -> Cow<'_, Raster> {
        match &self.predicted_form {
            Some(f) => Cow::Borrowed(&f.map),
            None => {
                let lin = &self.linearization.map;
                Cow::Owned(Raster {
                    values: vec![f64::NAN; lin.values.len()],
                    ..*lin
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::Job;
    use crate::tool::ToolPath;

    #[test]
    fn a_two_way_job_is_refused_naming_the_field() {
        let mut job = Job::default_job();
        job.strategy.compensation = Compensation::TwoWay;
        let planner = ToolPath::new(&job).unwrap();
        let e = Analysis::run(&planner, 8, &mut |_| ControlFlow::Continue(())).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("strategy.compensation = two_way:"),
            "{e}"
        );
    }
}
