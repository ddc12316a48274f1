//! Hybrid constant-angle / constant-arc sampling (HCAA, paper 000, "HCAA method" and
//! "Evaluation of critical machining parameters for HCAA method") and adaptive sampling: the
//! largest steps along the spiral that keep the cutting linearization error PVerr
//! ([`crate::analysis::linearization`]) under a tolerance.
//!
//! **Error of one step.** The controller moves C, X and Z linearly between NC points, so along a
//! segment θ and ρ are linear in the angle travelled t and the error is the chord error of the
//! compensated tip height `z*(ρ − b·t, θ + t)` (b = f/2π) over `t ∈ [0, Δθ]`:
//! `|e| ≤ Δθ²·Q/8`, `Q = max |d²z*/dt²|` (the chord error κL²/8 of a section of curvature κ,
//! written in the angle). Because the interpolation is polar, a surface of revolution has
//! `d²z*/dt² = b²·z*_ρρ` only (the feed's share, ~1e-8 of the height's curvature): its error
//! vanishes at any Δθ, which is why paper 000 finds 180° enough in its rotationally symmetric
//! outer and inner regions. Where the surface varies along the circle,
//! `d²z*/dt² ≈ ρ²·z_vv − ρ·z_u` (v along the circle, u radial): Δθ must shrink as 1/ρ where that
//! curvature is uniform, i.e. a constant arc length `ΔS = ρ·Δθ = √(8·tol/κ_t)`.
//!
//! **Estimate.** Q is measured on the compensated height itself (so the nose's smoothing of
//! convex and sharpening of concave features counts), by second differences along the spiral
//! `c_j = z*(ρ + bh, θ_j − h) − 2 z*(ρ, θ_j) + z*(ρ − bh, θ_j + h)` on circles `ρ_i`, h = 2π/M.
//! A smooth section gives `c = Q·h²`, hence `Δθ ≤ h·√(8·tol/|c|)`. Across a slope kink (a
//! lenslet rim; the nose's contact jumping between lenslets) the chord error is not κL²/8 but
//! up to `Δm·Δθ/4` (Δm the jump of dz*/dt, kink mid-segment), and the largest second difference
//! next to a kink is at least `Δm·h/2`, hence `Δθ ≤ 2·tol·h/|c|`. Each sample's step is the
//! smaller of the two, so kinks are held without knowing where they are; on smooth sections the
//! kink bound is the smaller only while `h > Δθ/4`, so a circle is resampled (up to twice, M up
//! to [`MAX_SAMPLES`]) until `h ≤ Δθ/4`. M starts at 8 samples per feature length
//! ([`crate::surface::Surface::feature_length_mm`]) along the circle, at least [`MIN_SAMPLES`].
//! A band between two circles takes the smaller step of the two; the tolerance used is
//! [`SAFETY`] × the one asked for (curvature between circles, the asymptotic chord formula),
//! and no step exceeds [`MAX_STEP_RAD`] (180°, paper 000: at least two points per revolution).
//! The bands are `max(f, feature/8)` wide, at most [`MAX_BANDS`].
//!
//! **HCAA.** Paper 000 starts with constant angle at the outer radius, switches to constant arc
//! at `r_trans1` and back to constant angle at `r_trans2` (3.9865 mm and 0.2782 mm, ΔS 0.0175 mm
//! for PVtol 1 µm on its compound eye). Which rule wins where follows from the error above:
//! constant angle holds the tolerance with the fewest points where the required Δθ does not
//! fall with ρ (rotationally symmetric zones: the outer rim and the central lenslet), constant
//! arc where the required Δθ falls as 1/ρ (a uniform field of features along the circle).
//! Here the two transition radii are chosen among the band edges to minimise the point count:
//! outer zone Δθ_o = the smallest required step outside r₁, middle ΔS = min over its bands of
//! `ρ_inner·Δθ_req` (so that `ΔS/ρ ≤ Δθ_req` everywhere in the band), inner Δθ_i = the smallest
//! required step inside r₂. r₁ = r₂ is plain constant angle in two zones, r₁ = R no outer zone.
//!
//! **Adaptive.** One constant-angle zone per band (about one revolution's feed wide or one
//! eighth of a feature): the step follows the required Δθ radius by radius.

