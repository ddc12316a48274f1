//! Why a program cannot be read: a [`Problem`] and where it is ([`ReadError`]: the file, the
//! line number counted from 1, and the line's text as written, shortened past 120 characters).

use std::sync::Arc;
use thiserror::Error;

/// Longest excerpt of a line an error quotes.
const QUOTED: usize = 120;

/// What is wrong.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Problem {
    /// The line does not parse.
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "G1 X[1+2\nM30\n").unwrap_err();
    /// assert!(matches!(e.problem, Problem::Syntax(_)));
    /// assert_eq!(e.line, 1);
    /// ```
    #[error("syntax: {0}")]
    Syntax(String),
    /// A word or code this reader does not know.
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "G1 X1 E2 F10\nM30\n").unwrap_err();
    /// assert_eq!(e.problem, Problem::Unknown("the word E2".into()));
    /// assert_eq!(e.to_string(), "p.nc:1: unknown: the word E2 (`G1 X1 E2 F10`)");
    /// ```
    #[error("unknown: {0}")]
    Unknown(String),
    /// Something the reader understands but does not follow (it would change the tool path in
    /// a way not modelled), with the reason.
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "G41 G1 X1 F10\nM30\n").unwrap_err();
    /// assert!(matches!(e.problem, Problem::Unsupported(_)));
    /// ```
    #[error("not read: {0}")]
    Unsupported(String),
    /// A variable read before it is set.
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "G1 X#7 F10\nM30\n").unwrap_err();
    /// assert_eq!(e.problem, Problem::Undefined("#7".into()));
    /// ```
    #[error("{0} is read before it is set")]
    Undefined(String),
    /// Arithmetic without a finite result (division by zero, √ of a negative…).
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "#1 = 0\nG1 X[1/#1] F10\nM30\n").unwrap_err();
    /// assert!(matches!(e.problem, Problem::Arithmetic(_)));
    /// assert_eq!(e.line, 2);
    /// ```
    #[error("arithmetic: {0}")]
    Arithmetic(String),
    /// A loop, `if` or subprogram whose start and end do not match.
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "G1 X1 F10\nEND 1\nM30\n").unwrap_err();
    /// assert!(matches!(e.problem, Problem::Unbalanced(_)));
    /// ```
    #[error("unbalanced: {0}")]
    Unbalanced(String),
    /// The text ends before the program does (no `M2`, `M30` or closing `%`).
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "G1 X1 F10\nG1 X2\n").unwrap_err();
    /// assert!(matches!(e.problem, Problem::Truncated(_)));
    /// ```
    #[error("truncated: {0}")]
    Truncated(String),
    /// A bound on time or memory is reached.
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "G1 X1 F10\no1 repeat [100000000]\no1 endrepeat\nM2\n");
    /// assert!(matches!(e.unwrap_err().problem, Problem::Limit { .. }));
    /// ```
    #[error("limit: {what} exceeds {limit}: {hint}")]
    Limit {
        /// What was counted.
        what: String,
        /// The bound.
        limit: u64,
        /// Why it is there and what to change.
        hint: String,
    },
    /// The program makes no move.
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "G21 G90\nM30\n").unwrap_err();
    /// assert_eq!(e.problem, Problem::NoMotion);
    /// ```
    #[error("the program makes no move")]
    NoMotion,
    /// A called program cannot be found or read.
    ///
    /// ```
    /// use spiralcam::nc::reader::{read_text, Problem};
    /// let e = read_text("p.nc", "G1 X1 F10\nM98 P1234\nM30\n").unwrap_err();
    /// assert!(matches!(e.problem, Problem::Subprogram(_)));
    /// ```
    #[error("subprogram: {0}")]
    Subprogram(String),
    /// The text could not be read.
    ///
    /// ```
    /// let p = spiralcam::nc::reader::Problem::Io("disk gone".into());
    /// assert_eq!(p.to_string(), "reading: disk gone");
    /// ```
    #[error("reading: {0}")]
    Io(String),
}

/// A program that cannot be read, and where.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{file}:{line}: {problem}{}", quote(text))]
pub struct ReadError {
    /// What is wrong.
    pub problem: Problem,
    /// The file (the program's name as given to the reader).
    pub file: Arc<str>,
    /// The line, from 1; 0 when the problem is the whole program.
    pub line: u64,
    /// The line as written (shortened), empty when the problem is the whole program.
    pub text: String,
}

fn quote(text: &str) -> String {
    if text.is_empty() {
        String::new()
    } else {
        format!(" (`{text}`)")
    }
}

impl ReadError {
    /// The error `problem` on line `line` of `file`, quoting `raw`.
    pub fn at(problem: Problem, file: &Arc<str>, line: u64, raw: &[u8]) -> Self {
        let text = String::from_utf8_lossy(raw);
        let text = text.trim();
        let text = match text.char_indices().nth(QUOTED) {
            Some((i, _)) => format!("{}…", &text[..i]),
            None => text.to_string(),
        };
        Self {
            problem,
            file: file.clone(),
            line,
            text,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_lines_are_shortened_in_messages() {
        let file: Arc<str> = "a.nc".into();
        let raw = "X".repeat(500);
        let e = ReadError::at(Problem::Unknown("x".into()), &file, 3, raw.as_bytes());
        assert_eq!(e.text.chars().count(), QUOTED + 1);
        assert!(e.to_string().starts_with("a.nc:3: unknown: x (`XXX"));
        let e = ReadError::at(Problem::NoMotion, &file, 0, b"");
        assert_eq!(e.to_string(), "a.nc:0: the program makes no move");
    }
}
