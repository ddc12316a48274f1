//! Helpers shared by the integration tests; a test file uses them with `mod common;`.
//!
//! - [`config`]: the proptest configuration of every file: a fixed seed (each file its own), no
//!   failure persistence, so that every run draws the same cases.
//! - [`check_derivatives`]: analytic gradient and second derivatives against central finite
//!   differences. With step h the central difference of a function g has truncation error
//!   `h²/6·|g‴|` and rounding error about `ε·|g|/h`. With h = 1e-5 mm, sags of a few mm and third
//!   (fourth, for the Hessian from the analytic gradient) derivatives below 10⁴ mm⁻² (mm⁻³), both
//!   stay below 2e-7 + 1e-7·|value|, the tolerance used (a wrong factor or index in any term is
//!   orders of magnitude larger).
//! - [`dense_gap`], [`NoseArc`] and [`check_planned_path`]: the brute-force gouge check of one-way
//!   nose compensation (paper 003 eqs 17–24). The nose arc of centre (ρ_s, z_c) and radius r is
//!   sampled at `samples + 1` equal steps Δa of the nose angle, plus the arc's ends and given
//!   offsets (the contact, slope kinks). Between samples the gap `g(a) = z_c − r·cos a − f(ρ_s +
//!   r·sin a)` is C² with `|g″| ≤ K = r·(1 + |f′|) + r²·|f″|`, so its true minimum is at most
//!   `K·Δa²/8` below the smallest sample: that bound is computed per point (with the sampled maxima
//!   of |f′|, |f″| doubled) and subtracted before asserting "no cut deeper than 0.1 nm"; "touches
//!   within 0.1 nm" needs no correction, the smallest sample being an upper bound of the true
//!   minimum.
//! - [`Closing`]: the brute-force morphological closing of a radial section by the nose, the
//!   oracle of the concave-zone report (its docs give its accuracy).
//! - [`field_error`] and [`check_example_jobs`]: a surface's JSON that must be refused, and the
//!   example jobs of the documentation that must plan; [`coarse_grid_fts`], the example split
//!   job coarsened for a debug build.
//! - [`half_unit`], [`c_error`] and [`split_program`]: NC words against planned values, and a
//!   program split between the slide and the fast tool servo.

#![allow(dead_code)]

use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngSeed};
use spiralcam::field::FieldError;
use spiralcam::job::Job;
use spiralcam::path::PathPoint;
use spiralcam::plan::Planner;
use spiralcam::surface::{Local, Surface, SurfaceSpec};
use std::f64::consts::TAU;

/// Finite-difference step, mm.
pub const H: f64 = 1e-5;
/// Absolute and relative tolerance of a finite-difference derivative (see the module docs).
pub const FD_ABS: f64 = 2e-7;
/// See [`FD_ABS`].
pub const FD_REL: f64 = 1e-7;
/// Contact and no-cut tolerance of the gouge check, mm (0.1 nm).
pub const TOUCH: f64 = 1e-7;

/// The proptest configuration: `cases` cases drawn from the fixed seed `seed`, no failure
/// persistence (every run checks the same cases).
pub fn config(cases: u32, seed: u64) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// The surface's local values at (x, y), panicking with the surface and the point if undefined.
pub fn local(s: &dyn Surface, x: f64, y: f64) -> Local {
    s.local(x, y)
        .unwrap_or_else(|e| panic!("{} at ({x}, {y}): {e}", s.describe()))
}

/// Compares the analytic gradient with central differences of the sag, and the analytic second
/// derivatives with central differences of the analytic gradient (both mixed derivatives),
/// within [`FD_ABS`] + [`FD_REL`]·|value| (see the module docs).
pub fn check_derivatives(s: &dyn Surface, x: f64, y: f64) -> Result<(), TestCaseError> {
    check_derivatives_within(s, x, y, FD_ABS, FD_REL)
}

