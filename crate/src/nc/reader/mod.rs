//! The NC program reader: runs a program as a controller would and hands out its moves and
//! events one at a time ([`Reader`]), for `spiralcam verify` and the page to compare a program
//! from any system with the design. It reads the three dialects spiralcam writes (ISO as
//! LinuxCNC reads it, the Moore Nanotech and Precitech styles) and programs as other systems
//! write them: Fanuc custom macro B loops and `#` variables, LinuxCNC O-codes, main programs
//! calling children, 2-D turning programs with arcs.
//!
//! | file | what it holds |
//! |---|---|
//! | [`source`] | where the text comes from: memory or a file streamed from disk, by line, with seeking |
//! | [`lexer`] | lines and words: comments, spaces, case, block delete, `%`; the statement's head |
//! | [`expression`], [`variables`] | bracket expressions, operators and functions; `#` variables and their scopes |
//! | [`block`] | a line's words evaluated: G and M codes, axis words, settings |
//! | [`modal`] | the interpreter's modal state: units, distance and feed modes, plane, offsets, motion |
//! | [`control`] | loops, `if`, `GOTO`: the loop stack and the skips |
//! | [`subprogram`] | `M98`/`M99` and `o<…> call`: finding and running called programs |
//! | [`detect`] | units, C wrapping, X side and dialect, detected from what was read |
//! | [`interpreter`] | the reader itself, its options and what it hands out |
//! | [`error`] | why a program cannot be read, with the file, line and text |
//!
//! Nothing here holds the expanded program: the reader keeps the current line, one open source
//! per called file, the loop and call stacks, the variables and a bounded cache of jump targets,
//! so memory stays flat for a 30 M-block program. Every run is bounded: [`MAX_LINES`] lines read
//! in all (executed or passed over; a loop's every pass counts), [`MAX_LOOP_ITERATIONS`] passes
//! of one loop, [`MAX_CALL_DEPTH`] nested calls, [`MAX_LOOP_NESTING`] open loops,
//! [`MAX_LINE_BYTES`] bytes a line, [`expression::MAX_DEPTH`] nested brackets,
//! [`variables::MAX_VARIABLES`] variables (names of [`expression::MAX_NAME`] characters at
//! most), [`MAX_FILES`] called files; the first three are
//! options ([`ReaderOptions`]). Reaching one is an error naming it, never a hang.
//!
//! Every length handed out is in mm, every angle in degrees, as commanded (C is not wrapped or
//! unwrapped: [`Summary::c`] says how the program writes it). Unknown words and codes are
//! errors with the file, the line number and the text, never skipped.

pub mod block;
pub mod control;
pub mod detect;
pub mod error;
pub mod expression;
pub mod interpreter;
pub mod lexer;
pub mod modal;
pub mod source;
pub mod subprogram;
pub mod variables;

pub use block::Code;
pub use detect::{CWrapping, DialectGuess, Summary};
pub use error::{Problem, ReadError};
pub use interpreter::{Event, EventKind, Location, Move, Reader, ReaderOptions, Step, read_text};
pub use modal::{
    AxisSet, Change, DistanceMode, Feed, FeedRateMode, InitialMotion, MachineAxis, MoveKind,
    OffsetTable, Plane, Position, Units,
};
pub use source::{Source, StreamSource, TextSource};
pub use subprogram::{Program, ProgramRef, Resolver, called_names, files_beside, texts_beside};

/// The most bytes in one line (LinuxCNC takes 255; long comments and expressions need more).
pub const MAX_LINE_BYTES: usize = 4096;
/// The most lines read in all, executed or passed over, every loop pass counted: about two
/// minutes of reading at the 0.6 µs a line measured natively (a 30 M-block program is 15 %
/// of it).
pub const MAX_LINES: u64 = 200_000_000;
/// The most passes of one loop (or backward jumps of one `GOTO`).
pub const MAX_LOOP_ITERATIONS: u64 = 10_000_000;
/// The deepest nesting of calls (Fanuc allows 4 to 10 levels, LinuxCNC about 10).
pub const MAX_CALL_DEPTH: usize = 16;
/// The most loops and `if`s open at once, in all calls.
pub const MAX_LOOP_NESTING: usize = 64;
/// The most distinct files a program may call.
pub const MAX_FILES: usize = 1024;
