//! Zemax Grid Sag through the public API.
//!
//! - Orientation: `.DAT` files written here by hand, literally as OpticStudio documents the
//!   format (first line the point at (−x, +y), rows left to right, then downward), of a sag
//!   that is odd in x and in y separately and differs along x and y (so that a flip of either
//!   axis or a transposition shows), on a grid with nx ≠ ny and Δx ≠ Δy. The sag is cubic in
//!   each variable, inside the bicubic space, so the surface must reproduce it to rounding
//!   (1e-14 mm) everywhere, with the file's derivatives and with computed ones (the not-a-knot
//!   spline reproduces cubics).
//! - Decentre, units (mm, cm, in, m: sag and cross derivative scaled, slopes not), the base,
//!   points without data and outside the grid (errors naming the point and the file line),
//!   short and long files (errors naming lines).
//! - Derivatives against central differences inside cells (proptest).
//! - The round trip of part 3: a smooth freeform (the XY polynomial and the Zernike example
//!   jobs) written as a 101 × 101 `.DAT` with its analytic derivatives, read back as `grid_sag`,
//!   against the closed form, with the file's derivatives and with computed ones, within the
//!   bicubic interpolation error bound (derived at the test); the figures are printed.
//! - A planned path on a grid surface through the gouge check; the example job.

mod common;

use common::{check_derivatives, check_example_jobs, check_planned_path, config, example_job};
use proptest::prelude::*;
use spiralcam::job::Job;
use spiralcam::plan::Planner;
use spiralcam::surface::grid_sag::Derivatives;
use spiralcam::surface::grid_sag::dat::GridData;
use spiralcam::surface::grid_sag::export::{GridExtent, sample};
use spiralcam::surface::{AsphereSpec, DataFile, GridSag, GridSagSpec, Surface, SurfaceSpec};

/// Seed of this file's property tests.
const SEED: u64 = 2424;

/// A sag odd in x and odd in y, cubic in each: `f = a·x + b·y + c·x³ + d·y³ + e·x·y`, with its
/// derivatives `[f, f_x, f_y, f_xy]`.
fn odd(x: f64, y: f64) -> [f64; 4] {
    let (a, b, c, d, e) = (0.011, -0.023, 0.0007, 0.0013, 0.004);
    [
        a * x + b * y + c * x * x * x + d * y * y * y + e * x * y,
        a + 3.0 * c * x * x + e * y,
        b + 3.0 * d * y * y + e * x,
        e,
    ]
}

/// A `.DAT` of `f` written by hand as OpticStudio documents it: header, then the points from
/// (−x, +y) rightwards, row after row downwards; lengths in `unit` (0 mm, 1 cm, 2 in, 3 m),
/// slopes as they are, the cross derivative per unit; `derivatives` false writes zeros.
/// `nodata` lists file points (from 0) written without data.
#[allow(clippy::too_many_arguments)]
fn dat(
    f: fn(f64, f64) -> [f64; 4],
    (nx, ny): (usize, usize),
    (dx, dy): (f64, f64),
    (xdec, ydec): (f64, f64),
    unit: u8,
    derivatives: bool,
    nodata: &[usize],
) -> String {
    let s = [1.0, 10.0, 25.4, 1000.0][unit as usize];
    let mut t = format!(
        "{nx} {ny} {} {} {unit} {} {}\n",
        dx / s,
        dy / s,
        xdec / s,
        ydec / s
    );
    let mut k = 0;
    for row in 0..ny {
        // Row 0 is the top: y = +(ny − 1)/2·dy relative to the grid's centre.
        let y = ((ny - 1) as f64 / 2.0 - row as f64) * dy;
        for col in 0..nx {
            let x = (col as f64 - (nx - 1) as f64 / 2.0) * dx;
            let [z, zx, zy, zxy] = f(x, y);
            if nodata.contains(&k) {
                t.push_str("0 0 0 0 1\n");
            } else if derivatives {
                t.push_str(&format!("{:e} {:e} {:e} {:e}\n", z / s, zx, zy, zxy * s));
            } else {
                t.push_str(&format!("{:e} 0 0 0\n", z / s));
            }
            k += 1;
        }
    }
    t
}

fn grid_sag(text: String, base: Option<AsphereSpec>) -> GridSag {
    GridSag::new(&GridSagSpec {
        data: DataFile {
            path: None,
            text: Some(text),
        },
        base,
    })
    .expect("valid grid sag")
}

/// Points spread over [−w, w] × [−h, h], edges included.
fn spread(w: f64, h: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in 0..=23 {
        for j in 0..=17 {
            out.push((
                -w + 2.0 * w * i as f64 / 23.0,
                -h + 2.0 * h * j as f64 / 17.0,
            ));
        }
    }
    out
}