/// [`check_derivatives`] within `abs + rel·|value|`, for a caller whose surface allows a
/// tighter bound than [`FD_ABS`] (it states why).
pub fn check_derivatives_within(
    s: &dyn Surface,
    x: f64,
    y: f64,
    abs: f64,
    rel: f64,
) -> Result<(), TestCaseError> {
    let l = local(s, x, y);
    let xp = local(s, x + H, y);
    let xm = local(s, x - H, y);
    let yp = local(s, x, y + H);
    let ym = local(s, x, y - H);
    let d = |p: f64, m: f64| (p - m) / (2.0 * H);
    let pairs = [
        ("dz/dx", l.zx, d(xp.z, xm.z)),
        ("dz/dy", l.zy, d(yp.z, ym.z)),
        ("d2z/dx2", l.zxx, d(xp.zx, xm.zx)),
        ("d2z/dxdy (d/dy of dz/dx)", l.zxy, d(yp.zx, ym.zx)),
        ("d2z/dxdy (d/dx of dz/dy)", l.zxy, d(xp.zy, xm.zy)),
        ("d2z/dy2", l.zyy, d(yp.zy, ym.zy)),
    ];
    for (what, analytic, fd) in pairs {
        let tol = abs + rel * analytic.abs();
        prop_assert!(
            (analytic - fd).abs() <= tol,
            "{}: {what} at ({x}, {y}): analytic {analytic}, finite difference {fd}, \
             difference {:e} > {tol:e}",
            s.describe(),
            (analytic - fd).abs()
        );
    }
    Ok(())
}

/// The outcome of the dense check of one nose position.
#[derive(Debug)]
pub struct Gap {
    /// Smallest gap between arc and surface over the samples, mm.
    pub min: f64,
    /// How far the true minimum can lie below `min`, mm.
    pub bound: f64,
    /// Offset u of the smallest sample.
    pub at: f64,
}

/// The nose arc's angle range: |a| ≤ β/2 and |ρ_s + r·sin a| ≤ the part radius.
pub fn arc_range(r: f64, half_angle: f64, rho_s: f64, limit: f64) -> (f64, f64) {
    let asin = |v: f64| v.clamp(-1.0, 1.0).asin();
    let hi = half_angle.min(asin((limit - rho_s) / r));
    let lo = (-half_angle).max(asin((-limit - rho_s) / r));
    (lo, hi)
}

/// Samples the gap between the nose arc of centre (ρ_s, z_c) and the section at angle θ, at
/// `samples + 1` equal steps of the nose angle a (u = r·sin a) plus the offsets `extra`.
#[allow(clippy::too_many_arguments)]
pub fn dense_gap(
    surface: &dyn Surface,
    r: f64,
    half_angle: f64,
    limit: f64,
    rho_s: f64,
    theta: f64,
    z_c: f64,
    extra: &[f64],
    samples: usize,
) -> Gap {
    let (s, c) = theta.sin_cos();
    let (lo, hi) = arc_range(r, half_angle, rho_s, limit);
    let da = (hi - lo) / samples as f64;
    let mut offsets: Vec<f64> = (0..=samples)
        .map(|i| r * (lo + da * i as f64).sin())
        .collect();
    offsets.push(r * hi.sin());
    let (ulo, uhi) = (r * lo.sin(), r * hi.sin());
    offsets.extend(extra.iter().copied().filter(|&u| u >= ulo && u <= uhi));
    let mut gap = Gap {
        min: f64::INFINITY,
        bound: 0.0,
        at: f64::NAN,
    };
    let (mut max_slope, mut max_curv): (f64, f64) = (0.0, 0.0);
    for u in offsets {
        let rho = rho_s + u;
        let l = local(surface, rho * c, rho * s).radial(c, s);
        let g = z_c - (r * r - u * u).max(0.0).sqrt() - l.z;
        if g < gap.min {
            gap.min = g;
            gap.at = u;
        }
        max_slope = max_slope.max(l.slope.abs());
        max_curv = max_curv.max(l.curvature_term.abs());
    }
    // g(a) = z_c − r·cos a − f(ρ_s + r·sin a): g″ = r·cos a − r²·cos²a·f″ + r·sin a·f′, so
    // |g″| ≤ r·(1 + |f′|) + r²·|f″|; the sampled maxima of |f′|, |f″| are doubled as bounds.
    let k = r * (1.0 + 2.0 * max_slope) + r * r * 2.0 * max_curv;
    gap.bound = k * da * da / 8.0;
    gap
}

