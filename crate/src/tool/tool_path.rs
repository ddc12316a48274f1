//! The tool path of a job: its surface as the spindle sees it, its spiral, and the nose
//! compensator that turns each spiral point into a commanded point ([`PathPoint`]). It is what
//! every analysis reads ([`crate::analysis`], [`crate::dynamics`]) and what the planner
//! ([`crate::plan`]) streams into the writers. The path is never stored: [`ToolPath::points`]
//! computes it one point at a time, [`ToolPath::for_each_point`] in batches on every core,
//! [`ToolPath::for_each_pair`] with a function of each point and its predecessor computed beside
//! it (an analysis's per-segment work), [`ToolPath::for_each_pair_in`] the same over a slice of
//! the indices (the page's workers each plan one, [`crate::plan::PlanSlice`]),
//! [`ToolPath::for_each_batch_in`] under both, a function of a whole batch (with the points
//! before it as context) computed on the worker (the planner's NC text and figures). Each point's
//! contact search starts from its predecessors' contacts within runs of [`WARM_RUN`] points
//! aligned on the index (the warm start of [`crate::tool::one_way`]), so a point is the same
//! bits however the path is computed.

use super::one_way::ContactTrail;
use super::reach::{self, Reach};
use super::{Concavity, NoseCompensator};
use crate::field::FieldError;
use crate::job::{Compensation, Job, Sampling, StrategySpec};
use crate::parallel::{fill_chunks, fill_each, pipeline_on, workers};
use crate::path::{PathError, PathPoint, Spiral, SpiralPoint};
use crate::progress::{PROGRESS_EVERY, Progress, ProgressFn, Stage, ignore};
use crate::surface::{Surface, UndefinedError};

/// Points compensated per batch before they are handed on: bounds the memory of a run.
const BATCH: usize = 16_384;

/// Points per batch, at most, where the surface keeps work along its lines
/// ([`Surface::keeps_lines`]) and several workers share the walk: each worker's kept lines
/// start afresh with every batch it takes (the whole nose arc's stretch of each line walked
/// again), so its batches are long. 23 MB a batch of path points, beside the line windows.
const LONG_BATCH: usize = 16 * BATCH;

/// The points of a batch for a walk of `total` points on `workers` workers (`long`: the
/// surface keeps its lines): at most [`BATCH`] ([`LONG_BATCH`]), a multiple of [`WARM_RUN`],
/// and as many batches as a multiple of the workers, all of a size but the last: the pipeline
/// deals batches to the workers in turn, and one batch more than the others get would leave
/// the rest idle while one computes it (a tenth of the time of a path of 11 batches on two
/// cores). How a path is cut into batches never changes a point ([`WARM_RUN`]).
fn even_batch(total: u64, workers: usize, long: bool) -> u64 {
    let most = if long && workers > 1 {
        LONG_BATCH
    } else {
        BATCH
    };
    batch_within(total, most, workers)
}

/// The points of a batch of at most `most`, a multiple of [`WARM_RUN`], for `total` points cut
/// into as many batches as a multiple of `workers`, all of a size but the last.
fn batch_within(total: u64, most: usize, workers: usize) -> u64 {
    let most = most as u64;
    let batches = total.div_ceil(most).next_multiple_of(workers as u64).max(1);
    // At least one run: `total` is an estimate on some spirals, and may be short.
    let even = total.div_ceil(batches).max(1).next_multiple_of(WARM_RUN);
    even.min(most)
}

/// Points per batch, at most, where a walk goes line by line on several workers
/// ([`ToolPath::line_order`]): one batch at a time is shared out over the workers by its
/// lines, so a line's chunks are walked once a batch (where each worker took batches of its
/// own, the arcs about the batches' common radius walked theirs twice: 18 % of the scattered
/// example's walks). About 100 MB of path points and results, one batch in flight.
const LINE_BATCH: usize = 2 * LONG_BATCH;

