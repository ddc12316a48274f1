//! Progressive addition lens (PAL): the freeform front surface of paper 003, section 2
//! (Wei, Zhai, Chen & He, "Study on design and diamond turning of optical freeform surface for
//! progressive addition lenses", 2020), eqs 1 and 9–15.
//!
//! **Construction.** The power along the meridian (the vertical line through the fitting
//! point O) rises from the far power D_F at F = (−L, 0) to D_N = D_F + A at N = (h − L, 0) by the
//! polynomial of eq 9 with the cᵢ of eqs 10–11 ([`power_law`]), and stays at D_F above F and at
//! D_N below N. The powers are front-surface powers, `D = 1000·(n − 1)/r` (eq 1, r in mm; the
//! lens power itself for a plano back surface), so the meridian has curvature
//! `κ(u) = 1/r(u) = D(u)/(1000(n − 1))` (eq 15), slope angle `sin θ = ∫₀ᵘ κ`, and height
//! `T(u) = ∫₀ᵘ tan θ` ([`meridian`]). Each contour curve u(x, y) = const ([`contour`]) carries
//! the sphere of curvature of the meridian at u, centred on the evolute
//! `ε = u − r·sin θ`, `ζ = r·cos θ + T` (eq 14) with radius r(u); the surface is eq 13,
//! `z = ζ(u) − √(r² − (x − ε)² − y²)`, evaluated at u = u(x, y). With a = x − u and
//! `B = κ(a² + y²) + 2a·sin θ` this is computed in the equivalent form
//!
//! `z_paper = T(u) + B / (cos θ + √(cos²θ − κ·B))`,
//!
//! (multiply eq 13 by its conjugate), which has no cancellation, stays valid for r < 0 (a concave
//! front, where eq 13 as printed picks the far branch of the sphere) and for κ = 0 (the sphere
//! becomes the tangent plane). It is undefined where `cos²θ − κB ≤ 0`, i.e.
//! `r² − (x − ε)² − y² ≤ 0`. Since dε/du = −r′·sin θ and dζ/du = r′·cos θ, the sphere at u
//! touches the surface along the meridian: the meridian is an umbilic line whose principal
//! curvatures are both κ(x), so the surface power there is D(x) for every contour family.
//!
//! **Frames.** The paper's X points vertically down along the meridian, Z towards the eye, and
//! the front surface is tangent to the XOY plane at O. We machine that front surface from the
//! object side, so our +Z (out of the material, towards the tool) is the paper's −Z, and
//! `(x, y, z)_ours = (X, −Y, −Z)_paper` (a half turn about X; the surface is even in y, so the
//! y flip changes nothing). The vertex O is at z = 0 and the far point F at x = −L. A
//! positive power (a convex front, the paper's r > 0) curves away from the tool:
//! z ≤ 0 falls away from O, and with A = 0 the surface is the sphere of (our, signed) radius
//! `−1000(n − 1)/D_F`.
//!
//! **Derivatives** are exact: u(x, y) with its gradient and Hessian in closed form, then κ, sin θ,
//! cos θ and T as functions of u (T′ = tan θ, T″ = κ/cos³θ, (sin θ)′ = κ), then the sum,
//! products, quotient and square root above, all by the chain rule through second-order jets
//! ([`super::jet`]).
//!
//! **Where the paper lost information** (its Table 1 keeps only D_F, A, h and L): the orders
//! m = l = 3 — the lowest for which κ is C² at F and N, which the sag's Hessian needs off the
//! meridian (it contains κ″) — giving the quintic `p(t) = 10t³ − 15t⁴ + 6t⁵`; resin of index
//! 1.498 (CR-39); the power held constant outside [F, N]; and explicit contour families with the
//! preset's hyperbolas centred 100 mm above O with 45° asymptotes ([`PalSpec::paper003`]).

pub mod contour;
pub mod gauss_legendre;
pub mod meridian;
pub mod power_law;

use super::jet::Jet;
use super::{Local, PartDisc, Surface, UndefinedError};
use crate::field::{FieldError, in_range, positive};
use contour::Contours;
use meridian::Meridian;
use power_law::PowerLaw;
use serde::{Deserialize, Serialize};

/// Smallest and largest order m, l accepted.
pub const ORDERS: (u32, u32) = (3, 8);

