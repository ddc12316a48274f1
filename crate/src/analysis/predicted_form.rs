//! Predicted form: the machined surface simulated as the lower envelope of the tool nose swept
//! along the path, compared with the design as a height map, giving the cusp height along the
//! feed, the PV and RMS form error and a map.
//!
//! **Model.** The cutting edge is the nose arc of radius r in the radial plane through the
//! spindle axis at the current C angle, limited to ±β/2 about the tool axis (reach
//! `w = r·sin(β/2)` either side of the nose centre; [`crate::tool`]). Between NC points the
//! controller moves C, X and Z linearly, so the edge passes through the half-plane at polar angle
//! φ once per revolution, at the point of the segment (k, k+1) whose C is φ (mod 2π): there
//! `t = (φ − θ_k)/(θ_{k+1} − θ_k)`, the nose centre sits at `ρ* = ρ_k + t·(ρ_{k+1} − ρ_k)`,
//! `c* = z_k + t·(z_{k+1} − z_k) + r` (z the commanded tip). A point of the part at (ρ, φ) is
//! cut only while the edge lies in its plane, so the machined height there is the lowest of those
//! passes' arcs, `H(ρ) = min_p c*_p − √(r² − (ρ − ρ*_p)²)` over the passes with
//! `|ρ − ρ*_p| ≤ w` (the passes through the opposite half-plane φ + π count too, at −ρ*: near the
//! axis the arc reaches across it). Rake and clearance faces are not modelled; the edge alone
//! shapes the surface. A measured edge (`tool.waviness`, [`crate::tool::waviness`]) replaces the
//! circle's depth `√(r² − d²)` by its own at the offset d, the centre lies `R(0)` above the
//! commanded tip, and w is the edge's own reach; the edge must be convex (checked), so that its
//! translates still cross at most once, and two pieces switch where their difference, monotone,
//! changes sign (found by bisection instead of the circles' closed form).
//!
//! **Grid.** `angles` (even) half-planes φ_j = j·2π/angles, radial samples ρ_i = i·h with
//! `h ≤ f/4` (default f/16, f the feed per revolution). The form error is
//! `e = H(ρ_i) − sag(ρ_i cos φ_j, ρ_i sin φ_j)` against the design surface; positive = material
//! left, negative = an overcut (a gouge).
//!
//! **Envelope, streamed.** The path is read once, in order. On each half-plane the passes arrive
//! with decreasing ρ*; the arcs are translates of one convex function, so any two cross at most
//! once (their difference is monotone) and the lower envelope is a sequence of pieces in the
//! order of ρ*, kept as a stack and updated in amortised O(1) per pass as in the monotone convex
//! hull trick. The switch between two arcs is the lower intersection of their circles, exact. A
//! sample ρ is final once `ρ > ρ*_latest + w` (no later pass can reach it) and `ρ > w` (near the
//! axis the opposite half-plane's last passes still count); it is then evaluated on its one
//! piece and handed to the statistics, and pieces above the finished samples are dropped. So the
//! memory is about `angles × 3w/f` pieces (2w/f in flight, w/f kept near the axis), whatever the
//! path length, plus the map. At the end of the path the opposite half-plane's arcs are merged in
//! (at −ρ*) and the rest is evaluated. Time: one sag evaluation per sample and per cusp apex.
//!
//! **Statistics band.** On each half-plane the samples outside the first pass's ρ* (the
//! outermost band, 0 to one feed wide, f/2 on average, where only the first arc's outer flank
//! passes) and beyond the part radius are not machined surface: they are left out of everything.
//! PV, RMS and mean cover the annulus `f ≤ ρ ≤ ρ*_first(φ)`; the centre disc `ρ < f`, where the
//! spiral's last revolution leaves one wider cusp (the passes either side of the axis are
//! 0.5 f to 1.5 f apart), is reported on its own as `centre_pv_um`; `max_overcut_um` and the map
//! cover both. The RMS is area-weighted (weight ρ_i, h/8 for the centre sample: the polar cell's
//! area) and taken about the area-weighted mean (`mean_um`, the piston: material left on
//! average); the RMS about zero is `√(rms² + mean²)`. Extremes include the exact cusp apexes
//! and the refined valleys as well as the samples.
//!
//! **Cusp height.** For two adjacent pieces of the envelope (passes p and p+1 on one half-plane,
//! both pieces wholly inside the annulus), the form error at their apex (the switch point,
//! exact) minus the mean of the two valleys either side, each valley the smallest error on its
//! piece, refined by the parabola through the lowest sample and its two neighbours (error of
//! order `e‴·h³`). `cusp_height_um` is the median over all such cusps (to 1e-5 relative, from a
//! histogram with 2¹⁶ bins per octave), `cusp_height_max_um` the largest. On a flat it is
//! `r − √(r² − f²/4) ≈ f²/(8r)`; on a sphere of radius R (R > 0 concave) it is
//! `f²/(8r)·R/(R − r)/cos³φ` to first order, φ the slope angle: the contacts lie `f·R/(R − r)`
//! apart.
//!
//! **Map.** Each cell of a square [`Raster`] over the part takes the mean error, µm, over the
//! samples of its nearest half-plane within `max(cell, h)/2` of its radius; NaN where no machined
//! sample falls.

