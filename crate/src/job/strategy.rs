//! How the path is laid (`strategy`): the feed, the sampling of points along the spiral
//! ([`crate::path`]), the sense of rotation, the compensation of the nose ([`crate::tool`]) and the
//! split between the slide and a fast tool servo
//! ([`crate::dynamics::split`](mod@crate::dynamics::split)). The samplers check their own fields
//! when they build the spiral.

use serde::{Deserialize, Serialize};

/// How the spiral is laid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrategySpec {
    /// Radial feed per revolution f, mm, > 0.
    pub feed_mm_per_rev: f64,
    /// Point spacing along the spiral.
    pub sampling: Sampling,
    /// Sense of θ along the path; default `ccw`.
    #[serde(default)]
    pub direction: Direction,
    /// Polar angle of the first point, degrees, in [−360, 360]; default 0.
    #[serde(default)]
    pub start_angle_deg: f64,
    /// Radius where the spiral starts, mm; default the part radius.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_radius_mm: Option<f64>,
    /// How far outside that radius the spiral starts, mm, ≥ 0 (at most the part's radius);
    /// default 0. Beyond the edge with no material (`part.beyond_edge: none`) the nose's arc
    /// rests on the design's continuation at its inner end: the tool is in the air there.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub overtravel_mm: f64,
    /// Tool nose compensation, `one_way` (default) or `two_way`
    /// ([`crate::job::Compensation`]).
    #[serde(default, skip_serializing_if = "Compensation::is_one_way")]
    pub compensation: Compensation,
    /// The split of the path between the Z slide and a fast tool servo
    /// ([`crate::job::SplitSpec`]); absent: the slide cuts alone.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub split: Option<SplitSpec>,
}

/// How points are spaced along the spiral.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum Sampling {
    /// Equal angle steps: `points_per_rev` points per revolution (paper 003 eq 21).
    ConstantAngle {
        /// Points per revolution N, 3 … 1 000 000.
        points_per_rev: u32,
    },
    /// Equal arc length along the planar spiral, the angle step capped near the centre.
    ConstantArc {
        /// Arc length ΔS between points, mm, at least 1e-6 (1 nm).
        arc_length_mm: f64,
        /// Largest angle step, degrees, in [0.00036, 90] (360° / 10⁶ at the finest); default 1°.
        #[serde(default = "default_max_angle_step")]
        max_angle_step_deg: f64,
    },
    /// Hybrid constant-angle / constant-arc sampling (paper 000, "HCAA method"): constant angle
    /// outside the first transition radius, constant arc between the two, constant angle inside
    /// the second, each step the largest that holds the tolerance, chosen from the surface's
    /// curvature along the cut ([`crate::path::hcaa`]).
    Hcaa {
        /// Linearization error allowed, PVerr, µm, in [0.001, 1000].
        pv_tolerance_um: f64,
    },
    /// Constant angle step per radius band (about one feed wide, at most 512 bands), each the
    /// largest that holds the tolerance in that band ([`crate::path::hcaa`]).
    Adaptive {
        /// Linearization error allowed, PVerr, µm, in [0.001, 1000].
        pv_tolerance_um: f64,
    },
    /// The space Archimedean spiral (paper 001, [`crate::path::space_spiral`]): passes `f` apart
    /// along the meridian of a best-fit surface of revolution, `points_per_rev` points per
    /// revolution at constant angle, projected onto the design surface along the base normal; the
    /// XY of the projected points are the spiral points. Built by
    /// [`crate::path::space_spiral::spiral`] and held in memory (16 bytes a point, at most
    /// [`crate::path::spiral::MAX_EXPLICIT_POINTS`]).
    SpaceSpiral {
        /// Points per revolution N, 3 … 1 000 000.
        points_per_rev: u32,
        /// Uniform knot spans of the base generating curve, 1 … 64; default 8.
        #[serde(default = "default_base_spans")]
        base_spans: u32,
    },
}

fn default_base_spans() -> u32 {
    8
}

fn default_max_angle_step() -> f64 {
    1.0
}

/// Sense in which the polar angle θ on the part advances along the path, seen from +Z.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// θ increases (counter-clockwise).
    #[default]
    Ccw,
    /// θ decreases (clockwise).
    Cw,
}

impl Direction {
    /// +1 for counter-clockwise, −1 for clockwise.
    pub fn sign(self) -> f64 {
        match self {
            Direction::Ccw => 1.0,
            Direction::Cw => -1.0,
        }
    }
}

/// How the nose is placed on the surface: the job's `strategy.compensation`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Compensation {
    /// X stays on the spiral; Z is lifted until the nose touches (paper 003 eqs 17–24).
    #[default]
    OneWay,
    /// The spiral point is the contact; the nose centre lies on its surface normal, X and C
    /// follow the centre (see the module docs).
    TwoWay,
}

impl Compensation {
    /// Whether this is the default, one-way compensation.
    pub fn is_one_way(&self) -> bool {
        *self == Compensation::OneWay
    }
}

/// How the path is split between the slide (Z) and the FTS (W): the job's `strategy.split`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum SplitSpec {
    /// Z the rotationally symmetric part, W the residual (paper 002).
    #[default]
    Symmetric,
    /// Z the zero-phase low-pass of z at `cutoff_hz`, W the rest (paper 000).
    LowPass {
        /// Cutoff frequency (half amplitude), Hz, in (0, the path's Nyquist frequency].
        cutoff_hz: f64,
    },
    /// The slide alone if it can, else the lowest cutoff at which W fits the FTS stroke.
    Auto,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}
