//! spiralcam: spiral tool paths for ultraprecision single-point diamond turning of freeform
//! optical surfaces with a slow slide servo (SSS) or a fast tool servo (FTS).
//!
//! The pipeline (DESIGN.md): a [`job::Job`] names a [`surface::Surface`], the
//! [`spiral`] sampler lays (ρ, θ) points from the outer radius to the centre, the
//! [`compensate`] stage lifts each point so that the round tool nose touches the surface without
//! cutting into it (paper 003 eqs 17–24, solved as a maximum), [`reach`] reports where the nose
//! cannot reach the surface, and the [`nc`] writers turn the points into NC programs and CSV.
//! [`plan`] runs the whole chain as a stream, so memory does not grow with the point count.
//! With machine limits or a split, [`dynamics`] first analyses the planned path in memory
//! ([`spectrum`], [`split`], [`axis_checks`]; paper 000's FFT/Hilbert splitting) and the
//! program is written with the slide's Z and the fast tool servo's W.

pub mod analysis;
pub mod axis_checks;
pub mod compensate;
pub mod data_file;
pub mod display;
pub mod dynamics;
pub mod field;
pub mod hcaa;
pub mod job;
pub mod linearization;
pub mod machine;
pub mod nc;
pub mod path_signal;
pub mod plan;
pub mod power_map;
pub mod predicted_form;
pub mod raster;
pub mod reach;
pub mod report;
pub mod space_spiral;
pub mod spectrum;
pub mod spiral;
pub mod split;
pub mod surface;
pub mod tool_geometry;
