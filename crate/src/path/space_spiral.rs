//! The space Archimedean spiral (paper 001): a spiral laid by arc length on a best-fit surface of
//! revolution, the *base surface*, and projected onto the design surface along the base
//! surface's normal.
//!
//! The axis of revolution is Z (the spindle axis). The steps, as this module reads the paper:
//!
//! 1. **Base surface** (paper 001 eqs 10–11 with the axis `t` = Z given). The design sag is
//!    sampled on a polar grid (rings × angles) over the part, the samples are "rotated to a
//!    plane" (kept as `(ρ, z)` pairs) and the generating curve `z_b(ρ)` is fitted by linear least
//!    squares as a clamped cubic B-spline with uniform knots on `[0, R]`. The first two control
//!    points are tied (`c₀ = c₁`), which makes `z_b′(0) = 0`: the base surface is smooth on the
//!    axis, with no cone at the apex. [`BaseSurface::fit`] reports the residual (RMS and max, µm).
//!    The paper minimises `max α`; least squares on the sag is its practical choice too (§4,
//!    "the least square method is used to fit the revolved projected points").
//! 2. **Quasi-revolution test** (eq 9): `α = arccos |n₁·n₂|`, `n₁` the unit normal of the design
//!    surface at a point, `n₂` the unit normal of the base surface; the surface is of
//!    quasi-revolution when `max α < α_lim`. Here `n₂` is taken at the same `(x, y)` as `n₁`
//!    rather than at the nearest point of the base surface: the two differ by the fit gap, of
//!    the order of the residual, which moves `n₂` by (gap × base curvature), negligible for a
//!    surface close to one of revolution. The paper gives no value for `α_lim`; the default here
//!    is [`DEFAULT_ALPHA_LIM_DEG`] = 10°.
//! 3. **Space spiral** (eqs 5–7): with `s` the arc length along the generating curve from the
//!    axis, `s = a + bθ` with `|b| = f/2π`; this module runs from the rim to the centre,
//!    `s(θ) = S − f·θ/2π` (`S` the arc length of the whole generating curve), so adjacent passes
//!    are `f` apart *on the base surface*, measured along its meridian. The point is
//!    `(ρ(s) cos θ, ρ(s) sin θ, z_b(ρ(s)))`, `ρ(s)` the inverse of the arc length. Points are
//!    taken at constant angle, `N` per revolution.
//! 4. **Projection** along the base normal `n_b = (−z_b′ cos θ, −z_b′ sin θ, 1)/√(1 + z_b′²)`:
//!    solve `g(t) = p_z + t n_z − f(p_x + t n_x, p_y + t n_y) = 0` by Newton's method,
//!    `g′(t) = n_z − f_x n_x − f_y n_y` (from the analytic gradient), with step halving where the
//!    residual does not fall or the surface is undefined. A plane base (`z_b′ ≡ 0`) is the
//!    ordinary projection along Z ([`z_projection`]).
//!
//! [`pass_spacing`] measures the 3-D distance between a point and the point one revolution
//! further in at the same angle, for either path.
//!
//! The planner uses it as the sampling `space_spiral` ([`spiral`] builds the spiral points
//! from the projected design points).

use crate::field::{FieldError, in_range, positive};
use crate::job::StrategySpec;
use crate::path::spiral::{MAX_EXPLICIT_POINTS, Spiral, SpiralPoint, check_points_per_rev};
use crate::surface::nurbs::basis::KnotVector;
use crate::surface::{Surface, UndefinedError};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;
use std::f64::consts::TAU;
use thiserror::Error;

/// Default allowable angle α_lim of the quasi-revolution test, degrees (the paper gives none).
pub const DEFAULT_ALPHA_LIM_DEG: f64 = 10.0;

