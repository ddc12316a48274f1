// The planning worker: loads the wasm module once and answers {id, kind, job} messages with
// progress messages and one result ({kind: "planned" | "analysed" | "bytes"}) or
// {kind: "error", message}.
// Typed arrays are transferred, not copied.

import init, { analyse, plan, nc_program, csv_table, fts_table, fts_grid, power_maps } from '../pkg/spiralcam_web.js';

/** Samples per side of the power maps. */
const MAP_SIZE = 161;

const ready = init();

self.onmessage = async (e) => {
  const { id, kind, job } = e.data;
  const progress = (done, total, stage) => self.postMessage({ id, kind: 'progress', done, total, stage });
  try {
    await ready;
    if (kind === 'plan') {
      const p = plan(job, progress);
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
      self.postMessage(m, transfer);
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
    } else {
      const write = { nc: nc_program, csv: csv_table, fts: fts_table, grid: fts_grid }[kind];
      const bytes = write(job, progress);
      self.postMessage({ id, kind: 'bytes', bytes }, [bytes.buffer]);
    }
  } catch (err) {
    self.postMessage({ id, kind: 'error', message: String(err && err.message ? err.message : err) });
  }
};
