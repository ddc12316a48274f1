// Types of spiralcam.js, the package's entry (README, "Use it from JavaScript"). The job and the
// report are the JSON documents of crate/docs/job-format.md and the command line's --report.

/** A job: the JSON object of crate/docs/job-format.md. */
export type Job = { format?: 1; name: string; [field: string]: unknown };

/** The plan's report (the command line's `--report` JSON); the figures most used are typed. */
export interface Report {
  job: string;
  surface: string;
  points: number;
  revolutions: number;
  cycle_time_s: number;
  nc_bytes: number;
  surface_pv_um: number;
  warnings: string[];
  [figure: string]: unknown;
}

export interface Progress { done: number; total: number; stage: string }

export interface Options {
  /** Called as the work goes: points done of the total, and the stage's name. */
  onProgress?: (progress: Progress) => void;
  /** Aborting it stops the work at once (its worker is terminated) and rejects the promise. */
  signal?: AbortSignal;
}

export interface Planned {
  report: Report;
  /** The path as x, y, z triples (mm), every revolution or every n-th. */
  path: Float32Array;
  /** The surface as a triangle mesh (mm). */
  mesh: { positions: Float32Array; normals: Float32Array; indices: Uint32Array; zMin: number; zMax: number };
  /** The program's file name (the job's name and the dialect's extension). */
  ncFileName: string;
}

/** Instantiates the wasm module once; the other calls do it when needed. */
export function load(): Promise<unknown>;
/** Plans `job` in a worker. Rejects with the core's message naming the field of a bad job. */
export function plan(job: Job, options?: Options): Promise<Planned>;
/** The NC program of `job`, as the command line writes it. */
export function ncText(job: Job, options?: Options): Promise<string>;
/** The surface height z (mm) at each point ([[x, y], …] or x0, y0, x1, y1, …; mm). */
export function sag(job: Job, points: Array<[number, number]> | Float64Array): Promise<Float64Array>;
/** The default job (paper 004's lens array). */
export function defaultJob(): Promise<Job>;
/** The version of spiralcam. */
export function spiralcamVersion(): Promise<string>;
