//! The tool of a job (`tool`): the diamond's nose radius and included angle, which the
//! compensation uses ([`crate::tool`]), and its rake and front clearance angles, which the tool
//! geometry check uses ([`crate::tool::geometry`], paper 000 "Optimization of tool geometry"),
//! and optionally the measured deviation of its edge from the circle ([`WavinessSpec`], used by
//! the one-way compensation and the predicted form through [`crate::tool::waviness`]).

use crate::field::{FieldError, in_range};
use serde::{Deserialize, Serialize};

/// The tool of a job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolSpec {
    /// Nose radius r, mm, ≥ 0 (0: a sharp tool, the tip follows the sag).
    pub nose_radius_mm: f64,
    /// Included angle β of the nose arc, degrees, in (0, 180]; default 100°. The arc reaches
    /// β/2 either side of the tool axis (−Z).
    #[serde(default = "default_included_angle")]
    pub included_angle_deg: f64,
    /// Rake angle γ, degrees, in [−80, 80]; default 0° (a zero-rake diamond). Used by the tool
    /// geometry check ([`crate::tool::geometry`]), not by the compensation.
    #[serde(default)]
    pub rake_deg: f64,
    /// Front clearance angle α, degrees, in [0, 80]; default 10°. Used by the tool geometry
    /// check, not by the compensation.
    #[serde(default = "default_clearance")]
    pub clearance_deg: f64,
    /// The nose's measured deviation from its circle, as tool makers and nose interferometers
    /// give it; absent, the edge is the circle of radius `nose_radius_mm`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub waviness: Option<WavinessSpec>,
}

/// The measured edge of a round nose (`tool.waviness`): its radius at nose angle a is
/// `r(a) = nose_radius_mm + δ(a)`, δ read from the table (see [`crate::tool::waviness`] for the
/// interpolation and the checks).
///
/// The angle is measured in the radial plane from the tool axis (−Z, the tip: a = 0), positive
/// towards larger radius (the part's rim, +X for a tool cutting at X ≥ 0), as the one-way
/// compensation's contact angle is; δ is positive where the edge lies outside the circle (a
/// larger radius there).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WavinessSpec {
    /// Nose angles a, degrees, strictly increasing, covering the arc ±β/2
    /// (`tool.included_angle_deg`); 2 … 10 000 of them.
    pub angle_deg: Vec<f64>,
    /// Radial deviation δ at each angle, µm; |δ| at most 5 % of the nose radius.
    pub deviation_um: Vec<f64>,
}

fn default_included_angle() -> f64 {
    100.0
}

fn default_clearance() -> f64 {
    ToolAngles::default().clearance_deg
}

impl ToolSpec {
    /// A tool of nose radius `r` mm and the default angles (included 100°, rake 0°, clearance
    /// 10°).
    pub fn with_nose_radius(r: f64) -> Self {
        Self {
            nose_radius_mm: r,
            included_angle_deg: default_included_angle(),
            rake_deg: 0.0,
            clearance_deg: default_clearance(),
            waviness: None,
        }
    }

    /// The rake and clearance angles, checked (field names relative to the tool).
    pub fn angles(&self) -> Result<ToolAngles, FieldError> {
        Ok(ToolAngles {
            rake_deg: in_range("rake_deg", self.rake_deg, -80.0, 80.0)?,
            clearance_deg: in_range("clearance_deg", self.clearance_deg, 0.0, 80.0)?,
        })
    }
}

/// The rake and front clearance angles of the tool, degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ToolAngles {
    /// Rake angle γ, degrees; default 0° (a zero-rake diamond, the usual tool for optics).
    pub rake_deg: f64,
    /// Front clearance angle α, degrees; default 10°, typical of single-crystal diamond tools
    /// (manufacturers make up to about 30°, paper 000).
    pub clearance_deg: f64,
}

impl Default for ToolAngles {
    fn default() -> Self {
        Self {
            rake_deg: 0.0,
            clearance_deg: 10.0,
        }
    }
}

impl ToolAngles {
    /// The effective angles with the holder tilted by `lambda_deg` away from the workpiece:
    /// clearance `α + λ`, rake `γ − λ`.
    pub fn tilted(&self, lambda_deg: f64) -> Self {
        Self {
            rake_deg: self.rake_deg - lambda_deg,
            clearance_deg: self.clearance_deg + lambda_deg,
        }
    }
}
