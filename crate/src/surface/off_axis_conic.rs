//! Off-axis conic segment: a piece of a parent conic of revolution (an even asphere, so
//! polynomial terms are allowed) whose centre lies at distance d from the parent's axis, turned
//! with that centre on the spindle axis (the usual way an off-axis parabola is diamond turned
//! on-axis when the offset is small, or in a fixture when it is not).
//!
//! Geometry, seen from +Z looking down on the part: the part's X and Y axes are the machine's;
//! the parent's axis is parallel to Z and pierces the XY plane at `−d·(cos α, sin α)`, where α
//! (the clocking angle) is the azimuth from +X towards +Y of the direction from the parent's
//! axis to the part centre. Picture α = 0: the parent's axis lies d to the left (−X) of the
//! part centre, and a concave parent (R > 0) rises towards +X, away from its axis. A part point
//! (x, y) is therefore the parent point `(x_p, y_p) = (x + d·cos α, y + d·sin α)` (a
//! translation; the parent is a surface of revolution, so no rotation of its coordinates is
//! needed), and the sag is measured from the parent's sag at the segment centre:
//!
//! `z(x, y) = p(x_p, y_p) − p(d, 0)`, p the parent sag,
//!
//! so z(0, 0) = 0. The segment keeps its tilt: the gradient at the centre is
//! `p′(d)·(cos α, sin α)`. With `remove_tilt` the plane tangent at the centre,
//! `p′(d)·(x·cos α + y·sin α)`, is subtracted from the sag; that is a shear of the sag along Z,
//! not a rotation of the part (the optical surface is then not the parent's any more unless the
//! tilt is put back by the fixture). Derivatives are the parent's (a translation does not
//! change them), less the constant tilt.

use super::{Asphere, AsphereSpec, Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite, non_negative};
use serde::{Deserialize, Serialize};

/// Job entry of an off-axis conic segment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OffAxisConicSpec {
    /// The parent conic of revolution: `radius_mm` or `curvature_per_mm`, `conic`, and
    /// optionally even polynomial `coefficients` (an off-axis asphere), as for `asphere`.
    pub parent: AsphereSpec,
    /// Off-axis distance d from the parent's axis to the segment centre, mm, ≥ 0 and inside
    /// the parent's rim.
    pub off_axis_distance_mm: f64,
    /// Clocking angle α, degrees, any finite value; default 0: the azimuth of the direction from
    /// the parent's axis to the part centre, so the parent's axis lies at `−d·(cos α, sin α)`.
    #[serde(default)]
    pub clocking_deg: f64,
    /// Subtract the plane tangent at the segment centre from the sag (a shear along Z, not a
    /// rotation of the part); default false.
    #[serde(default)]
    pub remove_tilt: bool,
}

/// An off-axis conic segment, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct OffAxisConic {
    parent: Asphere,
    d: f64,
    clocking_deg: f64,
    /// d·(cos α, sin α): the part centre in parent coordinates.
    centre: (f64, f64),
    /// p at the centre, mm.
    z0: f64,
    /// The tilt subtracted: the parent's gradient at the centre, or 0.
    tilt: (f64, f64),
}

impl OffAxisConic {
    /// Checks a spec and builds the surface (the part disc is not needed).
    pub fn new(spec: &OffAxisConicSpec, _part: PartDisc) -> Result<Self, FieldError> {
        let parent = Asphere::new(&spec.parent).map_err(|e| e.within("parent"))?;
        let d = non_negative("off_axis_distance_mm", spec.off_axis_distance_mm)?;
        let alpha = finite("clocking_deg", spec.clocking_deg)?;
        let (s, c) = alpha.to_radians().sin_cos();
        let centre = (d * c, d * s);
        let at_centre = parent.local(centre.0, centre.1).map_err(|_| {
            FieldError::new(
                "off_axis_distance_mm",
                d,
                format!(
                    "must be less than the parent's rim radius {} mm",
                    parent.rim_radius_mm().unwrap_or(f64::INFINITY)
                ),
            )
        })?;
        let tilt = if spec.remove_tilt {
            (at_centre.zx, at_centre.zy)
        } else {
            (0.0, 0.0)
        };
        Ok(Self {
            parent,
            d,
            clocking_deg: alpha,
            centre,
            z0: at_centre.z,
            tilt,
        })
    }

    /// The parent's sag at the segment centre `p(d, 0)`, mm (the amount subtracted).
    pub fn centre_sag_mm(&self) -> f64 {
        self.z0
    }

    /// The slope subtracted with `remove_tilt` (zero without it).
    pub fn removed_tilt(&self) -> (f64, f64) {
        self.tilt
    }
}

