//! Zemax Grid Sag: a rectangular grid of sag data from a `.DAT` file ([`dat`]) added to a base
//! asphere, `z(x, y) = base(x, y) + g(x − x_dec, y − y_dec)`, as OpticStudio's "Grid Sag" surface
//! defines it (OpticStudio User Guide, "Grid Sag"), with g the bicubic interpolation of the grid
//! (OpticStudio's default, "bicubic spline"; its linear option is not offered, it is not C¹).
//!
//! **Interpolation.** Each cell is the bicubic Hermite patch of its four corners' sags, slopes
//! and cross derivatives (module `bicubic`), its 16 coefficients computed when the surface is built,
//! so an evaluation is a cell lookup and two cubic polynomials: C¹ everywhere, the designer's
//! derivatives honoured at every grid point. When the file's derivatives are all zero they are
//! computed: the slopes of the not-a-knot cubic splines through each row and column and, for the
//! cross derivative, the column splines of the row slopes (module `spline`), which makes g the
//! tensor-product cubic spline of the sags (C², exact for bicubic polynomials). OpticStudio does
//! not document how it computes missing derivatives, so on such a file its sag may differ from
//! this one by up to the interpolation error (measured in `tests/tests/surface_grid_sag.rs`).
//!
//! **Domain.** The grid's rectangle (to 1e-9 of a cell); a point outside, or in a cell with a
//! corner without data, is undefined, an error naming the point, the grid point and its line in
//! the file (OpticStudio would use the base alone there; a made-up sag is never cut). The grid
//! must therefore cover the part and the path's first point, which may lie one angle step
//! outside it.
//!
//! **Planner.** No slope kinks (C¹); the feature length is twice the smaller spacing (the
//! shortest wave the data can hold), as for scattered data on a grid.

pub mod dat;
pub mod export;

mod bicubic;
mod spline;

use super::{Asphere, AsphereSpec, DataFile, Local, SectionBounds, Surface, UndefinedError};
use crate::field::FieldError;
use dat::GridData;
use serde::{Deserialize, Serialize};

/// Tolerance on the grid's edges, in cells.
const EDGE: f64 = 1e-9;

/// Job entry of a Grid Sag surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSagSpec {
    /// The `.DAT` file, as `{"path": …}` (command line) or `{"text": …}`.
    pub data: DataFile,
    /// The base surface the grid is added to; default the plane z = 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base: Option<AsphereSpec>,
}

/// Where the grid's derivatives came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Derivatives {
    /// The file's.
    File,
    /// Computed by splines (the file's were all zero).
    Computed,
}

/// A Grid Sag surface, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct GridSag {
    base: Asphere,
    flat_base: bool,
    name: String,
    /// The grid as read (the nodes' derivatives are the file's).
    grid: GridData,
    derivatives: Derivatives,
    /// Position of the first point (i = j = 0), mm.
    x0: f64,
    y0: f64,
    /// 1/Δx and 1/Δy, mm⁻¹ (an evaluation multiplies: no division on the lookup's path).
    inv_dx: f64,
    inv_dy: f64,
    /// Coefficients per cell, `cells[j·(nx − 1) + i]`; all infinite in a cell with a corner
    /// without data (a valid cell's first coefficient is its corner's sag, finite), so one load
    /// says both.
    cells: Vec<[f64; 16]>,
    missing: usize,
}

