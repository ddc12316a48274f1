//! The JavaScript API of the planner, called from the page's Web Worker (`web/worker.js`).
//!
//! A job arrives as a plain JavaScript object and is read with serde-wasm-bindgen into the core's
//! [`Job`], with the same field checks as the command line (unknown fields rejected). Results
//! come back as flat typed arrays for the renderer and bytes for downloads. Every error becomes a
//! JavaScript exception whose message is the core's, e.g.
//! `tool.nose_radius_mm = -1: must be a finite number ≥ 0`; the page reads the field path before
//! ` = ` to put the message beside that field.
//!
//! Planning a job for display ([`plan`]) writes the NC program into a byte counter only; the
//! program and the CSV are produced on demand ([`nc_program`], [`csv_table`]) by planning again,
//! which is deterministic, so memory stays flat however many points the path has. A long path
//! is planned by several workers in slices ([`plan_slice`], joined by [`plan_merge`]), and its
//! program written slice by slice ([`plan_slice`] with its text), where [`slicing`] allows.

use spiralcam::analysis::Analysis;
use spiralcam::analysis::power_map::PowerMap;
use spiralcam::display::{DisplayPath, SurfaceMesh};
use spiralcam::field::short;
use spiralcam::job::Job;
use spiralcam::nc::program::ChildFiles;
use spiralcam::plan::{AnalysisLimits, Limits, PlanSlice, Planner, Sinks};
use spiralcam::progress::Progress;
use spiralcam::raster::Raster;
use spiralcam::report::{Cost, Outputs, Stats};
use spiralcam::surface::{PartDisc, SurfaceSpec};
use std::ops::ControlFlow;
use wasm_bindgen::prelude::*;

/// Most path points sent to the renderer.
pub const DISPLAY_POINTS: u64 = 200_000;

/// The page's default job (paper 004's lens array) as JSON text.
#[wasm_bindgen]
pub fn default_job() -> String {
    spiralcam::job::DEFAULT_JOB.to_string()
}

/// The height colour scale as a CSS gradient, for the legend.
#[wasm_bindgen]
pub fn colormap_css() -> String {
    crate::colormap::css_gradient()
}

/// The crate version, shown on the page.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// The job of a JavaScript object, read with the core's field checks. The job's `format` is
/// checked first: a job from a newer spiralcam is refused naming its version, not the first
/// field this version does not know. The object is read as it is, so that a number the form
/// could not read (NaN: a field left blank) meets its field's own check ("= NaN: must be a
/// finite number > 0"); a job the object's reader refuses is read again through its JSON text
/// ([`Job::from_json`]) for the command line's words (the object's reader said "TypeError:
/// Reflect.get called on non-object" for a number where the surface belongs, and wrote 1e300
/// with all its 301 digits), less the text's line and column, which the page's user never sees.
pub(crate) fn parse_job(job: JsValue) -> Result<Job, JsError> {
    let format =
        js_sys::Reflect::get(&job, &JsValue::from_str("format")).unwrap_or(JsValue::UNDEFINED);
    if !format.is_undefined() {
        let value: serde_json::Value = serde_wasm_bindgen::from_value(format)
            .unwrap_or_else(|_| serde_json::Value::String("an object".into()));
        spiralcam::job::format::check_format(&value).map_err(|e| JsError::new(&e.to_string()))?;
    }
    Job::deserialize_from(serde_wasm_bindgen::Deserializer::from(job.clone())).map_err(|e| {
        let text = js_sys::JSON::stringify(&job)
            .ok()
            .and_then(|t| t.as_string());
        match text.map(|t| Job::from_json(&t)) {
            Some(Err(worded)) => JsError::new(without_position(&worded.to_string())),
            _ => JsError::new(&e.to_string()),
        }
    })
}

/// `message` without the " at line L column C" that a JSON reader puts at its end.
fn without_position(message: &str) -> &str {
    const AT: &str = " at line ";
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    match message.rfind(AT) {
        Some(i) => match message[i + AT.len()..].split_once(" column ") {
            Some((line, column)) if digits(line) && digits(column) => &message[..i],
            _ => message,
        },
        None => message,
    }
}

