//! Designers' files in (issue 13), through the public API: files written here by hand.
//!
//! - Every `.zmx` type read (STANDARD, EVENASPH with and without α1, ODDASPHE, TOROIDAL with
//!   its y terms and Zernike terms, BICONICX, XPOLYNOM, SZERNSAG with α1 and a Zernike
//!   decentre, FZERNSAG, GRIDSAG with its `.DAT`) in every lens unit (MM, CM, IN, METER), and
//!   every `.seq` profile (SPH, CON, ASP, SPS XYP, SPS QBF) in every `DIM` and in curvature
//!   mode: the imported job's sag against the closed form written here from the definitions
//!   (OpticStudio's User Guide, Noll's and the Fringe tables, Forbes 2007's first Qbfs
//!   polynomials), within 1e-12 mm (the unit conversions' rounding). One file in UTF-16LE and
//!   UTF-16BE with their marks and in ISO-8859-1 reads as its UTF-8 twin.
//! - The piece and the frame on a freeform odd in x: the optic of a front surface and the mould
//!   of a rear one are turned (g = −f(−x, y), not the mirror image −f(x, y)), the others kept; a
//!   mirror defaults to the optic, turned for the first mirror and kept behind one.
//! - Grid Sag through import: the orientation of a hand-written `.DAT` odd in x and in y, with
//!   the file's derivatives and computed ones, a decentre, and a point without data inside the
//!   part refused naming it.
//! - Errors: an unsupported type, a surface behind a coordinate break, a missing semi-diameter,
//!   a parameter a type does not read, a term beyond degree 10, a short `.DAT`, a `.DAT` with a
//!   line too many, an unknown unit, a CODE V Zernike surface.

use spiralcam::job::design::{DesignChoice, DesignError, DesignJob, job_from_design};
use spiralcam::job::{Frame, Piece};
use spiralcam::surface::import::{ImportError, read_design};
use std::f64::consts::PI;

/// The OpticStudio unit names, CODE V's `DIM` letter and mm per unit.
const UNITS: [(&str, &str, f64); 4] = [
    ("MM", "M", 1.0),
    ("CM", "C", 10.0),
    ("IN", "I", 25.4),
    ("METER", "", 1000.0),
];

/// The conic sag at r².
fn conic(c: f64, k: f64, r2: f64) -> f64 {
    c * r2 / (1.0 + (1.0 - (1.0 + k) * c * c * r2).sqrt())
}

/// The first Noll (Standard) terms, Z1 … Z8.
fn noll(j: usize, rho: f64, t: f64) -> f64 {
    let (s3, s6, s8) = (3f64.sqrt(), 6f64.sqrt(), 8f64.sqrt());
    match j {
        1 => 1.0,
        2 => 2.0 * rho * t.cos(),
        3 => 2.0 * rho * t.sin(),
        4 => s3 * (2.0 * rho * rho - 1.0),
        5 => s6 * rho * rho * (2.0 * t).sin(),
        6 => s6 * rho * rho * (2.0 * t).cos(),
        7 => s8 * (3.0 * rho.powi(3) - 2.0 * rho) * t.sin(),
        8 => s8 * (3.0 * rho.powi(3) - 2.0 * rho) * t.cos(),
        _ => unreachable!(),
    }
}

/// The first Fringe terms, Z1 … Z9.
fn fringe(j: usize, rho: f64, t: f64) -> f64 {
    match j {
        1 => 1.0,
        2 => rho * t.cos(),
        3 => rho * t.sin(),
        4 => 2.0 * rho * rho - 1.0,
        5 => rho * rho * (2.0 * t).cos(),
        6 => rho * rho * (2.0 * t).sin(),
        7 => (3.0 * rho.powi(3) - 2.0 * rho) * t.cos(),
        8 => (3.0 * rho.powi(3) - 2.0 * rho) * t.sin(),
        9 => 6.0 * rho.powi(4) - 6.0 * rho * rho + 1.0,
        _ => unreachable!(),
    }
}

/// Σ cⱼ·Zⱼ((x, y)/N) for the listed (j, c).
fn zernike(z: fn(usize, f64, f64) -> f64, terms: &[(usize, f64)], n: f64, x: f64, y: f64) -> f64 {
    let (rho, t) = (x.hypot(y) / n, y.atan2(x));
    terms.iter().map(|&(j, c)| c * z(j, rho, t)).sum()
}