/// What can go wrong while fitting the base surface or laying the space spiral.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SpaceSpiralError {
    /// A parameter out of range, e.g. `spans: must be at least 1, got 0`.
    #[error("{name}: {reason}")]
    Invalid {
        /// The parameter.
        name: &'static str,
        /// Why, with the value.
        reason: String,
    },
    /// The design surface has no value at a sample point.
    #[error(transparent)]
    Undefined(#[from] UndefinedError),
    /// The least-squares solve failed (a rank-deficient system).
    #[error("least-squares fit of the base generating curve failed: {0}")]
    Fit(String),
    /// Newton's method did not find where the base normal meets the design surface.
    #[error(
        "projection along the base normal from ({x_mm}, {y_mm}, {z_mm}) mm did not reach the \
         design surface: {reason}"
    )]
    Projection {
        /// Base point, mm.
        x_mm: f64,
        /// Base point, mm.
        y_mm: f64,
        /// Base point, mm.
        z_mm: f64,
        /// Why (the residual, or the normal tangent to the surface).
        reason: String,
    },
}

fn invalid(name: &'static str, reason: String) -> SpaceSpiralError {
    SpaceSpiralError::Invalid { name, reason }
}

/// Options of the base-surface fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BaseFitOptions {
    /// Number of uniform knot spans of the cubic B-spline on `[0, R]`; default 8.
    pub spans: usize,
    /// Sample rings from the axis to the rim (ring 0 is the axis itself); default 64.
    pub rings: usize,
    /// Samples per ring; default 64.
    pub angles: usize,
}

impl Default for BaseFitOptions {
    fn default() -> Self {
        Self {
            spans: 8,
            rings: 64,
            angles: 64,
        }
    }
}

/// The best-fit surface of revolution about Z: `z = z_b(ρ)`, a clamped cubic B-spline on
/// `[0, R]` with uniform knots, and its arc-length table.
#[derive(Debug, Clone, PartialEq)]
pub struct BaseSurface {
    radius_mm: f64,
    /// The knots (degree 3), evaluated with the NURBS module's basis functions.
    knots: KnotVector,
    /// Control values of z_b.
    c: Vec<f64>,
    /// Cumulative arc length along the generating curve at `ρ_k = k·R/M`.
    arc_table: Vec<f64>,
}

/// The fitted base surface and the residual of the fit over the samples.
#[derive(Debug, Clone, PartialEq)]
pub struct BaseFit {
    /// The base surface.
    pub base: BaseSurface,
    /// RMS of `f(x, y) − z_b(ρ)` over the polar grid, µm.
    pub rms_um: f64,
    /// Largest `|f(x, y) − z_b(ρ)|` over the polar grid, µm.
    pub max_um: f64,
}

/// 5-point Gauss–Legendre nodes and weights on [−1, 1].
const GL_X: [f64; 5] = [
    0.0,
    -0.538_469_310_105_683,
    0.538_469_310_105_683,
    -0.906_179_845_938_664,
    0.906_179_845_938_664,
];
const GL_W: [f64; 5] = [
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_5,
    0.478_628_670_499_366_5,
    0.236_926_885_056_189_1,
    0.236_926_885_056_189_1,
];

/// Arc-length table pieces per knot span.
const ARC_PIECES_PER_SPAN: usize = 32;

