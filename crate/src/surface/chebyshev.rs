//! Chebyshev polynomial surface on a conic base: `z = asphere(x, y) + Σ cᵢⱼ·Tᵢ(x/X₀)·Tⱼ(y/Y₀)`,
//! Tₙ the Chebyshev polynomials of the first kind (T₀ = 1, T₁ = t, Tₙ₊₁ = 2t·Tₙ − Tₙ₋₁), X₀ and
//! Y₀ the normalisation half-widths, every cᵢⱼ in mm. This is the sag of OpticStudio's
//! "Chebyshev Polynomial" surface (OpticStudio User Guide: a base radius and the product basis
//! Tᵢ(x/X₀)·Tⱼ(y/Y₀) with "normalized polynomial coefficients", up to order 14 in each of x
//! and y; accepted here up to 20), with the full polynomials, constants included.
//!
//! **Half-widths.** Given in the job, or by default the part's extent about the surface's origin
//! (|x_c| + R and |y_c| + R for a part disc of radius R centred at (x_c, y_c)), so that the part
//! lies in [−1, 1]².
//!
//! **Outside [−1, 1].** OpticStudio leaves the surface undefined there (rays are vignetted). Here
//! the polynomials continue, so that the path's first point, which may lie one angle step
//! outside the part, and a nose arc reaching the edge have a value; a part that extends beyond
//! the half-widths is reported as a warning ([`Surface::warnings`]), naming how far, because
//! the designer never analysed the extrapolation.
//!
//! Derivatives by the recurrences `Tₙ₊₁′ = 2Tₙ + 2t·Tₙ′ − Tₙ₋₁′`, `Tₙ₊₁″ = 4Tₙ′ + 2t·Tₙ″ − Tₙ₋₁″`,
//! scaled by 1/X₀ and 1/Y₀.

use super::{Asphere, AsphereSpec, Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite, positive};
use serde::{Deserialize, Serialize};

/// The highest order in each of x and y.
pub const MAX_ORDER: u32 = 20;

/// One term `coefficient_mm · T_x(x/X₀) · T_y(y/Y₀)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChebyshevTerm {
    /// Order i of T_i(x/X₀), 0 … 20.
    pub x: u32,
    /// Order j of T_j(y/Y₀), 0 … 20.
    pub y: u32,
    /// cᵢⱼ, mm.
    pub coefficient_mm: f64,
}

/// Job entry of a Chebyshev surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChebyshevSpec {
    /// The base asphere (use `{"curvature_per_mm": 0}` for a plane).
    pub base: AsphereSpec,
    /// X₀, mm, > 0; default the part's extent along x (module docs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub half_width_x_mm: Option<f64>,
    /// Y₀, mm, > 0; default the part's extent along y.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub half_width_y_mm: Option<f64>,
    /// The terms; each (x, y) pair at most once.
    pub terms: Vec<ChebyshevTerm>,
}

/// A Chebyshev surface, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Chebyshev {
    base: Asphere,
    hx: f64,
    hy: f64,
    /// (i, j, cᵢⱼ), non-zero.
    terms: Vec<(usize, usize, f64)>,
    /// Highest orders in x and y.
    order: (usize, usize),
    /// How far the part reaches beyond [−1, 1] in x̂ and ŷ (0 if inside).
    overreach: (f64, f64),
}

/// `[Tₙ(t), Tₙ′(t), Tₙ″(t)]` for n = 0 … `order`.
fn chebyshev_table(t: f64, order: usize) -> [[f64; 3]; MAX_ORDER as usize + 1] {
    let mut p = [[0.0; 3]; MAX_ORDER as usize + 1];
    p[0] = [1.0, 0.0, 0.0];
    if order >= 1 {
        p[1] = [t, 1.0, 0.0];
    }
    for n in 1..order {
        let (a, b) = (p[n], p[n - 1]);
        p[n + 1] = [
            2.0 * t * a[0] - b[0],
            2.0 * a[0] + 2.0 * t * a[1] - b[1],
            4.0 * a[1] + 2.0 * t * a[2] - b[2],
        ];
    }
    p
}

