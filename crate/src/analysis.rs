//! The accuracy analysis of a planned path, in one pass over it: the cutting linearization
//! error between NC points ([`crate::linearization`], paper 000), the machined form predicted
//! from the nose swept along the path ([`crate::predicted_form`]), the tool angles the surface
//! asks for ([`crate::tool_geometry`], paper 000), and how far the part is from a surface of
//! revolution with the pass spacing the space spiral would give
//! ([`crate::space_spiral::survey`], paper 001). The command line prints it as JSON
//! (`spiralcam analyse`); the page shows its figures and maps.
//!
//! All three assume one-way compensation (X on the spiral); a two-way job is refused.
//!
//! The two measure different things: the linearization error is found at its extremes on every
//! segment; the predicted form samples the path where it crosses 360 half-planes through the
//! axis, so it sees the linearization error only at those crossings (with constant-angle
//! sampling of 720 points per revolution the half-planes fall on NC points, where it is zero),
//! and adds what the linearization check leaves out: the cusps between passes and the nose's
//! envelope.

use crate::compensate::Compensation;
use crate::field::FieldError;
use crate::linearization::{LinearizationCheck, LinearizationReport};
use crate::plan::{PROGRESS_EVERY, PlanError, Planner, Progress};
use crate::predicted_form::{FormPredictor, FormSettings, PredictedForm};
use crate::raster::Raster;
use crate::space_spiral::{Survey, survey};
use crate::tool_geometry::{ToolGeometryCheck, ToolGeometryReport};
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
    /// Runs both analyses over `planner`'s path with maps of `map_size` × `map_size` samples;
    /// `progress` sees the points read and may stop the run ([`PlanError::Cancelled`]).
    pub fn run(
        planner: &Planner,
        map_size: usize,
        progress: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<Self, PlanError> {
        if planner.job().strategy.compensation == Compensation::TwoWay {
            return Err(FieldError::new(
                "strategy.compensation",
                "two_way",
                "the accuracy analysis covers one-way compensation only (X on the spiral)",
            )
            .into());
        }
        let total = planner.spiral().point_count_hint();
        let mut linearization = LinearizationCheck::new(planner, map_size);
        let angles = planner.job().tool.angles().map_err(|e| e.within("tool"))?;
        let mut tool_geometry = ToolGeometryCheck::new(planner, &angles, map_size);
        let mut notes = Vec::new();
        let mut form = match FormPredictor::new(planner, &FormSettings::default(), map_size) {
            Ok(f) => Some(f),
            Err(PlanError::Job(e)) => {
                notes.push(format!("no predicted form: {e}"));
                None
            }
            Err(e) => return Err(e),
        };
        let mut done = 0u64;
        for p in planner.points() {
            let p = p?;
            linearization.add(planner, &p)?;
            tool_geometry.add(planner, &p)?;
            if let Some(f) = form.as_mut() {
                f.push(&p)?;
            }
            done += 1;
            if done.is_multiple_of(PROGRESS_EVERY) && progress(Progress { done, total }).is_break()
            {
                return Err(PlanError::Cancelled);
            }
        }
        let _ = progress(Progress { done, total });
        let job = planner.job();
        let revolution = match survey(
            planner.surface(),
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
            job: planner.job().name.clone(),
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

    #[test]
    fn a_two_way_job_is_refused_naming_the_field() {
        let mut job = Job::default_job();
        job.strategy.compensation = Compensation::TwoWay;
        let planner = Planner::new(&job).unwrap();
        let e = Analysis::run(&planner, 8, &mut |_| ControlFlow::Continue(())).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("strategy.compensation = two_way:"),
            "{e}"
        );
    }
}
