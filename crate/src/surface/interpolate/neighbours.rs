//! The n nearest data points of a query (a kd-tree, the `kiddo` crate), and where that set
//! changes along a line.
//!
//! **Order.** Point i is ranked by the key `|q − pᵢ|² + i·δ`, δ a tie-break far below the
//! spacing (`δ = 256·ε·(R + h)·h`, ε the f64 epsilon, R the largest coordinate of the data,
//! h the spacing; N·δ stays under 1e-7·h² for the largest data sets). On a regular grid many
//! points are exactly equidistant from a query on a symmetry line (a radial section at 0°
//! through a grid row, say); without the tie-break the set there would depend on rounding and
//! flicker from one query to the next. δ is larger than the rounding of `|q − pᵢ|²` (about
//! 24·ε·R·h), so ties are broken by the point's index, consistently. The set is returned in
//! ascending index order, so that the same set always gives the same local system.
//!
//! **Switches along a line** (paper 004 interpolates "to the n neighbour points" of each query
//! point, eq 5: the interpolant jumps wherever that set changes). Along `p(t) = p₀ + t·u` the
//! key difference of two points, `|p(t) − q|² − |p(t) − p|² + (i_q − i_p)·δ`, is linear in t, so
//! the set changes exactly where an outside point's key first falls to a member's. The line is
//! walked in chunks of one spacing: the candidates of a chunk are the points within
//! `d_n + 1.5·chunk` of its midpoint (d_n the n-th distance at its start, which grows by at
//! most the distance walked), and the earliest crossing of any (member, outsider) pair is
//! swapped in, repeatedly ([`super::kinetic`]). The chunks lie on a grid anchored at t = 0,
//! `[k·c, (k+1)·c)`, and each starts from the kd-tree's set at its start: a chunk's pieces
//! depend on the line and k only, so that a stretch's switches are the same bits whichever
//! range they were asked for in, and chunks walked once can be kept ([`super::cache`]).
//! Chunks of one spacing planned the scattered example in 2.45 s, of half a spacing 2.6–2.9 s,
//! three quarters 2.5–2.9 s, one and a half 2.6–2.8 s, two 3.1–3.8 s (the same program): a
//! longer chunk starts fewer kd-tree queries and kinetic structures, but over more candidates.

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use std::num::NonZero;

use super::kinetic::{Candidate, Kinetic};
use crate::surface::Line;

/// The most neighbours any method uses.
pub const MAX_NEIGHBOURS: usize = 16;

/// Room for the candidates of a chunk, made at once.
const CANDIDATES: usize = 4 * MAX_NEIGHBOURS;

/// Events handled per chunk before the set is simply re-queried (a guard, never reached in
/// practice: a chunk of one spacing sees a handful of switches).
const MAX_EVENTS: usize = 4096;

/// A set of up to [`MAX_NEIGHBOURS`] point indices, ascending.
#[derive(Debug, Clone, Copy, Eq)]
pub struct NeighbourSet {
    idx: [u32; MAX_NEIGHBOURS],
    len: usize,
}

/// The same indices: compared one by one up to the first that differs, inline, rather than
/// the whole array through a library `memcmp` (sets are compared at every piece of a walk).
impl PartialEq for NeighbourSet {
    fn eq(&self, other: &Self) -> bool {
        self.len == other.len
            && self
                .indices()
                .iter()
                .zip(other.indices())
                .all(|(a, b)| a == b)
    }
}

impl NeighbourSet {
    /// The set of the first [`MAX_NEIGHBOURS`] of `items`, in any order (without a vector in
    /// between: a walk makes one at every switch).
    fn from_unsorted(items: impl IntoIterator<Item = u32>) -> Self {
        let mut idx = [0; MAX_NEIGHBOURS];
        let mut len = 0;
        for (slot, item) in idx.iter_mut().zip(items) {
            *slot = item;
            len += 1;
        }
        idx[..len].sort_unstable();
        Self { idx, len }
    }

    /// The indices, ascending.
    pub fn indices(&self) -> &[u32] {
        &self.idx[..self.len]
    }
}

/// A stretch of a line `[start, next piece's start)` over which the neighbour set is constant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// Line parameter where the set takes effect, mm.
    pub start: f64,
    /// The set.
    pub set: NeighbourSet,
}

