//! Inversion of a patch's projection onto XY: for a part point (x, y), the parameters (u, v)
//! with `S_x(u, v) = x`, `S_y(u, v) = y`.
//!
//! A coarse grid of (u, v) samples (every knot, and at least 48 steps across each direction) is
//! laid once, with the Jacobian `J = ∂(S_x, S_y)/∂(u, v)` at each sample, and bucketed by its XY
//! position. A query takes the sample nearest in XY, makes one Newton step from it with the
//! stored Jacobian, and then iterates Newton's method on the 2 × 2 system
//! `J·Δ = (x, y) − S_xy(u, v)` with backtracking (a step is halved until the residual
//! decreases) and clamping to the parameter domain, until the residual is below 1e-14 of the
//! face's size (the rounding floor of the evaluation is a few 1e-15 of it). A query that ends on
//! the domain's boundary with a larger residual lies outside the face. Should the nearest sample
//! fail, the four neighbouring grid cells' centres are tried too: no state is kept between
//! queries, so the surface stays `Send + Sync` and the result depends on (x, y) alone.
//!
//! The grid also tells whether the projection folds: `det J` must keep one sign, away from
//! zero, at every sample (and, checked at each query, at the solution).

use super::patch::{Derivs, Patch};
use crate::surface::cell_grid::CellGrid;

/// Residual at which Newton stops, relative to the face's size.
const FINE: f64 = 1e-14;
/// Residual still accepted where Newton stalls at rounding, relative to the face's size.
const ACCEPT: f64 = 1e-11;
/// `|det J|` below this fraction of the largest sampled one counts as degenerate.
const DEGENERATE: f64 = 1e-9;
/// Residual, relative to the face's size, below which the next Newton point is expected to be
/// the last (quadratic convergence) and is evaluated to second order at once.
const NEAR: f64 = 1e-6;
/// Newton iterations at most.
const MAX_ITER: usize = 60;
/// Step halvings at most.
const MAX_HALVINGS: usize = 40;
/// Grid steps across a direction, at least (every knot span gets as many as it needs).
const MIN_STEPS: usize = 48;

/// Parameters found and the patch's derivatives to second order there.
pub type Found = (f64, f64, Derivs);

/// Why a point has no parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Miss {
    /// Newton ended on the domain's boundary with residual `residual` mm.
    Uncovered {
        /// Distance in XY from the edge point where the search ended, mm.
        residual: f64,
    },
    /// Newton did not converge inside the domain.
    NoConvergence {
        /// Residual left, mm.
        residual: f64,
    },
    /// The projection folds or degenerates at the solution.
    Folded {
        /// `det ∂(x, y)/∂(u, v)` there, times the face's orientation.
        det: f64,
        /// Where, in the parameters.
        u: f64,
        /// Where, in the parameters.
        v: f64,
    },
}

impl Miss {
    /// The reason, for an `UndefinedError`.
    pub fn reason(&self) -> String {
        match self {
            Miss::Uncovered { residual } => format!(
                "the face does not cover this point (the search for (u, v) ends on the face's \
                 edge, {residual:.3e} mm away in XY)"
            ),
            Miss::NoConvergence { residual } => format!(
                "Newton's method found no (u, v) for this point (residual {residual:.3e} mm)"
            ),
            Miss::Folded { det, u, v } => format!(
                "the face's projection onto XY folds or degenerates at (u, v) = ({u}, {v}) \
                 (det ∂(x, y)/∂(u, v) = {det:e}), so the sag is not single valued"
            ),
        }
    }
}

/// One grid sample: where it lies and the inverse Jacobian there.
#[derive(Debug, Clone, Copy)]
struct Sample {
    x: f64,
    y: f64,
    u: f64,
    v: f64,
    /// `J⁻¹` row-major: `[u_x, u_y, v_x, v_y]`.
    inv: [f64; 4],
}

