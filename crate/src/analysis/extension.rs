//! The residual continued smoothly where nothing was measured (issue 15: "extended smoothly to
//! the whole area the tool passes"): the edge the interferometer's aperture left out, the holes
//! of its mask, the space between a profilometer's traces.
//!
//! **Method: minimum curvature** (I. C. Briggs, "Machine contouring using minimum curvature",
//! Geophysics 39(1), 1974; W. H. F. Smith and P. Wessel, "Gridding with continuous curvature
//! splines in tension", Geophysics 55(3), 1990, GMT's `surface` at tension 0). The unmeasured
//! nodes of the residual grid take the values that minimise the discrete thin-plate bending
//! energy `E = Σ g_xx² + 2·Σ g_xy² + Σ g_yy²`, the second differences `g_xx`, `g_yy` at every
//! kept node with both neighbours along the axis kept and `g_xy` on every cell with its four
//! corners kept, the measured nodes held fixed: in the interior the discrete biharmonic equation
//! ∇⁴g = 0, at the edge of the kept disc the plate's natural conditions (only a plane bends not
//! at all, so the continuation is unique and a plane continues as itself). The result joins the
//! data with continuous value and slope and bends as little as it can beyond them.
//!
//! **Solution.** E is a quadratic in the unmeasured values u, `E = ‖A·u + b‖²_W` (A the second
//! differences' dependence on u, b that on the measured values, W their weights), minimised by
//! conjugate gradients on its normal equations `AᵀWA·u = −AᵀWb` (M. R. Hestenes and E. Stiefel,
//! 1952), matrix-free: each product is two passes over the differences. The iterations stop when the gradient
//! has fallen below [`TOLERANCE`] of its start, or after [`MAX_ITERATIONS`]. They start from the
//! caller's values (the 37-term Zernike fit of the residual, [`super::zernike_fit`], taken at
//! the rim in the direction of a node outside it); the report says how many iterations ran and
//! whether they converged.

use super::residual::ResidualGrid;
use serde::Serialize;

/// Relative size of the energy gradient that ends the iterations.
pub const TOLERANCE: f64 = 1e-12;
/// The most iterations.
pub const MAX_ITERATIONS: usize = 20_000;

/// What the extension did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExtensionReport {
    /// The method, in words.
    pub method: String,
    /// Nodes of the grid kept (inside the disc the tool passes and a margin).
    pub nodes: usize,
    /// Nodes whose value came from the data.
    pub measured_nodes: usize,
    /// Nodes filled by the extension.
    pub filled_nodes: usize,
    /// Conjugate-gradient iterations run.
    pub iterations: usize,
    /// Whether the gradient fell below the tolerance.
    pub converged: bool,
}

/// One squared second difference of the energy: up to four nodes with their weights, and the
/// term's own weight (1 for g_xx and g_yy, 2 for g_xy).
#[derive(Debug, Clone, Copy)]
struct Difference {
    nodes: [usize; 4],
    weights: [f64; 4],
    len: usize,
    scale: f64,
}

impl Difference {
    fn value(&self, g: &[f64]) -> f64 {
        (0..self.len)
            .map(|i| self.weights[i] * g[self.nodes[i]])
            .sum()
    }
}

/// Every second difference of the kept nodes: g_xx and g_yy at each node with both neighbours
/// along the axis kept, g_xy on each cell with its four corners kept.
fn differences(n: usize, kept: &[bool]) -> Vec<Difference> {
    let mut out = Vec::new();
    for k in 0..n * n {
        let (i, j) = (k % n, k / n);
        if !kept[k] {
            continue;
        }
        if i > 0 && i + 1 < n && kept[k - 1] && kept[k + 1] {
            out.push(Difference {
                nodes: [k - 1, k, k + 1, 0],
                weights: [1.0, -2.0, 1.0, 0.0],
                len: 3,
                scale: 1.0,
            });
        }
        if j > 0 && j + 1 < n && kept[k - n] && kept[k + n] {
            out.push(Difference {
                nodes: [k - n, k, k + n, 0],
                weights: [1.0, -2.0, 1.0, 0.0],
                len: 3,
                scale: 1.0,
            });
        }
        if i + 1 < n && j + 1 < n && kept[k + 1] && kept[k + n] && kept[k + n + 1] {
            out.push(Difference {
                nodes: [k, k + 1, k + n, k + n + 1],
                weights: [1.0, -1.0, -1.0, 1.0],
                len: 4,
                scale: 2.0,
            });
        }
    }
    out
}