fn read_job(job: JsValue, progress: &js_sys::Function) -> Result<Planner, JsError> {
    Planner::with_progress(&parse_job(job)?, &mut reporter(progress))
        .map_err(|e| JsError::new(&e.to_string()))
}

thread_local! {
    /// The planner of the last job sliced in this worker, by the job's JSON: a worker plans
    /// several slices of one job, and a surface-dependent sampling takes seconds to set up.
    static SLICED: std::cell::RefCell<Option<(String, std::rc::Rc<Planner>)>> =
        const { std::cell::RefCell::new(None) };
}

/// The planner of `job` for its slices: the one kept from the last call when the job is the same.
fn sliced_planner(
    job: JsValue,
    progress: &js_sys::Function,
) -> Result<std::rc::Rc<Planner>, JsError> {
    // The page's own text of the job (the core's JSON of it may order a map differently).
    let key =
        String::from(js_sys::JSON::stringify(&job).map_err(|_| JsError::new("job: not JSON"))?);
    if let Some(p) = SLICED.with_borrow(|c| {
        c.as_ref()
            .filter(|(k, _)| *k == key)
            .map(|(_, p)| p.clone())
    }) {
        return Ok(p);
    }
    SLICED.set(None);
    let job = parse_job(job)?;
    let planner = std::rc::Rc::new(
        Planner::with_progress(&job, &mut reporter(progress))
            .map_err(|e| JsError::new(&e.to_string()))?,
    );
    SLICED.set(Some((key, planner.clone())));
    Ok(planner)
}

/// Calls `progress(done, total, stage)` in JavaScript (`stage` as `spiralcam::progress::Stage::label` names it);
/// a thrown exception cancels the plan.
pub(crate) fn reporter(
    progress: &js_sys::Function,
) -> impl FnMut(Progress) -> ControlFlow<()> + '_ {
    move |p: Progress| {
        let done = JsValue::from_f64(p.done as f64);
        let total = JsValue::from_f64(p.total as f64);
        let stage = JsValue::from_str(p.stage.label());
        match progress.call3(&JsValue::NULL, &done, &total, &stage) {
            Ok(_) => ControlFlow::Continue(()),
            Err(_) => ControlFlow::Break(()),
        }
    }
}

/// A planned job: the report and what the page draws.
#[wasm_bindgen]
pub struct Planned {
    report: String,
    mesh: SurfaceMesh,
    path: Vec<f32>,
    revolution_step: u32,
    file_stem: String,
    extension: String,
}

#[wasm_bindgen]
impl Planned {
    /// The report as JSON text (the command line's `--report`).
    #[wasm_bindgen(getter)]
    pub fn report(&self) -> String {
        self.report.clone()
    }

    /// Surface mesh vertex positions, x y z per vertex, mm.
    #[wasm_bindgen(getter)]
    pub fn mesh_positions(&self) -> Vec<f32> {
        self.mesh.positions.clone()
    }

    /// Surface mesh unit normals, x y z per vertex.
    #[wasm_bindgen(getter)]
    pub fn mesh_normals(&self) -> Vec<f32> {
        self.mesh.normals.clone()
    }

    /// Surface mesh triangles.
    #[wasm_bindgen(getter)]
    pub fn mesh_indices(&self) -> Vec<u32> {
        self.mesh.indices.clone()
    }

    /// Lowest sag on the mesh, mm.
    #[wasm_bindgen(getter)]
    pub fn z_min(&self) -> f64 {
        self.mesh.z_min
    }

    /// Highest sag on the mesh, mm.
    #[wasm_bindgen(getter)]
    pub fn z_max(&self) -> f64 {
        self.mesh.z_max
    }

    /// The decimated path as line segments, two x y z points each, mm, on the surface.
    #[wasm_bindgen(getter)]
    pub fn path(&self) -> Vec<f32> {
        self.path.clone()
    }

    /// Only every this many revolutions is in [`Planned::path`].
    #[wasm_bindgen(getter)]
    pub fn revolution_step(&self) -> u32 {
        self.revolution_step
    }