/// A fold found on the grid: the parameters and the signed determinant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fold {
    /// Where, in the parameters.
    pub u: f64,
    /// Where, in the parameters.
    pub v: f64,
    /// Where, in XY, mm.
    pub x: f64,
    /// Where, in XY, mm.
    pub y: f64,
    /// `det J` there.
    pub det: f64,
}

/// The inversion of a patch's XY projection.
#[derive(Clone)]
pub struct Inverse {
    samples: Vec<Sample>,
    /// Grid size: samples along u, along v (`samples[i·nv + j]`).
    nu: usize,
    nv: usize,
    /// Grid steps per knot span along u, along v.
    per_span_u: usize,
    per_span_v: usize,
    buckets: Buckets,
    /// +1 or −1: the sign of det J over the face.
    orientation: f64,
    /// |det J| below this is degenerate.
    det_floor: f64,
    /// Face size for the residual tolerances, mm.
    scale: f64,
    /// `[x_min, x_max, y_min, y_max]` of the samples, mm.
    extent: [f64; 4],
}

impl std::fmt::Debug for Inverse {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Inverse")
            .field("grid", &(self.nu, self.nv))
            .field("orientation", &self.orientation)
            .field("extent", &self.extent)
            .finish_non_exhaustive()
    }
}

impl Inverse {
    /// Lays the grid over `patch`; fails where det J changes sign or vanishes.
    pub fn new(patch: &Patch) -> Result<Self, Fold> {
        let (us, per_span_u) = steps(patch.knots_u().breaks());
        let (vs, per_span_v) = steps(patch.knots_v().breaks());
        let mut grid = Vec::with_capacity(us.len() * vs.len());
        for &u in &us {
            for &v in &vs {
                grid.push((u, v, patch.eval(u, v, 1)));
            }
        }
        let det_max = grid.iter().map(|g| det(&g.2).abs()).fold(0.0, f64::max);
        let orientation = if det(&grid[grid.len() / 2].2) < 0.0 {
            -1.0
        } else {
            1.0
        };
        let det_floor = DEGENERATE * det_max;
        let mut samples = Vec::with_capacity(grid.len());
        for &(u, v, d) in &grid {
            let dj = det(&d);
            if orientation * dj <= det_floor || dj.is_nan() {
                return Err(Fold {
                    u,
                    v,
                    x: d.s[0],
                    y: d.s[1],
                    det: dj,
                });
            }
            samples.push(Sample {
                x: d.s[0],
                y: d.s[1],
                u,
                v,
                inv: inverse(&d, dj),
            });
        }
        let extent = bounds(&samples);
        let scale = 1f64.max(extent.iter().fold(0.0, |m: f64, e| m.max(e.abs())));
        let buckets = Buckets::new(&samples, extent);
        Ok(Self {
            samples,
            nu: us.len(),
            nv: vs.len(),
            per_span_u,
            per_span_v,
            buckets,
            orientation,
            det_floor,
            scale,
            extent,
        })
    }

    /// `[x_min, x_max, y_min, y_max]` of the grid samples, mm.
    pub fn extent(&self) -> [f64; 4] {
        self.extent
    }

    /// The shortest XY length of a knot span along u or v, measured along the grid lines, mm.
    pub fn shortest_span(&self) -> f64 {
        let at = |i: usize, j: usize| {
            let s = &self.samples[i * self.nv + j];
            (s.x, s.y)
        };
        let step = |a: (f64, f64), b: (f64, f64)| (b.0 - a.0).hypot(b.1 - a.1);
        let mut shortest = f64::INFINITY;
        for j in 0..self.nv {
            for first in (0..self.nu - 1).step_by(self.per_span_u) {
                let length = (first..first + self.per_span_u)
                    .map(|i| step(at(i, j), at(i + 1, j)))
                    .sum();
                shortest = shortest.min(length);
            }
        }
        for i in 0..self.nu {
            for first in (0..self.nv - 1).step_by(self.per_span_v) {
                let length = (first..first + self.per_span_v)
                    .map(|j| step(at(i, j), at(i, j + 1)))
                    .sum();
                shortest = shortest.min(length);
            }
        }
        shortest
    }

