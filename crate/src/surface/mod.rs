//! Surfaces `z = f(x, y)` in millimetres with analytic gradient and second derivatives.
//!
//! Sag is measured along +Z from the vertex plane, +Z pointing out of the material towards the
//! tool (DESIGN.md, "Domain primer"). Every family implements [`Surface`]; the planner only ever
//! asks for [`Local`] values (sag, gradient, Hessian) at Cartesian points, and for the radial
//! section at a spindle angle through [`Local::radial`], which is the polar form `z = f(ρ, θ)`
//! of paper 003 eq (17) differentiated along ρ.
//!
//! The surface layer sits on the helpers alone: every family's spec (its job parameters, read
//! by [`crate::job`] above) lives beside its maths, and a family made from data reads it from a
//! [`DataFile`]. A new surface type goes here: a file, a [`SurfaceSpec`] variant, derivative
//! tests against finite differences.
//!
//! The families: even asphere ([`asphere`]), odd asphere ([`odd_asphere`]), zoned asphere
//! ([`zoned_asphere`]), XY polynomial ([`xy_polynomial`]), Zernike ([`zernike`]), Forbes'
//! Q-types ([`q_bfs`], [`q_con`], [`q_2d`], on [`q_polynomials`]), Chebyshev ([`chebyshev`]),
//! biconic ([`biconic`]), toroid ([`toroid`]), off-axis conic ([`off_axis_conic`]), tilted flat
//! ([`tilted_flat`]), lens array ([`lens_array`], paper 004), sinusoid ([`sinusoid`]), compound
//! eye ([`compound_eye`], papers 000/001), progressive lens ([`pal`], paper 003), NURBS
//! ([`nurbs`]) and STEP faces ([`step_face`]), scattered data ([`scattered`], paper 004's
//! RBF), Zemax Grid Sag data ([`grid_sag`], with its `.DAT` reader and writer and the export of
//! any surface to a grid), and any base with decentred terms ([`composite`]); [`reframed`] sees
//! any of them along its normal at a point, and [`turned`] any of them turned 180° about Y (the
//! part cut from the side its +Z points away from). A spec is read from its `"type"` by
//! [`family_tag`].
//!
//! Measured data: [`measured`] reads what metrology hands back after a cut (CSV point clouds,
//! Zygo `.datx` and MetroPro `.dat` maps) into one map of heights in millimetres, oriented into
//! the machine's frame, for the layers above to register and correct.

pub mod asphere;
pub mod biconic;
pub(crate) mod cell_grid;
pub mod chebyshev;
pub mod composite;
pub mod compound_eye;
pub mod data_file;
pub mod family_tag;
pub mod grid_sag;
pub mod import;
pub mod jet;
pub mod lens_array;
pub mod measured;
pub mod nurbs;
pub mod odd_asphere;
pub mod off_axis_conic;
pub mod pal;
pub mod polynomial;
pub mod q_2d;
pub mod q_bfs;
pub mod q_con;
pub mod q_polynomials;
pub mod q_section_bounds;
pub mod reframed;
pub mod scattered;
pub mod section_bounds;
pub mod sinusoid;
pub mod step_face;
pub mod tilted_flat;
pub mod toroid;
pub mod turned;
pub mod xy_polynomial;
pub mod zernike;
pub mod zoned_asphere;

use crate::field::FieldError;
use serde::Serialize;
use thiserror::Error;

pub use asphere::{Asphere, AsphereSpec};
pub use biconic::{Biconic, BiconicSpec};
pub use chebyshev::{Chebyshev, ChebyshevSpec};
pub use composite::{Composite, CompositeSpec, Placed, TermSpec};
pub use compound_eye::{CompoundEye, CompoundEyeSpec};
pub use data_file::DataFile;
pub use grid_sag::{GridSag, GridSagSpec};
pub use lens_array::{LensArray, LensArraySpec};
pub use nurbs::{Nurbs, NurbsSpec};
pub use odd_asphere::{OddAsphere, OddAsphereSpec};
pub use off_axis_conic::{OffAxisConic, OffAxisConicSpec};
pub use pal::{Pal, PalSpec};
pub use q_2d::{Q2d, Q2dSpec};
pub use q_bfs::{QBfs, QBfsSpec};
pub use q_con::{QCon, QConSpec};
pub use reframed::Reframed;
pub use scattered::{Scattered, ScatteredSpec};
pub use section_bounds::SectionBounds;
pub use sinusoid::{Sinusoid, SinusoidSpec};
pub use step_face::{StepFace, StepFaceSpec};
pub use tilted_flat::{TiltedFlat, TiltedFlatSpec};
pub use toroid::{Toroid, ToroidSpec};
pub use turned::Turned;
pub use xy_polynomial::{XyPolynomial, XyPolynomialSpec};
pub use zernike::{Zernike, ZernikeSpec};
pub use zoned_asphere::{ZonedAsphere, ZonedAsphereSpec};