/// The points of a batch for a walk of `total` points computed line by line on several
/// workers: at most [`LINE_BATCH`], a multiple of [`WARM_RUN`], the batches of a size.
fn line_batch(total: u64) -> u64 {
    batch_within(total, LINE_BATCH, 1)
}

/// The path is compensated in runs of this many points, aligned on the index: the first point
/// of a run starts its contact search cold, every other one from its predecessors' contacts
/// ([`NoseCompensator::compensate_from`], [`ContactTrail`]). A point's result thus depends on its
/// index alone, however the path is cut into batches, slices or threads, as long as each piece
/// starts on a run boundary or recomputes the run it starts in. A divisor of the batch size.
pub const WARM_RUN: u64 = 64;

/// What a walk over a slice of the path saw ([`ToolPath::for_each_pair_in`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Walked {
    /// Points handed on.
    pub points: u64,
    /// The path ends within the slice: no point lies past it.
    pub ended: bool,
}

/// The spiral of a strategy on `surface`, by the builder of its sampling: [`Spiral::new`] for
/// constant angle and constant arc, [`crate::path::hcaa::spiral`] for `hcaa` and `adaptive`
/// (which reads the one-way compensated tip height of `nose`),
/// [`crate::path::space_spiral::spiral`] for `space_spiral`. Field errors are named from
/// `strategy`.
pub fn spiral(
    outer_radius_mm: f64,
    strategy: &StrategySpec,
    surface: &dyn Surface,
    nose: &NoseCompensator,
    progress: &mut ProgressFn,
) -> Result<Spiral, PathError> {
    let st = strategy;
    let within = |e: FieldError| PathError::from(e.within("strategy"));
    match st.sampling {
        Sampling::ConstantAngle { .. } | Sampling::ConstantArc { .. } => Spiral::new(
            outer_radius_mm,
            st.feed_mm_per_rev,
            &st.sampling,
            st.direction,
            st.start_angle_deg,
        )
        .map_err(within),
        Sampling::Hcaa { .. } | Sampling::Adaptive { .. } => {
            let concavity = nose.concavity(surface);
            let tip = |rho: f64, theta: f64| nose.tip_height(surface, concavity, rho, theta);
            crate::path::hcaa::spiral(outer_radius_mm, st, surface, &tip, progress)
        }
        Sampling::SpaceSpiral {
            points_per_rev,
            base_spans,
        } => crate::path::space_spiral::spiral(
            outer_radius_mm,
            st,
            surface,
            points_per_rev,
            base_spans,
        )
        .map_err(within),
    }
}

/// Three consecutive points of the path somewhere along it ([`ToolPath::probe`]), and how many
/// points the path has per mm of radius there.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Probe {
    /// The points, each one step further along the path than the one before.
    pub points: [PathPoint; 3],
    /// Points per mm of radius at that place: 1 / (the radial advance of one step).
    pub per_mm: f64,
}

/// A checked job's tool path, ready to stream.
#[derive(Debug)]
pub struct ToolPath {
    job: Job,
    surface: Box<dyn Surface>,
    spiral: Spiral,
    /// The spiral's [`Spiral::turn_directions`], read at every point.
    directions: Vec<(f64, f64)>,
    nose: NoseCompensator,
    /// The nose's concavity bound on the surface ([`NoseCompensator::concavity`]).
    concavity: Option<Concavity>,
}

impl ToolPath {
    /// Validates the job and builds its surface, compensator and spiral.
    pub fn new(job: &Job) -> Result<Self, PathError> {
        Self::with_progress(job, &mut ignore)
    }

