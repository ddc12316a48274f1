//! Cutting linearization error (paper 000, section "Cutting linearization error", after eq 8):
//! between two NC blocks the controller moves C, X and Z linearly, while the height the tool
//! should have follows the curved surface; the largest gap along each segment is the local
//! PVerr δerr, found as the paper does by Newton's iteration along the segment.
//!
//! Between path points k and k+1 the machine passes through `ρ(s) = ρ_k + s·Δρ`,
//! `θ(s) = θ_k + s·Δθ`, `Z_lin(s) = z_k + s·Δz`, s ∈ [0, 1]. The height the tool tip should
//! have there is the compensated tip height `z*(s)` of [`crate::tool`] at `(ρ(s), θ(s))`
//! (the sag for a sharp tool), and the error is `e(s) = Z_lin(s) − z*(s)`: e < 0 the tool dips
//! into the design surface (overcut), e > 0 it leaves material (undercut); e(0) = e(1) = 0.
//! The paper iterates on the angle ∂θ reached at an arc length ∂S from the first point (to
//! |∂θ_j − ∂θ_{j+1}| ≤ 1e-9); along one segment θ is linear in s, so iterating on s is the same
//! search. The paper then projects the height gap ∂Zmax with the chord's slope ϕ (δerr; the
//! equation is lost in our copy of the text); this module reports the height gap itself, the
//! error of the Z that the NC commands.
//!
//! **Derivatives (envelope theorem).** `z*` is the maximum over the nose arc of
//! `F(a, s) = f(Q) + r·cos a` with the arc point `Q = (ρ(s) + r·sin a)·û(θ(s))`; at the maximiser
//! `∂F/∂a = 0` (or a is held at an end of the arc), so `dz*/ds = ∂F/∂s` at fixed a: the surface
//! gradient at the contact dotted with the contact's motion
//! `Q′ = Δρ·û + ρ_c·Δθ·v̂` (û radial, v̂ tangential, ρ_c the contact's signed radius), i.e.
//! `dz*/ds = Δρ·f_u + ρ_c·Δθ·f_v`. The second derivative adds the contact's slide along the
//! nose: `d²z*/ds² = F_ss − F_sa²/F_aa` with
//! `F_ss = Q′ᵀ·H·Q′ + ∇f·Q″`, `Q″ = 2ΔρΔθ·v̂ − ρ_c·Δθ²·û`,
//! `F_sa = r·cos a·(Δρ·H_uu + ρ_c·Δθ·H_uv + Δθ·f_v)`, `F_aa = r²cos²a·H_uu − r·sin a·f_u − r·cos a`
//! (only `F_ss` where a sits at an end of the arc, and for r = 0). Where the arc is cut at the
//! part edge and the contact sits on that edge, ρ_c = ±R is fixed instead of a, and
//! `dz*/ds = ρ_c·Δθ·f_v + tan a·Δρ`, `d²z*/ds² = ρ_c²Δθ²·H_vv − ρ_c·Δθ²·f_u − Δρ²/(r·cos³a)`.
//! All of it comes from one surface evaluation at the contact.
//!
//! **Contacts on a ridge.** Where the contact sits on a slope kink of the section (a concave
//! lens array's rim: F′ ≠ 0 at the maximum, the surface's radial slope falling through tan a
//! across the contact), the contact follows the ridge, not the envelope condition: the ridge is
//! where two smooth pieces meet, so it runs across the jump `Δ∇f` of the surface gradient
//! (the other side's, read 10⁻¹¹·(1 + r) mm beyond the contact, less the contact's), and its
//! crossing with the section at θ moves by `ρ_c′ = −ρ_c·Δθ·Δf_v/Δf_u`. Then
//! `dz*/ds = f_u·ρ_c′ + ρ_c·Δθ·f_v − tan a·(ρ_c′ − Δρ)` (the sag along the ridge plus the arc's
//! height over it; the same from either side of the kink, and the envelope theorem's where
//! tan a = f_u); the second derivative is not formed. The envelope theorem's slope there is
//! wrong at the order of the slope itself, which sent the refinement bisecting on wrong signs
//! (20–30 steps) and could miss an extreme by nanometres.
//!
//! **Extremes.** A segment can have a negative and a positive extreme (an inflection of the
//! surface under it), and on a wavy surface several of each. e, e′ and e″ are sampled at the ends
//! (from the path points themselves) and at `n − 1` interior points, `n ≥ 4` intervals, at least
//! one per 15° of Δθ and one per eighth of the surface's feature length
//! ([`crate::surface::Surface::feature_length_mm`]) along the contact's path, at most
//! [`MAX_INTERVALS`]. Every interval where e′ changes sign brackets a local extreme, refined by
//! a safeguarded Newton iteration on `e′(s) = 0` (NR's `rtsafe`): the Newton step
//! `s − e′/e″` (where e″ is not formed, on a ridge, the secant of e′ across the bracket) is
//! taken when it stays inside the bracket, has the right curvature and at least halves the
//! step before last; otherwise the bracket is bisected, so the bracket shrinks at
//! least geometrically and the loop ends within [`MAX_ITERATIONS`] steps whatever the surface
//! (kinks included: bisection then converges on the kink, where e′ jumps through 0). It stops
//! when the height still to gain is below [`HEIGHT_TOLERANCE`] (1e-13 mm): by the bracket
//! (where its ends' tangents cross, over the best e: a bound where e′ is monotone in it) or by
//! the Newton model (`e′²/(2|e″|)`). The extremes of the segment are the most negative and
//! most positive e over every sample and refined point. Each interior sample's contact search
//! starts from the angle interpolated between the contacts of the segment's ends
//! ([`crate::tool::WarmStart::toward`]); where the surface proves the nose height concave the
//! contact found does not depend on the start (to 10⁻¹⁰ rad), and the ridge's slope does not
//! depend on the side of the kink the contact is reported on. A segment along which the tool
//! stands still has no error. Accuracy: each refined extreme is within
//! 1e-13 mm of the local extreme of the computed e(s), whose own rounding (that of the
//! compensated height, ~1e-13 mm) dominates. With the cubic-like e of a short segment on a smooth
//! surface (`e = s(1 − s)(α + βs)`, extremes ≥ 1/√3 apart in s) four intervals can hold at most
//! one extreme each, so none is missed; the feature-length rule extends this to wavy surfaces.
//! Two extremes closer than one sample interval are the limitation: their heights differ by at
//! most the variation of e over that interval.
//!
//! [`LinearizationCheck`] consumes a path in order and keeps the worst overcut and undercut and a
//! map; [`analyse`] runs it over a tool_path's path.