use super::PathError;
use super::spiral::{MAX_POINTS_PER_REV, Spiral, Step, Zone, arc_length};
use crate::field::FieldError;
use crate::job::{Compensation, Sampling, StrategySpec};
use crate::parallel::{fill_chunks, workers};
use crate::progress::{Progress, ProgressFn, Stage};
use crate::surface::{Surface, UndefinedError};
use std::f64::consts::{PI, TAU};
use std::sync::atomic::{AtomicU64, Ordering};

/// Fraction of the tolerance the estimate plans for.
pub const SAFETY: f64 = 0.7;
/// Largest angle step, radians (180°, paper 000).
pub const MAX_STEP_RAD: f64 = PI;
/// Fewest samples on a circle.
pub const MIN_SAMPLES: usize = 64;
/// Most samples on a circle.
pub const MAX_SAMPLES: usize = 1 << 16;
/// Most radius bands.
pub const MAX_BANDS: usize = 512;
/// Most compensated heights one estimate computes: 3·10⁷, about two minutes on two cores for
/// a smooth surface (the paper000 compound eye at 0.1 µm takes 8.6·10⁶ in 23 s).
pub const MAX_BAND_HEIGHTS: u64 = 30_000_000;
/// Samples per feature length along a circle, before refinement.
const SAMPLES_PER_FEATURE: f64 = 8.0;

/// The largest angle step that holds the tolerance, per radius band.
#[derive(Debug, Clone, PartialEq)]
pub struct Bands {
    /// Band edges, mm, ascending from 0 to the outer radius (one more than the bands).
    pub edges_mm: Vec<f64>,
    /// Largest angle step of each band, radians, in (0, [`MAX_STEP_RAD`]].
    pub step_rad: Vec<f64>,
    /// Feed per revolution, mm.
    pub feed_mm: f64,
    /// The PV tolerance the steps hold, mm (before [`SAFETY`]).
    pub tolerance_mm: f64,
}

/// The compensated tip height `z*(ρ, θ)` the estimate samples: the one-way compensation of the
/// job's nose ([`crate::tool::NoseCompensator::compensate`]), given by the caller so that the
/// sampler needs no tool.
pub type TipHeight<'a> = dyn Fn(f64, f64) -> Result<f64, UndefinedError> + Sync + 'a;

/// The compensated heights the estimate has computed, against [`MAX_BAND_HEIGHTS`].
struct HeightCount(AtomicU64);

impl HeightCount {
    /// Counts `m` more heights, or refuses once the total would pass the bound.
    fn take(&self, m: usize) -> Result<(), PathError> {
        let total = self.0.fetch_add(m as u64, Ordering::Relaxed) + m as u64;
        if total > MAX_BAND_HEIGHTS {
            return Err(too_costly(total, "computed so far").into());
        }
        Ok(())
    }
}

/// The refusal of an estimate that would compute more than [`MAX_BAND_HEIGHTS`] heights.
fn too_costly(heights: u64, when: &str) -> FieldError {
    FieldError::new(
        "sampling.type",
        format!("{heights} compensated heights {when}"),
        format!(
            "the hcaa and adaptive estimates compute at most {MAX_BAND_HEIGHTS:.0e} heights: \
             the surface's features are too fine for them; use constant_angle or constant_arc \
             sampling"
        ),
    )
}

/// Largest step on the circle of radius `rho` (see the module docs), with M samples.
fn circle_step_with(
    tip: &TipHeight,
    count: &HeightCount,
    rho: f64,
    b: f64,
    tol: f64,
    m: usize,
) -> Result<(f64, f64), PathError> {
    let h = TAU / m as f64;
    let ring = |r: f64| -> Result<Vec<f64>, PathError> {
        count.take(m)?;
        Ok((0..m)
            .map(|j| tip(r, h * j as f64))
            .collect::<Result<_, _>>()?)
    };
    let (zp, z0, zm) = (
        ring(rho + b * h)?,
        ring(rho)?,
        ring((rho - b * h).max(0.0))?,
    );
    let (mut step, mut smooth) = (MAX_STEP_RAD, MAX_STEP_RAD);
    for j in 0..m {
        let c = (zp[(j + m - 1) % m] - 2.0 * z0[j] + zm[(j + 1) % m]).abs();
        if c > 0.0 {
            let s = h * (8.0 * tol / c).sqrt();
            smooth = smooth.min(s);
            step = step.min(s).min(2.0 * tol * h / c);
        }
    }
    Ok((step, smooth))
}

