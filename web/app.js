// The page: the job form, planning in Web Workers (progress, cancel; a long path in slices on
// one worker per core, its program streamed to the file), the 3-D view, the report,
// the machine dynamics (split verdict, axis checks, 2-D plots) and the downloads; the measured
// panel (a measured file corrected against the job: residual before and after, the corrected
// job and its program), the set-up panel (a test cut turned into offsets) and Open NC… (a
// program verified against the job: its report, the last pass's deviation map in nm, and the
// last pass drawn in the 3-D view over a grey surface, coloured by deviation with its legend
// in nm, until the next plan or the box is unticked). Planning never
// runs on this thread, so the page stays responsive; a new
// edit or Cancel terminates the worker and starts a fresh one. The page's state is mirrored on
// `document.body.dataset.state` ("loading", "planning", "done", "analysing", "analysed",
// "correcting", "corrected", "verifying", "verified", "error", "cancelled") and
// `window.spiralcam` (plans started and finished, the report, the accuracy analysis, the
// correction's and the verification's reports, the backend, what the
// last design import read) for the browser tests. "Import design…" is web/import.js.

import init, { Viewer, default_job, colormap_css, colormap_stops, machine_presets, version } from '../pkg/spiralcam_web.js';
import { JobForm } from './form.js';
import { bindImport } from './import.js';
import { bindGestures } from './gestures.js';
import { drawPlot, prepare } from './plots.js';
import { offlineCopy } from './offline.js';
import { FORMAT, dataFiles, formatProblem, jobFromLocation, shareLink } from './share.js';

const $ = (id) => document.getElementById(id);
const status = (window.spiralcam = { streamAbove: 200e6, saved: null, slices: 0, state: 'loading', stale: false, backend: null, report: null, analysis: null, correction: null, verification: null, started: 0, plans: 0, error: null, imported: null });

function setState(s) {
  status.state = s;
  document.body.dataset.state = s;
}

/** The wasm module, compiled once for the page and each of its workers (each would otherwise
 * fetch and compile its 7 MB again, three or more at once on the page's first plan). */
let compiled = null;
function wasmModule() {
  compiled ??= (async () => {
    const url = new URL('../pkg/spiralcam_web_bg.wasm', import.meta.url);
    try {
      return await WebAssembly.compileStreaming(fetch(url));
    } catch {
      // A server that does not label .wasm as application/wasm.
      return WebAssembly.compile(await (await fetch(url)).arrayBuffer());
    }
  })();
  return compiled;
}

/** One module worker and its call in flight. */
class Lane {
  constructor() {
    this.pending = null;
    this.nextId = 1;
    this.start();
  }

  start() {
    this.worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    const worker = this.worker;
    // Calls are posted after the module, so the worker does not compile its own.
    this.loaded = wasmModule().then((module) => worker.postMessage({ kind: 'module', module }), () => {});
    this.worker.onmessage = (e) => this.message(e.data);
    this.worker.onerror = (e) => this.fail(new Error(`worker: ${e.message}`));
  }

  message(m) {
    if (!this.pending || m.id !== this.pending.id) return;
    if (m.kind === 'progress') {
      this.pending.onProgress(m.done, m.total, m.stage);
      return;
    }
    const { resolve, reject } = this.pending;
    this.pending = null;
    if (m.kind === 'error') reject(new Error(m.message));
    else resolve(m);
  }

  fail(err) {
    if (!this.pending) return;
    const { reject } = this.pending;
    this.pending = null;
    reject(err);
  }

  /** Runs one call; `transfer` the buffers handed over with it. */
  call(kind, job, extra, onProgress, transfer = []) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending = { id, resolve, reject, onProgress };
      const worker = this.worker;
      this.loaded.then(() => worker.postMessage({ id, kind, job, extra }, transfer));
    });
  }

  /** Stops the call in flight, if any: the worker is terminated and a fresh one started. */
  stop() {
    if (!this.pending) return;
    const { reject } = this.pending;
    this.pending = null;
    this.worker.terminate();
    this.start();
    reject(cancelled());
  }
}

function cancelled() {
  const err = new Error('cancelled');
  err.cancelled = true;
  return err;
}

/** Most workers planning slices at once. */
const MAX_WORKERS = 8;
/** Paths with fewer points are planned in one worker (the slices' set-up would cost more). */
const SLICED_ABOVE = 300_000;
/** Points of a slice of a program being written: about 2.3 MB of text (larger slices grew each
 * worker's memory by their text and its copy, and the tab's garbage with them). */
const PROGRAM_SLICE = 65_536;
/** Slices are cut on multiples of the warm-start run (spiralcam::tool::WARM_RUN): each then
 * computes again only the run before it (its first point's predecessor's). */
const RUN = 64;

/** Runs planner calls in module workers (progress, cancel): one call at a time on the first,
 * or a long path cut into slices planned by one worker per core and joined in order (a
 * point's position and compensation are functions of its index). */
class PlannerWorker {
  constructor(onProgress) {
    this.onProgress = onProgress;
    // Every worker loads its module now, in parallel with the first call.
    this.lanes = Array.from({ length: this.size }, () => new Lane());
    this.session = 0;
  }

  /** Workers for slices: one per core, at most [`MAX_WORKERS`] (`window.spiralcam.workers`
   * sets another count, for measurements). */
  get size() {
    return Math.max(1, Math.min(status.workers ?? navigator.hardwareConcurrency ?? 1, MAX_WORKERS));
  }

  /** `kind`: "plan", "analyse", "nc", "csv", "fts", "grid", "correct" (`extra`: the measured
   * file's name, bytes and options), "setup" (`extra`: the observations as JSON) or "verify"
   * (`extra`: the program's name and text, the other files' names and texts). */
  run(kind, job, extra) {
    this.cancel();
    const transfer = extra?.bytes ? [extra.bytes.buffer] : [];
    return this.lanes[0].call(kind, job, extra, (done, total, stage) => this.onProgress(kind, done, total, stage), transfer);
  }

  /** Plans `job` for display: in slices on every worker when the path is long and the job
   * allows it, else in one. */
  async plan(job) {
    const how = this.size > 1 ? await this.slicing(job, 'plan') : null;
    if (!how || how.points < SLICED_ABOVE) return this.run('plan', job);
    const parts = [];
    const segments = [];
    await this.slices(job, how.points, cut(how.points, 4 * this.size), false, (m) => {
      parts.push(m.part);
      segments.push(m.segments);
    });
    const all = new Float32Array(segments.reduce((n, s) => n + s.length, 0));
    segments.reduce((at, s) => (all.set(s, at), at + s.length), 0);
    const extra = { parts: `[${parts.join(',')}]`, segments: all, counts: segments.map((s) => s.length) };
    const m = await this.lanes[0].call('merge', job, extra, (done, total, stage) => this.onProgress('plan', done, total, stage), [all.buffer]);
    return { ...m, slices: parts.length };
  }

  /** Writes the program of `job` in slices, handing each slice's text to `write` in order
   * (awaited); false when the job is written in one piece (a program with passes, machine
   * dynamics, a space spiral), then nothing is written. */
  async program(job, write) {
    const how = await this.slicing(job, 'nc');
    if (!how) return false;
    await this.slices(job, how.points, cut(how.points, Math.ceil(how.points / PROGRAM_SLICE)), true, (m) => write(m.nc));
    return true;
  }

  /** How `job` may be sliced ({points}), or null when it may not. Every worker sets the job up
   * at once (a surface-dependent sampling takes seconds) and keeps it for its slices; the
   * others are stopped when the job is not sliced. `kind` names the work for the progress. */
  async slicing(job, kind) {
    this.cancel();
    while (this.lanes.length < this.size) this.lanes.push(new Lane());
    const progress = (done, total, stage) => this.onProgress(kind, done, total, stage);
    const [first, ...rest] = this.lanes.map((lane, k) => lane.call('slicing', job, undefined, k === 0 ? progress : () => {}));
    rest.forEach((p) => p.catch(() => {}));
    const m = await first;
    if (!m.slicing.sliced) {
      this.lanes.slice(1).forEach((lane) => lane.stop());
      return null;
    }
    await Promise.all(rest);
    return m.slicing;
  }

