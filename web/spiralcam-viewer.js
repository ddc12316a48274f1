// <spiralcam-viewer>: the 3-D surface and spiral of one job, its key figures, optional controls
// that re-plan as they move, a Download NC button and a link "Open in spiralcam" carrying the
// job, for documentation pages (README, "Embed the viewer"). A page adds
//
//   <script type="module" src="…/web/spiralcam-viewer.js"></script>
//   <spiralcam-viewer src="jobs/lens-array.json" controls="feed_mm_per_rev"></spiralcam-viewer>
//
// Attributes: `src` (a job JSON on the same site, data files beside it as with ?job=), `job`
// (a link's fragment, `job=…` as "Copy link" makes it), `controls` (job fields, by their last
// name or full path, each a slider and a field), `downloads="none"`, `max-points` (the most
// points planned in the box, default MAX_POINTS), `app` (the page "Open in spiralcam" opens,
// default the index.html beside web/). Every viewer of a page shares one wasm module, one
// planning worker and, on WebGPU, one GPU device with its pipelines; a viewer creates its GPU
// context when it first comes into view, draws only while visible (IntersectionObserver) and
// gives the context back when it leaves the document (browsers keep about 16 live WebGL
// contexts a page). Every failure (a src that 404s or is not
// JSON, a bad fragment, an invalid job, a job too large) is a message in the box, never a
// blank box or an uncaught error. `spiralcam:planned` events carry each report.

import init, { Viewer } from '../pkg/spiralcam_web.js';
import { bindGestures } from './gestures.js';
import { LinkError, jobFragment, jobFromFragment, jobFromUrl, formatProblem } from './share.js';

/** The most points a viewer plans unless `max-points` says otherwise: a page of several
 * viewers stays quick; a larger job is offered in the full page. */
export const MAX_POINTS = 1_000_000;

/** What the shared module holds: the wasm instantiations started (one per page) and the
 * viewers made and released, for hosts and tests. */
export const shared = { instantiations: 0, contexts: 0, released: 0, worker: null, ready: null };

/** The page's one wasm instance for the viewers' GPU side. */
function wasm() {
  if (!shared.ready) {
    shared.instantiations += 1;
    shared.ready = init();
  }
  return shared.ready;
}

/** The one planning worker of every viewer on the page: requests answered in order by id. */
function plan(job, onProgress) {
  if (!shared.worker) {
    const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    shared.worker = { worker, next: 1, pending: new Map() };
    worker.onmessage = (e) => {
      const m = e.data;
      const p = shared.worker.pending.get(m.id);
      if (!p) return;
      if (m.kind === 'progress') return p.onProgress?.(m.done, m.total, m.stage);
      shared.worker.pending.delete(m.id);
      if (m.kind === 'error') p.reject(new Error(m.message));
      else p.resolve(m);
    };
    worker.onerror = (e) => {
      for (const p of shared.worker.pending.values()) p.reject(new Error(`worker: ${e.message}`));
      shared.worker.pending.clear();
    };
  }
  const w = shared.worker;
  const id = w.next++;
  return new Promise((resolve, reject) => {
    w.pending.set(id, { resolve, reject, onProgress });
    w.worker.postMessage({ id, kind: 'plan', job });
  });
}

/** The NC program of `job` from the shared worker. */
function ncProgram(job) {
  const w = shared.worker;
  const id = w.next++;
  return new Promise((resolve, reject) => {
    w.pending.set(id, { resolve, reject });
    w.worker.postMessage({ id, kind: 'nc', job });
  });
}

/** The points a job will plan, estimated from its sampling before planning (null: the
 * sampling sets them as it goes, HCAA and adaptive). */
export function estimatePoints(job) {
  const s = job.strategy ?? {};
  const radius = s.outer_radius_mm ?? job.part?.diameter_mm / 2;
  const revs = (radius + (s.overtravel_mm ?? 0)) / s.feed_mm_per_rev;
  const sampling = s.sampling ?? {};
  if (sampling.points_per_rev) return revs * sampling.points_per_rev;
  if (sampling.type === 'constant_arc') {
    // Σ 2πρ/ΔS over the turns ≈ πR²/(f ΔS), at least the angle cap's points per turn.
    return Math.max((Math.PI * radius * radius) / (s.feed_mm_per_rev * sampling.arc_length_mm), revs * 2);
  }
  return null;
}

