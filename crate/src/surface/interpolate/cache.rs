//! Per-thread memory of the last work done for a scattered surface, which the planner's access
//! pattern reuses heavily: the compensation asks for the slope kinks along a nose arc's line
//! and then evaluates the surface at points of that same line, in order.
//!
//! - **Pieces**: the neighbour sets along the last line ([`remember_pieces`]); a query on that
//!   line takes its piece's set instead of a kd-tree search ([`set_on_last_line`]), except
//!   within [`SWITCH_BAND`] of a switch, where the search decides (the two agree everywhere
//!   else: `neighbours::tests` and `tests/tests/surface_scattered.rs`).
//! - **Local systems**: the last [`RBF_SLOTS`] solved RBF interpolants by neighbour set
//!   ([`with_local_rbf`]), so that samples going back and forth across a few pieces solve each
//!   system once.
//!
//! Both are keyed by a surface identity ([`next_id`]), so surfaces never share entries; the
//! values returned are those a fresh computation gives.

use super::neighbours::{NeighbourSet, Piece};
use super::rbf::LocalRbf;
use crate::surface::Line;
use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};

/// Distance from a switch (mm, plus 1e-15 of |t|) within which a query on the remembered line
/// is searched for afresh: several times the uncertainty of a switch position (~2e-14 mm).
pub const SWITCH_BAND: f64 = 1e-13;
/// Local RBF systems kept per thread.
pub const RBF_SLOTS: usize = 8;

static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// A new surface identity.
pub fn next_id() -> u64 {
    NEXT_ID.fetch_add(1, Ordering::Relaxed)
}

/// The pieces along one line of one surface.
struct LinePieces {
    id: u64,
    line: Line,
    t1: f64,
    pieces: Vec<Piece>,
}

thread_local! {
    static PIECES: RefCell<Option<LinePieces>> = const { RefCell::new(None) };
    static SYSTEMS: RefCell<Systems> = const { RefCell::new(Systems { slots: Vec::new(), next: 0 }) };
}

/// Kept local systems; `next` is the slot the next new one overwrites (round robin).
struct Systems {
    slots: Vec<(u64, NeighbourSet, LocalRbf)>,
    next: usize,
}

/// Remembers the pieces of surface `id` along `line` up to `t1` (the first starts at t0).
pub fn remember_pieces(id: u64, line: Line, t1: f64, pieces: Vec<Piece>) {
    PIECES.with(|c| {
        *c.borrow_mut() = Some(LinePieces {
            id,
            line,
            t1,
            pieces,
        })
    });
}

/// The neighbour set at `q` from the remembered pieces of surface `id`, when q lies on their
/// line (to 1e-13 mm), within their range and away from every switch.
pub fn set_on_last_line(id: u64, q: [f64; 2]) -> Option<NeighbourSet> {
    PIECES.with(|c| {
        let c = c.borrow();
        let lp = c.as_ref().filter(|lp| lp.id == id)?;
        let (dx, dy) = (q[0] - lp.line.x0, q[1] - lp.line.y0);
        let t = dx * lp.line.c + dy * lp.line.s;
        let band = SWITCH_BAND + 1e-15 * t.abs();
        if (dy * lp.line.c - dx * lp.line.s).abs() > band {
            return None;
        }
        let k = lp.pieces.partition_point(|p| p.start <= t).checked_sub(1)?;
        let lo = lp.pieces[k].start;
        let hi = lp.pieces.get(k + 1).map_or(lp.t1, |p| p.start);
        (t - lo > band && hi - t > band).then_some(lp.pieces[k].set)
    })
}

/// `eval` of the local RBF of `set` for surface `id`: a kept one, or `solve()`'s, kept.
pub fn with_local_rbf<T>(
    id: u64,
    set: NeighbourSet,
    solve: impl FnOnce() -> Result<LocalRbf, f64>,
    eval: impl FnOnce(&LocalRbf) -> T,
) -> Result<T, f64> {
    SYSTEMS.with(|c| {
        let mut sys = c.borrow_mut();
        if let Some(hit) = sys.slots.iter().find(|(i, s, _)| *i == id && *s == set) {
            return Ok(eval(&hit.2));
        }
        let rbf = solve()?;
        let out = eval(&rbf);
        let k = sys.next;
        if k < sys.slots.len() {
            sys.slots[k] = (id, set, rbf);
        } else {
            sys.slots.push((id, set, rbf));
        }
        sys.next = (k + 1) % RBF_SLOTS;
        Ok(out)
    })
}
