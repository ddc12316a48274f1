// What you download is what you see, and the view frames the part (issue 17, items 6 and 7):
// an invalid field, a decimal comma or a plan in flight marks the report and the view stale
// (naming the job and time they belong to) and disables every download; the 3-D view keeps the
// whole part in its canvas beside the colour legend at desktop widths and on a phone.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { PNG } from 'pngjs';
import { launch, openPage, setField, startServer, waitForState } from './harness.mjs';

let server;
before(async () => {
  server = await startServer();
});
after(() => server.stop());

/** Every download button of the report panel that is shown, with whether it is enabled. */
async function downloads(page) {
  return page.evaluate(() => [...document.querySelectorAll('[data-needs-plan]')]
    .filter((b) => !b.hidden)
    .map((b) => ({ id: b.id, enabled: !b.disabled })));
}

async function assertStale(page, why) {
  const enabled = (await downloads(page)).filter((b) => b.enabled);
  assert.deepEqual(enabled, [], 'a download of another job is enabled');
  assert.equal(await page.evaluate(() => window.spiralcam.stale), true);
  assert.equal(await page.locator('main.stale').count(), 1);
  const note = await page.textContent('#stale');
  assert.match(note, /^Stale: the report, the view and the downloads are the plan of “lens-array-paper004” made at \d\d:\d\d:\d\d; /);
  assert.ok(note.includes(why), note);
}

async function assertFresh(page) {
  assert.ok((await downloads(page)).every((b) => b.enabled), JSON.stringify(await downloads(page)));
  assert.equal(await page.evaluate(() => window.spiralcam.stale), false);
  assert.equal(await page.isHidden('#stale'), true);
  assert.equal(await page.locator('main.stale').count(), 0);
}

describe('what you download is what you see', () => {
  let browser;
  let page;
  let errors;
  before(async () => {
    let context;
    ({ browser, context } = await launch('WebGL2'));
    ({ page, errors } = await openPage(context, server.url));
  });
  after(() => browser.close());

  test('a planned job is fresh: downloads enabled, nothing greyed', async () => {
    await assertFresh(page);
  });

  test('an invalid field marks the previous plan stale and disables its downloads', async () => {
    await setField(page, 'tool.nose_radius_mm', '-1', ['error']);
    assert.equal(await page.textContent('[data-error-for="tool.nose_radius_mm"]'), 'tool.nose_radius_mm = -1: must be a finite number ≥ 0');
    await assertStale(page, 'fix the highlighted field');
  });

  test('a decimal comma gets its own message, not NaN', async () => {
    await setField(page, 'tool.nose_radius_mm', '0,5', ['error']);
    assert.equal(await page.textContent('[data-error-for="tool.nose_radius_mm"]'), 'tool.nose_radius_mm = 0,5: a decimal comma; use a point: 0.5');
    await assertStale(page, 'fix the highlighted field');
    await setField(page, 'strategy.feed_mm_per_rev', '1e-2x', ['error']);
    assert.equal(await page.textContent('#error'), 'Fix the highlighted field.');
    assert.ok(['strategy.feed_mm_per_rev = 1e-2x: not a number', 'tool.nose_radius_mm = 0,5: a decimal comma; use a point: 0.5']
      .includes(await page.evaluate(() => window.spiralcam.error)));
    await setField(page, 'strategy.feed_mm_per_rev', '0.01', ['error']);
    await setField(page, 'tool.nose_radius_mm', '0.5');
    await assertFresh(page);
  });

  test('a plan in flight marks the shown plan stale; cancelled, it stays stale', async () => {
    await setField(page, 'strategy.feed_mm_per_rev', '0.001', ['planning']);
    await setField(page, 'strategy.sampling.points_per_rev', '2000', ['planning']);
    await assertStale(page, 're-planning the job the form shows');
    await page.click('#cancel');
    await waitForState(page, ['cancelled']);
    await assertStale(page, 'the form has changed since');
    await setField(page, 'strategy.feed_mm_per_rev', '0.01');
    await setField(page, 'strategy.sampling.points_per_rev', '720');
    await assertFresh(page);
    assert.deepEqual(errors, []);
  });
});

/** The bounding box of the canvas pixels that differ from the clear colour. */
function drawnBox({ width, height, data }, clear = [0x1e, 0x1f, 0x24]) {
  let [x0, y0, x1, y1] = [width, height, -1, -1];
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const i = 4 * (y * width + x);
      const d = Math.abs(data[i] - clear[0]) + Math.abs(data[i + 1] - clear[1]) + Math.abs(data[i + 2] - clear[2]);
      if (d > 24) {
        x0 = Math.min(x0, x);
        x1 = Math.max(x1, x);
        y0 = Math.min(y0, y);
        y1 = Math.max(y1, y);
      }
    }
  }
  return { x0, y0, x1, y1 };
}

describe('the view frames the part', () => {
  let browser;
  let page;
  before(async () => {
    let context;
    ({ browser, context } = await launch('WebGL2'));
    ({ page } = await openPage(context, server.url));
    // The notes drawn over the canvas are text, not the part.
    await page.addStyleTag({ content: '#path-note, .hint { visibility: hidden; }' });
  });
  after(() => browser.close());

  for (const [width, height] of [[1280, 800], [1366, 768], [1440, 900], [1920, 1080], [390, 844]]) {
    test(`${width} × ${height}: the whole part in the canvas, beside the legend`, async () => {
      await page.setViewportSize({ width, height });
      // The resize observer re-sizes the viewer's canvas, which draws on the next frame.
      await page.waitForFunction(() => {
        const c = document.querySelector('#view');
        const r = c.getBoundingClientRect();
        return Math.abs(c.width - Math.round(r.width * devicePixelRatio)) <= 1 && Math.abs(c.height - Math.round(r.height * devicePixelRatio)) <= 1;
      });
      await page.waitForTimeout(200);
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      const view = await page.locator('#view').boundingBox();
      const legend = await page.locator('#legend').boundingBox();
      assert.ok(view.x + view.width <= legend.x + 0.5, `canvas ${JSON.stringify(view)} under the legend ${JSON.stringify(legend)}`);
      // The canvas's whole pixels only: a fractional edge would show a row of the page below.
      const x = Math.ceil(view.x);
      const y = Math.ceil(view.y);
      const clip = { x, y, width: Math.floor(view.x + view.width) - x, height: Math.floor(view.y + view.height) - y };
      const png = PNG.sync.read(await page.screenshot({ clip }));
      const box = drawnBox(png);
      const margin = 2;
      assert.ok(box.x0 >= margin && box.y0 >= margin && box.x1 < png.width - margin && box.y1 < png.height - margin,
        `part ${JSON.stringify(box)} cut by the canvas edge (${png.width} × ${png.height})`);
      // Framed, not lost in a corner: it spans most of the canvas one way.
      const fill = Math.max((box.x1 - box.x0) / png.width, (box.y1 - box.y0) / png.height);
      assert.ok(fill > 0.6, `the part spans only ${(100 * fill).toFixed(0)} % of the canvas`);
      if (width < 600) {
        // A phone: the view comes first and is tall enough to orbit.
        assert.ok(view.y < 120 && view.height >= 250, `view at ${JSON.stringify(view)}`);
      }
    });
  }
});
