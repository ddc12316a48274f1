//! A reader for the clear-text encoding of STEP exchange files, ISO 10303-21 ("Part 21"):
//! `ISO-10303-21;`, a `HEADER;` section, one or more `DATA;` sections of entity instances
//! `#id = NAME(parameters);` (or complex instances `#id = (NAME(…) NAME(…) …);`), and
//! `END-ISO-10303-21;`. Parameters are integers, reals (`1.`, `-2.5E-3`), strings (`'it''s'`),
//! entity references (`#12`), enumerations (`.T.`, `.MILLI.`), binaries (`"0F"`), lists
//! (`(…)`), typed values (`LENGTH_MEASURE(25.4)`), unset `$` and derived `*`; comments `/* … */`
//! are skipped. It reads the syntax only, for any schema; the meaning of the entities a surface
//! needs is read by the caller. Errors name the line and, inside the data, the instance.

use std::collections::HashMap;
use std::fmt;

/// Nesting depth of lists and typed values accepted (files nest two or three deep).
const MAX_DEPTH: usize = 64;

/// A parameter of an entity instance.
#[derive(Debug, Clone, PartialEq)]
pub enum Param {
    /// An integer.
    Integer(i64),
    /// A real number.
    Real(f64),
    /// A string, without its quotes (`''` read as `'`; other escapes kept as written).
    Str(String),
    /// A reference to the instance `#id`.
    Ref(u64),
    /// An enumeration value without its dots, e.g. `MILLI`.
    Enum(String),
    /// A binary value, as written.
    Binary(String),
    /// A list.
    List(Vec<Param>),
    /// A typed value, e.g. `LENGTH_MEASURE(25.4)`.
    Typed(String, Box<Param>),
    /// `$`: no value.
    Unset,
    /// `*`: derived.
    Derived,
}

impl Param {
    /// The number, integer or real.
    pub fn number(&self) -> Option<f64> {
        match self {
            Param::Integer(i) => Some(*i as f64),
            Param::Real(r) => Some(*r),
            Param::Typed(_, inner) => inner.number(),
            _ => None,
        }
    }

    /// A non-negative integer (a real with an integral value is accepted).
    pub fn count(&self) -> Option<usize> {
        match self {
            Param::Integer(i) => usize::try_from(*i).ok(),
            Param::Real(r) if r.fract() == 0.0 && *r >= 0.0 && *r < 1e15 => Some(*r as usize),
            _ => None,
        }
    }

    /// The list's items.
    pub fn list(&self) -> Option<&[Param]> {
        match self {
            Param::List(items) => Some(items),
            _ => None,
        }
    }

    /// The referenced instance id.
    pub fn reference(&self) -> Option<u64> {
        match self {
            Param::Ref(id) => Some(*id),
            _ => None,
        }
    }

    /// The enumeration value.
    pub fn enumeration(&self) -> Option<&str> {
        match self {
            Param::Enum(e) => Some(e),
            _ => None,
        }
    }

    /// The string.
    pub fn string(&self) -> Option<&str> {
        match self {
            Param::Str(s) => Some(s),
            _ => None,
        }
    }
}

/// One record `NAME(parameters)`: a simple instance, or one part of a complex one.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Entity name, upper case.
    pub name: String,
    /// Its parameters.
    pub params: Vec<Param>,
}

/// An entity instance of the data section.
#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    /// The id n of `#n`.
    pub id: u64,
    /// Line where it starts.
    pub line: usize,
    /// One record for a simple instance, its parts for a complex one.
    pub records: Vec<Record>,
}

impl Instance {
    /// The record named `name`, if the instance has one.
    pub fn record(&self, name: &str) -> Option<&Record> {
        self.records.iter().find(|r| r.name == name)
    }

    /// The entity name(s), `A` or `(A B C)`, for messages.
    pub fn names(&self) -> String {
        match self.records.as_slice() {
            [one] => one.name.clone(),
            many => {
                let names: Vec<&str> = many.iter().map(|r| r.name.as_str()).collect();
                format!("({})", names.join(" "))
            }
        }
    }
}

/// A parsed exchange file: the data instances in file order.
#[derive(Debug, Clone, Default)]
pub struct Exchange {
    /// The instances of all data sections, in file order.
    pub instances: Vec<Instance>,
    by_id: HashMap<u64, usize>,
}

impl Exchange {
    /// Parses the text of a Part 21 file.
    pub fn parse(text: &str) -> Result<Self, ParseError> {
        Parser::new(text)?.file()
    }

