//! Second-order forward differentiation in two variables: a value with its gradient and
//! Hessian in (x, y), carried through sums, products, quotients, square roots and functions of
//! one variable by the chain rule (the "jets" of automatic differentiation; Griewank & Walther,
//! *Evaluating Derivatives*, 2008, ch. 13). Used where a closed form of the second derivatives
//! would be long: Shepard's weights of the scattered-data interpolation
//! ([`super::scattered::interpolate::shepard`]), and the progressive surface ([`super::pal`]),
//! whose derivatives (paper 003, eqs 13–15 through the contour function u(x, y)) are exact
//! compositions of hand-written elementary derivatives, not differences.
//!
//! For g(v) with g′ and g″: `∂g/∂x = g′·v_x`, `∂²g/∂x∂y = g″·v_x·v_y + g′·v_xy`; for a product
//! `(ab)_xy = a_xy·b + a_x·b_y + a_y·b_x + a·b_xy`. The reciprocal is g(v) = 1/v
//! (g′ = −1/v², g″ = 2/v³) and a quotient `a·(1/b)`.

use super::Local;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// f, ∂f/∂x, ∂f/∂y, ∂²f/∂x², ∂²f/∂x∂y, ∂²f/∂y² at one point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Jet {
    /// f.
    pub v: f64,
    /// ∂f/∂x.
    pub x: f64,
    /// ∂f/∂y.
    pub y: f64,
    /// ∂²f/∂x².
    pub xx: f64,
    /// ∂²f/∂x∂y.
    pub xy: f64,
    /// ∂²f/∂y².
    pub yy: f64,
}

impl Jet {
    /// A constant.
    pub fn constant(v: f64) -> Self {
        Self {
            v,
            ..Self::default()
        }
    }

    /// The coordinate x at `x`.
    pub fn var_x(x: f64) -> Self {
        Self {
            v: x,
            x: 1.0,
            ..Self::default()
        }
    }

    /// The coordinate y at `y`.
    pub fn var_y(y: f64) -> Self {
        Self {
            v: y,
            y: 1.0,
            ..Self::default()
        }
    }

    /// `(x − px)² + (y − py)²` at the point with offsets `(dx, dy) = (x − px, y − py)`.
    pub fn squared_distance(dx: f64, dy: f64) -> Self {
        Self {
            v: dx * dx + dy * dy,
            x: 2.0 * dx,
            y: 2.0 * dy,
            xx: 2.0,
            xy: 0.0,
            yy: 2.0,
        }
    }

    /// `g(self)` for a function g of one variable with `g = f0`, `g′ = f1`, `g″ = f2` at
    /// `self.v`.
    pub fn compose(self, f0: f64, f1: f64, f2: f64) -> Self {
        Self {
            v: f0,
            x: f1 * self.x,
            y: f1 * self.y,
            xx: f2 * self.x * self.x + f1 * self.xx,
            xy: f2 * self.x * self.y + f1 * self.xy,
            yy: f2 * self.y * self.y + f1 * self.yy,
        }
    }

    /// √self; the caller ensures `self.v > 0`.
    pub fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        self.compose(r, 0.5 / r, -0.25 / (r * self.v))
    }

    /// 1/self; the caller ensures `self.v ≠ 0`.
    pub fn recip(self) -> Self {
        let r = 1.0 / self.v;
        self.compose(r, -r * r, 2.0 * r * r * r)
    }

    /// self · o by the product rule.
    pub fn product(self, o: Jet) -> Self {
        Jet {
            v: self.v * o.v,
            x: self.x * o.v + self.v * o.x,
            y: self.y * o.v + self.v * o.y,
            xx: self.xx * o.v + 2.0 * self.x * o.x + self.v * o.xx,
            xy: self.xy * o.v + self.x * o.y + self.y * o.x + self.v * o.xy,
            yy: self.yy * o.v + 2.0 * self.y * o.y + self.v * o.yy,
        }
    }

    /// self · k for a constant k.
    pub fn scale(self, k: f64) -> Self {
        Self {
            v: self.v * k,
            x: self.x * k,
            y: self.y * k,
            xx: self.xx * k,
            xy: self.xy * k,
            yy: self.yy * k,
        }
    }
}

/// A surface's derivative record is the jet of its sag.
impl From<Local> for Jet {
    fn from(l: Local) -> Jet {
        Jet {
            v: l.z,
            x: l.zx,
            y: l.zy,
            xx: l.zxx,
            xy: l.zxy,
            yy: l.zyy,
        }
    }
}

/// The jet of a sag as the surface's derivative record.
impl From<Jet> for Local {
    fn from(j: Jet) -> Local {
        Local {
            z: j.v,
            zx: j.x,
            zy: j.y,
            zxx: j.xx,
            zxy: j.xy,
            zyy: j.yy,
        }
    }
}

