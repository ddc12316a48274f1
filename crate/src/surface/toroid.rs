//! Toroid (OpticStudio's "Toroidal" surface, without its Zernike terms): a profile in the YZ
//! plane, `z_y(y) = cy·y² / (1 + √(1 − (1+ky)·cy²·y²)) + Σᵢ αᵢ·y²ⁱ`, a conic plus even powers
//! of y from y² (OpticStudio's parameters 2–8, α1 … α7 on y² … y¹⁴: "similar to the even
//! aspheric surface sag formula, except the sixteenth order term has been omitted, and the
//! coordinate argument is y", OpticStudio User Guide, "Toroidal"), swept about an axis parallel
//! to Y that crosses the Z axis at `z = Rx` (the radius of rotation, cx = 1/Rx).
//!
//! A profile point lies at distance `d·Rx` from the axis, `d = 1 − cx·z_y`; swept about the
//! axis it traces the circle `(Rx − z)² + x² = (Rx − z_y)²`, so the sag is that of a circle of
//! curvature `e = cx/d` in x on top of the profile:
//! `z = z_y(y) + F(x, e(y))`, `F(x, e) = e·x² / (1 + w)`, `w = √(1 − e²x²)`,
//! the cancellation-free form of `Rx − √((Rx − z_y)² − x²)`, and a cylinder (the profile
//! extruded along X) when cx = 0. Derivatives: `F_x = e·x/w`, `F_xx = e/w³`,
//! `F_e = x²/(w(1+w))`, `F_xe = x/w³`, `F_ee = e·x⁴(1+2w)/(w³(1+w)²)`, with
//! `e′ = e²·z_y′`, `e″ = 2e³·z_y′² + e²·z_y″`, `z_y′ = cy·y/w_y + 2y·P′`,
//! `z_y″ = cy/w_y³ + 2P′ + 4y²·P″` (`w_y = √(1 − (1+ky)cy²y²)`, `P(s) = Σ αᵢ·sⁱ` in s = y²);
//! then `∂z/∂y = z_y′ + F_e·e′`,
//! `∂²z/∂x∂y = F_xe·e′`, `∂²z/∂y² = z_y″ + F_ee·e′² + F_e·e″`.
//!
//! How it differs from the [`super::Biconic`]: every XZ section of a toroid is an exact circle
//! about the one rotation axis, so there is no kx; a biconic's XZ sections are conics whose
//! shape changes with y under the shared square root. Both have the vertex curvatures cx, cy,
//! but away from the axes they differ (at fourth order in x·y already for spheres). With
//! ky = 0 the toroid is an exact torus (profile circle of radius Ry swept on a circle of radius
//! Rx), and with Rx = Ry a sphere.

use super::biconic::{describe_radius, section_curvatures};
use super::{Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite};
use serde::{Deserialize, Serialize};

/// Job entry of a toroid. Give exactly one of `radius_x_mm` and `curvature_x_per_mm`, and
/// exactly one of `radius_y_mm` and `curvature_y_per_mm`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToroidSpec {
    /// Radius of rotation Rx, mm, finite and non-zero: the rotation axis (parallel to Y) crosses
    /// the Z axis at z = Rx, so Rx is also the vertex radius of the XZ section. Use
    /// `curvature_x_per_mm: 0` for a cylinder (no rotation: the profile extruded along X).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_x_mm: Option<f64>,
    /// 1/Rx, 1/mm, finite; 0 for a cylinder.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_x_per_mm: Option<f64>,
    /// Vertex radius Ry of the YZ profile, mm, finite and non-zero; positive when its centre
    /// of curvature lies on +Z.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_y_mm: Option<f64>,
    /// Vertex curvature of the profile cy = 1/Ry, 1/mm, finite; 0 for a straight profile.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_y_per_mm: Option<f64>,
    /// Conic constant ky of the profile, finite; default 0.
    #[serde(default)]
    pub conic_y: f64,
    /// α1, α2, … of y², y⁴, … added to the profile, mm^(1−2i) (OpticStudio's Toroidal
    /// parameters 2–8); at most [`MAX_PROFILE_TERMS`], default none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub profile_coefficients: Vec<f64>,
}

/// The most profile terms: α1 … α10 (y² … y²⁰).
pub const MAX_PROFILE_TERMS: usize = 10;

/// A toroid, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Toroid {
    cx: f64,
    cy: f64,
    ky: f64,
    /// (1 + ky)·cy².
    py: f64,
    /// α1, α2, … of y², y⁴, … (trailing zeros dropped).
    alpha: Vec<f64>,
}

