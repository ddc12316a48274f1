//! The program an operator runs as written (`program`, issue 12): the set-up words (work
//! offset, tool, the C-axis mode), the safe and retract heights, a staged approach, the passes
//! (roughing with a depth of cut, then the finish), whether the controller repeats one pass body
//! in a loop or every pass is written out, and the size past which the program is split into a
//! main program calling child programs. Absent, a job gets today's one-spiral program.
//!
//! **Passes.** `passes` is a list of groups, cut in order; group g has `count` passes of
//! `depth_of_cut_um` each. The stock is S = Σ countₖ·depthₖ; the k-th pass overall cuts the design
//! raised along Z by the stock still left after it, `S − (depth of passes 1…k)`, so the last
//! pass cuts the design itself. A group with its own `feed_mm_per_rev` or `spindle_rpm` is its
//! own spiral (the others use the strategy's feed and the machine's speed).
//!
//! The words are styles, not any controller's specification: check them against the
//! controller's manual (see the NC dialects' docs for the defaults each writes).

use crate::field::{FieldError, finite, positive};
use serde::{Deserialize, Serialize};

/// Most passes in all.
pub const MAX_PASSES: u32 = 1000;
/// The smallest program size limit, bytes: a header, a loop and a call must fit.
pub const MIN_PROGRAM_BYTES: u64 = 4096;

/// The `program` section of a job.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProgramSpec {
    /// Work offset, `G54` … `G59`; absent: none written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub work_offset: Option<String>,
    /// Tool word, `T` and 1 to 8 digits (`T0303`); absent: none written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tool: Option<String>,
    /// M word that puts the spindle in C-axis (position) mode (`M26.1` on the lab's Moore);
    /// absent: none written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c_axis_on: Option<String>,
    /// M word that ends C-axis mode (`M29`); absent: none written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c_axis_off: Option<String>,
    /// Z the program starts and ends at, mm, in the part's frame; default the path's highest
    /// commanded Z plus the stock plus `output.clearance_mm`. Must clear every pass.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub safe_z_mm: Option<f64>,
    /// Z of the retract after each pass and of the link to the next, mm, in the pass's frame
    /// (the design raised by the stock left); default the path's highest Z plus
    /// `output.clearance_mm`. Must clear the pass.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub retract_height_mm: Option<f64>,
    /// Staged approach above the first cutting point: heights decreasing, each reached at its
    /// feed (G94); then the last step to the cut at `output.plunge_feed_mm_per_min`. Empty
    /// (default): straight from the retract height at the plunge feed.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub approach: Vec<ApproachStep>,
    /// The passes, cut in order; default (absent) one pass cutting the design. A list given
    /// empty is refused.
    #[serde(
        default,
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "non_empty"
    )]
    pub passes: Vec<PassGroup>,
    /// `unrolled` (default: every pass written out, its Z raised by its stock) or
    /// `controller` (one pass body per group that the controller repeats, the stock kept in a
    /// variable and applied by a `G52` Z shift).
    #[serde(default, rename = "loop")]
    pub loop_kind: LoopKind,
    /// Largest program file, bytes; past it the cutting blocks go into child programs that a
    /// main program calls (`M98 P…`, or `o<…> call` in ISO). Absent: one file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_program_bytes: Option<u64>,
}

/// One step of the staged approach.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ApproachStep {
    /// Height above the first cutting point, mm, > 0.
    pub height_mm: f64,
    /// Feed to reach it, mm/min, > 0.
    pub feed_mm_per_min: f64,
}

/// A group of equal passes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PassGroup {
    /// Passes in the group, ≥ 1.
    pub count: u32,
    /// Depth of cut of each, µm, > 0.
    pub depth_of_cut_um: f64,
    /// Feed of the group's spiral, mm/rev; default the strategy's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub feed_mm_per_rev: Option<f64>,
    /// Spindle speed of the group, rev/min; default the machine's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spindle_rpm: Option<f64>,
}

/// How the passes of a group are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LoopKind {
    /// Every pass written out.
    #[default]
    Unrolled,
    /// One body per group, repeated by the controller.
    Controller,
}

/// One pass of the program, as cut.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pass {
    /// Its group's index in `passes`.
    pub group: usize,
    /// Stock left after it, mm (the design is raised by this along Z).
    pub stock_mm: f64,
}