use crate::field::FieldError;
use crate::path::PathError;
use crate::path::PathPoint;
use crate::progress::PROGRESS_EVERY;
use crate::raster::Raster;
use crate::surface::{Surface, UndefinedError};
use crate::tool::{ToolPath, Waviness};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, VecDeque};
use std::f64::consts::TAU;

/// Default number of half-planes.
pub const DEFAULT_ANGLES: usize = 360;
/// Most half-planes accepted (0.01°).
pub const MAX_ANGLES: usize = 36_000;
/// Default radial samples per feed.
pub const DEFAULT_SAMPLES_PER_FEED: f64 = 16.0;
/// Fewest radial samples per feed accepted: the valley refinement needs three on each pass.
pub const MIN_SAMPLES_PER_FEED: f64 = 4.0;
/// Most grid samples accepted (angles × radial samples).
pub const MAX_SAMPLES: f64 = 1e10;

/// Grid of the prediction (JSON: `{"angles": 360, "radial_step_mm": 0.000625}`, both optional).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FormSettings {
    /// Half-planes through the axis, equally spaced from φ = 0: even (each has its opposite),
    /// 4 … 36 000; default 360.
    #[serde(default = "default_angles")]
    pub angles: usize,
    /// Radial sample step h, mm, in (0, f/4]; default f/16 (f the feed per revolution).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radial_step_mm: Option<f64>,
}

fn default_angles() -> usize {
    DEFAULT_ANGLES
}

impl Default for FormSettings {
    fn default() -> Self {
        Self {
            angles: DEFAULT_ANGLES,
            radial_step_mm: None,
        }
    }
}

impl FormSettings {
    /// The radial step for a feed of `feed_mm` per revolution, checked; field names are relative
    /// to the settings (`angles`, `radial_step_mm`).
    pub fn radial_step(&self, feed_mm: f64) -> Result<f64, FieldError> {
        let n = self.angles;
        if !(4..=MAX_ANGLES).contains(&n) || !n.is_multiple_of(2) {
            return Err(FieldError::new(
                "angles",
                n,
                format!("must be an even number in [4, {MAX_ANGLES}]"),
            ));
        }
        let max = feed_mm / MIN_SAMPLES_PER_FEED;
        match self.radial_step_mm {
            None => Ok(feed_mm / DEFAULT_SAMPLES_PER_FEED),
            Some(h) if h.is_finite() && h > 0.0 && h <= max => Ok(h),
            Some(h) => Err(FieldError::new(
                "radial_step_mm",
                h,
                format!(
                    "must lie in (0, {max}]: at least {MIN_SAMPLES_PER_FEED} samples per feed of {feed_mm} mm"
                ),
            )),
        }
    }
}

/// The predicted form of a planned path (see the module documentation for the definitions).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PredictedForm {
    /// Peak-to-valley of the form error over the annulus `f ≤ ρ ≤ ρ*_first`, µm.
    pub pv_um: f64,
    /// Area-weighted RMS of the form error about its mean over the annulus, µm.
    pub rms_um: f64,
    /// Area-weighted mean of the form error over the annulus (material left on average), µm.
    pub mean_um: f64,
    /// Median cusp height along the feed, µm; 0 when there is no cusp (`cusps` = 0).
    pub cusp_height_um: f64,
    /// Largest cusp height along the feed, µm; 0 when there is none.
    pub cusp_height_max_um: f64,
    /// The most negative form error anywhere on the machined surface (a gouge), µm, ≤ 0; 0 when
    /// the nose nowhere cuts below the design.
    pub max_overcut_um: f64,
    /// Peak-to-valley of the form error in the centre disc ρ < f, µm; 0 when it has no sample.
    pub centre_pv_um: f64,
    /// Grid samples on the machined surface (annulus and centre).
    pub samples: u64,
    /// Cusps in the median.
    pub cusps: u64,
    /// Half-planes of the grid.
    pub angles: usize,
    /// Radial step of the grid, mm.
    pub radial_step_mm: f64,
    /// Form error, µm, mean per cell (see the module documentation); empty for a map size of 0.
    #[serde(skip)]
    pub map: Raster,
}

/// One sample of a radial section of the predicted surface ([`predict_section`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SectionSample {
    /// Radius, mm.
    pub rho_mm: f64,
    /// Machined height, mm.
    pub machined_mm: f64,
    /// Design sag, mm.
    pub design_mm: f64,
}

/// Predicts the form of `tool_path`'s path on the grid `settings`, with a `map_size` × `map_size`
/// map over the part (0: no map). Reads the path once ([`ToolPath::points`]); `progress` gets
/// the number of path points read every [`PROGRESS_EVERY`] points and at the end.
///
/// Errors: a setting out of range ([`FieldError`] on `form.angles` or `form.radial_step_mm`), a
/// tool that leaves uncut ridges between passes (`tool.nose_radius_mm` = 0, or
/// `strategy.feed_mm_per_rev` ≥ the nose's chord `2r·sin(β/2)`), and a surface undefined where
/// the path or a sample needs it.
pub fn predict(
    tool_path: &ToolPath,
    settings: &FormSettings,
    map_size: usize,
    mut progress: impl FnMut(u64),
) -> Result<PredictedForm, PathError> {
    let mut predictor = FormPredictor::new(tool_path, settings, map_size)?;
    for p in tool_path.points() {
        predictor.push(&p?)?;
        if predictor.points.is_multiple_of(PROGRESS_EVERY) {
            progress(predictor.points);
        }
    }
    progress(predictor.points);
    predictor.finish()
}

