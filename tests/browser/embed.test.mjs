// The embeddable viewer (issue 17, items 2, 3 and 5) on web/examples/embed.html, the page a
// vendor copies: two <spiralcam-viewer> elements and one iframe of index.html?embed all draw
// (pixels read back) through WebGPU and WebGL2 with one wasm instantiation for the page's
// viewers; a control re-plans; the viewer's NC is the command line's; 40 viewers made and
// removed in a row lose no context (on WebGPU they open no device: the page's serves them);
// postMessage loads a job into the iframe and answers with the report, and a message from a
// foreign origin is ignored; every bad input is a message in the box. The time from connected
// to first frame is printed (test diagnostics) as a figure; with SPIRALCAM_SCREENSHOT=1 the
// page's screenshot is written to web/examples/embed.png.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { PNG } from 'pngjs';
import { ROOT, download, launch, pixelStats, planWithCli, startServer } from './harness.mjs';

let server;
before(async () => {
  server = await startServer();
});
after(() => server.stop());

const EXAMPLE = 'web/examples/embed.html';

/** Waits until the viewer `selector` (in `frame`, a page or frame) is in one of `states`. */
async function viewerState(frame, selector, states = ['done'], timeout = 120_000) {
  await frame.waitForFunction(([sel, s]) => s.includes(document.querySelector(sel)?.getAttribute('state')), [selector, states], { timeout });
}

async function drawn(locator) {
  const stats = pixelStats(PNG.sync.read(await locator.screenshot()));
  return stats;
}

