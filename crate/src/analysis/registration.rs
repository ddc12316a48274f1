//! The design registered to measured data by least squares (issue 15): what of a measurement
//! is set-up (the part tilted or shifted on the instrument, the instrument's piston) is fitted
//! and taken out, so that what is left is form.
//!
//! **Model.** A measured point `(x, y, z)` (mm, in the measurement's frame after its
//! orientation) is modelled as
//!
//! `z ≈ S(q) + p + t_x·x + t_y·y + w·(x² + y²)/N²`, `q = R(−φ)·((x, y) − d)`,
//!
//! with S the design's sag for `kind = height` (S = 0 for `kind = error`, whose file is the
//! error itself), p the piston, t the tilt (the slope of the data against the design, rad), w
//! the power (optional: the sag at radius N, the part radius), d the decentre (where the
//! design's centre lies in the measurement's frame) and φ the clocking (the part turned
//! counter-clockwise by φ, seen from the tool). Piston and tilt are always fitted; power when
//! asked; decentre and clocking with `height` only (an error map holds no shape to place).
//!
//! **Solution.** Gauss–Newton from d = 0, φ = 0: the model's columns are `1, x, y, ρ²/N²,
//! −R(φ)·∇S(q), S_x·q_y − S_y·q_x` (the derivatives of S(q) by d and φ), the normal equations of
//! the residuals are solved ([`super::normal_equations`]) and the step added, until the decentre
//! moves less than 1e-10 mm and the clocking less than 1e-12 rad (at most [`MAX_ITERATIONS`]);
//! the linear terms are exact after one step.
//!
//! **What the data can tell.** On a sphere a decentre is a tilt (−∇S = −(x, y)/R is a plane),
//! and on a surface of revolution a clocking changes nothing. Before solving, each of decentre
//! x, decentre y and clocking is tested by its multiple correlation with all the other terms'
//! columns at the start ([`NormalEquations::correlation`]; a clocking column below [`NOISE`] of
//! its scale counts as 1); one above [`SEPARABLE_CORRELATION`]
//! is not fitted and is reported as `None` with its correlation, the data being unable to
//! separate it (its effect is then absorbed by the terms it resembles, tilt for a decentre).
//!
//! **Residual.** `e = z − model` (measured after registration − design: positive where
//! material is left), each at the point's place on the part, `q`.

use super::normal_equations::NormalEquations;
use crate::surface::{Surface, UndefinedError};
use serde::Serialize;

/// Gauss–Newton steps at most.
pub const MAX_ITERATIONS: usize = 30;
/// The largest correlation with the other terms at which a decentre or clocking is still fitted.
pub const SEPARABLE_CORRELATION: f64 = 0.999;

/// The relative RMS below which the clocking column is taken for rounding noise: a clocking
/// of 1 rad would move the sag by less than 1e-9 of `|∇S|·|q|`.
pub const NOISE: f64 = 1e-9;

/// What the measured file holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MeasuredKind {
    /// The form error itself, measured − design (interferometers, metrology software).
    Error,
    /// Measured heights of the part (profilometers, coordinate measuring machines).
    Height,
}

/// The terms fitted besides piston and tilt.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct RegisterTerms {
    /// Power (x² + y²).
    pub power: bool,
    /// Decentre in x and y (`height` only).
    pub decentre: bool,
    /// Clocking about the axis (`height` only).
    pub clocking: bool,
}

impl RegisterTerms {
    /// The default for `kind`: decentre and clocking for heights, neither for an error map;
    /// power never.
    pub fn default_for(kind: MeasuredKind) -> Self {
        let height = kind == MeasuredKind::Height;
        Self {
            power: false,
            decentre: height,
            clocking: height,
        }
    }

