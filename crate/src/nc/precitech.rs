//! Precitech style: `G71` millimetres, `G18 G90 G40`, `G1 X Z C` blocks with F only when it
//! changes, X negative by default (the tool works on the −X side of the spindle axis), C wrapped
//! to [0, 360); `M30` ends the program. A style, not Precitech's specification: check against the
//! machine's programming manual; every sign is an option of the job.

use super::{Axis, Macros, Style};

/// The Precitech style.
pub static STYLE: Style = Style {
    name: "Precitech style",
    extension: "nc",
    preamble: &["G71 G18 G90 G40 G94"],
    block_prefix: "G1 ",
    words: [Axis::X, Axis::Z, Axis::C],
    feed_every_block: false,
    x_sign: -1.0,
    wrap_c: true,
    end: &["M30"],
    fts_word: b'W',
    max_line: 128,
    macros: Macros::Fanuc,
};