/// The machined and design heights along the half-plane `angle` (φ = angle·360°/angles) of the
/// grid `settings`, from the centre out to the band edge; the same computation as [`predict`],
/// for plots and checks. Errors as [`predict`], and `form.angle` when `angle ≥ angles`.
pub fn predict_section(
    tool_path: &ToolPath,
    settings: &FormSettings,
    angle: usize,
) -> Result<Vec<SectionSample>, PathError> {
    if angle >= settings.angles {
        return Err(FieldError::new(
            "form.angle",
            angle,
            format!("must be below form.angles = {}", settings.angles),
        )
        .into());
    }
    let mut predictor = FormPredictor::new(tool_path, settings, 0)?;
    predictor.only = Some(angle);
    predictor.ctx.section = Some((angle, Vec::new()));
    for p in tool_path.points() {
        predictor.push(&p?)?;
    }
    let mut samples = predictor
        .complete()?
        .section
        .map(|s| s.1)
        .unwrap_or_default();
    samples.reverse();
    Ok(samples)
}

/// The prediction as a sink of path points, for callers that already stream the path:
/// [`FormPredictor::push`] every point in path order, then [`FormPredictor::finish`].
#[derive(Debug)]
pub struct FormPredictor<'a> {
    ctx: Context<'a>,
    planes: Vec<HalfPlane>,
    /// The previous point: θ in grid units, ρ, tip z.
    prev: Option<(f64, f64, f64)>,
    points: u64,
    /// Only this half-plane and its opposite (for [`predict_section`]).
    only: Option<usize>,
}

impl<'a> FormPredictor<'a> {
    /// Checks the settings against the job and prepares the grid and the map (see [`predict`]).
    pub fn new(
        tool_path: &'a ToolPath,
        settings: &FormSettings,
        map_size: usize,
    ) -> Result<Self, PathError> {
        let f = tool_path.spiral().feed_mm();
        let h = settings.radial_step(f).map_err(|e| e.within("form"))?;
        let nose = tool_path.nose();
        let r = nose.nose_radius();
        if r <= 0.0 {
            return Err(FieldError::new(
                "tool.nose_radius_mm",
                r,
                "must be > 0 for the predicted form (a sharp tool leaves uncut ridges)",
            )
            .into());
        }
        let w = nose.reach();
        if let Some(edge) = nose.waviness()
            && let Some(at) = edge.first_concave(-nose.half_angle(), nose.half_angle())
        {
            return Err(FieldError::new(
                "tool.waviness",
                format!("the measured edge near a = {:.3}°", at.to_degrees()),
                "must be convex for the predicted form (its envelope of cuts assumes an edge \
                 that bends one way): the table's deviations change too fast there",
            )
            .into());
        }
        if f >= 2.0 * w {
            return Err(FieldError::new(
                "strategy.feed_mm_per_rev",
                f,
                format!(
                    "must be below the nose's chord 2r·sin(β/2) = {} mm for the predicted form (the cuts must overlap)",
                    2.0 * w
                ),
            )
            .into());
        }
        let part = tool_path.job().part_radius_mm();
        let rho_max = tool_path.spiral().start_radius_mm().min(part);
        let n = settings.angles;
        let radial = (rho_max / h).floor() + 1.0;
        if n as f64 * radial > MAX_SAMPLES {
            return Err(FieldError::new(
                "form.radial_step_mm",
                h,
                format!(
                    "gives {:.3e} samples with {n} angles; at most {MAX_SAMPLES:.0e}",
                    n as f64 * radial
                ),
            )
            .into());
        }
        let delta = TAU / n as f64;
        let grid = Grid {
            n,
            delta,
            h,
            edge: Edge {
                r,
                measured: nose.waviness(),
            },
            tip: nose.tip_offset(),
            w,
            f,
            rho_max,
        };
        let planes = (0..n)
            .map(|j| {
                let (s, c) = (delta * j as f64).sin_cos();
                HalfPlane::new(j, c, s)
            })
            .collect();
        let map = (map_size > 0).then(|| MapAcc::new(&grid, part, map_size));
        Ok(Self {
            ctx: Context {
                surface: tool_path.surface(),
                grid,
                stats: Stats::default(),
                map,
                section: None,
            },
            planes,
            prev: None,
            points: 0,
            only: None,
        })
    }

    /// Takes the next point of the path.
    pub fn push(&mut self, p: &PathPoint) -> Result<(), PathError> {
        if !(p.rho.is_finite() && p.theta.is_finite() && p.z.is_finite()) {
            return Err(undefined(p.rho, p.theta, "the path point is not finite").into());
        }
        let q = p.theta / self.ctx.grid.delta;
        if let Some((q0, rho0, z0)) = self.prev {
            // Grid angles m·Δ in [θ_k, θ_{k+1}) (or (θ_{k+1}, θ_k]): each exactly once along
            // the path, the end of the path added by `finish`.
            if q > q0 {
                let mut m = q0.ceil();
                while m < q {
                    self.pass(m, (m - q0) / (q - q0), (rho0, z0), (p.rho, p.z))?;
                    m += 1.0;
                }
            } else if q < q0 {
                let mut m = q0.floor();
                while m > q {
                    self.pass(m, (q0 - m) / (q0 - q), (rho0, z0), (p.rho, p.z))?;
                    m -= 1.0;
                }
            }
        }
        self.prev = Some((q, p.rho, p.z));
        self.points += 1;
        Ok(())
    }

