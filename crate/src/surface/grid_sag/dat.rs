//! The Zemax Grid Sag `.DAT` format, read and written: a rectangular grid of sag values with
//! their slopes and cross derivative, as OpticStudio's "Grid Sag" surface imports it
//! (OpticStudio User Guide, "Grid Sag", section "Importing Grid Data"):
//!
//! ```text
//! nx ny delx dely unitflag xdec ydec
//! z dz/dx dz/dy d2z/dxdy [nodata]      (nx·ny lines)
//! ```
//!
//! - The header: the whole numbers of points nx, ny (OpticStudio needs at least 5 each), the
//!   spacings delx, dely (OpticStudio takes their absolute values; 0 is refused here), the unit
//!   flag (0 mm, 1 cm, 2 in, 3 m) and the decentre of the grid relative to the base surface.
//! - Then one line per point: the sag, its first derivatives, its cross derivative, and an
//!   optional whole number, 0 for data and any other value for none. The first line is the
//!   point at the upper left, (−x, +y) seen looking down −Z; each row runs left to right (x
//!   increasing), and the rows run downward (y decreasing). The grid is centred on (xdec, ydec):
//!   the point of column i (from 0) and row j from the bottom is at
//!   `(xdec + (i − (nx − 1)/2)·delx, ydec + (j − (ny − 1)/2)·dely)` (the centring is inferred
//!   from OpticStudio's description of a grid "decentered relative to the base"; the row order
//!   is OpticStudio's).
//! - Units: sag and cross derivative "have dimensions and are therefore scaled, but first
//!   derivative values are dimensionless and are not scaled" (OpticStudio): here the sag,
//!   spacings and decentres are multiplied by the unit's length in mm and the cross derivative,
//!   a 1/length, divided by it (the physically consistent reading; whether OpticStudio divides
//!   is not stated).
//! - OpticStudio replaces a point without data by zero (the base alone) and a field that is not
//!   a number by zero; here a point without data stays without data ([`GridNode::valid`], the
//!   surface is undefined there) and anything that is not a number is an error.
//!
//! **Bounds and errors.** At most [`MAX_NODES`] points, refused from the header before anything
//! is allocated. Blank lines and comments (lines whose first character other than a blank is
//! `!`, as scripts write them above the header; Gwyddion's reader of the format skips them there
//! too) are allowed before the header, before the first data line and after the last, not among
//! the data lines; a short file, an extra data line, a wrong number of fields or a value that is
//! not a finite number is an error naming its line ([`DatError`]).
//!
//! The reader and writer are independent of the surface that uses them, so that an importer of
//! measured maps can reuse them: [`GridData::parse`] and [`GridData::to_dat`].

use std::fmt::Write;
use thiserror::Error;

/// The most points a grid may hold (1024 × 1024): with its 16 coefficients per cell the
/// surface keeps about 170 bytes per point.
pub const MAX_NODES: usize = 1 << 20;
/// The fewest points along each axis (OpticStudio's rule).
pub const MIN_POINTS: usize = 5;