use crate::path::Location;
use crate::path::PathPoint;
use crate::progress::PROGRESS_EVERY;
use crate::raster::Raster;
use crate::surface::{Local, Surface, UndefinedError};
use crate::tool::ToolPath;
use crate::tool::WarmStart;
use crate::tool::{Concavity, NoseCompensator};
use serde::Serialize;

/// Height, mm, below which the refinement of an extreme stops (see the module docs).
pub const HEIGHT_TOLERANCE: f64 = 1e-13;
/// Most steps of the refinement of one extreme.
pub const MAX_ITERATIONS: usize = 100;
/// Fewest sample intervals per segment.
pub const MIN_INTERVALS: usize = 4;
/// Most sample intervals per segment.
pub const MAX_INTERVALS: usize = 4096;
/// Sample intervals per feature length along the contact's path.
pub const INTERVALS_PER_FEATURE: f64 = 8.0;
/// Largest Δθ of one sample interval, radians (15°).
const MAX_ANGLE_STEP: f64 = std::f64::consts::PI / 12.0;
/// Tolerance, radians, of "the contact sits at this end of the arc".
const AT_END: f64 = 1e-12;
/// Least |f_u − tan a| at a free contact, mm/mm, that marks it as pinned on a slope kink
/// (at a smooth maximum it is zero to the compensation's 10⁻¹⁰ rad).
const RIDGE_SLOPE: f64 = 1e-7;
/// How far beyond a contact pinned on a slope kink the other side's gradient is read, mm per
/// (1 + r/mm): past the kink, which the compensation places within 2·10⁻¹² rad of the nose.
const RIDGE_STEP: f64 = 1e-11;

/// The error at one point of a segment and its derivatives along it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorSample {
    /// Segment parameter s ∈ [0, 1].
    pub s: f64,
    /// Tool radius ρ(s), mm.
    pub rho: f64,
    /// Cumulative polar angle θ(s), radians.
    pub theta: f64,
    /// e(s) = Z_lin(s) − z*(s), mm.
    pub error_mm: f64,
    /// de/ds, mm (per unit s).
    pub slope_mm: f64,
    /// d²e/ds², mm; NaN where undefined (the contact jumps, or its nose angle is degenerate).
    pub curvature_mm: f64,
}

/// An extreme of the error along a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extreme {
    /// e at the extreme, mm: ≤ 0 for an overcut, ≥ 0 for an undercut (0 when the segment has
    /// none of that sign, at s = 0).
    pub error_mm: f64,
    /// Where along the segment, s ∈ [0, 1].
    pub s: f64,
    /// Tool radius there, mm.
    pub rho: f64,
    /// Cumulative polar angle there, radians.
    pub theta: f64,
}

impl Extreme {
    /// Where on the part.
    pub fn location(&self) -> Location {
        Location::new(self.rho, self.theta)
    }
}

/// The largest overcut and undercut of one segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentError {
    /// The most negative e (the tool below the design surface), ≤ 0.
    pub overcut: Extreme,
    /// The most positive e (material left), ≥ 0.
    pub undercut: Extreme,
}

/// The figures of a whole path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinearizationReport {
    /// Segments checked (points − 1).
    pub segments: u64,
    /// Largest overcut (tool below the design surface), µm, as a magnitude ≥ 0.
    pub max_overcut_um: f64,
    /// Where it occurs (tool position).
    pub max_overcut_at: Location,
    /// Largest undercut (material left), µm, ≥ 0.
    pub max_undercut_um: f64,
    /// Where it occurs (tool position).
    pub max_undercut_at: Location,
    /// Max undercut + max overcut: the PVerr of paper 000, µm.
    pub pv_um: f64,
    /// Where the larger of the two occurs.
    pub worst_at: Location,
    /// Signed error (µm) of largest magnitude among the segments' extremes in each cell, at the
    /// tool position (ρ(s), θ(s)); NaN where none fell.
    #[serde(skip)]
    pub map: Raster,
}

