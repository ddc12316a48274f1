//! CSV point clouds, the export of profilometers and coordinate measuring machines: one point
//! per line under a header that names the columns and their units.
//!
//! - **Header** (required, the first line that is not blank or a comment): the three columns
//!   `x_<unit>`, `y_<unit>`, `z_<unit>` in any order, each unit one of `mm`, `um` (also `µm`),
//!   `nm`; names are case-insensitive, surrounding spaces and double quotes are ignored. Any
//!   other column, a missing or repeated one, or a header of numbers is an error: the units are
//!   never guessed.
//! - **Separator**: taken from the header line: a comma if it has one, else a semicolon, else a
//!   tab, else runs of spaces. Data lines use the same one; decimal commas are not numbers.
//! - **Comments**: everything after a `#`; blank lines are skipped. A UTF-8 byte-order mark at
//!   the start is dropped.
//! - **Numbers**: Rust's decimal floating-point syntax (`-1.5e-3`); each line holds exactly one
//!   number per header column. NaN and infinities are errors: a point without a value is left
//!   out of the file, there is no nodata token.
//! - **Output**: [`MeasuredData::Cloud`], every value converted to millimetres (`um` × 10⁻³,
//!   `nm` × 10⁻⁶), points in file order. Errors name the line (1-based, counting every line)
//!   and the column.
//!
//! Limits: [`super::MAX_FILE_BYTES`] of text, [`super::MAX_CLOUD_POINTS`] points.

use super::{
    MAX_CLOUD_POINTS, MAX_FILE_BYTES, MeasuredData, MeasuredError, MeasuredMap, PointCloud,
    check_limit,
};

/// A header column: which coordinate, and millimetres per file unit.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Column {
    axis: usize,
    mm_per_unit: f64,
}

/// How the fields of a line are separated.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Separator {
    Char(char),
    Spaces,
}

impl Separator {
    /// The separator the header line uses.
    fn of(header: &str) -> Self {
        [',', ';', '\t']
            .into_iter()
            .find(|c| header.contains(*c))
            .map_or(Separator::Spaces, Separator::Char)
    }

    fn split(self, line: &str) -> Vec<&str> {
        match self {
            Separator::Char(c) => line.split(c).map(str::trim).collect(),
            Separator::Spaces => line.split_whitespace().collect(),
        }
    }
}

/// A header name's column, if it is one.
fn column(name: &str) -> Option<Column> {
    let name = name.trim().trim_matches('"').trim().to_lowercase();
    let (axis, unit) = name.split_once('_')?;
    let axis = ["x", "y", "z"].iter().position(|a| *a == axis)?;
    let mm_per_unit = match unit {
        "mm" => 1.0,
        "um" | "µm" | "μm" => 1e-3,
        "nm" => 1e-6,
        _ => return None,
    };
    Some(Column { axis, mm_per_unit })
}

/// The columns of the header line `line` (number `n`).
fn header(file: &str, n: usize, fields: &[&str]) -> Result<Vec<Column>, MeasuredError> {
    let mut columns: Vec<Column> = Vec::with_capacity(fields.len());
    for (k, f) in fields.iter().enumerate() {
        let c = column(f).ok_or_else(|| {
            MeasuredError::line(
                file,
                n,
                format!(
                    "header column {} = {f:?}: expected x_<unit>, y_<unit> or z_<unit> with \
                     unit mm, um or nm (a header naming the columns and units is required, \
                     e.g. x_mm,y_mm,z_um)",
                    k + 1
                ),
            )
        })?;
        if columns.iter().any(|o| o.axis == c.axis) {
            return Err(MeasuredError::line(
                file,
                n,
                format!(
                    "header column {} = {f:?}: that coordinate is named twice",
                    k + 1
                ),
            ));
        }
        columns.push(c);
    }
    if columns.len() != 3 {
        return Err(MeasuredError::line(
            file,
            n,
            format!(
                "the header names {} columns: expected x, y and z, each with its unit",
                columns.len()
            ),
        ));
    }
    Ok(columns)
}

/// The text of `bytes`, without a leading byte-order mark.
fn text<'a>(file: &str, bytes: &'a [u8]) -> Result<&'a str, MeasuredError> {
    let s = std::str::from_utf8(bytes).map_err(|e| {
        let good = &bytes[..e.valid_up_to()];
        let line = good.iter().filter(|b| **b == b'\n').count() + 1;
        MeasuredError::line(file, line, "not UTF-8 text")
    })?;
    Ok(s.strip_prefix('\u{feff}').unwrap_or(s))
}

