//! Critical tool angles and holder tilt (paper 000, section "Optimization of tool geometry"):
//! from the slopes of the surface along the cutting direction and along the feed, the front
//! clearance angle α_cr the tool needs, the most negative rake angle γ_cr it may have, the
//! included angle β_cr its nose must span, the path points where a given tool's flank rubs the
//! surface, and the least tilt λ of the tool holder that clears them.
//!
//! The paper's equations are lost in our copy of the text; what follows is derived from its
//! prose ("the slopes of the surface contour ϕ along the cutting direction", "ε the slope of the
//! surface contour along the feed direction", "tilting the tool holder away from the workpiece")
//! with the conventions of this crate.
//!
//! **Conventions.** Z is the axis, the sag `z = f(x, y)` rises towards the tool (+Z). At a path
//! point (ρ, θ) the radial direction is `û = (cos θ, sin θ)` and the tangential one
//! `v̂ = (−sin θ, cos θ)`. The path is the tool's track on the part: θ advances with the sign `s`
//! of `strategy.direction` (+1 ccw, −1 cw, [`crate::job::Direction::sign`]), so the tool
//! moves over the part along the cutting direction `t̂ = s·v̂` (the radial feed, f per
//! revolution, is neglected against the circumferential motion). The slope along the cutting
//! direction is `ϕ = ∇f·t̂ = s·(−f_x sin θ + f_y cos θ)`, positive where the surface rises
//! ahead of the tool; the radial slope is `f_ρ = ∇f·û`, positive where it rises outward (the
//! feed goes inward, so the slope along the feed is `ε = −f_ρ`). Angles are in degrees; the
//! slopes are those of the design surface at the path's spiral point (ρ, θ), so that the path
//! samples the whole surface; the nose's contact lies `r·sin a` away radially.
//!
//! **Front clearance.** The rake face leads (faces +t̂, the nose arc lies in it); the flank
//! (clearance) face leaves the cutting edge backwards, over the surface just cut, rising at the
//! clearance angle α above the cutting direction: a distance d behind the edge it lies
//! `d·tan α` above the edge. The surface just cut lies, to first order, `−d·ϕ` above the edge
//! there. The flank clears it when `tan α ≥ −ϕ`, so the required clearance at a point is
//! `α_req = max(0, atan(−ϕ))` — the angle of the surface's fall ahead of the tool (the tool
//! runs downhill, the cut surface behind it rises towards the flank) — and the critical front
//! clearance is `α_cr = max α_req` over the path. Curvature along the cut is neglected (first
//! order, as in the paper): a concave section bends the cut surface further towards a long
//! flank.
//!
//! **Rake.** A rake angle γ tilts the rake face away from the Z axis: going up from the edge it
//! moves `−tan γ` per unit height along +t̂, so the face makes the angle `90° + γ` with the
//! cutting direction ahead. The surface ahead rises at `atan ϕ`; the rake face stays above it
//! when `90° + γ ≥ atan ϕ`, so the rake limit at a point is `γ_lim = atan(max(0, ϕ)) − 90°`
//! (−90° where the surface does not rise ahead), and the critical rake angle is
//! `γ_cr = max γ_lim`: a tool needs `γ ≥ γ_cr`. Only negative rakes can interfere, as the paper
//! says; it quotes |γ_cr| = 90° − (steepest rise), about 70° in its example.
//!
//! **Included angle.** The nose arc spans `a ∈ [−β/2, β/2]` about −Z in the radial plane
//! ([`crate::tool`]); its point at nose angle a has tangent slope `tan a`, so it touches a
//! radial slope f_ρ at `a = atan f_ρ` (outward half for f_ρ > 0, inward half for f_ρ < 0). The
//! nose reaches every radial slope when `β/2 ≥ ε_out = max atan(max(0, f_ρ))` and
//! `β/2 ≥ ε_in = max atan(max(0, −f_ρ))`: the critical included angle is
//! `β_cr = 2·max(ε_out, ε_in)`, and the tool needs `β ≥ β_cr`. Where it does not, the
//! compensation puts the contact at an end of the arc (its "arc-end contacts") and the straight
//! flank beyond the arc would have to cut the rest. The paper states β_cr as an upper bound with
//! a clearance C of the side faces; that bound (the side faces rubbing a steep wall) needs the
//! tool's side clearance, which [`crate::job::ToolSpec`] does not describe, and is not
//! checked here.
//!
//! **Holder tilt.** Rotating the tool holder by λ about the radial axis, away from the
//! workpiece, turns the rake and flank faces in the (t̂, Z) plane: the effective clearance
//! becomes `α + λ` and the effective rake `γ − λ` (paper 000, Figure 8). The least tilt that
//! clears every flank interference is `λ = max(0, α_cr − α)`; it is allowed while the rake
//! face still clears, `γ − λ ≥ γ_cr`, i.e. up to the paper's `λ_max = γ − γ_cr`. Where
//! `α_cr − α > γ − γ_cr`, or the rake already interferes (γ < γ_cr), no tilt clears the path.
//! The tilt also turns the nose arc out of the radial plane (its height profile shrinks by
//! cos λ); the compensation does not model that.
//!
//! A point interferes when `α_req > α + 1e-9°` ([`ANGLE_TOLERANCE`]): the margin absorbs the
//! rounding of `α + (α_cr − α)`, so that the reported tilt clears exactly.

