//! STEP faces through the public API: STEP files written here (a small Part 21 writer, below)
//! from nets known in closed form (`nurbs_nets`), imported, and compared with the same net given
//! as JSON (`nurbs`) and with the closed form; face selection; length units; flip and offset;
//! malformed files; the example job; a whole planned path through the brute-force gouge check.
//!
//! Reals are written with 17 significant digits, which read back to the same double, so a file
//! in millimetres gives the very surface of its JSON net: the sags are compared for equality. A
//! file in inches holds each coordinate divided by 25.4 and rounded, then multiplied back by
//! 25.4: two roundings of 1.1e-16 relative on coordinates ≤ 6 mm move a point by < 2e-15 mm,
//! and the sag by less than that times (1 + |∇z|): 1e-13 mm is asserted.

mod common;
mod nurbs_nets;

use common::{check_planned_path, example_job, local};
use nurbs_nets::{clamped, polynomial_net, sphere, sphere_cap};
use spiralcam::job::Job;
use spiralcam::plan::Planner;
use spiralcam::surface::DataFile;
use spiralcam::surface::step_face::{FaceChoice, StepUnits};
use spiralcam::surface::{
    Nurbs, NurbsSpec, PartDisc, StepFace, StepFaceSpec, Surface, SurfaceSpec,
};

/// The sphere of the caps, mm, and the part radius of the tests.
const R: f64 = 20.0;
const PART: f64 = 5.0;

fn sphere_net() -> NurbsSpec {
    let a = 0.14;
    sphere_cap(R, 2, &clamped(2, -a, a, &[-0.5 * a, 0.0, 0.5 * a]))
}

/// A bicubic polynomial freeform: a paraboloid plus a few µm of cubic terms, control points on
/// a sheared grid.
fn freeform_net() -> NurbsSpec {
    let x = vec![(1.0, 1, 0), (0.05, 0, 1)];
    let y = vec![(1.0, 0, 1)];
    let z = vec![
        (1.0 / 60.0, 2, 0),
        (1.0 / 60.0, 0, 2),
        (2e-5, 3, 0),
        (-3e-5, 1, 2),
    ];
    let k = clamped(3, -6.0, 6.0, &[-2.0, 1.0, 3.5]);
    polynomial_net(3, 3, &k, &k, [&x, &y, &z])
}

/// A Part 21 real with 17 significant digits.
fn real(v: f64) -> String {
    format!("{v:.16E}")
}

/// Writes STEP instances for nets.
struct Writer {
    lines: Vec<String>,
    next: u64,
}

impl Writer {
    fn new(first: u64) -> Self {
        Self {
            lines: Vec::new(),
            next: first,
        }
    }

    fn add(&mut self, text: String) -> u64 {
        let id = self.next;
        self.next += 1;
        self.lines.push(format!("#{id} = {text};"));
        id
    }

