//! Lines and words, as RS-274/NGC (LinuxCNC's G-code reference, "Format of a line") and the
//! Fanuc-style controllers read them: spaces and tabs are ignored everywhere outside comments,
//! so `X9.0Z0.04`, `G1X1.5` and `G 1 X 1.5` are the same block; letters are case-insensitive
//! (the line is lowered once); `( … )` is a comment (a `(` inside one is an error, as in
//! LinuxCNC: comments do not nest) and `;` starts a comment to the end of the line; a line that
//! is only `%` marks the start or the end of the tape; `/` first marks a block-delete line.
//!
//! [`normalize`] turns a raw line into this form, keeping where its comments were;
//! [`Cursor`] walks the result. [`head`] classifies a normalized line without evaluating
//! anything, which is what the control flow needs when it passes over lines looking for an
//! `END`, an `N` label or an `o` word.

use std::ops::Range;

/// A raw line normalized: no spaces, lower case, comments cut out.
#[derive(Debug, Default)]
pub struct Normalized {
    /// The text outside comments.
    pub text: Vec<u8>,
    /// Where the comments' texts are in the raw line (without their delimiters).
    pub comments: Vec<Range<usize>>,
    /// The line starts with `/` (block delete).
    pub block_delete: bool,
}

/// What is wrong with a raw line.
#[derive(Debug, Clone, PartialEq)]
pub enum LexError {
    /// A `(` without its `)`.
    UnclosedComment,
    /// A `(` inside a comment.
    NestedComment,
    /// A byte that no word uses.
    BadByte(u8),
}

impl std::fmt::Display for LexError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LexError::UnclosedComment => write!(f, "a comment `(` is not closed on its line"),
            LexError::NestedComment => write!(f, "a `(` inside a comment (comments do not nest)"),
            LexError::BadByte(b) if b.is_ascii_graphic() => {
                write!(f, "unexpected character '{}'", *b as char)
            }
            LexError::BadByte(b) => write!(f, "unexpected byte 0x{b:02x}"),
        }
    }
}

/// Bytes copied as they are (letters lowered): letters, digits and `. + - * [ ] = , #`.
const PLAIN: [bool; 256] = {
    let mut t = [false; 256];
    let mut b = 0;
    while b < 256 {
        let c = b as u8;
        t[b] = c.is_ascii_alphanumeric()
            || matches!(
                c,
                b'.' | b'+' | b'-' | b'*' | b'[' | b']' | b'=' | b',' | b'#'
            );
        b += 1;
    }
    t
};

/// Normalizes `raw` into `out` (cleared first).
pub fn normalize(raw: &[u8], out: &mut Normalized) -> Result<(), LexError> {
    out.text.clear();
    out.comments.clear();
    out.block_delete = false;
    let mut i = 0;
    let mut in_name = false;
    while i < raw.len() {
        let b = raw[i];
        if PLAIN[b as usize] && !in_name {
            out.text
                .push(b | if b.is_ascii_uppercase() { 0x20 } else { 0 });
            i += 1;
            continue;
        }
        match b {
            b' ' | b'\t' | b'\r' | 0x0c => {}
            b'(' if !in_name => {
                let start = i + 1;
                let len = raw[start..].iter().position(|&c| c == b')' || c == b'(');
                match len.map(|l| raw[start + l]) {
                    Some(b')') => {
                        let end = start + len.unwrap_or(0);
                        out.comments.push(start..end);
                        i = end;
                    }
                    Some(_) => return Err(LexError::NestedComment),
                    None => return Err(LexError::UnclosedComment),
                }
            }
            b';' if !in_name => {
                out.comments.push(i + 1..raw.len());
                break;
            }
            b'/' if out.text.is_empty() && !out.block_delete => out.block_delete = true,
            _ if in_name => {
                if b == b'>' {
                    in_name = false;
                }
                if !b.is_ascii() || b.is_ascii_control() {
                    return Err(LexError::BadByte(b));
                }
                out.text.push(b.to_ascii_lowercase());
            }
            b'a'..=b'z' | b'0'..=b'9' => out.text.push(b),
            b'A'..=b'Z' => out.text.push(b.to_ascii_lowercase()),
            b'.' | b'+' | b'-' | b'*' | b'/' | b'[' | b']' | b'=' | b',' | b'%' | b'#' => {
                out.text.push(b)
            }
            b'<' => {
                // `#<name>`: a named parameter (or `o<name>`); any character but `>` in it.
                in_name = matches!(out.text.last(), Some(b'#' | b'o'));
                out.text.push(b);
            }
            _ => return Err(LexError::BadByte(b)),
        }
        i += 1;
    }
    Ok(())
}

/// A position in a normalized line.
#[derive(Debug, Clone, Copy)]
pub struct Cursor<'t> {
    /// The normalized text.
    pub s: &'t [u8],
    /// The next byte.
    pub i: usize,
}

