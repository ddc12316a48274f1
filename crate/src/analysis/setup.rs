//! Set-up errors a test cut shows, turned into offsets (issue 15, `spiralcam setup`). The
//! geometry, in the machine's frame (X radial, Z axial, the tool cutting at X ≥ 0; f(r) the
//! design's sag along +X, the section the tool cuts at C = 0):
//!
//! - **Tool height** (the centre post). A tool tip h above the spindle centre line (h < 0:
//!   below) at commanded X cuts the radius `√(X² + h²)`: it never comes nearer the axis than
//!   |h|, and leaves a post of diameter `d = 2|h|` at the centre, so `|h| = d/2`. The sign comes
//!   from the post's shape, the lathe rule "a tapered cone if the tool is too high, a narrow
//!   cylinder if too low" (for example the OTMT SC4 lathe manual, "Setting the tool height"; with
//!   the tool high its clearance face rubs the post into a cone). The tool moves by −h.
//! - **X offset** (a W or M shaped profile error). A tip δx further out than commanded
//!   (δx > 0: it stops short of the axis; δx < 0: it runs past it) cuts at radius r the height
//!   the program gives for r − δx: `e(r) = f(r − δx) − f(r) ≈ −δx·f′(r)`, a cone across the
//!   diameter whose centre, where the tool stops short or crosses over, turns the V or Λ into a
//!   W or M. Its size follows the surface's slope: from the rise `Δe = e(r₂) − e(r₁)` of the
//!   error between two radii on its arms, δx solves
//!   `[f(r₂ − δx) − f(r₂)] − [f(r₁ − δx) − f(r₁)] = Δe` (Newton's method on the design's own
//!   sag, exact for any surface of revolution along X). The X offset moves by −δx.
//! - **Radius of curvature.** A sphere (or any design) cut with an X offset δx measures, fitted
//!   as a sphere `z = p + R_m − √(R_m² − r²)` by least squares over the profile r ∈ [0, a]
//!   (uniform weight along the diameter), with a radius that differs from the design's fit R:
//!   to first order `R_m − R = −δx·cov(f′, g)/var(g)`, g = ∂z/∂R_m = `1 − |R|/√(R² − r²)`, the
//!   covariances over the profile (computed from the design by 2 001-point quadrature). So
//!   `δx = −(R_m − R)·var(g)/cov(f′, g)`. On a machine that generates the sphere about a rotary
//!   B axis, the radius is the tool's distance from the pivot, and a Z offset (along that
//!   distance) changes it one for one: `δz = R_m − R`. Both are reported.

use crate::field::{FieldError, positive, short};
use crate::surface::Surface;
use serde::{Deserialize, Serialize};

/// Newton steps at most for the X offset.
const NEWTON_STEPS: usize = 60;
/// Quadrature points of the radius relation.
const PROFILE_SAMPLES: usize = 2001;

/// The shape of the post left at the centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PostShape {
    /// A tapered cone: the tool is above the centre.
    Cone,
    /// A narrow cylinder: the tool is below the centre.
    Cylinder,
}

/// The post at the centre of a test cut.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CentrePost {
    /// Its diameter, µm, ≥ 0.
    pub diameter_um: f64,
    /// Its shape.
    pub shape: PostShape,
}

/// A W or M shaped profile error: its rise between two radii on its arms.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileRise {
    /// The inner radius, mm, > 0 (outside the centre feature).
    pub inner_radius_mm: f64,
    /// The outer radius, mm, > inner, within the part.
    pub outer_radius_mm: f64,
    /// The form error at the outer radius minus that at the inner one, µm (positive: more
    /// material left outside).
    pub rise_um: f64,
}

/// A measured radius of curvature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeasuredRadius {
    /// The radius of the sphere fitted to the measured profile, mm (positive: concave towards
    /// the tool, as the asphere family's radius).
    pub measured_mm: f64,
    /// The half-width of the profile fitted, a, mm, within the part.
    pub aperture_radius_mm: f64,
}

/// What a test cut showed (`spiralcam setup --params`): any of the three.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SetupSpec {
    /// The post at the centre.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centre_post: Option<CentrePost>,
    /// A W or M shaped profile error.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<ProfileRise>,
    /// A measured radius of curvature.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<MeasuredRadius>,
}

/// The tool height found from the post.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeightOffset {
    /// The tool tip's height above the spindle centre line, µm (negative: below).
    pub tool_height_um: f64,
    /// The move that centres it, µm (positive: up).
    pub move_tool_um: f64,
}

/// The X offset found from a profile or a radius.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct XOffset {
    /// How far the tip lies outward of the commanded X, µm (positive: it stops short of the
    /// axis).
    pub x_offset_um: f64,
    /// The change to the X offset that centres it, µm.
    pub move_x_um: f64,
}

