//! Spiral sampling from the outer radius to the centre: `ρ(θ) = R − f·(θ − θ₀)/2π` (paper 003
//! eq 18, paper 000 "spiral point P"), at constant angle (paper 003 eqs 21–22: N points per
//! revolution, equal time steps at constant spindle speed) or at constant arc length ΔS along the
//! planar spiral with a cap on the angle step near the centre.
//!
//! Constant angle: the path has K = ⌈N·R/f⌉ steps and starts at `R′ = K·f/N`, at most one angle
//! step outside R, so that every step is exactly 2π/N, the radial pitch is exactly f per
//! revolution and the last point lies exactly at ρ = 0. Point k is computed from k alone, never
//! by accumulation.
//!
//! Constant arc: with `b = f/2π` the spiral is `ρ = b·φ` and its arc length from the centre is
//! `S(φ) = (b/2)·(φ√(1+φ²) + asinh φ)` (closed form of `∫ b√(1+t²) dt`). Each step solves
//! `S(φ_k) − S(φ_{k+1}) = ΔS` by Newton's method, then takes the smaller of that angle step and
//! the cap; the last step ends exactly at the centre and may be shorter.
//!
//! Hybrid (HCAA, paper 000) and adaptive sampling depend on the surface: [`crate::path::hcaa`]
//! turns the PV tolerance into [`Zone`]s (radius bands, each with a constant angle step or a
//! constant arc length) and builds the spiral with [`Spiral::with_zones`]. Within a zone the step
//! rule is that of the plain sampling; a step that would end in a zone further in takes the smaller
//! of the two zones' steps, so every segment obeys the rule of each zone it touches. The path
//! starts at the outer radius and its last step ends exactly at the centre.
//!
//! [`crate::tool::spiral`] picks the builder of each sampling: [`Spiral::new`],
//! [`crate::path::hcaa::spiral`] or [`crate::path::space_spiral::spiral`].

use crate::field::{FieldError, feed_within, in_range, length, positive};
use crate::job::{Direction, Sampling};
use crate::rounding;
use std::f64::consts::TAU;
use std::sync::Arc;

/// The most points of a spiral held in memory ([`Spiral::from_points`]): 2·10⁷, 320 MB.
pub const MAX_EXPLICIT_POINTS: u64 = 20_000_000;

/// Smallest PV tolerance of the surface-dependent samplings, µm.
pub const MIN_PV_TOLERANCE_UM: f64 = 0.001;
/// Largest PV tolerance of the surface-dependent samplings, µm.
pub const MAX_PV_TOLERANCE_UM: f64 = 1000.0;

/// The step rule of one [`Zone`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Step {
    /// Constant angle step, radians, in (0, π].
    Angle {
        /// Δθ, radians.
        step_rad: f64,
    },
    /// Constant arc length along the planar spiral, the angle step capped.
    Arc {
        /// ΔS, mm, > 0.
        arc_length_mm: f64,
        /// Largest Δθ, radians, in (0, π].
        max_step_rad: f64,
    },
}

/// A radius band of a zoned spiral: from the previous zone's inner radius (the outer radius for
/// the first) down to `inner_radius_mm`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Zone {
    /// Inner radius of the band, mm, ≥ 0; the last zone's is 0.
    pub inner_radius_mm: f64,
    /// How points are spaced in it.
    pub step: Step,
}

impl Step {
    /// The angle step from `φ = ρ/b` inward.
    fn at(self, b: f64, phi: f64) -> f64 {
        match self {
            Step::Angle { step_rad } => step_rad,
            Step::Arc {
                arc_length_mm,
                max_step_rad,
            } => arc_step(b, phi, arc_length_mm).min(max_step_rad),
        }
    }

    /// Steps over `φ ∈ [lo, hi]` (an estimate for arc steps).
    pub(crate) fn count(self, b: f64, lo: f64, hi: f64) -> f64 {
        match self {
            Step::Angle { step_rad } => (hi - lo) / step_rad,
            Step::Arc {
                arc_length_mm,
                max_step_rad,
            } => {
                // Inside φ_c the cap binds: ds/(b√(1+φ²)) = cap.
                let r = arc_length_mm / (b * max_step_rad);
                let phi_c = (r * r - 1.0).max(0.0).sqrt().clamp(lo, hi);
                (arc_length(b, hi) - arc_length(b, phi_c)) / arc_length_mm
                    + (phi_c - lo) / max_step_rad
            }
        }
    }
}

/// One sample of the spiral: polar radius and the cumulative (unwrapped) polar angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpiralPoint {
    /// ρ, mm, ≥ 0.
    pub rho: f64,
    /// θ, radians, cumulative from the start angle (not wrapped).
    pub theta: f64,
}

/// The points of a spiral whose points are a function of their index k = 0 … K, the same
/// bits as [`SpiralPoints`] gives them: a constant-angle spiral's by the one expression the
/// iterator computes them by, a spiral given as a list ([`Spiral::from_points`]) from the list
/// it holds. The dynamics read a path's angles and radii from it instead of holding them
/// ([`crate::dynamics::path_signal::PathSignal`]).
#[derive(Debug, Clone, PartialEq)]
pub struct IndexedPoints(Indexed);

#[derive(Debug, Clone, PartialEq)]
enum Indexed {
    Angle(AngleRule),
    Listed(Arc<[SpiralPoint]>),
}

impl IndexedPoints {
    /// Point `k` (at most [`Self::last`]).
    #[inline]
    pub fn at(&self, k: u64) -> SpiralPoint {
        match &self.0 {
            Indexed::Angle(rule) => rule.at(k),
            Indexed::Listed(points) => points[(k as usize).min(points.len() - 1)],
        }
    }

    /// The index of the last point, K (at the centre).
    pub fn last(&self) -> u64 {
        match &self.0 {
            Indexed::Angle(rule) => rule.steps,
            Indexed::Listed(points) => points.len() as u64 - 1,
        }
    }
}

/// Point k of a constant-angle spiral: `ρ = (K − k)·f/N`, `θ = θ₀ ± 2π·k/N`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct AngleRule {
    theta0: f64,
    sign: f64,
    feed: f64,
    per_rev: f64,
    steps: u64,
}

impl AngleRule {
    #[inline]
    fn at(&self, k: u64) -> SpiralPoint {
        let remaining = self.steps.saturating_sub(k) as f64;
        SpiralPoint {
            rho: remaining * self.feed / self.per_rev,
            theta: self.theta0 + self.sign * TAU * (k as f64) / self.per_rev,
        }
    }
}