/// Largest step on the circle of radius `rho`, resampled until `h ≤ Δθ/4` (at most twice).
fn circle_step(
    surface: &dyn Surface,
    (tip, count): (&TipHeight, &HeightCount),
    rho: f64,
    b: f64,
    tol: f64,
) -> Result<f64, PathError> {
    let mut m = first_samples(surface, rho);
    let mut best = 0.0f64;
    for _ in 0..3 {
        let (step, smooth) = circle_step_with(tip, count, rho, b, tol, m)?;
        best = best.max(step);
        let want = ((4.0 * TAU / smooth).ceil() as usize).min(MAX_SAMPLES);
        if want <= m {
            break;
        }
        m = want;
    }
    Ok(best)
}

/// The samples M a circle of radius `rho` starts with: 8 per feature length along it.
fn first_samples(surface: &dyn Surface, rho: f64) -> usize {
    let along = surface.feature_length_mm() / SAMPLES_PER_FEATURE;
    ((TAU * rho / along).ceil() as usize).clamp(MIN_SAMPLES, MAX_SAMPLES)
}

/// The largest step per radius band from 0 to `outer_radius_mm` for PVerr ≤ `tolerance_mm`.
/// The estimate is refused up front when its first pass alone would compute more than
/// [`MAX_BAND_HEIGHTS`] heights, and stopped when its resampling would; `progress` sees the
/// circles done ([`Stage::Bands`]) and may cancel.
pub fn bands(
    surface: &dyn Surface,
    tip: &TipHeight,
    (outer_radius_mm, feed_mm, tolerance_mm): (f64, f64, f64),
    progress: &mut ProgressFn,
) -> Result<Bands, PathError> {
    let width = feed_mm.max(surface.feature_length_mm() / SAMPLES_PER_FEATURE);
    let n = ((outer_radius_mm / width).ceil() as usize).clamp(1, MAX_BANDS);
    let edges: Vec<f64> = (0..=n)
        .map(|i| outer_radius_mm * i as f64 / n as f64)
        .collect();
    let b = feed_mm / TAU;
    let tol = SAFETY * tolerance_mm;
    // Circle 0 sits one sample's feed off the centre, so that its inner ring is the centre.
    let radius = |i: usize| edges[i].max(b * TAU / MIN_SAMPLES as f64);
    let first_pass: u64 = (0..=n)
        .map(|i| 3 * first_samples(surface, radius(i)) as u64)
        .sum();
    if first_pass > MAX_BAND_HEIGHTS {
        return Err(too_costly(first_pass, "in its first pass").into());
    }
    let count = HeightCount(AtomicU64::new(0));
    let mut circles = vec![0.0; n + 1];
    let batch = 2 * workers();
    for (k, part) in circles.chunks_mut(batch).enumerate() {
        let first = k * batch;
        fill_chunks(part, |start, out| {
            for (j, slot) in out.iter_mut().enumerate() {
                let rho = radius(first + start + j);
                *slot = circle_step(surface, (tip, &count), rho, b, tol)?;
            }
            Ok::<(), PathError>(())
        })?;
        let done = (first + part.len()) as u64;
        let total = (n + 1) as u64;
        if progress(Progress {
            stage: Stage::Bands,
            done,
            total,
        })
        .is_break()
        {
            return Err(PathError::Cancelled);
        }
    }
    let step_rad = circles.windows(2).map(|w| w[0].min(w[1])).collect();
    Ok(Bands {
        edges_mm: edges,
        step_rad,
        feed_mm,
        tolerance_mm,
    })
}

/// The three zones of HCAA and their figures.
#[derive(Debug, Clone, PartialEq)]
pub struct Hcaa {
    /// r_trans1: constant angle outside, constant arc inside, mm (= outer radius: no outer zone).
    pub outer_transition_mm: f64,
    /// r_trans2: constant arc outside, constant angle inside, mm (= r_trans1: no arc zone).
    pub inner_transition_mm: f64,
    /// Angle step outside r_trans1, radians.
    pub outer_step_rad: f64,
    /// Arc length between r_trans1 and r_trans2, mm (NaN without an arc zone).
    pub arc_length_mm: f64,
    /// Angle step inside r_trans2, radians.
    pub inner_step_rad: f64,
    /// Estimated points.
    pub points: f64,
}

