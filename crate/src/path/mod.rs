//! The path layer: the tool path's data types ([`PathPoint`], [`Location`]) and the samplers
//! that lay the spiral's (ρ, θ) points from the outer radius to the centre. It uses the job, the
//! surface and the helpers below it.
//!
//! - [`spiral`]: constant angle and constant arc sampling, and zoned spirals (paper 003 eqs
//!   18, 21–22; paper 000's spiral point P);
//! - [`hcaa`]: hybrid constant-angle / constant-arc and adaptive sampling from a PV tolerance
//!   on the linearization error (paper 000, "HCAA method"); it reads the compensated tip
//!   height through a function, so it needs no tool;
//! - [`space_spiral`]: the space Archimedean spiral on a best-fit surface of revolution
//!   (paper 001, eq 7).

pub mod hcaa;
pub mod space_spiral;
pub mod spiral;

pub use spiral::{IndexedPoints, MAX_POINTS, Spiral, SpiralPoint, WalkedRule};

use crate::field::FieldError;
use crate::job::JobError;
use crate::surface::UndefinedError;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// One point of the tool path.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
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
    /// The contact is at an end of the nose arc (see [`crate::tool::Contact`]).
    pub at_arc_end: bool,
}

/// Where on the part: polar radius and angle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Location {
    /// Radius, mm.
    pub rho_mm: f64,
    /// Polar angle, degrees in [0, 360).
    pub theta_deg: f64,
}

impl Location {
    /// From ρ and a cumulative θ in radians.
    pub fn new(rho: f64, theta: f64) -> Self {
        Self {
            rho_mm: rho,
            theta_deg: theta.to_degrees().rem_euclid(360.0),
        }
    }
}

/// Why a path could not be laid or followed.
#[derive(Debug, Error)]
pub enum PathError {
    /// The job has a value the stage cannot use.
    ///
    /// ```
    /// let e = spiralcam::path::PathError::from(spiralcam::field::FieldError::new("x", 1, "no"));
    /// assert_eq!(e.to_string(), "x = 1: no");
    /// ```
    #[error(transparent)]
    Job(#[from] JobError),
    /// The surface has no value where the path needs one.
    #[error(transparent)]
    Surface(#[from] UndefinedError),
    /// The progress callback asked to stop.
    ///
    /// ```
    /// assert_eq!(spiralcam::path::PathError::Cancelled.to_string(), "cancelled");
    /// ```
    #[error("cancelled")]
    Cancelled,
}

impl PathError {
    /// The same error with `prefix.` in front of a field's path (see [`FieldError::within`]).
    pub fn within(self, prefix: &str) -> Self {
        match self {
            PathError::Job(JobError::Field(e)) => e.within(prefix).into(),
            other => other,
        }
    }
}

impl From<FieldError> for PathError {
    fn from(e: FieldError) -> Self {
        PathError::Job(JobError::Field(e))
    }
}
