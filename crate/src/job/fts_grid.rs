//! The fast tool servo's gridded table (`output.fts_grid`): how finely the table written by
//! `spiralcam plan --fts-table` must reproduce the planned W, and the controller's counts and
//! motors it is written in. The grid itself is the dynamics' ([`crate::dynamics::fts_grid`]),
//! the PMAC-style text and the CSV the NC layer's ([`crate::nc::fts_grid`]).

use crate::field::{FieldError, positive};
use serde::{Deserialize, Serialize};

/// The highest motor number a table may name: Turbo PMAC has motors 1 to 32.
pub const MAX_MOTOR: u8 = 32;

/// The most counts per revolution or per mm accepted: 2⁴⁷, so that every position and span of
/// a part within a metre stays exact in an `f64` and an `i64`.
pub const MAX_COUNTS: f64 = 140_737_488_355_328.0;

/// The table's options. Every field has a default; an empty object `{}` takes them all.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FtsGridSpec {
    /// The largest error allowed of the table's bilinear interpolation against the planned W
    /// at any path point, µm, > 0 and above the table's resolution (half of 1/16 count of the
    /// servo); default 0.05.
    pub tolerance_um: f64,
    /// Counts per mm of the X motor, > 0; default 1 000 000 (1 nm a count).
    pub x_counts_per_mm: f64,
    /// Counts per revolution of the spindle's (C) motor, a whole number ≥ 4; default
    /// 3 600 000 (0.0001° a count).
    pub c_counts_per_rev: u64,
    /// Counts per mm of the servo's motor (the table's target), > 0; default 1 000 000.
    pub w_counts_per_mm: f64,
    /// The X motor's number, 1…32; default 1.
    pub x_motor: u8,
    /// The spindle (C) motor's number, 1…32; default 3.
    pub c_motor: u8,
    /// The servo (W) motor's number, 1…32; default 4. The table belongs to it.
    pub w_motor: u8,
    /// The table reads the source motors' desired (commanded) positions (`D` after their
    /// numbers) rather than their actual ones; default false.
    pub desired_position: bool,
}

impl Default for FtsGridSpec {
    fn default() -> Self {
        Self {
            tolerance_um: 0.05,
            x_counts_per_mm: 1e6,
            c_counts_per_rev: 3_600_000,
            w_counts_per_mm: 1e6,
            x_motor: 1,
            c_motor: 3,
            w_motor: 4,
            desired_position: false,
        }
    }
}

impl FtsGridSpec {
    /// The table's resolution: half of 1/16 count of the servo, µm (what rounding an entry
    /// to a whole 1/16 count may add).
    pub fn resolution_um(&self) -> f64 {
        1e3 / (32.0 * self.w_counts_per_mm)
    }

