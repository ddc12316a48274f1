//! Surfaces through the public API: every family's analytic gradient and second derivatives
//! against central finite differences (proptest over the parameter ranges), its sag against an
//! independent implementation (closed forms, direct `powi` sums, direct monomials, a brute-force
//! search over every lenslet centre), and the errors for undefined points and bad parameters.
//!
//! Finite differences: `common::check_derivatives`, whose docs derive its tolerance.

mod common;

use common::{check_derivatives, check_field_errors, config, local};
use proptest::prelude::*;
use spiralcam::surface::lens_array::{Form, Grid};
use spiralcam::surface::xy_polynomial::XyTerm;
use spiralcam::surface::{
    Asphere, AsphereSpec, LensArray, LensArraySpec, Local, PartDisc, Sinusoid, SinusoidSpec,
    Surface, SurfaceSpec, XyPolynomial, XyPolynomialSpec,
};
use std::f64::consts::PI;

/// Seed of this file's property tests.
const SEED: u64 = 1001;

// ---------------------------------------------------------------------------------------------
// Even asphere

/// The ISO 10110-12 sag written out directly: conic term plus `Σ A₂ᵢ·ρ²ⁱ` by `powi`.
fn asphere_reference(c: f64, k: f64, coefficients: &[f64], x: f64, y: f64) -> f64 {
    let rho2 = x * x + y * y;
    let rho = rho2.sqrt();
    let conic = c * rho2 / (1.0 + (1.0 - (1.0 + k) * c * c * rho2).sqrt());
    let poly: f64 = coefficients
        .iter()
        .enumerate()
        .map(|(i, a)| a * rho.powi(2 * i as i32 + 4))
        .sum();
    conic + poly
}

/// An asphere's parameters and a radius inside which it is well defined (q ≥ 0.19).
#[derive(Debug, Clone)]
struct AsphereCase {
    radius: f64,
    conic: f64,
    coefficients: Vec<f64>,
    max_rho: f64,
}

fn asphere_case() -> impl Strategy<Value = AsphereCase> {
    (
        prop_oneof![5.0..200.0f64, -200.0..-5.0f64],
        -3.0..2.0f64,
        prop::collection::vec(-1.0..1.0f64, 0..=9),
    )
        .prop_map(|(radius, conic, unit)| {
            let c = 1.0 / radius;
            let p = (1.0 + conic) * c * c;
            let rim = if p > 0.0 {
                (1.0 / p).sqrt()
            } else {
                f64::INFINITY
            };
            let max_rho = (0.9 * rim).min(10.0);
            // Each term at most 0.1 mm at ρ = 10 mm, so derivatives stay moderate.
            let coefficients = unit
                .iter()
                .enumerate()
                .map(|(i, t)| t * 0.1 / 10f64.powi(2 * i as i32 + 4))
                .collect();
            AsphereCase {
                radius,
                conic,
                coefficients,
                max_rho,
            }
        })
}

fn build_asphere(case: &AsphereCase) -> Asphere {
    Asphere::new(&AsphereSpec {
        radius_mm: Some(case.radius),
        conic: case.conic,
        coefficients: case.coefficients.clone(),
        ..Default::default()
    })
    .expect("valid asphere")
}

/// A point in the disc of radius `max_rho` from unit-square fractions.
fn in_disc(max_rho: f64, t: f64, phi: f64) -> (f64, f64) {
    let rho = max_rho * t.sqrt();
    (rho * phi.cos(), rho * phi.sin())
}