/// What the derivatives need of one contact: the tool's direction, the contact and the
/// surface's jet there.
#[derive(Debug, Clone, Copy)]
struct Jet {
    c: f64,
    s: f64,
    /// Signed radial coordinate of the contact.
    rho_c: f64,
    /// Nose angle of the contact.
    angle: f64,
    /// Its sine and cosine.
    sin_cos: (f64, f64),
    z_tip: f64,
    local: Local,
    regime: Regime,
}

/// How the contact moves with the tool.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Regime {
    /// An interior maximum of F over the arc (or r = 0): a follows the surface.
    Free,
    /// At an end of the arc (±β/2), or the arc range has collapsed: a is fixed.
    ArcEnd,
    /// On the part edge, where the arc is cut: ρ_c = ±R is fixed.
    PartEdge,
    /// On a slope kink of the section (a lenslet rim), where F′ ≠ 0: the contact follows the
    /// ridge. The jump of the surface gradient across it (the other side's less the contact's),
    /// radial and tangential components, mm/mm.
    Ridge { jump_u: f64, jump_v: f64 },
}

/// The surface and the nose of a plan.
struct Context<'a> {
    surface: &'a dyn Surface,
    nose: &'a NoseCompensator,
    /// The path's certificate for the concave shortcut ([`NoseCompensator::concavity`]).
    concavity: Option<Concavity>,
}

/// An error for a value that came out non-finite at (ρ, θ).
fn not_finite(rho: f64, theta: f64, what: &str) -> UndefinedError {
    let (s, c) = theta.sin_cos();
    UndefinedError {
        surface: "surface",
        x_mm: rho * c,
        y_mm: rho * s,
        radius_mm: rho.abs(),
        reason: format!("the linearization check found {what} not finite"),
    }
}

impl<'a> Context<'a> {
    fn new(tool_path: &'a ToolPath) -> Self {
        Self {
            surface: tool_path.surface(),
            nose: tool_path.nose(),
            concavity: tool_path.concavity(),
        }
    }

    fn regime(&self, rho_s: f64, a: f64) -> Regime {
        let nose = self.nose;
        if nose.nose_radius() == 0.0 {
            return Regime::Free;
        }
        let half = nose.half_angle();
        let (lo, hi) = nose.arc_range(rho_s);
        let at = |bound: f64| (a - bound).abs() <= AT_END;
        if hi <= lo {
            Regime::ArcEnd
        } else if (at(hi) && hi < half - AT_END) || (at(lo) && lo > -half + AT_END) {
            Regime::PartEdge
        } else if at(half) || at(-half) {
            Regime::ArcEnd
        } else {
            Regime::Free
        }
    }

    /// The jet of a path point, from its recorded contact.
    fn jet_of_point(&self, p: &PathPoint) -> Result<Jet, UndefinedError> {
        if !(p.rho.is_finite() && p.theta.is_finite() && p.z.is_finite()) {
            return Err(not_finite(p.rho, p.theta, "a path point"));
        }
        let (s, c) = p.theta.sin_cos();
        let [x, y, _] = p.contact;
        let local = self.surface.local(x, y)?;
        self.on_ridge(Jet {
            c,
            s,
            rho_c: x * c + y * s,
            angle: p.contact_angle,
            sin_cos: p.contact_angle.sin_cos(),
            z_tip: p.z,
            local,
            regime: self.regime(p.rho, p.contact_angle),
        })
    }

    /// `j`, its regime [`Regime::Ridge`] where a free contact has F′ = r·cos a·(f_u − tan a)
    /// away from 0 and the surface's radial slope across the contact falls through tan a (a
    /// maximum of F at a slope kink); the other side is read [`RIDGE_STEP`] beyond the contact
    /// in the direction F rises.
    fn on_ridge(&self, j: Jet) -> Result<Jet, UndefinedError> {
        let r = self.nose.nose_radius();
        if j.regime != Regime::Free || r == 0.0 || self.nose.waviness().is_some() {
            return Ok(j);
        }
        let (sa, ca) = j.sin_cos;
        let gradient = |l: &Local| (l.zx * j.c + l.zy * j.s, -l.zx * j.s + l.zy * j.c);
        let (f_u, f_v) = gradient(&j.local);
        let rises = f_u - sa / ca;
        if rises.abs() <= RIDGE_SLOPE {
            return Ok(j);
        }
        let rho = j.rho_c + rises.signum() * RIDGE_STEP * (1.0 + r);
        let (o_u, o_v) = gradient(&self.surface.local(rho * j.c, rho * j.s)?);
        if (o_u - sa / ca) * rises >= 0.0 {
            return Ok(j);
        }
        Ok(Jet {
            regime: Regime::Ridge {
                jump_u: o_u - f_u,
                jump_v: o_v - f_v,
            },
            ..j
        })
    }