    /// File name of the NC program: the job name and the dialect's extension.
    #[wasm_bindgen(getter)]
    pub fn nc_file_name(&self) -> String {
        format!("{}.{}", self.file_stem, self.extension)
    }

    /// File name of the CSV table.
    #[wasm_bindgen(getter)]
    pub fn csv_file_name(&self) -> String {
        format!("{}.csv", self.file_stem)
    }
}

/// Plans `job` for display: report, surface mesh and decimated path. `progress(done, total)` is
/// called every 65 536 points.
#[wasm_bindgen]
pub fn plan(job: JsValue, progress: &js_sys::Function) -> Result<Planned, JsError> {
    let planner = read_job(job, progress)?;
    let cost = admit(&planner, Outputs::default())?;
    let mut display = display_path(&planner);
    let sinks = Sinks {
        display: Some(&mut display),
        ..Default::default()
    };
    let mut report = planner
        .run_with_dynamics(sinks, &mut reporter(progress))
        .map_err(|e| JsError::new(&e.to_string()))?;
    report.estimate = Some(cost);
    planned(&planner, report.to_json(), display)
}

/// The display copy of the whole path.
fn display_path(planner: &Planner) -> DisplayPath {
    let total = planner.spiral().point_count_hint();
    DisplayPath::new(total, planner.spiral().revolutions(), DISPLAY_POINTS)
}

/// What the page draws of a plan whose report is `report`.
fn planned(planner: &Planner, report: String, display: DisplayPath) -> Result<Planned, JsError> {
    let mesh = SurfaceMesh::for_surface(planner.surface(), planner.job().part_radius_mm())
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok(Planned {
        report,
        mesh,
        revolution_step: display.revolution_step() as u32,
        path: display.segments,
        file_stem: planner.job().name.clone(),
        extension: planner.job().output.style().extension.to_string(),
    })
}

/// Whether `job` can be planned in slices on several workers, as JSON:
/// `{"points": N, "sliced": true}`, or `{"points": N, "sliced": false, "why": "…"}` (a program
/// with passes, machine dynamics, a space spiral: [`Planner::slicing`]), `N` the path's point
/// count (an estimate for constant-arc and surface-dependent samplings).
#[wasm_bindgen]
pub fn slicing(job: JsValue, progress: &js_sys::Function) -> Result<String, JsError> {
    let planner = sliced_planner(job, progress)?;
    let points = planner.spiral().point_count_hint();
    Ok(match planner.slicing() {
        Ok(()) => serde_json::json!({ "points": points, "sliced": true }),
        Err(why) => serde_json::json!({ "points": points, "sliced": false, "why": why }),
    }
    .to_string())
}

/// One slice of a plan ([`plan_slice`]).
#[wasm_bindgen]
pub struct PlannedSlice {
    part: String,
    segments: Vec<f32>,
    nc: Vec<u8>,
}

#[wasm_bindgen]
impl PlannedSlice {
    /// Its figures and display state as JSON, for [`plan_merge`].
    #[wasm_bindgen(getter)]
    pub fn part(&self) -> String {
        self.part.clone()
    }

    /// Its display segments, for [`plan_merge`].
    #[wasm_bindgen(getter)]
    pub fn segments(&self) -> Vec<f32> {
        self.segments.clone()
    }

    /// The length of its program text in bytes (0 unless asked for).
    #[wasm_bindgen(getter)]
    pub fn nc_length(&self) -> u32 {
        self.nc.len() as u32
    }

    /// Copies its program text into `into`, exactly [`Self::nc_length`] bytes long (a view on a
    /// buffer the page handed back from a slice already written): writing a program of any
    /// length then leaves no buffers behind for the collector.
    pub fn copy_nc(&self, into: &js_sys::Uint8Array) -> Result<(), JsError> {
        if into.length() != self.nc_length() {
            return Err(JsError::new(&format!(
                "slice: a view of {} bytes for {} bytes of program text",
                into.length(),
                self.nc.len()
            )));
        }
        into.copy_from(&self.nc);
        Ok(())
    }
}