    /// Evaluates what is left and returns the prediction.
    pub fn finish(self) -> Result<PredictedForm, PathError> {
        let (n, h) = (self.ctx.grid.n, self.ctx.grid.h);
        let ctx = self.complete()?;
        Ok(ctx.stats.result(n, h, ctx.map))
    }

    /// The pass at grid angle `m` (unwrapped), `t` along the segment from `a` to `b` (ρ, z).
    fn pass(&mut self, m: f64, t: f64, a: (f64, f64), b: (f64, f64)) -> Result<(), PathError> {
        let n = self.ctx.grid.n;
        let j = (m.rem_euclid(n as f64) as usize).min(n - 1);
        if let Some(k) = self.only
            && j != k
            && j != (k + n / 2) % n
        {
            return Ok(());
        }
        let t = t.clamp(0.0, 1.0);
        let rho = a.0 + t * (b.0 - a.0);
        let z = a.1 + t * (b.1 - a.1);
        let g = self.ctx.grid;
        let plane = &mut self.planes[j];
        plane.add_pass(rho, z + g.tip, &g);
        plane.walk(&mut self.ctx, (plane.latest + g.w).max(g.w))?;
        Ok(())
    }

    /// Adds the last point's pass, merges each half-plane with its opposite near the axis and
    /// evaluates every sample left.
    fn complete(mut self) -> Result<Context<'a>, PathError> {
        if let Some((q, rho, z)) = self.prev
            && q == q.round()
        {
            self.pass(q, 0.0, (rho, z), (rho, z))?;
        }
        let n = self.ctx.grid.n;
        for j in 0..n / 2 {
            let k = j + n / 2;
            let arcs_j: Vec<(f64, f64)> =
                self.planes[j].pieces.iter().map(|p| (p.a, p.c)).collect();
            let arcs_k: Vec<(f64, f64)> =
                self.planes[k].pieces.iter().map(|p| (p.a, p.c)).collect();
            let g = &self.ctx.grid;
            for (plane, other) in [(j, &arcs_k), (k, &arcs_j)] {
                // The opposite arcs at −ρ*, in decreasing signed position.
                for &(a, c) in other.iter().rev() {
                    insert(&mut self.planes[plane].pieces, -a, c, g.edge, g.w);
                }
            }
            for plane in [j, k] {
                if self.only.is_some_and(|o| o != plane) {
                    continue;
                }
                let hp = &mut self.planes[plane];
                hp.walk(&mut self.ctx, f64::NEG_INFINITY)?;
                if hp.valley.n > 0 {
                    hp.finish_front(&mut self.ctx)?;
                }
            }
        }
        Ok(self.ctx)
    }
}

/// The grid and the tool.
#[derive(Debug, Clone, Copy)]
struct Grid<'a> {
    /// Half-planes.
    n: usize,
    /// Angle between half-planes, radians.
    delta: f64,
    /// Radial step, mm.
    h: f64,
    /// The cutting edge.
    edge: Edge<'a>,
    /// Height of the nose centre above the commanded tip, mm: r, or R(0) for a measured edge.
    tip: f64,
    /// Reach of the arc either side of the nose centre, `r·sin(β/2)`, mm.
    w: f64,
    /// Feed per revolution, mm: the radius of the centre disc.
    f: f64,
    /// Outermost sample radius: the smaller of the spiral's start and the part radius, mm.
    rho_max: f64,
}

/// What the half-planes share: the surface, statistics and map.
#[derive(Debug)]
struct Context<'a> {
    surface: &'a dyn Surface,
    grid: Grid<'a>,
    stats: Stats,
    map: Option<MapAcc>,
    /// The half-plane recorded ([`predict_section`]) and its samples, outermost first.
    section: Option<(usize, Vec<SectionSample>)>,
}

fn undefined(rho: f64, theta: f64, reason: &str) -> UndefinedError {
    UndefinedError {
        surface: "predicted form",
        x_mm: rho * theta.cos(),
        y_mm: rho * theta.sin(),
        radius_mm: rho,
        reason: reason.into(),
    }
}

/// One piece of a lower envelope: the arc of centre (a, c) (a signed along the half-plane) is
/// the lowest over [lo, hi].
#[derive(Debug, Clone, Copy, PartialEq)]
struct Piece {
    a: f64,
    c: f64,
    lo: f64,
    hi: f64,
}

impl Piece {
    fn height(&self, u: f64, e: Edge) -> f64 {
        self.c - e.depth(u - self.a)
    }
}

/// The cutting edge's profile below the nose centre: the circle of radius r, or a measured edge.
#[derive(Debug, Clone, Copy)]
struct Edge<'a> {
    r: f64,
    measured: Option<&'a Waviness>,
}