    /// The parameters of (x, y), and the patch's derivatives to second order there.
    pub fn solve(&self, patch: &Patch, x: f64, y: f64) -> Result<Found, Miss> {
        let nearest = self.buckets.nearest(&self.samples, x, y);
        let mut miss = match self.start_at_sample(patch, nearest, x, y) {
            Ok(found) => return self.checked(found),
            Err(m) => m,
        };
        for start in self.neighbour_starts(nearest) {
            match self.newton(patch, start, x, y) {
                Ok(found) => return self.checked(found),
                Err(m) => miss = worse(miss, m),
            }
        }
        Err(miss)
    }

    /// Newton from a sample, after one step with its stored inverse Jacobian.
    fn start_at_sample(&self, patch: &Patch, k: usize, x: f64, y: f64) -> Result<Found, Miss> {
        let s = &self.samples[k];
        let (dx, dy) = (x - s.x, y - s.y);
        let u = s.u + s.inv[0] * dx + s.inv[1] * dy;
        let v = s.v + s.inv[2] * dx + s.inv[3] * dy;
        self.newton(patch, self.clamp(patch, u, v), x, y)
    }

    /// The solution, unless the projection folds there.
    fn checked(&self, (u, v, d): Found) -> Result<Found, Miss> {
        let dj = self.orientation * det(&d);
        if dj > self.det_floor {
            Ok((u, v, d))
        } else {
            Err(Miss::Folded { det: dj, u, v })
        }
    }

    /// The centres of the four grid cells around sample k.
    fn neighbour_starts(&self, k: usize) -> Vec<(f64, f64)> {
        let (i, j) = (k / self.nv, k % self.nv);
        let mut out = Vec::with_capacity(4);
        for (di, dj) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            let (Some(i0), Some(j0)) = ((i + di).checked_sub(1), (j + dj).checked_sub(1)) else {
                continue;
            };
            if i0 + 1 >= self.nu || j0 + 1 >= self.nv {
                continue;
            }
            let a = &self.samples[i0 * self.nv + j0];
            let b = &self.samples[(i0 + 1) * self.nv + j0 + 1];
            out.push((0.5 * (a.u + b.u), 0.5 * (a.v + b.v)));
        }
        out
    }

    /// Damped, clamped Newton from `start` (see the module docs).
    fn newton(&self, patch: &Patch, start: (f64, f64), x: f64, y: f64) -> Result<Found, Miss> {
        let (fine, accept) = (FINE * self.scale, ACCEPT * self.scale);
        let (mut u, mut v) = start;
        let mut d = patch.eval(u, v, 1);
        let mut res = residual(&d, x, y);
        let mut order = 1;
        for _ in 0..MAX_ITER {
            if res <= fine {
                break;
            }
            let dj = det(&d);
            if dj == 0.0 || !dj.is_finite() {
                break;
            }
            let inv = inverse(&d, dj);
            let (rx, ry) = (x - d.s[0], y - d.s[1]);
            let (du, dv) = (inv[0] * rx + inv[1] * ry, inv[2] * rx + inv[3] * ry);
            // Close to the solution the next point is likely the last: evaluate it in full.
            order = if res <= NEAR * self.scale { 2 } else { 1 };
            match self.backtrack(patch, (u, v), (du, dv), res, order, x, y) {
                Some((nu, nv, nd, nres)) => (u, v, d, res) = (nu, nv, nd, nres),
                None => break,
            }
        }
        if res <= accept {
            if order < 2 {
                d = patch.eval(u, v, 2);
            }
            Ok((u, v, d))
        } else if self.on_boundary(patch, u, v) {
            Err(Miss::Uncovered { residual: res })
        } else {
            Err(Miss::NoConvergence { residual: res })
        }
    }

    /// The first of the steps λ·Δ, λ = 1, ½, ¼, …, clamped to the domain, that lowers the
    /// residual below `res`.
    #[allow(clippy::too_many_arguments)]
    fn backtrack(
        &self,
        patch: &Patch,
        (u, v): (f64, f64),
        (du, dv): (f64, f64),
        res: f64,
        order: usize,
        x: f64,
        y: f64,
    ) -> Option<(f64, f64, Derivs, f64)> {
        let mut lambda = 1.0;
        for _ in 0..MAX_HALVINGS {
            let (nu, nv) = self.clamp(patch, u + lambda * du, v + lambda * dv);
            if (nu, nv) == (u, v) {
                return None;
            }
            let nd = patch.eval(nu, nv, order);
            let nres = residual(&nd, x, y);
            if nres < res {
                return Some((nu, nv, nd, nres));
            }
            lambda *= 0.5;
        }
        None
    }

    fn clamp(&self, patch: &Patch, u: f64, v: f64) -> (f64, f64) {
        let [a, b, c, d] = patch.domain();
        let u = if u.is_nan() { a } else { u.clamp(a, b) };
        let v = if v.is_nan() { c } else { v.clamp(c, d) };
        (u, v)
    }

    fn on_boundary(&self, patch: &Patch, u: f64, v: f64) -> bool {
        let [a, b, c, d] = patch.domain();
        u == a || u == b || v == c || v == d
    }
}

