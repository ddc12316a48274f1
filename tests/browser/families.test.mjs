// Every surface family through the page's form (WebGL2): choosing a family plans its defaults
// without an error, the accuracy analysis shows its figures and maps, the data families (STEP,
// Grid Sag, scattered points) plan from files chosen in the page, "Import design…" fills the
// form with the job `spiralcam import` writes from the same files, the scattered form drops the
// RBF options when another interpolator is chosen, and the progressive-lens preset shows its
// power maps.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import {
  ROOT, download, launch, openPage, planWithCli, replan, setField, spiralcamCli, startServer, waitForState,
} from './harness.mjs';

/** Sphere radius of the scattered test data, mm. */
const R = 20;

/** A CSV of the sphere z = R − √(R² − ρ²) on a 0.1 mm grid over [−2.3, 2.3]² mm. */
function sphereCsv() {
  const lines = ['x_mm,y_mm,z_mm'];
  for (let j = -23; j <= 23; j++) {
    for (let i = -23; i <= 23; i++) {
      const [x, y] = [i / 10, j / 10];
      lines.push(`${x},${y},${R - Math.sqrt(R * R - x * x - y * y)}`);
    }
  }
  return lines.join('\n');
}

let server;
before(async () => {
  server = await startServer();
});
after(() => server.stop());