impl BaseSurface {
    /// Fits the generating curve about Z to the design sag over a part of radius
    /// `part_radius_mm` (see the module docs, step 1).
    pub fn fit(
        surface: &dyn Surface,
        part_radius_mm: f64,
        options: &BaseFitOptions,
    ) -> Result<BaseFit, SpaceSpiralError> {
        let r = part_radius_mm;
        if !(r.is_finite() && r > 0.0) {
            return Err(invalid(
                "part_radius_mm",
                format!("must be finite and positive, got {r}"),
            ));
        }
        let BaseFitOptions {
            spans,
            rings,
            angles,
        } = *options;
        if spans == 0 {
            return Err(invalid("spans", "must be at least 1, got 0".into()));
        }
        // Unknowns: spans + 3 control values less one (c₀ = c₁). Rings 0..=rings give
        // rings + 1 distinct ρ; ask for twice the unknowns.
        let unknowns = spans + 2;
        if rings < 2 * unknowns {
            return Err(invalid(
                "rings",
                format!(
                    "must be at least 2·(spans + 2) = {}, got {rings}",
                    2 * unknowns
                ),
            ));
        }
        if angles == 0 {
            return Err(invalid("angles", "must be at least 1, got 0".into()));
        }
        let h = r / spans as f64;
        let mut knot_values = vec![0.0; 4];
        knot_values.extend((1..spans).map(|k| k as f64 * h));
        knot_values.extend([r; 4]);
        let n_basis = spans + 3;
        let knots = KnotVector::new("spans", 3, n_basis, &knot_values)
            .map_err(|e| invalid("spans", e.to_string()))?;

        // Sample the design; rows of one ring share the basis row, so the least-squares
        // problem reduces to one row per ring weighted by √(samples on the ring) with the
        // ring's mean sag (the normal equations are the same).
        let mut ring_rho = Vec::with_capacity(rings + 1);
        let mut samples: Vec<Vec<f64>> = Vec::with_capacity(rings + 1);
        for i in 0..=rings {
            let rho = r * i as f64 / rings as f64;
            let m = if i == 0 { 1 } else { angles };
            let mut zs = Vec::with_capacity(m);
            for j in 0..m {
                let th = TAU * j as f64 / m as f64;
                zs.push(surface.sag(rho * th.cos(), rho * th.sin())?);
            }
            ring_rho.push(rho);
            samples.push(zs);
        }
        let mut a = DMatrix::<f64>::zeros(rings + 1, unknowns);
        let mut b = DVector::<f64>::zeros(rings + 1);
        for (row, (&rho, zs)) in ring_rho.iter().zip(&samples).enumerate() {
            let w = (zs.len() as f64).sqrt();
            let i = knots.span(rho);
            let n = knots.ders(i, rho, 0)[0];
            for (j, &nj) in n[..4].iter().enumerate() {
                let col = (i - 3 + j).saturating_sub(1); // c₀ and c₁ share column 0
                a[(row, col)] += w * nj;
            }
            b[row] = w * zs.iter().sum::<f64>() / zs.len() as f64;
        }
        let x = a
            .svd(true, true)
            .solve(&b, 1e-14)
            .map_err(|e| SpaceSpiralError::Fit(e.to_string()))?;
        let mut c = Vec::with_capacity(n_basis);
        c.push(x[0]);
        c.extend(x.iter().copied());
        let mut base = Self {
            radius_mm: r,
            knots,
            c,
            arc_table: Vec::new(),
        };
        base.build_arc_table();
        // Sags near the largest double fit to infinities, and every later step would be NaN.
        if !(base.c.iter().all(|v| v.is_finite()) && base.total_arc_length().is_finite()) {
            return Err(SpaceSpiralError::Fit(
                "the base curve fitted to the design's sags is not finite (sags too large)".into(),
            ));
        }

        let (mut sum2, mut max, mut count) = (0.0_f64, 0.0_f64, 0usize);
        for (&rho, zs) in ring_rho.iter().zip(&samples) {
            let zb = base.z(rho);
            for &z in zs {
                let d = z - zb;
                sum2 += d * d;
                max = max.max(d.abs());
                count += 1;
            }
        }
        Ok(BaseFit {
            base,
            rms_um: 1e3 * (sum2 / count as f64).sqrt(),
            max_um: 1e3 * max,
        })
    }

    /// Radius of the part the curve was fitted over, mm.
    pub fn radius_mm(&self) -> f64 {
        self.radius_mm
    }

    /// The `order`-th derivative (0, 1, 2) of z_b at ρ; beyond `[0, R]` the end polynomials
    /// continue.
    fn derivative(&self, rho: f64, order: usize) -> f64 {
        let span = self.knots.span(rho);
        let d = self.knots.ders(span, rho, order);
        (0..4).map(|j| d[order][j] * self.c[span - 3 + j]).sum()
    }

    /// `z_b(ρ)`, mm (even in ρ).
    pub fn z(&self, rho: f64) -> f64 {
        self.derivative(rho.abs(), 0)
    }

    /// `dz_b/dρ` at ρ ≥ 0.
    pub fn slope(&self, rho: f64) -> f64 {
        self.derivative(rho, 1)
    }

    /// `d²z_b/dρ²` at ρ ≥ 0, 1/mm.
    pub fn curvature_term(&self, rho: f64) -> f64 {
        self.derivative(rho, 2)
    }

