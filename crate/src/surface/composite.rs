//! Composition: a surface is a base plus any number of added terms (an asphere plus a Zernike
//! deformation plus a lens array, say), each term optionally decentred by (dx, dy) and rotated
//! by φ about Z.
//!
//! A placed term `g` gives `z(p) = g(Rᵀ(p − d))` with R the rotation by φ, so its gradient is
//! `R·∇g` and its Hessian `R·H_g·Rᵀ` at the mapped point; a line maps to the line
//! `Rᵀ(o − d) + t·Rᵀu` with the same parameter, so slope kinks carry over unchanged. The sum's
//! derivatives are the sums of the parts'; its feature length is the shortest of the parts'.

use super::{Line, Local, PartDisc, SectionBounds, Surface, SurfaceSpec, UndefinedError};
use crate::field::{FieldError, finite};
use serde::{Deserialize, Serialize};

/// A term of a composite: a surface and where it sits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TermSpec {
    /// The term's surface (any family).
    pub surface: SurfaceSpec,
    /// Decentre along X of the term's origin, mm; default 0.
    #[serde(default)]
    pub decenter_x_mm: f64,
    /// Decentre along Y of the term's origin, mm; default 0.
    #[serde(default)]
    pub decenter_y_mm: f64,
    /// Rotation of the term about Z, degrees, counter-clockwise seen from +Z; default 0.
    #[serde(default)]
    pub rotation_deg: f64,
    /// Marks the measured correction that `spiralcam correct` wrote (a grid of −gain ×
    /// residual): a later correction of the job adds its residual to this term instead of
    /// adding a term; default false. It does not change the sag.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub correction: bool,
}

/// Job entry of a composite surface: `base + Σ terms`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompositeSpec {
    /// The base surface, on the spindle axis.
    pub base: Box<SurfaceSpec>,
    /// Terms added to the base; at least one.
    pub terms: Vec<TermSpec>,
}

/// A surface moved by a decentre and a rotation about Z.
#[derive(Debug)]
pub struct Placed {
    inner: Box<dyn Surface>,
    dx: f64,
    dy: f64,
    cos: f64,
    sin: f64,
    rotation_deg: f64,
}

impl Placed {
    /// `inner` with its origin at (dx, dy) and turned by `rotation_deg` about Z.
    pub fn new(inner: Box<dyn Surface>, dx: f64, dy: f64, rotation_deg: f64) -> Self {
        let (sin, cos) = rotation_deg.to_radians().sin_cos();
        Self {
            inner,
            dx,
            dy,
            cos,
            sin,
            rotation_deg,
        }
    }

    /// A part point in the term's own coordinates: Rᵀ(p − d).
    fn to_inner(&self, x: f64, y: f64) -> (f64, f64) {
        let (u, v) = (x - self.dx, y - self.dy);
        (self.cos * u + self.sin * v, -self.sin * u + self.cos * v)
    }

    /// A part vector in the term's own coordinates: Rᵀv.
    fn turn_in(&self, u: f64, v: f64) -> (f64, f64) {
        (self.cos * u + self.sin * v, -self.sin * u + self.cos * v)
    }
}

impl Surface for Placed {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let (xi, yi) = self.to_inner(x, y);
        let l = self.inner.local(xi, yi)?;
        let (c, s) = (self.cos, self.sin);
        // R·g and R·H·Rᵀ with R = [[c, −s], [s, c]].
        let (a, b, d) = (l.zxx, l.zxy, l.zyy);
        Ok(Local {
            z: l.z,
            zx: c * l.zx - s * l.zy,
            zy: s * l.zx + c * l.zy,
            zxx: c * c * a - 2.0 * c * s * b + s * s * d,
            zxy: c * s * (a - d) + (c * c - s * s) * b,
            zyy: s * s * a + 2.0 * c * s * b + c * c * d,
        })
    }

    fn sag(&self, x: f64, y: f64) -> Result<f64, UndefinedError> {
        let (xi, yi) = self.to_inner(x, y);
        self.inner.sag(xi, yi)
    }

    fn feature_length_mm(&self) -> f64 {
        self.inner.feature_length_mm()
    }

    fn slope_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        let (x0, y0) = self.to_inner(line.x0, line.y0);
        let (c, s) = self.turn_in(line.c, line.s);
        self.inner.slope_kinks(Line { x0, y0, c, s }, t0, t1, out);
    }

    /// The term's.
    fn keeps_lines(&self) -> bool {
        self.inner.keeps_lines()
    }

    /// The term's own at the point in its coordinates (a rigid move keeps distances).
    fn kink_free_radius(&self, x: f64, y: f64) -> f64 {
        let (xi, yi) = self.to_inner(x, y);
        self.inner.kink_free_radius(xi, yi)
    }

    /// The term's own where it is not decentred (turned about the axis, its radial sections
    /// are its own at θ − φ); where it is, its [`Surface::disc_bounds`] over the disc moved
    /// with it (radius + decentre), which hold on any line.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        if self.dx != 0.0 || self.dy != 0.0 {
            return self.disc_bounds(radius_mm);
        }
        self.inner.section_bounds(radius_mm)
    }

    /// The term's disc bounds over the disc that holds the moved one (turning changes none).
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.inner
            .disc_bounds(radius_mm.abs() + self.dx.hypot(self.dy))
    }

    fn warnings(&self) -> Vec<String> {
        self.inner.warnings()
    }

    fn describe(&self) -> String {
        let moved = self.dx != 0.0 || self.dy != 0.0 || self.rotation_deg != 0.0;
        if moved {
            format!(
                "{} decentred by ({}, {}) mm, rotated {}°",
                self.inner.describe(),
                self.dx,
                self.dy,
                self.rotation_deg
            )
        } else {
            self.inner.describe()
        }
    }
}