/// What a measured radius says.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RadiusOffsets {
    /// The design's own fitted radius over the aperture, mm.
    pub design_radius_mm: f64,
    /// The X offset that explains the difference on an XZ lathe.
    pub x: XOffset,
    /// The Z offset that explains it on a machine generating the sphere about a B axis, µm
    /// (the tool's distance from the pivot is too long by this much).
    pub b_axis_z_offset_um: f64,
}

/// The offsets (`spiralcam setup` prints them as JSON).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct SetupReport {
    /// From the centre post.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub centre_post: Option<HeightOffset>,
    /// From the W or M profile.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profile: Option<XOffset>,
    /// From the radius.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<RadiusOffsets>,
}

impl SetupSpec {
    /// The offsets for the design `surface` (as the spindle sees it) on a part of radius
    /// `part_radius_mm`. Field names start with the entry (`profile.outer_radius_mm`).
    pub fn offsets(
        &self,
        surface: &dyn Surface,
        part_radius_mm: f64,
    ) -> Result<SetupReport, FieldError> {
        if self.centre_post.is_none() && self.profile.is_none() && self.radius.is_none() {
            return Err(FieldError::new(
                "setup",
                "{}",
                "give centre_post, profile or radius (see crate/docs/correction.md)",
            ));
        }
        Ok(SetupReport {
            centre_post: self.centre_post.as_ref().map(height_offset).transpose()?,
            profile: self
                .profile
                .as_ref()
                .map(|p| x_offset_from_profile(p, surface, part_radius_mm))
                .transpose()?,
            radius: self
                .radius
                .as_ref()
                .map(|r| offsets_from_radius(r, surface, part_radius_mm))
                .transpose()?,
        })
    }
}

/// The tool height of a post.
fn height_offset(post: &CentrePost) -> Result<HeightOffset, FieldError> {
    let d = post.diameter_um;
    if !(d.is_finite() && d >= 0.0) {
        return Err(FieldError::new(
            "centre_post.diameter_um",
            d,
            "must be a finite diameter ≥ 0",
        ));
    }
    let h = match post.shape {
        PostShape::Cone => d / 2.0,
        PostShape::Cylinder => -d / 2.0,
    };
    Ok(HeightOffset {
        tool_height_um: h,
        move_tool_um: -h,
    })
}

/// The sag and slope of `surface` along +X at r (mm).
fn along_x(surface: &dyn Surface, r: f64, field: &str) -> Result<(f64, f64), FieldError> {
    let l = surface.local(r, 0.0).map_err(|e| {
        FieldError::new(
            field,
            r,
            format!("the design is not defined there: {}", e.reason),
        )
    })?;
    Ok((l.z, l.zx))
}

/// The X offset of a profile's rise (Newton's method on the design's sag).
fn x_offset_from_profile(
    p: &ProfileRise,
    surface: &dyn Surface,
    part_radius: f64,
) -> Result<XOffset, FieldError> {
    let r1 = positive("profile.inner_radius_mm", p.inner_radius_mm)?;
    let r2 = positive("profile.outer_radius_mm", p.outer_radius_mm)?;
    if r2 <= r1 || r2 > part_radius {
        return Err(FieldError::new(
            "profile.outer_radius_mm",
            r2,
            format!(
                "must lie beyond inner_radius_mm ({}) and within the part radius {} mm",
                short(r1),
                short(part_radius)
            ),
        ));
    }
    if !p.rise_um.is_finite() {
        return Err(FieldError::new(
            "profile.rise_um",
            p.rise_um,
            "must be finite",
        ));
    }
    let want = p.rise_um * 1e-3;
    let field = "profile.outer_radius_mm";
    let (f1, _) = along_x(surface, r1, field)?;
    let (f2, _) = along_x(surface, r2, field)?;
    // F(δ) = [f(r₂ − δ) − f₂] − [f(r₁ − δ) − f₁] − Δe; F′(δ) = f′(r₁ − δ) − f′(r₂ − δ).
    let mut dx = 0.0;
    for _ in 0..NEWTON_STEPS {
        let (a, sa) = along_x(surface, r2 - dx, field)?;
        let (b, sb) = along_x(surface, r1 - dx, field)?;
        let value = (a - f2) - (b - f1) - want;
        let slope = sb - sa;
        if slope.abs() < 1e-12 {
            return Err(FieldError::new(
                "profile",
                format!("the design's slope {} at both radii", short(sa)),
                "must change between the radii to tell an X offset (a flat or a cone has the \
                 same slope everywhere: its error from an X offset is a step at the centre, not \
                 a W or M)",
            ));
        }
        let step = value / slope;
        dx -= step;
        if step.abs() < 1e-15 * (1.0 + dx.abs()) || !dx.is_finite() {
            break;
        }
    }
    if !dx.is_finite() || dx.abs() >= r1 {
        return Err(FieldError::new(
            "profile.rise_um",
            p.rise_um,
            format!(
                "gives no X offset smaller than the inner radius {} mm on this design",
                short(r1)
            ),
        ));
    }
    Ok(XOffset {
        x_offset_um: dx * 1e3,
        move_x_um: -dx * 1e3,
    })
}

