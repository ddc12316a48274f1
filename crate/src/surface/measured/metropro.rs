//! Zygo MetroPro binary `.dat` files: a big-endian header (format 1 or 2: 834 bytes; format 3:
//! 4096 bytes), the intensity frames (`u16`, `ac_width × ac_height` per bucket) and the
//! connected phase array (`i32`, `cn_width × cn_height`), each stored top row first.
//!
//! **Layout.** The offsets are those of the MetroPro Reference Guide's header description as
//! the open readers quote it: Gwyddion's `modules/file/metropro.c` (2.61, which also checks the
//! magic number against the header format and size), prysm's `prysm/io.py`
//! (`read_zygo_dat`, `_zygo_metadata_helper`) and SurfaceTopography's `IO/MetroPro.py`:
//!
//! | offset | field | type | use |
//! |---|---|---|---|
//! | 0 | magic number | u32 | 881B036F, 881B0370, 881B0371 for formats 1, 2, 3 |
//! | 4 | header format | u16 | must match the magic number |
//! | 6 | header size | u32 | 834 (formats 1, 2) or 4096 (format 3) |
//! | 52, 54, 56 | `ac_width`, `ac_height`, `ac_n_buckets` | u16 | intensity bytes to skip: 2·w·h·buckets |
//! | 68, 70 | `cn_width`, `cn_height` | u16 | the phase array's columns and rows |
//! | 164 | `intf_scale_factor` S | f32 | waves per fringe |
//! | 168 | `wavelength_in` λ | f32 | metres |
//! | 176 | `obliquity_factor` O | f32 | |
//! | 184 | `lateral_res` | f32 | metres per pixel |
//! | 218 | `phase_res` | i16 | R = 4096, 32768, 131072 for 0, 1, 2 |
//! | 232 | `sign` | i16 | 1: data inverted |
//!
//! **Heights** (MetroPro Reference Guide p. 12-6 as prysm quotes it): `z = raw · S · O · λ / R`,
//! metres, negated when `sign` is 1 (as Gwyddion and SurfaceTopography do; prysm ignores the
//! field); raw values ≥ 2147483640 are invalid (no data). Converted to millimetres.
//!
//! **Grid.** Spacing `lateral_res` in x and y; the array's first row is the top of the image,
//! so it becomes the highest y (prysm flips the array the same way "so their y coordinates
//! increase upward"); columns run along +x. The origin is the array's centre (the `cn_org`
//! offsets place it in camera pixels, not on the part).
//!
//! When `ac_n_buckets` is 0 there is no intensity (Gwyddion, SurfaceTopography; prysm counts
//! one frame). Bytes after the phase array are allowed, as Gwyddion allows them. Limits: the
//! file's size ([`super::MAX_FILE_BYTES`]), the phase nodes ([`super::MAX_GRID_NODES`]); the
//! header's dimensions must fit in the file before anything is allocated.

use super::{
    HeightGrid, MAX_FILE_BYTES, MAX_GRID_NODES, MeasuredData, MeasuredError, MeasuredMap,
    check_limit,
};

/// Header size of formats 1 and 2, bytes.
const HEADER_SIZE_12: u32 = 834;
/// Header size of format 3, bytes.
const HEADER_SIZE_3: u32 = 4096;
/// The magic numbers of header formats 1, 2 and 3.
const MAGIC: [u32; 3] = [0x881B_036F, 0x881B_0370, 0x881B_0371];
/// Raw phase values at or above this are invalid.
pub const INVALID_PHASE: i32 = 2_147_483_640;

/// Whether `bytes` start with a MetroPro magic number.
pub fn is_metropro(bytes: &[u8]) -> bool {
    bytes
        .get(..4)
        .is_some_and(|b| MAGIC.contains(&u32::from_be_bytes([b[0], b[1], b[2], b[3]])))
}

