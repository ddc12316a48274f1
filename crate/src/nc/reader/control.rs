//! Control flow without holding the program: loops go back by seeking their source to the line
//! that opened them, and skips (a false `WHILE`, an `if` branch not taken, `GOTO`, `break`) read
//! forward to the line they need; each skip's target is cached by the line that asked for it, so
//! a loop passes over its body once, not once per pass. The loop stack is a vector.
//!
//! - Fanuc custom macro (Moore and Precitech style): `WHILE[cond] DO n` … `END n` (nested
//!   loops of the same n match by depth); `DO n` … `END n` alone loops for ever (up to the cap);
//!   `IF[cond] GOTO n`, `IF[cond] THEN …`, `GOTO n`. GOTO looks for `N n` after the line to the
//!   end of the file, then from the start of the file (Fanuc searches the same way); going
//!   forward past an `END` leaves that loop, going back before a loop's `WHILE` leaves it, and
//!   jumping into a loop is an error.
//! - LinuxCNC O-codes: `o… while` / `endwhile`, `o… do` / `while`, `o… repeat [n]` /
//!   `endrepeat`, `o… if` / `elseif` / `else` / `endif`, `o… break`, `o… continue`, matched by
//!   their label as LinuxCNC does.
//!
//! Every loop counts its passes against `max_loop_iterations` (a backward `GOTO` counts for
//! its line); the total of lines read, executed or passed over, against `max_lines`.

use super::error::Problem;
use super::expression::Evaluator;
use super::interpreter::{Mark, Reader, Scan};
use super::lexer::{Classified, Cursor, Head, Label, OKeyword};
use super::variables::Key;
use std::collections::{HashMap, HashSet};

/// Most cached skip targets, sub bodies and program numbers (past it the cache starts over).
pub const MAX_CACHED: usize = 65_536;

/// An open loop or `if`.
#[derive(Debug, Clone)]
pub(crate) struct LoopEntry {
    /// What it is.
    pub kind: LoopKind,
    /// The line that opened it.
    pub start: Mark,
    /// The line after that.
    pub body: Mark,
    /// Passes so far.
    pub passes: u64,
}

/// The kinds of loops and `if`s.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum LoopKind {
    /// `WHILE[…] DO n`.
    While(u64),
    /// `DO n` alone.
    Do(u64),
    /// `o… while`.
    OWhile(Label),
    /// `o… do`.
    ODo(Label),
    /// `o… repeat`, with the passes left.
    ORepeat(Label, u64),
    /// `o… if` (or a branch) being run.
    OIf(Label),
}

impl LoopKind {
    /// The statement that opens it, for messages.
    pub fn describe(&self) -> String {
        match self {
            LoopKind::While(n) => format!("WHILE … DO {n}"),
            LoopKind::Do(n) => format!("DO {n}"),
            LoopKind::OWhile(l) => format!("{l} while"),
            LoopKind::ODo(l) => format!("{l} do"),
            LoopKind::ORepeat(l, _) => format!("{l} repeat"),
            LoopKind::OIf(l) => format!("{l} if"),
        }
    }

    fn label(&self) -> Option<&Label> {
        match self {
            LoopKind::OWhile(l) | LoopKind::ODo(l) | LoopKind::ORepeat(l, _) => Some(l),
            _ => None,
        }
    }
}

/// Why a target was cached.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum Purpose {
    /// Past the end of a loop or sub that is not run.
    Past,
    /// To the line that closes the structure (`endif`, `endwhile`, …).
    ToEnd,
    /// To the next branch of an `if`.
    ToBranch,
    /// A `GOTO` to this label (the target can be an expression).
    Goto(u64),
}

/// A cached jump: the target line, the line after it, and for a forward GOTO how many loops
/// it leaves (`None` for a backward one).
#[derive(Debug, Clone, Copy)]
struct Target {
    at: Mark,
    after: Mark,
    exits: Option<u32>,
    passes: u64,
}

/// Targets found by reading forward, by the file and line that asked.
#[derive(Debug, Default)]
pub(crate) struct Cache {
    targets: HashMap<(u32, u64, Purpose), Target>,
    subs: HashMap<(u32, Label), Mark>,
    /// Files read to their end looking for subs: every sub of theirs is in `subs`.
    subs_complete: HashSet<u32>,
    programs: HashMap<(u32, u64), Option<Mark>>,
}

