//! The NC layer: point-to-point `C X Z` programs in three dialects, a CSV of the points, the
//! fast tool servo's table and its gridded table ([`fts_grid`], a PMAC-style 2-D compensation
//! table and its CSV), written from the path's points ([`crate::path::PathPoint`]) with the
//! job's output options ([`crate::job::OutputSpec`]); it uses nothing else above the helpers.
//!
//! Every program has the same shape: a header of comments restating the job; the dialect's
//! preamble; the approach (rapid to `Z = z₀ + clearance`, rapid to `X₀ C₀`, feed down to z₀);
//! one linear block per path point after the first; the retract (`Z + clearance`) and the end.
//! Machine words come from the path through the sign options: `X = x_sign·ρ`,
//! `Z = z_sign·z_tip` (the tool tip, nose centre − r), `C = c_sign·θ` in degrees, wrapped to
//! [0, 360) or cumulative. A path split between the slide and a fast tool servo
//! ([`NcWriter::point_split`]) adds the FTS word (`W` unless `output.fts_word` names another)
//! after the others: `Z` is the slide's share, `W` the servo's, rounded so that the written
//! `Z + W` equals, digit for digit, the `Z` a single-channel program would write. With
//! inverse-time feed (G93) each block's F is
//! `1 / (block time in minutes) = rpm·360° / |ΔC|`, so the spindle turns at the job's speed.
//!
//! The dialects ([`Dialect`]) are styles, not vendor specifications: ISO RS-274 as read by
//! LinuxCNC's interpreter, and our reading of Moore Nanotech (Delta Tau) and Precitech programs.
//! Check signs and words against your controller; each is an option. Output is reproducible: no
//! dates, no host names. Comments are plain ASCII.
//!
//! The [`reader`] goes the other way: it runs a program of any of these dialects (or written by
//! another system) and hands out its moves, for verification against the design.

pub mod blocks;
pub mod csv;
pub mod fts_grid;
pub mod fts_table;
mod iso;
mod moore;
pub mod number;
mod precitech;
pub mod program;
pub mod reader;

pub use csv::CsvWriter;
pub use fts_table::FtsTableWriter;

use crate::job::{Dialect, FeedMode, OutputSpec};
use crate::path::PathPoint;
pub use blocks::{Blocks, comment_lines};
use number::{push_scaled, scaled};
use std::io::Write;
use thiserror::Error;

/// What the writers make of a job's output options ([`crate::job::output`]).
impl OutputSpec {
    /// The dialect's style.
    pub fn style(&self) -> &'static Style {
        match self.dialect {
            Dialect::Iso => &iso::STYLE,
            Dialect::Moore => &moore::STYLE,
            Dialect::Precitech => &precitech::STYLE,
        }
    }

    /// The conventions in effect: signs and wrapping after the dialect's defaults.
    pub fn conventions(&self) -> Conventions {
        let st = self.style();
        Conventions {
            x_sign: self.x_sign.map_or(st.x_sign, f64::from),
            z_sign: self.z_sign.map_or(1.0, f64::from),
            c_sign: self.c_sign.map_or(1.0, f64::from),
            wrap_c: self.wrap_c.unwrap_or(st.wrap_c),
            decimals_xz: self.decimals_xz,
            decimals_c: self.decimals_c,
            fts_word: self
                .fts_word
                .as_deref()
                .and_then(|w| w.bytes().next())
                .unwrap_or(st.fts_word),
        }
    }

    /// The longest line written, characters.
    pub fn max_line(&self) -> usize {
        self.max_line_chars.unwrap_or(self.style().max_line) as usize
    }

    /// Decimals of F.
    pub fn decimals_f(&self) -> u32 {
        self.decimals_f.unwrap_or(match self.feed_mode {
            FeedMode::BlockTimeS | FeedMode::BlockTimeMin => 6,
            _ => 3,
        })
    }
}

