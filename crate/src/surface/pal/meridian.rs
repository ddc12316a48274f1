//! The meridian of a progressive surface (paper 003, section 2.2, eqs 14–15): the plane curve
//! through O along x whose curvature is `κ(u) = 1/r(u) = D(u) / (1000·(n − 1))` (front-surface
//! power, eq 1 with r in mm), its slope angle θ with
//!
//! `sin θ(u) = ∫₀ᵘ κ du` (eq 14, exact: the antiderivative of the piecewise polynomial D),
//!
//! and its height `T(u) = ∫₀ᵘ tan θ du` (the integral of eq 14's ζ, which has no closed form).
//! T is computed by Gauss–Legendre quadrature: in the far and near zones κ is constant and
//! `∫ tan θ du = Δu·(sin θ + sin θ₀)/(cos θ₀ + cos θ)` exactly (the stable form of
//! `(cos θ₀ − cos θ)/κ`); over the corridor the integral is tabulated once at panel ends ≤ 0.5 mm
//! apart, and a point inside a panel adds an 8-point rule from the panel's start. The integrand
//! is analytic on each panel (the panel ends include F and N, where D is only C²), so the rule's
//! error is far below 1e-13 mm (tests: against composite Simpson with Richardson extrapolation).
//!
//! Where |sin θ| reaches 1 the meridian turns vertical and has no height: T is then NaN, which
//! the surface reports as undefined.

use super::gauss_legendre::GaussLegendre;
use super::power_law::PowerLaw;

/// Gauss–Legendre points per panel.
const RULE_POINTS: usize = 8;
/// Largest corridor panel, mm.
const MAX_PANEL_MM: f64 = 0.5;

/// The meridian quantities at one u.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeridianPoint {
    /// κ, dκ/du, d²κ/du² (1/mm, 1/mm², 1/mm³); positive κ: the paper's r > 0, convex front.
    pub curvature: [f64; 3],
    /// sin θ.
    pub sin: f64,
    /// cos θ > 0.
    pub cos: f64,
    /// T(u) = ∫₀ᵘ tan θ du, mm, in the paper's frame (Z towards the eye).
    pub height: f64,
}

/// A meridian built from a power law.
#[derive(Debug, Clone, PartialEq)]
pub struct Meridian {
    law: PowerLaw,
    /// 1/(1000(n − 1)): curvature per dioptre, 1/mm.
    per_dioptre: f64,
    /// ∫ D from F to O, D·mm.
    integral_at_origin: f64,
    rule: GaussLegendre,
    panel: f64,
    /// ∫ tan θ from F to each corridor panel end.
    table: Vec<f64>,
    /// ∫ tan θ from F to O.
    height_at_origin: f64,
}

impl Meridian {
    /// The meridian of `law` for refractive index n > 1.
    pub fn new(law: PowerLaw, refractive_index: f64) -> Self {
        let panels = (law.corridor() / MAX_PANEL_MM).ceil().max(1.0) as usize;
        let mut meridian = Self {
            per_dioptre: 1.0 / (1000.0 * (refractive_index - 1.0)),
            integral_at_origin: law.integral_from_far(0.0),
            rule: GaussLegendre::new(RULE_POINTS),
            panel: law.corridor() / panels as f64,
            table: Vec::with_capacity(panels + 1),
            height_at_origin: 0.0,
            law,
        };
        let mut sum = 0.0;
        meridian.table.push(sum);
        for j in 0..panels {
            let a = meridian.law.far_x() + j as f64 * meridian.panel;
            sum += meridian
                .rule
                .integrate(a, a + meridian.panel, |u| meridian.tan(u));
            meridian.table.push(sum);
        }
        meridian.height_at_origin = meridian.height_from_far(0.0);
        meridian
    }

    /// The power law.
    pub fn law(&self) -> &PowerLaw {
        &self.law
    }

    /// sin θ(u).
    pub fn sin(&self, u: f64) -> f64 {
        self.per_dioptre * (self.law.integral_from_far(u) - self.integral_at_origin)
    }

