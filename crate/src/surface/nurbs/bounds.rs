//! Bounds on a NURBS height field's slope and curvature over a disc, from its control net:
//! what the concave shortcut of the one-way compensation needs
//! ([`crate::surface::SectionBounds`]), for every line through the disc.
//!
//! **Pieces.** Each knot cell meeting the disc is cut into pieces about 1/24 of the disc's
//! radius across, and each piece's Bézier net is found by blossoming: the i-th Bézier point of
//! the parameter interval [a, b] of a degree-p span is the blossom `P(a, …, a, b, …, b)` (p − i
//! a's), evaluated by de Boor's algorithm with one argument a level (Piegl & Tiller, "The NURBS
//! Book", section 5.2; Ramshaw's blossoming), along u for every column, then along v.
//!
//! **Derivative nets.** The derivative of a Bézier segment of degree p on [a, b] is one of
//! degree p − 1 with points `p·(Pᵢ₊₁ − Pᵢ)/(b − a)` (eq 3.4 with the segment's knots; twice
//! for the second derivative, along u or v or both for the tensor product, eqs 3.7–3.8); the
//! Bernstein polynomials are non-negative and sum to one, so over the piece a derivative lies
//! in the hull of its net. Applied to the homogeneous net `(w·x, w·y, w·z, w)` this bounds
//! `A^(k,l)` and `w^(k,l)`, and the piece's points bound `S` (positive weights keep the convex
//! hull).
//!
//! **Height field.** The rational derivatives follow from the homogeneous ones by A4.4
//! (`S_u = (A_u − w_u·S)/w`, …: `patch.rs`) and the height field's gradient and Hessian from
//! those by the chain rule of `height.rs` (`∇z = J⁻ᵀ·∇_uv Z`, `H = J⁻ᵀ·M·J⁻¹`), all in interval
//! arithmetic with outward rounding (`interval.rs`), the blossoms included. The slope bound is
//! `|∇z| ≤ √(max z_x² + max z_y²)`; the curvature of any section lies between the Hessian's
//! eigenvalues, `(h_xx + h_yy)/2 ± √(((h_xx − h_yy)/2)² + h_xy²)`, bounded from the entries'
//! intervals. The intervals lose the correlation between the entries, by about the piece's size
//! times the next derivative: hence the pieces (on the whole cells of the sphere cap of the
//! tests the bounds were 2–3 times the extremes). A piece where `det J` may vanish gives no
//! bounds, and the paths are then searched in full, as before. The face is C¹ (interior knots
//! repeat at most p − 1 times): no kinks.

use super::basis::KnotVector;
use super::interval::Interval;
use super::patch::Patch;
use crate::surface::SectionBounds;

/// The deepest halving of a knot cell (into 4^12 pieces at most).
const MAX_DEPTH: u32 = 12;

/// The most pieces meeting the disc that the bounds examine; beyond, none are given (the
/// paths are then searched in full).
pub const MAX_PIECES: usize = 100_000;

/// A piece is fine enough when its gradient's entries vary by at most this plus
/// [`SLOPE_SPREAD_RELATIVE`] times the slope bound…
const SLOPE_SPREAD: f64 = 0.01;
/// … (see [`SLOPE_SPREAD`]).
const SLOPE_SPREAD_RELATIVE: f64 = 0.02;
/// … and its Hessian's entries by at most this, 1/mm, plus [`CURVATURE_SPREAD_RELATIVE`] times
/// the curvature bound's size.
const CURVATURE_SPREAD: f64 = 0.01;
/// … (see [`CURVATURE_SPREAD`]).
const CURVATURE_SPREAD_RELATIVE: f64 = 0.05;

/// The homogeneous coordinates `(w·x, w·y, w·z, w)` of a net point, or their bounds.
type Homogeneous = [Interval; 4];

/// Bounds over the disc of radius `radius_mm` about the axis on every line: the gradient's size
/// and the Hessian's eigenvalues (module docs); `None` where a piece meeting the disc cannot be
/// bounded, where none meets it, or where more than [`MAX_PIECES`] would be needed.
pub fn disc_bounds(patch: &Patch, radius_mm: f64) -> Option<SectionBounds> {
    let (ku, kv) = (patch.knots_u(), patch.knots_v());
    let mut found = Found {
        radius: radius_mm.abs(),
        bounds: None,
        pieces: 0,
    };
    let (u, v) = (ku.knots(), kv.knots());
    for s in spans(ku) {
        for t in spans(kv) {
            let (us, vs) = ([u[s], u[s + 1]], [v[t], v[t + 1]]);
            let bezier = Net::of_cell(patch, s, t)
                .bezier(false, ku, s, us)
                .bezier(true, kv, t, vs);
            found.refine(bezier, [us[1] - us[0], vs[1] - vs[0]], 0)?;
        }
    }
    // The sum with a flat section adds the margins every bound carries.
    SectionBounds::FLAT.and(found.bounds?)
}

