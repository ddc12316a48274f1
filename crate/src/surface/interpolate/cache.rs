//! Per-thread memory of the last work done for a scattered surface, which the planner's access
//! pattern reuses heavily: the compensation asks for the slope kinks along a nose arc's line
//! and then evaluates the surface at points of that same line, in order.
//!
//! - **Line windows**: the walked chunks of the neighbour-set walk along recent lines, with
//!   what the surface made of each chunk (its kinks and the L1 RBF's cubic stretches,
//!   [`Made`]; [`along`]), in a table of [`LINE_SLOTS`] entries, [`LINE_WAYS`] to a hash of the
//!   line, the least recently used of them giving way: each holds the chunks around the last
//!   range asked for on its line. The nose arcs of a constant-angle spiral's points at one
//!   angle lie on one line (the same bits on every turn: [`crate::path::Spiral::sin_cos`]), a
//!   feed apart, and the concave-zone report compensates many points of each of its sections:
//!   a chunk is walked once for many arcs instead of once for each. The chunks are those of
//!   the uncached walk ([`NeighbourIndex::chunk_pieces`], anchored at t = 0), so the pieces
//!   are the same bits; ranges longer than `MAX_WINDOW_CHUNKS` chunks are walked unkept.
//! - **Pieces**: the neighbour sets along the last line ([`remember_line`]); a query on that
//!   line takes its piece's set instead of a kd-tree search ([`set_on_last_line`]), except
//!   within [`SWITCH_BAND`] of a switch, where the search decides (the two agree everywhere
//!   else: `neighbours::tests` and `tests/tests/surface_scattered.rs`).
//! - **Section**: the L1 RBF along the last line as its cubics between kinks
//!   ([`remember_line`], [`super::line_section`]): a sample of the compensation on that
//!   line is a cubic's value ([`radial_on_last_line`]), away from the switches as above.
//! - **Local systems**: solved RBF interpolants in a table of [`RBF_SLOTS`] entries indexed by
//!   a hash of the neighbour set, a new one taking its slot's place ([`with_local_rbf`]): the
//!   samples of one nose arc go back and forth across its pieces, and the next point's arc,
//!   beside it, crosses mostly the same neighbour sets, so most systems are solved once for
//!   several points.
//!
//! Measured on the scattered example (`crate/jobs/scattered-lens-array.json`, 180 001 points,
//! 2 cores): 56–59 s before the windows, 29–32 s with them (peak memory 41 → 70 MB), the
//! program byte-identical. The walk fell from about 45 % of the time to 3 %; the rest was the
//! search of each arc, about 250 surface evaluations a point (every switch sampled either
//! side), a fifth of it solving systems the table had lost. With the windows, 8 192 system
//! slots gave 13.8 s on the example at a feed of 0.1 mm/rev against 16.3 s with 1 024 and
//! 14.4 s with 32 768; 65 536 slots gave 28 s at the example's feed for 90 MB more. With the
//! cubics kept in the windows and read for those evaluations, 16–18 s (peak memory 108 MB),
//! the program byte-identical again. With 4 ways to a line's hash, a thread's 1 080 or so lines
//! (512 sets, 2.1 a set on average) overfilled some sets, whose lines then evicted each other
//! every turn and walked their whole range afresh: 11 000 windows made and 800 000 chunks
//! walked where 2 200 and 490 000 do; 16 ways (128 sets of 16, 8.4 a set) keep them, and the
//! example's CPU time fell by a fifth (19.2–21.8 s → 15.6–17.6 s, the same peak memory).
//!
//! All are keyed by a surface identity ([`next_id`]), so surfaces never share entries; the
//! values returned are those a fresh computation gives.

use super::line_section::{LineSection, Stretch};
use super::neighbours::{NeighbourIndex, NeighbourSet, Piece, clip};
use super::rbf::LocalRbf;
use crate::surface::{Line, Radial};
use std::cell::RefCell;
use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, Ordering};

/// Distance from a switch (mm, plus 1e-15 of |t|) within which a query on the remembered line
/// is searched for afresh: several times the uncertainty of a switch position (~2e-14 mm).
pub const SWITCH_BAND: f64 = 1e-13;
/// Local RBF systems kept per thread (a power of two; about 4.5 MB).
pub const RBF_SLOTS: usize = 8192;

/// Lines whose walked chunks are kept per thread (a power of two): the 720 or so angles of a
/// spiral's turn and the 360 sections of the concave-zone report.
pub const LINE_SLOTS: usize = 2048;
/// Entries a line may take (its hash picks a set of this many).
pub const LINE_WAYS: usize = 16;
/// The most chunks a window keeps (longer ranges are walked without keeping them).
const MAX_WINDOW_CHUNKS: i64 = 1024;