/// Job entry of a progressive addition lens (JSON `"type": "pal"`). Every field defaults to the
/// paper 003 design ([`PalSpec::paper003`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PalSpec {
    /// Far power D_F, dioptres, in [−50, 50]: the front-surface power at the far point F;
    /// positive for a convex front. Default 1 (Table 1).
    #[serde(default = "default_far_power")]
    pub far_power_d: f64,
    /// Addition A = D_N − D_F, dioptres, in [−10, 10] (negative: a degressive lens; 0: a
    /// sphere). Default 2 (Table 1).
    #[serde(default = "default_addition")]
    pub addition_d: f64,
    /// Corridor length h, the distance from F down to the near point N, mm, in [1, 1000].
    /// Default 30 (Table 1).
    #[serde(default = "default_corridor")]
    pub corridor_length_mm: f64,
    /// L, mm, in [−1000, 1000]: the far point F lies at x = −L on the meridian (above O for
    /// L > 0), N at x = h − L. Default 10 (Table 1).
    #[serde(default = "default_far_point")]
    pub far_point_mm: f64,
    /// m, integer in [3, 8]: the first derivative of D(x) that is non-zero at F; higher keeps
    /// the far zone stable longer. Default 3.
    #[serde(default = "default_order")]
    pub far_order: u32,
    /// l, integer in [3, 8]: the first derivative of D(x) that is non-zero at N. Default 3.
    #[serde(default = "default_order")]
    pub near_order: u32,
    /// Refractive index n of the lens material, in [1.3, 2.5], converting power to curvature
    /// (`κ = D/(1000(n − 1))` per mm). Default 1.498 (CR-39 resin).
    #[serde(default = "default_index")]
    pub refractive_index: f64,
    /// The contour curves orthogonal to the meridian. Default: hyperbolas as in the paper
    /// (centre and slope are our choice),
    /// `{"type": "hyperbola", "centre_x_mm": -100, "asymptote_slope": 1}`.
    #[serde(default)]
    pub contours: ContourSpec,
}

/// The contour curves u(x, y) = const that carry the meridian's curvature across the lens.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ContourSpec {
    /// Horizontal lines u = x.
    StraightLine,
    /// Circles centred on the meridian's extension at (X, 0):
    /// `(x − X)² + y² = (u − X)²`.
    Circle {
        /// X, mm, in [−10 000, 10 000]: the common centre, outside the part. Default 100
        /// (below the lens: the contours bend down, towards N, at the sides).
        #[serde(default = "default_circle_centre")]
        centre_x_mm: f64,
    },
    /// Hyperbolas with the common centre (X, 0) and asymptotes `y = ±a·(x − X)`:
    /// `(x − X)² − y²/a² = (u − X)²`.
    Hyperbola {
        /// X, mm, in [−10 000, 10 000], such that the part lies between the asymptotes on one
        /// side of the centre. Default −100 (above the lens: the contours bend down at the
        /// sides).
        #[serde(default = "default_hyperbola_centre")]
        centre_x_mm: f64,
        /// a = |dy/dx| of the asymptotes, in (0, 1000]. Default 1 (45°).
        #[serde(default = "default_asymptote_slope")]
        asymptote_slope: f64,
    },
}

impl Default for ContourSpec {
    fn default() -> Self {
        ContourSpec::Hyperbola {
            centre_x_mm: default_hyperbola_centre(),
            asymptote_slope: default_asymptote_slope(),
        }
    }
}

fn default_far_power() -> f64 {
    1.0
}
fn default_addition() -> f64 {
    2.0
}
fn default_corridor() -> f64 {
    30.0
}
fn default_far_point() -> f64 {
    10.0
}
fn default_order() -> u32 {
    3
}
fn default_index() -> f64 {
    1.498
}
fn default_circle_centre() -> f64 {
    100.0
}
fn default_hyperbola_centre() -> f64 {
    -100.0
}
fn default_asymptote_slope() -> f64 {
    1.0
}

impl Default for PalSpec {
    fn default() -> Self {
        Self {
            far_power_d: default_far_power(),
            addition_d: default_addition(),
            corridor_length_mm: default_corridor(),
            far_point_mm: default_far_point(),
            far_order: default_order(),
            near_order: default_order(),
            refractive_index: default_index(),
            contours: ContourSpec::default(),
        }
    }
}

impl PalSpec {
    /// Paper 003's Table 1 lens, for its Ø70 mm resin blank: far power 1 D, addition 2 D,
    /// corridor h = 30 mm, F at (−10, 0) mm (so N at (20, 0) mm), hyperbolic contours; the
    /// values the paper lost are this module's defaults (m = l = 3, n = 1.498, hyperbolas
    /// centred at (−100, 0) mm with asymptote slope 1).
    pub fn paper003() -> Self {
        Self::default()
    }
}