proptest! {
    #![proptest_config(config(256, SEED))]

    #[test]
    fn asphere_derivatives_match_finite_differences(
        case in asphere_case(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 4),
    ) {
        let s = build_asphere(&case);
        for (t, phi) in pts {
            let (x, y) = in_disc(case.max_rho, t, phi);
            check_derivatives(&s, x, y)?;
        }
    }

    #[test]
    fn asphere_sag_matches_the_direct_sum(
        case in asphere_case(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 8),
    ) {
        let s = build_asphere(&case);
        for (t, phi) in pts {
            let (x, y) = in_disc(case.max_rho, t, phi);
            let z = local(&s, x, y).z;
            let reference = asphere_reference(1.0 / case.radius, case.conic, &case.coefficients, x, y);
            // Terms up to ~1 mm summed in different orders (Horner in ρ² vs powi): a few ulps.
            prop_assert!((z - reference).abs() <= 1e-14 * (1.0 + reference.abs()) + 1e-15,
                "({x}, {y}): {z} vs {reference}");
            prop_assert_eq!(s.sag(x, y).unwrap(), z);
        }
    }

    #[test]
    fn sphere_matches_its_closed_form(
        radius in prop_oneof![1.0..500.0f64, -500.0..-1.0f64],
        t in 0.0..0.98f64,
        phi in 0.0..2.0 * PI,
    ) {
        let s = Asphere::new(&AsphereSpec { radius_mm: Some(radius), ..Default::default() }).unwrap();
        let (x, y) = in_disc(radius.abs(), t, phi);
        let w = (radius * radius - x * x - y * y).sqrt();
        let sg = radius.signum();
        let l = local(&s, x, y);
        // z = R − sgn(R)·√(R² − ρ²) cancels: its rounding error is a few ε·|R|.
        let tol_z = 8.0 * f64::EPSILON * radius.abs();
        prop_assert!((l.z - (radius - sg * w)).abs() <= tol_z, "z {} vs {}", l.z, radius - sg * w);
        // ∇z = sgn·(x, y)/w, ∇²z = sgn·[R² − y², xy; xy, R² − x²]/w³.
        let w3 = w * w * w;
        let r2 = radius * radius;
        let expect = [
            sg * x / w,
            sg * y / w,
            sg * (r2 - y * y) / w3,
            sg * x * y / w3,
            sg * (r2 - x * x) / w3,
        ];
        let got = [l.zx, l.zy, l.zxx, l.zxy, l.zyy];
        for (g, e) in got.iter().zip(expect) {
            prop_assert!((g - e).abs() <= 1e-12 * (1.0 + e.abs()), "{got:?} vs {expect:?}");
        }
        let rim = s.rim_radius_mm().expect("a sphere has a rim");
        prop_assert!((rim - radius.abs()).abs() <= 4.0 * f64::EPSILON * radius.abs());
    }

    #[test]
    fn paraboloid_matches_its_closed_form(
        radius in prop_oneof![1.0..500.0f64, -500.0..-1.0f64],
        x in -50.0..50.0f64,
        y in -50.0..50.0f64,
    ) {
        let s = Asphere::new(&AsphereSpec {
            radius_mm: Some(radius),
            conic: -1.0,
            ..Default::default()
        })
        .unwrap();
        let l = local(&s, x, y);
        let z = (x * x + y * y) / (2.0 * radius);
        prop_assert!((l.z - z).abs() <= 1e-14 * z.abs(), "{} vs {z}", l.z);
        prop_assert!((l.zx - x / radius).abs() <= 1e-14 * (x / radius).abs() + 1e-300);
        prop_assert!((l.zy - y / radius).abs() <= 1e-14 * (y / radius).abs() + 1e-300);
        prop_assert!((l.zxx - 1.0 / radius).abs() <= 1e-14 / radius.abs());
        prop_assert!((l.zyy - 1.0 / radius).abs() <= 1e-14 / radius.abs());
        prop_assert_eq!(l.zxy, 0.0);
        // A paraboloid has no rim: defined everywhere.
        prop_assert_eq!(s.rim_radius_mm(), None);
    }
}

#[test]
fn plane_is_flat_everywhere() {
    let by_curvature = Asphere::new(&AsphereSpec {
        curvature_per_mm: Some(0.0),
        ..Default::default()
    })
    .unwrap();
    for s in [by_curvature, Asphere::plane()] {
        for &(x, y) in &[(0.0, 0.0), (3.0, -4.0), (-1e3, 2e3)] {
            assert_eq!(local(&s, x, y), Local::default(), "({x}, {y})");
        }
        assert_eq!(s.rim_radius_mm(), None);
    }
    // A plane with polynomial terms is the polynomial alone.
    let s = Asphere::new(&AsphereSpec {
        curvature_per_mm: Some(0.0),
        coefficients: vec![2e-4, -3e-6],
        ..Default::default()
    })
    .unwrap();
    let (x, y) = (1.5, -2.0);
    let rho: f64 = 2.5;
    let z = 2e-4 * rho.powi(4) - 3e-6 * rho.powi(6);
    assert!((local(&s, x, y).z - z).abs() < 1e-16);
    // d/dx (A·ρ⁴ + B·ρ⁶) = (4A·ρ² + 6B·ρ⁴)·x.
    let zx = (4.0 * 2e-4 * rho.powi(2) - 6.0 * 3e-6 * rho.powi(4)) * x;
    assert!((local(&s, x, y).zx - zx).abs() < 1e-16);
}

