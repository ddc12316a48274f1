//! ISO RS-274 style, as LinuxCNC's interpreter reads it (`rs274 -g` is the test suite's
//! independent reader): `G21` millimetres, `G18` ZX plane, `G90` absolute, `G40` no cutter
//! compensation; `G1 X Z C F` blocks with F on every block in `G93` inverse-time mode (LinuxCNC
//! requires it); C cumulative by default, since a rotary axis in absolute mode would turn back
//! at each wrap; `M2` ends the program.

use super::{Axis, Macros, Style};

/// The ISO style.
pub static STYLE: Style = Style {
    name: "ISO RS-274 (LinuxCNC)",
    extension: "ngc",
    preamble: &["G21 G18 G90 G40 G94"],
    block_prefix: "G1 ",
    words: [Axis::X, Axis::Z, Axis::C],
    feed_every_block: true,
    x_sign: 1.0,
    wrap_c: false,
    end: &["M2"],
    fts_word: b'Y',
    max_line: 252,
    macros: Macros::LinuxCnc,
};