/// A slice's figures and display state ([`PlannedSlice::part`]); no display state for a slice
/// planned for its program.
#[derive(serde::Serialize, serde::Deserialize)]
struct SlicePart {
    slice: PlanSlice,
    display: Option<DisplayPath>,
}

/// Plans the points `first` ≤ index < `end` of `job` (`end` infinite: to the path's end), the
/// work of one of the page's workers ([`Planner::run_slice`]): their report figures and either
/// their display copy or, when `nc`, their program text (the header in the first slice, the
/// end in the last). The texts of consecutive slices concatenated are the program `nc_program`
/// writes.
#[wasm_bindgen]
pub fn plan_slice(
    job: JsValue,
    first: f64,
    end: f64,
    nc: bool,
    progress: &js_sys::Function,
) -> Result<PlannedSlice, JsError> {
    let planner = sliced_planner(job, progress)?;
    admit_sliced(&planner, nc)?;
    let index = |v: f64, name: &str| {
        if v.is_finite() && v >= 0.0 && v.fract() == 0.0 {
            Ok(v as u64)
        } else if v == f64::INFINITY {
            Ok(u64::MAX)
        } else {
            Err(JsError::new(&format!(
                "slice {name} = {v}: must be a whole number ≥ 0"
            )))
        }
    };
    let range = index(first, "first")?..index(end, "end")?;
    let theta0 = planner
        .first_point()
        .map_err(|e| JsError::new(&e.to_string()))?
        .theta;
    let mut display = (!nc).then(|| display_path(&planner).starting_at(range.start, theta0));
    let mut text = Vec::new();
    let slice = planner
        .run_slice(
            range,
            nc.then_some(&mut text as &mut dyn std::io::Write),
            display.as_mut(),
            &mut reporter(progress),
        )
        .map_err(|e| JsError::new(&e.to_string()))?;
    let segments = display
        .as_mut()
        .map(|d| std::mem::take(&mut d.segments))
        .unwrap_or_default();
    let part = serde_json::to_string(&SlicePart { slice, display })
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok(PlannedSlice {
        part,
        segments,
        nc: text,
    })
}

/// The plan of `job` from its slices ([`plan_slice`], in order): `parts` their
/// [`PlannedSlice::part`]s as a JSON array, `segments` their segments one after the other,
/// `counts` how many numbers each has. The same report and drawing as [`plan`]; the concave
/// zones are searched here.
#[wasm_bindgen]
pub fn plan_merge(
    job: JsValue,
    parts: &str,
    segments: Vec<f32>,
    counts: Vec<u32>,
    progress: &js_sys::Function,
) -> Result<Planned, JsError> {
    let planner = sliced_planner(job, progress)?;
    let cost = admit(&planner, Outputs::default())?;
    let parts: Vec<SlicePart> =
        serde_json::from_str(parts).map_err(|e| JsError::new(&format!("slices: {e}")))?;
    if parts.len() != counts.len()
        || counts.iter().map(|&c| c as usize).sum::<usize>() != segments.len()
    {
        return Err(JsError::new(
            "slices: the parts, counts and segments disagree",
        ));
    }
    let (mut stats, mut nc_bytes, mut display) = (Stats::default(), 0, None::<DisplayPath>);
    let mut rest = segments.as_slice();
    for (part, count) in parts.into_iter().zip(counts) {
        let (mine, after) = rest.split_at(count as usize);
        rest = after;
        let mut d = part
            .display
            .ok_or_else(|| JsError::new("slices: a part planned for its program has no drawing"))?;
        d.segments = mine.to_vec();
        display = Some(match display {
            None => d,
            Some(before) => before.merge(d),
        });
        stats = stats.merge(part.slice.stats);
        nc_bytes += part.slice.nc_bytes;
    }
    let mut report = planner
        .report_of(&stats, nc_bytes, &mut reporter(progress))
        .map_err(|e| JsError::new(&e.to_string()))?;
    report.estimate = Some(cost);
    planned(
        &planner,
        report.to_json(),
        display.unwrap_or_else(|| display_path(&planner)),
    )
}