/// A `.DAT` that cannot be read.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DatError {
    /// There is no header line.
    ///
    /// ```
    /// use spiralcam::surface::grid_sag::dat::{DatError, GridData};
    /// assert_eq!(GridData::parse("\n  \n"), Err(DatError::Empty));
    /// ```
    #[error("the file is empty: expected the header `nx ny delx dely unitflag xdec ydec`")]
    Empty,
    /// The header is not `nx ny delx dely unitflag xdec ydec` with valid values.
    ///
    /// ```
    /// use spiralcam::surface::grid_sag::dat::GridData;
    /// let e = GridData::parse("5 5 0.1 0.1 7 0 0\n").unwrap_err();
    /// assert!(e.to_string().starts_with("line 1: unit flag 7:"), "{e}");
    /// ```
    #[error("line {line}: {what} {value}: {allowed}")]
    Header {
        /// Line number, from 1.
        line: usize,
        /// Which value.
        what: &'static str,
        /// The text found.
        value: String,
        /// What would be accepted.
        allowed: String,
    },
    /// The header asks for more points than [`MAX_NODES`].
    ///
    /// ```
    /// use spiralcam::surface::grid_sag::dat::GridData;
    /// let e = GridData::parse("5000 5000 0.01 0.01 0 0 0\n").unwrap_err();
    /// assert!(e.to_string().contains("25000000 points"), "{e}");
    /// ```
    #[error("line {line}: {nx} × {ny} = {points} points: at most {max} (1024 × 1024)")]
    TooLarge {
        /// Line of the header.
        line: usize,
        /// Points along x.
        nx: usize,
        /// Points along y.
        ny: usize,
        /// nx·ny, saturated.
        points: usize,
        /// The limit.
        max: usize,
    },
    /// A data line is not `z dz/dx dz/dy d2z/dxdy [nodata]` with finite numbers.
    ///
    /// ```
    /// use spiralcam::surface::grid_sag::dat::GridData;
    /// let mut text = String::from("5 5 1 1 0 0 0\n");
    /// text.push_str("0 0 0\n");
    /// let e = GridData::parse(&text).unwrap_err();
    /// assert!(e.to_string().starts_with("line 2 (point 1 of 25"), "{e}");
    /// ```
    #[error(
        "line {line} (point {point} of {points}, column {column} of row {row} from the top): {text:?}: {reason}"
    )]
    Data {
        /// Line number, from 1.
        line: usize,
        /// The point's number in the file, from 1.
        point: usize,
        /// nx·ny.
        points: usize,
        /// Its column, from 1 at −x.
        column: usize,
        /// Its row, from 1 at the top (+y).
        row: usize,
        /// The line, shortened.
        text: String,
        /// What is wrong.
        reason: String,
    },
    /// The file ends before nx·ny data lines.
    ///
    /// ```
    /// use spiralcam::surface::grid_sag::dat::GridData;
    /// let e = GridData::parse("5 5 1 1 0 0 0\n0 0 0 0\n").unwrap_err();
    /// assert!(e.to_string().starts_with("the file ends after 1 of the 25 data lines"), "{e}");
    /// ```
    #[error(
        "the file ends after {found} of the {expected} data lines (nx·ny) the header at line {header_line} announces{blank}"
    )]
    Short {
        /// nx·ny.
        expected: usize,
        /// Data lines read.
        found: usize,
        /// Line of the header.
        header_line: usize,
        /// A note when a blank line cut the data short.
        blank: String,
    },
    /// There is more after the nx·ny data lines than blank lines.
    ///
    /// ```
    /// use spiralcam::surface::grid_sag::dat::GridData;
    /// let mut text = String::from("5 5 1 1 0 0 0\n");
    /// text.push_str(&"0 0 0 0\n".repeat(26));
    /// let e = GridData::parse(&text).unwrap_err();
    /// assert!(e.to_string().starts_with("line 27: more than the 25 data lines"), "{e}");
    /// ```
    #[error(
        "line {line}: more than the {expected} data lines (nx·ny) the header announces: {text:?}"
    )]
    Extra {
        /// Line number, from 1.
        line: usize,
        /// nx·ny.
        expected: usize,
        /// The line, shortened.
        text: String,
    },
}

/// The length unit of a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DatUnit {
    /// Flag 0.
    Millimetre,
    /// Flag 1.
    Centimetre,
    /// Flag 2.
    Inch,
    /// Flag 3.
    Metre,
}

impl DatUnit {
    /// The unit of flag `flag`, if it is one.
    pub fn from_flag(flag: i64) -> Option<Self> {
        Some(match flag {
            0 => Self::Millimetre,
            1 => Self::Centimetre,
            2 => Self::Inch,
            3 => Self::Metre,
            _ => return None,
        })
    }

    /// The flag written in a file.
    pub fn flag(self) -> u8 {
        match self {
            Self::Millimetre => 0,
            Self::Centimetre => 1,
            Self::Inch => 2,
            Self::Metre => 3,
        }
    }

    /// Millimetres per unit.
    pub fn mm(self) -> f64 {
        match self {
            Self::Millimetre => 1.0,
            Self::Centimetre => 10.0,
            Self::Inch => 25.4,
            Self::Metre => 1000.0,
        }
    }

    /// The unit's name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Millimetre => "mm",
            Self::Centimetre => "cm",
            Self::Inch => "in",
            Self::Metre => "m",
        }
    }
}