/// A progressive addition lens surface, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Pal {
    spec: PalSpec,
    meridian: Meridian,
    contours: Contours,
}

impl Pal {
    /// Checks a spec (field paths relative to the surface) against the part disc `part` and
    /// builds the surface.
    pub fn new(spec: &PalSpec, part: PartDisc) -> Result<Self, FieldError> {
        let far = in_range("far_power_d", spec.far_power_d, -50.0, 50.0)?;
        let add = in_range("addition_d", spec.addition_d, -10.0, 10.0)?;
        let h = in_range("corridor_length_mm", spec.corridor_length_mm, 1.0, 1000.0)?;
        let big_l = in_range("far_point_mm", spec.far_point_mm, -1000.0, 1000.0)?;
        let m = order("far_order", spec.far_order)?;
        let l = order("near_order", spec.near_order)?;
        let n = in_range("refractive_index", spec.refractive_index, 1.3, 2.5)?;
        let contours = contours(&spec.contours, part).map_err(|e| e.within("contours"))?;
        let law = PowerLaw::new(far, add, h, big_l, m, l).ok_or_else(|| {
            FieldError::new(
                "far_order",
                m,
                "eqs 10–11 have no solution for these orders",
            )
        })?;
        Ok(Self {
            spec: spec.clone(),
            meridian: Meridian::new(law, n),
            contours,
        })
    }

    /// The power D(x) along the meridian (eq 9, held at D_F above F and D_N below N), D.
    pub fn meridian_power_d(&self, x_mm: f64) -> f64 {
        self.meridian.law().power(x_mm)[0]
    }

    /// The paper's coefficients cᵢ of `(x + L)ⁱ` in eq 9, mm⁻ⁱ, index i = 0 … m + l − 1 (zero
    /// below m).
    pub fn coefficients_per_mm(&self) -> Vec<f64> {
        self.meridian.law().coefficients_per_mm()
    }

    /// The far point F and the near point N, (x, y) in mm.
    pub fn far_and_near_points(&self) -> [(f64, f64); 2] {
        let law = self.meridian.law();
        [(law.far_x(), 0.0), (law.near_x(), 0.0)]
    }

    /// The refractive index the powers refer to.
    pub fn refractive_index(&self) -> f64 {
        self.spec.refractive_index
    }

    /// Sag with its derivatives as a jet, our frame (z = −z_paper), or why there is none.
    fn sag_jet(&self, x: f64, y: f64) -> Result<Jet, String> {
        let u = self.contours.u(x, y)?;
        let p = self.meridian.at(u.v)?;
        let [k0, k1, k2] = p.curvature;
        let kappa = u.compose(k0, k1, k2);
        let sin = u.compose(p.sin, k0, k1);
        let cos = (Jet::constant(1.0) - sin * sin).sqrt();
        let height = u.compose(p.height, p.sin / p.cos, k0 / (p.cos * p.cos * p.cos));
        let a = Jet::var_x(x) - u;
        let y = Jet::var_y(y);
        let b = kappa * (a * a + y * y) + (sin * a).scale(2.0);
        let disc = cos * cos - kappa * b;
        if disc.v.is_nan() || disc.v <= 0.0 {
            return Err(format!(
                "outside the sphere of curvature of the meridian at u = {} mm (radius {} mm): \
                 r² − (x − ε)² − y² ≤ 0",
                u.v,
                1.0 / k0
            ));
        }
        Ok(-(height + b / (cos + disc.sqrt())))
    }
}

/// An order m or l, checked against [`ORDERS`].
fn order(field: &str, v: u32) -> Result<usize, FieldError> {
    if (ORDERS.0..=ORDERS.1).contains(&v) {
        Ok(v as usize)
    } else {
        Err(FieldError::new(
            field,
            v,
            format!("must be an integer in [{}, {}]", ORDERS.0, ORDERS.1),
        ))
    }
}