/// What distinguishes the dialects.
#[derive(Debug)]
pub struct Style {
    /// Name for headers.
    pub name: &'static str,
    /// File extension of programs.
    pub extension: &'static str,
    /// Lines after the header comments.
    pub preamble: &'static [&'static str],
    /// Prefix of each linear block (`"G1 "` or empty).
    pub block_prefix: &'static str,
    /// Word order within a block.
    pub words: [Axis; 3],
    /// F on every inverse-time block (LinuxCNC requires it) or only when it changes.
    pub feed_every_block: bool,
    /// Default sign of X.
    pub x_sign: f64,
    /// Default for wrapping C.
    pub wrap_c: bool,
    /// Lines that end the program.
    pub end: &'static [&'static str],
    /// Default word of the fast tool servo.
    pub fts_word: u8,
    /// Longest line the controller reads, characters (a style's assumption; the job can set it).
    pub max_line: u32,
    /// How loops, variables and subprogram calls are written.
    pub macros: Macros,
}

/// The dialect's control flow: loops, variables and calls of child programs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Macros {
    /// Fanuc macro B style (Moore, Precitech styles): `#100 = …`, `WHILE [#103 LT #100] DO 1`
    /// … `END 1`, `G52 Z[#102]`; children `O1` … `M99`, called by `M98 P1`.
    Fanuc,
    /// LinuxCNC: `#<stock> = …`, `o100 repeat [n]` … `o100 endrepeat`, `G52 Z#<stock>`;
    /// children `o<name-1> sub` … `o<name-1> endsub`, called by `o<name-1> call`.
    LinuxCnc,
}

/// An axis word.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// Spindle angle, degrees.
    C,
    /// Radial slide, mm.
    X,
    /// Axial slide, mm.
    Z,
}

/// Signs, wrapping and decimals in effect for a program and its CSV.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conventions {
    /// X = x_sign·ρ.
    pub x_sign: f64,
    /// Z = z_sign·z.
    pub z_sign: f64,
    /// C = c_sign·θ.
    pub c_sign: f64,
    /// Wrap C to [0, 360).
    pub wrap_c: bool,
    /// Decimals of X and Z.
    pub decimals_xz: u32,
    /// Decimals of C.
    pub decimals_c: u32,
    /// Letter of the fast tool servo's word.
    pub fts_word: u8,
}

/// Machine words of one point, in units of their last digit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Words {
    /// C, units of 10^−decimals_c degrees.
    pub c: i64,
    /// X, units of 10^−decimals_xz mm.
    pub x: i64,
    /// Z, units of 10^−decimals_xz mm (the slide's share in a split program).
    pub z: i64,
    /// W, the fast tool servo's share, units of 10^−decimals_xz mm; `None` without a servo.
    pub w: Option<i64>,
}

impl Conventions {
    /// The words of a point at (ρ, θ, z), or an error naming the value that cannot be written.
    pub fn words(&self, index: u64, rho: f64, theta: f64, z: f64) -> Result<Words, NcError> {
        let at = Some((rho, theta));
        let bad = |what: &'static str, value: f64| NcError::Unwritable {
            index,
            what,
            value,
            at,
        };
        let x = scaled(self.x_sign * rho, self.decimals_xz).ok_or_else(|| bad("X", rho))?;
        let z = scaled(self.z_sign * z, self.decimals_xz).ok_or_else(|| bad("Z", z))?;
        let mut c = scaled(self.c_sign * theta.to_degrees(), self.decimals_c)
            .ok_or_else(|| bad("C", theta))?;
        if self.wrap_c {
            c = wrap(c, 360 * number::pow10(self.decimals_c));
        }
        Ok(Words { c, x, z, w: None })
    }

    /// The words of a point whose height `z` is split: the slide at `z_slide`, the servo the
    /// rest. Z and the sum are rounded, W is their difference, so `Z + W` is exactly the
    /// single-channel Z word.
    pub fn split_words(
        &self,
        index: u64,
        rho: f64,
        theta: f64,
        z: f64,
        z_slide: f64,
    ) -> Result<Words, NcError> {
        let whole = self.words(index, rho, theta, z)?;
        let slide = self.z_units(index, z_slide)?;
        Ok(Words {
            z: slide,
            w: Some(whole.z - slide),
            ..whole
        })
    }

    /// The Z word of height `z` alone (approach and retract), in units of its last digit.
    pub fn z_units(&self, index: u64, z: f64) -> Result<i64, NcError> {
        scaled(self.z_sign * z, self.decimals_xz).ok_or(NcError::Unwritable {
            index,
            what: "Z",
            value: z,
            at: None,
        })
    }
}