/// One point of the grid, in millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GridNode {
    /// Sag, mm.
    pub z_mm: f64,
    /// ∂z/∂x.
    pub dz_dx: f64,
    /// ∂z/∂y.
    pub dz_dy: f64,
    /// ∂²z/∂x∂y, 1/mm.
    pub d2z_dxdy_per_mm: f64,
    /// Whether the point has data (the file's nodata field is 0 or absent); a point without
    /// data has every value 0.
    pub valid: bool,
}

/// A grid of sag data in millimetres.
#[derive(Debug, Clone, PartialEq)]
pub struct GridData {
    /// Points along x, ≥ [`MIN_POINTS`].
    pub nx: usize,
    /// Points along y, ≥ [`MIN_POINTS`].
    pub ny: usize,
    /// Spacing along x, mm, > 0.
    pub dx_mm: f64,
    /// Spacing along y, mm, > 0.
    pub dy_mm: f64,
    /// Centre of the grid, mm.
    pub x_decenter_mm: f64,
    /// Centre of the grid, mm.
    pub y_decenter_mm: f64,
    /// The unit of the file read, and of the file written by [`GridData::to_dat`].
    pub unit: DatUnit,
    /// The points, row by row from the bottom (j = 0 at −y), x fastest: `nodes[j·nx + i]`.
    pub nodes: Vec<GridNode>,
    /// The line of the file that holds the first data point (the upper left), if read.
    pub first_data_line: Option<usize>,
}

/// A line shortened for an error message.
fn shown(text: &str) -> String {
    text.trim().chars().take(60).collect()
}

/// The fields of a line: separated by whitespace (or commas).
fn fields(line: &str) -> Vec<&str> {
    line.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|f| !f.is_empty())
        .collect()
}

/// Whether `line` is a comment: its first character other than a blank is `!`.
fn is_comment(line: &str) -> bool {
    line.trim_start().starts_with('!')
}

/// A finite number, or None.
fn number(f: &str) -> Option<f64> {
    f.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// The header's values: nx, ny, delx, dely (mm), unit, xdec, ydec (mm).
struct Header {
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    unit: DatUnit,
    xdec: f64,
    ydec: f64,
}

fn parse_header(line: usize, text: &str) -> Result<Header, DatError> {
    let f = fields(text);
    let bad = |what: &'static str, value: &str, allowed: &str| DatError::Header {
        line,
        what,
        value: value.to_string(),
        allowed: allowed.to_string(),
    };
    if f.len() != 7 {
        return Err(bad(
            "header",
            &format!("{:?} ({} fields)", shown(text), f.len()),
            "expected 7 values: nx ny delx dely unitflag xdec ydec",
        ));
    }
    let count = |what: &'static str, v: &str| -> Result<usize, DatError> {
        match v.parse::<usize>() {
            Ok(n) if n >= MIN_POINTS => Ok(n),
            _ => Err(bad(
                what,
                v,
                &format!("must be a whole number ≥ {MIN_POINTS}"),
            )),
        }
    };
    let (nx, ny) = (count("nx", f[0])?, count("ny", f[1])?);
    let spacing = |what: &'static str, v: &str| match number(v) {
        Some(d) if d != 0.0 => Ok(d.abs()),
        _ => Err(bad(what, v, "must be a finite number ≠ 0")),
    };
    let (dx, dy) = (spacing("delx", f[2])?, spacing("dely", f[3])?);
    let unit = f[4]
        .parse::<i64>()
        .ok()
        .and_then(DatUnit::from_flag)
        .ok_or_else(|| bad("unit flag", f[4], "must be 0 (mm), 1 (cm), 2 (in) or 3 (m)"))?;
    let decenter = |what: &'static str, v: &str| {
        number(v).ok_or_else(|| bad(what, v, "must be a finite number"))
    };
    let (xdec, ydec) = (decenter("xdec", f[5])?, decenter("ydec", f[6])?);
    let s = unit.mm();
    Ok(Header {
        nx,
        ny,
        dx: dx * s,
        dy: dy * s,
        unit,
        xdec: xdec * s,
        ydec: ydec * s,
    })
}

