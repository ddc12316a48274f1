//! The measured-data readers (issue 15) through the public API, against fixtures that
//! `tests/fixtures/measured/make.py` writes from a known asymmetric pattern and checks against
//! prysm 0.21.1 and SurfaceTopography 1.27.1 (the `.expected.csv` beside each: nanometres in the
//! file's row order); a crop of a real MetroPro 8 file (SurfaceTopography's `metropro-1.dat`)
//! against both readers; the orientation options moving a known asymmetric map; the errors of
//! refused files; and truncated or corrupted files of every format read without a panic.

use proptest::prelude::*;
use spiralcam::surface::measured::{
    self, HeightGrid, MAX_GRID_NODES, MeasuredData, MeasuredError, MeasuredMap, Mirror, Orientation,
};
use std::path::PathBuf;

/// Heights agree with the references within this, nm (the conversions are a product of a few
/// exactly widened f32 header values; the references compute in f64 too).
const TOL_NM: f64 = 1e-9;

fn fixture(name: &str) -> Vec<u8> {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/measured")
        .join(name);
    std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The expected heights (nm, file row order, None for no data) and spacing (m).
struct Expected {
    rows: Vec<Vec<Option<f64>>>,
    dx_m: f64,
    dy_m: f64,
}

fn expected(name: &str) -> Expected {
    let text = String::from_utf8(fixture(&format!("{name}.expected.csv"))).unwrap();
    let key = |k: &str| -> f64 {
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("# {k} ")))
            .unwrap();
        line.rsplit(' ').next().unwrap().parse().unwrap()
    };
    let rows = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            l.split(',')
                .map(|v| (v != "nan").then(|| v.parse().unwrap()))
                .collect()
        })
        .collect();
    Expected {
        rows,
        dx_m: key("dx_m"),
        dy_m: key("dy_m"),
    }
}

fn grid(map: &MeasuredMap) -> &HeightGrid {
    match &map.data {
        MeasuredData::Grid(g) => g,
        MeasuredData::Cloud(_) => panic!("an instrument map is a grid"),
    }
}

/// Reads `name` and checks every node against its expected heights: the file's first row is
/// the highest y, columns run along +x, the origin is the array's centre, heights in mm.
fn check(name: &str) -> MeasuredMap {
    let map = measured::read(name, fixture(name)).unwrap_or_else(|e| panic!("{e}"));
    let want = expected(name);
    let g = grid(&map);
    let (ny, nx) = (want.rows.len(), want.rows[0].len());
    assert_eq!((g.nx, g.ny), (nx, ny), "{name}");
    assert!(
        (g.dx_mm - want.dx_m * 1e3).abs() <= 1e-15 * g.dx_mm,
        "{name} dx {}",
        g.dx_mm
    );
    assert!(
        (g.dy_mm - want.dy_m * 1e3).abs() <= 1e-15 * g.dy_mm,
        "{name} dy {}",
        g.dy_mm
    );
    assert!(
        (g.node(0, 0)[0] + g.node(nx - 1, 0)[0]).abs() < 1e-15,
        "{name}: centred in x"
    );
    assert!(
        (g.node(0, 0)[1] + g.node(0, ny - 1)[1]).abs() < 1e-15,
        "{name}: centred in y"
    );
    let mut worst = 0.0f64;
    for (r, row) in want.rows.iter().enumerate() {
        for (c, w) in row.iter().enumerate() {
            let got = g.height(c, ny - 1 - r);
            match (got, w) {
                (Some(z), Some(w)) => worst = worst.max((z * 1e6 - w).abs()),
                (None, None) => {}
                _ => panic!("{name}: file row {r} column {c}: {got:?} mm, expected {w:?} nm"),
            }
        }
    }
    assert!(worst <= TOL_NM, "{name}: worst {worst:e} nm");
    map
}

#[test]
fn metropro_formats_1_2_3_match_prysm_and_surface_topography() {
    let m = check("metropro-f1.dat");
    assert!(m.source.contains("header format 1"), "{}", m.source);
    assert_eq!(m.len(), 7 * 5 - 3);
    let m = check("metropro-f2.dat");
    assert!(m.source.contains("phase_res 0 (R 4096)"), "{}", m.source);
    let m = check("metropro-f3.dat");
    assert!(m.source.contains("header format 3"), "{}", m.source);
    assert!(m.source.contains("sign inverted"), "{}", m.source);
}

#[test]
fn a_real_metropro_header_reads_as_both_public_readers_read_it() {
    let m = check("metropro-real-crop.dat");
    assert!(m.source.contains("λ 570.0000 nm"), "{}", m.source);
    assert_eq!(m.len(), 32 * 24);
}