impl ProgramSpec {
    /// The passes in order, with the stock each leaves; one pass at stock 0 when `passes` is
    /// empty.
    pub fn pass_list(&self) -> Vec<Pass> {
        if self.passes.is_empty() {
            return vec![Pass {
                group: 0,
                stock_mm: 0.0,
            }];
        }
        let mut left = self.stock_mm();
        let mut out = Vec::new();
        for (g, group) in self.passes.iter().enumerate() {
            for _ in 0..group.count {
                left -= group.depth_of_cut_um * 1e-3;
                out.push(Pass {
                    group: g,
                    stock_mm: left.max(0.0),
                });
            }
        }
        // The last pass cuts the design exactly, whatever the rounding of the sum.
        if let Some(last) = out.last_mut() {
            last.stock_mm = 0.0;
        }
        out
    }

    /// The stock before the first pass, mm: Σ count·depth.
    pub fn stock_mm(&self) -> f64 {
        self.passes
            .iter()
            .map(|g| g.count as f64 * g.depth_of_cut_um * 1e-3)
            .sum()
    }

    /// Checks every field (paths relative to `program`).
    pub fn validate(&self) -> Result<(), FieldError> {
        if let Some(w) = &self.work_offset
            && !["G54", "G55", "G56", "G57", "G58", "G59"].contains(&w.as_str())
        {
            return Err(FieldError::new(
                "work_offset",
                format!("{w:?}"),
                "one of G54, G55, G56, G57, G58, G59",
            ));
        }
        if let Some(t) = &self.tool {
            let digits = t.strip_prefix('T').unwrap_or("");
            if digits.is_empty() || digits.len() > 8 || !digits.bytes().all(|b| b.is_ascii_digit())
            {
                return Err(FieldError::new(
                    "tool",
                    format!("{t:?}"),
                    "a T word: T and 1 to 8 digits, e.g. \"T0303\"",
                ));
            }
        }
        for (field, m) in [
            ("c_axis_on", &self.c_axis_on),
            ("c_axis_off", &self.c_axis_off),
        ] {
            if let Some(m) = m
                && !is_m_word(m)
            {
                return Err(FieldError::new(
                    field,
                    format!("{m:?}"),
                    "an M word: M, 1 to 4 digits and an optional .digit, e.g. \"M26.1\"",
                ));
            }
        }
        if let Some(z) = self.safe_z_mm {
            finite("safe_z_mm", z)?;
        }
        if let Some(z) = self.retract_height_mm {
            finite("retract_height_mm", z)?;
        }
        let mut above = f64::INFINITY;
        for (k, step) in self.approach.iter().enumerate() {
            let h = positive(&format!("approach[{k}].height_mm"), step.height_mm)?;
            positive(
                &format!("approach[{k}].feed_mm_per_min"),
                step.feed_mm_per_min,
            )?;
            if h >= above {
                return Err(FieldError::new(
                    format!("approach[{k}].height_mm"),
                    h,
                    format!("must be below the step before it ({above} mm): heights decrease"),
                ));
            }
            above = h;
        }
        let mut total = 0u64;
        for (k, g) in self.passes.iter().enumerate() {
            if g.count == 0 {
                return Err(FieldError::new(
                    format!("passes[{k}].count"),
                    0,
                    "at least 1",
                ));
            }
            total += g.count as u64;
            let depth = positive(&format!("passes[{k}].depth_of_cut_um"), g.depth_of_cut_um)?;
            if depth > 1e4 {
                return Err(FieldError::new(
                    format!("passes[{k}].depth_of_cut_um"),
                    depth,
                    "at most 10000 µm (10 mm) a pass",
                ));
            }
            if let Some(f) = g.feed_mm_per_rev {
                positive(&format!("passes[{k}].feed_mm_per_rev"), f)?;
            }
            if let Some(n) = g.spindle_rpm {
                positive(&format!("passes[{k}].spindle_rpm"), n)?;
            }
        }
        if total > MAX_PASSES as u64 {
            return Err(FieldError::new(
                "passes",
                format!("{total} passes"),
                format!("at most {MAX_PASSES} passes in all"),
            ));
        }
        if let Some(b) = self.max_program_bytes
            && b < MIN_PROGRAM_BYTES
        {
            return Err(FieldError::new(
                "max_program_bytes",
                b,
                format!(
                    "at least {MIN_PROGRAM_BYTES} bytes: a header, a pass and a call must fit in \
                     the main program"
                ),
            ));
        }
        Ok(())
    }

