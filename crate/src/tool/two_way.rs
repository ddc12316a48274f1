//! Two-way tool nose radius compensation ([`NoseCompensator::compensate_two_way`], job
//! `strategy.compensation: "two_way"`): the spiral point P = (ρ_s cos θ, ρ_s sin θ, f) is the
//! contact itself and the nose centre lies on the surface normal: `centre = P + r·n`,
//! `n = (−f_x, −f_y, 1)/√(1 + f_x² + f_y²)` (out of the
//! material, towards the tool). The tool is commanded at the centre's polar coordinates:
//! X = ρ_c = |centre_xy| ≥ 0 and C = θ + δ, δ ∈ (−π, π] the centre's polar angle measured from
//! θ (so C is the centre's polar angle, unwrapped to lie within 180° of θ), and Z the tip,
//! `centre z − r`. X thus leaves the spiral. Near the axis, where ρ_s < r·sin(slope), the centre
//! may no longer wind about the axis and C departs far from θ.
//!
//! The centre is a point of the offset surface, which folds (the offset self-intersects, leaving
//! loops in the path) wherever a principal curvature κ of the surface, positive where it is concave
//! towards the tool, reaches 1/r: such points are flagged ([`TwoWay::folds`]), not corrected. A
//! slope kink (a concave V between lenslets) folds the offset too but is not flagged (no curvature
//! to measure there); the concave-zone report ([`crate::tool::reach`], one-way) covers it. The arc
//! is not cut at the part edge in two-way mode.

use super::NoseCompensator;
use crate::surface::{Local, Surface, UndefinedError};

/// The two-way placement of the nose for one spiral point (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoWay {
    /// Nose centre `P + r·n` (x, y, z), mm.
    pub center: [f64; 3],
    /// Commanded X: the centre's radial position `|centre_xy|`, mm, ≥ 0.
    pub x: f64,
    /// C − θ: the centre's polar angle relative to the spiral point's, radians in (−π, π].
    pub c_offset: f64,
    /// Commanded Z: the tool tip `centre z − r`, mm.
    pub z_tip: f64,
    /// The contact P: the spiral point on the surface (x, y, z), mm.
    pub contact: [f64; 3],
    /// Unit surface normal at P, out of the material.
    pub normal: [f64; 3],
    /// Nose angle of the contact in the centre's radial plane, radians (positive: outward).
    pub angle: f64,
    /// The normal tilts further from the tool axis than β/2: the contact lies beyond the
    /// nose arc, and the tool's flank may cut.
    pub at_arc_end: bool,
    /// The offset surface folds here (a principal curvature ≥ 1/r, concave towards the tool):
    /// the path has a loop.
    pub folds: bool,
}

/// The largest principal curvature of the surface at `l`, 1/mm, positive where the surface
/// is concave towards the tool (+Z): `−κ₂` of [`Local::principal_curvatures`]
/// (whose curvatures are positive where the surface is convex towards +Z).
pub fn max_principal_curvature(l: &Local) -> f64 {
    -l.principal_curvatures()[1]
}

impl NoseCompensator {
    /// Two-way compensation of the spiral point at radius `rho_s` and angle with cosine/sine
    /// `(c, s)`: the point is the contact, the nose centre lies r along the normal (see the
    /// module docs).
    pub fn compensate_two_way(
        &self,
        surface: &dyn Surface,
        rho_s: f64,
        c: f64,
        s: f64,
    ) -> Result<TwoWay, UndefinedError> {
        let r = self.nose_radius();
        let (px, py) = (rho_s * c, rho_s * s);
        let l = surface.local(px, py)?;
        let w = (1.0 + l.zx * l.zx + l.zy * l.zy).sqrt();
        let normal = [-l.zx / w, -l.zy / w, 1.0 / w];
        let center = [px + r * normal[0], py + r * normal[1], l.z + r * normal[2]];
        // The centre in the frame of the spiral point's radial line.
        let along = center[0] * c + center[1] * s;
        let across = center[1] * c - center[0] * s;
        let c_offset = across.atan2(along);
        let (sd, cd) = c_offset.sin_cos();
        let (cos_c, sin_c) = (c * cd - s * sd, s * cd + c * sd);
        let n_radial = normal[0] * cos_c + normal[1] * sin_c;
        Ok(TwoWay {
            center,
            x: along.hypot(across),
            c_offset,
            z_tip: center[2] - r,
            contact: [px, py, l.z],
            normal,
            angle: (-n_radial).atan2(normal[2]),
            at_arc_end: r > 0.0 && normal[2].clamp(-1.0, 1.0).acos() > self.half_angle() + 1e-12,
            folds: r * max_principal_curvature(&l) >= 1.0,
        })
    }
}
