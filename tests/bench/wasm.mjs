// Planning throughput of the WebAssembly build under Node: the page's own pkg/ module runs
// nc_program (plan + compensation + ISO NC) on 1 M-point versions of the lens-array and asphere
// jobs, and on the 1 M-point sine grid split between slide and servo (two planning passes, the
// spectrum, the split and the axis checks, the program with W).
// Usage: node tests/bench/wasm.mjs   (after web/build.sh; pkg/ is committed)

import { readFileSync } from 'node:fs';
import { performance } from 'node:perf_hooks';
import init, { nc_program } from '../../pkg/spiralcam_web.js';

const root = new URL('../../', import.meta.url);
await init({ module_or_path: readFileSync(new URL('pkg/spiralcam_web_bg.wasm', root)) });

function million(file, revs) {
  const job = JSON.parse(readFileSync(new URL(`crate/jobs/${file}`, root), 'utf8'));
  job.strategy.feed_mm_per_rev = job.part.diameter_mm / 2 / revs;
  job.strategy.sampling = { type: 'constant_angle', points_per_rev: Math.floor(1e6 / revs) };
  job.output = { dialect: 'iso' };
  return job;
}

for (const [name, job] of [
  ['lens_array_paper004', million('lens-array-paper004.json', 500)],
  ['asphere', million('asphere-f20.json', 1000)],
  ['sine_grid_split', million('sinusoid-grid-fts.json', 1000)],
]) {
  let points = 0;
  const runs = [];
  for (let i = 0; i < 3; i++) {
    const t = performance.now();
    // The largest count reported: later stages (the concave-zone scan) count their own steps.
    const bytes = nc_program(job, (done) => { points = Math.max(points, done); });
    runs.push((performance.now() - t) / 1000);
    if (i === 0) console.log(`${name}: NC ${(bytes.length / 1e6).toFixed(1)} MB`);
  }
  const best = Math.min(...runs);
  console.log(`${name}: ${points} points, best of 3 ${best.toFixed(3)} s → ${(points / best / 1e6).toFixed(3)} M points/s (wasm, Node ${process.version})`);
}