    /// Whether the program has a group whose feed or speed differs from the strategy's.
    pub fn has_own_spirals(&self) -> bool {
        self.passes
            .iter()
            .any(|g| g.feed_mm_per_rev.is_some() || g.spindle_rpm.is_some())
    }
}

/// Reads `passes`, refusing an empty list (absent means one pass; empty is a mistake).
fn non_empty<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<PassGroup>, D::Error> {
    let passes = Vec::<PassGroup>::deserialize(d)?;
    if passes.is_empty() {
        return Err(serde::de::Error::custom(
            "no passes: give at least one {\"count\", \"depth_of_cut_um\"}, or leave `passes` \
             out for one pass cutting the design",
        ));
    }
    Ok(passes)
}

/// `M`, 1 to 4 digits, optionally `.` and one or two digits.
fn is_m_word(m: &str) -> bool {
    let Some(rest) = m.strip_prefix('M') else {
        return false;
    };
    let (whole, frac) = rest.split_once('.').unwrap_or((rest, ""));
    let digits = |s: &str, lo: usize, hi: usize| {
        (lo..=hi).contains(&s.len()) && s.bytes().all(|b| b.is_ascii_digit())
    };
    digits(whole, 1, 4) && (!rest.contains('.') || digits(frac, 1, 2))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn group(count: u32, depth: f64) -> PassGroup {
        PassGroup {
            count,
            depth_of_cut_um: depth,
            feed_mm_per_rev: None,
            spindle_rpm: None,
        }
    }

    #[test]
    fn each_pass_leaves_the_stock_after_it() {
        let p = ProgramSpec {
            passes: vec![group(2, 5.0), group(1, 2.0), group(1, 1.0)],
            ..Default::default()
        };
        assert!((p.stock_mm() - 0.013).abs() < 1e-15);
        let stock: Vec<f64> = p.pass_list().iter().map(|q| q.stock_mm).collect();
        let want = [0.008, 0.003, 0.001, 0.0];
        for (s, w) in stock.iter().zip(want) {
            assert!((s - w).abs() < 1e-15, "{stock:?}");
        }
        assert_eq!(
            p.pass_list().iter().map(|q| q.group).collect::<Vec<_>>(),
            [0, 0, 1, 2]
        );
        assert_eq!(ProgramSpec::default().pass_list().len(), 1);
    }

    #[test]
    fn bad_fields_are_named() {
        let bad = |p: ProgramSpec| p.validate().unwrap_err().to_string();
        let step = |h: f64| ApproachStep {
            height_mm: h,
            feed_mm_per_min: 100.0,
        };
        assert!(
            bad(ProgramSpec {
                approach: vec![step(5.0), step(5.0)],
                ..Default::default()
            })
            .starts_with("approach[1].height_mm = 5: must be below")
        );
        assert!(
            bad(ProgramSpec {
                approach: vec![step(-1.0)],
                ..Default::default()
            })
            .starts_with("approach[0].height_mm = -1")
        );
        assert!(
            bad(ProgramSpec {
                passes: vec![group(0, 1.0)],
                ..Default::default()
            })
            .starts_with("passes[0].count = 0")
        );
        assert!(
            bad(ProgramSpec {
                passes: vec![group(1, -2.0)],
                ..Default::default()
            })
            .starts_with("passes[0].depth_of_cut_um = -2")
        );
        assert!(
            bad(ProgramSpec {
                tool: Some("T3a".into()),
                ..Default::default()
            })
            .starts_with("tool = \"T3a\"")
        );
        assert!(
            bad(ProgramSpec {
                c_axis_on: Some("G26".into()),
                ..Default::default()
            })
            .starts_with("c_axis_on = \"G26\"")
        );
        assert!(
            bad(ProgramSpec {
                work_offset: Some("G60".into()),
                ..Default::default()
            })
            .starts_with("work_offset = \"G60\"")
        );
        assert!(
            bad(ProgramSpec {
                max_program_bytes: Some(100),
                ..Default::default()
            })
            .starts_with("max_program_bytes = 100")
        );
        assert!(is_m_word("M26.1") && is_m_word("M29") && !is_m_word("M") && !is_m_word("M2."));
    }
}
