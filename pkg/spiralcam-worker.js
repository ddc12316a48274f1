// The worker of spiralcam.js: plans one job, or writes its NC program, and answers with progress
// messages and one result ({kind: "planned" | "nc" | "error"}).

import init, { plan, nc_program } from './spiralcam_web.js';

self.onmessage = async (e) => {
  const { kind, job } = e.data;
  const progress = (done, total, stage) => self.postMessage({ kind: 'progress', done, total, stage });
  try {
    await init({ module_or_path: new URL('./spiralcam_web_bg.wasm', import.meta.url) });
    if (kind === 'plan') {
      const p = plan(job, progress);
      const planned = {
        report: JSON.parse(p.report),
        path: p.path,
        mesh: { positions: p.mesh_positions, normals: p.mesh_normals, indices: p.mesh_indices, zMin: p.z_min, zMax: p.z_max },
        ncFileName: p.nc_file_name,
      };
      p.free();
      self.postMessage({ kind: 'planned', planned }, [planned.path.buffer, planned.mesh.positions.buffer, planned.mesh.normals.buffer, planned.mesh.indices.buffer]);
    } else {
      const text = new TextDecoder().decode(nc_program(job, progress));
      self.postMessage({ kind: 'nc', text });
    }
  } catch (err) {
    self.postMessage({ kind: 'error', message: String(err && err.message ? err.message : err) });
  }
};
