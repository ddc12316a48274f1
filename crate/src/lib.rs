//! spiralcam: spiral tool paths for ultraprecision single-point diamond turning of freeform
//! optical surfaces with a slow slide servo (SSS) or a fast tool servo (FTS).
//!
//! The crate's folders are its layers; each uses only the ones listed below it, never one
//! above, and a test (`crate/tests/layers.rs`) keeps it so. Read it top-down:
//!
//! | layer | what it holds |
//! |---|---|
//! | [`plan`] | the pipeline: a job admitted (its cost against the limits), then streamed through every layer into NC, CSV and the report |
//! | [`report`], [`display`] | the plan's report and checks; what the page draws |
//! | [`analysis`], [`dynamics`] | accuracy (linearization, predicted form, power map); machine dynamics (spectrum, split, axis checks) |
//! | [`nc`] | the NC writers (three dialects), the CSV and the servo's table |
//! | [`tool`] | nose compensation (one-way, two-way), concave zones, tool geometry, the tool path |
//! | [`path`] | the path's points and places; the spiral samplers (constant angle/arc, HCAA, space spiral) |
//! | [`job`] | the job document: spec types, defaults, validation |
//! | [`surface`] | every surface family with sag, gradient and Hessian; the data files they read |
//! | [`field`], [`progress`], [`parallel`], [`raster`], [`rounding`] | helpers: field errors, progress, threads, maps, rounding without libm |
//!
//! A job's way through them: JSON → [`job::Job`] → [`surface::Surface`] → the spiral
//! ([`path::spiral`], [`path::hcaa`], [`path::space_spiral`]) → the nose compensation
//! ([`tool::NoseCompensator`], paper 003 eqs 17–24 solved as a maximum) giving the
//! [`tool::ToolPath`] → with a split or machine limits the [`dynamics`] (paper 000's FFT/Hilbert
//! splitting) → the [`nc`] writers → files; [`analysis`] reads the same tool path for the
//! accuracy report. [`plan::Planner`] runs the chain as a stream, so memory does not grow with
//! the point count.

pub mod analysis;
pub mod display;
pub mod dynamics;
pub mod field;
pub mod job;
pub mod nc;
pub mod parallel;
pub mod path;
pub mod plan;
pub mod progress;
pub mod raster;
pub mod report;
pub mod rounding;
pub mod surface;
pub mod tool;