    /// The terms of a list such as `piston,tilt,power,decentre,clocking` (piston and tilt are
    /// always fitted and may be named or not). Errors say what is allowed.
    pub fn parse(list: &str, kind: MeasuredKind) -> Result<Self, String> {
        let mut t = Self {
            power: false,
            decentre: false,
            clocking: false,
        };
        for word in list.split(',').map(str::trim).filter(|w| !w.is_empty()) {
            match word.to_ascii_lowercase().as_str() {
                "piston" | "tilt" => {}
                "power" => t.power = true,
                "decentre" | "decenter" => t.decentre = true,
                "clocking" => t.clocking = true,
                _ => {
                    return Err(format!(
                        "{word}: expected a comma-separated list of piston, tilt, power, \
                         decentre, clocking"
                    ));
                }
            }
        }
        if kind == MeasuredKind::Error && (t.decentre || t.clocking) {
            return Err(
                "decentre and clocking need --kind height: an error map holds no shape of the \
                 design to place"
                    .into(),
            );
        }
        Ok(t)
    }
}

/// The fitted set-up, in the measurement's frame (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Registration {
    /// Piston p, µm.
    pub piston_um: f64,
    /// Tilt along x, µrad: the data's slope against the design.
    pub tilt_x_urad: f64,
    /// Tilt along y, µrad.
    pub tilt_y_urad: f64,
    /// Power: its sag at the part's rim, µm; `None` when not fitted.
    pub power_um: Option<f64>,
    /// Decentre along x: where the design's centre lies, µm; `None` when not fitted or not
    /// separable from the other terms (see `decentre_correlation`).
    pub decentre_x_um: Option<f64>,
    /// Decentre along y, µm; `None` as `decentre_x_um`.
    pub decentre_y_um: Option<f64>,
    /// Clocking, degrees counter-clockwise seen from the tool; `None` when not fitted or not
    /// separable.
    pub clocking_deg: Option<f64>,
    /// Multiple correlation of decentre x and y with the other terms (1: indistinguishable);
    /// `None` when decentre was not asked for.
    pub decentre_correlation: Option<[f64; 2]>,
    /// Multiple correlation of the clocking with the other terms; `None` when not asked for.
    pub clocking_correlation: Option<f64>,
    /// Gauss–Newton steps taken.
    pub iterations: usize,
    /// Whether the steps converged within [`MAX_ITERATIONS`].
    pub converged: bool,
    /// Why a term asked for was not fitted.
    pub notes: Vec<String>,
}

/// The unknowns, in column order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Unknown {
    Piston,
    TiltX,
    TiltY,
    Power,
    DecentreX,
    DecentreY,
    Clocking,
}

const ALL: [Unknown; 7] = [
    Unknown::Piston,
    Unknown::TiltX,
    Unknown::TiltY,
    Unknown::Power,
    Unknown::DecentreX,
    Unknown::DecentreY,
    Unknown::Clocking,
];

/// The current estimate.
#[derive(Debug, Clone, Copy, Default)]
struct Estimate {
    piston: f64,
    tilt: [f64; 2],
    power: f64,
    decentre: [f64; 2],
    clocking: f64,
}

impl Estimate {
    fn add(&mut self, u: Unknown, v: f64) {
        match u {
            Unknown::Piston => self.piston += v,
            Unknown::TiltX => self.tilt[0] += v,
            Unknown::TiltY => self.tilt[1] += v,
            Unknown::Power => self.power += v,
            Unknown::DecentreX => self.decentre[0] += v,
            Unknown::DecentreY => self.decentre[1] += v,
            Unknown::Clocking => self.clocking += v,
        }
    }
}

/// The registration problem: the points, the design and the terms.
struct Problem<'a> {
    points: &'a [[f64; 3]],
    design: Option<&'a dyn Surface>,
    norm: f64,
}

