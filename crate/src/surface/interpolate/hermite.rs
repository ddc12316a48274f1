//! Bicubic Hermite interpolation on a regular grid (paper 004 section 3 compares "Hermite"
//! interpolation, after Li et al. 2017 and Liu et al. 2014; the patch is the classic bicubic
//! of Hermite data, e.g. Press et al., *Numerical Recipes*, 3rd ed., §3.6.1).
//!
//! On the cell `[xᵢ, xᵢ₊₁] × [yⱼ, yⱼ₊₁]` with local coordinates u, v ∈ [0, 1],
//! `f = Σ_{a,b∈{0,1}} [F·H₀ₐ(u)H₀ᵦ(v) + F_u·H₁ₐ(u)H₀ᵦ(v) + F_v·H₀ₐ(u)H₁ᵦ(v) + F_uv·H₁ₐ(u)H₁ᵦ(v)]`
//! at the four corners, with the cubic Hermite basis `H₀₀ = 2u³ − 3u² + 1`, `H₀₁ = 3u² − 2u³`,
//! `H₁₀ = u³ − 2u² + u`, `H₁₁ = u³ − u²`. The corner slopes and cross derivatives are
//! estimated from the heights by second-order differences: central inside, one-sided
//! `(∓3z₀ ± 4z₁ ∓ z₂)/2` at the border, and `F_uv` as the x difference of the y differences.
//! Polynomials of degree ≤ 2 in each of x and y are reproduced exactly.
//!
//! Neighbouring patches share the corner values and slopes, so f and its gradient are
//! continuous everywhere (C¹): no slope kinks. The Hessian jumps across the grid lines. It
//! uses the 4 × 4 nodes around the cell (16 neighbours) and needs at least 3 nodes along
//! each axis.

use super::data::Grid;
use crate::surface::Local;

/// Second-order difference weights (index units) for the derivative at node `i` of `n ≥ 3`.
fn weights(i: usize, n: usize) -> [(usize, f64); 3] {
    if i == 0 {
        [(0, -1.5), (1, 2.0), (2, -0.5)]
    } else if i + 1 == n {
        [(n - 1, 1.5), (n - 2, -2.0), (n - 3, 0.5)]
    } else {
        [(i - 1, -0.5), (i + 1, 0.5), (i, 0.0)]
    }
}

/// Value, first and second derivative of the Hermite basis at u: `[order][kind][end]`, kind 0
/// the value functions H₀ₐ, kind 1 the slope functions H₁ₐ.
fn basis(u: f64) -> [[[f64; 2]; 2]; 3] {
    let (u2, u3) = (u * u, u * u * u);
    [
        [
            [2.0 * u3 - 3.0 * u2 + 1.0, 3.0 * u2 - 2.0 * u3],
            [u3 - 2.0 * u2 + u, u3 - u2],
        ],
        [
            [6.0 * u2 - 6.0 * u, 6.0 * u - 6.0 * u2],
            [3.0 * u2 - 4.0 * u + 1.0, 3.0 * u2 - 2.0 * u],
        ],
        [
            [12.0 * u - 6.0, 6.0 - 12.0 * u],
            [6.0 * u - 4.0, 6.0 * u - 2.0],
        ],
    ]
}

/// The cell containing a coordinate along one axis, and the local coordinate in it.
fn cell(x: f64, x0: f64, d: f64, n: usize) -> (usize, f64) {
    let t = (x - x0) / d;
    let i = (t.floor().max(0.0) as usize).min(n - 2);
    (i, t - i as f64)
}

/// The Hermite data `[F, F_u, F_v, F_uv]` at node (i, j), in index units.
fn node(g: &Grid, z: &[f64], i: usize, j: usize) -> [f64; 4] {
    let at = |i: usize, j: usize| z[j * g.nx + i];
    let du = |j: usize| {
        weights(i, g.nx)
            .iter()
            .map(|&(k, w)| w * at(k, j))
            .sum::<f64>()
    };
    let dv = weights(j, g.ny)
        .iter()
        .map(|&(k, w)| w * at(i, k))
        .sum::<f64>();
    let duv = weights(j, g.ny)
        .iter()
        .map(|&(k, w)| w * du(k))
        .sum::<f64>();
    [at(i, j), du(j), dv, duv]
}