/// A slice's cost, refused beyond the command line's limits: a slice holds only its own text,
/// so the page's limit on a download built in memory does not apply.
fn admit_sliced(planner: &Planner, nc: bool) -> Result<(), JsError> {
    let cost = planner
        .cost(None)
        .map_err(|e| JsError::new(&e.to_string()))?;
    let outputs = Outputs {
        nc,
        ..Outputs::default()
    };
    Limits::default()
        .check(&cost, outputs, planner.job().strategy.feed_mm_per_rev)
        .map_err(|e| JsError::new(&e.to_string()))
}

/// The NC program of `job`, byte for byte what `spiralcam plan JOB --nc FILE` writes; for a
/// program split into child programs (`program.max_program_bytes`), a zip of the main program
/// (`NAME.nc`) and its children (`NAME-1.nc`, … as the command line names them beside it).
#[wasm_bindgen]
pub fn nc_program(job: JsValue, progress: &js_sys::Function) -> Result<Vec<u8>, JsError> {
    let mut children = ChildBuffers::default();
    let (main, name) = output_file(job, progress, Download::Nc, Some(&mut children))?;
    if children.0.is_empty() {
        return Ok(main);
    }
    let mut files = vec![(name, main)];
    files.extend(children.0);
    crate::bundle::zip_files(&files).map_err(|e| JsError::new(&e))
}

/// Child programs kept in memory for the zip, in the order they are first written.
#[derive(Default)]
struct ChildBuffers(Vec<crate::bundle::NamedFile>);

impl ChildFiles for ChildBuffers {
    fn child(&mut self, number: usize, name: &str) -> std::io::Result<&mut dyn std::io::Write> {
        if number > self.0.len() {
            self.0.push((name.to_string(), Vec::new()));
        }
        let (_, bytes) = self
            .0
            .get_mut(number - 1)
            .ok_or_else(|| std::io::Error::other(format!("child {number} out of order")))?;
        Ok(bytes)
    }
}

/// The CSV table of `job`, byte for byte what `spiralcam plan JOB --csv FILE` writes.
#[wasm_bindgen]
pub fn csv_table(job: JsValue, progress: &js_sys::Function) -> Result<Vec<u8>, JsError> {
    Ok(output_file(job, progress, Download::Csv, None)?.0)
}

/// The example machines (`spiralcam::job::machine::presets`) as JSON: a list of objects with `key`,
/// `label`, `description`, `block_rate_hz`, `x_slide`, `z_slide` and `fts` (null: none), in the
/// job's units, for the page's machine presets.
#[wasm_bindgen]
pub fn machine_presets() -> String {
    serde_json::to_string(&spiralcam::job::machine::presets()).unwrap_or_default()
}

/// The fast tool servo's table of a split `job` (`c_deg,x_mm,w_mm`), byte for byte what
/// `spiralcam plan JOB --fts-csv FILE` writes.
#[wasm_bindgen]
pub fn fts_table(job: JsValue, progress: &js_sys::Function) -> Result<Vec<u8>, JsError> {
    Ok(output_file(job, progress, Download::FtsTable, None)?.0)
}

/// The servo's gridded table of a split `job` (`spiralcam plan JOB --fts-table FILE`): a zip of
/// the Delta Tau PMAC table (`NAME-fts-grid.pmc`) and the same grid as CSV
/// (`NAME-fts-grid.csv`), byte for byte what the command line writes.
#[wasm_bindgen]
pub fn fts_grid(job: JsValue, progress: &js_sys::Function) -> Result<Vec<u8>, JsError> {
    let job: Job = parse_job(job)?;
    let planner = Planner::with_progress(&job, &mut reporter(progress))
        .map_err(|e| JsError::new(&e.to_string()))?;
    let outputs = Outputs {
        fts_grid: true,
        ..Outputs::default()
    };
    admit(&planner, outputs)?;
    let (mut pmac, mut csv) = (Vec::new(), Vec::new());
    planner
        .run_with_dynamics(
            Sinks {
                fts_grid: Some(&mut pmac),
                fts_grid_csv: Some(&mut csv),
                ..Default::default()
            },
            &mut reporter(progress),
        )
        .map_err(|e| JsError::new(&e.to_string()))?;
    let name = &planner.job().name;
    crate::bundle::zip_files(&[
        (format!("{name}-fts-grid.pmc"), pmac),
        (format!("{name}-fts-grid.csv"), csv),
    ])
    .map_err(|e| JsError::new(&e))
}