impl Problem<'_> {
    /// The place on the part of point i, the model's columns for `unknowns` and the residual.
    fn row(
        &self,
        i: usize,
        est: &Estimate,
        unknowns: &[Unknown],
        a: &mut [f64],
    ) -> Result<([f64; 2], f64), UndefinedError> {
        let [x, y, z] = self.points[i];
        let (s, c) = est.clocking.sin_cos();
        let (wx, wy) = (x - est.decentre[0], y - est.decentre[1]);
        // q = R(−φ)·w.
        let q = [c * wx + s * wy, -s * wx + c * wy];
        let (sag, gx, gy) = match self.design {
            Some(d) => {
                let l = d.local(q[0], q[1])?;
                (l.z, l.zx, l.zy)
            }
            None => (0.0, 0.0, 0.0),
        };
        let rho2 = (x * x + y * y) / (self.norm * self.norm);
        let model = sag + est.piston + est.tilt[0] * x + est.tilt[1] * y + est.power * rho2;
        for (slot, u) in a.iter_mut().zip(unknowns) {
            *slot = match u {
                Unknown::Piston => 1.0,
                Unknown::TiltX => x,
                Unknown::TiltY => y,
                Unknown::Power => rho2,
                // ∂S(q)/∂d = −R(φ)·∇S.
                Unknown::DecentreX => -(c * gx - s * gy),
                Unknown::DecentreY => -(s * gx + c * gy),
                // ∂q/∂φ = (q_y, −q_x).
                Unknown::Clocking => gx * q[1] - gy * q[0],
            };
        }
        Ok((q, z - model))
    }

    /// Whether the clocking column `S_x·q_y − S_y·q_x` at the start is below [`NOISE`] of its
    /// scale `|∇S|·|q|` in RMS over the points: a design that looks the same turned.
    fn clocking_is_noise(&self) -> Result<bool, UndefinedError> {
        let Some(d) = self.design else {
            return Ok(true);
        };
        let (mut column, mut scale) = (0.0, 0.0);
        for &[x, y, _] in self.points {
            let l = d.local(x, y)?;
            column += (l.zx * y - l.zy * x).powi(2);
            scale += (l.zx.hypot(l.zy) * x.hypot(y)).powi(2);
        }
        Ok(column <= NOISE * NOISE * scale)
    }

    fn normal_equations(
        &self,
        est: &Estimate,
        unknowns: &[Unknown],
    ) -> Result<NormalEquations, UndefinedError> {
        NormalEquations::accumulate(self.points.len(), unknowns.len(), |i, a, b| {
            *b = self.row(i, est, unknowns, a)?.1;
            Ok(())
        })
    }
}

