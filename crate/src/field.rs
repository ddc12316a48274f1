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
