//! A Zemax Grid Sag `.DAT` as a design of one surface: the grid on a plane, read by the
//! `.DAT` reader of [`crate::surface::grid_sag::dat`] (its docs give the format, the orientation
//! and the units). The file says nothing of the part's size or of the media: the part's
//! diameter must be given, and the side it is cut from chosen.

use super::{Aperture, Design, DesignFormat, DesignSurface, ImportError, LengthUnit, Optics, Role};
use crate::surface::grid_sag::dat::GridData;
use crate::surface::{DataFile, GridSagSpec, SurfaceSpec};

/// Reads a `.DAT` text.
pub fn parse(file: &str, text: &str) -> Result<Design, ImportError> {
    let grid = GridData::parse(text).map_err(|error| ImportError::Grid {
        file: file.to_string(),
        error,
    })?;
    let missing = grid.nodes.iter().filter(|n| !n.valid).count();
    let (hx, hy) = (
        grid.dx_mm * (grid.nx - 1) as f64 / 2.0,
        grid.dy_mm * (grid.ny - 1) as f64 / 2.0,
    );
    let mut read = vec![
        format!(
            "{} × {} points, spacing {} × {} mm, unit {} (flag {})",
            grid.nx,
            grid.ny,
            grid.dx_mm,
            grid.dy_mm,
            grid.unit.name(),
            grid.unit.flag()
        ),
        format!(
            "grid centred at ({}, {}) mm, covering x {} … {} mm, y {} … {} mm",
            grid.x_decenter_mm,
            grid.y_decenter_mm,
            grid.x_decenter_mm - hx,
            grid.x_decenter_mm + hx,
            grid.y_decenter_mm - hy,
            grid.y_decenter_mm + hy
        ),
        if grid.has_derivatives() {
            "derivatives: the file's".to_string()
        } else {
            "derivatives: all zero in the file, computed (not-a-knot splines)".to_string()
        },
    ];
    if missing > 0 {
        read.push(format!("{missing} points without data"));
    }
    let unit = LengthUnit {
        name: grid.unit.name(),
        mm: grid.unit.mm(),
    };
    Ok(Design {
        file: file.to_string(),
        format: DesignFormat::GridSag,
        encoding: super::Encoding::Utf8,
        unit,
        unit_from: format!("the header's unit flag {}", grid.unit.flag()),
        surfaces: vec![DesignSurface {
            number: 1,
            line: grid.first_data_line.unwrap_or(1),
            kind: "Grid Sag".into(),
            label: None,
            role: Role::Surface,
            shape: Ok(SurfaceSpec::GridSag(GridSagSpec {
                data: DataFile {
                    path: Some(file.to_string()),
                    text: Some(text.to_string()),
                },
                base: None,
            })),
            aperture: Aperture::default(),
            optics: Optics::unknown(),
            frame_moved: None,
            read,
            not_read: Vec::new(),
        }],
        notes: Vec::new(),
    })
}