/// The contour family, checked against the part disc (field paths relative to `contours`).
fn contours(spec: &ContourSpec, part: PartDisc) -> Result<Contours, FieldError> {
    match *spec {
        ContourSpec::StraightLine => Ok(Contours::StraightLine),
        ContourSpec::Circle { centre_x_mm } => {
            let x = centre("centre_x_mm", centre_x_mm)?;
            let distance = (x - part.x_mm).hypot(part.y_mm);
            if distance <= part.radius_mm {
                return Err(FieldError::new(
                    "centre_x_mm",
                    x,
                    format!(
                        "must lie outside the part (farther than {} mm from its centre)",
                        part.radius_mm
                    ),
                ));
            }
            Ok(conic(x, 1.0, part))
        }
        ContourSpec::Hyperbola {
            centre_x_mm,
            asymptote_slope,
        } => {
            let x = centre("centre_x_mm", centre_x_mm)?;
            let a = positive("asymptote_slope", asymptote_slope)?;
            let a = in_range("asymptote_slope", a, 0.0, 1000.0)?;
            let (dx, dy) = (part.x_mm - x, part.y_mm);
            let norm = a.hypot(1.0);
            let clear = (a * dx.abs() - dy.abs()) / norm;
            if clear <= part.radius_mm {
                return Err(FieldError::new(
                    "centre_x_mm",
                    x,
                    format!(
                        "with asymptote slope {a} the part must lie between the asymptotes \
                         y = ±{a}·(x − X) on one side of the centre: the part's centre is {} mm \
                         inside them, more than its radius {} mm needed",
                        clear, part.radius_mm
                    ),
                ));
            }
            Ok(conic(x, -1.0 / (a * a), part))
        }
    }
}

/// A conic family's centre X: within 10 m, so that u = X ∓ √(…) loses < 1e-12 mm to
/// cancellation.
fn centre(field: &str, x: f64) -> Result<f64, FieldError> {
    in_range(field, x, -1e4, 1e4)
}

/// `(x − X)² + k·y² = (u − X)²` with σ chosen so that u = x on the part's side of the centre.
fn conic(centre: f64, k: f64, part: PartDisc) -> Contours {
    Contours::Conic {
        centre,
        k,
        sigma: if centre >= part.x_mm { 1.0 } else { -1.0 },
    }
}