    /// The jet at tool position (ρ, θ), compensated afresh, the contact search starting from
    /// `start` (from a = 0 without one; where the surface proves the nose height concave the
    /// contact does not depend on it: [`NoseCompensator::compensate_from`]).
    fn jet_at(
        &self,
        rho: f64,
        theta: f64,
        start: Option<WarmStart>,
    ) -> Result<Jet, UndefinedError> {
        let (s, c) = theta.sin_cos();
        let (contact, local) =
            self.nose
                .compensate_with_local(self.surface, self.concavity, rho, c, s, start)?;
        self.on_ridge(Jet {
            c,
            s,
            rho_c: contact.rho,
            angle: contact.angle,
            sin_cos: contact.sin_cos,
            z_tip: contact.z_tip,
            local,
            regime: self.regime(rho, contact.angle),
        })
    }

    /// dz*/ds and d²z*/ds² for a tool moving by (Δρ, Δθ) per unit s (see the module docs).
    fn z_derivatives(&self, j: &Jet, drho: f64, dtheta: f64) -> (f64, f64) {
        let l = &j.local;
        let (c, s) = (j.c, j.s);
        let f_u = l.zx * c + l.zy * s;
        let f_v = -l.zx * s + l.zy * c;
        let h_uu = l.zxx * c * c + 2.0 * l.zxy * c * s + l.zyy * s * s;
        let h_uv = (l.zyy - l.zxx) * c * s + l.zxy * (c * c - s * s);
        let h_vv = l.zxx * s * s - 2.0 * l.zxy * c * s + l.zyy * c * c;
        let rc = j.rho_c;
        let r = self.nose.nose_radius();
        match j.regime {
            Regime::Ridge { jump_u, jump_v } => {
                let (sa, ca) = j.sin_cos;
                let drho_c = -rc * dtheta * jump_v / jump_u;
                let d1 = f_u * drho_c + rc * dtheta * f_v - sa / ca * (drho_c - drho);
                (d1, f64::NAN)
            }
            Regime::PartEdge => {
                let (sa, ca) = j.sin_cos;
                let d1 = rc * dtheta * f_v + sa / ca * drho;
                let d2 = rc * rc * dtheta * dtheta * h_vv
                    - rc * dtheta * dtheta * f_u
                    - drho * drho / (r * ca * ca * ca);
                (d1, d2)
            }
            Regime::Free | Regime::ArcEnd => {
                let d1 = drho * f_u + rc * dtheta * f_v;
                let f_ss = drho * drho * h_uu
                    + 2.0 * drho * rc * dtheta * h_uv
                    + rc * rc * dtheta * dtheta * h_vv
                    + 2.0 * drho * dtheta * f_v
                    - rc * dtheta * dtheta * f_u;
                if j.regime == Regime::ArcEnd || r == 0.0 {
                    return (d1, f_ss);
                }
                let (sa, ca) = j.sin_cos;
                let f_aa = r * r * ca * ca * h_uu - r * sa * f_u - r * ca;
                let f_sa = r * ca * (drho * h_uu + rc * dtheta * h_uv + dtheta * f_v);
                let d2 = if f_aa < 0.0 {
                    f_ss - f_sa * f_sa / f_aa
                } else {
                    f64::NAN
                };
                (d1, d2)
            }
        }
    }
}

/// One segment between two path points.
struct Segment<'c, 'a> {
    ctx: &'c Context<'a>,
    rho0: f64,
    theta0: f64,
    z0: f64,
    drho: f64,
    dtheta: f64,
    dz: f64,
    /// The jets of the two ends.
    ends: [Jet; 2],
}

/// A sample of e along a segment, with the sign σ applied when refining.
#[derive(Debug, Clone, Copy)]
struct Node {
    s: f64,
    e: f64,
    d1: f64,
    d2: f64,
}

impl Segment<'_, '_> {
    fn rho(&self, s: f64) -> f64 {
        self.rho0 + s * self.drho
    }

    fn theta(&self, s: f64) -> f64 {
        self.theta0 + s * self.dtheta
    }

    fn node(&self, s: f64, e: f64, j: &Jet) -> Node {
        let (z1, z2) = self.ctx.z_derivatives(j, self.drho, self.dtheta);
        Node {
            s,
            e,
            d1: self.dz - z1,
            d2: -z2,
        }
    }

    /// e and its derivatives at an interior s, the contact search starting from the angle
    /// interpolated between the ends' contacts.
    fn eval(&self, s: f64) -> Result<Node, UndefinedError> {
        let (rho, theta) = (self.rho(s), self.theta(s));
        let [a, b] = &self.ends;
        let start = WarmStart::toward(a.angle, a.sin_cos, a.angle + s * (b.angle - a.angle));
        let j = self.ctx.jet_at(rho, theta, Some(start))?;
        let e = self.z0 + s * self.dz - j.z_tip;
        let n = self.node(s, e, &j);
        if !(n.e.is_finite() && n.d1.is_finite()) {
            return Err(not_finite(rho, theta, "the error or its slope"));
        }
        Ok(n)
    }

    fn extreme(&self, n: &Node) -> Extreme {
        Extreme {
            error_mm: n.e,
            s: n.s,
            rho: self.rho(n.s),
            theta: self.theta(n.s),
        }
    }

