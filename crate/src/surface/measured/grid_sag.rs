//! Zemax Grid Sag `.DAT` files as measured maps: metrology scripts convert interferograms to
//! this format so that a map can be loaded into the design software, and issue 15 asks the
//! correction to take them too. The file is read by the Grid Sag family's own reader
//! ([`crate::surface::grid_sag::dat`]: header `nx ny delx dely unitflag xdec ydec`, one line per
//! point from the upper left, rows running downward, the unit flag converting to millimetres,
//! the nodata flag honoured); the sags become the heights, the derivatives are not used.
//!
//! **Frame.** The grid's x and y are the design's (the frame of the `grid_sag` surface family),
//! which is the machine's frame seen from the tool; the grid's centre is its decentre
//! `(xdec, ydec)`. An orientation may still be applied ([`super::Orientation`]).

use super::{HeightGrid, MeasuredData, MeasuredError, MeasuredMap};
use crate::surface::grid_sag::dat::GridData;

/// Reads the `.DAT` text in `bytes` (UTF-8) of the file `name`.
pub fn read(name: &str, bytes: &[u8]) -> Result<MeasuredMap, MeasuredError> {
    let text = std::str::from_utf8(bytes).map_err(|e| MeasuredError::Format {
        file: name.to_string(),
        problem: format!(
            "a Zemax Grid Sag .DAT is text, but this file is not UTF-8 (at byte {}); a binary \
             MetroPro .dat starts with the magic number 881B036F, 881B0370 or 881B0371",
            e.valid_up_to()
        ),
    })?;
    let grid = GridData::parse(text).map_err(|e| MeasuredError::Format {
        file: name.to_string(),
        problem: format!("Zemax Grid Sag .DAT: {e}"),
    })?;
    let (x0, y0) = grid.position(0, 0);
    let heights = HeightGrid {
        x0_mm: x0,
        y0_mm: y0,
        dx_mm: grid.dx_mm,
        dy_mm: grid.dy_mm,
        nx: grid.nx,
        ny: grid.ny,
        z_mm: grid.nodes.iter().map(|n| n.z_mm).collect(),
        valid: grid.nodes.iter().map(|n| n.valid).collect(),
    };
    let source = format!(
        "{name}: Zemax Grid Sag .DAT, {} × {} points {} × {} mm centred at ({}, {}) mm, file unit \
         {} (sags × {} to mm)",
        grid.nx,
        grid.ny,
        grid.dx_mm,
        grid.dy_mm,
        grid.x_decenter_mm,
        grid.y_decenter_mm,
        grid.unit.name(),
        grid.unit.mm()
    );
    Ok(MeasuredMap::new(MeasuredData::Grid(heights), source))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sags_become_heights_in_the_grid_frame() {
        // 5 × 6 in cm, decentred; the sag is the point's number in the file; point 8 has none.
        let mut t = String::from("5 6 0.2 0.1 1 0.5 -1\n");
        for k in 0..30 {
            t.push_str(&format!("{k} 0 0 0 {}\n", if k == 7 { 1 } else { 0 }));
        }
        let m = read("map.DAT", t.as_bytes()).unwrap();
        let MeasuredData::Grid(g) = &m.data else {
            panic!("a grid")
        };
        assert_eq!((g.nx, g.ny, g.dx_mm, g.dy_mm), (5, 6, 2.0, 1.0));
        // The upper left (first line) is column 0 of the top row, at (5 − 4, −10 + 2.5) mm.
        assert_eq!(g.node(0, 5), [1.0, -7.5]);
        assert_eq!(g.height(0, 5), Some(0.0));
        assert_eq!(g.height(4, 0), Some(290.0));
        assert_eq!(g.height(2, 4), None);
        assert_eq!(m.len(), 29);
        assert!(m.source.contains("file unit cm"), "{}", m.source);
        let e = read("map.DAT", b"5 5 1 1 0 0 0\n0 0 0\n").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("map.DAT: Zemax Grid Sag .DAT: line 2"),
            "{e}"
        );
    }
}