  /** Plans the slices `ranges` ([first, end) pairs) of `job`'s path of about `total` points on
   * every worker and hands the results to `take` in order (awaited); at most two slices per
   * worker wait to be taken. With `nc` each slice's text comes in an ArrayBuffer that goes back
   * to the workers once `take` is done with it (a write to a file or a Blob copies it), so a
   * long program reuses a few buffers instead of leaving one per slice to the collector. */
  slices(job, total, ranges, nc, take) {
    this.cancel();
    while (this.lanes.length < this.size) this.lanes.push(new Lane());
    const session = this.session;
    const done = ranges.map(() => 0);
    let sum = 0;
    const results = new Map();
    const spare = [];
    let next = 0;
    let taken = 0;
    let chain = Promise.resolve();
    return new Promise((resolve, reject) => {
      const fail = (e) => {
        if (session === this.session) this.cancel();
        reject(e);
      };
      const launch = (lane) => {
        if (session !== this.session || next >= ranges.length || next - taken >= 2 * this.lanes.length) return;
        const k = next++;
        const [first, end] = ranges[k];
        const progress = (d, _t, stage) => {
          sum += d - done[k];
          done[k] = d;
          // Each slice also counts the two points before it that it computes again.
          this.onProgress(nc ? 'nc' : 'plan', Math.min(sum, total), total, stage);
        };
        const buffer = nc ? spare.pop() : undefined;
        lane.call('slice', job, { first, end, nc, buffer }, progress, buffer ? [buffer] : []).then((m) => {
          results.set(k, m);
          while (results.has(taken)) {
            const r = results.get(taken);
            results.delete(taken);
            taken += 1;
            // Once written, the text's buffer goes back to a worker for a later slice.
            chain = chain.then(() => session === this.session && take(r)).then(() => nc && spare.push(r.nc.buffer));
          }
          if (taken === ranges.length) chain.then(resolve, fail);
          else for (const l of this.lanes) if (!l.pending) launch(l);
        }, fail);
      };
      this.lanes.forEach(launch);
    });
  }

  /** Stops every call in flight. */
  cancel() {
    this.session += 1;
    for (const lane of this.lanes) lane.stop();
  }
}

/** `parts` slices of a path of about `points` points, [first, end) on multiples of [`RUN`],
 * the last to the path's end (the count is an estimate for some samplings). */
function cut(points, parts) {
  const at = (k) => Math.round((points * k) / parts / RUN) * RUN;
  const ranges = [];
  for (let k = 0; k < parts; k++) {
    const first = at(k);
    const end = k + 1 === parts ? Infinity : at(k + 1);
    if (end > first) ranges.push([first, end]);
  }
  return ranges;
}

const fmt = (v, digits = 3) => (Number.isFinite(v) ? v.toLocaleString('en-US', { maximumFractionDigits: digits }) : '–');

/** `v` to four significant digits (tiny figures of a path that hardly moves an axis stay
 * readable). */
function sig(v) {
  if (!Number.isFinite(v)) return '–';
  if (v !== 0 && Math.abs(v) < 1e-3) return v.toExponential(2);
  return Math.abs(v) >= 1000 ? fmt(v, 0) : v.toLocaleString('en-US', { maximumSignificantDigits: 4 });
}

function duration(s) {
  const m = Math.floor(s / 60);
  const h = Math.floor(m / 60);
  const sec = (s - 60 * m).toFixed(1).padStart(4, '0');
  return h ? `${h} h ${String(m % 60).padStart(2, '0')} min` : `${m} min ${sec} s`;
}

function bytes(n) {
  if (!Number.isFinite(n)) return '?';
  if (n >= 1e9) return `${fmt(n / 1e9, 2)} GB`;
  return n >= 1e6 ? `${fmt(n / 1e6, 2)} MB` : `${fmt(n / 1e3, 1)} kB`;
}

/** Table rows `<th>key</th><td data-key="key">value</td>` of [key, value] pairs. */
function keyRows(rows) {
  return rows.map(([k, v]) => {
    const tr = document.createElement('tr');
    const td = Object.assign(document.createElement('td'), { textContent: v });
    td.dataset.key = k;
    tr.append(Object.assign(document.createElement('th'), { textContent: k }), td);
    return tr;
  });
}

/** The report panel. */
function showReport(report, job) {
  const zVelocity = report.max_dz_dtheta_um_per_deg * 360 * job.machine.spindle_rpm / 60 / 1000;
  const rows = [
    ['Surface', report.surface],
    ['Points', fmt(report.points, 0)],
    ['Revolutions', fmt(report.revolutions, 2)],
    ['Start radius', `${fmt(report.start_radius_mm, 6)} mm`],
    ['Cycle time', `${duration(report.cycle_time_s)} at ${fmt(job.machine.spindle_rpm)} rpm`],
    ['NC program', `${bytes(report.nc_bytes)} (${report.dialect})`],
    ['Surface PV', `${fmt(report.surface_pv_um, 4)} µm`],
    ['Commanded Z', `${fmt(report.z_min_mm * 1000, 4)} … ${fmt(report.z_max_mm * 1000, 4)} µm`],
    ['Max |dZ/dC|', `${fmt(report.max_dz_dtheta_um_per_deg, 4)} µm/° (Z speed ${fmt(zVelocity, 3)} mm/s) at ρ ${fmt(report.max_dz_dtheta_at.rho_mm, 3)} mm, θ ${fmt(report.max_dz_dtheta_at.theta_deg, 1)}°`],
    ['Arc-end contacts', fmt(report.arc_end_contacts, 0)],
    ['Unreachable zones', `${report.concave_zones.length}${report.shallow_concave_zones ? ` (+${report.shallow_concave_zones} below 0.1 nm)` : ''}`],
  ];
  if (report.part_edge) rows.push(['Part edge', report.part_edge]);
  const program = report.program;
  if (program) {
    const time = program.passes.reduce((t, p) => t + p.cutting_time_s, 0);
    rows.push(
      ['Passes', `${program.passes.length} (${program.loop_kind === 'controller' ? 'repeated by the controller' : 'written out'}), stock ${fmt(program.stock_mm * 1000, 4)} µm, cutting ${duration(time)}`],
      ['Safe Z', `${fmt(program.safe_z_mm, 6)} mm`],
    );
    if (program.children.length) {
      const total = program.children.reduce((t, c) => t + c.bytes, 0);
      rows.push(['Child programs', `${program.children.length} (${bytes(total)}): ${program.children[0].name} … ${program.children[program.children.length - 1].name}; downloaded as one zip with the main program`]);
    }
  }
  if (job.strategy.compensation === 'two_way') {
    const loopAt = report.first_two_way_loop_at;
    rows.push(
      ['X reversals', fmt(report.x_reversals, 0)],
      ['Largest X acceleration', `${fmt(report.max_x_acceleration_mm_s2, 4)} mm/s² at ρ ${fmt(report.max_x_acceleration_at.rho_mm, 3)} mm, θ ${fmt(report.max_x_acceleration_at.theta_deg, 1)}°`],
      ['Two-way loops', loopAt ? `${fmt(report.two_way_loops, 0)} (${fmt(report.two_way_loop_points, 0)} points), first at ρ ${fmt(loopAt.rho_mm, 3)} mm` : '0'],
    );
  }
  $('report-table').replaceChildren(...keyRows(rows));
  const warnings = $('warnings');
  warnings.replaceChildren(...report.warnings.map((w) => Object.assign(document.createElement('li'), { textContent: w })));
  const zones = $('zones');
  zones.hidden = report.concave_zones.length === 0;
  const body = zones.querySelector('tbody');
  body.replaceChildren(...report.concave_zones.slice(0, 20).map((z) => {
    const tr = document.createElement('tr');
    const cells = [
      `${fmt(z.rho_min_mm, 3)} … ${fmt(z.rho_max_mm, 3)}`,
      `${fmt(z.theta_from_deg, 0)}° … ${fmt(z.theta_to_deg, 0)}°`,
      z.slope_kink ? 'kink' : fmt(z.min_curvature_radius_mm, 4),
      fmt(z.depth_um, 4),
      `ρ ${fmt(z.at.rho_mm, 4)}, θ ${fmt(z.at.theta_deg, 1)}°`,
    ];
    tr.append(...cells.map((c) => Object.assign(document.createElement('td'), { textContent: c })));
    return tr;
  }));
}