#[test]
fn datx_layouts_and_units_match_prysm_and_surface_topography() {
    let m = check("datx-fringes.datx");
    assert!(m.source.contains("named by /MetaData"), "{}", m.source);
    assert!(m.source.contains("from X/Y Converter"), "{}", m.source);
    check("datx-nanometers.datx");
    let m = check("datx-attributes-lateral.datx");
    assert!(m.source.contains("/Measurement/Surface"), "{}", m.source);
    assert!(
        m.source.contains("Lateral Resolution:Value"),
        "{}",
        m.source
    );
    let m = check("datx-measurement-um.datx");
    assert!(m.source.contains("MicroMeters"), "{}", m.source);
    assert!(!m.source.contains("No Data"), "{}", m.source);
}

#[test]
fn refused_datx_files_say_which_object_and_why() {
    let cases = [
        (
            "datx-bad-no-unit.datx",
            "/Measurement/Surface:Unit: missing",
        ),
        (
            "datx-bad-unit.datx",
            "\"Waves\": expected Fringes, NanoMeters",
        ),
        (
            "datx-bad-no-lateral.datx",
            "/Measurement/Surface: no lateral calibration",
        ),
        ("datx-bad-1d.datx", "shape [5]: expected a 2-D map"),
        (
            "datx-bad-two-surfaces.datx",
            "/Data/Surface: 2 datasets ({A}, {B})",
        ),
        (
            "datx-bad-fringes-no-wavelength.datx",
            "Interferometric Scale Factor: missing: a map in fringes needs",
        ),
    ];
    for (name, want) in cases {
        let e = measured::read(name, fixture(name)).unwrap_err().to_string();
        assert!(e.starts_with(name) && e.contains(want), "{name}: {e}");
    }
}

/// A MetroPro header with its fields patched: `(offset, bytes)`.
fn patched(name: &str, patches: &[(usize, &[u8])]) -> Vec<u8> {
    let mut b = fixture(name);
    for (at, bytes) in patches {
        b[*at..*at + bytes.len()].copy_from_slice(bytes);
    }
    b
}

#[test]
fn refused_metropro_files_say_which_byte_and_why() {
    let f1 = "metropro-f1.dat";
    let err = |b: Vec<u8>| measured::metropro::read(f1, &b).unwrap_err().to_string();
    let whole = fixture(f1);
    assert_eq!(
        err(whole[..900].to_vec()),
        "metropro-f1.dat: byte 900: the file ends early: the header's dimensions need 974 \
         bytes (834-byte header, 0 × 0 × 0 intensity values of 2 bytes, 7 × 5 phase values \
         of 4 bytes)"
    );
    assert!(err(whole[..100].to_vec()).contains("byte 100: the file ends inside the header"));
    for cut in [0, 4, 833, 834, 973] {
        assert!(
            measured::metropro::read(f1, &whole[..cut]).is_err(),
            "{cut}"
        );
    }
    assert!(err(patched(f1, &[(4, &[0, 2])])).contains("byte 4: header format 2"));
    assert!(err(patched(f1, &[(6, &[0, 0, 16, 0])])).contains("byte 6: header size 4096"));
    assert!(err(patched(f1, &[(218, &[0, 7])])).contains("byte 218: phase_res 7"));
    assert!(err(patched(f1, &[(168, &[0; 4])])).contains("byte 168: wavelength_in (m) 0e0"));
    assert!(err(patched(f1, &[(184, &[0; 4])])).contains("byte 184: lateral_res 0e0 m"));
    assert!(err(patched(f1, &[(68, &[0, 0])])).contains("byte 68: connected phase array 0 × 5"));
    // Absurd dimensions are refused from the header, before anything is allocated.
    let e = measured::metropro::read(f1, &patched(f1, &[(68, &[0xff; 4])])).unwrap_err();
    assert_eq!(
        e,
        MeasuredError::TooLarge {
            file: f1.into(),
            what: "phase nodes".into(),
            value: 65535 * 65535,
            limit: MAX_GRID_NODES,
        }
    );
    assert!(err(patched(f1, &[(52, &[0xff; 6])])).contains("the file ends early"));
}

#[test]
fn a_csv_cloud_converts_its_units_and_keeps_its_points() {
    let text = "# CMM export\nz_um,x_mm,y_mm\n12.5,1,2\n-3,-1.5,0.25\n";
    let m = measured::read("probe.csv", text.as_bytes().to_vec()).unwrap();
    assert_eq!(m.points(), vec![[1.0, 2.0, 0.0125], [-1.5, 0.25, -0.003]]);
    assert!(m.source.contains("z_um, x_mm, y_mm"), "{}", m.source);
}

/// Every valid node of `g` lands, through `o`, on a node of `turned` with the same height, and
/// the two hold the same number of values.
fn lands_where_it_should(g: &HeightGrid, o: Orientation, turned: &HeightGrid) {
    assert_eq!(g.valid_count(), turned.valid_count(), "{o}");
    for j in 0..g.ny {
        for i in 0..g.nx {
            let [x, y] = g.node(i, j);
            let (u, v) = o.apply(x, y);
            let ti = ((u - turned.x0_mm) / turned.dx_mm).round() as usize;
            let tj = ((v - turned.y0_mm) / turned.dy_mm).round() as usize;
            let [tu, tv] = turned.node(ti, tj);
            assert!(
                (tu - u).abs() < 1e-12 && (tv - v).abs() < 1e-12,
                "{o}: node"
            );
            assert_eq!(turned.height(ti, tj), g.height(i, j), "{o}: ({i}, {j})");
        }
    }
}

