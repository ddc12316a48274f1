//! Where the nose cannot reach: zones whose radial section is concave with a curvature radius
//! smaller than the nose radius r, and the form error they leave (DESIGN.md, "Tool nose
//! compensation"; paper 003, Figure 8).
//!
//! Detection: the radial sections at 360 angles are sampled at spacing δ (a sixteenth of the
//! surface's feature length or an eighth of r, at most 4000 samples per section). A sample is
//! flagged where the curvature `κ = f″/(1+f′²)^{3/2}` exceeds 1/r, and both ends of an interval
//! are flagged where the slope rises faster than `(1+f′²)^{3/2}/r` per mm across it — a slope
//! kink, such as the foot of a convex lenslet, or a sharp bend between samples; and every slope
//! kink the surface itself reports ([`Surface::slope_kinks`]) across which the slope rises is
//! flagged with curvature radius 0, however small its jump. Flagged samples
//! that touch (in ρ, or in θ at the same ρ) form one zone.
//!
//! Depth: the cut surface is the lower envelope of the nose arcs, `cut(u) = min_ρs [z_c(ρ_s) − √(r²
//! − (u − ρ_s)²)]`, with z_c the compensated centre height ([`crate::tool`]); the form error is the
//! closing residual `cut(u) − f(u)` (with a measured edge, `tool.waviness`, the edge's own depth
//! below the centre replaces the circle's, [`NoseCompensator::edge_depth`]). It is found on a grid around the zone and refined by nested
//! golden-section searches (over u for the largest residual, over ρ_s for the envelope), because at
//! a kink both functions have corners that a grid would only resolve to first order. The depth
//! reported is the largest of those found at up to five angles of each zone: the sharpest, and four
//! spread evenly over the zone's angles. Each reported kink and each general search at those
//! angles is one probe. A kink probe scans the tool positions whose arc covers its kink, at
//! the spacing δ, before refining the best: those positions lie on one lattice per section,
//! whose compensated heights are computed once for all the section's kink probes (the
//! scattered example's 596 kink probes read 12 400 heights where their own scans computed about
//! 120 000; its report took 0.55 s instead of 0.76). The probes of a batch of zones go to the
//! cores one at a time ([`crate::parallel::fill_each`]: one zone's may outweigh the others',
//! as the scattered example's largest, 131 kinks at each of four angles), their depths
//! compared in the probes' order.
//! At a kink the surface reports, the residual is read against the surface at the kink and just
//! either side of it: where the surface jumps there (a neighbour-set switch of scattered data)
//! the lower side is the form error, and the value exactly at the kink is either side's by
//! rounding. Zones shallower than 0.1 nm (a radial section grazing a slope kink) are counted but
//! not listed.

use crate::parallel::{fill_chunks, fill_each, workers};
use crate::path::{Location, PathError};
use crate::progress::{Progress, ProgressFn, Stage};
use crate::surface::{Line, Surface, UndefinedError};
use crate::tool::{Concavity, NoseCompensator};
use serde::Serialize;
use std::f64::consts::TAU;

/// Angles at which radial sections are examined.
pub const ANGLES: usize = 360;
/// Distance either side of a reported kink where its slopes are read, relative to max(|t|, 1) mm.
const KINK_SIDE: f64 = 1e-9;
/// Most samples per radial section.
const MAX_SAMPLES: usize = 4000;
/// Most zones listed.
pub const MAX_ZONES: usize = 500;
/// Most zones measured (the sharpest first): each costs up to a few thousand compensations.
pub const MAX_MEASURED_ZONES: usize = 5000;
/// Most tool positions one section's envelope search samples.
const MAX_SECTION_SAMPLES: f64 = 100_000.0;
/// Zones whose form error is below this are counted, not listed, mm (0.1 nm).
pub const LISTED_DEPTH_MM: f64 = 1e-7;

/// A zone the nose cannot reach.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConcaveZone {
    /// Inner radius, mm.
    pub rho_min_mm: f64,
    /// Outer radius, mm.
    pub rho_max_mm: f64,
    /// First angle, degrees: the zone runs counter-clockwise from here…
    pub theta_from_deg: f64,
    /// …to here, degrees (smaller than `theta_from_deg` when it crosses 0°).
    pub theta_to_deg: f64,
    /// Smallest curvature radius found, mm (a slope kink shows as less than the sample spacing).
    pub min_curvature_radius_mm: f64,
    /// The zone contains a slope kink (or a bend sharper than the sampling).
    pub slope_kink: bool,
    /// Largest form error found: material the nose leaves above the surface, µm.
    pub depth_um: f64,
    /// Where that error is deepest.
    pub at: Location,
}

/// A flagged sample: curvature radius there, and whether a kink flagged it.
#[derive(Debug, Clone, Copy)]
struct Flag {
    radius: f64,
    kink: bool,
    /// ρ of a kink the surface reported: the valley bottom, exactly.
    exact: Option<f64>,
}