/** The splitter's limits (`crate/src/split.rs` `Limit`): name, and the value in the unit of
 * its job field. */
const SPLIT_LIMITS = {
  fts_stroke_mm: ['FTS stroke (W PV)', (v) => `${sig(v * 1000)} µm`],
  fts_bandwidth_hz: ['FTS bandwidth', (v) => `${sig(v)} Hz`],
  fts_acceleration_mm_per_s2: ['FTS acceleration', (v) => `${sig(v / 1000)} m/s²`],
  slide_velocity_mm_per_s: ['Z slide velocity', (v) => `${sig(v * 60)} mm/min`],
  slide_acceleration_mm_per_s2: ['Z slide acceleration', (v) => `${sig(v)} mm/s²`],
  slide_bandwidth_hz: ['Z slide bandwidth', (v) => `${sig(v)} Hz`],
};

const splitLimit = (c) => SPLIT_LIMITS[c.limit] || [c.limit.replaceAll('_', ' '), sig];

/** The split's verdict in words. */
function verdictText(v) {
  if (v.status === 'unchecked') return 'not checked: the machine needs a Z slide and a servo for the split\'s checks';
  if (v.status === 'feasible') {
    return v.slide_alone ? 'feasible: the slide cuts alone (W = 0)' : 'feasible: both channels within the machine\'s limits';
  }
  const what = (v.conflicts || []).map((c) => {
    const [name, unit] = splitLimit(c);
    return `${name} ${unit(c.value)} > ${unit(c.allowed)}${c.at_rho_mm == null ? '' : ` at ρ ${fmt(c.at_rho_mm, 3)} mm`}`;
  });
  const speed = v.feasible_spindle_rpm == null
    ? 'no spindle speed makes it feasible (the stroke)'
    : `feasible at ${fmt(v.feasible_spindle_rpm, 1)} rpm or less`;
  return `infeasible: ${what.join('; ')}; ${speed}`;
}

/** One axis's largest velocity and acceleration against its limits, in the units of the job's
 * fields: mm/min and mm/s² for a slide, m/s² for the servo (whose velocity has no limit). */
function axisText(a, servo = false) {
  const over = (n) => (n ? ` (${fmt(n, 0)} points over)` : '');
  const of = (limit, scale) => (limit == null ? '' : ` of ${sig(limit * scale)}`);
  const v = servo
    ? `${sig(a.max_velocity_mm_per_s)} mm/s`
    : `${sig(a.max_velocity_mm_per_min)}${of(a.velocity_limit_mm_per_s, 60)} mm/min`;
  const acc = servo
    ? `${sig(a.max_acceleration_mm_per_s2 / 1000)}${of(a.acceleration_limit_mm_per_s2, 1e-3)} m/s²`
    : `${sig(a.max_acceleration_mm_per_s2)}${of(a.acceleration_limit_mm_per_s2, 1)} mm/s²`;
  return `velocity ${v}${over(a.velocity_violation_count)}, acceleration ${acc}${over(a.acceleration_violation_count)}`;
}

const at = (p) => (p ? ` at ρ ${fmt(p.rho_mm, 3)} mm, θ ${fmt(p.theta_deg, 1)}°` : '');

/** A slide's bandwidth check: the frequency its channel asks for against its limit. */
function bandwidthText(b) {
  if (b.needed_hz == null) return 'not analysed';
  const limit = b.limit_hz == null ? ' (not checked)' : ` of ${fmt(b.limit_hz, 1)} Hz${b.within_limit ? '' : ': too fast'}`;
  return `${fmt(b.needed_hz, 2)} Hz needed${limit}`;
}