    /// Unit normal of the base surface at `(x, y)`, pointing to +Z.
    pub fn normal(&self, x: f64, y: f64) -> [f64; 3] {
        let rho = x.hypot(y);
        if rho == 0.0 {
            return [0.0, 0.0, 1.0];
        }
        let d = self.slope(rho);
        let n = (1.0 + d * d).sqrt();
        [-d * x / (rho * n), -d * y / (rho * n), 1.0 / n]
    }

    fn arc_pieces(&self) -> usize {
        (self.knots.count() - 3) * ARC_PIECES_PER_SPAN
    }

    /// `∫ √(1 + z_b′²) dρ` over `[r0, r1]` by 5-point Gauss–Legendre (one call per short piece).
    fn arc_piece(&self, r0: f64, r1: f64) -> f64 {
        let (m, hw) = (0.5 * (r0 + r1), 0.5 * (r1 - r0));
        GL_X.iter()
            .zip(GL_W)
            .map(|(&x, w)| {
                let d = self.slope(m + hw * x);
                w * (1.0 + d * d).sqrt()
            })
            .sum::<f64>()
            * hw
    }

    fn build_arc_table(&mut self) {
        let m = self.arc_pieces();
        let dr = self.radius_mm / m as f64;
        let mut t = Vec::with_capacity(m + 1);
        t.push(0.0);
        for k in 0..m {
            let s = t[k] + self.arc_piece(k as f64 * dr, (k + 1) as f64 * dr);
            t.push(s);
        }
        self.arc_table = t;
    }

    /// Arc length along the generating curve from the axis to ρ ∈ [0, R], mm.
    ///
    /// Each table piece is a fraction 1/32 of a knot span, on which z_b′ is a quadratic: the
    /// 5-point rule is exact for polynomials of degree 9 and √(1 + z_b′²) is analytic there, so
    /// the error is far below 1e-12 mm for the slopes met in practice.
    pub fn arc_length(&self, rho: f64) -> f64 {
        let m = self.arc_pieces();
        let dr = self.radius_mm / m as f64;
        let k = ((rho / dr).floor() as usize).min(m - 1);
        self.arc_table[k] + self.arc_piece(k as f64 * dr, rho)
    }

    /// Arc length of the whole generating curve, axis to rim, mm.
    pub fn total_arc_length(&self) -> f64 {
        *self.arc_table.last().unwrap_or(&0.0)
    }

    /// The ρ at which the arc length from the axis is `s` (clamped to `[0, S]`): table lookup,
    /// then Newton on `s(ρ) − s` with `ds/dρ = √(1 + z_b′²) ≥ 1`.
    pub fn rho_at_arc(&self, s: f64) -> f64 {
        let s = s.clamp(0.0, self.total_arc_length());
        let m = self.arc_pieces();
        let dr = self.radius_mm / m as f64;
        let k = self.arc_table.partition_point(|&t| t <= s).clamp(1, m) - 1;
        let (s0, s1) = (self.arc_table[k], self.arc_table[k + 1]);
        let mut rho = dr * (k as f64 + if s1 > s0 { (s - s0) / (s1 - s0) } else { 0.0 });
        for _ in 0..8 {
            let e = self.arc_table[k] + self.arc_piece(k as f64 * dr, rho) - s;
            let d = self.slope(rho);
            let step = e / (1.0 + d * d).sqrt();
            rho -= step;
            if step.abs() < 1e-15 * self.radius_mm {
                break;
            }
        }
        rho.clamp(0.0, self.radius_mm)
    }
}

/// The result of the quasi-revolution test (eq 9).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct QuasiRevolution {
    /// `max α` over the polar grid, degrees.
    pub max_alpha_deg: f64,
    /// Where the maximum is, mm.
    pub at_xy_mm: (f64, f64),
    /// The limit tested against, degrees.
    pub alpha_lim_deg: f64,
    /// `max α < α_lim`.
    pub is_quasi_revolution: bool,
}