static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// A new surface identity.
pub fn next_id() -> u64 {
    NEXT_ID.fetch_add(1, Ordering::Relaxed)
}

/// What is remembered of the last line of one surface asked about: its pieces up to `t1`, and
/// its section where the surface made one (the L1 RBF's).
struct LastLine {
    id: u64,
    line: Line,
    t1: f64,
    pieces: Vec<Piece>,
    section: Option<LineSection>,
    /// The buffer the line's kinks came in, kept for the next line's ([`spare_along`]).
    kinks: Vec<f64>,
}

/// The walked chunks `first..` of one line of one surface, in order.
struct LineWindow {
    /// When it was last asked for (the thread's count of requests).
    used: u64,
    id: u64,
    line: Line,
    n: usize,
    first: i64,
    chunks: VecDeque<Chunk>,
}

/// What is kept of one chunk of a line: the walk's pieces and what the surface made of them.
struct Chunk {
    pieces: Vec<Piece>,
    made: Made,
}

/// What a surface makes of a chunk's pieces ([`along`]'s `make`): the slope kinks inside its
/// pieces, at or after each piece's start and before its end, ascending, and its section's
/// stretches ([`super::line_section`]), in order; either may be empty.
#[derive(Debug, Default)]
pub struct Made {
    /// The kinks.
    pub kinks: Vec<f64>,
    /// The stretches.
    pub stretches: Vec<Stretch>,
}

/// What [`along`] hands out for a range of a line.
#[derive(Debug, Default)]
pub struct Along {
    /// The pieces of constant neighbour set, as [`NeighbourIndex::pieces`] gives them.
    pub pieces: Vec<Piece>,
    /// The kinks the surface made of the chunks covering the range, ascending (some may lie
    /// outside it).
    pub kinks: Vec<f64>,
    /// Their stretches, in order, covering the range.
    pub stretches: Vec<Stretch>,
}

thread_local! {
    static WINDOWS: RefCell<(u64, Vec<Option<LineWindow>>)> = const { RefCell::new((0, Vec::new())) };
    static LAST_LINE: RefCell<Option<LastLine>> = const { RefCell::new(None) };
    static SYSTEMS: RefCell<Vec<Option<Kept>>> = const { RefCell::new(Vec::new()) };
}

/// A local system kept: the surface, the neighbour set and its interpolant.
type Kept = (u64, NeighbourSet, LocalRbf);

/// FxHash's multiply-rotate mixing of `words` after the surface `id`: the top `bits` bits.
fn hash_bits(id: u64, words: impl Iterator<Item = u64>, bits: u32) -> usize {
    const K: u64 = 0x517c_c1b7_2722_0a95;
    let h = words.fold(id.wrapping_mul(K), |h, w| {
        (h.rotate_left(5) ^ w).wrapping_mul(K)
    });
    (h >> (64 - bits)) as usize
}

/// The slot of surface `id`'s neighbour set `set`.
fn slot(id: u64, set: &NeighbourSet) -> usize {
    let words = set.indices().iter().map(|&i| u64::from(i));
    hash_bits(id, words, RBF_SLOTS.trailing_zeros())
}

/// The first of the [`LINE_WAYS`] slots of surface `id`'s line.
fn line_ways(id: u64, line: &Line) -> usize {
    let words = [line.x0, line.y0, line.c, line.s]
        .map(f64::to_bits)
        .into_iter();
    let sets = LINE_SLOTS / LINE_WAYS;
    hash_bits(id, words, sets.trailing_zeros()) * LINE_WAYS
}