/// The header fields the reader uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Header {
    /// Header format, 1, 2 or 3.
    pub format: u16,
    /// Header size, bytes.
    pub size: u32,
    /// Intensity frame width, pixels.
    pub ac_width: u16,
    /// Intensity frame height, pixels.
    pub ac_height: u16,
    /// Intensity frames.
    pub ac_n_buckets: u16,
    /// Phase array width (columns).
    pub cn_width: u16,
    /// Phase array height (rows).
    pub cn_height: u16,
    /// Interferometric scale factor S, waves per fringe.
    pub scale_factor: f32,
    /// Wavelength λ, metres.
    pub wavelength_m: f32,
    /// Obliquity factor O.
    pub obliquity: f32,
    /// Lateral resolution, metres per pixel.
    pub lateral_res_m: f32,
    /// Phase resolution code, 0, 1 or 2.
    pub phase_res: i16,
    /// Data sign: 0 normal, 1 inverted.
    pub sign: i16,
}

/// Big-endian reads at fixed offsets of a slice known to hold the header.
struct Be<'a>(&'a [u8]);

impl Be<'_> {
    fn bytes<const N: usize>(&self, at: usize) -> [u8; N] {
        let mut b = [0; N];
        b.copy_from_slice(&self.0[at..at + N]);
        b
    }
    fn u16(&self, at: usize) -> u16 {
        u16::from_be_bytes(self.bytes(at))
    }
    fn i16(&self, at: usize) -> i16 {
        i16::from_be_bytes(self.bytes(at))
    }
    fn u32(&self, at: usize) -> u32 {
        u32::from_be_bytes(self.bytes(at))
    }
    fn f32(&self, at: usize) -> f32 {
        f32::from_be_bytes(self.bytes(at))
    }
}

impl Header {
    /// Reads and checks the header of the file `file`.
    pub fn parse(file: &str, bytes: &[u8]) -> Result<Header, MeasuredError> {
        if bytes.len() < HEADER_SIZE_12 as usize {
            return Err(MeasuredError::bytes(
                file,
                bytes.len() as u64,
                format!(
                    "the file ends inside the header: a MetroPro header has at least \
                     {HEADER_SIZE_12} bytes"
                ),
            ));
        }
        let be = Be(bytes);
        let magic = be.u32(0);
        let Some(k) = MAGIC.iter().position(|m| *m == magic) else {
            return Err(MeasuredError::bytes(
                file,
                0,
                format!(
                    "magic number {magic:08X}: expected 881B036F, 881B0370 or 881B0371 \
                     (MetroPro header format 1, 2 or 3)"
                ),
            ));
        };
        let format = be.u16(4);
        if usize::from(format) != k + 1 {
            return Err(MeasuredError::bytes(
                file,
                4,
                format!(
                    "header format {format}: the magic number {magic:08X} is format {}",
                    k + 1
                ),
            ));
        }
        let want = if format == 3 {
            HEADER_SIZE_3
        } else {
            HEADER_SIZE_12
        };
        let size = be.u32(6);
        if size != want {
            return Err(MeasuredError::bytes(
                file,
                6,
                format!("header size {size}: format {format} headers have {want} bytes"),
            ));
        }
        if bytes.len() < size as usize {
            return Err(MeasuredError::bytes(
                file,
                bytes.len() as u64,
                format!("the file ends inside the {size}-byte header"),
            ));
        }
        Ok(Header {
            format,
            size,
            ac_width: be.u16(52),
            ac_height: be.u16(54),
            ac_n_buckets: be.u16(56),
            cn_width: be.u16(68),
            cn_height: be.u16(70),
            scale_factor: be.f32(164),
            wavelength_m: be.f32(168),
            obliquity: be.f32(176),
            lateral_res_m: be.f32(184),
            phase_res: be.i16(218),
            sign: be.i16(232),
        })
    }

    /// Phase counts per fringe, R.
    fn counts_per_fringe(&self, file: &str) -> Result<f64, MeasuredError> {
        match self.phase_res {
            0 => Ok(4096.0),
            1 => Ok(32768.0),
            2 => Ok(131072.0),
            r => Err(MeasuredError::bytes(
                file,
                218,
                format!("phase_res {r}: expected 0, 1 or 2 (4096, 32768 or 131072 per fringe)"),
            )),
        }
    }

