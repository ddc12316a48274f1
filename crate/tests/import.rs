//! `spiralcam import` and `spiralcam export-grid` as processes (issue 13): a UTF-16 `.zmx`
//! becomes a job that plans, whose NC header and report state the cut, whose sag (`spiralcam
//! sag`) is the design's turned 180° about Y; a Grid Sag surface's `.DAT` is written beside the
//! job and named relative to it; a Grid Sag `.DAT` imports alone; usage errors exit 2, files
//! that give no job exit 1 naming the option that answers them and leave nothing behind; the
//! round trip export-grid → import reproduces a freeform within the bicubic interpolation
//! error, with the file's derivatives and with computed ones (the figures are printed).

use spiralcam::job::Job;
use spiralcam::surface::Surface;
use std::ffi::OsStr;
use std::path::Path;

mod common;
use common::{Scratch, spiralcam, stderr, stdout};

fn run(args: &[&OsStr]) -> std::process::Output {
    spiralcam(args)
}

fn os<P: AsRef<OsStr> + ?Sized>(p: &P) -> &OsStr {
    p.as_ref()
}

/// A front surface (an even asphere with an r² term, glass after it) of semi-diameter 1 mm.
const LENS: &str = "VERS 150514 200 30221\r\nMODE SEQ\r\nUNIT MM X W X CM MR CPMM\r\n\
    SURF 0\r\n  TYPE STANDARD\r\n  CURV 0.0 0 0 0 0 \"\"\r\n  DISZ INFINITY\r\n\
    SURF 1\r\n  COMM front\r\n  TYPE EVENASPH\r\n  CURV 5.0E-2 0 0 0 0 \"\"\r\n  CONI -0.8\r\n\
    PARM 1 1.0E-3\r\n  PARM 2 2.0E-4\r\n  GLAS N-BK7 1 0 1.5168 64.17\r\n  DIAM 1 1 0 0 1 \"\"\r\n\
    MIRR 2 0\r\nSURF 2\r\n  TYPE STANDARD\r\n  CURV -0.01\r\n  DIAM 1\r\nSURF 3\r\n";

fn utf16le(text: &str) -> Vec<u8> {
    let mut b = vec![0xFF, 0xFE];
    b.extend(text.encode_utf16().flat_map(u16::to_le_bytes));
    b
}

/// The design's sag: R 20 mm, k −0.8, α1 r² + α2 r⁴.
fn lens(x: f64, y: f64) -> f64 {
    let (c, r2) = (0.05, x * x + y * y);
    c * r2 / (1.0 + (1.0 - 0.2 * c * c * r2).sqrt()) + 1e-3 * r2 + 2e-4 * r2 * r2
}

/// The z column of `spiralcam sag JOB --at POINTS`.
fn sags(job: &Path, points: &Path) -> Vec<f64> {
    let o = run(&[os("sag"), os(job), os("--at"), os(points)]);
    assert!(o.status.success(), "{}", stderr(&o));
    stdout(&o)
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
        .collect()
}

