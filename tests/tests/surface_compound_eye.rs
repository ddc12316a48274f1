//! The compound eye (paper 000's multiple-compound eye, paper 001's "small spherical patches on
//! a big sphere") through the public API, against an independent model written here from the
//! definition: every element and lenslet sphere listed (hexagonal rings by the hexagonal
//! distance `(|i| + |j| + |i + j|)/2`, rows of lenslets, each sphere standing on its parent's
//! normal, normals from the parents' centres), the sag the largest upper cap over all of them
//! and the base, no index.
//!
//! - Sag and `local().z` equal the model's within 1e-12 mm: the same spheres, centres computed
//!   by other formulas (normals from centres, not gradients) and caps written `C_z + √(r² − d²)`
//!   rather than `apex − d²/(r + √(r² − d²))`, so only rounding differs, a few ε times the
//!   coordinates of a few mm (≈ 1e-15 mm); 1e-12 mm leaves a factor of 1000.
//! - Gradient and Hessian against central differences (h = 1e-5 mm) at points whose top piece is
//!   the same over the whole stencil (±2h), so the envelope is one smooth cap there: truncation
//!   `h²/6·|g‴|` with third (fourth, for the Hessian from the gradient) derivatives of caps of
//!   radius ≥ 0.3 mm at slopes ≤ 1 below ~10³ mm⁻² (mm⁻³) gives ≤ 2e-8; rounding
//!   `ε·|g|/h` ≤ 1e-10. Tolerance 1e-7 + 1e-7·|value|; a wrong sign or factor is ≥ 1e-3.
//! - Slope kinks against a brute-force scan of the line (the model's top piece at 10 001 samples):
//!   every change of the top piece between two samples holds a reported kink, and at every
//!   reported kink the model's two highest pieces agree within 1e-10 mm (a kink placed δ off
//!   would show the slope jump times δ; the library's kinks are good to ~1e-13 mm).
//! - The paper-000 preset has 7 elements × 17 lenslets and matches the model.
//! - A planned job's every path point passes the brute-force gouge check of
//!   `tests/tests/compensation.rs` (`common::check_planned_path`): the nose arc touches within
//!   0.1 nm and cuts nowhere deeper than 0.1 nm, on 2001 samples of the arc plus its ends, the
//!   contact and the surface's kinks, with the sampling bound `K·Δa²/8` subtracted. Every kink
//!   of this surface is a valley (an upper envelope of convex caps): the gap between arc and
//!   surface is then the smaller of smooth functions there, whose minimum the bound still
//!   covers, so the check holds even between kinks it were not told of.
//! - The concave-zone report finds the valleys between the lenslets: one of its zones covers the
//!   valley between the central lenslet and its neighbour, its deepest zones lie within 1 nm of
//!   a change of the top piece, and their depth equals the brute-force closing of
//!   `tests/tests/reach.rs` (`common::Closing`) at the reported place within 1 nm; the oracle
//!   itself matches the closed-form fillet of a nose resting on two neighbouring lenslets within
//!   0.05 nm.
//! - The nose compensation on the paper-000 preset rests on its spheres: the nose centre equals
//!   the closed-form highest clearance height over every piece's circular section within
//!   1e-10 mm (the compensation refines to ~1e-13 mm).
//! - A base sphere smaller than the part is an error naming the radius where the path needs the
//!   surface.

mod common;

use common::{
    Closing, DEPTH_TOL, H, ORACLE_TOL, check_derivatives_within, check_planned_path, config, local,
};
use proptest::prelude::*;
use spiralcam::job::Job;
use spiralcam::job::ToolSpec;
use spiralcam::plan::Planner;
use spiralcam::progress::ignore;
use spiralcam::surface::{CompoundEye, CompoundEyeSpec, Line, PartDisc, Surface, SurfaceSpec};
use spiralcam::tool::NoseCompensator;
use std::f64::consts::PI;

/// Seed of this file's property tests.
const SEED: u64 = 4242;

