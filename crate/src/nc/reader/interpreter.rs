//! The reader: runs a program line by line and hands out what it does, one [`Step`] at a
//! time, in program order — each executed move ([`Move`]: its kind, the absolute machine
//! target after offsets, the feed in effect, the file and line) and the events around the
//! moves ([`Event`]: comments, M codes, tool, spindle, mode changes, calls, the end).
//!
//! It holds the current line, the call stack (one open source per called file), the loop
//! stack, the variables and a bounded cache of jump targets; never the expanded program, so
//! memory stays flat however many blocks the loops and calls run. The program must end with
//! `M2`, `M30` or a closing `%`, as LinuxCNC requires ("File ended with no percent sign or
//! program end"): a text that stops before is reported as truncated. A program that makes no
//! move is an error at its end.

use super::block::{Block, Code};
use super::control::{Cache, LoopEntry};
use super::detect::{Detector, Feature, Summary};
use super::error::{Problem, ReadError};
use super::expression::{Context, Evaluator};
use super::lexer::{Cursor, Head, Label, Normalized, head, normalize};
use super::modal::{
    AxisSet, Change, Feed, Flow, InitialMotion, Modal, MoveKind, OffsetTable, Position,
};
use super::source::LineRead;
use super::subprogram::{Program, ProgramRef, Resolver};
use super::variables::{Key, Variables};
use super::{MAX_CALL_DEPTH, MAX_FILES, MAX_LINE_BYTES, MAX_LINES, MAX_LOOP_ITERATIONS};
use std::collections::{HashMap, VecDeque};
use std::sync::Arc;

/// How to read a program.
#[derive(Debug, Clone, PartialEq)]
pub struct ReaderOptions {
    /// The work offsets of G54…G59.3 (zero by default: program and machine coordinates agree).
    pub offsets: OffsetTable,
    /// Where the machine is when the program starts (zero by default, as rs274 assumes).
    pub start: Position,
    /// The block-delete switch: `true` skips lines starting with `/`; `false` (the default,
    /// as rs274 starts) runs them. Either way each such line is reported.
    pub skip_block_delete: bool,
    /// Codes of the controller that move nothing and are to be accepted (each reported), such
    /// as `G63` or `G103` of a lab's Moore program. Any other unknown code is an error.
    pub accepted_codes: Vec<Code>,
    /// The most lines read in all, executed or passed over ([`MAX_LINES`]).
    pub max_lines: u64,
    /// The most passes of one loop ([`MAX_LOOP_ITERATIONS`]).
    pub max_loop_iterations: u64,
    /// The deepest nesting of calls ([`MAX_CALL_DEPTH`]).
    pub max_call_depth: usize,
    /// The motion mode before the program names one (none by default, as in LinuxCNC).
    pub initial_motion: InitialMotion,
}

impl Default for ReaderOptions {
    fn default() -> Self {
        Self {
            offsets: OffsetTable::default(),
            start: Position::default(),
            skip_block_delete: false,
            accepted_codes: Vec::new(),
            max_lines: MAX_LINES,
            max_loop_iterations: MAX_LOOP_ITERATIONS,
            max_call_depth: MAX_CALL_DEPTH,
            initial_motion: InitialMotion::None,
        }
    }
}

/// A file and line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The program's name.
    pub file: Arc<str>,
    /// The line, from 1.
    pub line: u64,
}

/// An executed move.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// Rapid, linear or arc.
    pub kind: MoveKind,
    /// The machine position at its end: every axis, after work and local offsets, in mm and
    /// degrees (axes not commanded keep their value).
    pub target: Position,
    /// The feed in effect.
    pub feed: Feed,
    /// The axes its block commands.
    pub words: AxisSet,
    /// Where it is written.
    pub at: Location,
}

