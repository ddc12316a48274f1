//! The fast tool servo's gridded table, as a controller's two-dimensional compensation table
//! takes it: W over a grid of spindle angle (columns) × X (rows), written as a Delta Tau PMAC
//! `DEFINE COMP` table ([`write_pmac`]) and as a CSV matrix of the same grid ([`write_csv`]).
//! The grid is computed by the dynamics ([`crate::dynamics::fts_grid`]); this module holds the
//! table as the controller holds it ([`CompTable`], with [`CompTable::correction_at`], the
//! controller's lookup) and writes it.
//!
//! **The format**, as the Turbo PMAC/PMAC2 Software Reference describes `DEFINE COMP`
//! (two-dimensional) and the Turbo PMAC User Manual its use (section "Setting Up the Servo
//! Loop", 2D compensation tables, and "Active Calculation of Corrections"); the PMAC 2 Software
//! Reference's text is the same:
//! - `DEFINE COMP {Rows}.{Columns},#{RowMotor}[D],#{ColumnMotor}[D],#{TargetMotor},{RowSpan},
//!   {ColumnSpan}`, sent with the table's owner motor addressed (here the servo's, `#w`); the
//!   user manual's example is `DEFINE COMP 15.20, #1, #2, #3, 20000, 15000`. `D` after a source
//!   motor reads its desired (commanded) position instead of its actual one.
//! - The spans are in encoder counts of the source motors. **The RowMotor's position runs
//!   along a row**: "the count spacing between columns in the table is {RowSpan} divided by
//!   {Columns}", and between rows {ColumnSpan} divided by {Rows}. So with rows X and columns C,
//!   as here, the RowMotor is the spindle (C) and the ColumnMotor is X:
//!   `DEFINE COMP rows.cols,#c,#x,#w,counts_per_rev,x_span`.
//! - (Rows+1)·(Columns+1) − 1 integer entries follow, separated by spaces or carriage returns,
//!   in 1/16 count of the target motor: row 0 (the ColumnMotor at zero) from one column spacing
//!   to {RowSpan}, then each further row from the RowMotor's zero to {RowSpan}. The entry at
//!   both motors' zero is not sent: the correction there is zero by definition, so the table's
//!   origin (X = 0, C = 0) is zero.
//! - A source position outside 0…{Span} is rolled over into it before the correction is
//!   computed; between the four entries around it the correction is interpolated linearly
//!   (bilinearly) and added to the target's desired position; `I51 = 1` enables the tables.
//!
//! **What we chose or inferred** (no vendor file was available to compare with):
//! - The spindle's span is exactly one revolution (`c_counts_per_rev`), so the column at 360° is
//!   the column at 0° and the table wraps with the spindle however many turns it has made.
//! - X's span S covers the path's largest |X| and one row spacing more, and the row at the
//!   span's far end stands for X = 0 again, reached by rollover: with X positive, rows
//!   0…rows − 1 are at X = j·spacing and the last row holds the centre's W, so that X a count
//!   below zero (the centre, where the path ends) reads the centre and not the rim; with X
//!   negative (`output.x_sign = -1`) the motor's positions −S…0 roll over to 0…S, so row 0 is
//!   X = 0, row j ≥ 1 is X = j·spacing − S, and the last row is X = 0 again. The interval
//!   between the part's edge and the rolled-over end is never on the path.
//! - Spacings are whole counts (the column count divides `c_counts_per_rev`): the manual gives
//!   the spacing as a quotient and does not say how a fraction is rounded.
//! - `{Rows}.{Columns}` is read as two whole numbers around the point, trailing zeros
//!   included, as the manual's own example `15.20` (20 columns) needs.
//! - Entries are held to ±(2²³ − 1), a 24-bit word (Turbo PMAC's data memory; not stated in the
//!   pages read).
//! - The motors' zeros are the program's X = 0 (the spindle axis) and C = 0; an axis definition
//!   with an offset moves the table with it.
//! - Lines hold at most [`ENTRIES_PER_LINE`] entries (under 255 characters), each table row
//!   starting a line; comments start with `;`.
//!
//! The **CSV** is the same grid in the program's units: a header `x_mm/c_deg` and the columns'
//! angles 0…360°, then one line per row: the X it stands for, mm (0 twice: the first and the
//! rolled-over last row), and W at each column, mm (the table's entry in mm plus the offset,
//! [`CompTable::w_offset_mm`]), to 1 pm.

