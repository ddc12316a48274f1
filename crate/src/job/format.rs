//! `format`: the version of the job format a job was written in (crate/docs/job-format.md,
//! "Format version"). Absent, the job is read as format 1, the only version so far; any other
//! value is refused before the rest of the job is read, so a job from a newer spiralcam fails
//! with its version named rather than with the first field this version does not know.

use crate::field::FieldError;
use serde::Deserialize;

/// The job format this version of spiralcam reads and writes.
pub const FORMAT: u32 = 1;

/// Checks a job's `format` value (a number from JSON text or from JavaScript).
///
/// ```
/// use spiralcam::job::format::check_format;
/// assert!(check_format(&serde_json::json!(1)).is_ok());
/// assert_eq!(check_format(&serde_json::json!(2)).unwrap_err().to_string(),
///            "format = 2: this spiralcam reads job format 1 only: the job was written by a \
///             newer spiralcam (or is not a spiralcam job)");
/// ```
pub fn check_format(value: &serde_json::Value) -> Result<(), FieldError> {
    let number = value.as_f64();
    if number == Some(f64::from(FORMAT)) {
        return Ok(());
    }
    let shown = match number {
        Some(x) => x.to_string(),
        None => value.to_string(),
    };
    Err(FieldError::new(
        "format",
        shown,
        format!(
            "this spiralcam reads job format {FORMAT} only: the job was written by a newer \
             spiralcam (or is not a spiralcam job)"
        ),
    ))
}

/// The one field read ahead of the job: its `format`, every other field ignored.
#[derive(Deserialize)]
pub(crate) struct FormatHeader {
    /// The value of `format`, if any (`null` too).
    #[serde(default, deserialize_with = "present")]
    pub format: Option<serde_json::Value>,
}

/// A field that is there, whatever its value (`null` is a value here, not an absence).
fn present<'de, D: serde::Deserializer<'de>>(de: D) -> Result<Option<serde_json::Value>, D::Error> {
    serde_json::Value::deserialize(de).map(Some)
}

impl FormatHeader {
    /// Reads `format` from a job's JSON text and checks it; text that is not a JSON object
    /// passes here and is refused by the full read.
    pub fn check(text: &str) -> Result<(), FieldError> {
        match serde_json::from_str::<FormatHeader>(text) {
            Ok(FormatHeader { format: Some(v) }) => check_format(&v),
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::job::{DEFAULT_JOB, Job};

    fn with_format(value: &str) -> String {
        DEFAULT_JOB.replacen('{', &format!("{{\"format\": {value},"), 1)
    }

    #[test]
    fn format_1_and_absent_are_read() {
        let job = Job::from_json(&with_format("1")).unwrap();
        assert_eq!(job.format, Some(1));
        assert_eq!(Job::from_json(DEFAULT_JOB).unwrap().format, None);
        // Written back as read.
        assert!(job.to_json().contains("\"format\": 1"));
        assert!(!Job::default_job().to_json().contains("\"format\""));
    }

    #[test]
    fn other_versions_are_refused_naming_them_before_unknown_fields() {
        for (value, shown) in [
            ("2", "2"),
            ("0", "0"),
            ("1.5", "1.5"),
            ("\"1\"", "\"1\""),
            ("null", "null"),
        ] {
            // A newer job may carry fields this version does not know: the version is named.
            let text = with_format(value).replacen('{', "{\"colour\": \"red\",", 1);
            let e = Job::from_json(&text).unwrap_err().to_string();
            assert!(
                e.starts_with(&format!(
                    "format = {shown}: this spiralcam reads job format 1 only"
                )),
                "{value}: {e}"
            );
        }
    }

    #[test]
    fn a_format_check_after_a_read_from_any_deserializer() {
        // The page reads jobs through serde-wasm-bindgen, not JSON text: the check runs on the
        // job read too.
        let value: serde_json::Value = serde_json::from_str(&with_format("7")).unwrap();
        let e = Job::deserialize_from(value).unwrap_err().to_string();
        assert!(e.starts_with("format = 7: "), "{e}");
    }
}