/// The point at φ of a spiral walked by its step rule (constant arc, HCAA, adaptive): the
/// planar spiral `ρ = b·φ`, `θ = θ₀ ± (φ₀ − φ)`, φ falling from `φ₀ = R/b` at the rim to 0,
/// the one expression [`SpiralPoints`] computes those points by. A point of such a spiral is
/// not a function of its index (its φ comes from walking the rule from the rim), but its φ can
/// be recovered from it ([`Self::phi_of`]): the dynamics hold that one number a point instead
/// of θ and ρ ([`crate::dynamics::path_signal::PathSignal`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WalkedRule {
    b: f64,
    phi0: f64,
    theta0: f64,
    sign: f64,
}

impl WalkedRule {
    /// The spiral's point at `phi`.
    #[inline]
    pub fn at(&self, phi: f64) -> SpiralPoint {
        SpiralPoint {
            rho: self.b * phi,
            theta: self.theta0 + self.sign * (self.phi0 - phi),
        }
    }

    /// A φ whose point [`Self::at`] is `(theta, rho)` to the bit, if there is one: a point of
    /// the spiral has `ρ = fl(b·φ)`, so its φ lies within two units in the last place of
    /// `ρ/b`, and the seven values from three below to three above are tried.
    pub fn phi_of(&self, theta: f64, rho: f64) -> Option<f64> {
        let guess = (rho / self.b).to_bits();
        [0, -1, 1, -2, 2, -3, 3]
            .into_iter()
            .map(|d| f64::from_bits(guess.wrapping_add_signed(d)))
            .find(|&phi| {
                let p = self.at(phi);
                phi >= 0.0
                    && p.rho.to_bits() == rho.to_bits()
                    && p.theta.to_bits() == theta.to_bits()
            })
    }
}

/// A validated spiral.
#[derive(Debug, Clone, PartialEq)]
pub struct Spiral {
    outer_radius: f64,
    feed: f64,
    sampling: Sampling,
    sign: f64,
    theta0: f64,
    zones: Vec<Zone>,
    /// The points of a spiral built from a list ([`Spiral::from_points`]), shared by its
    /// iterators.
    explicit: Option<Arc<[SpiralPoint]>>,
}

/// The most points per revolution.
pub const MAX_POINTS_PER_REV: u32 = 1_000_000;
/// The longest turn whose directions are tabulated ([`Spiral::turn_directions`]): 1 MiB.
pub const MAX_TABULATED_DIRECTIONS: usize = 65_536;
/// The most points on a path: 10⁹, three times the largest path of paper 000 (303 million
/// points before HCAA); more is a mistake in the feed or the sampling, not a job.
pub const MAX_POINTS: u64 = 1_000_000_000;

/// The outer radius and feed (both > 0) and the start angle in radians, checked.
fn checked_geometry(
    outer_radius_mm: f64,
    feed_mm_per_rev: f64,
    start_angle_deg: f64,
) -> Result<(f64, f64, f64), FieldError> {
    let outer = positive("outer_radius_mm", outer_radius_mm)?;
    let feed = positive("feed_mm_per_rev", feed_mm_per_rev)?;
    if feed > outer {
        return Err(FieldError::new(
            "feed_mm_per_rev",
            feed,
            format!(
                "must be at most the radius the spiral starts at, {} mm: the path would not make \
                 one turn",
                crate::field::short(outer)
            ),
        ));
    }
    Ok((
        outer,
        feed,
        in_range("start_angle_deg", start_angle_deg, -360.0, 360.0)?.to_radians(),
    ))
}

impl Spiral {
    /// Checks the parameters (`field` prefixes name them as in the job) and builds the spiral.
    pub fn new(
        outer_radius_mm: f64,
        feed_mm_per_rev: f64,
        sampling: &Sampling,
        direction: Direction,
        start_angle_deg: f64,
    ) -> Result<Self, FieldError> {
        let (outer_radius, feed, theta0) =
            checked_geometry(outer_radius_mm, feed_mm_per_rev, start_angle_deg)?;
        match *sampling {
            Sampling::ConstantAngle { points_per_rev } => {
                check_points_per_rev(points_per_rev)?;
            }
            Sampling::ConstantArc {
                arc_length_mm,
                max_angle_step_deg,
            } => {
                length("sampling.arc_length_mm", arc_length_mm)?;
                // The finest cap is the finest constant-angle step, 360° / 10⁶.
                let finest = 360.0 / MAX_POINTS_PER_REV as f64;
                in_range(
                    "sampling.max_angle_step_deg",
                    max_angle_step_deg,
                    finest,
                    90.0,
                )?;
            }
            Sampling::Hcaa { pv_tolerance_um } | Sampling::Adaptive { pv_tolerance_um } => {
                check_tolerance(pv_tolerance_um)?;
                return Err(surface_dependent("hcaa/adaptive"));
            }
            Sampling::SpaceSpiral { .. } => return Err(surface_dependent("space_spiral")),
        }
        Self::planar(
            (outer_radius, feed, theta0),
            sampling,
            direction,
            Vec::new(),
        )
    }

    /// A spiral through the given points (outside in; `theta` cumulative, already including the
    /// start angle and direction), labelled with the `sampling` they were made by. The list is
    /// held: 16 bytes a point, at most [`MAX_EXPLICIT_POINTS`]. The last point must be at the
    /// centre (ρ = 0) and every point finite with ρ ≥ 0.
    pub fn from_points(
        feed_mm_per_rev: f64,
        sampling: &Sampling,
        points: Vec<SpiralPoint>,
    ) -> Result<Self, FieldError> {
        let feed = positive("feed_mm_per_rev", feed_mm_per_rev)?;
        if points.len() as u64 > MAX_EXPLICIT_POINTS {
            return Err(FieldError::new(
                "sampling.points",
                points.len(),
                format!("at most {MAX_EXPLICIT_POINTS} points are held in memory"),
            ));
        }
        if let Some((i, p)) = points
            .iter()
            .enumerate()
            .find(|(_, p)| !(p.rho.is_finite() && p.rho >= 0.0 && p.theta.is_finite()))
        {
            return Err(FieldError::new(
                "sampling.points",
                format!("point {i} (rho {}, theta {})", p.rho, p.theta),
                "must be finite with rho >= 0",
            ));
        }
        let (Some(first), Some(last)) = (points.first(), points.last()) else {
            return Err(FieldError::new("sampling.points", 0, "at least one point"));
        };
        if last.rho != 0.0 {
            return Err(FieldError::new(
                "sampling.points",
                format!("last rho {}", last.rho),
                "the last point must be at the centre (rho = 0)",
            ));
        }
        let sign = if last.theta >= first.theta { 1.0 } else { -1.0 };
        Ok(Self {
            outer_radius: first.rho,
            feed,
            sampling: sampling.clone(),
            sign,
            theta0: first.theta,
            zones: Vec::new(),
            explicit: Some(points.into()),
        })
    }