/// The derivatives at every node in mm units: `[z_x, z_y, z_xy]`, from the file or computed.
fn node_derivatives(g: &GridData) -> (Vec<[f64; 3]>, Derivatives) {
    if g.has_derivatives() {
        let d = g
            .nodes
            .iter()
            .map(|n| [n.dz_dx, n.dz_dy, n.d2z_dxdy_per_mm])
            .collect();
        return (d, Derivatives::File);
    }
    let (nx, ny) = (g.nx, g.ny);
    let mut d = vec![[0.0; 3]; nx * ny];
    let mut z = Vec::new();
    let mut s = Vec::new();
    // Along rows: z_x.
    for j in 0..ny {
        let row = &g.nodes[j * nx..(j + 1) * nx];
        spline::runs(row.iter().map(|n| n.valid), |start, len| {
            z.clear();
            z.extend(row[start..start + len].iter().map(|n| n.z_mm));
            s.resize(len, 0.0);
            spline::slopes(&z, g.dx_mm, &mut s);
            for (k, v) in s.iter().enumerate() {
                d[j * nx + start + k][0] = *v;
            }
        });
    }
    // Along columns: z_y from the sags, z_xy from the row slopes.
    for i in 0..nx {
        let valid = (0..ny).map(|j| g.nodes[j * nx + i].valid);
        spline::runs(valid, |start, len| {
            for (what, out) in [(0, 1), (1, 2)] {
                z.clear();
                z.extend((start..start + len).map(|j| {
                    let k = j * nx + i;
                    if what == 0 { g.nodes[k].z_mm } else { d[k][0] }
                }));
                s.resize(len, 0.0);
                spline::slopes(&z, g.dy_mm, &mut s);
                for (k, v) in s.iter().enumerate() {
                    d[(start + k) * nx + i][out] = *v;
                }
            }
        });
    }
    (d, Derivatives::Computed)
}

impl GridSag {
    /// Reads the data file, checks the spec and builds the surface.
    pub fn new(spec: &GridSagSpec) -> Result<Self, FieldError> {
        let text = spec.data.text("data")?;
        let grid = GridData::parse(text)
            .map_err(|e| FieldError::new("data", spec.data.name(), e.to_string()))?;
        let mut s = Self::from_grid(grid, spec.base.as_ref())?;
        s.name = spec.data.name().to_string();
        Ok(s)
    }

    /// Builds the surface from a grid already read, on `base` (None: the plane).
    pub fn from_grid(grid: GridData, base: Option<&AsphereSpec>) -> Result<Self, FieldError> {
        let base = match base {
            Some(b) => Asphere::new(b).map_err(|e| e.within("base"))?,
            None => Asphere::plane(),
        };
        let (d, derivatives) = node_derivatives(&grid);
        let (nx, ny, dx, dy) = (grid.nx, grid.ny, grid.dx_mm, grid.dy_mm);
        let mut cells = Vec::with_capacity((nx - 1) * (ny - 1));
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let corner = |a: usize, b: usize| {
                    let k = (j + b) * nx + i + a;
                    let [zx, zy, zxy] = d[k];
                    [grid.nodes[k].z_mm, zx * dx, zy * dy, zxy * dx * dy]
                };
                let valid = [(0, 0), (1, 0), (0, 1), (1, 1)]
                    .iter()
                    .all(|&(a, b)| grid.nodes[(j + b) * nx + i + a].valid);
                cells.push(if valid {
                    bicubic::coefficients(&[corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1)])
                } else {
                    [f64::INFINITY; 16]
                });
            }
        }
        let (x0, y0) = grid.position(0, 0);
        Ok(Self {
            flat_base: base.is_plane(),
            base,
            name: "inline data".into(),
            derivatives,
            x0,
            y0,
            inv_dx: 1.0 / dx,
            inv_dy: 1.0 / dy,
            cells,
            missing: grid.nodes.iter().filter(|n| !n.valid).count(),
            grid,
        })
    }

    /// The grid as read.
    pub fn grid(&self) -> &GridData {
        &self.grid
    }

    /// Where the derivatives came from.
    pub fn derivatives(&self) -> Derivatives {
        self.derivatives
    }

    fn undefined(x: f64, y: f64, reason: String) -> UndefinedError {
        UndefinedError {
            surface: "grid sag",
            x_mm: x,
            y_mm: y,
            radius_mm: x.hypot(y),
            reason,
        }
    }

    /// Why the cell (i, j) has no value: its first corner without data.
    fn missing_corner(&self, i: usize, j: usize) -> String {
        let g = &self.grid;
        let (a, b) = [(0, 1), (1, 1), (0, 0), (1, 0)]
            .into_iter()
            .find(|&(a, b)| !g.node(i + a, j + b).valid)
            .unwrap_or((0, 0));
        let (px, py) = g.position(i + a, j + b);
        let line = g
            .line_of(i + a, j + b)
            .map_or(String::new(), |l| format!(", line {l} of the file"));
        format!(
            "the grid has no data at its point in column {} from −x and row {} from the top \
             ({px} mm, {py} mm{line}), a corner of the cell here",
            i + a + 1,
            g.ny - (j + b)
        )
    }

    /// `[g, g_x, g_y, g_xx, g_xy, g_yy]` of the grid part at (x, y).
    fn grid_local(&self, x: f64, y: f64) -> Result<[f64; 6], String> {
        let g = &self.grid;
        let (ix, iy) = (self.inv_dx, self.inv_dy);
        let (t, s) = ((x - self.x0) * ix, (y - self.y0) * iy);
        let (last_i, last_j) = ((g.nx - 1) as f64, (g.ny - 1) as f64);
        if !(t >= -EDGE && t <= last_i + EDGE && s >= -EDGE && s <= last_j + EDGE) {
            let (x1, y1) = g.position(g.nx - 1, g.ny - 1);
            return Err(format!(
                "outside the grid, which spans x {} … {x1} mm, y {} … {y1} mm",
                self.x0, self.y0
            ));
        }
        // Truncation is the floor for t ≥ 0; `as` saturates t in [−EDGE, 0) to 0.
        let i = (t as usize).min(g.nx - 2);
        let j = (s as usize).min(g.ny - 2);
        let cell = match self.cells.get(j * (g.nx - 1) + i) {
            Some(cell) if cell[0].is_finite() => cell,
            _ => return Err(self.missing_corner(i, j)),
        };
        let [p, pu, pv, puu, puv, pvv] = bicubic::eval(cell, t - i as f64, s - j as f64);
        Ok([
            p,
            pu * ix,
            pv * iy,
            puu * (ix * ix),
            puv * (ix * iy),
            pvv * (iy * iy),
        ])
    }
}