/** The dynamics panel: the split's verdict and checks, the axis checks and three plots. */
function showDynamics(d, job) {
  const panel = $('dynamics');
  panel.hidden = !d;
  if (!d) return;
  const rpm = d.axes.spindle_rpm;
  const split = d.split;
  const rows = [];
  if (split) {
    const how = {
      symmetric: 'symmetric part on the slide (paper 002)',
      low_pass: 'low-pass',
      auto: 'automatic (lowest cutoff the stroke allows)',
    }[split.spec.type] || split.spec.type;
    rows.push(
      ['Split', how],
      ['Verdict', verdictText(split.verdict)],
      ['Cutoff', split.cutoff_hz == null ? '–' : `${fmt(split.cutoff_hz, 3)} Hz (${fmt((split.cutoff_hz * 60) / rpm, 3)} cycles/rev)`],
      ['Z slide PV', `${fmt(split.z_slide_pv_um, 4)} µm`],
      ['W servo PV', `${fmt(split.w_fts_pv_um, 4)} µm`],
    );
  } else {
    rows.push(['Split', 'none: Z cuts alone']);
  }
  const a = d.axes;
  rows.push(['X axis', axisText(a.x)], ['Z axis', axisText(a.z)]);
  if (split) {
    const g = d.fts_grid;
    if (g) rows.push(['FTS grid (PMAC)', `${g.rows} × ${g.columns} entries (X every ${fmt(g.x_spacing_mm * 1000, 4)} µm, C every ${fmt(g.c_spacing_deg, 4)}°), ${bytes(g.pmac_bytes)}; bilinear error max ${fmt(g.max_error_um * 1000, 3)} nm, RMS ${fmt(g.rms_error_um * 1000, 3)} nm (tolerance ${fmt(g.tolerance_um * 1000, 3)} nm)`]);
    rows.push(['W axis', `${axisText(a.w, true)}, stroke ${sig(a.fts_stroke.used_um)}${a.fts_stroke.limit_um == null ? '' : ` of ${sig(a.fts_stroke.limit_um)}`} µm`]);
  }
  const br = a.block_rate;
  rows.push(
    ['Block rate', `${fmt(br.required_hz, 1)} Hz needed${at(br.at)}${br.limit_hz == null ? ' (not checked)' : `; limit ${fmt(br.limit_hz, 1)} Hz${br.violation_count ? ` (${fmt(br.violation_count, 0)} blocks over)` : ''}`}`],
    ['X bandwidth', bandwidthText(d.bandwidth.x)],
    ['Z bandwidth', bandwidthText(d.bandwidth.z)],
    ['Cycle time', `${duration(a.cycle_time_s)} at ${fmt(rpm)} rpm`],
    ['Highest spindle speed', a.max_spindle ? `${fmt(a.max_spindle.max_spindle_rpm, 1)} rpm, bound by ${a.max_spindle.binding_limit}${at(a.max_spindle.at)}` : 'no limit given binds it'],
    ['Within limits', a.within_limits && d.bandwidth.x.within_limit && d.bandwidth.z.within_limit ? 'yes' : 'no (see the warnings above)'],
  );
  $('dynamics-table').replaceChildren(...keyRows(rows));
  const checks = split?.verdict.checks || [];
  $('split-checks').hidden = !checks.length;
  $('split-checks').querySelector('tbody').replaceChildren(...checks.map((c) => {
    const [name, unit] = splitLimit(c);
    const tr = document.createElement('tr');
    tr.dataset.limit = c.limit;
    if (!(c.value <= c.allowed)) tr.className = 'fail';
    const cells = [name, unit(c.value), unit(c.allowed), c.at_rho_mm == null ? '–' : `${fmt(c.at_rho_mm, 3)} mm`];
    tr.append(...cells.map((t) => Object.assign(document.createElement('td'), { textContent: t })));
    return tr;
  }));

  const m = job.machine;
  const slideHz = m.z_slide?.bandwidth_hz;
  const ftsHz = m.fts?.bandwidth_hz;
  // (a) The amplitude spectrum, peaks marked with their frequency.
  const s = d.spectrum;
  const sp = prepare($('plot-spectrum'));
  const spectrumSeries = [
    { type: 'line', x: s.freq_hz, y: s.amplitude_um, colour: '#1f6feb', label: 'amplitude', width: 1 },
    { type: 'markers', x: s.peaks.map((p) => p.freq_hz), y: s.peaks.map((p) => p.amplitude_um), labels: s.peaks.map((p) => `${fmt(p.freq_hz, 1)} Hz`), colour: '#c62828' },
  ];
  if (split?.cutoff_hz != null) spectrumSeries.push({ type: 'vline', x: split.cutoff_hz, colour: '#2e7d32', dash: [4, 3], label: `cutoff ${fmt(split.cutoff_hz, 2)} Hz` });
  // Up to the highest frequency the log scale shows (1e-5 of the largest amplitude).
  const top = Math.max(...s.amplitude_um.filter(Number.isFinite));
  let last = s.freq_hz.length - 1;
  while (last > 0 && !(s.amplitude_um[last] >= top * 1e-5)) last--;
  const fMax = Math.max(s.freq_hz[last] * 1.1, split?.cutoff_hz * 1.1 || 0);
  drawPlot(sp.ctx, { x: 0, y: 0, w: sp.width, h: sp.height }, {
    x: { label: 'frequency', unit: 'Hz', min: 0, max: Number.isFinite(fMax) && fMax > 0 ? Math.min(fMax, s.freq_hz[s.freq_hz.length - 1]) : undefined },
    y: { label: 'amplitude', unit: 'µm', log: true, floorRatio: 1e5, headroom: 3 },
    series: spectrumSeries,
  });
  // (b) Instantaneous frequency against radius, with the bandwidths.
  const bands = d.instantaneous_frequency;
  const mid = bands.map((b) => (b.rho_outer_mm + b.rho_inner_mm) / 2);
  const fp = prepare($('plot-frequency'));
  const frequencySeries = [
    { type: 'line', x: mid, y: bands.map((b) => b.p95_hz), colour: '#9a5b00', label: '95th percentile', dash: [5, 3] },
    { type: 'line', x: mid, y: bands.map((b) => b.median_hz), colour: '#1f6feb', label: 'median' },
  ];
  if (slideHz) frequencySeries.push({ type: 'hline', y: slideHz, colour: '#2e7d32', label: `Z slide bandwidth ${fmt(slideHz, 1)} Hz`, dash: [2, 2] });
  if (ftsHz) frequencySeries.push({ type: 'hline', y: ftsHz, colour: '#c62828', label: `FTS bandwidth ${fmt(ftsHz, 1)} Hz`, dash: [2, 2] });
  drawPlot(fp.ctx, { x: 0, y: 0, w: fp.width, h: fp.height }, {
    x: { label: 'radius ρ', unit: 'mm', min: 0 },
    y: { label: 'frequency', unit: 'Hz', min: 0 },
    series: frequencySeries,
  });
  // (c) Both channels along the path: Z over W, envelopes against radius.
  const ch = d.channels;
  $('channels-figure').hidden = !ch;
  if (ch) {
    const cp = prepare($('plot-channels'), 1.05);
    const half = cp.height / 2;
    drawPlot(cp.ctx, { x: 0, y: 0, w: cp.width, h: half }, {
      x: { label: 'radius ρ', unit: 'mm', min: 0 },
      y: { label: 'Z slide', unit: 'mm' },
      series: [{ type: 'band', x: ch.rho_mm, lo: ch.z_min_mm, hi: ch.z_max_mm, colour: '#1f6feb', label: 'Z (slide)' }],
    });
    drawPlot(cp.ctx, { x: 0, y: half, w: cp.width, h: half }, {
      x: { label: 'radius ρ', unit: 'mm', min: 0 },
      y: { label: 'W servo', unit: 'µm' },
      series: [{ type: 'band', x: ch.rho_mm, lo: ch.w_min_um, hi: ch.w_max_um, colour: '#c62828', label: `${job.output.fts_word || 'W'} (servo)` }],
    });
  }
}

/** A colour from the shared scale at t in [0, 1]: [r, g, b] in 0…255. */
function colour(stops, t) {
  const n = stops.length / 4;
  t = Math.min(1, Math.max(0, t));
  for (let k = 1; k < n; k++) {
    const [t0, t1] = [stops[4 * (k - 1)], stops[4 * k]];
    if (t <= t1 || k === n - 1) {
      const w = t1 > t0 ? (t - t0) / (t1 - t0) : 0;
      return [1, 2, 3].map((c) => 255 * (stops[4 * (k - 1) + c] * (1 - w) + stops[4 * k + c] * w));
    }
  }
  return [0, 0, 0];
}

/** Draws a map (row j = −y … +y, column i = −x … +x) on `canvas`, +y up; NaN left blank. */
function drawMap(canvas, values, size, stops) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of values) if (Number.isFinite(v)) [lo, hi] = [Math.min(lo, v), Math.max(hi, v)];
  const ctx = canvas.getContext('2d');
  const image = ctx.createImageData(size, size);
  for (let j = 0; j < size; j++) {
    for (let i = 0; i < size; i++) {
      const v = values[j * size + i];
      const o = 4 * ((size - 1 - j) * size + i);
      if (!Number.isFinite(v)) continue;
      const [r, g, b] = colour(stops, hi > lo ? (v - lo) / (hi - lo) : 0.5);
      image.data.set([r, g, b, 255], o);
    }
  }
  ctx.putImageData(image, 0, 0);
  return [lo, hi];
}

/** Draws the map `map-<name>` and writes its range, `digits` decimals, under it. */
function showMap(name, values, size, stops, digits, unit) {
  const [lo, hi] = drawMap($(`map-${name}`), values, size, stops);
  $(`map-${name}-range`).textContent = `${fmt(lo, digits)} … ${fmt(hi, digits)} ${unit}`;
}

/** The power maps panel (progressive lenses). */
function showMaps(maps, stops) {
  $('maps').hidden = !maps;
  if (!maps) return;
  showMap('mean', maps.mean, maps.size, stops, 2, 'D');
  showMap('cylinder', maps.cylinder, maps.size, stops, 2, 'D');
}