/// Something a program does besides moving.
#[derive(Debug, Clone, PartialEq)]
pub enum EventKind {
    /// A comment's text (`( … )` or after `;`), trimmed.
    Comment(String),
    /// A change of mode, tool, spindle or offsets, or an M code.
    Change(Change),
    /// A line starting with `/`, run or skipped as the block-delete option says.
    BlockDelete {
        /// Whether it ran.
        executed: bool,
    },
    /// A call: the program's name, and `L` repeats.
    Call {
        /// The called program (file name, with the `O` number or `o<…>` label when in a file).
        program: Arc<str>,
        /// How many times it runs.
        repeats: u64,
    },
    /// A return to the caller.
    Return,
    /// The end: `M2`, `M30` or `%`.
    End(String),
}

/// An event and where it is written.
#[derive(Debug, Clone, PartialEq)]
pub struct Event {
    /// What happened.
    pub kind: EventKind,
    /// Where.
    pub at: Location,
}

/// What the reader hands out.
#[derive(Debug, Clone, PartialEq)]
pub enum Step {
    /// A move.
    Move(Move),
    /// An event.
    Event(Event),
}

/// A line of a source: its byte offset and number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct Mark {
    /// Byte offset of its start.
    pub offset: u64,
    /// Line number, from 1.
    pub line: u64,
}

impl Mark {
    /// The first line.
    pub const START: Mark = Mark { offset: 0, line: 1 };
}

/// An open source.
pub(crate) struct OpenFile<'a> {
    /// Its name.
    pub name: Arc<str>,
    /// Its interned id (caches are keyed by it).
    pub id: u32,
    source: Box<dyn super::source::Source + 'a>,
    next_line: u64,
    /// Offset of its first line with anything on it (an opening `%` is that line).
    first_content: Option<u64>,
}

impl<'a> OpenFile<'a> {
    /// Opens `program` under the interned id `id`.
    pub fn new(program: Program<'a>, id: u32) -> Self {
        Self {
            name: program.name,
            id,
            source: program.source,
            next_line: 1,
            first_content: None,
        }
    }
}

/// What kind of program a frame runs.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum FrameKind {
    /// The main program.
    Main,
    /// An `M98` child, with its first line and the runs left.
    Child {
        /// P.
        number: u64,
        /// Its first line.
        start: Mark,
        /// Runs left, this one included.
        left: u64,
    },
    /// An `o<…> call`.
    Sub {
        /// Its label.
        label: Label,
    },
}

impl FrameKind {
    /// One run of a repeated child done.
    pub fn count_down(&mut self) {
        if let FrameKind::Child { left, .. } = self {
            *left = left.saturating_sub(1);
        }
    }
}

/// A frame of the call stack.
#[derive(Debug, Clone)]
pub(crate) struct Frame {
    /// Index in the open files.
    pub file: usize,
    /// What it runs.
    pub kind: FrameKind,
    /// Loops opened before it (its own are above).
    pub loops_base: usize,
    /// Where the caller goes on.
    pub return_to: Option<Mark>,
    /// Whether it has its own variable scope.
    pub scoped: bool,
}

/// What a scan does with a line.
pub(crate) enum Scan {
    /// Read on.
    Continue,
    /// This is the line.
    Found,
    /// Give up with this problem.
    Stop(Problem),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Running,
    Ended,
    Done,
}

/// Reads a program; see the module docs.
pub struct Reader<'a> {
    pub(super) options: ReaderOptions,
    pub(super) resolver: Option<Box<Resolver<'a>>>,
    pub(super) files: Vec<OpenFile<'a>>,
    pub(super) frames: Vec<Frame>,
    pub(super) loops: Vec<LoopEntry>,
    pub(super) vars: Variables,
    pub(super) cache: Cache,
    pub(super) arrived_by_skip: Option<Label>,
    modal: Modal,
    names: HashMap<Arc<str>, u32>,
    queue: VecDeque<Step>,
    raw: Vec<u8>,
    norm: Normalized,
    scan_raw: Vec<u8>,
    scan_norm: Normalized,
    block: Block,
    here: Location,
    lines_read: u64,
    detector: Detector,
    state: State,
}

impl std::fmt::Debug for Reader<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Reader")
            .field("here", &self.here)
            .field("lines_read", &self.lines_read)
            .finish_non_exhaustive()
    }
}

