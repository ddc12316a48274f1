//! Progress of long work: which stage is running, how many items of it are done out of how
//! many, reported to a callback every [`PROGRESS_EVERY`] items (or every batch, for stages
//! whose items are costly) and at the end, so that the command line can draw a bar and the
//! page its own. Returning `ControlFlow::Break` from the callback cancels the run; every stage
//! checks it, so a cancelled run ends within one batch.

use std::ops::ControlFlow;

/// A stage of a run, in the order a plan goes through them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// HCAA or adaptive sampling estimating its steps: items are radius circles.
    Bands,
    /// The path computed and written: items are points.
    Path,
    /// The machine dynamics reading the path into memory: items are points.
    Dynamics,
    /// The servo's gridded table sized against the path: items are passes over the path.
    FtsGrid,
    /// The concave-zone report: items are radial sections, then zones measured.
    Zones,
    /// The accuracy analysis reading the path: items are points.
    Analysis,
    /// An NC program read through once to count its moves and passes: items are moves.
    Scan,
    /// An NC program verified against the design: items are moves.
    Verify,
}

impl Stage {
    /// What the stage does, for a progress bar.
    pub fn label(self) -> &'static str {
        match self {
            Stage::Bands => "sampling bands",
            Stage::Path => "planning",
            Stage::Dynamics => "dynamics",
            Stage::FtsGrid => "FTS grid",
            Stage::Zones => "concave zones",
            Stage::Analysis => "analysing",
            Stage::Scan => "reading the program",
            Stage::Verify => "verifying",
        }
    }
}

/// Progress of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// The stage running.
    pub stage: Stage,
    /// Items done.
    pub done: u64,
    /// Items expected (exact for constant angle sampling).
    pub total: u64,
}

/// How often the progress callback is called, in points.
pub const PROGRESS_EVERY: u64 = 65_536;

/// A progress callback: returns `Break` to cancel.
pub type ProgressFn<'a> = dyn FnMut(Progress) -> ControlFlow<()> + 'a;

/// A callback that never cancels, for callers without a progress bar.
pub fn ignore(_: Progress) -> ControlFlow<()> {
    ControlFlow::Continue(())
}