    /// Sample intervals: see the module docs.
    fn intervals(&self) -> usize {
        let nose = self.ctx.nose;
        let reach =
            self.rho0.abs().max(self.rho(1.0).abs()) + nose.nose_radius() * nose.half_angle().sin();
        let path = self.drho.abs() + reach * self.dtheta.abs();
        let by_feature = path / self.ctx.surface.feature_length_mm() * INTERVALS_PER_FEATURE;
        let by_angle = self.dtheta.abs() / MAX_ANGLE_STEP;
        let wanted = by_feature.max(by_angle).ceil();
        if wanted.is_nan() {
            MAX_INTERVALS
        } else {
            // The cast saturates; +∞ (a zero feature length) gives the cap.
            (wanted as usize).clamp(MIN_INTERVALS, MAX_INTERVALS)
        }
    }

    /// The extremes.
    fn errors(&self) -> Result<SegmentError, UndefinedError> {
        let n = self.intervals();
        let [ja, jb] = &self.ends;
        let first = self.node(0.0, 0.0, ja);
        if self.drho == 0.0 && self.dtheta == 0.0 {
            // The tool stands still: z* is constant, so e is linear and zero at both ends.
            let none = self.extreme(&first);
            return Ok(SegmentError {
                overcut: none,
                undercut: none,
            });
        }
        let mut lowest = first;
        let mut highest = first;
        let mut prev = first;
        for i in 1..=n {
            let next = if i == n {
                self.node(1.0, 0.0, jb)
            } else {
                self.eval(i as f64 / n as f64)?
            };
            if next.e < lowest.e {
                lowest = next;
            }
            if next.e > highest.e {
                highest = next;
            }
            // e′ from + to − (through an exact 0 at most at one end): a local maximum.
            if (prev.d1 > 0.0 && next.d1 <= 0.0) || (prev.d1 >= 0.0 && next.d1 < 0.0) {
                let peak = self.refine(prev, next, 1.0)?;
                if peak.e > highest.e {
                    highest = peak;
                }
            }
            if (prev.d1 < 0.0 && next.d1 >= 0.0) || (prev.d1 <= 0.0 && next.d1 > 0.0) {
                let pit = self.refine(prev, next, -1.0)?;
                if pit.e < lowest.e {
                    lowest = pit;
                }
            }
            prev = next;
        }
        Ok(SegmentError {
            overcut: self.extreme(&lowest),
            undercut: self.extreme(&highest),
        })
    }

    /// The local maximum of σ·e in [lo.s, hi.s], given σ·e′(lo) ≥ 0 ≥ σ·e′(hi): safeguarded
    /// Newton on e′ = 0 (see the module docs). Returns the best node seen (unsigned).
    fn refine(&self, lo: Node, hi: Node, sigma: f64) -> Result<Node, UndefinedError> {
        let signed = |n: Node| Node {
            s: n.s,
            e: sigma * n.e,
            d1: sigma * n.d1,
            d2: sigma * n.d2,
        };
        let (mut lo, mut hi) = (signed(lo), signed(hi));
        let mut best = if lo.e >= hi.e { lo } else { hi };
        // Start from the end with the flatter slope.
        let mut x = if lo.d1.abs() <= hi.d1.abs() { lo } else { hi };
        let mut step_before_last = hi.s - lo.s;
        let mut last_step = step_before_last;
        for _ in 0..MAX_ITERATIONS {
            let width = hi.s - lo.s;
            if width <= 4.0 * f64::EPSILON || bracket_gain(&lo, &hi) - best.e <= HEIGHT_TOLERANCE {
                break;
            }
            // Newton where e″ is known, else the secant of e′ across the bracket.
            let newton = if x.d2 < 0.0 {
                x.s - x.d1 / x.d2
            } else if !x.d2.is_finite() {
                lo.s + lo.d1 * (width / (lo.d1 - hi.d1))
            } else {
                f64::NAN
            };
            let t = if newton > lo.s
                && newton < hi.s
                && 2.0 * (newton - x.s).abs() <= step_before_last.abs()
            {
                newton
            } else {
                0.5 * (lo.s + hi.s)
            };
            step_before_last = last_step;
            last_step = t - x.s;
            let y = signed(self.eval(t)?);
            if y.e > best.e {
                best = y;
            }
            if y.d1 > 0.0 {
                lo = y;
            } else if y.d1 < 0.0 {
                hi = y;
            } else {
                break;
            }
            let converged = y.d2 < 0.0 && y.d1 * y.d1 <= 2.0 * HEIGHT_TOLERANCE * -y.d2;
            x = y;
            if converged {
                break;
            }
        }
        Ok(Node {
            s: best.s,
            e: sigma * best.e,
            d1: sigma * best.d1,
            d2: sigma * best.d2,
        })
    }
}

/// The most σ·e can reach in the bracket [`lo`, `hi`] (σ applied: e′ ≥ 0 at `lo`, ≤ 0 at `hi`)
/// where e′ falls monotonically across it (e concave there): below both ends' tangents, so at
/// most where they cross. Never above `max(e(ends)) + width·max|e′(ends)|`, the bound it
/// replaced, and far below it once one end has converged: the secant of e′ across the bracket
/// (on a ridge, where e″ is not formed) keeps landing on one side, the other end staying put.
fn bracket_gain(lo: &Node, hi: &Node) -> f64 {
    let (up, down) = (lo.d1, -hi.d1);
    let slopes = up + down;
    if slopes > 0.0 {
        let cross = ((hi.e - lo.e + lo.s * up + hi.s * down) / slopes).clamp(lo.s, hi.s);
        (lo.e + (cross - lo.s) * up).min(hi.e + (hi.s - cross) * down)
    } else {
        lo.e.max(hi.e) + (hi.s - lo.s) * up.max(down)
    }
}