/// The bounds found so far.
struct Found {
    radius: f64,
    bounds: Option<SectionBounds>,
    pieces: usize,
}

impl Found {
    /// Adds the bounds of the Bézier piece `net`, of parameter widths `widths`, halved in both
    /// directions until they are fine enough or [`MAX_DEPTH`] is reached; `None` where they
    /// cannot be had.
    fn refine(&mut self, net: Net, widths: [f64; 2], depth: u32) -> Option<()> {
        let hull = net.cartesian()?;
        if !meets_disc(&hull, self.radius) {
            return Some(());
        }
        self.pieces += 1;
        if self.pieces > MAX_PIECES {
            return None;
        }
        match net.graph_bounds(hull, widths) {
            Some(g) if g.fine_enough() || depth == MAX_DEPTH => {
                self.add(g.bounds);
                Some(())
            }
            None if depth == MAX_DEPTH => None,
            _ => {
                let half = [0.5 * widths[0], 0.5 * widths[1]];
                let (low, high) = net.halves(false);
                for strip in [low, high] {
                    let (a, b) = strip.halves(true);
                    self.refine(a, half, depth + 1)?;
                    self.refine(b, half, depth + 1)?;
                }
                Some(())
            }
        }
    }

    fn add(&mut self, piece: SectionBounds) {
        self.bounds = Some(self.bounds.map_or(piece, |b| b.or(piece)));
    }
}

/// A piece's bounds and how much its gradient's and Hessian's entries vary over it.
struct PieceBounds {
    bounds: SectionBounds,
    slope_spread: f64,
    curvature_spread: f64,
}

impl PieceBounds {
    /// Whether the piece is small enough for its bounds to be near the extremes (the intervals'
    /// loss grows with the piece's size).
    fn fine_enough(&self) -> bool {
        let b = &self.bounds;
        let curvature = b.max_curvature.abs().max(b.min_curvature.abs());
        self.slope_spread <= SLOPE_SPREAD + SLOPE_SPREAD_RELATIVE * b.max_slope
            && self.curvature_spread <= CURVATURE_SPREAD + CURVATURE_SPREAD_RELATIVE * curvature
    }
}

/// The non-empty knot spans `[u_s, u_{s+1})` of the domain, by index s.
fn spans(k: &KnotVector) -> impl Iterator<Item = usize> + '_ {
    let knots = k.knots();
    (k.degree()..k.count()).filter(move |&s| knots[s] < knots[s + 1])
}

/// Whether the box of the x and y bounds meets the disc.
fn meets_disc(s: &[Interval; 3], radius: f64) -> bool {
    let near = |i: Interval| 0f64.clamp(i.lo, i.hi);
    near(s[0]).hypot(near(s[1])) <= radius
}

/// A net of homogeneous points, `rows × cols`, row-major (rows along u).
struct Net {
    rows: usize,
    cols: usize,
    at: Vec<Homogeneous>,
}

impl Net {
    /// The (p + 1) × (q + 1) points of the patch whose basis functions are not zero on the cell
    /// of u-span `s` and v-span `t`.
    fn of_cell(patch: &Patch, s: usize, t: usize) -> Self {
        let (p, q) = (patch.knots_u().degree(), patch.knots_v().degree());
        let cols = patch.knots_v().count();
        let pw = patch.homogeneous_net();
        let at = (s - p..=s)
            .flat_map(|i| (t - q..=t).map(move |j| pw[i * cols + j].map(Interval::point)))
            .collect();
        Self {
            rows: p + 1,
            cols: q + 1,
            at,
        }
    }

    /// The point at row `a`, column `b`.
    fn get(&self, a: usize, b: usize) -> Homogeneous {
        self.at[a * self.cols + b]
    }