/// The data points in a kd-tree, with the tie-break.
#[derive(Debug)]
pub struct NeighbourIndex {
    tree: ImmutableKdTree<f64, 2>,
    points: Vec<[f64; 2]>,
    /// δ, mm².
    tie: f64,
    /// N·δ: the most the tie-break can add to a key, mm².
    tie_span: f64,
    /// Chunk length of the line walk, mm.
    chunk: f64,
}

impl NeighbourIndex {
    /// Indexes `points` (at least one); `spacing` is the data spacing h, mm.
    pub fn new(points: &[[f64; 2]], spacing: f64) -> Option<Self> {
        let tree = ImmutableKdTree::new_from_slice(points).ok()?;
        let mut this = Self {
            tree,
            points: points.to_vec(),
            tie: 0.0,
            tie_span: 0.0,
            chunk: spacing,
        };
        this.set_spacing(spacing);
        Some(this)
    }

    /// Sets the data spacing h, which fixes the tie-break δ and the chunk of the line walk.
    pub fn set_spacing(&mut self, spacing: f64) {
        let extent = self
            .points
            .iter()
            .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
        self.tie = 256.0 * f64::EPSILON * (extent + spacing) * spacing;
        self.tie_span = self.tie * self.points.len() as f64;
        self.chunk = spacing;
    }

    /// The indexed points, mm.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// The ranking key of point `i` from `q`.
    fn key(&self, q: [f64; 2], i: u32) -> f64 {
        let p = self.points[i as usize];
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        dx * dx + dy * dy + i as f64 * self.tie
    }

    /// The distance from `q` to its nearest data point other than `q`'s own index `own`, mm,
    /// with that point's index.
    pub fn nearest_other(&self, own: usize) -> (f64, usize) {
        let q = self.points[own];
        let k = NonZero::new(2.min(self.points.len())).unwrap_or(NonZero::<usize>::MIN);
        self.tree
            .query(&q)
            .nearest_n::<SquaredEuclidean<f64>>(k)
            .execute()
            .into_iter()
            .map(|r| r.item as usize)
            .filter(|&i| i != own)
            .map(|i| {
                let p = self.points[i];
                ((p[0] - q[0]).hypot(p[1] - q[1]), i)
            })
            .next()
            .unwrap_or((f64::INFINITY, own))
    }

    /// The `n` points of smallest key from `q` (n ≤ the point count, ≤ 16).
    pub fn nearest(&self, q: [f64; 2], n: usize) -> NeighbourSet {
        let total = self.points.len();
        let n = n.min(total).min(MAX_NEIGHBOURS);
        let want = (n + 1).min(total);
        let found = self
            .tree
            .query(&q)
            .nearest_n::<SquaredEuclidean<f64>>(NonZero::new(want).unwrap_or(NonZero::<usize>::MIN))
            .execute();
        let mut cand: Vec<(f64, u32)> = found
            .iter()
            .map(|r| (self.key(q, r.item), r.item))
            .collect();
        sort_keys(&mut cand);
        if want > n && n > 0 {
            // Every point outside `found` has a key ≥ its distance² ≥ the farthest found.
            let farthest = found.iter().fold(0.0f64, |m, r| m.max(r.distance));
            let nth = cand[n - 1].0;
            if farthest <= nth * (1.0 + 1e-12) + f64::MIN_POSITIVE {
                cand = self.within_keys(q, nth * (1.0 + 1e-12) + f64::MIN_POSITIVE);
            }
        }
        NeighbourSet::from_unsorted(cand.iter().take(n).map(|c| c.1))
    }

    /// Keys of all points within squared distance `r2` of `q`, ascending.
    fn within_keys(&self, q: [f64; 2], r2: f64) -> Vec<(f64, u32)> {
        let mut cand: Vec<(f64, u32)> = self
            .tree
            .query(&q)
            .within::<SquaredEuclidean<f64>>(r2)
            .execute()
            .into_iter()
            .map(|r| (self.key(q, r.item), r.item))
            .collect();
        sort_keys(&mut cand);
        cand
    }

    /// The pieces of constant `n`-neighbour set along `line` over `[t0, t1]`, in order; the
    /// first starts at t0, every later start is a switch.
    pub fn pieces(&self, line: Line, t0: f64, t1: f64, n: usize, out: &mut Vec<Piece>) {
        let mut walked = Vec::new();
        for k in self.chunks(t0, t1) {
            self.chunk_pieces(line, k, n, &mut walked);
        }
        clip(&walked, t0, t1, out);
    }