/// The most bytes a download is built from, in the page's memory (the command line writes any
/// size to disk).
const MAX_DOWNLOAD_BYTES: u64 = 1_000_000_000;

/// The most points the page runs the machine dynamics on: they hold the path in the worker's
/// memory, beside the download's buffer, in a wasm32 memory of at most 4 GiB.
const MAX_DYNAMICS_POINTS: u64 = 17_000_000;

/// The most memory the machine dynamics may hold in the page, bytes (their estimate,
/// [`spiralcam::dynamics::memory_bytes`]): 1.9 GB. A path whose densest turn is denser than the
/// others (HCAA, constant arc) has more samples than points, and reaches it with fewer points.
const MAX_DYNAMICS_BYTES: u64 = 1_900_000_000;

/// The job's cost ([`Planner::cost`]; no clock in the browser), refused beyond the page's
/// limits for the file that `outputs` names.
fn admit(planner: &Planner, outputs: Outputs) -> Result<Cost, JsError> {
    let cost = planner
        .cost(None)
        .map_err(|e| JsError::new(&e.to_string()))?;
    let limits = Limits {
        max_output_bytes: MAX_DOWNLOAD_BYTES,
        max_dynamics_points: MAX_DYNAMICS_POINTS,
        max_dynamics_bytes: Some(MAX_DYNAMICS_BYTES),
        ..Limits::default()
    };
    limits
        .check(&cost, outputs, planner.job().strategy.feed_mm_per_rev)
        .map_err(|e| {
            JsError::new(&format!(
                "{e} (in the page a download is at most 1 GB and the machine dynamics take at \
                 most {MAX_DYNAMICS_POINTS} points and {}; the command line writes any size and \
                 takes {} points with the dynamics)",
                spiralcam::report::bytes(MAX_DYNAMICS_BYTES),
                spiralcam::dynamics::MAX_POINTS
            ))
        })?;
    Ok(cost)
}

/// A file the page downloads.
#[derive(Clone, Copy)]
enum Download {
    Nc,
    Csv,
    FtsTable,
}

/// Plans `job` into a byte buffer as the `download` file (child programs into `children`);
/// returns the bytes and the file's name as the command line would write it.
fn output_file(
    job: JsValue,
    progress: &js_sys::Function,
    download: Download,
    children: Option<&mut dyn ChildFiles>,
) -> Result<(Vec<u8>, String), JsError> {
    let planner = read_job(job, progress)?;
    let outputs = Outputs {
        nc: matches!(download, Download::Nc),
        csv: matches!(download, Download::Csv),
        fts_table: matches!(download, Download::FtsTable),
        fts_grid: false,
    };
    let cost = admit(&planner, outputs)?;
    let job = planner.job();
    let name = match download {
        Download::Nc => format!("{}.{}", job.name, job.output.style().extension),
        Download::Csv => format!("{}.csv", job.name),
        Download::FtsTable => format!("{}-fts.csv", job.name),
    };
    // Room for the whole file at once: growing by doubling would hold it twice.
    let mut out = Vec::with_capacity((cost.output_bytes(outputs) as f64 * 1.02) as usize + 4096);
    let mut sinks = Sinks {
        // The trait object's lifetime shortened to the buffer's.
        children: children.map(|c| c as &mut dyn ChildFiles),
        ..Default::default()
    };
    match download {
        Download::Nc => sinks.nc = Some(&mut out),
        Download::Csv => sinks.csv = Some(&mut out),
        Download::FtsTable => sinks.fts_table = Some(&mut out),
    }
    planner
        .run_with_dynamics(sinks, &mut reporter(progress))
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok((out, name))
}

/// The accuracy analysis of a job's path, for the page's accuracy panel.
#[wasm_bindgen]
pub struct Accuracy {
    analysis: Analysis,
}

/// A map's values as f32 (NaN where there is none), row by row from −y to +y.
fn map_values(map: &Raster) -> Vec<f32> {
    map.values.iter().map(|&v| v as f32).collect()
}