impl Hcaa {
    /// The zones, outside in.
    pub fn zones(&self) -> Vec<Zone> {
        let mut z = vec![Zone {
            inner_radius_mm: self.outer_transition_mm,
            step: Step::Angle {
                step_rad: self.outer_step_rad,
            },
        }];
        if self.inner_transition_mm < self.outer_transition_mm {
            z.push(Zone {
                inner_radius_mm: self.inner_transition_mm,
                step: Step::Arc {
                    arc_length_mm: self.arc_length_mm,
                    max_step_rad: MAX_STEP_RAD,
                },
            });
        }
        z.push(Zone {
            inner_radius_mm: 0.0,
            step: Step::Angle {
                step_rad: self.inner_step_rad,
            },
        });
        z
    }
}

impl Bands {
    fn b(&self) -> f64 {
        self.feed_mm / TAU
    }

    /// HCAA: the transition radii (band edges) that need the fewest points.
    pub fn hcaa(&self) -> Hcaa {
        let (e, s, b) = (&self.edges_mm, &self.step_rad, self.b());
        let n = s.len();
        let phi = |i: usize| e[i] / b;
        // prefix[a]: smallest step of bands [0, a); suffix[c]: of bands [c, n).
        let mut prefix = vec![MAX_STEP_RAD; n + 1];
        for i in 0..n {
            prefix[i + 1] = prefix[i].min(s[i]);
        }
        let mut suffix = vec![MAX_STEP_RAD; n + 1];
        for i in (0..n).rev() {
            suffix[i] = suffix[i + 1].min(s[i]);
        }
        let mut best = Hcaa {
            outer_transition_mm: e[n],
            inner_transition_mm: e[n],
            outer_step_rad: prefix[n],
            arc_length_mm: f64::NAN,
            inner_step_rad: prefix[n],
            points: phi(n) / prefix[n],
        };
        for a in 1..=n {
            let inner = phi(a) / prefix[a];
            let mut ds = f64::INFINITY;
            for c in a..=n {
                if c > a {
                    ds = ds.min(e[c - 1] * s[c - 1]);
                }
                let outer = (phi(n) - phi(c)) / suffix[c];
                let middle = if c > a {
                    Step::Arc {
                        arc_length_mm: ds,
                        max_step_rad: MAX_STEP_RAD,
                    }
                    .count(b, phi(a), phi(c))
                } else {
                    0.0
                };
                let points = inner + middle + outer;
                if points < best.points {
                    best = Hcaa {
                        outer_transition_mm: e[c],
                        inner_transition_mm: e[a],
                        outer_step_rad: suffix[c],
                        arc_length_mm: if c > a { ds } else { f64::NAN },
                        inner_step_rad: prefix[a],
                        points,
                    };
                }
            }
        }
        best
    }

    /// Adaptive: one constant-angle zone per band, outside in.
    pub fn adaptive(&self) -> Vec<Zone> {
        (0..self.step_rad.len())
            .rev()
            .map(|i| Zone {
                inner_radius_mm: self.edges_mm[i],
                step: Step::Angle {
                    step_rad: self.step_rad[i],
                },
            })
            .collect()
    }

    /// Points per revolution of the uniform constant-angle sampling that holds the same
    /// tolerance: `⌈2π / smallest step⌉`, at least 3.
    pub fn uniform_points_per_rev(&self) -> u32 {
        let min = self.step_rad.iter().copied().fold(MAX_STEP_RAD, f64::min);
        ((TAU / min).ceil().max(3.0) as u32).min(MAX_POINTS_PER_REV)
    }
}

/// One line for the NC header: the sampling, its tolerance and its zones.
pub fn describe(sampling: &Sampling, pv_tolerance_um: f64, zones: &[Zone]) -> String {
    match sampling {
        Sampling::Hcaa { .. } => {
            let parts: Vec<String> = zones
                .iter()
                .map(|z| match z.step {
                    Step::Angle { step_rad } => format!(
                        "angle {:.4} deg to r {:.4} mm",
                        step_rad.to_degrees(),
                        z.inner_radius_mm
                    ),
                    Step::Arc { arc_length_mm, .. } => {
                        format!("arc {arc_length_mm:.6} mm to r {:.4} mm", z.inner_radius_mm)
                    }
                })
                .collect();
            format!("hcaa pv {pv_tolerance_um} um: {}", parts.join(", "))
        }
        _ => format!("adaptive pv {pv_tolerance_um} um, {} zones", zones.len()),
    }
}

