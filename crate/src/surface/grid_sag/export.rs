//! Any surface written as a Grid Sag grid ([`super::dat::GridData`], hence a `.DAT` by
//! [`GridData::to_dat`]), so that the designer can load in the design software the surface that
//! will be cut: nx × ny points over a rectangle, each with the surface's sag, slopes and cross
//! derivative from [`Surface::local`] (analytic, not differenced), a point where the surface is
//! undefined written without data. The grid is centred on the rectangle's centre (written as
//! the decentre), in millimetres.

use super::dat::{GridData, GridNode, MAX_NODES, MIN_POINTS};
use crate::field::{FieldError, finite, positive};
use crate::surface::Surface;

/// The points and the rectangle of an exported grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridExtent {
    /// Points along x, ≥ 5.
    pub nx: usize,
    /// Points along y, ≥ 5.
    pub ny: usize,
    /// Half the rectangle's width along x, mm, > 0: the points span centre ± this.
    pub half_width_x_mm: f64,
    /// Half its height along y, mm, > 0.
    pub half_width_y_mm: f64,
    /// The rectangle's centre, mm.
    pub centre_x_mm: f64,
    /// The rectangle's centre, mm.
    pub centre_y_mm: f64,
}

impl GridExtent {
    /// nx × ny points over the square of half-width `half_width_mm` on the axis.
    pub fn square(nx: usize, ny: usize, half_width_mm: f64) -> Self {
        Self {
            nx,
            ny,
            half_width_x_mm: half_width_mm,
            half_width_y_mm: half_width_mm,
            centre_x_mm: 0.0,
            centre_y_mm: 0.0,
        }
    }

    /// Checks the counts (5 … and at most [`MAX_NODES`] points) and the rectangle; errors name
    /// `nx`, `ny`, `half_width_x_mm`, … .
    pub fn check(&self) -> Result<(), FieldError> {
        for (name, n) in [("nx", self.nx), ("ny", self.ny)] {
            if n < MIN_POINTS {
                return Err(FieldError::new(
                    name,
                    n,
                    format!("must be at least {MIN_POINTS} (OpticStudio's minimum)"),
                ));
            }
        }
        let points = self.nx.saturating_mul(self.ny);
        if points > MAX_NODES {
            return Err(FieldError::new(
                "nx",
                format!("{} × {} = {points} points", self.nx, self.ny),
                format!("at most {MAX_NODES} points (1024 × 1024)"),
            ));
        }
        positive("half_width_x_mm", self.half_width_x_mm)?;
        positive("half_width_y_mm", self.half_width_y_mm)?;
        finite("centre_x_mm", self.centre_x_mm)?;
        finite("centre_y_mm", self.centre_y_mm)?;
        Ok(())
    }
}

/// `surface` sampled on `extent` (checked first).
pub fn sample(surface: &dyn Surface, extent: &GridExtent) -> Result<GridData, FieldError> {
    extent.check()?;
    let mut grid = GridData {
        nx: extent.nx,
        ny: extent.ny,
        dx_mm: 2.0 * extent.half_width_x_mm / (extent.nx - 1) as f64,
        dy_mm: 2.0 * extent.half_width_y_mm / (extent.ny - 1) as f64,
        x_decenter_mm: extent.centre_x_mm,
        y_decenter_mm: extent.centre_y_mm,
        unit: super::dat::DatUnit::Millimetre,
        nodes: Vec::with_capacity(extent.nx * extent.ny),
        first_data_line: None,
    };
    for j in 0..extent.ny {
        for i in 0..extent.nx {
            let (x, y) = grid.position(i, j);
            grid.nodes.push(match surface.local(x, y) {
                Ok(l) => GridNode {
                    z_mm: l.z,
                    dz_dx: l.zx,
                    dz_dy: l.zy,
                    d2z_dxdy_per_mm: l.zxy,
                    valid: true,
                },
                Err(_) => GridNode::default(),
            });
        }
    }
    Ok(grid)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{Asphere, AsphereSpec};

    #[test]
    fn a_sphere_is_written_with_its_derivatives_and_holes_beyond_its_rim() {
        let s = Asphere::new(&AsphereSpec {
            radius_mm: Some(5.0),
            ..Default::default()
        })
        .unwrap();
        let g = sample(&s, &GridExtent::square(11, 11, 5.0)).unwrap();
        assert_eq!((g.dx_mm, g.dy_mm), (1.0, 1.0));
        // The corners (5, 5) lie beyond the rim r = 5: no data there, nor on the rim itself.
        assert!(!g.node(0, 0).valid && !g.node(10, 5).valid && g.node(9, 5).valid);
        let n = g.node(8, 6);
        let l = s.local(3.0, 1.0).unwrap();
        assert_eq!(
            (n.z_mm, n.dz_dx, n.dz_dy, n.d2z_dxdy_per_mm),
            (l.z, l.zx, l.zy, l.zxy)
        );
        let e = sample(&s, &GridExtent::square(4, 11, 5.0)).unwrap_err();
        assert_eq!(e.field, "nx");
        let e = sample(&s, &GridExtent::square(2000, 2000, 5.0)).unwrap_err();
        assert!(e.allowed.starts_with("at most 1048576"), "{e}");
    }
}