/// `c` modulo `turn` (> 0) in `[0, turn)`, as `rem_euclid`: below 2⁵² the quotient from a
/// floating-point product, off by at most one and corrected, instead of a 64-bit division
/// every block.
fn wrap(c: i64, turn: i64) -> i64 {
    if c.unsigned_abs() >= 1 << 52 {
        return c.rem_euclid(turn);
    }
    let q = (c as f64 * (1.0 / turn as f64)).floor() as i64;
    let r = c - q * turn;
    if r < 0 {
        r + turn
    } else if r >= turn {
        r - turn
    } else {
        r
    }
}

/// An NC program or CSV that cannot be written.
#[derive(Debug, Error)]
pub enum NcError {
    /// A coordinate is NaN, infinite or too large for the decimals asked. The message names
    /// the point, where it is, and the job's inputs that make that word.
    ///
    /// ```
    /// use spiralcam::nc::NcError;
    /// use spiralcam::job::OutputSpec;
    /// let e = OutputSpec::default().conventions().words(7, 2.0, 0.5, f64::NAN).unwrap_err();
    /// assert!(matches!(e, NcError::Unwritable { index: 7, what: "Z", .. }));
    /// assert!(e.to_string().starts_with(
    ///     "point 7 (radius 2 mm, angle 28.64789°): Z = NaN cannot be written: the surface"));
    /// ```
    #[error("{}", unwritable(*index, what, *value, *at))]
    Unwritable {
        /// Point index along the path.
        index: u64,
        /// The word.
        what: &'static str,
        /// The value.
        value: f64,
        /// Where: ρ mm and θ radians, when known.
        at: Option<(f64, f64)>,
    },
    /// A line is longer than the dialect's (or the job's) limit.
    ///
    /// ```
    /// let e = spiralcam::nc::NcError::LineTooLong { index: 3, chars: 140, limit: 128 };
    /// assert!(e.to_string().starts_with("point 3: a line of 140 characters"));
    /// ```
    #[error(
        "point {index}: a line of {chars} characters, longer than {limit} \
         (output.max_line_chars, or the dialect's limit): fewer decimals or a longer limit"
    )]
    LineTooLong {
        /// Point index along the path.
        index: u64,
        /// The line's length.
        chars: usize,
        /// The limit.
        limit: usize,
    },
    /// The output failed.
    ///
    /// ```
    /// let e = spiralcam::nc::NcError::from(std::io::Error::other("disk full"));
    /// assert_eq!(e.to_string(), "writing: disk full");
    /// ```
    #[error("writing: {0}")]
    Io(#[from] std::io::Error),
}

/// The message of [`NcError::Unwritable`]: the point, where, and what makes the word.
fn unwritable(index: u64, what: &str, value: f64, at: Option<(f64, f64)>) -> String {
    let cause = match what {
        "X" | "rho" => "the spiral's radius (part.diameter_mm, strategy.outer_radius_mm)",
        "C" | "theta" => "the spindle angle (strategy.start_angle_deg, the sampling)",
        "F" => {
            "the inverse-time feed rpm·360°/ΔC (machine.spindle_rpm, the sampling's angle step): \
             two points at the same angle, or a speed too high"
        }
        "W" => "the split between the slide and the servo (strategy.split)",
        _ => {
            "the surface or the nose compensation gives a height that is not finite or too large \
             for the decimals asked there: check the surface's parameters, tool.nose_radius_mm \
             and output.decimals_xz"
        }
    };
    let value = crate::field::short(value);
    match at {
        Some((rho, theta)) => format!(
            "point {index} (radius {} mm, angle {}°): {what} = {value} cannot be written: {cause}",
            crate::field::short(rho),
            crate::field::short(theta.to_degrees().rem_euclid(360.0)),
        ),
        None => format!("{what} = {value} cannot be written: {cause}"),
    }
}

/// What the header restates, besides the job itself.
#[derive(Debug, Clone)]
pub struct Header {
    /// Comment lines, plain text (made ASCII and parenthesis-free on writing).
    pub lines: Vec<String>,
    /// Spindle speed, rev/min.
    pub spindle_rpm: f64,
}

/// Streams the one-spiral program of a job without a `program` section: header, preamble,
/// approach, one block per point, retract, end.
pub struct NcWriter<W: Write> {
    out: W,
    blocks: Blocks,
    feed_mm_per_min: f64,
    plunge_feed: f64,
    clearance: f64,
    /// z of the last point.
    last_z: Option<f64>,
    bytes: u64,
}

