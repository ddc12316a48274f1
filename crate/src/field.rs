//! Validation of job fields: one error type that names the field, the value given and what is
//! allowed, used by every module that checks user input, so that the page can show the message
//! beside the offending field and the command line can print it as is.

use serde::de::{DeserializeOwned, Error as _};
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
    /// A field error from its three parts. Numbers written out at length in the value or the
    /// message (an `f64` of 1e300 prints with 301 digits) are put in short form ([`short`]).
    ///
    /// ```
    /// let e = spiralcam::field::FieldError::new("feed", 1.8e305, "must be below 1e3");
    /// assert_eq!(e.to_string(), "feed = 1.8e305: must be below 1e3");
    /// ```
    pub fn new(field: impl Into<String>, value: impl ToString, allowed: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            value: shorten_numbers(&value.to_string()),
            allowed: shorten_numbers(&allowed.into()),
        }
    }

    /// The same error with `prefix.` put in front of the field path.
    pub fn within(mut self, prefix: &str) -> Self {
        self.field = format!("{prefix}.{}", self.field);
        self
    }
}

/// The shortest length a surface's feature may have, mm: 1 nm, the last digit of the program's
/// coordinates at the default 6 decimals. A wavelength, pitch or normalisation radius below it
/// describes nothing a lathe can cut and would only make the planner sample without end.
pub const MIN_LENGTH_MM: f64 = 1e-6;

/// A number in short form, at most 7 significant digits: as Rust writes it between 1e-4 and 1e6
/// (`0.25`, `1234.567`), else in scientific notation (`9.7e-17`, `1.8e305`).
///
/// ```
/// use spiralcam::field::short;
/// assert_eq!(short(0.25), "0.25");
/// assert_eq!(short(9.7e-17), "9.7e-17");
/// assert_eq!(short(1.0 / 3.0 * 1e20), "3.333333e19");
/// assert_eq!(short(f64::NAN), "NaN");
/// ```
pub fn short(v: f64) -> String {
    let a = v.abs();
    if !v.is_finite() || a == 0.0 {
        return v.to_string();
    }
    if (1e-4..1e6).contains(&a) {
        let plain = v.to_string();
        if plain.len() <= 12 {
            return plain;
        }
        let decimals = (6 - a.log10().floor() as i32).max(0) as usize;
        let fixed = format!("{v:.decimals$}");
        return match fixed.contains('.') {
            true => fixed
                .trim_end_matches('0')
                .trim_end_matches('.')
                .to_string(),
            false => fixed,
        };
    }
    let s = format!("{v:.6e}");
    match s.split_once('e') {
        Some((mantissa, exp)) if mantissa.contains('.') => {
            let m = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{m}e{exp}")
        }
        _ => s,
    }
}