/** A job field named by `name`: its full path if it is one, else the first path in the job
 * ending in `.name`. */
function findField(job, name) {
  const get = (path) => path.split('.').reduce((o, k) => (o == null ? undefined : o[k]), job);
  if (typeof get(name) === 'number') return name;
  const walk = (o, prefix) => {
    for (const [k, v] of Object.entries(o ?? {})) {
      const path = prefix ? `${prefix}.${k}` : k;
      if (k === name && typeof v === 'number') return path;
      if (v && typeof v === 'object' && !Array.isArray(v)) {
        const found = walk(v, path);
        if (found) return found;
      }
    }
    return null;
  };
  return walk(job, '');
}

function setPath(job, path, value) {
  const keys = path.split('.');
  const last = keys.pop();
  keys.reduce((o, k) => o[k], job)[last] = value;
}

const fmt = (v, digits = 3) => (Number.isFinite(v) ? v.toLocaleString('en-US', { maximumFractionDigits: digits }) : '–');

function duration(s) {
  const m = Math.floor(s / 60);
  return m >= 60 ? `${Math.floor(m / 60)} h ${m % 60} min` : `${m} min ${(s - 60 * m).toFixed(1)} s`;
}

const STYLE = `
:host { display: block; position: relative; min-height: 240px; height: 420px; font: 13px/1.4 system-ui, sans-serif;
  color: #1d2330; background: #fff; border: 1px solid #dde1e7; border-radius: 6px; overflow: hidden;
  --view: #1e1f24; }
@media (prefers-color-scheme: dark) { :host { color: #e6e8ee; background: #16181d; border-color: #333842; } }
.box { display: grid; grid-template-rows: minmax(0, 1fr) auto; height: 100%; }
.view { position: relative; background: var(--view); min-height: 0; }
canvas { width: 100%; height: 100%; display: block; touch-action: none; }
.message { position: absolute; inset: 0; display: flex; align-items: center; justify-content: center; padding: 16px;
  text-align: center; color: #fff; margin: 0; white-space: pre-wrap; }
.message:empty { display: none; }
.message.error { background: rgba(60, 10, 10, 0.85); }
.figures { display: flex; flex-wrap: wrap; gap: 2px 14px; padding: 6px 10px; margin: 0; list-style: none; }
.figures b { font-weight: 600; }
.warnings { color: #9a5b00; padding: 0 10px 4px 26px; margin: 0; font-size: 12px; }
@media (prefers-color-scheme: dark) { .warnings { color: #f0b75a; } }
.warnings:empty { display: none; }
.bar { display: flex; flex-wrap: wrap; align-items: center; gap: 6px 12px; padding: 6px 10px; border-top: 1px solid rgba(128, 128, 128, 0.25); }
.bar label { display: flex; align-items: center; gap: 6px; }
.bar input[type="number"] { width: 7em; font: inherit; }
.spacer { flex: 1; }
button, a.open { font: inherit; padding: 4px 10px; border-radius: 4px; border: 1px solid #1f6feb; cursor: pointer; text-decoration: none; }
button { background: #1f6feb; color: #fff; }
button:disabled { opacity: 0.5; cursor: default; }
a.open { color: #1f6feb; background: transparent; }
.stale canvas { filter: grayscale(0.9) brightness(0.6); }
.stale .figures { opacity: 0.45; }
`;

/** The element. */
export class SpiralcamViewer extends HTMLElement {
  static observedAttributes = ['src', 'job', 'controls', 'downloads', 'max-points'];

