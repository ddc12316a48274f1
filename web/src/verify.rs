//! The page's "Open NC…": a program (and the child programs chosen with it) verified against
//! the job in the worker ([`spiralcam::analysis::verify`], the command line's
//! `spiralcam verify`), with progress and cancel. The page shows the report beside the plan's,
//! draws the last pass's deviation as a map over the part with a legend in nm, and draws the
//! last pass itself (its trace: every k-th cutting point, at most 200 000) over the surface in
//! the 3-D view, coloured by deviation ([`crate::viewer::Viewer::set_deviation_path`]).

use crate::api::{parse_job, reporter};
use spiralcam::analysis::verify::{Verification, VerifySettings, verify};
use spiralcam::nc::reader::{Program, Reader, ReaderOptions, texts_beside};
use spiralcam::tool::ToolPath;
use wasm_bindgen::prelude::*;

/// Samples per side of the deviation map.
pub const MAP_SIZE: usize = 161;
/// The most bytes of all the program's files together (the page holds them as text).
pub const MAX_PROGRAM_BYTES: usize = 512 << 20;

/// A program verified.
#[wasm_bindgen]
pub struct Verified {
    verification: Verification,
}

#[wasm_bindgen]
impl Verified {
    /// The report as JSON.
    #[wasm_bindgen(getter)]
    pub fn report(&self) -> String {
        self.verification.to_json()
    }

    /// Samples per side of the map.
    #[wasm_bindgen(getter)]
    pub fn size(&self) -> usize {
        self.verification.map.size
    }

    /// The last pass's deviation, µm, row by row from −y to +y (NaN where no point fell).
    #[wasm_bindgen(getter)]
    pub fn deviation_um(&self) -> Vec<f32> {
        self.verification
            .map
            .values
            .iter()
            .map(|&v| v as f32)
            .collect()
    }

    /// The trace: x, y, z (mm) and deviation (µm) of every k-th cutting point of the last
    /// pass, in order, flat.
    #[wasm_bindgen(getter)]
    pub fn trace(&self) -> Vec<f32> {
        self.verification
            .trace
            .iter()
            .flat_map(|p| [p.x as f32, p.y as f32, p.z as f32, p.deviation_um as f32])
            .collect()
    }
}

/// Verifies the program `name` (`text`) against `job`; `names` and `texts` are the other files
/// chosen with it, where its child programs are looked for. `progress(done, total, stage)`
/// sees the moves read and may cancel by throwing.
#[wasm_bindgen]
pub fn verify_program(
    job: JsValue,
    name: &str,
    text: &str,
    names: Vec<String>,
    texts: Vec<String>,
    progress: &js_sys::Function,
) -> Result<Verified, JsError> {
    let total = text.len() + texts.iter().map(String::len).sum::<usize>();
    if total > MAX_PROGRAM_BYTES {
        return Err(JsError::new(&format!(
            "{name}: the files weigh {total} bytes together; at most {MAX_PROGRAM_BYTES} are read"
        )));
    }
    let job = parse_job(job)?;
    let tool_path = ToolPath::new(&job).map_err(|e| JsError::new(&e.to_string()))?;
    let files: Vec<(String, String)> = names.into_iter().zip(texts).collect();
    let mut open = || -> Result<Reader<'_>, String> {
        Ok(
            Reader::new(Program::from_text(name, text), ReaderOptions::default())
                .with_resolver(texts_beside(name, &files)),
        )
    };
    let settings = VerifySettings {
        map_size: MAP_SIZE,
        ..VerifySettings::default()
    };
    let verification = verify(&tool_path, &mut open, &settings, &mut reporter(progress))
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok(Verified { verification })
}
