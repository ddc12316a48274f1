//! Control nets of surfaces known in closed form, for the NURBS and STEP tests, built
//! independently of the library's evaluator by blossoming (Marsden's identity): a polynomial
//! f(u) of degree ≤ p equals `Σᵢ F(u_{i+1}, …, u_{i+p})·N_{i,p}(u)` on the domain of any knot
//! vector, F the blossom of f, and the blossom of `u^k` is `e_k(t₁ … t_p) / C(p, k)` with `e_k`
//! the k-th elementary symmetric polynomial. For a tensor product the blossoms multiply; a
//! rational surface `(X, Y, Z) = (A_x, A_y, A_z) / W` with polynomial numerators and denominator
//! gets weights `wᵢⱼ = blossom(W)` and points `blossom(A)/wᵢⱼ` (Piegl & Tiller eq 4.15 in
//! homogeneous form).
//!
//! The sphere cap is the inverse stereographic projection, which is rational of degree 2 in each
//! of (s, t): `(2Rs, 2Rt, 2R(s² + t²)) / (1 + s² + t²)` lies on the sphere of radius R centred at
//! (0, 0, R) (its squared distance from the centre is `R²·(1 + ρ²)²/(1 + ρ²)²`), and near
//! s = t = 0 it is the lower cap `z = R − √(R² − x² − y²)`, without a degenerate pole.

#![allow(dead_code)]

use spiralcam::surface::NurbsSpec;

/// A polynomial in (s, t): terms `(coefficient, power of s, power of t)`.
pub type Poly = Vec<(f64, usize, usize)>;

/// The product of two polynomials.
pub fn mul(a: &Poly, b: &Poly) -> Poly {
    let mut out = Vec::new();
    for &(ca, sa, ta) in a {
        for &(cb, sb, tb) in b {
            out.push((ca * cb, sa + sb, ta + tb));
        }
    }
    out
}

/// The sum of two polynomials.
pub fn add(a: &Poly, b: &Poly) -> Poly {
    a.iter().chain(b).copied().collect()
}

/// `c·a`.
pub fn scale(c: f64, a: &Poly) -> Poly {
    a.iter().map(|&(k, s, t)| (c * k, s, t)).collect()
}

/// The value of a polynomial at (s, t).
pub fn value(a: &Poly, s: f64, t: f64) -> f64 {
    a.iter()
        .map(|&(c, i, j)| c * s.powi(i as i32) * t.powi(j as i32))
        .sum()
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// `e_k(t₁ … t_p)` for k = 0 … p.
fn elementary(ts: &[f64]) -> Vec<f64> {
    let mut e = vec![0.0; ts.len() + 1];
    e[0] = 1.0;
    for (n, &t) in ts.iter().enumerate() {
        for k in (1..=n + 1).rev() {
            e[k] += e[k - 1] * t;
        }
    }
    e
}

/// The tensor blossom of `a` at the knots `us` (p of them) and `vs` (q of them).
pub fn blossom(a: &Poly, us: &[f64], vs: &[f64]) -> f64 {
    let (eu, ev) = (elementary(us), elementary(vs));
    let (p, q) = (us.len(), vs.len());
    a.iter()
        .map(|&(c, i, j)| {
            assert!(i <= p && j <= q, "degree too high for the net");
            c * eu[i] / binomial(p, i) * ev[j] / binomial(q, j)
        })
        .sum()
}

/// The net of the rational surface `(ax, ay, az) / w` of degrees (p, q) on the knot vectors.
pub fn rational_net(
    p: usize,
    q: usize,
    knots_u: &[f64],
    knots_v: &[f64],
    numerators: [&Poly; 3],
    w: &Poly,
) -> NurbsSpec {
    let (rows, cols) = (knots_u.len() - p - 1, knots_v.len() - q - 1);
    let mut control_points = Vec::with_capacity(rows);
    let mut weights = Vec::with_capacity(rows);
    for i in 0..rows {
        let (mut row, mut wrow) = (Vec::with_capacity(cols), Vec::with_capacity(cols));
        for j in 0..cols {
            let (us, vs) = (&knots_u[i + 1..=i + p], &knots_v[j + 1..=j + q]);
            let wij = blossom(w, us, vs);
            assert!(wij > 0.0, "weight {wij} at ({i}, {j})");
            row.push(numerators.map(|a| blossom(a, us, vs) / wij));
            wrow.push(wij);
        }
        control_points.push(row);
        weights.push(wrow);
    }
    NurbsSpec {
        degree_u: p as u32,
        degree_v: q as u32,
        knots_u: knots_u.to_vec(),
        knots_v: knots_v.to_vec(),
        control_points,
        weights: Some(weights),
        allow_uncovered: false,
    }
}

/// The polynomial surface `(x, y, z)` as a B-spline net (no weights).
pub fn polynomial_net(
    p: usize,
    q: usize,
    knots_u: &[f64],
    knots_v: &[f64],
    xyz: [&Poly; 3],
) -> NurbsSpec {
    let mut spec = rational_net(p, q, knots_u, knots_v, xyz, &vec![(1.0, 0, 0)]);
    spec.weights = None;
    spec
}

/// A clamped knot vector of degree p on [a, b] with the given interior knots.
pub fn clamped(p: usize, a: f64, b: f64, interior: &[f64]) -> Vec<f64> {
    let mut k = vec![a; p + 1];
    k.extend_from_slice(interior);
    k.extend(vec![b; p + 1]);
    k
}

/// A uniform unclamped knot vector of degree p whose domain [u_p, u_n] is [a, b] in `spans`.
pub fn uniform(p: usize, a: f64, b: f64, spans: usize) -> Vec<f64> {
    let h = (b - a) / spans as f64;
    (0..spans + 2 * p + 1)
        .map(|k| a + (k as f64 - p as f64) * h)
        .collect()
}

/// The sphere cap `z = R − √(R² − x² − y²)` over the parameter square [−a, a]² (see the
/// module docs), degrees (p, p) on `knots` in both directions.
pub fn sphere_cap(radius: f64, p: usize, knots: &[f64]) -> NurbsSpec {
    let two_r = 2.0 * radius;
    let ax: Poly = vec![(two_r, 1, 0)];
    let ay: Poly = vec![(two_r, 0, 1)];
    let az: Poly = vec![(two_r, 2, 0), (two_r, 0, 2)];
    let w: Poly = vec![(1.0, 0, 0), (1.0, 2, 0), (1.0, 0, 2)];
    rational_net(p, p, knots, knots, [&ax, &ay, &az], &w)
}

/// The closed-form sphere: sag, gradient and Hessian `[z, zx, zy, zxx, zxy, zyy]`.
pub fn sphere(radius: f64, x: f64, y: f64) -> [f64; 6] {
    let q = radius * radius - x * x - y * y;
    let w = q.sqrt();
    let w3 = q * w;
    [
        radius - w,
        x / w,
        y / w,
        (radius * radius - y * y) / w3,
        x * y / w3,
        (radius * radius - x * x) / w3,
    ]
}