/** The accuracy panel: linearization error, predicted form and tool angles, figures and maps. */
function showAnalysis(m, stops) {
  const rows = [];
  if (m) {
    const lin = m.report.linearization;
    const form = m.report.predicted_form;
    rows.push(
      ['Linearization PV', `${fmt(lin.pv_um, 4)} µm over ${fmt(lin.segments, 0)} segments`],
      ['Largest overcut between points', `${fmt(lin.max_overcut_um, 4)} µm at ρ ${fmt(lin.worst_at.rho_mm, 3)} mm, θ ${fmt(lin.worst_at.theta_deg, 1)}°`],
      ['Largest undercut between points', `${fmt(lin.max_undercut_um, 4)} µm`],
      ['Cusp height along the feed', `${fmt(form.cusp_height_um, 4)} µm`],
      ['Predicted form error', `PV ${fmt(form.pv_um, 4)} µm, RMS ${fmt(form.rms_um, 4)} µm`],
      ['Predicted overcut', `${fmt(form.max_overcut_um, 4)} µm`],
    );
    const tool = m.report.tool_geometry;
    const at = (c) => `at ρ ${fmt(c.at.rho_mm, 3)} mm, θ ${fmt(c.at.theta_deg, 1)}°`;
    rows.push(
      ['Clearance needed', `${fmt(tool.critical_clearance.deg, 3)}° ${at(tool.critical_clearance)}`],
      ['Rake limit', `${fmt(tool.critical_rake.deg, 3)}° ${at(tool.critical_rake)}`],
      ['Included angle needed', `${fmt(tool.critical_included_angle_deg, 3)}°`],
      ['Clearance interferences', fmt(tool.clearance_interferences, 0)],
      ['Holder tilt', tool.holder_tilt_deg == null ? `none: ${tool.holder_tilt_note}` : `${fmt(tool.holder_tilt_deg, 3)}°`],
      ['Tool verdict', tool.verdict],
    );
    const rev = m.report.revolution;
    if (rev) {
      const q = rev.quasi_revolution;
      const ratio = (p) => (p ? fmt(p.ratio, 4) : '–');
      rows.push(
        ['Surface of revolution (paper 001)', `max α ${fmt(q.max_alpha_deg, 3)}° at (${fmt(q.at_xy_mm[0], 3)}, ${fmt(q.at_xy_mm[1], 3)}) mm: ${q.is_quasi_revolution ? '' : 'not '}quasi-revolution at ${fmt(q.alpha_lim_deg, 1)}°`],
        ['Base surface fit', `RMS ${fmt(rev.base_fit_rms_um, 3)} µm, max ${fmt(rev.base_fit_max_um, 3)} µm`],
        ['Pass spacing max/min', `space spiral ${ratio(rev.space_spiral)}, Z projection ${ratio(rev.z_projection)}`],
      );
    }
    for (const note of m.report.notes) rows.push(['Note', note]);
  }
  $('analysis-table').replaceChildren(...keyRows(rows));
  $('analysis-maps').hidden = !m;
  if (!m) return;
  showMap('linearization', m.linearization, m.size, stops, 4, 'µm');
  showMap('form', m.form, m.size, stops, 4, 'µm');
  showMap('clearance', m.clearance, m.size, stops, 4, '°');
}

/** The measured panel: registration, residual before and predicted after, their maps. */
function showCorrection(m, stops) {
  const rows = [];
  if (m) {
    const reg = m.report.registration;
    const res = m.report.residual;
    const after = m.report.corrected.predicted_residual;
    const um = (v, d = 3) => (v == null ? 'not fitted' : `${fmt(v, d)} µm`);
    rows.push(
      ['Measured', `${m.report.measured.points.toLocaleString('en-US')} points, ${m.report.measured.kind}, ${m.report.measured.orientation}`],
      ['Piston', um(reg.piston_um, 4)],
      ['Tilt x, y', `${fmt(reg.tilt_x_urad, 3)}, ${fmt(reg.tilt_y_urad, 3)} µrad`],
      ['Decentre x, y', reg.decentre_x_um == null ? 'not fitted' : `${fmt(reg.decentre_x_um, 3)}, ${fmt(reg.decentre_y_um, 3)} µm`],
      ['Clocking', reg.clocking_deg == null ? 'not fitted' : `${fmt(reg.clocking_deg, 5)}°`],
      ['Residual before', `PV ${fmt(res.pv_um, 4)} µm, RMS ${fmt(res.rms_um, 4)} µm`],
      ['Largest Zernike terms', topZernike(res.zernike_fringe_um)],
      ['Predicted after the re-cut', `PV ${fmt(after.pv_um, 4)} µm, RMS ${fmt(after.rms_um, 4)} µm (gain ${fmt(m.report.corrected.gain, 3)})`],
    );
    for (const w of m.report.warnings) rows.push(['Warning', w]);
  }
  $('correction-table').replaceChildren(...keyRows(rows));
  $('correction-maps').hidden = !m;
  $('download-corrected').hidden = !m;
  $('download-corrected-nc').hidden = !m;
  if (!m) return;
  // Both maps on the before map's scale, so that the after map shows how much is left.
  const [lo, hi] = drawMap($('map-before'), m.before, m.size, stops);
  $('map-before-range').textContent = `${fmt(lo, 4)} … ${fmt(hi, 4)} µm`;
  const [alo, ahi] = drawMap($('map-after'), m.after, m.size, stops);
  $('map-after-range').textContent = `${fmt(alo, 4)} … ${fmt(ahi, 4)} µm`;
}

/** The Open NC panel: the verify report's figures and the last pass's deviation map, its
 * range in nm. */
function showVerification(m, stops) {
  const rows = [];
  if (m) {
    const r = m.report;
    const nm = (v) => `${fmt(1000 * v, 1)} nm`;
    const at = (a) => (a ? ` at ρ ${fmt(a.rho_mm, 4)} mm, θ ${fmt(a.theta_deg, 2)}° (${a.file}:${a.line})` : '');
    const d = r.deviation_um;
    rows.push(
      ['Program', `${fmt(r.blocks, 0)} blocks, ${fmt(r.cutting_points, 0)} cutting points; units ${r.program.units}, C ${r.program.c}, dialect ${r.program.dialect ?? 'not clear'}`],
      ['Passes', r.passes.map((p) => `${fmt(p.points, 0)} points, stock ${fmt(p.stock_um, 4)} µm`).join('; ') || 'none'],
      ['Deviation, last pass', `min ${nm(d.min)}${at(d.min_at)}, max ${nm(d.max)}${at(d.max_at)}, RMS ${nm(d.rms)}`],
      ['Linearization (last pass)', r.linearization ? `PV ${fmt(r.linearization.pv_um, 4)} µm` : 'not computed'],
      ['Predicted form (last pass)', r.predicted_form ? `PV ${fmt(r.predicted_form.pv_um, 4)} µm, RMS ${fmt(r.predicted_form.rms_um, 4)} µm` : 'not computed'],
      ['Cycle time', `${duration(r.timing.cycle_time_s)} (rapids left out)`],
      ['Spindle', r.timing.spindle_rpm ? `${fmt(r.timing.spindle_rpm.min, 1)} … ${fmt(r.timing.spindle_rpm.max, 1)} rpm` : '–'],
      ['Collisions', r.collisions.count ? `${r.collisions.count} moves, deepest ${fmt(r.collisions.deepest_um, 3)} µm (first at line ${r.collisions.listed[0].at.line})` : 'none'],
    );
    for (const l of r.axis_limits) rows.push([l.field, `${fmt(l.largest, 3)} (limit ${fmt(l.limit, 3)}), ${fmt(l.moves_beyond, 0)} moves beyond`]);
    for (const w of r.warnings) rows.push(['Warning', w]);
    for (const n of r.notes) rows.push(['Note', n]);
  }
  $('verify-table').replaceChildren(...keyRows(rows));
  $('verify-maps').hidden = !m;
  if (!m) return;
  const [lo, hi] = drawMap($('map-deviation'), m.deviation, m.size, stops);
  $('map-deviation-range').textContent = `${fmt(1000 * lo, 1)} … ${fmt(1000 * hi, 1)} nm`;
}

/** The three largest Fringe Zernike terms, e.g. "Z5 0.4 µm, Z10 −0.25 µm, Z9 0.01 µm". */
function topZernike(z) {
  return z
    .map((v, k) => [k + 1, v])
    .filter(([k, v]) => k > 3 && Math.abs(v) >= 5e-5)
    .sort((a, b) => Math.abs(b[1]) - Math.abs(a[1]))
    .slice(0, 3)
    .map(([k, v]) => `Z${k} ${fmt(v, 4)} µm`)
    .join(', ') || 'none above 0.05 nm';
}

