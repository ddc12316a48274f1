//! A block's words, evaluated: `G` and `M` codes (several per line, `G59.1`, `M26.1`), the axis
//! words `X Y Z A B C U V W`, the other letters RS-274 and the Fanuc-style controls use
//! (`F S T P L Q R I J K D H`), and parameter settings `#… = …`, which take effect after the
//! whole line is read (LinuxCNC: "parameter setting does not take effect until after all
//! parameter values on the same line have been found"). A letter given twice on one line
//! (other than G and M) is an error, as in LinuxCNC; `E`, `N` inside a line and any other letter
//! is an unknown word.

use super::error::Problem;
use super::expression::{Context, Evaluator};
use super::lexer::Cursor;
use super::variables::Key;

/// A `G` or `M` code with at most one decimal (`G1`, `G59.1`, `M26.1`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Code {
    /// `b'G'` or `b'M'`.
    pub letter: u8,
    /// Ten times the number.
    pub tenths: u16,
}

impl Code {
    /// `G` code `number` (in tenths, `G59.1` is 591).
    pub const fn g(tenths: u16) -> Self {
        Self {
            letter: b'G',
            tenths,
        }
    }

    /// `M` code `number` (in tenths).
    pub const fn m(tenths: u16) -> Self {
        Self {
            letter: b'M',
            tenths,
        }
    }

    /// Reads a code as written (`"G63"`, `"m26.1"`), for options naming codes.
    pub fn parse(s: &str) -> Option<Self> {
        let s = s.trim();
        let letter = s.bytes().next()?.to_ascii_uppercase();
        let v: f64 = s.get(1..)?.parse().ok()?;
        if letter != b'G' && letter != b'M' {
            return None;
        }
        Self::from_value(letter, v)
    }

    fn from_value(letter: u8, v: f64) -> Option<Self> {
        let t = (v * 10.0).round();
        ((0.0..=9999.0).contains(&t) && (v * 10.0 - t).abs() < 1e-6).then_some(Self {
            letter,
            tenths: t as u16,
        })
    }
}

impl std::fmt::Display for Code {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (whole, tenth) = (self.tenths / 10, self.tenths % 10);
        if tenth == 0 {
            write!(f, "{}{whole}", self.letter as char)
        } else {
            write!(f, "{}{whole}.{tenth}", self.letter as char)
        }
    }
}

/// The axis letters, in the order of [`super::modal::Position`].
pub const AXIS_LETTERS: [u8; 9] = *b"xyzabcuvw";

/// The other word letters, in the order of [`Block::other`].
pub const OTHER_LETTERS: [u8; 12] = *b"fstplqrijkdh";

/// The words of one line.
#[derive(Debug, Default, Clone)]
pub struct Block {
    /// G codes in the order written.
    pub g: Vec<Code>,
    /// M codes in the order written.
    pub m: Vec<Code>,
    /// Axis words, by [`AXIS_LETTERS`].
    pub axes: [Option<f64>; 9],
    /// Other words, by [`OTHER_LETTERS`].
    pub other: [Option<f64>; 12],
    /// Parameter settings, applied after the line is read.
    pub settings: Vec<(Key, f64)>,
}

impl Block {
    /// Empties the block for the next line (keeping its buffers).
    pub fn clear(&mut self) {
        self.g.clear();
        self.m.clear();
        self.axes = [None; 9];
        self.other = [None; 12];
        self.settings.clear();
    }

    /// The word `letter` (one of [`OTHER_LETTERS`]).
    pub fn word(&self, letter: u8) -> Option<f64> {
        OTHER_LETTERS
            .iter()
            .position(|&l| l == letter)
            .and_then(|i| self.other[i])
    }

    /// Takes the word `letter` out of the block (so that unused words can be found after).
    pub fn take(&mut self, letter: u8) -> Option<f64> {
        OTHER_LETTERS
            .iter()
            .position(|&l| l == letter)
            .and_then(|i| self.other[i].take())
    }

    /// Whether any axis word is given.
    pub fn has_axes(&self) -> bool {
        self.axes.iter().any(Option::is_some)
    }

    /// Whether the block has the G code `tenths`.
    pub fn has_g(&self, tenths: u16) -> bool {
        self.g.contains(&Code::g(tenths))
    }