// ---------------------------------------------------------------------------------------------
// XY polynomial

#[derive(Debug, Clone)]
struct XyCase {
    base: AsphereCase,
    norm: f64,
    terms: Vec<(u32, u32, f64)>,
}

fn xy_case() -> impl Strategy<Value = XyCase> {
    let term = (0u32..=10)
        .prop_flat_map(|i| (Just(i), 0u32..=(10 - i), -0.01..0.01f64))
        .prop_map(|(i, j, c)| (i, j, c));
    (
        asphere_case(),
        1.0..10.0f64,
        prop::collection::vec(term, 0..20),
    )
        .prop_map(|(base, norm, raw)| {
            let mut terms: Vec<(u32, u32, f64)> = Vec::new();
            for t in raw {
                if !terms.iter().any(|u| u.0 == t.0 && u.1 == t.1) {
                    terms.push(t);
                }
            }
            XyCase { base, norm, terms }
        })
}

fn build_xy(case: &XyCase) -> XyPolynomial {
    XyPolynomial::new(&XyPolynomialSpec {
        base: AsphereSpec {
            radius_mm: Some(case.base.radius),
            conic: case.base.conic,
            coefficients: case.base.coefficients.clone(),
            ..Default::default()
        },
        norm_radius_mm: case.norm,
        terms: case
            .terms
            .iter()
            .map(|&(x, y, c)| XyTerm {
                x,
                y,
                coefficient_mm: c,
            })
            .collect(),
    })
    .expect("valid XY polynomial")
}

/// A point within the normalisation radius and the base's domain.
fn xy_point(case: &XyCase, t: f64, phi: f64) -> (f64, f64) {
    in_disc(case.norm.min(case.base.max_rho), t, phi)
}