/** The set-up offsets as rows. */
function showOffsets(o) {
  const rows = [];
  if (o.centre_post) rows.push(['Tool height (post)', `${fmt(o.centre_post.tool_height_um, 3)} µm: move the tool ${fmt(o.centre_post.move_tool_um, 3)} µm`]);
  if (o.profile) rows.push(['X offset (W/M profile)', `${fmt(o.profile.x_offset_um, 4)} µm: move X ${fmt(o.profile.move_x_um, 4)} µm`]);
  if (o.radius) {
    rows.push(
      ['Design radius fitted', `${fmt(o.radius.design_radius_mm, 6)} mm`],
      ['X offset (radius)', `${fmt(o.radius.x.x_offset_um, 4)} µm: move X ${fmt(o.radius.x.move_x_um, 4)} µm`],
      ['B-axis Z offset (radius)', `${fmt(o.radius.b_axis_z_offset_um, 4)} µm`],
    );
  }
  $('setup-table').replaceChildren(...keyRows(rows));
}

/** The observations of the set-up panel as `spiralcam setup --params` JSON; empty groups left
 * out. */
function setupParams() {
  const num = (id) => {
    const t = $(id).value.trim();
    return t === '' ? null : Number(t);
  };
  const p = {};
  if (num('setup-post') != null) p.centre_post = { diameter_um: num('setup-post'), shape: $('setup-shape').value };
  if (num('setup-rise') != null) {
    p.profile = { inner_radius_mm: num('setup-r1'), outer_radius_mm: num('setup-r2'), rise_um: num('setup-rise') };
  }
  if (num('setup-radius') != null) p.radius = { measured_mm: num('setup-radius'), aperture_radius_mm: num('setup-aperture') };
  return JSON.stringify(p);
}

/** Five ticks from `hi` (top) to `lo` (bottom), each `label(value)`. */
function legendTicks(lo, hi, label) {
  const n = 5;
  $('legend-ticks').replaceChildren(...Array.from({ length: n }, (_, i) => {
    const v = hi - ((hi - lo) * i) / (n - 1);
    return Object.assign(document.createElement('span'), { textContent: label(v) });
  }));
}

/** The colour legend beside the view: heights in µm. */
function showLegend(zMin, zMax, exaggeration, revolutionStep, passNote = '') {
  legendTicks(zMin, zMax, (z) => `${fmt(z * 1000, 3)} µm`);
  $('legend').setAttribute('aria-label', 'height colour scale');
  $('exaggeration').textContent = `Z × ${fmt(exaggeration, 1)}`;
  $('path-note').textContent = (revolutionStep > 1 ? `path: every ${revolutionStep}th revolution shown` : 'path: every revolution shown') + passNote;
}

/** The colour scale of a verified program's deviation, nm: the last pass's extremes (from
 * every point, not only those drawn), widened to 1 nm when flatter. */
function deviationRange(d) {
  let [lo, hi] = [1000 * d.min, 1000 * d.max];
  if (!(hi - lo >= 1)) [lo, hi] = [(lo + hi) / 2 - 0.5, (lo + hi) / 2 + 0.5];
  return [lo, hi];
}

/** A verified program's last pass in the 3-D view (`trace`: x, y, z mm and deviation µm of
 * every k-th point), coloured by deviation with the legend in nm; returns what was drawn. */
function showProgramPath(viewer, m) {
  const n = m.trace.length / 4;
  const xyz = new Float32Array(3 * n);
  const nm = new Float32Array(n);
  for (let i = 0; i < n; i++) {
    xyz.set(m.trace.subarray(4 * i, 4 * i + 3), 3 * i);
    nm[i] = 1000 * m.trace[4 * i + 3];
  }
  const [lo, hi] = deviationRange(m.report.deviation_um);
  viewer.set_deviation_path(xyz, nm, lo, hi);
  if (!viewer.shows_deviation()) return null;
  legendTicks(lo, hi, (v) => `${fmt(v, 1)} nm`);
  $('legend').setAttribute('aria-label', 'deviation colour scale, nm');
  $('exaggeration').textContent = `Z × ${fmt(viewer.z_exaggeration(), 1)} · colour: deviation`;
  const passes = m.report.pass_count;
  $('path-note').textContent = `program: ${passes > 1 ? `last of ${fmt(passes, 0)} passes` : 'its pass'}, ${fmt(n, 0)} of ${fmt(m.report.deviation_um.points, 0)} cutting points drawn, coloured by deviation from the design (positive: material left)`;
  return { points: n, lo_nm: lo, hi_nm: hi };
}

/** Most passes drawn in the 3-D view. */
const MAX_PASSES_DRAWN = 8;

/** The path drawn once for each pass of a program, raised by the stock the pass leaves (the
 * first and last pass of every group, at most `MAX_PASSES_DRAWN`), and a note saying which. */
function passPaths(path, program) {
  const stocks = [];
  (program?.passes ?? []).forEach((p, i, all) => {
    const edge = i === 0 || i === all.length - 1 || all[i - 1].group !== p.group || all[i + 1].group !== p.group;
    if (edge && p.stock_left_mm > 0 && !stocks.includes(p.stock_left_mm)) stocks.push(p.stock_left_mm);
  });
  if (!stocks.length) return { path, note: '' };
  const drawn = stocks.slice(0, MAX_PASSES_DRAWN - 1);
  const out = new Float32Array(path.length * (drawn.length + 1));
  out.set(path);
  drawn.forEach((stock, k) => {
    const copy = out.subarray(path.length * (k + 1), path.length * (k + 2));
    copy.set(path);
    for (let i = 2; i < copy.length; i += 3) copy[i] += stock;
  });
  const list = drawn.map((s) => fmt(s * 1000, 3)).join(', ');
  return { path: out, note: `; passes drawn raised by their stock left (${list} µm) above the finishing pass` };
}

/** The download buttons say what each file will weigh before it is made: the program's size
 * from the plan, the tables' from the estimate the plan was admitted on. */
function labelDownloads(report) {
  const e = report.estimate ?? {};
  const children = report.program?.children ?? [];
  const all = children.reduce((t, c) => t + c.bytes, report.nc_bytes);
  $('download-nc').textContent = children.length
    ? `Download NC zip (main + ${children.length} children, ${bytes(all)} before compression)`
    : `Download NC (${bytes(report.nc_bytes)})`;
  $('download-csv').textContent = `Download CSV (about ${bytes(e.csv_bytes)})`;
  $('download-fts').textContent = `Download FTS table (about ${bytes(e.fts_table_bytes)})`;
}