impl Chebyshev {
    /// Checks a spec and builds the surface for the part disc `part` (which sets the default
    /// half-widths).
    pub fn new(spec: &ChebyshevSpec, part: PartDisc) -> Result<Self, FieldError> {
        let base = Asphere::new(&spec.base).map_err(|e| e.within("base"))?;
        let hx = match spec.half_width_x_mm {
            Some(h) => positive("half_width_x_mm", h)?,
            None => part.x_mm.abs() + part.radius_mm,
        };
        let hy = match spec.half_width_y_mm {
            Some(h) => positive("half_width_y_mm", h)?,
            None => part.y_mm.abs() + part.radius_mm,
        };
        let mut terms = Vec::with_capacity(spec.terms.len());
        for (k, t) in spec.terms.iter().enumerate() {
            let field = format!("terms[{k}]");
            for (name, v) in [("x", t.x), ("y", t.y)] {
                if v > MAX_ORDER {
                    return Err(FieldError::new(
                        format!("{field}.{name}"),
                        v,
                        format!("must lie in 0 … {MAX_ORDER}"),
                    ));
                }
            }
            if spec.terms[..k].iter().any(|u| u.x == t.x && u.y == t.y) {
                return Err(FieldError::new(
                    field,
                    format!("x{} y{}", t.x, t.y),
                    "each term at most once",
                ));
            }
            let c = finite(&format!("{field}.coefficient_mm"), t.coefficient_mm)?;
            if c != 0.0 {
                terms.push((t.x as usize, t.y as usize, c));
            }
        }
        let order = terms
            .iter()
            .fold((0, 0), |(a, b), &(i, j, _)| (a.max(i), b.max(j)));
        let reach = |centre: f64, h: f64| ((centre.abs() + part.radius_mm) / h - 1.0).max(0.0);
        Ok(Self {
            base,
            hx,
            hy,
            terms,
            order,
            overreach: (reach(part.x_mm, hx), reach(part.y_mm, hy)),
        })
    }

    /// The half-widths (X₀, Y₀) in use, mm.
    pub fn half_widths_mm(&self) -> (f64, f64) {
        (self.hx, self.hy)
    }
}