impl<'t> Cursor<'t> {
    /// A cursor at the start of `s`.
    pub fn new(s: &'t [u8]) -> Self {
        Self { s, i: 0 }
    }

    /// The next byte.
    pub fn peek(&self) -> Option<u8> {
        self.s.get(self.i).copied()
    }

    /// The byte after the next.
    pub fn peek2(&self) -> Option<u8> {
        self.s.get(self.i + 1).copied()
    }

    /// Whether the line is used up.
    pub fn done(&self) -> bool {
        self.i >= self.s.len()
    }

    /// Takes `b` if it is next.
    pub fn eat(&mut self, b: u8) -> bool {
        if self.peek() == Some(b) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    /// Takes `word` if the text continues with it.
    pub fn eat_keyword(&mut self, word: &[u8]) -> bool {
        if self.s[self.i..].starts_with(word) {
            self.i += word.len();
            true
        } else {
            false
        }
    }

    /// Whether the text continues with `word`.
    pub fn at_keyword(&self, word: &[u8]) -> bool {
        self.s[self.i..].starts_with(word)
    }

    /// An unsigned decimal number (`12`, `1.5`, `.5`, `3.`), if one is next, correctly
    /// rounded: up to 15 significant digits and 22 decimals exactly (an integer below 2⁵³
    /// divided by an exact power of ten, one rounding: Clinger's fast path), longer ones by
    /// the standard library's parser.
    pub fn number(&mut self) -> Option<f64> {
        const POW10: [f64; 23] = [
            1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
            1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
        ];
        let start = self.i;
        let mut mantissa: u64 = 0;
        let mut digits = 0usize;
        let mut decimals = 0usize;
        let mut point = false;
        while let Some(b) = self.peek() {
            match b {
                b'0'..=b'9' => {
                    if mantissa < 1 << 60 {
                        mantissa = mantissa * 10 + u64::from(b - b'0');
                    }
                    if mantissa > 0 {
                        digits += 1;
                    }
                    if point {
                        decimals += 1;
                    }
                }
                b'.' if !point => point = true,
                _ => break,
            }
            self.i += 1;
        }
        let text = &self.s[start..self.i];
        if text == b"." || text.is_empty() {
            self.i = start;
            return None;
        }
        if digits <= 15 && decimals < POW10.len() {
            return Some(mantissa as f64 / POW10[decimals]);
        }
        // Only ASCII digits and one point: always valid for f64's parser.
        std::str::from_utf8(text).ok().and_then(|t| t.parse().ok())
    }

    /// An unsigned integer of at most 18 digits, if one is next.
    pub fn integer(&mut self) -> Option<u64> {
        let start = self.i;
        let mut v: u64 = 0;
        while let Some(b @ b'0'..=b'9') = self.peek() {
            if self.i - start >= 18 {
                self.i = start;
                return None;
            }
            v = v * 10 + u64::from(b - b'0');
            self.i += 1;
        }
        (self.i > start).then_some(v)
    }

    /// The text from `from` to the cursor, for messages.
    pub fn since(&self, from: usize) -> &'t str {
        std::str::from_utf8(&self.s[from.min(self.i)..self.i]).unwrap_or("?")
    }

    /// The rest of the line, for messages.
    pub fn rest(&self) -> &'t str {
        std::str::from_utf8(&self.s[self.i.min(self.s.len())..]).unwrap_or("?")
    }
}

/// The label of an `o` word: `o100` or `o<name>`.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Label {
    /// `o100`.
    Number(u64),
    /// `o<name>`, lower case, without the brackets.
    Name(Box<str>),
}

impl std::fmt::Display for Label {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Label::Number(n) => write!(f, "o{n}"),
            Label::Name(s) => write!(f, "o<{s}>"),
        }
    }
}

/// The keyword after an `o` label (LinuxCNC's O-codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OKeyword {
    /// `sub`
    Sub,
    /// `endsub`
    EndSub,
    /// `call`
    Call,
    /// `return`
    Return,
    /// `do`
    Do,
    /// `while`
    While,
    /// `endwhile`
    EndWhile,
    /// `repeat`
    Repeat,
    /// `endrepeat`
    EndRepeat,
    /// `if`
    If,
    /// `elseif`
    ElseIf,
    /// `else`
    Else,
    /// `endif`
    EndIf,
    /// `break`
    Break,
    /// `continue`
    Continue,
}