impl Cache {
    fn room(&mut self) {
        let len = self.targets.len() + self.subs.len() + self.subs_complete.len();
        if len + self.programs.len() >= MAX_CACHED {
            *self = Cache::default();
        }
    }

    /// The body of `label sub` in file `id`, if seen.
    pub fn sub(&self, id: u32, label: &Label) -> Option<Mark> {
        self.subs.get(&(id, label.clone())).copied()
    }

    /// Notes the body of `label sub` in file `id`.
    pub fn set_sub(&mut self, id: u32, label: Label, body: Mark) {
        self.room();
        self.subs.entry((id, label)).or_insert(body);
    }

    /// Whether every sub of file `id` is known.
    pub fn all_subs_known(&self, id: u32) -> bool {
        self.subs_complete.contains(&id)
    }

    /// Notes that every sub of file `id` is known.
    pub fn set_all_subs_known(&mut self, id: u32) {
        self.room();
        self.subs_complete.insert(id);
    }

    /// Where `O number` of file `id` was found (`Some(None)`: looked for, absent).
    pub fn program(&self, id: u32, number: u64) -> Option<Option<Mark>> {
        self.programs.get(&(id, number)).copied()
    }

    /// Notes where `O number` of file `id` is.
    pub fn set_program(&mut self, id: u32, number: u64, body: Option<Mark>) {
        self.room();
        self.programs.insert((id, number), body);
    }
}

impl<'a> Reader<'a> {
    fn loop_top(&self) -> Option<&LoopEntry> {
        self.loops[self.frame().loops_base..].last()
    }

    fn push_loop(&mut self, kind: LoopKind, start: Mark) -> Result<(), Problem> {
        if self.loops.len() >= super::MAX_LOOP_NESTING {
            return Err(Problem::Limit {
                what: "loop and if nesting".into(),
                limit: super::MAX_LOOP_NESTING as u64,
                hint: "loops and ifs open at once (all calls together)".into(),
            });
        }
        let body = self.next_mark();
        self.loops.push(LoopEntry {
            kind,
            start,
            body,
            passes: 0,
        });
        Ok(())
    }

    /// Counts a pass of the innermost loop.
    fn count_pass(&mut self) -> Result<(), Problem> {
        let cap = self.options.max_loop_iterations;
        let top = self.loops.last_mut().ok_or(Problem::NoMotion)?;
        top.passes += 1;
        if top.passes > cap {
            let what = top.kind.describe();
            let line = top.start.line;
            return Err(Problem::Limit {
                what: format!("the passes of {what} (line {line})"),
                limit: cap,
                hint: "a runaway loop? the cap is ReaderOptions::max_loop_iterations".into(),
            });
        }
        Ok(())
    }

    fn condition(&mut self, text: &[u8], at: usize) -> Result<bool, Problem> {
        let mut c = Cursor { s: text, i: at };
        if c.peek() != Some(b'[') {
            return Err(Problem::Syntax(format!(
                "a condition is written in brackets, found `{}`",
                c.rest()
            )));
        }
        Ok(Evaluator::new(&self.vars).operand(&mut c)? != 0.0)
    }

    /// `WHILE[cond] DO id` on the line at `at`.
    pub(super) fn fanuc_while(
        &mut self,
        text: &[u8],
        cond: usize,
        id: u64,
        at: Mark,
    ) -> Result<(), Problem> {
        let truth = self.condition(text, cond)?;
        let what = format!("WHILE … DO {id} (line {})", at.line);
        self.while_test(LoopKind::While(id), truth, at, &what, |c| match c.head {
            Head::While { id: i, .. } | Head::Do(i) if i == id => Nest::Open,
            Head::End(i) if i == id => Nest::Close,
            _ => Nest::Other,
        })
    }

