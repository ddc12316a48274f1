//! Progress of long work: how many items are done out of how many, reported to a callback
//! every [`PROGRESS_EVERY`] items and at the end, so the command line can draw a bar and the
//! page can move its own (and cancel by returning `ControlFlow::Break`).

/// Progress of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Points done.
    pub done: u64,
    /// Points expected (exact for constant angle sampling).
    pub total: u64,
}

/// How often the progress callback is called, in points.
pub const PROGRESS_EVERY: u64 = 65_536;