// ---------------------------------------------------------------------------------------------
// The independent model

/// Which piece is on top: the base, or a sphere of the model's list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Top {
    Base,
    Sphere(usize),
}

/// Every sphere of a compound eye, listed from the definition.
#[derive(Debug, Clone)]
struct Model {
    /// Signed base radius (None: plane).
    base: Option<f64>,
    /// (centre, radius) of every element and lenslet.
    spheres: Vec<([f64; 3], f64)>,
    elements: usize,
}

impl Model {
    fn new(spec: &CompoundEyeSpec) -> Self {
        let mut model = Self {
            base: spec.base_radius_mm,
            spheres: Vec::new(),
            elements: 0,
        };
        let n = spec.element_rings as i64;
        let row = 3f64.sqrt() / 2.0;
        let mut poles = Vec::new();
        for i in -2 * n..=2 * n {
            for j in -2 * n..=2 * n {
                if (i.abs() + j.abs() + (i + j).abs()) / 2 > n {
                    continue;
                }
                let x = (i as f64 + j as f64 / 2.0) * spec.element_pitch_mm;
                let y = j as f64 * row * spec.element_pitch_mm;
                let s = [x, y, model.base_sag(x, y)];
                let normal = model.base_normal(s);
                let (centre, pole) =
                    stand(s, normal, spec.element_height_mm, spec.element_radius_mm);
                model.spheres.push((centre, spec.element_radius_mm));
                poles.push(pole);
            }
        }
        model.elements = model.spheres.len();
        for (e, pole) in poles.iter().enumerate() {
            let (ce, re) = model.spheres[e];
            let m = spec.lenslet_rows.len() as f64;
            for (k, &count) in spec.lenslet_rows.iter().enumerate() {
                let oy = (k as f64 - (m - 1.0) / 2.0) * row * spec.lenslet_pitch_mm;
                for i in 0..count {
                    let ox = (i as f64 - (count as f64 - 1.0) / 2.0) * spec.lenslet_pitch_mm;
                    let (x, y) = (pole[0] + ox, pole[1] + oy);
                    let d2 = (x - ce[0]).powi(2) + (y - ce[1]).powi(2);
                    let s = [x, y, ce[2] + (re * re - d2).sqrt()];
                    let normal = [
                        (s[0] - ce[0]) / re,
                        (s[1] - ce[1]) / re,
                        (s[2] - ce[2]) / re,
                    ];
                    let (centre, _) =
                        stand(s, normal, spec.lenslet_height_mm, spec.lenslet_radius_mm);
                    model.spheres.push((centre, spec.lenslet_radius_mm));
                }
            }
        }
        model
    }

    /// The base: a sphere through the origin with centre (0, 0, R), or z = 0.
    fn base_sag(&self, x: f64, y: f64) -> f64 {
        match self.base {
            None => 0.0,
            Some(r) => r - r.signum() * (r * r - x * x - y * y).sqrt(),
        }
    }

    /// The base's upward unit normal at its point s: away from a dome's centre, towards a
    /// bowl's.
    fn base_normal(&self, s: [f64; 3]) -> [f64; 3] {
        match self.base {
            None => [0.0, 0.0, 1.0],
            Some(r) => {
                let k = -1.0 / r;
                [s[0] * k, s[1] * k, (s[2] - r) * k]
            }
        }
    }

    /// Every piece defined at (x, y) with its sag.
    fn pieces(&self, x: f64, y: f64) -> Vec<(Top, f64)> {
        let mut out = vec![(Top::Base, self.base_sag(x, y))];
        for (k, &(c, r)) in self.spheres.iter().enumerate() {
            let d2 = (x - c[0]).powi(2) + (y - c[1]).powi(2);
            if d2 < r * r {
                out.push((Top::Sphere(k), c[2] + (r * r - d2).sqrt()));
            }
        }
        out
    }