    /// The length unit `mm` per file unit (1: millimetres, 25.4: inches) and its context.
    fn units(&mut self, inch: bool) {
        let mm = self.add("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )".into());
        let unit = if inch {
            let m = self.add(format!(
                "LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#{mm})"
            ));
            let dims = self.add("DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.)".into());
            self.add(format!(
                "( CONVERSION_BASED_UNIT('INCH',#{m}) LENGTH_UNIT() NAMED_UNIT(#{dims}) )"
            ))
        } else {
            mm
        };
        let rad = self.add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )".into());
        self.add(format!(
            "( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{unit},#{rad})) \
             REPRESENTATION_CONTEXT('','') )"
        ));
    }

    /// The net as a surface (coordinates divided by `per_unit` mm): a plain
    /// B_SPLINE_SURFACE_WITH_KNOTS without weights, the rational complex instance with them.
    fn surface(&mut self, spec: &NurbsSpec, per_unit: f64, name: &str) -> u64 {
        let rows: Vec<String> = spec
            .control_points
            .iter()
            .map(|row| {
                let ids: Vec<String> = row
                    .iter()
                    .map(|p| {
                        let c: Vec<String> = p.iter().map(|v| real(v / per_unit)).collect();
                        format!(
                            "#{}",
                            self.add(format!("CARTESIAN_POINT('',({}))", c.join(",")))
                        )
                    })
                    .collect();
                format!("({})", ids.join(","))
            })
            .collect();
        let points = format!("({})", rows.join(","));
        let (mu, ku) = compress(&spec.knots_u);
        let (mv, kv) = compress(&spec.knots_v);
        let (p, q) = (spec.degree_u, spec.degree_v);
        match &spec.weights {
            None => self.add(format!(
                "B_SPLINE_SURFACE_WITH_KNOTS('{name}',{p},{q},{points},.UNSPECIFIED.,.F.,.F.,.F.,\
                 {mu},{mv},{ku},{kv},.UNSPECIFIED.)"
            )),
            Some(w) => {
                let rows: Vec<String> = w
                    .iter()
                    .map(|r| {
                        let r: Vec<String> = r.iter().map(|&v| real(v)).collect();
                        format!("({})", r.join(","))
                    })
                    .collect();
                self.add(format!(
                    "( BOUNDED_SURFACE() B_SPLINE_SURFACE({p},{q},{points},.UNSPECIFIED.,.F.,.F.,\
                     .F.) B_SPLINE_SURFACE_WITH_KNOTS({mu},{mv},{ku},{kv},.UNSPECIFIED.) \
                     GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE(({})) \
                     REPRESENTATION_ITEM('{name}') SURFACE() )",
                    rows.join(",")
                ))
            }
        }
    }

    fn file(&self) -> String {
        format!(
            "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('test'),'2;1');\n\
             FILE_NAME('t.step','2025-01-01T00:00:00',(''),(''),'','','');\n\
             FILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{}\nENDSEC;\nEND-ISO-10303-21;\n",
            self.lines.join("\n")
        )
    }
}

/// Distinct knots and multiplicities, as STEP lists: `((m, …), (k, …))`.
fn compress(knots: &[f64]) -> (String, String) {
    let mut mults: Vec<usize> = Vec::new();
    let mut values: Vec<f64> = Vec::new();
    for &k in knots {
        if values.last() == Some(&k) {
            *mults.last_mut().unwrap() += 1;
        } else {
            values.push(k);
            mults.push(1);
        }
    }
    let m: Vec<String> = mults.iter().map(|m| m.to_string()).collect();
    let v: Vec<String> = values.iter().map(|&v| real(v)).collect();
    (format!("({})", m.join(",")), format!("({})", v.join(",")))
}

/// A file holding `nets` (in mm or inches).
fn file_of(nets: &[&NurbsSpec], inch: bool) -> String {
    let mut w = Writer::new(1);
    w.units(inch);
    let per_unit = if inch { 25.4 } else { 1.0 };
    for (k, net) in nets.iter().enumerate() {
        w.surface(net, per_unit, &format!("face {k}"));
    }
    w.file()
}

fn spec(text: String) -> StepFaceSpec {
    StepFaceSpec {
        file: DataFile {
            path: Some("t.step".into()),
            text: Some(text),
        },
        face: None,
        units: StepUnits::File,
        flip: false,
        z_offset_mm: 0.0,
        allow_uncovered: false,
    }
}

fn import(spec: &StepFaceSpec) -> StepFace {
    StepFace::new(spec, PartDisc::centred(PART)).unwrap_or_else(|e| panic!("{e}"))
}

fn error(spec: &StepFaceSpec) -> String {
    StepFace::new(spec, PartDisc::centred(PART))
        .unwrap_err()
        .to_string()
}

fn json(net: &NurbsSpec) -> Nurbs {
    Nurbs::new(net, PartDisc::centred(PART)).unwrap_or_else(|e| panic!("{e}"))
}

/// Points over the part: a polar grid including the centre and the rim.
fn points() -> Vec<(f64, f64)> {
    let mut out = vec![(0.0, 0.0)];
    for ring in 1..=10 {
        let r = PART * ring as f64 / 10.0;
        for k in 0..24 {
            let (s, c) = (k as f64 * std::f64::consts::TAU / 24.0 + 0.1 * ring as f64).sin_cos();
            out.push((r * c, r * s));
        }
    }
    out
}