  constructor() {
    super();
    const root = this.attachShadow({ mode: 'open' });
    root.innerHTML = `<style>${STYLE}</style>
      <div class="box" part="box">
        <div class="view"><canvas part="canvas" aria-label="3-D view of the surface and the tool path"></canvas><p class="message" role="status"></p></div>
        <div class="info"><ul class="figures"></ul><ul class="warnings"></ul>
          <div class="bar"><span class="controls"></span><span class="spacer"></span>
            <button type="button" class="nc" disabled>Download NC</button>
            <a class="open" target="_blank" rel="noopener">Open in spiralcam</a></div></div>
      </div>`;
    this.$ = (sel) => root.querySelector(sel);
    this.canvas = this.$('canvas');
    this.state = 'idle';
    this.job = null;
    this.report = null;
    this.generation = 0;
    this.visible = false;
    this.viewer = null;
    this.frame = 0;
    this.$('.nc').addEventListener('click', () => this.downloadNc());
    this.bindCanvas();
  }

  /** Gestures on the canvas act on whichever viewer is live. */
  bindCanvas() {
    const camera = {
      orbit: (dx, dy) => this.viewer?.orbit(dx, dy),
      pan: (dx, dy) => this.viewer?.pan(dx, dy),
      zoom: (f) => this.viewer?.zoom(f),
      reset_view: () => this.viewer?.reset_view(),
    };
    bindGestures(this.canvas, camera, () => this.redraw());
  }

  connectedCallback() {
    this.connectedAt = performance.now();
    this.observer = new IntersectionObserver((entries) => {
      this.visible = entries[entries.length - 1].isIntersecting;
      if (this.visible) this.ensureViewer().then(() => this.redraw());
    });
    this.observer.observe(this);
    this.resizer = new ResizeObserver(() => this.resize());
    this.resizer.observe(this.canvas);
    if (!this.job && !this.loading) this.load();
  }

  disconnectedCallback() {
    this.observer?.disconnect();
    this.resizer?.disconnect();
    this.release();
  }

  attributeChangedCallback(name, old, value) {
    if (old === value || !this.isConnected) return;
    if (name === 'src' || name === 'job') this.load();
    else if (name === 'controls') this.showControls();
    else if (name === 'downloads') this.$('.nc').hidden = value === 'none';
    else if (name === 'max-points' && this.job) this.planJob();
  }

