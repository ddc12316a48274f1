//! Reproduces paper 004's Table 2 (mean interpolation error, eq 7, of four methods on the
//! Table 1 lens array at five sample spacings) and prints the figures of
//! `crate/docs/rbf-table2.md`:
//!
//! ```text
//! cargo run --release -p spiralcam --example table2            # everything
//! cargo run --release -p spiralcam --example table2 -- bench   # only the 1.5 M-point timing
//! cargo run --release -p spiralcam --example table2 -- csv crate/jobs/scattered-lens-array.csv
//! ```
//!
//! The last form writes the data of the example job `crate/jobs/scattered-lens-array.json`:
//! the lens array sampled at 0.04 mm on the square grid described below, as CSV.
//!
//! Data: the lens array (`LensArraySpec::paper004()` on a Ø10 mm part) sampled on the square
//! grid of nodes (i·h, j·h) with |i·h|, |j·h| ≤ 5 + 2h. Test points: the grid of step
//! 0.0173 mm offset by (0.00317, 0.00212) mm from the origin, inside the part (ρ ≤ 5 mm):
//! 262 045 points, none on a data point or data line.

use spiralcam::surface::DataFile;
use spiralcam::surface::scattered::interpolate::data::{Grid, Samples};
use spiralcam::surface::scattered::interpolate::rbf::{Polynomial, RbfSettings, condition_number};
use spiralcam::surface::scattered::{Method, Scattered, ScatteredSpec};
use spiralcam::surface::{LensArray, LensArraySpec, Line, PartDisc, Surface};
use std::time::Instant;

/// The spacings of Table 2, mm.
const SPACINGS: [f64; 5] = [0.125, 0.08, 0.04, 0.02, 0.01];
/// Paper 004, Table 2 (mm): RBF, Hermite, four-point mean, Shepard.
const PAPER: [(&str, [f64; 5]); 4] = [
    (
        "rbf",
        [8.6338e-4, 3.5278e-4, 1.0250e-4, 2.5318e-5, 7.2162e-6],
    ),
    (
        "hermite",
        [0.0011, 6.0755e-4, 3.1390e-4, 1.5349e-4, 7.9757e-5],
    ),
    ("four_point_mean", [0.0059, 0.0045, 0.0034, 0.0063, 0.0044]),
    (
        "shepard",
        [0.0015, 8.5607e-4, 4.3173e-4, 2.0430e-4, 1.0157e-4],
    ),
];
/// The part radius, mm.
const PART: f64 = 5.0;

fn lens() -> LensArray {
    LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(PART)).expect("Table 1")
}

/// The square data grid of spacing h covering the part with a margin of 2h.
fn data(truth: &dyn Surface, h: f64) -> Samples {
    let k = ((PART + 2.0 * h) / h).floor() as usize;
    let n = 2 * k + 1;
    let grid = Grid {
        x0: -(k as f64) * h,
        y0: -(k as f64) * h,
        dx: h,
        dy: h,
        nx: n,
        ny: n,
    };
    let z = (0..n)
        .flat_map(|j| (0..n).map(move |i| (i, j)))
        .map(|(i, j)| {
            let p = grid.node(i, j);
            truth.sag(p[0], p[1]).expect("defined")
        })
        .collect();
    Samples::from_grid(grid, z, Vec::new()).expect("grid")
}

/// Test points of eq 7: an offset grid of step `step` inside the part.
fn test_points(step: f64) -> Vec<[f64; 2]> {
    let n = (2.0 * PART / step).ceil() as i64;
    let mut out = Vec::new();
    for j in -n..=n {
        for i in -n..=n {
            let (x, y) = (i as f64 * step + 0.00317, j as f64 * step + 0.00212);
            if x.hypot(y) <= PART {
                out.push([x, y]);
            }
        }
    }
    out
}

fn spec(method: Method) -> ScatteredSpec {
    ScatteredSpec {
        method,
        ..ScatteredSpec::new(DataFile::default())
    }
}

fn surface(spec: &ScatteredSpec, samples: Samples) -> Scattered {
    Scattered::from_samples(spec, samples, PartDisc::centred(PART)).expect("valid")
}

