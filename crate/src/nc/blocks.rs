//! The cutting blocks of a stretch of path, as every program writes them: one linear block a
//! point, the words in the dialect's order, the servo's word last, F from the spindle speed
//! under `G93` (every block, or only when it changes, as the dialect does). Shared by the
//! one-spiral program ([`super::NcWriter`]), the programs with passes ([`super::program`]) and
//! their child programs.

use super::number::{MAX_SCALED_LEN, push_fixed, push_scaled, put_scaled, scaled};
use super::{Axis, Conventions, NcError, Style, Words};
use crate::job::{FeedMode, OutputSpec};
use crate::path::PathPoint;

/// Room for the text of an F word: ` F`, a sign, 19 digits, the point, with room.
const F_TEXT: usize = 32;

/// Room for a block's prefix (`G1 ` or none).
const PREFIX: usize = 4;

/// Room for the words of a block: three axes and the servo's, each a space, a letter and a
/// number.
const WORDS_ROOM: usize = 4 * (2 + MAX_SCALED_LEN);

/// Room for a whole block: its prefix, words, F and newline.
const BLOCK_ROOM: usize = PREFIX + WORDS_ROOM + F_TEXT + 1;

/// Formats blocks into a line buffer.
#[derive(Debug, Clone)]
pub struct Blocks {
    /// The dialect.
    pub style: &'static Style,
    /// Signs, wrapping, decimals.
    pub conv: Conventions,
    feed_mode: FeedMode,
    decimals_f: u32,
    max_line: usize,
    rpm: f64,
    last_theta: Option<f64>,
    last_f: Option<i64>,
    /// The text of the F word `last_f` (` F…`, its first `f_len` bytes), copied while F
    /// stays the same.
    f_text: [u8; F_TEXT],
    f_len: usize,
    /// The dialect's block prefix, its first `prefix_len` bytes.
    prefix: [u8; PREFIX],
    prefix_len: usize,
    /// The line being formatted.
    pub line: Vec<u8>,
}

impl Blocks {
    /// Blocks of `spec`'s dialect at `rpm`.
    pub fn new(spec: &OutputSpec, rpm: f64) -> Self {
        let style = spec.style();
        let mut prefix = [0; PREFIX];
        let prefix_len = style.block_prefix.len();
        prefix[..prefix_len].copy_from_slice(style.block_prefix.as_bytes());
        Self {
            style,
            conv: spec.conventions(),
            feed_mode: spec.feed_mode,
            decimals_f: spec.decimals_f(),
            max_line: spec.max_line(),
            rpm,
            last_theta: None,
            last_f: None,
            f_text: [0; F_TEXT],
            f_len: 0,
            prefix,
            prefix_len,
            line: Vec::with_capacity(BLOCK_ROOM),
        }
    }

    /// The words of `p`, its height raised by `lift` (the stock a pass leaves), split with the
    /// slide at `z_slide` (then raised alike) when given.
    pub fn words(&self, p: &PathPoint, z_slide: Option<f64>, lift: f64) -> Result<Words, NcError> {
        match z_slide {
            None => self.conv.words(p.index, p.rho, p.theta, p.z + lift),
            Some(s) => self
                .conv
                .split_words(p.index, p.rho, p.theta, p.z + lift, s + lift),
        }
    }

    /// Starts a stretch whose first point, at angle `theta`, the approach reached: the next
    /// block writes F whatever the last one was.
    pub fn start(&mut self, theta: f64) {
        self.last_theta = Some(theta);
        self.last_f = None;
    }

    /// The next block writes F whatever the last one was (a new file).
    pub fn restart_feed(&mut self) {
        self.last_f = None;
    }

    /// The longest line allowed, characters.
    pub fn max_line(&self) -> usize {
        self.max_line
    }

    /// Whether a stretch has started.
    pub fn started(&self) -> bool {
        self.last_theta.is_some()
    }

    /// Formats the block that moves to `p` with words `w` into [`Blocks::line`] (cleared
    /// first): written by index into a window of fixed room, cut to its length once.
    pub fn block(&mut self, p: &PathPoint, w: Words) -> Result<(), NcError> {
        let feed = self.feed_word(p)?;
        let line = &mut self.line;
        line.clear();
        line.extend_from_slice(&[0; BLOCK_ROOM]);
        line[..PREFIX].copy_from_slice(&self.prefix);
        let mut i = put_words(&self.conv, self.style.words, line, self.prefix_len, w);
        if feed {
            // A copy of fixed size, cut to the text's: no library call a block.
            line[i..i + F_TEXT].copy_from_slice(&self.f_text);
            i += self.f_len;
        }
        line[i] = b'\n';
        line.truncate(i + 1);
        self.last_theta = Some(p.theta);
        self.fits(p.index)
    }

