//! The discs (footprints of pieces, XY extents of seams) filed on a uniform grid of square cells
//! ([`CellGrid`]) under every cell they meet: a point or a short segment then looks only at the
//! few discs listed in its cells, so a lookup costs O(1) in the number of discs (the standard
//! "bucket grid" of computational geometry).

use crate::surface::cell_grid::CellGrid;

/// Most cells along one side of the grid: bounds the memory to a few MiB whatever the layout.
const MAX_CELLS_PER_SIDE: f64 = 1024.0;

/// The grid.
#[derive(Debug, Clone, PartialEq)]
pub struct DiscIndex {
    grid: CellGrid,
}

impl DiscIndex {
    /// Indexes `discs` (centre x, centre y, radius, mm) on cells no smaller than `cell` mm (and
    /// large enough that the grid has at most 1024 cells a side).
    pub fn new(discs: &[[f64; 3]], cell: f64) -> Self {
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for &[x, y, r] in discs {
            x0 = x0.min(x - r);
            x1 = x1.max(x + r);
            y0 = y0.min(y - r);
            y1 = y1.max(y + r);
        }
        if discs.is_empty() {
            (x0, x1, y0, y1) = (0.0, 0.0, 0.0, 0.0);
        }
        let span = (x1 - x0).max(y1 - y0);
        let cell = cell.max(span / MAX_CELLS_PER_SIDE).max(f64::MIN_POSITIVE);
        let nx = ((x1 - x0) / cell).floor() as usize + 1;
        let ny = ((y1 - y0) / cell).floor() as usize + 1;
        let mut index = Self {
            grid: CellGrid::new(x0, y0, cell, nx, ny),
        };
        let mut filed = Vec::new();
        for (k, &[x, y, r]) in discs.iter().enumerate() {
            let [i0, i1, j0, j1] = index.cell_range(x - r, x + r, y - r, y + r);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    if index.cell_meets_disc(i, j, x, y, r) {
                        filed.push((j * nx + i, k as u32));
                    }
                }
            }
        }
        index.grid.fill(&filed);
        index
    }

    /// The discs meeting the cell that contains (x, y); none outside the grid.
    pub fn at(&self, x: f64, y: f64) -> &[u32] {
        let g = &self.grid;
        let (fi, fj) = g.cell_coordinates(x, y);
        if !(fi >= 0.0 && fj >= 0.0 && fi < g.nx as f64 && fj < g.ny as f64) {
            return &[];
        }
        let k = fj as usize * g.nx + fi as usize;
        g.items(k, k)
    }

    /// Appends to `out` the discs meeting any cell that meets the box `[x0, x1] × [y0, y1]`
    /// (with repeats; sort and deduplicate as needed).
    pub fn in_box(&self, [x0, x1, y0, y1]: [f64; 4], out: &mut Vec<u32>) {
        let g = &self.grid;
        let (fx0, fy0) = g.cell_coordinates(x0, y0);
        let (fx1, fy1) = g.cell_coordinates(x1, y1);
        // Entirely outside (or NaN): nothing.
        if !(fx1 >= 0.0 && fy1 >= 0.0 && fx0 < g.nx as f64 && fy0 < g.ny as f64) {
            return;
        }
        let [i0, i1, j0, j1] = self.cell_range(x0, x1, y0, y1);
        for j in j0..=j1 {
            let row = j * g.nx;
            out.extend_from_slice(g.items(row + i0, row + i1));
        }
    }

    /// Cell index ranges (clamped to the grid) covering the box.
    fn cell_range(&self, x0: f64, x1: f64, y0: f64, y1: f64) -> [usize; 4] {
        let g = &self.grid;
        let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n - 1);
        let (fx0, fy0) = g.cell_coordinates(x0, y0);
        let (fx1, fy1) = g.cell_coordinates(x1, y1);
        [
            clamp(fx0, g.nx),
            clamp(fx1, g.nx),
            clamp(fy0, g.ny),
            clamp(fy1, g.ny),
        ]
    }

    /// Whether cell (i, j) and the disc of centre (x, y) and radius r meet.
    fn cell_meets_disc(&self, i: usize, j: usize, x: f64, y: f64, r: f64) -> bool {
        let g = &self.grid;
        let (cx0, cy0) = (g.x0 + g.cell * i as f64, g.y0 + g.cell * j as f64);
        let dx = (cx0 - x).max(x - (cx0 + g.cell)).max(0.0);
        let dy = (cy0 - y).max(y - (cy0 + g.cell)).max(0.0);
        dx * dx + dy * dy <= r * r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force: the discs that contain the point.
    fn containing(discs: &[[f64; 3]], x: f64, y: f64) -> Vec<u32> {
        (0..discs.len() as u32)
            .filter(|&k| {
                let [cx, cy, r] = discs[k as usize];
                (x - cx).hypot(y - cy) <= r
            })
            .collect()
    }

    #[test]
    fn every_disc_containing_a_point_is_listed_at_it() {
        let discs: Vec<[f64; 3]> = (0..40)
            .map(|k| {
                let a = k as f64 * 2.399_963;
                let rho = 0.3 * (k as f64).sqrt();
                [rho * a.cos(), rho * a.sin(), 0.05 + 0.01 * (k % 7) as f64]
            })
            .collect();
        let grid = DiscIndex::new(&discs, 0.05);
        let mut found = 0;
        for i in 0..200 {
            for j in 0..200 {
                let (x, y) = (-2.2 + 0.022 * i as f64, -2.2 + 0.022 * j as f64);
                let listed = grid.at(x, y);
                for k in containing(&discs, x, y) {
                    found += 1;
                    assert!(listed.contains(&k), "({x}, {y}): disc {k} missing");
                }
                let mut boxed = Vec::new();
                grid.in_box([x - 0.01, x + 0.01, y, y], &mut boxed);
                for k in containing(&discs, x, y) {
                    assert!(boxed.contains(&k));
                }
            }
        }
        assert!(found > 1000, "{found}");
        // Far outside, and NaN: nothing.
        assert!(grid.at(50.0, 0.0).is_empty() && grid.at(f64::NAN, 0.0).is_empty());
        let mut none = Vec::new();
        grid.in_box([10.0, 11.0, 10.0, 11.0], &mut none);
        assert!(none.is_empty());
    }
}
