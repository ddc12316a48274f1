// spiralcam's JavaScript API (README, "Use it from JavaScript"): the package's entry, copied into
// pkg/ by web/build.sh beside the wasm-bindgen output it wraps. Planning and the NC text run in a
// module worker (spiralcam-worker.js) so the calling thread stays free: progress comes back as
// it goes, and aborting the signal terminates the worker, which stops the work at once. sag()
// runs here, on the wasm module this file instantiates once.

import init, { sag as wasmSag, default_job, version } from './spiralcam_web.js';

let ready = null;

/** Instantiates the wasm module (once); resolves when the synchronous calls can run. */
export function load() {
  ready ??= init({ module_or_path: new URL('./spiralcam_web_bg.wasm', import.meta.url) });
  return ready;
}

/** Runs `kind` ("plan" or "nc") on `job` in a fresh worker. */
function inWorker(kind, job, { onProgress, signal } = {}) {
  return new Promise((resolve, reject) => {
    if (signal?.aborted) {
      reject(signal.reason ?? new DOMException('aborted', 'AbortError'));
      return;
    }
    const worker = new Worker(new URL('./spiralcam-worker.js', import.meta.url), { type: 'module' });
    const abort = () => {
      worker.terminate();
      reject(signal.reason ?? new DOMException('aborted', 'AbortError'));
    };
    signal?.addEventListener('abort', abort, { once: true });
    const done = () => {
      signal?.removeEventListener('abort', abort);
      worker.terminate();
    };
    worker.onmessage = (e) => {
      const m = e.data;
      if (m.kind === 'progress') {
        onProgress?.({ done: m.done, total: m.total, stage: m.stage });
        return;
      }
      done();
      if (m.kind === 'error') reject(new Error(m.message));
      else resolve(m);
    };
    worker.onerror = (e) => {
      done();
      reject(new Error(`spiralcam worker: ${e.message}`));
    };
    worker.postMessage({ kind, job });
  });
}

/** Plans `job` (a job object as in crate/docs/job-format.md). Resolves to { report, path,
 * mesh: { positions, normals, indices, zMin, zMax }, ncFileName }. */
export async function plan(job, options) {
  return (await inWorker('plan', job, options)).planned;
}

/** The NC program of `job` as text. */
export async function ncText(job, options) {
  return (await inWorker('nc', job, options)).text;
}

/** The surface height z (mm, the spindle's frame) of `job` at each point: `points` is
 * [[x, y], …] or a Float64Array x0, y0, x1, y1, … (mm). Returns a Float64Array. */
export async function sag(job, points) {
  await load();
  const xy = points instanceof Float64Array ? points : Float64Array.from(points.flat());
  return wasmSag(job, xy);
}

/** The default job (paper 004's lens array) as an object. */
export async function defaultJob() {
  await load();
  return JSON.parse(default_job());
}

/** The version of spiralcam. */
export async function spiralcamVersion() {
  await load();
  return version();
}
