//! Interpolation of scattered data for [`super::Scattered`] (paper 004): the data text
//! ([`data`]), its convex hull ([`hull`]), nearest neighbours from a kd-tree and where they
//! change along a line ([`neighbours`], [`kinetic`]), and the four interpolators the paper
//! compares: its radial basis function (eqs 4–6, [`rbf`]), Shepard's inverse distance weighting
//! ([`shepard`], derivatives by [`jet`](crate::surface::jet)s), the four-point mean
//! ([`four_point`]) and Hermite (bicubic) interpolation ([`hermite`]); [`cache`] keeps
//! per-thread work the planner reuses, among it the RBF's section along the last line asked
//! about as the cubics it is between kinks ([`line_section`]).

pub mod cache;
pub mod data;
pub mod four_point;
pub mod hermite;
pub mod hull;
pub mod kinetic;
pub mod line_section;
pub mod neighbours;
pub mod rbf;
pub mod shepard;