impl Add for Jet {
    type Output = Jet;
    fn add(self, o: Jet) -> Jet {
        Jet {
            v: self.v + o.v,
            x: self.x + o.x,
            y: self.y + o.y,
            xx: self.xx + o.xx,
            xy: self.xy + o.xy,
            yy: self.yy + o.yy,
        }
    }
}

impl Neg for Jet {
    type Output = Jet;
    fn neg(self) -> Jet {
        self.scale(-1.0)
    }
}

impl Sub for Jet {
    type Output = Jet;
    fn sub(self, o: Jet) -> Jet {
        self + (-o)
    }
}

impl Mul for Jet {
    type Output = Jet;
    fn mul(self, o: Jet) -> Jet {
        self.product(o)
    }
}

impl Div for Jet {
    type Output = Jet;
    /// `self · (1/o)`; the caller ensures `o.v ≠ 0`.
    fn div(self, o: Jet) -> Jet {
        self.product(o.recip())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The jet of a test function of (x, y) built from the operations under test.
    fn via_jets(x: f64, y: f64) -> Jet {
        let (x, y) = (Jet::var_x(x), Jet::var_y(y));
        let q = x * x + y * y.scale(3.0) + Jet::constant(2.0);
        (q.sqrt() - x * y) / (Jet::constant(1.5) + x.compose(x.v.sin(), x.v.cos(), -x.v.sin()))
    }

    /// The same function written out: f = (√(x² + 3y² + 2) − xy) / (1.5 + sin x).
    fn direct(x: f64, y: f64) -> f64 {
        ((x * x + 3.0 * y * y + 2.0).sqrt() - x * y) / (1.5 + x.sin())
    }

    #[test]
    fn jets_match_central_differences_of_a_closed_form() {
        // Step 1e-4: truncation h²/6·|f‴| ~ 1e-8·10 and rounding ε·|f|/h² ~ 1e-8 for the second
        // differences; 1e-6 is well above both and far below any wrong term.
        let h = 1e-4;
        for &(x, y) in &[(0.3, -0.7), (1.2, 0.4), (-0.9, 1.1)] {
            let j = via_jets(x, y);
            let f = direct;
            assert!((j.v - f(x, y)).abs() < 1e-14);
            let fx = (f(x + h, y) - f(x - h, y)) / (2.0 * h);
            let fy = (f(x, y + h) - f(x, y - h)) / (2.0 * h);
            let fxx = (f(x + h, y) - 2.0 * f(x, y) + f(x - h, y)) / (h * h);
            let fyy = (f(x, y + h) - 2.0 * f(x, y) + f(x, y - h)) / (h * h);
            let fxy = (f(x + h, y + h) - f(x + h, y - h) - f(x - h, y + h) + f(x - h, y - h))
                / (4.0 * h * h);
            for (a, b) in [(j.x, fx), (j.y, fy), (j.xx, fxx), (j.xy, fxy), (j.yy, fyy)] {
                assert!(
                    (a - b).abs() < 1e-6,
                    "({x}, {y}): jet {a} vs difference {b}"
                );
            }
        }
    }

    /// The jet of f(x, y) = x²y + 3 at (x, y), written out by hand.
    fn poly(x: f64, y: f64) -> Jet {
        Jet {
            v: x * x * y + 3.0,
            x: 2.0 * x * y,
            y: x * x,
            xx: 2.0 * y,
            xy: 2.0 * x,
            yy: 0.0,
        }
    }

    #[test]
    fn quotient_by_a_squared_distance_matches_finite_differences() {
        // h = (x²y + 3) / ((x − 1)² + (y + 2)²) at (0.4, −0.7).
        let h = |x: f64, y: f64| poly(x, y) / Jet::squared_distance(x - 1.0, y + 2.0);
        let (x, y, e) = (0.4, -0.7, 1e-5);
        let j = h(x, y);
        assert!((j.v - (x * x * y + 3.0) / ((x - 1.0).powi(2) + (y + 2.0).powi(2))).abs() < 1e-15);
        let fx = (h(x + e, y).v - h(x - e, y).v) / (2.0 * e);
        let fy = (h(x, y + e).v - h(x, y - e).v) / (2.0 * e);
        let fxx = (h(x + e, y).x - h(x - e, y).x) / (2.0 * e);
        let fxy = (h(x, y + e).x - h(x, y - e).x) / (2.0 * e);
        let fyy = (h(x, y + e).y - h(x, y - e).y) / (2.0 * e);
        // Central differences: error e²·|f‴|/6, |f‴| ≲ 10 here.
        for (a, b) in [(j.x, fx), (j.y, fy), (j.xx, fxx), (j.xy, fxy), (j.yy, fyy)] {
            assert!((a - b).abs() < 1e-8, "{a} {b}");
        }
        let s = (poly(x, y) + Jet::constant(1.0)).scale(2.0);
        assert_eq!(s.v, 2.0 * (x * x * y + 4.0));
        let l = Local::from(s);
        assert_eq!(l.zxy, 4.0 * x);
        assert_eq!(Jet::from(l), s);
    }
}
