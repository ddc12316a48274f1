/* tslint:disable */
/* eslint-disable */

/**
 * The accuracy analysis of a job's path, for the page's accuracy panel.
 */
export class Accuracy {
    private constructor();
    free(): void;
    [Symbol.dispose](): void;
    /**
     * The clearance angle the surface requires, degrees.
     */
    readonly clearance_deg: Float32Array;
    /**
     * Predicted form error, µm (positive: material left); NaN without a prediction.
     */
    readonly form_error_um: Float32Array;
    /**
     * Signed linearization error, µm (negative: overcut).
     */
    readonly linearization_um: Float32Array;
    /**
     * The figures as JSON (see `spiralcam::analysis::Analysis`).
     */
    readonly report: string;
    /**
     * Samples per side of both maps.
     */
    readonly size: number;
}

/**
 * A correction made: its report, maps and the corrected job.
 */
export class Corrected {
    private constructor();
    free(): void;
    [Symbol.dispose](): void;
    /**
     * The residual predicted after the re-cut, µm.
     */
    readonly after_um: Float32Array;
    /**
     * The residual before, µm (mean per cell of the measured points; NaN where none).
     */
    readonly before_um: Float32Array;
    /**
     * The corrected job as JSON, its correction grid inline.
     */
    readonly job_json: string;
    /**
     * The file name of the corrected job's NC program: its name and the dialect's extension.
     */
    readonly nc_file_name: string;
    /**
     * The report as JSON (registration, residual, corrected, warnings).
     */
    readonly report: string;
    /**
     * Samples per side of both maps.
     */
    readonly size: number;
}

/**
 * A planned job: the report and what the page draws.
 */
export class Planned {
    private constructor();
    free(): void;
    [Symbol.dispose](): void;
    /**
     * File name of the CSV table.
     */
    readonly csv_file_name: string;
    /**
     * Surface mesh triangles.
     */
    readonly mesh_indices: Uint32Array;
    /**
     * Surface mesh unit normals, x y z per vertex.
     */
    readonly mesh_normals: Float32Array;
    /**
     * Surface mesh vertex positions, x y z per vertex, mm.
     */
    readonly mesh_positions: Float32Array;
    /**
     * File name of the NC program: the job name and the dialect's extension.
     */
    readonly nc_file_name: string;
    /**
     * The decimated path as line segments, two x y z points each, mm, on the surface.
     */
    readonly path: Float32Array;
    /**
     * The report as JSON text (the command line's `--report`).
     */
    readonly report: string;
    /**
     * Only every this many revolutions is in [`Planned::path`].
     */
    readonly revolution_step: number;
    /**
     * Highest sag on the mesh, mm.
     */
    readonly z_max: number;
    /**
     * Lowest sag on the mesh, mm.
     */
    readonly z_min: number;
}

/**
 * One slice of a plan ([`plan_slice`]).
 */
export class PlannedSlice {
    private constructor();
    free(): void;
    [Symbol.dispose](): void;
    /**
     * Copies its program text into `into`, exactly [`Self::nc_length`] bytes long (a view on a
     * buffer the page handed back from a slice already written): writing a program of any
     * length then leaves no buffers behind for the collector.
     */
    copy_nc(into: Uint8Array): void;
    /**
     * The length of its program text in bytes (0 unless asked for).
     */
    readonly nc_length: number;
    /**
     * Its figures and display state as JSON, for [`plan_merge`].
     */
    readonly part: string;
    /**
     * Its display segments, for [`plan_merge`].
     */
    readonly segments: Float32Array;
}

/**
 * Mean-power and cylinder maps of a progressive lens, for the page's map panel.
 */
export class PowerMaps {
    private constructor();
    free(): void;
    [Symbol.dispose](): void;
    /**
     * Cylinder, D (NaN outside the part).
     */
    readonly cylinder_d: Float32Array;
    /**
     * Mean power, D, row by row from −y to +y (NaN outside the part).
     */
    readonly mean_d: Float32Array;
    /**
     * Samples per side of the square grid.
     */
    readonly size: number;
    /**
     * Grid spacing, mm.
     */
    readonly step_mm: number;
}

/**
 * A program verified.
 */