    /// A spiral whose steps follow `zones` (outside in; see the module docs), labelled with the
    /// surface-dependent `sampling` they were derived from. Zones with an inner radius at or
    /// above the outer radius are skipped; the last zone is taken down to the centre.
    pub fn with_zones(
        outer_radius_mm: f64,
        feed_mm_per_rev: f64,
        sampling: &Sampling,
        zones: &[Zone],
        direction: Direction,
        start_angle_deg: f64,
    ) -> Result<Self, FieldError> {
        let (outer_radius, feed, theta0) =
            checked_geometry(outer_radius_mm, feed_mm_per_rev, start_angle_deg)?;
        if let Sampling::Hcaa { pv_tolerance_um } | Sampling::Adaptive { pv_tolerance_um } =
            *sampling
        {
            check_tolerance(pv_tolerance_um)?;
        }
        let mut kept: Vec<Zone> = Vec::with_capacity(zones.len());
        for z in zones {
            let bad = |what: &str, v: f64| {
                Err(FieldError::new(
                    format!("sampling.zones.{what}"),
                    v,
                    "must be > 0 and finite (angles at most π)",
                ))
            };
            match z.step {
                Step::Angle { step_rad }
                    if !(step_rad > 0.0 && step_rad <= std::f64::consts::PI) =>
                {
                    return bad("step_rad", step_rad);
                }
                Step::Arc { arc_length_mm, .. }
                    if !(arc_length_mm > 0.0 && arc_length_mm.is_finite()) =>
                {
                    return bad("arc_length_mm", arc_length_mm);
                }
                Step::Arc { max_step_rad, .. }
                    if !(max_step_rad > 0.0 && max_step_rad <= std::f64::consts::PI) =>
                {
                    return bad("max_step_rad", max_step_rad);
                }
                _ => {}
            }
            if z.inner_radius_mm < outer_radius
                && kept
                    .last()
                    .is_none_or(|k| z.inner_radius_mm < k.inner_radius_mm)
            {
                kept.push(*z);
            }
        }
        match kept.last_mut() {
            Some(last) => last.inner_radius_mm = 0.0,
            None => {
                return Err(FieldError::new(
                    "sampling.zones",
                    zones.len(),
                    "at least one zone inside the outer radius",
                ));
            }
        }
        Self::planar((outer_radius, feed, theta0), sampling, direction, kept)
    }

    /// The zones of a surface-dependent spiral (empty for constant angle and constant arc).
    pub fn zones(&self) -> &[Zone] {
        &self.zones
    }

    /// A spiral computed from its parameters (not [`Spiral::from_points`]), from the checked
    /// geometry of [`checked_geometry`]; refused above [`MAX_POINTS`].
    fn planar(
        (outer_radius, feed, theta0): (f64, f64, f64),
        sampling: &Sampling,
        direction: Direction,
        zones: Vec<Zone>,
    ) -> Result<Self, FieldError> {
        let spiral = Self {
            outer_radius,
            feed,
            sampling: sampling.clone(),
            sign: direction.sign(),
            theta0,
            zones,
            explicit: None,
        };
        let points = spiral.point_count_estimate();
        if points.is_nan() || points > MAX_POINTS as f64 {
            // The count goes as 1/f for every sampling: the feed that keeps it under the cap,
            // from the count at a feed of the part's radius where this one overflows.
            let (f, n) = match points.is_finite() {
                true => (feed, points),
                false => {
                    let wide = Self {
                        feed: outer_radius,
                        ..spiral.clone()
                    };
                    (outer_radius, wide.point_count_estimate())
                }
            };
            let least = feed_within(f, n / MAX_POINTS as f64);
            if !least.is_finite() {
                // No feed helps (the steps are bounded below: not met by a checked sampling).
                return Err(FieldError::new(
                    "sampling",
                    "its steps",
                    "give more points than can be counted, whatever the feed",
                ));
            }
            return Err(FieldError::new(
                "feed_mm_per_rev",
                feed,
                format!(
                    "gives {} with this sampling; at most {MAX_POINTS:.0e} are planned: a feed of \
                     at least {} mm/rev keeps this part under the limit",
                    match points.is_finite() {
                        true => format!("about {} points", crate::field::short(points)),
                        false => "more points than can be counted".to_string(),
                    },
                    crate::field::short(least),
                ),
            ));
        }
        Ok(spiral)
    }

    /// The radius of the first point, mm (≥ the outer radius asked for; see the module docs).
    pub fn start_radius_mm(&self) -> f64 {
        match self.sampling {
            Sampling::ConstantAngle { points_per_rev } => {
                self.angle_steps(points_per_rev) as f64 * self.feed / points_per_rev as f64
            }
            _ => self.outer_radius,
        }
    }

    /// Feed per revolution, mm.
    pub fn feed_mm(&self) -> f64 {
        self.feed
    }

    /// Number of revolutions from the start to the centre.
    pub fn revolutions(&self) -> f64 {
        match &self.explicit {
            Some(p) => (p[p.len() - 1].theta - p[0].theta).abs() / TAU,
            None => self.start_radius_mm() / self.feed,
        }
    }

    /// `(sin θ, cos θ)` of a point's angle θ. On a constant-angle spiral, from the angle reduced
    /// to its turn, `θ₀ ± 2π·(k mod N)/N` (k the point's step, recovered from θ): the points of
    /// one angle share their radial direction to the bit on every turn (so that work along a
    /// section can be kept from one turn to the next, [`crate::surface::scattered`]), and the
    /// cumulative angle's rounding (about 2·10⁻¹³ rad after 250 turns) is left out.
    pub fn sin_cos(&self, theta: f64) -> (f64, f64) {
        self.sin_cos_from(&[], theta)
    }

    /// [`Spiral::sin_cos`], read from `table` (this spiral's [`Spiral::turn_directions`]) where
    /// it has the point's step: the same bits without a sine and cosine a point.
    pub fn sin_cos_from(&self, table: &[(f64, f64)], theta: f64) -> (f64, f64) {
        match self.step_in_turn(theta) {
            Some((step, _)) if step < table.len() => table[step],
            Some((step, n)) => self.step_sin_cos(step, n),
            None => theta.sin_cos(),
        }
    }

    /// On a constant-angle spiral, the step k mod N of its turn's N angles of the point at
    /// `theta` (the points of one step share their radial line on every turn); `None` on any
    /// other spiral.
    pub fn turn_step(&self, theta: f64) -> Option<usize> {
        self.step_in_turn(theta).map(|(step, _)| step)
    }