#[test]
fn orientation_options_move_an_asymmetric_map_where_they_say() {
    // MetroPro format 2 fixture: 7 × 5, every pixel different, one without a value; its file
    // row 0, column 0 is the top-left corner as the instrument shows it.
    let name = "metropro-f2.dat";
    let map = measured::read(name, fixture(name)).unwrap();
    let g = grid(&map).clone();
    let top_left = g.height(0, g.ny - 1).unwrap();
    let want = expected(name).rows[0][0].unwrap();
    assert!((top_left * 1e6 - want).abs() < TOL_NM);
    for deg in [0, 90, 180, 270] {
        for mirror in [Mirror::None, Mirror::X, Mirror::Y] {
            let o = Orientation::new(deg, mirror).unwrap();
            let turned = map.clone().oriented(o);
            assert_eq!(turned.orientation, o);
            lands_where_it_should(&g, o, grid(&turned));
        }
    }
    // Named cases: a quarter turn counter-clockwise takes the top-left corner (x < 0, y > 0)
    // to the bottom-left (x < 0, y < 0); a mirror in x to the top-right.
    let corner = |o: Orientation| {
        let t = map.clone().oriented(o);
        let t = grid(&t);
        let k = t.z_mm.iter().position(|z| *z == top_left).unwrap();
        t.node(k % t.nx, k / t.nx)
    };
    let [x, y] = corner(Orientation::new(90, Mirror::None).unwrap());
    assert!(x < 0.0 && y < 0.0, "{x} {y}");
    let [x, y] = corner(Orientation::new(0, Mirror::X).unwrap());
    assert!(x > 0.0 && y > 0.0, "{x} {y}");
    // Orientations compose: a quarter turn after a quarter turn is a half turn.
    let q = Orientation::new(90, Mirror::None).unwrap();
    let twice = map.clone().oriented(q).oriented(q);
    assert_eq!(
        twice,
        map.clone()
            .oriented(Orientation::new(180, Mirror::None).unwrap())
    );
}

#[test]
fn orientation_options_move_a_cloud_where_they_say() {
    let text = "x_mm,y_mm,z_mm\n3,1,5\n-2,0.5,7\n";
    let map = measured::read("c.csv", text.as_bytes().to_vec()).unwrap();
    let turned = map.oriented(Orientation::new(270, Mirror::Y).unwrap());
    // Mirror y: (3, 1) → (3, −1); then 270° counter-clockwise: (x, y) → (y, −x) = (−1, −3).
    assert_eq!(turned.points()[0], [-1.0, -3.0, 5.0]);
    assert_eq!(turned.points()[1], [-0.5, 2.0, 7.0]);
}

/// The fixtures whose corruptions the property tests read.
const CORRUPTED: [&str; 4] = [
    "metropro-f3.dat",
    "datx-fringes.datx",
    "datx-nanometers.datx",
    "datx-attributes-lateral.datx",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn truncated_files_are_errors_not_panics(which in 0..CORRUPTED.len(), cut in 0.0..1.0f64) {
        // An error, or (HDF5 files may end in bytes no object uses) the whole file's map.
        let name = CORRUPTED[which];
        let mut b = fixture(name);
        b.truncate((cut * b.len() as f64) as usize);
        if let Ok(m) = measured::read(name, b) {
            prop_assert_eq!(m, measured::read(name, fixture(name)).unwrap());
        }
    }

    #[test]
    fn corrupted_files_read_without_panic(
        which in 0..CORRUPTED.len(),
        edits in proptest::collection::vec((0.0..1.0f64, any::<u8>()), 1..12),
    ) {
        let name = CORRUPTED[which];
        let mut b = fixture(name);
        let n = b.len();
        for (at, v) in edits {
            b[((at * n as f64) as usize).min(n - 1)] = v;
        }
        // Ok or a clear error; a map read from corrupted bytes holds finite heights only.
        if let Ok(m) = measured::read(name, b) {
            prop_assert!(m.points().iter().all(|p| p.iter().all(|v| v.is_finite())));
        }
    }

    #[test]
    fn metropro_header_fields_never_panic_or_overallocate(
        at in 0usize..834,
        v in any::<[u8; 4]>(),
    ) {
        let mut b = fixture("metropro-f1.dat");
        let at = at.min(b.len() - 4);
        b[at..at + 4].copy_from_slice(&v);
        let _ = measured::read("metropro-f1.dat", b);
    }

    #[test]
    fn csv_lines_of_any_text_never_panic(text in "[-+0-9eE.,;# \\t\\nxyzmun_a\u{feff}]{0,120}") {
        let _ = measured::read("p.csv", format!("x_mm,y_mm,z_mm\n{text}").into_bytes());
    }
}