    /// The chunks of the line walk that cover `[t0, t1]` (module docs).
    pub fn chunks(&self, t0: f64, t1: f64) -> std::ops::RangeInclusive<i64> {
        // The quotients may round across a chunk's start: the chunks' own starts decide.
        let mut first = (t0 / self.chunk).floor() as i64;
        if self.chunk_start(first) > t0 {
            first = first.saturating_sub(1);
        }
        let mut last = (t1 / self.chunk).floor() as i64;
        if self.chunk_start(last.saturating_add(1)) < t1 {
            last = last.saturating_add(1);
        }
        // A range ending on a chunk's start does not need that chunk.
        if last > first && self.chunk_start(last) >= t1 {
            last -= 1;
        }
        first..=last
    }

    /// Where chunk `k` starts, mm of line parameter.
    pub fn chunk_start(&self, k: i64) -> f64 {
        k as f64 * self.chunk
    }

    /// Appends chunk `k`'s pieces along `line`: the first at the chunk's start with the
    /// kd-tree's set there, then each switch inside it.
    pub fn chunk_pieces(&self, line: Line, k: i64, n: usize, out: &mut Vec<Piece>) {
        let (ta, tb) = (self.chunk_start(k), self.chunk_start(k + 1));
        let mut set = self.nearest(line.at(ta).into(), n);
        out.push(Piece { start: ta, set });
        self.walk_chunk(line, [ta, tb], n, &mut set, out);
    }

    /// Kinetic update of `set` over `[ta, tb]`, recording every switch in `out`.
    fn walk_chunk(
        &self,
        line: Line,
        [ta, tb]: [f64; 2],
        n: usize,
        set: &mut NeighbourSet,
        out: &mut Vec<Piece>,
    ) {
        let tm = 0.5 * (ta + tb);
        let m: [f64; 2] = line.at(tm).into();
        let mut cand = self.candidates(line, [ta, tb], m, set);
        // The candidates hold the n nearest at the start whatever the set carried in (its
        // farthest member bounds their distance): check the carried set against them.
        let start = self.set_among(&cand, line.at(ta).into(), n);
        if start != *set {
            *set = start;
            record(out, ta, start);
            for c in &mut cand {
                c.member = start.indices().contains(&c.index);
            }
        }
        // Times relative to the midpoint, so that their rounding stays at the chunk's scale.
        let mut kinetic = Kinetic::new(cand, self.tie, ta - tm, tb - tm);
        for _ in 0..MAX_EVENTS {
            let Some(tau) = kinetic.next_swap() else {
                return;
            };
            *set = NeighbourSet::from_unsorted(kinetic.members());
            record(out, tm + tau, *set);
        }
    }

    /// The `n` smallest keys from `q` among the candidates.
    fn set_among(&self, cand: &[Candidate], q: [f64; 2], n: usize) -> NeighbourSet {
        let mut keys: Vec<(f64, u32)> = cand
            .iter()
            .map(|c| (self.key(q, c.index), c.index))
            .collect();
        sort_keys(&mut keys);
        NeighbourSet::from_unsorted(keys.iter().take(n).map(|k| k.1))
    }

    /// The points that can be members anywhere on `[ta, tb]`, the current members marked.
    fn candidates(
        &self,
        line: Line,
        [ta, tb]: [f64; 2],
        m: [f64; 2],
        set: &NeighbourSet,
    ) -> Vec<Candidate> {
        let start: [f64; 2] = line.at(ta).into();
        let dn2 = set
            .indices()
            .iter()
            .fold(0.0f64, |a, &i| a.max(self.key(start, i)));
        let reach = dn2.sqrt() + 1.5 * (tb - ta);
        let r2 = (reach * reach + self.tie_span) * (1.0 + 1e-9);
        // Visited into one vector (a chunk of one spacing has a few dozen candidates) rather
        // than collected from the tree's own, which grows one by one.
        let mut cand = Vec::with_capacity(CANDIDATES);
        self.tree
            .query(&m)
            .within::<SquaredEuclidean<f64>>(r2)
            .unsorted()
            .visit(|r| cand.push(self.candidate(r.item, m, line, set)));
        // Members always take part, even if rounding left one out of the radius.
        for &i in set.indices() {
            if !cand.iter().any(|c| c.index == i) {
                cand.push(self.candidate(i, m, line, set));
            }
        }
        cand
    }

