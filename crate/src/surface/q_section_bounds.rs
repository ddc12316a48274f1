//! Section bounds of Forbes' Q surfaces ([`super::SectionBounds`] for Qcon, Qbfs and Q₂D): along
//! a radial section at any spindle angle a Q term is a polynomial in the signed radius t, so its
//! derivatives are bounded from samples by Markov brothers' inequality, and the factor
//! `1/√(1 − c²t²)` of a departure along the best-fit sphere's normal by its value at the rim.
//!
//! **A term's section.** `u^m·cos mθ·P(u²)` (or sin mθ), u = ρ/N, P of degree d in x = u², along
//! the line through the axis at angle θ with signed coordinate t (ρ = |t|, the angle θ + π for
//! t < 0, where `cos m(θ + π) = (−1)^m·cos mθ`): `cos mθ·h(t)`, `h(t) = (t/N)^m·P(t²/N²)`, a
//! polynomial of degree n = m + 2d in t, even or odd; |cos mθ| ≤ 1 whatever θ. So the bounds of
//! |h|, |h′|, |h″| over [0, T] bound the term's section over |t| ≤ T at every angle, and a sum's
//! bounds are the sum of its terms' (the cos mθ and sin mθ parts of each order separately).
//!
//! **Bounds from samples.** h, h′ and h″ are sampled at K + 1 equally spaced points of [0, T]:
//! every t lies within T/(2K) of one, and for a polynomial q of degree ≤ n Markov brothers'
//! inequality bounds its slope on [0, T] by `(2n²/T)·max|q|`, so `max|q| ≤ M + (n²/K)·max|q|`,
//! `max|q| ≤ M/(1 − n²/K)` with M the largest sampled |q|. K = 16n² + 64 leaves the bounds within
//! 1/15 of the extremes; n is at most 30 + 2·30 (Q₂D's m, n ≤ 30), so at most 130 000 samples
//! a sum, once a path.
//!
//! **Along the sphere's normal.** With `g = (1 − c²t²)^(−1/2)`, `g′ = c²t·g³` and
//! `g″ = c²g³ + 3c⁴t²g⁵` grow with |t| (their largest on |t| ≤ T are at T), and
//! `(Ag)′ = A′g + Ag′`, `(Ag)″ = A″g + 2A′g′ + Ag″` are bounded term by term.

use super::q_polynomials::Jet1;

/// Upper bounds of `[|h|, |h′|, |h″|]` over |t| ≤ `radius` for the section `h(t) =
/// (t/N)^m·P(t²/N²)` of a Q term (N = `norm`; see the module docs), P of `degree` in x = u²
/// given by its jet `p` at x; infinite where a sample is not finite.
pub fn section_term_bounds(
    m: usize,
    degree: usize,
    norm: f64,
    radius: f64,
    p: impl Fn(f64) -> Jet1,
) -> [f64; 3] {
    let n = m + 2 * degree;
    let k = 16 * n * n + 64;
    let mut max = [0.0f64; 3];
    for i in 0..=k {
        let w = radius * i as f64 / k as f64 / norm;
        let h = in_w(m, w, p(w * w));
        if !h.iter().all(|v| v.is_finite()) {
            return [f64::INFINITY; 3];
        }
        for (largest, v) in max.iter_mut().zip(h) {
            *largest = largest.max(v.abs());
        }
    }
    // M/(1 − n²/K), with a relative margin far above the samples' rounding.
    let widen = (1.0 + 1e-9) / (1.0 - (n * n) as f64 / k as f64);
    [
        max[0] * widen,
        max[1] * widen / norm,
        max[2] * widen / (norm * norm),
    ]
}

/// `[h, dh/dw, d²h/dw²]` of `h = w^m·P(w²)` at w ≥ 0 from P's jet at w²:
/// `dh/dw = m·w^(m−1)·P + 2w^(m+1)·P′`,
/// `d²h/dw² = m(m − 1)·w^(m−2)·P + (4m + 2)·w^m·P′ + 4w^(m+2)·P″`.
fn in_w(m: usize, w: f64, [p, p1, p2]: Jet1) -> Jet1 {
    let mf = m as f64;
    let wm = w.powi(m as i32);
    let below = |k: usize| if m >= k { w.powi((m - k) as i32) } else { 0.0 };
    [
        wm * p,
        mf * below(1) * p + 2.0 * wm * w * p1,
        mf * (mf - 1.0) * below(2) * p + (4.0 * mf + 2.0) * wm * p1 + 4.0 * wm * w * w * p2,
    ]
}

