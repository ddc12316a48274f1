//! A tensor-product NURBS patch `S(u, v) = Σᵢⱼ Nᵢ,p(u)·Nⱼ,q(v)·wᵢⱼ·Pᵢⱼ / Σᵢⱼ Nᵢ,p(u)·Nⱼ,q(v)·wᵢⱼ`
//! and its partial derivatives up to second order: Piegl & Tiller, "The NURBS Book", A3.6
//! (derivatives of the homogeneous B-spline surface `Aʷ = (wx, wy, wz, w)`) and A4.4 / eq 4.20
//! (the rational derivatives from the homogeneous ones):
//!
//! ```text
//! S     = A / w
//! S_u   = (A_u  − w_u·S) / w                 S_v  = (A_v − w_v·S) / w
//! S_uu  = (A_uu − 2·w_u·S_u − w_uu·S) / w    S_vv = (A_vv − 2·w_v·S_v − w_vv·S) / w
//! S_uv  = (A_uv − w_u·S_v − w_v·S_u − w_uv·S) / w
//! ```
//!
//! with A the first three homogeneous coordinates. These are exact (no differencing).

use super::basis::{KnotVector, WIDTH};

/// A point of the patch and its partial derivatives, mm per unit parameter.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Derivs {
    /// S(u, v).
    pub s: [f64; 3],
    /// ∂S/∂u.
    pub su: [f64; 3],
    /// ∂S/∂v.
    pub sv: [f64; 3],
    /// ∂²S/∂u².
    pub suu: [f64; 3],
    /// ∂²S/∂u∂v.
    pub suv: [f64; 3],
    /// ∂²S/∂v².
    pub svv: [f64; 3],
}

/// A validated tensor-product NURBS patch in homogeneous form.
#[derive(Debug, Clone, PartialEq)]
pub struct Patch {
    u: KnotVector,
    v: KnotVector,
    /// `(w·x, w·y, w·z, w)` of control point (i, j) at `i·cols + j`.
    pw: Vec<[f64; 4]>,
    rational: bool,
}

/// Homogeneous derivatives `A^(k,l)` for k + l ≤ 2, indexed `[k][l]`.
type Homogeneous = [[[f64; 4]; 3]; 3];

impl Patch {
    /// The patch from its knot vectors, control points `points[i·cols + j]` (i along u) and
    /// weights in the same order; the caller has checked shapes and values.
    pub fn new(u: KnotVector, v: KnotVector, points: &[[f64; 3]], weights: &[f64]) -> Self {
        let pw = points
            .iter()
            .zip(weights)
            .map(|(p, &w)| [w * p[0], w * p[1], w * p[2], w])
            .collect();
        let rational = weights.iter().any(|&w| w != 1.0);
        Self { u, v, pw, rational }
    }

    /// The knot vector along u.
    pub fn knots_u(&self) -> &KnotVector {
        &self.u
    }

    /// The knot vector along v.
    pub fn knots_v(&self) -> &KnotVector {
        &self.v
    }

    /// The homogeneous control points `(w·x, w·y, w·z, w)`, point (i, j) at `i·cols + j`.
    pub fn homogeneous_net(&self) -> &[[f64; 4]] {
        &self.pw
    }

    /// Whether any weight differs from 1.
    pub fn rational(&self) -> bool {
        self.rational
    }

    /// `[u_min, u_max, v_min, v_max]`.
    pub fn domain(&self) -> [f64; 4] {
        let (a, b) = self.u.domain();
        let (c, d) = self.v.domain();
        [a, b, c, d]
    }

    /// S and its derivatives up to `order` (0, 1 or 2; higher ones are left zero) at (u, v),
    /// clamped to the domain.
    pub fn eval(&self, u: f64, v: f64, order: usize) -> Derivs {
        let [a, b, c, d] = self.domain();
        let (u, v) = (u.clamp(a, b), v.clamp(c, d));
        let aw = self.homogeneous(u, v, order);
        rational(&aw, order)
    }