/// Mean and largest |f − g| over the points (eq 7), mm.
fn errors(f: &dyn Surface, g: &dyn Surface, points: &[[f64; 2]]) -> (f64, f64) {
    let (mut sum, mut max) = (0.0, 0.0f64);
    for p in points {
        let e = (f.sag(p[0], p[1]).expect("inside") - g.sag(p[0], p[1]).expect("g")).abs();
        sum += e;
        max = max.max(e);
    }
    (sum / points.len() as f64, max)
}

fn table2(points: &[[f64; 2]]) {
    let g = lens();
    println!(
        "## Table 2: mean error (eq 7) on the lens array, nm ({} test points)\n",
        points.len()
    );
    println!(
        "| method | {} |",
        SPACINGS.map(|h| format!("{h} mm")).join(" | ")
    );
    println!("|---|---|---|---|---|---|");
    let methods = [
        ("rbf", Method::Rbf),
        ("hermite", Method::Hermite),
        ("four_point_mean", Method::FourPointMean),
        ("shepard", Method::Shepard),
    ];
    let sets: Vec<Samples> = SPACINGS.iter().map(|&h| data(&g, h)).collect();
    for ((name, m), (_, paper)) in methods.iter().zip(PAPER) {
        let mut ours = Vec::new();
        for s in &sets {
            let t = Instant::now();
            let f = surface(&spec(*m), s.clone());
            let (mean, max) = errors(&f, &g, points);
            eprintln!(
                "{name} h {}: mean {:.2} nm, max {:.1} nm, {:.1} s",
                f.spacing_mm(),
                mean * 1e6,
                max * 1e6,
                t.elapsed().as_secs_f64()
            );
            ours.push(mean);
        }
        println!(
            "| {name} (ours) | {} |",
            ours.iter()
                .map(|e| format!("{:.1}", e * 1e6))
                .collect::<Vec<_>>()
                .join(" | ")
        );
        println!(
            "| {name} (paper) | {} |",
            paper
                .iter()
                .map(|e| format!("{:.1}", e * 1e6))
                .collect::<Vec<_>>()
                .join(" | ")
        );
    }
    println!(
        "\nData points per spacing: {}\n",
        sets.iter()
            .map(|s| s.len().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
}

/// The RBF's variants: neighbours and polynomial.
fn rbf_variants(points: &[[f64; 2]]) {
    let g = lens();
    println!("## RBF variants: mean (max) error, nm\n");
    println!(
        "| variant | {} |",
        SPACINGS.map(|h| format!("{h} mm")).join(" | ")
    );
    println!("|---|---|---|---|---|---|");
    let sets: Vec<Samples> = SPACINGS.iter().map(|&h| data(&g, h)).collect();
    let variants: Vec<(String, ScatteredSpec)> = vec![
        (
            "n 4, linear".into(),
            ScatteredSpec {
                neighbours: Some(4),
                ..spec(Method::Rbf)
            },
        ),
        ("n 8, linear (default)".into(), spec(Method::Rbf)),
        (
            "n 10, linear".into(),
            ScatteredSpec {
                neighbours: Some(10),
                ..spec(Method::Rbf)
            },
        ),
        (
            "n 8, constant (c → ∞)".into(),
            ScatteredSpec {
                rbf_polynomial: Some(Polynomial::Constant),
                ..spec(Method::Rbf)
            },
        ),
        (
            "n 8, none, c 0 (eq 6)".into(),
            ScatteredSpec {
                rbf_polynomial: Some(Polynomial::None),
                ..spec(Method::Rbf)
            },
        ),
        (
            "n 8, none, c 10 (eq 6)".into(),
            ScatteredSpec {
                rbf_polynomial: Some(Polynomial::None),
                rbf_c: Some(10.0),
                ..spec(Method::Rbf)
            },
        ),
        (
            "n 8, none, c 100, scale 10".into(),
            ScatteredSpec {
                rbf_polynomial: Some(Polynomial::None),
                rbf_c: Some(100.0),
                rbf_scale: Some(10.0),
                ..spec(Method::Rbf)
            },
        ),
    ];
    for (name, sp) in variants {
        let cells: Vec<String> = sets
            .iter()
            .map(|s| {
                let f = surface(&sp, s.clone());
                let (mean, max) = errors(&f, &g, points);
                format!("{:.1} ({:.0})", mean * 1e6, max * 1e6)
            })
            .collect();
        println!("| {name} | {} |", cells.join(" | "));
    }
    println!();
}

/// Condition numbers of the local systems on a regular grid: every distinct neighbour set
/// of the queries in one cell (a 64 × 64 scan).
fn conditioning() {
    println!("## Condition numbers (2-norm) of the local systems on a regular grid\n");
    println!("| n | polynomial | sets | largest | smallest |");
    println!("|---|---|---|---|---|");
    let g = lens();
    let samples = data(&g, 0.04);
    for n in [4, 8, 10] {
        for poly in [Polynomial::Linear, Polynomial::Constant, Polynomial::None] {
            let sp = ScatteredSpec {
                neighbours: Some(n),
                rbf_polynomial: Some(poly),
                ..spec(Method::Rbf)
            };
            let f = surface(&sp, samples.clone());
            let (sets, hi, lo) = grid_conditions(&f, n);
            let name = format!("{poly:?}").to_lowercase();
            println!("| {n} | {name} | {sets} | {hi:.0} | {lo:.1} |");
        }
    }
    println!();
}

/// Distinct neighbour sets of queries in the cell [0, h]² and their largest and smallest
/// condition numbers.
fn grid_conditions(f: &Scattered, n: usize) -> (usize, f64, f64) {
    let h = f.spacing_mm();
    let st: RbfSettings = f.rbf_settings();
    let mut seen: Vec<Vec<u32>> = Vec::new();
    let (mut hi, mut lo) = (0.0f64, f64::INFINITY);
    for i in 0..64 {
        for j in 0..64 {
            let q = [(i as f64 + 0.5) / 64.0 * h, (j as f64 + 0.5) / 64.0 * h];
            let mut pieces = Vec::new();
            f.pieces(
                Line {
                    x0: q[0],
                    y0: q[1],
                    c: 1.0,
                    s: 0.0,
                },
                0.0,
                0.0,
                &mut pieces,
            );
            let set = pieces[0].set.indices().to_vec();
            if !seen.contains(&set) {
                let c: Vec<[f64; 2]> = set
                    .iter()
                    .map(|&k| f.samples().points[k as usize])
                    .collect();
                let k = condition_number(&c, &st);
                hi = hi.max(k);
                lo = lo.min(k);
                seen.push(set);
            }
        }
    }
    assert!(seen.iter().all(|s| s.len() == n));
    (seen.len(), hi, lo)
}

/// Jumps of the interpolant where the neighbour set switches, along 24 radial lines.
fn jumps() {
    println!(
        "## Jumps of the surface at neighbour-set switches (24 radial sections, ρ 0…4.9 mm), nm\n"
    );
    println!("| method | spacing mm | switches | median | 90 % | max |");
    println!("|---|---|---|---|---|---|");
    let g = lens();
    for m in [Method::Rbf, Method::Shepard, Method::FourPointMean] {
        for &h in &SPACINGS {
            let f = surface(&spec(m), data(&g, h));
            let mut j = switch_jumps(&f);
            j.sort_by(f64::total_cmp);
            let q = |p: f64| j[((j.len() - 1) as f64 * p) as usize] * 1e6;
            println!(
                "| {m:?} | {h} | {} | {:.2} | {:.2} | {:.1} |",
                j.len(),
                q(0.5),
                q(0.9),
                q(1.0)
            );
        }
    }
    println!();
}

fn switch_jumps(f: &Scattered) -> Vec<f64> {
    let mut out = Vec::new();
    for k in 0..24 {
        let theta = k as f64 * 2.399963229728653 + 0.1;
        let line = Line::radial(theta.cos(), theta.sin());
        let mut pieces = Vec::new();
        f.pieces(line, 0.0, 4.9, &mut pieces);
        for p in pieces.iter().skip(1) {
            let e = 1e-9;
            let (a, b) = (line.at(p.start - e), line.at(p.start + e));
            out.push((f.sag(b.0, b.1).expect("in") - f.sag(a.0, a.1).expect("in")).abs());
        }
    }
    out
}

/// Convergence on a smooth closed-form surface.
fn smooth() {
    println!(
        "## Smooth surface z = 0.01·sin(2x + 0.3)·cos(1.5y − 0.2) + (x² + y²)/40: mean (max) error, nm\n"
    );
    struct Smooth;
    impl std::fmt::Debug for Smooth {
        fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            write!(f, "smooth")
        }
    }
    impl Surface for Smooth {
        fn local(
            &self,
            x: f64,
            y: f64,
        ) -> Result<spiralcam::surface::Local, spiralcam::surface::UndefinedError> {
            Ok(spiralcam::surface::Local {
                z: 0.01 * (2.0 * x + 0.3).sin() * (1.5 * y - 0.2).cos() + (x * x + y * y) / 40.0,
                ..Default::default()
            })
        }
        fn feature_length_mm(&self) -> f64 {
            1.0
        }
        fn describe(&self) -> String {
            "smooth".into()
        }
    }
    let points = test_points(0.0373);
    println!(
        "| method | {} | order |",
        SPACINGS.map(|h| format!("{h} mm")).join(" | ")
    );
    println!("|---|---|---|---|---|---|---|");
    for m in [
        Method::Rbf,
        Method::Hermite,
        Method::Shepard,
        Method::FourPointMean,
    ] {
        let e: Vec<(f64, f64)> = SPACINGS
            .iter()
            .map(|&h| errors(&surface(&spec(m), data(&Smooth, h)), &Smooth, &points))
            .collect();
        let order = (e[3].0 / e[4].0).log2();
        println!(
            "| {m:?} | {} | {order:.2} |",
            e.iter()
                .map(|(a, b)| format!("{:.4} ({:.3})", a * 1e6, b * 1e6))
                .collect::<Vec<_>>()
                .join(" | ")
        );
    }
    println!();
}

/// The 1.5 M query points of the timing: the centres of a 1382 × 1382 grid over the part's
/// bounding square, inside the part.
fn bench_points() -> Vec<[f64; 2]> {
    let n = 1382;
    let q = 2.0 * PART / n as f64;
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (-PART + (i as f64 + 0.5) * q, -PART + (j as f64 + 0.5) * q);
            if x * x + y * y <= PART * PART {
                out.push([x, y]);
            }
        }
    }
    out
}