#[test]
fn a_rational_sphere_face_is_the_json_net_and_the_sphere() {
    let net = sphere_net();
    let face = import(&spec(file_of(&[&net], false)));
    let reference = json(&net);
    for (x, y) in points() {
        let (a, b) = (local(&face, x, y), local(&reference, x, y));
        assert_eq!(a, b, "({x}, {y})");
        let want = sphere(R, x, y);
        assert!(
            (a.z - want[0]).abs() <= 1e-12,
            "({x}, {y}): {} vs {}",
            a.z,
            want[0]
        );
    }
    let d = face.describe();
    assert!(d.contains("rational") && d.contains("#"), "{d}");
}

#[test]
fn a_polynomial_freeform_face_is_the_json_net_and_the_polynomial() {
    let net = freeform_net();
    let face = import(&spec(file_of(&[&net], false)));
    let reference = json(&net);
    for (x, y) in points() {
        let (a, b) = (local(&face, x, y), local(&reference, x, y));
        assert_eq!(a, b, "({x}, {y})");
        // x = u + 0.05v, y = v: the closed form in (u, v) at the face's own parameters.
        let (u, v) = (x - 0.05 * y, y);
        let z = (u * u + v * v) / 60.0 + 2e-5 * u.powi(3) - 3e-5 * u * v * v;
        assert!((a.z - z).abs() <= 1e-12, "({x}, {y}): {} vs {z}", a.z);
    }
}

#[test]
fn a_file_in_inches_is_converted() {
    let net = sphere_net();
    let inch = import(&spec(file_of(&[&net], true)));
    let mm = import(&spec(file_of(&[&net], false)));
    for (x, y) in points() {
        let (a, b) = (local(&inch, x, y), local(&mm, x, y));
        assert!((a.z - b.z).abs() <= 1e-13, "({x}, {y}): {} vs {}", a.z, b.z);
    }
    assert!(
        inch.describe().contains("INCH (25.4 mm)"),
        "{}",
        inch.describe()
    );
    // "units" overrides the file: read as mm, the inch file is 25.4 times too small.
    let small = StepFaceSpec {
        units: StepUnits::Mm,
        allow_uncovered: true,
        ..spec(file_of(&[&net], true))
    };
    let small = import(&small);
    assert!(small.local(0.2, 0.0).is_ok());
    assert!(small.local(0.3, 0.0).is_err());
}

#[test]
fn several_surfaces_need_a_choice_and_the_error_lists_them() {
    let (a, b) = (sphere_net(), freeform_net());
    let text = file_of(&[&a, &b], false);
    let e = error(&spec(text.clone()));
    assert!(
        e.starts_with("face = none given: t.step has 2 B-spline surfaces: "),
        "{e}"
    );
    // The writer numbers: units 1–3, then #4–#39 sphere points, #40 the sphere, #41… freeform.
    assert!(e.contains("[0] #40 'face 0' (line"), "{e}");
    assert!(e.contains("degree 2 × 2, 6 × 6 points, rational"), "{e}");
    assert!(e.contains("[1] #"), "{e}");
    assert!(e.contains("degree 3 × 3, 7 × 7 points, polynomial"), "{e}");
    let pick = |face: FaceChoice| {
        import(&StepFaceSpec {
            face: Some(face),
            ..spec(text.clone())
        })
    };
    let second = json(&b);
    let (x, y) = (1.3, -2.1);
    assert_eq!(
        local(&pick(FaceChoice::Index(1)), x, y),
        local(&second, x, y)
    );
    let first = json(&a);
    assert_eq!(
        local(&pick(FaceChoice::Id("#40".into())), x, y),
        local(&first, x, y)
    );
    let bad = StepFaceSpec {
        face: Some(FaceChoice::Index(2)),
        ..spec(text.clone())
    };
    assert!(error(&bad).starts_with("face = 2: t.step has 2 B-spline surfaces"));
    let bad = StepFaceSpec {
        face: Some(FaceChoice::Id("#7".into())),
        ..spec(text)
    };
    assert!(error(&bad).starts_with("face = #7: must be \"#n\" naming one of"));
}