#[test]
fn the_first_point_is_the_upper_left_and_rows_run_down() {
    let (n, d) = ((9, 6), (0.5, 0.3));
    let (w, h) = (4.0 * 0.5, 2.5 * 0.3);
    for derivatives in [true, false] {
        let s = grid_sag(dat(odd, n, d, (0.0, 0.0), 0, derivatives, &[]), None);
        let expected = if derivatives {
            Derivatives::File
        } else {
            Derivatives::Computed
        };
        assert_eq!(s.derivatives(), expected);
        for (x, y) in spread(w, h) {
            let l = s.local(x, y).unwrap();
            let [z, zx, zy, zxy] = odd(x, y);
            for (what, got, want) in [
                ("z", l.z, z),
                ("zx", l.zx, zx),
                ("zy", l.zy, zy),
                ("zxy", l.zxy, zxy),
            ] {
                assert!(
                    (got - want).abs() < 1e-14,
                    "derivatives {derivatives}: {what} at ({x}, {y}): {got} vs {want}"
                );
            }
        }
        // Flipped axes would give the other signs of the odd parts.
        let (x, y) = (1.3, 0.55);
        let z = s.sag(x, y).unwrap();
        assert!((z - odd(-x, y)[0]).abs() > 1e-3 && (z - odd(x, -y)[0]).abs() > 1e-3);
    }
}

#[test]
fn the_grid_is_decentred_and_added_to_the_base() {
    let (xdec, ydec) = (0.7, -0.4);
    let base = AsphereSpec {
        radius_mm: Some(50.0),
        conic: -1.0,
        ..Default::default()
    };
    let s = grid_sag(
        dat(odd, (7, 9), (0.4, 0.25), (xdec, ydec), 0, true, &[]),
        Some(base),
    );
    for (x, y) in spread(1.2, 1.0) {
        let (x, y) = (x + xdec, y + ydec);
        let want = odd(x - xdec, y - ydec)[0] + (x * x + y * y) / 100.0;
        let got = s.sag(x, y).unwrap();
        assert!((got - want).abs() < 1e-14, "({x}, {y}): {got} vs {want}");
    }
    // Beyond the decentred grid's edge: undefined, naming the grid's span.
    let e = s.local(xdec + 1.21, 0.0).unwrap_err().to_string();
    assert!(e.contains("outside the grid, which spans x -0.5"), "{e}");
}

#[test]
fn units_scale_the_sag_and_cross_derivative_but_not_the_slopes() {
    let mm = grid_sag(dat(odd, (7, 5), (0.4, 0.5), (0.2, 0.1), 0, true, &[]), None);
    for unit in 1..=3 {
        let s = grid_sag(
            dat(odd, (7, 5), (0.4, 0.5), (0.2, 0.1), unit, true, &[]),
            None,
        );
        for (x, y) in spread(1.2, 1.0) {
            let (a, b) = (
                s.local(x + 0.2, y + 0.1).unwrap(),
                mm.local(x + 0.2, y + 0.1).unwrap(),
            );
            for (p, q) in [
                (a.z, b.z),
                (a.zx, b.zx),
                (a.zy, b.zy),
                (a.zxy, b.zxy),
                (a.zxx, b.zxx),
            ] {
                // The file holds the values divided by the unit: a rounding of each.
                assert!(
                    (p - q).abs() < 1e-13 * (1.0 + q.abs()),
                    "unit {unit}: {p} vs {q}"
                );
            }
        }
        assert!(
            s.describe()
                .contains(["mm", "cm", "in", "m"][unit as usize])
        );
    }
}

#[test]
fn a_point_without_data_leaves_its_cells_undefined() {
    // File point 16 of a 7 × 5 grid: column 3 of row 3 from the top (line 18), at
    // (−0.4, 0) relative to the centre with Δx 0.4, Δy 0.5.
    let s = grid_sag(
        dat(odd, (7, 5), (0.4, 0.5), (0.0, 0.0), 0, true, &[16]),
        None,
    );
    let e = s.local(-0.6, 0.2).unwrap_err().to_string();
    assert!(
        e.contains("no data at its point in column 3 from −x and row 3 from the top (-0.4 mm, 0 mm, line 18 of the file)"),
        "{e}"
    );
    assert!(s.local(-0.2, -0.3).is_err());
    assert!(s.local(0.1, 0.1).is_ok() && s.local(-0.9, 0.6).is_ok());
    assert!(s.describe().contains("1 points without data"));
    // Computed derivatives spline each run between the holes.
    let s = grid_sag(
        dat(odd, (7, 5), (0.4, 0.5), (0.0, 0.0), 0, false, &[16]),
        None,
    );
    assert_eq!(s.derivatives(), Derivatives::Computed);
    assert!(s.local(1.0, 0.9).is_ok());
}