/// A base plus placed terms, validated.
#[derive(Debug)]
pub struct Composite {
    parts: Vec<Box<dyn Surface>>,
}

impl Composite {
    /// Checks a spec and builds the surface for the part disc `part` (in the composite's own
    /// coordinates).
    pub fn new(spec: &CompositeSpec, part: PartDisc) -> Result<Self, FieldError> {
        if spec.terms.is_empty() {
            return Err(FieldError::new(
                "terms",
                "[]",
                "at least one term (or use the base family alone)",
            ));
        }
        let mut parts = vec![spec.base.build_in(part).map_err(|e| e.within("base"))?];
        for (i, t) in spec.terms.iter().enumerate() {
            let field = |name: &str| format!("terms[{i}].{name}");
            let dx = finite(&field("decenter_x_mm"), t.decenter_x_mm)?;
            let dy = finite(&field("decenter_y_mm"), t.decenter_y_mm)?;
            let rot = finite(&field("rotation_deg"), t.rotation_deg)?;
            // The part disc in the term's own coordinates.
            let placed = Placed::new(Box::new(super::asphere::Asphere::plane()), dx, dy, rot);
            let (cx, cy) = placed.to_inner(part.x_mm, part.y_mm);
            let disc = PartDisc {
                radius_mm: part.radius_mm,
                x_mm: cx,
                y_mm: cy,
            };
            let inner = t
                .surface
                .build_in(disc)
                .map_err(|e| e.within(&format!("terms[{i}].surface")))?;
            parts.push(Box::new(Placed { inner, ..placed }));
        }
        Ok(Self { parts })
    }
}

