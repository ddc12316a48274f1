//! The page's "Import design…": a designer's file (`.zmx`, `.seq`, Grid Sag `.DAT`) read by the
//! core ([`spiralcam::surface::import::read_design`]) and one of its surfaces made a job
//! ([`spiralcam::job::design::job_from_design`]), exactly as `spiralcam import` does, with the
//! data files a surface names (a `.zmx`'s Grid Sag `.DAT`) taken from the files the user chose
//! with it instead of the disk. Both answers are JSON text for the page's script; the wasm
//! bindings that call them are in `api`. This module is plain Rust so that it is tested natively.

use serde_json::{Value, json};
use spiralcam::job::Piece;
use spiralcam::job::design::{DesignChoice, default_surface, job_from_design};
use spiralcam::surface::import::{Design, Role, read_design};

/// A file the user chose beside the design: its name and its text.
pub struct SideFile {
    /// The file's name (no folder: the browser gives none).
    pub name: String,
    /// Its contents.
    pub text: String,
}

/// The last component of a path written with `/` or `\`.
fn base_name(path: &str) -> &str {
    path.rsplit(['/', '\\']).next().unwrap_or(path)
}

/// The data files a surface names and does not carry, as the design writes them.
fn data_files_named(design: &Design, number: usize) -> Vec<String> {
    let Some(Ok(spec)) = design.surface(number).map(|s| s.shape.clone()) else {
        return Vec::new();
    };
    let mut spec = spec;
    spec.data_files_mut()
        .into_iter()
        .filter(|(_, f)| f.text.is_none())
        .filter_map(|(_, f)| f.path.clone())
        .collect()
}

/// The design `name` read from `bytes`, for the page's list: the file's format, encoding,
/// unit and notes, the surface taken when none is chosen (`null` when the user must choose),
/// and each surface's number, one-line summary, role, whether it is a mirror (a refracting
/// surface needs the piece chosen), whether its type is read, and the data files it names.
pub fn design_surfaces(name: &str, bytes: &[u8]) -> Result<String, String> {
    let design = read_design(name, bytes).map_err(|e| e.to_string())?;
    let surfaces: Vec<Value> = design
        .surfaces
        .iter()
        .map(|s| {
            json!({
                "number": s.number,
                "summary": s.summary(),
                "role": match s.role {
                    Role::Object => "object",
                    Role::Surface => "surface",
                    Role::Image => "image",
                },
                "mirror": s.optics.mirror,
                "readable": s.shape.is_ok(),
                "data_files": data_files_named(&design, s.number),
            })
        })
        .collect();
    Ok(json!({
        "file": design.file,
        "format": design.format.name(),
        "encoding": design.encoding.name(),
        "unit": format!("{} ({} mm; {})", design.unit.name, design.unit.mm, design.unit_from),
        "notes": design.notes,
        "default_surface": default_surface(&design),
        "surfaces": surfaces,
    })
    .to_string())
}

/// The piece a page's choice names: `optic`, `mould`, or empty for the file's default.
fn piece(text: &str) -> Result<Option<Piece>, String> {
    match text {
        "" => Ok(None),
        "optic" => Ok(Some(Piece::Optic)),
        "mould" => Ok(Some(Piece::Mould)),
        t => Err(format!("cut {t:?}: must be optic or mould")),
    }
}

