//! The errors of the designers' file readers: each names the file and, for a line that is not
//! what the format allows, the line, what was found and what was expected.

use crate::surface::grid_sag::dat::DatError;
use thiserror::Error;

/// A designer's file that cannot be read.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ImportError {
    /// A file whose name says none of the formats read.
    ///
    /// ```
    /// use spiralcam::surface::import::read_design;
    /// let e = read_design("lens.txt", b"SURF 1").unwrap_err();
    /// assert!(e.to_string().starts_with("lens.txt: not a design file spiralcam reads"), "{e}");
    /// ```
    #[error("{file}: {problem}")]
    Format {
        /// The file's name.
        file: String,
        /// What was found and which formats are read.
        problem: String,
    },
    /// Bytes that are not text in an encoding the design tools write.
    ///
    /// ```
    /// use spiralcam::surface::import::read_design;
    /// let e = read_design("lens.zmx", b"SURF\0 1").unwrap_err();
    /// assert!(e.to_string().starts_with("lens.zmx: not text: byte 4 is NUL"), "{e}");
    /// ```
    #[error("{file}: not text: {problem}")]
    Encoding {
        /// The file's name.
        file: String,
        /// What is wrong, at which byte.
        problem: String,
    },
    /// A file larger than [`super::MAX_DESIGN_BYTES`], refused before it is decoded.
    ///
    /// ```
    /// use spiralcam::surface::import::read_design;
    /// let big = vec![b' '; (spiralcam::surface::import::MAX_DESIGN_BYTES + 1) as usize];
    /// let e = read_design("lens.seq", &big).unwrap_err();
    /// assert!(e.to_string().contains("more than the 67108864 bytes read"), "{e}");
    /// ```
    #[error("{file}: {bytes} bytes, more than the {limit} bytes read (64 MiB)")]
    TooLarge {
        /// The file's name.
        file: String,
        /// Its size.
        bytes: u64,
        /// The limit.
        limit: u64,
    },
    /// A line that is not what the format allows.
    ///
    /// ```
    /// use spiralcam::surface::import::read_design;
    /// let e = read_design("lens.zmx", b"UNIT FURLONG\nSURF 0\n").unwrap_err();
    /// assert!(e.to_string().starts_with("lens.zmx: line 1: lens unit FURLONG"), "{e}");
    /// ```
    #[error("{file}: line {line}: {problem}")]
    Line {
        /// The file's name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong and what was expected.
        problem: String,
    },
    /// A Grid Sag `.DAT` that cannot be read.
    ///
    /// ```
    /// use spiralcam::surface::import::read_design;
    /// let e = read_design("grid.DAT", b"5 5 1 1 0 0 0\n0 0 0 0\n").unwrap_err();
    /// assert!(e.to_string().starts_with("grid.DAT: the file ends after 1 of the 25"), "{e}");
    /// ```
    #[error("{file}: {error}")]
    Grid {
        /// The file's name.
        file: String,
        /// The reader's error.
        error: DatError,
    },
}

impl ImportError {
    /// An [`ImportError::Line`].
    pub(crate) fn line(file: &str, line: usize, problem: impl Into<String>) -> Self {
        Self::Line {
            file: file.to_string(),
            line,
            problem: problem.into(),
        }
    }
}