/// The pieces of constant `n`-neighbour set along `line` over `[t0, t1]`
/// ([`NeighbourIndex::pieces`]'s, the same bits) for surface `id`, and what `make` made of
/// their chunks, from the chunks kept for the line, walking (and making) and keeping those
/// missing. The window then keeps the chunks of the range and a quarter of its length either
/// side; ranges over `MAX_WINDOW_CHUNKS` chunks are walked without keeping. A surface passes
/// the same `make` to every call: the window keeps what it made.
pub fn along(
    id: u64,
    index: &NeighbourIndex,
    (line, n): (Line, usize),
    [t0, t1]: [f64; 2],
    make: &dyn Fn(&[Piece], f64) -> Made,
    out: &mut Along,
) {
    let want = index.chunks(t0, t1);
    let (first, last) = (*want.start(), *want.end());
    let walk = |k: i64| Chunk::walk(index, (line, n), k, make);
    if last.saturating_sub(first) >= MAX_WINDOW_CHUNKS {
        let chunks: Vec<Chunk> = want.map(walk).collect();
        return hand_out(chunks.iter(), [t0, t1], out);
    }
    WINDOWS.with(|c| {
        let (clock, table) = &mut *c.borrow_mut();
        if table.is_empty() {
            table.resize_with(LINE_SLOTS, || None);
        }
        *clock += 1;
        let first_way = line_ways(id, &line);
        let ways = &mut table[first_way..first_way + LINE_WAYS];
        let mine = |w: &LineWindow| w.id == id && w.line == line && w.n == n;
        let way = match ways.iter().position(|w| w.as_ref().is_some_and(mine)) {
            Some(k) => k,
            None => {
                let oldest = (0..LINE_WAYS)
                    .min_by_key(|&k| ways[k].as_ref().map_or(0, |w| w.used))
                    .unwrap_or(0);
                ways[oldest] = Some(LineWindow {
                    used: 0,
                    id,
                    line,
                    n,
                    first,
                    chunks: VecDeque::new(),
                });
                oldest
            }
        };
        let Some(window) = ways[way].as_mut() else {
            return;
        };
        window.used = *clock;
        window.cover(first, last, walk);
        let skip = usize::try_from(first - window.first).unwrap_or(0);
        let count = usize::try_from(last - first + 1).unwrap_or(0);
        hand_out(window.chunks.iter().skip(skip).take(count), [t0, t1], out);
        let margin = (last - first) / 4 + 1;
        window.trim(first - margin, last + margin);
    });
}

/// [`along`]'s pieces alone, made of nothing (a surface passes one `make` to every call).
#[cfg(test)]
fn pieces_along(
    id: u64,
    index: &NeighbourIndex,
    line_n: (Line, usize),
    range: [f64; 2],
    out: &mut Vec<Piece>,
) {
    let mut got = Along::default();
    along(id, index, line_n, range, &|_, _| Made::default(), &mut got);
    out.append(&mut got.pieces);
}

/// The pieces of `chunks` (those covering `[t0, t1]`) clipped to the range, their kinks and
/// stretches, into `out`.
fn hand_out<'a>(
    chunks: impl Iterator<Item = &'a Chunk> + Clone,
    [t0, t1]: [f64; 2],
    out: &mut Along,
) {
    let (mut pieces, mut kinks, mut stretches) = (0, 0, 0);
    for c in chunks.clone() {
        pieces += c.pieces.len();
        kinks += c.made.kinks.len();
        stretches += c.made.stretches.len();
    }
    out.pieces.reserve(pieces);
    out.kinks.reserve(kinks);
    out.stretches.reserve(stretches);
    clip(
        chunks.clone().flat_map(|c| &c.pieces),
        t0,
        t1,
        &mut out.pieces,
    );
    for c in chunks {
        out.kinks.extend_from_slice(&c.made.kinks);
        out.stretches.extend_from_slice(&c.made.stretches);
    }
}

impl Chunk {
    /// Chunk `k` of `line`, walked for `n` neighbours, and what `make` makes of it.
    fn walk(
        index: &NeighbourIndex,
        (line, n): (Line, usize),
        k: i64,
        make: &dyn Fn(&[Piece], f64) -> Made,
    ) -> Self {
        let mut pieces = Vec::new();
        index.chunk_pieces(line, k, n, &mut pieces);
        let made = make(&pieces, index.chunk_start(k + 1));
        Self { pieces, made }
    }
}

impl LineWindow {
    /// The chunk after the last kept.
    fn end(&self) -> i64 {
        self.first + self.chunks.len() as i64
    }

    /// Walks the chunks of `first..=last` not kept yet (all of them when the window lies
    /// apart), each by `walk`.
    fn cover(&mut self, first: i64, last: i64, walk: impl Fn(i64) -> Chunk) {
        if self.chunks.is_empty() || last < self.first - 1 || first > self.end() {
            self.chunks.clear();
            self.first = first;
        }
        for k in (first..self.first).rev() {
            self.chunks.push_front(walk(k));
            self.first = k;
        }
        for k in self.end()..=last {
            self.chunks.push_back(walk(k));
        }
    }

    /// Drops the chunks outside `first..=last`.
    fn trim(&mut self, first: i64, last: i64) {
        while !self.chunks.is_empty() && self.end() - 1 > last {
            self.chunks.pop_back();
        }
        while self.first < first && !self.chunks.is_empty() {
            self.chunks.pop_front();
            self.first += 1;
        }
    }
}

