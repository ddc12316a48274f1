//! Why a program cannot be verified against a job.

use crate::field::FieldError;
use crate::nc::reader::ReadError;
use crate::path::PathError;
use crate::surface::UndefinedError;
use thiserror::Error;

/// Why a program cannot be verified.
#[derive(Debug, Error)]
pub enum VerifyError {
    /// The program cannot be read (its file, line and text are in the message).
    ///
    /// ```
    /// use spiralcam::analysis::verify::VerifyError;
    /// use spiralcam::nc::reader::{Program, Reader, ReaderOptions};
    /// let mut r = Reader::new(Program::from_text("p.ngc", "G1 X1 F10\n"), ReaderOptions::default());
    /// let e = VerifyError::from(loop {
    ///     match r.next_step() {
    ///         Err(e) => break e,
    ///         Ok(Some(_)) => continue,
    ///         Ok(None) => unreachable!(),
    ///     }
    /// });
    /// assert!(e.to_string().starts_with("p.ngc"), "{e}");
    /// ```
    #[error(transparent)]
    Read(#[from] ReadError),
    /// The program's file cannot be opened.
    ///
    /// ```
    /// let e = spiralcam::analysis::verify::VerifyError::Open("p.nc: not found".into());
    /// assert_eq!(e.to_string(), "p.nc: not found");
    /// ```
    #[error("{0}")]
    Open(String),
    /// The job cannot be verified against (two-way compensation, a bad field).
    ///
    /// ```
    /// let e = spiralcam::analysis::verify::VerifyError::from(
    ///     spiralcam::field::FieldError::new("part.diameter_mm", 0, "must be > 0"));
    /// assert_eq!(e.to_string(), "part.diameter_mm = 0: must be > 0");
    /// ```
    #[error(transparent)]
    Job(#[from] FieldError),
    /// The program has moves but none that cut: no feed move turns C or moves X.
    ///
    /// ```
    /// let e = spiralcam::analysis::verify::VerifyError::NoCuttingMoves { moves: 3 };
    /// assert!(e.to_string().starts_with("the program has 3 moves and none cuts"));
    /// ```
    #[error(
        "the program has {moves} moves and none cuts: no feed move (G1, G2, G3) turns C or moves X"
    )]
    NoCuttingMoves {
        /// Moves read.
        moves: u64,
    },
    /// The program is for another part: too many of its cutting points lie beyond the job's.
    ///
    /// ```
    /// let e = spiralcam::analysis::verify::VerifyError::OtherPart {
    ///     beyond: 600, points: 1000, largest_radius_mm: 10.0, part_radius_mm: 5.0 };
    /// assert!(e.to_string().contains("part.diameter_mm"), "{e}");
    /// ```
    #[error(
        "{beyond} of the program's {points} cutting points lie beyond the part (radius up to \
         {largest_radius_mm:.6} mm; the job's part.diameter_mm and strategy.overtravel_mm give \
         {part_radius_mm:.6} mm): the program is for another part size, or its X is scaled \
         (G7 diameter mode, inch units) or signed otherwise than output.x_sign says"
    )]
    OtherPart {
        /// Cutting points beyond the part.
        beyond: u64,
        /// Cutting points in all.
        points: u64,
        /// The largest radius of a cutting point, mm.
        largest_radius_mm: f64,
        /// The part's radius with the overtravel, mm.
        part_radius_mm: f64,
    },
    /// The design has no value where the program cuts.
    ///
    /// ```
    /// let e = spiralcam::analysis::verify::VerifyError::Surface {
    ///     line: 12,
    ///     source: spiralcam::surface::UndefinedError {
    ///         surface: "sphere", x_mm: 1.0, y_mm: 0.0, radius_mm: 1.0, reason: "beyond".into() },
    /// };
    /// assert!(e.to_string().starts_with("line 12: "), "{e}");
    /// ```
    #[error("line {line}: {source}")]
    Surface {
        /// The program's line.
        line: u64,
        /// What the surface says.
        source: UndefinedError,
    },
    /// The accuracy analysis failed.
    ///
    /// ```
    /// let e = spiralcam::analysis::verify::VerifyError::from(spiralcam::path::PathError::Cancelled);
    /// assert_eq!(e.to_string(), "cancelled");
    /// ```
    #[error(transparent)]
    Path(#[from] PathError),
    /// The progress callback asked to stop.
    ///
    /// ```
    /// assert_eq!(spiralcam::analysis::verify::VerifyError::Cancelled.to_string(), "cancelled");
    /// ```
    #[error("cancelled")]
    Cancelled,
}
