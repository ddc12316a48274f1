//! The page's "Measured…" and "Set-up" panels: a measured file corrected against the job
//! ([`spiralcam::analysis::correction`], the command line's `spiralcam correct`) and a test
//! cut's observations turned into offsets ([`spiralcam::analysis::setup`], `spiralcam setup`).
//! The measured file arrives as bytes with its name (the format is detected as on the command
//! line); the corrected job comes back as JSON with its correction grid inline, ready to be
//! planned and downloaded like any job.

use crate::api::parse_job;
use serde::Deserialize;
use spiralcam::analysis::correction::{Correction, CorrectionSettings};
use spiralcam::analysis::registration::{MeasuredKind, RegisterTerms};
use spiralcam::analysis::setup::SetupSpec;
use spiralcam::surface::measured::{self, MAX_FILE_BYTES, Mirror, Orientation};
use wasm_bindgen::prelude::*;

/// Samples per side of the before and after maps.
pub const MAP_SIZE: usize = 161;

/// A correction made: its report, maps and the corrected job.
#[wasm_bindgen]
pub struct Corrected {
    correction: Correction,
}

/// A raster's values as f32 (NaN where there is none), row by row from −y to +y.
fn values(map: &spiralcam::raster::Raster) -> Vec<f32> {
    map.values.iter().map(|&v| v as f32).collect()
}

#[wasm_bindgen]
impl Corrected {
    /// The report as JSON (registration, residual, corrected, warnings).
    #[wasm_bindgen(getter)]
    pub fn report(&self) -> String {
        self.correction.report_json()
    }

    /// Samples per side of both maps.
    #[wasm_bindgen(getter)]
    pub fn size(&self) -> usize {
        self.correction.before.size
    }

    /// The residual before, µm (mean per cell of the measured points; NaN where none).
    #[wasm_bindgen(getter)]
    pub fn before_um(&self) -> Vec<f32> {
        values(&self.correction.before)
    }

    /// The residual predicted after the re-cut, µm.
    #[wasm_bindgen(getter)]
    pub fn after_um(&self) -> Vec<f32> {
        values(&self.correction.after)
    }

    /// The file name of the corrected job's NC program: its name and the dialect's extension.
    #[wasm_bindgen(getter)]
    pub fn nc_file_name(&self) -> String {
        let job = &self.correction.corrected_job;
        format!("{}.{}", job.name, job.output.style().extension)
    }

    /// The corrected job as JSON, its correction grid inline.
    #[wasm_bindgen(getter)]
    pub fn job_json(&self) -> String {
        self.correction.corrected_job.to_json()
    }
}

/// The kind of a measured file: `error` or `height`.
fn kind(text: &str) -> Result<MeasuredKind, JsError> {
    match text {
        "error" => Ok(MeasuredKind::Error),
        "height" => Ok(MeasuredKind::Height),
        other => Err(JsError::new(&format!(
            "kind = {other}: expected error or height"
        ))),
    }
}

/// How to correct, from the page's panel.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CorrectOptions {
    /// `error` or `height`.
    pub kind: String,
    /// The fraction of the residual taken off, (0, 2].
    pub gain: f64,
    /// The terms besides piston and tilt (`power,decentre,clocking`); empty: the kind's default.
    #[serde(default)]
    pub register: String,
    /// The data turned by this many degrees (a multiple of 90), counter-clockwise from the tool.
    #[serde(default)]
    pub rotate_deg: i64,
    /// Mirrored first: "", `none`, `x` or `y`.
    #[serde(default)]
    pub mirror: String,
}

/// Corrects `job` with the measured file `name` (`bytes`) under `options` ([`CorrectOptions`]).
#[wasm_bindgen]
pub fn correct(
    job: JsValue,
    name: &str,
    bytes: Vec<u8>,
    options: JsValue,
) -> Result<Corrected, JsError> {
    let job = parse_job(job)?;
    let options: CorrectOptions =
        serde_wasm_bindgen::from_value(options).map_err(|e| JsError::new(&e.to_string()))?;
    let kind = kind(&options.kind)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(JsError::new(&format!(
            "{name}: {} bytes: at most {MAX_FILE_BYTES} are read",
            bytes.len()
        )));
    }
    let mut settings = CorrectionSettings::new(kind);
    settings.gain = options.gain;
    settings.map_size = MAP_SIZE;
    if !options.register.trim().is_empty() {
        settings.terms = RegisterTerms::parse(&options.register, kind)
            .map_err(|e| JsError::new(&format!("register: {e}")))?;
    }
    let mirror = match options.mirror.as_str() {
        "" | "none" => Mirror::None,
        m => m
            .parse::<Mirror>()
            .map_err(|_| JsError::new(&format!("mirror = {m}: expected none, x or y")))?,
    };
    let orientation =
        Orientation::new(options.rotate_deg, mirror).map_err(|e| JsError::new(&e.to_string()))?;
    let map = measured::read(name, bytes)
        .map_err(|e| JsError::new(&e.to_string()))?
        .oriented(orientation);
    let correction =
        Correction::run(&job, &map, &settings).map_err(|e| JsError::new(&e.to_string()))?;
    Ok(Corrected { correction })
}

/// The offsets a test cut of `job` shows (`params`: the JSON of `spiralcam setup --params`),
/// as JSON.
#[wasm_bindgen]
pub fn setup_offsets(job: JsValue, params: &str) -> Result<String, JsError> {
    let job = parse_job(job)?;
    let de = &mut serde_json::Deserializer::from_str(params);
    let spec: SetupSpec = serde_path_to_error::deserialize(de)
        .map_err(|e| JsError::new(&format!("{}: {}", e.path(), e.inner())))?;
    let surface = job
        .build_surface()
        .map_err(|e| JsError::new(&e.to_string()))?;
    let report = spec
        .offsets(surface.as_ref(), job.part_radius_mm())
        .map_err(|e| JsError::new(&e.to_string()))?;
    serde_json::to_string_pretty(&report).map_err(|e| JsError::new(&e.to_string()))
}
