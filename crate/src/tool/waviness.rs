//! The measured edge of a round nose (`tool.waviness`, issue 15): a real diamond's edge departs
//! from its nominal circle by a fraction of a micrometre, and tool makers and nose
//! interferometers give that departure as a table of nose angle a and radial deviation δ. The
//! edge then has the radius `R(a) = r + δ(a)` at nose angle a, its point at
//! `(R(a)·sin a, −R(a)·cos a)` from the nose centre in the radial plane (a from the tool axis
//! −Z, positive towards larger radius; [`crate::job::WavinessSpec`]).
//!
//! **Interpolation.** δ between the table's angles is the monotone piecewise cubic Hermite
//! interpolant (PCHIP: F. N. Fritsch and R. E. Carlson, "Monotone piecewise cubic
//! interpolation", SIAM J. Numer. Anal. 17(2), 1980), with the slopes of Fritsch and Butland for
//! unequal spacing as scipy's `PchipInterpolator` computes them: at an inner angle the weighted
//! harmonic mean of the two neighbouring secants (`w₁ = 2hₖ + hₖ₋₁`, `w₂ = hₖ + 2hₖ₋₁`), 0
//! where the secants differ in sign or one is 0; at the ends the three-point formula, set to 0
//! when its sign differs from the first secant's and limited to 3× the secant when the secants
//! differ in sign. So δ is C¹, never overshoots the table (its extrema lie at table angles, the
//! measured values), reproduces a constant and a linear table exactly, and needs no solve.
//!
//! **Where it is used.** The one-way compensation ([`super::one_way`]) takes the maximum of
//! `F(a) = f(ρ_s + R(a)·sin a) + R(a)·cos a` over the arc, which keeps the path gouge-free for
//! the measured edge; the tip, which the NC commands, is `R(0)` below the centre. The predicted
//! form ([`crate::analysis::predicted_form`]) and the concave-zone report ([`super::reach`]) cut
//! with the edge's depth below the centre at a horizontal offset d ([`Waviness::depth`]).
//!
//! **Checks** (field names relative to `tool`): 2 … [`MAX_WAVINESS_POINTS`] rows, angles finite
//! in [−90°, 90°] and strictly increasing, covering the arc ±β/2; deviations finite and at most
//! [`MAX_DEVIATION_FRACTION`] of the nose radius; and the edge a graph over the radial
//! coordinate (`R′·sin a + R·cos a > 0` across the arc, checked on 16 samples per table
//! interval), so that each horizontal offset has one edge point.

use crate::field::{FieldError, short};
use crate::job::WavinessSpec;

/// The most rows of a waviness table.
pub const MAX_WAVINESS_POINTS: usize = 10_000;
/// The largest |δ| as a fraction of the nose radius: a measured waviness is a fraction of a
/// micrometre, so a larger value is a unit or sign mistake.
pub const MAX_DEVIATION_FRACTION: f64 = 0.05;
/// Samples per table interval of the shape checks.
const CHECK_SAMPLES: usize = 16;

/// A nose edge measured as a deviation from its circle, interpolated (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Waviness {
    r: f64,
    /// Table angles, radians, increasing.
    angle: Vec<f64>,
    /// δ at each angle, mm.
    delta: Vec<f64>,
    /// dδ/da at each angle, mm per radian (the PCHIP slopes).
    slope: Vec<f64>,
}