describe('surface families on the page', () => {
  let browser;
  let page;
  let errors;

  before(async () => {
    let context;
    ({ browser, context } = await launch('WebGL2'));
    ({ page, errors } = await openPage(context, server.url));
    await setField(page, 'part.diameter_mm', '4');
  });
  after(async () => {
    await browser.close();
  });

  /** The job as the page holds it (its "Save job" download). */
  async function currentJob() {
    return JSON.parse((await download(page, '#download-job')).bytes.toString());
  }

  test('every family without a data file plans its defaults', async () => {
    const families = await page.$$eval('[data-field="surface.type"] option', (os) => os.map((o) => o.value));
    assert.ok(families.length >= 22, `only ${families.length} families`);
    const withFiles = ['step_face', 'scattered', 'grid_sag'];
    for (const family of families.filter((f) => !withFiles.includes(f))) {
      await replan(page, () => page.selectOption('[data-field="surface.type"]', family));
      const report = await page.evaluate(() => window.spiralcam.report);
      assert.ok(report.points > 1000, `${family}: ${report.points} points`);
      assert.ok(Number.isFinite(report.surface_pv_um), `${family}: PV ${report.surface_pv_um}`);
      assert.equal((await currentJob()).surface.type, family);
    }
    assert.deepEqual(errors, []);
  });

  test('the accuracy analysis shows its figures and maps', async () => {
    await replan(page, () => page.selectOption('[data-field="surface.type"]', 'sinusoid'));
    const points = await page.evaluate(() => window.spiralcam.report.points);
    await page.click('#analyse');
    await waitForState(page, ['analysed']);
    const a = await page.evaluate(() => window.spiralcam.analysis);
    assert.equal(a.linearization.segments, points - 1);
    assert.ok(a.linearization.pv_um > 0 && a.predicted_form.cusp_height_um > 0, JSON.stringify(a));
    assert.equal(await page.locator('#analysis-maps').isVisible(), true);
    assert.match(await page.textContent('[data-key="Cusp height along the feed"]'), /µm/);
    assert.match(await page.textContent('#map-form-range'), /µm/);
    assert.match(await page.textContent('#map-clearance-range'), /°/);
    assert.equal(a.tool_geometry.tool.clearance_deg, 10);
    assert.ok(a.tool_geometry.verdict.length > 0);
    assert.equal(await page.textContent('[data-key="Tool verdict"]'), a.tool_geometry.verdict);
    assert.match(await page.textContent('[data-key="Pass spacing max/min"]'), /space spiral \d.*Z projection \d/);
    // A new plan clears the analysis of the old one.
    await setField(page, 'strategy.feed_mm_per_rev', '0.02');
    assert.equal(await page.locator('#analysis-maps').isVisible(), false);
    // HCAA sampling from a PV tolerance, the space spiral, and two-way compensation with its X
    // figures.
    await replan(page, () => page.selectOption('[data-field="strategy.sampling.type"]', 'hcaa'));
    assert.equal((await currentJob()).strategy.sampling.pv_tolerance_um, 1);
    assert.ok(await page.locator('[data-field="strategy.sampling.pv_tolerance_um"]').isVisible());
    await replan(page, () => page.selectOption('[data-field="strategy.sampling.type"]', 'space_spiral'));
    assert.ok(await page.locator('[data-field="strategy.sampling.base_spans"]').isVisible());
    assert.equal((await currentJob()).strategy.sampling.base_spans, 8);
    await replan(page, () => page.selectOption('[data-field="strategy.sampling.type"]', 'constant_angle'));
    await replan(page, () => page.selectOption('[data-field="strategy.compensation"]', 'two_way'));
    assert.match(await page.textContent('[data-key="X reversals"]'), /^\d/);
    await replan(page, () => page.selectOption('[data-field="strategy.compensation"]', 'one_way'));
  });

  test('a STEP face chosen in the page plans', async () => {
    await page.selectOption('[data-field="surface.type"]', 'step_face');
    await replan(page, () => page.setInputFiles('[data-field="surface.file"]', join(ROOT, 'crate/jobs/step-face-sphere.step')));
    const report = await page.evaluate(() => window.spiralcam.report);
    assert.match(report.surface, /STEP|NURBS|B-spline/i);
  });

  test('a Grid Sag file chosen in the page plans', async () => {
    await page.selectOption('[data-field="surface.type"]', 'grid_sag');
    await replan(page, () => page.setInputFiles('[data-field="surface.data"]', join(ROOT, 'crate/jobs/grid-sag.dat')));
    const report = await page.evaluate(() => window.spiralcam.report);
    assert.match(report.surface, /^grid sag \(Zemax DAT\) from inline data: 33 × 33 points/);
    assert.equal((await currentJob()).surface.type, 'grid_sag');
  });

  test('a design imported in the page is the job the command line imports', async () => {
    // A lens whose rear surface is a Grid Sag on a sphere; the .DAT chosen with the .zmx.
    const dir = mkdtempSync(join(tmpdir(), 'spiralcam-design-'));
    const zmx = join(dir, 'lens.zmx');
    writeFileSync(zmx, 'UNIT MM\nSURF 0\nSURF 1\n  TYPE EVENASPH\n  CURV 0.02\n  GLAS N-BK7\n  DIAM 2\n'
      + 'SURF 2\n  TYPE GRIDSAG\n  CURV -0.01\n  UDAD "grid-sag.dat"\n  DIAM 2\nSURF 3\n');
    const dat = join(ROOT, 'crate/jobs/grid-sag.dat');
    writeFileSync(join(dir, 'grid-sag.dat'), readFileSync(dat));
    await page.setInputFiles('#import-design', [zmx, dat]);
    await page.locator('#import-dialog').waitFor({ state: 'visible' });
    const listed = await page.$$eval('#import-surface option', (os) => os.map((o) => o.textContent));
    assert.deepEqual(listed, ['0 STANDARD (object)', '1 EVENASPH, semi-diameter 2 mm', '2 GRIDSAG, semi-diameter 2 mm', '3 STANDARD (image)']);
    await page.selectOption('#import-surface', '2');
    // A refracting surface: the piece must be chosen; the core's message says so.
    await page.click('#import-fill');
    assert.match(await page.textContent('#import-error'), /choose optic \(its own surface, cut from the air side\) or mould/);
    await page.selectOption('#import-cut', 'mould');
    await replan(page, () => page.click('#import-fill'));
    assert.equal(await page.locator('#import-dialog').isVisible(), false);
    assert.match(await page.textContent('#import-listing'), /surface 2 GRIDSAG/);
    assert.equal(await page.inputValue('[data-field="part.cut"]'), 'mould turned');
    const job = await currentJob();
    // The command line, from the same files: the same job, its grid named instead of carried.
    const out = join(dir, 'cli.json');
    execFileSync(spiralcamCli(), ['import', zmx, '--surface', '2', '--cut', 'mould', '--out', out]);
    const cli = JSON.parse(readFileSync(out, 'utf8'));
    assert.deepEqual(cli.surface.data, { path: 'cli.grid.DAT' });
    assert.deepEqual(job.surface.data, { text: readFileSync(dat, 'utf8') });
    cli.surface.data = job.surface.data;
    assert.deepEqual(job, cli);
    assert.match(await page.evaluate(() => window.spiralcam.report.cut), /^a mould insert forming the surface, the design turned 180° about Y/);
    await replan(page, () => page.selectOption('[data-field="part.cut"]', ''));
    assert.equal((await currentJob()).part.cut, undefined);
  });

  test('scattered points chosen in the page regenerate the sphere they sample', async () => {
    const csv = join(mkdtempSync(join(tmpdir(), 'spiralcam-data-')), 'sphere.csv');
    writeFileSync(csv, sphereCsv());
    // A coarse path (20 turns of 90 points) keeps the RBF's plan quick.
    await setField(page, 'strategy.feed_mm_per_rev', '0.1');
    await setField(page, 'strategy.sampling.points_per_rev', '90');
    await page.selectOption('[data-field="surface.type"]', 'scattered');
    await replan(page, () => page.setInputFiles('[data-field="surface.data"]', csv));
    // The path runs from ρ = 2 mm to the centre, so the PV is about the sphere's sag at 2 mm,
    // 100.2509 µm; the RBF on 0.1 mm data is second order, within 0.1 µm here (49 nm seen; see
    // crate/docs/rbf-table2.md for its accuracy). Exactly, the page's NC is the command line's
    // for the job the page saves (the data travel inside it as text).
    const pv = await page.evaluate(() => window.spiralcam.report.surface_pv_um);
    const exact = 1000 * (R - Math.sqrt(R * R - 4));
    assert.ok(Math.abs(pv - exact) < 0.1, `PV ${pv} µm, sphere ${exact} µm`);
    const saved = await download(page, '#download-job');
    const jobPath = join(mkdtempSync(join(tmpdir(), 'spiralcam-job-')), saved.name);
    writeFileSync(jobPath, saved.bytes);
    const nc = await download(page, '#download-nc');
    assert.ok(nc.bytes.equals(planWithCli(jobPath).nc), 'NC differs from the command line');

    await replan(page, () => page.fill('[data-field="surface.rbf_scale"]', '2'));
    assert.equal((await currentJob()).surface.rbf_scale, 2);
    // Shepard takes no RBF options: they leave the job and their rows hide.
    await replan(page, () => page.selectOption('[data-field="surface.method"]', 'shepard'));
    const job = await currentJob();
    assert.equal(job.surface.method, 'shepard');
    assert.equal(job.surface.rbf_scale, undefined);
    assert.equal(await page.locator('[data-field="surface.rbf_scale"]').isVisible(), false);
    assert.equal(await page.locator('[data-field="surface.neighbours"]').isVisible(), true);
  });

  test('the progressive-lens preset shows mean-power and cylinder maps', async () => {
    await replan(page, () => page.selectOption('[data-role="preset"]', 'paper003'), ['done']);
    assert.equal(await page.locator('#maps').isVisible(), true);
    // Finite ranges in dioptres; the mean power spans at least most of the 2 D addition.
    const range = async (name) => {
      const text = await page.textContent(`#map-${name}-range`);
      const m = text.match(/^(-?[\d.,]+) … (-?[\d.,]+) D$/);
      assert.ok(m, `${name}: ${text}`);
      return m.slice(1).map((v) => Number(v.replaceAll(',', '')));
    };
    const [lo, hi] = await range('mean');
    assert.ok(hi - lo > 1.5, `mean power ${lo} … ${hi} D`);
    await range('cylinder');
    assert.deepEqual(errors, []);
  });
});
