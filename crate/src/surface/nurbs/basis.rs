//! Knot vectors and B-spline basis functions with their derivatives: the span search and
//! `BasisFuns` of Piegl & Tiller, "The NURBS Book", 2nd ed., algorithms A2.1 and A2.2 (the
//! Cox–de Boor recursion, eq 2.5), and the derivative formula eq 2.7 that their A2.3 is built
//! on, written without allocation (fixed arrays of p + 1 ≤ 16 entries) so that a surface can
//! evaluate them from parallel code through `&self`.
//!
//! A degree-p B-spline with n basis functions has a knot vector `U = (u₀ … u_{n+p})`,
//! non-decreasing; its parameter domain is `[u_p, u_n]`, where the basis functions sum to one,
//! whether the vector is clamped (end knots repeated p + 1 times) or not. A knot of multiplicity
//! k strictly inside the domain leaves the curve `C^(p−k)`; this module accepts k ≤ p − 1 there,
//! so that every surface built on it has a continuous slope (a slope jump along a curved knot
//! line could not be reported to the planner as a kink).

use crate::field::{FieldError, finite};

/// The highest degree accepted in u and in v.
pub const MAX_DEGREE: usize = 15;

/// Row width of the fixed-size tables: p + 1 non-zero functions at most.
pub const WIDTH: usize = MAX_DEGREE + 1;

/// `ders[k][j]`: the k-th derivative (k = 0, 1, 2) of the j-th non-zero basis function
/// `N_{span−p+j, p}` at the parameter.
pub type BasisDers = [[f64; WIDTH]; 3];

/// A validated knot vector of a degree-p B-spline with `count` basis functions.
#[derive(Debug, Clone, PartialEq)]
pub struct KnotVector {
    degree: usize,
    count: usize,
    knots: Vec<f64>,
}

impl KnotVector {
    /// Checks `knots` for a degree-`degree` B-spline with `count` control points; errors name
    /// `field` (e.g. `knots_u`) and the offending index.
    pub fn new(
        field: &str,
        degree: usize,
        count: usize,
        knots: &[f64],
    ) -> Result<Self, FieldError> {
        if !(1..=MAX_DEGREE).contains(&degree) {
            return Err(FieldError::new(
                field,
                format!("degree {degree}"),
                format!("the degree must lie in [1, {MAX_DEGREE}]"),
            ));
        }
        let wanted = count + degree + 1;
        if knots.len() != wanted {
            return Err(FieldError::new(
                field,
                format!("{} knots", knots.len()),
                format!(
                    "a degree-{degree} direction with {count} control points needs \
                     {count} + {degree} + 1 = {wanted} knots"
                ),
            ));
        }
        for (i, &k) in knots.iter().enumerate() {
            finite(&format!("{field}[{i}]"), k)?;
            if i > 0 && k < knots[i - 1] {
                return Err(FieldError::new(
                    format!("{field}[{i}]"),
                    k,
                    format!(
                        "knots must not decrease: {field}[{}] = {}",
                        i - 1,
                        knots[i - 1]
                    ),
                ));
            }
        }
        let (lo, hi) = (knots[degree], knots[count]);
        if lo >= hi {
            return Err(FieldError::new(
                field,
                format!("[{lo}, {hi}]"),
                format!(
                    "the parameter domain [{field}[{degree}], {field}[{count}]] must not be empty"
                ),
            ));
        }
        check_multiplicities(field, degree, knots, lo, hi)?;
        Ok(Self {
            degree,
            count,
            knots: knots.to_vec(),
        })
    }

    /// Degree p.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Number of basis functions (control points along this direction).
    pub fn count(&self) -> usize {
        self.count
    }