    /// Checks the options; fields are named from `fts_grid` (the job's checks put `output.`
    /// before them).
    ///
    /// ```
    /// use spiralcam::job::FtsGridSpec;
    /// let spec = FtsGridSpec { w_motor: 1, ..FtsGridSpec::default() };
    /// assert_eq!(spec.validate().unwrap_err().to_string(),
    ///     "fts_grid.w_motor = 1: must differ from output.fts_grid.x_motor (1) and \
    ///      output.fts_grid.c_motor (3)");
    /// ```
    pub fn validate(&self) -> Result<(), FieldError> {
        for (field, v) in [
            ("x_counts_per_mm", self.x_counts_per_mm),
            ("w_counts_per_mm", self.w_counts_per_mm),
        ] {
            positive(field, v).map_err(|e| e.within("fts_grid"))?;
            if v > MAX_COUNTS {
                return Err(FieldError::new(
                    format!("fts_grid.{field}"),
                    v,
                    format!("must be at most {MAX_COUNTS}"),
                ));
            }
        }
        if !(4..=MAX_COUNTS as u64).contains(&self.c_counts_per_rev) {
            return Err(FieldError::new(
                "fts_grid.c_counts_per_rev",
                self.c_counts_per_rev,
                format!("must be a whole number in [4, {MAX_COUNTS}]"),
            ));
        }
        for (field, m) in [
            ("x_motor", self.x_motor),
            ("c_motor", self.c_motor),
            ("w_motor", self.w_motor),
        ] {
            if !(1..=MAX_MOTOR).contains(&m) {
                return Err(FieldError::new(
                    format!("fts_grid.{field}"),
                    m,
                    format!("must be a motor number in [1, {MAX_MOTOR}]"),
                ));
            }
        }
        if self.c_motor == self.x_motor {
            return Err(FieldError::new(
                "fts_grid.c_motor",
                self.c_motor,
                "must differ from output.fts_grid.x_motor: the table's two source motors",
            ));
        }
        if self.w_motor == self.x_motor || self.w_motor == self.c_motor {
            return Err(FieldError::new(
                "fts_grid.w_motor",
                self.w_motor,
                format!(
                    "must differ from output.fts_grid.x_motor ({}) and output.fts_grid.c_motor \
                     ({})",
                    self.x_motor, self.c_motor
                ),
            ));
        }
        positive("fts_grid.tolerance_um", self.tolerance_um)?;
        let resolution = self.resolution_um();
        if self.tolerance_um <= resolution {
            return Err(FieldError::new(
                "fts_grid.tolerance_um",
                self.tolerance_um,
                format!(
                    "must exceed the table's resolution, {resolution:.3e} µm (half of 1/16 count \
                     at output.fts_grid.w_counts_per_mm = {})",
                    self.w_counts_per_mm
                ),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(spec: FtsGridSpec) -> String {
        spec.validate().unwrap_err().to_string()
    }

    #[test]
    fn defaults_are_valid_and_an_empty_object_takes_them() {
        FtsGridSpec::default().validate().unwrap();
        let spec: FtsGridSpec = serde_json::from_str("{}").unwrap();
        assert_eq!(spec, FtsGridSpec::default());
        let e = serde_json::from_str::<FtsGridSpec>(r#"{"tolerance":1}"#).unwrap_err();
        assert!(e.to_string().contains("unknown field `tolerance`"), "{e}");
    }

    #[test]
    fn bad_options_are_named() {
        let d = FtsGridSpec::default;
        assert_eq!(
            error(FtsGridSpec {
                tolerance_um: 0.0,
                ..d()
            }),
            "fts_grid.tolerance_um = 0: must be a finite number > 0"
        );
        assert_eq!(
            error(FtsGridSpec {
                tolerance_um: 1e-5,
                ..d()
            }),
            "fts_grid.tolerance_um = 0.00001: must exceed the table's resolution, 3.125e-5 µm \
             (half of 1/16 count at output.fts_grid.w_counts_per_mm = 1000000)"
        );
        assert_eq!(
            error(FtsGridSpec {
                x_counts_per_mm: f64::NAN,
                ..d()
            }),
            "fts_grid.x_counts_per_mm = NaN: must be a finite number > 0"
        );
        assert_eq!(
            error(FtsGridSpec {
                w_counts_per_mm: 1e20,
                ..d()
            }),
            "fts_grid.w_counts_per_mm = 1e20: must be at most 140737488355328"
        );
        assert_eq!(
            error(FtsGridSpec {
                c_counts_per_rev: 3,
                ..d()
            }),
            "fts_grid.c_counts_per_rev = 3: must be a whole number in [4, 140737488355328]"
        );
        assert_eq!(
            error(FtsGridSpec { x_motor: 0, ..d() }),
            "fts_grid.x_motor = 0: must be a motor number in [1, 32]"
        );
        assert_eq!(
            error(FtsGridSpec { c_motor: 33, ..d() }),
            "fts_grid.c_motor = 33: must be a motor number in [1, 32]"
        );
        assert_eq!(
            error(FtsGridSpec { c_motor: 1, ..d() }),
            "fts_grid.c_motor = 1: must differ from output.fts_grid.x_motor: the table's two \
             source motors"
        );
        assert!(error(FtsGridSpec { w_motor: 3, ..d() }).starts_with("fts_grid.w_motor = 3"));
    }
}
