// Offline (issue 17, item 4): after one visit the service worker holds a complete copy keyed by
// the hash of the page's files; with the browser context offline the page reloads, plans the
// default job and says it runs from the offline copy; every file the page loads online is in
// the copy's list (sw.js FILES), so the list stays current.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { ROOT, launch, openPage, startServer, waitForState } from './harness.mjs';

let server;
before(async () => {
  server = await startServer();
});
after(() => server.stop());

describe('the offline copy', () => {
  let browser;
  let context;
  let page;
  let requests;
  before(async () => {
    ({ browser, context } = await launch('WebGL2'));
    ({ page, requests } = await openPage(context, server.url));
    await page.waitForFunction(() => window.spiralcam.offline?.cached || window.spiralcam.offline?.error, null, { timeout: 60_000 });
  });
  after(() => browser.close());

  test('the copy is complete and named after its hash', async () => {
    const offline = await page.evaluate(() => window.spiralcam.offline);
    assert.equal(offline.error, null);
    assert.match(offline.cached, /^[0-9a-f]{16}$/);
    const names = await page.evaluate(() => caches.keys());
    assert.deepEqual(names, [`spiralcam-${offline.cached}`]);
  });

  test('every file the page loads is in the copy', () => {
    const files = /const FILES = \[([^\]]*)\]/.exec(readFileSync(join(ROOT, 'sw.js'), 'utf8'))[1];
    const listed = new Set([...files.matchAll(/'([^']+)'/g)].map((m) => m[1]));
    const loaded = new Set(requests.filter((u) => u.startsWith(server.url)).map((u) => new URL(u).pathname.slice(1) || 'index.html'));
    const missing = [...loaded].filter((f) => !listed.has(f));
    assert.deepEqual(missing, []);
  });

  test('offline, the page reloads, plans the default job and says so', async () => {
    const hash = await page.evaluate(() => window.spiralcam.offline.cached);
    await context.setOffline(true);
    try {
      await page.reload();
      await waitForState(page, ['done']);
      assert.equal(await page.textContent('[data-key="Points"]'), '360,001');
      assert.equal(await page.textContent('#offline'), `offline copy ${hash}`);
      assert.equal(await page.isVisible('#offline'), true);
    } finally {
      await context.setOffline(false);
    }
  });
});
