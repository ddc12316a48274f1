//! A uniform grid of square cells over the plane, each cell listing indices of items (points,
//! discs) filed under it: the "bucket grid" of computational geometry, on which a query looks
//! only at the few items of the cells near it. The lists are stored compressed, one offset per
//! cell into one array of indices (cells row-major, x fastest; each list in increasing order),
//! filled by a counting sort. What is filed where, and how a point outside the grid is treated,
//! is up to the user: the compound eye files discs under every cell they meet, the NURBS
//! inversion files each sample point under its one cell.

/// The grid: cell `(i, j)` is `[x0 + i·cell, x0 + (i + 1)·cell] × [y0 + j·cell, …]`, `i < nx`,
/// `j < ny`, and has the flat index `k = j·nx + i`.
#[derive(Debug, Clone, PartialEq)]
pub struct CellGrid {
    /// Lower left corner, mm.
    pub x0: f64,
    /// Lower left corner, mm.
    pub y0: f64,
    /// Cell side, mm.
    pub cell: f64,
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// `items[start[k]..start[k + 1]]` are the items of cell k.
    start: Vec<u32>,
    items: Vec<u32>,
}

impl CellGrid {
    /// A grid of `nx × ny` empty cells of side `cell` from `(x0, y0)`.
    pub fn new(x0: f64, y0: f64, cell: f64, nx: usize, ny: usize) -> Self {
        Self {
            x0,
            y0,
            cell,
            nx,
            ny,
            start: vec![0; nx * ny + 1],
            items: Vec::new(),
        }
    }

    /// The point's position in cell units from the corner, `((x − x0)/cell, (y − y0)/cell)`.
    pub fn cell_coordinates(&self, x: f64, y: f64) -> (f64, f64) {
        ((x - self.x0) / self.cell, (y - self.y0) / self.cell)
    }

    /// Files `item` under flat cell index `k` for each `(k, item)`, replacing what the cells
    /// listed. A cell lists its items in the order given, so give them in increasing order.
    pub fn fill(&mut self, filed: &[(usize, u32)]) {
        self.start.iter_mut().for_each(|s| *s = 0);
        for &(k, _) in filed {
            self.start[k + 1] += 1;
        }
        for k in 0..self.nx * self.ny {
            self.start[k + 1] += self.start[k];
        }
        self.items = vec![0; filed.len()];
        let mut next = self.start.clone();
        for &(k, item) in filed {
            self.items[next[k] as usize] = item;
            next[k] += 1;
        }
    }

    /// The items of the cells `k0..=k1` (flat indices; within one row, a run of cells along x),
    /// one cell's list after another.
    pub fn items(&self, k0: usize, k1: usize) -> &[u32] {
        &self.items[self.start[k0] as usize..self.start[k1 + 1] as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filed_items_come_back_by_cell_in_order() {
        let mut g = CellGrid::new(-1.0, 2.0, 0.5, 3, 2);
        assert_eq!(g.cell_coordinates(-0.25, 2.5), (1.5, 1.0));
        g.fill(&[(4, 0), (0, 1), (4, 2), (5, 2), (0, 3)]);
        assert_eq!(g.items(0, 0), &[1, 3]);
        assert!(g.items(1, 3).is_empty());
        assert_eq!(g.items(4, 4), &[0, 2]);
        assert_eq!(g.items(3, 5), &[0, 2, 2]);
        g.fill(&[]);
        assert!(g.items(0, 5).is_empty());
    }
}