    /// On a constant-angle spiral of N points a turn, the step k mod N of the point at `theta`
    /// and N; `None` on any other.
    fn step_in_turn(&self, theta: f64) -> Option<(usize, usize)> {
        let points_per_rev = self.turn_points()?;
        let n = points_per_rev as f64;
        // k is a whole number far below 2⁵³ (at most MAX_POINTS steps), θ within rounding of
        // its angle: rounded without a library call, its remainder in integers is the float
        // remainder's, without a software fmod.
        let k = rounding::nearest(self.sign * (theta - self.theta0) * (n / TAU)) as i64;
        let step = k.rem_euclid(i64::from(points_per_rev));
        Some((step as usize, points_per_rev as usize))
    }

    /// N, the points of a turn, on a constant-angle spiral (not one given as a list); `None`
    /// on any other.
    pub fn turn_points(&self) -> Option<u32> {
        match self.sampling {
            Sampling::ConstantAngle { points_per_rev } if self.explicit.is_none() => {
                Some(points_per_rev)
            }
            _ => None,
        }
    }

    /// The points by their index, on a constant-angle spiral or one given as a list; `None` on
    /// any other, whose points are found by walking the step rule.
    pub fn indexed_points(&self) -> Option<IndexedPoints> {
        if let Some(points) = &self.explicit {
            return Some(IndexedPoints(Indexed::Listed(points.clone())));
        }
        let n = self.turn_points()?;
        Some(IndexedPoints(Indexed::Angle(AngleRule {
            theta0: self.theta0,
            sign: self.sign,
            feed: self.feed,
            per_rev: n as f64,
            steps: self.angle_steps(n),
        })))
    }

    /// The rule of a spiral walked by its step rule on the plane (constant arc, HCAA,
    /// adaptive), whose points are found by walking but follow from their φ; `None` for a
    /// constant-angle spiral, one given as a list, and a space spiral (its points are moved
    /// onto the surface).
    pub fn walked_rule(&self) -> Option<WalkedRule> {
        match self.sampling {
            _ if self.explicit.is_some() => None,
            Sampling::ConstantArc { .. } | Sampling::Hcaa { .. } | Sampling::Adaptive { .. } => {
                let b = self.feed / TAU;
                Some(WalkedRule {
                    b,
                    phi0: self.outer_radius / b,
                    theta0: self.theta0,
                    sign: self.sign,
                })
            }
            _ => None,
        }
    }

    /// (sin, cos) of the `step`-th of `n` angles of a turn from the start angle.
    fn step_sin_cos(&self, step: usize, n: usize) -> (f64, f64) {
        (self.theta0 + self.sign * TAU * step as f64 / n as f64).sin_cos()
    }

    /// The (sin, cos) of every angle of a constant-angle turn of at most
    /// [`MAX_TABULATED_DIRECTIONS`] points, in step order, for [`Spiral::sin_cos_from`]; empty
    /// for any other spiral.
    pub fn turn_directions(&self) -> Vec<(f64, f64)> {
        match self.turn_points().map(|n| n as usize) {
            Some(n) if n <= MAX_TABULATED_DIRECTIONS => {
                (0..n).map(|step| self.step_sin_cos(step, n)).collect()
            }
            _ => Vec::new(),
        }
    }

    /// The angle steps K = ⌈N·R/f⌉ of constant-angle sampling, in floating point.
    fn angle_steps_exact(&self, n: u32) -> f64 {
        // Guard against N·R/f landing a hair above an integer through rounding.
        let exact = n as f64 * self.outer_radius / self.feed;
        (exact * (1.0 - 4.0 * f64::EPSILON)).ceil().max(1.0)
    }

    /// K as an integer: exact, since a checked spiral has at most [`MAX_POINTS`] points.
    fn angle_steps(&self, n: u32) -> u64 {
        self.angle_steps_exact(n) as u64
    }

    /// The number of points (exact for constant angle, an estimate within a few points for
    /// constant arc), for progress bars; at most `u64::MAX`.
    pub fn point_count_hint(&self) -> u64 {
        // The cast saturates (and NaN gives 0, which no checked spiral has).
        self.point_count_estimate() as u64
    }

    /// The number of points as [`Spiral::point_count_hint`], computed in floating point so that
    /// an absurd feed gives an absurd count (1e19, 1e300) instead of one that wraps.
    pub fn point_count_estimate(&self) -> f64 {
        if let Some(p) = &self.explicit {
            return p.len() as f64;
        }
        match self.sampling {
            Sampling::ConstantAngle { points_per_rev } => {
                self.angle_steps_exact(points_per_rev) + 1.0
            }
            Sampling::ConstantArc {
                arc_length_mm,
                max_angle_step_deg,
            } => {
                let b = self.feed / TAU;
                let cap = max_angle_step_deg.to_radians();
                // Inside ρ_cap the cap binds: the angle steps are `cap`.
                let rho_cap = (arc_length_mm / cap).min(self.outer_radius);
                let arc = arc_length(b, self.outer_radius / b) - arc_length(b, rho_cap / b);
                (arc / arc_length_mm).ceil() + (rho_cap / b / cap).ceil() + 1.0
            }
            Sampling::Hcaa { .. } | Sampling::Adaptive { .. } | Sampling::SpaceSpiral { .. } => {
                let b = self.feed / TAU;
                let mut hi = self.outer_radius / b;
                let mut n = 1.0;
                for z in &self.zones {
                    let lo = z.inner_radius_mm / b;
                    n += z.step.count(b, lo, hi).ceil() + 1.0;
                    hi = lo;
                }
                n
            }
        }
    }

    /// Points from radius `rho` inward, so that a stretch of the path can be looked at without
    /// walking it from the start: for constant-angle and explicit spirals the spiral's own points
    /// from the first at or inside `rho`; for constant-arc and zoned ones the same curve and step
    /// rule from `rho` exactly (the spiral's own points lie within one step of them).
    pub fn points_from(&self, rho: f64) -> SpiralPoints {
        let mut it = self.points();
        let rho = rho.clamp(0.0, self.start_radius_mm());
        match &mut it.state {
            State::Explicit { k } => {
                let points = self.explicit.as_deref().unwrap_or(&[]);
                // Explicit spirals run inward: ρ decreases along them.
                *k = points
                    .partition_point(|p| p.rho > rho)
                    .min(points.len().saturating_sub(1));
            }
            State::Angle { k, steps, n } => {
                let inside = (rho * *n / self.feed).floor() as u64;
                *k = steps.saturating_sub(inside.min(*steps));
            }
            State::Arc { b, phi, .. } | State::Zoned { b, phi, .. } => *phi = (rho / *b).min(*phi),
        }
        it
    }