    /// The test of a `while` loop opened by the line at `at`: on into the body (a further pass
    /// if this line opened the innermost loop), or past the loop's end.
    fn while_test(
        &mut self,
        kind: LoopKind,
        truth: bool,
        at: Mark,
        what: &str,
        nest: impl FnMut(&Classified) -> Nest,
    ) -> Result<(), Problem> {
        let again = self
            .loop_top()
            .is_some_and(|l| l.kind == kind && l.start == at);
        if truth {
            if again {
                self.count_pass()
            } else {
                self.push_loop(kind, at)
            }
        } else {
            if again {
                self.loops.pop();
            }
            self.skip_past(at, what, nest)
        }
    }

    /// `DO id` alone on the line at `at`.
    pub(super) fn fanuc_do(&mut self, id: u64, at: Mark) -> Result<(), Problem> {
        self.push_loop(LoopKind::Do(id), at)
    }

    /// `END id`.
    pub(super) fn fanuc_end(&mut self, id: u64) -> Result<(), Problem> {
        match self.loop_top().map(|l| (&l.kind, l.start, l.body)) {
            Some((LoopKind::While(i), start, _)) if *i == id => self.seek(start),
            Some((LoopKind::Do(i), _, body)) if *i == id => {
                self.count_pass()?;
                self.seek(body)
            }
            other => Err(Problem::Unbalanced(format!(
                "END {id} without WHILE … DO {id}{}",
                other.map_or(String::new(), |(k, s, _)| format!(
                    " (the innermost open loop is {} on line {})",
                    k.describe(),
                    s.line
                ))
            ))),
        }
    }

    /// `GOTO target` (target evaluated) on the line at `at`.
    pub(super) fn goto(&mut self, target: u64, at: Mark) -> Result<(), Problem> {
        let id = self.file().id;
        let key = (id, at.offset, Purpose::Goto(target));
        let t = match self.cache.targets.get(&key) {
            Some(t) => *t,
            None => {
                let t = self.find_label(target, at)?;
                self.cache.room();
                self.cache.targets.insert(key, t);
                t
            }
        };
        let base = self.frame().loops_base;
        match t.exits {
            Some(n) => {
                let open = self.loops.len() - base;
                if (n as usize) > open {
                    return Err(Problem::Unbalanced(format!(
                        "GOTO {target} leaves {n} loop(s) but {open} are open"
                    )));
                }
                self.loops.truncate(self.loops.len() - n as usize);
            }
            None => {
                while self.loops.len() > base
                    && self
                        .loops
                        .last()
                        .is_some_and(|l| l.start.offset >= t.at.offset)
                {
                    self.loops.pop();
                }
                let passes = t.passes + 1;
                if passes > self.options.max_loop_iterations {
                    return Err(Problem::Limit {
                        what: format!("the backward jumps of GOTO {target} (line {})", at.line),
                        limit: self.options.max_loop_iterations,
                        hint: "a runaway loop? the cap is ReaderOptions::max_loop_iterations"
                            .into(),
                    });
                }
                if let Some(c) = self.cache.targets.get_mut(&key) {
                    c.passes = passes;
                }
            }
        }
        self.seek(t.at)
    }

    /// Finds `N target` forward from the line after `at`, then from the start of the file.
    fn find_label(&mut self, target: u64, at: Mark) -> Result<Target, Problem> {
        let mut depth: i64 = 0;
        let mut exits: u32 = 0;
        let forward = self.scan(|c, _, _| {
            if c.n == Some(target) {
                return if depth > 0 {
                    Scan::Stop(Problem::Unbalanced(format!(
                        "GOTO {target} jumps into a loop"
                    )))
                } else {
                    Scan::Found
                };
            }
            match c.head {
                Head::While { .. } | Head::Do(_) => depth += 1,
                Head::End(_) if depth > 0 => depth -= 1,
                Head::End(_) => exits += 1,
                _ => {}
            }
            Scan::Continue
        })?;
        if let Some((at, after)) = forward {
            return Ok(Target {
                at,
                after,
                exits: Some(exits),
                passes: 0,
            });
        }
        self.seek(super::interpreter::Mark::START)?;
        let stop = at.offset;
        let mut past = false;
        let back = self.scan(|c, after, _| {
            if c.n == Some(target) {
                return Scan::Found;
            }
            if after.offset > stop {
                past = true;
                return Scan::Found;
            }
            Scan::Continue
        })?;
        match back {
            Some((at, after)) if !past => Ok(Target {
                at,
                after,
                exits: None,
                passes: 0,
            }),
            _ => Err(Problem::Unbalanced(format!(
                "GOTO {target}: no line N{target} in {}",
                self.file().name
            ))),
        }
    }

