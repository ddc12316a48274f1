//! The errors of the measured-data readers: each names the file and where in it (a line of
//! text, a byte offset of a binary header, an HDF5 object), what was found and what was
//! expected, so that the command line can print it as is and the page can show it beside the
//! file it loaded.

use thiserror::Error;

/// A measured-data file that cannot be read, or a reading option outside what is allowed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MeasuredError {
    /// A line of a text file that is not what the format allows.
    ///
    /// ```
    /// use spiralcam::surface::measured::csv;
    /// let e = csv::read("scan.csv", b"x_mm,y_mm,z_mm\n1,2,three\n").unwrap_err();
    /// assert_eq!(
    ///     e.to_string(),
    ///     "scan.csv: line 2: column 3 (z_mm) = \"three\": expected a number"
    /// );
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
    /// Bytes of a binary file at an offset that are not what the format says.
    ///
    /// ```
    /// use spiralcam::surface::measured::metropro;
    /// let e = metropro::read("part.dat", &[0u8; 900]).unwrap_err();
    /// assert!(e.to_string().starts_with("part.dat: byte 0: magic number 00000000"), "{e}");
    /// ```
    #[error("{file}: byte {offset}: {problem}")]
    Bytes {
        /// The file's name.
        file: String,
        /// Offset from the start of the file.
        offset: u64,
        /// What is wrong and what was expected.
        problem: String,
    },
    /// An HDF5 object or attribute of a Zygo .datx file that is missing or not as Zygo writes
    /// it.
    ///
    /// ```
    /// use spiralcam::surface::measured::datx;
    /// let e = datx::read("part.datx", b"not an HDF5 file".to_vec()).unwrap_err();
    /// assert!(e.to_string().starts_with("part.datx: HDF5 file: "), "{e}");
    /// ```
    #[error("{file}: {object}: {problem}")]
    Object {
        /// The file's name.
        file: String,
        /// The HDF5 path of the object, with the attribute after a colon.
        object: String,
        /// What is wrong and what was expected.
        problem: String,
    },
    /// More data than the readers' limits allow, refused before it is allocated.
    ///
    /// ```
    /// use spiralcam::surface::measured::{MeasuredError, check_limit};
    /// let e = check_limit("big.csv", "size (bytes)", 1 << 40, 1 << 28).unwrap_err();
    /// assert_eq!(
    ///     e.to_string(),
    ///     "big.csv: size (bytes) is 1099511627776, more than the limit of 268435456"
    /// );
    /// ```
    #[error("{file}: {what} is {value}, more than the limit of {limit}")]
    TooLarge {
        /// The file's name.
        file: String,
        /// What was counted, with its unit.
        what: String,
        /// The count.
        value: u64,
        /// The limit.
        limit: u64,
    },
    /// A reading option outside what is allowed.
    ///
    /// ```
    /// use spiralcam::surface::measured::{Mirror, Orientation};
    /// let e = Orientation::new(45, Mirror::None).unwrap_err();
    /// assert_eq!(e.to_string(), "rotate_deg = 45: must be a multiple of 90");
    /// ```
    #[error("{option} = {value}: {allowed}")]
    Option {
        /// The option's name.
        option: String,
        /// The value given.
        value: String,
        /// What would be accepted.
        allowed: String,
    },
    /// A file none of the readers recognises.
    ///
    /// ```
    /// use spiralcam::surface::measured::read;
    /// let e = read("part.xyz", vec![0, 1, 2]).unwrap_err();
    /// assert!(e.to_string().starts_with("part.xyz: not a measured-data format"), "{e}");
    /// ```
    #[error("{file}: {problem}")]
    Format {
        /// The file's name.
        file: String,
        /// What was found and which formats are read.
        problem: String,
    },
}

impl MeasuredError {
    /// A [`MeasuredError::Line`].
    pub(crate) fn line(file: &str, line: usize, problem: impl Into<String>) -> Self {
        Self::Line {
            file: file.to_string(),
            line,
            problem: problem.into(),
        }
    }

    /// A [`MeasuredError::Bytes`].
    pub(crate) fn bytes(file: &str, offset: u64, problem: impl Into<String>) -> Self {
        Self::Bytes {
            file: file.to_string(),
            offset,
            problem: problem.into(),
        }
    }

    /// A [`MeasuredError::Object`].
    pub(crate) fn object(file: &str, object: &str, problem: impl Into<String>) -> Self {
        Self::Object {
            file: file.to_string(),
            object: object.to_string(),
            problem: problem.into(),
        }
    }
}

/// `Ok(())` when `value ≤ limit`, else [`MeasuredError::TooLarge`] naming `what`.
pub fn check_limit(file: &str, what: &str, value: u64, limit: u64) -> Result<(), MeasuredError> {
    if value <= limit {
        Ok(())
    } else {
        Err(MeasuredError::TooLarge {
            file: file.to_string(),
            what: what.to_string(),
            value,
            limit,
        })
    }
}