    fn candidate(&self, index: u32, m: [f64; 2], line: Line, set: &NeighbourSet) -> Candidate {
        let p = self.points[index as usize];
        let (dx, dy) = (p[0] - m[0], p[1] - m[1]);
        Candidate {
            index,
            r2: dx * dx + dy * dy,
            along: line.c * dx + line.s * dy,
            member: set.indices().contains(&index),
        }
    }
}

/// The pieces of `[t0, t1]` from the pieces of the chunks covering it, in order: the one
/// holding t0 (starting there), then each later one whose set differs from the one before.
pub fn clip<'a>(
    walked: impl IntoIterator<Item = &'a Piece>,
    t0: f64,
    t1: f64,
    out: &mut Vec<Piece>,
) {
    let mut walked = walked.into_iter().peekable();
    let Some(mut holding) = walked.next() else {
        return;
    };
    while let Some(p) = walked.next_if(|p| p.start <= t0) {
        holding = p;
    }
    let mut last = holding.set;
    out.push(Piece {
        start: t0,
        set: last,
    });
    for p in walked {
        if p.start >= t1 {
            break;
        }
        if p.set != last {
            out.push(*p);
            last = p.set;
        }
    }
}

/// Records a switch at `t`: a new piece, or a new set for the last piece when it starts at `t`
/// already (simultaneous swaps, or swaps at the walk's start).
fn record(out: &mut Vec<Piece>, t: f64, set: NeighbourSet) {
    match out.last_mut() {
        Some(last) if last.start >= t => last.set = set,
        _ => out.push(Piece { start: t, set }),
    }
}

