//! Shepard's inverse distance weighting over the n nearest neighbours (D. Shepard, "A
//! two-dimensional interpolation function for irregularly-spaced data", Proc. 23rd ACM National
//! Conference, 1968; paper 004 section 3 compares it as "Shepard"):
//! `f(p) = Σ wⱼ zⱼ / Σ wⱼ`, `wⱼ = 1/|p − pⱼ|²` (power 2, Shepard's choice).
//!
//! Near the nearest neighbour j₀ the same function is written
//! `f = z₀ + u·A / (1 + u·W)`, `u = |p − p₀|²`, `A = Σ_{k≠0} w_k (z_k − z₀)`, `W = Σ_{k≠0} w_k`
//! (multiply numerator and denominator by u): algebraically identical, finite at p₀ itself,
//! and free of cancellation there. It shows the method's known flat spots: at every data point
//! the gradient is zero and the Hessian is `2A·I` — the "duck egg" distortion of the lenslet
//! vertices that paper 004 notes. Derivatives by jets ([`crate::surface::jet`]). Between
//! switches of the neighbour set f is smooth; at a switch it jumps.

use crate::surface::Local;
use crate::surface::jet::Jet;

/// f with its derivatives at `q` from the neighbours `centres` with heights `z`.
pub fn local(centres: &[[f64; 2]], z: &[f64], q: [f64; 2]) -> Local {
    let d2 = |p: [f64; 2]| (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
    let Some(j0) = (0..centres.len()).min_by(|&a, &b| d2(centres[a]).total_cmp(&d2(centres[b])))
    else {
        return Local::default();
    };
    let p0 = centres[j0];
    let u = Jet::squared_distance(q[0] - p0[0], q[1] - p0[1]);
    let (mut a, mut w) = (Jet::default(), Jet::default());
    for (k, p) in centres.iter().enumerate().filter(|&(k, _)| k != j0) {
        let wk = Jet::squared_distance(q[0] - p[0], q[1] - p[1]).recip();
        a = a + wk.scale(z[k] - z[j0]);
        w = w + wk;
    }
    let f = u * a / (Jet::constant(1.0) + u * w) + Jet::constant(z[j0]);
    f.into()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stencil() -> (Vec<[f64; 2]>, Vec<f64>) {
        let c: Vec<[f64; 2]> = vec![
            [0.0, 0.0],
            [0.04, 0.003],
            [-0.002, 0.041],
            [0.038, 0.043],
            [-0.041, 0.001],
            [0.001, -0.039],
            [-0.04, 0.04],
            [0.042, -0.04],
        ];
        let z = c
            .iter()
            .map(|p| 1e-3 * (20.0 * p[0]).sin() + p[1])
            .collect();
        (c, z)
    }

    #[test]
    fn equals_the_weighted_mean_and_interpolates() {
        let (c, z) = stencil();
        for q in [[0.013, 0.027], [-0.02, -0.011], [0.035, 0.039]] {
            let w: Vec<f64> = c
                .iter()
                .map(|p| 1.0 / ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)))
                .collect();
            let mean = w.iter().zip(&z).map(|(w, z)| w * z).sum::<f64>() / w.iter().sum::<f64>();
            assert!((local(&c, &z, q).z - mean).abs() < 1e-15);
        }
        for (p, zj) in c.iter().zip(&z) {
            let l = local(&c, &z, *p);
            assert_eq!(l.z, *zj);
            assert_eq!((l.zx, l.zy, l.zxy), (0.0, 0.0, 0.0), "flat spot");
            assert_eq!(l.zxx, l.zyy);
        }
    }

    #[test]
    fn derivatives_match_finite_differences_also_at_a_data_point() {
        let (c, z) = stencil();
        for q in [[0.013, 0.027], [0.0, 0.0], [0.04, 0.003], [1e-4, -2e-4]] {
            let l = local(&c, &z, q);
            let e = 1e-6;
            let at = |dx: f64, dy: f64| local(&c, &z, [q[0] + dx, q[1] + dy]);
            let fx = (at(e, 0.0).z - at(-e, 0.0).z) / (2.0 * e);
            let fy = (at(0.0, e).z - at(0.0, -e).z) / (2.0 * e);
            let fxx = (at(e, 0.0).zx - at(-e, 0.0).zx) / (2.0 * e);
            let fxy = (at(0.0, e).zx - at(0.0, -e).zx) / (2.0 * e);
            let fyy = (at(0.0, e).zy - at(0.0, -e).zy) / (2.0 * e);
            // |f‴| of a weighted mean over spacing 0.04 mm is ~ |Δz|/0.04³ ≈ 1e3: the central
            // difference error e²·|f‴|/6 is ~2e-10; rounding e⁻¹·1e-16 ~ 1e-10 (1e-7 for the
            // second derivatives' differences of first derivatives of size 1).
            assert!(
                (l.zx - fx).abs() < 1e-8 && (l.zy - fy).abs() < 1e-8,
                "{q:?}"
            );
            for (a, b) in [(l.zxx, fxx), (l.zxy, fxy), (l.zyy, fyy)] {
                assert!((a - b).abs() < 1e-5 * (1.0 + a.abs()), "{q:?}: {a} {b}");
            }
        }
    }
}