impl Edge<'_> {
    /// The edge's depth below the centre at the horizontal offset `d`, mm.
    fn depth(&self, d: f64) -> f64 {
        match self.measured {
            None => (self.r * self.r - d * d).max(0.0).sqrt(),
            Some(w) => w.depth(d),
        }
    }
}

/// Bisection steps of a measured edge's switch point: the overlap (≤ 2w) shrinks below 1e-15 of
/// it.
const SWITCH_BISECTIONS: usize = 60;

/// Where the arc (a, c) inserted below `top` (a ≤ top.a, overlapping domains) stops being the
/// lower: it is for u < x, `top` for u > x, over the overlap `[top.a − w, a + w]`. Two lower arcs
/// of equal radius cross at most once, at the lower intersection of their circles; when that
/// point is not on both arcs, one arc is the lower over the whole overlap.
fn switch_point(top: &Piece, a: f64, c: f64, e: Edge, w: f64) -> f64 {
    let (lo, hi) = (top.a - w, a + w);
    if e.measured.is_some() {
        return measured_switch_point(top, a, c, e, lo, hi);
    }
    let r = e.r;
    let (da, dc) = (a - top.a, c - top.c);
    let d2 = da * da + dc * dc;
    if d2 > 0.0 && d2 < 4.0 * r * r {
        let k = (r * r - 0.25 * d2).sqrt() / d2.sqrt();
        let u = 0.5 * (a + top.a) - k * dc;
        let z = 0.5 * (c + top.c) + k * da;
        if u >= lo && u <= hi && z <= c.min(top.c) {
            return u;
        }
    }
    let m = 0.5 * (lo + hi);
    let new = Piece { a, c, lo, hi };
    if new.height(m, e) < top.height(m, e) {
        hi
    } else {
        lo
    }
}

/// [`switch_point`] for a measured (convex) edge: the difference of the two cuts, new − top,
/// grows with u over the overlap `[lo, hi]`; where it changes sign is found by bisection, and
/// where it does not, one cut is the lower over the whole overlap.
fn measured_switch_point(top: &Piece, a: f64, c: f64, e: Edge, lo: f64, hi: f64) -> f64 {
    let new = Piece { a, c, lo, hi };
    let diff = |u: f64| new.height(u, e) - top.height(u, e);
    if diff(lo) >= 0.0 {
        return lo;
    }
    if diff(hi) <= 0.0 {
        return hi;
    }
    let (mut l, mut h) = (lo, hi);
    for _ in 0..SWITCH_BISECTIONS {
        let m = 0.5 * (l + h);
        if diff(m) < 0.0 {
            l = m;
        } else {
            h = m;
        }
    }
    0.5 * (l + h)
}

/// Adds the arc of centre (a, c), a no larger than any in `stack`, to the lower envelope
/// `stack` (outermost piece first).
fn insert(stack: &mut VecDeque<Piece>, a: f64, c: f64, e: Edge, w: f64) {
    // A path whose radius grew would break the order; clamp (planned paths never do).
    let a = stack.back().map_or(a, |t| a.min(t.a));
    loop {
        let Some(top) = stack.back_mut() else {
            stack.push_back(Piece {
                a,
                c,
                lo: a - w,
                hi: a + w,
            });
            return;
        };
        if top.a - w > a + w {
            // A gap between the two arcs' reaches.
            stack.push_back(Piece {
                a,
                c,
                lo: a - w,
                hi: a + w,
            });
            return;
        }
        let x = switch_point(top, a, c, e, w);
        if x >= top.hi {
            stack.pop_back();
            continue;
        }
        let x = x.max(top.lo);
        if x <= a - w {
            return;
        }
        top.lo = x;
        stack.push_back(Piece {
            a,
            c,
            lo: a - w,
            hi: x,
        });
        return;
    }
}

/// The lowest samples of the piece being walked: the minimum and its neighbours.
#[derive(Debug, Clone, Copy, Default)]
struct Valley {
    n: u32,
    last: f64,
    min: f64,
    min_rho: f64,
    left: Option<f64>,
    right: Option<f64>,
    last_was_min: bool,
}

impl Valley {
    fn push(&mut self, rho: f64, e: f64) {
        if self.n == 0 || e < self.min {
            self.left = (self.n > 0).then_some(self.last);
            self.min = e;
            self.min_rho = rho;
            self.right = None;
            self.last_was_min = true;
        } else {
            if self.last_was_min {
                self.right = Some(e);
            }
            self.last_was_min = false;
        }
        self.last = e;
        self.n += 1;
    }

    /// The valley refined by the parabola through the lowest sample and its neighbours, if the
    /// lowest sample has both.
    fn refined(&self) -> Option<f64> {
        let (l, r) = (self.left?, self.right?);
        let d = l - 2.0 * self.min + r;
        let v = if d > 0.0 {
            self.min - (r - l) * (r - l) / (8.0 * d)
        } else {
            self.min
        };
        Some(v.min(self.min))
    }
}

/// The apex at the lower end of the last finished piece, waiting for the next piece's valley.
#[derive(Debug, Clone, Copy)]
struct Apex {
    e: f64,
    valley: Option<f64>,
}