#[test]
fn an_advanced_face_id_selects_its_surface() {
    let net = sphere_net();
    let mut w = Writer::new(1);
    w.units(false);
    let other = w.surface(&freeform_net(), 1.0, "other");
    let surface = w.surface(&net, 1.0, "lens");
    let face = w.add(format!("ADVANCED_FACE('front',(),#{surface},.T.)"));
    w.add(format!("ADVANCED_FACE('back',(),#{other},.F.)"));
    let s = import(&StepFaceSpec {
        face: Some(FaceChoice::Id(format!("#{face}"))),
        ..spec(w.file())
    });
    assert_eq!(local(&s, 0.4, 2.2), local(&json(&net), 0.4, 2.2));
}

#[test]
fn flip_and_offset_place_a_face_exported_upside_down() {
    // The sphere turned over about Y, (x, y, z) → (−x, y, −z), and lifted by 3 mm.
    let mut net = sphere_net();
    for row in &mut net.control_points {
        for p in row {
            *p = [-p[0], p[1], 3.0 - p[2]];
        }
    }
    let placed = import(&StepFaceSpec {
        flip: true,
        z_offset_mm: 3.0,
        ..spec(file_of(&[&net], false))
    });
    for (x, y) in points() {
        let z = local(&placed, x, y).z;
        assert!((z - sphere(R, x, y)[0]).abs() <= 1e-12, "({x}, {y}): {z}");
    }
}

#[test]
fn malformed_files_give_the_line_and_the_entity() {
    let good = file_of(&[&sphere_net()], false);
    let cases: [(String, &str); 6] = [
        (
            good.replacen("CARTESIAN_POINT('',(", "CARTESIAN_POINT('',((", 1),
            "file = t.step: line 11: in #4 = CARTESIAN_POINT: expected ',' or ')', found ';'",
        ),
        (
            good.replacen("#5 = CARTESIAN_POINT", "#5 = DIRECTION", 1),
            "file = t.step: #40 (BOUNDED_SURFACE B_SPLINE_SURFACE B_SPLINE_SURFACE_WITH_KNOTS \
             GEOMETRIC_REPRESENTATION_ITEM RATIONAL_B_SPLINE_SURFACE REPRESENTATION_ITEM SURFACE): \
             control point [0][1]: #5 is a DIRECTION, not a CARTESIAN_POINT",
        ),
        (
            good.replacen("(3,1,1,1,3)", "(3,1,1,1,2)", 1),
            "the u multiplicities add up to 8, but 6 control points of degree 2 need 6 + 2 + 1 = 9",
        ),
        (
            good.replacen("#4 = CARTESIAN_POINT", "#99 = CARTESIAN_POINT", 1),
            "control point [0][0]: #4 is not in the file",
        ),
        (
            "solid lens\nfacet normal 0 0 1\n".to_string(),
            "file = t.step: line 1: not a STEP file (ISO 10303-21)",
        ),
        (
            good.replace("END-ISO-10303-21;", ""),
            "the file ends without END-ISO-10303-21;",
        ),
    ];
    for (text, want) in cases {
        let e = error(&spec(text));
        assert!(e.contains(want), "{e}\n  does not contain\n{want}");
    }
    let plane = good
        .split('\n')
        .filter(|l| !l.contains("B_SPLINE"))
        .collect::<Vec<_>>()
        .join("\n")
        .replace("ENDSEC;\nEND", "#90 = PLANE('',#1);\nENDSEC;\nEND");
    let e = error(&spec(plane));
    assert!(
        e.ends_with(
            "has no B_SPLINE_SURFACE_WITH_KNOTS (plain or rational): it has only PLANE #90"
        ),
        "{e}"
    );
    let mut unread = spec(good);
    unread.file.text = None;
    assert_eq!(
        error(&unread),
        "file = t.step: the file has not been read (the command line reads it)"
    );
}

