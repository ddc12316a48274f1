//! The one result of every measured-data reader: heights in millimetres over the part, either
//! a scattered point cloud (profilometers, coordinate measuring machines) or a regular grid
//! with a nodata mask (interferometers), in one stated frame.
//!
//! **Units.** x, y and z are millimetres whatever the file used; each reader converts (µm, nm,
//! metres, fringes) and says how in [`MeasuredMap::source`].
//!
//! **Frame.** Seen from the tool (+Z), x to the right, y up, z positive towards the tool
//! (material above the reference), the frame of the job's surfaces (DESIGN.md, "Domain
//! primer"). An instrument's map is read as its own display shows it, seen from the instrument
//! with its first image row at the top; when the instrument's frame is not the machine's (a
//! Fizeau cavity images the part mirrored, the part was clocked on the stage), an
//! [`Orientation`] turns it, and [`MeasuredMap::orientation`] records the one applied. The
//! origin of an instrument's grid is the centre of its array (the files place the array in
//! camera pixels, not on the part); registration to the design finds the decentre.

use super::Orientation;

/// A regular grid of heights: node `(i, j)` at `(x0 + i·dx, y0 + j·dy)`, row `j` running along
/// +x, rows stacked towards +y; values row by row (`j·nx + i`); a node without a value has
/// `valid[k] == false` and `z_mm[k] == 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightGrid {
    /// x of column 0, mm.
    pub x0_mm: f64,
    /// y of row 0, mm.
    pub y0_mm: f64,
    /// Spacing along x, mm, > 0.
    pub dx_mm: f64,
    /// Spacing along y, mm, > 0.
    pub dy_mm: f64,
    /// Nodes along x.
    pub nx: usize,
    /// Nodes along y.
    pub ny: usize,
    /// Heights, mm, row by row; 0 where there is no value.
    pub z_mm: Vec<f64>,
    /// Whether each node holds a measured value.
    pub valid: Vec<bool>,
}

impl HeightGrid {
    /// A grid of `nx` × `ny` nodes centred on the origin (the middle of the array at x = y =
    /// 0), heights `z_mm` and mask `valid` row by row from the lowest row (most negative y).
    pub fn centred(
        nx: usize,
        ny: usize,
        dx_mm: f64,
        dy_mm: f64,
        z_mm: Vec<f64>,
        valid: Vec<bool>,
    ) -> Self {
        Self {
            x0_mm: -0.5 * nx.saturating_sub(1) as f64 * dx_mm,
            y0_mm: -0.5 * ny.saturating_sub(1) as f64 * dy_mm,
            dx_mm,
            dy_mm,
            nx,
            ny,
            z_mm,
            valid,
        }
    }

    /// The position of node `(i, j)`, mm.
    pub fn node(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.x0_mm + i as f64 * self.dx_mm,
            self.y0_mm + j as f64 * self.dy_mm,
        ]
    }

    /// The height at node `(i, j)`, mm, if it has one.
    pub fn height(&self, i: usize, j: usize) -> Option<f64> {
        let k = j.checked_mul(self.nx)?.checked_add(i)?;
        (i < self.nx && *self.valid.get(k)?).then(|| self.z_mm[k])
    }

    /// Nodes with a value.
    pub fn valid_count(&self) -> usize {
        self.valid.iter().filter(|v| **v).count()
    }
}

/// Scattered measured points `[x, y, z]`, mm.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PointCloud {
    /// The points, in file order.
    pub points: Vec<[f64; 3]>,
}

/// A map's heights: scattered points or a grid.
#[derive(Debug, Clone, PartialEq)]
pub enum MeasuredData {
    /// Scattered points (CSV).
    Cloud(PointCloud),
    /// A regular grid with a nodata mask (interferometers).
    Grid(HeightGrid),
}

/// Measured heights in millimetres in the frame of the module docs.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredMap {
    /// The heights.
    pub data: MeasuredData,
    /// Where they came from and how they were converted to millimetres, one line.
    pub source: String,
    /// The orientation applied to the file's own frame ([`Orientation::IDENTITY`] as read).
    pub orientation: Orientation,
}

impl MeasuredMap {
    /// A map read as the file has it (no orientation applied).
    pub fn new(data: MeasuredData, source: impl Into<String>) -> Self {
        Self {
            data,
            source: source.into(),
            orientation: Orientation::IDENTITY,
        }
    }

    /// The measured points `[x, y, z]`, mm: every point of a cloud, every valid node of a grid.
    pub fn points(&self) -> Vec<[f64; 3]> {
        match &self.data {
            MeasuredData::Cloud(c) => c.points.clone(),
            MeasuredData::Grid(g) => (0..g.ny)
                .flat_map(|j| (0..g.nx).map(move |i| (i, j)))
                .filter_map(|(i, j)| {
                    let [x, y] = g.node(i, j);
                    g.height(i, j).map(|z| [x, y, z])
                })
                .collect(),
        }
    }

    /// The number of measured points (valid nodes of a grid).
    pub fn len(&self) -> usize {
        match &self.data {
            MeasuredData::Cloud(c) => c.points.len(),
            MeasuredData::Grid(g) => g.valid_count(),
        }
    }

    /// Whether the map holds no measured point.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The map seen through `orientation` after the one already applied: points move, heights
    /// stay (see [`Orientation`]).
    pub fn oriented(self, orientation: Orientation) -> Self {
        let data = match self.data {
            MeasuredData::Cloud(c) => MeasuredData::Cloud(orientation.apply_to_cloud(&c)),
            MeasuredData::Grid(g) => MeasuredData::Grid(orientation.apply_to_grid(&g)),
        };
        Self {
            data,
            source: self.source,
            orientation: orientation.after(self.orientation),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_centred_grid_puts_the_array_middle_at_the_origin() {
        let g = HeightGrid::centred(3, 2, 0.5, 2.0, vec![1.0; 6], vec![true; 6]);
        assert_eq!(g.node(0, 0), [-0.5, -1.0]);
        assert_eq!(g.node(2, 1), [0.5, 1.0]);
        assert_eq!(g.height(3, 0), None);
        let mut g = g;
        g.valid[4] = false;
        let m = MeasuredMap::new(MeasuredData::Grid(g), "test");
        assert_eq!(m.len(), 5);
        assert!(!m.points().iter().any(|p| p[0] == 0.0 && p[1] == 1.0));
    }
}