/// The segment from `a` to `b`, whose jets are `ends`.
fn segment<'c, 'a>(
    ctx: &'c Context<'a>,
    a: &PathPoint,
    b: &PathPoint,
    ends: [Jet; 2],
) -> Result<Segment<'c, 'a>, UndefinedError> {
    for p in [a, b] {
        if !(p.rho.is_finite() && p.theta.is_finite() && p.z.is_finite()) {
            return Err(not_finite(p.rho, p.theta, "a path point"));
        }
    }
    let seg = Segment {
        ctx,
        rho0: a.rho,
        theta0: a.theta,
        z0: a.z,
        drho: b.rho - a.rho,
        dtheta: b.theta - a.theta,
        dz: b.z - a.z,
        ends,
    };
    if !(seg.drho.is_finite() && seg.dtheta.is_finite() && seg.dz.is_finite()) {
        return Err(not_finite(b.rho, b.theta, "the step between path points"));
    }
    Ok(seg)
}

/// The largest overcut and undercut of the linear move from `a` to `b` (consecutive points of
/// `tool_path`'s path; see the module docs).
pub fn segment_error(
    tool_path: &ToolPath,
    a: &PathPoint,
    b: &PathPoint,
) -> Result<SegmentError, UndefinedError> {
    let ctx = Context::new(tool_path);
    let ends = [ctx.jet_of_point(a)?, ctx.jet_of_point(b)?];
    segment(&ctx, a, b, ends)?.errors()
}

/// The error of the segment from `a` to `b` ([`segment_error`]); for the path's first point
/// (`a` None) none, after the check [`LinearizationCheck::add`] makes of a first point (its
/// contact's surface is defined). What [`LinearizationCheck::take`] is fed from other threads.
pub fn error_ending_at(
    tool_path: &ToolPath,
    a: Option<&PathPoint>,
    b: &PathPoint,
) -> Result<Option<SegmentError>, UndefinedError> {
    match a {
        Some(a) => segment_error(tool_path, a, b).map(Some),
        None => Context::new(tool_path).jet_of_point(b).map(|_| None),
    }
}

/// The sample intervals the check of the move from `a` to `b` takes (at least
/// [`MIN_INTERVALS`], at most [`MAX_INTERVALS`]; see the module docs), for an estimate of its
/// cost: its interior samples are one compensation each, as its refined points are.
pub fn segment_intervals(
    tool_path: &ToolPath,
    a: &PathPoint,
    b: &PathPoint,
) -> Result<usize, UndefinedError> {
    let ctx = Context::new(tool_path);
    let ends = [ctx.jet_of_point(a)?, ctx.jet_of_point(b)?];
    Ok(segment(&ctx, a, b, ends)?.intervals())
}

/// e(s), de/ds and d²e/ds² of the move from `a` to `b` at s (0 and 1 use the points' own
/// contacts, so e is exactly 0 there), for checks and plots.
pub fn error_at(
    tool_path: &ToolPath,
    a: &PathPoint,
    b: &PathPoint,
    s: f64,
) -> Result<ErrorSample, UndefinedError> {
    let ctx = Context::new(tool_path);
    let seg = segment(&ctx, a, b, [ctx.jet_of_point(a)?, ctx.jet_of_point(b)?])?;
    let n = if s == 0.0 {
        seg.node(0.0, 0.0, &seg.ends[0])
    } else if s == 1.0 {
        seg.node(1.0, 0.0, &seg.ends[1])
    } else if s.is_finite() {
        seg.eval(s)?
    } else {
        return Err(not_finite(a.rho, a.theta, "the segment parameter"));
    };
    Ok(ErrorSample {
        s,
        rho: seg.rho(s),
        theta: seg.theta(s),
        error_mm: n.e,
        slope_mm: n.d1,
        curvature_mm: if n.d2.is_finite() { n.d2 } else { f64::NAN },
    })
}

/// Checks a path point by point, in order.
#[derive(Debug, Clone)]
pub struct LinearizationCheck {
    prev: Option<(PathPoint, Jet)>,
    segments: u64,
    overcut: Option<Extreme>,
    undercut: Option<Extreme>,
    map: Raster,
}

impl LinearizationCheck {
    /// A check of a path of `tool_path`, mapped on a `map_size` × `map_size` raster over the part
    /// (clamped as [`Raster::over_part`] does).
    pub fn new(tool_path: &ToolPath, map_size: usize) -> Self {
        Self {
            prev: None,
            segments: 0,
            overcut: None,
            undercut: None,
            map: Raster::over_part(tool_path.job().part_radius_mm(), map_size),
        }
    }

    /// Takes the next point of the path (the first only starts it).
    pub fn add(&mut self, tool_path: &ToolPath, p: &PathPoint) -> Result<(), UndefinedError> {
        let ctx = Context::new(tool_path);
        let jet = ctx.jet_of_point(p)?;
        if let Some((a, ja)) = &self.prev {
            let err = segment(&ctx, a, p, [*ja, jet])?.errors()?;
            self.take(&err);
        }
        self.prev = Some((*p, jet));
        Ok(())
    }

