// The planning worker: loads the wasm module once and answers {id, kind, job} messages with
// progress messages and one result ({kind: "planned" | "analysed" | "corrected" | "offsets" |
// "verified" | "bytes" | "slicing" | "slice"}) or {kind: "error", message}. The page runs
// several: a large plan or program is cut into slices of the path ("slice": `extra` {first, end,
// nc, buffer}: `buffer` an ArrayBuffer of an earlier slice's text handed back for this one's),
// one per worker at a time, and joined in order ("merge": `extra` {parts, segments,
// counts}, answered as "planned").
// Typed arrays are transferred, not copied.

import init, { analyse, plan, plan_slice, plan_merge, slicing, nc_program, csv_table, fts_table, fts_grid, power_maps, correct, setup_offsets, verify_program } from '../pkg/spiralcam_web.js';

/** Samples per side of the power maps. */
const MAP_SIZE = 161;

/** The module: compiled once by the page and handed over ({kind: "module", module}) when the
 * page does so, else fetched and compiled here at the first call. */
let ready = null;

/** The "planned" message of a plan (`p`, freed here) of `job`, and what it transfers. */
function planned(id, p, job) {
  const m = {
    id,
    kind: 'planned',
    report: JSON.parse(p.report),
    positions: p.mesh_positions,
    normals: p.mesh_normals,
    indices: p.mesh_indices,
    zMin: p.z_min,
    zMax: p.z_max,
    path: p.path,
    revolutionStep: p.revolution_step,
    names: { nc: p.nc_file_name, csv: p.csv_file_name },
  };
  p.free();
  const transfer = [m.positions.buffer, m.normals.buffer, m.indices.buffer, m.path.buffer];
  const maps = power_maps(job, MAP_SIZE);
  if (maps) {
    m.maps = { size: maps.size, stepMm: maps.step_mm, mean: maps.mean_d, cylinder: maps.cylinder_d };
    maps.free();
    transfer.push(m.maps.mean.buffer, m.maps.cylinder.buffer);
  }
  return [m, transfer];
}

self.onmessage = async (e) => {
  const { id, kind, job, extra } = e.data;
  if (kind === 'module') {
    ready ??= init({ module_or_path: e.data.module });
    return;
  }
  ready ??= init();
  const progress = (done, total, stage) => self.postMessage({ id, kind: 'progress', done, total, stage });
  try {
    await ready;
    if (kind === 'plan') {
      self.postMessage(...planned(id, plan(job, progress), job));
    } else if (kind === 'merge') {
      const p = plan_merge(job, extra.parts, extra.segments, extra.counts, progress);
      self.postMessage(...planned(id, p, job));
    } else if (kind === 'slicing') {
      self.postMessage({ id, kind: 'slicing', slicing: JSON.parse(slicing(job, progress)) });
    } else if (kind === 'slice') {
      const s = plan_slice(job, extra.first, extra.end, extra.nc, progress);
      // The text goes into the buffer the page handed back when it fits, else into a new one
      // with room for the slices after it.
      const length = s.nc_length;
      const buffer = extra.buffer?.byteLength >= length ? extra.buffer : new ArrayBuffer(Math.ceil(length * 1.25));
      const nc = new Uint8Array(buffer, 0, length);
      s.copy_nc(nc);
      const m = { id, kind: 'slice', part: s.part, segments: s.segments, nc };
      s.free();
      self.postMessage(m, [m.segments.buffer, buffer]);
    } else if (kind === 'analyse') {
      const a = analyse(job, MAP_SIZE, progress);
      const m = {
        id,
        kind: 'analysed',
        report: JSON.parse(a.report),
        size: a.size,
        linearization: a.linearization_um,
        form: a.form_error_um,
        clearance: a.clearance_deg,
      };
      a.free();
      self.postMessage(m, [m.linearization.buffer, m.form.buffer, m.clearance.buffer]);
    } else if (kind === 'correct') {
      const c = correct(job, extra.name, extra.bytes, extra.options);
      const m = {
        id,
        kind: 'corrected',
        report: JSON.parse(c.report),
        size: c.size,
        before: c.before_um,
        after: c.after_um,
        job: JSON.parse(c.job_json),
        ncName: c.nc_file_name,
      };
      c.free();
      self.postMessage(m, [m.before.buffer, m.after.buffer]);
    } else if (kind === 'verify') {
      const v = verify_program(job, extra.name, extra.text, extra.names, extra.texts, progress);
      const m = {
        id,
        kind: 'verified',
        report: JSON.parse(v.report),
        size: v.size,
        deviation: v.deviation_um,
        trace: v.trace,
      };
      v.free();
      self.postMessage(m, [m.deviation.buffer, m.trace.buffer]);
    } else if (kind === 'setup') {
      self.postMessage({ id, kind: 'offsets', offsets: JSON.parse(setup_offsets(job, extra)) });
    } else {
      const write = { nc: nc_program, csv: csv_table, fts: fts_table, grid: fts_grid }[kind];
      const bytes = write(job, progress);
      self.postMessage({ id, kind: 'bytes', bytes }, [bytes.buffer]);
    }
  } catch (err) {
    self.postMessage({ id, kind: 'error', message: String(err && err.message ? err.message : err) });
  }
};