/// `max α = max arccos |n_design · n_base|` over the polar grid of `options` (rings × angles
/// out to the base's radius), against `alpha_lim_deg` (module docs, step 2).
pub fn quasi_revolution(
    surface: &dyn Surface,
    base: &BaseSurface,
    options: &BaseFitOptions,
    alpha_lim_deg: f64,
) -> Result<QuasiRevolution, SpaceSpiralError> {
    let r = base.radius_mm;
    let (mut best, mut at) = (0.0_f64, (0.0, 0.0));
    for i in 0..=options.rings {
        let rho = r * i as f64 / options.rings.max(1) as f64;
        let m = if i == 0 { 1 } else { options.angles.max(1) };
        for j in 0..m {
            let th = TAU * j as f64 / m as f64;
            let (x, y) = (rho * th.cos(), rho * th.sin());
            let n1 = surface.local(x, y)?.normal();
            let n2 = base.normal(x, y);
            let c = (n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2])
                .abs()
                .min(1.0);
            let alpha = c.acos();
            if alpha > best {
                best = alpha;
                at = (x, y);
            }
        }
    }
    let max_alpha_deg = best.to_degrees();
    Ok(QuasiRevolution {
        max_alpha_deg,
        at_xy_mm: at,
        alpha_lim_deg,
        is_quasi_revolution: max_alpha_deg < alpha_lim_deg,
    })
}

/// One point of a projected spiral.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpacePoint {
    /// Spiral angle θ from the start, rad (increasing inwards).
    pub theta: f64,
    /// The point on the base surface (or on the plane z = 0 for [`z_projection`]), mm.
    pub base: [f64; 3],
    /// The projection direction (unit base normal, or +Z).
    pub direction: [f64; 3],
    /// The point on the design surface, `base + t·direction`, mm.
    pub design: [f64; 3],
}

/// Projects `p` onto the design surface along the unit vector `n` (module docs, step 4). The
/// result satisfies `|z − f(x, y)| ≤ 1e-12 mm` or an error is returned.
pub fn project_along(
    surface: &dyn Surface,
    p: [f64; 3],
    n: [f64; 3],
) -> Result<[f64; 3], SpaceSpiralError> {
    const TOL: f64 = 1e-12;
    let fail = |reason: String| SpaceSpiralError::Projection {
        x_mm: p[0],
        y_mm: p[1],
        z_mm: p[2],
        reason,
    };
    let at = |t: f64| [p[0] + t * n[0], p[1] + t * n[1], p[2] + t * n[2]];
    let mut t = 0.0;
    let q = at(t);
    let mut l = surface.local(q[0], q[1]).map_err(|e| fail(e.to_string()))?;
    let mut g = q[2] - l.z;
    for _ in 0..60 {
        if g.abs() <= TOL {
            return Ok(at(t));
        }
        let dg = n[2] - l.zx * n[0] - l.zy * n[1];
        if dg.abs() < 1e-9 {
            return Err(fail(format!(
                "the base normal is tangent to the design surface (g′ = {dg:e}, residual {g:e} mm)"
            )));
        }
        let mut step = -g / dg;
        let mut accepted = false;
        for _ in 0..40 {
            let q = at(t + step);
            if let Ok(ln) = surface.local(q[0], q[1]) {
                let gn = q[2] - ln.z;
                if gn.abs() < g.abs() {
                    t += step;
                    l = ln;
                    g = gn;
                    accepted = true;
                    break;
                }
            }
            step *= 0.5;
        }
        if !accepted {
            return Err(fail(format!(
                "Newton's method stalled at t = {t} mm with residual {g:e} mm"
            )));
        }
    }
    if g.abs() <= TOL {
        Ok(at(t))
    } else {
        Err(fail(format!(
            "no convergence in 60 iterations (residual {g:e} mm)"
        )))
    }
}

fn check_spiral_args(feed_mm: f64, points_per_rev: usize) -> Result<(), SpaceSpiralError> {
    if !(feed_mm.is_finite() && feed_mm > 0.0) {
        return Err(invalid(
            "feed_mm",
            format!("must be finite and positive, got {feed_mm}"),
        ));
    }
    if points_per_rev < 3 {
        return Err(invalid(
            "points_per_rev",
            format!("must be at least 3, got {points_per_rev}"),
        ));
    }
    Ok(())
}