#[wasm_bindgen]
impl Accuracy {
    /// The figures as JSON (see `spiralcam::analysis::Analysis`).
    #[wasm_bindgen(getter)]
    pub fn report(&self) -> String {
        self.analysis.to_json()
    }

    /// Samples per side of both maps.
    #[wasm_bindgen(getter)]
    pub fn size(&self) -> usize {
        self.analysis.linearization_map().size
    }

    /// Signed linearization error, µm (negative: overcut).
    #[wasm_bindgen(getter)]
    pub fn linearization_um(&self) -> Vec<f32> {
        map_values(self.analysis.linearization_map())
    }

    /// The clearance angle the surface requires, degrees.
    #[wasm_bindgen(getter)]
    pub fn clearance_deg(&self) -> Vec<f32> {
        map_values(self.analysis.clearance_map())
    }

    /// Predicted form error, µm (positive: material left); NaN without a prediction.
    #[wasm_bindgen(getter)]
    pub fn form_error_um(&self) -> Vec<f32> {
        map_values(&self.analysis.form_map())
    }
}

/// Plans `job` and analyses its accuracy (linearization error, predicted form) with maps of
/// `size` × `size` samples, the same figures `spiralcam analyse` prints; admitted first as
/// `spiralcam analyse` admits it, with its default limits ([`AnalysisLimits`]), timed by the
/// worker's clock.
#[wasm_bindgen]
pub fn analyse(
    job: JsValue,
    size: usize,
    progress: &js_sys::Function,
) -> Result<Accuracy, JsError> {
    let planner = read_job(job, progress)?;
    planner
        .admit_analysis(AnalysisLimits::default(), &|| js_sys::Date::now() / 1e3)
        .map_err(|e| {
            JsError::new(&format!(
                "{e} (the page analyses as the command line does by default; \
                 `spiralcam analyse` takes --max-points and --max-seconds)"
            ))
        })?;
    let analysis = Analysis::run(&planner, size, &mut reporter(progress))
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok(Accuracy { analysis })
}

/// Mean-power and cylinder maps of a progressive lens, for the page's map panel.
#[wasm_bindgen]
pub struct PowerMaps {
    map: PowerMap,
}

#[wasm_bindgen]
impl PowerMaps {
    /// Samples per side of the square grid.
    #[wasm_bindgen(getter)]
    pub fn size(&self) -> usize {
        self.map.mean_d.size
    }

    /// Mean power, D, row by row from −y to +y (NaN outside the part).
    #[wasm_bindgen(getter)]
    pub fn mean_d(&self) -> Vec<f32> {
        self.map.mean_d.values.iter().map(|&v| v as f32).collect()
    }

    /// Cylinder, D (NaN outside the part).
    #[wasm_bindgen(getter)]
    pub fn cylinder_d(&self) -> Vec<f32> {
        self.map
            .cylinder_d
            .values
            .iter()
            .map(|&v| v as f32)
            .collect()
    }

    /// Grid spacing, mm.
    #[wasm_bindgen(getter)]
    pub fn step_mm(&self) -> f64 {
        self.map.mean_d.step_mm
    }
}

/// The power maps of `job` when its surface is a progressive lens (with the lens's refractive
/// index), else `undefined`.
#[wasm_bindgen]
pub fn power_maps(job: JsValue, size: usize) -> Result<Option<PowerMaps>, JsError> {
    let job = parse_job(job)?;
    let SurfaceSpec::Pal(pal) = &job.surface else {
        return Ok(None);
    };
    let part = PartDisc::centred(job.part_radius_mm());
    let surface = job
        .build_surface()
        .map_err(|e| JsError::new(&e.to_string()))?;
    let map = PowerMap::sample(surface.as_ref(), part, pal.refractive_index, size)
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok(Some(PowerMaps { map }))
}

/// The height colour scale's stops, (t, r, g, b) each in [0, 1], for maps drawn in JavaScript.
#[wasm_bindgen]
pub fn colormap_stops() -> Vec<f32> {
    crate::colormap::STOPS.iter().flatten().copied().collect()
}