    /// The highest piece and the envelope's sag.
    fn top(&self, x: f64, y: f64) -> (Top, f64) {
        self.pieces(x, y)
            .into_iter()
            .fold((Top::Base, f64::NEG_INFINITY), |a, b| {
                if b.1 > a.1 { b } else { a }
            })
    }

    /// The gap between the highest and the second highest piece.
    fn top_gap(&self, x: f64, y: f64) -> f64 {
        let mut z: Vec<f64> = self.pieces(x, y).into_iter().map(|p| p.1).collect();
        z.sort_by(|a, b| b.total_cmp(a));
        z[0] - z[1]
    }

    fn lenslets(&self) -> usize {
        self.spheres.len() - self.elements
    }
}

/// A sphere of radius r standing on the surface point s along the unit normal n, its pole h out:
/// (centre, pole).
fn stand(s: [f64; 3], n: [f64; 3], h: f64, r: f64) -> ([f64; 3], [f64; 3]) {
    let at = |t: f64| [s[0] + t * n[0], s[1] + t * n[1], s[2] + t * n[2]];
    (at(h - r), at(h))
}

// ---------------------------------------------------------------------------------------------
// Random layouts

/// A layout built from ratios so that every piece is rooted: lenslet footprints of 0.4…0.75
/// pitches, element footprints a margin beyond the lenslet cluster, element pitch 0.8…1.2 times
/// the element footprint's diameter, heights from the footprints and the relative curvature.
#[derive(Debug, Clone)]
struct Layout {
    spec: CompoundEyeSpec,
    /// Radius of the disc the pieces cover, mm.
    extent: f64,
}

fn layout() -> impl Strategy<Value = Layout> {
    let rows = prop_oneof![
        Just(vec![]),
        Just(vec![1]),
        Just(vec![1, 2]),
        Just(vec![2, 3, 2]),
        Just(vec![3, 4, 3, 4, 3]),
    ];
    (
        (
            prop_oneof![Just(0.0), -1.0..-0.3f64, 0.3..1.0f64],
            0u32..=1,
            rows,
        ),
        (0.2..0.5f64, 2.0..6.0f64, 0.4..0.75f64),
        (0.3..1.0f64, 3.0..8.0f64, 0.8..1.2f64),
    )
        .prop_map(
            |((base, rings, rows), (pl, rl_ratio, al_ratio), (margin, re_ratio, pe_ratio))| {
                let rl = pl * rl_ratio;
                let al = pl * al_ratio;
                let offsets = rows.iter().enumerate().map(|(k, &c)| {
                    let m = rows.len() as f64;
                    let y = (k as f64 - (m - 1.0) / 2.0) * pl * 0.866;
                    let x = (c as f64 - 1.0) / 2.0 * pl;
                    x.hypot(y)
                });
                let farthest = offsets.fold(0.0, f64::max);
                let ae = farthest + al + margin * pl;
                let re = (ae * re_ratio).max(2.5 * (farthest + rl));
                let hl = al * al * (1.0 / rl - 1.0 / re) / 2.0;
                let pe = 2.0 * ae * pe_ratio;
                let extent = rings as f64 * pe + 1.5 * ae;
                // Base radius: a dome or a bowl 6…20 extents in radius, or flat.
                let rb = (base != 0.0).then(|| base.signum() * extent * (6.0 + 14.0 * base.abs()));
                let kb = rb.map_or(0.0, |r| -1.0 / r);
                let he = ae * ae * (1.0 / re - kb) / 2.0;
                Layout {
                    spec: CompoundEyeSpec {
                        base_radius_mm: rb,
                        element_rings: rings,
                        element_pitch_mm: pe,
                        element_radius_mm: re,
                        element_height_mm: he,
                        lenslet_rows: rows,
                        lenslet_pitch_mm: pl,
                        lenslet_radius_mm: rl,
                        lenslet_height_mm: hl,
                    },
                    extent,
                }
            },
        )
}

fn build(spec: &CompoundEyeSpec) -> CompoundEye {
    CompoundEye::new(spec, PartDisc::centred(5.0))
        .unwrap_or_else(|e| panic!("the layout should be valid: {e}\n{spec:?}"))
}

