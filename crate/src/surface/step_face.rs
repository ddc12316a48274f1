//! A B-spline or NURBS face imported from a STEP file (ISO 10303-21 clear text, AP203/AP214
//! geometry): the file is read by a small Part 21 reader (`part21.rs`), the chosen
//! `B_SPLINE_SURFACE_WITH_KNOTS` (plain, or the complex instance with
//! `RATIONAL_B_SPLINE_SURFACE`) becomes a control net (`bspline.rs`) scaled from the file's
//! length unit to millimetres (`units.rs`), and the net is evaluated as a height field by the
//! `nurbs` family ([`super::nurbs`]: exact derivatives, Newton inversion of the XY projection,
//! coverage and fold checks).
//!
//! The face is used as it lies in the file: the design must be exported with the optical axis
//! along +Z (pointing out of the material, towards the tool) and the vertex at the origin.
//! `flip` turns a face exported with its axis along −Z over (a half-turn about Y), `z_offset_mm`
//! moves the vertex to z = 0; decentring and rotating about Z are done by making the face a
//! term of a `composite` surface. Trimming curves are not read: the untrimmed surface must cover
//! the part.
//!
//! Why not truck-stepio: truck-stepio 0.3 and truck-geometry 0.5 pull wasm-bindgen and js-sys
//! into the core on wasm32 (truck-geotrait → rand → getrandom's `js` feature; chrono's
//! `wasmbind`), which the core must not depend on, along with truck-modeling, -topology,
//! -polymesh and rayon; and they read no length units.

mod bspline;
mod part21;
mod units;

use super::nurbs::Nurbs;
use super::{Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite};
use crate::surface::DataFile;
use part21::{Exchange, Instance};
use serde::{Deserialize, Serialize};

/// Which surface of the file to use: its index among the file's B-spline surfaces in file
/// order (from 0), or its entity id `"#123"` (the id of an `ADVANCED_FACE` or `FACE_SURFACE`
/// on it is accepted too).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum FaceChoice {
    /// Index among the B-spline surfaces, in file order, from 0.
    Index(usize),
    /// Entity id, `"#123"`.
    Id(String),
}

impl<'de> Deserialize<'de> for FaceChoice {
    fn deserialize<D: serde::Deserializer<'de>>(de: D) -> Result<Self, D::Error> {
        struct Choice;
        impl serde::de::Visitor<'_> for Choice {
            type Value = FaceChoice;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(
                    "the index of a B-spline surface in the file (0, 1, …) or an entity id \"#123\"",
                )
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<FaceChoice, E> {
                usize::try_from(v)
                    .map(FaceChoice::Index)
                    .map_err(|_| E::invalid_value(serde::de::Unexpected::Unsigned(v), &self))
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<FaceChoice, E> {
                Ok(FaceChoice::Id(v.to_string()))
            }
        }
        de.deserialize_any(Choice)
    }
}

/// The length unit of the file's coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StepUnits {
    /// As the file states (`SI_UNIT` or `CONVERSION_BASED_UNIT` such as inches); millimetres
    /// where it states none.
    #[default]
    File,
    /// Millimetres, whatever the file states.
    Mm,
    /// Micrometres.
    Um,
    /// Metres.
    M,
    /// Inches (25.4 mm).
    Inch,
}

/// Job entry of a STEP face (JSON type `"step_face"`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepFaceSpec {
    /// The STEP file: `{"path": "lens.step"}` (command line, relative to the job) or
    /// `{"text": "ISO-10303-21; …"}`.
    pub file: DataFile,
    /// Which B-spline surface; default the only one (an error listing them if there are
    /// several).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub face: Option<FaceChoice>,
    /// Length unit of the file; default `file` (as stated in the file, else mm).
    #[serde(default, skip_serializing_if = "is_default")]
    pub units: StepUnits,
    /// Turn the face over by a half-turn about the Y axis, `(x, y, z) → (−x, y, −z)`, for a
    /// design exported with its optical axis along −Z; default false. Applied before
    /// `z_offset_mm`.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub flip: bool,
    /// Added to the face's z, mm (e.g. minus the vertex height in the file); default 0.
    #[serde(default, skip_serializing_if = "is_default")]
    pub z_offset_mm: f64,
    /// Accept a face that does not cover the whole part; points outside it are undefined.
    /// Default false.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub allow_uncovered: bool,
}

fn is_default<T: Default + PartialEq>(t: &T) -> bool {
    *t == T::default()
}

/// A STEP face, validated: the NURBS height field and where it came from.
#[derive(Debug, Clone)]
pub struct StepFace {
    nurbs: Nurbs,
    origin: String,
}