    /// [`ToolPath::new`], with the progress of the sampling's estimate (HCAA and adaptive:
    /// [`Stage::Bands`]), which may cancel.
    pub fn with_progress(job: &Job, progress: &mut ProgressFn) -> Result<Self, PathError> {
        job.validate()?;
        let surface = job.build_surface()?;
        // The material ends at the part edge, wherever the spiral starts.
        let nose = NoseCompensator::new(
            &job.tool,
            surface.feature_length_mm(),
            job.material_radius_mm(),
        )
        .map_err(|e| e.within("tool"))?;
        if nose.waviness().is_some() && job.strategy.compensation == Compensation::TwoWay {
            return Err(FieldError::new(
                "tool.waviness",
                "set",
                "is used by the one-way compensation only: set strategy.compensation to one_way, \
                 or remove tool.waviness",
            )
            .into());
        }
        let spiral = spiral(
            job.outer_radius_mm(),
            &job.strategy,
            surface.as_ref(),
            &nose,
            progress,
        )?;
        let concavity = nose.concavity(surface.as_ref());
        Ok(Self {
            job: job.clone(),
            surface,
            directions: spiral.turn_directions(),
            spiral,
            nose,
            concavity,
        })
    }

    /// The job.
    pub fn job(&self) -> &Job {
        &self.job
    }

    /// The surface.
    pub fn surface(&self) -> &dyn Surface {
        self.surface.as_ref()
    }

    /// The spiral.
    pub fn spiral(&self) -> &Spiral {
        &self.spiral
    }

    /// The compensator.
    pub fn nose(&self) -> &NoseCompensator {
        &self.nose
    }

    /// The nose's concavity bound on the surface, the certificate of the concave shortcut
    /// ([`NoseCompensator::concavity`]), computed once.
    pub fn concavity(&self) -> Option<Concavity> {
        self.concavity
    }

    /// The one-way tip height over (ρ, θ) ([`NoseCompensator::tip_height`]).
    pub fn tip_height(&self, rho: f64, theta: f64) -> Result<f64, UndefinedError> {
        self.nose
            .tip_height(self.surface(), self.concavity, rho, theta)
    }

    /// The path's first point (a slice's display copy counts revolutions from its angle).
    pub fn first_point(&self) -> Result<PathPoint, UndefinedError> {
        self.points().next().unwrap_or(Ok(PathPoint::default()))
    }