    /// Whether the block to `p` writes F, its text then in `f_text`: under `G93` F follows the
    /// C step from the last block, written where it changes or on every block as the dialect
    /// does.
    fn feed_word(&mut self, p: &PathPoint) -> Result<bool, NcError> {
        if !self.feed_mode.per_block() {
            return Ok(false);
        }
        let prev = self.last_theta.unwrap_or(p.theta);
        let dc = (p.theta - prev).abs().to_degrees();
        let f = self.feed_mode.block_f(self.rpm, dc);
        let units = scaled(f, self.decimals_f).ok_or(NcError::Unwritable {
            index: p.index,
            what: "F",
            value: f,
            at: Some((p.rho, p.theta)),
        })?;
        if self.last_f == Some(units) {
            return Ok(self.style.feed_every_block);
        }
        self.f_text[..2].copy_from_slice(b" F");
        self.f_len = put_scaled(&mut self.f_text, 2, units, self.decimals_f);
        self.last_f = Some(units);
        Ok(true)
    }

    /// Refuses a line longer than the dialect's or the job's limit.
    pub fn fits(&self, index: u64) -> Result<(), NcError> {
        let n = self.line.len().saturating_sub(1);
        if n > self.max_line {
            return Err(NcError::LineTooLong {
                index,
                chars: n,
                limit: self.max_line,
            });
        }
        Ok(())
    }

    /// The X and C words of `w` in the dialect's order.
    pub fn push_xc(&mut self, w: Words) {
        let line = &mut self.line;
        let start = line.len();
        line.extend_from_slice(&[0; WORDS_ROOM]);
        let mut i = start;
        for axis in self.style.words.into_iter().filter(|&a| a != Axis::Z) {
            if i > start {
                line[i] = b' ';
                i += 1;
            }
            i = put_word(&self.conv, line, i, axis, w);
        }
        line.truncate(i);
    }

    /// ` W…` when `w` is split.
    pub fn push_fts_word(&mut self, w: Words) {
        let line = &mut self.line;
        let start = line.len();
        line.extend_from_slice(&[0; 2 + MAX_SCALED_LEN]);
        let end = put_fts_word(&self.conv, line, start, w);
        line.truncate(end);
    }

    /// `Z` and the height `z` mm (signed by the conventions).
    pub fn push_z(&mut self, z: f64) -> Result<(), NcError> {
        let units = self.conv.z_units(u64::MAX, z)?;
        self.line.push(b'Z');
        push_scaled(&mut self.line, units, self.conv.decimals_xz);
        Ok(())
    }

    /// ` F` and a feed in mm/min.
    pub fn push_feed(&mut self, mm_per_min: f64) {
        self.line.extend_from_slice(b" F");
        push_fixed(&mut self.line, mm_per_min, 3);
    }

    /// The line that sets the cutting feed mode after an approach: `G93`, or the `F` of
    /// per-minute feed.
    pub fn push_cutting_mode(&mut self, feed_mm_per_min: f64) {
        match self.feed_mode {
            FeedMode::PerMinute => {
                self.line.push(b'F');
                push_fixed(&mut self.line, feed_mm_per_min, 3);
                self.line.push(b'\n');
            }
            _ => self.line.extend_from_slice(b"G93\n"),
        }
    }

    /// The feed mode.
    pub fn feed_mode(&self) -> FeedMode {
        self.feed_mode
    }
}

/// Every word of `w` in the order `axes`, the servo's last, at `text[at..]` (which has
/// [`WORDS_ROOM`] bytes); returns where the words end.
fn put_words(conv: &Conventions, axes: [Axis; 3], text: &mut [u8], at: usize, w: Words) -> usize {
    let mut i = at;
    for (k, axis) in axes.into_iter().enumerate() {
        if k > 0 {
            text[i] = b' ';
            i += 1;
        }
        i = put_word(conv, text, i, axis, w);
    }
    put_fts_word(conv, text, i, w)
}

/// ` W…` at `text[at..]` when `w` is split; returns where it ends.
#[inline(always)]
fn put_fts_word(conv: &Conventions, text: &mut [u8], at: usize, w: Words) -> usize {
    match w.w {
        Some(units) => {
            text[at] = b' ';
            text[at + 1] = conv.fts_word;
            put_scaled(text, at + 2, units, conv.decimals_xz)
        }
        None => at,
    }
}