    /// Reads forward past the end of the structure opened at `at`: `nest` says which lines
    /// open and close one like it. Cached by the opening line.
    fn skip_past(
        &mut self,
        at: Mark,
        what: &str,
        mut nest: impl FnMut(&Classified) -> Nest,
    ) -> Result<(), Problem> {
        let key = (self.file().id, at.offset, Purpose::Past);
        if let Some(t) = self.cache.targets.get(&key).copied() {
            return self.seek(t.after);
        }
        let mut depth = 0u64;
        let found = self.scan(|c, _, _| match nest(c) {
            Nest::Open => {
                depth += 1;
                Scan::Continue
            }
            Nest::Close if depth == 0 => Scan::Found,
            Nest::Close => {
                depth -= 1;
                Scan::Continue
            }
            Nest::Other => Scan::Continue,
        })?;
        self.remember(key, found, what).map(|_| ())
    }

    /// Reads forward to the next line that `is_target` accepts, leaving it to be read next.
    fn skip_to(
        &mut self,
        at: Mark,
        purpose: Purpose,
        what: &str,
        mut is_target: impl FnMut(&Classified) -> bool,
    ) -> Result<(), Problem> {
        let key = (self.file().id, at.offset, purpose);
        if let Some(t) = self.cache.targets.get(&key).copied() {
            return self.seek(t.at);
        }
        let found = self.scan(|c, _, _| {
            if is_target(c) {
                Scan::Found
            } else {
                Scan::Continue
            }
        })?;
        let to = self.remember(key, found, what)?;
        self.seek(to.at)
    }

    /// Caches the line a skip found (an error naming `what` if it found none).
    fn remember(
        &mut self,
        key: (u32, u64, Purpose),
        found: Option<(Mark, Mark)>,
        what: &str,
    ) -> Result<Target, Problem> {
        let (at, after) =
            found.ok_or_else(|| Problem::Unbalanced(format!("{what} is never closed")))?;
        let t = Target {
            at,
            after,
            exits: None,
            passes: 0,
        };
        self.cache.room();
        self.cache.targets.insert(key, t);
        Ok(t)
    }

