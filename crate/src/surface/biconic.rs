//! Biconic (Zemax "Biconic" surface): two conic sections, one in XZ and one in YZ, blended under
//! one square root,
//! `z = (cx·x² + cy·y²) / (1 + √(1 − (1+kx)·cx²·x² − (1+ky)·cy²·y²))`.
//!
//! With `A = cx·x² + cy·y²` and `P = (1+kx)·cx²·x² + (1+ky)·cy²·y²` the sag is `z = A·g(P)`,
//! `g(P) = 1/(1 + w)`, `w = √(1 − P)`, whose derivatives are free of cancellation:
//! `g′ = g²/(2w)` and `g″ = (1 + 3w)·g³/(4w³)`. Then by the product and chain rules
//! `∂z/∂x = A_x·g + A·g′·P_x` and
//! `∂²z/∂x∂y = A_xy·g + (A_x·P_y + A_y·P_x)·g′ + A·(g″·P_x·P_y + g′·P_xy)`, with
//! `A_x = 2cx·x`, `A_xx = 2cx`, `P_x = 2(1+kx)cx²·x`, `P_xx = 2(1+kx)cx²`, `A_xy = P_xy = 0`.
//! With cx = cy and kx = ky it is the conic of revolution of [`super::Asphere`]. It is
//! undefined where `1 − P ≤ 0` (the slope turns vertical there).

use super::{Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite};
use serde::{Deserialize, Serialize};

/// Job entry of a biconic. Give exactly one of `radius_x_mm` and `curvature_x_per_mm`, and
/// exactly one of `radius_y_mm` and `curvature_y_per_mm`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BiconicSpec {
    /// Vertex radius of curvature of the XZ section, Rx, mm, finite and non-zero; positive when
    /// the centre of curvature lies on +Z. Use `curvature_x_per_mm: 0` for a straight section.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_x_mm: Option<f64>,
    /// Vertex curvature of the XZ section cx = 1/Rx, 1/mm, finite; 0 for a straight section.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_x_per_mm: Option<f64>,
    /// Vertex radius of curvature of the YZ section, Ry, mm, finite and non-zero.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_y_mm: Option<f64>,
    /// Vertex curvature of the YZ section cy = 1/Ry, 1/mm, finite; 0 for a straight section.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_y_per_mm: Option<f64>,
    /// Conic constant kx of the XZ section, finite; default 0.
    #[serde(default)]
    pub conic_x: f64,
    /// Conic constant ky of the YZ section, finite; default 0.
    #[serde(default)]
    pub conic_y: f64,
}

/// A biconic, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Biconic {
    cx: f64,
    cy: f64,
    kx: f64,
    ky: f64,
    /// (1 + kx)·cx².
    px: f64,
    /// (1 + ky)·cy².
    py: f64,
}

/// The vertex curvature from exactly one of a radius (finite, non-zero) and a curvature (finite;
/// 0 for a straight section), the rule of [`super::AsphereSpec`], with the field names given.
fn curvature_from(
    radius_field: &str,
    radius: Option<f64>,
    curvature_field: &str,
    curvature: Option<f64>,
) -> Result<f64, FieldError> {
    match (radius, curvature) {
        (Some(r), None) if r.is_finite() && r != 0.0 => Ok(1.0 / r),
        (Some(r), None) => Err(FieldError::new(
            radius_field,
            r,
            format!("must be finite and non-zero (use {curvature_field}: 0 for a flat section)"),
        )),
        (None, Some(c)) => finite(curvature_field, c),
        (Some(r), Some(_)) => Err(FieldError::new(
            radius_field,
            r,
            format!("give {radius_field} or {curvature_field}, not both"),
        )),
        (None, None) => Err(FieldError::new(
            radius_field,
            "missing",
            format!("give {radius_field} or {curvature_field} (0 for a flat section)"),
        )),
    }
}

/// The vertex curvatures `[cx, cy]` of the XZ and YZ sections from the spec fields
/// `radius_x_mm`, `radius_y_mm` (`radii`) and `curvature_x_per_mm`, `curvature_y_per_mm`
/// (`curvatures`) that the biconic and the toroid share, each section by [`curvature_from`].
pub(crate) fn section_curvatures(
    [radius_x, radius_y]: [Option<f64>; 2],
    [curvature_x, curvature_y]: [Option<f64>; 2],
) -> Result<[f64; 2], FieldError> {
    Ok([
        curvature_from("radius_x_mm", radius_x, "curvature_x_per_mm", curvature_x)?,
        curvature_from("radius_y_mm", radius_y, "curvature_y_per_mm", curvature_y)?,
    ])
}

