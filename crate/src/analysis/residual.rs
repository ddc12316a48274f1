//! The residual of a registration (measured − design, positive where material is left) as
//! figures and as a grid over the part, the grid the corrected job is written on (issue 15).
//!
//! **Figures.** PV (largest − smallest), RMS about the mean, and the number of points, over the
//! measured points as they are: nothing is smoothed before the figures.
//!
//! **Grid.** A square of `n × n` nodes (n odd, [`MIN_GRID_SIDE`] … [`MAX_GRID_SIDE`]) centred on the spindle
//! axis, spacing h, covering the disc the tool passes (the part radius and a margin,
//! [`GridLayout::covering`]); nodes farther than two spacings outside that disc are not kept, so
//! every cell that meets the disc has its four corners. The spacing follows the data (the grid
//! spacing of a map, `√(area/points)` of a cloud), never finer than the part's diameter / 256
//! nor coarser than its diameter / 32, so a dense map is averaged down and a coarse one is not
//! invented.
//!
//! **Node values where the data reach** (a local polynomial regression, W. S. Cleveland,
//! "Robust locally weighted regression and smoothing scatterplots", JASA 74, 1979, with the
//! biweight kernel and degree 2): at each node the quadratic
//! `a + b·u + c·v + d·u² + e·uv + f·v²` (u, v the offsets from the node over the window radius)
//! is fitted by weighted least squares to the residual points within the window radius
//! `ρ_f = max(1.5·h, 2.5·data spacing)`, weights `(1 − (r/ρ_f)²)²`, and the node takes a. A node
//! is *measured* when at least 12 points fall in its window, their weighted centroid lies within
//! ρ_f/2 of it (it is surrounded by data, not extrapolated from one side) and the fit is well
//! conditioned; every other node is filled by the extension ([`super::extension`]). The fit
//! reproduces a quadratic exactly, so a smooth residual is sampled with an error of order
//! `ρ_f³·|e‴|`; noise is averaged over the window.

use super::normal_equations::NormalEquations;
use crate::parallel::fill_chunks;
use serde::Serialize;

/// The most nodes along a side of the residual grid (a spacing of the part's diameter/256 and
/// the margin).
pub const MAX_GRID_SIDE: usize = 271;
/// The fewest nodes along a side.
pub const MIN_GRID_SIDE: usize = 33;
/// The fewest points in a node's window for it to count as measured.
pub const MIN_WINDOW_POINTS: usize = 12;

/// PV, RMS and count of residual values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ResidualFigures {
    /// Peak to valley, µm.
    pub pv_um: f64,
    /// RMS about the mean, µm.
    pub rms_um: f64,
    /// Mean, µm.
    pub mean_um: f64,
    /// Values counted.
    pub points: usize,
}

impl ResidualFigures {
    /// The figures of the values `e` (mm); zeros for none.
    pub fn of(e: impl Iterator<Item = f64>) -> Self {
        let (mut n, mut lo, mut hi, mut sum) = (0usize, f64::INFINITY, f64::NEG_INFINITY, 0.0);
        let mut values = Vec::new();
        for v in e {
            n += 1;
            lo = lo.min(v);
            hi = hi.max(v);
            sum += v;
            values.push(v);
        }
        if n == 0 {
            return Self {
                pv_um: 0.0,
                rms_um: 0.0,
                mean_um: 0.0,
                points: 0,
            };
        }
        let mean = sum / n as f64;
        let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n as f64;
        Self {
            pv_um: (hi - lo) * 1e3,
            rms_um: var.sqrt() * 1e3,
            mean_um: mean * 1e3,
            points: n,
        }
    }
}

/// The bounding box `[x_min, y_min, x_max, y_max]` of the points, mm (zeros for none).
pub fn bounds(points: &[[f64; 3]]) -> [f64; 4] {
    if points.is_empty() {
        return [0.0; 4];
    }
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for p in points {
        b = [
            b[0].min(p[0]),
            b[1].min(p[1]),
            b[2].max(p[0]),
            b[3].max(p[1]),
        ];
    }
    b
}

/// Where the grid's nodes lie: `x_i = y_i = −half + i·h`, i = 0 … n − 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GridLayout {
    /// Nodes along each side (odd).
    pub n: usize,
    /// Spacing h, mm.
    pub step_mm: f64,
    /// Radius of the disc the grid must cover, mm.
    pub cover_radius_mm: f64,
}