impl<W: Write> NcWriter<W> {
    /// Starts a program: writes the header comments (wrapped to the line limit) and the
    /// preamble.
    pub fn new(mut out: W, spec: &OutputSpec, header: &Header) -> Result<Self, NcError> {
        let style = spec.style();
        let mut text = String::new();
        for l in &header.lines {
            for c in comment_lines(l, spec.max_line()) {
                text.push_str(&c);
                text.push('\n');
            }
        }
        for l in style.preamble {
            text.push_str(l);
            text.push('\n');
        }
        out.write_all(text.as_bytes())?;
        let mut writer = Self::resume(out, spec, header.spindle_rpm);
        writer.bytes = text.len() as u64;
        Ok(writer)
    }

    /// Goes on with a program whose header and first blocks another writer wrote (a slice of
    /// the path, [`crate::plan::PlanSlice`]): writes nothing until the blocks after the
    /// [context](NcWriter::context).
    pub fn resume(out: W, spec: &OutputSpec, spindle_rpm: f64) -> Self {
        Self {
            out,
            blocks: Blocks::new(spec, spindle_rpm),
            feed_mm_per_min: spec.feed_mm_per_min.unwrap_or(0.0),
            plunge_feed: spec.plunge_feed_mm_per_min,
            clearance: spec.clearance_mm,
            last_z: None,
            bytes: 0,
        }
    }

    /// Takes `p`, a point before the slice, as the writer of the whole program would, without
    /// writing it: the blocks after the last two such points carry the same F words. `z_slide`
    /// as [`Self::point_split`]'s.
    pub fn context(&mut self, p: &PathPoint, z_slide: Option<f64>) -> Result<(), NcError> {
        if self.blocks.started() {
            let w = self.blocks.words(p, z_slide, 0.0)?;
            self.blocks.block(p, w)
        } else {
            self.blocks.start(p.theta);
            Ok(())
        }
    }

    /// Writes the block that reaches `p` (the approach for the first point).
    pub fn point(&mut self, p: &PathPoint) -> Result<(), NcError> {
        let w = self.blocks.words(p, None, 0.0)?;
        self.block(p, w)
    }

    /// Writes the block that reaches `p` with its height split: Z the slide at `z_slide`, and
    /// the fast tool servo's word the rest (see [`Conventions::split_words`]).
    pub fn point_split(&mut self, p: &PathPoint, z_slide: f64) -> Result<(), NcError> {
        let w = self.blocks.words(p, Some(z_slide), 0.0)?;
        self.block(p, w)
    }

    fn block(&mut self, p: &PathPoint, w: Words) -> Result<(), NcError> {
        if self.blocks.started() {
            self.blocks.block(p, w)?;
        } else {
            self.approach(w, p)?;
            self.blocks.start(p.theta);
        }
        self.out.write_all(&self.blocks.line)?;
        self.bytes += self.blocks.line.len() as u64;
        self.last_z = Some(p.z);
        Ok(())
    }

    /// Rapid above the first point, rapid to its X and C, feed down at the plunge feed.
    fn approach(&mut self, w: Words, p: &PathPoint) -> Result<(), NcError> {
        let b = &mut self.blocks;
        b.line.clear();
        b.line.extend_from_slice(b"G0 ");
        b.push_z(p.z + self.clearance)?;
        b.line.extend_from_slice(b"\nG0 ");
        b.push_xc(w);
        b.line.extend_from_slice(b"\nG1 Z");
        push_scaled(&mut b.line, w.z, b.conv.decimals_xz);
        b.push_fts_word(w);
        b.push_feed(self.plunge_feed);
        b.line.push(b'\n');
        b.push_cutting_mode(self.feed_mm_per_min);
        Ok(())
    }

    /// Writes blocks another writer formatted ([`Self::resume`]d after this one's last block),
    /// the last of them reaching the height `last_z`.
    pub fn append(&mut self, blocks: &[u8], last_z: f64) -> Result<(), NcError> {
        self.out.write_all(blocks)?;
        self.bytes += blocks.len() as u64;
        self.last_z = Some(last_z);
        Ok(())
    }

    /// Bytes written so far.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    /// Writes the retract and the end; returns the program's size in bytes.
    pub fn finish(self) -> Result<u64, NcError> {
        self.finish_slice(true)
    }