/// A point in the disc of radius `r` from unit-square fractions.
fn in_disc(r: f64, t: f64, phi: f64) -> (f64, f64) {
    let rho = r * t.sqrt();
    (rho * phi.cos(), rho * phi.sin())
}

/// Finite-difference tolerances (step `common::H` = 1e-5 mm): the module docs bound the error
/// by 2e-8 here, so the absolute tolerance is tighter than `common::FD_ABS`.
const FD_ABS: f64 = 1e-7;
const FD_REL: f64 = 1e-7;
/// Agreement of the sag with the model, mm (see the module docs).
const SAG_TOL: f64 = 1e-12;
/// Agreement of the two top pieces at a reported kink, mm (see the module docs).
const KINK_TIE: f64 = 1e-10;

/// Whether the model's top piece is the same over the whole finite-difference stencil.
fn smooth_around(m: &Model, x: f64, y: f64) -> bool {
    let top = m.top(x, y).0;
    [
        (2.0, 0.0),
        (-2.0, 0.0),
        (0.0, 2.0),
        (0.0, -2.0),
        (2.0, 2.0),
        (-2.0, -2.0),
    ]
    .iter()
    .all(|(i, j)| m.top(x + i * H, y + j * H).0 == top)
}

proptest! {
    #![proptest_config(config(48, SEED))]

    #[test]
    fn sag_is_the_highest_of_all_spheres(
        l in layout(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 16),
    ) {
        let s = build(&l.spec);
        let m = Model::new(&l.spec);
        prop_assert_eq!(s.element_count(), m.elements);
        prop_assert_eq!(s.lenslet_count(), m.lenslets());
        for (t, phi) in pts {
            let (x, y) = in_disc(l.extent, t, phi);
            let z = s.sag(x, y).unwrap();
            let reference = m.top(x, y).1;
            prop_assert!((z - reference).abs() <= SAG_TOL, "({x}, {y}): {z} vs {reference}");
            prop_assert_eq!(local(&s, x, y).z, z);
        }
    }

    #[test]
    fn derivatives_match_finite_differences_away_from_the_seams(
        l in layout(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 8),
    ) {
        let s = build(&l.spec);
        let m = Model::new(&l.spec);
        let mut checked = 0;
        for (t, phi) in pts {
            let (x, y) = in_disc(l.extent, t, phi);
            if smooth_around(&m, x, y) {
                check_derivatives_within(&s, x, y, FD_ABS, FD_REL)?;
                checked += 1;
            }
        }
        prop_assert!(checked >= 4, "only {checked} points away from the seams");
    }
}

proptest! {
    #![proptest_config(config(24, SEED))]

    #[test]
    fn slope_kinks_are_where_the_top_sphere_changes(
        l in layout(),
        origin in (0.0..0.5f64, 0.0..2.0 * PI),
        direction in 0.0..PI,
    ) {
        let s = build(&l.spec);
        let m = Model::new(&l.spec);
        let (x0, y0) = in_disc(l.extent, origin.0, origin.1);
        let (sin, cos) = direction.sin_cos();
        let line = Line { x0, y0, c: cos, s: sin };
        let (t0, t1) = (-l.extent, l.extent);
        let mut kinks = Vec::new();
        s.slope_kinks(line, t0, t1, &mut kinks);
        let n = 10_000;
        let step = (t1 - t0) / n as f64;
        let top = |t: f64| {
            let (x, y) = line.at(t);
            m.top(x, y).0
        };
        let mut prev = top(t0);
        let mut changes = 0;
        for k in 1..=n {
            let (a, b) = (t0 + step * (k - 1) as f64, t0 + step * k as f64);
            let next = top(b);
            if next != prev {
                changes += 1;
                prop_assert!(
                    kinks.iter().any(|t| *t >= a - 1e-12 && *t <= b + 1e-12),
                    "top piece changes in [{a}, {b}] with no kink reported: {kinks:?}"
                );
            }
            prev = next;
        }
        for &t in &kinks {
            prop_assert!(t > t0 && t < t1);
            let (x, y) = line.at(t);
            let gap = m.top_gap(x, y);
            prop_assert!(gap <= KINK_TIE, "kink {t}: the two top pieces differ by {gap:e} mm");
        }
        if origin.0 < 0.1 {
            prop_assert!(changes > 0, "a line near the middle crosses no seam");
        }
    }
}