    /// The compensated path, streamed.
    pub fn points(&self) -> impl Iterator<Item = Result<PathPoint, UndefinedError>> + '_ {
        let mut warm = None;
        self.spiral.points().enumerate().map(move |(i, sp)| {
            let p = self.warm_point(i as u64, sp, &mut warm)?.0;
            Ok(p)
        })
    }

    /// The order in which to compute a batch's points (indices into `input`) where the surface
    /// keeps the lines it is asked about ([`Surface::keeps_lines`]) and each point's contact is
    /// found without a warm start (one-way, no concavity certificate): on a constant-angle
    /// spiral, line by line (the points of one step of the turn, turn after turn), so that each
    /// line's walk is made once and read while it is in the cache, rather than the lines of a
    /// whole turn taken in turn. `None` (the path's order) otherwise. Each point's contact does
    /// not depend on the order (the kept walks and systems give the same bits as fresh ones).
    fn line_order(&self, input: &[(u64, SpiralPoint, bool)]) -> Option<Vec<usize>> {
        if !self.walks_line_by_line() {
            return None;
        }
        let mut keyed = Vec::with_capacity(input.len());
        for (k, (_, sp, _)) in input.iter().enumerate() {
            keyed.push((self.spiral.turn_step(sp.theta)?, k));
        }
        keyed.sort_unstable();
        Some(keyed.into_iter().map(|(_, k)| k).collect())
    }

    /// Whether a walk's batches are computed line by line ([`Self::line_order`]): the surface
    /// keeps its lines, no contact is searched from a warm start (one-way, no concavity
    /// certificate), and the spiral is constant-angle (a point's line depends on its step in
    /// the turn alone).
    fn walks_line_by_line(&self) -> bool {
        let one_way = self.job.strategy.compensation != Compensation::TwoWay;
        self.surface.keeps_lines()
            && one_way
            && self.concavity.is_none()
            && self.spiral.turn_points().is_some()
    }

    /// Whether a walk computes one batch at a time, shared out over the cores (line by line on
    /// several, [`LINE_BATCH`]), rather than each worker a batch of its own: then the work
    /// beside the points ([`Self::for_each_pair_in`]'s pairs) is shared out too.
    fn shares_batches(&self) -> bool {
        self.walks_line_by_line() && workers() > 1
    }

    /// The points of `input` computed in `order` ([`Self::line_order`]) into `batch`, in the
    /// input's order; the first point that fails in the input's order gives the error.
    fn points_in_order(
        &self,
        input: &[(u64, SpiralPoint, bool)],
        order: &[usize],
        batch: &mut Vec<Batched>,
    ) -> Result<(), UndefinedError> {
        // Each worker takes a contiguous share of the order: whole lines, but where a share
        // ends inside one.
        let mut computed = vec![(0, Ok((PathPoint::default(), false))); order.len()];
        fill_chunks(&mut computed, |first, out| {
            for (slot, &k) in out.iter_mut().zip(&order[first..]) {
                *slot = (k, self.path_point(input[k].0, input[k].1, &mut None));
            }
            Ok::<(), UndefinedError>(())
        })?;
        computed.sort_unstable_by_key(|(k, _)| *k);
        for ((_, result), &(_, _, handed_on)) in computed.into_iter().zip(input) {
            let (point, folds) = result?;
            batch.push(Batched {
                point,
                folds,
                handed_on,
            });
        }
        Ok(())
    }

    /// [`Self::path_point`] in a walk along the path: `warm` holds the contacts of the points
    /// before and the start they give ([`ContactTrail`]), dropped at the start of each
    /// [`WARM_RUN`], and takes this one's.
    fn warm_point(
        &self,
        index: u64,
        sp: SpiralPoint,
        warm: &mut Option<ContactTrail>,
    ) -> Result<(PathPoint, bool), UndefinedError> {
        if index.is_multiple_of(WARM_RUN) {
            *warm = None;
        }
        self.path_point(index, sp, warm)
    }

    /// The compensated path point of the `index`-th spiral point, and whether the two-way
    /// offset folds there (a loop; always false one-way); one-way, the contact search starts
    /// from `warm` where it can ([`NoseCompensator::compensate_from`]), which then takes this
    /// point's contact.
    /// Two-way, `rho` and `theta` are the nose centre's X and C
    /// ([`NoseCompensator::compensate_two_way`]).
    fn path_point(
        &self,
        index: u64,
        sp: SpiralPoint,
        warm: &mut Option<ContactTrail>,
    ) -> Result<(PathPoint, bool), UndefinedError> {
        if self.job.strategy.compensation == Compensation::TwoWay {
            // The angle's own sine: the C offset of a centre across the axis (±π) follows its
            // sign, as the closed forms of tests/tests/two_way.rs do.
            let (s, c) = sp.theta.sin_cos();
            let t = self
                .nose
                .compensate_two_way(self.surface.as_ref(), sp.rho, c, s)?;
            return Ok((
                PathPoint {
                    index,
                    rho: t.x,
                    theta: sp.theta + t.c_offset,
                    z: t.z_tip,
                    contact: t.contact,
                    contact_angle: t.angle,
                    at_arc_end: t.at_arc_end,
                },
                t.folds,
            ));
        }
        // One-way the radial section is all that matters: the turn's direction, the same bits
        // for the points of one angle on every turn ([`Spiral::sin_cos`]).
        let (s, c) = self.spiral.sin_cos_from(&self.directions, sp.theta);
        let contact = self.nose.compensate_from(
            self.surface.as_ref(),
            self.concavity,
            sp.rho,
            c,
            s,
            warm.map(|t| t.start),
        )?;
        match warm {
            Some(trail) => trail.push(&contact),
            None => *warm = Some(ContactTrail::new(&contact)),
        }
        Ok((
            PathPoint {
                index,
                rho: sp.rho,
                theta: sp.theta,
                z: contact.z_tip,
                contact: [contact.rho * c, contact.rho * s, contact.z],
                contact_angle: contact.angle,
                at_arc_end: contact.at_arc_end,
            },
            false,
        ))
    }

    /// Up to `n` runs of three consecutive points spread evenly in radius from the start of the
    /// path to the centre (a run with fewer than three points left before the centre is left
    /// out), computed without walking the path: what an estimate of the job's cost reads (and
    /// where a surface that is undefined or not finite shows itself before any output). Their
    /// indices are estimates, exact for constant-angle sampling.
    pub fn probe(&self, n: usize) -> Result<Vec<Probe>, UndefinedError> {
        Ok(self.probe_runs(n, None)?.0)
    }

    /// [`Self::probe`], and the time by `clock` that the runs' second and third points took:
    /// each is started from the contact before it, as the walk computes every point but a
    /// run's first ([`WARM_RUN`]), so this is the time of the points of a walk, summed over
    /// the runs, which are shared out over the cores as the walk's points are. Each run's
    /// first point, searched without a start, is computed before its clock starts (a search
    /// of the whole arc costs more than a step from the last contact; the first points also
    /// meet every cache's cold start, so one pass is timed). Where the walk goes line by line
    /// (scattered data on a constant-angle spiral), each timed point's line is first walked
    /// by the point one turn outward, untimed, as in the walk.
    pub fn probe_timed(
        &self,
        n: usize,
        clock: &(dyn Fn() -> f64 + Sync),
    ) -> Result<(Vec<Probe>, f64), UndefinedError> {
        self.probe_runs(n, Some(clock))
    }

    /// [`Self::probe`], timed by `clock` where one is given ([`Self::probe_timed`]; untimed,
    /// the time is 0 and no line is walked beforehand).
    fn probe_runs(
        &self,
        n: usize,
        clock: Option<&(dyn Fn() -> f64 + Sync)>,
    ) -> Result<(Vec<Probe>, f64), UndefinedError> {
        let now = || clock.map_or(0.0, |c| c());
        let r0 = self.spiral.start_radius_mm();
        let total = self.spiral.point_count_estimate();
        let runs: Vec<[SpiralPoint; 3]> = (0..n)
            .filter_map(|i| {
                let rho = r0 * (n - i) as f64 / n as f64;
                let mut points = self.spiral.points_from(rho);
                // Near the centre a short path may have fewer than three points left.
                Some([points.next()?, points.next()?, points.next()?])
            })
            .collect();
        let index = |a: &SpiralPoint| (total * (1.0 - a.rho / r0)).max(0.0) as u64;
        let line_by_line = clock.is_some() && self.walks_line_by_line();
        let mut timed = vec![(Probe::default(), 0.0); runs.len()];
        fill_each(&mut timed, |k| {
            let [a, b, c] = runs[k];
            let i = index(&a);
            let mut warm = None;
            let first = self.path_point(i, a, &mut warm)?.0;
            if line_by_line {
                // Such a walk finds each point's line walked as far as the point one turn
                // outward, computed just before it: so do the timed points, whose lines are
                // walked there first, untimed (a point beyond the part is left out).
                for p in [b, c] {
                    let outward = SpiralPoint {
                        rho: p.rho + self.spiral.feed_mm(),
                        theta: p.theta - std::f64::consts::TAU,
                    };
                    let _ = self.path_point(0, outward, &mut None);
                }
            }
            let advance = a.rho - b.rho;
            let start = now();
            let points = [
                first,
                self.path_point(i + 1, b, &mut warm)?.0,
                self.path_point(i + 2, c, &mut warm)?.0,
            ];
            let elapsed = now() - start;
            let per_mm = if advance > 0.0 { 1.0 / advance } else { 0.0 };
            Ok::<_, UndefinedError>((Probe { points, per_mm }, elapsed))
        })?;
        let elapsed = timed.iter().map(|t| t.1).sum();
        Ok((timed.into_iter().map(|t| t.0).collect(), elapsed))
    }

    /// Zones where the nose cannot reach the surface (see [`crate::tool::reach`]); `progress`
    /// as [`reach::concave_zones`] calls it.
    pub fn concave_zones(&self, progress: &mut ProgressFn) -> Result<Reach, PathError> {
        reach::concave_zones(
            self.surface.as_ref(),
            &self.nose,
            self.spiral.start_radius_mm(),
            progress,
        )
    }

    /// Computes every point in order, compensating batches of 16 384 points on every core
    /// ([`crate::parallel::pipeline`]: the next batches are computed while `visit` takes this
    /// one; where the walk goes line by line, batches of up to 524 288 points, one at a time,
    /// each shared out over the cores by its lines), and hands each to `visit` with whether
    /// the two-way offset folds there; `progress` is called every [`PROGRESS_EVERY`] points
    /// and at the end, as `stage` (`Break` cancels). Returns the count.
    pub fn for_each_point<E: From<PathError> + Send>(
        &self,
        stage: Stage,
        progress: &mut ProgressFn,
        visit: &mut dyn FnMut(&PathPoint, bool) -> Result<(), E>,
    ) -> Result<u64, E> {
        self.for_each_pair(stage, progress, |_, _| Ok(()), &mut |p, folds, _| {
            visit(p, folds)
        })
    }

    /// [`Self::for_each_point`] with more work on the workers: `pair(previous, point)` (the
    /// previous point `None` for the first) is computed beside each point's compensation, in
    /// parallel, and its result handed to `visit` with the point, in order. Each batch also
    /// compensates the last point of the batch before it, so its first point has its
    /// predecessor: every point and every result is the same whatever the number of workers.
    pub fn for_each_pair<T: Send, E: From<PathError> + Send>(
        &self,
        stage: Stage,
        progress: &mut ProgressFn,
        pair: impl Fn(Option<&PathPoint>, &PathPoint) -> Result<T, E> + Sync,
        visit: &mut dyn FnMut(&PathPoint, bool, &T) -> Result<(), E>,
    ) -> Result<u64, E> {
        let walked = self.for_each_pair_in(0..u64::MAX, stage, progress, pair, visit)?;
        Ok(walked.points)
    }

    /// [`Self::for_each_pair`] over the points whose index lies in `range` only: a slice of the
    /// path, computed exactly as in the whole walk (the run the slice starts in is compensated
    /// again from its start, not handed on), so that slices planned apart (the page's workers)
    /// join into the whole path bit for bit. `range.end` may lie past the path's end.
    pub fn for_each_pair_in<T: Send, E: From<PathError> + Send>(
        &self,
        range: std::ops::Range<u64>,
        stage: Stage,
        progress: &mut ProgressFn,
        pair: impl Fn(Option<&PathPoint>, &PathPoint) -> Result<T, E> + Sync,
        visit: &mut dyn FnMut(&PathPoint, bool, &T) -> Result<(), E>,
    ) -> Result<Walked, E> {
        self.for_each_batch_in(
            range,
            stage,
            progress,
            |batch, pairs: &mut Vec<T>| {
                pairs.clear();
                let handed_on = (0..batch.len()).filter(|&k| batch[k].handed_on);
                let of = |k: usize| {
                    let previous = k.checked_sub(1).map(|j| &batch[j].point);
                    pair(previous, &batch[k].point)
                };
                if !self.shares_batches() {
                    for k in handed_on {
                        pairs.push(of(k)?);
                    }
                    return Ok(());
                }
                // One batch at a time: its pairs shared out over the cores as its points were.
                let handed_on: Vec<usize> = handed_on.collect();
                let mut computed: Vec<Option<T>> = handed_on.iter().map(|_| None).collect();
                fill_chunks(&mut computed, |first, out| {
                    for (slot, &k) in out.iter_mut().zip(&handed_on[first..]) {
                        *slot = Some(of(k)?);
                    }
                    Ok::<(), E>(())
                })?;
                pairs.extend(computed.into_iter().flatten());
                Ok(())
            },
            &mut |batch, pairs| {
                let handed_on = batch.iter().filter(|b| b.handed_on);
                for (b, t) in handed_on.zip(pairs) {
                    visit(&b.point, b.folds, t)?;
                }
                Ok(())
            },
        )
    }

    /// The walk under the others, a batch at a time: the points of `range` computed in batches
    /// on every core, each batch also computing the points before its first one back to the
    /// start of the run that holds the second point before it (its context: at least the two
    /// points before the first one handed on, where there are any, computed as in the whole
    /// walk). `work(batch, out)` runs on a worker beside the compensation, `visit(batch, out)`
    /// on the calling thread in order; [`Batched::handed_on`] marks the points of `range`.
    /// `progress` is called about every [`PROGRESS_EVERY`] points handed on and at the end, as
    /// `stage` (`Break` cancels).
    pub fn for_each_batch_in<B: Default + Send, E: From<PathError> + Send>(
        &self,
        range: std::ops::Range<u64>,
        stage: Stage,
        progress: &mut ProgressFn,
        work: impl Fn(&[Batched], &mut B) -> Result<(), E> + Sync,
        visit: &mut BatchVisit<'_, B, E>,
    ) -> Result<Walked, E> {
        let run_of = |index: u64| index.saturating_sub(2) / WARM_RUN * WARM_RUN;
        let begin = run_of(range.start);
        let total = self
            .spiral
            .point_count_hint()
            .min(range.end)
            .saturating_sub(range.start);
        // Line by line on several cores, one batch at a time is shared out over them by its
        // lines ([`Self::points_in_order`]); else each worker computes batches of its own.
        let w = workers();
        let (batch, pipeline_workers) = match self.shares_batches() {
            true => (line_batch(total), 1),
            false => (even_batch(total, w, self.surface.keeps_lines()), w),
        };
        let mut done = 0u64;
        let mut spiral = self.spiral.points();
        // A batch's points with their indices and whether they are handed on: in every batch
        // but the first, the first points are the context carried from the batch before,
        // computed again and not handed on twice; in the first, those before the range.
        let mut next = begin;
        let mut ended = match usize::try_from(begin) {
            Ok(0) => false,
            Ok(n) => spiral.nth(n - 1).is_none(),
            Err(_) => true,
        };
        let mut carried: Vec<(u64, SpiralPoint, bool)> = Vec::new();
        pipeline_on::<(u64, SpiralPoint, bool), (Vec<Batched>, B), E>(
            pipeline_workers,
            |input: &mut Vec<(u64, SpiralPoint, bool)>| {
                input.clear();
                let room = batch.min(range.end.saturating_sub(next)) as usize;
                if ended || room == 0 {
                    // Whether the path goes on past the slice.
                    ended = ended || spiral.clone().next().is_none();
                    return;
                }
                input.append(&mut carried);
                let start = input.len();
                input.extend(spiral.by_ref().take(room).map(|sp| {
                    next += 1;
                    (next - 1, sp, next > range.start)
                }));
                ended = input.len() - start < room;
                if input.len() == start {
                    input.clear();
                    return;
                }
                let run = run_of(next);
                carried.extend(
                    input
                        .iter()
                        .filter(|&&(index, _, _)| index >= run)
                        .map(|&(index, sp, _)| (index, sp, false)),
                );
            },
            |_, input, slot: &mut Vec<(Vec<Batched>, B)>| {
                // One output a batch, its buffers reused from batch to batch.
                if slot.is_empty() {
                    slot.push(Default::default());
                }
                let (batch, out) = &mut slot[0];
                batch.clear();
                if let Some(order) = self.line_order(input) {
                    self.points_in_order(input, &order, batch)
                        .map_err(|e| E::from(e.into()))?;
                    return work(batch, out);
                }
                let mut warm = None;
                for &(index, sp, handed_on) in input {
                    let (point, folds) = self
                        .warm_point(index, sp, &mut warm)
                        .map_err(|e| E::from(e.into()))?;
                    batch.push(Batched {
                        point,
                        folds,
                        handed_on,
                    });
                }
                work(batch, out)
            },
            |slot| {
                let (batch, out) = &slot[0];
                visit(batch, out)?;
                let before = done;
                // The context comes first in a batch, the points handed on after it.
                done += (batch.len() - batch.partition_point(|b| !b.handed_on)) as u64;
                if done / PROGRESS_EVERY > before / PROGRESS_EVERY
                    && progress(Progress { stage, done, total }).is_break()
                {
                    return Err(PathError::Cancelled.into());
                }
                Ok(())
            },
        )?;
        let _ = progress(Progress {
            stage,
            done,
            total: done,
        });
        Ok(Walked {
            points: done,
            ended,
        })
    }
}