    /// A3.6 on the homogeneous net: `A^(k,l) = Σ_r N^(k)_r(u) Σ_s N^(l)_s(v) Pʷ`.
    fn homogeneous(&self, u: f64, v: f64, order: usize) -> Homogeneous {
        let (p, q) = (self.u.degree(), self.v.degree());
        let cols = self.v.count();
        let (su, sv) = (self.u.span(u), self.v.span(v));
        let nu = self.u.ders(su, u, order);
        let nv = self.v.ders(sv, v, order);
        let mut out = [[[0.0; 4]; 3]; 3];
        for r in 0..=p {
            let row = (su - p + r) * cols + (sv - q);
            // temp[l] = Σ_s N^(l)_s(v) Pʷ_{row, s}
            let mut temp = [[0.0; 4]; 3];
            for (s, pw) in self.pw[row..=row + q].iter().enumerate() {
                for (l, t) in temp.iter_mut().enumerate().take(order + 1) {
                    let n = nv[l][s];
                    for c in 0..4 {
                        t[c] += n * pw[c];
                    }
                }
            }
            accumulate(&mut out, &nu, r, &temp, order);
        }
        out
    }
}

/// Adds `N^(k)_r(u)·temp[l]` to `out[k][l]` for k + l ≤ order.
fn accumulate(
    out: &mut Homogeneous,
    nu: &[[f64; WIDTH]; 3],
    r: usize,
    temp: &[[f64; 4]; 3],
    order: usize,
) {
    for k in 0..=order {
        let n = nu[k][r];
        for l in 0..=(order - k) {
            for c in 0..4 {
                out[k][l][c] += n * temp[l][c];
            }
        }
    }
}

/// A4.4 for second order: the Cartesian derivatives from the homogeneous ones.
fn rational(aw: &Homogeneous, order: usize) -> Derivs {
    let w = aw[0][0][3];
    let a = |k: usize, l: usize| [aw[k][l][0], aw[k][l][1], aw[k][l][2]];
    let wd = |k: usize, l: usize| aw[k][l][3];
    let combine = |base: [f64; 3], terms: &[(f64, [f64; 3])]| {
        let mut out = base;
        for (f, t) in terms {
            for c in 0..3 {
                out[c] -= f * t[c];
            }
        }
        out.map(|x| x / w)
    };
    let s = a(0, 0).map(|x| x / w);
    let mut d = Derivs {
        s,
        ..Derivs::default()
    };
    if order >= 1 {
        d.su = combine(a(1, 0), &[(wd(1, 0), s)]);
        d.sv = combine(a(0, 1), &[(wd(0, 1), s)]);
    }
    if order >= 2 {
        d.suu = combine(a(2, 0), &[(2.0 * wd(1, 0), d.su), (wd(2, 0), s)]);
        d.svv = combine(a(0, 2), &[(2.0 * wd(0, 1), d.sv), (wd(0, 2), s)]);
        d.suv = combine(
            a(1, 1),
            &[(wd(1, 0), d.sv), (wd(0, 1), d.su), (wd(1, 1), s)],
        );
    }
    d
}