/// One half-plane of the grid.
#[derive(Debug)]
struct HalfPlane {
    index: usize,
    cos: f64,
    sin: f64,
    pieces: VecDeque<Piece>,
    /// Outer edge of the machined band: the first pass's ρ*, at most the part radius.
    edge: f64,
    /// ρ* of the latest pass.
    latest: f64,
    /// Next sample to evaluate (descending); None before the first pass and when done.
    next: Option<usize>,
    valley: Valley,
    apex: Option<Apex>,
    /// Map cells: the window of active cells and the next to activate.
    cells: (usize, usize),
}

impl HalfPlane {
    fn new(index: usize, cos: f64, sin: f64) -> Self {
        Self {
            index,
            cos,
            sin,
            pieces: VecDeque::new(),
            edge: f64::NEG_INFINITY,
            latest: f64::INFINITY,
            next: None,
            valley: Valley::default(),
            apex: None,
            cells: (0, 0),
        }
    }

    fn add_pass(&mut self, rho: f64, c: f64, g: &Grid) {
        if self.edge == f64::NEG_INFINITY {
            // The first pass: the machined band ends here.
            self.edge = rho.min(g.rho_max).max(0.0);
            self.next = Some((self.edge / g.h).floor() as usize);
        }
        self.latest = self.latest.min(rho);
        insert(&mut self.pieces, rho, c, g.edge, g.w);
    }

    /// Evaluates the samples above `above`, outermost first.
    fn walk(&mut self, ctx: &mut Context, above: f64) -> Result<(), UndefinedError> {
        while let Some(i) = self.next {
            let rho = i as f64 * ctx.grid.h;
            if rho <= above {
                break;
            }
            self.sample(ctx, i, rho)?;
            self.next = i.checked_sub(1);
        }
        Ok(())
    }

    fn sample(&mut self, ctx: &mut Context, i: usize, rho: f64) -> Result<(), UndefinedError> {
        while self.pieces.front().is_some_and(|p| p.lo > rho) {
            self.finish_front(ctx)?;
        }
        let Some(p) = self.pieces.front() else {
            return Ok(());
        };
        if p.hi < rho {
            // Between two passes' reaches: no arc cut here (cannot happen for f < 2w).
            return Ok(());
        }
        let g = &ctx.grid;
        let z = p.height(rho, g.edge);
        let design = ctx.surface.sag(rho * self.cos, rho * self.sin)?;
        let e = z - design;
        if !e.is_finite() {
            return Err(undefined(
                rho,
                self.sin.atan2(self.cos),
                "the machined or design height is not finite",
            ));
        }
        self.valley.push(rho, e);
        let weight = if i == 0 { 0.125 * g.h } else { rho };
        ctx.stats.sample(rho >= g.f, e, weight);
        if let Some(map) = ctx.map.as_mut() {
            map.add(&mut self.cells, self.index, rho, e);
        }
        if let Some((plane, s)) = ctx.section.as_mut()
            && *plane == self.index
        {
            s.push(SectionSample {
                rho_mm: rho,
                machined_mm: z,
                design_mm: design,
            });
        }
        Ok(())
    }

    /// Drops the front piece, whose samples are all done: its valley, the cusp above it and the
    /// apex below it.
    fn finish_front(&mut self, ctx: &mut Context) -> Result<(), UndefinedError> {
        let Some(p) = self.pieces.pop_front() else {
            return Ok(());
        };
        let g = ctx.grid;
        let refined = self.valley.refined();
        if let Some(v) = refined {
            ctx.stats.extreme(self.valley.min_rho >= g.f, v);
        }
        let whole = p.lo >= g.f && p.hi <= self.edge;
        let valley = refined.filter(|_| whole);
        if let Some(apex) = self.apex.take()
            && let (Some(outer), Some(v)) = (apex.valley, valley)
        {
            ctx.stats.cusp(apex.e - 0.5 * (outer + v));
        }
        if let Some(q) = self.pieces.front()
            && q.hi == p.lo
            && p.lo >= 0.0
            && p.lo <= self.edge
        {
            let x = p.lo;
            let e = p.height(x, g.edge) - ctx.surface.sag(x * self.cos, x * self.sin)?;
            if e.is_finite() {
                ctx.stats.extreme(x >= g.f, e);
                if x >= g.f {
                    self.apex = Some(Apex { e, valley });
                }
            }
        }
        self.valley = Valley::default();
        Ok(())
    }
}

/// Running statistics.
#[derive(Debug, Default)]
struct Stats {
    /// Reference subtracted before summing (the first annulus sample), mm.
    shift: Option<f64>,
    weight: f64,
    sum: f64,
    sum_sq: f64,
    annulus: Range,
    centre: Range,
    overcut: f64,
    samples: u64,
    /// Cusp heights binned by their top 16 mantissa bits.
    cusps: BTreeMap<u64, u64>,
    cusp_count: u64,
    cusp_max: f64,
}

/// Smallest and largest value seen.
#[derive(Debug, Clone, Copy, Default)]
struct Range {
    seen: bool,
    min: f64,
    max: f64,
}

impl Range {
    fn add(&mut self, v: f64) {
        if self.seen {
            self.min = self.min.min(v);
            self.max = self.max.max(v);
        } else {
            *self = Self {
                seen: true,
                min: v,
                max: v,
            };
        }
    }

    fn span(&self) -> f64 {
        if self.seen { self.max - self.min } else { 0.0 }
    }
}