/// Longest first, so that `endwhile` is not read as `end…`.
const O_KEYWORDS: [(&[u8], OKeyword); 15] = [
    (b"endrepeat", OKeyword::EndRepeat),
    (b"endwhile", OKeyword::EndWhile),
    (b"continue", OKeyword::Continue),
    (b"endsub", OKeyword::EndSub),
    (b"elseif", OKeyword::ElseIf),
    (b"repeat", OKeyword::Repeat),
    (b"return", OKeyword::Return),
    (b"endif", OKeyword::EndIf),
    (b"while", OKeyword::While),
    (b"break", OKeyword::Break),
    (b"else", OKeyword::Else),
    (b"call", OKeyword::Call),
    (b"sub", OKeyword::Sub),
    (b"do", OKeyword::Do),
    (b"if", OKeyword::If),
];

/// What a normalized line is, read without evaluating anything.
#[derive(Debug, Clone, PartialEq)]
pub enum Head {
    /// Nothing but comments (or an empty line).
    Empty,
    /// A `%` line.
    Percent,
    /// `O1000` alone: a Fanuc-style program number.
    ProgramNumber(u64),
    /// `o… keyword …`; the rest starts at `rest`.
    OWord {
        /// The label.
        label: Label,
        /// The keyword.
        keyword: OKeyword,
        /// Where the text after the keyword starts.
        rest: usize,
    },
    /// `WHILE[…]DO n` (Fanuc custom macro); the condition starts at `cond`.
    While {
        /// The loop's identification number.
        id: u64,
        /// Where the condition's `[` is.
        cond: usize,
    },
    /// `DO n` alone: an endless loop up to `END n`.
    Do(u64),
    /// `END n`.
    End(u64),
    /// `IF[…]…`; the condition's `[` is at `cond`.
    If {
        /// Where the condition's `[` is.
        cond: usize,
    },
    /// `GOTO …`; the target expression starts at `target`.
    Goto {
        /// Where the target starts.
        target: usize,
    },
    /// Words and parameter settings, starting at `words`.
    Words {
        /// Where the first word is.
        words: usize,
    },
}

/// A classified line: its `N` label and what follows.
#[derive(Debug, Clone, PartialEq)]
pub struct Classified {
    /// The `N` label, if any.
    pub n: Option<u64>,
    /// The statement.
    pub head: Head,
}

/// Classifies a normalized line. `Err` carries what is malformed in the statement's head.
pub fn head(text: &[u8]) -> Result<Classified, String> {
    if text == b"%" {
        return Ok(Classified {
            n: None,
            head: Head::Percent,
        });
    }
    let mut c = Cursor::new(text);
    let mut n = None;
    if c.peek() == Some(b'n') && c.peek2().is_some_and(|b| b.is_ascii_digit()) {
        c.i += 1;
        n = Some(c.integer().ok_or("an N label has more than 18 digits")?);
        // LinuxCNC allows a decimal N; the fraction is not a label.
        if c.eat(b'.') {
            while c.peek().is_some_and(|b| b.is_ascii_digit()) {
                c.i += 1;
            }
        }
    }
    let head = if c.done() {
        Head::Empty
    } else if c.peek() == Some(b'o') {
        o_word(&mut c)?
    } else if c.eat_keyword(b"while") {
        let cond = c.i;
        skip_brackets(&mut c)?;
        if !c.eat_keyword(b"do") {
            return Err(format!(
                "WHILE[…] must be followed by DO n, found `{}`",
                c.rest()
            ));
        }
        Head::While {
            id: loop_id(&mut c, "DO")?,
            cond,
        }
    } else if c.peek() == Some(b'd') && c.peek2() == Some(b'o') {
        c.i += 2;
        Head::Do(loop_id(&mut c, "DO")?)
    } else if c.at_keyword(b"end") && c.s.get(c.i + 3).is_some_and(u8::is_ascii_digit) {
        c.i += 3;
        Head::End(loop_id(&mut c, "END")?)
    } else if c.at_keyword(b"if[") {
        Head::If { cond: c.i + 2 }
    } else if c.eat_keyword(b"goto") {
        Head::Goto { target: c.i }
    } else {
        Head::Words { words: c.i }
    };
    Ok(Classified { n, head })
}

fn loop_id(c: &mut Cursor, what: &str) -> Result<u64, String> {
    let id = c
        .integer()
        .ok_or_else(|| format!("{what} needs a loop number, found `{}`", c.rest()))?;
    if !c.done() {
        return Err(format!("unexpected `{}` after {what} {id}", c.rest()));
    }
    Ok(id)
}