    /// tan θ(u); NaN where |sin θ| ≥ 1.
    fn tan(&self, u: f64) -> f64 {
        let s = self.sin(u);
        s / (1.0 - s * s).sqrt()
    }

    /// ∫ tan θ du from F to u; NaN if the meridian turns vertical on the way.
    fn height_from_far(&self, u: f64) -> f64 {
        let (far, near) = (self.law.far_x(), self.law.near_x());
        if u <= far {
            return constant_curvature_height(u - far, self.sin(far), self.sin(u));
        }
        if u >= near {
            let last = self.table[self.table.len() - 1];
            return last + constant_curvature_height(u - near, self.sin(near), self.sin(u));
        }
        let j = (((u - far) / self.panel) as usize).min(self.table.len() - 2);
        let start = far + j as f64 * self.panel;
        self.table[j] + self.rule.integrate(start, u, |v| self.tan(v))
    }

    /// The meridian at u, or why it has none there.
    pub fn at(&self, u: f64) -> Result<MeridianPoint, String> {
        let s = self.sin(u);
        let height = self.height_from_far(u) - self.height_at_origin;
        if !(s.abs() < 1.0 && height.is_finite()) {
            return Err(format!(
                "the meridian turns vertical (|sin θ| ≥ 1) between u = 0 and u = {u} mm"
            ));
        }
        let [d, d1, d2] = self.law.power(u);
        let k = self.per_dioptre;
        Ok(MeridianPoint {
            curvature: [k * d, k * d1, k * d2],
            sin: s,
            cos: (1.0 - s * s).sqrt(),
            height,
        })
    }
}

