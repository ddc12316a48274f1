//! The data of a scattered surface: points `(x, y, z)` in mm read from CSV text, or a regular
//! height grid read from a small text format, both as a job's data file carries them
//! ([`crate::surface::DataFile`]).
//!
//! **CSV**: one point per line, `x, y, z` in mm, separated by commas, semicolons, tabs or
//! spaces. Blank lines and everything after a `#` are ignored; a first line whose fields are
//! not all numbers is a header and skipped. Any other line that is not three finite numbers is an
//! error naming its line number.
//!
//! **Grid**: a first (non-comment) line `grid x0_mm y0_mm dx_mm dy_mm nx ny`, then `ny` rows
//! of `nx` heights each (same separators): row `j` holds z at `y = y0 + j·dy`, its `i`-th
//! value is at `x = x0 + i·dx`. dx and dy are > 0; nx, ny ≥ 2.
//!
//! CSV points that happen to form a complete regular grid (every x of an evenly spaced set
//! with every y of another) are recognised as one, so that the grid-only Hermite method can
//! use them. Duplicate points (the same x and y, or closer than a millionth of the spacing)
//! are errors naming both lines.

use crate::field::FieldError;

/// The most points a data set may hold.
pub const MAX_POINTS: usize = 4_000_000;

/// The field every data error names, relative to the surface spec.
const FIELD: &str = "data";

/// A regular grid: `nx × ny` nodes `(x0 + i·dx, y0 + j·dy)`, heights row by row (`j·nx + i`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// First node, mm.
    pub x0: f64,
    /// First node, mm.
    pub y0: f64,
    /// Node spacing along x, mm, > 0.
    pub dx: f64,
    /// Node spacing along y, mm, > 0.
    pub dy: f64,
    /// Nodes along x, ≥ 2.
    pub nx: usize,
    /// Nodes along y, ≥ 2.
    pub ny: usize,
}

impl Grid {
    /// The node `(i, j)`, mm.
    pub fn node(&self, i: usize, j: usize) -> [f64; 2] {
        [self.x0 + i as f64 * self.dx, self.y0 + j as f64 * self.dy]
    }
}

/// Sample points of a surface: positions, heights and where each came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Samples {
    /// (x, y) per point, mm.
    pub points: Vec<[f64; 2]>,
    /// Height per point, mm.
    pub z: Vec<f64>,
    /// Line of the data text per point (1-based; for grids, the row's line).
    pub lines: Vec<usize>,
    /// The points form this grid, in its node order (index `j·nx + i`).
    pub grid: Option<Grid>,
}

/// One line of text split into its fields, comments stripped.
fn fields(line: &str) -> Vec<&str> {
    let body = line.split('#').next().unwrap_or("");
    body.split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|f| !f.is_empty())
        .collect()
}