/// Mantissa bits kept by the cusp histogram: bins 2⁻¹⁶ wide relative.
const CUSP_BITS: u32 = 16;

impl Stats {
    /// A sample of the machined surface: in the annulus or the centre disc.
    fn sample(&mut self, annulus: bool, e: f64, weight: f64) {
        self.samples += 1;
        self.extreme(annulus, e);
        if annulus {
            let s = e - *self.shift.get_or_insert(e);
            self.weight += weight;
            self.sum += weight * s;
            self.sum_sq += weight * s * s;
        }
    }

    /// A value that counts for the extremes only (an apex, a refined valley).
    fn extreme(&mut self, annulus: bool, e: f64) {
        if annulus {
            self.annulus.add(e);
        } else {
            self.centre.add(e);
        }
        self.overcut = self.overcut.min(e);
    }

    fn cusp(&mut self, height: f64) {
        if !height.is_finite() {
            return;
        }
        let key = if height > 0.0 {
            height.to_bits() >> (52 - CUSP_BITS)
        } else {
            0
        };
        *self.cusps.entry(key).or_insert(0) += 1;
        self.cusp_max = if self.cusp_count == 0 {
            height
        } else {
            self.cusp_max.max(height)
        };
        self.cusp_count += 1;
    }

    /// The median cusp height: the centre of the histogram bin holding it.
    fn cusp_median(&self) -> f64 {
        let half = self.cusp_count.div_ceil(2);
        let mut seen = 0;
        for (&key, &count) in &self.cusps {
            seen += count;
            if seen >= half {
                if key == 0 {
                    return 0.0;
                }
                let lo = f64::from_bits(key << (52 - CUSP_BITS));
                let hi = f64::from_bits((key + 1) << (52 - CUSP_BITS));
                return 0.5 * (lo + hi);
            }
        }
        0.0
    }

    fn result(&self, angles: usize, h: f64, map: Option<MapAcc>) -> PredictedForm {
        let um = |v: f64| if v.is_finite() { 1e3 * v } else { 0.0 };
        let (mean, rms) = if self.weight > 0.0 {
            let m = self.sum / self.weight;
            let var = (self.sum_sq / self.weight - m * m).max(0.0);
            (m + self.shift.unwrap_or(0.0), var.sqrt())
        } else {
            (0.0, 0.0)
        };
        PredictedForm {
            pv_um: um(self.annulus.span()),
            rms_um: um(rms),
            mean_um: um(mean),
            cusp_height_um: um(self.cusp_median()),
            cusp_height_max_um: um(self.cusp_max),
            max_overcut_um: um(self.overcut.min(0.0)),
            centre_pv_um: um(self.centre.span()),
            samples: self.samples,
            cusps: self.cusp_count,
            angles,
            radial_step_mm: h,
            map: map.map_or_else(
                || Raster {
                    size: 0,
                    x0_mm: 0.0,
                    y0_mm: 0.0,
                    step_mm: 0.0,
                    values: Vec::new(),
                },
                MapAcc::finish,
            ),
        }
    }
}

/// The map being filled: each cell listed under its nearest half-plane, by decreasing radius.
#[derive(Debug)]
struct MapAcc {
    raster: Raster,
    count: Vec<u32>,
    /// Cells of half-plane j: `cells[offsets[j]..offsets[j + 1]]`, (radius, index).
    offsets: Vec<usize>,
    cells: Vec<(f32, u32)>,
    /// Half-width of a cell's radial window, mm.
    half: f64,
}

impl MapAcc {
    fn new(g: &Grid, part_radius: f64, size: usize) -> Self {
        let mut raster = Raster::over_part(part_radius, size);
        let half = 0.5 * raster.step_mm.max(g.h);
        // The nearest half-plane of each cell within reach of the samples, then the cells
        // grouped by half-plane (counting sort) and sorted by decreasing radius.
        let n = raster.size;
        let mut plane_of = vec![u32::MAX; n * n];
        let mut offsets = vec![0; g.n + 1];
        for j in 0..n {
            for i in 0..n {
                let (x, y) = raster.position(i, j);
                if x.hypot(y) - half > g.rho_max {
                    continue;
                }
                let plane =
                    ((y.atan2(x) / g.delta).round().rem_euclid(g.n as f64) as usize).min(g.n - 1);
                plane_of[j * n + i] = plane as u32;
                offsets[plane + 1] += 1;
            }
        }
        for j in 0..g.n {
            offsets[j + 1] += offsets[j];
        }
        let mut fill = offsets.clone();
        let mut cells = vec![(0f32, 0u32); offsets[g.n]];
        for (k, &plane) in plane_of.iter().enumerate() {
            if plane != u32::MAX {
                let (x, y) = raster.position(k % n, k / n);
                cells[fill[plane as usize]] = (x.hypot(y) as f32, k as u32);
                fill[plane as usize] += 1;
                raster.values[k] = 0.0;
            }
        }
        for j in 0..g.n {
            cells[offsets[j]..offsets[j + 1]].sort_by(|a, b| b.0.total_cmp(&a.0));
        }
        let count = vec![0; raster.values.len()];
        Self {
            raster,
            count,
            offsets,
            cells,
            half,
        }
    }

