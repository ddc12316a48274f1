//! Forbes' freeform Q polynomials on a best-fit sphere (G. W. Forbes, "Characterizing the shape
//! of freeform optics", Opt. Express 20, 2483, 2012, eq 2.2 with appendices A and B):
//!
//! `z = c·ρ²/(1 + √(1 − c²ρ²)) + 1/√(1 − c²ρ²) · { u²(1 − u²)·Σₙ aₙ⁰·Qₙ⁰(u²)
//!      + Σₘ₌₁ u^m·Σₙ [aₙᵐ·cos mθ + bₙᵐ·sin mθ]·Qₙᵐ(u²) }`,
//!
//! u = ρ/N, θ from +X towards +Y, every coefficient in mm; Qₙ⁰ = Qbfsₙ. The departure is along
//! the sphere's normal (hence the factor 1/√(1 − c²ρ²), as in [`super::q_bfs`]). The radial
//! sums Σₙ cₙ·Qₙᵐ(x) come from [`super::q_polynomials`] (Forbes' recurrences with the change of
//! basis of appendix B). The angular factors are taken as the harmonic polynomials
//! `u^m·cos mθ = Re wᵐ`, `u^m·sin mθ = Im wᵐ`, w = (x + iy)/N, with `∂wᵐ/∂x = (m/N)·wᵐ⁻¹` and
//! `∂wᵐ/∂y = i·(m/N)·wᵐ⁻¹`, so the derivatives are exact at the axis, where polar ones are
//! singular; products and the radial functions of s = ρ² are carried by [`super::jet::Jet`].
//! Undefined where c²ρ² ≥ 1; beyond u = 1 the polynomials continue.

use super::jet::Jet;
use super::q_polynomials::{MAX_ORDER, QSum, envelope, feature_length};
use super::q_section_bounds::{along_sphere_normal, section_term_bounds};
use super::{Asphere, AsphereSpec, Local, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite, positive};
use serde::{Deserialize, Serialize};

/// One term: the radial order n and azimuthal order m, with the cos mθ and sin mθ coefficients.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Q2dTerm {
    /// Radial order n, 0 … 30.
    pub n: u32,
    /// Azimuthal order m, 0 … 30 (0: the rotationally symmetric Qbfs part).
    pub m: u32,
    /// aₙᵐ, mm: multiplies cos mθ (for m = 0, the Qbfs coefficient); default 0.
    #[serde(default)]
    pub a_mm: f64,
    /// bₙᵐ, mm: multiplies sin mθ; 0 for m = 0; default 0.
    #[serde(default)]
    pub b_mm: f64,
}

/// Job entry of a Q₂D freeform. Give exactly one of `radius_mm` and `curvature_per_mm`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Q2dSpec {
    /// Radius of the best-fit sphere, mm, non-zero.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_mm: Option<f64>,
    /// Its curvature c = 1/R, 1/mm; 0 for a plane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_per_mm: Option<f64>,
    /// Normalisation radius N, mm, > 0: u = ρ/N.
    pub norm_radius_mm: f64,
    /// The terms; each (n, m) at most once.
    pub terms: Vec<Q2dTerm>,
}

/// The radial sums of one azimuthal order m ≥ 1.
#[derive(Debug, Clone, PartialEq)]
struct Order {
    m: usize,
    cos: QSum,
    sin: QSum,
}

/// A Q₂D freeform, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Q2d {
    sphere: Asphere,
    c: f64,
    norm: f64,
    terms: Vec<Q2dTerm>,
    symmetric: QSum,
    orders: Vec<Order>,
    /// Highest m present.
    max_m: usize,
    /// Highest degree in u² of a term present (n + 2 for m = 0, n + m/2 otherwise).
    degree: f64,
}

/// Dense coefficient lists per m: `cos[m][n]`, `sin[m][n]`.
type Dense = (Vec<Vec<f64>>, Vec<Vec<f64>>);