/// `text` with every long number (see `is_long`) put in [`short`] form.
pub fn shorten_numbers(text: &str) -> String {
    let is_num = |c: char| c.is_ascii_digit() || c == '.';
    let mut out = String::with_capacity(text.len().min(256));
    let mut rest = text;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        let (head, tail) = rest.split_at(start);
        // A sign directly before the digits belongs to the number.
        let (head, sign) = match head.strip_suffix('-') {
            Some(h) => (h, "-"),
            None => (head, ""),
        };
        out.push_str(head);
        let mut end = tail.find(|c: char| !is_num(c)).unwrap_or(tail.len());
        // An exponent: e or E, an optional sign, digits.
        let after = &tail[end..];
        if let Some(exp) = after.strip_prefix(['e', 'E']) {
            let digits = exp.strip_prefix(['-', '+']).unwrap_or(exp);
            let n = digits
                .find(|c: char| !c.is_ascii_digit())
                .unwrap_or(digits.len());
            if n > 0 {
                end += 1 + (exp.len() - digits.len()) + n;
            }
        }
        let token = format!("{sign}{}", &tail[..end]);
        match token.parse::<f64>() {
            Ok(v) if is_long(&token, v) => out.push_str(&short(v)),
            _ => out.push_str(&token),
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

/// Whether a number as written is long enough to shorten: over 20 characters, or a decimal
/// fraction of over 10 beyond 1e±6 (`0.000000000000000097`); whole numbers (counts, indices)
/// of 20 digits or fewer are kept as they are.
fn is_long(token: &str, v: f64) -> bool {
    let a = v.abs();
    token.len() > 20
        || (token.contains('.') && token.len() > 10 && !(a == 0.0 || (1e-6..1e6).contains(&a)))
}

/// `value` if it is a length of at least [`MIN_LENGTH_MM`] (finite).
pub fn length(field: &str, value: f64) -> Result<f64, FieldError> {
    if value.is_finite() && value >= MIN_LENGTH_MM {
        Ok(value)
    } else {
        Err(FieldError::new(
            field,
            value,
            "must be a length of at least 1e-6 mm (1 nm, the last digit of the program's \
             coordinates)",
        ))
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

/// An internally tagged object (`{"type": "asphere", …}`) split into its tag and the rest, for
/// enums whose variants are deserialized by [`tagged_variant`]. serde's derived tagged enums
/// buffer the content and lose the path of an error inside a variant (`surface` instead of
/// `surface.phase_y_deg`); these two keep it.
pub fn split_tag<'de, D: serde::Deserializer<'de>>(
    de: D,
    tag: &str,
) -> Result<(String, serde_json::Value), D::Error> {
    let value = serde_json::Value::deserialize(de)?;
    let serde_json::Value::Object(mut map) = value else {
        return Err(D::Error::custom(format!(
            "must be an object with \"{tag}\", not {}",
            json_kind(&value)
        )));
    };
    match map.remove(tag) {
        Some(serde_json::Value::String(t)) => Ok((t, serde_json::Value::Object(map))),
        Some(other) => Err(D::Error::custom(format!(
            "{tag}: must be a string, not {}",
            json_kind(&other)
        ))),
        None => Err(D::Error::custom(format!("missing field `{tag}`"))),
    }
}

/// The content of a tagged variant, deserialized with the path of an error inside it kept at the
/// front of the message (`base.radius_mm: invalid type …`), where [`join_path`] finds it.
pub fn tagged_variant<T: DeserializeOwned, E: serde::de::Error>(
    content: serde_json::Value,
) -> Result<T, E> {
    serde_path_to_error::deserialize(content).map_err(|e| {
        let path = e.path().to_string();
        E::custom(join_path(&path, &e.inner().to_string()))
    })
}

use serde::Deserialize as _;

/// `outer: message`, with a path that `message` starts with (`inner.path: …`, as
/// [`tagged_variant`] writes it) joined to `outer` (`outer.inner.path: …`). A path is a run of
/// identifiers and `[n]` indices joined by dots, directly followed by `": "`; serde's own
/// messages never start that way.
///
/// ```
/// use spiralcam::field::join_path;
/// assert_eq!(join_path("surface", "base.radius_mm: invalid type"), "surface.base.radius_mm: invalid type");
/// assert_eq!(join_path("surface", "missing field `type`"), "surface: missing field `type`");
/// assert_eq!(join_path(".", "invalid type: map"), "invalid type: map");
/// ```
pub fn join_path(outer: &str, message: &str) -> String {
    let outer = if outer == "." { "" } else { outer };
    let inner = message.split_once(": ").filter(|(p, _)| is_path(p));
    match (outer.is_empty(), inner) {
        (true, _) => message.to_string(),
        (false, Some((p, rest))) if p.starts_with('[') => format!("{outer}{p}: {rest}"),
        (false, Some((p, rest))) => format!("{outer}.{p}: {rest}"),
        (false, None) => format!("{outer}: {message}"),
    }
}

/// Whether `s` is a field path such as `base.coefficients[2]`.
fn is_path(s: &str) -> bool {
    !s.is_empty()
        && s.split('.').all(|part| {
            let name = part.split('[').next().unwrap_or("");
            let indices = &part[name.len()..];
            (!name.is_empty() || indices.starts_with('['))
                && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
                && indices.split_inclusive(']').all(|i| {
                    i.starts_with('[')
                        && i.ends_with(']')
                        && i[1..i.len() - 1].chars().all(|c| c.is_ascii_digit())
                })
        })
}

/// "an array", "a string", … for messages.
fn json_kind(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "a boolean",
        serde_json::Value::Number(_) => "a number",
        serde_json::Value::String(_) => "a string",
        serde_json::Value::Array(_) => "an array",
        serde_json::Value::Object(_) => "an object",
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

    #[test]
    fn long_numbers_are_put_in_short_form() {
        let long = format!("{}", 1.8e305);
        assert!(long.len() > 300);
        let e = FieldError::new("a", 1.8e305, format!("at most {long} or {}", 9.7e-300));
        assert_eq!(e.to_string(), "a = 1.8e305: at most 1.8e305 or 9.7e-300");
        assert_eq!(
            shorten_numbers("x -0.000000000000000000097 y"),
            "x -9.7e-20 y"
        );
        assert_eq!(
            shorten_numbers("point 12 at 3.25 mm, 1e-3"),
            "point 12 at 3.25 mm, 1e-3"
        );
        assert_eq!(short(123456.0), "123456");
        assert_eq!(short(1234.56789012345), "1234.568");
        assert_eq!(short(1.000001000001e-6), "1.000001e-6");
        assert_eq!(short(-2.5e-7), "-2.5e-7");
        assert_eq!(short(f64::INFINITY), "inf");
    }

    #[test]
    fn lengths_below_a_nanometre_are_refused() {
        assert!(length("w", 1e-6).is_ok());
        let e = length("surface.wavelength_x_mm", 1e-9).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("surface.wavelength_x_mm = 1e-9: must be a length")
        );
        assert!(length("w", f64::INFINITY).is_err());
    }
}