/// The space Archimedean spiral projected onto the design surface (module docs, steps 3–4):
/// `s(θ) = S − f·θ/2π` along the base generating curve, `points_per_rev` points per
/// revolution at constant angle, from the rim while `s ≥ 0` (the point at exactly `s = 0` is
/// included only when `N·S/f` is an integer).
pub fn space_spiral(
    surface: &dyn Surface,
    base: &BaseSurface,
    feed_mm: f64,
    points_per_rev: usize,
) -> Result<Vec<SpacePoint>, SpaceSpiralError> {
    check_spiral_args(feed_mm, points_per_rev)?;
    let count = space_spiral_count(base, feed_mm, points_per_rev);
    (0..count)
        .map(|k| {
            let theta = TAU * k as f64 / points_per_rev as f64;
            let s = base.total_arc_length() - feed_mm * k as f64 / points_per_rev as f64;
            space_point(surface, base, s, theta, theta)
        })
        .collect()
}

/// Points of [`space_spiral`]: `⌊N·S/f⌋ + 1`.
pub fn space_spiral_count(base: &BaseSurface, feed_mm: f64, points_per_rev: usize) -> usize {
    (points_per_rev as f64 * base.total_arc_length() / feed_mm + 1e-9).floor() as usize + 1
}

/// The point of the space spiral at arc length `s` from the axis along the base meridian,
/// spiral angle `theta` (stored in the result), laid at the polar angle `polar` in XY (θ for
/// [`space_spiral`]; the planner adds its start angle and direction), projected onto the design
/// surface along the base normal.
pub fn space_point(
    surface: &dyn Surface,
    base: &BaseSurface,
    s: f64,
    theta: f64,
    polar: f64,
) -> Result<SpacePoint, SpaceSpiralError> {
    let rho = base.rho_at_arc(s);
    let (sn, cs) = polar.sin_cos();
    let (x, y) = (rho * cs, rho * sn);
    let p = [x, y, base.z(rho)];
    let d = base.slope(rho);
    let w = (1.0 + d * d).sqrt();
    let n = [-d * cs / w, -d * sn / w, 1.0 / w];
    let design = project_along(surface, p, n)?;
    Ok(SpacePoint {
        theta,
        base: p,
        direction: n,
        design,
    })
}

/// The ordinary spiral projected along Z: `ρ(θ) = R − f·θ/2π` in the XY plane, the same angle
/// sampling as [`space_spiral`], each point lifted to `z = f(x, y)`.
pub fn z_projection(
    surface: &dyn Surface,
    part_radius_mm: f64,
    feed_mm: f64,
    points_per_rev: usize,
) -> Result<Vec<SpacePoint>, SpaceSpiralError> {
    check_spiral_args(feed_mm, points_per_rev)?;
    let count = (points_per_rev as f64 * part_radius_mm / feed_mm + 1e-9).floor() as usize + 1;
    let mut out = Vec::with_capacity(count);
    for k in 0..count {
        let theta = TAU * k as f64 / points_per_rev as f64;
        let rho = (part_radius_mm - feed_mm * k as f64 / points_per_rev as f64).max(0.0);
        let (sn, cs) = theta.sin_cos();
        let (x, y) = (rho * cs, rho * sn);
        let z = surface.sag(x, y)?;
        out.push(SpacePoint {
            theta,
            base: [x, y, 0.0],
            direction: [0.0, 0.0, 1.0],
            design: [x, y, z],
        });
    }
    Ok(out)
}