use crate::job::ToolAngles;
use crate::path::Location;
use crate::path::PathPoint;
use crate::raster::Raster;
use crate::surface::UndefinedError;
use crate::tool::ToolPath;
use serde::Serialize;

/// Margin, degrees, by which the required clearance must exceed the tool's to count as an
/// interference (rounding of the tilted clearance; see the module docs).
pub const ANGLE_TOLERANCE: f64 = 1e-9;
/// Interference locations listed in the report.
pub const MAX_LISTED: usize = 10;

/// The critical angles at one point (see the module docs), degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointAngles {
    /// Slope along the cutting direction ϕ = ∇f·t̂ (dimensionless; > 0 rising ahead).
    pub cutting_slope: f64,
    /// Radial slope f_ρ = ∇f·û (> 0 rising outward).
    pub radial_slope: f64,
    /// Required front clearance `max(0, atan(−ϕ))`.
    pub clearance_deg: f64,
    /// Rake limit `atan(max(0, ϕ)) − 90°`: the rake must be at least this.
    pub rake_limit_deg: f64,
    /// Half angle the outward half of the nose must reach, `atan(max(0, f_ρ))`.
    pub outward_half_deg: f64,
    /// Half angle the inward half of the nose must reach, `atan(max(0, −f_ρ))`.
    pub inward_half_deg: f64,
}

impl PointAngles {
    /// From the gradient (f_x, f_y) at polar angle `theta` (radians), the path advancing in
    /// θ with `direction_sign` (+1 ccw, −1 cw).
    pub fn from_gradient(zx: f64, zy: f64, theta: f64, direction_sign: f64) -> Self {
        let (s, c) = theta.sin_cos();
        let cutting_slope = direction_sign * (-zx * s + zy * c);
        let radial_slope = zx * c + zy * s;
        Self {
            cutting_slope,
            radial_slope,
            clearance_deg: (-cutting_slope).max(0.0).atan().to_degrees(),
            rake_limit_deg: cutting_slope.max(0.0).atan().to_degrees() - 90.0,
            outward_half_deg: radial_slope.max(0.0).atan().to_degrees(),
            inward_half_deg: (-radial_slope).max(0.0).atan().to_degrees(),
        }
    }
}

/// An extreme over the path and where it occurs (tool position).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Critical {
    /// The angle, degrees.
    pub deg: f64,
    /// Where (the first point reaching it).
    pub at: Location,
}

impl Critical {
    fn new(deg: f64) -> Self {
        Self {
            deg,
            at: Location::new(0.0, 0.0),
        }
    }

    fn keep_max(&mut self, deg: f64, rho: f64, theta: f64) {
        if deg > self.deg {
            self.deg = deg;
            self.at = Location::new(rho, theta);
        }
    }
}