impl Surface for Pal {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let z = self.sag_jet(x, y).map_err(|reason| UndefinedError {
            surface: "progressive addition lens",
            x_mm: x,
            y_mm: y,
            radius_mm: x.hypot(y),
            reason,
        })?;
        Ok(z.into())
    }

    /// A tenth of the corridor: the power law, a polynomial of degree ≤ 15 across h, changes
    /// on that scale; the surface has no shorter feature.
    fn feature_length_mm(&self) -> f64 {
        self.spec.corridor_length_mm / 10.0
    }

    fn describe(&self) -> String {
        let s = &self.spec;
        let contours = match s.contours {
            ContourSpec::StraightLine => "straight-line contours".to_string(),
            ContourSpec::Circle { centre_x_mm } => {
                format!("circular contours centred at x {centre_x_mm} mm")
            }
            ContourSpec::Hyperbola {
                centre_x_mm,
                asymptote_slope,
            } => format!(
                "hyperbolic contours centred at x {centre_x_mm} mm, asymptote slope {asymptote_slope}"
            ),
        };
        format!(
            "progressive addition lens: far power {} D, addition {} D, corridor {} mm, F at x {} mm, \
             m {}, l {}, n {}, {contours}",
            s.far_power_d,
            s.addition_d,
            s.corridor_length_mm,
            -s.far_point_mm,
            s.far_order,
            s.near_order,
            s.refractive_index
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn part() -> PartDisc {
        PartDisc::centred(35.0)
    }

    #[test]
    fn the_paper_lens_is_table_1_with_the_stated_choices() {
        let spec = PalSpec::paper003();
        assert_eq!(
            (
                spec.far_power_d,
                spec.addition_d,
                spec.corridor_length_mm,
                spec.far_point_mm
            ),
            (1.0, 2.0, 30.0, 10.0)
        );
        let pal = Pal::new(&spec, part()).unwrap();
        assert_eq!(pal.far_and_near_points(), [(-10.0, 0.0), (20.0, 0.0)]);
        assert_eq!(pal.meridian_power_d(-10.0), 1.0);
        assert_eq!(pal.meridian_power_d(20.0), 3.0);
        // Halfway down the corridor the quintic gives exactly half the addition.
        assert!((pal.meridian_power_d(5.0) - 2.0).abs() < 1e-14);
        let c = pal.coefficients_per_mm();
        assert_eq!(c.len(), 6);
        assert!((c[3] - 10.0 / 27_000.0).abs() < 1e-18);
        assert_eq!(pal.local(0.0, 0.0).unwrap().z, 0.0);
        assert!(
            pal.describe().contains("hyperbolic contours"),
            "{}",
            pal.describe()
        );
    }

    #[test]
    fn json_defaults_unknown_fields_and_contour_types() {
        let spec: PalSpec = serde_json::from_str("{}").unwrap();
        assert_eq!(spec, PalSpec::paper003());
        let spec: PalSpec =
            serde_json::from_str(r#"{"contours":{"type":"circle"},"far_order":4}"#).unwrap();
        assert_eq!(
            spec.contours,
            ContourSpec::Circle {
                centre_x_mm: default_circle_centre()
            }
        );
        assert_eq!(spec.far_order, 4);
        let e = serde_json::from_str::<PalSpec>(r#"{"add":2}"#).unwrap_err();
        assert!(e.to_string().contains("add"), "{e}");
        let e = serde_json::from_str::<PalSpec>(
            r#"{"contours":{"type":"circle","centre_x_mm":80,"slope":1}}"#,
        )
        .unwrap_err();
        assert!(e.to_string().contains("slope"), "{e}");
        let e = serde_json::from_str::<PalSpec>(r#"{"contours":{"type":"ellipse"}}"#).unwrap_err();
        assert!(e.to_string().contains("ellipse"), "{e}");
        let back: PalSpec =
            serde_json::from_str(&serde_json::to_string(&PalSpec::paper003()).unwrap()).unwrap();
        assert_eq!(back, PalSpec::paper003());
    }

    #[test]
    fn spec_errors_name_the_field() {
        let bad = |f: &dyn Fn(&mut PalSpec)| {
            let mut spec = PalSpec::paper003();
            f(&mut spec);
            Pal::new(&spec, part()).unwrap_err()
        };
        assert_eq!(bad(&|s| s.far_power_d = f64::NAN).field, "far_power_d");
        assert_eq!(bad(&|s| s.addition_d = 11.0).field, "addition_d");
        assert_eq!(
            bad(&|s| s.corridor_length_mm = 0.0).field,
            "corridor_length_mm"
        );
        assert_eq!(
            bad(&|s| s.far_point_mm = f64::INFINITY).field,
            "far_point_mm"
        );
        assert_eq!(bad(&|s| s.far_order = 2).field, "far_order");
        assert_eq!(bad(&|s| s.near_order = 9).field, "near_order");
        assert_eq!(bad(&|s| s.refractive_index = 1.0).field, "refractive_index");
        let e = bad(&|s| s.contours = ContourSpec::Circle { centre_x_mm: -30.0 });
        assert_eq!(e.field, "contours.centre_x_mm");
        assert!(e.allowed.contains("outside the part"), "{e}");
        // 45° asymptotes from (−45, 0): the part's centre is 31.8 mm from them, less than 35.
        let e = bad(&|s| {
            s.contours = ContourSpec::Hyperbola {
                centre_x_mm: -45.0,
                asymptote_slope: 1.0,
            }
        });
        assert_eq!(e.field, "contours.centre_x_mm");
        let e = bad(&|s| {
            s.contours = ContourSpec::Hyperbola {
                centre_x_mm: -60.0,
                asymptote_slope: 0.0,
            }
        });
        assert_eq!(e.field, "contours.asymptote_slope");
        let e = bad(&|s| s.contours = ContourSpec::Circle { centre_x_mm: 1e5 });
        assert_eq!(e.field, "contours.centre_x_mm");
        // The same hyperbolas fit a part decentred away from the asymptotes.
        let off = PartDisc {
            radius_mm: 35.0,
            x_mm: 10.0,
            y_mm: 0.0,
        };
        let spec = PalSpec {
            contours: ContourSpec::Hyperbola {
                centre_x_mm: -45.0,
                asymptote_slope: 1.0,
            },
            ..PalSpec::paper003()
        };
        assert!(Pal::new(&spec, off).is_ok());
    }

    #[test]
    fn undefined_points_name_the_family_and_the_radius() {
        // A 40 D front of index 1.498 has r = 12.45 mm: no sag 20 mm out along y, and the
        // meridian turns vertical at u = 12.45 mm.
        let spec = PalSpec {
            far_power_d: 40.0,
            addition_d: 0.0,
            contours: ContourSpec::StraightLine,
            ..PalSpec::paper003()
        };
        let pal = Pal::new(&spec, PartDisc::centred(5.0)).unwrap();
        let e = pal.local(0.0, 20.0).unwrap_err();
        assert_eq!(e.radius_mm, 20.0);
        assert!(e.to_string().contains("progressive addition lens"), "{e}");
        assert!(e.reason.contains("sphere of curvature"), "{e}");
        let e = pal.local(20.0, 0.0).unwrap_err();
        assert!(e.reason.contains("vertical"), "{e}");
        assert!(pal.local(f64::NAN, 0.0).is_err());
    }
}