export class Verified {
    private constructor();
    free(): void;
    [Symbol.dispose](): void;
    /**
     * The last pass's deviation, µm, row by row from −y to +y (NaN where no point fell).
     */
    readonly deviation_um: Float32Array;
    /**
     * The report as JSON.
     */
    readonly report: string;
    /**
     * Samples per side of the map.
     */
    readonly size: number;
    /**
     * The trace: x, y, z (mm) and deviation (µm) of every k-th cutting point of the last
     * pass, in order, flat.
     */
    readonly trace: Float32Array;
}

/**
 * The 3-D view of a surface and its tool path on a canvas. A viewer freed (its element
 * removed from the page) gives its buffers and textures back at once, and with the last
 * viewer the page's WebGPU device ([`gpu`]).
 */
export class Viewer {
    private constructor();
    free(): void;
    [Symbol.dispose](): void;
    /**
     * "WebGPU" or "WebGL2": the backend actually in use.
     */
    backend(): string;
    /**
     * Creates a viewer on the canvas: WebGPU if the browser offers an adapter, else WebGL2;
     * on WebGPU with the page's device where another viewer holds one.
     * Errors (no backend at all) become a JS exception with a clear message.
     */
    static create(canvas: HTMLCanvasElement): Promise<Viewer>;
    /**
     * How many GPU devices the page's viewers have opened: on WebGPU one serves them all.
     */
    static devices_opened(): number;
    /**
     * Orbits about the part centre by a drag of `dx`, `dy` CSS pixels.
     */
    orbit(dx: number, dy: number): void;
    /**
     * Pans the view by a drag of `dx`, `dy` CSS pixels.
     */
    pan(dx: number, dy: number): void;
    /**
     * Draws one frame. Reconfigures the surface and retries on Lost/Outdated.
     */
    render(): void;
    /**
     * Back to the default view (part seen from above at 35° elevation, fitted to the canvas).
     */
    reset_view(): void;
    /**
     * New canvas size in CSS pixels and the devicePixelRatio; the drawing buffer is
     * size × dpr, each at least 1 (and at most the device's texture limit).
     */
    resize(css_width: number, css_height: number, device_pixel_ratio: number): void;
    /**
     * A verified program's path, drawn instead of the planned path until cleared: `xyz` its
     * points in order (mm, a line strip), `deviation_nm` each point's deviation from the
     * design (nm), coloured on the height scale's colours from `lo_nm` (bottom) to `hi_nm`
     * (top) while the surface is drawn grey. Fewer than two points, or lengths that disagree
     * (reported on the console), go back to the planned path and the height colours. The
     * placement stays the surface's.
     */
    set_deviation_path(xyz: Float32Array | number[], deviation_nm: Float32Array | number[], lo_nm: number, hi_nm: number): void;
    /**
     * The tool path as line segments, two xyz points (mm) each, lying on the surface; drawn
     * on top in a contrasting colour.
     */
    set_path(xyz: Float32Array | number[]): void;
    /**
     * The surface mesh: positions xyz (mm), unit normals xyz, triangle indices; z_min/z_max
     * (mm) the height range used for the colour scale (0 → bottom of the colormap, 1 → top).
     * Inconsistent input (lengths, indices out of range) is reported on the console and
     * clears the surface. A new part (other extent) resets the view.
     */
    set_surface(positions: Float32Array | number[], normals: Float32Array | number[], indices: Uint32Array | number[], z_min: number, z_max: number): void;
    /**
     * Whether a verified program's path is shown (see [`Viewer::set_deviation_path`]).
     */
    shows_deviation(): boolean;
    /**
     * Vertical exaggeration in use: heights are drawn this many times their true size.
     */
    z_exaggeration(): number;
    /**
     * Zooms by `factor` (> 1 zooms in).
     */
    zoom(factor: number): void;
}

/**
 * Plans `job` and analyses its accuracy (linearization error, predicted form) with maps of
 * `size` × `size` samples, the same figures `spiralcam analyse` prints; admitted first as
 * `spiralcam analyse` admits it, with its default limits ([`AnalysisLimits`]), timed by the
 * worker's clock.
 */
export function analyse(job: any, size: number, progress: Function): Accuracy;

/**
 * Checks `job` without planning; throws the first field error.
 */
export function check_job(job: any): void;

/**
 * The height colour scale as a CSS gradient, for the legend.
 */
export function colormap_css(): string;

/**
 * The height colour scale's stops, (t, r, g, b) each in [0, 1], for maps drawn in JavaScript.
 */
export function colormap_stops(): Float32Array;

/**
 * Corrects `job` with the measured file `name` (`bytes`) under `options` ([`CorrectOptions`]).
 */
