// Open NC draws the program in the 3-D view (issue 14), through WebGPU and WebGL2: a program the
// command line writes for a Ø10 asphere, edited so that every cutting block inside ρ = 2.5 mm
// leaves 400 nm of material (Z raised by 0.0004 mm) and the rest cuts the design, is verified
// on the page. The last pass is drawn over a grey surface coloured by deviation: the colour
// scale runs from the report's minimum (≈ 0 nm, the scale's bottom colour, #440154) to its
// maximum (≈ 400 nm, the top colour, #fde725), the legend reads in nm, and pixels read back
// from the canvas show both ends of the scale and none of the planned path's red. Unticking
// the box, or a new plan, gives back the planned path and the height legend.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { execFileSync } from 'node:child_process';
import { canvasPixels, launch, openJob, openPage, setField, spiralcamCli, startServer, waitForState } from './harness.mjs';

const JOB = {
  name: 'verify-view',
  part: { diameter_mm: 10.0 },
  surface: { type: 'asphere', radius_mm: 20.0, conic: -1.0 },
  tool: { nose_radius_mm: 0.5 },
  machine: { spindle_rpm: 600 },
  strategy: { feed_mm_per_rev: 0.05, sampling: { type: 'constant_angle', points_per_rev: 90 } },
  output: { dialect: 'iso' },
};

/** Pixels within `tolerance` (sum of channel differences) of `rgb`. */
function near({ data }, rgb, tolerance = 40) {
  let n = 0;
  for (let i = 0; i < data.length; i += 4) {
    if (Math.abs(data[i] - rgb[0]) + Math.abs(data[i + 1] - rgb[1]) + Math.abs(data[i + 2] - rgb[2]) <= tolerance) n++;
  }
  return n;
}

const BOTTOM = [0x44, 0x01, 0x54];
const TOP = [0xfd, 0xe7, 0x25];
const PATH_RED = [255, 64, 77];

/** The command line's ISO program of JOB with Z raised 0.0004 mm on cutting blocks inside ρ 2.5. */
function editedProgram() {
  const dir = mkdtempSync(join(tmpdir(), 'spiralcam-verify-view-'));
  const jobPath = join(dir, 'job.json');
  writeFileSync(jobPath, JSON.stringify(JOB));
  const nc = join(dir, 'program.ngc');
  execFileSync(spiralcamCli(), ['plan', jobPath, '--nc', nc, '--report', join(dir, 'r.json')]);
  let raised = 0;
  const lines = readFileSync(nc, 'utf8').split('\n').map((line) => {
    const x = /X(-?\d+\.\d+)/.exec(line);
    const z = /Z(-?\d+\.\d+)/.exec(line);
    if (!/^G1\b/.test(line) || !/C-?\d/.test(line) || !x || !z || Number(x[1]) > 2.5) return line;
    raised++;
    return line.replace(z[0], `Z${(Number(z[1]) + 0.0004).toFixed(6)}`);
  });
  assert.ok(raised > 1000, `${raised} blocks raised`);
  const out = join(dir, 'edited.ngc');
  writeFileSync(out, lines.join('\n'));
  return out;
}

let server;
let program;
before(async () => {
  server = await startServer();
  program = editedProgram();
});
after(() => server.stop());

for (const backend of ['WebGPU', 'WebGL2']) {
  describe(`Open NC draws the program coloured by deviation through ${backend}`, () => {
    let browser;
    let page;
    let errors;
    before(async () => {
      let context;
      ({ browser, context } = await launch(backend));
      ({ page, errors } = await openPage(context, server.url));
      assert.equal(await page.evaluate(() => window.spiralcam.backend), backend);
      await openJob(page, JOB);
    });
    after(async () => {
      await browser.close();
    });

    test('the last pass is drawn over a grey surface, its deviation on the legend in nm', async () => {
      const planned = await canvasPixels(page);
      assert.ok(near(planned, PATH_RED) > 100, 'the planned path is drawn in red');

      await page.setInputFiles('#nc-file', program);
      await waitForState(page, ['verified']);
      const v = await page.evaluate(() => window.spiralcam.verification);
      assert.ok(Math.abs(v.deviation_um.min) < 1e-3, JSON.stringify(v.deviation_um));
      assert.ok(Math.abs(v.deviation_um.max - 0.4) < 1e-3, JSON.stringify(v.deviation_um));
      const drawn = await page.evaluate(() => window.spiralcam.programDrawn);
      assert.equal(drawn.points, v.deviation_um.points, 'every point drawn (fewer than 200 000)');
      assert.ok(Math.abs(drawn.lo_nm - 1000 * v.deviation_um.min) < 1e-9);
      assert.ok(Math.abs(drawn.hi_nm - 1000 * v.deviation_um.max) < 1e-9);
      const ticks = await page.$$eval('#legend-ticks span', (s) => s.map((e) => e.textContent));
      assert.equal(ticks.length, 5);
      assert.ok(ticks.every((t) => t.endsWith(' nm')), ticks.join(' | '));
      assert.ok(Math.abs(parseFloat(ticks[0]) - 400) <= 1, `top tick ${ticks[0]}`);
      assert.ok(Math.abs(parseFloat(ticks[4])) <= 1, `bottom tick ${ticks[4]}`);
      assert.match(await page.textContent('#path-note'), /coloured by deviation from the design/);

      const shown = await canvasPixels(page);
      const [bottom, top, red] = [near(shown, BOTTOM), near(shown, TOP), near(shown, PATH_RED)];
      assert.ok(bottom > 100, `${bottom} pixels of the scale's bottom (the outer zone, cut to the design)`);
      assert.ok(top > 100, `${top} pixels of the scale's top (the inner zone, 400 nm left)`);
      assert.equal(red, 0, 'the planned path is not drawn');
      assert.deepEqual(errors, []);
    });

    test('unticking the box and a new plan give back the planned path', async () => {
      await page.uncheck('#verify-show-path');
      assert.equal(await page.evaluate(() => window.spiralcam.programDrawn), null);
      assert.match(await page.textContent('#legend-ticks span'), / µm$/);
      assert.ok(near(await canvasPixels(page), PATH_RED) > 100, 'the planned path again');
      await page.check('#verify-show-path');
      assert.ok((await page.evaluate(() => window.spiralcam.programDrawn)).points > 0);
      assert.equal(near(await canvasPixels(page), PATH_RED), 0);

      // The program was verified against the job planned before: a new plan drops it.
      await setField(page, 'strategy.feed_mm_per_rev', '0.04');
      assert.equal(await page.evaluate(() => window.spiralcam.programDrawn), null);
      assert.ok(await page.isHidden('#verify-show'));
      assert.ok(near(await canvasPixels(page), PATH_RED) > 100);
      assert.deepEqual(errors, []);
    });
  });
}