for (const backend of ['WebGPU', 'WebGL2']) {
  describe(`the embed example through ${backend}`, () => {
    let browser;
    let page;
    const errors = [];
    const consoleLines = [];
    before(async () => {
      let context;
      ({ browser, context } = await launch(backend));
      page = await context.newPage();
      page.on('pageerror', (e) => errors.push(String(e)));
      page.on('console', (m) => consoleLines.push(m.text()));
      await page.goto(`${server.url}${EXAMPLE}`);
      await viewerState(page, '#lens-array');
      await viewerState(page, '#sinusoid');
      await page.frameLocator('#frame').locator('body[data-state="done"]').waitFor({ timeout: 120_000 });
    });
    after(() => browser.close());

    test('both viewers and the iframe draw', async (t) => {
      for (const sel of ['#lens-array', '#sinusoid']) {
        assert.equal(await page.getAttribute(sel, 'backend'), backend);
        const stats = await drawn(page.locator(`${sel} canvas`));
        assert.ok(stats.covered > 0.1 && stats.colours > 20, `${sel}: ${JSON.stringify(stats)}`);
      }
      const frameStats = await drawn(page.frameLocator('#frame').locator('spiralcam-viewer canvas'));
      assert.ok(frameStats.covered > 0.1 && frameStats.colours > 20, `iframe: ${JSON.stringify(frameStats)}`);
      assert.equal(await page.textContent('#lens-array >> [data-key="points"] b'), '360,001');
      const ms = Number(await page.getAttribute('#lens-array', 'first-frame-ms'));
      assert.ok(ms > 0);
      t.diagnostic(`${backend}: default job, <spiralcam-viewer> connected to first frame: ${ms} ms`);
      // SPIRALCAM_SCREENSHOT=1 refreshes the committed screenshot of the example.
      if (backend === 'WebGPU' && process.env.SPIRALCAM_SCREENSHOT === '1') writeFileSync(join(ROOT, 'web/examples/embed.png'), await page.screenshot({ fullPage: true }));
    });

    test('one wasm instantiation and one worker for the page\'s viewers', async () => {
      const shared = await page.evaluate(async () => {
        const { shared: s } = await import('/web/spiralcam-viewer.js');
        return { instantiations: s.instantiations, worker: Boolean(s.worker), contexts: s.contexts };
      });
      assert.deepEqual(shared, { instantiations: 1, worker: true, contexts: 2 });
    });

    test('the viewer\'s NC is the command line\'s', async () => {
      const cli = planWithCli(join(ROOT, 'crate/jobs/lens-array-paper004.json'));
      const nc = await download(page, '#lens-array >> button.nc');
      assert.equal(nc.name, 'lens-array-paper004.ngc');
      assert.ok(nc.bytes.equals(cli.nc), 'NC differs from the command line');
      assert.equal(await page.isHidden('#sinusoid >> button.nc'), true);
    });

    test('a control re-plans', async () => {
      await page.fill('#lens-array >> input[type="number"][data-field="strategy.feed_mm_per_rev"]', '0.02');
      await page.waitForFunction(() => document.querySelector('#lens-array').shadowRoot.querySelector('[data-key="points"] b')?.textContent === '180,001', null, { timeout: 60_000 });
      await viewerState(page, '#lens-array');
      const open = await page.getAttribute('#lens-array >> a.open', 'href');
      assert.match(open, /\/index\.html#job=[A-Za-z0-9_-]+$/);
    });

    // Bounded: once, headless Chromium's WebGPU (SwiftShader) stalled the page inside this
    // loop and the run waited on it for 11 minutes; a stall now fails here, naming the last
    // viewer that got its context. The limit is kept here in Node: a page whose main thread
    // waits on a stalled GPU process runs no timer of its own.
    test('40 viewers made and removed in a row lose no context', { timeout: 180_000 }, async () => {
      const loop = page.evaluate(async () => {
        const { shared: s, SpiralcamViewer } = await import('/web/spiralcam-viewer.js');
        const { Viewer } = await import('/pkg/spiralcam_web.js');
        const before = s.contexts;
        const devicesBefore = Viewer.devices_opened();
        const job = await (await fetch('/crate/jobs/lens-array-paper004.json')).json();
        job.strategy.feed_mm_per_rev = 0.5;
        for (let i = 0; i < 40; i++) {
          const v = document.createElement('spiralcam-viewer');
          v.style.height = '120px';
          document.body.prepend(v);
          // A viewer opens its context once seen: bring it into view.
          v.scrollIntoView();
          v.setJob(job);
          // Wait for its GPU context, then remove it.
          await new Promise((resolve, reject) => {
            const end = performance.now() + 30_000;
            const check = () => {
              if (v.getAttribute('backend')) resolve();
              else if (performance.now() > end) reject(new Error(`viewer ${i}: no GPU context after 30 s (state ${v.getAttribute('state')}, visible ${v.visible})`));
              else setTimeout(check, 20);
            };
            check();
          });
          console.debug(`viewer ${i} had its context`);
          v.remove();
        }
        return { made: s.contexts - before, released: s.released, devices: Viewer.devices_opened() - devicesBefore, viewer: SpiralcamViewer.name };
      });
      let timer;
      const stalled = new Promise((_, reject) => {
        timer = setTimeout(() => {
          const last = consoleLines.findLast((l) => /^viewer \d+ had its context$/.test(l)) ?? 'no viewer had its context';
          reject(new Error(`the page stopped answering within the 40 viewers (last: ${last})`));
        }, 150_000);
      });
      const made = await Promise.race([loop, stalled]).finally(() => clearTimeout(timer));
      assert.equal(made.made, 40);
      assert.ok(made.released >= 40, JSON.stringify(made));
      // WebGPU: the 40 draw with the page's device (the two viewers above hold it); WebGL2: a
      // context, hence a device, each.
      assert.equal(made.devices, backend === 'WebGPU' ? 0 : 40, JSON.stringify(made));
      // The two viewers of the page still draw: their contexts were never the oldest lost.
      for (const sel of ['#lens-array', '#sinusoid']) {
        await page.evaluate((s) => document.querySelector(s).redraw(), sel);
        const stats = await drawn(page.locator(`${sel} canvas`));
        assert.ok(stats.covered > 0.1, `${sel} after 40 viewers: ${JSON.stringify(stats)}`);
      }
      const lost = consoleLines.filter((l) => /too many active webgl contexts|context lost/i.test(l));
      assert.deepEqual(lost, []);
      assert.deepEqual(errors, []);
    });
  });
}

describe('index.html?embed answers postMessage from allowed origins only', () => {
  let browser;
  let context;
  before(async () => {
    ({ browser, context } = await launch('WebGL2'));
  });
  after(() => browser.close());

  /** A host page on `origin` with an iframe of index.html?embed`query` on the server's origin;
   * posts a job to it and returns what came back within `wait` ms. */
  async function roundTrip(origin, query, wait) {
    const page = await context.newPage();
    await page.goto(`${origin}/web/share.js`);
    const job = await (await fetch(`${server.url}crate/jobs/q-bfs.json`)).json();
    const answers = await page.evaluate(async ([src, j, ms]) => {
      const frame = document.createElement('iframe');
      frame.src = src;
      frame.style.cssText = 'width: 600px; height: 400px';
      document.body.append(frame);
      await new Promise((r) => frame.addEventListener('load', r, { once: true }));
      const got = [];
      window.addEventListener('message', (e) => got.push({ origin: e.origin, data: { type: e.data.type, job: e.data.report?.job, points: e.data.report?.points } }));
      // The embed page waits for a job; give its module time to listen.
      await new Promise((r) => setTimeout(r, 500));
      frame.contentWindow.postMessage({ type: 'spiralcam:load', job: j }, '*');
      const end = Date.now() + ms;
      while (!got.length && Date.now() < end) await new Promise((r) => setTimeout(r, 50));
      return got;
    }, [`${server.url}index.html?embed${query}`, job, wait]);
    const frame = page.frames().find((f) => f.url().includes('?embed'));
    const ignored = await frame.evaluate(() => window.spiralcam.ignored);
    await page.close();
    return { answers, ignored };
  }

  test('same origin: the job is planned and the report comes back', async () => {
    const { answers } = await roundTrip(server.url.replace(/\/$/, ''), '', 120_000);
    assert.equal(answers.length, 1);
    assert.equal(answers[0].origin, server.url.replace(/\/$/, ''));
    assert.equal(answers[0].data.type, 'spiralcam:planned');
    assert.equal(answers[0].data.job, 'q-bfs');
    assert.ok(answers[0].data.points > 1000);
  });

  test('a foreign origin is ignored unless allowed', async () => {
    const foreign = server.url.replace('127.0.0.1', 'localhost').replace(/\/$/, '');
    const ignored = await roundTrip(foreign, '', 3_000);
    assert.deepEqual(ignored.answers, []);
    assert.equal(ignored.ignored, 1);
    const allowed = await roundTrip(foreign, `&allow=${encodeURIComponent(foreign)}`, 120_000);
    assert.equal(allowed.answers[0]?.data.type, 'spiralcam:planned');
    assert.equal(allowed.answers[0].origin, server.url.replace(/\/$/, ''));
  });
});

describe('bad input in the viewer is a message in the box', () => {
  let browser;
  let page;
  const errors = [];
  before(async () => {
    let context;
    ({ browser, context } = await launch('WebGL2'));
    page = await context.newPage();
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.goto(`${server.url}web/share.js`);
    await page.evaluate(async () => {
      await import('/web/spiralcam-viewer.js');
    });
  });
  after(() => browser.close());

  /** A viewer with `attrs` on the page; returns its state and message. */
  async function viewer(attrs, states = ['error', 'too-large']) {
    const id = `v${Math.random().toString(36).slice(2)}`;
    await page.evaluate(([a, i]) => {
      const v = document.createElement('spiralcam-viewer');
      v.id = i;
      for (const [k, val] of Object.entries(a)) v.setAttribute(k, val);
      document.body.append(v);
    }, [attrs, id]);
    await viewerState(page, `#${id}`, states);
    return page.evaluate((i) => {
      const v = document.getElementById(i);
      return { state: v.getAttribute('state'), message: v.shadowRoot.querySelector('.message').textContent, open: v.shadowRoot.querySelector('a.open').href };
    }, id);
  }

  test('a src that 404s', async () => {
    const v = await viewer({ src: '/crate/jobs/missing.json' });
    assert.match(v.message, /the job \/crate\/jobs\/missing\.json could not be loaded: 404/);
  });

  test('a src that is not JSON', async () => {
    const v = await viewer({ src: '/README.md' });
    assert.match(v.message, /the job \/README\.md is not JSON/);
  });

  test('a truncated and a tampered fragment', async () => {
    const fragment = await page.evaluate(async () => {
      const job = await (await fetch('/crate/jobs/q-bfs.json')).json();
      return (await import('/web/share.js')).jobFragment(job);
    });
    assert.match((await viewer({ job: fragment.slice(0, -30) })).message, /cut short/);
    assert.match((await viewer({ job: `${fragment.slice(0, 20)}!${fragment.slice(21)}` })).message, /a character that base64url does not use/);
  });

  test('an invalid job names the field', async () => {
    const fragment = await page.evaluate(async () => {
      const job = await (await fetch('/crate/jobs/q-bfs.json')).json();
      job.tool.nose_radius_mm = -1;
      return (await import('/web/share.js')).jobFragment(job);
    });
    assert.equal((await viewer({ job: fragment })).message, 'tool.nose_radius_mm = -1: must be a finite number ≥ 0');
  });

  test('a job too large for the box offers the full page', async () => {
    const v = await viewer({ src: '/crate/jobs/lens-array-paper004.json', 'max-points': '100000' });
    assert.equal(v.state, 'too-large');
    assert.match(v.message, /about 360,000 points, more than the 100,000 this viewer plans/);
    assert.match(v.open, /\/index\.html#job=[A-Za-z0-9_-]+$/);
    assert.deepEqual(errors, []);
  });
});
