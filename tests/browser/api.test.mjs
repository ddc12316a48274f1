// The JavaScript API of pkg/ (issue 17, item 3): package.json names files that exist; plan()
// reports progress and its report equals the command line's; an aborted signal rejects with
// AbortError; ncText() is the command line's NC byte for byte; sag() equals `spiralcam sag` at the
// same points (printed with 16 significant digits: within 1e-12 relative); a bad job rejects
// naming the field.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { ROOT, launch, planWithCli, spiralcamCli, startServer } from './harness.mjs';

let server;
before(async () => {
  server = await startServer();
});
after(() => server.stop());

test('pkg/package.json names the files the package holds', () => {
  const pkg = JSON.parse(readFileSync(join(ROOT, 'pkg/package.json'), 'utf8'));
  const cargo = readFileSync(join(ROOT, 'Cargo.toml'), 'utf8');
  assert.equal(pkg.version, /^version = "(.*)"/m.exec(cargo)[1]);
  assert.equal(pkg.type, 'module');
  for (const f of [pkg.main, pkg.module, pkg.types, ...pkg.files, ...Object.values(pkg.exports).flatMap((e) => (typeof e === 'string' ? [e] : Object.values(e)))]) {
    assert.ok(existsSync(join(ROOT, 'pkg', f)), `${f} is not in pkg/`);
  }
});

describe('pkg/spiralcam.js in the browser', () => {
  let browser;
  let page;
  const job = JSON.parse(readFileSync(join(ROOT, 'crate/jobs/q-bfs.json'), 'utf8'));
  before(async () => {
    let context;
    ({ browser, context } = await launch('WebGL2'));
    page = await context.newPage();
    await page.goto(`${server.url}pkg/package.json`);
  });
  after(() => browser.close());

  test('plan() with progress; ncText() is the command line\'s NC', async () => {
    const got = await page.evaluate(async (j) => {
      const api = await import('/pkg/spiralcam.js');
      const stages = new Set();
      const { report, path, mesh } = await api.plan(j, { onProgress: ({ stage }) => stages.add(stage) });
      const nc = await api.ncText(j);
      return { report, pathLength: path.length, triangles: mesh.indices.length / 3, stages: [...stages], nc };
    }, job);
    const cli = planWithCli(join(ROOT, 'crate/jobs/q-bfs.json'));
    const cliReport = JSON.parse(readFileSync(join(cli.dir, 'report.json'), 'utf8'));
    rmSync(cli.dir, { recursive: true, force: true });
    assert.equal(got.report.points, cliReport.points);
    assert.equal(got.report.surface_pv_um, cliReport.surface_pv_um);
    assert.ok(got.pathLength > 0 && got.pathLength % 3 === 0);
    assert.ok(got.triangles > 100);
    assert.ok(got.stages.includes('planning'), got.stages.join());
    assert.ok(Buffer.from(got.nc).equals(cli.nc), 'NC text differs from the command line');
  });

  test('an aborted signal rejects with AbortError', async () => {
    const name = await page.evaluate(async (j) => {
      const api = await import('/pkg/spiralcam.js');
      const big = structuredClone(j);
      // 10 000 turns: seconds of planning, aborted at its first progress message or at 200 ms.
      big.strategy.feed_mm_per_rev = 0.0005;
      const abort = new AbortController();
      const p = api.plan(big, { onProgress: () => abort.abort(), signal: abort.signal });
      setTimeout(() => abort.abort(), 200);
      try {
        await p;
        return 'resolved';
      } catch (e) {
        return e.name;
      }
    }, job);
    assert.equal(name, 'AbortError');
  });

  test('sag() equals `spiralcam sag` at the same points', async () => {
    const points = [];
    for (let i = 0; i < 40; i++) points.push([-4 + 0.2 * i, 3 * Math.sin(i)]);
    const z = await page.evaluate(async ([j, p]) => [...await (await import('/pkg/spiralcam.js')).sag(j, p)], [job, points]);
    const dir = mkdtempSync(join(tmpdir(), 'spiralcam-sag-'));
    writeFileSync(join(dir, 'at.csv'), `x_mm,y_mm\n${points.map((p) => p.join(',')).join('\n')}\n`);
    const out = execFileSync(spiralcamCli(), ['sag', join(ROOT, 'crate/jobs/q-bfs.json'), '--at', join(dir, 'at.csv')], { encoding: 'utf8' });
    rmSync(dir, { recursive: true, force: true });
    const rows = out.trim().split('\n').slice(1).map((l) => Number(l.split(',')[2]));
    assert.equal(rows.length, points.length);
    rows.forEach((zc, i) => assert.ok(Math.abs(z[i] - zc) <= 1e-12 * Math.max(Math.abs(zc), 1e-3), `point ${i}: ${z[i]} vs ${zc}`));
  });

  test('a bad job rejects naming the field', async () => {
    const message = await page.evaluate(async (j) => {
      const bad = structuredClone(j);
      bad.tool.nose_radius_mm = -1;
      try {
        await (await import('/pkg/spiralcam.js')).plan(bad);
        return 'resolved';
      } catch (e) {
        return e.message;
      }
    }, job);
    assert.equal(message, 'tool.nose_radius_mm = -1: must be a finite number ≥ 0');
  });

  test('a split path too long for the page is refused with both limits', async () => {
    // The sine grid at 35 500 points a revolution: 28 400 001 points, which the command line
    // takes with its dynamics and the page (a tab's memory) does not.
    const grid = JSON.parse(readFileSync(join(ROOT, 'crate/jobs/sinusoid-grid-fts.json'), 'utf8'));
    grid.strategy.sampling.points_per_rev = 35500;
    const message = await page.evaluate(async (j) => {
      try {
        await (await import('/pkg/spiralcam.js')).plan(j);
        return 'resolved';
      } catch (e) {
        return e.message;
      }
    }, grid);
    assert.match(message, /^strategy\.feed_mm_per_rev = 0\.005: gives about [^;]+ points; the machine dynamics/, message);
    assert.ok(message.includes('take at most 17000000: a feed of at least 0.008352'), message);
    assert.ok(message.includes('the command line writes any size and takes 30000000 points'), message);
  });

  test('a job of the wrong shape rejects with the command line\'s words', async () => {
    // Read field by field from the object, a number for the surface said "TypeError:
    // Reflect.get called on non-object", and 1e300 was written out in 301 digits.
    const messages = await page.evaluate(async (j) => {
      const api = await import('/pkg/spiralcam.js');
      const out = [];
      for (const [section, value] of [['surface', 2.5], ['machine', 1e300]]) {
        const bad = structuredClone(j);
        bad[section] = value;
        try {
          await api.plan(bad);
          out.push('resolved');
        } catch (e) {
          out.push(e.message);
        }
      }
      return out;
    }, job);
    assert.deepEqual(messages, [
      'job: surface: invalid type: floating point `2.5`, expected a surface: an object whose "type" names its family',
      'job: machine: invalid type: floating point `1e+300`, expected struct MachineSpec',
    ]);
  });
});
