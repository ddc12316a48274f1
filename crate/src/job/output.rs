//! What is written (`output`): the NC dialect, decimals, signs, wrapping of C, feed mode,
//! approach and the fast tool servo's word. What the writers make of it, the dialect's style
//! and the conventions in effect, is [`crate::nc`]'s (`OutputSpec::style`,
//! `OutputSpec::conventions`).

use super::fts_grid::FtsGridSpec;
use crate::field::{FieldError, non_negative, positive};
use serde::{Deserialize, Serialize};

/// The most decimals of a word: 10⁹ units of the last digit still leave an i64 room for any
/// coordinate below 9·10⁹ mm or degrees.
pub const MAX_DECIMALS: u32 = 9;

/// The words a fast tool servo's channel may take: axis letters no dialect uses for anything
/// else (LinuxCNC reads A, B, U, V, W and Y as axes).
pub const FTS_WORDS: [&str; 6] = ["W", "U", "V", "A", "B", "Y"];

/// The NC dialect.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Dialect {
    /// ISO RS-274 (`G1 X Z C F`), readable by LinuxCNC's `rs274`.
    #[default]
    Iso,
    /// Moore Nanotech style: `G93` once, then bare `C X Z` blocks, C wrapped to [0, 360).
    Moore,
    /// Precitech style: its own header, `G1` blocks, X negative by default.
    Precitech,
}

/// How the feed is programmed. Under `G93` each block's F is computed from the spindle speed
/// and the block's spindle angle ΔC, so that the spindle turns at `machine.spindle_rpm`; what
/// the number means differs between controllers, and no vendor manual of Moore's or
/// Precitech's controllers was available: the three readings known from public material are
/// options, and the program's header states the spindle speed and the cycle time either way.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FeedMode {
    /// `G93` inverse time: F = 1/(block time in minutes) = rpm·360°/ΔC, as RS274/NGC and
    /// LinuxCNC define it (default).
    #[default]
    InverseTime,
    /// `G93` with F the block's time in seconds = 60·ΔC/(360°·rpm), as Beckhoff's TwinCAT CNC
    /// manual defines G93 ("machining time in seconds"); a lab's Moore program running 360
    /// blocks a revolution at `G93 F0.001` reads this way as 167 rpm.
    BlockTimeS,
    /// `G93` with F the block's time in minutes = ΔC/(360°·rpm).
    BlockTimeMin,
    /// `G94` with one F in mm/min (`feed_mm_per_min`), for controllers that run the spindle on
    /// its own.
    PerMinute,
}

impl FeedMode {
    /// Whether the blocks are written under `G93` (F per block from the spindle speed).
    pub fn per_block(self) -> bool {
        self != FeedMode::PerMinute
    }

    /// F of a block turning the spindle by `dc_deg` degrees at `rpm`.
    pub fn block_f(self, rpm: f64, dc_deg: f64) -> f64 {
        match self {
            FeedMode::InverseTime => rpm * 360.0 / dc_deg,
            FeedMode::BlockTimeS => 60.0 * dc_deg / (360.0 * rpm),
            FeedMode::BlockTimeMin => dc_deg / (360.0 * rpm),
            FeedMode::PerMinute => f64::NAN,
        }
    }

    /// What F means, for the program's header.
    pub fn meaning(self) -> &'static str {
        match self {
            FeedMode::InverseTime => "G93 F = 1/block time in minutes (inverse time)",
            FeedMode::BlockTimeS => "G93 F = block time in seconds",
            FeedMode::BlockTimeMin => "G93 F = block time in minutes",
            FeedMode::PerMinute => "G94 F = mm/min",
        }
    }
}

/// The shortest line limit a job may set, characters.
pub const MIN_LINE_CHARS: u32 = 40;

