//! The contour curves of a progressive surface (paper 003, section 2.2): the level curves of the
//! auxiliary function u(x, y), each crossing the meridian (y = 0) at right angles at x = u and
//! carrying the circle of curvature of the meridian at u. Paper 003 names straight lines,
//! circles, hyperbolas and ellipses but gives no equations, and its reference \[22\] (Tang et al.,
//! Opt. Express 25, 28100, 2017) obtains u numerically; the families here are explicit:
//!
//! - straight lines: `u = x`;
//! - circles centred on the meridian's extension at (X, 0): `(x − X)² + y² = (u − X)²`;
//! - hyperbolas sharing the centre (X, 0) and the asymptotes `y = ±a·(x − X)`:
//!   `(x − X)² − y²/a² = (u − X)²`.
//!
//! Both conics are `(x − X)² + k·y² = (u − X)²` (k = 1, k = −1/a²), so
//! `u = X − σ·√((x − X)² + k·y²)` with σ = sign(X − x) on the part, and with
//! `d = √((x − X)² + k·y²)`: `d_x = (x − X)/d`, `d_y = k·y/d`, `d_xx = (1 − d_x²)/d`,
//! `d_xy = −d_x·d_y/d`, `d_yy = (k − d_y²)/d`. On the meridian u = x and `u_y = k·y·(…) = 0`:
//! every contour meets it at right angles. A circle bends towards its centre (its vertex
//! curvature is 1/|u − X|), a hyperbola away from it (vertex curvature 1/(a²·|u − X|)).

use crate::surface::jet::Jet;

/// A contour family, validated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Contours {
    /// u = x.
    StraightLine,
    /// `(x − X)² + k·y² = (u − X)²`.
    Conic {
        /// X, mm.
        centre: f64,
        /// k: 1 for circles, −1/a² for hyperbolas.
        k: f64,
        /// σ = ±1: the side of the centre the part lies on (u = X − σ·d).
        sigma: f64,
    },
}

impl Contours {
    /// u(x, y) with its derivatives, or why there is none.
    pub fn u(&self, x: f64, y: f64) -> Result<Jet, String> {
        match *self {
            Contours::StraightLine => Ok(Jet::var_x(x)),
            Contours::Conic { centre, k, sigma } => conic_u(centre, k, sigma, x, y),
        }
    }
}

fn conic_u(centre: f64, k: f64, sigma: f64, x: f64, y: f64) -> Result<Jet, String> {
    let dx = x - centre;
    let q = dx * dx + k * y * y;
    if q.is_nan() || q <= 0.0 {
        return Err(if k > 0.0 {
            format!("at the contour circles' common centre x = {centre} mm")
        } else {
            format!("outside the contour hyperbolas' domain: (x − {centre})² + ({k})·y² ≤ 0 mm²")
        });
    }
    let d = q.sqrt();
    let (d_x, d_y) = (dx / d, k * y / d);
    let d = Jet {
        v: d,
        x: d_x,
        y: d_y,
        xx: (1.0 - d_x * d_x) / d,
        xy: -d_x * d_y / d,
        yy: (k - d_y * d_y) / d,
    };
    Ok(Jet::constant(centre) - d.scale(sigma))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn families() -> [Contours; 4] {
        [
            Contours::StraightLine,
            Contours::Conic {
                centre: 90.0,
                k: 1.0,
                sigma: 1.0,
            },
            Contours::Conic {
                centre: -120.0,
                k: -1.0 / 0.64,
                sigma: -1.0,
            },
            Contours::Conic {
                centre: 70.0,
                k: -0.25,
                sigma: 1.0,
            },
        ]
    }

    #[test]
    fn contours_cross_the_meridian_at_right_angles_at_x_equals_u() {
        for f in families() {
            for x in [-30.0, -4.0, 0.0, 11.0, 29.0] {
                let u = f.u(x, 0.0).unwrap();
                assert!((u.v - x).abs() < 1e-13, "{f:?} {x}: {}", u.v);
                assert_eq!(u.y, 0.0, "{f:?}: ∂u/∂y at y = 0");
                assert!((u.x - 1.0).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn points_laid_on_a_conic_give_its_u_back() {
        // Parametrise each contour independently of the formula: the circle of radius ρ = |u − X|
        // about (X, 0), x = X − σρ·cos φ, y = ρ·sin φ; the hyperbola x = X − σρ·cosh t,
        // y = aρ·sinh t.
        let u0 = 7.5;
        let circle = Contours::Conic {
            centre: 90.0,
            k: 1.0,
            sigma: 1.0,
        };
        let rho: f64 = 90.0 - u0;
        for phi in [-0.4, 0.1, 0.35] {
            let (x, y) = (90.0 - rho * f64::cos(phi), rho * f64::sin(phi));
            assert!((circle.u(x, y).unwrap().v - u0).abs() < 1e-12);
        }
        let a: f64 = 0.8;
        let hyperbola = Contours::Conic {
            centre: -120.0,
            k: -1.0 / (a * a),
            sigma: -1.0,
        };
        let rho: f64 = u0 + 120.0;
        for t in [-0.3, 0.05, 0.25] {
            let (x, y) = (-120.0 + rho * f64::cosh(t), a * rho * f64::sinh(t));
            assert!((hyperbola.u(x, y).unwrap().v - u0).abs() < 1e-12);
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        // Step 1e-5 mm on u of size ≤ 200 mm: rounding 1e-14·200/1e-5 ≈ 2e-7 for the gradient
        // and the Hessian from the analytic gradient ≈ 1e-10/1e-5; truncation h²/6·|u‴| ≪ 1e-9.
        let h = 1e-5;
        for f in families() {
            for &(x, y) in &[(3.0, 4.0), (-20.0, 17.0), (25.0, -30.0)] {
                let j = f.u(x, y).unwrap();
                let g = |x: f64, y: f64| f.u(x, y).unwrap();
                let fx = (g(x + h, y).v - g(x - h, y).v) / (2.0 * h);
                let fy = (g(x, y + h).v - g(x, y - h).v) / (2.0 * h);
                let fxx = (g(x + h, y).x - g(x - h, y).x) / (2.0 * h);
                let fxy = (g(x, y + h).x - g(x, y - h).x) / (2.0 * h);
                let fyx = (g(x + h, y).y - g(x - h, y).y) / (2.0 * h);
                let fyy = (g(x, y + h).y - g(x, y - h).y) / (2.0 * h);
                for (a, b) in [(j.x, fx), (j.y, fy)] {
                    assert!((a - b).abs() < 1e-6, "{f:?} ({x}, {y}): {a} vs {b}");
                }
                for (a, b) in [(j.xx, fxx), (j.xy, fxy), (j.xy, fyx), (j.yy, fyy)] {
                    assert!((a - b).abs() < 1e-8, "{f:?} ({x}, {y}): {a} vs {b}");
                }
            }
        }
    }

    #[test]
    fn a_hyperbola_has_no_value_between_its_asymptotes() {
        let f = Contours::Conic {
            centre: 70.0,
            k: -0.25,
            sigma: 1.0,
        };
        // a = 2: at x = 60 the asymptotes are at |y| = 20.
        assert!(f.u(60.0, 19.9).is_ok());
        assert!(f.u(60.0, 20.1).unwrap_err().contains("hyperbolas"));
        let c = Contours::Conic {
            centre: 90.0,
            k: 1.0,
            sigma: 1.0,
        };
        assert!(c.u(90.0, 0.0).unwrap_err().contains("centre"));
    }
}