/// A rational patch on the knot vectors `u` and `v` for tests: control point (i, j) at
/// `(i + 0.1j, j − 0.2i, 0.3ij − 0.1i²)`, weight `1 + 0.3·((i·cols + j) mod 4)`.
#[cfg(test)]
pub(super) fn sample_patch(u: KnotVector, v: KnotVector) -> Patch {
    let (rows, cols) = (u.count(), v.count());
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..rows {
        for j in 0..cols {
            let (x, y) = (i as f64, j as f64);
            points.push([x + 0.1 * y, y - 0.2 * x, 0.3 * x * y - 0.1 * x * x]);
            weights.push(1.0 + 0.3 * ((i * cols + j) % 4) as f64);
        }
    }
    Patch::new(u, v, &points, &weights)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A biquadratic rational patch with uneven weights and interior knots.
    fn patch() -> Patch {
        let u = KnotVector::new("u", 2, 4, &[0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0]).unwrap();
        let v = KnotVector::new("v", 2, 3, &[0.0, 0.0, 0.0, 2.0, 2.0, 2.0]).unwrap();
        sample_patch(u, v)
    }

    /// The rational surface evaluated the slow way: every basis function by the Cox–de Boor
    /// recursion (eq 2.5), then Σ N N w P / Σ N N w.
    fn direct(u: f64, v: f64) -> [f64; 3] {
        fn cox(knots: &[f64], i: usize, p: usize, t: f64) -> f64 {
            if p == 0 {
                return if knots[i] <= t && t < knots[i + 1] {
                    1.0
                } else {
                    0.0
                };
            }
            let mut out = 0.0;
            let d1 = knots[i + p] - knots[i];
            if d1 > 0.0 {
                out += (t - knots[i]) / d1 * cox(knots, i, p - 1, t);
            }
            let d2 = knots[i + p + 1] - knots[i + 1];
            if d2 > 0.0 {
                out += (knots[i + p + 1] - t) / d2 * cox(knots, i + 1, p - 1, t);
            }
            out
        }
        let ku = [0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0];
        let kv = [0.0, 0.0, 0.0, 2.0, 2.0, 2.0];
        let (mut num, mut den) = ([0.0; 3], 0.0);
        for i in 0..4 {
            for j in 0..3 {
                let (x, y) = (i as f64, j as f64);
                let p = [x + 0.1 * y, y - 0.2 * x, 0.3 * x * y - 0.1 * x * x];
                let w = 1.0 + 0.3 * ((i * 3 + j) % 4) as f64;
                let n = cox(&ku, i, 2, u) * cox(&kv, j, 2, v) * w;
                for c in 0..3 {
                    num[c] += n * p[c];
                }
                den += n;
            }
        }
        num.map(|x| x / den)
    }

    #[test]
    fn points_match_the_cox_de_boor_recursion() {
        let p = patch();
        for &(u, v) in &[
            (0.0, 0.0),
            (0.2, 0.7),
            (0.4, 1.0),
            (0.77, 1.9),
            (0.99, 0.01),
        ] {
            let s = p.eval(u, v, 0).s;
            let d = direct(u, v);
            for c in 0..3 {
                assert!((s[c] - d[c]).abs() < 1e-14, "({u}, {v}) {c}: {s:?} {d:?}");
            }
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        // Step 1e-5 in a parameter of range ~1: truncation h²/6·|S‴| ≲ 1e-9 and rounding
        // ε·|S|/h ≲ 1e-10 for this patch; 1e-7 leaves a margin and still catches any wrong term.
        let p = patch();
        let h = 1e-5;
        for &(u, v) in &[(0.1, 0.3), (0.25, 1.2), (0.6, 0.5), (0.9, 1.7)] {
            let d = p.eval(u, v, 2);
            let du = |f: fn(&Derivs) -> [f64; 3]| {
                let a = f(&p.eval(u + h, v, 2));
                let b = f(&p.eval(u - h, v, 2));
                [0, 1, 2].map(|c| (a[c] - b[c]) / (2.0 * h))
            };
            let dv = |f: fn(&Derivs) -> [f64; 3]| {
                let a = f(&p.eval(u, v + h, 2));
                let b = f(&p.eval(u, v - h, 2));
                [0, 1, 2].map(|c| (a[c] - b[c]) / (2.0 * h))
            };
            let pairs = [
                (d.su, du(|d| d.s)),
                (d.sv, dv(|d| d.s)),
                (d.suu, du(|d| d.su)),
                (d.suv, dv(|d| d.su)),
                (d.suv, du(|d| d.sv)),
                (d.svv, dv(|d| d.sv)),
            ];
            for (k, (a, f)) in pairs.iter().enumerate() {
                for c in 0..3 {
                    assert!(
                        (a[c] - f[c]).abs() < 1e-7,
                        "({u}, {v}) pair {k} {c}: {a:?} {f:?}"
                    );
                }
            }
        }
    }
}