/// Remembers the pieces of surface `id` along `line` up to `t1` (the first starts at t0) and
/// its section there, if any, and keeps the buffer `kinks` for [`spare_along`].
pub fn remember_line(
    id: u64,
    (line, t1): (Line, f64),
    pieces: Vec<Piece>,
    section: Option<LineSection>,
    kinks: Vec<f64>,
) {
    LAST_LINE.with(|c| {
        *c.borrow_mut() = Some(LastLine {
            id,
            line,
            t1,
            pieces,
            section,
            kinks,
        })
    });
}

/// Empty buffers for the next [`along`], made of the last line's, which is forgotten: every
/// nose arc's pieces, kinks and stretches are gathered into the memory of the arc's before,
/// not into fresh allocations.
pub fn spare_along() -> Along {
    let last = LAST_LINE.with(|c| c.borrow_mut().take());
    let Some(last) = last else {
        return Along::default();
    };
    let mut spare = Along {
        pieces: last.pieces,
        kinks: last.kinks,
        stretches: last
            .section
            .map(LineSection::into_stretches)
            .unwrap_or_default(),
    };
    spare.pieces.clear();
    spare.kinks.clear();
    spare.stretches.clear();
    spare
}

/// The neighbour set at `q` from the remembered pieces of surface `id`, when q lies on their
/// line (to 1e-13 mm), within their range and away from every switch.
pub fn set_on_last_line(id: u64, q: [f64; 2]) -> Option<NeighbourSet> {
    LAST_LINE.with(|c| {
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

/// The remembered section of surface `id` at t on `line` (the same bits), away from every
/// switch as [`set_on_last_line`] asks.
pub fn radial_on_last_line(id: u64, line: Line, t: f64) -> Option<Radial> {
    LAST_LINE.with(|c| {
        let c = c.borrow();
        let last = c.as_ref().filter(|l| l.id == id && l.line == line)?;
        let section = last.section.as_ref()?;
        section.radial_at(t, SWITCH_BAND + 1e-15 * t.abs())
    })
}

/// The lowest and highest heights of the remembered section of surface `id` on `line` over
/// each interval between consecutive `ts` (ascending), every sample there included
/// ([`LineSection::ranges_over`]); `None` where it has no section there.
pub fn ranges_on_last_line(id: u64, line: Line, ts: &[f64]) -> Option<Vec<[f64; 2]>> {
    LAST_LINE.with(|c| {
        let c = c.borrow();
        let last = c.as_ref().filter(|l| l.id == id && l.line == line)?;
        last.section.as_ref()?.ranges_over(ts)
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
    fn kept_windows_give_each_range_its_own_walk_to_the_bit() {
        // A jittered grid and ranges along one line as a spiral asks for them (inward a feed
        // at a time), then one back outward, one apart from the window, one overlapping its
        // low side, one over both sides and one longer than a window keeps; another surface on
        // the same line, and another line. Each range's pieces through the windows are those
        // of a walk of that range alone.
        let h = 0.04;
        let points: Vec<[f64; 2]> = (-15..=15)
            .flat_map(|j| {
                (-15..=15).map(move |i| {
                    let jitter = 0.2 * ((i * 7 + j * 13) as f64).sin();
                    [(i as f64 + jitter) * h, (j as f64 - 0.5 * jitter) * h]
                })
            })
            .collect();
        let index = NeighbourIndex::new(&points, h).unwrap();
        let mut ranges: Vec<[f64; 2]> = (0..40)
            .map(|k| {
                let centre = 0.5 - 0.01 * k as f64;
                [centre - 0.15, centre + 0.15]
            })
            .collect();
        ranges.extend([
            [0.3, 0.5],
            [-0.55, -0.5],
            [-0.6, -0.45],
            [-0.7, -0.3],
            [-12.0, 12.0],
            [0.1, 0.2],
        ]);
        // Ranges sliding back and forth by up to a chunk, of varying length: their ends fall
        // at, inside and just beyond the kept windows' edges.
        ranges.extend((0..240).map(|k| {
            let centre = 0.3 * (k as f64 * 0.05).sin();
            let half = 0.03 + 0.02 * (k % 5) as f64;
            [centre - half, centre + half]
        }));
        let (first, second) = (next_id(), next_id());
        let lines = [Line::radial(0.6, 0.8), Line::radial(-0.8, 0.6)];
        let mut switches = 0;
        for [t0, t1] in ranges {
            for (id, line) in [(first, lines[0]), (second, lines[0]), (first, lines[1])] {
                let (mut kept, mut walked) = (Vec::new(), Vec::new());
                pieces_along(id, &index, (line, 8), [t0, t1], &mut kept);
                index.pieces(line, t0, t1, 8, &mut walked);
                assert_eq!(kept, walked, "[{t0}, {t1}] {line:?}");
                switches += walked.len() - 1;
            }
        }
        assert!(switches > 1000, "{switches}");
    }

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
