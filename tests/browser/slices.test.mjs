// The page on every core (issue 16): a long path is planned in slices, one Web Worker per core,
// joined in order into the command line's report, and its program is written in slices into a
// file (the File System Access API, stubbed here with a writer that keeps the chunks) or into a
// Blob built from them; either way byte for byte the command line's program. A program that is
// not sliced (a space spiral) goes into the file too. A cancel while the slices run leaves the
// page cancelled.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { createHash } from 'node:crypto';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { download, launch, openJob, openPage, planWithCli, startServer, waitForState } from './harness.mjs';

/** Paper 004's lens array on a Ø8 part at 1000 points a revolution: 400 001 points, past the
 * page's threshold for slices; Moore-style, whose F words are modal. */
const JOB = {
  name: 'sliced-lens-array',
  part: { diameter_mm: 8.0 },
  surface: { type: 'lens_array', lens_radius_mm: 2.84, aperture_mm: 1.0, pitch_mm: 1.0, grid: 'rectangular', form: 'concave' },
  tool: { nose_radius_mm: 0.5, included_angle_deg: 100.0 },
  machine: { spindle_rpm: 800.0 },
  strategy: { feed_mm_per_rev: 0.01, sampling: { type: 'constant_arc', arc_length_mm: 0.02, max_angle_step_deg: 0.5 } },
  output: { dialect: 'moore' },
};

/** Slices of the program: 65 536 points each (web/app.js PROGRAM_SLICE). */
const programSlices = () => Math.ceil(cli.report.points / 65_536);

const sha256 = (bytes) => createHash('sha256').update(bytes).digest('hex');

/** The report without the cost estimate (the command line's has a clock, the page's none). */
const figures = (report) => JSON.stringify({ ...report, estimate: null });

let server;
let browser;
let page;
let cli;
before(async () => {
  server = await startServer();
  const dir = mkdtempSync(join(tmpdir(), 'spiralcam-slices-'));
  const path = join(dir, `${JOB.name}.json`);
  writeFileSync(path, JSON.stringify(JOB));
  cli = planWithCli(path);
  cli.report = JSON.parse(readFileSync(join(cli.dir, 'report.json'), 'utf8'));
  let context;
  ({ browser, context } = await launch('WebGL2'));
  ({ page } = await openPage(context, server.url));
});
after(async () => {
  await browser.close();
  server.stop();
});

/** Saves the page's program through a stubbed save dialog whose writer keeps the chunks (Blobs
 * or bytes, as the page writes them); returns its name, length, chunk count, SHA-256 and the
 * page's `saved`. */
async function streamed() {
  await page.evaluate(() => {
    window.spiralcam.streamAbove = 0;
    window.spiralcam.saved = null;
    window.written = [];
    window.showSaveFilePicker = async ({ suggestedName }) => ({
      createWritable: async () => ({
        write: async (data) => window.written.push(new Uint8Array(await new Blob([data]).arrayBuffer())),
        close: async () => window.written.push(suggestedName),
        abort: async () => window.written.push('aborted'),
      }),
    });
  });
  await page.click('#download-nc');
  await page.waitForFunction(() => window.spiralcam.saved !== null, null, { timeout: 120_000 });
  return page.evaluate(async () => {
    const name = window.written.pop();
    const all = new Uint8Array(window.written.reduce((n, b) => n + b.length, 0));
    window.written.reduce((at, b) => (all.set(b, at), at + b.length), 0);
    const digest = new Uint8Array(await crypto.subtle.digest('SHA-256', all));
    return { name, length: all.length, chunks: window.written.length, sha: [...digest].map((b) => b.toString(16).padStart(2, '0')).join(''), saved: window.spiralcam.saved };
  });
}

describe('a long path on every core', () => {
  test('is planned in slices into the command line report', async () => {
    const cores = await page.evaluate(() => navigator.hardwareConcurrency);
    await openJob(page, JOB);
    const { report, slices } = await page.evaluate(() => ({ report: window.spiralcam.report, slices: window.spiralcam.slices }));
    assert.equal(slices, cores > 1 ? 4 * Math.min(cores, 8) : 0, `${cores} cores`);
    if (cores > 1) assert.match(await page.textContent('#plan-time'), new RegExp(` in ${slices} slices on ${Math.min(cores, 8)} workers$`));
    assert.equal(report.points, cli.report.points);
    assert.equal(figures(report), figures(cli.report));
  });

  test('writes its program in slices into a Blob, byte for byte the command line program', async () => {
    const nc = await download(page, '#download-nc');
    assert.equal(nc.name, `${JOB.name}.nc`);
    assert.equal(nc.bytes.length, cli.nc.length);
    assert.ok(nc.bytes.equals(cli.nc), 'program differs');
    const saved = await page.evaluate(() => window.spiralcam.saved);
    assert.deepEqual(saved, { name: nc.name, streamed: false, slices: programSlices() });
  });

  test('streams its program into the file the save dialog gives', async () => {
    const got = await streamed();
    assert.equal(got.name, `${JOB.name}.nc`);
    assert.equal(got.length, cli.nc.length);
    assert.equal(got.sha, sha256(cli.nc));
    assert.equal(got.chunks, programSlices());
    assert.deepEqual(got.saved, { name: got.name, streamed: true, slices: programSlices() });
  });

  test('a cancel while the slices run sticks', async () => {
    const started = await page.evaluate(() => window.spiralcam.started);
    await page.fill('[data-field="part.diameter_mm"]', '9');
    await page.waitForFunction((n) => window.spiralcam.started > n && document.body.dataset.state === 'planning', started);
    await page.click('#cancel');
    await waitForState(page, ['cancelled']);
    await page.waitForTimeout(700);
    assert.equal(await page.evaluate(() => document.body.dataset.state), 'cancelled');
  });

  test('streams a program written in one piece into the file too', async () => {
    // A space spiral is not sliced: one worker writes the whole text, which goes to the file.
    const job = { ...JOB, name: 'space-spiral-lens-array', part: { diameter_mm: 2.0 }, strategy: { feed_mm_per_rev: 0.02, sampling: { type: 'space_spiral', points_per_rev: 360, base_spans: 8 } } };
    const dir = mkdtempSync(join(tmpdir(), 'spiralcam-space-'));
    const path = join(dir, `${job.name}.json`);
    writeFileSync(path, JSON.stringify(job));
    const whole = planWithCli(path).nc;
    await openJob(page, job);
    const got = await streamed();
    assert.equal(got.name, `${job.name}.nc`);
    assert.equal(got.length, whole.length);
    assert.equal(got.sha, sha256(whole));
    assert.deepEqual(got.saved, { name: got.name, streamed: true, slices: 0 });
  });
});