impl StepFace {
    /// Reads the file, picks the face and builds the surface for the part disc `part`.
    pub fn new(spec: &StepFaceSpec, part: PartDisc) -> Result<Self, FieldError> {
        let text = spec.file.text("file")?;
        let file = spec.file.name();
        let file_error = |message: String| FieldError::new("file", file, message);
        let ex = Exchange::parse(text).map_err(|e| file_error(e.to_string()))?;
        let surface = choose(&ex, spec.face.as_ref(), file)?;
        let (mm, unit) = unit(spec.units, &ex).map_err(|e| FieldError::new("units", file, e))?;
        let mut net = bspline::read(&ex, surface, mm).map_err(file_error)?;
        let offset = finite("z_offset_mm", spec.z_offset_mm)?;
        place(&mut net, spec.flip, offset);
        net.allow_uncovered = spec.allow_uncovered;
        let nurbs = Nurbs::build(&net, part, "STEP face").map_err(|e| {
            FieldError::new(
                "file",
                format!("{file} #{}", surface.id),
                format!("{} = {}: {}", e.field, e.value, e.allowed),
            )
        })?;
        let flip = if spec.flip { ", flipped" } else { "" };
        Ok(Self {
            nurbs,
            origin: format!(
                "#{} of {file}, {unit}{flip}, z offset {} mm",
                surface.id, spec.z_offset_mm
            ),
        })
    }

    /// The NURBS height field.
    pub fn nurbs(&self) -> &Nurbs {
        &self.nurbs
    }
}

impl Surface for StepFace {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        self.nurbs.local(x, y)
    }

    fn feature_length_mm(&self) -> f64 {
        self.nurbs.feature_length_mm()
    }

    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.nurbs.section_bounds(radius_mm)
    }

    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.nurbs.disc_bounds(radius_mm)
    }

    fn describe(&self) -> String {
        format!("{} ({})", self.nurbs.describe(), self.origin)
    }
}

/// The surface the spec names, or the only one.
fn choose<'a>(
    ex: &'a Exchange,
    face: Option<&FaceChoice>,
    file: &str,
) -> Result<&'a Instance, FieldError> {
    let candidates = bspline::candidates(ex);
    let listing = || {
        let items: Vec<String> = candidates
            .iter()
            .enumerate()
            .map(|(k, c)| format!("[{k}] {}", bspline::summary(c)))
            .collect();
        items.join("; ")
    };
    if candidates.is_empty() {
        let others = bspline::other_surfaces(ex);
        let has = if others.is_empty() {
            "no surfaces at all".to_string()
        } else {
            format!("only {}", others.join(", "))
        };
        return Err(FieldError::new(
            "file",
            file,
            format!("has no B_SPLINE_SURFACE_WITH_KNOTS (plain or rational): it has {has}"),
        ));
    }
    match face {
        None if candidates.len() == 1 => Ok(candidates[0]),
        None => Err(FieldError::new(
            "face",
            "none given",
            format!(
                "{file} has {} B-spline surfaces: {}; choose one with \"face\": its index or \"#id\"",
                candidates.len(),
                listing()
            ),
        )),
        Some(FaceChoice::Index(k)) => candidates.get(*k).copied().ok_or_else(|| {
            FieldError::new(
                "face",
                k,
                format!(
                    "{file} has {} B-spline surfaces: {}",
                    candidates.len(),
                    listing()
                ),
            )
        }),
        Some(FaceChoice::Id(id)) => by_id(ex, &candidates, id).ok_or_else(|| {
            FieldError::new(
                "face",
                id,
                format!(
                    "must be \"#n\" naming one of the B-spline surfaces of {file} (or a face on \
                     one): {}",
                    listing()
                ),
            )
        }),
    }
}

/// The candidate `#n`, or the one an `ADVANCED_FACE` / `FACE_SURFACE` `#n` lies on.
fn by_id<'a>(ex: &'a Exchange, candidates: &[&'a Instance], id: &str) -> Option<&'a Instance> {
    let n: u64 = id.trim().strip_prefix('#')?.parse().ok()?;
    let instance = ex.get(n)?;
    let target = ["ADVANCED_FACE", "FACE_SURFACE"]
        .iter()
        .find_map(|name| instance.record(name))
        .and_then(|face| face.params.get(2)?.reference())
        .unwrap_or(n);
    candidates.iter().copied().find(|c| c.id == target)
}

/// Millimetres per file unit and its name.
fn unit(units: StepUnits, ex: &Exchange) -> Result<(f64, String), String> {
    Ok(match units {
        StepUnits::Mm => (1.0, "mm (set)".into()),
        StepUnits::Um => (1e-3, "µm (set)".into()),
        StepUnits::M => (1e3, "m (set)".into()),
        StepUnits::Inch => (25.4, "inch (set)".into()),
        StepUnits::File => match units::file_length_unit(ex)? {
            Some(u) => (u.mm, format!("{} (from the file)", u.name)),
            None => (1.0, "mm (the file states none)".into()),
        },
    })
}

/// The optional half-turn about Y and the z offset, applied to the control points (a NURBS
/// surface moves with its control points).
fn place(net: &mut crate::surface::NurbsSpec, flip: bool, z_offset: f64) {
    for row in &mut net.control_points {
        for p in row {
            if flip {
                p[0] = -p[0];
                p[2] = -p[2];
            }
            p[2] += z_offset;
        }
    }
}
