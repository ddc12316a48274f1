// The offline copy of the page (README, "Offline"): after one visit the page and the viewer open
// and plan with no network. On install and on every visit online, the service worker fetches the
// page's files (FILES), hashes them (SHA-256 over each file's bytes in order) and, when the hash
// is new, fills a cache named after it completely before deleting the older one: a new version
// replaces the old one whole and the two are never mixed. Requests go to the network first; when
// it fails, the cached copy answers, marked with the header `X-Spiralcam-Offline: <hash>` so the
// page can say it is running from the offline copy.

/** The files of the page and the viewer, relative to this file (the site's root). */
const FILES = [
  'index.html',
  'manifest.webmanifest',
  'web/style.css',
  'web/app.js',
  'web/form.js',
  'web/import.js',
  'web/plots.js',
  'web/worker.js',
  'web/share.js',
  'web/gestures.js',
  'web/embed-page.js',
  'web/spiralcam-viewer.js',
  'web/offline.js',
  'web/icon.svg',
  'pkg/spiralcam_web.js',
  'pkg/spiralcam_web_bg.wasm',
];

const PREFIX = 'spiralcam-';

/** The cache of the files as the server has them now, made if the hash is new; older caches
 * deleted once it is complete. Resolves to the hash. */
async function refresh() {
  // Each body read as soon as its headers come: a browser opens about six connections a host,
  // and bodies left unread would hold them while the other files wait.
  const fetched = await Promise.all(FILES.map(async (f) => {
    const r = await fetch(new URL(f, self.registration.scope), { cache: 'no-store' });
    if (!r.ok) throw new Error(`${f}: ${r.status}`);
    return { status: r.status, headers: r.headers, body: await r.arrayBuffer() };
  }));
  const bodies = fetched.map((r) => r.body);
  const digests = await Promise.all(bodies.map((b) => crypto.subtle.digest('SHA-256', b)));
  const all = new Uint8Array(digests.length * 32);
  digests.forEach((d, i) => all.set(new Uint8Array(d), 32 * i));
  const hash = [...new Uint8Array(await crypto.subtle.digest('SHA-256', all))].slice(0, 8).map((b) => b.toString(16).padStart(2, '0')).join('');
  const name = `${PREFIX}${hash}`;
  const names = await caches.keys();
  if (!names.includes(name)) {
    // Filled under a temporary name and renamed by copying: a cache named after a hash is
    // complete.
    const filling = await caches.open(`${name}-filling`);
    await Promise.all(FILES.map((f, i) => filling.put(new URL(f, self.registration.scope),
      new Response(bodies[i], { status: fetched[i].status, headers: fetched[i].headers }))));
    const cache = await caches.open(name);
    for (const request of await filling.keys()) await cache.put(request, await filling.match(request));
    await caches.delete(`${name}-filling`);
  }
  for (const old of await caches.keys()) if (old.startsWith(PREFIX) && old !== name) await caches.delete(old);
  return hash;
}

/** The complete cache, if any: the one named after a hash. */
async function current() {
  const name = (await caches.keys()).find((n) => n.startsWith(PREFIX) && !n.endsWith('-filling'));
  return name ? { name, cache: await caches.open(name) } : null;
}

self.addEventListener('install', (e) => {
  e.waitUntil(refresh().then(() => self.skipWaiting()));
});

self.addEventListener('activate', (e) => {
  e.waitUntil(self.clients.claim());
});

self.addEventListener('message', (e) => {
  if (e.data?.type !== 'spiralcam:refresh') return;
  e.waitUntil(refresh().then(
    (hash) => e.source.postMessage({ type: 'spiralcam:cached', hash }),
    (err) => e.source.postMessage({ type: 'spiralcam:cache-failed', message: String(err.message || err) }),
  ));
});

self.addEventListener('fetch', (e) => {
  const url = new URL(e.request.url);
  if (e.request.method !== 'GET' || url.origin !== self.location.origin) return;
  e.respondWith(fetch(e.request).catch(async (err) => {
    const c = await current();
    // The page's address with its query (?embed, ?job=) is the cached index.html.
    const key = e.request.mode === 'navigate' ? new URL('index.html', self.registration.scope) : new URL(url.pathname, url.origin);
    const hit = c && await c.cache.match(key);
    if (!hit) throw err;
    const headers = new Headers(hit.headers);
    headers.set('X-Spiralcam-Offline', c.name.slice(PREFIX.length));
    return new Response(hit.body, { status: hit.status, statusText: hit.statusText, headers });
  }));
});
