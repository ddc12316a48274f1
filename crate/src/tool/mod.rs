//! The tool layer: where the round diamond nose meets the surface. It uses the path, the job,
//! the surface and the helpers below it.
//!
//! - [`one_way`]: one-way nose radius compensation (paper 003, eqs 17–24), X on the spiral and
//!   Z lifted to the maximum over the nose arc, gouge-free by construction;
//! - [`two_way`]: two-way compensation, the nose centre on the surface normal;
//! - [`reach`]: the zones the nose cannot reach (concave with a curvature radius below r);
//! - [`geometry`]: the critical rake, clearance and included angles and the holder tilt
//!   (paper 000, "Optimization of tool geometry");
//! - [`waviness`]: the measured edge `tool.waviness`, r(a) = r + δ(a) (PCHIP between the
//!   table's angles), used by the one-way compensation, the concave zones and the predicted form;
//! - [`tool_path`]: a job's surface, spiral and compensator together, streaming the commanded
//!   points that every stage above reads.

pub mod geometry;
pub mod one_way;
pub mod reach;
pub mod tool_path;
pub mod two_way;
pub mod waviness;

pub use one_way::{Concavity, Contact, ContactTrail, NoseCompensator, WarmStart};
pub use tool_path::{Batched, Probe, ToolPath, Walked, spiral};
pub use two_way::{TwoWay, max_principal_curvature};
pub use waviness::Waviness;