/// The zones of a surface for a nose, on a part of radius `part_radius_mm`.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Reach {
    /// Zones with a form error of at least 0.1 nm, deepest first, at most [`MAX_ZONES`].
    pub zones: Vec<ConcaveZone>,
    /// Zones found whose form error is below 0.1 nm (grazing crossings of a slope kink).
    pub shallow_zones: usize,
    /// Zones with a form error of at least 0.1 nm left out of `zones` beyond [`MAX_ZONES`].
    pub unlisted_zones: usize,
    /// Zones found but not measured, beyond [`MAX_MEASURED_ZONES`] (the least sharp).
    pub unmeasured_zones: usize,
}

/// Finds the zones of `surface` that `nose` cannot reach on a part of radius `part_radius_mm`.
/// The work is bounded: [`ANGLES`] × at most 4001 samples are flagged, and at most
/// [`MAX_MEASURED_ZONES`] zones measured, the sharpest first (the rest are counted as
/// `unmeasured_zones`); `progress` sees the sections, then the zones, done ([`Stage::Zones`])
/// and may cancel.
pub fn concave_zones(
    surface: &dyn Surface,
    nose: &NoseCompensator,
    part_radius_mm: f64,
    progress: &mut ProgressFn,
) -> Result<Reach, PathError> {
    let r = nose.nose_radius();
    if r == 0.0 {
        return Ok(Reach::default());
    }
    let wanted = (surface.feature_length_mm() / 16.0).min(r / 8.0);
    let n = ((part_radius_mm / wanted).ceil() as usize).clamp(16, MAX_SAMPLES);
    let delta = part_radius_mm / n as f64;
    let grid = flag_grid(surface, r, n, delta, progress)?;
    let mut found = components(&grid, n + 1);
    let cols = n + 1;
    let sharpest = |cells: &Vec<(usize, usize)>| {
        cells
            .iter()
            .filter_map(|&(i, j)| grid[i * cols + j].map(|f| f.radius))
            .fold(f64::INFINITY, f64::min)
    };
    found.sort_by(|a, b| sharpest(a).total_cmp(&sharpest(b)));
    let unmeasured_zones = found.len().saturating_sub(MAX_MEASURED_ZONES);
    found.truncate(MAX_MEASURED_ZONES);
    let mut zones = vec![None; found.len()];
    // The nose's certificate on the surface, proven once for every zone's envelopes.
    let concavity = if found.is_empty() {
        None
    } else {
        nose.concavity(surface)
    };
    let total = (ANGLES + found.len()) as u64;
    let batch = 4 * workers();
    for (k, part) in zones.chunks_mut(batch).enumerate() {
        let first = k * batch;
        let cells = &found[first..first + part.len()];
        // Every probe of the batch's zones handed out one at a time: one zone's may take
        // seconds (131 kinks at each of four angles) where the others' take milliseconds.
        let probes: Vec<(usize, usize, Probe)> = cells
            .iter()
            .enumerate()
            .flat_map(|(z, c)| {
                probes(&grid, c, delta)
                    .into_iter()
                    .map(move |(i, p)| (z, i, p))
            })
            .collect();
        let section = |i: usize| {
            let theta = TAU * i as f64 / ANGLES as f64;
            Envelope::new(surface, nose, concavity, theta, part_radius_mm)
        };
        let scans = KinkScans::of(&probes, delta, &section)?;
        let mut depths = vec![(0.0, 0.0); probes.len()];
        fill_each(&mut depths, |t| {
            let (_, i, probe) = probes[t];
            probe.depth(&section(i), scans.row(i), delta)
        })?;
        for (z, slot) in part.iter_mut().enumerate() {
            let mine = probes.iter().zip(&depths).filter(|((y, _, _), _)| *y == z);
            let zone_depths = mine.map(|(&(_, i, _), &depth)| (i, depth));
            *slot = Some(zone(&grid, &cells[z], delta, zone_depths));
        }
        let done = (ANGLES + first + part.len()) as u64;
        if progress(Progress {
            stage: Stage::Zones,
            done,
            total,
        })
        .is_break()
        {
            return Err(PathError::Cancelled);
        }
    }
    let mut zones: Vec<ConcaveZone> = zones.into_iter().flatten().collect();
    let found = zones.len();
    zones.retain(|z| z.depth_um >= LISTED_DEPTH_MM * 1e3);
    let shallow_zones = found - zones.len();
    zones.sort_by(|a, b| b.depth_um.total_cmp(&a.depth_um));
    let unlisted_zones = zones.len().saturating_sub(MAX_ZONES);
    zones.truncate(MAX_ZONES);
    Ok(Reach {
        zones,
        shallow_zones,
        unlisted_zones,
        unmeasured_zones,
    })
}

/// Flags per angle and radial sample, row-major (angle, sample).
fn flag_grid(
    surface: &dyn Surface,
    r: f64,
    n: usize,
    delta: f64,
    progress: &mut ProgressFn,
) -> Result<Vec<Option<Flag>>, PathError> {
    let cols = n + 1;
    let mut rows: Vec<Vec<Option<Flag>>> = vec![Vec::new(); ANGLES];
    let batch = 8 * workers();
    for (k, part) in rows.chunks_mut(batch).enumerate() {
        fill_each(part, |j| flag_row(surface, r, k * batch + j, cols, delta))?;
        let done = (k * batch + part.len()) as u64;
        let total = ANGLES as u64;
        if progress(Progress {
            stage: Stage::Zones,
            done,
            total,
        })
        .is_break()
        {
            return Err(PathError::Cancelled);
        }
    }
    Ok(rows.concat())
}