    /// Adds the sample (ρ, e) of half-plane `plane` to the cells whose window holds it;
    /// `window` is the plane's (first active, next) cell, samples coming by decreasing ρ.
    fn add(&mut self, window: &mut (usize, usize), plane: usize, rho: f64, e: f64) {
        let (start, end) = (self.offsets[plane], self.offsets[plane + 1]);
        let (first, next) = window;
        *first = (*first).max(start);
        *next = (*next).max(start);
        while *next < end && f64::from(self.cells[*next].0) + self.half >= rho {
            *next += 1;
        }
        while *first < *next && f64::from(self.cells[*first].0) - self.half > rho {
            *first += 1;
        }
        for &(_, k) in &self.cells[*first..*next] {
            let k = k as usize;
            self.raster.values[k] += e;
            self.count[k] += 1;
        }
    }

    fn finish(mut self) -> Raster {
        for (v, &n) in self.raster.values.iter_mut().zip(&self.count) {
            *v = if n > 0 {
                1e3 * *v / f64::from(n)
            } else {
                f64::NAN
            };
        }
        self.raster
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::test_random::uniform;

    /// The envelope by brute force: the lowest arc over u.
    fn brute(arcs: &[(f64, f64)], u: f64, r: f64, w: f64) -> Option<f64> {
        arcs.iter()
            .filter(|(a, _)| (u - a).abs() <= w)
            .map(|&(a, c)| c - (r * r - (u - a) * (u - a)).sqrt())
            .min_by(f64::total_cmp)
    }

    #[test]
    fn the_stack_is_the_lower_envelope() {
        let (r, w) = (0.5, 0.5 * 50f64.to_radians().sin());
        let mut state = 7;
        for case in 0..200 {
            // Arcs by decreasing centre, irregular spacing and heights: some dominated, some
            // with gaps between their reaches, some at the same centre.
            let mut arcs = Vec::new();
            let mut a = 3.0;
            let spread = [1e-4, 0.02, 0.3][case % 3];
            for _ in 0..40 {
                arcs.push((a, spread * (uniform(&mut state) - 0.5)));
                a -= [0.0, 0.01, 0.05, 0.9][(uniform(&mut state) * 4.0) as usize];
            }
            let mut stack = VecDeque::new();
            let edge = Edge { r, measured: None };
            for &(a, c) in &arcs {
                insert(&mut stack, a, c, edge, w);
            }
            for p in stack.iter().zip(stack.iter().skip(1)) {
                assert!(p.0.lo >= p.1.hi, "{:?}", p);
            }
            for p in &stack {
                assert!(p.lo <= p.hi && p.lo >= p.a - w - 1e-15 && p.hi <= p.a + w + 1e-15);
            }
            let (lo, hi) = (a - w - 0.1, 3.0 + w + 0.1);
            for k in 0..=4000 {
                let u = lo + (hi - lo) * k as f64 / 4000.0;
                let want = brute(&arcs, u, r, w);
                let piece = stack.iter().find(|p| p.lo <= u && u <= p.hi);
                match (want, piece) {
                    (None, None) => {}
                    (Some(z), Some(p)) => {
                        assert!((p.height(u, edge) - z).abs() < 1e-12, "case {case} u {u}")
                    }
                    _ => panic!("case {case} u {u}: {want:?} vs {piece:?}"),
                }
            }
        }
    }

    #[test]
    fn the_valley_is_refined_by_a_parabola() {
        let mut v = Valley::default();
        for k in 0..9 {
            let u = 0.3 + 0.1 * k as f64;
            v.push(u, 2.0 * (u - 0.63) * (u - 0.63) + 0.01);
        }
        assert!((v.refined().unwrap() - 0.01).abs() < 1e-15);
        let mut edge = Valley::default();
        edge.push(0.0, 1.0);
        edge.push(0.1, 2.0);
        assert_eq!(edge.refined(), None);
    }

    #[test]
    fn the_cusp_median_is_read_from_the_histogram() {
        let mut s = Stats::default();
        for h in [3e-4, 1e-4, 2e-4, 5e-4, 2.5e-4] {
            s.cusp(h);
        }
        assert!((s.cusp_median() / 2.5e-4 - 1.0).abs() < 1e-5);
        assert_eq!(s.cusp_max, 5e-4);
        assert_eq!(Stats::default().cusp_median(), 0.0);
    }

    #[test]
    fn settings_are_checked() {
        let f = 0.01;
        assert_eq!(FormSettings::default().radial_step(f), Ok(f / 16.0));
        for n in [0, 2, 5, 36_002] {
            let s = FormSettings {
                angles: n,
                radial_step_mm: None,
            };
            assert_eq!(s.radial_step(f).unwrap_err().field, "angles");
        }
        for h in [0.0, -1.0, f64::NAN, 0.003] {
            let s = FormSettings {
                angles: 360,
                radial_step_mm: Some(h),
            };
            assert_eq!(s.radial_step(f).unwrap_err().field, "radial_step_mm");
        }
        let s: FormSettings = serde_json::from_str(r#"{"radial_step_mm": 0.001}"#).unwrap();
        assert_eq!((s.angles, s.radial_step(f)), (360, Ok(0.001)));
        assert!(serde_json::from_str::<FormSettings>(r#"{"angle": 3}"#).is_err());
    }
}