#[test]
fn a_face_that_does_not_cover_the_part_is_refused() {
    let text = file_of(&[&sphere_net()], false);
    let e = StepFace::new(&spec(text.clone()), PartDisc::centred(5.6)).unwrap_err();
    assert_eq!(e.field, "file");
    assert_eq!(e.value, "t.step #40");
    assert!(
        e.allowed
            .starts_with("control_points = a 6 × 6 net spanning x in [-5.4923"),
        "{e}"
    );
    assert!(
        e.allowed.contains("does not cover the part (radius 5.6 mm"),
        "{e}"
    );
    let allowed = StepFaceSpec {
        allow_uncovered: true,
        ..spec(text)
    };
    let s = StepFace::new(&allowed, PartDisc::centred(5.6)).unwrap();
    let u = s.local(5.55, 0.0).unwrap_err();
    assert_eq!(u.surface, "STEP face");
    assert!(u.to_string().contains("radius 5.55 mm"), "{u}");
    assert!(u.to_string().contains("does not cover this point"), "{u}");
}

#[test]
fn the_job_format_reads_a_step_face() {
    let text = file_of(&[&sphere_net()], false);
    let surface = format!(
        r#"{{"type":"step_face","file":{{"text":{}}},"face":0,"units":"file","z_offset_mm":0}}"#,
        serde_json::to_string(&text).unwrap()
    );
    let spec: SurfaceSpec = serde_json::from_str(&surface).unwrap();
    let again: SurfaceSpec = serde_json::from_str(&serde_json::to_string(&spec).unwrap()).unwrap();
    assert_eq!(again, spec);
    let SurfaceSpec::StepFace(read) = &spec else {
        panic!("{spec:?}")
    };
    assert_eq!(read.face, Some(FaceChoice::Index(0)));
    assert_eq!(
        (read.units, read.flip, read.allow_uncovered),
        (StepUnits::File, false, false)
    );
    let s = spec.build(PART).unwrap();
    assert!((local(s.as_ref(), 3.0, 4.0).z - sphere(R, 3.0, 4.0)[0]).abs() <= 1e-12);
    let e = serde_json::from_str::<SurfaceSpec>(&surface.replace("\"file\",", "\"feet\","));
    assert!(e.unwrap_err().to_string().contains("feet"));
    let e = spec_error(&surface.replace("\"face\":0", "\"face\":\"#1\""));
    assert!(e.starts_with("surface.face = #1: must be"), "{e}");
}

fn spec_error(json: &str) -> String {
    let spec: SurfaceSpec = serde_json::from_str(json).unwrap();
    spec.build(PART).unwrap_err().to_string()
}

#[test]
fn the_example_job_reads_its_file_and_cuts_the_sphere() {
    let job = example_job("step-face-sphere.json");
    let planner = Planner::new(&job).unwrap_or_else(|e| panic!("{e}"));
    let s = planner.surface();
    for (x, y) in points() {
        let (l, want) = (local(s, x, y), sphere(R, x, y));
        assert!(
            (l.z - want[0]).abs() <= 1e-12,
            "({x}, {y}): {} vs {}",
            l.z,
            want[0]
        );
        // Slope and curvature as in surface_nurbs.rs (largest errors seen 3e-15, 5e-16).
        for k in 1..6 {
            let got = [l.z, l.zx, l.zy, l.zxx, l.zxy, l.zyy][k];
            assert!(
                (got - want[k]).abs() <= 1e-13,
                "({x}, {y}) [{k}]: {got} vs {}",
                want[k]
            );
        }
    }
}

#[test]
fn a_planned_step_face_path_touches_without_cutting() {
    let text = serde_json::to_string(&file_of(&[&freeform_net()], false)).unwrap();
    let job = format!(
        r#"{{"name":"step-path","part":{{"diameter_mm":1.2}},
            "surface":{{"type":"step_face","file":{{"text":{text}}}}},
            "tool":{{"nose_radius_mm":0.1,"included_angle_deg":110}},"machine":{{"spindle_rpm":500}},
            "strategy":{{"feed_mm_per_rev":0.1,"sampling":{{"type":"constant_angle","points_per_rev":24}}}}}}"#
    );
    // The face's net bounds the sections: the concave shortcut, held to the same check.
    let planner = Planner::new(&Job::from_json(&job).unwrap()).unwrap();
    assert!(planner.path().concavity().is_some());
    let n = check_planned_path(&job, &|_, _| Vec::new(), 2000);
    assert_eq!(n, 145);
}