/// The word of `axis` at `text[at..]`; returns where it ends.
#[inline(always)]
fn put_word(conv: &Conventions, text: &mut [u8], at: usize, axis: Axis, w: Words) -> usize {
    let (letter, units, d) = match axis {
        Axis::C => (b'C', w.c, conv.decimals_c),
        Axis::X => (b'X', w.x, conv.decimals_xz),
        Axis::Z => (b'Z', w.z, conv.decimals_xz),
    };
    text[at] = letter;
    put_scaled(text, at + 1, units, d)
}

/// `text` as comment lines `( … )` of at most `max` characters, broken between words (a word
/// longer than a line is cut), plain ASCII ([`super::ascii_comment`]).
pub fn comment_lines(text: &str, max: usize) -> Vec<String> {
    let text = super::ascii_comment(text);
    let room = max.saturating_sub(2).max(8);
    let mut out = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let mut word = word;
        loop {
            let sep = usize::from(!line.is_empty());
            if line.len() + sep + word.len() <= room {
                if sep == 1 {
                    line.push(' ');
                }
                line.push_str(word);
                break;
            }
            if !line.is_empty() {
                out.push(std::mem::take(&mut line));
                continue;
            }
            let (head, tail) = word.split_at(room.min(word.len()));
            out.push(head.to_string());
            word = tail;
            if word.is_empty() {
                break;
            }
        }
    }
    if !line.is_empty() || out.is_empty() {
        out.push(line);
    }
    out.into_iter().map(|l| format!("({l})")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::Dialect;

    /// The blocks of points at cumulative C steps `steps_deg`, as `dialect` writes them.
    fn blocks_at(dialect: Dialect, steps_deg: &[f64]) -> (Blocks, Vec<(f64, String)>) {
        let spec = OutputSpec {
            dialect,
            ..OutputSpec::default()
        };
        let mut b = Blocks::new(&spec, 1000.0);
        b.start(0.0);
        let mut theta = 0.0;
        let mut lines = Vec::new();
        for (i, step) in steps_deg.iter().enumerate() {
            let p = PathPoint {
                index: i as u64 + 1,
                rho: 1.0,
                theta: theta + step.to_radians(),
                z: 0.1,
                ..PathPoint::default()
            };
            let dc = (p.theta - theta).abs().to_degrees();
            theta = p.theta;
            let w = b.words(&p, None, 0.0).unwrap();
            b.block(&p, w).unwrap();
            lines.push((dc, String::from_utf8(b.line.clone()).unwrap()));
        }
        (b, lines)
    }

    #[test]
    fn every_block_carries_the_f_of_its_own_step() {
        // Equal steps (the kept text copied), then changes back and forth.
        let steps = [0.09, 0.09, 0.18, 0.09, 0.045, 0.045, 0.07, 0.09, 0.09];
        let (b, lines) = blocks_at(Dialect::Iso, &steps);
        for (dc, line) in &lines {
            let mut f = b" F".to_vec();
            assert!(push_fixed(&mut f, 1000.0 * 360.0 / dc, b.decimals_f));
            let f = String::from_utf8(f).unwrap();
            assert!(
                line.ends_with(&format!("{f}\n")),
                "{line:?} for a step of {dc}°"
            );
            assert_eq!(line.matches(" F").count(), 1, "{line:?}");
        }
        // A dialect that writes F only when it changes writes it at the changes alone.
        let (_, lines) = blocks_at(Dialect::Moore, &steps);
        let with_f: Vec<bool> = lines.iter().map(|(_, l)| l.contains(" F")).collect();
        let changed: Vec<bool> = (0..steps.len())
            .map(|i| i == 0 || steps[i] != steps[i - 1])
            .collect();
        assert_eq!(with_f, changed, "{lines:?}");
    }

    #[test]
    fn long_comments_wrap_between_words() {
        let text = "surface: composite of an asphere and lenslets ".repeat(10);
        let lines = comment_lines(&text, 60);
        assert!(lines.len() > 5);
        assert!(
            lines
                .iter()
                .all(|l| l.len() <= 60 && l.starts_with('(') && l.ends_with(')'))
        );
        let joined: Vec<&str> = lines.iter().map(|l| &l[1..l.len() - 1]).collect();
        assert_eq!(joined.join(" "), text.trim_end());
        // A word longer than a line is cut.
        let long = "x".repeat(130);
        let lines = comment_lines(&long, 50);
        assert!(lines.iter().all(|l| l.len() <= 50), "{lines:?}");
        assert_eq!(lines.iter().map(|l| l.len() - 2).sum::<usize>(), 130);
        assert_eq!(comment_lines("short", 50), ["(short)"]);
    }
}