/// Fills every kept, unmeasured node of `grid` by minimum curvature, starting from
/// `start(x, y)` (mm).
pub fn fill(grid: &mut ResidualGrid, start: impl Fn(f64, f64) -> f64) -> ExtensionReport {
    let n = grid.layout.n;
    let g = &mut grid.values_mm;
    let mut slot = vec![usize::MAX; n * n];
    let mut unknown = Vec::new();
    for k in 0..n * n {
        if !grid.kept[k] {
            g[k] = 0.0;
        } else if !grid.measured[k] {
            let (x, y) = grid.layout.node(k % n, k / n);
            g[k] = start(x, y);
            slot[k] = unknown.len();
            unknown.push(k);
        }
    }
    let measured_nodes = grid.kept.iter().filter(|k| **k).count() - unknown.len();
    // The differences that hold an unknown, and for each unknown its (difference, weight).
    let terms: Vec<Difference> = differences(n, &grid.kept)
        .into_iter()
        .filter(|d| d.nodes[..d.len].iter().any(|&k| slot[k] != usize::MAX))
        .collect();
    let mut holds: Vec<Vec<(usize, f64)>> = vec![Vec::new(); unknown.len()];
    for (t, d) in terms.iter().enumerate() {
        for i in 0..d.len {
            let u = slot[d.nodes[i]];
            if u != usize::MAX {
                holds[u].push((t, d.weights[i] * d.scale));
            }
        }
    }
    // r = −∇E/2 = −Σ_t scale·value_t·weight.
    let gather = |values: &[f64], out: &mut [f64]| {
        for (o, h) in out.iter_mut().zip(&holds) {
            *o = h.iter().map(|&(t, w)| values[t] * w).sum();
        }
    };
    let mut values: Vec<f64> = terms.iter().map(|d| d.value(g)).collect();
    let mut r = vec![0.0; unknown.len()];
    gather(&values, &mut r);
    r.iter_mut().for_each(|v| *v = -*v);
    let mut p = r.clone();
    let mut rs: f64 = r.iter().map(|v| v * v).sum();
    let first = rs.sqrt();
    let mut full = vec![0.0; n * n];
    let mut hp = vec![0.0; unknown.len()];
    let (mut iterations, mut converged) = (0, rs == 0.0);
    while !converged && iterations < MAX_ITERATIONS {
        for (&k, &v) in unknown.iter().zip(&p) {
            full[k] = v;
        }
        for (v, d) in values.iter_mut().zip(&terms) {
            *v = d.value(&full);
        }
        gather(&values, &mut hp);
        let php: f64 = p.iter().zip(&hp).map(|(a, b)| a * b).sum();
        if php <= 0.0 {
            break;
        }
        let alpha = rs / php;
        for (i, &k) in unknown.iter().enumerate() {
            g[k] += alpha * p[i];
            r[i] -= alpha * hp[i];
        }
        let next: f64 = r.iter().map(|v| v * v).sum();
        iterations += 1;
        converged = next.sqrt() <= TOLERANCE * first;
        let beta = next / rs;
        rs = next;
        for (pi, ri) in p.iter_mut().zip(&r) {
            *pi = ri + beta * *pi;
        }
    }
    ExtensionReport {
        method: "minimum curvature (discrete thin-plate energy g_xx² + 2·g_xy² + g_yy², measured \
                 nodes held; Briggs 1974), conjugate gradients from the 37-term Fringe Zernike fit"
            .into(),
        nodes: measured_nodes + unknown.len(),
        measured_nodes,
        filled_nodes: unknown.len(),
        iterations,
        converged,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::residual::GridLayout;

    #[test]
    fn a_plane_is_continued_as_itself_and_a_hole_is_closed_smoothly() {
        // Measured: the plane e = 1e-4·(1 + x − 2y) on the disc r < 3 of a Ø10 part, except a
        // hole at (1, 1); the minimum-curvature fill of a plane is the plane (zero Laplacian).
        let layout = GridLayout::covering(5.0, 0.2);
        let n = layout.n;
        let plane = |x: f64, y: f64| 1e-4 * (1.0 + x - 2.0 * y);
        let mut grid = ResidualGrid {
            layout,
            values_mm: vec![f64::NAN; n * n],
            kept: (0..n * n).map(|k| layout.keeps(k % n, k / n)).collect(),
            measured: vec![false; n * n],
        };
        for k in 0..n * n {
            let (x, y) = layout.node(k % n, k / n);
            if grid.kept[k] && x.hypot(y) < 3.0 && (x - 1.0).hypot(y - 1.0) > 0.6 {
                grid.measured[k] = true;
                grid.values_mm[k] = plane(x, y);
            }
        }
        let report = fill(&mut grid, |_, _| 0.0);
        assert!(report.converged, "{report:?}");
        assert!(report.filled_nodes > 0 && report.measured_nodes > 0);
        for k in 0..n * n {
            if grid.kept[k] {
                let (x, y) = layout.node(k % n, k / n);
                let err = (grid.values_mm[k] - plane(x, y)).abs();
                assert!(err < 1e-9, "({x}, {y}): {err:e}");
            }
        }
    }
}