#[test]
fn the_paper000_preset_has_seven_elements_of_seventeen_lenslets() {
    let spec = CompoundEyeSpec::paper000();
    let s = build(&spec);
    let m = Model::new(&spec);
    assert_eq!((s.element_count(), s.lenslet_count()), (7, 119));
    assert_eq!((m.elements, m.lenslets()), (7, 119));
    // The whole part against the model on a sunflower of points.
    let golden = PI * (3.0 - 5f64.sqrt());
    for i in 0..3000 {
        let r = 5.0 * ((i as f64 + 0.5) / 3000.0).sqrt();
        let (sn, c) = (golden * i as f64).sin_cos();
        let (x, y) = (r * c, r * sn);
        let z = s.sag(x, y).unwrap();
        assert!((z - m.top(x, y).1).abs() <= SAG_TOL, "({x}, {y})");
    }
    // The same through the job format.
    let via_json = SurfaceSpec::CompoundEye(spec).build(5.0).unwrap();
    assert_eq!(via_json.sag(1.0, 0.7).unwrap(), s.sag(1.0, 0.7).unwrap());
}

// ---------------------------------------------------------------------------------------------
// A planned job and the concave-zone report: a small eye (7 elements × 7 lenslets on Ø3 mm)

const SMALL: &str = r#"{"type":"compound_eye","base_radius_mm":-10,"element_rings":1,
    "element_pitch_mm":0.85,"element_radius_mm":3,"element_height_mm":0.0236,
    "lenslet_rows":[2,3,2],"lenslet_pitch_mm":0.2,"lenslet_radius_mm":0.8,
    "lenslet_height_mm":0.0066}"#;
const SMALL_PART: f64 = 1.5;
const SMALL_R: f64 = 0.05;

fn small_job_json() -> String {
    format!(
        r#"{{"name":"small-eye","part":{{"diameter_mm":{}}},"surface":{SMALL},
            "tool":{{"nose_radius_mm":{SMALL_R}}},"machine":{{"spindle_rpm":100}},
            "strategy":{{"feed_mm_per_rev":0.05,"sampling":{{"type":"constant_angle","points_per_rev":36}}}}}}"#,
        2.0 * SMALL_PART
    )
}

fn small_job() -> Job {
    Job::from_json(&small_job_json()).expect("job JSON")
}

fn small_model() -> Model {
    let SurfaceSpec::CompoundEye(spec) = serde_json::from_str(SMALL).unwrap() else {
        unreachable!("a compound eye")
    };
    Model::new(&spec)
}

/// Samples along the arc: Δa = 100°/2000 gives a sampling bound K·Δa²/8 ≤ 1e-8 mm here
/// (K ≤ r·(1 + 2·|f′|) + 2r²·|f″| ≈ 0.09 mm for r = 0.05 mm, slopes ≤ 0.4, curvature ≤ 1.3/mm).
const DENSE: usize = 2000;

#[test]
fn every_point_of_a_planned_compound_eye_path_touches_without_cutting() {
    // The surface's own kinks along each whole radial section are extra samples of the arc.
    let planner = Planner::new(&small_job()).expect("valid job");
    // The caps and the base bound the sections, valleys at every seam: the nose height is
    // searched stretch by stretch between them, held to the same check.
    assert!(planner.path().concavity().is_some_and(|c| c.valleys));
    let surface = planner.surface();
    let kinks = |c: f64, s: f64| {
        let mut kinks = Vec::new();
        surface.slope_kinks(Line::radial(c, s), -SMALL_PART, SMALL_PART, &mut kinks);
        kinks
    };
    let n = check_planned_path(&small_job_json(), &kinks, DENSE);
    assert!(n > 1000);
}

