//! Moore Nanotech style (Delta Tau controllers), as DESIGN.md describes it: `G71` millimetres,
//! `G18 G90 G40`; after the approach, `G93` inverse-time feed once and then bare `C X Z` blocks,
//! F repeated only when it changes; C in degrees wrapped to [0, 360); `M30` ends the program.
//! A style, not Moore's specification: check against the machine's programming manual.

use super::{Axis, Macros, Style};

/// The Moore Nanotech style.
pub static STYLE: Style = Style {
    name: "Moore Nanotech style",
    extension: "nc",
    preamble: &["G71 G18 G90 G40 G94"],
    block_prefix: "",
    words: [Axis::C, Axis::X, Axis::Z],
    feed_every_block: false,
    x_sign: 1.0,
    wrap_c: true,
    end: &["M30"],
    fts_word: b'W',
    max_line: 128,
    macros: Macros::Fanuc,
};