use super::NcError;
use super::number::push_fixed;
use std::io::Write;

/// The most entries on one line of the PMAC text.
pub const ENTRIES_PER_LINE: usize = 16;

/// The largest entry, 1/16 counts (a 24-bit word).
pub const MAX_ENTRY: i64 = (1 << 23) - 1;

/// Decimals of the CSV's numbers (mm and degrees): 1 pm.
const DECIMALS_CSV: u32 = 9;

/// Bytes of the comments, the `DEFINE COMP` line and the CSV's header label, at most.
const MAX_HEAD_BYTES: u64 = 4096;

/// The most bytes the PMAC text and the CSV of a table of `entries` entries weigh together:
/// an entry is at most 9 bytes in the PMAC text (`-8388607` and a separator) and 17 in the
/// CSV (a W within ±1000 mm at 9 decimals and a comma), and each row's X and column's angle
/// at most 17 more, of which there are fewer than entries.
pub fn max_bytes(entries: u64) -> u64 {
    entries.saturating_mul(9 + 17 + 17) + MAX_HEAD_BYTES
}

/// The table's source and target motors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Motors {
    /// X: the ColumnMotor (its position selects the row).
    pub x: u8,
    /// The spindle C: the RowMotor (its position selects the column).
    pub c: u8,
    /// The servo W: the target, and the table's owner.
    pub w: u8,
    /// The sources' desired positions (`D`) rather than their actual ones.
    pub desired_position: bool,
}

/// A two-dimensional compensation table of the servo's W, as the controller holds it.
#[derive(Debug, Clone, PartialEq)]
pub struct CompTable {
    /// Intervals along X (PMAC's Rows); the grid has `rows + 1` rows.
    pub rows: usize,
    /// Intervals along C (PMAC's Columns); the grid has `columns + 1` columns, the last at 360°.
    pub columns: usize,
    /// Spacing of the rows, counts of X.
    pub x_spacing_counts: u64,
    /// Counts of X per mm.
    pub x_counts_per_mm: f64,
    /// Counts of C per revolution: the columns' span.
    pub c_counts_per_rev: u64,
    /// Counts of W per mm.
    pub w_counts_per_mm: f64,
    /// X negative: row j ≥ 1 stands for X = j·spacing − span; else row j < rows for
    /// X = j·spacing, and the last row for X = 0 rolled over (module docs).
    pub x_negative: bool,
    /// Entries, 1/16 count of W, row by row, `(rows + 1)·(columns + 1)`; the first is 0.
    pub entries: Vec<i64>,
    /// W where the table reads 0 (at the origin), mm: the servo's programmed position, to which
    /// the table adds.
    pub w_offset_mm: f64,
    /// The motors.
    pub motors: Motors,
}

impl CompTable {
    /// The rows' span, counts of X.
    pub fn x_span_counts(&self) -> u64 {
        self.rows as u64 * self.x_spacing_counts
    }

    /// The columns' spacing, counts of C.
    pub fn c_spacing_counts(&self) -> u64 {
        self.c_counts_per_rev / self.columns as u64
    }

    /// The machine X that row `j` stands for, mm: 0 for the first and the last row (module
    /// docs).
    pub fn row_x_mm(&self, j: usize) -> f64 {
        let q = (j as u64 * self.x_spacing_counts) as f64;
        match (self.x_negative, j) {
            (_, 0) => 0.0,
            (_, j) if j == self.rows => 0.0,
            (false, _) => q / self.x_counts_per_mm,
            (true, _) => (q - self.x_span_counts() as f64) / self.x_counts_per_mm,
        }
    }

    /// The machine C of column `k`, degrees in [0, 360].
    pub fn column_c_deg(&self, k: usize) -> f64 {
        360.0 * k as f64 / self.columns as f64
    }

    /// The entry at row `j`, column `k`, 1/16 count.
    pub fn entry(&self, j: usize, k: usize) -> i64 {
        self.entries[j * (self.columns + 1) + k]
    }

