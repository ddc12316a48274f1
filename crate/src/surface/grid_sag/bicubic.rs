//! Bicubic Hermite patches on a grid's cells, their 16 coefficients computed once per cell
//! (the classic bicubic interpolation from values, slopes and cross derivatives at the four
//! corners: Press et al., *Numerical Recipes*, 3rd ed., §3.6.3, "bcucof"/"bcuint", written
//! here as a tensor product): in local coordinates u, v ∈ [0, 1] of a cell,
//! `p(u, v) = Σₖₗ aₖₗ·uᵏ·vˡ` with `A = M·G·Mᵀ`, G the corner data
//! `[[F₀₀, F_v₀₀, F₀₁, F_v₀₁], [F_u₀₀, F_uv₀₀, F_u₀₁, F_uv₀₁], [F₁₀, …], [F_u₁₀, …]]` (first
//! index u, second v; slopes in cell units, `F_u = ∂z/∂x·Δx`, `F_uv = ∂²z/∂x∂y·Δx·Δy`) and M the
//! cubic Hermite basis in monomials, `[p₀, p₀′, p₁, p₁′] ↦ [c₀, c₁, c₂, c₃]`:
//! `c₀ = p₀`, `c₁ = p₀′`, `c₂ = −3p₀ − 2p₀′ + 3p₁ − p₁′`, `c₃ = 2p₀ + p₀′ − 2p₁ + p₁′`.
//!
//! Neighbouring patches share their edge's values and slopes (each edge's cubic is fixed by the
//! two corners' data), so the surface is C¹ across cells; the Hessian jumps there unless the
//! corner data come from a spline ([`super::spline`]).

/// The corner data of a patch in cell units: `[F, F_u, F_v, F_uv]` at corners (0,0), (1,0),
/// (0,1), (1,1) (first index u).
pub type Corners = [[f64; 4]; 4];

/// `M` of the module docs.
const M: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [-3.0, -2.0, 3.0, -1.0],
    [2.0, 1.0, -2.0, 1.0],
];

/// The coefficients `a[4k + l]` of uᵏvˡ of the patch with corner data `c`.
pub fn coefficients(c: &Corners) -> [f64; 16] {
    let [c00, c10, c01, c11] = c;
    let g = [
        [c00[0], c00[2], c01[0], c01[2]],
        [c00[1], c00[3], c01[1], c01[3]],
        [c10[0], c10[2], c11[0], c11[2]],
        [c10[1], c10[3], c11[1], c11[3]],
    ];
    // A = M·G·Mᵀ.
    let mut mg = [[0.0; 4]; 4];
    for (k, row) in mg.iter_mut().enumerate() {
        for (l, slot) in row.iter_mut().enumerate() {
            *slot = (0..4).map(|q| M[k][q] * g[q][l]).sum();
        }
    }
    let mut a = [0.0; 16];
    for k in 0..4 {
        for l in 0..4 {
            a[4 * k + l] = (0..4).map(|q| mg[k][q] * M[l][q]).sum();
        }
    }
    a
}

/// `[p, p_u, p_v, p_uu, p_uv, p_vv]` of the patch `a` at (u, v): each row's cubic in v and
/// its two derivatives by Horner's rule, then the same in u over the rows.
#[inline]
pub fn eval(a: &[f64; 16], u: f64, v: f64) -> [f64; 6] {
    let mut r = [0.0; 4];
    let mut rv = [0.0; 4];
    let mut rvv = [0.0; 4];
    for k in 0..4 {
        let [c0, c1, c2, c3] = [a[4 * k], a[4 * k + 1], a[4 * k + 2], a[4 * k + 3]];
        r[k] = c0 + v * (c1 + v * (c2 + v * c3));
        rv[k] = c1 + v * (2.0 * c2 + v * (3.0 * c3));
        rvv[k] = 2.0 * c2 + v * (6.0 * c3);
    }
    let cubic = |q: &[f64; 4]| q[0] + u * (q[1] + u * (q[2] + u * q[3]));
    let slope = |q: &[f64; 4]| q[1] + u * (2.0 * q[2] + u * (3.0 * q[3]));
    [
        cubic(&r),
        slope(&r),
        cubic(&rv),
        2.0 * r[2] + u * (6.0 * r[3]),
        slope(&rv),
        cubic(&rvv),
    ]
}

/// Bounds of `[|p_u|, |p_v|, |p_uu|, |p_uv|, |p_vv|]` over the cell (u, v ∈ [0, 1], where every
/// |uᵏvˡ| ≤ 1) of the patch with coefficients `a`: `Σ k·|aₖₗ|`, `Σ l·|aₖₗ|`, `Σ k(k − 1)·|aₖₗ|`,
/// `Σ kl·|aₖₗ|`, `Σ l(l − 1)·|aₖₗ|`.
pub fn derivative_bounds(a: &[f64; 16]) -> [f64; 5] {
    let mut b = [0.0; 5];
    for (i, c) in a.iter().enumerate() {
        let (k, l, c) = ((i / 4) as f64, (i % 4) as f64, c.abs());
        b[0] += k * c;
        b[1] += l * c;
        b[2] += k * (k - 1.0) * c;
        b[3] += k * l * c;
        b[4] += l * (l - 1.0) * c;
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bicubic_polynomial_is_reproduced_from_its_corner_data() {
        // f(u, v) = Σ bₖₗ uᵏ vˡ with all 16 terms: its own corner data give back its coefficients.
        let b: [f64; 16] = std::array::from_fn(|k| (k as f64 * 0.37).sin());
        let f = |u: f64, v: f64| -> [f64; 4] {
            let mut out = [0.0; 4];
            for k in 0..4 {
                for l in 0..4 {
                    let c = b[4 * k + l];
                    let (kf, lf) = (k as f64, l as f64);
                    out[0] += c * u.powi(k as i32) * v.powi(l as i32);
                    if k > 0 {
                        out[1] += c * kf * u.powi(k as i32 - 1) * v.powi(l as i32);
                    }
                    if l > 0 {
                        out[2] += c * lf * u.powi(k as i32) * v.powi(l as i32 - 1);
                    }
                    if k > 0 && l > 0 {
                        out[3] += c * kf * lf * u.powi(k as i32 - 1) * v.powi(l as i32 - 1);
                    }
                }
            }
            out
        };
        let a = coefficients(&[f(0.0, 0.0), f(1.0, 0.0), f(0.0, 1.0), f(1.0, 1.0)]);
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() < 1e-13, "{x} {y}");
        }
        let e = eval(&a, 0.3, 0.8);
        assert!((e[0] - f(0.3, 0.8)[0]).abs() < 1e-14);
        assert!((e[4] - f(0.3, 0.8)[3]).abs() < 1e-13);
    }
}
