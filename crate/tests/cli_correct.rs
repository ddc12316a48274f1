//! `spiralcam correct` and `spiralcam setup` run as processes: the report holds the library's
//! figures under the names issue 15 gives them; the corrected job, its correction grid beside it
//! and the maps are written; the corrected job plans and is corrected again (the second report
//! says so); bad measurements exit 1 with nothing written; usage errors exit 2; `setup` prints
//! the library's offsets.

use spiralcam::analysis::correction::{Correction, CorrectionSettings};
use spiralcam::analysis::registration::MeasuredKind;
use spiralcam::analysis::setup::SetupSpec;
use spiralcam::job::Job;
use spiralcam::surface::measured::{self, Mirror, Orientation};
use std::ffi::OsStr;

mod common;
use common::{Scratch, spiralcam, stderr, stdout};

/// A small asphere job: Ø4 mm, a coarse feed so that planning the corrected job is quick.
const JOB: &str = r#"{
  "name": "cli-correct",
  "part": { "diameter_mm": 4.0 },
  "surface": { "type": "asphere", "radius_mm": 12.0, "conic": -0.5 },
  "tool": { "nose_radius_mm": 0.2 },
  "machine": { "spindle_rpm": 450.0 },
  "strategy": { "feed_mm_per_rev": 0.05, "sampling": { "type": "constant_angle", "points_per_rev": 60 } },
  "output": { "dialect": "iso" }
}"#;

/// A measured error map as a CSV cloud in µm heights, in an instrument frame mirrored in x:
/// astigmatism and trefoil × `scale` with a tilt, on a 41 × 41 grid over the part, the
/// lateral coordinates × `lateral` (1000: µm written under an `_mm` header).
fn error_csv(scale: f64, lateral: f64) -> String {
    let mut s = String::from("# synthetic interferometer export\nx_mm,y_mm,z_um\n");
    for j in 0..41 {
        for i in 0..41 {
            let (x, y) = (-2.0 + 0.1 * f64::from(i), -2.0 + 0.1 * f64::from(j));
            if x.hypot(y) > 1.98 {
                continue;
            }
            // Seen in the instrument: x mirrored.
            let (u, v) = (-x, y);
            let z =
                scale * (0.1 * (u * u - v * v) + 0.02 * (u.powi(3) - 3.0 * u * v * v)) + 0.05 * u;
            s.push_str(&format!("{:.3},{:.3},{z:.9}\n", x * lateral, y * lateral));
        }
    }
    s
}

fn number(v: &serde_json::Value, path: &[&str]) -> f64 {
    let mut v = v;
    for p in path {
        v = &v[*p];
    }
    v.as_f64().unwrap_or_else(|| panic!("{path:?} in {v}"))
}