/// The tool-geometry figures of a path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ToolGeometryReport {
    /// Points checked.
    pub points: u64,
    /// The tool checked.
    pub tool: ToolAngles,
    /// The tool's included angle β, degrees (from the job's tool).
    pub included_angle_deg: f64,
    /// Critical front clearance α_cr = max α_req (0 where nothing falls ahead of the tool).
    pub critical_clearance: Critical,
    /// Critical rake γ_cr = max γ_lim (−90° where nothing rises ahead): the rake must be ≥ it.
    pub critical_rake: Critical,
    /// Steepest outward-rising radial slope angle ε_out: the outward half of the nose must
    /// reach it.
    pub critical_outward_half: Critical,
    /// Steepest inward-rising radial slope angle ε_in.
    pub critical_inward_half: Critical,
    /// Critical included angle β_cr = 2·max(ε_out, ε_in), degrees: β must be ≥ it.
    pub critical_included_angle_deg: f64,
    /// Points where the required clearance exceeds the tool's (flank interference).
    pub clearance_interferences: u64,
    /// The first [`MAX_LISTED`] of them, in path order.
    pub first_interferences: Vec<Location>,
    /// Points where the surface rise ahead meets the rake face (γ < γ_lim).
    pub rake_interferences: u64,
    /// The least holder tilt λ, degrees, that clears every flank interference without the rake
    /// face meeting the surface (0 where none is needed); None where no tilt does.
    pub holder_tilt_deg: Option<f64>,
    /// Why the tilt is what it is, or why there is none.
    pub holder_tilt_note: String,
    /// One-line summary.
    pub verdict: String,
    /// Required clearance α_req, degrees, largest in each cell, at the tool position; NaN where
    /// no point fell.
    #[serde(skip)]
    pub map: Raster,
}

/// Consumes a path point by point and keeps the critical angles and the interferences.
#[derive(Debug, Clone)]
pub struct ToolGeometryCheck {
    tool: ToolAngles,
    included_angle_deg: f64,
    sign: f64,
    points: u64,
    clearance: Critical,
    rake: Critical,
    outward: Critical,
    inward: Critical,
    interferences: u64,
    first: Vec<Location>,
    rake_interferences: u64,
    map: Raster,
}

impl ToolGeometryCheck {
    /// A check of `tool` on `tool_path`'s path with a map of `map_size` × `map_size` samples.
    pub fn new(tool_path: &ToolPath, tool: &ToolAngles, map_size: usize) -> Self {
        let job = tool_path.job();
        Self {
            tool: *tool,
            included_angle_deg: job.tool.included_angle_deg,
            sign: job.strategy.direction.sign(),
            points: 0,
            clearance: Critical::new(0.0),
            rake: Critical::new(-90.0),
            outward: Critical::new(0.0),
            inward: Critical::new(0.0),
            interferences: 0,
            first: Vec::new(),
            rake_interferences: 0,
            map: Raster::over_part(job.part_radius_mm(), map_size),
        }
    }

    /// Adds the next path point.
    pub fn add(&mut self, tool_path: &ToolPath, p: &PathPoint) -> Result<(), UndefinedError> {
        let (s, c) = p.theta.sin_cos();
        let (x, y) = (p.rho * c, p.rho * s);
        let l = tool_path.surface().local(x, y)?;
        let a = PointAngles::from_gradient(l.zx, l.zy, p.theta, self.sign);
        self.points += 1;
        self.clearance.keep_max(a.clearance_deg, p.rho, p.theta);
        self.rake.keep_max(a.rake_limit_deg, p.rho, p.theta);
        self.outward.keep_max(a.outward_half_deg, p.rho, p.theta);
        self.inward.keep_max(a.inward_half_deg, p.rho, p.theta);
        if a.clearance_deg > self.tool.clearance_deg + ANGLE_TOLERANCE {
            self.interferences += 1;
            if self.first.len() < MAX_LISTED {
                self.first.push(Location::new(p.rho, p.theta));
            }
        }
        if self.tool.rake_deg < a.rake_limit_deg - ANGLE_TOLERANCE {
            self.rake_interferences += 1;
        }
        self.map.keep_largest(x, y, a.clearance_deg);
        Ok(())
    }