/// The flags of the radial section at angle index `i`.
fn flag_row(
    surface: &dyn Surface,
    r: f64,
    i: usize,
    cols: usize,
    delta: f64,
) -> Result<Vec<Option<Flag>>, UndefinedError> {
    let mut row = vec![None; cols];
    let mut slopes = vec![0.0; cols];
    let (s, c) = (TAU * i as f64 / ANGLES as f64).sin_cos();
    // The kinks first: a surface that keeps the section of the line asked about then answers
    // the samples from it ([`Surface::kept_radial`]).
    let mut kinks = Vec::new();
    let end = delta * (cols - 1) as f64;
    surface.slope_kinks(Line::radial(c, s), 0.0, end, &mut kinks);
    for j in 0..cols {
        let rho = delta * j as f64;
        let l = match surface.kept_radial(c, s, rho) {
            Some(kept) => kept?,
            None => surface.local(rho * c, rho * s)?.radial(c, s),
        };
        let stretch = (1.0 + l.slope * l.slope).powf(1.5);
        let kappa = l.curvature_term / stretch;
        if kappa > 1.0 / r {
            row[j] = Some(Flag {
                radius: 1.0 / kappa,
                kink: false,
                exact: None,
            });
        }
        slopes[j] = l.slope;
        if j > 0 {
            let mean = (slopes[j] - slopes[j - 1]) / delta / stretch;
            if mean > 1.0 / r {
                for k in [j - 1, j] {
                    let radius = row[k].map_or(f64::INFINITY, |f| f.radius);
                    if 1.0 / mean < radius {
                        row[k] = Some(Flag {
                            radius: 1.0 / mean,
                            kink: true,
                            exact: None,
                        });
                    }
                }
            }
        }
    }
    flag_reported_kinks(surface, (c, s), delta, &kinks, &mut row)?;
    Ok(row)
}

/// Flags the slope `kinks` the surface reports along the section ([`Surface::slope_kinks`])
/// where the slope rises across the kink: a valley the nose cannot reach, however small the
/// jump (the sampled test above only sees jumps steeper than δ/r).
fn flag_reported_kinks(
    surface: &dyn Surface,
    (c, s): (f64, f64),
    delta: f64,
    kinks: &[f64],
    row: &mut [Option<Flag>],
) -> Result<(), UndefinedError> {
    let slope = |t: f64| -> Result<f64, UndefinedError> {
        Ok(surface.local(t * c, t * s)?.radial(c, s).slope)
    };
    for &t in kinks {
        let step = KINK_SIDE * t.abs().max(1.0);
        if slope(t + step)? > slope(t - step)? {
            let j = ((t / delta).round() as usize).min(row.len() - 1);
            row[j] = Some(Flag {
                radius: 0.0,
                kink: true,
                exact: Some(t),
            });
        }
    }
    Ok(())
}

/// Connected groups of flagged cells: neighbours along a section, and cells of neighbouring
/// angles (θ wrapping round) no farther apart in ρ than the arc between the two angles.
fn components(grid: &[Option<Flag>], cols: usize) -> Vec<Vec<(usize, usize)>> {
    let mut seen = vec![false; grid.len()];
    let mut out = Vec::new();
    let arc_cells = TAU / ANGLES as f64 * (cols - 1) as f64; // cells of arc per unit j
    for start in 0..grid.len() {
        if grid[start].is_none() || seen[start] {
            continue;
        }
        seen[start] = true;
        let mut stack = vec![start];
        let mut cells = Vec::new();
        while let Some(k) = stack.pop() {
            let (i, j) = (k / cols, k % cols);
            cells.push((i, j));
            let reach = (j as f64 * arc_cells / (cols - 1) as f64).ceil() as usize + 1;
            let across = [(i + 1) % ANGLES, (i + ANGLES - 1) % ANGLES]
                .into_iter()
                .flat_map(|ii| {
                    (j.saturating_sub(reach)..(j + reach + 1).min(cols))
                        .map(move |jj| ii * cols + jj)
                });
            let along = [j.checked_sub(1), (j + 1 < cols).then_some(j + 1)]
                .into_iter()
                .flatten()
                .map(|jj| i * cols + jj);
            for m in along.chain(across) {
                if grid[m].is_some() && !seen[m] {
                    seen[m] = true;
                    stack.push(m);
                }
            }
        }
        out.push(cells);
    }
    out
}

/// Where a zone's depth is probed ([`probes`]).
#[derive(Debug, Clone, Copy)]
enum Probe {
    /// At a kink the surface reported, ρ mm: the bottom of its valley.
    Kink(f64),
    /// The general search over `[lo, hi]`, mm, around flags away from reported kinks.
    Search(f64, f64),
}

