//! Data a job refers to, such as scattered points or a STEP file: a path, which the command
//! line reads relative to the job file before planning ([`crate::job::Job::load_files`]), or
//! the text itself, which is what the page sends (the browser has no file system). A surface
//! that needs the data reads [`DataFile::text`] and reports a missing one as a field error.

use crate::field::FieldError;
use serde::{Deserialize, Serialize};

/// A data file of a job: `{"path": "points.csv"}` or `{"text": "…"}`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DataFile {
    /// Path, relative to the job file (command line only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub path: Option<String>,
    /// The file's contents.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub text: Option<String>,
}

/// The largest data file read, bytes (256 MiB): larger files are refused before they are read.
pub const MAX_DATA_BYTES: u64 = 256 << 20;

/// The longest path accepted, bytes.
pub const MAX_PATH_BYTES: usize = 4096;

impl DataFile {
    /// Checks the sizes: the path at most [`MAX_PATH_BYTES`], the text at most
    /// [`MAX_DATA_BYTES`]; `field` names the data file (`surface.data`).
    pub fn check(&self, field: &str) -> Result<(), FieldError> {
        if let Some(p) = self.path.as_ref().filter(|p| p.len() > MAX_PATH_BYTES) {
            return Err(FieldError::new(
                format!("{field}.path"),
                format!("{} bytes", p.len()),
                format!("a path of at most {MAX_PATH_BYTES} bytes"),
            ));
        }
        if let Some(t) = self
            .text
            .as_ref()
            .filter(|t| t.len() as u64 > MAX_DATA_BYTES)
        {
            return Err(FieldError::new(
                format!("{field}.text"),
                format!("{} bytes", t.len()),
                format!("at most {MAX_DATA_BYTES} bytes (256 MiB)"),
            ));
        }
        Ok(())
    }

    /// The contents, or an error naming `field` when only a path was given and not read.
    pub fn text(&self, field: &str) -> Result<&str, FieldError> {
        self.check(field)?;
        match (&self.text, &self.path) {
            (Some(t), _) => Ok(t),
            (None, Some(p)) => Err(FieldError::new(
                field,
                p,
                "the file has not been read (the command line reads it)",
            )),
            (None, None) => Err(FieldError::new(
                field,
                "{}",
                "give \"path\" (command line) or \"text\"",
            )),
        }
    }

    /// A short name for reports: the path, or "inline data".
    pub fn name(&self) -> &str {
        self.path.as_deref().unwrap_or("inline data")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_or_a_clear_error() {
        let f = DataFile {
            path: Some("a.csv".into()),
            text: None,
        };
        assert_eq!(
            f.text("surface.data").unwrap_err().to_string(),
            "surface.data = a.csv: the file has not been read (the command line reads it)"
        );
        let f = DataFile {
            path: None,
            text: Some("1,2,3".into()),
        };
        assert_eq!(f.text("x").unwrap(), "1,2,3");
        assert_eq!(f.name(), "inline data");
    }
}