proptest! {
    #![proptest_config(config(256, SEED))]

    #[test]
    fn xy_polynomial_derivatives_match_finite_differences(
        case in xy_case(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 4),
    ) {
        let s = build_xy(&case);
        for (t, phi) in pts {
            let (x, y) = xy_point(&case, t, phi);
            check_derivatives(&s, x, y)?;
        }
    }

    #[test]
    fn xy_polynomial_sag_is_the_base_plus_each_monomial(
        case in xy_case(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 8),
    ) {
        let s = build_xy(&case);
        let b = &case.base;
        for (t, phi) in pts {
            let (x, y) = xy_point(&case, t, phi);
            let base = asphere_reference(1.0 / b.radius, b.conic, &b.coefficients, x, y);
            let poly: f64 = case
                .terms
                .iter()
                .map(|&(i, j, c)| c * (x / case.norm).powi(i as i32) * (y / case.norm).powi(j as i32))
                .sum();
            let z = local(&s, x, y).z;
            let reference = base + poly;
            // Up to 20 terms of ≤ 0.01 mm and a base of a few mm: a few ulps of the larger.
            prop_assert!((z - reference).abs() <= 1e-14 * (1.0 + base.abs()),
                "({x}, {y}): {z} vs {reference}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Lens array: an independent brute-force model

/// The lens array written from its definition, with every lenslet centre listed.
#[derive(Debug, Clone)]
struct LensModel {
    lens_radius: f64,
    aperture: f64,
    pitch: f64,
    grid: Grid,
    form: Form,
    part_radius: f64,
    /// Centres with |c| + a/2 ≤ part radius (the lenslets that are cut).
    cut: Vec<(f64, f64)>,
    /// Every grid node within the part and a pitch beyond.
    all: Vec<(f64, f64)>,
}

impl LensModel {
    fn new(
        lens_radius: f64,
        aperture: f64,
        pitch: f64,
        grid: Grid,
        form: Form,
        part_radius: f64,
    ) -> Self {
        let n = (part_radius / pitch).ceil() as i64 * 2 + 3;
        let (mut cut, mut all) = (Vec::new(), Vec::new());
        for i in -n..=n {
            for j in -n..=n {
                let (cx, cy) = match grid {
                    Grid::Rectangular => (i as f64 * pitch, j as f64 * pitch),
                    Grid::Hexagonal => (
                        (i as f64 + 0.5 * j as f64) * pitch,
                        j as f64 * pitch * 3f64.sqrt() / 2.0,
                    ),
                };
                let d = cx.hypot(cy);
                if d <= part_radius + pitch {
                    all.push((cx, cy));
                }
                if d + aperture / 2.0 <= part_radius {
                    cut.push((cx, cy));
                }
            }
        }
        Self {
            lens_radius,
            aperture,
            pitch,
            grid,
            form,
            part_radius,
            cut,
            all,
        }
    }

    fn spec(&self) -> LensArraySpec {
        LensArraySpec {
            lens_radius_mm: self.lens_radius,
            aperture_mm: self.aperture,
            pitch_mm: self.pitch,
            grid: self.grid,
            form: self.form,
        }
    }

    fn build(&self) -> LensArray {
        LensArray::new(&self.spec(), PartDisc::centred(self.part_radius)).expect("valid lens array")
    }

    /// Sag from the definition: the lenslet whose disc contains the point, else land.
    fn sag(&self, x: f64, y: f64) -> f64 {
        let h = self.aperture / 2.0;
        let inside: Vec<&(f64, f64)> = self
            .cut
            .iter()
            .filter(|(cx, cy)| (x - cx).hypot(y - cy) <= h)
            .collect();
        assert!(inside.len() <= 1, "({x}, {y}) lies in two lenslets");
        match inside.first() {
            None => 0.0,
            Some((cx, cy)) => {
                let rho2 = (x - cx).powi(2) + (y - cy).powi(2);
                let r2 = self.lens_radius * self.lens_radius;
                let rim = (r2 - h * h).sqrt() - (r2 - rho2).sqrt();
                match self.form {
                    Form::Concave => rim,
                    Form::Convex => -rim,
                }
            }
        }
    }

    /// Distance from the point to the nearest lenslet rim (of any grid node) and to the part
    /// edge: the slope may jump there.
    fn distance_to_a_jump(&self, x: f64, y: f64) -> f64 {
        let h = self.aperture / 2.0;
        let rims = self
            .all
            .iter()
            .map(|(cx, cy)| ((x - cx).hypot(y - cy) - h).abs())
            .fold(f64::INFINITY, f64::min);
        rims.min((self.part_radius - x.hypot(y)).abs())
    }
}

fn lens_model() -> impl Strategy<Value = LensModel> {
    (
        0.2..2.0f64,
        1.0..1.5f64,
        0.8..5.0f64,
        prop_oneof![Just(Grid::Rectangular), Just(Grid::Hexagonal)],
        prop_oneof![Just(Form::Convex), Just(Form::Concave)],
        1.5..6.0f64,
    )
        .prop_map(|(a, pitch_ratio, radius_ratio, grid, form, part_ratio)| {
            let pitch = a * pitch_ratio;
            LensModel::new(a * radius_ratio, a, pitch, grid, form, pitch * part_ratio)
        })
}

/// Margin from a rim or the part edge for finite differences, mm (10 steps).
const RIM_MARGIN: f64 = 1e-4;

/// Points from fractions: half inside cut lenslets (away from the rim), half anywhere on the
/// part; those too close to a slope jump are left out.
fn lens_points(m: &LensModel, fractions: &[(f64, f64, f64, bool)]) -> Vec<(f64, f64)> {
    fractions
        .iter()
        .filter_map(|&(u, t, phi, in_lens)| {
            let (x, y) = if in_lens && !m.cut.is_empty() {
                let (cx, cy) = m.cut[((u * m.cut.len() as f64) as usize).min(m.cut.len() - 1)];
                let rho = (m.aperture / 2.0 - 2.0 * RIM_MARGIN) * t.sqrt();
                (cx + rho * phi.cos(), cy + rho * phi.sin())
            } else {
                in_disc(m.part_radius, t, phi)
            };
            (m.distance_to_a_jump(x, y) > RIM_MARGIN).then_some((x, y))
        })
        .collect()
}

fn lens_fractions() -> impl Strategy<Value = Vec<(f64, f64, f64, bool)>> {
    prop::collection::vec((0.0..1.0f64, 0.0..1.0f64, 0.0..2.0 * PI, any::<bool>()), 8)
}

proptest! {
    #![proptest_config(config(256, SEED))]

    #[test]
    fn lens_array_derivatives_match_finite_differences(m in lens_model(), f in lens_fractions()) {
        let s = m.build();
        for (x, y) in lens_points(&m, &f) {
            check_derivatives(&s, x, y)?;
        }
    }

    #[test]
    fn lens_array_sag_matches_a_search_over_every_centre(m in lens_model(), f in lens_fractions()) {
        let s = m.build();
        for (x, y) in lens_points(&m, &f) {
            let z = local(&s, x, y).z;
            let reference = m.sag(x, y);
            // Same formula from a different centre search: only rounding of (x − cx) differs.
            prop_assert!((z - reference).abs() <= 1e-12, "({x}, {y}): {z} vs {reference}");
            if reference == 0.0 {
                prop_assert_eq!(local(&s, x, y), Local::default(), "land at ({}, {})", x, y);
            }
        }
        prop_assert_eq!(s.lenslet_count(), m.cut.len());
        let h = m.aperture / 2.0;
        let depth = m.lens_radius - (m.lens_radius * m.lens_radius - h * h).sqrt();
        let expect = match m.form { Form::Convex => depth, Form::Concave => -depth };
        prop_assert!((s.lenslet_sag_mm() - expect).abs() <= 1e-15 * (1.0 + m.lens_radius));
        // The vertex of every cut lenslet is at the lenslet sag.
        for &(cx, cy) in &m.cut {
            prop_assert!((local(&s, cx, cy).z - expect).abs() <= 1e-12);
        }
    }
}

#[test]
fn paper004_preset_has_69_lenslets_of_minus_44_4_um() {
    // Table 1 of paper 004: Ø10 mm, R 2.84 mm, aperture 1 mm, pitch 1 mm, sag −44.4 µm.
    let m = LensModel::new(2.84, 1.0, 1.0, Grid::Rectangular, Form::Concave, 5.0);
    let s = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(5.0)).unwrap();
    assert_eq!(s.lenslet_count(), m.cut.len());
    // Lattice points with i² + j² ≤ 4.5² = 20.25: 69 of them.
    assert_eq!(m.cut.len(), 69);
    assert!((s.lenslet_sag_mm() * 1e3 + 44.4).abs() < 0.05);
    for &(x, y) in &[(0.3, 0.1), (4.0, 0.2), (0.5, 0.5), (4.7, 0.0), (-3.1, 2.95)] {
        assert!(
            (local(&s, x, y).z - m.sag(x, y)).abs() < 1e-12,
            "({x}, {y})"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Sinusoid

#[derive(Debug, Clone)]
struct SineCase {
    amplitude: f64,
    lx: f64,
    ly: f64,
    px: f64,
    py: f64,
}

fn sine_case() -> impl Strategy<Value = SineCase> {
    (
        prop_oneof![1e-4..0.01f64, -0.01..-1e-4f64],
        0.2..5.0f64,
        0.2..5.0f64,
        0.0..360.0f64,
        -360.0..360.0f64,
    )
        .prop_map(|(amplitude, lx, ly, px, py)| SineCase {
            amplitude,
            lx,
            ly,
            px,
            py,
        })
}

fn build_sine(c: &SineCase) -> Sinusoid {
    Sinusoid::new(&SinusoidSpec {
        amplitude_mm: c.amplitude,
        wavelength_x_mm: c.lx,
        wavelength_y_mm: c.ly,
        phase_x_deg: c.px,
        phase_y_deg: c.py,
    })
    .expect("valid sinusoid")
}

proptest! {
    #![proptest_config(config(256, SEED))]

    #[test]
    fn sinusoid_derivatives_match_finite_differences(
        c in sine_case(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 4),
    ) {
        let s = build_sine(&c);
        for (t, phi) in pts {
            let (x, y) = in_disc(10.0, t, phi);
            check_derivatives(&s, x, y)?;
        }
    }

    #[test]
    fn sinusoid_sag_is_the_product_of_sines(
        c in sine_case(),
        pts in prop::collection::vec((0.0..1.0f64, 0.0..2.0 * PI), 8),
    ) {
        let s = build_sine(&c);
        for (t, phi) in pts {
            let (x, y) = in_disc(10.0, t, phi);
            let z = c.amplitude
                * (2.0 * PI * x / c.lx + c.px.to_radians()).sin()
                * (2.0 * PI * y / c.ly + c.py.to_radians()).sin();
            // Arguments up to ~320 rad formed in a different order: ~1e-13 rad apart.
            prop_assert!((local(&s, x, y).z - z).abs() <= 1e-13 * c.amplitude.abs(),
                "({x}, {y}): {} vs {z}", local(&s, x, y).z);
        }
        prop_assert!((s.feature_length_mm() - c.lx.min(c.ly) / 4.0).abs() < 1e-15);
    }
}

// ---------------------------------------------------------------------------------------------
// Errors

#[test]
fn conics_beyond_their_rim_are_undefined_and_say_where() {
    // Sphere R 5: undefined beyond ρ = 5 and at the rim itself (vertical slope).
    let s = Asphere::new(&AsphereSpec {
        radius_mm: Some(5.0),
        ..Default::default()
    })
    .unwrap();
    let e = s.local(3.0, 4.5).unwrap_err();
    assert_eq!(e.surface, "even asphere");
    assert_eq!((e.x_mm, e.y_mm), (3.0, 4.5));
    assert_eq!(e.radius_mm, 3f64.hypot(4.5));
    let text = e.to_string();
    assert!(
        text.starts_with(&format!(
            "surface: even asphere is undefined at radius {} mm (x 3 mm, y 4.5 mm)",
            spiralcam::field::short(3f64.hypot(4.5))
        )),
        "{text}"
    );
    assert!(text.contains("rim at radius 5 mm"), "{text}");
    assert!(s.local(5.0, 0.0).is_err(), "the rim itself has no slope");
    assert!(s.local(0.0, 4.999).is_ok());
    assert!(s.sag(0.0, -6.0).is_err());

    // Oblate ellipsoid k = 1, R 10: rim at 10/√2.
    let s = Asphere::new(&AsphereSpec {
        radius_mm: Some(10.0),
        conic: 1.0,
        ..Default::default()
    })
    .unwrap();
    let rim = 10.0 / 2f64.sqrt();
    assert!((s.rim_radius_mm().unwrap() - rim).abs() < 1e-14);
    assert!(s.local(rim - 1e-6, 0.0).is_ok());
    let e = s.local(0.0, rim + 1e-6).unwrap_err();
    assert_eq!(e.radius_mm, rim + 1e-6);
    assert!(
        e.reason
            .contains(&format!("{}", s.rim_radius_mm().unwrap()))
    );

    // Hyperboloid (k < −1) and paraboloid: no rim.
    for k in [-1.0, -2.5] {
        let s = Asphere::new(&AsphereSpec {
            radius_mm: Some(10.0),
            conic: k,
            ..Default::default()
        })
        .unwrap();
        assert!(s.local(1e3, -1e3).is_ok(), "k {k}");
    }

    // An XY polynomial inherits its base's domain.
    let s = XyPolynomial::new(&XyPolynomialSpec {
        base: AsphereSpec {
            radius_mm: Some(-4.0),
            ..Default::default()
        },
        norm_radius_mm: 2.0,
        terms: vec![XyTerm {
            x: 1,
            y: 1,
            coefficient_mm: 1e-3,
        }],
    })
    .unwrap();
    let e = s.local(4.0, 1.0).unwrap_err();
    assert_eq!(e.radius_mm, 4f64.hypot(1.0));
    assert!(e.to_string().contains("radius"), "{e}");
}

#[test]
fn bad_parameters_name_their_field() {
    let cases = [
        (
            r#"{"type":"asphere","radius_mm":0}"#,
            "surface.radius_mm",
            "0",
        ),
        (
            r#"{"type":"asphere","radius_mm":5,"curvature_per_mm":0.2}"#,
            "surface.radius_mm",
            "5",
        ),
        (r#"{"type":"asphere"}"#, "surface.radius_mm", "missing"),
        (
            r#"{"type":"asphere","curvature_per_mm":0,"coefficients":[0,0,0,0,0,0,0,0,0,0]}"#,
            "surface.coefficients",
            "10 terms",
        ),
        (
            r#"{"type":"xy_polynomial","base":{"radius_mm":50},"norm_radius_mm":0,"terms":[]}"#,
            "surface.norm_radius_mm",
            "0",
        ),
        (
            r#"{"type":"xy_polynomial","base":{"radius_mm":50},"norm_radius_mm":5,
                "terms":[{"x":6,"y":5,"coefficient_mm":1}]}"#,
            "surface.terms[0]",
            "x6 y5",
        ),
        (
            r#"{"type":"xy_polynomial","base":{"radius_mm":50},"norm_radius_mm":5,
                "terms":[{"x":1,"y":2,"coefficient_mm":1},{"x":1,"y":2,"coefficient_mm":2}]}"#,
            "surface.terms[1]",
            "x1 y2",
        ),
        (
            r#"{"type":"xy_polynomial","base":{},"norm_radius_mm":5,"terms":[]}"#,
            "surface.base.radius_mm",
            "missing",
        ),
        (
            r#"{"type":"lens_array","lens_radius_mm":-1,"aperture_mm":1,"pitch_mm":1,
                "grid":"rectangular","form":"convex"}"#,
            "surface.lens_radius_mm",
            "-1",
        ),
        (
            r#"{"type":"lens_array","lens_radius_mm":2,"aperture_mm":1.5,"pitch_mm":1,
                "grid":"hexagonal","form":"convex"}"#,
            "surface.aperture_mm",
            "1.5",
        ),
        (
            r#"{"type":"lens_array","lens_radius_mm":0.4,"aperture_mm":1,"pitch_mm":1,
                "grid":"hexagonal","form":"concave"}"#,
            "surface.aperture_mm",
            "1",
        ),
        (
            r#"{"type":"lens_array","lens_radius_mm":2,"aperture_mm":1,"pitch_mm":0,
                "grid":"rectangular","form":"concave"}"#,
            "surface.pitch_mm",
            "0",
        ),
        (
            r#"{"type":"sinusoid","amplitude_mm":0.001,"wavelength_x_mm":-2,"wavelength_y_mm":1}"#,
            "surface.wavelength_x_mm",
            "-2",
        ),
        (
            r#"{"type":"sinusoid","amplitude_mm":0.001,"wavelength_x_mm":2,"wavelength_y_mm":0}"#,
            "surface.wavelength_y_mm",
            "0",
        ),
    ];
    check_field_errors(&cases);
    // Non-finite values cannot come from JSON; through the Rust API they name their field.
    let e = Asphere::new(&AsphereSpec {
        radius_mm: Some(10.0),
        conic: f64::NAN,
        ..Default::default()
    })
    .unwrap_err();
    assert_eq!(e.field, "conic");
    let e = Asphere::new(&AsphereSpec {
        curvature_per_mm: Some(0.0),
        coefficients: vec![0.0, 0.0, f64::INFINITY],
        ..Default::default()
    })
    .unwrap_err();
    assert_eq!(e.field, "coefficients[2] (A8)");
    let sine = SinusoidSpec {
        amplitude_mm: f64::NAN,
        wavelength_x_mm: 1.0,
        wavelength_y_mm: 1.0,
        phase_x_deg: 0.0,
        phase_y_deg: 0.0,
    };
    assert_eq!(Sinusoid::new(&sine).unwrap_err().field, "amplitude_mm");
    let sine = SinusoidSpec {
        amplitude_mm: 0.001,
        phase_y_deg: f64::INFINITY,
        ..sine
    };
    assert_eq!(Sinusoid::new(&sine).unwrap_err().field, "phase_y_deg");
    let xy = XyPolynomialSpec {
        base: AsphereSpec {
            radius_mm: Some(50.0),
            ..Default::default()
        },
        norm_radius_mm: 5.0,
        terms: vec![XyTerm {
            x: 2,
            y: 2,
            coefficient_mm: f64::NAN,
        }],
    };
    assert_eq!(
        XyPolynomial::new(&xy).unwrap_err().field,
        "terms[0].coefficient_mm"
    );
    // Unknown fields are rejected by name.
    let e = serde_json::from_str::<SurfaceSpec>(
        r#"{"type":"sinusoid","amplitude_mm":1,"wavelength_x_mm":1,"wavelength_y_mm":1,"wavelenght":2}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("wavelenght"), "{e}");
}

#[test]
fn every_example_job_reads_back_what_it_writes() {
    // The surface's "type" is written by serde's tag and read by hand (family_tag): every
    // family's name must agree, and every field survive, for each example job.
    let dir = format!("{}/../crate/jobs", env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".json"))
        .collect();
    files.sort();
    assert!(files.len() >= 25, "{files:?}");
    for file in files {
        let job = common::example_job(&file);
        let again = spiralcam::job::Job::from_json(&job.to_json())
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(again, job, "{file}");
    }
}

// ---------------------------------------------------------------------------------------------
// Kink-free radius

/// `Surface::kink_free_radius` against `Surface::slope_kinks`: along 72 lines through each of
/// 300 points of the part, no kink lies nearer than the radius said (to 1e-9 mm), for every
/// example job's surface as the spindle sees it and for the families with kinks in more
/// settings (convex and hexagonal lens arrays, a lens array cut turned over or on its normal at a
/// lenslet's vertex, an odd asphere with a cone at its apex); a surface that says "none
/// anywhere" has none along a whole diameter. Where the family's radius is exact (lens
/// arrays, zoned aspheres, away from the part's edge, where uncut lenslets have no rims) the
/// nearest kink on those lines lies within 5 % + 2 µm of it (the lines are 2.5° apart: a
/// circle of 4 mm met 1.25° off its normal is about 1 µm farther; a radius far below the
/// truth would make the compensation ask for kinks it need not).
#[test]
fn no_slope_kink_lies_within_the_kink_free_radius() {
    let jobs_dir = format!("{}/../crate/jobs", env!("CARGO_MANIFEST_DIR"));
    let mut jobs: Vec<(String, spiralcam::job::Job)> = std::fs::read_dir(&jobs_dir)
        .unwrap()
        .filter_map(|e| {
            let name = e.unwrap().file_name().into_string().unwrap();
            name.ends_with(".json")
                .then(|| (name.clone(), common::example_job(&name)))
        })
        .collect();
    let lenses = r#"{"type":"lens_array","lens_radius_mm":2.84,"aperture_mm":0.8,"pitch_mm":1.0"#;
    let concave = r#""grid":"rectangular","form":"concave"}"#;
    let turned = r#","cut":{"piece":"optic","frame":"turned"}"#;
    for (name, surface, part) in [
        (
            "convex",
            format!(r#"{lenses},"grid":"rectangular","form":"convex"}}"#),
            "",
        ),
        (
            "hexagonal",
            format!(r#"{lenses},"grid":"hexagonal","form":"concave"}}"#),
            "",
        ),
        ("turned", format!("{lenses},{concave}"), turned),
        (
            "vertex",
            format!("{lenses},{concave}"),
            r#","normal_axis_at_mm":[1.0,2.0]"#,
        ),
        (
            "cone",
            r#"{"type":"odd_asphere","radius_mm":50,"coefficients":[-0.001,0,2e-5]}"#.into(),
            "",
        ),
    ] {
        let json = common::small_job(name, &surface, 8.0)
            .replace(r#""diameter_mm":8"#, &format!(r#""diameter_mm":8{part}"#));
        let job = spiralcam::job::Job::from_json(&json).unwrap_or_else(|e| panic!("{name}: {e}"));
        jobs.push((name.to_string(), job));
    }
    assert!(jobs.len() > 25);
    let (mut checked, mut tight) = (0, 0);
    for (name, job) in &jobs {
        let surface = job.build_surface().unwrap();
        let big = job.part_radius_mm();
        let exact = job.part.normal_axis_at_mm.is_none()
            && matches!(
                job.surface,
                SurfaceSpec::LensArray(_) | SurfaceSpec::ZonedAsphere(_)
            );
        for k in 0..300 {
            // A spiral of points over the part, irrational in angle.
            let (rho, phi) = (big * ((k as f64 + 0.5) / 300.0).sqrt(), 2.399963 * k as f64);
            let (x, y) = (rho * phi.cos(), rho * phi.sin());
            let free = surface.kink_free_radius(x, y);
            if free == 0.0 {
                continue;
            }
            let reach = free.min(2.0 * big) + 0.5;
            let mut nearest = f64::INFINITY;
            for j in 0..72 {
                let (s, c) = (j as f64 * PI / 72.0).sin_cos();
                let mut kinks = Vec::new();
                let line = spiralcam::surface::Line { x0: x, y0: y, c, s };
                surface.slope_kinks(line, -reach, reach, &mut kinks);
                for t in kinks {
                    assert!(
                        t.abs() >= free - 1e-9,
                        "{name} at ({x}, {y}): a kink at {t} along {j}°·2.5, radius {free}"
                    );
                    nearest = nearest.min(t.abs());
                }
            }
            checked += 1;
            if exact && free.is_finite() && rho < big - 1.5 {
                assert!(
                    nearest <= free * 1.05 + 0.002,
                    "{name} at ({x}, {y}): nearest kink {nearest}, radius {free}"
                );
                tight += 1;
            }
        }
    }
    assert!(checked > 5_000 && tight > 500, "{checked} {tight}");
}