impl Waviness {
    /// Checks the table of `spec` for a nose of radius `nose_radius_mm` whose arc reaches
    /// `half_angle` (radians) either side of the tool axis, and prepares the interpolant. Field
    /// names start with `waviness`.
    pub fn new(
        spec: &WavinessSpec,
        nose_radius_mm: f64,
        half_angle: f64,
    ) -> Result<Self, FieldError> {
        let r = nose_radius_mm;
        if r.is_nan() || r <= 0.0 {
            return Err(FieldError::new(
                "waviness",
                "set",
                "needs nose_radius_mm > 0: a sharp tool has no edge to measure",
            ));
        }
        let (a, d) = (&spec.angle_deg, &spec.deviation_um);
        if a.len() != d.len() || !(2..=MAX_WAVINESS_POINTS).contains(&a.len()) {
            return Err(FieldError::new(
                "waviness",
                format!("{} angles, {} deviations", a.len(), d.len()),
                format!("as many deviations as angles, 2 to {MAX_WAVINESS_POINTS} of each"),
            ));
        }
        for (k, &v) in a.iter().enumerate() {
            let increasing = k == 0 || v > a[k - 1];
            if !(v.is_finite() && (-90.0..=90.0).contains(&v) && increasing) {
                return Err(FieldError::new(
                    format!("waviness.angle_deg[{k}]"),
                    v,
                    "angles must be finite, within [-90, 90] and strictly increasing",
                ));
            }
        }
        let max_um = MAX_DEVIATION_FRACTION * r * 1e3;
        for (k, &v) in d.iter().enumerate() {
            if !(v.is_finite() && v.abs() <= max_um) {
                return Err(FieldError::new(
                    format!("waviness.deviation_um[{k}]"),
                    v,
                    format!(
                        "must be a finite deviation of at most {} µm (5 % of the nose radius; \
                         deviations are in µm)",
                        short(max_um)
                    ),
                ));
            }
        }
        let half_deg = half_angle.to_degrees();
        let (first, last) = (a[0], a[a.len() - 1]);
        if first > -half_deg + 1e-9 || last < half_deg - 1e-9 {
            return Err(FieldError::new(
                "waviness.angle_deg",
                format!("{} … {}°", short(first), short(last)),
                format!(
                    "must cover the nose arc ±{}° (included_angle_deg = {}): give the deviation \
                     over the whole arc, or reduce included_angle_deg to the measured span",
                    short(half_deg),
                    short(2.0 * half_deg)
                ),
            ));
        }
        let angle: Vec<f64> = a.iter().map(|v| v.to_radians()).collect();
        let delta: Vec<f64> = d.iter().map(|v| v * 1e-3).collect();
        let slope = pchip_slopes(&angle, &delta);
        let w = Self {
            r,
            angle,
            delta,
            slope,
        };
        if let Some(at) = w.first_sample(-half_angle, half_angle, |[rr, r1, _], a| {
            r1 * a.sin() + rr * a.cos() <= 0.0
        }) {
            return Err(FieldError::new(
                "waviness.deviation_um",
                format!("the table near a = {}°", short(at.to_degrees())),
                "must describe an edge that is a graph over the radius: r(a)·sin a must grow \
                 with a across the arc",
            ));
        }
        Ok(w)
    }

    /// The nominal nose radius r, mm.
    pub fn nominal_radius(&self) -> f64 {
        self.r
    }

    /// The table's angles, radians.
    pub fn angles(&self) -> &[f64] {
        &self.angle
    }

    /// `[R, dR/da, d²R/da²]` at nose angle `a` (radians): R = r + δ(a), mm. Outside the table
    /// (never inside the arc, which the table covers) δ keeps its end value.
    pub fn radius(&self, a: f64) -> [f64; 3] {
        let n = self.angle.len();
        if a <= self.angle[0] {
            return [self.r + self.delta[0], 0.0, 0.0];
        }
        if a >= self.angle[n - 1] {
            return [self.r + self.delta[n - 1], 0.0, 0.0];
        }
        let k = (self.angle.partition_point(|&v| v <= a) - 1).min(n - 2);
        let h = self.angle[k + 1] - self.angle[k];
        let t = (a - self.angle[k]) / h;
        let (y0, y1) = (self.delta[k], self.delta[k + 1]);
        let (m0, m1) = (self.slope[k], self.slope[k + 1]);
        let (t2, t3) = (t * t, t * t * t);
        let p = (2.0 * t3 - 3.0 * t2 + 1.0) * y0
            + (t3 - 2.0 * t2 + t) * h * m0
            + (-2.0 * t3 + 3.0 * t2) * y1
            + (t3 - t2) * h * m1;
        let secant = (y0 - y1) / h;
        let p1 = (6.0 * t2 - 6.0 * t) * secant
            + (3.0 * t2 - 4.0 * t + 1.0) * m0
            + (3.0 * t2 - 2.0 * t) * m1;
        let p2 = ((12.0 * t - 6.0) * secant + (6.0 * t - 4.0) * m0 + (6.0 * t - 2.0) * m1) / h;
        [self.r + p, p1, p2]
    }