/// The job for surface `surface` (`None`: the only one) of the design `name`, cut as `piece`
/// (`optic`, `mould` or empty) with the part's diameter `diameter_mm` (`None`: twice the
/// semi-diameter), as JSON `{"job": …, "listing": […], "surface": n}`. A data file the
/// surface names is looked up among `side` by its name, then by its last path component
/// (any case), and carried in the job as text.
pub fn import_design(
    name: &str,
    bytes: &[u8],
    surface: Option<usize>,
    piece_text: &str,
    diameter_mm: Option<f64>,
    side: &[SideFile],
) -> Result<String, String> {
    let design = read_design(name, bytes).map_err(|e| e.to_string())?;
    let choice = DesignChoice {
        surface,
        piece: piece(piece_text)?,
        diameter_mm,
    };
    let read = |wanted: &str| {
        side.iter()
            .find(|f| f.name == wanted)
            .or_else(|| {
                side.iter()
                    .find(|f| f.name.eq_ignore_ascii_case(base_name(wanted)))
            })
            .map(|f| f.text.clone())
            .ok_or_else(|| {
                format!(
                    "not among the files chosen: choose {} together with {name}",
                    base_name(wanted)
                )
            })
    };
    let mut made = job_from_design(&design, &choice, read).map_err(|e| e.to_string())?;
    for (_, file) in made.job.surface.data_files_mut() {
        file.path = None;
    }
    let job: Value = serde_json::from_str(&made.job.to_json()).map_err(|e| e.to_string())?;
    Ok(json!({ "job": job, "listing": made.listing, "surface": made.surface }).to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use spiralcam::job::Job;

    /// A 5 × 5 Grid Sag of 0.5 mm spacing, zero but for 1 µm at the centre.
    fn grid() -> String {
        let mut t = String::from("5 5 0.5 0.5 0 0 0\n");
        for k in 0..25 {
            t.push_str(if k == 12 {
                "0.001 0 0 0\n"
            } else {
                "0 0 0 0\n"
            });
        }
        t
    }

    fn lens() -> String {
        "UNIT MM\nSURF 0\nSURF 1\n  TYPE EVENASPH\n  CURV 0.02\n  PARM 2 1e-5\n  GLAS N-BK7\n  \
         DIAM 4\nSURF 2\n  TYPE GRIDSAG\n  UDAD \"C:\\designs\\back.DAT\"\n  DIAM 1\nSURF 3\n"
            .into()
    }

    fn parse(text: &str) -> Value {
        serde_json::from_str(text).unwrap()
    }

    #[test]
    fn the_list_names_every_surface_and_the_files_they_need() {
        let v = parse(&design_surfaces("lens.zmx", lens().as_bytes()).unwrap());
        let s = v["surfaces"].as_array().unwrap();
        assert_eq!(s.len(), 4);
        assert_eq!(s[1]["summary"], "1 EVENASPH, semi-diameter 4 mm");
        assert_eq!(s[1]["role"], "surface");
        assert_eq!(s[1]["mirror"], false);
        assert_eq!(s[2]["data_files"][0], "C:\\designs\\back.DAT");
        assert_eq!(s[0]["role"], "object");
        // Two surfaces between object and image: the user chooses.
        assert!(v["default_surface"].is_null());
        let grid = parse(&design_surfaces("g.DAT", grid().as_bytes()).unwrap());
        assert_eq!(grid["default_surface"], 1);
        assert_eq!(grid["format"], "Zemax Grid Sag file (.DAT)");
    }

    #[test]
    fn the_job_is_the_command_lines_with_its_data_carried_as_text() {
        let side = [SideFile {
            name: "back.dat".into(),
            text: grid(),
        }];
        let text =
            import_design("lens.zmx", lens().as_bytes(), Some(2), "mould", None, &side).unwrap();
        let v = parse(&text);
        assert_eq!(v["surface"], 2);
        assert_eq!(v["job"]["surface"]["data"], json!({ "text": grid() }));
        assert_eq!(
            v["job"]["part"]["cut"],
            json!({"piece": "mould", "frame": "turned"})
        );
        assert!(
            v["listing"][0]
                .as_str()
                .unwrap()
                .starts_with("lens.zmx: OpticStudio lens file")
        );
        // The job reads back, and its sag is the grid's turned: −z(−x, y) at the grid point
        // (0, 0) where the file has 1 µm, on the glass-before rear surface (mould: turned).
        let job = Job::from_json(&v["job"].to_string()).unwrap();
        let z = job.build_surface().unwrap().sag(0.0, 0.0).unwrap();
        assert!((z + 0.001).abs() < 1e-15, "{z}");
        // The same as the command line's job: the core's job_from_design, files by path.
        let design = read_design("lens.zmx", lens().as_bytes()).unwrap();
        let choice = DesignChoice {
            surface: Some(2),
            piece: Some(Piece::Mould),
            diameter_mm: None,
        };
        let mut cli = job_from_design(&design, &choice, |_| Ok(grid()))
            .unwrap()
            .job;
        cli.surface.data_files_mut()[0].1.path = None;
        assert_eq!(job, cli);
    }

    #[test]
    fn what_is_missing_is_named() {
        let e =
            import_design("lens.zmx", lens().as_bytes(), Some(2), "mould", None, &[]).unwrap_err();
        assert!(
            e.contains("surface.data.path = C:\\designs\\back.DAT: cannot be read: not among the files chosen: choose back.DAT together with lens.zmx"),
            "{e}"
        );
        let e = import_design("lens.zmx", lens().as_bytes(), Some(1), "", None, &[]).unwrap_err();
        assert!(e.contains("choose optic"), "{e}");
        let e =
            import_design("lens.zmx", lens().as_bytes(), Some(1), "side", None, &[]).unwrap_err();
        assert_eq!(e, "cut \"side\": must be optic or mould");
        let e = design_surfaces("lens.txt", b"").unwrap_err();
        assert!(e.contains("not a design file"), "{e}");
    }
}