impl<'a> Reader<'a> {
    /// A reader of `main`; without a resolver, calls find only programs in the same file.
    pub fn new(main: Program<'a>, options: ReaderOptions) -> Self {
        let modal = Modal::new(
            options.offsets,
            options.start,
            options.initial_motion,
            options.accepted_codes.clone(),
        );
        let name = main.name.clone();
        let mut names = HashMap::new();
        names.insert(name.clone(), 0);
        Self {
            options,
            resolver: None,
            files: vec![OpenFile::new(main, 0)],
            frames: vec![Frame {
                file: 0,
                kind: FrameKind::Main,
                loops_base: 0,
                return_to: None,
                scoped: false,
            }],
            loops: Vec::new(),
            vars: Variables::default(),
            cache: Cache::default(),
            arrived_by_skip: None,
            modal,
            names,
            queue: VecDeque::new(),
            raw: Vec::new(),
            norm: Normalized::default(),
            scan_raw: Vec::new(),
            scan_norm: Normalized::default(),
            block: Block::default(),
            here: Location {
                file: name,
                line: 0,
            },
            lines_read: 0,
            detector: Detector::default(),
            state: State::Running,
        }
    }

    /// Sets how called programs are found ([`super::files_beside`] for files on disk).
    pub fn with_resolver(
        mut self,
        resolver: impl FnMut(ProgramRef<'_>) -> Result<Option<Program<'a>>, String> + 'a,
    ) -> Self {
        self.resolver = Some(Box::new(resolver));
        self
    }

    /// The next move or event; `Ok(None)` after the end. After an error, `Ok(None)`.
    pub fn next_step(&mut self) -> Result<Option<Step>, ReadError> {
        loop {
            if let Some(s) = self.queue.pop_front() {
                return Ok(Some(s));
            }
            match self.state {
                State::Running => {
                    if let Err(e) = self.run_line() {
                        self.state = State::Done;
                        self.queue.clear();
                        return Err(e);
                    }
                }
                State::Ended => {
                    self.state = State::Done;
                    if self.detector.moves() == 0 {
                        let file = self.files[0].name.clone();
                        return Err(ReadError::at(Problem::NoMotion, &file, 0, b""));
                    }
                }
                State::Done => return Ok(None),
            }
        }
    }

    /// What was seen so far (complete once [`Reader::next_step`] gives `Ok(None)`).
    pub fn summary(&self) -> Summary {
        self.detector.summary(self.lines_read)
    }

    /// The modal state now: units, modes, offsets, position.
    pub fn modal(&self) -> &Modal {
        &self.modal
    }

    /// Lines read so far (executed or passed over), for progress.
    pub fn lines_read(&self) -> u64 {
        self.lines_read
    }

    /// How far into the main program's text the reader is, in bytes, for progress against
    /// its size (loops and calls go back and forth).
    pub fn main_offset(&self) -> u64 {
        self.files[0].source.offset()
    }

    fn run_line(&mut self) -> Result<(), ReadError> {
        let at = match self.read_line_counted() {
            Ok(Some(at)) => at,
            Ok(None) => return Err(self.end_of_file()),
            Err(p) => return Err(self.error(p)),
        };
        self.here = Location {
            file: self.file().name.clone(),
            line: at.line,
        };
        self.execute_line(at).map_err(|p| self.error(p))
    }

    fn error(&self, p: Problem) -> ReadError {
        ReadError::at(p, &self.here.file, self.here.line, &self.raw)
    }

    fn end_of_file(&mut self) -> ReadError {
        let last = self.file().next_line.saturating_sub(1);
        let open = self.loops[self.frame().loops_base..]
            .last()
            .map(|l| (l.kind.describe(), l.start.line));
        let p = match (&self.frame().kind, open) {
            (_, Some((kind, line))) => {
                Problem::Unbalanced(format!("the text ends inside {kind} opened on line {line}"))
            }
            (FrameKind::Main, None) => Problem::Truncated(format!(
                "the text ends after line {last} without M2, M30 or a closing %"
            )),
            (FrameKind::Child { number, .. }, None) => Problem::Truncated(format!(
                "program {number} ends after line {last} without M99"
            )),
            (FrameKind::Sub { label }, None) => {
                Problem::Unbalanced(format!("{label} sub has no {label} endsub"))
            }
        };
        ReadError::at(p, &self.file().name, last, b"")
    }

    fn execute_line(&mut self, at: Mark) -> Result<(), Problem> {
        let raw = std::mem::take(&mut self.raw);
        let mut norm = std::mem::take(&mut self.norm);
        let r = self.execute_normalized(&raw, &mut norm, at);
        self.raw = raw;
        self.norm = norm;
        r
    }

    fn execute_normalized(
        &mut self,
        raw: &[u8],
        norm: &mut Normalized,
        at: Mark,
    ) -> Result<(), Problem> {
        normalize(raw, norm).map_err(|e| Problem::Syntax(e.to_string()))?;
        for r in &norm.comments {
            let text = String::from_utf8_lossy(&raw[r.clone()]).trim().to_string();
            self.emit(EventKind::Comment(text));
        }
        let c = head(&norm.text).map_err(Problem::Syntax)?;
        if c.head != Head::Empty && self.file().first_content.is_none() {
            self.file_mut().first_content = Some(at.offset);
        }
        if norm.block_delete {
            let executed = !self.options.skip_block_delete;
            self.emit(EventKind::BlockDelete { executed });
            if !executed {
                return Ok(());
            }
        }
        let text = &norm.text;
        match c.head {
            Head::Empty | Head::ProgramNumber(_) => Ok(()),
            Head::Percent => self.percent(at),
            Head::OWord {
                label,
                keyword,
                rest,
            } => {
                self.detector.feature(Feature::OWord);
                self.o_word(label, keyword, text, rest, at)
            }
            Head::While { id, cond } => {
                self.detector.feature(Feature::FanucMacro);
                self.fanuc_while(text, cond, id, at)
            }
            Head::Do(id) => {
                self.detector.feature(Feature::FanucMacro);
                self.fanuc_do(id, at)
            }
            Head::End(id) => {
                self.detector.feature(Feature::FanucMacro);
                self.fanuc_end(id)
            }
            Head::If { cond } => {
                self.detector.feature(Feature::FanucMacro);
                self.fanuc_if(text, cond, at)
            }
            Head::Goto { target } => {
                self.detector.feature(Feature::FanucMacro);
                let n = self.goto_target(text, target)?;
                self.goto(n, at)
            }
            Head::Words { words } => self.words(text, words),
        }
    }

    fn percent(&mut self, at: Mark) -> Result<(), Problem> {
        if self.file().first_content == Some(at.offset) {
            return Ok(());
        }
        match self.frame().kind {
            FrameKind::Main => {
                self.emit(EventKind::End("%".into()));
                self.state = State::Ended;
                Ok(())
            }
            FrameKind::Child { number, .. } => Err(Problem::Truncated(format!(
                "program {number} reaches its closing % without M99"
            ))),
            FrameKind::Sub { ref label } => Err(Problem::Unbalanced(format!(
                "{label} sub reaches a closing % without endsub"
            ))),
        }
    }

    /// `IF[cond] GOTO n` or `IF[cond] THEN …`.
    fn fanuc_if(&mut self, text: &[u8], cond: usize, at: Mark) -> Result<(), Problem> {
        let mut c = Cursor { s: text, i: cond };
        let v = Evaluator::new(&self.vars).operand(&mut c)?;
        if c.eat_keyword(b"goto") {
            if v != 0.0 {
                let n = self.goto_target(text, c.i)?;
                return self.goto(n, at);
            }
            Ok(())
        } else if c.eat_keyword(b"then") {
            if v != 0.0 {
                return self.words(text, c.i);
            }
            Ok(())
        } else {
            Err(Problem::Syntax(format!(
                "IF[…] must be followed by GOTO n or THEN, found `{}`",
                c.rest()
            )))
        }
    }

    fn goto_target(&mut self, text: &[u8], at: usize) -> Result<u64, Problem> {
        let mut c = Cursor { s: text, i: at };
        let v = Evaluator::new(&self.vars).expression(&mut c, Context::Word)?;
        if !c.done() {
            return Err(Problem::Syntax(format!(
                "unexpected `{}` after GOTO",
                c.rest()
            )));
        }
        super::modal::whole("GOTO ", v)
    }

    /// A line of words and settings.
    fn words(&mut self, text: &[u8], from: usize) -> Result<(), Problem> {
        let mut block = std::mem::take(&mut self.block);
        let r = self.run_block(&mut block, text, from);
        self.block = block;
        r
    }

    fn run_block(&mut self, block: &mut Block, text: &[u8], from: usize) -> Result<(), Problem> {
        block.clear();
        let mut c = Cursor { s: text, i: from };
        block.parse(&mut c, &mut Evaluator::new(&self.vars))?;
        for (key, v) in std::mem::take(&mut block.settings) {
            self.set_var(&key, v)?;
        }
        for &code in block.g.iter().chain(&block.m) {
            self.detector.code(code);
        }
        let bare = !block.g.iter().any(|g| matches!(g.tenths, 0 | 10 | 20 | 30));
        let here = self.here.clone();
        let queue = &mut self.queue;
        let (moved, flow) = self.modal.execute(block, &mut |ch| {
            queue.push_back(Step::Event(Event {
                kind: EventKind::Change(ch),
                at: here.clone(),
            }))
        })?;
        if let Some((kind, words)) = moved {
            let target = self.modal.position;
            self.detector.motion(kind, &target, words, bare);
            self.queue.push_back(Step::Move(Move {
                kind,
                target,
                feed: self.modal.feed(),
                words,
                at: self.here.clone(),
            }));
        }
        match flow {
            Flow::Next => Ok(()),
            Flow::Call { number, repeats } => {
                self.detector.feature(Feature::M98);
                self.call_number(number, repeats)
            }
            Flow::Return => self.ret(None),
            Flow::End(code) => {
                self.emit(EventKind::End(code.to_string()));
                self.state = State::Ended;
                Ok(())
            }
        }
    }

    /// Sets a variable, within the bound on their number.
    pub(super) fn set_var(&mut self, key: &Key, v: f64) -> Result<(), Problem> {
        self.vars.set(key, v).map_err(|_| Problem::Limit {
            what: format!("the variables set (setting {key})"),
            limit: super::variables::MAX_VARIABLES as u64,
            hint: "distinct variables in all scopes".into(),
        })
    }

    /// Refuses a repeat count past the loop cap.
    pub(super) fn check_repeats(&self, n: u64) -> Result<(), Problem> {
        if n > self.options.max_loop_iterations {
            return Err(Problem::Limit {
                what: format!("the repeat count L{n}"),
                limit: self.options.max_loop_iterations,
                hint: "the cap is ReaderOptions::max_loop_iterations".into(),
            });
        }
        Ok(())
    }

    /// Queues an event at the current line.
    pub(super) fn emit(&mut self, kind: EventKind) {
        self.queue.push_back(Step::Event(Event {
            kind,
            at: self.here.clone(),
        }));
    }

    /// The current frame.
    pub(super) fn frame(&self) -> &Frame {
        &self.frames[self.frames.len() - 1]
    }

    /// The current frame, to change.
    pub(super) fn frame_mut(&mut self) -> &mut Frame {
        let i = self.frames.len() - 1;
        &mut self.frames[i]
    }

    /// The file being read.
    pub(super) fn file(&self) -> &OpenFile<'a> {
        &self.files[self.frame().file]
    }