/// What [`ToolPath::for_each_batch_in`] calls on the calling thread with each batch, in order.
pub type BatchVisit<'v, B, E> = dyn FnMut(&[Batched], &B) -> Result<(), E> + 'v;

/// A point of a batch of [`ToolPath::for_each_batch_in`].
#[derive(Debug, Clone, Copy)]
pub struct Batched {
    /// The point.
    pub point: PathPoint,
    /// The two-way offset folds there.
    pub folds: bool,
    /// It lies in the walk's range and is handed on here (not context).
    pub handed_on: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_batches_are_even_and_bounded() {
        // The scattered example's 180 001 points: one batch (a multiple of the runs).
        assert_eq!(line_batch(180_001), 180_032);
        for total in [
            0, 1, 63, 64, 180_001, 524_288, 524_289, 4_000_001, 28_400_001,
        ] {
            let b = line_batch(total);
            assert!(b >= WARM_RUN && b.is_multiple_of(WARM_RUN) && b <= LINE_BATCH as u64);
            // As few batches as the bound allows, the last at most a run's rounding short.
            let batches = total.div_ceil(b);
            assert_eq!(batches, total.div_ceil(LINE_BATCH as u64));
            assert!(
                batches * b - total < WARM_RUN * batches.max(1),
                "{total}: {b}"
            );
        }
    }