#[test]
fn short_and_long_files_name_their_lines() {
    let full = dat(odd, (5, 5), (1.0, 1.0), (0.0, 0.0), 0, true, &[]);
    let lines: Vec<&str> = full.lines().collect();
    let short = lines[..20].join("\n");
    let long = format!("{full}0 0 0 0\n");
    let cases = [
        (short, "the file ends after 19 of the 25 data lines"),
        (long, "line 27: more than the 25 data lines"),
        (full.replacen("5 5 1 1", "5 5 1", 1), "line 1: header"),
        (full.replace("\n", "\n\n"), "line 4 is blank"),
    ];
    for (text, needle) in cases {
        let json = serde_json::json!({"type": "grid_sag", "data": {"text": text}}).to_string();
        let e = common::field_error(&json);
        assert_eq!(e.field, "surface.data", "{e}");
        assert_eq!(e.value, "inline data");
        assert!(e.allowed.contains(needle), "{needle}: {e}");
    }
    // A path not read: the command line's job.
    let e = common::field_error(r#"{"type":"grid_sag","data":{"path":"a.dat"}}"#);
    assert!(e.to_string().contains("has not been read"), "{e}");
}

/// A smooth non-polynomial sag (so the interpolation is not exact) with derivatives.
fn wavy(x: f64, y: f64) -> [f64; 4] {
    let (a, k) = (0.002, 1.3);
    let (sx, cx, sy, cy) = (
        (k * x).sin(),
        (k * x).cos(),
        (0.8 * k * y).sin(),
        (0.8 * k * y).cos(),
    );
    [
        a * sx * cy + 0.01 * x * y,
        a * k * cx * cy + 0.01 * y,
        -a * 0.8 * k * sx * sy + 0.01 * x,
        -a * 0.8 * k * k * cx * sy + 0.01,
    ]
}

proptest! {
    #![proptest_config(config(64, SEED))]

    #[test]
    fn derivatives_match_finite_differences_inside_cells(
        derivatives in any::<bool>(),
        (i, j, u, v) in (0usize..10, 0usize..8, 0.05..0.95f64, 0.05..0.95f64),
    ) {
        // The Hessian jumps across cell lines: the differences stay inside a cell.
        let s = grid_sag(dat(wavy, (11, 9), (0.3, 0.35), (0.0, 0.0), 0, derivatives, &[]), None);
        let (x, y) = (-1.5 + (i as f64 + u) * 0.3, -1.4 + (j as f64 + v) * 0.35);
        check_derivatives(&s, x, y)?;
    }
}

/// The largest |∂⁴f/∂x⁴|, |∂⁴f/∂y⁴| and |∂⁵f/∂x∂y⁴| of a surface over [−w, w]², by central
/// differences of its analytic second derivatives (step 1e-3 mm: truncation ~1e-7 of the
/// values, rounding ε·|f″|/1e-9 ~ 1e-9 mm⁻⁴, far below the values used).
fn high_derivatives(s: &dyn Surface, w: f64) -> [f64; 3] {
    let e = 1e-3;
    let mut m = [0.0f64; 3];
    for (x, y) in spread(w - e, w - e) {
        let l = |dx: f64, dy: f64| s.local(x + dx, y + dy).unwrap();
        let (c, xp, xm) = (l(0.0, 0.0), l(e, 0.0), l(-e, 0.0));
        let y4 = |dx: f64| (l(dx, e).zyy - 2.0 * l(dx, 0.0).zyy + l(dx, -e).zyy) / (e * e);
        m[0] = m[0].max(((xp.zxx - 2.0 * c.zxx + xm.zxx) / (e * e)).abs());
        m[1] = m[1].max(y4(0.0).abs());
        m[2] = m[2].max(((y4(e) - y4(-e)) / (2.0 * e)).abs());
    }
    m
}

/// The largest sag error of `grid` against `exact` over the disc of radius `r` (a 201 × 201
/// sweep of the square, off the grid points), mm.
fn largest_error(grid: &dyn Surface, exact: &dyn Surface, r: f64) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..=200 {
        for j in 0..=200 {
            let (x, y) = (
                -r + 2.0 * r * (i as f64 + 0.37) / 201.0,
                -r + 2.0 * r * (j as f64 + 0.61) / 201.0,
            );
            if x.hypot(y) <= r {
                worst = worst.max((grid.sag(x, y).unwrap() - exact.sag(x, y).unwrap()).abs());
            }
        }
    }
    worst
}