    /// Takes the error of the path's next segment, computed elsewhere by [`error_ending_at`]
    /// (on another thread: the same figures as [`Self::add`] point by point, when every
    /// segment is taken in order). Not to be mixed with `add` on one check.
    pub fn take(&mut self, err: &SegmentError) {
        self.segments += 1;
        for x in [err.overcut, err.undercut] {
            let (s, c) = x.theta.sin_cos();
            self.map
                .keep_largest(x.rho * c, x.rho * s, x.error_mm * 1e3);
        }
        if self
            .overcut
            .is_none_or(|o| err.overcut.error_mm < o.error_mm)
        {
            self.overcut = Some(err.overcut);
        }
        if self
            .undercut
            .is_none_or(|u| err.undercut.error_mm > u.error_mm)
        {
            self.undercut = Some(err.undercut);
        }
    }

    /// The figures of the path seen so far.
    pub fn finish(self) -> LinearizationReport {
        let at = |x: Option<Extreme>| x.map_or(Location::new(0.0, 0.0), |x| x.location());
        let over = self.overcut.map_or(0.0, |x| -x.error_mm * 1e3).max(0.0);
        let under = self.undercut.map_or(0.0, |x| x.error_mm * 1e3).max(0.0);
        LinearizationReport {
            segments: self.segments,
            max_overcut_um: over,
            max_overcut_at: at(self.overcut),
            max_undercut_um: under,
            max_undercut_at: at(self.undercut),
            pv_um: over + under,
            worst_at: if over > under {
                at(self.overcut)
            } else {
                at(self.undercut)
            },
            map: self.map,
        }
    }
}