/// The sample parameters along one direction: every break, and each span cut into as many
/// equal steps as make at least `MIN_STEPS` in all; and the steps per span.
fn steps(breaks: Vec<f64>) -> (Vec<f64>, usize) {
    let spans = breaks.len() - 1;
    let per_span = MIN_STEPS.div_ceil(spans).max(1);
    let mut out = Vec::with_capacity(spans * per_span + 1);
    for w in breaks.windows(2) {
        for k in 0..per_span {
            out.push(w[0] + (w[1] - w[0]) * k as f64 / per_span as f64);
        }
    }
    out.push(breaks[spans]);
    (out, per_span)
}

/// The worse of two misses: an uncovered point stays uncovered; a fold found anywhere wins.
fn worse(a: Miss, b: Miss) -> Miss {
    match (a, b) {
        (Miss::Folded { .. }, _) => a,
        (_, Miss::Folded { .. }) => b,
        (Miss::Uncovered { .. }, _) => a,
        _ => b,
    }
}

fn det(d: &Derivs) -> f64 {
    d.su[0] * d.sv[1] - d.sv[0] * d.su[1]
}

/// `J⁻¹ = [[y_v, −x_v], [−y_u, x_u]] / det`, row-major.
fn inverse(d: &Derivs, det: f64) -> [f64; 4] {
    [d.sv[1] / det, -d.sv[0] / det, -d.su[1] / det, d.su[0] / det]
}

fn residual(d: &Derivs, x: f64, y: f64) -> f64 {
    let (dx, dy) = (d.s[0] - x, d.s[1] - y);
    (dx * dx + dy * dy).sqrt()
}