/// Checks the terms and spreads them into dense lists per m.
fn dense_terms(terms: &[Q2dTerm]) -> Result<Dense, FieldError> {
    let size = MAX_ORDER + 1;
    let (mut cos, mut sin) = (vec![Vec::new(); size], vec![Vec::new(); size]);
    for (i, t) in terms.iter().enumerate() {
        let field = |name: &str| format!("terms[{i}].{name}");
        for (name, v) in [("n", t.n), ("m", t.m)] {
            if v as usize > MAX_ORDER {
                return Err(FieldError::new(
                    field(name),
                    v,
                    format!("must lie in 0 … {MAX_ORDER}"),
                ));
            }
        }
        if terms[..i].iter().any(|u| u.n == t.n && u.m == t.m) {
            return Err(FieldError::new(
                format!("terms[{i}]"),
                format!("n {} m {}", t.n, t.m),
                "each (n, m) at most once",
            ));
        }
        let a = finite(&field("a_mm"), t.a_mm)?;
        let b = finite(&field("b_mm"), t.b_mm)?;
        if t.m == 0 && b != 0.0 {
            return Err(FieldError::new(
                field("b_mm"),
                b,
                "must be 0 for m = 0 (the rotationally symmetric part has no sin mθ)",
            ));
        }
        let (m, n) = (t.m as usize, t.n as usize);
        for (list, v) in [(&mut cos[m], a), (&mut sin[m], b)] {
            if list.len() <= n {
                list.resize(n + 1, 0.0);
            }
            list[n] = v;
        }
    }
    Ok((cos, sin))
}

impl Q2d {
    /// Checks a spec and builds the surface.
    pub fn new(spec: &Q2dSpec) -> Result<Self, FieldError> {
        let sphere = Asphere::new(&AsphereSpec {
            radius_mm: spec.radius_mm,
            curvature_per_mm: spec.curvature_per_mm,
            ..Default::default()
        })?;
        let norm = positive("norm_radius_mm", spec.norm_radius_mm)?;
        let (cos, sin) = dense_terms(&spec.terms)?;
        let orders: Vec<Order> = (1..=MAX_ORDER)
            .filter(|&m| cos[m].iter().chain(&sin[m]).any(|&v| v != 0.0))
            .map(|m| Order {
                m,
                cos: QSum::q2d(m, &cos[m]),
                sin: QSum::q2d(m, &sin[m]),
            })
            .collect();
        let degree = spec
            .terms
            .iter()
            .filter(|t| t.a_mm != 0.0 || t.b_mm != 0.0)
            .map(|t| match t.m {
                0 => t.n as f64 + 2.0,
                m => t.n as f64 + m as f64 / 2.0,
            })
            .fold(0.0, f64::max);
        Ok(Self {
            c: sphere.curvature_per_mm(),
            sphere,
            norm,
            terms: spec.terms.clone(),
            symmetric: QSum::qbfs(&cos[0]),
            max_m: orders.last().map_or(0, |o| o.m),
            orders,
            degree,
        })
    }

    /// A function of s = ρ² given by `[f, df/dξ, d²f/dξ²]` in ξ = s/N², as a jet in (x, y).
    fn radial(&self, s: &Jet, [f, f1, f2]: [f64; 3]) -> Jet {
        let n2 = self.norm * self.norm;
        s.compose(f, f1 / n2, f2 / (n2 * n2))
    }

