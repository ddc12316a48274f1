// Shared pieces of the browser tests: the page's own server (web/serve.py on a free loopback
// port), Debian's Chromium driven by playwright-core with either the WebGPU flags of DESIGN.md
// or none (WebGL2 fallback through SwiftShader), pixel readback of the canvas, and the
// command-line tool for byte-for-byte comparisons.

import { spawn, execFileSync } from 'node:child_process';
import { createServer } from 'node:net';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';
import { PNG } from 'pngjs';

export const ROOT = new URL('../../', import.meta.url).pathname;

const BASE_ARGS = [
  '--no-sandbox',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

/** Chromium flags per backend: WebGPU on SwiftShader's Vulkan, or nothing (WebGL2 fallback). */
export const BACKENDS = {
  WebGPU: [...BASE_ARGS, '--enable-unsafe-webgpu', '--enable-features=Vulkan', '--use-vulkan=swiftshader', '--use-angle=swiftshader'],
  WebGL2: BASE_ARGS,
};

function freePort() {
  return new Promise((resolve, reject) => {
    const s = createServer();
    s.once('error', reject);
    s.listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}

/** Starts the page's server; resolves to { url, stop }. */
export async function startServer() {
  const port = await freePort();
  const proc = spawn('python3', [join(ROOT, 'web/serve.py'), String(port)], {
    env: { ...process.env, SPIRALCAM_QUIET: '1' },
    stdio: ['ignore', 'pipe', 'inherit'],
  });
  await new Promise((resolve, reject) => {
    proc.once('error', reject);
    proc.once('exit', (code) => reject(new Error(`web/serve.py exited with ${code}`)));
    proc.stdout.once('data', resolve);
  });
  return { url: `http://127.0.0.1:${port}/`, stop: () => proc.kill() };
}

/** A browser for one backend, with downloads enabled. */
export async function launch(backend) {
  const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', headless: true, args: BACKENDS[backend] });
  const context = await browser.newContext({ acceptDownloads: true, viewport: { width: 1400, height: 860 } });
  return { browser, context };
}

/** Opens the page, records every request, and waits for the default job to be planned. */
export async function openPage(context, url) {
  const page = await context.newPage();
  const requests = [];
  const errors = [];
  page.on('request', (r) => requests.push(r.url()));
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(url);
  await waitForState(page, ['done']);
  return { page, requests, errors };
}

/** Waits until the page's state is one of `states`; throws with the page's error otherwise. */
export async function waitForState(page, states, timeout = 120_000) {
  await page.waitForFunction((s) => s.includes(document.body.dataset.state) || document.body.dataset.state === 'error', states, { timeout });
  const state = await page.evaluate(() => document.body.dataset.state);
  if (!states.includes(state)) {
    const error = await page.evaluate(() => window.spiralcam.error);
    throw new Error(`page state ${state}: ${error}`);
  }
}

/** Runs `action` (an edit), waits for the re-plan it starts, then for one of the `settle`
 * states. */
export async function replan(page, action, settle = ['done']) {
  const started = await page.evaluate(() => window.spiralcam.started);
  await action();
  await page.waitForFunction((n) => window.spiralcam.started > n, started, { timeout: 10_000 });
  await waitForState(page, settle);
}

/** Opens `job` through the page's "Open job…" (from a file named after it) and waits for its
 * plan. */
export async function openJob(page, job) {
  const dir = mkdtempSync(join(tmpdir(), 'spiralcam-open-'));
  const path = join(dir, `${job.name}.json`);
  writeFileSync(path, JSON.stringify(job));
  await replan(page, () => page.setInputFiles('#upload-job', path));
}

/** Types `text` into the job field at `path` and waits as [`replan`] does. */
export async function setField(page, path, text, settle = ['done']) {
  await replan(page, () => page.fill(`[data-field="${path}"]`, text), settle);
}

/** The canvas as RGBA pixels: { width, height, data }. */
export async function canvasPixels(page) {
  // Let the render loop draw the latest frame before reading back.
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const png = await page.locator('#view').screenshot();
  return PNG.sync.read(png);
}

/** Share of pixels differing from the clear colour, and the number of distinct colours. */
export function pixelStats({ data }, clear = [0x1e, 0x1f, 0x24]) {
  let differ = 0;
  const colours = new Set();
  const n = data.length / 4;
  for (let i = 0; i < data.length; i += 4) {
    const d = Math.abs(data[i] - clear[0]) + Math.abs(data[i + 1] - clear[1]) + Math.abs(data[i + 2] - clear[2]);
    if (d > 24) differ++;
    colours.add((data[i] >> 3) * 1024 + (data[i + 1] >> 3) * 32 + (data[i + 2] >> 3));
  }
  return { covered: differ / n, colours: colours.size };
}

/** Clicks `selector` and returns the downloaded file's name and bytes. */
export async function download(page, selector) {
  const [d] = await Promise.all([page.waitForEvent('download', { timeout: 120_000 }), page.click(selector)]);
  const path = await d.path();
  return { name: d.suggestedFilename(), bytes: readFileSync(path) };
}

let cli = null;
/** The command-line tool's path, built on first use in the workspace's `cli-test` profile
 * (optimised, quick to build: the examples plan in seconds, not minutes as in a debug build). */
export function spiralcamCli() {
  if (!cli) {
    execFileSync('cargo', ['build', '--quiet', '--locked', '-p', 'spiralcam', '--bin', 'spiralcam', '--profile', 'cli-test'], { cwd: ROOT, stdio: 'inherit' });
    cli = join(ROOT, 'target/cli-test/spiralcam');
  }
  return cli;
}

/** Runs `spiralcam plan JOB --nc … --csv …` and returns { nc, csv } as Buffers; with `fts`
 * (a split job) also `--fts-csv …`, returned as `fts`. */
export function planWithCli(jobPath, { fts = false } = {}) {
  spiralcamCli();
  const dir = mkdtempSync(join(tmpdir(), 'spiralcam-cli-'));
  const nc = join(dir, 'out.nc');
  const csv = join(dir, 'out.csv');
  const ftsCsv = join(dir, 'out-fts.csv');
  const args = ['plan', jobPath, '--nc', nc, '--csv', csv, '--report', join(dir, 'report.json')];
  execFileSync(cli, fts ? [...args, '--fts-csv', ftsCsv] : args);
  return { nc: readFileSync(nc), csv: readFileSync(csv), fts: fts ? readFileSync(ftsCsv) : null, dir };
}