#[test]
fn a_freeform_survives_the_dat_round_trip_within_the_interpolation_error() {
    // 101 × 101 points over the part's square (the part radius plus 2 %, so that the path's
    // first point is inside), each example freeform. Error bounds, with P_x and P_y the cubic
    // Hermite interpolations along x and y: f − P_xP_y f = (f − P_x f) + P_x(f − P_y f). The
    // 1-D remainder is at most h⁴/384·|f⁗|; P_x of an error e uses e and h·e_x at the nodes with
    // weights H₀₀ + H₀₁ = 1 and |H₁₀| + |H₁₁| = t(1 − t) ≤ 1/4, so with exact derivatives the
    // error is at most h⁴/384·(|f_xxxx| + |f_yyyy| + h/4·|f_xyyyy|). With computed (not-a-knot
    // spline) derivatives the 1-D error is of the complete spline's order, 5h⁴/384·|f⁗| (de
    // Boor, ch. IV); twice that per direction is allowed for the not-a-knot ends and the tensor
    // product.
    for (file, what) in [
        ("xy-polynomial-freeform.json", "XY polynomial"),
        ("zernike-standard.json", "Zernike"),
    ] {
        let job = example_job(file);
        let exact = job.build_surface().unwrap();
        let r = job.part_radius_mm();
        let half = 1.02 * r;
        let grid = sample(exact.as_ref(), &GridExtent::square(101, 101, half)).unwrap();
        let h = grid.dx_mm;
        let [m4x, m4y, m5] = high_derivatives(exact.as_ref(), half);
        let text = grid.to_dat();
        let from_file = grid_sag(text, None);
        assert_eq!(from_file.derivatives(), Derivatives::File);
        let mut zeroed = GridData::parse(&grid.to_dat()).unwrap();
        for n in &mut zeroed.nodes {
            (n.dz_dx, n.dz_dy, n.d2z_dxdy_per_mm) = (0.0, 0.0, 0.0);
        }
        let computed = grid_sag(zeroed.to_dat(), None);
        assert_eq!(computed.derivatives(), Derivatives::Computed);
        let e_file = largest_error(&from_file, exact.as_ref(), r);
        let e_computed = largest_error(&computed, exact.as_ref(), r);
        let h4 = h.powi(4) / 384.0;
        // The maxima come from 24 × 18 samples (edges included): 10 % is allowed for that.
        let bound_file = 1.1 * h4 * (m4x + m4y + h / 4.0 * m5) + 1e-14;
        let bound_computed = 2.0 * 5.0 * h4 * (m4x + m4y) + 1e-14;
        println!(
            "{what} ({file}), 101 × 101 over ±{half} mm (h {h:.4} mm): largest sag error \
             {:.3e} nm with the file's derivatives (bound {:.3e} nm), {:.3e} nm with computed ones \
             (bound {:.3e} nm)",
            e_file * 1e6,
            bound_file * 1e6,
            e_computed * 1e6,
            bound_computed * 1e6
        );
        assert!(e_file <= bound_file, "{what}: {e_file:e} > {bound_file:e}");
        assert!(
            e_computed <= bound_computed,
            "{what}: {e_computed:e} > {bound_computed:e}"
        );
    }
}

#[test]
fn a_planned_path_touches_without_cutting() {
    // A sphere with a 2 µm ripple, written on a 41 × 41 grid over ±1.6 mm, cut on Ø3: C¹, no
    // kinks; slopes below 0.06 keep the sampling bound of 2000 steps near 0.01 nm.
    let exact = SurfaceSpec::Composite(
        serde_json::from_str(
            r#"{"base":{"type":"asphere","radius_mm":-30},"terms":[{"surface":
                {"type":"sinusoid","amplitude_mm":0.002,"wavelength_x_mm":1.1,"wavelength_y_mm":1.7}}]}"#,
        )
        .unwrap(),
    )
    .build(1.5)
    .unwrap();
    let text = sample(exact.as_ref(), &GridExtent::square(41, 41, 1.6))
        .unwrap()
        .to_dat();
    let job = serde_json::json!({
        "name": "grid",
        "part": {"diameter_mm": 3},
        "surface": {"type": "grid_sag", "data": {"text": text}},
        "tool": {"nose_radius_mm": 0.1, "included_angle_deg": 100},
        "machine": {"spindle_rpm": 300},
        "strategy": {"feed_mm_per_rev": 0.15, "sampling": {"type": "constant_angle", "points_per_rev": 24}}
    });
    // The grid's cells bound its sections (`Surface::section_bounds`): the contacts come from
    // the concave shortcut, held to the same check.
    let planner = Planner::new(&Job::from_json(&job.to_string()).unwrap()).unwrap();
    assert!(planner.path().concavity().is_some());
    let none = |_: f64, _: f64| Vec::new();
    assert!(check_planned_path(&job.to_string(), &none, 2000) > 200);
}

#[test]
fn the_example_job_builds() {
    check_example_jobs(&[(
        "grid-sag.json",
        "grid sag (Zemax DAT) from grid-sag.dat: 33 × 33",
    )]);
}