/// The X and B-axis Z offsets of a measured radius.
fn offsets_from_radius(
    m: &MeasuredRadius,
    surface: &dyn Surface,
    part_radius: f64,
) -> Result<RadiusOffsets, FieldError> {
    let a = positive("radius.aperture_radius_mm", m.aperture_radius_mm)?;
    if a > part_radius {
        return Err(FieldError::new(
            "radius.aperture_radius_mm",
            a,
            format!("must lie within the part radius {} mm", short(part_radius)),
        ));
    }
    let rm = m.measured_mm;
    if !(rm.is_finite() && rm.abs() > a) {
        return Err(FieldError::new(
            "radius.measured_mm",
            rm,
            format!("must be a radius larger than the aperture {} mm", short(a)),
        ));
    }
    let field = "radius.aperture_radius_mm";
    let mut profile = Vec::with_capacity(PROFILE_SAMPLES);
    for k in 0..PROFILE_SAMPLES {
        let r = a * k as f64 / (PROFILE_SAMPLES - 1) as f64;
        profile.push((r, along_x(surface, r, field)?));
    }
    let design = fit_sphere(&profile, rm).ok_or_else(|| {
        FieldError::new(
            "radius",
            "the design's profile",
            "must be close enough to a sphere over the aperture to fit one",
        )
    })?;
    let g: Vec<f64> = profile.iter().map(|(r, _)| g_of(design, *r)).collect();
    let slope: Vec<f64> = profile.iter().map(|(_, (_, s))| *s).collect();
    let (cov, var) = (covariance(&slope, &g), covariance(&g, &g));
    if cov.abs() < 1e-300 || var <= 0.0 {
        return Err(FieldError::new(
            "radius",
            "the design's profile",
            "must have a slope that a radius change can show",
        ));
    }
    let dx = -(rm - design) * var / cov;
    Ok(RadiusOffsets {
        design_radius_mm: design,
        x: XOffset {
            x_offset_um: dx * 1e3,
            move_x_um: -dx * 1e3,
        },
        b_axis_z_offset_um: (rm - design) * 1e3,
    })
}

/// ∂z/∂R of the sphere `z = p + R ∓ √(R² − r²)` (− for R > 0): `1 − |R|/√(R² − r²)`.
fn g_of(radius: f64, r: f64) -> f64 {
    1.0 - radius.abs() / (radius * radius - r * r).sqrt()
}

/// The covariance of two equally weighted samples.
fn covariance(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - ma) * (y - mb))
        .sum::<f64>()
        / n
}

/// The radius R of the sphere `p + R − √(R² − r²)` fitted by least squares to the profile
/// `(r, (z, _))`, by Gauss–Newton from `guess` (the sign of the guess picks concave or convex).
pub fn fit_sphere(profile: &[(f64, (f64, f64))], guess: f64) -> Option<f64> {
    let mut radius = guess;
    for _ in 0..100 {
        let r_max = profile.iter().map(|(r, _)| r.abs()).fold(0.0, f64::max);
        if radius.abs() <= r_max {
            return None;
        }
        let model: Vec<f64> = profile
            .iter()
            .map(|(r, _)| radius - radius.signum() * (radius * radius - r * r).sqrt())
            .collect();
        let g: Vec<f64> = profile.iter().map(|(r, _)| g_of(radius, *r)).collect();
        let resid: Vec<f64> = profile
            .iter()
            .zip(&model)
            .map(|((_, (z, _)), m)| z - m)
            .collect();
        // The piston drops out of the covariances.
        let step = covariance(&g, &resid) / covariance(&g, &g);
        if !step.is_finite() {
            return None;
        }
        radius += step;
        if step.abs() < 1e-13 * radius.abs() {
            return Some(radius);
        }
    }
    Some(radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_post_gives_the_height_with_its_sign() {
        let cone = CentrePost {
            diameter_um: 12.0,
            shape: PostShape::Cone,
        };
        let h = height_offset(&cone).unwrap();
        assert_eq!((h.tool_height_um, h.move_tool_um), (6.0, -6.0));
        let cyl = CentrePost {
            diameter_um: 4.0,
            shape: PostShape::Cylinder,
        };
        assert_eq!(height_offset(&cyl).unwrap().tool_height_um, -2.0);
        let bad = CentrePost {
            diameter_um: -1.0,
            shape: PostShape::Cone,
        };
        assert_eq!(
            height_offset(&bad).unwrap_err().field,
            "centre_post.diameter_um"
        );
    }
}