/// One data line's point, mm.
fn point(
    file: &str,
    n: usize,
    fields: &[&str],
    columns: &[Column],
    names: &[&str],
) -> Result<[f64; 3], MeasuredError> {
    if fields.len() != columns.len() {
        return Err(MeasuredError::line(
            file,
            n,
            format!(
                "{} fields: expected {} ({})",
                fields.len(),
                columns.len(),
                names.join(", ")
            ),
        ));
    }
    let mut p = [0.0; 3];
    for (k, (f, c)) in fields.iter().zip(columns).enumerate() {
        let bad = |what: &str| {
            let shown: String = f.chars().take(40).collect();
            MeasuredError::line(
                file,
                n,
                format!("column {} ({}) = {shown:?}: {what}", k + 1, names[k].trim()),
            )
        };
        let v: f64 = f.parse().map_err(|_| {
            bad(if f.contains(',') {
                "expected a number (decimal commas are not accepted)"
            } else {
                "expected a number"
            })
        })?;
        if !v.is_finite() {
            return Err(bad(
                "must be finite: leave a point without a value out of the file",
            ));
        }
        p[c.axis] = v * c.mm_per_unit;
    }
    Ok(p)
}

/// Reads a CSV point cloud (see the module docs) from the file `file`'s bytes.
pub fn read(file: &str, bytes: &[u8]) -> Result<MeasuredMap, MeasuredError> {
    check_limit(file, "size (bytes)", bytes.len() as u64, MAX_FILE_BYTES)?;
    let mut lines = text(file, bytes)?
        .lines()
        .enumerate()
        .map(|(k, l)| (k + 1, l.split('#').next().unwrap_or("")))
        .filter(|(_, l)| !l.trim().is_empty());
    let Some((hn, hline)) = lines.next() else {
        return Err(MeasuredError::line(file, 1, "no header and no data"));
    };
    let sep = Separator::of(hline);
    let names = sep.split(hline);
    let columns = header(file, hn, &names)?;
    let mut points = Vec::new();
    for (n, line) in lines {
        check_limit(
            file,
            "number of points",
            points.len() as u64 + 1,
            MAX_CLOUD_POINTS,
        )?;
        points.push(point(file, n, &sep.split(line), &columns, &names)?);
    }
    if points.is_empty() {
        return Err(MeasuredError::line(file, hn, "a header but no points"));
    }
    let units: Vec<String> = names.iter().map(|n| n.trim().to_string()).collect();
    Ok(MeasuredMap::new(
        MeasuredData::Cloud(PointCloud { points }),
        format!("CSV point cloud {file}, columns {}", units.join(", ")),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cloud(text: &str) -> Vec<[f64; 3]> {
        match read("t.csv", text.as_bytes()).unwrap().data {
            MeasuredData::Cloud(c) => c.points,
            MeasuredData::Grid(_) => panic!("a CSV is a cloud"),
        }
    }

    fn error(text: &[u8]) -> String {
        read("t.csv", text).unwrap_err().to_string()
    }

    #[test]
    fn columns_in_any_order_and_units_convert_to_mm() {
        let p = cloud("\u{feff}# probe scan\nz_nm; X_UM ;y_mm\n\n1500;2000;-3 # a point\n");
        assert_eq!(p.len(), 1);
        assert!((p[0][0] - 2.0).abs() < 1e-15);
        assert_eq!(p[0][1], -3.0);
        assert!((p[0][2] - 1.5e-3).abs() < 1e-18);
        let p = cloud("\"x_mm\"\t\"y_mm\"\t\"z_µm\"\n1\t2\t3\n4\t5\t6\n");
        assert_eq!(p[1][..2], [4.0, 5.0]);
        assert!((p[1][2] - 6e-3).abs() < 1e-18);
        let p = cloud("x_mm y_mm z_mm\n 1   2\t3\n");
        assert_eq!(p, vec![[1.0, 2.0, 3.0]]);
    }

    #[test]
    fn errors_name_line_column_and_what_was_expected() {
        assert_eq!(
            error(b"x_mm,y_mm,z_mm\n1,2,3\n\n1,2\n"),
            "t.csv: line 4: 2 fields: expected 3 (x_mm, y_mm, z_mm)"
        );
        assert_eq!(
            error(b"x_mm,y_mm,z_mm\n1,2,nan\n"),
            "t.csv: line 2: column 3 (z_mm) = \"nan\": must be finite: leave a point without a \
             value out of the file"
        );
        assert!(error(b"x_mm,y_mm,z_mm\n1,inf,0\n").contains("column 2 (y_mm)"));
        assert!(error(b"1,2,3\n").contains("line 1: header column 1 = \"1\""));
        assert!(error(b"x_mm,y_in,z_mm\n").contains("header column 2 = \"y_in\""));
        assert!(error(b"x_mm,x_um,z_mm\n").contains("named twice"));
        assert!(error(b"x_mm,z_mm\n1,2\n").contains("names 2 columns"));
        assert!(error(b"x_mm;y_mm;z_mm\n1,5;2;3\n").contains("decimal commas"));
        assert!(error(b"# only\nx_mm,y_mm,z_mm\n").contains("line 2: a header but no points"));
        assert!(error(b"").contains("line 1: no header and no data"));
        assert!(error(b"x_mm,y_mm,z_mm\n1,2,3\n\xff\n").contains("line 3: not UTF-8"));
    }
}