/// The valley on θ = 0 between the central lenslet and its neighbour at layout (0.2, 0), and
/// the fillet a nose of radius r leaves there, in closed form: both lenslets' sections are
/// circles of radius R_l in the XZ plane (the plane holds both centres); the valley is their
/// upper crossing, and the nose centre the upper crossing of the circles of radius R_l + r.
fn small_valley_fillet(m: &Model, r: f64) -> (f64, f64) {
    let rl = m.spheres[m.elements].1;
    // The lenslet centres on the X axis nearest to the layout points (the neighbour's centre
    // lies inwards of its layout point: it stands on the element's tilted normal).
    let centre_of = |x: f64| {
        m.spheres[m.elements..]
            .iter()
            .map(|s| s.0)
            .filter(|c| c[1].abs() < 1e-12)
            .min_by(|a, b| (a[0] - x).abs().total_cmp(&(b[0] - x).abs()))
            .expect("a lenslet on the X axis")
    };
    let (a, b) = (centre_of(0.0), centre_of(0.2));
    let upper = |ra: f64, rb: f64| {
        let (dx, dz) = (b[0] - a[0], b[2] - a[2]);
        let d = dx.hypot(dz);
        let p = (d * d + ra * ra - rb * rb) / (2.0 * d);
        let q = (ra * ra - p * p).sqrt();
        let (ux, uz) = (dx / d, dz / d);
        // The crossing on the +Z side of the line of centres.
        (a[0] + p * ux - q * uz, a[2] + p * uz + q * ux)
    };
    let (xk, zk) = upper(rl, rl);
    let (nx, nz) = upper(rl + r, rl + r);
    (xk, nz - (r * r - (xk - nx).powi(2)).sqrt() - zk)
}

#[test]
fn the_concave_zone_report_finds_the_valleys_between_lenslets() {
    let job = small_job();
    let planner = Planner::new(&job).expect("valid job");
    let surface = planner.surface();
    let m = small_model();
    // The oracle against the closed form at the first valley on θ = 0.
    let (xk, fillet) = small_valley_fillet(&m, SMALL_R);
    // Halfway between the layout points, and a fillet of 0.2 µm, far above the tolerances.
    assert!((xk - 0.1).abs() < 1e-3 && fillet > 1e-4, "{xk} {fillet}");
    let oracle = Closing::new(surface, 0.0, SMALL_R, 100.0, SMALL_PART, xk).residual(xk);
    assert!(
        (oracle - fillet).abs() < ORACLE_TOL,
        "oracle {oracle} vs closed form {fillet}"
    );
    let reach = planner.concave_zones(&mut ignore).unwrap();
    // At least the valley network of each of the seven elements.
    assert!(reach.zones.len() >= 7, "{reach:?}");
    // The valley at (xk, 0°) lies in a zone.
    let covered = reach.zones.iter().any(|z| {
        let spans_zero = z.theta_to_deg < z.theta_from_deg || z.theta_from_deg == 0.0;
        z.rho_min_mm <= xk + 0.01 && xk - 0.01 <= z.rho_max_mm && spans_zero
    });
    assert!(covered, "no zone at ρ {xk}, θ 0: {:?}", reach.zones);
    for z in reach.zones.iter().take(2) {
        assert!(z.slope_kink, "{z:?}");
        let (v, theta) = (z.at.rho_mm, z.at.theta_deg);
        let (s, c) = theta.to_radians().sin_cos();
        // The deepest point is a valley: the top piece changes within 1 nm of it.
        let (a, b) = (v - 1e-6, v + 1e-6);
        assert_ne!(m.top(a * c, a * s).0, m.top(b * c, b * s).0, "{z:?}");
        let brute = Closing::new(surface, theta, SMALL_R, 100.0, SMALL_PART, v).residual(v);
        let depth = z.depth_um * 1e-3;
        assert!(
            (brute - depth).abs() <= DEPTH_TOL,
            "zone at {theta}°, ρ {v}: reported {depth} mm, brute force {brute} mm"
        );
    }
}