/// Sag and its first and second derivatives at one point (mm, mm/mm, 1/mm).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Local {
    /// Sag z, mm.
    pub z: f64,
    /// ∂z/∂x.
    pub zx: f64,
    /// ∂z/∂y.
    pub zy: f64,
    /// ∂²z/∂x², 1/mm.
    pub zxx: f64,
    /// ∂²z/∂x∂y, 1/mm.
    pub zxy: f64,
    /// ∂²z/∂y², 1/mm.
    pub zyy: f64,
}

/// The radial section of a surface at one spindle angle: sag and its first two derivatives
/// along the signed radial coordinate ρ (the line through the axis at angle θ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Radial {
    /// Sag, mm.
    pub z: f64,
    /// dz/dρ (the slope `f′` of paper 003 eq 20).
    pub slope: f64,
    /// d²z/dρ², 1/mm.
    pub curvature_term: f64,
}

impl Local {
    /// The principal curvatures `[κ₁, κ₂]`, κ₁ ≥ κ₂, 1/mm, positive where the surface is
    /// convex towards +Z: the eigenvalues of the shape operator, computed as the power map
    /// ([`crate::analysis::power_map`]) documents, with full relative accuracy at umbilics.
    pub fn principal_curvatures(&self) -> [f64; 2] {
        let (p, q) = (self.zx, self.zy);
        let (e, f) = (1.0 + p * p, p * q);
        let w = (1.0 + p * p + q * q).sqrt();
        let (ll, mm, nn) = (-self.zxx / w, -self.zxy / w, -self.zyy / w);
        let s11 = ll / e;
        let s12 = (mm - ll * f / e) / w;
        let s22 = (nn * e - 2.0 * mm * f + ll * f * f / e) / (w * w);
        let mean = 0.5 * (s11 + s22);
        let half_gap = (0.5 * (s11 - s22)).hypot(s12);
        [mean + half_gap, mean - half_gap]
    }

    /// The derivatives along the unit direction `(cos θ, sin θ)`.
    pub fn radial(&self, cos_t: f64, sin_t: f64) -> Radial {
        Radial {
            z: self.z,
            slope: self.zx * cos_t + self.zy * sin_t,
            curvature_term: self.zxx * cos_t * cos_t
                + 2.0 * self.zxy * cos_t * sin_t
                + self.zyy * sin_t * sin_t,
        }
    }

    /// ∂z/∂θ at polar radius ρ: `ρ(−zx sin θ + zy cos θ)`, mm per radian.
    pub fn angular_slope(&self, rho: f64, cos_t: f64, sin_t: f64) -> f64 {
        rho * (-self.zx * sin_t + self.zy * cos_t)
    }

    /// The unit normal pointing to +Z (towards the tool).
    pub fn normal(&self) -> [f64; 3] {
        let n = (1.0 + self.zx * self.zx + self.zy * self.zy).sqrt();
        [-self.zx / n, -self.zy / n, 1.0 / n]
    }
}

impl std::ops::Add for Local {
    type Output = Local;
    /// The sum of two sags, term by term: the sum of their jets ([`jet::Jet`]).
    fn add(self, o: Local) -> Local {
        (jet::Jet::from(self) + jet::Jet::from(o)).into()
    }
}

/// The part as a surface sees it: a disc of `radius_mm` centred at `(x_mm, y_mm)` in the
/// surface's own coordinates (the origin, unless the surface is a decentred term of a
/// [`Composite`]). Families that lay features out over the part (a lens array keeps only the
/// lenslets inside it) use it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartDisc {
    /// Part radius, mm.
    pub radius_mm: f64,
    /// Centre, mm.
    pub x_mm: f64,
    /// Centre, mm.
    pub y_mm: f64,
}

impl PartDisc {
    /// A part of radius `radius_mm` on the surface's axis.
    pub fn centred(radius_mm: f64) -> Self {
        Self {
            radius_mm,
            x_mm: 0.0,
            y_mm: 0.0,
        }
    }
}