impl Surface for Composite {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let mut sum = Local::default();
        for p in &self.parts {
            sum = sum + p.local(x, y)?;
        }
        Ok(sum)
    }

    fn sag(&self, x: f64, y: f64) -> Result<f64, UndefinedError> {
        let mut z = 0.0;
        for p in &self.parts {
            z += p.sag(x, y)?;
        }
        Ok(z)
    }

    fn feature_length_mm(&self) -> f64 {
        self.parts
            .iter()
            .map(|p| p.feature_length_mm())
            .fold(f64::INFINITY, f64::min)
    }

    fn slope_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        for p in &self.parts {
            p.slope_kinks(line, t0, t1, out);
        }
    }

    /// Whether any part does.
    fn keeps_lines(&self) -> bool {
        self.parts.iter().any(|p| p.keeps_lines())
    }

    /// The nearest of the parts'.
    fn kink_free_radius(&self, x: f64, y: f64) -> f64 {
        self.parts
            .iter()
            .map(|p| p.kink_free_radius(x, y))
            .fold(f64::INFINITY, f64::min)
    }

    /// The sum of the parts' bounds ([`SectionBounds::and`]) where every part gives them: the
    /// sum's slope kinks are its parts', each a ridge, and a ridge plus a smooth or ridged
    /// section is a ridge.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let mut parts = self.parts.iter().map(|p| p.section_bounds(radius_mm));
        let first = parts.next()??;
        parts.try_fold(first, |sum, b| sum.and(b?))
    }

    /// The sum of the parts' disc bounds, where every part gives them.
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let mut parts = self.parts.iter().map(|p| p.disc_bounds(radius_mm));
        let first = parts.next()??;
        parts.try_fold(first, |sum, b| sum.and(b?))
    }

    fn warnings(&self) -> Vec<String> {
        self.parts.iter().flat_map(|p| p.warnings()).collect()
    }

    fn describe(&self) -> String {
        self.parts
            .iter()
            .map(|p| p.describe())
            .collect::<Vec<_>>()
            .join(" + ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{LensArraySpec, SinusoidSpec};

    fn sinusoid() -> SurfaceSpec {
        SurfaceSpec::Sinusoid(SinusoidSpec {
            amplitude_mm: 0.001,
            wavelength_x_mm: 2.0,
            wavelength_y_mm: 3.0,
            phase_x_deg: 20.0,
            phase_y_deg: 50.0,
        })
    }

    #[test]
    fn a_placed_term_is_the_term_at_the_moved_point() {
        let inner = sinusoid().build(5.0).unwrap();
        let (dx, dy, rot) = (0.7, -1.2, 35.0);
        let placed = Placed::new(sinusoid().build(5.0).unwrap(), dx, dy, rot);
        let (s, c) = f64::to_radians(rot).sin_cos();
        for &(x, y) in &[(0.0, 0.0), (1.3, 2.1), (-2.0, 0.4)] {
            let (u, v) = (x - dx, y - dy);
            let (xi, yi) = (c * u + s * v, -s * u + c * v);
            assert_eq!(
                placed.local(x, y).unwrap().z,
                inner.local(xi, yi).unwrap().z
            );
            // Gradient and Hessian against central differences of the placed sag.
            let h = 1e-5;
            let l = placed.local(x, y).unwrap();
            let f = |x: f64, y: f64| placed.local(x, y).unwrap();
            let fd_x = (f(x + h, y).z - f(x - h, y).z) / (2.0 * h);
            let fd_y = (f(x, y + h).z - f(x, y - h).z) / (2.0 * h);
            assert!((l.zx - fd_x).abs() < 1e-10 && (l.zy - fd_y).abs() < 1e-10);
            let fd_xx = (f(x + h, y).zx - f(x - h, y).zx) / (2.0 * h);
            let fd_xy = (f(x, y + h).zx - f(x, y - h).zx) / (2.0 * h);
            let fd_yy = (f(x, y + h).zy - f(x, y - h).zy) / (2.0 * h);
            assert!((l.zxx - fd_xx).abs() < 1e-9, "{} {fd_xx}", l.zxx);
            assert!((l.zxy - fd_xy).abs() < 1e-9, "{} {fd_xy}", l.zxy);
            assert!((l.zyy - fd_yy).abs() < 1e-9, "{} {fd_yy}", l.zyy);
        }
    }

    #[test]
    fn a_decentred_lens_array_keeps_its_kinks_and_the_part_disc() {
        let spec = CompositeSpec {
            base: Box::new(SurfaceSpec::Asphere(crate::surface::AsphereSpec {
                curvature_per_mm: Some(0.0),
                ..Default::default()
            })),
            terms: vec![TermSpec {
                surface: SurfaceSpec::LensArray(LensArraySpec::paper004()),
                decenter_x_mm: 0.5,
                decenter_y_mm: 0.0,
                rotation_deg: 30.0,
                correction: false,
            }],
        };
        let comp = Composite::new(&spec, PartDisc::centred(5.0)).unwrap();
        // The lenslet the term had at its origin now sits at (0.5, 0).
        let sag = LensArraySpec::paper004();
        let vertex = -(sag.lens_radius_mm - (sag.lens_radius_mm.powi(2) - 0.25).sqrt());
        assert!((comp.sag(0.5, 0.0).unwrap() - vertex).abs() < 1e-15);
        // Kinks along the X axis: the rim of that lenslet at x = 0 and x = 1.
        let mut kinks = Vec::new();
        comp.slope_kinks(Line::radial(1.0, 0.0), -0.2, 1.2, &mut kinks);
        kinks.sort_by(f64::total_cmp);
        assert!(
            kinks.len() == 2 && kinks[0].abs() < 1e-12 && (kinks[1] - 1.0).abs() < 1e-12,
            "{kinks:?}"
        );
        // The term's lenslet at (4, 2) lies inside the part seen from the term's origin
        // (|c| + a/2 = 4.97 mm) but, placed, its aperture would cross the part edge: land.
        let (c30, s30) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let edge = (0.5 + 4.0 * c30 - 2.0 * s30, 4.0 * s30 + 2.0 * c30);
        assert!(20f64.sqrt() + 0.5 <= 5.0 && edge.0.hypot(edge.1) + 0.5 > 5.0);
        assert_eq!(comp.sag(edge.0, edge.1).unwrap(), 0.0);
        let unplaced = LensArraySpec::paper004();
        let lone = SurfaceSpec::LensArray(unplaced).build(5.0).unwrap();
        assert!(lone.sag(4.0, 2.0).unwrap() < 0.0);
    }

    #[test]
    fn terms_are_checked_with_their_path() {
        let spec = CompositeSpec {
            base: Box::new(sinusoid()),
            terms: vec![TermSpec {
                surface: SurfaceSpec::LensArray(LensArraySpec {
                    pitch_mm: 0.0,
                    ..LensArraySpec::paper004()
                }),
                decenter_x_mm: 0.0,
                decenter_y_mm: 0.0,
                rotation_deg: 0.0,
                correction: false,
            }],
        };
        assert_eq!(
            Composite::new(&spec, PartDisc::centred(5.0))
                .unwrap_err()
                .field,
            "terms[0].surface.pitch_mm"
        );
        let none = CompositeSpec {
            base: Box::new(sinusoid()),
            terms: vec![],
        };
        assert_eq!(
            Composite::new(&none, PartDisc::centred(5.0))
                .unwrap_err()
                .field,
            "terms"
        );
    }
}