/// Arc length of the spiral `ρ = bφ` between radii, mm (for reports).
pub fn spiral_length_mm(feed_mm: f64, inner_mm: f64, outer_mm: f64) -> f64 {
    let b = feed_mm / TAU;
    arc_length(b, outer_mm / b) - arc_length(b, inner_mm / b)
}

/// The spiral of an `hcaa` or `adaptive` strategy on `surface`: zones from [`bands`] (any other
/// sampling is refused: [`crate::tool::spiral`] picks the builder). Field errors are named from
/// `strategy`.
pub fn spiral(
    outer_radius_mm: f64,
    strategy: &StrategySpec,
    surface: &dyn Surface,
    tip: &TipHeight,
    progress: &mut ProgressFn,
) -> Result<Spiral, PathError> {
    let st = strategy;
    let within = |e: FieldError| e.within("strategy");
    let tol_um = match st.sampling {
        Sampling::Hcaa { pv_tolerance_um } | Sampling::Adaptive { pv_tolerance_um } => {
            pv_tolerance_um
        }
        _ => {
            return Err(within(FieldError::new(
                "sampling.type",
                format!("{:?}", st.sampling),
                "is not hcaa or adaptive: plan it with spiralcam::tool::spiral",
            ))
            .into());
        }
    };
    if st.compensation == Compensation::TwoWay {
        return Err(within(FieldError::new(
            "sampling.type",
            match st.sampling {
                Sampling::Hcaa { .. } => "hcaa",
                _ => "adaptive",
            },
            "estimates the linearization error of one-way compensation: use \"compensation\": \"one_way\" or a constant-angle or constant-arc sampling",
        ))
        .into());
    }
    // Check the fields before the (costly) estimate.
    Spiral::with_zones(
        outer_radius_mm,
        st.feed_mm_per_rev,
        &st.sampling,
        &[Zone {
            inner_radius_mm: 0.0,
            step: Step::Angle { step_rad: PI },
        }],
        st.direction,
        st.start_angle_deg,
    )
    .map_err(within)?;
    let bands = bands(
        surface,
        tip,
        (outer_radius_mm, st.feed_mm_per_rev, tol_um * 1e-3),
        progress,
    )
    .map_err(|e| e.within("strategy"))?;
    let zones = match st.sampling {
        Sampling::Hcaa { .. } => bands.hcaa().zones(),
        _ => bands.adaptive(),
    };
    Ok(Spiral::with_zones(
        outer_radius_mm,
        st.feed_mm_per_rev,
        &st.sampling,
        &zones,
        st.direction,
        st.start_angle_deg,
    )
    .map_err(within)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat_bands(steps: &[f64]) -> Bands {
        let n = steps.len();
        Bands {
            edges_mm: (0..=n).map(|i| i as f64).collect(),
            step_rad: steps.to_vec(),
            feed_mm: 0.01,
            tolerance_mm: 1e-3,
        }
    }

    #[test]
    fn uniform_field_gives_one_arc_zone() {
        // Rotationally symmetric centre band and rim, a field of features between whose
        // required step falls as 1/ρ: HCAA puts its transitions at the field's edges.
        let mut s = vec![PI; 10];
        for (i, v) in s.iter_mut().enumerate().take(8).skip(2) {
            *v = 0.01 / (i as f64 + 1.0);
        }
        let h = flat_bands(&s).hcaa();
        assert_eq!(h.inner_transition_mm, 2.0);
        assert_eq!(h.outer_transition_mm, 8.0);
        assert_eq!(h.outer_step_rad, PI);
        assert_eq!(h.inner_step_rad, PI);
        // ΔS = min over the arc bands of ρ_inner·Δθ = 2·0.01/3 (band [2, 3]).
        assert!((h.arc_length_mm - 0.02 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn smooth_surface_gives_the_cap() {
        let h = flat_bands(&[PI; 4]).hcaa();
        assert_eq!(h.zones().len(), 2);
        assert_eq!(flat_bands(&[PI; 4]).uniform_points_per_rev(), 3);
    }
}