    /// The points, from the outer radius to the centre, streamed.
    pub fn points(&self) -> SpiralPoints {
        let state = match self.sampling {
            _ if self.explicit.is_some() => State::Explicit { k: 0 },
            Sampling::ConstantAngle { points_per_rev } => State::Angle {
                k: 0,
                steps: self.angle_steps(points_per_rev),
                n: points_per_rev as f64,
            },
            Sampling::ConstantArc {
                arc_length_mm,
                max_angle_step_deg,
            } => {
                let b = self.feed / TAU;
                let phi = self.outer_radius / b;
                State::Arc {
                    b,
                    phi0: phi,
                    phi,
                    ds: arc_length_mm,
                    cap: max_angle_step_deg.to_radians(),
                }
            }
            Sampling::Hcaa { .. } | Sampling::Adaptive { .. } | Sampling::SpaceSpiral { .. } => {
                let b = self.feed / TAU;
                let phi = self.outer_radius / b;
                State::Zoned {
                    b,
                    phi0: phi,
                    phi,
                    zone: 0,
                }
            }
        };
        SpiralPoints {
            spiral: self.clone(),
            state,
            done: false,
        }
    }
}

/// Points per revolution N, checked: 3 … [`MAX_POINTS_PER_REV`].
pub(crate) fn check_points_per_rev(points_per_rev: u32) -> Result<u32, FieldError> {
    if (3..=MAX_POINTS_PER_REV).contains(&points_per_rev) {
        Ok(points_per_rev)
    } else {
        Err(FieldError::new(
            "sampling.points_per_rev",
            points_per_rev,
            format!("must lie in [3, {MAX_POINTS_PER_REV}]"),
        ))
    }
}

/// The refusal of [`Spiral::new`] for a sampling that depends on the surface.
fn surface_dependent(sampling: &str) -> FieldError {
    FieldError::new(
        "sampling.type",
        sampling,
        "depends on the surface: plan it with spiralcam::tool::spiral (the planner does)",
    )
}

fn check_tolerance(pv_tolerance_um: f64) -> Result<f64, FieldError> {
    in_range(
        "sampling.pv_tolerance_um",
        pv_tolerance_um,
        MIN_PV_TOLERANCE_UM,
        MAX_PV_TOLERANCE_UM,
    )
}

/// `S(φ)`: arc length of `ρ = bφ` from the centre to φ.
pub fn arc_length(b: f64, phi: f64) -> f64 {
    0.5 * b * (phi * (1.0 + phi * phi).sqrt() + phi.asinh())
}

/// `S(φ) − S(φ − d)` for `0 ≤ d ≤ φ`: the arc length of `ρ = bφ` over the last d of φ, from
/// d itself, not from the two lengths from the centre (each about `bφ²/2`) and their `asinh`.
/// With `x = φ − d`: `φ√(1+φ²) − x√(1+x²) = d(φ+x)(1+φ²+x²)/(φ√(1+φ²) + x√(1+x²))` and
/// `asinh φ − asinh x = asinh u`, `u = d(φ+x)/(φ√(1+x²) + x√(1+φ²))`, u's series where u is
/// below 10⁻³ (its first term left out is below 10⁻¹⁹ of it). x's rounding moves the result
/// by a relative 10⁻¹⁶ only: the length is d times factors that x enters smoothly.
fn arc_between(b: f64, phi: f64, d: f64) -> f64 {
    if phi <= 0.0 {
        return 0.0;
    }
    let x = phi - d;
    let (sx, sp) = ((1.0 + x * x).sqrt(), (1.0 + phi * phi).sqrt());
    let sum = phi + x;
    let polynomial = d * sum * (1.0 + phi * phi + x * x) / (phi * sp + x * sx);
    let u = d * sum / (phi * sx + x * sp);
    let asinh = if u.abs() < 1e-3 {
        let u2 = u * u;
        u * (1.0 - u2 / 6.0 * (1.0 - 0.45 * u2))
    } else {
        u.asinh()
    };
    0.5 * b * (polynomial + asinh)
}

/// The decrease d of φ from `phi` (> 0) at arc length `ds` further in along `ρ = bφ`, so that
/// [`arc_between`]`(φ, d) = ds`; `phi` itself where the centre is nearer than `ds`
/// (`S(φ) ≤ ds`; `S(φ)` is above `bφ²/2`, which settles the question without it on all but
/// the last turns).
///
/// With `g(t) = √(1+t²)`, `G = g(φ)`, `c = φ/G`, `t = ds/(bG)` and `w = t/G` (about d/φ), the
/// reversion of `ds/b = ∫ g` over the last d of φ (`Gd − (φ/G)d²/2 + d³/6G³ − …`) gives
/// `d = t·(1 + (c/2)w + ((4c² − 1)/6)w² + (c(28c² − 13)/24)w³ + ((280c⁴ − 188c² + 13)/120)w⁴ +
/// …)`, the next coefficient at most 1.32 (derived with sympy; checked against Newton's root by
/// `the_arc_step_series_is_newtons_root`): where w is below 2·10⁻⁴ (all of a path but its last
/// turns) the terms left out are below 10⁻¹⁸ of d, and the step costs a square root and a
/// division. Elsewhere, [`arc_step_by_newton`] from t.
fn arc_step(b: f64, phi: f64, ds: f64) -> f64 {
    if phi <= 0.0 || (0.5 * b * phi * phi <= ds && arc_length(b, phi) <= ds) {
        return phi.max(0.0);
    }
    let inverse = 1.0 / (1.0 + phi * phi).sqrt();
    let t = ds / b * inverse;
    let w = t * inverse;
    if w <= 2e-4 {
        let (c, c2) = (phi * inverse, phi * phi * inverse * inverse);
        let series = [
            0.5 * c,
            (4.0 * c2 - 1.0) / 6.0,
            c * (28.0 * c2 - 13.0) / 24.0,
            ((280.0 * c2 - 188.0) * c2 + 13.0) / 120.0,
        ];
        let sum = series.iter().rev().fold(0.0, |acc, &k| (acc + k) * w);
        return (t + t * sum).min(phi);
    }
    arc_step_by_newton(b, phi, ds, t)
}

/// [`arc_step`] by Newton's method on [`arc_between`] from `start`, whose derivative in d is
/// `b·g(φ − d)`: its error after a correction δ is at most `2δ²/g` (the second derivative is at
/// most b, g is 1-Lipschitz and at least 1), and once that is below 10⁻¹⁷ of d the iteration
/// stops without a further evaluation.
fn arc_step_by_newton(b: f64, phi: f64, ds: f64, start: f64) -> f64 {
    let mut d = start;
    for _ in 0..50 {
        let x = phi - d;
        let g = (1.0 + x * x).sqrt();
        let dd = (ds - arc_between(b, phi, d)) / (b * g);
        d = (d + dd).clamp(0.0, phi);
        if 2.0 * dd * dd <= 1e-17 * d * g {
            break;
        }
    }
    d
}