    /// The Bézier nets of the two halves of this Bézier net along u (`along_v` false) or v, by
    /// de Casteljau's algorithm at ½ ("The NURBS Book", A1.5; each level the mean of
    /// neighbours): the left half's points are the first of each level, the right half's the
    /// last, in reverse.
    fn halves(&self, along_v: bool) -> (Self, Self) {
        let (lines, len) = if along_v {
            (self.rows, self.cols)
        } else {
            (self.cols, self.rows)
        };
        let index = |l: usize, k: usize| {
            if along_v {
                l * self.cols + k
            } else {
                k * self.cols + l
            }
        };
        let (mut left, mut right) = (self.at.clone(), self.at.clone());
        for l in 0..lines {
            let mut level: Vec<Homogeneous> = (0..len).map(|k| self.at[index(l, k)]).collect();
            for r in 0..len {
                left[index(l, r)] = level[0];
                right[index(l, len - 1 - r)] = level[len - 1 - r];
                for k in 0..len - 1 - r {
                    level[k] = [0, 1, 2, 3].map(|c| level[k][c].add(level[k + 1][c]).scale(0.5));
                }
            }
        }
        let net = |at| Self { at, ..*self };
        (net(left), net(right))
    }

    /// The Bézier net over `[lo, hi]` ⊂ span `span` along u (`along_v` false) or v of this
    /// B-spline cell net, on `knots`: each line of points along that direction replaced by the
    /// blossoms `P(lo^(p−i), hi^i)`, i = 0…p (module docs).
    fn bezier(&self, along_v: bool, knots: &KnotVector, span: usize, [lo, hi]: [f64; 2]) -> Self {
        let p = knots.degree();
        let lines = if along_v { self.rows } else { self.cols };
        let mut out = vec![[Interval::point(0.0); 4]; self.at.len()];
        for l in 0..lines {
            let line: Vec<Homogeneous> = (0..=p)
                .map(|k| {
                    if along_v {
                        self.get(l, k)
                    } else {
                        self.get(k, l)
                    }
                })
                .collect();
            for i in 0..=p {
                let args: Vec<f64> = (0..p).map(|r| if r < p - i { lo } else { hi }).collect();
                let point = blossom(&line, knots.knots(), span, &args);
                let (a, b) = if along_v { (l, i) } else { (i, l) };
                out[a * self.cols + b] = point;
            }
        }
        Self { at: out, ..*self }
    }

    /// Bounds of x, y and z over the net's patch: the hull of the points themselves; `None` if a
    /// weight may not be positive.
    fn cartesian(&self) -> Option<[Interval; 3]> {
        let mut out: Option<[Interval; 3]> = None;
        for h in &self.at {
            let c = [0, 1, 2].map(|c| h[c].div(h[3]));
            let c = [c[0]?, c[1]?, c[2]?];
            out = Some(match out {
                None => c,
                Some(o) => [0, 1, 2].map(|k| o[k].hull(c[k])),
            });
        }
        out
    }

    /// The hull of the points; zero for an empty net (a derivative above the degree).
    fn hull(&self) -> Homogeneous {
        let zero = [Interval::point(0.0); 4];
        let mut it = self.at.iter();
        let Some(first) = it.next() else {
            return zero;
        };
        it.fold(*first, |acc, h| [0, 1, 2, 3].map(|c| acc[c].hull(h[c])))
    }

    /// The Bézier net of one more derivative along u (`along_v` false) or v, this net being of
    /// degree `degree` along it over a parameter interval `width` long:
    /// `degree·(Pᵢ₊₁ − Pᵢ)/width`.
    fn derivative(&self, along_v: bool, degree: usize, width: f64) -> Self {
        let (rows, cols) = if along_v {
            (self.rows, self.cols.saturating_sub(1))
        } else {
            (self.rows.saturating_sub(1), self.cols)
        };
        let factor = Interval::point(degree as f64)
            .div(Interval::point(width))
            .unwrap_or(Interval::point(0.0));
        let mut at = Vec::with_capacity(rows * cols);
        for a in 0..rows {
            for b in 0..cols {
                let (here, next) = if along_v {
                    (self.get(a, b), self.get(a, b + 1))
                } else {
                    (self.get(a, b), self.get(a + 1, b))
                };
                at.push([0, 1, 2, 3].map(|c| next[c].sub(here[c]).mul(factor)));
            }
        }
        Self { rows, cols, at }
    }