/// `"R 12 mm"`, or `"flat"` for zero curvature.
pub(crate) fn describe_radius(c: f64) -> String {
    super::asphere::radius_words(c, "flat")
}

impl Biconic {
    /// Checks a spec and builds the surface (the part disc is not needed).
    pub fn new(spec: &BiconicSpec, _part: PartDisc) -> Result<Self, FieldError> {
        let [cx, cy] = section_curvatures(
            [spec.radius_x_mm, spec.radius_y_mm],
            [spec.curvature_x_per_mm, spec.curvature_y_per_mm],
        )?;
        let kx = finite("conic_x", spec.conic_x)?;
        let ky = finite("conic_y", spec.conic_y)?;
        Ok(Self {
            cx,
            cy,
            kx,
            ky,
            px: (1.0 + kx) * cx * cx,
            py: (1.0 + ky) * cy * cy,
        })
    }

    /// The half-widths, mm, where the surface turns vertical on the X and on the Y axis
    /// (infinite where it never does).
    pub fn rim_mm(&self) -> (f64, f64) {
        let rim = |p: f64| {
            if p > 0.0 {
                1.0 / p.sqrt()
            } else {
                f64::INFINITY
            }
        };
        (rim(self.px), rim(self.py))
    }
}

impl Surface for Biconic {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let (x2, y2) = (x * x, y * y);
        let q = 1.0 - self.px * x2 - self.py * y2;
        if q.is_nan() || q <= 0.0 {
            let (rx, ry) = self.rim_mm();
            return Err(UndefinedError {
                surface: "biconic",
                x_mm: x,
                y_mm: y,
                radius_mm: x.hypot(y),
                reason: format!(
                    "beyond the biconic's rim (at |x| = {rx} mm on the X axis, |y| = {ry} mm \
                     on the Y axis), where 1 − (1+kx)cx²x² − (1+ky)cy²y² ≤ 0"
                ),
            });
        }
        let w = q.sqrt();
        let a = self.cx * x2 + self.cy * y2;
        let g = 1.0 / (1.0 + w);
        let g1 = 0.5 * g * g / w;
        let g2 = (1.0 + 3.0 * w) * g * g * g / (4.0 * w * w * w);
        let (ax, ay) = (2.0 * self.cx * x, 2.0 * self.cy * y);
        let (px, py) = (2.0 * self.px * x, 2.0 * self.py * y);
        Ok(Local {
            z: a / (1.0 + w),
            zx: ax * g + a * g1 * px,
            zy: ay * g + a * g1 * py,
            zxx: 2.0 * self.cx * g + 2.0 * ax * g1 * px + a * (g2 * px * px + g1 * 2.0 * self.px),
            zxy: (ax * py + ay * px) * g1 + a * g2 * px * py,
            zyy: 2.0 * self.cy * g + 2.0 * ay * g1 * py + a * (g2 * py * py + g1 * 2.0 * self.py),
        })
    }

    fn feature_length_mm(&self) -> f64 {
        f64::INFINITY
    }

    /// A radial section at angle θ is itself a conic profile: with `x = t·cos θ`, `y = t·sin θ`,
    /// `A = c·t²` and `P = p·t²`, `c = cx·cos²θ + cy·sin²θ`, `p = px·cos²θ + py·sin²θ`, so
    /// `f = c·t²/(1 + w)`, `f′ = c·t/w`, `f″ = c/w³` with `w = √(1 − p·t²)` (from
    /// `f = c(1 − w)/p`). c and p are convex combinations of their X and Y values, and w is
    /// least at |t| = T, so `|f′| ≤ max(|cx|, |cy|)·T/w₀` and
    /// `min(cx, cy, 0)/w₀³ ≤ f″ ≤ max(cx, cy, 0)/w₀³` with `w₀ = √(1 − max(px, py, 0)·T²)`;
    /// none where w₀ is not real (the rim inside the disc).
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let q = 1.0 - self.px.max(self.py).max(0.0) * t * t;
        if q.is_nan() || q <= 0.0 {
            return None;
        }
        let w = q.sqrt();
        SectionBounds::FLAT.and(SectionBounds {
            max_slope: self.cx.abs().max(self.cy.abs()) * t / w,
            max_curvature: self.cx.max(self.cy).max(0.0) / (q * w),
            min_curvature: self.cx.min(self.cy).min(0.0) / (q * w),
            has_ridges: false,
            has_valleys: false,
        })
    }

    fn describe(&self) -> String {
        format!(
            "biconic X: {}, kx {}; Y: {}, ky {}",
            describe_radius(self.cx),
            self.kx,
            describe_radius(self.cy),
            self.ky
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn biconic(spec: BiconicSpec) -> Result<Biconic, FieldError> {
        Biconic::new(&spec, PartDisc::centred(5.0))
    }

    #[test]
    fn section_bounds_hold_on_dense_sections() {
        use crate::surface::section_bounds::assert_bounds_hold;
        let spec = |rx, ry, kx, ky| BiconicSpec {
            radius_x_mm: Some(rx),
            radius_y_mm: Some(ry),
            conic_x: kx,
            conic_y: ky,
            ..Default::default()
        };
        for (s, radius) in [
            (spec(40.0, 55.0, -0.8, 0.3), 8.0),
            (spec(-12.0, 30.0, 2.0, -3.0), 4.0),
            (spec(-20.0, -9.0, 0.0, -1.0), 5.0),
        ] {
            assert_bounds_hold(&biconic(s).unwrap(), radius, 72, 4000);
        }
        // A conic of revolution: the bounds are its slope and curvature at the disc's edge.
        let conic = biconic(spec(15.0, 15.0, 0.5, 0.5)).unwrap();
        let (b, slope, curvature) = assert_bounds_hold(&conic, 6.0, 8, 4000);
        assert!(b.max_slope <= slope * (1.0 + 1e-8), "{b:?} {slope}");
        assert!(
            b.max_curvature <= curvature * (1.0 + 1e-8),
            "{b:?} {curvature}"
        );
        // The rim inside the disc: none.
        assert!(conic.section_bounds(15.0 / 1.5f64.sqrt()).is_none());
    }

    #[test]
    fn a_radius_whose_curvature_is_subnormal_is_not_described_as_infinite() {
        let s = biconic(BiconicSpec {
            radius_x_mm: Some(40.0),
            radius_y_mm: Some(f64::MAX),
            ..Default::default()
        })
        .unwrap();
        let text = s.describe();
        assert!(!text.contains("inf"), "{text}");
        assert!(
            text.contains("Y: flat to within a curvature of 5.56"),
            "{text}"
        );
        assert!(text.contains("X: R 40 mm"), "{text}");
    }

    #[test]
    fn a_cylinder_is_a_circle_in_one_direction_only() {
        // Rx 10, flat in Y: z = 10 − √(100 − x²), independent of y.
        let s = biconic(BiconicSpec {
            radius_x_mm: Some(10.0),
            curvature_y_per_mm: Some(0.0),
            ..Default::default()
        })
        .unwrap();
        let l = s.local(6.0, 123.0).unwrap();
        assert!((l.z - 2.0).abs() < 1e-15, "{}", l.z);
        // Slope x/√(R² − x²) = 6/8, curvature R²/(R² − x²)^{3/2} = 100/512.
        assert!((l.zx - 0.75).abs() < 1e-15);
        assert!((l.zxx - 100.0 / 512.0).abs() < 1e-15);
        assert_eq!((l.zy, l.zxy, l.zyy), (0.0, 0.0, 0.0));
        assert_eq!(s.rim_mm(), (10.0, f64::INFINITY));
        let e = s.local(10.0, 0.0).unwrap_err();
        assert!(e.to_string().contains("biconic"), "{e}");
        assert!(e.reason.contains("|x| = 10 mm"), "{e}");
    }

    #[test]
    fn each_section_takes_exactly_one_of_radius_and_curvature() {
        let e = biconic(BiconicSpec {
            radius_x_mm: Some(10.0),
            curvature_x_per_mm: Some(0.1),
            radius_y_mm: Some(5.0),
            ..Default::default()
        })
        .unwrap_err();
        assert_eq!(e.field, "radius_x_mm");
        let e = biconic(BiconicSpec {
            radius_x_mm: Some(10.0),
            ..Default::default()
        })
        .unwrap_err();
        assert_eq!(
            (e.field.as_str(), e.value.as_str()),
            ("radius_y_mm", "missing")
        );
        let e = biconic(BiconicSpec {
            radius_x_mm: Some(10.0),
            radius_y_mm: Some(0.0),
            ..Default::default()
        })
        .unwrap_err();
        assert!(e.allowed.contains("curvature_y_per_mm: 0"), "{e}");
    }
}