    /// The figures.
    pub fn finish(self) -> ToolGeometryReport {
        let tool = self.tool;
        let beta_cr = 2.0 * self.outward.deg.max(self.inward.deg);
        let need = self.clearance.deg - tool.clearance_deg;
        let lambda_max = tool.rake_deg - self.rake.deg;
        let (holder_tilt_deg, holder_tilt_note) = if self.rake_interferences > 0 {
            (
                None,
                format!(
                    "the rake {:.3}° is below the critical rake {:.3}°; tilting only lowers it",
                    tool.rake_deg, self.rake.deg
                ),
            )
        } else if self.interferences == 0 {
            (Some(0.0), "no flank interference: no tilt needed".into())
        } else if need > lambda_max + ANGLE_TOLERANCE {
            (
                None,
                format!(
                    "the flank needs {need:.3}° of tilt but the rake face meets the surface \
                     beyond λmax = {lambda_max:.3}°"
                ),
            )
        } else {
            (
                Some(need),
                format!(
                    "tilting by {need:.3}° gives clearance {:.3}° and rake {:.3}° (λmax {lambda_max:.3}°)",
                    tool.clearance_deg + need,
                    tool.rake_deg - need
                ),
            )
        };
        let mut problems = Vec::new();
        if self.interferences > 0 {
            problems.push(format!(
                "flank interference at {} points (needs clearance {:.3}°, tool {:.3}°)",
                self.interferences, self.clearance.deg, tool.clearance_deg
            ));
        }
        if self.rake_interferences > 0 {
            problems.push(format!(
                "rake face interference at {} points (rake must be ≥ {:.3}°)",
                self.rake_interferences, self.rake.deg
            ));
        }
        if self.included_angle_deg < beta_cr - ANGLE_TOLERANCE {
            problems.push(format!(
                "included angle {:.3}° below the critical {beta_cr:.3}°: the nose arc cannot \
                 reach the steepest radial slope (arc-end contacts)",
                self.included_angle_deg
            ));
        }
        let verdict = if problems.is_empty() {
            "the tool clears the surface".to_string()
        } else {
            let tilt = match holder_tilt_deg {
                Some(l) if l > 0.0 => format!("; a holder tilt of {l:.3}° clears the flank"),
                _ => String::new(),
            };
            format!("{}{tilt}", problems.join("; "))
        };
        ToolGeometryReport {
            points: self.points,
            tool,
            included_angle_deg: self.included_angle_deg,
            critical_clearance: self.clearance,
            critical_rake: self.rake,
            critical_outward_half: self.outward,
            critical_inward_half: self.inward,
            critical_included_angle_deg: beta_cr,
            clearance_interferences: self.interferences,
            first_interferences: self.first,
            rake_interferences: self.rake_interferences,
            holder_tilt_deg,
            holder_tilt_note,
            verdict,
            map: self.map,
        }
    }
}

/// Runs the check of `tool` over `tool_path`'s whole path.
pub fn check(
    tool_path: &ToolPath,
    tool: &ToolAngles,
    map_size: usize,
) -> Result<ToolGeometryReport, UndefinedError> {
    let mut c = ToolGeometryCheck::new(tool_path, tool, map_size);
    for p in tool_path.points() {
        c.add(tool_path, &p?)?;
    }
    Ok(c.finish())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn tool_geometry_point_angles_follow_the_direction() {
        // z = 0.2·x at θ = 90°: ccw the tool moves along −x, downhill at slope −0.2.
        let a = PointAngles::from_gradient(0.2, 0.0, FRAC_PI_2, 1.0);
        assert!((a.cutting_slope + 0.2).abs() < 1e-15);
        assert!((a.clearance_deg - 0.2f64.atan().to_degrees()).abs() < 1e-12);
        assert_eq!(a.rake_limit_deg, -90.0);
        assert!(a.radial_slope.abs() < 1e-15);
        // cw the same point runs uphill: no clearance needed, rake limit atan(0.2) − 90°.
        let b = PointAngles::from_gradient(0.2, 0.0, FRAC_PI_2, -1.0);
        assert_eq!(b.clearance_deg, 0.0);
        assert!((b.rake_limit_deg - (0.2f64.atan().to_degrees() - 90.0)).abs() < 1e-12);
        // Radial slope at θ = 0 rising outward: the outward half must reach it.
        let c = PointAngles::from_gradient(0.5, 0.0, 0.0, 1.0);
        assert!((c.outward_half_deg - 0.5f64.atan().to_degrees()).abs() < 1e-12);
        assert_eq!(c.inward_half_deg, 0.0);
    }

    #[test]
    fn tool_geometry_tilt_trades_rake_for_clearance() {
        let t = ToolAngles::default().tilted(5.0);
        assert_eq!(t.clearance_deg, 15.0);
        assert_eq!(t.rake_deg, -5.0);
    }
}