    /// An `o` word with its keyword, on the line at `at`; `rest` is where its arguments start.
    pub(super) fn o_word(
        &mut self,
        label: Label,
        keyword: OKeyword,
        text: &[u8],
        rest: usize,
        at: Mark,
    ) -> Result<(), Problem> {
        let top = self.loop_top().map(|l| l.kind.clone());
        let arrived = self.arrived_by_skip.take();
        let is_top = |k: LoopKind| top.as_ref() == Some(&k);
        let o_kw = |kw: OKeyword, l: Label| move |c: &Classified| matches!(&c.head, Head::OWord { label: x, keyword: k, .. } if *x == l && *k == kw);
        let o_nest = |open: OKeyword, close: OKeyword, l: Label| {
            move |c: &Classified| match &c.head {
                Head::OWord {
                    label: x,
                    keyword: k,
                    ..
                } if *x == l && *k == open => Nest::Open,
                Head::OWord {
                    label: x,
                    keyword: k,
                    ..
                } if *x == l && *k == close => Nest::Close,
                _ => Nest::Other,
            }
        };
        match keyword {
            OKeyword::Sub => {
                let id = self.file().id;
                let body = self.next_mark();
                self.cache.set_sub(id, label.clone(), body);
                let what = format!("{label} sub (line {})", at.line);
                self.skip_past(at, &what, o_nest(OKeyword::Sub, OKeyword::EndSub, label))
            }
            OKeyword::EndSub | OKeyword::Return => {
                if let Some(v) = self.optional_bracket(text, rest)? {
                    // LinuxCNC hands a returned value to the caller in #<_value>.
                    self.set_var(&Key::Name("_value".into()), v)?;
                }
                self.ret(Some(&label))
            }
            OKeyword::Call => {
                let args = self.call_args(text, rest)?;
                self.call_sub(label, &args)
            }
            OKeyword::Do => self.push_loop(LoopKind::ODo(label), at),
            OKeyword::While if is_top(LoopKind::ODo(label.clone())) => {
                if self.condition(text, rest)? {
                    self.count_pass()?;
                    let body = self.loops.last().map(|l| l.body).unwrap_or(at);
                    self.seek(body)
                } else {
                    self.loops.pop();
                    Ok(())
                }
            }
            OKeyword::While => {
                let truth = self.condition(text, rest)?;
                let what = format!("{label} while (line {})", at.line);
                let nest = o_nest(OKeyword::While, OKeyword::EndWhile, label.clone());
                self.while_test(LoopKind::OWhile(label), truth, at, &what, nest)
            }
            OKeyword::EndWhile => match self.loop_top() {
                Some(l) if l.kind == LoopKind::OWhile(label.clone()) => self.seek(l.start),
                _ => Err(self.unmatched(&label, "endwhile", "while")),
            },
            OKeyword::Repeat => {
                // LinuxCNC rounds the count (round_to_int).
                let n = (self.bracket(text, rest, "repeat")? + 0.5).floor();
                let n = if n < 1.0 {
                    0
                } else {
                    n.min(u64::MAX as f64) as u64
                };
                if n > self.options.max_loop_iterations {
                    return Err(Problem::Limit {
                        what: format!("{label} repeat [{n}]"),
                        limit: self.options.max_loop_iterations,
                        hint: "the cap is ReaderOptions::max_loop_iterations".into(),
                    });
                }
                if n == 0 {
                    let what = format!("{label} repeat (line {})", at.line);
                    return self.skip_past(
                        at,
                        &what,
                        o_nest(OKeyword::Repeat, OKeyword::EndRepeat, label),
                    );
                }
                self.push_loop(LoopKind::ORepeat(label, n), at)
            }
            OKeyword::EndRepeat => {
                let left = match self.loop_top() {
                    Some(LoopEntry {
                        kind: LoopKind::ORepeat(x, left),
                        ..
                    }) if *x == label => *left,
                    _ => return Err(self.unmatched(&label, "endrepeat", "repeat")),
                };
                if left > 1 {
                    let l = self.loops.last_mut().ok_or(Problem::NoMotion)?;
                    l.kind = LoopKind::ORepeat(label, left - 1);
                    let body = l.body;
                    self.count_pass()?;
                    self.seek(body)
                } else {
                    self.loops.pop();
                    Ok(())
                }
            }
            OKeyword::If => {
                if self.condition(text, rest)? {
                    self.push_loop(LoopKind::OIf(label), at)
                } else {
                    self.next_branch(label, at)
                }
            }
            OKeyword::ElseIf | OKeyword::Else if is_top(LoopKind::OIf(label.clone())) => {
                // The branch that ran is over.
                self.loops.pop();
                let what = format!("{label} if");
                self.skip_to(
                    at,
                    Purpose::ToEnd,
                    &what,
                    o_kw(OKeyword::EndIf, label.clone()),
                )
                .and_then(|()| self.read_and_drop())
            }
            OKeyword::ElseIf if arrived.as_ref() == Some(&label) => {
                if self.condition(text, rest)? {
                    self.push_loop(LoopKind::OIf(label), at)
                } else {
                    self.next_branch(label, at)
                }
            }
            OKeyword::Else if arrived.as_ref() == Some(&label) => {
                self.push_loop(LoopKind::OIf(label), at)
            }
            OKeyword::EndIf if is_top(LoopKind::OIf(label.clone())) => {
                self.loops.pop();
                Ok(())
            }
            OKeyword::EndIf if arrived.as_ref() == Some(&label) => Ok(()),
            OKeyword::ElseIf | OKeyword::Else | OKeyword::EndIf => {
                let kw = match keyword {
                    OKeyword::ElseIf => "elseif",
                    OKeyword::Else => "else",
                    _ => "endif",
                };
                Err(self.unmatched(&label, kw, "if"))
            }
            OKeyword::Break | OKeyword::Continue => self.break_or_continue(label, keyword, at),
        }
    }