impl GridLayout {
    /// The grid for a part of radius `part_radius_mm` measured with points `data_spacing_mm`
    /// apart: spacing the data's, between the part's diameter/256 and its diameter/32; the disc
    /// covered is the part and 2 % of its radius and two spacings more.
    pub fn covering(part_radius_mm: f64, data_spacing_mm: f64) -> Self {
        let target = data_spacing_mm.max(2.0 * part_radius_mm / 256.0);
        let target = target.min(2.0 * part_radius_mm / 32.0);
        // n odd with the cover disc inside ±half = (n − 1)·h/2, h the target spacing or a little
        // less: n from the target, then h from n.
        let cover = |h: f64| Self::with_nodes(part_radius_mm, 0, h).cover_radius_mm;
        let mut n = (2.0 * cover(target) / target).ceil() as usize + 1;
        n = n.clamp(MIN_GRID_SIDE, MAX_GRID_SIDE) | 1;
        // With h = 2·cover(h)/(n − 1): h·(n − 1)/2 = 1.02 R + 2h.
        let h = 1.02 * part_radius_mm / ((n - 1) as f64 / 2.0 - 2.0);
        Self::with_nodes(part_radius_mm, n, h)
    }

    /// The grid of `n` nodes a side `step_mm` apart over a part of radius `part_radius_mm`
    /// (the layout of a grid already written, [`GridLayout::covering`]'s margin).
    pub fn with_nodes(part_radius_mm: f64, n: usize, step_mm: f64) -> Self {
        Self {
            n,
            step_mm,
            cover_radius_mm: 1.02 * part_radius_mm + 2.0 * step_mm,
        }
    }

    /// Half the side, mm: the grid spans ±this.
    pub fn half_mm(&self) -> f64 {
        (self.n - 1) as f64 / 2.0 * self.step_mm
    }

    /// The position of node (i, j), mm.
    pub fn node(&self, i: usize, j: usize) -> (f64, f64) {
        let h = self.half_mm();
        (-h + i as f64 * self.step_mm, -h + j as f64 * self.step_mm)
    }

    /// Whether node (i, j) is kept: within two spacings outside the covered disc.
    pub fn keeps(&self, i: usize, j: usize) -> bool {
        let (x, y) = self.node(i, j);
        x.hypot(y) <= self.cover_radius_mm + 2.0 * self.step_mm
    }
}

/// The residual on a [`GridLayout`]: each kept node's value, measured or filled.
#[derive(Debug, Clone, PartialEq)]
pub struct ResidualGrid {
    /// The nodes.
    pub layout: GridLayout,
    /// Values, mm, row by row from −y (`j·n + i`); NaN where no value (yet).
    pub values_mm: Vec<f64>,
    /// Whether the node is kept ([`GridLayout::keeps`]).
    pub kept: Vec<bool>,
    /// Whether its value came from the data (else from the extension).
    pub measured: Vec<bool>,
}

/// The measured points bucketed by cells of the window's size, for the windows' queries.
struct Buckets<'a> {
    points: &'a [[f64; 3]],
    x0: f64,
    y0: f64,
    cell: f64,
    nx: usize,
    ny: usize,
    start: Vec<usize>,
    index: Vec<u32>,
}

impl<'a> Buckets<'a> {
    fn new(points: &'a [[f64; 3]], cell: f64) -> Self {
        let [x0, y0, x1, y1] = bounds(points);
        let nx = (((x1 - x0) / cell).floor() as usize + 1).min(1 << 14);
        let ny = (((y1 - y0) / cell).floor() as usize + 1).min(1 << 14);
        let cell_of = |p: &[f64; 3]| {
            let i = (((p[0] - x0) / cell) as usize).min(nx - 1);
            let j = (((p[1] - y0) / cell) as usize).min(ny - 1);
            j * nx + i
        };
        let mut start = vec![0usize; nx * ny + 1];
        for p in points {
            start[cell_of(p) + 1] += 1;
        }
        for k in 0..nx * ny {
            start[k + 1] += start[k];
        }
        let mut fill = start.clone();
        let mut index = vec![0u32; points.len()];
        for (k, p) in points.iter().enumerate() {
            let c = cell_of(p);
            index[fill[c]] = k as u32;
            fill[c] += 1;
        }
        Self {
            points,
            x0,
            y0,
            cell,
            nx,
            ny,
            start,
            index,
        }
    }

    /// Calls `f` with every point within `radius` of (x, y).
    fn near(&self, x: f64, y: f64, radius: f64, mut f: impl FnMut(&[f64; 3])) {
        let lo_i = ((x - radius - self.x0) / self.cell).floor().max(0.0) as usize;
        let lo_j = ((y - radius - self.y0) / self.cell).floor().max(0.0) as usize;
        let hi_i = ((x + radius - self.x0) / self.cell).floor();
        let hi_j = ((y + radius - self.y0) / self.cell).floor();
        if hi_i < 0.0 || hi_j < 0.0 {
            return;
        }
        let hi_i = (hi_i as usize).min(self.nx - 1);
        let hi_j = (hi_j as usize).min(self.ny - 1);
        let r2 = radius * radius;
        for j in lo_j..=hi_j {
            for i in lo_i..=hi_i {
                let c = j * self.nx + i;
                for &k in &self.index[self.start[c]..self.start[c + 1]] {
                    let p = &self.points[k as usize];
                    let (dx, dy) = (p[0] - x, p[1] - y);
                    if dx * dx + dy * dy <= r2 {
                        f(p);
                    }
                }
            }
        }
    }
}