/// Parses a field as a finite number.
fn number(f: &str) -> Option<f64> {
    f.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// An error about line `line` of the data.
fn line_error(line: usize, text: &str, what: impl Into<String>) -> FieldError {
    let shown: String = text.trim().chars().take(60).collect();
    FieldError::new(FIELD, format!("line {line}: {shown:?}"), what)
}

impl Samples {
    /// Reads CSV or grid text (see the module docs) and checks the points.
    pub fn parse(text: &str) -> Result<Self, FieldError> {
        let mut rows = text
            .lines()
            .enumerate()
            .map(|(k, l)| (k + 1, l, fields(l)))
            .filter(|(_, _, f)| !f.is_empty());
        let Some(first) = rows.next() else {
            return Err(FieldError::new(FIELD, "empty", "no data points"));
        };
        if first.2[0].eq_ignore_ascii_case("grid") {
            Self::parse_grid(first, rows)
        } else {
            Self::parse_csv(first, rows)
        }
    }

    fn parse_csv<'a>(
        first: (usize, &'a str, Vec<&'a str>),
        rows: impl Iterator<Item = (usize, &'a str, Vec<&'a str>)>,
    ) -> Result<Self, FieldError> {
        let header = first.2.iter().any(|f| number(f).is_none());
        let mut s = Self::empty();
        for (line, text, f) in std::iter::once(first).skip(header as usize).chain(rows) {
            if f.len() != 3 {
                return Err(line_error(
                    line,
                    text,
                    format!("expected 3 numbers x, y, z (mm), found {} fields", f.len()),
                ));
            }
            let v: Vec<f64> = f.iter().filter_map(|x| number(x)).collect();
            if v.len() != 3 {
                return Err(line_error(
                    line,
                    text,
                    "x, y and z must be finite numbers (mm)",
                ));
            }
            if s.points.len() == MAX_POINTS {
                return Err(FieldError::new(
                    FIELD,
                    format!("line {line}"),
                    format!("at most {MAX_POINTS} points"),
                ));
            }
            s.points.push([v[0], v[1]]);
            s.z.push(v[2]);
            s.lines.push(line);
        }
        s.grid = s.detect_grid();
        s.check_duplicates()?;
        Ok(s)
    }

    fn parse_grid<'a>(
        (line, text, head): (usize, &'a str, Vec<&'a str>),
        rows: impl Iterator<Item = (usize, &'a str, Vec<&'a str>)>,
    ) -> Result<Self, FieldError> {
        let bad = || {
            line_error(
                line,
                text,
                "expected `grid x0_mm y0_mm dx_mm dy_mm nx ny` with dx, dy > 0 and whole nx, ny ≥ 2",
            )
        };
        if head.len() != 7 {
            return Err(bad());
        }
        let v: Vec<f64> = head[1..].iter().filter_map(|f| number(f)).collect();
        let whole = |x: f64| x >= 2.0 && x.fract() == 0.0 && x <= MAX_POINTS as f64;
        if v.len() != 6 || v[2] <= 0.0 || v[3] <= 0.0 || !whole(v[4]) || !whole(v[5]) {
            return Err(bad());
        }
        let grid = Grid {
            x0: v[0],
            y0: v[1],
            dx: v[2],
            dy: v[3],
            nx: v[4] as usize,
            ny: v[5] as usize,
        };
        if grid.nx * grid.ny > MAX_POINTS {
            return Err(line_error(
                line,
                text,
                format!("at most {MAX_POINTS} points"),
            ));
        }
        let mut z = Vec::with_capacity(grid.nx * grid.ny);
        let mut lines = Vec::with_capacity(grid.nx * grid.ny);
        let mut count = 0;
        for (line, text, f) in rows {
            if count == grid.ny {
                return Err(line_error(
                    line,
                    text,
                    format!("more than ny = {} rows", grid.ny),
                ));
            }
            if f.len() != grid.nx {
                return Err(line_error(
                    line,
                    text,
                    format!("expected nx = {} heights, found {}", grid.nx, f.len()),
                ));
            }
            for x in &f {
                z.push(number(x).ok_or_else(|| {
                    line_error(line, text, "heights must be finite numbers (mm)")
                })?);
                lines.push(line);
            }
            count += 1;
        }
        if count != grid.ny {
            return Err(FieldError::new(
                FIELD,
                format!("{count} rows"),
                format!("the grid header asks for ny = {} rows", grid.ny),
            ));
        }
        Self::from_grid(grid, z, lines)
    }

    fn empty() -> Self {
        Self {
            points: Vec::new(),
            z: Vec::new(),
            lines: Vec::new(),
            grid: None,
        }
    }

    /// A grid data set from its heights (row by row, `j·nx + i`); `lines` per node, or empty
    /// to number the nodes from 1.
    pub fn from_grid(grid: Grid, z: Vec<f64>, lines: Vec<usize>) -> Result<Self, FieldError> {
        let n = grid.nx * grid.ny;
        if z.len() != n || !(grid.dx > 0.0 && grid.dy > 0.0 && grid.nx >= 2 && grid.ny >= 2) {
            return Err(FieldError::new(
                FIELD,
                format!("{} heights", z.len()),
                format!("a grid of {} × {} nodes with dx, dy > 0", grid.nx, grid.ny),
            ));
        }
        let points = (0..grid.ny)
            .flat_map(|j| (0..grid.nx).map(move |i| grid.node(i, j)))
            .collect();
        let lines = if lines.len() == n {
            lines
        } else {
            (1..=n).collect()
        };
        Ok(Self {
            points,
            z,
            lines,
            grid: Some(grid),
        })
    }

    /// A data set from points `(x, y, z)`, numbered from line 1.
    pub fn from_points(points: &[[f64; 3]]) -> Result<Self, FieldError> {
        let mut s = Self::empty();
        for (k, p) in points.iter().enumerate() {
            if !p.iter().all(|v| v.is_finite()) {
                return Err(FieldError::new(
                    FIELD,
                    format!("point {}", k + 1),
                    "x, y and z must be finite numbers (mm)",
                ));
            }
            s.points.push([p[0], p[1]]);
            s.z.push(p[2]);
            s.lines.push(k + 1);
        }
        if s.points.len() > MAX_POINTS {
            return Err(FieldError::new(
                FIELD,
                s.points.len(),
                format!("at most {MAX_POINTS} points"),
            ));
        }
        s.grid = s.detect_grid();
        s.check_duplicates()?;
        Ok(s)
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// No points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Exact duplicates: two points with the same x and y, named by their lines.
    fn check_duplicates(&self) -> Result<(), FieldError> {
        let mut order: Vec<usize> = (0..self.len()).collect();
        order.sort_by(|&a, &b| {
            let (p, q) = (self.points[a], self.points[b]);
            p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]))
        });
        for w in order.windows(2) {
            if self.points[w[0]] == self.points[w[1]] {
                let (a, b) = (w[0].min(w[1]), w[0].max(w[1]));
                return Err(duplicate_error(self, a, b, "the same x and y"));
            }
        }
        Ok(())
    }

    /// The grid the points form, if they form one: sorted distinct x and y evenly spaced
    /// (to 1e-9 of the spacing) and every combination present exactly once.
    fn detect_grid(&mut self) -> Option<Grid> {
        let axis = |k: usize| -> Option<(f64, f64, usize)> {
            let mut v: Vec<f64> = self.points.iter().map(|p| p[k]).collect();
            v.sort_by(f64::total_cmp);
            v.dedup();
            if v.len() < 2 {
                return None;
            }
            let step = (v[v.len() - 1] - v[0]) / (v.len() - 1) as f64;
            let even = v
                .iter()
                .enumerate()
                .all(|(i, x)| (x - (v[0] + i as f64 * step)).abs() <= 1e-9 * step);
            even.then_some((v[0], step, v.len()))
        };
        let (x0, dx, nx) = axis(0)?;
        let (y0, dy, ny) = axis(1)?;
        if nx * ny != self.len() {
            return None;
        }
        let mut slot = vec![usize::MAX; nx * ny];
        for (k, p) in self.points.iter().enumerate() {
            let i = ((p[0] - x0) / dx).round() as usize;
            let j = ((p[1] - y0) / dy).round() as usize;
            let s = slot.get_mut(j * nx + i)?;
            if *s != usize::MAX {
                return None;
            }
            *s = k;
        }
        let grid = Grid {
            x0,
            y0,
            dx,
            dy,
            nx,
            ny,
        };
        // Put the points in node order, with the grid's exact node positions.
        self.z = slot.iter().map(|&k| self.z[k]).collect();
        self.lines = slot.iter().map(|&k| self.lines[k]).collect();
        self.points = (0..ny)
            .flat_map(|j| (0..nx).map(move |i| grid.node(i, j)))
            .collect();
        Some(grid)
    }
}