  /** Loads the job the attributes name and plans it. */
  async load() {
    this.loading = true;
    this.$('.nc').hidden = this.getAttribute('downloads') === 'none';
    this.say('loading…');
    try {
      const src = this.getAttribute('src');
      const fragment = this.getAttribute('job');
      let job;
      if (fragment) job = await jobFromFragment(fragment.replace(/^.*#/, '').replace(/^(job=)?/, 'job='));
      else if (src) job = await jobFromUrl(src, document.baseURI);
      else throw new LinkError('no job: give the element a src="…json" or job="job=…" attribute');
      this.setJob(job);
    } catch (e) {
      this.fail(e.message);
    } finally {
      this.loading = false;
    }
  }

  /** Shows and plans `job` (a job object as in the job JSON). */
  setJob(job) {
    const problem = formatProblem(job);
    if (problem) {
      this.fail(problem);
      return;
    }
    this.job = structuredClone(job);
    this.showControls();
    this.planJob();
  }

  /** The job as it stands (with the controls' values). */
  currentJob() {
    return structuredClone(this.job);
  }

  async planJob() {
    const mine = ++this.generation;
    const job = this.currentJob();
    this.setAttribute('state', 'planning');
    this.state = 'planning';
    this.$('.nc').disabled = true;
    this.$('.box').classList.toggle('stale', Boolean(this.report));
    const linked = this.updateOpenLink(job);
    const limit = Number(this.getAttribute('max-points')) || MAX_POINTS;
    const estimate = estimatePoints(job);
    if (estimate > limit) {
      // The message offers the full page: its link is written before the state says so.
      await linked;
      if (mine !== this.generation) return;
      this.fail(`This job plans about ${fmt(estimate, 0)} points, more than the ${fmt(limit, 0)} this viewer plans.\nOpen it in spiralcam to plan it in full.`, 'too-large');
      return;
    }
    if (!this.report) this.say('planning…');
    try {
      const m = await plan(job, (done, total, stage) => {
        if (mine === this.generation && !this.report) this.say(`${stage}: ${Math.round((100 * done) / Math.max(total, 1))} %`);
      });
      if (mine !== this.generation) return;
      if (m.report.points > limit) {
        this.fail(`This job has ${fmt(m.report.points, 0)} points, more than the ${fmt(limit, 0)} this viewer shows.\nOpen it in spiralcam to see it in full.`, 'too-large');
        return;
      }
      this.report = m.report;
      this.planned = { job, m };
      this.showFigures(m.report);
      this.say('');
      await this.ensureViewer();
      if (mine !== this.generation) return;
      this.upload();
      this.$('.nc').disabled = false;
      this.$('.box').classList.remove('stale');
      this.state = 'done';
      this.setAttribute('state', 'done');
      this.dispatchEvent(new CustomEvent('spiralcam:planned', { detail: { report: m.report }, bubbles: true, composed: true }));
    } catch (e) {
      if (mine === this.generation) this.fail(e.message);
    }
  }

  /** The 3-D view, made on first sight; null where the browser has no WebGPU or WebGL2. */
  async ensureViewer() {
    if (this.viewer || this.viewerFailed || !this.isConnected || !this.visible) return this.viewer;
    if (!this.creating) {
      this.creating = (async () => {
        await wasm();
        this.resizeCanvas();
        try {
          const v = await Viewer.create(this.canvas);
          if (!this.isConnected) {
            v.free();
            return;
          }
          this.viewer = v;
          shared.contexts += 1;
          this.backend = v.backend();
          this.setAttribute('backend', this.backend);
          this.resize();
          this.upload();
        } catch (e) {
          this.viewerFailed = true;
          this.setAttribute('backend', 'none');
          this.say(`The 3-D view is not available here: ${e.message}`);
        } finally {
          this.creating = null;
        }
      })();
    }
    await this.creating;
    return this.viewer;
  }

  /** The planned mesh and path into the viewer. */
  upload() {
    if (!this.viewer || !this.planned) return;
    const { m } = this.planned;
    this.viewer.set_surface(m.positions, m.normals, m.indices, m.zMin, m.zMax);
    this.viewer.set_path(m.path);
    this.uploaded = true;
    this.redraw();
  }

  resizeCanvas() {
    const r = this.canvas.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    this.canvas.width = Math.max(1, Math.round(r.width * dpr));
    this.canvas.height = Math.max(1, Math.round(r.height * dpr));
  }

  resize() {
    if (!this.viewer) return;
    const r = this.canvas.getBoundingClientRect();
    if (r.width < 1 || r.height < 1) return;
    this.viewer.resize(r.width, r.height, window.devicePixelRatio || 1);
    this.redraw();
  }

  redraw() {
    if (!this.viewer || this.frame || !this.visible) return;
    this.frame = requestAnimationFrame(() => {
      this.frame = 0;
      if (!this.viewer || !this.visible) return;
      try {
        this.viewer.render();
        if (!this.firstFrameMs && this.uploaded) {
          this.firstFrameMs = performance.now() - this.connectedAt;
          this.setAttribute('first-frame-ms', this.firstFrameMs.toFixed(0));
        }
      } catch (e) {
        this.say(`render error: ${e.message}`);
      }
    });
  }

  /** Gives the GPU context back: the viewer freed (its buffers, and with the page's last viewer
   * the WebGPU device) and its canvas's context lost (WebGL2) or unconfigured (WebGPU) now
   * rather than when the canvas is collected. */
  release() {
    if (this.frame) cancelAnimationFrame(this.frame);
    this.frame = 0;
    if (!this.viewer) return;
    this.viewer.free();
    this.viewer = null;
    shared.released += 1;
    if (this.backend === 'WebGL2') this.canvas.getContext('webgl2')?.getExtension('WEBGL_lose_context')?.loseContext();
    // The page's WebGPU device outlives this canvas: let go of the canvas's configuration.
    else if (this.backend === 'WebGPU') this.canvas.getContext('webgpu')?.unconfigure();
    // A fresh canvas for the next time the element is connected: a lost context stays lost.
    const canvas = this.canvas.cloneNode();
    this.canvas.replaceWith(canvas);
    this.canvas = canvas;
    this.bindCanvas();
    this.resizer?.observe(canvas);
  }

  showFigures(r) {
    const stroke = r.dynamics?.axes?.fts_stroke?.used_um ?? r.dynamics?.split?.w_fts_pv_um;
    const rows = [
      ['points', fmt(r.points, 0)],
      ['cycle time', duration(r.cycle_time_s)],
      ['surface PV', `${fmt(r.surface_pv_um, 3)} µm`],
      ['servo stroke', stroke == null ? 'no servo' : `${fmt(stroke, 3)} µm`],
    ];
    this.$('.figures').replaceChildren(...rows.map(([k, v]) => {
      const li = document.createElement('li');
      li.dataset.key = k;
      li.append(`${k} `, Object.assign(document.createElement('b'), { textContent: v }));
      return li;
    }));
    this.$('.warnings').replaceChildren(...r.warnings.map((w) => Object.assign(document.createElement('li'), { textContent: w })));
  }

  /** A slider and a field for each job field `controls` names. */
  showControls() {
    const box = this.$('.controls');
    box.replaceChildren();
    if (!this.job) return;
    const names = (this.getAttribute('controls') ?? '').split(',').map((n) => n.trim()).filter(Boolean);
    for (const name of names) {
      const path = findField(this.job, name);
      if (!path) {
        box.append(Object.assign(document.createElement('span'), { textContent: `${name}: no such number in the job` }));
        continue;
      }
      const value = path.split('.').reduce((o, k) => o[k], this.job);
      const field = Object.assign(document.createElement('input'), { type: 'number', step: 'any', value: String(value) });
      const slider = Object.assign(document.createElement('input'), { type: 'range', min: String(value / 4), max: String(value * 4), step: String(value / 100), value: String(value) });
      for (const c of [field, slider]) c.dataset.field = path;
      let timer = 0;
      const changed = (text, from) => {
        const v = Number(text);
        if (from !== field) field.value = text;
        if (from !== slider) slider.value = text;
        if (!Number.isFinite(v) || text.trim() === '') return;
        setPath(this.job, path, v);
        this.$('.box').classList.add('stale');
        this.$('.nc').disabled = true;
        clearTimeout(timer);
        timer = setTimeout(() => this.planJob(), 150);
      };
      field.addEventListener('input', () => changed(field.value, field));
      slider.addEventListener('input', () => changed(slider.value, slider));
      const label = document.createElement('label');
      label.append(name.replaceAll('_', ' '), slider, field);
      box.append(label);
    }
  }

  async updateOpenLink(job) {
    const app = new URL(this.getAttribute('app') ?? '../index.html', import.meta.url);
    this.$('.open').href = `${app.href}#${await jobFragment(job)}`;
  }

  async downloadNc() {
    if (!this.planned || this.state !== 'done') return;
    const { job } = this.planned;
    const m = await ncProgram(job);
    const url = URL.createObjectURL(new Blob([m.bytes], { type: 'text/plain' }));
    const a = Object.assign(document.createElement('a'), { href: url, download: this.planned.m.names.nc });
    this.shadowRoot.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10_000);
  }

  say(text) {
    const p = this.$('.message');
    p.classList.remove('error');
    p.textContent = text;
  }

  /** A message in the box instead of the view; `kind` "error" or "too-large". */
  fail(message, kind = 'error') {
    this.state = kind;
    this.setAttribute('state', kind);
    this.error = message;
    this.$('.nc').disabled = true;
    const p = this.$('.message');
    p.textContent = message;
    p.classList.add('error');
    if (this.job) this.updateOpenLink(this.currentJob());
    this.dispatchEvent(new CustomEvent('spiralcam:error', { detail: { message }, bubbles: true, composed: true }));
  }
}

if (!customElements.get('spiralcam-viewer')) customElements.define('spiralcam-viewer', SpiralcamViewer);