    /// The knots, `count + degree + 1` of them.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The parameter domain `[u_p, u_n]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.count])
    }

    /// The distinct knots inside the domain, ends included, in increasing order: the ends of
    /// the non-empty spans.
    pub fn breaks(&self) -> Vec<f64> {
        let (lo, hi) = self.domain();
        let mut out: Vec<f64> = Vec::new();
        for &k in &self.knots[self.degree..=self.count] {
            if (lo..=hi).contains(&k) && out.last() != Some(&k) {
                out.push(k);
            }
        }
        out
    }

    /// The span index i (p ≤ i < n, `u_i < u_{i+1}`) with `u_i ≤ t < u_{i+1}`, or the last
    /// non-empty span at the domain's end (A2.1). `t` is clamped to the domain.
    pub fn span(&self, t: f64) -> usize {
        let (p, n) = (self.degree, self.count);
        let inner = &self.knots[p..n];
        let below = inner.partition_point(|&k| k <= t);
        let mut i = (p + below).saturating_sub(1).clamp(p, n - 1);
        while i > p && self.knots[i] >= self.knots[i + 1] {
            i -= 1;
        }
        i
    }

    /// The non-zero basis functions at `t` in span `span` and their derivatives up to `order`
    /// (≤ 2); derivatives above the degree are zero. The values of degrees p − 2, p − 1 and p
    /// come from one run of A2.2; the derivatives from eq 2.7 (the recursion A2.3 is built on),
    /// `N′_{i,d} = d·(N_{i,d−1}/(u_{i+d} − u_i) − N_{i+1,d−1}/(u_{i+d+1} − u_{i+1}))`, applied
    /// once for N′ and twice (to the N′ of degree p − 1) for N″.
    pub fn ders(&self, span: usize, t: f64, order: usize) -> BasisDers {
        let p = self.degree;
        let [lower2, lower1, values] = self.values(span, t);
        let mut ders = [[0.0; WIDTH]; 3];
        ders[0] = values;
        if order >= 1 {
            ders[1] = self.differentiate(span, p, &lower1);
        }
        if order >= 2 && p >= 2 {
            let d_lower1 = self.differentiate(span, p - 1, &lower2);
            ders[2] = self.differentiate(span, p, &d_lower1);
        }
        ders
    }

    /// A2.2: the non-zero basis functions of degrees p − 2, p − 1 and p at t (entry k of
    /// degree d is `N_{span−d+k, d}`); degrees below 0 are left zero.
    fn values(&self, span: usize, t: f64) -> [[f64; WIDTH]; 3] {
        let (p, u) = (self.degree, &self.knots);
        let mut out = [[0.0; WIDTH]; 3];
        let mut n = [0.0; WIDTH];
        let mut left = [0.0; WIDTH];
        let mut right = [0.0; WIDTH];
        n[0] = 1.0;
        if p >= 2 {
            out[0][0] = 1.0;
        }
        if p == 1 {
            out[1][0] = 1.0;
        }
        for j in 1..=p {
            left[j] = t - u[span + 1 - j];
            right[j] = u[span + j] - t;
            let mut saved = 0.0;
            for r in 0..j {
                let temp = n[r] / (right[r + 1] + left[j - r]);
                n[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            n[j] = saved;
            if j + 2 == p {
                out[0] = n;
            } else if j + 1 == p {
                out[1] = n;
            }
        }
        out[2] = n;
        out
    }

    /// Eq 2.7: the derivatives of the degree-d functions `N_{span−d+j, d}`, j = 0 … d, from
    /// `lower[k]`, the degree-(d − 1) functions `N_{span−d+1+k, d−1}` (or their derivatives);
    /// a term whose knot difference is zero is zero (its function vanishes).
    fn differentiate(&self, span: usize, d: usize, lower: &[f64; WIDTH]) -> [f64; WIDTH] {
        let u = &self.knots;
        let mut out = [0.0; WIDTH];
        for (j, o) in out.iter_mut().enumerate().take(d + 1) {
            let i = span + j - d;
            let ratio = |num: f64, den: f64| if den > 0.0 { num / den } else { 0.0 };
            let left = if j > 0 {
                ratio(lower[j - 1], u[i + d] - u[i])
            } else {
                0.0
            };
            let right = if j < d {
                ratio(lower[j], u[i + d + 1] - u[i + 1])
            } else {
                0.0
            };
            *o = d as f64 * (left - right);
        }
        out
    }
}

/// Multiplicity at most p + 1 anywhere, and at most p − 1 strictly inside the domain.
fn check_multiplicities(
    field: &str,
    degree: usize,
    knots: &[f64],
    lo: f64,
    hi: f64,
) -> Result<(), FieldError> {
    let mut start = 0;
    while start < knots.len() {
        let k = knots[start];
        let end = start + knots[start..].iter().take_while(|&&x| x == k).count();
        let m = end - start;
        let inside = k > lo && k < hi;
        let limit = if inside { degree - 1 } else { degree + 1 };
        if m > limit {
            let why = if inside {
                format!(
                    "appears {m} times inside the domain; at most p − 1 = {limit} keeps the \
                     slope continuous (a slope jump along a knot line cannot be planned)"
                )
            } else {
                format!("appears {m} times; at most p + 1 = {limit}")
            };
            return Err(FieldError::new(format!("{field}[{start}]"), k, why));
        }
        start = end;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binomial(n: usize, k: usize) -> f64 {
        (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
    }

    /// Bernstein polynomial `B_{j,p}(t)` on [0, 1] and its first two derivatives, from the
    /// closed form `C(p,j)·t^j·(1−t)^(p−j)` differentiated by hand.
    fn bernstein(p: usize, j: usize, t: f64) -> [f64; 3] {
        let c = binomial(p, j);
        let term = |a: i32, b: i32| {
            if a < 0 || b < 0 {
                0.0
            } else {
                t.powi(a) * (1.0 - t).powi(b)
            }
        };
        let (j, q) = (j as i32, (p - j) as i32);
        let (jf, qf) = (j as f64, q as f64);
        [
            c * term(j, q),
            c * (jf * term(j - 1, q) - qf * term(j, q - 1)),
            c * (jf * (jf - 1.0) * term(j - 2, q) - 2.0 * jf * qf * term(j - 1, q - 1)
                + qf * (qf - 1.0) * term(j, q - 2)),
        ]
    }

    #[test]
    #[allow(clippy::needless_range_loop)] // d[k][j] against b[k]: two indices.
    fn clamped_single_span_basis_is_bernstein() {
        for p in 1..=MAX_DEGREE {
            let mut knots = vec![0.0; p + 1];
            knots.extend(vec![1.0; p + 1]);
            let kv = KnotVector::new("k", p, p + 1, &knots).unwrap();
            for &t in &[0.0, 0.13, 0.5, 0.77, 1.0] {
                let span = kv.span(t);
                assert_eq!(span, p);
                let d = kv.ders(span, t, 2);
                for j in 0..=p {
                    let b = bernstein(p, j, t);
                    for k in 0..3 {
                        let scale = binomial(p, j) * (p * p) as f64;
                        assert!(
                            (d[k][j] - b[k]).abs() <= 1e-13 * scale.max(1.0),
                            "p {p} j {j} k {k} t {t}: {} vs {}",
                            d[k][j],
                            b[k]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn uniform_quadratic_matches_the_piecewise_closed_form() {
        // Uniform unclamped knots 0..6, degree 2, 4 functions: domain [2, 4]; on [2, 3) with
        // s = t − 2 the non-zero functions are (1−s)²/2, (−2s² + 2s + 1)/2, s²/2.
        let kv = KnotVector::new("k", 2, 4, &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]).unwrap();
        assert_eq!(kv.domain(), (2.0, 4.0));
        let t = 2.3;
        let s = t - 2.0;
        let span = kv.span(t);
        assert_eq!(span, 2);
        let d = kv.ders(span, t, 2);
        let want = [
            [
                (1.0 - s) * (1.0 - s) / 2.0,
                (-2.0 * s * s + 2.0 * s + 1.0) / 2.0,
                s * s / 2.0,
            ],
            [s - 1.0, 1.0 - 2.0 * s, s],
            [1.0, -2.0, 1.0],
        ];
        for k in 0..3 {
            for j in 0..3 {
                assert!((d[k][j] - want[k][j]).abs() < 1e-15, "{k} {j}");
            }
        }
    }

    #[test]
    fn spans_skip_repeated_knots_and_the_domain_end_uses_the_last_span() {
        let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 3.0, 3.0, 3.0, 3.0];
        let kv = KnotVector::new("k", 3, 7, &knots).unwrap();
        assert_eq!(kv.span(0.0), 3);
        assert_eq!(kv.span(0.999), 3);
        assert_eq!(kv.span(1.0), 4);
        assert_eq!(kv.span(2.0), 6);
        assert_eq!(kv.span(3.0), 6);
        assert_eq!(kv.span(-1.0), 3);
        assert_eq!(kv.breaks(), vec![0.0, 1.0, 2.0, 3.0]);
    }

    #[test]
    fn basis_sums_to_one_and_derivatives_match_differences() {
        let knots = [0.0, 0.0, 0.0, 0.0, 0.4, 1.1, 1.1, 2.0, 2.0, 2.0, 2.0];
        let kv = KnotVector::new("k", 3, 7, &knots).unwrap();
        let h = 1e-6;
        for i in 0..=40 {
            let t = 0.02 + 1.96 * i as f64 / 40.0;
            let span = kv.span(t);
            let d = kv.ders(span, t, 2);
            let sum: f64 = d[0].iter().sum();
            assert!((sum - 1.0).abs() < 1e-14, "{t}");
            // Compare in the same span (central differences stay inside it away from knots).
            if knots.iter().any(|&k| (k - t).abs() < 2.0 * h) {
                continue;
            }
            let p = kv.ders(span, t + h, 1);
            let m = kv.ders(span, t - h, 1);
            for j in 0..4 {
                let d1 = (p[0][j] - m[0][j]) / (2.0 * h);
                let d2 = (p[1][j] - m[1][j]) / (2.0 * h);
                assert!((d[1][j] - d1).abs() < 1e-8, "{t} {j}");
                assert!((d[2][j] - d2).abs() < 1e-7, "{t} {j}");
            }
        }
    }

    #[test]
    fn bad_knot_vectors_name_the_knot() {
        let e = KnotVector::new("knots_u", 2, 3, &[0.0, 0.0, 1.0, 1.0]).unwrap_err();
        assert_eq!(e.field, "knots_u");
        assert!(e.allowed.contains("3 + 2 + 1 = 6"), "{e}");
        let e = KnotVector::new("knots_u", 1, 2, &[0.0, 1.0, 0.5, 2.0]).unwrap_err();
        assert_eq!(e.field, "knots_u[2]");
        let e = KnotVector::new("knots_u", 1, 2, &[0.0, 1.0, 1.0, 2.0]).unwrap_err();
        assert_eq!(e.field, "knots_u");
        assert!(e.allowed.contains("empty"), "{e}");
        let e = KnotVector::new("knots_v", 2, 5, &[0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]);
        let e = e.unwrap_err();
        assert_eq!(e.field, "knots_v[3]");
        assert!(e.allowed.contains("slope"), "{e}");
        let e = KnotVector::new("k", 1, 3, &[0.0, 0.0, 0.0, 1.0, 2.0]).unwrap_err();
        assert!(e.allowed.contains("at most p + 1 = 2"), "{e}");
        let e = KnotVector::new("k", 1, 2, &[0.0, f64::NAN, 1.0, 1.0]).unwrap_err();
        assert_eq!(e.field, "k[1]");
    }
}