fn o_word(c: &mut Cursor) -> Result<Head, String> {
    c.i += 1;
    let label = if c.eat(b'<') {
        let start = c.i;
        let len = c.s[start..]
            .iter()
            .position(|&b| b == b'>')
            .ok_or("an o<name> has no closing `>`")?;
        c.i = start + len + 1;
        let name = std::str::from_utf8(&c.s[start..start + len]).map_err(|_| "bad o<name>")?;
        if name.is_empty() {
            return Err("an o<> label has an empty name".into());
        }
        Label::Name(name.into())
    } else {
        Label::Number(
            c.integer()
                .ok_or_else(|| format!("an o word needs a number or <name>: `o{}`", c.rest()))?,
        )
    };
    if c.done() {
        return match label {
            Label::Number(n) => Ok(Head::ProgramNumber(n)),
            Label::Name(_) => Err(format!("{label} without a keyword (sub, call, while, …)")),
        };
    }
    for (word, keyword) in O_KEYWORDS {
        if c.eat_keyword(word) {
            return Ok(Head::OWord {
                label,
                keyword,
                rest: c.i,
            });
        }
    }
    Err(format!("unknown keyword after {label}: `{}`", c.rest()))
}

/// Moves the cursor past a bracketed group `[…]` (nesting counted).
pub fn skip_brackets(c: &mut Cursor) -> Result<(), String> {
    if !c.eat(b'[') {
        return Err(format!("expected `[`, found `{}`", c.rest()));
    }
    let mut depth = 1usize;
    while let Some(b) = c.peek() {
        c.i += 1;
        match b {
            b'[' => depth += 1,
            b']' => {
                depth -= 1;
                if depth == 0 {
                    return Ok(());
                }
            }
            _ => {}
        }
    }
    Err("a `[` is not closed on its line".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn norm(s: &str) -> (String, Vec<String>, bool) {
        let mut n = Normalized::default();
        normalize(s.as_bytes(), &mut n).unwrap();
        let comments = n
            .comments
            .iter()
            .map(|r| s[r.clone()].to_string())
            .collect();
        (String::from_utf8(n.text).unwrap(), comments, n.block_delete)
    }

    #[test]
    fn spaces_case_and_comments_are_normalized() {
        assert_eq!(norm("G1 X9.0Z0.04").0, "g1x9.0z0.04");
        assert_eq!(norm("g 1 x 1 . 5").0, "g1x1.5");
        assert_eq!(
            norm("N10 G1 (feed) X1 ; rest (x"),
            (
                "n10g1x1".into(),
                vec!["feed".into(), " rest (x".into()],
                false
            )
        );
        assert_eq!(norm("/G1 X#<My Var>").0, "g1x#<myvar>");
        assert!(norm("/G1 X1").2);
        assert_eq!(norm("#1 = [#2 / 3]").0, "#1=[#2/3]");
    }

    #[test]
    fn malformed_lines_are_refused() {
        let mut n = Normalized::default();
        assert_eq!(
            normalize(b"G1 (open", &mut n),
            Err(LexError::UnclosedComment)
        );
        assert_eq!(
            normalize(b"G1 (a (b) c)", &mut n),
            Err(LexError::NestedComment)
        );
        assert_eq!(normalize(b"G1 X1 $", &mut n), Err(LexError::BadByte(b'$')));
        assert_eq!(
            normalize("X1 µ".as_bytes(), &mut n),
            Err(LexError::BadByte(0xc2))
        );
    }

    fn h(s: &str) -> Classified {
        let (t, _, _) = norm(s);
        head(t.as_bytes()).unwrap()
    }

    #[test]
    fn heads_are_classified() {
        assert_eq!(h("%").head, Head::Percent);
        assert_eq!(h("(only)").head, Head::Empty);
        assert_eq!(h("O1000").head, Head::ProgramNumber(1000));
        assert_eq!(
            h("N20 WHILE [#5 LT #100] DO 2"),
            Classified {
                n: Some(20),
                head: Head::While { id: 2, cond: 8 }
            }
        );
        assert_eq!(h("END 2").head, Head::End(2));
        assert_eq!(h("DO1").head, Head::Do(1));
        assert_eq!(h("IF [#1 GT 2] GOTO 10").head, Head::If { cond: 2 });
        assert_eq!(h("GOTO10").head, Head::Goto { target: 4 });
        assert_eq!(
            h("o100 endwhile").head,
            Head::OWord {
                label: Label::Number(100),
                keyword: OKeyword::EndWhile,
                rest: 12
            }
        );
        assert_eq!(
            h("o<Pass> call [1]").head,
            Head::OWord {
                label: Label::Name("pass".into()),
                keyword: OKeyword::Call,
                rest: 11
            }
        );
        assert_eq!(h("N5 G1 X1").head, Head::Words { words: 2 });
        // D and I words are not DO and IF.
        assert_eq!(h("D1").head, Head::Words { words: 0 });
        assert_eq!(h("I1 K2").head, Head::Words { words: 0 });
    }

    #[test]
    fn malformed_heads_are_refused() {
        for bad in [
            "WHILE [#1 LT 2]",
            "WHILE [#1 LT 2 DO 1",
            "o100 fly",
            "o<>call",
            "END 1 X",
        ] {
            let (t, _, _) = norm(bad);
            assert!(head(t.as_bytes()).is_err(), "{bad}");
        }
    }
}