/// A straight line in the XY plane, `p(t) = (x0, y0) + t·(c, s)` with `(c, s)` a unit vector:
/// the trace of a radial section (through the axis) or of a decentred one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// Point at t = 0, mm.
    pub x0: f64,
    /// Point at t = 0, mm.
    pub y0: f64,
    /// Unit direction, x component.
    pub c: f64,
    /// Unit direction, y component.
    pub s: f64,
}

impl Line {
    /// The radial line through the axis at angle θ with `(cos θ, sin θ) = (c, s)`.
    pub fn radial(c: f64, s: f64) -> Self {
        Self {
            x0: 0.0,
            y0: 0.0,
            c,
            s,
        }
    }

    /// The point at parameter t.
    pub fn at(&self, t: f64) -> (f64, f64) {
        (self.x0 + t * self.c, self.y0 + t * self.s)
    }
}

/// A point where a surface has no value.
///
/// ```
/// use spiralcam::surface::{Asphere, AsphereSpec, Surface};
/// // A sphere of radius 5 mm has no sag beyond 5 mm from its axis.
/// let s = Asphere::new(&AsphereSpec { radius_mm: Some(5.0), ..Default::default() }).unwrap();
/// let e = s.local(6.0, 0.0).unwrap_err();
/// assert!(e.to_string().contains("radius 6 mm"));
/// ```
#[derive(Debug, Clone, PartialEq, Error)]
#[error(
    "surface: {surface} is undefined at radius {} mm (x {} mm, y {} mm): {reason}",
    crate::field::short(*.radius_mm),
    crate::field::short(*.x_mm),
    crate::field::short(*.y_mm)
)]
pub struct UndefinedError {
    /// The family, e.g. `even asphere`.
    pub surface: &'static str,
    /// Where, mm.
    pub x_mm: f64,
    /// Where, mm.
    pub y_mm: f64,
    /// Distance from the axis, mm.
    pub radius_mm: f64,
    /// Why, with the limit.
    pub reason: String,
}

/// A surface of the library: sag with analytic derivatives.
pub trait Surface: Send + Sync + std::fmt::Debug {
    /// Sag, gradient and Hessian at `(x, y)`, mm.
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError>;

    /// Sag only, mm. Families override it where the sag alone is cheaper.
    fn sag(&self, x: f64, y: f64) -> Result<f64, UndefinedError> {
        Ok(self.local(x, y)?.z)
    }

    /// The shortest lateral distance, mm, over which the slope can change sign or jump (a
    /// lenslet's half aperture, a quarter wavelength). Samplers that must not step over a
    /// feature use a fraction of it.
    fn feature_length_mm(&self) -> f64;

    /// Pushes onto `out` the parameters t in (t0, t1), in any order, where the slope of the
    /// section `t ↦ f(line.at(t))` jumps (a lenslet's rim, the edge between two pieces of an
    /// envelope). Samplers of a section add points either side of each, so that between
    /// samples the section is smooth. Smooth surfaces have none, the default.
    fn slope_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        let _ = (line, t0, t1, out);
    }

    /// The radial section at signed radius `rho` of the line through the axis in direction
    /// `(c, s)` — what `local(ρc, ρs)` gives seen along that line ([`Local::radial`]), to the
    /// rounding of either — where the surface keeps that line's section at hand from the last
    /// [`Surface::slope_kinks`] asked about it (scattered data with the L1 RBF:
    /// [`crate::surface::scattered::interpolate::line_section`]). `None` where it does not
    /// (the default): the caller then asks [`Surface::local`].
    fn kept_radial(&self, c: f64, s: f64, rho: f64) -> Option<Result<Radial, UndefinedError>> {
        let _ = (c, s, rho);
        None
    }

    /// The lowest and highest heights over each interval between consecutive signed radii
    /// `ts` (ascending) of the line through the axis along `(c, s)`, bounding every value
    /// [`Surface::kept_radial`] gives there, where the surface keeps that line's section (the
    /// L1 RBF's cubics: their extremes) and all of `ts` lies where the surface is defined;
    /// `None` otherwise (the default). The compensation skips the stretches of the arc these
    /// bounds show cannot hold the contact.
    fn kept_ranges(&self, c: f64, s: f64, ts: &[f64]) -> Option<Vec<[f64; 2]>> {
        let _ = (c, s, ts);
        None
    }

    /// Whether the surface keeps work along the lines it is asked about from one point to the
    /// next (scattered data's line windows, [`crate::surface::scattered::interpolate::cache`]):
    /// a walk on several cores then gives each worker long runs of turns, whose nose arcs slide
    /// along the kept lines, rather than short batches that each start them afresh. False by
    /// default.
    fn keeps_lines(&self) -> bool {
        false
    }

    /// A radius, mm, about `(x, y)` within which the surface has no slope kink: a stretch of
    /// any line inside that disc holds none of [`Surface::slope_kinks`]. The compensation then
    /// need not ask for the kinks under a short step. Infinite where there are none (the
    /// default, with the default `slope_kinks`); every family that has kinks says how far the
    /// nearest may be, or 0 where it cannot say cheaply.
    fn kink_free_radius(&self, x: f64, y: f64) -> f64 {
        let _ = (x, y);
        f64::INFINITY
    }

    /// Bounds on the radial sections (through the axis) over the disc of radius `radius_mm`
    /// about the axis ([`SectionBounds`]), or `None` where the family cannot prove them or has
    /// a slope kink there that is not a ridge (the slope rising across it). `None` by default:
    /// the one-way compensation then searches the whole nose arc.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let _ = radius_mm;
        None
    }

    /// Bounds over the disc of radius `radius_mm` about the axis on every line, whatever its
    /// direction and offset: the gradient's size, and the Hessian's eigenvalues (so every
    /// section's curvature lies between them); they are also [`Surface::section_bounds`]. What
    /// a surface seen along a tilted axis ([`crate::surface::Reframed`]) needs; `None` by
    /// default.
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let _ = radius_mm;
        None
    }

    /// One line restating the definition, for NC headers and reports.
    fn describe(&self) -> String;

    /// Findings about the definition that the operator must read before cutting (a zone
    /// boundary whose slope jumps, a polynomial extrapolated beyond its normalisation); the
    /// plan's report lists them with its own warnings. None by default.
    fn warnings(&self) -> Vec<String> {
        Vec::new()
    }
}