impl Probe {
    /// Where the residual peaks and its depth, (u, mm), on `section`, whose kink probes share
    /// the scan `row` ([`KinkScans`]).
    fn depth(
        self,
        section: &Envelope,
        row: Option<&ScanRow>,
        delta: f64,
    ) -> Result<(f64, f64), UndefinedError> {
        match self {
            Probe::Kink(t) => Ok((t, section.residual_at_kink(t, row, delta)?)),
            Probe::Search(lo, hi) => section.deepest(lo, hi, delta),
        }
    }
}

/// The compensated centre heights at the tool positions a kink probe scans
/// ([`Envelope::envelope_at`]), computed once per section for all its kink probes: the
/// positions lie on the lattice `k·step` of the section, so the scans of kinks closer together
/// than the nose's width (a zone of scattered data has a kink at every neighbour-set switch,
/// 131 along one section of the example) share their heights instead of each computing its
/// own. The heights of every section of a batch are computed on every core at once.
struct KinkScans {
    /// The sections' angle indices, ascending, and their rows.
    rows: Vec<(usize, ScanRow)>,
}

/// One section's heights on its lattice, from index `first`; NaN where no scan reaches.
struct ScanRow {
    first: i64,
    z_center: Vec<f64>,
}

impl ScanRow {
    /// The height at lattice index `k`, when it was computed.
    fn at(&self, k: i64) -> Option<f64> {
        let z = *self.z_center.get(usize::try_from(k - self.first).ok()?)?;
        (!z.is_nan()).then_some(z)
    }
}

impl KinkScans {
    /// The rows of the sections with kink probes among `probes` ((zone, angle index, probe)).
    fn of<'a>(
        probes: &[(usize, usize, Probe)],
        delta: f64,
        section: &(dyn Fn(usize) -> Envelope<'a> + Sync),
    ) -> Result<Self, UndefinedError> {
        // Every (angle index, lattice index) a scan reaches, once.
        let mut wanted: Vec<(usize, i64)> = Vec::new();
        for &(_, i, probe) in probes {
            if let Probe::Kink(t) = probe {
                wanted.extend(section(i).lattice(t, delta).map(|k| (i, k)));
            }
        }
        wanted.sort_unstable();
        wanted.dedup();
        let mut heights = vec![0.0; wanted.len()];
        fill_chunks(&mut heights, |first, out| {
            let mut at = (usize::MAX, None);
            for (slot, &(i, k)) in out.iter_mut().zip(&wanted[first..]) {
                if at.0 != i {
                    at = (i, Some(section(i)));
                }
                let env = at.1.as_ref().expect("set above");
                *slot = env.center(env.lattice_position(k, delta))?;
            }
            Ok(())
        })?;
        let mut rows: Vec<(usize, ScanRow)> = Vec::new();
        for (&(i, k), &z) in wanted.iter().zip(&heights) {
            if rows.last().is_none_or(|r| r.0 != i) {
                let first = k;
                rows.push((
                    i,
                    ScanRow {
                        first,
                        z_center: Vec::new(),
                    },
                ));
            }
            let row = &mut rows.last_mut().expect("pushed above").1;
            let at = usize::try_from(k - row.first).expect("ascending");
            row.z_center.resize(at, f64::NAN);
            row.z_center.push(z);
        }
        Ok(Self { rows })
    }

    /// The row of the section at angle index `i`.
    fn row(&self, i: usize) -> Option<&ScanRow> {
        let at = self.rows.binary_search_by_key(&i, |r| r.0).ok()?;
        Some(&self.rows[at].1)
    }
}

/// The flag of cell (angle, sample), or an unflagged one.
fn flag_of(grid: &[Option<Flag>], (i, j): (usize, usize)) -> Flag {
    let cols = grid.len() / ANGLES;
    grid[i * cols + j].unwrap_or(Flag {
        radius: f64::INFINITY,
        kink: false,
        exact: None,
    })
}

/// The zone's sharpest cell.
fn sharpest_cell(grid: &[Option<Flag>], cells: &[(usize, usize)]) -> (usize, usize) {
    cells
        .iter()
        .min_by(|a, b| {
            flag_of(grid, **a)
                .radius
                .total_cmp(&flag_of(grid, **b).radius)
        })
        .copied()
        .unwrap_or((0, 0))
}

