// The page's side of the offline copy (sw.js at the site's root): registers the service worker,
// asks it to bring its copy up to date after each visit online, and says whether this visit runs
// from the offline copy (the copy's answers carry `X-Spiralcam-Offline: <hash>`). `state` gets
// `offline` ({ copy: hash or null, cached: hash once the copy is complete, error }).

/** Starts the offline copy; `show(text)` is called with a line for the page when it runs from
 * the copy. */
export async function offlineCopy(state, show) {
  state.offline = { copy: null, cached: null, error: null };
  if (!('serviceWorker' in navigator) || !window.isSecureContext) {
    state.offline.error = 'no service worker here (it needs https or localhost)';
    return;
  }
  try {
    navigator.serviceWorker.addEventListener('message', (e) => {
      if (e.data?.type === 'spiralcam:cached') state.offline.cached = e.data.hash;
      if (e.data?.type === 'spiralcam:cache-failed') state.offline.error = e.data.message;
    });
    await navigator.serviceWorker.register(new URL('../sw.js', import.meta.url));
    const probe = await fetch(new URL('../index.html', import.meta.url), { cache: 'no-store' }).catch(() => null);
    const copy = probe?.headers.get('x-spiralcam-offline');
    if (copy) {
      state.offline.copy = copy;
      state.offline.cached = copy;
      show(`offline copy ${copy}`);
      return;
    }
    const ready = await navigator.serviceWorker.ready;
    ready.active.postMessage({ type: 'spiralcam:refresh' });
  } catch (e) {
    state.offline.error = String(e.message || e);
  }
}