/// The surface of a job, one of the families (JSON: an object with `"type"` naming the family;
/// read by [`family_tag`], which keeps the path of an error inside it).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum SurfaceSpec {
    /// Even asphere (plane and sphere included).
    Asphere(AsphereSpec),
    /// XY polynomial up to degree 10 on an asphere base.
    XyPolynomial(XyPolynomialSpec),
    /// Spherical lenslets on a grid.
    LensArray(LensArraySpec),
    /// Product of two sines.
    Sinusoid(SinusoidSpec),
    /// Zernike polynomial sag (Standard or Fringe) on a conic base.
    Zernike(ZernikeSpec),
    /// Biconic (Rx, Ry, kx, ky).
    Biconic(BiconicSpec),
    /// Toroid.
    Toroid(ToroidSpec),
    /// Off-axis conic segment re-centred on the spindle axis.
    OffAxisConic(OffAxisConicSpec),
    /// Tilted flat.
    TiltedFlat(TiltedFlatSpec),
    /// Compound eye: lenslets on element spheres on a base sphere.
    CompoundEye(CompoundEyeSpec),
    /// Progressive addition lens (paper 003).
    Pal(PalSpec),
    /// NURBS surface from a JSON control net.
    Nurbs(NurbsSpec),
    /// B-spline or NURBS face from a STEP file.
    StepFace(StepFaceSpec),
    /// Scattered data regenerated by an interpolator (paper 004).
    Scattered(ScatteredSpec),
    /// A base plus decentred and rotated terms.
    Composite(CompositeSpec),
    /// Odd asphere: conic plus β1·r + β2·r² + … (OpticStudio "Odd Asphere").
    OddAsphere(OddAsphereSpec),
    /// Forbes' Qbfs asphere (best-fit sphere plus normal departure, 2007).
    QBfs(QBfsSpec),
    /// Forbes' Qcon asphere (conic plus sag departure, 2007).
    QCon(QConSpec),
    /// Forbes' Q₂D freeform polynomials on a best-fit sphere (2012).
    #[serde(rename = "q_2d")]
    Q2d(Q2dSpec),
    /// Chebyshev polynomials Tᵢ(x/X₀)·Tⱼ(y/Y₀) on a conic base.
    Chebyshev(ChebyshevSpec),
    /// Concentric zones, each its own even asphere.
    ZonedAsphere(ZonedAsphereSpec),
    /// Zemax Grid Sag: a `.DAT` grid of sags on a base asphere, bicubic between points.
    GridSag(GridSagSpec),
}

impl SurfaceSpec {
    /// Builds the surface for a part of radius `part_radius_mm` on its axis, checking every
    /// parameter.
    pub fn build(&self, part_radius_mm: f64) -> Result<Box<dyn Surface>, FieldError> {
        self.build_in(PartDisc::centred(part_radius_mm))
            .map_err(|e| e.within("surface"))
    }