    fn file_mut(&mut self) -> &mut OpenFile<'a> {
        let i = self.frame().file;
        &mut self.files[i]
    }

    /// An id for a file name (caches are keyed by it), within [`MAX_FILES`].
    pub(super) fn intern(&mut self, name: &Arc<str>) -> Result<u32, Problem> {
        if let Some(&id) = self.names.get(name) {
            return Ok(id);
        }
        if self.names.len() >= MAX_FILES {
            return Err(Problem::Limit {
                what: "distinct called files".into(),
                limit: MAX_FILES as u64,
                hint: "programs called by different names".into(),
            });
        }
        let id = self.names.len() as u32;
        self.names.insert(name.clone(), id);
        Ok(id)
    }

    /// Where the current file will be read next.
    pub(super) fn next_mark(&self) -> Mark {
        let f = self.file();
        Mark {
            offset: f.source.offset(),
            line: f.next_line,
        }
    }

    /// Makes `to` the next line of the current file.
    pub(super) fn seek(&mut self, to: Mark) -> Result<(), Problem> {
        let f = self.file_mut();
        f.source
            .seek(to.offset)
            .map_err(|e| Problem::Io(format!("{}: {e}", f.name)))?;
        f.next_line = to.line;
        Ok(())
    }

    /// Reads the next line of the current file into the line buffer, counting it.
    pub(super) fn read_line_counted(&mut self) -> Result<Option<Mark>, Problem> {
        let mut buf = std::mem::take(&mut self.raw);
        let r = self.read_into(&mut buf);
        self.raw = buf;
        r
    }

    fn read_into(&mut self, buf: &mut Vec<u8>) -> Result<Option<Mark>, Problem> {
        let at = self.next_mark();
        let f = self.file_mut();
        let read = f
            .source
            .read_line(buf, MAX_LINE_BYTES)
            .map_err(|e| Problem::Io(format!("{}: {e}", f.name)))?;
        match read {
            LineRead::End => return Ok(None),
            LineRead::TooLong => {
                return Err(Problem::Limit {
                    what: format!("the length of line {}", at.line),
                    limit: MAX_LINE_BYTES as u64,
                    hint: "bytes in one line".into(),
                });
            }
            LineRead::Line => f.next_line += 1,
        }
        // A byte-order mark (text saved on Windows) before the first line is not text.
        if at.offset == 0 && buf.starts_with(b"\xef\xbb\xbf") {
            buf.drain(..3);
        }
        self.lines_read += 1;
        if self.lines_read > self.options.max_lines {
            return Err(Problem::Limit {
                what: "the lines read".into(),
                limit: self.options.max_lines,
                hint: "lines executed or passed over, every loop pass counted; the cap is \
                       ReaderOptions::max_lines"
                    .into(),
            });
        }
        Ok(Some(at))
    }

    /// Reads lines of the current file until `f` finds one: `Some((its mark, the mark after))`
    /// with the file positioned after it, or `None` at the end of the text.
    pub(super) fn scan(
        &mut self,
        mut f: impl FnMut(&super::lexer::Classified, Mark, &mut Cache) -> Scan,
    ) -> Result<Option<(Mark, Mark)>, Problem> {
        let mut raw = std::mem::take(&mut self.scan_raw);
        let mut norm = std::mem::take(&mut self.scan_norm);
        let r = loop {
            let at = match self.read_into(&mut raw) {
                Ok(Some(at)) => at,
                Ok(None) => break Ok(None),
                Err(p) => break Err(p),
            };
            let passed = |e: String| {
                Problem::Syntax(format!("line {} (read while looking ahead): {e}", at.line))
            };
            if let Err(e) = normalize(&raw, &mut norm) {
                break Err(passed(e.to_string()));
            }
            let c = match head(&norm.text) {
                Ok(c) => c,
                Err(e) => break Err(passed(e)),
            };
            if c.head != Head::Empty && self.file().first_content.is_none() {
                self.file_mut().first_content = Some(at.offset);
            }
            if c.head == Head::Percent && self.file().first_content != Some(at.offset) {
                break Ok(None);
            }
            let after = self.next_mark();
            match f(&c, after, &mut self.cache) {
                Scan::Continue => {}
                Scan::Found => break Ok(Some((at, after))),
                Scan::Stop(p) => break Err(p),
            }
        };
        self.scan_raw = raw;
        self.scan_norm = norm;
        r
    }
}

impl Iterator for Reader<'_> {
    type Item = Result<Step, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_step().transpose()
    }
}

/// Reads a whole program held in memory, without a resolver, into a vector: for small
/// programs and examples (the [`Reader`] streams).
pub fn read_text(name: &str, text: &str) -> Result<Vec<Step>, ReadError> {
    Reader::new(Program::from_text(name, text), ReaderOptions::default()).collect()
}