/// The point at `phi` of a walked spiral, by [`WalkedRule::at`].
fn walked_point(b: f64, phi0: f64, theta0: f64, sign: f64, phi: f64) -> SpiralPoint {
    let rule = WalkedRule {
        b,
        phi0,
        theta0,
        sign,
    };
    rule.at(phi)
}

#[derive(Debug, Clone)]
enum State {
    Angle {
        k: u64,
        steps: u64,
        n: f64,
    },
    Arc {
        b: f64,
        phi0: f64,
        phi: f64,
        ds: f64,
        cap: f64,
    },
    Zoned {
        b: f64,
        phi0: f64,
        phi: f64,
        zone: usize,
    },
    Explicit {
        k: usize,
    },
}

/// Iterator over the points of a [`Spiral`].
#[derive(Debug, Clone)]
pub struct SpiralPoints {
    spiral: Spiral,
    state: State,
    done: bool,
}

impl Iterator for SpiralPoints {
    type Item = SpiralPoint;

    /// The `n`-th next point: in one step for constant-angle and explicit spirals (a point
    /// there is a function of its index), by walking the step rule otherwise. A slice of the
    /// path (the page's workers) starts here.
    fn nth(&mut self, n: usize) -> Option<SpiralPoint> {
        let points = self.spiral.explicit.as_ref().map_or(0, |p| p.len());
        match &mut self.state {
            _ if self.done || n == 0 => {}
            State::Explicit { k } => {
                *k = k.saturating_add(n).min(points);
                self.done = *k >= points;
            }
            State::Angle { k, steps, .. } => {
                *k = k.saturating_add(n as u64).min(*steps + 1);
                self.done = *k > *steps;
            }
            State::Arc { .. } | State::Zoned { .. } => {
                for _ in 0..n {
                    self.next()?;
                }
            }
        }
        self.next()
    }

