//! Measured form data in (issue 15): the files a lab's metrology hands back after a test cut,
//! read into one [`MeasuredMap`] of heights in millimetres, in the frame the job's surfaces use
//! (seen from the tool, x right, y up), with an [`Orientation`] to turn an instrument's frame
//! into the machine's. Registration, the residual and the corrected job are built on top of it
//! by the layers above.
//!
//! | format | reader | data |
//! |---|---|---|
//! | CSV point cloud (profilometers, coordinate measuring machines) | [`csv`] | points |
//! | Zygo `.datx` (HDF5; Mx, newer MetroPro) | [`datx`] | grid with nodata |
//! | Zygo MetroPro `.dat` (binary, header formats 1–3) | [`metropro`] | grid with nodata |
//! | Zemax Grid Sag `.DAT` (text; metrology scripts export it) | [`grid_sag`] | grid with nodata |
//!
//! `crate/docs/measured-data.md` describes each format as read, its units, frame and limits, and
//! the public readers the layouts were taken from.
//!
//! **Limits.** Every reader refuses, before allocating, a file larger than [`MAX_FILE_BYTES`],
//! a grid of more than [`MAX_GRID_NODES`] nodes (4096 × 4096) and a cloud of more than
//! [`MAX_CLOUD_POINTS`] points; header dimensions are checked against the bytes the file holds.

pub mod csv;
pub mod datx;
mod error;
pub mod grid_sag;
pub mod map;
pub mod metropro;
pub mod orientation;

pub use error::{MeasuredError, check_limit};
pub use map::{HeightGrid, MeasuredData, MeasuredMap, PointCloud};
pub use orientation::{Mirror, Orientation};

/// The largest file any reader accepts, bytes (256 MiB).
pub const MAX_FILE_BYTES: u64 = 256 * 1024 * 1024;
/// The most nodes of a grid (4096 × 4096).
pub const MAX_GRID_NODES: u64 = 4096 * 4096;
/// The most points of a point cloud.
pub const MAX_CLOUD_POINTS: u64 = 4_000_000;

/// A measured-data format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// CSV point cloud ([`csv`]).
    Csv,
    /// Zygo `.datx` ([`datx`]).
    Datx,
    /// Zygo MetroPro `.dat` ([`metropro`]).
    MetroPro,
    /// Zemax Grid Sag `.DAT` ([`grid_sag`]).
    GridSag,
}

/// The HDF5 signature at the start of a `.datx`.
const HDF5_MAGIC: &[u8] = b"\x89HDF\r\n\x1a\n";

impl Format {
    /// The format of the file `name` with contents `bytes`: by signature (HDF5, MetroPro's
    /// magic numbers) first, then by name: `.csv` or `.txt` for a point cloud, `.dat` (without
    /// MetroPro's magic number) for a Zemax Grid Sag file.
    pub fn detect(name: &str, bytes: &[u8]) -> Result<Format, MeasuredError> {
        if bytes.starts_with(HDF5_MAGIC) {
            return Ok(Format::Datx);
        }
        if metropro::is_metropro(bytes) {
            return Ok(Format::MetroPro);
        }
        let ext = name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("csv" | "txt") => Ok(Format::Csv),
            Some("dat") => Ok(Format::GridSag),
            _ => Err(MeasuredError::Format {
                file: name.to_string(),
                problem: "not a measured-data format spiralcam reads: expected a Zygo .datx \
                          (HDF5 signature), a MetroPro .dat (magic 881B036F, 881B0370 or \
                          881B0371), a Zemax Grid Sag .DAT (text) or a CSV point cloud named \
                          .csv or .txt"
                    .into(),
            }),
        }
    }
}

/// Reads the file `name` with contents `bytes` in the format [`Format::detect`] finds.
pub fn read(name: &str, bytes: Vec<u8>) -> Result<MeasuredMap, MeasuredError> {
    check_limit(name, "size (bytes)", bytes.len() as u64, MAX_FILE_BYTES)?;
    match Format::detect(name, &bytes)? {
        Format::Csv => csv::read(name, &bytes),
        Format::Datx => datx::read(name, bytes),
        Format::MetroPro => metropro::read(name, &bytes),
        Format::GridSag => grid_sag::read(name, &bytes),
    }
}

/// Reads the file at `path` (command line): its size is checked against [`MAX_FILE_BYTES`]
/// before it is read.
pub fn read_path(path: &std::path::Path) -> Result<MeasuredMap, MeasuredError> {
    let name = path.display().to_string();
    let io = |e: std::io::Error| MeasuredError::Format {
        file: name.clone(),
        problem: format!("cannot be read: {e}"),
    };
    let size = std::fs::metadata(path).map_err(io)?.len();
    check_limit(&name, "size (bytes)", size, MAX_FILE_BYTES)?;
    read(&name, std::fs::read(path).map_err(io)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_are_told_by_signature_then_name() {
        assert_eq!(Format::detect("a.bin", HDF5_MAGIC).unwrap(), Format::Datx);
        let mut mp = vec![0x88, 0x1b, 0x03, 0x71];
        mp.resize(10, 0);
        assert_eq!(Format::detect("a.DAT", &mp).unwrap(), Format::MetroPro);
        assert_eq!(Format::detect("scan.CSV", b"x_mm").unwrap(), Format::Csv);
        assert_eq!(
            Format::detect("grid.DAT", b"33 33 1 1 0 0 0").unwrap(),
            Format::GridSag
        );
        let e = Format::detect("grid.xyz", b"! Zemax grid").unwrap_err();
        assert!(
            e.to_string().contains("MetroPro .dat (magic 881B036F"),
            "{e}"
        );
    }
}