/// The gouge check of one nose position `at` (named in the messages): the arc touches the
/// surface within 0.1 nm, cuts nowhere deeper than 0.1 nm once the sampling bound is subtracted,
/// and that bound stays under 0.02 nm (see the module docs).
pub fn check_gap(at: &str, gap: &Gap) -> Result<(), TestCaseError> {
    prop_assert!(
        gap.min <= TOUCH,
        "{at}: the arc does not touch, smallest gap {:e} mm",
        gap.min
    );
    prop_assert!(
        gap.min - gap.bound >= -TOUCH,
        "{at}: the arc cuts {:e} mm into the surface at u {} (sampling bound {:e})",
        -gap.min,
        gap.at,
        gap.bound
    );
    prop_assert!(
        gap.bound < 0.2 * TOUCH,
        "{at}: sampling too coarse, bound {:e}",
        gap.bound
    );
    Ok(())
}

/// The nose arc of a job: its radius, half its included angle, and the part radius that cuts it.
#[derive(Debug, Clone, Copy)]
pub struct NoseArc {
    /// Nose radius r, mm.
    pub r: f64,
    /// Half the included angle β/2, rad.
    pub half_angle: f64,
    /// The part radius, mm.
    pub limit: f64,
}

impl NoseArc {
    /// The nose arc of `job`.
    pub fn of(job: &Job) -> Self {
        Self {
            r: job.tool.nose_radius_mm,
            half_angle: (job.tool.included_angle_deg / 2.0).to_radians(),
            limit: job.part_radius_mm(),
        }
    }

    /// The arc's radial span [ρ_s + r·sin a_lo, ρ_s + r·sin a_hi] over [`arc_range`] at ρ_s.
    pub fn span(&self, rho_s: f64) -> (f64, f64) {
        let (lo, hi) = arc_range(self.r, self.half_angle, rho_s, self.limit);
        (rho_s + self.r * lo.sin(), rho_s + self.r * hi.sin())
    }

    /// [`dense_gap`] of the nose at path point `p` on `surface`: `samples` steps plus the
    /// contact and the offsets `extra` from ρ_s.
    pub fn gap(&self, surface: &dyn Surface, p: &PathPoint, extra: &[f64], samples: usize) -> Gap {
        let (s, c) = p.theta.sin_cos();
        let mut extra = extra.to_vec();
        extra.push(p.contact[0] * c + p.contact[1] * s - p.rho);
        dense_gap(
            surface,
            self.r,
            self.half_angle,
            self.limit,
            p.rho,
            p.theta,
            p.z + self.r,
            &extra,
            samples,
        )
    }
}

/// Names path point `p` of `what` in a gouge-check message.
pub fn point_name(what: &str, p: &PathPoint) -> String {
    format!("{what}: point {} (ρ {}, θ {})", p.index, p.rho, p.theta)
}

/// Plans `job_json` and checks every point of its path with [`dense_gap`] (`samples` steps,
/// the arc cut at the part radius): the nose touches the surface within 0.1 nm, cuts nowhere
/// deeper than 0.1 nm, and the sampling bound stays under 0.02 nm. `kinks(cos θ, sin θ)` lists
/// the signed radial coordinates where the section at θ has a slope kink (none for a smooth
/// surface). Returns the number of points checked, which must be the whole spiral.
pub fn check_planned_path(
    job_json: &str,
    kinks: &dyn Fn(f64, f64) -> Vec<f64>,
    samples: usize,
) -> u64 {
    let job = Job::from_json(job_json).expect("job JSON");
    let planner = Planner::new(&job).unwrap_or_else(|e| panic!("{}: {e}", job.name));
    let arc = NoseArc::of(&job);
    let mut n = 0;
    for p in planner.points() {
        let p = p.unwrap_or_else(|e| panic!("{}: {e}", job.name));
        let (s, c) = p.theta.sin_cos();
        let extra: Vec<f64> = kinks(c, s).iter().map(|k| k - p.rho).collect();
        let gap = arc.gap(planner.surface(), &p, &extra, samples);
        check_gap(&point_name(&job.name, &p), &gap).unwrap_or_else(|e| panic!("{e}"));
        n += 1;
    }
    assert_eq!(n, planner.spiral().point_count_hint());
    n
}

/// Spacing of the surface samples of [`Closing`], mm.
pub const H_U: f64 = 4e-6;
/// Accuracy of the brute-force oracle [`Closing`], mm (0.05 nm; see its docs).
pub const ORACLE_TOL: f64 = 5e-8;
/// Agreement of a reported concave-zone depth with [`Closing`], mm (1 nm).
pub const DEPTH_TOL: f64 = 1e-6;