impl Surface for Chebyshev {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let mut l = self.base.local(x, y)?;
        let tx = chebyshev_table(x / self.hx, self.order.0);
        let ty = chebyshev_table(y / self.hy, self.order.1);
        let [mut z, mut zu, mut zv, mut zuu, mut zuv, mut zvv] = [0.0; 6];
        for &(i, j, c) in &self.terms {
            let ([a0, a1, a2], [b0, b1, b2]) = (tx[i], ty[j]);
            z += c * a0 * b0;
            zu += c * a1 * b0;
            zv += c * a0 * b1;
            zuu += c * a2 * b0;
            zuv += c * a1 * b1;
            zvv += c * a0 * b2;
        }
        l.z += z;
        l.zx += zu / self.hx;
        l.zy += zv / self.hy;
        l.zxx += zuu / (self.hx * self.hx);
        l.zxy += zuv / (self.hx * self.hy);
        l.zyy += zvv / (self.hy * self.hy);
        Ok(l)
    }

    /// The slope of Tₙ changes sign at its extrema cos(kπ/n), at least `1 − cos(π/n) ≥
    /// π²/(2n²)·(1 − π²/(12n²)) > π²/(4n²)` apart in t (closest at the ends): `X₀·π²/(4n²)` for
    /// the highest order n ≥ 2 in x, the same in y, and the smaller of the two.
    fn feature_length_mm(&self) -> f64 {
        let along = |n: usize, h: f64| {
            if n < 2 {
                f64::INFINITY
            } else {
                let n = n as f64;
                h * std::f64::consts::PI.powi(2) / (4.0 * n * n)
            }
        };
        along(self.order.0, self.hx)
            .min(along(self.order.1, self.hy))
            .min(self.base.feature_length_mm())
    }

    /// Where the disc lies inside the half-widths (R ≤ min(X₀, Y₀)), the base's bounds plus
    /// each term's along the direction (c, s): with |Tₙ| ≤ 1, |Tₙ′| ≤ n² and
    /// |Tₙ″| ≤ n²(n² − 1)/3 on [−1, 1] (the Markov brothers' inequalities, equal at ±1),
    /// `|d/dt Tᵢ(tc/X₀)·Tⱼ(ts/Y₀)| ≤ i²/X₀ + j²/Y₀` and
    /// `|d²/dt²| ≤ i²(i² − 1)/(3X₀²) + i²j²/(X₀Y₀) + j²(j² − 1)/(3Y₀²)` (|c·s| ≤ ½). Beyond the
    /// half-widths the polynomials grow unbounded: none.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let r = radius_mm.abs();
        if r > self.hx.min(self.hy) {
            return None;
        }
        let (hx, hy) = (self.hx, self.hy);
        let (mut slope, mut curvature) = (0.0, 0.0);
        for &(i, j, c) in &self.terms {
            let (i2, j2, a) = ((i * i) as f64, (j * j) as f64, c.abs());
            slope += a * (i2 / hx + j2 / hy);
            curvature += a
                * (i2 * (i2 - 1.0) / (3.0 * hx * hx)
                    + i2 * j2 / (hx * hy)
                    + j2 * (j2 - 1.0) / (3.0 * hy * hy));
        }
        self.base.section_bounds(r)?.plus(slope, curvature)
    }

    fn warnings(&self) -> Vec<String> {
        let (ox, oy) = self.overreach;
        if ox == 0.0 && oy == 0.0 {
            return Vec::new();
        }
        vec![format!(
            "the part reaches beyond the Chebyshev normalisation half-widths X0 {} mm, Y0 {} mm \
             (to |x/X0| = {:.4}, |y/Y0| = {:.4}): the polynomials are extrapolated there, where \
             OpticStudio leaves the surface undefined",
            self.hx,
            self.hy,
            1.0 + ox,
            1.0 + oy
        )]
    }

    fn describe(&self) -> String {
        let terms: Vec<String> = self
            .terms
            .iter()
            .map(|(i, j, c)| format!("T{i}(x)T{j}(y) {c:e}"))
            .collect();
        format!(
            "Chebyshev polynomial, X0 {} mm, Y0 {} mm [{}] on {}",
            self.hx,
            self.hy,
            terms.join(", "),
            self.base.describe()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_the_cosine_form() {
        // Tₙ(cos φ) = cos nφ; Tₙ′(cos φ) = n·sin nφ / sin φ.
        let phi: f64 = 0.7;
        let t = chebyshev_table(phi.cos(), 20);
        for (n, [v, d, _]) in t.iter().enumerate() {
            let nf = n as f64;
            assert!((v - (nf * phi).cos()).abs() < 1e-13, "{n}");
            assert!((d - nf * (nf * phi).sin() / phi.sin()).abs() < 1e-11, "{n}");
        }
    }

    #[test]
    fn section_bounds_hold_on_dense_sections_inside_the_half_widths() {
        let t = |x, y, c| ChebyshevTerm {
            x,
            y,
            coefficient_mm: c,
        };
        let spec = |terms| ChebyshevSpec {
            base: AsphereSpec {
                radius_mm: Some(80.0),
                ..Default::default()
            },
            half_width_x_mm: Some(6.0),
            half_width_y_mm: Some(5.0),
            terms,
        };
        let terms = vec![
            t(2, 0, 0.003),
            t(0, 2, -0.002),
            t(1, 2, 0.0012),
            t(3, 1, -0.0006),
            t(4, 4, 0.0002),
            t(9, 0, 1e-4),
        ];
        let s = Chebyshev::new(&spec(terms), PartDisc::centred(10.0)).unwrap();
        crate::surface::section_bounds::assert_bounds_hold(&s, 5.0, 360, 4000);
        // One term T₃(x/X₀) on a flat base: the bounds are reached where the disc meets x = X₀.
        let flat = ChebyshevSpec {
            base: AsphereSpec {
                curvature_per_mm: Some(0.0),
                ..Default::default()
            },
            half_width_x_mm: Some(5.0),
            ..spec(vec![t(3, 0, 1e-3)])
        };
        let flat = Chebyshev::new(&flat, PartDisc::centred(10.0)).unwrap();
        let (b, slope, curvature) =
            crate::surface::section_bounds::assert_bounds_hold(&flat, 5.0, 4, 4000);
        assert!(
            slope <= b.max_slope && slope > 0.9999 * b.max_slope,
            "{b:?} {slope}"
        );
        assert!(
            curvature <= b.max_curvature && curvature > 0.9999 * b.max_curvature,
            "{b:?} {curvature}"
        );
        // Beyond the half-widths: none.
        assert!(flat.section_bounds(5.5).is_none());
    }

    #[test]
    fn half_widths_default_to_the_part() {
        let spec = ChebyshevSpec {
            base: AsphereSpec {
                curvature_per_mm: Some(0.0),
                ..Default::default()
            },
            half_width_x_mm: None,
            half_width_y_mm: Some(7.5),
            terms: vec![],
        };
        let part = PartDisc {
            radius_mm: 5.0,
            x_mm: -1.0,
            y_mm: 2.5,
        };
        let s = Chebyshev::new(&spec, part).unwrap();
        assert_eq!(s.half_widths_mm(), (6.0, 7.5));
        assert!(s.warnings().is_empty());
        let s = Chebyshev::new(
            &ChebyshevSpec {
                half_width_y_mm: Some(6.0),
                ..spec
            },
            part,
        )
        .unwrap();
        assert!(
            s.warnings()[0].contains("|y/Y0| = 1.2500"),
            "{:?}",
            s.warnings()
        );
    }
}