    /// The correction the controller computes with X at `x_counts` and C at `c_counts` (any
    /// number of turns), 1/16 count: each position rolled over into its span, then the four
    /// entries around it interpolated bilinearly.
    pub fn correction_at(&self, x_counts: f64, c_counts: f64) -> f64 {
        let locate = |pos: f64, span: u64, spacing: u64, cells: usize| {
            let p = pos.rem_euclid(span as f64) / spacing as f64;
            let i = (p.floor().max(0.0) as usize).min(cells - 1);
            (i, p - i as f64)
        };
        let (j, v) = locate(
            x_counts,
            self.x_span_counts(),
            self.x_spacing_counts,
            self.rows,
        );
        let (k, u) = locate(
            c_counts,
            self.c_counts_per_rev,
            self.c_spacing_counts(),
            self.columns,
        );
        let e = |j, k| self.entry(j, k) as f64;
        let low = e(j, k) + u * (e(j, k + 1) - e(j, k));
        let high = e(j + 1, k) + u * (e(j + 1, k + 1) - e(j + 1, k));
        low + v * (high - low)
    }

    /// W the table gives at machine X `x_mm` and C `c_deg`, mm: the offset plus the correction.
    pub fn w_mm_at(&self, x_mm: f64, c_deg: f64) -> f64 {
        let x = x_mm * self.x_counts_per_mm;
        let c = c_deg / 360.0 * self.c_counts_per_rev as f64;
        self.w_offset_mm + self.correction_at(x, c) / (16.0 * self.w_counts_per_mm)
    }

    /// The `DEFINE COMP` line.
    pub fn define_line(&self) -> String {
        let d = if self.motors.desired_position {
            "D"
        } else {
            ""
        };
        format!(
            "DEFINE COMP {}.{},#{}{d},#{}{d},#{},{},{}",
            self.rows,
            self.columns,
            self.motors.c,
            self.motors.x,
            self.motors.w,
            self.c_counts_per_rev,
            self.x_span_counts()
        )
    }
}

/// Writes `table` as PMAC text: `comments` (each line after `; `), the owner motor addressed,
/// the `DEFINE COMP` line and the entries (module docs). Returns the bytes written.
pub fn write_pmac(
    out: &mut dyn Write,
    table: &CompTable,
    comments: &[String],
) -> Result<u64, NcError> {
    let mut text = String::new();
    for c in comments {
        text.push_str("; ");
        text.push_str(&super::ascii_comment(c));
        text.push('\n');
    }
    text.push_str(&format!("#{}\n{}\n", table.motors.w, table.define_line()));
    let mut bytes = text.len() as u64;
    out.write_all(text.as_bytes())?;
    let mut line = String::with_capacity(ENTRIES_PER_LINE * 10);
    for j in 0..=table.rows {
        // The origin's entry is implied.
        let first = usize::from(j == 0);
        let row = &table.entries[j * (table.columns + 1) + first..(j + 1) * (table.columns + 1)];
        for chunk in row.chunks(ENTRIES_PER_LINE) {
            line.clear();
            for (i, e) in chunk.iter().enumerate() {
                if i > 0 {
                    line.push(' ');
                }
                line.push_str(&e.to_string());
            }
            line.push('\n');
            out.write_all(line.as_bytes())?;
            bytes += line.len() as u64;
        }
    }
    out.flush()?;
    Ok(bytes)
}

/// Writes `table` as a CSV matrix (module docs). Returns the bytes written.
pub fn write_csv(out: &mut dyn Write, table: &CompTable) -> Result<u64, NcError> {
    let mut line: Vec<u8> = Vec::with_capacity((table.columns + 2) * 14);
    line.extend_from_slice(b"x_mm/c_deg");
    for k in 0..=table.columns {
        line.push(b',');
        push_fixed(&mut line, table.column_c_deg(k), DECIMALS_CSV);
    }
    line.push(b'\n');
    let mut bytes = line.len() as u64;
    out.write_all(&line)?;
    let per_mm = 16.0 * table.w_counts_per_mm;
    for j in 0..=table.rows {
        line.clear();
        push_number(&mut line, table.row_x_mm(j), "X")?;
        for k in 0..=table.columns {
            line.push(b',');
            let w = table.w_offset_mm + table.entry(j, k) as f64 / per_mm;
            push_number(&mut line, w, "W")?;
        }
        line.push(b'\n');
        out.write_all(&line)?;
        bytes += line.len() as u64;
    }
    out.flush()?;
    Ok(bytes)
}