/// Brute-force closing of one radial section by the nose, the oracle of the concave-zone report.
///
/// On the section f(u) = sag(u·cos θ, u·sin θ), |u| ≤ part radius R: dilation
/// `z_c(p) = max_{|u| ≤ w} f(p + u) + √(r² − u²)` (w = r·sin(β/2), arc cut at ±R), taken over
/// every surface sample of a uniform grid of spacing h_u = 4e-6 mm plus the arc's ends (error
/// ≤ K·h_u²/8 ≈ 2e-10 mm with K ≈ 1/(r·cos³(β/2)) + |f″| ≈ 80 mm⁻¹ for r = 0.05 mm); erosion
/// `cut(v) = min_p z_c(p) − √(r² − (v − p)²)` over tool positions p on grids of 51 points across
/// the nose's reach, then of spacings five times finer down to < 2e-8 mm, each zoomed onto ±2
/// steps of the previous minimiser (the function of p is unimodal in the cases tested: V-shaped
/// at a kink, quadratic in a bowl), so its error is ≤ |slope|·2e-8/2 < 2e-8 mm. The oracle is
/// thus good to ~0.02 nm (checked against closed forms to 0.05 nm, [`ORACLE_TOL`]); the library
/// refines by golden-section search to ~1e-11 mm.
pub struct Closing<'a> {
    surface: &'a dyn Surface,
    c: f64,
    s: f64,
    r: f64,
    w: f64,
    part_radius: f64,
    /// Surface samples (u, f(u)) on the uniform grid.
    x0: f64,
    h: f64,
    f: Vec<f64>,
}

impl<'a> Closing<'a> {
    /// Samples the section at angle `theta_deg` around v (enough for every nose of radius `r`
    /// and included angle `beta` degrees that can reach v).
    pub fn new(
        surface: &'a dyn Surface,
        theta_deg: f64,
        r: f64,
        beta: f64,
        part_radius: f64,
        v: f64,
    ) -> Self {
        let (s, c) = theta_deg.to_radians().sin_cos();
        let w = r * (beta / 2.0).to_radians().sin();
        let x0 = (v - 2.0 * w).max(-part_radius);
        let x1 = (v + 2.0 * w).min(part_radius);
        let n = ((x1 - x0) / H_U).floor() as usize;
        let mut out = Self {
            surface,
            c,
            s,
            r,
            w,
            part_radius,
            x0,
            h: H_U,
            f: Vec::with_capacity(n + 1),
        };
        for i in 0..=n {
            let u = x0 + H_U * i as f64;
            let z = out.sag(u);
            out.f.push(z);
        }
        out
    }

