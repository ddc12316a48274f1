//! The height field `z(x, y)` of a parametric patch `S(u, v) = (X, Y, Z)` whose projection
//! onto XY is one-to-one, with its exact first and second derivatives by the chain rule.
//!
//! With `J = ∂(X, Y)/∂(u, v) = [[X_u, X_v], [Y_u, Y_v]]` and `Z(u, v) = z(X(u, v), Y(u, v))`:
//!
//! - first order: `[Z_u, Z_v] = [z_x, z_y]·J`, so `[z_x, z_y] = [Z_u, Z_v]·J⁻¹`, where
//!   `J⁻¹ = [[u_x, u_y], [v_x, v_y]] = [[Y_v, −X_v], [−Y_u, X_u]] / det J`;
//! - second order: differentiating `Z_u = z_x·X_u + z_y·Y_u` and `Z_v = z_x·X_v + z_y·Y_v` once
//!   more in u and v gives `∇²_uv Z = Jᵀ·H·J + z_x·∇²_uv X + z_y·∇²_uv Y`, H the Hessian of z in
//!   (x, y); hence `H = J⁻ᵀ·M·J⁻¹` with `M = ∇²_uv Z − z_x·∇²_uv X − z_y·∇²_uv Y`. This is the
//!   same as differentiating the inverse Jacobian, `∂(J⁻¹)/∂x = −J⁻¹·(∂J/∂x)·J⁻¹`, in
//!   `∇z = J⁻ᵀ·∇_uv Z`, written so that no third derivative or differencing is needed.

use super::patch::Derivs;
use crate::surface::Local;

/// Sag, gradient and Hessian of the height field at the patch point with derivatives `d`;
/// `det J` must be non-zero (the caller checks it).
pub fn height(d: &Derivs) -> Local {
    let (xu, xv, yu, yv) = (d.su[0], d.sv[0], d.su[1], d.sv[1]);
    let det = xu * yv - xv * yu;
    let (ux, uy, vx, vy) = (yv / det, -xv / det, -yu / det, xu / det);
    let zx = d.su[2] * ux + d.sv[2] * vx;
    let zy = d.su[2] * uy + d.sv[2] * vy;
    let m = |h: [f64; 3]| h[2] - zx * h[0] - zy * h[1];
    let (muu, muv, mvv) = (m(d.suu), m(d.suv), m(d.svv));
    // aᵀ·M·b for columns a, b of J⁻¹.
    let form = |a: (f64, f64), b: (f64, f64)| {
        a.0 * (muu * b.0 + muv * b.1) + a.1 * (muv * b.0 + mvv * b.1)
    };
    let (cx, cy) = ((ux, vx), (uy, vy));
    Local {
        z: d.s[2],
        zx,
        zy,
        zxx: form(cx, cx),
        zxy: form(cx, cy),
        zyy: form(cy, cy),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sheared_polynomial_parametrisation_gives_the_closed_form() {
        // X = u + 0.3v, Y = −0.2u + v, Z = z(X, Y) with z = a·x² + b·xy + c·y² + d·x + e·y, so
        // the height field's derivatives are known exactly whatever the parametrisation.
        let (a, b, c, dd, e) = (0.7, -0.4, 1.3, 0.2, -0.5);
        let (u, v) = (0.6, -1.1);
        let (x, y) = (u + 0.3 * v, -0.2 * u + v);
        let (xu, xv, yu, yv) = (1.0, 0.3, -0.2, 1.0);
        let zx = 2.0 * a * x + b * y + dd;
        let zy = b * x + 2.0 * c * y + e;
        let (hxx, hxy, hyy) = (2.0 * a, b, 2.0 * c);
        // Z_u = zx·X_u + zy·Y_u; Z_uu = Jᵀ H J (X, Y linear in u, v).
        let zu = zx * xu + zy * yu;
        let zv = zx * xv + zy * yv;
        let zuu = hxx * xu * xu + 2.0 * hxy * xu * yu + hyy * yu * yu;
        let zuv = hxx * xu * xv + hxy * (xu * yv + xv * yu) + hyy * yu * yv;
        let zvv = hxx * xv * xv + 2.0 * hxy * xv * yv + hyy * yv * yv;
        let z = a * x * x + b * x * y + c * y * y + dd * x + e * y;
        let d = Derivs {
            s: [x, y, z],
            su: [xu, yu, zu],
            sv: [xv, yv, zv],
            suu: [0.0, 0.0, zuu],
            suv: [0.0, 0.0, zuv],
            svv: [0.0, 0.0, zvv],
        };
        let l = height(&d);
        let want = [z, zx, zy, hxx, hxy, hyy];
        let got = [l.z, l.zx, l.zy, l.zxx, l.zxy, l.zyy];
        for k in 0..6 {
            assert!((got[k] - want[k]).abs() < 1e-14, "{k}: {got:?} {want:?}");
        }
    }

    #[test]
    fn a_curved_parametrisation_needs_the_second_derivative_terms() {
        // X = u + u², Y = v, Z = X² (so z = x², z_xx = 2): at u = 1, X_u = 3, X_uu = 2.
        let (u, v) = (1.0, 0.5);
        let x: f64 = u + u * u;
        let d = Derivs {
            s: [x, v, x * x],
            su: [1.0 + 2.0 * u, 0.0, 2.0 * x * (1.0 + 2.0 * u)],
            sv: [0.0, 1.0, 0.0],
            suu: [2.0, 0.0, 2.0 * (1.0 + 2.0 * u).powi(2) + 2.0 * x * 2.0],
            suv: [0.0; 3],
            svv: [0.0; 3],
        };
        let l = height(&d);
        assert!((l.zx - 2.0 * x).abs() < 1e-14);
        assert!((l.zxx - 2.0).abs() < 1e-14, "{}", l.zxx);
        assert_eq!((l.zy, l.zxy, l.zyy), (0.0, 0.0, 0.0));
    }
}