/// The spiral of the `space_spiral` sampling ([`crate::tool::spiral`] picks it): fits the base
/// surface over the outer radius, lays the space spiral (passes f apart along the base meridian,
/// N points per revolution, oriented by the strategy's start angle and direction, a last point
/// at s = 0 added where the constant-angle steps miss it) and takes the XY of the projected
/// design points as the spiral points, θ unwrapped within half a turn of the spiral's own angle.
/// The points are held in memory. Field errors are named relative to the strategy.
pub fn spiral(
    outer_radius_mm: f64,
    st: &StrategySpec,
    surface: &dyn Surface,
    points_per_rev: u32,
    base_spans: u32,
) -> Result<Spiral, FieldError> {
    check_points_per_rev(points_per_rev)?;
    if !(1..=64).contains(&base_spans) {
        return Err(FieldError::new(
            "sampling.base_spans",
            base_spans,
            "must lie in [1, 64]",
        ));
    }
    let feed = positive("feed_mm_per_rev", st.feed_mm_per_rev)?;
    let theta0 = in_range("start_angle_deg", st.start_angle_deg, -360.0, 360.0)?.to_radians();
    let fail = |e: SpaceSpiralError| FieldError::new("sampling", "space_spiral", e.to_string());
    let spans = base_spans as usize;
    let options = BaseFitOptions {
        spans,
        rings: (2 * (spans + 2)).max(64),
        angles: 64,
    };
    let base = BaseSurface::fit(surface, outer_radius_mm, &options)
        .map_err(fail)?
        .base;
    let n = points_per_rev as usize;
    let total = base.total_arc_length();
    let count = space_spiral_count(&base, feed, n);
    // The last constant-angle point lies at s = 0 or a centre point is added.
    let exact_end = total - feed * (count - 1) as f64 / n as f64 <= 1e-12 * total.max(1.0);
    let planned = count as u64 + u64::from(!exact_end);
    if planned > MAX_EXPLICIT_POINTS {
        return Err(FieldError::new(
            "sampling.points_per_rev",
            points_per_rev,
            format!(
                "with this feed gives {planned} points; a space spiral is held in memory (16 bytes a point) and at most {MAX_EXPLICIT_POINTS} are planned"
            ),
        ));
    }
    let sign = st.direction.sign();
    let point = |s: f64, theta: f64| -> Result<SpiralPoint, FieldError> {
        let polar = theta0 + sign * theta;
        let p = space_point(surface, &base, s, theta, polar).map_err(fail)?;
        let rho = p.design[0].hypot(p.design[1]);
        let dphi = if rho > 0.0 {
            let d = p.design[1].atan2(p.design[0]) - polar;
            d - TAU * (d / TAU).round()
        } else {
            0.0
        };
        Ok(SpiralPoint {
            rho,
            theta: polar + dphi,
        })
    };
    let mut points = Vec::with_capacity(planned as usize);
    for k in 0..count {
        let theta = TAU * k as f64 / n as f64;
        points.push(point(total - feed * k as f64 / n as f64, theta)?);
    }
    if !exact_end {
        points.push(point(0.0, TAU * total / feed)?);
    }
    if let Some(last) = points.last_mut() {
        // The axis point projects along +Z onto the axis.
        last.rho = 0.0;
    }
    Spiral::from_points(feed, &st.sampling, points)
}

/// Spacing between adjacent passes on the design surface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PassSpacing {
    /// Smallest 3-D distance between a point and the point one revolution further in, mm.
    pub min_mm: f64,
    /// Largest such distance, mm.
    pub max_mm: f64,
    /// `max/min`.
    pub ratio: f64,
    /// Number of pairs measured.
    pub pairs: usize,
}