/// Registers `design` (for `kind = height`; ignored for `error`) to `points` with the terms
/// `terms`, power normalised at `norm_radius_mm`. Returns the registration and the residual
/// points `[x, y, e]` on the part (mm). Errors: the design undefined where a point falls.
pub fn register(
    points: &[[f64; 3]],
    kind: MeasuredKind,
    terms: RegisterTerms,
    design: &dyn Surface,
    norm_radius_mm: f64,
) -> Result<(Registration, Vec<[f64; 3]>), UndefinedError> {
    let height = kind == MeasuredKind::Height;
    let problem = Problem {
        points,
        design: height.then_some(design),
        norm: norm_radius_mm,
    };
    let wanted: Vec<Unknown> = ALL
        .into_iter()
        .filter(|u| match u {
            Unknown::Power => terms.power,
            Unknown::DecentreX | Unknown::DecentreY => height && terms.decentre,
            Unknown::Clocking => height && terms.clocking,
            _ => true,
        })
        .collect();
    let mut est = Estimate::default();
    let first = problem.normal_equations(&est, &wanted)?;
    let mut notes = Vec::new();
    let correlation = |u: Unknown| {
        wanted
            .iter()
            .position(|w| *w == u)
            .map(|i| first.correlation(i, 0))
    };
    let (cx, cy, cc) = (
        correlation(Unknown::DecentreX),
        correlation(Unknown::DecentreY),
        correlation(Unknown::Clocking),
    );
    // A clocking column that is rounding noise (a surface of revolution) correlates with
    // nothing, yet tells nothing: it counts as a correlation of 1.
    let cc = match cc {
        Some(_) if problem.clocking_is_noise()? => Some(1.0),
        other => other,
    };
    let separable = |c: Option<f64>| c.is_some_and(|c| c <= SEPARABLE_CORRELATION);
    let unknowns: Vec<Unknown> = wanted
        .iter()
        .copied()
        .filter(|u| match u {
            Unknown::DecentreX | Unknown::DecentreY => separable(cx) && separable(cy),
            Unknown::Clocking => separable(cc),
            _ => true,
        })
        .collect();
    if let (Some(x), Some(y)) = (cx, cy)
        && !(separable(cx) && separable(cy))
    {
        notes.push(format!(
            "decentre not fitted: the design's shape cannot tell it from tilt over the measured \
             area (correlation {x:.6} in x, {y:.6} in y; at most {SEPARABLE_CORRELATION}); a \
             sphere or a flat has no centre to find"
        ));
    }
    if let Some(c) = cc
        && !separable(cc)
    {
        notes.push(format!(
            "clocking not fitted: the design looks the same turned (correlation {c:.6}; at most \
             {SEPARABLE_CORRELATION}), as a surface of revolution does"
        ));
    }
    let nonlinear = unknowns.iter().any(|u| {
        matches!(
            u,
            Unknown::DecentreX | Unknown::DecentreY | Unknown::Clocking
        )
    });
    let (mut iterations, mut converged) = (0, false);
    let mut sums = if unknowns.len() == wanted.len() {
        first
    } else {
        problem.normal_equations(&est, &unknowns)?
    };
    while iterations < MAX_ITERATIONS {
        let (step, _) = sums.solve();
        let mut moved: f64 = 0.0;
        for (u, v) in unknowns.iter().zip(step.iter()) {
            est.add(*u, *v);
            if matches!(u, Unknown::DecentreX | Unknown::DecentreY) {
                moved = moved.max(v.abs() / 1e-10);
            }
            if *u == Unknown::Clocking {
                moved = moved.max(v.abs() / 1e-12);
            }
        }
        iterations += 1;
        if !nonlinear || moved < 1.0 {
            converged = true;
            break;
        }
        sums = problem.normal_equations(&est, &unknowns)?;
    }
    let mut residual = Vec::with_capacity(points.len());
    let mut scratch = vec![0.0; unknowns.len()];
    for i in 0..points.len() {
        let (q, e) = problem.row(i, &est, &unknowns, &mut scratch)?;
        residual.push([q[0], q[1], e]);
    }
    let has = |u: Unknown| unknowns.contains(&u);
    Ok((
        Registration {
            piston_um: est.piston * 1e3,
            tilt_x_urad: est.tilt[0] * 1e6,
            tilt_y_urad: est.tilt[1] * 1e6,
            power_um: has(Unknown::Power).then_some(est.power * 1e3),
            decentre_x_um: has(Unknown::DecentreX).then_some(est.decentre[0] * 1e3),
            decentre_y_um: has(Unknown::DecentreY).then_some(est.decentre[1] * 1e3),
            clocking_deg: has(Unknown::Clocking).then_some(est.clocking.to_degrees()),
            decentre_correlation: cx.zip(cy).map(|(x, y)| [x, y]),
            clocking_correlation: cc,
            iterations,
            converged,
            notes,
        },
        residual,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn terms_are_read_from_a_list() {
        let t = RegisterTerms::parse("piston, tilt,power", MeasuredKind::Error).unwrap();
        assert!(t.power && !t.decentre && !t.clocking);
        let t = RegisterTerms::parse("decentre,clocking", MeasuredKind::Height).unwrap();
        assert!(!t.power && t.decentre && t.clocking);
        assert!(
            RegisterTerms::parse("coma", MeasuredKind::Height)
                .unwrap_err()
                .starts_with("coma: expected")
        );
        assert!(
            RegisterTerms::parse("decentre", MeasuredKind::Error)
                .unwrap_err()
                .contains("--kind height")
        );
    }
}