impl ResidualGrid {
    /// The grid of `layout` with the nodes the residual points `[x, y, e]` (mm, on the part)
    /// measure (see the module docs), from points `data_spacing_mm` apart; the other kept nodes
    /// are NaN until the extension fills them.
    pub fn measure(layout: GridLayout, points: &[[f64; 3]], data_spacing_mm: f64) -> Self {
        let n = layout.n;
        let window = (1.5 * layout.step_mm).max(2.5 * data_spacing_mm);
        let buckets = Buckets::new(points, window);
        let mut values: Vec<Option<f64>> = vec![None; n * n];
        let _ = fill_chunks(&mut values, |first, out| {
            for (k, slot) in out.iter_mut().enumerate() {
                let (i, j) = ((first + k) % n, (first + k) / n);
                if layout.keeps(i, j) {
                    let (x, y) = layout.node(i, j);
                    *slot = local_fit(&buckets, x, y, window);
                }
            }
            Ok::<(), ()>(())
        });
        let kept = (0..n * n).map(|k| layout.keeps(k % n, k / n)).collect();
        Self {
            layout,
            measured: values.iter().map(Option::is_some).collect(),
            values_mm: values.iter().map(|v| v.unwrap_or(f64::NAN)).collect(),
            kept,
        }
    }
}

/// The weighted local quadratic's value at (x, y), if the node counts as measured.
fn local_fit(buckets: &Buckets, x: f64, y: f64, window: f64) -> Option<f64> {
    let mut pts: Vec<[f64; 4]> = Vec::new();
    let (mut wsum, mut cx, mut cy) = (0.0, 0.0, 0.0);
    buckets.near(x, y, window, |p| {
        let (u, v) = ((p[0] - x) / window, (p[1] - y) / window);
        let t = 1.0 - (u * u + v * v);
        let w = t * t;
        if w > 0.0 {
            pts.push([u, v, p[2], w]);
            wsum += w;
            cx += w * u;
            cy += w * v;
        }
    });
    if pts.len() < MIN_WINDOW_POINTS || cx.hypot(cy) > 0.5 * wsum {
        return None;
    }
    let sums = NormalEquations::accumulate(pts.len(), 6, |k, a, b| {
        let [u, v, e, w] = pts[k];
        let s = w.sqrt();
        a.copy_from_slice(&[s, s * u, s * v, s * u * u, s * u * v, s * v * v]);
        *b = s * e;
        Ok::<(), ()>(())
    })
    .ok()?;
    let (c, singular) = sums.solve();
    (!singular && c[0].is_finite()).then_some(c[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_layout_covers_the_part_with_an_odd_grid() {
        for (r, d) in [(10.0, 0.02), (10.0, 1.0), (3.0, 0.001), (50.0, 0.5)] {
            let g = GridLayout::covering(r, d);
            assert!(
                g.n % 2 == 1 && g.n >= MIN_GRID_SIDE && g.n <= MAX_GRID_SIDE,
                "{g:?}"
            );
            assert!(g.half_mm() >= g.cover_radius_mm - 1e-9, "{g:?}");
            assert!(g.cover_radius_mm >= 1.02 * r);
            assert_eq!(g.node(g.n / 2, g.n / 2), (0.0, 0.0));
        }
    }

    #[test]
    fn a_quadratic_residual_is_sampled_exactly_inside_the_data() {
        let e = |x: f64, y: f64| {
            1e-4 * (0.3 + 0.2 * x - 0.1 * y + 0.05 * x * x - 0.02 * x * y + 0.03 * y * y)
        };
        let mut pts = Vec::new();
        for j in -100..=100 {
            for i in -100..=100 {
                let (x, y) = (i as f64 * 0.05, j as f64 * 0.05);
                if x.hypot(y) <= 4.0 {
                    pts.push([x, y, e(x, y)]);
                }
            }
        }
        let layout = GridLayout::covering(5.0, 0.05);
        let g = ResidualGrid::measure(layout, &pts, 0.05);
        let (mut inside, mut outside) = (0, 0);
        for j in 0..layout.n {
            for i in 0..layout.n {
                let k = j * layout.n + i;
                let (x, y) = layout.node(i, j);
                if g.measured[k] {
                    assert!((g.values_mm[k] - e(x, y)).abs() < 1e-15, "({x}, {y})");
                    assert!(x.hypot(y) <= 4.0 + 0.1);
                    inside += 1;
                } else if x.hypot(y) < 3.8 {
                    panic!("({x}, {y}) inside the data but not measured");
                } else {
                    outside += 1;
                }
            }
        }
        assert!(inside > 1000 && outside > 100, "{inside} {outside}");
    }
}