/// A designer's file (`name` says its format: `.zmx`, `.seq` or `.DAT`) read for the page's
/// "Import design…": its surfaces as JSON ([`crate::design::design_surfaces`]).
#[wasm_bindgen]
pub fn design_surfaces(name: &str, bytes: &[u8]) -> Result<String, JsError> {
    crate::design::design_surfaces(name, bytes).map_err(|e| JsError::new(&e))
}

/// A job from surface `surface` (`undefined`: the only one) of a designer's file, cut as
/// `piece` (`"optic"`, `"mould"` or `""`) with the part's diameter `diameter_mm`
/// (`undefined`: twice the semi-diameter); `file_names` and `file_texts` are the other files
/// chosen with it (a Grid Sag `.DAT` the `.zmx` names). JSON `{job, listing, surface}`
/// ([`crate::design::import_design`]), the job `spiralcam import` writes with its data carried
/// as text.
#[wasm_bindgen]
pub fn import_design(
    name: &str,
    bytes: &[u8],
    surface: Option<u32>,
    piece: &str,
    diameter_mm: Option<f64>,
    file_names: Vec<String>,
    file_texts: Vec<String>,
) -> Result<String, JsError> {
    let side: Vec<crate::design::SideFile> = file_names
        .into_iter()
        .zip(file_texts)
        .map(|(name, text)| crate::design::SideFile { name, text })
        .collect();
    crate::design::import_design(
        name,
        bytes,
        surface.map(|s| s as usize),
        piece,
        diameter_mm,
        &side,
    )
    .map_err(|e| JsError::new(&e))
}

/// Checks `job` without planning; throws the first field error.
#[wasm_bindgen]
pub fn check_job(job: JsValue) -> Result<(), JsError> {
    Planner::new(&parse_job(job)?)
        .map(|_| ())
        .map_err(|e| JsError::new(&e.to_string()))
}

/// The most points [`sag`] evaluates in one call (80 MB of coordinates).
pub const MAX_SAG_POINTS: usize = 5_000_000;

/// The job's surface height z (mm, the spindle's frame, as `spiralcam sag` prints it) at each
/// point of `xy` (x0, y0, x1, y1, … in mm). Throws naming the point where the surface is
/// undefined or not finite, an odd length, or more than [`MAX_SAG_POINTS`] points.
#[wasm_bindgen]
pub fn sag(job: JsValue, xy: &[f64]) -> Result<Vec<f64>, JsError> {
    if !xy.len().is_multiple_of(2) {
        return Err(JsError::new(&format!(
            "points: {} numbers, not pairs x, y",
            xy.len()
        )));
    }
    if xy.len() / 2 > MAX_SAG_POINTS {
        return Err(JsError::new(&format!(
            "points: {} points, at most {MAX_SAG_POINTS} a call",
            xy.len() / 2
        )));
    }
    let job = parse_job(job)?;
    job.validate().map_err(|e| JsError::new(&e.to_string()))?;
    let surface = job
        .build_surface()
        .map_err(|e| JsError::new(&e.to_string()))?;
    xy.chunks_exact(2)
        .enumerate()
        .map(|(i, p)| {
            let at = || format!("point {i} (x = {}, y = {})", short(p[0]), short(p[1]));
            let z = surface
                .local(p[0], p[1])
                .map_err(|e| JsError::new(&format!("{}: {e}", at())))?
                .z;
            if z.is_finite() {
                Ok(z)
            } else {
                Err(JsError::new(&format!(
                    "{}: the surface is not finite",
                    at()
                )))
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_position_in_the_page_s_json_text_is_left_out() {
        assert_eq!(
            without_position(
                "job: surface: invalid type: floating point `2.5`, expected a surface at line 1 column 69"
            ),
            "job: surface: invalid type: floating point `2.5`, expected a surface"
        );
        // Only a position at the end, in digits.
        for kept in [
            "job: name: a name at line 3",
            "job: a cut at line 1 column x",
            "part.diameter_mm = -1: must be a finite number > 0",
        ] {
            assert_eq!(without_position(kept), kept);
        }
    }
}
