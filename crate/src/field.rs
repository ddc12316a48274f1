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

/// The feed that brings a cost going as 1/f (points, bytes, time) from `ratio` times its limit
/// to within it, as the refusals suggest it: `feed · ratio`, a millionth over, so that its
/// [`short`] digits do not fall back under the limit.
///
/// ```
/// use spiralcam::field::{feed_within, short};
/// assert_eq!(short(feed_within(0.01, 4.32)), "0.04320004");
/// ```
pub fn feed_within(feed: f64, ratio: f64) -> f64 {
    feed * ratio * (1.0 + 1e-6)
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

/// Deterministic pseudo-random numbers for tests: one generator, so that test data are drawn
/// alike everywhere.
#[cfg(test)]
pub(crate) mod test_random {
    /// The next number in [0, 1) of the linear congruential sequence in `state` (Knuth's MMIX
    /// constants, the top 53 bits).
    pub fn uniform(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }
}