/// The probes of a zone, (angle index, probe), in the order their depths are compared: at its
/// sharpest angle and four spread over its angles, ascending, each reported kink of the
/// angle's flagged cells (a reported kink is the bottom of its valley: the residual peaks
/// there exactly, on the lower side where the surface jumps, a neighbour-set switch of
/// scattered data), then the general search around the sampled flags away from them.
fn probes(grid: &[Option<Flag>], cells: &[(usize, usize)], delta: f64) -> Vec<(usize, Probe)> {
    let mut angles: Vec<usize> = cells.iter().map(|c| c.0).collect();
    angles.sort_unstable();
    angles.dedup();
    let mut reps: Vec<usize> = (0..SPREAD_ANGLES)
        .map(|q| angles[q * angles.len() / SPREAD_ANGLES])
        .collect();
    reps.push(sharpest_cell(grid, cells).0);
    reps.sort_unstable();
    reps.dedup();
    let mut out = Vec::new();
    for i in reps {
        let row: Vec<(usize, Flag)> = cells
            .iter()
            .filter(|c| c.0 == i)
            .map(|&c| (c.1, flag_of(grid, c)))
            .collect();
        let kinks: Vec<f64> = row.iter().filter_map(|(_, f)| f.exact).collect();
        out.extend(kinks.iter().map(|&t| (i, Probe::Kink(t))));
        let sampled = row.iter().filter(|(j, f)| {
            f.exact.is_none()
                && kinks
                    .iter()
                    .all(|t| (t - delta * *j as f64).abs() > 2.0 * delta)
        });
        let (lo, hi) = sampled.fold((usize::MAX, 0), |(lo, hi), (j, _)| (lo.min(*j), hi.max(*j)));
        if lo <= hi {
            let search = Probe::Search(delta * lo as f64 - delta, delta * hi as f64 + delta);
            out.push((i, search));
        }
    }
    out
}

/// The zone of `cells` whose probes found `depths` ((angle index, (u, depth mm)) in the order
/// of [`probes`]): the first deepest is where it is deepest.
fn zone(
    grid: &[Option<Flag>],
    cells: &[(usize, usize)],
    delta: f64,
    depths: impl Iterator<Item = (usize, (f64, f64))>,
) -> ConcaveZone {
    let mut deepest = (0.0, Location::new(0.0, 0.0));
    for (i, (u, depth)) in depths {
        if depth > deepest.0 {
            deepest = (depth, Location::new(u, TAU * i as f64 / ANGLES as f64));
        }
    }
    let mut angles: Vec<usize> = cells.iter().map(|c| c.0).collect();
    angles.sort_unstable();
    angles.dedup();
    let (from, to) = angular_extent(&angles);
    let rhos = cells.iter().map(|c| c.1 as f64 * delta);
    let step = 360.0 / ANGLES as f64;
    ConcaveZone {
        rho_min_mm: rhos.clone().fold(f64::INFINITY, f64::min),
        rho_max_mm: rhos.fold(0.0, f64::max),
        theta_from_deg: from as f64 * step,
        theta_to_deg: to as f64 * step,
        min_curvature_radius_mm: flag_of(grid, sharpest_cell(grid, cells)).radius,
        slope_kink: cells.iter().any(|&c| flag_of(grid, c).kink),
        depth_um: deepest.0 * 1e3,
        at: deepest.1,
    }
}

/// The smallest arc of angle indices covering `sorted` (first, last), across 0 if shorter.
fn angular_extent(sorted: &[usize]) -> (usize, usize) {
    let n = sorted.len();
    let mut best_gap = (ANGLES + sorted[0] - sorted[n - 1], n - 1);
    for k in 0..n - 1 {
        let gap = sorted[k + 1] - sorted[k];
        if gap > best_gap.0 {
            best_gap = (gap, k);
        }
    }
    let k = best_gap.1;
    (sorted[(k + 1) % n], sorted[k])
}

/// The nose envelope along one radial section.
struct Envelope<'a> {
    surface: &'a dyn Surface,
    nose: &'a NoseCompensator,
    /// The nose's certificate on the surface ([`NoseCompensator::concavity`]), proven once.
    concavity: Option<Concavity>,
    c: f64,
    s: f64,
    half_width: f64,
    part_radius: f64,
}

/// Iterations of golden-section search: shrinks an interval by 0.618^40 ≈ 4·10⁻⁹ (the
/// brackets are a few µm wide, so positions come out to 10⁻¹¹ mm).
const GOLDEN_ITERATIONS: usize = 40;
/// Angles spread over a zone (besides its sharpest) where the depth is computed.
const SPREAD_ANGLES: usize = 4;
/// Tool positions scanned across the nose width before refining the envelope at one u.
const RESIDUAL_SCAN: usize = 32;
/// Coarse residual peaks refined per section.
const REFINED_PEAKS: usize = 2;

impl<'a> Envelope<'a> {
    fn new(
        surface: &'a dyn Surface,
        nose: &'a NoseCompensator,
        concavity: Option<Concavity>,
        theta: f64,
        part_radius: f64,
    ) -> Self {
        let (s, c) = theta.sin_cos();
        let half_width = nose.reach();
        Self {
            surface,
            nose,
            concavity,
            c,
            s,
            half_width,
            part_radius,
        }
    }

    fn center(&self, rho_s: f64) -> Result<f64, UndefinedError> {
        Ok(self
            .nose
            .compensate_from(self.surface, self.concavity, rho_s, self.c, self.s, None)?
            .z_center)
    }

    fn arc(&self, z_center: f64, offset: f64) -> f64 {
        z_center - self.nose.edge_depth(offset)
    }

    fn sag(&self, u: f64) -> Result<f64, UndefinedError> {
        self.surface.sag(u * self.c, u * self.s)
    }

