// The page's speed and memory (issue 16), in headless Chromium through WebGL2 on this machine:
// the default job from a fresh visit and from a reload (time from navigation to the path drawn,
// and the page's own "planned in"), paper 004's lens array at 4 M and 28.4 M points planned on
// one worker and on every core, and the 28.4 M-point program downloaded. While it runs, the
// private resident memory of Chromium's processes (resident less shared pages, the figure
// closest to Chrome's own "memory footprint") is sampled every 250 ms from /proc (`statm`,
// cheap to read; `smaps_rollup` cost 70 ms a sample, which slowed what was measured): the
// renderer is the tab with its workers, the browser process holds the Blobs of a download.
// Times from navigation come from the page's clock (`performance.now()` when the path is drawn).
// Prints a table; asserts nothing.
//
//   node tests/bench/page.mjs [--quick]      (--quick: leaves out the 28.4 M-point rows)

import { readFileSync, readdirSync, rmSync, statSync } from 'node:fs';
import { launch, startServer, waitForState, setField } from '../browser/harness.mjs';

const quick = process.argv.includes('--quick');

/** Private resident memory (MB) of every Chromium process, summed by kind. */
function chromiumMemory() {
  const kinds = {};
  for (const pid of readdirSync('/proc').filter((p) => /^\d+$/.test(p))) {
    try {
      const cmd = readFileSync(`/proc/${pid}/cmdline`, 'utf8');
      if (!cmd.includes('chromium')) continue;
      const kind = cmd.match(/--type=([a-z-]+)/)?.[1] ?? 'browser';
      const [, resident, shared] = readFileSync(`/proc/${pid}/statm`, 'utf8').split(' ').map(Number);
      const pages = resident - shared;
      kinds[kind] = (kinds[kind] ?? 0) + (pages * 4096) / 2 ** 20;
    } catch {
      // The process ended while it was read.
    }
  }
  return kinds;
}

/** Samples `chromiumMemory` until stopped; `peak()` gives the largest figure per kind and of
 * the sum. */
function sampler() {
  const peak = { total: 0 };
  const timer = setInterval(() => {
    const m = chromiumMemory();
    let total = 0;
    for (const [k, v] of Object.entries(m)) {
      peak[k] = Math.max(peak[k] ?? 0, v);
      total += v;
    }
    peak.total = Math.max(peak.total, total);
  }, 250);
  return { peak: () => peak, stop: () => clearInterval(timer) };
}

const rows = [];
function row(what, seconds, memory) {
  const mb = (k) => (memory[k] === undefined ? '–' : `${memory[k].toFixed(0)} MB`);
  rows.push(`| ${what} | ${seconds} | ${mb('renderer')} | ${mb('browser')} | ${mb('total')} |`);
  console.log(rows[rows.length - 1]);
}

/** Plans the page's current job after `edit`; returns [planned-in text, peak memory]. */
async function timed(page, edit) {
  const s = sampler();
  await edit();
  s.stop();
  return [await page.textContent('#plan-time'), s.peak()];
}

const server = await startServer();
const { browser, context } = await launch('WebGL2');
try {
  console.log('| step | time | renderer (tab, workers) | browser process | all Chromium |');
  console.log('|---|---|---|---|---|');
  // The default job: a first visit compiles the module; a reload takes it from the cache.
  const page = await context.newPage();
  // The page's clock when the state first reads "done" (the path drawn).
  await page.addInitScript(() => {
    new MutationObserver(() => {
      if (document.body?.dataset.state === 'done' && window.drawnAt === undefined) window.drawnAt = performance.now();
    }).observe(document, { subtree: true, attributes: true, attributeFilter: ['data-state'] });
  });
  for (const visit of ['first visit', 'reload']) {
    const s = sampler();
    if (visit === 'first visit') await page.goto(server.url);
    else await page.reload();
    await waitForState(page, ['done']);
    const sinceLoad = await page.evaluate(() => window.drawnAt);
    s.stop();
    row(`default job, ${visit}: drawn after navigation (${await page.textContent('#plan-time')})`, `${(sinceLoad / 1000).toFixed(2)} s`, s.peak());
  }
  const jobs = [
    ['4 000 001', '0.005', '4000'],
    ...(quick ? [] : [['28 400 001', '0.001', '5680']]),
  ];
  for (const [points, feed, ppr] of jobs) {
    for (const workers of [1, 2]) {
      await page.evaluate((w) => {
        window.spiralcam.workers = w;
      }, workers);
      // Back to the default job first, so each row plans from the same state.
      await setField(page, 'strategy.feed_mm_per_rev', '0.01');
      await setField(page, 'strategy.sampling.points_per_rev', '360', ['done']);
      const [planned, memory] = await timed(page, async () => {
        await setField(page, 'strategy.feed_mm_per_rev', feed, ['planning', 'done']);
        await setField(page, 'strategy.sampling.points_per_rev', ppr, ['done']);
      });
      row(`lens array, ${points} points, ${workers} worker${workers > 1 ? 's' : ''}: ${planned}`, planned.match(/[\d.]+ s/)[0], memory);
      if (points.startsWith('28')) {
        // Through a Blob of the slices (the save dialog, which headless Chromium cannot
        // answer, taken away), then on two workers also into a file the dialog would give (a
        // stub writer that counts the bytes: the page's side of streaming to disk).
        await page.evaluate(() => {
          window.savedDialog = window.showSaveFilePicker;
          delete window.showSaveFilePicker;
        });
        const s = sampler();
        const t0 = Date.now();
        const [download] = await Promise.all([page.waitForEvent('download', { timeout: 600_000 }), page.click('#download-nc')]);
        const path = await download.path();
        const seconds = (Date.now() - t0) / 1000;
        s.stop();
        const size = statSync(path).size;
        rmSync(path);
        row(`its program, ${(size / 1e9).toFixed(2)} GB, into a Blob and downloaded`, `${seconds.toFixed(1)} s`, s.peak());
        if (workers > 1) {
          await page.evaluate(() => {
            window.spiralcam.saved = null;
            window.streamed = 0;
            window.showSaveFilePicker = async () => ({
              createWritable: async () => ({
                write: async (text) => {
                  window.streamed += text.size ?? text.length;
                },
                close: async () => {},
                abort: async () => {},
              }),
            });
          });
          const st = sampler();
          const t1 = Date.now();
          await page.click('#download-nc');
          await page.waitForFunction(() => window.spiralcam.saved !== null, null, { timeout: 600_000, polling: 100 });
          st.stop();
          const bytes = await page.evaluate(() => window.streamed);
          row(`its program, ${(bytes / 1e9).toFixed(2)} GB, written in slices to the save dialog's file (stub)`, `${((Date.now() - t1) / 1000).toFixed(1)} s`, st.peak());
        }
      }
    }
  }
} finally {
  await browser.close();
  server.stop();
}