    fn sag(&self, u: f64) -> f64 {
        self.surface
            .sag(u * self.c, u * self.s)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// Height of the nose centre at tool position p: the largest f(x) + √(r² − (x − p)²) over
    /// the samples under the arc and the arc's two ends.
    fn dilate(&self, p: f64) -> f64 {
        let r2 = self.r * self.r;
        let lo = (p - self.w).max(-self.part_radius);
        let hi = (p + self.w).min(self.part_radius);
        let mut best = f64::NEG_INFINITY;
        for x in [lo, hi] {
            best = best.max(self.sag(x) + (r2 - (x - p) * (x - p)).max(0.0).sqrt());
        }
        let i0 = ((lo - self.x0) / self.h).ceil().max(0.0) as usize;
        let i1 = (((hi - self.x0) / self.h).floor() as usize).min(self.f.len() - 1);
        for i in i0..=i1 {
            let x = self.x0 + self.h * i as f64;
            let d = x - p;
            best = best.max(self.f[i] + (r2 - d * d).max(0.0).sqrt());
        }
        best
    }

    /// Height of the cut surface at v: the lowest nose arc over v.
    pub fn cut(&self, v: f64) -> f64 {
        let r2 = self.r * self.r;
        let g = |p: f64| self.dilate(p) - (r2 - (v - p) * (v - p)).max(0.0).sqrt();
        let (mut lo, mut hi) = (
            (v - self.w).max(-self.part_radius),
            (v + self.w).min(self.part_radius),
        );
        let mut step = (hi - lo) / 50.0;
        let mut best = (f64::INFINITY, v);
        while step >= 2e-9 {
            let n = ((hi - lo) / step).ceil() as usize;
            for k in 0..=n {
                let p = (lo + step * k as f64).min(hi);
                let value = g(p);
                if value < best.0 {
                    best = (value, p);
                }
            }
            lo = (best.1 - 2.0 * step).max(lo);
            hi = (best.1 + 2.0 * step).min(hi);
            step /= 5.0;
        }
        best.0
    }

    /// The closing residual at v: material the nose leaves above the surface, mm.
    pub fn residual(&self, v: f64) -> f64 {
        self.cut(v) - self.sag(v)
    }
}

/// Builds a surface from its JSON on a Ø10 mm part, expecting a field error.
pub fn field_error(json: &str) -> FieldError {
    let spec: SurfaceSpec = serde_json::from_str(json).unwrap_or_else(|e| panic!("{json}: {e}"));
    match spec.build(5.0) {
        Ok(s) => panic!("{json} built {}", s.describe()),
        Err(e) => e,
    }
}

/// Each `(json, field, value)` of `cases`: the surface JSON is refused with a field error naming
/// `field` and `value`, with a non-empty allowed text, whose message is `field = value: allowed`.
pub fn check_field_errors(cases: &[(&str, &str, &str)]) {
    for &(json, field, value) in cases {
        let e = field_error(json);
        assert_eq!(e.field, field, "{json}: {e}");
        assert_eq!(e.value, value, "{json}: {e}");
        assert!(!e.allowed.is_empty(), "{json}: {e}");
        assert_eq!(e.to_string(), format!("{field} = {value}: {}", e.allowed));
    }
}

/// The example job `crate/jobs/<file>` of the documentation, with the data files it names
/// (relative to that folder) read in, as the command line reads them.
pub fn example_job(file: &str) -> Job {
    let dir = format!("{}/../crate/jobs", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(format!("{dir}/{file}"))
        .unwrap_or_else(|e| panic!("{dir}/{file}: {e}"));
    let mut job = Job::from_json(&text).unwrap_or_else(|e| panic!("{file}: {e}"));
    job.load_files(|p| std::fs::read_to_string(format!("{dir}/{p}")).map_err(|e| e.to_string()))
        .unwrap_or_else(|e| panic!("{file}: {e}"));
    job
}

/// The example split job `sinusoid-grid-fts.json` coarsened for a debug build: 200 revolutions
/// of 512 points (102 401 points) instead of 800 of 1024.
pub fn coarse_grid_fts() -> Job {
    let mut job = example_job("sinusoid-grid-fts.json");
    job.strategy.feed_mm_per_rev = 0.02;
    job.strategy.sampling = spiralcam::job::Sampling::ConstantAngle {
        points_per_rev: 512,
    };
    job
}

/// The example jobs of the documentation, `crate/jobs/<file>` ([`example_job`]), parse, validate
/// and describe themselves: each planner's surface description contains its `family` text, and
/// its spiral has fewer than a million points.
pub fn check_example_jobs(jobs: &[(&str, &str)]) {
    for &(file, family) in jobs {
        let job = example_job(file);
        let planner = Planner::new(&job).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert!(planner.surface().describe().contains(family), "{file}");
        let points = planner.spiral().point_count_hint();
        assert!(points < 1_000_000, "{file}: {points} points");
    }
}

/// A random smooth surface for property tests: its JSON, the part radius, and a bound on the
/// curvature |f″| of its sections, 1/mm (for choosing nose radii that keep the compensated
/// height smooth).
#[derive(Debug, Clone)]
pub struct RandomSurface {
    /// The surface spec.
    pub json: String,
    /// Part radius, mm.
    pub part_radius: f64,
    /// Bound on |f″|, 1/mm.
    pub curvature: f64,
}

/// An even asphere (|R| 2…50 mm, conic −2…1, A4 and A6 of at most 5 µm each at the edge) on a
/// part of radius 0.5…5 mm cut at `rim_fraction` of the conic's rim. Its curvature bound is
/// 2/|R| (a conic's section curvature `c/(1 − (1 + k)c²ρ²)^{3/2}` stays below 2c inside 0.9 of
/// the rim for these conics, and the terms add little).
pub fn random_asphere(rim_fraction: f64) -> impl Strategy<Value = RandomSurface> {
    (
        prop_oneof![2.0..50.0f64, -50.0..-2.0f64],
        -2.0..1.0f64,
        -1.0..1.0f64,
        -1.0..1.0f64,
        0.5..5.0f64,
    )
        .prop_map(move |(radius, conic, a4, a6, part)| {
            let c = 1.0 / radius;
            let p = (1.0 + conic) * c * c;
            let rim = if p > 0.0 { (1.0 / p).sqrt() } else { f64::INFINITY };
            let part_radius = part.min(rim_fraction * rim);
            // Terms of at most 5 µm each at the part edge.
            let a4 = a4 * 5e-3 / part_radius.powi(4);
            let a6 = a6 * 5e-3 / part_radius.powi(6);
            RandomSurface {
                json: format!(
                    r#"{{"type":"asphere","radius_mm":{radius},"conic":{conic},"coefficients":[{a4},{a6}]}}"#
                ),
                part_radius,
                curvature: 2.0 / radius.abs(),
            }
        })
}

/// An XY polynomial of up to 7 terms of degree ≤ 6 (|c| ≤ 5 µm) on a sphere of |R| 20…200 mm,
/// normalised to the part radius 1…5 mm. Each term's |f″| is at most |c|·36/N².
pub fn random_xy_polynomial() -> impl Strategy<Value = RandomSurface> {
    let term = (0u32..=6).prop_flat_map(|i| (Just(i), 0u32..=(6 - i), -5e-3..5e-3f64));
    (
        prop_oneof![20.0..200.0f64, -200.0..-20.0f64],
        1.0..5.0f64,
        prop::collection::vec(term, 1..8),
    )
        .prop_map(|(radius, part_radius, raw)| {
            let mut terms: Vec<(u32, u32, f64)> = Vec::new();
            for t in raw {
                if !terms.iter().any(|u| u.0 == t.0 && u.1 == t.1) {
                    terms.push(t);
                }
            }
            let curvature: f64 = terms.iter().map(|t| t.2.abs() * 36.0).sum::<f64>()
                / (part_radius * part_radius)
                + 1.0 / radius.abs();
            let terms: Vec<String> = terms
                .iter()
                .map(|(x, y, c)| format!(r#"{{"x":{x},"y":{y},"coefficient_mm":{c}}}"#))
                .collect();
            RandomSurface {
                json: format!(
                    r#"{{"type":"xy_polynomial","base":{{"radius_mm":{radius}}},"norm_radius_mm":{part_radius},"terms":[{}]}}"#,
                    terms.join(",")
                ),
                part_radius,
                curvature,
            }
        })
}

/// A sinusoidal grid (amplitude 0.1…5 µm, wavelengths from `wavelength`, any phases) on a part
/// radius from `part`; |f″| ≤ A·(kx² + ky²).
pub fn random_sinusoid(
    wavelength: std::ops::Range<f64>,
    part: std::ops::Range<f64>,
) -> impl Strategy<Value = RandomSurface> {
    (
        1e-4..5e-3f64,
        wavelength.clone(),
        wavelength,
        0.0..360.0f64,
        0.0..360.0f64,
        part,
    )
        .prop_map(|(a, lx, ly, px, py, part_radius)| {
            let k2 = (TAU / lx).powi(2) + (TAU / ly).powi(2);
            RandomSurface {
                json: format!(
                    r#"{{"type":"sinusoid","amplitude_mm":{a},"wavelength_x_mm":{lx},"wavelength_y_mm":{ly},"phase_x_deg":{px},"phase_y_deg":{py}}}"#
                ),
                part_radius,
                curvature: a * k2,
            }
        })
}

/// The planner of a job given as JSON, panicking with the JSON and the error.
pub fn planner_of(json: &str) -> Planner {
    let job = Job::from_json(json).unwrap_or_else(|e| panic!("{json}: {e}"));
    Planner::new(&job).unwrap_or_else(|e| panic!("{json}: {e}"))
}

/// Every point of a planner's path.
pub fn path_points(p: &Planner) -> Vec<PathPoint> {
    p.points()
        .map(|x| x.unwrap_or_else(|e| panic!("{e}")))
        .collect()
}

/// Half a unit of the last of `decimals` digits, plus 1e-9 for the rounding of the planned
/// value: how far a written NC word may lie from the value it writes.
pub fn half_unit(decimals: u32) -> f64 {
    0.5 * 10f64.powi(-(decimals as i32)) + 1e-9
}

/// The difference of two C values in degrees, across the wrap when wrapping.
pub fn c_error(a: f64, b: f64, wrap: bool) -> f64 {
    let d = a - b;
    if wrap {
        (d + 180.0).rem_euclid(360.0) - 180.0
    } else {
        d
    }
    .abs()
}

/// The points of `job` and its NC program with every height split: the slide at `slide(p)`,
/// the fast tool servo the rest (`NcWriter::point_split`).
pub fn split_program(job: &Job, slide: impl Fn(&PathPoint) -> f64) -> (Vec<PathPoint>, String) {
    use spiralcam::nc::NcWriter;
    let planner = Planner::new(job).expect("valid job");
    let pts: Vec<PathPoint> = planner.points().map(|p| p.unwrap()).collect();
    let mut nc = Vec::new();
    let mut writer = NcWriter::new(&mut nc, &job.output, &planner.header()).unwrap();
    for p in &pts {
        writer.point_split(p, slide(p)).unwrap();
    }
    writer.finish().unwrap();
    (pts, String::from_utf8(nc).unwrap())
}

/// Nodes and weights of Gauss–Legendre quadrature on [0, 1] with `k` nodes: Newton's method on
/// Pₖ from the three-term recurrence, weights `2/((1 − x²)·Pₖ′(x)²)` halved for [0, 1].
pub fn gauss_legendre(k: usize) -> Vec<(f64, f64)> {
    (0..k)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (k as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for n in 2..=k {
                    let p2 = ((2 * n - 1) as f64 * x * p1 - (n - 1) as f64 * p0) / n as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = k as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            ((x + 1.0) / 2.0, w / 2.0)
        })
        .collect()
}

/// A small job for the gouge checks: a Ø`diameter_mm` part, nose r 0.1 mm and 100°, 0.15 mm
/// feed, 24 points per revolution at 300 rpm.
pub fn small_job(name: &str, surface: &str, diameter_mm: f64) -> String {
    format!(
        r#"{{"name":"{name}","part":{{"diameter_mm":{diameter_mm}}},"surface":{surface},
            "tool":{{"nose_radius_mm":0.1,"included_angle_deg":100}},"machine":{{"spindle_rpm":300}},
            "strategy":{{"feed_mm_per_rev":0.15,"sampling":{{"type":"constant_angle","points_per_rev":24}}}}}}"#
    )
}

/// A small sinusoid job named `name` in `dialect` with a `program` section: three passes in two
/// groups (stock 11 µm; 6, 1 and 0 µm left after them), `loop_kind`, and `max_program_bytes`
/// when `limit` is given.
pub fn passes_job_json(name: &str, dialect: &str, loop_kind: &str, limit: Option<u64>) -> String {
    let limit = limit.map_or(String::new(), |b| format!(r#", "max_program_bytes": {b}"#));
    format!(
        r#"{{
  "name": "{name}",
  "part": {{ "diameter_mm": 1.2 }},
  "surface": {{ "type": "sinusoid", "amplitude_mm": 0.002, "wavelength_x_mm": 0.5,
               "wavelength_y_mm": 0.4 }},
  "tool": {{ "nose_radius_mm": 0.1 }},
  "machine": {{ "spindle_rpm": 300.0 }},
  "strategy": {{ "feed_mm_per_rev": 0.05,
                 "sampling": {{ "type": "constant_angle", "points_per_rev": 36 }} }},
  "output": {{ "dialect": "{dialect}" }},
  "program": {{
    "tool": "T0303", "safe_z_mm": 10, "retract_height_mm": 1,
    "approach": [ {{ "height_mm": 0.5, "feed_mm_per_min": 200 }} ],
    "passes": [ {{ "count": 2, "depth_of_cut_um": 5 }}, {{ "count": 1, "depth_of_cut_um": 1 }} ],
    "loop": "{loop_kind}"{limit}
  }}
}}"#
    )
}

/// Child programs kept in memory as a program writes them: (file name, bytes), child `n` at
/// index `n − 1`.
#[derive(Default)]
pub struct ChildBuffers(pub Vec<(String, Vec<u8>)>);

impl spiralcam::nc::program::ChildFiles for ChildBuffers {
    fn child(&mut self, number: usize, name: &str) -> std::io::Result<&mut dyn std::io::Write> {
        if number > self.0.len() {
            self.0.push((name.to_string(), Vec::new()));
        }
        Ok(&mut self.0[number - 1].1)
    }
}