    /// The closing residual at a reported kink u, mm: the nose envelope there less the surface,
    /// read at u and either side ([`KINK_SIDE`]): where it jumps, the lower side leaves the
    /// larger residual.
    fn residual_at_kink(
        &self,
        u: f64,
        row: Option<&ScanRow>,
        delta: f64,
    ) -> Result<f64, UndefinedError> {
        let step = KINK_SIDE * u.abs().max(1.0);
        let lowest = [u - step, u + step]
            .into_iter()
            .filter(|v| v.abs() <= self.part_radius)
            .try_fold(self.sag(u)?, |m, v| {
                Ok::<_, UndefinedError>(m.min(self.sag(v)?))
            })?;
        Ok((self.envelope_at(u, row, delta)? - lowest).max(0.0))
    }

    /// The tool positions whose arc covers u, `[lo, hi]`, mm.
    fn covering(&self, u: f64) -> (f64, f64) {
        let lo = (u - self.half_width).max(-self.part_radius);
        let hi = (u + self.half_width).min(self.part_radius);
        (lo, hi)
    }

    /// The spacing of the scan of tool positions, mm: the sample spacing δ, or finer to give a
    /// nose narrower than 32 δ its [`RESIDUAL_SCAN`] positions.
    fn scan_step(&self, delta: f64) -> f64 {
        (2.0 * self.half_width / RESIDUAL_SCAN as f64).min(delta)
    }

    /// The lattice indices k of the scan's positions `k·step` inside the positions covering u.
    fn lattice(&self, u: f64, delta: f64) -> std::ops::RangeInclusive<i64> {
        let (lo, hi) = self.covering(u);
        let step = self.scan_step(delta);
        ((lo / step).ceil() as i64)..=((hi / step).floor() as i64)
    }

    /// The tool position of lattice index `k`, mm (within the part).
    fn lattice_position(&self, k: i64, delta: f64) -> f64 {
        (k as f64 * self.scan_step(delta)).clamp(-self.part_radius, self.part_radius)
    }

    /// The nose envelope at u, mm: a coarse scan of tool positions whose arc covers u (its ends
    /// and the lattice between them, the heights read from `row` where it has them), refined
    /// by golden-section search.
    fn envelope_at(
        &self,
        u: f64,
        row: Option<&ScanRow>,
        delta: f64,
    ) -> Result<f64, UndefinedError> {
        let (lo, hi) = self.covering(u);
        let step = self.scan_step(delta);
        let mut best = (u, f64::INFINITY);
        let mut scan = |p: f64, z_center: f64| {
            let cut = self.arc(z_center, u - p);
            if cut < best.1 {
                best = (p, cut);
            }
        };
        scan(lo, self.center(lo)?);
        for k in self.lattice(u, delta) {
            let p = self.lattice_position(k, delta);
            match row.and_then(|r| r.at(k)) {
                Some(z) => scan(p, z),
                None => scan(p, self.center(p)?),
            }
        }
        scan(hi, self.center(hi)?);
        let (_, cut) = golden((best.0 - step).max(lo), (best.0 + step).min(hi), |q| {
            Ok(-self.arc(self.center(q)?, u - q))
        })?;
        Ok((-cut).min(best.1))
    }

