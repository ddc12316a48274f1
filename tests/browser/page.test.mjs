// The real page in headless Chromium, once through WebGPU and once through the WebGL2
// fallback: it plans the default job on load, draws the surface (pixels read back), re-plans on
// an edit, puts errors beside their field, stays responsive and cancellable on a
// multi-million-point job, loads nothing from the network, and its downloads equal the
// command-line tool's output byte for byte.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import {
  ROOT, canvasPixels, download, launch, openPage, pixelStats, planWithCli, replan, setField, startServer,
  waitForState,
} from './harness.mjs';

let server;
before(async () => {
  server = await startServer();
});
after(() => server.stop());

for (const backend of ['WebGPU', 'WebGL2']) {
  describe(`page through ${backend}`, () => {
    let browser;
    let context;
    let page;
    let requests;
    let errors;

    before(async () => {
      ({ browser, context } = await launch(backend));
      ({ page, requests, errors } = await openPage(context, server.url));
    });
    after(async () => {
      await browser.close();
    });

    test('plans the default job on load and reports it', async () => {
      const points = await page.textContent('[data-key="Points"]');
      assert.equal(points, '360,001');
      const report = await page.evaluate(() => window.spiralcam.report);
      assert.equal(report.job, 'lens-array-paper004');
      assert.ok(Math.abs(report.surface_pv_um - 44.3605) < 1e-3, `PV ${report.surface_pv_um}`);
      assert.deepEqual(errors, []);
    });

    test(`uses ${backend} and shows which`, async () => {
      assert.equal(await page.textContent('#backend'), backend);
    });

    test('draws the surface: canvas pixels are not blank', async () => {
      const stats = pixelStats(await canvasPixels(page));
      assert.ok(stats.covered > 0.15, `only ${(100 * stats.covered).toFixed(1)} % of the canvas is drawn`);
      assert.ok(stats.colours > 30, `only ${stats.colours} distinct colours: no colour map?`);
    });

    test('orbit and zoom change the picture', async () => {
      const before = await canvasPixels(page);
      const box = await page.locator('#view').boundingBox();
      await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
      await page.mouse.down();
      await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2 + 40, { steps: 5 });
      await page.mouse.up();
      await page.mouse.wheel(0, -400);
      const afterMove = await canvasPixels(page);
      let changed = 0;
      for (let i = 0; i < before.data.length; i += 4) {
        if (before.data[i] !== afterMove.data[i] || before.data[i + 1] !== afterMove.data[i + 1]) changed++;
      }
      assert.ok(changed > before.data.length / 40, `only ${changed} pixels changed`);
      await page.dblclick('#view');
    });

    test('loads nothing from the network but its own files', async () => {
      const foreign = requests.filter((u) => !u.startsWith(server.url) && !u.startsWith('blob:') && !u.startsWith('data:'));
      assert.deepEqual(foreign, []);
    });

    test('downloads equal the command-line output byte for byte', async () => {
      const cli = planWithCli(join(ROOT, 'crate/jobs/lens-array-paper004.json'));
      // The buttons say what each file weighs before it is made: the program exactly, the
      // table from the estimate the plan was admitted on (within 1 %).
      const mb = (n) => (n / 1e6).toFixed(2);
      assert.equal(await page.textContent('#download-nc'), `Download NC (${mb(cli.nc.length)} MB)`);
      const label = await page.textContent('#download-csv');
      const shown = Number(label.match(/about ([0-9.]+) MB/)[1]) * 1e6;
      assert.ok(Math.abs(shown - cli.csv.length) < 0.01 * cli.csv.length, `${label} vs ${cli.csv.length} B`);
      const nc = await download(page, '#download-nc');
      assert.equal(nc.name, 'lens-array-paper004.ngc');
      assert.ok(nc.bytes.equals(cli.nc), 'NC differs from the command line');
      const csv = await download(page, '#download-csv');
      assert.equal(csv.name, 'lens-array-paper004.csv');
      assert.ok(csv.bytes.equals(cli.csv), 'CSV differs from the command line');
    });

    test('an edit re-plans and changes the report', async () => {
      await setField(page, 'strategy.feed_mm_per_rev', '0.02');
      assert.equal(await page.textContent('[data-key="Points"]'), '180,001');
      await replan(page, () => page.selectOption('[data-field="output.dialect"]', 'moore'));
      const report = await page.evaluate(() => window.spiralcam.report);
      assert.equal(report.dialect, 'Moore Nanotech style');
      // The edited job, saved from the page and planned by the command line, gives the same NC.
      const job = await download(page, '#download-job');
      assert.equal(job.name, 'lens-array-paper004.json');
      const jobPath = join(mkdtempSync(join(tmpdir(), 'spiralcam-job-')), job.name);
      writeFileSync(jobPath, job.bytes);
      const cli = planWithCli(jobPath);
      const nc = await download(page, '#download-nc');
      assert.equal(nc.name, 'lens-array-paper004.nc');
      assert.ok(nc.bytes.equals(cli.nc), 'NC of the edited job differs from the command line');
    });

    test('invalid input shows the error beside the field', async () => {
      await setField(page, 'tool.nose_radius_mm', '-1', ['error']);
      const message = await page.textContent('[data-error-for="tool.nose_radius_mm"]');
      assert.equal(message, 'tool.nose_radius_mm = -1: must be a finite number ≥ 0');
      assert.ok(await page.locator('[data-field="tool.nose_radius_mm"].invalid').count());
      await setField(page, 'tool.nose_radius_mm', '0.5');
      assert.equal(await page.textContent('[data-error-for="tool.nose_radius_mm"]'), '');
    });

    test('the spindle axis can be the normal at a point', async () => {
      await setField(page, 'part.normal_axis_at_mm', '0.3, 0.2');
      const report = await page.evaluate(() => window.spiralcam.report);
      assert.match(report.surface, /on a spindle axis along its normal at \(0\.3, 0\.2\) mm .*tilted 7\./);
      await setField(page, 'part.normal_axis_at_mm', 'x, 0', ['error']);
      assert.equal(await page.textContent('[data-error-for="part.normal_axis_at_mm"]'),
        'part.normal_axis_at_mm[0] = NaN: must be a finite number');
      await setField(page, 'part.normal_axis_at_mm', '');
      assert.equal((await page.evaluate(() => window.spiralcam.report)).surface.includes('tilted'), false);
    });

    test('a multi-million-point job keeps the page responsive and can be cancelled', async () => {
      // The first edit's 3.6 M points may be planned before the state is looked at (two
      // workers plan them in about 2 s): either state will do, the second edit is the test.
      await setField(page, 'strategy.feed_mm_per_rev', '0.001', ['planning', 'done']);
      await setField(page, 'strategy.sampling.points_per_rev', '5000', ['planning']);
      // 5000 revolutions × 5000 points = 25 M points: progress moves while the page answers
      // (10 M points were planned on two workers in under 2 s, before the click could land).
      await page.waitForFunction(() => document.querySelector('#progress').value > 0, null, { timeout: 60_000 });
      const first = await page.evaluate(() => document.querySelector('#progress').value);
      const frames = await page.evaluate(() => new Promise((resolve) => {
        let n = 0;
        const tick = () => (++n === 10 ? resolve(n) : requestAnimationFrame(tick));
        requestAnimationFrame(tick);
      }));
      assert.equal(frames, 10);
      await page.waitForFunction((v) => document.querySelector('#progress').value > v, first, { timeout: 60_000 });
      assert.equal(await page.evaluate(() => document.body.dataset.state), 'planning');
      assert.equal(await page.evaluate(() => document.querySelector('#progress').max), 25_000_001);
      // Cancel takes the focus from the field just typed in: its `change` must not re-plan.
      await page.click('#cancel');
      await waitForState(page, ['cancelled']);
      await page.waitForTimeout(700);
      assert.equal(await page.evaluate(() => document.body.dataset.state), 'cancelled');
      assert.equal(await page.isHidden('#busy'), true);
      await setField(page, 'strategy.feed_mm_per_rev', '0.01');
      await setField(page, 'strategy.sampling.points_per_rev', '720');
    });
  });
}