    /// The height field's bounds over this Bézier piece (module docs), its parameter widths
    /// `[u, v]`, its points' Cartesian hull `s`; `None` where `det J` or a weight may vanish.
    fn graph_bounds(&self, s: [Interval; 3], [du, dv]: [f64; 2]) -> Option<PieceBounds> {
        // Moved to the piece's centre c (S − c has the derivatives of S): A4.4's products of a
        // weight's derivative with S are then of the piece's size, not of its distance from
        // the origin, and shrink with it.
        let c = s.map(|i| Interval::point(0.5 * (i.lo + i.hi)));
        let s = [0, 1, 2].map(|k| s[k].sub(c[k]));
        let centred = Self {
            at: (self.at.iter())
                .map(|h| {
                    [
                        h[0].sub(h[3].mul(c[0])),
                        h[1].sub(h[3].mul(c[1])),
                        h[2].sub(h[3].mul(c[2])),
                        h[3],
                    ]
                })
                .collect(),
            ..*self
        };
        let (p, q) = (self.rows - 1, self.cols - 1);
        let nu = centred.derivative(false, p, du);
        let nv = centred.derivative(true, q, dv);
        let nuu = nu.derivative(false, p.saturating_sub(1), du);
        let nvv = nv.derivative(true, q.saturating_sub(1), dv);
        let nuv = nu.derivative(true, q, dv);
        let (a, au, av) = (centred.hull(), nu.hull(), nv.hull());
        let (auu, auv, avv) = (nuu.hull(), nuv.hull(), nvv.hull());
        let w = a[3];
        // A4.4 component by component.
        let rational = |f: &dyn Fn(usize) -> Interval| -> Option<[Interval; 3]> {
            let c = [0, 1, 2].map(|c| f(c).div(w));
            Some([c[0]?, c[1]?, c[2]?])
        };
        let su = rational(&|c| au[c].sub(au[3].mul(s[c])))?;
        let sv = rational(&|c| av[c].sub(av[3].mul(s[c])))?;
        let suu = rational(&|c| {
            auu[c]
                .sub(au[3].mul(su[c]).scale(2.0))
                .sub(auu[3].mul(s[c]))
        })?;
        let svv = rational(&|c| {
            avv[c]
                .sub(av[3].mul(sv[c]).scale(2.0))
                .sub(avv[3].mul(s[c]))
        })?;
        let suv = rational(&|c| {
            auv[c]
                .sub(au[3].mul(sv[c]))
                .sub(av[3].mul(su[c]))
                .sub(auv[3].mul(s[c]))
        })?;
        graph([su, sv, suu, suv, svv])
    }
}

/// The blossom `P(args)` of the degree-p B-spline segment on span `span` of `knots` with the
/// p + 1 points `line` (those of basis functions not zero there), by de Boor's algorithm with
/// argument `args[r − 1]` at level r: `d_j ← (1 − α)·d_{j−1} + α·d_j`,
/// `α = (t_r − u_i)/(u_{i+p+1−r} − u_i)` for i = span − p + j (A2.2's triangle with its
/// arguments apart; the denominators are positive on a non-empty span).
fn blossom(line: &[Homogeneous], knots: &[f64], span: usize, args: &[f64]) -> Homogeneous {
    let p = line.len() - 1;
    let mut d = line.to_vec();
    for (r, &t) in (1..=p).zip(args) {
        for j in (r..=p).rev() {
            let lo = Interval::point(knots[span + j - p]);
            let hi = Interval::point(knots[span + j + 1 - r]);
            let alpha = Interval::point(t)
                .sub(lo)
                .div(hi.sub(lo))
                .unwrap_or(Interval::point(0.0));
            let beta = Interval::point(1.0).sub(alpha);
            d[j] = [0, 1, 2, 3].map(|c| beta.mul(d[j - 1][c]).add(alpha.mul(d[j][c])));
        }
    }
    d[p]
}