impl Toroid {
    /// Checks a spec and builds the surface (the part disc is not needed).
    pub fn new(spec: &ToroidSpec, _part: PartDisc) -> Result<Self, FieldError> {
        let [cx, cy] = section_curvatures(
            [spec.radius_x_mm, spec.radius_y_mm],
            [spec.curvature_x_per_mm, spec.curvature_y_per_mm],
        )?;
        let ky = finite("conic_y", spec.conic_y)?;
        if spec.profile_coefficients.len() > MAX_PROFILE_TERMS {
            return Err(FieldError::new(
                "profile_coefficients",
                format!("{} terms", spec.profile_coefficients.len()),
                format!("at most {MAX_PROFILE_TERMS} terms (α1 … α{MAX_PROFILE_TERMS})"),
            ));
        }
        for (i, &a) in spec.profile_coefficients.iter().enumerate() {
            finite(
                &format!("profile_coefficients[{i}] (α{}, y^{})", i + 1, 2 * i + 2),
                a,
            )?;
        }
        let mut alpha = spec.profile_coefficients.clone();
        while alpha.last() == Some(&0.0) {
            alpha.pop();
        }
        Ok(Self {
            cx,
            cy,
            ky,
            py: (1.0 + ky) * cy * cy,
            alpha,
        })
    }

    /// `[P, P′, P″]` of `P(s) = Σ αᵢ·sⁱ` at s = y², by Horner's rule.
    fn polynomial(&self, s: f64) -> [f64; 3] {
        let (mut p, mut dp, mut ddp) = (0.0, 0.0, 0.0);
        for &a in self.alpha.iter().rev() {
            ddp = ddp * s + 2.0 * dp;
            dp = dp * s + p;
            p = p * s + a;
        }
        // The loop gave Q(s) = Σ αᵢ·sⁱ⁻¹ and its derivatives: P = s·Q.
        [s * p, p + s * dp, 2.0 * dp + s * ddp]
    }

    /// The profile `[z_y, z_y′, z_y″]` at y, or why it has none.
    fn profile(&self, y: f64) -> Result<[f64; 3], String> {
        let q = 1.0 - self.py * y * y;
        if q.is_nan() || q <= 0.0 {
            return Err(format!(
                "beyond the YZ profile's rim at |y| = {} mm, where 1 − (1+ky)cy²y² ≤ 0",
                1.0 / self.py.sqrt()
            ));
        }
        let w = q.sqrt();
        let s = y * y;
        let [p, p1, p2] = self.polynomial(s);
        Ok([
            // cy·y·y as the conic writes it, so a cylinder is its profile bit for bit.
            self.cy * y * y / (1.0 + w) + p,
            self.cy * y / w + 2.0 * y * p1,
            self.cy / (q * w) + 2.0 * p1 + 4.0 * s * p2,
        ])
    }

    fn undefined(x: f64, y: f64, reason: String) -> UndefinedError {
        UndefinedError {
            surface: "toroid",
            x_mm: x,
            y_mm: y,
            radius_mm: x.hypot(y),
            reason,
        }
    }
}