impl Surface for OffAxisConic {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let (xp, yp) = (x + self.centre.0, y + self.centre.1);
        let mut l = self.parent.local(xp, yp).map_err(|e| UndefinedError {
            surface: "off-axis conic",
            x_mm: x,
            y_mm: y,
            radius_mm: x.hypot(y),
            reason: format!(
                "the point lies {} mm from the parent's axis, {}",
                e.radius_mm, e.reason
            ),
        })?;
        l.z -= self.z0 + self.tilt.0 * x + self.tilt.1 * y;
        l.zx -= self.tilt.0;
        l.zy -= self.tilt.1;
        Ok(l)
    }

    fn feature_length_mm(&self) -> f64 {
        f64::INFINITY
    }

    /// The parent's bounds over the disc of radius d + T about its axis (which holds the part):
    /// a section's curvature is `uᵀHu` for the parent's Hessian H, between its eigenvalues
    /// `p″` and `p′/ρ` (the mean of p″ over [0, ρ]), both within the parent's sections'
    /// bounds; its slope is the parent's gradient less the removed tilt, at most the
    /// parent's slope bound plus |tilt|.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.parent
            .section_bounds(self.d + radius_mm.abs())?
            .plus(self.tilt.0.hypot(self.tilt.1), 0.0)
    }

    /// Its section bounds, which hold for any line (the parent's gradient and Hessian bound
    /// them, whatever the direction).
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.section_bounds(radius_mm)
    }

    fn describe(&self) -> String {
        format!(
            "off-axis segment of the {} at d {} mm, clocking {}°{}",
            self.parent.describe(),
            self.d,
            self.clocking_deg,
            if self.tilt == (0.0, 0.0) {
                ""
            } else {
                ", tilt at the centre removed"
            }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(radius: f64, conic: f64, d: f64) -> OffAxisConicSpec {
        OffAxisConicSpec {
            parent: AsphereSpec {
                radius_mm: Some(radius),
                conic,
                ..Default::default()
            },
            off_axis_distance_mm: d,
            clocking_deg: 0.0,
            remove_tilt: false,
        }
    }

    fn build(spec: &OffAxisConicSpec) -> Result<OffAxisConic, FieldError> {
        OffAxisConic::new(spec, PartDisc::centred(5.0))
    }

    #[test]
    fn section_bounds_hold_on_dense_sections() {
        use crate::surface::section_bounds::assert_bounds_hold;
        for (radius, conic, d, clocking, remove_tilt, edge) in [
            (100.0, -1.0, 15.0, 0.0, false, 6.0),
            (100.0, -1.0, 15.0, 30.0, true, 6.0),
            (-60.0, 0.5, 8.0, -100.0, true, 4.0),
            (40.0, -2.0, 0.0, 0.0, false, 5.0),
        ] {
            let mut s = spec(radius, conic, d);
            s.clocking_deg = clocking;
            s.remove_tilt = remove_tilt;
            assert_bounds_hold(&build(&s).unwrap(), edge, 72, 4000);
        }
        // The parent's rim within d + T: none.
        assert!(
            build(&spec(20.0, 0.0, 15.0))
                .unwrap()
                .section_bounds(6.0)
                .is_none()
        );
    }

    #[test]
    fn the_centre_is_the_vertex_and_keeps_the_parent_slope() {
        // Sphere R 50 at d 30: p(30) = 50 − 40 = 10, slope 30/40.
        let s = build(&spec(50.0, 0.0, 30.0)).unwrap();
        let l = s.local(0.0, 0.0).unwrap();
        assert_eq!(l.z, 0.0);
        assert!((s.centre_sag_mm() - 10.0).abs() < 1e-13);
        assert!((l.zx - 0.75).abs() < 1e-15 && l.zy == 0.0);
        // 10 mm further out the parent point is at 40 mm: p = 50 − 30 = 20.
        assert!((s.local(10.0, 0.0).unwrap().z - 10.0).abs() < 1e-13);
    }

    #[test]
    fn remove_tilt_flattens_the_centre() {
        let mut sp = spec(50.0, 0.0, 30.0);
        sp.remove_tilt = true;
        sp.clocking_deg = 90.0;
        let s = build(&sp).unwrap();
        let l = s.local(0.0, 0.0).unwrap();
        assert_eq!((l.z, l.zx, l.zy), (0.0, 0.0, 0.0));
        assert!((s.removed_tilt().1 - 0.75).abs() < 1e-15);
    }

    #[test]
    fn the_centre_must_lie_inside_the_rim() {
        let e = build(&spec(10.0, 0.0, 10.0)).unwrap_err();
        assert_eq!(e.field, "off_axis_distance_mm");
        assert!(e.allowed.contains("rim radius 10 mm"), "{e}");
        let e = build(&spec(10.0, 0.0, -1.0)).unwrap_err();
        assert_eq!(e.field, "off_axis_distance_mm");
        let mut sp = spec(10.0, 0.0, 1.0);
        sp.parent.radius_mm = Some(0.0);
        assert_eq!(build(&sp).unwrap_err().field, "parent.radius_mm");
        // A point whose parent point is beyond the rim names both radii.
        let s = build(&spec(10.0, 0.0, 6.0)).unwrap();
        let e = s.local(5.0, 0.0).unwrap_err();
        assert_eq!(e.radius_mm, 5.0);
        assert!(e.reason.contains("11 mm from the parent's axis"), "{e}");
        assert!(e.reason.contains("rim at radius 10 mm"), "{e}");
    }
}