    /// The nose angle whose edge point lies at the horizontal offset `d` from the centre:
    /// `R(a)·sin a = d`, by Newton's method from the circle's `asin(d/r)` (the edge is a graph
    /// over the offset, so the root is unique).
    pub fn angle_at_offset(&self, d: f64) -> f64 {
        let mut a = (d / self.r).clamp(-1.0, 1.0).asin();
        for _ in 0..20 {
            let [rr, r1, _] = self.radius(a);
            let (sa, ca) = a.sin_cos();
            let slope = r1 * sa + rr * ca;
            if slope.is_nan() || slope <= 0.0 {
                break;
            }
            let step = (rr * sa - d) / slope;
            a = (a - step).clamp(-std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2);
            if step.abs() < 1e-15 {
                break;
            }
        }
        a
    }

    /// The depth of the edge below the nose centre at the horizontal offset `d`, mm: `R(a)·cos a`
    /// at the angle of [`Waviness::angle_at_offset`] (the circle's `√(r² − d²)` when δ = 0).
    pub fn depth(&self, d: f64) -> f64 {
        let a = self.angle_at_offset(d);
        self.radius(a)[0] * a.cos()
    }

    /// The first nose angle in `[lo, hi]` (16 samples per table interval and the ends) where the
    /// edge is not convex: its curvature `R² + 2R′² − R·R″` (over a positive factor) is ≤ 0. The
    /// predicted form's envelope needs a convex edge.
    pub fn first_concave(&self, lo: f64, hi: f64) -> Option<f64> {
        self.first_sample(lo, hi, |[rr, r1, r2], _| {
            rr * rr + 2.0 * r1 * r1 - rr * r2 <= 0.0
        })
    }

    /// The first of the check samples in `[lo, hi]` where `bad(radius(a), a)` holds.
    fn first_sample(&self, lo: f64, hi: f64, bad: impl Fn([f64; 3], f64) -> bool) -> Option<f64> {
        let mut points: Vec<f64> = vec![lo, hi];
        for w in self.angle.windows(2) {
            for i in 0..CHECK_SAMPLES {
                points.push(w[0] + (w[1] - w[0]) * i as f64 / CHECK_SAMPLES as f64);
            }
        }
        points.retain(|a| *a >= lo && *a <= hi);
        points.sort_by(f64::total_cmp);
        points.into_iter().find(|&a| bad(self.radius(a), a))
    }
}

/// The PCHIP slopes of the data `(x, y)` (see the module docs): scipy's
/// `PchipInterpolator._find_derivatives`.
fn pchip_slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let secant: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
    if n == 2 {
        return vec![secant[0]; 2];
    }
    let mut m = vec![0.0; n];
    for k in 1..n - 1 {
        let (s0, s1) = (secant[k - 1], secant[k]);
        if s0 * s1 > 0.0 {
            let w1 = 2.0 * h[k] + h[k - 1];
            let w2 = h[k] + 2.0 * h[k - 1];
            m[k] = (w1 + w2) / (w1 / s0 + w2 / s1);
        }
    }
    m[0] = end_slope(h[0], h[1], secant[0], secant[1]);
    m[n - 1] = end_slope(h[n - 2], h[n - 3], secant[n - 2], secant[n - 3]);
    m
}