/// The height field's slope and curvature bounds from bounds of `[S_u, S_v, S_uu, S_uv, S_vv]`
/// (`height.rs` in interval arithmetic); `None` where `det J` may vanish.
fn graph([su, sv, suu, suv, svv]: [[Interval; 3]; 5]) -> Option<PieceBounds> {
    let (xu, xv, yu, yv) = (su[0], sv[0], su[1], sv[1]);
    let det = xu.mul(yv).sub(xv.mul(yu));
    // J⁻¹ = [[u_x, u_y], [v_x, v_y]].
    let ux = yv.div(det)?;
    let uy = xv.div(det)?.scale(-1.0);
    let vx = yu.div(det)?.scale(-1.0);
    let vy = xu.div(det)?;
    let zx = su[2].mul(ux).add(sv[2].mul(vx));
    let zy = su[2].mul(uy).add(sv[2].mul(vy));
    let m = |h: [Interval; 3]| h[2].sub(zx.mul(h[0])).sub(zy.mul(h[1]));
    let (muu, muv, mvv) = (m(suu), m(suv), m(svv));
    // aᵀ·M·b for columns a, b of J⁻¹; the squares where a = b.
    let diagonal = |a: (Interval, Interval)| {
        a.0.square()
            .mul(muu)
            .add(a.0.mul(a.1).mul(muv).scale(2.0))
            .add(a.1.square().mul(mvv))
    };
    let (cx, cy) = ((ux, vx), (uy, vy));
    let hxx = diagonal(cx);
    let hyy = diagonal(cy);
    let hxy =
        cx.0.mul(muu.mul(cy.0).add(muv.mul(cy.1)))
            .add(cx.1.mul(muv.mul(cy.0).add(mvv.mul(cy.1))));
    let mean = hxx.add(hyy).scale(0.5);
    let half_gap = hxx.sub(hyy).scale(0.5).magnitude();
    let spread = half_gap.hypot(hxy.magnitude()) * (1.0 + 4.0 * f64::EPSILON);
    let bounds = SectionBounds {
        max_slope: zx.magnitude().hypot(zy.magnitude()) * (1.0 + 4.0 * f64::EPSILON),
        max_curvature: mean.hi + spread,
        min_curvature: mean.lo - spread,
        has_ridges: false,
        has_valleys: false,
    };
    let width = |i: Interval| i.hi - i.lo;
    let piece = PieceBounds {
        bounds,
        slope_spread: width(zx).max(width(zy)),
        curvature_spread: width(hxx).max(width(hxy)).max(width(hyy)),
    };
    [bounds.max_slope, bounds.max_curvature, bounds.min_curvature]
        .iter()
        .all(|v| v.is_finite())
        .then_some(piece)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A biquadratic-by-cubic rational patch with uneven weights and interior knots.
    fn patch() -> Patch {
        let u = KnotVector::new("u", 2, 5, &[0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.0, 1.0]).unwrap();
        let v = KnotVector::new("v", 3, 5, &[0.0, 0.0, 0.0, 0.0, 1.5, 2.0, 2.0, 2.0, 2.0]).unwrap();
        super::super::patch::sample_patch(u, v)
    }

    /// The point of the Bézier net at (a, b) ∈ [0, 1]², by Bernstein sums of the nets' centres.
    fn evaluate(net: &Net, a: f64, b: f64) -> [f64; 3] {
        let bernstein = |n: usize, i: usize, t: f64| {
            let choose = (0..i).fold(1.0, |c, k| c * (n - k) as f64 / (k + 1) as f64);
            choose * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32)
        };
        let mut h = [0.0; 4];
        for r in 0..net.rows {
            for c in 0..net.cols {
                let k = bernstein(net.rows - 1, r, a) * bernstein(net.cols - 1, c, b);
                for (m, x) in h.iter_mut().enumerate() {
                    let i = net.get(r, c)[m];
                    *x += k * 0.5 * (i.lo + i.hi);
                }
            }
        }
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    #[test]
    fn bezier_pieces_and_their_halves_are_the_patch() {
        // The blossomed net of a piece of each cell, and the de Casteljau halves of it, against
        // the patch evaluated by A3.6/A4.4 at the same parameters.
        let patch = patch();
        let (ku, kv) = (patch.knots_u(), patch.knots_v());
        for s in spans(ku) {
            for t in spans(kv) {
                let (a, b) = (ku.knots()[s], ku.knots()[s + 1]);
                let (c, d) = (kv.knots()[t], kv.knots()[t + 1]);
                let u = [a + 0.1 * (b - a), a + 0.8 * (b - a)];
                let v = [c + 0.3 * (d - c), d];
                let net = Net::of_cell(&patch, s, t)
                    .bezier(false, ku, s, u)
                    .bezier(true, kv, t, v);
                let (low, _) = net.halves(false);
                let (_, quarter) = low.halves(true);
                for (x, y) in [(0.0, 0.0), (0.3, 0.9), (1.0, 0.5), (0.7, 1.0)] {
                    let at = |fx: f64, fy: f64| {
                        let p = u[0] + fx * (u[1] - u[0]);
                        patch.eval(p, v[0] + fy * (v[1] - v[0]), 0).s
                    };
                    let pairs = [
                        (evaluate(&net, x, y), at(x, y)),
                        (evaluate(&quarter, x, y), at(0.5 * x, 0.5 + 0.5 * y)),
                    ];
                    for (got, want) in pairs {
                        for k in 0..3 {
                            assert!((got[k] - want[k]).abs() < 1e-13, "{got:?} {want:?}");
                        }
                    }
                }
            }
        }
    }
}
