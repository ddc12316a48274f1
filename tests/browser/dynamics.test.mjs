// The machine model and the hybrid FTS/SSS split on the page (issue 5), once through WebGPU and
// once through the WebGL2 fallback: a machine preset fills the limits, the automatic split
// shows its verdict, figures and three plots (pixels read back), the NC program with the servo's
// word and the servo's table equal the command line's byte for byte, invalid limits and cutoffs
// and splits the machine cannot make show their error beside the field, and removing the split
// (then the machine) takes the servo (then the panel) away.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { download, launch, openPage, planWithCli, replan, setField, startServer } from './harness.mjs';

/** Share of a 2-D canvas's pixels that are not white, and its number of distinct colours. */
async function plotStats(page, id) {
  return page.evaluate((canvasId) => {
    const c = document.getElementById(canvasId);
    const { data } = c.getContext('2d').getImageData(0, 0, c.width, c.height);
    let ink = 0;
    const colours = new Set();
    for (let i = 0; i < data.length; i += 4) {
      if (data[i] + data[i + 1] + data[i + 2] < 3 * 250) ink++;
      colours.add((data[i] >> 3) * 1024 + (data[i + 1] >> 3) * 32 + (data[i + 2] >> 3));
    }
    return { width: c.width, ink: ink / (data.length / 4), colours: colours.size };
  }, id);
}

/** A servo word with a value in an NC program, e.g. ` W-0.001234`. */
const servoWord = (word) => new RegExp(` ${word}-?\\d+\\.\\d+`);

let server;
before(async () => {
  server = await startServer();
});
after(() => server.stop());