impl GridData {
    /// Reads a `.DAT` (see the module docs), converting to millimetres.
    pub fn parse(text: &str) -> Result<Self, DatError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut lines = text.lines().enumerate().map(|(k, l)| (k + 1, l));
        let (header_line, header) = loop {
            match lines.next() {
                None => return Err(DatError::Empty),
                Some((_, l)) if l.trim().is_empty() || is_comment(l) => continue,
                Some((k, l)) => break (k, parse_header(k, l)?),
            }
        };
        let points = header.nx.saturating_mul(header.ny);
        if points > MAX_NODES {
            return Err(DatError::TooLarge {
                line: header_line,
                nx: header.nx,
                ny: header.ny,
                points,
                max: MAX_NODES,
            });
        }
        let mut nodes = vec![GridNode::default(); points];
        let mut first_data_line = None;
        let mut count = 0;
        let mut blank = String::new();
        for (line, text) in lines {
            let comment = is_comment(text);
            if text.trim().is_empty() || comment {
                if count < points && count > 0 && blank.is_empty() {
                    let what = if comment { "a comment" } else { "blank" };
                    blank = format!(" (line {line} is {what}: data lines must follow one another)");
                }
                continue;
            }
            if count == points {
                return Err(DatError::Extra {
                    line,
                    expected: points,
                    text: shown(text),
                });
            }
            if !blank.is_empty() {
                break;
            }
            first_data_line.get_or_insert(line);
            let (column, row) = (count % header.nx, count / header.nx);
            let node = Self::parse_node(text, header.unit).map_err(|reason| DatError::Data {
                line,
                point: count + 1,
                points,
                column: column + 1,
                row: row + 1,
                text: shown(text),
                reason,
            })?;
            // File row `row` from the top is row ny − 1 − row from the bottom.
            nodes[(header.ny - 1 - row) * header.nx + column] = node;
            count += 1;
        }
        if count < points {
            return Err(DatError::Short {
                expected: points,
                found: count,
                header_line,
                blank,
            });
        }
        Ok(Self {
            nx: header.nx,
            ny: header.ny,
            dx_mm: header.dx,
            dy_mm: header.dy,
            x_decenter_mm: header.xdec,
            y_decenter_mm: header.ydec,
            unit: header.unit,
            nodes,
            first_data_line,
        })
    }

    /// One data line, converted to millimetres. A point flagged without data may carry any
    /// numbers, NaN included (they are not used); a point with data needs finite ones.
    fn parse_node(text: &str, unit: DatUnit) -> Result<GridNode, String> {
        let f = fields(text);
        if !(4..=5).contains(&f.len()) {
            return Err(format!(
                "expected 4 numbers z dz/dx dz/dy d2z/dxdy and an optional nodata flag, found {} fields",
                f.len()
            ));
        }
        let valid = match f.get(4) {
            None => true,
            Some(flag) => flag.parse::<i64>().map(|n| n == 0).map_err(|_| {
                format!("the nodata flag {flag:?} must be a whole number (0: data)")
            })?,
        };
        let mut v = [0.0; 4];
        for (k, (slot, name)) in v
            .iter_mut()
            .zip(["z", "dz/dx", "dz/dy", "d2z/dxdy"])
            .enumerate()
        {
            *slot = match f[k].parse::<f64>() {
                Ok(x) if x.is_finite() || !valid => x,
                _ => return Err(format!("{name} {:?} is not a finite number", f[k])),
            };
        }
        if !valid {
            // A point without data carries no values (OpticStudio reads them as zeros too).
            return Ok(GridNode::default());
        }
        let s = unit.mm();
        Ok(GridNode {
            z_mm: v[0] * s,
            dz_dx: v[1],
            dz_dy: v[2],
            d2z_dxdy_per_mm: v[3] / s,
            valid,
        })
    }

    /// The position of point (i, j) (column from −x, row from −y), mm.
    pub fn position(&self, i: usize, j: usize) -> (f64, f64) {
        (
            self.x_decenter_mm + (i as f64 - (self.nx - 1) as f64 / 2.0) * self.dx_mm,
            self.y_decenter_mm + (j as f64 - (self.ny - 1) as f64 / 2.0) * self.dy_mm,
        )
    }

    /// Point (i, j).
    pub fn node(&self, i: usize, j: usize) -> &GridNode {
        &self.nodes[j * self.nx + i]
    }

    /// The line of the file holding point (i, j), if the grid was read from one.
    pub fn line_of(&self, i: usize, j: usize) -> Option<usize> {
        self.first_data_line
            .map(|first| first + (self.ny - 1 - j) * self.nx + i)
    }

    /// Whether any point with data has a non-zero derivative (otherwise the derivatives are to
    /// be computed from the sags).
    pub fn has_derivatives(&self) -> bool {
        self.nodes
            .iter()
            .any(|n| n.valid && (n.dz_dx != 0.0 || n.dz_dy != 0.0 || n.d2z_dxdy_per_mm != 0.0))
    }

    /// The grid as `.DAT` text in [`GridData::unit`], numbers in Rust's shortest exact forms
    /// (decimal in the header, `1.25e-3` in the data; reading it back gives the same doubles
    /// when the unit is mm), every line with its nodata flag; points without data are written
    /// `0 0 0 0 1`.
    pub fn to_dat(&self) -> String {
        let s = self.unit.mm();
        let mut out = String::with_capacity(self.nodes.len() * 64 + 64);
        let _ = writeln!(
            out,
            "{} {} {} {} {} {} {}",
            self.nx,
            self.ny,
            self.dx_mm / s,
            self.dy_mm / s,
            self.unit.flag(),
            self.x_decenter_mm / s,
            self.y_decenter_mm / s
        );
        for row in (0..self.ny).rev() {
            for i in 0..self.nx {
                let n = self.node(i, row);
                if n.valid {
                    let _ = writeln!(
                        out,
                        "{:e} {:e} {:e} {:e} 0",
                        n.z_mm / s,
                        n.dz_dx,
                        n.dz_dy,
                        n.d2z_dxdy_per_mm * s
                    );
                } else {
                    out.push_str("0 0 0 0 1\n");
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 5 × 6 grid in cm whose sag is the point's number in the file.
    fn numbered(unit: u8) -> String {
        let mut t = format!("5 6 0.2 -0.1 {unit} 0.5 -1\n");
        for k in 0..30 {
            t.push_str(&format!("{k} 0.5 -0.25 2 {}\n", if k == 7 { 3 } else { 0 }));
        }
        t
    }

    #[test]
    fn rows_start_at_the_upper_left_and_run_down() {
        let g = GridData::parse(&numbered(0)).unwrap();
        // The first line is column 0 of the top row (j = ny − 1, +y); the last is (4, 0).
        assert_eq!(g.node(0, 5).z_mm, 0.0);
        assert_eq!(g.node(4, 5).z_mm, 4.0);
        assert_eq!(g.node(0, 4).z_mm, 5.0);
        assert_eq!(g.node(4, 0).z_mm, 29.0);
        assert_eq!(g.line_of(4, 0), Some(31));
        assert!(!g.node(2, 4).valid && g.node(1, 4).valid);
        // Centred on the decentre; |dely| taken.
        assert_eq!(g.position(0, 0), (0.5 - 0.4, -1.0 - 0.25));
        assert_eq!(g.position(4, 5), (0.5 + 0.4, -1.0 + 0.25));
    }

    #[test]
    fn units_scale_lengths_and_the_cross_derivative_only() {
        let g = GridData::parse(&numbered(1)).unwrap();
        let n = g.node(4, 0);
        assert_eq!(
            (n.z_mm, n.dz_dx, n.dz_dy, n.d2z_dxdy_per_mm),
            (290.0, 0.5, -0.25, 0.2)
        );
        assert_eq!(
            (g.dx_mm, g.dy_mm, g.x_decenter_mm, g.y_decenter_mm),
            (2.0, 1.0, 5.0, -10.0)
        );
        let g = GridData::parse(&numbered(2)).unwrap();
        assert_eq!(g.node(1, 5).z_mm, 25.4);
        assert_eq!(g.node(1, 5).d2z_dxdy_per_mm, 2.0 / 25.4);
        let g = GridData::parse(&numbered(3)).unwrap();
        assert_eq!(g.dx_mm, 200.0);
    }

    #[test]
    fn writing_and_reading_back_is_exact() {
        for unit in 0..4 {
            let g = GridData::parse(&numbered(unit)).unwrap();
            let again = GridData::parse(&g.to_dat()).unwrap();
            assert_eq!(again.nodes.len(), g.nodes.len());
            for (a, b) in again.nodes.iter().zip(&g.nodes) {
                assert_eq!(a.valid, b.valid);
                if a.valid {
                    let close = |p: f64, q: f64| (p - q).abs() <= 1e-15 * q.abs();
                    assert!(close(a.z_mm, b.z_mm) && close(a.d2z_dxdy_per_mm, b.d2z_dxdy_per_mm));
                    assert_eq!((a.dz_dx, a.dz_dy), (b.dz_dx, b.dz_dy));
                }
            }
        }
        let g = GridData::parse(&numbered(0)).unwrap();
        assert_eq!(
            GridData::parse(&g.to_dat()).unwrap(),
            GridData {
                first_data_line: Some(2),
                ..g
            }
        );
    }

    #[test]
    fn comments_are_skipped_around_the_data_not_among_it() {
        let plain = GridData::parse(&numbered(0)).unwrap();
        let text = numbered(0);
        let mut lines: Vec<&str> = text.lines().collect();
        let mut t = String::from("! Grid sag written by a script\r\n  ! units: mm\r\n\r\n");
        for (k, line) in lines.iter().enumerate() {
            t.push_str(line);
            t.push_str("\r\n");
            if k == 0 {
                t.push_str("! the data, from the upper left\r\n");
            }
        }
        t.push_str("! end\r\n\r\n");
        let g = GridData::parse(&t).unwrap();
        assert_eq!(
            g,
            GridData {
                first_data_line: Some(6),
                ..plain
            }
        );
        let e = GridData::parse(&t.replacen("4 0.5 -0.25", "4 x -0.25", 1)).unwrap_err();
        assert!(e.to_string().starts_with("line 10 (point 5 of 30"), "{e}");
        // Among the data a comment would shift every later point's line: refused like a gap.
        lines.insert(4, "! a comment");
        let e = GridData::parse(&lines.join("\n")).unwrap_err().to_string();
        assert!(
            e.starts_with("the file ends after 3 of the 30 data lines")
                && e.contains("line 5 is a comment"),
            "{e}"
        );
    }

    #[test]
    fn bad_files_name_their_line() {
        let cases = [
            (
                "4 5 1 1 0 0 0\n",
                "line 1: nx 4: must be a whole number ≥ 5",
            ),
            ("5 5 0 1 0 0 0\n", "line 1: delx 0:"),
            ("5 5 1 1 0 0\n", "line 1: header"),
            ("\n5 5 1 1 0 0 x\n", "line 2: ydec x:"),
        ];
        for (text, start) in cases {
            let e = GridData::parse(text).unwrap_err().to_string();
            assert!(e.starts_with(start), "{text:?}: {e}");
        }
        let mut t = numbered(0);
        t = t.replacen("3 0.5 -0.25 2 0", "3 0.5 nan 2 0", 1);
        let e = GridData::parse(&t).unwrap_err().to_string();
        assert!(
            e.starts_with("line 5 (point 4 of 30, column 4 of row 1 from the top)"),
            "{e}"
        );
        assert!(e.contains("dz/dy \"nan\" is not a finite number"), "{e}");
        let t = numbered(0).replacen("12 0.5 -0.25 2 0\n", "12 0.5 -0.25 2 0\n\n", 1);
        let e = GridData::parse(&t).unwrap_err().to_string();
        assert!(e.contains("line 15 is blank"), "{e}");
        let e = GridData::parse(&numbered(0).replacen("5 0.5", "5 0.5 1 1 1", 1))
            .unwrap_err()
            .to_string();
        assert!(e.contains("found 8 fields"), "{e}");
        assert!(GridData::parse(&(numbered(0) + "\n\n")).is_ok());
        // A point without data may hold NaN; one with data may not.
        let t = numbered(0).replacen("7 0.5 -0.25 2 3", "NaN NaN NaN NaN 3", 1);
        assert!(!GridData::parse(&t).unwrap().node(2, 4).valid);
        let t = numbered(0).replacen("7 0.5 -0.25 2 3", "NaN NaN NaN NaN 0", 1);
        assert!(GridData::parse(&t).is_err());
    }
}