    /// After a false `if`/`elseif`: on to the next `elseif`, `else` or `endif` of `label`.
    fn next_branch(&mut self, label: Label, at: Mark) -> Result<(), Problem> {
        let what = format!("{label} if (line {})", at.line);
        let l = label.clone();
        self.skip_to(at, Purpose::ToBranch, &what, move |c| {
            matches!(&c.head, Head::OWord { label: x, keyword: OKeyword::ElseIf | OKeyword::Else | OKeyword::EndIf, .. } if *x == l)
        })?;
        self.arrived_by_skip = Some(label);
        Ok(())
    }

    fn break_or_continue(
        &mut self,
        label: Label,
        keyword: OKeyword,
        at: Mark,
    ) -> Result<(), Problem> {
        let base = self.frame().loops_base;
        let i = self.loops[base..]
            .iter()
            .rposition(|l| l.kind.label() == Some(&label))
            .map(|i| i + base)
            .ok_or_else(|| {
                let kw = if keyword == OKeyword::Break {
                    "break"
                } else {
                    "continue"
                };
                Problem::Unbalanced(format!("{label} {kw} outside a loop labelled {label}"))
            })?;
        self.loops.truncate(i + 1);
        let kind = self.loops[i].kind.clone();
        let closing = match kind {
            LoopKind::OWhile(_) => OKeyword::EndWhile,
            LoopKind::ORepeat(..) => OKeyword::EndRepeat,
            _ => OKeyword::While,
        };
        let what = kind.describe();
        let is_end = move |c: &Classified| matches!(&c.head, Head::OWord { label: x, keyword: k, .. } if *x == label && *k == closing);
        if keyword == OKeyword::Break {
            self.loops.pop();
            self.skip_to(at, Purpose::ToEnd, &what, is_end)?;
            return self.read_and_drop();
        }
        match kind {
            LoopKind::OWhile(_) => {
                let start = self.loops[i].start;
                self.seek(start)
            }
            _ => self.skip_to(at, Purpose::ToEnd, &what, is_end),
        }
    }

    fn unmatched(&self, label: &Label, kw: &str, opener: &str) -> Problem {
        Problem::Unbalanced(format!(
            "{label} {kw} without an open {label} {opener}{}",
            self.loop_top().map_or(String::new(), |l| format!(
                " (the innermost open one is {} on line {})",
                l.kind.describe(),
                l.start.line
            ))
        ))
    }

    fn bracket(&mut self, text: &[u8], at: usize, what: &str) -> Result<f64, Problem> {
        self.optional_bracket(text, at)?
            .ok_or_else(|| Problem::Syntax(format!("{what} needs a value in brackets")))
    }

    fn optional_bracket(&mut self, text: &[u8], at: usize) -> Result<Option<f64>, Problem> {
        let mut c = Cursor { s: text, i: at };
        if c.done() {
            return Ok(None);
        }
        if c.peek() != Some(b'[') {
            return Err(Problem::Syntax(format!(
                "expected a value in brackets, found `{}`",
                c.rest()
            )));
        }
        let v = Evaluator::new(&self.vars).operand(&mut c)?;
        if !c.done() {
            return Err(Problem::Syntax(format!("unexpected `{}`", c.rest())));
        }
        Ok(Some(v))
    }

    fn call_args(&mut self, text: &[u8], at: usize) -> Result<Vec<f64>, Problem> {
        let mut c = Cursor { s: text, i: at };
        let mut args = Vec::new();
        let mut eval = Evaluator::new(&self.vars);
        while !c.done() {
            if c.peek() != Some(b'[') {
                return Err(Problem::Syntax(format!(
                    "call arguments are written in brackets, found `{}`",
                    c.rest()
                )));
            }
            if args.len() >= super::variables::CALL_LOCALS as usize {
                return Err(Problem::Syntax(format!(
                    "more than {} call arguments",
                    super::variables::CALL_LOCALS
                )));
            }
            args.push(eval.operand(&mut c)?);
        }
        Ok(args)
    }

    /// Reads the line just skipped to (an `endif`, the end of a loop) without running it.
    fn read_and_drop(&mut self) -> Result<(), Problem> {
        self.read_line_counted().map(|_| ())
    }
}

/// How a line bears on the structure being skipped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Nest {
    /// Opens one like it.
    Open,
    /// Closes one.
    Close,
    /// Neither.
    Other,
}