impl Surface for GridSag {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let [z, zx, zy, zxx, zxy, zyy] = self
            .grid_local(x, y)
            .map_err(|r| Self::undefined(x, y, r))?;
        let grid = Local {
            z,
            zx,
            zy,
            zxx,
            zxy,
            zyy,
        };
        if self.flat_base {
            return Ok(grid);
        }
        let base = self
            .base
            .local(x, y)
            .map_err(|e| Self::undefined(x, y, e.reason))?;
        Ok(base + grid)
    }

    fn feature_length_mm(&self) -> f64 {
        (2.0 * self.grid.dx_mm.min(self.grid.dy_mm)).min(self.base.feature_length_mm())
    }

    /// The base's bounds plus the grid's over every cell that meets the disc
    /// (`bicubic::derivative_bounds`, in mm through the spacings): a section's slope is at most
    /// |∇g| and its curvature `dᵀHd` at most the larger eigenvalue of the matrix of the Hessian's
    /// bounds, whatever the line's direction and offset (so the grid's decentre does not
    /// matter). C¹ across cells: no kinks (the Hessian's jumps at the edges leave F′ falling).
    /// None where a cell meeting the disc lacks data.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let g = &self.grid;
        let (dx, dy) = (g.dx_mm, g.dy_mm);
        // The cells whose index range meets [−t, t] along an axis.
        let range = |origin: f64, step: f64, cells: usize| {
            let first = ((-t - origin) / step).floor().max(0.0) as usize;
            let end = (((t - origin) / step).ceil().max(0.0) as usize).min(cells);
            first..end
        };
        let (mut slope, mut curvature) = (0.0f64, 0.0f64);
        for j in range(self.y0, dy, g.ny - 1) {
            for i in range(self.x0, dx, g.nx - 1) {
                let (xa, ya) = (self.x0 + i as f64 * dx, self.y0 + j as f64 * dy);
                let (nx, ny) = (0f64.clamp(xa, xa + dx), 0f64.clamp(ya, ya + dy));
                if nx * nx + ny * ny > t * t {
                    continue;
                }
                let cell = &self.cells[j * (g.nx - 1) + i];
                if !cell[0].is_finite() {
                    return None;
                }
                let [bu, bv, buu, buv, bvv] = bicubic::derivative_bounds(cell);
                slope = slope.max((bu / dx).hypot(bv / dy));
                let (p, q, r) = (buu / (dx * dx), buv / (dx * dy), bvv / (dy * dy));
                curvature = curvature.max(0.5 * (p + r) + (0.5 * (p - r)).hypot(q));
            }
        }
        self.base.section_bounds(t)?.plus(slope, curvature)
    }

    /// Its section bounds, which hold for any line (the cells' and the base's).
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.section_bounds(radius_mm)
    }

    fn describe(&self) -> String {
        let g = &self.grid;
        let derivatives = match self.derivatives {
            Derivatives::File => "derivatives from the file",
            Derivatives::Computed => {
                "derivatives computed (the file's are all zero): not-a-knot bicubic spline"
            }
        };
        let missing = if self.missing > 0 {
            format!(", {} points without data", self.missing)
        } else {
            String::new()
        };
        format!(
            "grid sag (Zemax DAT) from {}: {} × {} points {} × {} mm centred at ({}, {}) mm, file \
             unit {}, bicubic, {derivatives}{missing}; on {}",
            self.name,
            g.nx,
            g.ny,
            g.dx_mm,
            g.dy_mm,
            g.x_decenter_mm,
            g.y_decenter_mm,
            g.unit.name(),
            if self.flat_base {
                "the plane z = 0".to_string()
            } else {
                self.base.describe()
            }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::export::{GridExtent, sample};
    use super::*;
    use crate::surface::section_bounds::assert_bounds_hold;

    #[test]
    fn section_bounds_hold_on_dense_sections_about_and_off_the_axis() {
        // A sine grid sampled on grids about and off the axis, on a base sphere; a node without
        // data inside the disc takes the bounds away.
        let exact: Box<dyn Surface> = serde_json::from_str::<crate::surface::SurfaceSpec>(
            r#"{"type":"sinusoid","amplitude_mm":0.002,"wavelength_x_mm":2.0,
                "wavelength_y_mm":2.6,"phase_y_deg":40}"#,
        )
        .unwrap()
        .build(3.0)
        .unwrap();
        let base = AsphereSpec {
            radius_mm: Some(-50.0),
            ..Default::default()
        };
        for (cx, cy) in [(0.0, 0.0), (0.35, -0.2)] {
            let extent = GridExtent {
                centre_x_mm: cx,
                centre_y_mm: cy,
                ..GridExtent::square(61, 61, 3.2)
            };
            let mut grid = sample(exact.as_ref(), &extent).unwrap();
            let s = GridSag::from_grid(grid.clone(), Some(&base)).unwrap();
            let (b, slope, _) = assert_bounds_hold(&s, 2.8, 36, 4000);
            assert!(b.max_slope < 1.1 * slope, "{b:?} {slope}");
            // The grid alone: its bounds are entrywise (|∇g| from the largest |g_x| and |g_y|,
            // reached at different points; the Hessian's from its entries' largest sizes), 1.24
            // and 1.48 times the sampled extremes on this sine grid; a guard against worse.
            let flat = GridSag::from_grid(grid.clone(), None).unwrap();
            let (f, slope, curvature) = assert_bounds_hold(&flat, 2.8, 36, 4000);
            assert!(f.max_slope < 1.3 * slope, "{f:?} {slope}");
            assert!(f.max_curvature < 1.6 * curvature, "{f:?} {curvature}");
            grid.nodes[30 * 61 + 31].valid = false;
            let holed = GridSag::from_grid(grid, Some(&base)).unwrap();
            assert!(holed.section_bounds(2.8).is_none());
        }
    }
}