#[test]
fn a_utf16_zmx_becomes_a_job_that_plans_and_states_its_cut() {
    let dir = Scratch::new("import-zmx");
    let design = dir.path("lens.zmx");
    std::fs::write(&design, utf16le(LENS)).unwrap();
    let job = dir.path("job.json");
    let o = run(&[
        os("import"),
        os(&design),
        os("--surface"),
        os("1"),
        os("--cut"),
        os("optic"),
        os("--out"),
        os(&job),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    for expected in [
        "UTF-16LE, lens unit mm",
        "surface 1 EVENASPH \"front\", semi-diameter 1 mm",
        "CURV 0.05 (line 11): vertex radius 20 mm",
        "PARM 1 = 0.001 (line 13): α1 (r^2)",
        "part diameter 2 mm (twice the semi-diameter, DIAM, line 16)",
        "cut: optic (as chosen): the optic's own surface, the design turned 180° about Y",
        "wrote ",
    ] {
        assert!(out.contains(expected), "{expected:?} not in\n{out}");
    }
    let j = Job::from_json(&std::fs::read_to_string(&job).unwrap()).unwrap();
    assert_eq!(j.part.diameter_mm, 2.0);
    // The sag the planner cuts: the design turned, −f(−x, y).
    let points = dir.write("p.csv", "x_mm,y_mm\n0.3,0.2\n-0.7,0.5\n0,-0.9\n");
    for (z, (x, y)) in sags(&job, &points)
        .into_iter()
        .zip([(0.3, 0.2), (-0.7, 0.5), (0.0, -0.9)])
    {
        assert!((z + lens(-x, y)).abs() < 1e-14, "{z} vs {}", -lens(-x, y));
    }
    // A coarser path than the defaults, to plan quickly.
    let mut small: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&job).unwrap()).unwrap();
    small["strategy"]["feed_mm_per_rev"] = 0.02.into();
    small["strategy"]["sampling"]["points_per_rev"] = 90.into();
    let small_job = dir.write("small.json", &small.to_string());
    let (nc, report) = (dir.path("small.nc"), dir.path("small-report.json"));
    let o = run(&[
        os("plan"),
        os(&small_job),
        os("--nc"),
        os(&nc),
        os("--report"),
        os(&report),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let program = std::fs::read_to_string(&nc).unwrap();
    assert!(
        program.contains(
            "(cut: the optic's own surface, the design turned 180 deg about Y [x -> -x, z -> -z])"
        ),
        "{}",
        &program[..600]
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert!(
        r["cut"]
            .as_str()
            .unwrap()
            .starts_with("the optic's own surface, the design turned")
    );
    // The rear surface (glass before it): the optic is cut in the design's frame.
    let rear = dir.path("rear.json");
    let o = run(&[
        os("import"),
        os(&design),
        os("--surface"),
        os("2"),
        os("--cut"),
        os("optic"),
        os("--out"),
        os(&rear),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("the material is the glass before it, on −Z"),
        "{}",
        stdout(&o)
    );
    assert!(
        stdout(&o).contains("in the design's frame (z kept)"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn a_grid_sag_surface_writes_its_dat_beside_the_job() {
    let dir = Scratch::new("import-grid");
    // 11 × 11 points of 0.25 mm: z = 0.01·x − 0.02·y + 0.003·x·y in mm, its derivatives.
    let mut dat = String::from("11 11 0.25 0.25 0 0 0\n");
    for row in 0..11 {
        for col in 0..11 {
            let (x, y) = ((col as f64 - 5.0) * 0.25, (5.0 - row as f64) * 0.25);
            dat.push_str(&format!(
                "{} {} {} 0.003 0\n",
                0.01 * x - 0.02 * y + 0.003 * x * y,
                0.01 + 0.003 * y,
                -0.02 + 0.003 * x
            ));
        }
    }
    std::fs::create_dir_all(dir.path("design")).unwrap();
    std::fs::write(dir.path("design/surface.DAT"), &dat).unwrap();
    let zmx = "MODE SEQ\nUNIT MM\nSURF 0\nSURF 1\n  TYPE GRIDSAG\n  CURV 0.01\n  UDAD \"surface.DAT\"\n  \
               GLAS MIRROR\n  DIAM 1.2\nSURF 2\n";
    let design = dir.write("design/mirror.zmx", zmx);
    std::fs::create_dir_all(dir.path("jobs")).unwrap();
    let job = dir.path("jobs/m.json");
    let o = run(&[os("import"), os(&design), os("--out"), os(&job)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let written = dir.path("jobs/m.grid.DAT");
    assert_eq!(std::fs::read_to_string(&written).unwrap(), dat);
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&job).unwrap()).unwrap();
    assert_eq!(j["surface"]["data"]["path"], "m.grid.DAT");
    assert!(j["surface"]["data"].get("text").is_none());
    assert_eq!(j["part"]["cut"]["piece"], "optic");
    assert_eq!(j["part"]["cut"]["frame"], "turned");
    let points = dir.write("p.csv", "0.4,-0.3\n");
    let z = sags(&job, &points)[0];
    // Turned: −(sphere + grid) at (−x, y).
    let (x, y): (f64, f64) = (-0.4, -0.3);
    let want = -(0.01 * (x * x + y * y) / (1.0 + (1.0 - 1e-4 * (x * x + y * y)).sqrt()) + 0.01 * x
        - 0.02 * y
        + 0.003 * x * y);
    assert!((z - want).abs() < 1e-14, "{z} vs {want}");
    // The .DAT alone: the diameter and the piece must be given.
    let o = run(&[
        os("import"),
        os(&dir.path("design/surface.DAT")),
        os("--out"),
        os(&dir.path("d.json")),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("(--cut optic or --cut mould)"),
        "{}",
        stderr(&o)
    );
    let o = run(&[
        os("import"),
        os(&dir.path("design/surface.DAT")),
        os("--cut"),
        os("mould"),
        os("--out"),
        os(&dir.path("d.json")),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "a Grid Sag file has none): give the part's diameter in mm (--diameter-mm D)"
        ),
        "{}",
        stderr(&o)
    );
    let o = run(&[
        os("import"),
        os(&dir.path("design/surface.DAT")),
        os("--cut"),
        os("mould"),
        os("--diameter-mm"),
        os("2"),
        os("--out"),
        os(&dir.path("d.json")),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.path("d.grid.DAT").exists());
    // A short grid: exit 1, nothing written.
    let short = dat.trim_end().rsplit_once('\n').unwrap().0;
    std::fs::write(dir.path("design/surface.DAT"), short).unwrap();
    let again = dir.path("jobs/again.json");
    let o = run(&[os("import"), os(&design), os("--out"), os(&again)]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("surface.data = surface.DAT: the file ends after 120 of the 121"),
        "{}",
        stderr(&o)
    );
    assert!(!again.exists() && !dir.path("jobs/again.grid.DAT").exists());
    assert_eq!(
        dir.files(),
        ["d.grid.DAT", "d.json", "design", "jobs", "p.csv"]
    );
}

#[test]
fn wrong_command_lines_exit_2_and_files_that_give_no_job_exit_1() {
    let dir = Scratch::new("import-errors");
    let design = dir.write("lens.zmx", LENS);
    let out = dir.path("j.json");
    for (args, message) in [
        (vec![os("import")], "missing DESIGN"),
        (
            vec![os("import"), os(&design)],
            "import needs --out JOB.json",
        ),
        (
            vec![
                os("import"),
                os(&design),
                os("--out"),
                os(&out),
                os("--cut"),
                os("sideways"),
            ],
            "--cut sideways: must be optic or mould",
        ),
        (
            vec![
                os("import"),
                os(&design),
                os("--out"),
                os(&out),
                os("--surface"),
                os("one"),
            ],
            "--surface one: must be a whole number",
        ),
        (
            vec![
                os("import"),
                os(&design),
                os("--out"),
                os(&out),
                os("--diameter-mm"),
                os("-2"),
            ],
            "--diameter-mm -2: must be a number > 0",
        ),
        (
            vec![os("import"), os(&design), os("--out"), os(&design)],
            "is an input of the job",
        ),
        (
            vec![
                os("export-grid"),
                os(&design),
                os("--nx"),
                os("3"),
                os("--ny"),
                os("9"),
                os("--out"),
                os(&out),
            ],
            "--nx 3: must be a whole number ≥ 5",
        ),
        (
            vec![
                os("export-grid"),
                os(&design),
                os("--nx"),
                os("9"),
                os("--out"),
                os(&out),
            ],
            "export-grid needs --ny N",
        ),
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{message}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(message),
            "{message:?} not in {}",
            stderr(&o)
        );
    }
    for (args, message) in [
        (
            vec![os("import"), os(&design), os("--out"), os(&out)],
            "choose one by its number: 0 STANDARD (object); 1 EVENASPH \"front\", semi-diameter 1 mm; 2 STANDARD, semi-diameter 1 mm; 3 STANDARD (image) (--surface N)",
        ),
        (
            vec![
                os("import"),
                os(&design),
                os("--surface"),
                os("1"),
                os("--out"),
                os(&out),
            ],
            "choose optic (its own surface, cut from the air side) or mould (an insert forming it, cut from the glass side) (--cut optic or --cut mould)",
        ),
        (
            vec![
                os("import"),
                os(&design),
                os("--surface"),
                os("9"),
                os("--cut"),
                os("optic"),
                os("--out"),
                os(&out),
            ],
            "has no surface 9",
        ),
        (
            vec![
                os("import"),
                os(&dir.path("none.zmx")),
                os("--out"),
                os(&out),
            ],
            "none.zmx: No such file",
        ),
        (
            vec![
                os("import"),
                os(&dir.write("lens.txt", "x")),
                os("--out"),
                os(&out),
            ],
            "lens.txt: not a design file spiralcam reads",
        ),
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(1), "{message}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(message),
            "{message:?} not in {}",
            stderr(&o)
        );
    }
    let unsupported = dir.write(
        "u.zmx",
        &LENS.replace("TYPE EVENASPH", "TYPE USERSURF us_x.dll"),
    );
    let o = run(&[
        os("import"),
        os(&unsupported),
        os("--surface"),
        os("1"),
        os("--cut"),
        os("optic"),
        os("--out"),
        os(&out),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("surface 1 (line 8) is of type USERSURF us_x.dll: a type spiralcam does not read; the types read: STANDARD"), "{}", stderr(&o));
    let no_diam = dir.write("n.zmx", &LENS.replace("DIAM 1 1 0 0 1 \"\"", "DIAM 0"));
    let o = run(&[
        os("import"),
        os(&no_diam),
        os("--surface"),
        os("1"),
        os("--cut"),
        os("optic"),
        os("--out"),
        os(&out),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o)
            .contains("no semi-diameter (DIAM): give the part's diameter in mm (--diameter-mm D)"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
    for command in ["import", "export-grid"] {
        let o = run(&[os(command), os("--help")]);
        assert!(o.status.success());
        assert!(
            stdout(&o).starts_with(&format!("spiralcam {command} ")),
            "{}",
            stdout(&o)
        );
    }
}

/// The largest |∂⁴f/∂x⁴|, |∂⁴f/∂y⁴| and |∂⁵f/∂x∂y⁴| over the square of half-width `half`, by
/// central differences of the analytic second derivatives (step 0.01 mm, 25 × 25 samples).
fn high_derivatives(s: &dyn Surface, half: f64) -> [f64; 3] {
    let e = 0.01;
    let yyyy = |x: f64, y: f64| {
        let l = |y| s.local(x, y).unwrap().zyy;
        (l(y + e) - 2.0 * l(y) + l(y - e)) / (e * e)
    };
    let mut m = [0.0f64; 3];
    for i in 0..25 {
        for j in 0..25 {
            let (x, y) = (
                -half + 2.0 * half * i as f64 / 24.0,
                -half + 2.0 * half * j as f64 / 24.0,
            );
            let xx = |x: f64| s.local(x, y).unwrap().zxx;
            m[0] = m[0].max(((xx(x + e) - 2.0 * xx(x) + xx(x - e)) / (e * e)).abs());
            m[1] = m[1].max(yyyy(x, y).abs());
            m[2] = m[2].max(((yyyy(x + e, y) - yyyy(x - e, y)) / (2.0 * e)).abs());
        }
    }
    m
}

#[test]
fn export_grid_then_import_reproduces_a_freeform_within_the_interpolation_error() {
    for example in ["xy-polynomial-freeform.json", "zernike-standard.json"] {
        round_trip(example);
    }
}

/// The round trip of the example job `file`.
fn round_trip(file: &str) {
    let dir = Scratch::new("grid-round-trip");
    let example = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("jobs")
        .join(file);
    let original = Job::from_json(&std::fs::read_to_string(&example).unwrap()).unwrap();
    let r = original.part_radius_mm();
    let job = dir.write("freeform.json", &original.to_json());
    let grid = dir.path("freeform.DAT");
    let o = run(&[
        os("export-grid"),
        os(&job),
        os("--nx"),
        os("101"),
        os("--ny"),
        os("101"),
        os("--out"),
        os(&grid),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("101 x 101 points, spacing 0.122"),
        "{}",
        stdout(&o)
    );
    // The same grid with its derivatives zeroed: spiralcam computes them.
    let text = std::fs::read_to_string(&grid).unwrap();
    let mut lines = text.lines();
    let mut zeroed = format!("{}\n", lines.next().unwrap());
    for l in lines {
        let f: Vec<&str> = l.split_whitespace().collect();
        zeroed.push_str(&format!("{} 0 0 0 {}\n", f[0], f[4]));
    }
    let zeroed_path = dir.write("zeroed.DAT", &zeroed);
    // 201 × 201 points over the part, off the grid points.
    let mut csv = String::from("x_mm,y_mm\n");
    for i in 0..=200 {
        for j in 0..=200 {
            let (x, y) = (
                -r + 2.0 * r * (i as f64 + 0.37) / 201.0,
                -r + 2.0 * r * (j as f64 + 0.61) / 201.0,
            );
            if x.hypot(y) <= r {
                csv.push_str(&format!("{x},{y}\n"));
            }
        }
    }
    let points = dir.write("points.csv", &csv);
    let exact = sags(&job, &points);
    let diameter = format!("{}", 2.0 * r);
    let mut errors = Vec::new();
    for (dat, name) in [(&grid, "file"), (&zeroed_path, "computed")] {
        let imported = dir.path(&format!("{name}.json"));
        let o = run(&[
            os("import"),
            os(dat),
            os("--cut"),
            os("mould"),
            os("--diameter-mm"),
            os(&diameter),
            os("--out"),
            os(&imported),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(stdout(&o).contains(if name == "file" {
            "derivatives: the file's"
        } else {
            "derivatives: all zero in the file, computed"
        }));
        let got = sags(&imported, &points);
        errors.push(
            got.iter()
                .zip(&exact)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max),
        );
    }
    // The bounds of tests/tests/surface_grid_sag.rs: h⁴/384·(|f_xxxx| + |f_yyyy| + h/4·|f_xyyyy|)
    // with the file's derivatives, 2·5h⁴/384·(|f_xxxx| + |f_yyyy|) with computed ones.
    let half = 1.02 * r;
    let h = 2.0 * half / 100.0;
    let [m4x, m4y, m5] = high_derivatives(original.build_surface().unwrap().as_ref(), half);
    let h4 = h.powi(4) / 384.0;
    let bound_file = 1.1 * h4 * (m4x + m4y + h / 4.0 * m5) + 2e-15;
    let bound_computed = 2.0 * 5.0 * h4 * (m4x + m4y) + 2e-15;
    println!(
        "export-grid → import of {} (101 × 101 over ±{half} mm, h {h:.4} mm), through the command \
         line: largest sag error {:.3e} nm with the file's derivatives (bound {:.3e} nm), \
         {:.3e} nm with computed ones (bound {:.3e} nm)",
        original.name,
        errors[0] * 1e6,
        bound_file * 1e6,
        errors[1] * 1e6,
        bound_computed * 1e6
    );
    assert!(errors[0] <= bound_file, "{} > {bound_file}", errors[0]);
    assert!(
        errors[1] <= bound_computed,
        "{} > {bound_computed}",
        errors[1]
    );
}