fn bench() {
    let g = lens();
    let samples = data(&g, 0.04);
    let points = bench_points();
    let f = surface(&spec(Method::Rbf), samples.clone());
    println!(
        "## Timing: RBF (n 8, linear) on the 0.04 mm data ({} points), one thread\n",
        samples.len()
    );
    for (what, derivs) in [("sag", false), ("sag + gradient + Hessian", true)] {
        let t = Instant::now();
        let mut sum = 0.0;
        for p in &points {
            sum += if derivs {
                f.local(p[0], p[1]).expect("in").z
            } else {
                f.sag(p[0], p[1]).expect("in")
            };
        }
        let s = t.elapsed().as_secs_f64();
        println!(
            "- {what}: {} points in {s:.2} s: {:.0} points/s (checksum {sum:.6})",
            points.len(),
            points.len() as f64 / s
        );
    }
    let (mean, max) = errors(&f, &g, &points);
    println!(
        "- mean error {:.2} nm, max {:.1} nm over the {} points\n",
        mean * 1e6,
        max * 1e6,
        points.len()
    );
}

/// Writes the 0.04 mm data set as CSV (x, y to 0.01 µm, z to 0.1 pm).
fn write_csv(path: &str) {
    use std::io::Write;
    let s = data(&lens(), 0.04);
    let mut out = std::io::BufWriter::new(std::fs::File::create(path).expect("create"));
    writeln!(out, "# paper 004 Table 1 lens array (R 2.84 mm, aperture 1 mm, pitch 1 mm, concave), Ø10 mm part, sampled every 0.04 mm").expect("write");
    writeln!(out, "x_mm,y_mm,z_mm").expect("write");
    for (p, z) in s.points.iter().zip(&s.z) {
        writeln!(out, "{:.5},{:.5},{:.10}", p[0], p[1], z).expect("write");
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(k) = args.iter().position(|a| a == "csv") {
        write_csv(
            args.get(k + 1)
                .map_or("scattered-lens-array.csv", String::as_str),
        );
        return;
    }
    let only_bench = args.iter().any(|a| a == "bench");
    if !only_bench {
        let points = test_points(0.0173);
        table2(&points);
        rbf_variants(&points);
        conditioning();
        jumps();
        smooth();
    }
    bench();
}