/// Two points that cannot both be interpolated, named by their lines.
pub fn duplicate_error(s: &Samples, a: usize, b: usize, why: &str) -> FieldError {
    let (la, lb) = (s.lines[a].min(s.lines[b]), s.lines[a].max(s.lines[b]));
    let p = s.points[a];
    FieldError::new(
        FIELD,
        format!("lines {la} and {lb}"),
        format!(
            "duplicate points: ({}, {}) mm and ({}, {}) mm have {why}",
            p[0], p[1], s.points[b][0], s.points[b][1]
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_with_header_comments_and_separators() {
        let text = "# measured\nx_mm, y_mm, z_mm\n0,0,1\n1;0;2 # trailing\n\n0\t1\t3\n1 1 4\n";
        let s = Samples::parse(text).unwrap();
        assert_eq!(s.len(), 4);
        // A complete 2 × 2 grid, in node order.
        let g = s.grid.unwrap();
        assert_eq!((g.nx, g.ny, g.dx, g.dy), (2, 2, 1.0, 1.0));
        assert_eq!(s.z, vec![1.0, 2.0, 3.0, 4.0]);
        assert_eq!(s.lines, vec![3, 4, 6, 7]);
        assert_eq!(s.points[3], [1.0, 1.0]);
    }

    #[test]
    fn scattered_csv_is_not_a_grid() {
        let s = Samples::parse("0,0,1\n1,0,2\n0,1,3\n1,1,4\n0.5,0.5,0\n").unwrap();
        assert!(s.grid.is_none());
        assert_eq!(s.lines, vec![1, 2, 3, 4, 5]);
        // Uneven x values.
        let s = Samples::parse("0,0,1\n1,0,2\n3,0,3\n0,1,1\n1,1,2\n3,1,3\n").unwrap();
        assert!(s.grid.is_none());
    }

    #[test]
    fn malformed_lines_are_named() {
        let e = Samples::parse("x,y,z\n0,0,1\n1,0\n").unwrap_err();
        assert_eq!(e.field, "data");
        assert!(e.value.starts_with("line 3:"), "{e}");
        assert!(e.allowed.contains("found 2 fields"), "{e}");
        let e = Samples::parse("0,0,1\n1,0,abc\n").unwrap_err();
        assert!(e.value.starts_with("line 2:"), "{e}");
        let e = Samples::parse("0,0,1\n1,0,inf\n").unwrap_err();
        assert!(e.value.starts_with("line 2:"), "{e}");
        let e = Samples::parse("# nothing\n\n").unwrap_err();
        assert_eq!(e.allowed, "no data points");
    }

    #[test]
    fn duplicates_name_both_lines() {
        let e = Samples::parse("0,0,1\n1,0,2\n0.5,0.5,3\n1,0,2.5\n").unwrap_err();
        assert_eq!(e.value, "lines 2 and 4", "{e}");
        assert!(e.allowed.contains("duplicate"), "{e}");
    }

    #[test]
    fn grid_text() {
        let text = "# heights\ngrid -1 2 0.5 0.25 3 2\n1 2 3\n4,5,6\n";
        let s = Samples::parse(text).unwrap();
        let g = s.grid.unwrap();
        assert_eq!(
            (g.x0, g.y0, g.dx, g.dy, g.nx, g.ny),
            (-1.0, 2.0, 0.5, 0.25, 3, 2)
        );
        assert_eq!(s.points[5], [0.0, 2.25]);
        assert_eq!(s.z[5], 6.0);
        assert_eq!(s.lines[4], 4);
        for (text, line) in [
            ("grid 0 0 1 1 3\n", 1),
            ("grid 0 0 -1 1 2 2\n1 2\n3 4\n", 1),
            ("grid 0 0 1 1 2.5 2\n", 1),
            ("grid 0 0 1 1 2 2\n1 2\n3\n", 3),
            ("grid 0 0 1 1 2 2\n1 2\n3 x\n", 3),
            ("grid 0 0 1 1 2 2\n1 2\n3 4\n5 6\n", 4),
        ] {
            let e = Samples::parse(text).unwrap_err();
            assert!(
                e.value.starts_with(&format!("line {line}:")),
                "{text:?}: {e}"
            );
        }
        let e = Samples::parse("grid 0 0 1 1 2 3\n1 2\n3 4\n").unwrap_err();
        assert!(e.allowed.contains("ny = 3"), "{e}");
    }
}