/// Appends `v` at the CSV's decimals, or the error naming the value.
fn push_number(line: &mut Vec<u8>, v: f64, what: &'static str) -> Result<(), NcError> {
    match push_fixed(line, v, DECIMALS_CSV) {
        true => Ok(()),
        false => Err(NcError::Unwritable {
            index: 0,
            what,
            value: v,
            at: None,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2 × 4 table over X 0…2 mm (1000 counts/mm) and a turn of 400 counts, W in 1 µm counts.
    fn table(x_negative: bool) -> CompTable {
        let (rows, columns) = (2, 4);
        let entries = (0..=rows)
            .flat_map(|j| (0..=columns).map(move |k| (j * 100 + k * 16 * (4 - k)) as i64))
            .collect();
        CompTable {
            rows,
            columns,
            x_spacing_counts: 1000,
            x_counts_per_mm: 1000.0,
            c_counts_per_rev: 400,
            w_counts_per_mm: 1000.0,
            x_negative,
            entries,
            w_offset_mm: 0.5,
            motors: Motors {
                x: 1,
                c: 3,
                w: 4,
                desired_position: false,
            },
        }
    }

    #[test]
    fn the_lookup_rolls_over_and_interpolates_bilinearly() {
        let t = table(false);
        // At grid points: the entries.
        assert_eq!(t.correction_at(1000.0, 100.0), t.entry(1, 1) as f64);
        assert_eq!(t.correction_at(0.0, 0.0), 0.0);
        // Midway between four entries: their mean.
        let mean = (t.entry(1, 2) + t.entry(1, 3) + t.entry(2, 2) + t.entry(2, 3)) as f64 / 4.0;
        assert_eq!(t.correction_at(1500.0, 250.0), mean);
        // Any number of turns, either way: the same.
        for turns in [-3.0, -1.0, 1.0, 7.0] {
            assert_eq!(t.correction_at(1500.0, 250.0 + 400.0 * turns), mean);
        }
        // X rolls over at its span: −500 counts reads as 1500.
        assert_eq!(t.correction_at(-500.0, 250.0), mean);
        assert_eq!(t.w_mm_at(1.5, 225.0), 0.5 + mean / 16_000.0);
    }

    #[test]
    fn the_pmac_text_has_the_header_and_every_entry_but_the_origin() {
        let t = table(false);
        let mut out = Vec::new();
        let bytes = write_pmac(&mut out, &t, &["a (µm)".into()]).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert_eq!(bytes, text.len() as u64);
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("; a [um]"));
        assert_eq!(lines.next(), Some("#4"));
        assert_eq!(lines.next(), Some("DEFINE COMP 2.4,#3,#1,#4,400,2000"));
        let entries: Vec<i64> = lines
            .flat_map(|l| l.split_whitespace().map(|e| e.parse::<i64>().unwrap()))
            .collect();
        assert_eq!(entries.len(), 3 * 5 - 1);
        assert_eq!(entries, t.entries[1..]);
        let d = CompTable {
            motors: Motors {
                desired_position: true,
                ..t.motors
            },
            ..t
        };
        assert_eq!(d.define_line(), "DEFINE COMP 2.4,#3D,#1D,#4,400,2000");
    }

    #[test]
    fn the_csv_is_the_same_grid_in_mm_and_degrees() {
        for x_negative in [false, true] {
            let t = table(x_negative);
            let mut out = Vec::new();
            write_csv(&mut out, &t).unwrap();
            let text = String::from_utf8(out).unwrap();
            let mut lines = text.lines();
            assert_eq!(
                lines.next(),
                Some(
                    "x_mm/c_deg,0.000000000,90.000000000,180.000000000,270.000000000,360.000000000"
                )
            );
            let rows: Vec<Vec<f64>> = lines
                .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
                .collect();
            assert_eq!(rows.len(), 3);
            let xs: Vec<f64> = rows.iter().map(|r| r[0]).collect();
            let expected = match x_negative {
                false => [0.0, 1.0, 0.0],
                true => [0.0, -1.0, 0.0],
            };
            assert_eq!(xs, expected);
            for (j, r) in rows.iter().enumerate() {
                for k in 0..=4 {
                    let w = 0.5 + t.entry(j, k) as f64 / 16_000.0;
                    assert!((r[k + 1] - w).abs() < 5e-10, "{j} {k}");
                }
            }
        }
    }
}