/// Output options of a job. Signs are +1 or −1; unset ones take the dialect's default.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSpec {
    /// `iso` (default), `moore` or `precitech`.
    pub dialect: Dialect,
    /// Decimals of X and Z, 0…9; default 6 (1 nm).
    pub decimals_xz: u32,
    /// Decimals of C, 0…9; default 5 (0.00001°).
    pub decimals_c: u32,
    /// X = x_sign·ρ; default +1 (Precitech −1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub x_sign: Option<i8>,
    /// Z = z_sign·z; default +1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub z_sign: Option<i8>,
    /// C = c_sign·θ; default +1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub c_sign: Option<i8>,
    /// Wrap C to [0, 360); default false for ISO (cumulative, as a rotary axis needs), true
    /// otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wrap_c: Option<bool>,
    /// `inverse_time` (default) or `per_minute`.
    pub feed_mode: FeedMode,
    /// Feed for `per_minute`, mm/min, > 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub feed_mm_per_min: Option<f64>,
    /// Feed of the plunge onto the first point, mm/min, > 0; default 50.
    pub plunge_feed_mm_per_min: f64,
    /// Height of the approach and retract above the first and last point, mm, ≥ 0; default 1.
    pub clearance_mm: f64,
    /// The word of the fast tool servo's channel in split programs: one of `A B U V W Y`;
    /// default `Y` for ISO (a linear axis LinuxCNC's interpreter always reads), `W` otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fts_word: Option<String>,
    /// Longest line, characters (≥ 40); default the dialect's (ISO 252: LinuxCNC's rs274 refuses
    /// lines of 253 characters and more;
    /// Moore and Precitech styles 128). Longer comments are wrapped over several lines; a block
    /// longer than this is an error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_line_chars: Option<u32>,
    /// Decimals of F, 0…9; default 3, 6 for the block-time feed modes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub decimals_f: Option<u32>,
    /// The servo's gridded table (`spiralcam plan --fts-table`): tolerance, counts and motors;
    /// absent: the defaults ([`FtsGridSpec::default`]) when the table is asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fts_grid: Option<FtsGridSpec>,
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            dialect: Dialect::Iso,
            decimals_xz: 6,
            decimals_c: 5,
            x_sign: None,
            z_sign: None,
            c_sign: None,
            wrap_c: None,
            feed_mode: FeedMode::InverseTime,
            feed_mm_per_min: None,
            plunge_feed_mm_per_min: 50.0,
            clearance_mm: 1.0,
            fts_word: None,
            max_line_chars: None,
            decimals_f: None,
            fts_grid: None,
        }
    }
}

impl OutputSpec {
    /// Checks the options.
    pub fn validate(&self) -> Result<(), FieldError> {
        if let Some(n) = self.max_line_chars
            && n < MIN_LINE_CHARS
        {
            return Err(FieldError::new(
                "max_line_chars",
                n,
                format!("at least {MIN_LINE_CHARS}"),
            ));
        }
        for (field, d) in [
            ("decimals_xz", self.decimals_xz),
            ("decimals_c", self.decimals_c),
            ("decimals_f", self.decimals_f.unwrap_or(0)),
        ] {
            if d > MAX_DECIMALS {
                return Err(FieldError::new(
                    field,
                    d,
                    format!("must lie in [0, {}]", MAX_DECIMALS),
                ));
            }
        }
        for (field, s) in [
            ("x_sign", self.x_sign),
            ("z_sign", self.z_sign),
            ("c_sign", self.c_sign),
        ] {
            if let Some(s) = s.filter(|s| s.abs() != 1) {
                return Err(FieldError::new(field, s, "must be 1 or -1"));
            }
        }
        match (self.feed_mode, self.feed_mm_per_min) {
            (FeedMode::PerMinute, None) => {
                return Err(FieldError::new(
                    "feed_mm_per_min",
                    "missing",
                    "required with feed_mode per_minute",
                ));
            }
            (_, Some(f)) => {
                positive("feed_mm_per_min", f)?;
            }
            _ => {}
        }
        positive("plunge_feed_mm_per_min", self.plunge_feed_mm_per_min)?;
        non_negative("clearance_mm", self.clearance_mm)?;
        if let Some(word) = &self.fts_word
            && !FTS_WORDS.iter().any(|w| w == word)
        {
            let allowed = format!("must be one of {}", FTS_WORDS.join(", "));
            return Err(FieldError::new("fts_word", format!("{word:?}"), allowed));
        }
        if let Some(grid) = &self.fts_grid {
            grid.validate()?;
        }
        Ok(())
    }
}