/// Checks the whole path of `tool_path`, mapped on a `map_size` raster; `progress` gets the points
/// done every [`PROGRESS_EVERY`] points and at the end.
pub fn analyse(
    tool_path: &ToolPath,
    map_size: usize,
    mut progress: impl FnMut(u64),
) -> Result<LinearizationReport, UndefinedError> {
    let mut check = LinearizationCheck::new(tool_path, map_size);
    let mut done = 0u64;
    for p in tool_path.points() {
        check.add(tool_path, &p?)?;
        done += 1;
        if done.is_multiple_of(PROGRESS_EVERY) {
            progress(done);
        }
    }
    progress(done);
    Ok(check.finish())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::Job;
    use crate::tool::ToolPath;

    fn planner(surface: &str, part_radius: f64, r: f64) -> ToolPath {
        let json = format!(
            r#"{{"name":"t","part":{{"diameter_mm":{}}},"surface":{surface},
            "tool":{{"nose_radius_mm":{r}}},"machine":{{"spindle_rpm":1000}},
            "strategy":{{"feed_mm_per_rev":0.3,"sampling":{{"type":"constant_angle","points_per_rev":12}}}}}}"#,
            2.0 * part_radius
        );
        ToolPath::new(&Job::from_json(&json).unwrap()).unwrap()
    }

    fn seg<'c, 'a>(ctx: &'c Context<'a>, a: (f64, f64), b: (f64, f64)) -> Segment<'c, 'a> {
        let ja = ctx.jet_at(a.0, a.1, None).unwrap();
        let jb = ctx.jet_at(b.0, b.1, None).unwrap();
        let (za, zb) = (ja.z_tip, jb.z_tip);
        Segment {
            ctx,
            rho0: a.0,
            theta0: a.1,
            z0: za,
            drho: b.0 - a.0,
            dtheta: b.1 - a.1,
            dz: zb - za,
            ends: [ja, jb],
        }
    }

    #[test]
    fn on_the_part_edge_the_contact_stays_on_the_edge() {
        // A concave sphere rises at the part edge, so a nose over the edge touches the edge
        // itself, where the arc is cut: ρ_c = R and a = asin((R − ρ_s)/r). The derivatives of
        // that regime agree with central differences (h = 1e-5: truncation and rounding below
        // 1e-10 mm here); those of a free contact would not.
        let p = planner(r#"{"type":"asphere","radius_mm":20}"#, 3.0, 0.5);
        let ctx = Context::new(&p);
        let j = ctx.jet_at(3.01, 0.2, None).unwrap();
        assert_eq!(j.regime, Regime::PartEdge);
        assert!((j.rho_c - 3.0).abs() < 1e-12);
        assert_eq!(ctx.jet_at(2.0, 0.2, None).unwrap().regime, Regime::Free);
        let segment = seg(&ctx, (3.03, 0.1), (2.99, 0.5));
        let s = 0.4;
        let (h, x) = (1e-5, segment.eval(s).unwrap());
        let (xp, xm) = (segment.eval(s + h).unwrap(), segment.eval(s - h).unwrap());
        assert!((x.d1 - (xp.e - xm.e) / (2.0 * h)).abs() < 1e-10);
        assert!((x.d2 - (xp.d1 - xm.d1) / (2.0 * h)).abs() < 1e-8 * (1.0 + x.d2.abs()));
        let free = Jet {
            regime: Regime::Free,
            ..ctx.jet_at(segment.rho(s), segment.theta(s), None).unwrap()
        };
        let (z1, _) = ctx.z_derivatives(&free, segment.drho, segment.dtheta);
        assert!((segment.dz - z1 - x.d1).abs() > 1e-4);
    }

    #[test]
    fn samples_follow_the_feature_length_and_the_angle_step() {
        let p = planner(r#"{"type":"asphere","radius_mm":20}"#, 3.0, 0.0);
        let ctx = Context::new(&p);
        // A smooth surface: four intervals, or one per 15° of Δθ.
        assert_eq!(seg(&ctx, (2.0, 0.0), (1.9, 0.1)).intervals(), MIN_INTERVALS);
        assert_eq!(seg(&ctx, (2.0, 0.0), (1.9, 2.0)).intervals(), 8);
        // A sinusoid with features of λ/4 = 0.1 mm: 8 per 0.1 mm of the contact's path
        // |Δρ| + ρ_max·|Δθ| = 0.125 + 2·0.18 = 0.485 mm, 38.8 intervals.
        let p = planner(
            r#"{"type":"sinusoid","amplitude_mm":0.001,"wavelength_x_mm":0.4,"wavelength_y_mm":0.4}"#,
            3.0,
            0.0,
        );
        let ctx = Context::new(&p);
        assert_eq!(p.surface().feature_length_mm(), 0.1);
        assert_eq!(seg(&ctx, (2.0, 0.0), (1.875, 0.18)).intervals(), 39);
        // Capped.
        assert_eq!(seg(&ctx, (2.0, 0.0), (1.9, 1e3)).intervals(), MAX_INTERVALS);
    }

    #[test]
    fn refinement_converges_on_a_smooth_extreme_in_a_few_steps() {
        // Paraboloid, sharp tool: e(s) = Δρ²/(2R)·s(1 − s), its maximum Δρ²/(8R) at s = ½.
        let p = planner(r#"{"type":"asphere","radius_mm":10,"conic":-1}"#, 3.0, 0.0);
        let ctx = Context::new(&p);
        let segment = seg(&ctx, (2.0, 0.0), (1.7, 0.4));
        let (lo, hi) = (segment.eval(0.3).unwrap(), segment.eval(0.9).unwrap());
        let top = segment.refine(lo, hi, 1.0).unwrap();
        assert!((top.e - 0.09 / 80.0).abs() < 1e-15);
        assert!((top.s - 0.5).abs() < 1e-7);
    }

    #[test]
    fn the_bracket_bound_holds_every_concave_e_and_tightens_the_old_one() {
        // Concave e on [a, b] with e′(a) > 0 > e′(b): a parabola, a quartic, a kink (two lines,
        // where the tangents meet at the maximum itself) and a ridge-like kink with curved
        // sides. The bound must lie above the maximum on a dense grid (brute force) and below
        // the width·max|e′| bound it replaced; on the kink it is the maximum.
        type Fun = (Box<dyn Fn(f64) -> f64>, Box<dyn Fn(f64) -> f64>);
        let cases: Vec<(Fun, f64, f64)> = vec![
            (
                (
                    Box::new(|s| -(s - 0.4) * (s - 0.4)),
                    Box::new(|s| -2.0 * (s - 0.4)),
                ),
                0.0,
                1.0,
            ),
            (
                (
                    Box::new(|s| -(s - 0.7f64).powi(4) - 0.1 * s * s),
                    Box::new(|s| -4.0 * (s - 0.7f64).powi(3) - 0.2 * s),
                ),
                0.2,
                0.95,
            ),
            (
                (
                    Box::new(|s: f64| (3.0 * s).min(1.0 - s)),
                    Box::new(|s| if s < 0.25 { 3.0 } else { -1.0 }),
                ),
                0.0,
                1.0,
            ),
            (
                (
                    Box::new(|s: f64| (2.0 * s - s * s).min(0.9 - 0.5 * s * s)),
                    Box::new(|s| {
                        if 2.0 * s - s * s < 0.9 - 0.5 * s * s {
                            2.0 - 2.0 * s
                        } else {
                            -s
                        }
                    }),
                ),
                0.1,
                0.9,
            ),
        ];
        for ((e, d), a, b) in cases {
            let node = |s: f64| Node {
                s,
                e: e(s),
                d1: d(s),
                d2: f64::NAN,
            };
            let (lo, hi) = (node(a), node(b));
            let top = (0..=100_000)
                .map(|k| e(a + (b - a) * k as f64 / 100_000.0))
                .fold(f64::MIN, f64::max);
            let bound = bracket_gain(&lo, &hi);
            let old = lo.e.max(hi.e) + (b - a) * lo.d1.max(-hi.d1);
            assert!(bound >= top - 1e-15, "[{a}, {b}]: {bound} < {top}");
            assert!(bound <= old, "[{a}, {b}]: {bound} > {old}");
        }
        let kink = |s: f64| (3.0 * s).min(1.0 - s);
        let (lo, hi) = (
            Node {
                s: 0.0,
                e: 0.0,
                d1: 3.0,
                d2: f64::NAN,
            },
            Node {
                s: 1.0,
                e: kink(1.0),
                d1: -1.0,
                d2: f64::NAN,
            },
        );
        assert!((bracket_gain(&lo, &hi) - 0.75).abs() < 1e-15);
    }
}