/// A `.zmx` of an object, the surface `lines` (surface 1) with a glass after it, and an image.
fn zmx(unit: &str, lines: &str) -> String {
    format!(
        "VERS 150514 200 30221\nMODE SEQ\nNAME hand-written\nUNIT {unit} X W X CM MR CPMM\n\
         SURF 0\n  TYPE STANDARD\n  CURV 0.0 0 0 0 0 \"\"\n  DISZ INFINITY\n\
         SURF 1\n  COMM under test\n{lines}  GLAS N-BK7 1 0 1.5168 64.17 0 0 0 0 0 0\n  DISZ 5\n\
         SURF 2\n  TYPE STANDARD\n  CURV 0.0\nSURF 3\n  TYPE STANDARD\n"
    )
}

/// The job of `name` with `choice`; `files` gives data files by name.
fn import(
    name: &str,
    bytes: &[u8],
    choice: DesignChoice,
    files: &[(&str, &str)],
) -> Result<DesignJob, String> {
    let design = read_design(name, bytes).map_err(|e| e.to_string())?;
    job_from_design(&design, &choice, |f| {
        files
            .iter()
            .find(|(n, _)| *n == f)
            .map(|(_, t)| t.to_string())
            .ok_or_else(|| format!("no file {f}"))
    })
    .map_err(|e| e.to_string())
}

fn mould(surface: usize) -> DesignChoice {
    DesignChoice {
        surface: Some(surface),
        piece: Some(Piece::Mould),
        diameter_mm: None,
    }
}

/// The job's surface (in the spindle's frame) against `exact` on 5 circles of 12 points within
/// radius `r`.
fn check(what: &str, job: &DesignJob, r: f64, exact: &dyn Fn(f64, f64) -> f64, tol: f64) {
    let s = job.job.build_surface().unwrap();
    for k in 0..=4 {
        for j in 0..12 {
            let rr = r * k as f64 / 4.0;
            let t = 2.0 * PI * (j as f64 + 0.3) / 12.0;
            let (x, y) = (rr * t.cos(), rr * t.sin());
            let (got, want) = (s.sag(x, y).unwrap(), exact(x, y));
            assert!(
                (got - want).abs() <= tol,
                "{what} at ({x}, {y}): {got} vs {want}"
            );
        }
    }
}