    /// Metres per raw phase count: `S · O · λ / R`, signed by `sign`.
    fn metres_per_count(&self, file: &str) -> Result<f64, MeasuredError> {
        let positive = |offset: u64, name: &str, v: f32| {
            if v.is_finite() && v > 0.0 {
                Ok(f64::from(v))
            } else {
                Err(MeasuredError::bytes(
                    file,
                    offset,
                    format!("{name} {v:e}: expected a finite number > 0"),
                ))
            }
        };
        let s = positive(164, "intf_scale_factor", self.scale_factor)?;
        let lambda = positive(168, "wavelength_in (m)", self.wavelength_m)?;
        let o = positive(176, "obliquity_factor", self.obliquity)?;
        let r = self.counts_per_fringe(file)?;
        let sign = if self.sign == 0 { 1.0 } else { -1.0 };
        Ok(sign * s * o * lambda / r)
    }

    /// Bytes of intensity frames before the phase array.
    fn intensity_bytes(&self) -> u64 {
        2 * u64::from(self.ac_width) * u64::from(self.ac_height) * u64::from(self.ac_n_buckets)
    }
}

/// Reads a MetroPro `.dat` (see the module docs) from the file `file`'s bytes.
pub fn read(file: &str, bytes: &[u8]) -> Result<MeasuredMap, MeasuredError> {
    check_limit(file, "size (bytes)", bytes.len() as u64, MAX_FILE_BYTES)?;
    let h = Header::parse(file, bytes)?;
    let (nx, ny) = (usize::from(h.cn_width), usize::from(h.cn_height));
    if nx == 0 || ny == 0 {
        return Err(MeasuredError::bytes(
            file,
            68,
            format!("connected phase array {nx} × {ny}: the file holds no phase data"),
        ));
    }
    check_limit(file, "phase nodes", (nx * ny) as u64, MAX_GRID_NODES)?;
    let start = u64::from(h.size) + h.intensity_bytes();
    let need = start + 4 * (nx * ny) as u64;
    if (bytes.len() as u64) < need {
        return Err(MeasuredError::bytes(
            file,
            bytes.len() as u64,
            format!(
                "the file ends early: the header's dimensions need {need} bytes ({}-byte \
                 header, {} × {} × {} intensity values of 2 bytes, {nx} × {ny} phase values \
                 of 4 bytes)",
                h.size, h.ac_width, h.ac_height, h.ac_n_buckets
            ),
        ));
    }
    let per_count = h.metres_per_count(file)?;
    let lateral = f64::from(h.lateral_res_m);
    if !(lateral.is_finite() && lateral > 0.0) {
        return Err(MeasuredError::bytes(
            file,
            184,
            format!(
                "lateral_res {lateral:e} m: the file has no lateral calibration (expected \
                 metres per pixel > 0)"
            ),
        ));
    }
    let phase = &bytes[start as usize..need as usize];
    let mut z = vec![0.0; nx * ny];
    let mut valid = vec![false; nx * ny];
    for (k, b) in phase.chunks_exact(4).enumerate() {
        let raw = i32::from_be_bytes([b[0], b[1], b[2], b[3]]);
        let (row, col) = (k / nx, k % nx);
        let at = (ny - 1 - row) * nx + col;
        if raw < INVALID_PHASE {
            z[at] = f64::from(raw) * per_count * 1e3;
            valid[at] = true;
        }
    }
    let step = lateral * 1e3;
    let source = format!(
        "MetroPro .dat {file}, header format {}, {nx} × {ny} phase, phase_res {} (R {}), \
         S {}, O {}, λ {:.4} nm, {:.6} µm per pixel{}",
        h.format,
        h.phase_res,
        h.counts_per_fringe(file)?,
        h.scale_factor,
        h.obliquity,
        f64::from(h.wavelength_m) * 1e9,
        lateral * 1e6,
        if h.sign == 0 { "" } else { ", sign inverted" },
    );
    Ok(MeasuredMap::new(
        MeasuredData::Grid(HeightGrid::centred(nx, ny, step, step, z, valid)),
        source,
    ))
}