    /// Builds the surface for the part disc `part`; field paths are relative to the surface.
    pub fn build_in(&self, part: PartDisc) -> Result<Box<dyn Surface>, FieldError> {
        Ok(match self {
            SurfaceSpec::Asphere(s) => Box::new(Asphere::new(s)?),
            SurfaceSpec::XyPolynomial(s) => Box::new(XyPolynomial::new(s)?),
            SurfaceSpec::LensArray(s) => Box::new(LensArray::new(s, part)?),
            SurfaceSpec::Sinusoid(s) => Box::new(Sinusoid::new(s)?),
            SurfaceSpec::Zernike(s) => Box::new(Zernike::new(s, part)?),
            SurfaceSpec::Biconic(s) => Box::new(Biconic::new(s, part)?),
            SurfaceSpec::Toroid(s) => Box::new(Toroid::new(s, part)?),
            SurfaceSpec::OffAxisConic(s) => Box::new(OffAxisConic::new(s, part)?),
            SurfaceSpec::TiltedFlat(s) => Box::new(TiltedFlat::new(s, part)?),
            SurfaceSpec::CompoundEye(s) => Box::new(CompoundEye::new(s, part)?),
            SurfaceSpec::Pal(s) => Box::new(Pal::new(s, part)?),
            SurfaceSpec::Nurbs(s) => Box::new(Nurbs::new(s, part)?),
            SurfaceSpec::StepFace(s) => Box::new(StepFace::new(s, part)?),
            SurfaceSpec::Scattered(s) => Box::new(Scattered::new(s, part)?),
            SurfaceSpec::Composite(s) => Box::new(Composite::new(s, part)?),
            SurfaceSpec::OddAsphere(s) => Box::new(OddAsphere::new(s)?),
            SurfaceSpec::QBfs(s) => Box::new(QBfs::new(s)?),
            SurfaceSpec::QCon(s) => Box::new(QCon::new(s)?),
            SurfaceSpec::Q2d(s) => Box::new(Q2d::new(s)?),
            SurfaceSpec::Chebyshev(s) => Box::new(Chebyshev::new(s, part)?),
            SurfaceSpec::ZonedAsphere(s) => Box::new(ZonedAsphere::new(s)?),
            SurfaceSpec::GridSag(s) => Box::new(GridSag::new(s)?),
        })
    }

    /// The data files the surface refers to (scattered points, STEP files, Grid Sag DATs), in composites too,
    /// each with its field path relative to the surface (`data`, `terms[1].surface.file`).
    pub fn data_files_mut(&mut self) -> Vec<(String, &mut DataFile)> {
        match self {
            SurfaceSpec::StepFace(s) => vec![("file".into(), &mut s.file)],
            SurfaceSpec::Scattered(s) => vec![("data".into(), &mut s.data)],
            SurfaceSpec::GridSag(s) => vec![("data".into(), &mut s.data)],
            SurfaceSpec::Composite(c) => {
                let mut files = Vec::new();
                for (f, d) in c.base.data_files_mut() {
                    files.push((format!("base.{f}"), d));
                }
                for (k, t) in c.terms.iter_mut().enumerate() {
                    for (f, d) in t.surface.data_files_mut() {
                        files.push((format!("terms[{k}].surface.{f}"), d));
                    }
                }
                files
            }
            _ => Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radial_derivatives_rotate_the_hessian() {
        let l = Local {
            z: 1.0,
            zx: 0.3,
            zy: -0.2,
            zxx: 2.0,
            zxy: 0.5,
            zyy: -1.0,
        };
        let (c, s) = (0.6_f64, 0.8_f64);
        let r = l.radial(c, s);
        assert!((r.slope - (0.3 * 0.6 - 0.2 * 0.8)).abs() < 1e-15);
        assert!((r.curvature_term - (2.0 * 0.36 + 2.0 * 0.5 * 0.48 - 0.64)).abs() < 1e-15);
        let n = l.normal();
        assert!(((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn unknown_fields_and_families_are_rejected() {
        let bad = r#"{"type":"asphere","radius_mm":10,"conic":0,"colour":"red"}"#;
        let e = serde_json::from_str::<SurfaceSpec>(bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains("colour"), "{e}");
        let e = serde_json::from_str::<SurfaceSpec>(r#"{"type":"torus"}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("torus"), "{e}");
    }
}