#[test]
fn the_nose_rests_on_the_spheres_of_the_preset() {
    // The example job's surface and tool. In the radial plane θ = 0 every piece's section is a
    // circle (centre (c_x, c_z), radius R' = √(R² − c_y²)); the nose arc (radius r, ±50°) over
    // ρ clears it from the height c_z + √((R' + r)² − (ρ − c_x)²) if it touches it within its
    // arc, else from the higher of its ends over the circle. The nose centre is the highest of
    // these over all pieces and the base (the envelope is their union): closed form, compared
    // at points over the first valleys around the central lenslet and between elements.
    let spec = CompoundEyeSpec::paper000();
    let surface = SurfaceSpec::CompoundEye(spec.clone()).build(5.0).unwrap();
    let r = 0.05;
    let half = 50f64.to_radians();
    let nose = NoseCompensator::new(
        &ToolSpec {
            nose_radius_mm: r,
            included_angle_deg: 100.0,
            ..ToolSpec::with_nose_radius(0.0)
        },
        surface.feature_length_mm(),
        5.0,
    )
    .unwrap();
    let m = Model::new(&spec);
    let mut circles: Vec<([f64; 2], f64)> = m
        .spheres
        .iter()
        .filter(|(c, big)| c[1].abs() < *big)
        .map(|&(c, big)| ([c[0], c[2]], (big * big - c[1] * c[1]).sqrt()))
        .collect();
    circles.push(([0.0, -40.0], 40.0));
    for rho in [0.2, 0.225, 0.25, 0.7, 1.3, 2.0] {
        let mut expect = f64::NEG_INFINITY;
        for &([cx, cz], big) in &circles {
            let reach = big + r;
            let dx = cx - rho;
            let height = if dx.abs() <= reach * half.sin() {
                cz + (reach * reach - dx * dx).sqrt()
            } else {
                [-1.0, 1.0]
                    .iter()
                    .map(|side| {
                        let u = rho + side * r * half.sin() - cx;
                        if u.abs() < big {
                            cz + (big * big - u * u).sqrt() + r * half.cos()
                        } else {
                            f64::NEG_INFINITY
                        }
                    })
                    .fold(f64::NEG_INFINITY, f64::max)
            };
            expect = expect.max(height);
        }
        let contact = nose.compensate(surface.as_ref(), rho, 1.0, 0.0).unwrap();
        // The library refines the contact to ~1e-13 mm; the closed form is exact.
        assert!(
            (contact.z_center - expect).abs() < 1e-10,
            "ρ {rho}: {} vs {expect}",
            contact.z_center
        );
    }
}

#[test]
fn a_base_sphere_smaller_than_the_part_is_an_error_naming_the_radius() {
    // The small eye on a Ø24 mm part: its base sphere (R −10 mm) ends at radius 10 mm, so the
    // nose arc of the first point of the path (radius 12 mm) finds no surface under it.
    let mut job = small_job();
    job.part.diameter_mm = 24.0;
    let planner = Planner::new(&job).expect("the surface itself is valid");
    let e = planner
        .run(spiralcam::plan::Sinks::default(), &mut |_| {
            std::ops::ControlFlow::Continue(())
        })
        .unwrap_err()
        .to_string();
    let radius: f64 = e
        .strip_prefix("surface: compound eye is undefined at radius ")
        .and_then(|rest| rest.split(' ').next())
        .and_then(|r| r.parse().ok())
        .unwrap_or_else(|| panic!("{e}"));
    assert!(radius > 10.0 && radius <= 12.0, "{e}");
    assert!(
        e.contains("beyond the base sphere's rim at radius 10 mm"),
        "{e}"
    );
}