impl Surface for Toroid {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let [p, p1, p2] = self.profile(y).map_err(|r| Self::undefined(x, y, r))?;
        let d = 1.0 - self.cx * p;
        let qx = d * d - self.cx * self.cx * x * x;
        if qx.is_nan() || qx <= 0.0 {
            return Err(Self::undefined(
                x,
                y,
                format!(
                    "the section at this y is a circle of radius |Rx − z_y| = {} mm about the \
                     rotation axis, and |x| reaches it",
                    (1.0 / self.cx - p).abs()
                ),
            ));
        }
        let e = self.cx / d;
        let w = qx.sqrt() / d.abs();
        let (x2, w3) = (x * x, w * w * w);
        let f = e * x2 / (1.0 + w);
        let fe = x2 / (w * (1.0 + w));
        let fee = e * x2 * x2 * (1.0 + 2.0 * w) / (w3 * (1.0 + w) * (1.0 + w));
        let e1 = e * e * p1;
        let e2 = 2.0 * e * e * e * p1 * p1 + e * e * p2;
        Ok(Local {
            z: p + f,
            zx: e * x / w,
            zy: p1 + fe * e1,
            zxx: e / w3,
            zxy: x / w3 * e1,
            zyy: p2 + fee * e1 * e1 + fe * e2,
        })
    }

    fn feature_length_mm(&self) -> f64 {
        f64::INFINITY
    }

    /// A toroid is a surface of revolution about its axis, so its principal curvatures are the
    /// profile's `z_y″/(1 + z_y′²)^(3/2)` (along the meridians, copies of the profile) and at
    /// most `1/|ρ|` in size along the parallel circles, `ρ = Rx − z_y` their radius. A section's
    /// curvature is `vᵀHv = κₙ·√(1 + |∇z|²)·(1 + (∇z·v)²) ≤ κ·(1 + G²)^(3/2)` (κₙ the normal
    /// curvature along v, at most the larger principal curvature's size κ; G ≥ |∇z|), and its
    /// slope at most G, with `∇z = (e·x, z_y′)/w`, e = 1/ρ, `w = √(1 − e²x²)`. Over the disc,
    /// |z_y|, |z_y′| and |z_y″| are bounded at |y| = T term by term (each grows with |y|; the
    /// conic's curvature `|cy|/w_y³` is largest at its least w_y), so `|ρ| ≥ ρ₀ = |Rx| − max|z_y|`
    /// and `G ≤ √(T²/ρ₀² + S_y²)/√(1 − T²/ρ₀²)`; none where ρ₀ ≤ T. A cylinder (cx = 0) has no
    /// parallel curvature and e = 0.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let q = 1.0 - self.py * t * t;
        if q.is_nan() || q <= 0.0 {
            return None;
        }
        let (c, w) = (self.cy.abs(), q.sqrt());
        let w_least = if self.py > 0.0 { w } else { 1.0 };
        let [mut z0, mut z1, mut z2] = [c * t * t / (1.0 + w), c * t / w, c / w_least.powi(3)];
        for (i, a) in self.alpha.iter().enumerate() {
            let n = (2 * i + 2) as f64;
            let power = t.powi(2 * i as i32);
            z0 += a.abs() * power * t * t;
            z1 += n * a.abs() * power * t;
            z2 += n * (n - 1.0) * a.abs() * power;
        }
        let (ex, parallel) = if self.cx == 0.0 {
            (0.0, 0.0)
        } else {
            let rho = 1.0 / self.cx.abs() - z0;
            if rho.is_nan() || rho <= t {
                return None;
            }
            (t / rho, 1.0 / rho)
        };
        let g = (ex * ex + z1 * z1).sqrt() / (1.0 - ex * ex).sqrt();
        let kappa = z2.max(parallel);
        SectionBounds::FLAT.plus(g, kappa * (1.0 + g * g).powf(1.5))
    }

    fn describe(&self) -> String {
        let sweep = if self.cx == 0.0 {
            "extruded along X (a cylinder with its axis parallel to X)".to_string()
        } else {
            format!(
                "swept about an axis parallel to Y at radius {} mm",
                1.0 / self.cx
            )
        };
        let terms = if self.alpha.is_empty() {
            String::new()
        } else {
            let a: Vec<String> = self
                .alpha
                .iter()
                .enumerate()
                .map(|(i, a)| format!("α{} {a}", i + 1))
                .collect();
            format!(" + {} on y², y⁴, …", a.join(", "))
        };
        format!(
            "toroid: YZ profile {}, ky {}{terms}, {sweep}",
            describe_radius(self.cy),
            self.ky,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toroid(spec: ToroidSpec) -> Result<Toroid, FieldError> {
        Toroid::new(&spec, PartDisc::centred(5.0))
    }

    #[test]
    fn section_bounds_hold_on_dense_sections() {
        use crate::surface::section_bounds::assert_bounds_hold;
        let spec = |rx: f64, ry: f64, ky: f64, alpha: Vec<f64>| ToroidSpec {
            radius_x_mm: (rx != 0.0).then_some(rx),
            curvature_x_per_mm: (rx == 0.0).then_some(0.0),
            radius_y_mm: Some(ry),
            conic_y: ky,
            profile_coefficients: alpha,
            ..Default::default()
        };
        for (s, radius) in [
            (spec(60.0, 35.0, -0.5, vec![]), 8.0),
            (spec(-25.0, 18.0, 0.0, vec![1e-3, -2e-5]), 5.0),
            (spec(30.0, -40.0, -3.0, vec![0.0, 1e-5]), 6.0),
            (spec(0.0, 20.0, 0.5, vec![]), 6.0),
        ] {
            assert_bounds_hold(&toroid(s).unwrap(), radius, 72, 4000);
        }
        // The rotation axis within the disc's reach: none.
        assert!(
            toroid(spec(6.0, 30.0, 0.0, vec![]))
                .unwrap()
                .section_bounds(6.0)
                .is_none()
        );
    }

    #[test]
    fn sections_through_the_vertex_are_the_two_circles() {
        // Rx 20, Ry 10: on the X axis z = 20 − √(400 − x²), on the Y axis z = 10 − √(100 − y²).
        let s = toroid(ToroidSpec {
            radius_x_mm: Some(20.0),
            radius_y_mm: Some(10.0),
            ..Default::default()
        })
        .unwrap();
        assert!((s.local(12.0, 0.0).unwrap().z - 4.0).abs() < 1e-14);
        assert!((s.local(0.0, 6.0).unwrap().z - 2.0).abs() < 1e-14);
        // At y = 6 the profile is 2 mm up, 18 mm from the axis: z = 2 + 18 − √(324 − x²).
        let z = 20.0 - (324.0f64 - 36.0).sqrt();
        assert!((s.local(6.0, 6.0).unwrap().z - z).abs() < 1e-14);
    }

    #[test]
    fn a_cylinder_follows_the_profile_along_x() {
        let s = toroid(ToroidSpec {
            curvature_x_per_mm: Some(0.0),
            radius_y_mm: Some(-10.0),
            conic_y: -1.0,
            ..Default::default()
        })
        .unwrap();
        let l = s.local(1e3, 4.0).unwrap();
        // Parabola y²/(2R).
        assert!((l.z + 16.0 / 20.0).abs() < 1e-15, "{}", l.z);
        assert_eq!((l.zx, l.zxx, l.zxy), (0.0, 0.0, 0.0));
        assert!(s.describe().contains("cylinder"));
    }

    #[test]
    fn the_profile_terms_add_even_powers_of_y() {
        // OpticStudio's toroid: α1 y² + α2 y⁴ + α3 y⁶ on the profile, then swept about Rx.
        let alpha = [2e-3, -1e-5, 3e-7];
        let s = toroid(ToroidSpec {
            radius_x_mm: Some(30.0),
            radius_y_mm: Some(-25.0),
            conic_y: -0.5,
            profile_coefficients: alpha.to_vec(),
            ..Default::default()
        })
        .unwrap();
        let profile = |y: f64| {
            let c = -1.0 / 25.0;
            c * y * y / (1.0 + (1.0 - 0.5 * c * c * y * y).sqrt())
                + alpha[0] * y.powi(2)
                + alpha[1] * y.powi(4)
                + alpha[2] * y.powi(6)
        };
        let (x, y) = (2.5_f64, 3.5_f64);
        // The section at y is a circle about the axis z = Rx through the profile point.
        let zy = profile(y);
        let z = 30.0 - ((30.0 - zy).powi(2) - x * x).sqrt();
        assert!((s.sag(x, y).unwrap() - z).abs() < 1e-14);
        assert!((s.sag(0.0, y).unwrap() - zy).abs() < 1e-15);
        // Derivatives against central differences.
        let h = 1e-5;
        let l = s.local(x, y).unwrap();
        let f = |x: f64, y: f64| s.local(x, y).unwrap();
        let (py, my, px, mx) = (f(x, y + h), f(x, y - h), f(x + h, y), f(x - h, y));
        assert!((l.zy - (py.z - my.z) / (2.0 * h)).abs() < 1e-9);
        assert!((l.zyy - (py.zy - my.zy) / (2.0 * h)).abs() < 1e-8);
        assert!((l.zxy - (py.zx - my.zx) / (2.0 * h)).abs() < 1e-8);
        assert!((l.zxx - (px.zx - mx.zx) / (2.0 * h)).abs() < 1e-8);
        assert!(
            s.describe()
                .contains("α1 0.002, α2 -0.00001, α3 0.0000003 on y²"),
            "{}",
            s.describe()
        );
        let e = toroid(ToroidSpec {
            radius_x_mm: Some(30.0),
            radius_y_mm: Some(-25.0),
            profile_coefficients: vec![0.0, f64::NAN],
            ..Default::default()
        })
        .unwrap_err();
        assert_eq!(e.field, "profile_coefficients[1] (α2, y^4)");
    }

    #[test]
    fn beyond_the_section_circle_is_undefined() {
        let s = toroid(ToroidSpec {
            radius_x_mm: Some(20.0),
            radius_y_mm: Some(10.0),
            ..Default::default()
        })
        .unwrap();
        let e = s.local(18.5, 6.0).unwrap_err();
        assert!(e.reason.contains("radius |Rx − z_y| = 18 mm"), "{e}");
        let e = s.local(0.0, 10.0).unwrap_err();
        assert!(e.reason.contains("|y| = 10 mm"), "{e}");
        assert_eq!(e.surface, "toroid");
    }
}