    /// Reads the words from the cursor to the end of the line.
    pub fn parse(&mut self, c: &mut Cursor, eval: &mut Evaluator) -> Result<(), Problem> {
        while let Some(b) = c.peek() {
            if b == b'#' {
                let key = eval.key(c)?;
                if !c.eat(b'=') {
                    return Err(Problem::Syntax(format!(
                        "a variable alone is not a word: expected `{key} = value`, found `{}`",
                        c.rest()
                    )));
                }
                let v = eval.expression(c, Context::Full)?;
                self.settings.push((key, v));
                continue;
            }
            let start = c.i;
            c.i += 1;
            if !b.is_ascii_lowercase() {
                return Err(Problem::Syntax(format!(
                    "expected a word (a letter and a value), found `{}`",
                    c.since(start).to_string() + c.rest()
                )));
            }
            if !AXIS_LETTERS.contains(&b) && !OTHER_LETTERS.contains(&b) && b != b'g' && b != b'm' {
                return Err(unknown_word(c, start));
            }
            let v = eval.expression(c, Context::Word)?;
            self.word_value(b, v, || c.since(start).to_string())?;
        }
        Ok(())
    }

    fn word_value(&mut self, letter: u8, v: f64, text: impl Fn() -> String) -> Result<(), Problem> {
        let upper = letter.to_ascii_uppercase();
        if letter == b'g' || letter == b'm' {
            let code = Code::from_value(upper, v).ok_or_else(|| {
                Problem::Syntax(format!(
                    "`{}`: a {} code is a number from 0 to 999.9 with at most one decimal",
                    text(),
                    upper as char
                ))
            })?;
            if letter == b'g' {
                self.g.push(code);
            } else {
                self.m.push(code);
            }
            return Ok(());
        }
        let slot = match AXIS_LETTERS.iter().position(|&l| l == letter) {
            Some(i) => &mut self.axes[i],
            None => {
                let i = OTHER_LETTERS
                    .iter()
                    .position(|&l| l == letter)
                    .unwrap_or_default();
                &mut self.other[i]
            }
        };
        if slot.is_some() {
            return Err(Problem::Syntax(format!(
                "two {} words on one line",
                upper as char
            )));
        }
        *slot = Some(v);
        Ok(())
    }
}

fn unknown_word(c: &mut Cursor, start: usize) -> Problem {
    // Quote the letter and its value as written, up to the next letter.
    while c
        .peek()
        .is_some_and(|b| !b.is_ascii_lowercase() || c.i == start + 1)
    {
        c.i += 1;
    }
    Problem::Unknown(format!("the word {}", c.since(start).to_ascii_uppercase()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::reader::variables::Variables;

    fn parse(s: &str) -> Result<Block, Problem> {
        let vars = Variables::default();
        let mut b = Block::default();
        b.parse(&mut Cursor::new(s.as_bytes()), &mut Evaluator::new(&vars))?;
        Ok(b)
    }

    #[test]
    fn words_codes_and_settings_are_read() {
        let b = parse("g52g63g71g103g40g18g90").unwrap();
        let codes: Vec<String> = b.g.iter().map(ToString::to_string).collect();
        assert_eq!(codes, ["G52", "G63", "G71", "G103", "G40", "G18", "G90"]);
        let b = parse("c335.7358x0.498407z-0.001176f18829.085m26.1").unwrap();
        assert_eq!(b.axes[5], Some(335.7358));
        assert_eq!(b.axes[0], Some(0.498407));
        assert_eq!(b.axes[2], Some(-0.001176));
        assert_eq!(b.word(b'f'), Some(18829.085));
        assert_eq!(b.m, [Code::m(261)]);
        let b = parse("#1=2#<a>=[3*4]").unwrap();
        assert_eq!(b.settings.len(), 2);
        assert_eq!(b.settings[1], (Key::Name("a".into()), 12.0));
        assert_eq!(Code::parse("g59.1"), Some(Code::g(591)));
        assert_eq!(Code::parse("X1"), None);
        assert_eq!(Code::parse("G1.25"), None);
    }

    #[test]
    fn bad_words_are_refused() {
        assert_eq!(
            parse("g1x1e2.5f10").unwrap_err(),
            Problem::Unknown("the word E2.5".into())
        );
        assert!(matches!(parse("x1x2"), Err(Problem::Syntax(_))));
        assert!(matches!(parse("g1.25"), Err(Problem::Syntax(_))));
        assert!(matches!(parse("g-1"), Err(Problem::Syntax(_))));
        assert!(matches!(parse("#1"), Err(Problem::Syntax(_))));
        assert!(matches!(parse("x"), Err(Problem::Syntax(_))));
        assert!(matches!(parse("n10"), Err(Problem::Unknown(_))));
        assert!(matches!(parse("o100"), Err(Problem::Unknown(_))));
        assert!(matches!(parse("x1%"), Err(Problem::Syntax(_))));
    }
}