    fn next(&mut self) -> Option<SpiralPoint> {
        if self.done {
            return None;
        }
        let (t0, sign) = (self.spiral.theta0, self.spiral.sign);
        match &mut self.state {
            State::Explicit { k } => {
                let points = self.spiral.explicit.as_deref().unwrap_or(&[]);
                let p = points.get(*k).copied();
                *k += 1;
                self.done = *k >= points.len();
                p
            }
            State::Angle { k, steps, n } => {
                let rule = AngleRule {
                    theta0: t0,
                    sign,
                    feed: self.spiral.feed,
                    per_rev: *n,
                    steps: *steps,
                };
                let p = rule.at(*k);
                self.done = *k == *steps;
                *k += 1;
                Some(p)
            }
            State::Arc {
                b,
                phi0,
                phi,
                ds,
                cap,
            } => {
                let p = walked_point(*b, *phi0, t0, sign, *phi);
                if *phi == 0.0 {
                    self.done = true;
                } else {
                    *phi -= arc_step(*b, *phi, *ds).min(*cap);
                }
                Some(p)
            }
            State::Zoned { b, phi0, phi, zone } => {
                let p = walked_point(*b, *phi0, t0, sign, *phi);
                if *phi == 0.0 {
                    self.done = true;
                    return Some(p);
                }
                let zones = &self.spiral.zones;
                // The zone of this point: the first whose inner radius lies below it.
                let rho = *b * *phi;
                while *zone + 1 < zones.len() && zones[*zone].inner_radius_mm >= rho {
                    *zone += 1;
                }
                let mut d = zones[*zone].step.at(*b, *phi);
                // The smaller step of every zone the segment reaches.
                let mut k = *zone;
                while k + 1 < zones.len() && zones[k].inner_radius_mm > *b * (*phi - d) {
                    k += 1;
                    d = d.min(zones[k].step.at(*b, *phi));
                }
                *phi = if d >= *phi { 0.0 } else { *phi - d };
                Some(p)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nth_is_the_walk() {
        let spirals = [
            Sampling::ConstantAngle { points_per_rev: 7 },
            Sampling::ConstantArc {
                arc_length_mm: 0.05,
                max_angle_step_deg: 30.0,
            },
        ]
        .map(|s| Spiral::new(1.0, 0.1, &s, Direction::Cw, 10.0).unwrap());
        let mut list: Vec<SpiralPoint> = spirals[0].points().step_by(3).collect();
        list.extend(
            spirals[0]
                .points()
                .last()
                .filter(|p| p.rho < list[list.len() - 1].rho),
        );
        let explicit =
            Spiral::from_points(0.1, &Sampling::ConstantAngle { points_per_rev: 7 }, list).unwrap();
        for spiral in spirals.iter().chain([&explicit]) {
            let walk: Vec<SpiralPoint> = spiral.points().collect();
            for n in [0, 1, 2, 5, walk.len() - 1, walk.len(), walk.len() + 3] {
                let mut it = spiral.points();
                assert_eq!(it.nth(n), walk.get(n).copied(), "n {n}");
                assert_eq!(it.next(), walk.get(n + 1).copied(), "after n {n}");
                let mut it = spiral.points();
                it.next();
                assert_eq!(it.nth(n), walk.get(n + 1).copied(), "1 + n {n}");
            }
        }
    }

    #[test]
    fn a_walked_spirals_points_give_back_their_phi() {
        let hcaa = Sampling::Hcaa {
            pv_tolerance_um: 1.0,
        };
        // Radii R from 50 mm to 2 mm with feeds from 0.1 mm to 0.04 µm (φ up to 3·10⁶ rad),
        // both directions, start angles that are no multiples of a step.
        for (radius, feed, ds, direction, start) in [
            (50.0, 0.1, 0.002, Direction::Cw, 0.0),
            (2.0, 1e-4, 0.002, Direction::Ccw, 37.5),
            (20.0, 4e-5, 0.5, Direction::Cw, -123.4),
        ] {
            let arc = Sampling::ConstantArc {
                arc_length_mm: ds,
                max_angle_step_deg: 20.0,
            };
            let zoned = [
                Zone {
                    inner_radius_mm: 0.4 * radius,
                    step: Step::Angle { step_rad: 0.3 },
                },
                Zone {
                    inner_radius_mm: 0.0,
                    step: Step::Arc {
                        arc_length_mm: ds,
                        max_step_rad: 0.5,
                    },
                },
            ];
            let spirals = [
                Spiral::new(radius, feed, &arc, direction, start).unwrap(),
                Spiral::with_zones(radius, feed, &hcaa, &zoned, direction, start).unwrap(),
            ];
            for spiral in &spirals {
                let rule = spiral.walked_rule().unwrap();
                for rho in [radius, 0.4 * radius + 1e-3, 0.7, 1e-3] {
                    for p in spiral.points_from(rho).take(20_000) {
                        let phi = rule.phi_of(p.theta, p.rho);
                        let back = phi.map(|phi| rule.at(phi));
                        assert_eq!(back, Some(p), "ρ {} θ {} feed {feed}", p.rho, p.theta);
                        // A point a nanometre off the spiral is not on it.
                        assert_eq!(rule.phi_of(p.theta, p.rho + 1e-6), None);
                    }
                }
            }
        }
        let arc = Sampling::ConstantArc {
            arc_length_mm: 0.002,
            max_angle_step_deg: 20.0,
        };
        // The last point, at the centre.
        let spiral = Spiral::new(0.05, 0.01, &arc, Direction::Cw, 10.0).unwrap();
        let centre = spiral.points().last().unwrap();
        assert_eq!(centre.rho, 0.0);
        let rule = spiral.walked_rule().unwrap();
        assert_eq!(rule.phi_of(centre.theta, 0.0), Some(0.0));
        // Spirals whose points are given by the index are not walked.
        let angle = Sampling::ConstantAngle { points_per_rev: 7 };
        assert!(
            Spiral::new(1.0, 0.1, &angle, Direction::Cw, 0.0)
                .unwrap()
                .walked_rule()
                .is_none()
        );
    }

    #[test]
    fn the_points_of_one_angle_share_their_direction_on_every_turn() {
        // 720 points a turn over 1 000 turns, clockwise from 10°: the points of one angle
        // have the same (sin θ, cos θ) to the bit on every turn, within 1e-15 of the first
        // turn's own angle (whose rounding is still at the ulp of 2π).
        let n = 720;
        let sampling = Sampling::ConstantAngle { points_per_rev: n };
        let spiral = Spiral::new(5.0, 0.005, &sampling, Direction::Cw, 10.0).unwrap();
        let points: Vec<SpiralPoint> = spiral.points().collect();
        assert_eq!(points.len(), 720_001);
        for j in [0, 1, 359, 718, 719] {
            let first = spiral.sin_cos(points[j].theta);
            let own = points[j].theta.sin_cos();
            assert!((first.0 - own.0).abs() < 1e-15 && (first.1 - own.1).abs() < 1e-15);
            for turn in 1..1000 {
                let p = points[j + turn * n as usize];
                assert_eq!(spiral.sin_cos(p.theta), first, "angle {j} turn {turn}");
            }
        }
        // The table gives the same bits at every point, and the computation does without it.
        let table = spiral.turn_directions();
        assert_eq!(table.len(), n as usize);
        for p in &points {
            assert_eq!(
                spiral.sin_cos_from(&table, p.theta),
                spiral.sin_cos(p.theta)
            );
        }
        for (step, p) in points.iter().take(n as usize).enumerate() {
            assert_eq!(table[step], spiral.sin_cos(p.theta), "step {step}");
        }
        // A turn longer than the table's bound is computed point by point.
        let long = Sampling::ConstantAngle {
            points_per_rev: MAX_TABULATED_DIRECTIONS as u32 + 1,
        };
        let spiral = Spiral::new(1.0, 0.5, &long, Direction::Ccw, 0.0).unwrap();
        assert!(spiral.turn_directions().is_empty());
        // Other samplings keep the angle's own sine.
        let arc = Sampling::ConstantArc {
            arc_length_mm: 0.05,
            max_angle_step_deg: 30.0,
        };
        let spiral = Spiral::new(1.0, 0.1, &arc, Direction::Ccw, 3.0).unwrap();
        assert!(spiral.turn_directions().is_empty());
        for p in spiral.points().take(100) {
            assert_eq!(spiral.sin_cos(p.theta), p.theta.sin_cos());
        }
    }

    #[test]
    fn arc_length_is_the_integral() {
        // Trapezoid rule on b√(1+t²) against the closed form.
        let (b, phi) = (0.01, 30.0);
        let n = 200_000;
        let h = phi / n as f64;
        let f = |t: f64| b * (1.0 + t * t).sqrt();
        let trap: f64 = (0..n)
            .map(|i| 0.5 * h * (f(i as f64 * h) + f((i + 1) as f64 * h)))
            .sum();
        assert!((trap - arc_length(b, phi)).abs() < 1e-8);
    }

    /// `S(φ) − S(x)` by an independent route: Simpson's rule on `b√(1+t²)` over 4 096
    /// intervals, summed with compensation (its error is below 10⁻¹⁶ of the length where
    /// `d = φ − x` is at most max(x, 1): the fourth derivative of √(1+t²) is at most 3, and
    /// 12/t⁵ beyond t = 1), else the closed form's difference (then at least a quarter of
    /// `S(φ)`: no cancellation to speak of).
    fn arc_reference(b: f64, x: f64, phi: f64) -> f64 {
        if phi - x > x.max(1.0) {
            return arc_length(b, phi) - arc_length(b, x);
        }
        let n = 4096;
        let h = (phi - x) / n as f64;
        let f = |i: usize| (1.0 + (x + i as f64 * h).powi(2)).sqrt();
        let (mut sum, mut carry) = (0.0f64, 0.0f64);
        for i in 0..=n {
            let weight = match i {
                0 => 1.0,
                _ if i == n => 1.0,
                _ if i % 2 == 1 => 4.0,
                _ => 2.0,
            };
            let y = weight * f(i) - carry;
            let t = sum + y;
            carry = (t - sum) - y;
            sum = t;
        }
        b * sum * h / 3.0
    }

    #[test]
    fn the_arc_between_two_turns_is_the_integral() {
        // From the centre to the rim of a 0.07 µm feed at 4 mm (φ 3.4e5) and beyond, steps
        // from a nanometre's worth to the whole way in.
        let b = 0.01 / TAU;
        for phi in [0.5, 3.0, 40.0, 3e3, 3.4e5, 1e7] {
            for fraction in [1e-12, 1e-9, 1e-6, 1e-3, 0.1, 0.5, 1.0] {
                let x = phi * (1.0 - fraction);
                let (got, want) = (arc_between(b, phi, phi - x), arc_reference(b, x, phi));
                assert!(
                    (got - want).abs() <= 1e-14 * want,
                    "φ {phi}, x {x}: {got} against {want}"
                );
            }
        }
        assert_eq!(arc_between(b, 0.0, 0.0), 0.0);
        assert_eq!(arc_between(b, 1.0, 0.0), 0.0);
    }

    #[test]
    fn an_arc_step_covers_its_length() {
        // Steps of 0.1 µm to 1 mm along spirals of 0.07 µm to 0.1 mm a turn: the step lands
        // within an ulp of φ of where it covers `ds` exactly (the point's φ is a double: an ulp
        // of it is about 2·10⁻¹⁰ mm along the finest spiral at 4 mm).
        for feed in [7e-5, 0.005, 0.1] {
            let b = feed / TAU;
            for rho in [0.003, 0.1, 1.0, 4.0] {
                let phi = rho / b;
                for ds in [1e-4, 1e-2, 1.0] {
                    let d = arc_step(b, phi, ds);
                    if arc_length(b, phi) <= ds {
                        assert_eq!(d, phi, "feed {feed}, ρ {rho}, ds {ds}");
                        continue;
                    }
                    assert!(d > 0.0 && d < phi, "feed {feed}, ρ {rho}, ds {ds}: {d}");
                    let x = phi - d;
                    let ulp = f64::from_bits(phi.to_bits() + 1) - phi;
                    let slack = 1e-14 * ds + b * (1.0 + x * x).sqrt() * ulp;
                    let covered = arc_reference(b, x, phi);
                    assert!(
                        (covered - ds).abs() <= slack,
                        "feed {feed}, ρ {rho}, ds {ds}: {covered}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_arc_step_series_is_newtons_root() {
        // Up to its bound w = 2e-4 (d/φ) and at a tenth of it, from φ = 0.05 (c = φ/√(1+φ²)
        // near 0) to 10⁷ (c = 1): the series and Newton's root agree to rounding, Newton's
        // being good to its residual's, a few 10⁻¹⁶ (at φ = 3.4e5, w = 2e-4: the series
        // 68.00680136063421, Newton 68.00680136063424, mpmath 68.006801360634222). A term
        // fewer in the series would be off by 1.4e-15 there.
        let b = 0.01 / TAU;
        for phi in [0.05, 0.5, 1.0, 3.0, 40.0, 3e3, 3.4e5, 1e7] {
            let big_g2 = 1.0 + phi * phi;
            for w in [2e-4, 2e-5, 1e-9] {
                // ds that gives this w: t = w·G, ds = b·t·G.
                let ds = b * w * big_g2;
                let series = arc_step(b, phi, ds);
                let newton = arc_step_by_newton(b, phi, ds, w * big_g2.sqrt());
                assert!(
                    (series - newton).abs() <= 8e-16 * newton,
                    "φ {phi}, w {w}: {series} against {newton}"
                );
            }
        }
    }

    #[test]
    fn bad_parameters_name_their_field() {
        let s = Sampling::ConstantAngle { points_per_rev: 2 };
        let e = Spiral::new(5.0, 0.01, &s, Direction::Ccw, 0.0).unwrap_err();
        assert_eq!(e.field, "sampling.points_per_rev");
        let s = Sampling::ConstantArc {
            arc_length_mm: 0.01,
            max_angle_step_deg: 0.0,
        };
        let e = Spiral::new(5.0, 0.01, &s, Direction::Ccw, 0.0).unwrap_err();
        assert_eq!(e.field, "sampling.max_angle_step_deg");
        let s = Sampling::ConstantAngle {
            points_per_rev: 100,
        };
        assert_eq!(
            Spiral::new(5.0, -1.0, &s, Direction::Ccw, 0.0)
                .unwrap_err()
                .field,
            "feed_mm_per_rev"
        );
        // 10 mm at 1e-9 mm/rev and 100 points/rev: 10¹² points.
        let s = Sampling::ConstantAngle {
            points_per_rev: 100,
        };
        let e = Spiral::new(10.0, 1e-9, &s, Direction::Ccw, 0.0).unwrap_err();
        assert_eq!(e.field, "feed_mm_per_rev");
        assert!(e.allowed.contains("about 1e12 points"), "{e}");
        // The feed that would do: 10 mm × 100 points/rev / 1e9 points.
        assert!(e.allowed.contains("at least 1.000001e-6 mm/rev"), "{e}");
        // A feed so small that the count overflows a u64 is refused, not wrapped to 0.
        let e = Spiral::new(10.0, 9.7e-17, &s, Direction::Ccw, 0.0).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("feed_mm_per_rev = 9.7e-17: gives about 1.030928e19"),
            "{e}"
        );
        let s = Sampling::ConstantArc {
            arc_length_mm: 1e-9,
            max_angle_step_deg: 1.0,
        };
        assert!(Spiral::new(10.0, 0.01, &s, Direction::Ccw, 0.0).is_err());
    }

    #[test]
    fn counts_past_the_largest_double_suggest_a_finite_feed_or_name_the_step() {
        // Found from outside: a feed of 5e-324 mm/rev (or a part of 1.8e308 mm) counted infinite
        // points and suggested "a feed of at least inf mm/rev". 10 mm at 100 points a turn:
        // 10 mm × 100 / 1e9 = 1e-6 mm/rev, counted here at a feed of 10 mm (101 points).
        let s = Sampling::ConstantAngle {
            points_per_rev: 100,
        };
        let e = Spiral::new(10.0, 5e-324, &s, Direction::Ccw, 0.0).unwrap_err();
        assert_eq!(e.field, "feed_mm_per_rev");
        assert!(
            e.allowed.starts_with(
                "gives more points than can be counted with this sampling; at most 1e9 are \
                 planned: a feed of at least 1.010001e-6 mm/rev"
            ),
            "{e}"
        );
        // The constant-arc steps are bounded below (5e-324 counted infinite points at any
        // feed), and the cap's message gives the range it checks (it said [0, 90], refusing 0).
        let arc = |arc_length_mm, max_angle_step_deg| Sampling::ConstantArc {
            arc_length_mm,
            max_angle_step_deg,
        };
        let e = Spiral::new(10.0, 0.01, &arc(5e-324, 1.0), Direction::Ccw, 0.0).unwrap_err();
        assert_eq!(e.field, "sampling.arc_length_mm", "{e}");
        assert!(e.allowed.contains("at least 1e-6 mm"), "{e}");
        for cap in [0.0, 5e-324, 3.5e-4, 90.5] {
            let e = Spiral::new(10.0, 0.01, &arc(0.01, cap), Direction::Ccw, 0.0).unwrap_err();
            assert_eq!(
                e.to_string().split(" = ").next(),
                Some("sampling.max_angle_step_deg")
            );
            assert_eq!(e.allowed, "must lie in [0.00036, 90]", "{e}");
        }
        // The finest steps of both, at a feed of the radius: a finite count, refused by the
        // feed that would do.
        let e = Spiral::new(10.0, 1e-300, &arc(1e-6, 3.6e-4), Direction::Ccw, 0.0).unwrap_err();
        assert_eq!(e.field, "feed_mm_per_rev", "{e}");
        assert!(e.allowed.contains("a feed of at least"), "{e}");
    }
}