    /// Writes the retract and the end when `ends` (the path ends in this writer's slice);
    /// returns the bytes written.
    pub fn finish_slice(mut self, ends: bool) -> Result<u64, NcError> {
        if !ends {
            self.out.flush()?;
            return Ok(self.bytes);
        }
        let b = &mut self.blocks;
        b.line.clear();
        if b.feed_mode().per_block() {
            b.line.extend_from_slice(b"G94\n");
        }
        if let Some(z) = self.last_z {
            b.line.extend_from_slice(b"G0 ");
            b.push_z(z + self.clearance)?;
            b.line.push(b'\n');
        }
        for l in b.style.end {
            b.line.extend_from_slice(l.as_bytes());
            b.line.push(b'\n');
        }
        self.out.write_all(&b.line)?;
        self.out.flush()?;
        Ok(self.bytes + b.line.len() as u64)
    }
}

/// A comment's text as plain ASCII without parentheses (RS-274 comments cannot nest).
pub fn ascii_comment(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '(' => out.push('['),
            ')' => out.push(']'),
            'µ' | 'μ' => out.push('u'),
            '°' => out.push_str(" deg"),
            'θ' => out.push_str("theta"),
            'ρ' => out.push_str("rho"),
            'λ' => out.push_str("lambda"),
            'φ' => out.push_str("phi"),
            'β' => out.push_str("beta"),
            'α' => out.push_str("alpha"),
            '→' => out.push_str("->"),
            '¹' => out.push_str("^1"),
            '²' => out.push_str("^2"),
            '³' => out.push_str("^3"),
            '⁴' => out.push_str("^4"),
            'Ø' => out.push_str("dia "),
            '−' | '–' | '—' => out.push('-'),
            '·' | '×' => out.push('*'),
            '≤' => out.push_str("<="),
            '≥' => out.push_str(">="),
            c if c.is_ascii() && !c.is_ascii_control() => out.push(c),
            _ => out.push('?'),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_words_add_up_to_the_single_channel_z_exactly() {
        let conv = OutputSpec::default().conventions();
        // Heights whose slide share rounds the other way from the whole (…5 at the 7th digit).
        for (z, slide) in [
            (0.1234565, 0.0000005),
            (-1.2345675, -1.2),
            (3.0, 2.9999995),
            (1e-7, -4e-7),
        ] {
            let whole = conv.words(0, 1.0, 0.0, z).unwrap();
            let split = conv.split_words(0, 1.0, 0.0, z, slide).unwrap();
            assert_eq!(split.z + split.w.unwrap(), whole.z, "{z} {slide}");
            assert_eq!(split.z, scaled(slide, 6).unwrap());
            assert_eq!((split.x, split.c), (whole.x, whole.c));
        }
    }

    #[test]
    fn every_dialect_writes_the_servo_word_after_the_others() {
        let header = Header {
            lines: vec![],
            spindle_rpm: 100.0,
        };
        let at = |theta: f64| PathPoint {
            rho: 1.0,
            theta,
            z: -0.0123456,
            ..Default::default()
        };
        for (dialect, block) in [
            (
                Dialect::Iso,
                "G1 X1.000000 Z-0.010000 C5.72958 V-0.002346 F",
            ),
            (Dialect::Moore, "C5.72958 X1.000000 Z-0.010000 V-0.002346"),
            (
                Dialect::Precitech,
                "G1 X-1.000000 Z-0.010000 C5.72958 V-0.002346",
            ),
        ] {
            let spec = OutputSpec {
                dialect,
                fts_word: Some("V".into()),
                ..Default::default()
            };
            let mut nc = Vec::new();
            let mut w = NcWriter::new(&mut nc, &spec, &header).unwrap();
            w.point_split(&at(0.0), -0.01).unwrap();
            w.point_split(&at(0.1), -0.01).unwrap();
            w.finish().unwrap();
            let text = String::from_utf8(nc).unwrap();
            assert!(
                text.lines().any(|l| l.starts_with(block)),
                "{dialect:?}:\n{text}"
            );
        }
    }

    #[test]
    fn the_fts_word_is_an_unused_axis_letter() {
        let spec = |w: &str| OutputSpec {
            fts_word: Some(w.into()),
            ..Default::default()
        };
        assert_eq!(spec("U").conventions().fts_word, b'U');
        // ISO's default is Y, a linear axis LinuxCNC's interpreter always reads; W elsewhere.
        assert_eq!(OutputSpec::default().conventions().fts_word, b'Y');
        let moore = OutputSpec {
            dialect: Dialect::Moore,
            ..Default::default()
        };
        assert_eq!(moore.conventions().fts_word, b'W');
        for bad in ["Z", "w", "WW", ""] {
            let e = spec(bad).validate().unwrap_err().to_string();
            assert_eq!(
                e,
                format!("fts_word = {bad:?}: must be one of W, U, V, A, B, Y")
            );
        }
    }

    #[test]
    fn the_fts_table_has_the_programs_c_x_and_w() {
        let spec = OutputSpec::default();
        let p = PathPoint {
            rho: 1.5,
            theta: 0.25,
            z: -0.0123456,
            ..Default::default()
        };
        let mut table = Vec::new();
        let mut t = FtsTableWriter::new(&mut table, spec.conventions()).unwrap();
        t.point(&p, -0.01).unwrap();
        t.finish().unwrap();
        assert_eq!(
            String::from_utf8(table).unwrap(),
            "c_deg,x_mm,w_mm\n14.32394,1.500000,-0.002346\n"
        );
        let header = Header {
            lines: vec![],
            spindle_rpm: 100.0,
        };
        let mut nc = Vec::new();
        let mut w = NcWriter::new(&mut nc, &spec, &header).unwrap();
        w.point_split(&p, -0.01).unwrap();
        w.finish().unwrap();
        let text = String::from_utf8(nc).unwrap();
        assert!(text.contains("G1 Z-0.010000 Y-0.002346 F"), "{text}");
        assert!(text.contains("G0 X1.500000 C14.32394"), "{text}");
    }

    #[test]
    fn comments_become_plain_ascii() {
        assert_eq!(
            ascii_comment("R 2.84 mm (−44.4 µm), 60°"),
            "R 2.84 mm [-44.4 um], 60 deg"
        );
    }

    #[test]
    fn wrap_is_rem_euclid() {
        // Every turn's size written (0 to 9 decimals), around every multiple of a turn up to
        // 10⁶ turns either way, at the fast path's limit and beyond.
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        for d in 0..=number::MAX_DECIMALS {
            let turn = 360 * number::pow10(d);
            for k in (-1_000_000i64..=1_000_000).step_by(997) {
                for off in [-2, -1, 0, 1, 2, turn / 2, turn - 1] {
                    let c = k * turn + off;
                    assert_eq!(wrap(c, turn), c.rem_euclid(turn), "{c} {turn}");
                }
            }
            for _ in 0..100_000 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let c = (x as i64) >> (x % 40);
                assert_eq!(wrap(c, turn), c.rem_euclid(turn), "{c} {turn}");
            }
            for c in [
                (1i64 << 52) - 1,
                1 << 52,
                -(1 << 52),
                i64::MAX,
                i64::MIN + 1,
            ] {
                assert_eq!(wrap(c, turn), c.rem_euclid(turn), "{c} {turn}");
            }
        }
    }

    #[test]
    fn c_wraps_after_rounding() {
        let conv = Conventions {
            x_sign: 1.0,
            z_sign: 1.0,
            c_sign: 1.0,
            wrap_c: true,
            decimals_xz: 6,
            decimals_c: 5,
            fts_word: b'W',
        };
        // 359.999996° rounds to 360.00000 and must wrap to 0.
        let w = conv
            .words(0, 1.0, 359.999_996f64.to_radians(), 0.0)
            .unwrap();
        assert_eq!(w.c, 0);
        let w = conv.words(0, 1.0, (-90.0f64).to_radians(), 0.0).unwrap();
        assert_eq!(w.c, 27_000_000);
    }

    #[test]
    fn options_are_checked() {
        let o = OutputSpec {
            x_sign: Some(2),
            ..Default::default()
        };
        assert_eq!(o.validate().unwrap_err().field, "x_sign");
        let o = OutputSpec {
            feed_mode: FeedMode::PerMinute,
            ..Default::default()
        };
        assert_eq!(o.validate().unwrap_err().field, "feed_mm_per_min");
        let o = OutputSpec {
            decimals_c: 12,
            ..Default::default()
        };
        assert_eq!(o.validate().unwrap_err().field, "decimals_c");
    }
}