    #[test]
    fn batches_are_even_across_the_workers_and_bounded() {
        // The scattered example's 180 001 points on two workers: 12 batches of 15 040 (the
        // runs' multiple of ⌈180 001 / 12⌉), or two of 90 048 where the surface keeps lines
        // (and the walk is not line by line, [`line_batch`]); on one worker, 16 384 either way.
        assert_eq!(even_batch(180_001, 2, false), 15_040);
        assert_eq!(even_batch(180_001, 2, true), 90_048);
        assert_eq!(even_batch(180_001, 1, true), BATCH as u64);
        for total in [0, 1, 63, 64, 1_000, 180_001, 4_000_001, 28_400_001] {
            for workers in [1, 2, 3, 16] {
                for long in [false, true] {
                    let b = even_batch(total, workers, long);
                    let most = if long && workers > 1 {
                        LONG_BATCH
                    } else {
                        BATCH
                    };
                    assert!(b >= WARM_RUN && b.is_multiple_of(WARM_RUN) && b <= most as u64);
                    // Dealt in turn, the workers' shares differ by the runs' rounding only.
                    let mut share = vec![0u64; workers];
                    let (mut k, mut left) = (0, total);
                    while left > 0 {
                        share[k % workers] += b.min(left);
                        left -= b.min(left);
                        k += 1;
                    }
                    let spread = share.iter().max().unwrap() - share.iter().min().unwrap();
                    let batches = total.div_ceil(b);
                    assert!(
                        spread <= WARM_RUN * batches || total < WARM_RUN * workers as u64 * 4,
                        "{total} points, {workers} workers, long {long}: batch {b}, {share:?}"
                    );
                }
            }
        }
    }
}