/// `(slope, curvature)` bounds over |t| ≤ `radius` of the section of a departure `A·g` along the
/// normal of a sphere of curvature `c` (see the module docs), from `a` = `[|A|, |A′|, |A″|]`;
/// `None` at or beyond the sphere's rim.
pub fn along_sphere_normal(c: f64, radius: f64, a: [f64; 3]) -> Option<(f64, f64)> {
    let q = 1.0 - c * c * radius * radius;
    if q.is_nan() || q <= 0.0 {
        return None;
    }
    let (c2, g) = (c * c, 1.0 / q.sqrt());
    let g3 = g * g * g;
    let g1 = c2 * radius * g3;
    let g2 = c2 * g3 + 3.0 * c2 * c2 * radius * radius * g3 * g * g;
    Some((a[1] * g + a[0] * g1, a[2] * g + 2.0 * a[1] * g1 + a[0] * g2))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// T_n(2x − 1) in x with its derivatives, by the recurrence.
    fn shifted_chebyshev(n: usize, x: f64) -> Jet1 {
        let t = 2.0 * x - 1.0;
        let (mut prev, mut cur) = ([1.0, 0.0, 0.0], [t, 2.0, 0.0]);
        if n == 0 {
            return prev;
        }
        for _ in 1..n {
            let next = [
                2.0 * t * cur[0] - prev[0],
                4.0 * cur[0] + 2.0 * t * cur[1] - prev[1],
                8.0 * cur[1] + 2.0 * t * cur[2] - prev[2],
            ];
            prev = cur;
            cur = next;
        }
        cur
    }

    #[test]
    fn a_chebyshev_term_is_bounded_within_a_fifteenth_of_its_extremes() {
        // h(t) = T_n(2t²/N² − 1) on |t| ≤ N: |h| ≤ 1, |h′| ≤ 4n²/N (at t = N, from
        // |T_n′(1)| = n²), |h″| reached at t = N too: (2/N²)·2n² + (4/N²)·4·n²(n² − 1)/3.
        for n in [1usize, 3, 8] {
            let norm = 2.5;
            let b = section_term_bounds(0, n, norm, norm, |x| shifted_chebyshev(n, x));
            let nf = n as f64;
            let exact = [
                1.0,
                4.0 * nf * nf / norm,
                (4.0 * nf * nf + 16.0 * nf * nf * (nf * nf - 1.0) / 3.0) / (norm * norm),
            ];
            for (bound, e) in b.iter().zip(exact) {
                assert!(
                    *bound >= e && *bound <= e * 16.0 / 15.0 * (1.0 + 1e-6),
                    "n {n}: {b:?} {exact:?}"
                );
            }
        }
    }

    #[test]
    fn odd_terms_carry_their_powers_of_t() {
        // m = 3, P = 1: h = (t/N)³, h′ = 3t²/N³, h″ = 6t/N³ over |t| ≤ T.
        let (norm, t) = (2.0, 1.5);
        let b = section_term_bounds(3, 0, norm, t, |_| [1.0, 0.0, 0.0]);
        let exact = [
            (t / norm).powi(3),
            3.0 * t * t / norm.powi(3),
            6.0 * t / norm.powi(3),
        ];
        for (bound, e) in b.iter().zip(exact) {
            assert!(
                *bound >= e && *bound <= e * 16.0 / 15.0 * (1.0 + 1e-6),
                "{b:?} {exact:?}"
            );
        }
    }

    fn q_con(spec: &str) -> crate::surface::q_con::QCon {
        crate::surface::q_con::QCon::new(&serde_json::from_str(spec).unwrap()).unwrap()
    }

    fn q_bfs(spec: &str) -> crate::surface::q_bfs::QBfs {
        crate::surface::q_bfs::QBfs::new(&serde_json::from_str(spec).unwrap()).unwrap()
    }

    fn q_2d(spec: &str) -> crate::surface::q_2d::Q2d {
        crate::surface::q_2d::Q2d::new(&serde_json::from_str(spec).unwrap()).unwrap()
    }

    /// Coefficients of every order up to `n`, alternating, of size `size`.
    fn many(n: usize, size: f64) -> String {
        let a: Vec<String> = (0..=n)
            .map(|i| format!("{:e}", size * if i % 2 == 0 { 1.0 } else { -0.7 }))
            .collect();
        a.join(",")
    }

    #[test]
    fn q_surface_bounds_hold_on_dense_sections() {
        use crate::surface::section_bounds::assert_bounds_hold;
        let surfaces: Vec<(Box<dyn crate::surface::Surface>, f64)> = vec![
            (
                Box::new(q_con(
                    r#"{"radius_mm":40,"conic":-2,"norm_radius_mm":1.5,"coefficients_mm":[0.002,0.001,-0.0005]}"#,
                )),
                3.0,
            ),
            (
                Box::new(q_con(&format!(
                    r#"{{"radius_mm":-25,"conic":0.5,"norm_radius_mm":4,"coefficients_mm":[{}]}}"#,
                    many(14, 2e-4)
                ))),
                4.0,
            ),
            (
                Box::new(q_bfs(
                    r#"{"radius_mm":-30,"norm_radius_mm":1.5,"coefficients_mm":[0.003,-0.001,0.0005]}"#,
                )),
                3.0,
            ),
            (
                Box::new(q_bfs(&format!(
                    r#"{{"radius_mm":12,"norm_radius_mm":5,"coefficients_mm":[{}]}}"#,
                    many(20, 1e-4)
                ))),
                5.0,
            ),
            (
                Box::new(q_2d(
                    r#"{"curvature_per_mm":0,"norm_radius_mm":1.5,"terms":[
                {"n":0,"m":0,"a_mm":0.002},{"n":0,"m":2,"a_mm":0.002,"b_mm":-0.001},
                {"n":1,"m":1,"a_mm":0.0008},{"n":0,"m":3,"b_mm":0.0006}]}"#,
                )),
                3.0,
            ),
            (
                Box::new(q_2d(
                    r#"{"radius_mm":-20,"norm_radius_mm":6,"terms":[
                {"n":4,"m":0,"a_mm":0.001},{"n":6,"m":5,"a_mm":0.0004,"b_mm":-0.0003},
                {"n":9,"m":2,"a_mm":-0.0002},{"n":3,"m":12,"b_mm":0.0005}]}"#,
                )),
                6.0,
            ),
        ];
        for (s, radius) in &surfaces {
            assert_bounds_hold(s.as_ref(), *radius, 48, 4000);
        }
    }

    #[test]
    fn q_surface_bounds_are_tight_where_one_term_dominates() {
        // On a plane (c = 0, no normal factor) the bounds are the term's own, reached along the
        // section at θ = 0 (cos mθ = 1) within the sampling's 1/15 (and the dense sampling's own
        // shortfall); the term and its negative have the same bounds, and the larger of their
        // upward curvatures is the largest |f″|.
        use crate::surface::section_bounds::assert_bounds_hold;
        type Build = fn(f64) -> Box<dyn crate::surface::Surface>;
        let families: [Build; 3] = [
            |a| {
                Box::new(q_con(&format!(
                    r#"{{"curvature_per_mm":0,"norm_radius_mm":2,"coefficients_mm":[0,0,0,{a}]}}"#
                )))
            },
            |a| {
                Box::new(q_bfs(&format!(
                    r#"{{"curvature_per_mm":0,"norm_radius_mm":2,"coefficients_mm":[0,0,{a}]}}"#
                )))
            },
            |a| {
                Box::new(q_2d(&format!(
                    r#"{{"curvature_per_mm":0,"norm_radius_mm":2,"terms":[{{"n":3,"m":4,"a_mm":{a}}}]}}"#
                )))
            },
        ];
        for build in families {
            let (up, down) = (build(0.001), build(-0.001));
            let (b, slope, curvature) = assert_bounds_hold(up.as_ref(), 2.0, 8, 20_000);
            let (_, _, curvature_down) = assert_bounds_hold(down.as_ref(), 2.0, 8, 20_000);
            let loose = 16.0 / 15.0 * 1.001;
            let largest = curvature.max(curvature_down);
            assert!(
                b.max_slope <= loose * slope,
                "{}: {b:?} {slope}",
                up.describe()
            );
            assert!(
                b.max_curvature <= loose * largest,
                "{}: {b:?} {largest}",
                up.describe()
            );
        }
    }

    #[test]
    fn the_normal_factor_is_bounded_at_the_rim() {
        // A = 1: (Ag)′ = g′, (Ag)″ = g″, both largest at the rim; against differences.
        let (c, t) = (0.05, 6.0);
        let g = |t: f64| 1.0 / (1.0 - c * c * t * t).sqrt();
        let (slope, curvature) = along_sphere_normal(c, t, [1.0, 0.0, 0.0]).unwrap();
        let h = 1e-3;
        let d1 = (g(t + h) - g(t - h)) / (2.0 * h);
        let d2 = (g(t + h) - 2.0 * g(t) + g(t - h)) / (h * h);
        assert!((slope - d1).abs() < 1e-7 * d1, "{slope} {d1}");
        assert!((curvature - d2).abs() < 1e-7 * d2, "{curvature} {d2}");
        assert!(along_sphere_normal(0.2, 5.0, [1.0, 0.0, 0.0]).is_none());
    }
}