fn bounds(samples: &[Sample]) -> [f64; 4] {
    samples.iter().fold(
        [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, s| [b[0].min(s.x), b[1].max(s.x), b[2].min(s.y), b[3].max(s.y)],
    )
}

/// Samples bucketed on a uniform XY grid ([`CellGrid`]) of about one sample per cell, for the
/// nearest-sample query.
#[derive(Debug, Clone)]
struct Buckets {
    grid: CellGrid,
}

impl Buckets {
    fn new(samples: &[Sample], [x0, x1, y0, y1]: [f64; 4]) -> Self {
        let area = ((x1 - x0) * (y1 - y0)).max(f64::MIN_POSITIVE);
        let span = (x1 - x0).max(y1 - y0).max(f64::MIN_POSITIVE);
        let cell = (area / samples.len() as f64).sqrt().max(span / 1024.0);
        let nx = (((x1 - x0) / cell) as usize + 1).min(4096);
        let ny = (((y1 - y0) / cell) as usize + 1).min(4096);
        let mut b = Self {
            grid: CellGrid::new(x0, y0, cell, nx, ny),
        };
        let filed: Vec<(usize, u32)> = samples
            .iter()
            .enumerate()
            .map(|(k, s)| (b.cell_of(s.x, s.y), k as u32))
            .collect();
        b.grid.fill(&filed);
        b
    }

    /// The cell of (x, y), clamped to the grid (a point outside it takes the nearest cell).
    fn index(&self, x: f64, y: f64) -> (usize, usize) {
        let (fi, fj) = self.grid.cell_coordinates(x, y);
        let clamp = |t: f64, n: usize| {
            if t.is_nan() {
                0
            } else {
                t.floor().clamp(0.0, (n - 1) as f64) as usize
            }
        };
        (clamp(fi, self.grid.nx), clamp(fj, self.grid.ny))
    }

    fn cell_of(&self, x: f64, y: f64) -> usize {
        let (i, j) = self.index(x, y);
        j * self.grid.nx + i
    }

    /// The sample nearest to (x, y) in XY: rings of cells around the point's (clamped) cell,
    /// until every cell not yet searched lies farther than the best sample found.
    fn nearest(&self, samples: &[Sample], x: f64, y: f64) -> usize {
        let (ci, cj) = self.index(x, y);
        let g = &self.grid;
        let (mut best, mut best_d2) = (0, f64::INFINITY);
        for ring in 0..=g.nx.max(g.ny) {
            for (i, j) in ring_cells(ci, cj, ring, g.nx, g.ny) {
                let c = j * g.nx + i;
                for &k in g.items(c, c) {
                    let s = &samples[k as usize];
                    let d2 = (s.x - x).powi(2) + (s.y - y).powi(2);
                    if d2 < best_d2 {
                        (best, best_d2) = (k as usize, d2);
                    }
                }
            }
            let margin = self.margin(ci, cj, ring, x, y);
            if margin >= 0.0 && margin * margin >= best_d2 {
                break;
            }
        }
        best
    }

    /// The distance from (x, y) to the cells outside the square of rings 0..=ring around
    /// (ci, cj) (infinite once that square covers the grid; negative when the point lies
    /// outside the square).
    fn margin(&self, ci: usize, cj: usize, ring: usize, x: f64, y: f64) -> f64 {
        let g = &self.grid;
        let side = |n: usize, c: usize, origin: f64, t: f64| {
            let lo = if c <= ring {
                f64::INFINITY
            } else {
                t - (origin + (c - ring) as f64 * g.cell)
            };
            let hi = if c + ring + 1 >= n {
                f64::INFINITY
            } else {
                origin + (c + ring + 1) as f64 * g.cell - t
            };
            lo.min(hi)
        };
        side(g.nx, ci, g.x0, x).min(side(g.ny, cj, g.y0, y))
    }
}

/// The cells at Chebyshev distance `ring` from (ci, cj), inside the grid.
fn ring_cells(
    ci: usize,
    cj: usize,
    ring: usize,
    nx: usize,
    ny: usize,
) -> impl Iterator<Item = (usize, usize)> {
    let (ci, cj, r) = (ci as isize, cj as isize, ring as isize);
    (cj - r..=cj + r).flat_map(move |j| {
        let edge = j == cj - r || j == cj + r;
        // Whole rows at the top and bottom of the ring, the two ends elsewhere.
        let step = if edge || r == 0 { 1 } else { (2 * r) as usize };
        (ci - r..=ci + r).step_by(step).filter_map(move |i| {
            (i >= 0 && j >= 0 && (i as usize) < nx && (j as usize) < ny)
                .then_some((i as usize, j as usize))
        })
    })
}