/// ∫ tan θ over Δu where κ is constant, from sin θ₀ to sin θ = sin θ₀ + κΔu:
/// `(cos θ₀ − cos θ)/κ = Δu·(sin θ + sin θ₀)/(cos θ₀ + cos θ)` (no division by κ, exact at κ = 0).
fn constant_curvature_height(du: f64, s0: f64, s: f64) -> f64 {
    let (c0, c) = ((1.0 - s0 * s0).sqrt(), (1.0 - s * s).sqrt());
    du * (s + s0) / (c0 + c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn meridian(far: f64, add: f64, h: f64, big_l: f64, m: usize, l: usize, n: f64) -> Meridian {
        Meridian::new(PowerLaw::new(far, add, h, big_l, m, l).unwrap(), n)
    }

    /// ∫₀ᵘ tan θ by composite Simpson on `steps` intervals, with one Richardson step against
    /// half as many (error O(Δ⁶) where the integrand is smooth, O(Δ⁴)·jump at F and N where D″
    /// has a corner): an independent reference built only on `sin`.
    fn simpson_reference(mer: &Meridian, u: f64, steps: usize) -> f64 {
        let simpson = |n: usize| {
            let dx = u / n as f64;
            let f = |i: usize| mer.tan(i as f64 * dx);
            let mut sum = f(0) + f(n);
            for i in 1..n {
                sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i);
            }
            sum * dx / 3.0
        };
        let (fine, coarse) = (simpson(steps), simpson(steps / 2));
        fine + (fine - coarse) / 15.0
    }

    #[test]
    fn sin_theta_integrates_the_curvature() {
        // d(sin θ)/du = κ(u) by central differences (step 1e-4 mm: error ≲ 1e-13).
        let mer = meridian(4.0, 2.5, 18.0, 5.0, 3, 4, 1.6);
        assert_eq!(mer.sin(0.0), 0.0);
        for u in [-30.0, -5.0, -1.0, 3.0, 12.9, 30.0] {
            let h = 1e-4;
            let fd = (mer.sin(u + h) - mer.sin(u - h)) / (2.0 * h);
            let k = mer.at(u).unwrap().curvature[0];
            assert!((fd - k).abs() < 1e-12, "{u}: {fd} vs {k}");
        }
    }

    #[test]
    fn height_matches_a_much_finer_independent_quadrature() {
        // A mild design (the paper's) and a steep one (|sin θ| up to 0.9 on ±30 mm). Simpson with
        // 2¹⁶ steps plus Richardson is accurate to ~1e-14 mm here; the tabulated Gauss rule must
        // agree to 1e-12 mm (the target accuracy of T).
        let cases = [
            (meridian(1.0, 2.0, 30.0, 10.0, 3, 3, 1.498), 35.0),
            (meridian(12.0, 6.0, 14.0, 4.0, 4, 5, 1.5), 21.0),
        ];
        for (mer, reach) in cases {
            for frac in [-1.0, -0.71, -0.3, 0.05, 0.42, 0.77, 1.0] {
                let u = frac * reach;
                let got = mer.at(u).unwrap().height;
                let want = simpson_reference(&mer, u, 1 << 16);
                assert!((got - want).abs() < 1e-12, "u {u}: {got} vs {want}");
            }
            let s = mer.sin(-reach).abs().max(mer.sin(reach).abs());
            assert!(s < 1.0, "{s}");
        }
    }

    #[test]
    fn the_evolute_moves_along_the_normal_as_the_paper_says() {
        // Eq 14: ε = u − r·sin θ, ζ = r·cos θ + T; differentiating with (sin θ)′ = 1/r gives
        // dε/du = −r′·sin θ and dζ/du = r′·cos θ, which holds only if T′ = tan θ: a check of the
        // tabulated height against sin θ. Central differences with step 1e-3 mm on ε, ζ of
        // size ≲ 400 mm: rounding 1e-13/1e-3 and truncation h²/6·|ζ‴| ≲ 1e-8, against
        // derivatives up to 40.
        let mer = meridian(1.0, 2.0, 30.0, 10.0, 3, 3, 1.498);
        let evolute = |u: f64| {
            let p = mer.at(u).unwrap();
            let r = 1.0 / p.curvature[0];
            (u - r * p.sin, r * p.cos + p.height)
        };
        for u in [-6.0, -3.5, 0.7, 6.0, 13.2, 16.0] {
            let h = 1e-3;
            let (ep, zp) = evolute(u + h);
            let (em, zm) = evolute(u - h);
            let p = mer.at(u).unwrap();
            let dr = -p.curvature[1] / (p.curvature[0] * p.curvature[0]);
            let (de, dz) = ((ep - em) / (2.0 * h), (zp - zm) / (2.0 * h));
            assert!(
                (de + dr * p.sin).abs() < 1e-6,
                "u {u}: dε/du {de} vs {}",
                -dr * p.sin
            );
            assert!(
                (dz - dr * p.cos).abs() < 1e-6,
                "u {u}: dζ/du {dz} vs {}",
                dr * p.cos
            );
            assert!(dr.abs() > 1.0, "u {u}: r′ {dr} too small to test anything");
        }
    }

    #[test]
    fn constant_power_gives_the_circle() {
        // Addition 0: κ constant, the meridian is the circle T = (1 − cos θ)/κ, sin θ = κu.
        let mer = meridian(5.0, 0.0, 20.0, 8.0, 3, 3, 1.5);
        let k = 5.0 / 500.0;
        for u in [-45.0, -8.0, -2.2, 0.0, 7.0, 12.0, 13.0, 60.0] {
            let p = mer.at(u).unwrap();
            let s = k * u;
            let c = (1.0 - s * s).sqrt();
            assert!((p.sin - s).abs() < 1e-15);
            let exact = s * s / (k * (1.0 + c));
            assert!(
                (p.height - exact).abs() < 1e-13,
                "{u}: {} vs {exact}",
                p.height
            );
        }
    }

    #[test]
    fn a_vertical_meridian_is_reported() {
        // 50 D with n = 1.5: r = 10 mm, so sin θ = u/10 reaches 1 at u = 10 mm.
        let mer = meridian(50.0, 0.0, 10.0, 5.0, 3, 3, 1.5);
        assert!(mer.at(9.9).is_ok());
        let e = mer.at(10.5).unwrap_err();
        assert!(e.contains("vertical"), "{e}");
        assert!(mer.at(-10.5).is_err());
    }
}
