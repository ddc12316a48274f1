// The page's Program panel (issue 12) and Measured panel (issue 15) in headless Chromium: a job
// with passes and a size limit opened from a file shows its passes in the report and the view,
// and its program downloads as one zip whose files equal, byte for byte and in order, the main
// program and the child programs the command-line tool writes; a measured error map (a known
// astigmatism with piston and tilt) is registered and its residual reported and drawn; Open NC
// verifies the command line's program with its children against the job (issue 14).

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { execFileSync } from 'node:child_process';
import { inflateRawSync } from 'node:zlib';
import { download, launch, openJob, openPage, replan, spiralcamCli, startServer, waitForState } from './harness.mjs';

/** A Moore-style job with two groups of passes and a limit that splits it into children. */
const PROGRAM_JOB = {
  name: 'passes-zip',
  part: { diameter_mm: 2.0 },
  surface: { type: 'asphere', radius_mm: 10.0, conic: -0.5 },
  tool: { nose_radius_mm: 0.1 },
  machine: { spindle_rpm: 500 },
  strategy: { feed_mm_per_rev: 0.01, sampling: { type: 'constant_angle', points_per_rev: 90 } },
  output: { dialect: 'moore', feed_mode: 'block_time_s' },
  program: {
    work_offset: 'G55',
    tool: 'T0303',
    c_axis_on: 'M26.1',
    c_axis_off: 'M29',
    approach: [{ height_mm: 0.5, feed_mm_per_min: 200 }, { height_mm: 0.05, feed_mm_per_min: 20 }],
    passes: [{ count: 2, depth_of_cut_um: 5 }, { count: 1, depth_of_cut_um: 2 }],
    loop: 'unrolled',
    max_program_bytes: 100000,
  },
};

/** The files of a zip archive in order, as { name, bytes } (stored or deflated entries). */
function unzip(buffer) {
  const files = [];
  let at = 0;
  while (buffer.readUInt32LE(at) === 0x04034b50) {
    const method = buffer.readUInt16LE(at + 8);
    const flags = buffer.readUInt16LE(at + 6);
    assert.equal(flags & 0x08, 0, 'sizes in the local header');
    const size = buffer.readUInt32LE(at + 18);
    const nameLength = buffer.readUInt16LE(at + 26);
    const extra = buffer.readUInt16LE(at + 28);
    const name = buffer.toString('utf8', at + 30, at + 30 + nameLength);
    const start = at + 30 + nameLength + extra;
    const data = buffer.subarray(start, start + size);
    files.push({ name, bytes: method === 8 ? inflateRawSync(data) : Buffer.from(data) });
    at = start + size;
  }
  return files;
}

let server;
/** Where the first test's command line wrote the program and its children. */
let cliDir;
before(async () => {
  server = await startServer();
});
after(() => server.stop());