export function correct(job: any, name: string, bytes: Uint8Array | number[], options: any): Corrected;

/**
 * The CSV table of `job`, byte for byte what `spiralcam plan JOB --csv FILE` writes.
 */
export function csv_table(job: any, progress: Function): Uint8Array;

/**
 * The page's default job (paper 004's lens array) as JSON text.
 */
export function default_job(): string;

/**
 * A designer's file (`name` says its format: `.zmx`, `.seq` or `.DAT`) read for the page's
 * "Import design…": its surfaces as JSON ([`crate::design::design_surfaces`]).
 */
export function design_surfaces(name: string, bytes: Uint8Array | number[]): string;

/**
 * The servo's gridded table of a split `job` (`spiralcam plan JOB --fts-table FILE`): a zip of
 * the Delta Tau PMAC table (`NAME-fts-grid.pmc`) and the same grid as CSV
 * (`NAME-fts-grid.csv`), byte for byte what the command line writes.
 */
export function fts_grid(job: any, progress: Function): Uint8Array;

/**
 * The fast tool servo's table of a split `job` (`c_deg,x_mm,w_mm`), byte for byte what
 * `spiralcam plan JOB --fts-csv FILE` writes.
 */
export function fts_table(job: any, progress: Function): Uint8Array;

/**
 * A job from surface `surface` (`undefined`: the only one) of a designer's file, cut as
 * `piece` (`"optic"`, `"mould"` or `""`) with the part's diameter `diameter_mm`
 * (`undefined`: twice the semi-diameter); `file_names` and `file_texts` are the other files
 * chosen with it (a Grid Sag `.DAT` the `.zmx` names). JSON `{job, listing, surface}`
 * ([`crate::design::import_design`]), the job `spiralcam import` writes with its data carried
 * as text.
 */
export function import_design(name: string, bytes: Uint8Array | number[], surface: number | null | undefined, piece: string, diameter_mm: number | null | undefined, file_names: string[], file_texts: string[]): string;

/**
 * The example machines (`spiralcam::job::machine::presets`) as JSON: a list of objects with `key`,
 * `label`, `description`, `block_rate_hz`, `x_slide`, `z_slide` and `fts` (null: none), in the
 * job's units, for the page's machine presets.
 */
export function machine_presets(): string;

/**
 * The NC program of `job`, byte for byte what `spiralcam plan JOB --nc FILE` writes; for a
 * program split into child programs (`program.max_program_bytes`), a zip of the main program
 * (`NAME.nc`) and its children (`NAME-1.nc`, … as the command line names them beside it).
 */
export function nc_program(job: any, progress: Function): Uint8Array;

/**
 * Plans `job` for display: report, surface mesh and decimated path. `progress(done, total)` is
 * called every 65 536 points.
 */
export function plan(job: any, progress: Function): Planned;

/**
 * The plan of `job` from its slices ([`plan_slice`], in order): `parts` their
 * [`PlannedSlice::part`]s as a JSON array, `segments` their segments one after the other,
 * `counts` how many numbers each has. The same report and drawing as [`plan`]; the concave
 * zones are searched here.
 */
export function plan_merge(job: any, parts: string, segments: Float32Array | number[], counts: Uint32Array | number[], progress: Function): Planned;

/**
 * Plans the points `first` ≤ index < `end` of `job` (`end` infinite: to the path's end), the
 * work of one of the page's workers ([`Planner::run_slice`]): their report figures and either
 * their display copy or, when `nc`, their program text (the header in the first slice, the
 * end in the last). The texts of consecutive slices concatenated are the program `nc_program`
 * writes.
 */
export function plan_slice(job: any, first: number, end: number, nc: boolean, progress: Function): PlannedSlice;

/**
 * The power maps of `job` when its surface is a progressive lens (with the lens's refractive
 * index), else `undefined`.
 */
export function power_maps(job: any, size: number): PowerMaps | undefined;

/**
 * The job's surface height z (mm, the spindle's frame, as `spiralcam sag` prints it) at each
 * point of `xy` (x0, y0, x1, y1, … in mm). Throws naming the point where the surface is
 * undefined or not finite, an odd length, or more than [`MAX_SAG_POINTS`] points.
 */
export function sag(job: any, xy: Float64Array | number[]): Float64Array;

/**
 * The offsets a test cut of `job` shows (`params`: the JSON of `spiralcam setup --params`),
 * as JSON.
 */
export function setup_offsets(job: any, params: string): string;