/// Sorts (key, index) pairs by key, then index: a total order.
fn sort_keys(v: &mut [(f64, u32)]) {
    v.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The n smallest keys by sorting every point: the reference.
    fn brute(ix: &NeighbourIndex, q: [f64; 2], n: usize) -> NeighbourSet {
        let mut all: Vec<(f64, u32)> = (0..ix.points.len() as u32)
            .map(|i| (ix.key(q, i), i))
            .collect();
        sort_keys(&mut all);
        NeighbourSet::from_unsorted(all.iter().take(n).map(|c| c.1))
    }

    fn grid(h: f64, k: i32) -> Vec<[f64; 2]> {
        (-k..=k)
            .flat_map(|j| (-k..=k).map(move |i| [i as f64 * h, j as f64 * h]))
            .collect()
    }

    /// A jittered grid: generic positions (no ties), deterministic.
    fn jittered(h: f64, k: i32) -> Vec<[f64; 2]> {
        let mut s = 0x2545F4914F6CDD1Du64;
        let mut r = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        grid(h, k)
            .into_iter()
            .map(|p| [p[0] + 0.6 * h * r(), p[1] + 0.6 * h * r()])
            .collect()
    }

    #[test]
    fn nearest_matches_sorting_every_point_also_on_ties() {
        let h = 0.04;
        for pts in [grid(h, 12), jittered(h, 12)] {
            let ix = NeighbourIndex::new(&pts, h).unwrap();
            for n in [4, 8, 10, 16] {
                for k in 0..400 {
                    let a = k as f64 * 0.7123;
                    let r = 0.4 * ((k % 37) as f64 / 37.0);
                    // Every fourth query on a symmetry line of the grid (ties).
                    let q = match k % 4 {
                        0 => [r * a.cos(), 0.0],
                        1 => [r * a.cos(), r * a.cos()],
                        2 => [(k as f64 * 0.01).round() * h * 0.5, r * a.sin()],
                        _ => [r * a.cos(), r * a.sin()],
                    };
                    assert_eq!(ix.nearest(q, n), brute(&ix, q, n), "n {n} q {q:?}");
                }
            }
        }
    }

    /// Dense scan: the set at every sample lies in the piece that covers it, and every change
    /// between two samples is a reported switch between them.
    fn check_pieces(ix: &NeighbourIndex, line: Line, t0: f64, t1: f64, n: usize) {
        let mut pieces = Vec::new();
        ix.pieces(line, t0, t1, n, &mut pieces);
        assert!(pieces.windows(2).all(|w| w[0].start < w[1].start));
        let samples = 1_500;
        let mut k = 0;
        for s in 0..=samples {
            let t = t0 + (t1 - t0) * s as f64 / samples as f64;
            while k + 1 < pieces.len() && pieces[k + 1].start <= t {
                k += 1;
            }
            let at = brute(ix, line.at(t).into(), n);
            // Exactly at a switch either side's set is right.
            let near_switch = pieces
                .iter()
                .any(|p| (p.start - t).abs() < 1e-12 && p.start > t0);
            if !near_switch {
                assert_eq!(pieces[k].set, at, "n {n} t {t} line {line:?}");
            }
        }
    }

    #[test]
    fn pieces_match_a_dense_scan() {
        let h = 0.04;
        for pts in [jittered(h, 8), grid(h, 8)] {
            let ix = NeighbourIndex::new(&pts, h).unwrap();
            for n in [4, 8, 10] {
                // Lines along a grid row and a diagonal (ties all along), and generic ones.
                for (k, theta) in [0.0f64, 0.3, std::f64::consts::FRAC_PI_4, 2.9]
                    .iter()
                    .enumerate()
                {
                    let (s, c) = theta.sin_cos();
                    let line = Line {
                        x0: 0.013 * k as f64 * (k % 2) as f64,
                        y0: 0.0,
                        c,
                        s,
                    };
                    check_pieces(&ix, line, -0.25, 0.2, n);
                }
            }
        }
    }

    #[test]
    fn pieces_far_from_the_line_origin() {
        // A grid around (4.9, 0.5) walked by radial lines from the origin, t ≈ 4.9: the
        // crossing times must not be rounded at the scale of t (a swap and its reverse at the
        // same time would chase each other).
        let h = 0.01;
        let pts: Vec<[f64; 2]> = grid(h, 8)
            .iter()
            .map(|p| [p[0] + 4.9, p[1] + 0.5])
            .collect();
        let ix = NeighbourIndex::new(&pts, h).unwrap();
        for n in [8, 10] {
            for theta in [0.1013f64, 0.0977] {
                let line = Line::radial(theta.cos(), theta.sin());
                check_pieces(&ix, line, 4.87, 4.97, n);
            }
        }
    }

    #[test]
    fn a_range_has_the_switches_of_any_range_holding_it_to_the_bit() {
        // The chunks are anchored at t = 0: the switches inside [0.05, 0.13] are the same
        // numbers asked over it as over [−0.3, 0.4], and its first piece is the longer
        // range's piece that covers 0.05.
        let h = 0.04;
        let ix = NeighbourIndex::new(&jittered(h, 8), h).unwrap();
        for (theta, n) in [(0.3f64, 8), (2.9, 4), (1.2, 10)] {
            let (s, c) = theta.sin_cos();
            let line = Line::radial(c, s);
            let (mut inner, mut outer) = (Vec::new(), Vec::new());
            ix.pieces(line, 0.05, 0.13, n, &mut inner);
            ix.pieces(line, -0.3, 0.4, n, &mut outer);
            let inside: Vec<Piece> = outer
                .iter()
                .filter(|p| p.start > 0.05 && p.start < 0.13)
                .copied()
                .collect();
            assert!(inside.len() >= 3, "{inside:?}");
            assert_eq!(&inner[1..], &inside[..], "theta {theta} n {n}");
            let covering = outer.partition_point(|p| p.start <= 0.05) - 1;
            assert_eq!(inner[0].start, 0.05);
            assert_eq!(inner[0].set, outer[covering].set);
        }
    }

    #[test]
    fn a_pair_that_swaps_is_found_at_its_bisector() {
        // Two points and n = 1: the switch is the perpendicular bisector, x = 0.5.
        let pts = [[0.0, 0.1], [1.0, -0.2], [5.0, 5.0]];
        let ix = NeighbourIndex::new(&pts, 1.0).unwrap();
        let mut pieces = Vec::new();
        ix.pieces(Line::radial(1.0, 0.0), -1.0, 2.0, 1, &mut pieces);
        assert_eq!(pieces.len(), 2, "{pieces:?}");
        // |(x, 0) − (0, 0.1)|² = |(x, 0) − (1, −0.2)|² ⇒ x = (1 + 0.04 − 0.01) / 2.
        assert!((pieces[1].start - 0.515).abs() < 1e-12, "{pieces:?}");
        assert_eq!(pieces[0].set.indices(), &[0]);
        assert_eq!(pieces[1].set.indices(), &[1]);
    }
}