describe('program and measured panels', () => {
  let browser;
  let page;
  let errors;

  before(async () => {
    let context;
    ({ browser, context } = await launch('WebGL2'));
    ({ page, errors } = await openPage(context, server.url));
  });
  after(async () => {
    await browser.close();
  });

  test('a job with passes shows them and downloads its children as one zip', async () => {
    await openJob(page, PROGRAM_JOB);
    assert.equal(await page.inputValue('[data-field="program"]'), 'set');
    assert.equal(await page.inputValue('[data-field="program.tool"]'), 'T0303');
    assert.ok(await page.isVisible('[data-field="program.passes"]'));
    const report = await page.evaluate(() => window.spiralcam.report);
    assert.equal(report.program.passes.length, 3);
    assert.ok(Math.abs(report.program.stock_mm - 0.012) < 1e-12, `stock ${report.program.stock_mm}`);
    assert.match(await page.textContent('[data-key="Passes"]'), /^3 \(written out\), stock 12 µm/);
    // The view draws the roughing passes raised by the stock each leaves.
    assert.match(await page.textContent('#path-note'), /passes drawn raised by their stock left \(7, 2 µm\)/);
    const children = report.program.children;
    assert.ok(children.length >= 2, `${children.length} children`);
    assert.match(await page.textContent('#download-nc'), new RegExp(`^Download NC zip \\(main \\+ ${children.length} children`));

    // The command line, from the same job: passes-zip.nc and passes-zip-1.nc … beside it.
    const dir = mkdtempSync(join(tmpdir(), 'spiralcam-zip-'));
    const jobPath = join(dir, 'job.json');
    writeFileSync(jobPath, JSON.stringify(PROGRAM_JOB));
    execFileSync(spiralcamCli(), ['plan', jobPath, '--nc', join(dir, 'passes-zip.nc'), '--report', join(dir, 'r.json')]);
    const written = readdirSync(dir).filter((f) => f.endsWith('.nc'));
    assert.equal(written.length, children.length + 1);

    const zip = await download(page, '#download-nc');
    assert.equal(zip.name, 'passes-zip.zip');
    const files = unzip(zip.bytes);
    assert.deepEqual(files.map((f) => f.name), ['passes-zip.nc', ...children.map((c) => c.name)]);
    for (const f of files) {
      assert.ok(f.bytes.equals(readFileSync(join(dir, f.name))), `${f.name} differs from the command line`);
    }
    cliDir = dir;
    assert.deepEqual(errors, []);
  });

  test('Open NC verifies the command-line program and its children against the job', async () => {
    const names = ['passes-zip.nc', ...readdirSync(cliDir).filter((f) => /^passes-zip-\d+\.nc$/.test(f)).sort()];
    await page.setInputFiles('#nc-file', names.map((n) => join(cliDir, n)));
    await waitForState(page, ['verified']);
    const v = await page.evaluate(() => window.spiralcam.verification);
    assert.equal(v.passes.length, 3);
    // Each pass leaves the stock after it: 7, 2 and 0 µm, to within the written digits.
    [7, 2, 0].forEach((stock, k) => assert.ok(Math.abs(v.passes[k].stock_um - stock) < 1e-3, `pass ${k + 1}: ${v.passes[k].stock_um} µm`));
    assert.ok(Math.max(Math.abs(v.deviation_um.min), Math.abs(v.deviation_um.max)) < 1e-3, JSON.stringify(v.deviation_um));
    assert.ok(await page.isVisible('#verify-maps'));
    assert.deepEqual(errors, []);
  });

  test('switching the program off gives one spiral again', async () => {
    await replan(page, () => page.selectOption('[data-field="program"]', ''));
    const report = await page.evaluate(() => window.spiralcam.report);
    assert.equal(report.program ?? null, null);
    assert.equal(await page.isVisible('[data-field="program.passes"]'), false);
    assert.match(await page.textContent('#download-nc'), /^Download NC \(/);
  });

  test('a measured error map is registered and its residual reported and drawn', async () => {
    // Astigmatism of 0.1 µm amplitude on the 2 mm part, plus piston 0.3 µm and a tilt: the
    // registration takes out piston and tilt, the residual is the astigmatism (PV 0.2 µm).
    const rows = ['x_mm,y_mm,z_mm'];
    for (let i = -40; i <= 40; i++) {
      for (let j = -40; j <= 40; j++) {
        const x = i / 40;
        const y = j / 40;
        if (x * x + y * y > 1) continue;
        const z = 1e-4 * (x * x - y * y) + 3e-4 + 2e-4 * x;
        rows.push(`${x},${y},${z}`);
      }
    }
    const dir = mkdtempSync(join(tmpdir(), 'spiralcam-measured-'));
    const file = join(dir, 'error.csv');
    writeFileSync(file, `${rows.join('\n')}\n`);
    await page.setInputFiles('#measured-file', file);
    await waitForState(page, ['corrected']);
    const c = await page.evaluate(() => window.spiralcam.correction);
    assert.ok(Math.abs(c.registration.piston_um - 0.3) < 1e-6, `piston ${c.registration.piston_um}`);
    assert.ok(Math.abs(c.residual.pv_um - 0.2) < 1e-6, `PV ${c.residual.pv_um}`);
    assert.equal(c.residual.points, rows.length - 1);
    assert.ok(await page.isVisible('#correction-maps'));
    assert.ok(await page.isVisible('#download-corrected'));
    const shots = process.env.SPIRALCAM_SCREENSHOTS;
    if (shots) await page.locator('#measured').screenshot({ path: join(shots, 'measured.png') });
    assert.deepEqual(errors, []);
  });
});