/// Each type's surface lines in `s` mm per unit, and its closed form in mm.
type Case = (&'static str, fn(f64) -> String, fn(f64, f64) -> f64);

fn cases() -> Vec<Case> {
    vec![
        (
            "STANDARD",
            |s| {
                format!(
                    "  TYPE STANDARD\n  CURV {} 0 0 0 0 \"\"\n  CONI -0.5\n  DIAM {} 1 0 0 1 \"\"\n",
                    s / 40.0,
                    4.0 / s
                )
            },
            |x, y| conic(1.0 / 40.0, -0.5, x * x + y * y),
        ),
        (
            "EVENASPH with α1",
            |s| {
                format!(
                    "  TYPE EVENASPH\n  CURV {}\n  CONI -0.8\n  PARM 1 {}\n  PARM 2 {}\n  PARM 3 {}\n  DIAM {}\n",
                    s / 50.0,
                    1e-3 * s,
                    2e-6 * s.powi(3),
                    -3e-9 * s.powi(5),
                    4.0 / s
                )
            },
            |x, y| {
                let r2 = x * x + y * y;
                conic(0.02, -0.8, r2) + 1e-3 * r2 + 2e-6 * r2 * r2 - 3e-9 * r2.powi(3)
            },
        ),
        (
            "EVENASPH without α1",
            |s| {
                format!(
                    "  TYPE EVENASPH\n  CURV {}\n  PARM 1 0\n  PARM 2 {}\n  DIAM {}\n",
                    -s / 30.0,
                    5e-6 * s.powi(3),
                    4.0 / s
                )
            },
            |x, y| {
                let r2 = x * x + y * y;
                conic(-1.0 / 30.0, 0.0, r2) + 5e-6 * r2 * r2
            },
        ),
        (
            "ODDASPHE",
            |s| {
                format!(
                    "  TYPE ODDASPHE\n  CURV {}\n  PARM 1 {}\n  PARM 2 {}\n  PARM 3 {}\n  DIAM {}\n",
                    s / 60.0,
                    2e-3,
                    -3e-5 * s,
                    4e-7 * s * s,
                    4.0 / s
                )
            },
            |x, y| {
                let r = x.hypot(y);
                conic(1.0 / 60.0, 0.0, r * r) + 2e-3 * r - 3e-5 * r * r + 4e-7 * r.powi(3)
            },
        ),
        (
            "TOROIDAL",
            |s| {
                format!(
                    "  TYPE TOROIDAL\n  CURV {}\n  CONI -0.5\n  PARM 0 1\n  PARM 1 {}\n  PARM 2 {}\n  PARM 3 {}\n  \
                     XDAT 1 8 0 0 1 0 0 \"\"\n  XDAT 2 {}\n  XDAT 6 {}\n  XDAT 7 {}\n  XDAT 10 {}\n  DIAM {}\n",
                    -s / 25.0,
                    30.0 / s,
                    2e-3 * s,
                    -1e-5 * s.powi(3),
                    6.0 / s,
                    1e-3 / s,
                    -2e-3 / s,
                    5e-4 / s,
                    4.0 / s
                )
            },
            |x, y| {
                let zy = conic(-1.0 / 25.0, -0.5, y * y) + 2e-3 * y * y - 1e-5 * y.powi(4);
                30.0 - ((30.0 - zy).powi(2) - x * x).sqrt()
                    + zernike(noll, &[(4, 1e-3), (5, -2e-3), (8, 5e-4)], 6.0, x, y)
            },
        ),
        (
            "BICONICX",
            |s| {
                format!(
                    "  TYPE BICONICX\n  CURV {}\n  CONI 0.3\n  PARM 1 {}\n  PARM 2 -1\n  DIAM {}\n",
                    s / 50.0,
                    30.0 / s,
                    4.0 / s
                )
            },
            |x, y| {
                let (cx, cy) = (1.0 / 30.0, 1.0 / 50.0);
                let a = cx * x * x + cy * y * y;
                a / (1.0 + (1.0 - 0.0 * cx * cx * x * x - 1.3 * cy * cy * y * y).sqrt())
            },
        ),
        (
            "XPOLYNOM",
            |s| {
                format!(
                    "  TYPE XPOLYNOM\n  CURV {}\n  XDAT 1 12\n  XDAT 2 {}\n  XDAT 3 {}\n  XDAT 4 {}\n  XDAT 6 {}\n  \
                     XDAT 9 {}\n  XDAT 14 {}\n  DIAM {}\n",
                    s / 80.0,
                    6.0 / s,
                    0.01 / s,
                    -0.02 / s,
                    0.003 / s,
                    0.001 / s,
                    -5e-4 / s,
                    4.0 / s
                )
            },
            |x, y| {
                let (u, v) = (x / 6.0, y / 6.0);
                conic(1.0 / 80.0, 0.0, x * x + y * y) + 0.01 * u - 0.02 * v
                    + 0.003 * u * v
                    + 0.001 * u * u * v
                    - 5e-4 * u * u * v * v
            },
        ),
        (
            "SZERNSAG",
            |s| {
                format!(
                    "  TYPE SZERNSAG\n  CURV {}\n  CONI -1\n  PARM 1 {}\n  PARM 2 {}\n  PARM 9 {}\n  XDAT 1 7\n  \
                     XDAT 2 {}\n  XDAT 4 {}\n  XDAT 6 {}\n  XDAT 8 {}\n  XDAT 9 {}\n  DIAM {}\n",
                    s / 60.0,
                    1e-4 * s,
                    1e-7 * s.powi(3),
                    0.5 / s,
                    5.0 / s,
                    2e-3 / s,
                    1e-3 / s,
                    -4e-4 / s,
                    3e-4 / s,
                    4.0 / s
                )
            },
            |x, y| {
                let r2 = x * x + y * y;
                conic(1.0 / 60.0, -1.0, r2)
                    + 1e-4 * r2
                    + 1e-7 * r2 * r2
                    + zernike(
                        noll,
                        &[(2, 2e-3), (4, 1e-3), (6, -4e-4), (7, 3e-4)],
                        5.0,
                        x - 0.5,
                        y,
                    )
            },
        ),
        (
            "FZERNSAG",
            |s| {
                format!(
                    "  TYPE FZERNSAG\n  CURV {}\n  XDAT 1 9\n  XDAT 2 {}\n  XDAT 6 {}\n  XDAT 7 {}\n  XDAT 10 {}\n  \
                     XDAT 11 {}\n  DIAM {}\n",
                    s / 60.0,
                    5.0 / s,
                    1e-3 / s,
                    -2e-3 / s,
                    4e-4 / s,
                    -3e-4 / s,
                    4.0 / s
                )
            },
            |x, y| {
                conic(1.0 / 60.0, 0.0, x * x + y * y)
                    + zernike(
                        fringe,
                        &[(4, 1e-3), (5, -2e-3), (8, 4e-4), (9, -3e-4)],
                        5.0,
                        x,
                        y,
                    )
            },
        ),
        (
            "GRIDSAG",
            |s| {
                format!(
                    "  TYPE GRIDSAG\n  CURV {}\n  PARM 2 {}\n  UDAD \"grid.DAT\"\n  DIAM {}\n",
                    s / 100.0,
                    1e-6 * s.powi(3),
                    4.0 / s
                )
            },
            |x, y| {
                let r2 = x * x + y * y;
                conic(0.01, 0.0, r2) + 1e-6 * r2 * r2 + odd(x - 0.3, y + 0.2)[0]
            },
        ),
    ]
}

/// A sag odd in x and in y, cubic in each, and `[f, f_x, f_y, f_xy]`.
fn odd(x: f64, y: f64) -> [f64; 4] {
    let (a, b, c, d, e) = (0.011, -0.023, 0.0007, 0.0013, 0.004);
    [
        a * x + b * y + c * x.powi(3) + d * y.powi(3) + e * x * y,
        a + 3.0 * c * x * x + e * y,
        b + 3.0 * d * y * y + e * x,
        e,
    ]
}

/// A `.DAT` of [`odd`] written as OpticStudio documents it: the first point at (−x, +y), rows
/// left to right, then downward; `derivatives` false writes zeros; `nodata` file points (from
/// 0) without data; lengths in mm.
fn dat(
    n: (usize, usize),
    d: (f64, f64),
    dec: (f64, f64),
    derivatives: bool,
    nodata: &[usize],
) -> String {
    let mut t = format!("{} {} {} {} 0 {} {}\n", n.0, n.1, d.0, d.1, dec.0, dec.1);
    let mut k = 0;
    for row in 0..n.1 {
        for col in 0..n.0 {
            let x = (col as f64 - (n.0 - 1) as f64 / 2.0) * d.0;
            let y = ((n.1 - 1) as f64 / 2.0 - row as f64) * d.1;
            let f = odd(x, y);
            let flag = if nodata.contains(&k) { 1 } else { 0 };
            if derivatives {
                t.push_str(&format!(
                    "{:e} {:e} {:e} {:e} {flag}\n",
                    f[0], f[1], f[2], f[3]
                ));
            } else {
                t.push_str(&format!("{:e} 0 0 0 {flag}\n", f[0]));
            }
            k += 1;
        }
    }
    t
}

#[test]
fn every_zmx_type_in_every_unit_is_its_closed_form() {
    let grid = dat((41, 35), (0.25, 0.3), (0.3, -0.2), true, &[]);
    for (unit, _, s) in UNITS {
        for (kind, lines, exact) in cases() {
            let text = zmx(unit, &lines(s));
            let what = format!("{kind} in {unit}");
            let job = import(
                "lens.zmx",
                text.as_bytes(),
                mould(1),
                &[("grid.DAT", &grid)],
            )
            .unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!((job.job.part.diameter_mm - 8.0).abs() < 1e-14, "{what}");
            let cut = job.job.part.cut.unwrap();
            assert_eq!(
                (cut.piece, cut.frame),
                (Piece::Mould, Frame::Design),
                "{what}"
            );
            check(&what, &job, 4.0, &exact, 1e-12);
        }
    }
}

#[test]
fn utf16_and_latin1_files_read_as_their_utf8_twin() {
    let (_, lines, exact) = cases().swap_remove(1);
    let text = zmx("MM", &lines(1.0)).replace("under test", "Linse Ø25");
    let mut le = vec![0xFF, 0xFE];
    le.extend(text.encode_utf16().flat_map(u16::to_le_bytes));
    let mut be = vec![0xFE, 0xFF];
    be.extend(text.encode_utf16().flat_map(u16::to_be_bytes));
    let latin1: Vec<u8> = text.chars().map(|c| c as u32 as u8).collect();
    let twin = import("lens.zmx", text.as_bytes(), mould(1), &[]).unwrap();
    for (what, bytes) in [("UTF-16LE", le), ("UTF-16BE", be), ("ISO-8859-1", latin1)] {
        let design = read_design("lens.ZMX", &bytes).unwrap();
        assert_eq!(design.encoding.name(), what);
        assert_eq!(design.surfaces[1].label.as_deref(), Some("Linse Ø25"));
        let job = import("lens.zmx", &bytes, mould(1), &[]).unwrap();
        assert_eq!(job.job, twin.job, "{what}");
        check(what, &job, 4.0, &exact, 1e-12);
    }
}

/// A `.seq` with `DIM dim` (none when empty), the surface lines and a glass after it.
fn seq(dim: &str, rdm: &str, surface: &str) -> String {
    let dim = if dim.is_empty() {
        String::new()
    } else {
        format!("DIM {dim}\n")
    };
    format!(
        "RDM {rdm};LEN \"hand-written\"\nTITLE 'test; lens'\n{dim}EPD 10\nWL 587.6\nSO 0.0 1e10\n{surface}\n\
         S 0 1\nSI 0 0\nGO\n"
    )
}

#[test]
fn every_seq_profile_in_every_unit_is_its_closed_form() {
    // Forbes 2007, section 3: Q0 = 1, Q1 = (13 − 16x)/√19, Q2 = 2(29 − 4x(25 − 19x))/√190.
    let qbfs = |x: f64, y: f64| {
        let (c, n) = (1.0 / 45.0, 5.0);
        let r2 = x * x + y * y;
        let u2 = r2 / (n * n);
        let q = 0.01 - 0.002 * (13.0 - 16.0 * u2) / 19f64.sqrt()
            + 0.0008 * 2.0 * (29.0 - 4.0 * u2 * (25.0 - 19.0 * u2)) / 190f64.sqrt();
        conic(c, 0.0, r2) + u2 * (1.0 - u2) / (1.0 - c * c * r2).sqrt() * q
    };
    type SeqCase = (
        &'static str,
        fn(f64, bool) -> String,
        Box<dyn Fn(f64, f64) -> f64>,
    );
    let cases: Vec<SeqCase> = vec![
        (
            "SPH",
            |s, radius| {
                format!(
                    "S {} 2 NBK7_SCHOTT\n  CIR {}",
                    if radius { 40.0 / s } else { s / 40.0 },
                    4.0 / s
                )
            },
            Box::new(|x, y| conic(1.0 / 40.0, 0.0, x * x + y * y)),
        ),
        (
            "CON",
            |s, radius| {
                format!(
                    "S {} 2 NBK7_SCHOTT\n  CON\n  K -1.2\n  CIR {}",
                    if radius { -40.0 / s } else { -s / 40.0 },
                    4.0 / s
                )
            },
            Box::new(|x, y| conic(-1.0 / 40.0, -1.2, x * x + y * y)),
        ),
        (
            "ASP",
            |s, radius| {
                format!(
                    "S {} 2 NBK7_SCHOTT\n  ASP\n  K -0.5; A {:e}; B {:e}\n  C {:e}\n  CIR S1 {}",
                    if radius { 50.0 / s } else { s / 50.0 },
                    2e-6 * s.powi(3),
                    -3e-9 * s.powi(5),
                    4e-12 * s.powi(7),
                    4.0 / s
                )
            },
            Box::new(|x, y| {
                let r2 = x * x + y * y;
                conic(0.02, -0.5, r2) + 2e-6 * r2 * r2 - 3e-9 * r2.powi(3) + 4e-12 * r2.powi(4)
            }),
        ),
        (
            "SPS XYP",
            |s, radius| {
                format!(
                    "S {} 2 NBK7_SCHOTT\n  SPS XYP\n  SCO C1 -0.7; SCO NRADIUS {}\n  SCO C2 {:e}; SCO C5 {:e}\n  \
                     SCO C8 {:e}; SCO C13 {:e}\n  CIR {}",
                    if radius { 80.0 / s } else { s / 80.0 },
                    6.0 / s,
                    0.01 / s,
                    0.003 / s,
                    0.001 / s,
                    -5e-4 / s,
                    4.0 / s
                )
            },
            Box::new(|x, y| {
                let (u, v) = (x / 6.0, y / 6.0);
                conic(1.0 / 80.0, -0.7, x * x + y * y)
                    + 0.01 * u
                    + 0.003 * u * v
                    + 0.001 * u * u * v
                    - 5e-4 * u * u * v * v
            }),
        ),
        (
            "SPS QBF",
            |s, radius| {
                format!(
                    "S {} 2 NBK7_SCHOTT\n  SPS QBF\n  SCO NRADIUS {}; SCO QB4 {:e}\n  SCO C4 {:e}; SCO QB8 {:e}\n  CIR {}",
                    if radius { 45.0 / s } else { s / 45.0 },
                    5.0 / s,
                    0.01 / s,
                    -0.002 / s,
                    0.0008 / s,
                    4.0 / s
                )
            },
            Box::new(qbfs),
        ),
    ];
    for (dim, letter, s) in UNITS
        .iter()
        .map(|u| (u.0, u.1, u.2))
        .chain([("none", "", 1.0)])
    {
        if letter.is_empty() && dim != "none" {
            continue; // CODE V has no metres.
        }
        for radius in [true, false] {
            for (kind, surface, exact) in &cases {
                let text = seq(letter, if radius { "Y" } else { "N" }, &surface(s, radius));
                let what = format!("{kind} in DIM {dim}, radius mode {radius}");
                let job = import("lens.seq", text.as_bytes(), mould(1), &[])
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                assert!((job.job.part.diameter_mm - 8.0).abs() < 1e-14, "{what}");
                check(&what, &job, 4.0, exact.as_ref(), 1e-12);
            }
        }
    }
}

/// A `.zmx` of an odd freeform (Extended Polynomial x³ and xy² terms on a sphere) as surface 2,
/// after surface 1 with glass `g1`, with `g2` after it.
fn odd_freeform(g1: &str, g2: &str) -> String {
    format!(
        "MODE SEQ\nUNIT MM\nSURF 0\nSURF 1\n  CURV 0.0\n{g1}SURF 2\n  TYPE XPOLYNOM\n  CURV 0.025\n  XDAT 1 8\n  \
         XDAT 2 1\n  XDAT 8 0.002\n  XDAT 10 0.001\n  DIAM 2\n{g2}SURF 3\n"
    )
}

fn freeform(x: f64, y: f64) -> f64 {
    conic(0.025, 0.0, x * x + y * y) + 0.002 * x.powi(3) + 0.001 * x * y * y
}

#[test]
fn the_optic_of_a_front_surface_is_turned_not_mirrored() {
    let glass = "  GLAS N-BK7\n";
    let mirror = "  GLAS MIRROR\n";
    // (surface before, surface itself, piece asked, frame expected)
    let cases = [
        (
            "",
            glass,
            Some(Piece::Optic),
            Frame::Turned,
            "front surface, optic",
        ),
        (
            "",
            glass,
            Some(Piece::Mould),
            Frame::Design,
            "front surface, mould",
        ),
        (
            glass,
            "",
            Some(Piece::Optic),
            Frame::Design,
            "rear surface, optic",
        ),
        (
            glass,
            "",
            Some(Piece::Mould),
            Frame::Turned,
            "rear surface, mould",
        ),
        (
            "",
            mirror,
            None,
            Frame::Turned,
            "first mirror, the optic by default",
        ),
        (
            mirror,
            mirror,
            None,
            Frame::Design,
            "a mirror behind a mirror",
        ),
        (
            mirror,
            glass,
            Some(Piece::Optic),
            Frame::Design,
            "a lens behind a mirror, optic",
        ),
    ];
    for (g1, g2, piece, frame, what) in cases {
        let text = odd_freeform(g1, g2);
        let choice = DesignChoice {
            surface: Some(2),
            piece,
            diameter_mm: None,
        };
        let job = import("odd.zmx", text.as_bytes(), choice, &[])
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        let cut = job.job.part.cut.unwrap();
        assert_eq!(cut.frame, frame, "{what}");
        assert_eq!(cut.piece, piece.unwrap_or(Piece::Optic), "{what}");
        let s = job.job.build_surface().unwrap();
        for (x, y) in [(1.5, 0.4), (-1.2, -0.9), (0.7, 1.6)] {
            let z = s.sag(x, y).unwrap();
            match frame {
                Frame::Design => assert!((z - freeform(x, y)).abs() < 1e-14, "{what}"),
                Frame::Turned => {
                    // A rotation about Y: g(x, y) = −f(−x, y); the x³ and xy² terms keep their
                    // sign. A mirror image, −f(x, y), would flip them.
                    assert!((z + freeform(-x, y)).abs() < 1e-14, "{what}");
                    assert!((z + freeform(x, y)).abs() > 1e-3, "{what}: mirrored");
                }
            }
        }
        let side = job
            .listing
            .iter()
            .find(|l| l.starts_with("side: "))
            .unwrap();
        assert!(
            side.contains(if g2 == mirror {
                "a mirror"
            } else {
                "refracting"
            }),
            "{side}"
        );
    }
    // A refracting surface needs the piece; the message names both.
    let e = import(
        "odd.zmx",
        odd_freeform("", glass).as_bytes(),
        DesignChoice {
            surface: Some(2),
            ..Default::default()
        },
        &[],
    )
    .unwrap_err();
    assert!(e.contains("choose optic") && e.contains("or mould"), "{e}");
}

#[test]
fn a_grid_sag_dat_keeps_its_orientation_derivatives_and_decentre() {
    let choice = DesignChoice {
        surface: None,
        piece: Some(Piece::Mould),
        diameter_mm: Some(6.0),
    };
    for (derivatives, dec) in [
        (true, (0.0, 0.0)),
        (false, (0.0, 0.0)),
        (true, (0.3, -0.2)),
        (false, (-0.4, 0.25)),
    ] {
        // nx ≠ ny and Δx ≠ Δy: a flip or a transposition shows.
        let text = dat((41, 35), (0.25, 0.3), dec, derivatives, &[]);
        let job = import("grid.DAT", text.as_bytes(), choice, &[]).unwrap();
        let what = format!("derivatives {derivatives}, decentre {dec:?}");
        assert_eq!(job.job.part.cut.unwrap().frame, Frame::Design, "{what}");
        let listed = job.listing.join("\n");
        assert!(
            listed.contains(if derivatives {
                "the file's"
            } else {
                "computed"
            }),
            "{listed}"
        );
        // Cubic in x and in y: the bicubic patches reproduce it to rounding.
        check(
            &what,
            &job,
            3.0,
            &|x, y| odd(x - dec.0, y - dec.1)[0],
            1e-13,
        );
        let s = job.job.build_surface().unwrap();
        let l = s.local(1.3 + dec.0, -2.1 + dec.1).unwrap();
        let f = odd(1.3, -2.1);
        assert!(
            (l.zx - f[1]).abs() < 1e-12
                && (l.zy - f[2]).abs() < 1e-12
                && (l.zxy - f[3]).abs() < 1e-11,
            "{what}"
        );
    }
    // A point without data inside the part: named with its line.
    let text = dat((41, 35), (0.25, 0.3), (0.0, 0.0), true, &[17 * 41 + 21]);
    let e = import("grid.DAT", text.as_bytes(), choice, &[]).unwrap_err();
    assert!(
        e.contains("undefined within the part") && e.contains("no data") && e.contains("line 720"),
        "{e}"
    );
}

#[test]
fn what_cannot_be_read_is_refused_naming_it() {
    let err = |name: &str, text: &str, surface: Option<usize>| {
        let choice = DesignChoice {
            surface,
            piece: Some(Piece::Optic),
            diameter_mm: None,
        };
        import(name, text.as_bytes(), choice, &[]).unwrap_err()
    };
    let e = err(
        "l.zmx",
        &zmx("MM", "  TYPE USERSURF us_freeform.dll\n  DIAM 4\n"),
        Some(1),
    );
    assert!(
        e.contains("surface 1 (line 9) is of type USERSURF us_freeform.dll")
            && e.contains(
                "the types read: STANDARD, EVENASPH, ODDASPHE, TOROIDAL, BICONICX, XPOLYNOM"
            ),
        "{e}"
    );
    let e = err(
        "l.zmx",
        &zmx("MM", "  TYPE QED_TYPE\n  XDAT 1 0\n  DIAM 4\n"),
        Some(1),
    );
    assert!(
        e.contains("QED_TYPE: OpticStudio's Q-type asphere")
            && e.contains("not publicly documented"),
        "{e}"
    );
    let text = "MODE SEQ\nSURF 0\nSURF 1\n  TYPE COORDBRK\n  PARM 3 5\nSURF 2\n  CURV 0.01\n  DIAM 3\nSURF 3\n";
    let e = err("l.zmx", text, Some(2));
    assert!(
        e.contains("behind the coordinate break of surface 1 (line 3)"),
        "{e}"
    );
    let e = err("l.zmx", text, Some(1));
    assert!(e.contains("is of type COORDBRK: a coordinate break"), "{e}");
    let e = err(
        "l.zmx",
        &zmx("MM", "  TYPE EVENASPH\n  CURV 0.01\n"),
        Some(1),
    );
    assert!(
        e.contains("surface 1 has no semi-diameter (DIAM): give the part's diameter"),
        "{e}"
    );
    let e = err(
        "l.zmx",
        &zmx(
            "MM",
            "  TYPE BICONICX\n  PARM 1 30\n  PARM 5 0.25\n  DIAM 4\n",
        ),
        Some(1),
    );
    assert!(
        e.contains("PARM 5 = 0.25 (line 13) is not read for TYPE BICONICX"),
        "{e}"
    );
    let e = err(
        "l.zmx",
        &zmx(
            "MM",
            "  TYPE XPOLYNOM\n  XDAT 1 66\n  XDAT 2 5\n  XDAT 68 0.001\n  DIAM 4\n",
        ),
        Some(1),
    );
    assert!(e.contains("term 66 (x^11·y^0, degree 11)"), "{e}");
    let e = err("l.zmx", &zmx("FURLONG", ""), Some(1));
    assert_eq!(
        e,
        "l.zmx: line 4: lens unit FURLONG: expected MM, CM, IN or METER"
    );
    let e = err(
        "l.seq",
        "SO 0 1e10\nS 50 2 NBK7\n  SPS ZFR\n  SCO C4 0.1\n  CIR 4\nSI 0 0\n",
        Some(1),
    );
    assert!(
        e.contains("SPS ZFR (line 3): no public material gives") && e.contains("SPS XYP, SPS QBF"),
        "{e}"
    );
    // Grid Sag files: short, and a line too many.
    let full = dat((5, 5), (1.0, 1.0), (0.0, 0.0), true, &[]);
    let mut short: Vec<&str> = full.lines().collect();
    short.pop();
    let e = read_design("g.DAT", short.join("\n").as_bytes()).unwrap_err();
    assert!(matches!(e, ImportError::Grid { .. }), "{e}");
    assert!(
        e.to_string()
            .starts_with("g.DAT: the file ends after 24 of the 25 data lines"),
        "{e}"
    );
    let long = dat((5, 5), (1.0, 1.0), (0.0, 0.0), true, &[]) + "0 0 0 0\n";
    let e = read_design("g.DAT", long.as_bytes()).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("g.DAT: line 27: more than the 25 data lines"),
        "{e}"
    );
    // The surface to cut must be chosen when there are several.
    let design = read_design("l.zmx", zmx("MM", "  DIAM 4\n").as_bytes()).unwrap();
    let e = job_from_design(&design, &DesignChoice::default(), |_| Err(String::new())).unwrap_err();
    assert!(
        matches!(e, DesignError::ChooseSurface { count: 2, .. }),
        "{e}"
    );
}