for (const backend of ['WebGPU', 'WebGL2']) {
  describe(`machine dynamics and the FTS split through ${backend}`, () => {
    let browser;
    let page;
    let errors;

    before(async () => {
      let context;
      ({ browser, context } = await launch(backend));
      ({ page, errors } = await openPage(context, server.url));
      // Paper 004's lens array on Ø4 mm, 100 turns of 180 points: 18 001 points, quick to plan.
      await setField(page, 'part.diameter_mm', '4');
      await setField(page, 'strategy.feed_mm_per_rev', '0.02');
      await setField(page, 'strategy.sampling.points_per_rev', '180');
    });
    after(async () => {
      await browser.close();
    });

    /** The job as the page holds it (its "Save job" download), and a file of it. */
    async function savedJob() {
      const saved = await download(page, '#download-job');
      const path = join(mkdtempSync(join(tmpdir(), 'spiralcam-job-')), saved.name);
      writeFileSync(path, saved.bytes);
      return { job: JSON.parse(saved.bytes.toString()), path };
    }

    test('a machine preset fills the limits and the axes are checked', async () => {
      assert.equal(await page.isVisible('#dynamics'), false);
      await replan(page, () => page.selectOption('[data-role="machine-preset"]', 'fts_70um_700hz'));
      assert.equal(await page.inputValue('[data-field="machine.block_rate_hz"]'), '10000');
      assert.equal(await page.inputValue('[data-field="machine.z_slide.bandwidth_hz"]'), '20');
      assert.equal(await page.inputValue('[data-field="machine.fts"]'), 'set');
      assert.equal(await page.inputValue('[data-field="machine.fts.stroke_um"]'), '70');
      const { job } = await savedJob();
      assert.deepEqual(job.machine.fts, { stroke_um: 70, bandwidth_hz: 700, acceleration_m_per_s2: 300 });
      assert.equal(job.strategy.split, undefined);
      // Limits without a split: the axis checks, no servo channel.
      assert.equal(await page.isVisible('#dynamics'), true);
      assert.equal(await page.textContent('[data-key="Split"]'), 'none: Z cuts alone');
      assert.match(await page.textContent('[data-key="Block rate"]'), /^2,400 Hz needed at ρ .*; limit 10,000 Hz$/);
      assert.match(await page.textContent('[data-key="Highest spindle speed"]'), /^[\d,.]+ rpm, bound by machine\./);
      // The lenslets at 800 rpm are far beyond the Z slide's 20 Hz; X, linear in the angle, asks nothing.
      assert.match(await page.textContent('[data-key="Z bandwidth"]'), /^[\d,.]+ Hz needed of 20(\.0)? Hz: too fast$/);
      assert.match(await page.textContent('[data-key="X bandwidth"]'), /^0(\.00)? Hz needed of 20(\.0)? Hz$/);
      assert.equal(await page.textContent('[data-key="Within limits"]'), 'no (see the warnings above)');
      assert.equal(await page.isVisible('#channels-figure'), false);
      assert.equal(await page.isVisible('#download-fts'), false);
      assert.equal(await page.isVisible('[data-field="output.fts_word"]'), false);
    });

    test('the automatic split shows its verdict, figures and three plots', async () => {
      await replan(page, () => page.selectOption('[data-field="strategy.split.type"]', 'auto'));
      const d = await page.evaluate(() => window.spiralcam.report.dynamics);
      assert.equal(d.split.verdict.status, 'feasible');
      assert.equal(d.split.verdict.slide_alone, false);
      assert.equal(await page.textContent('[data-key="Verdict"]'), 'feasible: both channels within the machine\'s limits');
      assert.match(await page.textContent('[data-key="Cutoff"]'), /^[\d.]+ Hz \([\d.]+ cycles\/rev\)$/);
      assert.match(await page.textContent('[data-key="W servo PV"]'), /^\d+\.\d+ µm$/);
      assert.match(await page.textContent('[data-key="W axis"]'), /m\/s², stroke [\d.]+ of 70 µm$/);
      assert.equal(await page.locator('#split-checks tbody tr').count(), d.split.verdict.checks.length);
      assert.equal(await page.locator('#split-checks tr.fail').count(), 0);
      assert.doesNotMatch(await page.textContent('[data-key="Z bandwidth"]'), /too fast/);
      for (const id of ['plot-spectrum', 'plot-frequency', 'plot-channels']) {
        const stats = await plotStats(page, id);
        assert.ok(stats.width > 200, `${id}: ${stats.width} pixels wide`);
        assert.ok(stats.ink > 0.03, `${id}: only ${(100 * stats.ink).toFixed(1)} % drawn`);
        assert.ok(stats.colours > 8, `${id}: only ${stats.colours} colours`);
      }
      assert.equal(await page.isVisible('#channels-figure'), true);
      assert.equal(await page.isVisible('#download-fts'), true);
      assert.deepEqual(errors, []);
    });

    test('the NC program with the servo word (Y in ISO) and the servo table equal the command line byte for byte', async () => {
      const { job, path } = await savedJob();
      assert.deepEqual(job.strategy.split, { type: 'auto' });
      const cli = planWithCli(path, { fts: true });
      const nc = await download(page, '#download-nc');
      assert.equal(nc.name, 'lens-array-paper004.ngc');
      assert.match(nc.bytes.toString(), servoWord('Y'));
      assert.ok(nc.bytes.equals(cli.nc), 'NC differs from the command line');
      const fts = await download(page, '#download-fts');
      assert.equal(fts.name, 'lens-array-paper004-fts.csv');
      assert.ok(fts.bytes.toString().startsWith('c_deg,x_mm,w_mm\n'));
      assert.ok(fts.bytes.equals(cli.fts), 'FTS table differs from the command line');
      // Another servo word.
      await replan(page, () => page.selectOption('[data-field="output.fts_word"]', 'U'));
      const u = (await download(page, '#download-nc')).bytes.toString();
      assert.match(u, servoWord('U'));
      assert.doesNotMatch(u, servoWord('Y'));
      await replan(page, () => page.selectOption('[data-field="output.fts_word"]', ''));
    });

    test('a low-pass beyond the slide is infeasible, with the speed that would do', async () => {
      await replan(page, () => page.selectOption('[data-field="strategy.split.type"]', 'low_pass'));
      // The cutoff starts at the Z slide's bandwidth.
      assert.equal(await page.inputValue('[data-field="strategy.split.cutoff_hz"]'), '20');
      await setField(page, 'strategy.split.cutoff_hz', '100');
      assert.match(await page.textContent('[data-key="Verdict"]'),
        /^infeasible: .*Z slide bandwidth 100 Hz > 20 Hz.*; feasible at [\d,.]+ rpm or less$/);
      assert.ok(await page.locator('#split-checks tr.fail[data-limit="slide_bandwidth_hz"]').count());
      assert.match(await page.textContent('#warnings'), /the split exceeds the machine/);
    });

    test('invalid limits and cutoffs show the error beside the field', async () => {
      await setField(page, 'strategy.split.cutoff_hz', '0', ['error']);
      assert.match(await page.textContent('[data-error-for="strategy.split.cutoff_hz"]'), /^strategy\.split\.cutoff_hz = 0: must be a finite number/);
      await replan(page, () => page.selectOption('[data-field="strategy.split.type"]', 'auto'));
      assert.equal(await page.isVisible('[data-field="strategy.split.cutoff_hz"]'), false);
      await setField(page, 'machine.fts.stroke_um', '0', ['error']);
      assert.equal(await page.textContent('[data-error-for="machine.fts.stroke_um"]'), 'machine.fts.stroke_um = 0: must be a finite number > 0');
      assert.ok(await page.locator('[data-field="machine.fts.stroke_um"].invalid').count());
      await setField(page, 'machine.fts.stroke_um', '70');
      assert.equal(await page.textContent('[data-error-for="machine.fts.stroke_um"]'), '');
      // One limit of a slide left blank is an error; all three blank: not checked.
      await setField(page, 'machine.x_slide.bandwidth_hz', '', ['error']);
      assert.equal(await page.textContent('[data-error-for="machine.x_slide.bandwidth_hz"]'), 'machine.x_slide.bandwidth_hz = NaN: must be a finite number > 0');
      await setField(page, 'machine.x_slide.velocity_mm_per_min', '', ['error']);
      await setField(page, 'machine.x_slide.acceleration_mm_per_s2', '');
      assert.equal((await savedJob()).job.machine.x_slide, undefined);
      assert.equal(await page.inputValue('[data-role="machine-preset"]'), '');
      // The automatic split without the Z slide's limits, then a split without a servo.
      await setField(page, 'machine.z_slide.velocity_mm_per_min', '', ['error']);
      await setField(page, 'machine.z_slide.acceleration_mm_per_s2', '', ['error']);
      await setField(page, 'machine.z_slide.bandwidth_hz', '', ['error']);
      assert.equal(await page.textContent('[data-error-for="strategy.split.type"]'), 'strategy.split.type = auto: needs the Z slide\'s limits: machine.z_slide');
      await replan(page, () => page.selectOption('[data-role="machine-preset"]', 'fts_70um_700hz'));
      await replan(page, () => page.selectOption('[data-field="machine.fts"]', ''), ['error']);
      assert.equal(await page.textContent('[data-error-for="strategy.split.type"]'), 'strategy.split = set: needs a fast tool servo: machine.fts');
      await replan(page, () => page.selectOption('[data-field="machine.fts"]', 'set'));
      assert.equal(await page.inputValue('[data-field="machine.fts.stroke_um"]'), '70');
      assert.equal(await page.inputValue('[data-role="machine-preset"]'), 'fts_70um_700hz');
      assert.equal(await page.evaluate(() => window.spiralcam.report.dynamics.split.verdict.status), 'feasible');
    });

    test('removing the split takes the servo away, removing the machine the panel', async () => {
      await replan(page, () => page.selectOption('[data-field="strategy.split.type"]', ''));
      assert.equal(await page.evaluate(() => window.spiralcam.report.dynamics.split), null);
      assert.equal(await page.isVisible('#dynamics'), true);
      assert.equal(await page.isVisible('#channels-figure'), false);
      assert.equal(await page.isVisible('#download-fts'), false);
      assert.equal(await page.isVisible('[data-field="output.fts_word"]'), false);
      assert.doesNotMatch((await download(page, '#download-nc')).bytes.toString(), servoWord('W'));
      await replan(page, () => page.selectOption('[data-role="machine-preset"]', 'none'));
      assert.equal(await page.isVisible('#dynamics'), false);
      assert.equal(await page.evaluate(() => window.spiralcam.report.dynamics), undefined);
      const { job } = await savedJob();
      assert.deepEqual(Object.keys(job.machine), ['spindle_rpm']);
      assert.equal(job.strategy.split, undefined);
      assert.deepEqual(errors, []);
    });
  });
}