    /// The largest closing residual for u in `[lo, hi]`: (u, residual), mm.
    fn deepest(&self, lo: f64, hi: f64, delta: f64) -> Result<(f64, f64), UndefinedError> {
        let lo = lo.max(0.0);
        let hi = hi.min(self.part_radius);
        let step = (delta / 2.0)
            .min(self.nose.nose_radius() / 400.0)
            .min((hi - lo).max(delta) / 8.0);
        let first = (lo - self.half_width).max(-self.part_radius);
        let last = (hi + self.half_width).min(self.part_radius);
        let step = step.max((last - first) / MAX_SECTION_SAMPLES);
        let count = ((last - first) / step).ceil() as usize + 1;
        let mut positions = Vec::with_capacity(count);
        for k in 0..count {
            let p = (first + step * k as f64).min(last);
            positions.push((p, self.center(p)?));
        }
        // The positions whose arc covers u: a window of the sorted positions.
        let coarse = |u: f64| -> Option<(f64, f64)> {
            let a = positions.partition_point(|(p, _)| *p < u - self.half_width);
            let b = positions.partition_point(|(p, _)| *p <= u + self.half_width);
            positions[a..b]
                .iter()
                .map(|&(p, zc)| (p, self.arc(zc, u - p)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
        };
        // The coarse residual over-estimates (its envelope is a minimum over fewer positions):
        // it only says where to refine.
        let mut samples = Vec::new();
        let mut u = lo;
        while u <= hi + 1e-15 {
            if let Some((_, cut)) = coarse(u) {
                samples.push((u, cut - self.sag(u)?));
            }
            u += step;
        }
        let mut peaks: Vec<(f64, f64)> = (0..samples.len())
            .filter(|&k| {
                let left = k == 0 || samples[k - 1].1 <= samples[k].1;
                let right = k + 1 == samples.len() || samples[k + 1].1 <= samples[k].1;
                left && right
            })
            .map(|k| samples[k])
            .collect();
        peaks.sort_by(|a, b| b.1.total_cmp(&a.1));
        peaks.truncate(REFINED_PEAKS);
        let residual = |u: f64| -> Result<f64, UndefinedError> {
            let Some((p, _)) = coarse(u) else {
                return Ok(f64::NEG_INFINITY);
            };

            let lo_p = (p - step).max(u - self.half_width);
            let hi_p = (p + step).min(u + self.half_width);
            let (_, cut) = golden(lo_p, hi_p, |q| Ok(-self.arc(self.center(q)?, u - q)))?;
            Ok(-cut - self.sag(u)?)
        };
        let mut best = (lo, 0.0);
        for (u0, _) in peaks {
            let (u, res) = golden((u0 - step).max(lo), (u0 + step).min(hi), residual)?;
            if res > best.1 {
                best = (u, res);
            }
        }
        Ok(best)
    }
}

/// Golden-section search for the maximum of `f` on `[a, b]`: (argmax, max).
fn golden(
    mut a: f64,
    mut b: f64,
    mut f: impl FnMut(f64) -> Result<f64, UndefinedError>,
) -> Result<(f64, f64), UndefinedError> {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let mut x1 = b - g * (b - a);
    let mut x2 = a + g * (b - a);
    let (mut f1, mut f2) = (f(x1)?, f(x2)?);
    for _ in 0..GOLDEN_ITERATIONS {
        if f1 < f2 {
            a = x1;
            (x1, f1) = (x2, f2);
            x2 = a + g * (b - a);
            f2 = f(x2)?;
        } else {
            b = x2;
            (x2, f2) = (x1, f1);
            x1 = b - g * (b - a);
            f1 = f(x1)?;
        }
    }
    Ok(if f1 > f2 { (x1, f1) } else { (x2, f2) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::ToolSpec;
    use crate::surface::Local;

    /// A rotationally symmetric V-groove `z = k·|ρ − ρ₀|`.
    #[derive(Debug)]
    struct Groove {
        k: f64,
        rho0: f64,
    }

    impl Surface for Groove {
        fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
            let rho = x.hypot(y);
            let d = rho - self.rho0;
            let slope = self.k * d.signum();
            let (cx, cy) = if rho > 0.0 {
                (x / rho, y / rho)
            } else {
                (1.0, 0.0)
            };
            // The bend of the circle of radius ρ adds a tangential second derivative.
            let t = if rho > 0.0 { slope / rho } else { 0.0 };
            Ok(Local {
                z: self.k * d.abs(),
                zx: slope * cx,
                zy: slope * cy,
                zxx: t * cy * cy,
                zxy: -t * cx * cy,
                zyy: t * cx * cx,
            })
        }
        fn feature_length_mm(&self) -> f64 {
            0.5
        }
        fn describe(&self) -> String {
            "groove".into()
        }
    }

    /// The concave zones of `surface` (part radius 4 mm) under a nose of radius r and included
    /// angle 100°, and that nose.
    fn zones_under(surface: &dyn Surface, r: f64) -> (NoseCompensator, Vec<ConcaveZone>) {
        let nose = NoseCompensator::new(
            &ToolSpec {
                nose_radius_mm: r,
                included_angle_deg: 100.0,
                ..ToolSpec::with_nose_radius(0.0)
            },
            0.5,
            4.0,
        )
        .unwrap();
        let zones = concave_zones(surface, &nose, 4.0, &mut crate::progress::ignore)
            .unwrap()
            .zones;
        (nose, zones)
    }

    #[test]
    fn a_v_groove_leaves_the_closed_form_fillet() {
        // The nose rests on both walls: its tip stays r·(1/cos α − 1) above the groove bottom.
        let (k, r) = (0.2, 0.5);
        let groove = Groove { k, rho0: 2.0 };
        let (_, zones) = zones_under(&groove, r);
        assert_eq!(zones.len(), 1, "{zones:?}");
        let z = &zones[0];
        let alpha = k.atan();
        let expect_um = r * (1.0 / alpha.cos() - 1.0) * 1e3;
        assert!(
            (z.depth_um - expect_um).abs() < 1e-3,
            "{} vs {expect_um}",
            z.depth_um
        );
        assert!((z.at.rho_mm - 2.0).abs() < 1e-6);
        assert!(z.slope_kink);
        assert!(z.rho_min_mm <= 2.0 && z.rho_max_mm >= 2.0);
        // The ring spans all angles.
        assert_eq!((z.theta_to_deg - z.theta_from_deg + 360.0) % 360.0, 359.0);
    }

    /// The groove with its outer wall lowered by `step` at ρ₀ (a jump, as where scattered
    /// data's neighbour set switches), the kink reported on the radial sections.
    #[derive(Debug)]
    struct SteppedGroove {
        groove: Groove,
        step: f64,
    }

    impl Surface for SteppedGroove {
        fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
            let mut l = self.groove.local(x, y)?;
            if x.hypot(y) > self.groove.rho0 {
                l.z -= self.step;
            }
            Ok(l)
        }
        fn slope_kinks(&self, _line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
            let rho0 = self.groove.rho0;
            out.extend([-rho0, rho0].into_iter().filter(|t| *t > t0 && *t < t1));
        }
        fn feature_length_mm(&self) -> f64 {
            0.5
        }
        fn describe(&self) -> String {
            "stepped groove".into()
        }
    }

    #[test]
    fn a_stepped_groove_is_measured_on_its_lower_side() {
        // The surface jumps down by 1 µm at the groove's bottom: the form error there is the
        // nose envelope less the lower side, which the surface gives just beyond the kink
        // (exactly at it, the upper one). Against the envelope by brute force: the lowest of
        // the nose arcs over ρ₀, on a grid of tool positions and again around its best.
        let (k, r, step, rho0) = (0.2, 0.5, 1e-3, 2.0);
        let surface = SteppedGroove {
            groove: Groove { k, rho0 },
            step,
        };
        let (nose, zones) = zones_under(&surface, r);
        let deepest = zones.iter().map(|z| z.depth_um).fold(0.0, f64::max);
        let arc_at_rho0 = |p: f64| {
            let zc = nose.compensate(&surface, p, 1.0, 0.0).unwrap().z_center;
            zc - (r * r - (rho0 - p) * (rho0 - p)).sqrt()
        };
        let lowest = |from: f64, to: f64, n: usize| {
            (0..=n)
                .map(|i| from + (to - from) * i as f64 / n as f64)
                .map(|p| (arc_at_rho0(p), p))
                .fold((f64::INFINITY, from), |b, c| if c.0 < b.0 { c } else { b })
        };
        let (_, p) = lowest(rho0 - 0.9 * r, rho0 + 0.9 * r, 2_000);
        let (cut, _) = lowest(p - 1e-3, p + 1e-3, 20_000);
        let expect_um = (cut - (-step)) * 1e3;
        assert!(expect_um > 1.0, "{expect_um}");
        assert!(
            (deepest - expect_um).abs() < 1e-3,
            "{deepest} µm vs {expect_um} µm"
        );
    }

    /// V-grooves `z = k·min_g |ρ − ρ_g|` closer together than the nose is wide, their valleys
    /// and the ridges between them reported as kinks.
    #[derive(Debug)]
    struct Grooves {
        k: f64,
        at: [f64; 3],
    }

    impl Surface for Grooves {
        fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
            let rho = x.hypot(y);
            let nearest = (self.at.iter())
                .min_by(|a, b| (rho - *a).abs().total_cmp(&(rho - *b).abs()))
                .copied()
                .unwrap_or(0.0);
            Groove {
                k: self.k,
                rho0: nearest,
            }
            .local(x, y)
        }
        fn slope_kinks(&self, _line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
            let ridges = self.at.windows(2).map(|w| (w[0] + w[1]) / 2.0);
            let kinks = self.at.into_iter().chain(ridges);
            out.extend(kinks.filter(|t| *t > t0 && *t < t1));
        }
        fn feature_length_mm(&self) -> f64 {
            0.2
        }
        fn describe(&self) -> String {
            "grooves".into()
        }
    }

    #[test]
    fn kink_probes_share_their_scans_and_find_what_their_own_would() {
        // Three valleys 0.2 mm apart under a nose 0.77 mm wide: their scans overlap. The
        // envelope read from the shared heights is the one each probe's own scan gives, to
        // the bit, and the section computes fewer heights than the three scans would.
        let surface = Grooves {
            k: 0.2,
            at: [1.8, 2.0, 2.2],
        };
        let (nose, zones) = zones_under(&surface, 0.5);
        assert_eq!(zones.len(), 3, "{zones:?}");
        let delta = 4.0 / 1000.0;
        let section = |i: usize| Envelope::new(&surface, &nose, None, TAU * i as f64 / 360.0, 4.0);
        let probes: Vec<(usize, usize, Probe)> = (surface.at.iter())
            .map(|&t| (0, 7, Probe::Kink(t)))
            .collect();
        let scans = KinkScans::of(&probes, delta, &section).unwrap();
        let row = scans.row(7).expect("the section's row");
        assert!(scans.row(8).is_none());
        let env = section(7);
        let own: usize = (surface.at.iter())
            .map(|&t| env.lattice(t, delta).count())
            .sum();
        let union = *env.lattice(1.8, delta).start()..=*env.lattice(2.2, delta).end();
        assert_eq!(row.z_center.len(), union.count());
        assert!(
            row.z_center.len() * 3 < own * 2,
            "{} of {own}",
            row.z_center.len()
        );
        for (_, _, probe) in probes {
            let shared = probe.depth(&env, Some(row), delta).unwrap();
            let alone = probe.depth(&env, None, delta).unwrap();
            assert_eq!(shared.1.to_bits(), alone.1.to_bits(), "{probe:?}");
            assert!(shared.1 > 1e-4, "{shared:?}");
        }
    }

    #[test]
    fn angular_extent_crosses_zero_when_shorter() {
        assert_eq!(angular_extent(&[0, 1, 2, 358, 359]), (358, 2));
        assert_eq!(angular_extent(&[10, 11, 12]), (10, 12));
    }
}