/// f with its derivatives at (x, y) on the grid `g` with heights `z` (row by row).
pub fn local(g: &Grid, z: &[f64], x: f64, y: f64) -> Local {
    let (i, u) = cell(x, g.x0, g.dx, g.nx);
    let (j, v) = cell(y, g.y0, g.dy, g.ny);
    let (bu, bv) = (basis(u), basis(v));
    // d[ou][ov]: ∂^{ou+ov} f / ∂u^{ou} ∂v^{ov}.
    let mut d = [[0.0; 3]; 3];
    for (a, b) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
        {
            let h = node(g, z, i + a, j + b);
            for (ou, ov) in [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)] {
                d[ou][ov] += h[0] * bu[ou][0][a] * bv[ov][0][b]
                    + h[1] * bu[ou][1][a] * bv[ov][0][b]
                    + h[2] * bu[ou][0][a] * bv[ov][1][b]
                    + h[3] * bu[ou][1][a] * bv[ov][1][b];
            }
        }
    }
    Local {
        z: d[0][0],
        zx: d[1][0] / g.dx,
        zy: d[0][1] / g.dy,
        zxx: d[2][0] / (g.dx * g.dx),
        zxy: d[1][1] / (g.dx * g.dy),
        zyy: d[0][2] / (g.dy * g.dy),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> Grid {
        Grid {
            x0: -0.3,
            y0: 0.1,
            dx: 0.05,
            dy: 0.03,
            nx: 9,
            ny: 7,
        }
    }

    fn heights(g: &Grid, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        (0..g.ny)
            .flat_map(|j| (0..g.nx).map(move |i| (i, j)))
            .map(|(i, j)| {
                let p = g.node(i, j);
                f(p[0], p[1])
            })
            .collect()
    }

    #[test]
    fn biquadratics_are_reproduced_with_their_derivatives() {
        let f = |x: f64, y: f64| {
            1.0 + 2.0 * x - y + 0.5 * x * x + 0.3 * x * y - 0.7 * y * y + 0.2 * x * x * y * y
        };
        let g = grid();
        let z = heights(&g, f);
        for &(x, y) in &[
            (-0.3, 0.1),
            (-0.21, 0.17),
            (0.1, 0.2),
            (0.1, 0.28),
            (0.07, 0.123),
        ] {
            let l = local(&g, &z, x, y);
            assert!((l.z - f(x, y)).abs() < 1e-14, "({x}, {y})");
            assert!((l.zx - (2.0 + x + 0.3 * y + 0.4 * x * y * y)).abs() < 1e-12);
            assert!((l.zy - (-1.0 + 0.3 * x - 1.4 * y + 0.4 * x * x * y)).abs() < 1e-12);
            assert!((l.zxx - (1.0 + 0.4 * y * y)).abs() < 1e-10);
            assert!((l.zxy - (0.3 + 0.8 * x * y)).abs() < 1e-10);
            assert!((l.zyy - (-1.4 + 0.4 * x * x)).abs() < 1e-10);
        }
    }

    #[test]
    fn interpolates_and_is_c1_across_cell_edges() {
        let g = grid();
        let f = |x: f64, y: f64| (9.0 * x).sin() * (7.0 * y).cos() * 1e-2;
        let z = heights(&g, f);
        for j in 0..g.ny {
            for i in 0..g.nx {
                let p = g.node(i, j);
                assert!((local(&g, &z, p[0], p[1]).z - z[j * g.nx + i]).abs() < 1e-15);
            }
        }
        // Across x = x₃ (between cells 2 and 3) and y = y₂, 2e-12 mm apart: f may differ by
        // |∇f|·2e-12 < 1e-12, the slopes by |∇²f|·2e-12 plus the rounding of the patch.
        let (xe, ye) = (g.node(3, 0)[0], g.node(0, 2)[1]);
        let e = 1e-12;
        for &y in &[0.13, 0.171, 0.25] {
            let (l, r) = (local(&g, &z, xe - e, y), local(&g, &z, xe + e, y));
            assert!(
                (l.z - r.z).abs() < 1e-12
                    && (l.zx - r.zx).abs() < 1e-9
                    && (l.zy - r.zy).abs() < 1e-9
            );
        }
        let (b, t) = (local(&g, &z, -0.12, ye - e), local(&g, &z, -0.12, ye + e));
        assert!(
            (b.z - t.z).abs() < 1e-12 && (b.zx - t.zx).abs() < 1e-9 && (b.zy - t.zy).abs() < 1e-9
        );
        // The curvature does jump there.
        let (l, r) = (local(&g, &z, xe - e, 0.171), local(&g, &z, xe + e, 0.171));
        assert!((l.zxx - r.zxx).abs() > 1e-4, "{} {}", l.zxx, r.zxx);
    }

    #[test]
    fn derivatives_match_finite_differences_inside_a_cell() {
        let g = grid();
        let f = |x: f64, y: f64| (9.0 * x).sin() * (7.0 * y).cos() * 1e-2 + x * y * y;
        let z = heights(&g, f);
        let (x, y, e) = (0.013, 0.187, 1e-6);
        let l = local(&g, &z, x, y);
        let at = |dx: f64, dy: f64| local(&g, &z, x + dx, y + dy);
        let c = |a: f64, b: f64| (a - b) / (2.0 * e);
        // A cubic patch: central differences are exact to e²·|f‴|/6 ≲ 1e-9 plus rounding.
        assert!((l.zx - c(at(e, 0.0).z, at(-e, 0.0).z)).abs() < 1e-8);
        assert!((l.zy - c(at(0.0, e).z, at(0.0, -e).z)).abs() < 1e-8);
        assert!((l.zxx - c(at(e, 0.0).zx, at(-e, 0.0).zx)).abs() < 1e-6);
        assert!((l.zxy - c(at(0.0, e).zx, at(0.0, -e).zx)).abs() < 1e-6);
        assert!((l.zyy - c(at(0.0, e).zy, at(0.0, -e).zy)).abs() < 1e-6);
    }
}
