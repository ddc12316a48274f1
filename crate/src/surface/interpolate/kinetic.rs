//! Kinetic sorting of the neighbour set along a line (used by [`super::neighbours`]): the
//! candidates' keys `|p(τ) − q|² + i·δ` less the common `τ²` are linear in the line parameter
//! τ, `k_q(τ) = |q − m|² − 2τ·u·(q − m) + i_q·δ`, so an outsider q overtakes a member p at
//! the root of `k_q − k_p = g0 + g1·τ`. Each outsider keeps its earliest crossing with any
//! member and that member (its partner); the next event is the outsider with the earliest
//! one. After a swap (p out, q in) only outsiders whose partner was p are recomputed
//! against every member, and every outsider is checked against q: O(n + m) per event
//! instead of O(n·m) (Basch, Guibas & Hershberger, "Data structures for mobile data",
//! J. Algorithms 31 (1999), the kinetic approach to sorting).

/// A candidate point of a stretch of line: offset from the stretch's midpoint m.
#[derive(Debug, Clone, Copy)]
pub struct Candidate {
    /// Index of the data point.
    pub index: u32,
    /// |p − m|², mm².
    pub r2: f64,
    /// u·(p − m), mm.
    pub along: f64,
    /// In the neighbour set.
    pub member: bool,
}

/// The earliest τ in `[tau_now, tau_end]` at which outsider q's key reaches member p's, if
/// any; a pair already out of order by more than its rounding crosses at once.
fn crossing(p: &Candidate, q: &Candidate, tie: f64, tau_now: f64, tau_end: f64) -> Option<f64> {
    let g1 = -2.0 * (q.along - p.along);
    let g0 = q.r2 - p.r2 + (q.index as f64 - p.index as f64) * tie;
    let now = g0 + g1 * tau_now;
    let rounding = 16.0 * f64::EPSILON * (q.r2 + p.r2 + g1.abs() * tau_end.abs());
    let te = if now < -rounding {
        tau_now
    } else if g1 < 0.0 {
        (-g0 / g1).max(tau_now)
    } else {
        return None;
    };
    (te <= tau_end).then_some(te)
}

/// No crossing ahead.
const NONE: (f64, usize) = (f64::INFINITY, usize::MAX);

/// The candidates of one stretch and the next crossing of each outsider.
#[derive(Debug)]
pub struct Kinetic {
    cand: Vec<Candidate>,
    /// The members' positions in `cand`, ascending: a crossing is looked for against these,
    /// not by filtering every candidate.
    members: Vec<usize>,
    /// Per candidate (outsiders only): earliest crossing τ and the member it overtakes.
    best: Vec<(f64, usize)>,
    tie: f64,
    tau: f64,
    tau_end: f64,
}

impl Kinetic {
    /// Starts at `tau` with `cand` (members marked), ending at `tau_end`; `tie` is δ.
    pub fn new(cand: Vec<Candidate>, tie: f64, tau: f64, tau_end: f64) -> Self {
        let members = (0..cand.len()).filter(|&i| cand[i].member).collect();
        let mut k = Self {
            best: vec![NONE; cand.len()],
            members,
            cand,
            tie,
            tau,
            tau_end,
        };
        for o in 0..k.cand.len() {
            if !k.cand[o].member {
                k.best[o] = k.against_members(o);
            }
        }
        k
    }

    /// The earliest crossing of outsider `o` with any member.
    fn against_members(&self, o: usize) -> (f64, usize) {
        let q = &self.cand[o];
        self.members
            .iter()
            .filter_map(|&pi| {
                crossing(&self.cand[pi], q, self.tie, self.tau, self.tau_end).map(|t| (t, pi))
            })
            .fold(NONE, |b, c| if c.0 < b.0 { c } else { b })
    }

    /// Makes the next swap and returns its τ, or `None` when no outsider gets in before the
    /// end of the stretch.
    pub fn next_swap(&mut self) -> Option<f64> {
        let (qi, &(te, pi)) = self
            .best
            .iter()
            .enumerate()
            .filter(|(i, _)| !self.cand[*i].member)
            .min_by(|a, b| a.1.0.total_cmp(&b.1.0))?;
        if pi == usize::MAX || te > self.tau_end {
            return None;
        }
        self.cand[pi].member = false;
        self.cand[qi].member = true;
        self.members.retain(|&m| m != pi);
        let at = self.members.partition_point(|&m| m < qi);
        self.members.insert(at, qi);
        self.best[qi] = NONE;
        self.tau = te;
        self.best[pi] = self.against_members(pi);
        for o in 0..self.cand.len() {
            if self.cand[o].member || o == pi {
                continue;
            }
            if self.best[o].1 == pi {
                self.best[o] = self.against_members(o);
            } else if let Some(t) = crossing(
                &self.cand[qi],
                &self.cand[o],
                self.tie,
                self.tau,
                self.tau_end,
            ) && t < self.best[o].0
            {
                self.best[o] = (t, qi);
            }
        }
        Some(te)
    }

    /// The members' point indices.
    pub fn members(&self) -> impl Iterator<Item = u32> + '_ {
        self.cand.iter().filter(|c| c.member).map(|c| c.index)
    }
}