/**
 * Whether `job` can be planned in slices on several workers, as JSON:
 * `{"points": N, "sliced": true}`, or `{"points": N, "sliced": false, "why": "…"}` (a program
 * with passes, machine dynamics, a space spiral: [`Planner::slicing`]), `N` the path's point
 * count (an estimate for constant-arc and surface-dependent samplings).
 */
export function slicing(job: any, progress: Function): string;

/**
 * Verifies the program `name` (`text`) against `job`; `names` and `texts` are the other files
 * chosen with it, where its child programs are looked for. `progress(done, total, stage)`
 * sees the moves read and may cancel by throwing.
 */
export function verify_program(job: any, name: string, text: string, names: string[], texts: string[], progress: Function): Verified;

/**
 * The crate version, shown on the page.
 */
export function version(): string;

export type InitInput = RequestInfo | URL | Response | BufferSource | WebAssembly.Module;

export interface InitOutput {
    readonly memory: WebAssembly.Memory;
    readonly __wbg_accuracy_free: (a: number, b: number) => void;
    readonly __wbg_corrected_free: (a: number, b: number) => void;
    readonly __wbg_planned_free: (a: number, b: number) => void;
    readonly __wbg_plannedslice_free: (a: number, b: number) => void;
    readonly __wbg_powermaps_free: (a: number, b: number) => void;
    readonly __wbg_verified_free: (a: number, b: number) => void;
    readonly __wbg_viewer_free: (a: number, b: number) => void;
    readonly accuracy_clearance_deg: (a: number) => [number, number];
    readonly accuracy_form_error_um: (a: number) => [number, number];
    readonly accuracy_linearization_um: (a: number) => [number, number];
    readonly accuracy_report: (a: number) => [number, number];
    readonly accuracy_size: (a: number) => number;
    readonly analyse: (a: any, b: number, c: any) => [number, number, number];
    readonly check_job: (a: any) => [number, number];
    readonly colormap_css: () => [number, number];
    readonly colormap_stops: () => [number, number];
    readonly correct: (a: any, b: number, c: number, d: number, e: number, f: any) => [number, number, number];
    readonly corrected_after_um: (a: number) => [number, number];
    readonly corrected_before_um: (a: number) => [number, number];
    readonly corrected_job_json: (a: number) => [number, number];
    readonly corrected_nc_file_name: (a: number) => [number, number];
    readonly corrected_report: (a: number) => [number, number];
    readonly corrected_size: (a: number) => number;
    readonly csv_table: (a: any, b: any) => [number, number, number, number];
    readonly default_job: () => [number, number];
    readonly design_surfaces: (a: number, b: number, c: number, d: number) => [number, number, number, number];
    readonly fts_grid: (a: any, b: any) => [number, number, number, number];
    readonly fts_table: (a: any, b: any) => [number, number, number, number];
    readonly import_design: (a: number, b: number, c: number, d: number, e: number, f: number, g: number, h: number, i: number, j: number, k: number, l: number, m: number) => [number, number, number, number];
    readonly machine_presets: () => [number, number];
    readonly nc_program: (a: any, b: any) => [number, number, number, number];
    readonly plan: (a: any, b: any) => [number, number, number];
    readonly plan_merge: (a: any, b: number, c: number, d: number, e: number, f: number, g: number, h: any) => [number, number, number];
    readonly plan_slice: (a: any, b: number, c: number, d: number, e: any) => [number, number, number];
    readonly planned_csv_file_name: (a: number) => [number, number];
    readonly planned_mesh_indices: (a: number) => [number, number];
    readonly planned_mesh_normals: (a: number) => [number, number];
    readonly planned_mesh_positions: (a: number) => [number, number];
    readonly planned_nc_file_name: (a: number) => [number, number];
    readonly planned_path: (a: number) => [number, number];
    readonly planned_report: (a: number) => [number, number];
    readonly planned_revolution_step: (a: number) => number;
    readonly planned_z_max: (a: number) => number;
    readonly planned_z_min: (a: number) => number;
    readonly plannedslice_copy_nc: (a: number, b: any) => [number, number];
    readonly plannedslice_nc_length: (a: number) => number;
    readonly plannedslice_part: (a: number) => [number, number];
    readonly plannedslice_segments: (a: number) => [number, number];
    readonly power_maps: (a: any, b: number) => [number, number, number];
    readonly powermaps_cylinder_d: (a: number) => [number, number];
    readonly powermaps_mean_d: (a: number) => [number, number];
    readonly powermaps_size: (a: number) => number;
    readonly powermaps_step_mm: (a: number) => number;
    readonly sag: (a: any, b: number, c: number) => [number, number, number, number];
    readonly setup_offsets: (a: any, b: number, c: number) => [number, number, number, number];
    readonly slicing: (a: any, b: any) => [number, number, number, number];
    readonly verified_deviation_um: (a: number) => [number, number];
    readonly verified_report: (a: number) => [number, number];
    readonly verified_size: (a: number) => number;
    readonly verified_trace: (a: number) => [number, number];
    readonly verify_program: (a: any, b: number, c: number, d: number, e: number, f: number, g: number, h: number, i: number, j: any) => [number, number, number];
    readonly version: () => [number, number];
    readonly viewer_backend: (a: number) => [number, number];
    readonly viewer_create: (a: any) => any;
    readonly viewer_devices_opened: () => number;
    readonly viewer_orbit: (a: number, b: number, c: number) => void;
    readonly viewer_pan: (a: number, b: number, c: number) => void;
    readonly viewer_render: (a: number) => [number, number];
    readonly viewer_reset_view: (a: number) => void;
    readonly viewer_resize: (a: number, b: number, c: number, d: number) => void;
    readonly viewer_set_deviation_path: (a: number, b: number, c: number, d: number, e: number, f: number, g: number) => void;
    readonly viewer_set_path: (a: number, b: number, c: number) => void;
    readonly viewer_set_surface: (a: number, b: number, c: number, d: number, e: number, f: number, g: number, h: number, i: number) => void;
    readonly viewer_shows_deviation: (a: number) => number;
    readonly viewer_z_exaggeration: (a: number) => number;
    readonly viewer_zoom: (a: number, b: number) => void;
    readonly wasm_bindgen__convert__closures_____invoke__h0c816e4ac06bbd87: (a: number, b: number, c: any) => [number, number];
    readonly wasm_bindgen__convert__closures_____invoke__h0c816e4ac06bbd87_74: (a: number, b: number, c: any) => [number, number];
    readonly wasm_bindgen__convert__closures_____invoke__h0c816e4ac06bbd87_75: (a: number, b: number, c: any) => [number, number];
    readonly wasm_bindgen__convert__closures_____invoke__h6a9a4c771fb11aad: (a: number, b: number, c: any, d: any) => void;
    readonly wasm_bindgen__convert__closures_____invoke__he0d491e625fe5b2c: (a: number, b: number, c: any) => [number, number];
    readonly wasm_bindgen__convert__closures_____invoke__h9a591c57c7a39bce: (a: number, b: number, c: any) => void;
    readonly wasm_bindgen__convert__closures_____invoke__h9a591c57c7a39bce_73: (a: number, b: number, c: any) => void;
    readonly __wbindgen_malloc: (a: number, b: number) => number;
    readonly __wbindgen_realloc: (a: number, b: number, c: number, d: number) => number;
    readonly __wbindgen_free: (a: number, b: number, c: number) => void;
    readonly __wbindgen_exn_store: (a: number) => void;
    readonly __externref_table_alloc: () => number;
    readonly __wbindgen_externrefs: WebAssembly.Table;
    readonly __wbindgen_destroy_closure: (a: number, b: number) => void;
    readonly __externref_table_dealloc: (a: number) => void;
    readonly __externref_drop_slice: (a: number, b: number) => void;
    readonly __wbindgen_start: () => void;
}

export type SyncInitInput = BufferSource | WebAssembly.Module;

/**
 * Instantiates the given `module`, which can either be bytes or
 * a precompiled `WebAssembly.Module`.
 *
 * @param {{ module: SyncInitInput }} module - Passing `SyncInitInput` directly is deprecated.
 *
 * @returns {InitOutput}
 */
export function initSync(module: { module: SyncInitInput } | SyncInitInput): InitOutput;

/**
 * If `module_or_path` is {RequestInfo} or {URL}, makes a request and
 * for everything else, calls `WebAssembly.instantiate` directly.
 *
 * @param {{ module_or_path: InitInput | Promise<InitInput> }} module_or_path - Passing `InitInput` directly is deprecated.
 *
 * @returns {Promise<InitOutput>}
 */
export default function __wbg_init (module_or_path?: { module_or_path: InitInput | Promise<InitInput> } | InitInput | Promise<InitInput>): Promise<InitOutput>;
