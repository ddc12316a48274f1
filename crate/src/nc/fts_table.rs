//! The fast tool servo's table, for controllers that drive the servo from a table indexed by
//! the spindle angle and the radius rather than from the program: one row per path point,
//! `c_deg, x_mm, w_mm`, with the program's signs, wrapping and decimals (W signed like Z), the
//! same numbers as the C, X and W words of the split program.

use super::number::push_scaled;
use super::{Conventions, NcError};
use crate::path::PathPoint;
use std::io::Write;

/// The header row.
pub const HEADER: &str = "c_deg,x_mm,w_mm\n";

/// Streams the table of a split path.
pub struct FtsTableWriter<W: Write> {
    out: W,
    conv: Conventions,
    line: Vec<u8>,
}

impl<W: Write> FtsTableWriter<W> {
    /// Starts the table with its header row.
    pub fn new(mut out: W, conv: Conventions) -> Result<Self, NcError> {
        out.write_all(HEADER.as_bytes())?;
        Ok(Self {
            out,
            conv,
            line: Vec::with_capacity(48),
        })
    }

    /// Writes the row of `p`, whose height is split with the slide at `z_slide`.
    pub fn point(&mut self, p: &PathPoint, z_slide: f64) -> Result<(), NcError> {
        let w = self
            .conv
            .split_words(p.index, p.rho, p.theta, p.z, z_slide)?;
        let d = self.conv.decimals_xz;
        let l = &mut self.line;
        l.clear();
        push_scaled(l, w.c, self.conv.decimals_c);
        l.push(b',');
        push_scaled(l, w.x, d);
        l.push(b',');
        push_scaled(l, w.w.unwrap_or(0), d);
        l.push(b'\n');
        self.out.write_all(l)?;
        Ok(())
    }

    /// Flushes the table.
    pub fn finish(mut self) -> Result<(), NcError> {
        self.out.flush()?;
        Ok(())
    }
}