/** Saves `data` (bytes or text, or a list of them and Blobs) as the file `name`. */
function download(name, data, type) {
  const url = URL.createObjectURL(new Blob(Array.isArray(data) ? data : [data], { type }));
  const a = Object.assign(document.createElement('a'), { href: url, download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

async function main() {
  await init({ module_or_path: await wasmModule() });
  // The workers load their module while the view starts.
  const worker = new PlannerWorker((kind, done, total, stage) => {
    progress.max = total;
    progress.value = done;
    const writing = { nc: 'writing NC', csv: 'writing CSV', fts: 'writing the FTS table', grid: 'writing the FTS grid' }[kind];
    const what = stage === 'planning' && writing ? writing : stage;
    const items = { 'sampling bands': 'circles', 'concave zones': 'sections and zones', 'FTS grid': 'passes (at most)', 'reading the program': 'moves', verifying: 'moves' }[stage] ?? 'points';
    progressText.textContent = total > 0
      ? `${what}: ${Math.round((100 * done) / total)} % (${fmt(done, 0)} / ${fmt(total, 0)} ${items})`
      : `${what}: ${fmt(done, 0)} ${items}`;
  });
  $('version').textContent = `v${version()}`;
  const scale = colormap_css();
  $('legend-bar').style.background = scale;
  const stops = colormap_stops();
  for (const bar of document.querySelectorAll('.maps .bar')) bar.style.background = scale.replace('to top', 'to right');

  const canvas = $('view');
  let viewer = null;
  let frame = 0;
  const redraw = () => {
    if (!viewer || frame) return;
    frame = requestAnimationFrame(() => {
      frame = 0;
      try {
        viewer.render();
      } catch (e) {
        $('backend').textContent = `render error: ${e.message}`;
      }
    });
  };
  // The view starts while the first job is planned (a plan waits for it before drawing): on a
  // first visit its context and pipelines take about as long as the default job's plan.
  const viewerReady = (async () => {
    try {
      viewer = await Viewer.create(canvas);
      status.backend = viewer.backend();
      $('backend').textContent = status.backend;
      const resize = () => {
        const r = canvas.getBoundingClientRect();
        viewer.resize(r.width, r.height, window.devicePixelRatio || 1);
        redraw();
      };
      new ResizeObserver(resize).observe(canvas);
      resize();
      bindGestures(canvas, viewer, redraw);
    } catch (e) {
      status.backend = 'none';
      $('backend').textContent = 'no 3-D view';
      $('view-message').textContent = `The 3-D view is not available: ${e.message}. Planning and downloads still work.`;
    }
  })();

  const progress = $('progress');
  const progressText = $('progress-text');
  let planned = null;
  /** The plan drawn in the view (its legend), and the verified program drawn over it. */
  let shownPlan = null;
  let verified = null;
  /** Draws the verified program `m` over the surface (while its box is ticked), or the plan's
   * path and height legend when `m` is null. */
  const showProgram = (m) => {
    verified = m;
    $('verify-show').hidden = !m || !viewer;
    status.programDrawn = null;
    if (!viewer) return;
    if (m && $('verify-show-path').checked) status.programDrawn = showProgramPath(viewer, m);
    if (!status.programDrawn) {
      viewer.set_deviation_path(new Float32Array(0), new Float32Array(0), 0, 0);
      if (shownPlan) showLegend(shownPlan.zMin, shownPlan.zMax, viewer.z_exaggeration(), shownPlan.revolutionStep, shownPlan.note);
    }
    redraw();
  };
  let working = false;
  let form = null;
  const busy = (on) => {
    working = on;
    $('busy').hidden = !on;
    freshness();
  };
  /** What you download is what you see: the report, the view and the downloads belong to the
   * job the form shows, or they are marked stale (greyed, naming the job and time they belong
   * to) and the downloads are disabled. */
  const freshness = () => {
    const same = planned && form && JSON.stringify(planned.job) === JSON.stringify(form.value());
    const problem = form?.typedProblem();
    const fresh = Boolean(same && !problem && status.state !== 'planning');
    status.stale = Boolean(planned && !fresh);
    document.querySelector('main').classList.toggle('stale', status.stale);
    for (const b of document.querySelectorAll('[data-needs-plan]')) b.disabled = working || !fresh;
    const note = $('stale');
    note.hidden = !status.stale;
    if (!status.stale) return;
    const why = status.state === 'planning' ? 're-planning the job the form shows…'
      : problem || status.state === 'error' ? 'the form has an error: fix the highlighted field'
        : 'the form has changed since';
    note.textContent = `Stale: the report, the view and the downloads are the plan of “${planned.job.name}” made at ${planned.at.toLocaleTimeString('en-GB')}; ${why}.`;
  };

  form = new JobForm($('job-form'), () => schedule(), JSON.parse(machine_presets()));
  status.formJob = () => form.value();
  const showFailure = (e) => {
    status.error = e.message;
    setState('error');
    const placed = form.showError(e.message);
    $('error').textContent = placed ? 'Fix the highlighted field.' : e.message;
  };

  let generation = 0;
  const plan = async () => {
    const mine = ++generation;
    status.started += 1;
    const job = form.value();
    const typed = form.typedProblem();
    if (typed) {
      worker.cancel();
      showFailure(new Error(typed));
      busy(false);
      return;
    }
    setState('planning');
    status.error = null;
    form.clearErrors();
    $('error').textContent = '';
    progress.removeAttribute('value');
    progressText.textContent = 'planning…';
    busy(true);
    try {
      const started = performance.now();
      const m = await worker.plan(job);
      const seconds = (performance.now() - started) / 1000;
      await viewerReady;
      // A newer plan started while the view was being made: this one is stale.
      if (mine !== generation) return;
      planned = { job, names: m.names, at: new Date() };
      status.report = m.report;
      status.slices = m.slices ?? 0;
      status.plans += 1;
      showReport(m.report, job);
      $('download-fts').hidden = !m.report.dynamics?.split;
      $('download-fts-grid').hidden = !m.report.dynamics?.split;
      labelDownloads(m.report);
      showDynamics(m.report.dynamics, job);
      showMaps(m.maps, stops);
      showAnalysis(null, stops);
      const on = status.slices ? ` in ${status.slices} slices on ${worker.size} workers` : '';
      $('plan-time').textContent = `planned in ${fmt(seconds, 2)} s${on}`;
      if (viewer) {
        viewer.set_surface(m.positions, m.normals, m.indices, m.zMin, m.zMax);
        const drawn = passPaths(m.path, m.report.program);
        viewer.set_path(drawn.path);
        shownPlan = { zMin: m.zMin, zMax: m.zMax, revolutionStep: m.revolutionStep, note: drawn.note };
      }
      showProgram(null);
      setState('done');
    } catch (e) {
      if (mine !== generation) return;
      if (!e.cancelled) showFailure(e);
      else setState('cancelled');
    } finally {
      if (mine === generation) busy(false);
    }
  };

  let timer = 0;
  const schedule = () => {
    freshness();
    clearTimeout(timer);
    timer = setTimeout(plan, 300);
  };

  const save = async (kind) => {
    if (!planned) return;
    generation++;
    if (kind === 'nc' && !(status.report?.program?.children?.length > 0)) {
      saveProgram(planned.names.nc, status.report.nc_bytes);
      return;
    }
    busy(true);
    try {
      const m = await worker.run(kind, planned.job);
      const zipped = kind === 'grid' || (kind === 'nc' && (status.report?.program?.children?.length ?? 0) > 0);
      const name = kind === 'grid' ? `${planned.job.name}-fts-grid.zip` : zipped ? `${planned.job.name}.zip` : { nc: planned.names.nc, csv: planned.names.csv, fts: `${planned.job.name}-fts.csv` }[kind];
      download(name, m.bytes, zipped ? 'application/zip' : kind === 'nc' ? 'text/plain' : 'text/csv');
    } catch (e) {
      if (!e.cancelled) showFailure(e);
    } finally {
      busy(false);
    }
  };

  /** The program, written in slices by every worker straight into the file where the browser
   * lets the page write one (the File System Access API, for programs past
   * `status.streamAbove` bytes: the save dialog comes first), else into a Blob built from the
   * slices' texts; in one piece by one worker for a job that is not sliced. Either way the
   * page never holds the whole text in its own memory twice. */
  const saveProgram = async (name, size) => {
    let file = null;
    busy(true);
    try {
      if (window.showSaveFilePicker && size > status.streamAbove) {
        const handle = await window.showSaveFilePicker({ suggestedName: name });
        file = await handle.createWritable();
      }
      const parts = [];
      let slices = 0;
      const sliced = await worker.program(planned.job, (bytes) => {
        slices += 1;
        return file ? file.write(bytes) : parts.push(new Blob([bytes]));
      });
      if (!sliced) {
        const { bytes } = await worker.run('nc', planned.job);
        if (file) await file.write(bytes);
        else parts.push(bytes);
      }
      if (file) await file.close();
      else download(name, parts, 'text/plain');
      status.saved = { name, streamed: Boolean(file), slices };
    } catch (e) {
      await file?.abort();
      if (!e.cancelled && e.name !== 'AbortError') showFailure(e);
    } finally {
      busy(false);
    }
  };

  $('cancel').addEventListener('click', () => worker.cancel());
  const analyse = async () => {
    if (!planned) return;
    generation++;
    setState('analysing');
    busy(true);
    try {
      const started = performance.now();
      const m = await worker.run('analyse', planned.job);
      showAnalysis(m, stops);
      $('plan-time').textContent = `analysed in ${fmt((performance.now() - started) / 1000, 2)} s`;
      status.analysis = m.report;
      setState('analysed');
    } catch (e) {
      if (!e.cancelled) showFailure(e);
      else setState('cancelled');
    } finally {
      busy(false);
    }
  };
  $('analyse').addEventListener('click', analyse);

  let corrected = null;
  let correctedNc = '';
  const runCorrection = async () => {
    const file = $('measured-file').files[0];
    if (!file) return;
    generation++;
    setState('correcting');
    busy(true);
    $('correction-error').textContent = '';
    try {
      const started = performance.now();
      const options = {
        kind: $('measured-kind').value,
        gain: Number($('measured-gain').value),
        register: $('measured-register').value,
        rotate_deg: Number($('measured-rotate').value),
        mirror: $('measured-mirror').value,
      };
      const bytes = new Uint8Array(await file.arrayBuffer());
      const m = await worker.run('correct', form.value(), { name: file.name, bytes, options });
      corrected = m.job;
      correctedNc = m.ncName;
      showCorrection(m, stops);
      $('plan-time').textContent = `corrected in ${fmt((performance.now() - started) / 1000, 2)} s`;
      status.correction = m.report;
      setState('corrected');
    } catch (e) {
      showCorrection(null, stops);
      corrected = null;
      if (!e.cancelled) {
        $('correction-error').textContent = e.message;
        status.error = e.message;
        setState('error');
      } else setState('cancelled');
    } finally {
      busy(false);
    }
  };
  $('nc-file').addEventListener('change', async () => {
    const files = [...$('nc-file').files];
    if (!files.length) return;
    generation++;
    setState('verifying');
    busy(true);
    $('verify-error').textContent = '';
    try {
      const started = performance.now();
      // The first file chosen is the main program; the others are where its children are
      // looked for, by name.
      const texts = await Promise.all(files.map((f) => f.text()));
      const extra = { name: files[0].name, text: texts[0], names: files.slice(1).map((f) => f.name), texts: texts.slice(1) };
      const m = await worker.run('verify', form.value(), extra);
      showVerification(m, stops);
      showProgram(m);
      $('plan-time').textContent = `verified in ${fmt((performance.now() - started) / 1000, 2)} s`;
      status.verification = m.report;
      setState('verified');
    } catch (e) {
      showVerification(null, stops);
      showProgram(null);
      if (!e.cancelled) {
        $('verify-error').textContent = e.message;
        status.error = e.message;
        setState('error');
      } else setState('cancelled');
    } finally {
      busy(false);
      $('nc-file').value = '';
    }
  });
  $('verify-show-path').addEventListener('change', () => showProgram(verified));
  $('measured-file').addEventListener('change', runCorrection);
  $('correct').addEventListener('click', runCorrection);
  $('download-corrected').addEventListener('click', () => {
    if (corrected) download(`${corrected.name}.json`, `${JSON.stringify(corrected, null, 2)}\n`, 'application/json');
  });
  $('download-corrected-nc').addEventListener('click', async () => {
    if (!corrected) return;
    generation++;
    busy(true);
    try {
      const m = await worker.run('nc', corrected);
      download(correctedNc, m.bytes, 'text/plain');
    } catch (e) {
      if (!e.cancelled) $('correction-error').textContent = e.message;
    } finally {
      busy(false);
    }
  });
  $('setup-run').addEventListener('click', async () => {
    $('setup-error').textContent = '';
    try {
      const m = await worker.run('setup', form.value(), setupParams());
      showOffsets(m.offsets);
    } catch (e) {
      $('setup-table').replaceChildren();
      if (!e.cancelled) $('setup-error').textContent = e.message;
    }
  });
  $('download-nc').addEventListener('click', () => save('nc'));
  $('download-csv').addEventListener('click', () => save('csv'));
  $('download-fts').addEventListener('click', () => save('fts'));
  $('download-fts-grid').addEventListener('click', () => save('grid'));
  $('download-job').addEventListener('click', () => {
    const job = { format: FORMAT, ...form.value() };
    download(`${job.name}.json`, `${JSON.stringify(job, null, 2)}\n`, 'application/json');
  });

  /** Shows `job` from `where` in the form and plans it; a job the form cannot show (no JSON
   * object of a job, a newer format) leaves the default job in the form, not planned, with the
   * core's message naming the field. */
  const openJob = async (job, where) => {
    const refuse = (message) => {
      form.show(JSON.parse(default_job()));
      status.error = `${where}: ${message}`;
      setState('error');
      $('error').textContent = `${status.error}\nThe form shows the default job, not planned.`;
    };
    const problem = formatProblem(job);
    if (problem) return refuse(problem);
    try {
      form.show(job);
    } catch {
      const message = await worker.run('plan', job).then(() => 'the form cannot show it', (e) => e.message);
      return refuse(message);
    }
    $('import-listing').hidden = true;
    const missing = dataFiles(job).filter((f) => f.file.text === undefined && f.file.path);
    $('share-note').textContent = missing.map((f) => `${where} leaves out the data file ${f.file.path}: choose it in the field ${f.field}.`).join(' ');
    return plan();
  };
  $('upload-job').addEventListener('change', async (e) => {
    const file = e.target.files[0];
    if (!file) return;
    try {
      await openJob(JSON.parse(await file.text()), file.name);
    } catch (err) {
      showFailure(new Error(`${file.name}: ${err.message}`));
    }
    e.target.value = '';
  });

  $('share').addEventListener('click', async () => {
    const { url, left } = await shareLink(form.value(), `${location.origin}${location.pathname}`);
    status.link = { url, left };
    let copied = false;
    try {
      await navigator.clipboard.writeText(url);
      copied = true;
    } catch {
      // No clipboard (an insecure origin, a denied permission): the link is shown to copy.
    }
    const field = $('share-url');
    field.value = url;
    field.hidden = false;
    field.select();
    const send = left.length ? ` It leaves out ${left.map((f) => f.name).join(', ')} (too large for a link): send ${left.length > 1 ? 'them' : 'it'} beside the link.` : '';
    $('share-note').textContent = `${copied ? 'Link copied' : 'Copy the link below'} (${url.length.toLocaleString('en-US')} characters).${send}`;
  });

  bindImport((job, listing) => {
    form.show(job);
    status.imported = listing;
    const shown = $('import-listing');
    shown.textContent = listing.join('\n');
    shown.hidden = false;
    schedule();
  });

  /** The job the address carries (`#job=…` or `?job=URL`), else the default job. */
  const openLocation = async () => {
    let carried;
    try {
      carried = await jobFromLocation();
    } catch (e) {
      form.show(JSON.parse(default_job()));
      status.error = e.message;
      setState('error');
      $('error').textContent = `The link cannot be opened: ${e.message}.\nThe form shows the default job, not planned.`;
      return;
    }
    if (!carried) {
      form.show(JSON.parse(default_job()));
      await plan();
      return;
    }
    await openJob(carried.job, carried.source === 'link' ? 'the link' : carried.source);
  };
  window.addEventListener('hashchange', openLocation);
  await openLocation();
  // The offline copy (the service worker fetching every file) waits for the first plan, so it
  // does not share the cores with it.
  offlineCopy(status, (text) => {
    $('offline').textContent = text;
    $('offline').hidden = false;
  });
}

const started = new URLSearchParams(location.search).has('embed') ? import('./embed-page.js').then((m) => m.startEmbed()) : main();
started.catch((e) => {
  status.error = String(e.message || e);
  setState('error');
  document.getElementById('error').textContent = `The page failed to start: ${status.error}`;
});