/// For each point `i` with a point `i + N` (the same angle, next revolution in), the 3-D
/// distance between their design points; min, max and ratio. `None` with fewer than N + 1 points.
pub fn pass_spacing(points: &[SpacePoint], points_per_rev: usize) -> Option<PassSpacing> {
    if points_per_rev == 0 || points.len() <= points_per_rev {
        return None;
    }
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for (a, b) in points.iter().zip(&points[points_per_rev..]) {
        let d = ((a.design[0] - b.design[0]).powi(2)
            + (a.design[1] - b.design[1]).powi(2)
            + (a.design[2] - b.design[2]).powi(2))
        .sqrt();
        lo = lo.min(d);
        hi = hi.max(d);
    }
    Some(PassSpacing {
        min_mm: lo,
        max_mm: hi,
        ratio: hi / lo,
        pairs: points.len() - points_per_rev,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{Asphere, AsphereSpec};

    #[test]
    fn spline_reproduces_a_parabola_exactly() {
        // z = ρ²/20 is a cubic polynomial with z′(0) = 0, inside the spline space.
        let s = Asphere::new(&AsphereSpec {
            curvature_per_mm: Some(0.1),
            conic: -1.0,
            ..Default::default()
        })
        .unwrap();
        let fit = BaseSurface::fit(&s, 5.0, &BaseFitOptions::default()).unwrap();
        assert!(fit.max_um < 1e-9, "{}", fit.max_um);
        for rho in [0.0, 0.7, 2.5, 4.99] {
            assert!((fit.base.slope(rho) - rho / 10.0).abs() < 1e-12);
            assert!((fit.base.curvature_term(rho) - 0.1).abs() < 1e-10);
        }
        // Arc length of a parabola against its closed form, and the inverse.
        let closed = |r: f64| {
            let u = r / 10.0;
            5.0 * (u * (1.0 + u * u).sqrt() + u.asinh())
        };
        for rho in [0.3, 1.0, 4.0, 5.0] {
            assert!((fit.base.arc_length(rho) - closed(rho)).abs() < 1e-12);
            assert!((fit.base.rho_at_arc(closed(rho)) - rho).abs() < 1e-12);
        }
    }

    #[test]
    fn bad_options_name_their_field() {
        let s = Asphere::new(&AsphereSpec {
            radius_mm: Some(50.0),
            ..Default::default()
        })
        .unwrap();
        let e = BaseSurface::fit(
            &s,
            5.0,
            &BaseFitOptions {
                spans: 0,
                ..Default::default()
            },
        )
        .unwrap_err();
        assert!(e.to_string().starts_with("spans:"));
        let fit = BaseSurface::fit(&s, 5.0, &BaseFitOptions::default()).unwrap();
        let e = space_spiral(&s, &fit.base, 0.0, 16).unwrap_err();
        assert!(e.to_string().starts_with("feed_mm:"));
        // Sags near the largest double: an error, not a base of infinities (a NaN arc length
        // once panicked the survey of `spiralcam analyse` in a clamp).
        let huge = Asphere::new(&AsphereSpec {
            radius_mm: Some(50.0),
            coefficients: vec![f64::MAX],
            ..Default::default()
        })
        .unwrap();
        let e = BaseSurface::fit(&huge, 5.0, &BaseFitOptions::default()).unwrap_err();
        assert!(matches!(e, SpaceSpiralError::Fit(_)), "{e}");
        assert!(survey(&huge, 5.0, 0.01).is_err());
    }
}

/// Points per revolution of the paths [`survey`] compares (the spacing between passes does not
/// depend on it).
pub const SURVEY_POINTS_PER_REV: usize = 32;

/// How far a part is from a surface of revolution, and what the space spiral would gain: the
/// base fit's residual, the quasi-revolution test and the pass spacing of the space spiral
/// against plain projection along Z at the job's feed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Survey {
    /// RMS of the design about the fitted base surface, µm.
    pub base_fit_rms_um: f64,
    /// Largest departure of the design from the base surface, µm.
    pub base_fit_max_um: f64,
    /// The quasi-revolution test against [`DEFAULT_ALPHA_LIM_DEG`].
    pub quasi_revolution: QuasiRevolution,
    /// Pass spacing of the space spiral (passes f apart along the base meridian).
    pub space_spiral: Option<PassSpacing>,
    /// Pass spacing of the plain spiral projected along Z (passes f apart in ρ).
    pub z_projection: Option<PassSpacing>,
}

/// The [`Survey`] of `surface` over a part of radius `part_radius_mm` at a feed of `feed_mm`,
/// with the default fit options.
pub fn survey(
    surface: &dyn Surface,
    part_radius_mm: f64,
    feed_mm: f64,
) -> Result<Survey, SpaceSpiralError> {
    let options = BaseFitOptions::default();
    let fit = BaseSurface::fit(surface, part_radius_mm, &options)?;
    let quasi = quasi_revolution(surface, &fit.base, &options, DEFAULT_ALPHA_LIM_DEG)?;
    let n = SURVEY_POINTS_PER_REV;
    let space = space_spiral(surface, &fit.base, feed_mm, n)?;
    let plain = z_projection(surface, part_radius_mm, feed_mm, n)?;
    Ok(Survey {
        base_fit_rms_um: fit.rms_um,
        base_fit_max_um: fit.max_um,
        quasi_revolution: quasi,
        space_spiral: pass_spacing(&space, n),
        z_projection: pass_spacing(&plain, n),
    })
}
