//! Derivatives of a grid's sags when the file gives none: the slopes of the not-a-knot cubic
//! spline through each row and each column (C. de Boor, *A Practical Guide to Splines*, 2001,
//! ch. IV, the "not-a-knot" end condition), and the cross derivative as the column splines'
//! slopes of the row slopes. Fed to the bicubic patches ([`super::bicubic`]), these make the
//! surface the tensor-product cubic spline through the sags: C² and exact for bicubic
//! polynomials (OpticStudio calls its grid interpolation a "bicubic spline" and does not say how
//! it computes missing derivatives; this is the spline of that name).
//!
//! With equal spacing h the slopes sᵢ solve `sᵢ₋₁ + 4sᵢ + sᵢ₊₁ = 3(zᵢ₊₁ − zᵢ₋₁)/h` inside
//! (continuous second derivative) and, for the not-a-knot ends (continuous third derivative at
//! the second and the last-but-one node), `s₀ + 2s₁ = (−5z₀ + 4z₁ + z₂)/(2h)` and
//! `2sₙ₋₂ + sₙ₋₁ = (5zₙ₋₁ − 4zₙ₋₂ − zₙ₋₃)/(2h)`: a tridiagonal system, solved by elimination
//! without pivoting (Thomas' algorithm; every pivot is at least 0.43 for these rows). A run of
//! points with data between gaps is splined alone: 3 points take the parabola's slopes, 2 the
//! chord's, 1 none (no cell uses it).

/// The slopes of the spline through `z` at spacing `h` into `out` (same length).
pub fn slopes(z: &[f64], h: f64, out: &mut [f64]) {
    let n = z.len();
    match n {
        0 => {}
        1 => out[0] = 0.0,
        2 => {
            let s = (z[1] - z[0]) / h;
            out[0] = s;
            out[1] = s;
        }
        3 => {
            out[0] = (-3.0 * z[0] + 4.0 * z[1] - z[2]) / (2.0 * h);
            out[1] = (z[2] - z[0]) / (2.0 * h);
            out[2] = (z[0] - 4.0 * z[1] + 3.0 * z[2]) / (2.0 * h);
        }
        _ => not_a_knot(z, h, out),
    }
}

/// The not-a-knot system for n ≥ 4 points, by forward elimination and back substitution.
fn not_a_knot(z: &[f64], h: f64, out: &mut [f64]) {
    let n = z.len();
    // Row i: a·s[i−1] + b·s[i] + c·s[i+1] = r; `c_prime` holds the eliminated super-diagonal.
    let row = |i: usize| -> (f64, f64, f64, f64) {
        if i == 0 {
            (0.0, 1.0, 2.0, (-5.0 * z[0] + 4.0 * z[1] + z[2]) / (2.0 * h))
        } else if i == n - 1 {
            (
                2.0,
                1.0,
                0.0,
                (5.0 * z[n - 1] - 4.0 * z[n - 2] - z[n - 3]) / (2.0 * h),
            )
        } else {
            (1.0, 4.0, 1.0, 3.0 * (z[i + 1] - z[i - 1]) / h)
        }
    };
    let mut c_prime = vec![0.0; n];
    let (mut prev_c, mut prev_r) = (0.0, 0.0);
    for (i, slot) in out.iter_mut().enumerate().take(n) {
        let (a, b, c, r) = row(i);
        let pivot = b - a * prev_c;
        prev_c = c / pivot;
        prev_r = (r - a * prev_r) / pivot;
        c_prime[i] = prev_c;
        *slot = prev_r;
    }
    for i in (0..n - 1).rev() {
        out[i] -= c_prime[i] * out[i + 1];
    }
}

/// Calls `f(start, len)` for every maximal run of consecutive `true` in `valid`.
pub fn runs(valid: impl Iterator<Item = bool>, mut f: impl FnMut(usize, usize)) {
    let mut start = None;
    let mut k = 0;
    for v in valid {
        match (v, start) {
            (true, None) => start = Some(k),
            (false, Some(s)) => {
                f(s, k - s);
                start = None;
            }
            _ => {}
        }
        k += 1;
    }
    if let Some(s) = start {
        f(s, k - s);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubics_are_reproduced() {
        // The not-a-knot spline through a cubic is the cubic: exact slopes.
        let h = 0.3;
        let p = |t: f64| 1.0 - 2.0 * t + 0.5 * t * t - 0.7 * t * t * t;
        let dp = |t: f64| -2.0 + t - 2.1 * t * t;
        for n in [4, 5, 9, 40] {
            let z: Vec<f64> = (0..n).map(|i| p(-1.0 + i as f64 * h)).collect();
            let mut s = vec![0.0; n];
            slopes(&z, h, &mut s);
            for (i, si) in s.iter().enumerate() {
                let want = dp(-1.0 + i as f64 * h);
                assert!((si - want).abs() < 1e-11, "n {n}, node {i}: {si} vs {want}");
            }
        }
        // Three points: a parabola's slopes.
        let mut s = [0.0; 3];
        slopes(&[1.0, 2.0, 5.0], 1.0, &mut s);
        assert_eq!(s, [0.0, 2.0, 4.0]);
    }

    #[test]
    fn runs_are_maximal() {
        let mut got = Vec::new();
        runs(
            [true, true, false, true, false, false, true, true, true].into_iter(),
            |s, l| got.push((s, l)),
        );
        assert_eq!(got, vec![(0, 2), (3, 1), (6, 3)]);
    }
}