#[test]
fn correct_writes_the_corrected_job_the_report_and_the_maps() {
    let dir = Scratch::new("correct");
    let job_path = dir.write("job.json", JOB);
    let data = dir.write("scan.csv", &error_csv(1.0, 1.0));
    let (out, report, maps) = (dir.path("next.json"), dir.path("r.json"), dir.path("m"));
    let o = spiralcam(&[
        OsStr::new("correct"),
        job_path.as_os_str(),
        OsStr::new("--measured"),
        data.as_os_str(),
        OsStr::new("--kind"),
        OsStr::new("error"),
        OsStr::new("--mirror"),
        OsStr::new("x"),
        OsStr::new("--gain"),
        OsStr::new("0.9"),
        OsStr::new("--out"),
        out.as_os_str(),
        OsStr::new("--report"),
        report.as_os_str(),
        OsStr::new("--maps"),
        maps.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut files = dir.files();
    files.sort();
    assert_eq!(
        files,
        [
            "job.json",
            "m-after.csv",
            "m-before.csv",
            "next.correction.dat",
            "next.json",
            "r.json",
            "scan.csv"
        ]
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    // The library on the same data gives the same figures.
    let map = measured::read_path(&data)
        .unwrap()
        .oriented(Orientation::new(0, Mirror::X).unwrap());
    let settings = CorrectionSettings {
        gain: 0.9,
        ..CorrectionSettings::new(MeasuredKind::Error)
    };
    let lib = Correction::run(&Job::from_json(JOB).unwrap(), &map, &settings).unwrap();
    for (path, want) in [
        (
            &["registration", "piston_um"][..],
            lib.report.registration.piston_um,
        ),
        (
            &["registration", "tilt_x_urad"][..],
            lib.report.registration.tilt_x_urad,
        ),
        (
            &["registration", "tilt_y_urad"][..],
            lib.report.registration.tilt_y_urad,
        ),
        (&["residual", "pv_um"][..], lib.report.residual.pv_um),
        (&["residual", "rms_um"][..], lib.report.residual.rms_um),
        (
            &["corrected", "predicted_residual", "rms_um"][..],
            lib.report.corrected.predicted_residual.rms_um,
        ),
    ] {
        assert_eq!(number(&r, path), want, "{path:?}");
    }
    // Mirrored into the machine's frame (u = −x of the file) the trefoil 0.02·(u³ − 3uv²) is
    // +0.16 µm of Fringe Z10 at ρ = r / 2 mm (−0.16 unmirrored), the astigmatism 0.4 µm of Z5,
    // and the tilt +0.05 µm/mm (less the trefoil's own plane over the grid's disc).
    let z = &r["residual"]["zernike_fringe_um"];
    assert!((z[9].as_f64().unwrap() - 0.16).abs() < 1e-9, "{z}");
    assert!((z[4].as_f64().unwrap() - 0.4).abs() < 1e-9, "{z}");
    assert!(
        (number(&r, &["registration", "tilt_x_urad"]) - 50.0).abs() < 1.0,
        "{r}"
    );
    assert_eq!(
        r["residual"]["zernike_fringe_um"].as_array().unwrap().len(),
        37
    );
    assert_eq!(r["residual"]["points"].as_u64(), Some(map.len() as u64));
    assert!(r["registration"]["decentre_x_um"].is_null());
    assert_eq!(
        r["corrected"]["job_file"].as_str(),
        Some(out.to_str().unwrap())
    );
    // The corrected job names its grid by the file beside it, and plans.
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("\"path\": \"next.correction.dat\""), "{text}");
    let nc = dir.path("next.nc");
    let o = spiralcam(&[
        OsStr::new("plan"),
        out.as_os_str(),
        OsStr::new("--nc"),
        nc.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The maps: x, y, residual in µm; the after map smaller.
    let rms = |file: &str| {
        let t = std::fs::read_to_string(dir.path(file)).unwrap();
        let mut lines = t.lines();
        assert_eq!(lines.next(), Some("x_mm,y_mm,residual_um"));
        let v: Vec<f64> = lines
            .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
            .collect();
        (v.iter().map(|e| e * e).sum::<f64>() / v.len() as f64).sqrt()
    };
    assert!(rms("m-after.csv") < 0.2 * rms("m-before.csv"));
    // Corrected again with a second measurement: the report says it added to the first.
    let second = dir.write("scan2.csv", &error_csv(0.1, 1.0));
    let o = spiralcam(&[
        OsStr::new("correct"),
        out.as_os_str(),
        OsStr::new("--measured"),
        second.as_os_str(),
        OsStr::new("--kind"),
        OsStr::new("error"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r2: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(r2["corrected"]["previous_correction"], true, "{r2}");
}

#[test]
fn bad_measurements_exit_1_with_nothing_written_and_usage_errors_2() {
    let dir = Scratch::new("correct-bad");
    let job_path = dir.write("job.json", JOB);
    let out = dir.path("next.json");
    let run = |data: &std::path::Path, kind: &str| {
        spiralcam(&[
            OsStr::new("correct"),
            job_path.as_os_str(),
            OsStr::new("--measured"),
            data.as_os_str(),
            OsStr::new("--kind"),
            OsStr::new(kind),
            OsStr::new("--out"),
            out.as_os_str(),
        ])
    };
    let mut lines: Vec<String> = error_csv(1.0, 1.0).lines().map(String::from).collect();
    let (x, y) = (lines[9].split(',').next().unwrap().to_string(), "0.5");
    lines[9] = format!("{x},{y},NaN");
    let nan = dir.write("nan.csv", &(lines.join("\n") + "\n"));
    let few = dir.write("few.csv", "x_mm,y_mm,z_um\n0,0,1\n1,0,2\n0,1,3\n");
    let wide = dir.write("wide.csv", &error_csv(1.0, 1000.0));
    for (file, message) in [
        (&nan, "nan.csv"),
        (&few, "the measured data hold 3 points"),
        (&wide, "measured points lie outside the part"),
    ] {
        let o = run(file, "error");
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains(message), "{message}: {}", stderr(&o));
        assert!(!out.exists() && !dir.path("next.correction.dat").exists());
    }
    let good = dir.write("scan.csv", &error_csv(1.0, 1.0));
    let o = run(&good, "heights");
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--kind heights: expected error or height"));
    let o = spiralcam(&[
        OsStr::new("correct"),
        job_path.as_os_str(),
        OsStr::new("--measured"),
        good.as_os_str(),
        OsStr::new("--kind"),
        OsStr::new("error"),
        OsStr::new("--rotate"),
        OsStr::new("45"),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--rotate 45"), "{}", stderr(&o));
}

#[test]
fn setup_prints_the_library_offsets() {
    let dir = Scratch::new("setup");
    let job_path = dir.write("job.json", JOB);
    let params = r#"{"centre_post": {"diameter_um": 6, "shape": "cylinder"},
                     "profile": {"inner_radius_mm": 0.5, "outer_radius_mm": 1.8, "rise_um": 0.2},
                     "radius": {"measured_mm": 12.004, "aperture_radius_mm": 1.5}}"#;
    let p = dir.write("setup.json", params);
    let o = spiralcam(&[
        OsStr::new("setup"),
        job_path.as_os_str(),
        OsStr::new("--params"),
        p.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let printed: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let job = Job::from_json(JOB).unwrap();
    let spec: SetupSpec = serde_json::from_str(params).unwrap();
    let lib = spec
        .offsets(job.build_surface().unwrap().as_ref(), job.part_radius_mm())
        .unwrap();
    // The same figures, within the last digit the JSON round trip may change.
    let want = serde_json::to_value(&lib).unwrap();
    let flat = |v: &serde_json::Value| -> Vec<(String, f64)> {
        let mut out = Vec::new();
        for (k, e) in v.as_object().unwrap() {
            for (k2, e2) in e.as_object().unwrap() {
                match e2.as_f64() {
                    Some(f) => out.push((format!("{k}.{k2}"), f)),
                    None => {
                        for (k3, e3) in e2.as_object().unwrap() {
                            out.push((format!("{k}.{k2}.{k3}"), e3.as_f64().unwrap()));
                        }
                    }
                }
            }
        }
        out
    };
    let (a, b) = (flat(&printed), flat(&want));
    assert_eq!(a.len(), 8, "{printed}");
    for ((ka, va), (kb, vb)) in a.iter().zip(&b) {
        assert_eq!(ka, kb);
        assert!(
            (va - vb).abs() <= 1e-15 * vb.abs(),
            "{ka}: {va} against {vb}"
        );
    }
    assert_eq!(printed["centre_post"]["tool_height_um"], -3.0);
    let bad = dir.write(
        "bad.json",
        r#"{"profile": {"inner_radius_mm": 0.5, "outer_radius_mm": 9, "rise_um": 0.2}}"#,
    );
    let o = spiralcam(&[
        OsStr::new("setup"),
        job_path.as_os_str(),
        OsStr::new("--params"),
        bad.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("profile.outer_radius_mm = 9"),
        "{}",
        stderr(&o)
    );
}
