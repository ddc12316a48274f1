//! Validation of job fields: one error type that names the field, the value given and what is
//! allowed, used by every module that checks user input, so that the page can show the message
//! beside the offending field and the command line can print it as is.

use thiserror::Error;

/// A job field with a value that cannot be used.
///
/// ```
/// use spiralcam::field::{FieldError, positive};
/// let err = positive("tool.nose_radius_mm", -0.5).unwrap_err();
/// assert_eq!(err.to_string(), "tool.nose_radius_mm = -0.5: must be a finite number > 0");
/// ```
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{field} = {value}: {allowed}")]
pub struct FieldError {
    /// Dotted path of the field in the job, e.g. `surface.aperture_mm`.
    pub field: String,
    /// The value as given.
    pub value: String,
    /// What would be accepted.
    pub allowed: String,
}

impl FieldError {
    /// A field error from its three parts.
    pub fn new(field: impl Into<String>, value: impl ToString, allowed: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// The same error with `prefix.` put in front of the field path.
    pub fn within(mut self, prefix: &str) -> Self {
        self.field = format!("{prefix}.{}", self.field);
        self
    }
}

/// `value` if it is finite, else an error naming `field`.
pub fn finite(field: &str, value: f64) -> Result<f64, FieldError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(FieldError::new(field, value, "must be a finite number"))
    }
}

/// `value` if it is finite and strictly positive.
pub fn positive(field: &str, value: f64) -> Result<f64, FieldError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(FieldError::new(field, value, "must be a finite number > 0"))
    }
}

/// `value` if it is finite and not negative.
pub fn non_negative(field: &str, value: f64) -> Result<f64, FieldError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(FieldError::new(field, value, "must be a finite number ≥ 0"))
    }
}

/// `value` if it lies in the closed range `[lo, hi]`.
pub fn in_range(field: &str, value: f64, lo: f64, hi: f64) -> Result<f64, FieldError> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(FieldError::new(
            field,
            value,
            format!("must lie in [{lo}, {hi}]"),
        ))
    }
}

/// Marks a field path carried in front of a deserialisation message ([`nest_path`]): a control
/// character that no message of serde or of this crate contains.
const NESTED: char = '\u{1f}';

/// The message of a deserialisation error seen at `path` inside a value that reads itself from a
/// buffered copy (a surface spec, whose family is named by a key inside it): serde loses the path
/// there, so the value's reader tracks it and puts it, marked, in front of the message, for the
/// reader of the enclosing document to join to its own ([`join_path`]). A message that already
/// carries a path (a surface inside a surface) gets the two joined.
pub fn nest_path(path: &str, message: &str) -> String {
    let (path, message) = join_path(path, message);
    format!("{NESTED}{path}: {message}")
}

/// The full path and the message of a deserialisation error that the enclosing reader saw at
/// `outer` (`.` or empty for the document itself): `outer` joined to the path the message carries
/// ([`nest_path`]), if any, as `outer.inner` or `outer[i]…`.
///
/// ```
/// use spiralcam::field::{join_path, nest_path};
/// let inner = nest_path("base", "unknown field `type`");
/// let outer = nest_path("terms[0].surface", &inner);
/// assert_eq!(
///     join_path("surface", &outer),
///     ("surface.terms[0].surface.base".to_string(), "unknown field `type`".to_string())
/// );
/// assert_eq!(join_path(".", "missing field `name`"), (".".to_string(), "missing field `name`".to_string()));
/// ```
pub fn join_path(outer: &str, message: &str) -> (String, String) {
    let Some((inner, rest)) = message
        .strip_prefix(NESTED)
        .and_then(|m| m.split_once(": "))
    else {
        return (outer.to_string(), message.to_string());
    };
    let path = match outer {
        "" | "." => inner.to_string(),
        _ if inner.starts_with('[') => format!("{outer}{inner}"),
        _ => format!("{outer}.{inner}"),
    };
    (path, rest.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_field_value_and_range() {
        let e = in_range("strategy.start_angle_deg", 400.0, 0.0, 360.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "strategy.start_angle_deg = 400: must lie in [0, 360]"
        );
        assert_eq!(e.within("job").field, "job.strategy.start_angle_deg");
        assert!(finite("a", f64::NAN).is_err());
        assert!(non_negative("a", 0.0).is_ok());
        assert!(positive("a", 0.0).is_err());
    }
}