    /// The instance `#id`.
    pub fn get(&self, id: u64) -> Option<&Instance> {
        self.by_id.get(&id).map(|&k| &self.instances[k])
    }
}

/// A file that is not valid Part 21.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    /// Line, from 1.
    pub line: usize,
    /// What is wrong, with the instance when inside one.
    pub message: String,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Keyword(String),
    Id(u64),
    Param(Param),
    Eq,
    Open,
    Close,
    Comma,
    Semi,
    End,
}

impl fmt::Display for Tok {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Tok::Keyword(k) => write!(f, "{k}"),
            Tok::Id(id) => write!(f, "#{id}"),
            Tok::Param(p) => write!(f, "{p:?}"),
            Tok::Eq => write!(f, "'='"),
            Tok::Open => write!(f, "'('"),
            Tok::Close => write!(f, "')'"),
            Tok::Comma => write!(f, "','"),
            Tok::Semi => write!(f, "';'"),
            Tok::End => write!(f, "the end of the file"),
        }
    }
}

struct Lexer<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl Lexer<'_> {
    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.pos).copied()
    }

    fn bump(&mut self) -> Option<u8> {
        let c = self.peek()?;
        self.pos += 1;
        if c == b'\n' {
            self.line += 1;
        }
        Some(c)
    }

    fn error(&self, message: impl Into<String>) -> ParseError {
        ParseError {
            line: self.line,
            message: message.into(),
        }
    }

    /// The next token and the line it starts on.
    fn token(&mut self) -> Result<(Tok, usize), ParseError> {
        self.skip_blanks()?;
        let line = self.line;
        let Some(c) = self.peek() else {
            return Ok((Tok::End, line));
        };
        Ok((self.token_at(c)?, line))
    }

    /// Skips white space and comments.
    fn skip_blanks(&mut self) -> Result<(), ParseError> {
        loop {
            match self.peek() {
                Some(c) if c.is_ascii_whitespace() => {
                    self.bump();
                }
                Some(b'/') if self.bytes.get(self.pos + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.pos += 2;
                    loop {
                        match self.bump() {
                            Some(b'*') if self.peek() == Some(b'/') => {
                                self.bump();
                                break;
                            }
                            Some(_) => {}
                            None => {
                                return Err(ParseError {
                                    line: start,
                                    message: "a comment /* is never closed".into(),
                                });
                            }
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    fn token_at(&mut self, c: u8) -> Result<Tok, ParseError> {
        let single = match c {
            b'=' => Some(Tok::Eq),
            b'(' => Some(Tok::Open),
            b')' => Some(Tok::Close),
            b',' => Some(Tok::Comma),
            b';' => Some(Tok::Semi),
            b'$' => Some(Tok::Param(Param::Unset)),
            b'*' => Some(Tok::Param(Param::Derived)),
            _ => None,
        };
        if let Some(t) = single {
            self.bump();
            return Ok(t);
        }
        let next_alpha = self
            .bytes
            .get(self.pos + 1)
            .is_some_and(|c| c.is_ascii_alphabetic());
        Ok(match c {
            b'#' => {
                self.bump();
                let digits = self.take(|c| c.is_ascii_digit());
                let id = digits
                    .parse()
                    .map_err(|_| self.error(format!("'#{digits}' is not an instance name")))?;
                Tok::Id(id)
            }
            b'\'' => Tok::Param(Param::Str(self.string()?)),
            b'"' => {
                self.bump();
                let body = self.take(|c| c != b'"');
                self.expect_byte(b'"', "a binary \"…\" is never closed")?;
                Tok::Param(Param::Binary(body))
            }
            b'.' if next_alpha => {
                self.bump();
                let name = self.take(|c| c.is_ascii_alphanumeric() || c == b'_');
                self.expect_byte(b'.', &format!("the enumeration .{name} has no closing '.'"))?;
                Tok::Param(Param::Enum(name.to_ascii_uppercase()))
            }
            c if c.is_ascii_digit() || matches!(c, b'+' | b'-' | b'.') => self.number()?,
            c if c.is_ascii_alphabetic() || matches!(c, b'!' | b'_') => {
                let word =
                    self.take(|c| c.is_ascii_alphanumeric() || matches!(c, b'_' | b'-' | b'!'));
                Tok::Keyword(word.to_ascii_uppercase())
            }
            other => {
                let shown = String::from_utf8_lossy(&self.bytes[self.pos..])
                    .chars()
                    .next()
                    .unwrap_or(other as char);
                return Err(self.error(format!("unexpected character '{shown}'")));
            }
        })
    }

    fn take(&mut self, keep: impl Fn(u8) -> bool) -> String {
        let start = self.pos;
        while self.peek().is_some_and(&keep) {
            self.bump();
        }
        String::from_utf8_lossy(&self.bytes[start..self.pos]).into_owned()
    }

    fn expect_byte(&mut self, want: u8, message: &str) -> Result<(), ParseError> {
        if self.peek() == Some(want) {
            self.bump();
            Ok(())
        } else {
            Err(self.error(message))
        }
    }

    /// A quoted string; `''` stands for one quote.
    fn string(&mut self) -> Result<String, ParseError> {
        let start = self.line;
        self.bump();
        let mut out = Vec::new();
        loop {
            match self.bump() {
                Some(b'\'') if self.peek() == Some(b'\'') => {
                    self.bump();
                    out.push(b'\'');
                }
                Some(b'\'') => return Ok(String::from_utf8_lossy(&out).into_owned()),
                Some(c) => out.push(c),
                None => {
                    return Err(ParseError {
                        line: start,
                        message: "a string ' is never closed".into(),
                    });
                }
            }
        }
    }

    /// `[+-] digits [. digits] [E [+-] digits]`: an integer without the point, else a real.
    fn number(&mut self) -> Result<Tok, ParseError> {
        let start = self.pos;
        if matches!(self.peek(), Some(b'+' | b'-')) {
            self.bump();
        }
        self.take(|c| c.is_ascii_digit());
        let real = self.peek() == Some(b'.');
        if real {
            self.bump();
            self.take(|c| c.is_ascii_digit());
            if matches!(self.peek(), Some(b'E' | b'e')) {
                self.bump();
                if matches!(self.peek(), Some(b'+' | b'-')) {
                    self.bump();
                }
                self.take(|c| c.is_ascii_digit());
            }
        }
        let text = String::from_utf8_lossy(&self.bytes[start..self.pos]).into_owned();
        let bad = || self.error(format!("'{text}' is not a number"));
        if !text.bytes().any(|c| c.is_ascii_digit()) {
            return Err(bad());
        }
        if !real {
            return Ok(Tok::Param(Param::Integer(text.parse().map_err(|_| bad())?)));
        }
        // Rust does not read "1." or "1.E-3": put a 0 after a bare point.
        let mut fixed = text.replacen(".E", ".0E", 1).replacen(".e", ".0e", 1);
        if fixed.ends_with('.') {
            fixed.push('0');
        }
        match fixed.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(Tok::Param(Param::Real(value))),
            _ => Err(bad()),
        }
    }
}

struct Parser<'a> {
    lexer: Lexer<'a>,
    /// The next token and its line.
    ahead: (Tok, usize),
    /// The instance being read, for messages: `#12 = NAME`.
    context: Option<String>,
}

impl<'a> Parser<'a> {
    fn new(text: &'a str) -> Result<Self, ParseError> {
        let mut lexer = Lexer {
            bytes: text.as_bytes(),
            pos: 0,
            line: 1,
        };
        let ahead = lexer.token()?;
        Ok(Self {
            lexer,
            ahead,
            context: None,
        })
    }

    fn peek(&self) -> &Tok {
        &self.ahead.0
    }

    fn line(&self) -> usize {
        self.ahead.1
    }

    fn next(&mut self) -> Result<Tok, ParseError> {
        let following = match self.ahead.0 {
            Tok::End => (Tok::End, self.ahead.1),
            _ => self.lexer.token().map_err(|e| self.within(e))?,
        };
        Ok(std::mem::replace(&mut self.ahead, following).0)
    }

    fn within(&self, e: ParseError) -> ParseError {
        match &self.context {
            Some(c) => ParseError {
                line: e.line,
                message: format!("in {c}: {}", e.message),
            },
            None => e,
        }
    }

    fn error(&self, message: impl Into<String>) -> ParseError {
        self.within(ParseError {
            line: self.line(),
            message: message.into(),
        })
    }

    fn expect(&mut self, want: Tok) -> Result<(), ParseError> {
        if *self.peek() == want {
            self.next()?;
            Ok(())
        } else {
            Err(self.error(format!("expected {want}, found {}", self.peek())))
        }
    }

    fn at_keyword(&self, want: &str) -> bool {
        matches!(self.peek(), Tok::Keyword(k) if k == want)
    }

    fn file(mut self) -> Result<Exchange, ParseError> {
        if !self.at_keyword("ISO-10303-21") {
            return Err(self.error(format!(
                "not a STEP file (ISO 10303-21): it must begin with ISO-10303-21; but begins with {}",
                self.peek()
            )));
        }
        self.next()?;
        self.expect(Tok::Semi)?;
        let mut exchange = Exchange::default();
        loop {
            let section = match self.peek() {
                Tok::Keyword(k) => k.clone(),
                Tok::End => return Err(self.error("the file ends without END-ISO-10303-21;")),
                other => {
                    return Err(self.error(format!(
                        "expected a section (HEADER;, DATA; or END-ISO-10303-21;), found {other}"
                    )));
                }
            };
            self.next()?;
            match section.as_str() {
                "END-ISO-10303-21" => {
                    self.expect(Tok::Semi)?;
                    return Ok(exchange);
                }
                "DATA" => {
                    if *self.peek() == Tok::Open {
                        self.params(0)?;
                    }
                    self.expect(Tok::Semi)?;
                    self.data(&mut exchange)?;
                }
                "HEADER" | "ANCHOR" | "REFERENCE" | "SIGNATURE" => self.skip_section()?,
                other => {
                    return Err(self.error(format!(
                        "expected a section (HEADER;, DATA; or END-ISO-10303-21;), found {other}"
                    )));
                }
            }
        }
    }

    /// Skips tokens to the section's `ENDSEC;`.
    fn skip_section(&mut self) -> Result<(), ParseError> {
        loop {
            match self.next()? {
                Tok::Keyword(k) if k == "ENDSEC" => return self.expect(Tok::Semi),
                Tok::End => return Err(self.error("a section has no ENDSEC;")),
                _ => {}
            }
        }
    }

    /// Instances up to `ENDSEC;`.
    fn data(&mut self, exchange: &mut Exchange) -> Result<(), ParseError> {
        loop {
            let id = match self.peek() {
                Tok::Keyword(k) if k == "ENDSEC" => {
                    self.next()?;
                    return self.expect(Tok::Semi);
                }
                Tok::Id(id) => *id,
                other => {
                    return Err(self.error(format!(
                        "expected an instance #n = …; or ENDSEC;, found {other}"
                    )));
                }
            };
            let line = self.line();
            self.next()?;
            let instance = self.instance(id, line)?;
            if let Some(&k) = exchange.by_id.get(&id) {
                return Err(ParseError {
                    line,
                    message: format!(
                        "#{id} is defined twice (first on line {})",
                        exchange.instances[k].line
                    ),
                });
            }
            exchange.by_id.insert(id, exchange.instances.len());
            exchange.instances.push(instance);
        }
    }

    /// `= NAME(…);` or `= (NAME(…) NAME(…));` after `#id`.
    fn instance(&mut self, id: u64, line: usize) -> Result<Instance, ParseError> {
        self.context = Some(format!("#{id}"));
        self.expect(Tok::Eq)?;
        let mut records = Vec::new();
        if *self.peek() == Tok::Open {
            self.next()?;
            while *self.peek() != Tok::Close {
                records.push(self.record(id)?);
            }
            self.next()?;
            if records.is_empty() {
                return Err(self.error("a complex instance needs at least one record"));
            }
        } else {
            records.push(self.record(id)?);
        }
        self.expect(Tok::Semi)?;
        self.context = None;
        Ok(Instance { id, line, records })
    }

    fn record(&mut self, id: u64) -> Result<Record, ParseError> {
        let Tok::Keyword(name) = self.peek().clone() else {
            return Err(self.error(format!("expected an entity name, found {}", self.peek())));
        };
        self.next()?;
        self.context = Some(format!("#{id} = {name}"));
        let params = self.params(0)?;
        Ok(Record { name, params })
    }

    /// `( p, p, … )`.
    fn params(&mut self, depth: usize) -> Result<Vec<Param>, ParseError> {
        if depth > MAX_DEPTH {
            return Err(self.error(format!("lists nested deeper than {MAX_DEPTH}")));
        }
        self.expect(Tok::Open)?;
        let mut out = Vec::new();
        if *self.peek() == Tok::Close {
            self.next()?;
            return Ok(out);
        }
        loop {
            out.push(self.param(depth)?);
            match self.peek() {
                Tok::Comma | Tok::Close => {
                    if self.next()? == Tok::Close {
                        return Ok(out);
                    }
                }
                other => return Err(self.error(format!("expected ',' or ')', found {other}"))),
            }
        }
    }

    fn param(&mut self, depth: usize) -> Result<Param, ParseError> {
        match self.peek().clone() {
            Tok::Param(p) => {
                self.next()?;
                Ok(p)
            }
            Tok::Id(id) => {
                self.next()?;
                Ok(Param::Ref(id))
            }
            Tok::Open => Ok(Param::List(self.params(depth + 1)?)),
            Tok::Keyword(name) => {
                self.next()?;
                let mut inner = self.params(depth + 1)?;
                if inner.len() != 1 {
                    return Err(self.error(format!(
                        "the typed value {name}(…) must hold exactly one value"
                    )));
                }
                Ok(Param::Typed(name, Box::new(inner.remove(0))))
            }
            other => Err(self.error(format!("expected a value, found {other}"))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wrap(data: &str) -> String {
        format!(
            "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('a;b'),'2;1');\nFILE_SCHEMA(('X'));\n\
             ENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
        )
    }

    #[test]
    fn reads_every_kind_of_parameter() {
        let text = wrap(
            "/* a comment; with #1 = X(); inside */\n\
             #1 = CARTESIAN_POINT('it''s', (1., -2.5E-3, .5, 1.e2, 3));\n\
             #2=ENTITY(#1,$,*,.T.,.milli.,\"0F\",LENGTH_MEASURE(25.4),((1,2),()));\n\
             #3 = (A() B(1, #2) C('x'));",
        );
        let ex = Exchange::parse(&text).unwrap();
        assert_eq!(ex.instances.len(), 3);
        let p = ex.get(1).unwrap();
        assert_eq!(p.line, 8);
        assert_eq!(p.records[0].params[0], Param::Str("it's".into()));
        let coords: Vec<f64> = p.records[0].params[1]
            .list()
            .unwrap()
            .iter()
            .map(|q| q.number().unwrap())
            .collect();
        assert_eq!(coords, vec![1.0, -2.5e-3, 0.5, 100.0, 3.0]);
        assert_eq!(p.records[0].params[1].list().unwrap()[4], Param::Integer(3));
        let e = &ex.get(2).unwrap().records[0].params;
        assert_eq!(e[0], Param::Ref(1));
        assert_eq!(e[1], Param::Unset);
        assert_eq!(e[2], Param::Derived);
        assert_eq!(e[3], Param::Enum("T".into()));
        assert_eq!(e[4], Param::Enum("MILLI".into()));
        assert_eq!(e[5], Param::Binary("0F".into()));
        assert_eq!(e[6].number(), Some(25.4));
        assert_eq!(
            e[7],
            Param::List(vec![
                Param::List(vec![Param::Integer(1), Param::Integer(2)]),
                Param::List(vec![])
            ])
        );
        let c = ex.get(3).unwrap();
        assert_eq!(c.names(), "(A B C)");
        assert_eq!(c.record("B").unwrap().params[1], Param::Ref(2));
    }

    fn error(text: &str) -> String {
        Exchange::parse(text).unwrap_err().to_string()
    }

    #[test]
    fn errors_name_the_line_and_the_instance() {
        assert_eq!(
            error(&wrap("#1 = POINT((1., 2.);\n#2 = X();")),
            "line 7: in #1 = POINT: expected ',' or ')', found ';'"
        );
        assert_eq!(
            error(&wrap("#1 = X();\n#1 = Y();")),
            "line 8: #1 is defined twice (first on line 7)"
        );
        assert_eq!(
            error(&wrap("#1 = X('abc);")),
            "line 7: in #1 = X: a string ' is never closed"
        );
        assert_eq!(
            error(&wrap("#1 = X(1.5.);")),
            "line 7: in #1 = X: '.' is not a number"
        );
        assert_eq!(
            error(&wrap("#1 = X(1 ?);")),
            "line 7: in #1 = X: unexpected character '?'"
        );
        assert!(error("IGES file").starts_with("line 1: not a STEP file"));
        let cut = wrap("#1 = X();");
        let cut = cut.trim_end().trim_end_matches("END-ISO-10303-21;");
        assert_eq!(
            error(cut),
            "line 9: the file ends without END-ISO-10303-21;"
        );
        assert!(error(&wrap("/* open")).contains("comment"));
        let deep = format!("#1 = X({}{});", "(".repeat(100), ")".repeat(100));
        assert!(error(&wrap(&deep)).contains("nested deeper"));
    }
}