    /// The jets of Re wᵐ and Im wᵐ, m = 0 … max_m, w = (x + iy)/N.
    fn harmonics(&self, x: f64, y: f64) -> Vec<(Jet, Jet)> {
        let (u, v) = (x / self.norm, y / self.norm);
        let mut powers = vec![(1.0, 0.0)];
        for k in 1..=self.max_m {
            let (re, im) = powers[k - 1];
            powers.push((re * u - im * v, re * v + im * u));
        }
        let (n1, n2) = (1.0 / self.norm, 1.0 / (self.norm * self.norm));
        (0..=self.max_m)
            .map(|m| {
                let mf = m as f64;
                let (p0, p1, p2) = (
                    powers[m],
                    powers[m.saturating_sub(1)],
                    powers[m.saturating_sub(2)],
                );
                let d1 = if m >= 1 { mf * n1 } else { 0.0 };
                let d2 = if m >= 2 { mf * (mf - 1.0) * n2 } else { 0.0 };
                // ∂/∂x = d1·wᵐ⁻¹, ∂/∂y = i·d1·wᵐ⁻¹, ∂²/∂x² = d2·wᵐ⁻², ∂²/∂x∂y = i·d2·wᵐ⁻²,
                // ∂²/∂y² = −d2·wᵐ⁻²; Re(i·z) = −Im z, Im(i·z) = Re z.
                let re = Jet {
                    v: p0.0,
                    x: d1 * p1.0,
                    y: -d1 * p1.1,
                    xx: d2 * p2.0,
                    xy: -d2 * p2.1,
                    yy: -d2 * p2.0,
                };
                let im = Jet {
                    v: p0.1,
                    x: d1 * p1.1,
                    y: d1 * p1.0,
                    xx: d2 * p2.1,
                    xy: d2 * p2.0,
                    yy: -d2 * p2.1,
                };
                (re, im)
            })
            .collect()
    }
}

impl Surface for Q2d {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let s2 = x * x + y * y;
        let base = self.sphere.in_s(s2).map_err(|reason| UndefinedError {
            surface: "Q2D freeform",
            x_mm: x,
            y_mm: y,
            radius_mm: x.hypot(y),
            reason,
        })?;
        let s = Jet::squared_distance(x, y);
        let xi = s2 / (self.norm * self.norm);
        let mut departure = self.radial(&s, envelope(xi, self.symmetric.eval(xi)));
        if !self.orders.is_empty() {
            let h = self.harmonics(x, y);
            for o in &self.orders {
                let (re, im) = h[o.m];
                departure = departure
                    + re * self.radial(&s, o.cos.eval(xi))
                    + im * self.radial(&s, o.sin.eval(xi));
            }
        }
        // 1/√(1 − c²s) and its derivatives in s.
        let c2 = self.c * self.c;
        let g = 1.0 / (1.0 - c2 * s2).sqrt();
        let g3 = g * g * g;
        let inverse = s.compose(g, 0.5 * c2 * g3, 0.75 * c2 * c2 * g3 * g * g);
        let sphere = s.compose(base[0], base[1], base[2]);
        Ok((sphere + departure * inverse).into())
    }

    /// [`feature_length`] of the highest degree in u² present (n + 2 for m = 0, n + m/2).
    fn feature_length_mm(&self) -> f64 {
        if self.degree == 0.0 {
            f64::INFINITY
        } else {
            feature_length(self.norm, self.degree)
        }
    }

    /// The sphere's bounds plus those of the departure along its normal: the symmetric part's
    /// and, for each order m, its cos mθ and sin mθ sums' ([`super::q_section_bounds`]).
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let (norm, sym) = (self.norm, &self.symmetric);
        let mut a = section_term_bounds(0, sym.degree() + 2, norm, t, |x| envelope(x, sym.eval(x)));
        for o in &self.orders {
            for sum in [&o.cos, &o.sin].into_iter().filter(|q| !q.is_zero()) {
                let b = section_term_bounds(o.m, sum.degree(), norm, t, |x| sum.eval(x));
                a = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
            }
        }
        let (slope, curvature) = along_sphere_normal(self.c, t, a)?;
        self.sphere.section_bounds(t)?.plus(slope, curvature)
    }

    fn describe(&self) -> String {
        let terms: Vec<String> = self
            .terms
            .iter()
            .filter(|t| t.a_mm != 0.0 || t.b_mm != 0.0)
            .map(|t| match (t.a_mm, t.b_mm) {
                (a, 0.0) => format!("n{} m{} a {a:e}", t.n, t.m),
                (0.0, b) => format!("n{} m{} b {b:e}", t.n, t.m),
                (a, b) => format!("n{} m{} a {a:e} b {b:e}", t.n, t.m),
            })
            .collect();
        let sphere = self.sphere.shape();
        format!(
            "Q2D freeform (Forbes 2012) on the sphere {}, N {} mm [{}]",
            sphere.strip_suffix(", k 0").unwrap_or(&sphere),
            self.norm,
            terms.join(", ")
        )
    }
}