/// The slope at an end: the three-point formula, kept to the first secant's sign and, where the
/// secants differ in sign, to at most three times it (scipy's `_edge_case`).
fn end_slope(h0: f64, h1: f64, s0: f64, s1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * s0 - h0 * s1) / (h0 + h1);
    if d.signum() != s0.signum() || s0 == 0.0 {
        0.0
    } else if s0.signum() != s1.signum() && d.abs() > 3.0 * s0.abs() {
        3.0 * s0
    } else {
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(a: &[f64], d: &[f64]) -> WavinessSpec {
        WavinessSpec {
            angle_deg: a.to_vec(),
            deviation_um: d.to_vec(),
        }
    }

    #[test]
    fn constant_and_linear_tables_are_reproduced_exactly() {
        let half = 50f64.to_radians();
        let w = Waviness::new(&spec(&[-60.0, -10.0, 5.0, 60.0], &[0.2; 4]), 0.5, half).unwrap();
        for a in [-0.9, -0.3, 0.0, 0.1, 0.8] {
            assert_eq!(w.radius(a), [0.5002, 0.0, 0.0]);
            let d = 0.5002 * f64::sin(a);
            assert!((w.depth(d) - 0.5002 * f64::cos(a)).abs() < 1e-15);
        }
        // δ = 0.1 + 0.3·a (a in degrees): R′ = 3e-4 mm/deg.
        let a: [f64; 5] = [-55.0, -20.0, -3.0, 30.0, 55.0];
        let d: Vec<f64> = a.iter().map(|v| 0.1 + 0.003 * v).collect();
        let w = Waviness::new(&spec(&a, &d), 0.5, half).unwrap();
        for deg in [-50.0, -17.5, 0.0, 12.25, 49.0] {
            let [rr, r1, r2] = w.radius(f64::to_radians(deg));
            assert!(
                (rr - (0.5 + 1e-4 + 3e-6 * deg)).abs() < 1e-16,
                "{deg}: {rr}"
            );
            assert!(
                (r1 - 3e-6 * 180.0 / std::f64::consts::PI).abs() < 1e-15,
                "{deg}: {r1}"
            );
            assert!(r2.abs() < 1e-13, "{deg}: {r2}");
        }
    }

    #[test]
    fn the_interpolant_matches_its_table_and_its_derivatives_are_its_own() {
        let a = [-60.0, -35.0, -12.0, 0.0, 7.0, 31.0, 60.0];
        let d = [0.05, -0.12, 0.08, 0.2, 0.1, -0.03, 0.0];
        let w = Waviness::new(&spec(&a, &d), 0.8, 50f64.to_radians()).unwrap();
        for (av, dv) in a.iter().zip(d) {
            let rr = w.radius(av.to_radians())[0];
            assert!((rr - (0.8 + dv * 1e-3)).abs() < 1e-16);
        }
        // Finite differences of R and R′ inside the intervals.
        let h = 1e-6;
        for deg in [-47.0, -20.0, -5.0, 3.0, 20.0, 44.0] {
            let x: f64 = f64::to_radians(deg);
            let [_, r1, r2] = w.radius(x);
            let fd1 = (w.radius(x + h)[0] - w.radius(x - h)[0]) / (2.0 * h);
            let fd2 = (w.radius(x + h)[1] - w.radius(x - h)[1]) / (2.0 * h);
            assert!((r1 - fd1).abs() < 1e-9, "{deg}: {r1} {fd1}");
            assert!((r2 - fd2).abs() < 1e-7, "{deg}: {r2} {fd2}");
        }
        // No overshoot: between two table values δ stays between them (monotone pieces).
        for k in 0..a.len() - 1 {
            let (lo, hi) = (d[k].min(d[k + 1]), d[k].max(d[k + 1]));
            for i in 0..=50 {
                let x = a[k] + (a[k + 1] - a[k]) * i as f64 / 50.0;
                let v = (w.radius(x.to_radians())[0] - 0.8) * 1e3;
                assert!(v >= lo - 1e-12 && v <= hi + 1e-12, "{x}: {v}");
            }
        }
    }

    #[test]
    fn bad_tables_name_their_field() {
        let half = 50f64.to_radians();
        let cases = [
            (
                spec(&[-60.0, 60.0], &[0.0]),
                "waviness",
                "as many deviations",
            ),
            (
                spec(&[-60.0, -60.0, 60.0], &[0.0; 3]),
                "waviness.angle_deg[1]",
                "strictly",
            ),
            (
                spec(&[-60.0, f64::NAN], &[0.0; 2]),
                "waviness.angle_deg[1]",
                "finite",
            ),
            (
                spec(&[-60.0, 60.0], &[0.0, 30.0]),
                "waviness.deviation_um[1]",
                "at most 25 µm",
            ),
            (
                spec(&[-40.0, 60.0], &[0.0; 2]),
                "waviness.angle_deg",
                "must cover the nose arc ±50°",
            ),
        ];
        for (s, field, allowed) in cases {
            let e = Waviness::new(&s, 0.5, half).unwrap_err();
            assert_eq!(e.field, field, "{e}");
            assert!(e.allowed.contains(allowed), "{e}");
        }
        let e = Waviness::new(&spec(&[-60.0, 60.0], &[0.0; 2]), 0.0, half).unwrap_err();
        assert_eq!(e.field, "waviness");
        assert_eq!(
            Waviness::new(&spec(&[-60.0, 60.0], &[0.0; 2]), 0.5, half)
                .unwrap()
                .first_concave(-half, half),
            None
        );
    }
}
