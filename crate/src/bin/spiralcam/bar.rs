//! The progress bar on standard error (only on a terminal), one line redrawn per update, with
//! the stage's name; and the progress callback that also answers a signal by cancelling.

use crate::cancel;
use spiralcam::progress::{Progress, Stage};
use std::io::IsTerminal;
use std::ops::ControlFlow;

/// A progress callback: draws the bar on a terminal; `Break` once a signal arrived.
pub fn callback() -> impl FnMut(Progress) -> ControlFlow<()> {
    let tty = std::io::stderr().is_terminal();
    move |p: Progress| {
        if tty {
            draw(p);
        }
        if cancel::cancelled() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

/// Ends the bar's line (on a terminal).
pub fn end() {
    if std::io::stderr().is_terminal() {
        eprintln!();
    }
}

fn draw(p: Progress) {
    let frac = if p.total > 0 {
        (p.done as f64 / p.total as f64).min(1.0)
    } else {
        1.0
    };
    let filled = (frac * 40.0) as usize;
    let items = match p.stage {
        Stage::Bands => "circles",
        Stage::Zones => "sections and zones",
        Stage::FtsGrid => "passes (at most)",
        Stage::Scan | Stage::Verify => "moves",
        _ => "points",
    };
    eprint!(
        "\r{:>15} [{}{}] {:5.1} % {}/{} {items}\x1b[K",
        p.stage.label(),
        "#".repeat(filled),
        ".".repeat(40 - filled),
        frac * 100.0,
        p.done,
        p.total
    );
}
