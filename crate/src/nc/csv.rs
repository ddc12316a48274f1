//! The path as CSV, one row per point: the machine words `c_deg, x_mm, z_mm` (with the same
//! signs, wrapping and decimals as the NC program), the path's own `rho_mm, theta_rad`
//! (θ cumulative) and the contact point `xc_mm, yc_mm, zc_mm` where the nose touches the surface.

use super::number::{push_fixed, push_scaled};
use super::{Conventions, NcError};
use crate::path::PathPoint;
use std::io::Write;

/// The header row.
pub const HEADER: &str = "c_deg,x_mm,z_mm,rho_mm,theta_rad,xc_mm,yc_mm,zc_mm\n";

/// Decimals of θ in radians (1e-9 rad ≈ 6e-8°).
const DECIMALS_THETA: u32 = 9;

/// Streams the CSV of a path.
pub struct CsvWriter<W: Write> {
    out: W,
    conv: Conventions,
    line: Vec<u8>,
}

impl<W: Write> CsvWriter<W> {
    /// Starts the file with its header row.
    pub fn new(mut out: W, conv: Conventions) -> Result<Self, NcError> {
        out.write_all(HEADER.as_bytes())?;
        Ok(Self {
            out,
            conv,
            line: Vec::with_capacity(128),
        })
    }

    /// Writes one row.
    pub fn point(&mut self, p: &PathPoint) -> Result<(), NcError> {
        let w = self.conv.words(p.index, p.rho, p.theta, p.z)?;
        let d = self.conv.decimals_xz;
        let l = &mut self.line;
        l.clear();
        push_scaled(l, w.c, self.conv.decimals_c);
        l.push(b',');
        push_scaled(l, w.x, d);
        l.push(b',');
        push_scaled(l, w.z, d);
        let values = [
            (p.rho, d),
            (p.theta, DECIMALS_THETA),
            (p.contact[0], d),
            (p.contact[1], d),
            (p.contact[2], d),
        ];
        for (what, (v, dec)) in ["rho", "theta", "xc", "yc", "zc"].into_iter().zip(values) {
            l.push(b',');
            if !push_fixed(l, v, dec) {
                return Err(NcError::Unwritable {
                    index: p.index,
                    what,
                    value: v,
                    at: Some((p.rho, p.theta)),
                });
            }
        }
        l.push(b'\n');
        self.out.write_all(l)?;
        Ok(())
    }

    /// Flushes the file.
    pub fn finish(mut self) -> Result<(), NcError> {
        self.out.flush()?;
        Ok(())
    }
}
