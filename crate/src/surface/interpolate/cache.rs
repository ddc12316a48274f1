//! Per-thread memory of the last work done for a scattered surface, which the planner's access
//! pattern reuses heavily: the compensation asks for the slope kinks along a nose arc's line
//! and then evaluates the surface at points of that same line, in order.
//!
//! - **Pieces**: the neighbour sets along the last line ([`remember_pieces`]); a query on that
//!   line takes its piece's set instead of a kd-tree search ([`set_on_last_line`]), except
//!   within [`SWITCH_BAND`] of a switch, where the search decides (the two agree everywhere
//!   else: `neighbours::tests` and `tests/tests/surface_scattered.rs`).
//! - **Local systems**: solved RBF interpolants in a table of [`RBF_SLOTS`] entries indexed by
//!   a hash of the neighbour set, a new one taking its slot's place ([`with_local_rbf`]): the
//!   samples of one nose arc go back and forth across its pieces, and the next point's arc,
//!   beside it, crosses mostly the same neighbour sets, so most systems are solved once for
//!   several points (the scattered example: 50–55 s with this table, 52 s with 64 entries and
//!   66–74 s with 8 searched in turn, round robin, 59 s with 4 096 slots).
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
/// Local RBF systems kept per thread (a power of two; about 0.6 MB).
pub const RBF_SLOTS: usize = 1024;

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
    static SYSTEMS: RefCell<Vec<Option<Kept>>> = const { RefCell::new(Vec::new()) };
}

/// A local system kept: the surface, the neighbour set and its interpolant.
type Kept = (u64, NeighbourSet, LocalRbf);

/// The slot of surface `id`'s neighbour set `set` (FxHash's multiply-rotate mixing, the top bits).
fn slot(id: u64, set: &NeighbourSet) -> usize {
    const K: u64 = 0x517c_c1b7_2722_0a95;
    let h = set.indices().iter().fold(id.wrapping_mul(K), |h, &i| {
        (h.rotate_left(5) ^ u64::from(i)).wrapping_mul(K)
    });
    (h >> (64 - RBF_SLOTS.trailing_zeros())) as usize
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
        let mut table = c.borrow_mut();
        if table.is_empty() {
            table.resize(RBF_SLOTS, None);
        }
        let k = slot(id, &set);
        if let Some((i, s, rbf)) = &table[k]
            && *i == id
            && *s == set
        {
            return Ok(eval(rbf));
        }
        let rbf = solve()?;
        let out = eval(&rbf);
        table[k] = Some((id, set, rbf));
        Ok(out)
    })
}

#[cfg(test)]
mod tests {
    use super::super::neighbours::NeighbourIndex;
    use super::super::rbf::{Distance, Polynomial, RbfSettings};
    use super::*;
    use std::cell::Cell;

    #[test]
    fn kept_systems_give_the_fresh_solution_and_surfaces_never_share_them() {
        // A jittered 41 × 41 grid and the 8-neighbour sets of 3 000 queries over it (2 198 sets
        // for 1 024 slots), so slots are overwritten and hashes collide; every value through the
        // table equals a fresh solve's, to the bit, and a second surface solves its own.
        let h = 0.05;
        let mut points = Vec::new();
        let mut heights = Vec::new();
        for j in -20..=20 {
            for i in -20..=20 {
                let (x, y) = (i as f64 * h, j as f64 * h);
                let jitter = 0.2 * h * ((i * 7 + j * 13) as f64).sin();
                points.push([x + jitter, y - 0.5 * jitter]);
                heights.push((x * 3.0).sin() * (y * 2.0).cos() * 1e-3);
            }
        }
        let index = NeighbourIndex::new(&points, h).unwrap();
        let settings = RbfSettings {
            c: 0.0,
            scale_mm: h,
            polynomial: Polynomial::Linear,
            distance: Distance::Euclidean,
        };
        let solve_set = |set: &NeighbourSet| {
            let c: Vec<[f64; 2]> = set.indices().iter().map(|&i| points[i as usize]).collect();
            let z: Vec<f64> = set.indices().iter().map(|&i| heights[i as usize]).collect();
            LocalRbf::solve(&c, &z, &settings)
        };
        let (first, second) = (next_id(), next_id());
        let solves = Cell::new(0);
        for round in 0..2 {
            for k in 0..3_000 {
                let q = [
                    0.9 * (k as f64 * 0.7123).cos() * (k % 97) as f64 / 97.0,
                    0.9 * (k as f64 * 0.7123).sin() * (k % 89) as f64 / 89.0,
                ];
                let set = index.nearest(q, 8);
                let fresh = solve_set(&set).unwrap().value(q[0], q[1]);
                for id in [first, second] {
                    let before = solves.get();
                    let kept = with_local_rbf(
                        id,
                        set,
                        || {
                            solves.set(solves.get() + 1);
                            solve_set(&set)
                        },
                        |f| f.value(q[0], q[1]),
                    );
                    assert_eq!(kept, Ok(fresh), "round {round} query {k}");
                    // The second surface never finds the first's entry in its slot.
                    if id == second && round == 0 && k == 0 {
                        assert_eq!(solves.get(), before + 1);
                    }
                }
            }
        }
        // Far fewer solves than lookups: the table keeps most sets between queries.
        assert!(solves.get() < 2 * 2 * 3_000, "{}", solves.get());
    }
}
